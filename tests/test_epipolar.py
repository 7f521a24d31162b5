"""Tests for camlab.epipolar: F, E, epipoles, epipolar lines, triangulation, with OpenCV cross-checks."""

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from camlab import epipolar as ep
from camlab._validate import CamlabInputError, DegenerateError
from camlab.camera import Camera, reprojection_errors, rotation_from_euler
from camlab.projective import to_homogeneous


def _rig(baseline=(0.3, -0.05, 0.02), seed=0, n=120):
    rng = np.random.default_rng(seed)
    c1 = Camera.look_at([0, -3, 0.5], [0, 0, 0.5])
    c2 = Camera.look_at(np.array([0, -3, 0.5]) + baseline, [0.05, 0, 0.5])
    X = rng.uniform(-0.8, 0.8, (n, 3)) + [0, 0, 0.5]
    return c1, c2, X, c1.project(X), c2.project(X)


def test_fundamental_from_cameras_satisfies_epipolar_constraint():
    c1, c2, X, x1, x2 = _rig()
    F = ep.fundamental_from_cameras(c1, c2)
    alg = np.sum(to_homogeneous(x2) @ F * to_homogeneous(x1), axis=1)
    assert np.abs(alg).max() < 1e-10
    assert np.linalg.matrix_rank(F, tol=1e-10) == 2
    assert np.allclose(
        F, ep.fundamental_from_cameras(c1.P, c2.P), atol=1e-12
    )  # camera and P forms agree


def test_estimate_equals_truth_up_to_scale_and_matches_opencv():
    c1, c2, X, x1, x2 = _rig()
    F = ep.estimate_fundamental_matrix(x1, x2)
    assert np.allclose(F, ep.fundamental_from_cameras(c1, c2), atol=1e-8)
    rng = np.random.default_rng(3)
    n1, n2 = x1 + rng.normal(0, 0.5, x1.shape), x2 + rng.normal(0, 0.5, x2.shape)
    F = ep.estimate_fundamental_matrix(n1, n2)
    Fc, _ = cv2.findFundamentalMat(n1, n2, cv2.FM_8POINT)
    # Same algorithm: the same Sampson error on the noisy data, and close to truth on the true points.
    ours, theirs = (
        np.median(ep.sampson_distance(F, n1, n2)),
        np.median(ep.sampson_distance(Fc, n1, n2)),
    )
    assert ours <= 1.01 * theirs
    assert np.median(ep.sampson_distance(F, x1, x2)) < 0.2


def test_normalisation_matters():
    c1, c2, X, x1, x2 = _rig()
    rng = np.random.default_rng(5)
    n1, n2 = x1 + rng.normal(0, 1.0, x1.shape), x2 + rng.normal(0, 1.0, x2.shape)
    good = np.median(ep.sampson_distance(ep.estimate_fundamental_matrix(n1, n2), x1, x2))
    bad = np.median(
        ep.sampson_distance(ep.estimate_fundamental_matrix(n1, n2, normalise=False), x1, x2)
    )
    assert good < bad


def test_ransac_finds_inliers_and_beats_or_matches_opencv():
    c1, c2, X, x1, x2 = _rig(n=150)
    rng = np.random.default_rng(1)
    n1, n2 = x1 + rng.normal(0, 0.3, x1.shape), x2 + rng.normal(0, 0.3, x2.shape)
    n2[:45] = rng.uniform(0, 640, (45, 2))
    res = ep.ransac_fundamental_matrix(n1, n2, threshold=1.0, rng=np.random.default_rng(2))
    truth = np.arange(150) >= 45
    assert res.inliers[:45].sum() <= 2 and res.inliers[45:].sum() >= 95
    Fc, mask = cv2.findFundamentalMat(n1, n2, cv2.FM_RANSAC, 1.0, 0.999)
    mask = mask.ravel().astype(bool)
    # Each F's Sampson error on the other's inliers (the cross-check).
    ours_on_cv = np.median(ep.sampson_distance(res.F, n1[mask], n2[mask]))
    cv_on_ours = np.median(ep.sampson_distance(Fc, n1[res.inliers], n2[res.inliers]))
    assert ours_on_cv < 1.0 and cv_on_ours < 1.0
    assert np.median(ep.sampson_distance(res.F, x1[truth], x2[truth])) < 0.2
    assert np.allclose(res.residuals, ep.sampson_distance(res.F, n1, n2))


def test_ransac_all_outliers_raises():
    rng = np.random.default_rng(0)
    with pytest.raises(DegenerateError, match="no hypothesis"):
        ep.ransac_fundamental_matrix(
            rng.uniform(0, 640, (40, 2)),
            rng.uniform(0, 640, (40, 2)),
            threshold=0.01,
            max_iters=200,
            rng=rng,
        )


def test_bad_input_messages():
    c1, c2, X, x1, x2 = _rig()
    with pytest.raises(
        CamlabInputError, match=r"x1: expected \(N, 2\) with N >= 8 point pairs, got shape \(7, 2\)"
    ):
        ep.estimate_fundamental_matrix(x1[:7], x2[:7])
    with pytest.raises(
        CamlabInputError, match=r"x1, x2: expected the same number of points .*got 120 and 119"
    ):
        ep.estimate_fundamental_matrix(x1, x2[:-1])
    with pytest.raises(CamlabInputError, match="threshold"):
        ep.ransac_fundamental_matrix(x1, x2, threshold=-1)
    with pytest.raises(CamlabInputError, match="image: expected 1 or 2"):
        ep.epipolar_lines(np.eye(3), [1, 2], image=3)
    with pytest.raises(CamlabInputError, match="non-zero"):
        ep.epipoles(np.zeros((3, 3)))


def test_coplanar_points_are_degenerate():
    c1, c2, X, _, _ = _rig()
    Xp = X.copy()
    Xp[:, 1] = 0.2  # all on the plane y = 0.2
    with pytest.raises(DegenerateError, match="rank < 8"):
        ep.estimate_fundamental_matrix(c1.project(Xp), c2.project(Xp))
    # Tiny noise hides the exact rank drop; the homography test still sees the plane.
    rng = np.random.default_rng(0)
    x1 = c1.project(Xp) + rng.normal(0, 1e-5, (len(Xp), 2))
    with pytest.raises(DegenerateError, match="one homography"):
        ep.estimate_fundamental_matrix(x1, c2.project(Xp))
    # A pure rotation is the same degeneracy.
    c3 = c1.replace(
        R=rotation_from_euler(0.0, 0.1, 0.0) @ c1.R, t=rotation_from_euler(0.0, 0.1, 0.0) @ c1.t
    )
    with pytest.raises(DegenerateError):
        ep.estimate_fundamental_matrix(c1.project(X), c3.project(X))


def test_identical_cameras_have_no_fundamental_matrix():
    c1, *_ = _rig()
    with pytest.raises(DegenerateError, match="same centre"):
        ep.fundamental_from_cameras(c1, c1)
    with pytest.raises(DegenerateError, match="same centre"):
        ep.fundamental_from_cameras(c1.P, c1.P)


def test_epipoles_are_the_other_camera_centres():
    c1, c2, *_ = _rig()
    F = ep.fundamental_from_cameras(c1, c2)
    e = ep.epipoles(F)
    assert np.allclose(F @ e.e1, 0, atol=1e-12) and np.allclose(F.T @ e.e2, 0, atol=1e-12)
    # e1 ~ P1 C2 (homogeneous: camera 2's centre is slightly behind camera 1, so Camera.project gives NaN)
    for e_, P, C in ((e.e1, c1.P, c2.centre), (e.e2, c2.P, c1.centre)):
        img = P @ np.append(C, 1.0)
        assert np.allclose(np.cross(e_, img / np.linalg.norm(img)), 0, atol=1e-12)


def test_parallel_cameras_put_epipoles_at_infinity():
    c1 = Camera.look_at([0, -3, 0.5], [0, 0, 0.5])
    c2 = c1.replace(t=c1.t - np.array([0.2, 0, 0]))  # moved 0.2 m along its own x axis
    F = ep.fundamental_from_cameras(c1, c2)
    e = ep.epipoles(F)
    assert abs(e.e1[2]) < 1e-12 and abs(e.e1[1]) < 1e-12
    lines = ep.epipolar_lines(F, [[100, 50], [300, 400]])
    assert np.allclose(np.abs(lines[:, :2]), [[0, 1], [0, 1]])  # horizontal rows
    assert np.allclose(-lines[:, 2] / lines[:, 1], [50, 400])


def test_epipolar_lines_pass_through_correspondences_and_match_opencv():
    c1, c2, X, x1, x2 = _rig()
    F = ep.fundamental_from_cameras(c1, c2)
    l2 = ep.epipolar_lines(F, x1, image=1)
    l1 = ep.epipolar_lines(F, x2, image=2)
    assert np.abs(np.sum(l2 * to_homogeneous(x2), axis=1)).max() < 1e-7
    assert np.abs(np.sum(l1 * to_homogeneous(x1), axis=1)).max() < 1e-7
    lc = cv2.computeCorrespondEpilines(x1.reshape(-1, 1, 2), 1, F).reshape(-1, 3)
    sign = np.sign(np.sum(lc[:, :2] * l2[:, :2], axis=1))[:, None]
    assert np.allclose(
        lc * sign, l2, atol=1e-6
    )  # the same lines (both have a^2 + b^2 = 1), up to sign
    single = ep.epipolar_lines(F, x1[0])
    assert single.shape == (3,) and np.allclose(single, l2[0])


def test_sampson_and_symmetric_distance_known_answer():
    F = np.array([[0, 0, 0], [0, 0, -1], [0, 1, 0.0]])  # rectified pair: rows match
    assert np.allclose(ep.epipolar_distance(F, [[0, 0]], [[5, 3]]), 3)
    assert np.allclose(ep.sampson_distance(F, [[0, 0]], [[5, 3]]), 3 / np.sqrt(2))
    assert float(ep.sampson_distance(F, [0, 0], [9, 0])) == 0


def test_essential_decomposition_and_recover_pose_match_opencv():
    c1, c2, X, x1, x2 = _rig()
    R, t = ep.relative_pose(c1, c2)
    E = ep.essential_matrix(R, t)
    cands = ep.decompose_essential_matrix(E)
    tn = t / np.linalg.norm(t)
    assert any(
        np.allclose(Rc, R, atol=1e-9) and np.allclose(tc, tn, atol=1e-9)
        for Rc, tc in zip(cands.R, cands.t, strict=True)
    )
    pose = ep.recover_pose(
        ep.essential_from_fundamental(ep.fundamental_from_cameras(c1, c2), c1.K), x1, x2, c1.K
    )
    assert np.allclose(pose.R, R, atol=1e-9) and np.allclose(pose.t, tn, atol=1e-9)
    assert sorted(pose.counts)[-1] == len(X) and sorted(pose.counts)[-2] < len(X) // 2 + 1
    _, Rc, tc, _ = cv2.recoverPose(E, x1, x2, c1.K)
    assert np.allclose(Rc, pose.R, atol=1e-8) and np.allclose(tc.ravel(), pose.t, atol=1e-8)
    Ec, _ = cv2.findEssentialMat(x1, x2, c1.K, cv2.RANSAC, 0.999, 0.5)
    assert (
        min(
            np.abs(Ec[:3] / np.linalg.norm(Ec[:3]) - s * E / np.linalg.norm(E)).max()
            for s in (1, -1)
        )
        < 1e-5
    )
    with pytest.raises(DegenerateError, match="not an essential matrix"):
        ep.decompose_essential_matrix(np.diag([1.0, 0.1, 0.0]))


def test_fundamental_essential_round_trip():
    c1, c2, *_ = _rig()
    F = ep.fundamental_from_cameras(c1, c2)
    E = ep.essential_from_fundamental(F, c1.K, c2.K)
    assert np.allclose(np.linalg.svd(E, compute_uv=False), [1, 1, 0], atol=1e-12)
    assert np.allclose(ep.fundamental_from_essential(E, c1.K, c2.K), F, atol=1e-9)


def test_triangulation_linear_exact_and_matches_opencv():
    c1, c2, X, x1, x2 = _rig()
    Xt = ep.triangulate_points(c1, c2, x1, x2)
    assert np.abs(Xt - X).max() < 1e-9
    Xc = cv2.triangulatePoints(c1.P, c2.P, x1.T, x2.T)
    assert np.abs((Xc[:3] / Xc[3]).T - X).max() < 1e-6
    assert ep.triangulate_points(c1.P, c2.P, x1[0], x2[0]).shape == (3,)


def test_triangulation_refinement_lowers_reprojection_error():
    c1, c2, X, x1, x2 = _rig(n=60)
    rng = np.random.default_rng(7)
    n1, n2 = x1 + rng.normal(0, 1.0, x1.shape), x2 + rng.normal(0, 1.0, x2.shape)
    lin = ep.triangulate_points(c1, c2, n1, n2)
    ref = ep.triangulate_points(c1, c2, n1, n2, refine=True)
    cost = lambda Y: reprojection_errors(c1, Y, n1) ** 2 + reprojection_errors(c2, Y, n2) ** 2  # noqa: E731
    assert np.all(cost(ref) <= cost(lin) + 1e-9)
    assert cost(ref).sum() < 0.999 * cost(lin).sum()
    # At the optimum the gradient vanishes: a small perturbation cannot do better.
    for d in np.eye(3) * 1e-5:
        assert np.all(cost(ref + d) >= cost(ref) - 1e-9)


@settings(max_examples=25, deadline=None)
@given(st.floats(-0.6, 0.6), st.floats(-0.3, 0.3), st.floats(0.05, 0.8), st.integers(0, 10_000))
def test_property_estimate_recovers_truth(yaw, pitch, base, seed):
    rng = np.random.default_rng(seed)
    c1 = Camera.look_at([0, -3, 0.5], [0, 0, 0.5])
    R2 = rotation_from_euler(pitch * 0.2, yaw * 0.2, 0.0) @ c1.R
    C2 = c1.centre + [base, 0.1 * base, 0.0]
    c2 = Camera(c1.K, R2, -R2 @ C2)
    X = rng.uniform(-0.7, 0.7, (30, 3)) + [0, 0, 0.5]
    x1, x2 = c1.project(X), c2.project(X)
    ok = np.all(np.isfinite(x1), axis=1) & np.all(np.isfinite(x2), axis=1)
    F = ep.estimate_fundamental_matrix(x1[ok], x2[ok])
    assert np.allclose(F, ep.fundamental_from_cameras(c1, c2), atol=1e-6)
    assert np.max(ep.sampson_distance(F, x1[ok], x2[ok])) < 1e-6


def test_rendered_rig_sift_matches_estimate_equals_truth_and_matches_opencv():
    """On the rendered rig (data/stereo): F from SIFT matches vs F from the true cameras, and vs OpenCV."""
    from camlab.data.stereo import load_stereo_rig
    from camlab.distortion import undistort_image, undistort_pixels

    rig = load_stereo_rig()
    c1, c2 = rig.camera1, rig.camera2
    L, R = undistort_image(rig.left, c1.K, c1.dist), undistort_image(rig.right, c2.K, c2.dist)
    sift = cv2.SIFT_create(1500)
    k1, d1 = sift.detectAndCompute(L, None)
    k2, d2 = sift.detectAndCompute(R, None)
    good = [m for m, n in cv2.BFMatcher().knnMatch(d1, d2, k=2) if m.distance < 0.8 * n.distance]
    x1 = np.array([k1[m.queryIdx].pt for m in good])
    x2 = np.array([k2[m.trainIdx].pt for m in good])
    res = ep.ransac_fundamental_matrix(x1, x2, threshold=1.0, rng=np.random.default_rng(0))
    F_true = ep.fundamental_from_cameras(c1.replace(dist=(0.0,) * 5), c2.replace(dist=(0.0,) * 5))
    # up to scale: the estimate agrees with the truth on the true correspondences (chessboard corners)
    t1 = undistort_pixels(rig.calib_corners_left.reshape(-1, 2), c1.K, c1.dist)
    t2 = undistort_pixels(rig.calib_corners_right.reshape(-1, 2), c2.K, c2.dist)
    assert np.median(ep.sampson_distance(F_true, t1, t2)) < 1e-6
    assert np.median(ep.sampson_distance(res.F, t1, t2)) < 0.1
    # and beats OpenCV's RANSAC estimate there (its final fit is not Sampson-weighted)
    Fc, mask = cv2.findFundamentalMat(x1, x2, cv2.FM_RANSAC, 1.0, 0.999)
    mask = mask.ravel().astype(bool)
    ours_on_cv = np.median(ep.sampson_distance(res.F, x1[mask], x2[mask]))
    cv_on_ours = np.median(ep.sampson_distance(Fc, x1[res.inliers], x2[res.inliers]))
    assert ours_on_cv <= 1.1 * cv_on_ours + 0.02
    assert np.median(ep.sampson_distance(res.F, t1, t2)) <= 1.1 * np.median(
        ep.sampson_distance(Fc, t1, t2)
    )
    assert res.inliers.sum() >= 0.9 * mask.sum()


def test_sampson_iterations_lower_the_geometric_error():
    c1, c2, X, x1, x2 = _rig(n=80)
    costs = []
    for seed in range(5):
        rng = np.random.default_rng(seed)
        n1, n2 = x1 + rng.normal(0, 1.0, x1.shape), x2 + rng.normal(0, 1.0, x2.shape)
        F0 = ep.estimate_fundamental_matrix(n1, n2)
        F1 = ep.estimate_fundamental_matrix(n1, n2, sampson_iterations=10)
        costs.append([np.sum(ep.sampson_distance(F, n1, n2) ** 2) for F in (F0, F1)])
        assert np.linalg.matrix_rank(F1, tol=1e-12) == 2
    costs = np.array(costs)
    # reweighting approximately minimises the Sampson cost (not exactly: rank 2 is imposed after each solve)
    assert np.all(costs[:, 1] <= 1.001 * costs[:, 0]) and costs[:, 1].sum() < costs[:, 0].sum()


def test_exactly_eight_pairs_are_enough():
    c1, c2, X, x1, x2 = _rig(n=8, seed=3)
    F = ep.estimate_fundamental_matrix(x1, x2)
    assert np.allclose(F, ep.fundamental_from_cameras(c1, c2), atol=1e-6)
    res = ep.ransac_fundamental_matrix(
        *_rig(n=9, seed=4)[3:], threshold=0.5, rng=np.random.default_rng(0)
    )
    assert res.inliers.all()


def test_epipolar_lines_are_nan_at_the_epipole():
    # forward motion: the left epipole is the image centre, where F x vanishes up to rounding
    from camlab import fixtures

    c1, c2 = fixtures.forward_pair(0.2, np.deg2rad(10))
    F = ep.fundamental_from_cameras(c1, c2)
    e1 = ep.epipoles(F).e1
    lines = ep.epipolar_lines(F, [e1[:2] / e1[2], [100.0, 50.0]])
    assert np.isnan(lines[0]).all()
    assert np.isfinite(lines[1]).all() and abs(np.hypot(*lines[1, :2]) - 1) < 1e-12
    # one pixel away it is a proper line again, through the right epipole
    l2 = ep.epipolar_lines(F, e1[:2] / e1[2] + [1.0, 0.0])
    e2 = ep.epipoles(F).e2
    assert abs(l2 @ e2) < 1e-9 * np.linalg.norm(e2)
