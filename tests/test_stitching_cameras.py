"""The rotation model of a panorama: focal, bundle adjustment, wave correction, canvases, bad input.

Ground truth comes from camlab.fixtures.panorama.turning_set: views of a real photograph used as a
360-degree world, rendered with an exact focal (500 px) and exact rotations.
"""

import warnings

import numpy as np
import pytest

from camlab import stitching as st
from camlab._validate import DegenerateError
from camlab.camera import rotation_from_axis_angle
from camlab.data import panorama as pd
from camlab.fixtures import panorama as fp
from camlab.homography import rotation_homography
from camlab.stitching import cameras as cm
from camlab.stitching import projections as pj


def angle_deg(R):
    return float(np.degrees(np.arccos(np.clip((np.trace(R) - 1) / 2, -1, 1))))


def relative_errors(cams, R_true, idx):
    """Largest error (degrees) of the estimated relative rotations R_j R_i^T against the truth."""
    out = []
    for a in range(len(idx)):
        for b in range(a + 1, len(idx)):
            i, j = idx[a], idx[b]
            Re = cams[j][1] @ cams[i][1].T
            out.append(angle_deg(Re @ (R_true[b] @ R_true[a].T).T))
    return max(out)


@pytest.fixture(scope="module")
def turn3():
    s = fp.turning_set("turn3", unrelated=True)
    with pytest.warns(UserWarning, match=r"'church \(unrelated\)' overlaps none"):
        r = st.stitch(s.images, names=s.names)
    return s, r


def test_focal_from_a_rotation_homography_and_its_degenerate_cases():
    K = cm.intrinsics(650.0, (480, 640))
    for w in ([0.0, 0.4, 0.0], [0.1, 0.3, 0.05], [0.3, 0.0, 0.0]):
        H = rotation_homography(K, rotation_from_axis_angle(w))
        fs, fd = cm.focal_from_homography(H, (480, 640), (480, 640))
        assert abs(fs - 650) < 1e-6 and abs(fd - 650) < 1e-6
    # two different cameras: the rows give the source's focal, the columns the destination's
    K2 = cm.intrinsics(900.0, (480, 640))
    H = rotation_homography(K, rotation_from_axis_angle([0.05, 0.35, 0.0]), K2)
    assert np.allclose(cm.focal_from_homography(H, (480, 640), (480, 640)), (650, 900))
    # long lenses: the cut-off is on H in units of the image diagonal, so it does not depend on f
    # (on the Frobenius-normalised H in pixels, h6 h7 at f = 1000 px is under 1e-12)
    for f in (1000.0, 2000.0, 4000.0):
        for w in ([0.0, np.radians(5), 0.0], [0.2, 0.4, 0.05], [np.radians(45), 0.0, 0.0]):
            H = rotation_homography(cm.intrinsics(f, (600, 800)), rotation_from_axis_angle(w))
            assert np.allclose(cm.focal_from_homography(H, (600, 800), (600, 800)), f, rtol=1e-6)
    # an affine map (no perspective terms at all): f -> infinity, undetermined
    assert np.isnan(
        cm.focal_from_homography(
            [[1.01, 0.06, -55], [-0.07, 1.01, 66], [0, 0, 1]], (480, 640), (480, 640)
        )
    ).all()
    # a pure translation (shift) constrains nothing: NaN, never a made-up number
    assert np.isnan(
        cm.focal_from_homography([[1, 0, 30], [0, 1, 0], [0, 0, 1]], (480, 640), (480, 640))
    ).all()


def test_turning_set_focal_within_1_percent_and_rotations_within_0_1_degree(turn3):
    s, r = turn3
    assert r.model == "rotation" and r.unconnected == [1] and r.cameras[1] is None
    idx = [0, 2, 3]
    for k in idx:
        assert abs(r.cameras[k][0][0, 0] / s.K[0, 0] - 1) < 0.01
    assert relative_errors(r.cameras, s.R, idx) < 0.1
    assert r.residual_rms < 1.0


def test_auto_projection_follows_the_field_of_view(turn3):
    _, r = turn3
    assert r.projection == "spherical"  # three 84-degree views over 80 degrees of turn: 164 degrees
    room = pd.load_panorama_set(scale=0.5)  # four 44-degree views over 54 degrees: 98 degrees
    r2 = st.stitch(room.images, max_features=1500)
    assert r2.projection == "planar" and r2.model == "rotation"
    wide = fp.turning_set("wide", size=(450, 330), f=250)
    with pytest.raises(
        DegenerateError, match="turn too far for a plane.*'cylindrical' or 'spherical'"
    ):
        st.stitch(wide.images, projection="planar")
    r3 = st.stitch(wide.images, projection="cylindrical")
    assert r3.projection == "cylindrical" and r3.panorama.shape[1] > r3.panorama.shape[0] * 2.5


def test_projection_round_trips():
    rng = np.random.default_rng(1)
    d = rng.normal(size=(50, 3))
    d[:, 2] = np.abs(d[:, 2]) + 0.2
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    for proj in pj.PROJECTIONS:
        u, v = pj.canvas_from_ray(d, proj, 300.0)
        back = np.stack(pj.ray_from_canvas(u, v, proj, 300.0), axis=-1)
        back /= np.linalg.norm(back, axis=1, keepdims=True)
        assert np.allclose(back, d, atol=1e-9), proj


def test_pixel_rays_and_canvas_points_of_a_camera_looking_backwards():
    from camlab.camera import intrinsic_matrix, rotation_from_axis_angle

    K = intrinsic_matrix(300, 290, 170, 118, 2.0)
    R = rotation_from_axis_angle([0.0, np.radians(179.0), 0.0])  # turned almost all the way round
    pixels = np.array([[0.0, 0.0], [339.0, 0.0], [170.0, 118.0], [339.0, 235.0]])
    rays = pj.pixel_rays(pixels, K, R)
    expected = (np.c_[pixels, np.ones(4)] @ np.linalg.inv(K).T) @ R  # R^T K^-1 x, row by row
    np.testing.assert_allclose(rays, expected, rtol=1e-12)
    s = 300.0
    u, v = pj.canvas_points(pixels, K, R, "cylindrical", s)
    # the image straddles the canvas's seam at +-pi s, but its points stay together around its optical axis
    axis = -np.radians(179.0) * s
    assert np.all(np.abs(u - axis) < np.pi / 2 * s) and np.ptp(u) < np.pi / 2 * s
    assert u.min() < -np.pi * s < u.max()
    wrapped, _ = pj.canvas_from_ray(
        rays, "cylindrical", s
    )  # without unrolling the points split across the seam
    assert np.ptp(wrapped) > np.pi * s
    np.testing.assert_allclose(np.angle(np.exp(1j * u / s)), wrapped / s, atol=1e-12)


def test_loop_closes_after_bundle_adjustment():
    """A full turn in 8 photos: the spanning tree leaves the loop open, bundle adjustment closes it."""
    s = fp.turning_set("loop", size=(450, 330), f=250)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = st.stitch(s.images, blend_method="feather")
    shapes = [im.shape for im in s.images]
    est = cm.estimate_cameras(r.graph, shapes)
    tree = {(min(k, p), max(k, p)) for k, p in enumerate(r.graph.parent) if p >= 0}
    closing = [key for key, p in r.graph.pairs.items() if p.accepted and key not in tree]
    assert closing, "a full turn has a pair that closes the loop"
    m = cm.inlier_matches(r.graph)
    K0 = [cm.intrinsics(est.focal_init, sh) for sh in shapes]

    def gap(Ks, Rs):
        return max(
            float(
                np.median(
                    np.linalg.norm(
                        cm.pair_transfer_errors(Ks[i], Rs[i], Ks[j], Rs[j], *m[(i, j)]), axis=1
                    )
                )
            )
            for i, j in closing
        )

    before, after = gap(K0, est.Rs_init), gap(est.Ks, est.Rs)
    assert before > 2 * after and after < 1.0, (before, after)
    assert all(abs(K[0, 0] / 250 - 1) < 0.01 for K in est.Ks)
    assert (
        relative_errors([(K, R) for K, R in zip(est.Ks, est.Rs, strict=True)], s.R, list(range(8)))
        < 0.1
    )


def test_wave_correction_levels_a_tilted_sweep():
    tilt = rotation_from_axis_angle([0.2, 0.0, 0.1])  # the whole sweep about a tilted axis
    Rs = [rotation_from_axis_angle([0, np.radians(a), 0]) @ tilt for a in (-40, -10, 20, 50)]
    out = cm.wave_correct(Rs)
    for R1 in out:
        assert abs(R1[0] @ [0, 1, 0]) < 1e-9  # every camera's x axis is horizontal
        assert np.allclose(R1 @ R1.T, np.eye(3))
    # relative rotations are unchanged
    assert np.allclose(out[1] @ out[0].T, Rs[1] @ Rs[0].T)


def test_transfer_error_on_independent_matches_against_cv2_stitcher():
    """Held-out ORB matches (neither method used them): camlab's cameras within 1 px median and within 10% of OpenCV's."""
    cv2 = pytest.importorskip("cv2")
    s = fp.turning_set("exposures")
    r = st.stitch(s.images)
    stitcher = cv2.Stitcher_create()
    status, _ = stitcher.stitch([np.ascontiguousarray(im[..., ::-1]) for im in s.images])
    assert status == cv2.Stitcher_OK
    orb = cv2.ORB_create(3000)
    gray = [cv2.cvtColor(im, cv2.COLOR_RGB2GRAY) for im in s.images]
    (k0, d0), (k1, d1) = (orb.detectAndCompute(g, None) for g in gray)
    good = [
        m
        for m, n in cv2.BFMatcher(cv2.NORM_HAMMING).knnMatch(d0, d1, k=2)
        if m.distance < 0.75 * n.distance
    ]
    a = np.array([k0[m.queryIdx].pt for m in good])
    b = np.array([k1[m.trainIdx].pt for m in good])
    _, inl = cv2.findHomography(a, b, cv2.RANSAC, 3.0)
    a, b = a[inl.ravel() > 0], b[inl.ravel() > 0]
    assert len(a) > 100
    (K0, R0), (K1, R1) = r.cameras
    e_cam = np.median(np.linalg.norm(cm.pair_transfer_errors(K0, R0, K1, R1, a, b), axis=1))
    cams = (
        stitcher.cameras()
    )  # OpenCV: R is world_from_cam, at the registration scale (1.0 here: 0.59 MP)
    Kc = [c.K().astype(float) for c in cams]
    e_cv = np.median(
        np.linalg.norm(
            cm.pair_transfer_errors(
                Kc[0], np.asarray(cams[0].R, float).T, Kc[1], np.asarray(cams[1].R, float).T, a, b
            ),
            axis=1,
        )
    )
    assert e_cam <= 1.0 and e_cam <= 1.1 * e_cv, (e_cam, e_cv)


def test_planar_scene_keeps_homographies_refined_together():
    photos = pd.load_aerial_mosaic(4)
    r = st.stitch(photos, names=[f"aerial_{k + 1}" for k in range(4)], blend_method="feather")
    assert r.model == "homography" and r.projection == "planar" and r.cameras == [None] * 4
    assert r.residual_rms < 0.5
    adj = cm.adjust_homographies(
        r.graph.homographies, cm.inlier_matches(r.graph), reference=r.graph.reference
    )
    assert adj.rms_after <= adj.rms_before + 1e-9


def test_same_photo_twice_different_sizes_and_crop(turn3):
    import cv2

    s, _ = turn3
    a, b = s.images[0], s.images[2]
    small = cv2.resize(b, (720, 528), interpolation=cv2.INTER_AREA)  # a different size: its own K
    with pytest.warns(
        UserWarning, match="'second' is the same photo as 'first'; the repeat is left out"
    ):
        r = st.stitch([a, a.copy(), small], names=["first", "second", "small"], crop=True)
    assert r.unconnected == [1] and r.cameras[1] is None
    assert (
        abs(r.cameras[2][0][0, 0] / (500 * 0.8) - 1) < 0.01
        and abs(r.cameras[0][0][0, 0] / 500 - 1) < 0.01
    )
    assert r.mask.all()  # cropped to the largest rectangle without empty canvas
    assert st.largest_rectangle(np.array([[0, 1, 1, 0], [1, 1, 1, 1], [0, 1, 1, 1]], bool)) == (
        0,
        3,
        1,
        3,
    )


def test_single_usable_image_is_named():
    s = fp.turning_set("turn3", unrelated=True)
    with pytest.raises(
        DegenerateError,
        match=r"no two images could be registered.*'turn3_0'-'church \(unrelated\)'",
    ):
        st.stitch([s.images[0], s.images[1]], names=s.names[:2])


def test_translating_camera_warns_with_the_residual():
    """The camera moves 30 cm in the room: the wall's homography leaves the nearer objects' matches on a second plane."""
    room = pd.load_panorama_set()
    R = fp.cam_from_world(np.radians(8))
    views = [
        fp.render_view(np.eye(3), K=room.K, rng=np.random.default_rng(0)),
        fp.render_view(R, t=-R @ np.array([0.3, 0.0, 0.0]), K=room.K, rng=np.random.default_rng(1)),
    ]
    with pytest.warns(
        UserWarning,
        match=r"'left'-'right': \d+ matches follow a second plane, \d+\.\d px .*parallax",
    ):
        st.stitch(views, names=["left", "right"], blend_method="feather")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the same room from one centre: no warning
        st.stitch(
            [views[0], fp.render_view(R, K=room.K, rng=np.random.default_rng(1))],
            blend_method="feather",
        )


def test_a_turn_past_360_degrees_is_reported():
    s = fp.turning_set("over360", size=(450, 330), f=250)
    with pytest.warns(UserWarning, match=r"turn through 405 degrees.*'over360_8', 'over360_9'"):
        r = st.stitch(s.images, names=s.names, blend_method="feather")
    assert r.projection == "spherical" and r.panorama.shape[1] == int(
        round(2 * np.pi * np.median([c[0][0, 0] for c in r.cameras]))
    )
