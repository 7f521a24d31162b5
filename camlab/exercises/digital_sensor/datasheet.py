"""Lesson 03's first exercise: the intrinsic matrix K from a datasheet (focal length, sensor size, pixel count)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import sensor
from .._answers import SameArray, Tolerance, shape_problem
from .._core import Exercise, Mistake, first_mistake, register_exercise
from ._datasheet_slips import AXIS_AND_SIGN_SLIPS, EQUIVALENT_OVER_FULL_WIDTH, PITCH_SLIPS

# -- intrinsics_from_datasheet -----------------------------------------------------------------


def _datasheet_cases():
    """A phone, a full-frame camera, a sensor with non-square pixels (10 x 9.375 µm), odd pixel counts."""
    return [
        (4.25, (5.6, 4.2), (4032, 3024)),
        (50.0, (36.0, 24.0), (6000, 4000)),
        (8.0, (6.4, 4.8), (640, 512)),
        (3.6, (4.8, 3.6), (801, 601)),
    ]


def _datasheet_reference(f_mm, sensor_mm, size):
    """camlab.sensor.intrinsics_from_sensor(f, pitch, size), in metres, with pitch = sensor size / pixel count."""
    W, H = size
    return sensor.intrinsics_from_sensor(
        f_mm * 1e-3, (sensor_mm[0] * 1e-3 / W, sensor_mm[1] * 1e-3 / H), size
    )


def _near(a, b):
    """Equal to rounding (the check's own tolerance is 1e-9)."""
    return np.isclose(a, b, rtol=1e-6, atol=1e-9)


def _unit_slip(factor, unit):
    """The row for f_x or f_y ``factor`` times the right value (a slip between mm, µm and m)."""

    def hint(s):
        x_off, y_off = _near(s.g[0, 0], s.fx * factor), _near(s.g[1, 1], s.fy * factor)
        which = "f_x and f_y are" if x_off and y_off else "f_x is" if x_off else "f_y is"
        return (
            f"{which} {unit}: a unit slip between mm, µm and m; keep f and the pitch in the same unit "
            f"(mm: s_x = sensor width / W), so f / s_x is in pixels"
        )

    return Mistake(
        f"f {unit}",
        lambda s: _near(s.g[0, 0], s.fx * factor) or _near(s.g[1, 1], s.fy * factor),
        hint,
    )


_MISTAKES = (
    Mistake(
        "transposed",
        lambda s: np.allclose(s.g, s.e.T),
        (
            "K is transposed: the principal point goes in the last column, K[0, 2] = c_x and K[1, 2] = c_y, "
            "and the bottom row is (0, 0, 1)"
        ),
    ),
    Mistake(
        "bottom row",
        lambda s: not _near(s.g[2], [0, 0, 1]).all(),
        (
            "the bottom row of K is (0, 0, 1): it keeps the homogeneous coordinate, K @ (x, y, 1) = (u, v, 1)"
        ),
    ),
    Mistake(
        "H, W = size",
        lambda s: (
            _near(s.g[0, 0], s.f_mm * s.H / s.w_mm)
            and _near(s.g[1, 1], s.f_mm * s.W / s.h_mm)
            and _near(s.g[0, 2], s.cy)
        ),
        (
            "you unpacked size as H, W = size: size is (width, height), as in OpenCV, so W, H = size; with the "
            "two swapped, f_x, f_y, c_x and c_y all come out wrong (an array's shape is (H, W), a size is not)"
        ),
    ),
    Mistake(
        "sensor_mm as (height, width)",
        lambda s: (
            _near(s.g[0, 0], s.f_mm * s.W / s.h_mm)
            and _near(s.g[1, 1], s.f_mm * s.H / s.w_mm)
            and (not _near(s.fx, s.f_mm * s.W / s.h_mm))
        ),
        (
            "sensor_mm is (width, height), like size: s_x = sensor_mm[0] / W = width / W, "
            "s_y = sensor_mm[1] / H; you divided the height by W and the width by H"
        ),
    ),
    Mistake(
        "f_y negative",
        lambda s: _near(s.g[1, 1], -s.fy) and (not _near(s.g[0, 0], -s.fx)),
        (
            "f_x and f_y are positive here: the course's image plane has y down, like v down the image, so "
            "f_y = f / s_y needs no minus sign (a y-up convention flips it; see docs/conventions.md)"
        ),
    ),
    Mistake(
        "f_x negative",
        lambda s: _near(s.g[0, 0], -s.fx) or _near(s.g[1, 1], -s.fy),
        (
            "f_x = f / s_x is positive: a focal length and a pitch are both positive lengths, so there is no "
            "minus sign in K (the course's x points right on the image plane, like u; docs/conventions.md)"
        ),
    ),
    Mistake(
        "field of view in degrees",
        lambda s: _near(s.g[0, 0], s.fx_degrees) or _near(s.g[1, 1], s.fy_degrees),
        (
            "f_x went through the field of view with the angle in degrees: np.tan takes radians, so "
            "(W / 2) / np.tan(np.degrees(fov) / 2) is far off (even negative). Leave the angle in radians, or skip "
            "it: f_x = f / s_x with s_x = width / W needs no angle"
        ),
    ),
    Mistake(
        "negative focal length",
        lambda s: s.g[0, 0] < 0 or s.g[1, 1] < 0,
        (
            "a negative focal length in pixels: f_x = f / s_x is a ratio of two positive lengths. A sign slip, or "
            "np.tan of an angle in degrees (np.tan takes radians)?"
        ),
    ),
    Mistake(
        "centre numbered from 1",
        lambda s: _near(s.g[0, 2], (s.W + 1) / 2) or _near(s.g[1, 2], (s.H + 1) / 2),
        (
            "(W + 1) / 2 is the centre when pixels are numbered from 1 (MATLAB's convention); numpy and camlab "
            "number them from 0, so u runs from 0 to W - 1 and the centre is (W - 1) / 2"
        ),
    ),
    Mistake(
        "W - 1/2: the brackets left out",
        lambda s: _near(s.g[0, 2], s.W - 0.5) or _near(s.g[1, 2], s.H - 0.5),
        lambda s: (
            f"c_x = {s.W - 0.5} is W - 1/2: Python divides before it subtracts, so W - 1 / 2 is W - 0.5, the "
            f"image's right edge, not its centre; write the brackets, (W - 1) / 2 = {(s.W - 1) / 2}"
        ),
    ),
    Mistake(
        "principal point left at the origin",
        lambda s: _near(s.g[0, 2], 0) or _near(s.g[1, 2], 0),
        (
            "the principal point is 0, pixel (0, 0), the top-left pixel: it is where the optical axis meets "
            "the sensor, which a datasheet takes to be the image centre, c = ((W - 1) / 2, (H - 1) / 2); "
            "K = diag(f_x, f_y, 1) alone leaves it out"
        ),
    ),
    Mistake(
        "centre by integer division",
        lambda s: (
            s.W % 2 == 0
            and _near(s.g[0, 2], (s.W - 1) // 2)
            or (s.H % 2 == 0 and _near(s.g[1, 2], (s.H - 1) // 2))
        ),
        lambda s: (
            f"c_x = {(s.W - 1) // 2} for W = {s.W} is the centre {(s.W - 1) / 2} cut short by half a pixel: integer "
            f"division, (W - 1) // 2, or int() drops the .5, and W / 2 - 1 (or (W - 1) / 2 - 0.5) subtracts a whole "
            f"pixel where the centre needs half of one; use (W - 1) / 2 = W / 2 - 0.5 (the centre of an even "
            f"number of pixels lies between two of them)"
        ),
    ),
    Mistake(
        "W // 2 - 0.5",
        lambda s: (
            s.W % 2
            and _near(s.g[0, 2], s.W // 2 - 0.5)
            or (s.H % 2 and _near(s.g[1, 2], s.H // 2 - 0.5))
        ),
        lambda s: (
            f"W // 2 - 0.5 is the centre only for an even W: for W = {s.W} it gives {s.W // 2 - 0.5}, half a pixel "
            f"short of {(s.W - 1) / 2} (so does W / 2 - 1, which takes a whole pixel off the half-way point "
            f"W / 2 instead of half of one); (W - 1) / 2 holds for both"
        ),
    ),
    Mistake(
        "c_x and c_y swapped",
        lambda s: _near(s.g[0, 2], s.cy) and _near(s.g[1, 2], s.cx) and (not _near(s.cx, s.cy)),
        (
            "c_x and c_y are swapped: c_x = (W - 1) / 2 comes from the width W = size[0], c_y = (H - 1) / 2 from "
            "the height H = size[1] (sizes are (width, height), as in OpenCV; an array's shape is (H, W))"
        ),
    ),
    Mistake(
        "centre W / 2",
        lambda s: _near(s.g[0, 2], s.W / 2) or _near(s.g[1, 2], s.H / 2),
        lambda s: (
            "half a pixel off: with pixel centres at integers, {0} runs from 0 to {1} - 1, so {2} is "
            "({1} - 1) / 2, not {1} / 2 (that is the centre in a pixel-corner convention), and not ({1} - 1) / 2 "
            "rounded to a whole pixel: keep the .5, the centre of an even number of pixels lies between two"
        ).format(*(("u", "W", "c_x") if _near(s.g[0, 2], s.W / 2) else ("v", "H", "c_y"))),
    ),
    Mistake(
        "c_x from the height",
        lambda s: _near(s.g[0, 2], s.cy) and (not _near(s.cx, s.cy)),
        lambda s: (
            f"c_x comes from the width: (W - 1) / 2 with W = size[0] = {s.W}; you used the height H = {s.H} "
            f"(size is (width, height), as in OpenCV)"
        ),
    ),
    Mistake(
        "c_y from the width",
        lambda s: _near(s.g[1, 2], s.cx) and (not _near(s.cx, s.cy)),
        lambda s: (
            f"c_y comes from the height: (H - 1) / 2 with H = size[1] = {s.H}; you used the width W = {s.W} "
            f"(size is (width, height), as in OpenCV)"
        ),
    ),
    Mistake(
        "principal point in millimetres",
        lambda s: _near(s.g[0, 2], s.w_mm / 2) or _near(s.g[1, 2], s.h_mm / 2),
        lambda s: (
            f"c_x and c_y are in pixels, not millimetres: sensor_mm / 2 = ({s.w_mm / 2:g}, {s.h_mm / 2:g}) mm is "
            f"the centre's distance from the sensor's corner; in pixels it is ((W - 1) / 2, (H - 1) / 2) = "
            f"({s.cx:g}, {s.cy:g})"
        ),
    ),
    Mistake(
        "centre at the image size",
        lambda s: _near(s.g[0, 2], s.W - 1) or _near(s.g[0, 2], s.W) or _near(s.g[1, 2], s.H - 1),
        (
            "the principal point is the image centre, (W - 1) / 2 and (H - 1) / 2, not the image size"
        ),
    ),
    Mistake(
        "f in millimetres",
        lambda s: _near(s.g[0, 0], s.f_mm) or _near(s.g[1, 1], s.f_mm),
        (
            "f_x is in pixels, not millimetres: divide the focal length by the pixel pitch, f_x = f / s_x with "
            "s_x = sensor width / W (both in mm, so the units cancel)"
        ),
    ),
    *(
        _unit_slip(factor, unit)
        for factor, unit in (
            (1e3, "1000 times too large"),
            (1e-3, "1000 times too small"),
            (1e6, "a million times too large"),
            (1e-6, "a million times too small"),
        )
    ),
    *(
        Mistake(
            f"centimetres, {unit}",
            lambda s, factor=factor: (
                _near(s.g[0, 0], s.fx * factor) and _near(s.g[1, 1], s.fy * factor)
            ),
            lambda s, unit=unit: (
                f"f_x and f_y are {unit}: a centimetre slip? f_mm = {s.f_mm:g} is already in millimetres, like "
                f"sensor_mm; f / s_x with both in mm is in pixels"
            ),
        )
        for factor, unit in ((0.1, "10 times too small"), (10, "10 times too large"))
    ),
    Mistake(
        "pitch along the diagonal",
        lambda s: (
            _near(s.g[0, 0], s.diagonal)
            and _near(s.g[1, 1], s.diagonal)
            and (not _near(s.fx, s.fy))
        ),
        lambda s: (
            f"you took the pitch along the diagonal, sqrt(w**2 + h**2) / sqrt(W**2 + H**2); that is each axis's "
            f"pitch only for square pixels, and here s_x = {s.w_mm / s.W * 1e3:.4g} µm, s_y = {s.h_mm / s.H * 1e3:.4g} µm: "
            f"s_x = width / W and s_y = height / H, each from its own axis"
        ),
    ),
    *AXIS_AND_SIGN_SLIPS,
    Mistake(
        "width over H",
        lambda s: (
            _near(s.g[1, 1], s.f_mm * s.H / s.w_mm) and (not _near(s.fy, s.f_mm * s.H / s.w_mm))
        ),
        (
            "s_y = height / H: you divided the sensor's width by H (sensor_mm = (width, height): height is sensor_mm[1])"
        ),
    ),
    Mistake(
        "height over W",
        lambda s: (
            _near(s.g[0, 0], s.f_mm * s.W / s.h_mm) and (not _near(s.fx, s.f_mm * s.W / s.h_mm))
        ),
        (
            "s_x = width / W: you divided the sensor's height by W (sensor_mm = (width, height): width is sensor_mm[0])"
        ),
    ),
    Mistake(
        "s_x / f",
        lambda s: _near(s.g[0, 0], 1 / s.fx) or _near(s.g[0, 0], s.w_mm / s.W / s.f_mm),
        ("f_x = f / s_x, not s_x / f: the focal length in units of the pixel pitch"),
    ),
    Mistake(
        "f times the pitch",
        lambda s: (
            _near(s.g[0, 0], s.f_mm * s.w_mm / s.W) or _near(s.g[1, 1], s.f_mm * s.h_mm / s.H)
        ),
        (
            "you multiplied the focal length by the pitch, f * s_x; divide: f_x = f / s_x counts how many pixel "
            "pitches fit in the focal length, so finer pixels give a larger f_x"
        ),
    ),
    Mistake(
        "half f_x",
        lambda s: _near(s.g[0, 0], s.fx / 2) or _near(s.g[1, 1], s.fy / 2),
        (
            "f_x is half the right value: did you use half the sensor (width / 2) or double the pitch? "
            "f_x = f / s_x with s_x = width / W, the pitch of one pixel; the half width belongs to the field "
            "of view, tan(fov / 2) = (width / 2) / f"
        ),
    ),
    Mistake(
        "twice f_x",
        lambda s: _near(s.g[0, 0], 2 * s.fx) or _near(s.g[1, 1], 2 * s.fy),
        (
            "f_x is twice the right value: did you halve the pitch (width / 2 / W), or take the pitch of a "
            "Quad-Bayer sensor's 48 MP (8064 pixels across) for a 12 MP image? A binned image's pixel is a 2 x 2 "
            "group of the sensor's; f_x = f / s_x with s_x = width / W, W the width of the image you work with"
        ),
    ),
    Mistake(
        "35 mm-equivalent focal length",
        lambda s: _near(s.g[0, 0], s.fx * np.hypot(36, 24) / np.hypot(s.w_mm, s.h_mm)),
        lambda s: (
            f"f_x is {np.hypot(36, 24) / np.hypot(s.w_mm, s.h_mm):.2f} times the right value, the ratio of a full "
            f"frame's 43.3 mm diagonal to this sensor's {np.hypot(s.w_mm, s.h_mm):.2f} mm: you used the "
            f"35 mm-equivalent focal length, a field of view; K needs the real one, f_x = f / s_x"
        ),
    ),
    EQUIVALENT_OVER_FULL_WIDTH,
    Mistake(
        "W - 1 pixels",
        lambda s: (
            _near(s.g[0, 0], s.f_mm * (s.W - 1) / s.w_mm)
            or _near(s.g[1, 1], s.f_mm * (s.H - 1) / s.h_mm)
        ),
        (
            "the pitch is sensor width / W: W pixels tile the width (W - 1 counts the gaps between centres)"
        ),
    ),
    *PITCH_SLIPS,
    Mistake(
        "square pixels assumed",
        lambda s: (_near(s.g[1, 1], s.fx) or _near(s.g[0, 0], s.fy)) and (not _near(s.fx, s.fy)),
        lambda s: (
            f"pixels need not be square: here s_x = {s.w_mm / s.W * 1e3:.4g} µm and s_y = {s.h_mm / s.H * 1e3:.4g} µm, so "
            f"f_x = f / s_x and f_y = f / s_y differ; compute each from its own axis"
        ),
    ),
    Mistake(
        "skew",
        lambda s: not _near(s.g[0, 1], 0),
        ("K[0, 1] is the skew, 0 for a sensor with perpendicular rows and columns"),
    ),
    Mistake(
        "rounded pitch",
        lambda s: np.allclose(s.g, s.e, rtol=0.01, atol=0),
        lambda s: (
            "within 1 % but not exact: a rounded intermediate value, such as the pitch rounded to a few digits "
            f"({s.w_mm / s.W * 1e3:.2f} µm for {s.w_mm / s.W * 1e3:.6g} µm)? Keep full precision: the check allows a relative 1e-9 (widened for a float32 K to a few of its 1e-7 steps)"
        ),
    ),
)
"""The datasheet slips, in the order they are tested: each row's test reads the answer ``s.g`` and the
input (``s.f_mm``, ``s.w_mm``, ``s.h_mm``, ``s.W``, ``s.H``), against the right ``s.fx``, ``s.fy``,
``s.cx``, ``s.cy``."""


def _datasheet_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + " (K is 3 x 3)"
    f_mm, (w_mm, h_mm), (W, H) = args
    g, e = np.asarray(got, dtype=float), np.asarray(expected)
    fx, fy, cx, cy = e[0, 0], e[1, 1], e[0, 2], e[1, 2]

    if np.issubdtype(np.asarray(got).dtype, np.integer):
        named = {"f_x": fx, "f_y": fy, "c_x = (W - 1) / 2": cx, "c_y = (H - 1) / 2": cy}
        cut = [
            f"{what} = {value:.6g}"
            for what, value in named.items()
            if not np.isclose(value, np.round(value))
        ]
        lost = (
            (
                f"it cannot hold {' or '.join(cut)}, so {'they were' if len(cut) > 1 else 'it was'} cut to "
                f"{'whole numbers' if len(cut) > 1 else 'a whole number'}"
            )
            if cut
            else "it holds whole numbers only"
        )
        return (
            f"K is an integer array (dtype {np.asarray(got).dtype}): {lost}. Build K from floats "
            f"(np.array([[...]], dtype=float), or write 0.0 and 1.0) and leave out .astype(int)"
        )

    context = SimpleNamespace(
        g=g,
        e=e,
        f_mm=f_mm,
        w_mm=w_mm,
        h_mm=h_mm,
        W=W,
        H=H,
        fx=fx,
        fy=fy,
        cx=cx,
        cy=cy,
        # f_x from the field of view, 2 atan(width / 2 / f), turned into degrees and passed to np.tan
        fx_degrees=W / 2 / np.tan(np.degrees(2 * np.arctan(w_mm / 2 / f_mm)) / 2),
        fy_degrees=H / 2 / np.tan(np.degrees(2 * np.arctan(h_mm / 2 / f_mm)) / 2),
        diagonal=f_mm
        * np.hypot(W, H)
        / np.hypot(w_mm, h_mm),  # f over the pitch along the diagonal
    )
    return first_mistake(_MISTAKES, context) or (
        "K = [[f / s_x, 0, (W - 1) / 2], [0, f / s_y, (H - 1) / 2], [0, 0, 1]] with s_x = width / W, s_y = height / H"
    )


def intrinsics_from_datasheet(f_mm, sensor_mm, size):
    """K in pixels from a datasheet: focal length (mm), sensor (width, height) in mm, resolution (W, H) in pixels.

    Parameters
    ----------
    f_mm : float
        The lens's focal length, mm.
    sensor_mm : (2,) array_like
        The sensor's active area (width, height), mm.
    size : (2,) array_like of int
        The resolution (W, H), pixels.

    Returns
    -------
    (3, 3) ndarray
        K = [[f / s_x, 0, (W - 1)/2], [0, f / s_y, (H - 1)/2], [0, 0, 1]], with the pixel pitch
        (s_x, s_y) = sensor_mm / size in mm per pixel and pixel centres at whole numbers.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 6.1 (alpha_x = f m_x).
    """
    W, H = size
    sx, sy = sensor_mm[0] / W, sensor_mm[1] / H  # pixel pitch, mm per pixel (need not be square)
    return np.array(
        [
            [f_mm / sx, 0.0, (W - 1) / 2],  # f in pixels: f / pitch, both in mm
            [0.0, f_mm / sy, (H - 1) / 2],  # pixel centres at integers: the centre is (W - 1) / 2
            [0.0, 0.0, 1.0],
        ]
    )


def _datasheet_variant(f_mm, sensor_mm, size, *, fx=None, fy=None, cx=None, cy=None):
    K = _datasheet_reference(f_mm, sensor_mm, size)
    for (i, j), v in (((0, 0), fx), ((1, 1), fy), ((0, 2), cx), ((1, 2), cy)):
        if v is not None:
            K[i, j] = v
    return K


register_exercise(
    Exercise(
        name="intrinsics_from_datasheet",
        lesson="03",
        reference=_datasheet_reference,
        cases=_datasheet_cases,
        compare=SameArray(Tolerance(1e-9, 1e-9)),
        diagnose=_datasheet_diagnosis,
        ndarray_only=True,  # the prompt asks for a numpy array, as every other matrix exercise does
        wrong_variants=(
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f * 43.27 / np.hypot(*s) * n[0] / 36
                ),
                "f_eq * W / 36",
            ),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f * n[0] / np.hypot(*s), fy=f * n[1] / np.hypot(*s)
                ),
                "the diagonal belongs to neither axis",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=-(n[0] - 1) / 2),
                "sign flipped",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=s[0] / 2, cy=s[1] / 2),
                "in pixels, not millimetres",
            ),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=n[0] / 2 / np.tan(np.degrees(2 * np.arctan(s[0] / 2 / f)) / 2)
                ),
                "with the angle in degrees",
            ),
            (lambda f, s, n: _datasheet_reference(f, s, n).T, "transposed"),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=(n[1] - 1) / 2, cy=(n[0] - 1) / 2),
                "swapped",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=n[0] / 2, cy=n[1] / 2),
                "half a pixel off",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cy=n[1] / 2),
                "c_y is (H - 1) / 2, not H / 2",
            ),
            (lambda f, s, n: _datasheet_variant(f, s, n, fx=f, fy=f), "not millimetres"),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f / (s[0] / n[0] * 1e3), fy=f / (s[1] / n[1] * 1e3)
                ),
                "1000 times too small",
            ),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f * 1e-3 / (s[0] / n[0] * 1e-6), fy=f * 1e-3 / (s[1] / n[1] * 1e-6)
                ),
                "1000 times too large",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fx=s[0] / n[0] / f, fy=s[1] / n[1] / f),
                "not s_x / f",
            ),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f * (n[0] - 1) / s[0], fy=f * (n[1] - 1) / s[1]
                ),
                "W pixels tile",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fx=f * n[0] / s[0], fy=f * n[0] / s[0]),
                "need not be square",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fx=f * n[1] / s[1], fy=f * n[0] / s[0]),
                "f_x and f_y are swapped",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=n[0] - 1, cy=n[1] - 1),
                "not the image size",
            ),
            (
                lambda f, s, n: _datasheet_variant(
                    f,
                    s,
                    n,
                    fx=f * n[1] / s[0],
                    fy=f * n[0] / s[1],
                    cx=(n[1] - 1) / 2,
                    cy=(n[0] - 1) / 2,
                ),
                "H, W = size",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fx=f * n[0] / s[1], fy=f * n[1] / s[0]),
                "sensor_mm is (width, height)",
            ),
            (lambda f, s, n: _datasheet_variant(f, s, n, fy=-f * n[1] / s[1]), "no minus sign"),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=(n[0] + 1) / 2, cy=(n[1] + 1) / 2),
                "numbered from 1",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=(n[0] - 1) // 2, cy=(n[1] - 1) // 2),
                "integer division",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=n[0] // 2 - 0.5, cy=n[1] // 2 - 0.5),
                "only for an even W",
            ),
            (lambda f, s, n: _datasheet_reference(f, s, n)[:2], "shape (3, 3)"),
            (lambda f, s, n: _datasheet_reference(f, s, n).astype(int), "integer array"),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, cx=np.round((n[0] - 1) / 2), cy=np.round((n[1] - 1) / 2)
                ),
                "keep the .5",
            ),
            (lambda f, s, n: _datasheet_reference(f, s, n).tolist(), "you returned a list"),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f / 10 * n[0] / s[0], fy=f / 10 * n[1] / s[1]
                ),
                "centimetre",
            ),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f * np.hypot(*n) / np.hypot(*s), fy=f * np.hypot(*n) / np.hypot(*s)
                ),
                "along the diagonal",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fy=f * n[1] / s[0]),
                "divided the sensor's width by H",
            ),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f / round(s[0] / n[0], 5), fy=f / round(s[1] / n[1], 5)
                ),
                "rounded",
            ),
            (lambda f, s, n: None, "return"),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=n[0] / 2 - 1, cy=n[1] / 2 - 1),
                "W / 2 - 1",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=n[0] - 1 / 2, cy=n[1] - 1 / 2),
                "Python divides before it subtracts",
            ),
            (lambda f, s, n: _datasheet_variant(f, s, n, cx=0.0, cy=0.0), "the top-left pixel"),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fx=f * s[0] / n[0], fy=f * s[1] / n[1]),
                "multiplied the focal",
            ),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f * n[0] / s[0] / 2, fy=f * n[1] / s[1] / 2
                ),
                "half the sensor",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fx=f * n[0] / s[0] * 1e3),
                "f_x is 1000 times too large",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=(n[1] - 1) / 2),
                "c_x comes from the width",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fx=-f * n[0] / s[0]),
                "both positive lengths",
            ),
        ),
        teaching=intrinsics_from_datasheet,
    )
)
