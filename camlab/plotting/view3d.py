"""The 3-D axes every camera figure sits in (lessons 00, 04, 05).

Made at a set viewpoint, scaled equally on x, y and z, fitted to what they show, and text turned
away from a line.

Helpers of :mod:`camlab.plotting.scene3d`, which re-exports them.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["align_away", "axes3d", "fit_view", "refresh_projection", "set_equal_aspect"]


def axes3d(fig, *args: Any, elev: float = 22.0, azim: float = -60.0, **kw: Any):
    """Add a 3-D axes to ``fig``, labelled X, Y, Z in metres, with a light pane style.

    ``fig.add_subplot(*args, projection='3d')``, with a pane style that keeps drawing fast.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure to add the axes to.
    *args
        Subplot position, as ``fig.add_subplot`` takes it (e.g. ``1, 2, 1``).
    elev, azim : float
        The viewpoint's elevation and azimuth, degrees (``view_init``).
    **kw
        Passed on to ``fig.add_subplot``.

    Returns
    -------
    mpl_toolkits.mplot3d.axes3d.Axes3D
        The new axes.
    """
    ax = fig.add_subplot(*args, projection="3d", **kw)
    ax.view_init(elev=elev, azim=azim)
    ax.set_xlabel("X (m)", labelpad=-8)
    ax.set_ylabel("Y (m)", labelpad=-8)
    ax.set_zlabel("Z (m)", labelpad=-8)
    ax.tick_params(labelsize=7, pad=-2)
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.pane.set_alpha(0.15)
    return ax


def set_equal_aspect(
    ax,
    points: ArrayLike | Sequence[ArrayLike],
    margin: float = 0.02,
    zoom: float = 1.0,
    tight: bool = False,
) -> None:
    """Give a 3-D axes equal scale on X, Y, Z: a cube of limits around ``points``, a (1, 1, 1) box aspect.

    Angles and lengths then look right. ``tight=True`` fits a box instead of a cube (limits per
    axis, box aspect in proportion, so the scale stays equal): a flat or long scene then fills
    the canvas, but the box changes shape when the points move.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        The 3-D axes.
    points : (N, 3) array_like or sequence of them
        World points (m) to fit, any shape that reshapes to rows of 3; non-finite rows are ignored.
    margin : float
        Extra room around the points, as a fraction of the half-extent.
    zoom : float
        matplotlib's box-aspect zoom.
    tight : bool
        Fit a box per axis instead of a cube.
    """
    if isinstance(points, (list, tuple)):
        pts = np.vstack([np.reshape(np.asarray(p, dtype=float), (-1, 3)) for p in points])
    else:
        pts = np.reshape(np.asarray(points, dtype=float), (-1, 3))
    pts = pts[np.isfinite(pts).all(axis=1)]
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    centre = (lo + hi) / 2.0
    if tight:
        half = np.maximum((hi - lo) / 2.0, 1e-3 * max(float((hi - lo).max()), 1e-6)) * (
            1.0 + margin
        )
        ax.set_xlim(centre[0] - half[0], centre[0] + half[0])
        ax.set_ylim(centre[1] - half[1], centre[1] + half[1])
        ax.set_zlim(centre[2] - half[2], centre[2] + half[2])
        ax.set_box_aspect(tuple(half), zoom=zoom)
        return
    half = max(float((hi - lo).max()) / 2.0, 1e-6) * (1.0 + margin)
    ax.set_xlim(centre[0] - half, centre[0] + half)
    ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_zlim(centre[2] - half, centre[2] + half)
    ax.set_box_aspect((1, 1, 1), zoom=zoom)


def fit_view(
    ax, points: ArrayLike | Sequence[ArrayLike], fill: float = 0.92, max_zoom: float = 3.0
) -> None:
    """Equal-aspect limits around ``points``, centred and zoomed so that their picture fills the axes.

    :func:`set_equal_aspect` fits a cube around the points, but what shows is the cube's *projection*:
    a flat scene seen from the side fills a third of it. Here the cube is then shifted across the
    line of sight until the points' projection is centred, and zoomed until its larger side spans
    ``fill`` of the (square) 3-D axes. Call after ``view_init``; the points must all stay in view.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        The 3-D axes.
    points : (N, 3) array_like or sequence of them
        World points (m) to fit, any shape that reshapes to rows of 3; non-finite rows are ignored.
    fill : float
        Fraction of the axes the points' picture spans along its larger side.
    max_zoom : float
        Upper bound of the zoom (the lower is 0.2).
    """
    from mpl_toolkits.mplot3d import proj3d

    if isinstance(points, (list, tuple)):
        pts = np.vstack([np.reshape(np.asarray(p, dtype=float), (-1, 3)) for p in points])
    else:
        pts = np.reshape(np.asarray(points, dtype=float), (-1, 3))
    pts = pts[np.isfinite(pts).all(axis=1)]
    set_equal_aspect(ax, pts, zoom=1.0)
    lim = np.array([ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()])
    half = (lim[:, 1] - lim[:, 0]) / 2.0
    view = ax.viewLim
    target = np.array([(view.x0 + view.x1) / 2.0, (view.y0 + view.y1) / 2.0])

    def picture(centre, zoom):
        ax.set_xlim3d(centre[0] - half[0], centre[0] + half[0])
        ax.set_ylim3d(centre[1] - half[1], centre[1] + half[1])
        ax.set_zlim3d(centre[2] - half[2], centre[2] + half[2])
        ax.set_box_aspect((1, 1, 1), zoom=zoom)
        xs, ys, _ = proj3d.proj_transform(*pts.T, ax.get_proj())
        return np.array([xs.min(), ys.min()]), np.array([xs.max(), ys.max()])

    az, el = np.radians(ax.azim), np.radians(ax.elev)
    across = np.array(
        [
            [-np.sin(az), np.cos(az), 0.0],  # screen right, up
            [-np.cos(az) * np.sin(el), -np.sin(az) * np.sin(el), np.cos(el)],
        ]
    )
    centre, zoom = lim.mean(axis=1), 1.0
    for _ in range(3):
        lo, hi = picture(centre, zoom)
        offset = (lo + hi) / 2.0 - target
        step = 1e-3 * half.max()
        jac = np.column_stack(
            [(sum(picture(centre + step * d, zoom)) / 2.0 - (lo + hi) / 2.0) / step for d in across]
        )
        centre = centre - across.T @ np.linalg.lstsq(jac, offset, rcond=None)[0]
        lo, hi = picture(centre, zoom)
        span = float(max(hi - lo))
        zoom = float(np.clip(zoom * fill * (view.x1 - view.x0) / max(span, 1e-12), 0.2, max_zoom))
    picture(centre, zoom)
    refresh_projection(ax)


def refresh_projection(ax) -> None:
    """Recompute a 3-D axes' projection matrix after its limits or view changed.

    A full draw does this itself; a blitted redraw (only animated artists) does not, so
    call it after :func:`set_equal_aspect` in an update.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        The 3-D axes; its ``M`` and ``invM`` are set.
    """
    ax.M = ax.get_proj()
    ax.invM = np.linalg.inv(ax.M)


def align_away(ax, text, start: ArrayLike, tip: ArrayLike) -> None:
    """Align a 3-D label at ``tip`` so it runs away from the segment start -> tip on screen.

    A label anchored at its left baseline is struck through by its own axis whenever that
    axis points right and up on screen; aligned by the screen direction, it clears the line.
    Call after the limits and view are final (:func:`refresh_projection`).

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        The 3-D axes the label is in.
    text : matplotlib.text.Text
        The label; its horizontal and vertical alignment are set.
    start, tip : (3,) array_like
        The segment's ends, world coordinates (m); the label sits at ``tip``.
    """
    from mpl_toolkits.mplot3d import proj3d

    M = ax.M if getattr(ax, "M", None) is not None else ax.get_proj()
    (x0, x1), (y0, y1), _ = proj3d.proj_transform(*np.c_[start, tip], M)
    text.set_horizontalalignment("left" if x1 >= x0 else "right")
    text.set_verticalalignment("bottom" if y1 >= y0 else "top")
