"""Tests for camlab.lens: textbook values, consistency between formulas, bad physical input."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from camlab import lens
from camlab._validate import CamlabInputError


def test_thin_lens_textbook_values():
    assert lens.image_distance(0.05, 0.1) == pytest.approx(0.1)  # 2f -> 2f
    assert lens.magnification(0.05, 0.1) == pytest.approx(-1.0)
    assert lens.image_distance(0.05, 1e9) == pytest.approx(0.05)  # infinity -> f
    assert lens.image_distance(0.1, 0.3) == pytest.approx(0.15)  # 1/0.1 - 1/0.3 = 1/0.15
    assert lens.magnification(0.1, 0.3) == pytest.approx(-0.5)
    assert lens.aperture_diameter(0.05, 1.4) == pytest.approx(0.0357142857)


def test_hyperfocal_and_dof_textbook_values():
    # 50 mm, f/8, c = 0.03 mm: H = 10.47 m; focused at H the DoF runs from H/2 to infinity
    H = lens.hyperfocal_distance(0.05, 8, 0.03e-3)
    assert H == pytest.approx(10.4667, abs=1e-3)
    dof = lens.depth_of_field(0.05, 8, H, 0.03e-3)
    assert dof.far == np.inf and dof.near == pytest.approx(H / 2, rel=0.01)
    # 50 mm f/2.8 focused at 3 m, c = 0.03 mm: about 2.73 m to 3.33 m (standard DoF tables)
    dof = lens.depth_of_field(0.05, 2.8, 3.0, 0.03e-3)
    assert dof.near == pytest.approx(2.73, abs=0.01) and dof.far == pytest.approx(3.33, abs=0.01)
    assert dof.total == pytest.approx(dof.far - dof.near)


@settings(max_examples=50, deadline=None)
@given(st.floats(0.01, 0.2), st.floats(1.0, 22.0), st.floats(1.5, 20.0))
def test_dof_limits_are_where_the_blur_equals_the_coc(f, N, s_over_f):
    s = f * 10 * s_over_f
    c = 0.02e-3
    dof = lens.depth_of_field(f, N, s, c)
    assert lens.circle_of_confusion(f, N, s, dof.near) == pytest.approx(c, rel=1e-6)
    if np.isfinite(dof.far):
        assert lens.circle_of_confusion(f, N, s, dof.far) == pytest.approx(c, rel=1e-6)
    assert lens.circle_of_confusion(f, N, s, s) == 0


def test_coc_equals_cone_geometry():
    f, N, s, z = 0.05, 2.0, 2.0, 4.0
    si, zi = lens.image_distance(f, s), lens.image_distance(f, z)
    assert lens.circle_of_confusion(f, N, s, z) == pytest.approx(f / N * abs(si - zi) / zi)
    assert lens.object_distance(f, si) == pytest.approx(s)
    assert np.allclose(lens.image_distance(f, [1.0, 2.0]), [f / (1 - f), 2 * f / (2 - f)])


def test_bad_physical_inputs():
    with pytest.raises(
        CamlabInputError, match=r"focal_length: expected a positive finite number metres, got -0.05"
    ):
        lens.image_distance(-0.05, 1.0)
    with pytest.raises(
        CamlabInputError, match=r"object_distance: object at 0.03 m is inside the focal length"
    ):
        lens.image_distance(0.05, 0.03)
    with pytest.raises(
        CamlabInputError, match=r"image_distance: a sensor 0.03 m behind the lens is not beyond"
    ):
        lens.object_distance(0.05, 0.03)
    with pytest.raises(
        CamlabInputError, match=r"object_distance: expected positive finite distances"
    ):
        lens.magnification(0.05, 0.0)
    with pytest.raises(CamlabInputError, match=r"depth: expected positive finite distances"):
        lens.circle_of_confusion(0.05, 2, 2.0, [-1.0])
    with pytest.raises(CamlabInputError, match=r"f_number: expected a positive finite number"):
        lens.aperture_diameter(0.05, 0)
    with pytest.raises(CamlabInputError, match=r"focus_distance: object at 0.04 m is inside"):
        lens.depth_of_field(0.05, 2, 0.04, 0.03e-3)


def test_angle_of_view_narrows_when_focused_close():
    w = 0.036
    assert lens.angle_of_view(0.05, w) == pytest.approx(2 * np.arctan(w / 0.1))
    near = lens.angle_of_view(0.05, w, 0.5)  # the pinhole focal length is z_i = 55.6 mm
    assert near == pytest.approx(2 * np.arctan(w / (2 * lens.image_distance(0.05, 0.5))))
    assert near < lens.angle_of_view(0.05, w, 5.0) < lens.angle_of_view(0.05, w)
    with pytest.raises(CamlabInputError, match="focus_distance"):
        lens.angle_of_view(0.05, w, 0.04)


def test_aperture_for_depth_of_field_gives_exactly_that_depth_of_field():
    for f, c, near, far in (
        (0.05, 3e-5, 2.0, 4.0),
        (0.028, 2e-5, 0.8, 1.6),
        (0.1, 1.5e-5, 9.0, 11.0),
    ):
        s, N = lens.aperture_for_depth_of_field(f, c, near, far)
        dof = lens.depth_of_field(f, N, s, c)
        assert (dof.near, dof.far) == pytest.approx((near, far), rel=1e-9)
        assert lens.circle_of_confusion(f, N, s, near) == pytest.approx(c)
    with pytest.raises(CamlabInputError, match="near < far"):
        lens.aperture_for_depth_of_field(0.05, 3e-5, 4.0, 2.0)


def test_aperture_kernel_is_the_aperture_scaled_to_the_blur():
    """Round: the renderer's disc, area pi r^2; six blades: a regular hexagon, 3 sqrt(3) / 2 pi of it."""
    from camlab.render.canvas import _disk_kernel

    disc, hexagon = lens.aperture_kernel(40), lens.aperture_kernel(40, blades=6)
    assert np.isclose(disc.sum(), 1) and np.isclose(hexagon.sum(), 1)
    assert np.allclose(disc, _disk_kernel(40))
    assert np.isclose(1 / disc.max(), np.pi * 20**2, rtol=0.01)
    assert np.isclose(disc.max() / hexagon.max(), 3 * np.sqrt(3) / (2 * np.pi), atol=0.005)
    assert np.allclose(hexagon, hexagon[::-1]) and np.allclose(hexagon, hexagon[:, ::-1])
    assert not np.allclose(hexagon, hexagon.T)  # corners up and down, flat sides left and right
    with pytest.raises(CamlabInputError, match="blades"):
        lens.aperture_kernel(10, blades=2)
    with pytest.raises(CamlabInputError, match="diameter_px"):
        lens.aperture_kernel(-1)
