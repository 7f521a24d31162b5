"""Tests for camlab.rectification on synthetic rigs and the rendered rig (data/stereo), with OpenCV cross-checks."""

import cv2
import numpy as np
import pytest

from camlab import epipolar as ep
from camlab import rectification as rc
from camlab._validate import CamlabInputError, DegenerateError
from camlab.camera import Camera, rotation_from_axis_angle
from camlab.data.stereo import load_stereo_rig
from camlab.distortion import undistort_pixels
from camlab.projective import map_points


@pytest.fixture(scope="module")
def rig():
    return load_stereo_rig()


@pytest.fixture(scope="module")
def rect(rig):
    return rc.rectify_calibrated(rig.camera1, rig.camera2, alpha=0.0)


def _opencv_rectify(c1, c2, alpha):
    R, t = ep.relative_pose(c1, c2)
    return cv2.stereoRectify(
        c1.K,
        np.array(c1.dist),
        c2.K,
        np.array(c2.dist),
        c1.image_size,
        R,
        t.reshape(3, 1),
        alpha=alpha,
    )  # OpenCV 5 wants T as (3, 1)


def _true_corners(rig):
    return rig.calib_corners_left.reshape(-1, 2), rig.calib_corners_right.reshape(-1, 2)


def test_calibrated_vertical_disparity_of_true_correspondences(rig, rect):
    tl, tr = _true_corners(rig)
    before = rc.vertical_disparity(tl, tr)
    after = rc.vertical_disparity(
        rc.rectify_points(rect, rig.camera1, tl, 1), rc.rectify_points(rect, rig.camera2, tr, 2)
    )
    assert before.median > 5  # the raw pair is far from rectified
    assert after.median < 0.1 and after.p95 < 0.1
    R1, R2, P1, P2, *_ = _opencv_rectify(rig.camera1, rig.camera2, 0.0)
    z1 = cv2.undistortPoints(
        tl.reshape(-1, 1, 2), rig.camera1.K, np.array(rig.camera1.dist), R=R1, P=P1
    ).reshape(-1, 2)
    z2 = cv2.undistortPoints(
        tr.reshape(-1, 1, 2), rig.camera2.K, np.array(rig.camera2.dist), R=R2, P=P2
    ).reshape(-1, 2)
    theirs = rc.vertical_disparity(z1, z2)
    assert after.median <= 1.1 * theirs.median + 1e-6
    assert after.p95 <= 1.1 * theirs.p95 + 1e-6


def test_calibrated_vertical_disparity_on_rectified_images_vs_opencv(rig, rect):
    """Rectify the rendered chessboard views, detect corners in both rectified images, compare rows."""
    R1, R2, P1, P2, *_ = _opencv_rectify(rig.camera1, rig.camera2, 0.0)
    cv_maps = [
        cv2.initUndistortRectifyMap(
            c.K, np.array(c.dist), Rr, P[:3, :3], c.image_size, cv2.CV_32FC1
        )
        for c, Rr, P in ((rig.camera1, R1, P1), (rig.camera2, R2, P2))
    ]
    ours, theirs = [], []
    for a, b in zip(rig.calib_left, rig.calib_right, strict=True):
        pairs = (
            rc.rectify_images(rect, a, b),
            [cv2.remap(img, *m, cv2.INTER_LINEAR) for img, m in zip((a, b), cv_maps, strict=True)],
        )
        for (A, B), store in zip(pairs, (ours, theirs), strict=True):
            f1, p = cv2.findChessboardCornersSB(A, rig.pattern_size)
            f2, q = cv2.findChessboardCornersSB(B, rig.pattern_size)
            assert f1 and f2
            p, q = p.reshape(-1, 2), q.reshape(-1, 2)
            if np.linalg.norm(p[0] - q[0]) > np.linalg.norm(p[0] - q[-1]):
                q = q[::-1]
            store.append(np.abs(p[:, 1] - q[:, 1]))
    ours, theirs = np.concatenate(ours), np.concatenate(theirs)
    assert np.median(ours) < 0.1
    # Both are at the corner detector's noise level (about 0.015 px); allow 0.005 px of that noise.
    assert np.median(ours) <= 1.1 * np.median(theirs) + 0.005
    assert np.mean(ours) <= 1.1 * np.mean(theirs) + 0.005


def test_rotations_close_to_opencv_and_rectified_cameras_are_parallel(rig, rect):
    R1, R2, *_ = _opencv_rectify(rig.camera1, rig.camera2, 0.0)
    # Same construction up to how the common orientation is split: within 0.5 degree.
    for a, b in ((rect.R1, R1), (rect.R2, R2)):
        angle = np.arccos(np.clip((np.trace(a @ b.T) - 1) / 2, -1, 1))
        assert angle < np.deg2rad(0.5)
        assert np.allclose(a @ a.T, np.eye(3), atol=1e-12) and np.isclose(np.linalg.det(a), 1)
    F = ep.fundamental_from_cameras(rect.camera1, rect.camera2)
    assert np.allclose(
        np.abs(F), np.abs(ep.normalise_fundamental(ep.skew([1.0, 0.0, 0.0]))), atol=1e-12
    )
    assert np.isclose(rect.baseline, np.linalg.norm(rig.camera2.centre - rig.camera1.centre))
    assert np.allclose(rect.P2[:, 3], rect.K @ [-rect.baseline, 0, 0])


def test_numpy_maps_equal_opencv_maps(rig, rect):
    for cam, Rr, m in ((rig.camera1, rect.R1, rect.maps1), (rig.camera2, rect.R2, rect.maps2)):
        mu, mv = cv2.initUndistortRectifyMap(
            cam.K, np.array(cam.dist), Rr, rect.K, rect.image_size, cv2.CV_32FC1
        )
        inside = (mu > 0) & (mu < 639) & (mv > 0) & (mv < 479)
        assert inside.mean() > 0.95
        assert (
            np.abs(mu - m.map_u)[inside].max() < 1e-3 and np.abs(mv - m.map_v)[inside].max() < 1e-3
        )
    fast = rc.rectify_calibrated(rig.camera1, rig.camera2, 0.0, method="cv2")
    assert (
        np.allclose(fast.K, rect.K)
        and np.abs(fast.maps1.map_u - rect.maps1.map_u)[inside].max() < 1e-3
    )


def test_alpha_trades_black_border_for_lost_pixels(rig):
    cov = {
        a: rc.rectification_coverage(
            rc.rectify_calibrated(rig.camera1, rig.camera2, a), rig.camera1, rig.camera2
        )
        for a in (0.0, 0.5, 1.0)
    }
    assert cov[0.0]["valid1"] > 0.995 and cov[0.0]["valid2"] > 0.995  # no black border
    assert cov[1.0]["kept1"] > 0.995 and cov[1.0]["kept2"] > 0.995  # no lost pixel
    assert cov[0.0]["kept1"] < cov[0.5]["kept1"] < cov[1.0]["kept1"]
    assert cov[0.0]["valid1"] > cov[0.5]["valid1"] > cov[1.0]["valid1"]


def test_q_matrix_matches_reproject_image_to_3d(rect):
    disp = np.full((480, 640), np.nan, dtype=np.float32)
    disp[100:110, 200:220] = 40.0
    from camlab.disparity import disparity_to_points

    pts = disparity_to_points(disp, rect.K, rect.baseline)
    cvp = cv2.reprojectImageTo3D(np.nan_to_num(disp, nan=0).astype(np.float32), rect.Q)[
        100:110, 200:220
    ].reshape(-1, 3)
    assert np.allclose(pts, cvp, rtol=1e-5)
    assert np.allclose(pts[:, 2], rect.K[0, 0] * rect.baseline / 40.0)


def test_uncalibrated_vertical_disparity_vs_opencv(rig):
    c1, c2 = rig.camera1, rig.camera2
    tl, tr = _true_corners(rig)
    ul, ur = undistort_pixels(tl, c1.K, c1.dist), undistort_pixels(tr, c2.K, c2.dist)
    # Matches: true scene points (undistorted pixels) with 0.3 px noise, F by the 8-point algorithm.
    rng = np.random.default_rng(4)
    X = rng.uniform([-0.6, 1.5, 0.5], [0.6, 3.5, 1.4], (300, 3))
    cu1, cu2 = c1.replace(dist=(0.0,) * 5), c2.replace(dist=(0.0,) * 5)
    x1, x2 = cu1.project(X), cu2.project(X)
    x1, x2 = x1 + rng.normal(0, 0.3, x1.shape), x2 + rng.normal(0, 0.3, x2.shape)
    F = ep.estimate_fundamental_matrix(x1, x2)
    res = rc.rectify_uncalibrated(x1, x2, F, (640, 480))
    ours = rc.vertical_disparity(map_points(res.H1, ul), map_points(res.H2, ur))
    ok, H1, H2 = cv2.stereoRectifyUncalibrated(x1, x2, F, (640, 480))
    theirs = rc.vertical_disparity(map_points(H1, ul), map_points(H2, ur))
    assert ours.median < 0.5
    assert ours.median <= 1.1 * theirs.median
    # With the true F both are exact.
    Ft = ep.fundamental_from_cameras(cu1, cu2)
    exact = rc.rectify_uncalibrated(x1, x2, Ft, (640, 480))
    assert rc.vertical_disparity(map_points(exact.H1, ul), map_points(exact.H2, ur)).max < 1e-6


def test_uncalibrated_keeps_images_upright_and_inside(rig):
    c1, c2 = rig.camera1.replace(dist=(0.0,) * 5), rig.camera2.replace(dist=(0.0,) * 5)
    rng = np.random.default_rng(1)
    X = rng.uniform([-0.6, 1.5, 0.5], [0.6, 3.5, 1.4], (100, 3))
    F = ep.fundamental_from_cameras(c1, c2)
    res = rc.rectify_uncalibrated(c1.project(X), c2.project(X), F, (640, 480))
    corners = np.array([[0, 0], [639, 0], [639, 479], [0, 479]], float)
    for H in (res.H1, res.H2):
        q = map_points(H, corners)
        assert q[0, 0] < q[1, 0] and q[0, 1] < q[3, 1]  # not mirrored or upside down
        assert (
            q[:, 0].min() > -1
            and q[:, 0].max() < 641
            and q[:, 1].min() > -1
            and q[:, 1].max() < 481
        )
        # the shear keeps the image's corners close to right angles
        e1, e2 = q[1] - q[0], q[3] - q[0]
        assert abs(e1 @ e2) / (np.linalg.norm(e1) * np.linalg.norm(e2)) < 0.1
    # rectified epipolar geometry: F' ~ [i]_x
    Hi1, Hi2 = np.linalg.inv(res.H1), np.linalg.inv(res.H2)
    Fr = ep.normalise_fundamental(Hi2.T @ F @ Hi1)
    assert np.allclose(
        np.abs(Fr), np.abs(ep.normalise_fundamental(ep.skew([1.0, 0, 0]))), atol=1e-6
    )


def test_rectify_images_shapes_and_border(rig, rect):
    A, B = rc.rectify_images(rect, rig.left, rig.right)
    assert A.shape == rig.left.shape and A.dtype == np.uint8
    U = rc.UncalibratedRectification(np.eye(3), np.diag([0.5, 0.5, 1.0]), (640, 480))
    _, B2 = rc.rectify_images(U, rig.left, rig.right)
    assert B2[300:, 400:].max() == 0 and B2[:200, :300].mean() > 20  # half size: black outside
    with pytest.raises(CamlabInputError, match="interpolation"):
        rc.rectify_images(rect, rig.left, rig.right, interpolation="cubic")


def test_vertical_disparity_known_answer_and_nan_handling():
    v = rc.vertical_disparity([[0, 1], [0, 2], [np.nan, 0]], [[5, 1.5], [9, 2], [1, 1]])
    assert v.median == 0.25 and v.max == 0.5 and len(v.values) == 2


def _simple_rig(offset=(0.1, 0.0, 0.0), yaw2=0.0):
    c1 = Camera.look_at([0, -2, 1], [0, 0, 1])
    R2 = rotation_from_axis_angle([0, yaw2, 0]) @ c1.R
    C2 = c1.centre + np.asarray(offset, float)
    return c1, Camera(c1.K, R2, -R2 @ C2)


def test_bad_input_messages():
    c1, c2 = _simple_rig()
    with pytest.raises(DegenerateError, match="same centre"):
        rc.rectify_calibrated(c1, c1)
    with pytest.raises(CamlabInputError, match=r"alpha: expected a number in \[0, 1\]"):
        rc.rectify_calibrated(c1, c2, alpha=2)
    with pytest.raises(DegenerateError, match="vertical"):
        rc.rectify_calibrated(*_simple_rig(offset=(0.0, 0.0, 0.2)))
    with pytest.raises(DegenerateError, match="opposite directions|no region in common|behind"):
        rc.rectify_calibrated(*_simple_rig(offset=(0.3, 0.0, 0.0), yaw2=np.pi))
    with pytest.raises(
        DegenerateError, match="no region in common"
    ):  # toed out by 52 degrees: no overlap
        rc.rectify_calibrated(*_simple_rig(offset=(0.3, 0.0, 0.0), yaw2=0.9))
    with pytest.raises(DegenerateError, match="behind the rectified camera"):  # 80 degrees apart
        rc.rectify_calibrated(*_simple_rig(offset=(0.3, 0.0, 0.0), yaw2=1.4))
    with pytest.raises(CamlabInputError, match="camera1: expected a camlab.camera.Camera"):
        rc.rectify_calibrated(c1.P, c2)
    with pytest.raises(CamlabInputError, match="which"):
        rc.rectify_points(rc.rectify_calibrated(c1, c2, maps=False), c1, [1, 2], 3)


def test_uncalibrated_forward_motion_is_degenerate():
    c1, c2 = _simple_rig(offset=(0.0, 0.5, 0.0))  # straight ahead: the epipole is the image centre
    rng = np.random.default_rng(0)
    X = rng.uniform([-0.5, 1.0, 0.5], [0.5, 2.0, 1.5], (40, 3))
    F = ep.fundamental_from_cameras(c1, c2)
    with pytest.raises(DegenerateError, match="epipole of image 2 is inside the image"):
        rc.rectify_uncalibrated(c1.project(X), c2.project(X), F, (640, 480))
    with pytest.raises(CamlabInputError, match="N >= 8"):
        rc.rectify_uncalibrated(c1.project(X)[:5], c2.project(X)[:5], F, (640, 480))


def test_rectify_unrectify_round_trip(rig, rect):
    tl, tr = _true_corners(rig)
    for cam, pts, which in ((rig.camera1, tl, 1), (rig.camera2, tr, 2)):
        back = rc.unrectify_points(rect, cam, rc.rectify_points(rect, cam, pts, which), which)
        assert np.abs(back - pts).max() < 1e-6
    # and the remap tables store exactly unrectify_points
    m = rect.maps1
    assert np.allclose(
        rc.unrectify_points(rect, rig.camera1, [[100.0, 50.0]], 1),
        [[m.map_u[50, 100], m.map_v[50, 100]]],
        atol=1e-3,
    )


def _angle_deg(A, B):
    return np.degrees(np.arccos(np.clip((np.trace(A @ B.T) - 1) / 2, -1, 1)))


def test_stereo_calibrate_matches_opencv_and_truth(rig):
    from camlab.calibration import find_chessboard

    p1 = [find_chessboard(im, rig.pattern_size).corners for im in rig.calib_left]
    p2 = [find_chessboard(im, rig.pattern_size).corners for im in rig.calib_right]
    sc = rc.stereo_calibrate(rig.object_points, p1, p2, (640, 480))
    assert sc.converged and sc.rms < 0.2
    R, t = ep.relative_pose(rig.camera1, rig.camera2)
    assert (
        _angle_deg(sc.R, R) < 0.5 and np.linalg.norm(sc.t - t) < 0.005
    )  # 5 mm of a 12 cm baseline
    obj = [rig.object_points.astype(np.float32)] * len(p1)
    rms, *_, Rc, tc, _, _ = cv2.stereoCalibrate(
        obj,
        [p.astype(np.float32) for p in p1],
        [p.astype(np.float32) for p in p2],
        sc.K1,
        sc.dist1,
        sc.K2,
        sc.dist2,
        (640, 480),
        flags=cv2.CALIB_FIX_INTRINSIC,
    )
    # the same problem (fixed intrinsics): the same optimum
    assert abs(sc.rms - rms) < 1e-4
    assert _angle_deg(sc.R, Rc) < 1e-3 and np.linalg.norm(sc.t - tc.ravel()) < 1e-5
    cam1, cam2 = sc.cameras()
    assert np.allclose(ep.relative_pose(cam1, cam2)[0], sc.R)


def test_stereo_calibrate_bad_input(rig):
    tl = list(rig.calib_corners_left)
    with pytest.raises(CamlabInputError, match="same number"):
        rc.stereo_calibrate(rig.object_points, tl, tl[:-1], (640, 480))
    with pytest.raises(CamlabInputError, match=">= 3"):
        rc.stereo_calibrate(rig.object_points, tl[:2], tl[:2], (640, 480))
    with pytest.raises(CamlabInputError, match="corners per view"):
        rc.stereo_calibrate(rig.object_points, [t[:-1] for t in tl], tl, (640, 480))


from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


@settings(max_examples=25, deadline=None)
@given(
    st.floats(0.05, 0.5),
    st.floats(-0.15, 0.15),
    st.floats(-0.05, 0.05),
    st.floats(-0.05, 0.05),
    st.floats(-0.03, 0.03),
    st.integers(0, 10_000),
)
def test_property_rows_match_after_rectification(base, yaw, pitch, roll, dz, seed):
    """Any horizontal rig with a small relative rotation: calibrated and uncalibrated (true F) rectification
    put every true match on one row."""
    rng = np.random.default_rng(seed)
    c1 = Camera.look_at([0, -2, 1], [0, 0, 1])
    R2 = rotation_from_axis_angle([pitch, yaw, roll]) @ c1.R
    C2 = c1.centre + [base, 0.0, dz]
    c2 = Camera(c1.K, R2, -R2 @ C2)
    X = rng.uniform([-0.8, 0.5, 0.4], [0.8, 3.0, 1.6], (40, 3))
    x1, x2 = c1.project(X), c2.project(X)
    ok = np.all(np.isfinite(x1), axis=1) & np.all(np.isfinite(x2), axis=1)
    x1, x2 = x1[ok], x2[ok]
    rect = rc.rectify_calibrated(c1, c2, alpha=0.5, maps=False)
    assert (
        rc.vertical_disparity(
            rc.rectify_points(rect, c1, x1, 1), rc.rectify_points(rect, c2, x2, 2)
        ).max
        < 1e-6
    )
    F = ep.fundamental_from_cameras(c1, c2)
    try:
        unc = rc.rectify_uncalibrated(x1, x2, F, (640, 480))
    except DegenerateError:
        return  # the epipole fell inside the image (strong toe-in): no homography rectification exists
    assert rc.vertical_disparity(map_points(unc.H1, x1), map_points(unc.H2, x2)).max < 1e-5


def test_masked_disparity_masks_the_warp_border_and_the_wedge(rig):
    """Nothing is matched on the left border; no kept match lands in the right image's border."""
    und = [
        cv2.undistort(im, c.K, np.array(c.dist))
        for im, c in ((rig.left, rig.camera1), (rig.right, rig.camera2))
    ]
    from camlab.fixtures.stereo import true_matches

    c1, c2 = (c.replace(dist=(0.0,) * 5) for c in (rig.camera1, rig.camera2))
    _, _, u1, u2 = true_matches(rig, step=40, start=30)  # undistorted true matches
    unc = rc.rectify_uncalibrated(u1, u2, ep.fundamental_from_cameras(c1, c2), (640, 480))
    md = rc.masked_disparity(unc, *und, max_disparity=48, min_disparity=0)
    assert md.disparity.shape == md.left.shape == (240, 320)
    assert not np.isfinite(md.disparity[~md.inside_left]).any() and md.inside_left.mean() > 0.8
    vv, uu = np.nonzero(np.isfinite(md.disparity))
    assert len(vv) > 0.3 * md.disparity.size
    u_r = np.round(uu - md.disparity[vv, uu]).astype(int)
    assert (u_r >= 0).all() and md.inside_right[vv, u_r].all()
    assert not np.isfinite(md.disparity[md.wedge]).any()
    with pytest.raises(CamlabInputError, match="scale: expected 0 < scale <= 1"):
        rc.masked_disparity(unc, *und, scale=2)
    with pytest.raises(CamlabInputError, match="grey"):
        rc.masked_disparity(unc, np.dstack([und[0]] * 3), und[1])


def test_pair_warnings_name_an_epipole_inside_and_too_few_inliers():
    """Forward motion puts the epipole in the image; a sideways step does not; < 50 inliers warns."""
    forward = ep.fundamental_from_cameras(*_simple_rig(offset=(0.0, 0.5, 0.0)))
    sideways = ep.fundamental_from_cameras(*_simple_rig(offset=(0.2, 0.0, 0.0)))
    found = rc.pair_warnings(forward, 200, (640, 480))
    assert len(found) == 2 and all("inside the image" in s for s in found)
    assert rc.pair_warnings(sideways, 200, (640, 480)) == []
    (few,) = rc.pair_warnings(sideways, 20, (640, 480))
    assert "only 20 matches" in few


def test_walls_specks_finds_a_low_patch_beside_the_wedge_and_where_its_match_lies():
    """A 6-pixel patch at d = 20 on paving at d = 80, beside the wedge, whose true match is in the border."""
    from camlab.fixtures.stereo_walls import walls_specks

    d = np.full((50, 120), 80.0)
    d[45:47, 100:103] = 20.0  # the speck: 6 pixels, bottom fifth, below half the paving
    d[45:47, 103:106] = np.nan  # the wedge beside it
    wedge = np.isnan(d)
    inside_right = np.ones(d.shape, bool)
    inside_right[:, :25] = False  # u - 80 < 25 for u < 105: the speck's true match is border
    sp = walls_specks(d, wedge, inside_right)
    assert sp.mask.sum() == 6 and sp.paving == 80.0
    assert sp.borders_wedge.tolist() == [True] and sp.disparity.tolist() == [20.0]
    assert (
        sp.true_match_in_border.tolist() == [1.0]
        and sp.size.tolist() == [6]
        and sp.first_column.tolist() == [100]
    )
