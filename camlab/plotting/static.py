"""Static pictures of live figures: what a notebook keeps for readers without a kernel.

A live figure (an ipympl canvas, or a camlab demo around one) is a widget. JupyterLab
draws it from the running kernel, but a saved notebook read on GitHub, nbviewer, in
nbconvert's HTML or PDF, or on the course website has no kernel. So whenever a live
figure is displayed, its display bundle carries one PNG of the figure as it is at that
moment next to the widget view, and the output metadata carries alt text::

    data     = {"application/vnd.jupyter.widget-view+json": {...},
                "image/png": <base64>, "text/plain": <alt text>}
    metadata = {"image/png": {"alt": <alt text>, "width": w, "height": h}}

A front end shows one entry of a bundle. JupyterLab, Notebook 7 and Voila rank the
widget view first and show only the live figure; static renderers, which cannot run a
widget, show the PNG. The PNG is rendered once per display, never per slider event.

Alt text says what the figure shows: for a demo, its description and the values of its
controls (:func:`demo_alt_text`); for a plain figure, the text a lesson gave with
:func:`alt_text`, or else a description built from the titles, axis labels and legend
entries (:func:`describe_figure`).
"""

from __future__ import annotations

import base64
import io
import struct
import weakref
from collections.abc import Mapping
from typing import Any, NamedTuple

from matplotlib.figure import Figure

WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"
OUTPUT_WIDTH_PX = 960
"""The widest a live figure (or a demo) may be: JupyterLab's output area is 968 px wide in a
1400 px window with the file browser open (measured in headless Chromium)."""
CANVAS_FRAME_PX = 8
"""What ipympl's canvas widget adds to its figure's width (measured: 1008 px for a 1000 px figure)."""
_ALT: weakref.WeakKeyDictionary[Figure, str] = weakref.WeakKeyDictionary()


def alt_text(fig: Figure, text: str) -> Figure:
    """Give a plain figure the alt text its static picture carries; returns ``fig``.

    Write what a reader should see, e.g. ``"Image height falls as 1/Z; a longer focal
    length scales every curve up"``, not "Figure 1".

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure (held weakly: the text goes when the figure does).
    text : str
        A sentence describing the figure; runs of whitespace become one space.

    Returns
    -------
    matplotlib.figure.Figure
        ``fig`` itself, so ``alt_text(fig, "...")`` can end a cell.

    Raises
    ------
    ValueError
        If ``text`` is empty or only whitespace.
    """
    text = " ".join(str(text).split())
    if not text:
        raise ValueError("alt_text: expected a sentence describing the figure, got an empty string")
    _ALT[fig] = text
    return fig


def _quoted(texts: list[str]) -> str:
    return ", ".join(f"'{t}'" for t in texts)


def _describe_axes(ax: Any) -> str:
    title = " ".join(
        " ".join(t.split())
        for t in (ax.get_title("left"), ax.get_title(), ax.get_title("right"))
        if t
    )
    title = title.replace(
        "$", ""
    )  # mathtext's dollars mean nothing read aloud: "$c_x$ = 200" reads "c_x = 200"
    kind = "3-D view" if ax.name == "3d" else ("image" if ax.images and not ax.lines else "plot")
    words = [f"{kind} '{title}'" if title else kind]
    z_label = ax.get_zlabel() if ax.name == "3d" else ""  # a 3-D view has a third axis to name
    labels = [lab for lab in (ax.get_xlabel(), ax.get_ylabel(), z_label) if lab]
    if (
        not ax.axison
    ):  # axes switched off (set_axis_off): their labels are not drawn, so not described (a figure
        labels = []  # may draw axes of its own, as arrows: saying "no axes" would then be false)
    if labels:
        words.append("axes " + _quoted(labels))
    legend = ax.get_legend()
    if legend is not None:
        entries = [t.get_text() for t in legend.get_texts() if t.get_text()]
        if entries:
            words.append("legend " + _quoted(entries))
    return ", ".join(words)


def describe_figure(fig: Figure) -> str:
    """Alt text for a figure: the lesson's own (:func:`alt_text`) or one built from its text.

    The built description lists each panel's title, axis labels and legend entries,
    which in camlab's figures name what is drawn.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure to describe (hidden axes and colour bars are left out).

    Returns
    -------
    str
        One sentence, e.g. ``"Figure with 2 panels: plot 'a', axes 'u (px)', 'v (px)'; image 'b'."``.
    """
    if fig in _ALT:
        return _ALT[fig]
    panels = [ax for ax in fig.axes if ax.get_visible() and ax.get_label() != "<colorbar>"]
    parts = [_describe_axes(ax) for ax in panels]
    suptitle = fig._suptitle.get_text() if fig._suptitle is not None else ""
    head = f"Figure '{suptitle}'" if suptitle else "Figure"
    if not parts:
        return f"{head} without axes"
    count = f" with {len(parts)} panels" if len(parts) > 1 else ""
    return f"{head}{count}: " + "; ".join(parts) + "."


def _format_value(control: Any) -> str:
    index = getattr(control, "index", None)  # selection widgets show an option's label
    if isinstance(index, int):
        option = tuple(control.options)[index]
        return str(option[0] if isinstance(option, tuple) and len(option) == 2 else option)
    value = control.value
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, (tuple, list)):
        return "(" + ", ".join(f"{v:g}" if isinstance(v, float) else str(v) for v in value) + ")"
    return str(value)


def demo_alt_text(description: str, controls: Mapping[str, Any], fig: Figure | None = None) -> str:
    """Alt text for a demo: what it shows, its panels, its readout and the settings it was drawn at.

    The readout is the demo figure's texts with gid ``'readout'``, joined in order.

    Parameters
    ----------
    description : str
        What the demo shows, a sentence (a final full stop is added if missing).
    controls : mapping of str to ipywidgets.Widget
        The demo's controls by name; each is described by its ``description`` (else its name)
        and its value (a selection's label, "on"/"off" for a checkbox).
    fig : matplotlib.figure.Figure or None
        The demo's figure, for its suptitle, panel titles and readout; None leaves them out.

    Returns
    -------
    str
        The alt text.
    """
    text = " ".join(description.split())
    if text and text[-1] not in ".!?":
        text += "."
    if fig is not None:
        heading = " ".join(fig.get_suptitle().split())  # the figure's own title
        if heading:
            text += f" Above the panels: '{heading}'."
        titles = [
            " ".join(ax.get_title().split())
            for ax in fig.axes
            if ax.get_visible() and ax.get_title()
        ]
        if titles:
            text += " Panels: " + _quoted(titles) + "."
        # Numbers a demo shows in its figure: texts with gid 'readout', read in order (a label, then its numbers).
        readout = " ".join(
            "".join(
                t.get_text()
                for t in [*fig.texts, *(t for ax in fig.axes for t in ax.texts)]
                if t.get_gid() == "readout"
            ).split()
        )
        if readout:
            text += f" Readout: '{readout}'."
    settings = [
        f"{(c.description or name).strip().rstrip('=:').strip()} = {_format_value(c)}"
        for name, c in controls.items()
    ]
    if settings:
        text += " Shown at " + "; ".join(settings) + "."
    return text.strip()


PNG_COMPRESS_LEVEL = 3
"""zlib level of the PNGs :func:`figure_png` writes (lossless at every level; see there)."""
_PIL_PNG = {"compress_level": PNG_COMPRESS_LEVEL}


def figure_png(fig: Figure, dpi: float | None = None) -> bytes:
    """The figure rendered to PNG, at its own size and dpi unless ``dpi`` says otherwise.

    Drawn once. ``Figure.savefig`` draws a figure that has a layout engine (constrained
    layout) twice: a dry run that lays it out, then the real draw. Every plot a lesson
    displays renders one PNG, and in the thirteen lessons those dry runs took a quarter of
    all the run time (cProfile of every lesson: 77 of 313 s). An Agg canvas, as ipympl's is,
    prints its own draw, and that draw runs the layout engine itself: the same pixels
    (tested against ``savefig``). It prints as ``savefig`` does, with the canvas saying it
    is saving, so that animated artists (a demo's moving parts) are drawn too.

    Other canvases, another dpi than the figure's, and a HiDPI screen's figure (drawn at a
    multiple of its dpi) go through ``savefig``.

    Compressed at zlib level :data:`PNG_COMPRESS_LEVEL`, not Pillow's default 6: the same
    pixels, half the encoding time (the 224 PNGs of the thirteen executed lessons: 9.4 s at
    level 6, 4.8 s at level 3) and 3 % fewer bytes (30.7 against 31.6 MiB).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure to render.
    dpi : float or None
        Dots per inch of the PNG; None (default) is the figure's own.

    Returns
    -------
    bytes
        The PNG file's bytes.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    buf = io.BytesIO()
    dpi = fig.dpi if dpi is None else dpi
    canvas = fig.canvas
    one_pass = (
        isinstance(canvas, FigureCanvasAgg)
        and dpi == fig.dpi == getattr(fig, "_original_dpi", fig.dpi)
        and not canvas.is_saving()
    )
    if not one_pass:
        fig.savefig(buf, format="png", dpi=dpi, pil_kwargs=_PIL_PNG)
        return buf.getvalue()
    canvas._is_saving = True  # what savefig sets: Axes.draw leaves animated artists out otherwise
    try:
        canvas.print_png(buf, pil_kwargs=_PIL_PNG)  # Agg's draw, then the PNG of its buffer
    finally:
        canvas._is_saving = False
    return buf.getvalue()


class DisplayBundle(NamedTuple):
    """The ``(data, metadata)`` pair IPython's ``_repr_mimebundle_`` returns.

    Attributes
    ----------
    data : dict
        Mime type -> content (the widget's entries, ``image/png`` in base64, ``text/plain`` the alt text).
    metadata : dict
        ``{"image/png": {"alt", "width", "height"}}``.
    """

    data: dict
    metadata: dict


def static_bundle(
    data: Mapping[str, Any], fig: Figure, alt: str, png: bytes | None = None
) -> DisplayBundle:
    """A widget's display bundle plus a PNG of ``fig`` and its alt text (module docstring).

    ``png`` reuses an image already rendered (the png display mode keeps one); otherwise
    the figure is rendered once here. ipympl's own ``text/html`` copy of the picture
    (an ``<img>`` without alt text) is dropped, so static renderers use the PNG entry.

    Parameters
    ----------
    data : mapping
        The widget's own bundle (mime type -> content).
    fig : matplotlib.figure.Figure
        The figure the PNG shows.
    alt : str
        The alt text (:func:`describe_figure`, :func:`demo_alt_text`).
    png : bytes or None
        A PNG of ``fig`` already rendered; None renders one (:func:`figure_png`).

    Returns
    -------
    DisplayBundle
        ``data`` with ``image/png`` (base64) and ``text/plain`` (the alt text), and ``metadata``
        with the PNG's alt text and its size in pixels (read from its header).
    """
    png = png if png is not None else figure_png(fig)
    out = {k: v for k, v in data.items() if k != "text/html"}
    out["image/png"] = base64.b64encode(png).decode("ascii")
    out["text/plain"] = alt
    width, height = struct.unpack(
        ">II", png[16:24]
    )  # the PNG's own size (IHDR), which matplotlib < 3.10 may round
    metadata = {"image/png": {"alt": alt, "width": width, "height": height}}
    return DisplayBundle(out, metadata)


def fit_output_width(fig: Figure) -> Figure:
    """Lower ``fig``'s dpi so that its canvas fits :data:`OUTPUT_WIDTH_PX`; returns ``fig``.

    An ipympl canvas keeps its figure's size in pixels, so a figure 10 inches wide at 100 dpi
    ran 40 px past the output area with the file browser open. Drawn at a lower dpi it keeps
    its layout and scales as a whole, as an inline PNG scales down to fit.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure; its dpi is changed in place when it is too wide, else left alone.

    Returns
    -------
    matplotlib.figure.Figure
        ``fig`` itself.
    """
    widest = OUTPUT_WIDTH_PX - CANVAS_FRAME_PX
    dpi = getattr(
        fig, "_original_dpi", fig.dpi
    )  # the dpi asked for; a HiDPI screen draws at a multiple of it
    if fig.get_figwidth() * dpi > widest:
        ratio = fig.dpi / dpi
        # matplotlib keeps the asked dpi apart: savefig(dpi="figure") and a screen's pixel ratio start from it
        fig._original_dpi = widest / fig.get_figwidth()
        fig.set_dpi(fig._original_dpi * ratio)
    return fig


def _canvas_bundle(canvas: Any) -> tuple[dict, dict]:
    """Display bundle of an ipympl canvas (a plain figure under ``%matplotlib widget``).

    The canvas loses ipympl's header, a title bar reading "Figure N" that says nothing
    (the figure's own titles do), as the demos' canvases do (``widgets._base.FigureView``).
    A figure wider than the output area is fitted to it (:func:`fit_output_width`).
    """
    canvas.header_visible = False
    fig = fit_output_width(canvas.figure)
    png = figure_png(
        fig, dpi=getattr(fig, "_original_dpi", fig.dpi)
    )  # ipympl's picture: dpi="figure"
    fig.savefig = _saving_once(fig.savefig, png)
    try:
        data = (
            canvas._repr_mimebundle_()
        )  # ipympl registers the view and saves the figure: it gets `png`
    finally:
        del fig.savefig  # the instance attribute goes; Figure.savefig is back
    return static_bundle(data, fig, describe_figure(fig), png)


def _saving_once(savefig: Any, png: bytes) -> Any:
    """``savefig`` that writes ``png`` for ipympl's call (a PNG at the figure's dpi into a buffer).

    ipympl's display bundle saves the figure with ``savefig``, which draws a laid-out figure
    twice; :func:`figure_png` drew it once. Any other call is passed on to ``savefig``.
    """

    def savefig_once(fname: Any, *args: Any, **kwargs: Any) -> None:
        if not args and kwargs == {"format": "png", "dpi": "figure"} and hasattr(fname, "write"):
            fname.write(png)
            return None
        return savefig(fname, *args, **kwargs)

    return savefig_once


def install_canvas_formatter() -> bool:
    """In an IPython kernel, give every displayed ipympl canvas alt text (module docstring).

    Safe to call more than once.

    Returns
    -------
    bool
        Whether a kernel was found (outside IPython nothing is installed).
    """
    try:
        from IPython import get_ipython
    except ImportError:  # pragma: no cover - IPython comes with ipywidgets
        return False
    shell = get_ipython()
    if shell is None:
        return False
    formatter = shell.display_formatter.mimebundle_formatter
    formatter.for_type_by_name("ipympl.backend_nbagg", "Canvas", _canvas_bundle)
    return True
