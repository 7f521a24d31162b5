"""Stitching stages 6-7.

Exposure gains, seams (Voronoi and dynamic-programming) and blending (overwrite, feather, multi-band
Laplacian pyramids), with the measures the lesson shows.

See :mod:`camlab.stitching` for the whole pipeline; every name here is re-exported there.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, check_image, check_integer
from .warping import WarpedImages

BLENDS = ("overwrite", "feather", "multiband")


def _over_channels(op, image: np.ndarray) -> np.ndarray:
    """``op`` (np.add, np.minimum, ...) folded over the channels of an (h, w, C) image.

    One channel at a time: the same as ``op.reduce(image, axis=2)``, which numpy runs about 10x
    slower for a short last axis.
    """
    out = image[..., 0]
    for c in range(1, image.shape[2]):
        out = op(out, image[..., c])
    return out


def _per_channel(op, image: np.ndarray, other: np.ndarray) -> None:
    """``op(image, other[..., None], out=image)`` (np.multiply, np.divide) for an (h, w, C) image.

    One channel at a time: numpy runs the broadcast over a short last axis 2-4x slower.
    """
    for c in range(image.shape[2]):
        op(image[..., c], other, out=image[..., c])


def gains_from_overlaps(
    N: ArrayLike, I_mean: ArrayLike, sigma_n: float = 10.0 / 255, sigma_g: float = 1.0
) -> np.ndarray:
    r"""Solve gain compensation's normal equations for the gains, given the overlaps' sizes and means.

    With :math:`N_{ij}` pixels in the overlap of images i and j and :math:`\bar I_{ij}` the mean
    of image i there, :math:`\partial e / \partial g_i = 0` (see :func:`gain_compensation`) is

    .. math:: g_i \sum_{j} N_{ij} \Big(\frac{2 \bar I_{ij}^2}{\sigma_N^2} + \frac{1}{\sigma_g^2}\Big)
              - \sum_j g_j N_{ij} \frac{2 \bar I_{ij} \bar I_{ji}}{\sigma_N^2} = \sum_j \frac{N_{ij}}{\sigma_g^2} ,

    one linear equation per image, :math:`A g = b`. An image with no overlap keeps the gain 1.

    Parameters
    ----------
    N : (n, n) array_like
        Pixels in each overlap, symmetric; the diagonal is ignored.
    I_mean : (n, n) array_like
        ``I_mean[i, j]``: the mean intensity of image i on its overlap with image j (the
        images' units; 0 where there is no overlap).
    sigma_n : float
        :math:`\sigma_N`, the intensity noise, in the images' units.
    sigma_g : float
        :math:`\sigma_g`, the prior's spread of the gains about 1.

    Returns
    -------
    (n,) ndarray
        The gains :math:`g`.

    Raises
    ------
    CamlabInputError
        N or I_mean not square, or of different sizes.
    """
    N = np.asarray(N, dtype=float)
    I_mean = np.asarray(I_mean, dtype=float)
    if N.ndim != 2 or N.shape[0] != N.shape[1] or I_mean.shape != N.shape:
        raise CamlabInputError(
            f"N, I_mean: expected two (n, n) arrays (overlap sizes and means), got shapes {N.shape} and "
            f"{I_mean.shape}; entry [i, j] is about the overlap of images i and j"
        )
    n = len(N)
    off = ~np.eye(n, dtype=bool)
    W = np.where(off, N, 0.0)
    A = -W * 2 * I_mean * I_mean.T / sigma_n**2  # off the diagonal: -N_ij 2 I_ij I_ji / sigma_N^2
    A[np.diag_indices(n)] = (W * (2 * I_mean**2 / sigma_n**2 + 1 / sigma_g**2)).sum(axis=1)
    b = W.sum(axis=1) / sigma_g**2
    alone = A.diagonal() == 0  # no overlap: keep the gain at 1
    A[alone, alone], b[alone] = 1.0, 1.0
    return np.linalg.solve(A, b)


def gain_compensation(
    warped: WarpedImages,
    sigma_n: float = 10.0 / 255,
    sigma_g: float = 1.0,
    reference: int | None = None,
    megapixels: float | None = 0.1,
    clip: tuple[float, float] = (2 / 255, 253 / 255),
) -> np.ndarray:
    r"""One exposure gain per image so that overlapping regions agree.

    Minimises, over all overlapping pairs with :math:`N_{ij}` common pixels and mean
    intensities :math:`\bar I_{ij}` (image i on the overlap) and :math:`\bar I_{ji}`,

    .. math:: e = \tfrac12 \sum_{i,j} N_{ij} \left( (g_i \bar I_{ij} - g_j \bar I_{ji})^2 / \sigma_N^2
              + (1 - g_i)^2 / \sigma_g^2 \right).

    Setting :math:`\partial e / \partial g_i = 0` gives one linear equation per image,

    .. math:: g_i \sum_{j} N_{ij} \Big(\frac{2 \bar I_{ij}^2}{\sigma_N^2} + \frac{1}{\sigma_g^2}\Big)
              - \sum_j g_j N_{ij} \frac{2 \bar I_{ij} \bar I_{ji}}{\sigma_N^2} = \sum_j \frac{N_{ij}}{\sigma_g^2},

    solved directly (the prior keeps the gains near 1 and the system regular). The default
    :math:`\sigma_g = 1` is weaker than Brown & Lowe's 0.1 [1]_: exposures in a hand-held set
    can differ by 30% or more, and a strong prior would leave part of that step. With
    ``reference`` given, all gains are divided by that image's gain (it keeps its look).

    Means are taken on a subsampled canvas of about ``megapixels`` (exposure is smooth; None:
    every pixel) and only over pixels that no image clips: a channel at or beyond ``clip``
    (black or saturated) has lost its true brightness, and an over-exposed white sky would
    otherwise pull the gain (and, scaled, turn grey or cyan).

    Parameters
    ----------
    warped : WarpedImages
        The n images on one canvas (:func:`warp_images`), values in [0, 1].
    sigma_n : float
        :math:`\sigma_N`, the intensity noise, in the images' units.
    sigma_g : float
        :math:`\sigma_g`, the prior's spread of the gains about 1.
    reference : int, optional
        The image whose gain becomes 1 (the others are divided by its gain).
    megapixels : float or None
        Size of the subsampled canvas the means are taken on; None: every pixel.
    clip : (2,) tuple of float
        (dark, bright): pixels with a channel at or below ``dark`` or at or above ``bright``
        in either image are left out.

    Returns
    -------
    (n,) ndarray
        Multiply image k by ``gains[k]``.

    References
    ----------
    .. [1] M. Brown and D. G. Lowe, 2007, "Automatic panoramic image stitching using invariant
       features", *International Journal of Computer Vision* 74(1), 59-73, section 6 (gain compensation).
    .. [2] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022,
       section 8.4 (compositing).
    """
    n = len(warped.patches)
    h, w = warped.shape
    step = 1 if megapixels is None else max(1, int(round(np.sqrt(h * w / (megapixels * 1e6)))))
    imgs, masks = warped.subsampled(step)
    lum = [_over_channels(np.add, im) / im.shape[2] for im in imgs]
    ok = [
        m & (_over_channels(np.minimum, im) > clip[0]) & (_over_channels(np.maximum, im) < clip[1])
        for m, im in zip(masks, imgs, strict=True)
    ]
    N = np.zeros((n, n))
    I_mean = np.zeros((n, n))
    for i in range(n):
        for j in range(n):
            both = ok[i] & ok[j]
            if i != j and both.any():
                N[i, j] = int(both.sum()) * step * step
                I_mean[i, j] = float(lum[i][both].mean())
    g = gains_from_overlaps(N, I_mean, sigma_n, sigma_g)
    if reference is not None:
        g = g / g[int(reference)]
    return g


# --------------------------------------------------------------------------- blending


def seam_masks(weights: Sequence[np.ndarray]) -> list[np.ndarray]:
    """Split the canvas between the images: each pixel goes to the image with the largest weight.

    With feather weights that is the image whose border is farthest (a Voronoi-like seam
    along the middle of each overlap).

    Parameters
    ----------
    weights : sequence of n (h, w) ndarray
        Each image's weight on the canvas (e.g. ``warped.weights``), 0 outside its footprint.

    Returns
    -------
    list of n (h, w) bool ndarray
        Disjoint masks covering every pixel some image has a positive weight at.
    """
    W = np.stack(weights)
    best = np.argmax(W, axis=0)
    covered = W.max(axis=0) > 0
    return [(best == k) & covered for k in range(len(weights))]


def _seam_path(cost: np.ndarray) -> np.ndarray:
    r"""The cheapest top-to-bottom path through ``cost`` (one column per row, steps of -1, 0, +1).

    Dynamic programming: :math:`E(r, c) = \text{cost}(r, c) + \min(E(r-1, c-1), E(r-1, c), E(r-1, c+1))`,
    then walk back up from the cheapest bottom cell.
    """
    h, w = cost.shape
    E = np.full((h, w + 2), np.inf)  # one column of infinity each side: no path leaves the grid
    E[0, 1:-1] = cost[0]
    for r in range(1, h):
        prev = E[r - 1]
        best = np.minimum(np.minimum(prev[:-2], prev[1:-1]), prev[2:])  # from c-1, c, c+1
        np.add(cost[r], best, out=E[r, 1:-1])
    # every row's step back, at once from the finished table (ties: the leftmost)
    left, up, right = E[:-1, :-2], E[:-1, 1:-1], E[:-1, 2:]
    best = np.minimum(np.minimum(left, up), right)
    back = np.zeros((h, w), np.int64)
    back[1:] = np.where(left == best, -1, np.where(up == best, 0, 1))
    E = E[:, 1:-1]
    path = np.zeros(h, np.int64)
    path[-1] = int(np.argmin(E[-1]))
    for r in range(h - 1, 0, -1):
        path[r - 1] = path[r] + back[r, path[r]]
    return path


def dp_seam_masks(warped: WarpedImages, megapixels: float = 0.1) -> list[np.ndarray]:
    r"""Seams along which the images differ least, found by dynamic programming at low resolution.

    Images are added one at a time. Where image k overlaps what is already placed, the
    cost of a seam through a pixel is how different the two images are there, in colour
    and in gradient, :math:`|I_a - I_k| + |\nabla I_a - \nabla I_k|` (summed over channels),
    and :func:`_seam_path` finds the cheapest path across the overlap (top to bottom, or
    left to right if the overlap is wider than tall); each side goes to the image that
    owns the pixels beyond it. A seam that avoids differences (a moving person, parallax, a
    small misregistration) hides them: the blend then only has to hide exposure. The
    search runs on a canvas subsampled to about ``megapixels``; the labels are scaled back
    up (nearest), and pixels the coarse labels miss go to the largest feather weight.

    Parameters
    ----------
    warped : WarpedImages
        The images on one canvas (:func:`warp_images`), added in their order.
    megapixels : float
        Size of the subsampled canvas the seams are searched on.

    Returns
    -------
    list of bool ndarray
        Disjoint seam masks covering the union of the footprints, each in its image's box
        (``masks[k]`` covers the canvas pixels ``warped.boxes[k]``, like ``warped.patch_masks[k]``).
    """
    h, w = warped.shape
    step = max(1, int(round(np.sqrt(h * w / (megapixels * 1e6)))))
    imgs, masks = warped.subsampled(step)
    label = np.full(masks[0].shape, -1, np.int16)
    comp = np.zeros_like(imgs[0])
    for k, (im, m) in enumerate(zip(imgs, masks, strict=True)):
        placed = label >= 0
        ov = placed & m
        if ov.sum() > 2:
            rows, cols = np.flatnonzero(ov.any(axis=1)), np.flatnonzero(ov.any(axis=0))
            box = (slice(rows[0], rows[-1] + 1), slice(cols[0], cols[-1] + 1))
            a, b = comp[box], im[box]
            diff = _over_channels(np.add, np.abs(a - b))
            for ax in (0, 1):
                diff += _over_channels(
                    np.add, np.abs(np.diff(a, axis=ax, prepend=0) - np.diff(b, axis=ax, prepend=0))
                )
            cost = np.where(ov[box], diff, 1e6)
            tall = cost.shape[0] >= cost.shape[1]
            path = _seam_path(cost if tall else cost.T)
            grid = np.arange(cost.shape[1] if tall else cost.shape[0])
            left = grid[None, :] <= path[:, None]
            left = left if tall else left.T
            # which side is k's: where k alone lies, in the box's frame
            only_k, only_a = (m & ~placed)[box], (placed & ~m)[box]
            axis = 1 if tall else 0
            pos = np.indices(only_k.shape)[axis]
            k_left = (pos[only_k].mean() if only_k.any() else np.inf) < (
                pos[only_a].mean() if only_a.any() else -np.inf
            )
            take = ov[box] & (left if k_left else ~left)
            label[box][take] = k
            np.copyto(comp[box], b, where=take[..., None])
        fresh = m & ~placed
        label[fresh] = k
        np.copyto(comp, im, where=fresh[..., None])  # comp[fresh] = im[fresh], 2x faster
    # back to full resolution, box by box: each pixel takes its nearest coarse label
    near_r = np.minimum((np.arange(h) + step // 2) // step, label.shape[0] - 1)
    near_c = np.minimum((np.arange(w) + step // 2) // step, label.shape[1] - 1)
    out, covered = [], np.zeros((h, w), bool)
    for k, (m, (r0, r1, c0, c1)) in enumerate(zip(warped.patch_masks, warped.boxes, strict=True)):
        # compared on the coarse grid, then rows and columns taken one axis at a time (a 2-D
        # fancy index of the int16 labels costs about 5x more)
        own = (label == k).take(near_r[r0:r1], axis=0).take(near_c[c0:c1], axis=1) & m
        covered[r0:r1, c0:c1] |= own
        out.append(own)
    missed = np.zeros(
        (h, w), bool
    )  # a thin rim: footprint pixels whose nearest coarse label is not theirs
    for m, (r0, r1, c0, c1) in zip(warped.patch_masks, warped.boxes, strict=True):
        missed[r0:r1, c0:c1] |= m & ~covered[r0:r1, c0:c1]
    ys, xs = np.nonzero(missed)
    best_w, best_k = np.zeros(len(ys), np.float32), np.full(len(ys), -1)
    for k, (wk, (r0, r1, c0, c1)) in enumerate(
        zip(warped.patch_weights, warped.boxes, strict=True)
    ):  # the largest feather weight
        inside = np.flatnonzero((ys >= r0) & (ys < r1) & (xs >= c0) & (xs < c1))
        wv = wk[ys[inside] - r0, xs[inside] - c0]
        better = wv > best_w[inside]
        best_w[inside[better]], best_k[inside[better]] = wv[better], k
    for k, (r0, _r1, c0, _c1) in enumerate(warped.boxes):
        mine = best_k == k
        out[k][ys[mine] - r0, xs[mine] - c0] = True
    return out


def overlap_difference(warped: WarpedImages, i: int = 0, j: int = 1) -> float:
    """Mean absolute difference of images i and j where both cover the canvas (0 if they never overlap).

    After registration a rotation panorama differs only by noise and exposure here; parallax
    (a camera that moved in front of a 3-D scene) leaves misaligned objects: the ghosts
    blending will show.

    Parameters
    ----------
    warped : WarpedImages
        The images on one canvas.
    i, j : int
        The two images' indices.

    Returns
    -------
    float
        The mean absolute difference over the overlap's pixels and channels, in the
        images' units; 0.0 without an overlap.
    """
    both = warped.masks[i] & warped.masks[j]
    if not both.any():
        return 0.0
    return float(np.abs(warped.images[i][both] - warped.images[j][both]).mean())


def seam_step(
    image: np.ndarray, seam: np.ndarray, overlap: np.ndarray, width: int = 4, signed: bool = False
) -> float:
    """How visible a vertical seam is: the mean brightness step across it, in the image's units.

    For every row, the seam is where ``seam`` (one image's seam mask) switches on or off
    inside ``overlap``; the step is the mean luminance of the ``width`` pixels after it
    minus the ``width`` pixels before it. Texture averages out over the rows (its
    differences have both signs); an exposure jump does not. Steps whose 2 ``width`` pixels
    are not all inside ``overlap`` or the image are skipped.

    Parameters
    ----------
    image : (h, w) or (h, w, C) ndarray
        The blended panorama (channels are averaged into a luminance).
    seam : (h, w) bool ndarray
        One image's seam mask on the canvas.
    overlap : (h, w) bool ndarray
        Where both images cover the canvas.
    width : int
        Pixels averaged on each side of the seam.
    signed : bool
        Return the mean step with its sign (from outside ``seam`` into it), so that two
        steps across the same line can be subtracted: a blend's step less the scene's own
        (one photo alone across the same line) is what the seam adds.

    Returns
    -------
    float
        The absolute mean step (0 for a perfect blend; the exposure difference times the
        brightness for overwrite), or 0.0 if there is no seam; with ``signed`` its sign kept.
    """
    lum = np.asarray(image, dtype=float)
    lum = lum.mean(axis=2) if lum.ndim == 3 else lum
    steps = []
    for r in range(lum.shape[0]):
        cols = np.flatnonzero((seam[r, 1:] != seam[r, :-1]) & overlap[r, 1:] & overlap[r, :-1])
        for c in cols:
            lo, hi = c + 1 - width, c + 1 + width
            if lo < 0 or hi > lum.shape[1] or not overlap[r, lo:hi].all():
                continue
            sign = 1.0 if seam[r, c + 1] else -1.0  # orient: from the other image into this one
            steps.append(sign * (lum[r, c + 1 : hi].mean() - lum[r, lo : c + 1].mean()))
    mean = float(np.mean(steps)) if steps else 0.0
    return mean if signed else abs(mean)


def _pyr_down(image: np.ndarray) -> np.ndarray:
    """``cv2.pyrDown`` of an (h, w, C) image, keeping the channel axis (OpenCV drops it when C is 1)."""
    import cv2

    out = cv2.pyrDown(image)
    return out.reshape(out.shape[:2] + image.shape[2:])


def _fill_outside(img: np.ndarray, mask: np.ndarray, levels: int) -> np.ndarray:
    """Extend an image beyond its mask by push-pull (normalised pyramid), so pyramids do not see black."""
    import cv2

    m = mask.astype(np.float32)
    stack = [(img * m[..., None], m)]
    for _ in range(levels):
        a, w = stack[-1]
        if min(w.shape) < 2:
            break
        stack.append((_pyr_down(a), cv2.pyrDown(w)))
    a, w = stack[-1]
    filled = a / np.maximum(w, 1e-6)[..., None]
    for a, w in reversed(stack[1:-1]):
        filled = cv2.pyrUp(filled, dstsize=(w.shape[1], w.shape[0])).reshape(a.shape)
        own = a / np.maximum(w, 1e-6)[..., None]
        own -= filled
        own *= np.minimum(w * 4, 1)[
            ..., None
        ]  # trust the pixel's own (normalised) value where it has support
        filled += own  # up + t (own - up)
    # full resolution: the image itself inside the mask, the pulled-up fill outside
    up = cv2.pyrUp(filled, dstsize=(mask.shape[1], mask.shape[0])).reshape(img.shape)
    np.copyto(up, img, where=mask[..., None])
    return up


def _blend_inputs(images, masks) -> tuple[list, list]:
    """Images as finite (h, w, C) arrays and masks as (h, w) bool of the same size, or a clear error."""
    for value, name in ((images, "images"), (masks, "masks")):
        if value is None or isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
            raise CamlabInputError(
                f"{name}: expected a list with one array per image, got {type(value).__name__}"
            )
    if len(images) != len(masks) or not len(images):
        raise CamlabInputError(
            f"masks: expected one mask per image, got {len(masks)} for {len(images)} images"
        )
    imgs = [check_image(im, f"images[{k}]", channels=(1, 2, 3, 4)) for k, im in enumerate(images)]
    shape = imgs[0].shape[:2]
    out = []
    for k, (im, m) in enumerate(zip(imgs, masks, strict=True)):
        mk = np.asarray(m)
        if mk.dtype != bool or mk.shape != shape or im.shape[:2] != shape or im.ndim != 3:
            raise CamlabInputError(
                f"masks[{k}]: expected a bool (h, w) mask of the (h, w, C) images' size {shape}, "
                f"got {mk.dtype} {mk.shape} for an image of shape {im.shape}"
            )
        out.append(mk)
    return imgs, out


def laplacian_blend(
    images: Sequence[np.ndarray],
    masks: Sequence[np.ndarray],
    levels: int = 5,
    footprints: Sequence[np.ndarray] | None = None,
) -> np.ndarray:
    r"""Multi-band blending of images with disjoint seam masks.

    Each image's Laplacian pyramid :math:`L_k^{(l)} = G_k^{(l)} - \mathrm{up}(G_k^{(l+1)})`
    holds its detail at band l; each seam mask's Gaussian pyramid :math:`M_k^{(l)}` gets
    smoother at coarser levels. Blend band by band and collapse:

    .. math:: L^{(l)} = \frac{\sum_k M_k^{(l)} L_k^{(l)}}{\sum_k M_k^{(l)}}, \qquad
              I = L^{(0)} + \mathrm{up}(L^{(1)} + \mathrm{up}(\dots)).

    Coarse bands (exposure, shading) cross the seam over about :math:`2^l` pixels, fine
    detail over one or two: no visible seam, no ghost of misregistered detail. Pixels
    outside an image are first filled by push-pull so its pyramid does not see a black
    border. Pyramids use ``cv2.pyrDown``/``cv2.pyrUp`` (the 5-tap binomial filter). The
    method is Burt & Adelson's [1]_, as Brown & Lowe [2]_ use it for panoramas.

    Parameters
    ----------
    images : sequence of (h, w, C) float32
        The images on one canvas, values in [0, 1].
    masks : sequence of (h, w) bool
        Disjoint seam masks (:func:`seam_masks`); the union is the panorama.
    levels : int
        Pyramid levels below the full resolution.
    footprints : sequence of (h, w) bool, optional
        Where each image has data (default: its seam mask); outside, it is extended by
        push-pull before its pyramid is built.

    Returns
    -------
    (h, w, C) float32 ndarray
        The blend, clipped to [0, 1]; 0 outside the union of the masks. The number of levels
        is capped at :math:`\log_2 \min(h, w) - 2`.

    Raises
    ------
    CamlabInputError
        Not one mask per image, images that are not (h, w, C) of one size, masks that are
        not bool of that size, or ``levels`` < 1.

    References
    ----------
    .. [1] P. J. Burt and E. H. Adelson, 1983, "A multiresolution spline with application to
       image mosaics", *ACM Transactions on Graphics* 2(4), 217-236.
    .. [2] M. Brown and D. G. Lowe, 2007, "Automatic panoramic image stitching using invariant
       features", *International Journal of Computer Vision* 74(1), 59-73, section 7 (multi-band blending).
    """
    images, masks = _blend_inputs(images, masks)
    levels = check_integer(levels, "levels", minimum=1)
    feet = masks if footprints is None else footprints
    boxes = []
    for m, f in zip(masks, feet, strict=True):  # each image's box: where it has data
        both = m | f
        rows, cols = np.flatnonzero(both.any(axis=1)), np.flatnonzero(both.any(axis=0))
        boxes.append((rows[0], rows[-1] + 1, cols[0], cols[-1] + 1) if len(rows) else (0, 0, 0, 0))
    return _multiband(
        [im[r0:r1, c0:c1] for im, (r0, r1, c0, c1) in zip(images, boxes, strict=True)],
        [m[r0:r1, c0:c1] for m, (r0, r1, c0, c1) in zip(masks, boxes, strict=True)],
        [f[r0:r1, c0:c1] for f, (r0, r1, c0, c1) in zip(feet, boxes, strict=True)],
        boxes,
        masks[0].shape,
        levels,
    )


def _seam_work_box(
    m: np.ndarray, r0: int, c0: int, shape: tuple, step: int, pad: int
) -> tuple[int, int, int, int]:
    """(y0, y1, x0, x1).

    The bounding box on the canvas of a seam mask ``m`` placed at (r0, c0), padded by the filters'
    reach and aligned to the coarsest grid; outside it the blurred seam mask is zero, so blending
    there changes nothing.
    """
    h, w = shape
    rows, cols = np.flatnonzero(m.any(axis=1)) + r0, np.flatnonzero(m.any(axis=0)) + c0
    y0, x0 = max(0, (rows[0] - pad) // step * step), max(0, (cols[0] - pad) // step * step)
    y1, x1 = min(h, rows[-1] + 1 + pad), min(w, cols[-1] + 1 + pad)
    if y1 < h:
        y1 = min(h, y0 + -(-(y1 - y0) // step) * step)
    if x1 < w:
        x1 = min(w, x0 + -(-(x1 - x0) // step) * step)
    return y0, y1, x0, x1


def _multiband(
    images: list,
    masks: list,
    feet: list,
    boxes: list,
    shape: tuple,
    levels: int,
    *,
    extended: bool = False,
    gains: np.ndarray | None = None,
) -> np.ndarray:
    """:func:`laplacian_blend` of images given in boxes of the canvas.

    ``images[k]``, ``masks[k]`` (seam) and ``feet[k]`` (footprint) cover the canvas pixels
    ``boxes[k] = (r0, r1, c0, c1)``.

    Each image is extended beyond its footprint before its pyramid is built: by push-pull
    (:func:`_fill_outside`), or, if ``extended`` (the images already repeat their edge
    pixels outside the footprint, as :func:`warp_images` makes them), by repeating the
    box's border pixels, as OpenCV's multi-band blender does. ``gains`` (with ``extended``)
    are applied to that copy as :func:`_gained` would to the whole image (the same values,
    without a second copy of every image).
    """
    import cv2

    h, w = shape
    levels = max(0, min(levels, int(np.log2(max(2, min(h, w)))) - 2))
    nch = images[0].shape[2]
    # level sizes of the whole canvas (pyrDown halves, rounding up)
    sizes = [(h, w)]
    for _ in range(levels):
        sizes.append(((sizes[-1][0] + 1) // 2, (sizes[-1][1] + 1) // 2))
    acc = [np.zeros((*sz, nch), np.float32) for sz in sizes]
    wsum = [np.zeros(sz, np.float32) for sz in sizes]
    union = np.zeros((h, w), bool)
    step = 1 << levels
    # each pyrDown's 5-tap filter reaches 2 pixels of its input, 2^l full-resolution pixels at level l,
    # so after `levels` of them a seam mask reaches 2 (2^levels - 1) < 2 step pixels beyond itself
    pad = 2 * step
    work = [
        _seam_work_box(m, r0, c0, (h, w), step, pad) if m.any() else None
        for m, (r0, _r1, c0, _c1) in zip(masks, boxes, strict=True)
    ]
    buf = _scratch(work, (h, w), nch)
    for k, (img, m, foot, (r0, r1, c0, c1)) in enumerate(
        zip(images, masks, feet, boxes, strict=True)
    ):
        if work[k] is None:
            continue
        union[r0:r1, c0:c1] |= m
        y0, y1, x0, x1 = work[k]
        # the image's box placed in that aligned box (each may stick out of the other)
        mk0 = _view(buf.mask, (y1 - y0, x1 - x0))
        mk0.fill(0)
        ys, xs = (
            slice(max(r0, y0) - y0, min(r1, y1) - y0),
            slice(max(c0, x0) - x0, min(c1, x1) - x0),
        )
        ps, qs = (
            slice(max(r0, y0) - r0, min(r1, y1) - r0),
            slice(max(c0, x0) - c0, min(c1, x1) - c0),
        )
        mk0[ys, xs] = m[ps, qs]
        if extended:
            sub = cv2.copyMakeBorder(
                np.asarray(img[ps, qs], np.float32),  # OpenCV reads the strided box as it is
                ys.start,
                y1 - y0 - ys.stop,
                xs.start,
                x1 - x0 - xs.stop,
                cv2.BORDER_REPLICATE,
                dst=_view(buf.copy, mk0.shape + (nch,)),
            ).reshape(mk0.shape + (nch,))
            g = [sub if gains is None else _gained(sub, gains[k], out=sub)]
        else:
            sub = np.zeros((y1 - y0, x1 - x0, nch), np.float32)
            valid = np.zeros((y1 - y0, x1 - x0), bool)
            sub[ys, xs] = img[ps, qs]
            valid[ys, xs] = foot[ps, qs] | m[ps, qs]
            g = [_fill_outside(sub, valid, levels).astype(np.float32, copy=False)]
        mk = [mk0]
        for _ in range(levels):
            g.append(_pyr_down(g[-1]))
            mk.append(cv2.pyrDown(mk[-1]))
        _add_bands(g, mk, acc, wsum, (y0, x0), buf.up)
    for a, s in zip(acc, wsum, strict=True):  # each band's weighted mean, in place
        _per_channel(np.divide, a, np.maximum(s, 1e-6, out=s))
    for lv in range(levels - 1, -1, -1):  # collapse: acc[lv] += up(acc[lv + 1])
        acc[lv] += _pyr_up(acc[lv + 1], _view(buf.up, acc[lv].shape))
    out = acc[0]
    np.clip(out, 0, 1, out=out)
    _per_channel(np.multiply, out, union)  # 0 outside the union (out[~union] = 0 is 4x slower)
    return out


def _add_bands(g: list, mk: list, acc: list, wsum: list, corner: tuple, up: np.ndarray) -> None:
    """Add one image's Laplacian bands, times its seam mask's pyramid, into ``acc`` (and the masks into ``wsum``).

    ``g`` and ``mk`` are the Gaussian pyramids of the image and of its seam mask in its work box,
    whose corner on the full-resolution canvas is ``corner`` = (y0, x0); ``up`` is scratch.
    """
    levels = len(g) - 1
    for lv in range(levels + 1):
        if lv < levels:  # band = g[lv] - up(g[lv + 1])
            band = _pyr_up(g[lv + 1], _view(up, g[lv].shape))
            np.subtract(g[lv], band, out=band)
        else:
            band = g[levels]
        _per_channel(np.multiply, band, mk[lv])
        oy, ox = corner[0] >> lv, corner[1] >> lv
        hh, ww = mk[lv].shape
        acc[lv][oy : oy + hh, ox : ox + ww] += band
        wsum[lv][oy : oy + hh, ox : ox + ww] += mk[lv]


class _Scratch(NamedTuple):
    """Flat float32 buffers :func:`_multiband` reuses for every image and level.

    A fresh multi-megabyte array costs a page fault per page (numpy asks for huge pages from
    4 MB, each zeroed on its first touch), so each image's arrays are views of these.
    """

    up: np.ndarray  # an upsampled level, of a band or of the collapse (up to the whole canvas)
    copy: np.ndarray  # an image's bordered copy: level 0 of its pyramid
    mask: np.ndarray  # its seam mask, level 0


def _scratch(work: list, shape: tuple, nch: int) -> _Scratch:
    """:class:`_Scratch` large enough for the canvas ``shape`` and every work box (None: skipped)."""
    area = max(((y1 - y0) * (x1 - x0) for y0, y1, x0, x1 in filter(None, work)), default=0)
    return _Scratch(
        *(np.empty(n, np.float32) for n in (shape[0] * shape[1] * nch, area * nch, area))
    )


def _view(buffer: np.ndarray, shape: tuple) -> np.ndarray:
    """A C-contiguous array of ``shape`` over the start of the flat scratch ``buffer``."""
    return buffer[: int(np.prod(shape))].reshape(shape)


def _pyr_up(image: np.ndarray, out: np.ndarray) -> np.ndarray:
    """``cv2.pyrUp`` of an (h, w, C) image into ``out`` (its shape sets the size), channel axis kept."""
    import cv2

    return cv2.pyrUp(image, dst=out, dstsize=(out.shape[1], out.shape[0])).reshape(out.shape)


def _gained(image: np.ndarray, gain: float, out: np.ndarray | None = None) -> np.ndarray:
    """``min(gain * image, 1)`` as float32 (image >= 0), in one new array or in ``out``."""
    out = np.multiply(image, np.float32(gain), out=out)
    return np.minimum(out, np.float32(1), out=out)


def blend(
    warped: WarpedImages,
    method: str = "multiband",
    *,
    gains: ArrayLike | None = None,
    levels: int = 5,
    feather_power: float = 1.0,
    seam: str = "voronoi",
    seams: Sequence[np.ndarray] | None = None,
) -> np.ndarray:
    r"""Blend images warped onto one canvas.

    * ``"overwrite"``: paint the images in order, each over the previous (hard seams:
      every exposure or alignment difference shows as an edge).
    * ``"feather"``: :math:`I = \sum_k w_k^p I_k / \sum_k w_k^p` with the warped
      :func:`feather_weights` (smooth seams; misaligned detail doubles: ghosts and blur).
    * ``"multiband"``: :func:`laplacian_blend` over seam masks: ``seam="voronoi"``
      (:func:`seam_masks`, the middle of each overlap) or ``"dp"`` (:func:`dp_seam_masks`,
      along the smallest differences).

    Parameters
    ----------
    warped : WarpedImages
        The images on one canvas (:func:`warp_images`).
    method : {"overwrite", "feather", "multiband"}
        How to combine them (above).
    gains : (n,) array_like, optional
        Exposure gains (:func:`gain_compensation`) applied first.
    levels : int
        Pyramid levels for ``"multiband"``.
    feather_power : float
        p above: larger values sharpen the transition towards a seam.
    seam : {"voronoi", "dp"}
        How ``"multiband"`` finds its seam masks when ``seams`` is not given.
    seams : list of bool ndarray, optional
        Seam masks already found, in the images' boxes (:func:`dp_seam_masks`); ``seam`` is
        then not used.

    Every image is blended within its own box of the canvas (``warped.boxes``).

    Returns
    -------
    (h, w, C) float32 ndarray
        The panorama, values in [0, 1] (gains are clipped at 1); 0 where no image lands.

    Raises
    ------
    CamlabInputError
        An unknown ``method`` or ``seam``, ``gains`` not one per image, or ``levels`` < 1.

    References
    ----------
    .. [1] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022,
       section 8.4 (compositing: feathering, seams, blending).
    """
    if method not in BLENDS:
        raise CamlabInputError(f"method: expected one of {BLENDS}, got {method!r}")
    if seam not in ("voronoi", "dp"):
        raise CamlabInputError(f"seam: expected 'voronoi' or 'dp', got {seam!r}")
    imgs = warped.patches
    g = None
    if gains is not None:
        g = np.asarray(gains, dtype=float).ravel()
        if g.shape != (len(imgs),):
            raise CamlabInputError(
                f"gains: expected {len(imgs)} gains (one per image), got shape {g.shape}"
            )
        if method != "multiband":  # multiband applies them to its own copy of each box
            imgs = [_gained(im, gk) for im, gk in zip(imgs, g, strict=True)]
    h, w = warped.shape
    boxes = warped.boxes
    if method == "overwrite":
        out = np.zeros((h, w, imgs[0].shape[2]), np.float32)
        for im, m, (r0, r1, c0, c1) in zip(imgs, warped.patch_masks, boxes, strict=True):
            out[r0:r1, c0:c1][m] = im[m]
        return out
    if method == "feather":
        num = np.zeros((h, w, imgs[0].shape[2]), np.float32)
        den = np.zeros((h, w), np.float32)
        for im, wk, (r0, r1, c0, c1) in zip(imgs, warped.patch_weights, boxes, strict=True):
            wp = wk ** np.float32(feather_power) if feather_power != 1 else wk
            num[r0:r1, c0:c1] += im * wp[..., None]
            den[r0:r1, c0:c1] += wp
        return np.where(den[..., None] > 0, num / np.maximum(den, 1e-12)[..., None], 0).astype(
            np.float32
        )
    if seams is None and seam == "dp":
        seams = dp_seam_masks(warped)
    elif seams is None:  # the Voronoi masks lie inside each image's footprint, so inside its box
        seams = [
            sk[r0:r1, c0:c1]
            for sk, (r0, r1, c0, c1) in zip(seam_masks(warped.weights), boxes, strict=True)
        ]
    return _multiband(
        imgs,
        seams,
        warped.patch_masks,
        boxes,
        warped.shape,
        check_integer(levels, "levels", minimum=1),
        extended=True,
        gains=g,
    )
