r"""Hartley's conditioning.

The similarity that centres points and scales them to unit size before a direct linear transform
(DLT) [1]_ [2]_, so that the DLT's matrix is well conditioned.

Used by camlab's DLT estimators (homographies, fundamental matrices, projection matrices)
and by :func:`camlab.projective.vanishing_point`.

References
----------
.. [1] R. I. Hartley, 1997, "In defense of the eight-point algorithm", *IEEE Transactions on Pattern
   Analysis and Machine Intelligence* 19(6), 580-593.
.. [2] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 4.4.4 (normalising
   transformations).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import DegenerateError, as_points

__all__ = [
    "HartleyNormalised",
    "hartley_normalise",
]


class HartleyNormalised(NamedTuple):
    r"""(N, D) points after Hartley's conditioning, and the (D + 1, D + 1) similarity T that did it.

    Attributes
    ----------
    points : (N, D) ndarray
        Centred, mean distance :math:`\sqrt D`.
    T : (D + 1, D + 1) ndarray
        :math:`\tilde x_n = T \tilde x`; undo a DLT estimate with :math:`T^{-1}`.
    """

    points: np.ndarray
    T: np.ndarray


def hartley_normalise(points: ArrayLike, name: str = "points") -> HartleyNormalised:
    r"""Hartley's similarity T that centres (N, D) points and scales their mean distance to :math:`\sqrt D`, and the points it makes.

    .. math:: T = \begin{pmatrix} s I_D & -s \bar x \\ 0^\top & 1 \end{pmatrix},
              \quad s = \frac{\sqrt D}{\operatorname{mean}_i \| x_i - \bar x \|}

    After the mapping, coordinates are of order 1, so the entries of a DLT matrix
    (products of coordinates such as :math:`u u'`) are of similar size and its SVD is well
    conditioned [1]_ [2]_. Image points (D = 2) end at
    mean distance :math:`\sqrt 2`, world points (D = 3) at :math:`\sqrt 3`.

    Parameters
    ----------
    points : (N, D) array_like
        D = 2 (image) or 3 (world), Euclidean.
    name : str
        The argument's name in error messages.

    Returns
    -------
    HartleyNormalised
        ``(points, T)``: the normalised (N, D) points :math:`T \tilde x`, and T, the
        (D + 1, D + 1) similarity acting on homogeneous points. Take ``.T`` when only the
        similarity is wanted.

    Raises
    ------
    DegenerateError
        All points coincide (nothing to scale).

    References
    ----------
    .. [1] R. I. Hartley, 1997, "In defense of the eight-point algorithm", *IEEE Transactions
       on Pattern Analysis and Machine Intelligence* 19(6), 580-593.
    .. [2] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 4.4.4 and algorithm
       4.2 (normalised DLT), algorithm 7.1.

    Examples
    --------
    >>> pn, T = hartley_normalise([[0, 0], [2, 0], [2, 2], [0, 2]])
    >>> pn
    array([[-1., -1.],
           [ 1., -1.],
           [ 1.,  1.],
           [-1.,  1.]])
    >>> from camlab.projective import map_points
    >>> map_points(T, [[0, 0], [2, 2]]).round(6)
    array([[-1., -1.],
           [ 1.,  1.]])
    """
    p = as_points(points, (2, 3), name).array
    d = p.shape[1]
    c = p.mean(axis=0)
    spread = np.mean(np.linalg.norm(p - c, axis=1))
    if spread == 0:
        raise DegenerateError(
            f"{name}: all points coincide, so they cannot be normalised; use distinct points"
        )
    s = np.sqrt(d) / spread
    T = np.eye(d + 1)
    T[:d, :d] *= s
    T[:d, d] = -s * c
    return HartleyNormalised(p * T[0, 0] + T[:d, d], T)
