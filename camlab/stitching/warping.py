"""Stitching stage 5: every image warped onto the panorama canvas, with its mask and feather weight.

:func:`warp_images` warps by homographies onto a planar canvas (:func:`camlab.warp.canvas_bounds`);
:func:`warp_images_by_rotation` warps by each camera's rotation onto a planar, cylindrical or
spherical canvas (:mod:`camlab.stitching.projections`). Both return :class:`WarpedImages`.

See :mod:`camlab.stitching` for the whole pipeline.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple

import numpy as np

from .. import homography as _hg
from .._validate import CamlabInputError, check_shape
from ..projective import map_points
from ..warp import canvas_bounds, warp_perspective
from .projections import Canvas, warp_by_rotation


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


def feather_weights(shape: Sequence[int]) -> np.ndarray:
    r"""Feathering weights of an image: each pixel's distance to the nearest image border.

    Pixel centres are at integer (u, v) and the border is at -1/2 and W - 1/2 (H - 1/2), so

    .. math:: w(u, v) = \min(u + \tfrac12,\; W - \tfrac12 - u,\; v + \tfrac12,\; H - \tfrac12 - v).

    Warped with the image, it falls to zero at the image's edge, so where two images
    overlap each fades out towards its own border and no seam jumps.

    Parameters
    ----------
    shape : (H, W) or (H, W, C)
        The image's shape (only H and W are used).

    Returns
    -------
    (H, W) ndarray
        The weights, pixels (0.5 on the outermost pixels).

    Raises
    ------
    CamlabInputError
        Not a valid image shape.

    References
    ----------
    .. [1] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022,
       section 8.4 (compositing: feathering).

    Examples
    --------
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
            # full[r0:r1, c0:c1][m] = p[m], without gathering p[m] first (2x faster)
            np.copyto(full[r0:r1, c0:c1], p, where=m.reshape(m.shape + (1,) * (p.ndim - 2)))
            out.append(full)
        return out

    @cached_property
    def images(self) -> list:
        """The full-canvas images, one per view (made on first use)."""
        return self._on_canvas(self.patches)

    @cached_property
    def masks(self) -> list:
        """The full-canvas masks, one per view (made on first use)."""
        return self._on_canvas(self.patch_masks)

    @cached_property
    def weights(self) -> list:
        """The full-canvas blending weights, one per view (made on first use)."""
        return self._on_canvas(self.patch_weights)

    def subsampled(self, step: int) -> SubsampledCanvas:
        """Every image and mask on the coarse canvas grid ``[::step, ::step]``, from the boxes.

        As ``images[k][::step, ::step]``, but with the patches' replicated border kept outside
        the masks, and built without the full canvas. Made once per step (exposure gains and
        seams search the same grid) and returned read-only.

        Parameters
        ----------
        step : int
            The grid spacing, canvas pixels (>= 1).

        Returns
        -------
        SubsampledCanvas
            ``images`` and ``masks``, each of the grid's shape (ceil(h / step), ceil(w / step)).
        """
        made = self.__dict__.setdefault("_subsampled", {})  # as cached_property stores its value
        if step not in made:
            made[step] = self._subsample(step)
        return made[step]

    def _subsample(self, step: int) -> SubsampledCanvas:
        """:meth:`subsampled`, built."""
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
        for a in imgs + masks:
            a.flags.writeable = False
        return SubsampledCanvas(imgs, masks)


def _inside(weight: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """A warped float32 feather ``weight`` made at least 1e-3 inside ``mask`` and 0 outside, in place."""
    np.maximum(weight, np.float32(1e-3), out=weight)
    np.multiply(weight, mask, out=weight)
    return weight


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
    shape: tuple[int, int] | None = None,
) -> WarpedImages:
    """Warp every image onto the panorama canvas (bounds from all warped corners, one translation).

    Each image is warped only into its own box of the canvas (the bounding box of its
    warped corners): ``T_box @ T @ H`` with ``T_box`` the translation to the box's corner.
    With ``shape`` given, the canvas is that frame instead (T the identity), and what falls
    outside it is cut off: e.g. one photo warped into another's own frame, where their
    overlap lies, when a canvas holding all of it would be huge (a corner far out).

    Parameters
    ----------
    images : sequence of (h, w, 3) or (h, w, 1) float32 ndarray
        The images (see :func:`prepare_images`); (h, w, 1) for grey.
    homographies : sequence of (3, 3)
        reference_from_image for each image (from :func:`match_graph`).
    max_pixels : int
        The largest canvas allowed (:func:`camlab.warp.canvas_bounds`).
    shape : (h, w), optional
        The canvas to warp onto, with ``homographies`` already canvas_from_image. Default:
        the canvas that holds every image whole.

    Returns
    -------
    WarpedImages
        With ``homographies[k] = T @ homographies[k]`` (canvas_from_image).

    Raises
    ------
    CamlabInputError
        Not one homography per image, an image that is not (h, w, 3) or (h, w, 1), or a
        ``shape`` that is not (h, w) in whole pixels.
    DegenerateError
        The canvas would exceed ``max_pixels`` (:func:`camlab.warp.canvas_bounds`; not
        checked with ``shape`` given).
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

    if shape is None:
        T, shape = canvas_bounds(
            list(homographies), [im.shape for im in images], max_pixels=max_pixels
        )
    else:
        T, shape = np.eye(3), check_shape(shape)
    out_i, out_m, out_w, out_h, boxes = [], [], [], [], []
    for im, H in zip(images, homographies, strict=True):
        Hc = _hg.normalise_homography(T @ np.asarray(H, dtype=float))
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
        wgt = _inside(wgt, mask)
        out_i.append(wimg)
        out_m.append(mask)
        out_w.append(wgt)
        out_h.append(Hc)
        boxes.append((r0, r1, c0, c1))
    return WarpedImages(out_i, out_m, out_w, boxes, tuple(shape), out_h, T)


def warp_images_by_rotation(
    images: Sequence[np.ndarray], Ks: Sequence[np.ndarray], Rs: Sequence[np.ndarray], canvas: Canvas
) -> WarpedImages:
    """Every image warped into its own box of a canvas by its camera (K, R) (:func:`warp_by_rotation`).

    A box that wraps around a full-turn canvas (columns modulo w) becomes a full-width one.

    Parameters
    ----------
    images : sequence of (h, w, C) ndarray
        The images (:func:`prepare_images`).
    Ks, Rs : sequence of (3, 3) ndarray
        Each image's intrinsics and cam_from_world rotation.
    canvas : Canvas
        From :func:`make_canvas` for these cameras (its ``boxes`` are used).

    Returns
    -------
    WarpedImages
        Patches, masks and feather weights box by box; no homographies (``None`` for each
        image) and ``T`` the identity.
    """
    h, w = canvas.shape
    out_i, out_m, out_w, boxes = [], [], [], []
    feathers: dict = {}  # one per image size (remap does not change its source)
    for im, K, R, box in zip(images, Ks, Rs, canvas.boxes, strict=True):
        if im.shape[:2] not in feathers:
            feathers[im.shape[:2]] = feather_weights(im.shape).astype(np.float32)
        patch, mask, wgt = warp_by_rotation(im, K, R, canvas, box, feathers[im.shape[:2]])
        wgt = _inside(wgt, mask)
        r0, r1, c0, c1 = box
        if c0 < 0 or c1 > w:
            cols = np.arange(c0, c1) % w
            parts = []
            for a in (patch, mask, wgt):
                full = np.zeros((r1 - r0, w) + a.shape[2:], a.dtype)
                full[:, cols] = a
                parts.append(full)
            (patch, mask, wgt), (c0, c1) = parts, (0, w)
        out_i.append(patch)
        out_m.append(mask)
        out_w.append(wgt)
        boxes.append((r0, r1, c0, c1))
    return WarpedImages(out_i, out_m, out_w, boxes, (h, w), [None] * len(images), np.eye(3))
