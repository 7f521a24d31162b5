"""The browser-side drawing path: demos whose per-move work is geometry, drawn on a <canvas>.

Under ipympl every slider move is a round trip: the browser sends the value to the kernel, the
kernel draws with matplotlib and sends a PNG back, the browser decodes and paints it (82-207 ms
measured in JupyterLab, issue 31). Here the kernel sends the *scene* once (the static part of the
figure as a PNG, each panel's data-to-pixel map, colours and sizes) and links each slider to a
synced trait of an anywidget canvas *in the browser* (``ipywidgets.jslink``). A keydown moves the
slider, the link sets the trait, and the browser computes the moving artists with
``geometry.js`` and draws them: nothing waits for the kernel.

Python stays the source of truth. Every function of ``geometry.js`` has a numpy twin in camlab
(named in its comment) and ``tests/test_browser_geometry_parity.py`` runs both under node on
random inputs. The matplotlib figure is still built and updated by the demo's ``update``: it is
the static PNG the website shows, what ``demo.pixels()`` returns headless, and what the headless
tests sweep. Without a kernel (tests, benchmarks) a :class:`BrowserView` is a plain
:class:`~camlab.widgets._base.FigureView` in the "agg" mode.

Set ``CAMLAB_BROWSER_DRAWING=0`` to draw such demos the old way (the kernel path), e.g. to
compare latencies.
"""

from __future__ import annotations

import base64
import io
import os
from collections.abc import Callable, Mapping, Sequence
from importlib import resources
from typing import Any

import anywidget
import ipywidgets as W
import numpy as np
import traitlets
from matplotlib.backend_bases import MouseButton, MouseEvent
from matplotlib.colors import to_hex
from matplotlib.font_manager import weight_dict

from .._base import Demo, FigureView, display_mode

__all__ = [
    "BrowserView",
    "axes_box",
    "browser_drawing",
    "canvas_class",
    "canvas_height",
    "esm_source",
    "line_style",
    "marker_style",
    "text_lines",
    "text_style",
    "to_canvas_pixels",
]

MODULES = (
    "geometry.js",
    "view3d.js",
    "drawing.js",
    "stack_check.js",
    "similar_triangles.js",
    "three_cameras.js",
    "dolly_zoom.js",
    "projective_plane.js",
    "epipolar.js",
    "homography.js",
    "hierarchy.js",
    "forward_inverse.js",
    "textured.js",
    "pinhole.js",
    "corners.js",
    "drag.js",
    "projective_camera.js",
    "widget.js",
)
"""The ES modules, in dependency order, joined into the one module anywidget loads."""


def esm_source() -> str:
    """The ES module the canvas runs: :data:`MODULES` joined, their imports of one another dropped.

    anywidget loads a single module from a string, so the files (kept apart for the node parity
    tests, which import ``geometry.js`` alone) are concatenated; nothing is built or fetched.

    Returns
    -------
    str
        The module's JavaScript.
    """
    here = resources.files(__name__)
    parts = [(here / name).read_text(encoding="utf-8") for name in MODULES]
    return "\n".join(
        line for part in parts for line in part.splitlines() if not line.startswith("import ")
    )


class BrowserCanvas(anywidget.AnyWidget):
    """A <canvas> that draws a scene in the browser (``drawing.js``); subclassed per demo by :func:`canvas_class`."""

    _esm = esm_source()
    scene = traitlets.Dict().tag(sync=True)
    alt = traitlets.Unicode("").tag(sync=True)


def canvas_class(
    params: Sequence[str],
    choices: Sequence[str] = (),
    texts: Sequence[str] = (),
    flags: Sequence[str] = (),
) -> type[BrowserCanvas]:
    """A :class:`BrowserCanvas` with one synced trait per parameter the browser redraws on.

    Parameters
    ----------
    params : sequence of str
        The control names whose values the browser needs (each is linked to its control): a float
        trait each, for a slider.
    choices : sequence of str
        Those among ``params`` whose control is a choice (toggle buttons, a dropdown): an integer
        trait each, linked to the control's ``index`` (its ``value`` is not synced to the browser).
    texts : sequence of str
        Those among ``params`` whose control is a text box: a string trait each.
    flags : sequence of str
        Those among ``params`` whose control is a checkbox: a boolean trait each.

    Returns
    -------
    type
        The canvas class.
    """

    def trait(name: str) -> traitlets.TraitType:
        if name in texts:
            return traitlets.Unicode("")
        if name in flags:
            return traitlets.Bool(False)
        return traitlets.Int(0) if name in choices else traitlets.Float(0.0)

    traits = {name: trait(name).tag(sync=True) for name in params}
    return type("BrowserCanvas_" + "_".join(params), (BrowserCanvas,), traits)


def browser_drawing(mode: str) -> bool:
    """True when a demo in display ``mode`` is drawn in the browser (a kernel, and not switched off).

    Parameters
    ----------
    mode : str
        :func:`~camlab.widgets._base.display_mode`'s answer.

    Returns
    -------
    bool
        True in a kernel ("ipympl" or "png") unless ``CAMLAB_BROWSER_DRAWING=0``.
    """
    return mode in ("ipympl", "png") and os.environ.get("CAMLAB_BROWSER_DRAWING", "1") != "0"


def canvas_height(fig: Any) -> int:
    """The height, in pixels, that matplotlib's Agg canvas flips y about: the figure's, rounded down.

    Agg draws into a buffer of ``int(height)`` rows and maps display y to row ``int(height) - y``;
    a figure whose height ends in half a pixel (3.35 in at 90 dpi: 301.5 px) would otherwise be
    drawn half a pixel low in the browser. A height within 1e-8 px below a whole number (4.6 in at
    90 dpi: 413.99999999999994 px) is rounded up, as matplotlib sizes its buffer.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.

    Returns
    -------
    int
        The rows of the figure's Agg buffer (and of the static background).
    """
    return int(fig.canvas.get_width_height(physical=True)[1])


def to_canvas_pixels(ax: Any) -> list[list[float]]:
    """The 3x3 map from ``ax``'s data coordinates to canvas pixels (u right, v down, origin top left).

    matplotlib's display coordinates run up from the bottom of the figure; a canvas runs down
    from its top, so v = height - y. Only linear axes have such a map.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes with linear scales, after the figure's layout is fixed.

    Returns
    -------
    list of 3 lists of 3 floats
        The map, rows, as JSON for the scene.
    """
    height = canvas_height(ax.figure)
    flip = np.array([[1.0, 0.0, 0.0], [0.0, -1.0, height], [0.0, 0.0, 1.0]])
    return (flip @ ax.transData.get_affine().get_matrix()).tolist()


def axes_box(ax: Any) -> dict:
    """The axes' box in canvas pixels (what matplotlib clips its lines and markers to).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes, after the figure's layout is fixed.

    Returns
    -------
    dict
        ``left``, ``right``, ``top`` and ``bottom``, px from the canvas's top left.
    """
    box = ax.get_window_extent()
    height = canvas_height(ax.figure)
    return dict(
        left=float(box.x0),
        right=float(box.x1),
        top=float(height - box.y1),
        bottom=float(height - box.y0),
    )


BACKGROUND_SCALE = 2
"""The static background is sent at twice the figure's pixels, sharp on screens of device pixel ratio up to 2."""


def _background_png(view: FigureView, scale: int = BACKGROUND_SCALE) -> str:
    """The figure without its animated artists, at ``scale`` times its pixels, as a PNG data URL.

    The Agg canvas is drawn again afterwards (printing at another dpi leaves it at that size), which
    also captures the blitting background at the figure's own size.
    """
    shown = [a for a in view._animated if a.get_visible()]  # noqa: SLF001 - the view's own artists
    for artist in shown:
        artist.set_visible(False)
    buf = io.BytesIO()
    try:
        view.fig.savefig(buf, format="png", dpi=view.fig.dpi * scale)
    finally:
        for artist in shown:
            artist.set_visible(True)
        view.fig.canvas.draw()
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii")


def _png(rgba: np.ndarray) -> str:
    """An RGBA image as a PNG data URL, compressed little (sent while a 3-D axes turns)."""
    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(rgba).save(buf, format="png", compress_level=1)
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii")


def _option_values(control: Any) -> list:
    """A choice control's option values, in order (an option may be a (label, value) pair)."""
    return [o[1] if isinstance(o, tuple) else o for o in control.options]


class BrowserView(FigureView):
    """A :class:`FigureView` whose live picture is drawn in the browser when a kernel shows it.

    The matplotlib figure is always an Agg figure, updated as in any demo; in a kernel the widget
    shown is a :class:`BrowserCanvas` instead of the figure, and the figure is drawn only when
    asked (:meth:`pixels`, the static PNG). Headless (no kernel), or with browser drawing switched
    off (:func:`browser_drawing`), it is a plain FigureView in the display mode. ``params`` names
    the controls the browser redraws on; ``choices``, those of them that are choices (buttons);
    ``texts``, those that are text boxes; ``flags``, those that are checkboxes.
    """

    def __init__(
        self,
        params: Sequence[str],
        figsize: tuple[float, float] = (8, 4),
        mode: str | None = None,
        dpi: float = 90,
        choices: Sequence[str] = (),
        texts: Sequence[str] = (),
        flags: Sequence[str] = (),
    ):
        wanted = mode or display_mode()
        browser = browser_drawing(wanted)
        # Drawn in the browser, the figure stays an Agg figure; switched off, the kernel path as ever.
        super().__init__(figsize, mode="agg" if browser else wanted, dpi=dpi)
        self.browser = browser
        self.params = tuple(params)
        self.choices = tuple(choices)  # the parameters whose controls are choices (buttons)
        self.texts = tuple(texts)  # the parameters whose controls are text boxes
        self.flags = tuple(flags)  # the parameters whose controls are checkboxes
        self._stale = False
        self.canvas: BrowserCanvas | None = None
        self.links: list[
            W.Widget
        ] = []  # slider -> canvas trait, in the browser (ipywidgets.jslink)
        if self.browser:
            self.canvas = canvas_class(self.params, self.choices, self.texts, self.flags)()
            self.canvas.layout = W.Layout(max_width="100%")
            self.widget = self.canvas

    def refresh(self) -> None:
        """Keep the figure for :meth:`pixels`; in the browser path the canvas draws itself."""
        if self.browser and self._background is not None:
            self._stale = True  # the Agg picture is drawn when someone asks for it
            return
        super().refresh()

    def pixels(self) -> np.ndarray:
        """The figure at the current settings, as an (H, W, 4) uint8 array (the numpy/matplotlib twin)."""
        if self._stale:
            super().refresh()
            self._stale = False
        return super().pixels()

    def publish(
        self, demo: Demo, scene: Mapping[str, Any] | Callable[[], Mapping[str, Any]]
    ) -> None:
        """Send the scene once and link each parameter's slider to the canvas, in the browser.

        Parameters
        ----------
        demo : Demo
            The built demo (its first update has drawn the figure, so the layout is fixed).
        scene : mapping or callable
            What the scene's drawer in ``drawing.js`` needs; ``kind``, ``params``, the size and
            the background are added here. A callable giving it, for a figure with 3-D axes: a
            drag on such axes in the browser turns them in the kernel (:meth:`_turn`), and the
            scene is built again.
        """
        if self.canvas is None:
            return
        self.canvas.scene = self._scene(demo, scene)
        for name in self.params:
            control = demo.controls[name]
            trait = "index" if name in self.choices else "value"  # a choice syncs its index only
            value = getattr(control, trait)
            kept = self.choices + self.texts + self.flags  # the rest are sliders' numbers
            setattr(self.canvas, name, value if name in kept else float(value))
            self.links.append(W.jslink((control, trait), (self.canvas, name)))
        self.canvas.alt = demo.alt_text

        def on_change(_change: Any = None) -> None:
            self.canvas.alt = demo.alt_text

        for control in demo.controls.values():
            control.observe(on_change, names="value")
        if callable(scene):
            self.canvas.on_msg(lambda _canvas, content, _buffers: self._turn(demo, scene, content))

    def _scene(
        self,
        demo: Demo,
        scene: Mapping[str, Any] | Callable[[], Mapping[str, Any]],
        background: str | None = None,
    ) -> dict:
        """The scene with what every drawer needs: the kind, the parameters, the size, the background.

        ``background``: a PNG data URL of the figure at its own size, without its moving artists
        (a 3-D axes being turned); None draws it at :data:`BACKGROUND_SCALE`.
        """
        fig = self.fig
        width, height = fig.canvas.get_width_height(physical=True)  # Agg's buffer
        scale = 1 if background else BACKGROUND_SCALE
        background = background or _background_png(self)  # drawn: a 3-D projection is current
        turn = [axes_box(ax) for ax in fig.axes if ax.name == "3d"] if callable(scene) else []
        return dict(
            scene() if callable(scene) else scene,
            kind=demo.name,
            params=list(self.params),
            width=width,
            height=height,
            pxPerPoint=fig.dpi / 72.0,
            background=background,
            backgroundScale=scale,
            # a choice's options by index: widget.js gives the drawer the chosen option itself
            choices={name: _option_values(demo.controls[name]) for name in self.choices},
            turn=turn,  # the 3-D axes' boxes: a drag there is sent to the kernel (widget.js)
        )

    def _turn(self, demo: Demo, scene: Callable[[], Mapping[str, Any]], content: Any) -> None:
        """A press, move or release on a 3-D axes in the browser, handed to matplotlib as ipympl would.

        mplot3d turns (left button), pans (middle) or zooms (right) the axes and draws the
        figure. While the button is held the scene is sent again with that draw as its
        background (the moving artists hidden for it: a third of the time of a sharp one); the
        release sends it sharp. The browser sends its next message once this one is answered
        (``{"turned": True}``).
        """
        names = {
            "pointerdown": "button_press_event",
            "pointermove": "motion_notify_event",
            "pointerup": "button_release_event",
        }
        name = names.get(content.get("type")) if isinstance(content, Mapping) else None
        if name is None:
            return
        space = [ax for ax in self.fig.axes if ax.name == "3d"]

        def view() -> list:
            return [(ax.elev, ax.azim, ax.roll, *ax.get_w_lims()) for ax in space]

        before, canvas = view(), self.fig.canvas
        x, y = float(content["u"]), canvas_height(self.fig) - float(content["v"])
        button = None if name == "motion_notify_event" else MouseButton(int(content["button"]))
        shown = [a for a in self._animated if a.get_visible()]
        for artist in shown:
            artist.set_visible(False)  # mplot3d's draw is then the background
        try:
            try:
                canvas.callbacks.process(name, MouseEvent(name, canvas, x, y, button=button))
                turned, quick = view() != before, None
                if turned and name == "motion_notify_event":
                    if self.fig.stale:
                        canvas.draw()
                    quick = _png(np.asarray(canvas.buffer_rgba()))
            finally:
                for artist in shown:
                    artist.set_visible(True)
            blurred = self.canvas.scene.get("backgroundScale") == 1
            if turned or (name == "button_release_event" and blurred):
                self._stale = True  # pixels() draws the figure at its new view
                self.canvas.scene = self._scene(demo, scene, quick)
        finally:
            self.canvas.send({"turned": True})  # even after an error: the browser sends on


def line_style(line: Any, px_per_point: float, **extra: Any) -> dict:
    """A matplotlib line's colour, width and dashes in canvas pixels (for :func:`drawing.js` polyline).

    Parameters
    ----------
    line : matplotlib.lines.Line2D
        The artist whose look the browser copies.
    px_per_point : float
        Figure dpi / 72.
    **extra
        Added to the style (``halo``, ``haloWidth``, ``closed`` ...).

    Returns
    -------
    dict
        ``color``, ``width`` (px), ``dash`` (px, [] for solid), ``join``, ``cap`` and ``snap``
        (matplotlib snaps a path of horizontal and vertical segments to the pixel grid unless the
        line says not to).
    """
    offset, dashes = line._dash_pattern  # noqa: SLF001 - the pattern matplotlib draws, already scaled by width
    join = {"round": "round", "miter": "miter", "bevel": "bevel"}
    caps = {"butt": "butt", "round": "round", "projecting": "square"}
    solid = dashes is None
    return dict(
        color=to_hex(line.get_color()),
        width=line.get_linewidth() * px_per_point,
        dash=[] if solid else [d * px_per_point for d in dashes],
        join=join[(line.get_solid_joinstyle() if solid else line.get_dash_joinstyle())],
        cap=caps[(line.get_solid_capstyle() if solid else line.get_dash_capstyle())],
        snap=line.get_snap() is not False,
        **extra,
    )


def marker_style(line: Any, px_per_point: float) -> dict:
    """A matplotlib marker's look in canvas pixels (for ``drawing.js``'s ``dot``).

    Parameters
    ----------
    line : matplotlib.lines.Line2D
        A line drawn with a round marker ("o").
    px_per_point : float
        Figure dpi / 72.

    Returns
    -------
    dict
        ``color``, ``edge``, ``size`` (the marker's diameter, px) and ``edgeWidth`` (px).
    """
    return dict(
        color=to_hex(line.get_markerfacecolor()),
        edge=to_hex(line.get_markeredgecolor()),
        size=line.get_markersize() * px_per_point,
        edgeWidth=line.get_markeredgewidth() * px_per_point,
    )


def text_style(text: Any, **extra: Any) -> dict:
    """A matplotlib text's font and colour, and its line box as matplotlib measures it, in canvas pixels.

    matplotlib aligns a line of text by the ink box of "lp" (its ascent above the baseline and
    descent below): ``drawing.js``'s ``label`` places a baseline from these two numbers, so the
    browser aligns as matplotlib does whatever the browser's own font metrics.

    Parameters
    ----------
    text : matplotlib.text.Text
        The artist whose look the browser copies (after a draw, so it has a renderer).
    **extra
        Added to the style (``box``: a background colour, ``pad``: its padding, px).

    Returns
    -------
    dict
        ``font`` (CSS), ``color``, ``ascent`` and ``descent`` (px).
    """
    fig = text.figure
    renderer = fig.canvas.get_renderer()
    _w, h, d = renderer.get_text_width_height_descent("lp", text.get_fontproperties(), ismath=False)
    px = text.get_fontsize() * fig.dpi / 72.0
    name = text.get_fontproperties().get_name()  # the font matplotlib found: DejaVu Sans (Mono)
    generic = "monospace" if "Mono" in name else "sans-serif"
    weight = text.get_fontweight()  # a number or a name ("bold"): CSS takes the number
    weight = weight if isinstance(weight, int) else weight_dict[weight]
    return dict(
        font=f"{weight} {px:.3f}px '{name}', {generic}",
        color=to_hex(text.get_color()),
        ascent=float(h - d),
        descent=float(d),
        **extra,
    )


def text_lines(text: Any) -> dict:
    """Where matplotlib puts each line of a text, in canvas pixels: its anchor x and each baseline.

    For a text whose anchor and number of lines stay put while its words change (a title).

    Parameters
    ----------
    text : matplotlib.text.Text
        The artist, after a draw.

    Returns
    -------
    dict
        ``x`` (the anchor, px from the left), ``baselines`` (px from the top, one per line) and
        ``align`` (the canvas's textAlign: left, center or right).
    """
    fig = text.figure
    _bbox, info, _d = text._get_layout(fig.canvas.get_renderer())  # noqa: SLF001 - matplotlib's own line layout
    x, y = text.get_transform().transform(text.get_unitless_position())
    height = canvas_height(fig)
    # each line's offset from the anchor: (line, wad, (dx, dy)) since matplotlib 3.10,
    # (line, (w, h), dx, dy) in 3.9 (the oldest the course supports)
    offsets = [row[2][1] if len(row) == 3 else row[3] for row in info]
    return dict(
        x=float(x),
        baselines=[float(height - (y + dy)) for dy in offsets],
        align=text.get_horizontalalignment(),
    )
