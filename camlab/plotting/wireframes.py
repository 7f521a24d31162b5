"""Wireframes drawn fast (lessons 04, 05, 11).

(M, 2, d) segments as one polyline with NaN breaks, in a 3-D axes or an image panel, world points
and world axes, and segments clipped to the image.

Helpers of :mod:`camlab.plotting.scene3d`, which re-exports them.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from . import palette, plane

__all__ = [
    "AxisArtists",
    "axis_artists",
    "clip_segments",
    "draw_points",
    "draw_segments",
    "draw_world_axes",
    "image_axes",
    "polyline_data",
    "update_segments",
]


def polyline_data(segments: ArrayLike) -> np.ndarray:
    """(M, 2, d) segments as one (3M, d) polyline with NaN rows between segments.

    One Line2D/Line3D with NaN breaks draws far faster than M separate lines.

    Parameters
    ----------
    segments : (M, 2, d) array_like
        Segments, each its two ends in ``d`` = 2 (pixels) or 3 (world, m) coordinates.

    Returns
    -------
    (3M, d) ndarray
        Start, end and a NaN row for each segment.
    """
    s = np.asarray(segments, dtype=float)
    out = np.full((len(s), 3, s.shape[-1]), np.nan)
    out[:, :2] = s
    return out.reshape(-1, s.shape[-1])


def draw_segments(ax, segments: ArrayLike, **kw: Any):
    """Draw (M, 2, 3) world segments as one Line3D; move them later with :func:`update_segments`.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        The 3-D axes to draw in.
    segments : (M, 2, 3) array_like
        World segments, metres.
    **kw
        Line properties for ``ax.plot`` (default colour ``"0.25"``, width 1.2).

    Returns
    -------
    mpl_toolkits.mplot3d.art3d.Line3D
        One polyline with NaN breaks (:func:`polyline_data`).
    """
    d = polyline_data(segments)
    kw.setdefault("color", "0.25")
    kw.setdefault("lw", 1.2)
    (line,) = ax.plot(d[:, 0], d[:, 1], d[:, 2], **kw)
    return line


def update_segments(line, segments: ArrayLike) -> None:
    """Move a line made by :func:`draw_segments` (3-D) or a 2-D ``ax.plot`` polyline to new segments.

    Parameters
    ----------
    line : matplotlib.lines.Line2D or mpl_toolkits.mplot3d.art3d.Line3D
        The line to move; a 3-D one when ``segments`` are 3-D.
    segments : (M, 2, 3) or (M, 2, 2) array_like
        The new segments, world (m) or pixels.
    """
    d = polyline_data(segments)
    if d.shape[1] == 3:
        line.set_data_3d(d[:, 0], d[:, 1], d[:, 2])
    else:
        line.set_data(d[:, 0], d[:, 1])


def draw_points(ax, points: ArrayLike, **kw: Any):
    """World points (N, 3) as markers on one Line3D (move with ``set_data_3d``).

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        The 3-D axes to draw in.
    points : (N, 3) array_like
        World points, metres (any shape that reshapes to rows of 3).
    **kw
        Line properties for ``ax.plot`` (default: marker ``"o"``, size 3, no line).

    Returns
    -------
    mpl_toolkits.mplot3d.art3d.Line3D
        The markers.
    """
    p = np.reshape(np.asarray(points, dtype=float), (-1, 3))
    kw.setdefault("marker", "o")
    kw.setdefault("ms", 3)
    kw.setdefault("ls", "none")
    (line,) = ax.plot(p[:, 0], p[:, 1], p[:, 2], **kw)
    return line


def draw_world_axes(
    ax, length: float = 1.0, origin: ArrayLike = (0.0, 0.0, 0.0), labels=("X", "Y", "Z")
) -> list:
    """World axes as three coloured arrows-as-lines from ``origin``, labelled X, Y, Z.

    The colours are :data:`~camlab.plotting.palette.AXIS_COLOURS` (x red, y green, z blue); the
    labels sit 1.12 axis lengths out, with a white halo.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        The 3-D axes to draw in.
    length : float
        Length of each axis, metres.
    origin : (3,) array_like
        Where the axes start, world coordinates (m).
    labels : sequence of 3 str
        The axes' names.

    Returns
    -------
    list
        The line and the label of each axis in turn: ``[x_line, x_text, y_line, y_text, z_line, z_text]``.
    """
    o = np.asarray(origin, dtype=float)
    out = []
    for i, (c, name) in enumerate(zip(palette.AXIS_COLOURS, labels, strict=True)):
        e = o.copy()
        e[i] += length
        out.extend(axis_artists(ax, c, name, (o, e)))
    return out


class AxisArtists(NamedTuple):
    """One drawn axis (:func:`axis_artists`).

    Attributes
    ----------
    line : Line3D
        The axis.
    label : Text
        Its name, bold, with a white halo.
    """

    line: Any
    label: Any


def axis_artists(ax, colour: str, name: str, segment: tuple | None = None) -> AxisArtists:
    """One axis in 3-D: its line and its bold label with a white halo (readable over the scene).

    The one style of every drawn axis, the world's (:func:`draw_world_axes`) and a camera's
    (:class:`~camlab.plotting.scene3d.CameraArtist`).

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        The 3-D axes to draw in.
    colour : str
        The axis colour, from :data:`~camlab.plotting.palette.AXIS_COLOURS`.
    name : str
        The label.
    segment : ((3,) array_like, (3,) array_like) or None
        The axis from its start to its end, world coordinates (m); the label sits 1.12 axis
        lengths out. None draws nothing yet (line empty, label at the origin) for an artist that
        is updated later.

    Returns
    -------
    AxisArtists
        ``line`` and ``label``.
    """
    if segment is None:
        xyz, tip = ([], [], []), (0, 0, 0)
    else:
        o, e = np.asarray(segment[0], dtype=float), np.asarray(segment[1], dtype=float)
        xyz, tip = np.c_[o, e], o + (e - o) * 1.12
    (line,) = ax.plot(*xyz, color=colour, lw=2.0)
    text = ax.text(
        *tip,
        name,
        color=colour,
        fontsize=9,
        fontweight="bold",
        ha="center",
        va="center",
        path_effects=palette.halo(),
    )
    return AxisArtists(line, text)


def image_axes(ax, image_size: tuple[int, int], title: str = "", labels: bool = True) -> None:
    """Set up a 2-D axes as an image: u right, v down, pixel centres at integers, equal aspect.

    ``labels=False`` leaves out the axis labels (each text costs about 1 ms per redraw in
    a slider demo); the title then says "u right, v down". This is
    :func:`camlab.plotting.plane.image_axes` with ``compact=True`` (small text, ticks on the
    first, middle and last pixel centres), returning nothing so that a notebook cell ending in it
    shows no repr.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to set up (changed in place).
    image_size : (width, height)
        Image size in pixels; ticks at the first, middle and last pixel centres.
    title : str
        The axes' title (none if empty).
    labels : bool
        Label the axes "u (px)" and "v (px)".
    """
    plane.image_axes(ax, image_size, title, labels=labels, compact=True)


def clip_segments(segments: ArrayLike, image_size: tuple[int, int]) -> np.ndarray:
    """Clip (M, 2, 2) pixel segments to the image rectangle (Liang-Barsky); outside ones become NaN.

    The image covers u in [-0.5, W - 0.5] and v in [-0.5, H - 0.5] (pixel centres at integers).
    A segment is the set p0 + s (p1 - p0), 0 <= s <= 1; each border cuts the allowed s to an
    interval, and what survives all four is the visible part. Segments with a NaN end stay NaN.

    Parameters
    ----------
    segments : (M, 2, 2) array_like
        Pixel segments (u, v), any shape that reshapes to (M, 2, 2).
    image_size : (width, height)
        Image size in pixels.

    Returns
    -------
    (M, 2, 2) ndarray
        The visible part of each segment; NaN where none is visible.

    References
    ----------
    .. [1] Y.-D. Liang and B. A. Barsky, 1984, "A new concept and method for line clipping",
       ACM Transactions on Graphics 3(1).

    Examples
    --------
    >>> clip_segments([[[-10.0, 5.0], [20.0, 5.0]]], (10, 10)).tolist()
    [[[-0.5, 5.0], [9.5, 5.0]]]
    """
    seg = np.asarray(segments, dtype=float).reshape(-1, 2, 2)
    w, h = image_size
    p0, d = seg[:, 0], seg[:, 1] - seg[:, 0]
    lo, hi = np.zeros(len(seg)), np.ones(len(seg))
    visible = np.isfinite(seg).all(axis=(1, 2))
    with np.errstate(divide="ignore", invalid="ignore"):
        for axis, (low, high) in enumerate(((-0.5, w - 0.5), (-0.5, h - 0.5))):
            for p, q in ((-d[:, axis], p0[:, axis] - low), (d[:, axis], high - p0[:, axis])):
                r = q / p
                lo = np.where(p < 0, np.maximum(lo, r), lo)
                hi = np.where(p > 0, np.minimum(hi, r), hi)
                visible &= ~((p == 0) & (q < 0))
    visible &= lo <= hi
    out = np.stack([p0 + lo[:, None] * d, p0 + hi[:, None] * d], axis=1)
    out[~visible] = np.nan
    return out
