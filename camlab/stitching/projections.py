r"""Panorama canvases for a rotating camera: the plane, the cylinder and the sphere.

Every image k has a camera (K_k, R_k cam_from_world) from :mod:`camlab.stitching.cameras`.
A canvas is a way of laying the directions of the world flat. For a world ray
:math:`d = (d_x, d_y, d_z)` (x right, y down, z forward, the mean viewing direction after
wave correction) and a scale s (pixels per radian at the centre, the median focal):

============  ====================================  ==========================================
canvas        (u, v) from the ray d                  ray d from (u, v)
============  ====================================  ==========================================
planar        :math:`s (d_x/d_z,\ d_y/d_z)`          :math:`(u/s,\ v/s,\ 1)`
cylindrical   :math:`s (\theta,\ d_y/\rho)`          :math:`(\sin(u/s),\ v/s,\ \cos(u/s))`
spherical     :math:`s (\theta,\ \phi)`              :math:`(\sin\theta\cos\phi,\ \sin\phi,\ \cos\theta\cos\phi)`
============  ====================================  ==========================================

with :math:`\theta = \operatorname{atan2}(d_x, d_z)` (longitude), :math:`\rho = \sqrt{d_x^2 + d_z^2}`
and :math:`\phi = \operatorname{atan2}(d_y, \rho)` (latitude). The plane keeps straight lines
straight but stretches without bound towards 90 degrees from its centre (it cannot show a
turn of 180 degrees at all); the cylinder holds any horizontal turn, up to 360 degrees, but
stretches vertically away from the horizon; the sphere holds every direction, bending
straight lines. Each image is warped backwards: canvas pixel -> ray -> :math:`\pi(K_k R_k d)`
(:func:`warp_by_rotation`), over only its own footprint (:func:`footprint`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from .._validate import CamlabInputError, DegenerateError
from ..distortion import pixels_to_normalised

__all__ = [
    "PROJECTIONS",
    "Canvas",
    "CanvasPatch",
    "CanvasPoints",
    "FieldOfView",
    "Rays",
    "border_ring",
    "canvas_from_ray",
    "canvas_points",
    "field_of_view",
    "footprint",
    "make_canvas",
    "outline_on_canvas",
    "pixel_rays",
    "ray_from_canvas",
    "warp_by_rotation",
]

PROJECTIONS = ("planar", "cylindrical", "spherical")


class CanvasPoints(NamedTuple):
    """Canvas coordinates ``u`` (across) and ``v`` (down), arrays of one shape; NaN where undefined."""

    u: np.ndarray
    v: np.ndarray


class Rays(NamedTuple):
    """World ray directions by component, ``x``, ``y``, ``z``, arrays broadcast to one shape (not unit length)."""

    x: np.ndarray
    y: np.ndarray
    z: np.ndarray


def canvas_from_ray(d: np.ndarray, projection: str, s: float) -> CanvasPoints:
    r"""Canvas coordinates (u, v) of world rays (see the module table); NaN where undefined.

    Parameters
    ----------
    d : (..., 3) ndarray
        World ray directions (any length).
    projection : {"planar", "cylindrical", "spherical"}
        The canvas (anything else is taken as spherical).
    s : float
        The canvas scale, pixels per radian at the centre.

    Returns
    -------
    CanvasPoints
        ``u``, ``v``, each of shape ``d.shape[:-1]``; on the plane NaN for rays with
        :math:`d_z \le 10^{-9}`.

    References
    ----------
    .. [1] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022,
       section 8.2 (image stitching: cylindrical and spherical coordinates).
    """
    x, y, z = d[..., 0], d[..., 1], d[..., 2]
    if projection == "planar":
        with np.errstate(divide="ignore", invalid="ignore"):
            zz = np.where(z > 1e-9, z, np.nan)
            return CanvasPoints(s * x / zz, s * y / zz)
    rho = np.hypot(x, z)
    theta = np.arctan2(x, z)
    if projection == "cylindrical":
        with np.errstate(divide="ignore", invalid="ignore"):
            return CanvasPoints(s * theta, s * y / rho)
    return CanvasPoints(s * theta, s * np.arctan2(y, rho))


def ray_from_canvas(u: np.ndarray, v: np.ndarray, projection: str, s: float) -> Rays:
    """World rays (x, y, z) of canvas pixels (u, v): the inverse of :func:`canvas_from_ray`.

    Parameters
    ----------
    u, v : ndarray
        Canvas coordinates (broadcastable against each other).
    projection : {"planar", "cylindrical", "spherical"}
        The canvas (anything else is taken as spherical).
    s : float
        The canvas scale, pixels per radian at the centre.

    Returns
    -------
    Rays
        ``x``, ``y``, ``z``, broadcast like ``u`` and ``v`` (not unit length).

    References
    ----------
    .. [1] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022,
       section 8.2 (image stitching: cylindrical and spherical coordinates).
    """
    if projection == "planar":
        return Rays(u / s, v / s, np.ones_like(u))
    theta = u / s
    if projection == "cylindrical":
        return Rays(np.sin(theta), v / s, np.cos(theta))
    phi = v / s
    return Rays(np.sin(theta) * np.cos(phi), np.sin(phi), np.cos(theta) * np.cos(phi))


def border_points(shape: Sequence[int], n: int = 16) -> np.ndarray:
    """Pixels along the four edges of an image, and its centre.

    Parameters
    ----------
    shape : (h, w) or (h, w, C)
        The image's shape.
    n : int
        Points per edge (corners included).

    Returns
    -------
    (4n + 1, 2) ndarray
        Pixels (u, v): the top, bottom, left and right edges, n each, then the centre.
    """
    h, w = shape[:2]
    t = np.linspace(0, 1, n)
    u, v = (w - 1) * t, (h - 1) * t
    return np.vstack(
        [
            np.c_[u, 0 * t],
            np.c_[u, 0 * t + h - 1],
            np.c_[0 * t, v],
            np.c_[0 * t + w - 1, v],
            [[(w - 1) / 2, (h - 1) / 2]],
        ]
    )


def border_ring(shape: Sequence[int], n: int = 40) -> np.ndarray:
    """Pixels around the border of an image, in order: a closed outline to draw where it went.

    Parameters
    ----------
    shape : (h, w) or (h, w, C)
        The image's shape.
    n : int
        Points per edge.

    Returns
    -------
    (4n, 2) ndarray
        Pixels (u, v) going round: top (left to right), right (down), bottom (right to
        left), left (up).
    """
    p = border_points(shape, n)[:-1]
    return np.vstack([p[:n], p[3 * n : 4 * n], p[n : 2 * n][::-1], p[2 * n : 3 * n][::-1]])


def pixel_rays(pixels: np.ndarray, K: np.ndarray, R: np.ndarray) -> np.ndarray:
    r"""World directions of a camera's pixels: :math:`d = R^\top K^{-1} (u, v, 1)^\top`.

    By :func:`camlab.distortion.pixels_to_normalised` (rows of the result: :math:`(x, y, 1) R`).

    Parameters
    ----------
    pixels : (N, 2) ndarray
        Pixels (u, v).
    K : (3, 3) ndarray
        The camera's intrinsics.
    R : (3, 3) ndarray
        Its cam_from_world rotation.

    Returns
    -------
    (N, 3) ndarray
        World directions, z = 1 in the camera's frame (not unit length).
    """
    xy = pixels_to_normalised(pixels, K)
    return np.c_[xy, np.ones(len(xy))] @ R


def canvas_points(
    pixels: np.ndarray, K: np.ndarray, R: np.ndarray, projection: str, s: float
) -> CanvasPoints:
    r"""Where pixels (N, 2) of image (K, R) land on a canvas: (u, v), each (N,).

    On the cylinder and the sphere the longitude is unrolled around the image's optical axis
    (within :math:`\pm\pi s` of it), so one image never splits across the canvas's seam; an
    image looking backwards may reach past :math:`\pm\pi s`.

    Parameters
    ----------
    pixels : (N, 2) ndarray
        Pixels (u, v) of the image.
    K : (3, 3) ndarray
        Its intrinsics.
    R : (3, 3) ndarray
        Its cam_from_world rotation.
    projection : {"planar", "cylindrical", "spherical"}
        The canvas.
    s : float
        The canvas scale, pixels per radian.

    Returns
    -------
    CanvasPoints
        ``u``, ``v``, each (N,), canvas coordinates (not yet shifted by a canvas origin).
    """
    u, v = canvas_from_ray(pixel_rays(pixels, K, R), projection, s)
    if projection != "planar":
        axis = canvas_from_ray(R[2:3], projection, s)[0][0]  # the optical axis R^T (0, 0, 1)
        u = axis + np.angle(np.exp(1j * (u - axis) / s)) * s
    return CanvasPoints(u, v)


def footprint(
    K: np.ndarray, R: np.ndarray, shape: Sequence[int], projection: str, s: float
) -> np.ndarray:
    """The canvas box ``[[u_min, v_min], [u_max, v_max]]`` of an image (its border's rays, mapped).

    On the cylinder and the sphere the longitude is unrolled around the image's optical axis
    (:func:`canvas_points`), so an image looking backwards (longitude near 180 degrees) gets one
    box, which may reach past +-pi*s.

    Parameters
    ----------
    K : (3, 3) ndarray
        The image's intrinsics.
    R : (3, 3) ndarray
        Its cam_from_world rotation.
    shape : (h, w) or (h, w, C)
        Its shape.
    projection : {"planar", "cylindrical", "spherical"}
        The canvas.
    s : float
        The canvas scale, pixels per radian.

    Returns
    -------
    (2, 2) ndarray
        ``[[u_min, v_min], [u_max, v_max]]``, canvas coordinates.

    Raises
    ------
    DegenerateError
        On the plane, if the image sees 90 degrees or more away from the canvas centre (its
        border has no image on the plane).
    """
    u, v = canvas_points(border_points(shape), K, R, projection, s)
    if not (np.all(np.isfinite(u)) and np.all(np.isfinite(v))):
        raise DegenerateError(
            f"footprint: part of the image looks 90 degrees or more away from the {projection} "
            "canvas's centre; a plane cannot hold it. Use projection='cylindrical' or 'spherical'"
        )
    return np.array([[u.min(), v.min()], [u.max(), v.max()]])


class Canvas(NamedTuple):
    """A panorama canvas.

    ``projection``, scale ``s`` (pixels per radian), ``origin`` (u, v) of pixel (0, 0), ``shape``
    (h, w), ``wraps`` (the canvas is one full turn wide, columns modulo w), and ``boxes``: each
    image's (row0, row1, col0, col1), columns unwrapped.
    """

    projection: str
    s: float
    origin: tuple
    shape: tuple
    wraps: bool
    boxes: list


def make_canvas(
    Ks: Sequence,
    Rs: Sequence,
    shapes: Sequence,
    projection: str,
    s: float,
    *,
    max_pixels: int = 40_000_000,
) -> Canvas:
    """Bounds of all images' footprints; a canvas that would be wider than one full turn wraps.

    Parameters
    ----------
    Ks, Rs : sequence of (3, 3) ndarray
        Intrinsics and cam_from_world rotations of the images in the panorama (no None).
    shapes : sequence of (h, w)
        Their shapes.
    projection : {"planar", "cylindrical", "spherical"}
        The canvas.
    s : float
        The canvas scale, pixels per radian.
    max_pixels : int
        The largest canvas allowed, pixels.

    Returns
    -------
    Canvas
        ``projection``, ``s``, ``origin`` (u, v of pixel (0, 0)), ``shape`` (h, w), ``wraps``
        and each image's box (row0, row1, col0, col1) in ``boxes``.

    Raises
    ------
    CamlabInputError
        An unknown projection, or a canvas larger than ``max_pixels``.
    DegenerateError
        An image that a planar canvas cannot hold (:func:`footprint`).
    """
    if projection not in PROJECTIONS:
        raise CamlabInputError(f"projection: expected one of {PROJECTIONS}, got {projection!r}")
    boxes = np.array(
        [footprint(K, R, sh, projection, s) for K, R, sh in zip(Ks, Rs, shapes, strict=True)]
    )
    lo = np.floor(boxes[:, 0].min(axis=0))
    hi = np.ceil(boxes[:, 1].max(axis=0))
    full = int(round(2 * np.pi * s))
    wraps = projection != "planar" and hi[0] - lo[0] + 1 > full
    w = full if wraps else int(hi[0] - lo[0]) + 1
    h = int(hi[1] - lo[1]) + 1
    if h * w > max_pixels:
        raise CamlabInputError(
            f"max_pixels: the {projection} canvas would be {w} x {h} = {w * h} pixels "
            f"(limit {max_pixels}); the images may be badly registered, or raise max_pixels"
        )
    out = []
    for (bu0, bv0), (bu1, bv1) in boxes:
        c0, c1 = int(np.floor(bu0 - lo[0])), int(np.ceil(bu1 - lo[0])) + 1
        r0, r1 = max(0, int(np.floor(bv0 - lo[1]))), min(h, int(np.ceil(bv1 - lo[1])) + 1)
        if not wraps:
            c0, c1 = max(0, c0), min(w, c1)
        out.append((r0, r1, c0, min(c1, c0 + w)))
    return Canvas(projection, float(s), (float(lo[0]), float(lo[1])), (h, w), bool(wraps), out)


class CanvasPatch(NamedTuple):
    """One image warped into its canvas box by :func:`warp_by_rotation`.

    Attributes
    ----------
    patch : (r1-r0, c1-c0[, C]) ndarray
        The warped image; outside ``mask`` it repeats the image's nearest edge pixels.
    mask : (r1-r0, c1-c0) bool ndarray
        Where the canvas pixel sees the image (in front of the camera).
    extra : (r1-r0, c1-c0) float32 ndarray or None
        The ``extra`` channel warped the same way (zero outside ``mask``); None if none was given.
    """

    patch: np.ndarray
    mask: np.ndarray
    extra: np.ndarray | None


def warp_by_rotation(
    image: np.ndarray,
    K: np.ndarray,
    R: np.ndarray,
    canvas: Canvas,
    box: tuple,
    extra: np.ndarray | None = None,
) -> CanvasPatch:
    r"""Warp one image into its canvas box: canvas pixel -> world ray -> :math:`\pi(K R d)` (bilinear).

    Returns the warped (r1-r0, c1-c0, C) patch, its bool mask (the pixel sees the image, in
    front of the camera) and, if given, ``extra`` (an (h, w) float32 channel such as feather
    weights) warped the same way (zero outside the mask). Outside the mask the patch repeats
    the image's nearest edge pixels (``cv2.BORDER_REPLICATE``): a pyramid built on it sees no
    black border. Use the mask to tell the two apart.

    Parameters
    ----------
    image : (h, w) or (h, w, C) ndarray
        The image (a dtype ``cv2.remap`` takes).
    K : (3, 3) ndarray
        Its intrinsics.
    R : (3, 3) ndarray
        Its cam_from_world rotation.
    canvas : Canvas
        From :func:`make_canvas`.
    box : (4,) tuple of int
        (row0, row1, col0, col1): the image's box on the canvas (``canvas.boxes[k]``).
    extra : (h, w) float32 ndarray, optional
        A channel to warp the same way (e.g. feather weights).

    Returns
    -------
    CanvasPatch
        ``patch`` (r1-r0, c1-c0[, C]), ``mask`` and ``extra`` (None if not given).
    """
    import cv2

    r0, r1, c0, c1 = box
    # a row of u and a column of v: every projection's ray separates into functions of u and
    # of v, so the trigonometry runs on the box's edges and broadcasting fills the box
    u = np.arange(c0, c1, dtype=np.float32)[None, :] + np.float32(canvas.origin[0])
    v = np.arange(r0, r1, dtype=np.float32)[:, None] + np.float32(canvas.origin[1])
    x, y, z = ray_from_canvas(u, v, canvas.projection, np.float32(canvas.s))
    M = (K @ R).astype(np.float32)
    p = [M[r, 0] * x + M[r, 1] * y + M[r, 2] * z for r in range(3)]
    behind = ~(p[2] > 1e-6)
    with np.errstate(divide="ignore", invalid="ignore"):
        mu, mv = np.divide(p[0], p[2], out=p[0]), np.divide(p[1], p[2], out=p[1])
    mu[behind], mv[behind] = -10, -10  # off the image: remap repeats its edge, the mask excludes it
    h, w = image.shape[:2]
    mask = (mu >= -0.5) & (mu <= w - 0.5) & (mv >= -0.5) & (mv <= h - 0.5)
    if extra is None:
        return CanvasPatch(_remap(image, mu, mv), mask, None)
    if image.ndim == 3 and image.shape[2] == 3 and image.dtype == extra.dtype:
        # one 4-channel remap: OpenCV 5 runs it 2x faster than a 3-channel one
        both = _remap(cv2.merge([image, extra]), mu, mv)
        out, more = cv2.cvtColor(both, cv2.COLOR_RGBA2RGB), cv2.extractChannel(both, 3)
    else:
        out, more = _remap(image, mu, mv), _remap(extra, mu, mv)
    more[~mask] = 0
    return CanvasPatch(out, mask, more)


def _remap(image: np.ndarray, mu: np.ndarray, mv: np.ndarray) -> np.ndarray:
    """``image`` sampled at (mu, mv), bilinear, its edge repeated beyond it; channel axis kept."""
    import cv2

    out = cv2.remap(image, mu, mv, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)
    return out.reshape(mu.shape + image.shape[2:])


def outline_on_canvas(
    K: np.ndarray, R: np.ndarray, shape: Sequence[int], canvas: Canvas
) -> np.ndarray:
    """The border of an image on the canvas, in order (:func:`border_ring`).

    Parameters
    ----------
    K : (3, 3) ndarray
        The image's intrinsics.
    R : (3, 3) ndarray
        Its cam_from_world rotation.
    shape : (h, w) or (h, w, C)
        Its shape.
    canvas : Canvas
        The canvas (its projection, scale and origin are used).

    Returns
    -------
    (160, 2) ndarray
        Canvas pixels (u, v) relative to the canvas's pixel (0, 0).
    """
    u, v = canvas_points(border_ring(shape), K, R, canvas.projection, canvas.s)
    return np.c_[u - canvas.origin[0], v - canvas.origin[1]]


class FieldOfView(NamedTuple):
    """How far a set of images reaches on the sphere, degrees."""

    horizontal: float
    vertical: float


def field_of_view(Ks: list, Rs: list, shapes: list) -> FieldOfView:
    """Horizontal and vertical extent of all images on the sphere, degrees.

    Parameters
    ----------
    Ks, Rs : list of (3, 3) ndarray
        Intrinsics and cam_from_world rotations.
    shapes : list of (h, w)
        The images' shapes.

    Returns
    -------
    FieldOfView
        ``horizontal`` (longitude) and ``vertical`` (latitude) spans of the union of the
        images' boxes, degrees.
    """
    boxes = np.array(
        [footprint(K, R, sh, "spherical", 1.0) for K, R, sh in zip(Ks, Rs, shapes, strict=True)]
    )
    return FieldOfView(
        float(np.degrees(boxes[:, 1, 0].max() - boxes[:, 0, 0].min())),
        float(np.degrees(boxes[:, 1, 1].max() - boxes[:, 0, 1].min())),
    )
