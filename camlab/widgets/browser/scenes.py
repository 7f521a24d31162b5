"""The scenes the kernel sends once for each browser-drawn demo: what its drawer in ``<demo>.js`` needs.

A scene holds the numbers the drawer cannot compute (each panel's data-to-pixel map, the demo's
constants, the control ranges a mouse drag clips to) and the look of every moving artist, read
off the matplotlib artists themselves (colours from :mod:`camlab.plotting.palette` through them,
sizes in canvas pixels), so the browser draws what the figure draws.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from matplotlib.colors import to_hex, to_rgba

from ...plotting import optics
from . import line_style, marker_style, text_lines, text_style, to_canvas_pixels

__all__ = ["fill_style", "similar_triangles_scene"]


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


def _arrow_style(arrow: Any, pt: float) -> dict:
    """A "<->" dimension arrow: its colour, width and heads, px (matplotlib's ``ArrowStyle.CurveAB``)."""
    patch = arrow.arrow_patch
    style = patch.get_arrowstyle()
    mutation = arrow.get_size() * pt  # annotate's mutation scale is its text size
    return dict(
        color=to_hex(patch.get_edgecolor()),
        width=patch.get_linewidth() * pt,
        headLength=style.head_length * mutation,
        headWidth=style.head_width * mutation,
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
    box = ax.get_window_extent()
    leader = pinhole.arrow_patch
    return dict(
        toPixels=to_canvas_pixels(ax),
        h=float(ax.get_ylim()[1] * 0.85),
        rooms=dict(
            shortest=optics.SHORTEST_ARROW, fRoom=optics.F_LABEL_ROOM, zRoom=optics.Z_LABEL_ROOM
        ),
        axes=dict(
            left=float(box.x0),
            right=float(box.x1),
            top=float(fig.bbox.height - box.y1),
            bottom=float(fig.bbox.height - box.y0),
        ),
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
                    arrow=_arrow_style(d["arrow"], pt),
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
