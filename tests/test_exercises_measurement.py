"""Lesson 12's exercises accept a right answer in another valid form, and name each typical mistake."""

import numpy as np
import pytest

from camlab.exercises import all_exercises, check

all_exercises()  # registers lesson 12's exercises (a lesson reaches them through check_<name>)


def test_point_jacobian_reference_is_pose_jacobian_and_accepts_central_differences(capsys):
    from camlab.camera import rotation_from_axis_angle
    from camlab.exercises.point_jacobian import _cases, _reference
    from camlab.measurement import pose_jacobian, project_pose

    for K, R, t, X in _cases():
        assert np.allclose(
            _reference(K, R, t, X), pose_jacobian(K, R, t, X[None]), rtol=1e-12, atol=1e-9
        )

    def numerical(K, R, t, X):  # the left perturbation, one parameter at a time
        def pixel(p):
            return project_pose(K, rotation_from_axis_angle(p[:3]) @ R, t + p[3:], X[None])[0]

        return np.column_stack([(pixel(h) - pixel(-h)) / 2e-6 for h in 1e-6 * np.eye(6)])

    assert check("point_jacobian", numerical).passed is True


@pytest.mark.parametrize(
    ("wrong", "phrase"),
    [
        (lambda K, R, t, X: np.zeros((2, 6)).tolist(), ""),
        (lambda K, R, t, X: None, "return"),
    ],
)
def test_point_jacobian_rejects_a_list_and_none(wrong, phrase):
    with pytest.raises(AssertionError) as info:
        check("point_jacobian", wrong)
    assert phrase in str(info.value)


def test_length_on_plane_accepts_rows_and_a_solve(capsys):
    def rows(H, a, b):  # points as rows: x @ inv(H).T, then the norm
        p = np.array([[*a, 1.0], [*b, 1.0]]) @ np.linalg.inv(H).T
        p = p[:, :2] / p[:, 2:]
        return float(np.hypot(*(p[0] - p[1])))

    def solved(H, a, b):  # np.linalg.solve instead of an inverse
        pa, pb = (np.linalg.solve(H, np.append(x, 1.0)) for x in (a, b))
        return np.linalg.norm(pa[:2] / pa[2] - pb[:2] / pb[2])

    assert check("length_on_plane", rows).passed is True
    assert check("length_on_plane", solved).passed is True


def test_max_depth_accepts_a_numerical_root(capsys):
    def bisect(f, B, sigma_d, max_error):
        lo, hi = 0.0, 1e4
        for _ in range(200):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if mid**2 * sigma_d / (f * B) < max_error else (lo, mid)
        return lo

    assert check("max_depth", bisect).passed is True


def test_pose_covariance_accepts_a_solve_and_a_pseudo_inverse(capsys):
    def solved(J, r):
        return (r @ r) / (len(r) - 6) * np.linalg.solve(J.T @ J, np.eye(6))

    def pseudo(J, r):
        return np.linalg.pinv(J) @ np.linalg.pinv(J).T * np.sum(r**2) / (len(r) - 6)

    assert check("pose_covariance", solved).passed is True
    assert check("pose_covariance", pseudo).passed is True


def test_length_sigma_reference_is_measure_on_plane_and_accepts_forward_differences(capsys):
    from types import SimpleNamespace

    from camlab.exercises.length_sigma import _K, _exp, _homography_of, length_sigma
    from camlab.measurement import measure_on_plane

    R, t = _exp([0.35, -0.1, 0.2]), np.array([-0.1, -0.05, 0.5])
    Sigma_p = np.diag([4e-6, 4e-6, 1e-6, 1e-8, 1e-8, 4e-8])
    a, b = np.array([250.0, 180.0]), np.array([420.0, 300.0])
    pose = SimpleNamespace(R=R, t=t, covariance=Sigma_p)
    library = measure_on_plane(pose, _K, a, b, None, pixel_sigma=0.3)
    ours = length_sigma(_homography_of(_K, R, t), Sigma_p, a, b, 0.3)
    assert abs(ours / library.sigma[0] - 1) < 1e-4

    def forward(H_of, Sigma_p, a, b, sigma_u):  # one-sided differences, other steps, points as rows
        def length(p, u):
            q = np.column_stack([np.reshape(u, (2, 2)), np.ones(2)]) @ np.linalg.inv(H_of(p)).T
            q = q[:, :2] / q[:, 2:]
            return np.hypot(*(q[0] - q[1]))

        p0, u0 = np.zeros(6), np.r_[a, b]
        g_p = np.array([(length(h, u0) - length(p0, u0)) / 1e-7 for h in 1e-7 * np.eye(6)])
        g_u = np.array([(length(p0, u0 + h) - length(p0, u0)) / 1e-3 for h in 1e-3 * np.eye(4)])
        return np.sqrt(g_p @ Sigma_p @ g_p + sigma_u**2 * np.sum(g_u**2))

    assert check("length_sigma", forward).passed is True


def test_length_on_plane_accepts_opencv_in_float32(capsys):
    import cv2

    def opencv(H, a, b):  # the usual call: float32 points, 30 nm off on 0.17 m
        p = cv2.perspectiveTransform(np.float32([[a, b]]), np.linalg.inv(H))[0]
        return float(np.linalg.norm(p[0] - p[1]))

    assert check("length_on_plane", opencv).passed is True


def test_point_jacobian_names_a_forward_difference_with_its_columns():
    from camlab.exercises.point_jacobian import _forward_difference

    with pytest.raises(AssertionError) as info:
        check("point_jacobian", _forward_difference)
    assert "forward difference" in str(info.value) and "columns []" not in str(info.value)


@pytest.mark.parametrize("focal", ["mean", "fy"])
def test_point_jacobian_names_one_focal_length_for_both_rows(focal):
    from camlab.exercises.point_jacobian import point_jacobian

    def one_focal(K, R, t, X):  # (fx + fy) / 2, or fy, for both rows
        K1 = np.array(K, dtype=float)
        K1[0, 0] = K1[1, 1] = (K1[0, 0] + K1[1, 1]) / 2 if focal == "mean" else K1[1, 1]
        return point_jacobian(K1, R, t, X)

    with pytest.raises(AssertionError) as info:
        check("point_jacobian", one_focal)
    assert "one focal length" in str(info.value) and "forward difference" not in str(info.value)


def test_pose_covariance_names_a_scaled_sigma():
    from camlab.exercises.pose_uncertainty import pose_covariance

    with pytest.raises(AssertionError) as info:
        check("pose_covariance", lambda J, r: 0.7 * pose_covariance(J, r))
    assert "0.7 times the answer" in str(info.value)


def test_point_covariance_accepts_one_stacked_product(capsys):
    from scipy.linalg import block_diag

    def stacked(
        J_A, Sigma_A, J_B, Sigma_B, J_u, sigma_u
    ):  # section 3's form: J Sigma_in J^T in one step
        J = np.hstack([J_A, J_B, J_u])
        return J @ block_diag(Sigma_A, Sigma_B, sigma_u**2 * np.eye(4)) @ J.T

    assert check("point_covariance", stacked).passed is True


def test_point_covariance_prints_tiny_covariances_in_significant_digits():
    from camlab.exercises.point_covariance import point_covariance

    def halved(J_A, Sigma_A, J_B, Sigma_B, J_u, sigma_u):  # sigma_u / 2: a range taken as 2 sigma
        return point_covariance(J_A, Sigma_A, J_B, Sigma_B, J_u, sigma_u / 2)

    with pytest.raises(AssertionError) as info:
        check("point_covariance", halved)
    message = str(info.value)
    got = message.split("got", 1)[1].split("expected", 1)[0]
    assert "e-0" in got and "0.0000" not in got, message  # about 1e-8 m^2, never all zeros
    assert "sigma_u / 2" in message, message


def test_point_covariance_names_the_transposed_product():
    def transposed(J_A, Sigma_A, J_B, Sigma_B, J_u, sigma_u):  # J^T Sigma J: the shapes clash
        return J_A.T @ Sigma_A @ J_A + J_B.T @ Sigma_B @ J_B + sigma_u**2 * J_u @ J_u.T

    with pytest.raises(AssertionError) as info:
        check("point_covariance", transposed)
    message = str(info.value)
    assert "J_A @ Sigma_A @ J_A.T" in message and "points as rows" not in message, message


def test_height_above_plane_accepts_opencv_in_float32_and_names_the_slips(capsys):
    import cv2

    def opencv(K, R, t, a, b, length):  # float32 points: h about 0.1 um off, a relative 1e-5
        H = K @ np.column_stack([R[:, 0], R[:, 1], t])
        p = cv2.perspectiveTransform(np.float32([[a, b]]), np.linalg.inv(H))[0]
        return abs((-R.T @ t)[2]) * (1 - length / np.linalg.norm(p[0] - p[1]))

    assert check("height_above_plane", opencv).passed is True

    from camlab.exercises.off_plane import height_above_plane

    with pytest.raises(AssertionError) as info:  # 2 um off: no named slip, digits that differ
        check("height_above_plane", lambda *args: height_above_plane(*args) + 2e-6)
    message = str(info.value)
    assert "+2.0 um off" in message, message


def test_max_depth_accepts_a_coarse_bisection_and_explains_a_near_miss(capsys):
    def bisect(f, B, sigma_d, max_error, steps=40):  # 1e4 / 2^40: about 0.01 um
        lo, hi = 0.0, 1e4
        for _ in range(steps):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if mid**2 * sigma_d / (f * B) < max_error else (lo, mid)
        return lo

    assert check("max_depth", bisect).passed is True
    with pytest.raises(AssertionError) as info:  # 2e-5 relative: nearly right, digits that differ
        check("max_depth", lambda *args: bisect(*args) * (1 + 2e-5))
    message = str(info.value)
    assert "nearly right" in message and "+2.0e-05 relative" in message, message


def test_pose_covariance_says_nearly_right_for_a_tiny_scale():
    from camlab.exercises.pose_uncertainty import pose_covariance

    with pytest.raises(AssertionError) as info:
        check("pose_covariance", lambda J, r: 1.0001 * pose_covariance(J, r))
    message = str(info.value)
    assert "nearly right" in message and "1 times" not in message, message


def test_point_covariance_in_mm2_prints_the_expected_in_significant_digits():
    from camlab.exercises.point_covariance import point_covariance

    with pytest.raises(AssertionError) as info:
        check("point_covariance", lambda *args: 1e6 * point_covariance(*args))
    message = str(info.value)
    assert "0.0000" not in message.split("expected", 1)[1], message


def test_point_covariance_names_a_transposed_picking_term():
    def picking_transposed(J_A, Sigma_A, J_B, Sigma_B, J_u, sigma_u):  # J_u.T @ J_u: (4, 4)
        return J_A @ Sigma_A @ J_A.T + J_B @ Sigma_B @ J_B.T + sigma_u**2 * J_u.T @ J_u

    with pytest.raises(AssertionError) as info:
        check("point_covariance", picking_transposed)
    assert "J_u @ J_u.T" in str(info.value) and "(4, 4) term" in str(info.value)


def test_flip_gap_accepts_opencv_and_names_the_per_coordinate_rms():
    import cv2

    def opencv(K, R1, t1, R2, t2, X, sigma):  # cv2.projectPoints, offsets added up with np.hypot
        x1, x2 = (
            cv2.projectPoints(X, cv2.Rodrigues(R)[0], t, K, None)[0].reshape(-1, 2)
            for R, t in ((R1, t1), (R2, t2))
        )
        d = x2 - x1
        return np.sqrt(np.sum(np.hypot(d[:, 0], d[:, 1]) ** 2)) / (2 * sigma)

    assert check("flip_gap", opencv).passed is True

    def rms(K, R1, t1, R2, t2, X, sigma):  # OpenCV's rms per coordinate, halved
        x1, x2 = (
            cv2.projectPoints(X, cv2.Rodrigues(R)[0], t, K, None)[0].reshape(-1, 2)
            for R, t in ((R1, t1), (R2, t2))
        )
        return np.sqrt(np.mean((x2 - x1) ** 2)) / 2 / sigma

    with pytest.raises(AssertionError) as info:
        check("flip_gap", rms)
    assert "ADDS them up" in str(info.value), str(info.value)
