"""Tests for camlab.features: detection, the ratio test, the mutual check, drawing helpers."""

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as hs

from camlab import features as ft
from camlab import homography as hg
from camlab._validate import CamlabInputError
from camlab.data import panorama as sd
from camlab.projective import map_points


@pytest.fixture(scope="module")
def pair():
    s = sd.load_panorama_set(scale=0.5)
    f = [ft.detect_features(s.images[k], max_features=1500) for k in (1, 2)]
    return s, f


def test_to_gray_uint8_known_values_and_types():
    rgb = np.zeros((8, 8, 3), np.uint8)
    rgb[..., 0] = 200
    assert ft.to_gray_uint8(rgb)[0, 0] == round(0.299 * 200)
    assert ft.to_gray_uint8(np.full((8, 8), 1.0))[0, 0] == 255
    assert ft.to_gray_uint8(np.full((8, 8), 65535, np.uint16))[0, 0] == 255
    assert ft.to_gray_uint8(np.full((8, 8, 4), 0.5))[0, 0] == 128


@pytest.mark.parametrize(
    "bad, match",
    [
        (np.zeros((4, 4)), r"image: expected .* at least 8 x 8 pixels, got shape \(4, 4\)"),
        (np.zeros((10, 10, 2)), r"got shape \(10, 10, 2\)"),
        (np.zeros((10, 10), np.int32), r"expected uint8, uint16 or float pixels, got dtype int32"),
    ],
)
def test_to_gray_uint8_bad_input(bad, match):
    with pytest.raises(CamlabInputError, match=match):
        ft.to_gray_uint8(bad)


def test_detect_sift_and_orb_shapes(pair):
    s, (f1, _) = pair
    assert f1.points.shape[1] == 2 and f1.points.shape[0] > 300
    assert f1.descriptors.shape == (len(f1.points), 128) and f1.descriptors.dtype == np.float32
    assert np.all((f1.points >= -0.5) & (f1.points <= [319.5, 239.5]))
    orb = ft.detect_features(s.images[1], "orb", 500)
    assert orb.descriptors.shape == (len(orb.points), 32) and orb.descriptors.dtype == np.uint8
    assert 100 < len(orb.points) <= 500
    assert orb.method == "orb"


def test_detect_bad_options_and_mask(pair):
    s, _ = pair
    with pytest.raises(
        CamlabInputError, match=r"method: expected one of \('sift', 'orb'\), got 'surf'"
    ):
        ft.detect_features(s.images[0], "surf")
    with pytest.raises(CamlabInputError, match="max_features: expected a whole number >= 1"):
        ft.detect_features(s.images[0], max_features=0)
    with pytest.raises(CamlabInputError, match=r"mask: expected shape \(240, 320\)"):
        ft.detect_features(s.images[0], mask=np.ones((10, 10), bool))
    mask = np.zeros((240, 320), bool)
    mask[:, :160] = True
    f = ft.detect_features(s.images[0], mask=mask)
    assert len(f.points) > 50 and f.points[:, 0].max() < 160


def test_an_image_seen_again_is_answered_from_memory_as_a_fresh_copy(pair, monkeypatch):
    """The same grey pixels, mask and settings are not detected again (lesson 09 stitches the
    same photos at several settings); the answer is a copy; anything else detects anew."""
    s, _ = pair
    monkeypatch.setattr(ft, "_SEEN", type(ft._SEEN)(keep=32))
    calls = []
    detect = ft._detect
    monkeypatch.setattr(ft, "_detect", lambda *a: calls.append(a[2:]) or detect(*a))
    img = s.images[3]
    first = ft.detect_features(img, max_features=800)
    first.points[:] = -1.0  # the caller's copy: changing it leaves the remembered answer alone
    again = ft.detect_features(img.copy(), max_features=800)
    fresh = detect(ft.to_gray_uint8(img), None, "sift", 800, 0.02)
    assert calls == [("sift", 800, 0.02)]
    for got, want in zip(again, fresh, strict=True):
        assert np.array_equal(got, want) if isinstance(want, np.ndarray) else got == want
    ft.detect_features(img, max_features=700)
    ft.detect_features(img, max_features=800, contrast_threshold=0.04)
    ft.detect_features(img, "orb", 800)
    ft.detect_features(img, "orb", 800, contrast_threshold=0.04)  # ORB ignores it: remembered
    ft.detect_features(img, max_features=800, mask=np.ones((240, 320), bool))
    other = ft.to_gray_uint8(img)
    other[0, 0] ^= 1  # one grey level of one pixel
    ft.detect_features(other, max_features=800)
    assert len(calls) == 6
    monkeypatch.setattr(ft._SEEN, "keep", 2)
    ft.detect_features(s.images[0], max_features=800)
    assert len(ft._SEEN) == 2


def test_flat_image_has_no_features_and_matches_nothing(pair):
    _, (f1, _) = pair
    flat = ft.detect_features(np.zeros((100, 100), np.uint8))
    assert flat.points.shape == (0, 2) and flat.descriptors.shape == (0, 128)
    m = ft.match_features(flat, f1)
    assert m.src.shape == (0, 2) and len(ft.match_features(f1, flat).src) == 0


def test_ratio_test_matches_are_mostly_correct(pair):
    s, (f1, f2) = pair
    H = s.true_homography(1, 2)
    m = ft.match_features(f1, f2, ratio=0.7)
    ok = hg.transfer_error(H, m.src, m.dst) < 2.0
    assert len(m.src) > 150 and ok.mean() > 0.95
    loose = ft.match_features(f1, f2, ratio=1.0)
    assert (hg.transfer_error(H, loose.src, loose.dst) >= 2.0).sum() > 5 * (~ok).sum()


def test_ratio_test_against_opencv_knn(pair):
    """The same ratio test done by hand on cv2's knnMatch keeps exactly the same pairs."""
    _, (f1, f2) = pair
    knn = cv2.BFMatcher(cv2.NORM_L2).knnMatch(f1.descriptors, f2.descriptors, k=2)
    expected = {(a.queryIdx, a.trainIdx) for a, b in knn if a.distance < 0.8 * b.distance}
    m = ft.match_features(f1, f2, ratio=0.8)
    assert set(zip(m.idx1.tolist(), m.idx2.tolist(), strict=True)) == expected
    assert np.all(np.diff(m.ratio) >= 0) and np.all(m.ratio < 0.8)
    assert np.allclose(m.src, f1.points[m.idx1]) and np.allclose(m.dst, f2.points[m.idx2])


def test_mutual_check_equals_opencv_cross_check(pair):
    _, (f1, f2) = pair
    cross = cv2.BFMatcher(cv2.NORM_L2, crossCheck=True).match(f1.descriptors, f2.descriptors)
    expected = {(c.queryIdx, c.trainIdx) for c in cross}
    m = ft.match_features(f1, f2, ratio=1.0, mutual=True)
    assert set(zip(m.idx1.tolist(), m.idx2.tolist(), strict=True)) == expected
    knn = ft.knn_match(f1, f2, backward=False)
    with pytest.raises(CamlabInputError, match="mutual: the mutual check needs knn_match"):
        ft.filter_matches(knn, 0.8, mutual=True)


def test_flann_index_agrees_with_brute_force(pair):
    """The FLANN path (one index per image, reused across pairs) finds nearly the same ratio-test
    matches as brute force, with the same (unsquared L2) distances where it finds the same neighbour."""
    s, (f1, f2) = pair
    bf = ft.match_features(f1, f2, ratio=0.75)
    index = ft.flann_index(f2)
    knn = ft.knn_match(f1, f2, backward=True, index2=index)
    exact = ft.knn_match(f1, f2)
    same = knn.nn12[:, 0] == exact.nn12[:, 0]
    assert np.allclose(knn.d12[same, 0], exact.d12[same, 0], rtol=1e-5)
    fl = ft.filter_matches(knn, 0.75)
    both = set(zip(fl.idx1.tolist(), fl.idx2.tolist(), strict=True)) & set(
        zip(bf.idx1.tolist(), bf.idx2.tolist(), strict=True)
    )
    assert len(both) >= 0.9 * len(bf.idx1) and len(fl.idx1) <= 1.05 * len(bf.idx1)
    H = s.true_homography(1, 2)
    right, right_bf = (
        hg.transfer_error(H, fl.src, fl.dst) < 2.0,
        hg.transfer_error(H, bf.src, bf.dst) < 2.0,
    )
    assert right.sum() >= 0.9 * right_bf.sum() and right.mean() >= right_bf.mean() - 0.02
    again = ft.filter_matches(
        ft.knn_match(f1, f2, backward=False, index2=index), 0.75
    )  # the index is reusable
    assert np.array_equal(again.idx1, fl.idx1)
    assert (knn.nn21 >= 0).all() and (
        knn.nn21[fl.idx2] == fl.idx1
    ).mean() > 0.9  # the backward pass
    with pytest.raises(CamlabInputError, match="features: expected SIFT features"):
        ft.flann_index(ft.detect_features(s.images[1], "orb", 500))


def test_flann_matches_do_not_depend_on_what_ran_before(pair):
    """FLANN's random trees come from OpenCV's global generator: flann_index seeds it, so the
    same features match the same way whatever was drawn before (the panorama stays the same)."""
    _, (f1, f2) = pair
    first = ft.knn_match(f1, f2, approximate=True)
    cv2.randu(
        np.zeros(1000, np.float32), 0, 1
    )  # draws from the global generator, as other code would
    ft.flann_index(f1)
    again = ft.knn_match(f1, f2, approximate=True)
    assert np.array_equal(first.nn12, again.nn12) and np.array_equal(first.nn21, again.nn21)


def test_orb_matching_uses_hamming(pair):
    """ORB, the fast option: binary descriptors, Hamming distances, coarser keypoint positions."""
    full = sd.load_panorama_set()
    o1, o2 = (ft.detect_features(full.images[k], "orb", 2000) for k in (1, 2))
    m = ft.match_features(o1, o2, ratio=0.8)
    assert np.all(m.distance == np.round(m.distance))  # Hamming distances are whole bits
    ok = hg.transfer_error(full.true_homography(1, 2), m.src, m.dst) < 3
    assert ok.sum() > 100 and ok.mean() > 0.7
    from camlab.stitching import register_pair

    r = register_pair(o1, o2, ratio=0.8)
    c = np.array([[0, 0], [639, 0], [639, 479], [0, 479]], float)
    err = np.linalg.norm(
        map_points(r.H, c) - map_points(full.true_homography(1, 2), c), axis=1
    ).max()
    assert (
        r.accepted and err < 10.0
    )  # measured about 6 px: ORB keypoints sit on pyramid-level grids
    with pytest.raises(
        CamlabInputError, match="features2: expected orb features like features1, got sift"
    ):
        ft.knn_match(o1, pair[1][1])


def test_filter_bad_input():
    with pytest.raises(CamlabInputError, match=r"ratio: expected a number in \(0, 1\]"):
        ft.filter_matches(
            ft.KnnMatches(
                np.zeros((0, 2), int), np.zeros((0, 2)), None, np.zeros((0, 2)), np.zeros((0, 2))
            ),
            1.5,
        )
    with pytest.raises(CamlabInputError, match="knn: expected camlab.features.KnnMatches"):
        ft.filter_matches([(0, 1)], 0.8)
    with pytest.raises(CamlabInputError, match="features1: expected camlab.features.Features"):
        ft.knn_match(np.zeros((3, 128)), np.zeros((3, 128)))


@settings(max_examples=40, deadline=None)
@given(hs.integers(0, 10_000), hs.floats(0.2, 1.0), hs.floats(0.2, 1.0))
def test_ratio_filter_is_monotone(seed, r1, r2):
    """A stricter ratio keeps a subset; every kept match passes d1 < r d2; mutual keeps a subset."""
    rng = np.random.default_rng(seed)
    n1, n2 = 30, 25
    d = np.sort(rng.uniform(0, 10, (n1, 2)), axis=1)
    nn = np.column_stack([rng.integers(0, n2, n1), rng.integers(0, n2, n1)])
    knn = ft.KnnMatches(
        nn, d, rng.integers(0, n1, n2), rng.uniform(0, 100, (n1, 2)), rng.uniform(0, 100, (n2, 2))
    )
    lo, hi = sorted((r1, r2))
    a, b = ft.filter_matches(knn, lo), ft.filter_matches(knn, hi)
    assert set(a.idx1) <= set(b.idx1)
    if lo < 1:
        assert np.all(d[a.idx1, 0] < lo * d[a.idx1, 1])
    assert set(ft.filter_matches(knn, hi, mutual=True).idx1) <= set(b.idx1)


def test_drawing_helpers(pair):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from camlab.plotting.stitching import draw_keypoints, draw_matches, match_segments, side_by_side

    s, (f1, f2) = pair
    m = ft.match_features(f1, f2)
    good = hg.transfer_error(s.true_homography(1, 2), m.src, m.dst) < 2
    fig, ax = plt.subplots()
    art = draw_matches(ax, s.images[1], s.images[2], m.src, m.dst, good)
    assert (
        len(art["good"].get_segments()) == good.sum()
        and len(art["bad"].get_segments()) == (~good).sum()
    )
    assert art["offset"] == 328.0
    seg = match_segments(m.src[:1], m.dst[:1], 328.0)
    assert np.allclose(seg[0], [m.src[0], m.dst[0] + [328, 0]])
    pts = draw_keypoints(ax, f1.points, f1.sizes)
    assert len(pts.get_offsets()) == len(f1.points)
    both, off = side_by_side(np.zeros((10, 5), np.uint8), np.zeros((12, 7, 3), np.uint8), gap=2)
    assert both.shape == (12, 14, 3) and off == 7.0
    plt.close(fig)
