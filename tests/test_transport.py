"""The fast browser-frame encoder sends exactly the pixels matplotlib's own encoder sends."""

import io

import numpy as np
import pytest
from PIL import Image

from camlab.widgets import _transport


@pytest.fixture
def ipympl_canvas():
    ipympl = pytest.importorskip("ipympl.backend_nbagg")
    from matplotlib.figure import Figure

    fig = Figure(
        figsize=(4, 3), dpi=80
    )  # not through pyplot: other tests may have chosen Agg there
    canvas = ipympl.Canvas(fig)
    ipympl.FigureManager(canvas, 0)
    image = fig.add_subplot().imshow(np.random.default_rng(0).random((30, 40)))
    yield canvas, image


def _decode(png: bytes) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGBA"))


def test_fast_diff_matches_matplotlib(ipympl_canvas):
    canvas, image = ipympl_canvas
    sent = []
    canvas.send_binary = sent.append  # what would go to the browser
    frames = {}
    for name in ("matplotlib", "fast"):
        if name == "fast":
            _transport.use_fast_png(canvas)
        canvas._force_full = True
        canvas.draw()  # a full frame
        image.set_data(np.random.default_rng(1).random((30, 40)))
        canvas.draw()  # only the changed pixels, the rest transparent
        image.set_data(np.random.default_rng(0).random((30, 40)))
        frames[name], sent[:] = list(sent), []
    assert len(frames["fast"]) == len(frames["matplotlib"]) == 2
    for slow, fast in zip(frames["matplotlib"], frames["fast"], strict=True):
        assert np.array_equal(_decode(slow), _decode(fast))
    changed = _decode(frames["fast"][1])[..., 3] > 0
    assert 0 < changed.mean() < 0.9  # a diff frame, not a full one


def test_nothing_sent_when_nothing_changed(ipympl_canvas):
    canvas, _ = ipympl_canvas
    _transport.use_fast_png(canvas)
    canvas.draw()
    canvas._png_is_old = False
    assert canvas.get_diff_image() is None


def test_animated_images_are_kept_at_the_resolution_shown():
    from camlab.widgets import FigureView

    view = FigureView(figsize=(4, 3), mode="agg", dpi=50)  # axes about 150 px wide
    ax = view.fig.add_subplot()
    big = np.random.default_rng(0).random((480, 640))
    image = view.animate(ax.imshow(big, cmap="gray"))
    crisp = view.animate(ax.imshow(big, interpolation="nearest", extent=(0, 640, 480, 0)))
    extent = image.get_extent()
    image.set_data(big)
    crisp.set_data(big > 0.5)  # bool: not an image type Agg averages; left alone
    shown = image.get_array()
    assert shown.shape[1] < 200 and shown.shape[0] < 160 and image.get_extent() == extent
    assert abs(shown.mean() - big.mean()) < 0.01  # area-averaged, not subsampled
    assert crisp.get_array().shape == (480, 640)
    crisp.set_data(big)
    assert set(np.unique(np.isin(crisp.get_array(), big))) == {True}  # nearest: source values only
    ax.set_autoscale_on(False)
    image.set_extent((0, 64, 48, 0))  # shown 10x smaller: refitted from the full array
    assert image.get_array().shape[1] < 20
    image.set_extent(extent)
    assert image.get_array().shape == shown.shape
    small = np.ones((20, 30))
    image.set_data(small)
    assert image.get_array().shape == (20, 30)  # smaller than shown: untouched


@pytest.mark.parametrize(
    "origin, inverted, clipped",
    [
        ("upper", False, False),
        ("lower", False, False),
        ("upper", True, False),
        ("upper", False, True),
    ],
)
def test_screen_images_land_where_matplotlib_draws_them(origin, inverted, clipped):
    """The live canvas' image path (no general resampler) matches matplotlib's own drawing:
    same orientation and place, colours within resampling differences, clipped to the axes."""
    from camlab.widgets import FigureView

    view = FigureView(figsize=(4, 3), mode="agg", dpi=60)
    ax = view.fig.add_subplot()
    yy, xx = np.mgrid[0:60, 0:80]
    gradient = (xx / 79.0) * (yy < 30) + (yy / 59.0) * (yy >= 30)  # asymmetric: a flip shows
    image = view.animate(ax.imshow(gradient, cmap="viridis", origin=origin))
    if inverted:
        ax.invert_xaxis()
    if clipped:
        ax.set_xlim(10, 50)  # part of the image lies outside the axes
    view.fig.canvas.draw()  # the live path (not saving)
    live = np.asarray(view.fig.canvas.buffer_rgba())[..., :3].astype(int)
    buf = io.BytesIO()
    view.fig.savefig(buf, format="png", dpi=60)  # saving: matplotlib's resampler
    reference = np.asarray(Image.open(buf).convert("RGB")).astype(int)
    assert image.make_image.__name__ == "screen_image"
    diff = np.abs(live - reference).max(axis=2)
    assert diff.mean() < 5 and (diff > 60).mean() < 0.02, (
        diff.mean(),
        (diff > 60).mean(),
    )  # a flip: mean > 40


@pytest.mark.parametrize("shape", [(1, 1), (1, 7), (5, 1), (37, 53)])
def test_encoded_png_decodes_to_the_same_pixels(shape):
    rgba = np.random.default_rng(1).integers(0, 256, (*shape, 4), dtype=np.uint8)
    assert np.array_equal(_decode(_transport.encode_png(rgba)), rgba)


def test_haloed_lines_draw_as_two_plain_passes_that_look_the_same():
    """An animated haloed line (markers and a collection) draws without the per-path
    path-effect renderer, and looks as the path effect draws it."""
    from matplotlib.collections import LineCollection

    from camlab.plotting import palette
    from camlab.widgets import FigureView

    def drawn(two_passes: bool) -> np.ndarray:
        view = FigureView(figsize=(4, 3), mode="agg", dpi=60)
        ax = view.fig.add_subplot()
        ax.imshow(np.random.default_rng(0).random((30, 40)), cmap="gray")
        dots = ax.plot(
            *np.random.default_rng(1).uniform(0, 30, (2, 50)),
            "o",
            ms=4,
            color=palette.GREEN,
            path_effects=palette.halo(),
        )[0]
        lines = ax.add_collection(
            LineCollection(
                [[(0, 0), (39, 29)], [(0, 29), (39, 0)]],
                colors=palette.RED,
                linewidths=1.0,
                path_effects=palette.halo(1.0),
            )
        )
        if two_passes:
            view.animate(dots, lines)
            assert "draw" in vars(dots) and "draw" in vars(lines) and dots.get_path_effects()
            for artist in (dots, lines):
                artist.set_animated(False)  # drawn by the full draw below, like a blitted frame
        view.fig.canvas.draw()
        return np.asarray(view.fig.canvas.buffer_rgba())[..., :3].astype(int)

    diff = np.abs(drawn(True) - drawn(False)).max(axis=2)
    assert diff.mean() < 3.0 and (diff > 60).mean() < 0.02  # antialiased edges differ by a pixel


def test_rotated_or_clipped_images_keep_matplotlibs_drawing():
    from matplotlib.patches import Circle
    from matplotlib.transforms import Affine2D

    from camlab.widgets import FigureView

    view = FigureView(figsize=(4, 3), mode="agg", dpi=60)
    ax = view.fig.add_subplot()
    rotated = view.animate(ax.imshow(np.random.default_rng(0).random((30, 40))))
    rotated.set_transform(Affine2D().rotate_deg(30) + ax.transData)
    clipped = view.animate(ax.imshow(np.random.default_rng(1).random((30, 40))))
    clipped.set_clip_path(Circle((20, 15), 10, transform=ax.transData))
    assert _transport._screen_image(rotated) is None and _transport._screen_image(clipped) is None


def test_an_image_fitted_before_the_layout_is_refitted_when_drawn():
    """animate() fits the array to the axes as they are before constrained layout runs; the
    first draw moves the axes, and the image must then be resampled once, from the caller's
    array, to the box it really covers (not fitted small, then stretched)."""
    from camlab.widgets import FigureView
    from camlab.widgets._transport import _pixel_box

    view = FigureView(figsize=(8, 4), mode="agg", dpi=90)
    ax_img, ax_side = view.fig.subplots(1, 2, width_ratios=[2.5, 1])
    ax_side.set_ylabel("a long label\nover two lines")
    ax_side.set_title("a title\nover two lines")
    image = view.animate(ax_img.imshow(np.zeros((360, 480))))
    image.set_data(np.random.default_rng(1).random((360, 480)))
    before = image.get_array().shape
    view.fig.canvas.draw()  # the first full draw: the layout moves the axes
    left, right, bottom, top = _pixel_box(image)
    assert (
        before != image.get_array().shape
    )  # the layout did change the box (else this test proves nothing)
    assert image.get_array().shape == (min(360, top - bottom), min(480, right - left))
