"""The demo of lesson 00: proof that sliders, figures and readouts work in your browser."""
from __future__ import annotations

import ipywidgets as W
import numpy as np
from matplotlib.colors import to_rgba

from .. import projective as pj
from ..plotting.plane import plane_axes
from ._base import Demo, FigureView, display_mode, build_demo, register, slider
from .controls import monospace
from ..plotting import palette

# A little house outline, in plot units: the course's running example of a shape. y points down, as in
# every image of the course, so the roof (drawn on top) has the most negative y.
HOUSE = np.array([[-1, 1], [1, 1], [1, -0.6], [0, -1.4], [-1, -0.6], [-1, 1]], dtype=float)


@register(lesson="00", sweep={"angle": [-180.0, 0.0, 45.0, 120.0, 180.0], "scale": [0.3, 0.5, 1.5, 2.0]})
def stack_check() -> Demo:
    """Rotate and scale a house with two sliders; if it moves, the interactive stack works.

    The axes have y down, like every image in the course, so a positive angle turns the house clockwise:
    the house is mapped by x' = s R(angle) x. The legend sits under the axes, since at scale 2 the house
    reaches every corner of them.
    """
    view = FigureView(figsize=(4.5, 4.9))
    ax = plane_axes(view.fig.subplots(), 3, "a house on axes with y pointing down",
                    xlabel="x, right (plot units)", ylabel="y, down (plot units)")
    ax.invert_yaxis()  # y down, as in images and in the camera frame
    # A light fill keeps the original visible where the moved outline covers its edge (angle 0, scale 1).
    ax.fill(HOUSE[:, 0], HOUSE[:, 1], facecolor=to_rgba(palette.GREY, 0.2), edgecolor=palette.GREY, lw=1, ls="--",
            label="original")
    house = view.animate(ax.plot([], [], color=palette.BLUE, lw=2, label="rotated and scaled")[0])
    tip = view.animate(ax.plot([], [], "o", color=palette.ORANGE, ms=7, label="roof tip")[0])
    view.fig.legend(loc="outside lower center", ncols=3, fontsize=9)
    readout = W.HTML()

    def update(v: dict, state: dict) -> None:
        t, s = np.radians(v["angle"]), v["scale"]
        H = np.array([[s * np.cos(t), -s * np.sin(t), 0], [s * np.sin(t), s * np.cos(t), 0], [0, 0, 1]])
        moved = pj.map_points(H, HOUSE)
        house.set_data(moved[:, 0], moved[:, 1])
        tip.set_data(moved[3:4, 0], moved[3:4, 1])
        x, y = (round(c, 2) + 0.0 for c in moved[3])  # + 0.0 turns a rounded -0.0 into 0.0
        readout.value = monospace(f"roof tip (orange dot) at ({x:+.2f}, {y:+.2f})")
        # tip: where the orange dot is drawn (lesson 00 recomputes it by hand); readout: the text beside it
        state.update(H=H, house=moved, tip=moved[3].copy(), readout=f"({x:+.2f}, {y:+.2f})")

    controls = {
        "angle": slider(20.0, -180.0, 180.0, 1.0, "angle (°)", readout_format=".0f"),
        "scale": slider(1.0, 0.3, 2.0, 0.05, "scale"),
    }
    return build_demo("stack_check", controls, view, update, title="Is everything working?", extra=[readout])


def stack_report() -> str:
    """What the kernel can see of the interactive stack: the versions, and whether demos will be live figures.

    The browser's half (JupyterLab's ipywidgets and ipympl extensions) is out of the kernel's
    sight: the demo below is its test.
    """
    from importlib.metadata import PackageNotFoundError, version

    import matplotlib

    from .. import __version__

    try:
        ipympl = version("ipympl")
    except PackageNotFoundError:
        ipympl = "missing"
    versions = (f"camlab {__version__}, numpy {np.__version__}, matplotlib {matplotlib.__version__}, "
                f"ipywidgets {W.__version__}, ipympl {ipympl}")
    if display_mode() == "ipympl":
        return versions + "\nfigures: live (%matplotlib widget is on); the demo below tests the browser's side"
    return (versions + f"\nfigures: still pictures, not live: the matplotlib backend is {matplotlib.get_backend()!r}; "
            "run `%matplotlib widget` first (the setup cell's first line)")
