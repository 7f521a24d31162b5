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
from camlab.epipolar import (
    estimate_fundamental_matrix,
    ransac_fundamental_matrix,
    triangulate_points,
)
from camlab.homography import estimate_homography, ransac_homography, refine_homography

FUZZ = settings(
    max_examples=int(__import__("os").environ.get("CAMLAB_FUZZ_EXAMPLES", 40)),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
)
coordinate = st.one_of(
    st.floats(-1e3, 1e3, allow_nan=False),
    st.sampled_from([0.0, 1.0, 1e-12, 1e12, -1e12, np.nan, np.inf]),
)


@st.composite
def point_sets(draw, dims=(2, 2), min_n=0, max_n=30):
    """Pairs of point sets with the same count; sometimes a copy, a line, or a tiny cluster."""
    n = draw(st.integers(min_n, max_n))
    a = np.array(
        draw(st.lists(coordinate, min_size=n * dims[0], max_size=n * dims[0])), float
    ).reshape(n, dims[0])
    kind = draw(st.sampled_from(["random", "related", "collinear", "duplicate"]))
    if kind == "related" and n:
        b = (
            a[:, : dims[1]] * 1.1 + 3.0
            if dims[1] <= dims[0]
            else np.c_[a, np.ones(n)][:, : dims[1]]
        )
    elif kind == "collinear" and n:
        t = np.linspace(0, 1, n)
        a[:, :2] = np.c_[t, 2 * t]
        b = np.array(
            draw(st.lists(coordinate, min_size=n * dims[1], max_size=n * dims[1])), float
        ).reshape(n, dims[1])
    elif kind == "duplicate" and n:
        a[:] = a[0]
        b = np.array(
            draw(st.lists(coordinate, min_size=n * dims[1], max_size=n * dims[1])), float
        ).reshape(n, dims[1])
    else:
        b = np.array(
            draw(st.lists(coordinate, min_size=n * dims[1], max_size=n * dims[1])), float
        ).reshape(n, dims[1])
    return a, b


# Each estimator: the point sets it is fed, and how it is called on them (``seed`` seeds RANSAC).
ESTIMATORS = {
    "estimate_homography": (point_sets(), lambda a, b, seed: estimate_homography(a, b)),
    "ransac_homography": (
        point_sets(min_n=4, max_n=60),
        lambda a, b, seed: ransac_homography(a, b, 3.0, max_iters=200, rng=seed),
    ),
    "refine_homography": (
        point_sets(min_n=4),
        lambda a, b, seed: refine_homography(np.eye(3), a, b, max_iters=5),
    ),
    "estimate_fundamental_matrix": (
        point_sets(),
        lambda a, b, seed: estimate_fundamental_matrix(a, b),
    ),
    "ransac_fundamental_matrix": (
        point_sets(min_n=8, max_n=60),
        lambda a, b, seed: ransac_fundamental_matrix(a, b, 1.0, max_iters=300, rng=seed),
    ),
    "estimate_projection_matrix": (
        point_sets(dims=(3, 2)),
        lambda a, b, seed: estimate_projection_matrix(a, b),
    ),
    "estimate_affine_camera": (
        point_sets(dims=(3, 2)),
        lambda a, b, seed: estimate_affine_camera(a, b),
    ),
}


@FUZZ
@pytest.mark.parametrize("name", list(ESTIMATORS))
@given(data=st.data())
def test_estimators_give_finite_numbers_or_a_clear_error(name, data):
    points, call = ESTIMATORS[name]
    a, b = data.draw(points, label="point sets")
    seed = data.draw(st.integers(0, 3), label="seed")
    try:
        out = call(a, b, seed)
    except (CamlabInputError, ConvergenceError):
        return
    arrays = [
        v
        for v in (out if isinstance(out, tuple) else (out,))
        if isinstance(v, np.ndarray) and v.dtype.kind == "f"
    ]
    assert arrays and np.isfinite(arrays[0]).all(), f"{name} returned non-finite numbers"


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
