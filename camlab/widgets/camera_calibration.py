"""Demos for lesson 08, camera calibration.

* :func:`accuracy_vs_views`: recalibrate a known camera from 3-15 views and 0-1 px of corner
  noise; see the estimates' errors against their reported 3-sigma bars.
* :func:`view_inspector`: one real photo (or any calibrated set) with its detected corners, the
  calibrated model's reprojections and the (magnified) residuals.
* :func:`undistort_alpha`: undistort a photo and trade black borders for lost pixels.

Each builds its figure once; updates call camlab.calibration and move artists.
"""

from __future__ import annotations

from types import SimpleNamespace

import ipywidgets as W
import numpy as np

from .. import calibration as C
from .._validate import CamlabInputError, ConvergenceError
from ..fixtures.calibration import real_calibration, real_calibration_k3_fixed
from ..plotting import palette
from ..plotting.calibration import arrow_colours, cap_arrows, image_frame
from ._base import Demo, FigureView, build_demo, register, slider
from .controls import int_slider, monospace

_NAMES = ("fx", "fy", "cx", "cy")
_PX_FLOOR, _PX_CEIL = 1e-2, 300.0  # the log axis of errors and 3 sigma, px
_ARROW_CAP_PX = 60.0  # the view inspector's longest arrow, px: longer ones are drawn this long
_TICK_HALF = 0.25  # half the width of each 3-sigma tick, centred on the error's dot


def _accuracy_figure(view: FigureView, s) -> SimpleNamespace:
    """The figure of :func:`accuracy_vs_views`.

    Each intrinsic's actual error (a dot) against three reported sigma (a tick), px on a log axis (left),
    and the corners used (right); returns its animated artists by name.
    """
    ax, axi = view.fig.subplots(1, 2, width_ratios=[1, 1.3])
    # In pixels on a log axis, so more views and less noise visibly lower both the bars and the
    # dots; a dot above its bar is an error beyond 3 reported sigma (the sigma is too optimistic).
    ax.set(
        xlim=(-0.6, 3.6),
        ylim=(_PX_FLOOR, _PX_CEIL),
        yscale="log",
        xticks=range(4),
        xticklabels=_NAMES,
        ylabel="px (log scale)",
        title="|error| against 3 × reported σ",
    )
    ax.title.set_fontsize(10)
    ax.grid(True, axis="y", which="major", color="0.9")
    # 3 reported sigma as a horizontal tick, the error as a dot on the same x: a dot above its
    # tick is an error beyond 3 sigma (on a log axis only heights mean something, so no bars)
    bars = ax.hlines(
        np.full(4, _PX_FLOOR),
        np.arange(4) - _TICK_HALF,
        np.arange(4) + _TICK_HALF,
        color=palette.BLUE,
        lw=3,
        label="3 × reported σ",
    )
    (dots,) = ax.plot([], [], "o", color="k", ms=6, ls="none", label="|actual error|")
    (above,) = ax.plot(
        [], [], "^", ls="none", color="k", ms=10
    )  # beyond the axis (not seen in practice)
    title = ax.title
    view.animate(bars, dots, above, title)
    ax.legend(
        loc="upper center",
        bbox_to_anchor=(0.5, -0.1),
        ncol=2,
        fontsize=7,
        handlelength=1.2,
        handletextpad=0.9,
    )
    view.animate(ax.get_legend())  # below the axes, off the data
    image_frame(axi, s.image_size, "Corners used; the last view added in black")
    pts = axi.scatter(np.zeros(0), np.zeros(0), s=3, color="0.55", linewidths=0)
    (last,) = axi.plot([], [], ".", color="k", ms=4)  # no purple: magenta-like is for residuals
    (outline,) = axi.plot([], [], "-", color="k", lw=1)
    view.animate(pts, last, outline)
    return SimpleNamespace(
        dots=dots, above=above, bars=bars, pts=pts, last=last, outline=outline, title=title
    )


def _accuracy_readout(n, sigma, res, s, est, std, truth, err, z) -> str:
    """The text beside :func:`accuracy_vs_views`.

    Each estimate with its reported sigma, the truth and the error in sigmas (a dash without
    noise, where both are rounding noise).
    """
    lines = [f"{n} views, noise σ = {sigma:.2f} px, rms = {res.rms:.3f} px per corner"]
    lines += [
        f"{k:>2} = {e:8.2f} ± {sd:5.2f}  (true {t:.1f}, error {round(d, 2) + 0.0:+.2f}"
        + (f" = {zz:+.1f}σ)" if np.isfinite(zz) else ")")
        for k, e, sd, t, d, zz in zip(_NAMES, est, std, truth, err, z, strict=True)
    ]
    lines.append(f"k1 = {res.dist[0]:+.3f} ± {res.std['k1']:.3f}  (true {s.dist[0]:+.3f})")
    if sigma == 0:
        lines.append("no noise: errors and σ are both rounding noise (not drawn)")
    return monospace("\n".join(lines))


def _accuracy_controls() -> dict:
    """The controls of :func:`accuracy_vs_views`: the number of views and the corner noise."""
    return {
        "n_views": int_slider(6, 3, 15, "views"),
        "noise": slider(0.3, 0.0, 1.0, 0.05, "corner noise σ (px)"),
    }


def _accuracy_title(n: int, sigma: float, err: np.ndarray, std: np.ndarray) -> str:
    """The title of :func:`accuracy_vs_views`: the setting and how many errors lie beyond 3 sigma."""
    outside = int(np.sum(np.abs(err) > 3 * std)) if sigma > 0 else 0
    if sigma == 0:
        verdict = "no noise, no error"
    else:
        verdict = f"{outside} of 4 beyond 3σ" if outside else "all within 3σ"
    return f"{n} views, σ = {sigma:.2f} px: {verdict}"


@register(lesson="08", sweep={"n_views": [3, 6, 10, 15], "noise": [0.0, 0.3, 1.0]})
def accuracy_vs_views() -> Demo:
    """Calibrate from the first n views with sigma px of noise: each error against 3 reported sigma.

    Returns
    -------
    Demo
        The demo: controls ``n_views`` (3-15 views of the lesson's synthetic camera) and
        ``noise`` (the corner noise sigma, px), the figure (each intrinsic's absolute error
        beside three reported sigma, px on a log axis, and the corners used) and ``state`` (``K``, ``dist``, ``errors``,
        ``std``, ``z``, ``rms``, ``n_views``, ``noise``).
    """
    s = C.make_synthetic_views(15, 0.0, rng=np.random.default_rng(0))  # the lesson's camera, exact
    unit = np.random.default_rng(1).normal(size=(15, len(s.object_points), 2))  # scaled by sigma
    truth = np.array([s.K[0, 0], s.K[1, 1], s.K[0, 2], s.K[1, 2]])
    view = FigureView(figsize=(9.4, 3.9))
    art = _accuracy_figure(view, s)
    dots, above, pts = art.dots, art.above, art.pts
    cols, n_pts = int(np.sum(s.object_points[:, 1] == s.object_points[0, 1])), len(s.object_points)
    board = [0, cols - 1, n_pts - 1, n_pts - cols, 0]  # the board's outer corners, in a loop
    readout = W.HTML()
    # Warm start: each update starts LM from the previous solution (K, dist and every view's
    # last pose) instead of Zhang's closed form. The minimum is the same (a full calibration
    # from scratch agrees to ~1e-6 relative, see the tests); LM just gets there in a few iterations.
    first = C.calibrate_camera(
        s.object_points, [s.exact[i] + 0.3 * unit[i] for i in range(len(unit))], s.image_size
    )
    warm = {"K": first.K, "dist": first.dist, "poses": np.column_stack([first.rvecs, first.tvecs])}

    def update(v: dict, state: dict) -> None:
        n, sigma = int(v["n_views"]), float(v["noise"])
        obs = [s.exact[i] + sigma * unit[i] for i in range(n)]
        pts.set_offsets(np.concatenate(obs[:-1]) if n > 1 else np.zeros((0, 2)))
        art.last.set_data(obs[-1][:, 0], obs[-1][:, 1])
        art.outline.set_data(obs[-1][board, 0], obs[-1][board, 1])  # the board's outer corners
        try:
            res = C.calibrate_camera(
                s.object_points,
                obs,
                s.image_size,
                K_guess=warm["K"],
                dist_guess=warm["dist"],
                pose_guess=warm["poses"][:n],
            )
            warm.update(K=res.K, dist=res.dist)
            warm["poses"][:n] = np.column_stack([res.rvecs, res.tvecs])
        except (CamlabInputError, ConvergenceError) as exc:
            state.update(K=None, dist=None, errors=None, std=None, rms=None)
            for artist in (dots, above):
                artist.set_data([], [])
            art.bars.set_segments([])
            readout.value = monospace(f"calibration failed:\n{exc}")
            return
        est = np.array([res.intrinsics[k] for k in _NAMES])
        std = np.array([res.std[k] for k in _NAMES])
        err = est - truth
        with np.errstate(divide="ignore", invalid="ignore"):
            # no noise: both ~1e-12, their ratio is meaningless
            z = np.where(std > 1e-9, err / std, np.nan)
        state.update(
            K=res.K, dist=res.dist, errors=err, std=std, z=z, rms=res.rms, n_views=n, noise=sigma
        )
        x = np.arange(4)
        top = _PX_CEIL / 1.3  # clipped values sit just inside the axis
        bar = np.clip(3 * std, _PX_FLOOR, top)
        art.bars.set_segments(
            [[(xi - _TICK_HALF, b), (xi + _TICK_HALF, b)] for xi, b in zip(x, bar, strict=True)]
        )
        size = np.clip(np.abs(err), _PX_FLOOR * 1.3, top)
        dots.set_data(x, size)
        if (
            sigma == 0
        ):  # both are rounding noise: a dot above a tick at the floor would read "beyond 3σ"
            dots.set_data([], [])
            art.bars.set_segments([])
        clipped = np.abs(err) > top
        above.set_data(x[clipped], np.full(clipped.sum(), top))
        art.title.set_text(_accuracy_title(n, sigma, err, std))
        readout.value = _accuracy_readout(n, sigma, res, s, est, std, truth, err, z)

    return build_demo(
        "accuracy_vs_views",
        _accuracy_controls(),
        view,
        update,
        title="Accuracy against views and noise",
        extra=[readout],
    )


def _inspector_figure(view: FigureView, res) -> SimpleNamespace:
    """The figure of :func:`view_inspector`.

    The photo, the detected and the reprojected corners and the residual arrows; returns its
    animated artists by name.
    """
    ax = view.fig.subplots()
    image_frame(ax, res.image_size)
    w, h = res.image_size
    im = view.animate(
        ax.imshow(
            np.zeros((h, w)), cmap="gray", vmin=0, vmax=255, extent=(-0.5, w - 0.5, h - 0.5, -0.5)
        )
    )
    (det,) = ax.plot(
        [],
        [],
        "+",
        color=palette.TAB_RED,
        ms=8,
        mew=1.5,
        label="detected",
        path_effects=palette.halo(1.5),
    )
    (rep,) = ax.plot(
        [],
        [],
        "o",
        mfc="none",
        color=palette.TAB_BLUE,
        ms=6,
        label="reprojected",
        path_effects=palette.halo(),
    )
    (worst,) = ax.plot(
        [],
        [],
        "o",
        mfc="none",
        color="k",
        ms=15,
        mew=1.6,
        label="worst corner",
        path_effects=palette.halo(1.6),
    )
    view.animate(det, rep, worst)
    # the legend's entry for the arrows (a quiver has no legend handle of its own)
    ax.plot(  # haloed black, as magenta alone is 3.1:1 on the legend's white
        [],
        [],
        "-",
        color=palette.MAGENTA,
        lw=1.5,
        label="residual, from o to +",
        path_effects=palette.halo(1.5, "black"),
    )
    ax.plot([], [], "-", color="k", lw=1.5, label="capped residual")
    n = len(res.object_points[0])
    arrows = view.animate(
        ax.quiver(
            np.zeros(n),
            np.zeros(n),
            np.zeros(n),
            np.zeros(n),
            color=palette.MAGENTA,
            angles="xy",
            scale_units="xy",
            scale=1,
            width=0.004,
            edgecolor="w",
            linewidth=0.4,
        )
    )
    # below the photo, off the corners and arrows
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.11), fontsize=8, ncol=5, frameon=False)
    ax.set_title(" \n ", fontsize=10)  # two lines: room kept for the animated title
    view.animate(ax.title)  # names the view, its rms, the arrows' magnification and the capped ones
    return SimpleNamespace(im=im, det=det, rep=rep, worst=worst, arrows=arrows, title=ax.title)


def _inspector_controls(n_views: int) -> dict:
    """The controls of :func:`view_inspector`.

    The view (0 to ``n_views`` - 1) and the arrows' magnification.
    """
    return {
        "view": int_slider(0, 0, n_views - 1, "view"),
        "magnify": slider(
            100.0, 10.0, 300.0, 1.0, "arrow magnification"
        ),  # 300 x 0.4 px: 120 px arrows
    }


@register(lesson="08", sweep={"view": [0, 5, 13], "magnify": [10.0, 100.0, 300.0]})
def view_inspector(
    calibration: C.ImageCalibration | None = None, images: list | None = None
) -> Demo:
    """Each photo with detected corners (+), reprojected corners (o) and residual arrows x magnify.

    Parameters
    ----------
    calibration : camlab.calibration.ImageCalibration, optional
        The outcome of :func:`camlab.calibration.calibrate_from_images`. Default: the 14 real
        photos in data/photos, calibrated once (:func:`camlab.fixtures.calibration.real_calibration`),
        as lesson 08 shows them.
    images : list of (H, W) arrays, optional
        The images ``calibration`` was computed from, in its input order (grey levels 0-255).
        Default: the real photos when ``calibration`` is the default too; with a
        ``calibration`` of your own and no ``images``, each view shows a grey background.

    Returns
    -------
    Demo
        The demo: controls ``view`` (which used view) and ``magnify`` (the residual arrows'
        scale), the figure (the photo, detected and reprojected corners, residual arrows) and
        ``state`` (``view``, ``image_index``, ``rms`` in px, ``worst_corner``,
        ``longest_arrow_px``).
    """
    if calibration is None:
        calibration, photos = real_calibration()
        images = photos if images is None else images
    out = calibration
    res = out.result
    view = FigureView(figsize=(7.5, 5))
    art = _inspector_figure(view, res)
    w, h = res.image_size
    readout = W.HTML()

    def update(v: dict, state: dict) -> None:
        k = int(v["view"])
        i = out.used[k]
        img = images[i] if images is not None else None
        art.im.set_data(img if img is not None else np.full((h, w), 128.0))
        obs = res.image_points[k]
        pred = res.reprojected(k)
        r = res.residuals[k]
        art.det.set_data(obs[:, 0], obs[:, 1])
        art.rep.set_data(pred[:, 0], pred[:, 1])
        art.arrows.set_offsets(pred)
        # as the coach's residual field: longer than _ARROW_CAP_PX, or leaving the photo, drawn black
        d, capped = cap_arrows(pred, r * v["magnify"], _ARROW_CAP_PX, res.image_size)
        art.arrows.set_facecolor(
            arrow_colours(capped)
        )  # the white edge stays: black reads on black squares
        art.arrows.set_UVC(d[:, 0], d[:, 1])
        worst = int(np.argmax(np.linalg.norm(r, axis=1)))
        art.worst.set_data(obs[worst, :1], obs[worst, 1:])
        state.update(
            view=k,
            image_index=i,
            rms=float(res.per_view_rms[k]),
            worst_corner=worst,
            longest_arrow_px=float(np.linalg.norm(r[worst]) * v["magnify"]),
            capped_arrows=int(capped.sum()),
        )
        art.title.set_text(
            f"view {k} ({out.names[i]}): rms {res.per_view_rms[k]:.3f} px, "
            f"worst corner {np.linalg.norm(r[worst]):.3f} px; arrows ×{v['magnify']:.0f}\n"
            + (
                f"black: {capped.sum()} capped at {_ARROW_CAP_PX:.0f} px or the frame"
                if capped.any()
                else "no arrow capped"
            )
        )
        readout.value = monospace(
            f"view {k} ({out.names[i]})\nrms {res.per_view_rms[k]:.3f} px "
            f"(median view {np.median(res.per_view_rms):.3f})\nworst corner (index {worst}): "
            f"{np.linalg.norm(r[worst]):.3f} px (ringed)\narrows ×{v['magnify']:.0f}"
            + (
                f", {capped.sum()} capped at {_ARROW_CAP_PX:.0f} px or the frame (black)"
                if capped.any()
                else ""
            )
        )

    return build_demo(
        "view_inspector",
        _inspector_controls(res.n_views),
        view,
        update,
        title="Detected versus reprojected corners",
        extra=[readout],
    )


def _undistort_figure(image: np.ndarray) -> tuple[FigureView, SimpleNamespace]:
    """The figure of :func:`undistort_alpha`: the photo and its undistorted version, 30 px margins.

    Returns the view and the artists updates move (``ax1``, ``im``, ``edge``, ``kept``).
    """
    h, w = image.shape[:2]
    view = FigureView(figsize=(9, 3.8))
    ax0, ax1 = view.fig.subplots(1, 2)
    image_frame(ax0, (w, h))
    ax0.imshow(image, cmap="gray", vmin=0, vmax=255, extent=(-0.5, w - 0.5, h - 0.5, -0.5))
    image_frame(ax1, (w, h), "undistorted, α = 0.00\nfx 000 px (photo 000)")  # 2 lines: room kept
    pad = 30  # px of white margin: the border (right) and the output's frame (left) run outside
    for a in (ax0, ax1):
        a.set(xlim=(-0.5 - pad, w - 0.5 + pad), ylim=(h - 0.5 + pad, -0.5 - pad))
    ax0.set_title("distorted photo\n(dashed: what the output shows)", fontsize=9)
    view.fig.set_layout_engine(None)  # the layout ignores an animated title: reserve its room
    view.fig.subplots_adjust(left=0.07, right=0.99, top=0.87, bottom=0.21, wspace=0.17)
    view.animate(ax1.title)  # the new focal length
    im = view.animate(
        ax1.imshow(
            np.zeros((h, w)), cmap="gray", vmin=0, vmax=255, extent=(-0.5, w - 0.5, h - 0.5, -0.5)
        )
    )
    (edge,) = ax1.plot(
        [], [], color=palette.ORANGE, lw=1.5, label="photo's border", path_effects=palette.halo(1.5)
    )
    (kept,) = ax0.plot(
        [],
        [],
        "--",
        color=palette.ORANGE,
        lw=1.5,
        label="what the output shows",
        path_effects=palette.halo(1.5),
    )
    view.animate(edge, kept)
    for a in (ax0, ax1):  # below the photos, off the data
        a.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), fontsize=8, frameon=False, ncol=2)
    return view, SimpleNamespace(ax1=ax1, im=im, edge=edge, kept=kept)


@register(lesson="08", sweep={"alpha": [0.0, 0.5, 1.0]})
def undistort_alpha(
    image: np.ndarray | None = None, K: np.ndarray | None = None, dist: np.ndarray | None = None
) -> Demo:
    """Undistort a photo; alpha trades black borders (alpha = 1) for cropped pixels (alpha = 0).

    Parameters
    ----------
    image : (H, W) or (H, W, 3) array, optional
        The distorted photo (0-255). Default, or when ``K`` is not given: the real photo
        ``calib_left03`` with the calibration of the 14 real photos with k3 fixed at 0
        (:func:`camlab.fixtures.calibration.real_calibration_k3_fixed`, as lesson 08 recommends
        for them; the three replace whatever was passed).
    K : (3, 3) array, optional
        The camera matrix the photo was taken with (px).
    dist : array of 5, optional
        Its distortion coefficients, in OpenCV's order (k1, k2, p1, p2, k3).

    Returns
    -------
    Demo
        The demo: control ``alpha`` (0 crops to valid pixels, 1 keeps every photo pixel), the
        figure (the photo beside its undistorted version with the photo's border traced) and
        ``state`` (``new_K``, ``black_fraction``, ``lost_fraction``).
    """
    if image is None or K is None:
        res = real_calibration_k3_fixed()
        image, K, dist = real_calibration().photos[2], res.K, res.dist
    h, w = image.shape[:2]
    view, art = _undistort_figure(image)
    ax1, im, edge, kept = art.ax1, art.im, art.edge, art.kept
    t = np.linspace(0, 1, 40)
    border = np.concatenate(
        [
            np.column_stack([t * (w - 1), 0 * t]),
            np.column_stack([(w - 1) + 0 * t, t * (h - 1)]),
            np.column_stack([(1 - t) * (w - 1), (h - 1) + 0 * t]),
            np.column_stack([0 * t, (1 - t) * (h - 1)]),
        ]
    )
    from ..distortion import distort_pixels, undistort_pixels

    border_ideal = undistort_pixels(border, K, dist)  # ideal pixels with the old K
    readout = W.HTML()

    def update(v: dict, state: dict) -> None:
        out = C.undistort(image, K=K, dist=dist, alpha=float(v["alpha"]))
        im.set_data(out.image)
        b = (border_ideal - K[:2, 2]) / np.diag(K)[:2] * np.diag(out.K)[:2] + out.K[:2, 2]
        edge.set_data(b[:, 0], b[:, 1])
        # the output's frame, traced back into the photo: outside it, photo pixels are lost
        seen = distort_pixels(
            (border - out.K[:2, 2]) / np.diag(out.K)[:2] * np.diag(K)[:2] + K[:2, 2], K, dist
        )
        kept.set_data(seen[:, 0], seen[:, 1])
        ax1.set_title(
            f"undistorted, α = {v['alpha']:.2f}\nfx {out.K[0, 0]:.0f} px (photo {K[0, 0]:.0f})",
            fontsize=9,
        )
        state.update(
            new_K=out.K, black_fraction=out.black_fraction, lost_fraction=out.lost_fraction
        )
        readout.value = monospace(
            f"alpha = {v['alpha']:.2f}\nnew fx = {out.K[0, 0]:.1f} (was {K[0, 0]:.1f})\n"
            f"black border: {100 * out.black_fraction:.1f}% of the output\n"
            f"photo pixels lost: {100 * out.lost_fraction:.1f}%"
        )

    # halfway by default: the border crosses the frame (at 0 it lies outside, invisible)
    controls = {"alpha": slider(0.5, 0.0, 1.0, 0.05, "alpha")}
    return build_demo(
        "undistort_alpha",
        controls,
        view,
        update,
        title="Undistortion: crop or keep everything?",
        extra=[readout],
    )
