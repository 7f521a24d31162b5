"""What every lesson-05 demo shares.

One colour and line style per camera model, the marker of the reference point X0, the legend; the
scene's target and the dolly zoom's constants.
"""

from __future__ import annotations

import numpy as np
from matplotlib.lines import Line2D

from ...plotting import palette

TARGET = np.array([0.0, 0.0, 0.5])
F0, D0 = 800.0, 4.0  # reference focal length (px) and distance (m) for the dolly zoom
DOLLY_VIEW = np.radians([-40.0, 20.0])  # the dolly zoom demo's azimuth and elevation
DOLLY_OFFSET = (
    100.0  # pixels right of the image centre where the dolly zoom keeps the cube (off axis)
)
# From 2 m with the cube up to 100 px off centre, every corner of all three images stays in the 640 x 480 frame.
DOLLY_DISTANCES = (2.0, 150.0)

# One colour per camera model in every lesson-05 figure and demo (the lesson's static figures use them too).
COLOURS = {
    "perspective": palette.RED,
    "weak perspective": palette.BLUE,
    "para-perspective": palette.GREEN,
    "orthographic": palette.PURPLE,
}
STYLES = {
    "perspective": "-",
    "weak perspective": "--",
    "para-perspective": ":",
    "orthographic": "-",
}


# The reference point X0 of every affine approximation (or its image), one marker in every lesson-05 figure.
REFERENCE_MARKER = dict(marker="D", ms=6, mfc="white", mec="0.1", mew=1.3, ls="none")
REFERENCE_LABEL = "$X_0$, the reference point"


def reference_marker(ax, zorder=4):
    """The X0 marker on ``ax``, empty until :func:`place_reference` moves it.

    A figure legend names it: a label beside it would cover the data.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    zorder : float
        The marker's drawing order.

    Returns
    -------
    tuple of matplotlib.lines.Line2D
        The one marker, as a one-artist tuple (for ``view.animate(*...)``).
    """
    (marker,) = ax.plot([], [], zorder=zorder, **REFERENCE_MARKER)
    return (marker,)


def place_reference(artists, xy):
    """Move the X0 marker made by :func:`reference_marker` to the point ``xy``.

    Parameters
    ----------
    artists : tuple of matplotlib.lines.Line2D
        What :func:`reference_marker` returned.
    xy : (2,) array_like
        The point, in the axes' data coordinates.
    """
    artists[0].set_data([xy[0]], [xy[1]])


def model_line(ax, model, lw=1.1, **kw):
    """An empty line in ``model``'s colour and style, labelled with the model's name (for legends).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    model : str
        A key of :data:`COLOURS` (``"perspective"``, ``"weak perspective"``, ...).
    lw : float
        The line width, points.
    **kw
        Other :meth:`matplotlib.axes.Axes.plot` options.

    Returns
    -------
    matplotlib.lines.Line2D
        The line, with no data yet.
    """
    (ln,) = ax.plot([], [], color=COLOURS[model], ls=STYLES[model], lw=lw, label=model, **kw)
    return ln


# Drawn above the X0 diamond (zorder 4), so the + stays visible where X0 images on the principal point.
PRINCIPAL_POINT_MARKER = dict(marker="+", color="0.3", ms=11, mew=1.2, ls="none", zorder=5)


def model_legend(fig, models, reference=False, principal_point=False, extra=(), ncols=None, **kw):
    """One legend above the figure naming each model's colour, drawn once, outside the data.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    models : sequence of str
        The models to name, keys of :data:`COLOURS`.
    reference : bool
        Also name the X0 marker.
    principal_point : bool
        Also name the principal point's marker.
    extra : sequence of artists
        More handles, after those.
    ncols : int, optional
        Columns of the legend; default one row (as many columns as handles).
    **kw
        Other :meth:`matplotlib.figure.Figure.legend` options.

    Returns
    -------
    matplotlib.legend.Legend
        The legend, one row unless ``ncols`` says otherwise, outside the axes at the top.
    """
    handles = [Line2D([], [], color=COLOURS[m], ls=STYLES[m], lw=1.5, label=m) for m in models]
    if reference:
        handles.append(Line2D([], [], label=REFERENCE_LABEL, **REFERENCE_MARKER))
    if principal_point:
        handles.append(Line2D([], [], label="principal point", **PRINCIPAL_POINT_MARKER))
    handles += list(extra)
    return fig.legend(
        handles=handles,
        loc="outside upper center",
        ncols=ncols or len(handles),
        fontsize=8,
        frameon=False,
        **kw,
    )
