r"""The virtual camera's model.

Its settings (:class:`Defocus`, :class:`Sensor`) and results (:class:`RenderResult`,
:class:`GroundTruth`), the exact projection of plane points, and the near plane (``NEAR``) every
stage clips at.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .. import distortion as _dist
from .. import sensor as _sensor
from .._validate import (
    CamlabInputError,
    as_points,
    check_intrinsics,
    check_pose,
)
from ..camera import Camera, Pose, look_at_rotation
from ..scenes import Plane

__all__ = [
    "Defocus",
    "GroundTruth",
    "align_detected_corners",
    "PlanePoints",
    "RenderResult",
    "Sensor",
    "look_at",
    "project",
]


def look_at(eye: ArrayLike, target: ArrayLike, up: ArrayLike = (0.0, 0.0, 1.0)) -> Pose:
    """The camera pose ``(R, t)`` (cam_from_world) of a camera at ``eye`` looking at ``target``.

    The rotation is :func:`camlab.camera.look_at_rotation`, with the same default ``up`` =
    +z (the world's up, docs/conventions.md). Scenes built in a camera's own frame (y down,
    the renderer's checkerboards in front of the origin) pass ``up=(0, -1, 0)``.

    Parameters
    ----------
    eye : (3,) array_like
        The camera's centre, world metres.
    target : (3,) array_like
        The point it looks at, world metres.
    up : (3,) array_like
        The world direction that appears up in the image.

    Returns
    -------
    Pose
        ``R`` (3, 3) and ``t = -R eye`` (3,), metres.

    Examples
    --------
    >>> R, t = look_at([0, 0, -2], [0, 0, 0], up=(0, -1, 0))
    >>> np.allclose(R, np.eye(3)), np.allclose(t, [0, 0, 2])
    (True, True)
    """
    R = look_at_rotation(eye, target, up)
    return Pose(R, -R @ np.asarray(eye, dtype=float))


@dataclass(frozen=True)
class Defocus:
    """Thin-lens defocus: blur each plane by its circle of confusion.

    ``focal_length`` (metres) defaults to ``fx * pixel_pitch``; ``pixel_pitch`` converts the
    blur diameter from metres on the sensor to pixels.
    """

    f_number: float = 2.8
    focus_distance: float = 1.0
    pixel_pitch: float = 5e-6
    focal_length: float | None = None


@dataclass(frozen=True)
class Sensor:
    """The sensor stage: bit depth, noise (None = noise-free) and an optional Bayer pattern."""

    bits: int = 8
    noise: _sensor.NoiseModel | None = None
    bayer: str | None = None


class PlanePoints(NamedTuple):
    """Ground truth for one plane's named points (M of them).

    Attributes
    ----------
    object_points : (M, 3) ndarray
        The points in the plane frame, z = 0, metres.
    world : (M, 3) ndarray
        The points in the world frame, metres.
    pixels : (M, 2) ndarray
        Their exact distorted pixel positions (u, v).
    visible : (M,) bool ndarray
        In front of the camera, inside the image and not occluded.
    pattern_size : (cols, rows) or None
        The checkerboard's inner corners, None for other planes.
    """

    object_points: np.ndarray
    world: np.ndarray
    pixels: np.ndarray
    visible: np.ndarray
    pattern_size: tuple[int, int] | None


@dataclass(frozen=True)
class GroundTruth:
    """Everything true about a render.

    ``K`` (3, 3), ``dist`` (5,) (k1, k2, p1, p2, k3), ``R`` (3, 3) and ``t`` (3,) with
    ``X_cam = R X_world + t``, ``size = (width, height)``, ``points`` maps each plane name to
    its :class:`PlanePoints`, ``depth`` is the (H, W) z_cam of the surface seen by each
    pixel centre (inf where only background is seen).
    """

    K: np.ndarray
    dist: np.ndarray
    R: np.ndarray
    t: np.ndarray
    size: tuple[int, int]
    points: dict[str, PlanePoints]
    depth: np.ndarray | None

    @property
    def centre(self) -> np.ndarray:
        """The camera's position in the world, ``-R^T t``."""
        return -self.R.T @ self.t

    @property
    def P(self) -> np.ndarray:
        """The (3, 4) projection matrix ``K [R | t]`` (ignores distortion)."""
        return self.K @ np.column_stack([self.R, self.t])

    def corners(self, name: str | None = None) -> np.ndarray:
        """The (M, 2) pixel positions of a plane's points; default: the only checkerboard in the scene.

        Parameters
        ----------
        name : str or None
            The plane's name; None for the scene's one checkerboard.

        Returns
        -------
        (M, 2) ndarray
            Exact distorted pixels (u, v) of its named points (for a board, in
            ``cv2.findChessboardCorners`` order).

        Raises
        ------
        CamlabInputError
            If ``name`` is None and the scene has no checkerboard or more than one.
        """
        if name is None:
            boards = [k for k, v in self.points.items() if v.pattern_size is not None]
            if len(boards) != 1:
                raise CamlabInputError(
                    f"corners: name the plane, the scene has checkerboards {boards}"
                )
            name = boards[0]
        return self.points[name].pixels


class RenderResult(NamedTuple):
    """What :func:`camlab.render.render` returns.

    Attributes
    ----------
    image : (H, W) or (H, W, 3) ndarray
        uint8 (bits <= 8) or uint16: grey, RGB or a Bayer mosaic (H, W).
    irradiance : (H, W) or (H, W, 3) float32 ndarray
        The image in [0, 1] before noise and quantisation (RGB before any mosaic).
    truth : GroundTruth
        Everything true about the render.
    """

    image: np.ndarray
    irradiance: np.ndarray
    truth: GroundTruth


def project(
    points_world: ArrayLike,
    K: ArrayLike,
    R: ArrayLike | None = None,
    t: ArrayLike = (0, 0, 0),
    dist: ArrayLike | None = None,
) -> np.ndarray:
    r"""Project world points to distorted pixels: the renderer's ground-truth projection.

    :math:`X_c = R X + t`, :math:`x = (X_c/Z_c, Y_c/Z_c)`, :math:`x_d = \mathrm{distort}(x)`,
    :math:`u = K [x_d, 1]`, by :meth:`camlab.camera.Camera.project`. Agrees with
    ``cv2.projectPoints`` (to 1e-9 px).

    Parameters
    ----------
    points_world : (N, 3) or (3,) array_like
        World points, metres.
    K : (3, 3) array_like
        Intrinsics, pixels.
    R : (3, 3) array_like or None
        cam_from_world rotation; None (the default) is the identity.
    t : (3,) array_like
        cam_from_world translation, metres.
    dist : (5,) array_like or None
        ``(k1, k2, p1, p2, k3)``; None for no distortion.

    Returns
    -------
    (N, 2) or (2,) ndarray
        Pixels (u, v); NaN for points with Z_c <= 0.
    """
    R, t = check_pose(R, t, "camera")
    return Camera(check_intrinsics(K), R, t, dist=tuple(_dist.as_dist(dist))).project(points_world)


def align_detected_corners(detected: ArrayLike, truth_pixels: ArrayLike) -> np.ndarray:
    """Reorder detector output to match the ground truth's corner order.

    ``cv2.findChessboardCorners[SB]`` may return a board's corners in reverse order (it
    cannot always tell a board from its 180-degree rotation).

    Parameters
    ----------
    detected : (N, 1, 2) or (N, 2) array_like
        The detected corners, pixels (OpenCV 4's or OpenCV 5's layout).
    truth_pixels : (N, 2) array_like
        The true corners in the ground truth's order (:meth:`GroundTruth.corners`).

    Returns
    -------
    (N, 2) ndarray
        ``detected`` as given or reversed, whichever is closer to ``truth_pixels`` (a new array).

    Raises
    ------
    CamlabInputError
        If the two hold different numbers of corners.
    """
    det = np.asarray(detected, dtype=float).reshape(-1, 2)
    gt = as_points(truth_pixels, 2, "truth_pixels").array
    if det.shape != gt.shape:
        raise CamlabInputError(
            f"detected: expected {gt.shape[0]} corners like truth_pixels, got {det.shape[0]}"
        )
    if np.sum((det[::-1] - gt) ** 2) < np.sum((det - gt) ** 2):
        det = det[::-1]
    return det.copy()


class CameraPlane(NamedTuple):
    """A plane as the camera sees it (:func:`~camlab.render.canvas.visible_planes`).

    Attributes
    ----------
    plane : Plane
        The scene's plane.
    Rc, tc : (3, 3), (3,) ndarray
        cam_from_plane: ``X_cam = Rc @ [x, y, 0] + tc``, metres.
    depth : float
        Mean z_cam of its visible polygon's vertices, metres (compositing order).
    poly : (M, 2) ndarray
        The visible polygon, plane metres (:func:`clip_to_near`).
    """

    plane: Plane
    Rc: np.ndarray
    tc: np.ndarray
    depth: float
    poly: np.ndarray


NEAR = 0.02  # metres: the renderer's near clipping distance


def clip_to_near(extent, Rc: np.ndarray, tc: np.ndarray) -> np.ndarray:
    """The plane rectangle's part with z_cam >= NEAR, as an (M, 2) convex polygon in plane coordinates.

    z_cam is linear on the plane, so one Sutherland-Hodgman step against a half-plane clips it.

    Parameters
    ----------
    extent : (x0, y0, x1, y1)
        The rectangle in the plane's frame, metres (:attr:`Plane.extent`).
    Rc : (3, 3) ndarray
        cam_from_plane rotation.
    tc : (3,) ndarray
        cam_from_plane translation, metres.

    Returns
    -------
    (M, 2) ndarray
        The visible polygon's vertices in order, plane metres; M = 0 when the whole rectangle is
        nearer than :data:`NEAR` (or behind the camera).

    References
    ----------
    .. [1] I. E. Sutherland and G. W. Hodgman, 1974, "Reentrant polygon clipping",
       Communications of the ACM 17(1).
    """
    x0, y0, x1, y1 = extent
    rect = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], dtype=float)
    z = rect @ Rc[2, :2] + tc[2] - NEAR
    out = []
    for i in range(4):
        a, b, za, zb = rect[i], rect[(i + 1) % 4], z[i], z[(i + 1) % 4]
        if za >= 0:
            out.append(a)
        if (za >= 0) != (zb >= 0):
            out.append(a + (b - a) * za / (za - zb))
    return np.array(out)


def metres_per_canvas_px(Hplane: np.ndarray, poly: np.ndarray) -> float:
    """Smallest plane-metres-per-canvas-pixel over the visible polygon's vertices (its closest part).

    At each vertex (and the centroid) the local scale is the square root of the Jacobian
    determinant of the plane-to-canvas homography: canvas pixels per plane metre; its reciprocal
    is the size of a canvas pixel on the plane.

    Parameters
    ----------
    Hplane : (3, 3) ndarray
        canvas_from_plane homography (plane metres to canvas pixels).
    poly : (M, 2) ndarray
        The visible polygon, plane metres (:func:`clip_to_near`).

    Returns
    -------
    float
        Metres on the plane per canvas pixel where the plane is seen largest; ``inf`` if the
        Jacobian vanishes everywhere.
    """
    best = np.inf
    for x, y in np.vstack([poly, poly.mean(axis=0)]):
        q = Hplane @ [x, y, 1.0]
        J = (Hplane[:2, :2] * q[2] - np.outer(q[:2], Hplane[2, :2])) / q[
            2
        ] ** 2  # d canvas / d plane
        s = np.sqrt(abs(np.linalg.det(J)))
        if s > 0:
            best = min(best, 1.0 / s)
    return best
