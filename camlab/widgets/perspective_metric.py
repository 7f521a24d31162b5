r"""Lesson 10, section 8: metric rectification from right angles alone, live.

A synthetic chessboard (6 x 9 corners) photographed by a camera the sliders turn; its right
angles give the image of :math:`C^*_\\infty` (:func:`camlab.perspective.metric_rectification`),
and the rectified corners show how square the squares come out, under corner noise, and what
happens without the second direction (the blocks' diagonals).
"""

from __future__ import annotations

import textwrap
from typing import NamedTuple

import ipywidgets as W
import numpy as np

from .. import perspective as pp
from ..plotting import palette
from ..projective import map_points
from ._base import Demo, FigureView, build_demo, register, slider
from .controls import monospace

_K = np.array([[800.0, 0.0, 319.5], [0.0, 800.0, 239.5], [0.0, 0.0, 1.0]])
_PLANE = np.stack(np.meshgrid(np.arange(9.0), np.arange(6.0)), axis=-1)  # (6, 9, 2), squares
_JITTER = np.random.default_rng(0).normal(size=(6, 9, 2))  # one noise pattern, scaled by the slider


def board_photo(pitch: float, yaw: float, noise_px: float) -> np.ndarray:
    """The image corners (6, 9, 2) of a 6 x 9 grid of unit squares, turned by pitch and yaw (rad).

    The camera is ``_K`` (f = 800 px) 14 squares from the board's centre; ``noise_px`` scales
    a fixed pattern of Gaussian corner noise (pixels), so moving it changes only its size.

    Parameters
    ----------
    pitch, yaw : float
        The board's turn about the camera's x and y axes, radians.
    noise_px : float
        The corner noise's standard deviation, pixels.

    Returns
    -------
    (6, 9, 2) ndarray
        The corners (u, v), pixels, row by row.
    """
    cp, sp, cy, sy = np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    R = np.array([[1, 0, 0], [0, cp, -sp], [0, sp, cp]]) @ np.array(
        [[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]]
    )
    G = _K @ np.column_stack([R[:, 0], R[:, 1], R @ [-4.0, -2.5, 0.0] + [0, 0, 14.0]])
    return map_points(G, _PLANE.reshape(-1, 2)).reshape(6, 9, 2) + noise_px * _JITTER


def rows_and_columns(grid: np.ndarray):
    """Every row against every column (54 pairs): right angles in one pair of directions only.

    Parameters
    ----------
    grid : (rows, cols, 2) ndarray
        Image corners (u, v), pixels, row by row.

    Returns
    -------
    OrthogonalLinePairs
        ``lines_l``, ``lines_m``, each (rows * cols, 3): each row's line (through its end
        corners) against each column's.
    """
    h = np.concatenate([grid, np.ones(grid.shape[:2] + (1,))], axis=2)
    rows = np.cross(h[:, 0], h[:, -1])
    cols = np.cross(h[0], h[-1])
    i, j = np.meshgrid(np.arange(len(rows)), np.arange(len(cols)), indexing="ij")
    return pp.OrthogonalLinePairs(rows[i.ravel()], cols[j.ravel()])


def upright_on_squares(H: np.ndarray, grid: np.ndarray) -> np.ndarray:
    """The rectified corners, moved by the similarity that best fits them to the plane's squares.

    Parameters
    ----------
    H : (3, 3) ndarray
        A rectifying homography, up to a similarity (:func:`camlab.perspective.metric_rectification`).
    grid : (6, 9, 2) ndarray
        The photo's corners (u, v), pixels.

    Returns
    -------
    (6, 9, 2) ndarray
        The rectified corners in squares, placed on the true ones (0..8, 0..5) by least squares.
    """
    z = map_points(H, grid.reshape(-1, 2)) @ [1, 1j]
    target = _PLANE.reshape(-1, 2) @ [1, 1j]
    (s, t), *_ = np.linalg.lstsq(np.c_[z, np.ones_like(z)], target, rcond=None)
    w = s * z + t
    return np.c_[w.real, w.imag].reshape(6, 9, 2)


class Squareness(NamedTuple):
    """How square a grid's squares are (:func:`squareness`)."""

    ratio: float
    """Mean side across over mean side down (1 for squares)."""
    worst_angle: float
    """The largest miss of 90 degrees over the squares' corners, degrees."""


def squareness(q: np.ndarray) -> Squareness:
    """Mean side across / side down of the squares, and the worst corner angle's miss of 90 deg.

    Parameters
    ----------
    q : (rows, cols, 2) ndarray
        Grid corners, row by row.

    Returns
    -------
    Squareness
        ``ratio``, mean side across over mean side down (1 for squares), and ``worst_angle``,
        the largest |angle - 90| over the squares' top-left corners, degrees.
    """
    across, down = np.diff(q, axis=1)[:-1, :], np.diff(q, axis=0)[:, :-1]
    cos = (across * down).sum(-1) / np.linalg.norm(across, axis=-1) / np.linalg.norm(down, axis=-1)
    ratio = np.linalg.norm(across, axis=-1).mean() / np.linalg.norm(down, axis=-1).mean()
    return Squareness(
        float(ratio), float(np.abs(np.degrees(np.arccos(np.clip(cos, -1, 1))) - 90).max())
    )


def _figure():
    """The demo's figure: the photo's axes (corners, 16 line artists) and the rectified corners'."""
    view = FigureView(figsize=(9, 3.8))
    ax_p, ax_r = view.fig.subplots(1, 2, width_ratios=[1.3, 1])
    ax_p.set(xlim=(-0.5, 639.5), ylim=(479.5, -0.5), aspect="equal")
    ax_p.set_xlabel(
        "u (px, right); each pair: a blue line (across) at right angles to a purple one (up)",
        fontsize=8,
        labelpad=1,
    )
    ax_p.set_ylabel("v (px, down)", fontsize=8, labelpad=1)
    ax_p.set_title("photo: corners and the right angles used", fontsize=10, pad=3)
    ax_r.set(xlim=(-0.7, 8.7), ylim=(5.7, -0.7), aspect="equal")  # the same margin on all sides
    ax_r.set_yticks(range(6))
    ax_r.set_xlabel("across (squares)", fontsize=8, labelpad=1)
    ax_r.set_ylabel("down (squares)", fontsize=8, labelpad=1)
    for ax in (ax_p, ax_r):
        ax.tick_params(labelsize=7)
    truth = view.animate(  # hidden with a refusal: then there is nothing to compare with
        ax_r.plot(*_PLANE.reshape(-1, 2).T, "+", color=palette.GREEN, ms=12, mew=1.2, zorder=4)[0]
    )
    ax_r.set_title("rectified (yellow) under the true corners (green +)", fontsize=10, pad=3)
    dots = view.animate(  # yellow: corners found on a photo (the lesson's colour key)
        ax_p.plot([], [], "o", ms=4, color=palette.YELLOW, mec="k", mew=0.6, zorder=3)[0]
    )
    lines = [
        view.animate(ax_p.plot([], [], color=c, lw=1.2, zorder=2)[0])
        for c in [palette.BLUE, palette.PURPLE] * 8
    ]
    rect = view.animate(
        ax_r.plot([], [], "o", ms=6, color=palette.YELLOW, mec="k", mew=0.8, zorder=3)[0]
    )
    why = view.animate(
        ax_r.text(
            4,
            2.5,
            "",
            ha="center",
            va="center",
            fontsize=8.5,
            color=palette.RED,
            zorder=4,
            bbox=dict(boxstyle="round,pad=0.3", fc="white", ec=palette.RED),
        )
    )
    return view, dots, lines, rect, why, truth


@register(
    lesson="10",
    sweep={
        "pitch": [0.0, 0.9, -0.6],
        "yaw": [0.0, 0.8],
        "noise": [0.0, 3.0],
        "diagonals": [False, True],
    },
)
def right_angle_rectification() -> Demo:
    """Rectify a chessboard photo up to a similarity from its right angles alone (section 8).

    Returns
    -------
    Demo
        The demo: controls ``pitch`` and ``yaw`` (the board's turn, rad), ``noise`` (corner
        noise, px) and ``diagonals`` (use the blocks' diagonals, the second direction), the
        figure (the photographed corners with the line pairs used; the rectified corners on
        the true squares) and ``state`` (``ratio`` side across / side down, ``worst_angle`` in
        degrees, ``exact_worst_angle`` the same for the estimated H applied to the noise-free
        corners, ``error`` the refusal when the right angles are all in one pair of directions).
    """
    view, dots, lines, rect, why, truth = _figure()
    readout = W.HTML()

    def update(v: dict, state: dict) -> None:
        grid = board_photo(v["pitch"], v["yaw"], v["noise"])
        dots.set_data(*grid.reshape(-1, 2).T)
        k = min(grid.shape[:2])
        if v[
            "diagonals"
        ]:  # the outer rows and columns, and two blocks' diagonals (blue with purple)
            segs = [grid[0, [0, -1]], grid[[0, -1], 0], grid[-1, [0, -1]], grid[[0, -1], -1]]
            segs += [grid[[0, k - 1], [0, k - 1]], grid[[k - 1, 0], [0, k - 1]]]
            segs += [grid[[0, k - 1], [8 - k + 1, 8]], grid[[k - 1, 0], [8 - k + 1, 8]]]
            colours, width = [palette.BLUE, palette.PURPLE] * 4, 1.2
            L, M = pp.square_grid_right_angles(grid)
        else:  # every row (blue) against every column (purple), thin
            segs = [r[[0, -1]] for r in grid] + [c[[0, -1]] for c in grid.transpose(1, 0, 2)]
            colours, width = [palette.BLUE] * len(grid) + [palette.PURPLE] * grid.shape[1], 0.8
            L, M = rows_and_columns(grid)
        for n, artist in enumerate(lines):
            artist.set_data(*(segs[n] if n < len(segs) else np.empty((0, 2))).T)
            artist.set(color=colours[n] if n < len(segs) else palette.BLUE, lw=width)
        try:
            met = pp.metric_rectification(L, M)
        except pp.DegenerateError as exc:
            rect.set_data([], [])
            truth.set_visible(False)
            why.set_text("no rectification: all right angles are\nbetween the same two directions")
            state.update(ratio=None, worst_angle=None, error=str(exc))
            readout.value = monospace(textwrap.fill("refused: " + str(exc), 76))
            return
        why.set_text("")
        truth.set_visible(True)
        q = upright_on_squares(met.H, grid)
        rect.set_data(*q.reshape(-1, 2).T)
        ratio, worst = squareness(q)
        photo_ratio, photo_worst = squareness(grid)
        # H's own error, apart from the noise on single corners: H applied to the exact corners
        exact = squareness(upright_on_squares(met.H, board_photo(v["pitch"], v["yaw"], 0.0)))
        state.update(
            ratio=ratio, worst_angle=worst, exact_worst_angle=exact.worst_angle, error=None
        )
        readout.value = monospace(
            f"{len(L)} orthogonal pairs"
            + ("" if v["diagonals"] else " (all 6 rows x 9 columns)")
            + f", corner noise {v['noise']:.2f} px\n"
            f"photo:     side across / down {photo_ratio:.3f}, worst angle off 90 by {photo_worst:.1f}\u00b0\n"
            f"rectified: side across / down {ratio:.3f}, worst angle off 90 by {worst:.1f}\u00b0\n"
            + (
                "  (the noisy corners: one square's angle moves with its corners' noise)\n"
                if v["noise"] > 0
                else "  (exact corners: no noise to move them)\n"
            )
            + f"H on the exact corners: across / down {exact.ratio:.4f}, worst angle off 90 by "
            f"{exact.worst_angle:.2f}\u00b0\n  (the rectification's own error)"
        )

    controls = {
        "pitch": slider(0.5, -0.9, 0.9, 0.05, "board pitch (rad)"),
        "yaw": slider(0.4, -0.9, 0.9, 0.05, "board yaw (rad)"),
        "noise": slider(0.5, 0.0, 3.0, 0.25, "corner noise (px)"),
        "diagonals": W.Checkbox(value=True, description="use the blocks' diagonals"),
    }
    return build_demo(
        "right_angle_rectification",
        controls,
        view,
        update,
        title="Right angles alone: the image of C*\u221e",
        extra=[readout],
    )
