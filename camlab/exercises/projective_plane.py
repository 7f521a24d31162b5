"""Exercises for lesson 06, the projective plane."""

from __future__ import annotations

import numpy as np

from .. import projective
from ._answers import same_up_to_scale, shape_problem
from ._core import Exercise, register_exercise


def _incidence(point: np.ndarray, line: np.ndarray) -> float:
    """|l . x| for unit-norm l and x: 0 when x lies on l, whatever their scales."""
    x = np.asarray(point, dtype=float)
    norms = np.linalg.norm(line) * np.linalg.norm(x)
    return float(abs(line @ x) / norms) if norms > 0 else np.inf


def _homogeneous_point_diagnosis(got, expected, lines, how: str) -> str:
    problem = shape_problem(got, expected)
    if problem and np.shape(got) == (2,):
        return (
            "you returned a Euclidean (x, y); return the homogeneous 3-vector instead. "
            "Parallel lines meet at an ideal point (x, y, 0), which has no (x, y)."
        )
    if problem:
        return problem
    off = [_incidence(got, ln) for ln in lines]
    if max(off) > 1e-6:
        return (
            f"your point is not on both lines (normalised |l . x| = {off[0]:.3g} and {off[1]:.3g}). "
            f"{how}"
        )
    return "the point is on both lines but differs from the expected one; check the inputs you used"


def _intersect_cases():
    return [
        (np.array([1.0, 0.0, -2.0]), np.array([0.0, 1.0, -3.0])),  # x = 2, y = 3
        (np.array([1.0, -1.0, 0.0]), np.array([1.0, 1.0, -4.0])),  # y = x, y = 4 - x
        (np.array([0.0, 1.0, -1.0]), np.array([0.0, 2.0, -6.0])),  # parallel: y = 1, y = 3
        (np.array([3.0, -2.0, 120.0]), np.array([-1.0, 5.0, -40.0])),
    ]


def intersect_lines(l1, l2):
    """The point on both lines is orthogonal to both: their cross product (kept homogeneous).

    Parameters
    ----------
    l1, l2 : (3,) array_like
        Lines (a, b, c): a x + b y + c = 0.

    Returns
    -------
    (3,) ndarray
        l1 x l2, their intersection, homogeneous (w = 0 for parallel lines).

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 2.2.1 (result 2.2).
    """
    return np.cross(np.asarray(l1, dtype=float), np.asarray(l2, dtype=float))


register_exercise(
    Exercise(
        name="intersect_lines",
        lesson="06",
        reference=projective.meet,
        cases=_intersect_cases,
        compare=same_up_to_scale,
        diagnose=lambda args, got, expected: _homogeneous_point_diagnosis(
            got, expected, args, "The point on two lines is their cross product l1 x l2."
        ),
        wrong_variants=(
            (lambda l1, l2: (np.cross(l1, l2) / np.cross(l1, l2)[2])[:2], "homogeneous 3-vector"),
            (lambda l1, l2: l1 + l2, "not on both lines"),
        ),
        teaching=intersect_lines,
    )
)


def _line_cases():
    return [
        (np.array([0.0, 0.0]), np.array([1.0, 1.0])),
        (np.array([100.0, 50.0]), np.array([100.0, 400.0])),  # vertical
        (np.array([-3.0, 7.0]), np.array([12.0, 7.0])),  # horizontal
        (np.array([320.0, 240.0]), np.array([10.0, 470.0])),
    ]


def _line_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". A line is the 3-vector (a, b, c) of ax + by + c = 0."
    if not np.any(got):
        return "you returned (0, 0, 0), which is no line. Lift p and q to (x, y, 1) before the cross product."
    p, q = (np.append(a, 1.0) for a in args)
    off = [_incidence(x, np.asarray(got, dtype=float)) for x in (p, q)]
    return (
        f"your line does not pass through both points (normalised |l . p| = {off[0]:.3g}, "
        f"|l . q| = {off[1]:.3g}). Lift p and q to (x, y, 1) before the cross product."
    )


def line_through_points(p, q):
    """Lift both pixels to (x, y, 1); the line through them is orthogonal to both: p x q.

    Parameters
    ----------
    p, q : (2,) array_like
        Two distinct points (x, y), pixels.

    Returns
    -------
    (3,) ndarray
        The line (a, b, c) through both, up to scale.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 2.2.1 (result 2.4).
    """
    p_h = np.array([p[0], p[1], 1.0])
    q_h = np.array([q[0], q[1], 1.0])
    return np.cross(p_h, q_h)


register_exercise(
    Exercise(
        name="line_through_points",
        lesson="06",
        reference=projective.join,
        cases=_line_cases,
        compare=same_up_to_scale,
        diagnose=_line_diagnosis,
        wrong_variants=(
            (lambda p, q: np.cross(np.append(p, 0.0), np.append(q, 0.0)), "Lift p and q"),
            (lambda p, q: np.append(q - p, 0.0), "does not pass through both points"),
        ),
        teaching=line_through_points,
    )
)


def _vanishing_cases():
    # Two images of parallel rails: segments [[u1, v1], [u2, v2]] in pixels.
    return [
        (np.array([[[100.0, 480.0], [280.0, 200.0]], [[540.0, 480.0], [360.0, 200.0]]]),),
        (np.array([[[0.0, 300.0], [640.0, 260.0]], [[0.0, 420.0], [640.0, 330.0]]]),),
        (np.array([[[10.0, 10.0], [110.0, 60.0]], [[10.0, 110.0], [110.0, 160.0]]]),),  # parallel
    ]


def _vanishing_diagnosis(args, got, expected) -> str:
    (segments,) = args
    lines = [projective.join(s[0], s[1]) for s in segments]
    return _homogeneous_point_diagnosis(
        got,
        expected,
        lines,
        "Make one line per segment (join its two endpoints), then intersect the two lines.",
    )


def vanishing_point(segments):
    """One line per segment (join its endpoints), then meet the two lines; stay homogeneous.

    Parameters
    ----------
    segments : (2, 2, 2) array_like
        Two image segments, each as its endpoints ((x, y), (x, y)), pixels.

    Returns
    -------
    (3,) ndarray
        Where the two segments' lines meet, homogeneous (w = 0 when they are parallel in the image).

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., sections 2.2.1 and 8.6.
    """
    (a1, b1), (a2, b2) = np.asarray(segments, dtype=float)
    line1 = np.cross([a1[0], a1[1], 1.0], [b1[0], b1[1], 1.0])
    line2 = np.cross([a2[0], a2[1], 1.0], [b2[0], b2[1], 1.0])
    return np.cross(line1, line2)


register_exercise(
    Exercise(
        name="vanishing_point",
        lesson="06",
        reference=projective.vanishing_point,
        cases=_vanishing_cases,
        compare=same_up_to_scale,
        diagnose=_vanishing_diagnosis,
        wrong_variants=(
            # Joins the two segments' start points instead of each segment's endpoints.
            (
                lambda s: np.cross(
                    np.cross([*s[0, 0], 1], [*s[1, 0], 1]), np.cross([*s[0, 1], 1], [*s[1, 1], 1])
                ),
                "not on both lines",
            ),
            (
                lambda s: projective.from_homogeneous(projective.vanishing_point(s)),
                "homogeneous 3-vector",
            ),
        ),
        teaching=vanishing_point,
    )
)
