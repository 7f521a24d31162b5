"""Stage 1: find a chessboard's inner corners in a photo, or say in plain words why not.

OpenCV finds the board (``cv2.findChessboardCorners``) and refines each corner
(``cv2.cornerSubPix``); camlab normalises the shapes of OpenCV 4 and 5 and explains
failures. Pixels (u, v) = (column, row), origin at the centre of the top-left pixel.
"""
from __future__ import annotations

from typing import NamedTuple, Sequence

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, check_positive


class ChessboardDetection(NamedTuple):
    """The outcome of :func:`find_chessboard`.

    ``found``; ``corners`` (N, 2) sub-pixel (u, v) in row-major order, first corner nearest
    the image's top-left, or None; ``reason`` a plain-language explanation when not found
    ("" when found); ``pattern_size`` (cols, rows) inner corners asked for.
    """

    found: bool
    corners: np.ndarray | None
    reason: str
    pattern_size: tuple[int, int]


def parse_pattern(pattern: str | Sequence[int]) -> tuple[int, int]:
    """``"9x6"`` or ``(9, 6)`` -> ``(9, 6)`` inner corners (columns, rows).

    >>> parse_pattern("9x6")
    (9, 6)
    """
    try:
        if isinstance(pattern, str):
            cols, rows = (int(p) for p in pattern.lower().replace("*", "x").split("x"))
        else:
            cols, rows = (int(p) for p in pattern)
    except (TypeError, ValueError):
        raise CamlabInputError(
            f"pattern_size: expected inner corners as (cols, rows) or 'COLSxROWS' like '9x6', got {pattern!r}"
        ) from None
    if cols < 2 or rows < 2:
        raise CamlabInputError(f"pattern_size: expected at least 2 x 2 inner corners, got {pattern!r}")
    return cols, rows


def board_points(pattern_size: Sequence[int] | str, square_size: float) -> np.ndarray:
    """The (N, 3) model points of a chessboard's inner corners in the board frame, metres.

    Row-major like OpenCV's corner order: ``(i * square, j * square, 0)`` for row j, column i,
    N = cols * rows.

    >>> board_points((3, 2), 0.5)
    array([[0. , 0. , 0. ],
           [0.5, 0. , 0. ],
           [1. , 0. , 0. ],
           [0. , 0.5, 0. ],
           [0.5, 0.5, 0. ],
           [1. , 0.5, 0. ]])
    """
    cols, rows = parse_pattern(pattern_size)
    s = check_positive(square_size, "square_size", "metres")
    j, i = np.divmod(np.arange(cols * rows), cols)
    return np.column_stack([i * s, j * s, np.zeros(cols * rows)])


def grey_uint8(image: ArrayLike, name: str = "image") -> np.ndarray:
    import cv2

    img = np.asarray(image)
    if img.ndim == 3 and img.shape[2] in (3, 4):
        img = cv2.cvtColor(img, cv2.COLOR_RGB2GRAY if img.shape[2] == 3 else cv2.COLOR_RGBA2GRAY)
    if img.ndim != 2 or img.size == 0:
        raise CamlabInputError(f"{name}: expected an (H, W) grey or (H, W, 3) colour image, got shape {img.shape}")
    if img.dtype != np.uint8:
        f = img.astype(float)
        if not np.isfinite(f).all():
            raise CamlabInputError(f"{name}: the image holds NaN or inf pixels")
        lo, hi = f.min(), f.max()
        img = np.zeros(f.shape, np.uint8) if hi <= lo else np.round(255 * (f - lo) / (hi - lo)).astype(np.uint8)
    return img


def _detect(img: np.ndarray, pattern: tuple[int, int]) -> np.ndarray | None:
    """OpenCV's classic detector + cornerSubPix, normalised to (N, 2) in a fixed order."""
    import cv2

    flags = cv2.CALIB_CB_ADAPTIVE_THRESH | cv2.CALIB_CB_NORMALIZE_IMAGE | cv2.CALIB_CB_FAST_CHECK
    ok, corners = cv2.findChessboardCorners(img, pattern, flags=flags)
    if not ok or corners is None:
        return None
    c = np.asarray(corners, dtype=np.float32).reshape(-1, 2)  # (N, 1, 2) in OpenCV 4, (N, 2) in 5
    spacing = np.min(np.linalg.norm(np.diff(c.reshape(pattern[1], pattern[0], 2), axis=1), axis=2))
    half = int(np.clip(0.4 * spacing, 2, 5))  # the search window must stay inside one square
    crit = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_COUNT, 50, 1e-4)
    c = cv2.cornerSubPix(img, c.reshape(-1, 1, 2), (half, half), (-1, -1), crit)
    c = np.asarray(c, dtype=float).reshape(-1, 2)
    if c[0].sum() > c[-1].sum():  # a fixed order: start at the corner nearer the image's top-left
        c = c[::-1].copy()
    return c


def _edge_width(img: np.ndarray) -> float:
    """Typical width in pixels of the strongest edges: intensity range / steepest gradients."""
    f = img.astype(np.float32)
    gy, gx = np.gradient(f)
    g = np.hypot(gx, gy)
    contrast = np.percentile(f, 99) - np.percentile(f, 1)
    steep = np.percentile(g, 99.7)
    return float(contrast / max(steep, 1e-6))


def find_chessboard(image: ArrayLike, pattern_size: Sequence[int] | str) -> ChessboardDetection:
    """Find a chessboard's inner corners with sub-pixel accuracy, or say why not.

    Parameters
    ----------
    image : (H, W) or (H, W, 3) array_like
        The photo; any dtype (non-uint8 images are stretched to 0..255).
    pattern_size : (cols, rows) or "COLSxROWS"
        *Inner* corners (where four squares meet): a board of 10 x 7 squares has 9 x 6.

    Returns
    -------
    ChessboardDetection
        ``corners`` (cols * rows, 2) pixels (u, v), row by row, starting at the end of the
        board nearer the image's top-left; ``reason`` explains a failure: no contrast,
        squares counted instead of inner corners, board cut off by the image border,
        partly hidden or the wrong size, too blurry.

    Notes
    -----
    ``cv2.findChessboardCorners`` finds the board and ``cv2.cornerSubPix`` refines each
    corner to the saddle point of the intensity (window at most 11 x 11 pixels, smaller
    for small boards). OpenCV 4 returns (N, 1, 2), OpenCV 5 (N, 2); both become (N, 2).
    """
    pattern = parse_pattern(pattern_size)
    img = grey_uint8(image)
    corners = _detect(img, pattern)
    if corners is not None:
        return ChessboardDetection(True, corners, "", pattern)
    return ChessboardDetection(False, None, _why_not_found(img, pattern), pattern)


def _why_not_found(img: np.ndarray, pattern: tuple[int, int]) -> str:
    cols, rows = pattern
    lo, hi = np.percentile(img, [1, 99])
    if hi - lo < 25:
        return (f"no chessboard found: the image has almost no contrast (grey levels {lo:.0f} to {hi:.0f}); "
                f"check exposure and that the board is in view")
    if cols > 2 and rows > 2 and _detect(img, (cols - 1, rows - 1)) is not None:
        return (f"wrong pattern size: a board with {cols - 1} x {rows - 1} inner corners was found; "
                f"pattern_size counts inner corners (where four squares meet), not squares: "
                f"use --pattern {cols - 1}x{rows - 1}")
    # OpenCV's "SB" detector with CALIB_CB_LARGER also reports partial boards
    import cv2

    h, w = img.shape
    ok, part, meta = cv2.findChessboardCornersSBWithMeta(img, (3, 3), cv2.CALIB_CB_LARGER)
    if ok and part is not None:
        part = np.asarray(part, dtype=float).reshape(-1, 2)
        spacing = np.median(np.linalg.norm(np.diff(part[:2], axis=0), axis=1))
        margin = min(part[:, 0].min(), part[:, 1].min(), w - 1 - part[:, 0].max(), h - 1 - part[:, 1].max())
        if len(part) < cols * rows and margin < 1.5 * spacing:  # fewer corners, and they reach the border
            return (f"board cut off: the chessboard runs into the image border, so not all {cols} x {rows} inner "
                    f"corners are visible; keep the whole board (with its white border) in view")
        return (f"a chessboard is visible but its {cols} x {rows} inner corners could not all be matched: check "
                f"--pattern (count inner corners, where four squares meet), glare and anything covering the board")
    width = _edge_width(img)
    if width > 4.0:
        return (f"no chessboard found: the image looks too blurry (edges about {width:.0f} px wide); "
                f"focus on the board and hold the camera still")
    return (f"no {cols} x {rows} chessboard found: check --pattern (inner corners, e.g. 9x6 for a board of "
            f"10 x 7 squares), that the whole board is visible with a white border, and that it is in focus")
