"""Stage 1: find a chessboard's inner corners in a photo, or say in plain words why not.

OpenCV finds the board and refines each corner; camlab normalises the shapes of OpenCV 4
and 5 and explains failures. A board that any of OpenCV's detectors finds is used: the
classic detector with its quick pre-check (``CALIB_CB_FAST_CHECK``, which rejects some
real photos), then without it, then the sector-based ``cv2.findChessboardCornersSB``.
Pixels (u, v) = (column, row), origin at the centre of the top-left pixel.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._recent import RecentAnswers
from .._validate import CamlabInputError, check_image, check_positive


class ChessboardDetection(NamedTuple):
    """The outcome of :func:`find_chessboard`.

    ``found``; ``corners`` (N, 2) sub-pixel (u, v) in row-major order, first corner nearest
    the image's top-left, or None; ``reason`` a plain-language explanation when not found
    ("" when found); ``pattern_size`` (cols, rows) inner corners asked for; ``detector``
    which detector found the board: "classic (fast check)", "classic" or "SB" ("" if none).
    """

    found: bool
    corners: np.ndarray | None
    reason: str
    pattern_size: tuple[int, int]
    detector: str = ""


class PatternSize(NamedTuple):
    """A chessboard's inner corners (OpenCV's ``patternSize``): ``cols`` across, ``rows`` down."""

    cols: int
    rows: int


def parse_pattern(pattern: str | Sequence[int], name: str = "pattern") -> PatternSize:
    """``"9x6"`` or ``(9, 6)`` -> ``(9, 6)`` inner corners (columns, rows); fractions are refused.

    Parameters
    ----------
    pattern : str or (2,) sequence of int
        ``"COLSxROWS"`` (``*`` also separates; case ignored) or (cols, rows).
    name : str
        The argument's name in error messages.

    Returns
    -------
    PatternSize
        ``cols``, ``rows``: whole numbers, each >= 2.

    Raises
    ------
    CamlabInputError
        Not two whole numbers, or fewer than 2 corners either way.

    Examples
    --------
    >>> parse_pattern("9x6")
    PatternSize(cols=9, rows=6)
    >>> parse_pattern((9.5, 6))
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: pattern: expected inner corners as whole numbers (cols, rows) or 'COLSxROWS' like '9x6', got (9.5, 6)
    """
    want = f"{name}: expected inner corners as whole numbers (cols, rows) or 'COLSxROWS' like '9x6', got {pattern!r}"
    try:
        parts = (
            pattern.lower().replace("*", "x").split("x")
            if isinstance(pattern, str)
            else list(pattern)
        )
        if len(parts) != 2 or any(isinstance(p, bool) for p in parts):
            raise ValueError
        vals = [float(p) for p in parts]
    except (TypeError, ValueError):
        raise CamlabInputError(want) from None
    if not all(np.isfinite(v) and v == int(v) for v in vals):
        raise CamlabInputError(want)
    cols, rows = int(vals[0]), int(vals[1])
    if cols < 2 or rows < 2:
        raise CamlabInputError(f"{name}: expected at least 2 x 2 inner corners, got {pattern!r}")
    return PatternSize(cols, rows)


def board_points(pattern_size: Sequence[int] | str, square_size: float) -> np.ndarray:
    """The (N, 3) model points of a chessboard's inner corners in the board frame, metres.

    Row-major like OpenCV's corner order: ``(i * square, j * square, 0)`` for row j, column i,
    N = cols * rows.

    Parameters
    ----------
    pattern_size : str or (2,) sequence of int
        Inner corners (cols, rows) or ``"COLSxROWS"`` (:func:`parse_pattern`).
    square_size : float
        The side of one square, metres (> 0).

    Returns
    -------
    (N, 3) ndarray
        The corners, metres, Z = 0.

    Raises
    ------
    CamlabInputError
        A bad pattern or a non-positive ``square_size``.

    Examples
    --------
    >>> board_points((3, 2), 0.5)
    array([[0. , 0. , 0. ],
           [0.5, 0. , 0. ],
           [1. , 0. , 0. ],
           [0. , 0.5, 0. ],
           [0.5, 0.5, 0. ],
           [1. , 0.5, 0. ]])
    """
    cols, rows = parse_pattern(pattern_size, "pattern_size")
    s = check_positive(square_size, "square_size", "metres")
    j, i = np.divmod(np.arange(cols * rows), cols)
    return np.column_stack([i * s, j * s, np.zeros(cols * rows)])


def grey_uint8(image: ArrayLike, name: str = "image") -> np.ndarray:
    """The (H, W) uint8 grey image OpenCV's detectors want, from a grey, RGB or RGBA image of any dtype.

    Non-uint8 images are first stretched to 0..255 (all channels together), then colour is
    converted to grey: ``cv2.cvtColor`` accepts only 8-bit, 16-bit and float32 input, so
    converting a float64 RGB image first would fail.

    Parameters
    ----------
    image : (H, W), (H, W, 1), (H, W, 3) or (H, W, 4) array_like
        Grey, RGB or RGBA, any dtype.
    name : str
        The argument's name in error messages.

    Returns
    -------
    (H, W) ndarray of uint8
        The grey image (a constant non-uint8 image gives zeros).

    Raises
    ------
    CamlabInputError
        Not an image of 1, 3 or 4 channels, non-finite pixels, or an empty image.
    """
    import cv2

    img = check_image(image, name, channels=(1, 3, 4))
    if img.ndim == 3 and img.shape[2] == 1:
        img = img[..., 0]
    if img.dtype != np.uint8:
        f = img.astype(float)
        if not np.isfinite(f).all():
            raise CamlabInputError(f"{name}: the image holds NaN or inf pixels")
        lo, hi = f.min(), f.max()
        img = (
            np.zeros(f.shape, np.uint8)
            if hi <= lo
            else np.round(255 * (f - lo) / (hi - lo)).astype(np.uint8)
        )
    if img.ndim == 3 and img.shape[2] in (3, 4):
        img = cv2.cvtColor(img, cv2.COLOR_RGB2GRAY if img.shape[2] == 3 else cv2.COLOR_RGBA2GRAY)
    if img.ndim != 2 or img.size == 0:
        raise CamlabInputError(
            f"{name}: expected an (H, W) grey or (H, W, 3) colour image, got shape {img.shape}"
        )
    return img


def _detect(
    img: np.ndarray, pattern: tuple[int, int], thorough: bool = True
) -> tuple[np.ndarray | None, str]:
    """OpenCV's detectors in turn, normalised to (N, 2) in a fixed order; returns (corners, detector).

    1. The classic detector with ``CALIB_CB_FAST_CHECK`` (quick on images without a board);
    2. without the fast check, which rejects some real photos with a board (``thorough``);
    3. ``findChessboardCornersSB``, sector based, robust to blur and uneven light (``thorough``).
    Corners of the classic detector are refined by ``cornerSubPix``; SB's are sub-pixel already.
    """
    import cv2

    base = cv2.CALIB_CB_ADAPTIVE_THRESH | cv2.CALIB_CB_NORMALIZE_IMAGE
    for flags, label in [
        (base | cv2.CALIB_CB_FAST_CHECK, "classic (fast check)"),
        (base, "classic"),
    ][: 2 if thorough else 1]:
        ok, corners = cv2.findChessboardCorners(img, pattern, flags=flags)
        if ok and corners is not None:
            return _fixed_order(_subpixel(img, corners, pattern)), label
    if thorough:
        ok, corners = cv2.findChessboardCornersSB(
            img,
            pattern,
            flags=cv2.CALIB_CB_NORMALIZE_IMAGE | cv2.CALIB_CB_EXHAUSTIVE | cv2.CALIB_CB_ACCURACY,
        )
        if ok and corners is not None:
            return _fixed_order(np.asarray(corners, dtype=float).reshape(-1, 2)), "SB"
    return None, ""


def _fixed_order(c: np.ndarray) -> np.ndarray:
    """Start at the corner nearer the image's top-left (detectors may return either end first)."""
    return c[::-1].copy() if c[0].sum() > c[-1].sum() else c


def _subpixel(
    img: np.ndarray, corners: np.ndarray, pattern: tuple[int, int], max_half: int = 5
) -> np.ndarray:
    import cv2

    c = np.asarray(corners, dtype=np.float32).reshape(-1, 2)  # (N, 1, 2) in OpenCV 4, (N, 2) in 5
    spacing = np.min(np.linalg.norm(np.diff(c.reshape(pattern[1], pattern[0], 2), axis=1), axis=2))
    half = int(np.clip(0.4 * spacing, 2, max_half))  # the search window must stay inside one square
    crit = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_COUNT, 50, 1e-4)
    c = cv2.cornerSubPix(img, c.reshape(-1, 1, 2), (half, half), (-1, -1), crit)
    return np.asarray(c, dtype=float).reshape(-1, 2)


def _work_copy(img: np.ndarray, max_side: int | None) -> tuple[np.ndarray, float, float]:
    """``img`` shrunk (area averaging) so its longest side is at most ``max_side``, and the x, y scales."""
    import cv2

    h, w = img.shape
    s = 1.0 if max_side is None else min(1.0, max_side / max(h, w))
    if s == 1.0:
        return img, 1.0, 1.0
    size = (max(1, round(w * s)), max(1, round(h * s)))
    return cv2.resize(img, size, interpolation=cv2.INTER_AREA), size[0] / w, size[1] / h


def _edge_width(img: np.ndarray) -> float:
    """Typical width in pixels of the strongest edges: intensity range / steepest gradients."""
    f = img.astype(np.float32)
    gy, gx = np.gradient(f)
    g = np.hypot(gx, gy)
    contrast = np.percentile(f, 99) - np.percentile(f, 1)
    steep = np.percentile(g, 99.7)
    return float(contrast / max(steep, 1e-6))


def find_chessboard(
    image: ArrayLike, pattern_size: Sequence[int] | str, max_side: int | None = 1600
) -> ChessboardDetection:
    """Find a chessboard's inner corners with sub-pixel accuracy, or say why not.

    Parameters
    ----------
    image : (H, W) or (H, W, 3) array_like
        The photo; any dtype (non-uint8 images are stretched to 0..255).
    pattern_size : (cols, rows) or "COLSxROWS"
        *Inner* corners (where four squares meet): a board of 10 x 7 squares has 9 x 6.
    max_side : int or None
        Look for the board on a copy whose longest side is at most this many pixels, then
        refine the corners on the full image. A phone's 40-megapixel photo is searched in
        seconds instead of minutes, and found more often (OpenCV's detector is tuned for
        squares tens of pixels wide, not hundreds). None: search the full image.

    Returns
    -------
    ChessboardDetection
        ``corners`` (cols * rows, 2) pixels (u, v) of the full image, row by row, starting
        at the end of the board nearer the image's top-left; ``reason`` explains a
        failure: no contrast, squares counted instead of inner corners, board cut off by the
        image border, partly hidden or the wrong size, too blurry.

    Notes
    -----
    ``cv2.findChessboardCorners`` finds the board (with its fast pre-check, then without
    it) and ``cv2.cornerSubPix`` refines each corner to the saddle point of the intensity
    (window at most 11 x 11 pixels, smaller for small boards); if both fail,
    ``cv2.findChessboardCornersSB`` tries (``detector`` says which one found it). OpenCV 4
    returns (N, 1, 2), OpenCV 5 (N, 2); both become (N, 2). On a shrunk copy (scales
    :math:`s_x, s_y`) a corner at :math:`u'` is at :math:`(u' + 1/2)/s_x - 1/2` in the full
    image (pixel centres), where ``cornerSubPix`` refines it again with a window
    :math:`1/s` times larger.

    The same photo asked again (the same grey pixels, pattern and ``max_side``) gets its
    earlier answer, not a second detection (the last 64 are kept, by a hash of the pixels):
    the lessons and ``camlab calibrate`` often look at the same photos more than once.
    """
    pattern = parse_pattern(pattern_size, "pattern_size")
    img = grey_uint8(image)
    if max_side is not None:
        max_side = int(check_positive(max_side, "max_side", "pixels"))
    found = _SEEN.get([img], (pattern, max_side), lambda: _find(img, pattern, max_side))
    return found._replace(corners=None if found.corners is None else found.corners.copy())


_SEEN: RecentAnswers[ChessboardDetection] = RecentAnswers(keep=64)
"""find_chessboard's recent answers, by the grey image's pixels, pattern and max_side."""


def _find(img: np.ndarray, pattern: PatternSize, max_side: int | None) -> ChessboardDetection:
    """find_chessboard on a checked grey image: detect on the work copy, refine on the full image."""
    small, sx, sy = _work_copy(img, max_side)
    corners, detector = _detect(small, pattern)
    if corners is None:
        return ChessboardDetection(False, None, _why_not_found(small, pattern), pattern)
    if small is not img:
        full = np.c_[(corners[:, 0] + 0.5) / sx - 0.5, (corners[:, 1] + 0.5) / sy - 0.5]
        corners = _subpixel(img, full, pattern, max_half=int(np.ceil(5 / min(sx, sy))))
    return ChessboardDetection(True, corners, "", pattern, detector)


def _why_not_found(img: np.ndarray, pattern: tuple[int, int]) -> str:
    cols, rows = pattern
    lo, hi = np.percentile(img, [1, 99])
    if hi - lo < 25:
        return (
            f"no chessboard found: the image has almost no contrast (grey levels {lo:.0f} to {hi:.0f}); "
            f"check exposure and that the board is in view"
        )
    if cols > 2 and rows > 2 and _detect(img, (cols - 1, rows - 1), thorough=False)[0] is not None:
        return (
            f"wrong pattern size: a board with {cols - 1} x {rows - 1} inner corners was found; "
            f"pattern_size counts inner corners (where four squares meet), not squares: "
            f"use pattern_size ({cols - 1}, {rows - 1}) (on the command line, --pattern {cols - 1}x{rows - 1})"
        )
    # OpenCV's "SB" detector with CALIB_CB_LARGER also reports partial boards
    import cv2

    h, w = img.shape
    ok, part, meta = cv2.findChessboardCornersSBWithMeta(img, (3, 3), cv2.CALIB_CB_LARGER)
    if ok and part is not None:
        part = np.asarray(part, dtype=float).reshape(-1, 2)
        spacing = np.median(np.linalg.norm(np.diff(part[:2], axis=0), axis=1))
        margin = min(
            part[:, 0].min(), part[:, 1].min(), w - 1 - part[:, 0].max(), h - 1 - part[:, 1].max()
        )
    # A few squares of a grid (windows, tiles) are not a board: only a good part of one counts.
    if ok and part is not None and len(part) >= 0.3 * cols * rows:
        if (
            len(part) < cols * rows and margin < 1.5 * spacing
        ):  # fewer corners, and they reach the border
            return (
                f"board cut off: the chessboard runs into the image border, so not all {cols} x {rows} inner "
                f"corners are visible; keep the whole board (with its white border) in view"
            )
        return (
            f"a chessboard is visible but its {cols} x {rows} inner corners could not all be matched: check "
            f"the pattern size (pattern_size, or --pattern on the command line: count inner corners, where four "
            f"squares meet), glare and anything covering the board"
        )
    width = _edge_width(img)
    if width > 4.0:
        return (
            f"no chessboard found: the image looks too blurry (edges about {width:.0f} px wide); "
            f"focus on the board and hold the camera still"
        )
    return (
        f"no {cols} x {rows} chessboard found: check the pattern size, in inner corners (pattern_size (9, 6), "
        f"or --pattern 9x6 on the command line, for a board of 10 x 7 squares), that the whole board "
        f"is visible with a white border, and that it is in focus"
    )
