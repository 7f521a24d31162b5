r"""Refining a homography by Levenberg-Marquardt.

On the symmetric transfer error, and the Gold Standard ([1]_, algorithm 4.3: the reprojection error
over H and corrected points).

Part of :mod:`camlab.homography` (every name here is importable from there).

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 4.5 and algorithm 4.3
   (the Gold Standard algorithm).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    ConvergenceError,
)
from ..optimise import levenberg_marquardt, unit_sphere_basis, unit_sphere_update
from ..projective import map_points
from .core import check_correspondences, check_homography, normalise_homography

__all__ = [
    "GoldStandardResult",
    "RefineResult",
    "correct_points",
    "gold_standard_homography",
    "refine_homography",
]


class RefineResult(NamedTuple):
    """What :func:`refine_homography` did.

    Attributes
    ----------
    H : (3, 3) ndarray
        The refined homography, H[2, 2] = 1.
    rms_initial, rms_final : float
        RMS symmetric transfer error in pixels before and after.
    iterations : int
        Levenberg-Marquardt steps taken (accepted or rejected).
    """

    H: np.ndarray
    rms_initial: float
    rms_final: float
    iterations: int


def _transfer_residuals_and_jacobian(h: np.ndarray, s: np.ndarray, d: np.ndarray):
    """Residual vector (4N,) and its Jacobian (4N, 9) with respect to h = H row-major."""
    H = h.reshape(3, 3)
    G = np.linalg.inv(H)
    n = len(s)
    xs = np.hstack([s, np.ones((n, 1))])
    xd = np.hstack([d, np.ones((n, 1))])
    y = xs @ H.T  # forward: y = H x
    z = xd @ G.T  # backward: z = H^-1 x'
    p = y[:, :2] / y[:, 2:]
    q = z[:, :2] / z[:, 2:]
    r = np.concatenate([(p - d).ravel(), (q - s).ravel()])

    def dproj(w: np.ndarray, proj: np.ndarray) -> np.ndarray:  # d(pi(w))/dw, (N, 2, 3)
        J = np.zeros((len(w), 2, 3))
        J[:, 0, 0] = J[:, 1, 1] = 1 / w[:, 2]
        J[:, :, 2] = -proj / w[:, 2:]
        return J

    # dy/dh = kron(I3, x^T): dy_i/dH_ij = x_j.
    Ky = np.einsum("ik,nj->nikj", np.eye(3), xs).reshape(n, 3, 9)
    Jf = dproj(y, p) @ Ky
    # d(H^-1) = -H^-1 dH H^-1, so dz = -G dH z and dz/dh = -G kron(I3, z^T).
    Kz = np.einsum("ik,nj->nikj", np.eye(3), z).reshape(n, 3, 9)
    Jb = dproj(z, q) @ (-G @ Kz)
    return r, np.concatenate([Jf.reshape(2 * n, 9), Jb.reshape(2 * n, 9)])


def refine_homography(
    H: ArrayLike,
    src: ArrayLike,
    dst: ArrayLike,
    max_iters: int = 50,
    tol: float = 1e-10,
) -> RefineResult:
    r"""Refine H by Levenberg-Marquardt on the symmetric transfer error (the geometric cost).

    Minimises :math:`\sum_i \|x'_i - \pi(H x_i)\|^2 + \|x_i - \pi(H^{-1} x'_i)\|^2` over
    H, starting from ``H`` (typically the DLT). The 9 entries carry one redundant scale,
    so steps are taken in the 8-dimensional space orthogonal to the current :math:`h`
    (a basis B from the SVD of :math:`h^T`), and h is re-normalised after each step.

    The steps are :func:`camlab.optimise.levenberg_marquardt`'s, on the unit sphere
    (:func:`camlab.optimise.unit_sphere_update`), with the analytic Jacobian J: for the
    forward term :math:`\partial (Hx)/\partial h = I_3 \otimes x^T`, and for the backward
    term :math:`d(H^{-1}) = -H^{-1}\, dH\, H^{-1}`.

    Parameters
    ----------
    H : (3, 3) array_like
        Starting homography (invertible).
    src, dst : (N, 2) array_like
        Corresponding pixel coordinates, N >= 4.
    max_iters : int
        Maximum LM steps (accepted or rejected).
    tol : float
        Stop when the relative cost decrease of an accepted step is below ``tol``.

    Returns
    -------
    RefineResult
        ``H``, ``rms_initial``, ``rms_final`` (pixels), ``iterations``.

    Raises
    ------
    ConvergenceError
        If the cost is not finite at the start (a point maps to infinity).
    """
    h = check_homography(H).ravel().copy()
    s, d = check_correspondences(src, dst)
    h /= np.linalg.norm(h)
    r0 = _transfer_residuals_and_jacobian(h, s, d)[0]
    if not np.all(np.isfinite(r0)):
        raise ConvergenceError(
            "refine_homography: the starting H maps some point to infinity; start from the DLT"
        )
    cache: dict = {}

    def evaluate(x: np.ndarray):
        key = x.tobytes()
        if key not in cache:
            cache.clear()
            try:
                cache[key] = _transfer_residuals_and_jacobian(x, s, d)
            except np.linalg.LinAlgError:  # a singular trial H: reject the step
                cache[key] = (np.full(4 * len(s), np.inf), None)
        return cache[key]

    lm = levenberg_marquardt(
        lambda x: evaluate(x)[0],
        h,
        lambda x: evaluate(x)[1] @ unit_sphere_basis(x),
        update=unit_sphere_update,
        max_iter=int(max_iters),
        ftol=tol,
        xtol=1e-14,
        gtol=0.0,
    )
    return RefineResult(
        normalise_homography(lm.x.reshape(3, 3)),
        float(np.sqrt(r0 @ r0 / (2 * len(s)))),
        float(np.sqrt(2 * lm.cost / (2 * len(s)))),
        lm.iterations,
    )


class GoldStandardResult(NamedTuple):
    r"""What :func:`gold_standard_homography` did.

    Attributes
    ----------
    H : (3, 3) ndarray
        The maximum-likelihood homography (H&Z algorithm 4.3), H[2, 2] = 1.
    src_corrected, dst_corrected : (N, 2) ndarray
        The corrected points :math:`\hat x_i` and :math:`\hat x'_i = \pi(H \hat x_i)`: the
        pairs closest to the measurements that H maps exactly onto each other.
    rms_initial, rms_final : float
        RMS reprojection error in pixels, :math:`\sqrt{\sum_i d(x_i, \hat x_i)^2 + d(x'_i, \hat x'_i)^2 / 2N}`,
        of the starting H (with its own best corrected points) and of the result.
    iterations : int
        Levenberg-Marquardt steps taken (accepted or rejected).
    """

    H: np.ndarray
    src_corrected: np.ndarray
    dst_corrected: np.ndarray
    rms_initial: float
    rms_final: float
    iterations: int


def _project_with_jacobian(H: np.ndarray, p: np.ndarray):
    """pi(H p) for (N, 2) points p and d pi(y) / d y at y = H p, (N, 2, 3)."""
    y = np.column_stack([p, np.ones(len(p))]) @ H.T
    q = y[:, :2] / y[:, 2:]
    D = np.zeros((len(p), 2, 3))
    D[:, 0, 0] = D[:, 1, 1] = 1 / y[:, 2]
    D[:, :, 2] = -q / y[:, 2:]
    return q, D


def correct_points(
    H: ArrayLike, src: ArrayLike, dst: ArrayLike, iterations: int = 10
) -> np.ndarray:
    r"""The points :math:`\hat x_i` minimising :math:`d(x_i, \hat x_i)^2 + d(x'_i, \pi(H \hat x_i))^2` for a fixed H.

    Each pair is a separate 2-parameter least-squares problem; Gauss-Newton from
    :math:`\hat x_i = x_i`, all pairs at once: with :math:`r_i = (\hat x_i - x_i,\ \pi(H\hat x_i) - x'_i)`
    and :math:`J_i = (I_2;\ D_i H_{:, :2})`, where :math:`D_i = \partial\pi/\partial y`,
    the step is :math:`-(J_i^T J_i)^{-1} J_i^T r_i`. The problem is nearly linear (a
    homography is locally affine), so a few steps reach the minimum to rounding.

    Returns
    -------
    (N, 2) ndarray
        The corrected source points; their images :math:`\pi(H \hat x_i)` are the corrected
        destination points.

    Parameters
    ----------
    H : (3, 3) array_like
        The homography, dst ~ H src.
    src, dst : (N, 2) array_like
        Measured pairs, pixels.
    iterations : int, optional
        Gauss-Newton steps (default 10).
    """
    Hm = check_homography(H)
    s, d = check_correspondences(src, dst, min_count=1)
    p = s.copy()
    for _ in range(int(iterations)):
        q, D = _project_with_jacobian(Hm, p)
        Jq = D @ Hm[:, :2]  # d pi(H p) / d p, (N, 2, 2)
        normal = np.eye(2) + np.einsum("nki,nkj->nij", Jq, Jq)
        grad = (p - s) + np.einsum("nki,nk->ni", Jq, q - d)
        p = p - np.linalg.solve(normal, grad[..., None])[..., 0]
    return p


class _GoldNormal(NamedTuple):
    """The normal equations of the Gold Standard problem in blocks.

    U (8, 8) for h, V (N, 2, 2) for the corrected points (block diagonal), W (N, 8, 2) coupling
    them.
    """

    U: np.ndarray
    V: np.ndarray
    W: np.ndarray

    def diagonal(self) -> np.ndarray:
        return np.concatenate([np.diag(self.U), np.einsum("nii->ni", self.V).ravel()])


def _gold_normal_equations(J, r):
    Jh, Jp = J  # d r2 / d h (N, 2, 8) and d r2 / d p (N, 2, 2); d r1 / d p = I
    n = len(Jh)
    r1, r2 = r[: 2 * n].reshape(n, 2), r[2 * n :].reshape(n, 2)
    U = np.einsum("nki,nkj->ij", Jh, Jh)
    V = np.eye(2) + np.einsum("nki,nkj->nij", Jp, Jp)
    W = np.einsum("nki,nkj->nij", Jh, Jp)
    g = np.concatenate(
        [np.einsum("nki,nk->i", Jh, r2), (r1 + np.einsum("nki,nk->ni", Jp, r2)).ravel()]
    )
    return _GoldNormal(U, V, W), g


def _gold_damped_solve(A: _GoldNormal, g: np.ndarray, mu: float) -> np.ndarray:
    r"""Solve the damped normal equations by the Schur complement (H&Z §A6.3).

    Eliminate the points' 2 x 2 blocks, solve 8 x 8 for h, back-substitute; O(N) instead of O(N^3).
    """
    n = len(A.V)
    U = A.U + mu * np.diag(np.maximum(np.diag(A.U), 1e-300))
    V = A.V + mu * np.einsum("nii->ni", A.V)[..., None] * np.eye(2)
    gh, gp = g[:8], g[8:].reshape(n, 2)
    Vinv = np.linalg.inv(V)
    WVinv = A.W @ Vinv  # (N, 8, 2)
    S = U - np.einsum("nij,nkj->ik", WVinv, A.W)
    dh = np.linalg.solve(S, -gh + np.einsum("nij,nj->i", WVinv, gp))
    dp = -np.einsum("nij,nj->ni", Vinv, gp + np.einsum("nji,j->ni", A.W, dh))
    return np.concatenate([dh, dp.ravel()])


def gold_standard_homography(
    H: ArrayLike, src: ArrayLike, dst: ArrayLike, max_iters: int = 50, tol: float = 1e-10
) -> GoldStandardResult:
    r"""The Gold Standard (maximum-likelihood) homography of Hartley & Zisserman, algorithm 4.3.

    With Gaussian noise on the points of *both* images, the most likely H minimises the
    reprojection error over H and corrected points :math:`\hat x_i`,

    .. math:: \sum_i d(x_i, \hat x_i)^2 + d(x'_i, \hat x'_i)^2, \qquad \hat x'_i = H \hat x_i,

    so 8 + 2N parameters (H&Z §4.2.3, eq. 4.8). This is not the symmetric transfer error of
    :func:`refine_homography`, which compares each measured point with the image of the
    other measured point. Levenberg-Marquardt (:func:`camlab.optimise.levenberg_marquardt`)
    steps h on the unit sphere and each :math:`\hat x_i` in the plane, starting from ``H``
    (typically the normalised DLT) and :func:`correct_points`. Each residual pair touches h
    and one :math:`\hat x_i` only, so the normal equations are solved by eliminating the
    points first (the sparse LM of H&Z §A6.3): 8 x 8 plus N 2 x 2 systems.

    Parameters
    ----------
    H : (3, 3) array_like
        Starting homography (invertible), typically :func:`estimate_homography`.
    src, dst : (N, 2) array_like
        Corresponding pixel coordinates (inliers), N >= 4.
    max_iters : int
        Maximum LM steps (accepted or rejected).
    tol : float
        Stop when the relative cost decrease of an accepted step is below ``tol``.

    Returns
    -------
    GoldStandardResult
        ``H``, ``src_corrected``, ``dst_corrected``, ``rms_initial`` (the starting H with its
        best corrected points) and ``rms_final`` in pixels, ``iterations``.

    Raises
    ------
    ConvergenceError
        If the starting H maps a point to infinity.

    References
    ----------
    Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., §4.2.3 (reprojection error, both
    images), algorithm 4.3 (§4.5, the Gold Standard); the sparse Levenberg-Marquardt of §A6.3.
    """
    h = check_homography(H).ravel().copy()
    h /= np.linalg.norm(h)
    s, d = check_correspondences(src, dst)
    n = len(s)

    def residuals(x: np.ndarray) -> np.ndarray:
        Hx, p = x[:9].reshape(3, 3), x[9:].reshape(n, 2)
        with np.errstate(divide="ignore", invalid="ignore"):
            q = _project_with_jacobian(Hx, p)[0]
        return np.concatenate([(p - s).ravel(), (q - d).ravel()])

    def jacobian(x: np.ndarray):
        Hx, p = x[:9].reshape(3, 3), x[9:].reshape(n, 2)
        _, D = _project_with_jacobian(Hx, p)
        Ky = np.einsum("ik,nj->nikj", np.eye(3), np.column_stack([p, np.ones(n)])).reshape(n, 3, 9)
        return D @ Ky @ unit_sphere_basis(x[:9]), D @ Hx[:, :2]

    def update(x: np.ndarray, delta: np.ndarray) -> np.ndarray:
        return np.concatenate([unit_sphere_update(x[:9], delta[:8]), x[9:] + delta[8:]])

    x0 = np.concatenate([h, correct_points(h.reshape(3, 3), s, d).ravel()])
    r0 = residuals(x0)
    if not np.all(np.isfinite(r0)):
        raise ConvergenceError(
            "gold_standard_homography: the starting H maps some point to infinity; "
            "start from the DLT"
        )
    lm = levenberg_marquardt(
        residuals,
        x0,
        jacobian,
        update=update,
        normal_equations=_gold_normal_equations,
        damped_solve=_gold_damped_solve,
        max_iter=int(max_iters),
        ftol=tol,
        xtol=1e-14,
        gtol=0.0,
    )
    H_final = lm.x[:9].reshape(3, 3)
    p = lm.x[9:].reshape(n, 2)
    return GoldStandardResult(
        normalise_homography(H_final),
        p,
        map_points(H_final, p),
        float(np.sqrt(r0 @ r0 / (2 * n))),
        float(np.sqrt(2 * lm.cost / (2 * n))),
        lm.iterations,
    )
