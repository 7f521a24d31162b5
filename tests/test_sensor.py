"""Tests for camlab.sensor: pixel mapping, sampling, quantisation, noise, Bayer and demosaicing."""

import numpy as np
import pytest

from camlab import render as r
from camlab import scenes
from camlab import sensor as S
from camlab._validate import CamlabInputError


def test_metric_pixel_round_trip_and_intrinsics():
    pts = np.array([[1e-3, -2e-3], [0.0, 0.0]])
    px = S.metric_to_pixels(pts, (4e-6, 5e-6), (320, 240))
    assert np.allclose(px, [[570, -160], [320, 240]])
    assert np.allclose(S.pixels_to_metric(px, (4e-6, 5e-6), (320, 240)), pts)
    K = S.intrinsics_from_sensor(4e-3, (4e-6, 5e-6), (640, 480), (2, -1))
    assert np.allclose(K, [[1000, 0, 321.5], [0, 800, 238.5], [0, 0, 1]])


def test_quantise_levels_and_errors():
    x = np.linspace(0, 1, 1001)
    for bits in (1, 3, 8, 12, 16):
        q = S.quantise(x, bits)
        assert len(np.unique(q)) == min(2**bits, 1001)
        assert np.abs(S.dequantise(q, bits) - x).max() <= 0.5 / (2**bits - 1) + 1e-12
    assert S.quantise(x, 12).dtype == np.uint16
    for bad in (0, 17, 8.5):
        with pytest.raises(
            CamlabInputError, match="bits: expected an integer bit depth from 1 to 16"
        ):
            S.quantise(x, bad)
    with pytest.raises(CamlabInputError, match="image: expected a float image"):
        S.quantise(np.zeros(3, np.uint8))


def test_aliasing_point_sampling_versus_box_filter():
    zp = S.zone_plate(512)
    point = S.sample(zp, 4, prefilter=False)
    box = S.sample(zp, 4, prefilter=True)
    assert point.shape == box.shape == (128, 128)
    # beyond the coarse Nyquist radius the true signal averages to 0.5 with tiny contrast;
    # point sampling shows full-contrast false rings there, the box filter mostly does not
    yy, xx = np.mgrid[0:128, 0:128] - 63.5
    outer = np.hypot(xx, yy) > 45
    assert point[outer].std() > 0.3 and box[outer].std() < 0.15


def test_noise_statistics():
    img = np.full((200, 200), 0.25)
    n = S.add_noise(img, S.NoiseModel(full_well=4000, read_noise=10), rng=0)
    assert n.mean() == pytest.approx(0.25, abs=2e-3)
    assert n.std() == pytest.approx(np.sqrt(0.25 * 4000 + 100) / 4000, rel=0.05)
    assert np.array_equal(n, S.add_noise(img, S.NoiseModel(4000, 10), rng=0))


@pytest.mark.parametrize("pattern", S.BAYER_PATTERNS)
def test_mosaic_and_bilinear_demosaic(pattern):
    rng = np.random.default_rng(0)
    rgb = rng.uniform(size=(8, 10, 3))
    raw = S.mosaic(rgb, pattern)
    m = S.bayer_masks(raw.shape, pattern)
    assert m.sum(axis=2).max() == 1 and m[..., 1].mean() == 0.5
    assert np.allclose(raw, (rgb * m).sum(axis=2))
    out = S.demosaic_bilinear(raw, pattern)
    assert np.allclose(out[m], rgb[m])  # measured samples kept
    # a smooth (linear) colour ramp is reconstructed exactly away from the border
    yy, xx = np.mgrid[0:12, 0:12].astype(float)
    ramp = np.stack([0.02 * xx + 0.01 * yy, 0.5 - 0.01 * xx, 0.03 * yy], axis=2)
    rec = S.demosaic_bilinear(S.mosaic(ramp, pattern), pattern)
    assert np.allclose(rec[1:-1, 1:-1], ramp[1:-1, 1:-1])


@pytest.mark.parametrize("pattern", S.BAYER_PATTERNS)
def test_bilinear_matches_or_beats_opencv_on_a_rendered_scene(pattern):
    K = np.array([[700.0, 0, 159.5], [0, 700, 119.5], [0, 0, 1]])
    truth = r.render(scenes.photo_plane(0.3, t=(0, 0, 0.9)), K, size=(320, 240)).irradiance
    raw = S.quantise(S.mosaic(truth, pattern))
    ours = S.demosaic_bilinear(raw, pattern) / 255
    cv_bilinear = S.demosaic_opencv(raw, pattern, "bilinear") / 255
    p_ours, p_cv = S.psnr(truth, ours, border=2), S.psnr(truth, cv_bilinear, border=2)
    assert p_cv > 25  # the adapter picks OpenCV's matching pattern (a wrong one gives ~15 dB)
    assert p_ours >= p_cv - 0.05
    for method in ("vng", "ea"):
        assert S.psnr(truth, S.demosaic_opencv(raw, pattern, method) / 255, border=2) > 25


def test_bad_inputs():
    with pytest.raises(
        CamlabInputError, match="pattern: expected one of RGGB, BGGR, GRBG, GBRG, got 'RGBG'"
    ):
        S.mosaic(np.zeros((4, 4, 3)), "RGBG")
    with pytest.raises(
        CamlabInputError, match=r"rgb: expected an image of shape \(H, W, 3\), got shape \(4, 4\)"
    ):
        S.mosaic(np.zeros((4, 4)))
    with pytest.raises(CamlabInputError, match=r"raw: expected an image of shape \(H, W\)"):
        S.demosaic_bilinear(np.zeros((4, 4, 3)))
    with pytest.raises(CamlabInputError, match="raw: OpenCV demosaicing needs uint8 or uint16"):
        S.demosaic_opencv(np.zeros((4, 4)))
    with pytest.raises(
        CamlabInputError, match="image: expected an image of integer or float pixels"
    ):
        S.add_noise(np.zeros((3, 3), dtype=bool))
    with pytest.raises(CamlabInputError, match="pitch: expected a pair of positive numbers"):
        S.metric_to_pixels([0, 0], (0, 1e-6), (0, 0))


def test_gamma_encode_is_srgb():
    L = np.linspace(0, 1, 1001)
    V = S.gamma_encode(L)
    assert V[0] == 0 and V[-1] == pytest.approx(1.0)
    assert np.all(np.diff(V) > 0)  # monotonic: no code is lost
    knee = 0.0031308
    assert 12.92 * knee == pytest.approx(
        1.055 * knee ** (1 / 2.4) - 0.055, abs=1e-6
    )  # the two pieces meet
    assert S.gamma_encode(0.18) == pytest.approx(
        0.4614, abs=1e-4
    )  # mid-grey is stored near the middle
    assert np.allclose(S.gamma_decode(V), L, atol=1e-9)  # the display's decoding undoes it
    assert S.gamma_decode(0.04045) == pytest.approx(0.04045 / 12.92)  # the linear toe
    assert S.gamma_decode(0.5) == pytest.approx(
        0.2140, abs=1e-4
    )  # half the code is a fifth of the light


def test_white_balance_neutralises_the_white_and_grey_world():
    rng = np.random.default_rng(3)
    scene = rng.uniform(0.1, 0.9, (20, 30, 3))
    light = np.array([1.0, 0.8, 0.55])
    seen = scene * light
    fixed = S.white_balance(seen, white=light * 0.9)
    assert np.allclose(fixed, np.clip(scene * 0.8, 0, 1))  # normalised to the green channel
    grey = S.white_balance(seen)  # grey world: mean colour -> grey
    m = grey.reshape(-1, 3).mean(axis=0)
    assert np.ptp(m) < 0.01
    with pytest.raises(CamlabInputError, match="white: expected three positive"):
        S.white_balance(seen, white=[1.0, 0.0, 1.0])
    with pytest.raises(CamlabInputError, match=r"rgb: expected an image of shape \(H, W, 3\)"):
        S.white_balance(seen[..., 0])


def test_sample_blur_is_a_gaussian_in_coarse_pixels():
    """blur = sigma in coarse pixels: a cosine of f cycles per coarse pixel keeps exp(-2 pi^2 sigma^2 f^2)."""
    factor, f = 4, 0.25  # 0.25 cycle per coarse pixel = 1/16 per fine pixel
    x = np.arange(512)
    image = np.tile(np.cos(2 * np.pi * f / factor * x), (8, 1))
    sharp = np.ptp(S.sample(image, factor)[1, 16:-16])
    for blur in (0.5, 1.0):
        kept = np.ptp(S.sample(image, factor, prefilter=False, blur=blur)[1, 16:-16]) / sharp
        assert kept == pytest.approx(np.exp(-2 * np.pi**2 * blur**2 * f**2), rel=0.02)
    with pytest.raises(CamlabInputError, match="blur: expected a standard deviation >= 0"):
        S.sample(image, factor, blur=-1)


def test_alias_frequency_gives_the_same_samples_in_the_band_below_the_limit():
    f = np.array([0.2, 0.45, 0.5, 0.55, 0.8, 1.0, 1.3, 2.2, -0.2, -1.4])
    a = S.alias_frequency(f)
    assert np.allclose(a, [0.2, 0.45, 0.5, 0.45, 0.2, 0.0, 0.3, 0.2, 0.2, 0.4])
    n = np.arange(50)
    assert np.allclose(np.cos(2 * np.pi * f[:, None] * n), np.cos(2 * np.pi * a[:, None] * n))
    assert a.dtype == float and S.alias_frequency(0.8).shape == ()
