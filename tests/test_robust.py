"""The robust driver (camlab.robust) with its two plug-ins, on synthetic data and on real photo pairs vs OpenCV."""

from __future__ import annotations

from functools import cache

import cv2
import numpy as np
import pytest

from camlab import robust
from camlab._validate import CamlabInputError, DegenerateError
from camlab.data import load_photo
from camlab.epipolar import ransac_fundamental_matrix
from camlab.features import detect_features, match_features
from camlab.homography import HomographyModel, ransac_homography, symmetric_transfer_error
from camlab.projective import map_points


@cache
def _matches(a: str, b: str, max_features: int, ratio: float) -> tuple[np.ndarray, np.ndarray]:
    m = match_features(
        detect_features(load_photo(a), max_features=max_features),
        detect_features(load_photo(b), max_features=max_features),
        ratio,
    )
    return m.src, m.dst


def _msac(H, src, dst, t=3.0) -> float:
    return float(np.sum(np.minimum(symmetric_transfer_error(H, src, dst), t) ** 2))


def _synthetic(outliers: float, n: int = 300, seed: int = 0):
    rng = np.random.default_rng(seed)
    H = np.array([[0.9, 0.1, 40.0], [-0.05, 1.1, -10.0], [3e-4, 2e-4, 1.0]])
    src = rng.uniform(0, 640, (n, 2))
    dst = map_points(H, src) + rng.normal(0, 0.5, (n, 2))
    bad = rng.random(n) < outliers
    dst[bad] = rng.uniform(0, 640, (bad.sum(), 2))
    return src, dst, ~bad


def test_same_inliers_for_every_seed_at_70_percent_outliers():
    src, dst, good = _synthetic(0.7)
    masks = [ransac_homography(src, dst, 3.0, rng=seed).inliers for seed in range(10)]
    assert all(np.array_equal(m, masks[0]) for m in masks)
    assert (masks[0] & good).sum() >= 0.97 * good.sum() and (masks[0] & ~good).sum() <= 3


def test_local_optimisation_never_raises_the_cost():
    src, dst, _ = _synthetic(0.5, seed=3)
    model = HomographyModel(src, dst)
    rng = np.random.default_rng(0)
    idx = np.flatnonzero(_synthetic(0.5, seed=3)[2])[:4][None]
    H4, ok = model.minimal(idx)
    assert ok[0]
    raw = float(robust.msac_cost(model.residuals(H4)[0], 3.0))
    H, cost = robust.local_optimisation(model, H4[0], 3.0, rng)
    assert cost < raw
    assert cost == pytest.approx(float(robust.msac_cost(model.residuals(H[None])[0], 3.0)))


def test_local_optimisation_beats_plain_msac_in_cost():
    src, dst, _ = _synthetic(0.6, seed=4)
    lo = robust.ransac(HomographyModel(src, dst), 3.0, rng=1)
    plain = robust.ransac(HomographyModel(src, dst), 3.0, rng=1, local_optimise=False)
    assert lo.cost <= plain.cost


def test_marginal_msac_cost_is_the_msac_loss_averaged_over_cuts():
    # The closed form against the average of min(e^2, tau^2) over 20001 cuts tau on (0, 2t].
    e, t = np.array([0.0, 0.4, 1.0, 2.9, 3.0, 4.5, 6.0, 50.0]), 3.0
    taus = (np.arange(20000) + 0.5) * (2 * t / 20000)
    numeric = np.minimum(e[:, None] ** 2, taus[None] ** 2).mean(axis=1)
    closed = [float(robust.marginal_msac_cost(x[None], t)) for x in e]
    assert np.allclose(closed, numeric, rtol=1e-6, atol=1e-8)
    # half an outlier at the threshold, 0.16 of one at t / 2 (the module docstring's numbers)
    outlier = float(robust.marginal_msac_cost(np.array([2 * t]), t))
    assert outlier == pytest.approx(4 * t**2 / 3)
    assert float(robust.marginal_msac_cost(np.array([t]), t)) / outlier == pytest.approx(0.5)
    assert float(robust.marginal_msac_cost(np.array([t / 2]), t)) / outlier == pytest.approx(
        0.15625
    )


def test_loss_is_checked_and_marginal_selectable():
    src, dst, _ = _synthetic(0.3)
    with pytest.raises(CamlabInputError, match="loss: expected one of"):
        robust.ransac(HomographyModel(src, dst), 3.0, rng=0, loss="magsac")
    fit = robust.ransac(HomographyModel(src, dst), 3.0, rng=0)
    assert fit.cost == pytest.approx(float(robust.msac_cost(fit.residuals, 3.0)))
    fit = robust.ransac(HomographyModel(src, dst), 3.0, rng=0, loss="marginal")
    assert fit.cost == pytest.approx(float(robust.marginal_msac_cost(fit.residuals, 3.0)))


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"threshold": "3"}, "threshold"),
        ({"threshold": -1}, "threshold"),
        ({"confidence": 1.5}, "confidence"),
        ({"confidence": None}, "confidence"),
        ({"max_iters": "many"}, "max_iters"),
        ({"max_iters": 2.5}, "max_iters"),
        ({"max_iters": 0}, "max_iters"),
    ],
)
def test_driver_settings_are_checked(kwargs, match):
    src, dst, _ = _synthetic(0.2)
    with pytest.raises(CamlabInputError, match=match):
        ransac_homography(src, dst, **kwargs)


# --------------------------------------------------------------------------- real photographs


@pytest.mark.parametrize(
    "pair, max_features, ratio",
    [
        (
            ("building_1", "building_3"),
            300,
            0.9,
        ),  # few matches, few inliers, large viewpoint change
        (("building_2", "building_3"), 300, 0.9),
        (("building_1", "building_2"), 2500, 0.8),
    ],
)
def test_homography_on_real_pairs_is_as_good_as_opencv_and_steady(pair, max_features, ratio):
    src, dst = _matches(*pair, max_features, ratio)
    ours = [ransac_homography(src, dst, 3.0, rng=seed).H for seed in range(10)]
    counts = np.array([(symmetric_transfer_error(H, src, dst) < 3).sum() for H in ours])
    costs = np.array([_msac(H, src, dst) for H in ours])
    cv = [cv2.findHomography(src, dst, m, 3.0)[0] for m in (cv2.RANSAC, cv2.USAC_MAGSAC)]
    cv_counts = [(symmetric_transfer_error(H, src, dst) < 3).sum() for H in cv]
    cv_cost = min(_msac(H, src, dst) for H in cv)
    # Every seed within 5 % of OpenCV's better inlier count and its MSAC cost, and seeds agree.
    assert counts.min() >= 0.95 * max(cv_counts), (counts, cv_counts)
    assert np.median(costs) <= 1.05 * cv_cost, (costs, cv_cost)
    assert counts.max() - counts.min() <= max(2, 0.05 * np.median(counts)), counts


@pytest.mark.parametrize(
    "pair, max_features, ratio",
    [(("building_2", "building_1"), 400, 0.85), (("building_3", "building_1"), 300, 0.85)],
)
def test_worst_seed_on_hard_real_pairs_keeps_up_with_magsac(pair, max_features, ratio):
    # Wide-baseline pairs of a non-planar building, 65-122 matches: MSAC at t prefers, for
    # some seeds, a tight fit to fewer pairs (79 of 122 at 0.86 px RMS, not 94 at 1.46 px);
    # the marginalised score keeps every seed within 5 % of the better of OpenCV's RANSAC
    # and MAGSAC (median inlier count over the same seeds).
    src, dst = _matches(*pair, max_features, ratio)

    def count(H):
        return int((symmetric_transfer_error(H, src, dst) < 3).sum())

    cv = []
    for method in (cv2.RANSAC, cv2.USAC_MAGSAC):
        runs = []
        for seed in range(10):
            cv2.setRNGSeed(seed)
            runs.append(count(cv2.findHomography(src, dst, method, 3.0)[0]))
        cv.append(np.median(runs))
    ours = [
        count(ransac_homography(src, dst, 3.0, rng=seed, loss="marginal").H) for seed in range(10)
    ]
    assert min(ours) >= 0.95 * max(cv), (ours, cv)
    msac = [
        count(robust.ransac(HomographyModel(src, dst), 3.0, rng=seed).model) for seed in range(10)
    ]
    assert min(msac) < min(ours), (msac, ours)  # what the marginalised score fixes


def test_fundamental_on_a_real_stereo_pair_matches_magsac():
    x1, x2 = _matches("walls_left", "walls_right", 2500, 0.8)
    counts = [
        int(ransac_fundamental_matrix(x1, x2, 1.0, rng=seed).inliers.sum()) for seed in range(5)
    ]
    magsac = int(cv2.findFundamentalMat(x1, x2, cv2.USAC_MAGSAC, 1.0, 0.999)[1].sum())
    assert min(counts) >= 0.98 * magsac and max(counts) - min(counts) <= 3, (counts, magsac)


@pytest.mark.parametrize(
    "estimator, args",
    [
        (ransac_fundamental_matrix, (1.0,)),
        (ransac_homography, (3.0,)),
    ],
)
def test_all_wrong_real_matches_give_too_few_inliers(estimator, args):
    x1, x2 = _matches("walls_left", "walls_right", 2500, 0.8)
    wrong = x2[np.random.default_rng(0).permutation(len(x2))]
    with pytest.raises(DegenerateError, match="too few inliers"):
        estimator(x1, wrong, *args, rng=0)
    # OpenCV returns a model on the same matches: it does not test for chance.
    assert cv2.findFundamentalMat(x1, wrong, cv2.FM_RANSAC, 1.0, 0.999)[1] is not None


# --------------------------------------------------------------------------- the fast paths


def test_homography_model_fast_paths_equal_the_plain_ones():
    """The batched solves equal the textbook ones: minimal samples against an SVD per sample
    (estimate_homography on the 4 pairs), fit_many against fit one set at a time."""
    from camlab.homography import estimate_homography, normalise_homography

    src, dst, good = _synthetic(0.3, n=120, seed=5)
    model = HomographyModel(src, dst)
    rng = np.random.default_rng(2)
    idx = np.array([rng.choice(120, 4, replace=False) for _ in range(40)])
    H, ok = model.minimal(idx)
    assert ok.sum() > 20
    for k in np.flatnonzero(ok):
        # the 4-point DLT by SVD (the last right singular vector), in pixels
        expected = estimate_homography(src[idx[k]], dst[idx[k]])
        got = normalise_homography(H[k])
        assert np.allclose(got, expected, rtol=1e-6, atol=1e-9), k
    masks = np.zeros((3, 120), bool)
    masks[0] = good
    masks[1, :60] = True
    masks[2, ::2] = good[::2]
    batched, usable = model.fit_many(masks)
    assert usable.all()
    for row, H_b in zip(masks, batched, strict=True):
        one = model.fit(np.flatnonzero(row))
        assert np.allclose(H_b * np.sign(H_b[2, 2]), one * np.sign(one[2, 2]), atol=1e-10)
    # a sample with three collinear points is skipped, its model NaN
    line = np.array([[0, 1, 2, 3]])
    flat = HomographyModel(np.array([[0, 0], [1, 1], [2, 2], [0, 5.0]] + [[3, 7.0]]), src[:5])
    assert not flat.minimal(line).usable[0] and np.isnan(flat.minimal(line).models[0]).all()


def test_batched_scoring_equals_one_model_at_a_time():
    src, dst, _ = _synthetic(0.3, n=200, seed=6)
    model = HomographyModel(src, dst)
    H, ok = model.minimal(np.random.default_rng(3).integers(0, 200, (30, 4)))
    H = H[ok]
    together = robust.marginal_msac_cost(model.residuals(H), 3.0)
    alone = [float(robust.marginal_msac_cost(model.residuals(h[None])[0], 3.0)) for h in H]
    assert np.allclose(together, alone, rtol=1e-12)
    assert np.allclose(
        model.residuals(H[:1])[0], symmetric_transfer_error(H[0], src, dst), rtol=1e-12
    )


def test_null_vectors_fall_back_to_the_svd_on_a_singular_system():
    from camlab.homography.estimation import _null_vectors

    A = np.random.default_rng(7).normal(size=(3, 8, 9))
    A[1, 7] = 0.0  # rank 7: the 8 x 8 solve fails, the whole batch takes the SVD
    h, ok = _null_vectors(A)
    assert ok.tolist() == [True, False, True]
    assert np.abs(np.einsum("bij,bj->bi", A, h)[ok]).max() < 1e-12
    assert np.allclose(np.linalg.norm(h, axis=1), 1.0)
    h_fast, ok_fast = _null_vectors(A[[0, 2]])  # the solve path gives the same unit vectors
    assert ok_fast.all() and np.allclose(np.abs((h_fast * h[[0, 2]]).sum(axis=1)), 1.0)


def test_chance_test_pairing_equals_mapping_every_pair():
    """HomographyModel maps each point once for the chance test's 3N shuffled pairs; the errors
    equal the plain per-pair ones, inf where a point maps to infinity."""
    from camlab.homography.estimation import _columns, _sym_err_batch

    src, dst, _ = _synthetic(0.3, n=150, seed=8)
    model = HomographyModel(src, dst)
    H = np.stack([model.fit(np.arange(150)), np.array([[1, 0, 0], [0, 1, 0], [1e-3, 0, 1.0]])])
    rng = np.random.default_rng(0)
    i1 = np.tile(np.arange(150), 3)
    i2 = np.concatenate([rng.permutation(150) for _ in range(3)])
    paired = model.residuals(H, i1, i2)
    plain = _sym_err_batch(H, None, _columns(src[i1]), _columns(dst[i2]))
    assert paired.shape == (2, 450) and np.array_equal(paired, plain)
    far = np.array([[-1000.0, 5.0], [3.0, 4.0]])  # u = -1000 maps to infinity under H[1]
    e = HomographyModel(far, far).residuals(H[1:], np.array([0, 1, 0]), np.array([1, 0, 0]))
    assert np.isinf(e[0, 0]) and np.isinf(e[0, 2]) and np.isfinite(e[0, 1])
