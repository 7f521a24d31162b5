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

__all__ = [
    "drag_scene",
    "forward_inverse_scene",
    "halo_style",
    "haloed_marker_style",
    "haloed_line_style",
    "hierarchy_scene",
    "image_box",
    "image_place",
    "patch_outline",
    "picture_data",
]


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


def halo_style(artist: Any, px_per_point: float) -> dict:
    """An artist's ``palette.halo`` (its one ``withStroke``) as ``halo`` (colour) and ``haloWidth`` (px).

    Parameters
    ----------
    artist : matplotlib.artist.Artist
        A line or text drawn with one ``withStroke`` path effect.
    px_per_point : float
        Canvas pixels per typographic point (the figure's dpi / 72).

    Returns
    -------
    dict
        ``halo`` (hex colour) and ``haloWidth`` (canvas pixels).
    """
    stroke = artist.get_path_effects()[0]._gc  # noqa: SLF001 - withStroke keeps its linewidth and foreground here
    return dict(
        halo=to_hex(stroke["foreground"]), haloWidth=float(stroke["linewidth"]) * px_per_point
    )


def haloed_marker_style(line: Any, px_per_point: float) -> dict:
    """:func:`~camlab.widgets.browser.marker_style` with the marker's halo (``palette.halo``).

    Parameters
    ----------
    line : matplotlib.lines.Line2D
        A line drawn with a round marker and one ``withStroke`` path effect.
    px_per_point : float
        Figure dpi / 72.

    Returns
    -------
    dict
        The marker's style (a face of "none" transparent, and ``hollow``), with ``halo`` and
        ``haloWidth``.
    """
    face = line.get_markerfacecolor()
    hollow = isinstance(face, str) and face == "none"
    return dict(
        marker_style(line, px_per_point),
        color=to_hex(face, keep_alpha=True),
        hollow=hollow,
        **halo_style(line, px_per_point),
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


def image_place(image: Any) -> dict:
    """Where the live canvas puts a pixelated image: its rounded box and its unrounded edges.

    ``homography.js``'s ``liveImage`` repeats what ``widgets/_transport.py`` does with an image
    shown with ``interpolation="nearest"``: kept at most at its box's size (OpenCV's nearest shrink),
    then, where the box is larger, each canvas pixel takes the data pixel under its centre, found
    from the extent's unrounded edges (``_nearest_at_centres``). For an image with row 0 at the top
    and columns left to right (``imshow``'s default), inside its axes.

    Parameters
    ----------
    image : matplotlib.image.AxesImage
        The image, after the figure's layout is fixed.

    Returns
    -------
    dict
        ``box`` (:func:`image_box`), ``us`` and ``vs`` (the extent's edges in display px, left and
        right, bottom and top: y up) and ``canvasHeight`` (the rows y is flipped about).
    """
    x0, x1, y0, y1 = image.get_extent()
    row0_y = y1 if image.origin == "upper" else y0
    (u_left, v_row0), (u_right, v_rown) = image.get_transform().transform(
        [(x0, row0_y), (x1, y0 + y1 - row0_y)]
    )
    return dict(
        box=image_box(image),
        us=sorted((float(u_left), float(u_right))),
        vs=sorted((float(v_row0), float(v_rown))),
        canvasHeight=canvas_height(image.figure),
    )


def patch_outline(patch: Any) -> dict:
    """An unfilled patch's outline as a closed canvas polyline with its look (``drawing.js``'s ``polyline``).

    Parameters
    ----------
    patch : matplotlib.patches.Patch
        The patch (a rectangle's frame), after the figure's layout is fixed.

    Returns
    -------
    dict
        ``points`` (its path's vertices, canvas px) and ``style`` (colour, width, joins, caps;
        closed, snapped as matplotlib snaps it).
    """
    fig = patch.figure
    xy = patch.get_transform().transform_path(patch.get_path()).vertices
    caps = {"butt": "butt", "round": "round", "projecting": "square"}
    return dict(
        points=np.column_stack([xy[:, 0], canvas_height(fig) - xy[:, 1]]).tolist(),
        style=dict(
            color=to_hex(patch.get_edgecolor()),
            width=patch.get_linewidth() * fig.dpi / 72.0,
            dash=[],
            join=patch.get_joinstyle(),
            cap=caps[patch.get_capstyle()],
            snap=patch.get_snap() is not False,
            closed=True,
        ),
    )


def forward_inverse_scene(
    images: Mapping[str, Any], frames: Any, picture: np.ndarray, fixed: Mapping[str, Any]
) -> dict:
    """What ``forward_inverse.js`` needs to draw lesson 07's ``forward_vs_inverse`` as matplotlib draws it.

    Parameters
    ----------
    images : mapping
        The four animated images by name: ``forward``, ``forward_zoom``, ``inverse_zoom``,
        ``inverse`` (the zoomed ones with their window's extent).
    frames : sequence of matplotlib.patches.Rectangle
        The yellow frames of the zoomed window, over the forward and the inverse warp.
    picture : (h, w, 3) uint8 ndarray
        The picture the browser warps.
    fixed : mapping
        :func:`~camlab.widgets.homographies.twins.forward_inverse_fixed`'s constants.

    Returns
    -------
    dict
        The scene (JSON): the picture, the constants (with the holes' colour and the grey outside),
        the zoomed window (top, left, height, width: output px) and, per panel in the order a full
        draw paints them, its image's name and place, its frames and its spines.
    """
    zoom = images["forward_zoom"]
    x0, x1, y0, y1 = zoom.get_extent()  # (left - 0.5, left + w - 0.5, top + h - 0.5, top - 0.5)
    window = [round(y1 + 0.5), round(x0 + 0.5), round(y0 - y1), round(x1 - x0)]
    panels = []
    for name, image in images.items():
        ax = image.axes
        panels.append(
            dict(
                image=name,
                place=image_place(image),
                frames=[patch_outline(f) for f in frames if f.axes is ax],
                spines=spine_lines(ax),
                order=image.figure.axes.index(ax),
            )
        )
    panels.sort(key=lambda p: p["order"])
    return dict(
        picture=picture_data(picture),
        fixed=dict(
            C=np.asarray(fixed["C"], float).tolist(),
            P=np.asarray(fixed["P"], float).tolist(),
            tilt=np.asarray(fixed["tilt"], float).tolist(),
            edges=np.asarray(fixed["edges"], float).tolist(),
            shape=[int(c) for c in fixed["shape"]],
            hole=[int(c) for c in fixed["hole"]],
            outside=int(fixed["outside"]),
        ),
        zoom=window,
        panels=panels,
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
        imagePlace=image_place(fig.im),
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


def drag_scene(
    axes: Any, art: Any, picture: np.ndarray, fixed: Mapping[str, Any], notes: Mapping[str, Any]
) -> dict:
    """What ``drag.js`` needs to draw lesson 07's ``drag_homography`` as matplotlib draws it.

    Parameters
    ----------
    axes : (2,) sequence of matplotlib.axes.Axes
        The source picture's axes and the target's.
    art : namespace
        The moving artists (``_drag_artists``): ``sent_away``, ``im``, ``quad``,
        ``mapped_line``, ``mapped_dots``, ``mapped_names``, ``handles``, ``chosen``, ``numbers``
        and ``warning`` (its ``artist``, the note on a box).
    picture : (h, w, 3) uint8 ndarray
        The picture the browser warps.
    fixed : mapping
        :func:`~camlab.widgets.homographies.corner_twins.drag_view`'s constants.
    notes : mapping
        ``torn`` (the note on a torn picture), ``longest`` (a note of as many lines as any the
        demo shows), ``margin`` (the corner sliders' stop short of a dent, px) and ``radius``
        (how near a press picks a corner, px).

    Returns
    -------
    dict
        The scene (JSON).
    """
    ax_s, ax_t = axes
    pt = ax_t.figure.dpi / 72.0
    note = art.warning.artist
    shown, visible = note.get_text(), note.get_visible()
    note.set_text(notes["longest"])  # the box's look and lines, top-aligned: any note's first lines
    try:
        warning = boxed_text_scene(note)
    finally:
        note.set_text(shown)
        note.set_visible(visible)
    name = art.mapped_names[0]
    return dict(
        source=plane_panel(ax_s),
        target=plane_panel(ax_t),
        picture=picture_data(picture),
        canvasShape=[int(c) for c in fixed["out_hw"]],
        imagePlace=image_place(art.im),
        fill=255,
        spines=spine_lines(ax_t),
        fixed={
            k: (list(v) if k == "out_hw" else np.asarray(v, dtype=float).tolist())
            for k, v in fixed.items()
        },
        names=[label.get_text() for label in art.mapped_names],
        torn=notes["torn"],
        margin=float(notes["margin"]),
        radius=float(notes["radius"]),
        styles=dict(
            away=line_style(art.sent_away, pt),
            quad=haloed_line_style(art.quad, pt),
            mappedLine=haloed_line_style(art.mapped_line, pt),
            mappedDots=marker_style(art.mapped_dots, pt),
            handles=haloed_marker_style(art.handles, pt),
            chosen=haloed_marker_style(art.chosen, pt),
            names=dict(text_style(name), **halo_style(name, pt)),
            numbers=dict(text_style(art.numbers), **text_lines(art.numbers)),
            warning=warning,
        ),
    )
