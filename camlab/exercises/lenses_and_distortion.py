"""Exercises for lesson 02: focus and field of view, depth of field, and lens distortion.

Each exercise asks for something the lesson has not printed: the field of view of a lens
focused closer than infinity (the thin lens of section 1 with the field of view of
section 3), distortion in pixels (section 4's model between K^-1 and K), the aperture that
makes a given depth range sharp (section 2's c(z) solved the other way), and one Newton
step of undistortion from any current estimate (so the whole 2 x 2 Jacobian matters).
"""

from __future__ import annotations

import numpy as np

from .. import distortion, lens
from ._core import Exercise, register_exercise, same_array, shape_problem
from ._numbers import is_number as _is_number
from ._numbers import not_one_number, same_number

# -- field_of_view ----------------------------------------------------------------------------


def _field_of_view_cases():
    # the first case focuses close (z_i = 1.2 f), so every slip in z_i or in the angle shows at once
    return [(0.05, 0.036, 0.3), (0.035, 0.0236, 2.0), (0.1, 0.036, 0.25), (0.024, 0.0063, 0.1)]


def _field_of_view_diagnosis(args, got, expected) -> str:
    f, w, zo = args
    if not _is_number(got):
        return not_one_number(got, "the field of view in radians")
    g = float(got)
    zi = f * zo / (zo - f)

    def fov(distance, width=w):
        return 2 * np.arctan(width / (2 * distance))

    if np.isclose(g, np.degrees(expected)):
        return "that is the angle in degrees; the course's functions return radians (np.degrees only for printing)"
    if np.isclose(-g, expected):
        return "the angle came out negative: a sign slip; the field of view 2 arctan(w / (2 z_i)) is positive"
    if g < 0:
        return (
            "the angle came out negative, so your z_i is negative: 1/f - 1/z_o < 0 means z_o < f in your units. "
            "Mixed units? (f in millimetres, z_o in metres: 50 mm 'inside' 0.3 m); keep every length in metres"
        )
    if np.isclose(g, 2 * np.tan(w / (2 * zi))):
        return "you took the tangent of the ratio; the angle is its arctangent: 2 np.arctan(w / (2 z_i))"
    if np.isclose(g, fov(f)):
        return (
            "that is the field of view focused at infinity, 2 arctan(w / 2f); focused at z_o the sensor sits at "
            "z_i = f z_o / (z_o - f), farther than f, so the pinhole focal length is z_i: 2 arctan(w / (2 z_i))"
        )
    if np.isclose(g, fov(zo)):
        return (
            "you used the object distance z_o; the angle is set on the sensor's side: half the sensor width "
            "over the lens-to-sensor distance z_i = f z_o / (z_o - f)"
        )
    if np.isclose(g, np.arctan(w / (2 * zi))):
        return "that is the half-angle; the field of view spans both sides of the axis: 2 arctan(w / (2 z_i))"
    if np.isclose(g, 2 * np.arctan(w / zi)) or np.isclose(g, np.arctan(w / zi)):
        return (
            "half the sensor width goes with the half-angle: tan(FOV / 2) = (w / 2) / z_i, so "
            "FOV = 2 arctan(w / (2 z_i))"
        )
    if np.isclose(g, w / zi):
        return (
            "w / z_i is the small-angle approximation; take the arctangent: 2 arctan(w / (2 z_i))"
        )
    m = -f / (zo - f)  # the signed magnification, negative for a real image
    for wrong, hint in (
        (
            f * zo / (zo + f),
            "sign slip in the thin lens: 1/z_i = 1/f - 1/z_o, so z_i = f z_o / (z_o - f)",
        ),
        (
            f * (1 + m),
            "z_i = (1 + |m|) f takes the size of m; the signed m = -f / (z_o - f) is negative "
            "for a real image, so f (1 + m) comes out shorter than f instead of longer",
        ),
        (
            f * (1 + f / zo),
            "f (1 + f / z_o) is the first-order approximation of z_i (good only for "
            "z_o >> f); the check wants the exact thin lens, z_i = f z_o / (z_o - f)",
        ),
        (
            f**2 / (zo - f),
            "f^2 / (z_o - f) is the image's distance from the focal point F', not from "
            "the lens; the lens-to-sensor distance is f plus that: z_i = f z_o / (z_o - f)",
        ),
        (1 / f - 1 / zo, "you used 1/z_i as the distance; invert it: z_i = 1 / (1/f - 1/z_o)"),
    ):
        if np.isclose(g, fov(wrong)):
            return hint
    if np.isclose(g, fov(zo - f)):
        return (
            "z_o - f is not where the image forms (it is the object's distance from the focal point F); the "
            "thin lens puts it at z_i = f z_o / (z_o - f), from 1/f = 1/z_o + 1/z_i"
        )
    for diagonal in (np.hypot(w, 2 * w / 3), np.hypot(w, 3 * w / 4), 0.0433):
        if np.isclose(g, fov(zi, diagonal)) or np.isclose(g, fov(f, diagonal)):
            return (
                "that is the diagonal field of view; the horizontal one uses the sensor's width w as given: "
                "2 arctan(w / (2 z_i))"
            )
    if np.isclose(g, fov(zi, f)) or (
        zo > w and np.isclose(g, 2 * np.arctan(f / (2 * w * zo / (zo - w))))
    ):
        return "w and f are swapped: the sensor width w goes over the lens-to-sensor distance, 2 arctan(w / (2 z_i))"
    for factor in (1e3, 1e-3):
        if np.isclose(g, fov(zi, w * factor)):
            return (
                "mixed units: the width and the distance must be in one unit (the inputs are all in metres; "
                "0.036 is 36 mm)"
            )
    return (
        "find z_i from 1/f = 1/z_o + 1/z_i, then the field of view 2 arctan(w / (2 z_i)) in radians"
    )


def _field_of_view_note(run) -> str:
    """Exercise 1's question, answered with the student's own function once it passes."""
    close, far = np.degrees(run(0.05, 0.036, 0.3)), np.degrees(2 * np.arctan(0.036 / (2 * 0.05)))
    return (
        f"The question: a 50 mm lens on full frame (w = 36 mm) sees {far:.1f} deg focused at infinity and "
        f"{close:.1f} deg focused at 0.3 m (z_i = 60 mm): {far - close:.1f} deg, {1 - close / far:.0%} narrower."
    )


def field_of_view(f, w, z_o):
    """Horizontal field of view (radians) of a lens f focused at z_o on a sensor w wide (metres)."""
    z_i = f * z_o / (z_o - f)  # the sensor's distance behind the lens: the pinhole focal length
    return 2 * np.arctan(w / (2 * z_i))  # half the width over z_i is the tangent of the half-angle


register_exercise(
    Exercise(
        name="field_of_view",
        lesson="02",
        reference=lens.angle_of_view,
        cases=_field_of_view_cases,
        compare=same_number(rtol=1e-9),
        diagnose=_field_of_view_diagnosis,
        success_note=_field_of_view_note,
        wrong_variants=(
            (lambda f, w, zo: 2 * np.arctan(w / (2 * f)), "focused at infinity"),
            (lambda f, w, zo: np.degrees(2 * np.arctan(w / (2 * f * zo / (zo - f)))), "degrees"),
            (lambda f, w, zo: np.arctan(w / (2 * f * zo / (zo - f))), "half-angle"),
            (lambda f, w, zo: 2 * np.arctan(w / (f * zo / (zo - f))), "half the sensor width"),
            (lambda f, w, zo: w / (f * zo / (zo - f)), "small-angle"),
            (lambda f, w, zo: 2 * np.arctan(w / (2 * f * zo / (zo + f))), "sign slip"),
            (
                lambda f, w, zo: 2 * np.arctan(w / (2 * f**2 / (zo - f))),
                "from the focal point F', not from",
            ),
            (
                lambda f, w, zo: 2 * np.arctan(w / (2 * f * (1 - f / (zo - f)))),
                "takes the size of m",
            ),
            (
                lambda f, w, zo: 2 * np.arctan(w / (2 * f * (1 + f / zo))),
                "first-order approximation",
            ),
            (
                lambda f, w, zo: 2 * np.arctan(w / (2 * 1e3 * f * zo / (zo - 1e3 * f))),
                "came out negative, so your z_i",
            ),
            (lambda f, w, zo: 2 * np.arctan(w / (2 * zo)), "object distance"),
            (lambda f, w, zo: 2 * np.arctan(1e3 * w / (2 * f * zo / (zo - f))), "mixed units"),
            (lambda f, w, zo: [2 * np.arctan(w / (2 * f * zo / (zo - f)))], "return one number"),
            (lambda f, w, zo: (2 * np.arctan(w / (2 * f * zo / (zo - f))),), "a trailing comma"),
            (
                lambda f, w, zo: 2 * np.arctan(w / (2 * (zo - f))),
                "z_o - f is not where the image forms",
            ),
            (
                lambda f, w, zo: 2 * np.arctan(np.hypot(w, 2 * w / 3) / (2 * f * zo / (zo - f))),
                "diagonal field of view",
            ),
            (lambda f, w, zo: 2 * np.arctan(f / (2 * w * zo / (zo - w))), "w and f are swapped"),
            (lambda f, w, zo: -2 * np.arctan(w / (2 * f * zo / (zo - f))), "a sign slip"),
            (lambda f, w, zo: 2 * np.tan(w / (2 * f * zo / (zo - f))), "its arctangent"),
        ),
        teaching=field_of_view,
    )
)


# -- distort_pixels ---------------------------------------------------------------------------

_K_TEST = np.array(
    [[800.0, 0.0, 331.2], [0.0, 790.0, 247.9], [0.0, 0.0, 1.0]]
)  # f_x != f_y, c off the centre


def _distort_cases():
    rng = np.random.default_rng(2)
    uv = rng.uniform((0, 0), (639, 479), (8, 2))
    return [
        (uv, _K_TEST, np.array([-0.2, 0.0, 0.0, 0.0, 0.0])),
        (uv, _K_TEST, np.array([-0.25, 0.08, 0.0, 0.0, -0.01])),
        (uv, _K_TEST, np.array([0.1, -0.02, 0.004, -0.003, 0.0])),
        (np.array([[600.0, 60.0]]), _K_TEST, np.array([-0.1, 0.02, 0.01, 0.02, 0.005])),
    ]


def _brown_variant(
    x,
    d,
    cross: float = 2.0,
    squares_swapped: bool = False,
    divide: bool = False,
    no_one: bool = False,
    y_copied: bool = False,
) -> np.ndarray:
    """The Brown-Conrady model with one typical slip: the cross term's 2, x^2 / y^2 swapped, x / L for x L,
    L without its 1 (the displacement), or y_d's p1 term copied from x_d's p2 term (r^2 + 2 x^2)."""
    k1, k2, p1, p2, k3 = d
    u, v = x[:, 0], x[:, 1]
    r2 = u**2 + v**2
    L = 1 + k1 * r2 + k2 * r2**2 + k3 * r2**3 - (1 if no_one else 0)
    su, sv = (v, u) if squares_swapped else (u, v)
    if y_copied:
        sv = u
    radial = (
        np.column_stack([u, v]) / L[:, None] if divide else np.column_stack([u, v]) * L[:, None]
    )
    return radial + np.column_stack(
        [cross * p1 * u * v + p2 * (r2 + 2 * su**2), p1 * (r2 + 2 * sv**2) + cross * p2 * u * v]
    )


_TANGENTIAL_TERMS = (
    "x_d's 2 p1 x y",
    "x_d's p2 (r^2 + 2 x^2)",
    "y_d's p1 (r^2 + 2 y^2)",
    "y_d's 2 p2 x y",
)


def _tangential_terms(x, d) -> np.ndarray:
    """(4, N, 2): the model's four tangential terms one by one, each in its own coordinate (the other column 0)."""
    _, _, p1, p2, _ = d
    u, v = x[:, 0], x[:, 1]
    r2, zero = u**2 + v**2, np.zeros(len(x))
    return np.array(
        [
            np.column_stack([2 * p1 * u * v, zero]),
            np.column_stack([p2 * (r2 + 2 * u**2), zero]),
            np.column_stack([zero, p1 * (r2 + 2 * v**2)]),
            np.column_stack([zero, 2 * p2 * u * v]),
        ]
    )


def _sign_slip(x, d, g) -> str:
    """A hint when ``g`` is the model with the radial or a tangential coefficient's sign flipped ('' if not)."""
    k1, k2, p1, p2, k3 = d
    flips = (
        (
            (-k1, -k2, p1, p2, -k3),
            "the radial terms have the wrong sign: L = 1 + k1 r^2 + k2 r^4 + k3 r^6 "
            "(k1 < 0 pulls points in, barrel)",
            k1 or k2 or k3,
        ),
        (
            (k1, k2, -p1, -p2, k3),
            "the tangential terms have the wrong sign: x gets + 2 p1 x y + p2 (r^2 + 2 x^2), "
            "y gets + p1 (r^2 + 2 y^2) + 2 p2 x y",
            p1 and p2,
        ),
        (
            (k1, k2, -p1, p2, k3),
            "the p1 terms have the wrong sign: + 2 p1 x y in x_d, + p1 (r^2 + 2 y^2) in y_d",
            p1,
        ),
        (
            (k1, k2, p1, -p2, k3),
            "the p2 terms have the wrong sign: + p2 (r^2 + 2 x^2) in x_d, + 2 p2 x y in y_d",
            p2,
        ),
    )
    for flipped, hint, present in flips:
        if present and np.allclose(g, distortion.distort_points(x, flipped)):
            return hint
    return ""


def _model_diagnosis(x, d, g, expected) -> str:
    """The likely slip in the Brown-Conrady model itself, on normalised points ('' if none is recognised)."""
    k1, k2, p1, p2, k3 = d
    if (p1 or p2 or k3) and np.allclose(g, distortion.distort_points(x, [k1, k2, p2, k3, p1])):
        return (
            "you read dist as (k1, k2, k3, p1, p2); OpenCV's order is (k1, k2, p1, p2, k3): "
            "k3 comes last, after the tangential p1, p2"
        )
    if (p1 or p2) and np.allclose(g, distortion.distort_points(x, [k1, k2, p2, p1, k3])):
        return "p1 and p2 are swapped: OpenCV's order is (k1, k2, p1, p2, k3), and x gets 2 p1 x y + p2 (r^2 + 2 x^2)"
    if (p1 or p2) and np.allclose(g, _brown_variant(x, d, cross=1.0)):
        return "the cross terms need their factor 2: x gets 2 p1 x y, y gets 2 p2 x y"
    if (p1 or p2) and np.allclose(g, _brown_variant(x, d, squares_swapped=True)):
        return "x^2 and y^2 are swapped in the tangential terms: x gets p2 (r^2 + 2 x^2), y gets p1 (r^2 + 2 y^2)"
    if p1 and np.allclose(g, _brown_variant(x, d, y_copied=True)):
        return (
            "y_d's p1 term is p1 (r^2 + 2 y^2), with y; yours has 2 x^2, copied from x_d's p2 term"
        )
    for k, term in enumerate(_TANGENTIAL_TERMS):
        if (
            np.allclose(g, expected - 2 * _tangential_terms(x, d)[k])
            and _tangential_terms(x, d)[k].any()
        ):
            return f"the sign of one tangential term: {term} enters with a plus sign (OpenCV's model, section 4)"
    if np.allclose(g, _brown_variant(x, d, divide=True)):
        return "you divided by the radial factor L; distortion multiplies: x_d = x L + ... (dividing is a rough inverse)"
    if np.allclose(g, _brown_variant(x, d, no_one=True)):
        return (
            "your radial factor lacks its 1: L = 1 + k1 r^2 + k2 r^4 + k3 r^6, so x L is the point itself plus "
            "the radial shift; without the 1 you return only the shift"
        )
    if np.allclose(g - x, expected) or np.allclose(x - g, expected):
        return "you returned the shift x_d - x (or x - x_d); return the distorted point x_d itself"
    sign = _sign_slip(x, d, g)
    if sign:
        return sign
    if (p1 or p2) and np.allclose(g, distortion.distort_points(x, [k1, k2, 0, 0, k3])):
        return "you left out the tangential terms p1, p2"
    if (k2 or k3 or p1 or p2) and np.allclose(g, distortion.distort_points(x, [k1, 0, 0, 0, 0])):
        return (
            "you used k1 alone; dist holds five coefficients (k1, k2, p1, p2, k3), and every one of them counts: "
            "L = 1 + k1 r^2 + k2 r^4 + k3 r^6, then the tangential terms with p1 and p2"
        )
    r = np.hypot(x[:, 0], x[:, 1])
    wrong_r = x * (1 + k1 * r + k2 * r**2 + k3 * r**3)[:, None]
    radial_only = distortion.distort_points(x, [k1, k2, 0, 0, k3])
    if np.allclose(g, wrong_r) or np.allclose(g, wrong_r + (expected - radial_only)):
        return "the radial factor uses even powers of r: 1 + k1 r^2 + k2 r^4 + k3 r^6 with r^2 = x^2 + y^2"
    if k3 and np.allclose(g, distortion.distort_points(x, [k1, k2, p1, p2, 0])):
        return "you dropped k3 (the fifth coefficient, r^6)"
    return ""


def _distort_pixels_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    uv, K, d = args
    g = np.asarray(got, dtype=float)
    f, c = np.array([K[0, 0], K[1, 1]]), np.array([K[0, 2], K[1, 2]])
    x = (uv - c) / f  # the ideal points, normalised
    x_d = distortion.distort_points(x, d)
    with np.errstate(all="ignore"):
        if np.allclose(g, distortion.distort_points(uv, d)):
            return (
                "you applied the model to pixel coordinates; it works on normalised ones: x = (u - c_x) / f_x, "
                "y = (v - c_y) / f_y first, then u_d = f_x x_d + c_x, v_d = f_y y_d + c_y"
            )
        if np.allclose(g, x_d):
            return "you returned normalised coordinates; map them back to pixels: u_d = f_x x_d + c_x, v_d = f_y y_d + c_y"
        if np.any(d) and np.allclose(g, distortion.undistort_pixels(uv, K, d), atol=1e-6):
            return (
                "you undistorted: that maps a distorted pixel to the ideal one. This function goes forward, ideal "
                "uv in, distorted out: normalise, apply x_d = x L + (tangential terms) as section 4 writes it, "
                "back to pixels (no inverse, no iteration)"
            )
        tangential = _tangential_terms(x, d).sum(axis=0)
        if tangential.any() and np.allclose(g, (x_d - tangential) * f + c + tangential):
            return (
                "your tangential terms are in normalised units but were added to pixels (so they shrink to "
                "~1e-3 px): add them to x L before scaling, u_d = f_x (x L + 2 p1 x y + p2 (r^2 + 2 x^2)) + c_x"
            )
        for f_wrong, c_wrong, hint in (
            (
                f,
                0 * c,
                "subtract the principal point before dividing by the focal length, x = (u - c_x) / f_x, "
                "and add it back afterwards: distortion grows from the optical axis, not from pixel (0, 0). "
                "(With matrices on row points: np.c_[uv, ones] @ np.linalg.inv(K) without .T, its first two "
                "columns taken, drops c just so; use @ np.linalg.inv(K).T, then @ K.T, and divide by w)",
            ),
            (
                f[[0, 0]],
                c,
                "v goes with f_y = K[1, 1], not f_x: x = (u - c_x) / f_x, y = (v - c_y) / f_y",
            ),
            (f[::-1], c, "f_x = K[0, 0] goes with u and f_y = K[1, 1] with v: you swapped them"),
            (f, c[::-1], "c_x = K[0, 2] and c_y = K[1, 2]: you swapped them"),
            (
                f,
                np.array([319.5, 239.5]),
                "you used the image centre as the principal point; take it from K, "
                "c_x = K[0, 2], c_y = K[1, 2]: a calibrated camera's is off the centre",
            ),
            (
                f,
                np.array([320.0, 240.0]),
                "you used the image centre as the principal point; take it from K, "
                "c_x = K[0, 2], c_y = K[1, 2]: a calibrated camera's is off the centre",
            ),
            (
                f,
                c + 0.5,
                "a half-pixel shift: the principal point is K[0, 2], K[1, 2] as it is (pixel centres sit at "
                "integers)",
            ),
            (
                f,
                c - 0.5,
                "a half-pixel shift: the principal point is K[0, 2], K[1, 2] as it is (pixel centres sit at "
                "integers)",
            ),
        ):
            xw = (uv - c_wrong) / f_wrong
            if np.allclose(g, distortion.distort_points(xw, d) * f_wrong + c_wrong) or np.allclose(
                g, distortion.distort_points(xw, d) * f_wrong + c
            ):
                return hint
        if np.allclose(g, x_d * f):
            return (
                "your u_d, v_d lack the principal point: after scaling by f, add c back, u_d = f_x x_d + c_x, "
                "v_d = f_y y_d + c_y. (With a matrix on row points, np.c_[x_d, ones] @ K without .T puts c_x into "
                "the third coordinate, which [:, :2] then drops: use @ K.T)"
            )
        if np.allclose(g, expected[:, ::-1]):
            return (
                "your columns come out as (v, u); return (u, v), the column u first, as uv came in: "
                "np.column_stack([u_d, v_d])"
            )
        if np.allclose(g, distortion.distort_pixels(uv[:, ::-1], K, d)) or np.allclose(
            g, distortion.distort_pixels(uv[:, ::-1], K, d)[:, ::-1]
        ):
            return (
                "you read uv as (v, u), width and height swapped: uv[:, 0] is u, the column (with f_x and c_x), "
                "uv[:, 1] is v, the row (with f_y and c_y)"
            )
        for way_in, way_out in (("wrong", "wrong"), ("wrong", "right"), ("right", "wrong")):
            xw = uv / f - c if way_in == "wrong" else x
            back = distortion.distort_points(xw, d)
            if np.allclose(g, (back + c) * f if way_out == "wrong" else back * f + c):
                return (
                    "normalising is subtract, then divide: x = (u - c_x) / f_x (u / f_x - c_x takes a pixel offset "
                    "from a normalised number); undo it in the reverse order, multiply, then add: "
                    "u_d = f_x x_d + c_x"
                )
        if _transposed_k(uv, K, d, g):
            return (
                "points are rows, so a matrix acts from the right transposed: normalise with "
                "np.c_[uv, ones] @ np.linalg.inv(K).T and map back with np.c_[x_d, ones] @ K.T (or write "
                "x = (u - c_x) / f_x, y = (v - c_y) / f_y out); K without .T mixes c_x into the third coordinate"
            )
        if np.allclose(g, (x_d - x) * f) or np.allclose(g, (x - x_d) * f):
            return "you returned the shift in pixels; return where the point lands: u_d = f_x x_d + c_x, v_d = f_y y_d + c_y"
        g_normalised = (g - c) / f
    model = _model_diagnosis(x, np.asarray(d, dtype=float), g_normalised, x_d)
    if model:
        return model
    return (
        "normalise with K (x = (u - c_x) / f_x, y = (v - c_y) / f_y), apply the model of section 4 term by term "
        "(radial factor, then the two tangential terms), then back to pixels"
    )


def _transposed_k(uv, K, d, g) -> bool:
    """True when ``g`` is distort_pixels with K (or its inverse) applied to row points without .T, either way."""
    K = np.asarray(K, dtype=float)
    rows = np.c_[uv, np.ones(len(uv))]

    def dehomogenise(h):
        return h[:, :2] / h[:, 2:]

    forward = {
        "right": dehomogenise(rows @ np.linalg.inv(K).T),
        "no .T": dehomogenise(rows @ np.linalg.inv(K)),
    }
    for way_in, x in forward.items():
        h = np.c_[distortion.distort_points(x, d), np.ones(len(x))]
        for way_out, back in (
            ("right", dehomogenise(h @ K.T)),
            ("no .T", dehomogenise(h @ K)),
            ("no .T", (h @ K)[:, :2]),
        ):
            if (way_in, way_out) != ("right", "right") and np.allclose(g, back):
                return True
    return False


def distort_pixels(uv, K, dist):
    """Where a lens with Brown-Conrady coefficients dist (OpenCV's order) moves (N, 2) ideal pixel positions."""
    k1, k2, p1, p2, k3 = dist  # note: k3 comes last
    fx, fy, cx, cy = K[0, 0], K[1, 1], K[0, 2], K[1, 2]
    x, y = (
        (uv[:, 0] - cx) / fx,
        (uv[:, 1] - cy) / fy,
    )  # normalised: the model works at f = 1, from the axis
    r2 = x**2 + y**2
    radial = 1 + k1 * r2 + k2 * r2**2 + k3 * r2**3  # even powers of r
    xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x**2)
    yd = y * radial + p1 * (r2 + 2 * y**2) + 2 * p2 * x * y
    return np.column_stack([fx * xd + cx, fy * yd + cy])  # back to pixels


def _in_place_distortion(uv, K, d):
    out = distortion.distort_pixels(uv, K, d)
    uv[:] = out  # the typical slip: the answer written over the caller's points
    return out


def _pixel_variant(model):
    """A student's distort_pixels whose normalisation is right and whose model is ``model(x, d)``."""

    def wrong(uv, K, d):
        f, c = np.array([K[0, 0], K[1, 1]]), np.array([K[0, 2], K[1, 2]])
        return model((uv - c) / f, np.asarray(d, dtype=float)) * f + c

    return wrong


register_exercise(
    Exercise(
        name="distort_pixels",
        lesson="02",
        reference=distortion.distort_pixels,
        cases=_distort_cases,
        compare=same_array(rtol=0, atol=1e-9),
        diagnose=_distort_pixels_diagnosis,
        ndarray_only=True,
        wrong_variants=(
            (lambda uv, K, d: distortion.distort_points(uv, d), "pixel coordinates"),
            (
                lambda uv, K, d: distortion.distort_points((uv - K[:2, 2]) / K[[0, 1], [0, 1]], d),
                "normalised coordinates",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points(uv / K[[0, 1], [0, 1]], d) * K[[0, 1], [0, 1]]
                ),
                "principal point",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points((uv - K[:2, 2]) / K[0, 0], d) * K[0, 0] + K[:2, 2]
                ),
                "f_y",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points((uv - K[:2, 2][::-1]) / K[[0, 1], [0, 1]], d)
                    * K[[0, 1], [0, 1]]
                    + K[:2, 2][::-1]
                ),
                "and c_y = K",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points((uv - K[:2, 2]) / K[[1, 0], [1, 0]], d)
                    * K[[1, 0], [1, 0]]
                    + K[:2, 2]
                ),
                "goes with u and f_y",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points((uv - K[:2, 2] - 0.5) / K[[0, 1], [0, 1]], d)
                    * K[[0, 1], [0, 1]]
                    + K[:2, 2]
                    + 0.5
                ),
                "half-pixel",
            ),
            (lambda uv, K, d: distortion.distort_pixels(uv, K, d) - uv, "shift in pixels"),
            (
                lambda uv, K, d: (
                    distortion.distort_points((uv - [319.5, 239.5]) / K[[0, 1], [0, 1]], d)
                    * K[[0, 1], [0, 1]]
                    + [319.5, 239.5]
                ),
                "image centre as the principal point",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points((uv - K[:2, 2]) / K[[0, 1], [0, 1]], d)
                    * K[[0, 1], [0, 1]]
                ),
                "lack the principal point",
            ),
            (lambda uv, K, d: distortion.distort_pixels(uv, K, d)[:, ::-1], "come out as"),
            (
                lambda uv, K, d: distortion.distort_pixels(uv[:, ::-1], K, d),
                "width and height swapped",
            ),
            (
                lambda uv, K, d: (
                    (distortion.distort_points(uv / K[[0, 1], [0, 1]] - K[:2, 2], d) + K[:2, 2])
                    * K[[0, 1], [0, 1]]
                ),
                "subtract, then divide",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points(uv / K[[0, 1], [0, 1]] - K[:2, 2], d)
                    * K[[0, 1], [0, 1]]
                    + K[:2, 2]
                ),
                "subtract, then divide",
            ),
            (
                lambda uv, K, d: (
                    np.c_[
                        distortion.distort_points(
                            np.c_[uv, np.ones(len(uv))] @ np.linalg.inv(K).T[:, :2], d
                        ),
                        np.ones(len(uv)),
                    ]
                    @ K
                )[:, :2],
                "without .T puts c_x into",
            ),
            (
                _pixel_variant(
                    lambda x, d: distortion.distort_points(x, [d[0], d[1], d[3], d[2], d[4]])
                ),
                "p1 and p2 are swapped",
            ),
            (
                _pixel_variant(lambda x, d: distortion.distort_points(x, [d[0], d[1], 0, 0, d[4]])),
                "tangential",
            ),
            (
                _pixel_variant(
                    lambda x, d: distortion.distort_points(x, [d[0], d[1], d[3], d[4], d[2]])
                ),
                "k3 comes last",
            ),
            (
                _pixel_variant(
                    lambda x, d: (
                        x
                        * (
                            1
                            + d[0] * np.hypot(*x.T)
                            + d[1] * np.hypot(*x.T) ** 2
                            + d[4] * np.hypot(*x.T) ** 3
                        )[:, None]
                    )
                ),
                "even powers",
            ),
            (_pixel_variant(lambda x, d: _brown_variant(x, d, cross=1.0)), "factor 2"),
            (
                _pixel_variant(lambda x, d: _brown_variant(x, d, squares_swapped=True)),
                "swapped in the tangential terms",
            ),
            (
                _pixel_variant(lambda x, d: _brown_variant(x, d, y_copied=True)),
                "copied from x_d's p2 term",
            ),
            (
                _pixel_variant(lambda x, d: _brown_variant(x, d, divide=True)),
                "divided by the radial factor",
            ),
            (_pixel_variant(lambda x, d: _brown_variant(x, d, no_one=True)), "lacks its 1"),
            (
                _pixel_variant(
                    lambda x, d: distortion.distort_points(x, [-d[0], -d[1], d[2], d[3], -d[4]])
                ),
                "radial terms have the wrong sign",
            ),
            (
                _pixel_variant(
                    lambda x, d: distortion.distort_points(x, [d[0], d[1], -d[2], -d[3], d[4]])
                ),
                "tangential terms have the wrong",
            ),
            (
                _pixel_variant(
                    lambda x, d: distortion.distort_points(x, [d[0], d[1], d[2], d[3], 0])
                ),
                "dropped k3",
            ),
            (
                lambda uv, K, d: distortion.distort_pixels(uv, K, d).tolist(),
                "wrap the values in np.array",
            ),
            (lambda uv, K, d: distortion.distort_pixels(uv, K, d).T, "expected an array of shape"),
            (_in_place_distortion, "in place"),
            (lambda uv, K, d: distortion.undistort_pixels(uv, K, d), "you undistorted"),
            (
                _pixel_variant(lambda x, d: distortion.distort_points(x, [d[0], 0, 0, 0, 0])),
                "you used k1 alone",
            ),
            (
                _pixel_variant(
                    lambda x, d: distortion.distort_points(x, d) - 2 * _tangential_terms(x, d)[3]
                ),
                "y_d's 2 p2 x y enters with a plus sign",
            ),
            (
                _pixel_variant(
                    lambda x, d: distortion.distort_points(x, d) - 2 * _tangential_terms(x, d)[0]
                ),
                "x_d's 2 p1 x y enters with a plus sign",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_pixels(uv, K, [d[0], d[1], 0, 0, d[4]])
                    + _tangential_terms((uv - K[:2, 2]) / K[[0, 1], [0, 1]], d).sum(axis=0)
                ),
                "in normalised units but were added to pixels",
            ),
            (
                lambda uv, K, d: (
                    np.c_[
                        distortion.distort_points(
                            (np.c_[uv, np.ones(len(uv))] @ np.linalg.inv(K))[:, :2], d
                        ),
                        np.ones(len(uv)),
                    ]
                    @ K
                )[:, :2],
                "without .T, its first two",
            ),
        ),
        teaching=distort_pixels,
    )
)


# -- f_number_for_depth -------------------------------------------------------------------------


def _f_number_cases():
    return [
        (0.05, 0.03e-3, 2.0, 4.0),
        (0.028, 0.02e-3, 0.8, 1.6),
        (0.085, 0.03e-3, 1.9, 2.1),
        (0.1, 0.015e-3, 9.0, 11.0),
    ]


def _f_number_reference(f, c, near, far):
    """camlab.lens.aperture_for_depth_of_field(f, c, near, far).f_number: the same two equal-blur conditions."""
    return lens.aperture_for_depth_of_field(f, c, near, far).f_number


def _f_number_diagnosis(args, got, expected) -> str:
    f, c, n, r = args
    if (
        isinstance(got, (tuple, list, np.ndarray))
        and np.size(got) == 2
        and np.isclose(np.ravel(got), expected).any()
    ):
        return "return N alone, one number: the focus distance s is only a step on the way"
    if not _is_number(got):
        return not_one_number(got, "the f-number N")
    g = float(got)
    s = 2 * n * r / (n + r)
    stop = [N for N in _MARKED_STOPS if np.isclose(g, N, rtol=1e-9)]
    # a whole number (int, floor, ceil, round), a marked full stop, or an exact half or third stop 2^(k/4), 2^(k/6)
    fraction_stop = g > 0 and any(
        np.isclose(k * np.log2(g), round(k * np.log2(g)), rtol=0, atol=1e-9) for k in (4, 6)
    )
    near_it = g > 0 and abs(np.log2(g / expected)) < 1  # within a stop of the answer
    if (
        (
            stop
            or fraction_stop
            or np.isclose(g, np.floor(expected))
            or np.isclose(g, np.ceil(expected))
            or np.isclose(g, np.round(expected))
        )
        and near_it
        and not np.isclose(g, expected)
    ):
        return (
            f"you rounded N (to {g:g}); return the exact f-number, {expected:.4g} here: picking the next marked "
            f"stop on the lens is your step afterwards, not the function's"
        )
    geometric = np.sqrt(n * r)
    if np.isclose(g, f**2 * (geometric - n) / (c * n * (geometric - f))) or np.isclose(
        g, f**2 * (r - geometric) / (c * r * (geometric - f))
    ):
        return (
            "you focused at the geometric mean sqrt(near far); equal blur at both ends needs "
            "(s - near) / near = (far - s) / far, whose solution is the harmonic mean 2 near far / (near + far)"
        )
    if np.isclose(g, 1 / expected):
        return "you returned 1/N; N = f / A is large for a small aperture (f/11 is N = 11)"
    if np.isclose(g, s) or np.isclose(g, (n + r) / 2):
        return "that is a focus distance; the function returns the f-number N (the focus is only a step on the way)"
    mid = (n + r) / 2
    if np.isclose(g, f**2 * (mid - n) / (c * n * (mid - f))) or np.isclose(
        g, f**2 * (r - mid) / (c * r * (mid - f))
    ):
        return (
            "you focused at the midpoint (near + far) / 2; the blur grows as |z - s| / z, faster in front of the "
            "focus than behind it, so equal blur at both ends needs s = 2 near far / (near + far), the harmonic mean"
        )
    if np.isclose(g, f**2 * (r - n) / (2 * c * n * r)):
        return (
            "you dropped f from s - f: the sensor sits at f s / (s - f), and c(z) = (f/N) (f/(s - f)) |z - s| / z; "
            "the check wants the exact thin-lens N (neglecting f against s is the usual approximation, and the "
            "same as the textbook's H = f^2 / (N c) with near = H s / (H + s), far = H s / (H - s))"
        )
    H_plain = (n * (s - 2 * f) + s * f) / (s - n)  # near = s (H - f) / (H + s - 2 f) solved for H
    if np.isclose(g, f**2 / (c * H_plain)):
        return (
            "H is off by f: with section 2's exact limits the hyperfocal distance is H = f^2 / (N c) + f, so "
            "N = f^2 / (c (H - f)); the + f belongs to the thin lens's exact H"
        )
    for end in (n, r):  # similar triangles with the apex at the sensor instead of the image point
        z_s, z_i = f * s / (s - f), f * end / (end - f)
        if np.isclose(g, f / c * abs(z_s - z_i) / z_s):
            return (
                "the cone's apex is the image point z_i, so similar triangles give c / A = |z_s - z_i| / z_i: "
                "divide by z_i (the end point's image distance), not by the sensor distance z_s"
            )
    if np.isclose(g, 2 * expected):
        return "c is the blur circle's diameter, not its radius: you used c / 2"
    if np.isclose(g, expected / 2):
        return "you doubled c; c is the blur circle's diameter already"
    if np.isclose(g, expected * 1e3) or np.isclose(g, expected * 1e-3):
        return "N is 1000 times off: mixed units (c in millimetres, f in metres?); keep every length in metres"
    if np.isclose(g, f**2 * (s - n) / (c * n * (s + f))):
        return "the sign of f: the sensor sits at f s / (s - f), so the cone's factor is f / (s - f), not f / (s + f)"
    if np.isclose(g, expected / f):
        return (
            "f enters squared: the aperture A = f / N and the cone's f / (s - f) each bring one f"
        )
    if np.isclose(g, -expected):
        return (
            "|z - s| with the wrong sign: the near end is in front of the focus, |near - s| = s - near; the far "
            "end behind it, |far - s| = far - s"
        )
    if np.isclose(g, f / expected):
        return "that is the aperture's diameter A = f / N (metres); return the f-number N itself"
    if g < 0:
        return (
            "N came out negative: an |z - s| taken with the wrong sign, or s - f < 0 because f and the "
            "distances are in different units (f in millimetres, s in metres?); keep every length in metres"
        )
    return (
        "first the focus s with c(near) = c(far), i.e. (s - near) / near = (far - s) / far; then N from "
        "c(near) = c, with c(z) = (f/N) (f/(s - f)) |z - s| / z"
    )


_MARKED_STOPS = (1.0, 1.4, 2.0, 2.8, 4.0, 5.6, 8.0, 11.0, 16.0, 22.0, 32.0, 45.0, 64.0)


def f_number_for_depth(f, c, near, far):
    """The f-number that keeps blur <= c from near to far (metres), focused where both ends blur equally."""
    s = 2 * near * far / (near + far)  # (s - near) / near = (far - s) / far: the harmonic mean
    return (
        f**2 * (s - near) / (c * near * (s - f))
    )  # c(near) = (f/N) (f/(s - f)) (s - near) / near = c


register_exercise(
    Exercise(
        name="f_number_for_depth",
        lesson="02",
        reference=_f_number_reference,
        cases=_f_number_cases,
        compare=same_number(rtol=1e-9),
        diagnose=_f_number_diagnosis,
        wrong_variants=(
            (
                lambda f, c, n, r: f**2 * ((n + r) / 2 - n) / (c * n * ((n + r) / 2 - f)),
                "harmonic mean",
            ),
            (
                lambda f, c, n, r: f**2 * (r - (n + r) / 2) / (c * r * ((n + r) / 2 - f)),
                "harmonic mean",
            ),
            (lambda f, c, n, r: f**2 * (r - n) / (2 * c * n * r), "dropped f from s - f"),
            (lambda f, c, n, r: 2 * _f_number_reference(f, c, n, r), "not its radius"),
            (lambda f, c, n, r: _f_number_reference(f, c, n, r) / 2, "you doubled c"),
            (lambda f, c, n, r: 1e3 * _f_number_reference(f, c, n, r), "mixed units"),
            (lambda f, c, n, r: 1 / _f_number_reference(f, c, n, r), "1/N"),
            (lambda f, c, n, r: 2 * n * r / (n + r), "focus distance"),
            (lambda f, c, n, r: _f_number_reference(f, c, n, r) / f, "f enters squared"),
            (
                lambda f, c, n, r: (
                    f**2 * (2 * n * r / (n + r) - n) / (c * n * (2 * n * r / (n + r) + f))
                ),
                "the sign of f",
            ),
            (lambda f, c, n, r: np.array([_f_number_reference(f, c, n, r)]), "return one number"),
            (
                lambda f, c, n, r: min(
                    N for N in _MARKED_STOPS if N >= _f_number_reference(f, c, n, r)
                ),
                "you rounded N",
            ),
            (lambda f, c, n, r: float(np.ceil(_f_number_reference(f, c, n, r))), "you rounded N"),
            (lambda f, c, n, r: int(_f_number_reference(f, c, n, r)), "you rounded N"),
            (
                lambda f, c, n, r: 2 ** (np.ceil(4 * np.log2(_f_number_reference(f, c, n, r))) / 4),
                "you rounded N",
            ),
            (
                lambda f, c, n, r: (
                    f**2
                    / (
                        c
                        * (
                            (n * (2 * n * r / (n + r) - 2 * f) + 2 * n * r / (n + r) * f)
                            / (2 * n * r / (n + r) - n)
                        )
                    )
                ),
                "H is off by f",
            ),
            (
                lambda f, c, n, r: (
                    f
                    / c
                    * abs(f * 2 * n * r / (n + r) / (2 * n * r / (n + r) - f) - f * n / (n - f))
                    / (f * 2 * n * r / (n + r) / (2 * n * r / (n + r) - f))
                ),
                "not by the sensor distance z_s",
            ),
            (
                lambda f, c, n, r: f**2 * (np.sqrt(n * r) - n) / (c * n * (np.sqrt(n * r) - f)),
                "geometric mean",
            ),
            (
                lambda f, c, n, r: (
                    f**2 * (2 * n * r / (n + r) - r) / (c * r * (2 * n * r / (n + r) - f))
                ),
                "the wrong sign",
            ),
            (lambda f, c, n, r: f / _f_number_reference(f, c, n, r), "the aperture's diameter"),
            (
                lambda f, c, n, r: (2 * n * r / (n + r), _f_number_reference(f, c, n, r)),
                "return N alone",
            ),
            (
                lambda f, c, n, r: (
                    (1e3 * f) ** 2
                    * (2 * n * r / (n + r) - n)
                    / (c * n * (2 * n * r / (n + r) - 1e3 * f))
                ),
                "N came out negative",
            ),
        ),
        teaching=f_number_for_depth,
    )
)


# -- newton_step --------------------------------------------------------------------------------


def _newton_cases():
    """Starts off the ray through x_d (rotated and scaled), where the residual has a part across the ray.

    From x = x_d a radial model keeps every iterate on that ray, so only J's radial
    eigenvalue acts; off it, the whole 2 x 2 Jacobian does (a scalar J or a dropped
    off-diagonal gives another step). The last case starts at x_d, as undistortion does.
    """
    rng = np.random.default_rng(5)
    x_d = rng.uniform(-0.4, 0.4, (8, 2))
    turn = np.array([[np.cos(0.3), -np.sin(0.3)], [np.sin(0.3), np.cos(0.3)]])
    x_a = 1.1 * x_d @ turn.T + rng.normal(0, 0.02, (8, 2))
    strong_d = np.array(
        [[0.45, -0.2], [0.05, 0.02], [-0.3, 0.35]]
    )  # strong barrel, inside its fold (0.609)
    strong_x = np.array([[0.5, -0.3], [0.0, 0.06], [-0.42, 0.4]])
    return [
        (x_a, x_d, -0.25, 0.05),
        (x_a, x_d, 0.12, 0.0),
        (strong_x, strong_d, -0.4, 0.1),
        (x_d, x_d, -0.25, 0.05),
    ]


def _newton_step_reference(x, x_d, k1, k2):
    """x - J(x)^-1 (F(x) - x_d) with camlab.distortion.distortion_jacobian and distort_points (dist = (k1, k2, 0, 0, 0)); camlab.distortion.newton_undistort repeats the step until it converges."""
    d = [k1, k2, 0.0, 0.0, 0.0]
    J = distortion.distortion_jacobian(x, d)
    return x - np.linalg.solve(J, (distortion.distort_points(x, d) - x_d)[:, :, None])[:, :, 0]


def _wrong_step(
    x,
    x_d,
    k1,
    k2,
    *,
    jacobian: str = "newton",
    chain: float = 2.0,
    k2_chain: float = 4.0,
    k1_power: float = 0.0,
    k2_power: float = 1.0,
    j_at_target: bool = False,
    l_at_target: bool = False,
    step_sign: float = -1.0,
    start_at_target: bool = False,
    return_delta: bool = False,
    residual_to_x: bool = False,
    multiply: bool = False,
) -> np.ndarray:
    """One step x - J^-1 (F(x) - x_d) with one typical slip (see :data:`_WRONG_STEPS`).

    ``k1_power``, ``k2_power``: the slope's k1 and k2 terms carry r^2 to these powers (right: 0 and 1);
    ``residual_to_x``: the residual x L - x; ``multiply``: delta = -J (F(x) - x_d), J not inverted.
    """
    x = np.array(x_d if start_at_target else x, dtype=float)
    where_j = np.asarray(x_d, dtype=float) if j_at_target else x
    r2 = (where_j**2).sum(axis=1, keepdims=True)
    L = 1 + k1 * r2 + k2 * r2**2
    slope = (
        chain * k1 * r2**k1_power + k2_chain * k2 * r2**k2_power
    )  # (1/x) dL/dx, times x x^T below
    outer = where_j[:, :, None] * where_j[:, None, :]
    eye = np.eye(2)
    J = {
        "newton": L[:, :, None] * eye + slope[:, :, None] * outer,
        "scalar": (L + slope * r2)[:, :, None] * eye,  # x^T x for x x^T
        "diagonal": (L[:, :, None] + slope[:, :, None] * where_j[:, :, None] ** 2) * eye,
        "minus": L[:, :, None] * eye - slope[:, :, None] * outer,
        "fixed": L[:, :, None] * eye,
    }[jacobian]
    r2x = (x**2).sum(axis=1, keepdims=True)
    L_res = (
        (1 + k1 * (x_d**2).sum(1, keepdims=True) + k2 * (x_d**2).sum(1, keepdims=True) ** 2)
        if l_at_target
        else 1 + k1 * r2x + k2 * r2x**2
    )
    residual = x * L_res - (x if residual_to_x else x_d)
    with np.errstate(all="ignore"):
        delta = (
            step_sign
            * (J @ residual[:, :, None] if multiply else np.linalg.solve(J, residual[:, :, None]))[
                :, :, 0
            ]
        )
    return delta if return_delta else x + delta


_WRONG_STEPS = (
    (
        dict(jacobian="scalar"),
        "your J is a number times I: you wrote x^T x (the number r^2) where the outer product x x^T (a 2 x 2 matrix) "
        "belongs. J = L I + (2 k1 + 4 k2 r^2) x x^T; for a stack of points x[:, :, None] * x[:, None, :]. (From "
        "x = x_d both give the same step, because the iterates stay on the ray; off it they differ)",
    ),
    (
        dict(jacobian="diagonal"),
        "your J has no off-diagonal terms: d(x L)/dy = x dL/dy = 2 x y (k1 + 2 k2 r^2) is not 0. "
        "J = L I + (2 k1 + 4 k2 r^2) x x^T, whose off-diagonal entries are (2 k1 + 4 k2 r^2) x y",
    ),
    (
        dict(jacobian="minus"),
        "the x x^T term of J has the wrong sign: J = L I + (2 k1 + 4 k2 r^2) x x^T (product rule: d(x L) = L dx + x dL)",
    ),
    (
        dict(jacobian="fixed"),
        "you used J = L I, leaving out how L changes with x: that is the fixed-point step x = x_d / L(x); "
        "differentiate x L(r^2) with the product rule: J = L I + x (dL/dx)^T = L I + (2 k1 + 4 k2 r^2) x x^T",
    ),
    (
        dict(chain=1.0, k2_chain=2.0),
        "the Jacobian misses the chain rule's factor 2: d(r^2)/dx = 2 x, so dL/dx = (2 k1 + 4 k2 r^2) x",
    ),
    (
        dict(chain=1.0, k2_chain=4.0),
        "the k1 term of the Jacobian misses the chain rule's factor 2: d(r^2)/dx = 2 x, so dL/dx = (2 k1 + 4 k2 r^2) x",
    ),
    (
        dict(k2_chain=2.0),
        "the k2 term of the Jacobian is off: d(r^4)/dx = 2 r^2 d(r^2)/dx = 4 r^2 x, so dL/dx = (2 k1 + 4 k2 r^2) x",
    ),
    (
        dict(k2_chain=0.0),
        "your J has no k2 term: L's k2 r^4 changes with x too, d(r^4)/dx = 4 r^2 x, so dL/dx = (2 k1 + 4 k2 r^2) x",
    ),
    (
        dict(j_at_target=True),
        "you evaluated J at x_d; Newton's J belongs to the current estimate x (recompute r^2, L and J from x)",
    ),
    (
        dict(l_at_target=True),
        "your residual uses L of x_d: F(x) = x L(r^2) with r^2 = x^2 + y^2 of the current x, so the residual is "
        "x L(x) - x_d",
    ),
    (
        dict(step_sign=1.0),
        "step against the residual: x + delta with J delta = -(F(x) - x_d); stepping along it walks away from the answer",
    ),
    (
        dict(start_at_target=True),
        "you stepped from x_d, not from the current estimate x: the step is x + delta with J(x) delta = -(F(x) - x_d) "
        "(the check's x is off the ray through x_d, where the whole 2 x 2 J matters)",
    ),
    (dict(return_delta=True), "you returned the step delta; return the new estimate x + delta"),
    (
        dict(multiply=True),
        "you multiplied the residual by J; Newton divides by it: solve J delta = -(F(x) - x_d), "
        "delta = np.linalg.solve(J, -residual[:, :, None])[:, :, 0] (J^-1, not J)",
    ),
    (
        dict(residual_to_x=True),
        "your residual is F(x) - x; it measures how far F(x) is from the distorted point x_d: F(x) - x_d, "
        "which is zero at the answer",
    ),
    (
        dict(k1_power=0.5),
        "the k1 term of the Jacobian has an extra r: d(k1 r^2)/dx = 2 k1 x (r^2 = x^2 + y^2, no square root), "
        "so dL/dx = (2 k1 + 4 k2 r^2) x",
    ),
    (
        dict(k2_power=2.0),
        "the k2 term of the Jacobian has r^4 where r^2 belongs: d(k2 r^4)/dx = 4 k2 r^2 x, so "
        "dL/dx = (2 k1 + 4 k2 r^2) x",
    ),
)


def _newton_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    x, x_d, k1, k2 = args
    g = np.asarray(got, dtype=float)
    if k1 != k2 and np.allclose(g, _newton_step_reference(x, x_d, k2, k1), rtol=0, atol=1e-10):
        return "k1 and k2 are swapped: L = 1 + k1 r^2 + k2 r^4 (k1 with r^2), and J = L I + (2 k1 + 4 k2 r^2) x x^T"
    if k2 and np.allclose(g, _newton_step_reference(x, x_d, k1, 0.0), rtol=0, atol=1e-10):
        return "you left k2 out: L = 1 + k1 r^2 + k2 r^4, and J = L I + (2 k1 + 4 k2 r^2) x x^T"
    converged = distortion.undistort_points(x_d, [k1, k2, 0.0, 0.0, 0.0])
    estimate = _newton_step_reference(x, x_d, k1, k2)
    for steps in (2, 3):  # a loop inside the step (not yet converged: that case follows)
        estimate = _newton_step_reference(estimate, x_d, k1, k2)
        if np.allclose(g, estimate, rtol=0, atol=1e-10) and not np.allclose(
            g, converged, rtol=0, atol=1e-8
        ):
            return (
                f"that is {steps} Newton steps from x; newton_step takes exactly one, from the x it is given "
                "(the loop that repeats it is the caller's)"
            )
    if np.allclose(g, converged, rtol=0, atol=1e-8):
        return (
            "that is the converged answer, after many steps; newton_step takes one step only, from the x it is "
            "given: return x + delta with J(x) delta = -(F(x) - x_d) (the loop that repeats it is the caller's)"
        )
    for slip, hint in _WRONG_STEPS:
        if np.allclose(g, _wrong_step(x, x_d, k1, k2, **slip), rtol=0, atol=1e-10):
            return hint
    r2 = (x**2).sum(axis=1, keepdims=True)
    if np.allclose(g, x * (1 + k1 * r2 + k2 * r2**2)):
        return "you returned F(x), the current estimate distorted; return x + delta, with J(x) delta = -(F(x) - x_d)"
    r = np.sqrt(r2)
    L_odd = 1 + k1 * r + k2 * r**2
    J_odd = (
        L_odd[:, :, None] * np.eye(2)
        + ((k1 + 2 * k2 * r) / np.maximum(r, 1e-300))[:, :, None] * x[:, :, None] * x[:, None, :]
    )
    with np.errstate(all="ignore"):
        odd = x - np.linalg.solve(J_odd, (x * L_odd - x_d)[:, :, None])[:, :, 0]
    if np.allclose(g, odd):
        return (
            "the radial factor uses even powers of r: L = 1 + k1 r^2 + k2 r^4 with r^2 = x^2 + y^2"
        )
    return (
        "one Newton step from the current x: J delta = -(x L - x_d) with J = L I + (2 k1 + 4 k2 r^2) x x^T, "
        "L and r^2 of x; return x + delta"
    )


def _newton_exception_hint(exc, args) -> str:
    """np.linalg.solve on a stack: the right-hand side must be (N, 2, 1), not (N, 2)."""
    if isinstance(exc, (ValueError, np.linalg.LinAlgError)) and (
        "solve" in str(exc) or "core dimension" in str(exc)
    ):
        return (
            "np.linalg.solve on a stack of N systems: J is (N, 2, 2), so give the right-hand side as (N, 2, 1), "
            "residual[:, :, None], and take [:, :, 0] of the result (an (N, 2) b is read as one N x 2 matrix)"
        )
    return ""


def newton_step(x, x_d, k1, k2):
    """One Newton step towards x L(r^2) = x_d (L = 1 + k1 r^2 + k2 r^4) from the current (N, 2) estimate x."""
    r2 = (x**2).sum(axis=1, keepdims=True)  # (N, 1), of the current x
    L = 1 + k1 * r2 + k2 * r2**2
    residual = x * L - x_d  # F(x) - x_d: zero at the answer
    # J = dF/dx = L I + x (dL/dx)^T, with dL/dx = (2 k1 + 4 k2 r^2) x (chain rule: d(r^2)/dx = 2x)
    J = (
        L[:, :, None] * np.eye(2)
        + (2 * k1 + 4 * k2 * r2)[:, :, None] * x[:, :, None] * x[:, None, :]
    )
    delta = np.linalg.solve(J, -residual[:, :, None])[
        :, :, 0
    ]  # J delta = -residual, one 2 x 2 system per point
    return x + delta  # a new array: x and x_d stay as they are


def _in_place_newton(x, x_d, k1, k2):
    out = _newton_step_reference(x, x_d, k1, k2)
    x[:] = out  # `x -= ...`: overwrites the caller's estimate
    return out


def _flat_rhs_newton(x, x_d, k1, k2):
    """np.linalg.solve(J, residual) with an (N, 2) residual: a ValueError in NumPy 2."""
    r2 = (x**2).sum(axis=1, keepdims=True)
    L = 1 + k1 * r2 + k2 * r2**2
    J = (
        L[:, :, None] * np.eye(2)
        + (2 * k1 + 4 * k2 * r2)[:, :, None] * x[:, :, None] * x[:, None, :]
    )
    return x - np.linalg.solve(J, x * L - x_d)


register_exercise(
    Exercise(
        name="newton_step",
        lesson="02",
        reference=_newton_step_reference,
        cases=_newton_cases,
        compare=same_array(rtol=0, atol=1e-10),
        diagnose=_newton_diagnosis,
        exception_hint=_newton_exception_hint,
        ndarray_only=True,
        wrong_variants=tuple(
            (lambda x, x_d, k1, k2, slip=slip: _wrong_step(x, x_d, k1, k2, **slip), phrase)
            for (slip, _), phrase in zip(
                _WRONG_STEPS,
                (
                    "your J is a number times I",
                    "no off-diagonal terms",
                    "term of J has the wrong sign",
                    "fixed-point step",
                    "misses the chain rule's factor 2",
                    "the k1 term of the Jacobian",
                    "the k2 term of the Jacobian",
                    "no k2 term",
                    "you evaluated J at x_d",
                    "your residual uses L of x_d",
                    "step against the residual",
                    "you stepped from x_d",
                    "you returned the step delta",
                    "you multiplied the residual by J",
                    "measures how far",
                    "has an extra r",
                    "the k2 term of the Jacobian has r",
                ),
                strict=True,
            )
        )
        + (
            (
                lambda x, x_d, k1, k2: (
                    x
                    * (
                        1
                        + k1 * (x**2).sum(1, keepdims=True)
                        + k2 * (x**2).sum(1, keepdims=True) ** 2
                    )
                ),
                "the current estimate distorted",
            ),
            (_in_place_newton, "in place"),
            (
                lambda x, x_d, k1, k2: _newton_step_reference(x, x_d, k2, k1),
                "k1 and k2 are swapped",
            ),
            (lambda x, x_d, k1, k2: _newton_step_reference(x, x_d, k1, 0.0), "you left k2 out"),
            (
                lambda x, x_d, k1, k2: distortion.undistort_points(x_d, [k1, k2, 0, 0, 0]),
                "the converged answer",
            ),
            (
                lambda x, x_d, k1, k2: newton_step(newton_step(x, x_d, k1, k2), x_d, k1, k2),
                "that is 2 Newton steps",
            ),
            (_flat_rhs_newton, "np.linalg.solve on a stack"),
            (
                lambda x, x_d, k1, k2: _newton_step_reference(x, x_d, k1, k2).tolist(),
                "wrap the values in np.array",
            ),
        ),
        teaching=newton_step,
    )
)
