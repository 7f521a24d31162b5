r"""Image stitching: a panorama pipeline with every stage exposed.

The stages, each a function you can call, inspect and replace (lesson 09):

1. **Features and matches** (:mod:`camlab.features`): SIFT keypoints, ratio test.
2. **Pairwise registration** :func:`register_pair`: match, then
   :func:`camlab.homography.ransac_homography`; the pair is accepted only if enough
   matches agree (Brown & Lowe's test: :math:`n_\text{inliers} > 8 + 0.3\, n_\text{matches}`
   and at least ``min_inliers``).
3. **Match graph** :func:`match_graph`: every pair is registered; the **reference** image
   is the one connected to most others (ties: most inliers); a maximum spanning tree
   (edges weighted by inliers) chains every other image to it,
   :math:`H_{\text{ref} \leftarrow k} = H_{\text{ref} \leftarrow p} H_{p \leftarrow k}`.
   Images that no accepted pair reaches are listed in ``unconnected``, never dropped
   silently.
4. **Canvas** (:func:`camlab.warp.canvas_bounds`): map every image's corners by its
   homography, take the bounding box, and prepend one translation T so nothing has a
   negative coordinate. ``T @ H_ref<-k`` maps image k onto the canvas.
5. **Warp** :func:`warp_images`: every image onto the canvas (:func:`camlab.warp.warp_perspective`,
   cv2 path), with its mask and its feather weight.
6. **Exposure** :func:`gain_compensation` (optional): one gain per image so overlaps agree.
7. **Blend** :func:`blend`: ``"overwrite"`` (hard seams), ``"feather"`` (weights falling
   to zero at each image border, :func:`feather_weights`) or ``"multiband"``
   (Burt & Adelson's Laplacian-pyramid blending: low frequencies blended over wide
   regions, fine detail over narrow ones, so neither seams nor ghosts).

:func:`stitch` runs them all. For wide rotations with a known focal length,
``projection="cylindrical"`` first maps every image onto a cylinder
(:func:`cylindrical_warp`), where a turning camera becomes a sliding one.

Why a homography? A camera that only rotates about its centre sees every point along
the same ray whatever its depth, :math:`x_j \sim K R_j R_i^T K^{-1} x_i`; a planar
scene is related by :math:`K (R - t n^T/d) K^{-1}`. Anything else (a camera that
translates in front of a 3-D scene) has parallax, and no single homography aligns it:
ghosts. Pixel convention: (u, v) = (column, row), origin at the centre of the top-left
pixel (docs/conventions.md).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple, Sequence

import numpy as np
from numpy.typing import ArrayLike

from .. import features as _feat
from .. import homography as _hg
from .._validate import CamlabInputError, DegenerateError, check_image, check_integer, check_intrinsics, check_shape
from ..projective import map_points
from ..warp import canvas_bounds, warp_perspective

__all__ = ["BLENDS", "PROJECTION_CHOICES", "MatchGraph", "PairRegistration", "PairReport", "StitchResult",
           "WarpedImages", "blend", "canvas_box", "cylindrical_warp", "dp_seam_masks", "feather_weights", "largest_rectangle",
           "gain_compensation", "laplacian_blend", "match_graph",
           "overlap_difference", "prepare_images", "register_pair", "seam_masks", "seam_step", "stitch", "warp_images"]

BLENDS = ("overwrite", "feather", "multiband")


# --------------------------------------------------------------------------- input

def prepare_images(images: Sequence[ArrayLike]) -> list[np.ndarray]:
    """Validate ``images`` and return them as float32 RGB arrays in [0, 1].

    Grey (H, W) or (H, W, 1) images become RGB (the panorama is colour if any input is);
    an alpha channel is dropped. uint8 is divided by 255, uint16 by 65535, floats are
    taken as already in [0, 1]. Sizes may differ.
    """
    if isinstance(images, np.ndarray) and images.ndim in (2, 3) and images.dtype != object:
        raise CamlabInputError(f"images: expected a list of images, got one array of shape {images.shape}; "
                               f"pass [image1, image2, ...]")
    imgs = list(images)
    if len(imgs) < 2:
        raise CamlabInputError(f"images: expected at least 2 images to stitch, got {len(imgs)}")
    out = []
    for i, im in enumerate(imgs):
        a = np.asarray(im)
        if a.ndim not in (2, 3) or (a.ndim == 3 and a.shape[2] not in (1, 3, 4)) or min(a.shape[:2]) < 16:
            raise CamlabInputError(f"images[{i}]: expected a (H, W) grey or (H, W, 3|4) colour image at least "
                                   f"16 x 16 pixels, got shape {a.shape}")
        if a.dtype == np.uint8:
            f = a.astype(np.float32) / 255
        elif a.dtype == np.uint16:
            f = a.astype(np.float32) / 65535
        elif np.issubdtype(a.dtype, np.floating):
            f = a.astype(np.float32)
        else:
            raise CamlabInputError(f"images[{i}]: expected uint8, uint16 or float pixels, got dtype {a.dtype}")
        if f.ndim == 2:
            f = f[..., None]
        if f.shape[2] == 4:
            f = f[..., :3]
        if f.shape[2] == 1:
            f = np.repeat(f, 3, axis=2)
        out.append(np.ascontiguousarray(f))
    return out


# --------------------------------------------------------------------------- registration

class PairRegistration(NamedTuple):
    """The registration of image i onto image j.

    Attributes
    ----------
    H : (3, 3) ndarray or None
        Maps image i's pixels to image j's (None if RANSAC found nothing).
    matches : camlab.features.Matches
        The putative matches (after the ratio test); ``matches.src`` in image i.
    inliers : (M,) bool ndarray
        Matches consistent with H (all False if H is None).
    residual_rms : float
        RMS one-way transfer error :math:`\\|x_j - \\pi(H x_i)\\|` of the inliers, pixels.
    accepted : bool
        Enough inliers to trust H (see :func:`register_pair`).
    reason : str
        Why the pair was rejected ("" if accepted).
    """

    H: np.ndarray | None
    matches: _feat.Matches
    inliers: np.ndarray
    residual_rms: float
    accepted: bool
    reason: str


def register_pair(features1: _feat.Features, features2: _feat.Features, *, ratio: float = 0.75,
                  mutual: bool = False, threshold: float = 3.0, min_inliers: int = 15,
                  rng: np.random.Generator | None = None, matches: _feat.Matches | None = None,
                  refine: bool = True, approximate: bool = False, confidence: float = 0.999,
                  max_iters: int = 2000) -> PairRegistration:
    r"""Register image 1 onto image 2: match features, fit H by RANSAC, judge the result.

    The pair is accepted when RANSAC finds at least ``min_inliers`` inliers *and* more
    than :math:`8 + 0.3 n_m` of the :math:`n_m` matches (Brown & Lowe 2007, eq. 13: the
    inliers of a wrong model are few and random, those of a right one a fixed share), and
    H does not mirror the image (a reflection fits the matches of a symmetric scene but
    no camera produces it).
    A rejected pair is returned with ``accepted=False`` and a ``reason``, not raised, so a
    panorama can report it. With ``refine`` (default), H is polished by
    :func:`camlab.homography.refine_homography` (Levenberg-Marquardt on the geometric
    error of the inliers) and the inliers recomputed: the DLT minimises an algebraic error
    and can be off by a pixel or more at the image corners, far from the matches.

    Parameters
    ----------
    features1, features2 : camlab.features.Features
    ratio, mutual : see :func:`camlab.features.filter_matches`
    threshold : float
        RANSAC inlier threshold (symmetric transfer error, pixels).
    min_inliers : int
    rng : np.random.Generator, optional
        RANSAC's randomness (default: seeded with 0, so results are reproducible).
    matches : camlab.features.Matches, optional
        Use these matches instead of matching (e.g. re-filtered ones from a slider).
    approximate : bool
        Match with FLANN instead of brute force (:func:`camlab.features.knn_match`).
    confidence, max_iters : float, int
        RANSAC's stopping rule (:func:`camlab.homography.ransac_homography`).
    """
    rng = np.random.default_rng(0) if rng is None else rng
    m = _feat.match_features(features1, features2, ratio, mutual, approximate=approximate) if matches is None else matches
    n = len(m.src)
    none = np.zeros(n, bool)
    if n < max(min_inliers, 5):
        return PairRegistration(None, m, none, float("nan"), False,
                                f"too few matches: {n} (need at least {max(min_inliers, 5)})")
    try:
        r = _hg.ransac_homography(m.src, m.dst, threshold, confidence, max_iters, rng)
    except DegenerateError as exc:
        return PairRegistration(None, m, none, float("nan"), False, f"RANSAC failed: {exc}")
    H, inl = r.H, r.inliers
    if refine and inl.sum() >= 8:
        try:
            H = _hg.refine_homography(H, m.src[inl], m.dst[inl]).H
            inl = _hg.symmetric_transfer_error(H, m.src, m.dst) < threshold
        except (DegenerateError, _hg.ConvergenceError):
            H, inl = r.H, r.inliers
    k = int(inl.sum())
    rms = float(np.sqrt(np.mean(_hg.transfer_error(H, m.src[inl], m.dst[inl]) ** 2))) if k else np.nan
    need = max(min_inliers, int(np.floor(8 + 0.3 * n)) + 1)
    if k < need:
        return PairRegistration(H, m, inl, rms, False,
                                f"too few inliers: {k} of {n} matches (need {need}); the images probably do not overlap")
    if _mirrors(H, m.src[inl]):
        return PairRegistration(H, m, inl, rms, False, f"the homography mirrors the image ({k} inliers): a "
                                "reflection, which no camera motion produces; wrong matches on a symmetric scene")
    return PairRegistration(H, m, inl, rms, True, "")


def _mirrors(H: np.ndarray, points: np.ndarray) -> bool:
    r"""Whether H reverses orientation at the points' centroid x: the Jacobian of
    :math:`\pi(H x)` has determinant :math:`\det H / w^3` with :math:`w = (H \tilde x)_3`."""
    c = np.append(points.mean(axis=0), 1.0)
    return float(np.linalg.det(H) / (H[2] @ c) ** 3) < 0


class PairReport(NamedTuple):
    """One row of the per-pair report: image ``i`` registered onto image ``j``."""

    i: int
    j: int
    matches: int
    inliers: int
    residual_rms: float
    accepted: bool
    reason: str


class MatchGraph(NamedTuple):
    """Who overlaps whom, and how every image reaches the reference.

    Attributes
    ----------
    pairs : dict[(i, j), PairRegistration]
        Every registered pair, i < j (H maps i to j).
    reference : int
        The image connected to most others.
    homographies : list of (3, 3) ndarray or None
        ``ref_from_k`` for each image k; None for images not connected to the reference.
    parent : list of int
        Each image's neighbour on its path to the reference (-1 for the reference and
        unconnected images).
    unconnected : list of int
        Images that no chain of accepted pairs links to the reference.
    """

    pairs: dict
    reference: int
    homographies: list
    parent: list
    unconnected: list

    def report(self) -> list[PairReport]:
        """One :class:`PairReport` per registered pair."""
        return [PairReport(i, j, len(p.matches.src), int(p.inliers.sum()), p.residual_rms, p.accepted, p.reason)
                for (i, j), p in sorted(self.pairs.items())]


def match_graph(features: Sequence[_feat.Features], *, ratio: float = 0.75, mutual: bool = False,
                threshold: float = 3.0, min_inliers: int = 15, rng: np.random.Generator | None = None,
                reference: int | None = None, approximate: bool = False, refine: bool = True,
                confidence: float = 0.999, max_iters: int = 2000) -> MatchGraph:
    r"""Register every pair, choose the reference image and chain homographies to it.

    1. Register each pair i < j (:func:`register_pair`).
    2. The reference is the image with the most accepted pairs (ties: the most inliers
       in them, then the lower index), unless ``reference`` is given.
    3. Grow a maximum spanning tree from the reference (Prim's algorithm, edges weighted
       by their inlier count: the strongest registrations first) and chain
       :math:`H_{r \leftarrow k} = H_{r \leftarrow p} H_{p \leftarrow k}` along it
       (:math:`H_{p \leftarrow k}` is the pair's H or its inverse).
    """
    feats = list(features)
    n = len(feats)
    if n < 2:
        raise CamlabInputError(f"features: expected the features of at least 2 images, got {n}")
    rng = np.random.default_rng(0) if rng is None else rng
    # FLANN: index each image's descriptors once (images 1..n-1 are searched), not once per pair
    index = [_feat.flann_index(f) if k and approximate and f.method == "sift" and len(f.points) >= 2 else None
             for k, f in enumerate(feats)]
    pairs = {}
    for i in range(n):
        for j in range(i + 1, n):
            knn = _feat.knn_match(feats[i], feats[j], backward=mutual, approximate=approximate, index2=index[j])
            pairs[(i, j)] = register_pair(feats[i], feats[j], ratio=ratio, mutual=mutual, threshold=threshold,
                                          min_inliers=min_inliers, rng=rng, refine=refine, confidence=confidence,
                                          max_iters=max_iters, matches=_feat.filter_matches(knn, ratio, mutual))
    degree = np.zeros(n, int)
    strength = np.zeros(n, int)
    for (i, j), p in pairs.items():
        if p.accepted:
            degree[[i, j]] += 1
            strength[[i, j]] += int(p.inliers.sum())
    if reference is None:
        ref = int(np.lexsort((np.arange(n), -strength, -degree))[0])
    else:
        if not 0 <= int(reference) < n:
            raise CamlabInputError(f"reference: expected an image index in [0, {n - 1}], got {reference!r}")
        ref = int(reference)
    Hs: list = [None] * n
    parent = [-1] * n
    Hs[ref] = np.eye(3)
    while True:  # Prim: attach the strongest accepted edge leaving the tree
        best = None
        for (i, j), p in pairs.items():
            if not p.accepted or (Hs[i] is None) == (Hs[j] is None):
                continue
            w = int(p.inliers.sum())
            if best is None or w > best[0]:
                best = (w, i, j, p)
        if best is None:
            break
        _, i, j, p = best
        if Hs[i] is not None:  # j joins: ref <- i <- j, H maps i to j so i <- j is H^-1
            Hs[j] = _hg.normalize_homography(Hs[i] @ np.linalg.inv(p.H))
            parent[j] = i
        else:
            Hs[i] = _hg.normalize_homography(Hs[j] @ p.H)
            parent[i] = j
    unconnected = [k for k in range(n) if Hs[k] is None]
    return MatchGraph(pairs, ref, Hs, parent, unconnected)


# --------------------------------------------------------------------------- projection

def cylindrical_warp(image: ArrayLike, K: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
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
    cyl : ndarray like ``image``
        The unrolled cylinder, same size, centred on the principal point.
    mask : (H, W) bool ndarray
        Where the cylinder sees the image.
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
    cyl = cv2.remap(src, map_u, map_v, cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    mask = (map_u >= -0.5) & (map_u <= w - 0.5) & (map_v >= -0.5) & (map_v <= h - 0.5)
    return cyl.reshape(img.shape).astype(img.dtype), mask


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
        raise CamlabInputError(f"shapes: expected one shape per homography, got {len(shapes)} for {len(homographies)}")
    pts = []
    for H, shape in zip(homographies, shapes):
        h, w = shape[:2]
        pts.append(map_points(np.asarray(H, dtype=float), [[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]]))
    allp = np.vstack(pts)
    if not np.all(np.isfinite(allp)):
        raise DegenerateError("canvas_box: a corner maps to infinity; the image crosses the horizon of its homography")
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
        for p, m, (r0, r1, c0, c1) in zip(parts, self.patch_masks, self.boxes):
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

    def subsampled(self, step: int) -> tuple[list, list]:
        """Every image and mask on the canvas grid ``[::step, ::step]`` (as ``images[k][::step, ::step]``,
        but with the patches' replicated border kept outside the masks), built from the boxes without
        the full canvas."""
        h, w = self.shape
        size = (-(-h // step), -(-w // step))
        imgs, masks = [], []
        for p, m, (r0, r1, c0, c1) in zip(self.patches, self.patch_masks, self.boxes):
            a, b = -(-r0 // step), -(-c0 // step)  # the first grid row and column in the box
            sp, sm = p[a * step - r0::step, b * step - c0::step], m[a * step - r0::step, b * step - c0::step]
            im = np.zeros(size + p.shape[2:], p.dtype)
            mk = np.zeros(size, bool)
            im[a:a + sp.shape[0], b:b + sp.shape[1]] = sp
            mk[a:a + sm.shape[0], b:b + sm.shape[1]] = sm
            imgs.append(im)
            masks.append(mk)
        return imgs, masks


def _image_box(H: np.ndarray, image_shape: Sequence[int], shape: tuple[int, int]) -> tuple[int, int, int, int]:
    """The canvas box (r0, r1, c0, c1) that can see image pixels through H (bilinear reach: one pixel beyond the edges)."""
    h, w = image_shape[:2]
    c = map_points(H, [[-1, -1], [w, -1], [w, h], [-1, h]])
    lo, hi = np.floor(c.min(axis=0)) - 1, np.ceil(c.max(axis=0)) + 2
    r0, c0 = int(min(max(lo[1], 0), shape[0])), int(min(max(lo[0], 0), shape[1]))
    return r0, max(r0, int(min(hi[1], shape[0]))), c0, max(c0, int(min(hi[0], shape[1])))


def warp_images(images: Sequence[np.ndarray], homographies: Sequence[np.ndarray], *,
                max_pixels: int = 40_000_000) -> WarpedImages:
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
        raise CamlabInputError(f"homographies: expected one per image, got {len(homographies)} for {len(images)} images")
    for k, im in enumerate(images):
        if np.ndim(im) != 3 or np.shape(im)[2] not in (1, 3):
            raise CamlabInputError(f"images[{k}]: expected an (h, w, 3) float32 image from prepare_images, "
                                   f"got shape {np.shape(im)}; call prepare_images(images) first")
    import cv2

    T, shape = canvas_bounds(list(homographies), [im.shape for im in images], max_pixels=max_pixels)
    out_i, out_m, out_w, out_h, boxes = [], [], [], [], []
    for im, H in zip(images, homographies):
        Hc = _hg.normalize_homography(T @ np.asarray(H, dtype=float))
        r0, r1, c0, c1 = _image_box(Hc, im.shape, shape)
        Hb = np.array([[1.0, 0, -c0], [0, 1, -r0], [0, 0, 1]]) @ Hc
        size = (r1 - r0, c1 - c0)
        # the image with a replicated border (no black edge for the blend's pyramids), its feather weight
        wimg = cv2.warpPerspective(np.asarray(im, np.float32), Hb, size[::-1], flags=cv2.INTER_LINEAR,
                                   borderMode=cv2.BORDER_REPLICATE).reshape(size + im.shape[2:])
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


def _over_channels(op, image: np.ndarray) -> np.ndarray:
    """``op`` (np.add, np.minimum, ...) folded over the channels of an (h, w, C) image, one channel at a
    time (the same as ``op.reduce(image, axis=2)``, which numpy runs about 10x slower for a short last axis)."""
    out = image[..., 0]
    for c in range(1, image.shape[2]):
        out = op(out, image[..., c])
    return out


def gain_compensation(warped: WarpedImages, sigma_n: float = 10.0 / 255, sigma_g: float = 1.0,
                      reference: int | None = None, megapixels: float | None = 0.1,
                      clip: tuple[float, float] = (2 / 255, 253 / 255)) -> np.ndarray:
    r"""One exposure gain per image so that overlapping regions agree (Brown & Lowe 2007, sec. 6).

    Minimises, over all overlapping pairs with :math:`N_{ij}` common pixels and mean
    intensities :math:`\bar I_{ij}` (image i on the overlap) and :math:`\bar I_{ji}`,

    .. math:: e = \tfrac12 \sum_{i,j} N_{ij} \left( (g_i \bar I_{ij} - g_j \bar I_{ji})^2 / \sigma_N^2
              + (1 - g_i)^2 / \sigma_g^2 \right).

    Setting :math:`\partial e / \partial g_i = 0` gives one linear equation per image,

    .. math:: g_i \sum_{j} N_{ij} \Big(\frac{2 \bar I_{ij}^2}{\sigma_N^2} + \frac{1}{\sigma_g^2}\Big)
              - \sum_j g_j N_{ij} \frac{2 \bar I_{ij} \bar I_{ji}}{\sigma_N^2} = \sum_j \frac{N_{ij}}{\sigma_g^2},

    solved directly (the prior keeps the gains near 1 and the system regular). The default
    :math:`\sigma_g = 1` is weaker than Brown & Lowe's 0.1: exposures in a hand-held set
    can differ by 30% or more, and a strong prior would leave part of that step. With
    ``reference`` given, all gains are divided by that image's gain (it keeps its look).

    Means are taken on a subsampled canvas of about ``megapixels`` (exposure is smooth; None:
    every pixel) and only over pixels that no image clips: a channel at or beyond ``clip``
    (black or saturated) has lost its true brightness, and an over-exposed white sky would
    otherwise pull the gain (and, scaled, turn grey or cyan).

    Returns
    -------
    (n,) ndarray
        Multiply image k by ``gains[k]``.
    """
    n = len(warped.patches)
    h, w = warped.shape
    step = 1 if megapixels is None else max(1, int(round(np.sqrt(h * w / (megapixels * 1e6)))))
    imgs, masks = warped.subsampled(step)
    lum = [_over_channels(np.add, im) / im.shape[2] for im in imgs]
    ok = [m & (_over_channels(np.minimum, im) > clip[0]) & (_over_channels(np.maximum, im) < clip[1])
          for m, im in zip(masks, imgs)]
    A = np.zeros((n, n))
    b = np.zeros(n)
    for i in range(n):
        for j in range(n):
            if i == j:
                continue
            both = ok[i] & ok[j]
            N = int(both.sum()) * step * step
            if N == 0:
                continue
            Iij, Iji = float(lum[i][both].mean()), float(lum[j][both].mean())
            # d e / d g_i from the (i, j) and (j, i) terms
            A[i, i] += N * (2 * Iij * Iij / sigma_n ** 2 + 1 / sigma_g ** 2)
            A[i, j] -= N * 2 * Iij * Iji / sigma_n ** 2
            b[i] += N / sigma_g ** 2
    for i in range(n):
        if A[i, i] == 0:  # no overlap: keep the gain at 1
            A[i, i], b[i] = 1.0, 1.0
    g = np.linalg.solve(A, b)
    if reference is not None:
        g = g / g[int(reference)]
    return g


# --------------------------------------------------------------------------- blending

def seam_masks(weights: Sequence[np.ndarray]) -> list[np.ndarray]:
    """Split the canvas between the images: each pixel goes to the image with the largest weight.

    With feather weights that is the image whose border is farthest (a Voronoi-like seam
    along the middle of each overlap).
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
    back = np.zeros((h, w), np.int64)
    cols = np.arange(w)
    for r in range(1, h):
        prev = np.stack([E[r - 1, :-2], E[r - 1, 1:-1], E[r - 1, 2:]])  # from c-1, c, c+1
        k = np.argmin(prev, axis=0)
        back[r] = k - 1
        E[r, 1:-1] = cost[r] + prev[k, cols]
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
    for k, (im, m) in enumerate(zip(imgs, masks)):
        placed = label >= 0
        ov = placed & m
        if ov.sum() > 2:
            rows, cols = np.flatnonzero(ov.any(axis=1)), np.flatnonzero(ov.any(axis=0))
            box = (slice(rows[0], rows[-1] + 1), slice(cols[0], cols[-1] + 1))
            a, b = comp[box], im[box]
            diff = _over_channels(np.add, np.abs(a - b))
            for ax in (0, 1):
                diff += _over_channels(np.add, np.abs(np.diff(a, axis=ax, prepend=0) - np.diff(b, axis=ax, prepend=0)))
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
            k_left = (pos[only_k].mean() if only_k.any() else np.inf) < (pos[only_a].mean() if only_a.any() else -np.inf)
            take = ov[box] & (left if k_left else ~left)
            label[box][take] = k
            comp[box][take] = b[take]
        fresh = m & ~placed
        label[fresh] = k
        comp[fresh] = im[fresh]
    # back to full resolution, box by box: each pixel takes its nearest coarse label
    near_r = np.minimum((np.arange(h) + step // 2) // step, label.shape[0] - 1)
    near_c = np.minimum((np.arange(w) + step // 2) // step, label.shape[1] - 1)
    out, covered = [], np.zeros((h, w), bool)
    for k, (m, (r0, r1, c0, c1)) in enumerate(zip(warped.patch_masks, warped.boxes)):
        own = (label[np.ix_(near_r[r0:r1], near_c[c0:c1])] == k) & m
        covered[r0:r1, c0:c1] |= own
        out.append(own)
    missed = np.zeros((h, w), bool)  # a thin rim: footprint pixels whose nearest coarse label is not theirs
    for m, (r0, r1, c0, c1) in zip(warped.patch_masks, warped.boxes):
        missed[r0:r1, c0:c1] |= m & ~covered[r0:r1, c0:c1]
    ys, xs = np.nonzero(missed)
    best_w, best_k = np.zeros(len(ys), np.float32), np.full(len(ys), -1)
    for k, (wk, (r0, r1, c0, c1)) in enumerate(zip(warped.patch_weights, warped.boxes)):  # the largest feather weight
        inside = np.flatnonzero((ys >= r0) & (ys < r1) & (xs >= c0) & (xs < c1))
        wv = wk[ys[inside] - r0, xs[inside] - c0]
        better = wv > best_w[inside]
        best_w[inside[better]], best_k[inside[better]] = wv[better], k
    for k, (r0, r1, c0, c1) in enumerate(warped.boxes):
        mine = best_k == k
        out[k][ys[mine] - r0, xs[mine] - c0] = True
    return out


def overlap_difference(warped: WarpedImages, i: int = 0, j: int = 1) -> float:
    """Mean absolute difference of images i and j where both cover the canvas (0 if they never overlap).

    After registration a rotation panorama differs only by noise and exposure here; parallax
    (a camera that moved in front of a 3-D scene) leaves misaligned objects: the ghosts
    blending will show. Same units as the images.
    """
    both = warped.masks[i] & warped.masks[j]
    if not both.any():
        return 0.0
    return float(np.abs(warped.images[i][both] - warped.images[j][both]).mean())


def seam_step(image: np.ndarray, seam: np.ndarray, overlap: np.ndarray, width: int = 4) -> float:
    """How visible a vertical seam is: the mean brightness step across it, in the image's units.

    For every row, the seam is where ``seam`` (one image's seam mask) switches on or off
    inside ``overlap``; the step is the mean luminance of the ``width`` pixels after it
    minus the ``width`` pixels before it. Texture averages out over the rows (its
    differences have both signs); an exposure jump does not. Returns the absolute mean
    step (0 for a perfect blend; the exposure difference times the brightness for
    overwrite), or 0.0 if there is no seam.
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
            steps.append(sign * (lum[r, c + 1:hi].mean() - lum[r, lo:c + 1].mean()))
    return float(abs(np.mean(steps))) if steps else 0.0


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
        own *= np.minimum(w * 4, 1)[..., None]  # trust the pixel's own (normalised) value where it has support
        filled += own  # up + t (own - up)
    # full resolution: the image itself inside the mask, the pulled-up fill outside
    up = cv2.pyrUp(filled, dstsize=(mask.shape[1], mask.shape[0])).reshape(img.shape)
    np.copyto(up, img, where=mask[..., None])
    return up


def _blend_inputs(images, masks) -> tuple[list, list]:
    """Images as finite (h, w, C) arrays and masks as (h, w) bool of the same size, or a clear error."""
    for value, name in ((images, "images"), (masks, "masks")):
        if value is None or isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
            raise CamlabInputError(f"{name}: expected a list with one array per image, got {type(value).__name__}")
    if len(images) != len(masks) or not len(images):
        raise CamlabInputError(f"masks: expected one mask per image, got {len(masks)} for {len(images)} images")
    imgs = [check_image(im, f"images[{k}]", channels=(1, 2, 3, 4)) for k, im in enumerate(images)]
    shape = imgs[0].shape[:2]
    out = []
    for k, (im, m) in enumerate(zip(imgs, masks)):
        mk = np.asarray(m)
        if mk.dtype != bool or mk.shape != shape or im.shape[:2] != shape or im.ndim != 3:
            raise CamlabInputError(f"masks[{k}]: expected a bool (h, w) mask of the (h, w, C) images' size {shape}, "
                                   f"got {mk.dtype} {mk.shape} for an image of shape {im.shape}")
        out.append(mk)
    return imgs, out


def laplacian_blend(images: Sequence[np.ndarray], masks: Sequence[np.ndarray], levels: int = 5,
                    footprints: Sequence[np.ndarray] | None = None) -> np.ndarray:
    r"""Multi-band blending (Burt & Adelson 1983) of images with disjoint seam masks.

    Each image's Laplacian pyramid :math:`L_k^{(l)} = G_k^{(l)} - \mathrm{up}(G_k^{(l+1)})`
    holds its detail at band l; each seam mask's Gaussian pyramid :math:`M_k^{(l)}` gets
    smoother at coarser levels. Blend band by band and collapse:

    .. math:: L^{(l)} = \frac{\sum_k M_k^{(l)} L_k^{(l)}}{\sum_k M_k^{(l)}}, \qquad
              I = L^{(0)} + \mathrm{up}(L^{(1)} + \mathrm{up}(\dots)).

    Coarse bands (exposure, shading) cross the seam over about :math:`2^l` pixels, fine
    detail over one or two: no visible seam, no ghost of misregistered detail. Pixels
    outside an image are first filled by push-pull so its pyramid does not see a black
    border. Pyramids use ``cv2.pyrDown``/``cv2.pyrUp`` (the 5-tap binomial filter).

    Parameters
    ----------
    images : sequence of (h, w, C) float32
    masks : sequence of (h, w) bool
        Disjoint seam masks (:func:`seam_masks`); the union is the panorama.
    levels : int
        Pyramid levels below the full resolution.
    footprints : sequence of (h, w) bool, optional
        Where each image has data (default: its seam mask); outside, it is extended by
        push-pull before its pyramid is built.
    """
    images, masks = _blend_inputs(images, masks)
    levels = check_integer(levels, "levels", minimum=1)
    feet = masks if footprints is None else footprints
    boxes = []
    for m, f in zip(masks, feet):  # each image's box: where it has data
        both = m | f
        rows, cols = np.flatnonzero(both.any(axis=1)), np.flatnonzero(both.any(axis=0))
        boxes.append((rows[0], rows[-1] + 1, cols[0], cols[-1] + 1) if len(rows) else (0, 0, 0, 0))
    return _multiband([im[r0:r1, c0:c1] for im, (r0, r1, c0, c1) in zip(images, boxes)],
                      [m[r0:r1, c0:c1] for m, (r0, r1, c0, c1) in zip(masks, boxes)],
                      [f[r0:r1, c0:c1] for f, (r0, r1, c0, c1) in zip(feet, boxes)], boxes, masks[0].shape, levels)


def _multiband(images: list, masks: list, feet: list, boxes: list, shape: tuple, levels: int, *,
               extended: bool = False) -> np.ndarray:
    """:func:`laplacian_blend` of images given in boxes of the canvas: ``images[k]``, ``masks[k]``
    (seam) and ``feet[k]`` (footprint) cover the canvas pixels ``boxes[k] = (r0, r1, c0, c1)``.

    Each image is extended beyond its footprint before its pyramid is built: by push-pull
    (:func:`_fill_outside`), or, if ``extended`` (the images already repeat their edge
    pixels outside the footprint, as :func:`warp_images` makes them), by repeating the
    box's border pixels, as OpenCV's multi-band blender does.
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
    for img, m, foot, (r0, r1, c0, c1) in zip(images, masks, feet, boxes):
        if not m.any():
            continue
        union[r0:r1, c0:c1] |= m
        # Work in the seam mask's bounding box (aligned to the coarsest grid, padded by the
        # filters' reach): outside it the blurred seam mask is zero, so nothing changes.
        rows, cols = np.flatnonzero(m.any(axis=1)) + r0, np.flatnonzero(m.any(axis=0)) + c0
        y0, x0 = max(0, (rows[0] - pad) // step * step), max(0, (cols[0] - pad) // step * step)
        y1, x1 = min(h, rows[-1] + 1 + pad), min(w, cols[-1] + 1 + pad)
        if y1 < h:
            y1 = min(h, y0 + -(-(y1 - y0) // step) * step)
        if x1 < w:
            x1 = min(w, x0 + -(-(x1 - x0) // step) * step)
        # the image's box placed in that aligned box (each may stick out of the other)
        mk0 = np.zeros((y1 - y0, x1 - x0), np.float32)
        ys, xs = slice(max(r0, y0) - y0, min(r1, y1) - y0), slice(max(c0, x0) - x0, min(c1, x1) - x0)
        ps, qs = slice(max(r0, y0) - r0, min(r1, y1) - r0), slice(max(c0, x0) - c0, min(c1, x1) - c0)
        mk0[ys, xs] = m[ps, qs]
        if extended:
            sub = cv2.copyMakeBorder(np.ascontiguousarray(img[ps, qs], np.float32), ys.start, y1 - y0 - ys.stop,
                                     xs.start, x1 - x0 - xs.stop, cv2.BORDER_REPLICATE).reshape(mk0.shape + (nch,))
            g = [sub]
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
        for lv in range(levels + 1):
            if lv < levels:  # band = g[lv] - up(g[lv + 1]), computed in place
                band = cv2.pyrUp(g[lv + 1], dstsize=(g[lv].shape[1], g[lv].shape[0])).reshape(g[lv].shape)
                np.subtract(g[lv], band, out=band)
            else:
                band = g[levels]
            band *= mk[lv][..., None]
            oy, ox = y0 >> lv, x0 >> lv
            hh, ww = mk[lv].shape
            acc[lv][oy:oy + hh, ox:ox + ww] += band
            wsum[lv][oy:oy + hh, ox:ox + ww] += mk[lv]
    for a, s in zip(acc, wsum):  # each band's weighted mean, in place
        np.divide(a, np.maximum(s, 1e-6)[..., None], out=a)
    out = acc[-1]
    for lv in range(levels - 1, -1, -1):
        out = cv2.pyrUp(out, dstsize=(acc[lv].shape[1], acc[lv].shape[0])).reshape(acc[lv].shape)
        out += acc[lv]
    np.clip(out, 0, 1, out=out)
    out[~union] = 0
    return out


def blend(warped: WarpedImages, method: str = "multiband", *, gains: ArrayLike | None = None,
          levels: int = 5, feather_power: float = 1.0, seam: str = "voronoi",
          seams: Sequence[np.ndarray] | None = None) -> np.ndarray:
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
    method : {"overwrite", "feather", "multiband"}
    gains : (n,) array_like, optional
        Exposure gains (:func:`gain_compensation`) applied first.
    levels : int
        Pyramid levels for ``"multiband"``.
    feather_power : float
        p above: larger values sharpen the transition towards a seam.
    seams : list of bool ndarray, optional
        Seam masks already found, in the images' boxes (:func:`dp_seam_masks`); ``seam`` is
        then not used.

    Every image is blended within its own box of the canvas (``warped.boxes``).

    Returns
    -------
    (h, w, 3) float32 ndarray in [0, 1]
    """
    if method not in BLENDS:
        raise CamlabInputError(f"method: expected one of {BLENDS}, got {method!r}")
    if seam not in ("voronoi", "dp"):
        raise CamlabInputError(f"seam: expected 'voronoi' or 'dp', got {seam!r}")
    imgs = warped.patches
    if gains is not None:
        g = np.asarray(gains, dtype=float).ravel()
        if g.shape != (len(imgs),):
            raise CamlabInputError(f"gains: expected {len(imgs)} gains (one per image), got shape {g.shape}")
        imgs = [np.minimum(im * np.float32(gk), np.float32(1)) for im, gk in zip(imgs, g)]  # im >= 0
    h, w = warped.shape
    boxes = warped.boxes
    if method == "overwrite":
        out = np.zeros((h, w, imgs[0].shape[2]), np.float32)
        for im, m, (r0, r1, c0, c1) in zip(imgs, warped.patch_masks, boxes):
            out[r0:r1, c0:c1][m] = im[m]
        return out
    if method == "feather":
        num = np.zeros((h, w, imgs[0].shape[2]), np.float32)
        den = np.zeros((h, w), np.float32)
        for im, wk, (r0, r1, c0, c1) in zip(imgs, warped.patch_weights, boxes):
            wp = wk ** np.float32(feather_power) if feather_power != 1 else wk
            num[r0:r1, c0:c1] += im * wp[..., None]
            den[r0:r1, c0:c1] += wp
        return np.where(den[..., None] > 0, num / np.maximum(den, 1e-12)[..., None], 0).astype(np.float32)
    if seams is None and seam == "dp":
        seams = dp_seam_masks(warped)
    elif seams is None:  # the Voronoi masks lie inside each image's footprint, so inside its box
        seams = [sk[r0:r1, c0:c1] for sk, (r0, r1, c0, c1) in zip(seam_masks(warped.weights), boxes)]
    return _multiband(imgs, seams, warped.patch_masks, boxes, warped.shape, check_integer(levels, "levels", minimum=1),
                      extended=True)


# --------------------------------------------------------------------------- the pipeline

from .pipeline import PROJECTION_CHOICES, StitchResult, largest_rectangle, stitch  # noqa: E402  (uses the stages above)
