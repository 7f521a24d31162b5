"""The demo of lesson 00: proof that sliders, figures and readouts work in your browser."""
from __future__ import annotations

import ipywidgets as W
import numpy as np

from .. import projective as pj
from ..plotting.plane import plane_axes
from ._base import Demo, FigureView, build_demo, register, slider
from ..plotting import palette

# A little house outline, in plot units: the course's running example of a shape. y points down, as in
# every image of the course, so the roof (drawn on top) has the most negative y.
HOUSE = np.array([[-1, 1], [1, 1], [1, -0.6], [0, -1.4], [-1, -0.6], [-1, 1]], dtype=float)


@register(lesson="00", sweep={"angle": [0.0, 45.0, 120.0], "scale": [0.5, 1.5]})
def stack_check() -> Demo:
    """Rotate and scale a house with two sliders; if it moves, the interactive stack works.

    The axes have y down, like every image in the course, so a positive angle turns the house clockwise.
    """
    view = FigureView(figsize=(4.5, 4.5))
    ax = plane_axes(view.fig.subplots(), 3, "drag the sliders", xlabel="x (right)", ylabel="y (down)")
    ax.invert_yaxis()  # y down, as in images and in the camera frame
    ax.plot(HOUSE[:, 0], HOUSE[:, 1], color=palette.GREY, lw=1, ls="--", label="original")
    house = view.animate(ax.plot([], [], color="tab:blue", lw=2, label="rotated and scaled")[0])
    ax.legend(loc="lower right", fontsize=8)
    readout = W.HTML()

    def update(v: dict, state: dict) -> None:
        t, s = np.radians(v["angle"]), v["scale"]
        H = np.array([[s * np.cos(t), -s * np.sin(t), 0], [s * np.sin(t), s * np.cos(t), 0], [0, 0, 1]])
        moved = pj.map_points(H, HOUSE)
        house.set_data(moved[:, 0], moved[:, 1])
        state.update(H=H, house=moved)
        readout.value = f"<pre>roof tip at ({moved[3, 0]:+.2f}, {moved[3, 1]:+.2f})</pre>"

    controls = {
        "angle": slider(20.0, -180.0, 180.0, 1.0, "angle (°)"),
        "scale": slider(1.0, 0.3, 2.0, 0.05, "scale"),
    }
    return build_demo("stack_check", controls, view, update, title="Is everything working?", extra=[readout])
