"""Tests for camlab.camera: P = K [R | t], decomposition, resectioning, rotations, frames."""

from __future__ import annotations

import os

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from camlab import camera as cm
from camlab import scenes
from camlab._validate import CamlabInputError, DegenerateError, check_rotation

os.environ.setdefault("CAMLAB_FIGURE_MODE", "agg")


def box_points(rng, n=40):
    """World points spread through a 2 m cube (never coplanar)."""
    return rng.uniform(-1.0, 1.0, (n, 3)) + [0.0, 0.0, 1.0]


def unit_scale(P):
    P = np.asarray(P, dtype=float)
    P = P / np.linalg.norm(P)
    return P * np.sign(P.ravel()[np.argmax(np.abs(P))])


# -- intrinsics and rotations ----------------------------------------------------------------


def test_intrinsic_matrix_known():
    K = cm.intrinsic_matrix(800, 780, 320, 240, 2.0)
    assert np.array_equal(K, [[800, 2, 320], [0, 780, 240], [0, 0, 1]])


@pytest.mark.parametrize("bad", [dict(fx=0), dict(fy=-5)])
def test_intrinsic_matrix_rejects_nonpositive_focal(bad):
    args = dict(fx=800, fy=800, cx=320, cy=240) | bad
    with pytest.raises(CamlabInputError, match=r"f[xy]: expected a positive finite number pixels"):
        cm.intrinsic_matrix(**args)


def test_rotation_from_axis_angle_matches_cv2(rng):
    for _ in range(20):
        r = rng.normal(size=3) * rng.uniform(0.0, 3.0)
        R_cv, _ = cv2.Rodrigues(r)
        assert np.allclose(cm.rotation_from_axis_angle(r), R_cv, atol=1e-12)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(-3.1, 3.1), min_size=3, max_size=3))
def test_axis_angle_round_trip(v):
    r = np.array(v)
    if np.linalg.norm(r) > np.pi - 1e-3:  # keep the angle in [0, pi)
        r = r / np.linalg.norm(r) * (np.pi - 1e-3)
    R = cm.rotation_from_axis_angle(r)
    assert cm.is_rotation(R)
    assert np.allclose(cm.axis_angle_from_rotation(R), r, atol=1e-7)


def _rodrigues_as_written(r):
    """Rodrigues' formula as rotation_from_axis_angle first wrote it (numpy norm, numpy scalars)."""
    theta = float(np.linalg.norm(r))
    if theta < 1e-15:
        return np.eye(3)
    k = r / theta
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + np.sin(theta) * kx + (1.0 - np.cos(theta)) * (kx @ kx)


def _axis_angle_as_written(a):
    """axis_angle_from_rotation as first written (np.trace, np.clip), for angles below pi."""
    cos = np.clip((np.trace(a) - 1.0) / 2.0, -1.0, 1.0)
    theta = float(np.arccos(cos))
    w = np.array([a[2, 1] - a[1, 2], a[0, 2] - a[2, 0], a[1, 0] - a[0, 1]]) / 2.0
    if theta < 1e-12:
        return w
    return w / np.sin(theta) * theta


def test_the_unchecked_rotations_give_the_readable_formulas_floats(rng):
    """The refiners' unchecked Rodrigues and its inverse: bit for bit the formulas as written."""
    scales = [0.0, 1e-16, 1e-9, 1e-3, 0.5, 2.0, np.pi - 1e-3, np.pi]
    for s in scales:
        for _ in range(50):
            r = rng.normal(size=3)
            r = r / np.linalg.norm(r) * s * rng.uniform(0.5, 1.0)
            R = cm.rotation_from_axis_angle_unchecked(r)
            assert np.array_equal(R, _rodrigues_as_written(r))
            assert np.array_equal(R, cm.rotation_from_axis_angle(r))
            back = cm.axis_angle_from_rotation_unchecked(R)
            assert np.array_equal(back, cm.axis_angle_from_rotation(R))
            if np.pi - np.linalg.norm(back) > 1e-6:
                assert np.array_equal(back, _axis_angle_as_written(R))
    with pytest.raises(CamlabInputError, match="rvec"):  # the checked entry points still check
        cm.rotation_from_axis_angle([1.0, np.nan, 0.0])
    with pytest.raises(CamlabInputError, match="rotation"):
        cm.axis_angle_from_rotation(np.diag([1.0, 1.0, -1.0]))


def test_axis_angle_at_pi():
    r = np.array([0.0, np.pi, 0.0])
    back = cm.axis_angle_from_rotation(cm.rotation_from_axis_angle(r))
    assert np.allclose(cm.rotation_from_axis_angle(back), cm.rotation_from_axis_angle(r), atol=1e-9)
    assert np.isclose(np.linalg.norm(back), np.pi)


@settings(max_examples=60, deadline=None)
@given(st.floats(-3.1, 3.1), st.floats(-1.5, 1.5), st.floats(-3.1, 3.1))
def test_euler_round_trip(rx, ry, rz):
    R = cm.rotation_from_euler(rx, ry, rz)
    assert cm.is_rotation(R)
    assert np.allclose(cm.euler_from_rotation(R), [rx, ry, rz], atol=1e-7)


def test_euler_order_is_z_y_x():
    a, b, c = 0.3, -0.2, 1.1
    assert np.allclose(
        cm.rotation_from_euler(a, b, c), cm.rotation_z(c) @ cm.rotation_y(b) @ cm.rotation_x(a)
    )
    # rotation_z(90 deg) takes the x axis to the y axis (right-handed)
    assert np.allclose(cm.rotation_z(np.pi / 2) @ [1, 0, 0], [0, 1, 0])


def test_check_rotation_errors():
    with pytest.raises(CamlabInputError, match=r"R: expected a rotation .* max \|R\^T R - I\|"):
        check_rotation(np.diag([1.0, 2.0, 1.0]))
    with pytest.raises(CamlabInputError, match=r"det R = -1 \(a reflection\)"):
        check_rotation(np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(
        CamlabInputError, match=r"R: expected a \(3, 3\) matrix, got shape \(2, 2\)"
    ):
        check_rotation(np.eye(2))


# -- Camera --------------------------------------------------------------------------------


def test_camera_rejects_non_rotation():
    with pytest.raises(CamlabInputError, match="expected a rotation"):
        cm.Camera(cm.intrinsic_matrix(800, 800, 320, 240), R=np.eye(3) * 1.1)


@pytest.mark.parametrize(
    "K, msg",
    [
        (np.diag([800.0, 0.0, 1.0]), r"fx = 800, fy = 0 \(a mirrored or singular K\)"),
        (np.diag([800.0, 800.0, 2.0]), r"last row \(0, 0, 1\)"),
        (np.zeros((3, 3)), r"last row \(0, 0, 1\)"),
    ],
)
def test_camera_rejects_singular_or_bad_K(K, msg):
    with pytest.raises(CamlabInputError, match=msg):
        cm.Camera(K)


def test_camera_rejects_bad_dist():
    with pytest.raises(CamlabInputError, match=r"dist: expected 5 finite coefficients"):
        cm.Camera(cm.intrinsic_matrix(800, 800, 320, 240), dist=(0.1, 0.0))


def test_camera_is_frozen_and_copies(cam):
    K = cm.intrinsic_matrix(800, 800, 320, 240)
    c = cm.Camera(K)
    K[0, 0] = 1.0
    assert c.K[0, 0] == 800.0
    with pytest.raises(ValueError):
        c.K[0, 0] = 5.0
    with pytest.raises(AttributeError):
        c.t = np.ones(3)


def test_P_centre_axis_principal_point(cam):
    P = cam.P
    assert np.allclose(P, cam.K @ np.hstack([cam.R, cam.t[:, None]]))
    assert np.allclose(cam.centre, [4.0, -3.0, 2.0])
    assert np.allclose(P @ np.append(cam.centre, 1.0), 0.0, atol=1e-9)
    assert np.allclose(cm.camera_centre(P), np.append(cam.centre, 1.0))
    target_dir = np.array([0.0, 0.0, 0.5]) - cam.centre
    assert np.allclose(cam.principal_axis, target_dir / np.linalg.norm(target_dir))
    assert np.allclose(cam.principal_point, [330, 235])
    # the target lies on the principal axis, so it images at the principal point
    assert np.allclose(cam.project([0.0, 0.0, 0.5]), cam.principal_point)
    assert np.allclose(cam.world_from_cam @ cam.cam_from_world, np.eye(4))


def test_look_at_keeps_up_up():
    c = cm.Camera.look_at([0.0, -5.0, 0.0], [0.0, 0.0, 0.0])
    top, bottom = c.project([[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]])
    assert top[1] < bottom[1]  # +Z appears higher in the image (smaller v)
    left, right = c.project([[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    assert left[0] < right[0]


def test_look_at_degenerate():
    with pytest.raises(DegenerateError, match="eye and target coincide"):
        cm.Camera.look_at([1, 2, 3], [1, 2, 3])
    with pytest.raises(DegenerateError, match="parallel to up"):
        cm.Camera.look_at([0, 0, 5], [0, 0, 0])


def test_from_fov():
    c = cm.Camera.from_fov(np.deg2rad(90), (640, 480))
    assert np.isclose(c.K[0, 0], 320.0)
    assert np.allclose(c.principal_point, [319.5, 239.5])
    with pytest.raises(CamlabInputError, match=r"fov_x: expected a field of view in radians"):
        cm.Camera.from_fov(90)


def test_project_matches_cv2_with_distortion(rng):
    K = cm.intrinsic_matrix(800, 790, 320, 240)
    c = cm.Camera.look_at(
        [3.0, -4.0, 2.0], [0.0, 0.0, 0.5], K=K, dist=(0.1, -0.05, 0.001, 0.002, 0.01)
    )
    X = box_points(rng)
    rvec, _ = cv2.Rodrigues(c.R)
    uv_cv, _ = cv2.projectPoints(X, rvec, c.t.reshape(3, 1), c.K, np.array(c.dist))
    assert np.abs(c.project(X) - uv_cv.reshape(-1, 2)).max() < 1e-9


def test_project_single_vs_batch(cam, rng):
    X = box_points(rng, 5)
    batch = cam.project(X)
    assert batch.shape == (5, 2)
    assert cam.project(X[2]).shape == (2,)
    assert np.allclose(cam.project(X[2]), batch[2])


def test_points_behind_camera_are_nan(cam):
    behind = cam.centre - 2.0 * cam.principal_axis
    uv = cam.project([behind, [0.0, 0.0, 0.5]])
    assert np.isnan(uv[0]).all() and np.isfinite(uv[1]).all()
    at_origin = cm.Camera(cm.intrinsic_matrix(800, 800, 320, 240))
    assert np.isnan(at_origin.project([1.0, 2.0, 0.0])).all()  # z_c = 0 exactly: no image
    assert np.isnan(cm.project_points(cam.P, behind)).all()
    assert np.isnan(cm.project_points(-7.0 * cam.P, behind)).all()  # whatever P's scale
    assert np.isfinite(cm.project_points(-7.0 * cam.P, [0.0, 0.0, 0.5])).all()


def test_project_points_matches_camera(cam, rng):
    X = box_points(rng)
    assert np.allclose(cm.project_points(cam.P, X), cam.project(X), atol=1e-9)
    assert np.allclose(cm.project_points(-0.01 * cam.P, X), cam.project(X), atol=1e-9)


@settings(max_examples=50, deadline=None)
@given(st.floats(0, 639), st.floats(0, 479), st.floats(0.1, 50.0))
def test_backproject_round_trip(u, v, depth):
    c = cm.Camera.look_at(
        [4.0, -3.0, 2.0], [0.0, 0.0, 0.5], K=cm.intrinsic_matrix(810, 790, 330, 235, 1.5)
    )
    X = c.backproject([u, v], depth)
    assert np.isclose(c.depth(X), depth)
    assert np.allclose(c.project(X), [u, v], atol=1e-7)


def test_backproject_rays(cam, rng):
    uv = rng.uniform([0, 0], [640, 480], (10, 2))
    d = cam.backproject(uv)
    assert np.allclose(np.linalg.norm(d, axis=1), 1.0)
    assert np.allclose(cam.project(cam.centre + 3.7 * d), uv)
    assert np.allclose(cam.backproject(cam.principal_point), cam.principal_axis)


def test_backproject_errors(cam):
    with pytest.raises(CamlabInputError, match=r"depth: expected depths > 0"):
        cam.backproject([100, 100], -1.0)
    with pytest.raises(
        CamlabInputError, match=r"depth: expected a number or one depth per pixel \(2\)"
    ):
        cam.backproject([[1, 2], [3, 4]], [1.0, 2.0, 3.0])
    with pytest.raises(CamlabInputError, match="lens distortion; undistort the pixels first"):
        cam.replace(dist=(0.1, 0, 0, 0, 0)).backproject([1, 2], 1.0)


# -- OpenCV vs OpenGL frames -------------------------------------------------------------------


def test_opengl_frame_round_trip(cam):
    R_gl, t_gl = cm.opengl_from_opencv(cam.R, cam.t)
    assert cm.is_rotation(R_gl)
    R2, t2 = cm.opencv_from_opengl(R_gl, t_gl)
    assert np.allclose(R2, cam.R) and np.allclose(t2, cam.t)
    # Same centre; the OpenGL camera looks along its -z axis: a point in front has z_gl < 0.
    assert np.allclose(-R_gl.T @ t_gl, cam.centre)
    X = np.array([0.0, 0.0, 0.5])
    assert (R_gl @ X + t_gl)[2] < 0
    assert (R_gl @ (X + [0, 0, 1]) + t_gl)[1] > (R_gl @ X + t_gl)[
        1
    ]  # world up is camera +y (up) in GL


# -- decomposition ----------------------------------------------------------------------------


@pytest.mark.parametrize("scale", [1.0, 3.7, -0.002, -250.0])
def test_decompose_round_trip(cam, scale):
    K, R, t, C = cm.decompose_projection_matrix(scale * cam.P)
    assert np.allclose(K, cam.K, atol=1e-9 * 800)
    assert np.abs(R - cam.R).max() < 1e-9
    assert np.abs(t - cam.t).max() < 1e-9
    assert np.abs(C - cam.centre).max() < 1e-9
    assert np.linalg.det(R) > 0 and np.all(np.diag(K) > 0) and K[2, 2] == 1.0


@settings(max_examples=40, deadline=None)
@given(
    st.lists(st.floats(-3.0, 3.0), min_size=3, max_size=3),
    st.floats(300, 1500),
    st.floats(0.5, 2.0),
    st.floats(-20, 20),
    st.floats(-100, 100),
)
def test_decompose_property(rvec, f, aspect, skew, scale):
    if abs(scale) < 1e-3:
        scale = 1.0
    K = cm.intrinsic_matrix(f, f * aspect, 320, 240, skew)
    c = cm.Camera(K, cm.rotation_from_axis_angle(rvec), [0.3, -0.2, 5.0])
    d = cm.decompose_projection_matrix(scale * c.P)
    assert np.allclose(d.K, c.K, rtol=1e-9, atol=1e-7)
    assert np.allclose(d.R, c.R, atol=1e-9)
    assert np.allclose(d.t, c.t, atol=1e-9)


def test_decompose_matches_cv2(cam, rng):
    for _ in range(10):
        c = cm.Camera(
            cm.intrinsic_matrix(*rng.uniform([600, 600, 280, 200], [1000, 1000, 360, 280])),
            cm.rotation_from_axis_angle(rng.normal(size=3)),
            rng.normal(size=3) + [0, 0, 6],
        )
        P = rng.uniform(0.01, 100.0) * c.P  # OpenCV assumes det M > 0, see the next test
        K_cv, R_cv, C_cv = cv2.decomposeProjectionMatrix(P)[:3]
        K, R, t, C = cm.decompose_projection_matrix(P)
        assert np.abs(K - K_cv / K_cv[2, 2]).max() < 1e-8
        assert np.abs(R - R_cv).max() < 1e-10
        assert np.abs(C - (C_cv[:3] / C_cv[3]).ravel()).max() < 1e-10


def test_cv2_does_not_fix_negative_scale(cam):
    """For -2.5 P OpenCV returns positive focal lengths but K33 = -2.5 and R turned 180 deg about z (lesson 04)."""
    K_cv, R_cv = cv2.decomposeProjectionMatrix(-2.5 * cam.P)[:2]
    assert K_cv[0, 0] > 0 and K_cv[1, 1] > 0
    assert np.isclose(K_cv[2, 2], -2.5)
    assert np.allclose(R_cv, np.diag([-1.0, -1.0, 1.0]) @ cam.R)
    assert (K_cv / K_cv[2, 2])[0, 0] < 0  # normalising afterwards gives negative focal lengths
    dec = cm.decompose_projection_matrix(-2.5 * cam.P)
    assert dec.K[0, 0] > 0 and np.allclose(dec.K, cam.K) and np.allclose(dec.R, cam.R)


def test_rq_decomposition_properties(rng):
    for _ in range(10):
        M = rng.normal(size=(3, 3))
        K, R = cm.rq_decomposition(M)
        assert np.allclose(K @ R, M)
        assert np.allclose(np.tril(K, -1), 0.0) and np.all(np.diag(K) > 0)
        assert np.allclose(R @ R.T, np.eye(3))
        assert np.isclose(np.linalg.det(R), np.sign(np.linalg.det(M)))


def test_decompose_bad_input(cam):
    with pytest.raises(DegenerateError, match="rank 3, this one has rank 2"):
        cm.decompose_projection_matrix(np.array([[1.0, 0, 0, 0], [0, 1, 0, 0], [1, 1, 0, 0]]))
    affine = np.array([[800.0, 0, 0, 320], [0, 800, 0, 240], [0, 0, 0, 1]])
    with pytest.raises(DegenerateError, match="affine camera"):
        cm.decompose_projection_matrix(affine)
    with pytest.raises(
        CamlabInputError, match=r"P: expected a \(3, 4\) matrix, got shape \(3, 3\)"
    ):
        cm.decompose_projection_matrix(np.eye(3))


def test_camera_centre_of_affine_camera_is_ideal():
    affine = np.array([[800.0, 0, 0, 320], [0, 800, 0, 240], [0, 0, 0, 1]])
    C = cm.camera_centre(affine)
    assert C[3] == 0 and np.allclose(np.abs(C[:3]), [0, 0, 1])


# -- resectioning -------------------------------------------------------------------------------


def test_dlt_noise_free_recovers_P(cam, rng):
    X = box_points(rng, 20)
    uv = cam.project(X)
    P = cm.estimate_projection_matrix(X, uv)
    assert np.abs(unit_scale(P) - unit_scale(cam.P)).max() < 1e-8
    assert np.linalg.norm(P[2, :3]) == pytest.approx(1.0)
    assert np.allclose(
        (np.hstack([X, np.ones((20, 1))]) @ P.T)[:, 2], cam.depth(X)
    )  # third coord = depth
    d = cm.decompose_projection_matrix(P)
    assert np.allclose(d.K, cam.K, atol=1e-5) and np.allclose(d.centre, cam.centre, atol=1e-8)


def test_dlt_minimal_six_points(cam, rng):
    X = box_points(rng, 6)
    P = cm.estimate_projection_matrix(X, cam.project(X))
    assert np.abs(unit_scale(P) - unit_scale(cam.P)).max() < 1e-8


@pytest.mark.parametrize("refine", [False, True])
def test_dlt_noise_rms_near_noise_level(cam, rng, refine):
    X = box_points(rng, 100)
    noise = rng.normal(0.0, 0.5, (100, 2))
    uv = cam.project(X) + noise
    P = cm.estimate_projection_matrix(X, uv, refine=refine)
    rms = np.sqrt(np.mean(cm.reprojection_errors(P, X, uv) ** 2))
    noise_rms = np.sqrt(np.mean(np.sum(noise**2, axis=1)))
    assert abs(rms - noise_rms) <= 0.1 * noise_rms
    # and the fit beats the truth on the data it saw, but only by the 11 absorbed degrees of freedom
    assert rms <= noise_rms


def test_dlt_refine_never_worse(cam, rng):
    X = box_points(rng, 30)
    uv = cam.project(X) + rng.normal(0.0, 2.0, (30, 2))
    e0 = np.sum(cm.reprojection_errors(cm.estimate_projection_matrix(X, uv), X, uv) ** 2)
    e1 = np.sum(
        cm.reprojection_errors(cm.estimate_projection_matrix(X, uv, refine=True), X, uv) ** 2
    )
    assert e1 <= e0 + 1e-9


def test_dlt_at_building_scale(cam, rng):
    """Tens of metres and hundreds of pixels: normalisation keeps the DLT at the noise level."""
    X = box_points(rng, 30) * 10 + [0, 0, 0]  # metres around the cube, pixels in the hundreds
    c = cm.Camera.look_at([40.0, -30.0, 20.0], [0, 0, 10])
    uv = c.project(X) + rng.normal(0, 1.0, (30, 2))
    P = cm.estimate_projection_matrix(X, uv)
    rms = np.sqrt(np.mean(cm.reprojection_errors(P, X, uv) ** 2))
    assert rms < 1.5


def test_dlt_bad_input(cam, rng):
    X = box_points(rng, 5)
    with pytest.raises(
        CamlabInputError,
        match=r"points_world: expected \(N, 3\) with N >= 6 point pairs, got shape \(5, 3\); P has 11",
    ):
        cm.estimate_projection_matrix(X, cam.project(X))
    X = box_points(rng, 10)
    with pytest.raises(
        CamlabInputError,
        match="points_world, points_image: expected the same number of points .*got 10 and 9",
    ):
        cm.estimate_projection_matrix(X, cam.project(X)[:9])
    plane = np.column_stack([rng.uniform(-1, 1, (10, 2)), np.zeros(10)])
    with pytest.raises(DegenerateError, match="coplanar"):
        cm.estimate_projection_matrix(plane, cam.project(plane))
    tilted = plane @ cm.rotation_from_euler(0.3, 0.4, 0.5).T + 2.0
    with pytest.raises(DegenerateError, match="coplanar"):
        cm.estimate_projection_matrix(tilted, cam.project(tilted))


def test_reprojection_errors_known(cam):
    X = np.array([[0.0, 0.0, 0.5], [0.5, 0.5, 0.5]])
    uv = cam.project(X) + [[3.0, 4.0], [0.0, 0.0]]
    assert np.allclose(cm.reprojection_errors(cam.P, X, uv), [5.0, 0.0])


# -- scenes ----------------------------------------------------------------------------------------


def test_wireframes_and_project_segments(cam):
    box = scenes.box_wireframe((0, 0, 0), (2, 2, 2))
    assert box.shape == (12, 2, 3)
    assert np.allclose(
        np.linalg.norm(box[:, 1] - box[:, 0], axis=1), 2.0
    )  # every edge is a cube edge
    house = scenes.house_wireframe()
    assert house.shape[1:] == (2, 3) and house[..., 2].min() == 0.0
    grid = scenes.ground_grid(2.0, 0.5)
    assert grid.shape == (18, 2, 3)
    pix = cm.project_segments(cam, box)
    assert pix.shape == (12, 2, 2)
    assert np.allclose(pix, cm.project_segments(cam.P, box))
    with pytest.raises(CamlabInputError, match=r"segments: expected \(M, 2, 3\)"):
        cm.project_segments(cam, np.zeros((3, 3)))


def test_project_segments_clips_a_segment_that_runs_behind_the_camera():
    cam = cm.Camera(cm.intrinsic_matrix(800, 800, 319.5, 239.5), np.eye(3), [0.0, 0.0, 0.0])
    segs = np.array(
        [
            [[0.5, 0.2, 4.0], [0.5, 0.2, -2.0]],  # from 4 m in front to 2 m behind
            [[0.0, 0.0, -1.0], [1.0, 0.0, -3.0]],  # wholly behind
            [[-1.0, 0.0, 2.0], [1.0, 0.0, 2.0]],
        ]
    )  # wholly in front
    for camera in (cam, cam.P, -2.0 * cam.P):  # a Camera, or P at any scale and sign
        pix = cm.project_segments(camera, segs)
        assert np.allclose(pix[0, 0], [319.5 + 100, 239.5 + 40])  # the front end is untouched
        far = pix[0, 1] - [319.5, 239.5]  # the clipped end: same ray direction, far out
        assert np.all(np.isfinite(far)) and np.linalg.norm(far) > 1e4
        assert np.allclose(far / np.linalg.norm(far), np.array([0.5, 0.2]) / np.hypot(0.5, 0.2))
        assert np.isnan(pix[1]).all() and np.allclose(pix[2], [[-80.5, 239.5], [719.5, 239.5]])
    affine = cm.project_segments(np.array([[100.0, 0, 0, 0], [0, 100, 0, 0], [0, 0, 0, 1]]), segs)
    assert np.allclose(affine[0], [[50, 20], [50, 20]])  # affine cameras clip nothing


# -- 3-D views (camlab.plotting.scene3d) --------------------------------------------------------


def _agg_figure():
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6, 4))
    FigureCanvasAgg(fig)
    return fig


def test_camera_artist_geometry_and_update(cam):
    from camlab.plotting import scene3d

    fig = _agg_figure()
    ax = scene3d.axes3d(fig, 111)
    art = scene3d.CameraArtist(
        ax, cam, size=0.5, image_lines=cm.project_segments(cam, scenes.box_wireframe())
    )
    corners = art.corners()
    assert np.allclose(cam.depth(corners), 0.5)  # the image plane is z_c = size
    assert np.allclose(
        cam.project(corners[0]), [-0.5, -0.5]
    )  # top-left corner of the top-left pixel
    x, y, z = art.axes_lines[2].get_data_3d()  # the z axis points along the principal axis
    assert np.allclose(np.array([x[1], y[1], z[1]]) - cam.centre, 0.3 * cam.principal_axis)
    assert [t.get_text() for t in art.axes_text] == ["x", "y", "z"]
    lx, ly, lz = art.lines.get_data_3d()
    on_plane = np.column_stack([lx, ly, lz])
    on_plane = on_plane[np.isfinite(on_plane).all(axis=1)]
    assert np.allclose(cam.depth(on_plane), 0.5)
    moved = cam.replace(t=cam.t + [0.0, 0.0, 1.0])
    art.update(moved)
    assert np.allclose(art.centre_marker.get_data_3d()[0], moved.centre[0])
    fig.canvas.draw()


def test_camera_artist_image_mesh(cam):
    from camlab.plotting import scene3d

    fig = _agg_figure()
    ax = scene3d.axes3d(fig, 111)
    img = np.zeros((48, 64, 3))
    img[:, 32:] = 1.0  # right half white
    art = scene3d.CameraArtist(ax, cam, image=img, image_grid=(8, 6))
    colours = art.mesh_colours.reshape(6, 8, 3)
    assert np.allclose(colours[:, :4], 0.0) and np.allclose(colours[:, 4:], 1.0)
    fig.canvas.draw()


def test_set_equal_aspect_makes_a_cube():
    from camlab.plotting import scene3d

    fig = _agg_figure()
    ax = scene3d.axes3d(fig, 111)
    scene3d.set_equal_aspect(ax, [[0, 0, 0], [4, 1, 2]], margin=0.0)
    spans = [np.diff(lim)[0] for lim in (ax.get_xlim(), ax.get_ylim(), ax.get_zlim())]
    assert np.allclose(spans, 4.0)


# -- lesson 04 demos and exercises -------------------------------------------------------------


def test_camera_explorer_state_follows_sliders():
    from camlab.widgets import projective_camera as demos

    d = demos.camera_explorer()
    d.set(fx=1000, cx=300, distance=6.0, azimuth=-90, elevation=0)
    cam_state = d.state["camera"]
    assert cam_state.K[0, 0] == 1000 and cam_state.K[0, 2] == 300
    assert np.allclose(d.state["centre"], demos.TARGET + [0.0, -6.0, 0.0])
    assert np.allclose(d.state["t"], -cam_state.R @ d.state["centre"])
    before = d.view.pixels()
    d.set(skew=200)
    assert np.allclose(d.state["K"][0, 1], 200)
    assert not np.array_equal(before, d.view.pixels())


def test_resectioning_demo_recovers_camera():
    from camlab.widgets import projective_camera as demos

    d = demos.resectioning()
    d.set(noise=0.0, n_points=20)
    assert (
        d.state["rms"] < 1e-6 and d.state["focal_error"] < 1e-4 and d.state["centre_error"] < 1e-8
    )
    d.set(noise=2.0)
    assert 1.0 < d.state["rms"] < 4.0


def test_resectioning_teaches_the_redundancy_trap():
    from camlab.widgets import projective_camera as demos

    d = demos.resectioning()
    d.set(noise=5.0, n_points=6, refine=True)
    assert d.state["redundancy"] == 1
    assert (
        d.state["rms"] < 2.0 and d.state["centre_error"] > 1.0
    )  # small residual, camera metres off
    assert "a small RMS" in d.widget.children[0].children[-1].value
    d.set(n_points=60)
    assert d.state["redundancy"] == 109 and d.state["centre_error"] < 0.2
    assert d.state["rms"] == pytest.approx(d.state["expected_rms"], rel=0.5)


def test_camera_image_plane_lines_are_clipped_to_the_picture():
    from camlab.plotting.scene3d import clip_segments
    from camlab.widgets import projective_camera as demos

    seg = np.array(
        [
            [[-100.0, 100.0], [700.0, 100.0]],
            [[700.0, -5.0], [800.0, 600.0]],
            [[10.0, 10.0], [20.0, 30.0]],
            [[np.nan, 0.0], [5.0, 5.0]],
        ]
    )
    out = clip_segments(seg, (640, 480))
    assert np.allclose(out[0], [[-0.5, 100.0], [639.5, 100.0]])
    assert np.isnan(out[1]).all() and np.isnan(out[3]).all()  # wholly outside; a NaN end
    assert np.allclose(out[2], seg[2])  # inside: unchanged
    d = demos.camera_explorer()
    d.set(fx=200, fy=1600, cx=0, cy=480, skew=300, azimuth=180, elevation=-10, distance=2.5)
    cam = d.state["camera"]  # the plane lines of the explorer's camera stay within its image plane
    lines = [ln for ax in d.figure.axes[:1] for ln in ax.lines if ln.get_color() == "0.15"][0]
    xyz = np.column_stack(lines.get_data_3d())
    xyz = xyz[np.isfinite(xyz).all(axis=1)]
    uvw = (xyz @ cam.R.T + cam.t) @ cam.K.T
    uv = uvw[:, :2] / uvw[:, 2:]
    assert (
        len(uv)
        and (uv[:, 0] > -0.6).all()
        and (uv[:, 0] < 639.6).all()
        and (uv[:, 1] < 479.6).all()
    )


def test_resectioning_outlier_and_click():
    from types import SimpleNamespace

    from camlab.widgets import projective_camera as demos

    d = demos.resectioning()
    d.set(noise=0.0, n_points=12)
    d.set(outlier=60.0)
    assert (
        d.state["rms"] > 5.0 and d.state["focal_error"] > 1.0
    )  # one bad pair spoils the linear fit
    d.set(outlier=0.0)
    assert d.state["rms"] < 1e-6
    target = d.state["points_image"][3] + [40.0, -30.0]
    d.handlers["button_press_event"](
        SimpleNamespace(inaxes=d.figure.axes[1], xdata=target[0], ydata=target[1])
    )
    assert np.allclose(d.state["points_image"][3], target) and d.state["rms"] > 5.0
    d.set(n_points=13)  # new measurements forget the click
    assert d.state["rms"] < 1e-6


def test_opencv_vs_opengl_demo_flips_y_and_z():
    from camlab.widgets import projective_camera as demos

    d = demos.opencv_vs_opengl()
    R_cv = d.state["R_axes"]
    d.set(frame="OpenGL / Blender")
    assert np.allclose(d.state["R_axes"], np.diag([1.0, -1.0, -1.0]) @ R_cv)


def test_lesson04_exercises_accept_reference_and_reject_stub(capsys):
    from camlab.exercises import all_exercises, check

    for name in ("project_points", "camera_centre", "rq_decomposition"):
        assert all_exercises()[name].lesson == "04"
        assert check(name, all_exercises()[name].reference)

        def stub(*args):
            raise NotImplementedError

        assert check(name, stub).passed is False
        assert "not attempted yet" in capsys.readouterr().out
    with pytest.raises(AssertionError, match="divide by the third coordinate|without dividing"):
        check("project_points", lambda P, X: (np.hstack([X, np.ones((len(X), 1))]) @ P.T)[:, :2])


def test_every_projection_path_gives_nan_behind_the_camera():
    """One rule (docs/conventions.md): z_cam <= 0 projects to NaN, never to a mirrored pixel."""
    from camlab import calibration, pinhole, render

    K = cm.intrinsic_matrix(800, 800, 320, 240)
    X = np.array(
        [[0.1, -0.2, 2.0], [0.1, -0.2, -2.0], [0.3, 0.1, 0.0]]
    )  # in front, behind, in the camera plane
    dist = (-0.2, 0.05, 0.0, 0.0, 0.0)
    paths = {
        "Camera.project": cm.Camera(K, dist=dist).project(X),
        "project_points": cm.project_points(cm.Camera(K).P, X),
        "render.project": render.project(X, K, dist=dist),
        "calibration.reproject": calibration.reproject(X, K, dist, np.zeros(3), np.zeros(3)),
        "project_pinhole": pinhole.project_pinhole(X, 0.05),
    }
    for name, uv in paths.items():
        assert np.isfinite(uv[0]).all(), name
        assert np.isnan(uv[1]).all() and np.isnan(uv[2]).all(), name


def test_scale_intrinsics_and_camera_resized_agree_with_resizing_pixels():
    cam = cm.Camera(cm.intrinsic_matrix(800, 780, 319.5, 239.5, 2.0), image_size=(640, 480))
    half = cam.resized(0.5)
    assert half.image_size == (320, 240)
    np.testing.assert_allclose(half.K, cm.scale_intrinsics(cam.K, 0.5))
    # pixel centres: output pixel u' covers input pixels 2u' and 2u' + 1, so u' = (u - 0.5) / 2
    X = np.array([[0.3, -0.1, 2.0], [-0.4, 0.2, 3.0]])
    np.testing.assert_allclose(half.project(X), (cam.project(X) - 0.5) / 2, atol=1e-12)
    with pytest.raises(
        CamlabInputError, match=r"image_size \* scale: expected \(width, height\) as whole numbers"
    ):
        cam.resized(0.33)


def test_orbit_eye_is_a_point_on_a_sphere_in_radians():
    T = np.array([0.0, 0.0, 0.5])
    eye = cm.orbit_eye(np.radians(-40), np.radians(20), 4.0, T)
    assert np.isclose(np.linalg.norm(eye - T), 4.0)
    assert np.isclose(np.degrees(np.arcsin((eye - T)[2] / 4.0)), 20.0)  # elevation up, towards +z
    np.testing.assert_allclose(cm.orbit_eye(0.0, 0.0, 2.0), [2.0, 0.0, 0.0])
    with pytest.raises(CamlabInputError, match="distance"):
        cm.orbit_eye(0.0, 0.0, -1.0)


def test_nearest_rotation_has_one_home():
    """Calibration (Zhang's R), rectification and panorama stitching all use camera.nearest_rotation."""
    from camlab import calibration
    from camlab.calibration import zhang

    assert (
        zhang.nearest_rotation is cm.nearest_rotation
        and "nearest_rotation" not in calibration.__all__
    )
    H = 3.0 * cm.rotation_from_axis_angle([0.1, -0.2, 0.3])  # a rotation homography's scale
    np.testing.assert_allclose(cm.nearest_rotation(H), H / 3.0, atol=1e-12)


def test_functions_returning_a_pose_or_factors_name_them():
    """No bare tuples (docs/conventions.md); each unpacks as before (``R, t = ...``) and reads by name."""
    from camlab import epipolar as ep
    from camlab import render
    from camlab.calibration import extrinsics_from_homography
    from camlab.camera import CameraPair
    from camlab.fixtures.stereo import rig_cameras

    pair = rig_cameras()
    assert isinstance(pair, CameraPair)
    pose = ep.relative_pose(pair.camera1, pair.camera2)
    assert isinstance(pose, cm.Pose) and np.allclose(pose.R, pair.camera2.R @ pair.camera1.R.T)
    R, t = render.look_at([0.0, -2.0, 1.0], [0.0, 0.0, 1.0])
    assert np.allclose(render.look_at([0.0, -2.0, 1.0], [0.0, 0.0, 1.0]).t, t)
    gl = cm.opengl_from_opencv(R, t)
    assert np.allclose(gl.R, cm.CV_FROM_GL @ R) and np.allclose(cm.opencv_from_opengl(*gl).t, t)
    K = cm.intrinsic_matrix(800, 800, 320, 240)
    H = K @ np.column_stack([R[:, 0], R[:, 1], t])  # the board plane z = 0 seen by (R, t)
    board = extrinsics_from_homography(K, H)
    assert np.allclose(board.R, R) and np.allclose(board.t, t)
    rq = cm.rq_decomposition(K @ R)
    assert np.allclose(rq.K, K) and np.allclose(rq.R, R)


def test_resectioning_keeps_a_wild_fit_in_view_and_says_when_it_failed():
    from camlab.widgets import projective_camera as demos

    d = demos.resectioning()
    d.set(
        n_points=6, outlier_v=-60.0, refine=True, noise=0.0
    )  # the review's setting: a focal length near 60 px
    assert abs(d.state["K"][0, 0]) < 100
    ax3d = d.figure.axes[0]
    frustum = [ln for ln in ax3d.lines if ln.get_color() == demos.palette.ORANGE][0]
    x, y, z = (np.asarray(a, dtype=float) for a in frustum.get_data_3d())
    pts = np.column_stack([x, y, z])[np.isfinite(x)]
    assert np.ptp(pts, axis=0).max() < 2.0  # shortened (13 m tall before): no frustum over the view
    assert np.isfinite(d.state["rms"])
    d.set(outlier_v=0.0, outlier=60.0)  # a fit with every point behind the estimated camera
    assert d.state["behind"] > 0 and not np.isfinite(d.state["rms"])

    def texts(widget):
        yield str(getattr(widget, "value", ""))
        for child in getattr(widget, "children", ()):
            yield from texts(child)

    assert any(
        "behind the estimated camera" in text for text in texts(d.widget)
    )  # said, not a silent 'nan'


def test_blender_matrix_world_is_world_from_cam_in_the_opengl_frame():
    cam = cm.Camera.look_at([4.0, -3.5, 2.5], [0.0, 0.0, 0.7])
    M = cm.blender_matrix_world(cam.R, cam.t)
    assert np.allclose(M[:3, 3], cam.centre) and np.allclose(M[3], [0, 0, 0, 1])
    assert np.allclose(
        M[:3, 2], -cam.R[2]
    )  # Blender's camera z points backward, away from the view
    assert np.allclose(M[:3, 1], -cam.R[1])  # and its y up
    R_gl, t_gl = cm.opengl_from_opencv(cam.R, cam.t)
    assert np.allclose(
        np.linalg.inv(M), np.block([[R_gl, t_gl[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]])
    )


def test_explorer_pan_turns_about_the_world_vertical_and_roll_is_right_handed():
    """+pan turns the camera left (anticlockwise seen from above) with the horizon level; +roll turns the picture
    anticlockwise; a short focal length never makes the image plane wider than at the default."""
    from camlab.widgets import projective_camera as demos

    cam0, panned = demos.explorer_camera(), demos.explorer_camera(pan=10.0)
    assert np.cross(cam0.R[2], panned.R[2])[2] > 0 and np.isclose(
        panned.R[0, 2], 0.0
    )  # left turn, x horizontal
    assert np.allclose(panned.centre, cam0.centre)
    right = cam0.centre + 5.0 * cam0.R[2] + cam0.R[0]  # a point right of the axis rises when +roll
    assert demos.explorer_camera(roll=10.0).project(right)[1] < cam0.project(right)[1] - 10
    default = demos.explorer_plane_size(5.0, cam0.K)
    assert default == demos.explorer_plane_size(5.0) == 2.0
    for k in (dict(fx=200), dict(fy=200), dict(cx=639.5), dict(skew=300)):
        K = demos.explorer_camera(**k).K
        corners = np.array(
            [[-0.5, -0.5, 1.0], [639.5, 479.5, 1.0], [639.5, -0.5, 1.0], [-0.5, 479.5, 1.0]]
        )
        reach = (
            demos.explorer_plane_size(5.0, K)
            * np.linalg.norm(np.linalg.solve(K, corners.T)[:2], axis=0).max()
        )
        assert reach <= 2.0 * 0.5 + 1e-9  # no corner farther from the axis than the default's


def test_resectioning_readout_flags_a_k_no_camera_has():
    from camlab.widgets import projective_camera as demos

    d = demos.resectioning()
    readout = lambda: d.widget.children[0].children[-1].value  # noqa: E731
    assert "estimated K" in readout() and "no real camera" not in readout()
    d.set(refine=True, outlier=60.0, pair=5)
    assert (
        "fx 1563.9, fy 1443.5, skew -95.9" in readout()
        and "principal point (137.7, -340.3)" in readout()
    )
    assert "no real camera has this K (fy != fx, skew, principal point off the image)" in readout()
    d.set(
        outlier=0.0, noise=0.0
    )  # the exact camera: the half-pixel principal point, no "-0.0" skew
    assert "skew 0.0 px" in readout() and "principal point (319.5, 239.5)" in readout()
    assert "on 30 fresh points of the box" in readout() and "RMS 0.00 px" in readout()
