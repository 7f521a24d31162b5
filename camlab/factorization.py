r"""Tomasi-Kanade factorisation: shape and motion from many affine views with one SVD.

m affine cameras :math:`u_{ij} = M_i X_j + t_i` (:math:`M_f` 2 x 3, lesson 05) see N points.
Stack every view's image coordinates into the 2m x N *measurement matrix*
:math:`W` (rows :math:`u` then :math:`v` of view 1, of view 2, ...; one column per point).
Subtract each row's mean: the mean of the images is the image of the points' centroid
(an affine camera maps means to means), so with the world origin at the centroid
:math:`t_i` drops out and

.. math::

    \hat W = \begin{pmatrix} M_1 \\ \vdots \\ M_m \end{pmatrix}
             \begin{pmatrix} X_1 & \cdots & X_N \end{pmatrix} = \hat M \hat S ,

a product of a 2m x 3 and a 3 x N matrix: **rank 3**, however many views and points. With
noise, the SVD :math:`\hat W = U \Sigma V^\top` gives the closest rank-3 matrix (Eckart-Young),
:math:`\hat M = U_3 \Sigma_3^{1/2}`, :math:`\hat S = \Sigma_3^{1/2} V_3^\top`, the
maximum-likelihood affine reconstruction under isotropic Gaussian pixel noise. It is
unique up to an affine map of space, :math:`\hat M A^{-1} \cdot A \hat S`; metric
constraints on the cameras (orthonormal rows) fix A up to a similarity, beyond this
module. The fourth singular value onwards measure what no affine camera explains:
noise, and perspective.

Conventions (docs/conventions.md): pixels (u, v) = (column, row); points are rows.

References
----------
C. Tomasi and T. Kanade, "Shape and motion from image streams under orthography: a
factorization method", *IJCV* 9(2), 1992. R. Hartley and A. Zisserman, *Multiple View
Geometry*, 2nd ed., section 18.2 (algorithm 18.1).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._validate import CamlabInputError, check_finite

__all__ = ["AffineReconstruction", "affine_factorization", "rank3_reprojection"]


class AffineReconstruction(NamedTuple):
    """Affine cameras and points from :func:`affine_factorization`."""

    cameras: np.ndarray
    """(m, 3, 4) affine cameras :math:`[M_i \\mid t_i]` over the last row (0, 0, 0, 1)."""
    points: np.ndarray
    """(N, 3) points, centroid at the origin, up to one affine map of space."""
    singular_values: np.ndarray
    """All singular values of the centred measurement matrix, largest first, pixels."""
    rms: float
    """RMS reprojection error of the rank-3 fit, pixels per coordinate (times sqrt(2): per point, the 2-D distance)."""


def affine_factorization(tracks: ArrayLike) -> AffineReconstruction:
    r"""Recover affine cameras and 3-D points from N points tracked through m >= 2 views.

    Derivation: the module docstring (H&Z algorithm 18.1). The steps:

    1. :math:`t_i` = the mean of view i's points (the image of the centroid);
    2. :math:`\hat W` = the 2m x N matrix of the centred coordinates;
    3. SVD; keep three singular values: :math:`\hat M = U_3 \Sigma_3^{1/2}`,
       :math:`\hat S = \Sigma_3^{1/2} V_3^\top` (the split of :math:`\Sigma_3` is one choice
       of the affine ambiguity).

    Parameters
    ----------
    tracks : (m, N, 2) array_like
        Pixel (u, v) of point j in view i; every point seen in every view, N >= 4.

    Returns
    -------
    AffineReconstruction
        The cameras, the points, every singular value and the RMS reprojection error.

    Raises
    ------
    CamlabInputError
        If ``tracks`` is not a finite (m, N, 2) array with m >= 2 and N >= 4.

    References
    ----------
    Tomasi & Kanade, *IJCV* 9(2), 1992; Hartley & Zisserman, *Multiple View Geometry*, 2nd
    ed., section 18.2, algorithm 18.1.

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> X = rng.normal(size=(20, 3))
    >>> M = rng.normal(size=(4, 2, 3))
    >>> fit = affine_factorization(np.einsum("fij,nj->fni", M, X) + 100.0)
    >>> fit.rms < 1e-9, bool(fit.singular_values[3] < 1e-9 * fit.singular_values[0])
    (True, True)
    """
    W = np.asarray(tracks, dtype=float)
    if W.ndim != 3 or W.shape[2] != 2 or W.shape[0] < 2 or W.shape[1] < 4:
        raise CamlabInputError(
            f"tracks: expected (m, N, 2) pixels of N >= 4 points in m >= 2 views, got shape {W.shape}; "
            "stack each view's (N, 2) points: np.stack([uv_view1, uv_view2, ...])"
        )
    check_finite(W, "tracks")
    views, count = W.shape[:2]
    t = W.mean(axis=1)  # (m, 2): each view's image of the centroid
    centred = (
        (W - t[:, None, :]).transpose(0, 2, 1).reshape(2 * views, count)
    )  # rows u1, v1, u2, ...
    U, s, Vt = np.linalg.svd(centred, full_matrices=False)
    root = np.sqrt(s[:3])
    motion, shape = U[:, :3] * root, root[:, None] * Vt[:3]
    cameras = np.zeros((views, 3, 4))
    cameras[:, :2, :3] = motion.reshape(views, 2, 3)
    cameras[:, :2, 3] = t
    cameras[:, 2, 3] = 1.0
    rms = float(
        np.sqrt(np.sum(s[3:] ** 2) / centred.size)
    )  # Eckart-Young: the dropped singular values
    return AffineReconstruction(cameras, shape.T, s, rms)


def rank3_reprojection(tracks: ArrayLike) -> np.ndarray:
    r"""The tracks as the rank-3 affine model sees them: every point reprojected by every fitted camera.

    :math:`\hat u_{ij} = \hat M_i \hat X_j + t_i` from :func:`affine_factorization`: the closest
    tracks (least squares over all pixels) that m affine cameras and N points can produce. Unlike the
    cameras and points, which are fixed only up to an affine map of space, this is unique (when the
    third singular value exceeds the fourth), so lesson 05's exercise checks it.

    Parameters
    ----------
    tracks : (m, N, 2) array_like
        Pixel (u, v) of point j in view i, as for :func:`affine_factorization`.

    Returns
    -------
    (m, N, 2) ndarray
        The reprojected pixels; ``tracks`` minus it is the part no affine camera explains.

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> exact = np.einsum("fij,nj->fni", rng.normal(size=(4, 2, 3)), rng.normal(size=(20, 3)))
    >>> bool(np.allclose(rank3_reprojection(exact), exact))
    True
    """
    fit = affine_factorization(tracks)
    return (
        np.einsum("fij,nj->fni", fit.cameras[:, :2, :3], fit.points) + fit.cameras[:, None, :2, 3]
    )
