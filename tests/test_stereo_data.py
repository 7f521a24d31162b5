"""The bundled stereo rig: deterministic, consistent with its ground truth."""

import numpy as np

from camlab import epipolar as ep
from camlab import rectification as rc
from camlab.data import load_stereo_rig
from camlab.distortion import undistort_pixels
from camlab.fixtures.stereo import STEREO_PARAMS, rig_cameras
from camlab.projective import map_points


def test_bundled_rig_loads_and_matches_its_generator_cameras():
    rig = load_stereo_rig()
    c1, c2 = rig_cameras(STEREO_PARAMS)
    assert np.allclose(rig.camera1.K, c1.K) and np.allclose(rig.camera2.R, c2.R, atol=1e-12)
    assert rig.left.shape == (480, 640) and rig.left.dtype == np.uint8
    assert len(rig.calib_left) == STEREO_PARAMS["n_calib"]
    # ground-truth corners are the projections of the boards through the cameras (with distortion)
    assert np.all(np.isfinite(rig.calib_corners_left))
    d = rig.disparity[np.isfinite(rig.disparity)]
    assert 0.8 < np.isfinite(rig.disparity).mean() <= 1 and 15 < d.min() < d.max() < 90


def test_true_disparity_agrees_with_calibrated_rectification():
    rig = load_stereo_rig()
    rect = rc.rectify_calibrated(
        rig.camera1, rig.camera2, alpha=STEREO_PARAMS["rectify_alpha"], maps=False
    )
    # a wall point: project through both rectified cameras, disparity = u1 - u2
    X = np.array([[0.3, 4.2, 1.6], [-1.2, 4.2, 2.0]])
    u1, u2 = rect.camera1.project(X), rect.camera2.project(X)
    assert np.allclose(u1[:, 1], u2[:, 1])
    d = u1[:, 0] - u2[:, 0]
    stored = rig.disparity[np.round(u1[:, 1]).astype(int), np.round(u1[:, 0]).astype(int)]
    assert np.allclose(stored, d, atol=0.05)
    assert np.allclose(ep.triangulate_points(rect.camera1, rect.camera2, u1, u2), X, atol=1e-9)


def test_true_matches_are_exact_correspondences():
    from camlab.fixtures.stereo import true_matches

    rig = load_stereo_rig()
    x1, x2, u1, u2 = true_matches(rig, step=40, start=30)
    assert x1.shape == x2.shape and len(x1) > 100
    assert np.all((x1 > 0) & (x1 < [639, 479]) & (x2 > 0) & (x2 < [639, 479]))
    # carried to the rectified images they lie on one row, apart by the true disparity
    rect = rc.rectify_calibrated(
        rig.camera1, rig.camera2, alpha=STEREO_PARAMS["rectify_alpha"], maps=False
    )
    r1, r2 = (
        rc.rectify_points(rect, rig.camera1, x1, 1),
        rc.rectify_points(rect, rig.camera2, x2, 2),
    )
    assert np.abs(r1[:, 1] - r2[:, 1]).max() < 1e-6
    d = rig.disparity[np.round(r1[:, 1]).astype(int), np.round(r1[:, 0]).astype(int)]
    assert np.abs((r1[:, 0] - r2[:, 0]) - d).max() < 1e-6
    # the undistorted pixels are the distortion-free cameras' images of the same rays: F holds exactly
    cu1, cu2 = (c.replace(dist=(0.0,) * 5) for c in (rig.camera1, rig.camera2))
    F = ep.fundamental_from_cameras(cu1, cu2)
    assert np.abs(ep.sampson_distance(F, u1, u2)).max() < 1e-6
    np.testing.assert_allclose(u1, undistort_pixels(x1, rig.camera1.K, rig.camera1.dist))


def test_calibrate_rig_recovers_the_true_relative_pose():
    from camlab.fixtures.stereo import calibrate_rig

    rig = load_stereo_rig()
    cal = calibrate_rig(rig)
    assert 0 < cal.rms < 0.2  # noise-free 8-bit boards: a few hundredths of a pixel
    assert np.array_equal(cal.camera1.R, np.eye(3)) and not np.any(cal.camera1.t)
    R, t = ep.relative_pose(rig.camera1, rig.camera2)
    assert abs(np.linalg.norm(cal.camera2.t) - np.linalg.norm(t)) < 1e-3  # baseline within 1 mm
    assert np.abs(cal.camera2.R - R).max() < 0.01
    assert np.allclose(cal.camera1.K, rig.camera1.K, atol=3.0)


def test_true_disparity_of_another_rectification():
    from camlab.fixtures.stereo import true_disparity

    rig = load_stereo_rig()
    alpha = STEREO_PARAMS["rectify_alpha"]
    same = rc.rectify_calibrated(rig.camera1, rig.camera2, alpha=alpha, maps=False)
    np.testing.assert_allclose(true_disparity(rig, same), rig.disparity, rtol=1e-6, equal_nan=True)
    half = rc.rectify_calibrated(
        rig.camera1.resized(0.5), rig.camera2.resized(0.5), alpha=alpha, maps=False
    )
    d = true_disparity(rig, half)
    assert d.shape == (240, 320)
    assert np.isclose(
        np.nanmedian(d), 0.5 * np.nanmedian(rig.disparity), rtol=0.02
    )  # f halves, B and Z stay


def test_bundled_rig_prepares_lesson_11_s_pair_once_and_read_only():
    import pytest

    from camlab.fixtures.stereo import HALF_SIZE, bundled_rig, true_matches

    prepared = bundled_rig()
    assert bundled_rig() is prepared  # cached
    rig, matches, half, und, unc = prepared
    again = true_matches(load_stereo_rig(), step=30, start=20)
    for a, b in zip(matches, again, strict=True):
        np.testing.assert_array_equal(a, b)
    assert [im.shape for im in half] == [HALF_SIZE[::-1]] * 2 and [im.shape for im in und] == [
        (480, 640)
    ] * 2
    # Hartley's rectification from the noisy matches leaves them on (almost) the same rows
    vd = rc.vertical_disparity(
        map_points(unc.H1, matches.ideal1), map_points(unc.H2, matches.ideal2)
    )
    assert vd.median < 0.5
    for a in (rig.left, rig.disparity, matches.raw1, half[0], und[1]):
        with pytest.raises(ValueError, match="read-only"):
            a[0] = 0  # a caller's edit must not corrupt the cache


def test_half_size_rectification_scores_only_smooth_surfaces():
    from camlab.fixtures.stereo import half_size_rectification

    rect, left, right, disparity, smooth = half_size_rectification()
    assert left.shape == right.shape == disparity.shape == smooth.shape == (240, 320)
    assert not left.flags.writeable and not smooth.flags.writeable
    assert np.all(np.isfinite(disparity[smooth]))
    # the depth edges (large disparity steps) are left out, most of the textured surface is kept
    step = np.abs(np.diff(np.nan_to_num(disparity, nan=-100.0), axis=1)) > 1
    assert not np.any(smooth[:, 1:] & step)
    assert 0.5 < smooth.mean() < 0.98
