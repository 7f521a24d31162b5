r"""The pinhole camera :math:`P = K [R \mid t]`: intrinsics, the :class:`Camera`, and any 3x4 camera matrix.

:class:`Camera` projects (with lens distortion), back-projects and looks at targets;
:func:`project_points`, :func:`camera_centre` and :func:`project_segments` work with any
3x4 matrix, affine cameras included. Part of :mod:`camlab.camera` (every name here is
importable from there).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    CamlabInputError,
    DegenerateError,
    as_float,
    as_points,
    check_intrinsics,
    check_matrix,
    check_number,
    check_positive,
    check_rotation,
    check_size,
)
from ..distortion import beyond_valid_radius, distort_points
from .rotations import look_at_rotation

__all__ = [
    "Camera",
    "CameraPair",
    "camera_centre",
    "check_camera_matrix",
    "intrinsic_matrix",
    "centred_intrinsics",
    "project_points",
    "scale_intrinsics",
    "project_segments",
]


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


def scale_intrinsics(K: ArrayLike, scale: float) -> np.ndarray:
    r"""Intrinsics of the same camera with its images resized by ``scale``.

    With the pixel-centre convention (u = 0 is the centre of the first pixel), resizing by
    s maps u to :math:`s (u + 1/2) - 1/2`: :math:`K' = S K`,
    :math:`S = \begin{pmatrix} s & 0 & (s-1)/2 \\ 0 & s & (s-1)/2 \\ 0 & 0 & 1\end{pmatrix}`.
    Also maps homographies between resized images: :math:`S H S^{-1}`.

    Parameters
    ----------
    K : (3, 3) array_like
        Intrinsics of the original images, pixels.
    scale : float
        Resize factor s (> 0; 2 doubles the width and height).

    Returns
    -------
    (3, 3) ndarray
        K' = S K, pixels of the resized images.

    Examples
    --------
    >>> scale_intrinsics(intrinsic_matrix(800, 800, 319.5, 239.5), 2.0)[:2]
    array([[1600. ,    0. ,  639.5],
           [   0. , 1600. ,  479.5]])
    """
    s = check_positive(scale, "scale")
    S = np.array([[s, 0, (s - 1) / 2], [0, s, (s - 1) / 2], [0, 0, 1]])
    return S @ check_matrix(K, (3, 3), "K")


class CameraPair(NamedTuple):
    """Two views of one scene (cam_from_world poses): ``camera1`` and ``camera2``."""

    camera1: Camera
    camera2: Camera


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
        """Check every field; store K, R and t read-only, dist and image_size normalised."""
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
        r"""A camera with square pixels and the principal point at the image centre, from its horizontal field of view.

        ``fov_x`` in radians, in (0, pi): :math:`f = (W / 2) / \tan(\mathrm{fov}_x / 2)`,
        :math:`c = ((W - 1)/2, (H - 1)/2)`.

        Parameters
        ----------
        fov_x : float
            Horizontal field of view, radians, in (0, pi).
        image_size : (2,) tuple of int, optional
            (width, height), pixels (default (640, 480)).
        R : (3, 3) array_like, optional
            cam_from_world rotation (default identity).
        t : (3,) array_like, optional
            cam_from_world translation, metres (default zero).
        dist : tuple of float, optional
            ``(k1, k2, p1, p2, k3)`` in OpenCV's order (default none).

        Returns
        -------
        Camera
            The camera.
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
        r"""A camera at ``eye`` (world metres) looking at ``target``, with ``up`` appearing up in the image.

        ``up`` defaults to world +z. ``K`` defaults to fx = fy = 800 px with the principal
        point at the image centre ((W - 1) / 2, (H - 1) / 2), as in :meth:`from_fov` (pixel
        centres are at integers). :math:`t = -R\,\text{eye}`.

        Parameters
        ----------
        eye : (3,) array_like
            The camera centre, world metres.
        target : (3,) array_like
            The point the principal axis passes through, world metres.
        up : (3,) array_like, optional
            The world direction that appears up in the image (default (0, 0, 1)).
        K : (3, 3) array_like, optional
            Intrinsics, pixels (default: f = 800 px, centred principal point).
        image_size : (2,) tuple of int, optional
            (width, height), pixels (default (640, 480)).
        dist : tuple of float, optional
            ``(k1, k2, p1, p2, k3)`` in OpenCV's order (default none).

        Returns
        -------
        Camera
            The camera, R from :func:`look_at_rotation`.
        """
        R = look_at_rotation(eye, target, up)
        e = np.asarray(eye, dtype=float)
        if K is None:
            w, h = (int(v) for v in image_size)
            K = centred_intrinsics(800.0, (w, h))
        return cls(K, R, -R @ e, dist, image_size)

    def replace(self, **changes) -> Camera:
        """A copy with some fields changed, e.g. ``cam.replace(K=new_K)``.

        Parameters
        ----------
        **changes
            Field names and their new values (``K``, ``R``, ``t``, ``dist``, ``image_size``).

        Returns
        -------
        Camera
            A new camera; this one is unchanged.
        """
        return dataclasses.replace(self, **changes)

    def resized(self, scale: float) -> Camera:
        """The same camera taking images resized by ``scale`` (K by :func:`scale_intrinsics`).

        ``image_size * scale`` must be whole pixels (e.g. 0.5 for 640 x 480).

        Parameters
        ----------
        scale : float
            Resize factor (> 0).

        Returns
        -------
        Camera
            The camera with K scaled and ``image_size`` multiplied by ``scale``.

        Examples
        --------
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
        r"""The camera centre in world coordinates, :math:`C = -R^\top t` (metres).

        The point with :math:`P \tilde C = 0`.
        """
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
        r"""The (4, 4) inverse ``[[R^T, C], [0, 1]]``.

        The camera's pose in the world (its columns are the camera axes and centre in world
        coordinates).
        """
        T = np.eye(4)
        T[:3, :3], T[:3, 3] = self.R.T, self.centre
        return T

    # -- mapping points --------------------------------------------------------------------
    def to_camera(self, points_world: ArrayLike) -> np.ndarray:
        """World points (N, 3) to camera coordinates :math:`X_c = R X + t` (metres).

        Parameters
        ----------
        points_world : (N, 3) or (3,) array_like
            World points, metres.

        Returns
        -------
        (N, 3) or (3,) ndarray
            Camera-frame coordinates, metres, the input's rank.
        """
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
        """The depth :math:`z_c` of each world point along the principal axis (metres).

        Parameters
        ----------
        points_world : (N, 3) or (3,) array_like
            World points, metres.

        Returns
        -------
        (N,) ndarray or float
            z_c, metres (negative behind the camera), one per point.
        """
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
        """(N,) bool: pixel lies inside the image (centre-of-pixel convention).

        Parameters
        ----------
        uv : (N, 2) or (2,) array_like
            Pixel coordinates (u, v) (NaN allowed).

        Returns
        -------
        (N,) bool ndarray or bool
            True where -0.5 <= u <= W - 0.5 and -0.5 <= v <= H - 0.5.
        """
        p = as_points(uv, 2, "uv", finite=False)
        w, h = self.image_size
        u, v = p.array.T
        ok = (u >= -0.5) & (u <= w - 0.5) & (v >= -0.5) & (v <= h - 0.5)
        return p.restore(ok)

    def __repr__(self) -> str:
        """The intrinsics, the centre and the image size, rounded."""
        fx, fy, cx, cy = self.K[0, 0], self.K[1, 1], self.K[0, 2], self.K[1, 2]
        C = np.round(self.centre, 4) + 0.0  # + 0.0: no "-0.0" in the printout
        return (
            f"Camera(fx={fx:.6g}, fy={fy:.6g}, cx={cx:.6g}, cy={cy:.6g}, skew={self.K[0, 1]:.3g}, "
            f"centre={C.tolist()}, image_size={self.image_size})"
        )


def check_camera_matrix(P: Camera | ArrayLike, name: str = "P") -> np.ndarray:
    """The (3, 4) matrix of a camera: ``P.P`` for a :class:`Camera`, else P checked to have rank 3.

    A :class:`Camera`'s distortion is left out.

    Parameters
    ----------
    P : Camera or (3, 4) array_like
        The camera.
    name : str, optional
        The argument's name in error messages.

    Returns
    -------
    (3, 4) ndarray
        The camera matrix.

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

    Parameters
    ----------
    P : Camera or (3, 4) array_like
        The camera (rank 3).

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


def project_segments(camera: Camera | ArrayLike, segments: ArrayLike) -> np.ndarray:
    """Project (M, 2, 3) world segments to (M, 2, 2) pixel segments with a Camera or a 3x4 P.

    A segment with one end behind the camera is clipped at a near plane first (at 1/1000 of
    its front end's depth), so the part in front of the camera is drawn, running off the
    picture, instead of vanishing. A segment wholly behind the camera comes back as NaN
    (matplotlib skips it). Affine cameras see every point and clip nothing.

    Parameters
    ----------
    camera : Camera or (3, 4) array_like
        The camera.
    segments : (M, 2, 3) array_like
        World segments, each two end points in metres.

    Returns
    -------
    (M, 2, 2) ndarray
        Pixel end points (u, v); NaN for segments wholly behind the camera.
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
