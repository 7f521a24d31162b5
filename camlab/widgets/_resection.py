"""The resection demo's words, labels and residual bars (lesson 04).

Its readout, where the two cameras' labels hang and the panel of residual bars. Helpers of
:func:`camlab.widgets.projective_camera.resectioning`.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
from matplotlib.ticker import MaxNLocator

from ..plotting import palette

__all__ = [
    "k_readout",
    "place_camera_labels",
    "resection_readout",
    "residual_bars",
    "show_residual_bars",
]


def resection_readout(err, K, cam_true, Xw, v, moved, info, centre_err, held_out=None):
    """The readout beside the figure.

    The residuals, the error on fresh points (``held_out``, px RMS), the errors of f and C, the
    redundancy and the RMS it leads one to expect; returns the numbers it states.
    """
    behind = int(
        np.count_nonzero(~np.isfinite(err))
    )  # points behind the estimated camera have no image
    rms = float(np.sqrt(np.mean(err**2)))
    focal_err = float(abs(K[0, 0] - cam_true.K[0, 0]))
    n = len(Xw)
    redundancy = 2 * n - 11  # equations minus unknowns: the noise the residuals can show
    # The expected RMS residual of the maximum-likelihood fit (H&Z 5.1.3); the true camera leaves sigma sqrt(2).
    expected = float(v["noise"]) * np.sqrt(2.0 * redundancy / (2 * n))
    warning = (
        "\n<b>few spare equations: the fit absorbs the noise, so a small RMS\n"
        "says little about the camera</b>"
        if redundancy < 10 and v["noise"] > 0
        else ""
    )
    rms_text = (
        f"RMS reprojection {rms:.2f} px"
        if not behind
        else f"<b>{behind} of {n} points lie behind the estimated camera:\n"
        f"no reprojection error; the fit has failed</b>"
    )
    worst = (
        ""
        if behind or not moved
        else (
            f"\nlargest residual: pair {int(np.argmax(err))} ({err.max():.1f} px)"
            f"\nmoved pair {', '.join(map(str, moved))}: {', '.join(f'{err[i]:.1f}' for i in moved)} px"
        )
    )
    fresh = (
        ""
        if held_out is None
        else "\non 30 fresh points of the box (not fitted,\n  true pixels): "
        + (f"RMS {held_out:.2f} px" if np.isfinite(held_out) else "some lie behind the estimate")
    )
    info.value = (
        f"<pre>{rms_text}{worst}{fresh}\n|fx - fx_true| = {focal_err:.1f} px\n"
        f"|C - C_true| = {100 * centre_err:.1f} cm\n"
        f"{k_readout(K, cam_true.image_size)}\n\n"
        f"redundancy 2N - 11 = {redundancy}\n"
        f"RMS expected of the ML (refined) fit:\n  sigma sqrt(2) sqrt((2N - 11) / 2N) = {expected:.2f} px\n"
        f"(the true camera leaves sigma sqrt(2) = {float(v['noise']) * np.sqrt(2.0):.2f} px)"
        f"{warning}</pre>"
    )
    return behind, rms, focal_err, redundancy, expected


def k_readout(K, image_size=(640, 480)) -> str:
    """The estimated K as a camera maker would read it, and a warning when no real camera has it.

    A real camera has square pixels (f_y = f_x within a few per cent), no skew and its principal point on
    the image; an estimate that breaks any of these is a failed resection, whatever its residual.
    """
    K = np.asarray(K, dtype=float) / K[2, 2]
    (fx, s, cx), (_, fy, cy) = K[0], K[1]
    w, h = image_size
    # one decimal, so the half-pixel principal point (319.5, 239.5) shows; + 0.0 turns -0.0 into 0.0
    fx, fy, s, cx, cy = (float(np.round(x, 1)) + 0.0 for x in (fx, fy, s, cx, cy))
    text = f"estimated K: fx {fx:.1f}, fy {fy:.1f}, skew {s:.1f} px,\n  principal point ({cx:.1f}, {cy:.1f})"
    odd = [
        what
        for what, bad in (
            ("fy != fx", abs(fy / fx - 1) > 0.05),
            ("skew", abs(s) > 0.02 * abs(fx)),
            ("principal point off the image", not (0 <= cx <= w - 1 and 0 <= cy <= h - 1)),
        )
        if bad
    ]
    return text + (
        f"\n<b>no real camera has this K ({', '.join(odd)}):\ndistrust this resection</b>"
        if odd
        else ""
    )


def place_camera_labels(ax, true_artist, est_artist) -> None:
    """Hang "true" and "est." off their centres on the sides facing away from each other on screen.

    Both frustums point right, towards the box, so the labels go left of their centres; the camera that is
    higher on screen takes its label above (along its -y, the image's up), the other below, so neither lands
    on the other camera. (Text3D's vertical alignment barely moves a label; an offset in the world does.)
    """
    from mpl_toolkits.mplot3d import proj3d

    cams = (true_artist.camera, est_artist.camera)
    (_, _), (y_true, y_est), _ = proj3d.proj_transform(*np.c_[cams[0].centre, cams[1].centre], ax.M)
    up, down = (-0.05, -0.3), (-0.05, 0.3)
    for artist, offset in zip(
        (true_artist, est_artist), (up, down) if y_true >= y_est else (down, up), strict=True
    ):
        artist.label_offset = offset
        artist.label.set(
            ha="right", va="center", path_effects=palette.halo()
        )  # readable over a grid line
        artist.label.set_position_3d(artist._label_position(artist.camera))


def residual_bars(ax):
    """The residual panel of :func:`~camlab.widgets.projective_camera.resectioning`: one bar per pair, its length |o - +| in pixels.

    Bar i stands at (i + 0.5) / N across; the vertical axis is in pixels, from 0 to 1.32 times the
    longest residual but never less than 1.32 px, so round-off (sigma = 0) stays flat. That axis
    changes with the data, so it is animated with the bars (a static one would go stale in live
    frames). The two longest bars are labelled with their lengths and pair numbers; the moved or
    ringed pairs' bars are black.
    """
    ax.set(xlim=(0.0, 1.0), ylim=(0.0, 1.32), xticks=[])
    ax.set_title("residual of each pair\n(o to +), to scale", fontsize=9)
    ax.set_xlabel("pairs 0 .. N - 1", fontsize=8)
    ax.set_ylabel("px", fontsize=8, labelpad=1)
    ax.tick_params(axis="y", labelsize=7, pad=1)
    ax.yaxis.set_major_locator(MaxNLocator(nbins=3, steps=[1, 2, 2.5, 5, 10]))
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    bar = dict(solid_capstyle="butt", lw=4.0)
    (innocent,) = ax.plot([], [], color=palette.ORANGE, **bar)
    (ringed,) = ax.plot([], [], color="k", **bar)
    labels = [
        ax.text(0, 0, "", fontsize=8, ha="center", va="bottom", path_effects=palette.halo())
        for _ in range(2)
    ]
    return SimpleNamespace(
        ax=ax,
        innocent=innocent,
        ringed=ringed,
        labels=labels,
        artists=[ax.yaxis, ax.spines["left"], innocent, ringed, *labels],
    )


RESIDUAL_FLOOR_PX = (
    1.0  # the bar panel's axis reaches at least 1.32 px: round-off is not drawn full height
)


def show_residual_bars(bars, err, ringed) -> list[tuple[int, float]]:
    """Draw the residuals ``err`` (px) as bars, ``ringed`` pairs black; return the two longest (pair, px).

    Bars of points behind the estimate (NaN residual) are left out. When the two longest bars stand
    close, one label over the taller names both, longest first.
    """
    err = np.asarray(err, dtype=float)
    n = len(err)
    finite = np.isfinite(err)
    top = max(float(err[finite].max()) if finite.any() else 0.0, RESIDUAL_FLOOR_PX)
    bars.ax.set_ylim(0.0, 1.32 * top)
    height = np.where(finite, err, 0.0)
    x = (np.arange(n) + 0.5) / n
    width = min(
        6.0, max(1.0, 0.55 * bars.ax.get_window_extent().width / n * 72 / bars.ax.figure.dpi)
    )
    black = np.zeros(n, dtype=bool)
    black[list(ringed)] = True
    for line, keep in ((bars.innocent, ~black), (bars.ringed, black)):
        xs = np.repeat(x[keep], 3)
        ys = np.column_stack(
            [np.zeros(keep.sum()), height[keep], np.full(keep.sum(), np.nan)]
        ).ravel()
        line.set_data(xs, ys)
        line.set_linewidth(width)
    order = [int(i) for i in np.argsort(np.where(finite, err, -1.0))[::-1][:2] if finite[i]]
    labelled = [i for i in order if err[i] >= 0.05]  # round-off (sigma = 0) gets no "0.0 px" labels
    for text in bars.labels:
        text.set_text("")
    close = len(labelled) == 2 and abs(x[labelled[1]] - x[labelled[0]]) < 0.3
    groups = [labelled] if close else [[i] for i in labelled]
    for text, group in zip(bars.labels, groups, strict=False):
        i = group[
            0
        ]  # over the longest bar of the group, a bar near either end taking its label inwards
        ha = "left" if x[i] < 0.25 else "right" if x[i] > 0.75 else "center"
        words = (
            "\n".join(f"pair {k}: {err[k]:.1f} px" for k in group)
            if close
            else f"{err[i]:.1f} px\npair {i}"
        )
        text.set(position=(x[i], height[i] + 0.02 * top), text=words, ha=ha)
    return [(i, float(err[i])) for i in order]
