"""Demos for lesson 07, homographies.

Every demo draws once and then moves artists; the geometry comes from
``camlab.homography`` and ``camlab.warp`` (the cv2 fast path warps pictures live).
Corners can be dragged with the mouse under ipympl; the same corners are a text
control ``"u0, v0; u1, v1; u2, v2; u3, v3"`` so tests and static pages drive them too.
"""

from __future__ import annotations

import textwrap
from collections.abc import Callable
from functools import lru_cache
from typing import Any

import ipywidgets as W
import numpy as np

from .. import fixtures, scenes
from .. import homography as hg
from .._validate import DegenerateError
from ..plotting import palette
from ..projective import (
    LINE_AT_INFINITY,
    clip_line,
    cross_ratio,
    map_lines,
    map_points,
    map_polyline,
    splits_at_infinity,
)
from ..robust import required_iterations
from ..warp import forward_warp, warp_perspective
from ._base import Demo, FigureView, build_demo, register, slider
from .controls import (
    connect_corner_drag,
    corner_keys,
    corner_text,
    format_corners,
    monospace,
    parse_corners,
)


def _warning(
    view: FigureView,
    ax: Any,
    x: float = 0.02,
    y: float = 0.02,
    ha: str = "left",
    va: str = "bottom",
) -> Callable[[str], None]:
    """An animated red note in ``ax`` (axes coordinates; default the bottom-left corner);
    returns ``say(text)`` ("" hides it: a hidden text costs nothing to draw, an empty one
    with a box does)."""
    note = view.animate(
        ax.text(
            x,
            y,
            "",
            transform=ax.transAxes,
            ha=ha,
            va=va,
            fontsize=8,
            color=palette.TAB_RED,
            bbox=dict(fc="white", ec=palette.TAB_RED, alpha=0.9),
            visible=False,
        )
    )

    def say(text: str) -> None:
        note.set_text(text)
        note.set_visible(bool(text))

    return say


CONFIDENCE = 0.995  # RANSAC's confidence p in the demo
MAX_SAMPLES = 1000  # RANSAC's cap on the samples drawn in the demo

TORN_SHORT = (  # beside a canvas, in a narrow column
    "torn: the line that H sends\nto infinity crosses the\npicture; its halves leave\nthrough infinity and come\nback on the other side"
)
TORN_DRAG = (
    "a bow tie or a dent: the line that H sends to\ninfinity (purple, dashed, above) crosses the\n"
    "picture. Its two halves leave through infinity\nand come back on the other side: torn."
)


# ----------------------------------------------------------------------------- hierarchy

_GROUPS = tuple(hg.HIERARCHY)  # euclidean, similarity, affine, projective


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
    """Euclidean, similarity, affine, projective: sliders for each group acting on a picture,
    with the image of the line at infinity (the vanishing line) drawn when H moves it into view."""
    pic = scenes.house_picture()
    ph, pw = pic.shape[:2]
    canvas_hw = (360, 480)
    xlim, ylim = (-0.5, canvas_hw[1] - 0.5), (-0.5, canvas_hw[0] - 0.5)
    # Picture coordinates centred on the origin; C places the origin at the canvas centre.
    C = np.array([[1.0, 0, canvas_hw[1] / 2], [0, 1, canvas_hw[0] / 2], [0, 0, 1]])
    P = np.array([[1.0, 0, -(pw - 1) / 2], [0, 1, -(ph - 1) / 2], [0, 0, 1]])
    view = FigureView(figsize=(8.5, 4.2))
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
    view.animate(
        ax.plot(box0[:, 0], box0[:, 1], ":", color="0.2", lw=1.5, label="original outline")[0]
    )
    samples = np.linspace(0, 1, 60)  # dense, so the polylines follow the picture up to its tear
    grid_lines = [np.column_stack([np.full(60, x), samples * (ph - 1)]) for x in np.linspace(0, pw - 1, 5)]
    grid_lines += [np.column_stack([samples * (pw - 1), np.full(60, y)]) for y in np.linspace(0, ph - 1, 4)]
    grid_art = view.animate(
        ax.plot([], [], color=palette.ORANGE, lw=1, path_effects=palette.halo(1), label="grid mapped by H")[0]
    )
    horizon_art = view.animate(
        ax.plot([], [], "--", color=palette.PURPLE, lw=2, label="vanishing line (image of\nl∞; at infinity unless\nthe group is projective)")[0]
    )
    ax.set_title("the picture mapped by H (its group, dof and invariants at the right)", fontsize=10)
    # beside the axes: over the warped picture the legend would need a redraw per update
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8)
    # The group, its dof and what it keeps, in the figure itself (a static page has no readout).
    facts = view.animate(
        ax.text(1.03, 0.72, "", transform=ax.transAxes, ha="left", va="top", fontsize=8, linespacing=1.3)
    )
    warning = _warning(view, ax, 1.03, 0.0, "left", "bottom")  # beside the canvas, never over it
    picture_corners = np.array([[0, 0], [pw - 1, 0], [pw - 1, ph - 1], [0, ph - 1]], float)
    readout = W.HTML()

    def update(v: dict, state: dict) -> None:
        Hg = hg.hierarchy_matrix(
            v["group"],
            theta=np.radians(v["theta"]),
            scale=v["scale"],
            shear=np.radians(v["phi"]),
            aspect=v["aspect"],
            tx=v["tx"],
            ty=v["ty"],
            v=(v["v1"] * 1e-3, v["v2"] * 1e-3),
        )
        H = hg.compose(C, Hg, P)
        im.set_data(warp_perspective(pic, H, canvas_hw, method="cv2", fill=255))
        pieces = [np.vstack([map_polyline(H, line), [[np.nan, np.nan]]]) for line in grid_lines]
        m = np.vstack(pieces)
        grid_art.set_data(m[:, 0], m[:, 1])
        # l' = H^-T l_inf: where parallel lines of the picture meet (outside the view for affine H)
        vanishing = clip_line(map_lines(H, LINE_AT_INFINITY), xlim, ylim)
        horizon_art.set_data(vanishing[:, 0], vanishing[:, 1])
        info = hg.HIERARCHY[v["group"]]
        kind = hg.classify(Hg)
        torn = splits_at_infinity(H, picture_corners)
        warning(TORN_SHORT if torn else "")
        state.update(
            H=Hg, group=v["group"], classified=kind, dof=info["dof"], torn=torn,
            vanishing_line_in_view=bool(np.isfinite(vanishing).all()),
        )
        keeps = [f"- {name}" for name in info["own"]]
        if info["larger"]:
            keeps.append(f"+ all that {'an' if info['larger'] == 'affine' else 'a'} {info['larger']} map keeps")
        facts.set_text(
            f"{v['group']}: {info['dof']} dof\n(H itself is {kind})\n\nkeeps:\n"
            + "\n".join("\n".join(textwrap.wrap(k, 24, subsequent_indent="  ")) for k in keeps)
        )
        readout.value = monospace(
            f"{v['group']}: {info['dof']} dof\nH =\n"
            + np.array2string(Hg, precision=4, suppress_small=True)
            + f"\nsmallest group holding H: {kind}\nkeeps: "
            + ", ".join(info["invariants"])
        )

    controls = {
        "group": W.Dropdown(options=list(_GROUPS), value="affine", description="group"),
        "theta": slider(15.0, -180.0, 180.0, 1.0, "rotation θ (°)"),
        "scale": slider(1.2, 0.3, 2.5, 0.05, "scale s"),
        "phi": slider(30.0, -90.0, 90.0, 1.0, "affine: stretch axes φ (°)"),
        "aspect": slider(1.4, 0.4, 2.5, 0.05, "affine: stretch √(sx/sy)"),
        "tx": slider(0.0, -100.0, 100.0, 1.0, "tx (px)"),
        "ty": slider(0.0, -80.0, 80.0, 1.0, "ty (px)"),
        "v1": slider(1.5, -15.0, 15.0, 0.1, "projective: v1 (×1e-3)"),
        "v2": slider(0.0, -15.0, 15.0, 0.1, "projective: v2 (×1e-3)"),
    }
    return build_demo(
        "transformation_hierarchy",
        controls,
        view,
        update,
        title="The transformation hierarchy",
        extra=[readout],
    )


# ----------------------------------------------------------------------------- drag corners

SQUARE = np.array([[0.0, 0.0], [159.0, 0.0], [159.0, 119.0], [0.0, 119.0]])
CORNER_NAMES = (
    "top left",
    "top right",
    "bottom right",
    "bottom left",
)  # of the source picture, SQUARE's order
_DRAG_START = np.array([[40.0, 30.0], [250.0, 60.0], [230.0, 200.0], [60.0, 230.0]])


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
    """Drag the four target corners: lines stay lines and the cross-ratio stays fixed,
    while lengths, angles and ratios of lengths change (the numbers are printed under the
    source picture). Without a mouse, pick a corner and move it with its two sliders (or type
    the corners)."""
    pic = scenes.house_picture()
    ph, pw = pic.shape[:2]
    out_hw = (260, 300)
    view = FigureView(figsize=(9, 4.6))
    ax_s, ax_t = view.fig.subplots(1, 2, width_ratios=[1, 1.6])
    ax_s.imshow(pic)
    ax_s.set_anchor("N")  # the room under the source picture holds the numbers and the warning
    ax_s.set(xlabel="u (pixels)", ylabel="v (pixels)")
    ax_s.set_title("source picture", fontsize=10, pad=3)
    ax_s.set(xlim=(-0.5, pw - 0.5), ylim=(ph - 0.5, -0.5))
    ax_t.set(xlim=(-0.5, out_hw[1] - 0.5), ylim=(out_hw[0] - 0.5, -0.5), aspect="equal")
    ax_t.set(xlabel="u (pixels)", ylabel="v (pixels)")
    ax_t.set_title("drag a corner, or use the sliders", fontsize=10, pad=3)
    # Four collinear points on the picture's diagonal (their cross-ratio is the invariant).
    line_pts = np.array([[10.0, 10.0], [50.0, 40.0], [90.0, 70.0], [150.0, 115.0]])
    line_dense = line_pts[0] + np.linspace(0, 1, 80)[:, None] * (line_pts[3] - line_pts[0])
    square_dense = np.vstack(
        [SQUARE[i] + np.linspace(0, 1, 40)[:, None] * (SQUARE[(i + 1) % 4] - SQUARE[i]) for i in range(4)]
    )
    ax_s.plot(*line_pts.T, "o-", color=palette.BROWN, ms=5, lw=1.5, path_effects=palette.halo(1.5))
    offsets = ((7, -3), (4, 6), (4, 6), (-14, 2))  # across the line; A and D sit near the frame
    for name, p, off in zip("ABCD", line_pts, offsets, strict=True):
        ax_s.annotate(name, p, xytext=off, textcoords="offset points", fontsize=9,
                      color="k", path_effects=palette.halo())  # black on a white halo: readable on any colour
    sent_away = view.animate(ax_s.plot([], [], "--", color=palette.PURPLE, lw=2)[0])
    im = view.animate(
        ax_t.imshow(
            np.zeros((*out_hw, 3), np.uint8), extent=(-0.5, out_hw[1] - 0.5, out_hw[0] - 0.5, -0.5)
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
        view.animate(ax_t.annotate(f"{name}'", (np.nan, np.nan), xytext=(4, 6), textcoords="offset points",
                                   fontsize=9, color="k", path_effects=palette.halo()))
        for name in "ABCD"
    ]
    handles = view.animate(ax_t.plot([], [], "o", color=palette.ORANGE, ms=10, mec="k")[0])
    chosen = view.animate(
        ax_t.plot([], [], "o", ms=17, mfc="none", mec="k", mew=2)[0]
    )  # the corner the keys move
    numbers = view.animate(
        ax_s.text(0.0, -0.27, "", transform=ax_s.transAxes, ha="left", va="top", fontsize=8,
                  family="monospace")
    )
    warning = _warning(view, ax_s, 0.0, -0.62, "left", "top")  # under the numbers, off the target
    readout = W.HTML()
    control = corner_text(format_corners(_DRAG_START), "corners (u, v; ...)")
    keys = corner_keys(control, CORNER_NAMES, out_hw[1] - 1, out_hw[0] - 1)
    current = {"corners": _DRAG_START.copy()}

    def update(v: dict, state: dict) -> None:
        try:
            corners = parse_corners(v["corners"])
            H = hg.estimate_homography(SQUARE, corners)
        except (ValueError, DegenerateError) as exc:
            state.update(error=str(exc))
            warning("cannot use these corners:\n" + "\n".join(textwrap.wrap(str(exc), 55)[:3]))
            readout.value = monospace(f"cannot use these corners:\n{exc}")
            return
        current["corners"] = corners
        torn = splits_at_infinity(H, SQUARE)
        warning(TORN_DRAG if torn else "")
        # H^T l_inf = (h31, h32, h33): the source line that H sends to infinity (drawn if in view)
        away = clip_line(H[2], (-0.5, pw - 0.5), (-0.5, ph - 0.5))
        sent_away.set_data(away[:, 0], away[:, 1])
        im.set_data(warp_perspective(pic, H, out_hw, method="cv2", fill=255))
        m = map_points(H, line_pts)
        dense = map_polyline(H, line_dense)  # broken where it passes through infinity
        mapped_line.set_data(dense[:, 0], dense[:, 1])
        mapped_dots.set_data(m[:, 0], m[:, 1])
        for label, p in zip(mapped_names, m, strict=True):
            label.xy = tuple(p)
        outline = map_polyline(H, square_dense)
        quad.set_data(outline[:, 0], outline[:, 1])
        handles.set_data(corners[:, 0], corners[:, 1])
        chosen.set_data(corners[v["corner"], :1], corners[v["corner"], 1:])
        cr0, cr1 = cross_ratio(line_pts), cross_ratio(m)
        ratio0 = np.linalg.norm(line_pts[1] - line_pts[0]) / np.linalg.norm(
            line_pts[3] - line_pts[2]
        )
        ratio1 = np.linalg.norm(m[1] - m[0]) / np.linalg.norm(m[3] - m[2])
        e1, e2 = corners[1] - corners[0], corners[3] - corners[0]
        angle = np.degrees(
            np.arccos(np.clip(e1 @ e2 / np.linalg.norm(e1) / np.linalg.norm(e2), -1, 1))
        )
        state.update(
            H=H,
            error=None,
            torn=torn,
            corner=v["corner"],
            cross_ratio_source=cr0,
            cross_ratio_image=cr1,
            length_ratio_source=ratio0,
            length_ratio_image=ratio1,
            corner_angle=angle,
            corners=corners,
        )
        table = (
            f"                 source   image\n"
            f"cross-ratio      {cr0:6.4f}  {cr1:6.4f}  kept\n"
            f"|AB| / |CD|      {ratio0:6.4f}  {ratio1:6.4f}  changes\n"
            f"top-left angle   {90:5.1f}°   {angle:5.1f}°  changes"
        )
        numbers.set_text(table)
        readout.value = monospace(
            table + "\nH =\n" + np.array2string(H, precision=4, suppress_small=True)
        )

    demo = build_demo(
        "drag_homography",
        {"corners": control, "corner": keys.pop("corner")},
        view,
        update,
        title="A homography from four corners",
        extra=[readout],
        linked=keys,
    )
    demo.handlers.update(connect_corner_drag(view, ax_t, control, lambda: current["corners"]))
    return demo


# ----------------------------------------------------------------------------- RANSAC

# What RANSAC did with each pair, against the truth the demo knows.
_VERDICTS = (
    ("inlier, kept", palette.GREEN),
    ("outlier, wrongly kept", palette.RED),
    ("inlier, wrongly rejected", palette.BLUE),
    ("outlier, rejected", palette.GREY),
)


@register(
    lesson="07", sweep={"outliers": [0.1, 0.4, 0.7], "threshold": [1.0, 3.0, 8.0], "seed": [0, 3]}
)
def ransac_outliers() -> Demo:
    """RANSAC against a growing outlier fraction ε: each pair's verdict against the truth,
    and the samples drawn against k = log(1 - p) / log(1 - (1 - ε)^4)."""
    from matplotlib.collections import LineCollection
    from matplotlib.colors import to_rgba

    view = FigureView(figsize=(9.6, 4.8))
    ax, ax_k = view.fig.subplots(1, 2, width_ratios=[1.35, 1])
    ax.set(
        xlim=(-10, 440), ylim=(330, -10), aspect="equal", xlabel="u (pixels)", ylabel="v (pixels)"
    )
    ax.set_title("each pair: a line from src to a dot at dst", fontsize=10, pad=3)
    arrows = view.animate(ax.add_collection(LineCollection([], lw=1.0)))
    heads = view.animate(ax.scatter(np.zeros(0), np.zeros(0), s=6))
    box_true = view.animate(
        ax.plot([], [], "-", color="0.3", lw=2, label="true H (image frame)")[0]
    )
    box_est = view.animate(ax.plot([], [], "--", color="k", lw=1.5, label="RANSAC H")[0])
    best = view.animate(
        ax.plot([], [], "o", mfc="none", mec="k", mew=2, ms=11, label="the winning sample of 4")[0]
    )
    for name, colour in _VERDICTS:
        ax.plot([], [], "-", color=colour, lw=2, label=name)
    # Below the figure (the layout makes room), never over the arrows; under the left panel it describes.
    view.fig.legend(*ax.get_legend_handles_labels(), loc="outside lower left", fontsize=8, ncol=3)
    failure = _warning(view, ax, 0.5, 0.55, "center", "center")
    eps = np.linspace(0.0, 0.97, 300)
    k_curve = [required_iterations(1.0 - e, CONFIDENCE, 4) for e in eps]
    ax_k.semilogy(eps, k_curve, color="0.5", label="k = log(1-p) / log(1-(1-ε)⁴), p = 0.995")
    ax_k.axhline(MAX_SAMPLES, color="0.3", ls=":", lw=1, label=f"the cap: {MAX_SAMPLES} samples")
    needed = view.animate(
        ax_k.plot([], [], "o", mfc="none", mec="k", mew=1.5, ms=10, label="k for the ε RANSAC found")[0]
    )
    dot = view.animate(
        ax_k.plot([], [], "o", color="k", ms=5, label="samples drawn (whole batches)")[0]
    )
    ax_k.set(
        xlabel="outlier fraction ε",
        ylabel="samples",
        ylim=(1, 1e7),  # the whole curve: the ring for any ε found is on the axes, never pinned
        xlim=(0, 0.97),
        title="adaptive number of samples",
    )
    ax_k.legend(loc="upper left", fontsize=8)
    ax_k.grid(True, color="0.93")
    ax_k.text(
        0.03,
        0.66,
        "samples come in batches (16, then\nup to 64), so the dot sits at or\nabove the ring, unless RANSAC\nstops at the cap",
        transform=ax_k.transAxes,
        ha="left",
        va="top",
        fontsize=8,
        color="0.3",
    )
    readout = W.HTML()
    frame = np.array([[0, 0], [399, 0], [399, 299], [0, 299], [0, 0]], float)

    @lru_cache(
        maxsize=256
    )  # sliders revisit settings; the answer is a pure (seeded) function of them
    def run(outlier_fraction: float, threshold: float, seed: int):
        """The demo's data and RANSAC's answer, or its error message."""
        data = fixtures.outlier_matches(outlier_fraction, seed)
        try:
            return data, hg.ransac_homography(
                data[1], data[2], threshold, CONFIDENCE, MAX_SAMPLES, np.random.default_rng(seed)
            )
        except DegenerateError as exc:
            return data, str(exc)

    def update(v: dict, state: dict) -> None:
        (H, src, dst, out), r = run(float(v["outliers"]), float(v["threshold"]), int(v["seed"]))
        if isinstance(r, str):  # RANSAC failed: clear the last result, a stale plot would be a lie
            exc = r
            state.update(
                iterations=None,
                inliers=None,
                recall=None,
                corner_error=None,
                H=None,
                verdicts=None,
                outlier_fraction_found=None,
                samples_needed=None,
                error=exc,
            )
            for artist in (box_est, dot, needed, best):
                artist.set_data([], [])
            arrows.set_segments([])
            heads.set_offsets(np.zeros((0, 2)))
            failure(
                "RANSAC failed: no hypothesis had real support\n(the full message is beside the sliders)"
            )
            readout.value = monospace(exc)
            return
        failure("")
        verdict = np.select([~out & r.inliers, out & r.inliers, ~out & ~r.inliers], [0, 1, 2], 3)
        colours = np.array([to_rgba(c) for _, c in _VERDICTS])[verdict]
        order = np.argsort(
            -verdict
        )  # rejected outliers first, so the interesting arrows sit on top
        arrows.set_segments(np.stack([src, dst], axis=1)[order])
        arrows.set_color(colours[order])
        heads.set_offsets(dst[order])
        heads.set_color(colours[order])
        bt, be = map_points(H, frame), map_points(r.H, frame)
        box_true.set_data(bt[:, 0], bt[:, 1])
        box_est.set_data(be[:, 0], be[:, 1])
        best.set_data(dst[r.sample, 0], dst[r.sample, 1])
        eps_found = 1.0 - r.inliers.mean()
        k_needed = required_iterations(1.0 - eps_found, CONFIDENCE, 4)
        dot.set_data([v["outliers"]], [r.iterations])
        needed.set_data([eps_found], [k_needed])
        counts = np.bincount(verdict, minlength=4)
        found_true = float(np.mean(r.inliers[~out])) if (~out).any() else float("nan")
        err = float(np.max(np.linalg.norm(be - bt, axis=1)))
        state.update(
            sample=r.sample,
            iterations=r.iterations,
            inliers=int(r.inliers.sum()),
            recall=found_true,
            corner_error=err,
            error=None,
            H=r.H,
            verdicts=counts,
            outlier_fraction_found=eps_found,
            samples_needed=k_needed,
        )
        readout.value = monospace(
            f"true ε = {v['outliers']:.2f}, found ε = {eps_found:.2f}\n"
            f"samples drawn: {r.iterations}{' (the cap)' if r.iterations >= MAX_SAMPLES else ''}; "
            f"needed for the found ε: {k_needed:.0f}\n"
            + "\n".join(
                f"{name:25s} {c:4d}" for (name, _), c in zip(_VERDICTS, counts, strict=True)
            )
            + f"\nworst corner error: {err:.1f} px"
        )

    controls = {
        "outliers": slider(0.4, 0.0, 0.8, 0.05, "outlier fraction ε"),
        "threshold": slider(3.0, 0.5, 10.0, 0.5, "threshold (px)"),
        "seed": W.IntSlider(value=0, min=0, max=9, description="seed"),
    }
    return build_demo("ransac_outliers", controls, view, update, title="RANSAC", extra=[readout])


# ----------------------------------------------------------------------------- forward vs inverse


@register(lesson="07", sweep={"scale": [0.6, 1.5, 2.8], "angle": [0.0, 25.0]})
def forward_vs_inverse() -> Demo:
    """Forward mapping leaves holes where H magnifies; inverse mapping never does."""
    pic = scenes.house_picture((80, 60))
    out_hw = (180, 240)
    view = FigureView(figsize=(9, 3.6))
    ax_f, ax_i = view.fig.subplots(1, 2)
    blank = np.zeros((*out_hw, 3), np.uint8)
    im_f = view.animate(ax_f.imshow(blank, interpolation="nearest"))
    im_i = view.animate(ax_i.imshow(blank, interpolation="nearest"))
    ax_f.set_title("forward: push each source pixel", fontsize=10, pad=3)
    for ax_ in (ax_f, ax_i):
        ax_.set(xlabel="u (pixels)", ylabel="v (pixels)")
    ax_i.set_title("inverse: pull each output pixel", fontsize=10, pad=3)
    readout = W.HTML()
    ones = np.ones(pic.shape[:2], np.uint8)

    def update(v: dict, state: dict) -> None:
        C = np.array([[1.0, 0, out_hw[1] / 2], [0, 1, out_hw[0] / 2], [0, 0, 1]])
        P = np.array([[1.0, 0, -39.5], [0, 1, -29.5], [0, 0, 1]])
        H = hg.compose(
            C,
            hg.similarity_homography(v["scale"], np.radians(v["angle"])),
            hg.projective_homography(v=(1e-3, 0)),
            P,
        )
        fwd = forward_warp(pic, H, out_hw)
        inv = warp_perspective(
            pic, H, out_hw, interpolation="nearest", method="cv2"
        )  # same picture, fast
        im_f.set_data(fwd)
        im_i.set_data(inv)
        covered = warp_perspective(ones, H, out_hw, interpolation="nearest", method="cv2") > 0
        inner = covered.copy()
        inner[1:-1, 1:-1] &= (
            covered[:-2, 1:-1] & covered[2:, 1:-1] & covered[1:-1, :-2] & covered[1:-1, 2:]
        )
        reached = forward_warp(ones, H, out_hw) > 0
        holes = float(np.mean(~reached[inner])) if inner.any() else 0.0
        state.update(H=H, hole_fraction=holes)
        readout.value = monospace(
            f"holes in the forward warp: {100 * holes:.0f}% of the covered area\n"
            f"holes in the inverse warp: 0%"
        )

    controls = {
        "scale": slider(2.0, 0.4, 3.0, 0.05, "scale"),
        "angle": slider(15.0, -45.0, 45.0, 1.0, "rotation (°)"),
    }
    return build_demo(
        "forward_vs_inverse",
        controls,
        view,
        update,
        title="Forward versus inverse warping",
        extra=[readout],
    )
