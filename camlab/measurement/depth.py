r"""Two views: points triangulated from a rectified pair, and how their depth error grows.

A rectified pair (lesson 11) has two cameras with the same rotation, focal length f (pixels)
and image rows, their centres B apart along x. Left :math:`P_1 = K_1 [I \mid 0]`, right
:math:`P_2 = K_2 [I \mid (-B, 0, 0)^\top]`, where :math:`K_2` may have its principal point
:math:`d_{offs}` pixels further right (Middlebury's convention). A point at depth Z appears at
left column :math:`u = f X / Z + c_x` and right column
:math:`u - d` with :math:`d = f B / Z - d_{offs}`, so

.. math:: Z = \frac{f B}{d + d_{offs}}, \qquad
          \frac{\partial Z}{\partial d} = -\frac{f B}{(d + d_{offs})^2} = -\frac{Z^2}{f B},

and a disparity error of standard deviation :math:`\sigma_d` gives, to first order,

.. math:: \sigma_Z = \frac{Z^2 \sigma_d}{f B}

(H&Z section 12.6 [1]_ on the uncertainty of triangulation; Szeliski 2022, section 12.1 [2]_):
the depth error grows with the *square* of the distance, and falls with f and with B.
:func:`triangulate_rectified` triangulates through the general two-camera DLT
(:func:`camlab.epipolar.triangulate_points`), so the law is checked, not assumed.

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, sections 12.2 (linear
   triangulation) and 12.6 (probability distribution of the estimated 3-D point).
.. [2] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022, section 12.1
   (epipolar geometry and rectification; depth from disparity).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, as_float, as_points, check_number, check_positive
from ..epipolar import triangulate_points

__all__ = ["RectifiedCameras", "depth_sigma", "rectified_cameras", "triangulate_rectified"]


class RectifiedCameras(NamedTuple):
    """The two 3 x 4 camera matrices of a rectified pair (world = the left camera's frame).

    Attributes
    ----------
    P1, P2 : (3, 4) ndarray
        Left and right cameras.
    """

    P1: np.ndarray
    P2: np.ndarray


def depth_sigma(Z: ArrayLike, f_px: float, baseline: float, sigma_d: float) -> np.ndarray:
    r"""The depth uncertainty of a rectified pair, :math:`\sigma_Z = Z^2 \sigma_d / (f B)`.

    Parameters
    ----------
    Z : array_like
        Depths, metres (> 0), any shape.
    f_px : float
        Focal length, pixels.
    baseline : float
        Distance between the camera centres, metres.
    sigma_d : float
        Standard deviation of the disparity, pixels (>= 0).

    Returns
    -------
    float ndarray
        :math:`\sigma_Z`, metres, the shape of ``Z``.

    Examples
    --------
    >>> float(depth_sigma(2.0, f_px=800, baseline=0.1, sigma_d=0.25))
    0.0125
    """
    z = as_float(Z, "Z")
    if np.any(~np.isfinite(z) | (z <= 0)):
        raise CamlabInputError(
            f"Z: expected depths in metres, all > 0 and finite, got values from {np.nanmin(z)!r}; "
            "drop the points with no depth (NaN) or behind the camera"
        )
    f = check_positive(f_px, "f_px", "pixels")
    B = check_positive(baseline, "baseline", "metres")
    s = check_number(sigma_d, "sigma_d", "pixels")
    if s < 0:
        raise CamlabInputError(
            f"sigma_d: expected a standard deviation >= 0 pixels, got {sigma_d!r}; pass abs(sigma_d)"
        )
    return z**2 * s / (f * B)


def rectified_cameras(
    focal: float, cx: float, cy: float, baseline: float, doffs: float = 0.0
) -> RectifiedCameras:
    r"""The 3 x 4 cameras of a rectified pair: :math:`K_1 [I \mid 0]` and :math:`K_2 [I \mid (-B, 0, 0)]`.

    Parameters
    ----------
    focal : float
        Focal length of both cameras, pixels.
    cx, cy : float
        The left camera's principal point, pixels.
    baseline : float
        Distance between the centres, metres; the right camera sits at (B, 0, 0).
    doffs : float
        The right principal point's offset, ``cx_right - cx_left``, pixels.

    Returns
    -------
    RectifiedCameras
        ``(P1, P2)``, world = the left camera's frame.
    """
    f = check_positive(focal, "focal", "pixels")
    B = check_positive(baseline, "baseline", "metres")
    cx, cy, doffs = (
        check_number(v, n, "pixels") for v, n in ((cx, "cx"), (cy, "cy"), (doffs, "doffs"))
    )
    K1 = np.array([[f, 0.0, cx], [0.0, f, cy], [0.0, 0.0, 1.0]])
    K2 = K1.copy()
    K2[0, 2] += doffs
    P1 = K1 @ np.hstack([np.eye(3), np.zeros((3, 1))])
    P2 = K2 @ np.hstack([np.eye(3), [[-B], [0.0], [0.0]]])
    return RectifiedCameras(P1, P2)


def triangulate_rectified(
    pixels_left: ArrayLike,
    disparity: ArrayLike,
    focal: float,
    cx: float,
    cy: float,
    baseline: float,
    doffs: float = 0.0,
) -> np.ndarray:
    r"""World points (the left camera's frame, metres) from left pixels and their disparities.

    The right pixel is :math:`(u - d, v)`; both rays are intersected by
    :func:`camlab.epipolar.triangulate_points` with :func:`rectified_cameras`.

    Parameters
    ----------
    pixels_left : (N, 2) array_like
        Left pixels (u, v).
    disparity : (N,) array_like
        Their disparities d, pixels (the match is at u - d in the right image).
    focal : float
        Focal length, pixels.
    cx, cy : float
        The left principal point, pixels.
    baseline : float
        Baseline, metres.
    doffs : float
        ``cx_right - cx_left``, pixels.

    Returns
    -------
    (N, 3) ndarray
        Points (X, Y, Z) in the left camera's frame, metres; NaN where d + doffs <= 0.

    Examples
    --------
    >>> triangulate_rectified([[420.0, 240.0]], [40.0], 800, 320, 240, 0.1).round(9) + 0.0
    array([[0.25, 0.  , 2.  ]])
    """
    uv = as_points(pixels_left, 2, "pixels_left").array
    d = as_float(disparity, "disparity").reshape(-1)
    if len(d) != len(uv):
        raise CamlabInputError(
            f"disparity: expected one disparity per left pixel ({len(uv)}), got {len(d)}; "
            "pass disparity[v, u] at each pixel"
        )
    P1, P2 = rectified_cameras(focal, cx, cy, baseline, doffs)
    ok = np.isfinite(d) & (d + doffs > 0)
    out = np.full((len(uv), 3), np.nan)
    if ok.any():
        right = uv[ok] - np.column_stack([d[ok], np.zeros(ok.sum())])
        out[ok] = triangulate_points(P1, P2, uv[ok], right)
    return out
