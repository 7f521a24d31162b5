r""":func:`render`.

The virtual camera's pipeline, stage by stage (:mod:`~camlab.render.canvas` paints,
:mod:`~camlab.render.truth` measures nothing and computes the truth).
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
from numpy.typing import ArrayLike

from .. import distortion as _dist
from .. import sensor as _sensor
from .._validate import (
    CamlabInputError,
    check_intrinsics,
    check_pose,
    check_size,
)
from ..scenes import Plane
from .canvas import IdealCanvas, draw_plane, optics, sensor_response, visible_planes
from .model import Defocus, RenderResult, Sensor
from .truth import coc_pixels, flatten, ground_truth

__all__ = [
    "render",
]


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
    planes = flatten(scene)
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

    geo = visible_planes(planes, R, t)  # 1. geometry in the camera frame
    canvas = IdealCanvas.around(K, d, (w, h), ss)  # 2. the undistorted canvas
    pixels = np.empty((canvas.height, canvas.width, 3 if color else 1), dtype=np.float32)
    pixels[:] = bg
    for g in sorted(geo, key=lambda g: -g.depth):  # 3. painter's algorithm, far to near
        draw_plane(
            pixels,
            g,
            canvas.K,
            coc_pixels(defocus, K, g.depth) * ss if defocus is not None else 0.0,
            color,
        )
    irradiance = optics(pixels, canvas, d, blur, bg)  # 4. blur, distortion, pixel area
    image = sensor_response(irradiance, sensor, rng)  # 5. mosaic, noise, quantisation
    truth = ground_truth(planes, geo, K, d, R, t, (w, h), depth)  # 6. exact answers
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
