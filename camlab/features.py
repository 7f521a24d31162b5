r"""Local features: detect, describe and match keypoints (OpenCV as the workhorse).

Stitching needs point pairs. They come from *local features*: a detector finds
distinctive, repeatable image locations (blob centres, corners) and a descriptor
summarises the patch around each one in a vector that barely changes with rotation,
scale and lighting. Two descriptors that are close probably show the same scene point.

* :func:`detect_features` runs SIFT (default: 128 floats from gradient histograms,
  scale and rotation invariant [1]_) or ORB (the fast option: 256-bit binary
  descriptors compared by Hamming distance) through OpenCV and returns a
  :class:`Features` with an (N, 2) array of pixel positions.
* :func:`knn_match` finds each descriptor's two nearest neighbours in the other image,
  once. :func:`filter_matches` then applies **Lowe's ratio test**: keep a match only if
  the best distance is clearly smaller than the second best,

  .. math:: d_1 < r \, d_2,

  because a repetitive or featureless patch has several near-equal candidates, and
  optionally the **mutual (cross) check**: keep i -> j only if j's best match is i.
  Splitting the two steps lets a slider re-filter without re-matching.
* :func:`match_features` does both and returns a :class:`Matches` with (M, 2) arrays
  ``src`` and ``dst`` ready for :func:`camlab.homography.ransac_homography`.

Pixel convention (docs/conventions.md): (u, v) = (column, row), origin at the centre of
the top-left pixel (OpenCV's keypoint convention). See lesson 09, section 2.

References
----------
.. [1] D. G. Lowe, 2004, "Distinctive image features from scale-invariant keypoints", *International
   Journal of Computer Vision* 60(2), 91-110 (SIFT and the ratio test, section 7.1).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._recent import RecentAnswers
from ._validate import CamlabInputError, check_image, check_integer, check_positive

__all__ = [
    "Features",
    "FlannIndex",
    "KnnMatches",
    "Matches",
    "detect_features",
    "filter_matches",
    "flann_index",
    "knn_match",
    "match_features",
    "to_gray_uint8",
]

_METHODS = ("sift", "orb")


class Features(NamedTuple):
    """Keypoints and descriptors of one image.

    Attributes
    ----------
    points : (N, 2) ndarray
        Keypoint positions (u, v) in pixels.
    descriptors : (N, D) ndarray
        float32 (SIFT, D = 128) or uint8 (ORB, D = 32 bytes = 256 bits).
    sizes : (N,) ndarray
        Keypoint diameters in pixels (the scale at which each was found).
    angles : (N,) ndarray
        Dominant orientations in degrees.
    responses : (N,) ndarray
        Detector strengths (larger = more distinctive).
    method : str
        ``"sift"`` or ``"orb"``.
    """

    points: np.ndarray
    descriptors: np.ndarray
    sizes: np.ndarray
    angles: np.ndarray
    responses: np.ndarray
    method: str


class KnnMatches(NamedTuple):
    """The two nearest neighbours in image 2 of every descriptor of image 1 (and back).

    ``nn12[i] = (j1, j2)``, ``d12[i] = (dist1, dist2)``; ``nn21[j]`` is the single nearest
    neighbour of descriptor j of image 2 in image 1 (for the mutual check; None if the
    backward pass was skipped).
    """

    nn12: np.ndarray
    d12: np.ndarray
    nn21: np.ndarray
    points1: np.ndarray
    points2: np.ndarray


class Matches(NamedTuple):
    """Putative correspondences, one row per match.

    Attributes
    ----------
    src, dst : (M, 2) ndarray
        Pixel positions in image 1 and image 2.
    idx1, idx2 : (M,) int ndarray
        Indices into the two :class:`Features`.
    distance : (M,) ndarray
        Descriptor distance of the match (L2 for SIFT, Hamming bits for ORB).
    ratio : (M,) ndarray
        Best over second-best distance (the score of the ratio test: smaller is better).
    """

    src: np.ndarray
    dst: np.ndarray
    idx1: np.ndarray
    idx2: np.ndarray
    distance: np.ndarray
    ratio: np.ndarray


def to_gray_uint8(image: ArrayLike, name: str = "image") -> np.ndarray:
    """An 8-bit grey copy of ``image`` for the detectors.

    ``image`` is (H, W) or (H, W, 3|4), uint8, uint16 or float in [0, 1]. Colour is converted with the Rec. 601 weights (0.299 R + 0.587 G + 0.114 B), images in
    RGB channel order as everywhere in camlab.

    Parameters
    ----------
    image : (H, W), (H, W, 3) or (H, W, 4) array_like
        uint8, uint16, or float in [0, 1]; RGB(A) channel order; at least 8 x 8 pixels.
    name : str, optional
        The argument's name in error messages.

    Returns
    -------
    (H, W) uint8 ndarray
        The grey image (floats scaled by 255, uint16 divided by 257, rounded).

    Examples
    --------
    >>> to_gray_uint8(np.full((8, 8, 3), 0.5))[0, :3].tolist()
    [128, 128, 128]
    """
    img = check_image(image, name)
    if min(img.shape[:2]) < 8:
        raise CamlabInputError(
            f"{name}: expected a (H, W) grey or (H, W, 3|4) colour image at least 8 x 8 pixels, got shape {img.shape}"
        )
    if img.dtype.kind == "f" and (img.min() < -1e-3 or img.max() > 1 + 1e-3):  # rounding slack
        raise CamlabInputError(
            f"{name}: a float image must hold values in [0, 1], got {img.min():.4g} to {img.max():.4g}; "
            f"divide 0..255 values by 255 (or pass them as uint8)"
        )
    if img.ndim == 3:
        img = (
            img[..., 0]
            if img.shape[2] == 1
            else img[..., :3].astype(float) @ np.array([299.0, 587.0, 114.0]) / 1000
        )
    if np.issubdtype(np.asarray(image).dtype, np.floating):
        img = np.asarray(img, dtype=float) * 255.0
    elif np.asarray(image).dtype == np.uint16:
        img = np.asarray(img, dtype=float) / 257.0
    elif np.asarray(image).dtype != np.uint8:
        raise CamlabInputError(
            f"{name}: expected uint8, uint16 or float pixels, got dtype {np.asarray(image).dtype}"
        )
    return np.clip(np.rint(img), 0, 255).astype(np.uint8)


def detect_features(
    image: ArrayLike,
    method: str = "sift",
    max_features: int = 2500,
    *,
    mask: ArrayLike | None = None,
    contrast_threshold: float = 0.02,
) -> Features:
    """Detect keypoints and compute descriptors with OpenCV (SIFT by default, ORB as the fast option).

    Parameters
    ----------
    image : (H, W) or (H, W, 3) array_like
        uint8, uint16 or float (in [0, 1]) image; colour is converted to grey.
    method : {"sift", "orb"}
    max_features : int
        Keep at most this many keypoints (the strongest).
    mask : (H, W) array_like of bool, optional
        Detect only where True.
    contrast_threshold : float
        SIFT's minimum contrast of a blob (OpenCV's default is 0.04; 0.02 finds about
        twice as many keypoints in low-contrast scenes, which makes homographies more
        accurate). Ignored by ORB.

    Returns
    -------
    Features
        ``points`` (N, 2) in pixels (u, v), ``descriptors``, ``sizes``, ``angles``, ``responses``.
        N may be 0 (a flat image has no features); matching then finds nothing.

    Notes
    -----
    The same image asked again (the same grey pixels, mask and settings) gets its earlier
    answer as a fresh copy, not a second detection: the last 32 are kept, by a hash of the
    pixels (:mod:`camlab._recent`). Lesson 09 stitches the same photos at several settings.
    """
    if method not in _METHODS:
        raise CamlabInputError(f"method: expected one of {_METHODS}, got {method!r}")
    max_features = check_integer(max_features, "max_features")
    gray = to_gray_uint8(image)
    m = None
    if mask is not None:
        mk = np.asarray(mask)
        if mk.shape != gray.shape:
            raise CamlabInputError(
                f"mask: expected shape {gray.shape} like the image, got {mk.shape}"
            )
        m = mk.astype(np.uint8) * 255
    threshold = float(contrast_threshold) if method == "sift" else None  # ORB ignores it
    found = _SEEN.get(
        [gray, m],
        (method, max_features, threshold),
        lambda: _detect(gray, m, method, max_features, threshold),
    )
    return Features(*(a.copy() if isinstance(a, np.ndarray) else a for a in found))


_SEEN: RecentAnswers[Features] = RecentAnswers(keep=32)
"""detect_features' recent answers, by the grey pixels, the mask and the settings."""


def _detect(
    gray: np.ndarray,
    mask: np.ndarray | None,
    method: str,
    max_features: int,
    threshold: float | None,
) -> Features:
    """detect_features on a checked grey image and mask (255 where to look, or None)."""
    import cv2

    if method == "sift":
        det = cv2.SIFT_create(nfeatures=int(max_features), contrastThreshold=threshold)
    else:
        det = cv2.ORB_create(nfeatures=int(max_features), fastThreshold=10)
    kps, desc = det.detectAndCompute(gray, mask)
    n = len(kps)
    dim, dtype = (128, np.float32) if method == "sift" else (32, np.uint8)
    if n == 0 or desc is None:
        z = np.zeros(0)
        return Features(np.zeros((0, 2)), np.zeros((0, dim), dtype), z, z.copy(), z.copy(), method)
    pts = np.array([k.pt for k in kps], dtype=float).reshape(-1, 2)
    return Features(
        pts,
        np.asarray(desc, dtype=dtype).reshape(n, dim),
        np.array([k.size for k in kps], float),
        np.array([k.angle for k in kps], float),
        np.array([k.response for k in kps], float),
        method,
    )


def _check_features(f, name: str) -> Features:
    if not isinstance(f, Features):
        raise CamlabInputError(
            f"{name}: expected camlab.features.Features from detect_features, got {type(f).__name__}"
        )
    return f


class FlannIndex(NamedTuple):
    """A FLANN search structure over one image's SIFT descriptors (:func:`flann_index`).

    It keeps the descriptors it indexes alive.
    """

    index: object
    descriptors: np.ndarray


def flann_index(features: Features) -> FlannIndex:
    """Index ``features``' SIFT descriptors once (FLANN, 4 randomised k-d trees), to search them from many images.

    :func:`knn_match` with ``index2=`` then skips building it per pair.

    FLANN draws the trees' random splits from OpenCV's global random generator, so the same
    descriptors would give a different index (and now and then different matches) depending
    on what ran before. The generator is seeded (``cv2.setRNGSeed(0)``, the state a fresh
    process starts in) before every build: the same features always give the same index.

    Parameters
    ----------
    features : Features
        SIFT features of one image (ORB is always matched by brute force).

    Returns
    -------
    FlannIndex
        ``index``, the OpenCV ``flann_Index``, and ``descriptors``, the float32 (N, 128) array it
        indexes (kept alive with it).

    References
    ----------
    .. [1] M. Muja and D. G. Lowe, 2009, "Fast approximate nearest neighbors with automatic
       algorithm configuration", *VISAPP*, 331-340.
    """
    import cv2

    f = _check_features(features, "features")
    if f.method != "sift":
        raise CamlabInputError(
            f"features: expected SIFT features (FLANN's k-d trees need float descriptors), "
            f"got {f.method}; ORB is always matched by brute force"
        )
    d = np.ascontiguousarray(f.descriptors, dtype=np.float32)
    cv2.setRNGSeed(0)
    return FlannIndex(cv2.flann_Index(d, {"algorithm": 1, "trees": 4}), d)


def _flann_knn(index: FlannIndex, queries: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
    """(n, k) indices and L2 distances of the k nearest indexed descriptors (32 leaf checks); inf where none found."""
    idx, d2 = index.index.knnSearch(
        np.ascontiguousarray(queries, dtype=np.float32), k, params={"checks": 32}
    )
    idx, d2 = np.asarray(idx, int).reshape(-1, k), np.asarray(d2, float).reshape(-1, k)
    missing = (idx < 0) | (idx >= len(index.descriptors))
    return np.where(missing, 0, idx), np.where(
        missing, np.inf, np.sqrt(np.maximum(d2, 0))
    )  # FLANN gives squared L2


def knn_match(
    features1: Features,
    features2: Features,
    backward: bool = True,
    *,
    approximate: bool = False,
    index2: FlannIndex | None = None,
) -> KnnMatches:
    """Find the two nearest descriptors in image 2 of each descriptor of image 1, and the reverse nearest.

    Brute force (every pair compared) with OpenCV's matcher: L2 distance for SIFT, Hamming
    for ORB. Done once; :func:`filter_matches` applies the ratio and mutual tests to the
    result as often as you like. ``backward=False`` skips the reverse pass (half the
    time) when no mutual check will be asked for. ``approximate=True`` searches SIFT
    descriptors with FLANN's randomised k-d trees (4 trees, 32 leaf checks: a few times
    faster than brute force for thousands of features, and it may miss a true nearest
    neighbour now and then; ORB always uses brute force); ``index2`` (:func:`flann_index`
    of ``features2``, made once and reused for every image matched against image 2)
    implies it.

    Parameters
    ----------
    features1, features2 : Features
        The two images' features, of one method (both SIFT or both ORB).
    backward : bool, optional
        Also find each descriptor of image 2's nearest neighbour in image 1 (for the mutual
        check; default True).
    approximate : bool, optional
        Search SIFT descriptors with FLANN instead of brute force (default False).
    index2 : FlannIndex, optional
        :func:`flann_index` of ``features2``, reused across calls; implies ``approximate``.

    Returns
    -------
    KnnMatches
        ``nn12`` (N1, 2) int, the indices of the two nearest descriptors in image 2; ``d12``
        (N1, 2), their distances (L2 for SIFT, Hamming bits for ORB); ``nn21`` (N2,) int, the
        nearest in image 1 of each descriptor of image 2 (None when the backward pass is skipped);
        ``points1`` (N1, 2) and ``points2`` (N2, 2), the keypoint positions in pixels.
    """
    import cv2

    f1 = _check_features(features1, "features1")
    f2 = _check_features(features2, "features2")
    if f1.method != f2.method:
        raise CamlabInputError(
            f"features2: expected {f1.method} features like features1, got {f2.method}"
        )
    n1, n2 = len(f1.points), len(f2.points)
    if n1 < 1 or n2 < 2:
        return KnnMatches(
            np.zeros((0, 2), int),
            np.zeros((0, 2)),
            np.full(n2, -1, dtype=int),
            f1.points,
            f2.points,
        )
    if f1.method == "sift" and (approximate or index2 is not None):
        nn12, d12 = _flann_knn(flann_index(f2) if index2 is None else index2, f1.descriptors, 2)
        nn21 = _flann_knn(flann_index(f1), f2.descriptors, 1)[0][:, 0] if backward else None
        return KnnMatches(nn12, d12, nn21, f1.points, f2.points)
    matcher = cv2.BFMatcher(cv2.NORM_L2 if f1.method == "sift" else cv2.NORM_HAMMING)
    knn = matcher.knnMatch(f1.descriptors, f2.descriptors, k=2)
    nn12 = np.array(
        [[m[min(t, len(m) - 1)].trainIdx if m else 0 for t in (0, 1)] for m in knn], dtype=int
    )
    d12 = np.array(
        [[m[t].distance if len(m) > t else np.inf for t in (0, 1)] for m in knn], dtype=float
    )
    nn12, d12 = nn12.reshape(-1, 2), d12.reshape(-1, 2)
    nn21 = None
    if backward:
        back = matcher.match(f2.descriptors, f1.descriptors)
        nn21 = np.full(n2, -1, dtype=int)
        nn21[[m.queryIdx for m in back]] = [m.trainIdx for m in back]
    return KnnMatches(nn12, d12, nn21, f1.points, f2.points)


def filter_matches(knn: KnnMatches, ratio: float = 0.75, mutual: bool = False) -> Matches:
    r"""Keep the matches of ``knn`` that pass Lowe's ratio test (and, optionally, the mutual check).

    A match i -> j1 survives if :math:`d_1 < r\, d_2` (its best distance is clearly better
    than the second best) and, with ``mutual=True``, if i is also j1's nearest neighbour.
    ``ratio = 1`` keeps every nearest neighbour (watch the wrong matches appear).

    Returns
    -------
    Matches
        Sorted by ratio (most distinctive first).

    Parameters
    ----------
    knn : KnnMatches
        The nearest neighbours from :func:`knn_match`.
    ratio : float, optional
        Ratio-test threshold r in (0, 1] (default 0.75; Lowe used 0.8).
    mutual : bool, optional
        Also keep only the matches that are each other's nearest neighbour (default False).

    References
    ----------
    .. [1] D. G. Lowe, 2004, "Distinctive image features from scale-invariant keypoints",
       *International Journal of Computer Vision* 60(2), 91-110, section 7.1 (the ratio test).

    Examples
    --------
    >>> pts = np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])
    >>> knn = KnnMatches(np.array([[0, 1], [1, 0], [2, 0]]), np.array([[1.0, 4.0], [3.0, 3.5], [0.5, 5.0]]),
    ...                  np.array([0, 1, 2]), pts, pts)
    >>> filter_matches(knn, 0.8).idx1.tolist()  # match 1 is ambiguous (3.0 vs 3.5)
    [2, 0]
    """
    if not isinstance(knn, KnnMatches):
        raise CamlabInputError(
            f"knn: expected camlab.features.KnnMatches from knn_match, got {type(knn).__name__}"
        )
    if not 0 < check_positive(ratio, "ratio") <= 1:
        raise CamlabInputError(
            f"ratio: expected a number in (0, 1] (Lowe used 0.8; 0.6-0.8 is typical), got {ratio!r}"
        )
    if len(knn.nn12) == 0:
        e = np.zeros(0)
        return Matches(
            np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0, int), np.zeros(0, int), e, e.copy()
        )
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(knn.d12[:, 1] > 0, knn.d12[:, 0] / knn.d12[:, 1], 1.0)
    keep = r < ratio if ratio < 1 else np.ones(len(r), bool)
    i1 = np.arange(len(knn.nn12))
    j1 = knn.nn12[:, 0]
    if mutual:
        if knn.nn21 is None:
            raise CamlabInputError("mutual: the mutual check needs knn_match(..., backward=True)")
        keep &= knn.nn21[j1] == i1
    order = np.argsort(r[keep], kind="stable")
    i1, j1 = i1[keep][order], j1[keep][order]
    return Matches(
        knn.points1[i1].copy(),
        knn.points2[j1].copy(),
        i1,
        j1,
        knn.d12[keep, 0][order],
        r[keep][order],
    )


def match_features(
    features1: Features,
    features2: Features,
    ratio: float = 0.75,
    mutual: bool = False,
    *,
    approximate: bool = False,
) -> Matches:
    """Match two images' features: nearest neighbours, ratio test, optional mutual check.

    ``filter_matches(knn_match(features1, features2, approximate=...), ratio, mutual)``; see both.

    Parameters
    ----------
    features1, features2 : Features
        The two images' features, of one method.
    ratio : float, optional
        Ratio-test threshold in (0, 1] (default 0.75).
    mutual : bool, optional
        Keep only mutual nearest neighbours (default False).
    approximate : bool, optional
        Search SIFT descriptors with FLANN (default False: brute force).

    Returns
    -------
    Matches
        ``src``, ``dst`` (M, 2) pixel positions in images 1 and 2, ``idx1``, ``idx2`` (M,) indices
        into the features, ``distance`` and ``ratio`` (M,), sorted by ratio (most distinctive
        first).

    References
    ----------
    .. [1] D. G. Lowe, 2004, "Distinctive image features from scale-invariant keypoints",
       *International Journal of Computer Vision* 60(2), 91-110, section 7.1 (the ratio test).
    """
    return filter_matches(
        knn_match(features1, features2, backward=mutual, approximate=approximate), ratio, mutual
    )
