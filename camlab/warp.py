r"""Warping images by homographies: inverse mapping, forward mapping, automatic canvas.

The output pixel (u, v) takes its colour from the source at :math:`H^{-1}(u, v)`
(*inverse mapping*): every output pixel gets exactly one value, so there are no holes.
*Forward mapping* pushes each source pixel to :math:`H(u, v)` and rounds; where H
magnifies, some output pixels receive nothing (holes), which is why every practical
warper maps backwards. :func:`forward_warp` exists to show that.

Pixel convention (docs/conventions.md): (u, v) = (column, row), the origin at the
centre of the top-left pixel, images indexed ``img[v, u]``; an image of width w covers
u in [-0.5, w - 0.5]. This matches ``cv2.warpPerspective``, and the numpy warp agrees
with it to within one grey level (bilinear) on interior pixels.

Two implementations give the same picture: ``method="numpy"`` (the readable teaching
path) and ``method="cv2"`` (the fast path for interactive demos). See lesson 07,
section 7.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._validate import CamlabInputError, DegenerateError, check_image, check_shape
from .homography import check_homography, compose

__all__ = [
    "CanvasBounds",
    "CanvasWarp",
    "canvas_bounds",
    "canvas_box",
    "forward_warp",
    "warp_perspective",
    "warp_to_canvas",
]

_INTERPOLATIONS = ("nearest", "bilinear")
_METHODS = ("numpy", "cv2")


def _check_shape(output_shape: Sequence[int]) -> tuple[int, int]:
    h, w = check_shape(
        tuple(output_shape)[:2] if isinstance(output_shape, (tuple, list)) else output_shape,
        "output_shape",
    )
    if h * w > 50_000_000:
        raise CamlabInputError(
            f"output_shape: expected a positive (height, width) under 50 megapixels, got ({h}, {w})"
        )
    return h, w


def _check_options(interpolation: str, method: str) -> None:
    if interpolation not in _INTERPOLATIONS:
        raise CamlabInputError(
            f"interpolation: expected one of {_INTERPOLATIONS}, got {interpolation!r}"
        )
    if method not in _METHODS:
        raise CamlabInputError(f"method: expected one of {_METHODS}, got {method!r}")


def _to_dtype(values: np.ndarray, dtype: np.dtype) -> np.ndarray:
    if values.dtype == dtype:  # cv2 already returns the input's dtype: nothing to round
        return values
    if np.issubdtype(dtype, np.integer):
        info = np.iinfo(dtype)
        return np.clip(np.rint(values), info.min, info.max).astype(dtype)
    return values.astype(dtype, copy=False)


def _padded_planes(img: np.ndarray, fill: float) -> np.ndarray:
    """The image as (C, (h + 2) * (w + 2)) float32 planes with a one-pixel border of ``fill``."""
    h, w = img.shape[:2]
    chans = 1 if img.ndim == 2 else img.shape[2]
    planes = np.full((chans, h + 2, w + 2), fill, dtype=np.float32)
    planes[:, 1:-1, 1:-1] = img.reshape(h, w, chans).transpose(2, 0, 1)
    return planes.reshape(chans, -1)


def _sample(
    planes: np.ndarray,
    shape: tuple[int, int],
    x: np.ndarray,
    y: np.ndarray,
    interpolation: str,
    out: np.ndarray,
) -> None:
    r"""Sample padded planes at float source coordinates (x, y) = (u, v) into ``out`` (C, N).

    Coordinates are shifted by one into the padded frame and clipped into it, so samples
    outside the image (and NaN, for points that are not visible) read the ``fill``
    border. Bilinear interpolation is two linear interpolations along u, then one along v:

    .. math:: I(x, y) = (1-b)\,[(1-a) I_{00} + a I_{10}] + b\,[(1-a) I_{01} + a I_{11}]

    with :math:`a = x - \lfloor x \rfloor`, :math:`b = y - \lfloor y \rfloor`
    (``cv2.BORDER_CONSTANT`` semantics).
    """
    h, w = shape
    W2 = w + 2
    x += 1
    y += 1
    if interpolation == "nearest":
        i = np.clip(np.floor(y + 0.5), 0, h + 1).astype(np.intp) * W2
        i += np.clip(np.floor(x + 0.5), 0, w + 1).astype(np.intp)
        for c, p in enumerate(planes):
            np.take(p, i, out=out[c])
        return
    np.clip(x, 0, w + 0.999, out=x)
    np.clip(y, 0, h + 0.999, out=y)
    x0 = x.astype(np.intp)  # floor, as x >= 0
    y0 = y.astype(np.intp)
    a = (x - x0).astype(np.float32)
    b = (y - y0).astype(np.float32)
    i = y0 * W2 + x0
    for c, p in enumerate(planes):
        i00, i10 = np.take(p, i), np.take(p, i + 1)
        i01, i11 = np.take(p, i + W2), np.take(p, i + W2 + 1)
        i10 -= i00
        i10 *= a
        i00 += i10  # top = i00 + a (i10 - i00)
        i11 -= i01
        i11 *= a
        i01 += i11  # bottom = i01 + a (i11 - i01)
        i01 -= i00
        i01 *= b
        i00 += i01  # top + b (bottom - top)
        out[c] = i00


_BLOCK = 16384  # output pixels per step: keeps the temporaries in the CPU cache


def _warp_numpy(
    img: np.ndarray,
    H: np.ndarray,
    shape: tuple[int, int],
    interpolation: str,
    fill: float,
    mirror: bool = False,
) -> np.ndarray:
    h, w = shape
    # Fix H's free sign so that the source origin (pixel (0, 0)) has w > 0, as with the
    # usual H[2, 2] = 1 (the image centre if H[2, 2] = 0); then an output pixel whose
    # source has Z <= 0 lies beyond the horizon of H (behind the viewer) and gets fill.
    centre = np.array([(img.shape[1] - 1) / 2, (img.shape[0] - 1) / 2, 1.0])
    ref = H[2, 2] if H[2, 2] != 0 else (H @ centre)[2]
    Hinv = np.linalg.inv(H) * np.sign(ref or 1.0)
    planes = _padded_planes(img, fill)
    out = np.empty((len(planes), h * w), dtype=np.float32)
    # float32 coordinates: 7 significant digits, ample for sub-pixel positions in images
    # of a few thousand pixels, and half the memory traffic of float64.
    Hi = Hinv.astype(np.float32)
    u = np.arange(w, dtype=np.float32)
    rows = max(1, _BLOCK // w)
    for v0 in range(0, h, rows):
        v = np.arange(v0, min(v0 + rows, h), dtype=np.float32)
        # Inverse mapping: output pixel (u, v) looks up the source at H^-1 (u, v, 1).
        # Each homogeneous coordinate is a row term plus a column term (an outer sum).
        X = np.add.outer(Hi[0, 1] * v + Hi[0, 2], Hi[0, 0] * u).ravel()
        Y = np.add.outer(Hi[1, 1] * v + Hi[1, 2], Hi[1, 0] * u).ravel()
        Z = np.add.outer(Hi[2, 1] * v + Hi[2, 2], Hi[2, 0] * u).ravel()
        # beyond the horizon (or NaN): not visible; mirrored, only w = 0 (or NaN) is
        hidden = ~(Z != 0) if mirror else ~(Z > 1e-30)
        with np.errstate(divide="ignore", invalid="ignore"):
            np.divide(1.0, Z, out=Z)
            X *= Z
            Y *= Z
        if hidden.any():
            X[hidden] = -2.0  # reads the fill border
            Y[hidden] = -2.0
        _sample(planes, img.shape[:2], X, Y, interpolation, out[:, v0 * w : (v0 + len(v)) * w])
    out = out.T.reshape(h, w, -1)
    return out[..., 0] if img.ndim == 2 else out


def _warp_cv2(
    img: np.ndarray, H: np.ndarray, shape: tuple[int, int], interpolation: str, fill: float
) -> np.ndarray:
    import cv2

    flags = cv2.INTER_NEAREST if interpolation == "nearest" else cv2.INTER_LINEAR
    src = img
    if img.dtype not in (np.uint8, np.uint16, np.int16, np.float32, np.float64):
        src = img.astype(np.float32)
    nch = 1 if img.ndim == 2 else img.shape[2]
    out = cv2.warpPerspective(
        src,
        H,
        (shape[1], shape[0]),
        flags=flags,
        borderMode=cv2.BORDER_CONSTANT,
        borderValue=(float(fill),) * max(nch, 1),
    )
    return _to_dtype(out.reshape(shape[0], shape[1], *img.shape[2:]), img.dtype)


def warp_perspective(
    image: ArrayLike,
    H: ArrayLike,
    output_shape: Sequence[int],
    *,
    interpolation: str = "bilinear",
    fill: float = 0,
    method: str = "numpy",
    mirror: bool = False,
) -> np.ndarray:
    r"""Warp an image by H (output = H applied to the image) by inverse mapping.

    Each output pixel (u, v) samples the source at :math:`\pi(H^{-1} (u, v, 1)^T)`;
    sample positions outside the source read ``fill`` (pixels straddling the border
    blend with it, like ``cv2.BORDER_CONSTANT``). Source points on the far side of the
    line that H sends to infinity (the side not holding pixel (0, 0)) are behind the
    viewer and get ``fill``; ``cv2.warpPerspective`` draws them mirrored instead.

    Parameters
    ----------
    image : (h, w) or (h, w, C) array_like
        uint8, other integer or float image, indexed ``image[v, u]``.
    H : (3, 3) array_like
        Homography output_from_image (maps source pixel coordinates to output ones).
    output_shape : (height, width)
        Size of the output in pixels. For a canvas that holds the whole warped image,
        use :func:`warp_to_canvas`.
    interpolation : {"bilinear", "nearest"}
    fill : float
        Value for output pixels whose source falls outside the image.
    method : {"numpy", "cv2"}
        ``"numpy"``: the readable implementation below; ``"cv2"``: ``cv2.warpPerspective``
        with the same conventions (fast; use it in interactive demos).
    mirror : bool
        The numpy path only: draw source points beyond the line H sends to infinity too, mirrored
        through it, as ``cv2.warpPerspective`` does (a picture torn by H then shows both halves,
        one leaving through infinity and coming back on the other side). Default False: ``fill``.

    Returns
    -------
    (height, width) or (height, width, C) ndarray
        Same dtype as ``image`` (integers rounded and clipped).

    Raises
    ------
    DegenerateError
        If H is singular.

    Examples
    --------
    >>> img = np.arange(12.0).reshape(3, 4)
    >>> warp_perspective(img, [[1, 0, 1], [0, 1, 0], [0, 0, 1]], (3, 4))  # shift right by 1
    array([[ 0.,  0.,  1.,  2.],
           [ 0.,  4.,  5.,  6.],
           [ 0.,  8.,  9., 10.]])
    """
    img = check_image(image)
    Hm = check_homography(H)
    shape = _check_shape(output_shape)
    _check_options(interpolation, method)
    if not np.isfinite(fill):
        raise CamlabInputError(f"fill: expected a finite number, got {fill!r}")
    if method == "cv2":
        return _warp_cv2(img, Hm, shape, interpolation, fill)
    return _to_dtype(_warp_numpy(img, Hm, shape, interpolation, fill, mirror), img.dtype)


def forward_warp(
    image: ArrayLike, H: ArrayLike, output_shape: Sequence[int], *, fill: float = 0
) -> np.ndarray:
    r"""Warp by *forward* mapping: push every source pixel to the rounded :math:`\pi(H x)`.

    Where H enlarges the image, neighbouring source pixels land more than one output
    pixel apart and the pixels between them are never written: they keep ``fill``
    (holes). Where H shrinks it, several source pixels land on one output pixel and the
    last one wins (aliasing). Compare :func:`warp_perspective`, which has neither problem.

    Parameters
    ----------
    image : (h, w) or (h, w, C) array_like
    H : (3, 3) array_like
        output_from_image.
    output_shape : (height, width)
    fill : float
        Value of pixels that no source pixel reached.

    Returns
    -------
    ndarray of ``image``'s dtype; holes hold ``fill``.

    Examples
    --------
    >>> forward_warp(np.ones((2, 2)), np.diag([2.0, 2.0, 1.0]), (4, 4))  # magnify 2x: holes
    array([[1., 0., 1., 0.],
           [0., 0., 0., 0.],
           [1., 0., 1., 0.],
           [0., 0., 0., 0.]])
    """
    img = check_image(image)
    Hm = check_homography(H)
    h, w = _check_shape(output_shape)
    sh, sw = img.shape[:2]
    vv, uu = np.mgrid[0:sh, 0:sw].reshape(2, -1).astype(float)
    # x' ~ H (u, v, 1) for every source pixel, each row of H written out: the same sums in any
    # numpy (a matrix product's rounding depends on the BLAS, and a landing spot exactly halfway
    # between two pixels, as at rotation 0, would round either way)
    w_ = Hm[2, 0] * uu + Hm[2, 1] * vv + Hm[2, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        pts = np.column_stack(
            [
                (Hm[0, 0] * uu + Hm[0, 1] * vv + Hm[0, 2]) / w_,
                (Hm[1, 0] * uu + Hm[1, 1] * vv + Hm[1, 2]) / w_,
            ]
        )
    ok = np.all(np.isfinite(pts), axis=1)
    ui = np.full(len(pts), -1, dtype=np.intp)
    vi = np.full(len(pts), -1, dtype=np.intp)
    ui[ok] = np.floor(pts[ok, 0] + 0.5).astype(np.intp)
    vi[ok] = np.floor(pts[ok, 1] + 0.5).astype(np.intp)
    inside = ok & (ui >= 0) & (ui < w) & (vi >= 0) & (vi < h)
    out = np.full((h, w, *img.shape[2:]), fill, dtype=img.dtype)
    out[vi[inside], ui[inside]] = img.reshape(sh * sw, *img.shape[2:])[inside]
    return out


class CanvasBounds(NamedTuple):
    """The outcome of :func:`canvas_bounds`.

    Attributes
    ----------
    T : (3, 3) ndarray
        The translation canvas_from_warped: ``[[1, 0, -u_min], [0, 1, -v_min], [0, 0, 1]]``.
    shape : (height, width)
        The canvas in pixels, numpy's order (a *shape*; a *size* would be (width, height)).
    """

    T: np.ndarray
    shape: tuple[int, int]


def canvas_box(homographies: Sequence[ArrayLike], shapes: Sequence[Sequence[int]]) -> np.ndarray:
    r"""The bounding box of every image's corners mapped by its homography, rounded outwards.

    The corner pixels (0, 0), (w-1, 0), (w-1, h-1), (0, h-1) of image k (shape (h, w[, C]))
    are mapped by :math:`H_k` (dividing by the third coordinate), and the box is rounded
    outwards to whole pixels, so no warped pixel is cut off. :func:`canvas_bounds` turns
    the box into a canvas. Lesson 09 writes this function as an exercise.

    Parameters
    ----------
    homographies : sequence of (3, 3) array_like
        canvas_from_image homographies, one per image.
    shapes : sequence of (h, w[, C])
        The images' shapes.

    Returns
    -------
    (2, 2) ndarray
        ``[[u_min, v_min], [u_max, v_max]]`` in pixels.

    Raises
    ------
    DegenerateError
        If a corner maps to or beyond infinity (the image crosses the line that its H
        sends to infinity): no finite canvas holds it.

    Examples
    --------
    >>> canvas_box([np.eye(3), [[1, 0, 50], [0, 1, -30], [0, 0, 1]]], [(240, 320), (240, 320)])
    array([[  0., -30.],
           [369., 239.]])
    """
    if len(homographies) != len(shapes) or len(shapes) == 0:
        raise CamlabInputError(
            f"shapes: expected one shape per homography (at least one), got {len(shapes)} for "
            f"{len(homographies)}"
        )
    corners = []
    for i, (H, shape) in enumerate(zip(homographies, shapes, strict=True)):
        Hm = check_homography(H, f"homographies[{i}]")
        h, w = int(shape[0]), int(shape[1])
        c = (
            np.array([[0, 0, 1], [w - 1, 0, 1], [w - 1, h - 1, 1], [0, h - 1, 1]], dtype=float)
            @ Hm.T
        )
        if np.all(c[:, 2] < 0):  # H and -H are one homography (a DLT's SVD returns either sign)
            c = -c
        if np.any(c[:, 2] <= 1e-12 * np.abs(c).max()):
            raise DegenerateError(
                f"homographies[{i}]: a corner of image {i} maps to or beyond infinity (the image "
                f"crosses the line that H sends to infinity), so no finite canvas holds it; crop "
                f"the image or give output_shape explicitly"
            )
        corners.append(c[:, :2] / c[:, 2:])
    pts = np.vstack(corners)
    return np.array([np.floor(pts.min(axis=0) + 1e-9), np.ceil(pts.max(axis=0) - 1e-9)])


def canvas_bounds(
    homographies: Sequence[ArrayLike],
    shapes: Sequence[Sequence[int]],
    max_pixels: int = 40_000_000,
) -> CanvasBounds:
    r"""The translation T and size of a canvas holding every image i warped by ``homographies[i]``.

    The canvas spans :func:`canvas_box` (each image's four corner pixels mapped by its H,
    rounded outwards to whole pixels), and T shifts its top-left corner to (0, 0). Warp
    image i with ``T @ homographies[i]`` so nothing is cropped at negative coordinates
    (panorama stitching uses the same canvas).

    Parameters
    ----------
    homographies : sequence of (3, 3) array_like
        canvas_from_image homographies (before the translation).
    shapes : sequence of (h, w[, C])
        The images' shapes.
    max_pixels : int
        Refuse canvases larger than this (a corner mapped near infinity).

    Returns
    -------
    CanvasBounds
        ``(T, shape)``: the translation and the canvas shape (height, width).

    Raises
    ------
    DegenerateError
        If a corner maps to or beyond infinity (the image crosses the horizon of H) or
        the canvas would exceed ``max_pixels``.

    Examples
    --------
    >>> T, shape = canvas_bounds([[[1, 0, -5], [0, 1, 3], [0, 0, 1]]], [(10, 20)])
    >>> T[:2, 2], shape
    (array([ 5., -3.]), (10, 20))
    """
    lo, hi = canvas_box(homographies, shapes)
    w_out, h_out = (hi - lo + 1).astype(int)
    if w_out * h_out > max_pixels:
        raise DegenerateError(
            f"canvas_bounds: the canvas would be {h_out} x {w_out} pixels (more than {max_pixels}); H stretches "
            f"the image enormously, probably because part of it lies near the line H sends to infinity"
        )
    T = np.array([[1.0, 0.0, -lo[0]], [0.0, 1.0, -lo[1]], [0.0, 0.0, 1.0]])
    return CanvasBounds(T, (int(h_out), int(w_out)))


class CanvasWarp(NamedTuple):
    """An image warped onto a canvas that holds all of it.

    Attributes
    ----------
    image : (height, width[, C]) ndarray
        The warped image.
    mask : (height, width) bool ndarray
        True where the output came from inside the source image.
    H : (3, 3) ndarray
        canvas_from_image: ``T @ H`` (map source points into canvas pixels with it).
    T : (3, 3) ndarray
        canvas_from_output: the translation that moved the bounding box to (0, 0); the
        point ``p`` of H's output frame is at ``map_points(T, p)`` on the canvas.
    """

    image: np.ndarray
    mask: np.ndarray
    H: np.ndarray
    T: np.ndarray


def warp_to_canvas(
    image: ArrayLike,
    H: ArrayLike,
    *,
    interpolation: str = "bilinear",
    fill: float = 0,
    method: str = "numpy",
    max_pixels: int = 40_000_000,
) -> CanvasWarp:
    """Warp the whole image by H onto an automatically sized canvas (nothing cropped).

    The canvas is the bounding box of the warped image (:func:`canvas_bounds`); its
    translation T is composed with H, so parts of the image that H sends to negative
    coordinates appear too.

    Parameters
    ----------
    image : (h, w) or (h, w, C) array_like
        The image to warp.
    H : (3, 3) array_like
        The homography, output_from_image.
    interpolation, fill, method
        As in :func:`warp_perspective`.
    max_pixels : int
        Refuse canvases larger than this (:func:`canvas_bounds`).

    Returns
    -------
    CanvasWarp
        ``image``, ``mask``, ``H`` (= T @ H, canvas_from_image) and ``T``.

    Examples
    --------
    >>> r = warp_to_canvas(np.ones((2, 3)), [[1, 0, -10], [0, 1, -20], [0, 0, 1]])
    >>> r.image.shape, r.T[:2, 2]
    ((2, 3), array([10., 20.]))
    """
    img = check_image(image)
    Hm = check_homography(H)
    _check_options(interpolation, method)
    T, shape = canvas_bounds([Hm], [img.shape], max_pixels=max_pixels)
    Hc = compose(T, Hm)
    out = warp_perspective(img, Hc, shape, interpolation=interpolation, fill=fill, method=method)
    ones = np.ones(img.shape[:2], dtype=np.float32)
    mask = warp_perspective(ones, Hc, shape, interpolation="nearest", method=method) > 0.5
    return CanvasWarp(out, mask, Hc, T)
