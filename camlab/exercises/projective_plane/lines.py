"""Lesson 06, exercises 1-3: the line through two points, the meet of two lines, a vanishing point."""

from __future__ import annotations

import numpy as np

from ... import projective
from .._answers import same_up_to_scale, shape_problem
from .._core import Exercise, register_exercise


def incidence(point: np.ndarray, line: np.ndarray) -> float:
    """|l . x| for unit-norm l and x: 0 when x lies on l, whatever their scales.

    Parameters
    ----------
    point, line : (3,) array_like
        A homogeneous point and a line, any non-zero scales.

    Returns
    -------
    float
        The normalised incidence, inf when either is all zeros.
    """
    x = np.asarray(point, dtype=float)
    norms = np.linalg.norm(line) * np.linalg.norm(x)
    return float(abs(line @ x) / norms) if norms > 0 else np.inf


def miss_px(point, line, unit: str = "px") -> str:
    """The distance of a homogeneous point from a line, in pixels, as text (for a hint).

    Parameters
    ----------
    point, line : (3,) array_like
        A homogeneous point and a line, any non-zero scales.
    unit : str
        The unit written after the distance: ``"px"`` for image lines, ``"units"`` for the
        abstract lines of the plane.

    Returns
    -------
    str
        ``"0.42 px"``, or the normalised incidence when the point is ideal (w = 0) or the line is
        the line at infinity, where no distance exists.
    """
    x, ln = np.asarray(point, dtype=float), np.asarray(line, dtype=float)
    scale = abs(x[2]) * np.hypot(ln[0], ln[1])
    if scale > 1e-12 * np.linalg.norm(x) * np.linalg.norm(ln):
        return f"{abs(ln @ x) / scale:.3g} {unit}"
    return f"normalised |l . x| = {incidence(x, ln):.3g}"


def silenced(f):
    """``f`` with numpy's divide warnings silenced (a wrong variant that divides by 0 on purpose).

    Parameters
    ----------
    f : callable
        A student's (wrong) function.

    Returns
    -------
    callable
        ``f`` run under ``np.errstate(divide="ignore", invalid="ignore")``.
    """

    def quiet(*args):
        with np.errstate(divide="ignore", invalid="ignore"):
            return f(*args)

    return quiet


def followed_by(problem: str, more: str) -> str:
    """``problem`` followed by the sentence ``more`` (no ". " after a question mark).

    Parameters
    ----------
    problem, more : str
        Two sentences of a hint.

    Returns
    -------
    str
        Both, joined.
    """
    return problem + (" " if problem.rstrip().endswith("?") else ". ") + more


def one_number_hint(got, a, b, fix: str) -> str:
    """Why one number came back where a join or meet (a 3-vector) belongs: a dot product or a 2-D cross.

    Parameters
    ----------
    got : scalar
        The student's answer.
    a, b : (3,) array_like
        The two inputs as homogeneous 3-vectors (points lifted to w = 1, or lines).
    fix : str
        The right call, quoted at the end of the hint.

    Returns
    -------
    str
        The hint: the incidence test (a dot product) used for a join or meet, or np.cross of 2-vectors.
    """
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    try:
        value = float(got)
    except (TypeError, ValueError):
        value = np.nan
    if np.isclose(value, a @ b, rtol=1e-9, atol=1e-12):
        return (
            "you returned one number, the dot product of the two inputs. A dot product l . x tests "
            "incidence (0 when x lies on l); the line through two points, or the point on two lines, "
            f"is the vector orthogonal to both: their cross product, {fix}"
        )
    return (
        "you returned one number: np.cross of two 2-vectors gives only the z of their 3-D cross "
        f"product (and numpy 2 deprecates it). Cross the whole 3-vectors: {fix}"
    )


_PARALLEL_MEET = (
    "two parallel lines meet at an ideal point (x, y, 0), whose w is 0: dividing by w gives inf or NaN, "
    "and solving the 2 x 2 system fails. Keep the cross product's (x, y, w) as it is"
)


def _parallel(lines) -> bool:
    """True when the two lines have the same normal direction (they meet at an ideal point)."""
    (a1, b1, _), (a2, b2, _) = (np.asarray(ln, dtype=float) for ln in lines)
    return abs(a1 * b2 - a2 * b1) <= 1e-12 * (np.hypot(a1, b1) * np.hypot(a2, b2))


def homogeneous_point_diagnosis(got, expected, lines, how: str) -> str:
    """The likely cause when a student's homogeneous point (exercises 2 and 3) is wrong.

    Parameters
    ----------
    got, expected : array_like
        The student's answer and the right point (x, y, w).
    lines : sequence of (3,) array_like
        The two lines the point must lie on.
    how : str
        The sentence that says how to get the point right, ending the generic hint.

    Returns
    -------
    str
        The hint: a named slip, or how far (in pixels) the point misses each line, then ``how``.
    """
    if np.ndim(got) == 0 and got is not None and not isinstance(got, (str, bytes)):
        return one_number_hint(got, *lines, "np.cross(l1, l2)")
    problem = shape_problem(got, expected)
    if problem and np.shape(got) == (2,):
        return (
            "you returned a Euclidean (x, y); return the homogeneous 3-vector instead. "
            "Parallel lines meet at an ideal point (x, y, 0), which has no (x, y)."
        )
    if problem and np.shape(got) == np.shape(expected) and _parallel(lines):
        return "this test input's lines are parallel: " + _PARALLEL_MEET + "."
    if problem:
        return problem
    g = np.asarray(got, dtype=float)
    if np.abs(g).max() > np.finfo(float).max / 1e8:
        return (
            f"your point holds {np.abs(g).max():.3g}, about the largest float: an inf from a division by w = 0, "
            "hidden by np.nan_to_num (or a clip). "
            + (
                "This test input's lines are parallel: " + _PARALLEL_MEET
                if _parallel(lines)
                else how
            )
            + "."
        )
    if _parallel(lines) and abs(g[2]) > 1e-9 * np.linalg.norm(g):
        return (
            "this test input's lines are parallel, so no finite point (x, y, 1) lies on both; a least-squares "
            "solve (np.linalg.lstsq, pinv) returns a compromise between them, but "
            + _PARALLEL_MEET
            + "."
        )
    if not np.any(g):
        return (
            "you returned (0, 0, 0), which is no point: did you lift with w = 0, or cross a vector with "
            "itself? Lift each pixel to (u, v, 1), join, then meet."
        )
    if same_up_to_scale(g, np.asarray(expected, dtype=float) * [-1, -1, 1]):
        return (
            "your point is (-x, -y) of the right one: a sign slip, such as solving A (x, y) = c instead of "
            "-c, or (x, y, -w). Keep the cross product l1 x l2 as it is."
        )
    for flip, axis, entry in (
        ([1, -1, 1], "x", "y = a3 b1 - a1 b3"),
        ([-1, 1, 1], "y", "x = a2 b3 - a3 b2"),
    ):
        if same_up_to_scale(g, np.asarray(expected, dtype=float) * flip):
            return (
                f"your point is the right one mirrored in the {axis} axis: one component of the cross product "
                f"has the wrong sign. Written out, {entry}; or let np.cross do it."
            )
    if same_up_to_scale(g, np.asarray(expected, dtype=float)[[1, 0, 2]]):
        return (
            "you swapped x and y: your point is (y, x, w) of the right one. Keep the cross product's "
            "entries in their order (x, y, w)."
        )
    if max(incidence(got, ln) for ln in lines) > 1e-6:
        off = [miss_px(g, ln, "units") for ln in lines]  # abstract lines: no pixels
        return f"your point is not on both lines (it misses them by {off[0]} and {off[1]}). {how}"
    return "the point is on both lines but differs from the expected one; check the inputs you used"


def solve_hint(exc: Exception, lines) -> str:
    """The likely cause when a student's Euclidean solve fails on two lines, or ''.

    Parameters
    ----------
    exc : Exception
        What the student's function raised.
    lines : sequence of (3,) array_like
        The two test lines.

    Returns
    -------
    str
        The hint for a solve on parallel lines, else ''.
    """
    if isinstance(
        exc, (np.linalg.LinAlgError, ZeroDivisionError, FloatingPointError)
    ) and _parallel(lines):
        return (
            f"{type(exc).__name__} on parallel lines: a Euclidean solve (np.linalg.solve, inv, Cramer's "
            "rule) has no answer there, but the projective plane has one: "
            + _PARALLEL_MEET
            + " (l1 x l2 gives it)"
        )
    return ""


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
        diagnose=lambda args, got, expected: homogeneous_point_diagnosis(
            got, expected, args, "The point on two lines is their cross product l1 x l2."
        ),
        wrong_variants=(
            (lambda l1, l2: (np.cross(l1, l2) / np.cross(l1, l2)[2])[:2], "homogeneous 3-vector"),
            (lambda l1, l2: l1 + l2, "not on both lines"),
            (lambda l1, l2: np.cross(l1, l2) * [-1, -1, 1], "(-x, -y)"),
            (lambda l1, l2: np.array(l1[0] * l2[1] - l1[1] * l2[0]), "np.cross of two 2-vectors"),
            (lambda l1, l2: l1 @ l2, "tests incidence"),
            (lambda l1, l2: np.cross(l1, l2) * [1, -1, 1], "mirrored in the x axis"),
            (lambda l1, l2: np.cross(l1, l2)[[1, 0, 2]], "swapped x and y"),
            (silenced(lambda l1, l2: np.cross(l1, l2) / np.cross(l1, l2)[2]), "lines are parallel"),
            (
                silenced(lambda l1, l2: np.nan_to_num(np.cross(l1, l2) / np.cross(l1, l2)[2])),
                "hidden by np.nan_to_num",
            ),
            (
                lambda l1, l2: np.append(
                    np.linalg.lstsq(np.array([l1[:2], l2[:2]]), -np.array([l1[2], l2[2]]))[0], 1.0
                ),
                "least-squares",
            ),
            (
                lambda l1, l2: np.append(
                    np.linalg.solve(np.array([l1[:2], l2[:2]]), -np.array([l1[2], l2[2]])), 1.0
                ),
                "parallel lines",
            ),
        ),
        exception_hint=solve_hint,
        teaching=intersect_lines,
    )
)


def _line_cases():
    return [
        (np.array([320.0, 240.0]), np.array([10.0, 470.0])),
        (np.array([100.0, 50.0]), np.array([100.0, 400.0])),  # vertical
        (np.array([-3.0, 7.0]), np.array([12.0, 7.0])),  # horizontal
        (np.array([0.0, 0.0]), np.array([1.0, 1.0])),  # through the origin: c = 0
    ]


def _line_through(p, q) -> np.ndarray:
    return np.cross(
        np.append(np.asarray(p, dtype=float), 1.0), np.append(np.asarray(q, dtype=float), 1.0)
    )


#: (shift (du, dv) in px, its likely cause): the pixel-offset slips exercises 1 and 3 name
PIXEL_SHIFTS = tuple(
    (np.array(d), why)
    for d, why in (
        ((0.5, 0.5), "a half-pixel offset"),
        ((-0.5, -0.5), "a half-pixel offset"),
        ((0.5, 0.0), "a half-pixel offset on one axis"),
        ((0.0, 0.5), "a half-pixel offset on one axis"),
        ((-0.5, 0.0), "a half-pixel offset on one axis"),
        ((0.0, -0.5), "a half-pixel offset on one axis"),
        ((1.0, 1.0), "1-based pixels?"),
        ((-1.0, -1.0), "an off-by-one?"),
    )
)


def _line_slips(p, q):
    """(the line a slip gives, its hint) for the slips a student makes on the points p, q."""
    right = _line_through(p, q)
    shifted = (
        "your line passes through both points shifted by ({:+g}, {:+g}) px in (x, y) ({}). Use the pixels as "
        "given: "
        "(u, v) lifts to (u, v, 1) with no offset"
    )
    return [
        (
            np.append(np.asarray(q, float) - p, 0.0),
            "your (a, b) is the line's direction q - p; the line's "
            "(a, b) is its normal, perpendicular to that, and c places it. Both come out of p~ x q~",
        ),
        (
            right * [1, 1, -1],
            "your (a, b) is right but c has the wrong sign, so the line is mirrored through "
            "the origin: for l = (a, b, c), a x + b y + c = 0. Take the whole cross product p~ x q~; do not "
            "recompute or negate c by hand",
        ),
        (
            _line_through(p * [1, -1], q * [1, -1]),
            "your line passes through (x, -y) of each point: a y flip "
            "(y up instead of the image's v down). Lift (u, v) as it is, to (u, v, 1)",
        ),
        (
            _line_through(p * [1, -1] + [0, 479], q * [1, -1] + [0, 479]),
            "your line passes through (x, 479 - y) of each point: the image flipped upside down (y up "
            "instead of the image's v down). Lift (u, v) as it is, to (u, v, 1)",
        ),
        *((_line_through(p + d, q + d), shifted.format(*d, why)) for d, why in PIXEL_SHIFTS),
    ]


def _line_diagnosis(args, got, expected) -> str:
    if np.ndim(got) == 0 and not isinstance(got, (str, bytes)) and got is not None:
        lifted = (np.append(np.asarray(a, dtype=float), 1.0) for a in args)
        return one_number_hint(got, *lifted, "np.cross(np.append(p, 1.0), np.append(q, 1.0))")
    problem = shape_problem(got, expected)
    p, q = (np.asarray(a, dtype=float) for a in args)
    if problem and np.shape(got) == (3,) and p[0] == q[0]:
        return followed_by(
            problem,
            "This test line is vertical (both points have x = "
            f"{p[0]:g}): it has no slope, so a slope-intercept form (m, -1, b) breaks. The cross "
            "product of the lifted points needs no slope: it gives (a, b, c) = (1, 0, -x) up to scale",
        )
    if problem and np.shape(got) == (3,) and 0 in np.asarray(expected)[2:]:
        return followed_by(
            problem,
            "This test input's line passes through the origin, so its c is 0: dividing by c "
            "(to make it 1) gives inf. Any non-zero scale is accepted; return the line unscaled",
        )
    if problem:
        return followed_by(problem, "A line is the 3-vector (a, b, c) of ax + by + c = 0.")
    g = np.asarray(got, dtype=float)
    if not np.any(g):
        return (
            "you returned (0, 0, 0), which is no line: did you lift with w = 0 (the point (0, 0) then becomes "
            "the zero vector)? Lift p and q to (x, y, 1) before the cross product."
        )
    if not np.any(g[:2]):
        return (
            "your line is (0, 0, c), the line at infinity: you lifted the points with w = 0, which makes them "
            "directions, not points. Lift p and q to (x, y, 1) before the cross product."
        )
    if same_up_to_scale(g, _line_through(p[::-1], q[::-1])):
        return (
            "you swapped the coordinates: your line passes through (y, x) of each point. A pixel "
            "(u, v) = (column, row) lifts to (u, v, 1): p[0] first, then p[1], then 1."
        )
    for line, hint in _line_slips(p, q):
        if same_up_to_scale(g, line):
            return hint
    d = q - p
    if any(same_up_to_scale(g, np.append(d, -d @ x)) for x in (p, q)):
        return (
            "your line's normal (a, b) is q - p, the direction from p to q, so your line crosses the segment pq "
            "at a right angle. The normal of the line through p and q is perpendicular to q - p, (-(qy - py), "
            "qx - px); the cross product of the lifted points (x1, y1, 1) x (x2, y2, 1) gives it with c."
        )
    off = [miss_px(np.append(x, 1.0), g) for x in (p, q)]
    return (
        f"your line does not pass through both points (it misses p by {off[0]} and q by {off[1]}). The line through them is the cross product of the lifted points, "
        "(x1, y1, 1) x (x2, y2, 1)."
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
            (lambda p, q: np.cross(np.append(p, 0.0), np.append(q, 0.0)), "with w = 0"),
            (lambda p, q: np.append(q - p, 0.0), "direction q - p"),
            (lambda p, q: _line_through(p + 0.5, q + 0.5), "half-pixel"),
            (lambda p, q: _line_through(p * [1, -1], q * [1, -1]), "y flip"),
            (lambda p, q: _line_through(p + [0.5, 0.0], q + [0.5, 0.0]), "on one axis"),
            (lambda p, q: _line_through(p * [1, -1] + [0, 479], q * [1, -1] + [0, 479]), "479 - y"),
            (lambda p, q: _line_through(p, q) * [1, 1, -1], "wrong sign"),
            (lambda p, q: np.array(p[0] * q[1] - p[1] * q[0]), "np.cross of two 2-vectors"),
            (lambda p, q: np.append(p, 1.0) @ np.append(q, 1.0), "tests incidence"),
            (lambda p, q: np.append(q - p, -(q - p) @ p), "normal (a, b) is q - p"),
            (silenced(lambda p, q: _line_through(p, q) / _line_through(p, q)[2]), "dividing by c"),
            (
                lambda p, q: _line_through(p, q) + [0.0, 0.0, 3.0],
                "does not pass through both points",
            ),
            (
                lambda p, q: np.cross([p[1], p[0], 1.0], [q[1], q[0], 1.0]),
                "swapped the coordinates",
            ),
            (  # slope-intercept form: breaks on the vertical test line
                silenced(
                    lambda p, q: (lambda m: np.array([m, -1.0, p[1] - m * p[0]]))(
                        (q[1] - p[1]) / (q[0] - p[0])
                    )
                ),
                "has no slope",
            ),
        ),
        teaching=line_through_points,
    )
)
