"""Helpers shared by the image-formation demos (lessons 01-03)."""
from __future__ import annotations

from ._base import FigureView


def freeze_layout(view: FigureView) -> None:
    """Lay the figure out once (constrained layout), then keep those positions.

    Re-running constrained layout on every slider event costs 20-80 ms with image and
    3-D axes; the layout does not change when only artists' data move. Titles that will
    change should be set to text of their final length before calling this.
    """
    view.fig.canvas.draw()
    view.fig.set_layout_engine("none")
