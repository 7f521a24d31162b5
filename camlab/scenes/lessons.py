"""The lessons' scenes and synthetic data sets, built here once for each lesson and its demos."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from functools import lru_cache
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, check_integer, check_number, check_positive, check_size
from ..camera import (
    Camera,
    CameraPair,
    estimate_projection_matrix,
    look_at_rotation,
    orbit_eye,
    project_points,
    reprojection_errors,
    rotation_from_axis_angle,
    rotation_from_euler,
)
from ..projective import map_points
from .planes import Plane, box, checkerboard, letter_chart, photo_plane, text_page, textured_plane
from .textures import portrait
from .wireframes import box_wireframe, ground_grid, house_wireframe

WALL_DISTANCE = 6.0  # metres: lesson 01's checkered wall behind the box
WALL_TEXELS = (
    128  # texels per 1 m square: at f = 100 mm a square is 148 px, so an edge ramps over ~1 px
)
WALL_GREYS = (
    0.08,
    0.26,
)  # the wall's two greys: darker than every box face, but the squares read clearly
WALL_MARK = (
    0.45  # one lighter square, up and left of the optical axis: a checkerboard alone looks the same
)
# turned by 180 degrees, so without it only the box would show that the real image is rotated


@lru_cache(maxsize=1)
def _wall() -> Plane:
    """Lesson 01's wall (built once: the renderer caches each texture's mipmaps while the array lives)."""
    dark, light = WALL_GREYS
    squares = (np.indices((12, 16)).sum(axis=0) % 2) * (
        light - dark
    ) + dark  # 12 rows x 16 columns of 1 m squares
    squares[5, 7] = (
        WALL_MARK  # the square x in [-1, 0] m, y in [-1, 0] m: up and left of the axis (y points down)
    )
    return textured_plane(
        np.kron(squares, np.ones((WALL_TEXELS, WALL_TEXELS), np.float32)),
        16.0,
        t=(0, 0, WALL_DISTANCE),
        name="wall",
    )


@lru_cache(maxsize=1)
def _box_at_origin() -> tuple:
    """Lesson 01's turned 0.3 m box centred on the origin, its textures built once (see :func:`_wall`)."""
    return tuple(
        box(
            [0.0, 0.0, 0.0],
            (0.3, 0.3, 0.3),
            R=rotation_from_euler(0.35, 0.6, 0.0),
            texels=160,
            rng=0,
        )
    )


def box_before_wall(distance: float) -> list:
    """Lesson 01: a turned 0.3 m box ``distance`` metres in front of the pinhole and a checkered wall behind it.

    Returns ``[faces, wall]``: the box's six faces (a list of :class:`Plane`, its top face
    darkest) and a wall (a :class:`Plane`) 16 m x 12 m of 1 m squares in two dark greys
    (:data:`WALL_GREYS`), one square up and left of the axis lighter (:data:`WALL_MARK`), at z = :data:`WALL_DISTANCE`, wide enough to fill the widest view
    lesson 01 shows, a scene for :func:`camlab.render.render`. The wall stays put while the
    box moves, so its squares show the perspective a focal length and a distance give (a dolly
    zoom keeps the box's size and changes the wall's). Both are textured finely enough
    (:data:`WALL_TEXELS`, 160 texels a box face) to look sharp at lesson 01's longest focal
    length, as a pinhole image is: an ideal pinhole has no depth of field.
    :func:`plane_outlines` of ``faces`` gives the (24, 2, 3) box edges.
    """
    d = check_positive(distance, "distance", "metres")
    return [[replace(face, t=face.t + [0.0, 0.0, d]) for face in _box_at_origin()], _wall()]


def depth_of_field_scene() -> list[Plane]:
    """Lesson 02: four planes at 0.6, 1.2, 2.4 and 4 m (small board, letter chart, large board, portrait wall).

    Seen by a camera at the origin looking along +z; a list of :class:`Plane` for
    :func:`camlab.render.render`, named ``"near"``, ``"chart"``, ``"far"``, ``"wall"``. The chart's
    rows of capitals shrink row by row (lesson 01's :func:`letter_chart`), so how many rows stay
    legible shows the blur; the wall, 3.6 m wide, fills the frame of lesson 02's 28 mm camera.
    """
    return [
        checkerboard((5, 4), 0.04, t=(-0.33, -0.02, 0.6), name="near", px_per_square=32),
        letter_chart(0.36, t=(0.02, -0.02, 1.2)),
        checkerboard((7, 5), 0.12, t=(0.1, -0.55, 2.4), name="far", px_per_square=32),
        textured_plane(portrait(), 3.6, t=(0, 0, 4.0), name="wall"),
    ]


def photo_and_page(linear: bool = False) -> list[Plane]:
    """Lesson 03: a colour photograph 1 m ahead and a slightly turned text page beside it, at 1.1 m.

    A list of two :class:`Plane` (``"photo"``, ``"page"``) for :func:`camlab.render.render`,
    framed by a camera at the origin looking along +z with f = 900 px on 320 x 240 pixels.
    ``linear``: the photograph in linear reflectance (see :func:`photo_plane`).
    """
    return [
        photo_plane(0.3, t=(0.05, 0.02, 1.0), linear=linear),
        # raised 6 cm so the page's heading lies above the frame instead of cut by its left edge
        text_page(0.2, t=(-0.2, -0.06, 1.1), R=rotation_from_euler(0, 0.2, 0.05)),
    ]


def house_scene() -> np.ndarray:
    """Lesson 04: a house on a 4 m x 4 m ground grid (z = 0), as (M, 2, 3) segments, metres."""
    return np.concatenate([house_wireframe(), ground_grid(2.0, 0.5)])


def box_and_rails() -> np.ndarray:
    """Lesson 05: a 1 m cube on four long parallel rails along x, as (M, 2, 3) segments, metres."""
    rails = np.array([[[-3.0, y, 0.0], [3.0, y, 0.0]] for y in (-0.8, -0.6, 0.6, 0.8)])
    return np.concatenate([box_wireframe((0.0, 0.0, 0.5), (1.0, 1.0, 1.0)), rails])


def rail_track(start: float = -3.0, end: float = 40.0) -> np.ndarray:
    """Lesson 05: four parallel rails along +y and a sleeper every metre on the ground, (M, 2, 3) metres.

    The rails run from y = ``start`` to ``end`` metres at x = -1.5, -0.5, 0.5, 1.5 m.
    """
    rails = np.array([[[x, start, 0.0], [x, end, 0.0]] for x in (-1.5, -0.5, 0.5, 1.5)])
    sleepers = np.array([[[-1.7, y, 0.0], [1.7, y, 0.0]] for y in np.arange(start, end, 1.0)])
    return np.concatenate([rails, sleepers])


def sleeper_gaps(P: ArrayLike, at: Sequence[float] = (-2.0, 20.0)) -> np.ndarray:
    """Lesson 05: the image length (pixels) under the camera matrix ``P`` of one metre of :func:`rail_track`
    (the ground line x = 0 from y to y + 1) for each y in ``at`` metres: equal for an affine
    camera, shrinking with distance for a perspective one (perspective diminution)."""
    ys = np.atleast_1d(np.asarray(at, dtype=float))
    zero = np.zeros_like(ys)
    near_end = project_points(P, np.column_stack([zero, ys, zero]))
    far_end = project_points(P, np.column_stack([zero, ys + 1.0, zero]))
    return np.linalg.norm(far_end - near_end, axis=1)


def _camera_800(R: np.ndarray, eye: np.ndarray) -> Camera:
    """A 640 x 480 camera with f = 800 px at ``eye`` (metres) turned by cam_from_world ``R``."""
    return Camera(
        np.array([[800.0, 0, 319.5], [0, 800.0, 239.5], [0, 0, 1]]),
        R,
        -R @ eye,
        image_size=(640, 480),
    )


def stereo_pair(baseline: float, toe_in: float, height: float = 0.0) -> CameraPair:
    """Lesson 11: two cameras ``baseline`` metres apart along world x at 1 m, looking along +y, each turned
    ``toe_in / 2`` radians towards the other (converging for toe_in > 0), the right one raised by ``height`` m.

    640 x 480 pixels, f = 800 px. With ``toe_in = 0`` the epipoles are at infinity (parallel cameras).
    """
    eye1 = np.array([-baseline / 2, 0.0, 1.0])
    eye2 = np.array([baseline / 2, 0.0, 1.0 + height])
    cams = []
    for eye, turn in ((eye1, -toe_in / 2), (eye2, toe_in / 2)):
        R = look_at_rotation(eye, eye + [0.0, 1.0, 0.0])
        R = rotation_from_axis_angle([0.0, turn, 0.0]) @ R  # about the camera's (downward) y axis
        cams.append(_camera_800(R, eye))
    return CameraPair(*cams)


def forward_pair(baseline: float, turn: float) -> CameraPair:
    """Lesson 11: the second camera ``baseline`` metres straight ahead of the first (forward motion, like a
    car's camera between two frames), turned by ``turn`` radians about its vertical axis.

    Its epipole is the image of the first centre: near the principal point, inside the image,
    and every epipolar line fans out from it. 640 x 480 pixels, f = 800 px.
    """
    eye1, eye2 = np.array([0.0, -1.0, 1.0]), np.array([0.0, -1.0 + baseline, 1.0])
    R1 = look_at_rotation(eye1, eye1 + [0.0, 1.0, 0.0])
    R2 = rotation_from_axis_angle([0.0, turn, 0.0]) @ look_at_rotation(eye2, eye2 + [0.0, 1.0, 0.0])
    return CameraPair(_camera_800(R1, eye1), _camera_800(R2, eye2))


class OutlierMatches(NamedTuple):
    """Point pairs related by a known homography, a known fraction of them replaced by random points (lesson 07).

    Attributes
    ----------
    H : (3, 3) ndarray
        The true dst_from_src homography.
    src, dst : (N, 2) ndarray
        The pairs, pixels in a 400 x 300 image; the inliers' ``dst`` carry Gaussian noise.
    is_outlier : (N,) bool ndarray
        Which pairs are random (wrong matches).
    """

    H: np.ndarray
    src: np.ndarray
    dst: np.ndarray
    is_outlier: np.ndarray


def outlier_matches(
    outlier_fraction: float, seed: int | None = 0, n: int = 200, noise: float = 1.0
) -> OutlierMatches:
    """``n`` matches of a fixed homography with ``noise`` pixels of noise, ``round(outlier_fraction n)`` of them wrong."""
    if not 0 <= check_number(outlier_fraction, "outlier_fraction") <= 1:
        raise CamlabInputError(
            f"outlier_fraction: expected a fraction in [0, 1], got {outlier_fraction!r}"
        )
    n = check_integer(n, "n", minimum=4)
    rng = np.random.default_rng(seed)
    H = np.array([[0.9, 0.15, 40.0], [-0.1, 0.85, 30.0], [4e-4, 2e-4, 1.0]])
    src = rng.uniform([0, 0], [400, 300], (n, 2))
    dst = map_points(H, src) + rng.normal(0, noise, (n, 2))
    out = np.zeros(n, bool)
    out[rng.choice(n, int(round(outlier_fraction * n)), replace=False)] = True
    dst[out] = rng.uniform([0, 0], [400, 300], (out.sum(), 2))
    return OutlierMatches(H, src, dst, out)


class ResectionSet(NamedTuple):
    """A true camera and noisy world-to-pixel correspondences (lesson 04, resectioning).

    Attributes
    ----------
    camera : Camera
        The true camera (640 x 480, f = 800 px), 5 m from (0, 0, 0.7) m.
    points_world : (N, 3) ndarray
        Points on two faces of a 2 m cube (x = 1 and y = -1): not coplanar, like a calibration rig.
    points_image : (N, 2) ndarray
        Their pixels with Gaussian noise.
    """

    camera: Camera
    points_world: np.ndarray
    points_image: np.ndarray


def resection_set(n_points: int, noise_px: float, seed: int | None = 0) -> ResectionSet:
    """``n_points`` world points on two faces of a cube, seen by a known camera with ``noise_px`` pixels of noise."""
    n_points = check_integer(n_points, "n_points", minimum=1)
    sigma = check_number(noise_px, "noise_px", "pixels")
    if sigma < 0:
        raise CamlabInputError(
            f"noise_px: expected a standard deviation >= 0 pixels, got {noise_px!r}"
        )
    rng = np.random.default_rng(seed)
    target = np.array([0.0, 0.0, 0.7])
    cam = Camera.look_at(orbit_eye(np.radians(-55), np.radians(25), 5.0, target), target)
    n1 = n_points // 2
    a = rng.uniform(-1, 1, (n_points, 2))
    X = np.empty((n_points, 3))
    X[:n1] = np.column_stack([np.full(n1, 1.0), a[:n1, 0], 1.0 + a[:n1, 1]])
    X[n1:] = np.column_stack([a[n1:, 0], np.full(n_points - n1, -1.0), 1.0 + a[n1:, 1]])
    uv = cam.project(X) + rng.normal(0.0, sigma, (n_points, 2))
    return ResectionSet(cam, X, uv)


class ResectionTrial(NamedTuple):
    """One run of lesson 04's resectioning demo: the data, one pair possibly moved, and the fitted P.

    Attributes
    ----------
    camera : Camera
        The true camera.
    points_world, points_image : (N, 3), (N, 2) ndarray
        The correspondences as fitted (the moved pixels included).
    P : (3, 4) ndarray
        The estimated camera matrix.
    errors : (N,) ndarray
        Each pair's reprojection error under P, pixels (NaN behind the estimated camera).
    """

    camera: Camera
    points_world: np.ndarray
    points_image: np.ndarray
    P: np.ndarray
    errors: np.ndarray


def resection_trial(
    n_points: int,
    noise_px: float,
    pair: int = 0,
    shift: ArrayLike = (0.0, 0.0),
    refine: bool = False,
    moved: dict | None = None,
) -> ResectionTrial:
    """:func:`resection_set`, with pair ``pair``'s pixel shifted by ``shift`` (u, v pixels) and any pixels
    in ``moved`` (index -> (u, v)) put there, then P estimated by the normalised DLT (``refine``: then
    Levenberg-Marquardt on the reprojection error). What the resectioning demo shows at its settings."""
    cam, X, uv = resection_set(n_points, noise_px)
    uv[int(pair)] += np.asarray(shift, dtype=float)
    for i, where in (moved or {}).items():
        uv[i] = where
    P = estimate_projection_matrix(X, uv, refine=refine)
    return ResectionTrial(cam, X, uv, P, reprojection_errors(P, X, uv))


class GroundView(NamedTuple):
    """A ground grid seen by a tilted camera (lesson 06), with its exact vanishing geometry.

    Attributes
    ----------
    K, R : (3, 3) ndarray
        Intrinsics and the cam_from_world rotation (the camera sits at the world origin).
    segments : (M, 2, 2) ndarray
        The grid lines' images (pixels), clipped to the part in front of the camera: first the
        ``n_along_z`` lines running ahead (along z), then the lines across (along x).
    n_along_z : int
        How many of ``segments`` run ahead.
    vp_z, vp_x : (3,) ndarray
        Homogeneous vanishing points of the world directions z and x, :math:`K R d`.
    horizon : (3,) ndarray
        The ground's horizon line :math:`K^{-T} R n` (n = (0, 1, 0), the ground's normal).
    """

    K: np.ndarray
    R: np.ndarray
    segments: np.ndarray
    n_along_z: int
    vp_z: np.ndarray
    vp_x: np.ndarray
    horizon: np.ndarray


def ground_plane_view(
    pitch: float, yaw: float, focal: float, size: tuple[int, int] = (640, 480), height: float = 1.5
) -> GroundView:
    """A camera ``height`` metres over a ground grid, tilted down by ``pitch`` and turned by ``yaw`` (radians).

    ``focal`` in pixels, ``size`` (width, height) in pixels. This scene's world frame is the
    camera's before it turns: x right, y down (the ground is the plane y = ``height``), z
    ahead. A world direction d vanishes at :math:`K R d`, and the ground's horizon is
    :math:`K^{-T} R n`. Lines are clipped at 5 cm in front of the camera, so none flips
    through the pinhole.
    """
    w, h = check_size(size)
    f = check_positive(focal, "focal", "pixels")
    cam_height = check_positive(height, "height", "metres")
    K = np.array([[f, 0, (w - 1) / 2], [0, f, (h - 1) / 2], [0, 0, 1.0]])
    cp, sp, cy, sy = np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    Rx = np.array([[1, 0, 0], [0, cp, -sp], [0, sp, cp]])  # optical axis tilted down by +pitch
    Ry = np.array([[cy, 0, -sy], [0, 1, 0], [sy, 0, cy]])
    R = Rx @ Ry  # cam_from_world (the camera sits at the world origin)
    ticks = np.arange(-12.0, 12.1, 2.0)
    along_z = [np.array([[x, cam_height, 0.5], [x, cam_height, 2000.0]]) for x in ticks]
    along_x = [
        np.array([[-60.0, cam_height, z], [60.0, cam_height, z]])
        for z in 2.0 * 1.4 ** np.arange(12)
    ]
    near = 0.05
    segments = []
    for seg in along_z + along_x:
        a, b = seg @ R.T
        if a[2] < near and b[2] < near:
            continue  # wholly behind the camera
        if (
            a[2] < near or b[2] < near
        ):  # clip at the near plane so nothing flips through the pinhole
            s = (near - a[2]) / (b[2] - a[2])
            a, b = (a + s * (b - a), b) if a[2] < near else (a, a + s * (b - a))
        uv = np.stack([a, b]) @ K.T
        segments.append(uv[:, :2] / uv[:, 2:])
    return GroundView(
        K,
        R,
        np.array(segments).reshape(-1, 2, 2),
        len(along_z),
        K @ R @ np.array([0, 0, 1.0]),
        K @ R @ np.array([1.0, 0, 0]),
        np.linalg.inv(K).T @ R @ np.array([0, 1.0, 0]),
    )
