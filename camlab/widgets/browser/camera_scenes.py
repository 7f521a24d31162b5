"""The scenes the kernel sends once for lesson 04's browser-drawn demos (``projective_camera.js``).

A 3-D view whose projection moves on every slider move (the viewer turns with the camera and the
limits refit) sends its world (segments, m), the 3-D axes' fixed 2-D map and box, and the look of
each artist read off matplotlib's; ``view3d.js`` recomputes the projection in the browser.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.colors import to_rgba

from . import line_style, marker_style, text_style, to_canvas_pixels
from .homography_scenes import halo_style, haloed_line_style
from .scenes import axes_box, cross_marker_style

__all__ = ["camera_explorer_scene", "draw_order", "panel3d"]


def _css(rgba: Any) -> str:
    r, g, b, a = to_rgba(rgba)
    return f"rgba({round(r * 255)}, {round(g * 255)}, {round(b * 255)}, {a:.4f})"


def panel3d(ax: Any, fill: float) -> dict:
    """A 3-D axes' fixed 2-D part: its map from projected coordinates to canvas pixels, box and view box.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        The 3-D axes, after the figure's layout is fixed.
    fill : float
        The share of the view box the fitted points span (:func:`camlab.plotting.view3d.fit_view`).

    Returns
    -------
    dict
        ``toPixels``, ``box`` (px), ``viewBox`` ([x0, y0, x1, y1]: the 2-D limits the projection
        lands in) and ``fill``.
    """
    v = ax.viewLim
    return dict(
        toPixels=to_canvas_pixels(ax),
        box=axes_box(ax),
        viewBox=[float(v.x0), float(v.y0), float(v.x1), float(v.y1)],
        fill=float(fill),
    )


def draw_order(view: Any, names: dict) -> list[str]:
    """The names of ``view``'s animated artists in the order a frame paints them (axes, then zorder).

    Parameters
    ----------
    view : camlab.widgets._base.FigureView
        The demo's view, drawn once (a 3-D fill's zorder is computed by the first draw).
    names : dict
        ``id(artist)`` -> the name the drawer knows it by.

    Returns
    -------
    list of str
    """
    return [names[id(a)] for a in view._in_draw_order() if id(a) in names]  # noqa: SLF001 - the view's own order


def _text(text: Any, pt: float) -> dict:
    """A (3-D) text's look, halo, string and alignment."""
    extra = halo_style(text, pt) if text.get_path_effects() else {}
    return dict(
        text_style(text, **extra),
        text=text.get_text(),
        ha=text.get_horizontalalignment(),
        va=text.get_verticalalignment(),
    )


def camera_explorer_scene(view: Any, sv: Any, pp: Any, world: dict) -> dict:
    """What ``projective_camera.js`` needs to draw ``camera_explorer`` as matplotlib draws it.

    Parameters
    ----------
    view : camlab.widgets._base.FigureView
        The demo's view, drawn once.
    sv : camlab.plotting.scene3d.SceneView
        The 3-D view and the image.
    pp : matplotlib.lines.Line2D
        The principal point's "+".
    world : dict
        ``target`` (the orbit's centre, m), ``viewer_offset``, ``pan_follow``, ``elev`` (the
        viewer's turn from the camera's azimuth, its share of the pan and its elevation, degrees)
        and ``fill`` (:meth:`SceneView.fit`'s).

    Returns
    -------
    dict
        The scene (JSON).
    """
    pt = view.fig.dpi / 72.0
    cam_art = sv.camera_artist
    plane = cam_art.plane
    styles = dict(
        world=line_style(sv.world, pt),
        frustum=haloed_line_style(cam_art.frustum, pt),
        plane=dict(
            color=_css(plane.get_edgecolor()[0]),
            fill=_css(plane.get_facecolor()[0]),
            width=float(plane.get_linewidth()[0]) * pt,
            dash=[],
            closed=True,
        ),
        centre=dict(marker=marker_style(cam_art.centre_marker, pt)),
        thumbnail=line_style(cam_art.lines, pt),
        label=_text(cam_art.label, pt),
        image=line_style(sv.image_lines, pt),
        principalPoint=cross_marker_style(pp, pt),
    )
    names = {id(a): n for n, a in [("world", sv.world), ("frustum", cam_art.frustum), ("plane", plane)]}
    names |= {
        id(cam_art.centre_marker): "centre",
        id(cam_art.lines): "thumbnail",
        id(cam_art.label): "label",
        id(sv.image_lines): "image",
        id(pp): "principalPoint",
    }
    world_lines, world_labels = sv.world_axes[0::2], sv.world_axes[1::2]
    for kind, lines, texts in (
        ("world", world_lines, world_labels),
        ("camera", cam_art.axes_lines, cam_art.axes_text),
    ):
        for i, (ln, tx) in enumerate(zip(lines, texts, strict=True)):
            styles[f"{kind}Axis{i}"] = line_style(ln, pt)
            styles[f"{kind}Label{i}"] = _text(tx, pt)
            names[id(ln)], names[id(tx)] = f"{kind}Axis{i}", f"{kind}Label{i}"
    axis_length = float(np.linalg.norm(np.asarray(world_lines[0].get_data_3d())[:, 1]))
    return dict(
        panel3d=panel3d(sv.ax3d, world["fill"]),
        panelImage=dict(toPixels=to_canvas_pixels(sv.ax_image), box=axes_box(sv.ax_image)),
        segments=sv.segments.tolist(),
        thumbnail=sv.thumbnail.tolist(),
        imageSize=[int(c) for c in sv.camera.image_size],
        labelOffset=[float(c) for c in cam_art.label_offset],
        worldAxisLength=axis_length,
        target=np.asarray(world["target"], dtype=float).tolist(),
        viewerOffset=float(world["viewer_offset"]),
        panFollow=float(world["pan_follow"]),
        elev=float(world["elev"]),
        order=draw_order(view, names),
        styles=styles,
    )
