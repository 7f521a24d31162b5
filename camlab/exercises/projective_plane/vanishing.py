"""Lesson 06, exercise 3: a vanishing point from two image segments."""

from __future__ import annotations

import numpy as np

from ... import projective
from .._answers import same_up_to_scale
from .._core import Exercise, register_exercise
from .lines import PIXEL_SHIFTS, homogeneous_point_diagnosis, silenced, solve_hint


def _vanishing_cases():
    # Two images of parallel edges: segments [[u1, v1], [u2, v2]] in pixels (not the worked example's rails).
    return [
        (np.array([[[120.0, 470.0], [250.0, 260.0]], [[600.0, 455.0], [420.0, 250.0]]]),),
        (np.array([[[0.0, 300.0], [640.0, 260.0]], [[0.0, 420.0], [640.0, 330.0]]]),),
        (np.array([[[10.0, 10.0], [110.0, 60.0]], [[10.0, 110.0], [110.0, 160.0]]]),),  # parallel
    ]


def _conditionings(segments):
    """Similarities T (centre, then scale) a student may condition the endpoints with, by name."""
    pts = np.asarray(segments, dtype=float).reshape(-1, 2)
    centre = pts.mean(axis=0)
    spread = {
        "mean distance sqrt(2)": np.sqrt(2) / np.linalg.norm(pts - centre, axis=1).mean(),
        "unit mean distance": 1 / np.linalg.norm(pts - centre, axis=1).mean(),
        "unit standard deviation": 1 / (pts - centre).std(),
        "largest |coordinate| 1": 1 / np.abs(pts - centre).max(),
        "centring only": 1.0,
    }
    return [
        np.array([[k, 0, -k * centre[0]], [0, k, -k * centre[1]], [0, 0, 1]])
        for k in spread.values()
    ]


def _translate_then_scale(T):
    """(S, T_t) with T = S @ T_t: the scale k and the translation by -c of a conditioning T.

    T x = k (x - c), so T_t moves by -c = T[:2, 2] / k and S scales by k. Undoing them in the
    wrong order, inv(S) @ inv(T_t) @ x_c, is the slip x = (x_c + c) / k.
    """
    k = T[0, 0]
    S = np.diag([k, k, 1.0])
    T_t = np.array([[1.0, 0.0, T[0, 2] / k], [0.0, 1.0, T[1, 2] / k], [0.0, 0.0, 1.0]])
    return S, T_t


def _undone_in_wrong_order(s):
    """The slip inv(S) @ inv(T_t) @ x_c for x_c = T x, T = S @ T_t (the reverse order is right)."""
    T = _conditionings(s)[0]
    S, T_t = _translate_then_scale(T)
    return np.linalg.inv(S) @ np.linalg.inv(T_t) @ T @ projective.vanishing_point(s)


def _hartley_undone_as_scale_after_shift(s):
    """A student's slip written out by hand: centre on c, scale by k (mean distance sqrt 2), then x = (x_c + c) / k."""
    pts = np.asarray(s, dtype=float).reshape(-1, 2)
    c = pts.mean(axis=0)
    k = np.sqrt(2) / np.linalg.norm(pts - c, axis=1).mean()
    q = np.column_stack([k * (pts - c), np.ones(len(pts))]).reshape(2, 2, 3)
    x_c = np.cross(np.cross(q[0, 0], q[0, 1]), np.cross(q[1, 0], q[1, 1]))
    return np.append((x_c[:2] / x_c[2] + c) / k, 1.0)


def _scaled_about_a_centre(segments, got, e) -> bool:
    """True when ``got`` is k (e - c) for some scale k and a centre c a student may condition with.

    Catches a conditioning (any scale k, centred on the endpoints' mean, their bounding box, the
    image centre, or not centred) that was not undone, whatever scale the student chose.
    """
    g = np.asarray(got, dtype=float)
    if (
        not (np.any(g) and np.any(e))
        or min(abs(g[2]) / np.linalg.norm(g), abs(e[2]) / np.linalg.norm(e)) < 1e-12
    ):
        return False  # an ideal point: a similarity keeps it ideal, and says nothing here
    pts = np.asarray(segments, dtype=float).reshape(-1, 2)
    g2, e2 = g[:2] / g[2], e[:2] / e[2]
    for c in (
        pts.mean(axis=0),
        (pts.min(axis=0) + pts.max(axis=0)) / 2,
        np.zeros(2),
        np.array([319.5, 239.5]),
    ):
        d = e2 - c
        k = (g2 @ d) / (d @ d) if d @ d > 0 else 0.0
        moved = abs(k - 1) > 1e-6 or np.any(c != 0)
        if (
            moved
            and abs(k) > 1e-12
            and np.linalg.norm(g2 - k * d) < 1e-7 * max(np.linalg.norm(g2), 1e-9)
        ):
            return True
    return False


def _conditioning_slip(segments, got, expected) -> str | None:
    """The hint when ``got`` is the vanishing point in conditioned coordinates, or undone wrongly."""
    e = np.asarray(expected, dtype=float)
    g = np.asarray(got, dtype=float)
    if not np.any(g[:2]) and g[2] != 0:
        return (
            "your point is (0, 0, w), the origin: did you cross the two segments' directions (d, 0)? Two "
            "directions are two ideal points, and their cross product is the line at infinity, read as a "
            "point. Join each segment's endpoints to a line first, then meet the two lines"
        )
    for T in _conditionings(segments):
        if same_up_to_scale(got, T @ e):
            return (
                "your point is the right one in conditioned coordinates (x_c = T x): the conditioning was not "
                "undone. Map it back with x = inv(T) @ x_c (lines, if you condition them, move by inv(T).T)"
            )
        for wrong, how in ((T.T @ T @ e, "T.T"), (T @ T @ e, "T again")):
            if same_up_to_scale(got, wrong):
                return (
                    f"you undid the conditioning with {how} instead of its inverse: the point in conditioned "
                    "coordinates is x_c = T x, so x = inv(T) @ x_c"
                )
        S, T_t = _translate_then_scale(T)  # T = S @ T_t: translate, then scale
        if T[0, 0] != 1 and same_up_to_scale(got, np.linalg.inv(S) @ np.linalg.inv(T_t) @ T @ e):
            return (
                "you undid the conditioning in the wrong order: T = S @ T_t (translate, then scale), so "
                "inv(T) = inv(T_t) @ inv(S): undo the scale first, then the translation"
            )
        if same_up_to_scale(got, np.linalg.inv(T).T @ T @ e):
            return (
                "you undid the conditioning with inv(T).T, the rule that moves *lines*; your result is a "
                "point, and points move back by inv(T) itself: x = inv(T) @ x_c"
            )
    if _scaled_about_a_centre(segments, got, e):
        return (
            "your point is the right one scaled about a centre (k (x - c)): conditioned coordinates "
            "(x_c = T x), the conditioning was not undone. Map it back with x = inv(T) @ x_c"
        )
    return None


def _vanishing_diagnosis(args, got, expected) -> str:
    (segments,) = args
    swapped = np.asarray(segments, dtype=float)[..., ::-1]
    if np.shape(got) == (3,) and same_up_to_scale(got, vanishing_point(swapped)):
        return (
            "you swapped the coordinates: your point is the vanishing point of the segments with (u, v) read "
            "as (v, u). A pixel (u, v) = (column, row) lifts to (u, v, 1)."
        )
    transposed = np.asarray(segments, dtype=float).transpose(1, 0, 2)
    if np.shape(got) == (3,) and same_up_to_scale(got, vanishing_point(transposed)):
        return (
            "you read the segments along the wrong axis: segments[:, k] (the k-th endpoint of every "
            "segment) where segments[k] (segment k, both endpoints) belongs. The axes are (segment, "
            "endpoint, coordinate): join segments[k][0] and segments[k][1] for each k, then meet the lines."
        )
    if np.shape(got) == (3,) and np.isfinite(np.asarray(got, dtype=float)).all():
        slip = _conditioning_slip(segments, np.asarray(got, dtype=float), expected)
        if slip:
            return slip
        seg = np.asarray(segments, dtype=float)
        for moved, why in (
            *(
                (seg + d, f"shifted by ({d[0]:+g}, {d[1]:+g}) px in (u, v): {w}")
                for d, w in PIXEL_SHIFTS
            ),
            (seg * [1.0, -1.0], "with v negated: a y flip (y up instead of the image's v down)"),
            (seg * [-1.0, 1.0] + [639.0, 0.0], "flipped left to right, u -> 639 - u"),
            (
                seg * [1.0, -1.0] + [0.0, 639.0],
                "flipped upside down with v -> 639 - v: width and height swapped (the image is 640 wide, "
                "480 tall; the last row is v = 479)",
            ),
            (
                seg * [-1.0, 1.0] + [479.0, 0.0],
                "flipped left to right with u -> 479 - u: width and height swapped (the image is 640 wide, "
                "480 tall; the last column is u = 639)",
            ),
            (
                seg * [1.0, -1.0] + [0.0, 479.0],
                "flipped upside down, v -> 479 - v: a y flip (y up instead of the image's v down)",
            ),
        ):
            if same_up_to_scale(got, vanishing_point(moved)):
                return (
                    f"your point is the vanishing point of the segments {why}"
                    + (" " if why.endswith("?") else ". ")
                    + "Use the endpoints as given: "
                    "(u, v) lifts to (u, v, 1)."
                )
    lines = [projective.join(s[0], s[1]) for s in segments]
    return homogeneous_point_diagnosis(
        got,
        expected,
        lines,
        "Make one line per segment (join its two endpoints), then intersect the two lines. If you "
        "conditioned the endpoints (x_c = T x), undo it at the end: x = inv(T) @ x_c.",
    )


def _cross_2d_twice(s):
    """The slip np.cross(np.cross(a1, b1), np.cross(a2, b2)) on raw 2-vectors: numpy raises on the scalars."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        return np.cross(np.cross(s[0, 0], s[0, 1]), np.cross(s[1, 0], s[1, 1]))


def _vanishing_exception_hint(exc: Exception, args) -> str:
    (segments,) = args
    lines = [projective.join(s[0], s[1]) for s in segments]
    if isinstance(exc, ValueError) and "zero dimension" in str(exc):
        return (
            "np.cross of two 2-vectors gives a number, not a line, and a second np.cross of those numbers "
            "fails. Lift each endpoint to (u, v, 1) before joining: np.cross(np.append(a, 1.0), "
            "np.append(b, 1.0))"
        )
    return solve_hint(exc, lines)


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
            (  # conditioned by 1/640 without centring, never undone
                lambda s: projective.vanishing_point(np.asarray(s, dtype=float) / 640.0),
                "conditioning was not undone",
            ),
            (  # centred, largest distance sqrt(2), never undone
                lambda s: projective.vanishing_point(
                    (s - s.reshape(-1, 2).mean(axis=0))
                    * np.sqrt(2)
                    / np.linalg.norm(s.reshape(-1, 2) - s.reshape(-1, 2).mean(axis=0), axis=1).max()
                ),
                "conditioning was not undone",
            ),
            (
                lambda s: np.cross(
                    np.append(s[0, 1] - s[0, 0], 0.0), np.append(s[1, 1] - s[1, 0], 0.0)
                ),
                "segments' directions",
            ),
            # Joins the two segments' start points instead of each segment's endpoints.
            (
                lambda s: np.cross(
                    np.cross([*s[0, 0], 1], [*s[1, 0], 1]), np.cross([*s[0, 1], 1], [*s[1, 1], 1])
                ),
                "wrong axis",
            ),
            (
                lambda s: projective.from_homogeneous(projective.vanishing_point(s)),
                "homogeneous 3-vector",
            ),
            (
                lambda s: projective.vanishing_point(np.asarray(s)[..., ::-1]),
                "swapped the coordinates",
            ),
            (
                lambda s: _conditionings(s)[0] @ projective.vanishing_point(s),
                "not undone",
            ),
            (
                lambda s: (
                    _conditionings(s)[0].T @ _conditionings(s)[0] @ projective.vanishing_point(s)
                ),
                "instead of its inverse",
            ),
            (
                silenced(
                    lambda s: projective.vanishing_point(s) / projective.vanishing_point(s)[2]
                ),
                "lines are parallel",
            ),
            (_cross_2d_twice, "np.cross of two 2-vectors"),
            (lambda s: projective.vanishing_point(np.asarray(s) + 0.5), "half-pixel"),
            (lambda s: projective.vanishing_point(np.asarray(s) * [1.0, -1.0]), "y flip"),
            (
                lambda s: projective.vanishing_point(np.asarray(s) * [1.0, -1.0] + [0.0, 479.0]),
                "479 - v",
            ),
            (lambda s: projective.vanishing_point(np.asarray(s) - 1.0), "(-1, -1) px"),
            (lambda s: projective.vanishing_point(np.asarray(s) + [0.5, 0.0]), "on one axis"),
            (
                lambda s: projective.vanishing_point(np.asarray(s) * [-1.0, 1.0] + [639, 0]),
                "639 - u",
            ),
            (lambda s: np.zeros(3), "(0, 0, 0)"),
            (_undone_in_wrong_order, "wrong order"),
            (_hartley_undone_as_scale_after_shift, "wrong order"),
            (
                lambda s: projective.vanishing_point(np.asarray(s).transpose(1, 0, 2)),
                "wrong axis",
            ),
            (
                lambda s: projective.vanishing_point(np.asarray(s) * [1.0, -1.0] + [0.0, 639.0]),
                "width and height swapped",
            ),
            (
                lambda s: (
                    np.linalg.inv(_conditionings(s)[0]).T
                    @ _conditionings(s)[0]
                    @ projective.vanishing_point(s)
                ),
                "moves *lines*",
            ),
        ),
        exception_hint=_vanishing_exception_hint,
        teaching=vanishing_point,
    )
)
