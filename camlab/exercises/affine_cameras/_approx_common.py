"""What lesson 05's two approximations share.

The test cameras, the matrices K E / d0 every mistake is built from, the slips both meet (a wrong
depth d0, K or R misused: the table :data:`COMMON_MISTAKES`) and the measured description of what
differs when no known slip matches.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import camera as cm
from .._core import Mistake, first_mistake

P_INF = "P_inf = K [[r1, t1], [r2, t2], [0, d0]] / d0"


P_PARA = "P_para = K [[r1 - a r3, t1 - a (t3 - d0)], [r2 - b r3, t2 - b (t3 - d0)], [0, d0]] / d0"


# -- shared by the two approximations -----------------------------------------------------------


def approx_cases():
    # X0 well off the optical axis in every case ((a, b) about 0.05 to 0.13): on the axis, any matrix that
    # scales the image about the principal point (a wrong d0, a missing division) would still image X0
    # correctly and slip past, and para-perspective would equal weak perspective.
    return [
        (cm.Camera.look_at([4.0, -3.0, 2.0], [0.0, 0.0, 0.5]), np.array([0.6, 0.3, 1.0])),
        (
            cm.Camera.look_at(
                [-6.0, -8.0, 3.0], [0.5, 0.0, 0.0], K=cm.intrinsic_matrix(1200, 1100, 310, 250)
            ),
            np.array([-0.6, 0.3, -0.7]),
        ),
        (
            cm.Camera(
                cm.intrinsic_matrix(800, 800, 320, 240),
                cm.rotation_from_euler(0.2, 0.1, -0.3),
                [0.1, 0.2, 9.0],
            ),
            np.array([1.0, -0.5, 0.3]),
        ),
        # a skewed K (H&Z's general camera): an answer built from fx, fy, cx, cy alone drops K[0, 1]
        (
            cm.Camera(
                cm.intrinsic_matrix(900, 870, 330, 250, skew=25.0),
                cm.rotation_from_euler(-0.3, 0.2, 0.1),
                [0.3, -0.2, 7.0],
            ),
            np.array([-0.6, 0.8, 0.2]),
        ),
    ]


def p_inf(K, R, t, d0):
    """K [[r1, t1], [r2, t2], [0, d0]] / d0 for any K, R, t, d0 (the mistakes below vary one of them)."""
    return p_para(K, R, t, d0, (0.0, 0.0))


def p_para(K, R, t, d0, ab, t_term=None):
    """K E / d0 with E's rows r_i - ab_i r3 | t_i - ab_i t_term (t_term defaults to t3 - d0)."""
    ab = np.asarray(ab, dtype=float)
    E = np.zeros((3, 4))
    E[:2, :3] = R[:2] - np.outer(ab, R[2])
    E[:2, 3] = t[:2] - ab * (t[2] - d0 if t_term is None else t_term)
    E[2, 3] = d0
    return K @ E / d0


def same_to_rounding(a, b) -> bool:
    """Equal to rounding: a mistake's matrix is recognised only when the answer is exactly it."""
    return bool(np.allclose(a, b, rtol=1e-9, atol=1e-7))


def proportional(a, b) -> bool:
    a, b = np.ravel(a), np.ravel(b)
    k = float(a @ b / (b @ b))
    return bool(k != 0 and np.allclose(a, k * b, rtol=1e-9, atol=1e-9 * np.abs(a).max()))


def depth_and_ab(camera, X0):
    x_c = camera.R @ X0 + camera.t
    return float(x_c[2]), x_c[:2] / x_c[2]


def last_row_cause(g, d0, expected, fix, r3=None, name="P_inf") -> str:
    """Why the last row is not (0, 0, 0, 1).

    ``r3`` is the camera's optical axis, to recognise a kept r3; ``name`` is the exercise's camera,
    P_inf or P_para, as the hint names it.
    """
    if r3 is not None and np.linalg.norm(g[2, :3]) > 1e-9:
        k = float(g[2, :3] @ r3)
        if np.allclose(g[2, :3], k * r3, rtol=1e-6, atol=1e-9):
            return (
                f"the last row still holds r3 (its first three entries are {k:.4g} r3): E's third row must be "
                f"(0, 0, 0, d0), every depth replaced by the constant d0, so set E[2, :3] to 0; {fix}."
            )
    if abs(g[2, 3]) > 1e-12 and np.allclose(g[2, :3], 0.0, atol=1e-9):
        if np.isclose(g[2, 3], 1.0 / d0, rtol=1e-6):
            return (
                f"the last row is (0, 0, 0, 1/d0): the (3, 4) entry of E is the depth d0 = {d0:.4g} m, not 1; "
                f"dividing K E by d0 then makes the last row (0, 0, 0, 1)."
            )
        if same_to_rounding(g / g[2, 3], expected):
            if np.isclose(g[2, 3], -1.0):
                return (
                    "the matrix is minus the answer (last row (0, 0, 0, -1)): the same camera projectively, "
                    "but the prompt fixes the last row to (0, 0, 0, +1); divide by d0 = r3 . X0 + t3, "
                    "which is positive."
                )
            if np.isclose(g[2, 3], d0, rtol=1e-6):
                return (
                    f"you set up K E but did not divide by d0 = {d0:.4g} m: the last row is (0, 0, 0, d0). "
                    f"Projectively it is the same camera (dividing by its third coordinate images every point "
                    f"where {name} does), but the prompt fixes the last row to (0, 0, 0, 1), so that u = M2 X + t2 "
                    f"holds with no division; divide the whole matrix by d0 once: {fix}."
                )
            return (
                f"your matrix is {g[2, 3]:.4g} times the answer: the same camera projectively, but the prompt "
                f"fixes the last row to (0, 0, 0, 1); divide by d0 = r3 . X0 + t3 = {d0:.4g} m, and only once."
            )
        return f"the last row is (0, 0, 0, {g[2, 3]:.4g}): divide the whole matrix by d0 so it is (0, 0, 0, 1)."
    return "the last row must be (0, 0, 0, 1): replace the depth r3 . X + t3 by the constant reference depth d0."


def what_differs(g, expected, camera, X0) -> str:
    """What differs in the top two rows, measured, with no guess at the cause."""
    M, m, M_e, m_e = g[:2, :3], g[:2, 3], expected[:2, :3], expected[:2, 3]
    parts = []
    x_X0 = camera.project(X0)
    got_X0 = M @ X0 + m
    if np.allclose(M, M_e, rtol=1e-7, atol=1e-7):
        parts.append("the 2x3 block is right")
    else:
        k = float(np.sum(M * M_e) / np.sum(M_e * M_e))
        if np.allclose(M, k * M_e, rtol=1e-6, atol=1e-7):
            parts.append(f"the 2x3 block is {k:.6g} times the right one")
        else:
            bad = ~np.isclose(M, M_e, rtol=1e-7, atol=1e-7)
            r, c = np.unravel_index(int(np.argmax(np.abs(M - M_e))), M.shape)
            count = "all 6" if bad.all() else f"{int(bad.sum())} of the 6"
            parts.append(
                f"{count} entries of the 2x3 block differ, most at ({r}, {c}): "
                f"{M[r, c]:.6g} for {M_e[r, c]:.6g}"
            )
    if np.allclose(m, m_e, rtol=1e-7, atol=1e-6):
        parts.append("the last column is right")
    else:
        du, dv = m - m_e
        parts.append(f"the last column is off by ({du:+.4g}, {dv:+.4g}) px")
    where = (
        "it does image X0 where the perspective camera does, but every approximation about X0 must, so that "
        "alone does not make it right"
        if np.allclose(got_X0, x_X0, atol=1e-6)
        else f"it images X0 at ({got_X0[0]:.2f}, {got_X0[1]:.2f}) px, but the perspective camera, and every "
        f"approximation about X0, at ({x_X0[0]:.2f}, {x_X0[1]:.2f}) px"
    )
    return "; ".join(parts) + "; " + where


def v_flip_cause(g, expected) -> str | None:
    """The cause when row 1 (u) is right and row 2 gives c - v for the right v.

    The v axis flipped (y up, -v) or the rows counted from the bottom (479 - v).
    """
    if not (same_to_rounding(g[0], expected[0]) and same_to_rounding(g[1, :3], -expected[1, :3])):
        return None
    c = float(g[1, 3] + expected[1, 3])  # g's v = c - the right v
    how = "-v" if abs(c) < 1e-6 else f"{c:.4g} - v"
    return (
        f"the first row (u) is right, but the second gives {how} instead of v: the v axis is flipped. Pixel v "
        f"is the row index and grows downwards, as the camera frame's y does (x right, y down, z forward: "
        f"docs/conventions.md), so K's second row gives v directly; do not negate it or count rows from the "
        f"bottom of the image."
    )


def image_of_X0_as_translation(g, expected, camera, X0) -> str | None:
    """The cause when M2 is right and the last column is X0's image x_X0.

    A first-order expansion about X0 written as x_X0 + M2 X instead of x_X0 + M2 (X - X0).
    """
    if same_to_rounding(g[:2, :3], expected[:2, :3]) and same_to_rounding(
        g[:2, 3], camera.project(X0)
    ):
        return (
            "the 2x3 block is right, but the last column is X0's image x_X0: the camera maps X0 to M2 X0 + t2, "
            "so t2 = x_X0 - M2 X0 (the expansion is x_X0 + M2 (X - X0))."
        )
    return None


def principal_point_cause(offset, c) -> str | None:
    """The cause when only the last column is off by ``offset`` (pixels) and K's principal point is ``c``."""
    off = f"({offset[0]:+g}, {offset[1]:+g}) px"
    own = f"this camera's principal point is its own K[:2, 2] = ({c[0]:g}, {c[1]:g}): take the whole K from the camera"
    centres = [
        what
        for p, what in (
            ((320.0, 240.0), "(320, 240), half the image size 640 x 480"),
            ((319.5, 239.5), "(319.5, 239.5), the centre of a 640 x 480 image"),
        )
        if not np.allclose(p, c) and np.allclose(offset, np.subtract(p, c), atol=1e-6)
    ]
    steps = np.abs(offset)
    half = bool(
        np.all(np.isclose(steps, 0.5, atol=1e-6) | np.isclose(steps, 0.0, atol=1e-6))
        and steps.max() > 0.25
    )
    one = bool(
        np.all(np.isclose(steps, 1.0, atol=1e-6) | np.isclose(steps, 0.0, atol=1e-6))
        and steps.max() > 0.5
    )
    if centres and half:
        return (
            f"the last column is off by half a pixel, {off}: either 0.5 was added or taken, or you used "
            f"{centres[0]} as the principal point; {own} (pixel centres are at integers, docs/conventions.md, "
            f"so no 0.5 belongs in it)."
        )
    if centres:
        return (
            f"the last column is off by {off}: you used {centres[0]} as the principal point; {own}."
        )
    if half:
        return (
            f"the last column is off by half a pixel, {off}: K's principal point is used as it is (pixel "
            f"centres are at integers, docs/conventions.md), with no 0.5 added or taken."
        )
    if one:
        return (
            f"the last column is off by one pixel, {off}: pixels count from 0 in this course, so no 1 "
            f"belongs in it (a 1-based index?)."
        )
    return None


def common_context(camera, X0, fix=""):
    """What the rows of :data:`COMMON_MISTAKES` read: the camera, X0, its depth d0 and the exercise's formula."""
    K, R, t = camera.K, camera.R, camera.t
    return SimpleNamespace(camera=camera, X0=X0, K=K, R=R, t=t, d0=float(R[2] @ X0 + t[2]), fix=fix)


def common_slip(name, formula):
    """The shared slip ``name`` (a row of :data:`COMMON_MISTAKES`) as a student's function.

    Parameters
    ----------
    name : str
        The row's name.
    formula : callable
        ``formula(camera, X0, K, R, t, d0)``: the exercise's camera built from the parts the
        slip may have changed (its row's answer replaces some of K, R, t and d0).

    Returns
    -------
    callable
        ``wrong(camera, X0)``, the 3x4 camera a student with that slip returns.
    """
    [row] = [m for m in COMMON_MISTAKES if m.name == name]

    def wrong(camera, X0):
        context = common_context(camera, X0)
        kw = {
            "K": context.K,
            "R": context.R,
            "t": context.t,
            "d0": context.d0,
            **(row.answer(context) or {}),  # None: the slip changes nothing here
        }
        return formula(camera, X0, **kw)

    return wrong


def nearly_right_cause(g, expected, fix) -> str | None:
    """The cause when every entry is near the answer but not within the exercise's 1e-7.

    Every entry is within 1e-4 (relative, or absolute near 0): the form is right and only the digits
    are off (rounded numbers, float32, a truncated constant), so no slip of the formula should be
    named.
    """
    if not np.allclose(g, expected, rtol=1e-4, atol=1e-4):
        return None
    gap = float(np.abs(g - expected).max())
    return (
        f"every entry is within {gap:.1g} of the answer, so the formula is right, but the check asks for "
        f"1e-7 (relative): were numbers rounded, or typed in from a printout? Compute {fix} from camera.K, "
        f"camera.R, camera.t and X0 directly, without rounding."
    )


def swapped(K, *pairs):
    """K with each ((row, col), (row, col)) pair of entries exchanged (fx <-> fy, cx <-> cy)."""
    K = np.array(K, dtype=float)
    for a, b in pairs:
        K[a], K[b] = K[b], K[a]
    return K


def square_pixels(K):
    """K with fy replaced by fx: the square-pixel slip."""
    K = np.array(K, dtype=float)
    K[1, 1] = K[0, 0]
    return K


COMMON_MISTAKES = (
    Mistake(
        "d0 = t3",
        lambda s: dict(d0=s.t[2]),
        "you used d0 = t3, the depth of the world origin; use the depth of the reference "
        "point, d0 = r3 . X0 + t3.",
    ),
    Mistake(
        "d0 lacks t3",
        lambda s: dict(d0=s.R[2] @ s.X0),
        "d0 lacks t3: the depth of X0 in the camera frame is r3 . X0 + t3.",
    ),
    Mistake(
        "d0 = r3 . X0 - t3",
        lambda s: dict(d0=s.R[2] @ s.X0 - s.t[2]),
        "t3 has the wrong sign in d0: X_cam = R X + t adds t, so d0 = r3 . X0 + t3.",
    ),
    Mistake(
        "d0 = world z",
        lambda s: dict(d0=s.X0[2]),
        "you used X0's world z as d0; the depth is measured along the camera's optical axis: "
        "d0 = r3 . X0 + t3.",
    ),
    Mistake(
        "d0 = distance",
        lambda s: dict(d0=np.linalg.norm(s.X0 - s.camera.centre)),
        "you used the Euclidean distance from the camera centre as "
        "d0; the depth is along the optical axis: d0 = r3 . X0 + t3.",
    ),
    Mistake(
        "d0 = |t|",
        lambda s: dict(d0=np.linalg.norm(s.t)),
        "you used |t| as d0, which equals |C|, the camera's distance from the world "
        "origin; the depth of X0 is d0 = r3 . X0 + t3.",
    ),
    Mistake(
        "d0 = -d0",
        lambda s: dict(d0=-s.d0),
        "d0 has the wrong sign: a point in front of the camera has positive depth r3 . X0 + t3.",
    ),
    Mistake(
        "no K",
        lambda s: dict(K=np.eye(3)),
        lambda s: (
            f"you left out K, so the matrix gives normalised coordinates, not pixels: {s.fix}."
        ),
    ),
    Mistake(
        "K^-1",
        lambda s: dict(K=np.linalg.inv(s.K)),
        lambda s: (
            f"you used K^-1: K maps normalised camera coordinates to pixels, so the camera "
            f"is K times E, not K^-1 times E; {s.fix}."
        ),
    ),
    Mistake(
        "no principal point",
        lambda s: dict(K=np.diag([s.K[0, 0], s.K[1, 1], 1.0])),
        lambda s: (
            "the principal point is missing: keep the whole K (its third column (cx, cy, 1) "
            f"multiplies the depth d0 in every row), {s.fix}."
        ),
    ),
    Mistake(
        "K.T",
        lambda s: dict(K=s.K.T),
        lambda s: (
            f"you used K.T: K is upper triangular, with the principal point in its last column; "
            f"{s.fix}."
        ),
    ),
    Mistake(
        "R.T",
        lambda s: dict(R=s.R.T),
        "you used R.T (the columns of R): r1, r2, r3 are the rows of R, R[0], R[1], R[2].",
    ),
    Mistake(
        "R.T, in d0 too",
        lambda s: dict(R=s.R.T, d0=s.R.T[2] @ s.X0 + s.t[2]),
        "you used R.T (the columns of R): r1, r2, r3 are the rows of R, R[0], R[1], R[2].",
    ),
    Mistake(
        "t1, t2 sign",
        lambda s: dict(t=s.t * [-1.0, -1.0, 1.0]),
        "t1 and t2 have the wrong sign: X_cam = R X + t, so E's last column holds +t1 and +t2.",
    ),
    Mistake(
        "t in millimetres",
        lambda s: dict(t=1000 * s.t, d0=1000 * s.d0),
        "t and d0 are in millimetres while R X is in metres: this is the camera "
        "for world points in millimetres. Keep t and X0 in metres, as the "
        "camera and the exercise give them.",
    ),
    Mistake(
        "no skew",
        lambda s: dict(K=without_skew(s.K)) if s.K[0, 1] else None,
        lambda s: (
            f"the skew K[0, 1] is missing (this camera's is {s.K[0, 1]:g} px): build the matrix "
            f"from the whole K, not from fx, fy, cx and cy alone: {s.fix}."
        ),
    ),
    Mistake(
        "fx for both focal lengths",
        lambda s: dict(K=square_pixels(s.K)),  # the right answer where fy = fx
        lambda s: (
            f"the second row is scaled by fx = {s.K[0, 0]:g} px where this camera's fy = {s.K[1, 1]:g} px: "
            f"pixels need not be square, so use all of K (K[1, 1] for v): {s.fix}."
        ),
    ),
    Mistake(
        "fx and fy swapped",
        lambda s: dict(K=swapped(s.K, ((0, 0), (1, 1)))) if s.K[0, 0] != s.K[1, 1] else None,
        lambda s: (
            f"fx and fy are swapped: u is scaled by {s.K[1, 1]:g} px and v by {s.K[0, 0]:g} px, but this "
            f"camera's fx = K[0, 0] = {s.K[0, 0]:g} px scales u (the image width direction) and "
            f"fy = K[1, 1] = {s.K[1, 1]:g} px scales v (the height); use K as it is: {s.fix}."
        ),
    ),
    Mistake(
        "cx and cy swapped",
        lambda s: dict(K=swapped(s.K, ((0, 2), (1, 2)))) if s.K[0, 2] != s.K[1, 2] else None,
        lambda s: (
            f"cx and cy are swapped: the last column is off by ({s.K[1, 2] - s.K[0, 2]:+g}, "
            f"{s.K[0, 2] - s.K[1, 2]:+g}) px, which is (cy - cx, cx - cy). The principal point is "
            f"(cx, cy) = (K[0, 2], K[1, 2]) = ({s.K[0, 2]:g}, {s.K[1, 2]:g}): cx is along u (the width), "
            f"cy along v (the height); use K as it is: {s.fix}."
        ),
    ),
    Mistake(
        "fx, fy and cx, cy swapped",
        lambda s: (
            dict(K=swapped(s.K, ((0, 0), (1, 1)), ((0, 2), (1, 2))))
            if s.K[0, 0] != s.K[1, 1] and s.K[0, 2] != s.K[1, 2]
            else None
        ),
        lambda s: (
            f"width and height are swapped throughout K: u gets fy = {s.K[1, 1]:g} px and cy = {s.K[1, 2]:g} px, "
            f"v gets fx = {s.K[0, 0]:g} px and cx = {s.K[0, 2]:g} px. K's first row (fx, skew, cx) belongs "
            f"to u, the width direction, its second (0, fy, cy) to v; use K as it is: {s.fix}."
        ),
    ),
    Mistake(
        "d0 = world z of X0 - C",
        lambda s: dict(d0=(s.X0 - s.camera.centre)[2]),
        lambda s: (
            f"you used the world z of X0 - C (here {(s.X0 - s.camera.centre)[2]:.4g} m) as d0: "
            f"the world's z axis is not the camera's. The depth is measured along the optical axis r3: "
            f"d0 = r3 . (X0 - C) = r3 . X0 + t3 = {s.d0:.4g} m."
        ),
    ),
    Mistake(
        "t sign everywhere",
        lambda s: dict(t=-s.t, d0=s.R[2] @ s.X0 - s.t[2]),
        "t has the wrong sign everywhere (in E's last column and in d0): "
        "camlab's extrinsics are X_cam = R X + t, so E holds +t1, +t2 and "
        "d0 = r3 . X0 + t3.",
    ),
    Mistake(
        "t as the centre",
        lambda s: dict(t=-s.R @ s.t, d0=s.R[2] @ (s.X0 - s.t)),
        "you used t as the camera centre, X_cam = R (X - t): camlab's t is "
        "the translation of X_cam = R X + t (the centre is C = -R^T t, "
        "camera.centre), so E holds t1, t2 as they are and d0 = r3 . X0 + t3.",
    ),
)
"""The slips both approximations share, each as the change it makes to (K, R, t, d0) in K E / d0."""


def match_mistake(g, camera, X0, ab_of, fix) -> str | None:
    """The cause of the first shared slip whose matrix ``g`` equals; ``ab_of(d0)`` gives (a, b) for a depth.

    A slip that changes d0 is tried with (a, b) for the right depth and for its own (the student may
    have used the wrong d0 in one place or in both).
    """
    s = common_context(camera, X0, fix)

    def shows(got, change):
        kw = {"K": s.K, "R": s.R, "t": s.t, "d0": s.d0, **change}
        if abs(kw["d0"]) < 1e-12:
            return False
        abs_tried = [ab_of(s.d0), ab_of(kw["d0"])] if "d0" in change else [ab_of(kw["d0"])]
        if np.any(ab_of(1.0)) and {"R", "t"} & change.keys():  # para-perspective only
            # the slip made in (a, b) too: x_c = R X0 + t with the slipped R or t, over the (slipped) d0
            x_c = np.asarray(kw["R"]) @ np.asarray(s.X0, dtype=float) + np.asarray(kw["t"])
            abs_tried.append(x_c[:2] / kw["d0"])
        return any(
            same_to_rounding(got, p_para(kw["K"], kw["R"], kw["t"], kw["d0"], ab))
            for ab in abs_tried
        )

    return first_mistake(COMMON_MISTAKES, s, g, shows)


def transposed_cause(got, expected) -> str | None:
    """A hint when ``got`` is the expected (3, 4) matrix transposed, else None."""
    try:
        g = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        return None
    if g.shape == expected.shape[::-1] and np.allclose(g.T, expected, rtol=1e-6, atol=1e-9):
        return (
            f"your array is the right matrix transposed (shape {g.shape}, expected {expected.shape}): "
            "build it from rows (np.vstack of its three rows), and drop any final .T"
        )
    return None


def without_skew(K):
    K = K.copy()
    K[0, 1] = 0.0
    return K
