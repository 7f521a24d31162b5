"""Lesson 05's first two exercises: the weak-perspective (P_inf) and para-perspective approximations
of a perspective camera about a reference point X0 (see the package docstring)."""

from __future__ import annotations

import numpy as np

from ... import affine as af
from ... import camera as cm
from .._answers import same_array, shape_problem
from .._core import Exercise, register_exercise

_P_INF = "P_inf = K [[r1, t1], [r2, t2], [0, d0]] / d0"
_P_PARA = "P_para = K [[r1 - a r3, t1 - a (t3 - d0)], [r2 - b r3, t2 - b (t3 - d0)], [0, d0]] / d0"


# -- shared by the two approximations -----------------------------------------------------------


def _approx_cases():
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


def _p_inf(K, R, t, d0):
    """K [[r1, t1], [r2, t2], [0, d0]] / d0 for any K, R, t, d0 (the mistakes below vary one of them)."""
    return _p_para(K, R, t, d0, (0.0, 0.0))


def _p_para(K, R, t, d0, ab, t_term=None):
    """K E / d0 with E's rows r_i - ab_i r3 | t_i - ab_i t_term (t_term defaults to t3 - d0)."""
    ab = np.asarray(ab, dtype=float)
    E = np.zeros((3, 4))
    E[:2, :3] = R[:2] - np.outer(ab, R[2])
    E[:2, 3] = t[:2] - ab * (t[2] - d0 if t_term is None else t_term)
    E[2, 3] = d0
    return K @ E / d0


def _same(a, b) -> bool:
    """Equal to rounding: a mistake's matrix is recognised only when the answer is exactly it."""
    return bool(np.allclose(a, b, rtol=1e-9, atol=1e-7))


def _same_up_to_scale(a, b) -> bool:
    a, b = np.ravel(a), np.ravel(b)
    k = float(a @ b / (b @ b))
    return bool(k != 0 and np.allclose(a, k * b, rtol=1e-9, atol=1e-9 * np.abs(a).max()))


def _depth_and_ab(camera, X0):
    x_c = camera.R @ X0 + camera.t
    return float(x_c[2]), x_c[:2] / x_c[2]


def _last_row_cause(g, d0, expected, fix, r3=None) -> str:
    """Why the last row is not (0, 0, 0, 1) (``r3``: the camera's optical axis, to recognise a kept r3)."""
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
        if _same(g / g[2, 3], expected):
            if np.isclose(g[2, 3], -1.0):
                return (
                    "the matrix is minus the answer (last row (0, 0, 0, -1)): the same camera projectively, "
                    "but the prompt fixes the last row to (0, 0, 0, +1); divide by d0 = r3 . X0 + t3, "
                    "which is positive."
                )
            if np.isclose(g[2, 3], d0, rtol=1e-6):
                return (
                    f"you set up K E but did not divide by d0 = {d0:.4g} m: the last row is (0, 0, 0, d0) "
                    f"and the image d0 times too large about the origin; divide the whole matrix: {fix}."
                )
            return (
                f"your matrix is {g[2, 3]:.4g} times the answer: the same camera projectively, but the prompt "
                f"fixes the last row to (0, 0, 0, 1); divide by d0 = r3 . X0 + t3 = {d0:.4g} m, and only once."
            )
        return f"the last row is (0, 0, 0, {g[2, 3]:.4g}): divide the whole matrix by d0 so it is (0, 0, 0, 1)."
    return "the last row must be (0, 0, 0, 1): replace the depth r3 . X + t3 by the constant reference depth d0."


def _what_differs(g, expected, camera, X0) -> str:
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


def _image_of_X0_as_translation(g, expected, camera, X0) -> str | None:
    """The cause when M2 is right and the last column is X0's image x_X0 (a first-order expansion about X0
    written as x_X0 + M2 X instead of x_X0 + M2 (X - X0))."""
    if _same(g[:2, :3], expected[:2, :3]) and _same(g[:2, 3], camera.project(X0)):
        return (
            "the 2x3 block is right, but the last column is X0's image x_X0: the camera maps X0 to M2 X0 + t2, "
            "so t2 = x_X0 - M2 X0 (the expansion is x_X0 + M2 (X - X0))."
        )
    return None


def _principal_point_cause(offset, c) -> str | None:
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


def _common_mistakes(camera, X0, fix):
    """(matrix, cause) for the slips both approximations share, built with ``_p_para`` at X0's (a, b)
    (zero for weak perspective is passed in by the caller as ``ab``)."""
    K, R, t = camera.K, camera.R, camera.t
    d0 = float(R[2] @ X0 + t[2])
    K_no_skew = K.copy()
    K_no_skew[0, 1] = 0.0
    return [
        (
            dict(d0=t[2]),
            "you used d0 = t3, the depth of the world origin; use the depth of the reference "
            "point, d0 = r3 . X0 + t3.",
        ),
        (dict(d0=R[2] @ X0), "d0 lacks t3: the depth of X0 in the camera frame is r3 . X0 + t3."),
        (
            dict(d0=R[2] @ X0 - t[2]),
            "t3 has the wrong sign in d0: X_cam = R X + t adds t, so d0 = r3 . X0 + t3.",
        ),
        (
            dict(d0=X0[2]),
            "you used X0's world z as d0; the depth is measured along the camera's optical axis: "
            "d0 = r3 . X0 + t3.",
        ),
        (
            dict(d0=np.linalg.norm(X0 - camera.centre)),
            "you used the Euclidean distance from the camera centre as "
            "d0; the depth is along the optical axis: d0 = r3 . X0 + t3.",
        ),
        (
            dict(d0=np.linalg.norm(t)),
            "you used |t| as d0, which equals |C|, the camera's distance from the world "
            "origin; the depth of X0 is d0 = r3 . X0 + t3.",
        ),
        (
            dict(d0=-d0),
            "d0 has the wrong sign: a point in front of the camera has positive depth r3 . X0 + t3.",
        ),
        (
            dict(K=np.eye(3)),
            f"you left out K, so the matrix gives normalised coordinates, not pixels: {fix}.",
        ),
        (
            dict(K=np.linalg.inv(K)),
            f"you used K^-1: K maps normalised camera coordinates to pixels, so the camera "
            f"is K times E, not K^-1 times E; {fix}.",
        ),
        (
            dict(K=np.diag([K[0, 0], K[1, 1], 1.0])),
            "the principal point is missing: keep the whole K (its third column (cx, cy, 1) multiplies the depth "
            f"d0 in every row), {fix}.",
        ),
        (
            dict(K=K.T),
            f"you used K.T: K is upper triangular, with the principal point in its last column; {fix}.",
        ),
        (
            dict(R=R.T),
            "you used R.T (the columns of R): r1, r2, r3 are the rows of R, R[0], R[1], R[2].",
        ),
        (
            dict(R=R.T, d0=R.T[2] @ X0 + t[2]),
            "you used R.T (the columns of R): r1, r2, r3 are the rows of R, R[0], R[1], R[2].",
        ),
        (
            dict(t=t * [-1.0, -1.0, 1.0]),
            "t1 and t2 have the wrong sign: X_cam = R X + t, so E's last column holds +t1 and +t2.",
        ),
        (
            dict(t=1000 * t, d0=1000 * d0),
            "t and d0 are in millimetres while R X is in metres: this is the camera "
            "for world points in millimetres. Keep t and X0 in metres, as the "
            "camera and the exercise give them.",
        ),
        (
            dict(K=K_no_skew if K[0, 1] else np.full((3, 3), np.nan)),
            f"the skew K[0, 1] is missing (this camera's is {K[0, 1]:g} px): build the matrix from "
            f"the whole K, not from fx, fy, cx and cy alone: {fix}.",
        ),
        (
            dict(d0=(X0 - camera.centre)[2]),
            f"you used the world z of X0 - C (here {(X0 - camera.centre)[2]:.4g} m) as d0: the world's z axis is not "
            f"the camera's. The depth is measured along the optical axis r3: d0 = r3 . (X0 - C) = r3 . X0 + t3 "
            f"= {d0:.4g} m.",
        ),
        (
            dict(t=-t, d0=R[2] @ X0 - t[2]),
            "t has the wrong sign everywhere (in E's last column and in d0): "
            "camlab's extrinsics are X_cam = R X + t, so E holds +t1, +t2 and "
            "d0 = r3 . X0 + t3.",
        ),
        (
            dict(t=-R @ t, d0=R[2] @ (X0 - t)),
            "you used t as the camera centre, X_cam = R (X - t): camlab's t is "
            "the translation of X_cam = R X + t (the centre is C = -R^T t, "
            "camera.centre), so E holds t1, t2 as they are and d0 = r3 . X0 + t3.",
        ),
    ]


def _match_mistake(g, camera, X0, ab_of, fix) -> str | None:
    """The cause of the first shared slip whose matrix ``g`` equals; ``ab_of(d0)`` gives (a, b) for a depth."""
    K, R, t = camera.K, camera.R, camera.t
    d0 = float(R[2] @ X0 + t[2])
    for change, cause in _common_mistakes(camera, X0, fix):
        kw = {"K": K, "R": R, "t": t, "d0": d0, **change}
        if abs(kw["d0"]) < 1e-12:
            continue
        for ab in {0: [ab_of(kw["d0"])], 1: [ab_of(d0), ab_of(kw["d0"])]}[int("d0" in change)]:
            if _same(g, _p_para(kw["K"], kw["R"], kw["t"], kw["d0"], ab)):
                return cause
    return None


# -- affine_approximation (P_inf, weak perspective) ------------------------------------------------


def _approx_specific(camera, X0):
    """(matrix, cause) for mistakes only this exercise meets."""
    K, R, t = camera.K, camera.R, camera.t
    d0 = R[2] @ X0 + t[2]
    only_row3 = camera.P / d0
    only_row3[2] = [0.0, 0.0, 0.0, 1.0]
    no_division = _p_inf(K, R, t, d0) * d0
    no_division[2] = [0.0, 0.0, 0.0, 1.0]
    last_column_undivided = _p_inf(K, R, t, d0)
    last_column_undivided[:2, 3] *= d0
    X0_mm = 1000 * np.asarray(X0, dtype=float)
    return [
        (
            last_column_undivided,
            "the 2x3 block is right, but the last column is K (t1, t2, d0) undivided: divide "
            f"all of K E by d0, its last column too: that column is K (t1, t2, d0) / d0; {_P_INF}.",
        ),
        (
            only_row3,
            "you replaced only P's third row: P's first two rows also hold the depth, through K's third "
            f"column times r3 . X + t3. Replace the depth inside [R | t] before K multiplies: {_P_INF}.",
        ),
        (
            no_division,
            "you set the last row to (0, 0, 0, 1) but did not divide the top two rows by d0, so the image "
            f"is d0 times too large about the origin: divide the whole matrix, {_P_INF}.",
        ),
        (
            _p_inf(K, R, t, d0) - np.c_[np.zeros((3, 3)), np.r_[K[:2, 2], 0.0]] * (d0 - 1) / d0,
            "the principal point is divided by d0: in K [[r1, t1], [r2, t2], [0, d0]] the (3, 4) entry is d0, so after "
            f"dividing by d0 K's third column (cx, cy) is added as it is; {_P_INF}.",
        ),
        (
            af.paraperspective_approximation(camera, X0),
            "this is the para-perspective camera (section 2, the next exercise), which projects along the line of "
            f"sight to X0; this exercise asks for P_inf, every depth replaced by d0 with no r3 terms in M2: {_P_INF}.",
        ),
        (
            _p_inf(K, R, t, R[2] @ X0_mm + t[2]),
            f"X0 was scaled by 1000 (millimetres?): its depth came out as r3 . (1000 X0) + t3 = {R[2] @ X0_mm + t[2]:.4g} "
            f"m where X0 is {d0:.4g} m deep. The camera's t and X0 are both in metres; use X0 as given: {_P_INF}.",
        ),
    ]


def _approx_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return the 3x4 affine camera."
    camera, X0 = args
    g = np.asarray(got, dtype=float)
    d0 = float(camera.R[2] @ X0 + camera.t[2])
    for matrix, cause in _approx_specific(camera, X0):
        if _same(g, matrix):
            return cause
    cause = _match_mistake(g, camera, X0, lambda d: (0.0, 0.0), _P_INF)
    if cause:
        return cause
    if not np.allclose(g[2], [0.0, 0.0, 0.0, 1.0], atol=1e-9):
        if _same_up_to_scale(g, camera.P):
            return (
                "this is the perspective camera P = K [R | t] itself (up to scale): its last row (r3, t3) gives "
                f"every point its own depth. The affine camera replaces that row by the constant depth d0: {_P_INF}."
            )
        return _last_row_cause(g, d0, expected, _P_INF, camera.R[2])
    return _approx_top_rows_cause(g, expected, camera, X0, d0)


def _approx_top_rows_cause(g, expected, camera, X0, d0) -> str:
    """Why the top two rows are wrong when the last row is right: a cause only where the answer is
    exactly what that mistake gives, else what differs."""
    M, m = g[:2, :3], g[:2, 3]
    M_e, m_e = expected[:2, :3], expected[:2, 3]
    c = camera.K[:2, 2]
    k = float(np.sum(M * M_e) / np.sum(M_e * M_e))  # the best scalar with M = k M_e
    if (
        not np.isclose(k, 1.0, rtol=1e-6)
        and k != 0
        and _same(M, k * M_e)
        and _same(m, c + k * (m_e - c))
    ):
        used = d0 / k
        unit = {1000.0: " (millimetres?)", 0.001: " (kilometres?)"}.get(round(used / d0, 6), "")
        sign = (
            " (negative: a point in front of the camera has a positive depth)" if used < 0 else ""
        )
        return (
            f"your matrix is P_inf for the depth d0 = {used:.4g} m{unit}{sign}, but X0 is {d0:.4g} m deep: "
            f"d0 = r3 . X0 + t3, the depth of the reference point along the optical axis."
        )
    if _same(g[[1, 0]], expected[:2]):
        return "the two rows are swapped: row 1 gives u (from r1 and fx), row 2 gives v (from r2 and fy)."
    slip = _image_of_X0_as_translation(g, expected, camera, X0)
    if slip:
        return slip
    if _same(M, M_e):
        if _same(m, m_e - c):
            return (
                f"the principal point is missing from the last column: K's third column (cx, cy, 1) times d0, "
                f"divided by d0, adds (cx, cy); {_P_INF}."
            )
        if _same(m, c):
            return f"the last column holds only (cx, cy): t1 and t2 are missing from it; {_P_INF}."
        offset = m - m_e
        slip = _principal_point_cause(offset, c)
        if slip:
            return slip
    return f"{_what_differs(g, expected, camera, X0)}. Compare each block with {_P_INF}."


def _mistake(index):
    """The ``index``-th shared slip, built for weak perspective, as a student's function."""

    def wrong(camera, X0):
        K, R, t = camera.K, camera.R, camera.t
        kw = {
            "K": K,
            "R": R,
            "t": t,
            "d0": float(R[2] @ X0 + t[2]),
            **_common_mistakes(camera, X0, "")[index][0],
        }
        return _p_inf(kw["K"], kw["R"], kw["t"], kw["d0"])

    return wrong


def _approx_unnormalised(camera, X0):
    d0 = camera.R[2] @ X0 + camera.t[2]
    return _p_inf(camera.K, camera.R, camera.t, d0) * d0


def _approx_only_block_divided(camera, X0):
    """K E with only its 2x3 block divided by d0 (P[:, :3] /= d0), then the last row set to (0, 0, 0, 1)."""
    K, R, t = camera.K, camera.R, camera.t
    E = np.zeros((3, 4))
    E[:2, :3], E[:2, 3], E[2, 3] = R[:2], t[:2], R[2] @ X0 + t[2]
    P = K @ E
    P[:, :3] /= E[2, 3]
    P[2] = [0.0, 0.0, 0.0, 1.0]
    return P


def _approx_r3_kept(camera, X0):
    """E = [R | t] with only its (3, 4) entry set to d0: the third row keeps r3."""
    d0 = camera.R[2] @ X0 + camera.t[2]
    E = np.c_[camera.R, camera.t]
    E[2, 3] = d0
    return camera.K @ E / d0


def _approx_e_last_one(camera, X0):
    """E's (3, 4) entry 1 instead of d0, then divided by d0: last row (0, 0, 0, 1/d0)."""
    E = np.zeros((3, 4))
    E[:2, :3], E[:2, 3], E[2, 3] = camera.R[:2], camera.t[:2], 1.0
    return camera.K @ E / (camera.R[2] @ X0 + camera.t[2])


def _approx_fx_fy_only(camera, X0):
    """Built entry by entry from fx, fy, cx, cy: the skew K[0, 1] is lost."""
    K, R, t = camera.K, camera.R, camera.t
    d0 = R[2] @ X0 + t[2]
    P = np.zeros((3, 4))
    P[0, :3], P[0, 3] = K[0, 0] * R[0] / d0, K[0, 0] * t[0] / d0 + K[0, 2]
    P[1, :3], P[1, 3] = K[1, 1] * R[1] / d0, K[1, 1] * t[1] / d0 + K[1, 2]
    P[2, 3] = 1.0
    return P


def _without_skew(K):
    K = K.copy()
    K[0, 1] = 0.0
    return K


def _approx_no_skew(camera, X0):
    return _p_inf(_without_skew(camera.K), camera.R, camera.t, camera.R[2] @ X0 + camera.t[2])


def _approx_image_centre(centre):
    """The principal point replaced by a fixed image centre (320, 240) or (319.5, 239.5)."""

    def wrong(camera, X0):
        K = camera.K.copy()
        K[:2, 2] = centre
        return _p_inf(K, camera.R, camera.t, camera.R[2] @ X0 + camera.t[2])

    return wrong


def _approx_shifted(shift):
    return lambda camera, X0: (
        af.affine_approximation(camera, X0) + np.c_[np.zeros((3, 3)), [shift, shift, 0.0]]
    )


def _approx_no_t(camera, X0):
    """t1, t2 left out of the last column."""
    t = np.array([0.0, 0.0, camera.t[2]])
    return _p_inf(camera.K, camera.R, t, camera.R[2] @ X0 + camera.t[2])


def _approx_centred_in_place(camera, X0):
    """Works relative to the camera centre by changing the caller's X0 in place."""
    X0 -= camera.centre
    return _p_inf(camera.K, camera.R, camera.t, camera.R[2] @ X0)


def _approx_K_in_place(camera, X0):
    """Divides camera.K in place (camlab's cameras keep their arrays read-only)."""
    K = camera.K
    K /= camera.R[2] @ X0 + camera.t[2]
    return _p_inf(K, camera.R, camera.t, 1.0)


def affine_approximation(camera, X0):
    """Give every point the depth d0 of the reference point X0 (H&Z §6.3.1), last row (0, 0, 0, 1)."""
    K, R, t = camera.K, camera.R, camera.t
    d0 = R[2] @ X0 + t[2]  # depth of X0 in the camera frame
    E = np.zeros((3, 4))
    E[:2, :3], E[:2, 3] = R[:2], t[:2]
    E[2, 3] = d0  # the third row no longer depends on the point
    return K @ E / d0


register_exercise(
    Exercise(
        name="affine_approximation",
        lesson="05",
        reference=af.affine_approximation,
        cases=_approx_cases,
        compare=same_array(rtol=1e-7, atol=1e-7),
        diagnose=_approx_diagnosis,
        ndarray_only=True,
        wrong_variants=(
            (_approx_unnormalised, "did not divide by d0"),
            (lambda camera, X0: camera.P, "perspective camera P = K [R | t] itself"),
            (lambda camera, X0: -af.affine_approximation(camera, X0), "minus the answer"),
            (_mistake(0), "depth of the world origin"),
            (_mistake(1), "lacks t3"),
            (_mistake(2), "t3 has the wrong sign"),
            (_mistake(3), "world z"),
            (_mistake(4), "Euclidean distance"),
            (_mistake(5), "|t|"),
            (_mistake(6), "wrong sign: a point in front"),
            (_mistake(7), "left out K"),
            (_mistake(8), "K^-1"),
            (_mistake(9), "principal point is missing"),
            (_mistake(10), "K.T"),
            (_mistake(11), "R.T"),
            (_mistake(12), "R.T"),
            (_mistake(13), "t1 and t2 have the wrong sign"),
            (_mistake(14), "millimetres"),
            (_approx_no_skew, "skew K[0, 1] is missing"),
            (_mistake(16), "world z of X0 - C"),
            (_mistake(17), "t has the wrong sign everywhere"),
            (_mistake(18), "t as the camera centre"),
            (
                lambda camera, X0: _approx_specific(camera, X0)[0][0],
                "last column is K (t1, t2, d0) undivided",
            ),
            (_approx_only_block_divided, "last column is K (t1, t2, d0) undivided"),
            (
                lambda camera, X0: _p_inf(
                    camera.K, camera.R, camera.t, -0.5 * (camera.R[2] @ X0 + camera.t[2])
                ),
                "negative: a point in front",
            ),
            (lambda camera, X0: _approx_specific(camera, X0)[1][0], "only P's third row"),
            (
                lambda camera, X0: _approx_specific(camera, X0)[2][0],
                "did not divide the top two rows",
            ),
            (
                lambda camera, X0: _approx_specific(camera, X0)[3][0],
                "principal point is divided by d0",
            ),
            (
                lambda camera, X0: _p_inf(
                    camera.K, camera.R, camera.t, 1000 * (camera.R[2] @ X0 + camera.t[2])
                ),
                "millimetres?",
            ),
            (
                lambda camera, X0: _p_inf(
                    camera.K, camera.R, camera.t, camera.R[2] @ X0 + camera.t[2] + 0.5
                ),
                "is P_inf for the depth",
            ),
            (_approx_e_last_one, "the (3, 4) entry"),
            (_approx_r3_kept, "the last row still holds r3"),
            (_approx_fx_fy_only, "skew K[0, 1] is missing"),
            (
                lambda camera, X0: af.paraperspective_approximation(camera, X0),
                "para-perspective camera",
            ),
            (lambda camera, X0: af.affine_approximation(camera, X0)[[1, 0, 2]], "rows are swapped"),
            (_approx_no_t, "t1 and t2 are missing"),
            (_approx_image_centre((320.0, 240.0)), "or you used (320, 240), half the image size"),
            (
                _approx_image_centre((319.5, 239.5)),
                "(319.5, 239.5), the centre of a 640 x 480 image as the principal",
            ),
            (_approx_shifted(0.5), "half a pixel"),
            (_approx_shifted(-1.0), "one pixel"),
            (
                lambda camera, X0: np.round(af.affine_approximation(camera, X0), 1),
                "entries of the 2x3 block differ",
            ),
            (
                lambda camera, X0: af.affine_approximation(camera, X0).tolist(),
                "you returned a list",
            ),
            (
                lambda camera, X0: affine_approximation(camera, 1000 * np.asarray(X0)),
                "scaled by 1000 (millimetres?)",
            ),
            (_approx_centred_in_place, "changed its input `X0` in place"),
            (_approx_K_in_place, "camera.K.copy()"),
        ),
        teaching=affine_approximation,
    )
)


# -- paraperspective_approximation -----------------------------------------------------------------


def _para_outer_reshaped(camera, X0):
    """The block of a r3 and b r3 built as np.outer(R[2], ab) (3, 2), reshaped to (2, 3): scrambled."""
    K, R, t = camera.K, camera.R, camera.t
    x_c = R @ X0 + t
    d0, ab = x_c[2], x_c[:2] / x_c[2]
    E = np.zeros((3, 4))
    E[:2, :3], E[:2, 3], E[2, 3] = (
        R[:2] - np.outer(R[2], ab).reshape(2, 3),
        t[:2] - ab * (t[2] - d0),
        d0,
    )
    return K @ E / d0


def _para_specific(camera, X0):
    """(matrix, cause) for mistakes only para-perspective meets."""
    K, R, t = camera.K, camera.R, camera.t
    x_c = R @ X0 + t
    d0, ab = float(x_c[2]), x_c[:2] / x_c[2]
    uv_X0 = camera.project(X0)
    no_skew = (uv_X0 - K[:2, 2]) / np.diag(K)[:2]
    x_mm = R @ (1000 * np.asarray(X0, dtype=float)) + t
    ray = (
        np.asarray(X0, dtype=float) - camera.centre
    )  # the line of sight to X0, in world coordinates
    unrotated = (
        "you took (a, b) from X0 - C, the line of sight in world coordinates: (a, b) is X0's position in "
        "the camera frame, so rotate the ray first, R (X0 - C) = R X0 + t = x_c, then (a, b) = x_c[:2] / "
        "x_c[2]; the world's axes are not the camera's."
    )
    return [
        (
            af.affine_approximation(camera, X0),
            "this is the weak-perspective camera P_inf (the first exercise): para-perspective also takes a r3 and "
            f"b r3 from the first two rows of E, with (a, b) = (x_c, y_c) / d0 X0's normalised position; {_P_PARA}.",
        ),
        (
            _p_para(K, R, t, d0, -ab),
            "the a and b terms have the wrong sign: the normalised image is "
            "(x - a (z - d0)) / d0, so E's rows are r1 - a r3 and r2 - b r3.",
        ),
        (
            _p_para(K, R, t, d0, ab[::-1]),
            "a and b are swapped: a = x_c / d0 goes with the first row (u), "
            "b = y_c / d0 with the second (v).",
        ),
        (
            _p_para(K, R, t, d0, ab, t_term=0.0),
            "the last column lacks -(a, b) (t3 - d0): z - d0 = r3 . X + t3 - d0 in camera coordinates, so the "
            f"a and b terms carry the constant t3 - d0 into E's last column; {_P_PARA}.",
        ),
        (
            _p_para(K, R, t, d0, ab, t_term=t[2]),
            "the last column has -(a, b) t3 where it needs -(a, b) (t3 - d0): the -d0 of z - d0 is missing there.",
        ),
        (
            _p_para(K, R, t, d0, ab, t_term=-d0),
            "the last column has +(a, b) d0 where it needs -(a, b) (t3 - d0): the t3 of z = r3 . X + t3 is missing.",
        ),
        (
            _p_para(K, R, t, d0, ab, t_term=d0 - t[2]),
            "the last column has +(a, b) (t3 - d0) where it needs -(a, b) (t3 - d0): the rows are right, but the sign of "
            "the a and b terms in E's last column is flipped.",
        ),
        (
            _p_para(K, R, t, d0, uv_X0),
            "you used X0's pixel coordinates as (a, b): they are its normalised image "
            "position, (x_c, y_c) / d0 with x_c = R X0 + t (metres over metres), or "
            "K^-1 (u, v, 1).",
        ),
        (
            _p_para(K, R, t, d0, no_skew)
            if K[0, 1]
            else np.full((3, 4), np.nan),  # no skew: that is right
            f"(a, b) = ((u - cx) / fx, (v - cy) / fy) ignores this camera's skew K[0, 1] = {K[0, 1]:g}: take (a, b) "
            "= (x_c, y_c) / d0 from x_c = R X0 + t, or the first two entries of K^-1 (u, v, 1).",
        ),
        (
            _p_para(K, R, t, d0, X0[:2] / X0[2]),
            "you took (a, b) from X0's world coordinates: they come from its "
            "camera-frame coordinates, x_c = R X0 + t, (a, b) = x_c[:2] / x_c[2].",
        ),
        (
            _p_para(K, R, t, d0, x_c[:2] / np.linalg.norm(x_c)),
            "you divided (x_c, y_c) by X0's distance |x_c|; (a, b) divide by its depth, x_c[2] = d0.",
        ),
        (
            _p_para(K, R, t, d0, (uv_X0 - K[:2, 2]) / K[0, 0])
            if K[0, 0] != K[1, 1]
            else np.full((3, 4), np.nan),
            f"(a, b) = (u - cx, v - cy) / fx divides both offsets by fx, but this camera's fy = {K[1, 1]:g} px is not "
            f"fx = {K[0, 0]:g} px: b = (v - cy) / fy. Safer: (a, b) = (x_c, y_c) / d0 from x_c = R X0 + t.",
        ),
        (
            _p_para(K, R, t, d0, ab / d0),
            "you divided (x_c, y_c) by d0 twice: (a, b) = (x_c, y_c) / d0 once, and "
            "the whole matrix is divided by d0 at the end.",
        ),
        (
            af.affine_approximation(camera, X0)
            - np.r_[np.outer(uv_X0, np.r_[R[2], t[2] - d0]) / d0, np.zeros((1, 4))],
            "you wrote the pixel form P_inf - x_X0 (r3, t3 - d0) / d0 with X0's pixel position: it needs the offset from "
            "the principal point, P_para = P_inf - (x_X0 - x0) (r3, t3 - d0) / d0 in the top two rows (K (a, b, 0) "
            "is x_X0 - x0).",
        ),
        (
            _p_para(K, R, t, x_mm[2], x_mm[:2] / x_mm[2]),
            f"X0 was scaled by 1000 (millimetres?): its depth came out as {x_mm[2]:.4g} m where X0 is {d0:.4g} m deep, "
            f"and (a, b) as {x_mm[0] / x_mm[2]:.4g}, {x_mm[1] / x_mm[2]:.4g} for {ab[0]:.4g}, {ab[1]:.4g}. The camera's "
            f"t and X0 are both in metres; use X0 as given: {_P_PARA}.",
        ),
        (_p_para(K, R, t, d0, ray[:2] / ray[2]), unrotated),
        (_p_para(K, R, t, d0, ray[:2] / d0), unrotated),
        (
            _p_para(K, R, t, d0, (ab[0], ab[0])),
            "both rows use a: the second row is r2 - b r3 with its own "
            "b = y_c / d0 (and t2 - b (t3 - d0)).",
        ),
        (
            _p_para(K, R, t, d0, (ab[1], ab[1])),
            "both rows use b: the first row is r1 - a r3 with a = x_c / d0 (and t1 - a (t3 - d0)).",
        ),
        (
            _para_outer_reshaped(camera, X0),
            "np.outer(R[2], ab) is (3, 2), and reshaping it to (2, 3) scrambles its entries: the block of a r3 and "
            "b r3 is np.outer(ab, R[2]) (2, 3), or ab[:, None] * R[2].",
        ),
        (
            _p_para(K, R, t, d0, np.arctan(ab)),
            "your (a, b) are angles, arctan(x_c / d0) and arctan(y_c / d0): (a, b) are the tangents themselves, "
            "(x_c, y_c) / d0, X0's normalised image position (no arctan, no degrees).",
        ),
    ]


def _para_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return the 3x4 affine camera."
    camera, X0 = args
    g = np.asarray(got, dtype=float)
    d0, ab = _depth_and_ab(camera, X0)
    for matrix, cause in _para_specific(camera, X0):
        if _same(g, matrix):
            return cause
    x_c = camera.R @ X0 + camera.t
    cause = _match_mistake(g, camera, X0, lambda d: x_c[:2] / d, _P_PARA)
    if cause:
        return cause
    if not np.allclose(g[2], [0.0, 0.0, 0.0, 1.0], atol=1e-9):
        return _last_row_cause(g, d0, expected, _P_PARA, camera.R[2])
    slip = _image_of_X0_as_translation(g, expected, camera, X0)
    if slip:
        return slip
    if _same(g[:2, :3], expected[:2, :3]):
        slip = _principal_point_cause(g[:2, 3] - expected[:2, 3], camera.K[:2, 2])
        if slip:
            return slip
    return f"{_what_differs(g, expected, camera, X0)}. Compare each block with {_P_PARA}."


def _para_mistake(index):
    """The ``index``-th shared slip, built for para-perspective, as a student's function."""

    def wrong(camera, X0):
        K, R, t = camera.K, camera.R, camera.t
        x_c = R @ X0 + t
        kw = {
            "K": K,
            "R": R,
            "t": t,
            "d0": float(x_c[2]),
            **_common_mistakes(camera, X0, "")[index][0],
        }
        return _p_para(kw["K"], kw["R"], kw["t"], kw["d0"], x_c[:2] / kw["d0"])

    return wrong


def _para_ab_without_skew(camera, X0):
    """(a, b) read off X0's pixels as ((u - cx) / fx, (v - cy) / fy): right unless K has a skew."""
    K, x_c = camera.K, camera.R @ X0 + camera.t
    ab = (camera.project(X0) - K[:2, 2]) / np.diag(K)[:2]
    return _p_para(K, camera.R, camera.t, x_c[2], ab)


def _para_ab_over_fx(camera, X0):
    """(a, b) = (u - cx, v - cy) / fx from X0's pixels: right only where fy = fx and there is no skew."""
    K, x_c = camera.K, camera.R @ X0 + camera.t
    return _p_para(K, camera.R, camera.t, x_c[2], (camera.project(X0) - K[:2, 2]) / K[0, 0])


def _para_image_of_X0_as_t(camera, X0):
    """The first-order expansion written as x_X0 + M2 X: M2 right, the last column X0's image."""
    P = af.paraperspective_approximation(camera, X0)
    P[:2, 3] = camera.project(X0)
    return P


def _para_no_skew(camera, X0):
    x_c = camera.R @ X0 + camera.t
    return _p_para(_without_skew(camera.K), camera.R, camera.t, x_c[2], x_c[:2] / x_c[2])


def paraperspective_approximation(camera, X0):
    """Perspective linearised at X0 (section 2): x -> (x - a (z - d0)) / d0, last row (0, 0, 0, 1)."""
    K, R, t = camera.K, camera.R, camera.t
    x_c = R @ X0 + t  # X0 in the camera frame
    d0 = x_c[2]  # its depth
    a, b = x_c[:2] / d0  # its normalised image position
    E = np.zeros((3, 4))  # rows act on (X, 1); z - d0 = r3 . X + t3 - d0
    E[0, :3], E[0, 3] = R[0] - a * R[2], t[0] - a * (t[2] - d0)  # x - a (z - d0)
    E[1, :3], E[1, 3] = R[1] - b * R[2], t[1] - b * (t[2] - d0)  # y - b (z - d0)
    E[2, 3] = d0
    return K @ E / d0


def _para_exception_hint(exc, args) -> str:
    """A broadcasting slip in the rows r_i - ab_i r3 (ab is (2,), r3 is (3,))."""
    if isinstance(exc, ValueError) and "broadcast" in str(exc):
        return (
            "a broadcasting slip building the rows r1 - a r3 and r2 - b r3: ab = (a, b) is (2,) and r3 = R[2] is "
            "(3,), so ab * R[2] (or R[:2] - ab * R[2][:2]) cannot line up. Make the (2, 3) block with "
            "np.outer(ab, R[2]) or ab[:, None] * R[2], then R[:2] - that block; the last column takes "
            "ab * (t3 - d0), a (2,) vector."
        )
    return ""


register_exercise(
    Exercise(
        name="paraperspective_approximation",
        lesson="05",
        reference=af.paraperspective_approximation,
        cases=_approx_cases,
        compare=same_array(rtol=1e-7, atol=1e-7),
        diagnose=_para_diagnosis,
        exception_hint=_para_exception_hint,
        ndarray_only=True,
        wrong_variants=(
            (
                lambda camera, X0: af.affine_approximation(camera, X0),
                "weak-perspective camera P_inf",
            ),
            (
                lambda camera, X0: _para_specific(camera, X0)[1][0],
                "a and b terms have the wrong sign",
            ),
            (lambda camera, X0: _para_specific(camera, X0)[2][0], "a and b are swapped"),
            (lambda camera, X0: _para_specific(camera, X0)[3][0], "lacks -(a, b) (t3 - d0)"),
            (lambda camera, X0: _para_specific(camera, X0)[4][0], "the -d0 of z - d0 is missing"),
            (lambda camera, X0: _para_specific(camera, X0)[5][0], "the t3 of z"),
            (
                lambda camera, X0: _para_specific(camera, X0)[6][0],
                "sign of the a and b terms in E's last column",
            ),
            (lambda camera, X0: _para_specific(camera, X0)[7][0], "pixel coordinates as (a, b)"),
            (_para_ab_without_skew, "ignores this camera's skew"),
            (lambda camera, X0: _para_specific(camera, X0)[9][0], "world coordinates"),
            (lambda camera, X0: _para_specific(camera, X0)[10][0], "distance |x_c|"),
            (_para_image_of_X0_as_t, "t2 = x_X0 - M2 X0"),
            (_para_ab_over_fx, "divides both offsets by fx"),
            (lambda camera, X0: _para_specific(camera, X0)[12][0], "by d0 twice"),
            (
                lambda camera, X0: _para_specific(camera, X0)[13][0],
                "offset from the principal point",
            ),
            (_para_mistake(17), "t has the wrong sign everywhere"),
            (_para_mistake(0), "depth of the world origin"),
            (_para_mistake(2), "t3 has the wrong sign"),
            (_para_mistake(7), "left out K"),
            (_para_mistake(8), "K^-1"),
            (_para_mistake(11), "R.T"),
            (_para_mistake(13), "t1 and t2 have the wrong sign"),
            (_para_no_skew, "skew K[0, 1] is missing"),
            (
                lambda camera, X0: (
                    af.paraperspective_approximation(camera, X0) * (camera.R[2] @ X0 + camera.t[2])
                ),
                "did not divide by d0",
            ),
            (lambda camera, X0: -af.paraperspective_approximation(camera, X0), "minus the answer"),
            (
                lambda camera, X0: (
                    af.paraperspective_approximation(camera, X0)
                    + np.c_[np.zeros((3, 3)), [0.5, 0.5, 0]]
                ),
                "half a pixel",
            ),
            (
                lambda camera, X0: np.round(af.paraperspective_approximation(camera, X0), 2),
                "entries of the 2x3 block differ",
            ),
            (lambda camera, X0: _para_specific(camera, X0)[14][0], "scaled by 1000 (millimetres?)"),
            (
                lambda camera, X0: _para_specific(camera, X0)[15][0],
                "line of sight in world coordinates",
            ),
            (
                lambda camera, X0: _para_specific(camera, X0)[16][0],
                "line of sight in world coordinates",
            ),
            (lambda camera, X0: _para_specific(camera, X0)[17][0], "both rows use a"),
            (lambda camera, X0: _para_specific(camera, X0)[18][0], "both rows use b"),
            (_para_outer_reshaped, "np.outer(ab, R[2])"),
            (lambda camera, X0: _para_specific(camera, X0)[20][0], "your (a, b) are angles"),
        ),
        teaching=paraperspective_approximation,
    )
)
