"""Exercises for lesson 01, the pinhole camera.

The lesson asks for three: ``project_to_pixels`` (the pinhole projection in pixels),
``focal_length_pixels`` (f_x from a field of view) and ``best_pinhole_exposure`` (the light a
best pinhole costs). ``pinhole_projection`` and ``best_pinhole_diameter``, the lesson's first
two exercises (their answers are printed in the lesson itself), stay registered: the course's
tests of the check machinery use them.
"""

from __future__ import annotations

import numpy as np

from .. import pinhole
from ._answers import Tolerance, same_array, shape_problem, unit_slip
from ._core import Exercise, register_exercise
from ._numbers import SameNumber, is_number


def _projection_cases():
    rng = np.random.default_rng(1)
    pts = np.column_stack([rng.uniform(-1, 1, (6, 2)), rng.uniform(1, 5, 6)])
    return [
        (np.array([[0.5, -0.25, 2.0]]), 0.05),
        (
            np.array([[0.0, 0.0, 1.0], [0.2, 0.4, 4.0]]),
            0.1,
        ),  # (2, 2) / (2,) broadcasts: a silent slip
        (pts, 0.035),
    ]


def _projection_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return one (x, y) row per point."
    slip = unit_slip(got, expected)
    if slip:
        return slip
    g = np.asarray(got, dtype=float)
    X, f = args
    if np.allclose(g, f * X[:, :2] / X[:, 2]):
        return (
            "a broadcasting slip: X[:, :2] / X[:, 2] divides column j by the depth of point j; "
            "keep the depth column 2-D, X[:, 2:3], so each row is divided by its own Z"
        )
    for variant, cause in _PROJECTION_SLIPS:
        if np.allclose(g, variant(X, f, expected)):
            return cause
    return "check the similar triangles: x / f = X / Z and y / f = Y / Z"


_PROJECTION_SLIPS = (  # (what the slip returns, given X, f and the right answer; its likely cause)
    (
        lambda X, f, e: -e,
        "your image is inverted: that is the real image behind the pinhole; use the virtual plane,"
        " x = f X / Z",
    ),
    (
        lambda X, f, e: e * [1, -1],
        "you negated y only: in the camera frame y points down, and the virtual image keeps"
        " that, y = f Y / Z with no minus sign (a y-up habit from maths plots?)",
    ),
    (lambda X, f, e: e * [-1, 1], "you negated x only: x = f X / Z, with no minus sign"),
    (
        lambda X, f, e: e[:, ::-1],
        "x and y are swapped: column 0 is x = f X / Z, column 1 is y = f Y / Z",
    ),
    (
        lambda X, f, e: f * X[:, 1:3] / X[:, 2:3],
        "you took columns 1 and 2 (y and Z) for x and y: Python counts from 0,"
        " so X is column 0, Y column 1 and Z column 2",
    ),
    (lambda X, f, e: f * X[:, :2], "you did not divide by the depth Z: x = f X / Z"),
    (lambda X, f, e: X[:, :2] / X[:, 2:3], "you forgot to multiply by the focal length f"),
    (
        lambda X, f, e: X[:, :2] / X[:, 2:3] / f,
        "you divided by f: x / f = X / Z, so x = f X / Z (multiply by f)",
    ),
    (
        lambda X, f, e: X[:, :2] * X[:, 2:3] / f,
        "you multiplied by Z and divided by f: the other way round, x = f X / Z",
    ),
    (
        lambda X, f, e: f * X[:, :2] / (X[:, 2:3] + f),
        "you divided by Z + f: the similar triangles meet at the pinhole,"
        " so the legs are Z and f, x = f X / Z",
    ),
    (
        lambda X, f, e: f * X[:, :2] / np.linalg.norm(X, axis=1, keepdims=True),
        "you divided by the distance to the point; divide by its depth Z (the third coordinate): x = f X / Z",
    ),
)


def pinhole_projection(X, f):
    """Virtual image of camera-frame points: x = f X / Z, y = f Y / Z (similar triangles)."""
    X = np.asarray(X, dtype=float)
    Z = X[:, 2:3]  # (N, 1), so one division scales both columns
    return f * X[:, :2] / Z


register_exercise(
    Exercise(
        name="pinhole_projection",
        lesson="01",
        reference=pinhole.project_pinhole,
        cases=_projection_cases,
        compare=same_array(rtol=1e-9, atol=1e-12),
        diagnose=_projection_diagnosis,
        wrong_variants=(
            (lambda X, f: -f * X[:, :2] / X[:, 2:3], "inverted"),
            (lambda X, f: f * X[:, :2], "divide by the depth"),
            (lambda X, f: X[:, :2] / X[:, 2:3], "multiply by the focal length"),
            (lambda X, f: 1e3 * f * X[:, :2] / X[:, 2:3], "millimetres"),
            (lambda X, f: f * X[:, :2] / X[:, 2], "broadcasting"),
            (lambda X, f: f * X[:, :2] / X[:, 2:3] * [1, -1], "negated y only"),
            (lambda X, f: (f * X[:, :2] / X[:, 2:3])[:, ::-1], "swapped"),
            (lambda X, f: X[:, :2] / X[:, 2:3] / f, "divided by f"),
            (lambda X, f: f * X[:, 1:3] / X[:, 2:3], "counts from 0"),
            (lambda X, f: f * X[:, 1:3] / X[:, 3:4], "counting columns from 1"),
        ),
        teaching=pinhole_projection,
    )
)


def _best_cases():
    return [(0.1, 550e-9), (0.05, 450e-9), (0.25, 650e-9)]


def _best_diagnosis(args, got, expected) -> str:
    f, lam = args
    try:
        g = float(got)
    except (TypeError, ValueError):
        return "return a single number: the diameter in metres"
    slip = unit_slip(got, expected) or _slip_under_root(g / expected)
    if slip:
        return slip
    for wrong, cause in (
        (
            np.sqrt(1.22 * lam * f),
            "you used the Airy disc's radius 1.22 lambda f / d; the blur to minimise adds"
            " diameters: d + 2.44 lambda f / d",
        ),
        (np.sqrt(lam * f), "you dropped the 2.44 of the Airy disc: minimise d + 2.44 lambda f / d"),
        (
            1.9 * np.sqrt(lam * f),
            "that is Rayleigh's 1.9 sqrt(lambda f), from another blur criterion; this exercise"
            " minimises the summed diameters d + 2.44 lambda f / d",
        ),
        (
            2.44 * lam * f,
            "you forgot the square root: setting the derivative 1 - 2.44 lambda f / d^2 to zero gives"
            " d^2 = 2.44 lambda f",
        ),
        (
            2 * expected,
            "you returned the blur at the best hole, b(d*) = 2 d*; return the diameter d* itself",
        ),
        (expected / 2, "you returned a radius, d*/2; return the hole's diameter"),
        (np.sqrt(2.44 * lam / f), "f belongs in the numerator: d^2 = 2.44 lambda f"),
        (
            np.sqrt(2.44 * 550e-9 * f),
            "you used 550 nm; use the `wavelength` argument (this test input is"
            f" {lam * 1e9:.0f} nm)",
        ),
    ):
        if np.isclose(g, wrong, rtol=1e-3, atol=0):
            return cause
    return "minimise the total blur d + 2.44 lambda f / d over d (a distant object)"


class NearMinimumBlur:
    """``Exercise.compare`` for the best diameter: one number whose total blur is within :attr:`excess` of the least.

    b(d) = d + 2.44 lambda f / d = d + d*^2 / d, so b(r d*) / b(d*) = (r + 1/r) / 2 depends only on
    r = got / expected. A numerical minimiser's answer (scipy's bounded ``minimize_scalar`` stops
    within a few tenths of a percent of d*, where the curve is flat) passes; an answer off by
    4.5 % or more does not, nor does any mistake the diagnosis names (the nearest, 550 nm for
    450 nm, is 10 % off).
    """

    excess = 1e-3

    def __call__(self, got, expected) -> bool:
        if not is_number(got) or not float(got) > 0:
            return False
        r = float(got) / float(expected)
        return (r + 1 / r) / 2 - 1 <= self.excess


def _slip_under_root(ratio: float) -> str | None:
    """A unit slip inside the square root: the answer off by sqrt(1000^k), e.g. f in mm or lambda in nm."""
    k = np.log10(ratio**2) / 3
    if abs(k - round(k)) > 0.01 or round(k) == 0:
        return None
    return (
        f"your answer is {ratio:.3g} times the expected one, sqrt(1000^{round(k)}): a unit slipped inside the"
        " square root (f in mm, or lambda in nm or um?); keep f and the wavelength in metres"
    )


def best_pinhole_diameter(f, wavelength):
    """Minimise b(d) = d + 2.44 wavelength f / d: b'(d) = 1 - 2.44 wavelength f / d**2 = 0."""
    return float(np.sqrt(2.44 * wavelength * f))


register_exercise(
    Exercise(
        name="best_pinhole_diameter",
        lesson="01",
        reference=pinhole.optimal_pinhole_diameter,
        cases=_best_cases,
        compare=NearMinimumBlur(),
        diagnose=_best_diagnosis,
        wrong_variants=(
            (lambda f, lam: float(np.sqrt(lam * f)), "2.44"),
            (lambda f, lam: 2.44 * lam * f, "square root"),
            (lambda f, lam: 1e3 * float(np.sqrt(2.44 * lam * f)), "millimetres"),
            (lambda f, lam: float(np.sqrt(2.44 * lam * f * 1e3)), "f in mm"),
            (lambda f, lam: float(np.sqrt(2.44 * lam * 1e-9 * f)), "nm"),
            (lambda f, lam: float(np.sqrt(1.22 * lam * f)), "radius"),
            (lambda f, lam: 1.9 * float(np.sqrt(lam * f)), "Rayleigh"),
            (lambda f, lam: 2 * float(np.sqrt(2.44 * lam * f)), "blur at the best hole"),
            (lambda f, lam: float(np.sqrt(2.44 * lam * f)) / 2, "a radius"),
            (lambda f, lam: float(np.sqrt(2.44 * 550e-9 * f)), "wavelength"),
        ),
        teaching=best_pinhole_diameter,
    )
)


# ---------------------------------------------------------------- project_to_pixels


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
    """``a / w`` for an (N, 2) ``a`` and an (N,) ``w`` as numpy broadcasts it (column j by w[j]), NaN where it cannot
    (N other than 1 or 2): the slip of dividing by a depth column that was not kept 2-D."""
    return a / w if len(w) in (1, 2) else np.full(a.shape, np.nan)


def _pixel_slips(X, f, pitch, size, e):
    """(what a slip returns, its likely cause) for the pixel projection, given the right answer ``e``."""
    W, H = size
    c = np.array([(W - 1) / 2, (H - 1) / 2])
    m = e - c  # the projection in pixels, before the centre is added
    metres = f * X[:, :2] / X[:, 2:3]
    K = np.array([[f / pitch, 0.0, c[0]], [0.0, f / pitch, c[1]], [0.0, 0.0, 1.0]])
    homogeneous = X @ K.T  # rows (u w, v w, w), w = Z
    x_at_K = X @ K
    return (
        (
            e + 0.5,
            "a half-pixel offset: with pixel centres at integers the image's centre is at ((W - 1) / 2,"
            " (H - 1) / 2), e.g. 159.5 for 320 pixels, not W / 2",
        ),
        (
            m + c[::-1],
            "width and height swapped: size is (width, height), so c_u = (W - 1) / 2 comes from size[0]"
            " and c_v = (H - 1) / 2 from size[1]",
        ),
        (
            m + c[::-1] + 0.5,
            "width and height swapped (size is (width, height)) and a half-pixel offset (the centre"
            " is (W - 1) / 2, not W / 2)",
        ),
        (
            m,
            "you left out the principal point: pixel (0, 0) is the image's top-left pixel, so add the centre"
            " ((W - 1) / 2, (H - 1) / 2)",
        ),
        (
            c - m,
            "your image is rotated by 180 degrees: that is the real image behind the pinhole; use the virtual"
            " plane, u = f_x X / Z + c_u",
        ),
        (
            np.column_stack([e[:, 0], c[1] - m[:, 1]]),
            "you flipped v: in the camera frame y points down, and so does v"
            " (row numbers grow downwards): v = f_y Y / Z + c_v, no minus",
        ),
        (
            metres + c,
            "you added the centre (pixels) to x = f X / Z (metres): divide by the pixel pitch first,"
            " f_x = f / pitch",
        ),
        (metres * pitch + c, "you multiplied by the pitch; divide by it: f_x = f / pitch pixels"),
        (
            m * 1e3 + c,
            "the projection is 1000 times too large: f in millimetres with the pitch in metres? Keep both in"
            " metres (f_x = f / pitch is a pure number of pixels)",
        ),
        (
            m / 1e3 + c,
            "the projection is 1000 times too small: the pitch in millimetres with f in metres? Keep both"
            " in metres",
        ),
        (f / pitch * X[:, :2] + c, "you did not divide by the depth Z: u = f_x X / Z + c_u"),
        (
            f / pitch * X[:, 1:3] / X[:, 2:3] + c,
            "you took columns 1 and 2 (Y and Z): Python counts from 0, so X is"
            " column 0, Y column 1 and Z column 2",
        ),
        (
            f / pitch * X[:, :2] / np.linalg.norm(X, axis=1, keepdims=True) + c,
            "you divided by the distance to the point; divide by its depth Z (the third coordinate)",
        ),
        (m[:, ::-1] + c, "u and v are swapped: column 0 is u (from X), column 1 is v (from Y)"),
        (
            e + 1,
            "off by one: 1-based pixels. Python and OpenCV count pixels from 0, so the centre of a W-pixel row is"
            " (W - 1) / 2 (159.5 for 320 pixels), not (W + 1) / 2",
        ),
        (
            e - 0.5,
            "the centre is (W - 1) / 2 = W / 2 - 0.5, a half-integer (159.5 for 320 pixels); yours is"
            " W / 2 - 1 (159): an integer division (W - 1) // 2 drops the .5 (divide with /, not //)",
        ),
        (
            e + [0.5, 0],
            "a half-pixel offset in u only: c_u = (W - 1) / 2, as c_v = (H - 1) / 2 (not W / 2)",
        ),
        (
            e + [0, 0.5],
            "a half-pixel offset in v only: c_v = (H - 1) / 2, as c_u = (W - 1) / 2 (not H / 2)",
        ),
        (
            m + c[0],
            "you used (W - 1) / 2 for both coordinates: c_v = (H - 1) / 2 comes from the height, size[1]",
        ),
        (
            m + c[1],
            "you used (H - 1) / 2 for both coordinates: c_u = (W - 1) / 2 comes from the width, size[0]",
        ),
        (
            m + [c[0], 0],
            "you left out c_v: add the centre to both coordinates, v = f_y Y / Z + (H - 1) / 2",
        ),
        (
            m + [0, c[1]],
            "you left out c_u: add the centre to both coordinates, u = f_x X / Z + (W - 1) / 2",
        ),
        (
            np.column_stack([c[0] - m[:, 0], e[:, 1]]),
            "you negated u only: u = f_x X / Z + c_u, with no minus sign",
        ),
        (
            f / pitch * X[:, :2] / (X[:, 2:3] + f) + c,
            "you divided by Z + f: the similar triangles meet at the pinhole,"
            " so the legs are Z and f, u = f_x X / Z + c_u",
        ),
        (
            f / pitch * X[:, :2] + c * X[:, 2:3],
            "you used the homogeneous form K X but did not divide by its third"
            " coordinate w = Z: (u, v) = (K X)[:2] / (K X)[2]",
        ),
        (
            _broadcast_divide(homogeneous[:, :2], homogeneous[:, 2]),
            "a broadcasting slip in the division by w: x[:, :2] / x[:, 2] divides"
            " column j by the w of point j; keep w 2-D, x[:, 2:3] (keepdims)",
        ),
        (
            x_at_K[:, :2] / x_at_K[:, 2:3],
            "X @ K multiplies by K transposed: with points as rows, K X is X @ K.T",
        ),
    )


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
    if np.allclose(g, _broadcast_divide(f / pitch * X[:, :2], X[:, 2]) + c):
        return (
            "a broadcasting slip: X[:, :2] / X[:, 2] divides column j by the depth of point j; keep the depth"
            " column 2-D, X[:, 2:3], so each row is divided by its own Z"
        )
    for variant, cause in _pixel_slips(X, f, pitch, size, expected):
        if np.allclose(g, variant, rtol=1e-9, atol=1e-6):
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
        compare=same_array(rtol=1e-9, atol=1e-6),
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
        ),
        teaching=project_to_pixels,
    )
)


# ---------------------------------------------------------------- focal_length_pixels


def _fx_reference(fov_deg, size):
    """f_x = (W / 2) / tan(FOV / 2): the sensor's half-width W / 2 pixels seen at half the field of view."""
    W = size[0]
    return float(W / 2 / np.tan(np.radians(fov_deg) / 2))


def _fx_cases():
    # no 60 or 90 degrees: tan 30 = 1 / tan 60 and tan 45 = 1 make slips coincide with each other or the answer
    return [(50.0, (640, 480)), (75.0, (1920, 1080)), (39.6, (320, 240))]


FX_TOLERANCE = Tolerance(2e-4, 0.0)
"""f_x to 0.1 px passes (a rounded 444.4 is 9e-5 off); (W - 1) / 2 for W / 2 (5e-4 off at W = 1920) does not."""


def _one_number(got, what: str) -> str | None:
    """Why ``got`` is not one number (a list or an array of numbers, say), or None."""
    if np.ndim(got) != 0:
        kind = "numpy array" if isinstance(got, np.ndarray) else type(got).__name__
        return (
            f"you returned a {kind} of shape {np.shape(got)}; return one number, {what} (a float:"
            f" take the entry out, x[0], or build a number, not a list or an array)"
        )
    try:
        float(got)
    except (TypeError, ValueError):
        return f"return one number: {what}"
    return None


def _fx_diagnosis(args, got, expected) -> str:
    fov, (W, H) = args
    problem = _one_number(got, "f_x in pixels")
    if problem:
        return problem
    g = float(got)
    half, full = np.radians(fov) / 2, np.radians(fov)
    for wrong, cause in (
        (
            W / 2 / np.tan(fov / 2),
            "np.tan takes radians: convert the field of view with np.radians(fov_deg) first",
        ),
        (
            W / np.tan(fov / 2),
            "np.tan takes radians (np.radians(fov_deg)), and the half-width is W / 2",
        ),
        (
            W / 2 / np.tan(full),
            "use half the field of view: the ray to the sensor's edge makes FOV / 2 with the axis,"
            " so tan(FOV / 2) = (W / 2) / f_x",
        ),
        (
            W / np.tan(half),
            "the ray to the sensor's edge runs W / 2 pixels sideways, not W: tan(FOV / 2) = (W / 2) / f_x",
        ),
        (
            W / np.tan(full),
            "both halves missing: tan(FOV / 2) = (W / 2) / f_x (half the angle, half the width)",
        ),
        (
            (W - 1) / 2 / np.tan(half),
            "the sensor spans all W pixels: its edges are the outer edges of the first and"
            " last pixels, W pixels apart; (W - 1) / 2 is the centre's coordinate, not the"
            " half-width",
        ),
        (
            (W + 1) / 2 / np.tan(half),
            "off by one, 1-based: (W + 1) / 2 is the centre pixel counted from 1; the half-width is W / 2,"
            " since the sensor's edges are the outer edges of its first and last pixels",
        ),
        (
            (W - 1) // 2 / np.tan(half),
            "(W - 1) // 2 is the centre pixel's index rounded down by the integer division"
            " //; the half-width is W / 2 (the sensor's edges are the outer edges of its"
            " first and last pixels), and divide with /",
        ),
        (
            W / full,
            "the small-angle shortcut tan(a) ~ a: FOV / 2 is no small angle (tan 25 deg is 0.466, against"
            " 0.436 rad); use the tangent itself, f_x = (W / 2) / tan(FOV / 2)",
        ),
        (
            W / 2 / np.arctan(half),
            "arctan is the inverse of tan: tan(FOV / 2) = (W / 2) / f_x needs np.tan, not"
            " np.arctan",
        ),
        (
            W / 2 / np.radians(np.tan(fov / 2)),
            "np.radians(np.tan(...)) converts the tangent, a plain number, as if it"
            " were an angle: convert the angle first, np.tan(np.radians(fov_deg) / 2)",
        ),
        (
            W / 2 / np.tan(half / 2),
            "the angle is halved twice: np.radians(fov_deg) / 2 is already FOV / 2 (or"
            " np.radians(fov_deg / 2)); do not halve it again",
        ),
        (
            H / 2 / np.tan(half),
            "size is (width, height): the horizontal field of view spans the width, size[0]",
        ),
        (
            W / 2 / np.sin(half),
            "tan, not sin: the right triangle has legs f_x (along the axis) and W / 2 (across)",
        ),
        (
            2 * np.tan(half) / W,
            "upside down: tan(FOV / 2) = (W / 2) / f_x, so f_x = (W / 2) / tan(FOV / 2)",
        ),
        (
            np.degrees(2 * np.arctan(W / (2 * fov))),
            "that is the field-of-view formula run the other way; solve"
            " FOV = 2 atan(W / (2 f_x)) for f_x",
        ),
        (
            W / 2 * np.tan(half),
            "you multiplied by tan(FOV / 2); divide: tan(FOV / 2) = (W / 2) / f_x, so"
            " f_x = (W / 2) / tan(FOV / 2)",
        ),
        (-expected, "a sign flip: f_x is a positive length, (W / 2) / tan(FOV / 2)"),
        (
            np.hypot(W, H) / 2 / np.tan(half),
            "you used the diagonal, hypot(W, H): the field of view here is the"
            " horizontal one, across the width W",
        ),
        (
            0.018 / np.tan(half),
            "that is f in metres for section 2's 36 mm sensor; the answer is in pixels, the"
            " sensor's W pixels: f_x = (W / 2) / tan(FOV / 2)",
        ),
        (
            18 / np.tan(half),
            "that is f in millimetres for section 2's 36 mm sensor; the answer is in pixels, the"
            " sensor's W pixels: f_x = (W / 2) / tan(FOV / 2)",
        ),
    ):
        if np.isclose(g, wrong, rtol=1e-6):
            return cause
    if abs(g - expected) <= 1.0 and g == round(g):
        return (
            "you rounded f_x to a whole pixel (round() or int()); return it unrounded, or to 0.1 px at least: a"
            " focal length in pixels is a measurement, not a pixel index"
        )
    return (
        "tan(FOV / 2) = (W / 2) / f_x, so f_x = (W / 2) / tan(FOV / 2); the tangent of the half-angle in radians,"
        " np.tan(np.radians(fov_deg) / 2)"
    )


def focal_length_pixels(fov_deg, size):
    """f_x in pixels for a horizontal field of view ``fov_deg`` (degrees) and an image ``size`` (width, height).

    The edge ray makes FOV / 2 with the axis and meets the sensor W / 2 pixels from its centre:
    tan(FOV / 2) = (W / 2) / f_x.
    """
    width = size[0]
    half_angle = np.radians(fov_deg) / 2
    return float(width / 2 / np.tan(half_angle))


register_exercise(
    Exercise(
        name="focal_length_pixels",
        lesson="01",
        reference=_fx_reference,
        cases=_fx_cases,
        compare=SameNumber(FX_TOLERANCE),
        diagnose=_fx_diagnosis,
        wrong_variants=(
            (lambda fov, size: size[0] / 2 / np.tan(fov / 2), "radians"),
            (lambda fov, size: size[0] / 2 / np.tan(np.radians(fov)), "half the field of view"),
            (lambda fov, size: size[0] / np.tan(np.radians(fov) / 2), "W / 2"),
            (lambda fov, size: (size[0] - 1) / 2 / np.tan(np.radians(fov) / 2), "all W pixels"),
            (lambda fov, size: size[1] / 2 / np.tan(np.radians(fov) / 2), "(width, height)"),
            (lambda fov, size: np.array([size[0] / 2 / np.tan(np.radians(fov) / 2)]), "one number"),
            (lambda fov, size: size[0] / 2 * np.tan(np.radians(fov) / 2), "you multiplied by tan"),
            (lambda fov, size: float(int(size[0] / 2 / np.tan(np.radians(fov) / 2))), "rounded"),
            (lambda fov, size: np.hypot(*size) / 2 / np.tan(np.radians(fov) / 2), "diagonal"),
            (lambda fov, size: 0.018 / np.tan(np.radians(fov) / 2), "f in metres"),
            (lambda fov, size: (size[0] + 1) / 2 / np.tan(np.radians(fov) / 2), "1-based"),
            (
                lambda fov, size: (size[0] - 1) // 2 / np.tan(np.radians(fov) / 2),
                "integer division",
            ),
            (lambda fov, size: size[0] / np.radians(fov), "small-angle"),
            (
                lambda fov, size: size[0] / 2 / np.arctan(np.radians(fov) / 2),
                "arctan is the inverse",
            ),
            (lambda fov, size: size[0] / 2 / np.tan(np.radians(fov / 2) / 2), "halved twice"),
            (lambda fov, size: (size[0] / 2 / np.tan(np.radians(fov) / 2),), "trailing comma"),
            (
                lambda fov, size: f"{size[0] / 2 / np.tan(np.radians(fov) / 2):.1f}",
                "you returned a str",
            ),
        ),
        teaching=focal_length_pixels,
    )
)


# ---------------------------------------------------------------- best_pinhole_exposure


def _exposure_reference(f, wavelength, t_lens, N_lens):
    """t_lens (f / d* / N_lens)^2 with d* = camlab.pinhole.optimal_pinhole_diameter(f, wavelength), in seconds."""
    d_star = pinhole.optimal_pinhole_diameter(f, wavelength)
    return float(t_lens * (f / d_star / N_lens) ** 2)


class NearMinimumExposure:
    """``Exercise.compare`` for the exposure time: the time of a hole whose blur is within 0.05 % of the least.

    The time goes as 1 / d^2, so a time t against the right t* means a hole r = sqrt(t* / t) times d*,
    whose blur is (r + 1/r) / 2 times the least (:class:`NearMinimumBlur`). Within 0.05 % is r within
    3.2 % of 1, a time within about 6.5 %: a hole found numerically on the flat minimum passes (scipy's
    bounded ``minimize_scalar`` with its default xatol of 1e-5 m stops up to 3 % from a 0.23 mm d*, so
    1 % on the time, 0.5 % on d, was too tight); Rayleigh's hole (22 % wider), a 550 nm hole for 450 nm
    (10 % wider) and the best hole for an object 1 m away (5 % narrower at f = 0.1 m) do not.
    """

    excess = 5e-4

    def __call__(self, got, expected) -> bool:
        if not is_number(got) or not float(got) > 0:
            return False
        r = np.sqrt(float(expected) / float(got))
        return (r + 1 / r) / 2 - 1 <= self.excess


def _exposure_cases():
    return [(0.1, 550e-9, 1 / 100, 2.8), (0.05, 450e-9, 1 / 250, 4.0), (0.3, 650e-9, 1 / 60, 8.0)]


def _exposure_diagnosis(args, got, expected) -> str:
    f, lam, t, N = args
    problem = _one_number(got, "the exposure time in seconds")
    if problem:
        return problem
    g = float(got)
    d = np.sqrt(2.44 * lam * f)
    Np = f / d
    for wrong, cause in (
        (t * Np / N, "light goes as the hole's area, (d / f)^2: square the ratio of the f-numbers"),
        (
            t * (N / Np) ** 2,
            "upside down: the pinhole gathers less light than the lens, so it needs the longer"
            " exposure, t (N_pinhole / N_lens)^2",
        ),
        (t * (d / f / N) ** 2, "the f-number is f / d (a large number for a pinhole), not d / f"),
        (
            t * (d / N) ** 2,
            "the f-number is f / d, a ratio of lengths: divide f by the hole's diameter",
        ),
        (t * (f / np.sqrt(lam * f) / N) ** 2, "you dropped the 2.44 from d* = sqrt(2.44 lambda f)"),
        (
            t * (f / np.sqrt(1.22 * lam * f) / N) ** 2,
            "you used the Airy radius's 1.22; the best hole (section 3) is"
            " d* = sqrt(2.44 lambda f)",
        ),
        (
            t * (f / (1.9 * np.sqrt(lam * f)) / N) ** 2,
            "that is Rayleigh's hole, 1.9 sqrt(lambda f); this lesson's best"
            " hole is d* = sqrt(2.44 lambda f)",
        ),
        (t * (f / (2.44 * lam * f) / N) ** 2, "d* needs the square root: d* = sqrt(2.44 lambda f)"),
        (
            t * (f / (d / 2) / N) ** 2,
            "you used the hole's radius; the f-number is f over the diameter d*",
        ),
        (Np, "you returned the pinhole's f-number f / d*; return the exposure time in seconds"),
        (d, "you returned the best diameter d*; return the exposure time in seconds"),
        (
            t * Np**2 / N,
            "square N_lens too: the light goes as 1 / N^2 for the lens as for the pinhole, so the"
            " time is t_lens (N / N_lens)^2 = t_lens N^2 / N_lens^2",
        ),
        (
            t * Np / N**2,
            "square the pinhole's f-number too: the time is t_lens (N / N_lens)^2 = t_lens N^2 / N_lens^2",
        ),
        (
            t * np.sqrt(Np / N),
            "square the ratio, do not take its root: light goes as the hole's area, (d / f)^2, so"
            " the time is t_lens (N / N_lens)^2",
        ),
        (
            t * (f / (2 * d) / N) ** 2,
            "you used the best blur, 2 d*, as the hole: b(d*) = d* + d* = 2 d* is the blur"
            " at the best hole; the hole itself is d* = sqrt(2.44 lambda f)",
        ),
        (
            (Np / N) ** 2,
            "you returned the ratio of the exposure times, (N / N_lens)^2; multiply by the lens's time"
            " t_lens for the pinhole's time in seconds",
        ),
        (
            1e3 * expected,
            "your answer is 1000 times the expected one: milliseconds, or f in millimetres (the time"
            " goes as N^2 = f / (2.44 lambda), so it grows with f)? The answer is in seconds, with f and"
            " the wavelength in metres",
        ),
        (expected / 60, "you answered in minutes; the answer is in seconds"),
        (expected / 3600, "you answered in hours; the answer is in seconds"),
        (
            t * (f / np.sqrt(2.44 * 550e-9 * f) / N) ** 2,
            "you used 550 nm; use the `wavelength` argument (this test"
            f" input is {lam * 1e9:.0f} nm)",
        ),
        (
            t * (f / np.sqrt(2.44 * lam * f / (1 + f / 1.0)) / N) ** 2,
            "you used the best hole for an object 1 m away, sqrt(2.44 lambda f / (1 + f/Z)); this camera looks at a"
            " distant object (Z -> infinity): d* = sqrt(2.44 lambda f)",
        ),
    ):
        if np.isclose(
            g, wrong, rtol=1e-3, atol=0
        ):  # atol=0: a tiny variant must not match an answer of 0
            return cause
    if not np.isfinite(g) or g <= 0:
        return (
            f"an exposure time is a positive number of seconds, but you returned {g:g}: check the signs, and that "
            "the square root's argument 2.44 lambda f is positive (every length in metres)"
        )
    ratio = g / expected
    k = np.log10(ratio) / 3
    if (
        abs(k - round(k)) < 1.5e-4 and round(k) != 0
    ):  # within 0.1 % of a power of 1000: true unit slips are exact
        return (
            f"your answer is {ratio:.3g} times the expected one: a unit slip (the wavelength in nm or um, or f in"
            " mm?); keep every length in metres, and the time in seconds"
        )
    return "exposure time t_lens (N / N_lens)^2, with the pinhole's f-number N = f / d* and d* = sqrt(2.44 lambda f)"


def best_pinhole_exposure(f, wavelength, t_lens, N_lens):
    """Exposure time (s) of a pinhole camera of length f with its best hole, matching a lens at N_lens for t_lens.

    The light on the image goes as (d / f)^2 = 1 / N^2, so the exposure time goes as N^2.
    """
    d_star = np.sqrt(2.44 * wavelength * f)  # the best hole for a distant object (section 3)
    N = f / d_star  # its f-number
    return float(t_lens * (N / N_lens) ** 2)


register_exercise(
    Exercise(
        name="best_pinhole_exposure",
        lesson="01",
        reference=_exposure_reference,
        cases=_exposure_cases,
        compare=NearMinimumExposure(),
        diagnose=_exposure_diagnosis,
        wrong_variants=(
            (lambda f, lam, t, N: t * f / np.sqrt(2.44 * lam * f) / N, "square the ratio"),
            (lambda f, lam, t, N: t * (N * np.sqrt(2.44 * lam * f) / f) ** 2, "upside down"),
            (lambda f, lam, t, N: t * (np.sqrt(2.44 * lam * f) / f / N) ** 2, "not d / f"),
            (lambda f, lam, t, N: t * (f / np.sqrt(lam * f) / N) ** 2, "2.44"),
            (lambda f, lam, t, N: t * (f / (1.9 * np.sqrt(lam * f)) / N) ** 2, "Rayleigh"),
            (lambda f, lam, t, N: t * (f / np.sqrt(2.44 * lam * 1e-9 * f) / N) ** 2, "unit slip"),
            (lambda f, lam, t, N: f / np.sqrt(2.44 * lam * f), "f-number"),
            (lambda f, lam, t, N: 1e3 * t * (f / np.sqrt(2.44 * lam * f) / N) ** 2, "milliseconds"),
            (
                lambda f, lam, t, N: (f / np.sqrt(2.44 * lam * f) / N) ** 2,
                "multiply by the lens's time",
            ),
            (lambda f, lam, t, N: t * (f / np.sqrt(2.44 * 550e-9 * f) / N) ** 2, "you used 550 nm"),
            (
                lambda f, lam, t, N: t * (f / np.sqrt(2.44 * lam * f / (1 + f)) / N) ** 2,
                "distant object",
            ),
            (lambda f, lam, t, N: t * (f / np.sqrt(2.44 * lam * f) / N) ** 2 / 60, "minutes"),
            (lambda f, lam, t, N: t * (f / np.sqrt(2.44 * lam * f)) ** 2 / N, "square N_lens too"),
            (
                lambda f, lam, t, N: t * np.sqrt(f / np.sqrt(2.44 * lam * f) / N),
                "do not take its root",
            ),
            (
                lambda f, lam, t, N: t * (f / (2 * np.sqrt(2.44 * lam * f)) / N) ** 2,
                "the best blur, 2 d*, as the hole",
            ),
            (lambda f, lam, t, N: [t * (f / np.sqrt(2.44 * lam * f) / N) ** 2], "brackets"),
            (
                lambda f, lam, t, N: f"{t * (f / np.sqrt(2.44 * lam * f) / N) ** 2:.0f} s",
                "you returned a str",
            ),
        ),
        teaching=best_pinhole_exposure,
    )
)
