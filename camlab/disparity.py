r"""Disparity and depth from a rectified stereo pair (lesson 11).

In a rectified pair a world point appears on the same row of both images, at column
:math:`u_1` on the left and :math:`u_2 = u_1 - d` on the right. Finding the disparity
:math:`d \ge 0` of every left pixel is a 1-D search along the row; the depth follows from
similar triangles, :math:`Z = f B / d`.

* :func:`block_matching_disparity` is the teaching path, readable numpy: compare a small
  window around each left pixel with windows shifted by every candidate d in the right
  image (sum of absolute differences of the images minus their local window mean: a
  high-pass prefilter like OpenCV StereoBM's normalized-response one; not textbook ZSAD,
  which removes one mean per compared window), take the best d
  (winner-takes-all), refine it to sub-pixel precision with a parabola through the three
  costs around the minimum, and reject pixels whose match is ambiguous or fails the
  left-right consistency check.
* :func:`sgbm_disparity` is the workhorse: OpenCV's semi-global matching, which adds
  smoothness costs aggregated along 5 directions (OpenCV's single-pass ``MODE_SGBM``; the
  8 paths of Hirschmuller's paper need the two-pass ``MODE_HH`` and far more memory) and is
  far more robust on weak texture.

Conventions: images are (H, W) arrays indexed ``img[v, u]``; disparities are float
pixels with NaN where there is no reliable match; depth is in metres (the baseline's
unit) along the rectified optical axis. See docs/conventions.md.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._validate import CamlabInputError, as_float, check_image, check_integer, check_positive

__all__ = [
    "bad_pixel_rate",
    "block_matching_disparity",
    "CostCurve",
    "box_sum",
    "matching_cost",
    "disparity_to_depth",
    "disparity_to_points",
    "sgbm_disparity",
]


def _grey_pair(left: ArrayLike, right: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    out = []
    for img, name in ((left, "left"), (right, "right")):
        a = check_image(img, name, channels=(1, 3))
        if a.ndim == 3 and a.shape[2] == 3:
            a = a.mean(axis=2)
        if a.ndim != 2 or min(a.shape) < 3:
            raise CamlabInputError(
                f"{name}: expected an (H, W) grey or (H, W, 3) colour image, got shape {np.shape(img)}"
            )
        out.append(a.astype(np.float32))
    if out[0].shape != out[1].shape:
        raise CamlabInputError(
            f"left, right: expected images of the same size (a rectified pair), got {out[0].shape} "
            f"and {out[1].shape}"
        )
    return out[0], out[1]


def _check_search(max_disparity: int, block_size: int, width: int) -> tuple[int, int]:
    D, b = check_integer(max_disparity, "max_disparity"), check_integer(block_size, "block_size")
    if D < 1 or D >= width:
        raise CamlabInputError(
            f"max_disparity: expected an integer in [1, image width), got {max_disparity!r}"
        )
    if b < 1 or b % 2 == 0:
        raise CamlabInputError(
            f"block_size: expected an odd window size >= 1 (pixels), got {block_size!r}"
        )
    return D, b


def box_sum(a: np.ndarray, size: int) -> np.ndarray:
    r"""Sum of ``a`` over the ``size`` x ``size`` window centred on each pixel (zero outside).

    Running sums: with :math:`S(v) = \sum_{v' < v} a(v')` (a cumulative sum down the
    columns) every vertical window sum is one subtraction :math:`S(v + r + 1) - S(v - r)`,
    whatever the window size; then the same along the rows. ``a`` may be a stack
    (..., H, W) of images.

    Parameters
    ----------
    a : (..., H, W) ndarray
        An image or a stack of images.
    size : int
        Odd window side, pixels.

    Returns
    -------
    (..., H, W) float ndarray
        The window sums, zero padding outside the image.

    Examples
    --------
    >>> box_sum(np.ones((4, 4)), 3)
    array([[4., 6., 6., 4.],
           [6., 9., 9., 6.],
           [6., 9., 9., 6.],
           [4., 6., 6., 4.]])
    """
    r = size // 2
    out = np.asarray(a, dtype=np.float64)
    for axis in (-2, -1):
        x = np.moveaxis(out, axis, 0)
        n = x.shape[0]
        S = np.zeros((n + 2 * r + 1,) + x.shape[1:])
        np.cumsum(x, axis=0, out=S[r + 1 : n + r + 1])
        S[n + r + 1 :] = S[n + r]  # zero beyond the edge: the running sum stays flat
        out = np.moveaxis(S[size:] - S[:-size], 0, axis)
    return out


class CostCurve(NamedTuple):
    """One left pixel's matching cost against disparity (:func:`matching_cost`).

    ``disparities`` (D,) int, pixels; ``cost`` (D,) float, inf where the window would leave the
    right image.
    """

    disparities: np.ndarray
    cost: np.ndarray


def matching_cost(
    left: ArrayLike,
    right: ArrayLike,
    u: int,
    v: int,
    max_disparity: int = 64,
    block_size: int = 9,
    *,
    min_disparity: int = 0,
) -> CostCurve:
    r"""The cost curve of one left pixel: step 1 of :func:`block_matching_disparity`, alone.

    For each :math:`d` the sum over the ``block_size`` window around (u, v) of
    :math:`|\tilde L(v, u) - \tilde R(v, u - d)|`, the images minus their local window
    mean, as in the cost volume: the volume's column at (u, v), to draw the curve whose
    minimum, parabola and second minimum the matcher uses.

    Parameters
    ----------
    left, right : (H, W) or (H, W, 3) array_like
        A rectified pair, ``img[v, u]``.
    u, v : int
        The left pixel (column, row).
    max_disparity, min_disparity : int
        The search range, pixels.
    block_size : int
        Odd window size, pixels.

    Returns
    -------
    CostCurve
        ``disparities`` ``min_disparity`` ... ``max_disparity`` and their ``cost``; inf where
        the window would leave the right image.
    """
    L, R = _grey_pair(left, right)
    h, w = L.shape
    D, b = _check_search(max_disparity, block_size, w)
    if not (0 <= int(u) < w and 0 <= int(v) < h):
        raise CamlabInputError(
            f"u, v: expected a pixel inside the {w} x {h} image, got ({u!r}, {v!r})"
        )
    r, u, v = b // 2, int(u), int(v)
    # the window means need the images only r beyond the windows compared (the leftmost at the
    # largest d): cropped to that, one pixel's curve costs its neighbourhood, not the whole image
    r0, c0 = max(v - 2 * r, 0), max(u - D - 2 * r, 0)
    crop = (slice(r0, v + 2 * r + 1), slice(c0, u + 2 * r + 1 + max(-int(min_disparity), 0)))
    L, R = L[crop], R[crop]
    count = box_sum(np.ones(L.shape), b)
    Lz = L - box_sum(L, b) / count
    Rz = R - box_sum(R, b) / count
    rows = slice(max(v - r, 0) - r0, v + r + 1 - r0)
    cols = np.arange(max(u - r, 0), min(u + r + 1, w)) - c0
    ds = np.arange(int(min_disparity), D + 1)
    cost = np.full(len(ds), np.inf)
    for k, d in enumerate(ds):
        if u >= d + r:  # the whole window stays inside the right image
            cost[k] = np.abs(Lz[rows, cols] - Rz[rows, cols - d]).sum()
    return CostCurve(ds, cost)


def block_matching_disparity(
    left: ArrayLike,
    right: ArrayLike,
    max_disparity: int = 64,
    block_size: int = 9,
    *,
    min_disparity: int = 0,
    uniqueness: float = 0.05,
    lr_check: float = 1.0,
) -> np.ndarray:
    r"""Disparity of every left pixel by block matching along rows (readable numpy).

    1. **Cost volume.** For each candidate disparity :math:`d` (``min_disparity`` ...
       ``max_disparity``) the cost of left pixel (u, v) is the sum over a ``block_size``
       window of :math:`|\tilde L(v, u) - \tilde R(v, u - d)|`, where :math:`\tilde L, \tilde R`
       are the images minus their local window mean, each pixel minus the mean of the
       window around *it* (so a brightness difference between the cameras costs nothing).
       That is a high-pass prefilter, like OpenCV StereoBM's
       ``PREFILTER_NORMALIZED_RESPONSE`` without its clipping, followed by SAD; textbook
       ZSAD instead subtracts one mean per compared window, a close but different cost. Window sums come from :func:`box_sum`, so one
       disparity costs a few whole-image operations; stacking them gives the (D, H, W)
       cost volume (the "disparity space image"; 4 bytes per entry).
    2. **Winner takes all**: the d with the smallest cost, per pixel.
    3. **Sub-pixel**: a parabola through the costs at d - 1, d, d + 1 has its minimum at
       :math:`d + \frac{c_{-} - c_{+}}{2 (c_{-} - 2 c_0 + c_{+})}`.
    4. **Uniqueness**: reject pixels whose best cost is not at least ``uniqueness`` (a
       fraction) below the best cost more than 1 disparity away (repeated or no texture).
    5. **Left-right check**: the right image's own winners come from the same volume
       (right pixel u' at disparity d is left pixel u' + d); reject left pixels whose
       match points back more than ``lr_check`` pixels away (occlusions). ``lr_check <= 0``
       skips it.

    Parameters
    ----------
    left, right : (H, W) or (H, W, 3) array_like
        A rectified pair, ``img[v, u]``.
    max_disparity, min_disparity : int
        The search range, pixels.
    block_size : int
        Odd window size, pixels. Small windows keep edges sharp but are noisy; large
        windows are smooth but blur depth edges.
    uniqueness : float
        Step 4's margin, a fraction of the best cost (0 keeps every winner).
    lr_check : float
        Step 5's tolerance, pixels (<= 0 skips the check).

    Returns
    -------
    (H, W) float ndarray
        Disparity in pixels, NaN where rejected or where the window reaches past the
        left edge of the right image.

    References
    ----------
    .. [1] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022,
       sections 12.3-12.4 (dense correspondence, local methods).
    .. [2] D. Scharstein and R. Szeliski, 2002, "A taxonomy and evaluation of dense two-frame
       stereo correspondence algorithms", *International Journal of Computer Vision* 47, 7-42.
    """
    L, R = _grey_pair(left, right)
    h, w = L.shape
    D, b = _check_search(max_disparity, block_size, w)
    d0 = int(min_disparity)
    if not 0 <= d0 < D:
        raise CamlabInputError(
            f"min_disparity: expected an integer in [0, max_disparity), got {min_disparity!r}"
        )
    count = box_sum(np.ones((h, w)), b)  # pixels inside each window (fewer at the border)
    Lz = L - box_sum(L, b) / count
    Rz = R - box_sum(R, b) / count
    ds = np.arange(d0, D + 1)
    cost = np.empty((len(ds), h, w), dtype=np.float32)
    for k, d in enumerate(ds):  # 1. the cost volume, one disparity at a time
        diff = np.zeros((h, w), dtype=np.float32)
        diff[:, d:] = np.abs(Lz[:, d:] - Rz[:, : w - d])
        cost[k] = box_sum(diff, b)
        cost[k, :, : d + b // 2] = np.inf  # the window would leave the right image
    k = np.argmin(cost, axis=0)  # 2. winner takes all
    best = np.take_along_axis(cost, k[None], axis=0)[0]
    cm = np.take_along_axis(cost, np.clip(k - 1, 0, len(ds) - 1)[None], axis=0)[0]
    cp = np.take_along_axis(cost, np.clip(k + 1, 0, len(ds) - 1)[None], axis=0)[0]
    with np.errstate(invalid="ignore"):  # inf - inf at the image edge
        den = cm.astype(np.float64) - 2 * best + cp  # 3. sub-pixel parabola
    ok = (k > 0) & (k < len(ds) - 1) & np.isfinite(den) & (den > 0)
    off = np.zeros((h, w))
    off[ok] = (cm[ok] - cp[ok]) / (2 * den[ok])
    disp = ds[k] + np.clip(off, -0.5, 0.5)
    valid = np.isfinite(best)
    if uniqueness > 0:  # 4. the best cost more than one disparity away
        second = np.full((h, w), np.inf, dtype=np.float32)
        for j in range(len(ds)):
            far = np.abs(k - j) > 1
            np.minimum(second, np.where(far, cost[j], np.inf), out=second)
        valid &= np.isfinite(second) & (best < (1 - uniqueness) * second)
    if lr_check > 0:  # 5. left-right consistency
        best_r = np.full((h, w), np.inf, dtype=np.float32)
        kr = np.zeros((h, w), dtype=np.int64)
        for j, d in enumerate(ds):  # right pixel u' at disparity d is left pixel u' + d
            c = np.full((h, w), np.inf, dtype=np.float32)
            c[:, : w - d] = cost[j, :, d:]
            win = c < best_r
            best_r[win], kr[win] = c[win], j
        uu = np.arange(w)[None, :] - ds[k]
        back = ds[np.take_along_axis(kr, np.clip(uu, 0, w - 1), axis=1)]
        valid &= (uu >= 0) & (np.abs(back - ds[k]) <= lr_check)
    disp[~valid] = np.nan
    return disp


def sgbm_disparity(
    left: ArrayLike,
    right: ArrayLike,
    max_disparity: int = 64,
    block_size: int = 5,
    *,
    min_disparity: int = 0,
    uniqueness: int = 5,
) -> np.ndarray:
    """Disparity by OpenCV's semi-global block matching (``cv2.StereoSGBM``), float pixels, NaN = no match.

    ``max_disparity`` is rounded up to OpenCV's multiple of 16 (the search covers
    ``min_disparity`` ... ``min_disparity + numDisparities``); smoothness penalties
    ``P1 = 8 b^2``, ``P2 = 32 b^2`` as OpenCV's samples use. The mode is OpenCV's default
    ``STEREO_SGBM_MODE_SGBM``: one pass that aggregates the costs along 5 directions instead of
    8 (OpenCV's documentation of ``StereoSGBM``); Hirschmuller's full 8 (or 16) paths need the
    two-pass ``STEREO_SGBM_MODE_HH``, which stores the whole cost volume.

    Parameters
    ----------
    left, right : (H, W) or (H, W, 3) array_like
        A rectified pair, ``img[v, u]``.
    max_disparity : int, optional
        Largest disparity searched, pixels (rounded up as above).
    block_size : int, optional
        Odd matching window, pixels.
    min_disparity : int, optional
        Smallest disparity searched, pixels.
    uniqueness : int, optional
        OpenCV's ``uniquenessRatio``, a percentage margin of the best cost over the second.

    Returns
    -------
    (H, W) float ndarray
        Disparity in pixels (OpenCV's fixed point divided by 16), NaN where there is no match.

    References
    ----------
    .. [1] H. Hirschmuller, 2008, "Stereo processing by semiglobal matching and mutual
       information", *IEEE Transactions on Pattern Analysis and Machine Intelligence* 30(2),
       328-341.
    """
    import cv2

    L, R = _grey_pair(left, right)
    D, b = _check_search(max_disparity, block_size, L.shape[1])
    n = int(np.ceil((D - int(min_disparity)) / 16.0)) * 16
    sgbm = cv2.StereoSGBM_create(
        minDisparity=int(min_disparity),
        numDisparities=max(16, n),
        blockSize=b,
        P1=8 * b * b,
        P2=32 * b * b,
        uniquenessRatio=int(uniqueness),
        disp12MaxDiff=1,
        speckleWindowSize=0,
        mode=cv2.STEREO_SGBM_MODE_SGBM,
    )
    to8 = [
        np.clip(np.round(a if a.max() > 1.5 else a * 255), 0, 255).astype(np.uint8) for a in (L, R)
    ]
    raw = sgbm.compute(to8[0], to8[1]).astype(np.float64) / 16.0
    raw[raw < int(min_disparity)] = np.nan
    return raw


def bad_pixel_rate(disparity: ArrayLike, truth: ArrayLike, threshold: float = 1.0) -> float:
    r"""Fraction of the scored pixels whose disparity error exceeds ``threshold``: a stereo benchmark's score.

    A pixel is scored when it has both a match (``disparity`` finite) and a true disparity
    (``truth`` finite); it is *bad* when :math:`|d - d_{true}| > \tau`. Pixels without a match
    are left out (report the fraction matched beside it). Middlebury's SDK (``evaldisp``) divides
    instead by every pixel with a true disparity, reports the unmatched ones apart ("invalid")
    and adds them in "totbad": its "bad 1.0" is this rate times the fraction matched.

    Parameters
    ----------
    disparity : (H, W) array_like
        The matcher's disparity, pixels; NaN where it found no match.
    truth : (H, W) array_like
        The true disparity, pixels; NaN where unknown.
    threshold : float, optional
        The error, pixels, above which a pixel is bad (default 1).

    Returns
    -------
    float
        The bad fraction, in [0, 1]; NaN if no pixel is scored.

    Examples
    --------
    >>> bad_pixel_rate([[10.0, 12.5, np.nan]], [[10.2, 11.0, 9.0]], threshold=1.0)
    0.5
    """
    d, t = as_float(disparity, "disparity"), as_float(truth, "truth")
    if d.shape != t.shape:
        raise CamlabInputError(
            f"disparity, truth: expected maps of the same shape, got {d.shape} and {t.shape}"
        )
    scored = np.isfinite(d) & np.isfinite(t)
    if not scored.any():
        return float("nan")
    return float(np.mean(np.abs(d[scored] - t[scored]) > threshold))


def disparity_to_depth(disparity: ArrayLike, focal_length: float, baseline: float) -> np.ndarray:
    r"""Depth :math:`Z = f B / d` (metres) from disparity d (pixels) in a rectified pair.

    Similar triangles: a point at depth Z seen from two centres B apart along x projects
    to columns :math:`u_1 = f X / Z + c` and :math:`u_2 = f (X - B) / Z + c`, so
    :math:`d = u_1 - u_2 = f B / Z`. Non-positive or non-finite disparities (no match)
    give NaN. A disparity error :math:`\delta d` gives a depth error
    :math:`\delta Z \approx Z^2 \delta d / (f B)`: it grows with the square of the depth.

    Parameters
    ----------
    disparity : array_like
        Disparities d, pixels, any shape.
    focal_length : float
        Focal length f of the rectified cameras, pixels (> 0).
    baseline : float
        Distance B between the camera centres, metres (> 0).

    Returns
    -------
    float ndarray
        Depth Z, metres, the shape of ``disparity``; NaN where d <= 0 or is not finite.

    Examples
    --------
    >>> disparity_to_depth([40.0, 0.0], focal_length=800, baseline=0.1)
    array([ 2., nan])
    """
    d = as_float(disparity, "disparity")
    f = check_positive(focal_length, "focal_length", "pixels")
    B = check_positive(baseline, "baseline", "metres")
    ok = np.isfinite(d) & (d > 0)
    return np.where(ok, f * B / np.where(ok, d, 1.0), np.nan)


def disparity_to_points(
    disparity: ArrayLike, K: ArrayLike, baseline: float, step: int = 1
) -> np.ndarray:
    r"""3-D points (N, 3) in rectified camera 1's frame from a disparity map (NaN pixels skipped).

    :math:`Z = f B / d`, :math:`X = (u - c_x) Z / f`, :math:`Y = (v - c_y) Z / f`; the same
    as ``cv2.reprojectImageTo3D`` with the Q of :func:`camlab.rectification.rectify_calibrated`.
    ``step`` subsamples the map (every step-th row and column).

    Parameters
    ----------
    disparity : (H, W) array_like
        Disparity map, pixels (NaN: no match).
    K : (3, 3) array_like
        Intrinsics of the rectified camera 1, pixels.
    baseline : float
        Distance B between the camera centres, metres (> 0).
    step : int, optional
        Keep every step-th row and column (default 1).

    Returns
    -------
    (N, 3) ndarray
        Points (X, Y, Z) in rectified camera 1's frame, metres, one per finite depth, in row
        order.
    """
    from ._validate import check_matrix

    Km = check_matrix(K, (3, 3), "K")
    d = np.asarray(disparity, dtype=float)
    if d.ndim != 2:
        raise CamlabInputError(f"disparity: expected an (H, W) map, got shape {d.shape}")
    v, u = np.mgrid[0 : d.shape[0] : step, 0 : d.shape[1] : step]
    dd = d[::step, ::step]
    Z = disparity_to_depth(dd, Km[0, 0], baseline)
    ok = np.isfinite(Z)
    Z = Z[ok]
    return np.column_stack(
        [(u[ok] - Km[0, 2]) * Z / Km[0, 0], (v[ok] - Km[1, 2]) * Z / Km[1, 1], Z]
    )
