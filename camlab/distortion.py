r"""Lens distortion: the Brown-Conrady model in OpenCV's coefficient order.

A real lens bends straight lines. In *normalised* image coordinates
:math:`x = X_c / Z_c,\ y = Y_c / Z_c` (the pinhole image before K is applied) the model
moves an ideal point :math:`(x, y)` to the distorted point

.. math::

    r^2 &= x^2 + y^2, \qquad L(r) = 1 + k_1 r^2 + k_2 r^4 + k_3 r^6 \\
    x_d &= x L(r) + 2 p_1 x y + p_2 (r^2 + 2 x^2) \\
    y_d &= y L(r) + p_1 (r^2 + 2 y^2) + 2 p_2 x y

with ``dist = (k1, k2, p1, p2, k3)``, the order ``cv2.projectPoints`` uses. Pixels follow
as :math:`u = f_x x_d + s\, y_d + c_x,\ v = f_y y_d + c_y`; pixel (u, v) = (column, row)
with the origin at the centre of the top-left pixel, images indexed ``img[v, u]``.

Undistortion has no closed form: :func:`undistort_points` inverts the model with Newton's
method and raises :class:`~camlab.ConvergenceError` rather than return garbage where the
model folds over (beyond :func:`max_valid_radius`). See lesson 02, section 3.
"""

from __future__ import annotations

import functools
from functools import lru_cache
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._validate import (
    CamlabInputError,
    ConvergenceError,
    as_float,
    as_points,
    check_finite,
    check_image,
    check_intrinsics,
    check_size,
)

__all__ = [
    "DistortionMaps",
    "NewtonUndistort",
    "as_dist",
    "beyond_valid_radius",
    "classify_distortion",
    "distort_pixels",
    "distort_points",
    "distortion_jacobian",
    "distortion_jacobian_unchecked",
    "max_valid_radius",
    "newton_undistort",
    "normalised_to_pixels",
    "pixels_to_normalised",
    "radial_scale",
    "undistort_image",
    "undistort_map",
    "undistort_pixels",
    "undistort_points",
    "distort_map",
    "distort_xy",
    "DistortedXY",
]


def as_dist(dist: ArrayLike | None, name: str = "dist") -> np.ndarray:
    """Return distortion coefficients as a float (5,) array ``(k1, k2, p1, p2, k3)``.

    ``None`` means no distortion; 4 coefficients ``(k1, k2, p1, p2)`` get ``k3 = 0``.

    Parameters
    ----------
    dist : (5,) or (4,) array_like or None
        ``(k1, k2, p1, p2[, k3])`` in OpenCV's order; None for no distortion.
    name : str, optional
        The argument's name in error messages (default "dist").

    Returns
    -------
    (5,) float ndarray
        ``(k1, k2, p1, p2, k3)``.

    Examples
    --------
    >>> as_dist([0.1, 0, 0, 0])
    array([0.1, 0. , 0. , 0. , 0. ])
    >>> as_dist([1, 2, 3])
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: dist: expected 4 or 5 coefficients (k1, k2, p1, p2[, k3]) in OpenCV's order, got shape (3,)
    """
    if dist is None:
        return np.zeros(5)
    try:
        d = np.array(dist, dtype=float).ravel()
    except (TypeError, ValueError) as exc:
        raise CamlabInputError(
            f"{name}: expected numbers, got {type(dist).__name__} ({exc})"
        ) from None
    if d.size == 4:
        d = np.append(d, 0.0)
    if d.size != 5:
        raise CamlabInputError(
            f"{name}: expected 4 or 5 coefficients (k1, k2, p1, p2[, k3]) in OpenCV's order, "
            f"got shape {np.shape(dist)}"
        )
    return check_finite(d, name)


def _distort(xy: np.ndarray, d: np.ndarray) -> np.ndarray:
    return np.stack(distort_xy(xy[..., 0], xy[..., 1], d), axis=-1)


class DistortedXY(NamedTuple):
    """What :func:`distort_xy` returns: the distorted normalised coordinates ``x``, ``y``."""

    x: np.ndarray
    y: np.ndarray


def distort_xy(x: np.ndarray, y: np.ndarray, d: np.ndarray) -> DistortedXY:
    r"""The Brown-Conrady polynomial on coordinate arrays that broadcast (a column of y, a row of x).

    .. math:: x_d = x L + 2 p_1 x y + p_2 (r^2 + 2 x^2), \quad
              y_d = y L + p_1 (r^2 + 2 y^2) + 2 p_2 x y, \quad
              L = 1 + k_1 r^2 + k_2 r^4 + k_3 r^6, \ r^2 = x^2 + y^2

    The one place camlab evaluates the model (:func:`distort_points`, :func:`distort_map`
    and calibration's projection call it). No checks: ``x``, ``y`` are float arrays of
    normalised coordinates and ``d`` the 5 coefficients ``(k1, k2, p1, p2, k3)`` from
    :func:`as_dist`.

    Parameters
    ----------
    x, y : ndarray
        Ideal normalised coordinates (dimensionless), float arrays that broadcast together.
    d : (5,) ndarray
        ``(k1, k2, p1, p2, k3)`` from :func:`as_dist`.

    Returns
    -------
    DistortedXY
        ``x`` and ``y``, the distorted normalised coordinates, of the broadcast shape.

    References
    ----------
    .. [1] D. C. Brown, 1966, "Decentering distortion of lenses", *Photogrammetric
       Engineering* 32(3), 444-462.
    .. [2] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022, section
       2.1.5 (lens distortions).
    """
    k1, k2, p1, p2, k3 = d
    r2 = x * x + y * y
    radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3))
    xd = x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x)
    yd = y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y
    return DistortedXY(xd, yd)


def distortion_jacobian_unchecked(xy: np.ndarray, d: np.ndarray) -> np.ndarray:
    """:func:`distortion_jacobian` without its checks: for refiners' inner loops (calibration).

    Like :func:`distort_xy`, no checks: ``xy`` is a float array of normalised coordinates and
    ``d`` the 5 coefficients from :func:`as_dist`.

    Parameters
    ----------
    xy : (..., 2) ndarray
        Ideal normalised coordinates (dimensionless).
    d : (5,) ndarray
        ``(k1, k2, p1, p2, k3)`` from :func:`as_dist`.

    Returns
    -------
    (..., 2, 2) ndarray
        d(distorted) / d(ideal) at each point: row i differentiates distorted coordinate i.
    """
    J = np.empty(xy.shape[:-1] + (2, 2))
    J[..., 0, 0], J[..., 0, 1], J[..., 1, 1] = _jacobian_entries(xy[..., 0], xy[..., 1], d)
    J[..., 1, 0] = J[..., 0, 1]
    return J


def _jacobian_entries(x: np.ndarray, y: np.ndarray, d: np.ndarray) -> tuple:
    """d(distorted) / d(ideal) as its entries ``(xx, xy, yy)``: the matrix is symmetric (yx = xy)."""
    k1, k2, p1, p2, k3 = d
    r2 = x * x + y * y
    radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3))
    dradial = k1 + r2 * (2.0 * k2 + 3.0 * k3 * r2)  # d radial / d(r^2)
    xx = radial + 2 * x * x * dradial + 2 * p1 * y + 6 * p2 * x
    xy = 2 * x * y * dradial + 2 * p1 * x + 2 * p2 * y
    yy = radial + 2 * y * y * dradial + 6 * p1 * y + 2 * p2 * x
    return xx, xy, yy


def distort_points(points: ArrayLike, dist: ArrayLike | None) -> np.ndarray:
    r"""Apply Brown-Conrady distortion to normalised image points.

    Parameters
    ----------
    points : (N, 2) or (2,) array_like
        Ideal normalised coordinates :math:`(X_c/Z_c, Y_c/Z_c)` (dimensionless).
    dist : (5,) or (4,) array_like or None
        ``(k1, k2, p1, p2[, k3])`` in OpenCV's order.

    Returns
    -------
    (N, 2) or (2,) ndarray
        Distorted normalised coordinates (see the module docstring for the formula).

    References
    ----------
    .. [1] D. C. Brown, 1966, "Decentering distortion of lenses", *Photogrammetric
       Engineering* 32(3), 444-462.
    .. [2] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022, section
       2.1.5 (lens distortions).

    Examples
    --------
    >>> distort_points([0.5, 0.0], [-0.2, 0, 0, 0, 0])   # barrel pulls points inwards
    array([0.475, 0.   ])
    """
    pts = as_points(points, 2, "points")
    return pts.restore(_distort(pts.array, as_dist(dist)))


def distortion_jacobian(points: ArrayLike, dist: ArrayLike | None) -> np.ndarray:
    """The Jacobian d(distorted) / d(ideal) of the distortion at normalised ``points``.

    Parameters
    ----------
    points : (N, 2) or (2,) array_like
        Ideal normalised coordinates (dimensionless).
    dist : (5,) or (4,) array_like or None
        ``(k1, k2, p1, p2[, k3])`` in OpenCV's order; None for no distortion.

    Returns
    -------
    (N, 2, 2) or (2, 2) ndarray
        One 2x2 Jacobian per point, the input's rank: row i is the derivative of distorted
        coordinate i with respect to (x, y).
    """
    pts = as_points(points, 2, "points")
    return pts.restore(distortion_jacobian_unchecked(pts.array, as_dist(dist)))


def undistort_points(
    points: ArrayLike, dist: ArrayLike | None, *, tol: float = 1e-12, max_iter: int = 30
) -> np.ndarray:
    r"""Invert :func:`distort_points` with Newton's method.

    Solves :math:`\mathrm{distort}(x) = x_d` for :math:`x`, starting from :math:`x = x_d`
    and iterating :math:`x \leftarrow x - J(x)^{-1} (\mathrm{distort}(x) - x_d)`.
    Newton converges quadratically inside the valid field of view; OpenCV's
    ``undistortPoints`` uses a fixed-point iteration instead (slower, and silent when it fails).

    Parameters
    ----------
    points : (N, 2) or (2,) array_like
        Distorted normalised coordinates.
    dist : (5,) or (4,) array_like or None
        ``(k1, k2, p1, p2[, k3])``.
    tol : float
        Convergence threshold on the residual, normalised units (1e-12 is about 1e-9 px
        for f = 800 px).
    max_iter : int
        Newton steps before giving up.

    Returns
    -------
    (N, 2) or (2,) ndarray
        Ideal normalised coordinates.

    Raises
    ------
    ConvergenceError
        If some point does not converge (it lies where the model folds over, beyond
        :func:`max_valid_radius`); the message names how many and the worst residual.

    Examples
    --------
    >>> d = [-0.2, 0.05, 0.001, -0.002, 0.0]
    >>> x = undistort_points(distort_points([0.3, -0.2], d), d)
    >>> np.allclose(x, [0.3, -0.2], atol=1e-12)
    True
    """
    pts = as_points(points, 2, "points")
    d = as_dist(dist)
    target = pts.array
    x, res = newton_undistort(target, d, tol, max_iter)
    bad = ~(res <= max(tol, 1e-9))
    if bad.any():
        i = int(np.argmax(bad))
        r_fold = max_valid_radius(d)
        how_far = (  # inf: Newton diverged, or its root lies beyond the fold, so no inverse was found at all
            "no ideal point found" if not np.isfinite(res[i]) else f"residual {res[i]:.3g} left"
        )
        raise ConvergenceError(
            f"undistort_points: {int(bad.sum())} of {len(bad)} points did not converge "
            f"(first: point {i} = ({target[i][0]:.3g}, {target[i][1]:.3g}), at distorted radius {np.hypot(*target[i]):.3g}: {how_far}); "
            f"they lie outside the valid field of view of dist = {d.tolist()}: the model folds over at ideal radius "
            f"{r_fold:.3g}, which it sends to distorted radius {r_fold * float(radial_scale(r_fold, d)):.3g}, "
            f"so a distorted point farther out has no inverse inside the fold"
        )
    return pts.restore(x)


class NewtonUndistort(NamedTuple):
    """The outcome of :func:`newton_undistort`.

    Attributes
    ----------
    points : (N, 2) ndarray
        Ideal normalised coordinates.
    residual : (N,) ndarray
        max-abs residual per point; inf where Newton failed or landed beyond the model's fold.
    """

    points: np.ndarray
    residual: np.ndarray


def newton_undistort(
    target: np.ndarray, d: np.ndarray, tol: float = 1e-12, max_iter: int = 30
) -> NewtonUndistort:
    """The Newton iterations of :func:`undistort_points`, without raising: check ``residual`` yourself.

    The renderer uses it to find which border pixels have an ideal ray at all.

    Parameters
    ----------
    target : (N, 2) ndarray
        Distorted normalised points.
    d : (5,) ndarray
        ``(k1, k2, p1, p2, k3)`` from :func:`as_dist`.
    tol : float, optional
        Convergence threshold on the max-abs residual, normalised units.
    max_iter : int, optional
        Newton steps before stopping.

    Returns
    -------
    NewtonUndistort
        ``points`` (N, 2), the ideal normalised coordinates, and ``residual`` (N,), max-abs
        residual per point (inf where Newton failed or landed beyond the fold).
    """
    if not d.any():
        return NewtonUndistort(target.copy(), np.zeros(len(target)))
    # x and y as separate contiguous arrays: the step is a 2 x 2 solve per point, written out
    tx, ty = target[:, 0].copy(), target[:, 1].copy()
    x, y = tx.copy(), ty.copy()
    res = np.full(len(x), np.inf)
    for _ in range(max_iter):
        with np.errstate(over="ignore", invalid="ignore"):
            xd, yd = distort_xy(x, y, d)
            rx, ry = xd - tx, yd - ty
            res = np.maximum(np.abs(rx), np.abs(ry))
        if not (res > tol).any():
            break
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            jxx, jxy, jyy = _jacobian_entries(x, y, d)
            det = jxx * jyy - jxy * jxy
            x = x - (jyy * rx - jxy * ry) / det
            y = y - (-jxy * rx + jxx * ry) / det
        x[~np.isfinite(x)] = 1e6
        y[~np.isfinite(y)] = 1e6
    else:
        with np.errstate(over="ignore", invalid="ignore"):
            xd, yd = distort_xy(x, y, d)
            res = np.maximum(np.abs(xd - tx), np.abs(yd - ty))
    res = np.where(np.isfinite(res), res, np.inf)
    # a root beyond the fold (slope of r L(r) <= 0) is not the physical inverse either
    r_fold = _valid_radius(tuple(d.tolist()))  # cached: PnP and Monte Carlo loops reuse one dist
    with np.errstate(over="ignore", invalid="ignore"):
        beyond = np.hypot(x, y) > r_fold
    res[beyond] = np.inf
    return NewtonUndistort(np.column_stack([x, y]), res)


def radial_scale(r: ArrayLike, dist: ArrayLike | None) -> np.ndarray:
    r"""The radial factor :math:`L(r) = 1 + k_1 r^2 + k_2 r^4 + k_3 r^6` at normalised radius ``r``.

    Parameters
    ----------
    r : float or array_like
        Normalised radius (dimensionless).
    dist : (5,) or (4,) array_like or None
        ``(k1, k2, p1, p2[, k3])`` in OpenCV's order; None for no distortion.

    Returns
    -------
    float ndarray
        L(r), the shape of ``r``.

    Examples
    --------
    >>> float(radial_scale(0.5, [-0.2, 0, 0, 0, 0]))
    0.95
    """
    k1, k2, _, _, k3 = as_dist(dist)
    r2 = check_finite(as_float(r, "r"), "r") ** 2
    return 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3))


def max_valid_radius(dist: ArrayLike | None, r_max: float = 3.0) -> float:
    r"""The normalised radius where the radial map :math:`r \mapsto r L(r)` stops increasing.

    Beyond it two ideal radii land on the same distorted radius, so undistortion is not
    unique. Returns ``r_max`` when the map is monotonic on ``[0, r_max]``.

    Parameters
    ----------
    dist : (5,) or (4,) array_like or None
        ``(k1, k2, p1, p2[, k3])`` in OpenCV's order; None for no distortion.
    r_max : float, optional
        The largest normalised radius searched (default 3).

    Returns
    -------
    float
        The fold radius (normalised, linearly interpolated between samples 1e-4 apart), or
        ``r_max`` when the map is monotonic up to it.

    Examples
    --------
    >>> round(max_valid_radius([-0.5, 0, 0, 0, 0]), 4)    # d/dr (r - 0.5 r^3) = 0 at r = sqrt(2/3)
    0.8165
    """
    k1, k2, _, _, k3 = as_dist(dist)
    r = np.linspace(0.0, r_max, 30001)
    r2 = r * r
    slope = 1 + 3 * k1 * r2 + 5 * k2 * r2**2 + 7 * k3 * r2**3
    bad = np.flatnonzero(slope <= 0)
    if bad.size == 0:
        return float(r_max)
    i = bad[0]
    # linear interpolation of the zero crossing
    return float(r[i - 1] + (r[i] - r[i - 1]) * slope[i - 1] / (slope[i - 1] - slope[i]))


@functools.lru_cache(maxsize=64)
def _valid_radius(dist: tuple[float, ...]) -> float:
    return max_valid_radius(dist)


def beyond_valid_radius(points: ArrayLike, dist: ArrayLike | None) -> np.ndarray:
    """(N,) bool: normalised points farther from the axis than :func:`max_valid_radius`.

    The polynomial model folds back beyond that radius (a point farther out lands on the
    same pixel as one farther in, a mirrored image), so projections mark them NaN.

    Parameters
    ----------
    points : (N, 2) or (2,) array_like
        Normalised points (NaN allowed).
    dist : (5,) or (4,) array_like or None
        ``(k1, k2, p1, p2[, k3])`` in OpenCV's order; None for no distortion.

    Returns
    -------
    (N,) bool ndarray
        True where a point lies beyond the fold radius (all False without distortion).

    Examples
    --------
    >>> beyond_valid_radius([[0.5, 0.0], [1.0, 0.0]], [-0.5, 0, 0, 0, 0]).tolist()
    [False, True]
    """
    p = as_points(points, 2, "points", finite=False).array
    d = as_dist(dist)
    if not d.any():
        return np.zeros(len(p), dtype=bool)
    return np.hypot(p[:, 0], p[:, 1]) > _valid_radius(tuple(d.tolist()))


def classify_distortion(dist: ArrayLike | None, r_max: float = 0.8, tol: float = 1e-4) -> str:
    r"""Name the distortion over radii ``(0, r_max]``: barrel, pincushion, mustache or none, plus tangential.

    Radial part: barrel when :math:`L(r) < 1` (points pulled inwards, straight lines bow
    outwards, typical of wide angles), pincushion when :math:`L(r) > 1` (telephoto),
    mustache when the sign changes within the field of view. Tangential part: when
    :math:`(p_1, p_2)` moves some point within ``r_max`` by more than ``tol`` (the shift
    is at most :math:`3\,|(p_1, p_2)|\,r^2`), ``" + tangential"`` is appended, or the
    answer is ``"tangential"`` alone when the radial part is none. ``tol`` is the smallest
    displacement (normalised units) that counts.

    Parameters
    ----------
    dist : (5,) or (4,) array_like or None
        ``(k1, k2, p1, p2[, k3])`` in OpenCV's order; None for no distortion.
    r_max : float, optional
        The largest normalised radius considered, the field of view's edge (default 0.8).
    tol : float, optional
        The smallest displacement that counts, normalised units (default 1e-4).

    Returns
    -------
    str
        "barrel", "pincushion", "mustache", "none" or "tangential", or one of the first three
        followed by " + tangential".

    Examples
    --------
    >>> classify_distortion([-0.3, 0, 0, 0, 0]), classify_distortion([0.2, 0, 0, 0, 0])
    ('barrel', 'pincushion')
    >>> classify_distortion([-0.3, 0.6, 0, 0, 0])
    'mustache'
    >>> classify_distortion([0, 0, 0.01, 0, 0]), classify_distortion([-0.3, 0, 0, 0.01, 0])
    ('tangential', 'barrel + tangential')
    """
    if not r_max > 0:
        raise CamlabInputError(f"r_max: expected a positive normalised radius, got {r_max!r}")
    d = as_dist(dist)
    r = np.linspace(0.0, r_max, 200)[1:]
    dev = radial_scale(r, d) - 1.0
    dev = dev[np.abs(dev) * r > tol]
    if dev.size == 0:
        radial = "none"
    elif (dev < 0).all():
        radial = "barrel"
    elif (dev > 0).all():
        radial = "pincushion"
    else:
        radial = "mustache"
    if 3.0 * np.hypot(d[2], d[3]) * r_max**2 <= tol:
        return radial
    return "tangential" if radial == "none" else f"{radial} + tangential"


# ---------------------------------------------------------------- pixels and images


def pixels_to_normalised(pixels: np.ndarray, K: np.ndarray) -> np.ndarray:
    r"""Pixels (N, 2) to normalised image coordinates: :math:`(x, y, 1)^\top = K^{-1} (u, v, 1)^\top`.

    Written out for an upper-triangular K: :math:`y = (v - c_y) / f_y`,
    :math:`x = (u - c_x - s\,y) / f_x`. ``K`` must already be checked
    (:func:`camlab._validate.check_intrinsics`). The inverse is :func:`normalised_to_pixels`.

    Parameters
    ----------
    pixels : (N, 2) ndarray
        Pixel coordinates (u, v).
    K : (3, 3) ndarray
        Checked intrinsics, pixels.

    Returns
    -------
    (N, 2) ndarray
        Normalised coordinates (x, y), dimensionless.

    Examples
    --------
    >>> K = np.array([[800.0, 0, 320], [0, 800, 240], [0, 0, 1]])
    >>> pixels_to_normalised(np.array([[400.0, 200.0]]), K)
    array([[ 0.1 , -0.05]])
    """
    y = (pixels[:, 1] - K[1, 2]) / K[1, 1]
    x = (pixels[:, 0] - K[0, 2] - K[0, 1] * y) / K[0, 0]
    return np.stack([x, y], axis=1)


def normalised_to_pixels(xy: np.ndarray, K: np.ndarray) -> np.ndarray:
    r"""Normalised image coordinates (N, 2) to pixels: :math:`(u, v, 1)^\top = K (x, y, 1)^\top`.

    Parameters
    ----------
    xy : (N, 2) ndarray
        Normalised coordinates (x, y), dimensionless.
    K : (3, 3) ndarray
        Checked intrinsics, pixels.

    Returns
    -------
    (N, 2) ndarray
        Pixel coordinates (u, v).

    Examples
    --------
    >>> K = np.array([[800.0, 0, 320], [0, 800, 240], [0, 0, 1]])
    >>> normalised_to_pixels(np.array([[0.1, -0.05]]), K)
    array([[400., 200.]])
    """
    return np.stack(
        [K[0, 0] * xy[:, 0] + K[0, 1] * xy[:, 1] + K[0, 2], K[1, 1] * xy[:, 1] + K[1, 2]], axis=1
    )


def distort_pixels(pixels: ArrayLike, K: ArrayLike, dist: ArrayLike | None) -> np.ndarray:
    """Move ideal pixel positions (u, v) to where the distorting lens images them (same K).

    Parameters
    ----------
    pixels : (N, 2) or (2,) array_like
        Ideal pixel positions (u, v).
    K : (3, 3) array_like
        Intrinsics (upper triangular), pixels.
    dist : (5,) or (4,) array_like or None
        ``(k1, k2, p1, p2[, k3])`` in OpenCV's order; None for no distortion.

    Returns
    -------
    (N, 2) or (2,) ndarray
        Distorted pixel positions, the input's rank.
    """
    pts = as_points(pixels, 2, "pixels")
    K = check_intrinsics(K)
    return pts.restore(
        normalised_to_pixels(_distort(pixels_to_normalised(pts.array, K), as_dist(dist)), K)
    )


def undistort_pixels(pixels: ArrayLike, K: ArrayLike, dist: ArrayLike | None) -> np.ndarray:
    """Inverse of :func:`distort_pixels`: distorted pixels (u, v) to ideal pixels (same K).

    Parameters
    ----------
    pixels : (N, 2) or (2,) array_like
        Distorted pixel positions (u, v).
    K : (3, 3) array_like
        Intrinsics (upper triangular), pixels.
    dist : (5,) or (4,) array_like or None
        ``(k1, k2, p1, p2[, k3])`` in OpenCV's order; None for no distortion.

    Returns
    -------
    (N, 2) or (2,) ndarray
        Ideal pixel positions, the input's rank.

    Raises
    ------
    ConvergenceError
        Where a pixel lies beyond the model's fold (:func:`undistort_points`).
    """
    pts = as_points(pixels, 2, "pixels")
    K = check_intrinsics(K)
    return pts.restore(
        normalised_to_pixels(undistort_points(pixels_to_normalised(pts.array, K), dist), K)
    )


class DistortionMaps(NamedTuple):
    """Per-pixel sampling maps for ``cv2.remap``.

    Output pixel (u, v) samples the source at ``(map_u[v, u], map_v[v, u])``. float32, shape
    (height, width).
    """

    map_u: np.ndarray
    map_v: np.ndarray


def undistort_map(
    K: ArrayLike, dist: ArrayLike | None, size: tuple[int, int], new_K: ArrayLike | None = None
) -> DistortionMaps:
    r"""Maps that undistort an image: like ``cv2.initUndistortRectifyMap`` without rectification.

    Each output pixel :math:`p` of the ideal (undistorted) image with intrinsics ``new_K``
    (default ``K``) samples the distorted input at
    :math:`K\,\mathrm{distort}(K_{new}^{-1} p)`: the forward model, no iteration needed.

    Parameters
    ----------
    K : (3, 3) array_like
        Intrinsics of the distorted input image, pixels.
    dist : (5,) array_like or None
        ``(k1, k2, p1, p2, k3)``.
    size : (width, height)
        Output size in pixels.
    new_K : (3, 3) array_like, optional
        Intrinsics of the undistorted output.

    Returns
    -------
    DistortionMaps
        ``map_u``, ``map_v``: (height, width) float32 source coordinates for ``cv2.remap``.
    """
    K = check_intrinsics(K)
    new_K = K if new_K is None else check_intrinsics(new_K, "new_K")
    w, h = check_size(size)
    # K_new^-1 p, written out (see pixels_to_normalised): y depends on the row only, so a
    # column of y broadcast against a row of u gives the whole grid without a pixel list
    y = ((np.arange(h, dtype=float) - new_K[1, 2]) / new_K[1, 1])[:, None]
    x = (np.arange(w, dtype=float)[None, :] - new_K[0, 2] - new_K[0, 1] * y) / new_K[0, 0]
    xd, yd = distort_xy(x, y, as_dist(dist))
    map_u = K[0, 0] * xd + K[0, 1] * yd + K[0, 2]  # K (xd, yd, 1)
    map_v = K[1, 1] * yd + K[1, 2]
    return DistortionMaps(
        map_u.astype(np.float32), np.broadcast_to(map_v, (h, w)).astype(np.float32)
    )


@lru_cache(maxsize=16)
def _distort_map_cached(Kb: bytes, db: bytes, newKb: bytes, w: int, h: int, step: int):
    K = np.frombuffer(Kb).reshape(3, 3)
    d = np.frombuffer(db)
    new_K = np.frombuffer(newKb).reshape(3, 3)
    # Exact Newton inversion on a coarse grid that covers the image, then bilinear
    # interpolation of the (smooth) map: about 1e-3 px error for step 4 and |k1| <= 0.5.
    gu = np.arange(0, w + step, step, dtype=float)
    gv = np.arange(0, h + step, step, dtype=float)
    U, V = np.meshgrid(gu, gv)
    xy = pixels_to_normalised(np.stack([U.ravel(), V.ravel()], axis=1) - 0.0, K)
    x, res = newton_undistort(xy, d)
    x[~(res <= 1e-9)] = -1e4  # beyond the fold of the model: sample far outside (background)
    ideal = normalised_to_pixels(x, new_K)
    coarse_u = ideal[:, 0].reshape(V.shape).astype(np.float32)
    coarse_v = ideal[:, 1].reshape(V.shape).astype(np.float32)
    if step == 1:
        return DistortionMaps(coarse_u[:h, :w].copy(), coarse_v[:h, :w].copy())
    import cv2

    fu, fv = np.meshgrid(
        np.arange(w, dtype=np.float32) / step, np.arange(h, dtype=np.float32) / step
    )
    mu = cv2.remap(coarse_u, fu, fv, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)
    mv = cv2.remap(coarse_v, fu, fv, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)
    mu.setflags(write=False)
    mv.setflags(write=False)
    return DistortionMaps(mu, mv)


def distort_map(
    K: ArrayLike,
    dist: ArrayLike | None,
    size: tuple[int, int],
    new_K: ArrayLike | None = None,
    *,
    step: int = 4,
) -> DistortionMaps:
    r"""Maps that *apply* distortion: each distorted output pixel samples an ideal image.

    Output pixel :math:`p_d` (intrinsics ``K``) samples the ideal image (intrinsics
    ``new_K``, default ``K``) at :math:`K_{new}\,\mathrm{undistort}(K^{-1} p_d)`. This is the
    direction a renderer needs, and it requires the iterative inverse; it is computed
    exactly every ``step`` pixels and interpolated bilinearly in between (``step=1``: exact
    everywhere). Results are cached and read-only.

    Pixels beyond the fold of the model (no physical inverse, see :func:`max_valid_radius`)
    map far outside the ideal image, so ``cv2.remap`` fills them with its border value.

    Parameters
    ----------
    K : (3, 3) array_like
        Intrinsics of the distorted output (upper triangular), pixels.
    dist : (5,) or (4,) array_like or None
        ``(k1, k2, p1, p2[, k3])`` in OpenCV's order; None for no distortion.
    size : (2,) tuple of int
        Output size (width, height), pixels.
    new_K : (3, 3) array_like, optional
        Intrinsics of the ideal image sampled (default ``K``).
    step : int, optional
        Spacing of the exactly inverted grid, pixels (>= 1; default 4).

    Returns
    -------
    DistortionMaps
        ``map_u``, ``map_v``: (height, width) read-only float32 source coordinates for
        ``cv2.remap``.
    """
    K = check_intrinsics(K)
    new_K = K if new_K is None else check_intrinsics(new_K, "new_K")
    w, h = check_size(size)
    if int(step) < 1:
        raise CamlabInputError(f"step: expected an integer >= 1, got {step!r}")
    return _distort_map_cached(
        K.tobytes(), as_dist(dist).tobytes(), new_K.tobytes(), w, h, int(step)
    )


def undistort_image(
    image: np.ndarray, K: ArrayLike, dist: ArrayLike | None, new_K: ArrayLike | None = None
) -> np.ndarray:
    """Undistort an image (H, W) or (H, W, C) with :func:`undistort_map` and ``cv2.remap`` (bilinear).

    Parameters
    ----------
    image : (H, W) or (H, W, C) ndarray
        The distorted image.
    K : (3, 3) array_like
        Intrinsics (upper triangular), pixels.
    dist : (5,) or (4,) array_like or None
        ``(k1, k2, p1, p2[, k3])`` in OpenCV's order; None for no distortion.
    new_K : (3, 3) array_like, optional
        Intrinsics of the undistorted output (default ``K``).

    Returns
    -------
    ndarray
        The undistorted image, the input's shape and dtype; pixels with no source are 0.
    """
    import cv2

    img = check_image(image)
    maps = undistort_map(K, dist, (img.shape[1], img.shape[0]), new_K)
    return cv2.remap(img, maps.map_u, maps.map_v, cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT)
