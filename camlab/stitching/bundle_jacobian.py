r"""The analytic Jacobian of the rotation model's transfer errors (bundle adjustment's derivatives).

:func:`camlab.stitching.bundle_adjust` minimises the transfer errors of every match
:math:`x_i \leftrightarrow x_j` of every pair of images,

.. math:: e = \pi(p) - x_j, \qquad p = K_j R_j R_i^\top K_i^{-1} \tilde x_i, \qquad
          \pi(p) = (p_1 / p_3,\; p_2 / p_3),

over each camera's focal :math:`f_k` (:math:`K_k` has :math:`f_k` in both diagonal places)
and rotation. Each error touches two cameras only, so its row of the Jacobian has two
non-zero blocks. The derivation, as in Brown & Lowe [1]_ (section 4) and OpenCV's
``detail::BundleAdjusterReproj``, with :math:`r = K_i^{-1}\tilde x_i`,
:math:`q = R_j R_i^\top r`, :math:`M = K_j R_j R_i^\top` (so :math:`p = K_j q = M r`) and
:math:`E = \mathrm{diag}(1, 1, 0) = \partial K / \partial f`:

* the projection: :math:`\partial \pi / \partial p = \frac{1}{p_3}
  \begin{pmatrix} 1 & 0 & -p_1/p_3 \\ 0 & 1 & -p_2/p_3 \end{pmatrix}`;
* turn camera j a little, :math:`R_j \leftarrow \exp([\delta]_\times) R_j \approx (I +
  [\delta]_\times) R_j`: :math:`p` changes by :math:`K_j [\delta]_\times q = -K_j [q]_\times
  \delta`;
* turn camera i a little: :math:`R_i^\top \leftarrow R_i^\top (I - [\delta]_\times)`, so
  :math:`p` changes by :math:`-M [\delta]_\times r = M [r]_\times \delta`;
* the focal of j: :math:`\partial p / \partial f_j = E q`; of i, from
  :math:`\partial K^{-1} = -K^{-1} (\partial K) K^{-1}`:
  :math:`\partial p / \partial f_i = -M K_i^{-1} E r`.

The adjustment stores each rotation as a rotation vector :math:`\omega` applied on the left of
its start, :math:`R = \exp([\omega]_\times) R^{(0)}`; a change :math:`d\omega` turns it by
:math:`\delta = J_l(\omega)\, d\omega` (:func:`left_jacobian`), so
:math:`\partial e / \partial \omega = (\partial e / \partial \delta)\, J_l(\omega)`.
``tests/test_stitching_bundle_jacobian.py`` checks all of it against central differences.

References
----------
.. [1] M. Brown and D. G. Lowe, 2007, "Automatic panoramic image stitching using invariant
   features", *International Journal of Computer Vision* 74(1), 59-73.
.. [2] J. Sola, J. Deray and D. Atchuthan, 2018, "A micro Lie theory for state estimation in
   robotics", arXiv:1812.01537, equation (145) (the left Jacobian of SO(3)).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import as_points, check_matrix
from ..camera import cross_matrix, division_jacobian

__all__ = [
    "PairJacobians",
    "homography_transfer_jacobians",
    "left_jacobian",
    "transfer_error_jacobians",
]


class PairJacobians(NamedTuple):
    """The derivatives of one pair's transfer errors with respect to each image's parameters.

    ``d_i`` (N, 2, n_i) for image i (the matches' source), ``d_j`` (N, 2, n_j) for image j.
    """

    d_i: np.ndarray
    d_j: np.ndarray


_E = np.diag([1.0, 1.0, 0.0])  # dK/df when f sits in both diagonal places


def left_jacobian(w: ArrayLike) -> np.ndarray:
    r"""The left Jacobian of SO(3): :math:`\exp([w + dw]_\times) \approx \exp([J_l(w)\,dw]_\times)\exp([w]_\times)`.

    .. math:: J_l(w) = I + \frac{1 - \cos\theta}{\theta^2} [w]_\times
              + \frac{\theta - \sin\theta}{\theta^3} [w]_\times^2, \qquad \theta = \|w\|,

    with the series :math:`I + \tfrac12 [w]_\times + \tfrac16 [w]_\times^2` near
    :math:`\theta = 0`, where the fractions lose their digits.

    Parameters
    ----------
    w : (3,) array_like
        Rotation vector (axis times angle, radians).

    Returns
    -------
    (3, 3) ndarray

    >>> np.allclose(left_jacobian([0.0, 0.0, 0.0]), np.eye(3))
    True
    """
    w = check_matrix(w, (3,), "w")
    theta = float(np.linalg.norm(w))
    W = cross_matrix(w)
    if theta < 1e-5:
        return np.eye(3) + W / 2 + W @ W / 6
    return (
        np.eye(3)
        + (1 - np.cos(theta)) / theta**2 * W
        + (theta - np.sin(theta)) / theta**3 * (W @ W)
    )


def transfer_error_jacobians(
    K_i: ArrayLike, R_i: ArrayLike, K_j: ArrayLike, R_j: ArrayLike, x_i: ArrayLike
) -> PairJacobians:
    r"""Derivatives of the transfer errors :math:`\pi(K_j R_j R_i^\top K_i^{-1} x_i) - x_j`.

    With respect to each camera's focal and a small turn :math:`\delta` on the left of its
    rotation (the module docstring derives every term).

    Parameters
    ----------
    K_i, R_i, K_j, R_j : (3, 3) array_like
        The two cameras (cam_from_world rotations).
    x_i : (N, 2) array_like
        The matches' pixels in image i (the errors do not depend on x_j's derivatives).

    Returns
    -------
    PairJacobians
        ``d_i``, ``d_j``: (N, 2, 4); ``d_k[n, :, 0]`` = d e_n / d f_k and
        ``d_k[n, :, 1:]`` = d e_n / d delta_k.
    """
    K_i, R_i, K_j, R_j = (
        check_matrix(m, (3, 3), name)
        for m, name in ((K_i, "K_i"), (R_i, "R_i"), (K_j, "K_j"), (R_j, "R_j"))
    )
    x = as_points(x_i, 2, "x_i").array
    K_i_inv = np.linalg.inv(K_i)
    r = np.c_[x, np.ones(len(x))] @ K_i_inv.T
    q = r @ (R_j @ R_i.T).T
    M = K_j @ R_j @ R_i.T
    p = q @ K_j.T
    dpi = division_jacobian(p)
    dp_i = np.concatenate([-(r @ _E.T @ K_i_inv.T @ M.T)[:, :, None], M @ cross_matrix(r)], axis=2)
    dp_j = np.concatenate([(q @ _E.T)[:, :, None], -K_j @ cross_matrix(q)], axis=2)
    return PairJacobians(dpi @ dp_i, dpi @ dp_j)


def homography_transfer_jacobians(H_i: ArrayLike, H_j: ArrayLike, x_i: ArrayLike) -> PairJacobians:
    r"""Derivatives of the planar model's transfer errors :math:`\pi(H_j^{-1} H_i x_i) - x_j`.

    With :math:`G = H_j^{-1}`, :math:`s = H_i \tilde x_i` and :math:`p = G s`: entry
    :math:`(r, c)` of :math:`H_i` moves :math:`p` by :math:`G_{:,r}\, \tilde x_c`; of
    :math:`H_j`, through :math:`\partial G = -G\, (\partial H_j)\, G`, by
    :math:`-G_{:,r}\, p_c`. Only the first eight entries are parameters (:math:`h_{33} = 1`).

    Parameters
    ----------
    H_i, H_j : (3, 3) array_like
        The two images' homographies onto the reference.
    x_i : (N, 2) array_like
        The matches' pixels in image i.

    Returns
    -------
    PairJacobians
        ``d_i``, ``d_j``: (N, 2, 8), with respect to ``H_i.ravel()[:8]`` and ``H_j.ravel()[:8]``.
    """
    H_i, H_j = check_matrix(H_i, (3, 3), "H_i"), check_matrix(H_j, (3, 3), "H_j")
    x = np.c_[as_points(x_i, 2, "x_i").array, np.ones(len(x_i))]
    G = np.linalg.inv(H_j)
    p = x @ (G @ H_i).T
    dpi = division_jacobian(p)
    dp_i = np.einsum("kr,nc->nkrc", G, x).reshape(len(x), 3, 9)[:, :, :8]
    dp_j = -np.einsum("kr,nc->nkrc", G, p).reshape(len(x), 3, 9)[:, :, :8]
    return PairJacobians(dpi @ dp_i, dpi @ dp_j)
