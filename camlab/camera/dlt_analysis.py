r"""Why the camera DLT normalises: its raw equations, their conditioning, and the error to expect.

:func:`dlt_matrix` stacks the equations :math:`\tilde u_i \times P \tilde X_i = 0` that
:func:`camlab.camera.estimate_projection_matrix` solves after Hartley normalisation;
:func:`unnormalised_dlt` solves them in raw metres and pixels (the plain DLT lesson 04 compares
with); :func:`dlt_conditioning` measures both systems; :func:`predicted_rms_error` is the pixel error
a least-squares camera is expected to make with a given noise (first-order error propagation).
Part of :mod:`camlab.camera` (every name here is importable from there).

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 4.4 (normalisation),
   section 5.2 (covariance propagation) and section 7.1 (the camera DLT).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, as_point_pairs, check_number
from ..projective import hartley_normalise
from .model import check_camera_matrix


def _pairs(points_world, points_image, min_count=6):
    X, uv, _ = as_point_pairs(
        points_world,
        points_image,
        ("points_world", "points_image"),
        (3, 2),
        min_count=min_count,
        why="P has 11 degrees of freedom and each point gives 2 equations; add more points",
    )
    return X, uv


def dlt_matrix(points_world: ArrayLike, points_image: ArrayLike) -> np.ndarray:
    r"""The DLT's equations for P in the coordinates given: A (2N x 12) with :math:`A p = 0`.

    Each pair gives two rows of :math:`\tilde u \times P \tilde X = 0` (H&Z 7.1 [1]_):
    :math:`(\tilde X^\top, 0^\top, -u \tilde X^\top)` and :math:`(0^\top, \tilde X^\top, -v \tilde X^\top)`,
    p being P's rows stacked. The N first rows are the u equations, the N last the v ones.

    Parameters
    ----------
    points_world : (N, 3) array_like
        World points, N >= 6.
    points_image : (N, 2) array_like
        Their pixels (u, v).

    Returns
    -------
    (2N, 12) ndarray
        The matrix A, unnormalised: its entries mix 1 with products such as u X.

    Raises
    ------
    CamlabInputError
        Fewer than 6 pairs, different counts or wrong shapes.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 7.1 (the camera DLT).
    """
    X, uv = _pairs(points_world, points_image)
    Xh, zero = np.column_stack([X, np.ones(len(X))]), np.zeros((len(X), 4))
    return np.vstack(
        [np.hstack([Xh, zero, -uv[:, :1] * Xh]), np.hstack([zero, Xh, -uv[:, 1:] * Xh])]
    )


def unnormalised_dlt(points_world: ArrayLike, points_image: ArrayLike) -> np.ndarray:
    """The plain DLT: P from the SVD null vector of :func:`dlt_matrix` in raw metres and pixels.

    The same recipe as :func:`camlab.camera.estimate_projection_matrix` without Hartley's
    normalisation [1]_, so its answer depends on the units and origins the data come in.

    Parameters
    ----------
    points_world : (N, 3) array_like
        World points, N >= 6, not coplanar.
    points_image : (N, 2) array_like
        Their pixels (u, v).

    Returns
    -------
    (3, 4) ndarray
        P with unit Frobenius norm (its sign is the SVD's).

    Raises
    ------
    CamlabInputError
        Fewer than 6 pairs, different counts or wrong shapes.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 4.4.4 (normalisation is essential).
    """
    return np.linalg.svd(dlt_matrix(points_world, points_image))[2][-1].reshape(3, 4)


def dlt_conditioning(points_world: ArrayLike, points_image: ArrayLike) -> dict[str, float]:
    r"""How sharply A fixes its null vector, raw and normalised: :math:`\sigma_1 / \sigma_{11}` of A.

    The 12th singular value is the noise's; the ratio of the largest to the 11th says how far a
    small change of A can turn the null vector. Hartley normalisation [1]_ (centroid 0, mean distance
    :math:`\sqrt 3` for the world points and :math:`\sqrt 2` for the pixels) brings it near 1.

    Parameters
    ----------
    points_world : (N, 3) array_like
        World points, N >= 6.
    points_image : (N, 2) array_like
        Their pixels (u, v).

    Returns
    -------
    dict
        ``{"pixels and metres": ratio, "normalised": ratio}``.

    Raises
    ------
    CamlabInputError
        Fewer than 6 pairs, different counts or wrong shapes.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 4.4.4 and section 7.1.
    """
    X, uv = _pairs(points_world, points_image)
    Xn, _ = hartley_normalise(X, "points_world")
    un, _ = hartley_normalise(uv, "points_image")
    ratios = {}
    for name, (world, image) in (("pixels and metres", (X, uv)), ("normalised", (Xn, un))):
        s = np.linalg.svd(dlt_matrix(world, image), compute_uv=False)
        ratios[name] = float(s[0] / s[-2])
    return ratios


def _pixels(P, X):
    x = np.column_stack([X, np.ones(len(X))]) @ P.T
    with np.errstate(divide="ignore", invalid="ignore"):
        return x[:, :2] / x[:, 2:3]


def predicted_rms_error(
    P: ArrayLike, points_world: ArrayLike, sigma: float, points_test: ArrayLike
) -> float:
    r"""The RMS pixel error at ``points_test`` expected of a least-squares camera fitted to ``points_world``.

    First-order covariance propagation (H&Z 5.2 [1]_): with J the Jacobian of the fitted pixels
    with respect to P's 12 entries (P normalised to unit norm), restricted to the 11 directions B
    orthogonal to P (the scale direction moves no pixel), the estimate's covariance is
    :math:`\Sigma_p = \sigma^2 B (B^\top J^\top J B)^{-1} B^\top`, and a test point's pixels have
    covariance :math:`J_t \Sigma_p J_t^\top`. Returns the square root of the mean trace. (A
    pseudo-inverse of :math:`J^\top J` with a relative cut-off would drop real directions: in
    metres and pixels its eigenvalues span 20 orders of magnitude.)

    Parameters
    ----------
    P : (3, 4) array_like
        The true camera.
    points_world : (N, 3) array_like
        The points the camera is fitted to.
    sigma : float
        Pixel noise per coordinate, pixels.
    points_test : (M, 3) array_like
        The points where the error is measured (points not fitted).

    Returns
    -------
    float
        The expected RMS distance, pixels, between the fitted and the true camera's pixels.

    Raises
    ------
    CamlabInputError
        A P that is not 3 x 4 or a negative ``sigma``.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 5.2 (covariance propagation).
    """
    p0 = check_camera_matrix(P).ravel()
    p0 = p0 / np.linalg.norm(p0)
    sigma = check_number(sigma, "sigma", "pixels")
    if sigma < 0:
        raise CamlabInputError(
            f"sigma: expected a noise level >= 0 pixels, got {sigma!r}; pass its absolute value"
        )

    def jacobian(points):
        points = np.asarray(points, dtype=float).reshape(-1, 3)
        J, h = np.zeros((2 * len(points), 12)), 1e-7
        for k in range(12):
            d = np.zeros(12)
            d[k] = h
            J[:, k] = (
                _pixels((p0 + d).reshape(3, 4), points) - _pixels((p0 - d).reshape(3, 4), points)
            ).ravel() / (2 * h)
        return J

    J, J_test = jacobian(points_world), jacobian(points_test)
    B = np.linalg.svd(p0[None, :])[2][1:].T  # (12, 11): the directions that change the camera
    JB = J @ B
    cov = sigma**2 * B @ np.linalg.inv(JB.T @ JB) @ B.T
    return float(np.sqrt(np.trace(J_test @ cov @ J_test.T) / len(J_test) * 2))
