"""Tests for camlab.affine: the affine camera family, the affine approximation, estimation."""

from __future__ import annotations

import os

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from camlab import affine as af
from camlab import camera as cm
from camlab._validate import CamlabInputError, DegenerateError
from camlab.fixtures import box_and_rails
from camlab.scenes import box_wireframe

os.environ.setdefault("CAMLAB_FIGURE_MODE", "agg")


def test_orthographic_known():
    R = cm.rotation_z(np.pi / 2)
    P = af.orthographic_matrix(R, [1.0, 2.0, 10.0])
    X = np.array([[1.0, 0.0, 5.0], [0.0, 1.0, -3.0]])
    # R maps x to y and y to -x; depth (t3 and X_z) is forgotten
    assert np.allclose(cm.project_points(P, X), [[1.0, 3.0], [0.0, 2.0]])
    assert af.is_affine(P) and not af.is_affine(cm.Camera.look_at([3, 0, 0], [0, 0, 0]).P)


def test_scaled_orthographic_and_weak_perspective(rng):
    R = cm.rotation_from_euler(0.1, 0.2, 0.3)
    t = np.array([0.1, -0.2, 7.0])
    X = rng.uniform(-1, 1, (10, 3))
    Xc = X @ R.T + t
    so = cm.project_points(af.scaled_orthographic_matrix(R, t, 150.0, (320, 240)), X)
    assert np.allclose(so, 150.0 * Xc[:, :2] + [320, 240])
    wp = cm.project_points(af.weak_perspective_matrix(R, t, 150.0, 120.0, 5.0, (320, 240)), X)
    assert np.allclose(wp, Xc[:, :2] @ np.array([[150.0, 5.0], [0.0, 120.0]]).T + [320, 240])
    with pytest.raises(CamlabInputError, match="ax: expected a positive finite number"):
        af.weak_perspective_matrix(R, t, 0.0, 1.0)
    with pytest.raises(CamlabInputError, match="expected a rotation"):
        af.orthographic_matrix(2 * np.eye(3), t)


def test_affine_camera_sees_points_behind():
    P = af.orthographic_matrix(np.eye(3), [0.0, 0.0, 0.0])
    assert np.allclose(cm.project_points(P, [1.0, 2.0, -5.0]), [1.0, 2.0])


def test_affine_approximation_exact_at_reference(cam, rng):
    X0 = np.array([0.3, -0.2, 0.7])
    PA = af.affine_approximation(cam, X0)
    assert af.is_affine(PA) and np.allclose(PA[2], [0, 0, 0, 1])
    assert np.allclose(cm.project_points(PA, X0), cam.project(X0))
    # Points at the reference depth (a fronto-parallel plane) image identically
    d0 = cam.depth(X0)
    uv = rng.uniform([0, 0], [640, 480], (10, 2))
    X = cam.backproject(uv, d0)
    assert np.allclose(cm.project_points(PA, X), uv)


def test_affine_approximation_error_formula(cam, rng):
    """H&Z §6.3.2: x_proj - x0 = d0 / (d0 + Delta) (x_affine - x0), x0 the principal point."""
    X0 = np.array([0.0, 0.0, 0.5])
    PA = af.affine_approximation(cam, X0)
    X = rng.uniform(-1, 1, (20, 3)) + X0
    d0, d = cam.depth(X0), cam.depth(X)
    x0 = cam.principal_point
    lhs = cam.project(X) - x0
    rhs = (d0 / d)[:, None] * (cm.project_points(PA, X) - x0)
    assert np.allclose(lhs, rhs)


def test_affine_approximation_errors(cam):
    with pytest.raises(
        CamlabInputError, match="reference_point: expected a point in front of the camera"
    ):
        af.affine_approximation(cam, cam.centre - cam.principal_axis)
    with pytest.raises(CamlabInputError, match="camera: expected a camlab.camera.Camera"):
        af.affine_approximation(cam.P, [0, 0, 0])


def test_weak_perspective_error_falls_like_one_over_distance(rng):
    cube = box_wireframe((0, 0, 0), (1, 1, 1)).reshape(-1, 3)
    rms = []
    for d in (5.0, 10.0, 20.0, 40.0):
        f = af.dolly_zoom_focal(800.0, 5.0, d)
        c = cm.Camera.look_at(
            [d, 0.3 * d, 0.2 * d], [0, 0, 0], K=cm.intrinsic_matrix(f, f, 320, 240)
        )
        rms.append(np.sqrt(np.mean(af.weak_perspective_error(c, cube, [0, 0, 0]) ** 2)))
    ratios = np.array(rms[:-1]) / np.array(rms[1:])
    assert np.all(ratios > 1.8) and np.all(
        ratios < 2.3
    )  # error ~ (size / d) * (image size): halves per doubling


def test_dolly_zoom_keeps_image_size():
    sizes = []
    for d in (3.0, 6.0, 30.0):
        f = af.dolly_zoom_focal(800.0, 3.0, d)
        c = cm.Camera.look_at([0, -d, 0], [0, 0, 0], K=cm.intrinsic_matrix(f, f, 320, 240))
        a, b = c.project([[-0.5, 0, 0], [0.5, 0, 0]])
        sizes.append(np.linalg.norm(a - b))
    assert np.allclose(sizes, sizes[0])
    assert af.dolly_zoom_focal(800, 2, 4) == 1600


def test_estimate_affine_exact_on_affine_data(rng):
    R = cm.rotation_from_euler(0.3, -0.1, 0.7)
    P = af.weak_perspective_matrix(R, [0.2, 0.1, 5], 180, 170, 3.0, (320, 240))
    X = rng.uniform(-1, 1, (12, 3))
    Pe = af.estimate_affine_camera(X, cm.project_points(P, X))
    assert np.abs(Pe - P).max() < 1e-10
    Pe4 = af.estimate_affine_camera(X[:4], cm.project_points(P, X[:4]))  # the minimum
    assert np.abs(Pe4 - P).max() < 1e-9


def test_estimate_affine_is_least_squares(rng):
    P = af.scaled_orthographic_matrix(cm.rotation_x(0.4), [0, 0, 5], 200.0, (320, 240))
    X = rng.uniform(-1, 1, (30, 3))
    uv = cm.project_points(P, X) + rng.normal(0, 1.0, (30, 2))
    Pe = af.estimate_affine_camera(X, uv)
    best = np.sum(cm.reprojection_errors(Pe, X, uv) ** 2)
    for _ in range(20):  # every perturbation of the 8 free entries does worse
        Q = Pe.copy()
        Q[:2] += rng.normal(0, 1e-3, (2, 4))
        assert np.sum(cm.reprojection_errors(Q, X, uv) ** 2) > best


def test_estimate_affine_bad_input(rng):
    X = rng.uniform(-1, 1, (3, 3))
    with pytest.raises(
        CamlabInputError,
        match=r"points_world: expected \(N, 3\) with N >= 4 point pairs, got shape \(3, 3\); an affine camera",
    ):
        af.estimate_affine_camera(X, X[:, :2])
    plane = np.column_stack([rng.uniform(-1, 1, (8, 2)), np.ones(8)])
    with pytest.raises(DegenerateError, match="coplanar"):
        af.estimate_affine_camera(plane, plane[:, :2])
    with pytest.raises(
        CamlabInputError,
        match="points_world, points_image: expected the same number of points .*got 8 and 7",
    ):
        af.estimate_affine_camera(rng.uniform(-1, 1, (8, 3)), np.zeros((7, 2)))


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(-1, 1), min_size=3, max_size=3), st.floats(0.5, 5), st.floats(-3, 3))
def test_parallel_lines_stay_parallel(direction, offset, angle):
    d = np.array(direction)
    if np.linalg.norm(d) < 1e-3:
        d = np.array([1.0, 0.0, 0.0])
    P = af.weak_perspective_matrix(
        cm.rotation_from_euler(angle, 0.3, -angle), [0, 0, 5], 100, 90, 2.0, (320, 240)
    )
    v = af.image_of_direction(P, d)
    assert v[2] == 0.0  # an ideal point: the image lines are parallel
    a = cm.project_points(P, [[0, 0, 0], d])
    b = cm.project_points(P, [[offset, 0, 1], np.array([offset, 0, 1]) + d])
    da, db = a[1] - a[0], b[1] - b[0]
    assert abs(da[0] * db[1] - da[1] * db[0]) <= 1e-9 * (
        1 + np.linalg.norm(da) * np.linalg.norm(db)
    )


def test_perspective_image_of_direction_is_vanishing_point(cam):
    d = np.array([0.0, 1.0, 0.0])
    v = af.image_of_direction(cam.P, d)
    far = cam.project(np.array([0.2, 0.0, 0.1]) + 1e7 * d)
    assert np.allclose(v[:2] / v[2], far, atol=1e-3)
    assert np.allclose(v, cam.K @ cam.R @ d)
    with pytest.raises(CamlabInputError, match="non-zero"):
        af.image_of_direction(cam.P, [0, 0, 0])


# -- lesson 05 demos and exercises ----------------------------------------------------------


def test_three_cameras_demo_difference_shrinks_with_distance():
    from camlab.widgets import affine_cameras as demos

    d = demos.three_cameras()
    d.set(distance=3.0)
    near = d.state["max_difference"]
    d.set(distance=18.0)
    assert d.state["max_difference"] < near / 3  # the largest gap inside the frame (px)
    assert af.is_affine(d.state["P_weak"])
    # a half turn about the vertical leaves the scene as it is: azimuth -90 .. 90 shows every view once

    def segments(S):
        return {frozenset(map(tuple, np.round(seg, 9) + 0.0)) for seg in S}

    scene = box_and_rails()
    assert segments(scene * [-1, -1, 1]) == segments(
        scene
    )  # demos.TARGET is on the vertical axis x = y = 0
    assert (d.controls["azimuth"].min, d.controls["azimuth"].max) == (-90, 90)
    d.set(distance=2.0)  # the slider's minimum: the near rails run behind the
    u, v = d.figure.axes[0].lines[0].get_data()  # camera, and are clipped there, not dropped
    assert np.isfinite(u).sum() == 2 * (12 + 4)  # both ends of the 12 cube edges and the 4 rails


def test_dolly_zoom_demo_state():
    from camlab.widgets import affine_cameras as demos

    d = demos.dolly_zoom()
    d.set(distance=8.0)
    assert d.state["focal"] == pytest.approx(1600.0)
    e8 = d.state["rms_error"]
    d.set(distance=32.0)
    assert d.state["rms_error"] < e8 / 3
    before = d.view.pixels()
    d.set(distance=2.0)
    assert not np.array_equal(before, d.view.pixels())


def test_parallel_rails_demo_state():
    from camlab.widgets import affine_cameras as demos

    d = demos.parallel_rails()
    assert d.state["affine_direction"][2] == 0.0
    vp = d.state["vanishing_point"]
    cam = d.state["camera"]
    far = cam.project([0.5, 1e8, 0.0])
    assert np.allclose(vp, far, atol=1e-2)
    d.set(yaw=15)
    assert d.state["vanishing_point"][0] != pytest.approx(vp[0])
    near, far_gap = d.state["sleeper_gaps"]["affine"]
    assert near == pytest.approx(far_gap)  # no shrinking with distance
    near, far_gap = d.state["sleeper_gaps"]["perspective"]
    assert near > 10 * far_gap  # perspective crowds the far sleepers


def test_parallel_rails_keeps_everything_in_frame():
    """At every corner of the yaw and pitch ranges the vanishing point, the whole affine track and the
    perspective samples the readout measures are inside the picture, and the affine track lengthens
    with pitch (what the lesson asks the student to watch)."""
    from camlab.widgets import affine_cameras as demos

    d = demos.parallel_rails()
    yaw, pitch = d.controls["yaw"], d.controls["pitch"]
    lengths = {}
    for y in (yaw.min, yaw.max):
        for p in (pitch.min, pitch.max):
            d.set(yaw=y, pitch=p)
            u, v = d.figure.axes[1].lines[0].get_data()
            ok = np.isfinite(u)
            assert (
                (u[ok].min() > 10)
                and (u[ok].max() < 630)
                and (v[ok].min() > 10)
                and (v[ok].max() < 470)
            ), (y, p)
            vp = d.state["vanishing_point"]
            assert 0 < vp[0] < 640 and 0 < vp[1] < 480, (y, p)
            samples = np.array(
                [[0.0, y_, 0.0] for y_ in (*demos.RAIL_SAMPLES, demos.RAIL_SAMPLES[1] + 1)]
            )
            uv = d.state["camera"].project(samples)
            assert np.all((uv > 0) & (uv < [640, 480])), (y, p)
            lengths[p] = np.ptp(v[ok])
    assert lengths[pitch.max] > 1.5 * lengths[pitch.min]


def test_projection_rays_top_view():
    pts = np.array([[2.8, 5.0], [1.2, 7.0]])
    ref = np.array([2.0, 6.0])
    persp = af.projection_rays(pts, ref, "perspective", 3.0)
    np.testing.assert_allclose(persp[:, 2], [[3 * 2.8 / 5, 3.0], [3 * 1.2 / 7, 3.0]])
    ortho = af.projection_rays(pts, ref, "orthographic", 3.0)
    np.testing.assert_allclose(ortho[:, 2, 0], pts[:, 0])
    weak = af.projection_rays(pts, ref, "weak perspective", 3.0)
    np.testing.assert_allclose(weak[:, 1], [[2.8, 6.0], [1.2, 6.0]])  # straight back onto z = d0
    para = af.projection_rays(pts, ref, "para-perspective", 3.0)
    # the bend lies on z = d0, reached along the line of sight to X0 (slope x0 / d0)
    np.testing.assert_allclose(
        (para[:, 0, 0] - para[:, 1, 0]) / (para[:, 0, 1] - para[:, 1, 1]), 2.0 / 6.0
    )
    # on the axis weak and para-perspective are the same camera
    np.testing.assert_allclose(
        af.projection_rays(pts - [2, 0], [0, 6], "para-perspective"),
        af.projection_rays(pts - [2, 0], [0, 6], "weak perspective"),
    )
    with pytest.raises(CamlabInputError, match="model"):
        af.projection_rays(pts, ref, "fisheye")


def test_affine_fit_departure_separates_affine_from_projective():
    assert af.affine_fit_departure([[1.1, 0.2, 5], [0.1, 0.9, -3], [0, 0, 1]], (640, 480)) < 1e-9
    # a projective part of 1e-4 per pixel bends a 640 x 480 frame by several pixels
    assert af.affine_fit_departure([[1, 0, 0], [0, 1, 0], [1e-4, 0, 1]], (640, 480)) > 5


def test_largest_gap_in_frame_counts_only_what_the_picture_shows():
    cam = cm.Camera.look_at([4.0, -3.0, 2.0], [0.0, 0.0, 0.5])
    P = af.affine_approximation(cam, [0.0, 0.0, 0.5])
    seg = np.array([[[0.0, 0.0, 0.5], [0.0, 0.0, 0.5]]])
    assert af.largest_gap_in_frame(cam, P, seg) == pytest.approx(0.0, abs=1e-9)  # exact at X0
    far = np.array([[[0.0, 500.0, 0.0], [0.0, 600.0, 0.0]]])  # out of the picture
    assert np.isnan(af.largest_gap_in_frame(cam, P, far))


def test_matched_points_pair_each_points_two_images():
    cam = cm.Camera.look_at([4.0, -3.0, 2.0], [0.0, 0.0, 0.5])
    P = af.affine_approximation(cam, [0.0, 0.0, 0.5])
    rail = np.array([[[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]])
    m = af.matched_points_in_frame(cam, P, rail, samples=3)  # the two ends and the middle
    ends = np.array([[-1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    assert m.perspective.shape == m.affine.shape == (3, 2)
    assert np.allclose(m.perspective, cam.project(ends)) and np.allclose(
        m.affine, cm.project_points(P, ends)
    )
    longest = np.linalg.norm(m.perspective - m.affine, axis=1).max()
    assert af.largest_gap_in_frame(cam, P, rail, samples=3) == pytest.approx(longest)
    with pytest.raises(CamlabInputError, match="segments"):
        af.matched_points_in_frame(cam, P, np.zeros((2, 3)))


def test_paraperspective_error_law_is_exact():
    cam = cm.Camera.look_at([4.0, -3.0, 2.0], [0.3, 0.2, 0.5])
    X0 = np.array([0.6, 0.4, 0.9])
    X = np.random.default_rng(1).uniform(-0.8, 0.8, (20, 3)) + X0
    d0 = cam.depth(X0)
    delta = cam.depth(X) - d0
    x_proj, x_para = cam.project(X), cm.project_points(af.paraperspective_approximation(cam, X0), X)
    np.testing.assert_allclose(
        x_para - x_proj, (delta / d0)[:, None] * (x_proj - cam.project(X0)), atol=1e-9
    )
    on_axis = cam.centre + 5.0 * cam.R[2]
    np.testing.assert_allclose(
        af.paraperspective_approximation(cam, on_axis),
        af.affine_approximation(cam, on_axis),
        atol=1e-12,
    )


def test_lesson05_exercises(capsys):
    from camlab.exercises import all_exercises, check

    for name in ("affine_approximation", "estimate_affine_camera"):
        ex = all_exercises()[name]
        assert ex.lesson == "05" and check(name, ex.reference)
    with pytest.raises(AssertionError, match="depth of the world origin"):
        check(
            "affine_approximation",
            lambda c, X0: (lambda E: c.K @ E / c.t[2])(
                np.vstack([np.c_[c.R[:2], c.t[:2]], [0, 0, 0, c.t[2]]])
            ),
        )


def test_three_images_of_a_scene(cam):
    from camlab.fixtures import box_and_rails

    segs = box_and_rails()
    imgs = af.three_images(cam, segs)
    assert isinstance(imgs, af.ThreeImages) and imgs.perspective.shape == imgs.weak.shape == (
        len(segs),
        2,
        2,
    )
    np.testing.assert_allclose(imgs.perspective, cm.project_segments(cam, segs))
    centre = segs.reshape(-1, 3).mean(axis=0)  # weak perspective is exact at the scene's centroid
    np.testing.assert_allclose(
        cm.project_points(imgs.P_weak, centre), cam.project(centre), atol=1e-9
    )
    assert af.is_affine(imgs.P_weak) and af.is_affine(imgs.P_orth)
    # parallel rails stay parallel in both affine images
    for img in (imgs.weak, imgs.orthographic):
        d = img[-4:, 1] - img[-4:, 0]
        assert np.allclose(d[:, 0] * d[0, 1] - d[:, 1] * d[0, 0], 0, atol=1e-9)
    with pytest.raises(CamlabInputError, match="segments"):
        af.three_images(cam, segs[:, 0])


def test_dolly_zoom_camera_keeps_the_target_size_and_the_error_falls_like_one_over_d():
    target = np.array([0.0, 0.0, 0.5])
    near, far = (
        af.dolly_zoom_camera(d, np.radians(-40), np.radians(20), target) for d in (4.0, 16.0)
    )
    assert np.isclose(np.linalg.norm(near.centre - target), 4.0) and np.isclose(
        far.K[0, 0], 4 * near.K[0, 0]
    )
    np.testing.assert_allclose(near.project(target), [319.5, 239.5], atol=1e-9)  # looking at it
    # image_offset slides the camera sideways; it then moves along its own principal axis (H&Z 6.3.1):
    # one R, the target exactly 100 px right at depth d, and P_inf about the target one fixed matrix.
    off = [
        af.dolly_zoom_camera(d, np.radians(-40), np.radians(20), target, image_offset=100.0)
        for d in (2.0, 16.0, 64.0)
    ]
    for d, cam in zip((2.0, 16.0, 64.0), off, strict=True):
        np.testing.assert_allclose(cam.project(target), [419.5, 239.5], atol=1e-9)
        assert cam.depth(target) == pytest.approx(d) and np.allclose(cam.R, near.R)
        np.testing.assert_allclose(
            af.affine_approximation(cam, target), af.affine_approximation(off[0], target), atol=1e-9
        )
    step = off[1].centre - off[0].centre
    np.testing.assert_allclose(step, -14.0 * near.R[2], atol=1e-9)  # along the principal axis
    cube = box_wireframe((0, 0, 0.5), (1, 1, 1)).reshape(-1, 3)
    d = np.array([8.0, 16.0, 32.0])
    rms = af.dolly_zoom_errors(cube, d, np.radians(-40), np.radians(20), target)
    np.testing.assert_allclose(
        rms[:-1] / rms[1:], 2.0, rtol=0.05
    )  # doubling the distance halves the error


def test_paraperspective_is_perspective_to_first_order_and_weak_perspective_is_not():
    cam = cm.Camera.look_at([4.0, -3.0, 2.0], [0.3, 0.2, 0.5])
    X0 = np.array([0.6, 0.4, 0.9])  # off the optical axis
    P_para, P_weak = af.paraperspective_approximation(cam, X0), af.affine_approximation(cam, X0)
    assert af.is_affine(P_para)
    assert np.allclose(cm.project_points(P_para, X0), cam.project(X0))
    step = np.array([0.3, -0.5, 0.8])

    def gap(P, s):
        X = X0 + s * step
        return np.linalg.norm(cam.project(X) - cm.project_points(P, X))

    assert gap(P_para, 0.01) / gap(P_para, 0.1) == pytest.approx(0.01, rel=0.05)  # second order
    assert gap(P_weak, 0.01) / gap(P_weak, 0.1) == pytest.approx(0.1, rel=0.1)  # first order
    on_axis = cm.Camera.look_at([4.0, -3.0, 2.0], X0)  # X0 on the optical axis:
    assert np.allclose(
        af.paraperspective_approximation(on_axis, X0), af.affine_approximation(on_axis, X0)
    )


def test_paraperspective_rejects_a_point_behind_the_camera():
    cam = cm.Camera.look_at([0.0, -4.0, 0.0], [0.0, 0.0, 0.0])
    with pytest.raises(CamlabInputError, match="in front of the camera"):
        af.paraperspective_approximation(cam, [0.0, -8.0, 0.0])


def test_paraperspective_looks_along_the_line_of_sight_to_X0_not_the_optical_axis():
    cam = cm.Camera.look_at([4.0, -3.0, 2.0], [0.0, 0.0, 0.5])
    X0 = np.array([0.6, 0.4, 0.9])
    C = cm.camera_centre(af.paraperspective_approximation(cam, X0))
    sight = (X0 - cam.centre) / np.linalg.norm(X0 - cam.centre)
    d = C[:3] / np.linalg.norm(C[:3])
    assert abs(C[3]) < 1e-12 and abs(abs(d @ sight) - 1) < 1e-12
    assert abs(d @ cam.R[2]) < 0.999  # X0 is off the axis: not r3
    weak = cm.camera_centre(af.affine_approximation(cam, X0))
    assert abs(abs(weak[:3] @ cam.R[2]) / np.linalg.norm(weak[:3]) - 1) < 1e-12


def test_a_camera_slid_in_its_principal_plane_gives_an_affine_homography_of_any_plane():
    """Why an affine homography does not prove affine cameras (lesson 05, section 3)."""
    low = cm.Camera.look_at(
        [0.0, 0.0, 2.0], [0.0, 10.0, 0.0], K=cm.intrinsic_matrix(800, 800, 319.5, 239.5)
    )
    for shift, affine in (
        ([1.5, 0.0, 0.0], True),
        ([0.0, 0.7, 0.0], True),
        ([0.0, 0.0, 1.5], False),
    ):
        moved = low.replace(t=low.t - np.array(shift))
        H = moved.P[:, [0, 1, 3]] @ np.linalg.inv(
            low.P[:, [0, 1, 3]]
        )  # the ground z = 0 from one view to the other
        departure = af.affine_fit_departure(H, (640, 480))
        assert (departure < 1e-9) if affine else (departure > 100), (shift, departure)


def _reference_markers(ax):
    from camlab.widgets.affine_cameras import REFERENCE_MARKER

    return [ln for ln in ax.lines if ln.get_marker() == REFERENCE_MARKER["marker"]]


@pytest.mark.parametrize("settings", [{}, {"azimuth": 90, "distance": 2.0}, {"elevation": 80}])
def test_three_cameras_marks_X0_in_every_panel_where_it_images(settings):
    from camlab.widgets import affine_cameras as demos

    d = demos.three_cameras()
    d.set(**settings)
    for ax, xy in zip(d.figure.axes, d.state["reference_images"], strict=True):
        (marker,) = _reference_markers(ax)
        assert np.allclose(np.column_stack(marker.get_data())[0], xy)
    assert np.allclose(
        d.state["reference_images"][0], d.state["reference_images"][1]
    )  # exact at X0


@pytest.mark.parametrize("offset", [0, 100])
def test_dolly_zoom_draws_each_affine_cube_in_its_own_panel_with_X0_and_the_principal_point(offset):
    """The para-perspective cube is not hidden under the weak-perspective dashes: each has its panel."""
    from camlab.widgets import affine_cameras as demos

    d = demos.dolly_zoom()
    d.set(offset=offset)
    ax_weak, ax_para, _ = d.figure.axes
    for ax, model in ((ax_weak, "weak perspective"), (ax_para, "para-perspective")):
        colours = {ln.get_color() for ln in ax.lines}
        assert demos.COLOURS[model] in colours and demos.COLOURS["perspective"] in colours
        other = "para-perspective" if model == "weak perspective" else "weak perspective"
        assert demos.COLOURS[other] not in colours
        (marker,) = _reference_markers(ax)
        assert np.allclose(np.column_stack(marker.get_data())[0], d.state["reference_image"])
    assert (
        abs(d.state["reference_image"][0] - 319.5 - offset) < 2.0
    )  # X0 images `offset` px right of centre
    if offset:
        assert d.state["rms_paraperspective"] < 0.8 * d.state["rms_error"]


def test_parallel_rails_marks_X0_in_both_panels_at_the_same_pixel():
    from camlab.widgets import affine_cameras as demos

    d = demos.parallel_rails()
    d.set(yaw=10, pitch=12)
    (p,), (a,) = (_reference_markers(ax) for ax in d.figure.axes)
    assert np.allclose(np.column_stack(p.get_data()), np.column_stack(a.get_data()))
    assert np.allclose(np.column_stack(a.get_data())[0], d.state["reference_image"])


def test_projection_rays_marks_X0_in_all_four_panels_and_the_line_of_sight_in_para_perspective():
    from camlab.widgets import affine_cameras as demos

    d = demos.projection_rays()
    d.set(offset=2.5)
    for ax in d.figure.axes:
        (marker,) = _reference_markers(ax)
        assert np.allclose(np.column_stack(marker.get_data())[0], d.state["reference"])
    from_centre = [
        ln
        for ln in d.figure.axes[2].lines
        if len(ln.get_xdata()) == 2
        and ln.get_linestyle() == "-."
        and np.allclose([ln.get_xdata()[0], ln.get_ydata()[0]], 0.0)
    ]
    (sight,) = from_centre  # one dash-dot line from the camera centre ...
    x, z = sight.get_data()
    assert np.isclose(
        x[1] / z[1], 2.5 / demos.RAY_DEPTH
    )  # ... through X0: the para-perspective rays' direction


def test_dolly_zoom_error_axis_fits_its_curves_and_the_distance_slider_is_logarithmic():
    """The y axis spans the curves at every offset (no empty decades), the markers are not clipped at the
    slider's ends, and the distance slider moves in equal ratios, as the log x axis does."""
    import ipywidgets as W

    from camlab.widgets import affine_cameras as demos

    lo, hi = demos.DOLLY_ERROR_LIMITS
    distances = np.geomspace(*demos.DOLLY_DISTANCES, 60)
    curves = [c for offset in (0, 50, 100) for c in demos.dolly_curves(offset, distances).values()]
    assert all(lo < c.min() and c.max() < hi for c in curves)
    assert (
        min(c.min() for c in curves) < 2 * lo and max(c.max() for c in curves) > hi / 2
    )  # no empty decade
    d = demos.dolly_zoom()
    assert isinstance(d.controls["distance"], W.FloatLogSlider)
    for marker in d.figure.axes[2].lines[-2:]:
        assert marker.get_marker() == "o" and not marker.get_clip_on()
    pp = [ln for ln in d.figure.axes[0].lines if ln.get_marker() == "+"]
    (marker,) = _reference_markers(d.figure.axes[0])
    assert (
        pp and pp[0].get_zorder() > marker.get_zorder()
    )  # the + stays visible on the diamond at offset 0


def test_affine_departure_maps_the_gap_over_the_frame_and_at_given_points():
    H = np.array([[1.0, 0.02, 3.0], [0.01, 0.98, -2.0], [2e-4, -1e-4, 1.0]])
    pts = np.array([[0.0, 0.0], [639.0, 479.0], [320.0, 240.0]])
    dep = af.affine_departure(H, (640, 480), samples=20, points=pts)
    assert dep.u.shape == dep.v.shape == dep.distance.shape == (20, 20) and dep.at_points.shape == (
        3,
    )
    assert dep.distance.max() == af.affine_fit_departure(H, (640, 480), samples=20)
    corners = dep.distance[[0, -1], :][:, [0, -1]]  # grid corners = the frame's corner pixels
    assert np.isclose(dep.at_points[0], corners[0, 0]) and np.isclose(
        dep.at_points[1], corners[1, 1]
    )
    affine = af.affine_departure([[1.1, 0.2, 5], [0.1, 0.9, -3], [0, 0, 1]], (640, 480), points=pts)
    assert affine.distance.max() < 1e-9 and affine.at_points.max() < 1e-9
    assert af.affine_departure(H, (640, 480)).at_points.size == 0
    with pytest.raises(CamlabInputError, match="points"):
        af.affine_departure(H, (640, 480), points=[1.0, 2.0, 3.0])
