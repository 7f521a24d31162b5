r"""Homographies from cameras and planes.

A rotating camera :math:`K' R K^{-1}`, a plane seen from two cameras :math:`K'(R - t
n^\top/d)K^{-1}`, and the world plane Z = 0 to the image :math:`K [r_1\ r_2\ t]`.

Part of :mod:`camlab.homography` (every name here is importable from there).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    CamlabInputError,
    DegenerateError,
    as_float,
    check_intrinsics,
    check_matrix,
    check_number,
    check_rotation,
)
from .core import check_homography, normalise_homography

__all__ = [
    "plane_homography",
    "pose_homography",
    "rotation_homography",
]


def rotation_homography(K: ArrayLike, R: ArrayLike, K2: ArrayLike | None = None) -> np.ndarray:
    r"""The homography between two views from one centre: :math:`H = K' R K^{-1}`.

    A camera that only rotates (R maps camera-1 coordinates to camera-2 coordinates)
    sees every scene point along the same ray, whatever its depth, so
    :math:`x_2 \sim K' R K^{-1} x_1`. This is why panoramas need no depth.

    Parameters
    ----------
    K : (3, 3) array_like
        Intrinsics of the first camera.
    R : (3, 3) array_like
        Rotation cam2_from_cam1.
    K2 : (3, 3) array_like, optional
        Intrinsics of the second camera (default: K).

    Returns
    -------
    (3, 3) ndarray
        H = K' R K^-1, normalised (H[2, 2] = 1).
    """
    Km = check_intrinsics(K, "K")
    K2m = Km if K2 is None else check_intrinsics(K2, "K2")
    return normalise_homography(K2m @ check_rotation(R) @ np.linalg.inv(Km))


def plane_homography(
    K: ArrayLike, R: ArrayLike, t: ArrayLike, n: ArrayLike, d: float, K2: ArrayLike | None = None
) -> np.ndarray:
    r"""The homography induced by a plane between two views: :math:`H = K'(R - t n^T / d) K^{-1}`.

    Camera 1 is :math:`K[I \mid 0]`, camera 2 is :math:`K'[R \mid t]` (cam2_from_cam1).
    The plane is :math:`n^T X + d = 0` in camera-1 coordinates (H&Z result 13.1 [1]_). For X
    on the plane, :math:`-n^T X / d = 1`, so
    :math:`R X + t = R X - t\, n^T X / d = (R - t n^T / d) X`; with
    :math:`X \sim K^{-1} x_1` this gives :math:`x_2 \sim K'(R - t n^T/d) K^{-1} x_1`.

    Parameters
    ----------
    K : (3, 3) array_like
        Intrinsics of camera 1, pixels.
    R : (3, 3) array_like
        Rotation cam2_from_cam1.
    t : (3,) array_like
        Translation cam2_from_cam1, metres.
    n : (3,) array_like
        Plane normal in camera-1 coordinates (need not be unit; d scales with it).
    d : float
        Plane offset: the plane is n . X + d = 0; d != 0 (the plane must not pass
        through camera 1's centre).
    K2 : (3, 3) array_like, optional
        Intrinsics of camera 2 (default: K).

    Returns
    -------
    (3, 3) ndarray
        H, x_2 ~ H x_1, normalised (H[2, 2] = 1).

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 13.1
       (homographies given the plane, result 13.1).
    """
    Km = check_intrinsics(K, "K")
    K2m = Km if K2 is None else check_intrinsics(K2, "K2")
    tv = check_matrix(np.ravel(as_float(t, "t")), (3,), "t")
    nv = check_matrix(np.ravel(as_float(n, "n")), (3,), "n")
    if check_number(d, "d", "metres") == 0:
        raise DegenerateError(
            f"d: the plane n . X + d = 0 must not pass through camera 1's centre; got d={d!r}"
        )
    if not np.any(nv):
        raise CamlabInputError("n: the plane normal must be non-zero")
    H = K2m @ (check_rotation(R) - np.outer(tv, nv) / d) @ np.linalg.inv(Km)
    return normalise_homography(check_homography(H, "plane_homography"))


def pose_homography(K: ArrayLike, R: ArrayLike, t: ArrayLike) -> np.ndarray:
    r"""The homography from the world plane Z = 0 to the image: :math:`H = K [r_1\ r_2\ t]`.

    A point (X, Y, 0) projects to :math:`K (X r_1 + Y r_2 + t)`, linear in (X, Y, 1).
    This is how a flat textured target (a page, a painting, a chessboard) photographed
    by a camera ``K [R | t]`` (cam_from_world) appears: Zhang's calibration and lesson 10
    start from it.

    Parameters
    ----------
    K : (3, 3) array_like
        Intrinsics, pixels.
    R : (3, 3) array_like
        Rotation cam_from_world.
    t : (3,) array_like
        Translation cam_from_world, metres (world units).

    Returns
    -------
    (3, 3) ndarray
        H from plane coordinates (X, Y) to pixels, normalised (H[2, 2] = 1).

    References
    ----------
    .. [1] Z. Zhang, 2000, "A flexible new technique for camera calibration", *IEEE
       Transactions on Pattern Analysis and Machine Intelligence* 22(11), 1330-1334, section
       2.2 (homography between the model plane and its image).

    Examples
    --------
    >>> from camlab.projective import map_points
    >>> K = np.array([[800.0, 0, 320], [0, 800, 240], [0, 0, 1]])
    >>> map_points(pose_homography(K, np.eye(3), [0, 0, 2.0]), [0.0, 0.0])
    array([320., 240.])
    """
    Km = check_intrinsics(K, "K")
    Rm = check_rotation(R)
    tv = check_matrix(np.ravel(as_float(t, "t")), (3,), "t")
    H = Km @ np.column_stack([Rm[:, 0], Rm[:, 1], tv])
    return normalise_homography(check_homography(H, "pose_homography"))
