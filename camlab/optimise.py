r"""Levenberg-Marquardt for nonlinear least squares, in readable numpy.

We minimise the cost :math:`F(x) = \tfrac12 \|r(x)\|^2` of a residual vector
:math:`r(x) \in \mathbb{R}^m` over parameters :math:`x \in \mathbb{R}^n` (for calibration:
reprojection errors in pixels over intrinsics, distortion and every view's pose).

**Gauss-Newton.** Linearise :math:`r(x + \delta) \approx r + J \delta` with the Jacobian
:math:`J = \partial r / \partial x` (m x n). The linear least-squares problem
:math:`\min_\delta \|r + J\delta\|^2` has the *normal equations*

.. math:: A \delta = -g, \qquad A = J^\top J, \quad g = J^\top r .

Near the minimum this converges fast, but far from it the linear model lies and the step
can increase the cost; where A is (nearly) singular the step is huge.

**Levenberg-Marquardt** damps the step:

.. math:: (A + \mu D) \delta = -g, \qquad D = \operatorname{diag}(A) .

Large :math:`\mu` gives a short step along the (scaled) steepest descent direction
:math:`-D^{-1} g / \mu`; small :math:`\mu` gives the Gauss-Newton step. Marquardt's
choice :math:`D = \operatorname{diag}(A)` makes the step independent of each
parameter's units (a focal length in pixels and a rotation in radians are damped alike).

**Damping strategy** (Nielsen 1999, as in Madsen, Nielsen & Tingleff, *Methods for
non-linear least squares problems*, 2004, section 3.2). Compare the actual decrease of
the cost with the decrease the linear model predicted, the *gain ratio*

.. math:: \rho = \frac{F(x) - F(x + \delta)}{L(0) - L(\delta)}, \qquad
          L(0) - L(\delta) = -\tfrac12 \delta^\top (2 g + A \delta)
          = \tfrac12 \delta^\top (\mu D \delta - g).

If :math:`\rho > 0` the step is accepted and damping is rescaled smoothly:
:math:`\mu \leftarrow \mu \max(\tfrac13, 1 - (2\rho - 1)^3)`, a factor in :math:`[\tfrac13, 2)` that
shrinks :math:`\mu` when the model predicted well (:math:`\rho > \tfrac12`) and grows it when
it did not (:math:`0 < \rho < \tfrac12`);
:math:`\nu \leftarrow 2`. If :math:`\rho \le 0` the step is rejected and damping grows
ever faster: :math:`\mu \leftarrow \mu \nu`, :math:`\nu \leftarrow 2 \nu`. The start is
:math:`\mu_0 = \tau` (default :math:`10^{-3}`): relative to D, so nearly Gauss-Newton.

**Stopping**: the gradient is tiny (:math:`\|g\|_\infty \le` ``gtol``), the step is tiny
(:math:`\|\delta\| \le` ``xtol`` :math:`(\|x\| + ` ``xtol`` :math:`)`), the relative
decrease of the cost in an accepted step is below ``ftol``, or ``max_iter`` iterations.

**Structure.** :func:`levenberg_marquardt` never forms J itself. It calls
``jacobian(x)`` and hands the result to ``normal_equations(J, r) -> (A, g)`` and
``damped_solve(A, g, mu) -> delta``. The defaults treat J as a dense matrix; camera
calibration passes block versions (:mod:`camlab.calibration`) that exploit that each
view's pose touches only that view's residuals. See lesson 08, section 4.

**Parameters that are not a vector space.** A homography or a projection matrix is
defined up to scale: its entries live on the unit sphere, one dimension is redundant, and a
plain step :math:`x + \delta` could shrink it towards 0. Pass ``update(x, delta)`` to step
in a local parametrisation instead (the Jacobian is then with respect to ``delta``):
:func:`unit_sphere_update` steps in the tangent space :math:`x^\perp` (basis
:func:`unit_sphere_basis`) and re-normalises. Without a Jacobian, :func:`numeric_jacobian`
differentiates the residuals by central differences.

**Robust losses.** Least squares on :func:`huber_residuals` minimises the Huber loss
exactly; wrap the residual function with it (and use the numeric Jacobian, or the chain
rule) to down-weight outliers.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._validate import CamlabInputError, ConvergenceError, check_finite

__all__ = [
    "IndependentBlocks",
    "LMResult",
    "NormalEquations",
    "block_damped_solve",
    "block_normal_equations",
    "dense_damped_solve",
    "dense_normal_equations",
    "huber_jacobian",
    "huber_residuals",
    "levenberg_marquardt",
    "lm_step",
    "numeric_jacobian",
    "unit_sphere_basis",
    "unit_sphere_update",
]


class LMResult(NamedTuple):
    r"""The outcome of :func:`levenberg_marquardt`.

    ``x`` the solution; ``cost`` :math:`\tfrac12\|r\|^2` there; ``residuals`` r(x);
    ``cost_history`` the cost after every iteration (entry 0 is the start; rejected steps
    repeat the previous cost); ``mu_history`` the damping used at each iteration;
    ``iterations``; ``converged`` and ``message`` say why it stopped; ``jacobian`` and
    ``normal`` hold J and the :class:`NormalEquations` ``(A, g)`` at ``x`` (for covariances).
    """

    x: np.ndarray
    cost: float
    residuals: np.ndarray
    cost_history: np.ndarray
    mu_history: np.ndarray
    iterations: int
    converged: bool
    message: str
    jacobian: Any
    normal: tuple


class NormalEquations(NamedTuple):
    r"""The Gauss-Newton normal equations :math:`A\,\delta = -g` that ``normal_equations`` returns.

    Attributes
    ----------
    A : (n, n) ndarray, or any object the ``damped_solve`` in use understands
        :math:`J^\top J` (a block structure for the calibration's sparse problem).
    g : (n,) ndarray
        The gradient :math:`J^\top r`.
    """

    A: Any
    g: np.ndarray


def dense_normal_equations(J: np.ndarray, r: np.ndarray) -> NormalEquations:
    r"""The Gauss-Newton normal equations of a dense Jacobian: :math:`(J^\top J,\ J^\top r)`.

    Parameters
    ----------
    J : (m, n) ndarray
        Jacobian of the residuals with respect to the parameters.
    r : (m,) ndarray
        Residual vector.

    Returns
    -------
    NormalEquations
        ``A`` = J^T J, (n, n), and ``g`` = J^T r, (n,).
    """
    return NormalEquations(J.T @ J, J.T @ r)


def dense_damped_solve(A: np.ndarray, g: np.ndarray, mu: float) -> np.ndarray:
    r"""Solve :math:`(A + \mu\,\operatorname{diag}(A))\,\delta = -g` for the LM step.

    A diagonal entry of 0 (a parameter the residuals ignore) is floored at a tiny value so
    the damped matrix stays invertible and that parameter simply does not move.

    Parameters
    ----------
    A : (n, n) ndarray
        J^T J from :func:`dense_normal_equations`.
    g : (n,) ndarray
        The gradient J^T r.
    mu : float
        Damping factor (>= 0).

    Returns
    -------
    (n,) ndarray
        The step delta.
    """
    d = np.diag(A).copy()
    d = np.maximum(d, 1e-12 * max(d.max(initial=0.0), 1e-300))
    return np.linalg.solve(A + mu * np.diag(d), -g)


class IndependentBlocks:
    r"""The normal matrix of N independent problems of n parameters each: N blocks (n, n).

    When the residuals split into N groups and group i depends only on parameters
    :math:`x_i` (each triangulated point on its own 3 coordinates), J is block diagonal and
    so is :math:`A = J^\top J`; its N small blocks are solved one by one
    (:func:`block_damped_solve`) instead of one dense (Nn, Nn) matrix.
    """

    def __init__(self, blocks: np.ndarray):
        self.blocks = blocks

    def diagonal(self) -> np.ndarray:
        """diag(A), (N n,), as :func:`levenberg_marquardt` needs for its gain ratio.

        Returns
        -------
        (N n,) ndarray
            The diagonal of A, block after block.
        """
        return np.diagonal(self.blocks, axis1=1, axis2=2).ravel()


def block_normal_equations(J: np.ndarray, r: np.ndarray) -> NormalEquations:
    r"""The normal equations of a block-diagonal Jacobian given as (N, m, n) blocks.

    Residuals are ordered group by group (``r.reshape(N, m)``); :math:`A_i = J_i^\top J_i`
    and :math:`g_i = J_i^\top r_i`. Pass it as ``normal_equations`` to
    :func:`levenberg_marquardt`, with :func:`block_damped_solve`.

    Parameters
    ----------
    J : (N, m, n) ndarray
        One (m, n) Jacobian block per independent group of n parameters.
    r : (N m,) ndarray
        Residuals, group after group.

    Returns
    -------
    NormalEquations
        ``A``, an :class:`IndependentBlocks` of the (N, n, n) blocks J_i^T J_i, and ``g``,
        (N n,), the blocks J_i^T r_i one after another.
    """
    rb = r.reshape(len(J), -1)
    A = IndependentBlocks(np.einsum("nki,nkj->nij", J, J))
    return NormalEquations(A, np.einsum("nki,nk->ni", J, rb).ravel())


def block_damped_solve(A: IndependentBlocks, g: np.ndarray, mu: float) -> np.ndarray:
    r"""Solve :math:`(A_i + \mu\,\operatorname{diag}(A_i))\,\delta_i = -g_i` block by block.

    The block form of :func:`dense_damped_solve` (a diagonal entry of 0 is floored, so a
    parameter the residuals ignore does not move).

    Parameters
    ----------
    A : IndependentBlocks
        The (N, n, n) blocks from :func:`block_normal_equations`.
    g : (N n,) ndarray
        The gradient, block after block.
    mu : float
        Damping factor (>= 0).

    Returns
    -------
    (N n,) ndarray
        The step, block after block.
    """
    n = A.blocks.shape[-1]
    d = np.diagonal(A.blocks, axis1=1, axis2=2)
    d = np.maximum(d, 1e-12 * max(d.max(initial=0.0), 1e-300))
    damped = A.blocks + mu * d[:, :, None] * np.eye(n)
    return np.linalg.solve(damped, -g.reshape(-1, n, 1))[:, :, 0].ravel()


def lm_step(J: ArrayLike, r: ArrayLike, mu: float) -> np.ndarray:
    r"""One Levenberg-Marquardt step: solve :math:`(J^\top J + \mu\,\operatorname{diag}(J^\top J))\,\delta = -J^\top r`.

    Parameters
    ----------
    J : (m, n) array_like
        Jacobian of the residuals at the current parameters.
    r : (m,) array_like
        Residuals at the current parameters.
    mu : float
        Damping, >= 0. ``mu = 0`` is the Gauss-Newton step.

    Returns
    -------
    (n,) ndarray
        The step :math:`\delta` to add to the parameters.

    Examples
    --------
    Fit y = a x to (1, 2), (2, 4): one Gauss-Newton step from a = 0 lands on a = 2.

    >>> lm_step([[-1.0], [-2.0]], [2.0, 4.0], 0.0)
    array([2.])
    >>> lm_step([[-1.0], [-2.0]], [2.0, 4.0], 1.0)   # damped: half way
    array([1.])
    """
    Jm = np.array(J, dtype=float)
    rv = np.array(r, dtype=float).ravel()
    if Jm.ndim != 2 or Jm.shape[0] != rv.size:
        raise CamlabInputError(
            f"J: expected an (m, n) Jacobian with m = len(r) = {rv.size}, got shape {Jm.shape}"
        )
    if not (np.isfinite(mu) and mu >= 0):
        raise CamlabInputError(f"mu: expected a damping >= 0, got {mu!r}")
    check_finite(Jm, "J")
    check_finite(rv, "r")
    A, g = dense_normal_equations(Jm, rv)
    return dense_damped_solve(A, g, float(mu))


def numeric_jacobian(
    residuals: Callable[[np.ndarray], np.ndarray], x: ArrayLike, step: float = 1e-6
) -> np.ndarray:
    r"""The (m, n) Jacobian of ``residuals`` at ``x`` by central differences.

    :math:`J_{:, k} \approx \frac{r(x + h_k e_k) - r(x - h_k e_k)}{2 h_k}` with
    :math:`h_k = \text{step} \cdot \max(1, |x_k|)`: error :math:`O(h^2)`, 2n evaluations.
    For a local parametrisation differentiate ``lambda d: residuals(update(x, d))`` at 0.

    Parameters
    ----------
    residuals : callable
        ``residuals(x) -> (m,) array``.
    x : (n,) array_like
        Where to differentiate (flattened).
    step : float, optional
        Relative step h (default 1e-6).

    Returns
    -------
    (m, n) ndarray
        The Jacobian: column k is the derivative with respect to x_k.

    Examples
    --------
    >>> numeric_jacobian(lambda x: np.array([x[0] ** 2, x[0] * x[1]]), [3.0, 2.0]).round(6)
    array([[6., 0.],
           [2., 3.]])
    """
    x = np.array(x, dtype=float).ravel()
    h = step * np.maximum(1.0, np.abs(x))
    cols = []
    for k in range(x.size):
        e = np.zeros_like(x)
        e[k] = h[k]
        cols.append(
            (np.asarray(residuals(x + e), dtype=float) - np.asarray(residuals(x - e), dtype=float))
            / (2 * h[k])
        )
    return np.stack(cols, axis=-1)


def unit_sphere_basis(x: ArrayLike) -> np.ndarray:
    r"""An orthonormal basis (n, n - 1) of the tangent space of the unit sphere at x.

    The tangent space is :math:`x^\perp`, spanned by the right singular vectors of the row
    :math:`x^\top` other than :math:`x / \|x\|` (the same basis for the same x, so a Jacobian
    and a step computed at x agree).

    Parameters
    ----------
    x : (n,) array_like
        A point on (or off) the unit sphere, not zero.

    Returns
    -------
    (n, n - 1) ndarray
        Orthonormal columns, each orthogonal to x.
    """
    v = np.asarray(x, dtype=float).ravel()
    return np.linalg.svd(v[None, :])[2][1:].T


def unit_sphere_update(x: ArrayLike, delta: ArrayLike) -> np.ndarray:
    r"""Step on the unit sphere: :math:`x' = (x + B\delta) / \|x + B\delta\|`, B = :func:`unit_sphere_basis`.

    For parameters defined up to scale (homographies, projection matrices): the step has
    n - 1 components and never changes the scale.

    Parameters
    ----------
    x : (n,) array_like
        The current point (not zero).
    delta : (n - 1,) array_like
        The step in the tangent basis of :func:`unit_sphere_basis`.

    Returns
    -------
    (n,) ndarray
        The new point, unit norm.

    Examples
    --------
    >>> unit_sphere_update([0.0, 0.0, 1.0], [0.0, 0.0]).tolist()
    [0.0, 0.0, 1.0]
    """
    v = np.asarray(x, dtype=float).ravel()
    y = v + unit_sphere_basis(v) @ np.asarray(delta, dtype=float)
    return y / np.linalg.norm(y)


def _add(x: np.ndarray, delta: np.ndarray) -> np.ndarray:
    return x + delta


def _jacobian_or_differences(
    residuals: Callable[[np.ndarray], np.ndarray],
    jacobian: Callable[[np.ndarray], Any] | None,
    update: Callable[[np.ndarray, np.ndarray], np.ndarray] | None,
) -> Callable[[np.ndarray], Any]:
    """The caller's Jacobian, or central differences of the residuals (only for ``x + delta``)."""
    if jacobian is not None:
        return jacobian
    if update is not None:
        raise CamlabInputError(
            "jacobian: with a custom update, pass the Jacobian with respect to the step, e.g. "
            "lambda x: numeric_jacobian(lambda d: residuals(update(x, d)), np.zeros(k))"
        )
    return lambda x: numeric_jacobian(residuals, x)


def _gain_ratio(decrease: float, delta: np.ndarray, A: Any, g: np.ndarray, mu: float) -> float:
    r"""Nielsen's gain ratio :math:`\rho`.

    The actual decrease of the cost over the decrease the linear model predicted, :math:`L(0) -
    L(\delta) = \tfrac12 \delta^\top (\mu D \delta - g)`; -1 when the model predicts no decrease.
    """
    predicted = 0.5 * float(delta @ (mu * _diag(A) * delta - g))
    return decrease / predicted if predicted > 0 else -1.0


def levenberg_marquardt(
    residuals: Callable[[np.ndarray], np.ndarray],
    x0: ArrayLike,
    jacobian: Callable[[np.ndarray], Any] | None = None,
    *,
    update: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
    normal_equations: Callable[[Any, np.ndarray], tuple[Any, np.ndarray]] = dense_normal_equations,
    damped_solve: Callable[[Any, np.ndarray, float], np.ndarray] = dense_damped_solve,
    max_iter: int = 100,
    ftol: float = 1e-12,
    xtol: float = 1e-12,
    gtol: float = 1e-10,
    tau: float = 1e-3,
    callback: Callable[[int, np.ndarray, float], None] | None = None,
) -> LMResult:
    r"""Minimise :math:`\tfrac12\|r(x)\|^2` by Levenberg-Marquardt (see the module docstring).

    Parameters
    ----------
    residuals : callable
        ``residuals(x) -> (m,) ndarray``.
    x0 : (n,) array_like
        Starting parameters.
    jacobian : callable, optional
        ``jacobian(x) -> J``; a dense (m, n) array with the default solvers, or any object
        that ``normal_equations`` understands. None: central differences
        (:func:`numeric_jacobian`), only without ``update``.
    update : callable, optional
        ``update(x, delta) -> x_new``, the step in a local parametrisation (e.g.
        :func:`unit_sphere_update`); the Jacobian is then d r / d delta. Default ``x + delta``.
    normal_equations : callable
        ``(J, r) -> (A, g)`` with :math:`A = J^\top J` (in any form ``damped_solve`` takes)
        and the gradient :math:`g = J^\top r` as an (n,) array.
    damped_solve : callable
        ``(A, g, mu) -> delta`` solving :math:`(A + \mu\,\mathrm{diag}(A))\delta = -g`.
    max_iter : int
        Most iterations (accepted plus rejected steps).
    ftol, xtol, gtol : float
        Stopping tolerances on the relative cost decrease, the step and the gradient.
    tau : float
        Initial damping :math:`\mu_0`, relative to diag(A).
    callback : callable, optional
        Called as ``callback(iteration, x, cost)`` after each accepted step.

    Returns
    -------
    LMResult

    Raises
    ------
    ConvergenceError
        If the residuals at ``x0`` are not finite (the start is invalid).

    Examples
    --------
    Fit :math:`y = e^{a t}` to exact data with a = 0.7:

    >>> t = np.linspace(0, 1, 20); y = np.exp(0.7 * t)
    >>> res = levenberg_marquardt(lambda x: np.exp(x[0] * t) - y, [0.0],
    ...                           lambda x: (t * np.exp(x[0] * t))[:, None])
    >>> round(float(res.x[0]), 10), res.converged
    (0.7, True)
    """
    x = np.array(x0, dtype=float).ravel()
    check_finite(x, "x0")
    step = _add if update is None else update
    jacobian = _jacobian_or_differences(residuals, jacobian, update)
    r = np.asarray(residuals(x), dtype=float)
    if not np.all(np.isfinite(r)):
        raise ConvergenceError(
            "levenberg_marquardt: the residuals at the starting point x0 are not finite; "
            "start from parameters where the model is defined"
        )
    cost = 0.5 * float(r @ r)
    J = jacobian(x)
    A, g = normal_equations(J, r)
    mu, nu = float(tau), 2.0
    costs, mus = [cost], [mu]
    converged, message = False, f"stopped after max_iter = {max_iter} iterations"
    it = 0
    if np.max(np.abs(g), initial=0.0) <= gtol:
        return LMResult(
            x, cost, r, np.array(costs), np.array(mus), 0, True, "gradient is zero at x0", J, (A, g)
        )
    while it < max_iter:
        it += 1
        delta = damped_solve(A, g, mu)
        if not np.all(np.isfinite(delta)):
            mu, nu = mu * nu, nu * 2.0
            costs.append(cost)
            mus.append(mu)
            continue
        if np.linalg.norm(delta) <= xtol * (np.linalg.norm(x) + xtol):
            converged, message = True, "step below xtol"
            break
        x_new = step(x, delta)
        r_new = np.asarray(residuals(x_new), dtype=float)
        cost_new = 0.5 * float(r_new @ r_new) if np.all(np.isfinite(r_new)) else np.inf
        rho = _gain_ratio(cost - cost_new, delta, A, g, mu)
        if rho > 0:  # accept: the cost went down
            small_decrease = (cost - cost_new) <= ftol * cost
            x, r, cost = x_new, r_new, cost_new
            J = jacobian(x)
            A, g = normal_equations(J, r)
            mu *= max(1.0 / 3.0, 1.0 - (2.0 * rho - 1.0) ** 3)
            nu = 2.0
            if callback is not None:
                callback(it, x, cost)
            costs.append(cost)
            mus.append(mu)
            if np.max(np.abs(g)) <= gtol:
                converged, message = True, "gradient below gtol"
                break
            if small_decrease:
                converged, message = True, "relative cost decrease below ftol"
                break
        else:  # reject: increase the damping, shorter and more gradient-like step
            mu, nu = mu * nu, nu * 2.0
            costs.append(cost)
            mus.append(mu)
            if mu > 1e20:
                converged, message = (
                    True,
                    "damping exploded: no step decreases the cost (at a minimum)",
                )
                break
    return LMResult(x, cost, r, np.array(costs), np.array(mus), it, converged, message, J, (A, g))


def _diag(A: Any) -> np.ndarray:
    """diag(A) for a dense matrix or any object with a ``diagonal()`` method."""
    return np.diag(A) if isinstance(A, np.ndarray) else A.diagonal()


def _error_rows(errors: ArrayLike, delta: float) -> np.ndarray:
    e = np.asarray(errors, dtype=float)
    if e.ndim != 2:
        raise CamlabInputError(
            f"errors: expected an (N, D) array of error vectors, got shape {e.shape}"
        )
    if not (np.isfinite(delta) and delta > 0):
        raise CamlabInputError(f"delta: expected a positive threshold, got {delta!r}")
    return e


def huber_residuals(errors: ArrayLike, delta: float) -> np.ndarray:
    r"""Rescale error vectors so that least squares on them minimises the Huber loss.

    A robust loss :math:`\rho` replaces :math:`\tfrac12 \|e\|^2` by :math:`\rho(\|e\|)`; for
    Huber's, quadratic near zero and linear beyond :math:`\delta`,

    .. math:: \rho(s) = \begin{cases} s^2/2 & s \le \delta \\ \delta s - \delta^2/2 & s > \delta \end{cases}

    Scaling each error vector by :math:`\sqrt{2\rho(s)}/s` gives residuals :math:`\tilde e`
    with :math:`\tfrac12\|\tilde e\|^2 = \rho(s)`, so :func:`levenberg_marquardt` on
    :math:`\tilde e` minimises :math:`\sum \rho` exactly (a wrong match pulls with a
    constant force instead of one growing with its error). Inliers are unchanged.

    Parameters
    ----------
    errors : (N, D) array_like
        One error vector per row (e.g. a match's 2-D reprojection error, pixels).
    delta : float
        Where the loss turns linear, same units (> 0).

    Returns
    -------
    (N, D) ndarray

    >>> huber_residuals([[3.0, 4.0], [0.3, 0.4]], 1.0)   # |e| = 5: sqrt(2*(5 - 0.5)) = 3
    array([[1.8, 2.4],
           [0.3, 0.4]])
    """
    e = _error_rows(errors, delta)
    s = np.linalg.norm(e, axis=1, keepdims=True)
    big = s > delta
    scale = np.ones_like(s)
    scale[big] = np.sqrt(2 * delta * s[big] - delta**2) / s[big]
    return e * scale


def huber_jacobian(errors: ArrayLike, delta: float) -> np.ndarray:
    r"""The derivative of :func:`huber_residuals` with respect to each error vector.

    Inside the threshold the residual is the error (identity). Beyond it
    :math:`\tilde e = g(s)\, e` with :math:`g(s) = \sqrt{2\delta s - \delta^2}/s` and
    :math:`s = \|e\|`, so

    .. math:: \frac{\partial \tilde e}{\partial e} = g(s)\, I + \frac{g'(s)}{s}\, e e^\top,
              \qquad g'(s) = \frac{\delta}{s \sqrt{2\delta s - \delta^2}} - \frac{\sqrt{2\delta s - \delta^2}}{s^2}.

    Parameters
    ----------
    errors : (N, D) array_like
        One error vector per row.
    delta : float
        Where the loss turns linear (> 0).

    Returns
    -------
    (N, D, D) ndarray
        ``out[n] @ de`` is the change of residual n for a change ``de`` of error n.

    >>> huber_jacobian([[0.3, 0.4]], 1.0)[0]
    array([[1., 0.],
           [0., 1.]])
    """
    e = _error_rows(errors, delta)
    s = np.linalg.norm(e, axis=1)
    out = np.repeat(np.eye(e.shape[1])[None], len(e), axis=0)
    big = s > delta
    sb, eb = s[big], e[big]
    root = np.sqrt(2 * delta * sb - delta**2)
    g = root / sb
    dg = delta / (sb * root) - root / sb**2
    out[big] = (
        g[:, None, None] * out[big] + (dg / sb)[:, None, None] * eb[:, :, None] * eb[:, None, :]
    )
    return out
