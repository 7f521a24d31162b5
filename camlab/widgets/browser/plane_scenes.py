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

from . import line_style, marker_style, text_lines, text_style
from .scenes import arrow_pointing_right, arrow_style, cross_marker_style, plane_panel

__all__ = [
    "boxed_text_scene",
    "collection_style",
    "conic_scene",
    "cross_ratio_scene",
    "duality_scene",
    "parallel_scene",
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
