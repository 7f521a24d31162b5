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
    # turned in its plane (roll 30 deg) it is still a similarity of the rectangle: right angles, ratio 2
    c, s = np.cos(np.pi / 6), np.sin(np.pi / 6)
    turned = np.array([[0, 0], [300, 0], [300, 150], [0, 150]]) @ [[c, s], [-s, c]] + [200, 100]
    est = pp.estimate_aspect_ratio(turned, (480, 640), focal_length=900.0)
    assert est.focal_source == "not needed" and np.isclose(est.ratio, 2.0)


@pytest.mark.parametrize("shear", [50.0, 3.0])
def test_sheared_parallelogram_is_no_rectangle(shear):
    """Both edge pairs parallel means a fronto-parallel plane: its photo keeps right angles."""
    q = [[200, 100], [450, 100], [450 + shear, 380], [200 + shear, 380]]  # 79.9 and 89.4 deg
    with pytest.raises(DegenerateError, match=r"parallel in the image.*meet at (79\.9|89\.4) deg"):
        pp.estimate_aspect_ratio(q, (480, 640))
    with pytest.raises(DegenerateError, match="no rectangle projects"):
        pp.rectify_quadrilateral(np.zeros((480, 640)), q)
    nearly = [
        [200, 100],
        [450, 100],
        [451, 380],
        [201, 380],
    ]  # 89.8 deg: within the 0.5 deg tolerance
    assert pp.estimate_aspect_ratio(nearly, (480, 640)).focal_source == "not needed"


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


# --------------------------------------------------------------------------- metric rectification from right angles


def _similarity_part(M):
    """M / M[2, 2] if it is a similarity (no projective row, A A^T = s^2 I), else None."""
    M = M / M[2, 2]
    A = M[:2, :2]
    s2 = np.trace(A @ A.T) / 2
    if np.allclose(M[2, :2], 0, atol=1e-9 * abs(M).max()) and np.allclose(
        A @ A.T, s2 * np.eye(2), rtol=0, atol=1e-7 * s2
    ):
        return M
    return None


@pytest.fixture(scope="module")
def synthetic_grid():
    """A 6 x 9 grid of 30 mm squares photographed obliquely by a known plane homography G."""
    G = np.array([[9.0, 2.5, 180.0], [-1.2, 7.5, 90.0], [0.012, 0.009, 1.0]])
    plane = np.stack(np.meshgrid(np.arange(9.0), np.arange(6.0)), axis=-1) * 30.0  # (6, 9, 2) mm
    return G, map_points(G, plane.reshape(-1, 2)).reshape(6, 9, 2)


def test_metric_rectification_recovers_the_plane_up_to_a_similarity(synthetic_grid):
    G, grid = synthetic_grid
    L, M = pp.square_grid_right_angles(grid)
    r = pp.metric_rectification(L, M)
    S = _similarity_part(r.H @ G)  # rectified <- plane
    assert S is not None, (r.H @ G) / (r.H @ G)[2, 2]
    assert np.linalg.det(S[:2, :2]) > 0  # not mirrored
    assert r.residual < 1e-9
    # the dual conic is the image of C*inf = diag(1, 1, 0), up to scale
    want = G @ np.diag([1.0, 1.0, 0.0]) @ G.T
    assert np.allclose(r.C_star, want / np.linalg.norm(want), atol=1e-9)
    assert np.allclose(pp.dual_conic_from_orthogonal_lines(L, M), r.C_star, atol=1e-9)
    # it agrees with camlab.projective.map_dual_conic and with the circular points
    from camlab.projective import DUAL_CONIC_AT_INFINITY, map_dual_conic

    C = map_dual_conic(r.H, r.C_star)
    assert np.allclose(C / C[0, 0], DUAL_CONIC_AT_INFINITY, atol=1e-9)


def test_metric_rectification_with_noise_stays_close(synthetic_grid):
    G, grid = synthetic_grid
    rng = np.random.default_rng(3)
    L, M = pp.square_grid_right_angles(grid + rng.normal(0, 0.3, grid.shape))
    S = pp.metric_rectification(L, M).H @ G
    S = S / S[2, 2]
    A = S[:2, :2] / np.sqrt(abs(np.linalg.det(S[:2, :2])))
    assert np.abs(A @ A.T - np.eye(2)).max() < 0.02
    assert np.abs(S[2, :2]).max() < 1e-4


def test_metric_rectification_rejects_one_direction_and_bad_input(synthetic_grid):
    G, grid = synthetic_grid
    L, M = pp.square_grid_right_angles(grid)
    with pytest.raises(DegenerateError, match="too few directions"):
        pp.metric_rectification(
            np.r_[L[:4], L[:4]], np.r_[M[:4], M[[1, 0, 3, 2]]]
        )  # rows vs columns only
    with pytest.raises(CamlabInputError, match=r"N >= 5"):
        pp.metric_rectification(L[:4], M[:4])
    with pytest.raises(CamlabInputError, match=r"lines_m: expected \(N, 3\)"):
        pp.metric_rectification(L, M[:, :2])
    with pytest.raises(CamlabInputError, match="grid: expected"):
        pp.square_grid_right_angles(grid.reshape(-1, 2))
    assert np.array_equal(L, pp.square_grid_right_angles(grid)[0])  # input untouched, deterministic


def test_metric_rectification_refuses_noisy_rows_against_columns(synthetic_grid):
    """Noise makes the one-direction rows full rank; the missing 6th-vs-5th gap still flags it."""
    G, grid = synthetic_grid
    noisy = grid + np.random.default_rng(5).normal(0, 0.5, grid.shape)
    from camlab.widgets.perspective_metric import rows_and_columns

    L, M = rows_and_columns(noisy)
    s = np.linalg.svd(pp.dual_conic_rows(L, M)[0], compute_uv=False)
    assert s[4] > 1e-8 * s[0] and s[5] > pp.NULL_GAP * s[4]  # not exactly degenerate, but no gap
    with pytest.raises(DegenerateError, match="too few directions.*noise would pick"):
        pp.metric_rectification(L, M)
    L, M = pp.square_grid_right_angles(noisy)  # with the diagonals: a clear gap, accepted
    s = np.linalg.svd(pp.dual_conic_rows(L, M)[0], compute_uv=False)
    assert s[5] < 0.01 * s[4]
    assert pp.metric_rectification(L, M).residual < 0.05


def test_metric_rectification_of_a_real_chessboard_photo():
    """OpenCV's left02 (Apache-2.0): the rectified corners fit a square grid to 4% of a square."""
    from camlab.data import load_photo

    image = load_photo("calib_left02", gray=True)
    found, corners = cv2.findChessboardCorners(image, (9, 6))
    assert found
    corners = cv2.cornerSubPix(image, corners, (5, 5), (-1, -1), (3, 30, 0.01)).reshape(6, 9, 2)
    r = pp.metric_rectification(*pp.square_grid_right_angles(corners))
    q = map_points(r.H, corners.reshape(-1, 2))
    board = np.stack(np.meshgrid(np.arange(9.0), np.arange(6.0)), axis=-1).reshape(-1, 2)
    # the best similarity board -> rectified, as complex numbers: q = a z + b
    z, w = board @ [1, 1j], q @ [1, 1j]
    (a, b), *_ = np.linalg.lstsq(np.c_[z, np.ones_like(z)], w, rcond=None)
    rms = np.sqrt(np.mean(np.abs(a * z + b - w) ** 2)) / abs(a)
    assert rms < 0.04  # lens distortion (uncorrected) is most of it
    assert r.residual < 0.01


@pytest.mark.parametrize(
    "kind, pose", [("facade", {}), ("page", {}), ("facade", {"pitch": -0.5, "yaw": 0.0})]
)
def test_affine_rectification_sends_the_vanishing_line_to_infinity(kind, pose):
    """H_P makes opposite edges parallel; an affinity then gives OpenCV's rectifying H."""
    import cv2

    from camlab.projective import map_lines

    photo = scenes.sample_photo(kind, **pose)
    H_P = pp.affine_rectification(photo.corners)
    c = np.c_[photo.corners, np.ones(4)]
    line = np.cross(
        np.cross(np.cross(c[0], c[1]), np.cross(c[3], c[2])),
        np.cross(np.cross(c[0], c[3]), np.cross(c[1], c[2])),
    )
    sent = map_lines(H_P, line)
    assert np.allclose(sent[:2] / sent[2], 0, atol=1e-12)
    par = map_points(H_P, photo.corners)
    assert np.allclose(par[1] - par[0], par[2] - par[3]) and np.allclose(
        par[3] - par[0], par[2] - par[1]
    )
    target = np.array([[0, 0], [299, 0], [299, 199], [0, 199]], float)
    A = np.linalg.lstsq(np.c_[par[:3], np.ones(3)], target[:3], rcond=None)[0].T
    H_cv = cv2.getPerspectiveTransform(np.float32(photo.corners), np.float32(target))
    from camlab.homography import same_homography

    assert same_homography(np.vstack([A, [0, 0, 1]]) @ H_P, H_cv, tol=1e-5)
    assert (c @ H_P[2] > 0).all()  # the corners keep w > 0


def test_affine_rectification_refuses_a_bow_tie():
    corners = scenes.sample_photo("page").corners[[0, 1, 3, 2]]
    with pytest.raises(pp.DegenerateError, match="corners"):
        pp.affine_rectification(corners)
