"""What lesson 02's distortion exercise recognises in an answer that is normalised and scaled back right:
the model itself done wrong (a term's sign, a missing term, Brown-Conrady variants), and its test cases."""

from __future__ import annotations

import numpy as np

from ... import distortion

# -- distort_pixels ---------------------------------------------------------------------------

_K_TEST = np.array(
    [[800.0, 0.0, 331.2], [0.0, 790.0, 247.9], [0.0, 0.0, 1.0]]
)  # f_x != f_y, c off the centre


def distort_cases():
    rng = np.random.default_rng(2)
    uv = rng.uniform((0, 0), (639, 479), (8, 2))
    return [
        (uv, _K_TEST, np.array([-0.2, 0.0, 0.0, 0.0, 0.0])),
        (uv, _K_TEST, np.array([-0.25, 0.08, 0.0, 0.0, -0.01])),
        (uv, _K_TEST, np.array([0.1, -0.02, 0.004, -0.003, 0.0])),
        (np.array([[600.0, 60.0]]), _K_TEST, np.array([-0.1, 0.02, 0.01, 0.02, 0.005])),
    ]


def brown_variant(
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


def tangential_terms(x, d) -> np.ndarray:
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


def model_diagnosis(x, d, g, expected) -> str:
    """The likely slip in the Brown-Conrady model itself, on normalised points ('' if none is recognised)."""
    k1, k2, p1, p2, k3 = d
    if (p1 or p2 or k3) and np.allclose(g, distortion.distort_points(x, [k1, k2, p2, k3, p1])):
        return (
            "you read dist as (k1, k2, k3, p1, p2); OpenCV's order is (k1, k2, p1, p2, k3): "
            "k3 comes last, after the tangential p1, p2"
        )
    if k1 != k2 and np.allclose(g, distortion.distort_points(x, [k2, k1, p1, p2, k3])):
        return "k1 and k2 are swapped: OpenCV's order is (k1, k2, p1, p2, k3), and L = 1 + k1 r^2 + k2 r^4 + k3 r^6"
    if (k1 or k2 or k3) and np.allclose(g, distortion.distort_points(x, [0, 0, p1, p2, 0])):
        return "you left out the radial factor: x_d = x L + (tangential terms), with L = 1 + k1 r^2 + k2 r^4 + k3 r^6"
    if (p1 or p2) and np.allclose(g, distortion.distort_points(x, [k1, k2, p2, p1, k3])):
        return "p1 and p2 are swapped: OpenCV's order is (k1, k2, p1, p2, k3), and x gets 2 p1 x y + p2 (r^2 + 2 x^2)"
    if (p1 or p2) and np.allclose(g, brown_variant(x, d, cross=1.0)):
        return "the cross terms need their factor 2: x gets 2 p1 x y, y gets 2 p2 x y"
    if (p1 or p2) and np.allclose(g, brown_variant(x, d, squares_swapped=True)):
        return "x^2 and y^2 are swapped in the tangential terms: x gets p2 (r^2 + 2 x^2), y gets p1 (r^2 + 2 y^2)"
    if p1 and np.allclose(g, brown_variant(x, d, y_copied=True)):
        return (
            "y_d's p1 term is p1 (r^2 + 2 y^2), with y; yours has 2 x^2, copied from x_d's p2 term"
        )
    for k, term in enumerate(_TANGENTIAL_TERMS):
        if (
            np.allclose(g, expected - 2 * tangential_terms(x, d)[k])
            and tangential_terms(x, d)[k].any()
        ):
            return f"the sign of one tangential term: {term} enters with a plus sign (OpenCV's model, section 4)"
    if np.allclose(g, brown_variant(x, d, divide=True)):
        return "you divided by the radial factor L; distortion multiplies: x_d = x L + ... (dividing is a rough inverse)"
    if np.allclose(g, brown_variant(x, d, no_one=True)):
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
    r2 = x[:, 0] ** 2 + x[:, 1] ** 2
    tangential = expected - distortion.distort_points(x, [k1, k2, 0, 0, k3])
    for L_wrong, hint, present in (  # one radial power wrong
        (
            1 + k1 * r2 + k2 * r2**2 + k3 * r2**2,
            "k3 goes with r^6: L = 1 + k1 r^2 + k2 r^4 + k3 r^6 (r2**3); yours gives k3 r^4",
            k3,
        ),
        (
            1 + k1 * r2 + k2 * r2**1.5 + k3 * r2**3,
            "k2 goes with r^4 (r2**2, even powers only): L = 1 + k1 r^2 + k2 r^4 + k3 r^6; yours gives k2 r^3",
            k2,
        ),
        (
            1 + k1 * r2 + k2 * r2**2 + k3 * r2**2.5,
            "k3 goes with r^6 (r2**3, even powers only): L = 1 + k1 r^2 + k2 r^4 + k3 r^6; yours gives k3 r^5",
            k3,
        ),
    ):
        if present and np.allclose(g, x * L_wrong[:, None] + tangential):
            return hint
    if p1 != p2:  # x_d right, y_d with p1 and p2 exchanged
        u, v = x[:, 0], x[:, 1]
        L = 1 + k1 * r2 + k2 * r2**2 + k3 * r2**3
        y_swapped = np.column_stack([expected[:, 0], v * L + p2 * (r2 + 2 * v**2) + 2 * p1 * u * v])
        if np.allclose(g, y_swapped):
            return (
                "x_d is right, but y_d has p1 and p2 swapped: y_d = y L + p1 (r^2 + 2 y^2) + 2 p2 x y (the "
                "pattern of x_d with x and y, p1 and p2 exchanged)"
            )
    r = np.hypot(x[:, 0], x[:, 1])
    wrong_r = x * (1 + k1 * r + k2 * r**2 + k3 * r**3)[:, None]
    radial_only = distortion.distort_points(x, [k1, k2, 0, 0, k3])
    if np.allclose(g, wrong_r) or np.allclose(g, wrong_r + (expected - radial_only)):
        return "the radial factor uses even powers of r: 1 + k1 r^2 + k2 r^4 + k3 r^6 with r^2 = x^2 + y^2"
    if k3 and np.allclose(g, distortion.distort_points(x, [k1, k2, p1, p2, 0])):
        return "you dropped k3 (the fifth coefficient, r^6)"
    return ""
