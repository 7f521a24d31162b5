"""Exercises for lesson 04, the projective camera P = K [R | t]."""
from __future__ import annotations

import numpy as np

from .. import camera as cm
from ._core import Exercise, register_exercise, same_array, shape_problem


def _cameras():
    """Realistic cameras (fx about 800, 640x480) in varied poses, one with skew."""
    return [
        cm.Camera.look_at([4.0, -3.0, 2.0], [0.0, 0.0, 0.5]),
        cm.Camera.look_at([-2.0, -5.0, 1.5], [0.3, 0.2, 0.8], K=cm.intrinsic_matrix(760, 820, 300, 250, 3.0)),
        cm.Camera(cm.intrinsic_matrix(900, 900, 330, 230), cm.rotation_from_euler(0.1, -0.2, 0.3), [0.2, -0.1, 6.0]),
    ]


def _world_points():
    rng = np.random.default_rng(4)
    return rng.uniform(-1.0, 1.0, (6, 3)) + [0.0, 0.0, 0.5]


# -- project_points -------------------------------------------------------------------

def _project_cases():
    X = _world_points()
    return [(c.P, X) for c in _cameras()] + [(-3.0 * _cameras()[0].P, X)]


def _project_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    P, X = args
    if problem:
        if np.shape(got) == (len(X), 3):
            return problem + ". You returned homogeneous pixels: divide by the third coordinate and drop it."
        if np.shape(got) == (3, len(X)):
            return problem + ". Points are rows: compute X_h @ P.T, not P @ X_h."
        return problem
    g = np.asarray(got, dtype=float)
    Xh = np.hstack([X, np.ones((len(X), 1))])
    x = Xh @ P.T
    if np.allclose(g, x[:, :2], rtol=1e-6, atol=1e-6):
        return "you kept (x, y) without dividing by the third coordinate w = depth: u = x / w, v = y / w."
    if np.allclose(g, (X @ P[:, :3].T)[:, :2] / (X @ P[:, :3].T)[:, 2:], rtol=1e-6):
        return "you ignored the fourth column of P (the translation): lift X to (X, Y, Z, 1) first."
    return "project with x = P (X, Y, Z, 1)^T, then (u, v) = (x / w, y / w)."


def project_points(P, X):
    """Pixels of (N, 3) world points: x = P (X, 1), then divide by the third coordinate."""
    X = np.asarray(X, dtype=float)
    Xh = np.hstack([X, np.ones((len(X), 1))])   # (N, 4) homogeneous world points
    x = Xh @ np.asarray(P).T                    # points are rows: (P Xh^T)^T = Xh P^T
    return x[:, :2] / x[:, 2:3]


register_exercise(Exercise(
    name="project_points",
    lesson="04",
    reference=cm.project_points,
    cases=_project_cases,
    compare=same_array(rtol=1e-8, atol=1e-6),
    diagnose=_project_diagnosis,
    wrong_variants=(
        (lambda P, X: (np.hstack([X, np.ones((len(X), 1))]) @ P.T)[:, :2], "without dividing"),
        (lambda P, X: (X @ P[:, :3].T)[:, :2] / (X @ P[:, :3].T)[:, 2:], "fourth column"),
        (lambda P, X: np.hstack([X, np.ones((len(X), 1))]) @ P.T, "homogeneous pixels"),
    ),
    teaching=project_points,
))


# -- camera_centre ----------------------------------------------------------------------

def _centre_cases():
    return [(c.P,) for c in _cameras()] + [(-0.01 * _cameras()[1].P,)]


def _centre_diagnosis(args, got, expected) -> str:
    (P,) = args
    g = np.asarray(got, dtype=float) if got is not None else None
    if g is not None and g.shape == (3,):
        return ("you returned a 3-vector; return the homogeneous centre (X, Y, Z, 1), "
                "the null vector of P (P C = 0).")
    problem = shape_problem(got, expected)
    if problem:
        return problem
    residual = np.linalg.norm(P @ g) / (np.linalg.norm(P) * max(np.linalg.norm(g), 1e-300))
    if residual > 1e-8:
        return (f"P C is not 0 (relative |P C| = {residual:.3g}). The centre is the null space of P: "
                f"the last right singular vector of np.linalg.svd(P), or (-M^-1 p4, 1).")
    return (f"P C = 0, but your last coordinate is {g[3]:.4g}: the null vector is defined only up to scale; "
            f"divide it by its last entry so that its last coordinate is 1 (C = (X, Y, Z, 1)).")


def camera_centre(P):
    """The homogeneous centre C with P C = 0: P's right null vector, scaled to w = 1."""
    _, _, Vt = np.linalg.svd(P)
    C = Vt[-1]                 # the right singular vector of the zero singular value
    return C / C[3]


register_exercise(Exercise(
    name="camera_centre",
    lesson="04",
    reference=cm.camera_centre,
    cases=_centre_cases,
    compare=same_array(rtol=1e-8, atol=1e-10),  # the prompt fixes the scale: last entry 1
    diagnose=_centre_diagnosis,
    wrong_variants=(
        (lambda P: -np.linalg.solve(P[:, :3], P[:, 3]), "returned a 3-vector"),
        (lambda P: np.append(-P[:, 3], 1.0), "P C is not 0"),  # confuses t with the centre
        (lambda P: np.linalg.svd(P)[2][-1], "last coordinate is 1"),  # the unit null vector, not scaled
    ),
    teaching=camera_centre,
))


# -- rq_decomposition ----------------------------------------------------------------------
# (The whole decomposition returns four arrays of different shapes, which the checker cannot
# print; the exercise is its heart, M = K R, and the lesson derives t and C from it.)

def _rq_cases():
    cams = _cameras()
    return [(cams[0].P[:, :3],), (2.5 * cams[1].P[:, :3],), (0.003 * cams[2].P[:, :3],),
            (cm.intrinsic_matrix(700, 650, 300, 200, 5.0) @ cm.rotation_from_axis_angle([0.3, -2.0, 0.5]),)]


def _rq_compare(got, expected) -> bool:
    try:
        K, R = (np.asarray(g, dtype=float) for g in got)
    except (TypeError, ValueError):
        return False
    return K.shape == R.shape == (3, 3) and bool(np.allclose(K, expected[0], rtol=1e-7, atol=1e-7)
                                                  and np.allclose(R, expected[1], rtol=1e-7, atol=1e-7))


def _rq_diagnosis(args, got, expected) -> str:
    (M,) = args
    try:
        K, R = (np.asarray(g, dtype=float) for g in got)
        assert K.shape == R.shape == (3, 3)
    except (TypeError, ValueError, AssertionError):
        return "return a pair (K, R) of (3, 3) arrays"
    if np.isclose(K[2, 2], 1.0) and not np.isclose(abs(M[2] @ M[2]), 1.0):
        return ("you divided K by K[2, 2], so K R = M / K[2, 2] and no longer M; and a negative K[2, 2] "
                "does not fix the signs. Keep K unnormalised (K[2, 2] carries M's scale) and fix the signs "
                "with D = diag(sign(diag(K))): K D and D R.")
    if not np.allclose(K @ R, M, rtol=1e-6, atol=1e-6 * np.abs(M).max()):
        if np.allclose(R @ K, M, rtol=1e-6, atol=1e-6 * np.abs(M).max()):
            return "you computed M = Q K (a QR decomposition); the camera needs M = K R with K on the left (RQ)."
        if np.allclose(K @ R.T, M, rtol=1e-6, atol=1e-6 * np.abs(M).max()):
            return "R is transposed: M = K R."
        if _signs_fixed_in_k_only(K, R, M):
            return ("you fixed the signs of K (K D) but not of R: K R = (K D)(D R), so apply the same "
                    "D = diag(sign(diag(K))) to R's rows too (D R), or K R no longer equals M.")
        return "K R does not reproduce M; an RQ decomposition must satisfy M = K R exactly."
    if np.abs(np.tril(K, -1)).max() > 1e-9 * np.abs(K).max():
        return "K must be upper triangular."
    if np.any(np.diag(K) < 0):
        return ("K has a negative diagonal entry: fix the signs. RQ is unique only up to D = diag(+-1); "
                "use K D and D R with D = diag(sign(diag(K))).")
    return "K R = M with K positive upper triangular, but the factors differ; is R orthogonal?"


def _signs_fixed_in_k_only(K, R, M) -> bool:
    """True if K D R = M for some D = diag(+-1) other than I (K's columns flipped, R's rows not)."""
    scale = 1e-6 * np.abs(M).max()
    for signs in np.array(np.meshgrid(*[[1.0, -1.0]] * 3)).reshape(3, -1).T[1:]:
        if np.allclose(K @ np.diag(signs) @ R, M, rtol=1e-6, atol=scale):
            return True
    return False


def _rq_signs_of_k_only(M):
    from scipy.linalg import rq

    K, R = rq(M)
    return K @ np.diag(np.sign(np.diag(K))), R


def _rq_no_sign_fix(M):
    from scipy.linalg import rq

    return rq(M)


def _rq_normalised_no_sign_fix(M):
    from scipy.linalg import rq

    K, R = rq(M)
    return K / K[2, 2], R


def _rq_qr(M):
    Q, U = np.linalg.qr(M)
    return U, Q


def rq_decomposition(M):
    """M = K R with K upper triangular (positive diagonal) and R orthogonal, from numpy's QR."""
    E = np.eye(3)[::-1]                 # the exchange matrix reverses row order; E = E^T = E^-1
    Q, U = np.linalg.qr((E @ M).T)      # (E M)^T = Q U, so M = (E U^T E)(E Q^T)
    K, R = E @ U.T @ E, E @ Q.T         # E U^T E is upper triangular
    D = np.diag(np.sign(np.diag(K)))    # K R = (K D)(D R): flip signs so diag(K) > 0
    return K @ D, D @ R


register_exercise(Exercise(
    name="rq_decomposition",
    lesson="04",
    reference=cm.rq_decomposition,
    cases=_rq_cases,
    compare=_rq_compare,
    diagnose=_rq_diagnosis,
    wrong_variants=(
        (_rq_no_sign_fix, "fix the signs"),
        (_rq_normalised_no_sign_fix, "divided K by K[2, 2]"),
        (_rq_qr, "QR decomposition"),
        (_rq_signs_of_k_only, "apply the same"),
        (lambda M: (lambda K, R: (K, R.T))(*cm.rq_decomposition(M)), "transposed"),
    ),
    teaching=rq_decomposition,
))
