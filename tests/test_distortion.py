"""Tests for camlab.distortion: the Brown-Conrady model, its inverse, maps, cross-checks with OpenCV."""

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from camlab import ConvergenceError
from camlab import distortion as D
from camlab._validate import CamlabInputError

K = np.array([[800.0, 0.0, 319.5], [0.0, 790.0, 239.5], [0.0, 0.0, 1.0]])
DISTS = [
    np.array([-0.28, 0.09, 0.0012, -0.0008, -0.01]),  # barrel, wide angle
    np.array([0.12, -0.05, -0.0005, 0.001, 0.0]),  # pincushion
    np.array([-0.1, 0.25, 0.002, 0.002, -0.1]),  # mixed
]
rng = np.random.default_rng(3)
PIX = np.column_stack([rng.uniform(0, 639, 300), rng.uniform(0, 479, 300)])


def _norm(px):
    return np.column_stack([(px[:, 0] - K[0, 2]) / K[0, 0], (px[:, 1] - K[1, 2]) / K[1, 1]])


def test_known_value_radial_and_tangential():
    # x = (0.5, 0.2): r^2 = 0.29, L = 1 - 0.1 * 0.29 = 0.971
    x = D.distort_points([0.5, 0.2], [-0.1, 0, 0.01, 0.02, 0])
    assert np.allclose(
        x,
        [
            0.5 * 0.971 + 2 * 0.01 * 0.1 + 0.02 * (0.29 + 0.5),
            0.2 * 0.971 + 0.01 * (0.29 + 0.08) + 2 * 0.02 * 0.1,
        ],
    )


def test_single_point_keeps_rank_and_batch_matches():
    d = DISTS[0]
    xs = _norm(PIX[:5])
    batch = D.distort_points(xs, d)
    assert D.distort_points(xs[2], d).shape == (2,)
    assert np.array_equal(D.distort_points(xs[2], d), batch[2])
    assert D.undistort_points(batch[2], d).shape == (2,)


@pytest.mark.parametrize("d", DISTS)
def test_distort_matches_cv2_project_points(d):
    Xc = np.column_stack([_norm(PIX) * 2.0, np.full(len(PIX), 2.0)])
    ours = D.distort_pixels(PIX, K, d)
    ref, _ = cv2.projectPoints(Xc.reshape(-1, 1, 3), np.zeros(3), np.zeros(3), K, d)
    assert np.abs(ours - ref.reshape(-1, 2)).max() < 1e-6


@pytest.mark.parametrize("d", DISTS)
def test_undistort_matches_cv2_undistort_points(d):
    distorted = D.distort_pixels(PIX, K, d)
    ours = D.undistort_points(_norm(distorted), d)
    crit = (cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 200, 1e-14)
    src = distorted.reshape(-1, 1, 2)
    if hasattr(cv2, "undistortPointsIter"):  # OpenCV 4.x: the variant that takes stopping criteria
        ref = cv2.undistortPointsIter(src, K, d, None, None, crit).reshape(-1, 2)
    else:  # OpenCV 5.x folded it into undistortPoints
        ref = cv2.undistortPoints(src, K, d, None, None, criteria=crit).reshape(-1, 2)
    assert np.abs(ours - ref).max() * 800 < 1e-4  # px
    assert (
        np.abs(ours - _norm(PIX)).max() * 800 < 1e-8
    )  # we invert exactly; OpenCV's fixed point is looser


@pytest.mark.parametrize("d", DISTS)
def test_undistort_map_matches_cv2_init_undistort_rectify_map(d):
    new_K = K.copy()
    new_K[:2, :2] *= 0.8
    ours = D.undistort_map(K, d, (640, 480), new_K)
    mu, mv = cv2.initUndistortRectifyMap(K, d, None, new_K, (640, 480), cv2.CV_32FC1)
    assert ours.map_u.shape == (480, 640) and ours.map_u.dtype == np.float32
    assert np.abs(ours.map_u - mu).max() < 2e-3 and np.abs(ours.map_v - mv).max() < 2e-3


@pytest.mark.parametrize("d", DISTS)
def test_distort_map_inverts_undistort_map(d):
    m = D.distort_map(K, d, (640, 480), step=4)
    ideal = np.column_stack([m.map_u.ravel(), m.map_v.ravel()]).astype(float)
    back = D.distort_pixels(ideal, K, d)
    u, v = np.meshgrid(np.arange(640.0), np.arange(480.0))
    err = np.hypot(back[:, 0] - u.ravel(), back[:, 1] - v.ravel())
    assert err.max() < 0.01  # the coarse-grid interpolation
    exact = D.distort_map(K, d, (64, 48), step=1)
    assert exact.map_u.shape == (48, 64)


def test_undistort_image_straightens_a_distorted_line():
    d = DISTS[0]
    img = np.zeros((480, 640), np.uint8)
    ys = D.distort_pixels(np.column_stack([np.arange(0, 640, 0.25), np.full(2560, 60.0)]), K, d)
    ok = (ys[:, 1] >= 0) & (ys[:, 1] < 480)
    img[np.rint(ys[ok, 1]).astype(int), np.rint(ys[ok, 0]).astype(int)] = 255
    out = D.undistort_image(img, K, d)
    rows = np.nonzero(out[:, 100:540].max(axis=1) > 60)[0]
    assert rows.min() >= 58 and rows.max() <= 62  # the bowed line is straight at v = 60 again


@settings(max_examples=60, deadline=None)
@given(
    st.floats(-0.4, 0.3),
    st.floats(-0.1, 0.1),
    st.floats(-0.003, 0.003),
    st.floats(-0.003, 0.003),
    st.floats(0, 1),
    st.floats(0, 2 * np.pi),
)
def test_round_trip_within_valid_field_of_view(k1, k2, p1, p2, frac, angle):
    d = [k1, k2, p1, p2, 0.0]
    r = frac * min(0.75, 0.9 * D.max_valid_radius(d))
    x = np.array([r * np.cos(angle), r * np.sin(angle)])
    back = D.undistort_points(D.distort_points(x, d), d)
    assert np.abs(back - x).max() * 800 < 1e-6


def test_jacobian_matches_finite_differences():
    d, x = DISTS[2], np.array([0.31, -0.22])
    J = D.distortion_jacobian(x, d)
    eps = 1e-7
    num = np.column_stack(
        [
            (D.distort_points(x + e, d) - D.distort_points(x - e, d)) / (2 * eps)
            for e in np.eye(2) * eps
        ]
    )
    assert np.allclose(J, num, atol=1e-7)


def test_undistort_reports_non_convergence_beyond_the_fold():
    d = [-0.5, 0, 0, 0, 0]  # r L(r) peaks at r = sqrt(2/3): distorted radius 0.544 at most
    assert D.max_valid_radius(d) == pytest.approx(np.sqrt(2 / 3), abs=1e-4)
    with pytest.raises(
        ConvergenceError, match=r"1 of 2 points did not converge.*valid field of view"
    ):
        D.undistort_points([[0.1, 0.0], [0.7, 0.0]], d)


def test_classification():
    assert (
        D.classify_distortion(DISTS[0]) == "barrel + tangential"
    )  # p1, p2 shift corners by ~2 px at f = 800
    assert D.classify_distortion(DISTS[1]) == "pincushion + tangential"
    assert D.classify_distortion([0.12, -0.05, 0, 0, 0]) == "pincushion"
    assert D.classify_distortion([-0.3, 0.6, 0, 0, 0]) == "mustache"
    assert D.classify_distortion(None) == "none"
    assert (
        D.classify_distortion([0, 0, 0.01, 0, 0]) == "tangential"
    )  # the grid is bent, so not "none"
    assert D.classify_distortion([0, 0, 0, -0.01, 0]) == "tangential"
    assert D.classify_distortion([0.2, 0, 0.002, 0, 0]) == "pincushion + tangential"
    assert D.classify_distortion([-0.3, 0, 1e-7, 0, 0]) == "barrel"  # below tol: invisible


def test_no_distortion_is_identity():
    xs = _norm(PIX)
    assert np.array_equal(D.distort_points(xs, None), xs)
    assert np.array_equal(D.undistort_points(xs, [0, 0, 0, 0]), xs)


def test_bad_inputs():
    with pytest.raises(CamlabInputError, match=r"dist: expected 4 or 5 coefficients"):
        D.distort_points([0, 0], [0.1, 0.2])
    with pytest.raises(CamlabInputError, match=r"points: expected \(N, 2\) points"):
        D.distort_points([[0, 0, 1]], None)
    with pytest.raises(CamlabInputError, match=r"dist: expected finite values"):
        D.distort_points([0, 0], [np.nan, 0, 0, 0, 0])
    with pytest.raises(CamlabInputError, match=r"K: expected an intrinsic matrix"):
        D.undistort_map(np.eye(3) * -1, None, (4, 4))
    with pytest.raises(CamlabInputError, match=r"size: expected \(width, height\)"):
        D.undistort_map(K, None, 640)
    with pytest.raises(CamlabInputError, match=r"image: expected an image of shape \(H, W\)"):
        D.undistort_image(np.zeros(5), K, None)
    with pytest.raises(CamlabInputError, match=r"step: expected an integer >= 1"):
        D.distort_map(K, None, (8, 8), step=0)
