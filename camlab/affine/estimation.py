r"""Affine cameras from data.

The least-squares affine camera from 3-D/2-D correspondences, and how far a homography between two
views departs from an affinity (the test of lesson 05).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    DegenerateError,
    as_point_pairs,
    as_points,
    check_matrix,
    check_positive,
)

__all__ = [
    "AffineDeparture",
    "affine_departure",
    "affine_fit_departure",
    "estimate_affine_camera",
]


def estimate_affine_camera(points_world: ArrayLike, points_image: ArrayLike) -> np.ndarray:
    r"""The Gold Standard affine camera from N >= 4 world/image correspondences.

    An affine camera is linear, :math:`u_i = M_2 X_i + t_2`, so the image error is linear
    in its 8 entries and the least-squares solution *is* the maximum-likelihood estimate
    under Gaussian pixel noise; no iteration is needed. Centring both point sets
    (:math:`\bar X`, :math:`\bar u`) removes :math:`t_2 = \bar u - M_2 \bar X`, and
    :math:`M_2` solves :math:`\min \sum_i \|(u_i - \bar u) - M_2 (X_i - \bar X)\|^2`,
    i.e. :math:`M_2^\top = (X_c^\top X_c)^{-1} X_c^\top U_c`.

    Parameters
    ----------
    points_world : (N, 3) array_like
        World points (metres), N >= 4, not coplanar.
    points_image : (N, 2) array_like
        Their images, pixels.

    Returns
    -------
    (3, 4) ndarray
        Affine camera with last row (0, 0, 0, 1).

    Raises
    ------
    CamlabInputError
        Fewer than 4 points or mismatched counts.
    DegenerateError
        Coplanar world points (M_2 is then not determined).

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, chapter 7,
       algorithm 7.2 (the Gold Standard algorithm for an affine camera).
    """
    X, uv, _ = as_point_pairs(
        points_world,
        points_image,
        ("points_world", "points_image"),
        (3, 2),
        min_count=4,
        why="an affine camera has 8 degrees of freedom and each point gives 2 equations; "
        "add more points",
    )
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    Xc, uc = X - Xm, uv - um
    sv = np.linalg.svd(Xc, compute_uv=False)
    if sv[2] <= 1e-9 * sv[0]:
        raise DegenerateError(
            "estimate_affine_camera: the world points are coplanar, so the affine camera is not determined; "
            "use points off a single plane"
        )
    M2 = np.linalg.lstsq(Xc, uc, rcond=None)[0].T
    P = np.zeros((3, 4))
    P[:2, :3] = M2
    P[:2, 3] = um - M2 @ Xm
    P[2, 3] = 1.0
    return P


class AffineDeparture(NamedTuple):
    """How far a homography is from its best affine fit, over an image (:func:`affine_departure`).

    Attributes
    ----------
    u, v : (S, S) ndarray
        The grid of pixel centres spanning the image (pixels).
    distance : (S, S) ndarray
        At each grid point, the distance (pixels) between the homography's and the affine fit's images.
    at_points : (N,) ndarray
        The same distance at the given points (empty without points).
    """

    u: np.ndarray
    v: np.ndarray
    distance: np.ndarray
    at_points: np.ndarray


def affine_departure(
    H: ArrayLike, size: tuple[int, int], samples: int = 30, points: ArrayLike | None = None
) -> AffineDeparture:
    r"""The distance between a homography and its least-squares affine fit, over an image.

    Everywhere on a ``samples`` x ``samples`` grid of pixel centres spanning the image, and at
    ``points`` (e.g. the matches ``H`` was fitted to, where it is not extrapolated). The affine
    fit minimises the squared distance over the grid. See :func:`affine_fit_departure` (the
    largest of these distances) and lesson 05, section 5.

    Parameters
    ----------
    H : (3, 3) array_like
        The homography, pixels to pixels.
    size : (2,) tuple of int
        The image (width, height), pixels.
    samples : int
        Grid points along each side.
    points : (N, 2) array_like, optional
        Pixels where the distance is also wanted.

    Returns
    -------
    AffineDeparture
        ``u``, ``v`` (the grid, pixels), ``distance`` (at each grid point, pixels) and
        ``at_points`` ((N,) pixels; empty without ``points``).

    Raises
    ------
    CamlabInputError
        ``H`` not (3, 3), a non-positive size, or ``points`` not (N, 2).
    """
    Hm = check_matrix(H, (3, 3), "H")
    width, height = (int(check_positive(n, "size", "pixels")) for n in size)
    u, v = np.meshgrid(np.linspace(0, width - 1, samples), np.linspace(0, height - 1, samples))

    def lifted(uv):
        return np.column_stack([uv, np.ones(len(uv))])

    def mapped(g):
        m = g @ Hm.T
        return m[:, :2] / m[:, 2:]

    grid = lifted(np.column_stack([u.ravel(), v.ravel()]))
    A = np.linalg.lstsq(grid, mapped(grid), rcond=None)[0]
    distance = np.linalg.norm(grid @ A - mapped(grid), axis=1).reshape(u.shape)
    if points is None:
        return AffineDeparture(u, v, distance, np.empty(0))
    pts = lifted(as_points(points, 2, "points").array)
    return AffineDeparture(u, v, distance, np.linalg.norm(pts @ A - mapped(pts), axis=1))


def affine_fit_departure(H: ArrayLike, size: tuple[int, int], samples: int = 30) -> float:
    r"""How far a homography is from an affine map over an image, pixels.

    The largest distance between ``H`` and its least-squares affine fit on a ``samples`` x
    ``samples`` grid of pixel centres spanning the image (:func:`affine_departure`).

    Two affine cameras see a plane through affine maps, so two views of a plane are related by an
    affinity; for perspective cameras the map is a homography. It is affine exactly when it keeps the
    line at infinity [1]_: when the plane meets both cameras' principal planes in the same
    line. That holds when both views see the plane face-on (its depth nearly constant across each
    picture), but also, exactly, for one perspective camera slid within its principal plane without
    turning. So a large departure proves perspective matters for the plane in at least one view; a
    small one does not prove affine cameras. See lesson 05, section 5.

    Parameters
    ----------
    H : (3, 3) array_like
        The homography, pixels to pixels.
    size : (2,) tuple of int
        The image (width, height), pixels.
    samples : int
        Grid points along each side.

    Returns
    -------
    float
        The largest distance, pixels.

    Raises
    ------
    CamlabInputError
        ``H`` not (3, 3) or a non-positive size.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 2.7.1
       (the line at infinity is fixed by a projective transformation exactly when it is an
       affinity).
    """
    return float(affine_departure(H, size, samples).distance.max())
