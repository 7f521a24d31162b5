"""Stitching stages 4-5: the canvas, feather weights, and every image warped onto it
(:class:`WarpedImages`, with masks and weights); also the cylindrical pre-warp.

See :mod:`camlab.stitching` for the whole pipeline; every name here is re-exported there.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .. import homography as _hg
from .._validate import (
    CamlabInputError,
    DegenerateError,
    check_image,
    check_intrinsics,
    check_shape,
)
from ..projective import map_points
from ..warp import canvas_bounds, warp_perspective

# --------------------------------------------------------------------------- projection


class CylinderImage(NamedTuple):
    """:func:`cylindrical_warp`'s unrolled cylinder.

    Attributes
    ----------
    image : ndarray like the input
        The unrolled cylinder, same size, centred on the principal point.
    mask : (H, W) bool ndarray
        Where the cylinder sees the image.
    """

    image: np.ndarray
    mask: np.ndarray


class SubsampledCanvas(NamedTuple):
    """:meth:`WarpedImages.subsampled`: every image and mask on the coarse canvas grid.

    Attributes
    ----------
    images : list of ndarray
        Each image on the grid (zero outside its mask).
    masks : list of bool ndarray
        Where each image has data on the grid.
    """

    images: list
    masks: list


def cylindrical_warp(image: ArrayLike, K: ArrayLike) -> CylinderImage:
    r"""Map an image onto a cylinder of radius f around the camera centre (unrolled).

    Output pixel (u', v') is the cylinder point at angle :math:`\theta = (u' - c_x)/f` and
    height :math:`h = (v' - c_y)/f`; its ray :math:`(\sin\theta, h, \cos\theta)` meets
    the image at :math:`\pi(K (\sin\theta, h, \cos\theta)^T)`. On the cylinder a camera
    turning about its vertical axis just slides sideways, so wide panoramas stay
    undistorted (a planar canvas stretches without bound towards 90 degrees).

    Parameters
    ----------
    image : (H, W[, C]) array_like
    K : (3, 3) array_like
        The camera's intrinsics (fx is used as the cylinder radius f).

    Returns
    -------
    CylinderImage
        ``(image, mask)``: the unrolled cylinder (like ``image``, same size, centred on the
        principal point) and the (H, W) bool mask of where it sees the image.
    """
    import cv2

    img = check_image(image)
    Km = check_intrinsics(K, "K")
    h, w = img.shape[:2]
    f, cx, cy = Km[0, 0], Km[0, 2], Km[1, 2]
    vv, uu = np.mgrid[0:h, 0:w].astype(np.float32)
    theta = (uu - cx) / f
    hh = (vv - cy) / f
    x, y, z = np.sin(theta), hh, np.cos(theta)
    map_u = (Km[0, 0] * x + Km[0, 1] * y + cx * z) / z
    map_v = (Km[1, 1] * y + cy * z) / z
    map_u, map_v = map_u.astype(np.float32), map_v.astype(np.float32)
    src = img.astype(np.float32) if img.dtype not in (np.uint8, np.float32) else img
    cyl = cv2.remap(
        src, map_u, map_v, cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=0
    )
    mask = (map_u >= -0.5) & (map_u <= w - 0.5) & (map_v >= -0.5) & (map_v <= h - 0.5)
    return CylinderImage(cyl.reshape(img.shape).astype(img.dtype), mask)


# --------------------------------------------------------------------------- warping


def canvas_box(homographies: Sequence[ArrayLike], shapes: Sequence[Sequence[int]]) -> np.ndarray:
    r"""The panorama's bounds: the bounding box of every image's corners mapped by its homography.

    The corner pixels (0, 0), (w-1, 0), (w-1, h-1), (0, h-1) of image k are mapped by
    :math:`H_k` (dividing by the third coordinate), and the box is rounded outwards to
    whole pixels. The canvas is then :math:`u_{max} - u_{min} + 1` pixels wide and
    :math:`T = \begin{pmatrix} 1 & 0 & -u_{min} \\ 0 & 1 & -v_{min} \\ 0 & 0 & 1 \end{pmatrix}`
    moves its top-left corner to (0, 0): that is :func:`camlab.warp.canvas_bounds`, which
    the pipeline uses (and which also refuses corners at infinity).

    Returns
    -------
    (2, 2) ndarray
        ``[[u_min, v_min], [u_max, v_max]]`` in pixels.

    >>> canvas_box([np.eye(3), [[1, 0, 50], [0, 1, -30], [0, 0, 1]]], [(240, 320), (240, 320)])
    array([[  0., -30.],
           [369., 239.]])
    """
    if len(homographies) != len(shapes) or not len(shapes):
        raise CamlabInputError(
            f"shapes: expected one shape per homography, got {len(shapes)} for {len(homographies)}"
        )
    pts = []
    for H, shape in zip(homographies, shapes, strict=True):
        h, w = shape[:2]
        pts.append(
            map_points(np.asarray(H, dtype=float), [[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]])
        )
    allp = np.vstack(pts)
    if not np.all(np.isfinite(allp)):
        raise DegenerateError(
            "canvas_box: a corner maps to infinity; the image crosses the horizon of its homography"
        )
    return np.array([np.floor(allp.min(axis=0) + 1e-9), np.ceil(allp.max(axis=0) - 1e-9)])


def feather_weights(shape: Sequence[int]) -> np.ndarray:
    r"""Feathering weights of an image: each pixel's distance to the nearest image border.

    Pixel centres are at integer (u, v) and the border is at -1/2 and W - 1/2 (H - 1/2), so

    .. math:: w(u, v) = \min(u + \tfrac12,\; W - \tfrac12 - u,\; v + \tfrac12,\; H - \tfrac12 - v).

    Warped with the image, it falls to zero at the image's edge, so where two images
    overlap each fades out towards its own border and no seam jumps.

    >>> feather_weights((3, 4))
    array([[0.5, 0.5, 0.5, 0.5],
           [0.5, 1.5, 1.5, 0.5],
           [0.5, 0.5, 0.5, 0.5]])
    """
    h, w = check_shape(tuple(shape)[:2] if isinstance(shape, (tuple, list)) else shape)
    u = np.arange(w, dtype=float)
    v = np.arange(h, dtype=float)
    du = np.minimum(u + 0.5, w - 0.5 - u)
    dv = np.minimum(v + 0.5, h - 0.5 - v)
    return np.minimum(dv[:, None], du[None, :])


@dataclass(frozen=True, eq=False)
class WarpedImages:
    """Images warped onto one canvas, each kept only in its own box of the canvas.

    Image k covers canvas rows ``r0:r1`` and columns ``c0:c1`` with
    ``boxes[k] = (r0, r1, c0, c1)``; there ``patches[k]`` is the warped image
    ((r1-r0, c1-c0, 3) float32), ``patch_masks[k]`` where it has data (bool) and
    ``patch_weights[k]`` its feather weights (float32, zero outside the mask). Outside its
    mask a patch repeats the image's nearest edge pixels (the warp's replicated border), so
    the blend's pyramids see no black edge. Exposure, seams and blending work box by box,
    so an image never costs more than its own footprint. ``images`` (zero outside each
    image), ``masks`` and ``weights`` are the same data on the full (h, w) canvas (built on
    first use). ``homographies[k]`` is the canvas_from_image H
    used (None on a curved canvas), ``T`` the canvas translation, ``shape`` (h, w).
    """

    patches: list
    patch_masks: list
    patch_weights: list
    boxes: list
    shape: tuple
    homographies: list
    T: np.ndarray

    def _on_canvas(self, parts: list) -> list:
        out = []
        for p, m, (r0, r1, c0, c1) in zip(parts, self.patch_masks, self.boxes, strict=True):
            full = np.zeros(tuple(self.shape) + p.shape[2:], p.dtype)
            full[r0:r1, c0:c1][m] = p[m]
            out.append(full)
        return out

    @cached_property
    def images(self) -> list:
        return self._on_canvas(self.patches)

    @cached_property
    def masks(self) -> list:
        return self._on_canvas(self.patch_masks)

    @cached_property
    def weights(self) -> list:
        return self._on_canvas(self.patch_weights)

    def subsampled(self, step: int) -> SubsampledCanvas:
        """Every image and mask on the canvas grid ``[::step, ::step]`` (as ``images[k][::step, ::step]``,
        but with the patches' replicated border kept outside the masks), built from the boxes without
        the full canvas."""
        h, w = self.shape
        size = (-(-h // step), -(-w // step))
        imgs, masks = [], []
        for p, m, (r0, _r1, c0, _c1) in zip(
            self.patches, self.patch_masks, self.boxes, strict=True
        ):
            a, b = -(-r0 // step), -(-c0 // step)  # the first grid row and column in the box
            sp, sm = (
                p[a * step - r0 :: step, b * step - c0 :: step],
                m[a * step - r0 :: step, b * step - c0 :: step],
            )
            im = np.zeros(size + p.shape[2:], p.dtype)
            mk = np.zeros(size, bool)
            im[a : a + sp.shape[0], b : b + sp.shape[1]] = sp
            mk[a : a + sm.shape[0], b : b + sm.shape[1]] = sm
            imgs.append(im)
            masks.append(mk)
        return SubsampledCanvas(imgs, masks)


def _image_box(
    H: np.ndarray, image_shape: Sequence[int], shape: tuple[int, int]
) -> tuple[int, int, int, int]:
    """The canvas box (r0, r1, c0, c1) that can see image pixels through H (bilinear reach: one pixel beyond the edges)."""
    h, w = image_shape[:2]
    c = map_points(H, [[-1, -1], [w, -1], [w, h], [-1, h]])
    lo, hi = np.floor(c.min(axis=0)) - 1, np.ceil(c.max(axis=0)) + 2
    r0, c0 = int(min(max(lo[1], 0), shape[0])), int(min(max(lo[0], 0), shape[1]))
    return r0, max(r0, int(min(hi[1], shape[0]))), c0, max(c0, int(min(hi[0], shape[1])))


def warp_images(
    images: Sequence[np.ndarray],
    homographies: Sequence[np.ndarray],
    *,
    max_pixels: int = 40_000_000,
) -> WarpedImages:
    """Warp every image onto the panorama canvas (bounds from all warped corners, one translation).

    Each image is warped only into its own box of the canvas (the bounding box of its
    warped corners): ``T_box @ T @ H`` with ``T_box`` the translation to the box's corner.

    Parameters
    ----------
    images : sequence of (h, w, 3) float32 arrays (see :func:`prepare_images`), or (h, w, 1) for grey
    homographies : sequence of (3, 3)
        reference_from_image for each image (from :func:`match_graph`).

    Returns
    -------
    WarpedImages
        With ``homographies[k] = T @ homographies[k]`` (canvas_from_image).
    """
    if len(images) != len(homographies) or not images:
        raise CamlabInputError(
            f"homographies: expected one per image, got {len(homographies)} for {len(images)} images"
        )
    for k, im in enumerate(images):
        if np.ndim(im) != 3 or np.shape(im)[2] not in (1, 3):
            raise CamlabInputError(
                f"images[{k}]: expected an (h, w, 3) float32 image from prepare_images, "
                f"got shape {np.shape(im)}; call prepare_images(images) first"
            )
    import cv2

    T, shape = canvas_bounds(list(homographies), [im.shape for im in images], max_pixels=max_pixels)
    out_i, out_m, out_w, out_h, boxes = [], [], [], [], []
    for im, H in zip(images, homographies, strict=True):
        Hc = _hg.normalize_homography(T @ np.asarray(H, dtype=float))
        r0, r1, c0, c1 = _image_box(Hc, im.shape, shape)
        Hb = np.array([[1.0, 0, -c0], [0, 1, -r0], [0, 0, 1]]) @ Hc
        size = (r1 - r0, c1 - c0)
        # the image with a replicated border (no black edge for the blend's pyramids), its feather weight
        wimg = cv2.warpPerspective(
            np.asarray(im, np.float32),
            Hb,
            size[::-1],
            flags=cv2.INTER_LINEAR,
            borderMode=cv2.BORDER_REPLICATE,
        ).reshape(size + im.shape[2:])
        wgt = warp_perspective(feather_weights(im.shape).astype(np.float32), Hb, size, method="cv2")
        ones = np.ones(im.shape[:2], np.float32)
        mask = warp_perspective(ones, Hb, size, interpolation="nearest", method="cv2") > 0.5
        wgt = np.where(mask, np.maximum(wgt, 1e-3), 0).astype(np.float32)
        out_i.append(wimg)
        out_m.append(mask)
        out_w.append(wgt)
        out_h.append(Hc)
        boxes.append((r0, r1, c0, c1))
    return WarpedImages(out_i, out_m, out_w, boxes, tuple(shape), out_h, T)
