"""Controls shared by the demos: sliders, text readouts, draggable corners and their keyboard twins.

One home for the small widgets every lesson's demos use, so they look and behave the
same everywhere. Demo modules hold their controls, artists and ``update`` only.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import ipywidgets as W
import numpy as np

if TYPE_CHECKING:
    from ._base import FigureView


def _look(kw: dict[str, Any]) -> dict[str, Any]:
    """The shared look of every slider: reports while dragging, readable label, 300 px wide (``kw`` overrides)."""
    return {
        "continuous_update": True,
        "style": {"description_width": "initial"},
        "layout": W.Layout(width="300px"),
        **kw,
    }


def slider(
    value: float, lo: float, hi: float, step: float, description: str, **kw: Any
) -> W.FloatSlider:
    """A float slider that reports while dragging, with a readable label width.

    Parameters
    ----------
    value : float
        The starting value.
    lo, hi : float
        The range.
    step : float
        The slider's step.
    description : str
        The label.
    **kw
        Other :class:`ipywidgets.FloatSlider` options; they override the shared look.

    Returns
    -------
    ipywidgets.FloatSlider
        Continuous updates, the whole label shown, 300 px wide.
    """
    return W.FloatSlider(
        value=value, min=lo, max=hi, step=step, description=description, **_look(kw)
    )


def int_slider(
    value: int, lo: int, hi: int, description: str, step: int = 1, **kw: Any
) -> W.IntSlider:
    """An integer slider with the look of :func:`slider`.

    Parameters
    ----------
    value : int
        The starting value.
    lo, hi : int
        The range.
    description : str
        The label.
    step : int
        The slider's step.
    **kw
        Other :class:`ipywidgets.IntSlider` options; they override the shared look.

    Returns
    -------
    ipywidgets.IntSlider
        The slider.
    """
    return W.IntSlider(value=value, min=lo, max=hi, step=step, description=description, **_look(kw))


def log_slider(
    value: float, lo: float, hi: float, step: float, description: str, **kw: Any
) -> W.FloatLogSlider:
    """A slider on a log10 scale from ``lo`` to ``hi`` (values, not exponents).

    Parameters
    ----------
    value : float
        The starting value.
    lo, hi : float
        The range (positive values, not exponents).
    step : float
        The step, in decades.
    description : str
        The label.
    **kw
        Other :class:`ipywidgets.FloatLogSlider` options; they override the shared look.

    Returns
    -------
    ipywidgets.FloatLogSlider
        The slider (base 10), with the look of :func:`slider`.
    """
    return W.FloatLogSlider(
        value=value,
        base=10,
        min=np.log10(lo),
        max=np.log10(hi),
        step=step,
        description=description,
        **_look(kw),
    )


def choice_slider(
    options: Sequence[Any], value: Any, description: str, **kw: Any
) -> W.SelectionSlider:
    """A slider over a few fixed values (f-numbers ...) with the look of :func:`slider`.

    Parameters
    ----------
    options : sequence
        The values, in order.
    value : object
        The starting value (one of ``options``).
    description : str
        The label.
    **kw
        Other :class:`ipywidgets.SelectionSlider` options; they override the shared look.

    Returns
    -------
    ipywidgets.SelectionSlider
        The slider.
    """
    return W.SelectionSlider(
        options=list(options), value=value, description=description, **_look(kw)
    )


def whole_label(control: W.Widget) -> W.Widget:
    """Let ``control`` show its whole description (``build_demo`` applies it to every control).

    ipywidgets' defaults cut labels short: a dropdown's description gets 80 px ("sensor's p...")
    and a checkbox's sits after an empty 80 px indent in a 300 px box ("show the real image
    (rotat..."). Labels get the width they need, and a checkbox its label right after the box.

    Parameters
    ----------
    control : ipywidgets.Widget
        Any control; a checkbox loses its indent (and gets ``width: auto`` unless it has a
        width), another control with a description and no description width gets
        ``"initial"``.

    Returns
    -------
    ipywidgets.Widget
        ``control`` itself, changed in place.
    """
    if isinstance(control, W.Checkbox):
        control.indent = False
        if not control.layout.width:
            control.layout.width = "auto"
    elif getattr(control, "description", "") and not getattr(
        control.style, "description_width", "initial"
    ):
        control.style.description_width = "initial"
    return control


def monospace(text: str) -> str:
    """HTML for a monospace readout beside the sliders (text in the figure is slow to draw).

    Parameters
    ----------
    text : str
        The readout (inserted as it is: escape any ``<`` yourself).

    Returns
    -------
    str
        A ``<pre>`` element, 12 px.
    """
    return f"<pre style='font-size: 12px; line-height: 1.3; margin: 4px 0'>{text}</pre>"


def corner_text(value: str, description: str) -> W.Text:
    """A text control holding four corners as ``"u0, v0; u1, v1; u2, v2; u3, v3"``.

    Parameters
    ----------
    value : str
        The starting corners (:func:`format_corners`).
    description : str
        The label.

    Returns
    -------
    ipywidgets.Text
        Updates on Enter or leaving the box (not on every keystroke), 300 px wide.
    """
    return W.Text(
        value=value,
        description=description,
        continuous_update=False,
        style={"description_width": "initial"},
        layout=W.Layout(width="300px"),
    )


CORNER_LIMIT_PX = 1e6
"""Corners farther out than this (pixels) are typing slips, not pictures."""


def parse_corners(text: str) -> np.ndarray:
    """Four corners from their text form, ``'u0, v0; u1, v1; ...'``.

    Parameters
    ----------
    text : str
        Four ``u, v`` pairs (pixels) separated by ``;``.

    Returns
    -------
    (4, 2) ndarray
        The corners, pixels.

    Raises
    ------
    ValueError
        Malformed text, non-finite or far-off (beyond :data:`CORNER_LIMIT_PX`) coordinates,
        or two corners less than a pixel apart.
    """
    rows = [r for r in str(text).split(";") if r.strip()]
    try:
        pts = np.array([[float(x) for x in r.split(",")] for r in rows], dtype=float)
    except ValueError:  # a word, or rows of different lengths
        pts = np.empty(0)
    if pts.shape != (4, 2):
        raise ValueError(f"expected 4 corners 'u, v' (pixels) separated by ';', got {text!r}")
    far = np.flatnonzero(~(np.abs(pts) <= CORNER_LIMIT_PX).all(axis=1))
    if far.size:
        u, v = pts[far[0]]
        raise ValueError(
            f"corner {far[0] + 1} is ({u:.4g}, {v:.4g}): expected finite pixel coordinates "
            f"within ±{CORNER_LIMIT_PX:.0e}"
        )
    gaps = np.linalg.norm(pts[:, None] - pts[None], axis=-1)
    np.fill_diagonal(gaps, np.inf)
    i, j = np.unravel_index(int(np.argmin(gaps)), gaps.shape)
    if gaps[i, j] < 1.0:
        raise ValueError(
            f"corners {min(i, j) + 1} and {max(i, j) + 1} coincide (less than 1 px apart): "
            f"four corners need four distinct points"
        )
    return pts


def format_corners(pts: np.ndarray) -> str:
    """Corners in the text form the corner controls use (:func:`parse_corners` reads it).

    Parameters
    ----------
    pts : (N, 2) array_like
        Corners, pixels.

    Returns
    -------
    str
        ``"u0, v0; u1, v1; ..."`` with two decimals.
    """
    return "; ".join(f"{u:.2f}, {v:.2f}" for u, v in np.asarray(pts, dtype=float))


def corner_keys(
    control: W.Text,
    names: Sequence[str],
    u_max: float,
    v_max: float,
    clamp: Callable[[np.ndarray, int, np.ndarray], np.ndarray] | None = None,
    browser_syncs: bool = False,
) -> dict[str, W.ValueWidget]:
    """Keyboard twins of dragging a corner: a dropdown picks the corner, two sliders move it.

    Moving a slider
    writes that corner into ``control`` (the corners text), so the demo updates through the
    same path as a drag. When the text changes (typed, dragged, a new photo) or another
    corner is picked, the sliders jump to that corner without writing back. Give the two
    sliders to :func:`~camlab.widgets.build_demo` as ``linked`` controls, so that only the
    text triggers an update; the demo's update can mark ``values["corner"]`` in the figure.

    Parameters
    ----------
    control : ipywidgets.Text
        The corners text (:func:`corner_text`).
    names : sequence of str
        The corners' names, in the order of the text's corners.
    u_max, v_max : float
        The sliders' upper ends, pixels (usually the image's width and height).
    clamp : callable, optional
        ``clamp(corners, index, wanted) -> (u, v)``: where a slider may put corner ``index``
        when it asks for ``wanted`` (e.g. :func:`convex_clamp`); the sliders then snap to it.
        None (default) puts it where asked.
    browser_syncs : bool, optional
        True when the browser keeps the text and the sliders in step itself (a demo drawn in the
        browser, :class:`~camlab.widgets.browser.BrowserView`; its twin of this function is
        ``followDrag`` in ``drag.js``): the kernel then only sets the sliders to the first corner
        and writes neither the text nor the sliders afterwards. Two writers raced: the kernel's
        copy of a slider or of the text, sent back while the browser was already a key press
        further, undid that press (6 PageUp moved a corner 10-25 px of 30 in the lecture mode).

    Returns
    -------
    dict of str to ipywidgets.ValueWidget
        ``{"corner": Dropdown, "corner_u": slider, "corner_v": slider}``.
    """
    pick = W.Dropdown(
        options=[(name, i) for i, name in enumerate(names)],
        value=0,
        description="move corner",
        style={"description_width": "initial"},
    )
    u = slider(0.0, 0.0, u_max, 1.0, "corner u (px, right)")
    v = slider(0.0, 0.0, v_max, 1.0, "corner v (px, down)")
    syncing = [False]

    def show_corner(_change: Any = None) -> None:
        try:
            pts = parse_corners(control.value)
        except ValueError:
            return  # the text is being typed: the sliders keep the last corner
        syncing[0] = True
        try:
            u.value, v.value = (float(x) for x in pts[pick.value])
        finally:
            syncing[0] = False

    def write_corner(_change: Any) -> None:
        if syncing[0] or not (np.isfinite(u.value) and np.isfinite(v.value)):
            return  # NaN from a slider: the demo reports it (widgets._base.build_demo)
        try:
            pts = parse_corners(control.value)
        except ValueError:
            return
        wanted = np.array([u.value, v.value], dtype=float)
        pts[pick.value] = wanted if clamp is None else clamp(pts, pick.value, wanted)
        before, control.value = control.value, format_corners(pts)
        if control.value == before or not np.allclose(pts[pick.value], wanted):
            show_corner()  # clamped: the sliders show where the corner stays

    keys = {"corner": pick, "corner_u": u, "corner_v": v}
    show_corner()
    if browser_syncs:
        return keys  # kept in step in the browser from here on (drag.js's followDrag)
    for widget, handler in (
        (control, show_corner),
        (pick, show_corner),
        (u, write_corner),
        (v, write_corner),
    ):
        widget.observe(handler, names="value")
    return keys


def _cross2(a: np.ndarray, b: np.ndarray) -> float:
    """The z component of a x b for 2-vectors (numpy 2 refuses np.cross of 2-vectors)."""
    return float(a[0] * b[1] - a[1] * b[0])


def convex_margin(corners: np.ndarray) -> float:
    """The smallest distance (px) of a corner from the line of a side it is not on; < 0 if not convex.

    A quadrilateral is convex when, for each side, the two other corners lie on its inner side;
    this is the least of those eight signed distances (positive inside).

    Parameters
    ----------
    corners : (4, 2) array_like
        The outline's corners in order (either way round), pixels.

    Returns
    -------
    float
        The least distance, pixels: positive for a convex outline, 0 or less for a dent or a
        bow tie, ``-inf`` for one with no area or a repeated corner.
    """
    q = np.asarray(corners, dtype=float)
    e = np.roll(q, -1, axis=0) - q  # side k runs from corner k to corner k + 1
    area = np.sum(q[:, 0] * np.roll(q[:, 1], -1) - np.roll(q[:, 0], -1) * q[:, 1])
    lengths = np.linalg.norm(e, axis=1)
    if area == 0 or not np.all(lengths > 0):
        return -np.inf
    return float(
        min(
            np.sign(area) * _cross2(e[k], q[(k + j) % 4] - q[k]) / lengths[k]
            for k in range(4)
            for j in (2, 3)
        )
    )


def convex_clamp(margin_px: float) -> Callable[[np.ndarray, int, np.ndarray], np.ndarray]:
    """A ``clamp`` for :func:`corner_keys`: a slider stops a corner ``margin_px`` short of a dent or bow tie.

    From a convex outline (:func:`convex_margin` at least ``margin_px``) the corner moves toward
    where the slider asks as far as the outline stays so; from any other outline (typed or
    dragged) it moves freely.

    Parameters
    ----------
    margin_px : float
        The least :func:`convex_margin` a slider may leave, pixels.

    Returns
    -------
    callable
        ``clamp(corners, index, wanted) -> (2,) ndarray``: where corner ``index`` goes.
    """

    def clamp(corners: np.ndarray, index: int, wanted: np.ndarray) -> np.ndarray:
        q = np.array(corners, dtype=float)
        start = q[index].copy()

        def ok(t: float) -> bool:
            q[index] = start + t * (wanted - start)
            return convex_margin(q) >= margin_px

        if not ok(0.0) or ok(1.0):
            return np.asarray(wanted, dtype=float)
        low, high = 0.0, 1.0  # ok at low, not at high
        for _ in range(30):
            mid = 0.5 * (low + high)
            low, high = (mid, high) if ok(mid) else (low, mid)
        return np.round(start + low * (wanted - start), 1)

    return clamp


def connect_corner_drag(
    view: FigureView,
    ax: Any,
    control: W.Text,
    get_corners: Callable[[], np.ndarray],
    radius_px: float = 15.0,
) -> dict[str, Callable]:
    """Let the mouse drag the four corners drawn in ``ax``; a drag writes ``control.value``.

    Press within ``radius_px`` screen pixels of a corner to pick it, move to drag it,
    release to drop it.

    Parameters
    ----------
    view : FigureView
        The demo's figure (its canvas gets the handlers).
    ax : matplotlib.axes.Axes
        The axes the corners are drawn in (data coordinates are pixels).
    control : ipywidgets.Text
        The corners text a drag writes.
    get_corners : callable
        ``get_corners() -> (4, 2)`` the corners as drawn now.
    radius_px : float
        How near (screen pixels) a press must be to pick a corner.

    Returns
    -------
    dict of str to callable
        The handlers by event name (``button_press_event``, ``motion_notify_event``,
        ``button_release_event``); tests call them with synthetic
        ``matplotlib.backend_bases.MouseEvent`` objects, or go through
        ``fig.canvas.callbacks.process``.
    """
    grabbed: dict[str, Any] = {"index": None}

    def on_press(event) -> None:
        if event.inaxes is not ax or event.button != 1 or event.xdata is None:
            return
        screen = ax.transData.transform(get_corners())
        d = np.hypot(screen[:, 0] - event.x, screen[:, 1] - event.y)
        k = int(np.argmin(d))
        grabbed["index"] = k if d[k] <= radius_px else None

    def on_move(event) -> None:
        k = grabbed["index"]
        if k is None or event.inaxes is not ax or event.xdata is None:
            return
        pts = get_corners().copy()
        pts[k] = event.xdata, event.ydata
        control.value = format_corners(pts)

    def on_release(_event) -> None:
        grabbed["index"] = None

    handlers = {
        "button_press_event": on_press,
        "motion_notify_event": on_move,
        "button_release_event": on_release,
    }
    for name, fn in handlers.items():
        view.fig.canvas.mpl_connect(name, fn)
    return handlers
