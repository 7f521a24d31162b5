import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from camlab import projective as pj
from camlab._validate import CamlabInputError, DegenerateError

coord = st.floats(-1e3, 1e3, allow_nan=False)
point2 = arrays(float, 2, elements=coord)


def random_homography(rng: np.random.Generator) -> np.ndarray:
    """A well-conditioned homography with a real perspective part."""
    H = np.eye(3) + 0.3 * rng.standard_normal((3, 3))
    H[2, :2] *= 0.01
    return H


# --- homogeneous coordinates -------------------------------------------------------


def test_to_homogeneous_keeps_rank():
    assert pj.to_homogeneous([1, 2]).shape == (3,)
    np.testing.assert_array_equal(pj.to_homogeneous([[1, 2], [3, 4]]), [[1, 2, 1], [3, 4, 1]])


def test_from_homogeneous_ideal_points_are_nan_not_huge():
    out = pj.from_homogeneous([[2, 4, 2], [1, 1, 0], [1, 1, 1e-300]])
    np.testing.assert_array_equal(out[0], [1, 2])
    assert np.isnan(out[1]).all()
    assert np.isfinite(out[2]).all()  # tiny but non-zero w is a real (far) point


@given(arrays(float, (5, 2), elements=coord), st.floats(-50, 50).filter(lambda s: abs(s) > 1e-3))
def test_homogeneous_round_trip_and_scale_invariance(x, s):
    np.testing.assert_allclose(pj.from_homogeneous(pj.to_homogeneous(x)), x)
    np.testing.assert_allclose(
        pj.from_homogeneous(s * pj.to_homogeneous(x)), x, rtol=1e-12, atol=1e-9
    )


def test_inputs_are_not_modified():
    x = np.array([[1.0, 2.0]])
    pj.to_homogeneous(x)
    pj.map_points(np.eye(3) * 2, x)
    np.testing.assert_array_equal(x, [[1.0, 2.0]])


# --- join, meet, incidence ---------------------------------------------------------


def test_join_and_meet_known_answers():
    np.testing.assert_allclose(pj.join([0, 0], [1, 1]), [-1, 1, 0])
    np.testing.assert_allclose(pj.meet([1, 0, -2], [0, 1, -3]), [2, 3, 1])
    vp = pj.meet([0, 1, 0], [0, 1, -1])  # y = 0 and y = 1
    assert vp[2] == 0 and pj.is_ideal(vp)
    assert pj.is_on_line(vp, pj.LINE_AT_INFINITY)


@given(point2, point2)
def test_join_passes_through_both_points(p, q):
    assume(np.linalg.norm(p - q) > 1e-3)
    line = pj.join(p, q)
    assert pj.is_on_line(p, line) and pj.is_on_line(q, line)


@given(point2, point2, point2, point2)
def test_meet_is_dual_to_join(a, b, c, d):
    assume(min(np.linalg.norm(a - b), np.linalg.norm(c - d)) > 1e-2)
    l1, l2 = pj.join(a, b), pj.join(c, d)
    u1, u2 = l1 / np.linalg.norm(l1), l2 / np.linalg.norm(l2)
    assume(np.linalg.norm(np.cross(u1, u2)) > 1e-6)  # distinct lines
    x = pj.meet(l1, l2)
    assert pj.is_on_line(x, l1, tol=1e-7) and pj.is_on_line(x, l2, tol=1e-7)


def test_join_meet_batches_broadcast_a_single_row():
    lines = pj.join([0, 0], [[1, 0], [0, 1], [1, 1]])
    assert lines.shape == (3, 3)
    pts = pj.meet(lines, [1, 0, -5])  # each with x = 5
    np.testing.assert_allclose(pj.from_homogeneous(pts)[:, 0], [5, np.nan, 5])  # x = 0 is parallel


def test_is_on_line_ignores_scale():
    line = np.array([1.0, -2.0, 3.0])
    p = np.array([1.0, 2.0, 1.0])
    for s in (1e-8, 1.0, 1e8):
        assert pj.is_on_line(s * p, line) and pj.is_on_line(p, s * line)
    assert not pj.is_on_line([1.0, 2.1], line)


def test_degenerate_join_and_meet_raise():
    with pytest.raises(DegenerateError, match="p and q coincide"):
        pj.join([1, 2], [2, 4, 2])
    with pytest.raises(DegenerateError, match="the same line"):
        pj.meet([1, 2, 3], [-2, -4, -6])


@pytest.mark.parametrize(
    "bad, message",
    [
        ([1, 2, 3, 4], r"p: expected \(N, 2\) or \(N, 3\) points"),
        ([np.nan, 1], r"p: expected finite values, found nan at index \(0, 0\)"),
        ("ab", r"p: expected numbers convertible to a float array"),
        ([0, 0, 0], r"p: \(0, 0, 0\) is not a point"),
    ],
)
def test_bad_points_name_the_argument(bad, message):
    with pytest.raises(CamlabInputError, match=message):
        pj.join(bad, [1, 1])


# --- normalisation, ideal points, distances ----------------------------------------


def test_normalise_points_and_lines():
    np.testing.assert_allclose(
        pj.normalise_points([[2, 4, 2], [3, 4, 0]]), [[1, 2, 1], [0.6, 0.8, 0]]
    )
    np.testing.assert_allclose(pj.normalise_lines([0, 0, -7]), [0, 0, 1])
    line = pj.normalise_lines([3, 4, 10])
    assert pj.point_line_distance([0, 0], line) == pytest.approx(2.0)


def test_ideal_point_lies_on_every_parallel_line():
    v = pj.ideal_point([1, 2])
    for c in (-5, 0, 3):
        assert pj.is_on_line(v, [2, -1, c])
    with pytest.raises(CamlabInputError, match="direction"):
        pj.ideal_point([0, 0])


def test_point_line_distance_rejects_line_at_infinity():
    with pytest.raises(DegenerateError, match="line at infinity"):
        pj.point_line_distance([1, 1], [0, 0, 1])


# --- homographies on points and lines ---------------------------------------------


@pytest.mark.parametrize("seed", range(5))
def test_lines_map_by_inverse_transpose_consistently_with_points(seed):
    rng = np.random.default_rng(seed)
    H = random_homography(rng)
    p, q = rng.uniform(-100, 100, (2, 2))
    mapped_line = pj.map_lines(H, pj.join(p, q))
    for x in (p, q, 0.3 * p + 0.7 * q):
        assert pj.is_on_line(pj.map_points(H, x), mapped_line, tol=1e-9)


def test_map_points_homogeneous_keeps_ideal_points():
    H = np.array([[1, 0, 0], [0, 1, 0], [1, 0, 1.0]])  # sends x = -1 to infinity
    out = pj.map_points(H, [[-1, 5], [1, 1]])
    assert np.isnan(out[0]).all()
    np.testing.assert_allclose(out[1], [0.5, 0.5])
    np.testing.assert_allclose(pj.map_points(H, [-1, 5, 1]), [-1, 5, 0])


def test_map_lines_rejects_singular_H():
    with pytest.raises(DegenerateError, match="singular"):
        pj.map_lines(np.diag([1.0, 1.0, 0.0]), [1, 2, 3])
    with pytest.raises(
        CamlabInputError, match=r"H: expected a \(3, 3\) matrix, got shape \(2, 2\)"
    ):
        pj.map_points(np.eye(2), [1, 2])


# --- cross-ratio ---------------------------------------------------------------------


def test_cross_ratio_known_value_and_ideal_point():
    assert pj.cross_ratio([[0, 0], [1, 0], [2, 0], [3, 0]]) == pytest.approx(4 / 3)
    # With D at infinity, (A, B; C, inf) = AC / BC.
    assert pj.cross_ratio([[0, 0, 1], [1, 0, 1], [3, 0, 1], [1, 0, 0]]) == pytest.approx(3 / 2)


@given(st.lists(st.floats(-50, 50), min_size=4, max_size=4, unique=True), st.integers(0, 10_000))
def test_cross_ratio_is_invariant_under_homographies(ts, seed):
    ts = np.sort(ts)
    assume(np.min(np.diff(ts)) > 1e-2)
    rng = np.random.default_rng(seed)
    origin, direction = rng.uniform(-10, 10, 2), rng.standard_normal(2)
    pts = origin + ts[:, None] * direction
    H = random_homography(rng)
    mapped = pj.map_points(H, pj.to_homogeneous(pts))  # homogeneous: robust if one goes to infinity
    assert pj.cross_ratio(mapped) == pytest.approx(pj.cross_ratio(pts), rel=1e-6)


def test_cross_ratio_errors():
    with pytest.raises(DegenerateError, match="point C .* is off the line"):
        pj.cross_ratio([[0, 0], [1, 0], [2, 0.5], [3, 0]])
    with pytest.raises(DegenerateError, match="B = C or A = D"):
        pj.cross_ratio([[0, 0], [1, 0], [1, 0], [3, 0]])
    with pytest.raises(CamlabInputError, match="exactly 4 collinear points"):
        pj.cross_ratio([[0, 0], [1, 0], [2, 0], [3, 0], [4, 0]])


# --- vanishing points and the horizon -----------------------------------------------


def test_vanishing_point_of_two_segments_is_their_meet():
    segs = [[[100, 480], [280, 200]], [[540, 480], [360, 200]]]
    vp = pj.vanishing_point(segs)
    expected = pj.normalise_points(pj.meet(pj.join(*segs[0]), pj.join(*segs[1])))
    np.testing.assert_allclose(vp, expected, rtol=1e-10)


def test_vanishing_point_least_squares_from_noisy_segments():
    rng = np.random.default_rng(1)
    vp_true = np.array([400.0, -150.0])
    starts = rng.uniform([0, 300], [640, 480], (12, 2))
    ends = starts + 0.6 * (vp_true - starts) + rng.normal(0, 0.3, (12, 2))
    vp = pj.from_homogeneous(pj.vanishing_point(np.stack([starts, ends], axis=1)))
    assert np.linalg.norm(vp - vp_true) < 5.0


def test_vanishing_point_of_parallel_segments_is_ideal():
    vp = pj.vanishing_point([[[0, 0], [1, 2]], [[5, 0], [6, 2]], [[9, 1], [10, 3]]])
    assert pj.is_ideal(vp, tol=1e-9)
    np.testing.assert_allclose(np.abs(vp[:2]), np.array([1, 2]) / np.sqrt(5), atol=1e-9)


def test_vanishing_point_errors():
    with pytest.raises(CamlabInputError, match=r"segments: expected \(N, 2, 2\)"):
        pj.vanishing_point([[[0, 0], [1, 1]]])
    with pytest.raises(DegenerateError, match="segment 1 has zero length"):
        pj.vanishing_point([[[0, 0], [1, 1]], [[2, 2], [2, 2]]])
    with pytest.raises(DegenerateError, match="all segments lie on one line"):
        pj.vanishing_point([[[0, 0], [1, 1]], [[2, 2], [3, 3]]])


def test_horizon_matches_camera_ground_truth():
    from camlab.fixtures import ground_plane_view

    g = ground_plane_view(np.radians(12), np.radians(20), 700.0)
    segs, n = g.segments, g.n_along_z
    assert segs.shape == (len(segs), 2, 2) and 0 < n < len(segs)
    hz = pj.horizon(pj.vanishing_point(segs[:n]), pj.vanishing_point(segs[n:]))
    truth = pj.normalise_lines(g.horizon)
    assert min(np.linalg.norm(hz - truth), np.linalg.norm(hz + truth)) < 1e-9


def test_clip_line():
    np.testing.assert_allclose(
        pj.clip_line([1, -1, 0], (0, 10), (0, 5)), [[0, 0], [5, 5]], atol=1e-12
    )
    assert np.isnan(pj.clip_line([0, 1, -20], (0, 10), (0, 5))).all()
    assert np.isnan(pj.clip_line([0, 0, 1], (0, 10), (0, 5))).all()


@pytest.mark.parametrize("d", [2, 3])
def test_hartley_normalise_centres_and_scales_n_by_d_points(d):
    rng = np.random.default_rng(d)
    p = rng.uniform(-300, 900, (40, d))
    pn, T = pj.hartley_normalise(p)
    assert T.shape == (d + 1, d + 1)
    np.testing.assert_allclose(pn.mean(axis=0), 0, atol=1e-12)
    assert np.isclose(np.linalg.norm(pn, axis=1).mean(), np.sqrt(d))
    np.testing.assert_allclose(np.c_[p, np.ones(40)] @ T.T, np.c_[pn, np.ones(40)], atol=1e-12)
    np.testing.assert_array_equal(pj.hartley_normalise(p).T, T)


def test_hartley_normalise_rejects_coincident_points_naming_them():
    with pytest.raises(DegenerateError, match=r"^points_world: all points coincide"):
        pj.hartley_normalise(np.ones((5, 3)), "points_world")
    with pytest.raises(CamlabInputError, match=r"points: expected \(N, 2\) or \(N, 3\) points"):
        pj.hartley_normalise(np.ones((5, 4)))


def test_vanishing_point_ransac_ignores_segments_that_point_elsewhere():
    rng = np.random.default_rng(4)
    v = np.array([900.0, 200.0])
    starts = rng.uniform([0, 0], [640, 480], (20, 2))
    good = np.stack([starts, starts + 0.3 * (v - starts)], axis=1) + rng.normal(0, 0.3, (20, 2, 2))
    bad = rng.uniform([0, 0], [640, 480], (8, 2, 2))
    fit = pj.vanishing_point_ransac(np.concatenate([good, bad]), tol_deg=1.0, rng=0)
    assert fit.inliers[:20].all() and fit.inliers[20:].sum() <= 1
    assert np.linalg.norm(pj.from_homogeneous(fit.point) - v) < 15
    # the least-squares point over all segments is dragged away by the stray ones
    assert (
        np.linalg.norm(pj.from_homogeneous(pj.vanishing_point(np.concatenate([good, bad]))) - v)
        > 50
    )


def test_vanishing_point_ransac_handles_an_ideal_point_and_bad_input():
    segs = np.array([[[0.0, y], [100.0, y + 1e-9]] for y in (10.0, 50.0, 90.0)])
    fit = pj.vanishing_point_ransac(segs, rng=1)
    assert fit.inliers.all() and abs(fit.point[2]) < 1e-6 * np.linalg.norm(fit.point)
    with pytest.raises(pj.CamlabInputError, match="segments"):
        pj.vanishing_point_ransac(np.zeros((1, 2, 2)))
    with pytest.raises(pj.CamlabInputError, match="two segments always meet"):
        pj.vanishing_point_ransac(segs[:2])


def test_vanishing_point_ransac_is_the_shared_ransac_and_refuses_chance(monkeypatch):
    """One RANSAC loop in camlab: the segments are a robust.PairModel; segments that point
    nowhere in common give no vanishing point, however many pairs are drawn."""
    from camlab import robust
    from camlab.projective import vanishing

    calls = []
    monkeypatch.setattr(
        vanishing, "ransac", lambda *a, **k: calls.append(a) or robust.ransac(*a, **k)
    )
    rng = np.random.default_rng(5)
    v = np.array([300.0, -2000.0])
    starts = rng.uniform([0, 0], [640, 480], (15, 2))
    good = np.stack([starts, starts + 0.2 * (v - starts)], axis=1)
    fit = pj.vanishing_point_ransac(good, rng=0)
    assert isinstance(calls[0][0], robust.PairModel) and fit.inliers.all()
    np.testing.assert_allclose(pj.from_homogeneous(fit.point), v, rtol=1e-9)
    with pytest.raises(pj.DegenerateError, match="vanishing_point_ransac: too few inliers"):
        pj.vanishing_point_ransac(rng.uniform(0, 640, (12, 2, 2)), tol_deg=0.5, rng=0)


def test_pointing_angles_are_what_segments_pointing_at_thresholds():
    from camlab.projective.vanishing import pointing_angles

    segs = np.array([[[0.0, 0.0], [1.0, 0.0]], [[0.0, 0.0], [1.0, 1.0]], [[2.0, 2.0], [2.0, 2.0]]])
    angles = pointing_angles([[10.0, 0.0, 1.0], [1.0, 0.0, 0.0]], segs[:, 0], segs[:, 1])
    # the diagonal segment's midpoint (0.5, 0.5) sees (10, 0) along (9.5, -0.5)
    slant = np.degrees(np.arccos(9.0 / np.sqrt(2 * 90.5)))
    np.testing.assert_allclose(angles[:, :2], [[0.0, slant], [0.0, 45.0]], atol=1e-6)
    assert (angles[:, 2] == 180.0).all()  # a segment of zero length points nowhere
    assert pj.segments_pointing_at(segs, [10.0, 0.0, 1.0], 1.0).tolist() == [True, False, False]


def test_splits_at_infinity_sees_a_bow_tie():
    from camlab.homography import estimate_homography

    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    convex = estimate_homography(square, [[0, 0], [2, 0.2], [1.8, 1.5], [0.1, 1.2]])
    bow_tie = estimate_homography(square, [[0, 0], [2, 0.2], [0.1, 1.2], [1.8, 1.5]])
    assert not pj.splits_at_infinity(convex, square) and pj.splits_at_infinity(bow_tie, square)


def test_vanishing_points_demo_draws_offimage_points_on_the_horizon():
    import os

    os.environ.setdefault("CAMLAB_FIGURE_MODE", "agg")
    from camlab.widgets import projective_plane as demos

    d = demos.vanishing_points()
    d.set(pitch=5.0, yaw=-35.0, focal=400.0)  # vp_x far left of the image
    ax = d.figure.axes[0]
    horizon, vz, vx = [line for line in ax.get_lines() if line.get_animated()][:3]
    (x, y), hz = (vx.get_xdata()[0], vx.get_ydata()[0]), d.state["horizon"]
    assert abs(hz @ [x, y, 1.0]) / np.linalg.norm(hz[:2]) < 1.0  # the arrow sits on the horizon
    d.set(pitch=40.0)
    assert d.state["horizon_visible"] is False
    assert "above the image" in ax.get_title()  # the title says so, in the image's frame
    assert any(
        "the horizon is above the image" in str(getattr(w, "value", ""))
        for w in _all_widgets(d.widget)
    )
    d.set(pitch=12.0)
    assert ax.get_title() == "ground grid seen by a tilted camera"


def _all_widgets(widget):
    yield widget
    for child in getattr(widget, "children", ()):
        yield from _all_widgets(child)


def test_map_polyline_lifts_the_pen_where_w_changes_sign():
    # x -> x / (1 - x): the segment from 0 to 3 leaves through infinity at x = 1.
    H = [[1, 0, 0], [0, 1, 0], [-1, 0, 1]]
    samples = np.column_stack([np.linspace(0, 3, 6), np.zeros(6)])  # 0, 0.6, 1.2, ...
    out = pj.map_polyline(H, samples)
    assert out.shape == (7, 2) and np.isnan(out[2]).all()
    assert np.allclose(out[:2], pj.map_points(H, samples[:2]))
    assert np.allclose(out[3:], pj.map_points(H, samples[2:]))
    # no sign change: the plain mapped samples
    assert np.allclose(pj.map_polyline(np.eye(3), samples), samples)
