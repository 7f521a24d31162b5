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
    "BandEdges",
    "BandHeights",
    "PinholeBlur",
    "band_edges",
    "band_heights",
    "diffraction_blur",
    "geometric_blur",
    "optimal_pinhole_diameter",
    "pinhole_blur",
    "project_pinhole",
    "level_crossing",
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


# ----------------------------------------------------------------------------------------------
# Reading image heights off a photograph (lesson 01, section 2: h = f H / Z on the church photo)


def level_crossing(profile: ArrayLike, level: float, start: int) -> float:
    """The first position from index ``start`` on where ``profile`` crosses ``level``, to a fraction of a pixel.

    The profile is sampled at whole pixels (pixel centres at integers); between the last
    sample on ``start``'s side and the first on the other side it is taken as a straight
    line, so the crossing is ``k - 1 + (level - p[k-1]) / (p[k] - p[k-1])``.

    Parameters
    ----------
    profile : (N,) array_like
        Brightness along a row or column of an image.
    level : float
        The brightness whose crossing is wanted.
    start : int
        Where to start looking (an index into ``profile``).

    Returns
    -------
    float
        The crossing's position, in pixels along the profile.
    """
    p = np.asarray(profile, dtype=float)
    if p.ndim != 1:
        raise CamlabInputError(
            f"profile: expected a 1-D array, got shape {p.shape}; pass one column, grey[:, u]"
        )
    side = p > level
    other = np.flatnonzero(side[start:] != side[start])
    if other.size == 0:
        raise CamlabInputError(
            f"profile: never crosses {level:.1f} after index {start}; start nearer the edge you want"
        )
    k = start + other[0]  # the first pixel on the other side
    return float(k - 1 + (level - p[k - 1]) / (p[k] - p[k - 1]))


class BandEdges(NamedTuple):
    """The edges of one dark band down one column (:func:`band_edges`).

    Attributes
    ----------
    top, bottom : float
        The edge rows (v, pixels).
    level : float
        The brightness they were found at.
    """

    top: float
    bottom: float
    level: float


def band_edges(
    column: ArrayLike, rough_top: int, rough_bottom: int, share: float = 0.5
) -> BandEdges:
    """The top and bottom edges of a dark band (a window's glass) under a bright one, down one image column.

    The bright level is the median of the 6 pixels ending 2 above ``rough_top`` (the frame
    above the glass), the dark level the median of the band's inside (5 pixels in from either
    rough edge). Each edge is where the column crosses ``share`` of the way from dark to
    bright, searched for from 6 pixels above its rough row (:func:`level_crossing`).

    Parameters
    ----------
    column : (H,) array_like
        Brightness down one column, ``grey[:, u]``.
    rough_top, rough_bottom : int
        The band's top and bottom rows read by eye, to a pixel or two.
    share : float, optional
        Where between dark (0) and bright (1) an edge lies; default half-way.

    Returns
    -------
    BandEdges
        ``top``, ``bottom``: the two edge rows (v, pixels); ``level``: the brightness they were
        found at.
    """
    c = np.asarray(column, dtype=float)
    bright = np.median(c[rough_top - 8 : rough_top - 2])
    dark = np.median(c[rough_top + 5 : rough_bottom - 5])
    level = dark + share * (bright - dark)
    return BandEdges(
        level_crossing(c, level, rough_top - 6),
        level_crossing(c, level, rough_bottom - 6),
        float(level),
    )


class BandHeights(NamedTuple):
    """Dark-band heights read off a photograph by :func:`band_heights` (rows v, pixels).

    Attributes
    ----------
    top, bottom, level : (K,) ndarray
        Each band's edges down its middle column at half-way, and that brightness.
    height : (K,) ndarray
        ``bottom - top``.
    low, high : (K,) ndarray
        The least and largest height over every column offset and share tried: the
        reading's spread.
    """

    top: np.ndarray
    bottom: np.ndarray
    level: np.ndarray
    height: np.ndarray
    low: np.ndarray
    high: np.ndarray


def band_heights(
    grey: ArrayLike,
    rough: dict,
    offsets: tuple = (-2, -1, 0, 1, 2),
    shares: tuple = (0.4, 0.5, 0.6),
) -> BandHeights:
    """Heights of dark bands (windows' glass) in a grey image, and how well each is read.

    Each band is read down its middle column at half-way (:func:`band_edges`), then again
    down the columns ``u + offsets`` with the edge at each of ``shares``; the least and
    largest of those readings give the spread.

    Parameters
    ----------
    grey : (H, W) array_like
        Brightness, indexed ``grey[v, u]``.
    rough : dict
        ``{u: (rough_top, rough_bottom)}``: each band's middle column and its edge rows read
        by eye.
    offsets, shares : tuple, optional
        The column offsets and edge shares of the repeat readings.

    Returns
    -------
    BandHeights
        Edges, heights and the spread, one entry per band in ``rough``'s order.
    """
    g = np.asarray(grey, dtype=float)
    if g.ndim != 2:
        raise CamlabInputError(
            f"grey: expected an (H, W) grey image, got shape {g.shape}; average the colours first"
        )
    top, bottom, level = np.array([band_edges(g[:, u], *rows) for u, rows in rough.items()]).T
    readings = np.array(
        [
            [
                np.subtract(*band_edges(g[:, u + du], *rows, share)[1::-1])
                for du in offsets
                for share in shares
            ]
            for u, rows in rough.items()
        ]
    )
    return BandHeights(top, bottom, level, bottom - top, readings.min(axis=1), readings.max(axis=1))
