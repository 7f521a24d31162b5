"""Tomasi-Kanade factorisation against the cameras and points that made the tracks."""

import numpy as np
import pytest

from camlab import affine as af
from camlab import camera as cm
from camlab._validate import CamlabInputError
from camlab.factorization import affine_factorization

K = cm.intrinsic_matrix(800, 800, 319.5, 239.5)


def views(distance, count=8, affine=True):
    """`count` cameras `distance` m from the origin, 5 degrees apart in azimuth, zooming so the
    scene keeps its size; their weak-perspective approximations about the origin if `affine`."""
    scale = np.diag([distance / 4, distance / 4, 1.0])
    out = []
    for k in range(count):
        eye = cm.orbit_eye(np.radians(5.0 * k), np.radians(15.0), distance)
        cam = cm.Camera.look_at(eye, [0.0, 0.0, 0.0], K=scale @ K)
        out.append(af.affine_approximation(cam, [0.0, 0.0, 0.0]) if affine else cam.P)
    return out


def tracks_of(Ps, X, rng=None, sigma=0.0):
    W = np.stack([cm.project_points(P, X) for P in Ps])
    return W if rng is None else W + rng.normal(0, sigma, W.shape)


def test_exact_affine_tracks_are_recovered_up_to_an_affine_map():
    rng = np.random.default_rng(0)
    X = rng.uniform(-1, 1, (40, 3))
    W = tracks_of(views(30.0), X)
    fit = affine_factorization(W)
    assert fit.rms < 1e-9 and fit.singular_values[3] < 1e-9 * fit.singular_values[0]
    reprojected = np.stack([cm.project_points(P, fit.points) for P in fit.cameras])
    assert np.abs(reprojected - W).max() < 1e-9
    truth = X - X.mean(axis=0)
    A = np.linalg.lstsq(fit.points, truth, rcond=None)[0]  # the affine ambiguity
    assert np.abs(fit.points @ A - truth).max() < 1e-9
    assert np.allclose(fit.cameras[:, 2], [0, 0, 0, 1])


def test_noise_leaves_the_fourth_singular_value_at_the_noise_level():
    rng = np.random.default_rng(1)
    X = rng.uniform(-1, 1, (200, 3))
    fit = affine_factorization(tracks_of(views(30.0), X, rng, sigma=0.5))
    # 2F x N = 16 x 200 entries; the rank-3 fit spends 3 (2F + N - 3) of them: the rest is noise
    kept = 1 - 3 * (16 + 200 - 3) / (16 * 200)
    assert abs(fit.rms / (0.5 * np.sqrt(kept)) - 1) < 0.05
    assert fit.singular_values[3] < 0.5 * np.sqrt(200) * 1.5  # about sigma sqrt(N) per direction


def test_close_perspective_views_are_not_rank_3():
    rng = np.random.default_rng(2)
    X = rng.uniform(-1, 1, (200, 3))
    affine = affine_factorization(tracks_of(views(30.0), X, rng, sigma=0.5))
    close = affine_factorization(tracks_of(views(3.0, affine=False), X, rng, sigma=0.5))
    assert close.singular_values[3] > 10 * affine.singular_values[3] and close.rms > 5 * affine.rms


@pytest.mark.parametrize("shape", [(1, 10, 2), (3, 3, 2), (3, 10, 3), (10, 2)])
def test_bad_shapes_name_the_argument(shape):
    with pytest.raises(CamlabInputError, match=r"tracks: expected \(m, N, 2\)"):
        affine_factorization(np.zeros(shape))


def test_nan_is_refused():
    W = np.zeros((3, 10, 2))
    W[1, 4, 0] = np.nan
    with pytest.raises(CamlabInputError, match="tracks"):
        affine_factorization(W)
