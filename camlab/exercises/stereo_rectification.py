"""Exercises for lesson 11, epipolar geometry and stereo rectification."""
from __future__ import annotations

import numpy as np

from .. import disparity, epipolar
from ..camera import Camera
from ..homography import hartley_normalization
from ._core import Exercise, register_exercise, same_array, same_up_to_scale, shape_problem


def _rig_points(seed: int, noise: float, n: int = 24, baseline=(0.3, 0.02, 0.01)):
    rng = np.random.default_rng(seed)
    c1 = Camera.look_at([0, -3, 0.5], [0, 0, 0.5])
    c2 = Camera.look_at(np.array([0, -3, 0.5]) + baseline, [0.1, 0, 0.5])
    X = rng.uniform(-0.8, 0.8, (n, 3)) + [0, 0, 0.5]
    x1, x2 = c1.project(X), c2.project(X)
    return x1 + rng.normal(0, noise, x1.shape), x2 + rng.normal(0, noise, x2.shape)


# --------------------------------------------------------------------------- the 8-point algorithm

def _eight_point_cases():
    return [_rig_points(0, 0.0), _rig_points(1, 0.5), _rig_points(2, 1.0, n=40, baseline=(0.5, -0.05, 0.1))]


def _eight_point_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". F is the (3, 3) matrix with x2_h @ F @ x1_h = 0."
    x1, x2 = args
    g = np.asarray(got, dtype=float)
    # judge the rank in normalised coordinates, where F's entries are all of order 1
    T1, T2 = hartley_normalization(x1), hartley_normalization(x2)
    s = np.linalg.svd(np.linalg.inv(T2).T @ g @ np.linalg.inv(T1), compute_uv=False)
    if s[2] > 1e-8 * s[0]:
        return ("your F has rank 3 (smallest singular value "
                f"{s[2] / s[0]:.2g} of the largest): enforce rank 2 by zeroing the smallest singular value, "
                "U diag(s1, s2, 0) V^T, so all epipolar lines meet in one epipole")
    if same_up_to_scale(g.T, expected, rtol=1e-5):
        return "your F is transposed: with rows (u'u, u'v, u', v'u, v'v, v', u, v, 1) the constraint is x2^T F x1 = 0"
    raw = epipolar.estimate_fundamental_matrix(x1, x2, normalize=False, plane_tol=0)
    if same_up_to_scale(g, raw, rtol=1e-4):
        return ("your F matches the 8-point algorithm without normalisation: normalise each image's points "
                "(centroid to 0, mean distance sqrt(2)) first, then undo it with F = T2^T F_n T1")
    err = np.median(epipolar.sampson_distance(g, x1, x2)) if np.any(g) else np.inf
    return (f"median Sampson error of your F on the input pairs is {err:.3g} px; check the row of the linear "
            "system (u'u, u'v, u', v'u, v'v, v', u, v, 1), the SVD (last row of V^T) and the un-normalisation")


def _no_rank2(x1, x2):
    a, b = np.asarray(x1, float), np.asarray(x2, float)
    T1, T2 = hartley_normalization(a), hartley_normalization(b)
    an = a @ T1[:2, :2].T + T1[:2, 2]
    bn = b @ T2[:2, :2].T + T2[:2, 2]
    A = np.column_stack([bn[:, 0] * an[:, 0], bn[:, 0] * an[:, 1], bn[:, 0], bn[:, 1] * an[:, 0],
                         bn[:, 1] * an[:, 1], bn[:, 1], an[:, 0], an[:, 1], np.ones(len(a))])
    F = np.linalg.svd(A)[2][-1].reshape(3, 3)
    return T2.T @ F @ T1


register_exercise(Exercise(
    name="eight_point",
    lesson="11",
    reference=epipolar.estimate_fundamental_matrix,
    cases=_eight_point_cases,
    compare=lambda got, expected: same_up_to_scale(got, expected, rtol=1e-5),
    diagnose=_eight_point_diagnosis,
    wrong_variants=(
        (_no_rank2, "rank 2"),
        (lambda x1, x2: epipolar.estimate_fundamental_matrix(x1, x2).T, "transposed"),
        (lambda x1, x2: epipolar.estimate_fundamental_matrix(x1, x2, normalize=False, plane_tol=0), "normalis"),
    ),
))


# --------------------------------------------------------------------------- epipoles from F

def _epipole_cases():
    F1 = epipolar.estimate_fundamental_matrix(*_rig_points(3, 0.0))
    c1 = Camera.look_at([0, -3, 0.5], [0, 0, 0.5])
    c2 = c1.replace(t=c1.t - np.array([0.2, 0.0, 0.0]))  # parallel cameras: epipoles at infinity
    F3 = epipolar.fundamental_from_cameras(c1, Camera.look_at([0.4, -2.5, 0.9], [0, 0, 0.5]))
    return [(F1,), (epipolar.fundamental_from_cameras(c1, c2),), (F3,)]


def _epipole_compare(got, expected) -> bool:
    try:
        e1, e2 = got
    except (TypeError, ValueError):
        return False
    return same_up_to_scale(e1, expected.e1, rtol=1e-6) and same_up_to_scale(e2, expected.e2, rtol=1e-6)


def _epipole_diagnosis(args, got, expected) -> str:
    (F,) = args
    try:
        e1, e2 = (np.asarray(e, dtype=float) for e in got)
    except (TypeError, ValueError):
        return "return two homogeneous 3-vectors (e1, e2): e1 in image 1 and e2 in image 2"
    for e, name in ((e1, "e1"), (e2, "e2")):
        if e.shape != (3,):
            return (f"{name} has shape {e.shape}; return homogeneous 3-vectors: an epipole can be at infinity "
                    f"(w = 0), which has no (u, v)")
    if same_up_to_scale(e1, expected.e2) and same_up_to_scale(e2, expected.e1):
        return "you swapped them: e1 is the right null vector (F e1 = 0), e2 the left one (F^T e2 = 0)"
    r1 = np.linalg.norm(F @ e1) / max(np.linalg.norm(e1), 1e-300)
    r2 = np.linalg.norm(F.T @ e2) / max(np.linalg.norm(e2), 1e-300)
    return (f"|F e1| / |e1| = {r1:.2g} and |F^T e2| / |e2| = {r2:.2g} should both be 0: take the last row of V^T "
            f"(for e1) and the last column of U (for e2) from the SVD F = U S V^T")


register_exercise(Exercise(
    name="epipoles",
    lesson="11",
    reference=epipolar.epipoles,
    cases=_epipole_cases,
    compare=_epipole_compare,
    diagnose=_epipole_diagnosis,
    wrong_variants=(
        (lambda F: tuple(reversed(epipolar.epipoles(F))), "swapped"),
        (lambda F: (np.linalg.svd(F)[2][0], np.linalg.svd(F)[0][:, 0]), "should both be 0"),
    ),
))


# --------------------------------------------------------------------------- depth from disparity

def _depth_cases():
    return [(np.array([80.0, 40.0, 16.0]), 800.0, 0.12), (np.array([[10.5, 64.0], [33.0, 7.25]]), 1200.0, 0.3)]


def _depth_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    d, f, B = args
    g = np.asarray(got, dtype=float)
    if np.allclose(g, d * B / f) or np.allclose(g, f * d / B):
        return "depth falls as disparity grows: Z = f B / d (similar triangles), not proportional to d"
    if np.allclose(g, B / d):
        return "you forgot the focal length: d is in pixels and B in metres, so Z = f B / d with f in pixels"
    return "compare with Z = f B / d at one pixel by hand"


register_exercise(Exercise(
    name="disparity_to_depth",
    lesson="11",
    reference=disparity.disparity_to_depth,
    cases=_depth_cases,
    compare=same_array(rtol=1e-9),
    diagnose=_depth_diagnosis,
    wrong_variants=(
        (lambda d, f, B: f * d / B, "Z = f B / d"),
        (lambda d, f, B: B / d, "focal length"),
    ),
))
