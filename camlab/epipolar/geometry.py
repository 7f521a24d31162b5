r"""Two-view geometry from known cameras: F and E, the epipoles, epipolar lines and distances.

:math:`\tilde x'^\top F \tilde x = 0`; :math:`F = [e']_\times P' P^+` from two cameras,
:math:`E = [t]_\times R` from the relative pose, :math:`F = K'^{-\top} E K^{-1}`; the
epipoles are F's null vectors and :math:`l' = F \tilde x` the epipolar line of x.

Part of :mod:`camlab.epipolar` (every name here is importable from there).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    CamlabInputError,
    DegenerateError,
    as_float,
    as_point_pairs,
    as_points,
    check_intrinsics,
    check_matrix,
    check_rotation,
)
from ..camera import Camera, Pose, camera_centre, check_camera_matrix, cross_matrix
from ..projective import normalise_lines, to_homogeneous

__all__ = [
    "Epipoles",
    "check_fundamental",
    "epipolar_distance",
    "epipolar_lines",
    "epipoles",
    "essential_from_fundamental",
    "essential_matrix",
    "fundamental_from_cameras",
    "fundamental_from_essential",
    "normalise_fundamental",
    "relative_pose",
    "skew",
]


def skew(v: ArrayLike) -> np.ndarray:
    r"""The cross-product matrix :math:`[v]_\times` with :math:`[v]_\times w = v \times w`.

    Parameters
    ----------
    v : (3,) array_like
        The vector.

    Returns
    -------
    (3, 3) ndarray
        [v]_x, antisymmetric.

    Examples
    --------
    >>> skew([1, 2, 3]) @ np.array([4, 5, 6]), np.cross([1, 2, 3], [4, 5, 6])
    (array([-3.,  6., -3.]), array([-3,  6, -3]))
    """
    return cross_matrix(check_matrix(v, (3,), "v"))


def check_fundamental(F: ArrayLike, name: str = "F") -> np.ndarray:
    """Return F as a float (3, 3) array, or raise if it is malformed or all zeros.

    Parameters
    ----------
    F : (3, 3) array_like
        The candidate.
    name : str, optional
        The argument's name in error messages.

    Returns
    -------
    (3, 3) float ndarray
        F, unscaled.
    """
    a = check_matrix(F, (3, 3), name)
    if not np.any(a):
        raise CamlabInputError(
            f"{name}: expected a non-zero (3, 3) fundamental matrix, got all zeros"
        )
    return a


def normalise_fundamental(F: ArrayLike) -> np.ndarray:
    """Scale F to unit Frobenius norm with its largest-magnitude entry positive (compare F's up to scale).

    Parameters
    ----------
    F : (3, 3) array_like
        A fundamental (or essential) matrix, not zero.

    Returns
    -------
    (3, 3) ndarray
        F / ||F||_F, sign chosen so the largest-magnitude entry is positive.

    Examples
    --------
    >>> normalise_fundamental(-2 * np.eye(3)).round(4)
    array([[0.5774, 0.    , 0.    ],
           [0.    , 0.5774, 0.    ],
           [0.    , 0.    , 0.5774]])
    """
    a = check_fundamental(F)
    a = a / np.linalg.norm(a)
    k = np.argmax(
        np.round(np.abs(a), 9)
    )  # ties (e.g. a skew-symmetric F): the first in row-major order
    return a * np.sign(a.flat[k])


def relative_pose(camera1: Camera, camera2: Camera) -> Pose:
    r"""Camera 2's pose relative to camera 1: ``(R, t)`` with :math:`X_2 = R X_1 + t`.

    With cam_from_world poses :math:`X_i = R_i X + t_i`:
    :math:`R = R_2 R_1^\top`, :math:`t = t_2 - R t_1`. The baseline length is
    :math:`\|t\| = \|C_2 - C_1\|` (metres).

    Parameters
    ----------
    camera1, camera2 : Camera
        The two cameras (cam_from_world poses).

    Returns
    -------
    Pose
        ``R`` (3, 3) and ``t`` (3,), cam2_from_cam1, metres.
    """
    for c, n in ((camera1, "camera1"), (camera2, "camera2")):
        if not isinstance(c, Camera):
            raise CamlabInputError(f"{n}: expected a camlab.camera.Camera, got {type(c).__name__}")
    R = camera2.R @ camera1.R.T
    return Pose(R, camera2.t - R @ camera1.t)


def essential_matrix(R: ArrayLike, t: ArrayLike) -> np.ndarray:
    r""":math:`E = [t]_\times R` for the relative pose :math:`X_2 = R X_1 + t`.

    Derivation: :math:`X_2 = R X_1 + t` and :math:`t`, :math:`X_2` and :math:`R X_1` are
    coplanar (the epipolar plane), so :math:`X_2 \cdot (t \times R X_1) = 0`, i.e.
    :math:`X_2^\top [t]_\times R X_1 = 0`; dividing by the depths gives
    :math:`\hat x_2^\top E \hat x_1 = 0` for normalised image points.

    Parameters
    ----------
    R : (3, 3) array_like
        Rotation cam2_from_cam1.
    t : (3,) array_like
        Translation cam2_from_cam1, metres.

    Returns
    -------
    (3, 3) ndarray
        E = [t]_x R (unscaled).

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 9.6 (the essential
       matrix).
    .. [2] H. C. Longuet-Higgins, 1981, "A computer algorithm for reconstructing a scene from
       two projections", *Nature* 293, 133-135.
    """
    Rm = check_rotation(R, "R")
    tv = check_matrix(np.ravel(as_float(t, "t")), (3,), "t")
    if not tv.any():
        raise DegenerateError(
            "t: zero translation gives E = 0: with no baseline the two views share one centre and "
            "there is no epipolar geometry (use a rotation homography instead)"
        )
    return skew(tv) @ Rm


def fundamental_from_cameras(
    camera1: Camera | ArrayLike, camera2: Camera | ArrayLike
) -> np.ndarray:
    r"""The fundamental matrix of two known cameras, unit Frobenius norm.

    Parameters
    ----------
    camera1, camera2 : Camera or (3, 4) array_like
        The cameras (distortion is ignored: F relates *undistorted* pixels), or their
        projection matrices.

    Returns
    -------
    (3, 3) ndarray
        F with ``x2_h @ F @ x1_h == 0`` for corresponding pixels.

    Notes
    -----
    For two :class:`~camlab.camera.Camera` objects,
    :math:`F = K_2^{-\top} [t]_\times R\, K_1^{-1}` with the relative pose from
    :func:`relative_pose`. For general projection matrices (H&Z result 9.1 [1]_),

    .. math:: F = [e']_\times P_2 P_1^+, \qquad e' = P_2 C_1,

    where :math:`C_1` is camera 1's centre (the null vector of :math:`P_1`) and
    :math:`P_1^+` its pseudo-inverse: :math:`P_1^+ x` is a point on the ray of :math:`x`,
    its image is :math:`P_2 P_1^+ x`, and the epipolar line joins it to the epipole.

    Raises
    ------
    DegenerateError
        If both cameras have the same centre (no baseline: no epipolar geometry).

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 9.2 (the
       fundamental matrix F, result 9.1).
    """
    if isinstance(camera1, Camera) and isinstance(camera2, Camera):
        R, t = relative_pose(camera1, camera2)
        base = np.linalg.norm(t)
        scale = max(np.linalg.norm(camera1.centre), np.linalg.norm(camera2.centre), 1.0)
        if base <= 1e-12 * scale:
            raise DegenerateError(
                "fundamental_from_cameras: the two cameras have the same centre (baseline 0 m); "
                "a pure rotation has no epipolar geometry (the images are related by a homography). "
                "Move one camera"
            )
        F = np.linalg.inv(camera2.K).T @ essential_matrix(R, t) @ np.linalg.inv(camera1.K)
        return normalise_fundamental(F)
    P1, P2 = check_camera_matrix(camera1, "camera1"), check_camera_matrix(camera2, "camera2")
    C1h = camera_centre(P1)  # (4,) homogeneous
    e2 = P2 @ C1h
    if np.linalg.norm(e2) <= 1e-12 * np.linalg.norm(P2) * np.linalg.norm(C1h):
        raise DegenerateError(
            "fundamental_from_cameras: camera 1's centre projects to 0 in camera 2, so both cameras have "
            "the same centre (no baseline); move one camera"
        )
    return normalise_fundamental(skew(e2) @ P2 @ np.linalg.pinv(P1))


def essential_from_fundamental(
    F: ArrayLike, K1: ArrayLike, K2: ArrayLike | None = None
) -> np.ndarray:
    r""":math:`E = K_2^\top F K_1`, projected onto the essential matrices (singular values (1, 1, 0)).

    A true essential matrix has two equal singular values and one zero (H&Z result 9.17 [1]_);
    an F estimated from noisy points gives an E that is close, and the closest one in the
    Frobenius norm replaces the singular values by their mean.

    Parameters
    ----------
    F : (3, 3) array_like
        The fundamental matrix, pixels.
    K1 : (3, 3) array_like
        Intrinsics of camera 1, pixels.
    K2 : (3, 3) array_like, optional
        Intrinsics of camera 2 (default K1).

    Returns
    -------
    (3, 3) ndarray
        E with singular values (1, 1, 0).

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 9.6.1 (properties
       of the essential matrix, result 9.17).
    """
    F = check_fundamental(F)
    K1 = check_intrinsics(K1, "K1")
    K2 = K1 if K2 is None else check_intrinsics(K2, "K2")
    U, s, Vt = np.linalg.svd(K2.T @ F @ K1)
    return U @ np.diag([1.0, 1.0, 0.0]) @ Vt


def fundamental_from_essential(
    E: ArrayLike, K1: ArrayLike, K2: ArrayLike | None = None
) -> np.ndarray:
    r""":math:`F = K_2^{-\top} E K_1^{-1}`, unit Frobenius norm.

    Parameters
    ----------
    E : (3, 3) array_like
        The essential matrix.
    K1 : (3, 3) array_like
        Intrinsics of camera 1, pixels.
    K2 : (3, 3) array_like, optional
        Intrinsics of camera 2 (default K1).

    Returns
    -------
    (3, 3) ndarray
        F, unit Frobenius norm.
    """
    E = check_fundamental(E, "E")
    K1 = check_intrinsics(K1, "K1")
    K2 = K1 if K2 is None else check_intrinsics(K2, "K2")
    return normalise_fundamental(np.linalg.inv(K2).T @ E @ np.linalg.inv(K1))


class Epipoles(NamedTuple):
    """Homogeneous epipoles, unit norm: ``e1`` in image 1 (F e1 = 0), ``e2`` in image 2 (F^T e2 = 0).

    An epipole with third coordinate 0 is an ideal point: the epipolar lines are parallel
    (the baseline is parallel to that image plane). ``from_homogeneous`` gives its pixel
    (NaN when ideal).
    """

    e1: np.ndarray
    e2: np.ndarray


def epipoles(F: ArrayLike) -> Epipoles:
    r"""The epipoles: the right and left null vectors of F (last singular vectors).

    ``e1`` is the image of camera 2's centre in image 1 and ``e2`` the image of camera 1's
    centre in image 2. Signs are chosen so the last non-zero coordinate is positive.

    Parameters
    ----------
    F : (3, 3) array_like
        The fundamental matrix.

    Returns
    -------
    Epipoles
        ``e1`` (3,) and ``e2`` (3,), homogeneous, unit norm.

    Examples
    --------
    >>> F = np.array([[0, 0, 0], [0, 0, -1], [0, 1, 0]])  # a pure x-translation: rows match
    >>> epipoles(F).e1
    array([1., 0., 0.])
    """
    F = check_fundamental(F)
    U, s, Vt = np.linalg.svd(F)
    out = []
    for e in (Vt[-1], U[:, -1]):
        nz = np.flatnonzero(np.abs(e) > 1e-12)
        out.append(e * np.sign(e[nz[-1]]) if len(nz) else e)
    return Epipoles(*out)


def epipolar_lines(F: ArrayLike, points: ArrayLike, image: int = 1) -> np.ndarray:
    r"""Epipolar lines in the *other* image for points in image ``image``.

    Parameters
    ----------
    F : (3, 3) array_like
        Fundamental matrix with ``x2_h @ F @ x1_h == 0``.
    points : (N, 2) or (2,) array_like
        Pixels (u, v) in image ``image``.
    image : {1, 2}
        1: points are in image 1, lines :math:`l' = F \tilde x` are in image 2;
        2: points are in image 2, lines :math:`l = F^\top \tilde x'` are in image 1.

    Returns
    -------
    (N, 3) or (3,) ndarray
        Lines (a, b, c) with :math:`a^2 + b^2 = 1`, so :math:`a u + b v + c` is the signed
        distance in pixels of (u, v) from the line. A point at the epipole (:math:`F \tilde x \approx 0`,
        relative to :math:`\|F\| \|\tilde x\|`, 1e-9) has no epipolar line: its row is NaN.

    >>> F = np.array([[0, 0, 0], [0, 0, -1], [0, 1, 0]])
    >>> epipolar_lines(F, [10, 20])  # the row v = 20
    array([ 0., -1., 20.])
    """
    F = check_fundamental(F)
    if image not in (1, 2):
        raise CamlabInputError(
            f"image: expected 1 or 2 (the image the points are in), got {image!r}"
        )
    p = as_points(points, 2, "points")
    M = F if image == 1 else F.T
    xh = to_homogeneous(p.array)
    lines = xh @ M.T
    # a point at the epipole has F x = 0 up to rounding: its line is undefined (NaN), not noise
    scale = np.linalg.norm(F) * np.linalg.norm(xh, axis=1)
    undefined = np.linalg.norm(lines[:, :2], axis=1) <= 1e-9 * scale
    lines[undefined] = 1.0  # a placeholder the normalisation accepts, replaced by NaN below
    out = normalise_lines(lines)
    out[undefined] = np.nan
    return p.restore(out)


def epipolar_distance(F: ArrayLike, x1: ArrayLike, x2: ArrayLike) -> np.ndarray:
    r"""Symmetric epipolar distance per pair, RMS in pixels.

    .. math:: d_i = \sqrt{\tfrac12\left(d(x'_i, F x_i)^2 + d(x_i, F^\top x'_i)^2\right)}

    Parameters
    ----------
    F : (3, 3) array_like
        The fundamental matrix, x2^T F x1 = 0.
    x1, x2 : (N, 2) or (2,) array_like
        Corresponding pixels in images 1 and 2.

    Returns
    -------
    (N,) ndarray
        d_i, pixels.
    """
    F = check_fundamental(F)
    a, b, single = as_point_pairs(x1, x2)
    d2 = np.sum(to_homogeneous(b) * epipolar_lines(F, a, 1), axis=1)
    d1 = np.sum(to_homogeneous(a) * epipolar_lines(F, b, 2), axis=1)
    out = np.sqrt(0.5 * (d1**2 + d2**2))
    return out[0] if single else out
