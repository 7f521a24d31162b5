"""Pictures of the course's conventions (lesson 00 and docs/conventions.md): pixels and the camera frame."""
from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.image import AxesImage

from . import palette
from .plane import image_axes


def draw_pixel_grid(ax: Axes, size: tuple[int, int], marked: tuple[int, int]) -> AxesImage:
    """A tiny ``size = (W, H)`` image: pixel centres at whole (u, v), edges at half-integers.

    ``imshow``'s own extent for an (H, W) array is (-0.5, W - 0.5, H - 0.5, -0.5), the course's
    convention, so the returned image's extent shows it. Pixel ``marked = (u, v)`` is outlined and
    labelled with how numpy reads it, ``img[v, u]``; the image centre ((W-1)/2, (H-1)/2) is a cross.
    Purple and brown: red, green and blue are the camera axes' colours (:data:`palette.AXIS_COLOURS`),
    which :func:`draw_camera_frame` draws beside this picture in lesson 00.
    """
    width, height = size
    u, v = np.meshgrid(np.arange(width), np.arange(height))
    image = ax.imshow((u + v) % 2, cmap="Greys", vmin=0, vmax=8)  # a light checkerboard: one square per pixel
    image_axes(ax, size)
    ax.set_title(f"a {width} x {height} image: pixel centres at whole numbers", fontsize=10)
    for set_ticks, n in ((ax.set_xticks, width), (ax.set_yticks, height)):  # the centres, and the edges -0.5 and n - 0.5
        ticks = [-0.5, *range(n), n - 0.5]
        set_ticks(ticks, [f"{t:g}" for t in ticks])
    ax.plot(u.ravel(), v.ravel(), ".", color="k", ms=4)
    mu, mv = marked
    ax.add_patch(_square(mu, mv, palette.PURPLE))
    ax.text(mu, mv - 0.1, f"(u, v) = ({mu}, {mv})", color=palette.PURPLE, ha="center", va="bottom", fontsize=9)
    ax.text(mu, mv + 0.1, f"img[{mv}, {mu}]", color=palette.PURPLE, ha="center", va="top", fontsize=9)
    centre = ((width - 1) / 2, (height - 1) / 2)
    ax.plot(*centre, "+", color=palette.BROWN, ms=14, mew=2)
    ax.text(centre[0], centre[1] + 0.2, f"centre ({centre[0]:g}, {centre[1]:g})", color=palette.BROWN, fontsize=9,
            ha="center", va="top")
    return image


def _square(u: float, v: float, colour: str):
    from matplotlib.patches import Rectangle

    return Rectangle((u - 0.5, v - 0.5), 1.0, 1.0, fill=False, edgecolor=colour, lw=2.5)


def draw_camera_frame(ax: Axes) -> None:
    """The camera frame seen from behind the camera, looking where it looks: x right, y down, z into the page.

    In the course's axis colours (:data:`palette.AXIS_COLOURS`): x red, y green, z blue, as the
    3-D cameras of lesson 04 draw them.
    """
    ax.set_xlim(-0.3, 1.6)
    ax.set_ylim(1.5, -0.6)  # y down
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title("the camera frame, seen from behind", fontsize=10)
    arrow = dict(arrowstyle="-|>", lw=2, mutation_scale=18)
    x_colour, y_colour, z_colour = palette.AXIS_COLOURS
    ax.annotate("", (1.1, 0), (0, 0), arrowprops=dict(color=x_colour, **arrow))
    ax.annotate("", (0, 1.1), (0, 0), arrowprops=dict(color=y_colour, **arrow))
    ax.text(1.15, 0, "x, right", color=x_colour, va="center", fontsize=10)
    ax.text(0, 1.2, "y, down", color=y_colour, ha="center", va="top", fontsize=10)
    ax.plot(0, 0, "o", ms=16, mfc="white", mec=z_colour, mew=2)
    ax.plot(0, 0, "x", ms=9, color=z_colour, mew=2)
    ax.text(0.15, -0.2, "z, forward: into the page\n(the viewing direction, +z)", color=z_colour,
            va="bottom", fontsize=10)
