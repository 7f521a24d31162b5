"""Lesson 01's exercise project_to_pixels: the pinhole projection in pixels, (u, v) = f X / Z / pitch + centre."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import pinhole
from .._answers import same_array, shape_problem
from .._core import Exercise, Mistake, first_mistake, register_exercise

# ---------------------------------------------------------------- project_to_pixels

PIXEL_ATOL = 1e-3
"""How close (pixels) an answer must be: a thousandth of a pixel, loose enough for a projection computed in
float32 (about 2e-4 px at u = 3600) and far tighter than any slip below (the smallest, half a pixel)."""


def _pixel_reference(X, f, pitch, size):
    """camlab.pinhole.project_pinhole(X, f) / pitch + ((W - 1) / 2, (H - 1) / 2): the projection, in pixels."""
    W, H = size
    return pinhole.project_pinhole(X, f) / pitch + [(W - 1) / 2, (H - 1) / 2]


def _pixel_cases():
    rng = np.random.default_rng(7)
    pts = np.column_stack([rng.uniform(-0.8, 0.8, (6, 2)), rng.uniform(1.5, 6, 6)])
    return [
        (
            np.array([[0.15, -0.15, 1.85]]),
            0.05,
            112.5e-6,
            (320, 240),
        ),  # the worked example's camera, an unturned box corner
        (
            np.array([[0.4, 0.1, 2.0], [-0.2, 0.3, 4.0]]),
            0.03,
            6e-6,
            (640, 480),
        ),  # (2, 2) / (2,) broadcasts
        (pts, 0.024, 4e-6, (1280, 720)),
    ]


def _broadcast_divide(a: np.ndarray, w: np.ndarray) -> np.ndarray:
    """``a / w`` for an (N, 2) ``a`` and an (N,) ``w`` as numpy broadcasts it.

    Column j is divided by w[j]; NaN where numpy cannot broadcast (N other than 1 or 2): the slip of
    dividing by a depth column that was not kept 2-D.
    """
    return a / w if len(w) in (1, 2) else np.full(a.shape, np.nan)


def _pixel_context(X, f, pitch, size, e):
    """What the rows of :data:`_PIXEL_SLIPS` read.

    The input, the right answer ``e``, the centre ``c`` and the numbers the slips start from.
    """
    W, H = size
    c = np.array([(W - 1) / 2, (H - 1) / 2])
    K = np.array([[f / pitch, 0.0, c[0]], [0.0, f / pitch, c[1]], [0.0, 0.0, 1.0]])
    return SimpleNamespace(
        X=X,
        f=f,
        pitch=pitch,
        e=e,
        c=c,
        m=e - c,  # the projection in pixels, before the centre is added
        metres=f * X[:, :2] / X[:, 2:3],
        homogeneous=X @ K.T,  # rows (u w, v w, w), w = Z
        x_at_K=X @ K,
        aspect=size[1] / size[0],  # H / W
        W=W,
    )


_PIXEL_SLIPS = (
    Mistake(
        "half a pixel",
        lambda s: s.e + 0.5,
        (
            "a half-pixel offset: with pixel centres at integers the image's centre is at ((W - 1) / 2,"
            " (H - 1) / 2), e.g. 159.5 for 320 pixels, not W / 2"
        ),
    ),
    Mistake(
        "size swapped",
        lambda s: s.m + s.c[::-1],
        (
            "width and height swapped: size is (width, height), so c_u = (W - 1) / 2 comes from size[0]"
            " and c_v = (H - 1) / 2 from size[1]"
        ),
    ),
    Mistake(
        "size swapped and half a pixel",
        lambda s: s.m + s.c[::-1] + 0.5,
        (
            "width and height swapped (size is (width, height)) and a half-pixel offset (the centre"
            " is (W - 1) / 2, not W / 2)"
        ),
    ),
    Mistake(
        "no principal point",
        lambda s: s.m,
        (
            "you left out the principal point: pixel (0, 0) is the image's top-left pixel, so add the centre"
            " ((W - 1) / 2, (H - 1) / 2)"
        ),
    ),
    Mistake(
        "rotated 180 degrees",
        lambda s: s.c - s.m,
        (
            "your image is rotated by 180 degrees: that is the real image behind the pinhole; use the virtual"
            " plane, u = f_x X / Z + c_u"
        ),
    ),
    Mistake(
        "v flipped",
        lambda s: np.column_stack([s.e[:, 0], s.c[1] - s.m[:, 1]]),
        (
            "you flipped v: in the camera frame y points down, and so does v"
            " (row numbers grow downwards): v = f_y Y / Z + c_v, no minus"
        ),
    ),
    Mistake(
        "centre added to metres",
        lambda s: s.metres + s.c,
        (
            "you added the centre (pixels) to x = f X / Z (metres): divide by the pixel pitch first,"
            " f_x = f / pitch"
        ),
    ),
    Mistake(
        "times the pitch",
        lambda s: s.metres * s.pitch + s.c,
        ("you multiplied by the pitch; divide by it: f_x = f / pitch pixels"),
    ),
    Mistake(
        "1000 times too large",
        lambda s: s.m * 1e3 + s.c,
        (
            "the projection is 1000 times too large: f in millimetres with the pitch in metres? Keep both in"
            " metres (f_x = f / pitch is a pure number of pixels)"
        ),
    ),
    Mistake(
        "1000 times too small",
        lambda s: s.m / 1e3 + s.c,
        (
            "the projection is 1000 times too small: the pitch in millimetres with f in metres? Keep both"
            " in metres"
        ),
    ),
    Mistake(
        "centre added before the pitch",
        lambda s: s.m + s.c / s.pitch,
        (
            "you added the centre before dividing by the pitch: (f X / Z + c) / pitch divides the centre too;"
            " the centre is already in pixels, so add it after the division: f X / Z / pitch + c"
        ),
    ),
    Mistake(
        "depth from column 1",
        lambda s: s.f / s.pitch * s.X[:, :2] / s.X[:, 1:2] + s.c,
        (
            "you divided by column 1 (Y) instead of the depth Z: Python counts from 0, so Z is column 2,"
            " X[:, 2:3]"
        ),
    ),
    Mistake(
        "depth from column 0",
        lambda s: s.f / s.pitch * s.X[:, :2] / s.X[:, 0:1] + s.c,
        ("you divided by column 0 (X) instead of the depth Z: Z is column 2, X[:, 2:3]"),
    ),
    Mistake(
        "f_y scaled by H / W",
        lambda s: np.column_stack([s.e[:, 0], s.m[:, 1] * s.aspect + s.c[1]]),
        (
            "you scaled f_y by H / W: the pixels are square (one pitch for both axes), so f_y = f_x = f / pitch;"
            " the image's shape sets only the centre"
        ),
    ),
    Mistake(
        "f_y scaled by W / H",
        lambda s: np.column_stack([s.e[:, 0], s.m[:, 1] / s.aspect + s.c[1]]),
        (
            "you scaled f_y by W / H: the pixels are square (one pitch for both axes), so f_y = f_x = f / pitch;"
            " the image's shape sets only the centre"
        ),
    ),
    Mistake(
        "no division by Z",
        lambda s: s.f / s.pitch * s.X[:, :2] + s.c,
        ("you did not divide by the depth Z: u = f_x X / Z + c_u"),
    ),
    Mistake(
        "columns 1 and 2",
        lambda s: s.f / s.pitch * s.X[:, 1:3] / s.X[:, 2:3] + s.c,
        (
            "you took columns 1 and 2 (Y and Z): Python counts from 0, so X is"
            " column 0, Y column 1 and Z column 2"
        ),
    ),
    Mistake(
        "over the distance",
        lambda s: s.f / s.pitch * s.X[:, :2] / np.linalg.norm(s.X, axis=1, keepdims=True) + s.c,
        ("you divided by the distance to the point; divide by its depth Z (the third coordinate)"),
    ),
    Mistake(
        "u and v swapped",
        lambda s: s.m[:, ::-1] + s.c,
        ("u and v are swapped: column 0 is u (from X), column 1 is v (from Y)"),
    ),
    Mistake(
        "(v, u) order",
        lambda s: s.e[:, ::-1],
        (
            "your columns are (v, u), the row-then-column order of img[v, u]; a pixel coordinate is (u, v):"
            " column 0 is u (from X, across), column 1 is v (from Y, down)"
        ),
    ),
    Mistake(
        "off by one",
        lambda s: s.e + 1,
        (
            "off by one: 1-based pixels. Python and OpenCV count pixels from 0, so the centre of a W-pixel row is"
            " (W - 1) / 2 (159.5 for 320 pixels), not (W + 1) / 2"
        ),
    ),
    Mistake(
        "integer division",
        lambda s: s.e - 0.5,
        (
            "the centre is (W - 1) / 2 = W / 2 - 0.5, a half-integer (159.5 for 320 pixels); yours is"
            " W / 2 - 1 (159): an integer division (W - 1) // 2 drops the .5 (divide with /, not //)"
        ),
    ),
    Mistake(
        "half a pixel in u",
        lambda s: s.e + [0.5, 0],
        ("a half-pixel offset in u only: c_u = (W - 1) / 2, as c_v = (H - 1) / 2 (not W / 2)"),
    ),
    Mistake(
        "half a pixel in v",
        lambda s: s.e + [0, 0.5],
        ("a half-pixel offset in v only: c_v = (H - 1) / 2, as c_u = (W - 1) / 2 (not H / 2)"),
    ),
    Mistake(
        "c_u for both",
        lambda s: s.m + s.c[0],
        (
            "you used (W - 1) / 2 for both coordinates: c_v = (H - 1) / 2 comes from the height, size[1]"
        ),
    ),
    Mistake(
        "c_v for both",
        lambda s: s.m + s.c[1],
        (
            "you used (H - 1) / 2 for both coordinates: c_u = (W - 1) / 2 comes from the width, size[0]"
        ),
    ),
    Mistake(
        "no c_v",
        lambda s: s.m + [s.c[0], 0],
        ("you left out c_v: add the centre to both coordinates, v = f_y Y / Z + (H - 1) / 2"),
    ),
    Mistake(
        "no c_u",
        lambda s: s.m + [0, s.c[1]],
        ("you left out c_u: add the centre to both coordinates, u = f_x X / Z + (W - 1) / 2"),
    ),
    Mistake(
        "u negated",
        lambda s: np.column_stack([s.c[0] - s.m[:, 0], s.e[:, 1]]),
        ("you negated u only: u = f_x X / Z + c_u, with no minus sign"),
    ),
    Mistake(
        "over Z + f",
        lambda s: s.f / s.pitch * s.X[:, :2] / (s.X[:, 2:3] + s.f) + s.c,
        (
            "you divided by Z + f: the similar triangles meet at the pinhole,"
            " so the legs are Z and f, u = f_x X / Z + c_u"
        ),
    ),
    Mistake(
        "homogeneous not divided",
        lambda s: s.f / s.pitch * s.X[:, :2] + s.c * s.X[:, 2:3],
        (
            "you used the homogeneous form K X but did not divide by its third"
            " coordinate w = Z: (u, v) = (K X)[:2] / (K X)[2]"
        ),
    ),
    Mistake(
        "centre divided by Z",
        lambda s: (s.f / s.pitch * s.X[:, :2] + s.c) / s.X[:, 2:3],
        (
            "you added the centre before dividing by Z, so the centre was divided too: divide first, then add"
            " the centre, u = f_x X / Z + c_u"
        ),
    ),
    Mistake(
        "over Z squared",
        lambda s: s.f / s.pitch * s.X[:, :2] / s.X[:, 2:3] ** 2 + s.c,
        ("you divided by Z twice (Z ** 2): one division by the depth, u = f_x X / Z + c_u"),
    ),
    Mistake(
        "f_x divided by W",
        lambda s: s.f / (s.pitch * s.W) * s.X[:, :2] / s.X[:, 2:3] + s.c,
        (
            "you divided f by the sensor's width in pixels too: f_x = f / pitch alone is the focal length in"
            " pixels (the width sets only the centre)"
        ),
    ),
    Mistake(
        "broadcasting slip",
        lambda s: _broadcast_divide(s.homogeneous[:, :2], s.homogeneous[:, 2]),
        (
            "a broadcasting slip in the division by w: x[:, :2] / x[:, 2] divides"
            " column j by the w of point j; keep w 2-D, x[:, 2:3] (keepdims)"
        ),
    ),
    Mistake(
        "X @ K",
        lambda s: s.x_at_K[:, :2] / s.x_at_K[:, 2:3],
        ("X @ K multiplies by K transposed: with points as rows, K X is X @ K.T"),
    ),
)
"""The pixel projection's slips, as the answers they give, in the order they are tested."""


def _pixel_diagnosis(args, got, expected) -> str:
    X, f, pitch, size = args
    g = np.asarray(got, dtype=float) if not isinstance(got, (str, bytes)) else None
    if (
        g is not None
        and g.shape == expected.T.shape
        and g.shape != expected.shape
        and np.allclose(g.T, expected)
    ):
        return "your array is transposed: return one (u, v) row per point, shape (N, 2) (use .T, or np.column_stack)"
    W, H = size
    c = np.array([(W - 1) / 2, (H - 1) / 2])
    if g is not None and g.dtype.kind in "biuf" and g.shape == (len(X), 3):
        homogeneous = f / pitch * X + np.column_stack([c[0] * X[:, 2], c[1] * X[:, 2], 0 * X[:, 2]])
        homogeneous[:, 2] = X[:, 2]
        if np.allclose(g, homogeneous):
            return (
                "you returned the homogeneous (u w, v w, w) = K X: divide by the third coordinate w and keep the"
                " first two, shape (N, 2)"
            )
        if np.allclose(g[:, :2], expected) or np.allclose(g[:, :2] / g[:, 2:3], expected):
            return "you returned three columns: keep only (u, v), shape (N, 2), after dividing by w"
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return one (u, v) row per point."
    broadcast = _broadcast_divide(f / pitch * X[:, :2], X[:, 2]) + c
    # only where the slip changes the answer (two points; with one, X[:, 2] broadcasts harmlessly)
    if not np.allclose(broadcast, expected, rtol=0, atol=PIXEL_ATOL) and np.allclose(
        g, broadcast, rtol=0, atol=PIXEL_ATOL
    ):
        return (
            "a broadcasting slip: X[:, :2] / X[:, 2] divides column j by the depth of point j; keep the depth"
            " column 2-D, X[:, 2:3], so each row is divided by its own Z"
        )
    cause = first_mistake(
        _PIXEL_SLIPS,
        _pixel_context(X, f, pitch, size, expected),
        g,
        # within PIXEL_ATOL, or a thousandth of the slip's own offset from the centre where that is smaller: slips
        # that squeeze every point onto the centre (a pitch in micrometres, times the pitch) stay told apart
        lambda got, slip: np.allclose(
            got, slip, rtol=0, atol=min(PIXEL_ATOL, 1e-3 * np.abs(slip - c).max())
        ),
    )
    if cause:
        return cause
    m, m_got = expected - c, g - c
    for k, cause in (
        (
            -2,
            "a million times too small: the pitch in micrometres (112.5 for 112.5 um) with f in metres?",
        ),
        (2, "a million times too large: f in micrometres, or the pitch in kilometres?"),
    ):
        if np.allclose(m_got, m * 1000.0**k, rtol=1e-9, atol=1e-9):
            return f"the projection (before the centre) is {cause} Keep f and the pitch in metres"
    if np.allclose(g, np.round(g)) and np.all(np.abs(g - expected) <= 1.0):
        return (
            "you rounded to whole pixels: return the exact (u, v); a projected point falls between pixel centres,"
            " and later lessons measure errors in fractions of a pixel"
        )
    return "check each step: x = f X / Z (metres), divide by the pitch (pixels), add the centre ((W - 1) / 2, (H - 1) / 2)"


def project_to_pixels(X, f, pitch, size):
    """Pixel coordinates (u, v) of camera-frame points on the virtual image.

    x = f X / Z on the image plane (metres); divide by the pitch for pixels, f_x = f / pitch;
    add the principal point, the centre of a W x H image with pixel centres at integers.

    Parameters
    ----------
    X : (N, 3) array_like
        Points in the camera frame (x right, y down, z forward), m, with Z > 0.
    f : float
        The focal length, m.
    pitch : float
        The pixel pitch, m per pixel (square pixels).
    size : (2,) array_like of int
        The image's (W, H), pixels.

    Returns
    -------
    (N, 2) ndarray
        (u, v) = (f / pitch) (X / Z, Y / Z) + ((W - 1)/2, (H - 1)/2), pixels.
    """
    X = np.asarray(X, dtype=float)
    W, H = size
    fx = f / pitch  # focal length in pixels
    centre = np.array([(W - 1) / 2, (H - 1) / 2])  # (c_u, c_v)
    return fx * X[:, :2] / X[:, 2:3] + centre  # X[:, 2:3] keeps Z as a column: one depth per row


register_exercise(
    Exercise(
        name="project_to_pixels",
        lesson="01",
        reference=_pixel_reference,
        cases=_pixel_cases,
        compare=same_array(rtol=1e-9, atol=PIXEL_ATOL),
        diagnose=_pixel_diagnosis,
        ndarray_only=True,
        wrong_variants=(
            (lambda X, f, s, size: f / s * X[:, :2] / X[:, 2:3] + np.array(size) / 2, "half-pixel"),
            (
                lambda X, f, s, size: f / s * X[:, :2] / X[:, 2:3] + (np.array(size[::-1]) - 1) / 2,
                "width and height",
            ),
            (lambda X, f, s, size: f / s * X[:, :2] / X[:, 2:3], "principal point"),
            (
                lambda X, f, s, size: (f / s * X[:, :2] / X[:, 2:3] + (np.array(size) - 1) / 2)[
                    :, ::-1
                ],
                "your columns are",
            ),
            (
                lambda X, f, s, size: f * X[:, :2] / X[:, 2:3] + (np.array(size) - 1) / 2,
                "divide by the pixel pitch",
            ),
            (
                lambda X, f, s, size: 1e3 * f / s * X[:, :2] / X[:, 2:3] + (np.array(size) - 1) / 2,
                "millimetres",
            ),
            (
                lambda X, f, s, size: f / s * X[:, :2] / X[:, 2] + (np.array(size) - 1) / 2,
                "broadcasting",
            ),
            (
                lambda X, f, s, size: (np.array(size) - 1) / 2 - f / s * X[:, :2] / X[:, 2:3],
                "real image",
            ),
            (
                lambda X, f, s, size: (
                    f / s * X[:, :2] / X[:, 2:3] * [1, -1] + (np.array(size) - 1) / 2
                ),
                "flipped v",
            ),
            (
                lambda X, f, s, size: (f / s * X[:, :2] / X[:, 2:3] + (np.array(size) - 1) / 2).T,
                "transposed",
            ),
            (
                lambda X, f, s, size: (
                    f / s * X[:, :2] / X[:, 2:3] + (np.array(size) - 1) / 2
                ).tolist(),
                "numpy array",
            ),
            (
                lambda X, f, s, size: f / s * X[:, 1:3] / X[:, 3:4] + (np.array(size) - 1) / 2,
                "counting columns from 1",
            ),
            (
                lambda X, f, s, size: f / s * X[:, :2] / X[:, 2:3] + (np.array(size) - 1) // 2,
                "integer division",
            ),
            (lambda X, f, s, size: f"{f / s * X[0, 0] / X[0, 2]:.1f}", "you returned a str"),
            (
                lambda X, f, s, size: (f / s * X[:, :2] + (np.array(size) - 1) / 2) / X[:, 2:3],
                "the centre was divided too",
            ),
            (
                lambda X, f, s, size: f / s * X[:, :2] / X[:, 2:3] ** 2 + (np.array(size) - 1) / 2,
                "Z twice",
            ),
            (
                lambda X, f, s, size: (
                    f / (s * size[0]) * X[:, :2] / X[:, 2:3] + (np.array(size) - 1) / 2
                ),
                "f_x = f / pitch alone",
            ),
        ),
        teaching=project_to_pixels,
    )
)
