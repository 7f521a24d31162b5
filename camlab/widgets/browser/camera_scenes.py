"""The scenes the kernel sends once for lesson 04's browser-drawn demos (``projective_camera.js``).

A 3-D view whose projection moves on every slider move (the viewer turns with the camera and the
limits refit) sends its world (segments, m), the 3-D axes' fixed 2-D map and box, and the look of
each artist read off matplotlib's; ``view3d.js`` recomputes the projection in the browser.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.collections import Collection
from matplotlib.colors import to_rgba
from matplotlib.text import Text

from . import marker_style, text_style, to_canvas_pixels
from .homography_scenes import halo_style, haloed_line_style
from .scenes import axes_box, cross_marker_style

__all__ = [
    "artist_style",
    "camera_explorer_scene",
    "draw_order",
    "named_artists",
    "opencv_vs_opengl_scene",
    "panel3d",
]


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


def artist_style(artist: Any, pt: float) -> dict:
    """How ``projective_camera.js`` draws one artist, read off it.

    Parameters
    ----------
    artist : matplotlib.artist.Artist
        A text, a (3-D) polygon collection, a line of round or "+" markers, or a line (with its
        halo, if it has one).
    pt : float
        Figure dpi / 72.

    Returns
    -------
    dict
        A text's look, string and alignment; a polygon's ``fill``, edge ``color``, ``width`` and
        ``closed``; ``marker`` (a round marker's look) or ``cross`` (a "+"'s); else the line's style.
    """
    if isinstance(artist, Text):
        return _text(artist, pt)
    if isinstance(artist, Collection):
        return dict(
            color=_css(artist.get_edgecolor()[0]),
            fill=_css(artist.get_facecolor()[0]),
            width=float(artist.get_linewidth()[0]) * pt,
            dash=[],
            closed=True,
        )
    if artist.get_marker() == "+":
        return dict(cross=cross_marker_style(artist, pt))
    if artist.get_marker() == "o":
        return dict(marker=marker_style(artist, pt))
    return haloed_line_style(artist, pt)


def named_artists(view: Any, named: dict) -> dict:
    """The styles of the named artists and their draw order (``scene["styles"]``, ``scene["order"]``).

    Parameters
    ----------
    view : camlab.widgets._base.FigureView
        The demo's view, drawn once.
    named : dict
        The name the drawer knows each animated artist by -> the artist.

    Returns
    -------
    dict
        ``styles`` (name -> :func:`artist_style`) and ``order`` (:func:`draw_order`).
    """
    pt = view.fig.dpi / 72.0
    return dict(
        styles={name: artist_style(a, pt) for name, a in named.items()},
        order=draw_order(view, {id(a): name for name, a in named.items()}),
    )


def _axes_named(kind: str, lines: Any, texts: Any) -> dict:
    """Axis lines and their labels by the drawer's names: ``<kind>Axis<i>``, ``<kind>Label<i>``."""
    out = {f"{kind}Axis{i}": ln for i, ln in enumerate(lines)}
    return out | {f"{kind}Label{i}": tx for i, tx in enumerate(texts)}


def _world_axes(world_axes: list) -> tuple[dict, float]:
    """:func:`~camlab.plotting.wireframes.draw_world_axes`' artists by name, and their length (m)."""
    lines, texts = world_axes[0::2], world_axes[1::2]
    length = float(np.linalg.norm(np.asarray(lines[0].get_data_3d())[:, 1]))
    return _axes_named("world", lines, texts), length


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
    cam_art = sv.camera_artist
    axes, length = _world_axes(sv.world_axes)
    named = dict(
        world=sv.world,
        frustum=cam_art.frustum,
        plane=cam_art.plane,
        centre=cam_art.centre_marker,
        thumbnail=cam_art.lines,
        label=cam_art.label,
        image=sv.image_lines,
        principalPoint=pp,
    )
    named |= axes | _axes_named("camera", cam_art.axes_lines, cam_art.axes_text)
    return dict(
        panel3d=panel3d(sv.ax3d, world["fill"]),
        panelImage=dict(toPixels=to_canvas_pixels(sv.ax_image), box=axes_box(sv.ax_image)),
        segments=sv.segments.tolist(),
        thumbnail=sv.thumbnail.tolist(),
        imageSize=[int(c) for c in sv.camera.image_size],
        labelOffset=[float(c) for c in cam_art.label_offset],
        worldAxisLength=length,
        target=np.asarray(world["target"], dtype=float).tolist(),
        viewerOffset=float(world["viewer_offset"]),
        panFollow=float(world["pan_follow"]),
        elev=float(world["elev"]),
        **named_artists(view, named),
    )


def opencv_vs_opengl_scene(view: Any, ax: Any, parts: dict, world: dict) -> dict:
    """What ``projective_camera.js`` needs to draw ``opencv_vs_opengl`` as matplotlib draws it.

    Parameters
    ----------
    view : camlab.widgets._base.FigureView
        The demo's view, drawn once.
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        The 3-D axes.
    parts : dict
        The artists: ``world`` (the world axes, :func:`~camlab.plotting.wireframes.draw_world_axes`),
        ``house`` (its line), ``camera`` (the :class:`~camlab.plotting.scene3d.CameraArtist`),
        ``lines`` and ``texts`` (the camera's three axes and their labels).
    world : dict
        ``house`` ((M, 2, 3) segments, m), ``eye`` (the camera at orbit 0, m), ``target`` (where it
        looks, m), ``camera`` (the camera at orbit 0: its K and image size), ``elev``, ``azim0`` and
        ``follow`` (the viewer: azimuth azim0 + follow * orbit, degrees), ``fill``, ``axis``,
        ``label`` and ``tips`` (the camera axes' length, where their labels sit and where the fit
        keeps both frames' labels, in metres along the axes) and ``names`` (the axes' labels by frame).

    Returns
    -------
    dict
        The scene (JSON).
    """
    art = parts["camera"]
    axes, length = _world_axes(parts["world"])
    named = dict(
        house=parts["house"], frustum=art.frustum, plane=art.plane, centre=art.centre_marker
    )
    named |= axes | _axes_named("camera", parts["lines"], parts["texts"])
    cam = world["camera"]
    return dict(
        panel3d=panel3d(ax, world["fill"]),
        house=np.asarray(world["house"], dtype=float).tolist(),
        eye=np.asarray(world["eye"], dtype=float).tolist(),
        target=np.asarray(world["target"], dtype=float).tolist(),
        K=cam.K.tolist(),
        imageSize=[int(c) for c in cam.image_size],
        planeSize=float(art.size),
        worldAxisLength=length,
        elev=float(world["elev"]),
        azim0=float(world["azim0"]),
        follow=float(world["follow"]),
        axis=float(world["axis"]),
        label=float(world["label"]),
        tips=float(world["tips"]),
        names={k: list(v) for k, v in world["names"].items()},
        **named_artists(view, named),
    )
