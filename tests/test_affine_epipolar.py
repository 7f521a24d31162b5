"""The affine fundamental matrix against the cameras that made the matches and against OpenCV."""

import cv2
import numpy as np
import pytest

from camlab import affine as af
from camlab import camera as cm
from camlab import epipolar as ep
from camlab._validate import CamlabInputError, DegenerateError
from camlab.affine_epipolar import affine_epipolar_test, estimate_affine_fundamental

K = cm.intrinsic_matrix(800, 800, 319.5, 239.5)


def cameras(distance, azimuth_deg, affine):
    """Two cameras `distance` m from the origin, turned `azimuth_deg` apart about the vertical;
    as weak-perspective approximations about the origin if `affine`."""
    out = []
    for az in (0.0, azimuth_deg):
        cam = cm.Camera.look_at(
            cm.orbit_eye(np.radians(az), np.radians(10.0), distance),
            [0.0, 0.0, 0.0],
            K=K.copy() * [[distance / 4], [distance / 4], [1]],
        )
        out.append(af.affine_approximation(cam, [0.0, 0.0, 0.0]) if affine else cam.P)
    return out


def two_facades(rng, n=400):
    """Points on two 4 m facades at right angles (a building's corner), with depth in the view."""
    s = rng.uniform(0, 4, (n, 2))
    half = n // 2
    return np.r_[
        np.c_[s[:half, 0], np.zeros(half), s[:half, 1]],
        np.c_[np.zeros(n - half), s[half:, 0], s[half:, 1]],
    ] - [
        1.0,
        1.0,
        2.0,
    ]


def matches(P1, P2, X, rng=None, sigma=0.0):
    x1, x2 = cm.project_points(P1, X), cm.project_points(P2, X)
    if rng is not None:
        x1, x2 = x1 + rng.normal(0, sigma, x1.shape), x2 + rng.normal(0, sigma, x2.shape)
    return x1, x2


def same_up_to_scale(F, G):
    F, G = F / np.linalg.norm(F), G / np.linalg.norm(G)
    return min(np.abs(F - G).max(), np.abs(F + G).max())


def test_exact_matches_of_two_affine_cameras_give_their_fundamental_matrix():
    rng = np.random.default_rng(0)
    P1, P2 = cameras(30.0, 8.0, affine=True)
    x1, x2 = matches(P1, P2, rng.uniform(-1, 1, (50, 3)))
    fit = estimate_affine_fundamental(x1, x2)
    assert fit.rms < 1e-9 and np.abs(fit.residuals).max() < 1e-9
    assert np.allclose(fit.F[:2, :2], 0) and np.isclose(
        np.linalg.norm(fit.F[[0, 1, 2, 2], [2, 2, 0, 1]]), 1
    )
    assert same_up_to_scale(fit.F, ep.fundamental_from_cameras(P1, P2)) < 1e-9


def test_agrees_with_opencv_eight_point_on_affine_views():
    rng = np.random.default_rng(1)
    P1, P2 = cameras(30.0, 12.0, affine=True)
    x1, x2 = matches(P1, P2, rng.uniform(-1, 1, (60, 3)))
    F_cv, _ = cv2.findFundamentalMat(x1, x2, cv2.FM_8POINT)
    assert same_up_to_scale(estimate_affine_fundamental(x1, x2).F, F_cv) < 1e-6


def test_residual_is_the_pixel_noise_per_coordinate():
    """The residual is the distance from a hyperplane of R^4: isotropic noise sigma in each of
    the four coordinates puts sigma along its normal."""
    rng = np.random.default_rng(2)
    P1, P2 = cameras(30.0, 8.0, affine=True)
    x1, x2 = matches(P1, P2, rng.uniform(-1, 1, (4000, 3)), rng, sigma=0.7)
    assert abs(estimate_affine_fundamental(x1, x2).rms / 0.7 - 1) < 0.05


def test_swapping_the_images_transposes_F():
    rng = np.random.default_rng(3)
    P1, P2 = cameras(30.0, 8.0, affine=True)
    x1, x2 = matches(P1, P2, rng.uniform(-1, 1, (100, 3)), rng, sigma=0.5)
    forward, backward = estimate_affine_fundamental(x1, x2), estimate_affine_fundamental(x2, x1)
    assert same_up_to_scale(forward.F, backward.F.T) < 1e-12
    assert np.isclose(forward.rms, backward.rms)


def test_the_test_accepts_affine_cameras_that_see_parallax():
    """Two facades seen by two affine cameras: the affinity-vs-homography test can fire on their
    parallax, this one must not (F_A models parallax)."""
    rng = np.random.default_rng(4)
    P1, P2 = cameras(30.0, 2.0, affine=True)
    statistics = []
    for _ in range(20):
        x1, x2 = matches(P1, P2, two_facades(rng), rng, sigma=1.0)
        statistics.append(affine_epipolar_test(x1, x2))
    rejected = sum(t.statistic > t.level for t in statistics)
    assert rejected <= 2  # a 1 % test: 0.2 false alarms expected in 20
    assert all(t.statistic >= 0 and t.rms_general <= t.rms_affine for t in statistics)
    assert 0.4 < np.median([t.statistic for t in statistics]) < 1.5  # F(3, N - 7): about 1


def test_the_test_rejects_a_close_perspective_pair():
    rng = np.random.default_rng(5)
    P1, P2 = cameras(5.0, 8.0, affine=False)
    x1, x2 = matches(P1, P2, two_facades(rng), rng, sigma=1.0)
    test = affine_epipolar_test(x1, x2)
    assert test.statistic > 10 * test.level and test.rms_affine > 1.5 * test.rms_general
    assert test.count == 400 and abs(test.rms_general - 1.0) < 0.15


def test_one_plane_seen_affinely_is_degenerate():
    rng = np.random.default_rng(6)
    P1, P2 = cameras(30.0, 8.0, affine=True)
    plane = np.c_[rng.uniform(-1, 1, (30, 2)), np.zeros(30)]
    with pytest.raises(DegenerateError, match="span fewer than three"):
        estimate_affine_fundamental(*matches(P1, P2, plane))


@pytest.mark.parametrize(
    "x1, x2, message",
    [
        (np.zeros((3, 2)), np.zeros((3, 2)), "N >= 4"),
        (np.zeros((5, 2)), np.zeros((4, 2)), "same number"),
        (np.zeros((5, 3)), np.zeros((5, 3)), r"\(N, 2\)"),
    ],
)
def test_bad_input_names_the_argument(x1, x2, message):
    with pytest.raises(CamlabInputError, match=message):
        estimate_affine_fundamental(x1, x2)
