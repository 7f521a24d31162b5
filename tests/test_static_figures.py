"""Live figures leave a static PNG with alt text in their display bundle (camlab.plotting.static)."""

import base64
import io

import matplotlib.image as mpimg
import numpy as np
import pytest
from matplotlib.figure import Figure

from camlab.plotting import static
from camlab.widgets import all_demos

DEMOS = all_demos()
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"


def _png_pixels(b64: str) -> np.ndarray:
    return (
        (mpimg.imread(io.BytesIO(base64.b64decode(b64)), format="png") * 255)
        .round()
        .astype(np.uint8)
    )


@pytest.mark.parametrize("name", sorted(DEMOS))
def test_demo_bundle_has_widget_png_and_alt_text(name):
    spec = DEMOS[name]
    demo = spec.builder()
    data, metadata = demo._repr_mimebundle_()
    assert WIDGET_VIEW in data and data[WIDGET_VIEW]["model_id"] == demo.widget.model_id
    assert "text/html" not in data
    png = _png_pixels(data["image/png"])
    shown = demo.view.pixels()
    # matplotlib < 3.10 may round the saved height one pixel differently from the canvas
    assert np.abs(np.subtract(png.shape[:2], shown.shape[:2])).max() <= 1, (
        f"{name}: the PNG is not the figure's size"
    )
    h, w = np.minimum(png.shape[:2], shown.shape[:2])
    diff = np.abs(png[:h, :w, :3].astype(int) - shown[:h, :w, :3].astype(int)).mean()
    assert diff < 3, (
        f"{name}: the PNG differs from the figure as shown (mean |diff| {diff:.1f} grey levels)"
    )
    alt = metadata["image/png"]["alt"]
    assert alt == data["text/plain"]
    first_words = " ".join(spec.builder.__doc__.split()[:3])
    assert alt.startswith(first_words), (
        f"{name}: alt text should start with the demo's description: {alt!r}"
    )
    for control in demo.controls.values():
        assert f"{control.description.strip().rstrip('=:').strip()} = " in alt, (
            f"{name}: alt text misses a setting"
        )
    h, w = png.shape[:2]
    assert (metadata["image/png"]["width"], metadata["image/png"]["height"]) == (w, h)


def test_alt_text_follows_the_settings():
    demo = DEMOS["stack_check"].builder()
    assert "angle θ (°) = 40; scale s = 1." in demo.alt_text
    demo.set(angle=-35.0, scale=1.5)
    assert "angle θ (°) = -35; scale s = 1.5." in demo.alt_text
    assert (
        "Panels: 'y down, as in images: θ > 0 clockwise, θ < 0 anticlockwise', 'y up, as in maths textbooks"
        in demo.alt_text
    )
    assert "Readout: 'roof tip (orange dot) at (-1.20, -1.72)'." in demo.alt_text


def test_selection_controls_show_their_label():
    import ipywidgets as W

    controls = {
        "b": W.SelectionSlider(options=[0.0, 0.25], value=0.0, description="baseline (m)"),
        "m": W.Dropdown(
            options=[("multi-band", "mb"), ("feather", "f")], value="f", description="blend"
        ),
        "on": W.Checkbox(value=True, description="outlines"),
    }
    assert (
        static.demo_alt_text("A demo", controls)
        == "A demo. Shown at baseline (m) = 0.0; blend = feather; outlines = on."
    )


def test_plain_figure_description_names_panels_labels_and_legend():
    fig = Figure()
    ax1, ax2 = fig.subplots(1, 2)
    ax1.plot([0, 1], label="f = 25 mm")
    ax1.plot([1, 0], label="f = 50 mm")
    ax1.set(title="image height", xlabel="distance Z (m)", ylabel="height (mm)")
    ax1.legend()
    ax2.imshow(np.zeros((4, 4)))
    ax2.set_title("photo")
    assert static.describe_figure(fig) == (
        "Figure with 2 panels: plot 'image height', axes 'distance Z (m)', 'height (mm)', "
        "legend 'f = 25 mm', 'f = 50 mm'; image 'photo'."
    )
    static.alt_text(fig, "  Image height falls as 1/Z.  ")
    assert static.describe_figure(fig) == "Image height falls as 1/Z."
    with pytest.raises(ValueError, match="alt_text: expected a sentence"):
        static.alt_text(fig, " ")


def test_ipympl_canvas_display_carries_png_and_alt_text_in_a_shell():
    """The formatter camlab.widgets installs in a kernel: real IPython display path, real ipympl canvas."""
    from ipympl.backend_nbagg import Canvas
    from IPython.core.interactiveshell import InteractiveShell

    shell = InteractiveShell.instance()
    try:
        assert static.install_canvas_formatter()
        fig = Figure(figsize=(3, 2), dpi=80)
        Canvas(fig)
        fig.subplots().set_title("join and meet")
        assert fig.canvas.header_visible
        data, metadata = shell.display_formatter.format(fig.canvas)
    finally:
        InteractiveShell.clear_instance()
    assert not fig.canvas.header_visible  # no "Figure N" title bar above a lesson's figure
    assert WIDGET_VIEW in data and "text/html" not in data
    assert _png_pixels(data["image/png"]).shape[:2] == (160, 240)
    assert metadata["image/png"]["alt"] == "Figure: plot 'join and meet'."


def test_a_plain_figure_wider_than_the_output_area_is_drawn_to_fit_it():
    """A 10 x 3 in figure at 100 dpi (lesson 04) is 1008 px with ipympl's frame; the output area
    is 968 px at 1400 px with the file browser open. Its canvas is drawn at a lower dpi instead."""
    from ipympl.backend_nbagg import Canvas
    from IPython.core.interactiveshell import InteractiveShell

    shell = InteractiveShell.instance()
    try:
        assert static.install_canvas_formatter()
        wide, narrow = Figure(figsize=(10, 3), dpi=100), Figure(figsize=(6, 3), dpi=100)
        for fig in (wide, narrow):
            Canvas(fig)
            fig.subplots().set_title("three cameras")
        (wide_png, _), (narrow_png, _) = (
            shell.display_formatter.format(f.canvas) for f in (wide, narrow)
        )
    finally:
        InteractiveShell.clear_instance()
    assert (
        wide.get_figwidth() == 10
        and wide.dpi * 10 + static.CANVAS_FRAME_PX == static.OUTPUT_WIDTH_PX
    )
    assert _png_pixels(wide_png["image/png"]).shape[1] == 952
    assert narrow.dpi == 100 and _png_pixels(narrow_png["image/png"]).shape[:2] == (300, 600)


def test_camera_frame_puts_pixel_0_0_half_a_pixel_in_and_its_labels_off_the_axes():
    """Lesson 00's camera frame: (u, v) = (0, 0) is the top-left pixel's centre, half a pixel in from the image
    plane's corner (the convention the panel beside it teaches), and no label sits on an axis arrow."""
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle
    from matplotlib.text import Text
    from matplotlib.transforms import Bbox

    from camlab.plotting import conventions

    fig, ax = plt.subplots(figsize=(3.2, 3.0))
    conventions.draw_camera_frame(ax, (4, 3))
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    (plane,) = [p for p in ax.patches if isinstance(p, Rectangle)]
    pixel = plane.get_width() / 4
    assert np.isclose(plane.get_height(), 3 * pixel)
    (origin,) = [a for a in ax.texts if a.get_text().startswith("(0, 0)")]
    assert np.allclose(
        origin.xy, np.add(plane.get_xy(), pixel / 2)
    )  # half a pixel in, not on the corner
    axes_arrows = [
        a.arrow_patch for a in ax.texts if not a.get_text() and getattr(a, "arrow_patch", None)
    ]
    assert len(axes_arrows) == 4  # u, v, x and y
    for text in ax.texts:
        if not text.get_text():
            continue
        box = Text.get_window_extent(
            text, renderer
        )  # the words alone (an annotation's box includes its arrow)
        for arrow in axes_arrows:
            assert not Bbox.intersection(
                box, arrow.get_window_extent(renderer).shrunk(0.9, 0.9)
            ) or text.get_text() in ("u", "v"), f"{text.get_text()!r} lies on an arrow"
    plt.close(fig)


def test_a_3d_view_with_its_axes_switched_off_is_not_described_by_axis_labels():
    fig = Figure()
    ax = fig.add_subplot(projection="3d")
    ax.set(xlabel="X (m)", ylabel="Y (m)", zlabel="Z (m)", title="the camera in the world")
    ax.set_axis_off()
    assert static.describe_figure(fig) == "Figure: 3-D view 'the camera in the world'."


def test_image_panels_tick_the_centre_where_the_course_puts_it():
    """Lesson 00 teaches (319.5, 239.5) as the centre of 640 x 480; image panels must not tick 320 and 240."""
    from camlab.plotting import scene3d

    fig = Figure()
    ax = fig.add_subplot()
    scene3d.image_axes(ax, (640, 480))
    assert list(ax.get_xticks()) == [0, 319.5, 639] and list(ax.get_yticks()) == [0, 239.5, 479]
    assert [t.get_text() for t in ax.get_xticklabels()] == ["0", "319.5", "639"]
    assert ax.get_xlim() == (-0.5, 639.5) and ax.get_ylim() == (479.5, -0.5)


def _laid_out_figure(canvas_class=None) -> Figure:
    """A constrained-layout figure with what lesson figures hold: panels, image, colour bar, legend,
    suptitle, and an animated line (a demo's moving part), built the same way on every call."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig = Figure(figsize=(6, 3.5), dpi=90, layout="constrained")
    (canvas_class or FigureCanvasAgg)(fig)
    ax1, ax2 = fig.subplots(1, 2)
    ax1.plot([0, 1, 3], [2, 0, 1], label="measured")
    ax1.plot([0, 3], [1, 1], animated=True, lw=3, color="tab:red")
    ax1.set(title="a plot", xlabel="x (px)", ylabel="y (px)")
    ax1.legend()
    fig.colorbar(ax2.imshow(np.arange(48.0).reshape(6, 8)), ax=ax2, label="grey level")
    ax2.set_title("an image")
    fig.suptitle("two panels, laid out")
    return fig


def _draws(monkeypatch) -> list:
    calls: list = []
    draw = Figure.draw
    monkeypatch.setattr(
        Figure, "draw", lambda self, renderer: calls.append(1) or draw(self, renderer)
    )
    return calls


def test_figure_png_draws_a_laid_out_figure_once_into_the_pixels_savefig_gives(monkeypatch):
    """savefig draws a figure with a layout engine twice; figure_png once, with the same pixels,
    the animated line included (a demo's static picture shows its moving parts)."""
    saved = io.BytesIO()
    _laid_out_figure().savefig(saved, format="png", dpi="figure")
    calls = _draws(monkeypatch)
    png = static.figure_png(_laid_out_figure())
    assert len(calls) == 1
    want, got = (_png_pixels(base64.b64encode(b).decode()) for b in (saved.getvalue(), png))
    assert got.shape == want.shape == (315, 540, 4) and np.array_equal(got, want)
    red = (got[..., 0] > 200) & (got[..., 1] < 60) & (got[..., 2] < 60)
    assert red.sum() > 300  # the animated line is in the picture


def _zlib_level_class(png: bytes) -> int:
    """FLEVEL of the first IDAT's zlib header (RFC 1950): 1 for levels 2-5, 2 for Pillow's default 6."""
    at = png.index(b"IDAT") + 4
    return png[at + 1] >> 6


@pytest.mark.parametrize("dpi", [None, 45])
def test_figure_png_compresses_faster_than_the_default_with_the_same_pixels(dpi):
    saved = io.BytesIO()
    _laid_out_figure().savefig(saved, format="png", dpi=dpi or "figure")
    png = static.figure_png(_laid_out_figure(), dpi=dpi)  # a fresh figure: a second layout moves it
    assert _zlib_level_class(saved.getvalue()) == 2 and _zlib_level_class(png) == 1
    want, got = (_png_pixels(base64.b64encode(b).decode()) for b in (saved.getvalue(), png))
    assert np.array_equal(got, want)


def test_figure_png_at_another_dpi_or_on_a_hidpi_screen_goes_through_savefig(monkeypatch):
    fig = _laid_out_figure()
    assert _png_pixels(base64.b64encode(static.figure_png(fig, dpi=45)).decode()).shape[:2] == (
        157,
        270,
    )
    fig._original_dpi, fig.dpi = 90, 180  # what a HiDPI browser does to an ipympl figure
    calls = _draws(monkeypatch)
    assert _png_pixels(base64.b64encode(static.figure_png(fig)).decode()).shape[:2] == (630, 1080)
    assert len(calls) == 2  # savefig's dry run and its draw


def test_an_ipympl_canvas_is_drawn_once_per_display_into_savefigs_pixels(monkeypatch):
    """ipympl's own bundle saves the figure (two draws); the formatter hands it the one picture it drew."""
    from ipympl.backend_nbagg import Canvas
    from IPython.core.interactiveshell import InteractiveShell

    saved = io.BytesIO()
    _laid_out_figure(Canvas).savefig(saved, format="png", dpi="figure")
    fig = _laid_out_figure(Canvas)
    shell = InteractiveShell.instance()
    try:
        assert static.install_canvas_formatter()
        calls = _draws(monkeypatch)
        data, _ = shell.display_formatter.format(fig.canvas)
    finally:
        InteractiveShell.clear_instance()
    assert len(calls) == 1
    assert np.array_equal(
        _png_pixels(data["image/png"]), _png_pixels(base64.b64encode(saved.getvalue()).decode())
    )
    assert fig.canvas._data_url.endswith(data["image/png"])  # ipympl's copy, for its own HTML embed
    assert "savefig" not in vars(fig)  # Figure.savefig is the figure's again
