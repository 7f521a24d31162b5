r"""The projective camera :math:`P = K [R \mid t]`: project, back-project, decompose, resection.

A pinhole camera maps a world point :math:`X` (metres) to a pixel :math:`(u, v)` in two
steps. The *extrinsics* ``R, t`` move the point into the camera frame
(``cam_from_world``), and the *intrinsics* ``K`` map camera-frame directions to pixels:

.. math::

    X_c = R X + t, \qquad
    \lambda \begin{pmatrix} u \\ v \\ 1 \end{pmatrix} = K X_c, \qquad
    K = \begin{pmatrix} f_x & s & c_x \\ 0 & f_y & c_y \\ 0 & 0 & 1 \end{pmatrix},

so :math:`\lambda \tilde u = P \tilde X` with the 3x4 matrix :math:`P = K [R \mid t]`.
The depth :math:`\lambda = z_c` is positive in front of the camera; points with
:math:`z_c \le 0` have no image and come back as NaN.

Conventions (docs/conventions.md): camera frame x right, y down, z forward (OpenCV,
Hartley & Zisserman); ``R, t`` are *cam_from_world*; the camera centre is
:math:`C = -R^\top t`; pixels (u, v) = (column, row) with the origin at the centre of the
top-left pixel; points are rows, so the textbook :math:`x = P X` is ``X_h @ P.T``;
angles in radians. See lesson 04.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._validate import (
    ROTATION_TOL,
    CamlabInputError,
    ConvergenceError,
    DegenerateError,
    as_float,
    as_point_pairs,
    as_points,
    check_finite,
    check_intrinsics,
    check_matrix,
    check_number,
    check_positive,
    check_rotation,
    check_size,
)
from .distortion import beyond_valid_radius, distort_points
from .optimize import levenberg_marquardt, unit_sphere_basis, unit_sphere_update
from .projective import hartley_normalise

__all__ = [
    "Camera",
    "CameraPair",
    "Decomposition",
    "CV_FROM_GL",
    "Pose",
    "RQ",
    "axis_angle_from_rotation",
    "camera_centre",
    "check_camera_matrix",
    "check_rotation",
    "decompose_projection_matrix",
    "estimate_projection_matrix",
    "euler_from_rotation",
    "intrinsic_matrix",
    "centred_intrinsics",
    "is_rotation",
    "look_at_rotation",
    "nearest_rotation",
    "orbit_eye",
    "blender_matrix_world",
    "opencv_from_opengl",
    "opengl_from_opencv",
    "project_points",
    "reprojection_errors",
    "rotation_from_axis_angle",
    "rotation_from_euler",
    "rq_decomposition",
    "rotation_x",
    "rotation_y",
    "rotation_z",
    "scale_intrinsics",
    "project_segments",
]

CV_FROM_GL = np.diag([1.0, -1.0, -1.0])
r"""Maps OpenGL/Blender camera axes (x right, y up, z backward) to OpenCV's (x right, y down,
z forward). It is its own inverse: :math:`F^{-1} = F`."""


# ---------------------------------------------------------------------------------------
# Intrinsics and rotations
# ---------------------------------------------------------------------------------------


def intrinsic_matrix(fx: float, fy: float, cx: float, cy: float, skew: float = 0.0) -> np.ndarray:
    r"""The calibration matrix :math:`K` (pixels).

    .. math:: K = \begin{pmatrix} f_x & s & c_x \\ 0 & f_y & c_y \\ 0 & 0 & 1 \end{pmatrix}

    Parameters
    ----------
    fx, fy : float
        Focal lengths in pixels (focal length in metres times pixels per metre), > 0.
    cx, cy : float
        Principal point in pixels (u, v).
    skew : float
        Skew :math:`s = f_x \cot\theta` for pixel axes at angle :math:`\theta`; 0 for
        every modern sensor.

    Returns
    -------
    (3, 3) ndarray

    Examples
    --------
    >>> intrinsic_matrix(800, 800, 320, 240)
    array([[800.,   0., 320.],
           [  0., 800., 240.],
           [  0.,   0.,   1.]])
    """
    fx = check_positive(fx, "fx", "pixels")
    fy = check_positive(fy, "fy", "pixels")
    cx, cy = check_number(cx, "cx", "pixels"), check_number(cy, "cy", "pixels")
    skew = check_number(skew, "skew", "pixels")
    return np.array([[fx, skew, cx], [0.0, fy, cy], [0.0, 0.0, 1.0]])


def centred_intrinsics(f: float, size: tuple[int, int]) -> np.ndarray:
    r"""K with focal ``f`` pixels, square pixels, no skew and the principal point at the image centre.

    With pixel centres at integers (docs/conventions.md) the centre of a W x H image is
    :math:`c = ((W - 1)/2, (H - 1)/2)`, so
    :math:`K = \begin{pmatrix} f & 0 & (W - 1)/2 \\ 0 & f & (H - 1)/2 \\ 0 & 0 & 1 \end{pmatrix}`:
    the camera of every rendered scene and synthetic view.

    Parameters
    ----------
    f : float
        Focal length in pixels, > 0.
    size : (int, int)
        Image (width, height) in pixels.

    Returns
    -------
    (3, 3) ndarray

    Examples
    --------
    >>> centred_intrinsics(800, (640, 480))
    array([[800. ,   0. , 319.5],
           [  0. , 800. , 239.5],
           [  0. ,   0. ,   1. ]])
    """
    w, h = check_size(size)
    return intrinsic_matrix(f, f, (w - 1) / 2, (h - 1) / 2)


def is_rotation(R: ArrayLike, tol: float = ROTATION_TOL) -> bool:
    r"""True if ``R`` is a (3, 3) rotation: :math:`R^\top R = I` and :math:`\det R = +1`."""
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
    r = check_matrix(rvec, (3,), "rvec")
    theta = float(np.linalg.norm(r))
    if theta < 1e-15:
        return np.eye(3)
    k = r / theta
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + np.sin(theta) * kx + (1.0 - np.cos(theta)) * (kx @ kx)


def axis_angle_from_rotation(R: ArrayLike) -> np.ndarray:
    r"""The rotation vector (axis times angle, radians) of a rotation; inverse of
    :func:`rotation_from_axis_angle`, angle in :math:`[0, \pi]`.

    Uses :math:`\cos\theta = (\operatorname{tr} R - 1)/2` and the skew part
    :math:`(R - R^\top)/2 = \sin\theta [k]_\times`; near :math:`\theta = \pi` the axis is
    read from :math:`R + I` instead.
    """
    a = check_rotation(R)
    cos = np.clip((np.trace(a) - 1.0) / 2.0, -1.0, 1.0)
    theta = float(np.arccos(cos))
    w = np.array([a[2, 1] - a[1, 2], a[0, 2] - a[2, 0], a[1, 0] - a[0, 1]]) / 2.0
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
    """Rotation by ``angle`` radians about the x axis (right-handed)."""
    angle = check_number(angle, "angle", "radians")
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rotation_y(angle: float) -> np.ndarray:
    """Rotation by ``angle`` radians about the y axis (right-handed)."""
    angle = check_number(angle, "angle", "radians")
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rotation_z(angle: float) -> np.ndarray:
    """Rotation by ``angle`` radians about the z axis (right-handed)."""
    angle = check_number(angle, "angle", "radians")
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rotation_from_euler(rx: float, ry: float, rz: float) -> np.ndarray:
    r"""Rotation from Euler angles in radians: :math:`R = R_z(r_z) R_y(r_y) R_x(r_x)`.

    Read right to left: rotate about the fixed x axis first, then y, then z (extrinsic
    x-y-z, the same matrix as intrinsic z-y'-x''; roll-pitch-yaw for a z-up body).
    Inverse: :func:`euler_from_rotation`.
    """
    angles = np.array([rx, ry, rz], dtype=float)
    check_finite(angles, "rx, ry, rz")
    return rotation_z(angles[2]) @ rotation_y(angles[1]) @ rotation_x(angles[0])


def nearest_rotation(M: ArrayLike) -> np.ndarray:
    r"""The rotation closest to M in the Frobenius norm: :math:`U \operatorname{diag}(1, 1, \det UV^\top) V^\top`.

    With the SVD :math:`M = U \Sigma V^\top`, :math:`\min_R \|R - M\|_F` over rotations is
    solved by replacing the singular values with ones (Zhang 2000, appendix C); the last
    sign keeps :math:`\det R = +1`.

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
    r"""The angles ``(rx, ry, rz)`` with :math:`R = R_z R_y R_x`, ``ry`` in
    :math:`[-\pi/2, \pi/2]`. At gimbal lock (:math:`|r_y| = \pi/2`) ``rx`` is set to 0."""
    a = check_rotation(R)
    ry = float(np.arcsin(np.clip(-a[2, 0], -1.0, 1.0)))
    if abs(a[2, 0]) < 1.0 - 1e-12:
        rx = float(np.arctan2(a[2, 1], a[2, 2]))
        rz = float(np.arctan2(a[1, 0], a[0, 0]))
    else:  # gimbal lock: only rz - rx (or rz + rx) is defined
        rx = 0.0
        rz = float(np.arctan2(-a[0, 1], a[1, 1]))
    return np.array([rx, ry, rz])


def scale_intrinsics(K: ArrayLike, scale: float) -> np.ndarray:
    r"""Intrinsics of the same camera with its images resized by ``scale``.

    With the pixel-centre convention (u = 0 is the centre of the first pixel), resizing by
    s maps u to :math:`s (u + 1/2) - 1/2`: :math:`K' = S K`,
    :math:`S = \begin{pmatrix} s & 0 & (s-1)/2 \\ 0 & s & (s-1)/2 \\ 0 & 0 & 1\end{pmatrix}`.
    Also maps homographies between resized images: :math:`S H S^{-1}`.

    >>> scale_intrinsics(intrinsic_matrix(800, 800, 319.5, 239.5), 2.0)[:2]
    array([[1600. ,    0. ,  639.5],
           [   0. , 1600. ,  479.5]])
    """
    s = check_positive(scale, "scale")
    S = np.array([[s, 0, (s - 1) / 2], [0, s, (s - 1) / 2], [0, 0, 1]])
    return S @ check_matrix(K, (3, 3), "K")


def orbit_eye(
    azimuth: float, elevation: float, distance: float, target: ArrayLike = (0.0, 0.0, 0.0)
) -> np.ndarray:
    r"""A camera position on the sphere of radius ``distance`` (metres) about ``target``, for a look-at.

    ``azimuth`` turns from world +x towards +y and ``elevation`` rises towards +z (up), in
    radians: :math:`C = T + d\,(\cos e \cos a, \cos e \sin a, \sin e)`.

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


class CameraPair(NamedTuple):
    """Two views of one scene (cam_from_world poses): ``camera1`` and ``camera2``."""

    camera1: Camera
    camera2: Camera


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
    """
    Rm = check_rotation(R)
    tv = check_matrix(t, (3,), "t")
    return Pose(CV_FROM_GL @ Rm, CV_FROM_GL @ tv)


def opencv_from_opengl(R_gl: ArrayLike, t_gl: ArrayLike) -> Pose:
    """Inverse of :func:`opengl_from_opencv` (the same flip, since F is its own inverse)."""
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
    """
    R_gl, t_gl = opengl_from_opencv(R, t)
    out = np.eye(4)
    out[:3, :3], out[:3, 3] = R_gl.T, -R_gl.T @ t_gl
    return out


# ---------------------------------------------------------------------------------------
# The Camera
# ---------------------------------------------------------------------------------------


def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=float)
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class Camera:
    r"""A pinhole camera :math:`P = K [R \mid t]` with optional lens distortion.

    Parameters
    ----------
    K : (3, 3) array_like
        Intrinsics (pixels), upper triangular, last row (0, 0, 1), positive focal lengths.
    R : (3, 3) array_like
        Rotation cam_from_world: its rows are the camera's x, y, z axes in world coordinates.
    t : (3,) array_like
        Translation cam_from_world (metres): the world origin in camera coordinates.
        It is *not* the camera's position; that is :attr:`centre` :math:`= -R^\top t`.
    dist : tuple of 5 floats
        Distortion ``(k1, k2, p1, p2, k3)`` in OpenCV's order. :meth:`project` applies it;
        :meth:`backproject` needs undistorted pixels (use camlab.distortion first).
    image_size : (width, height)
        Image size in pixels.

    All arrays are stored as read-only float copies; use :meth:`replace` for a changed copy.

    Examples
    --------
    >>> cam = Camera.look_at(eye=[0, -5, 1], target=[0, 0, 1])
    >>> cam.project([0, 0, 1])
    array([319.5, 239.5])
    >>> np.round(cam.centre, 12) + 0.0
    array([ 0., -5.,  1.])
    """

    K: np.ndarray
    R: np.ndarray = dataclasses.field(default_factory=lambda: np.eye(3))
    t: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(3))
    dist: tuple[float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0)
    image_size: tuple[int, int] = (640, 480)

    def __post_init__(self) -> None:
        object.__setattr__(self, "K", _frozen(check_intrinsics(self.K)))
        object.__setattr__(self, "R", _frozen(check_rotation(self.R)))
        object.__setattr__(self, "t", _frozen(check_matrix(self.t, (3,), "t")))
        d = np.asarray(self.dist, dtype=float).ravel()
        if d.shape != (5,) or not np.isfinite(d).all():
            raise CamlabInputError(
                f"dist: expected 5 finite coefficients (k1, k2, p1, p2, k3) in OpenCV order, got {self.dist!r}; "
                f"pad with zeros"
            )
        object.__setattr__(self, "dist", tuple(float(v) for v in d))
        object.__setattr__(self, "image_size", check_size(self.image_size, "image_size"))

    # -- constructors --------------------------------------------------------------------
    @classmethod
    def from_fov(
        cls,
        fov_x: float,
        image_size: tuple[int, int] = (640, 480),
        R: ArrayLike | None = None,
        t: ArrayLike | None = None,
        dist: tuple[float, ...] = (0.0,) * 5,
    ) -> Camera:
        r"""A camera with square pixels and the principal point at the image centre, from
        its horizontal field of view ``fov_x`` (radians, in (0, pi)):
        :math:`f = (W / 2) / \tan(\mathrm{fov}_x / 2)`, :math:`c = ((W - 1)/2, (H - 1)/2)`.
        """
        fov = float(fov_x)
        if not 0.0 < fov < np.pi:
            raise CamlabInputError(
                f"fov_x: expected a field of view in radians in (0, pi), got {fov_x!r}; "
                f"use np.deg2rad(60) for 60 degrees"
            )
        w, h = (int(v) for v in image_size)
        f = (w / 2.0) / np.tan(fov / 2.0)
        K = centred_intrinsics(f, (w, h))
        return cls(K, np.eye(3) if R is None else R, np.zeros(3) if t is None else t, dist, (w, h))

    @classmethod
    def look_at(
        cls,
        eye: ArrayLike,
        target: ArrayLike,
        up: ArrayLike = (0.0, 0.0, 1.0),
        K: ArrayLike | None = None,
        image_size: tuple[int, int] = (640, 480),
        dist: tuple[float, ...] = (0.0,) * 5,
    ) -> Camera:
        r"""A camera at ``eye`` (world metres) looking at ``target``, with ``up`` (default world
        +z) appearing up in the image. ``K`` defaults to fx = fy = 800 px with the principal
        point at the image centre ((W - 1) / 2, (H - 1) / 2), as in :meth:`from_fov` (pixel
        centres are at integers). :math:`t = -R\,\text{eye}`."""
        R = look_at_rotation(eye, target, up)
        e = np.asarray(eye, dtype=float)
        if K is None:
            w, h = (int(v) for v in image_size)
            K = centred_intrinsics(800.0, (w, h))
        return cls(K, R, -R @ e, dist, image_size)

    def replace(self, **changes) -> Camera:
        """A copy with some fields changed, e.g. ``cam.replace(K=new_K)``."""
        return dataclasses.replace(self, **changes)

    def resized(self, scale: float) -> Camera:
        """The same camera taking images resized by ``scale`` (K by :func:`scale_intrinsics`).

        ``image_size * scale`` must be whole pixels (e.g. 0.5 for 640 x 480).

        >>> Camera(intrinsic_matrix(800, 800, 319.5, 239.5)).resized(0.5).K[0]
        array([400. ,   0. , 159.5])
        """
        s = check_positive(scale, "scale")
        w, h = self.image_size
        size = check_size((w * s, h * s), "image_size * scale")
        return dataclasses.replace(self, K=scale_intrinsics(self.K, s), image_size=size)

    # -- derived quantities --------------------------------------------------------------
    @property
    def P(self) -> np.ndarray:
        r"""The (3, 4) projection matrix :math:`K [R \mid t]`."""
        return self.K @ np.hstack([self.R, self.t[:, None]])

    @property
    def centre(self) -> np.ndarray:
        r"""The camera centre in world coordinates, :math:`C = -R^\top t` (metres): the
        point with :math:`P \tilde C = 0`."""
        return -self.R.T @ self.t

    @property
    def principal_axis(self) -> np.ndarray:
        """Unit viewing direction (camera +z) in world coordinates: the third row of R."""
        return self.R[2].copy()

    @property
    def principal_point(self) -> np.ndarray:
        """(cx, cy) in pixels: where the principal axis pierces the image."""
        return self.K[:2, 2].copy()

    @property
    def cam_from_world(self) -> np.ndarray:
        """The (4, 4) rigid transform ``[[R, t], [0, 1]]`` taking world points to the camera frame."""
        T = np.eye(4)
        T[:3, :3], T[:3, 3] = self.R, self.t
        return T

    @property
    def world_from_cam(self) -> np.ndarray:
        r"""The (4, 4) inverse ``[[R^T, C], [0, 1]]``: the camera's pose in the world (its
        columns are the camera axes and centre in world coordinates)."""
        T = np.eye(4)
        T[:3, :3], T[:3, 3] = self.R.T, self.centre
        return T

    # -- mapping points --------------------------------------------------------------------
    def to_camera(self, points_world: ArrayLike) -> np.ndarray:
        """World points (N, 3) to camera coordinates :math:`X_c = R X + t` (metres)."""
        p = as_points(points_world, 3, "points_world", finite=False)
        return p.restore(p.array @ self.R.T + self.t)

    def project(self, points_world: ArrayLike) -> np.ndarray:
        r"""Project world points to pixels.

        Parameters
        ----------
        points_world : (N, 3) or (3,) array_like
            Points in the world frame, metres.

        Returns
        -------
        (N, 2) or (2,) ndarray
            Pixel coordinates (u, v); NaN for points with :math:`z_c \le 0` (behind or
            on the camera's plane), which have no image, and for points beyond the
            distortion model's valid radius (:func:`camlab.distortion.max_valid_radius`).

        Notes
        -----
        .. math:: x_n = (X_c / Z_c,\ Y_c / Z_c),\quad x_d = \operatorname{distort}(x_n),\quad
                  \tilde u = K \tilde x_d

        The distortion step is OpenCV's (k1, k2, p1, p2, k3) model and is the identity
        when ``dist`` is all zero. See lesson 04, section 2.
        """
        p = as_points(points_world, 3, "points_world", finite=False)
        Xc = p.array @ self.R.T + self.t
        z = Xc[:, 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            xn = Xc[:, :2] / np.where(z > 0, z, np.nan)[:, None]
        if any(self.dist):
            ok = np.isfinite(xn).all(axis=1)  # points behind the camera stay NaN
            far = beyond_valid_radius(
                xn, self.dist
            )  # the model folds back there: no pixel, not a mirrored one
            if ok.any():
                xn[ok] = distort_points(xn[ok], self.dist)
            xn[far] = np.nan
        uv = xn @ self.K[:2, :2].T + self.K[:2, 2]
        return p.restore(uv)

    def depth(self, points_world: ArrayLike) -> np.ndarray:
        """The depth :math:`z_c` of each world point along the principal axis (metres)."""
        p = as_points(points_world, 3, "points_world", finite=False)
        return p.restore(p.array @ self.R[2] + self.t[2])

    def backproject(self, uv: ArrayLike, depth: ArrayLike | None = None) -> np.ndarray:
        r"""Back-project pixels to world rays or to world points at a given depth.

        Parameters
        ----------
        uv : (N, 2) or (2,) array_like
            Undistorted pixel coordinates (u, v).
        depth : None, float or (N,) array_like
            ``None``: return unit ray directions (world frame) from :attr:`centre` through
            each pixel. A number or one per pixel: return the world points whose camera
            depth :math:`z_c` equals it (metres, > 0), so that
            ``project(backproject(uv, d)) == uv``.

        Returns
        -------
        (N, 3) or (3,) ndarray
            Unit directions (``depth=None``) or world points.

        Notes
        -----
        .. math:: X_c = z\,K^{-1}\tilde u, \qquad X = R^\top (X_c - t) = C + z\,R^\top K^{-1} \tilde u
        """
        if any(self.dist):
            raise CamlabInputError(
                "backproject: this camera has lens distortion; undistort the pixels first "
                "(camlab.distortion) and call backproject on camera.replace(dist=(0,) * 5)"
            )
        p = as_points(uv, 2, "uv")
        rays_c = np.linalg.solve(self.K, np.hstack([p.array, np.ones((len(p.array), 1))]).T).T
        if depth is None:
            d = rays_c @ self.R  # = (R^T rays_c^T)^T
            return p.restore(d / np.linalg.norm(d, axis=1, keepdims=True))
        z = np.asarray(depth, dtype=float)
        if z.ndim > 1 or (z.ndim == 1 and len(z) != len(p.array)):
            raise CamlabInputError(
                f"depth: expected a number or one depth per pixel ({len(p.array)}), "
                f"got shape {z.shape}"
            )
        if not np.all(np.isfinite(z)) or np.any(z <= 0):
            raise CamlabInputError(
                f"depth: expected depths > 0 (metres in front of the camera), got {depth!r}; "
                f"points at depth <= 0 are behind the camera and have no pixel"
            )
        Xc = rays_c * np.reshape(z, (-1, 1))
        return p.restore((Xc - self.t) @ self.R)

    def in_image(self, uv: ArrayLike) -> np.ndarray:
        """(N,) bool: pixel lies inside the image (centre-of-pixel convention)."""
        p = as_points(uv, 2, "uv", finite=False)
        w, h = self.image_size
        u, v = p.array.T
        ok = (u >= -0.5) & (u <= w - 0.5) & (v >= -0.5) & (v <= h - 0.5)
        return p.restore(ok)

    def __repr__(self) -> str:
        fx, fy, cx, cy = self.K[0, 0], self.K[1, 1], self.K[0, 2], self.K[1, 2]
        C = np.round(self.centre, 4)
        return (
            f"Camera(fx={fx:.6g}, fy={fy:.6g}, cx={cx:.6g}, cy={cy:.6g}, skew={self.K[0, 1]:.3g}, "
            f"centre={C.tolist()}, image_size={self.image_size})"
        )


# ---------------------------------------------------------------------------------------
# General projection matrices
# ---------------------------------------------------------------------------------------


def check_camera_matrix(P: Camera | ArrayLike, name: str = "P") -> np.ndarray:
    """The (3, 4) matrix of a camera: ``P.P`` for a :class:`Camera` (its distortion left out), else P
    checked to have rank 3.

    Raises
    ------
    CamlabInputError
        P is not a finite (3, 4) array.
    DegenerateError
        P has rank below 3 (it maps all of space to a line or a point).
    """
    if isinstance(P, Camera):
        return P.P
    a = check_matrix(P, (3, 4), name)
    s = np.linalg.svd(a, compute_uv=False)
    if s[0] == 0 or s[2] <= 1e-12 * s[0]:
        raise DegenerateError(
            f"{name}: a camera matrix has rank 3, this one has rank {int(np.sum(s > 1e-12 * s[0]))} "
            f"(singular values {np.array2string(s, precision=3)}); it maps all of space to a line or "
            f"point; pass a Camera or K @ [R | t]"
        )
    return a


def project_points(P: Camera | ArrayLike, points_world: ArrayLike) -> np.ndarray:
    r"""Project world points with any 3x4 camera matrix: :math:`\lambda \tilde u = P \tilde X`.

    Works for projective and affine cameras alike. For a finite camera the sign of the
    depth is :math:`\operatorname{sign}(\det M)\,w` (M = P's left 3x3 block), which does not
    change when P is scaled, so points behind the camera come back as NaN whatever the
    scale of P. Affine cameras (M singular) see every point.

    Parameters
    ----------
    P : Camera or (3, 4) array_like
        A :class:`Camera` projects with :meth:`Camera.project` (its lens distortion too).
    points_world : (N, 3) or (3,) array_like

    Returns
    -------
    (N, 2) or (2,) ndarray
        Pixels; NaN where the point is behind a finite camera or maps to infinity.
    """
    if isinstance(P, Camera):
        return P.project(points_world)
    Pm = check_camera_matrix(P)
    p = as_points(points_world, 3, "points_world", finite=False)
    x = p.array @ Pm[:, :3].T + Pm[:, 3]
    w = x[:, 2]
    det = np.linalg.det(Pm[:, :3])
    scale = np.abs(Pm).max()
    if abs(det) > 1e-12 * scale**3:
        behind = np.sign(det) * w <= 0
    else:
        behind = w == 0
    with np.errstate(divide="ignore", invalid="ignore"):
        uv = x[:, :2] / np.where(behind, np.nan, w)[:, None]
    return p.restore(uv)


def camera_centre(P: ArrayLike) -> np.ndarray:
    r"""The camera centre: the right null space of P, :math:`P \tilde C = 0`.

    Returns
    -------
    (4,) ndarray
        The homogeneous centre, scaled to w = 1 for a finite camera. An affine camera has
        its centre at infinity: w = 0 and (x, y, z) is the (unit) viewing direction.

    Notes
    -----
    The last right singular vector of P spans its null space. For a finite camera
    :math:`P = [M \mid p_4]` this equals :math:`(-M^{-1} p_4, 1)`.
    """
    Pm = check_camera_matrix(P)
    _, _, Vt = np.linalg.svd(Pm)
    C = Vt[-1]
    if abs(C[3]) > 1e-12 * np.abs(C).max():
        return C / C[3]
    return C / np.linalg.norm(C[:3])


class Decomposition(NamedTuple):
    """The factors of :math:`P = \\lambda K [R \\mid t]`: K (K[2, 2] = 1, positive focal lengths),
    R (det +1), t (cam_from_world) and the camera centre C = -R^T t."""

    K: np.ndarray
    R: np.ndarray
    t: np.ndarray
    centre: np.ndarray


class RQ(NamedTuple):
    """The factors of :func:`rq_decomposition`: ``K`` upper triangular, ``R`` orthogonal."""

    K: np.ndarray
    R: np.ndarray


def rq_decomposition(M: ArrayLike) -> RQ:
    r"""RQ decomposition :math:`M = K R`: K upper triangular with a positive diagonal, R orthogonal.

    numpy only has QR (orthogonal times triangular), so we reverse the order of rows.
    With the exchange matrix E (ones on the anti-diagonal, :math:`E = E^\top = E^{-1}`),
    QR of :math:`(E M)^\top = Q' U'` gives :math:`M = E U'^\top Q'^\top = (E U'^\top E)(E Q'^\top)`,
    and :math:`E U'^\top E` is upper triangular. The factors are unique only up to
    :math:`D = \operatorname{diag}(\pm 1, \pm 1, \pm 1)` since :math:`K R = (K D)(D R)`;
    choosing D = sign(diag(K)) makes the diagonal of K positive. Then
    :math:`\det R = \operatorname{sign}(\det M)`: R is a rotation exactly when det M > 0.

    Parameters
    ----------
    M : (3, 3) array_like
        Invertible, e.g. the left 3x3 block of a camera matrix.

    Returns
    -------
    RQ
        ``K`` (3, 3): upper triangular, positive diagonal (not normalised: K[2, 2] carries
        M's scale); ``R`` (3, 3): orthogonal.

    Examples
    --------
    >>> K, R = rq_decomposition(np.diag([2.0, -3.0, 4.0]))
    >>> np.diag(K), np.diag(R)
    (array([2., 3., 4.]), array([ 1., -1.,  1.]))
    """
    Mm = check_matrix(M, (3, 3), "M")
    if abs(np.linalg.det(Mm)) <= 1e-12 * max(np.abs(Mm).max(), 1e-300) ** 3:
        raise DegenerateError(
            "rq_decomposition: M is singular, so K would have a zero on its diagonal; "
            "a finite camera has an invertible left 3x3 block"
        )
    E = np.eye(3)[::-1]
    Q, U = np.linalg.qr((E @ Mm).T)
    K, R = E @ U.T @ E, E @ Q.T
    D = np.diag(np.sign(np.diag(K)))
    return RQ(K @ D, D @ R)


def decompose_projection_matrix(P: ArrayLike) -> Decomposition:
    r"""Factor a finite camera :math:`P = \lambda K [R \mid t]` by RQ decomposition.

    Derivation (H&Z section 6.2.4): the left 3x3 block is :math:`M = \lambda K R`, an
    upper-triangular matrix times a rotation, which is exactly an RQ decomposition.
    RQ is unique only up to signs: :math:`K R = (K D)(D R)` for any
    :math:`D = \operatorname{diag}(\pm 1, \pm 1, \pm 1)`. We

    1. flip the sign of P if :math:`\det M < 0` (P is defined up to scale; now
       :math:`\det(\lambda K R) > 0`);
    2. choose D = sign(diag(K)) so the focal lengths and K[2, 2] are positive; then
       :math:`\det R = \det M / \det K > 0`, so R is a rotation;
    3. read :math:`t = K^{-1} p_4` with the still unnormalised K (it carries
       :math:`\lambda`), then divide K by K[2, 2].

    The centre is :math:`C = -R^\top t`, the null space of P.

    Parameters
    ----------
    P : (3, 4) array_like
        A finite projective camera (left 3x3 block invertible), any scale or sign.

    Returns
    -------
    Decomposition
        ``(K, R, t, centre)``.

    Raises
    ------
    DegenerateError
        If P has rank < 3, or M is singular (an affine camera: use camlab.affine).

    Examples
    --------
    >>> cam = Camera.look_at([4, -3, 2], [0, 0, 0])
    >>> K, R, t, C = decompose_projection_matrix(-2.5 * cam.P)
    >>> bool(np.allclose(K, cam.K) and np.allclose(R, cam.R) and np.allclose(C, [4, -3, 2]))
    True
    """
    Pm = check_camera_matrix(P)
    M = Pm[:, :3]
    s = np.linalg.svd(M, compute_uv=False)
    if s[2] <= 1e-10 * s[0]:
        raise DegenerateError(
            "decompose_projection_matrix: P's left 3x3 block M is singular, so the camera centre is at "
            "infinity (an affine camera) and P has no K [R | t] form; see camlab.affine"
        )
    if np.linalg.det(M) < 0:
        Pm = -Pm
        M = Pm[:, :3]
    K, R = rq_decomposition(M)
    t = np.linalg.solve(K, Pm[:, 3])
    K = K / K[2, 2]
    K[1, 0] = K[2, 0] = K[2, 1] = 0.0  # exactly triangular (they are ~1e-17 after RQ)
    return Decomposition(K, R, t, -R.T @ t)


# ---------------------------------------------------------------------------------------
# Resectioning: the DLT for cameras
# ---------------------------------------------------------------------------------------


def reprojection_errors(
    P: Camera | ArrayLike, points_world: ArrayLike, points_image: ArrayLike
) -> np.ndarray:
    """(N,) distances in pixels between ``points_image`` and the projections of ``points_world``.

    ``P`` is a :class:`Camera` or a (3, 4) camera matrix (:func:`project_points`); a point
    behind the camera has no projection, and its distance is NaN.
    """
    X, uv, _ = as_point_pairs(
        points_world, points_image, ("points_world", "points_image"), (3, 2), finite=False
    )
    check_finite(uv, "points_image")
    return np.linalg.norm(project_points(P, X) - uv, axis=1)


def _thinnest_spread(sv: np.ndarray) -> str:
    """Words for how flat a point set is, from its singular values (widest first)."""
    ratio = sv[2] / max(sv[0], 1e-300)
    if ratio == 0.0:
        return "they have no spread at all across their thinnest direction"
    return f"their spread across the thinnest direction is only {ratio:.1e} times the widest"


def estimate_projection_matrix(
    points_world: ArrayLike,
    points_image: ArrayLike,
    refine: bool = False,
) -> np.ndarray:
    r"""Estimate P from N >= 6 world-image correspondences (resectioning, the camera DLT).

    Each correspondence :math:`\tilde u_i \simeq P \tilde X_i` gives, from
    :math:`\tilde u_i \times P \tilde X_i = 0`, two linear equations in the 12 entries
    of P (rows :math:`p^{1\top}, p^{2\top}, p^{3\top}`):

    .. math::

        \begin{pmatrix} \tilde X_i^\top & 0^\top & -u_i \tilde X_i^\top \\
                        0^\top & \tilde X_i^\top & -v_i \tilde X_i^\top \end{pmatrix}
        \begin{pmatrix} p^1 \\ p^2 \\ p^3 \end{pmatrix} = 0 .

    Stacking gives :math:`A p = 0` with A of size 2N x 12; P has 11 degrees of freedom, so
    5.5 correspondences are needed and we ask for 6. The least-squares solution with
    :math:`\|p\| = 1` is the right singular vector of A with the smallest singular value.

    Hartley normalisation (H&Z algorithm 7.1) makes this well conditioned: the image
    points are moved to centroid 0 and mean distance :math:`\sqrt 2` by T, the world
    points to centroid 0 and mean distance :math:`\sqrt 3` by U, the DLT estimates
    :math:`\hat P` for the normalised points, and :math:`P = T^{-1} \hat P U`.

    With ``refine=True`` the linear estimate seeds Levenberg-Marquardt
    (:func:`camlab.optimize.levenberg_marquardt`, on the unit sphere of P's 12 entries) on the
    reprojection error
    :math:`\sum_i \|u_i - \pi(P, X_i)\|^2`, the maximum-likelihood (gold standard)
    estimate under Gaussian pixel noise.

    Parameters
    ----------
    points_world : (N, 3) array_like
        World points (metres), not all on one plane.
    points_image : (N, 2) array_like
        Their pixels (u, v).
    refine : bool
        Polish the linear estimate by minimising reprojection error.

    Returns
    -------
    (3, 4) ndarray
        P scaled so that its third row's first three entries have unit norm and
        :math:`\det M > 0`; then ``P @ [X, 1]`` has the point's depth as third coordinate.

    Raises
    ------
    CamlabInputError
        Fewer than 6 correspondences, or different counts.
    DegenerateError
        The world points are coplanar (or collinear): P is then not determined, since a
        plane only fixes a homography (8 of P's 11 degrees of freedom). Also raised when
        the solution is not unique for another reason.
    """
    X, uv, _ = as_point_pairs(
        points_world,
        points_image,
        ("points_world", "points_image"),
        (3, 2),
        min_count=6,
        why="P has 11 degrees of freedom and each point gives 2 equations; add more points",
    )
    sv = np.linalg.svd(X - X.mean(axis=0), compute_uv=False)
    if sv[2] <= 1e-9 * sv[0]:
        raise DegenerateError(
            f"estimate_projection_matrix: the {len(X)} world points are coplanar ({_thinnest_spread(sv)}), "
            f"so P is not determined; "
            f"use points on at least two planes (e.g. two faces of a box), or a homography for one plane"
        )
    T = hartley_normalise(uv, "points_image").T
    U = hartley_normalise(X, "points_world").T
    Xn = np.hstack([X, np.ones((len(X), 1))]) @ U.T
    un = (np.hstack([uv, np.ones((len(uv), 1))]) @ T.T)[:, :2]
    n = len(X)
    A = np.zeros((2 * n, 12))
    A[0::2, 0:4] = Xn
    A[0::2, 8:12] = -un[:, :1] * Xn
    A[1::2, 4:8] = Xn
    A[1::2, 8:12] = -un[:, 1:] * Xn
    _, s, Vt = np.linalg.svd(A, full_matrices=False)  # U is never needed: keep it (2N, 12)
    if s[-2] <= 1e-10 * s[0]:
        raise DegenerateError(
            "estimate_projection_matrix: the correspondences do not fix P uniquely (A has a null space of "
            "dimension > 1); the points and camera may lie on a twisted cubic, pick more varied points"
        )
    Pn = Vt[-1].reshape(3, 4)
    P = np.linalg.solve(T, Pn @ U)
    P = _normalise_P(P)
    if refine:
        P = _refine_projection_matrix(P, X, uv)
    return P


def _normalise_P(P: np.ndarray) -> np.ndarray:
    P = P / np.linalg.norm(P[2, :3])
    if np.linalg.det(P[:, :3]) < 0:
        P = -P
    return P


def _refine_projection_matrix(P0: np.ndarray, X: np.ndarray, uv: np.ndarray) -> np.ndarray:
    """Gold-standard P: LM on the reprojection error, stepping on the unit sphere of the 12 entries."""
    Xh = np.hstack([X, np.ones((len(X), 1))])

    def residuals(p: np.ndarray) -> np.ndarray:
        x = Xh @ p.reshape(3, 4).T
        return (x[:, :2] / x[:, 2:] - uv).ravel()

    def jacobian(p: np.ndarray) -> np.ndarray:
        # u = a / w, v = b / w with a = p1 . X, b = p2 . X, w = p3 . X:
        # du/dp1 = X / w, du/dp3 = -u X / w, dv/dp2 = X / w, dv/dp3 = -v X / w.
        x = Xh @ p.reshape(3, 4).T
        w = x[:, 2:]
        u, v = x[:, :1] / w, x[:, 1:2] / w
        J = np.zeros((len(Xh), 2, 12))
        J[:, 0, 0:4] = Xh / w
        J[:, 0, 8:12] = -u * Xh / w
        J[:, 1, 4:8] = Xh / w
        J[:, 1, 8:12] = -v * Xh / w
        return J.reshape(-1, 12) @ unit_sphere_basis(p)

    p0 = P0.ravel() / np.linalg.norm(P0)
    res = levenberg_marquardt(
        residuals,
        p0,
        jacobian,
        update=unit_sphere_update,
        max_iter=200,
        ftol=1e-15,
        xtol=1e-15,
        gtol=1e-12,
    )
    if not np.all(np.isfinite(res.x)):
        raise ConvergenceError(
            f"estimate_projection_matrix: refinement did not converge ({res.message})"
        )
    return _normalise_P(res.x.reshape(3, 4))


# ---------------------------------------------------------------------------------------
# Projecting wireframes (scenes from camlab.scenes)
# ---------------------------------------------------------------------------------------


def project_segments(camera: Camera | ArrayLike, segments: ArrayLike) -> np.ndarray:
    """Project (M, 2, 3) world segments to (M, 2, 2) pixel segments with a Camera or a 3x4 P.

    A segment with one end behind the camera is clipped at a near plane first (at 1/1000 of
    its front end's depth), so the part in front of the camera is drawn, running off the
    picture, instead of vanishing. A segment wholly behind the camera comes back as NaN
    (matplotlib skips it). Affine cameras see every point and clip nothing.
    """
    if not isinstance(camera, Camera):
        camera = check_camera_matrix(camera, "camera")
    s = as_float(segments, "segments")
    if s.ndim != 3 or s.shape[1:] != (2, 3):
        raise CamlabInputError(
            f"segments: expected (M, 2, 3) pairs of world points, got shape {s.shape}"
        )
    s = _clip_behind(s, _signed_depth(camera, s.reshape(-1, 3)).reshape(-1, 2))
    flat = s.reshape(-1, 3)
    uv = camera.project(flat) if isinstance(camera, Camera) else project_points(camera, flat)
    return uv.reshape(-1, 2, 2)


def _signed_depth(camera: Camera | np.ndarray, points: np.ndarray) -> np.ndarray:
    """Positive in front of the camera (any scale); +1 everywhere for an affine camera."""
    if isinstance(camera, Camera):
        return camera.depth(points)
    det = np.linalg.det(camera[:, :3])
    if abs(det) <= 1e-12 * np.abs(camera).max() ** 3:
        return np.ones(len(points))
    return np.sign(det) * (points @ camera[2, :3] + camera[2, 3])


def _clip_behind(segments: np.ndarray, depth: np.ndarray, near: float = 1e-3) -> np.ndarray:
    """Move the behind end of each half-visible segment to depth ``near`` times its front end's depth."""
    out = segments.copy()
    for behind, front in ((0, 1), (1, 0)):
        half = (depth[:, behind] <= 0) & (depth[:, front] > 0)
        if not half.any():
            continue
        z_b, z_f = depth[half, behind], depth[half, front]
        s = ((1 - near) * z_f / (z_f - z_b))[
            :, None
        ]  # fraction of the way from the front end to the behind end
        out[half, behind] = segments[half, front] + s * (
            segments[half, behind] - segments[half, front]
        )
    return out
