"""Tests for camlab.homography: DLT, RANSAC, LM refinement, algebra, hierarchy, geometry."""

from __future__ import annotations

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from camlab import homography as hg
from camlab._validate import CamlabInputError, DegenerateError
from camlab.projective import cross_ratio, is_on_line, join, map_lines, map_points
from camlab.robust import required_iterations

K = np.array([[800.0, 0, 320], [0, 800, 240], [0, 0, 1]])
H_TRUE = np.array([[1.1, 0.05, 30.0], [-0.03, 0.95, -20.0], [2e-4, -1e-4, 1.0]])


def _rot(axis, angle):
    return cv2.Rodrigues(np.asarray(axis, float) * angle)[0]


def _pairs(n=200, seed=0, H=H_TRUE):
    rng = np.random.default_rng(seed)
    src = rng.uniform([0, 0], [640, 480], (n, 2))
    return src, map_points(H, src)


def _outliers(frac, seed=0, n=1000, noise=0.5):
    rng = np.random.default_rng(seed)
    src, dst = _pairs(n, seed)
    dst = dst + rng.normal(0, noise, dst.shape)
    out = rng.random(n) < frac
    dst[out] = rng.uniform([0, 0], [640, 480], (out.sum(), 2))
    return src, dst, out


# ------------------------------------------------------------------ estimate_homography


def test_exact_recovery_noise_free():
    src, dst = _pairs()
    H = hg.estimate_homography(src, dst)
    assert np.allclose(H, H_TRUE, atol=1e-9, rtol=0)
    assert hg.same_homography(H, H_TRUE, tol=1e-9)


def test_minimal_four_points_exact():
    src = np.array([[10.0, 20], [600, 30], [620, 460], [15, 440]])
    dst = map_points(H_TRUE, src)
    assert hg.same_homography(hg.estimate_homography(src, dst), H_TRUE, tol=1e-9)
    # unnormalised also recovers noise-free minimal data
    assert hg.same_homography(hg.estimate_homography(src, dst, normalise=False), H_TRUE, tol=1e-7)


def test_matches_cv2_findhomography_plain():
    rng = np.random.default_rng(3)
    src, dst = _pairs(300, 3)
    dst = dst + rng.normal(0, 1.0, dst.shape)
    H = hg.estimate_homography(src, dst)
    Hcv, _ = cv2.findHomography(src, dst, 0)
    # cv2 refines the DLT by LM on the transfer error: both fit the same data to within
    # a small fraction of the noise; compare where they send the points.
    diff = np.abs(map_points(H, src) - map_points(Hcv, src)).max()
    assert diff < 0.1, diff
    Hr = hg.refine_homography(H, src, dst).H
    assert np.abs(map_points(Hr, src) - map_points(Hcv, src)).max() < 0.1


def test_normalisation_beats_unnormalised_on_badly_scaled_data():
    errs = {True: [], False: []}
    for seed in range(10):
        rng = np.random.default_rng(seed)
        src = rng.uniform([2000, 2000], [2600, 2400], (30, 2))  # far from the origin
        Htrue = np.array([[1.0, 0.02, 15], [0.01, 0.98, -10], [1e-5, 2e-5, 1]])
        dst = map_points(Htrue, src) + rng.normal(0, 0.5, (30, 2))
        for norm in (True, False):
            H = hg.estimate_homography(src, dst, normalise=norm)
            errs[norm].append(
                np.sqrt(np.mean(hg.transfer_error(H, src, map_points(Htrue, src)) ** 2))
            )
    assert np.median(errs[True]) * 3 < np.median(errs[False]), errs


def test_single_pair_rank_errors():
    with pytest.raises(
        CamlabInputError,
        match=r"src: expected \(N, 2\) with N >= 4 point pairs, got shape \(3, 2\)",
    ):
        hg.estimate_homography(np.zeros((3, 2)), np.zeros((3, 2)))
    with pytest.raises(CamlabInputError, match="same number of points"):
        hg.estimate_homography(np.ones((5, 2)), np.ones((4, 2)))
    src, dst = _pairs(10)
    bad = src.copy()
    bad[2, 1] = np.nan
    with pytest.raises(CamlabInputError, match="src: expected finite values"):
        hg.estimate_homography(bad, dst)
    bad = dst.copy()
    bad[0, 0] = np.inf
    with pytest.raises(CamlabInputError, match="dst: expected finite values"):
        hg.estimate_homography(src, bad)
    with pytest.raises(CamlabInputError, match=r"expected \(N, 2\) points"):
        hg.estimate_homography(np.zeros((5, 3)), np.zeros((5, 3)))


def test_degenerate_sets():
    four = np.array([[0.0, 0], [1, 1], [2, 2], [0, 5]])
    with pytest.raises(
        DegenerateError, match=r"3 of the 4 points in src are collinear \(points \[0, 1, 2\]\)"
    ):
        hg.estimate_homography(four, [[0, 0], [1, 0], [1, 1], [0, 1]])
    line = np.column_stack([np.arange(8.0), 2 * np.arange(8.0) + 1])
    with pytest.raises(DegenerateError, match="all 8 points in dst are collinear"):
        hg.estimate_homography(np.random.default_rng(0).random((8, 2)), line)
    # all but one point on a line: not collinear overall, but no unique solution
    pts = np.vstack([np.column_stack([np.arange(6.0), np.zeros(6)]), [[2.0, 3.0]]])
    with pytest.raises(DegenerateError, match="do not fix a unique homography"):
        hg.estimate_homography(pts, pts * 2)


# ------------------------------------------------------------------ properties

finite = st.floats(-0.3, 0.3)


@st.composite
def homographies(draw):
    H = np.eye(3) + np.array(
        [
            [draw(finite), draw(finite), draw(st.floats(-50, 50))],
            [draw(finite), draw(finite), draw(st.floats(-50, 50))],
            [draw(st.floats(-5e-4, 5e-4)), draw(st.floats(-5e-4, 5e-4)), 0],
        ]
    )
    return H


@settings(max_examples=40, deadline=None)
@given(homographies(), st.integers(0, 10_000))
def test_property_inverse_is_identity(H, seed):
    pts = np.random.default_rng(seed).uniform(0, 640, (20, 2))
    back = map_points(hg.invert(H), map_points(H, pts))
    assert np.allclose(back, pts, atol=1e-7)


@settings(max_examples=40, deadline=None)
@given(homographies(), homographies(), st.integers(0, 10_000))
def test_property_composition(H1, H2, seed):
    pts = np.random.default_rng(seed).uniform(0, 640, (20, 2))
    assert np.allclose(
        map_points(hg.compose(H2, H1), pts), map_points(H2, map_points(H1, pts)), atol=1e-6
    )


@settings(max_examples=40, deadline=None)
@given(homographies(), st.integers(0, 10_000))
def test_property_collinearity_cross_ratio_and_lines(H, seed):
    rng = np.random.default_rng(seed)
    a, b = rng.uniform(0, 480, (2, 2))
    if np.linalg.norm(a - b) < 10:
        b = a + 50
    ts = np.sort(rng.uniform(-0.5, 1.5, 4))
    if np.min(np.diff(ts)) < 1e-2:
        ts = np.array([-0.3, 0.2, 0.7, 1.3])
    pts = a + ts[:, None] * (b - a)
    img = map_points(H, pts)
    line = join(pts[0], pts[3])
    line_img = map_lines(H, line)
    assert np.all(is_on_line(img, line_img, tol=1e-8))  # lines map by H^-T
    assert np.isclose(cross_ratio(img), cross_ratio(pts), rtol=1e-6)  # cross-ratio kept


@settings(max_examples=25, deadline=None)
@given(homographies(), st.integers(0, 10_000))
def test_property_dlt_recovers_any_homography(H, seed):
    src = np.random.default_rng(seed).uniform(0, 640, (12, 2))
    assert hg.same_homography(hg.estimate_homography(src, map_points(H, src)), H, tol=1e-8)


# ------------------------------------------------------------------ RANSAC


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_ransac_finds_all_inliers_at_50_percent_outliers(seed):
    src, dst, out = _outliers(0.5, seed=seed, n=400)
    r = hg.ransac_homography(src, dst, threshold=3.0, rng=np.random.default_rng(seed))
    # every true inlier (noise 0.5 px) is found; an outlier may land near H by chance
    true_in = ~out
    assert r.inliers[true_in].all()
    chance = r.inliers & out
    if chance.any():
        assert np.all(hg.symmetric_transfer_error(H_TRUE, src[chance], dst[chance]) < 3.5)
    assert r.inliers.dtype == bool and r.inliers.shape == (400,)
    assert r.residuals.shape == (400,)
    assert np.array_equal(r.inliers, r.residuals < 3.0)
    assert np.abs(map_points(r.H, src) - map_points(H_TRUE, src)).max() < 0.5
    assert 4 < r.iterations <= 2000


def test_ransac_adaptive_iteration_count():
    src, dst, _ = _outliers(0.1, seed=5, n=500)
    few = hg.ransac_homography(src, dst, rng=np.random.default_rng(0))
    src, dst, _ = _outliers(0.6, seed=5, n=500)
    many = hg.ransac_homography(src, dst, rng=np.random.default_rng(0))
    assert few.iterations < many.iterations
    w = many.inliers.mean()
    assert many.iterations >= required_iterations(w, 0.995, 4) * 0.5


def test_ransac_sampson_score_and_agreement_with_cv2():
    src, dst, out = _outliers(0.3, seed=7, n=1000)
    r = hg.ransac_homography(src, dst, threshold=3.0, rng=np.random.default_rng(1), score="sampson")
    Hcv, mask = cv2.findHomography(src, dst, cv2.RANSAC, 3.0)
    mask = mask.ravel().astype(bool)
    assert (r.inliers == ~out).mean() > 0.99
    assert (r.inliers == mask).mean() > 0.98
    assert np.abs(map_points(r.H, src[~out]) - map_points(Hcv, src[~out])).max() < 0.3


def test_ransac_reproducible_with_seed():
    src, dst, _ = _outliers(0.4, seed=2, n=300)
    a = hg.ransac_homography(src, dst, rng=np.random.default_rng(9))
    b = hg.ransac_homography(src, dst, rng=np.random.default_rng(9))
    assert np.array_equal(a.H, b.H) and a.iterations == b.iterations


def test_ransac_bad_input():
    src, dst = _pairs(20)
    with pytest.raises(CamlabInputError, match="threshold: expected a positive finite number"):
        hg.ransac_homography(src, dst, threshold=0)
    with pytest.raises(CamlabInputError, match="confidence: expected a probability"):
        hg.ransac_homography(src, dst, confidence=1.0)
    with pytest.raises(CamlabInputError, match="score: expected 'transfer' or 'sampson'"):
        hg.ransac_homography(src, dst, score="l1")
    rng = np.random.default_rng(0)
    with pytest.raises(DegenerateError, match="no hypothesis"):
        hg.ransac_homography(
            rng.random((50, 2)) * 600,
            rng.random((50, 2)) * 600,
            threshold=0.01,
            max_iters=50,
            rng=rng,
        )


# ------------------------------------------------------------------ LM refinement and errors


def test_refine_lowers_geometric_error_and_matches_cv2():
    rng = np.random.default_rng(11)
    src, dst = _pairs(60, 11)
    dst = dst + rng.normal(0, 2.0, dst.shape)
    H0 = hg.estimate_homography(src, dst)
    r = hg.refine_homography(H0, src, dst)
    assert r.rms_final <= r.rms_initial
    rms = np.sqrt(np.mean(hg.symmetric_transfer_error(r.H, src, dst) ** 2))
    assert np.isclose(rms, r.rms_final, rtol=1e-9)
    # A perturbed start converges back to the same optimum.
    H_bad = H0 @ np.array([[1.02, 0.01, 3], [0, 0.99, -2], [1e-5, 0, 1]])
    r2 = hg.refine_homography(H_bad, src, dst)
    assert r2.rms_initial > 2 * r2.rms_final
    assert np.isclose(r2.rms_final, r.rms_final, rtol=1e-4)
    # The Jacobian is right: compare with finite differences.
    h = H0.ravel() / np.linalg.norm(H0)
    res, J = hg.refinement._transfer_residuals_and_jacobian(h, src[:5], dst[:5])
    num = np.empty_like(J)
    for k in range(9):
        dh = np.zeros(9)
        dh[k] = 1e-5 * abs(h[k]) + 1e-14  # central differences, step relative to the entry
        plus = hg.refinement._transfer_residuals_and_jacobian(h + dh, src[:5], dst[:5])[0]
        minus = hg.refinement._transfer_residuals_and_jacobian(h - dh, src[:5], dst[:5])[0]
        num[:, k] = (plus - minus) / (2 * dh[k])
    assert np.allclose(J, num, rtol=1e-5, atol=1e-6 * np.abs(J).max())


def test_error_measures_known_values():
    assert np.allclose(hg.transfer_error(np.eye(3), [[0, 0]], [[3, 4]]), [5.0])
    assert np.allclose(hg.symmetric_transfer_error(np.eye(3), [[0, 0]], [[3, 4]]), [5.0])
    # Sampson: for a pure translation error the optimal split is half in each image.
    assert np.allclose(hg.sampson_distance(np.eye(3), [[0, 0]], [[0, 2]]), [np.sqrt(2)])
    src, dst = _pairs(20)
    assert np.allclose(hg.sampson_distance(H_TRUE, src, dst), 0, atol=1e-8)


# ------------------------------------------------------------------ algebra and hierarchy


def test_compose_invert_and_singular():
    A = hg.similarity_homography(2.0, 0.3, 5, -4)
    assert np.allclose(hg.compose(A, hg.invert(A)), np.eye(3), atol=1e-12)
    with pytest.raises(DegenerateError, match="H: singular"):
        hg.invert(np.diag([1.0, 1.0, 0.0]))
    with pytest.raises(CamlabInputError, match="compose: expected at least one"):
        hg.compose()


def test_hierarchy_matrix_builds_a_member_of_each_group():
    params = dict(theta=0.4, scale=1.6, shear=0.3, aspect=1.3, tx=5.0, ty=-2.0, v=(1e-3, 2e-3))
    for group in hg.HIERARCHY:
        assert hg.classify(hg.hierarchy_matrix(group, **params)) == group
    # each group ignores the parameters it does not have
    assert np.allclose(
        hg.hierarchy_matrix("euclidean", **params), hg.euclidean_homography(0.4, 5.0, -2.0)
    )
    assert np.allclose(
        hg.hierarchy_matrix("similarity", **params), hg.similarity_homography(1.6, 0.4, 5.0, -2.0)
    )
    A = hg.hierarchy_matrix("affine", **params)
    assert np.allclose(A, hg.affine_homography(0.4, 0.3, 1.6 * 1.3, 1.6 / 1.3, 5.0, -2.0))
    assert np.allclose(
        hg.hierarchy_matrix("projective", **params), A @ hg.projective_homography(v=(1e-3, 2e-3))
    )
    with pytest.raises(
        CamlabInputError,
        match="group: expected one of euclidean, similarity, affine, projective, got 'rigid'",
    ):
        hg.hierarchy_matrix("rigid")
    with pytest.raises(CamlabInputError, match="aspect"):
        hg.hierarchy_matrix("affine", aspect=0.0)


def test_hierarchy_classify_and_invariants():
    rng = np.random.default_rng(0)
    E = hg.euclidean_homography(0.7, 10, -3)
    S = hg.similarity_homography(1.7, -0.2, 4, 1)
    A = hg.affine_homography(0.3, 0.5, 1.5, 0.7, 2, 2)
    P = hg.projective_homography(np.eye(2), (3, 4), (1e-3, -2e-3))
    assert [hg.classify(M) for M in (E, S, A, P)] == [
        "euclidean",
        "similarity",
        "affine",
        "projective",
    ]
    assert [
        hg.HIERARCHY[k]["dof"] for k in ("euclidean", "similarity", "affine", "projective")
    ] == [3, 4, 6, 8]
    p, q, r_ = rng.uniform(0, 100, (3, 2))

    def length(M, a, b):
        return np.linalg.norm(map_points(M, a) - map_points(M, b))

    assert np.isclose(length(E, p, q), np.linalg.norm(p - q))  # Euclidean keeps length
    assert np.isclose(
        length(S, p, q) / length(S, p, r_), np.linalg.norm(p - q) / np.linalg.norm(p - r_)
    )
    d1 = map_points(A, q) - map_points(A, p)
    d2 = map_points(A, q + 10) - map_points(A, p + 10)
    assert np.allclose(d1, d2)  # affine keeps parallels
    e1 = map_points(P, q) - map_points(P, p)
    e2 = map_points(P, q + 200) - map_points(P, p + 200)
    sine = (e1[0] * e2[1] - e1[1] * e2[0]) / (np.linalg.norm(e1) * np.linalg.norm(e2))
    assert abs(sine) > 1e-2  # projective does not keep parallels
    # The projective map moves the line at infinity, an affinity does not.
    assert np.allclose(np.cross(map_lines(A, [0, 0, 1]), [0, 0, 1]), 0)
    assert not np.allclose(np.cross(map_lines(P, [0, 0, 1]), [0, 0, 1]), 0)


def test_decompose_reassembles():
    H = hg.normalise_homography(H_TRUE)
    HS, HA, HP = hg.decompose_homography(H)
    assert np.allclose(HS @ HA @ HP, H, atol=1e-12)
    assert hg.classify(HS) in ("similarity", "euclidean")
    assert np.isclose(np.linalg.det(HA[:2, :2]), 1.0)
    assert np.isclose(HA[1, 0], 0.0)


# ------------------------------------------------------------------ geometry


def test_plane_homography_matches_projection():
    rng = np.random.default_rng(4)
    R = _rot([0.2, 1.0, 0.1], 0.25)
    t = np.array([0.4, -0.1, 0.05])
    n = np.array([0.1, -0.2, -1.0])
    n /= np.linalg.norm(n)
    d = 3.0  # plane n . X + d = 0 about 3 m in front of camera 1
    H = hg.plane_homography(K, R, t, n, d)
    # 3-D points on the plane seen by both cameras
    xy = rng.uniform(-1, 1, (30, 2))
    X = np.column_stack([xy, np.zeros(30)])
    X[:, 2] = -(d + X[:, :2] @ n[:2]) / n[2]
    x1 = X @ K.T
    x1 = x1[:, :2] / x1[:, 2:]
    X2 = X @ R.T + t
    x2 = X2 @ K.T
    x2 = x2[:, :2] / x2[:, 2:]
    assert np.allclose(map_points(H, x1), x2, atol=1e-9)


def test_rotation_homography_and_pose_homography_vs_cv2():
    R = _rot([0, 1, 0], 0.3)
    H = hg.rotation_homography(K, R)
    rays = np.random.default_rng(0).uniform(-0.3, 0.3, (10, 2))
    X = np.column_stack([rays, np.ones(10)]) * np.random.default_rng(1).uniform(1, 9, (10, 1))
    x1 = X @ K.T
    x2 = (X @ R.T) @ K.T
    assert np.allclose(map_points(H, x1[:, :2] / x1[:, 2:]), x2[:, :2] / x2[:, 2:], atol=1e-9)
    # pose_homography = the projection of the plane Z = 0 (cv2.projectPoints)
    Rp = _rot([1, 0.2, 0], 0.5)
    tp = np.array([-0.1, 0.05, 2.0])
    XY = np.random.default_rng(2).uniform(-0.5, 0.5, (15, 2))
    proj, _ = cv2.projectPoints(
        np.column_stack([XY, np.zeros(15)]), cv2.Rodrigues(Rp)[0], tp, K, None
    )
    assert np.allclose(
        map_points(hg.pose_homography(K, Rp, tp), XY), proj.reshape(-1, 2), atol=1e-8
    )


def test_geometry_bad_input():
    with pytest.raises(DegenerateError, match="must not pass through camera 1's centre"):
        hg.plane_homography(K, np.eye(3), [1, 0, 0], [0, 0, 1], 0.0)
    with pytest.raises(CamlabInputError, match="R: expected a rotation matrix"):
        hg.rotation_homography(K, np.diag([1.0, 1.0, -1.0]))


def test_map_points_single_and_batch():
    src, _ = _pairs(5)
    assert map_points(H_TRUE, src[0]).shape == (2,)
    assert np.allclose(map_points(H_TRUE, src[0]), map_points(H_TRUE, src)[0])


def test_ransac_reports_the_winning_minimal_sample():
    rng = np.random.default_rng(5)
    H = np.array([[1.1, 0.05, 20.0], [-0.03, 0.95, -10.0], [2e-4, -1e-4, 1.0]])
    src = rng.uniform(0, 500, (120, 2))
    dst = map_points(H, src) + rng.normal(0, 0.3, src.shape)
    dst[:30] = rng.uniform(0, 500, (30, 2))
    r = hg.ransac_homography(src, dst, 2.0, rng=rng)
    assert r.sample.shape == (4,) and len(set(r.sample.tolist())) == 4
    assert r.inliers[r.sample].all()  # a clean sample won, and its pairs fit the answer


# ------------------------------------------------------------------ Gold Standard (H&Z algorithm 4.3)


def _noisy_both(n, seed, sigma=1.0):
    rng = np.random.default_rng(seed)
    H = np.array([[1.0, 0.05, 10.0], [-0.02, 1.0, 5.0], [1e-4, 4e-3, 1.0]])  # strong perspective
    src = rng.uniform([0, 0], [640, 480], (n, 2))
    dst = map_points(H, src)
    return H, src + rng.normal(0, sigma, src.shape), dst + rng.normal(0, sigma, dst.shape)


def test_gold_standard_is_the_minimum_of_the_reprojection_error():
    from scipy.optimize import least_squares

    _, src, dst = _noisy_both(25, 3)
    H0 = hg.estimate_homography(src, dst)
    g = hg.gold_standard_homography(H0, src, dst)

    def residuals(
        x,
    ):  # H with h33 = 1 (nonzero here) and the corrected points: an independent solver
        p = x[8:].reshape(-1, 2)
        return np.concatenate(
            [(p - src).ravel(), (map_points(np.append(x[:8], 1.0).reshape(3, 3), p) - dst).ravel()]
        )

    ls = least_squares(
        residuals,
        np.concatenate([H0.ravel()[:8], src.ravel()]),
        method="lm",
        xtol=1e-15,
        ftol=1e-15,
        max_nfev=20000,
    )
    assert np.isclose(g.rms_final, np.sqrt(2 * ls.cost / 50), rtol=1e-9)
    assert hg.same_homography(g.H, np.append(ls.x[:8], 1.0).reshape(3, 3), tol=1e-6)
    # The corrected pairs are exactly consistent with H, and the reported cost is theirs.
    assert np.allclose(map_points(g.H, g.src_corrected), g.dst_corrected, atol=1e-9)
    cost = np.sum((g.src_corrected - src) ** 2) + np.sum((g.dst_corrected - dst) ** 2)
    assert np.isclose(np.sqrt(cost / 50), g.rms_final, rtol=1e-9)
    assert g.rms_final <= g.rms_initial


def test_gold_standard_start_is_the_dlt_with_its_best_corrected_points():
    _, src, dst = _noisy_both(30, 4)
    H0 = hg.estimate_homography(src, dst)
    p = hg.correct_points(H0, src, dst)
    rms = np.sqrt((np.sum((p - src) ** 2) + np.sum((map_points(H0, p) - dst) ** 2)) / 60)
    assert np.isclose(hg.gold_standard_homography(H0, src, dst).rms_initial, rms, rtol=1e-12)

    # correct_points is a minimum for fixed H: moving any corrected point raises its pair's cost.
    def pair_cost(q, i):
        return np.sum((q - src[i]) ** 2) + np.sum((map_points(H0, q) - dst[i]) ** 2)

    for i in range(5):
        for step in ([0.01, 0], [0, -0.01]):
            assert pair_cost(p[i] + step, i) > pair_cost(p[i], i)


def test_gold_standard_on_exact_data_is_exact_and_beats_the_transfer_cost_under_perspective():
    H, src, dst = _noisy_both(12, 5, sigma=0.0)
    g = hg.gold_standard_homography(hg.estimate_homography(src, dst), src, dst)
    assert hg.same_homography(g.H, H, tol=1e-8) and g.rms_final < 1e-9
    # Under strong perspective with noise in both images, the ML estimate is closer to the truth
    # than the normalised DLT on average, and the symmetric transfer cost is not the ML cost.
    errs = {"dlt": [], "gold": []}
    for seed in range(20):
        H, src, dst = _noisy_both(20, 100 + seed)
        clean = map_points(H, src - 0)  # noisy src mapped by the truth: compare maps, not points
        H0 = hg.estimate_homography(src, dst)
        for name, E in (("dlt", H0), ("gold", hg.gold_standard_homography(H0, src, dst).H)):
            errs[name].append(np.sqrt(np.mean(np.sum((map_points(E, src) - clean) ** 2, axis=1))))
    assert np.mean(errs["gold"]) < np.mean(errs["dlt"])


def test_gold_standard_rejects_bad_input():
    _, src, dst = _noisy_both(6, 6)
    with pytest.raises(CamlabInputError, match="src"):
        hg.gold_standard_homography(np.eye(3), src[:3], dst[:3])
    with pytest.raises(CamlabInputError, match="H"):
        hg.gold_standard_homography(np.eye(2), src, dst)
