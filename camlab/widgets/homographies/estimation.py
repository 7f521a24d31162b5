"""Lesson 07 demos on fitting and applying a homography: RANSAC against outliers, forward versus inverse warping."""

from __future__ import annotations

from functools import lru_cache
from types import SimpleNamespace

import ipywidgets as W
import numpy as np
from matplotlib.patches import Rectangle

from ... import fixtures, scenes
from ... import homography as hg
from ..._validate import DegenerateError
from ...plotting import palette
from ...projective import (
    map_points,
)
from ...robust import required_iterations
from .._base import Demo, FigureView, build_demo, register, slider
from ..browser import BrowserView
from ..browser.homography_scenes import forward_inverse_scene
from ..controls import (
    monospace,
)
from .notes import warning_note
from .twins import forward_inverse_fixed, forward_inverse_view

CONFIDENCE = 0.995  # RANSAC's confidence p in the demo
MAX_SAMPLES = 1000  # RANSAC's cap on the samples drawn in the demo

# ----------------------------------------------------------------------------- RANSAC

# What RANSAC did with each pair, against the truth the demo knows.
_VERDICTS = (
    ("inlier, kept", palette.GREEN),
    ("outlier, wrongly kept", palette.RED),
    ("inlier, wrongly rejected", palette.BLUE),
    ("outlier, rejected", palette.GREY),
)


def _ransac_figure() -> SimpleNamespace:
    """The RANSAC demo's figure: the pairs' panel and the k(ε) panel, with their animated artists."""
    from matplotlib.collections import LineCollection

    view = FigureView(figsize=(9.6, 4.8))
    ax, ax_k = view.fig.subplots(1, 2, width_ratios=[1.35, 1])
    ax.set(
        xlim=(-10, 440), ylim=(330, -40), aspect="equal", xlabel="u (pixels)", ylabel="v (pixels)"
    )
    ax.set_title("each pair: a line from src to a dot at dst", fontsize=10, pad=3)
    # rejected outliers thin and underneath, so the pairs with a verdict worth reading show through
    rejected = view.animate(ax.add_collection(LineCollection([], lw=0.5, color=palette.GREY)))
    arrows = view.animate(ax.add_collection(LineCollection([], lw=1.0)))
    heads = view.animate(ax.scatter(np.zeros(0), np.zeros(0), s=6))
    box_true = view.animate(  # a wide band (3.4:1 on white): RANSAC's dashed frame lies on it
        ax.plot([], [], "-", color="0.55", lw=6, label="frame mapped by the true H (grey band)")[0]
    )
    box_est = view.animate(
        ax.plot([], [], "--", color="k", lw=1.5, label="frame mapped by RANSAC's H")[0]
    )
    best = view.animate(
        ax.plot([], [], "o", mfc="none", mec="k", mew=2, ms=11, label="the winning sample of 4")[0]
    )
    # "wrongly kept" is told from "kept" by its open triangle as well as its hue (red and green
    # look alike to a deuteranope)
    wrong = view.animate(ax.plot([], [], "^", mfc="white", mec=palette.RED, mew=1.2, ms=6)[0])
    for name, colour in _VERDICTS:
        marker = dict(marker="^", mfc="white", mec=colour, ms=6) if colour == palette.RED else {}
        ax.plot([], [], "-", color=colour, lw=2, label=name, **marker)
    # Below the figure (the layout makes room), never over the arrows; under the left panel it describes.
    view.fig.legend(*ax.get_legend_handles_labels(), loc="outside lower left", fontsize=8, ncol=3)
    # Between the legend and the cap line (the batch note's place, hidden then), off the k(ε) curve.
    failure = warning_note(view, ax_k, 0.03, 0.72, "left", "top")
    eps = np.linspace(0.0, 0.97, 300)
    k_curve = [required_iterations(1.0 - e, CONFIDENCE, 4) for e in eps]
    ax_k.semilogy(eps, k_curve, color="0.5", label="k: samples needed for p = 0.995 (exercise 3)")
    ax_k.axhline(MAX_SAMPLES, color="0.3", ls=":", lw=1, label=f"the cap: {MAX_SAMPLES} samples")
    needed = view.animate(
        ax_k.plot(
            [],
            [],
            "o",
            mfc="none",
            mec="k",
            mew=1.5,
            ms=10,
            label="k for the ε RANSAC found (ring)",
        )[0]
    )
    dot = view.animate(
        ax_k.plot([], [], "o", color="k", ms=5, label="samples drawn, at the same ε (dot)")[0]
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
    batches = view.animate(
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
    )
    return SimpleNamespace(
        view=view,
        arrows=arrows,
        rejected=rejected,
        heads=heads,
        box_true=box_true,
        box_est=box_est,
        best=best,
        failure=failure,
        wrong=wrong,
        needed=needed,
        dot=dot,
        batches=batches,
    )


@lru_cache(maxsize=256)  # sliders revisit settings; the answer is a pure (seeded) function of them
def _ransac_run(outlier_fraction: float, threshold: float, seed: int, near: float = 0.0):
    """The demo's data and RANSAC's answer, or its error message."""
    data = fixtures.outlier_matches(outlier_fraction, seed, near_share=near)
    try:
        return data, hg.ransac_homography(
            data[1], data[2], threshold, CONFIDENCE, MAX_SAMPLES, np.random.default_rng(seed)
        )
    except DegenerateError as exc:
        return data, str(exc)


def _ransac_failed(art, state, src, dst, exc) -> None:
    """RANSAC failed: clear the last answer's marks and draw the pairs without a verdict."""
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
    for artist in (art.box_est, art.dot, art.needed, art.best, art.wrong):
        artist.set_data([], [])
    # the pairs are still the data: drawn in one neutral grey, since there is no verdict
    art.arrows.set_segments(np.stack([src, dst], axis=1))
    art.arrows.set_color("0.8")
    art.arrows.set_linewidth(1.0)
    art.rejected.set_segments([])
    art.heads.set_offsets(dst)
    art.heads.set_color("0.8")
    art.batches.set_visible(False)
    art.failure(
        "RANSAC failed: no hypothesis had real support.\n"
        "Pairs in light grey: the legend's verdicts\n"
        "do not apply (message beside the sliders)"
    )


@register(
    lesson="07",
    sweep={
        "outliers": [0.1, 0.4, 0.7],
        "threshold": [1.0, 3.0, 8.0],
        "seed": [0, 3],
        "near": [0.5, 1.0],
    },
)
def ransac_outliers() -> Demo:
    """RANSAC against a growing outlier fraction ε: each pair's verdict and the samples drawn.

    The 200 pairs of :func:`camlab.fixtures.outlier_matches` (a 400 x 300 image, 1 px of
    noise, a fraction ε of them wrong: random, or a chosen share of them 4 to 15 px off the true H,
    as parallax places real mismatches) go to :func:`camlab.homography.ransac_homography`
    with confidence p = :data:`CONFIDENCE` and at most :data:`MAX_SAMPLES` samples. Each
    pair's verdict is judged against the truth the demo knows, and the samples drawn are
    set against k, the number needed for the ε found (H&Z section 4.7.1; exercise 3).
    RANSAC draws its samples in numpy batches (16, then up to 64), so when its estimate of ε
    improves mid-batch it draws up to one batch more than k: the dot of samples drawn then sits
    above the ring of k (at seed 0 and 3 px, 80 drawn against k = 45); at a tiny threshold it
    stops at the cap. The two wrong verdicts (red, blue) are drawn heavier than the right ones.
    Results are cached per setting, so revisiting one redraws without re-running RANSAC.

    Returns
    -------
    Demo
        The demo: controls ``outliers`` (the true outlier fraction ε), ``threshold``
        (RANSAC's inlier threshold, px), ``near`` (the share of the outliers placed near the
        model) and ``seed`` (of both the data and RANSAC), the
        figure (left: each pair as a line from src to a dot at dst, coloured by its verdict,
        the image frame mapped by the true H and by RANSAC's H, and the winning sample of 4;
        right: k against ε on a log scale, the cap, the k needed for the ε found and the
        samples drawn) and ``state`` (``H`` RANSAC's estimate, ``sample`` the indices of
        its winning 4 pairs, ``iterations`` the samples drawn, ``inliers`` their count,
        ``recall`` the share of the true inliers kept, ``corner_error`` the worst corner of
        the mapped frame against the truth in px, ``verdicts`` the counts of inlier kept,
        outlier wrongly kept, inlier wrongly rejected and outlier rejected,
        ``outlier_fraction_found`` 1 - the inlier share, ``samples_needed`` k for it rounded up, and
        ``error``, None or RANSAC's message when it fails; then every key above but
        ``sample`` is None).

    References
    ----------
    .. [1] M. A. Fischler and R. C. Bolles, 1981, "Random sample consensus: a paradigm for model
       fitting with applications to image analysis and automated cartography",
       *Communications of the ACM* 24(6), 381-395.
    .. [2] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 4.7.1
       (how many samples?).
    """
    art = _ransac_figure()
    view = art.view
    readout = W.HTML()
    frame = np.array([[0, 0], [399, 0], [399, 299], [0, 299], [0, 0]], float)

    def update(v: dict, state: dict) -> None:
        from matplotlib.colors import to_rgba

        (H, src, dst, out), r = _ransac_run(
            float(v["outliers"]), float(v["threshold"]), int(v["seed"]), float(v["near"])
        )
        if isinstance(r, str):  # RANSAC failed: clear the last result, a stale plot would be a lie
            _ransac_failed(art, state, src, dst, r)
            readout.value = monospace(r)
            return
        art.failure("")
        art.batches.set_visible(True)
        verdict = np.select([~out & r.inliers, out & r.inliers, ~out & ~r.inliers], [0, 1, 2], 3)
        colours = np.array([to_rgba(c) for _, c in _VERDICTS])[verdict]
        order = np.argsort(
            -verdict
        )  # rejected outliers first, so the interesting arrows sit on top
        segments, kept = np.stack([src, dst], axis=1)[order], verdict[order] != 3
        art.rejected.set_segments(segments[~kept])  # thin, underneath
        art.arrows.set_segments(segments[kept])
        art.arrows.set_color(colours[order][kept])
        # the two wrong verdicts (red, blue) heavier, so a few stand out among ~200 green lines
        art.arrows.set_linewidth(np.where(np.isin(verdict[order][kept], (1, 2)), 2.2, 1.0))
        art.heads.set_offsets(dst[order])
        art.heads.set_color(colours[order])
        bt, be = map_points(H, frame), map_points(r.H, frame)
        art.box_true.set_data(bt[:, 0], bt[:, 1])
        art.box_est.set_data(be[:, 0], be[:, 1])
        art.best.set_data(dst[r.sample, 0], dst[r.sample, 1])
        art.wrong.set_data(dst[verdict == 1, 0], dst[verdict == 1, 1])
        eps_found = 1.0 - r.inliers.mean()
        k_needed = required_iterations(1.0 - eps_found, CONFIDENCE, 4)
        art.dot.set_data(
            [eps_found], [r.iterations]
        )  # RANSAC knows only the ε it found, not the true one
        art.needed.set_data([eps_found], [k_needed])
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
            samples_needed=int(np.ceil(k_needed)),  # whole samples: rounded up, never to nearest
        )
        readout.value = monospace(
            f"true ε = {v['outliers']:.2f}, found ε = {eps_found:.2f}\n"
            f"samples drawn: {r.iterations}{' (the cap)' if r.iterations >= MAX_SAMPLES else ''}; "
            f"needed for the found ε: k = {k_needed:.1f}, so {int(np.ceil(k_needed))} samples\n"
            + "\n".join(
                f"{name:25s} {c:4d}" for (name, _), c in zip(_VERDICTS, counts, strict=True)
            )
            + f"\nframe corners, RANSAC H vs true H: worst {err:.1f} px apart"
        )

    controls = {
        "outliers": slider(0.4, 0.0, 0.8, 0.05, "outlier fraction ε"),
        "threshold": slider(3.0, 0.5, 10.0, 0.5, "threshold (px)"),
        "near": slider(0.0, 0.0, 1.0, 0.25, "outliers near H (share)"),
        "seed": W.IntSlider(value=0, min=0, max=9, description="seed"),
    }
    return build_demo("ransac_outliers", controls, view, update, title="RANSAC", extra=[readout])


# ----------------------------------------------------------------------------- forward vs inverse

ZOOM = (81, 108, 18, 24)
"""The zoomed window of both warps: (top row, left column, height, width) in output pixels, centred
on the canvas's centre (119.5, 89.5), where the picture's centre lands at every scale and angle: it
lies inside the covered area, one pixel clear of its rim, at every angle from scale 0.6 up, so the
enlarged panels always show the picture (the door and the wall at 0.6 and 1, the wall at 2)."""


def _label_warp_axes(ax_f, ax_z, ax_zi, ax_i):
    """Titles and axis labels of the four panels: forward, its box enlarged, the inverse's, inverse."""
    ax_f.set_title("forward: push each source pixel\n(holes lime green)", fontsize=10, pad=6)
    ax_z.set_title("forward, yellow box\nenlarged", fontsize=10, pad=6)
    ax_zi.set_title("inverse, yellow box\nenlarged: no holes", fontsize=10, pad=6)
    for ax_ in (ax_f, ax_z, ax_zi, ax_i):
        ax_.set(xlabel="u (pixels)", ylabel="v (pixels)")
    ax_i.set_title("inverse: pull each output pixel", fontsize=10, pad=6)


@register(lesson="07", sweep={"scale": [0.6, 1.5, 2.8], "angle": [0.0, 25.0]})
def forward_vs_inverse() -> Demo:
    """Forward mapping leaves holes where H magnifies; inverse mapping never does.

    An 80 x 60 picture is given a small projective part (v = (1e-3, 0)), scaled and rotated
    about its centre, then warped into a 240 x 180 output twice, nearest neighbour both
    times: forward (:func:`camlab.warp.forward_warp`, each source pixel pushed to where H
    sends it) and inverse (:func:`camlab.warp.warp_perspective`, each output pixel pulled
    from where H^-1 sends it). The area the picture covers is the output pixels whose centres
    lie inside its mapped outline. In a kernel both warps are drawn in the browser, pixel by
    pixel (``browser/forward_inverse.js``; their numpy twin
    :func:`~camlab.widgets.homographies.twins.forward_inverse_view`).

    Returns
    -------
    Demo
        The demo: controls ``scale`` and ``angle`` (the rotation, degrees), the figure (the
        forward warp with its holes lime green, the window :data:`ZOOM` of it and of the inverse
        warp enlarged, and the inverse warp; outside the picture both are grey) and ``state`` (``H``, source to output pixels,
        and ``hole_fraction``, the share of the covered area's pixels, its rim included, that
        the forward warp never reaches).

    References
    ----------
    .. [1] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022, section
       3.6.1 (parametric transformations: forward and inverse warping).
    """
    pic = scenes.house_picture((80, 60))
    out_hw = (180, 240)
    fixed = forward_inverse_fixed(pic.shape, out_hw)
    view = BrowserView(("scale", "angle"), figsize=(10.5, 2.9))
    ax_f, ax_z, ax_zi, ax_i = view.fig.subplots(1, 4, width_ratios=[1, 0.56, 0.56, 1])
    blank = np.zeros((*out_hw, 3), np.uint8)
    im_f = view.animate(ax_f.imshow(blank, interpolation="nearest"))
    im_i = view.animate(ax_i.imshow(blank, interpolation="nearest"))
    top, left, h, w = ZOOM
    im_z, im_zi = (
        view.animate(
            ax_.imshow(
                blank[:h, :w],
                interpolation="nearest",
                extent=(left - 0.5, left + w - 0.5, top + h - 0.5, top - 0.5),
            )
        )
        for ax_ in (ax_z, ax_zi)
    )
    # animated after the image, or the live frame paints the picture over it
    boxes = [
        view.animate(
            ax_.add_patch(
                Rectangle((left - 0.5, top - 0.5), w, h, fill=False, ec=palette.YELLOW, lw=1.5)
            )
        )
        for ax_ in (ax_f, ax_i)
    ]
    _label_warp_axes(ax_f, ax_z, ax_zi, ax_i)
    readout = W.HTML()

    def update(v: dict, state: dict) -> None:
        # both warps as shown (their twin forwardInverseView in the browser's homography.js)
        g = forward_inverse_view(v, pic, fixed)
        H, outline, shown, inv, reached, pulled = (
            g.H,
            g.outline,
            g.shown,
            g.inverse,
            g.reached,
            g.pulled,
        )
        im_f.set_data(shown)
        im_z.set_data(shown[top : top + h, left : left + w])
        im_zi.set_data(inv[top : top + h, left : left + w])
        im_i.set_data(inv)
        # over the whole covered area, rim included: every lime pixel the figure shows is counted
        area = g.covered
        holes = float(np.mean(~reached[area])) if area.any() else 0.0
        holes_inverse = float(np.mean(~pulled[area])) if area.any() else 0.0
        state.update(H=H, hole_fraction=holes, hole_fraction_inverse=holes_inverse)
        # the picture runs off the canvas at large scales: say that the share is of the part on it
        # (by more than 3 px: a corner that grazes the edge leaves the share as it is, and is not visible)
        clipped = not np.all((outline >= -3.5) & (outline <= [out_hw[1] + 2.5, out_hw[0] + 2.5]))
        where = "of the covered area" + (
            " on the canvas (the picture runs off it)" if clipped else ""
        )
        readout.value = monospace(
            f"holes in the forward warp: {100 * holes:.0f}% {where}\n"
            f"holes in the inverse warp: {100 * holes_inverse:.0f}%"
        )

    controls = {
        "scale": slider(2.0, 0.4, 3.0, 0.05, "scale"),
        "angle": slider(15.0, -45.0, 45.0, 1.0, "rotation (°)"),
    }
    demo = build_demo(
        "forward_vs_inverse",
        controls,
        view,
        update,
        title="Forward versus inverse warping",
        extra=[readout],
    )
    images = dict(forward=im_f, forward_zoom=im_z, inverse_zoom=im_zi, inverse=im_i)
    view.publish(
        demo, forward_inverse_scene(images, boxes, pic, fixed)
    )  # the browser draws the moves
    return demo
