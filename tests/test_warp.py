"""Tests for camlab.warp: inverse and forward mapping, automatic canvas, cv2 agreement."""

from __future__ import annotations

import cv2
import numpy as np
import pytest
from conftest import assert_close_to_cv2_warp

from camlab import warp
from camlab._validate import CamlabInputError, DegenerateError
from camlab.homography import similarity_homography
from camlab.projective import map_points

H = np.array([[0.9, 0.1, 30.0], [-0.05, 0.95, 20.0], [2e-4, 1e-4, 1.0]])


def _image(shape=(480, 640, 3), seed=0):
    rng = np.random.default_rng(seed)
    img = (rng.random(shape) * 255).astype(np.uint8)
    return cv2.GaussianBlur(img, (0, 0), 2)


def _interior(shape, H, margin=3):
    """Output pixels whose bilinear support lies well inside the source image."""
    h, w = shape[:2]
    v, u = np.mgrid[0:h, 0:w]
    src = map_points(np.linalg.inv(H), np.column_stack([u.ravel(), v.ravel()]).astype(float))
    ok = (
        (src[:, 0] > margin)
        & (src[:, 0] < w - 1 - margin)
        & (src[:, 1] > margin)
        & (src[:, 1] < h - 1 - margin)
    )
    return ok.reshape(h, w)


@pytest.mark.parametrize("shape", [(480, 640, 3), (480, 640)])
def test_bilinear_matches_cv2_within_one_grey_level(shape):
    img = _image(shape)
    ours = warp.warp_perspective(img, H, (480, 640))
    ref = cv2.warpPerspective(img, H, (640, 480), flags=cv2.INTER_LINEAR)
    diff = np.abs(ours.astype(int) - ref.astype(int))
    inside = _interior(shape, H)
    assert inside.mean() > 0.6
    assert (
        diff[inside].max() <= 1 and diff[inside].mean() < 0.05
    )  # measured 0.0001 (OpenCV 5.0), 0.037 (4.12)
    assert (
        diff.max() <= 3
    )  # even at the border (blend with fill; OpenCV 4.x's fixed-point weights: 3, 5.x: 1)
    assert ours.dtype == np.uint8 and ours.shape == ref.shape


def test_nearest_matches_cv2_nearly_everywhere():
    img = _image()
    ours = warp.warp_perspective(img, H, (480, 640), interpolation="nearest")
    ref = cv2.warpPerspective(img, H, (640, 480), flags=cv2.INTER_NEAREST)
    # differences only where the source position is within rounding of a pixel boundary
    assert (np.any(ours != ref, axis=2)).mean() < 1e-3


def test_cv2_path_gives_the_same_picture():
    img = _image()
    inside = _interior(img.shape, H)
    a = warp.warp_perspective(img, H, (480, 640))
    b = warp.warp_perspective(img, H, (480, 640), method="cv2")
    assert np.abs(a.astype(int) - b.astype(int))[inside].max() <= 1
    # nearest: a different pixel is picked only where the position rounds differently
    a = warp.warp_perspective(img, H, (480, 640), interpolation="nearest")
    b = warp.warp_perspective(img, H, (480, 640), interpolation="nearest", method="cv2")
    assert np.any(a != b, axis=2)[inside].mean() < 1e-3


def test_float_image_and_known_values():
    img = np.arange(12.0).reshape(3, 4)
    # half-pixel shift: bilinear averages neighbours
    out = warp.warp_perspective(img, [[1, 0, 0.5], [0, 1, 0], [0, 0, 1]], (3, 4))
    assert np.allclose(out[1, 1:], [4.5, 5.5, 6.5])
    assert out.dtype == np.float64
    # identity is exact, nearest and bilinear
    for interp in ("nearest", "bilinear"):
        assert np.array_equal(
            warp.warp_perspective(img, np.eye(3), (3, 4), interpolation=interp), img
        )


def test_fill_and_points_behind_horizon():
    img = np.full((20, 20), 100, np.uint8)
    out = warp.warp_perspective(img, [[1, 0, 100], [0, 1, 0], [0, 0, 1]], (20, 20), fill=7)
    assert np.all(out == 7)
    # A homography with a horizon inside the output: pixels beyond it are not visible.
    # Hh sends the source row v = 10 to infinity and rows v > 10 (w < 0) "behind" the
    # viewer, where they would reappear upside down at the top of the output.
    Hh = np.array([[1.0, 0, 0], [0, 1, 30], [0, 0, 1]]) @ np.array(
        [[1.0, 0, 0], [0, 1, 0], [0, -0.1, 1]]
    )
    src = np.full((40, 40), 200, np.uint8)
    out = warp.warp_perspective(src, Hh, (60, 40), fill=0)
    ref = cv2.warpPerspective(src, Hh, (40, 60))
    assert out[:18].max() == 0 and ref[:18].max() == 200  # cv2 draws the mirrored part
    assert out[35:].min() == 200  # rows v < 10 are visible below
    # -H is the same homography: same picture
    a = warp.warp_perspective(_image((60, 80)), H, (60, 80))
    b = warp.warp_perspective(_image((60, 80)), -H, (60, 80))
    assert np.array_equal(a, b)


def test_mirror_draws_the_far_side_of_the_horizon_as_cv2_does():
    """mirror=True: the points beyond the line H sends to infinity show mirrored, as OpenCV draws them."""
    Hh = np.array([[1.0, 0, 0], [0, 1, 30], [0, 0, 1]]) @ np.array(
        [[1.0, 0, 0], [0, 1, 0], [0, -0.1, 1]]
    )
    src = _image((40, 40))
    out = warp.warp_perspective(src, Hh, (60, 40), fill=0, mirror=True)
    ref = cv2.warpPerspective(src, Hh, (40, 60))
    assert out[:18].max() > 0  # the mirrored part, which mirror=False leaves at fill
    # every row but the horizon's own (w = 0 exactly at row 20: OpenCV 4.12 draws a clamped
    # sample there, 5.0 leaves it at fill, as camlab does)
    Hi = np.linalg.inv(Hh)
    on_horizon = np.isclose(Hi[2, 1] * np.arange(60) + Hi[2, 2], 0, atol=1e-12)
    assert on_horizon.sum() == 1
    assert np.abs(out.astype(int) - ref)[~on_horizon].max() <= 2  # rounding: 1 (5.0), 2 (4.12)
    assert not warp.warp_perspective(src, Hh, (60, 40), fill=0)[:18].any()


def test_forward_warp_has_holes_inverse_does_not():
    img = np.full((50, 50), 255, np.uint8)
    Hs = similarity_homography(2.5, 0.2, 10, 10)
    fwd = warp.forward_warp(img, Hs, (150, 150))
    inv = warp.warp_perspective(img, Hs, (150, 150))
    region = (
        warp.warp_perspective(
            np.ones((50, 50), np.float32), Hs, (150, 150), interpolation="nearest"
        )
        > 0
    )
    inner = cv2.erode(region.astype(np.uint8), np.ones((5, 5))) > 0
    holes_fwd = (fwd[inner] == 0).mean()
    holes_inv = (inv[inner] == 0).mean()
    assert holes_fwd > 0.5 and holes_inv == 0.0


def test_canvas_contains_whole_image_and_translation_composes():
    img = _image((120, 160, 3))
    Hneg = similarity_homography(1.0, 0.5, -60, -30)  # rotates parts to negative coordinates
    r = warp.warp_to_canvas(img, Hneg)
    corners = np.array([[0, 0], [159, 0], [159, 119], [0, 119]], float)
    mapped = map_points(r.H, corners)
    assert mapped.min() >= -1e-9
    assert np.all(mapped[:, 0] <= r.image.shape[1] - 1 + 1e-9) and np.all(
        mapped[:, 1] <= r.image.shape[0] - 1 + 1e-9
    )
    assert np.allclose(r.H, r.T @ Hneg / (r.T @ Hneg)[2, 2])
    assert r.mask.shape == r.image.shape[:2]
    assert np.isclose(r.mask.sum(), 120 * 160, rtol=0.03)  # area preserved by a rigid motion
    # The canvas image agrees with cv2 on the same composed H.
    ref = cv2.warpPerspective(img, r.H, (r.image.shape[1], r.image.shape[0]))
    inside = _interior(r.image.shape, r.H)
    assert_close_to_cv2_warp(r.image[inside], ref[inside])


def test_bad_input():
    img = _image((20, 30))
    with pytest.raises(DegenerateError, match="H: singular"):
        warp.warp_perspective(img, np.diag([1.0, 1.0, 0.0]), (20, 30))
    with pytest.raises(CamlabInputError, match=r"H: expected a \(3, 3\) matrix"):
        warp.warp_perspective(img, np.eye(2), (20, 30))
    with pytest.raises(CamlabInputError, match="image: expected a"):
        warp.warp_perspective(np.zeros((4, 4, 2)), np.eye(3), (4, 4))
    with pytest.raises(CamlabInputError, match=r"output_shape: expected \(height, width\)"):
        warp.warp_perspective(img, np.eye(3), (0, 10))
    with pytest.raises(CamlabInputError, match="interpolation: expected one of"):
        warp.warp_perspective(img, np.eye(3), (20, 30), interpolation="cubic")
    with pytest.raises(DegenerateError, match="maps to or beyond infinity"):
        warp.warp_to_canvas(img, [[1, 0, 0], [0, 1, 0], [0, -0.1, 1]])


@pytest.mark.parametrize("dtype", [np.uint8, np.uint16, np.int32, np.float32, np.float64])
def test_dtype_kept_and_methods_agree(dtype):
    img = (np.arange(48).reshape(6, 8) * 3).astype(dtype)
    H_half = [[1, 0, 0.5], [0, 1, 0], [0, 0, 1]]
    a = warp.warp_perspective(img, H_half, (6, 8))
    b = warp.warp_perspective(img, H_half, (6, 8), method="cv2")
    assert a.dtype == b.dtype == dtype
    assert np.abs(a.astype(float) - b.astype(float))[:, 1:-1].max() <= 1
