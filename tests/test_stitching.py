"""Tests for camlab.stitching (and camlab.data.panorama): ground truth, OpenCV cross-checks, bad input."""

import dataclasses
import warnings

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as hs

from camlab import features as ft
from camlab import homography as hg
from camlab import scenes
from camlab import stitching as st
from camlab._validate import CamlabInputError, DegenerateError
from camlab.camera import scale_intrinsics
from camlab.data import panorama as sd
from camlab.fixtures import panorama as fp
from camlab.projective import map_points
from camlab.stitching import projections
from camlab.warp import canvas_bounds, canvas_box

CORNERS = np.array([[0, 0], [639, 0], [639, 479], [0, 479]], float)


def corner_error(H, H_true, corners=CORNERS) -> float:
    return float(np.linalg.norm(map_points(H, corners) - map_points(H_true, corners), axis=1).max())


@pytest.fixture(scope="module")
def full():
    """The full-size rotation set, its features and match graph (computed once)."""
    s = sd.load_panorama_set()
    feats = [ft.detect_features(im) for im in s.images]
    return s, feats, st.match_graph(feats)


@pytest.fixture(scope="module")
def result(full):
    s, _, _ = full
    return st.stitch(s.images, blend_method="multiband")


@pytest.fixture(scope="module")
def half():
    return sd.load_panorama_set(scale=0.5)


# ----------------------------------------------------------------------------- ground truth


def test_pairwise_homographies_match_ground_truth(full):
    """Every homography on the spanning tree is within 1 px of K R_j R_i^T K^-1 at the image corners."""
    s, _, g = full
    for k, p in enumerate(g.parent):
        if p < 0:
            continue
        i, j = min(k, p), max(k, p)
        reg = g.pairs[(i, j)]
        assert reg.accepted
        assert corner_error(reg.H, s.true_homography(i, j)) < 1.0, (i, j)
        assert reg.residual_rms < 0.6


def test_chained_homographies_and_reference(full):
    s, _, g = full
    assert g.reference in (1, 2) and g.unconnected == []  # the middle views see most others
    assert (
        g.pairs[(0, 3)].accepted is False and "too few" in g.pairs[(0, 3)].reason
    )  # 54 degrees apart
    for k in range(4):
        H_true = s.true_homography(k, g.reference)
        # chains amplify errors towards the canvas edge (view 3 is 36 degrees from the reference)
        assert corner_error(g.homographies[k], H_true) < (1.0 if abs(k - g.reference) <= 1 else 2.5)


def test_panorama_matches_a_direct_render(full, result):
    """Render the canvas view directly and compare pixels.

    The planar canvas is the image plane of a virtual camera K' = T diag(s, s, 1) looking along
    the estimated world's z: canvas_from_image_k = K' R_k^T K_k^-1. The estimated world is the
    true one turned by W (R_k^est = R_k^true W), so the canvas camera's true rotation is W^T.
    """
    s, _, _ = full
    r = result
    assert r.projection == "planar" and r.model == "rotation"
    ref = r.reference
    K_ref, R_ref = r.cameras[ref]
    K_canvas = r.homographies[ref] @ K_ref @ R_ref
    K_canvas /= K_canvas[2, 2]
    assert np.allclose(K_canvas[[0, 1, 2, 2], [1, 0, 0, 1]], 0, atol=1e-9) and np.isclose(
        K_canvas[0, 0], K_canvas[1, 1]
    )
    K_canvas[[0, 1, 2, 2], [1, 0, 0, 1]] = 0
    R_canvas = R_ref.T @ s.R[ref]
    h, w = r.panorama.shape[:2]
    direct = fp.render_view(R_canvas, K=K_canvas, size=(w, h), gain=s.gains[ref], noise=False)
    inside = cv2.erode(r.mask.astype(np.uint8), np.ones((5, 5), np.uint8)) > 0
    err = np.abs(r.panorama.astype(float) - direct.astype(float))
    overlap = (np.sum(r.masks, axis=0) >= 2) & inside
    assert err[inside].mean() < 4.0  # measured 2.9 grey levels (noise alone about 1.5)
    assert (
        err[overlap].mean() < 5.5
    )  # measured 5.2 with OpenCV 4.12 (fixed-point warps, other SIFT matches)
    assert np.median(err[inside]) <= 3
    # and the mask is the union of the footprints, matching where the direct render sees the canvas
    assert np.array_equal(r.mask, np.logical_or.reduce(r.masks))


def test_gain_compensation_recovers_the_exposures(result, full):
    s, _, _ = full
    expected = s.gains[result.reference] / s.gains
    assert np.allclose(result.gains, expected, rtol=0.05)
    assert result.gains[result.reference] == 1.0


# ----------------------------------------------------------------------------- OpenCV cross-checks


@pytest.mark.parametrize("pair", [(0, 1), (1, 2), (2, 3)])
def test_ransac_agrees_with_opencv_magsac(full, pair):
    """Same matches: inlier sets agree within 2%, inlier RMS no worse than 1.05x cv2 USAC_MAGSAC's."""
    _, feats, _ = full
    i, j = pair
    m = ft.match_features(feats[i], feats[j])
    reg = st.register_pair(feats[i], feats[j], matches=m, threshold=3.0)
    cv2.setRNGSeed(0)
    Hc, mask = cv2.findHomography(
        m.src, m.dst, cv2.USAC_MAGSAC, 3.0, confidence=0.999, maxIters=2000
    )
    ours, theirs = reg.inliers, mask.ravel().astype(bool)
    assert (ours ^ theirs).sum() <= 0.02 * theirs.sum()
    rms_cv = np.sqrt(np.mean(hg.transfer_error(Hc, m.src[theirs], m.dst[theirs]) ** 2))
    assert reg.residual_rms <= 1.05 * rms_cv


def test_warp_matches_opencv_warp_perspective(half):
    """warp_images puts each image where cv2.warpPerspective with T @ H would."""
    imgs = st.prepare_images(half.images[:2])
    H = half.true_homography(1, 0)
    wi = st.warp_images(imgs, [np.eye(3), H])
    T, (h, w) = canvas_bounds([np.eye(3), H], [im.shape for im in imgs])
    # the image's border is replicated (no black rim for the blend): compare inside its footprint
    ref = cv2.warpPerspective(
        imgs[1], T @ H, (w, h), flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE
    )
    assert wi.shape == (h, w)
    # warped into its box by the translated H: the same samples up to float rounding (1e-4 = 0.03 grey levels)
    inside = wi.masks[1]
    assert (
        np.abs(wi.images[1][inside] - ref[inside]).max() < 1e-4 and not wi.images[1][~inside].any()
    )
    assert np.allclose(wi.homographies[1], hg.normalise_homography(T @ H))
    h1, w1 = imgs[1].shape[:2]
    quad = map_points(
        T @ H, [[-0.5, -0.5], [w1 - 0.5, -0.5], [w1 - 0.5, h1 - 0.5], [-0.5, h1 - 0.5]]
    )
    assert wi.masks[1].sum() == pytest.approx(cv2.contourArea(quad.astype(np.float32)), rel=0.01)


# ----------------------------------------------------------------------------- pieces


def test_feather_weights_known_values_and_errors():
    w = st.feather_weights((4, 6))
    assert w.shape == (4, 6) and w[0, 0] == 0.5 and w[1, 2] == 1.5 and w.max() == 1.5
    assert np.allclose(w, w[::-1, ::-1])
    with pytest.raises(
        CamlabInputError,
        match=r"shape: expected \(height, width\) as whole numbers of pixels >= 1, got \(0, 3\)",
    ):
        st.feather_weights((0, 3))
    with pytest.raises(CamlabInputError, match="shape: expected"):
        st.feather_weights("big")


@settings(max_examples=40, deadline=None)
@given(
    hs.lists(
        hs.tuples(hs.floats(-300, 300), hs.floats(-300, 300), hs.floats(-0.3, 0.3)),
        min_size=1,
        max_size=4,
    )
)
def test_canvas_box_agrees_with_canvas_bounds(moves):
    Hs = [hg.similarity_homography(1.0, th, tx, ty) for tx, ty, th in moves]
    shapes = [(120, 160)] * len(Hs)
    box = canvas_box(Hs, shapes)
    T, (h, w) = canvas_bounds(Hs, shapes)
    assert np.allclose(T[:2, 2], -box[0])
    assert (w, h) == tuple((box[1] - box[0] + 1).astype(int))


def test_canvas_box_takes_a_homography_of_either_sign():
    # H and -H are one homography (a DLT's SVD returns either): w < 0 at every corner is no horizon
    H = np.array([[0.9, 0.25, 410.3], [-0.15, 1.1, 60.6], [0.0004, -0.0006, 1.0]])
    assert np.array_equal(canvas_box([-0.01 * H], [(240, 320)]), canvas_box([H], [(240, 320)]))
    assert canvas_box([-0.01 * H], [(240, 320)])[0, 0] == 410  # not mirrored through the origin


def test_canvas_box_bad_input():
    with pytest.raises(
        CamlabInputError,
        match=r"shapes: expected one shape per homography \(at least one\), got 1 for 2",
    ):
        canvas_box([np.eye(3), np.eye(3)], [(10, 10)])
    with pytest.raises(DegenerateError, match=r"homographies\[0\]: .* maps to or beyond infinity"):
        canvas_box([[[1, 0, 0], [0, 1, 0], [-0.2, 0, 1]]], [(10, 10)])


def _two_constant_images():
    a = np.full((60, 80, 3), 0.2, np.float32)
    b = np.full((60, 80, 3), 0.6, np.float32)
    return st.warp_images([a, b], [np.eye(3), hg.euclidean_homography(0, 40, 0)])


def test_blend_methods_on_two_constant_images():
    wi = _two_constant_images()
    assert wi.shape == (60, 120)
    over = st.blend(wi, "overwrite")
    assert over[30, 50, 0] == pytest.approx(0.6) and over[30, 30, 0] == pytest.approx(0.2)
    fe = st.blend(wi, "feather")
    row = fe[30, 40:80, 0]
    assert (
        np.all(np.diff(row) >= -1e-6) and row[0] < 0.25 and row[-1] > 0.55
    )  # a smooth ramp across the overlap
    assert fe[30, 60, 0] == pytest.approx(0.4, abs=0.01)  # mid-overlap: equal weights
    mb = st.blend(wi, "multiband", levels=4)
    assert np.all(np.diff(mb[30, :, 0]) >= -1e-3)  # monotone transition, no overshoot ring
    assert mb[30, 2, 0] == pytest.approx(0.2, abs=0.01) and mb[30, -3, 0] == pytest.approx(
        0.6, abs=0.01
    )
    assert np.abs(np.diff(mb[30, :, 0])).max() < 0.1  # no hard step at the seam
    assert np.abs(np.diff(over[30, :, 0])).max() == pytest.approx(0.4)
    with pytest.raises(
        CamlabInputError, match=r"method: expected one of \('overwrite', 'feather', 'multiband'\)"
    ):
        st.blend(wi, "average")
    with pytest.raises(
        CamlabInputError, match=r"gains: expected 2 gains \(one per image\), got shape \(3,\)"
    ):
        st.blend(wi, "feather", gains=[1, 1, 1])


def test_multiband_reconstructs_a_single_image(half):
    """One image with a full mask: the Laplacian pyramid collapses back to the image exactly."""
    img = st.prepare_images(half.images[:2])[0]
    out = st.laplacian_blend([img], [np.ones(img.shape[:2], bool)], levels=5)
    assert np.abs(out - img).max() < 1e-5
    grey = img[..., :1]  # one channel (OpenCV's pyramids drop a single channel's axis)
    out = st.laplacian_blend([grey], [np.ones(img.shape[:2], bool)], levels=5)
    assert out.shape == grey.shape and np.abs(out - grey).max() < 1e-5


def test_blend_in_boxes_agrees_with_laplacian_blend_on_the_canvas(half):
    """The pipeline's blend (each image in its own box, pyramids padded by the warp's replicated
    border) and the teaching laplacian_blend (full-canvas images, push-pull fill) give the same
    panorama: they differ only in how an image is extended past its own edge."""
    imgs = st.prepare_images(half.images[1:3])
    wi = st.warp_images(imgs, [np.eye(3), half.true_homography(2, 1)])
    seams = st.seam_masks(wi.weights)
    boxed = st.blend(wi, "multiband", levels=4)
    canvas = st.laplacian_blend(wi.images, seams, levels=4, footprints=wi.masks)
    union = wi.masks[0] | wi.masks[1]
    d = np.abs(boxed - canvas)[union]
    assert (
        d.mean() < 1e-4 and d.max() < 0.02
    )  # measured 2e-5 and 0.01 (2.5 grey levels, at the rim)
    assert not boxed[~union].any()


def test_multiband_gains_equal_gained_patches(half):
    """blend(gains=...) applies each gain to its bordered copy of the box inside the multi-band
    blend; the panorama is bit-for-bit the one blended from patches gained beforehand."""
    imgs = st.prepare_images(half.images[:3])
    wi = st.warp_images(imgs, [half.true_homography(k, 1) for k in range(3)])
    gains = np.array([1.3, 1.0, 0.8])
    gained = dataclasses.replace(
        wi,
        patches=[
            np.minimum(p * np.float32(g), np.float32(1))
            for p, g in zip(wi.patches, gains, strict=True)
        ],
    )
    seams = st.dp_seam_masks(wi)
    out = st.blend(wi, "multiband", gains=gains, seams=seams)
    assert np.array_equal(out, st.blend(gained, "multiband", seams=seams))
    assert np.array_equal(
        out, st.blend(wi, "multiband", gains=gains, seams=seams)
    )  # scratch reuse leaves no trace


def test_overlap_difference():
    wi = _two_constant_images()
    assert st.overlap_difference(wi) == pytest.approx(0.4)
    apart = st.warp_images(
        [np.zeros((10, 10, 3), np.float32)] * 2, [np.eye(3), hg.euclidean_homography(0, 50, 0)]
    )
    assert st.overlap_difference(apart) == 0.0


def test_gain_compensation_on_scaled_copies():
    rng = np.random.default_rng(0)
    base = rng.uniform(0.2, 0.8, (50, 50, 3)).astype(np.float32)
    wi = st.warp_images([base, base * 0.8, base * 1.2], [np.eye(3)] * 3)
    g = st.gain_compensation(wi, sigma_g=10.0, reference=0)
    assert np.allclose(g, [1, 1.25, 1 / 1.2], rtol=1e-3)


def test_cylindrical_canvas_geometry():
    """A vertical line 140.5 px right of the principal point lands at s * atan(140.5 / f) on the cylinder."""
    K = np.array([[400.0, 0, 159.5], [0, 400.0, 119.5], [0, 0, 1]])
    img = np.zeros((240, 320), np.float32)
    img[:, 300] = 1.0
    canvas = projections.make_canvas([K], [np.eye(3)], [img.shape], "cylindrical", 400.0)
    box = canvas.boxes[0]
    patch, mask, _ = projections.warp_by_rotation(img, K, np.eye(3), canvas, box)
    row = int(round(-canvas.origin[1])) - box[0]  # canvas v = 0: the principal point's row
    u = box[2] + np.argmax(patch[row]) + canvas.origin[0]
    assert abs(u - 400 * np.arctan(140.5 / 400)) < 1.0
    assert mask[row].any() and not mask.all()  # the cylinder's box reaches past the image's corners
    ones, _, _ = projections.warp_by_rotation(
        np.ones((240, 320), np.float32), K, np.eye(3), canvas, box
    )
    assert ones[row, patch.shape[1] // 2] == 1.0


def test_warp_by_rotation_extra_channel_agrees_with_separate_warps(half):
    """A colour image and its extra channel go through one 4-channel remap (OpenCV's is faster
    than its 3-channel one); each comes out bit-for-bit as warping it alone would give."""
    img = st.prepare_images(half.images[:2])[0]
    K = np.array([[400.0, 0, 159.5], [0, 400.0, 119.5], [0, 0, 1]])
    R = fp.cam_from_world(np.radians(10.0), np.radians(-3.0), np.radians(2.0))
    extra = st.feather_weights(img.shape).astype(np.float32)
    for projection in projections.PROJECTIONS:
        canvas = projections.make_canvas([K], [R], [img.shape], projection, 400.0)
        box = canvas.boxes[0]
        patch, mask, more = projections.warp_by_rotation(img, K, R, canvas, box, extra)
        alone, mask_alone, _ = projections.warp_by_rotation(img, K, R, canvas, box)
        weight, _, _ = projections.warp_by_rotation(extra, K, R, canvas, box)
        assert np.array_equal(patch, alone) and np.array_equal(mask, mask_alone)
        assert np.array_equal(more, np.where(mask, weight, 0)) and mask.any() and not mask.all()


# ----------------------------------------------------------------------------- the pipeline and bad input


def test_stitch_result_structure(result, full):
    s, _, _ = full
    r = result
    assert r.panorama.dtype == np.uint8 and r.panorama.shape[2] == 3
    assert len(r.homographies) == len(r.masks) == 4 and r.unconnected == []
    assert len(r.pairs) == 6 and all(isinstance(p, st.PairReport) for p in r.pairs)
    accepted = {(p.i, p.j) for p in r.pairs if p.accepted}
    assert {(0, 1), (1, 2), (2, 3)} <= accepted
    for k in range(4):  # each image's corners land inside the canvas
        c = map_points(r.homographies[k], CORNERS)
        assert np.all(c >= -0.5) and np.all(c <= np.array(r.panorama.shape[1::-1]) - 0.5)


def test_seams_multiband_versus_overwrite(half):
    """Without gain compensation the overwrite seam shows the exposure step; multi-band smooths it."""
    imgs = st.prepare_images(half.images)
    feats = [ft.detect_features(im, max_features=1500) for im in imgs]
    g = st.match_graph(feats)
    wi = st.warp_images([imgs[1], imgs[2]], [g.homographies[1], g.homographies[2]])
    seam = st.seam_masks(wi.weights)[0]
    both = wi.masks[0] & wi.masks[1]
    # overwrite's seam is the border of the image painted last (image 2 over image 1)
    j_over = st.seam_step(st.blend(wi, "overwrite"), wi.masks[1], wi.masks[0])
    j_feather = st.seam_step(st.blend(wi, "feather"), seam, both)
    j_multi = st.seam_step(st.blend(wi, "multiband"), seam, both)
    # views 1 and 2 differ in exposure by 1.12 / 0.86: a step of about 0.1 where they meet
    assert j_over > 0.05 and j_multi < j_over / 4 and j_feather < j_over / 4
    gains = st.gain_compensation(wi, reference=0)
    assert (
        st.seam_step(st.blend(wi, "overwrite", gains=gains), wi.masks[1], wi.masks[0]) < j_over / 4
    )


def test_seam_step_known_answer():
    img = np.zeros((10, 20))
    img[:, 10:] = 0.3
    seam = np.zeros((10, 20), bool)
    seam[:, 10:] = True
    assert st.seam_step(img, seam, np.ones((10, 20), bool)) == pytest.approx(0.3)
    assert st.seam_step(img, seam, np.zeros((10, 20), bool)) == 0.0


def _cheapest_paths(cost: np.ndarray) -> tuple[float, list]:
    """Every top-to-bottom path (steps -1, 0, +1), enumerated: the least cost and the paths reaching it."""
    h, w = cost.shape
    paths = [[c] for c in range(w)]
    for _ in range(1, h):
        paths = [p + [p[-1] + d] for p in paths for d in (-1, 0, 1) if 0 <= p[-1] + d < w]
    costs = [float(cost[np.arange(h), p].sum()) for p in paths]
    best = min(costs)
    return best, [p for p, c in zip(paths, costs, strict=True) if c == best]


@pytest.mark.parametrize("seed", range(6))
def test_seam_path_is_a_cheapest_path(seed):
    """dp_seam_masks' dynamic programme finds a cheapest path, as exhaustive search does (ties included:
    small integer costs, and 1e6 for pixels outside the overlap)."""
    from camlab.stitching.blending import _seam_path

    rng = np.random.default_rng(seed)
    cost = rng.integers(0, 3, (6, 5)).astype(np.float32)
    cost[rng.random(cost.shape) < 0.2] = 1e6
    path = _seam_path(cost)
    best, cheapest = _cheapest_paths(cost)
    assert np.all(np.abs(np.diff(path)) <= 1) and np.all((path >= 0) & (path < cost.shape[1]))
    assert float(cost[np.arange(6), path].sum()) == best and path.tolist() in cheapest


def test_cylindrical_stitch_with_a_known_or_estimated_focal(half):
    r = st.stitch(half.images, projection="cylindrical", K=half.K, max_features=1500)
    assert r.unconnected == [] and r.projection == "cylindrical" and r.homographies == [None] * 4
    assert all(np.allclose(c[0], half.K) for c in r.cameras)  # a given K is kept
    R12 = r.cameras[2][1] @ r.cameras[1][1].T
    true = half.R[2] @ half.R[1].T
    assert np.degrees(np.arccos(np.clip((np.trace(R12 @ true.T) - 1) / 2, -1, 1))) < 0.1
    r2 = st.stitch(half.images, projection="cylindrical", max_features=1500)  # focal estimated
    assert all(abs(c[0][0, 0] / half.K[0, 0] - 1) < 0.01 for c in r2.cameras)
    # on the cylinder a yaw is a horizontal shift of f * yaw: the panorama is about f * (54 deg + fov) wide
    fov = 2 * np.arctan(160 / 400)
    assert abs(r2.panorama.shape[1] - 400 * (np.radians(54) + fov)) < 25


def test_planar_pair_registration():
    pp = sd.load_planar_pair(scale=0.5)
    f = [ft.detect_features(im, max_features=1500) for im in pp.images]
    reg = st.register_pair(f[0], f[1])
    c = np.array([[0, 0], [319, 0], [319, 239], [0, 239]], float)
    assert reg.accepted and corner_error(reg.H, pp.H, c) < 1.0


def test_single_image_and_bad_options(half):
    with pytest.raises(
        CamlabInputError, match="images: expected at least 2 images to stitch, got 1"
    ):
        st.stitch([half.images[0]])
    with pytest.raises(CamlabInputError, match="images: expected a list of images, got one array"):
        st.stitch(half.images[0])
    with pytest.raises(
        CamlabInputError,
        match=r"images\[1\]: expected a \(H, W\) grey or \(H, W, 3\|4\) colour image",
    ):
        st.stitch([half.images[0], np.zeros((240, 320, 2))])
    with pytest.raises(
        CamlabInputError,
        match=r"images\[1\]: expected uint8, uint16 or float pixels, got dtype int64",
    ):
        st.stitch([half.images[0], np.zeros((240, 320), np.int64)])
    with pytest.raises(CamlabInputError, match="blend_method: expected one of"):
        st.stitch(half.images, blend_method="max")
    with pytest.raises(CamlabInputError, match="projection: expected one of"):
        st.stitch(half.images, projection="mercator")


def test_no_overlap_is_reported_not_dropped(half):
    """An image of something else, an all-black image: listed in `unconnected`, with a warning and reasons."""
    other = np.ascontiguousarray(
        np.rot90(scenes.wall_texture((2100, 800))[400:640, 1500:1820]) * 255
    ).astype(np.uint8)
    other = np.ascontiguousarray(other[:240, :240])
    black = np.zeros((240, 320, 3), np.uint8)
    with pytest.warns(
        UserWarning,
        match=r"left out of the panorama: 'image 2' overlaps none.*'image 3' overlaps none",
    ):
        r = st.stitch(
            [half.images[1], half.images[2], other, black],
            max_features=1500,
            blend_method="feather",
        )
    assert r.unconnected == [2, 3]
    assert r.homographies[2] is None and r.masks[3] is None and np.isnan(r.gains[3])
    reasons = {(p.i, p.j): p.reason for p in r.pairs}
    assert "too few matches: 0" in reasons[(0, 3)]
    assert reasons[(0, 1)] == ""
    assert r.panorama.shape[0] < 400  # only the two connected views are on the canvas


def test_nothing_to_stitch_raises(half):
    black = np.zeros((240, 320, 3), np.uint8)
    with pytest.raises(
        DegenerateError,
        match=r"stitch: no two images could be registered.*'image 0'-'image 1': 0 matches",
    ):
        st.stitch([half.images[0], black], max_features=500)
    with pytest.raises(DegenerateError, match="too few"):
        st.stitch(
            [half.images[0], half.images[3]], max_features=1500
        )  # 54 degrees apart: no overlap


def test_different_sizes_and_channel_counts(half):
    """A grey, smaller view stitches with a colour one; the panorama is colour."""
    grey = cv2.cvtColor(half.images[2], cv2.COLOR_RGB2GRAY)[20:220, 10:300]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = st.stitch([half.images[1], grey], max_features=1500)
    assert r.panorama.ndim == 3 and r.unconnected == []
    # the crop shifts the true homography by the crop offset
    H_true = half.true_homography(2, 1) @ hg.euclidean_homography(0, 10, 20)
    H_est = np.linalg.inv(r.homographies[0]) @ r.homographies[1]
    c = np.array([[0, 0], [289, 0], [289, 199], [0, 199]], float)
    assert corner_error(H_est, H_true, c) < 1.0
    f = r.panorama.astype(np.float32) / 255
    r2 = st.stitch([f[..., 0], half.images[1].astype(np.float32) / 255], max_features=1500)
    assert r2.panorama.dtype == np.float32


def test_register_pair_too_few_matches(half):
    f = [ft.detect_features(im, max_features=1500) for im in half.images[:2]]
    few = ft.Matches(*(a[:6] for a in ft.match_features(f[0], f[1])))
    r = st.register_pair(f[0], f[1], matches=few)
    assert not r.accepted and r.H is None and r.reason == "too few matches: 6 (need at least 15)"


def test_loaders_and_truth():
    s = sd.load_panorama_set()
    assert (
        len(s.images) == 4 and s.images[0].shape == (480, 640, 3) and s.images[0].dtype == np.uint8
    )
    H = s.true_homography(0, 1)
    assert np.allclose(H, hg.rotation_homography(s.K, s.R[1] @ s.R[0].T))
    half = sd.load_panorama_set(scale=0.5)
    S = scale_intrinsics(np.eye(3), 0.5)
    assert np.allclose(
        half.true_homography(0, 1), hg.normalise_homography(S @ H @ np.linalg.inv(S))
    )
    with pytest.raises(CamlabInputError, match="directory: no truth.json"):
        sd.load_panorama_set("/nonexistent")


def test_warp_images_onto_a_given_frame(half):
    """shape=: image 1 warped into image 0's own frame is the full canvas cropped to image 0's box."""
    imgs = st.prepare_images(half.images[:2])
    H = half.true_homography(1, 0)
    full = st.warp_images(imgs, [np.eye(3), H])
    own = st.warp_images(imgs, [np.eye(3), H], shape=imgs[0].shape[:2])
    h, w = imgs[0].shape[:2]
    c0, r0 = full.T[:2, 2].astype(int)  # image 0's corner on the full canvas
    crop = [a[r0 : r0 + h, c0 : c0 + w] for a in (full.images[1], full.masks[1])]
    assert own.shape == (h, w) and np.array_equal(own.T, np.eye(3))
    assert np.array_equal(own.images[0], imgs[0]) and own.masks[0].all()
    # the same footprint and samples, to float rounding (the two warps compose different translations)
    assert (own.masks[1] != crop[1]).sum() <= 0.001 * h * w and own.masks[1].sum() > 0.3 * h * w
    both = own.masks[1] & crop[1]
    assert np.abs(own.images[1][both] - crop[0][both]).max() < 1e-3
    with pytest.raises(CamlabInputError, match="shape: expected"):
        st.warp_images(imgs, [np.eye(3), H], shape=(240, 0))


def test_warp_images_bad_input():
    with pytest.raises(
        CamlabInputError,
        match=r"images\[0\]: expected an \(h, w, 3\) float32 image from prepare_images",
    ):
        st.warp_images([np.zeros((10, 10))], [np.eye(3)])
    with pytest.raises(
        CamlabInputError, match="homographies: expected one per image, got 2 for 1 images"
    ):
        st.warp_images([np.zeros((10, 10, 3))], [np.eye(3), np.eye(3)])


def test_gains_from_overlaps_known_answers_and_bad_input():
    # two images that agree on their overlap keep gain 1; a 30 % brighter one is pulled down towards the other
    N = np.array([[0.0, 5000], [5000, 0]])
    same = st.gains_from_overlaps(N, np.array([[0.0, 0.4], [0.4, 0]]))
    np.testing.assert_allclose(same, [1, 1], atol=1e-12)
    g = st.gains_from_overlaps(N, np.array([[0.0, 0.4], [0.52, 0]]))
    assert g[0] * 0.4 == pytest.approx(g[1] * 0.52, rel=0.01) and g[1] < 1 < g[0]
    # an image with no overlap keeps gain 1
    N3 = np.zeros((3, 3))
    N3[0, 1] = N3[1, 0] = 100
    I3 = np.array([[0, 0.5, 0], [0.6, 0, 0], [0, 0, 0]])
    assert st.gains_from_overlaps(N3, I3)[2] == 1.0
    with pytest.raises(CamlabInputError, match="I_mean: expected two"):
        st.gains_from_overlaps(N, np.zeros((3, 3)))
