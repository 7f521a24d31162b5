r"""The pinhole camera: projection by similar triangles and the size of the hole.

A point :math:`(X, Y, Z)` in the camera frame (x right, y down, z forward, metres) sends
one ray through the pinhole at the origin. On the *real* image plane a distance
:math:`f` behind the hole it lands, inverted, at :math:`(-fX/Z, -fY/Z)`; on the
*virtual* image plane a distance :math:`f` in front it lands upright at

.. math:: x = f \frac{X}{Z}, \qquad y = f \frac{Y}{Z}.

Cameras and all later lessons use the virtual plane. A real hole of diameter :math:`d`
blurs each point into a disc: geometric blur :math:`d (1 + f / Z)` grows with the hole,
diffraction (the Airy disc, :math:`2.44 \lambda f / d`) grows as it shrinks, and their sum
is smallest at :math:`d^* = \sqrt{2.44 \lambda f / (1 + f/Z)}`. See lesson 01.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._validate import CamlabInputError, as_float, as_points, check_positive

__all__ = [
    "PinholeBlur",
    "diffraction_blur",
    "geometric_blur",
    "optimal_pinhole_diameter",
    "pinhole_blur",
    "project_pinhole",
]


def project_pinhole(points: ArrayLike, focal_length: float, plane: str = "virtual") -> np.ndarray:
    r"""Project camera-frame points through a pinhole onto an image plane at distance ``focal_length``.

    Parameters
    ----------
    points : (N, 3) or (3,) array_like
        Points (X, Y, Z) in the camera frame, metres.
    focal_length : float
        Pinhole-to-image-plane distance f, metres (> 0).
    plane : {"virtual", "real"}
        ``"virtual"``: the upright image in front of the hole, :math:`(fX/Z, fY/Z)`;
        ``"real"``: the inverted image behind it, :math:`(-fX/Z, -fY/Z)`, in the same axes.

    Returns
    -------
    (N, 2) or (2,) ndarray
        Image-plane coordinates in metres; NaN for points with Z <= 0 (behind the hole).

    Examples
    --------
    >>> project_pinhole([0.5, -0.25, 2.0], 0.05)
    array([ 0.0125 , -0.00625])
    >>> project_pinhole([0.5, -0.25, 2.0], 0.05, plane="real")
    array([-0.0125 ,  0.00625])
    """
    pts = as_points(points, 3, "points")
    f = check_positive(focal_length, "focal_length", "metres")
    if plane not in ("virtual", "real"):
        raise CamlabInputError(f"plane: expected 'virtual' or 'real', got {plane!r}")
    X = pts.array
    Z = X[:, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        xy = f * X[:, :2] / Z[:, None]
    xy[Z <= 0] = np.nan
    return pts.restore(-xy if plane == "real" else xy)


def _diameters(diameter: ArrayLike) -> np.ndarray:
    d = as_float(diameter, "diameter")
    if np.any(~(d > 0)) or not np.all(np.isfinite(d)):
        raise CamlabInputError(
            f"diameter: expected positive finite pinhole diameters in metres, got {diameter!r}"
        )
    return d


def geometric_blur(
    diameter: ArrayLike, focal_length: float, object_distance: float = np.inf
) -> np.ndarray | float:
    r"""Blur-disc diameter from the hole's size alone: :math:`d (Z + f) / Z` (metres).

    Rays from a point at distance Z through a hole of diameter d diverge into a cone that
    meets the plane f behind the hole in a disc slightly larger than the hole.

    Parameters
    ----------
    diameter : float or array_like
        Pinhole diameter d, metres (> 0); an array gives one blur per diameter.
    focal_length : float
        Pinhole-to-image-plane distance f, metres (> 0).
    object_distance : float, optional
        Distance Z of the point in front of the hole, metres (> 0); ``np.inf`` (the default)
        for a point at infinity, whose blur is the hole itself.

    Returns
    -------
    float or ndarray
        Blur-disc diameter on the image plane, metres: a float for a scalar ``diameter``, else an
        array of its shape.

    Examples
    --------
    >>> round(float(geometric_blur(0.5e-3, 0.1, 1.0)) * 1e3, 3)
    0.55
    """
    d = _diameters(diameter)
    f = check_positive(focal_length, "focal_length", "metres")
    Z = (
        check_positive(object_distance, "object_distance", "metres")
        if np.isfinite(object_distance)
        else np.inf
    )
    out = d * (1 + f / Z)
    return float(out) if out.ndim == 0 else out


def diffraction_blur(
    diameter: ArrayLike, focal_length: float, wavelength: float = 550e-9
) -> np.ndarray | float:
    r"""Airy-disc diameter (to the first dark ring) for a hole of ``diameter``: :math:`2.44 \lambda f / d`.

    Parameters
    ----------
    diameter : float or array_like
        Pinhole diameter d, metres (> 0).
    focal_length : float
        Pinhole-to-image-plane distance f, metres (> 0).
    wavelength : float, optional
        Wavelength of the light, metres (default 550 nm, green).

    Returns
    -------
    float or ndarray
        Airy-disc diameter on the image plane, metres: a float for a scalar ``diameter``, else an
        array of its shape.

    References
    ----------
    .. [1] E. Hecht, *Optics*, 5th ed., 2017, chapter 10 (Fraunhofer diffraction by a circular
       aperture: the Airy disc).

    Examples
    --------
    >>> round(float(diffraction_blur(0.5e-3, 0.1)) * 1e3, 4)     # green light, f = 100 mm
    0.2684
    """
    d = _diameters(diameter)
    f = check_positive(focal_length, "focal_length", "metres")
    lam = check_positive(wavelength, "wavelength", "metres")
    out = 2.44 * lam * f / d
    return float(out) if out.ndim == 0 else out


class PinholeBlur(NamedTuple):
    """Blur-disc diameters (metres on the image plane): geometric, diffraction and their sum."""

    geometric: np.ndarray | float
    diffraction: np.ndarray | float
    total: np.ndarray | float


def pinhole_blur(
    diameter: ArrayLike,
    focal_length: float,
    object_distance: float = np.inf,
    wavelength: float = 550e-9,
) -> PinholeBlur:
    """Both blur terms for a pinhole of ``diameter`` and their sum (a simple, conservative total).

    Parameters
    ----------
    diameter : float or array_like
        Pinhole diameter d, metres (> 0).
    focal_length : float
        Pinhole-to-image-plane distance f, metres (> 0).
    object_distance : float, optional
        Distance of the point in front of the hole, metres (default ``np.inf``).
    wavelength : float, optional
        Wavelength of the light, metres (default 550 nm).

    Returns
    -------
    PinholeBlur
        ``geometric`` (:func:`geometric_blur`), ``diffraction`` (:func:`diffraction_blur`) and
        ``total``, their sum: diameters in metres on the image plane, floats or arrays of
        ``diameter``'s shape.
    """
    g = geometric_blur(diameter, focal_length, object_distance)
    k = diffraction_blur(diameter, focal_length, wavelength)
    return PinholeBlur(g, k, g + k)


def optimal_pinhole_diameter(
    focal_length: float, wavelength: float = 550e-9, object_distance: float = np.inf
) -> float:
    r"""The diameter minimising :func:`pinhole_blur`'s total, :math:`\sqrt{2.44 \lambda f / (1 + f/Z)}`.

    Setting :math:`\frac{d}{dd}\,[d m + 2.44 \lambda f / d] = 0` with :math:`m = 1 + f/Z`.
    Textbook value: f = 100 mm in green light gives about 0.37 mm.

    Parameters
    ----------
    focal_length : float
        Pinhole-to-image-plane distance f, metres (> 0).
    wavelength : float, optional
        Wavelength of the light, metres (default 550 nm).
    object_distance : float, optional
        Distance Z of the subject, metres (default ``np.inf``: m = 1).

    Returns
    -------
    float
        The best hole diameter d*, metres.

    Examples
    --------
    >>> round(optimal_pinhole_diameter(0.1) * 1e3, 3)
    0.366
    """
    f = check_positive(focal_length, "focal_length", "metres")
    lam = check_positive(wavelength, "wavelength", "metres")
    m = (
        1 + f / check_positive(object_distance, "object_distance", "metres")
        if np.isfinite(object_distance)
        else 1.0
    )
    return float(np.sqrt(2.44 * lam * f / m))
