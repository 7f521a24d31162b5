"""The widget pattern every camlab demo follows.

A demo builds its controls and one figure once. Each control change calls ``update``,
which runs tested pure functions from camlab, moves existing artists (``set_data``,
``set_array``...) and records what it computed in ``state``; the figure is then
redrawn in place. Nothing is rebuilt per event, so sliders stay fast.

The figure is shown according to the matplotlib backend:

* ``ipympl`` (``%matplotlib widget``, what the lessons use): the figure's canvas is
  itself a widget, redrawn with ``draw_idle`` and able to take mouse events;
* ``png`` (any other backend inside a kernel, e.g. inline or Voila without ipympl): the
  figure is rendered to an ``ipywidgets.Image`` after every change;
* ``agg`` (no kernel: tests and benchmarks): the figure is drawn with Agg and nothing
  is sent anywhere.
"""

from __future__ import annotations

import html
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import ipywidgets as W
import matplotlib
import numpy as np
from matplotlib.figure import Figure
from matplotlib.image import AxesImage
from matplotlib.spines import Spine

from ..plotting.static import (
    CANVAS_FRAME_PX,
    OUTPUT_WIDTH_PX,
    demo_alt_text,
    figure_png,
    static_bundle,
)
from ._transport import halo_in_two_passes, show_at_display_resolution, use_fast_png
from .controls import slider as slider  # re-exported: every demo module imports it from here
from .controls import whole_label

MAX_DEMO_WIDTH_PX = OUTPUT_WIDTH_PX
"""The widest a demo may be, its controls or its figure (:data:`camlab.plotting.static.OUTPUT_WIDTH_PX`)."""
PANEL_WIDTH_PX = 300
"""The width of the controls' column (every slider is 300 px wide: :mod:`.controls`)."""


def display_mode() -> str:
    """How figures will show: "ipympl" (live, `%matplotlib widget`), "png" (a kernel without it) or "agg" (headless)."""
    forced = os.environ.get("CAMLAB_FIGURE_MODE")
    if forced:
        return forced
    backend = matplotlib.get_backend().lower()
    if backend == "widget" or "ipympl" in backend:  # `%matplotlib widget` reports "widget"
        return "ipympl"
    try:
        from IPython import get_ipython

        if get_ipython() is not None and getattr(get_ipython(), "kernel", None) is not None:
            return "png"
    except ImportError:  # IPython is always present with ipywidgets, but be safe
        pass
    return "agg"


def _draws_frame(ax: Any) -> bool:
    """True if a full draw of ``ax`` draws its spines (as ``Axes.draw`` decides: visible, axis on, frame on)."""
    return ax is not None and ax.get_visible() and ax.axison and ax.get_frame_on()


class FigureView:
    """One matplotlib figure inside a widget, redrawn in place (see the module docstring).

    Artists that change per event are registered with :meth:`animate`. The static rest of
    the figure (axes, ticks, grids, legends) is drawn once and cached; each refresh restores
    that background and draws only the animated artists on top (blitting). That keeps an
    update to a few milliseconds instead of a full redraw of every tick label.
    """

    def __init__(
        self, figsize: tuple[float, float] = (8, 4), mode: str | None = None, dpi: float = 90
    ):
        widest = (MAX_DEMO_WIDTH_PX - CANVAS_FRAME_PX) / dpi
        if figsize[0] > widest:
            raise ValueError(
                f"FigureView: expected a figure at most {widest:.2f} in wide at {dpi:g} dpi "
                f"({MAX_DEMO_WIDTH_PX} px with the canvas frame, the output area of JupyterLab at 1400 px "
                f"with the file browser open), got figsize {tuple(figsize)}; make it narrower"
            )
        self.mode = mode or display_mode()
        self._animated: list[Any] = []
        self._background = None
        if self.mode == "ipympl":
            import matplotlib.pyplot as plt

            with plt.ioff():  # the demo container displays the canvas, not pyplot
                self.fig = plt.figure(figsize=figsize, dpi=dpi, layout="constrained")
            canvas = self.fig.canvas
            canvas.header_visible = False
            canvas.footer_visible = False
            canvas.toolbar_position = "left"
            canvas.resizable = False
            use_fast_png(canvas)
            self.widget: W.Widget = canvas
        else:
            from matplotlib.backends.backend_agg import FigureCanvasAgg

            self.fig = Figure(figsize=figsize, dpi=dpi, layout="constrained")
            FigureCanvasAgg(self.fig)
            self.widget = W.Image(format="png", layout=W.Layout(max_width="100%"))
        # A full draw (first show, resize, zoom) re-captures the background.
        self.fig.canvas.mpl_connect("draw_event", self._on_full_draw)

    def animate(self, *artists: Any) -> Any:
        """Register artists that updates move; returns them (one artist if one was given).

        Images among them keep their data at the resolution they are shown; haloed lines draw
        their halo as a plain pass (see :mod:`._transport`). Anything static that must show
        *above* an animated artist (a marker on a moving line) must be animated too: the live
        path paints the animated artists over the cached background, in zorder, as a full draw
        does (a legend over an image: ``tests/test_widgets.py`` finds any left static). An
        animated image's frame, its axes' spines, is animated with it before the first full
        draw (:meth:`_frame_images`), so no demo has to remember it.
        """
        for artist in artists:
            if isinstance(artist, AxesImage):
                show_at_display_resolution(artist)
            halo_in_two_passes(artist)
            artist.set_animated(True)
            self._animated.append(artist)
        return artists[0] if len(artists) == 1 else artists

    def _frame_images(self) -> None:
        """Animate the spines of every axes that holds an animated image.

        A full draw paints the spines (zorder 2.5) over the image (zorder 0). Left static, they
        would be in the cached background, and every live frame would paint the image over
        them: the top and left frame lines lost the half inside the axes in every lesson.
        Called before the first full draw; the spines of an axes turned off after
        that are not drawn live either (:meth:`_in_draw_order`).
        """
        animated = {id(a) for a in self._animated}
        for ax in dict.fromkeys(
            a.axes for a in self._animated if isinstance(a, AxesImage) and a.axes is not None
        ):
            self.animate(*(s for s in ax.spines.values() if id(s) not in animated))

    def _on_full_draw(self, _event: Any = None) -> None:
        canvas = self.fig.canvas
        if getattr(canvas, "is_saving", lambda: False)():
            return
        self._background = canvas.copy_from_bbox(self.fig.bbox)
        self._draw_animated()
        if self.fig.get_layout_engine() is not None:
            # Freeze the layout that draw computed: blitting needs the axes to stay put.
            self.fig.set_layout_engine("none")

    def _in_draw_order(self) -> list[Any]:
        """The animated artists in the order a full draw paints them: axes by axes (figure texts last), then zorder.

        Drawing them in registration order would let a fill registered after a line cover it
        live but not in a full redraw (a colour that changes on the first move). The spines of
        an axes that a full draw leaves unframed (``set_axis_off``, ``set_frame_on(False)``) are
        left out, as ``Axes.draw`` leaves them out.
        """
        axes = self.fig.axes
        drawn = [a for a in self._animated if not isinstance(a, Spine) or _draws_frame(a.axes)]
        return sorted(
            drawn,
            key=lambda a: (
                axes.index(a.axes) if getattr(a, "axes", None) in axes else len(axes),
                a.get_zorder(),
            ),
        )

    def _draw_animated(self) -> None:
        for artist in self._in_draw_order():
            if hasattr(artist, "do_3d_projection"):
                # 3-D fills and patches keep the 2-D paths of the last full draw: Axes3D.draw
                # projects them, draw_artist does not, so a moved face would be drawn where it was.
                artist.do_3d_projection()
            self.fig.draw_artist(artist)

    def invalidate(self) -> None:
        """Say that the static part changed (an axis's limits): the next :meth:`refresh` draws it all anew.

        The cached background would show the old limits under the new artists; dropping it makes the
        next refresh a full draw, which caches the new background (its ``draw_event``).
        """
        self._background = None

    def refresh(self) -> None:
        """Show the figure's current artists."""
        if self.mode == "png":
            self.widget.value = figure_png(self.fig)
            return
        canvas = self.fig.canvas
        if self._background is None:
            self._frame_images()
        if self._animated and self._background is not None:
            canvas.restore_region(self._background)
            self._draw_animated()
            if self.mode == "ipympl":
                canvas.blit(self.fig.bbox)
        elif self.mode == "ipympl":
            # A full draw when the browser shows the canvas; its draw_event captures the background.
            canvas.draw_idle()
        else:
            canvas.draw()

    def pixels(self) -> np.ndarray:
        """The figure as currently shown, as an (H, W, 4) uint8 array (for tests)."""
        if self.mode == "png":
            self.fig.canvas.draw()
        return np.asarray(self.fig.canvas.buffer_rgba()).copy()


@dataclass(slots=True)
class Demo:
    """A built demo: its container widget, named controls, figure view and latest state.

    Display it by making it the last expression of a cell. Tests and benchmarks drive
    it with ``demo.set(name=value)`` and read ``demo.state``.
    """

    name: str
    widget: W.Widget
    controls: dict[str, W.ValueWidget]
    view: FigureView
    state: dict[str, Any] = field(default_factory=dict)
    updates: int = 0
    handlers: dict[str, Callable] = field(default_factory=dict)
    """Mouse handlers by matplotlib event name (``"button_press_event"`` ...), for tests to call."""
    problem: str = ""
    """Why the last change could not be drawn (the control and the reason), '' when it was."""

    @property
    def figure(self) -> Figure:
        return self.view.fig

    def set(self, **values: Any) -> None:
        """Set control values as a user would; observers fire and the figure updates."""
        for key, value in values.items():
            if key not in self.controls:
                raise KeyError(
                    f"{self.name}: no control {key!r}; controls are {sorted(self.controls)}"
                )
            self.controls[key].value = value

    @property
    def alt_text(self) -> str:
        """What the figure shows at the current settings (the static picture's alt text)."""
        spec = REGISTRY.get(self.name)
        doc = (spec.builder.__doc__ or "") if spec is not None else ""
        description = doc.strip().split("\n\n")[0] or self.name.replace("_", " ")
        return demo_alt_text(description, self.controls, self.figure)

    def _repr_mimebundle_(self, **kwargs: Any):
        """The live widget, plus one PNG with alt text for readers without a kernel.

        See :mod:`camlab.plotting.static`: JupyterLab shows only the widget view; saved
        HTML, nbviewer and the course website show the PNG.
        """
        png = self.view.widget.value if self.view.mode == "png" and self.view.widget.value else None
        return static_bundle(
            self.widget._repr_mimebundle_(**kwargs), self.figure, self.alt_text, png
        )


def _label(control: W.ValueWidget, key: str) -> str:
    return (control.description or "").strip().rstrip("=:").strip() or key


def _not_a_number(controls: Mapping[str, W.ValueWidget]) -> str:
    """A problem naming the first control holding NaN (float sliders accept it), or ''."""
    for key, control in controls.items():
        value = control.value
        if isinstance(value, (float, np.floating)) and not np.isfinite(value):
            return f"{_label(control, key)} = {value}: not a number the demo can draw; move the slider or type a number"
    return ""


def _show_problem(demo: Demo, line: W.HTML, problem: str) -> None:
    demo.problem = problem
    line.value = (
        f"<b>\u26a0 {html.escape(problem)}</b><br>The figure keeps the last settings that worked."
        if problem
        else ""
    )


def build_demo(
    name: str,
    controls: Mapping[str, W.ValueWidget],
    view: FigureView,
    update: Callable[[dict[str, Any], dict[str, Any]], None],
    *,
    title: str = "",
    extra: Sequence[W.Widget] = (),
    linked: Mapping[str, W.ValueWidget] | None = None,
) -> Demo:
    """Wire controls to ``update(values, state)`` and lay the demo out.

    ``update`` receives every control's current value by name and the demo's state dict
    to fill in; it moves artists but does not draw (the view redraws once afterwards).
    ``linked`` controls only drive another control (the corner sliders of
    :func:`~camlab.widgets.controls.corner_keys` write the corners text): they are shown,
    set and swept like controls but not observed, so each change updates the figure once.

    The controls' column (each control showing its whole label: :func:`.controls.whole_label`)
    sits beside the figure where the output area is wide enough for both, and the figure wraps
    under it where not; so a demo needs only its wider part, at most :data:`MAX_DEMO_WIDTH_PX`
    (a :class:`FigureView` refuses a wider figure).

    A demo never dies: a control holding NaN, or a change that makes ``update`` (or the
    redraw) raise, is reported under the controls naming the control (``Demo.problem``),
    and the figure and ``state`` stay at the last settings that worked. Only the first
    update, at build time, raises: a demo whose defaults fail is a bug.
    """
    state: dict[str, Any] = {}
    demo_controls = dict(controls) | dict(linked or {})
    problem_line = W.HTML()
    panel: list[W.Widget] = []
    if title:
        panel.append(W.HTML(f"<b>{title}</b>"))
    panel += (
        [whole_label(c) for c in demo_controls.values()] + [problem_line] + list(extra)
    )  # the problem under them
    box = W.HBox(
        [
            W.VBox(panel, layout=W.Layout(flex=f"1 1 {PANEL_WIDTH_PX}px", min_width="min-content")),
            view.widget,
        ],
        layout=W.Layout(
            align_items="flex-start", flex_flow="row wrap"
        ),  # the figure goes under the controls if need be
    )
    box.add_class(f"camlab-demo-{name.replace('_', '-')}")
    demo = Demo(name=name, widget=box, controls=demo_controls, view=view, state=state)
    last_good: dict[str, Any] = {}

    def draw(values: dict[str, Any]) -> None:
        trial = dict(state)  # a failing update leaves the demo's state as it was
        update(values, trial)
        view.refresh()
        state.clear()
        state.update(trial)

    def on_change(change: Any = None) -> None:
        values = {k: c.value for k, c in demo_controls.items()}
        if not last_good:  # the defaults: a failure here is a bug, so it raises
            draw(values)
        elif problem := _not_a_number(demo_controls) or try_draw(values, change):
            _show_problem(demo, problem_line, problem)
            return
        last_good.clear()
        last_good.update(values)
        _show_problem(demo, problem_line, "")
        demo.updates += 1

    def try_draw(values: dict[str, Any], change: Any) -> str:
        """'' once drawn; else what went wrong, naming the control, with the artists back at the last good settings."""
        try:
            draw(values)
            return ""
        except Exception as exc:  # noqa: BLE001 - any failure is shown in the demo, never raised into the page
            reason = str(exc) or type(exc).__name__
        try:
            update(last_good, dict(state))  # a failing update may have moved some artists
        except Exception:  # noqa: BLE001 - it worked before; if not now, the problem is shown anyway
            pass
        key = next(
            (k for k, c in demo_controls.items() if change is not None and c is change["owner"]), ""
        )
        return (
            f"{_label(demo_controls[key], key)} = {values[key]!r}: {reason}"
            if key
            else f"these settings: {reason}"
        )

    def on_linked(change: Any) -> None:
        """A linked control drives the figure through another; only its own NaN is reported here."""
        control = change["owner"]
        problem = _not_a_number({k: c for k, c in (linked or {}).items() if c is control})
        if problem or demo.problem.startswith(f"{_label(control, '')} = "):
            _show_problem(demo, problem_line, problem)

    for control in controls.values():
        control.observe(on_change, names="value")
    for control in (linked or {}).values():
        control.observe(on_linked, names="value")
    on_change()
    return demo


@dataclass(frozen=True)
class DemoSpec:
    """A registered demo: how to build it and the control values to sweep it through."""

    name: str
    lesson: str
    builder: Callable[[], Demo]
    sweep: dict[str, Sequence[Any]]


REGISTRY: dict[str, DemoSpec] = {}


def register(lesson: str, sweep: Mapping[str, Sequence[Any]]):
    """Decorator: register a demo builder with the values to sweep each control through.

    Every demo has the same latency target, two frames at 60 Hz as the browser receives it
    (see ``benchmarks/latency.py``).

    The benchmark and the headless widget tests drive every registered demo with its
    sweep, so a new demo is measured and tested as soon as it is registered.
    """

    def deco(builder: Callable[[], Demo]) -> Callable[[], Demo]:
        name = builder.__name__
        if name in REGISTRY and REGISTRY[name].builder.__module__ != builder.__module__:
            raise ValueError(
                f"register: a demo named {name!r} is already registered by {REGISTRY[name].builder.__module__}"
            )
        REGISTRY[name] = DemoSpec(name, lesson, builder, {k: list(v) for k, v in sweep.items()})
        return builder

    return deco
