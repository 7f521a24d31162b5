"""Tests for camlab.calibration: detection, Zhang's stages, LM refinement, coach, undistortion, files.

Ground truth comes from the virtual camera (camlab.render via make_synthetic_views and the
bundled rendered set in data/); OpenCV is run live on the same corners for cross-checks.
"""

import cv2
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from camlab import calibration as C
from camlab._validate import CamlabInputError, DegenerateError
from camlab.calibration.refinement import BlockNormal, project_views
from camlab.camera import nearest_rotation, rotation_from_axis_angle, rotation_from_euler
from camlab.data import load_calibration_set
from camlab.fixtures.calibration import bundled_calibration
from camlab.homography import pose_homography
from camlab.optimise import dense_damped_solve, lm_step
from camlab.render import align_detected_corners, project

K_TRUE = np.array([[820.0, 0.0, 322.4], [0.0, 818.0, 236.8], [0.0, 0.0, 1.0]])
D_TRUE = np.array([-0.21, 0.09, 0.0006, -0.0004, -0.02])


@pytest.fixture(scope="module")
def bundled():
    return load_calibration_set()


@pytest.fixture(scope="module")
def noisy15():
    s = C.make_synthetic_views(15, 0.2, rng=np.random.default_rng(7))
    return s, C.calibrate_camera(s.object_points, s.image_points, s.image_size)


def _opencv(obj, imgs, size, flags=0):
    objs = [np.asarray(obj, np.float32)] * len(imgs)
    pts = [np.asarray(p, np.float32).reshape(-1, 1, 2) for p in imgs]
    crit = (cv2.TERM_CRITERIA_COUNT + cv2.TERM_CRITERIA_EPS, 100, 1e-15)
    return cv2.calibrateCameraExtended(
        objs, pts, tuple(size), None, None, flags=flags, criteria=crit
    )


# ---------------------------------------------------------------- board and detection


def test_board_points_order_and_units():
    P = C.board_points((9, 6), 0.025)
    assert P.shape == (54, 3)
    np.testing.assert_allclose(P[1], [0.025, 0, 0])
    np.testing.assert_allclose(P[9], [0, 0.025, 0])
    np.testing.assert_allclose(P[-1], [0.2, 0.125, 0])
    assert C.parse_pattern("9X6") == (9, 6)


@pytest.mark.parametrize(
    "pattern, match", [("9-6", "expected inner corners"), ((1, 6), "at least 2 x 2")]
)
def test_board_points_bad_pattern(pattern, match):
    with pytest.raises(CamlabInputError, match=match):
        C.board_points(pattern, 0.025)
    with pytest.raises(CamlabInputError, match="square_size: expected a positive"):
        C.board_points((9, 6), 0.0)


def test_find_chessboard_matches_the_rendered_truth(bundled):
    det = C.find_chessboard(bundled.images[0], (9, 6))
    assert det.found and det.reason == "" and det.corners.shape == (54, 2)
    c = align_detected_corners(det.corners, bundled.corners[0])
    err = np.linalg.norm(c - bundled.corners[0], axis=1)
    assert err.max() < 0.25 and np.sqrt(np.mean(err**2)) < 0.1
    # the fixed order: starts at the end nearer the image's top-left
    assert det.corners[0].sum() < det.corners[-1].sum()
    # colour input works too (and gives the same corners)
    rgb = np.dstack([bundled.images[0]] * 3)
    np.testing.assert_allclose(C.find_chessboard(rgb, "9x6").corners, det.corners, atol=1e-6)


@pytest.mark.parametrize("dtype", [np.float64, np.float32, np.uint16])
def test_find_chessboard_on_a_colour_image_of_any_dtype(bundled, dtype):
    """The docstring promises any dtype: a float64 RGB photo used to raise cv2.error (colour
    conversion ran before the dtype was normalised, and cvtColor rejects float64)."""
    grey = bundled.images[0]
    scale = {np.float64: 1 / 255, np.float32: 1 / 255, np.uint16: 257}[dtype]
    rgb = (np.dstack([grey] * 3).astype(float) * scale).astype(dtype)
    det = C.find_chessboard(rgb, (9, 6))
    assert det.found
    ref = C.find_chessboard(grey, (9, 6)).corners
    assert np.abs(det.corners - ref).max() < 0.05  # the same grey levels up to the 0..255 stretch


def test_find_chessboard_explains_failures(bundled):
    img = bundled.images[0]
    assert (
        "inner corners" in C.find_chessboard(img, (10, 7)).reason
        and "--pattern 9x6" in C.find_chessboard(img, (10, 7)).reason
    )
    blank = C.find_chessboard(np.full_like(img, 128), (9, 6))
    assert not blank.found and blank.corners is None and "contrast" in blank.reason
    gt = bundled.corners[0]
    cut = np.ascontiguousarray(img[:, : int(np.sort(gt[:, 0])[-15])])
    assert "cut off" in C.find_chessboard(cut, (9, 6)).reason
    assert "too blurry" in C.find_chessboard(cv2.GaussianBlur(img, (0, 0), 30), (9, 6)).reason
    with pytest.raises(CamlabInputError, match="image: expected an image of shape \\(H, W\\)"):
        C.find_chessboard(np.zeros((4, 4, 2)), (9, 6))


def test_find_chessboard_answers_a_photo_seen_again_from_memory(bundled, monkeypatch):
    """A photo asked again (the same pixels, pattern and max_side) is not detected again: the
    answer is the first one's, as a fresh copy; other pixels, patterns or max_side detect anew."""
    from camlab.calibration import detection

    monkeypatch.setattr(detection, "_SEEN", type(detection._SEEN)(keep=64))
    img = bundled.images[3]
    calls = []
    find = detection._find
    monkeypatch.setattr(detection, "_find", lambda *a: calls.append(a[1:]) or find(*a))
    first = C.find_chessboard(img, (9, 6))
    first.corners[:] = -1.0  # the caller's copy: changing it leaves the remembered answer alone
    again = C.find_chessboard(img.copy(), "9x6")
    fresh = find(img, detection.PatternSize(9, 6), 1600)
    assert calls == [((9, 6), 1600)]
    assert again == fresh._replace(corners=again.corners)
    assert np.array_equal(again.corners, fresh.corners)
    C.find_chessboard(img, (9, 6), max_side=None)
    C.find_chessboard(img, (10, 7))
    other = img.copy()
    other[0, 0] ^= 1  # one grey level of one pixel
    C.find_chessboard(other, (9, 6))
    assert len(calls) == 4
    monkeypatch.setattr(detection._SEEN, "keep", 2)
    C.find_chessboard(bundled.images[4], (9, 6))
    assert len(detection._SEEN) == 2


# ---------------------------------------------------------------- Zhang's stages, noise-free


def _exact_views(n=6, seed=0):
    return C.make_synthetic_views(n, 0.0, dist=None, rng=np.random.default_rng(seed))


def test_zhang_constraints_vanish_at_the_true_b():
    s = _exact_views()
    Kinv = np.linalg.inv(K_TRUE)
    B = Kinv.T @ Kinv
    b = B[[0, 0, 1, 0, 1, 2], [0, 1, 1, 2, 2, 2]]
    for R, t in zip(s.R, s.t, strict=True):
        H = pose_homography(K_TRUE, R, t)
        V = C.zhang_constraints(H)
        assert V.shape == (2, 6)
        assert np.abs(V @ b).max() < 1e-12 * np.abs(V).max() * np.abs(b).max()
        # v_ij^T b = h_i^T B h_j
        assert C.zhang_v(H, 0, 2) @ b == pytest.approx(H[:, 0] @ B @ H[:, 2])


@pytest.mark.parametrize("skew", [False, True])
def test_closed_form_K_and_poses_from_exact_homographies(skew):
    K = K_TRUE.copy()
    if skew:
        K[0, 1] = 1.5
    s = C.make_synthetic_views(5, 0.0, K=K, dist=None, rng=np.random.default_rng(1))
    Hs = C.view_homographies(s.object_points, s.image_points)
    K0 = C.intrinsics_from_homographies(Hs, skew=skew, image_size=(640, 480))
    np.testing.assert_allclose(K0, K, rtol=1e-7, atol=1e-6)
    R, t = C.extrinsics_from_homography(K0, Hs[2])
    np.testing.assert_allclose(R, s.R[2], atol=1e-8)
    np.testing.assert_allclose(t, s.t[2], rtol=1e-7)


def test_initial_radial_distortion_is_exact_for_radial_data():
    s = C.make_synthetic_views(6, 0.0, dist=[-0.25, 0.08, 0, 0, 0], rng=np.random.default_rng(2))
    k = C.initial_radial_distortion(K_TRUE, s.object_points, s.image_points, s.R, s.t)
    np.testing.assert_allclose(k, [-0.25, 0.08], rtol=1e-9)


def test_linear_distortion_with_homography_poses_has_the_wrong_sign_and_the_alternation_fixes_it():
    # The lesson's camera: barrel distortion k1 = -0.21, k2 = +0.09, corner noise 0.2 px.
    s = C.make_synthetic_views(12, 0.2, rng=np.random.default_rng(3))
    Hs = C.view_homographies(s.object_points, s.image_points)
    K0 = C.intrinsics_from_homographies(Hs, image_size=s.image_size)
    poses = [C.extrinsics_from_homography(K0, H) for H in Hs]
    linear = C.initial_radial_distortion(
        K0, s.object_points, s.image_points, [p[0] for p in poses], [p[1] for p in poses]
    )
    assert linear[0] > 0 > s.dist[0]  # the poses absorbed the distortion: wrong sign
    start = C.closed_form_with_distortion(s.object_points, s.image_points, s.image_size)
    assert len(start.rounds) == 3 and start.dist[2:].tolist() == [0, 0, 0]
    assert start.dist[0] == pytest.approx(s.dist[0], rel=0.03)
    assert 0 < start.dist[1] < 2 * s.dist[1]  # right sign, right size; k2 is weakly determined
    np.testing.assert_allclose(np.diag(start.K)[:2], np.diag(s.K)[:2], rtol=5e-3)
    assert start.rounds[-1][2] < start.rounds[0][2]  # the rms falls as the rounds alternate


def test_closed_form_with_distortion_rejects_zero_rounds():
    s = C.make_synthetic_views(4, 0.0, rng=np.random.default_rng(1))
    with pytest.raises(CamlabInputError, match="rounds"):
        C.closed_form_with_distortion(s.object_points, s.image_points, s.image_size, rounds=0)


@given(st.integers(0, 10_000))
def test_nearest_rotation_is_a_rotation_and_fixes_rotations(seed):
    rng = np.random.default_rng(seed)
    M = rng.normal(size=(3, 3))
    R = nearest_rotation(M)
    np.testing.assert_allclose(R.T @ R, np.eye(3), atol=1e-12)
    assert np.linalg.det(R) == pytest.approx(1.0)
    Q = rotation_from_axis_angle(rng.normal(size=3))
    np.testing.assert_allclose(nearest_rotation(Q), Q, atol=1e-12)
    # it is the closest: no nearby rotation does better
    for _ in range(5):
        Q2 = rotation_from_axis_angle(rng.normal(0, 0.05, 3)) @ R
        assert np.linalg.norm(Q2 - M) >= np.linalg.norm(R - M) - 1e-12


def test_intrinsics_from_b_rejects_an_indefinite_b():
    with pytest.raises(DegenerateError, match="indefinite"):
        C.intrinsics_from_b([1.0, 0.0, -1.0, 0.0, 0.0, 1.0])


# ---------------------------------------------------------------- refinement internals


def test_analytic_jacobian_matches_finite_differences():
    rng = np.random.default_rng(4)
    g = np.array([800.0, 790.0, 320.0, 240.0, 0.7, -0.2, 0.05, 0.001, -0.002, 0.01])
    poses = np.array([[0.3, -0.2, 0.1, 0.02, -0.01, 0.5], [-0.1, 0.4, 2.0, -0.05, 0.03, 0.4]])
    X = np.concatenate([rng.uniform(-0.1, 0.1, (2, 7, 2)), np.zeros((2, 7, 1))], axis=-1)
    _, Jg, Jp = project_views(g, poses, X, jac=True)
    for k in range(10):
        h = 1e-6 * max(abs(g[k]), 1.0)
        gp, gm = g.copy(), g.copy()
        gp[k] += h
        gm[k] -= h
        num = (project_views(gp, poses, X) - project_views(gm, poses, X)) / (2 * h)
        np.testing.assert_allclose(Jg[..., k], num, rtol=1e-5, atol=1e-6)
    for k in range(6):
        pp, pm = poses.copy(), poses.copy()
        pp[:, k] += 1e-7
        pm[:, k] -= 1e-7
        num = (project_views(g, pp, X) - project_views(g, pm, X)) / 2e-7
        np.testing.assert_allclose(Jp[..., k], num, rtol=1e-5, atol=1e-4)


def test_the_pose_jacobian_is_the_chain_rule_point_by_point():
    """project_views multiplies -[RX]x Jl one view at a time (all its points in one product) and
    differentiates the distortion unchecked: the readable per-point chain gives the same numbers."""
    from camlab.calibration.refinement import _rotations_and_left_jacobians
    from camlab.camera import cross_matrix, division_jacobian
    from camlab.distortion import distortion_jacobian

    rng = np.random.default_rng(6)
    g = np.array([800.0, 790.0, 320.0, 240.0, 0.7, -0.2, 0.05, 0.001, -0.002, 0.01])
    poses = np.c_[rng.normal(0, 0.5, (5, 3)), rng.normal(0, 0.05, (5, 2)), rng.uniform(0.4, 1, 5)]
    X = np.concatenate([rng.uniform(-0.1, 0.1, (5, 12, 2)), np.zeros((5, 12, 1))], axis=-1)
    _, _, Jp = project_views(g, poses, X, jac=True)
    R, Jl = _rotations_and_left_jacobians(poses[:, :3])
    for v in range(5):
        for m in range(12):
            RX = R[v] @ X[v, m]
            Xc = RX + poses[v, 3:]
            Jd = distortion_jacobian(Xc[:2] / Xc[2], g[5:])
            A = np.array([[g[0], g[4]], [0.0, g[1]]]) @ Jd
            dXc = A @ division_jacobian(Xc)
            want = np.hstack([dXc @ (-cross_matrix(RX) @ Jl[v]), dXc])
            np.testing.assert_allclose(Jp[v, m], want, rtol=1e-13, atol=1e-13 * np.abs(want).max())


def test_schur_complement_solve_equals_the_dense_solve():
    rng = np.random.default_rng(5)
    V, M, ni = 4, 10, 9
    Ji, Jp, r = (
        rng.normal(size=(V, 2 * M, ni)),
        rng.normal(size=(V, 2 * M, 6)),
        rng.normal(size=(V, 2 * M)),
    )
    J = np.zeros((V * 2 * M, ni + 6 * V))
    for v in range(V):
        J[v * 2 * M : (v + 1) * 2 * M, :ni] = Ji[v]
        J[v * 2 * M : (v + 1) * 2 * M, ni + 6 * v : ni + 6 * v + 6] = Jp[v]
    A = BlockNormal(Ji, Jp, r)
    np.testing.assert_allclose(A.gradient(), J.T @ r.ravel(), rtol=1e-12)
    np.testing.assert_allclose(A.diagonal(), np.diag(J.T @ J), rtol=1e-12)
    for mu in (0.0, 1e-3, 10.0):
        np.testing.assert_allclose(
            A.solve(mu), dense_damped_solve(J.T @ J, J.T @ r.ravel(), mu), rtol=1e-8, atol=1e-10
        )


def test_reproject_matches_opencv_project_points():
    rng = np.random.default_rng(6)
    X = np.column_stack([rng.uniform(-0.1, 0.1, (20, 2)), np.zeros(20)])
    rvec, tvec = np.array([0.2, -0.3, 0.1]), np.array([0.01, 0.02, 0.5])
    ref = cv2.projectPoints(X, rvec, tvec, K_TRUE, D_TRUE)[0].reshape(-1, 2)
    np.testing.assert_allclose(C.reproject(X, K_TRUE, D_TRUE, rvec, tvec), ref, atol=1e-9)


# ---------------------------------------------------------------- calibrate_camera: accuracy


def test_noise_free_recovery_to_1e6_relative():
    s = C.make_synthetic_views(12, 0.0, rng=np.random.default_rng(11))
    res = C.calibrate_camera(s.object_points, s.image_points, s.image_size)
    assert res.converged
    assert np.abs(res.K - K_TRUE).max() / K_TRUE[0, 0] < 1e-6
    assert np.abs(res.dist - D_TRUE).max() / np.abs(D_TRUE).max() < 1e-6
    assert res.rms < 1e-6
    np.testing.assert_allclose(res.R, s.R, atol=1e-7)
    np.testing.assert_allclose(res.tvecs, s.t, atol=1e-8)
    # the LM cost history starts at Zhang's closed form and ends near 0
    assert res.cost_history[0] > 1 and res.cost_history[-1] < 1e-12
    assert np.all(np.diff(res.cost_history) <= 0)


def test_rms_matches_the_maximum_likelihood_expectation(noisy15):
    s, res = noisy15
    N = res.n_points
    p = len(res.free_params) + 6 * res.n_views
    expected = 0.2 * np.sqrt(1 - p / (2 * N))  # per-coordinate rms (H&Z 5.1.3)
    assert res.rms / np.sqrt(2) == pytest.approx(expected, rel=0.05)


def test_errors_are_consistent_with_the_reported_std():
    z = []
    for seed in range(4):
        s = C.make_synthetic_views(15, 0.2, rng=np.random.default_rng(100 + seed))
        res = C.calibrate_camera(s.object_points, s.image_points, s.image_size)
        p = res.intrinsics
        for name, true in zip(("fx", "fy", "cx", "cy"), (820.0, 818.0, 322.4, 236.8), strict=True):
            z.append((p[name] - true) / res.std[name])
    z = np.array(z)
    assert np.all(np.abs(z) < 3), z
    assert 0.3 < np.sqrt(np.mean(z**2)) < 2.0  # neither over- nor under-confident


def test_agrees_with_opencv_on_the_same_corners(noisy15):
    s, res = noisy15
    rms, K, dist, rv, tv, std_i, _, per_view = _opencv(
        s.object_points, s.image_points, s.image_size
    )
    assert abs(res.K[0, 0] / K[0, 0] - 1) < 1e-3 and abs(res.K[1, 1] / K[1, 1] - 1) < 1e-3
    assert abs(res.K[0, 2] - K[0, 2]) < 0.5 and abs(res.K[1, 2] - K[1, 2]) < 0.5
    assert res.rms == pytest.approx(rms, rel=0.01)
    np.testing.assert_allclose(res.per_view_rms, per_view.ravel(), rtol=0.01)
    ours_std = [res.std[k] for k in ("fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2", "k3")]
    np.testing.assert_allclose(ours_std, std_i.ravel()[:9], rtol=0.05)


def test_agrees_with_opencv_on_detected_corners_of_rendered_images(bundled):
    corners = [C.find_chessboard(img, (9, 6)).corners for img in bundled.images[:10]]
    obj = C.board_points((9, 6), 0.025)
    res = C.calibrate_camera(obj, corners, (640, 480), fix=("k3",))
    rms, K, dist, *_ = _opencv(obj, corners, (640, 480), flags=cv2.CALIB_FIX_K3)
    assert abs(res.K[0, 0] / K[0, 0] - 1) < 1e-3 and abs(res.K[1, 1] / K[1, 1] - 1) < 1e-3
    assert abs(res.K[0, 2] - K[0, 2]) < 0.5 and abs(res.K[1, 2] - K[1, 2]) < 0.5
    assert res.rms == pytest.approx(rms, rel=0.01)
    assert res.dist[4] == 0.0
    # and close to the camera that rendered them
    assert abs(res.K[0, 0] / 820.0 - 1) < 0.005 and abs(res.dist[0] + 0.21) < 0.01


def test_skew_and_fixed_parameters():
    K = K_TRUE.copy()
    K[0, 1] = 2.0
    s = C.make_synthetic_views(
        8, 0.0, K=K, dist=[-0.2, 0.05, 0, 0, 0], rng=np.random.default_rng(8)
    )
    res = C.calibrate_camera(
        s.object_points, s.image_points, s.image_size, skew=True, fix=("p1", "p2", "k3")
    )
    assert res.K[0, 1] == pytest.approx(2.0, abs=1e-6)
    assert res.dist[2:].tolist() == [0.0, 0.0, 0.0] and res.std["k3"] == 0.0
    assert "skew" in res.free_params and "k3" not in res.free_params


# ---------------------------------------------------------------- calibrate_camera: bad input


def test_bad_input_messages():
    s = C.make_synthetic_views(4, 0.1, rng=np.random.default_rng(9))
    with pytest.raises(CamlabInputError, match="at least 3 views"):
        C.calibrate_camera(s.object_points, s.image_points[:2], s.image_size)
    bad = [p.copy() for p in s.image_points]
    bad[1][5] = np.nan
    with pytest.raises(CamlabInputError, match=r"image_points\[1\]: corner 5 is NaN"):
        C.calibrate_camera(s.object_points, bad, s.image_size)
    with pytest.raises(CamlabInputError, match=r"image_points\[2\]: expected 54 points"):
        C.calibrate_camera(
            s.object_points,
            [p if i != 2 else p[:50] for i, p in enumerate(s.image_points)],
            s.image_size,
        )
    X3 = s.object_points.copy()
    X3[:, 2] = np.linspace(0, 0.1, len(X3))
    with pytest.raises(CamlabInputError, match="flat target with Z = 0"):
        C.calibrate_camera(X3, s.image_points, s.image_size)
    with pytest.raises(CamlabInputError, match="fix: unknown parameter"):
        C.calibrate_camera(s.object_points, s.image_points, s.image_size, fix=("focal",))
    with pytest.raises(CamlabInputError, match="image_size: expected"):
        C.calibrate_camera(s.object_points, s.image_points, 640)


def test_boards_parallel_to_the_image_are_degenerate():
    obj = C.board_points((9, 6), 0.025)
    rng = np.random.default_rng(10)
    views = []
    for _ in range(5):
        R = rotation_from_euler(0, 0, rng.uniform(-0.5, 0.5))
        t = np.array([rng.uniform(-0.12, 0.0), rng.uniform(-0.08, 0.0), rng.uniform(0.4, 0.6)])
        views.append(project(obj, K_TRUE, R, t, None) + rng.normal(0, 0.1, (54, 2)))
    with pytest.raises(DegenerateError, match="same orientation"):
        C.calibrate_camera(obj, views, (640, 480))


def test_unequal_point_counts_per_view():
    s = C.make_synthetic_views(6, 0.0, rng=np.random.default_rng(12))
    keep = [np.arange(54) if v % 2 else np.arange(0, 54, 2) for v in range(6)]
    res = C.calibrate_camera(
        [s.object_points[k] for k in keep],
        [p[k] for p, k in zip(s.image_points, keep, strict=True)],
        s.image_size,
    )
    assert np.abs(res.K - K_TRUE).max() < 1e-5 and [len(r) for r in res.residuals][:2] == [27, 54]


# ---------------------------------------------------------------- from images


def test_calibrate_from_images_reports_and_skips_failures(bundled, tmp_path):
    imgs = list(bundled.images[:5])
    imgs.insert(1, np.full((480, 640), 90, np.uint8))  # no board
    imgs.append(bundled.images[5][:240, :320])  # a different size
    out = C.calibrate_from_images(imgs + [str(tmp_path / "missing.png")], (9, 6), 0.025)
    assert out.used == [0, 2, 3, 4, 5]
    assert set(out.failed) == {1, 6, 7}
    assert (
        "contrast" in out.failed[1]
        and "differs" in out.failed[6]
        and "could not read" in out.failed[7]
    )
    assert out.result.n_views == 5 and "skipped image[1]" in out.report()
    assert abs(out.result.K[0, 0] / 820 - 1) < 0.01


def test_calibrate_from_images_needs_three_good_views(bundled):
    imgs = [bundled.images[0], np.zeros((480, 640), np.uint8), bundled.images[1]]
    with pytest.raises(
        CamlabInputError,
        match=r"need at least 3 images with the board detected, got 2 of 3:\n"
        r"  image\[1\]: no chessboard found",
    ):
        C.calibrate_from_images(imgs, "9x6", 0.025)
    with pytest.raises(CamlabInputError, match="no files match"):
        C.calibrate_from_images("/nonexistent/*.png", "9x6", 0.025)


# ---------------------------------------------------------------- coach


def test_coach_points_at_the_bad_view_and_the_empty_edge():
    s = C.make_synthetic_views(12, 0.2, rng=np.random.default_rng(13))
    pts = [p.copy() for p in s.image_points]
    pts[4] += np.random.default_rng(0).normal(0, 2.0, pts[4].shape)  # a badly detected view
    res = C.calibrate_camera(s.object_points, pts, s.image_size)
    rep = C.coach(res)
    assert rep.worst_views[0] == 4 and rep.error_ratio[4] > 3
    assert any(a.startswith("view 4 has") for a in rep.advice)
    # only the left half of the image covered
    left = [i for i, p in enumerate(s.image_points) if p[:, 0].max() < 380]
    s2 = C.make_synthetic_views(40, 0.1, rng=np.random.default_rng(14))
    keep = [p for p in s2.image_points if p[:, 0].max() < 420][:8]
    res2 = C.calibrate_camera(s2.object_points, keep, s2.image_size)
    rep2 = C.coach(res2)
    assert any("right edge" in a for a in rep2.advice), rep2.advice
    assert 0 < rep2.coverage < 1 and left is not None


def test_projection_uncertainty_grows_towards_the_corners(noisy15):
    _, res = noisy15
    us, vs, sig = C.projection_uncertainty(res, step=40)
    assert sig.shape == (len(vs), len(us)) and np.all(sig > 0)
    assert sig[0, 0] > sig[len(vs) // 2, len(us) // 2]
    # the centre is about as uncertain as the principal point
    assert sig.min() == pytest.approx(max(res.std["cx"], res.std["cy"]), rel=0.5)


# ---------------------------------------------------------------- undistortion and files


@pytest.mark.parametrize("alpha", [0.0, 0.5, 1.0])
def test_optimal_new_camera_matrix_matches_opencv(alpha):
    ours = C.optimal_new_camera_matrix(K_TRUE, D_TRUE, (640, 480), alpha)
    ref, _ = cv2.getOptimalNewCameraMatrix(K_TRUE, D_TRUE, (640, 480), alpha)
    np.testing.assert_allclose(ours, ref, rtol=5e-3, atol=1.0)


def test_undistort_trades_black_borders_for_lost_pixels(bundled):
    cut = C.undistort(bundled.images[0], K=K_TRUE, dist=D_TRUE, alpha=0.0)
    full = C.undistort(bundled.images[0], K=K_TRUE, dist=D_TRUE, alpha=1.0)
    assert cut.image.shape == (480, 640)
    assert cut.black_fraction < 0.01 < cut.lost_fraction
    assert full.lost_fraction < 0.01 < full.black_fraction
    assert (full.image == 0).mean() > (cut.image == 0).mean()
    with pytest.raises(CamlabInputError, match="alpha: expected a number in \\[0, 1\\]"):
        C.optimal_new_camera_matrix(K_TRUE, D_TRUE, (640, 480), 1.5)


@pytest.mark.parametrize("suffix", [".json", ".yaml"])
def test_save_is_loadable_by_opencv(noisy15, tmp_path, suffix):
    _, res = noisy15
    path = C.save_calibration(res, tmp_path / f"cam{suffix}")
    fs = cv2.FileStorage(str(path), cv2.FILE_STORAGE_READ)
    np.testing.assert_allclose(fs.getNode("camera_matrix").mat(), res.K)
    np.testing.assert_allclose(fs.getNode("distortion_coefficients").mat().ravel(), res.dist)
    assert fs.getNode("rms").real() == pytest.approx(res.rms)
    fs.release()
    K, d, size = C.load_calibration(path)
    np.testing.assert_allclose(K, res.K)
    assert size == (640, 480)
    with pytest.raises(CamlabInputError, match="expected a file name ending in .json, .yaml"):
        C.save_calibration(res, tmp_path / "cam.txt")


# ---------------------------------------------------------------- lesson 08 demos and exercises


def test_accuracy_demo_recalibrates_and_reports_consistent_errors():
    from camlab.widgets import camera_calibration as demos

    demo = demos.accuracy_vs_views()
    demo.set(n_views=10, noise=0.0)
    np.testing.assert_allclose(demo.state["K"], K_TRUE, atol=1e-6)
    demo.set(noise=0.5)
    err, std = demo.state["errors"], demo.state["std"]
    assert np.all(np.abs(err) < 4 * std) and np.all(std > 0.5)
    before = demo.view.pixels()
    demo.set(n_views=3)
    assert demo.state["std"][0] > std[0]  # fewer views: larger uncertainty
    assert not np.array_equal(before, demo.view.pixels())
    np.testing.assert_allclose(demo.state["z"], demo.state["errors"] / demo.state["std"])


def test_accuracy_demo_plots_errors_against_three_sigma_in_pixels():
    from camlab.widgets import camera_calibration as demos

    demo = demos.accuracy_vs_views()
    demo.set(n_views=3, noise=1.0)  # the setting the lesson recommends: cx lands far outside
    err, std = demo.state["errors"], demo.state["std"]
    assert np.abs(demo.state["z"]).max() > 3
    ax = demo.figure.axes[0]
    dots = next(
        line for line in ax.get_lines() if line.get_animated() and len(line.get_xdata()) == 4
    )
    np.testing.assert_allclose(dots.get_ydata(), np.abs(err))  # the dots are the errors, px
    bars = next(c for c in ax.collections if c.get_animated())
    tops = [seg[1][1] for seg in bars.get_segments()]
    np.testing.assert_allclose(tops, 3 * std)  # the bars reach 3 reported sigma
    assert f"{int(np.sum(np.abs(err) > 3 * std))} of 4 beyond 3σ" in ax.get_title()
    big = np.abs(err).max()
    demo.set(n_views=15, noise=0.3)
    assert np.abs(demo.state["errors"]).max() < big / 5  # more views, less noise: smaller errors
    demo.set(noise=0.0)
    assert "no noise" in ax.get_title()
    assert np.all(
        np.array(dots.get_ydata()) >= ax.get_ylim()[0]
    )  # rounding noise drawn at the floor


def test_bundled_calibration_is_computed_once_and_read_only():
    out = bundled_calibration()
    assert bundled_calibration() is out
    assert out.used == list(range(16)) and out.failed == {}
    for a in (
        out.result.K,
        out.result.dist,
        out.result.rvecs,
        out.result.residuals[0],
        out.detections[0],
    ):
        with pytest.raises(ValueError, match="read-only"):
            a[0] = 0  # shared by every caller: an edit must not change the next one's answer


def test_view_inspector_shows_the_chosen_view(bundled):
    from camlab.data import load_calibration_set
    from camlab.widgets import camera_calibration as demos

    out = bundled_calibration()
    demo = demos.view_inspector(out, load_calibration_set().images)
    demo.set(view=4)
    assert demo.state["image_index"] == out.used[4]
    assert demo.state["rms"] == pytest.approx(out.result.per_view_rms[4])
    assert out.result.rms < 0.1  # the rendered corners are detected to a few hundredths of a pixel
    assert f"rms {out.result.per_view_rms[4]:.3f} px" in demo.figure.axes[0].get_title()


def test_view_inspector_defaults_to_the_real_photos():
    from camlab.fixtures.calibration import real_calibration
    from camlab.widgets import camera_calibration as demos

    real, photos = real_calibration()
    demo = demos.view_inspector()
    demo.set(view=5, magnify=100.0)
    assert "calib_left06" in demo.figure.axes[0].get_title()
    assert demo.state["rms"] == pytest.approx(real.result.per_view_rms[5])
    assert 0.15 < real.result.rms < 0.25  # real corners: four times the rendered set's error
    assert "arrows ×100" in demo.figure.axes[0].get_title()
    with pytest.raises(ValueError, match="read-only"):
        photos[0][0, 0] = 0


def test_undistort_demo_tradeoff_moves_with_alpha():
    from camlab.widgets import camera_calibration as demos

    demo = demos.undistort_alpha()
    demo.set(alpha=1.0)
    assert demo.state["lost_fraction"] < 0.01 < demo.state["black_fraction"]
    demo.set(alpha=0.0)
    assert demo.state["black_fraction"] < 0.01 < demo.state["lost_fraction"]


def test_exercise_diagnoses_specific_mistakes():
    from camlab.exercises import all_exercises, check

    all_exercises()
    H = np.array([[2.0, 0.3, 5.0], [-0.1, 1.5, 2.0], [0.01, 0.02, 1.0]])
    with pytest.raises(AssertionError, match="rows of H"):
        check("zhang_constraints", lambda H: C.zhang_constraints(H.T))
    with pytest.raises(AssertionError, match="wrong sign"):
        check("lm_step", lambda J, r, mu: -lm_step(J, r, mu))
    with pytest.raises(AssertionError, match="reflection"):
        check("nearest_rotation", lambda M: (lambda U, S, Vt: U @ Vt)(*np.linalg.svd(M)))
    assert C.zhang_constraints(H).shape == (2, 6)


def test_warm_start_reaches_the_same_minimum(noisy15):
    s, cold = noisy15
    pts = [p + 0.05 * np.random.default_rng(1).normal(size=p.shape) for p in s.image_points]
    ref = C.calibrate_camera(s.object_points, pts, s.image_size)
    warm = C.calibrate_camera(
        s.object_points,
        pts,
        s.image_size,
        K_guess=cold.K,
        dist_guess=cold.dist,
        pose_guess=np.column_stack([cold.rvecs, cold.tvecs]),
    )
    assert warm.initial["closed_form"] is False and warm.initial["homographies"] is None
    np.testing.assert_allclose(warm.K, ref.K, rtol=1e-6)  # 1e-6 of 322 px is far below the 2 px std
    np.testing.assert_allclose(warm.dist, ref.dist, rtol=1e-4, atol=1e-6)
    assert warm.iterations <= ref.iterations
    with pytest.raises(CamlabInputError, match="pose_guess: pass K_guess too"):
        C.calibrate_camera(s.object_points, pts, s.image_size, pose_guess=np.zeros((15, 6)))
    with pytest.raises(CamlabInputError, match=r"pose_guess: expected \(15, 6\)"):
        C.calibrate_camera(
            s.object_points, pts, s.image_size, K_guess=cold.K, pose_guess=np.zeros((3, 6))
        )


def test_plot_extrinsics_puts_each_board_where_the_truth_has_it(bundled):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from camlab.plotting import calibration as cplot
    from camlab.plotting import scene3d

    out = bundled_calibration()
    fig = plt.figure()
    ax = scene3d.axes3d(fig, 111)
    boards = cplot.plot_extrinsics(ax, out.result)
    obj = C.board_points(bundled.pattern_size, bundled.square)
    truth = np.stack([obj @ R.T + t for R, t in zip(bundled.R, bundled.t, strict=True)])
    np.testing.assert_allclose(
        boards, truth, atol=2e-3
    )  # within 2 mm of where the renderer put them
    assert np.all(boards[:, :, 2] > 0)  # in front of the camera
    drawn = [line for line in ax.get_lines() if len(line.get_data_3d()[0]) == 5]
    assert len(drawn) >= 16  # one closed outline per view
    plt.close(fig)


def test_synthetic_views_fixed_tilt():
    """tilt=(a, a) turns every board by exactly a from facing the camera; None keeps 15-50 degrees."""
    a = np.radians(30.0)
    s = C.make_synthetic_views(5, 0.0, tilt=(a, a), rng=np.random.default_rng(1))
    assert np.allclose(np.arccos(np.abs(s.R[:, 2, 2])), a, atol=1e-12)
    free = C.make_synthetic_views(20, 0.0, rng=np.random.default_rng(1))
    angles = np.degrees(np.arccos(np.abs(free.R[:, 2, 2])))
    assert angles.min() >= 15 - 1e-9 and angles.max() <= 50 + 1e-9 and np.ptp(angles) > 10


def test_view_inspector_caps_long_arrows():
    """At x300 the longest real residuals would leave the photo: drawn at most 60 px long, black, counted."""
    from camlab.widgets import camera_calibration as demos

    demo = demos.view_inspector()
    demo.set(view=4, magnify=300.0)
    quiver = [c for c in demo.figure.axes[0].collections if hasattr(c, "U")][0]
    lengths = np.hypot(quiver.U, quiver.V)
    assert demo.state["longest_arrow_px"] > 60 and demo.state["capped_arrows"] > 0
    black = np.all(quiver.get_facecolors()[:, :3] == 0, axis=1)
    assert lengths.max() == pytest.approx(60.0) and np.all(lengths[~black] <= 60.0)
    assert black.sum() == demo.state["capped_arrows"]  # capped arrows drawn black, as section 5's
    tips = quiver.get_offsets() + np.column_stack([quiver.U, quiver.V])
    assert np.all(
        (tips >= -0.5 - 1e-9) & (tips <= np.array([639.5, 479.5]) + 1e-9)
    )  # inside the photo
    demo.set(magnify=10.0)
    assert demo.state["capped_arrows"] == 0
