"""Lesson 07 demos on what a homography does: the transformation hierarchy and four dragged corners."""

from __future__ import annotations

import textwrap
from types import SimpleNamespace

import ipywidgets as W
import numpy as np

from ... import homography as hg
from ... import scenes
from ...plotting import palette
from ...projective import (
    cross_ratio,
    map_points,
)
from ...warp import warp_perspective
from .._base import Demo, build_demo, register, slider
from ..browser import BrowserView
from ..browser.homography_scenes import drag_scene, hierarchy_scene
from ..controls import (
    connect_corner_drag,
    convex_clamp,
    corner_keys,
    corner_text,
    format_corners,
    monospace,
)
from .corner_twins import across_line, drag_table_text, drag_view, length_ratio, shown_measure
from .notes import TORN_DRAG, TORN_SHORT, warning_note
from .twins import diagonal_points as _diagonal_points
from .twins import hierarchy_fixed, hierarchy_view

# ----------------------------------------------------------------------------- hierarchy

_GROUPS = tuple(hg.HIERARCHY)  # euclidean, similarity, affine, projective
_SLIDERS_USED = {  # the sliders each group's matrix reads; the others are greyed out
    "euclidean": {"theta", "tx", "ty"},
    "similarity": {"theta", "tx", "ty", "scale"},
    "affine": {"theta", "tx", "ty", "scale", "phi", "aspect"},
    "projective": {"theta", "tx", "ty", "scale", "phi", "aspect", "v1", "v2"},
}
HIERARCHY_PARAMS = ("group", "theta", "scale", "phi", "aspect", "tx", "ty", "v1", "v2")
"""The hierarchy demo's controls, which the browser redraws on."""
_GROUP_NAMES = {
    "euclidean": "Euclidean",
    "similarity": "similarity",
    "affine": "affine",
    "projective": "projective",
}
_A_MAP = {
    "euclidean": "a Euclidean map",
    "similarity": "a similarity",
    "affine": "an affinity",
    "projective": "a projective map",
}


def _hierarchy_texts(group, kind, Hg, H, picture_shape, canvas_hw):
    """The hierarchy demo's two texts: the facts beside the canvas, and the readout.

    Parameters
    ----------
    group, kind : str
        The chosen group, and the smallest group holding ``Hg``.
    Hg, H : (3, 3) ndarray
        The group's matrix (centred coordinates) and the map drawn, C Hg P.
    picture_shape, canvas_hw : tuple of int
        The picture's shape and the canvas (height, width).

    Returns
    -------
    tuple of str
        The facts (group, dof, what it keeps) and the readout (both matrices).
    """
    info = hg.HIERARCHY[group]
    ph, pw = picture_shape[:2]
    keeps = [f"- {name}" for name in info["own"]]
    if info["larger"]:
        keeps.append(
            f"+ all that {'an' if info['larger'] == 'affine' else 'a'} {info['larger']} map keeps"
        )
    facts = (
        f"{_GROUP_NAMES[group]}: {info['dof']} dof\n(H itself is {_A_MAP[kind]})\n\nkeeps:\n"
        + "\n".join("\n".join(textwrap.wrap(k, 24, subsequent_indent="  ")) for k in keeps)
    )
    readout = (
        f"{_GROUP_NAMES[group]}: {info['dof']} dof\n"
        "H, in coordinates centred on the picture and the canvas (what the sliders set;\n"
        "θ turns about the picture's centre) =\n"
        + _matrix_text(Hg)
        + "\nthe map drawn, from source pixels to canvas pixels, C H P =\n"
        + _matrix_text(H)
        + f"\n(P moves the picture's centre ({(pw - 1) / 2:g}, {(ph - 1) / 2:g}) to 0,"
        f" C moves 0 to the canvas centre ({(canvas_hw[1] - 1) / 2:g}, {(canvas_hw[0] - 1) / 2:g}))"
        + f"\nsmallest group holding H: {kind}\nkeeps: "
        + ", ".join(info["invariants"])
    )
    return facts, readout


def _hierarchy_measures(H: np.ndarray, picture_shape) -> dict:
    """What the hierarchy demo measures on the picture's outline, before and after H.

    Parameters
    ----------
    H : (3, 3) ndarray
        The map drawn, source pixels to canvas pixels.
    picture_shape : tuple of int
        The picture's shape (height, width, ...).

    Returns
    -------
    dict
        Name -> (before, after, kept): the top-left angle (degrees, from the mapping's derivative,
        ``hg.mapped_angle``), the top edge's length (px: Euclidean maps keep it), the ratio of the
        top and left edges (two directions: similarities keep it), of the top and bottom edges
        (parallel: affinities keep it), the angles between the mapped top and bottom edges and
        between the left and right ones (0: still parallel) and the cross-ratio of four points on
        the diagonal (every homography keeps it). A length or ratio with an edge through infinity
        is ``inf``. *kept* means within 0.1° for the angles (absolute: a 1° change reads
        *changes*), within 0.1 % of the value for lengths and ratios, and within 1e-6 of it for
        the cross-ratio.
    """
    ph, pw = picture_shape[:2]
    tl, tr, br, bl = np.array([[0.0, 0.0], [pw - 1, 0.0], [pw - 1, ph - 1], [0.0, ph - 1]])
    w = np.c_[[tl, tr, br, bl], np.ones(4)] @ H[2]
    m = map_points(H, [tl, tr, br, bl])

    def length(i: int, j: int) -> float:  # an edge's image; infinite when w changes sign along it
        return float(np.linalg.norm(m[i] - m[j])) if w[i] * w[j] > 0 else np.inf

    def between(x1: np.ndarray, x2: np.ndarray, axis: int) -> float:
        """The angle (degrees) between the images of one source direction at x1 and at x2 (J d, J as in mapped_angle)."""
        d1, d2 = (
            (H[:2, axis] - map_points(H, x) * H[2, axis]) / (H[2] @ [*x, 1.0]) for x in (x1, x2)
        )
        return float(np.degrees(np.arctan2(abs(d1[0] * d2[1] - d1[1] * d2[0]), abs(d1 @ d2))))

    diagonal = _diagonal_points(picture_shape)
    # (before, after, tolerance, absolute?): angles within 0.1° absolutely, lengths and ratios
    # within 0.1 % of their value, the cross-ratio within 1e-6 of its value
    rows = {
        "top-left angle (°)": (90.0, hg.mapped_angle(H, tl, tr - tl, bl - tl), 0.1, True),
        "|top| (px)": (pw - 1.0, length(0, 1), 1e-3, False),
        "|top| / |left|": (
            (pw - 1) / (ph - 1),
            length_ratio(length(0, 1), length(0, 3)),
            1e-3,
            False,
        ),
        "|top| / |bottom|": (1.0, length_ratio(length(0, 1), length(3, 2)), 1e-3, False),
        "top vs bottom edge (°)": (0.0, between(tl, bl, 0), 0.1, True),
        "left vs right edge (°)": (0.0, between(tl, tr, 1), 0.1, True),
        "cross-ratio, diagonal": (
            cross_ratio(diagonal),
            cross_ratio(map_points(H, diagonal)),
            1e-6,
            False,
        ),
    }
    return {
        k: (a, b, bool(abs(b - a) <= (tol if absolute else tol * abs(a))))
        for k, (a, b, tol, absolute) in rows.items()
    }


def _measures_text(measures: dict) -> str:
    """The hierarchy readout's table of measured invariants: before, after, kept or changes."""
    lines = [f"{'measured on the picture':24s}{'source':>9s}{'mapped':>10s}"]
    for name, (a, b, kept) in measures.items():
        verdict = "kept" if kept else ("(∞ / ∞)" if np.isnan(b) else "changes")
        lines.append(f"{name:24s}{a:9.3f}{shown_measure(b, '.3f'):>10s}  {verdict}")
    return "\n".join(lines)


def _diagonal_artists(view, ax, before):
    """The four diagonal points of the cross-ratio: before H (open) and mapped (filled).

    Both are animated: the warped picture is an animated image, and a static marker would sit in
    the cached background under it, lost in every live frame. Returns the two lines, before first.
    """
    before_art = view.animate(
        ax.plot(
            *before.T,
            "o",
            color=palette.BROWN,
            mfc="none",
            mec=palette.BROWN,
            path_effects=palette.halo(1),  # readable over the dark picture too
            mew=1.5,
            ms=10,
            zorder=4,
            label="cross-ratio points, before H",
        )[0]
    )
    after_art = view.animate(
        ax.plot(
            [],
            [],
            "o",
            color=palette.BROWN,
            mec="white",
            mew=1.0,
            ms=7,
            zorder=5,
            label="cross-ratio points, after H",
        )[0]
    )
    return before_art, after_art


def _hierarchy_figure(pic, C, P, canvas_hw):
    """The hierarchy demo's figure: its view, the animated artists and the grid lines to map.

    Parameters
    ----------
    pic : (h, w, 3) ndarray
        The picture.
    C, P : (3, 3) ndarray
        The canvas-centring and picture-centring translations.
    canvas_hw : tuple of int
        The canvas (height, width).

    Returns
    -------
    SimpleNamespace
        ``view``, ``ax``, ``im``, ``grid_art``, ``horizon_art``, ``diagonal_art`` (and
        ``diagonal_before``, ``outline_art``: animated, never moved), ``facts``, ``warning``,
        ``xlim``, ``ylim``.
    """
    ph, pw = pic.shape[:2]
    xlim, ylim = (-0.5, canvas_hw[1] - 0.5), (-0.5, canvas_hw[0] - 0.5)
    # drawn in the browser when a kernel shows it (browser/hierarchy.js), the group a choice
    view = BrowserView(HIERARCHY_PARAMS, figsize=(8.5, 4.2), choices=("group",))
    ax = view.fig.subplots()
    ax.set(xlim=xlim, ylim=ylim[::-1], aspect="equal", xlabel="u (pixels)", ylabel="v (pixels)")
    im = view.animate(
        ax.imshow(
            np.zeros((*canvas_hw, 3), np.uint8),
            interpolation="nearest",
            extent=(xlim[0], xlim[1], ylim[1], ylim[0]),
        )
    )
    outline0 = C @ P
    box0 = map_points(
        outline0, np.array([[0, 0], [pw - 1, 0], [pw - 1, ph - 1], [0, ph - 1], [0, 0]], float)
    )
    outline_art = view.animate(
        ax.plot(
            box0[:, 0],
            box0[:, 1],
            ":",
            color="0.2",
            lw=1.5,
            label="original outline",
            path_effects=palette.halo(1.5),  # over the dark mapped picture too
        )[0]
    )
    grid_art = view.animate(
        ax.plot(
            [],
            [],
            color=palette.ORANGE,
            lw=1,
            path_effects=palette.halo(1),
            label="grid mapped by H",
        )[0]
    )
    horizon_art = view.animate(
        ax.plot(
            [],
            [],
            "--",
            color=palette.PURPLE,
            lw=2,
            label="vanishing line (image\nof l∞), when in view",
        )[0]
    )
    diagonal_before, diagonal_art = _diagonal_artists(
        view, ax, map_points(outline0, _diagonal_points(pic.shape))
    )
    ax.set_title(
        "the picture mapped by H about its centre (group, dof, invariants at the right)",
        fontsize=10,
        pad=10,  # clear of the top tick label "0", which stands half its height above the axes
    )
    # beside the axes: over the warped picture the legend would need a redraw per update
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=9)
    # The group, its dof and what it keeps, in the figure itself (a static page has no readout).
    facts = view.animate(
        ax.text(
            1.03, 0.6, "", transform=ax.transAxes, ha="left", va="top", fontsize=9, linespacing=1.3
        )
    )
    warning = warning_note(
        view, ax, 1.03, 0.0, "left", "bottom"
    )  # beside the canvas, never over it
    return SimpleNamespace(
        view=view,
        ax=ax,
        im=im,
        grid_art=grid_art,
        horizon_art=horizon_art,
        diagonal_art=diagonal_art,
        diagonal_before=diagonal_before,
        outline_art=outline_art,
        facts=facts,
        warning=warning,
        xlim=xlim,
        ylim=ylim,
    )


@register(
    lesson="07",
    sweep={
        "group": list(_GROUPS),
        "theta": [-30.0, 20.0],
        "phi": [0.0, 40.0],
        "v1": [0.0, 2.0, 14.0],
        "tx": [-20.0, 30.0],
    },
)
def transformation_hierarchy() -> Demo:
    """Euclidean, similarity, affine, projective: sliders for each group acting on a picture.

    The group's matrix :math:`H_g` (:func:`camlab.homography.hierarchy_matrix`, which uses
    only the parameters its group has) acts about the picture's centre: the picture
    shown is mapped by :math:`H = C H_g P`, where P moves the 160 x 120 picture's centre to
    the origin and C the origin to the centre of the 480 x 360 canvas. The image of the
    line at infinity (the vanishing line, H^-T l∞) is drawn when H moves it into view; the
    group's dof and what it keeps are printed beside the picture, and a black note says when
    the picture is torn (the line H sends to infinity crosses it).

    Returns
    -------
    Demo
        The demo: controls ``group`` (``"euclidean"``, ``"similarity"``, ``"affine"`` or
        ``"projective"``), ``theta`` (the rotation, degrees), ``scale``, ``phi`` (the angle
        of the affine stretch's axes, degrees), ``aspect`` (the affine stretch, √(sx/sy)),
        ``tx`` and ``ty`` (the translation, px) and ``v1``, ``v2`` (the projective bottom
        row, in units of 1e-3), the figure (the mapped picture with the original outline,
        the mapped grid and the vanishing line) and ``state``
        (``H`` the group's matrix :math:`H_g`, ``group``, ``classified`` the smallest group
        holding it, ``dof``, ``torn``, ``vanishing_line_in_view``).

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 2.4 (a
       hierarchy of transformations), table 2.1.
    """
    pic = scenes.house_picture()
    canvas_hw = (360, 480)
    # Picture coordinates centred on the origin; C places the origin at the canvas centre.
    # Pixel centres at integers: the centre of a W-pixel axis is (W - 1) / 2, so (239.5, 179.5).
    fixed = hierarchy_fixed(pic.shape, canvas_hw)
    fig = _hierarchy_figure(pic, fixed["C"], fixed["P"], canvas_hw)
    view, im, grid_art, horizon_art = fig.view, fig.im, fig.grid_art, fig.horizon_art
    facts, warning = fig.facts, fig.warning
    readout = W.HTML()

    def update(v: dict, state: dict) -> None:
        # the per-move geometry (its twin hierarchyView in the browser's homography.js)
        g = hierarchy_view(v, fixed)
        Hg, H, kind, torn = g.Hg, g.H, g.kind, g.torn
        for name, control in controls.items():  # grey out what the group ignores
            control.disabled = name != "group" and name not in _SLIDERS_USED[v["group"]]
        # cv2's warp, fast; the browser warps with the twin of warp_perspective's numpy path
        im.set_data(warp_perspective(pic, H, canvas_hw, method="cv2", fill=255))
        grid_art.set_data(g.grid[:, 0], g.grid[:, 1])
        # the four points of the cross-ratio, mapped
        fig.diagonal_art.set_data(*g.diagonal.T)
        # l' = H^-T l_inf: where parallel lines of the picture meet (outside the view for affine H)
        vanishing = g.vanishing
        horizon_art.set_data(vanishing[:, 0], vanishing[:, 1])
        info = hg.HIERARCHY[v["group"]]
        warning(TORN_SHORT if torn else "")
        state.update(
            H=Hg,
            H_canvas=H,
            group=v["group"],
            classified=kind,
            dof=info["dof"],
            torn=torn,
            vanishing_line_in_view=bool(np.isfinite(vanishing).all()),
        )
        facts_text, readout_text = _hierarchy_texts(v["group"], kind, Hg, H, pic.shape, canvas_hw)
        state["measures"] = _hierarchy_measures(H, pic.shape)
        facts.set_text(facts_text)
        readout.value = monospace(_measures_text(state["measures"]) + "\n\n" + readout_text)

    controls = {
        "group": W.Dropdown(options=list(_GROUPS), value="affine", description="group"),
        "theta": slider(15.0, -180.0, 180.0, 1.0, "rotation θ (°)"),
        "scale": slider(1.2, 0.3, 2.5, 0.05, "scale s"),
        "phi": slider(60.0, -90.0, 90.0, 1.0, "affine: stretch axes φ (°)"),
        "aspect": slider(1.4, 0.4, 2.5, 0.05, "affine: stretch √(sx/sy)"),
        "tx": slider(0.0, -100.0, 100.0, 1.0, "tx (px)"),
        "ty": slider(0.0, -80.0, 80.0, 1.0, "ty (px)"),
        "v1": slider(1.5, -15.0, 15.0, 0.1, "projective: v1 (×1e-3 /px)"),
        "v2": slider(0.0, -15.0, 15.0, 0.1, "projective: v2 (×1e-3 /px)"),
    }
    demo = build_demo(
        "transformation_hierarchy",
        controls,
        view,
        update,
        title="The transformation hierarchy",
        extra=[readout],
    )
    # the texts beside the canvas for each group and the smallest group holding its matrix
    texts = {
        g: {
            k: _hierarchy_texts(g, k, np.eye(3), np.eye(3), pic.shape, canvas_hw)[0]
            for k in _GROUPS
        }
        for g in _GROUPS
    }
    view.publish(
        demo, hierarchy_scene(fig, pic, fixed, texts, TORN_SHORT)
    )  # the browser draws the moves
    return demo


# ----------------------------------------------------------------------------- drag corners

SQUARE = np.array([[0.0, 0.0], [159.0, 0.0], [159.0, 119.0], [0.0, 119.0]])
CORNER_NAMES = (
    "top left",
    "top right",
    "bottom right",
    "bottom left",
)  # of the source picture, SQUARE's order
_DRAG_START = np.array([[40.0, 30.0], [250.0, 60.0], [230.0, 200.0], [60.0, 230.0]])
DRAG_PARAMS = ("corners", "corner", "corner_u", "corner_v")
"""The drag demo's controls, which the browser redraws on (the corners text and its keyboard twins)."""
DRAG_RADIUS_PX = 15.0
"""How near a press must be to a corner to pick it (figure px)."""
SLIDER_MARGIN_PX = 40.0
"""How far short of a dent or bow tie the corner sliders stop a corner (px; typing or a drag go on)."""


def _matrix_text(M: np.ndarray, significant: int | None = None) -> str:
    """A matrix as the readouts print it: 4 decimals, and what rounds to zero printed as 0, never -0.

    Parameters
    ----------
    M : ndarray
        The matrix.
    significant : int, optional
        Print this many significant digits instead of 4 decimals, so that a small entry such as
        h31 = -0.00704 keeps its digits (the drag demo's H must reproduce its table). Entries
        below 1e-12 of the largest are round-off of the solve and print as 0, so an affine H's
        third row reads (0, 0, 1).

    Returns
    -------
    str
        ``np.array2string`` of M with its negative zeros cleared.
    """
    M = np.asarray(M, dtype=float)
    if significant is not None:
        M = np.where(np.abs(M) <= 1e-12 * np.abs(M).max(), 0.0, M)
        return np.array2string(
            M, formatter={"float_kind": lambda x: f"{x:>{significant + 6}.{significant}g}"}
        )
    return np.array2string(np.where(np.round(M, 4) == 0, 0.0, M), precision=4, suppress_small=True)


def _off_canvas(points, out_hw) -> str:
    """A readout line naming the mapped points A'..D' that fall off the canvas ("" if none)."""
    with np.errstate(invalid="ignore"):
        seen = np.all((points >= -0.5) & (points <= [out_hw[1] - 0.5, out_hw[0] - 0.5]), axis=1)
    off = [f"{name}'" for name, inside in zip("ABCD", seen, strict=True) if not inside]
    return f"\n{', '.join(off)} off the canvas" if off else ""


def _unlabelled(labels, points, out_hw) -> str:
    """A readout line naming the mapped points on the canvas whose names are hidden ("" if none)."""
    with np.errstate(invalid="ignore"):
        seen = np.all((points >= -0.5) & (points <= [out_hw[1] - 0.5, out_hw[0] - 0.5]), axis=1)
    hidden = [
        f"{name}'"
        for name, label, inside in zip("ABCD", labels, seen, strict=True)
        if inside and not label.get_visible()
    ]
    if not hidden:
        return ""
    return f"\n{', '.join(hidden)} drawn without a name: under a corner handle, near the edge or beside another name"


def _drag_notes(labels, points, out_hw, H) -> str:
    """The drag readout under its table: points off the canvas or unnamed, and H to 5 significant digits."""
    return (
        _off_canvas(points, out_hw)
        + _unlabelled(labels, points, out_hw)
        + "\nH (h33 = 1, 5 significant digits) =\n"
        + _matrix_text(H / H[2, 2], significant=5)
    )


def _dense_outline(quad: np.ndarray) -> np.ndarray:
    """A closed quadrilateral's four sides, 40 points each (dense, so a map through infinity shows its break)."""
    return np.vstack(
        [quad[i] + np.linspace(0, 1, 40)[:, None] * (quad[(i + 1) % 4] - quad[i]) for i in range(4)]
    )


def _drag_artists(view, ax_s, ax_t, out_hw) -> SimpleNamespace:
    """The drag demo's animated artists: the line sent to infinity, the warp, the mapped marks and the texts."""
    sent_away = view.animate(ax_s.plot([], [], "--", color=palette.PURPLE, lw=2)[0])
    im = view.animate(
        ax_t.imshow(
            np.zeros((*out_hw, 3), np.uint8),
            extent=(-0.5, out_hw[1] - 0.5, out_hw[0] - 0.5, -0.5),
            interpolation="nearest",  # as the hierarchy demo: a live frame then equals the first draw
        )
    )
    quad = view.animate(
        ax_t.plot([], [], "-", color=palette.ORANGE, lw=1, path_effects=palette.halo(1))[0]
    )
    mapped_line = view.animate(
        ax_t.plot([], [], "-", color=palette.BROWN, lw=1.5, path_effects=palette.halo(1.5))[0]
    )
    mapped_dots = view.animate(ax_t.plot([], [], "o", color=palette.BROWN, ms=5, mec="white")[0])
    mapped_names = [
        view.animate(
            ax_t.annotate(
                f"{name}'",
                (np.nan, np.nan),
                xytext=(4, 6),
                textcoords="offset points",
                ha="center",
                va="center",
                fontsize=9,
                color="k",
                path_effects=palette.halo(),
            )
        )
        for name in "ABCD"
    ]
    # white halos: drawn "nearest", the picture under a corner can be as dark as the marks
    handles = view.animate(
        ax_t.plot([], [], "o", color=palette.ORANGE, ms=10, mec="k", path_effects=palette.halo(1))[
            0
        ]
    )
    chosen = view.animate(
        ax_t.plot([], [], "o", ms=17, mfc="none", mec="k", mew=2, path_effects=palette.halo(1))[0]
    )  # the corner the keys move
    numbers = view.animate(
        ax_s.text(
            0.0,
            -0.27,
            "",
            transform=ax_s.transAxes,
            ha="left",
            va="top",
            fontsize=8,
            family="monospace",
        )
    )
    warning = warning_note(
        view, ax_s, 0.0, -0.62, "left", "top"
    )  # under the numbers, off the target
    return SimpleNamespace(
        sent_away=sent_away,
        im=im,
        quad=quad,
        mapped_line=mapped_line,
        mapped_dots=mapped_dots,
        mapped_names=mapped_names,
        handles=handles,
        chosen=chosen,
        numbers=numbers,
        warning=warning,
    )


def _show_drag_view(art, g, warped, chosen: int) -> None:
    """Move the drag demo's artists to ``g`` (:func:`.corner_twins.drag_view`), the picture ``warped`` by its H."""
    art.warning(TORN_DRAG if g.torn else "")
    # H^T l_inf = (h31, h32, h33): the source line that H sends to infinity (drawn if in view)
    art.sent_away.set_data(g.away[:, 0], g.away[:, 1])
    art.im.set_data(warped)
    art.mapped_line.set_data(g.dense[:, 0], g.dense[:, 1])
    art.mapped_dots.set_data(g.mapped[:, 0], g.mapped[:, 1])
    for label, p, offset, shown in zip(art.mapped_names, g.mapped, *g.names, strict=True):
        label.xy, label.xyann = tuple(p), tuple(offset)
        label.set_visible(bool(shown))
    art.quad.set_data(g.outline[:, 0], g.outline[:, 1])
    art.handles.set_data(g.corners[:, 0], g.corners[:, 1])
    art.chosen.set_data(g.corners[chosen, :1], g.corners[chosen, 1:])


def _drag_axes(ax_s, ax_t, pic, out_hw) -> None:
    """The drag demo's two axes: the source picture (anchored at the top) and the empty target canvas."""
    ph, pw = pic.shape[:2]
    ax_s.imshow(pic)
    ax_s.set_anchor("N")  # the room under the source picture holds the numbers and the warning
    ax_s.set(xlabel="u (pixels)", ylabel="v (pixels)")
    ax_s.set_title("source picture", fontsize=10, pad=3)
    ax_s.set(xlim=(-0.5, pw - 0.5), ylim=(ph - 0.5, -0.5))
    ax_t.set(xlim=(-0.5, out_hw[1] - 0.5), ylim=(out_hw[0] - 0.5, -0.5), aspect="equal")
    ax_t.set(xlabel="u (pixels)", ylabel="v (pixels)")
    ax_t.set_title("drag a corner, or use the sliders", fontsize=10, pad=3)


def _drag_fixed(picture_shape, out_hw) -> dict:
    """The drag demo's constants (:func:`.corner_twins.drag_view`'s ``fixed``).

    Four collinear points A..D on the picture's diagonal (their cross-ratio is the invariant), the
    line and the picture's outline sampled densely, the picture's edges and the target canvas.
    """
    ph, pw = picture_shape[:2]
    line_pts = np.array([[10.0, 10.0], [50.0, 40.0], [90.0, 70.0], [140.0, 107.5]])
    return dict(
        square=SQUARE,
        line=line_pts,
        line_dense=line_pts[0] + np.linspace(0, 1, 80)[:, None] * (line_pts[3] - line_pts[0]),
        square_dense=_dense_outline(SQUARE),
        xlim=(-0.5, pw - 0.5),
        ylim=(-0.5, ph - 0.5),
        out_hw=out_hw,
    )


def _drag_line_names(ax_s, line_pts) -> None:
    """The points A..D on the source picture's diagonal, with their names."""
    ax_s.plot(*line_pts.T, "o-", color=palette.BROWN, ms=5, lw=1.5, path_effects=palette.halo(1.5))
    # centred across the line, clear of its halo and dots: B, C, D above it (below B lies the
    # bow tie's dashed line, below D the frame), A to its right (left of A is the dark border)
    across = across_line(line_pts)
    offsets = [(15.0, 0.0), *(tuple(k * across) for k in (18, 18, 16))]
    for name, p, offset in zip("ABCD", line_pts, offsets, strict=True):
        ax_s.annotate(
            name,
            p,
            xytext=offset,
            textcoords="offset points",
            ha="center",
            va="center",
            fontsize=9,
            color="k",
            path_effects=palette.halo(),
        )  # black on a white halo: readable on any colour


def _drag_keys(control, out_hw, browser: bool) -> dict:
    """The corner sliders, stopped short of a dent or bow tie (typed or dragged corners go anywhere)."""
    return corner_keys(
        control,
        CORNER_NAMES,
        out_hw[1] - 1,
        out_hw[0] - 1,
        clamp=convex_clamp(SLIDER_MARGIN_PX),
        browser_syncs=browser,
    )


@register(
    lesson="07",
    sweep={
        "corners": [
            format_corners(_DRAG_START),
            "20.0, 20.0; 280.0, 20.0; 280.0, 230.0; 20.0, 230.0",
            "100.0, 40.0; 200.0, 40.0; 280.0, 230.0; 20.0, 230.0",
        ],
        "corner": [0, 2],
        "corner_u": [10.0, 290.0],
        "corner_v": [10.0, 250.0],
    },
)
def drag_homography() -> Demo:
    """Drag the four target corners: lines and the cross-ratio stay, lengths and angles change.

    H maps the 160 x 120 source picture's corners (:data:`SQUARE`, in the order of
    :data:`CORNER_NAMES`) to the four target corners
    (:func:`camlab.homography.estimate_homography`). Four collinear points A, B, C, D of the
    picture and their images A', B', C', D' are marked; under the source picture, the
    cross-ratio, the ratio of lengths |AB| / |CD| and the top-left corner's angle are
    printed for the source and the image. When the source line that H sends to infinity
    crosses the picture it is drawn (purple, dashed) and a black note says the picture is
    torn. Without a mouse, pick a corner and move it with its two sliders (or type the
    corners).

    Returns
    -------
    Demo
        The demo: controls ``corners`` (the text ``"u0, v0; u1, v1; u2, v2; u3, v3"``, the
        target corners in :data:`CORNER_NAMES`' order, px) and ``corner`` (the corner its
        linked ``corner_u`` and ``corner_v`` sliders move), the figure (the source picture
        with A-D and the numbers; the warped picture with its outline, A'-D' and the
        corners to drag) and ``state`` (``H`` source to target pixels, ``corners``,
        ``corner``, ``torn``, ``cross_ratio_source`` and ``cross_ratio_image``,
        ``length_ratio_source`` and ``length_ratio_image`` (|AB| / |CD|), ``corner_angle``
        the angle in degrees between the two mapped edges at the top-left corner (their
        tangents there, right also when an edge passes through infinity), ``error``: the message when the corners
        cannot be used, else None). ``handlers`` holds the mouse handlers of the corner
        drag.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 2.5 (the
       projective geometry of 1D: the cross ratio).
    .. [2] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 4.1 (the
       direct linear transformation).
    """
    pic = scenes.house_picture()
    out_hw = (260, 300)
    view = BrowserView(DRAG_PARAMS, figsize=(9, 4.6), choices=("corner",), texts=("corners",))
    ax_s, ax_t = view.fig.subplots(1, 2, width_ratios=[1, 1.6])
    _drag_axes(ax_s, ax_t, pic, out_hw)
    fixed = _drag_fixed(pic.shape, out_hw)  # A..D on the diagonal, their cross-ratio the invariant
    _drag_line_names(ax_s, fixed["line"])
    art = _drag_artists(view, ax_s, ax_t, out_hw)
    readout = W.HTML()
    control = corner_text(format_corners(_DRAG_START), "corners (u, v; ...)")
    keys = _drag_keys(control, out_hw, view.browser)
    current = {"corners": _DRAG_START.copy()}

    def update(v: dict, state: dict) -> None:
        # the per-move geometry (its twin dragView in the browser's corners.js)
        g = drag_view(v, fixed)
        if g.error is not None:
            state.update(error=g.error)
            art.warning("cannot use these corners:\n" + "\n".join(textwrap.wrap(g.error, 55)[:3]))
            readout.value = monospace(f"cannot use these corners:\n{g.error}")
            return
        corners, H, m = g.corners, g.H, g.mapped
        current["corners"] = corners
        _show_drag_view(
            art, g, warp_perspective(pic, H, out_hw, method="cv2", fill=255), v["corner"]
        )
        measures, rows = g.measures
        state.update(
            H=H,
            error=None,
            torn=g.torn,
            corner=v["corner"],
            corners=corners,
            verdicts={name: verdict for name, _, _, verdict in rows},
            **measures,
        )
        table = drag_table_text(rows)
        art.numbers.set_text(table)
        readout.value = monospace(table + _drag_notes(art.mapped_names, m, out_hw, H))

    demo = build_demo(
        "drag_homography",
        {"corners": control, "corner": keys.pop("corner")},
        view,
        update,
        title="A homography from four corners",
        extra=[readout],
        linked=keys,
    )
    demo.handlers.update(
        connect_corner_drag(
            view, ax_t, control, lambda: current["corners"], radius_px=DRAG_RADIUS_PX
        )
    )
    longest = "cannot use these corners:\n" + "\n".join(["x"] * 3)  # as many lines as TORN_DRAG
    notes = dict(torn=TORN_DRAG, longest=longest, margin=SLIDER_MARGIN_PX, radius=DRAG_RADIUS_PX)
    view.publish(
        demo, drag_scene((ax_s, ax_t), art, pic, fixed, notes)
    )  # the browser draws the moves
    return demo
