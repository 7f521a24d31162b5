r"""The two small derivatives every refiner in camlab shares.

Calibration (:mod:`camlab.calibration.refinement`), pose (:mod:`camlab.measurement.pnp`) and
bundle adjustment (:mod:`camlab.stitching.bundle_jacobian`) all differentiate a pinhole
projection of a rotated point, so they all need

* the cross-product matrix :math:`[w]_\times` (a small turn :math:`\delta` on the left moves a
  point :math:`X` by :math:`[\delta]_\times X = -[X]_\times \delta`), and
* the Jacobian of the perspective division :math:`\pi(p) = (p_1 / p_3,\; p_2 / p_3)`:

.. math:: \frac{\partial \pi}{\partial p} = \frac{1}{p_3}
          \begin{pmatrix} 1 & 0 & -p_1/p_3 \\ 0 & 1 & -p_2/p_3 \end{pmatrix}.

Both take stacks of vectors, because the refiners evaluate them for every point at every
iteration.
"""

from __future__ import annotations

import numpy as np

__all__ = ["cross_matrix", "division_jacobian"]


def cross_matrix(w: np.ndarray) -> np.ndarray:
    r"""The cross-product matrices :math:`[w]_\times` of a stack of 3-vectors.

    Parameters
    ----------
    w : (..., 3) ndarray
        The vectors.

    Returns
    -------
    (..., 3, 3) ndarray
        ``out[k] @ v == np.cross(w[k], v)``.

    >>> cross_matrix(np.array([1.0, 2.0, 3.0])) @ np.array([4.0, 5.0, 6.0])
    array([-3.,  6., -3.])
    """
    w = np.asarray(w, dtype=float)
    out = np.zeros(w.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2] = -w[..., 2], w[..., 1]
    out[..., 1, 0], out[..., 1, 2] = w[..., 2], -w[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -w[..., 1], w[..., 0]
    return out


def division_jacobian(p: np.ndarray) -> np.ndarray:
    r"""The Jacobians :math:`\partial \pi / \partial p` of the perspective division at a stack of points.

    Parameters
    ----------
    p : (..., 3) ndarray
        Homogeneous points (or camera-frame points), third entry non-zero.

    Returns
    -------
    (..., 2, 3) ndarray
        Row 0 differentiates :math:`p_1 / p_3`, row 1 :math:`p_2 / p_3`.

    >>> division_jacobian(np.array([2.0, 4.0, 2.0]))
    array([[ 0.5,  0. , -0.5],
           [ 0. ,  0.5, -1. ]])
    """
    p = np.asarray(p, dtype=float)
    inv_z = 1.0 / p[..., 2]
    out = np.zeros(p.shape[:-1] + (2, 3))
    out[..., 0, 0] = out[..., 1, 1] = inv_z
    out[..., :, 2] = -p[..., :2] * (inv_z**2)[..., None]
    return out
