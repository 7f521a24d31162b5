"""Pictures of the course's conventions (lesson 00): points as rows, pixels, and the camera frame."""
from __future__ import annotations

from typing import Sequence

import numpy as np
from matplotlib.axes import Axes
from matplotlib.image import AxesImage
from matplotlib.patches import Rectangle

from . import palette
from .plane import image_axes

# The camera frame's axes, here and wherever lesson 00 ties u and v to them (one home for the three).
X_COLOUR, Y_COLOUR, Z_COLOUR = palette.AXIS_COLOURS  # x red, y green, z blue, as every 3-D camera
POINT_COLOUR = palette.ORANGE  # the points lesson 00 reads: the demo's roof tip, the rows of X here


def draw_pixel_grid(ax: Axes, size: tuple[int, int], points: np.ndarray, marked: int) -> AxesImage:
    """A tiny ``size = (W, H)`` image: pixel centres at whole (u, v), edges at half-integers, and ``points``.

    ``imshow``'s own extent for an (H, W) array is (-0.5, W - 0.5, H - 0.5, -0.5), the course's
    convention, so the returned image's extent shows it. Each row ``points[k]`` = (u, v) is a dot
    labelled ``X[k]``; the pixel under ``points[marked]`` is outlined and labelled with how numpy
    reads it, ``img[v, u]``. The u and v labels take the colours of the camera's x and y, which
    they run along.
    """
    width, height = size
    u, v = np.meshgrid(np.arange(width), np.arange(height))
    image = ax.imshow((u + v) % 2, cmap="Greys", vmin=0, vmax=8)  # a light checkerboard: one square per pixel
    image_axes(ax, size)
    ax.set_title(f"a {width} x {height} image:\npixel centres at whole numbers", fontsize=10)
    ax.set_anchor("N")  # the top of its slot, like the panels beside it, so their titles line up
    ax.set_xlabel("u (px): column, along the camera's x", color=X_COLOUR)
    ax.set_ylabel("v (px): row, along y", color=Y_COLOUR)
    for set_ticks, n in ((ax.set_xticks, width), (ax.set_yticks, height)):  # the centres, and the edges -0.5 and n - 0.5
        ticks = [-0.5, *range(n), n - 0.5]
        set_ticks(ticks, [f"{t:g}" for t in ticks])
    ax.plot(u.ravel(), v.ravel(), ".", color="0.45", ms=3)
    points = np.asarray(points, dtype=float)
    ax.plot(points[:, 0], points[:, 1], "o", color=POINT_COLOUR, ms=7)
    for k, (pu, pv) in enumerate(points):
        ax.annotate(f"X[{k}]", (pu, pv), xytext=(0, 7), textcoords="offset points", ha="center", va="bottom",
                    fontsize=9, fontweight="bold")
    mu, mv = points[marked]
    ax.add_patch(Rectangle((mu - 0.5, mv - 0.5), 1.0, 1.0, fill=False, edgecolor=POINT_COLOUR, lw=2.5))
    ax.annotate(f"img[{mv:g}, {mu:g}]", (mu, mv), xytext=(0, -7), textcoords="offset points", ha="center", va="top",
                fontsize=9)
    return image


def draw_point_rows(ax: Axes, points: np.ndarray, notes: Sequence[str]) -> None:
    """The array ``points`` as numpy holds it: one row per point, the columns u and v, each row with a note.

    The axes box has the 4:3 shape of :func:`draw_pixel_grid`'s image and :func:`draw_camera_frame`,
    and all three sit at the top of their slots, so the panels' titles line up in one row.
    """
    points = np.asarray(points, dtype=float)
    ax.set_axis_off()
    ax.set_box_aspect(0.75)
    ax.set_anchor("N")
    ax.set_xlim(0, 1)
    ax.set_ylim(1, 0)
    ax.set_title(f"points are rows:\nX, shape {points.shape}", fontsize=10)
    mono = dict(family="monospace", fontsize=9.5, va="center")
    rows = [f"X[{k}]  {pu:4.1f} {pv:4.1f}  {note}" for k, ((pu, pv), note) in enumerate(zip(points, notes))]
    top, step = 0.12, 0.13
    # The column names over the last digit of each column (characters 9 and 14): spaces keep a monospace text aligned.
    ax.text(0, top, " " * 9 + "u", color=X_COLOUR, fontweight="bold", **mono)
    ax.text(0, top, " " * 14 + "v", color=Y_COLOUR, fontweight="bold", **mono)
    for k, row in enumerate(rows):
        ax.text(0, top + step * (k + 1), row, **mono)
    ax.text(0, top + step * (len(rows) + 1.5), "X[k]     point k, a (2,) row\nX[:, 0]  every u\nX[:, 1]  every v",
            linespacing=1.6, **(mono | dict(va="top")))


def draw_camera_frame(ax: Axes) -> None:
    """The camera frame seen from behind the camera, looking where it looks: x right, y down, z into the page.

    The image plane (in front of the camera, where the virtual image of lesson 01 forms) is the
    rectangle around the principal axis; its u runs along x from the top-left corner, v along y.
    """
    ax.set_xlim(-1.45, 2.55)
    ax.set_ylim(1.75, -1.25)  # y down; the box is 4:3 like the image beside it
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title("the camera frame,\nseen from behind", fontsize=10)
    ax.set_anchor("N")
    w, h = 1.0, 0.75  # half the image plane's width and height (4:3)
    ax.add_patch(Rectangle((-w, -h), 2 * w, 2 * h, facecolor="0.95", edgecolor="0.55", lw=1))
    ax.text(-w + 0.05, h - 0.05, "image plane", color="0.35", ha="left", va="bottom", fontsize=8.5)
    # (u, v) = (0, 0) is the centre of the top-left pixel, a little inside the corner (pixels drawn 0.07 wide).
    u0, v0 = -w + 0.035, -h + 0.035
    thin = dict(arrowstyle="-|>", lw=1.5, mutation_scale=12)
    ax.annotate("", (u0 + 0.7, v0), (u0, v0), arrowprops=dict(color=X_COLOUR, **thin))
    ax.annotate("", (u0, v0 + 0.55), (u0, v0), arrowprops=dict(color=Y_COLOUR, **thin))
    ax.text(u0 + 0.72, v0 - 0.04, "u", color=X_COLOUR, ha="left", va="bottom", fontsize=10, fontweight="bold")
    ax.text(u0 - 0.08, v0 + 0.57, "v", color=Y_COLOUR, ha="right", va="top", fontsize=10, fontweight="bold")
    ax.plot(u0, v0, "o", color="0.35", ms=4)
    ax.text(u0 - 0.06, v0 - 0.06, "(0, 0): top-left\npixel's centre", color="0.35", ha="right", va="bottom", fontsize=8,
            linespacing=1.1)
    thick = dict(arrowstyle="-|>", lw=2, mutation_scale=18)
    ax.annotate("", (1.5, 0), (0, 0), arrowprops=dict(color=X_COLOUR, **thick))
    ax.annotate("", (0, 1.3), (0, 0), arrowprops=dict(color=Y_COLOUR, **thick))
    ax.text(1.55, 0, "x, right", color=X_COLOUR, va="center", fontsize=10)
    ax.text(0, 1.37, "y, down", color=Y_COLOUR, ha="center", va="top", fontsize=10)
    ax.plot(0, 0, "o", ms=16, mfc="white", mec=Z_COLOUR, mew=2)
    ax.plot(0, 0, "x", ms=9, color=Z_COLOUR, mew=2)
    ax.text(w + 0.08, 0.12, "z, forward:\ninto the page", color=Z_COLOUR, va="top", fontsize=9)
