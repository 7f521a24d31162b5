"""Tests for camlab.optimise: Levenberg-Marquardt and one damped step."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from camlab import ConvergenceError
from camlab._validate import CamlabInputError
from camlab.optimise import (
    dense_damped_solve,
    huber_residuals,
    levenberg_marquardt,
    lm_step,
    numeric_jacobian,
    unit_sphere_basis,
    unit_sphere_update,
)


def rosenbrock():
    """Rosenbrock as least squares: r = (10 (y - x^2), 1 - x), minimum 0 at (1, 1)."""

    def res(p):
        return np.array([10 * (p[1] - p[0] ** 2), 1 - p[0]])

    def jac(p):
        return np.array([[-20 * p[0], 10.0], [-1.0, 0.0]])

    return res, jac


def test_rosenbrock_from_the_classic_start():
    res, jac = rosenbrock()
    out = levenberg_marquardt(res, [-1.2, 1.0], jac)
    assert out.converged
    np.testing.assert_allclose(out.x, [1.0, 1.0], atol=1e-9)
    assert out.cost < 1e-20
    # accepted steps never increase the cost
    assert np.all(np.diff(out.cost_history) <= 1e-15)
    assert len(out.cost_history) == out.iterations + 1 == len(out.mu_history)


def test_damping_grows_after_a_rejected_step_and_shrinks_after_good_ones():
    res, jac = rosenbrock()
    out = levenberg_marquardt(res, [-1.2, 1.0], jac, tau=1e-8)
    d = np.diff(out.cost_history)
    mus = out.mu_history
    rejected = np.flatnonzero(d == 0)
    assert len(rejected) > 0, "from a nearly Gauss-Newton start Rosenbrock must reject some steps"
    for i in rejected:
        assert mus[i + 1] > mus[i]
    accepted = np.flatnonzero(d < 0)
    assert any(mus[i + 1] < mus[i] for i in accepted)


def test_matches_scipy_least_squares_on_a_curve_fit():
    from scipy.optimize import least_squares

    rng = np.random.default_rng(3)
    t = np.linspace(0, 3, 60)
    y = 2.5 * np.exp(-1.3 * t) + 0.4 + rng.normal(0, 0.01, t.size)

    def res(p):
        return p[0] * np.exp(-p[1] * t) + p[2] - y

    def jac(p):
        e = np.exp(-p[1] * t)
        return np.column_stack([e, -p[0] * t * e, np.ones_like(t)])

    ours = levenberg_marquardt(res, [1.0, 0.5, 0.0], jac)
    ref = least_squares(res, [1.0, 0.5, 0.0], jac=jac, method="lm", xtol=1e-14, ftol=1e-14)
    np.testing.assert_allclose(ours.x, ref.x, rtol=1e-7)
    assert ours.cost == pytest.approx(ref.cost, rel=1e-9)


def test_structured_solvers_are_used():
    calls = {"normal": 0, "solve": 0}

    def normal(J, r):
        calls["normal"] += 1
        return J.T @ J, J.T @ r

    def solve(A, g, mu):
        calls["solve"] += 1
        return dense_damped_solve(A, g, mu)

    res, jac = rosenbrock()
    out = levenberg_marquardt(res, [0.0, 0.0], jac, normal_equations=normal, damped_solve=solve)
    assert out.converged and calls["normal"] >= 2 and calls["solve"] >= out.iterations - 1


def test_max_iter_stops_and_says_so():
    res, jac = rosenbrock()
    out = levenberg_marquardt(res, [-1.2, 1.0], jac, max_iter=2)
    assert out.iterations == 2 and not out.converged and "max_iter" in out.message


def test_starting_at_the_minimum_returns_at_once():
    res, jac = rosenbrock()
    out = levenberg_marquardt(res, [1.0, 1.0], jac)
    assert out.iterations == 0 and out.converged


def test_non_finite_start_raises():
    with pytest.raises(ConvergenceError, match="not finite"):
        levenberg_marquardt(lambda x: np.where(x < 0, np.nan, x), [-1.0], lambda x: np.eye(1))
    with pytest.raises(CamlabInputError, match="x0: expected finite"):
        levenberg_marquardt(lambda x: x, [np.nan], lambda x: np.eye(1))


def test_lm_step_known_answers_and_limits():
    J = np.array([[1.0, 0.0], [0.0, 10.0], [1.0, 1.0]])
    r = np.array([1.0, -2.0, 0.5])
    gn = np.linalg.lstsq(J, -r, rcond=None)[0]
    np.testing.assert_allclose(lm_step(J, r, 0.0), gn, atol=1e-12)
    # large damping: a short step along -D^-1 g / mu
    A, g = J.T @ J, J.T @ r
    np.testing.assert_allclose(lm_step(J, r, 1e8) * 1e8, -g / np.diag(A), rtol=1e-6)


def test_lm_step_bad_input():
    with pytest.raises(
        CamlabInputError, match="J: expected an \\(m, n\\) Jacobian with m = len\\(r\\) = 3"
    ):
        lm_step(np.ones((2, 2)), np.ones(3), 0.1)
    with pytest.raises(CamlabInputError, match="mu: expected a damping >= 0"):
        lm_step(np.ones((3, 2)), np.ones(3), -1.0)


@given(st.floats(0.0, 1e3), st.integers(0, 10_000))
def test_damped_step_never_points_uphill(mu, seed):
    rng = np.random.default_rng(seed)
    J, r = rng.normal(size=(8, 3)), rng.normal(size=8)
    d = lm_step(J, r, mu)
    # a descent direction: g . delta <= 0, and the linear model does not get worse
    assert (J.T @ r) @ d <= 1e-9
    assert np.linalg.norm(r + J @ d) <= np.linalg.norm(r) + 1e-9


def test_huber_residuals_give_the_huber_cost_and_a_robust_fit():
    rng = np.random.default_rng(3)
    e = rng.normal(0, 3, (200, 2))
    s = np.linalg.norm(e, axis=1)
    rho = np.where(s <= 1.5, s**2 / 2, 1.5 * s - 1.5**2 / 2)
    assert np.allclose(0.5 * (huber_residuals(e, 1.5) ** 2).sum(axis=1), rho)
    # a line fit with 20% gross outliers: plain least squares is pulled away, Huber is not
    t = np.linspace(0, 1, 50)
    y = 2 * t + 1 + rng.normal(0, 0.01, 50)
    y[::5] += 5
    plain = levenberg_marquardt(
        lambda p: p[0] * t + p[1] - y, [0.0, 0.0], lambda p: np.c_[t, np.ones_like(t)]
    )
    robust = levenberg_marquardt(
        lambda p: huber_residuals((p[0] * t + p[1] - y)[:, None], 0.05).ravel(),
        [0.0, 0.0],
        lambda p: np.stack(
            [
                (
                    huber_residuals((p[0] * t + p[1] - y)[:, None], 0.05).ravel()
                    - huber_residuals(((p[0] + d[0]) * t + p[1] + d[1] - y)[:, None], 0.05).ravel()
                )
                / -1e-7
                for d in ([1e-7, 0], [0, 1e-7])
            ],
            axis=1,
        ),
    )
    assert abs(plain.x[1] - 1) > 0.5
    assert abs(robust.x[0] - 2) < 0.05 and abs(robust.x[1] - 1) < 0.05
    with pytest.raises(CamlabInputError, match="delta"):
        huber_residuals(e, 0)
    with pytest.raises(CamlabInputError, match="errors"):
        huber_residuals([1.0, 2.0], 1)


def test_numeric_jacobian_matches_the_analytic_one():
    t = np.linspace(0, 1, 7)

    def res(x):
        return x[0] * np.exp(x[1] * t) - 1.0

    x = np.array([1.3, -0.4])
    analytic = np.c_[np.exp(x[1] * t), x[0] * t * np.exp(x[1] * t)]
    np.testing.assert_allclose(numeric_jacobian(res, x), analytic, rtol=1e-8, atol=1e-10)
    # without a Jacobian levenberg_marquardt differentiates numerically and still converges
    y = 2.0 * np.exp(0.7 * t)
    out = levenberg_marquardt(lambda p: p[0] * np.exp(p[1] * t) - y, [1.0, 0.0])
    np.testing.assert_allclose(out.x, [2.0, 0.7], atol=1e-8)
    assert out.converged


def test_unit_sphere_steps_stay_on_the_sphere():
    rng = np.random.default_rng(5)
    x = rng.normal(size=9)
    x /= np.linalg.norm(x)
    B = unit_sphere_basis(x)
    assert B.shape == (9, 8)
    np.testing.assert_allclose(B.T @ B, np.eye(8), atol=1e-12)
    np.testing.assert_allclose(B.T @ x, 0, atol=1e-12)
    y = unit_sphere_update(x, rng.normal(size=8))
    assert np.isclose(np.linalg.norm(y), 1.0) and not np.allclose(y, x)
    # a tiny step moves x along B delta, to first order
    d = 1e-7 * rng.normal(size=8)
    np.testing.assert_allclose(unit_sphere_update(x, d) - x, B @ d, atol=1e-13)


def test_lm_on_the_sphere_finds_the_smallest_eigenvector():
    """min ||A x||^2 over unit x is the eigenvector of A^T A with the smallest eigenvalue."""
    rng = np.random.default_rng(2)
    A = rng.normal(size=(20, 5))
    out = levenberg_marquardt(
        lambda x: A @ x,
        np.ones(5) / np.sqrt(5),
        lambda x: A @ unit_sphere_basis(x),
        update=unit_sphere_update,
        max_iter=200,
        ftol=1e-15,
        xtol=1e-15,
        gtol=1e-13,
    )
    w, V = np.linalg.eigh(A.T @ A)
    assert np.isclose(np.linalg.norm(out.x), 1.0)
    assert abs(abs(out.x @ V[:, 0]) - 1) < 1e-9
    with pytest.raises(CamlabInputError, match="jacobian: with a custom update, pass the Jacobian"):
        levenberg_marquardt(lambda x: A @ x, np.ones(5), update=unit_sphere_update)


def test_independent_blocks_solve_as_the_dense_block_diagonal_matrix():
    """N independent problems (each point's triangulation) as (N, m, n) Jacobian blocks: the
    block normal equations and damped step equal the dense ones of the block-diagonal J."""
    from scipy.linalg import block_diag

    from camlab.optimise import (
        block_damped_solve,
        block_normal_equations,
        dense_damped_solve,
        dense_normal_equations,
    )

    rng = np.random.default_rng(3)
    J = rng.normal(size=(5, 4, 3))
    r = rng.normal(size=20)
    A, g = block_normal_equations(J, r)
    Ad, gd = dense_normal_equations(block_diag(*J), r)
    np.testing.assert_allclose(g, gd, atol=1e-12)
    np.testing.assert_allclose(A.diagonal(), np.diag(Ad), atol=1e-12)
    np.testing.assert_allclose(
        block_damped_solve(A, g, 0.3), dense_damped_solve(Ad, gd, 0.3), atol=1e-12
    )
