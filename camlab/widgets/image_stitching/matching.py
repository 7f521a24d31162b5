"""Lesson 09's first demos.

Features matched between two photos, and the homography RANSAC registers them with (sections 1-2).
Re-exported by :mod:`camlab.widgets.image_stitching`.
"""

from __future__ import annotations

from types import SimpleNamespace

import ipywidgets as W
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.ticker import NullFormatter

from ... import features as ft
from ... import homography as hg
from ... import stitching as st
from ...fixtures import panorama_examples as pe
from ...plotting import palette
from ...plotting.stitching import (
    VIEW_COLOURS,
    draw_keypoints,
    draw_matches,
    match_segments,
    outline,
    thin_matches,
)
from ...projective import map_points
from .._base import Demo, FigureView, build_demo, register, slider
from ..controls import log_slider, monospace

# ----------------------------------------------------------------------------- matches

MATCH_STRIDE = 4  # feature_matches draws 1 in 4 matches of each kind, at every setting


def _dropped_match_lines(ax) -> tuple[LineCollection, LineCollection]:
    """The mutual check's dropped matches: mid-grey dashes over a dashed black rim, both empty at first.

    The rim is a dashed line of its own, each dash 1 pt longer at both ends than the grey one's
    12.5 pt (a halo's dashes would scale with its width and fill the gaps black).
    """
    rim = LineCollection(
        [], colors="black", linewidths=4.5, linestyles=(1 / 4.5, (14.5 / 4.5, 3 / 4.5)), zorder=2.5
    )
    dropped = LineCollection([], colors="0.6", linewidths=2.5, linestyles=(0, (5, 2)), zorder=2.5)
    ax.add_collection(rim)
    ax.add_collection(dropped)
    return rim, dropped


@register(
    lesson="09",
    sweep={"ratio": [0.6, 0.8, 0.95, 1.0], "mutual": [True, False], "keypoints": [True, False]},
)
def feature_matches() -> Demo:
    """SIFT matches between views 0 and 1: loosen the ratio test and watch wrong matches (red) appear.

    Views 0 and 1 of the half-size set with their SIFT keypoints; each match is judged by
    the true homography (green within 2 px, red otherwise:
    :func:`camlab.fixtures.panorama_examples.correct_matches`; green drawn over red). Every
    match is counted, only those whose keypoint index in view 0 is divisible by
    :data:`MATCH_STRIDE` (4) are drawn, at every setting
    (:func:`camlab.plotting.stitching.thin_matches`), so the picture keeps about the true share
    of right matches and the number of lines drawn falls when matches fall. With the mutual
    check on, every match it drops is drawn in black-edged grey dashes over the others.

    Returns
    -------
    Demo
        The demo: controls ``ratio`` (the ratio-test threshold r of
        :func:`camlab.features.filter_matches`), ``mutual`` (keep only mutual nearest
        neighbours) and ``keypoints`` (draw the SIFT keypoints, off at first), the figure (both views side by side with their keypoints and the
        matches) and ``state`` (``matches`` the matches kept, ``wrong`` those the truth
        rejects, ``precision`` the share that is right, NaN without matches, ``drawn_right``
        and ``drawn_wrong`` the green and red lines drawn, ``drawn_dropped`` the black-edged
        grey dashes of the matches the mutual check drops, ``keypoints_drawn`` the circles
        shown).

    References
    ----------
    .. [1] D. G. Lowe, 2004, "Distinctive image features from scale-invariant keypoints",
       *International Journal of Computer Vision* 60(2), 91-110, section 7.1 (the ratio test).
    """
    s, _, feats, knn = pe.panorama_example()
    i, j = 0, 1
    view = FigureView(figsize=(9, 3.4))
    ax = view.fig.subplots()
    art = draw_matches(ax, s.images[i], s.images[j], np.zeros((0, 2)), np.zeros((0, 2)))
    # the images stay, only the lines (and the keypoints' visibility) change. Green over red here
    # (at r near 1 the many red lines would bury the few green ones), and over both, in mid-grey
    # dashes, each edged in black (so they read over any photo), the matches the mutual check drops
    # (a handful: none may hide under the green bundle)
    art["good"].set_zorder(2.2)
    rim, dropped = _dropped_match_lines(ax)
    view.animate(rim, dropped, art["bad"], art["good"])
    # keypoints under every match line (zorder 1.5 < 2) and light: thin, half-transparent, no black
    # halo, whose ink buried the red dashes' black edges among 1900 circles
    kps = [
        draw_keypoints(
            ax, feats[k].points + [off, 0], feats[k].sizes, linewidths=0.5, alpha=0.5, zorder=1.5
        )
        for k, off in ((i, 0), (j, art["offset"]))
    ]
    view.animate(*kps)  # shown only when asked (K12: 1900 circles hid the lines)
    title = view.animate(ax.set_title(" ", fontsize=9))
    readout = W.HTML()

    def update(v: dict, state: dict) -> None:
        m = ft.filter_matches(knn[(i, j)], v["ratio"], v["mutual"])
        good = pe.correct_matches(s, i, j, m.src, m.dst)
        seg = match_segments(m.src, m.dst, art["offset"])
        # a fixed 1 in MATCH_STRIDE (the photos stay visible), chosen by the query keypoint's
        # index: a match keeps its line at every setting, so a filter removes only its own lines
        show, every = thin_matches(good, every=MATCH_STRIDE, key=m.idx1)
        for kp in kps:
            kp.set_visible(bool(v["keypoints"]))
        art["good"].set_segments(seg[good & show])
        art["bad"].set_segments(seg[~good & show])
        # the ratio test's matches that the mutual check removed: every one drawn (a handful at
        # r = 0.75, none of them among the 1 in 4), so the toggle shows what it does
        m_all = ft.filter_matches(knn[(i, j)], v["ratio"]) if v["mutual"] else m
        gone = ~np.isin(m_all.idx1, m.idx1)
        dropped.set_segments(match_segments(m_all.src, m_all.dst, art["offset"])[gone])
        rim.set_segments(dropped.get_segments())
        n, nbad = len(good), int((~good).sum())
        thinned = (
            f"1 match in {every} drawn (keypoint index divisible by {every}); wrong ones dashed"
        )
        # the keys on a third line (after `thinned` they ran past the figure's edges), kept even when
        # empty, as a blank first line: the layout, frozen at the first draw, leaves room for three
        keys = []
        if v["mutual"]:
            keys.append(f"black-edged grey dashes: the {len(m_all.src) - n} it dropped")
        if v["keypoints"]:
            keys.append("yellow circles: SIFT keypoints, radius ~ their scale")
        head = (
            f"views {i} and {j}, r = {v['ratio']:.2f}, mutual check {'on' if v['mutual'] else 'off'}: {n} matches, {n - nbad} right (green: within 2 px "
            f"of the true H), {nbad} wrong (red)"
        )
        title.set_text(
            "\n".join([head, thinned, "; ".join(keys)] if keys else [" ", head, thinned])
        )
        state.update(
            matches=n,
            wrong=nbad,
            precision=(n - nbad) / n if n else float("nan"),
            drawn_right=int((good & show).sum()),
            drawn_wrong=int((~good & show).sum()),
            keypoints_drawn=sum(len(f.points) for f in feats[: j + 1]) if v["keypoints"] else 0,
            drawn_dropped=int(gone.sum()),
        )
        readout.value = monospace(
            f"keypoints: view {i} {len(feats[i].points)}, view {j} {len(feats[j].points)}\n"
            f"matches kept: {n}\nwrong (red): {nbad} ({100 * nbad / max(n, 1):.0f}%)"
            + f"\nlines drawn: {int((good & show).sum())} green, {int((~good & show).sum())} red:\n"
            f"  1 match in {every} (keypoint index divisible by {every})"
            + (
                f"\ndropped by the mutual check: {int(gone.sum())} (black-edged grey dashes)"
                if v["mutual"]
                else ""
            )
        )

    controls = {
        "ratio": slider(0.75, 0.4, 1.0, 0.01, "ratio test r"),
        "mutual": W.Checkbox(value=False, description="mutual check"),
        "keypoints": W.Checkbox(value=False, description="keypoints"),
    }
    return build_demo(
        "feature_matches", controls, view, update, title="Feature matching", extra=[readout]
    )


# ----------------------------------------------------------------------------- RANSAC


# the residual histogram's bins, log-spaced from 0.02 to 300 px; one more below, one bin wide and left of
# 0.02 px (the slider's least threshold), for every error under 0.02 px, so it holds inliers only; and one
# more from 300 to 450 px for every error above 300 px (drawn whole inside the axis)
_LOG_BINS = np.logspace(np.log10(0.02), np.log10(300), 43)
_RESIDUAL_BINS = np.concatenate([[0.02**2 / _LOG_BINS[1]], _LOG_BINS, [450.0]])


def _registration_image(view: FigureView, ax, s, imgs, i: int, j: int) -> tuple:
    """The image panel of :func:`ransac_registration`.

    Image ``j`` of the set ``s``, the frame of image ``i`` under the true H, the legend below;
    returns the moving inliers, wrong inliers, outliers and estimated frame (registered with
    ``view`` in that order).
    """
    ax.imshow(s.images[j], interpolation="nearest")
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_title(f"matches in view {j}; frame of view {i} mapped by H", fontsize=9)
    inl = view.animate(
        ax.plot(
            [], [], ".", color=palette.GREEN, ms=4, label="inliers", path_effects=palette.halo()
        )[0]
    )
    # inliers the truth rejects (> 2 px off the true H): a black ring (white edge) round their
    # green dot; black, not a view colour (orange is view 1's)
    bad_inl = view.animate(
        ax.plot(
            [],
            [],
            "o",
            color="black",
            mfc="none",
            mew=1.4,
            ms=8,
            label="inlier, but > 2 px off the true H",
            path_effects=palette.halo(1.5, "white"),
        )[0]
    )
    outl = view.animate(
        ax.plot(
            [],
            [],
            "x",
            color=palette.RED,
            ms=4,
            label="rejected by RANSAC",
            path_effects=palette.halo(),
        )[0]
    )
    outline(
        ax,
        s.true_homography(i, j),
        imgs[i].shape,
        color=VIEW_COLOURS[i],  # view i's colour (the lesson's key), with a black edge
        lw=5,  # wide enough to show beside the RANSAC frame drawn over it
        label="true",
        path_effects=palette.halo(1.5, "black"),
        zorder=1.5,  # under the moving marks and frame, in a full redraw as in a live frame
    )
    est_box = view.animate(
        outline(
            ax,
            np.eye(3),
            imgs[i].shape,
            color="black",
            lw=1.5,
            ls="--",
            label="RANSAC",
            path_effects=palette.halo(
                1.5, "white"
            ),  # black dashes on white: yellow is kept for keypoints
        )
    )
    h, w = imgs[j].shape[:2]
    # wide enough for image i's mapped frame too (it lies left of image j), with room for a frame that is
    # 20 px off, so the worst corner stays in view
    true_frame = map_points(
        s.true_homography(i, j), np.array([[0, 0], [w - 1, h - 1], [0, h - 1], [w - 1, 0]], float)
    )
    ax.set(
        xlim=(min(-0.5, true_frame[:, 0].min() - 20), w - 0.5),
        ylim=(max(h - 0.5, true_frame[:, 1].max() + 20), min(-0.5, true_frame[:, 1].min() - 20)),
    )
    ax.legend(
        loc="upper center", bbox_to_anchor=(0.5, -0.02), ncols=3, fontsize=7, facecolor="0.75"
    )
    return inl, bad_inl, outl, est_box


def _residual_axes(view: FigureView, ax_e) -> tuple:
    """The histogram panel of :func:`ransac_registration`.

    The verdict text, two stacked bars per bin of :data:`_RESIDUAL_BINS` (the inliers green at
    the bottom, the outliers red on top, as in the image panel; the end bars, which also hold
    everything beyond the axis, hatched) on a log count axis, and the threshold line,
    registered with ``view`` in that order and returned.
    """
    ax_e.set(
        xlabel="symmetric transfer error (px, log)",
        ylabel="matches per bin (log)\ngreen inliers, red rejected",
        xscale="log",
        yscale="log",
        xlim=(0.013, 640),  # the < 0.02 px bar and the > 300 px bar whole, off the spines
        # fixed limits (no stale axis in a live frame): the tallest bin at any setting (122 at
        # r = 1) stays below the verdict, which takes the top third
        ylim=(0.5, 3000),
        yticks=[1, 10, 100],
        yticklabels=["1", "10", "100"],
    )
    ax_e.yaxis.set_minor_formatter(NullFormatter())  # the minor ticks unlabelled
    # the verdict in the figure (the static picture has no side panel), above the tallest bar
    verdict = view.animate(
        ax_e.text(0.5, 0.97, "", transform=ax_e.transAxes, ha="center", va="top", fontsize=8)
    )
    ax_e.set_title(
        "residuals under H (dashed: threshold)\nhatched: all < 0.02 px, all > 300 px",
        fontsize=9,
    )
    bins, zeros = _RESIDUAL_BINS, np.zeros(len(_RESIDUAL_BINS) - 1)
    # each bin stacked by what RANSAC decided: a bin that straddles the threshold shows both kinds
    inl_bars = ax_e.bar(bins[:-1], zeros, width=np.diff(bins), align="edge", color=palette.GREEN)
    out_bars = ax_e.bar(bins[:-1], zeros, width=np.diff(bins), align="edge", color=palette.RED)
    for end in (out_bars[0], out_bars[-1], inl_bars[0], inl_bars[-1]):
        end.set(
            hatch="///", edgecolor="white", linewidth=0
        )  # they also hold everything beyond the axis
    view.animate(*inl_bars, *out_bars)
    # below the verdict (which sits in the top third, over no bar): the line never crosses its text
    thr_line = view.animate(
        ax_e.axvline(3, ymax=0.68, color="black", ls="--", lw=1.5, zorder=0.5)
    )  # under the bars
    return verdict, (inl_bars, out_bars), thr_line


def _set_residual_bars(bars: tuple, res: np.ndarray, inliers: np.ndarray) -> int:
    """Stack each bin of :data:`_RESIDUAL_BINS`: the ``inliers`` of residuals ``res`` green, the rest red on top.

    Heights are counts of matches; the red bar starts where the green one ends, so a bar's top
    is the bin's total. Residuals below 0.02 px or above 300 px are counted in the end bins.
    Returns the number of matches the green bars hold (every inlier, so the picture agrees with
    the verdict's count).
    """
    clipped = np.clip(res, 1.001 * _RESIDUAL_BINS[0], 449)
    n_in, _ = np.histogram(clipped[inliers], _RESIDUAL_BINS)
    n_out, _ = np.histogram(clipped[~inliers], _RESIDUAL_BINS)
    for b_in, b_out, a, o in zip(*bars, n_in, n_out, strict=True):
        b_in.set_height(a)
        b_out.set_y(a)
        b_out.set_height(o)
    return int(n_in.sum())


def _registration_figure(view: FigureView, s, imgs, i: int, j: int) -> SimpleNamespace:
    """The figure of :func:`ransac_registration`.

    Image ``j`` with the matches and the two frames, and the histogram of residuals under H; returns
    its moving artists by name.
    """
    ax, ax_e = view.fig.subplots(1, 2, width_ratios=[1.5, 1])
    inl, bad_inl, outl, est_box = _registration_image(view, ax, s, imgs, i, j)
    verdict, bars, thr_line = _residual_axes(view, ax_e)
    return SimpleNamespace(
        inl=inl,
        bad_inl=bad_inl,
        outl=outl,
        est_box=est_box,
        verdict=verdict,
        bars=bars,
        thr_line=thr_line,
    )


def _registration_texts(r, n: int, wrong: int, err: float) -> tuple[str, str]:
    """The verdict in the figure and the readout beside :func:`ransac_registration`.

    For the registration ``r`` of ``n`` matches with ``wrong`` false inliers and the worst corner
    ``err`` px from the truth.
    """
    need = max(15, int(np.floor(8 + 0.3 * n)) + 1)  # register_pair's acceptance test
    verdict = (
        f"{int(r.inliers.sum())} of {n} matches are inliers, {wrong} of them\n"
        f"> 2 px off the true H; worst corner {err:.2f} px off\n"
        + ("accepted" if r.accepted else f"rejected: {r.reason.split(':')[0]} (need {need})")
        + (
            "\nthe threshold is below the features' noise"
            if "localisation noise" in r.reason
            else ""
        )
    )
    readout = monospace(
        f"matches: {n}\ninliers: {int(r.inliers.sum())} "
        f"({wrong} of them > 2 px off the true H)\n"
        f"inlier RMS: {r.residual_rms:.2f} px\nworst corner vs truth: {err:.2f} px\n"
        + ("verdict: accepted" if r.accepted else f"verdict: rejected, {r.reason}")
    )
    return verdict, readout


def _registration_controls() -> dict:
    """The controls of :func:`ransac_registration`: the inlier threshold (px, log) and the ratio test r."""
    return {
        "threshold": log_slider(3.0, 0.02, 40.0, 0.01, "threshold (px)"),
        "ratio": slider(0.75, 0.4, 1.0, 0.01, "ratio test r"),  # as in feature_matches
    }


@register(lesson="09", sweep={"threshold": [0.02, 0.05, 3.0, 15.0, 40.0], "ratio": [0.95, 0.7]})
def ransac_registration() -> Demo:
    """RANSAC on the rendered photos' matches: the threshold decides which matches count as inliers, and the H you get.

    The ratio-tested matches from image 1 to image 2 of the half-size set are registered by
    :func:`camlab.stitching.register_pair` (RANSAC seeded with 0) at the chosen threshold,
    and the pair is accepted or rejected by its test. Image 1's frame mapped by the
    estimated H is drawn over image 2 beside the frame the true H gives.

    Returns
    -------
    Demo
        The demo: controls ``threshold`` (RANSAC's inlier threshold on the symmetric
        transfer error, px, on a log slider) and ``ratio`` (the ratio-test threshold r),
        the figure (image 2 with the inliers and outliers and the two frames; a histogram
        of the matches' symmetric transfer errors under H on a log axis, with the
        threshold and the verdict) and ``state`` (``inliers`` their count, ``corner_error``
        the worst corner of the estimated frame against the true one in px, NaN without an
        H, ``accepted`` whether the pair passes, and, when RANSAC finds an H,
        ``false_inliers`` the inliers the truth rejects; ``histogram_inliers`` the matches
        the histogram's green bars hold, every inlier).

    References
    ----------
    .. [1] M. A. Fischler and R. C. Bolles, 1981, "Random sample consensus: a paradigm for model
       fitting with applications to image analysis and automated cartography",
       *Communications of the ACM* 24(6), 381-395.
    .. [2] M. Brown and D. G. Lowe, 2007, "Automatic panoramic image stitching using invariant
       features", *International Journal of Computer Vision* 74(1), 59-73, section 3.2.
    """
    s, imgs, feats, knn = pe.panorama_example()
    i, j = 1, 2
    view = FigureView(figsize=(9, 3.6))
    art = _registration_figure(view, s, imgs, i, j)
    readout = W.HTML()
    true_H = s.true_homography(i, j)
    h, w = imgs[j].shape[:2]
    corners = np.array([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]], float)

    def update(v: dict, state: dict) -> None:
        m = ft.filter_matches(knn[(i, j)], v["ratio"])
        r = st.register_pair(
            feats[i], feats[j], matches=m, threshold=v["threshold"], rng=np.random.default_rng(0)
        )
        art.thr_line.set_xdata([v["threshold"], v["threshold"]])
        if r.H is None:
            art.inl.set_data([], [])
            art.bad_inl.set_data([], [])
            art.outl.set_data(m.dst[:, 0], m.dst[:, 1])
            art.est_box.set_data([], [])
            _set_residual_bars(art.bars, np.zeros(0), np.zeros(0, bool))  # no H, no residuals
            state.update(inliers=0, corner_error=float("nan"), accepted=False, histogram_inliers=0)
            readout.value = monospace(r.reason)
            art.verdict.set_text(f"{len(m.src)} matches: no homography\n{r.reason.split(';')[0]}")
            return
        art.inl.set_data(m.dst[r.inliers, 0], m.dst[r.inliers, 1])
        art.outl.set_data(m.dst[~r.inliers, 0], m.dst[~r.inliers, 1])
        box = map_points(r.H, np.vstack([corners, corners[:1]]))
        art.est_box.set_data(box[:, 0], box[:, 1])
        res = hg.symmetric_transfer_error(r.H, m.src, m.dst)
        green = _set_residual_bars(art.bars, res, r.inliers)
        err = float(
            np.max(np.linalg.norm(map_points(r.H, corners) - map_points(true_H, corners), axis=1))
        )
        good = pe.correct_matches(s, i, j, m.src, m.dst)
        wrong = int((r.inliers & ~good).sum())
        art.bad_inl.set_data(m.dst[r.inliers & ~good, 0], m.dst[r.inliers & ~good, 1])
        state.update(
            inliers=int(r.inliers.sum()),
            corner_error=err,
            accepted=r.accepted,
            false_inliers=wrong,
            histogram_inliers=green,
        )
        verdict, readout.value = _registration_texts(r, len(m.src), wrong, err)
        art.verdict.set_text(verdict)

    return build_demo(
        "ransac_registration",
        _registration_controls(),
        view,
        update,
        title="RANSAC on SIFT matches",
        extra=[readout],
    )
