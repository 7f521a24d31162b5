"""The church figure of lesson 01, section 2: equal windows whose image heights fall as 1 / Z.

:func:`draw_band_heights` draws what :func:`camlab.pinhole.band_heights` read: the photo with a
bar beside each window and the dashed lines through the windows' tops and bottoms, and one
window's brightness profile with its two edges.
"""

from __future__ import annotations

import numpy as np

from .. import palette


def _glass(grey: np.ndarray, u: int, top: float, bottom: float, level: float) -> tuple[int, int]:
    """The first and last column of a window's glass along its middle row (darker than ``level``)."""
    row = grey[int(top + bottom) // 2]
    return u - int(np.argmax(row[u::-1] > level)), u + int(np.argmax(row[u:] > level))


def draw_band_heights(ax, ax_col, photo: np.ndarray, columns: np.ndarray, read, lines) -> None:
    """Draw the measured windows on ``ax`` and the nearest one's brightness profile on ``ax_col``.

    Parameters
    ----------
    ax, ax_col : Axes
        The photo's axes and the profile's.
    photo : (H, W, 3) ndarray
        The photograph, 0-255.
    columns : (K,) ndarray
        Each window's middle column u.
    read : camlab.pinhole.BandHeights
        The windows' edges and heights.
    lines : tuple of two (2,) ndarrays
        ``np.polyfit`` lines v = a u + b through the tops and through the bottoms.
    """
    grey = photo.mean(axis=2)
    ax.imshow(photo)
    glass = [
        _glass(grey, u, t, b, lv)
        for u, t, b, lv in zip(columns, read.top, read.bottom, read.level, strict=True)
    ]
    # the dashed lines run to the image's right edge, broken at each window so the edges measured stay visible
    gaps = (
        [glass[0][0] - 40]
        + [end for pair in glass for end in (pair[0] - 3, pair[1] + 3)]
        + [photo.shape[1] - 1]
    )
    for line in lines:
        for start, end in zip(gaps[::2], gaps[1::2], strict=True):
            ax.plot(
                [start, end],
                np.polyval(line, [start, end]),
                color="k",
                ls="--",
                lw=1.3,
                path_effects=palette.halo(1.3),
            )
    low = (
        read.bottom.max() + 10
    )  # the height labels: under the lowest window, every other one lower
    for k, (u, top, bottom, (_, right)) in enumerate(
        zip(columns, read.top, read.bottom, glass, strict=True)
    ):
        ax.plot(
            [right + 4] * 2, [top, bottom], color="k", lw=1.5, marker="_", ms=7, mew=1.5
        )  # beside the glass
        ax.text(
            u,
            low + 18 * (k % 2),
            f"{bottom - top:.1f}",
            color="white",
            ha="center",
            va="top",
            fontsize=8.5,
            bbox=dict(fc="k", alpha=0.75, lw=0, pad=1.5),
        )
    ax.text(
        columns[0] - 30,
        low,
        "height (px):",
        color="white",
        ha="right",
        va="top",
        fontsize=8.5,
        bbox=dict(fc="k", alpha=0.75, lw=0, pad=1.5),
    )
    ax.set_xlim(-0.5, photo.shape[1] - 0.5)
    ax.set_ylim(photo.shape[0] - 0.5, -0.5)
    ax.set_xlabel("u (px)")
    ax.set_ylabel("v (px)")

    rows = np.arange(int(read.top[0]) - 15, int(read.bottom[0]) + 20)  # the nearest window's column
    ax_col.plot(grey[rows, columns[0]], rows, color="k", lw=1.2)
    ax_col.axvline(read.level[0], color=palette.GREY, ls="--", lw=1)
    for edge, name, at in (
        (read.top[0], "top", 0.2),
        (read.bottom[0], "bottom", 0.75),
    ):  # on the empty bright side
        ax_col.plot(read.level[0], edge, "o", color="k", mfc="white", ms=6)
        ax_col.annotate(
            f"{name}\nrow {edge:.1f}",
            (read.level[0], edge),
            (250, rows[0] + at * np.ptp(rows)),
            ha="right",
            va="center",
            fontsize=8.5,
            arrowprops=dict(arrowstyle="-", color=palette.GREY, lw=0.8),
        )
    ax_col.set_ylim(rows[-1], rows[0])
    ax_col.set_xlim(0, 255)
    ax_col.set_xlabel("brightness (0-255)")
    ax_col.set_ylabel("v (px)")
    ax_col.set_title(
        f"nearest window, column\nu = {columns[0]}: edges where it\ncrosses half-way (dashed)",
        fontsize=9,
    )
