"""Lesson 06, exercise 5: the cross-ratio of four collinear image points.

The points A, B, C, D come homogeneous, (x, y, w) at any scale. On their line, with signed
lengths (positions t along one direction of the line),

    (A, B; C, D) = AC BD / (BC AD) = (t_C - t_A)(t_D - t_B) / ((t_C - t_B)(t_D - t_A)).

Each point appears once above and once below, so the choice of direction and of origin on the
line cancels; a homography leaves the number unchanged (H&Z section 2.5).

References
----------
Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 2.5 (the cross-ratio).
"""

from __future__ import annotations

from itertools import permutations
from types import SimpleNamespace

import numpy as np

from ... import projective
from .._core import Exercise, Mistake, register_exercise
from .._numbers import is_number, not_one_number, same_number
from .lines import silenced

_ORDER_NAMES = "ABCD"


def _cross_cases():
    """Four collinear points each, homogeneous rows (x, y, w), at scales w != 1 on most."""

    def lift(points, w):
        points, w = np.asarray(points, dtype=float), np.asarray(w, dtype=float)
        return np.column_stack([points * w[:, None], w])

    return [
        # a slanted row of a photographed fence: spacing squeezed towards D
        (
            lift(
                [[100.0, 400.0], [260.0, 340.0], [356.0, 304.0], [420.0, 280.0]],
                [1.0, 2.0, 0.5, 4.0],
            ),
        ),
        # a vertical line (x = 250): x alone says nothing; w negative on one point
        (
            lift(
                [[250.0, 60.0], [250.0, 140.0], [250.0, 230.0], [250.0, 410.0]],
                [2.0, -1.0, 3.0, 0.25],
            ),
        ),
        # a horizontal line, D between A and B: the cross-ratio is negative
        (
            lift(
                [[40.0, 300.0], [520.0, 300.0], [610.0, 300.0], [170.0, 300.0]],
                [1.0, 1.0, 1.0, 1.0],
            ),
        ),
        # a slanted line with A between B and C: positions -1, 0, 2, 3 steps from A, (A, B; C, D) = 8/9
        (
            lift(
                [[300.0, 250.0], [240.0, 295.0], [420.0, 160.0], [480.0, 115.0]],
                [1.5, 1.0, 2.0, 1.0],
            ),
        ),
    ]


def _signed_ratio(t) -> float:
    a, b, c, d = t
    return float((c - a) * (d - b) / ((c - b) * (d - a)))


def _euclidean(points) -> np.ndarray:
    x = np.asarray(points, dtype=float)
    return x[:, :2] / x[:, 2:]


def _positions(xy) -> np.ndarray:
    """Signed positions of the rows of ``xy`` along the direction from the first to the last."""
    return (xy - xy[0]) @ (xy[3] - xy[0])


def _distance_from_a(xy) -> float:
    """The slip: each point's position taken as its unsigned distance from A."""
    return _signed_ratio(np.linalg.norm(xy - xy[0], axis=1))


def _unsigned(xy) -> float:
    n = lambda i, j: np.linalg.norm(xy[j] - xy[i])  # noqa: E731
    return float(n(0, 2) * n(1, 3) / (n(1, 2) * n(0, 3)))


def _cross_reference(points) -> float:
    """The cross-ratio (A, B; C, D), from ``camlab.projective.cross_ratio``."""
    return float(projective.cross_ratio(np.asarray(points, dtype=float)))


def _context(points):
    x = np.asarray(points, dtype=float)
    xy = _euclidean(x)
    r = _signed_ratio(_positions(xy))
    orders = {}
    for order in permutations(range(4)):
        if order != (0, 1, 2, 3):
            orders.setdefault(round(_signed_ratio(_positions(xy[list(order)])), 9), order)
    return SimpleNamespace(
        x=x,
        xy=xy,
        right=r,
        w=x[:, 2],
        raw=_every_order(x[:, :2]) + _every_order(x),
        abs_w=_every_order(x[:, :2] / np.abs(x[:, 2:])),
        orders=orders,
    )


def _every_order(xy) -> list[float]:
    """Signed and unsigned cross-ratios of the rows of ``xy`` taken in each of the 24 orders."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return [
            f(xy[list(order)])
            for order in permutations(range(4))
            for f in (lambda q: _signed_ratio(_positions(q)), _unsigned)
        ]


def _slip_among(candidates, right):
    """The candidates that differ from the right answer (a slip that gives the right number is no slip)."""
    return [c for c in candidates if np.isfinite(c) and abs(c - right) > 1e-9 * abs(right)]


def _order_hint(a, got) -> str | None:
    order = a.orders.get(round(float(got), 9))
    if order is None:
        return None
    p, q, s, u = (_ORDER_NAMES[i] for i in order)
    return (
        f"your number is the cross-ratio of the same points in another order, ({p}, {q}; {s}, {u}) = "
        f"{p}{s} {q}{u} / ({q}{s} {p}{u}). Books differ in which of the orderings they call the "
        "cross-ratio; this exercise (and pj.cross_ratio) takes them as given: (A, B; C, D) = "
        "AC BD / (BC AD), with A, B, C, D the rows 0, 1, 2, 3."
    )


_CROSS_MISTAKES = (
    Mistake(
        "H&Z's Cross",
        lambda a: 1.0 - 1.0 / a.right,
        "you computed Hartley & Zisserman's Cross(x1, x2, x3, x4) = |x1 x2| |x3 x4| / (|x1 x3| |x2 x4|), "
        "which for the same points is 1 - 1/(A, B; C, D) (section 6 checks the identity). This exercise asks "
        "for the course's convention, (A, B; C, D) = AC BD / (BC AD).",
    ),
    Mistake(
        "upside down",
        lambda a: 1.0 / a.right,
        "your number is 1 / (A, B; C, D): numerator and denominator swapped, or A and B (or C and D) "
        "taken in each other's place. (A, B; C, D) = AC BD / (BC AD), with A, B, C, D the rows 0, 1, 2, 3.",
    ),
    Mistake(
        "unsigned lengths",
        lambda a: abs(a.right) if a.right < 0 else None,
        "you used unsigned lengths (np.linalg.norm): here D lies between A and B, so AD and BD point "
        "opposite ways along the line and the cross-ratio is negative. Measure each point by its signed "
        "position t along the line, t = (P - A) . (D - A), and take AC = t_C - t_A.",
    ),
    Mistake(
        "distance from A",
        lambda a: _slip_among([_distance_from_a(a.xy)], a.right),
        "you measured each point's position as its unsigned distance from A, |P - A|. That is its "
        "signed position only while no point lies on the far side of A; here B does (A lies between "
        "B and C), so t_B gets the wrong sign. Project on one direction of the line instead: "
        "t = (P - A) . (D - A).",
    ),
    Mistake(
        "divided by |w|",
        lambda a: _slip_among(a.abs_w, a.right) if np.any(a.w < 0) else None,
        lambda a: (
            "you divided by |w|, not by w: a point whose w is negative (here w = "
            f"{', '.join(f'{w:g}' for w in a.w)}) lands on the mirror image of itself through the origin, "
            "off the line. Divide by w itself, keeping its sign: points[:, :2] / points[:, 2:]."
        ),
    ),
    Mistake(
        "not divided by w",
        lambda a: _slip_among(a.raw, a.right) if np.any(a.w != 1) else None,
        lambda a: (
            "you measured lengths between the homogeneous vectors (x, y, w) as they came, without "
            f"dividing by w (their w here are {', '.join(f'{w:g}' for w in a.w)}): x and y are scaled by w, so "
            "the lengths are not the image's. Divide first, points[:, :2] / points[:, 2:] (keepdims), then measure."
        ),
    ),
    Mistake(
        "a ratio of two lengths",
        lambda a: _simple_ratio(a.xy),
        "you returned a ratio of two lengths (AC / BC). A homography changes that; the cross-ratio is a "
        "ratio of two such ratios, (AC / BC) / (AD / BD) = AC BD / (BC AD).",
    ),
)


def _simple_ratio(xy) -> float:
    t = _positions(xy)
    return float((t[2] - t[0]) / (t[2] - t[1]))


def _cross_diagnosis(args, got, expected) -> str:
    context = _context(*args)
    if isinstance(got, (float, np.floating)) and np.isnan(got):
        if np.ptp(context.xy[:, 0]) < 1e-9 or np.ptp(context.xy[:, 1]) < 1e-9:
            axis = "x" if np.ptp(context.xy[:, 0]) < 1e-9 else "y"
            return (
                f"your answer is NaN on a line where every point has the same {axis}: positions read off "
                f"{axis} alone are all equal there (0 / 0). Measure along the line itself: t = (P - A) . (D - A)."
            )
        return "your answer is NaN: a 0 / 0. Are two of your positions equal? Measure t = (P - A) . (D - A)."
    if not is_number(got):
        return not_one_number(got, "the cross-ratio (A, B; C, D)")
    for mistake in _CROSS_MISTAKES:
        slips = mistake.answer(context)  # one number, or every number this slip can give
        if slips is not None and np.any(np.isclose(float(got), np.atleast_1d(slips), rtol=1e-9)):
            return mistake.hint(context) if callable(mistake.hint) else mistake.hint
    for digits in range(5):  # rounded before returning: name it, as the angle check does
        rounded = round(context.right, digits)
        if abs(rounded - float(got)) < 1e-12 and abs(rounded - context.right) > 1e-9 * abs(
            context.right
        ):
            return (
                f"you rounded the cross-ratio to {digits} decimal{'s' * (digits != 1)}: {rounded:g}, where it is "
                f'{context.right:.9g}. Return it as computed, and round only when you print it (f"{{r:.3f}}").'
            )
    return _order_hint(context, got) or (
        f"(A, B; C, D) = {expected:.6g} here, not {float(got):.6g}. Divide by w, measure signed positions "
        "t along the line, then (t_C - t_A)(t_D - t_B) / ((t_C - t_B)(t_D - t_A))."
    )


def cross_ratio(points):
    """The cross-ratio (A, B; C, D) = AC BD / (BC AD) of four collinear homogeneous points.

    Divide by w, give each point its signed position t along the line (its projection on the
    direction D - A), and take the signed lengths as differences of positions: the direction's
    length and the origin cancel in the ratio.

    Parameters
    ----------
    points : (4, 3) array_like
        A, B, C, D as homogeneous rows (x, y, w), w != 0.

    Returns
    -------
    float
        (A, B; C, D).

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 2.5.
    """
    x = np.asarray(points, dtype=float)
    xy = x[:, :2] / x[:, 2:]  # Euclidean points
    t = (xy - xy[0]) @ (xy[3] - xy[0])  # signed positions along the line
    a, b, c, d = t
    return (c - a) * (d - b) / ((c - b) * (d - a))


def _unsigned_wrong(points):
    return _unsigned(_euclidean(points))


register_exercise(
    Exercise(
        name="cross_ratio",
        lesson="06",
        reference=_cross_reference,
        cases=_cross_cases,
        compare=same_number(rtol=1e-9),
        diagnose=_cross_diagnosis,
        wrong_variants=(
            (_unsigned_wrong, "unsigned lengths"),
            (lambda p: _distance_from_a(_euclidean(p)), "unsigned distance from A"),
            (lambda p: _unsigned(np.asarray(p, dtype=float)[:, :2]), "without dividing by w"),
            (
                lambda p: _signed_ratio(_positions(np.asarray(p, dtype=float)[:, :2])),
                "without dividing by w",
            ),
            (
                lambda p: _signed_ratio(_positions(np.asarray(p, dtype=float))),
                "without dividing by w",
            ),
            (lambda p: _unsigned(np.asarray(p, dtype=float)), "without dividing by w"),
            (
                lambda p: _signed_ratio(_positions(np.asarray(p, dtype=float)[[0, 2, 1, 3], :2])),
                "without dividing by w",
            ),
            (
                lambda p: _signed_ratio(
                    _positions(
                        np.asarray(p, dtype=float)[:, :2]
                        / np.abs(np.asarray(p, dtype=float)[:, 2:])
                    )
                ),
                "divided by |w|",
            ),
            (lambda p: 1.0 - 1.0 / _cross_reference(p), "Hartley & Zisserman's Cross"),
            (lambda p: 1.0 / _cross_reference(p), "numerator and denominator swapped"),
            (lambda p: _signed_ratio(_positions(_euclidean(p)[[0, 2, 1, 3]])), "(A, C; B, D)"),
            (silenced(lambda p: _signed_ratio(_euclidean(p)[:, 0])), "same x"),
            (lambda p: [_cross_reference(p)], "one number"),
            (lambda p: _simple_ratio(_euclidean(p)), "ratio of two lengths"),
            (lambda p: round(_cross_reference(p), 3), "rounded the cross-ratio to 3 decimals"),
        ),
        teaching=cross_ratio,
    )
)
