"""Lesson 06, exercise 7: the angle between two lines of a plane, measured in a photo of it.

The lines l', m' are image lines and ``C_star`` the image of the dual conic of the circular
points, C*' = H C*inf H^T. The angle between the *world* lines is

    cos(theta) = |l'^T C*' m'| / sqrt((l'^T C*' l') (m'^T C*' m')),

since l' = H^-T l gives l'^T C*' m' = l^T C*inf m = l_1 m_1 + l_2 m_2: the ordinary formula for
the angle between the normals (l_1, l_2) and (m_1, m_2).

References
----------
Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 2.7.4 (angles on the projective plane).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from .._core import Exercise, Mistake, register_exercise
from .._numbers import is_number, not_one_number, same_number

_DUAL_AT_INFINITY = np.diag([1.0, 1.0, 0.0])

# A photo of the plane: a homography with a strong perspective part (angles change by tens of degrees)
_PHOTO = np.array([[1.1, 0.35, 40.0], [-0.15, 0.8, 25.0], [0.004, 0.0025, 1.0]])


def _world_line(angle_deg: float, through) -> np.ndarray:
    """The world line through the point ``through`` with direction at ``angle_deg`` to the x axis."""
    a = np.radians(angle_deg)
    normal = np.array([-np.sin(a), np.cos(a)])
    return np.append(normal, -normal @ np.asarray(through, dtype=float))


def _angle_cases():
    """(l', m', C*') for world lines at known angles, seen through _PHOTO; C*' at several scales."""
    H = _PHOTO
    H_inv_t = np.linalg.inv(H).T
    C_image = H @ _DUAL_AT_INFINITY @ H.T
    cases = []
    # world angles 0/35.2644 (35.2644 deg), 20/92.4326 (72.4326 deg), 10/170.6183 (19.3817 deg;
    # cos < 0 as given), 15/105 (90 deg): no round numbers, so an angle rounded to whole degrees,
    # tenths or hundredths fails
    for (a, b), scale, (s1, s2) in (
        ((0.0, 35.2644), 1.0, (2.0, 0.7)),
        ((20.0, 92.4326), 1e-4, (1.0, 3.0)),
        ((10.0, 170.6183), -3.0, (0.5, -1.0)),
        ((15.0, 105.0), 2.5, (1.5, 1.0)),
    ):
        l1 = s1 * H_inv_t @ _world_line(a, (30.0, 50.0))
        l2 = s2 * H_inv_t @ _world_line(b, (120.0, 10.0))
        cases.append((l1, l2, scale * C_image))
    return cases


def _cosine(l1, l2, C):
    return (l1 @ C @ l2) / np.sqrt((l1 @ C @ l1) * (l2 @ C @ l2))


def _angle_deg(l1, l2, C):
    """The acute angle, in degrees, between the world lines (camlab.projective.line_angle's formula)."""
    l1, l2, C = (np.asarray(a, dtype=float) for a in (l1, l2, C))
    return float(np.degrees(np.arccos(np.clip(abs(_cosine(l1, l2, C)), 0.0, 1.0))))


def _quiet_degrees(value):
    with np.errstate(invalid="ignore", divide="ignore"):
        return float(np.degrees(np.arccos(value)))


def _inv_angle(l1, l2, C) -> float | None:
    """The angle a student gets through np.linalg.inv(C), or None where inv raises.

    C is rank 2, so its computed inverse is huge along C's null vector n, nearly k n n^T, and
    every pair of lines looks parallel (0 deg).
    """
    try:
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            C_inv = np.linalg.inv(C)
            return float(np.degrees(np.arccos(min(abs(_cosine(l1, l2, C_inv)), 1.0))))
    except (np.linalg.LinAlgError, ValueError):
        return None


def _angle_context(l1, l2, C):
    l1, l2, C = (np.asarray(a, dtype=float) for a in (l1, l2, C))
    right = _angle_deg(l1, l2, C)
    with np.errstate(invalid="ignore", divide="ignore"):
        no_norm = np.degrees(np.arccos(np.clip(l1 @ C @ l2, -1, 1)))
        no_sqrt = np.degrees(
            np.arccos(np.clip(abs(l1 @ C @ l2) / ((l1 @ C @ l1) * (l2 @ C @ l2)), -1, 1))
        )
    return SimpleNamespace(
        l1=l1,
        l2=l2,
        C=C,
        right=right,
        signed=_quiet_degrees(np.clip(_cosine(l1, l2, C), -1, 1)),
        image=_angle_deg(l1, l2, _DUAL_AT_INFINITY),
        inverted=_angle_deg(l1, l2, np.linalg.pinv(C)),
        inv=_inv_angle(l1, l2, C),
        no_norm=float(no_norm),
        no_sqrt=float(no_sqrt),
        negative_scale=bool(l1 @ C @ l1 < 0),
        cosine=float(_cosine(l1, l2, C)),
        block=_angle_deg(l1[:2], l2[:2], C[:2, :2]),
    )


_FORMULA = (
    "section 7's cosine is |l^T C* m| divided by the square root of the product (l^T C* l)(m^T C* m), "
    "all with the given C_star, and the angle is its arccos in degrees"
)

_NEGATIVE_SCALE = (
    "C_star came at a negative scale here (-3 H C*inf H^T), so l^T C* l and m^T C* m are both "
    "negative: np.sqrt of each alone is NaN (and min(1, nan) is 1, i.e. 0 deg). Take the square "
    "root of their product, which is positive, or the absolute value inside each root."
)

_ANGLE_MISTAKES = (
    Mistake(
        "separate square roots, negative C_star",
        lambda a: 0.0 if a.negative_scale and a.right > 1e-3 else None,
        "you returned 0 deg. " + _NEGATIVE_SCALE,
    ),
    Mistake(
        "radians",
        lambda a: np.radians(a.right),
        "your angle is in radians; the prompt asks for degrees (np.degrees converts).",
    ),
    Mistake(
        "the image's own angle",
        lambda a: a.image,
        "you measured the angle the lines make *in the image* (C* = diag(1, 1, 0), or the normals "
        "(a, b) directly). The photo changes angles; the world's angle comes through the given C_star, "
        "the image of C*inf: " + _FORMULA + ".",
    ),
    Mistake(
        "inv(C_star)",
        lambda a: a.inv if a.inv is not None and abs(a.inv - a.right) > 1e-6 else None,
        lambda a: (
            f"you returned {a.inv:.3g} deg, as if the lines were parallel. "
            + (
                "Two slips give that here. Either you took arccos of l^T C* m alone, unnormalised (it "
                "scales with l, m and C_star, and np.clip makes it 1), or "
                if abs(a.no_norm - a.inv) < 1e-6
                else ""
            )
            + "you inverted C_star (np.linalg.inv): C*inf = diag(1, 1, 0) has rank 2, and so has "
            "H C*inf H^T, so it has no inverse, and the computed one is huge along C_star's null vector, "
            "which makes every pair of lines look parallel. C* = C^-1 holds for a non-degenerate conic "
            "only; lines pair with the dual conic as given. "
            + _FORMULA[0].upper()
            + _FORMULA[1:]
            + "."
        ),
    ),
    Mistake(
        "C_star inverted",
        lambda a: a.inverted,
        "you used the (pseudo-)inverse of C_star. Lines pair with the dual conic itself, l^T C* m; C* is "
        "rank 2 and has no inverse, and pinv(C*) is no conic of points that lines could use. "
        + _FORMULA
        + ".",
    ),
    Mistake(
        "no absolute value",
        lambda a: a.signed if abs(a.signed - a.right) > 1e-6 else None,
        "you returned the obtuse angle 180 - theta: l^T C* m is negative here because a line's sign is "
        "free (l and -l are one line), and lines have no direction. Take the absolute value of the "
        "cosine, so the angle is between 0 and 90 degrees.",
    ),
    Mistake(
        "always 180 - theta",
        lambda a: 180.0 - a.right if a.right < 90.0 - 1e-6 else None,
        "you returned 180 - theta, the obtuse angle, although the cosine is positive here: lines have no "
        "direction, so the angle between two lines is the acute one, between 0 and 90 degrees. Return "
        "the acute angle itself.",
    ),
    Mistake(
        "the complement",
        lambda a: 90.0 - a.right,
        "you returned 90 - theta: np.arcsin where np.arccos belongs (or the angle between a line and "
        "the other's normal). l^T C* m is the cosine of the angle between the lines' normals, which is "
        "the angle between the lines.",
    ),
    Mistake(
        "not normalised",
        lambda a: a.no_norm,
        "you took arccos of l^T C* m alone: it scales with l, m and C_star (the check passes C_star "
        "at scales 1e-4 and -3), so it is no cosine. Normalise it: " + _FORMULA + ".",
    ),
    Mistake(
        "no square root",
        lambda a: a.no_sqrt,
        "you divided by (l^T C* l) (m^T C* m) without the square root: the denominator must scale like "
        "the numerator (once in l, once in m): " + _FORMULA + ".",
    ),
    Mistake(
        "the cosine",
        lambda a: (abs(a.cosine), a.cosine),
        "you returned the cosine of the angle, not the angle: finish with its arccos, in degrees.",
    ),
    Mistake(
        "the 2 x 2 block",
        lambda a: a.block if abs(a.block - a.right) > 1e-6 else None,
        "you used only the 2 x 2 block of C_star with the lines' normals (a, b): that shortcut holds only "
        "where C* keeps the form diag(1, 1, 0), on the plane itself or after an affinity. Through a "
        "homography C*' = H C*inf H^T fills its last row and column; use the whole 3-vectors and 3 x 3 "
        "matrix: " + _FORMULA + ".",
    ),
)


def _angle_diagnosis(args, got, expected) -> str:
    if np.ndim(got) == 0 and isinstance(got, (float, np.floating)) and np.isnan(got):
        if _angle_context(*args).negative_scale:
            return "your angle is NaN. " + _NEGATIVE_SCALE
        return (
            "your angle is NaN: np.arccos of a number outside [-1, 1]. Is the cosine normalised by the "
            "square root of (l^T C* l)(m^T C* m)? (Rounding can also push it just past 1 for "
            "parallel lines: min(|c|, 1).)"
        )
    if not is_number(got):
        return not_one_number(got, "the angle in degrees")
    context = _angle_context(*args)
    for mistake in _ANGLE_MISTAKES:
        slips = mistake.answer(context)  # one number, or every number the slip can give
        if slips is not None and np.any(
            np.isclose(float(got), np.atleast_1d(slips), rtol=1e-9, atol=1e-9)
        ):
            return mistake.hint(context) if callable(mistake.hint) else mistake.hint
    for digits, unit in (
        (0, "whole degrees"),
        (1, "tenths of a degree"),
        (2, "hundredths of a degree"),
    ):
        rounded = round(context.right, digits)
        if abs(rounded - float(got)) < 1e-9 and abs(rounded - context.right) > 1e-7 * context.right:
            return (
                f"you rounded the angle to {unit}: {rounded:g} deg, where it is {context.right:.4f} deg. "
                'Return it as computed, and round only when you print it (f"{angle:.1f}").'
            )
    return (
        f"the world lines meet at {expected:.4f} deg here, not {float(got):.6g}. In the photo, angles "
        "are measured through C_star, the image of C*inf: " + _FORMULA + "."
    )


def angle_between_lines(l1, l2, C_star):
    """The angle between two world lines, from their images and the image of C*inf.

    Lines move by H^-T and C*inf by H C*inf H^T, so l'^T C*' m' = l^T C*inf m = l_1 m_1 + l_2 m_2:
    the dot product of the world lines' normals. Normalise by both lengths, and take the absolute
    value, since a line's sign is free.

    Parameters
    ----------
    l1, l2 : (3,) array_like
        Two image lines (a, b, c), any scale and sign.
    C_star : (3, 3) array_like
        The image of the dual conic of the circular points, H C*inf H^T, any non-zero scale.

    Returns
    -------
    float
        The angle between the world lines, degrees, in [0, 90].

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 2.7.4 (angles on the projective plane).
    """
    c = l1 @ C_star @ l2 / np.sqrt((l1 @ C_star @ l1) * (l2 @ C_star @ l2))
    return np.degrees(np.arccos(min(abs(c), 1.0)))


register_exercise(
    Exercise(
        name="angle_between_lines",
        lesson="06",
        reference=_angle_deg,
        cases=_angle_cases,
        compare=same_number(rtol=1e-7),
        diagnose=_angle_diagnosis,
        wrong_variants=(
            (
                lambda l1, l2, C: np.radians(_angle_deg(l1, l2, C)),
                "radians",
            ),
            (lambda l1, l2, C: _angle_deg(l1, l2, _DUAL_AT_INFINITY), "*in the image*"),
            (
                lambda l1, l2, C: np.degrees(
                    np.arccos(l1 @ C @ l2 / np.sqrt((l1 @ C @ l1) * (l2 @ C @ l2)))
                ),
                "obtuse angle",
            ),
            (
                lambda l1, l2, C: np.degrees(
                    np.arcsin(abs(l1 @ C @ l2) / np.sqrt((l1 @ C @ l1) * (l2 @ C @ l2)))
                ),
                "90 - theta",
            ),
            (
                lambda l1, l2, C: _quiet_degrees(np.clip(l1 @ C @ l2, -1, 1)),
                "l^T C* m alone",
            ),
            (lambda l1, l2, C: _quiet_degrees(l1 @ C @ l2), "NaN"),
            (
                lambda l1, l2, C: _quiet_degrees(
                    abs(l1 @ C @ l2) / ((l1 @ C @ l1) * (l2 @ C @ l2))
                ),
                "without the square root",
            ),
            (lambda l1, l2, C: _angle_deg(l1, l2, np.linalg.pinv(C)), "pseudo-)inverse"),
            (lambda l1, l2, C: _inv_angle(l1, l2, C), "you inverted C_star"),
            (lambda l1, l2, C: [_angle_deg(l1, l2, C)], "one number"),
            (lambda l1, l2, C: 180.0 - _angle_deg(l1, l2, C), "cosine is positive here"),
            (lambda l1, l2, C: float(round(_angle_deg(l1, l2, C))), "rounded the angle"),
            (lambda l1, l2, C: abs(_cosine(l1, l2, C)), "the cosine of the angle"),
            (
                lambda l1, l2, C: _angle_deg(
                    np.asarray(l1)[:2], np.asarray(l2)[:2], np.asarray(C)[:2, :2]
                ),
                "2 x 2 block",
            ),
            (lambda l1, l2, C: float(round(_angle_deg(l1, l2, C), 1)), "tenths of a degree"),
            (lambda l1, l2, C: float(f"{_angle_deg(l1, l2, C):.2f}"), "hundredths of a degree"),
        ),
        teaching=angle_between_lines,
    )
)
