"""Exercises for lesson 05, affine cameras."""
from __future__ import annotations

import numpy as np

from .. import affine as af
from .. import camera as cm
from ._core import Exercise, register_exercise, same_array, shape_problem



# -- affine_approximation ------------------------------------------------------------------

def _approx_cases():
    # X0 off the optical axis in every case: on the axis, any matrix that scales the image about the
    # principal point (a wrong d0, a missing division) would still image X0 correctly and slip past.
    return [
        (cm.Camera.look_at([4.0, -3.0, 2.0], [0.0, 0.0, 0.5]), np.array([0.3, -0.2, 0.6])),
        (cm.Camera.look_at([-6.0, -8.0, 3.0], [0.5, 0.0, 0.0], K=cm.intrinsic_matrix(1200, 1100, 310, 250)),
         np.array([0.2, 0.3, 0.4])),
        (cm.Camera(cm.intrinsic_matrix(800, 800, 320, 240), cm.rotation_from_euler(0.2, 0.1, -0.3), [0.1, 0.2, 9.0]),
         np.array([1.0, -0.5, 0.3])),
        # a skewed K (H&Z's general camera): an answer built from fx, fy, cx, cy alone drops K[0, 1]
        (cm.Camera(cm.intrinsic_matrix(900, 870, 330, 250, skew=25.0), cm.rotation_from_euler(-0.3, 0.2, 0.1),
                   [0.3, -0.2, 7.0]), np.array([-0.6, 0.8, 0.2])),
    ]


def _p_inf(K, R, t, d0):
    """K [[r1, t1], [r2, t2], [0, d0]] / d0 for any K, R, t, d0 (the mistakes below vary one of them)."""
    E = np.zeros((3, 4))
    E[:2, :3], E[:2, 3], E[2, 3] = R[:2], t[:2], d0
    return K @ E / d0


def _approx_mistakes(camera, X0):
    """(matrix, cause) for the typical mistakes."""
    K, R, t = camera.K, camera.R, camera.t
    d0 = R[2] @ X0 + t[2]
    centre = camera.centre
    only_row3 = camera.P / d0
    only_row3[2] = [0.0, 0.0, 0.0, 1.0]
    no_division = _p_inf(K, R, t, d0) * d0
    no_division[2] = [0.0, 0.0, 0.0, 1.0]
    fix = "P_inf = K [[r1, t1], [r2, t2], [0, d0]] / d0"
    K_no_skew = K.copy()
    K_no_skew[0, 1] = 0.0
    return [
        (_p_inf(K, R, t, t[2]), "you used d0 = t3, the depth of the world origin; use the depth of the reference "
                                "point, d0 = r3 . X0 + t3."),
        (_p_inf(K, R, t, R[2] @ X0), "d0 lacks t3: the depth of X0 in the camera frame is r3 . X0 + t3."),
        (_p_inf(K, R, t, X0[2]), "you used X0's world z as d0; the depth is measured along the camera's "
                                 "optical axis: d0 = r3 . X0 + t3."),
        (_p_inf(K, R, t, np.linalg.norm(X0 - centre)), "you used the Euclidean distance from the camera centre "
                                                       "as d0; the depth is along the optical axis: d0 = r3 . X0 + t3."),
        (_p_inf(K, R, t, np.linalg.norm(t)), "you used |t| as d0; the depth of X0 is d0 = r3 . X0 + t3."),
        (_p_inf(K, R, t, -d0), "d0 has the wrong sign: a point in front of the camera has positive depth "
                               "r3 . X0 + t3."),
        (_p_inf(np.eye(3), R, t, d0), f"you left out K, so the matrix gives normalised coordinates, not pixels: {fix}."),
        (_p_inf(np.diag([K[0, 0], K[1, 1], 1.0]), R, t, d0),
         "the principal point is missing: keep the whole K (its third column (cx, cy, 1) multiplies the depth "
         f"d0 in every row), {fix}."),
        (_p_inf(K.T, R, t, d0), f"you used K.T: K is upper triangular, with the principal point in its last column; {fix}."),
        (_p_inf(K, R.T, t, R.T[2] @ X0 + t[2]), "you used R.T (the columns of R): r1, r2, r3 are the rows of R, "
                                                "R[0], R[1], R[2]."),
        (only_row3, "you replaced only P's third row: P's first two rows also hold the depth, through K's third "
                    f"column times r3 . X + t3. Replace the depth inside [R | t] before K multiplies: {fix}."),
        (no_division, "you set the last row to (0, 0, 0, 1) but did not divide the top two rows by d0, so the image "
                      f"is d0 times too large about the origin: divide the whole matrix, {fix}."),
        (_p_inf(K_no_skew, R, t, d0),
         f"the skew K[0, 1] is missing (this camera's is {K[0, 1]:g} px): build the matrix from the whole K, "
         f"not from fx, fy, cx and cy alone: {fix}."),
        (_p_inf(K, R, t, d0) - np.c_[np.zeros((3, 3)), np.r_[K[:2, 2], 0.0]] * (d0 - 1) / d0,
         "the principal point is divided by d0: in K [[r1, t1], [r2, t2], [0, d0]] the (3, 4) entry is d0, so after "
         f"dividing by d0 K's third column (cx, cy) is added as it is; {fix}."),
    ]


def _approx_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return the 3x4 affine camera."
    camera, X0 = args
    g = np.asarray(got, dtype=float)
    K, R, t = camera.K, camera.R, camera.t
    d0 = float(R[2] @ X0 + t[2])
    if np.allclose(g, -expected, atol=1e-7):
        return ("the matrix is -P_inf (last row (0, 0, 0, -1)): the same camera projectively, but the prompt fixes "
                "the last row to (0, 0, 0, +1); divide by d0 = r3 . X0 + t3, which is positive.")
    for matrix, cause in _approx_mistakes(camera, X0):
        if np.allclose(g, matrix, atol=1e-7):
            return cause
    if not np.allclose(g[2], [0.0, 0.0, 0.0, 1.0], atol=1e-9):
        if abs(g[2, 3]) > 1e-12 and np.allclose(g[2, :3], 0.0, atol=1e-9):
            if np.isclose(g[2, 3], 1.0 / d0, rtol=1e-6):
                return (f"the last row is (0, 0, 0, 1/d0): the (3, 4) entry of [[r1, t1], [r2, t2], [0, d0]] is the "
                        f"depth d0 = {d0:.4g} m, not 1; dividing by d0 then makes the last row (0, 0, 0, 1).")
            if np.allclose(g / g[2, 3], expected, atol=1e-7) and not np.isclose(g[2, 3], d0, rtol=1e-6):
                return (f"your matrix is {g[2, 3]:.4g} times P_inf: the same camera projectively, but the prompt "
                        f"fixes the last row to (0, 0, 0, 1); divide by d0 = r3 . X0 + t3 = {d0:.4g} m, and only once.")
            return f"the last row is (0, 0, 0, {g[2, 3]:.4g}): divide the whole matrix by d0 so it is (0, 0, 0, 1)."
        return "the last row must be (0, 0, 0, 1): replace r3 . X + t3 by the constant reference depth d0."
    return _approx_top_rows_cause(g, expected, camera, X0, d0)


def _approx_top_rows_cause(g, expected, camera, X0, d0) -> str:
    """Why the top two rows are wrong when the last row is right: name what differs, blaming d0 only if
    the answer is P_inf for another depth."""
    fix = "P_inf = K [[r1, t1], [r2, t2], [0, d0]] / d0"
    M, m = g[:2, :3], g[:2, 3]
    M_e, m_e = expected[:2, :3], expected[:2, 3]
    c = camera.K[:2, 2]
    k = float(np.sum(M * M_e) / np.sum(M_e * M_e))  # the best scalar with M = k M_e
    if not np.isclose(k, 1.0, rtol=1e-6) and k > 0 and np.allclose(M, k * M_e, atol=1e-7) \
            and np.allclose(m, c + k * (m_e - c), atol=1e-6):
        used = d0 / k
        unit = {1000.0: " (millimetres?)", 0.001: " (kilometres?)"}.get(round(used / d0, 6), "")
        return (f"your matrix is P_inf for the depth d0 = {used:.4g} m{unit}, but X0 is {d0:.4g} m deep: "
                f"d0 = r3 . X0 + t3, the depth of the reference point along the optical axis.")
    if np.allclose(g, af.paraperspective_approximation(camera, X0), atol=1e-7):
        return ("this is the para-perspective camera (section 2), which projects along the line of sight to X0; the "
                f"exercise asks for weak perspective, every depth replaced by d0 with no r3 terms in M2: {fix}.")
    if np.allclose(g[[1, 0]], expected[:2], atol=1e-7):
        return "the two rows are swapped: row 1 gives u (from r1 and fx), row 2 gives v (from r2 and fy)."
    if np.allclose(M, M_e, atol=1e-7):
        if np.allclose(m, m_e - c, atol=1e-6):
            return (f"the principal point is missing from the last column: K's third column (cx, cy, 1) times d0, "
                    f"divided by d0, adds (cx, cy); {fix}.")
        return (f"the 2x3 block is right, but the last column is not: it is (K [t1, t2, d0]^T) / d0, the top two "
                f"entries of K's product with the translation column (t1, t2, d0); {fix}.")
    return (f"the last row is right, but the top two rows differ from P_inf (see the worst entry above): their 2x3 "
            f"block is K's top-left 2x2 times [r1; r2] / d0, their last column (K [t1, t2, d0]^T) / d0; {fix}.")


def _mistake(index):
    """The ``index``-th typical mistake as a student's function (for the wrong-answer tests)."""
    return lambda camera, X0: _approx_mistakes(camera, X0)[index][0]


def _approx_unnormalised(camera, X0):
    d0 = camera.R[2] @ X0 + camera.t[2]
    return _p_inf(camera.K, camera.R, camera.t, d0) * d0


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
    """Give every point the depth d0 of the reference point X0 (H&Z eq. 6.16), last row (0, 0, 0, 1)."""
    K, R, t = camera.K, camera.R, camera.t
    d0 = R[2] @ X0 + t[2]        # depth of X0 in the camera frame
    E = np.zeros((3, 4))
    E[:2, :3], E[:2, 3] = R[:2], t[:2]
    E[2, 3] = d0                 # the third row no longer depends on the point
    return K @ E / d0


register_exercise(Exercise(
    name="affine_approximation",
    lesson="05",
    reference=af.affine_approximation,
    cases=_approx_cases,
    compare=same_array(rtol=1e-7, atol=1e-7),
    diagnose=_approx_diagnosis,
    wrong_variants=(
        (_approx_unnormalised, "divide the whole matrix by d0"),
        (lambda camera, X0: camera.P, "last row must be"),
        (lambda camera, X0: -af.affine_approximation(camera, X0), "-P_inf"),
        (_mistake(0), "depth of the world origin"),
        (_mistake(1), "lacks t3"),
        (_mistake(2), "world z"),
        (_mistake(3), "Euclidean distance"),
        (_mistake(4), "|t|"),
        (_mistake(5), "wrong sign"),
        (_mistake(6), "left out K"),
        (_mistake(7), "principal point is missing"),
        (_mistake(8), "K.T"),
        (_mistake(9), "R.T"),
        (_mistake(10), "only P's third row"),
        (_mistake(11), "did not divide the top two rows"),
        (_mistake(12), "skew K[0, 1] is missing"),
        (_mistake(13), "principal point is divided by d0"),
        (lambda camera, X0: _p_inf(camera.K, camera.R, camera.t, 1000 * (camera.R[2] @ X0 + camera.t[2])),
         "millimetres?"),
        (lambda camera, X0: _p_inf(camera.K, camera.R, camera.t, camera.R[2] @ X0 + camera.t[2] + 0.5),
         "is P_inf for the depth"),
        (_approx_e_last_one, "the (3, 4) entry"),
        (_approx_fx_fy_only, "skew K[0, 1] is missing"),
        (lambda camera, X0: af.paraperspective_approximation(camera, X0), "para-perspective camera"),
        (lambda camera, X0: af.affine_approximation(camera, X0)[[1, 0, 2]], "rows are swapped"),
        (_approx_no_t, "last column is not"),
        (_approx_centred_in_place, "changed its input `X0` in place"),
        (_approx_K_in_place, "camera.K.copy()"),
    ),
    teaching=affine_approximation,
))


# -- estimate_affine_camera -------------------------------------------------------------------

def _estimate_cases():
    rng = np.random.default_rng(5)
    out = []
    for k in range(3):
        R = cm.rotation_from_euler(*rng.uniform(-0.5, 0.5, 3))
        P = af.weak_perspective_matrix(R, [0.1 * k, -0.2, 5.0], 160 + 20 * k, 150, 0.0, (320, 240))
        X = rng.uniform(-1.0, 1.0, (10 + 5 * k, 3))
        uv = cm.project_points(P, X) + rng.normal(0.0, 1.0, (len(X), 2))  # noisy: least squares matters
        out.append((X, uv))
    return out


def _estimate_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return the 3x4 affine camera with last row (0, 0, 0, 1)."
    X, uv = args
    g = np.asarray(got, dtype=float)
    if not np.allclose(g[2], [0.0, 0.0, 0.0, 1.0], atol=1e-9):
        k = g[2, 3]
        if np.allclose(g[2, :3], 0.0, atol=1e-9) and abs(k) > 1e-12 and np.allclose(g / k, expected, atol=1e-6):
            return (f"your camera is {k:.4g} times the least-squares one: the same camera projectively, but an "
                    f"affine camera's last row is fixed to (0, 0, 0, 1); divide by its last entry.")
        return "the last row of an affine camera is (0, 0, 0, 1); estimate only the top 2x4 block (8 numbers)."
    M2, t2 = g[:2, :3], g[:2, 3]
    M2_expected, t2_expected = expected[:2, :3], expected[:2, 3]
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    for wrong_mean, cause in ((_fit_centred(X, uv, X.mean(axis=1, keepdims=True), uv.mean(axis=1, keepdims=True)),
                               "you averaged along axis=1, each point's own coordinates (x, y, z): the centroid of "
                               "N points is X.mean(axis=0), one mean per coordinate"),
                              (_fit_centred(X, uv, X.mean(), uv.mean()),
                               "you took the mean of every entry together (X.mean() with no axis), a single number: "
                               "the centroid is X.mean(axis=0), one mean per coordinate")):
        if np.allclose(M2, wrong_mean, atol=1e-6):
            return cause + "; then t2 = mean(uv) - M2 @ mean(X)."
    if np.linalg.matrix_rank(M2, tol=1e-9 * max(np.abs(M2).max(), 1e-300)) < 2:
        return ("M2 has rank < 2 (its rows are parallel or zero), so every point would image onto one line: each "
                "row of M2 is fitted to its own pixel coordinate; did you fit the same column of uv twice, or "
                "broadcast one row?")
    if np.allclose(M2, M2_expected.T.reshape(2, 3), atol=1e-6):
        return ("M2 is scrambled: lstsq returns the (3, 2) matrix M2^T; transpose it (.T), do not reshape it to (2, 3).")
    if np.allclose(g[:2], expected[1::-1], atol=1e-6):
        return "u and v are swapped: uv[:, 0] is u (the column), uv[:, 1] is v (the row), and row 1 of P predicts u."
    if np.allclose(M2, np.linalg.lstsq(uv - um, X - Xm, rcond=None)[0], atol=1e-6):
        return ("you regressed the world points on the pixels (lstsq(uv, X)); the camera predicts pixels from "
                "points: lstsq(X - mean(X), uv - mean(uv)) gives M2^T.")
    uncentred = np.linalg.lstsq(X, uv, rcond=None)[0].T
    if np.allclose(M2, uncentred, atol=1e-6):
        return ("you regressed the pixels on the raw world points, so the fit had no constant term and M2 absorbed "
                "the offset: centre both point sets first (or append a column of ones to X).")
    if np.allclose(M2, M2_expected, atol=1e-6):
        return _translation_cause(t2, t2_expected, um, M2 @ Xm)
    scale = _image_scaling(g, expected, X)
    if scale is not None and (np.isclose(scale, 1e-3, rtol=1e-4) or np.isclose(scale, 1e3, rtol=1e-4)):
        small = scale < 1
        return (f"your camera's image is {scale:g} times the size of the least-squares one: a unit slip by 1000 "
                f"(metres and millimetres). The world points X are in metres and the pixels uv in pixels; fit them "
                f"as they are ({'X * 1000 or uv / 1000' if small else 'X / 1000 or uv * 1000'} gives this).")
    if scale is not None:
        return (f"your camera's image is the least-squares one scaled by {scale:.4g} (and shifted): did you "
                f"normalise the points (divide by their spread) and not undo it? Map the fitted camera back: "
                f"P = T_uv^-1 P_normalised T_X.")
    if _same_up_to_scale(g[:2], cm.estimate_projection_matrix(X, uv)[:2]):
        return ("this is a projective camera (DLT) with its last row overwritten: it does not minimise the pixel "
                "error of an affine camera; fit the 8 affine parameters directly by linear least squares.")
    r_got = np.sqrt(np.mean(np.sum((X @ M2.T + t2 - uv) ** 2, axis=1)))
    r_exp = np.sqrt(np.mean(np.sum((X @ M2_expected.T + t2_expected - uv) ** 2, axis=1)))
    return (f"your camera's RMS residual is {r_got:.3f} px, the least-squares optimum is {r_exp:.3f} px: use all "
            f"the points in one least-squares solve (np.linalg.lstsq), not an exact fit to a few of them.")


def _translation_cause(t2, t2_expected, um, M2Xm) -> str:
    """Why t2 is wrong when M2 is right."""
    if np.allclose(t2, um + M2Xm, atol=1e-6):
        return "t2 has a sign flipped: the centroids correspond, mean(uv) = M2 @ mean(X) + t2, so t2 = mean(uv) - M2 @ mean(X)."
    offset = t2 - t2_expected
    if np.allclose(np.abs(offset), 0.5, atol=1e-6):
        return ("t2 is off by half a pixel: pixel centres are at integers (docs/conventions.md), so no 0.5 "
                "belongs in the fit; t2 = mean(uv) - M2 @ mean(X).")
    if np.allclose(np.abs(offset), 1.0, atol=1e-6):
        return ("t2 is off by one pixel: pixels count from 0 in numpy and this course, not from 1 (a 1-based "
                "index?); fit the pixels as given, t2 = mean(uv) - M2 @ mean(X).")
    return ("the translation column is wrong: after fitting M2 on centred points, the centroids must "
            "correspond, t2 = mean(uv) - M2 @ mean(X).")


def _fit_centred(X, uv, X_mean, uv_mean):
    """M2 fitted after subtracting the given (possibly wrong) means."""
    return np.linalg.lstsq(X - X_mean, uv - uv_mean, rcond=None)[0].T


def _image_scaling(got, expected, X):
    """s if ``got`` images every point at s (expected's image) + b for one scalar s != 1, else None."""
    a, b = X @ got[:2, :3].T + got[:2, 3], X @ expected[:2, :3].T + expected[:2, 3]
    A = np.column_stack([b.ravel(), np.tile(np.eye(2), (len(X), 1))])
    sol, *_ = np.linalg.lstsq(A, a.ravel(), rcond=None)
    if np.allclose(A @ sol, a.ravel(), atol=1e-6) and not np.isclose(sol[0], 1.0, rtol=1e-6):
        return float(sol[0])
    return None


def _same_up_to_scale(a, b) -> bool:
    a, b = np.ravel(a), np.ravel(b)
    k = (a @ b) / (b @ b) if b @ b > 0 else 0.0
    return bool(k != 0 and np.allclose(a, k * b, atol=1e-6 * np.abs(a).max()))


def _estimate_reshaped(X, uv):
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    M2 = np.linalg.lstsq(X - Xm, uv - um, rcond=None)[0].reshape(2, 3)
    return np.vstack([np.c_[M2, um - M2 @ Xm], [0.0, 0.0, 0.0, 1.0]])


def _estimate_uncentred(X, uv):
    M2 = np.linalg.lstsq(X, uv, rcond=None)[0].T
    return np.vstack([np.c_[M2, uv.mean(axis=0) - M2 @ X.mean(axis=0)], [0.0, 0.0, 0.0, 1.0]])


def _estimate_no_translation(X, uv):
    M2 = af.estimate_affine_camera(X, uv)[:2, :3]
    return np.vstack([np.c_[M2, np.zeros(2)], [0.0, 0.0, 0.0, 1.0]])


def _estimate_with_ones(X, uv):
    """A right answer in another form: one lstsq with a column of ones, no centring."""
    A = np.linalg.lstsq(np.c_[X, np.ones(len(X))], uv, rcond=None)[0].T
    return np.vstack([A, [0.0, 0.0, 0.0, 1.0]])


def _estimate_four_points(X, uv):
    return af.estimate_affine_camera(X[:4], uv[:4])


def _estimate_dlt(X, uv):
    return cm.estimate_projection_matrix(X, uv)


def _estimate_dlt_last_row_forced(X, uv):
    P = cm.estimate_projection_matrix(X, uv)
    P[2] = [0.0, 0.0, 0.0, 1.0]
    return P


def _estimate_swapped_uv(X, uv):
    return af.estimate_affine_camera(X, uv[:, ::-1])


def _estimate_t2_sign(X, uv):
    P = af.estimate_affine_camera(X, uv)
    P[:2, 3] = uv.mean(axis=0) + P[:2, :3] @ X.mean(axis=0)
    return P


def _estimate_half_pixel(X, uv):
    P = af.estimate_affine_camera(X, uv)
    P[:2, 3] += 0.5
    return P


def _estimate_scaling_not_undone(X, uv):
    um, s = uv.mean(axis=0), uv.std()
    return af.estimate_affine_camera(X, (uv - um) / s)


def _estimate_points_on_pixels(X, uv):
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    M2 = np.linalg.lstsq(uv - um, X - Xm, rcond=None)[0]
    return np.vstack([np.c_[M2, um - M2 @ Xm], [0.0, 0.0, 0.0, 1.0]])


def _estimate_rank_two(X, uv):
    P = af.estimate_affine_camera(X, uv)
    P[1, :3] = P[0, :3]   # the same row fitted twice
    return P


def _estimate_centred_in_place(X, uv):
    """Right numbers, but centres the caller's arrays in place (X -= ..., uv -= ...)."""
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    X -= Xm
    uv -= um
    M2 = np.linalg.lstsq(X, uv, rcond=None)[0].T
    return np.vstack([np.c_[M2, um - M2 @ Xm], [0.0, 0.0, 0.0, 1.0]])


def _estimate_mean_axis_1(X, uv):
    Xm, um = X.mean(axis=1, keepdims=True), uv.mean(axis=1, keepdims=True)
    M2 = np.linalg.lstsq(X - Xm, uv - um, rcond=None)[0].T
    return np.vstack([np.c_[M2, uv.mean(axis=0) - M2 @ X.mean(axis=0)], [0.0, 0.0, 0.0, 1.0]])


def _estimate_mean_of_everything(X, uv):
    Xm, um = X.mean(), uv.mean()
    M2 = np.linalg.lstsq(X - Xm, uv - um, rcond=None)[0].T
    return np.vstack([np.c_[M2, um - M2 @ np.full(3, Xm)], [0.0, 0.0, 0.0, 1.0]])


def estimate_affine_camera(X, uv):
    """Least-squares affine camera (H&Z algorithm 7.2): centre both point sets, then solve for M2."""
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    M2 = np.linalg.lstsq(X - Xm, uv - um, rcond=None)[0].T   # (2, 3): uv - um = M2 (X - Xm)
    P = np.zeros((3, 4))
    P[:2, :3], P[:2, 3] = M2, um - M2 @ Xm                   # the centroids correspond
    P[2, 3] = 1.0
    return P


register_exercise(Exercise(
    name="estimate_affine_camera",
    lesson="05",
    reference=af.estimate_affine_camera,
    cases=_estimate_cases,
    compare=same_array(rtol=1e-7, atol=1e-7),
    diagnose=_estimate_diagnosis,
    wrong_variants=(
        (_estimate_four_points, "all the points"),
        (_estimate_dlt, "last row of an affine camera"),
        (_estimate_reshaped, "transpose it"),
        (_estimate_uncentred, "centre both point sets"),
        (_estimate_no_translation, "translation column"),
        (_estimate_dlt_last_row_forced, "last row overwritten"),
        (_estimate_swapped_uv, "u and v are swapped"),
        (_estimate_t2_sign, "sign flipped"),
        (_estimate_half_pixel, "half a pixel"),
        (_estimate_scaling_not_undone, "not undo it"),
        (_estimate_points_on_pixels, "regressed the world points on the pixels"),
        (_estimate_rank_two, "rank < 2"),
        (_estimate_centred_in_place, "changed its input `X`, `uv` in place"),
        (lambda X, uv: af.estimate_affine_camera(1000 * X, uv), "unit slip by 1000"),
        (lambda X, uv: af.estimate_affine_camera(X, 1000 * uv), "unit slip by 1000"),
        (lambda X, uv: af.estimate_affine_camera(X, uv + 1), "off by one pixel"),
        (lambda X, uv: -af.estimate_affine_camera(X, uv), "-1 times the least-squares one"),
        (_estimate_mean_axis_1, "axis=1"),
        (_estimate_mean_of_everything, "no axis"),
    ),
    teaching=estimate_affine_camera,
))
