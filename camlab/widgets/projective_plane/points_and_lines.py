"""Demos of lesson 06, sections 1-6: points, lines, their duality, vanishing points and the cross-ratio."""

from __future__ import annotations

from types import SimpleNamespace

import ipywidgets as W
import numpy as np

from ... import projective as pj
from ...plotting import palette
from ...plotting.plane import (
    ARROW_PATH,
    arrow_marker,
    arrow_to_infinity,
    image_axes,
    plane_axes,
    set_line,
)
from .._base import Demo, FigureView, build_demo, register, slider
from ..browser import BrowserView
from ..browser.plane_scenes import (
    cross_ratio_scene,
    duality_scene,
    lift_scene,
    parallel_scene,
    vanishing_scene,
)
from ..controls import monospace
from .twins import (
    LIFT_NOTES,
    ab_over_bc,
    cross_ratio_caption,
    cross_ratio_homography,
    drawn_vanishing_point,
    duality_caption,
    horizon_note,
    label_offset,
    lift_view,
    line_at_angle,
    meet_or_none,
    meet_w_curve,
    normal_line,
    rolled_view,
)

# The sliders' ranges, and the 3-D box that holds every scaled point they reach: |λ x| <= 2 * 1.5.
_LIFT_XY, _LIFT_SCALE = 1.5, 2.0
_LIFT_BOX = _LIFT_XY * _LIFT_SCALE


def _lift_figure(view: FigureView) -> SimpleNamespace:
    """The figure of :func:`lift_to_plane`: the ray in 3-D (left), the plane w = 1 (right)."""
    ax3 = view.fig.add_subplot(1, 2, 1, projection="3d")
    ax2 = plane_axes(view.fig.add_subplot(1, 2, 2), 2, "the plane w = 1 (drawn y up)")
    box, w_max = _LIFT_BOX, _LIFT_SCALE
    pad = 1.12  # the ray is clipped to |x|, |y| <= box, |w| <= w_max: the axes' box holds it with room
    ax3.set(
        xlim=(-pad * box, pad * box),
        ylim=(-pad * box, pad * box),
        zlim=(-pad * w_max, pad * w_max),
        xlabel="x",
        ylabel="y",
        zlabel="w",
    )
    ax3.set_box_aspect((1, 1, 0.75))
    ax3.view_init(elev=16, azim=-60)
    ax3.set_title("homogeneous space (x, y, w)")
    view.fig.get_layout_engine().set(wspace=0.12)  # the 3-D w label and the plane's y label apart
    ax3.set(xticks=[-3, 0, 3], yticks=[-3, 0, 3], zticks=[-2, -1, 0, 1, 2])
    gx, gy = np.meshgrid(*[np.linspace(-box, box, 7)] * 2)  # w = 1 over the whole box
    ax3.plot_surface(
        gx,
        gy,
        np.ones_like(gx),
        color=palette.TAB_BLUE,
        alpha=0.12,
        edgecolor=palette.TAB_BLUE,
        lw=0.3,
    )
    ax3.plot_surface(  # the plane w = 0, faintly: where an ideal point's ray lies
        gx, gy, np.zeros_like(gx), color="0.5", alpha=0.08, edgecolor="none"
    )
    ax3.text(
        -0.6 * box, -box, 1.3, "w = 1", color=palette.TAB_BLUE, ha="left"
    )  # near the left corner, off the ray's path and clear of the panel's edge
    ax3.text(
        -0.8 * box, -box, 0.0, "w = 0", color="0.35", ha="left", va="top"
    )  # the faint plane, its front edge
    ax3.scatter([0], [0], [0], color="k", s=15)
    (ray,) = ax3.plot(
        [], [], [], color=palette.TAB_BLUE, lw=1.5, label="line through 0 = one projective point"
    )
    (scaled,) = ax3.plot([], [], [], "o", color=palette.ORANGE, label="λ(x, y, w), any λ ≠ 0")
    (hit,) = ax3.plot([], [], [], "o", color=palette.TAB_BLUE, label="(x/w, y/w, 1)")
    # under the 3-D box, where nothing is drawn (inside it, the line reaches every corner)
    ax3.legend(loc="upper center", bbox_to_anchor=(0.5, 0.02), ncol=2, fontsize=8)
    (dot,) = ax2.plot([], [], "o", color=palette.TAB_BLUE, ms=9)
    note = ax2.text(0, -1.8, "", ha="center", fontsize=8, color="k", bbox={"fc": "w", "ec": "none"})
    return SimpleNamespace(ax3=ax3, ax2=ax2, ray=ray, scaled=scaled, hit=hit, dot=dot, note=note)


@register(
    lesson="06",
    sweep={
        "x": [-1.5, 0.0, 1.5],
        "y": [1.5, -1.5],
        "w": [1.0, 0.4, 0.1, 0.0],
        "scale": [-2.0, -0.6, 0.0, 2.0],
    },
)
def lift_to_plane() -> Demo:
    """A point (x, y) is the line through the origin and (x, y, 1): every non-zero multiple names it.

    The ray's direction is (x, y, w). Tilting it down to w = 0 sends the point it names,
    (x/w, y/w), off to infinity: at w = 0 the ray lies in the plane w = 0 and never meets w = 1,
    an ideal point, drawn as an arrow at the edge of the plane. The 3-D box is sized once; the
    ray is clipped to it. A negative λ puts the scaled point on the other half of the ray, and
    λ = 0 gives (0, 0, 0), which names no point (its marker is then hidden).

    Returns
    -------
    Demo
        The demo: controls ``x``, ``y``, ``w`` (the ray's direction) and ``scale`` (λ), the
        figure (the ray in 3-D, the plane w = 1 drawn flat) and ``state`` (``point_h`` the scaled
        homogeneous 3-vector λ (x, y, w), ``point`` the Euclidean (x/w, y/w) it names, or None
        at w = 0).
    """
    view = BrowserView(("x", "y", "w", "scale"), figsize=(9, 4.6))
    f = _lift_figure(view)
    ax2, ray, scaled, hit, dot, note = f.ax2, f.ray, f.scaled, f.hit, f.dot, f.note
    view.animate(ray, scaled, hit, dot, note)
    readout = W.HTML()

    def update(v: dict, state: dict) -> None:
        # the per-move geometry (its twin liftView in the browser's geometry.js)
        lam, r = v["scale"], np.array([v["x"], v["y"], v["w"]])
        g = lift_view(r, lam, _LIFT_BOX, _LIFT_SCALE, ax2.get_xlim(), ax2.get_ylim())
        xh = g.point_h
        state.update(point_h=xh, point=g.point)
        ray.set_data_3d(*g.ends.T)
        scaled.set_data_3d([xh[0]], [xh[1]], [xh[2]])
        scaled.set_visible(g.scaled_shown)  # λ = 0 names no point: the legend says λ ≠ 0
        hit.set_data_3d(*([[c] for c in g.hit] if g.hit is not None else [[], [], []]))
        note.set_text(g.note)
        if g.dot is None:  # x = y = w = 0: the zero vector is no ray
            dot.set_data([], [])
            readout.value = monospace("(x, y, w) = (0, 0, 0): no ray through 0, no point")
            return
        pos, direction = g.dot
        dot.set_data([pos[0]], [pos[1]])
        dot.set_marker("o" if not direction.any() else arrow_marker(direction, ax2))
        if not g.scaled_shown:
            second = "λ = 0 gives (0, 0, 0): on every line through 0, so it names no point"
        elif g.point is None:
            second = "w = 0: no division; the ray lies in the plane w = 0 and never meets w = 1"
        else:
            back = xh[:2] / xh[2]
            second = f"divide by w = {xh[2]:.2f} → ({back[0]:.2f}, {back[1]:.2f})"
        readout.value = monospace(f"λ(x, y, w) = ({xh[0]:.2f}, {xh[1]:.2f}, {xh[2]:.2f})\n{second}")

    controls = {
        "x": slider(1.0, -_LIFT_XY, _LIFT_XY, 0.05, "ray's x"),
        "y": slider(0.5, -_LIFT_XY, _LIFT_XY, 0.05, "ray's y"),
        "w": slider(1.0, 0.0, 1.0, 0.05, "ray's w"),
        "scale": slider(1.6, -_LIFT_SCALE, _LIFT_SCALE, 0.05, "scale λ"),
    }
    demo = build_demo(
        "lift_to_plane",
        controls,
        view,
        update,
        title="Homogeneous coordinates are defined up to scale",
        extra=[readout],
    )
    world = dict(
        box=_LIFT_BOX, w_max=_LIFT_SCALE, arrow=ARROW_PATH, notes=LIFT_NOTES, longest=LIFT_NOTES[0]
    )
    # the browser draws the moves; a drag on the 3-D box turns it in the kernel (the scene built again)
    view.publish(demo, lambda: lift_scene(f, world))
    return demo


SAME_LINE_NOTE = "l2 = l1 at 30°: one line,\nno single meet point, no w"
"""What :func:`parallel_lines` says over its |w| panel when l2 turns onto l1."""


def _parallel_figure(view: FigureView) -> SimpleNamespace:
    """The figure of :func:`parallel_lines`.

    The two lines and their meet (left), |w| of the meet against l2's angle with l1's angle dotted
    (right), and the note for coincident lines; returns the artists.
    """
    ax, axw = view.fig.subplots(1, 2, width_ratios=[1.3, 1])
    plane_axes(ax, 4, "l1 = 30° fixed; turn l2")
    (l1_artist,) = ax.plot([], [], color=palette.TAB_BLUE, lw=2, label="l1")
    (l2_artist,) = ax.plot([], [], "--", color=palette.ORANGE, lw=2, label="l2")  # l1 shows through
    (meet_dot,) = ax.plot([], [], "o", color=palette.TAB_RED, ms=8, label="l1 × l2 (when l2 ≠ l1)")
    arrow = ax.annotate(
        "", xy=(0, 0), xytext=(0, 0), arrowprops=dict(arrowstyle="->", color=palette.TAB_RED, lw=2)
    )
    ax.legend(
        loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=3, fontsize=8
    )  # not over the lines
    angle1 = 30.0
    (w_curve,) = axw.plot([], [], color=palette.GREY)
    (w_dot,) = axw.plot(
        [], [], "o", color=palette.TAB_RED, clip_on=False, zorder=4
    )  # whole at w = 0
    axw.axvline(angle1, color=palette.TAB_BLUE, ls=":", lw=1)
    axw.text(angle1, 0.97, " l1's angle", color=palette.TAB_BLUE, fontsize=8, ha="left", va="top")
    axw.set(
        xlim=(0, 60),
        xlabel="angle of l2 (degrees)",
        ylabel="|w| of the unit meet point",
        title="w → 0: the meet point runs to infinity",
        ylim=(0, 1.02),
    )
    axw.grid(True, color="0.93")
    # constrained layout leaves the last tick label ("60") half outside the figure: pad the right edge
    view.fig.get_layout_engine().set(w_pad=0.12)
    boxed = {"ha": "center", "va": "center", "fontsize": 9, "color": palette.TAB_RED}
    same_note = axw.text(0.5, 0.45, SAME_LINE_NOTE, transform=axw.transAxes, **boxed)
    same_note.set_bbox({"fc": "white", "ec": palette.TAB_RED})
    same_note.set_visible(False)
    return SimpleNamespace(
        ax=ax,
        axw=axw,
        l1=l1_artist,
        l2=l2_artist,
        meet_dot=meet_dot,
        arrow=arrow,
        w_curve=w_curve,
        w_dot=w_dot,
        same_note=same_note,
    )


@register(lesson="06", sweep={"angle2": [10.0, 25.0, 29.5, 30.0, 45.0], "offset2": [-2.5, 1.5]})
def parallel_lines() -> Demo:
    """Two lines meet at l1 x l2; as they turn parallel the point runs to infinity (w -> 0).

    Returns
    -------
    Demo
        The demo: controls ``angle2`` (l2's angle, degrees) and ``offset2`` (where l2 crosses
        x = 0), the figure (the two lines and their meet, |w| against the angle) and ``state``
        (``l2``, ``meet`` the homogeneous meet point, ``w`` its |w| once normalised to unit
        length, ``point`` its Euclidean position; ``meet`` and ``point`` None, ``w`` NaN, when
        the lines coincide).
    """
    view = BrowserView(("angle2", "offset2"), figsize=(9, 4.4))
    f = _parallel_figure(view)
    ax, l1_artist, l2_artist, meet_dot, arrow = f.ax, f.l1, f.l2, f.meet_dot, f.arrow
    w_curve, w_dot, same_note = f.w_curve, f.w_dot, f.same_note
    readout = W.HTML()
    angle1 = 30.0
    angles = np.linspace(0, 60, 241)
    view.animate(l1_artist, l2_artist, meet_dot, arrow, w_curve, w_dot, same_note)

    l1 = line_at_angle(angle1, 0.5)

    def update(v: dict, state: dict) -> None:
        l2 = line_at_angle(v["angle2"], v["offset2"])
        # Through l1's own point (0, 0.5) every l2 meets l1 there, except at l1's angle: a gap there
        w_curve.set_data(angles, meet_w_curve(l1, angle1, angles, v["offset2"]))
        set_line(l1_artist, l1, ax)
        set_line(l2_artist, l2, ax)
        x = meet_or_none(l1, l2)
        if x is None:
            state.update(l2=l2, meet=None, w=float("nan"), point=None)
            meet_dot.set_data([], [])
            arrow.set_visible(False)
            w_dot.set_data([], [])
            same_note.set_text(SAME_LINE_NOTE)
            same_note.set_visible(True)
            readout.value = monospace(
                "l2 = l1: one line, every point shared,\nno single meet point"
            )
            return
        same_note.set_visible(False)
        xu = x / np.linalg.norm(x)
        state.update(l2=l2, meet=x, w=float(abs(xu[2])), point=pj.from_homogeneous(x))
        pos, direction = arrow_to_infinity(x, ax)
        if direction.any():  # outside the view or ideal: point along its direction
            meet_dot.set_data([], [])
            arrow.xy, arrow.xyann = tuple(pos), tuple(pos - 1.2 * direction)
            arrow.set_visible(True)
        else:
            meet_dot.set_data([pos[0]], [pos[1]])
            arrow.set_visible(False)
        where = (
            "ideal point: at infinity"
            if x[2] == 0
            else f"(x, y) = ({x[0] / x[2]:.2f}, {x[1] / x[2]:.2f})"
        )
        readout.value = monospace(
            f"l1 × l2 = ({xu[0]:+.3f}, {xu[1]:+.3f}, {xu[2]:+.3f})  (unit length)\n{where}"
        )
        w_dot.set_data([v["angle2"]], [state["w"]])

    controls = {
        "angle2": slider(55.0, 0.0, 60.0, 0.5, "angle of l2 (°)"),
        "offset2": slider(-1.0, -3.0, 3.0, 0.1, "l2 crosses x = 0 at y ="),
    }
    demo = build_demo(
        "parallel_lines",
        controls,
        view,
        update,
        title="Parallel lines meet at infinity",
        extra=[readout],
    )
    world = dict(l1=l1, angle1=angle1, angles=angles, note=SAME_LINE_NOTE)
    view.publish(demo, parallel_scene((ax, f.axw), vars(f), world))  # the browser draws the moves
    return demo


@register(
    lesson="06",
    sweep={
        "px": [-1.0, 0.5],
        "py": [0.8, -1.2],
        "line_angle": [20.0, 45.0, 120.0, 180.0],
        "line_dist": [0.2, 1.2, 2.5],
    },
)
def point_line_duality() -> Demo:
    """A point (a, b, c) and the line (a, b, c) swap roles; incidence survives the swap.

    Returns
    -------
    Demo
        The demo: controls ``px``, ``py`` (the point p), ``line_angle`` (the line's normal,
        degrees) and ``line_dist`` (its distance from the origin), the figure (the point and
        line, and their duals) and ``state`` (``point`` and ``line`` homogeneous,
        ``incidence`` p · l, ``on_line``).
    """
    view = BrowserView(("px", "py", "line_angle", "line_dist"), figsize=(9, 4.9))
    axes = view.fig.subplot_mosaic([["primal", "dual"], ["text", "text"]], height_ratios=[1, 0.06])
    ax_p, ax_d, ax_t = axes["primal"], axes["dual"], axes["text"]
    ax_t.set_axis_off()
    # the incidence in the figure itself, so a static copy shows whether p is on l
    text = ax_t.text(0.5, 0.5, "", transform=ax_t.transAxes, ha="center", va="center", fontsize=10)
    plane_axes(ax_p, 3, "primal: point p, line l")
    plane_axes(ax_d, 3, "dual: line p*, point l*", xlabel="a/c", ylabel="b/c")  # l* = (a/c, b/c)
    (p_dot,) = ax_p.plot([], [], "o", color=palette.TAB_BLUE, ms=9, label="p")
    (l_line,) = ax_p.plot([], [], color=palette.ORANGE, lw=2, label="l")
    (pd_line,) = ax_d.plot([], [], color=palette.TAB_BLUE, lw=2, label="p* (same 3 numbers as p)")
    (ld_dot,) = ax_d.plot([], [], "o", color=palette.ORANGE, ms=9, label="l* (same 3 numbers as l)")
    # l* off the dual panel (far out as l nears the origin): an arrow at the edge points to it
    ld_arrow = ax_d.annotate(
        "", xy=(0, 0), xytext=(0, 0), arrowprops=dict(arrowstyle="->", color=palette.ORANGE, lw=2)
    )
    for a in (ax_p, ax_d):  # under the plots: inside, the lines would run through them
        a.legend(loc="upper center", bbox_to_anchor=(0.5, -0.15), ncol=2, fontsize=8)
    view.animate(p_dot, l_line, pd_line, ld_dot, ld_arrow, text)
    readout = W.HTML()

    def update(v: dict, state: dict) -> None:
        p = pj.to_homogeneous([v["px"], v["py"]])
        line = normal_line(v["line_angle"], v["line_dist"])
        incidence = float(p @ line)
        state.update(
            point=p, line=line, incidence=incidence, on_line=bool(pj.is_on_line(p, line, tol=1e-3))
        )
        p_dot.set_data([p[0]], [p[1]])
        set_line(l_line, line, ax_p)
        set_line(pd_line, p, ax_d)
        pos, direction = arrow_to_infinity(line, ax_d)
        if direction.any():  # l* is off the panel: an arrow at the edge, pointing where it is
            ld_dot.set_data([], [])
            ld_arrow.xy, ld_arrow.xyann = tuple(pos), tuple(pos - 0.9 * direction)
            ld_arrow.set_visible(True)
        else:
            ld_dot.set_data([pos[0]], [pos[1]])
            ld_arrow.set_visible(False)
        p_text, l_text = (", ".join(f"{c:+.2f}" for c in x) for x in (p, line))
        text.set_text(duality_caption(p, line, ax_d.get_xlim(), ax_d.get_ylim()))
        readout.value = monospace(
            f"p = ({p_text})\nl = ({l_text})\np · l = {incidence:+.3f}\n(0 ⇔ p on l ⇔ l* on p*)"
        )

    controls = {
        "px": slider(1.0, -2.5, 2.5, 0.05, "p: x"),
        "py": slider(0.5, -2.5, 2.5, 0.05, "p: y"),
        "line_angle": slider(
            0.0, 0.0, 359.0, 1.0, "l: normal angle (°)"
        ),  # every line: y = -1 at 270
        "line_dist": slider(1.0, 0.2, 2.5, 0.05, "l: distance from origin"),
    }
    demo = build_demo(
        "point_line_duality",
        controls,
        view,
        update,
        title="Duality: points and lines are the same 3-vectors",
        extra=[readout],
    )
    art = dict(p_dot=p_dot, l_line=l_line, pd_line=pd_line, ld_dot=ld_dot, ld_arrow=ld_arrow)
    view.publish(demo, duality_scene((ax_p, ax_d), art, text))  # the browser draws the moves
    return demo


_VANISHING_SWEEP = {
    "pitch": [5.0, 15.0, 30.0, 40.0],
    "yaw": [0.0, 20.0, -35.0],
    "roll": [12.0, -12.0],
    "focal": [400.0, 800.0],
}


_VANISHING_TITLE = "ground grid seen by a tilted camera"


def _vanishing_figure(view: FigureView, size: tuple[int, int]) -> SimpleNamespace:
    """The figure of :func:`vanishing_points`.

    The image of ``size`` (width, height) with the two families of ground lines, the horizon and the
    two vanishing points; the axes' title doubles as the note for a horizon above the image (the
    readout says it in full). Returns its axes and artists by name.
    """
    ax = view.fig.subplots()
    image_axes(ax, size, _VANISHING_TITLE)
    from matplotlib.collections import LineCollection

    grid_z = LineCollection([], colors=palette.TAB_BLUE, lw=1, label="lines along z (ahead)")
    grid_x = LineCollection([], colors=palette.TAB_GREEN, lw=1, label="lines along x (across)")
    ax.add_collection(grid_z)
    ax.add_collection(grid_x)
    (horizon_artist,) = ax.plot(
        [],
        [],
        "--",
        color=palette.TAB_RED,
        lw=1.5,
        label="horizon = v_z × v_x (when in the image)",
    )
    # an arrowhead on the horizon when the point is off the image; never clipped at the frame
    (vz_dot,) = ax.plot(
        [],
        [],
        "o",
        color=palette.TAB_BLUE,
        mec="k",
        ms=12,
        clip_on=False,
        label="v_z (or an arrow to it)",
    )
    (vx_dot,) = ax.plot(
        [],
        [],
        "o",
        color=palette.TAB_GREEN,
        mec="k",
        ms=12,
        clip_on=False,
        label="v_x (or an arrow to it)",
    )
    # below the image: inside it, the grid's lines would run through the legend at some setting
    view.fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncol=3, fontsize=8)
    # the note for a horizon above the image replaces the title (one line, so the layout, fixed at
    # the first draw, stays right); no band is reserved for it under the legend
    note = ax.title
    return SimpleNamespace(
        ax=ax,
        grid_z=grid_z,
        grid_x=grid_x,
        horizon=horizon_artist,
        vz_dot=vz_dot,
        vx_dot=vx_dot,
        note=note,
    )


@register(
    lesson="06",
    sweep=_VANISHING_SWEEP,
)
def vanishing_points() -> Demo:
    """A tilted camera looks at a ground grid; parallel rails meet at vanishing points on the horizon.

    Returns
    -------
    Demo
        The demo: controls ``pitch``, ``yaw`` and ``roll`` (the camera's, degrees) and ``focal`` (px),
        the figure (the image of the ground grid with the horizon and the two vanishing points,
        arrows when off the image) and ``state`` (``vp_z``, ``vp_x`` estimated from the drawn
        lines, ``horizon``, their camera truths ``vp_z_true``, ``vp_x_true``,
        ``horizon_true``, and ``horizon_visible``).
    """
    size = (640, 480)
    view = BrowserView(("pitch", "yaw", "roll", "focal"), figsize=(7, 6))
    parts = _vanishing_figure(view, size)
    ax, grid_z, grid_x, note = parts.ax, parts.grid_z, parts.grid_x, parts.note
    horizon_artist, vz_dot, vx_dot = parts.horizon, parts.vz_dot, parts.vx_dot
    readout = W.HTML()
    box = ((-0.5, size[0] - 0.5), (-0.5, size[1] - 0.5))
    view.animate(grid_z, grid_x, horizon_artist, vz_dot, vx_dot, note)

    def update(v: dict, state: dict) -> None:
        g = rolled_view(v["pitch"], v["yaw"], v["roll"], v["focal"], size)
        segs = g.segments
        n = g.n_along_z
        grid_z.set_segments(segs[:n])
        grid_x.set_segments(segs[n:])
        vp_z = drawn_vanishing_point(segs[:n])  # estimated from the drawn lines
        vp_x = (
            drawn_vanishing_point(segs[n:]) if len(segs) - n >= 2 else pj.normalise_points(g.vp_x)
        )
        hz = pj.horizon(vp_z, vp_x)
        state.update(
            vp_z=vp_z,
            vp_x=vp_x,
            horizon=hz,
            horizon_true=pj.normalise_lines(g.horizon),
            vp_z_true=pj.normalise_points(g.vp_z),
            vp_x_true=pj.normalise_points(g.vp_x),
        )
        ends = pj.clip_line(hz, *box)
        horizon_artist.set_data(ends[:, 0], ends[:, 1])
        visible = bool(np.isfinite(ends).all())
        # An off-image vanishing point is drawn as an arrow ON the horizon (it lies on it),
        # from the middle of the horizon's visible piece towards the point.
        anchor = ends.mean(axis=0) if visible else None
        lines = []
        for dot, vp, name in ((vz_dot, vp_z, "v_z"), (vx_dot, vp_x, "v_x")):
            pos, direction = arrow_to_infinity(vp, ax, anchor)
            dot.set_data([pos[0]], [pos[1]])
            dot.set_marker("o" if not direction.any() else arrow_marker(direction, ax))
            lines.append(
                f"{name} = "
                + (
                    "at infinity, direction ({:+.2f}, {:+.2f})".format(*vp[:2])
                    if abs(vp[2]) < 1e-9
                    else f"({vp[0]:.1f}, {vp[1]:.1f}) px"
                    + ("" if not direction.any() else " (off image)")
                )
            )
        v_horizon = float(-hz[2] / hz[1]) if abs(hz[1]) > 1e-12 else float("nan")
        note.set_text(horizon_note(hz, visible, _VANISHING_TITLE))
        note.set_color("k" if visible else palette.TAB_RED)
        if not visible:
            lines.append(
                f"the horizon is above the image (v = {v_horizon:.0f} px at u = 0): pitched down "
                f"{v['pitch']:.0f}°, the camera sees only ground; the lines still meet there (arrows)"
            )
        state.update(horizon_visible=visible)
        readout.value = monospace("\n".join(lines))

    controls = {
        "pitch": slider(12.0, 0.0, 40.0, 0.5, "pitch down (°)"),
        "yaw": slider(15.0, -45.0, 45.0, 0.5, "yaw (°, + moves v_z left)"),
        "roll": slider(0.0, -20.0, 20.0, 0.5, "roll (°, + = clockwise)"),
        "focal": slider(600.0, 300.0, 1200.0, 10.0, "focal length (px)"),
    }
    demo = build_demo(
        "vanishing_points",
        controls,
        view,
        update,
        title="Vanishing points and the horizon",
        extra=[readout],
    )
    world = dict(size=size, title=_VANISHING_TITLE, note_color=palette.TAB_RED, arrow=ARROW_PATH)
    view.publish(demo, vanishing_scene(vars(parts), world))  # the browser draws the moves
    return demo


_CR_H = 0.3  # the cross-ratio demo's largest |h31|, |h32|


_MID = {"ha": "center", "va": "center"}


def _cross_ratio_figure(view: FigureView) -> SimpleNamespace:
    """The figure of :func:`cross_ratio_invariance`.

    A grid and four collinear points (left), their images (right) and a text strip for the two
    numbers; returns the points and artists by name.
    """
    axes = view.fig.subplot_mosaic([["before", "after"], ["text", "text"]], height_ratios=[1, 0.08])
    ax_s, ax_t = axes["before"], axes["after"]
    axes["text"].set_axis_off()
    # the two numbers the demo is about, in the figure, so a static copy shows them too
    centred = {"ha": "center", "va": "center", "family": "monospace", "fontsize": 9}
    numbers = axes["text"].text(0.5, 0.5, "", transform=axes["text"].transAxes, **centred)
    plane_axes(ax_s, 2.2, "before: four collinear points")
    plane_axes(ax_t, 2.2, "after the homography H (same scale)")
    # The grid is the rectangle |x| <= 1, |y| <= 0.5 whose diagonal carries A, B, C, D. With |h31|,
    # |h32| <= _CR_H its w = 1 + h31 x + h32 y stays >= 1 - 0.3 - 0.15 = 0.55 > 0: no grid line
    # crosses the line H sends to infinity, so each maps to one straight segment, and every grid
    # point (|p| <= 1.12) stays within 1.12 / 0.55 = 2.03 of the origin: inside the +-2.2 panel,
    # drawn at the before panel's scale, at every setting (nothing is cut).
    grid = np.array(
        [[[x, -0.5], [x, 0.5]] for x in np.linspace(-1.0, 1.0, 5)]
        + [[[-1.0, y], [1.0, y]] for y in np.linspace(-0.5, 0.5, 3)]
    )
    points = np.array([[-1.0, -0.5], [-0.3, -0.15], [0.4, 0.2], [1.0, 0.5]])
    colors = [palette.TAB_BLUE] * 4  # one colour: the letters name them (lesson 06's colour code)
    from matplotlib.collections import LineCollection

    ax_s.add_collection(LineCollection(grid, colors=palette.GREY, lw=0.8))
    ax_s.plot(points[:, 0], points[:, 1], "-", color="0.3")
    ax_s.scatter(points[:, 0], points[:, 1], c=colors, s=50, zorder=3)
    for name, p in zip("ABCD", points, strict=True):  # beside the line, on its normal
        ax_s.annotate(
            name, p, xytext=tuple(label_offset(points)), textcoords="offset points", **_MID
        )
    mapped_grid = LineCollection([], colors=palette.GREY, lw=0.8)
    ax_t.add_collection(mapped_grid)
    (mapped_line,) = ax_t.plot([], [], "-", color="0.3")
    mapped_pts = ax_t.scatter(  # orange: the points moved (lesson 06's colour code)
        points[:, 0], points[:, 1], c=[palette.ORANGE] * 4, s=50, zorder=3
    )
    labels = [
        ax_t.annotate(name, (0, 0), xytext=(0, 10), textcoords="offset points", **_MID)
        for name in "ABCD"
    ]
    return SimpleNamespace(
        grid=grid,
        points=points,
        mapped_grid=mapped_grid,
        mapped_line=mapped_line,
        mapped_pts=mapped_pts,
        labels=labels,
        numbers=numbers,
    )


@register(
    lesson="06",
    sweep={"h31": [0.0, 0.25, -0.3, 0.3], "h32": [0.0, 0.2, -0.3, 0.3], "angle": [0.0, 30.0]},
)
def cross_ratio_invariance() -> Demo:
    """A homography changes lengths and ratios of lengths, but never the cross-ratio.

    Returns
    -------
    Demo
        The demo: controls ``h31``, ``h32`` (the homography's perspective row) and ``angle``
        (its rotation, degrees), the figure (a grid and four collinear points A, B, C, D, before
        and after) and ``state`` (``H``, ``mapped`` the points after, ``cross_ratio_before``,
        ``cross_ratio_after``, ``ratio_before``, ``ratio_after`` AB / BC).
    """
    view = BrowserView(("h31", "h32", "angle"), figsize=(9, 4.6))
    f = _cross_ratio_figure(view)
    grid, points, mapped_grid, mapped_line = f.grid, f.points, f.mapped_grid, f.mapped_line
    mapped_pts, labels, numbers = f.mapped_pts, f.labels, f.numbers
    view.animate(mapped_grid, mapped_line, mapped_pts, *labels, numbers)
    readout = W.HTML()
    ratio = ab_over_bc  # an affine invariant only: AB / BC

    def update(v: dict, state: dict) -> None:
        H = cross_ratio_homography(v["h31"], v["h32"], v["angle"])
        # each grid line by its two ends: a homography keeps lines straight (none crosses H's l_inf)
        mapped_grid.set_segments(pj.map_points(H, grid.reshape(-1, 2)).reshape(-1, 2, 2))
        q = pj.map_points(H, points)
        mapped_line.set_data(q[:, 0], q[:, 1])
        mapped_pts.set_offsets(q)
        for lab, p in zip(labels, q, strict=True):
            lab.xy, lab.xyann = tuple(p), tuple(label_offset(q))
        cr_before, cr_after = pj.cross_ratio(points), pj.cross_ratio(q)
        state.update(
            H=H,
            mapped=q,
            cross_ratio_before=cr_before,
            cross_ratio_after=cr_after,
            ratio_before=ratio(points),
            ratio_after=ratio(q),
        )
        numbers.set_text(cross_ratio_caption(points, q))
        readout.value = monospace(
            f"             before   after\n"
            f"(A,B;C,D)  {cr_before:8.4f} {cr_after:8.4f}\n"
            f"AB / BC    {ratio(points):8.4f} {ratio(q):8.4f}"
        )

    controls = {
        "h31": slider(0.2, -_CR_H, _CR_H, 0.01, "h31 (perspective x)"),
        "h32": slider(0.1, -_CR_H, _CR_H, 0.01, "h32 (perspective y)"),
        "angle": slider(10.0, -45.0, 45.0, 1.0, "rotation (°)"),
    }
    demo = build_demo(
        "cross_ratio_invariance",
        controls,
        view,
        update,
        title="The cross-ratio is projectively invariant",
        extra=[readout],
    )
    view.publish(demo, cross_ratio_scene(vars(f)))  # the browser draws the moves
    return demo
