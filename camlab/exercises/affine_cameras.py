"""Exercises for lesson 05, affine cameras."""
from __future__ import annotations

import numpy as np

from .. import affine as af
from .. import camera as cm
from ._core import Exercise, register_exercise, same_array, shape_problem



# -- affine_approximation ------------------------------------------------------------------

def _approx_cases():
    return [
        (cm.Camera.look_at([4.0, -3.0, 2.0], [0.0, 0.0, 0.5]), np.array([0.0, 0.0, 0.5])),
        (cm.Camera.look_at([-6.0, -8.0, 3.0], [0.5, 0.0, 0.0], K=cm.intrinsic_matrix(1200, 1100, 310, 250)),
         np.array([0.2, 0.3, 0.4])),
        (cm.Camera(cm.intrinsic_matrix(800, 800, 320, 240), cm.rotation_from_euler(0.2, 0.1, -0.3), [0.1, 0.2, 9.0]),
         np.array([1.0, -0.5, 0.3])),
    ]


def _approx_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return the 3x4 affine camera."
    camera, X0 = args
    g = np.asarray(got, dtype=float)
    if not np.allclose(g[2], [0.0, 0.0, 0.0, 1.0], atol=1e-9):
        if abs(g[2, 3]) > 1e-12 and np.allclose(g[2, :3], 0.0, atol=1e-9):
            return "the last row is (0, 0, 0, d0): divide the whole matrix by d0 so it is (0, 0, 0, 1)."
        return "the last row must be (0, 0, 0, 1): replace r3 . X + t3 by the constant reference depth d0."
    d0_origin = camera.t[2]
    E = np.zeros((3, 4))
    E[:2, :3], E[:2, 3], E[2, 3] = camera.R[:2], camera.t[:2], d0_origin
    if np.allclose(g, camera.K @ E / d0_origin, atol=1e-7):
        return ("you used d0 = t3, the depth of the world origin; use the depth of the reference point, "
                "d0 = r3 . X0 + t3.")
    if not np.allclose(cm.project_points(g, X0), camera.project(X0), atol=1e-6):
        return "the reference point must image where the perspective camera puts it; use d0 = r3 . X0 + t3."
    return "the matrix images X0 correctly but differs elsewhere: P = K [[r1, t1], [r2, t2], [0, d0]] / d0."


def _approx_origin_depth(camera, X0):
    E = np.zeros((3, 4))
    E[:2, :3], E[:2, 3], E[2, 3] = camera.R[:2], camera.t[:2], camera.t[2]
    return camera.K @ E / camera.t[2]


def _approx_unnormalised(camera, X0):
    d0 = camera.R[2] @ X0 + camera.t[2]
    E = np.zeros((3, 4))
    E[:2, :3], E[:2, 3], E[2, 3] = camera.R[:2], camera.t[:2], d0
    return camera.K @ E


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
        (_approx_origin_depth, "depth of the world origin"),
        (_approx_unnormalised, "divide the whole matrix by d0"),
        (lambda camera, X0: camera.P, "last row must be"),
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
        return "the last row of an affine camera is (0, 0, 0, 1); estimate only the top 2x4 block (8 numbers)."
    M2, t2 = g[:2, :3], g[:2, 3]
    M2_expected = expected[:2, :3]
    if np.allclose(M2, M2_expected.T.reshape(2, 3), atol=1e-6):
        return ("M2 is scrambled: lstsq returns the (3, 2) matrix M2^T; transpose it (.T), do not reshape it to (2, 3).")
    uncentred = np.linalg.lstsq(X, uv, rcond=None)[0].T
    if np.allclose(M2, uncentred, atol=1e-6):
        return ("you regressed the pixels on the raw world points, so the fit had no constant term and M2 absorbed "
                "the offset: centre both point sets first (or append a column of ones to X).")
    if np.allclose(t2, 0.0, atol=1e-6) or np.allclose(t2, uv.mean(axis=0), atol=1e-6):
        return ("the translation column is wrong: after fitting M2 on centred points, the centroids must "
                "correspond, t2 = mean(uv) - M2 @ mean(X).")
    r_got = np.sqrt(np.mean(np.sum((cm.project_points(g, X) - uv) ** 2, axis=1)))
    r_exp = np.sqrt(np.mean(np.sum((cm.project_points(expected, X) - uv) ** 2, axis=1)))
    return (f"your camera's RMS residual is {r_got:.3f} px, the least-squares optimum is {r_exp:.3f} px: use all "
            f"the points in one least-squares solve (np.linalg.lstsq), not an exact fit to a few of them.")


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
    ),
    teaching=estimate_affine_camera,
))
