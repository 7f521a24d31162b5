"""The scenes of lesson 06's browser-drawn demos (the projective plane): what ``projective_plane.js`` needs.

As in :mod:`.scenes`, a scene holds each panel's data-to-pixel map and limits, and the look of
every moving artist read off the matplotlib artists themselves, so the browser draws what the
figure draws.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from matplotlib.colors import to_hex

from . import line_style, marker_style, text_lines, text_style, to_canvas_pixels
from .scenes import arrow_pointing_right, arrow_style, axes_box, cross_marker_style, plane_panel

__all__ = [
    "boxed_text_scene",
    "collection_style",
    "conic_scene",
    "cross_ratio_scene",
    "duality_scene",
    "lift_scene",
    "parallel_scene",
    "space_panel",
    "plane_panel",
    "scatter_style",
    "text_scene",
    "vanishing_scene",
]


def text_scene(text: Any) -> dict:
    """A moving text whose anchor stays put: its font and colour, its anchor and line baselines (px).

    Parameters
    ----------
    text : matplotlib.text.Text
        The artist, after a draw.

    Returns
    -------
    dict
        :func:`~camlab.widgets.browser.text_style` and :func:`~camlab.widgets.browser.text_lines`
        in one (``drawing.js``'s ``textLines`` draws it).
    """
    return dict(text_style(text), **text_lines(text))


def duality_scene(axes: Any, art: Mapping[str, Any], text: Any) -> dict:
    """What ``projective_plane.js`` needs to draw ``point_line_duality`` as matplotlib draws it.

    Parameters
    ----------
    axes : (2,) sequence of matplotlib.axes.Axes
        The primal and the dual panel (drawn once).
    art : mapping
        The moving artists: ``p_dot``, ``l_line`` (primal), ``pd_line``, ``ld_dot``, ``ld_arrow``
        (dual; the arrow an annotation with "->").
    text : matplotlib.text.Text
        The caption under the panels.

    Returns
    -------
    dict
        The scene (JSON).
    """
    pt = axes[0].figure.dpi / 72.0
    return dict(
        panels=[plane_panel(ax) for ax in axes],
        styles=dict(
            point=marker_style(art["p_dot"], pt),
            line=line_style(art["l_line"], pt),
            dualLine=line_style(art["pd_line"], pt),
            dualPoint=marker_style(art["ld_dot"], pt),
            arrow=arrow_style(art["ld_arrow"], pt),
            caption=text_scene(text),
        ),
    )


def boxed_text_scene(text: Any) -> dict:
    """:func:`text_scene` for a text on a box (``drawing.js``'s ``boxedText``): the box's colours, edge and pad.

    Parameters
    ----------
    text : matplotlib.text.Text
        A text with a bbox (its text already of as many lines as it will show).

    Returns
    -------
    dict
        :func:`text_scene`, with ``box`` (face), ``edge``, ``edgeWidth`` and ``pad`` (px).
    """
    patch = text.get_bbox_patch()
    pt = text.figure.dpi / 72.0
    return dict(
        text_scene(text),
        box=to_hex(patch.get_facecolor()),
        edge=to_hex(patch.get_edgecolor(), keep_alpha=True),  # "none": transparent
        edgeWidth=patch.get_linewidth() * pt,
        pad=patch.get_boxstyle().pad * text.get_fontsize() * pt,
    )


def parallel_scene(axes: Any, art: Mapping[str, Any], world: Mapping[str, Any]) -> dict:
    """What ``projective_plane.js`` needs to draw ``parallel_lines`` as matplotlib draws it.

    Parameters
    ----------
    axes : (2,) sequence of matplotlib.axes.Axes
        The plane and the |w| panel (drawn once).
    art : mapping
        The moving artists: ``l1``, ``l2``, ``meet_dot``, ``arrow`` (an annotation with "->"),
        ``w_curve``, ``w_dot`` and ``same_note``.
    world : mapping
        ``l1`` (the fixed line), ``angle1`` (its angle, degrees), ``angles`` (the curve's
        abscissae, degrees) and ``note`` (the text for l2 = l1).

    Returns
    -------
    dict
        The scene (JSON).
    """
    pt = axes[0].figure.dpi / 72.0
    return dict(
        panels=[plane_panel(ax) for ax in axes],
        l1=[float(c) for c in world["l1"]],
        angle1=float(world["angle1"]),
        angles=[float(a) for a in world["angles"]],
        note=str(world["note"]),
        styles=dict(
            l1=line_style(art["l1"], pt),
            l2=line_style(art["l2"], pt),
            meet=marker_style(art["meet_dot"], pt),
            arrow=arrow_style(art["arrow"], pt),
            curve=line_style(art["w_curve"], pt),
            wDot=marker_style(art["w_dot"], pt),
            note=boxed_text_scene(art["same_note"]),
        ),
    )


def collection_style(collection: Any, px_per_point: float) -> dict:
    """A LineCollection's look (one colour, one width, solid) for ``drawing.js``'s ``polyline``.

    Parameters
    ----------
    collection : matplotlib.collections.LineCollection
        The segments' artist.
    px_per_point : float
        Figure dpi / 72.

    Returns
    -------
    dict
        ``color``, ``width`` (px), ``dash`` ([]), ``join`` and ``cap`` (a collection's defaults:
        round and butt) and ``snap``.
    """
    return dict(
        color=to_hex(collection.get_colors()[0]),
        width=float(collection.get_linewidths()[0]) * px_per_point,
        dash=[],
        join="round",
        cap="butt",
        snap=collection.get_snap() is not False,
    )


def scatter_style(points: Any, px_per_point: float) -> dict:
    """A scatter's round markers (one size, one colour) for ``drawing.js``'s ``dot``.

    Parameters
    ----------
    points : matplotlib.collections.PathCollection
        What ``ax.scatter`` made (its sizes are areas, points squared).
    px_per_point : float
        Figure dpi / 72.

    Returns
    -------
    dict
        ``color``, ``edge``, ``size`` (the diameter, px) and ``edgeWidth`` (px).
    """
    face = to_hex(points.get_facecolors()[0])
    edges = points.get_edgecolors()
    return dict(
        color=face,
        edge=to_hex(edges[0]) if len(edges) else face,
        size=float(np.sqrt(points.get_sizes()[0])) * px_per_point,
        edgeWidth=float(points.get_linewidths()[0]) * px_per_point,
    )


def cross_ratio_scene(art: Mapping[str, Any]) -> dict:
    """What ``projective_plane.js`` needs to draw ``cross_ratio_invariance`` as matplotlib draws it.

    Parameters
    ----------
    art : mapping
        The figure's parts: ``grid`` ((M, 2, 2) segments) and ``points`` ((4, 2): A, B, C, D)
        before the map, and the moving artists ``mapped_grid``, ``mapped_line``, ``mapped_pts``,
        ``labels`` (annotations offset in points) and ``numbers`` (the caption).

    Returns
    -------
    dict
        The scene (JSON).
    """
    ax = art["mapped_line"].axes
    pt = ax.figure.dpi / 72.0
    return dict(
        panel=plane_panel(ax),
        grid=np.asarray(art["grid"], dtype=float).tolist(),
        points=np.asarray(art["points"], dtype=float).tolist(),
        names=[label.get_text() for label in art["labels"]],
        styles=dict(
            grid=collection_style(art["mapped_grid"], pt),
            line=line_style(art["mapped_line"], pt),
            points=scatter_style(art["mapped_pts"], pt),
            label=text_style(art["labels"][0]),
            caption=text_scene(art["numbers"]),
        ),
    )


def vanishing_scene(art: Mapping[str, Any], world: Mapping[str, Any]) -> dict:
    """What ``projective_plane.js`` needs to draw ``vanishing_points`` as matplotlib draws it.

    Parameters
    ----------
    art : mapping
        The figure's parts: ``ax`` (the image) and the moving artists ``grid_z``, ``grid_x``
        (LineCollections), ``horizon``, ``vz_dot``, ``vx_dot`` (lines with one marker, not clipped)
        and ``note`` (the axes' title).
    world : mapping
        ``size`` (the image, px), ``title`` (the title while the horizon is in the image),
        ``note_color`` (the title's colour when it is not) and ``arrow`` (the arrowhead marker's
        closed path, pointing up).

    Returns
    -------
    dict
        The scene (JSON); the arrowhead's vertices turned to point right (``drawing.js``'s ``marker``).
    """
    ax = art["ax"]
    pt = ax.figure.dpi / 72.0
    w, h = world["size"]
    return dict(
        panel=plane_panel(ax),
        size=[int(w), int(h)],
        box=[[-0.5, w - 0.5], [-0.5, h - 0.5]],
        title=str(world["title"]),
        noteColor=to_hex(world["note_color"]),
        arrow=arrow_pointing_right(world["arrow"]),
        styles=dict(
            gridZ=collection_style(art["grid_z"], pt),
            gridX=collection_style(art["grid_x"], pt),
            horizon=line_style(art["horizon"], pt),
            vz=marker_style(art["vz_dot"], pt),
            vx=marker_style(art["vx_dot"], pt),
            note=text_scene(art["note"]),
        ),
    )


def conic_scene(parts: Any) -> dict:
    """What ``projective_plane.js`` needs to draw ``conic_under_homography`` as matplotlib draws it.

    Parameters
    ----------
    parts : namespace
        The figure's parts (``_conic_figure``): ``ax_b``, ``ax_a`` (before and after, drawn once),
        ``samples`` ((8, 2) points on the unit circle) and the moving artists ``to_infinity``,
        ``conic``, ``tangents``, ``centre_image`` ("+"), ``centre_conic`` ("x"), ``mapped`` (a
        scatter) and ``text`` (the caption).

    Returns
    -------
    dict
        The scene (JSON).
    """
    pt = parts.ax_a.figure.dpi / 72.0
    return dict(
        panels=[plane_panel(parts.ax_b), plane_panel(parts.ax_a)],
        samples=np.asarray(parts.samples, dtype=float).tolist(),
        styles=dict(
            toInfinity=line_style(parts.to_infinity, pt),
            conic=line_style(parts.conic, pt),
            tangent=line_style(parts.tangents[0], pt),
            centreImage=cross_marker_style(parts.centre_image, pt),
            centreConic=cross_marker_style(parts.centre_conic, pt),
            mapped=scatter_style(parts.mapped, pt),
            caption=text_scene(parts.text),
        ),
    )


def space_panel(ax: Any) -> dict:
    """A 3-D panel: its map from data (x, y, z) to canvas pixels, and its box (what lines are clipped to).

    mplot3d draws a 3-D line by projecting its points with the axes' matrix ``M`` (set at each
    draw: the view, the limits and the box's aspect), ``(M X)[:2] / (M X)[3]``, onto the axes'
    2-D data coordinates, which its ``transData`` takes to the screen. Both are linear in the
    homogeneous point, so one 3 x 4 matrix ``P`` gives the pixel ``(P X)[:2] / (P X)[2]``
    (``geometry.js``'s ``projectSpace``; twin :func:`space_pixels`).

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D
        The axes, drawn once at their final layout and view.

    Returns
    -------
    dict
        ``toPixels`` (the 3 x 4 map, rows) and ``box`` (px).
    """
    flat = np.asarray(to_canvas_pixels(ax))  # the axes' 2-D data coordinates to canvas pixels
    return dict(toPixels=(flat @ ax.M[[0, 1, 3]]).tolist(), box=axes_box(ax))


def space_pixels(P: Any, points: Any) -> np.ndarray:
    """Points (x, y, z) in canvas pixels under a 3-D panel's map (:func:`space_panel`'s ``toPixels``).

    Parameters
    ----------
    P : (3, 4) array_like
        The panel's map.
    points : (N, 3) array_like
        Data points.

    Returns
    -------
    (N, 2) ndarray
        Their pixels (u right, v down).
    """
    X = np.column_stack([np.asarray(points, dtype=float).reshape(-1, 3), np.ones(len(points))])
    h = X @ np.asarray(P, dtype=float).T
    return h[:, :2] / h[:, 2:]


def lift_scene(parts: Any, world: Mapping[str, Any]) -> dict:
    """What ``projective_plane.js`` needs to draw ``lift_to_plane`` as matplotlib draws it.

    Parameters
    ----------
    parts : namespace
        The figure's parts (``_lift_figure``), drawn once: ``ax3`` (the 3-D box), ``ax2`` (the
        plane w = 1) and the moving artists ``ray``, ``scaled``, ``hit`` (3-D lines), ``dot``
        (a round marker, or an arrowhead at the edge) and ``note`` (a text on a box).
    world : mapping
        ``box`` and ``w_max`` (the 3-D box's half-extents in x, y and in w), ``arrow`` (the
        arrowhead marker's closed path, pointing up), ``notes`` (the notes over the plane:
        ``twins.LIFT_NOTES``) and ``longest`` (a note of as many lines as any the demo shows: its
        lines' baselines are sent).

    Returns
    -------
    dict
        The scene (JSON); the arrowhead's vertices turned to point right (``drawing.js``'s ``marker``).
    """
    pt = parts.ax2.figure.dpi / 72.0
    note = parts.note
    shown = note.get_text()
    note.set_text(
        world["longest"]
    )  # baseline-aligned: a shorter note's lines are this one's first ones
    try:
        note_style = boxed_text_scene(note)
    finally:
        note.set_text(shown)
    return dict(
        space=space_panel(parts.ax3),
        plane=plane_panel(parts.ax2),
        box=float(world["box"]),
        wMax=float(world["w_max"]),
        arrow=arrow_pointing_right(world["arrow"]),
        notes=list(world["notes"]),
        styles=dict(
            ray=line_style(parts.ray, pt),
            scaled=marker_style(parts.scaled, pt),
            hit=marker_style(parts.hit, pt),
            dot=marker_style(parts.dot, pt),
            note=note_style,
        ),
    )
