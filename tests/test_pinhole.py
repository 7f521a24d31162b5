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
