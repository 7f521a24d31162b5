"""Drawing helpers for features, matches and panoramas (lesson 09).

Images are shown pixel-exact: pixel (u, v) has its centre at data coordinates (u, v)
(docs/conventions.md). Helpers return the artists they create so demos can move them.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from . import palette

__all__ = [
    "VIEW_COLOURS",
    "SideBySide",
    "Thinned",
    "draw_keypoints",
    "draw_matches",
    "match_segments",
    "outline",
    "side_by_side",
    "thin_matches",
]


VIEW_COLOURS = (
    palette.BLUE,
    palette.ORANGE,
    palette.PURPLE,
    palette.BROWN,
    palette.MAGENTA,
    palette.TAB_CYAN,
)
"""Lesson 09's one colour per image or view (0, 1, 2, ...). Green and red are kept out: in this lesson they
mean a right and a wrong match (inlier, outlier); yellow marks keypoints and zoom windows."""


class SideBySide(NamedTuple):
    """Two images on one canvas (:func:`side_by_side`).

    Attributes
    ----------
    canvas : (H, W, 3) ndarray
        Image 1, a white gap, image 2.
    offset : float
        Image 2's u offset on the canvas, pixels (add it to image 2's u coordinates).
    """

    canvas: np.ndarray
    offset: float


def side_by_side(image1: np.ndarray, image2: np.ndarray, gap: int = 8) -> SideBySide:
    """Two images next to each other on one canvas (white gap); returns it and image 2's u offset.

    Grey images are repeated to RGB; the canvas is as tall as the taller image, white below the
    shorter one.

    Parameters
    ----------
    image1, image2 : (H, W) or (H, W, 3) ndarray
        The images, uint8 or float in [0, 1] (image 2 is cast to image 1's dtype).
    gap : int
        Width of the white gap, pixels.

    Returns
    -------
    SideBySide
        ``canvas`` (H, W1 + gap + W2, 3) and ``offset`` = W1 + gap, image 2's u offset (px).
    """
    a, b = np.asarray(image1), np.asarray(image2)
    if a.ndim == 2:
        a = np.repeat(a[..., None], 3, axis=2)
    if b.ndim == 2:
        b = np.repeat(b[..., None], 3, axis=2)
    h = max(a.shape[0], b.shape[0])
    fill = 255 if a.dtype == np.uint8 else 1.0
    out = np.full((h, a.shape[1] + gap + b.shape[1], 3), fill, dtype=a.dtype)
    out[: a.shape[0], : a.shape[1]] = a
    out[: b.shape[0], a.shape[1] + gap :] = b.astype(a.dtype)
    return SideBySide(out, float(a.shape[1] + gap))


def match_segments(src: np.ndarray, dst: np.ndarray, offset: float) -> np.ndarray:
    """(M, 2, 2) line segments from ``src`` (image 1) to ``dst`` shifted right by ``offset`` (image 2).

    Parameters
    ----------
    src, dst : (M, 2) ndarray
        Matched points (u, v) in image 1 and image 2, pixels.
    offset : float
        Image 2's u offset on the canvas (:func:`side_by_side`).

    Returns
    -------
    (M, 2, 2) ndarray
        Segment k runs from ``src[k]`` to ``dst[k] + (offset, 0)``, as ``LineCollection`` takes them.
    """
    src = np.asarray(src, dtype=float).reshape(-1, 2)
    dst = np.asarray(dst, dtype=float).reshape(-1, 2) + [offset, 0.0]
    return np.stack([src, dst], axis=1)


class Thinned(NamedTuple):
    """:func:`thin_matches`: which matches to draw.

    Attributes
    ----------
    show : (n,) ndarray of bool
        True for the matches to draw.
    every : int
        The stride k: 1 in k of each kind is drawn (1: all).
    """

    show: np.ndarray
    every: int


def thin_matches(
    good: np.ndarray, limit: int = 200, every: int | None = None, key: np.ndarray | None = None
) -> Thinned:
    """Which matches to draw: 1 in k of the right ones and 1 in k of the wrong ones.

    Both kinds are thinned by the same stride k, so the share of right matches among the
    lines drawn equals their share among all ``n`` matches, up to one line of each kind. With
    ``every`` given, k is that fixed stride, so the number of lines drawn rises and falls with
    the number of matches (a demo that re-filters matches should fix it); otherwise
    ``k = ceil(n / limit)`` (every match when ``n <= limit``), at most about ``limit`` lines.

    Parameters
    ----------
    good : (n,) array_like of bool
        True where a match is right.
    limit : int, optional
        The most lines to draw (each kind may round up by one); ignored when ``every`` is given.
    every : int or None, optional
        A fixed stride k (1: draw all).
    key : (n,) array_like of int or None, optional
        A stable number per match (e.g. its query keypoint's index): with it, a match is drawn
        when ``key % k == 0``, so a match that survives a re-filtering keeps its line and a
        filter removes only the lines of the matches it removes. The drawn share of right
        matches is then the true share only on average (a few lines either way).

    Returns
    -------
    Thinned
        ``show`` (True for the matches to draw: the 1st, (k+1)-th, ... right match and likewise
        the wrong ones) and ``every``, the stride k (1: all drawn).
    """
    good = np.asarray(good, dtype=bool).ravel()
    if every is not None:
        if int(every) != every or every < 1:
            raise ValueError(
                f"thin_matches: every must be a whole stride of at least 1, got {every}; "
                "pass 1 to draw every match"
            )
        every = int(every)
    else:
        if limit < 1:
            raise ValueError(f"thin_matches: limit must be a positive number of lines, got {limit}")
        every = max(1, -(-len(good) // int(limit)))  # ceil(n / limit)
    if key is not None:
        key = np.asarray(key).ravel()
        if key.shape != good.shape:
            raise ValueError(
                f"thin_matches: key must hold one number per match ({good.size}), got shape "
                f"{key.shape}; pass e.g. the matches' query keypoint indices"
            )
        return Thinned(key.astype(np.int64) % every == 0, every)
    rank = np.where(good, np.cumsum(good), np.cumsum(~good)) - 1  # 0, 1, 2 ... within each kind
    return Thinned(rank % every == 0, every)


def draw_keypoints(
    ax, points: np.ndarray, sizes: np.ndarray | None = None, color: str = palette.YELLOW, **kw
):
    """Keypoints as circles of their detection size (scatter); returns the PathCollection.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The image axes to draw in.
    points : (N, 2) ndarray
        Keypoints (u, v), pixels.
    sizes : (N,) ndarray or None
        Detection diameters, pixels, clipped to [2, 60]; None draws every circle the same size.
    color : str
        The circles' colour (a palette colour).
    **kw
        Passed on to ``ax.scatter``.

    Returns
    -------
    matplotlib.collections.PathCollection
        The circles.
    """
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    s = 12.0 if sizes is None else np.clip(np.asarray(sizes, dtype=float), 2, 60) ** 2 / 4
    kw.setdefault("linewidths", 0.7)
    return ax.scatter(pts[:, 0], pts[:, 1], s=s, facecolors="none", edgecolors=color, **kw)


def draw_matches(
    ax,
    image1: np.ndarray,
    image2: np.ndarray,
    src: np.ndarray,
    dst: np.ndarray,
    good: np.ndarray | None = None,
    gap: int = 8,
) -> dict:
    """Show two images side by side with a line per match (green where ``good``, red dashed elsewhere, on top).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in (ticks removed, limits set to the canvas).
    image1, image2 : (H, W) or (H, W, 3) ndarray
        The two images (:func:`side_by_side`).
    src, dst : (M, 2) ndarray
        Matched points (u, v) in image 1 and image 2, pixels.
    good : (M,) bool ndarray or None
        Which matches are good (inliers); None: all.
    gap : int
        Width of the white gap between the images, pixels.

    Returns
    -------
    dict
        ``"image"`` (the AxesImage), ``"good"`` and ``"bad"`` (LineCollections) and ``"offset"``
        (image 2's u offset, px), so a demo can update the segments
        (``art["good"].set_segments(match_segments(...))``).
    """
    from matplotlib.collections import LineCollection

    both, off = side_by_side(image1, image2, gap)
    im = ax.imshow(both, interpolation="nearest")
    ax.set_xticks([])
    ax.set_yticks([])
    seg = match_segments(src, dst, off)
    g = np.ones(len(seg), bool) if good is None else np.asarray(good, bool)
    from matplotlib import patheffects

    # thin lines with a hairline dark edge (0.4 pt a side, where palette.halo gives 1 pt), so they
    # read on the photo and the photo shows between them; red a little wider and on top, so a wrong
    # match is never buried under the right ones, yet green keeps its weight where both are many
    lc_good = LineCollection(
        seg[g],
        colors=palette.GREEN,
        linewidths=0.8,
        path_effects=[patheffects.withStroke(linewidth=1.6, foreground="black")],
        zorder=2,
    )
    lc_bad = LineCollection(
        seg[~g],
        colors=palette.RED,
        linewidths=1.0,
        linestyles=(0, (3, 1.5)),  # dashed: wrong tells from right without colour
        path_effects=[patheffects.withStroke(linewidth=1.8, foreground="black")],
        zorder=2.1,
    )
    ax.add_collection(lc_good)
    ax.add_collection(lc_bad)
    ax.set(xlim=(-0.5, both.shape[1] - 0.5), ylim=(both.shape[0] - 0.5, -0.5))
    return {"image": im, "good": lc_good, "bad": lc_bad, "offset": off}


def outline(ax, H: np.ndarray, shape: tuple[int, ...], **kw):
    """Draw the border of an image of ``shape`` mapped by H (e.g. onto a panorama canvas); returns the Line2D.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in.
    H : (3, 3) ndarray
        Homography from the image's pixels to the axes' coordinates.
    shape : tuple
        The image's shape ``(height, width, ...)``; its outer pixel edges are outlined.
    **kw
        Line properties, passed on to ``ax.plot``.

    Returns
    -------
    matplotlib.lines.Line2D
        The closed outline.
    """
    from ..projective import map_points

    h, w = shape[:2]
    c = np.array([[-0.5, -0.5], [w - 0.5, -0.5], [w - 0.5, h - 0.5], [-0.5, h - 0.5], [-0.5, -0.5]])
    p = map_points(np.asarray(H, dtype=float), c)
    return ax.plot(p[:, 0], p[:, 1], **kw)[0]
