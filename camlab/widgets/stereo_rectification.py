"""Demos for lesson 11, epipolar geometry and stereo rectification.

Every demo computes with tested camlab functions (:mod:`camlab.epipolar`,
:mod:`camlab.rectification`, :mod:`camlab.disparity`) and only moves artists. Images
come from the bundled rendered rig (:mod:`camlab.data.stereo`, prepared by :mod:`camlab.fixtures.stereo`), shown at half
resolution so that re-warping stays within the latency budget.
"""

from __future__ import annotations

from functools import lru_cache
from types import SimpleNamespace

import ipywidgets as W
import numpy as np

from .. import disparity as dp
from .. import epipolar as ep
from .. import rectification as rc
from .. import scenes
from ..camera import scale_intrinsics
from ..fixtures.stereo import (
    bundled_rig,
    bundled_rig_calibration,
    half_size_rectification,
    stereo_scene,
)
from ..plotting import palette
from ..plotting.plane import ARROW_PATH, arrow_marker, arrow_to_infinity, image_axes
from ..projective import map_points
from ._base import Demo, FigureView, build_demo, register, slider
from .browser import BrowserView
from .browser.scenes import epipolar_scene
from .controls import int_slider, monospace
from .epipolar_twins import MOTIONS, epipolar_view, line_polyline, projected_segments

SIZE = (640, 480)
# the epipolar demo's fixed pixels (their epipolar lines drawn thin red): four near the corners, the centre
REF_PIXELS = np.array([[79.5, 59.5], [559.5, 99.5], [319.5, 239.5], [139.5, 419.5], [499.5, 399.5]])


# --------------------------------------------------------------------------- shared data

HALF = scale_intrinsics(
    np.eye(3), 0.5
)  # full-size pixels -> half-size pixels: u' = (u + 0.5) / 2 - 0.5


# --------------------------------------------------------------------------- demo 1: epipolar lines


def _epipolar_legends(fig, depth_dots, epi_r) -> None:
    """The keys of :func:`_epipolar_figure`, below the images, not over them.

    Every corner of the right image carries lines; the epipole's two looks (a star inside, an
    arrow at the border towards it) are both keyed.
    """
    from matplotlib.lines import Line2D

    def key(**kw):
        return Line2D([], [], **kw)

    pale = {
        "color": palette.RED,
        "lw": 1.1,
        "ls": ":",
    }  # epipolar lines are red; the fixed pencil thin, dotted
    fig.legend(  # one key below both images, in column pairs: left | right
        [
            key(**pale, marker="s", mfc="w", mec=palette.RED, ms=6),
            key(**pale),
            key(color=palette.TAB_RED, lw=1.2, ls="--"),
            key(color=palette.TAB_RED, lw=1.8),
            key(marker="o", color=palette.TAB_RED, ls="none"),
            depth_dots,
            epi_r,
            key(marker=">", color="k", lw=1.8, ms=7),
        ],
        [
            "left: 5 fixed pixels, their epipolar lines",
            "right: the 5 pixels' lines",
            "left: l, the point's line",
            "right: l' = F x",
            "left: point x",
            "right: depth 1, ..., 6 m",
            "star: epipole in the image",
            "arrow: epipole off the image",
        ],
        loc="outside lower center",
        ncol=4,
        handlelength=1.8,
        columnspacing=1.2,
        fontsize=9,
        frameon=False,
    )


def _epipolar_figure(view: FigureView) -> SimpleNamespace:
    """The figure of :func:`epipolar_lines`.

    The left and right images with the scene's outlines, the pencils of epipolar lines, the point
    and its lines, the depth marks and the epipoles (an arrow at the border for one off the image);
    returns its axes and moving artists by name.
    """
    axl, axr = view.fig.subplots(1, 2)
    image_axes(axl, SIZE, "left image: click a point")
    image_axes(axr, SIZE, "right image: its epipolar line")
    (wl,) = axl.plot([], [], color="0.55", lw=0.8)
    (wr,) = axr.plot([], [], color="0.55", lw=0.8)
    # the fixed pencil thin and dotted: told apart from the point's line by more than colour
    (pencil_l,) = axl.plot([], [], color=palette.RED, lw=1.1, ls=":")
    (pencil_r,) = axr.plot([], [], color=palette.RED, lw=1.1, ls=":")
    (point,) = axl.plot([], [], "o", color=palette.TAB_RED, ms=8)
    (line_l,) = axl.plot([], [], color=palette.TAB_RED, lw=1.2, ls="--")
    (line_r,) = axr.plot([], [], color=palette.TAB_RED, lw=1.8)
    (depth_dots,) = axr.plot([], [], "o", color=palette.GREEN, mec="k", ms=5)
    (epi_l,) = axl.plot([], [], "*", color="k", ms=13)
    (epi_r,) = axr.plot([], [], "*", color="k", ms=13)
    # an epipole off the image: an arrow (shaft + head) at the border pointing to it
    shafts = [ax.plot([], [], color="k", lw=1.8)[0] for ax in (axl, axr)]
    heads = [ax.plot([], [], color="k", ms=9, ls="none")[0] for ax in (axl, axr)]
    _epipolar_legends(view.fig, depth_dots, epi_r)
    moving = (
        wl,
        wr,
        pencil_l,
        pencil_r,
        point,
        line_l,
        line_r,
        depth_dots,
        epi_l,
        epi_r,
        *shafts,
        *heads,
    )
    for a in moving:
        a.set_in_layout(False)  # they move: the layout must not follow them
    view.animate(*moving)
    return SimpleNamespace(
        axl=axl,
        axr=axr,
        wl=wl,
        wr=wr,
        pencil_l=pencil_l,
        pencil_r=pencil_r,
        point=point,
        line_l=line_l,
        line_r=line_r,
        depth_dots=depth_dots,
        epi_l=epi_l,
        epi_r=epi_r,
        shafts=shafts,
        heads=heads,
    )


def _show_epipole(e, marker, shaft, head, ax) -> None:
    """Epipole ``e`` (homogeneous) as ``marker`` inside the image, else as an arrow.

    The arrow (``shaft`` and ``head``) sits at the border of ``ax`` pointing to it.
    """
    if abs(e[2]) < 1e-9 * np.linalg.norm(
        e
    ):  # an ideal point: no side to point to (the readout says so)
        for art in (marker, shaft, head):
            art.set_data([], [])
        return
    xy, direction = arrow_to_infinity(e, ax)
    if not direction.any():  # inside the image
        marker.set_data([xy[0]], [xy[1]])
        shaft.set_data([], [])
        head.set_data([], [])
        return
    marker.set_data([], [])
    tail = xy - 60 * direction
    shaft.set_data([tail[0], xy[0]], [tail[1], xy[1]])
    head.set_data([xy[0]], [xy[1]])
    # a triangle marker rotated to point along the direction (v grows downwards on screen)
    head.set_marker(arrow_marker(direction, ax))


def _epipolar_readout(
    v: dict, e2: np.ndarray, inside: bool, uv: np.ndarray, l2: np.ndarray, skipped: np.ndarray
) -> str:
    """The text beside :func:`epipolar_lines`.

    The motion, the right epipole ``e2``, how far the depth marks ``uv`` (px) lie from the
    epipolar line ``l2``, and the reference pixels ``skipped`` because they are the left epipole.
    """
    at_inf = abs(e2[2]) < 1e-9
    ep2 = (
        "at infinity (lines parallel)"
        if at_inf
        else f"({e2[0] / e2[2]:.0f}, {e2[1] / e2[2]:.1f}) px, "
        f"|u(e') - c_x| = {abs(e2[0] / e2[2] - (SIZE[0] - 1) / 2):,.0f} px"
    )
    return monospace(
        f"{v['motion']}: baseline {v['baseline']:.2f} m, "
        + (
            f"toe-in {v['toe_in']:g} deg in all (each camera turned {v['toe_in'] / 2:g} deg)\n"
            if v["motion"].startswith("sideways")
            else f"second camera turned {v['toe_in']:g} deg\n"
        )
        + ("the right epipole is inside the image: the lines fan out from it\n" if inside else "")
        + "".join(
            f"the pixel ({u:g}, {w:g}) is the left epipole: its epipolar line is undefined (not drawn)\n"
            for u, w in skipped
        )
        + f"right epipole e' = {ep2}\n"
        f"max distance of the depth marks from l' = "
        f"{np.nanmax(np.abs(np.append(uv, np.ones((len(uv), 1)), 1) @ l2)):.1e} px"
    )


def _epipolar_controls() -> dict:
    """The controls of :func:`epipolar_lines`: the point (u, v), the baseline, the toe-in and the motion."""
    return {
        # 10 px inside the border: the point's marker stays whole at the ends of the sweep
        "u": slider(420.0, 10.0, 629.0, 1.0, "u (px)"),
        "v": slider(300.0, 10.0, 469.0, 1.0, "v (px)"),
        "baseline": slider(0.2, 0.02, 0.5, 0.01, "baseline (m)"),
        "toe_in": slider(10.0, -20.0, 20.0, 0.5, "toe-in, total / turn (deg)"),
        "motion": W.ToggleButtons(
            options=list(MOTIONS),
            value="sideways (stereo rig)",
            description="motion",
            style={"button_width": "150px"},
        ),
    }


@register(
    lesson="11",
    sweep={
        "u": [120.0, 500.0],
        "v": [100.0, 380.0],
        "baseline": [0.05, 0.4],
        "toe_in": [0.0, 15.0, -10.0],
        "motion": list(MOTIONS),
    },
)
def epipolar_lines() -> Demo:
    """Click (or slide) a point in the left image: its epipolar line appears in the right image.

    The world point could be anywhere on the ray through the pixel; its images for depths
    1-6 m are marked on the line. Baseline and toe-in move the cameras: with toe-in 0
    the cameras are parallel and the epipoles go to infinity (all lines horizontal).

    Returns
    -------
    Demo
        The demo: controls ``u``, ``v`` (the left pixel, px; a click in the left image sets
        them), ``baseline`` (m), ``toe_in`` (degrees) and ``motion`` (sideways or forward),
        the figure (both images with the scene's outlines, the epipolar lines, the depth
        marks 1-6 m and the epipoles) and ``state`` (``F``, ``epipoles``, ``line_right`` l',
        ``depth_points`` in px, ``point``, ``epipole_inside``). ``handlers`` holds the click.
    """
    view = BrowserView(
        ("u", "v", "baseline", "toe_in", "motion"), figsize=(9.4, 4.3), choices=("motion",)
    )
    segs = scenes.plane_outlines(stereo_scene())
    art = _epipolar_figure(view)
    axl, axr, shafts, heads = art.axl, art.axr, art.shafts, art.heads
    readout = W.HTML()
    # four pixels, one near each corner, and the centre of the 640 x 480 image (319.5, 239.5), with
    # pixel centres at integers: the pencil of the thin red lines. No two of the four lie on one line
    # through the centre, so in forward motion (epipole at the centre) they give four distinct lines
    ref = REF_PIXELS
    # the fixed pixels themselves, animated: the moving lines' halos would paint over a static marker
    (refs,) = axl.plot(*ref.T, "s", mfc="w", mec=palette.RED, mew=1.5, ms=6, zorder=4)
    view.animate(refs)

    def update(v, state):
        x = np.array([v["u"], v["v"]])
        g = epipolar_view(v["motion"], v["baseline"], v["toe_in"], x, ref)
        c1, c2 = g.cameras
        F, l2, uv = g.F, g.line_right, g.depth_points
        e = ep.epipoles(F)  # unit null vectors of F, for the state and the readout
        art.wl.set_data(*projected_segments(c1, segs).T)
        art.wr.set_data(*projected_segments(c2, segs).T)
        art.point.set_data([x[0]], [x[1]])
        art.line_r.set_data(*line_polyline(l2[None]).T)
        art.line_l.set_data(*line_polyline(g.line_left[None]).T)
        # a reference pixel at the left epipole (the centre, in forward motion) has no epipolar
        # line: epipolar_lines gives NaN there and the pencils skip it rather than draw noise
        on_epipole = np.isnan(g.pencil_right[:, 0])
        art.pencil_r.set_data(*line_polyline(g.pencil_right[~on_epipole]).T)
        art.pencil_l.set_data(*line_polyline(g.pencil_left[~on_epipole]).T)
        state.update(pencil_skipped=ref[on_epipole])
        art.depth_dots.set_data(uv[:, 0], uv[:, 1])
        # the epipoles as the images of the other camera's centre, P' C and P C': the same points as
        # F's null vectors, with a sign that says on which side the other camera is (for w = 0 too)
        e1_dir, e2_dir = g.epipoles
        _show_epipole(e1_dir, art.epi_l, shafts[0], heads[0], axl)
        _show_epipole(e2_dir, art.epi_r, shafts[1], heads[1], axr)
        inside = not arrow_to_infinity(e.e2, axr)[1].any()
        state.update(epipole_inside=inside)
        readout.value = _epipolar_readout(v, e.e2, inside, uv, l2, ref[on_epipole])
        state.update(F=F, epipoles=e, line_right=l2, depth_points=uv, point=x)

    demo = build_demo(
        "epipolar_lines",
        _epipolar_controls(),
        view,
        update,
        title="Epipolar lines: a point in one image is a line in the other",
        extra=[readout],
    )

    def on_click(event):
        if event.inaxes is not axl or event.xdata is None:
            return
        demo.controls["u"].value = float(np.clip(event.xdata, 10, 629))
        demo.controls["v"].value = float(np.clip(event.ydata, 10, 469))

    view.fig.canvas.mpl_connect("button_press_event", on_click)
    demo.handlers["button_press_event"] = (
        on_click  # tests call it with an object carrying inaxes, xdata, ydata
    )
    world = dict(segments=segs, ref=ref, size=SIZE, arrow=ARROW_PATH)
    view.publish(
        demo, epipolar_scene(art, refs, world, demo.controls)
    )  # the browser draws the moves
    return demo


# --------------------------------------------------------------------------- demo 2: rectification


ZOOM = 12  # half-size pixels each side of the zoomed match: 25 x 25 crops


def _crop(img: np.ndarray, u: int, v: int, r: int = ZOOM) -> np.ndarray:
    """The (2r + 1) x (2r + 1) window of ``img`` centred on pixel (u, v), zero outside the image."""
    pad = np.pad(img, r + 1)
    return pad[v + 1 : v + 2 * r + 2, u + 1 : u + 2 * r + 2]


def _zoom_pair(L: np.ndarray, R: np.ndarray, p1: np.ndarray, p2: np.ndarray):
    """Crops of ``L`` and ``R`` around the match, side by side, and where it falls.

    ``L`` around the match's left point ``p1`` and ``R`` around ``p2``, both on the left point's
    row, one black column between; and where the two points and the left point's row fall in that
    strip (its pixels, the left crop's centre at (ZOOM, ZOOM)).
    """
    r = ZOOM
    cu1, cv = (int(round(c)) for c in p1)
    cu2 = int(round(p2[0]))
    strip = np.hstack([_crop(L, cu1, cv), np.zeros((2 * r + 1, 1), L.dtype), _crop(R, cu2, cv)])
    a = np.array([r + p1[0] - cu1, r + p1[1] - cv])
    b = np.array([3 * r + 2 + p2[0] - cu2, r + p2[1] - cv])
    return strip, a, b


def _zoomed_match(left_half: np.ndarray, x1: np.ndarray, x2: np.ndarray) -> int:
    """The match to zoom on.

    Among those 30 px inside the half-size images whose raw vertical disparity exceeds 6 px, the one
    with the most structure around it (the spread of the gradient magnitude over its 17 x 17
    half-size neighbourhood), so the eye can follow it.
    """
    s1 = map_points(HALF, x1)
    inner = np.all((x1 > 60) & (x1 < [579, 419]) & (x2 > 60) & (x2 < [579, 419]), axis=1)
    candidates = np.flatnonzero(inner & (np.abs(x1[:, 1] - x2[:, 1]) > 6))
    grad = np.hypot(*np.gradient(left_half.astype(float)))
    u, v = np.round(s1[candidates]).astype(int).T
    spread = [grad[b - 8 : b + 9, a - 8 : a + 9].std() for a, b in zip(u, v, strict=True)]
    return int(candidates[np.argmax(spread)])


def _zoom_axes(axz, view: FigureView):
    """The zoom panel of :func:`rectify_pair`: the strip image, the left point's row and the two points."""
    r = ZOOM
    axz.set(xticks=[], yticks=[], xlim=(-0.5, 4 * r + 2.5), ylim=(2 * r + 0.5, -0.5))
    axz.set_title("yellow squares, zoomed", fontsize=10)
    zim = axz.imshow(
        np.zeros((2 * r + 1, 4 * r + 3)),
        cmap="gray",
        vmin=0,
        vmax=255,
        interpolation="nearest",
        extent=(-0.5, 4 * r + 2.5, 2 * r + 0.5, -0.5),
    )
    halo = palette.halo(1.0, "k")
    (row,) = axz.plot([], [], color=palette.YELLOW, lw=1.0, ls="--", path_effects=halo)
    dot = dict(ms=7, mfc="none", mec=palette.TAB_CYAN, mew=2, path_effects=palette.halo(2, "k"))
    (dots,) = axz.plot([], [], "o", **dot)
    view.animate(zim, row, dots)
    return zim, row, dots


def _pair_figure(view: FigureView, half: list) -> SimpleNamespace:
    """The figure of :func:`rectify_pair`.

    The ``half``-size pair side by side under a row grid, the match lines, the cumulative histogram
    of vertical disparity and a zoom on one match; returns the moving artists.
    """
    gs = view.fig.add_gridspec(2, 3, width_ratios=[2.6, 0.05, 1], height_ratios=[1.3, 1])
    ax = view.fig.add_subplot(gs[:, 0])
    axh = view.fig.add_subplot(gs[0, 2])
    axz = view.fig.add_subplot(gs[1, 2])
    ax.set(xlim=(-0.5, 639.5), ylim=(239.5, -0.5), xticks=[], yticks=[])
    title = ax.set_title("left | right (half size)", fontsize=10)  # the update names the method
    im = ax.imshow(
        np.hstack(half),
        cmap="gray",
        vmin=0,
        vmax=255,
        extent=(-0.5, 639.5, 239.5, -0.5),
        interpolation="nearest",
    )
    # guides over the animated pair (drawn under it they would be hidden): rows to judge rectification by
    guides = [
        ax.axhline(r, color=palette.YELLOW, lw=0.7, alpha=0.9, gid="grid")
        for r in range(20, 240, 20)
    ]
    guides.append(ax.axvline(319.5, color="w", lw=1, gid="grid"))
    # the true matches: cyan (far from the yellow rows) in a dark halo, a dot at each end
    (match_lines,) = ax.plot(
        [],
        [],
        color=palette.TAB_CYAN,
        lw=1.0,
        marker="o",
        ms=3.5,
        mec="k",
        mew=0.6,
        path_effects=palette.halo(1.0, "k"),
    )
    # Cumulative, on a log axis: raw (pixels), calibrated and uncalibrated (hundredths) all readable.
    (step,) = axh.plot([], [], drawstyle="steps-post", color="0.15", lw=2.5)
    axh.set(
        xscale="log",
        xlim=(1e-3, 30),
        ylim=(0, 1.05),
        xlabel="|v1 - v2| (px, full size, log)",
        ylabel="fraction ≤ x",
    )
    axh.axvline(0.5, color=palette.GREY, ls=":", lw=1)
    # beside the line at mid height, where no curve passes (they cross 0.5 px near 0 or near 1)
    axh.text(
        0.6,
        0.5,
        "0.5 px",
        color="0.35",
        fontsize=7,
        rotation=90,
        va="center",
        transform=axh.get_xaxis_transform(),
    )
    axh.set_title("vertical disparity", fontsize=10)
    axh.grid(True, which="major", color="0.93")
    # the zoomed match, yellow as every mark over a photo (red is kept for epipolar lines)
    mark = dict(ms=9, mfc="none", mec=palette.YELLOW, mew=1.5, path_effects=palette.halo(1.5, "k"))
    (zmark,) = ax.plot([], [], "s", ls="none", **mark)
    view.animate(im, *guides, match_lines, step, zmark, title)
    zim, zrow, zdots = _zoom_axes(axz, view)
    return SimpleNamespace(
        im=im,
        match_lines=match_lines,
        step=step,
        zmark=zmark,
        zim=zim,
        zrow=zrow,
        zdots=zdots,
        title=title,
    )


def _pair_views(method: str, alpha: float, ctx: SimpleNamespace) -> tuple:
    """The half-size pair of :func:`rectify_pair` for ``method``, with its matches.

    Returns the left and right images ``L, R``, the true matches in full-size rectified pixels
    ``y1, y2`` (what the vertical disparity is measured on), the same in half-size pixels
    ``s1, s2`` (what is drawn) and the calibrated route's ``K_new`` (None otherwise).
    """
    import cv2

    (cal1, cal2), (h1, h2), half = ctx.cal, ctx.half_cams, ctx.half
    x1, x2, u1, u2 = ctx.matches
    if method == "calibrated":
        rect = rc.rectify_calibrated(h1, h2, alpha=alpha, method="cv2")
        L, R = rc.rectify_images(rect, half[0], half[1])
        full = rc.rectify_calibrated(cal1, cal2, alpha=alpha, maps=False)
        y1 = rc.rectify_points(full, cal1, x1, 1)
        y2 = rc.rectify_points(full, cal2, x2, 2)
        s1 = rc.rectify_points(rect, h1, map_points(HALF, x1), 1)
        s2 = rc.rectify_points(rect, h2, map_points(HALF, x2), 2)
        return L, R, y1, y2, s1, s2, full.K
    if method == "uncalibrated":
        L, R = (
            cv2.warpPerspective(im_, H, (320, 240))
            for im_, H in zip(ctx.und_half, ctx.unc_half, strict=True)
        )
        y1, y2 = map_points(ctx.unc.H1, u1), map_points(ctx.unc.H2, u2)
        return L, R, y1, y2, map_points(HALF, y1), map_points(HALF, y2), None
    L, R = half
    return L, R, x1, x2, map_points(HALF, x1), map_points(HALF, x2), None


def _pair_readout(method: str, cal_rms: float, vd) -> str:
    """The text beside :func:`rectify_pair`: the route and the true matches' vertical disparity."""
    source = {
        "calibrated": f"cameras from a stereo calibration (rms {cal_rms:.3f} px)",
        "uncalibrated": "F from noisy matches (0.3 px); alpha: calibrated only",
        "original": "the raw pair; alpha: calibrated only",
    }[method]
    return monospace(
        f"{method}: {source}\nvertical disparity of {len(vd.values)} true matches\n"
        f"median {vd.median:.3g} px, 95th percentile {vd.p95:.3g} px"
    )


def _pair_controls() -> dict:
    """The controls of :func:`rectify_pair`: the pair shown (original, calibrated, uncalibrated) and alpha."""
    return {
        "method": W.ToggleButtons(
            options=["original", "calibrated", "uncalibrated"],
            value="calibrated",
            description="pair",
            style={"button_width": "90px"},
        ),
        "alpha": slider(0.0, 0.0, 1.0, 0.05, "alpha (0: crop, 1: keep all)"),
    }


@register(
    lesson="11", sweep={"alpha": [0.5, 1.0], "method": ["original", "calibrated", "uncalibrated"]}
)
def rectify_pair() -> Demo:
    """The rendered pair before and after rectification, with a row grid and the true matches.

    The calibrated route uses the cameras a stereo calibration found
    (:func:`camlab.fixtures.stereo.bundled_rig_calibration`),
    as a real rig would, so its vertical disparity is the calibration's error, not zero.

    After rectification every match line is horizontal and the vertical disparity
    histogram collapses to 0; ``alpha`` trades black borders (1) against lost pixels (0).

    Returns
    -------
    Demo
        The demo: controls ``method`` (the original, calibrated or uncalibrated pair) and
        ``alpha``, the figure (the pair with a row grid and match lines, the cumulative
        vertical disparity) and ``state`` (``vertical_median``, ``vertical_p95`` in full-size
        px, ``vertical_values``, ``method``; ``rectified_K`` once the calibrated route ran).
    """
    import cv2

    _, matches, half, und, unc = bundled_rig()
    und_half = [
        cv2.resize(im_, (320, 240), interpolation=cv2.INTER_AREA) for im_ in und
    ]  # once, not per update
    unc_half = [
        HALF @ H @ np.linalg.inv(HALF) for H in (unc.H1, unc.H2)
    ]  # the same rectification in half-size pixels
    x1, x2, u1, u2 = matches
    cal1, cal2, cal_rms = bundled_rig_calibration()
    h1, h2 = cal1.resized(0.5), cal2.resized(0.5)
    ctx = SimpleNamespace(
        half=half,
        und_half=und_half,
        unc=unc,
        unc_half=unc_half,
        matches=matches,
        cal=(cal1, cal2),
        half_cams=(h1, h2),
    )
    view = FigureView(figsize=(9.4, 3.3))
    art = _pair_figure(view, half)
    im, match_lines, step = art.im, art.match_lines, art.step
    sel = np.linspace(0, len(x1) - 1, 14).astype(int)
    zi = _zoomed_match(half[0], x1, x2)
    readout = W.HTML()

    def update(v, state):
        L, R, y1, y2, s1, s2, K_new = _pair_views(v["method"], v["alpha"], ctx)
        if K_new is not None:
            state.update(rectified_K=K_new)  # alpha sets the zoom of the rectified images
        im.set_data(np.hstack([L, R]))
        art.title.set_text(
            f"left | right (half size): {v['method']}"
            + (f", alpha = {v['alpha']:g}" if v["method"] == "calibrated" else "")
        )
        seg = np.full((len(sel), 3, 2), np.nan)
        seg[:, 0], seg[:, 1] = s1[sel], s2[sel] + [320, 0]
        match_lines.set_data(*seg.reshape(-1, 2).T)
        strip, a, b = _zoom_pair(L, R, s1[zi], s2[zi])
        art.zim.set_data(strip)
        art.zrow.set_data([-0.5, 4 * ZOOM + 2.5], [a[1], a[1]])
        art.zdots.set_data([a[0], b[0]], [a[1], b[1]])
        art.zmark.set_data([s1[zi, 0], s2[zi, 0] + 320], [s1[zi, 1], s2[zi, 1]])
        vd = rc.vertical_disparity(y1, y2)
        values = np.sort(np.clip(vd.values, 1e-3, None))
        step.set_data(
            np.r_[1e-3, values], np.r_[0.0, np.arange(1, len(values) + 1) / max(1, len(values))]
        )
        readout.value = _pair_readout(v["method"], cal_rms, vd)
        state.update(
            vertical_median=vd.median,
            vertical_p95=vd.p95,
            vertical_values=vd.values,
            method=v["method"],
            zoom_offset=float(b[1] - a[1]),  # the zoomed match's vertical disparity, half-size px
        )

    demo = build_demo(
        "rectify_pair",
        _pair_controls(),
        view,
        update,
        title="Rectification makes epipolar lines the same rows",
        extra=[readout],
    )
    alpha = demo.controls["alpha"]

    def alpha_only_when_calibrated(
        change,
    ) -> None:  # alpha sets K_new: only the calibrated route has one
        alpha.disabled = change["new"] != "calibrated"

    demo.controls["method"].observe(alpha_only_when_calibrated, names="value")
    return demo


# --------------------------------------------------------------------------- demo 3: disparity and depth


def _disparity_figure(gt: np.ndarray) -> tuple:
    """The figure of :func:`disparity_depth`: disparity, depth error and the 3-D points.

    ``gt`` is the true disparity the first panel starts with; returns the view and the three
    moving artists (the two images and the points).
    """
    from matplotlib import colormaps

    from ..plotting import scene3d

    plt_colormap = colormaps.get_cmap
    view = FigureView(figsize=(9.4, 3.6))
    # the 2-D maps get the width; the empty fourth column keeps the 3-D panel's z label inside
    gs = view.fig.add_gridspec(1, 4, width_ratios=[1.2, 1.2, 1.0, 0.05])
    ax1 = view.fig.add_subplot(gs[0])
    ax2 = view.fig.add_subplot(gs[1])
    ax3 = scene3d.axes3d(view.fig, gs[2], elev=18, azim=-62)
    for a, t in (
        (ax1, "disparity (half-size px);\ngrey: no match"),
        (ax2, "depth error (%), red: too far,\nblue: too near; grey: no match"),
    ):
        a.set(xticks=[], yticks=[])
        a.set_title(t, fontsize=9)
    # no match (NaN) in the same mid grey in both maps: darker than coolwarm's light-grey 0 %
    viridis = plt_colormap("viridis").with_extremes(bad=palette.GREY)
    coolwarm = plt_colormap("coolwarm").with_extremes(bad=palette.GREY)
    im1 = ax1.imshow(gt, cmap=viridis, vmin=8, vmax=40, interpolation="nearest")
    view.fig.colorbar(
        im1, ax=ax1, shrink=0.85, location="bottom", pad=0.03, label="d (half-size px)"
    )
    # +-2 %: the far wall's 0.7 % pixel-locking bias reads as a clear pink, not a faint tint
    im2 = ax2.imshow(np.zeros_like(gt), cmap=coolwarm, vmin=-2, vmax=2, interpolation="nearest")
    view.fig.colorbar(
        im2,
        ax=ax2,
        shrink=0.85,
        location="bottom",
        pad=0.03,
        label="depth error (%), clipped at ±2",
    )
    ax3.set_title("3-D points, left camera", fontsize=9)
    ax3.set(xlim=(-1.6, 1.6), ylim=(1.0, 4.5), zlim=(-0.8, 1.4))
    ax3.set_box_aspect(None, zoom=1.2)  # fill the panel: the default leaves a wide empty margin
    ax3.set_xlabel("X (m)", fontsize=9, labelpad=-4)
    ax3.set_ylabel("depth Z (m)", fontsize=9, labelpad=0)
    ax3.set_zlabel("up (m)", fontsize=9, labelpad=-4)
    ax3.set(xticks=[-1, 0, 1], yticks=[1, 2, 3, 4], zticks=[-0.5, 0.5])
    ax3.tick_params(labelsize=8, pad=0)
    (pts,) = ax3.plot([], [], [], ".", ms=1.0, color=palette.INDIGO)
    view.animate(im1, im2, pts)
    return view, im1, im2, pts


@register(
    lesson="11",
    sweep={"block_size": [3, 7, 15], "method": ["block matching (numpy)", "SGBM (OpenCV)"]},
)
def disparity_depth() -> Demo:
    """Disparity by block matching (numpy) or SGBM, its depth error, and the 3-D points.

    Small windows are noisy, large ones blur depth edges; SGBM adds smoothness costs
    along 5 directions (OpenCV's single-pass ``MODE_SGBM``). Each result is computed once
    per setting and cached.

    Returns
    -------
    Demo
        The demo: controls ``block_size`` (the matching window, px) and ``method`` (block
        matching in numpy or OpenCV's SGBM), the figure (disparity, depth error, 3-D points)
        and ``state`` (``disparity`` map in half-size px, ``median_error_percent`` of depth,
        ``within_5`` the fraction of matched pixels within 5 % of the true depth,
        ``coverage`` the fraction of textured pixels matched, ``edge_bad`` the fraction of matched
        pixels within 4 px of a depth jump whose disparity is off by more than 1 px).
    """
    import scipy.ndimage as ndi

    rect, L, R, gt, smooth = half_size_rectification()
    f, B = rect.K[0, 0], rect.baseline

    @lru_cache(maxsize=16)  # sliders revisit settings; matching is the slow part
    def match(method: str, block: int) -> np.ndarray:
        if method == "block matching (numpy)":
            return dp.block_matching_disparity(
                L, R, max_disparity=44, block_size=block, min_disparity=8
            )
        return dp.sgbm_disparity(L, R, max_disparity=44, block_size=block, min_disparity=8)

    view, im1, im2, pts = _disparity_figure(gt)
    zt = dp.disparity_to_depth(gt, f, B)
    # near depth jumps: within 4 px of a disparity step over 2 px (a 9 x 9 window's range), where a
    # large window straddles two depths; small windows lose the planes, large ones these pixels
    g = np.nan_to_num(gt, nan=-100.0)
    jumps = np.isfinite(gt) & (ndi.maximum_filter(g, 9) - ndi.minimum_filter(g, 9) > 2)
    readout = W.HTML()

    def update(v, state):
        d = match(v["method"], int(v["block_size"]))
        z = dp.disparity_to_depth(d, f, B)
        err = 100 * (z - zt) / zt
        im1.set_data(d)
        im2.set_data(err)
        # the lesson's matcher colours: block matching indigo, SGBM brown
        pts.set_color(palette.INDIGO if v["method"].startswith("block") else palette.BROWN)
        P = dp.disparity_to_points(d, rect.K, B, step=3)
        pts.set_data_3d(
            P[:, 0], P[:, 2], -P[:, 1]
        )  # camera frame (y down) drawn with depth back, up up
        ok = smooth & np.isfinite(err)
        rel = np.abs(err[ok])
        near = jumps & np.isfinite(d)
        state.update(
            disparity=d,
            edge_bad=float(np.mean(np.abs(d[near] - gt[near]) > 1)),
            median_error_percent=float(np.median(rel)),
            within_5=float(np.mean(rel < 5)),
            coverage=float(ok.sum() / smooth.sum()),
        )
        readout.value = monospace(
            f"{v['method']}, {int(v['block_size'])} x {int(v['block_size'])} window\n"
            f"on textured planes: {100 * state['coverage']:.0f}% matched, median depth error "
            f"{state['median_error_percent']:.2f}%\n"
            f"{100 * state['within_5']:.1f}% of matched pixels within 5% of the true depth\n"
            f"near depth jumps: {100 * state['edge_bad']:.0f}% of matched pixels off by > 1 px"
        )

    controls = {
        "block_size": int_slider(7, 3, 21, "block size (px)", step=2, continuous_update=False),
        "method": W.ToggleButtons(
            options=["block matching (numpy)", "SGBM (OpenCV)"],
            value="block matching (numpy)",
            description="matcher",
            style={"button_width": "150px"},
        ),
    }
    return build_demo(
        "disparity_depth",
        controls,
        view,
        update,
        title="Disparity, depth Z = f B / d, and the 3-D points",
        extra=[readout],
    )
