"""Tests for camlab.disparity: the numpy block matcher, SGBM, depth from disparity, on the rendered rig."""

import numpy as np
import pytest
import scipy.ndimage as ndi

from camlab import disparity as dp
from camlab import rectification as rc
from camlab._validate import CamlabInputError
from camlab.data.stereo import load_stereo_rig

BAND = slice(
    150, 330
)  # rows crossing the wall, the photo, both panels and both boxes (keeps the test fast)


@pytest.fixture(scope="module")
def pair():
    rig = load_stereo_rig()
    rect = rc.rectify_calibrated(rig.camera1, rig.camera2, alpha=rig.params["rectify_alpha"])
    L, R = rc.rectify_images(rect, rig.left, rig.right)
    gt = rig.disparity
    g = np.nan_to_num(gt, nan=-100.0)
    # "textured planes": valid truth away from depth edges (true disparity varies < 1 px over 15 x 15)
    planar = np.isfinite(gt) & (ndi.maximum_filter(g, 15) - ndi.minimum_filter(g, 15) < 1.0)
    return rect, L, R, gt, planar


def _depth_errors(d, pair):
    rect, L, R, gt, planar = pair
    ok = planar[BAND] & np.isfinite(d)
    z = dp.disparity_to_depth(d[ok], rect.K[0, 0], rect.baseline)
    zt = dp.disparity_to_depth(gt[BAND][ok], rect.K[0, 0], rect.baseline)
    return np.abs(z - zt) / zt, ok.sum() / planar[BAND].sum()


def test_block_matcher_depth_within_5_percent_on_textured_planes(pair):
    rect, L, R, gt, planar = pair
    d = dp.block_matching_disparity(
        L[BAND], R[BAND], max_disparity=88, block_size=9, min_disparity=16
    )
    rel, coverage = _depth_errors(d, pair)
    assert coverage > 0.7
    assert np.median(rel) < 0.01
    assert np.mean(rel < 0.05) > 0.98


def test_sgbm_depth_within_5_percent(pair):
    rect, L, R, gt, planar = pair
    d = dp.sgbm_disparity(L[BAND], R[BAND], max_disparity=88, block_size=5, min_disparity=16)
    rel, coverage = _depth_errors(d, pair)
    assert coverage > 0.7 and np.median(rel) < 0.01 and np.mean(rel < 0.05) > 0.98


def test_block_matcher_known_shift_subpixel_and_occlusion():
    rng = np.random.default_rng(0)
    import cv2

    tex = cv2.GaussianBlur(rng.uniform(0, 255, (60, 200)).astype(np.float32), (0, 0), 1.2)
    shift = 7.4
    M = np.float32([[1, 0, -shift], [0, 1, 0]])  # right(u) = left(u + shift): disparity 7.4
    right = cv2.warpAffine(tex, M, (200, 60), flags=cv2.INTER_CUBIC, borderMode=cv2.BORDER_REFLECT)
    d = dp.block_matching_disparity(tex, right, max_disparity=16, block_size=7)
    inner = d[10:-10, 30:-10]
    assert np.nanmedian(np.abs(inner - shift)) < 0.1
    assert np.all(np.isnan(d[:, :3]))  # every window would leave the right image
    assert np.mean(np.isnan(d[:, :7])) > 0.7  # occluded (no right-image pixel): mostly rejected


def test_block_matcher_rejects_textureless_regions():
    flat = np.full((40, 80), 100.0)
    d = dp.block_matching_disparity(flat, flat, max_disparity=10, block_size=5)
    assert np.all(np.isnan(d))  # every disparity costs the same: ambiguous


def test_box_sum_matches_scipy():
    a = np.random.default_rng(1).random((23, 31))
    assert np.allclose(dp.box_sum(a, 5), ndi.uniform_filter(a, 5, mode="constant") * 25)


def test_depth_and_points():
    assert np.allclose(
        dp.disparity_to_depth([[80.0, -1.0]], 800, 0.1), [[1.0, np.nan]], equal_nan=True
    )
    K = np.array([[800, 0, 320], [0, 800, 240], [0, 0, 1.0]])
    disp = np.full((480, 640), np.nan)
    disp[240, 400] = 40.0
    p = dp.disparity_to_points(disp, K, 0.1)
    assert np.allclose(p, [[80 * 2 / 800, 0, 2.0]])


def test_bad_input():
    img = np.zeros((20, 30))
    with pytest.raises(CamlabInputError, match="block_size: expected an odd window"):
        dp.block_matching_disparity(img, img, 8, block_size=4)
    with pytest.raises(CamlabInputError, match="max_disparity"):
        dp.block_matching_disparity(img, img, 40)
    with pytest.raises(CamlabInputError, match="same size"):
        dp.block_matching_disparity(img, img[:, :-1], 8)
    with pytest.raises(CamlabInputError, match="baseline: expected a positive"):
        dp.disparity_to_depth([1.0], 800, 0)


def test_matching_cost_is_the_block_matchers_cost_curve():
    from camlab.fixtures.stereo import half_size_rectification

    hs = half_size_rectification()
    d = dp.block_matching_disparity(
        hs.left, hs.right, 44, 5, min_disparity=8, uniqueness=0, lr_check=0
    )
    for u, v in [(200, 120), (150, 60), (250, 200)]:
        ds, c = dp.matching_cost(hs.left, hs.right, u, v, 44, 5, min_disparity=8)
        k = int(np.argmin(c))
        cm, c0, cp = c[k - 1 : k + 2]
        assert d[v, u] == pytest.approx(ds[k] + (cm - cp) / (2 * (cm - 2 * c0 + cp)), abs=1e-4)
    assert np.isinf(dp.matching_cost(hs.left, hs.right, 3, 50, 44, 5)[1][-1])
    with pytest.raises(CamlabInputError, match="u, v"):
        dp.matching_cost(hs.left, hs.right, -1, 50, 44, 5)


def test_matching_cost_crop_is_the_whole_image_prefilter():
    """matching_cost prefilters only around its pixel: the curve of the whole images' prefilter, at the borders too."""
    from camlab.fixtures.stereo import half_size_rectification

    hs = half_size_rectification()
    # grey uint8, read as float32 as matching_cost reads them
    L, R = (np.asarray(im, np.float32) for im in (hs.left, hs.right))
    h, w = L.shape
    count = dp.box_sum(np.ones((h, w)), 5)
    Lz, Rz = (a - dp.box_sum(a, 5) / count for a in (L, R))
    for u, v in [(200, 120), (60, 0), (w - 1, h - 1), (47, 1), (120, h - 3)]:
        ds, c = dp.matching_cost(hs.left, hs.right, u, v, 44, 5, min_disparity=3)
        rows, cols = slice(max(v - 2, 0), v + 3), np.arange(max(u - 2, 0), min(u + 3, w))
        ref = [
            np.abs(Lz[rows, cols] - Rz[rows, cols - d]).sum() if u >= d + 2 else np.inf for d in ds
        ]
        assert np.allclose(c, ref, rtol=1e-9, atol=1e-9) and np.isfinite(c).any()
