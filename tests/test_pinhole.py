"""Tests for camlab.pinhole: similar triangles, the real and virtual image, the best pinhole size."""

import numpy as np
import pytest

from camlab import pinhole
from camlab._validate import CamlabInputError


def test_similar_triangles_and_inversion():
    X = np.array([[0.2, -0.1, 2.0], [0.0, 0.0, 1.0], [1.0, 1.0, -1.0]])
    v = pinhole.project_pinhole(X, 0.05)
    assert np.allclose(v[0], [0.005, -0.0025]) and np.allclose(v[1], [0, 0])
    assert np.isnan(v[2]).all()
    real = pinhole.project_pinhole(X, 0.05, plane="real")
    assert np.allclose(real[:2], -v[:2])
    # doubling the distance halves the image
    assert np.allclose(pinhole.project_pinhole([0.2, -0.1, 4.0], 0.05), v[0] / 2)


def test_blur_terms_and_optimum():
    f, lam = 0.1, 550e-9
    d_star = pinhole.optimal_pinhole_diameter(f, lam)
    assert d_star == pytest.approx(np.sqrt(2.44 * lam * f)) and d_star == pytest.approx(
        0.366e-3, abs=1e-6
    )
    ds = np.linspace(0.05e-3, 2e-3, 4001)
    total = pinhole.pinhole_blur(ds, f, wavelength=lam).total
    assert ds[np.argmin(total)] == pytest.approx(d_star, rel=2e-3)
    # at the optimum both terms are equal
    b = pinhole.pinhole_blur(d_star, f, wavelength=lam)
    assert b.geometric == pytest.approx(b.diffraction)
    # a near object needs a smaller hole
    assert pinhole.optimal_pinhole_diameter(f, lam, 0.3) < d_star
    assert pinhole.geometric_blur(1e-3, 0.1, 0.1) == pytest.approx(2e-3)


def test_bad_inputs():
    with pytest.raises(
        CamlabInputError, match=r"focal_length: expected a positive finite number metres, got 0"
    ):
        pinhole.project_pinhole([0, 0, 1], 0)
    with pytest.raises(CamlabInputError, match=r"plane: expected 'virtual' or 'real'"):
        pinhole.project_pinhole([0, 0, 1], 0.05, plane="front")
    with pytest.raises(
        CamlabInputError, match=r"diameter: expected positive finite pinhole diameters"
    ):
        pinhole.diffraction_blur(-1e-3, 0.1)
    with pytest.raises(CamlabInputError, match=r"points: expected \(N, 3\) points"):
        pinhole.project_pinhole([0, 1], 0.05)


def test_level_crossing_interpolates_between_pixels_and_names_a_missing_crossing():
    profile = [200, 200, 150, 50, 50]  # crosses 125 a quarter of the way from 2 to 3
    assert np.isclose(pinhole.level_crossing(profile, 125, 0), 2.25)
    with pytest.raises(ValueError, match="never crosses"):
        pinhole.level_crossing(profile, 125, 3)
    with pytest.raises(ValueError, match="profile: expected a 1-D array"):
        pinhole.level_crossing(np.zeros((3, 3)), 1, 0)


def test_band_heights_reads_a_known_dark_band_and_its_spread():
    # a dark band (brightness 40) from row 30.5 to row 70.5 under a white frame (220), blurred over one pixel:
    # the half-way crossings fall exactly on the band's edges, 40 px apart, in every column
    v = np.arange(100.0)
    column = 220 - 180 * np.clip(v - 30, 0, 1) + 180 * np.clip(v - 70, 0, 1)
    grey = np.tile(column[:, None], (1, 20))
    read = pinhole.band_heights(grey, {10: (31, 71)})
    assert np.allclose([read.top[0], read.bottom[0], read.height[0]], [30.5, 70.5, 40.0])
    assert np.isclose(read.level[0], 130)
    # the 40 % and 60 % levels cross 0.1 px either side of half-way at both edges: heights 40 -+ 0.2
    assert np.allclose([read.low[0], read.high[0]], [39.8, 40.2])
    with pytest.raises(ValueError, match="grey: expected an \\(H, W\\) grey image"):
        pinhole.band_heights(np.zeros((4, 4, 3)), {1: (1, 2)})


def test_band_heights_reads_the_church_windows_of_lesson_01():
    from camlab.data import load_photo

    grey = load_photo("church").mean(axis=2)
    by_eye = {266: (355, 443), 344: (370, 450), 408: (383, 455), 461: (394, 459), 505: (403, 462)}
    read = pinhole.band_heights(grey, by_eye)
    assert np.allclose(read.height, [88.8, 79.7, 72.0, 65.7, 59.9], atol=0.05)
    assert np.all(read.low <= read.height) and np.all(read.height <= read.high)
