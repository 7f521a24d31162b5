"""Stitching stages 1-3.

Prepare the images, register each pair (matches + RANSAC, Brown and Lowe's acceptance test) and
build the match graph that chains every image to the reference.

Also what :func:`camlab.stitching.stitch` checks on the way: a photo given twice
(:func:`repeated_photos`), features on a reduced copy (:func:`detect_at_resolution`), pairs
whose outliers follow a second plane (:func:`second_planes`).

See :mod:`camlab.stitching` for the whole pipeline.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .. import features as _feat
from .. import homography as _hg
from .._validate import CamlabInputError, DegenerateError

# --------------------------------------------------------------------------- input


def prepare_images(images: Sequence[ArrayLike]) -> list[np.ndarray]:
    """Validate ``images`` and return them as float32 RGB arrays in [0, 1].

    Grey (H, W) or (H, W, 1) images become RGB (the panorama is colour if any input is);
    an alpha channel is dropped. uint8 is divided by 255, uint16 by 65535, floats are
    taken as already in [0, 1]. Sizes may differ.

    Parameters
    ----------
    images : sequence of (H, W), (H, W, 1), (H, W, 3) or (H, W, 4) array_like
        At least two images, each at least 16 x 16 pixels; uint8, uint16 or float.

    Returns
    -------
    list of (H, W, 3) float32 ndarray
        The images, RGB in [0, 1] (floats are not clipped), contiguous.

    Raises
    ------
    CamlabInputError
        One array instead of a list, fewer than two images, a wrong shape, a side under 16
        pixels or another dtype.
    """
    if isinstance(images, np.ndarray) and images.ndim in (2, 3) and images.dtype != object:
        raise CamlabInputError(
            f"images: expected a list of images, got one array of shape {images.shape}; "
            f"pass [image1, image2, ...]"
        )
    imgs = list(images)
    if len(imgs) < 2:
        raise CamlabInputError(f"images: expected at least 2 images to stitch, got {len(imgs)}")
    out = []
    for i, im in enumerate(imgs):
        a = np.asarray(im)
        if (
            a.ndim not in (2, 3)
            or (a.ndim == 3 and a.shape[2] not in (1, 3, 4))
            or min(a.shape[:2]) < 16
        ):
            raise CamlabInputError(
                f"images[{i}]: expected a (H, W) grey or (H, W, 3|4) colour image at least "
                f"16 x 16 pixels, got shape {a.shape}"
            )
        if a.dtype == np.uint8:
            f = a.astype(np.float32) / 255
        elif a.dtype == np.uint16:
            f = a.astype(np.float32) / 65535
        elif np.issubdtype(a.dtype, np.floating):
            f = a.astype(np.float32)
        else:
            raise CamlabInputError(
                f"images[{i}]: expected uint8, uint16 or float pixels, got dtype {a.dtype}"
            )
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
    r"""The registration of image i onto image j.

    Attributes
    ----------
    H : (3, 3) ndarray or None
        Maps image i's pixels to image j's (None if RANSAC found nothing).
    matches : camlab.features.Matches
        The putative matches (after the ratio test); ``matches.src`` in image i.
    inliers : (M,) bool ndarray
        Matches consistent with H (all False if H is None).
    residual_rms : float
        RMS one-way transfer error :math:`\|x_j - \pi(H x_i)\|` of the inliers, pixels.
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


def register_pair(
    features1: _feat.Features,
    features2: _feat.Features,
    *,
    ratio: float = 0.75,
    mutual: bool = False,
    threshold: float = 3.0,
    min_inliers: int = 15,
    rng: np.random.Generator | None = None,
    matches: _feat.Matches | None = None,
    refine: bool = True,
    approximate: bool = False,
    confidence: float = 0.999,
    max_iters: int = 2000,
) -> PairRegistration:
    r"""Register image 1 onto image 2: match features, fit H by RANSAC, judge the result.

    The pair is accepted when RANSAC finds at least ``min_inliers`` inliers *and* more
    than :math:`8 + 0.3 n_m` of the :math:`n_m` matches (Brown & Lowe's test [1]_: the
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
        The two images' features.
    ratio, mutual
        See :func:`camlab.features.filter_matches`.
    threshold : float
        RANSAC inlier threshold (symmetric transfer error, pixels).
    min_inliers : int
        The fewest inliers (and matches) a pair needs.
    rng : np.random.Generator, optional
        RANSAC's randomness (default: seeded with 0, so results are reproducible).
    matches : camlab.features.Matches, optional
        Use these matches instead of matching (e.g. re-filtered ones from a slider).
    refine : bool
        Polish H on the inliers (needs at least 8) and recompute them; if that fails, the
        RANSAC result is kept.
    approximate : bool
        Match with FLANN instead of brute force (:func:`camlab.features.knn_match`).
    confidence, max_iters : float, int
        RANSAC's stopping rule (:func:`camlab.homography.ransac_homography`).

    Returns
    -------
    PairRegistration
        ``H`` (image 1 to image 2; None if RANSAC found nothing), ``matches``, ``inliers``,
        ``residual_rms`` (one-way transfer error of the inliers, pixels), ``accepted`` and
        the ``reason`` for a rejection.

    References
    ----------
    .. [1] M. Brown and D. G. Lowe, 2007, "Automatic panoramic image stitching using invariant
       features", *International Journal of Computer Vision* 74(1), 59-73, section 3.2 (probabilistic model for image match verification), eq. 13.
    .. [2] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022,
       section 8.3 (global alignment: recognising panoramas).
    """
    rng = np.random.default_rng(0) if rng is None else rng
    m = (
        _feat.match_features(features1, features2, ratio, mutual, approximate=approximate)
        if matches is None
        else matches
    )
    n = len(m.src)
    none = np.zeros(n, bool)
    if n < max(min_inliers, 5):
        return PairRegistration(
            None,
            m,
            none,
            float("nan"),
            False,
            f"too few matches: {n} (need at least {max(min_inliers, 5)})",
        )
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
    rms = (
        float(np.sqrt(np.mean(_hg.transfer_error(H, m.src[inl], m.dst[inl]) ** 2))) if k else np.nan
    )
    need = max(min_inliers, int(np.floor(8 + 0.3 * n)) + 1)
    if k < need:
        # A right model starved by a threshold below the features' localisation noise still has most matches
        # close to it (within a pixel or ten thresholds); a wrong one (no overlap, wrong matches) does not.
        near_px = max(1.0, 10 * threshold)
        near = int((_hg.symmetric_transfer_error(H, m.src, m.dst) < near_px).sum())
        cause = (
            f"the threshold {threshold:.3g} px is below the features' localisation noise: {near} matches lie "
            f"within {near_px:.3g} px of this H, so the model is likely right but starved of inliers; raise "
            "the threshold (1 to 3 px is usual)"
            if near >= need
            else "the images probably do not overlap, or most matches are wrong"
        )
        return PairRegistration(
            H, m, inl, rms, False, f"too few inliers: {k} of {n} matches (need {need}); {cause}"
        )
    if _mirrors(H, m.src[inl]):
        return PairRegistration(
            H,
            m,
            inl,
            rms,
            False,
            f"the homography mirrors the image ({k} inliers): a "
            "reflection, which no camera motion produces; wrong matches on a symmetric scene",
        )
    return PairRegistration(H, m, inl, rms, True, "")


def _mirrors(H: np.ndarray, points: np.ndarray) -> bool:
    r"""Whether H reverses orientation at the points' centroid x.

    The Jacobian of :math:`\pi(H x)` has determinant :math:`\det H / w^3` with :math:`w = (H \tilde
    x)_3`.
    """
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

    def groups(self) -> list[list[int]]:
        """The connected groups of images (linked by chains of accepted pairs), largest first.

        Two separate panoramas in one folder are two groups of two or more; a photo that
        overlaps nothing is a group of one.

        Returns
        -------
        list of list of int
            The image indices of each group, ascending; groups by size, largest first (ties:
            the lowest first index).
        """
        n = len(self.homographies)
        label = list(range(n))

        def root(k: int) -> int:
            while label[k] != k:
                k = label[k]
            return k

        for (i, j), p in self.pairs.items():
            if p.accepted:
                label[root(i)] = root(j)
        groups: dict = {}
        for k in range(n):
            groups.setdefault(root(k), []).append(k)
        return sorted(groups.values(), key=lambda g: (-len(g), g[0]))

    def report(self) -> list[PairReport]:
        """One :class:`PairReport` per registered pair.

        Returns
        -------
        list of PairReport
            (i, j, matches, inliers, residual_rms, accepted, reason), pairs in (i, j) order.
        """
        return [
            PairReport(
                i, j, len(p.matches.src), int(p.inliers.sum()), p.residual_rms, p.accepted, p.reason
            )
            for (i, j), p in sorted(self.pairs.items())
        ]


def match_graph(
    features: Sequence[_feat.Features],
    *,
    ratio: float = 0.75,
    mutual: bool = False,
    threshold: float = 3.0,
    min_inliers: int = 15,
    rng: np.random.Generator | None = None,
    reference: int | None = None,
    approximate: bool = False,
    refine: bool = True,
    confidence: float = 0.999,
    max_iters: int = 2000,
) -> MatchGraph:
    r"""Register every pair, choose the reference image and chain homographies to it.

    1. Register each pair i < j (:func:`register_pair`).
    2. The reference is the image with the most accepted pairs (ties: the most inliers
       in them, then the lower index), unless ``reference`` is given.
    3. Grow a maximum spanning tree from the reference (Prim's algorithm, edges weighted
       by their inlier count: the strongest registrations first) and chain
       :math:`H_{r \leftarrow k} = H_{r \leftarrow p} H_{p \leftarrow k}` along it
       (:math:`H_{p \leftarrow k}` is the pair's H or its inverse).

    Parameters
    ----------
    features : sequence of camlab.features.Features
        Every image's features (at least two).
    ratio, mutual, threshold, min_inliers, rng, refine, confidence, max_iters
        As for :func:`register_pair` (``rng`` default: seeded with 0).
    reference : int, optional
        Force the reference image.
    approximate : bool
        Match with FLANN (each image's index built once) instead of brute force.

    Returns
    -------
    MatchGraph
        ``pairs`` (every i < j), ``reference``, ``homographies`` (ref_from_k; None if not
        connected), ``parent`` and ``unconnected``.

    Raises
    ------
    CamlabInputError
        Fewer than two images' features, or a ``reference`` out of range.
    """
    feats = list(features)
    n = len(feats)
    if n < 2:
        raise CamlabInputError(f"features: expected the features of at least 2 images, got {n}")
    rng = np.random.default_rng(0) if rng is None else rng
    # FLANN: index each image's descriptors once (images 1..n-1 are searched), not once per pair
    index = [
        _feat.flann_index(f)
        if k and approximate and f.method == "sift" and len(f.points) >= 2
        else None
        for k, f in enumerate(feats)
    ]
    pairs = {}
    for i in range(n):
        for j in range(i + 1, n):
            knn = _feat.knn_match(
                feats[i], feats[j], backward=mutual, approximate=approximate, index2=index[j]
            )
            pairs[(i, j)] = register_pair(
                feats[i],
                feats[j],
                ratio=ratio,
                mutual=mutual,
                threshold=threshold,
                min_inliers=min_inliers,
                rng=rng,
                refine=refine,
                confidence=confidence,
                max_iters=max_iters,
                matches=_feat.filter_matches(knn, ratio, mutual),
            )
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
            raise CamlabInputError(
                f"reference: expected an image index in [0, {n - 1}], got {reference!r}"
            )
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
            Hs[j] = _hg.normalise_homography(Hs[i] @ np.linalg.inv(p.H))
            parent[j] = i
        else:
            Hs[i] = _hg.normalise_homography(Hs[j] @ p.H)
            parent[i] = j
    unconnected = [k for k in range(n) if Hs[k] is None]
    return MatchGraph(pairs, ref, Hs, parent, unconnected)


# --------------------------------------------------------------------------- checks for stitch


def repeated_photos(imgs: list) -> dict:
    """The images that repeat an earlier one: the same photo given twice.

    Compared on every 8th pixel: the same size and a mean absolute difference under 1/255.

    Parameters
    ----------
    imgs : list of ndarray
        The images, values in [0, 1] (:func:`prepare_images`).

    Returns
    -------
    dict of int to int
        {later: earlier}, each later image mapped to the first earlier one it repeats.
    """
    small = [im[::8, ::8] for im in imgs]
    out = {}
    for j in range(len(imgs)):
        for i in range(j):
            if (
                i not in out
                and small[i].shape == small[j].shape
                and float(np.abs(small[i] - small[j]).mean()) < 1 / 255
            ):
                out[j] = i
                break
    return out


def detect_at_resolution(
    im: np.ndarray, method: str, max_features: int, mask, megapixels: float | None
) -> _feat.Features:
    """Features of ``im`` found on a copy of at most ``megapixels``, positions in ``im``'s pixels.

    Resizing by s maps pixel centres u to s (u + 1/2) - 1/2, so back is (u' + 1/2)/s - 1/2.
    An image already within 5% of the size (s > 0.95) is used as it is.

    Parameters
    ----------
    im : (H, W[, C]) ndarray
        The image.
    method : {"sift", "orb"}
        The detector (:func:`camlab.features.detect_features`).
    max_features : int
        The most features kept.
    mask : (H, W) bool ndarray or None
        Where features may be found.
    megapixels : float or None
        The copy's largest size; None: full resolution.

    Returns
    -------
    camlab.features.Features
        The features, ``points`` in ``im``'s pixels and ``sizes`` scaled back likewise.
    """
    import cv2

    h, w = im.shape[:2]
    s = 1.0 if megapixels is None else min(1.0, float(np.sqrt(megapixels * 1e6 / (h * w))))
    if s > 0.95:
        return _feat.detect_features(im, method, max_features, mask=mask)
    size = (max(16, int(round(w * s))), max(16, int(round(h * s))))
    small = cv2.resize(im, size, interpolation=cv2.INTER_AREA)
    m = (
        None
        if mask is None
        else cv2.resize(mask.astype(np.uint8), size, interpolation=cv2.INTER_NEAREST) > 0
    )
    f = _feat.detect_features(small, method, max_features, mask=m)
    sx, sy = size[0] / w, size[1] / h
    pts = np.c_[(f.points[:, 0] + 0.5) / sx - 0.5, (f.points[:, 1] + 0.5) / sy - 0.5]
    return f._replace(points=pts, sizes=f.sizes / s)


class SecondPlane(NamedTuple):
    """An accepted pair whose outliers follow a second homography (:func:`second_planes`).

    Attributes
    ----------
    i, j : int
        The pair's images.
    matches : int
        How many of its matches follow the second plane.
    offset : float
        Their median transfer error under the pair's homography, pixels.
    """

    i: int
    j: int
    matches: int
    offset: float


def second_planes(graph: MatchGraph, rng: np.random.Generator | None) -> list[SecondPlane]:
    """Accepted pairs whose outliers follow a second homography: two planes, so the camera moved (parallax).

    A camera that only turns maps every scene point by one homography; if the matches that
    the first homography rejects agree on another one (at least 10 of them, and more than
    8 + 0.3 of the outliers, the Brown & Lowe test [1]_), the scene has depth and the centre
    moved.

    Parameters
    ----------
    graph : MatchGraph
        The registrations (:func:`match_graph`).
    rng : numpy.random.Generator or None
        RANSAC's randomness (None: seeded with 1).

    Returns
    -------
    list of SecondPlane
        One per accepted pair whose outliers follow a second homography: ``i``, ``j``,
        ``matches`` and ``offset`` (pixels).

    References
    ----------
    .. [1] M. Brown and D. G. Lowe, 2007, "Automatic panoramic image stitching using invariant
       features", *International Journal of Computer Vision* 74(1), 59-73, section 3.2.
    """
    rng = np.random.default_rng(1) if rng is None else rng
    found = []
    for (i, j), p in sorted(graph.pairs.items()):
        out = ~p.inliers
        n = int(out.sum())
        if not p.accepted or n < 10:
            continue
        try:
            r2 = _hg.ransac_homography(p.matches.src[out], p.matches.dst[out], 3.0, 0.99, 300, rng)
        except (DegenerateError, CamlabInputError):
            continue
        k2 = int(r2.inliers.sum())
        if k2 >= max(10, 8 + 0.3 * n):
            src, dst = p.matches.src[out][r2.inliers], p.matches.dst[out][r2.inliers]
            found.append(SecondPlane(i, j, k2, float(np.median(_hg.transfer_error(p.H, src, dst)))))
    return found
