r"""Rotations and rigid poses.

Axis-angle (Rodrigues), Euler angles, the nearest rotation, look-at, and the conversion between the
OpenCV camera frame and OpenGL's and Blender's.

A rotation R is a (3, 3) orthonormal matrix with det R = +1; as cam_from_world its rows are
the camera's x, y, z axes written in world coordinates (docs/conventions.md). Angles in
radians. Part of :mod:`camlab.camera` (every name here is importable from there).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    ROTATION_TOL,
    DegenerateError,
    check_finite,
    check_matrix,
    check_number,
    check_positive,
    check_rotation,
)

__all__ = [
    "CV_FROM_GL",
    "Pose",
    "axis_angle_from_rotation",
    "axis_angle_from_rotation_unchecked",
    "euler_from_rotation",
    "is_rotation",
    "look_at_rotation",
    "nearest_rotation",
    "orbit_eye",
    "blender_matrix_world",
    "opencv_from_opengl",
    "opengl_from_opencv",
    "rotation_from_axis_angle",
    "rotation_from_axis_angle_unchecked",
    "rotation_from_euler",
    "rotation_x",
    "rotation_y",
    "rotation_z",
]


CV_FROM_GL = np.diag([1.0, -1.0, -1.0])
r"""Maps OpenGL/Blender camera axes (x right, y up, z backward) to OpenCV's (x right, y down,
z forward). It is its own inverse: :math:`F^{-1} = F`."""


def is_rotation(R: ArrayLike, tol: float = ROTATION_TOL) -> bool:
    r"""True if ``R`` is a (3, 3) rotation: :math:`R^\top R = I` and :math:`\det R = +1`.

    Parameters
    ----------
    R : array_like
        The candidate.
    tol : float, optional
        Tolerance on the entries of R^T R - I and on det R - 1.

    Returns
    -------
    bool
        True for a finite (3, 3) rotation.
    """
    a = np.asarray(R, dtype=float)
    if a.shape != (3, 3) or not np.isfinite(a).all():
        return False
    return bool(np.abs(a.T @ a - np.eye(3)).max() <= tol and abs(np.linalg.det(a) - 1.0) <= tol)


def rotation_from_axis_angle(rvec: ArrayLike) -> np.ndarray:
    r"""Rodrigues' formula: the rotation by angle :math:`\theta = \|r\|` (radians) about :math:`r / \|r\|`.

    .. math:: R = I + \sin\theta\,[k]_\times + (1 - \cos\theta)\,[k]_\times^2

    This is the ``rvec`` convention of ``cv2.Rodrigues``.

    Parameters
    ----------
    rvec : (3,) array_like
        Rotation vector: unit axis times angle in radians.

    Returns
    -------
    (3, 3) ndarray

    Examples
    --------
    >>> np.round(rotation_from_axis_angle([0, 0, np.pi / 2]), 12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    return rotation_from_axis_angle_unchecked(check_matrix(rvec, (3,), "rvec"))


def rotation_from_axis_angle_unchecked(r: np.ndarray) -> np.ndarray:
    """:func:`rotation_from_axis_angle` (the same formula, the same floats) without checking ``r``.

    For refiners that call it at every iteration on parameters they made themselves
    (:func:`camlab.measurement.solve_pnp`); anything else calls the checked one.

    Parameters
    ----------
    r : (3,) ndarray
        A finite float rotation vector, radians.

    Returns
    -------
    (3, 3) ndarray
        The rotation.
    """
    theta = math.sqrt(r.dot(r))  # np.linalg.norm(r), the same float
    if theta < 1e-15:
        return np.eye(3)
    k0, k1, k2 = (r / theta).tolist()
    kx = np.array([[0.0, -k2, k1], [k2, 0.0, -k0], [-k1, k0, 0.0]])
    return np.eye(3) + np.sin(theta) * kx + (1.0 - np.cos(theta)) * (kx @ kx)


def axis_angle_from_rotation(R: ArrayLike) -> np.ndarray:
    r"""The rotation vector (axis times angle, radians) of a rotation; inverse of :func:`rotation_from_axis_angle`.

    The angle is in :math:`[0, \pi]`.

    Uses :math:`\cos\theta = (\operatorname{tr} R - 1)/2` and the skew part
    :math:`(R - R^\top)/2 = \sin\theta [k]_\times`; near :math:`\theta = \pi` the axis is
    read from :math:`R + I` instead.

    Parameters
    ----------
    R : (3, 3) array_like
        A rotation matrix.

    Returns
    -------
    (3,) ndarray
        The unit axis times the angle, radians.

    References
    ----------
    .. [1] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022, section
       2.1.3 (axis/angle, Rodrigues' formula).
    """
    return axis_angle_from_rotation_unchecked(check_rotation(R))


def axis_angle_from_rotation_unchecked(a: np.ndarray) -> np.ndarray:
    """:func:`axis_angle_from_rotation` (the same formula, the same floats) without checking ``a``.

    For refiners that step a rotation at every iteration (:func:`camlab.measurement.solve_pnp`);
    anything else calls the checked one.

    Parameters
    ----------
    a : (3, 3) ndarray
        A float rotation matrix (orthonormal, det +1), e.g. a product of rotations.

    Returns
    -------
    (3,) ndarray
        The unit axis times the angle, radians.
    """
    (a00, a01, a02), (a10, a11, a12), (a20, a21, a22) = a.tolist()
    cos = min(max((a00 + a11 + a22 - 1.0) / 2.0, -1.0), 1.0)  # (tr R - 1) / 2, clipped
    theta = float(np.arccos(cos))
    w = np.array([a21 - a12, a02 - a20, a10 - a01]) / 2.0
    if theta < 1e-12:
        return w  # sin(theta) ~ theta: the skew part is already the rotation vector
    if np.pi - theta > 1e-6:
        return w / np.sin(theta) * theta
    # theta ~ pi: R + I = 2 k k^T; take the largest column for the axis, sign from w.
    B = (a + np.eye(3)) / 2.0
    k = B[:, int(np.argmax(np.diag(B)))]
    k = k / np.linalg.norm(k)
    if np.dot(k, w) < 0:
        k = -k
    return k * theta


def rotation_x(angle: float) -> np.ndarray:
    """Rotation by ``angle`` radians about the x axis (right-handed).

    Parameters
    ----------
    angle : float
        Rotation angle, radians.

    Returns
    -------
    (3, 3) ndarray
        The rotation matrix.
    """
    angle = check_number(angle, "angle", "radians")
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rotation_y(angle: float) -> np.ndarray:
    """Rotation by ``angle`` radians about the y axis (right-handed).

    Parameters
    ----------
    angle : float
        Rotation angle, radians.

    Returns
    -------
    (3, 3) ndarray
        The rotation matrix.
    """
    angle = check_number(angle, "angle", "radians")
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rotation_z(angle: float) -> np.ndarray:
    """Rotation by ``angle`` radians about the z axis (right-handed).

    Parameters
    ----------
    angle : float
        Rotation angle, radians.

    Returns
    -------
    (3, 3) ndarray
        The rotation matrix.
    """
    angle = check_number(angle, "angle", "radians")
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rotation_from_euler(rx: float, ry: float, rz: float) -> np.ndarray:
    r"""Rotation from Euler angles in radians: :math:`R = R_z(r_z) R_y(r_y) R_x(r_x)`.

    Read right to left: rotate about the fixed x axis first, then y, then z (extrinsic
    x-y-z, the same matrix as intrinsic z-y'-x''; roll-pitch-yaw for a z-up body).
    Inverse: :func:`euler_from_rotation`.

    Parameters
    ----------
    rx, ry, rz : float
        Angles about x, y and z, radians.

    Returns
    -------
    (3, 3) ndarray
        R = R_z R_y R_x.
    """
    angles = np.array([rx, ry, rz], dtype=float)
    check_finite(angles, "rx, ry, rz")
    return rotation_z(angles[2]) @ rotation_y(angles[1]) @ rotation_x(angles[0])


def nearest_rotation(M: ArrayLike) -> np.ndarray:
    r"""The rotation closest to M in the Frobenius norm: :math:`U \operatorname{diag}(1, 1, \det UV^\top) V^\top`.

    With the SVD :math:`M = U \Sigma V^\top`, :math:`\min_R \|R - M\|_F` over rotations is
    solved by replacing the singular values with ones (Zhang [1]_, appendix C); the last
    sign keeps :math:`\det R = +1`.

    Parameters
    ----------
    M : (3, 3) array_like
        A matrix of rank 2 or 3.

    Returns
    -------
    (3, 3) ndarray
        The nearest rotation.

    References
    ----------
    .. [1] Z. Zhang, 2000, "A flexible new technique for camera calibration", *IEEE
       Transactions on Pattern Analysis and Machine Intelligence* 22(11), 1330-1334 (technical
       report MSR-TR-98-71, appendix C).

    Examples
    --------
    >>> np.round(nearest_rotation(2 * np.eye(3)), 12) + 0.0
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    Mm = check_matrix(M, (3, 3), "M")
    U, sv, Vt = np.linalg.svd(Mm)
    if sv[1] <= 1e-12 * max(sv[0], 1e-300):
        raise DegenerateError(
            f"M: rank {int(np.sum(sv > 1e-12 * sv[0]))} (singular values "
            f"{np.array2string(sv, precision=3)}), so no rotation is nearest to it; "
            f"at least two of its columns must be independent"
        )
    D = np.diag([1.0, 1.0, np.sign(np.linalg.det(U @ Vt))])
    return U @ D @ Vt


def euler_from_rotation(R: ArrayLike) -> np.ndarray:
    r"""The angles ``(rx, ry, rz)`` with :math:`R = R_z R_y R_x`; inverse of :func:`rotation_from_euler`.

    ``ry`` is in :math:`[-\pi/2, \pi/2]`. At gimbal lock (:math:`|r_y| = \pi/2`) ``rx`` is
    set to 0.

    Parameters
    ----------
    R : (3, 3) array_like
        A rotation matrix.

    Returns
    -------
    (3,) ndarray
        ``(rx, ry, rz)``, radians.
    """
    a = check_rotation(R)
    ry = float(np.arcsin(np.clip(-a[2, 0], -1.0, 1.0)))
    if abs(a[2, 0]) < 1.0 - 1e-12:
        rx = float(np.arctan2(a[2, 1], a[2, 2]))
        rz = float(np.arctan2(a[1, 0], a[0, 0]))
    else:  # gimbal lock: only rz - rx (or rz + rx) is defined
        rx = 0.0
        rz = float(np.arctan2(-a[0, 1], a[1, 1]))
    return np.array([rx, ry, rz])


def orbit_eye(
    azimuth: float, elevation: float, distance: float, target: ArrayLike = (0.0, 0.0, 0.0)
) -> np.ndarray:
    r"""A camera position on the sphere of radius ``distance`` (metres) about ``target``, for a look-at.

    ``azimuth`` turns from world +x towards +y and ``elevation`` rises towards +z (up), in
    radians: :math:`C = T + d\,(\cos e \cos a, \cos e \sin a, \sin e)`.

    Parameters
    ----------
    azimuth : float
        Angle from world +x towards +y, radians.
    elevation : float
        Angle above the xy plane, radians.
    distance : float
        Radius d, metres (> 0).
    target : (3,) array_like, optional
        The centre T, world metres.

    Returns
    -------
    (3,) ndarray
        The camera position C, world metres.

    Examples
    --------
    >>> orbit_eye(np.pi / 2, 0.0, 2.0, (0, 0, 1)).round(12) + 0.0
    array([0., 2., 1.])
    """
    d = check_positive(distance, "distance", "metres")
    a, e = (
        check_number(azimuth, "azimuth", "radians"),
        check_number(elevation, "elevation", "radians"),
    )
    return check_matrix(target, (3,), "target") + d * np.array(
        [np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)]
    )


def look_at_rotation(
    eye: ArrayLike, target: ArrayLike, up: ArrayLike = (0.0, 0.0, 1.0)
) -> np.ndarray:
    r"""The cam_from_world rotation of a camera at ``eye`` looking at ``target``.

    The rows of R are the camera axes written in world coordinates: z (forward) points
    from eye to target, x (right) is :math:`z \times \text{up}` normalised, y (down)
    is :math:`z \times x`, so "up" appears up in the image.

    Parameters
    ----------
    eye : (3,) array_like
        The camera centre, world metres.
    target : (3,) array_like
        The point looked at, world metres.
    up : (3,) array_like, optional
        The world direction that appears up (default (0, 0, 1)).

    Returns
    -------
    (3, 3) ndarray
        R, cam_from_world: its rows are the camera's x, y, z axes in world coordinates.

    Raises
    ------
    DegenerateError
        If eye == target or the viewing direction is parallel to ``up``.
    """
    e = check_matrix(eye, (3,), "eye")
    g = check_matrix(target, (3,), "target")
    u = check_matrix(up, (3,), "up")
    z = g - e
    if np.linalg.norm(z) < 1e-12:
        raise DegenerateError(
            "look_at: eye and target coincide, so there is no viewing direction; move the eye"
        )
    z = z / np.linalg.norm(z)
    x = np.cross(z, u)
    if np.linalg.norm(x) < 1e-9 * max(np.linalg.norm(u), 1e-300):
        raise DegenerateError(
            f"look_at: the viewing direction {np.round(z, 6)} is parallel to up={u}, so 'right' is "
            f"undefined; choose another up vector"
        )
    x = x / np.linalg.norm(x)
    y = np.cross(z, x)
    return np.vstack([x, y, z])


class Pose(NamedTuple):
    """A rigid pose ``(R, t)``: :math:`X_{to} = R X_{from} + t`, R (3, 3) a rotation, t (3,).

    cam_from_world unless the function that returns it says otherwise; unpack it as ``R, t = ...``.
    """

    R: np.ndarray
    t: np.ndarray


def opengl_from_opencv(R: ArrayLike, t: ArrayLike) -> Pose:
    r"""Convert a cam_from_world pose from the OpenCV camera frame to the OpenGL/Blender one.

    Both describe the same physical camera; only the camera's axes are renamed:
    OpenGL's camera looks down its -z axis with y up. With :math:`F =
    \operatorname{diag}(1, -1, -1)`, :math:`R_{gl} = F R`, :math:`t_{gl} = F t`. A
    Blender camera's ``matrix_world`` is the inverse: ``[[R_gl^T, -R_gl^T t_gl], [0, 1]]``.

    Returns
    -------
    Pose
        ``R`` = :math:`R_{gl}` (3, 3) and ``t`` = :math:`t_{gl}` (3,).

    Parameters
    ----------
    R : (3, 3) array_like
        cam_from_world rotation, OpenCV camera frame.
    t : (3,) or (3, 1) array_like
        cam_from_world translation, metres (OpenCV's ``tvec`` is a (3, 1) column).
    """
    Rm = check_rotation(R)
    if np.shape(t) == (3, 1):  # OpenCV's tvec is a column
        t = np.reshape(t, 3)
    tv = check_matrix(t, (3,), "t")
    return Pose(CV_FROM_GL @ Rm, CV_FROM_GL @ tv)


def opencv_from_opengl(R_gl: ArrayLike, t_gl: ArrayLike) -> Pose:
    """Inverse of :func:`opengl_from_opencv` (the same flip, since F is its own inverse).

    Parameters
    ----------
    R_gl : (3, 3) array_like
        cam_from_world rotation, OpenGL/Blender camera frame.
    t_gl : (3,) array_like
        cam_from_world translation, metres.

    Returns
    -------
    Pose
        ``R`` (3, 3) and ``t`` (3,) in the OpenCV camera frame.
    """
    Rm = check_rotation(R_gl, "R_gl")
    tv = check_matrix(t_gl, (3,), "t_gl")
    return Pose(CV_FROM_GL @ Rm, CV_FROM_GL @ tv)


def blender_matrix_world(R: ArrayLike, t: ArrayLike) -> np.ndarray:
    r"""A Blender camera's ``matrix_world`` for the OpenCV pose cam_from_world ``(R, t)``.

    ``matrix_world`` is world_from_cam in the OpenGL/Blender camera frame, so two steps: flip the
    camera's y and z axes, :math:`R_{gl} = F R`, :math:`t_{gl} = F t` (:func:`opengl_from_opencv`),
    then invert the rigid motion:

    .. math:: \begin{pmatrix} R_{gl}^\top & -R_{gl}^\top t_{gl} \\ 0 & 1 \end{pmatrix}
              = \begin{pmatrix} R^\top F & C \\ 0 & 1 \end{pmatrix}, \qquad C = -R^\top t .

    Its columns are the camera's axes in the world (x right, y up, z backward) and its centre.

    Returns
    -------
    (4, 4) ndarray
        world_from_cam in the Blender camera frame.

    Parameters
    ----------
    R : (3, 3) array_like
        cam_from_world rotation, OpenCV camera frame.
    t : (3,) or (3, 1) array_like
        cam_from_world translation, metres (OpenCV's ``tvec`` is a (3, 1) column).
    """
    R_gl, t_gl = opengl_from_opencv(R, t)
    out = np.eye(4)
    out[:3, :3], out[:3, 3] = R_gl.T, -R_gl.T @ t_gl
    return out
