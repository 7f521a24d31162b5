"""What lesson 02's distortion exercise recognises in the model itself.

In an answer that is normalised and scaled back right: the model itself done wrong (a term's sign, a
missing term, Brown-Conrady variants), and its test cases.

The slips are the rows of :data:`MODEL_MISTAKES` (:class:`~camlab.exercises._core.Mistake`), checked in
order by :func:`model_diagnosis`.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import distortion
from .._core import Mistake, first_mistake

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
    """The Brown-Conrady model with one typical slip.

    The cross term's 2, x^2 / y^2 swapped, x / L for x L, L without its 1 (the displacement), or
    y_d's p1 term copied from x_d's p2 term (r^2 + 2 x^2).
    """
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


def _is(s, coefficients) -> bool:
    """Whether the answer is the model with the coefficients ``coefficients`` (in OpenCV's order)."""
    return np.allclose(s.g, distortion.distort_points(s.x, coefficients))


def _tangential_sign(k: int, term: str) -> Mistake:
    """The row for tangential term ``k`` (named ``term``) entering with a minus sign."""

    def shows(s) -> bool:
        t = tangential_terms(s.x, s.d)[k]
        return np.allclose(s.g, s.expected - 2 * t) and t.any()

    return Mistake(
        f"minus {term}",
        shows,
        f"the sign of one tangential term: {term} enters with a plus sign (OpenCV's model, section 4)",
    )


def _r2(s) -> np.ndarray:
    return s.x[:, 0] ** 2 + s.x[:, 1] ** 2


def _one_power_wrong(s, L_wrong) -> bool:
    """Whether the answer is the model with the radial factor ``L_wrong(s, r2)`` and the tangential terms right."""
    tangential = s.expected - distortion.distort_points(s.x, [s.k1, s.k2, 0, 0, s.k3])
    return np.allclose(s.g, s.x * L_wrong(s, _r2(s))[:, None] + tangential)


def _y_with_p1_p2_swapped(s) -> bool:
    """x_d right, y_d with p1 and p2 exchanged."""
    r2 = _r2(s)
    u, v = s.x[:, 0], s.x[:, 1]
    L = 1 + s.k1 * r2 + s.k2 * r2**2 + s.k3 * r2**3
    y_swapped = np.column_stack(
        [s.expected[:, 0], v * L + s.p2 * (r2 + 2 * v**2) + 2 * s.p1 * u * v]
    )
    return np.allclose(s.g, y_swapped)


def _tangential_with_r(s) -> np.ndarray:
    """The model with r where the tangential terms take r^2 (the radial factor right)."""
    u, v = s.x[:, 0], s.x[:, 1]
    r = np.hypot(u, v)
    radial = distortion.distort_points(s.x, [s.k1, s.k2, 0, 0, s.k3])
    return radial + np.column_stack(
        [2 * s.p1 * u * v + s.p2 * (r + 2 * u**2), s.p1 * (r + 2 * v**2) + 2 * s.p2 * u * v]
    )


def _odd_powers_of_r(s) -> bool:
    """The radial factor in powers of r, not r^2 (with or without the tangential terms)."""
    r = np.hypot(s.x[:, 0], s.x[:, 1])
    wrong_r = s.x * (1 + s.k1 * r + s.k2 * r**2 + s.k3 * r**3)[:, None]
    radial_only = distortion.distort_points(s.x, [s.k1, s.k2, 0, 0, s.k3])
    return np.allclose(s.g, wrong_r) or np.allclose(s.g, wrong_r + (s.expected - radial_only))


# Checked in order on ``s``: the normalised points ``s.x``, the coefficients ``s.d`` (and each by name,
# ``s.k1`` .. ``s.k3``, ``s.p1``, ``s.p2``), the answer ``s.g`` and the right one ``s.expected``, both
# normalised. A row tests a slip only where the coefficients let it show (a k3 slip needs k3 != 0).
MODEL_MISTAKES = (
    Mistake(
        "k3 read third",
        lambda s: (s.p1 or s.p2 or s.k3) and _is(s, [s.k1, s.k2, s.p2, s.k3, s.p1]),
        (
            "you read dist as (k1, k2, k3, p1, p2); OpenCV's order is (k1, k2, p1, p2, k3): "
            "k3 comes last, after the tangential p1, p2"
        ),
    ),
    Mistake(
        "k1 and k2 swapped",
        lambda s: s.k1 != s.k2 and _is(s, [s.k2, s.k1, s.p1, s.p2, s.k3]),
        "k1 and k2 are swapped: OpenCV's order is (k1, k2, p1, p2, k3), and L = 1 + k1 r^2 + k2 r^4 + k3 r^6",
    ),
    Mistake(
        "no radial factor",
        lambda s: (s.k1 or s.k2 or s.k3) and _is(s, [0, 0, s.p1, s.p2, 0]),
        "you left out the radial factor: x_d = x L + (tangential terms), with L = 1 + k1 r^2 + k2 r^4 + k3 r^6",
    ),
    Mistake(
        "p1 and p2 swapped",
        lambda s: (s.p1 or s.p2) and _is(s, [s.k1, s.k2, s.p2, s.p1, s.k3]),
        "p1 and p2 are swapped: OpenCV's order is (k1, k2, p1, p2, k3), and x gets 2 p1 x y + p2 (r^2 + 2 x^2)",
    ),
    Mistake(
        "the cross terms' 2",
        lambda s: (s.p1 or s.p2) and np.allclose(s.g, brown_variant(s.x, s.d, cross=1.0)),
        "the cross terms need their factor 2: x gets 2 p1 x y, y gets 2 p2 x y",
    ),
    Mistake(
        "x^2 and y^2 swapped",
        lambda s: (
            (s.p1 or s.p2) and np.allclose(s.g, brown_variant(s.x, s.d, squares_swapped=True))
        ),
        "x^2 and y^2 are swapped in the tangential terms: x gets p2 (r^2 + 2 x^2), y gets p1 (r^2 + 2 y^2)",
    ),
    Mistake(
        "r for r^2 in the tangential terms",
        lambda s: (s.p1 or s.p2) and np.allclose(s.g, _tangential_with_r(s)),
        (
            "the tangential terms take r^2, not r: x gets p2 (r^2 + 2 x^2), y gets p1 (r^2 + 2 y^2), with "
            "the same r^2 = x^2 + y^2 as in L"
        ),
    ),
    Mistake(
        "y_d's p1 term copied from x_d",
        lambda s: s.p1 and np.allclose(s.g, brown_variant(s.x, s.d, y_copied=True)),
        "y_d's p1 term is p1 (r^2 + 2 y^2), with y; yours has 2 x^2, copied from x_d's p2 term",
    ),
    *(_tangential_sign(k, term) for k, term in enumerate(_TANGENTIAL_TERMS)),
    Mistake(
        "divided by L",
        lambda s: np.allclose(s.g, brown_variant(s.x, s.d, divide=True)),
        "you divided by the radial factor L; distortion multiplies: x_d = x L + ... (dividing is a rough inverse)",
    ),
    Mistake(
        "L without its 1",
        lambda s: np.allclose(s.g, brown_variant(s.x, s.d, no_one=True)),
        (
            "your radial factor lacks its 1: L = 1 + k1 r^2 + k2 r^4 + k3 r^6, so x L is the point itself plus "
            "the radial shift; without the 1 you return only the shift"
        ),
    ),
    Mistake(
        "the shift",
        lambda s: np.allclose(s.g - s.x, s.expected) or np.allclose(s.x - s.g, s.expected),
        "you returned the shift x_d - x (or x - x_d); return the distorted point x_d itself",
    ),
    Mistake(
        "radial sign",
        lambda s: (s.k1 or s.k2 or s.k3) and _is(s, [-s.k1, -s.k2, s.p1, s.p2, -s.k3]),
        (
            "the radial terms have the wrong sign: L = 1 + k1 r^2 + k2 r^4 + k3 r^6 "
            "(k1 < 0 pulls points in, barrel)"
        ),
    ),
    Mistake(
        "tangential sign",
        lambda s: (s.p1 and s.p2) and _is(s, [s.k1, s.k2, -s.p1, -s.p2, s.k3]),
        (
            "the tangential terms have the wrong sign: x gets + 2 p1 x y + p2 (r^2 + 2 x^2), "
            "y gets + p1 (r^2 + 2 y^2) + 2 p2 x y"
        ),
    ),
    Mistake(
        "p1's sign",
        lambda s: s.p1 and _is(s, [s.k1, s.k2, -s.p1, s.p2, s.k3]),
        "the p1 terms have the wrong sign: + 2 p1 x y in x_d, + p1 (r^2 + 2 y^2) in y_d",
    ),
    Mistake(
        "p2's sign",
        lambda s: s.p2 and _is(s, [s.k1, s.k2, s.p1, -s.p2, s.k3]),
        "the p2 terms have the wrong sign: + p2 (r^2 + 2 x^2) in x_d, + 2 p2 x y in y_d",
    ),
    Mistake(
        "no tangential terms",
        lambda s: (s.p1 or s.p2) and _is(s, [s.k1, s.k2, 0, 0, s.k3]),
        "you left out the tangential terms p1, p2",
    ),
    Mistake(
        "k1 alone",
        lambda s: (s.k2 or s.k3 or s.p1 or s.p2) and _is(s, [s.k1, 0, 0, 0, 0]),
        (
            "you used k1 alone; dist holds five coefficients (k1, k2, p1, p2, k3), and every one of them counts: "
            "L = 1 + k1 r^2 + k2 r^4 + k3 r^6, then the tangential terms with p1 and p2"
        ),
    ),
    # one radial power wrong
    Mistake(
        "k3 r^4",
        lambda s: (
            s.k3 and _one_power_wrong(s, lambda s, r2: 1 + s.k1 * r2 + s.k2 * r2**2 + s.k3 * r2**2)
        ),
        "k3 goes with r^6: L = 1 + k1 r^2 + k2 r^4 + k3 r^6 (r2**3); yours gives k3 r^4",
    ),
    Mistake(
        "k2 r^3",
        lambda s: (
            s.k2
            and _one_power_wrong(s, lambda s, r2: 1 + s.k1 * r2 + s.k2 * r2**1.5 + s.k3 * r2**3)
        ),
        "k2 goes with r^4 (r2**2, even powers only): L = 1 + k1 r^2 + k2 r^4 + k3 r^6; yours gives k2 r^3",
    ),
    Mistake(
        "k3 r^5",
        lambda s: (
            s.k3
            and _one_power_wrong(s, lambda s, r2: 1 + s.k1 * r2 + s.k2 * r2**2 + s.k3 * r2**2.5)
        ),
        "k3 goes with r^6 (r2**3, even powers only): L = 1 + k1 r^2 + k2 r^4 + k3 r^6; yours gives k3 r^5",
    ),
    Mistake(
        "y_d with p1 and p2 swapped",
        lambda s: s.p1 != s.p2 and _y_with_p1_p2_swapped(s),
        (
            "x_d is right, but y_d has p1 and p2 swapped: y_d = y L + p1 (r^2 + 2 y^2) + 2 p2 x y (the "
            "pattern of x_d with x and y, p1 and p2 exchanged)"
        ),
    ),
    Mistake(
        "odd powers of r",
        _odd_powers_of_r,
        "the radial factor uses even powers of r: 1 + k1 r^2 + k2 r^4 + k3 r^6 with r^2 = x^2 + y^2",
    ),
    Mistake(
        "no k3",
        lambda s: s.k3 and _is(s, [s.k1, s.k2, s.p1, s.p2, 0]),
        "you dropped k3 (the fifth coefficient, r^6)",
    ),
)


def model_diagnosis(x, d, g, expected) -> str:
    """The likely slip in the Brown-Conrady model itself, on normalised points ('' if none is recognised).

    ``x`` are the normalised points, ``d`` the coefficients (k1, k2, p1, p2, k3), ``g`` the answer and
    ``expected`` the right one, both normalised; the slips are the rows of :data:`MODEL_MISTAKES`.
    """
    k1, k2, p1, p2, k3 = d
    s = SimpleNamespace(x=x, d=d, g=g, expected=expected, k1=k1, k2=k2, p1=p1, p2=p2, k3=k3)
    return first_mistake(MODEL_MISTAKES, s) or ""


def transposed_k(uv, K, d, g) -> bool:
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


def in_place_distortion(uv, K, d):
    out = distortion.distort_pixels(uv, K, d)
    uv[:] = out  # the typical slip: the answer written over the caller's points
    return out


def pixel_variant(model):
    """A student's distort_pixels whose normalisation is right and whose model is ``model(x, d)``."""

    def wrong(uv, K, d):
        f, c = np.array([K[0, 0], K[1, 1]]), np.array([K[0, 2], K[1, 2]])
        return model((uv - c) / f, np.asarray(d, dtype=float)) * f + c

    return wrong


def normalised_with(f_wrong, c_wrong):
    """The test for a wrong focal length or principal point used to normalise.

    ``f_wrong(s)`` and ``c_wrong(s)`` (and either it or the right c to map back).
    """

    def shows(s):
        fw, cw = f_wrong(s), c_wrong(s)
        back = distortion.distort_points((s.uv - cw) / fw, s.d) * fw
        return np.allclose(s.g, back + cw) or np.allclose(s.g, back + s.c)

    return shows


def back_with(s, f_back):
    """The model on the right normalised points, mapped back to pixels with focal lengths ``f_back``."""
    return np.allclose(s.g, s.x_d * f_back + s.c)


ROUNDED_HINT = (
    "you rounded the positions; return them exact, as floats (round only when you print them: a distorted "
    "corner lands between pixel centres, and calibration needs every fraction of a pixel)"
)


def rounded_positions(s) -> bool:
    """True when the answer ``s.g`` is the right positions rounded: to whole pixels (or floored), or to 1-4 decimals."""
    return np.allclose(s.g, np.floor(s.expected), rtol=0, atol=1e-9) or any(
        np.allclose(s.g, np.round(s.expected, k), rtol=0, atol=1e-9) for k in range(5)
    )
