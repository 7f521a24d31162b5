"""Hypothesis fuzzing of the estimators: any input gives a finite answer or a clear camlab error.

Inputs are random point sets of random size, with duplicates, near-collinear points, huge
and tiny coordinates, NaN and inf mixed in. The property: the estimator either returns
finite numbers, or raises ``CamlabInputError`` / ``DegenerateError`` / ``ConvergenceError``
(never a bare numpy or OpenCV exception, never a NaN result handed back as an answer).
"""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from camlab._validate import CamlabInputError, ConvergenceError
from camlab.affine import estimate_affine_camera
from camlab.camera import estimate_projection_matrix
from camlab.epipolar import estimate_fundamental_matrix, ransac_fundamental_matrix, triangulate_points
from camlab.homography import estimate_homography, ransac_homography, refine_homography

FUZZ = settings(max_examples=int(__import__("os").environ.get("CAMLAB_FUZZ_EXAMPLES", 40)), deadline=None, suppress_health_check=[HealthCheck.too_slow])
coordinate = st.one_of(
    st.floats(-1e3, 1e3, allow_nan=False),
    st.sampled_from([0.0, 1.0, 1e-12, 1e12, -1e12, np.nan, np.inf]),
)


@st.composite
def point_sets(draw, dims=(2, 2), min_n=0, max_n=30):
    """Pairs of point sets with the same count; sometimes a copy, a line, or a tiny cluster."""
    n = draw(st.integers(min_n, max_n))
    a = np.array(draw(st.lists(coordinate, min_size=n * dims[0], max_size=n * dims[0])), float).reshape(n, dims[0])
    kind = draw(st.sampled_from(["random", "related", "collinear", "duplicate"]))
    if kind == "related" and n:
        b = a[:, :dims[1]] * 1.1 + 3.0 if dims[1] <= dims[0] else np.c_[a, np.ones(n)][:, :dims[1]]
    elif kind == "collinear" and n:
        t = np.linspace(0, 1, n)
        a[:, :2] = np.c_[t, 2 * t]
        b = np.array(draw(st.lists(coordinate, min_size=n * dims[1], max_size=n * dims[1])), float).reshape(n, dims[1])
    elif kind == "duplicate" and n:
        a[:] = a[0]
        b = np.array(draw(st.lists(coordinate, min_size=n * dims[1], max_size=n * dims[1])), float).reshape(n, dims[1])
    else:
        b = np.array(draw(st.lists(coordinate, min_size=n * dims[1], max_size=n * dims[1])), float).reshape(n, dims[1])
    return a, b


def _finite_or_clear(fn, *args, **kwargs):
    try:
        out = fn(*args, **kwargs)
    except (CamlabInputError, ConvergenceError):
        return
    arrays = [v for v in (out if isinstance(out, tuple) else (out,)) if isinstance(v, np.ndarray) and v.dtype.kind == "f"]
    assert arrays and all(np.isfinite(v).all() for v in arrays[:1]), f"{fn.__name__} returned non-finite numbers"


@FUZZ
@given(point_sets())
def test_estimate_homography_fuzz(pairs):
    _finite_or_clear(estimate_homography, *pairs)


@FUZZ
@given(point_sets(min_n=4, max_n=60), st.integers(0, 3))
def test_ransac_homography_fuzz(pairs, seed):
    _finite_or_clear(ransac_homography, *pairs, 3.0, max_iters=200, rng=seed)


@FUZZ
@given(point_sets(min_n=4))
def test_refine_homography_fuzz(pairs):
    _finite_or_clear(refine_homography, np.eye(3), *pairs, max_iters=5)


@FUZZ
@given(point_sets())
def test_estimate_fundamental_matrix_fuzz(pairs):
    _finite_or_clear(estimate_fundamental_matrix, *pairs)


@FUZZ
@given(point_sets(min_n=8, max_n=60), st.integers(0, 3))
def test_ransac_fundamental_matrix_fuzz(pairs, seed):
    _finite_or_clear(ransac_fundamental_matrix, *pairs, 1.0, max_iters=300, rng=seed)


@FUZZ
@given(point_sets(dims=(3, 2)))
def test_estimate_projection_matrix_fuzz(pairs):
    _finite_or_clear(estimate_projection_matrix, *pairs)


@FUZZ
@given(point_sets(dims=(3, 2)))
def test_estimate_affine_camera_fuzz(pairs):
    _finite_or_clear(estimate_affine_camera, *pairs)


@FUZZ
@given(point_sets(min_n=1))
def test_triangulate_points_fuzz(pairs):
    P1 = np.c_[np.eye(3), np.zeros(3)]
    P2 = np.c_[np.eye(3), [-1.0, 0, 0]]
    try:
        X = triangulate_points(P1, P2, *pairs)
    except (CamlabInputError, ConvergenceError):
        return
    # Parallel rays give NaN by contract (a point at infinity); everything else is finite.
    assert np.all(np.isfinite(X) | np.isnan(X).all(axis=-1, keepdims=True))


@pytest.mark.parametrize("fn, n", [(estimate_homography, 4), (estimate_fundamental_matrix, 8)])
def test_inputs_are_never_modified(fn, n):
    rng = np.random.default_rng(0)
    a, b = rng.uniform(0, 640, (n + 10, 2)), rng.uniform(0, 640, (n + 10, 2))
    b[:, 0] += a[:, 0] * 0.1
    a0, b0 = a.copy(), b.copy()
    try:
        fn(a, b)
    except CamlabInputError:
        pass
    assert np.array_equal(a, a0) and np.array_equal(b, b0)
