"""Drawing points and lines of the projective plane (lesson 06)."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from matplotlib.axes import Axes
from matplotlib.lines import Line2D

from ..projective import clip_line


def set_line(artist: Line2D, line: np.ndarray, ax: Axes) -> None:
    """Move ``artist`` to show the infinite ``line`` (a, b, c) clipped to ``ax``'s limits.

    Parameters
    ----------
    artist : matplotlib.lines.Line2D
        The line artist to move (its data are replaced).
    line : (3,) ndarray
        The line ``a x + b y + c = 0``, homogeneous.
    ax : matplotlib.axes.Axes
        The axes whose current limits clip the line.
    """
    ends = clip_line(line, ax.get_xlim(), sorted(ax.get_ylim()))
    artist.set_data(ends[:, 0], ends[:, 1])


def plane_axes(ax: Axes, lim: float, title: str = "", xlabel: str = "x", ylabel: str = "y") -> Axes:
    """A square, equal-aspect axes centred on the origin with light axis lines.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to set up (changed in place).
    lim : float
        Half-width of the view: both axes span ``[-lim, lim]`` (data units).
    title, xlabel, ylabel : str
        The axes' title (none if empty) and axis labels.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax`` itself, for chaining.
    """
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_aspect("equal")
    ax.axhline(0, color="0.85", lw=0.8, zorder=0, gid="grid")
    ax.axvline(0, color="0.85", lw=0.8, zorder=0, gid="grid")
    ax.grid(True, color="0.93")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title)
    return ax


def image_axes(
    ax: Axes, size: tuple[int, int], title: str = "", *, labels: bool = True, compact: bool = False
) -> Axes:
    """Axes in pixel coordinates for an image of ``size``: u right, v down, origin at pixel (0, 0).

    The origin is the centre of the top-left pixel. :func:`camlab.plotting.scene3d.image_axes`
    (the image panel beside a 3-D view) is this with ``compact=True``.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to set up (changed in place).
    size : (width, height)
        Image size in pixels; the limits are ``[-0.5, width - 0.5]`` and ``[height - 0.5, -0.5]``.
    title : str
        The axes' title (none if empty).
    labels : bool
        Label the axes "u (px)" and "v (px)"; without them (each text costs about 1 ms per redraw
        in a slider demo) the title, if any, ends in "(u right, v down, px)".
    compact : bool
        Small text (labels 8 pt, title 9 pt, tick labels 7 pt) and ticks only on the first, middle
        and last pixel centres, for small panels; else matplotlib's default text and ticks.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax`` itself, for chaining.
    """
    width, height = size
    ax.set_xlim(-0.5, width - 0.5)
    ax.set_ylim(height - 0.5, -0.5)
    ax.set_aspect("equal")
    if labels:
        text = {"fontsize": 8} if compact else {}
        ax.set_xlabel("u (px)", **text)
        ax.set_ylabel("v (px)", **text)
    elif title:
        title = f"{title} (u right, v down, px)"
    if compact:
        # Ticks on the first and last pixel centres and the image's centre ((W - 1)/2, (H - 1)/2):
        # 319.5, not 320, for 640 (docs/conventions.md); a tick at W would widen the limits past
        # the last pixel's edge.
        for axis, n in ((ax.xaxis, width), (ax.yaxis, height)):
            ticks = [0, (n - 1) / 2, n - 1]
            axis.set_ticks(ticks, [f"{t:g}" for t in ticks])
        ax.set_xlim(-0.5, width - 0.5)
        ax.set_ylim(height - 0.5, -0.5)
        ax.tick_params(labelsize=7)
    if title:
        ax.set_title(title, **({"fontsize": 9} if compact else {}))
    return ax


class ArrowPlacement(NamedTuple):
    """Where :func:`arrow_to_infinity` draws a point.

    Attributes
    ----------
    position : (2,) ndarray
        The point itself if it is finite and inside the axes, else the arrow's tip near the edge.
    direction : (2,) ndarray
        The arrow's unit direction; (0, 0) when the point is drawn where it is.
    """

    position: np.ndarray
    direction: np.ndarray


def arrow_placement(
    point_h: np.ndarray,
    xlim: tuple[float, float],
    ylim: tuple[float, float],
    anchor: np.ndarray | None = None,
) -> ArrowPlacement:
    """Where to draw a point that may be outside the box ``xlim`` x ``ylim`` or ideal.

    :func:`arrow_to_infinity` for a box given by its limits: the twin of ``arrowPlacement`` in
    ``camlab/widgets/browser/geometry.js``, which the browser-drawn demos of lesson 06 run.

    Parameters
    ----------
    point_h : (3,) ndarray
        The point, homogeneous ``(x, y, w)``; ``w = 0`` for an ideal point.
    xlim, ylim : (lo, hi)
        The box (data units); ``ylim`` in either order (inverted axes give it high first).
    anchor : (2,) ndarray or None
        Where the arrow starts from; None for the box's centre.

    Returns
    -------
    ArrowPlacement
        ``position`` (where to draw) and ``direction`` (unit vector; zero when the point is
        drawn where it is).
    """
    x, y, w = np.asarray(point_h, dtype=float)
    (x0, x1), (y0, y1) = xlim, sorted(ylim)
    centre = np.array([(x0 + x1) / 2, (y0 + y1) / 2])
    start = centre if anchor is None else np.asarray(anchor, dtype=float)
    if w != 0:
        p = np.array([x / w, y / w])
        if x0 <= p[0] <= x1 and y0 <= p[1] <= y1:
            return ArrowPlacement(p, np.zeros(2))
        direction = p - start
    else:
        direction = np.array([x, y])
        if anchor is not None and np.dot(direction, start - centre) < 0:
            direction = -direction  # an ideal point lies both ways: point to the nearer edge
    direction = direction / np.linalg.norm(direction)
    half = np.array([(x1 - x0), (y1 - y0)]) / 2 * 0.9
    lo, hi = centre - half, centre + half
    with np.errstate(divide="ignore", invalid="ignore"):
        steps = np.where(direction > 0, (hi - start) / direction, (lo - start) / direction)
    s = max(0.0, float(np.min(steps[np.abs(direction) > 1e-12])))
    return ArrowPlacement(start + s * direction, direction)


def arrow_to_infinity(
    point_h: np.ndarray, ax: Axes, anchor: np.ndarray | None = None
) -> ArrowPlacement:
    """Where to draw a point that may be off-axes or ideal: (position, unit direction).

    A finite point inside the axes is drawn where it is; otherwise an arrow near the edge
    of the axes points from ``anchor`` (default: the axes' centre) towards the point (for
    an ideal point, along its direction (x, y)). Give an anchor on a line through the point
    (e.g. a vanishing point's horizon) and the arrow sits on that line.

    Parameters
    ----------
    point_h : (3,) ndarray
        The point, homogeneous ``(x, y, w)``; ``w = 0`` for an ideal point.
    ax : matplotlib.axes.Axes
        The axes whose current limits decide "inside"; the arrow's tip stays within 90 % of
        its half-extent from the centre.
    anchor : (2,) ndarray or None
        Where the arrow starts from; None for the axes' centre.

    Returns
    -------
    ArrowPlacement
        ``position`` (where to draw) and ``direction`` (unit vector; zero when the point is
        drawn where it is).
    """
    return arrow_placement(point_h, ax.get_xlim(), ax.get_ylim(), anchor)


ARROW_PATH = np.array([[0.0, 1.0], [-0.55, -0.7], [0.0, -0.3], [0.55, -0.7], [0.0, 1.0]])
"""The arrowhead of :func:`arrow_marker`, pointing up (+y), closed (its last vertex is its first)."""


def arrow_marker(direction: np.ndarray, ax: Axes):
    """A marker shaped like an arrowhead pointing along ``direction`` (data units) in ``ax``.

    Screen and data directions differ when the y axis is inverted (image axes, v down);
    an equilateral triangle would not do: it seems to point at whichever vertex is nearest.

    Parameters
    ----------
    direction : (2,) ndarray
        The direction to point along, in data units (need not be unit length).
    ax : matplotlib.axes.Axes
        The axes the marker is drawn in (only whether its y axis is inverted matters).

    Returns
    -------
    matplotlib.markers.MarkerStyle
        An arrowhead path rotated to point along ``direction`` on screen.
    """
    from matplotlib.markers import MarkerStyle
    from matplotlib.path import Path
    from matplotlib.transforms import Affine2D

    dx, dy = np.asarray(direction, dtype=float)
    if ax.yaxis_inverted():
        dy = -dy
    angle = np.degrees(np.arctan2(dy, dx)) - 90.0  # the path points up (+y) at angle 0
    return MarkerStyle(Path(ARROW_PATH), transform=Affine2D().rotate_deg(angle))
