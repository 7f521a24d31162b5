r"""The virtual camera: render scenes of textured planes with exact ground truth.

Every later lesson needs images whose true camera is known. :func:`render` draws a
scene made of flat textured rectangles (:class:`camlab.scenes.Plane`: checkerboards, photographs,
a text page, the faces of boxes; :mod:`camlab.scenes` builds them) through

1. pinhole projection with intrinsics ``K`` and pose ``(R, t)`` (``X_cam = R X_world + t``),
2. Brown-Conrady lens distortion ``dist = (k1, k2, p1, p2, k3)`` (:mod:`camlab.distortion`),
3. optional defocus from the thin lens' circle of confusion (:mod:`camlab.lens`),
4. the sensor: box-filtered (anti-aliased) pixels, shot and read noise, quantisation and
   an optional Bayer mosaic (:mod:`camlab.sensor`),

and returns the image with its :class:`GroundTruth`: K, dist, pose, image size, the exact
pixel position of every named plane point (all checkerboard inner corners, in OpenCV's
order) and a depth map.

Conventions: pixels (u, v) = (column, row), origin at the centre of the top-left pixel,
``img[v, u]``; camera frame x right, y down, z forward; metres. A plane's own frame has its
x axis along texture columns, y along texture rows and z = x cross y; for a checkerboard
its origin is the first inner corner, so ``board.object_points`` are the
``(i * square, j * square, 0)`` points ``cv2.calibrateCamera`` expects.

How it works (one pass per plane, all with cv2): the texture -> image map of a plane is
the homography :math:`H = K [r_1\ r_2\ t] S` (S maps texels to plane metres); each plane is
warped into an ideal (undistorted) canvas at ``supersample`` times the output resolution,
composited far to near with its anti-aliased coverage, blurred by its circle of
confusion (one disc per plane, at the depth of its centre), remapped through the inverse
distortion (:func:`camlab.distortion.distort_map`) and box-filtered down to the sensor.
Textures are pre-filtered (halved until a texel covers about one canvas pixel) so
photographs do not alias. Ground-truth corners are computed analytically by projecting
the points, never measured on the image.

See lesson 02, section 4, and docs/conventions.md.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from . import distortion as _dist
from . import lens as _lens
from . import sensor as _sensor
from ._validate import (
    CamlabInputError,
    as_points,
    check_intrinsics,
    check_pose,
    check_positive,
    check_size,
)
from .camera import Camera, Pose, look_at_rotation, scale_intrinsics
from .scenes import Plane

__all__ = [
    "Defocus",
    "GroundTruth",
    "align_detected_corners",
    "PlanePoints",
    "RenderResult",
    "Sensor",
    "look_at",
    "project",
    "render",
]


# ------------------------------------------------------------------------- poses


def look_at(eye: ArrayLike, target: ArrayLike, up: ArrayLike = (0.0, 0.0, 1.0)) -> Pose:
    r"""The camera pose ``(R, t)`` (cam_from_world) of a camera at ``eye`` looking at ``target``.

    The rotation is :func:`camlab.camera.look_at_rotation`, with the same default ``up`` =
    +z (the world's up, docs/conventions.md). Scenes built in a camera's own frame (y down,
    the renderer's checkerboards in front of the origin) pass ``up=(0, -1, 0)``. Returns the
    :class:`camlab.camera.Pose` ``R`` (3, 3), ``t = -R eye`` (3,).

    >>> R, t = look_at([0, 0, -2], [0, 0, 0], up=(0, -1, 0))
    >>> np.allclose(R, np.eye(3)), np.allclose(t, [0, 0, 2])
    (True, True)
    """
    R = look_at_rotation(eye, target, up)
    return Pose(R, -R @ np.asarray(eye, dtype=float))


# ------------------------------------------------------------------------- scene

# ------------------------------------------------------------------------- camera model parts


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
    """Ground truth for one plane's named points (M of them)."""

    object_points: np.ndarray  # (M, 3) in the plane frame, z = 0 (metres)
    world: np.ndarray  # (M, 3) world frame (metres)
    pixels: np.ndarray  # (M, 2) exact distorted pixel positions (u, v)
    visible: np.ndarray  # (M,) bool: in front of the camera, inside the image and not occluded
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
    def camera_center(self) -> np.ndarray:
        """The camera's position in the world, ``-R^T t``."""
        return -self.R.T @ self.t

    @property
    def P(self) -> np.ndarray:
        """The (3, 4) projection matrix ``K [R | t]`` (ignores distortion)."""
        return self.K @ np.column_stack([self.R, self.t])

    def corners(self, name: str | None = None) -> np.ndarray:
        """The (M, 2) pixel positions of a plane's points; default: the only checkerboard in the scene."""
        if name is None:
            boards = [k for k, v in self.points.items() if v.pattern_size is not None]
            if len(boards) != 1:
                raise CamlabInputError(
                    f"corners: name the plane, the scene has checkerboards {boards}"
                )
            name = boards[0]
        return self.points[name].pixels


class RenderResult(NamedTuple):
    """``image``: uint8 (bits <= 8) or uint16, (H, W) grey, (H, W, 3) RGB or (H, W) Bayer mosaic;
    ``irradiance``: the float32 image in [0, 1] before noise and quantisation (RGB before any
    mosaic); ``truth``: :class:`GroundTruth`."""

    image: np.ndarray
    irradiance: np.ndarray
    truth: GroundTruth


# ------------------------------------------------------------------------- projection


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
    ``cv2.projectPoints`` (to 1e-9 px). ``R=None`` (the default) is the identity.

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
    cannot always tell a board from its 180-degree rotation). Accepts OpenCV 4's
    (N, 1, 2) or OpenCV 5's (N, 2) corners; returns (N, 2), reversed if that matches
    ``truth_pixels`` better.
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


# ------------------------------------------------------------------------- rendering

_MIP_CACHE: dict = {}


def _texture_level(tex: np.ndarray, level: int) -> np.ndarray:
    """``tex`` halved ``level`` times with area averaging, cached while ``tex`` is alive."""
    import weakref

    import cv2

    entry = _MIP_CACHE.get(id(tex))
    if entry is None or entry[0]() is not tex:
        entry = (weakref.ref(tex), [tex])
        _MIP_CACHE[id(tex)] = entry
        weakref.finalize(tex, _MIP_CACHE.pop, id(tex), None)
    levels = entry[1]
    while len(levels) <= level:
        a = levels[-1]
        levels.append(
            cv2.resize(
                a, (max(1, a.shape[1] // 2), max(1, a.shape[0] // 2)), interpolation=cv2.INTER_AREA
            )
        )
    return levels[level]


def _disk_kernel(diameter: float) -> np.ndarray:
    r = diameter / 2
    n = int(np.ceil(r)) + 1
    y, x = np.mgrid[-n : n + 1, -n : n + 1]
    # 4x4 supersampled coverage of each kernel cell by the disc: soft, unbiased edges
    s = (np.arange(4) + 0.5) / 4 - 0.5
    cov = np.zeros(x.shape)
    for dy in s:
        for dx in s:
            cov += ((x + dx) ** 2 + (y + dy) ** 2) <= r * r
    if cov.sum() == 0:
        cov[n, n] = 1
    return (cov / cov.sum()).astype(np.float32)


def render(
    scene: Plane | Iterable[Plane | Iterable[Plane]],
    K: ArrayLike,
    size: tuple[int, int] = (640, 480),
    *,
    R: ArrayLike | None = None,
    t: ArrayLike = (0, 0, 0),
    dist: ArrayLike | None = None,
    defocus: Defocus | None = None,
    blur: float = 0.0,
    sensor: Sensor = Sensor(),
    background: float | tuple[float, float, float] = 0.5,
    supersample: int = 2,
    color: bool | None = None,
    depth: bool = False,
    rng: np.random.Generator | int | None = None,
) -> RenderResult:
    r"""Render ``scene`` with camera ``K``, pose ``(R, t)`` and lens distortion ``dist``.

    Parameters
    ----------
    scene : Plane or iterable of Planes (nested lists, e.g. from :func:`camlab.scenes.box`, are flattened)
    K : (3, 3) array_like
        Intrinsics, pixels.
    size : (width, height)
        Image size in pixels.
    R, t : (3, 3), (3,) array_like
        cam_from_world pose: ``X_cam = R X_world + t``; ``R=None`` (the default) is the identity.
    dist : (5,) array_like or None
        ``(k1, k2, p1, p2, k3)``; the whole image must lie inside the model's valid radius.
    defocus : Defocus or None
        Thin-lens blur per plane (its circle of confusion at the depth of its centre).
    blur : float
        Extra disc blur over the whole image, diameter in pixels (e.g. a pinhole's blur).
    sensor : Sensor
        Bit depth, noise and Bayer pattern. The default is a noise-free 8-bit grey sensor.
    background : float or RGB
        Irradiance where no plane is seen.
    supersample : int
        Canvas resolution factor (anti-aliasing by box filtering ``supersample**2`` samples).
    color : bool or None
        Render RGB; default: True if any texture is RGB or a Bayer pattern is set.
    depth : bool
        Compute ``truth.depth`` (about 10 ms per plane at 640x480); otherwise it is None.
    rng : Generator, int seed or None
        Randomness for noise only; the same seed gives the same bytes.

    Returns
    -------
    RenderResult
        ``(image, irradiance, truth)``; see :class:`GroundTruth`.

    Raises
    ------
    CamlabInputError
        Bad K/pose/size, bad sensor settings, an empty scene.

    Planes may reach behind the camera (a floor, a wall beside it): the part nearer than
    ``NEAR`` = 2 cm is clipped away.

    Where the distortion model folds over inside the image (strong barrel distortion at
    the corners, beyond :func:`camlab.distortion.max_valid_radius`) no ideal ray maps to the
    pixel and it shows the background.

    Examples
    --------
    >>> K = [[800, 0, 319.5], [0, 800, 239.5], [0, 0, 1]]
    >>> from camlab.scenes import checkerboard
    >>> board = checkerboard((9, 6), 0.025, t=(-0.1, -0.0625, 0.6))
    >>> out = render(board, K)
    >>> out.image.shape, out.image.dtype, out.truth.corners().shape
    ((480, 640), dtype('uint8'), (54, 2))
    """
    planes = _flatten(scene)
    K = check_intrinsics(K)
    w, h = check_size(size)
    R, t = check_pose(R, t, "camera")
    d = _dist.as_dist(dist)
    ss = int(supersample)
    if ss < 1 or ss > 8:
        raise CamlabInputError(f"supersample: expected an integer from 1 to 8, got {supersample!r}")
    if not isinstance(sensor, Sensor):
        raise CamlabInputError(
            f"sensor: expected a camlab.render.Sensor, got {type(sensor).__name__}"
        )
    _sensor.check_bits(sensor.bits)
    if sensor.bayer is not None:
        _sensor.check_bayer_pattern(sensor.bayer)
    if not blur >= 0:
        raise CamlabInputError(f"blur: expected a diameter >= 0 pixels, got {blur!r}")
    if color is None:
        color = sensor.bayer is not None or any(p.is_color for p in planes)
    bg = _background(background, color)

    geo = _visible_planes(planes, R, t)  # 1. geometry in the camera frame
    canvas = _IdealCanvas.around(K, d, (w, h), ss)  # 2. the undistorted canvas
    pixels = np.empty((canvas.height, canvas.width, 3 if color else 1), dtype=np.float32)
    pixels[:] = bg
    for g in sorted(geo, key=lambda g: -g.depth):  # 3. painter's algorithm, far to near
        _draw_plane(
            pixels,
            g,
            canvas.K,
            _coc_pixels(defocus, K, g.depth) * ss if defocus is not None else 0.0,
            color,
        )
    irradiance = _optics(pixels, canvas, d, blur, bg)  # 4. blur, distortion, pixel area
    image = _sensor_response(irradiance, sensor, rng)  # 5. mosaic, noise, quantisation
    truth = _ground_truth(planes, geo, K, d, R, t, (w, h), depth)  # 6. exact answers
    return RenderResult(image, irradiance, truth)


def _background(background: float | tuple[float, float, float], color: bool) -> np.ndarray:
    """The background irradiance as 3 (RGB) or 1 (grey) float32 values."""
    bg = (
        np.broadcast_to(np.asarray(background, dtype=np.float32).ravel(), (3,))
        if np.ndim(background)
        else np.full(3, float(background), dtype=np.float32)
    )
    if not color:
        bg = bg[:1] if np.ndim(background) == 0 else np.array([bg.mean()], dtype=np.float32)
    return bg


class _CameraPlane(NamedTuple):
    """A plane as the camera sees it: cam_from_plane (Rc, tc), depth of its visible centre, visible polygon."""

    plane: Plane
    Rc: np.ndarray
    tc: np.ndarray
    depth: float
    poly: np.ndarray


def _visible_planes(planes: list[Plane], R: np.ndarray, t: np.ndarray) -> list[_CameraPlane]:
    """Stage 1: each plane in the camera frame, clipped at NEAR; planes behind the camera and back faces dropped."""
    geo = []
    for p in planes:
        Rc = R @ p.R
        tc = R @ p.t + t
        zc = (p.corners_world @ R.T + t)[:, 2]
        if zc.max() <= NEAR:
            continue  # entirely behind the camera (or closer than NEAR): invisible
        if not p.two_sided and Rc[:, 2] @ tc >= 0:
            continue  # a one-sided face seen from behind (its normal points away from the camera)
        poly = _clip_to_near(
            p.extent, Rc, tc
        )  # the part in front of the near plane (floors, walls)
        zpoly = poly @ Rc[2, :2] + tc[2]
        geo.append(_CameraPlane(p, Rc, tc, float(np.mean(zpoly)), poly))
    return geo


class _IdealCanvas(NamedTuple):
    """Stage 2: the supersampled, undistorted canvas; ``K`` maps camera rays to canvas pixels and ``Ks``
    to the supersampled output grid (the two differ when distortion pulls in rays from outside)."""

    K: np.ndarray
    Ks: np.ndarray
    width: int
    height: int
    size: tuple[int, int]
    supersample: int

    @classmethod
    def around(cls, K: np.ndarray, d: np.ndarray, size: tuple[int, int], ss: int) -> _IdealCanvas:
        w, h = size
        Ks = scale_intrinsics(K, ss)  # output px -> supersampled px
        if not d.any():
            return cls(Ks, Ks, w * ss, h * ss, (w, h), ss)
        border = np.concatenate(
            [
                np.column_stack([np.linspace(-0.5, w - 0.5, 64), np.full(64, -0.5)]),
                np.column_stack([np.linspace(-0.5, w - 0.5, 64), np.full(64, h - 0.5)]),
                np.column_stack([np.full(64, -0.5), np.linspace(-0.5, h - 0.5, 64)]),
                np.column_stack([np.full(64, w - 0.5), np.linspace(-0.5, h - 0.5, 64)]),
            ]
        )
        x, res = _dist.newton_undistort(_dist.pixels_to_normalised(border, K), d)
        ideal = _dist.normalised_to_pixels(
            x[res <= 1e-9], K
        )  # pixels beyond the model's fold see background
        if len(ideal) == 0:
            ideal = np.array([[-0.5, -0.5], [w - 0.5, h - 0.5]])
        lo = np.minimum(ideal.min(axis=0), [-0.5, -0.5]) - 2
        hi = np.maximum(ideal.max(axis=0), [w - 0.5, h - 0.5]) + 2
        lo = np.maximum(
            lo, [-1.5 * w, -1.5 * h]
        )  # cap the canvas at 4x the image in each direction
        hi = np.minimum(hi, [2.5 * w, 2.5 * h])
        off = np.floor(-lo * ss)
        Kc = Ks.copy()
        Kc[:2, 2] += off
        cw, ch = int(np.ceil((hi[0] - lo[0]) * ss)) + 1, int(np.ceil((hi[1] - lo[1]) * ss)) + 1
        return cls(Kc, Ks, cw, ch, (w, h), ss)


def _draw_plane(
    canvas: np.ndarray, g: _CameraPlane, Kc: np.ndarray, c_px: float, color: bool
) -> None:
    """Stage 3: warp one plane's texture into the canvas (in place), anti-aliased and defocused by ``c_px``."""
    import cv2

    p = g.plane
    ch, cw = canvas.shape[:2]
    x0, y0, x1, y1 = p.extent
    # coarsest texture level whose texel still covers >= 1 canvas pixel at the plane's nearest point
    Hplane = Kc @ np.column_stack([g.Rc[:, 0], g.Rc[:, 1], g.tc])  # plane metres -> canvas px
    mpp = _metres_per_canvas_px(Hplane, g.poly)
    level = 0
    while (
        level < 8
        and (x1 - x0) / (p.texture.shape[1] >> (level + 1) or 1) < mpp
        and (p.texture.shape[1] >> (level + 1)) >= 2
        and (p.texture.shape[0] >> (level + 1)) >= 2
    ):
        level += 1
    tex = _texture_level(p.texture, level)
    th, tw = tex.shape[:2]
    S = np.array(
        [
            [(x1 - x0) / tw, 0, x0 + 0.5 * (x1 - x0) / tw],
            [0, (y1 - y0) / th, y0 + 0.5 * (y1 - y0) / th],
            [0, 0, 1],
        ]
    )
    H = Hplane @ S  # texel (c, r) -> canvas px
    if p.is_color and not color:
        tex = np.ascontiguousarray(tex @ np.array([0.299, 0.587, 0.114], dtype=np.float32))
    # a grey texture in a colour render stays one channel: compositing broadcasts it
    quad = cv2.perspectiveTransform(g.poly[None].astype(np.float64), Hplane)[
        0
    ]  # visible outline, canvas px
    # work only inside the plane's bounding box plus room for its blur, reaching that far past the canvas's edges
    # too: a plane that continues beyond the frame must blur into the frame as it is, not fade into the backdrop
    # (a blur cut at the canvas edge would mix in empty coverage there)
    # (only a blurred plane reaches out: a sharp one is drawn exactly as the bundled data sets were made)
    pad = int(np.ceil(c_px / 2)) + 2
    reach = pad if c_px > 0 else 0
    bx0, by0 = np.maximum(np.floor(quad.min(axis=0)).astype(int) - pad, -reach)
    bx1, by1 = np.minimum(np.ceil(quad.max(axis=0)).astype(int) + pad + 1, [cw + reach, ch + reach])
    if min(bx1, cw) <= max(bx0, 0) or min(by1, ch) <= max(by0, 0):
        return
    T = np.array([[1.0, 0, -bx0], [0, 1.0, -by0], [0, 0, 1]])
    layer = cv2.warpPerspective(
        tex,
        T @ H,
        (int(bx1 - bx0), int(by1 - by0)),
        flags=cv2.INTER_LINEAR,
        borderMode=cv2.BORDER_REPLICATE,
    )
    if layer.ndim == 2:
        layer = layer[..., None]
    # coverage: the warped rectangle, anti-aliased (LINE_AA edges, then the supersampling)
    alpha = np.zeros(layer.shape[:2], dtype=np.float32)
    cv2.fillConvexPoly(
        alpha,
        np.round((quad - [bx0, by0]) * 16).astype(np.int32),
        1.0,
        lineType=cv2.LINE_AA,
        shift=4,
    )
    if c_px > 1.0:
        kern = _disk_kernel(c_px)
        layer = cv2.filter2D(layer * alpha[..., None], -1, kern, borderType=cv2.BORDER_CONSTANT)
        alpha = cv2.filter2D(alpha, -1, kern, borderType=cv2.BORDER_CONSTANT)
        if layer.ndim == 2:
            layer = layer[..., None]
        layer = layer / np.maximum(alpha, 1e-6)[..., None]
    inside = np.s_[
        max(-by0, 0) : (by1 - by0) - max(by1 - ch, 0), max(-bx0, 0) : (bx1 - bx0) - max(bx1 - cw, 0)
    ]
    layer, alpha = layer[inside], alpha[inside]  # the part on the canvas
    roi = canvas[max(by0, 0) : min(by1, ch), max(bx0, 0) : min(bx1, cw)]
    roi += alpha[..., None] * (layer - roi)


def _optics(
    canvas: np.ndarray, ideal: _IdealCanvas, d: np.ndarray, blur: float, bg: np.ndarray
) -> np.ndarray:
    """Stage 4: extra blur, lens distortion (remap) and the pixels' area (box filter): irradiance in [0, 1]."""
    import cv2

    ss = ideal.supersample
    w, h = ideal.size
    if blur > 1.0 / ss:
        canvas = cv2.filter2D(canvas, -1, _disk_kernel(blur * ss), borderType=cv2.BORDER_REFLECT)
        if canvas.ndim == 2:
            canvas = canvas[..., None]
    if d.any():
        maps = _dist.distort_map(ideal.Ks, d, (w * ss, h * ss), new_K=ideal.K, step=4)
        canvas = cv2.remap(
            canvas,
            maps.map_u,
            maps.map_v,
            cv2.INTER_LINEAR,
            borderMode=cv2.BORDER_CONSTANT,
            borderValue=tuple(float(v) for v in bg) + (0,) * (4 - len(bg)),
        )
        if canvas.ndim == 2:
            canvas = canvas[..., None]
    img = cv2.resize(canvas, (w, h), interpolation=cv2.INTER_AREA) if ss > 1 else canvas
    if img.ndim == 3 and img.shape[2] == 1:
        img = img[..., 0]
    return np.clip(img, 0.0, 1.0).astype(np.float32)


def _sensor_response(irradiance: np.ndarray, sensor: Sensor, rng) -> np.ndarray:
    """Stage 5: Bayer mosaic, shot and read noise, quantisation to digital numbers."""
    signal = irradiance
    if sensor.bayer is not None:
        signal = _sensor.mosaic(irradiance, sensor.bayer)
    if sensor.noise is not None:
        signal = _sensor.add_noise(signal, sensor.noise, rng)
    return _sensor.quantize(signal, sensor.bits)


def _ground_truth(
    planes: list[Plane],
    geo: list[_CameraPlane],
    K: np.ndarray,
    d: np.ndarray,
    R: np.ndarray,
    t: np.ndarray,
    size: tuple[int, int],
    depth: bool,
) -> GroundTruth:
    """Stage 6: exact pixels of every named point (projected, never measured), visibility, depth map."""
    w, h = size
    truth = GroundTruth(
        K=K,
        dist=d,
        R=R,
        t=t,
        size=(w, h),
        points={},
        depth=_depth_map(geo, K, d, w, h) if depth else None,
    )
    for g in geo:
        p = g.plane
        if len(p.points):
            wp = p.world_points
            px = project(wp, K, R, t, d)
            zc = (wp @ R.T + t)[:, 2]
            inside = (
                (zc > 0)
                & (px[:, 0] >= -0.5)
                & (px[:, 0] <= w - 0.5)
                & (px[:, 1] >= -0.5)
                & (px[:, 1] <= h - 0.5)
            )
            vis = inside.copy()
            if inside.any():  # occluded if another plane meets the point's ray in front of it
                Xc = wp[inside] @ R.T + t
                vis[inside] = _nearest_hit(Xc / Xc[:, 2:3], geo) >= Xc[:, 2] * (1 - 1e-6)
            truth.points[p.name] = PlanePoints(p.object_points, wp, px, vis, p.pattern_size)
    for (
        p
    ) in planes:  # culled planes (behind the camera, back faces) still get an entry, all invisible
        if len(p.points) and p.name not in truth.points:
            wp = p.world_points
            truth.points[p.name] = PlanePoints(
                p.object_points,
                wp,
                project(wp, K, R, t, d),
                np.zeros(len(wp), bool),
                p.pattern_size,
            )
    return truth


def _flatten(scene) -> list[Plane]:
    if isinstance(scene, Plane):
        return [scene]
    out: list[Plane] = []
    try:
        items = list(scene)
    except TypeError:
        raise CamlabInputError(
            f"scene: expected a Plane or a list of Planes, got {type(scene).__name__}"
        ) from None
    for item in items:
        out += _flatten(item)
    if not out:
        raise CamlabInputError("scene: expected at least one Plane, got an empty scene")
    return out


NEAR = 0.02  # metres: the renderer's near clipping distance


def _clip_to_near(extent, Rc: np.ndarray, tc: np.ndarray) -> np.ndarray:
    """The plane rectangle's part with z_cam >= NEAR, as an (M, 2) convex polygon in plane coordinates.

    z_cam is linear on the plane, so one Sutherland-Hodgman step against a half-plane clips it.
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


def _metres_per_canvas_px(Hplane: np.ndarray, poly: np.ndarray) -> float:
    """Smallest plane-metres-per-canvas-pixel over the visible polygon's vertices (its closest part)."""
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


def _coc_pixels(defocus: Defocus, K: np.ndarray, depth: float) -> float:
    pitch = check_positive(defocus.pixel_pitch, "pixel_pitch", "metres")
    f = defocus.focal_length if defocus.focal_length is not None else K[0, 0] * pitch
    return (
        float(_lens.circle_of_confusion(f, defocus.f_number, defocus.focus_distance, depth)) / pitch
    )


def _nearest_hit(rays: np.ndarray, geo) -> np.ndarray:
    """Depth z_cam where each ray ``(x, y, 1)`` first meets a plane of the scene (inf: none)."""
    depth = np.full(len(rays), np.inf)
    for p, Rc, tc, *_ in geo:  # _CameraPlane rows
        n = Rc[:, 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            z = (n @ tc) / (rays @ n)  # the plane n . X = n . tc meets the ray z * (x, y, 1) here
            loc = (rays * z[:, None] - tc) @ Rc[:, :2]  # hit point in plane coordinates
        x0, y0, x1, y1 = p.extent
        hit = (
            (z > 0) & (loc[:, 0] >= x0) & (loc[:, 0] <= x1) & (loc[:, 1] >= y0) & (loc[:, 1] <= y1)
        )
        depth = np.where(hit & (z < depth), z, depth)
    return depth


def _depth_map(geo, K, d, w, h) -> np.ndarray:
    """z_cam of the nearest plane through each pixel centre (inf for background)."""
    if d.any():
        maps = _dist.distort_map(K, d, (w, h), step=4)
        ideal = np.stack([maps.map_u.ravel(), maps.map_v.ravel()], axis=1).astype(float)
    else:
        u, v = np.meshgrid(np.arange(w, dtype=float), np.arange(h, dtype=float))
        ideal = np.stack([u.ravel(), v.ravel()], axis=1)
    xy = _dist.pixels_to_normalised(ideal, K)
    return _nearest_hit(np.column_stack([xy, np.ones(len(xy))]), geo).reshape(h, w)
