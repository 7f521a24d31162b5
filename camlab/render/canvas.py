r"""How :func:`camlab.render.render` paints.

Each plane warped by its homography into an ideal canvas at ``supersample`` times the output
resolution, composited far to near, blurred by its circle of confusion, distorted, and box-filtered
down to the sensor.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .. import distortion as _dist
from .. import sensor as _sensor
from ..camera import scale_intrinsics
from ..scenes import Plane
from .model import NEAR, CameraPlane, Sensor, clip_to_near, metres_per_canvas_px

__all__ = []


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


def visible_planes(planes: list[Plane], R: np.ndarray, t: np.ndarray) -> list[CameraPlane]:
    """Stage 1: each plane in the camera frame, clipped at NEAR; planes behind the camera and back faces dropped.

    Parameters
    ----------
    planes : list of Plane
        The scene, flattened.
    R : (3, 3) ndarray
        cam_from_world rotation.
    t : (3,) ndarray
        cam_from_world translation, metres.

    Returns
    -------
    list of CameraPlane
        The planes that can be seen, in scene order: each with its cam_from_plane pose, the mean
        depth of its visible polygon (metres) and that polygon (:func:`clip_to_near`).
    """
    geo = []
    for p in planes:
        Rc = R @ p.R
        tc = R @ p.t + t
        zc = (p.corners_world @ R.T + t)[:, 2]
        if zc.max() <= NEAR:
            continue  # entirely behind the camera (or closer than NEAR): invisible
        if not p.two_sided and Rc[:, 2] @ tc >= 0:
            continue  # a one-sided face seen from behind (its normal points away from the camera)
        poly = clip_to_near(p.extent, Rc, tc)  # the part in front of the near plane (floors, walls)
        zpoly = poly @ Rc[2, :2] + tc[2]
        geo.append(CameraPlane(p, Rc, tc, float(np.mean(zpoly)), poly))
    return geo


class IdealCanvas(NamedTuple):
    """Stage 2.

    The supersampled, undistorted canvas; ``K`` maps camera rays to canvas pixels and ``Ks`` to the
    supersampled output grid (the two differ when distortion pulls in rays from outside).
    """

    K: np.ndarray
    Ks: np.ndarray
    width: int
    height: int
    size: tuple[int, int]
    supersample: int

    @classmethod
    def around(cls, K: np.ndarray, d: np.ndarray, size: tuple[int, int], ss: int) -> IdealCanvas:
        """The canvas that holds every ray the distorted output image sees.

        Without distortion it is the output grid supersampled; with it, the output's border is
        undistorted (pixels beyond the model's fold are left out) and the canvas grows to hold it,
        capped at 4 times the image in each direction.

        Parameters
        ----------
        K : (3, 3) ndarray
            The output image's intrinsics, pixels.
        d : (5,) ndarray
            Distortion ``(k1, k2, p1, p2, k3)``.
        size : (width, height)
            The output image's size, pixels.
        ss : int
            Supersampling factor.

        Returns
        -------
        IdealCanvas
            The canvas's intrinsics ``K``, the supersampled output's ``Ks``, its width and height
            (supersampled pixels), the output ``size`` and ``supersample``.
        """
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


def draw_plane(
    canvas: np.ndarray, g: CameraPlane, Kc: np.ndarray, c_px: float, color: bool
) -> None:
    """Stage 3: warp one plane's texture into the canvas (in place), anti-aliased and defocused by ``c_px``.

    The texture level is the coarsest mipmap level whose texel still covers a canvas pixel where
    the plane is seen largest (:func:`metres_per_canvas_px`); the plane's coverage is drawn with
    anti-aliased edges, and both texture and coverage are blurred by a disc of ``c_px`` before
    compositing over what is already in the canvas.

    Parameters
    ----------
    canvas : (ch, cw, C) float32 ndarray
        The ideal canvas (:class:`IdealCanvas`), composited in place.
    g : CameraPlane
        The plane as the camera sees it (:func:`visible_planes`).
    Kc : (3, 3) ndarray
        The canvas's intrinsics (:attr:`IdealCanvas.K`).
    c_px : float
        Diameter of the plane's circle of confusion, canvas pixels (0: sharp).
    color : bool
        The render is RGB (else an RGB texture is turned grey).

    References
    ----------
    .. [1] L. Williams, 1983, "Pyramidal parametrics", SIGGRAPH '83 (mipmaps).
    """
    import cv2

    p = g.plane
    ch, cw = canvas.shape[:2]
    x0, y0, x1, y1 = p.extent
    # coarsest texture level whose texel still covers >= 1 canvas pixel at the plane's nearest point
    Hplane = Kc @ np.column_stack([g.Rc[:, 0], g.Rc[:, 1], g.tc])  # plane metres -> canvas px
    mpp = metres_per_canvas_px(Hplane, g.poly)
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


def optics(
    canvas: np.ndarray, ideal: IdealCanvas, d: np.ndarray, blur: float, bg: np.ndarray
) -> np.ndarray:
    """Stage 4: extra blur, lens distortion (remap) and the pixels' area (box filter): irradiance in [0, 1].

    Parameters
    ----------
    canvas : (ch, cw, C) float32 ndarray
        The composited ideal canvas.
    ideal : IdealCanvas
        Its geometry (intrinsics, size, supersampling).
    d : (5,) ndarray
        Distortion ``(k1, k2, p1, p2, k3)``.
    blur : float
        Extra disc blur over the whole image, diameter in output pixels.
    bg : (C,) ndarray
        The background irradiance, for pixels the distortion pulls from beyond the canvas.

    Returns
    -------
    (H, W) or (H, W, 3) float32 ndarray
        The irradiance at the output size, in [0, 1].
    """
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


def sensor_response(irradiance: np.ndarray, sensor: Sensor, rng) -> np.ndarray:
    """Stage 5: Bayer mosaic, shot and read noise, quantisation to digital numbers.

    Parameters
    ----------
    irradiance : (H, W) or (H, W, 3) float32 ndarray
        The image reaching the sensor, in [0, 1].
    sensor : Sensor
        Bit depth, noise model and Bayer pattern.
    rng : numpy.random.Generator, int seed or None
        Randomness of the noise.

    Returns
    -------
    ndarray
        The digital image: uint8 for 8 bits or fewer, else uint16; (H, W) when mosaicked.
    """
    signal = irradiance
    if sensor.bayer is not None:
        signal = _sensor.mosaic(irradiance, sensor.bayer)
    if sensor.noise is not None:
        signal = _sensor.add_noise(signal, sensor.noise, rng)
    return _sensor.quantise(signal, sensor.bits)
