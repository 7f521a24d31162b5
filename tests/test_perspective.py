"""Tests for camlab.perspective: corners, aspect ratio, rectification, document finder."""

from __future__ import annotations

import cv2
import numpy as np
import pytest
from conftest import assert_close_to_cv2_warp

from camlab import perspective as pp
from camlab import scenes
from camlab._validate import CamlabInputError, DegenerateError
from camlab.projective import map_points


@pytest.fixture(scope="module")
def photos():
    return {k: scenes.sample_photo(k) for k in ("page", "painting", "facade")}


@pytest.mark.parametrize("kind", ["page", "painting", "facade"])
def test_aspect_ratio_and_focal_recovered_exactly(photos, kind):
    ph = photos[kind]
    est = pp.estimate_aspect_ratio(ph.corners, ph.image.shape)
    assert est.focal_source == "estimated"
    assert np.isclose(est.focal_length, ph.K[0, 0], rtol=1e-8)
    assert np.isclose(est.ratio, ph.aspect, rtol=1e-8)
    # given the focal length, the same answer
    assert np.isclose(
        pp.estimate_aspect_ratio(ph.corners, ph.image.shape, focal_length=800).ratio, ph.aspect
    )


@pytest.mark.parametrize("yaw,pitch", [(0.7, 0.0), (0.0, -0.6), (0.3, 0.4), (-0.8, 0.2)])
def test_aspect_ratio_many_poses_and_textures(yaw, pitch):
    tex = np.zeros((150, 300, 3), np.uint8)  # true ratio 299 / 149
    ph = scenes.photograph_plane(tex, yaw=yaw, pitch=pitch, width_m=0.8, distance=2.5)
    est = pp.estimate_aspect_ratio(ph.corners, ph.image.shape)
    given = pp.estimate_aspect_ratio(ph.corners, ph.image.shape, focal_length=800)
    assert np.isclose(given.ratio, 299 / 149, rtol=1e-6)
    if yaw == 0.0 or pitch == 0.0:  # an edge pair stays parallel: f cannot be estimated
        assert est.focal_source == "assumed" and est.focal_length == 640
        assert abs(est.ratio / (299 / 149) - 1) < 0.1  # approximate with the assumed f
    else:
        assert est.focal_source == "estimated"
        assert np.isclose(est.ratio, 299 / 149, rtol=1e-6)


def test_aspect_ratio_with_noise_is_close():
    ph = scenes.sample_photo("facade")
    rng = np.random.default_rng(0)
    errs = [
        abs(
            pp.estimate_aspect_ratio(ph.corners + rng.normal(0, 0.5, (4, 2)), ph.image.shape).ratio
            / ph.aspect
            - 1
        )
        for _ in range(20)
    ]
    assert np.median(errs) < 0.03


def test_fronto_parallel_needs_no_focal():
    est = pp.estimate_aspect_ratio([[100, 100], [400, 100], [400, 250], [100, 250]], (480, 640))
    assert est.focal_source == "not needed" and np.isclose(est.ratio, 2.0)


def test_rectify_recovers_the_texture(photos):
    ph = photos["painting"]
    tex = scenes.painting_texture()
    th, tw = tex.shape[:2]
    r = pp.rectify_quadrilateral(ph.image, ph.corners, size=(tw, th))
    # H maps the photo corners to the output corners
    assert np.allclose(
        map_points(r.H, ph.corners), [[0, 0], [tw - 1, 0], [tw - 1, th - 1], [0, th - 1]], atol=1e-6
    )
    # H undoes the photographing homography: rect_from_image @ image_from_texture = identity
    M = r.H @ ph.H
    assert np.allclose(M / M[2, 2], np.eye(3), atol=1e-6)
    # content agrees with the texture away from the border (the photo is a resampled, smaller copy)
    inner = (slice(40, th - 40), slice(40, tw - 40))
    err = np.abs(
        cv2.GaussianBlur(r.image, (0, 0), 2).astype(float)
        - cv2.GaussianBlur(tex, (0, 0), 2).astype(float)
    )
    assert np.median(err[inner]) < 12
    # size from the estimated aspect ratio
    auto = pp.rectify_quadrilateral(ph.image, ph.corners)
    h, w = auto.image.shape[:2]
    assert abs(w / h - ph.aspect) < 0.01 and auto.aspect.focal_source == "estimated"


def test_rectify_cv2_and_numpy_same_picture(photos):
    ph = photos["page"]
    a = pp.rectify_quadrilateral(ph.image, ph.corners, size=(200, 283))
    b = pp.rectify_quadrilateral(ph.image, ph.corners, size=(200, 283), method="cv2")
    assert_close_to_cv2_warp(a.image[2:-2, 2:-2], b.image[2:-2, 2:-2])


def test_corner_order_errors_and_reorder(photos):
    ph = photos["page"]
    c = ph.corners
    bowtie = c[[0, 1, 3, 2]]
    with pytest.raises(DegenerateError, match="self-intersecting"):
        pp.rectify_quadrilateral(ph.image, bowtie)
    with pytest.raises(DegenerateError, match="counter-clockwise"):
        pp.rectify_quadrilateral(ph.image, c[::-1])
    shuffled = c[[2, 0, 3, 1]]
    assert np.allclose(pp.order_corners(shuffled), c)
    r = pp.rectify_quadrilateral(ph.image, bowtie, reorder=True, size=(100, 141))
    assert np.allclose(r.corners, c)
    with pytest.raises(DegenerateError, match="collinear"):
        pp.check_quadrilateral([[0, 0], [5, 0], [10, 0], [0, 10]])
    with pytest.raises(DegenerateError, match="not convex"):
        pp.check_quadrilateral([[0, 0], [10, 0], [3, 3], [0, 10]])
    with pytest.raises(CamlabInputError, match="expected 4 corners"):
        pp.check_quadrilateral(np.zeros((3, 2)))
    with pytest.raises(CamlabInputError, match="expected finite values"):
        pp.check_quadrilateral([[0, 0], [1, 0], [1, np.nan], [0, 1]])


@pytest.mark.parametrize("kind", ["page", "painting", "facade"])
def test_find_document(photos, kind):
    ph = photos[kind]
    corners = pp.find_document(ph.image)
    assert np.abs(corners - ph.corners).max() < 4.0


def test_find_document_reports_when_none():
    rng = np.random.default_rng(0)
    flat = np.full((240, 320, 3), 120, np.uint8)
    with pytest.raises(pp.DocumentNotFoundError, match="no edges formed a closed outline"):
        pp.find_document(flat)
    small = flat.copy()
    cv2.rectangle(small, (10, 10), (40, 40), (255, 255, 255), -1)
    with pytest.raises(
        pp.DocumentNotFoundError, match="no convex quadrilateral covering at least 10%"
    ):
        pp.find_document(small)
    disc = flat.copy()
    cv2.circle(disc, (160, 120), 100, (250, 250, 250), -1)
    with pytest.raises(pp.DocumentNotFoundError, match="vertices"):
        pp.find_document(disc + rng.integers(0, 3, disc.shape, dtype=np.uint8))
