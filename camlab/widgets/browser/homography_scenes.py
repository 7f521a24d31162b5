"""The scenes of lesson 07's browser-drawn demos (homographies): what ``hierarchy.js`` needs.

As in :mod:`.scenes`, a scene holds the panel's data-to-pixel map and limits, the demo's constants
(here the picture itself, which the browser warps pixel by pixel) and the look of every moving
artist read off the matplotlib artists, so the browser draws what the figure draws.
"""

from __future__ import annotations

import base64
from collections.abc import Mapping
from typing import Any

import numpy as np
from matplotlib.colors import to_hex

from . import canvas_height, line_style, marker_style, text_lines, text_style
from .plane_scenes import boxed_text_scene
from .scenes import plane_panel, spine_lines

__all__ = ["haloed_line_style", "hierarchy_scene", "image_box", "picture_data"]


def haloed_line_style(line: Any, px_per_point: float) -> dict:
    """:func:`~camlab.widgets.browser.line_style` with the line's halo (``palette.halo``), if it has one.

    Parameters
    ----------
    line : matplotlib.lines.Line2D
        The line; its first path effect, a ``withStroke``, is its halo.
    px_per_point : float
        Figure dpi / 72.

    Returns
    -------
    dict
        The line's style, with ``halo`` (colour) and ``haloWidth`` (px) when it has a halo.
    """
    effects = line.get_path_effects()
    if not effects:
        return line_style(line, px_per_point)
    stroke = effects[0]._gc  # noqa: SLF001 - withStroke keeps its linewidth and foreground here
    return line_style(
        line,
        px_per_point,
        halo=to_hex(stroke["foreground"]),
        haloWidth=float(stroke["linewidth"]) * px_per_point,
    )


def picture_data(picture: np.ndarray) -> dict:
    """A uint8 picture as ``homography.js``'s ``warpPerspective`` takes it: its bytes in base64.

    Parameters
    ----------
    picture : (h, w) or (h, w, C) uint8 ndarray
        The picture, rows first.

    Returns
    -------
    dict
        ``data`` (base64 of the bytes, rows then columns then channels), ``width``, ``height``
        and ``channels``.
    """
    pic = np.ascontiguousarray(picture, dtype=np.uint8)
    return dict(
        data=base64.b64encode(pic.tobytes()).decode("ascii"),
        width=int(pic.shape[1]),
        height=int(pic.shape[0]),
        channels=1 if pic.ndim == 2 else int(pic.shape[2]),
    )


def _fixed_shape(fixed: Mapping[str, Any]) -> tuple[int, int]:
    """The warped canvas's (height, width) from its edges (``xlim``, ``ylim``: -0.5 to size - 0.5)."""
    return round(fixed["ylim"][1] + 0.5), round(fixed["xlim"][1] + 0.5)


def _jsonable(fixed: Mapping[str, Any]) -> dict:
    """:func:`~camlab.widgets.homographies.twins.hierarchy_fixed`'s constants as JSON."""
    out = {k: np.asarray(v, dtype=float).tolist() for k, v in fixed.items() if k != "grid_lines"}
    out["grid_lines"] = [np.asarray(line, dtype=float).tolist() for line in fixed["grid_lines"]]
    return out


def image_box(image: Any) -> dict:
    """The canvas pixels an image's extent covers, its edges rounded as the live canvas places it.

    camlab's views keep an animated image's data at the size it is shown and blit it there
    (``widgets/_transport.py``): the extent's edges rounded to whole pixels.

    Parameters
    ----------
    image : matplotlib.image.AxesImage
        The image, after the figure's layout is fixed.

    Returns
    -------
    dict
        ``left``, ``top`` (canvas px from the top left), ``width`` and ``height`` (px).
    """
    x0, x1, y0, y1 = image.get_extent()
    (u0, v0), (u1, v1) = image.get_transform().transform([(x0, y0), (x1, y1)])
    left, right = round(min(u0, u1)), round(max(u0, u1))
    bottom, top = round(min(v0, v1)), round(max(v0, v1))
    return dict(
        left=left, top=canvas_height(image.figure) - top, width=right - left, height=top - bottom
    )


def _each_text(text: Any, texts: Mapping[str, Mapping[str, str]]) -> dict:
    """Per group and kind, the text and where matplotlib puts its lines (the artist's text restored)."""
    shown = text.get_text()
    try:
        out = {}
        for group, by_kind in texts.items():
            out[group] = {}
            for kind, words in by_kind.items():
                text.set_text(words)
                out[group][kind] = dict(text_lines(text), text=words)
    finally:
        text.set_text(shown)
    return out


def hierarchy_scene(
    fig: Any, picture: np.ndarray, fixed: Mapping[str, Any], texts: Mapping, torn: str
) -> dict:
    """What ``hierarchy.js`` needs to draw lesson 07's ``transformation_hierarchy`` as matplotlib draws it.

    Parameters
    ----------
    fig : namespace
        The figure's parts (``_hierarchy_figure``): ``ax`` (drawn once) and the moving artists
        ``outline_art``, ``grid_art``, ``horizon_art``, ``diagonal_before``, ``diagonal_art``,
        ``facts`` and ``warning`` (its ``artist``, the note on a box).
    picture : (h, w, 3) uint8 ndarray
        The picture the browser warps.
    fixed : mapping
        :func:`~camlab.widgets.homographies.twins.hierarchy_fixed`'s constants.
    texts : mapping
        The facts beside the canvas, by group and then by the smallest group holding its matrix.
    torn : str
        The note shown when the picture is torn.

    Returns
    -------
    dict
        The scene (JSON).
    """
    ax = fig.ax
    pt = ax.figure.dpi / 72.0
    note = fig.warning.artist
    shown, visible = note.get_text(), note.get_visible()
    note.set_text(torn)  # the box's look and lines with the words it shows
    try:
        warning = boxed_text_scene(note)
    finally:
        note.set_text(shown)
        note.set_visible(visible)
    before = fig.diagonal_before
    return dict(
        panel=plane_panel(ax),
        picture=picture_data(picture),
        canvasShape=[int(c) for c in _fixed_shape(fixed)],
        imageBox=image_box(fig.im),
        spines=spine_lines(ax),
        fill=255,
        fixed=_jsonable(fixed),
        outline=np.column_stack(fig.outline_art.get_data()).astype(float).tolist(),
        before=np.column_stack(before.get_data()).astype(float).tolist(),
        facts=_each_text(fig.facts, texts),
        torn=torn,
        styles=dict(
            outline=haloed_line_style(fig.outline_art, pt),
            grid=haloed_line_style(fig.grid_art, pt),
            horizon=line_style(fig.horizon_art, pt),
            # an open ring: its face transparent
            before=dict(
                marker_style(before, pt),
                color=to_hex(before.get_markerfacecolor(), keep_alpha=True),
            ),
            after=marker_style(fig.diagonal_art, pt),
            facts=text_style(fig.facts),
            warning=warning,
        ),
    )
