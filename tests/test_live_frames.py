"""The frame a demo sends after a control moves equals a full redraw of the same figure.

The live path (``FigureView.refresh``) restores a cached background and draws only the
animated artists on it. Anything that a full draw does and ``draw_artist`` skips (3-D
projection of fills, a changed axis limit, a stale legend) makes the live frame differ from
what the same state looks like drawn from scratch. For every registered demo, at its
default and at both ends of every control's sweep, the two must agree up to anti-aliasing.
"""

import numpy as np
import pytest

from camlab.widgets import all_demos

DEMOS = all_demos()


def full_redraw(view) -> np.ndarray:
    """The figure drawn from scratch, every artist in one ordinary draw, as an (H, W, 4) uint8 array.

    The draw is flagged as a save so that ``FigureView`` keeps its cached background; the
    next live frame restores that background, so the demo carries on unchanged.
    """
    canvas = view.fig.canvas
    animated = list(view._animated)
    for artist in animated:
        artist.set_animated(False)
    canvas._is_saving = True
    try:
        canvas.draw()
        return np.asarray(canvas.buffer_rgba()).copy()
    finally:
        canvas._is_saving = False
        for artist in animated:
            artist.set_animated(True)


def frame_difference(live: np.ndarray, full: np.ndarray, levels: int = 64) -> tuple[float, float]:
    """(share of pixels that differ, largest difference in grey levels), edges forgiven.

    Anti-aliasing and image resampling may put an edge one pixel over, so a pixel counts as
    different only if no pixel of the other frame within one pixel of it is within ``levels`` grey
    levels; a stale or missing artist differs over its whole area.
    """
    a, b = (
        live[..., :3].astype(int),
        np.pad(full[..., :3].astype(int), ((1, 1), (1, 1), (0, 0)), mode="edge"),
    )
    h, w = a.shape[:2]
    diff = np.min(
        [np.abs(a - b[dy : dy + h, dx : dx + w]).max(axis=2) for dy in range(3) for dx in range(3)],
        axis=0,
    )
    return float(np.mean(diff > levels)), float(diff.max())


def image_frames_lost(
    view, live: np.ndarray, full: np.ndarray, band: int = 2, levels: int = 48
) -> list[str]:
    """The sides of animated images' frames that the live frame lost: ``["axes 1 top: 97 %", ...]``.

    A spine is a one-pixel line on the edge of the image's axes: :func:`frame_difference` forgives
    it (a one-pixel shift) and it is far below its share of pixels, yet a reader sees the frame
    open at the top and the left (in every lesson, once). So along each side of every framed
    axes that holds an animated image, compare the darkest pixel across a band of ``band`` pixels
    either side of the edge, live against full, with no shift forgiven; a side counts as lost
    where over 2 % of its length differs by more than ``levels`` grey levels.
    """
    from matplotlib.image import AxesImage

    height = live.shape[0]
    grey_live, grey_full = (f[..., :3].astype(int).max(axis=2) for f in (live, full))
    lost = []
    for k, ax in enumerate(view.fig.axes):
        if not (ax.get_visible() and ax.axison and ax.get_frame_on()) or not any(
            isinstance(a, AxesImage) and a in view._animated for a in ax.get_images()
        ):
            continue
        box = ax.get_window_extent()
        x0, x1, y0, y1 = (int(round(c)) for c in (box.x0, box.x1, height - box.y1, height - box.y0))
        along_x, along_y = slice(x0 + 3, x1 - 3), slice(y0 + 3, y1 - 3)  # corners left out
        sides = {
            "top": (slice(y0 - band, y0 + band + 1), along_x, 0),
            "bottom": (slice(y1 - band, y1 + band + 1), along_x, 0),
            "left": (along_y, slice(x0 - band, x0 + band + 1), 1),
            "right": (along_y, slice(x1 - band, x1 + band + 1), 1),
        }
        for side, (rows, cols, across) in sides.items():
            darkest_live, darkest_full = (
                grey_live[rows, cols].min(axis=across),
                grey_full[rows, cols].min(axis=across),
            )
            share = float(np.mean(np.abs(darkest_live - darkest_full) > levels))
            if share > 0.02:
                lost.append(f"axes {k} {side}: {share:.0%}")
    return lost


def sweep_points(spec) -> list[tuple[str, object]]:
    """Each control at both ends of its sweep (the other controls where the sweep left them)."""
    return [
        (control, value)
        for control, values in spec.sweep.items()
        for value in (values[0], values[-1])
    ]


# Live frames that differ from a full redraw today by 0.1-1.7 % of their pixels,
# not yet triaged. Strict: a fix that makes one pass must take it off this list.
KNOWN_DIFFERENT: set[str] = set()
# (epipolar_lines passed once its legend moved off the animated lines, below the right image)
# (undistort_alpha passed once every animated image's spines were drawn live)
# (ransac_outliers passed once its legend moved off the animated arrows, below the figure; panorama_canvas
# once its canvas filled fixed axes)


@pytest.mark.parametrize(
    "name",
    [
        pytest.param(n, marks=pytest.mark.xfail(strict=True, reason="a known live/full difference"))
        if n in KNOWN_DIFFERENT
        else n
        for n in sorted(DEMOS)
    ],
)
def test_live_frame_equals_a_full_redraw_at_every_sweep_end(name):
    spec = DEMOS[name]
    demo = spec.builder()
    wrong = []
    for control, value in [("default", None), *sweep_points(spec)]:
        if control != "default":
            demo.set(**{control: value})
        live, full = demo.view.pixels(), full_redraw(demo.view)
        share, worst = frame_difference(live, full)
        if share > 0.001:
            wrong.append(
                f"{control}={value!r}: {share:.2%} of pixels differ (up to {worst:.0f} grey levels)"
            )
        if lost := image_frames_lost(demo.view, live, full):
            wrong.append(f"{control}={value!r}: image frame lost at {', '.join(lost)}")
    assert not wrong, (
        f"{name}: the live frame is not what a full redraw shows at\n  " + "\n  ".join(wrong)
    )


@pytest.mark.parametrize("name", sorted(KNOWN_DIFFERENT))
def test_known_different_demos_keep_their_image_frames(name):
    """The demos the test above expects to fail are held to the frame check on its own."""
    spec = DEMOS[name]
    demo = spec.builder()
    for control, value in [("default", None), *sweep_points(spec)]:
        if control != "default":
            demo.set(**{control: value})
        live = demo.view.pixels()
        assert not image_frames_lost(demo.view, live, full_redraw(demo.view)), (
            f"{name} {control}={value!r}"
        )


def test_the_frame_check_catches_an_image_painted_over_its_spines():
    """As every demo once was: static spines in the cached background, under the image."""
    from matplotlib.image import AxesImage

    from camlab.widgets.digital_sensor import bit_depth_and_noise

    demo = bit_depth_and_noise()
    ax = next(a for a in demo.view._animated if isinstance(a, AxesImage)).axes
    for spine in ax.spines.values():
        spine.set_animated(False)
        demo.view._animated.remove(spine)
    demo.view.fig.canvas.draw()
    demo.set(bits=3)
    live, full = demo.view.pixels(), full_redraw(demo.view)
    assert (
        frame_difference(live, full)[0] <= 0.001
    )  # the pixel comparison forgives a one-pixel line
    lost = image_frames_lost(demo.view, live, full)
    assert any(" top: " in side for side in lost) and any(" left: " in side for side in lost), lost


def largest_patch_lost(live: np.ndarray, full: np.ndarray, size: int = 5) -> float:
    """The largest share of a size x size patch that differs (a lost marker is small but solid)."""
    a, b = (
        live[..., :3].astype(int),
        np.pad(full[..., :3].astype(int), ((1, 1), (1, 1), (0, 0)), mode="edge"),
    )
    h, w = a.shape[:2]
    diff = (
        np.min(
            [
                np.abs(a - b[dy : dy + h, dx : dx + w]).max(axis=2)
                for dy in range(3)
                for dx in range(3)
            ],
            axis=0,
        )
        > 64
    )
    sums = np.pad(diff.cumsum(0).cumsum(1), ((1, 0), (1, 0)))
    box = sums[size:, size:] - sums[:-size, size:] - sums[size:, :-size] + sums[:-size, :-size]
    return float(box.max()) / size**2


# Demos checked for small lost details too (a static marker under a moving line: lesson 01's
# pinhole dot went white under a ray's halo in every live frame, 0.03 % of the pixels).
# Lesson 07's hierarchy demo lost its open "before H" cross-ratio markers under the warped
# picture in every live frame (235 pixels, 0.07 %).
SMALL_DETAILS = [
    "pinhole_projection",
    "pinhole_size",
    "similar_triangles",
    "transformation_hierarchy",
]


@pytest.mark.parametrize("name", SMALL_DETAILS)
def test_live_frame_loses_no_small_detail(name):
    spec = DEMOS[name]
    demo = spec.builder()
    for control, value in [("default", None), *sweep_points(spec)]:
        if control != "default":
            demo.set(**{control: value})
        lost = largest_patch_lost(demo.view.pixels(), full_redraw(demo.view))
        assert lost < 0.5, (
            f"{name} {control}={value!r}: {lost:.0%} of a 5 x 5 patch differs from a full redraw"
        )


def test_the_patch_check_catches_a_static_marker_under_a_moving_line():
    from camlab.widgets.pinhole_camera import similar_triangles

    demo = similar_triangles()
    dot = next(a for a in demo.view._animated if a.get_gid() == "pinhole")
    dot.set_animated(False)  # as it was: in the cached background, painted over by the ray
    demo.view._animated.remove(dot)
    demo.view.fig.canvas.draw()
    demo.set(Z=3.5)
    assert largest_patch_lost(demo.view.pixels(), full_redraw(demo.view)) > 0.5


def test_the_comparison_catches_a_frame_that_missed_a_move():
    """The check can fail: an artist moved without a refresh leaves the live frame stale."""
    from camlab.widgets.pinhole_camera import pinhole_projection

    demo = pinhole_projection()
    demo.view._animated[0].set_data(
        np.zeros_like(demo.state["image"])
    )  # the image goes black, unsent
    share, worst = frame_difference(demo.view.pixels(), full_redraw(demo.view))
    assert share > 0.01 and worst > 200


@pytest.mark.parametrize(
    "name", [*SMALL_DETAILS, "drag_homography"]
)  # lesson 07's warp: 12,000 pixels differed before its image was drawn with "nearest"
def test_first_draw_equals_a_live_frame(name):
    """The static PNG (the first draw, before any layout) shows the pixels every later frame shows.

    An image's data is fitted to the pixels it covers; fitted before the first layout, the
    first draw resampled it again and showed another noise texture (5,600 pixels of lesson 01).
    """
    import io

    import matplotlib.pyplot as plt

    from camlab.plotting.static import figure_png

    demo = DEMOS[name].builder()
    first = (plt.imread(io.BytesIO(figure_png(demo.figure)))[..., :3] * 255).round().astype(int)
    control, values = next(iter(DEMOS[name].sweep.items()))
    default = demo.controls[control].value
    demo.set(**{control: values[0] if values[0] != default else values[-1]})
    demo.set(**{control: default})
    live = demo.view.pixels()
    assert first.shape == live[..., :3].shape
    first_rgba = np.dstack([first, np.full(first.shape[:2], 255)]).astype(np.uint8)
    share, worst = frame_difference(
        live, first_rgba, levels=16
    )  # a resampled texture differs by 20-60 levels
    assert share == 0, f"{share:.3%} of the pixels differ, up to {worst:.0f} grey levels"


@pytest.mark.parametrize(
    "setting", [{}, {"scale": 1.0, "angle": 15.0}, {"scale": 2.8, "angle": 0.0}]
)
def test_a_pixelated_enlarged_image_is_sampled_live_as_a_full_draw_samples_it(setting):
    """The forward warp's one-pixel holes, enlarged about 1.4 times: a live frame that picks its
    columns from each canvas pixel's corner (OpenCV's nearest) shows another moiré than the saved
    figure, though every difference is a one-pixel shift that the test above forgives. Exact here."""
    demo = DEMOS["forward_vs_inverse"].builder()
    if setting:
        demo.set(**setting)
    live, full = (
        demo.view.pixels()[..., :3].astype(int),
        full_redraw(demo.view)[..., :3].astype(int),
    )
    differ = float(np.mean(np.abs(live - full).max(axis=2) > 30))
    assert differ < 1e-4, (
        f"{differ:.2%} of the pixels differ between the live frame and a full redraw"
    )


def test_sampling_demo_first_draw_equals_its_live_frame():
    """The notebook's static picture (a saved figure) is the frame a student sees live at that setting.

    Once the first draw resampled the blocks through matplotlib and the live path through OpenCV:
    21 344 pixels of the sampled panel differed by over 20 grey levels, and the fold's grey disc
    that the prose points at faded in the first draw.
    """
    import base64
    import io

    import matplotlib.image as mpimg

    from camlab.widgets.digital_sensor import sampling_aliasing

    demo = sampling_aliasing()
    png = base64.b64decode(demo._repr_mimebundle_()[0]["image/png"])
    first = (mpimg.imread(io.BytesIO(png))[..., :3] * 255).round().astype(int)
    demo.set(factor=4)
    demo.set(factor=3)
    live = demo.view.pixels()[..., :3].astype(int)
    assert first.shape == live.shape
    differ = int((np.abs(first - live).max(axis=2) > 20).sum())
    assert differ < 50, (
        f"{differ} pixels of the first draw differ from the live frame by over 20 levels"
    )
