"""The note the lesson-07 demos show beside a torn or failed picture (black in a black box: red means a verdict)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from .._base import FigureView


def warning_note(
    view: FigureView,
    ax: Any,
    x: float = 0.02,
    y: float = 0.02,
    ha: str = "left",
    va: str = "bottom",
) -> Callable[[str], None]:
    """An animated black note in a black-edged white box in ``ax``, hidden until there is something to say.

    Parameters
    ----------
    view : FigureView
        The demo's view; the note is one of its animated artists.
    ax : matplotlib.axes.Axes
        The axes the note belongs to.
    x, y : float
        The note's anchor, axes coordinates (default the bottom-left corner).
    ha, va : str
        Its alignment to the anchor, as matplotlib's ``ha`` and ``va``.

    Returns
    -------
    callable
        ``say(text)``: show ``text`` in the note, or hide it for ``""`` (a hidden text
        costs nothing to draw, an empty one with a box does); ``say.artist`` is the text.
    """
    note = view.animate(
        ax.text(
            x,
            y,
            "",
            transform=ax.transAxes,
            ha=ha,
            va=va,
            fontsize=8,
            color="k",
            bbox=dict(fc="white", ec="k", lw=1.2, alpha=0.9),
            visible=False,
        )
    )

    def say(text: str) -> None:
        note.set_text(text)
        note.set_visible(bool(text))

    say.artist = note  # the text itself, for a browser-drawn demo's scene
    return say


TORN_SHORT = (  # beside a canvas, in a narrow column
    "torn: the line that H sends\nto infinity crosses the\npicture; its halves leave\nthrough infinity and come\nback on the other side"
)
TORN_DRAG = (
    "a bow tie or a dent: the line that H sends to\ninfinity (purple, dashed, above) crosses the\n"
    "picture. Its two halves leave through infinity\nand come back on the other side: torn."
)
