"""Tests for camlab.measurement: PnP against cv2.solvePnP, plane measurements, the depth law."""

import cv2
import numpy as np
import pytest

from camlab._validate import CamlabInputError, DegenerateError
from camlab.camera import rotation_from_axis_angle
from camlab.data.middlebury import load_middlebury
from camlab.fixtures.calibration import real_calibration
from camlab.measurement import (
    area_on_plane,
    depth_sigma,
    measure_on_plane,
    pixels_to_plane,
    project_pose,
    rectified_cameras,
    solve_pnp,
    triangulate_rectified,
)

# OpenCV's camera model has no skew (it reads fx, fy, cx, cy only), so K has none here.
K = np.array([[800.0, 0.0, 320.0], [0.0, 790.0, 240.0], [0.0, 0.0, 1.0]])
BOARD = np.hstack([np.mgrid[0:9, 0:6].T.reshape(-1, 2) * 0.025, np.zeros((54, 1))])
POSES = [([0.3, -0.2, 0.1], [-0.1, -0.05, 0.8]), ([2.9, 0.1, 0.2], [0.1, 0.05, 0.6])]


def _general_points():
    return np.random.default_rng(0).uniform(-0.2, 0.2, (30, 3))


def _tilted_plane():
    R = rotation_from_axis_angle([0.4, -0.3, 0.2])
    return BOARD @ R.T + [0.05, -0.02, 0.1]


@pytest.mark.parametrize(
    "points", [BOARD, _general_points(), _tilted_plane()], ids=["board", "general", "tilted"]
)
@pytest.mark.parametrize("pose", POSES, ids=["front", "turned"])
@pytest.mark.parametrize(
    "flag", [cv2.SOLVEPNP_ITERATIVE, cv2.SOLVEPNP_SQPNP], ids=["iterative", "sqpnp"]
)
def test_solve_pnp_matches_opencv_on_noise_free_points(points, pose, flag):
    R, t = rotation_from_axis_angle(pose[0]), np.array(pose[1])
    uv = project_pose(K, R, t, points)
    ours = solve_pnp(points, uv, K)
    _, rvec, tvec = cv2.solvePnP(points, uv, K, None, flags=flag)
    R_cv, t_cv = cv2.Rodrigues(rvec)[0], tvec.ravel()
    assert np.abs(ours.R - R_cv).max() < 1e-6
    assert np.linalg.norm(ours.t - t_cv) / np.linalg.norm(t_cv) < 1e-6
    assert np.allclose(ours.R, R, atol=1e-9) and np.allclose(ours.t, t, atol=1e-9)
    assert ours.rms < 1e-8
    assert ours.method == ("dlt" if points is not BOARD and points.shape == (30, 3) else "planar")


@pytest.fixture(scope="module")
def real():
    return real_calibration().calibration.result


def test_solve_pnp_rms_equals_opencv_on_the_real_photos(real):
    ratios = []
    for X, uv in zip(real.object_points, real.image_points, strict=True):
        ours = solve_pnp(X, uv, real.K, real.dist)
        _, rvec, tvec = cv2.solvePnP(X, uv, real.K, real.dist, flags=cv2.SOLVEPNP_ITERATIVE)
        proj = cv2.projectPoints(X, rvec, tvec, real.K, real.dist)[0].reshape(-1, 2)
        rms_cv = np.sqrt(np.mean(np.sum((proj - uv) ** 2, axis=1)))
        ratios.append(ours.rms / rms_cv)
        assert np.sqrt(np.mean(np.sum(ours.residuals**2, axis=1))) == pytest.approx(ours.rms)
    assert len(ratios) == 14
    assert np.all(np.abs(np.array(ratios) - 1) < 0.01), ratios


@pytest.mark.parametrize("mm", [0.003, 0.01, 0.03, 0.1, 0.2, 0.5, 1, 2, 5])
def test_solve_pnp_on_nearly_planar_points_matches_opencv(real, mm):
    """Board corners scattered off their plane: no mirrored pose, at every scatter (the DLT's
    sign from det M alone returned a pose 180 deg off in 8/10 seeds at 0.003-0.03 mm)."""
    X, uv = real.object_points[0], real.image_points[0]
    truth = solve_pnp(X, uv, real.K, real.dist)

    def angle(Ra, Rb):
        return np.degrees(np.arccos(np.clip((np.trace(Ra @ Rb.T) - 1) / 2, -1, 1)))

    for seed in range(10):
        rng = np.random.default_rng(seed)
        Xn = X + np.column_stack([np.zeros((54, 2)), rng.normal(0, mm / 1000, 54)])
        uvn = cv2.projectPoints(Xn, cv2.Rodrigues(truth.R)[0], truth.t, real.K, real.dist)[0]
        uvn = uvn.reshape(-1, 2) + rng.normal(0, truth.sigma, (54, 2))
        ours = solve_pnp(Xn, uvn, real.K, real.dist)
        _, rvec, tvec = cv2.solvePnP(Xn, uvn, real.K, real.dist, flags=cv2.SOLVEPNP_ITERATIVE)
        assert ours.method == ("planar" if mm <= 1 else "dlt")
        assert angle(ours.R, truth.R) < 0.2 and np.linalg.norm(ours.t - truth.t) < 5e-4
        assert angle(ours.R, cv2.Rodrigues(rvec)[0]) < 0.02
        assert np.linalg.norm(ours.t - tvec.ravel()) < 5e-5
        assert ours.rms < 0.3 and np.all((Xn @ ours.R.T + ours.t)[:, 2] > 0)


def test_solve_pnp_refuses_a_pose_with_points_behind_the_camera():
    X = _general_points()  # z from -0.2 to 0.2 m, seen from 0.1 m: 7 of the 30 are behind
    uv = project_pose(K, np.eye(3), np.array([0.0, 0.0, 0.1]), X)
    with pytest.raises(DegenerateError, match="7 of 30 points behind the camera"):
        solve_pnp(X, uv, K)


def _held_out(X, square=0.025):
    """Fit on the corners with even i + j; pairs of odd corners two squares apart."""
    ij = np.round(X[:, :2] / square).astype(int)
    fit = ij.sum(axis=1) % 2 == 0
    where = {tuple(k): n for n, k in enumerate(ij)}
    a, b = [], []
    for n, (i, j) in enumerate(ij):
        for di, dj in ((2, 0), (0, 2)):
            m = where.get((i + di, j + dj))
            if not fit[n] and m is not None:
                a.append(n)
                b.append(m)
    return fit, np.array(a), np.array(b)


def test_measure_on_plane_against_held_out_squares_on_the_real_photos(real):
    z_all, err_all = [], []
    for X, uv in zip(real.object_points, real.image_points, strict=True):
        fit, a, b = _held_out(X)
        pose = solve_pnp(X[fit], uv[fit], real.K, real.dist)
        m = measure_on_plane(pose, real.K, uv[a], uv[b], real.dist)
        err_all.append(m.value - 0.05)
        z_all.append((m.value - 0.05) / m.sigma)
    err, z = np.concatenate(err_all), np.concatenate(z_all)
    assert np.sqrt(np.mean(err**2)) < 0.0003  # 0.3 mm on 50 mm: 0.6 %
    assert 0.9 <= np.mean(np.abs(z) < 2) <= 0.995


def test_measure_on_plane_uncertainty_is_calibrated_on_synthetic_boards():
    rng = np.random.default_rng(1)
    R, t = rotation_from_axis_angle([0.5, -0.3, 0.1]), np.array([-0.1, -0.05, 0.7])
    uv_true = project_pose(K, R, t, BOARD)
    fit, a, b = _held_out(BOARD)
    inside, areas = [], []
    for _ in range(200):
        uv = uv_true + rng.normal(0, 0.3, uv_true.shape)
        pose = solve_pnp(BOARD[fit], uv[fit], K)
        m = measure_on_plane(pose, K, uv[a[:6]], uv[b[:6]])
        inside.append(np.abs(m.value - 0.05) < 2 * m.sigma)
        quad = uv[[0, 8, 53, 45]]
        ar = area_on_plane(pose, K, quad)
        areas.append(abs(ar.value[0] - 0.2 * 0.125) < 2 * ar.sigma[0])
    assert 0.92 <= np.mean(inside) <= 0.98
    assert 0.90 <= np.mean(areas) <= 0.99


def test_pixels_to_plane_inverts_the_projection_and_undistorts(real):
    X, uv = real.object_points[0], real.image_points[0]
    pose = solve_pnp(X, uv, real.K, real.dist)
    back = pixels_to_plane(pose, real.K, uv, real.dist)
    assert np.sqrt(np.mean(np.sum((back - X[:, :2]) ** 2, axis=1))) < 0.0005
    no_dist = pixels_to_plane(pose, real.K, uv)
    assert np.abs(no_dist - X[:, :2]).max() > 2 * np.abs(back - X[:, :2]).max()


def test_pose_covariance_predicts_the_spread_of_poses():
    rng = np.random.default_rng(2)
    R, t = rotation_from_axis_angle([0.3, -0.2, 0.1]), np.array([-0.1, -0.05, 0.8])
    uv_true = project_pose(K, R, t, BOARD)
    centres = []
    for _ in range(300):
        fit = solve_pnp(BOARD, uv_true + rng.normal(0, 0.5, uv_true.shape), K)
        centres.append(fit.centre)
    predicted = solve_pnp(BOARD, uv_true + rng.normal(0, 0.5, uv_true.shape), K).std()["centre"]
    spread = np.std(centres, axis=0)
    assert np.allclose(spread / predicted, 1, atol=0.2), (spread, predicted)


def test_triangulate_rectified_agrees_with_the_middlebury_calibration():
    mb = load_middlebury()
    v, u = np.nonzero(np.isfinite(mb.disparity))
    pick = np.random.default_rng(3).choice(len(u), 2000, replace=False)
    uv, d = np.column_stack([u[pick], v[pick]]).astype(float), mb.disparity[v[pick], u[pick]]
    P = triangulate_rectified(uv, d, mb.focal, mb.cx, mb.cy, mb.baseline, mb.doffs)
    assert np.allclose(P[:, 2], mb.focal * mb.baseline / (d + mb.doffs), rtol=1e-9)
    P1, P2 = rectified_cameras(mb.focal, mb.cx, mb.cy, mb.baseline, mb.doffs)
    back = np.hstack([P, np.ones((len(P), 1))]) @ P1.T
    assert np.allclose(back[:, :2] / back[:, 2:], uv, atol=1e-6)


def test_depth_law_matches_triangulated_errors_on_middlebury():
    mb = load_middlebury()
    rng = np.random.default_rng(4)
    v, u = np.nonzero(np.isfinite(mb.disparity))
    pick = rng.choice(len(u), 20000, replace=False)
    uv, d = np.column_stack([u[pick], v[pick]]).astype(float), mb.disparity[v[pick], u[pick]]
    Z = triangulate_rectified(uv, d, mb.focal, mb.cx, mb.cy, mb.baseline, mb.doffs)[:, 2]
    sigma_d = 0.5
    Zn = triangulate_rectified(
        uv, d + rng.normal(0, sigma_d, len(d)), mb.focal, mb.cx, mb.cy, mb.baseline, mb.doffs
    )[:, 2]
    edges = np.quantile(Z, np.linspace(0, 1, 6))
    for lo, hi in zip(edges[:-1], edges[1:], strict=True):
        inside = (Z >= lo) & (Z < hi)
        measured = np.std(Zn[inside] - Z[inside])
        predicted = np.sqrt(np.mean(depth_sigma(Z[inside], mb.focal, mb.baseline, sigma_d) ** 2))
        assert measured == pytest.approx(predicted, rel=0.08)


def test_depth_sigma_values():
    assert depth_sigma(2.0, 800, 0.1, 0.25) == pytest.approx(0.0125)
    assert np.allclose(
        depth_sigma([1.0, 2.0], 800, 0.1, 1.0) / depth_sigma(1.0, 800, 0.1, 1.0), [1, 4]
    )


@pytest.mark.parametrize(
    ("call", "words"),
    [
        (lambda: solve_pnp(BOARD[:3], np.zeros((3, 2)), K), ("object_points", "4")),
        (lambda: solve_pnp(BOARD, np.zeros((53, 2)), K), ("image_points", "same number")),
        (lambda: solve_pnp(BOARD, np.zeros((54, 3)), K), ("image_points",)),
        (lambda: solve_pnp(BOARD, np.zeros((54, 2)), np.eye(2)), ("K",)),
        (lambda: solve_pnp(BOARD, np.zeros((54, 2)), K, method="epnp"), ("method", "auto")),
        (
            lambda: solve_pnp(_general_points(), np.zeros((30, 2)), K, method="planar"),
            ("planar", "near one plane", "span 3-D"),
        ),
        (lambda: solve_pnp(BOARD, np.zeros((54, 2)), K, method="dlt"), ("dlt", "near one")),
        (lambda: solve_pnp(_general_points()[:5], np.zeros((5, 2)), K), ("N >= 6",)),
        (lambda: measure_on_plane("pose", K, [[0, 0]], [[1, 1]]), ("pose", "solve_pnp")),
        (lambda: depth_sigma(-1.0, 800, 0.1, 0.5), ("Z", "> 0")),
        (lambda: depth_sigma(1.0, 800, 0.0, 0.5), ("baseline",)),
        (lambda: depth_sigma(1.0, 800, 0.1, -0.5), ("sigma_d", ">= 0")),
        (
            lambda: triangulate_rectified([[1.0, 2.0]], [1.0, 2.0], 800, 320, 240, 0.1),
            ("disparity", "one"),
        ),
    ],
)
def test_bad_input_names_the_argument(call, words):
    with pytest.raises(CamlabInputError) as err:
        call()
    for w in words:
        assert w in str(err.value)


def test_bad_plane_inputs():
    uv = project_pose(K, np.eye(3), np.array([-0.1, -0.05, 0.8]), BOARD)
    pose = solve_pnp(BOARD, uv, K)
    with pytest.raises(CamlabInputError, match="pixels_a, pixels_b"):
        measure_on_plane(pose, K, uv[:3], uv[:2])
    with pytest.raises(CamlabInputError, match="pixel_sigma"):
        measure_on_plane(pose, K, uv[:3], uv[3:6], pixel_sigma=-1)
    with pytest.raises(CamlabInputError, match="polygon"):
        area_on_plane(pose, K, uv[:2])
    with pytest.raises(DegenerateError, match="collinear|general position|three"):
        solve_pnp(BOARD[:9], uv[:9], K)


def test_the_refinements_unchecked_steps_give_the_readable_ones_floats():
    """solve_pnp's inner loop (cached, unchecked rotations; unchecked distortion) is bit for bit
    the readable, checked step and distort_pixels."""
    from camlab.camera import axis_angle_from_rotation
    from camlab.distortion import distort_pixels
    from camlab.measurement import pnp

    def readable_step(x, delta):
        R = rotation_from_axis_angle(delta[:3]) @ rotation_from_axis_angle(x[:3])
        return np.concatenate([axis_angle_from_rotation(R), x[3:] + delta[3:]])

    rng = np.random.default_rng(5)
    rotation = pnp._Rotations(keep=2)
    step = pnp._step(rotation)
    for _ in range(200):
        x = np.r_[rng.normal(0, 1.2, 3), rng.normal(0, 1, 3)]
        delta = rng.normal(0, 10.0 ** rng.uniform(-12, 0), 6)
        assert np.array_equal(step(x, delta), readable_step(x, delta))
        again = step(x, delta)  # R of x from the cache now
        assert np.array_equal(again, readable_step(x, delta))
        assert np.array_equal(rotation(x[:3]), rotation_from_axis_angle(x[:3]))
    assert len(rotation.seen) <= 2
    dist = np.array([-0.3, 0.12, 0.001, -0.002, 0.01])
    uv = rng.uniform(0, 640, (50, 2))
    assert np.array_equal(pnp._distorted(uv, K, dist), distort_pixels(uv, K, dist))


def test_the_picking_sigma_is_the_central_difference_of_pixels_to_plane():
    """measure_on_plane inverts the plane's homography once for all its pixel steps: the same
    numbers as stepping each pixel through the readable pixels_to_plane."""
    from camlab.measurement.plane import _STEP_PIXEL

    uv = project_pose(
        K, rotation_from_axis_angle([0.3, -0.2, 0.1]), np.array([-0.1, 0, 0.8]), BOARD
    )
    pose = solve_pnp(BOARD, uv + np.random.default_rng(1).normal(0, 0.2, uv.shape), K)
    ends = uv[[0, 53]]
    m = measure_on_plane(pose, K, ends[:1], ends[1:], pixel_sigma=0.5)
    g = []
    for k in range(4):
        d = np.zeros(4)
        d[k] = _STEP_PIXEL
        plus, minus = (
            pixels_to_plane(pose, K, ends + d.reshape(2, 2)),
            pixels_to_plane(pose, K, ends - d.reshape(2, 2)),
        )
        g.append(
            (np.linalg.norm(plus[0] - plus[1]) - np.linalg.norm(minus[0] - minus[1]))
            / (2 * _STEP_PIXEL)
        )
    np.testing.assert_allclose(m.sigma_pixels[0], 0.5 * np.linalg.norm(g), rtol=1e-12)
    np.testing.assert_allclose(
        m.value[0], np.linalg.norm(np.subtract(*pixels_to_plane(pose, K, ends))), rtol=1e-14
    )


def _pointwise_differences(mapping, pixels, h=1e-4):
    """(N, 2, 2) central differences of a pixel map taken at each pixel on its own."""
    steps = h * np.eye(2)
    columns = [(mapping(pixels + e) - mapping(pixels - e)) / (2 * h) for e in steps]
    return np.stack(columns, axis=-1)


def test_pixel_distortion_jacobian_equals_differences_and_inverts_to_the_undistortion():
    """The analytic pixel Jacobian (K2 J(x) K2^-1) against central differences of distort_pixels,
    and its inverse against central differences of undistort_pixels at the measured pixels."""
    from camlab.distortion import as_dist, distort_pixels, undistort_pixels
    from camlab.measurement.pnp import pixel_distortion_jacobian

    K = np.array([[530.0, 1.5, 341], [0, 528, 236], [0, 0, 1]])  # a skew, so K2 is not diagonal
    d = as_dist([-0.28, 0.08, 0.0012, -0.0008, -0.02])
    ideal = np.array([[20.0, 30], [341, 236], [600, 400], [100, 450]])
    D = pixel_distortion_jacobian(ideal, K, d)
    np.testing.assert_allclose(
        D, _pointwise_differences(lambda p: distort_pixels(p, K, d), ideal), atol=1e-7
    )
    measured = distort_pixels(ideal, K, d)
    np.testing.assert_allclose(
        np.linalg.inv(D),
        _pointwise_differences(lambda p: undistort_pixels(p, K, d), measured),
        atol=1e-7,
    )
