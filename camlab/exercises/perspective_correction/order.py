"""Exercise 3 of lesson 10: the four corners in the order TL, TR, BR, BL (`order_corners`)."""

from __future__ import annotations

import numpy as np

from ... import perspective as pp
from ... import scenes
from .._answers import same_array, shape_problem
from .._core import Exercise, register_exercise


def _rotated_rectangle(angle_deg: float, centre=(320.0, 240.0), size=(260.0, 150.0)) -> np.ndarray:
    """Corners of a w x h rectangle turned by angle_deg on screen, in TL, TR, BR, BL order of the unturned one."""
    t = np.radians(angle_deg)
    R = np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])
    w, h = size
    return np.array([[-w, -h], [w, -h], [w, h], [-w, h]]) / 2 @ R.T + centre


def _order_cases():
    page = scenes.sample_photo("page").corners
    return [
        # a 20 x 10 rectangle, not a square: on a square, (v, u) and counter-clockwise look alike
        (np.array([[20.0, 0.0], [0.0, 0.0], [0.0, 10.0], [20.0, 10.0]]),),
        (page[[2, 0, 3, 1]],),
        (page[[3, 2, 1, 0]],),
        (
            np.array([[300.0, 50.0], [520.0, 120.0], [90.0, 300.0], [480.0, 420.0]]),
        ),  # bow-tie order
        # turned quadrilaterals: the corner with the smallest angle around the centroid is
        # then not the top-left one, so sorting by angle alone starts in the wrong place
        (_rotated_rectangle(25.0)[[1, 3, 0, 2]],),
        (_rotated_rectangle(-35.0)[[2, 1, 3, 0]],),
        (_rotated_rectangle(40.0, size=(200.0, 300.0))[[3, 0, 2, 1]],),
        # pages seen in perspective and turned: convex, but no rectangle, so the "u + v, v - u"
        # trick (TL = argmin u + v, TR = argmin v - u, ...) picks one corner twice
        (np.array([[482.0, 344.0], [194.0, 290.0], [352.0, 18.0], [211.0, 505.0]]),),
        (np.array([[150.0, 60.0], [600.0, 180.0], [420.0, 300.0], [60.0, 250.0]]),),
    ]


def _sum_difference_trick(corners):
    """A popular shortcut that holds for rectangles only: TL, TR, BR, BL by the extremes of u + v and v - u."""
    q = np.asarray(corners, dtype=float)
    s, d = q.sum(axis=1), q[:, 1] - q[:, 0]
    return q[[np.argmin(s), np.argmin(d), np.argmax(s), np.argmax(d)]]


def _order_diagnosis(args, got, expected, run=None) -> str:
    if np.shape(got) == (4,) and sorted(np.asarray(got).tolist()) == [0, 1, 2, 3]:
        return (
            "you returned the order, indices of the input corners; return the corners themselves, "
            "corners[order], a (4, 2) array (u, v) in the order TL, TR, BR, BL."
        )
    problem = shape_problem(got, expected)
    if problem:
        return problem
    g = np.asarray(got, dtype=float)
    corners = np.asarray(args[0], dtype=float)
    which = [np.flatnonzero(np.all(np.isclose(corners, p), axis=1)) for p in g]
    swapped = [np.flatnonzero(np.all(np.isclose(corners, p), axis=1)) for p in g[:, ::-1]]
    if any(len(k) == 0 for k in which) and all(len(k) for k in swapped):
        return (
            "your points come back as (v, u), row first: return each corner as it came in, (u, v), column "
            "first (did you swap the columns, or index img-style [row, col]?)."
        )
    if any(len(k) == 0 for k in which):
        return (
            "your four points are not the input corners: return the same four points (u, v), reordered "
            "(not indices, not moved, not (v, u))."
        )
    if len({int(k[0]) for k in which}) < 4:
        twice = (
            "the u + v / v - u shortcut"
            if np.allclose(g, _sum_difference_trick(corners))
            else "your method"
        )
        return (
            f"one input corner comes back twice and another is missing: {twice} (TL = argmin u + v, TR = argmin "
            "v - u, ...) holds for upright rectangles only; a page seen in perspective can have one corner "
            "extreme in both sums. Sort by the angle around the centroid (np.arctan2(v - v_c, u - u_c)), then "
            "start at the smallest u + v."
        )
    for shift in (1, 2, 3):
        if np.allclose(g, np.roll(expected, shift, axis=0)):
            return (
                "the cyclic order is right but it does not start at the top-left corner"
                + _start_rule(g, corners, run)
            )
    ccw = [s for s in range(4) if np.allclose(g, np.roll(expected[::-1], s, axis=0))]
    if ccw:
        # the usual slips all give the same answer on every input (arctan2(u, v) is arctan2(v, u)
        # reflected; -(v - v_c) and a descending sort reverse the order), so name them all
        start = (
            "" if np.allclose(g[0], expected[0]) else " (and start at the top-left, smallest u + v)"
        )
        return (
            "your corners go counter-clockwise on screen. v points down, so clockwise on screen is "
            f"increasing np.arctan2(v - v_c, u - u_c){start}. Each of these reverses it: a descending "
            "sort, the arguments of np.arctan2 swapped (it takes (y, x), v first), v flipped to point "
            "up (-(v - v_c)), or cv2.convexHull(..., clockwise=True), which means clockwise with y up."
        )
    if np.allclose(g, expected[[0, 1, 3, 2]]):
        return (
            "your corners are in Z order (TL, TR, BL, BR, what sorting by v, then u, gives): it zig-zags "
            "across the page, and a homography fed that order makes a bow tie. Go round the quadrilateral: "
            "sort by the angle around the centroid (np.arctan2(v - v_c, u - u_c)), then start at the "
            "smallest u + v."
        )
    if np.allclose(g, _two_topmost(corners)):
        return (
            "you took the two topmost corners (smallest v) as the top edge: a shortcut for upright pages "
            "only; here the two topmost corners are opposite corners, so your order crosses itself. Sort by "
            "the angle around the centroid (np.arctan2(v - v_c, u - u_c)), then start at the smallest u + v."
        )
    return (
        "your order crosses itself or does not go round the quadrilateral; sort by the angle around the "
        "centroid (np.arctan2(v - v_c, u - u_c)), which works for any convex quadrilateral, then start at "
        "the top-left corner (smallest u + v)."
    )


_ROLL = "np.roll(q, -np.argmin(q.sum(axis=1)), axis=0)"


# Quadrilaterals on which the four start rules below pairwise differ, to tell them apart
_PROBES = (
    np.array([[150.0, 235.0], [260.0, 40.0], [540.0, 250.0], [330.0, 430.0]]),
    np.array([[482.0, 344.0], [194.0, 290.0], [352.0, 18.0], [211.0, 505.0]]),
    np.array([[100.0, 300.0], [200.0, 80.0], [450.0, 60.0], [420.0, 400.0]]),
)


def _start_rule(got, corners, run=None) -> str:
    """Name the start rule the answer followed, where it is one of the tempting ones, else the fix.

    Several rules can give the same order on one input; ``run`` (the student's function, on other
    input) then tells them apart on :data:`_PROBES`.
    """
    rules = [
        (
            _sorted_by_angle,
            "you sorted by angle but did not rotate the sorted corners to start at the top-left one: "
            "the sort starts wherever np.arctan2's -pi falls (the corner left of the centroid)",
        ),
        (
            _two_topmost,
            "you took the two topmost corners (smallest v) as the top edge, sorted by u: a shortcut "
            "for upright pages only; once a page is turned further than its diagonal (tan of the turn "
            "> h / w) the two topmost corners are a side edge, TL and BL or TR and BR",
        ),
        (
            _start_at(1),
            "you started at the topmost corner (smallest v), often the top-right one in a turned page",
        ),
        (
            _start_at(0),
            "you started at the leftmost corner (smallest u), often the bottom-left one in a turned page",
        ),
    ]
    named = [(rule, hint) for rule, hint in rules if np.allclose(got, rule(corners))]
    if len(named) > 1 and run is not None:
        try:
            answers = [np.asarray(run(q.copy()), dtype=float) for q in _PROBES]
            named = [
                (rule, hint)
                for rule, hint in named
                if all(
                    a.shape == (4, 2) and np.allclose(a, rule(q))
                    for a, q in zip(answers, _PROBES, strict=True)
                )
            ] or named
        except Exception:  # the student's function fails on a probe: keep every candidate
            pass
    named = [hint for _, hint in named]
    fix = f". The top-left corner is the one with the smallest u + v: {_ROLL}."
    if not named:
        return f" (smallest u + v): rotate the sorted corners, {_ROLL}."
    if len(named) == 1:
        return ": " + named[0] + fix
    return (
        ": on this input several slips give this order, one of them: " + "; or ".join(named) + fix
    )


def _start_at(k):
    """A tempting slip: sort by angle, then start at the corner with the smallest coordinate ``k``."""

    def student(corners):
        q = _sorted_by_angle(corners)
        return np.roll(q, -np.argmin(q[:, k]), axis=0)

    return student


def order_corners(corners):
    """Sort by angle around the centroid (clockwise on screen, v down), then start at min u + v.

    Parameters
    ----------
    corners : (4, 2) array_like
        A convex quadrilateral's corners (u, v), pixels, in any order.

    Returns
    -------
    (4, 2) ndarray
        The corners clockwise on screen, starting at the top-left one (smallest u + v).
    """
    q = np.asarray(corners, dtype=float)
    c = q.mean(axis=0)
    q = q[np.argsort(np.arctan2(q[:, 1] - c[1], q[:, 0] - c[0]))]
    return np.roll(q, -np.argmin(q.sum(axis=1)), axis=0)


def _sorted_by_angle(corners):
    """A plausible mistake: sort by angle around the centroid, but never rotate to the top-left."""
    q = np.asarray(corners, dtype=float)
    c = q.mean(axis=0)
    return q[np.argsort(np.arctan2(q[:, 1] - c[1], q[:, 0] - c[0]))]


def _two_topmost(corners):
    """A tempting shortcut: the two topmost corners (smallest v) as the top edge, sorted by u.

    The other two are the bottom edge, sorted by u descending.
    """
    q = np.asarray(corners, dtype=float)
    q = q[np.argsort(q[:, 1], kind="stable")]
    top, bottom = q[:2][np.argsort(q[:2, 0])], q[2:][np.argsort(-q[2:, 0])]
    return np.vstack([top, bottom])


def _swapped_arctan2(corners):
    """A typical slip: np.arctan2(u - u_c, v - v_c), arguments swapped, then started at the top-left."""
    q = np.asarray(corners, dtype=float)
    c = q.mean(axis=0)
    q = q[np.argsort(np.arctan2(q[:, 0] - c[0], q[:, 1] - c[1]))]
    return np.roll(q, -np.argmin(q.sum(axis=1)), axis=0)


register_exercise(
    Exercise(
        name="order_corners",
        lesson="10",
        reference=pp.order_corners,
        cases=_order_cases,
        compare=same_array(),
        diagnose=_order_diagnosis,
        diagnosis_runs=True,
        wrong_variants=(
            (lambda c: np.roll(pp.order_corners(c), 1, axis=0), "does not start at the top-left"),
            (lambda c: pp.order_corners(c)[::-1], "counter-clockwise"),
            (_swapped_arctan2, "the arguments of np.arctan2 swapped"),
            (
                lambda c: np.array(
                    [np.flatnonzero(np.isclose(c, p).all(1))[0] for p in pp.order_corners(c)]
                ),
                "indices of the input corners",
            ),
            (
                lambda c: np.asarray(c, float)[
                    np.lexsort((np.asarray(c)[:, 0], np.asarray(c)[:, 1]))
                ],
                "sort by the angle",
            ),
            (_sorted_by_angle, "did not rotate the sorted corners"),
            (_two_topmost, "two topmost corners"),
            (_start_at(1), "started at the topmost corner"),
            (_start_at(0), "started at the leftmost corner"),
            (lambda c: pp.order_corners(c)[[0, 1, 3, 2]], "Z order"),
            (lambda c: pp.order_corners(c)[:, ::-1], "(v, u)"),
            (_sum_difference_trick, "holds for upright rectangles only"),
        ),
        ndarray_only=True,
        teaching=order_corners,
    )
)
