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
    "mapped_angle",
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


def mapped_angle(H: ArrayLike, corner: ArrayLike, d1: ArrayLike, d2: ArrayLike) -> float:
    r"""The angle, in degrees, between the images under H of two directions leaving ``corner``.

    Write :math:`H = \begin{pmatrix} A & t \\ b^\top & h_{33} \end{pmatrix}`, so a point x maps
    to :math:`f(x) = (A x + t) / w` with :math:`w = b^\top x + h_{33}`. Differentiating,

    .. math:: J = \frac{\partial f}{\partial x} = \frac{A - f(x)\, b^\top}{w},

    and a curve leaving x along d leaves f(x) along :math:`J d`. The angle between two mapped
    edges at a corner is the angle between :math:`J d_1` and :math:`J d_2`. This is exact, and it
    stays right when an edge passes through infinity: the chord from f(x) to the image of the
    edge's far end then points *backwards* (the edge's image leaves f(x) the other way, runs
    out to infinity and comes back from the opposite side), so an angle built from the mapped
    corners gives the supplement. Scaling H by any non-zero number (even a negative one)
    leaves J unchanged.

    Parameters
    ----------
    H : (3, 3) array_like
        The homography.
    corner : (2,) array_like
        The corner x in the source, pixels; H must not send it to infinity (w != 0).
    d1, d2 : (2,) array_like
        The two edge directions leaving the corner in the source (any non-zero lengths).

    Returns
    -------
    float
        The mapped angle in degrees, in [0, 180].

    Raises
    ------
    DegenerateError
        If H sends the corner to infinity, or maps a direction to zero.

    Examples
    --------
    >>> H = np.array([[2.0, 0, 0], [0, 1, 0], [0, 0, 1]])
    >>> round(mapped_angle(H, [0, 0], [1, 0], [1, 1]), 2)   # x stretched twice: 45 deg becomes 26.57
    26.57
    """
    Hm = check_homography(H, "H")
    x = check_matrix(np.ravel(as_float(corner, "corner")), (2,), "corner")
    D = np.stack(
        [check_matrix(np.ravel(as_float(d, n)), (2,), n) for d, n in ((d1, "d1"), (d2, "d2"))]
    )
    w = Hm[2, :2] @ x + Hm[2, 2]
    if abs(w) < 1e-12 * np.abs(Hm[2]).max() * (1 + np.abs(x).max()):
        raise DegenerateError(
            f"corner: H sends {x} to infinity (w = 0), so no angle is defined there; move the corner"
        )
    f = (Hm[:2, :2] @ x + Hm[:2, 2]) / w
    J = (Hm[:2, :2] - np.outer(f, Hm[2, :2])) / w  # the derivative of the mapping at the corner
    e1, e2 = D @ J.T
    n1, n2 = np.linalg.norm(e1), np.linalg.norm(e2)
    if min(n1, n2) == 0:
        raise DegenerateError(
            "d1, d2: expected non-zero directions that H does not flatten, got a zero image; check them"
        )
    return float(np.degrees(np.arccos(np.clip(e1 @ e2 / (n1 * n2), -1.0, 1.0))))
