"""Drawing helpers for lesson 07's static figures (homographies, RANSAC on real photographs).

The lesson computes, prints and asserts; these helpers only draw what it computed, so the
student reads ``fig = draw_...(...)`` between the ideas. Pixel (u, v) has its centre at data
coordinates (u, v), v points down (docs/conventions.md). Neutrals are spelt directly, every hue
comes from :mod:`camlab.plotting.palette`.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.lines import Line2D

from camlab.projective import map_points

from . import palette

__all__ = [
    "DEPTH_LOOKS",
    "draw_error_histograms",
    "draw_fit_comparison",
    "draw_hypotheses",
    "draw_overlay",
    "draw_parallax",
    "draw_plan_view",
    "draw_verdicts",
    "torn_outline",
]

_CORNERS = ("TL", "TR", "BR", "BL")
_LABEL_OFFSET = {"TL": (-12, -8), "TR": (12, -8), "BL": (12, 8), "BR": (10, 0)}


def torn_outline(H: np.ndarray, quad: np.ndarray, n: int = 200) -> np.ndarray:
    """A closed polygon's sides, sampled densely, mapped by H and broken where w changes sign.

    Parameters
    ----------
    H : (3, 3) ndarray
        The homography.
    quad : (M, 2) ndarray
        The polygon's vertices in pixels, the first repeated at the end.
    n : int
        Samples per side.

    Returns
    -------
    (n (M - 1), 2) ndarray
        The mapped samples; a NaN row wherever w changes sign, so no segment is drawn across
        infinity (lesson 07, section 3).
    """
    t = np.linspace(0, 1, n)[:, None]
    dense = np.vstack([quad[i] + t * (quad[i + 1] - quad[i]) for i in range(len(quad) - 1)])
    w, pts = np.c_[dense, np.ones(len(dense))] @ H[2], map_points(H, dense)
    pts[1:][np.sign(w[1:]) != np.sign(w[:-1])] = np.nan
    return pts


def _draw_pairs(ax, src, dst, inl) -> None:
    """A hypothesis's support: dark lines src -> dst for pairs within the threshold, faint dots else."""
    ax.plot(*dst[~inl].T, "o", color="0.75", ms=2, zorder=1)
    ax.plot(
        *np.stack([src[inl], dst[inl]], axis=1).transpose(2, 1, 0),
        "-",
        color="0.1",
        lw=0.8,
        zorder=2,
    )
    ax.plot(*dst[inl].T, "o", color="0.1", ms=2.5, zorder=2)


def _hypotheses_key(ax) -> None:
    """The legend of :func:`draw_hypotheses`, in its own axes."""
    ax.axis("off")
    handles = [
        Line2D(
            [],
            [],
            color="0.1",
            marker="o",
            ms=3,
            lw=0.8,
            label="pair within 3 px: line from src to a dot at dst",
        ),
        Line2D(
            [],
            [],
            color="0.75",
            marker="o",
            ms=3,
            lw=0,
            label="pair farther off: a faint dot at dst",
        ),
        Line2D(
            [],
            [],
            ls="none",
            marker="o",
            mfc="none",
            mec="k",
            mew=2,
            ms=9,
            label="the 4 pairs H is fitted to",
        ),
        Line2D([], [], ls="--", color="k", lw=1.5, label="the 400 × 300 frame mapped by H"),
        Line2D([], [], ls="-", color="0.55", lw=6, label="the frame mapped by the true H"),
        Line2D(
            [],
            [],
            ls="none",
            marker="s",
            mfc="none",
            mec="k",
            mew=1.5,
            ms=8,
            label="a corner of the frame mapped by H",
        ),
        Line2D(
            [],
            [],
            ls="none",
            marker="x",
            color="k",
            mew=1.8,
            ms=7,
            label="a corner mapped by H with w < 0 (zoom)",
        ),
    ]
    ax.legend(handles=handles, loc="center left", ncols=1, fontsize=10, frameon=False)


def _draw_zoom(ax, box_ax, src, dst, pick, H, inl, frame) -> None:
    """The crushed, torn frame of a contaminated sample, boxed in ``box_ax`` and magnified in ``ax``."""
    mapped = map_points(H, frame[:4])
    front = (
        np.c_[frame[:4], np.ones(4)] @ H[2] > 0
    )  # the corners in front; the one with w < 0 is a cross
    box_ax.plot(*mapped[front].T, "s", mfc="none", mec="k", mew=1.5, ms=8)
    lo, hi = mapped[front].min(axis=0), mapped[front].max(axis=0)
    centre, half = (lo + hi) / 2, 0.5 * np.ptp(mapped[front], axis=0).max() + 8
    box_ax.add_patch(
        plt.Rectangle(centre - half, 2 * half, 2 * half, fill=False, ec="k", lw=1.5, zorder=6)
    )
    _draw_pairs(ax, src, dst, inl)
    ax.plot(*torn_outline(H, frame).T, "--", color="k", lw=1.5)
    ax.plot(*dst[pick].T, "o", mfc="none", mec="k", mew=2, ms=10, zorder=5)
    ax.plot(*mapped[front].T, "s", mfc="none", mec="k", mew=1.2, ms=5, zorder=6)
    ax.plot(*mapped[~front].T, "x", color="k", mew=1.8, ms=7, zorder=6)
    ring = dst[pick][np.argmin(np.linalg.norm(dst[pick] - mapped[0], axis=1))]  # the large ring
    to_ring = np.linalg.norm(mapped - ring, axis=1)
    names = np.array(_CORNERS)
    for name, p, w_pos in zip(names, mapped, front, strict=True):
        dx, dy = _LABEL_OFFSET[name]
        ax.annotate(
            name + ("" if w_pos else " (w < 0)"),
            p,
            xytext=(dx, dy),
            textcoords="offset points",
            fontsize=10,
            weight="bold",
            ha="right" if dx < 0 else "left",
            va="center",
            path_effects=palette.halo(),
        )
    ax.set(
        xlim=(centre[0] - half, centre[0] + half),
        ylim=(centre[1] + half, centre[1] - half),
        aspect="equal",
        xlabel="u (pixels)",
        ylabel="v (pixels)",
    )
    for side in ax.spines.values():
        side.set(color="k", lw=1.5)
    near = names != "BR"
    ax.set_title(
        f"panel 1's box, magnified: all four corners within {np.ptp(mapped, axis=0).max():.0f} px;\n"
        f"TL, TR, BL within {to_ring[near].max():.1f} px of the large ring, BR {to_ring[~near][0]:.0f} px; "
        f"BL (cross): w < 0",
        fontsize=10,
    )


def draw_hypotheses(src, dst, H_true, steps, frame, threshold: float = 3.0):
    """Lesson 07's RANSAC taken apart: one panel per hypothesis, the contaminated one magnified.

    Parameters
    ----------
    src, dst : (N, 2) ndarray
        The point pairs (pixels).
    H_true : (3, 3) ndarray
        The true homography (its mapped frame is the grey band).
    steps : list of (str, (k,) ndarray, (3, 3) ndarray, (N,) bool ndarray)
        Per panel: its title, the indices of the pairs H is fitted to (4: a sample, ringed), that H,
        and which pairs lie within ``threshold`` under it. The first step with 4 pairs is the
        contaminated sample: its crushed frame is boxed and magnified below.
    frame : (5, 2) ndarray
        The frame's corners TL, TR, BR, BL and TL again (pixels).
    threshold : float
        The threshold the titles quote (pixels).

    Returns
    -------
    matplotlib.figure.Figure
        Three panels on top; the zoom and the key below.
    """
    fig = plt.figure(figsize=(11.5, 7.4), layout="constrained")
    top, bottom = fig.subfigures(2, 1, height_ratios=[4.2, 3.2])
    axes = top.subplots(1, 3, sharey=True)
    zoom, key = bottom.subplots(1, 2, width_ratios=[1, 1.1])
    for k, (ax, (title, pick, H, inl)) in enumerate(zip(axes, steps, strict=True)):
        _draw_pairs(ax, src, dst, inl)
        ax.plot(
            *map_points(H_true, frame).T, "-", color="0.55", lw=6, zorder=0
        )  # the demo's grey band
        ax.plot(*torn_outline(H, frame).T, "--", color="k", lw=1.5)
        if len(pick) == 4:  # rings above the points; the one the frame is crushed onto, large
            crushed = np.linalg.norm(dst[pick] - map_points(H, frame[:1]), axis=1) < 15
            for mask, size in ((~crushed, 10), (crushed, 20)):
                ax.plot(*dst[pick][mask].T, "o", mfc="none", mec="k", mew=2, ms=size, zorder=5)
        if k == 0:
            _draw_zoom(zoom, ax, src, dst, pick, H, inl, frame)
        if k == 1:  # the clean sample's drift at the top-left corner
            a, b = map_points(H_true, frame[0]), map_points(H, frame[0])
            ax.annotate(
                "", b, a, arrowprops=dict(arrowstyle="<->", color="k", lw=1.5, shrinkA=0, shrinkB=0)
            )
            ax.annotate(
                f"{np.linalg.norm(b - a):.0f} px",
                (a + b) / 2,
                xytext=(2, -16),
                textcoords="offset points",
                fontsize=9,
                ha="center",
                va="center",
                path_effects=palette.halo(),
                weight="bold",
            )
        ax.set(xlabel="u (pixels)", aspect="equal", xlim=(-30, 430), ylim=(330, -30))
        ax.set_title(f"{title}:\n{int(inl.sum())} pairs within {threshold:g} px", fontsize=10)
    axes[0].set_ylabel("v (pixels)")
    _hypotheses_key(key)
    return fig


def _draw_explained(ax_t, fits, errors, threshold: float) -> None:
    """The right panel of :func:`draw_fit_comparison`: how many pairs each fit explains within t."""
    t_axis = np.geomspace(0.1, 1000, 400)
    for e, (_, colour, style, label) in zip(errors, fits, strict=True):
        n_in = int((e < threshold).sum())
        ax_t.plot(
            t_axis, (e[:, None] <= t_axis).sum(axis=0), style, color=colour, lw=2, label=label
        )
        ax_t.plot(threshold, n_in, "o", color=colour, ms=7)
        ax_t.annotate(
            f"{n_in}",
            (threshold, n_in),
            xytext=(-8, 6),
            textcoords="offset points",
            ha="right",
            fontsize=9,
            weight="bold",
            color="k",
        )
    ax_t.axvline(threshold, color="0.2", ls=":", lw=1)
    ax_t.set(
        xscale="log",
        xlabel="threshold t (pixels)",
        ylabel="pairs with $e_i \\leq t$",
        ylim=(0, 1.04 * max(len(e) for e in errors)),
    )
    ax_t.set_title("pairs each fit explains within t", fontsize=10)
    ax_t.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), fontsize=8, frameon=False)
    ax_t.grid(True, which="major", color="0.92")


def draw_fit_comparison(
    photo,
    corners,
    fits,
    wrong_src_mapped,
    wrong_dst,
    errors,
    names=("image 1", "image 2"),
    threshold: float = 3.0,
):
    """Least squares against RANSAC on a real pair: the mapped frames, and pairs explained per threshold.

    Parameters
    ----------
    photo : (H, W) ndarray
        The second photo (grey levels), drawn dimmed.
    corners : (4, 2) ndarray
        The first photo's frame corners (pixels).
    fits : list of ((3, 3) ndarray, str, str, str)
        Per fit: H, its colour (a grey level), line style and label. The first is RANSAC's.
    wrong_src_mapped, wrong_dst : (K, 2) ndarray
        The plainly wrong pairs: where RANSAC's H sends their source, and their match.
    errors : list of (N,) ndarray
        Each fit's e_i over all pairs (pixels), in the order of ``fits``.
    names : tuple of str
        The two photos' names, for the labels.
    threshold : float
        The inlier threshold marked on the right panel (pixels).

    Returns
    -------
    matplotlib.figure.Figure
        Left: the frame mapped by each fit over the photo, with an arrow at the corner where they
        differ most; right: the number of pairs each fit explains within t, against t.
    """
    fig, (ax, ax_t) = plt.subplots(
        1, 2, figsize=(11, 5.4), layout="constrained", width_ratios=[1.9, 1]
    )
    ax.imshow(photo // 2 + 100, cmap="gray", vmin=0, vmax=255)  # dimmed, so the marks read
    loop = np.vstack([corners, corners[:1]])
    for H, colour, style, label in fits:
        ax.plot(
            *map_points(H, loop).T,
            style,
            color=colour,
            lw=2,
            label=f"{names[0]}'s frame mapped by {label}",
        )
    for p, q in zip(
        wrong_src_mapped, wrong_dst, strict=True
    ):  # each wrong pair: its match against H x
        ax.plot([p[0], q[0]], [p[1], q[1]], "-", color="0.25", lw=1)
    ax.plot(
        *wrong_dst.T,
        "X",
        ms=6.5,
        color=palette.GREY,
        mec="k",
        mew=0.7,
        ls="none",
        label=f"the {len(wrong_dst)} plainly wrong matches, rejected even at 10 px (line: to where RANSAC's H puts them)",
    )
    gaps = np.linalg.norm(map_points(fits[1][0], corners) - map_points(fits[0][0], corners), axis=1)
    a, b = (
        map_points(fits[0][0], corners[np.argmax(gaps)]),
        map_points(fits[1][0], corners[np.argmax(gaps)]),
    )
    ax.annotate("", b, a, arrowprops=dict(arrowstyle="->", color="k", lw=1.5, shrinkA=0, shrinkB=0))
    ax.annotate(
        f"{gaps.max():.0f} px",
        (a + b) / 2,
        xytext=(12, 0),
        textcoords="offset points",
        fontsize=9,
        weight="bold",
        va="center",
        path_effects=palette.halo(),
    )
    ax.set(
        xlim=(-330, 830),
        ylim=(710, -150),
        xlabel=f"u in {names[1]} (pixels)",
        ylabel=f"v in {names[1]} (pixels)",
    )
    ax.set_title(f"{names[1]}: {names[0]}'s frame mapped by each fit", fontsize=10)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), fontsize=8, frameon=False)
    _draw_explained(ax_t, fits, errors, threshold)
    return fig


def draw_verdicts(
    photo, src, errors, verdicts, name="image 1", bands=(400, 600), thresholds=(3, 10)
):
    """RANSAC's verdict on each match of a real pair, over the photo and as a stacked histogram of e_i.

    Parameters
    ----------
    photo : (H, W) ndarray
        The first photo (grey levels), drawn dimmed.
    src : (N, 2) ndarray
        The matches' points in that photo (pixels).
    errors : (N,) ndarray
        Each pair's e_i under the 3 px homography (pixels).
    verdicts : list of ((N,) bool ndarray, colour, marker, float, str)
        Per verdict: its pairs, colour, marker, marker size and label.
    name : str
        The photo's name, for the title.
    bands : tuple of float
        The values of u marked by dotted lines (the bands the text uses).
    thresholds : tuple of float
        The thresholds marked on the histogram (pixels).

    Returns
    -------
    matplotlib.figure.Figure
        Left: the matches by verdict over the photo; right: the stacked histogram of e_i on a log axis.
    """
    fig, (ax, ax_h) = plt.subplots(
        1, 2, figsize=(10, 4.0), layout="constrained", width_ratios=[1.25, 1]
    )
    ax.imshow(photo // 2 + 100, cmap="gray", vmin=0, vmax=255)  # dimmed, so the marks read
    for mask, colour, marker, size, label in verdicts:
        cross = marker == "X"
        ax.plot(
            *src[mask].T,
            marker,
            ms=size,
            color=colour,
            mec="k" if cross else "white",
            mew=0.8 if cross else 0.4,
            ls="none",
            label=f"{label} ({int(mask.sum())})",
        )
    for u_band in bands:
        ax.axvline(u_band, color="k", ls=":", lw=1.2, path_effects=palette.halo(1.2))
        ax.annotate(
            f"u = {u_band}",
            (u_band, 0),
            xycoords=("data", "axes fraction"),
            xytext=(3, 4),
            textcoords="offset points",
            fontsize=8,
            path_effects=palette.halo(),
        )
    ax.set(xlabel="u (pixels)", ylabel="v (pixels)")
    ax.set_title(f"{name} and its matches, by RANSAC's verdict", fontsize=10)
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower left", ncol=3, fontsize=8)
    bins = 3 * (10 / 3) ** (
        np.arange(-16, 21) / 4
    )  # equal widths on the log axis, edges at 3 and 10 px
    ax_h.hist(
        [errors[mask] for mask, *_ in verdicts],
        bins=bins,
        stacked=True,
        color=[v[1] for v in verdicts],
    )
    for t in thresholds:
        _mark_threshold(ax_h, t)
    ax_h.set(xscale="log", xlabel="error $e_i$ under the 3 px H (pixels)", ylabel="pairs")
    ax_h.set_title("each pair's error", fontsize=10)
    return fig


def draw_overlay(
    overlay,
    crops,
    title,
    side=None,
    side_title="",
    brighten=False,
    mark_u=None,
    crop=(80, 60),
    covered=None,
    outline=None,
):
    """A red-cyan overlay of two registered photos, with crops of it enlarged.

    Parameters
    ----------
    overlay : (H, W, 3) uint8 ndarray
        The first photo in red, the second warped into its frame in cyan (grey where they agree).
    crops : dict
        Name -> (u, v) of a crop's top-left pixel; each is boxed in yellow and enlarged.
    title : str
        The overlay's title.
    side : (H, W) ndarray, optional
        A grey-level photo drawn beside the overlay (the second photo as taken); then the
        crops go in a row below, else beside the overlay.
    side_title : str
        Its title.
    brighten : bool
        Draw the overlay at half contrast, lifted (``overlay // 2 + 110``), so the grey of a dark
        photo reads; the crops stay as they are.
    mark_u : float, optional
        A column marked by a dotted line on the overlay (where a region starts).
    crop : tuple of int
        The crops' (width, height) in pixels.
    covered : (H, W) bool ndarray, optional
        The pixels the second photo covers; the rest is drawn black, so "not covered" never
        reads as the grey of "the two agree".
    outline : (K, 2) ndarray, optional
        The second photo's frame brought into the first's (a closed polygon, px), drawn white
        and dashed with a black edge.

    Returns
    -------
    matplotlib.figure.Figure
        Axes in order: the side photo (if any), the overlay, then one per crop.
    """
    w, h = crop
    if covered is not None:
        overlay = overlay.copy()
        overlay[~covered] = 0
    if side is not None:
        fig = plt.figure(figsize=(10, 6.6), layout="constrained")
        top, bottom = fig.subfigures(2, 1, height_ratios=[1.35, 1])
        ax_side, ax_o = top.subplots(1, 2)
        ax_side.imshow(side, cmap="gray", vmin=0, vmax=255)
        ax_side.set_title(side_title, fontsize=10)
        ax_side.set(xlabel="u (pixels)", ylabel="v (pixels)")
        zooms = np.atleast_1d(bottom.subplots(1, len(crops)))
    else:
        fig = plt.figure(figsize=(10, 3.9), layout="constrained")
        ax_o, *zooms = fig.subplots(1, 1 + len(crops), width_ratios=[1.5] + [1] * len(crops))
    shown = overlay // 2 + 110 if brighten else overlay
    if covered is not None:
        shown[~covered] = 0  # black: no second photo here
    ax_o.imshow(shown)
    ax_o.set_title(title, fontsize=10)
    if outline is not None:
        ax_o.plot(
            *np.asarray(outline).T, "--", color="w", lw=1.6, path_effects=palette.halo(1.6, "k")
        )
        ax_o.set(xlim=(-0.5, overlay.shape[1] - 0.5), ylim=(overlay.shape[0] - 0.5, -0.5))
    if mark_u is not None:
        ax_o.axvline(mark_u, color="k", ls=":", lw=1.2, path_effects=palette.halo(1.2))
    for ax, (name, (u0, v0)) in zip(zooms, crops.items(), strict=True):
        ax_o.add_patch(
            plt.Rectangle((u0 - 0.5, v0 - 0.5), w, h, fill=False, ec=palette.YELLOW, lw=1.5)
        )
        ax_o.annotate(
            name,
            (u0 + w / 2, v0 - 4),
            ha="center",
            va="bottom",
            fontsize=8,
            color="k",
            path_effects=palette.halo(),
        )
        ax.imshow(
            overlay[v0 : v0 + h, u0 : u0 + w],
            extent=(u0 - 0.5, u0 + w - 0.5, v0 + h - 0.5, v0 - 0.5),
            interpolation="nearest",
        )
        ax.set_title(f"{name}, zoomed", fontsize=10)
    for ax in (ax_o, *zooms):
        ax.set(xlabel="u (pixels)", ylabel="v (pixels)")
    return fig


def _mark_threshold(ax, t: float) -> None:
    """A dotted vertical line at the threshold ``t`` with its "t px" label just below the axes' top."""
    ax.axvline(t, color="0.2", ls=":", lw=1)
    ax.annotate(
        f"{t:g} px",
        (t, 1),
        xycoords=("data", "axes fraction"),
        xytext=(3, -12),
        textcoords="offset points",
        fontsize=8,
    )


def draw_error_histograms(errors, threshold: float = 3.0, title=""):
    """Normalised histograms of e_i for several photo pairs on one log axis.

    Parameters
    ----------
    errors : dict
        Label -> (N,) ndarray of e_i (pixels), clipped to 0.1 to 30 px for the plot. The first is
        drawn as a black outline, the second as filled grey bars.
    threshold : float
        The threshold marked by a dotted line (pixels).
    title : str
        The axes' title.

    Returns
    -------
    matplotlib.figure.Figure
        One axes: the fraction of each pair's pairs per bin (26 bins, equal widths on the log axis).
    """
    fig, ax = plt.subplots(figsize=(5.6, 3.4), layout="constrained")
    bins = np.geomspace(0.1, 30, 26)
    styles = (dict(histtype="step", color="k", lw=2), dict(color=palette.GREY, alpha=0.8))
    for (label, e), style in zip(errors.items(), styles, strict=False):
        e = np.clip(e, 0.1, 30)
        ax.hist(
            e, bins=bins, weights=np.full(len(e), 1 / len(e)), label=f"{label} ({len(e)})", **style
        )
    ax.set_ylim(0, 1.3 * ax.get_ylim()[1])  # room above the bars for the key and the label
    _mark_threshold(ax, threshold)
    ax.set(
        xscale="log", xlabel="error $e_i$ under the 3 px H (pixels)", ylabel="fraction of the pairs"
    )
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=8, loc="upper left")
    return fig


DEPTH_LOOKS = {
    "in front, Z = 1.5 m": ("o", palette.MAGENTA, 9),
    "on the plane, Z = 3 m": ("s", "k", 5.5),
    "behind, Z = 6 m": ("D", palette.OLIVE, 6),
}
"""Lesson 07's section 9: marker, colour and size of the points in front of, on and behind the plane
(magenta and olive appear nowhere else in the lesson)."""


def draw_plan_view(ray, depths, centre_2, axis_2, far=7.2):
    """Two cameras, the plane Z = 3 m and one ray of camera 1 with its points, seen from above.

    Parameters
    ----------
    ray : (3,) ndarray
        A ray of camera 1 (camera 1's frame; its point at depth Z is ``ray * Z`` with ``ray[2] = 1``).
    depths : dict
        Label (a key of :data:`DEPTH_LOOKS`) -> depth Z in metres.
    centre_2, axis_2 : (3,) ndarray
        Camera 2's centre and optical axis in camera 1's frame (metres).
    far : float
        The depth to which rays are drawn (metres).

    Returns
    -------
    matplotlib.figure.Figure
        The plan (Z across, X down the page): camera 2's ray to each point, extended dotted.
    """
    plan = lambda P: np.asarray(P, float).reshape(-1, 3)[:, [2, 0]]  # noqa: E731 - from above: (Z, X)
    fig, ax = plt.subplots(figsize=(10, 3.6), layout="constrained")
    ax.axvline(3.0, color="0.6", lw=4, alpha=0.5, zorder=0)
    ax.annotate(
        "the plane Z = 3 m (edge on)",
        (3.0, -1.5),
        xytext=(6, 0),
        textcoords="offset points",
        fontsize=9,
        va="center",
    )
    ax.plot(
        *plan([np.zeros(3), ray * far]).T,
        "--",
        color="k",
        lw=1.2,
        label="the ray of camera 1 through pixel $x_1$",
    )
    for name, Z in depths.items():
        P = ray * Z
        marker, colour, size = DEPTH_LOOKS[name]
        beyond = centre_2 + (P - centre_2) * (far - centre_2[2]) / (
            P[2] - centre_2[2]
        )  # camera 2's ray, on to `far`
        ax.plot(*plan([centre_2, P]).T, "-", color=colour, lw=1.4)
        ax.plot(*plan([P, beyond]).T, ":", color=colour, lw=1.4)
        ax.plot(
            *plan(P).T,
            marker,
            ms=size,
            color=colour,
            mec="k",
            mew=0.6,
            ls="none",
            label=f"{name}, and camera 2's ray to it",
        )
    for C, axis, name in (
        (np.zeros(3), np.array([0, 0, 1.0]), "camera 1"),
        (centre_2, axis_2, "camera 2"),
    ):
        first = name == "camera 1"
        ax.annotate(
            "",
            plan(C + 0.5 * axis)[0],
            plan(C)[0],
            arrowprops=dict(arrowstyle="-|>", color="0.2", lw=1.2),
        )
        ax.plot(*plan(C).T, "^" if first else "v", ms=9, color="0.2", ls="none")
        ax.annotate(
            name,
            plan(C)[0],
            xytext=(0, -16) if first else (-8, 6),
            textcoords="offset points",
            fontsize=9,
            ha="center" if first else "right",
        )
    ax.annotate(
        "H sends $x_1$ to camera 2's image\nof the plane's point on the ray",
        plan(ray * 3.0)[0],
        xytext=(-40, 30),
        textcoords="offset points",
        fontsize=8,
        ha="right",
        arrowprops=dict(arrowstyle="-", color="0.3", lw=0.8),
    )
    ax.set(
        xlabel="Z, depth in camera 1 (m)",
        ylabel="X (m; seen from above, +X down the page)",
        aspect="equal",
        xlim=(-0.75, far + 0.2),
        ylim=(0.6, -1.65),
    )
    ax.legend(loc="lower right", fontsize=8)
    ax.set_title(
        "seen from above: camera 1's ray, its three points, and camera 2's rays to them",
        fontsize=10,
    )
    return fig


def draw_parallax(predicted, seen, titles, size=(640, 480)):
    """Where H sends camera 1's pixels (rings) and where camera 2 sees the points at each depth.

    Parameters
    ----------
    predicted : dict
        Panel name -> (N, 2) ndarray: H x1 for each ray (pixels).
    seen : dict
        (panel name, depth label) -> (N, 2) ndarray: where camera 2 sees the ray's point at that
        depth (pixels); the labels are keys of :data:`DEPTH_LOOKS`.
    titles : dict
        Panel name -> its title. A panel whose name is ``"only turns"`` nests its coinciding marks.
    size : tuple of int
        Camera 2's image (width, height), drawn dotted.

    Returns
    -------
    matplotlib.figure.Figure
        One panel per entry of ``predicted``; each point joined to its ring by a line (the parallax).
    """
    fig, axes = plt.subplots(1, len(predicted), figsize=(10, 4.7), sharey=True)
    fig.subplots_adjust(
        left=0.07, right=0.99, top=0.93, bottom=0.26, wspace=0.06
    )  # room for the titles and the legend
    nested = {
        "in front, Z = 1.5 m": 11,
        "on the plane, Z = 3 m": 7,
        "behind, Z = 6 m": 4,
    }  # coinciding: all visible
    for ax, (which, rings) in zip(axes, predicted.items(), strict=True):
        ax.plot(
            *rings.T,
            "o",
            ms=14,
            mfc="none",
            mec=palette.GREY,
            mew=1.5,
            label="H x: camera 1's pixel, mapped by H",
        )
        for name, (marker, colour, ms) in DEPTH_LOOKS.items():
            where = seen[(which, name)]
            for p, q in zip(rings, where, strict=True):  # the parallax: from H x to the point seen
                ax.plot([p[0], q[0]], [p[1], q[1]], "-", color=colour, lw=1.2)
            ax.plot(
                *where.T,
                marker,
                ms=nested[name] if which == "only turns" else ms,
                color=colour,
                mec="k",
                mew=0.6,
                ls="none",
                label=f"seen by camera 2: {name}",
            )
        ax.add_patch(
            plt.Rectangle(
                (-0.5, -0.5),
                *size,
                fill=False,
                ec="0.6",
                lw=1,
                ls=":",
                label=f"camera 2's {size[0]} x {size[1]} image",
            )
        )
        ax.set(
            xlabel="u (pixels)", aspect="equal", xlim=(-20, size[0] + 20), ylim=(size[1] + 20, -20)
        )
        ax.set_title(titles[which], fontsize=10)
    axes[0].set_ylabel("v (pixels)")
    fig.legend(*axes[0].get_legend_handles_labels(), loc="lower center", ncol=2, fontsize=8)
    return fig
