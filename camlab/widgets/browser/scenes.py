"""The scenes the kernel sends once for each browser-drawn demo: what its drawer in ``<demo>.js`` needs.

A scene holds the numbers the drawer cannot compute (each panel's data-to-pixel map, the demo's
constants, the control ranges a mouse drag clips to) and the look of every moving artist, read
off the matplotlib artists themselves (colours from :mod:`camlab.plotting.palette` through them,
sizes in canvas pixels), so the browser draws what the figure draws.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from matplotlib.colors import to_hex, to_rgba

from ...plotting import optics
from . import (
    axes_box,
    canvas_height,
    line_style,
    marker_style,
    text_lines,
    text_style,
    to_canvas_pixels,
)

__all__ = [
    "arrow_pointing_right",
    "arrow_style",
    "axes_box",
    "cross_marker_style",
    "dolly_zoom_scene",
    "epipolar_scene",
    "fill_style",
    "log_canvas_pixels",
    "path_marker_style",
    "plane_panel",
    "similar_triangles_scene",
    "spine_lines",
    "three_cameras_scene",
]


def fill_style(patch: Any) -> dict:
    """A filled polygon's colour with its alpha, as CSS ``rgba(...)``.

    Parameters
    ----------
    patch : matplotlib.patches.Polygon
        The fill (drawn without an edge).

    Returns
    -------
    dict
        ``fill``: the CSS colour.
    """
    r, g, b, a = to_rgba(patch.get_facecolor())
    return dict(fill=f"rgba({round(r * 255)}, {round(g * 255)}, {round(b * 255)}, {a:.4f})")


def arrow_style(arrow: Any, pt: float) -> dict:
    """An annotation's "<->" or "->" arrow: its colour, width, heads and shrinks, px (``drawing.js``'s arrows).

    Parameters
    ----------
    arrow : matplotlib.text.Annotation
        The annotation (its text empty: the arrow leaves the text's point, shrunk by shrinkA).
    pt : float
        Figure dpi / 72.

    Returns
    -------
    dict
        ``color``, ``width``, ``headLength``, ``headWidth`` (matplotlib's ``ArrowStyle.CurveAB``
        and ``CurveB``: the head's size times the annotation's text size), ``shrinkA`` and
        ``shrinkB`` (px).
    """
    patch = arrow.arrow_patch
    style = patch.get_arrowstyle()
    mutation = arrow.get_size() * pt  # annotate's mutation scale is its text size
    return dict(
        color=to_hex(patch.get_edgecolor()),
        width=patch.get_linewidth() * pt,
        headLength=style.head_length * mutation,
        headWidth=style.head_width * mutation,
        shrinkA=patch.shrinkA * pt,
        shrinkB=patch.shrinkB * pt,
    )


def _ranges(controls: Mapping[str, Any], *names: str) -> dict:
    return {n: dict(min=controls[n].min, max=controls[n].max, step=controls[n].step) for n in names}


def similar_triangles_scene(ax: Any, art: dict, controls: Mapping[str, Any]) -> dict:
    """What ``similar_triangles.js`` needs to draw lesson 01's side view as matplotlib draws it.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The side view (drawn once, so its layout is fixed).
    art : dict
        :func:`camlab.plotting.optics.draw_similar_triangles`'s artists.
    controls : mapping
        The demo's sliders: the ranges a click or drag in the browser clips ``Z`` and ``Y`` to.

    Returns
    -------
    dict
        The scene (JSON): the panel's map, ``h`` and the layout's constants (``rooms``), the
        styles, the title's lines, the axes' box in pixels and the controls' ranges.
    """
    fig = ax.figure
    pt = fig.dpi / 72.0
    dims = art["dims"]
    ray = art["ray"]
    pinhole = art["pinhole"]
    leader = pinhole.arrow_patch
    return dict(
        toPixels=to_canvas_pixels(ax),
        h=float(ax.get_ylim()[1] * 0.85),
        rooms=dict(
            shortest=optics.SHORTEST_ARROW, fRoom=optics.F_LABEL_ROOM, zRoom=optics.Z_LABEL_ROOM
        ),
        axes=axes_box(ax),
        ranges=_ranges(controls, "Z", "Y"),
        styles=dict(
            big=fill_style(art["big"]),
            small=fill_style(art["small"]),
            object=line_style(art["object"], pt),
            virtual=line_style(art["virtual"], pt),
            real=line_style(art["real"], pt),
            planes=line_style(art["planes"], pt),
            ray=line_style(ray, pt, halo="#ffffff", haloWidth=(ray.get_linewidth() + 2.0) * pt),
            point=marker_style(art["point"], pt),
            pinholeDot=marker_style(art["pinhole_dot"], pt),
            pinhole=text_style(pinhole),
            leader=dict(
                color=to_hex(leader.get_edgecolor()),
                width=leader.get_linewidth() * pt,
                # the line leaves the text's box padded by 2 points (annotate's patchA), then shrinkA
                shrinkA=(2.0 + leader.shrinkA) * pt,
                shrinkB=leader.shrinkB * pt,
            ),
            dims={
                key: dict(
                    arrow=arrow_style(d["arrow"], pt),
                    label=text_style(
                        d["label"],
                        box=to_hex(d["label"].get_bbox_patch().get_facecolor()),
                        pad=d["label"].get_bbox_patch().get_boxstyle().pad
                        * d["label"].get_fontsize()
                        * pt,
                    ),
                )
                for key, d in dims.items()
            },
            title=dict(text_style(ax.title), **text_lines(ax.title)),
        ),
    )


def path_marker_style(line: Any, px_per_point: float) -> dict:
    """A line's marker as a closed path (``drawing.js``'s ``pathMarker``): vertices in points, y up.

    Parameters
    ----------
    line : matplotlib.lines.Line2D
        A line drawn with a polygon marker ("D", "s", ...).
    px_per_point : float
        Figure dpi / 72.

    Returns
    -------
    dict
        ``verts`` (the marker's outline for a size of 1), ``size`` (px), ``color`` (face),
        ``edge`` and ``edgeWidth`` (px).
    """
    marker = line._marker  # noqa: SLF001 - the MarkerStyle matplotlib draws
    verts = marker.get_path().transformed(marker.get_transform()).vertices
    return dict(
        verts=np.round(verts[:-1], 12).tolist(),
        size=line.get_markersize() * px_per_point,
        color=to_hex(line.get_markerfacecolor()),
        edge=to_hex(line.get_markeredgecolor()),
        edgeWidth=line.get_markeredgewidth() * px_per_point,
    )


def three_cameras_scene(
    axes: Any, lines: Mapping[str, Any], reference: Any, world: Mapping[str, Any]
) -> dict:
    """What ``three_cameras.js`` needs to draw lesson 05's three images as matplotlib draws them.

    Parameters
    ----------
    axes : sequence of 3 matplotlib.axes.Axes
        The perspective, weak-perspective and orthographic panels (drawn once).
    lines : mapping
        The moving lines: ``perspective``, ``ghost``, ``weak``, ``orthographic``, ``gaps``.
    reference : matplotlib.lines.Line2D
        One of the X0 markers (all three look alike).
    world : mapping
        The numbers of the scene: ``segments`` ((M, 2, 3) world segments, m), ``parts`` (name ->
        (first, last) rows of ``segments`` and the samples along each), ``X0``, ``target``, ``f0``,
        ``d0``, ``principal_point``, ``size`` (the frame, px).

    Returns
    -------
    dict
        The scene (JSON): per panel its map and box, the world's numbers and the styles.
    """
    pt = axes[0].figure.dpi / 72.0
    gaps = lines["gaps"]
    return dict(
        panels=[dict(toPixels=to_canvas_pixels(ax), box=axes_box(ax)) for ax in axes],
        segments=np.asarray(world["segments"], dtype=float).tolist(),
        parts=dict(world["parts"]),
        X0=np.asarray(world["X0"], dtype=float).tolist(),
        target=np.asarray(world["target"], dtype=float).tolist(),
        f0=float(world["f0"]),
        d0=float(world["d0"]),
        principalPoint=[float(c) for c in world["principal_point"]],
        size=[int(c) for c in world["size"]],
        styles=dict(
            {k: line_style(lines[k], pt) for k in ("perspective", "ghost", "weak", "orthographic")},
            gaps=line_style(gaps, pt),
            gapDots=marker_style(gaps, pt),
            reference=path_marker_style(reference, pt),
        ),
    )


def log_canvas_pixels(ax: Any) -> list[list[float]]:
    """The 3x3 map from (log10 x, log10 y) to canvas pixels, for an axes with log scales on both axes.

    matplotlib maps data through the axes' scale (log10 here), then an affine map from the scaled
    view limits to the display; this is that affine map with the canvas's flip (v = height - y).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Log-log axes, after the figure's layout is fixed.

    Returns
    -------
    list of 3 lists of 3 floats
        The map, rows.
    """
    height = canvas_height(ax.figure)
    flip = np.array([[1.0, 0.0, 0.0], [0.0, -1.0, height], [0.0, 0.0, 1.0]])
    return (flip @ (ax.transLimits + ax.transAxes).get_matrix()).tolist()


def cross_marker_style(line: Any, px_per_point: float) -> dict:
    """A "+" marker's colour, size (px) and stroke width (px).

    Parameters
    ----------
    line : matplotlib.lines.Line2D
        A line drawn with the "+" marker.
    px_per_point : float
        Figure dpi / 72.

    Returns
    -------
    dict
        ``color``, ``size`` and ``width``.
    """
    return dict(
        color=to_hex(line.get_markeredgecolor()),
        size=line.get_markersize() * px_per_point,
        width=line.get_markeredgewidth() * px_per_point,
    )


def dolly_zoom_scene(
    panels: Mapping[str, Any], err: Mapping[str, Any], world: Mapping[str, Any]
) -> dict:
    """What ``dolly_zoom.js`` needs to draw lesson 05's dolly zoom as matplotlib draws it.

    Parameters
    ----------
    panels : mapping
        Per affine model (``"weak perspective"``, ``"para-perspective"``) its image panel's
        artists: ``ax``, ``under`` (the perspective image), ``line`` (the model's), ``reference``
        (X0's marker), ``centre`` (the principal point's +) and ``readout`` (the RMS text).
    err : mapping
        The error panel: ``ax`` (log-log), ``curves`` and ``markers`` (per model).
    world : mapping
        ``cube`` ((M, 2, 3) segments, m), ``view`` (azimuth and elevation, radians), ``target``,
        ``f0``, ``d0``, ``principal_point``, ``distances`` (the curves' abscissae, m).

    Returns
    -------
    dict
        The scene (JSON).
    """
    ax_err = err["ax"]
    pt = ax_err.figure.dpi / 72.0
    height = canvas_height(ax_err.figure)
    images = []
    for model, art in panels.items():
        x, y = art["readout"].get_transform().transform(art["readout"].get_position())
        images.append(
            dict(
                model=model,
                toPixels=to_canvas_pixels(art["ax"]),
                box=axes_box(art["ax"]),
                under=line_style(art["under"], pt),
                line=line_style(art["line"], pt),
                reference=path_marker_style(art["reference"], pt),
                centre=cross_marker_style(art["centre"], pt),
                centreAt=np.asarray(art["centre"].get_xydata()[0], dtype=float).tolist(),
                readout=dict(text_style(art["readout"]), x=float(x), y=float(height - y)),
            )
        )
    return dict(
        images=images,
        error=dict(
            toPixels=log_canvas_pixels(ax_err),
            box=axes_box(ax_err),
            curves={m: line_style(c, pt) for m, c in err["curves"].items()},
            markers={m: marker_style(c, pt) for m, c in err["markers"].items()},
        ),
        cube=np.asarray(world["cube"], dtype=float).tolist(),
        view=[float(a) for a in world["view"]],
        target=np.asarray(world["target"], dtype=float).tolist(),
        f0=float(world["f0"]),
        d0=float(world["d0"]),
        principalPoint=[float(c) for c in world["principal_point"]],
        distances=np.asarray(world["distances"], dtype=float).tolist(),
    )


def epipolar_scene(
    art: Any, refs: Any, world: Mapping[str, Any], controls: Mapping[str, Any]
) -> dict:
    """What ``epipolar.js`` needs to draw lesson 11's ``epipolar_lines`` as matplotlib draws it.

    Parameters
    ----------
    art : namespace
        The figure's parts: ``axl``, ``axr`` (the two images, drawn once) and the moving artists
        ``wl``, ``wr`` (outlines), ``pencil_l``, ``point``, ``line_l``, ``line_r``, ``depth_dots``,
        ``epi_l`` (a star), ``shafts`` and ``heads`` (an epipole off the image).
    refs : matplotlib.lines.Line2D
        The reference pixels' square markers.
    world : mapping
        ``segments`` ((M, 2, 3) world outlines, m), ``ref`` ((K, 2) reference pixels), ``size``
        (the image, px) and ``arrow`` (the arrowhead's closed path, pointing up).
    controls : mapping
        The demo's controls: the ranges a click or drag in the left image clips ``u`` and ``v`` to.

    Returns
    -------
    dict
        The scene (JSON); the arrowhead's vertices turned to point right (``drawing.js``'s ``marker``).
    """
    pt = art.axl.figure.dpi / 72.0
    return dict(
        panels=[plane_panel(art.axl), plane_panel(art.axr)],
        segments=np.asarray(world["segments"], dtype=float).tolist(),
        ref=np.asarray(world["ref"], dtype=float).tolist(),
        size=[int(c) for c in world["size"]],
        arrow=arrow_pointing_right(world["arrow"]),
        ranges=_ranges(controls, "u", "v"),
        styles=dict(
            wire=line_style(art.wl, pt),
            pencil=line_style(art.pencil_l, pt),
            point=marker_style(art.point, pt),
            lineLeft=line_style(art.line_l, pt),
            lineRight=line_style(art.line_r, pt),
            depth=marker_style(art.depth_dots, pt),
            epipole=path_marker_style(art.epi_l, pt),
            shaft=line_style(art.shafts[0], pt),
            head=marker_style(art.heads[0], pt),
            ref=path_marker_style(refs, pt),
        ),
    )


def plane_panel(ax: Any) -> dict:
    """One panel: its map to canvas pixels, its box (what its lines are clipped to) and its limits.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes, after the figure's layout is fixed.

    Returns
    -------
    dict
        ``toPixels``, ``box`` (px), ``xlim`` and ``ylim`` (data units, low first: what
        ``set_line`` clips an infinite line to).
    """
    return dict(
        toPixels=to_canvas_pixels(ax),
        box=axes_box(ax),
        xlim=[float(c) for c in ax.get_xlim()],
        ylim=sorted(float(c) for c in ax.get_ylim()),
    )


def arrow_pointing_right(path: Any) -> list[list[float]]:
    """An arrowhead marker's closed path pointing up (+y), turned to point right (+x), its last vertex dropped.

    ``drawing.js``'s ``marker`` turns a path from +x to the way it is asked to point.

    Parameters
    ----------
    path : (N, 2) array_like
        The closed path (its last vertex its first), e.g. :data:`camlab.plotting.plane.ARROW_PATH`.

    Returns
    -------
    list of N - 1 [x, y]
        The open path, turned by -90 degrees.
    """
    verts = np.asarray(path, dtype=float)[:-1]
    return np.column_stack([verts[:, 1], -verts[:, 0]]).tolist()


def spine_lines(ax: Any) -> list[dict]:
    """An axes' visible spines as canvas polylines with their look (``drawing.js``'s ``polyline``).

    A demo whose image is animated has its spines animated too (a full draw paints them over the
    image), so they are not in the static background: the browser draws them after the image.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes, after the figure's layout is fixed.

    Returns
    -------
    list of dict
        Per visible spine ``points`` (its path, canvas px) and ``style`` (colour, width, caps,
        joins; snapped as matplotlib snaps it).
    """
    pt = ax.figure.dpi / 72.0
    height = canvas_height(ax.figure)
    caps = {"butt": "butt", "round": "round", "projecting": "square"}
    out = []
    for spine in ax.spines.values():
        if not spine.get_visible():
            continue
        xy = spine.get_transform().transform_path(spine.get_path()).vertices
        out.append(
            dict(
                points=np.column_stack([xy[:, 0], height - xy[:, 1]]).tolist(),
                style=dict(
                    color=to_hex(spine.get_edgecolor()),
                    width=spine.get_linewidth() * pt,
                    dash=[],
                    join=spine.get_joinstyle(),
                    cap=caps[spine.get_capstyle()],
                    snap=spine.get_snap() is not False,
                ),
            )
        )
    return out
