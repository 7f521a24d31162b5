"""Demo- and exercise-specific tests for lessons 01-03 (the generic sweeps live in test_widgets.py)."""

import contextlib
import io
import os
import re

import numpy as np
import pytest

os.environ.setdefault("CAMLAB_FIGURE_MODE", "agg")

from camlab import distortion, fixtures, lens, render, scenes, sensor  # noqa: E402
from camlab.exercises import all_exercises, check  # noqa: E402
from camlab.widgets import (  # noqa: E402
    REGISTRY,  # noqa: E402
    digital_sensor,
    lenses_and_distortion,
    pinhole_camera,
)

MODULES = {"01": pinhole_camera, "02": lenses_and_distortion, "03": digital_sensor}


@pytest.mark.parametrize("name", sorted(n for n, s in REGISTRY.items() if s.lesson in MODULES))
def test_every_demo_sweeps_and_moves_pixels(name):
    spec = REGISTRY[name]
    demo = spec.builder()
    before = demo.view.pixels()
    for key, values in spec.sweep.items():
        for v in values:
            demo.set(**{key: v})
    assert not np.array_equal(before, demo.view.pixels())


def test_pinhole_projection_box_width_follows_f_over_z():
    demo = pinhole_camera.pinhole_projection()
    demo.set(focal_mm=50, distance=2.0)
    w1 = demo.state["box_width_px"]
    box_alone = render.render(
        fixtures.box_before_wall(2.0)[0], demo.state["K"], pinhole_camera.SIZE, background=0.0
    )
    box_columns = np.flatnonzero(np.any(box_alone.irradiance > 0.02, axis=0))
    assert w1 == pytest.approx(
        box_columns.max() - box_columns.min(), abs=2.0
    )  # the readout is what you see
    demo.set(focal_mm=100)
    assert demo.state["box_width_px"] == pytest.approx(2 * w1)
    demo.set(distance=4.0)
    assert demo.state["box_width_px"] == pytest.approx(
        w1, rel=0.1
    )  # about f / Z (the box has depth)
    for f_mm, Z in ((100, 0.8), (15, 0.8), (100, 4.0)):
        demo.set(focal_mm=f_mm, distance=Z)
        nearest = np.unique(
            scenes.plane_outlines(fixtures.box_before_wall(Z)[0]).reshape(-1, 3), axis=0
        )[:, 2].min()
        assert (
            0 < demo.state["f_draw"] < nearest
        )  # the drawn image planes stay between pinhole and box
    demo.set(focal_mm=50, distance=4.0)
    drawn = demo.state["f_draw"]
    demo.set(
        focal_mm=100
    )  # the 3-D planes move out with f (lesson 01's complaint: frozen above 50 mm)
    assert demo.state["f_draw"] == pytest.approx(2 * drawn) and demo.state[
        "draw_scale"
    ] == pytest.approx(12)
    demo.set(focal_mm=50, distance=2.0)
    drawn = demo.state["f_draw"]
    demo.set(
        focal_mm=100
    )  # nearer the box they stop half way to it, still further out than at 50 mm
    assert drawn < demo.state["f_draw"] <= pinhole_camera.PLANE_ROOM * 1.76
    demo.set(focal_mm=100, distance=0.8)
    assert demo.state["bar_clipped"] and demo.state["box_width_px"] > pinhole_camera.SIZE[0]
    demo.set(focal_mm=50, distance=2.0)
    upright = demo.state["image"].copy()
    demo.set(real_plane=True)
    assert np.array_equal(demo.state["image"], upright[::-1, ::-1])


def test_pinhole_size_regimes():
    demo = pinhole_camera.pinhole_size()
    demo.set(focal_mm=100, diameter_mm=0.05)
    assert demo.state["limited_by"] == "diffraction-limited"
    demo.set(diameter_mm=2.0)
    assert demo.state["limited_by"] == "geometry-limited"
    assert demo.state["best_mm"] == pytest.approx(
        np.sqrt(2.44 * 550e-9 * 0.1 / 1.1) * 1e3
    )  # object at 1 m
    rows = {}
    for d in (
        0.05,
        0.35,
        1.5,
    ):  # the lesson's claim: the best hole leaves all five rows legible, the extremes three or two
        demo.set(diameter_mm=d)
        rows[d] = demo.state["legible_rows"]
    assert rows == {0.05: 3, 0.35: 5, 1.5: 2}
    demo.set(diameter_mm=2.5)  # as wide a blur as d = 0.05 mm, but a flat disc: one row
    assert demo.state["legible_rows"] == 1
    demo.set(diameter_mm=0.35)  # within 5 % of the best 0.349 mm: the two terms are equal to 0.5 %
    assert demo.state["limited_by"] == "balanced"
    demo.set(focal_mm=300)  # the hole left at 0.35 mm, now too small: diffraction-limited
    assert demo.state["blur_mm"] == pytest.approx(1.61, abs=0.01) and demo.state[
        "blur_px"
    ] == pytest.approx(4.8, abs=0.1)
    assert demo.state["limited_by"] == "diffraction-limited"
    assert (
        demo.state["legible_rows"] == 5
    )  # the long camera is sharper: the fifth row comes back even at d = 0.35 mm
    demo.set(
        diameter_mm=demo.state["best_mm"]
    )  # at f = 300 mm's own best hole: 1.45 mm, 4.3 px (lesson 01)
    assert demo.state["blur_mm"] == pytest.approx(1.45, abs=0.01) and demo.state[
        "blur_px"
    ] == pytest.approx(4.3, abs=0.1)
    assert demo.state["legible_rows"] == 5


def test_pinhole_size_shows_the_light_a_hole_costs():
    demo = pinhole_camera.pinhole_size()
    compensated = demo.state["image"].copy()
    demo.set(fixed_exposure=True)  # the default's own exposure: the same picture
    assert np.allclose(demo.state["image"], compensated) and demo.state["light"] == pytest.approx(
        1.0
    )
    assert demo.state["legible_rows"] == 5
    demo.set(diameter_mm=0.05)  # 1/49 of the light: nearly black, no row legible
    assert demo.state["light"] == pytest.approx(1 / 49) and demo.state["image"].max() < 0.03
    assert demo.state["legible_rows"] == 0
    demo.set(diameter_mm=1.5)  # 18.4 times the light: the white page burns out
    assert (
        demo.state["light"] == pytest.approx(18.37, abs=0.01)
        and np.mean(demo.state["image"] >= 1.0) > 0.5
    )
    assert demo.state["legible_rows"] == 0  # burnt out: no row legible
    demo.set(fixed_exposure=False)
    assert 0.2 < demo.state["image"].mean() < 0.9


def test_pinhole_wall_is_sharp_at_the_longest_focal_length():
    """An ideal pinhole has no depth of field: the wall's square edges rise over about a pixel, not ten."""
    demo = pinhole_camera.pinhole_projection()
    demo.set(focal_mm=100, distance=4.0)
    row = demo.state["image"][30]  # above the box: only the wall
    steps = np.abs(np.diff(row))
    edge = int(np.argmax(steps))
    lo, hi = sorted((row[edge - 6], row[edge + 7]))
    rising = np.flatnonzero(
        (row[edge - 6 : edge + 7] > lo + 0.1 * (hi - lo))
        & (row[edge - 6 : edge + 7] < lo + 0.9 * (hi - lo))
    )
    assert hi - lo > 0.15 and len(rising) <= 2  # contrast 0.08 vs 0.26, a 10-90 % rise within 2 px


def test_letter_chart_rows_shrink():
    from camlab import scenes

    chart = scenes.letter_chart(0.3)
    ink = chart.texture < 0.5
    assert chart.texture.shape == (500, 600) and ink.any()
    rows = np.flatnonzero(ink.any(axis=1))
    runs = np.split(rows, np.flatnonzero(np.diff(rows) > 1) + 1)
    heights = [len(r) for r in runs]
    assert len(heights) == 5 and heights == sorted(heights, reverse=True)
    # lesson 02's chart, seen small, prints only its four largest rows: the same four
    four = scenes.letter_chart(0.3, rows=4).texture < 0.5
    assert (four[: runs[3][-1] + 1] == ink[: runs[3][-1] + 1]).all() and not four[runs[4]].any()
    with pytest.raises(ValueError, match="rows must be 1 to 5, got 6"):
        scenes.letter_chart(0.3, rows=6)


def test_thin_lens_and_dof_state():
    demo = lenses_and_distortion.thin_lens()
    demo.set(focal_mm=40, object_m=0.12)
    assert demo.state["image_distance"] == pytest.approx(0.06) and demo.state[
        "magnification"
    ] == pytest.approx(-0.5)
    assert not demo.state["object_held"] and "held" not in demo.view.fig.axes[0].get_title()
    demo.set(
        focal_mm=90, object_m=0.06
    )  # the slider inside f: the object is held at 1.05 f, and the readout says so
    assert demo.state["object_held"] and demo.state["image_distance"] == pytest.approx(0.09 * 21)
    assert (
        "z_o = 0.060 m is inside f (no real image): held at 0.095 m"
        in demo.view.fig.axes[0].get_title()
    )
    # far away (16 f, m = -1/15) the image is a tick without a head, with one dot where the rays meet
    demo.set(focal_mm=50, object_m=0.8)
    dots = [line for line in demo.view.fig.axes[0].lines if line.get_marker() == "o"]
    assert not demo.state["image_head"] and len(dots) == 1 and len(dots[0].get_xdata()) == 1
    demo.set(object_m=lenses_and_distortion.THIN_LENS_DEFAULT_M)
    assert demo.state["image_head"] and demo.state["magnification"] == pytest.approx(-2)
    dof = lenses_and_distortion.depth_of_field()
    dof.set(f_number=16.0, focus_m=1.2)
    wide = dof.state["far"] - dof.state["near"]
    dof.set(f_number=1.4)
    assert dof.state["far"] - dof.state["near"] < wide
    assert dof.state["coc_px"][1.2] == 0 and dof.state["coc_px"][0.6] > 2


def test_distortion_demo_classifies_and_undistorts():
    demo = lenses_and_distortion.lens_distortion()
    demo.set(k1=-0.3, k2=0.0, p1=0.0, p2=0.0)
    assert demo.state["kind"] == "barrel"
    demo.set(k1=0.2)
    assert demo.state["kind"] == "pincushion"
    c_dist = demo.state["corner0"].copy()
    demo.set(undistort=True)
    ideal = distortion.undistort_pixels(c_dist, lenses_and_distortion.K_D, [0.2, 0, 0, 0, 0])
    assert np.allclose(demo.state["corner0"], ideal)


def _texts(widget):
    """Every text a widget and its children show (the readouts beside the sliders)."""
    if isinstance(getattr(widget, "value", None), str):
        yield widget.value
    for child in getattr(widget, "children", ()):
        yield from _texts(child)


def test_sensor_demos_state():
    s = digital_sensor.sampling_aliasing()
    s.set(factor=6, prefilter=False)
    aliased = s.state["alias_contrast"]
    s.set(prefilter=True)
    assert s.state["alias_contrast"] < 0.5 * aliased
    b = digital_sensor.bit_depth_and_noise()
    b.set(bits=2, read_noise=0.0, exposure=1.0)
    assert b.state["levels"] == 4
    coarse = b.state["rms_error"]
    b.set(bits=10)
    assert b.state["rms_error"] < coarse
    d = digital_sensor.demosaicing()
    d.set(method="truth")
    assert d.state["psnr"] == np.inf
    d.set(method="camlab bilinear")
    ours = d.state["psnr"]
    d.set(method="OpenCV bilinear")
    assert ours >= d.state["psnr"] - 0.05


@pytest.mark.parametrize(
    "name",
    [
        "project_to_pixels",
        "focal_length_pixels",
        "best_pinhole_exposure",
        "pinhole_projection",
        "best_pinhole_diameter",
        "field_of_view",
        "distort_pixels",
        "f_number_for_depth",
        "newton_step",
        "quantize_image",
        "demosaic_bilinear",
    ],
)
def test_exercises_accept_reference_and_catch_mistakes(name):
    ex = all_exercises()[name]
    with contextlib.redirect_stdout(io.StringIO()) as out:
        assert check(name, ex.reference)
    assert "correct" in out.getvalue()
    for wrong, phrase in ex.wrong_variants:
        with pytest.raises(AssertionError, match=re.escape(phrase)):
            check(name, wrong)


def test_lesson_02_exercises_start_where_slips_show():
    """No degenerate first case: 1:1 focusing (z_i = z_o) or a start on the ray through x_d hides slips."""
    from camlab.exercises.lenses_and_distortion.fov import _field_of_view_cases
    from camlab.exercises.lenses_and_distortion.newton import _newton_cases

    f, _, z_o = _field_of_view_cases()[0]
    z_i = lens.image_distance(f, z_o)
    assert (
        not np.isclose(z_i, z_o) and z_i > 1.1 * f
    )  # focused close: z_i differs from f and from z_o
    x, x_d, _, _ = _newton_cases()[0]
    across = np.abs(x[:, 0] * x_d[:, 1] - x[:, 1] * x_d[:, 0]) / np.hypot(*x_d.T)
    assert across.min() > 0.01  # every start is off the ray through its x_d
    assert all(
        len(case[0]) != 2 for case in _newton_cases()
    )  # N = 2 would let solve(J, (N, 2)) pass silently


def test_newton_step_check_rejects_wrong_jacobians_with_the_right_radial_part():
    """Round 3's defect: from x = x_d only J's radial eigenvalue acts, so these passed."""

    def step(J_of):
        def newton_step(x, x_d, k1, k2):
            r2 = (x**2).sum(1, keepdims=True)
            L = 1 + k1 * r2 + k2 * r2**2
            return x - np.linalg.solve(J_of(x, L, r2, k1, k2), (x * L - x_d)[:, :, None])[:, :, 0]

        return newton_step

    def outer(x):
        return x[:, :, None] * x[:, None, :]

    def right(x, L, r2, k1, k2):
        return L[:, :, None] * np.eye(2) + (2 * k1 + 4 * k2 * r2)[:, :, None] * outer(x)

    def scalar(x, L, r2, k1, k2):
        return (L + (2 * k1 + 4 * k2 * r2) * r2)[:, :, None] * np.eye(2)

    def tilted(x, L, r2, k1, k2):
        return right(x, L, r2, k1, k2) + 5 * (r2[:, :, None] * np.eye(2) - outer(x))

    with contextlib.redirect_stdout(io.StringIO()):
        assert check("newton_step", step(right))
    with pytest.raises(AssertionError, match="you wrote x\\^T x"):
        check("newton_step", step(scalar))
    with pytest.raises(AssertionError, match="wrong answer"):
        check("newton_step", step(tilted))


def test_sensor_demos_show_what_they_claim():
    d = digital_sensor.demosaicing()
    d.set(pattern="GBRG", method="camlab bilinear")
    right = d.state["psnr"]
    d.set(assume="RGGB")  # the classic mistake: demosaic with the wrong pattern
    assert d.state["assumed"] == "RGGB" and d.state["psnr"] < right - 5
    raw_panel = d.figure.axes[0].images[0]
    assert raw_panel.get_array().shape[:2] == (digital_sensor.CROP,) * 2
    assert raw_panel.get_extent() == [
        -0.5,
        digital_sensor.CROP - 0.5,
        digital_sensor.CROP - 0.5,
        -0.5,
    ]  # no stretching
    s = digital_sensor.sampling_aliasing()
    scene, samples = (ax.images[0] for ax in s.figure.axes[:2])
    assert (
        scene.get_interpolation() == "antialiased"
    )  # 384 px drawn smaller: smoothed, no display moire
    for factor in (2, 4, 8):
        # the samples as blocks of factor x factor fine px, area-averaged to the screen like the scene: a block
        # 1.65 screen px wide (pixel size 2) drawn 'nearest' alternates 1 and 2 px and beats into a screen moire
        s.set(factor=factor)
        # (the demo averages them to the screen's pixels itself and draws those 1:1, so that the first draw,
        # a saved figure, and the live frame agree)
        assert (
            samples.get_interpolation() == "nearest"
            and samples.get_array().shape[0] < 384
            and s.state["samples"] == (384 // factor,) * 2
        )
        assert samples.get_extent() == [-0.5, 383.5, 383.5, -0.5]  # at the scene's scale
    s.set(factor=1)
    assert samples.get_interpolation() == "nearest" and samples.get_array().shape[0] < 384
    b = digital_sensor.bit_depth_and_noise()
    ax_img, ax_p = b.figure.axes[:2]
    # the row is marked by ticks beside the image (round 5: a line over it hid the very row the profile shows)
    # (F12-11: and short bars inside both edges, clear of the profiled pixels between them)
    assert list(ax_img.get_yticks()) == [150] and len(ax_img.lines) == 1
    marks = np.asarray(ax_img.lines[0].get_xdata(), float)
    assert np.nanmax(marks[:2]) < 30 and np.nanmin(marks[3:]) > digital_sensor.SIZE[0] - 30
    # no legend over the profile: the title names the lines, and the truth is drawn wide beneath the recording
    assert (
        ax_p.get_legend() is None
        and ax_p.lines[0].get_linewidth() > 2 * ax_p.lines[1].get_linewidth()
    )
    b.set(bits=1, exposure=1.0, read_noise=40.0)
    assert ax_p.lines[1].get_ydata().max() <= 1.0 < ax_p.get_ylim()[1]
    # the profile in display (sRGB) values, as the image: at the default 4 bits the shadows' bands show in it
    b.set(bits=4, exposure=0.3, read_noise=5.0)
    true, recorded = (np.asarray(line.get_ydata()) for line in ax_p.lines[:2])
    assert np.allclose(true, sensor.gamma_encode(b.state["clean_row"]))
    assert np.abs(recorded - true)[digital_sensor.UNIFORM].mean() > 0.03
    # lesson 03, cell "Interactive: bit depth and noise": the electrons the prose quotes, at the settings it names
    b.set(bits=4, exposure=0.3, read_noise=5.0)
    assert b.state["dn_electrons"] == pytest.approx(
        10000 / 3 / 15
    )  # ISO gain 3: full scale 3333 e-
    b.set(exposure=0.02)
    e = b.state["electrons"]
    assert (
        e["white"] == pytest.approx(200)
        and e["background"] == pytest.approx(40)
        and 0.5 < e["uniform"] < 2
    )
    assert f"dark uniform {e['uniform']:.1f}" in ax_p.get_title()
    b.set(
        bits=12
    )  # the ISO gain stops at 1 e-/DN (F12-3: it once reached 0.049 e-/DN): the whole title stays
    assert (
        "row 150" in ax_p.get_title()
        and "dark uniform 1.0" in ax_p.get_title()
        and "1 DN = 1.00" in ax_p.get_title()
    )
    assert b.state["gain"] == pytest.approx(10000 / 4095)
    b.set(bits=1, exposure=0.3)
    assert "1 DN = 3333" in ax_p.get_title()
    # exposure is light, ISO the gain before the converter: low light at base ISO bands, ISO 16 restores the codes
    b.set(bits=8, exposure=0.01, iso=1.0)
    few = b.state["codes"]
    b.set(iso=16.0)
    assert few <= 5 and b.state["codes"] > 8 * few


def test_focus_and_blur_follows_the_cone():
    demo = lenses_and_distortion.focus_and_blur()
    demo.set(f_number=2.8, object_m=1.0, sensor_mm=52.6)
    s = dict(demo.state)
    A = 0.05 / 2.8
    assert s["c"] == pytest.approx(A * abs(0.0526 - s["z_i"]) / s["z_i"])
    assert s["c"] == pytest.approx(lens.circle_of_confusion(0.05, 2.8, s["focus"], 1.0), rel=1e-9)
    demo.set(f_number=16.0)
    assert demo.state["far"] - demo.state["near"] > s["far"] - s["near"]


def test_similar_triangles_ratios_agree():
    demo = pinhole_camera.similar_triangles()
    for f, Z, Y in ((0.3, 1.2, -1.0), (1.0, 5.0, 0.4)):
        demo.set(f=f, Z=Z, Y=Y)
        assert demo.state["ratio_image"] == pytest.approx(demo.state["ratio_object"])
        assert demo.state["y"] == pytest.approx(f * Y / Z)


@pytest.mark.parametrize(
    "f, Z, Y",
    [
        (0.8, 3.0, -0.8),
        (0.3, 1.2, -1.0),
        (1.0, 1.2, 1.0),
        (1.0, 5.0, 0.4),
        (0.3, 5.0, 1.0),
        (0.8, 1.2, -0.8),
        (1.0, 1.2, -1.0),
    ],
)
def test_similar_triangles_labels_keep_off_the_triangles(f, Z, Y):
    """The image labels sit beyond their bars' tips: no corner of their boxes inside a shaded triangle."""
    demo = pinhole_camera.similar_triangles()
    demo.set(f=f, Z=Z, Y=Y)
    fig = demo.figure
    fig.canvas.draw()
    ax = fig.axes[0]
    triangles = [patch for patch in ax.patches if patch.get_alpha() in (0.15, 0.3)]
    assert len(triangles) == 2
    to_data = ax.transData.inverted()
    for text in ax.texts:
        if "cm" not in text.get_text():
            continue
        box = text.get_window_extent(fig.canvas.get_renderer()).expanded(1.05, 1.1)
        corners = to_data.transform(box.corners())
        for triangle in triangles:
            assert not triangle.get_path().contains_points(corners).any(), text.get_text()


def test_similar_triangles_at_y_zero_print_no_negative_zero_and_hide_collapsed_arrows():
    demo = pinhole_camera.similar_triangles()
    demo.set(Y=0.0)
    ax = demo.figure.axes[0]
    texts = " ".join(t.get_text() for t in ax.texts)
    assert (
        "-0.0" not in texts and "+0.0" not in texts and "y = 0.0 cm" in texts
    )  # as the title prints it
    arrows = [
        a
        for a in ax.texts
        if getattr(a, "arrowprops", None) and a.arrowprops.get("arrowstyle") == "<->"
    ]
    hidden = [a for a in arrows if not a.get_visible()]
    assert len(hidden) == 3  # Y, y and the real image's arrows: zero long


def test_cone_figure_is_drawn_to_scale_so_rays_run_straight():
    import matplotlib.pyplot as plt

    from camlab.plotting import optics

    fig, ax = plt.subplots()
    optics.draw_pinhole_cones(
        ax, 2e-3, focal_length=0.1, object_distance=1.0, heights=(-0.01, 0.01)
    )
    cones = [np.asarray(p.get_xy()) for p in ax.patches if p.get_alpha() == 0.35]
    before, after = cones[0][:4], cones[1][:4]  # the first point's cone before and after the hole
    (x_in, upper), (_, a) = before[0], before[1]
    (_, a2), (x_img, top) = after[0], after[1]
    assert (
        a == a2 and x_in == pytest.approx(300) and x_img == pytest.approx(-100)
    )  # drawn as cell 6: z right
    assert (a - upper) / (0 - x_in) == pytest.approx(
        (top - a) / x_img
    )  # the ray through the hole's top edge
    plt.close(fig)


def test_sensor_demos_read_as_the_lesson_says():
    p = digital_sensor.pixel_pitch()
    p.set(cx_offset=40)
    ax = p.figure.axes[0]
    assert ax.get_xlabel() == "u (px)" and ax.get_ylabel() == "v (px)" and len(ax.get_xticks()) > 3
    centre, principal = (line.get_xydata()[0] for line in ax.lines)
    assert np.allclose(centre, (159.5, 119.5)) and np.allclose(
        principal, (199.5, 119.5)
    )  # the shift reads on u
    # lesson 03, "Interactive: pixel pitch": f_x and the field of view in the figure itself, not only beside it
    p.set(cx_offset=0)
    for pitch, fx, fov in ((6.0, 500, 35.5), (2.0, 1500, 12.2), (15.0, 200, 77.3)):
        p.set(pitch_um=pitch)
        assert (
            f"f_x = f / s_x = {fx} px" in ax.get_title()
            and f"field of view {fov:.1f}°" in ax.get_title()
        )
    # round 5: off centre, the frame's edges seen from the principal point, not 2 atan(W / 2 / f_x)
    p.set(pitch_um=6.0, cx_offset=60)
    left, right = p.state["fov_left_right"]
    assert left == pytest.approx(np.degrees(np.arctan(220 / 500))) and right == pytest.approx(
        np.degrees(np.arctan(100 / 500))
    )
    assert "field of view 35.1°" in ax.get_title()
    # round i28: the top view is not mirrored. The ray it draws through the plane's left end is the one
    # that projects to u = -1/2 and holds the wider half (23.7°), on the world's left (X < 0), and the
    # image centre (u = 159.5 < c_x = 219.5) sits left of the axis there as it does in the image
    top = p.figure.axes[1]
    plane, rays, mark_top = top.lines[2], top.lines[3], top.lines[4]
    K = p.state["K"]
    x_left, x_right = plane.get_xdata()
    x_far_left, x_far_right = np.asarray(rays.get_xdata())[[1, 4]]
    z_far = rays.get_ydata()[1]
    assert x_left < 0 < x_right and x_far_left < 0 < x_far_right
    assert K[0, 0] * x_far_left / z_far + K[0, 2] == pytest.approx(-0.5)
    assert K[0, 0] * x_far_right / z_far + K[0, 2] == pytest.approx(319.5)
    assert np.degrees(np.arctan(-x_far_left / z_far)) == pytest.approx(left)
    assert mark_top.get_xdata()[0] < 0 and centre[0] < K[0, 2]
    p.set(cx_offset=-60)  # and the other way round
    x_far_left, x_far_right = np.asarray(rays.get_xdata())[[1, 4]]
    assert (
        top.lines[4].get_xdata()[0] > 0 and -x_far_left < x_far_right
    )  # the wider half now on the right
    # lesson 03, "Interactive: sampling and aliasing": the title's false-ring contrast (0.55 to 0.75 cycle/px) is
    # section 2's 0.34 and 0.12, and box samples give about the same at every pixel size (0.14 at the default 3)
    s = digital_sensor.sampling_aliasing()
    s.set(factor=6, prefilter=False)
    assert (
        "contrast 0.34" in s.figure.axes[1].get_title()
    )  # a full-contrast cosine's 0.354, point samples
    s.set(prefilter=True)
    assert "contrast 0.12" in s.figure.axes[1].get_title()
    assert any("false rings, 0.55 to 0.75 cycle/px: 0.12" in t for t in _texts(s.widget))
    s.set(factor=3)
    assert "contrast 0.14" in s.figure.axes[1].get_title()
    s.set(prefilter=False)
    s.set(factor=2)  # the square is the frame's edge: drawn just inside it, so it shows
    square = s.figure.axes[1].patches[0]
    assert (
        -0.5 < square.get_x() < 6
        and square.get_x() + square.get_width() < 383.5
        and square.get_visible()
    )
    s.set(factor=1)  # round 5: the limit lies beyond the frame, so no square is drawn
    assert not square.get_visible() and "beyond the frame" in s.figure.axes[1].get_title()
    s.set(factor=7)  # 54 samples of 7 fine px cover 378 of the 384: drawn there, not stretched
    assert s.figure.axes[1].images[0].get_extent() == [-0.5, 377.5, 377.5, -0.5]
    assert s.figure.axes[1].get_xlim() == (-0.5, 383.5)
    s.set(
        factor=6, prefilter=False, blur=0.5
    )  # a lens blur of half a pixel: the false rings all but gone
    assert (
        "contrast 0.03" in s.figure.axes[1].get_title()
        and "blur σ = 0.5 coarse px" in s.figure.axes[1].get_title()
    )
    assert any(
        "true rings, below 0.3 cycle/px: 0.27" in t for t in _texts(s.widget)
    )  # costs sharpness
    d = digital_sensor.demosaicing()
    psnr = {}
    for method in ("camlab bilinear", "OpenCV VNG", "OpenCV edge-aware"):
        d.set(method=method)
        psnr[method] = d.state["psnr"]
    # the zoom reaches the frame's right edge, and at u = 216 still shows the face's right side
    assert digital_sensor.ZOOM_MAX + digital_sensor.CROP == digital_sensor.SIZE[0]
    d.set(method="truth", zoom_u=216)
    zoom = d.figure.axes[2].images[0].get_array()
    assert np.ptp(np.asarray(zoom, float)) > 0.3
    d.set(zoom_u=120)
    # lesson 03: VNG several dB above bilinear, OpenCV's EA about the same as bilinear
    assert psnr["OpenCV VNG"] > psnr["camlab bilinear"] + 3
    assert abs(psnr["OpenCV edge-aware"] - psnr["camlab bilinear"]) < 0.5


def test_lesson_02_demos_show_what_the_prose_says():
    dof = lenses_and_distortion.depth_of_field()
    dof.figure.canvas.draw()
    ax_img = dof.figure.axes[0]
    # "drawn 1:1": the 480 x 360 image on exactly 480 x 360 whole canvas pixels, so neither the live frame nor a full
    # draw resamples it (they placed its pixels differently at 493 x 370)
    box = ax_img.get_window_extent()
    assert np.allclose([box.width, box.height], lenses_and_distortion.SIZE) and np.allclose(
        box.p0, np.round(box.p0)
    )
    assert (
        dof.figure.get_figwidth() * dof.figure.dpi + 8 + 300 <= 968
    )  # beside the controls at 1400 px
    blur = lenses_and_distortion.focus_and_blur()
    assert blur.state["c"] * 1e6 == pytest.approx(313, abs=1) and blur.state[
        "focus"
    ] == pytest.approx(1.0, abs=0.005)
    # the face-on view zooms: the largest disc fills 40-84 % of it at every setting, and the 4 µm Airy ring beside
    # a 1 µm disc at the focus ("shrinks to a dot, no larger than the Airy disc") is at least 9 screen pixels wide
    ax = blur.figure.axes[1]
    for setting in (
        {},
        {"object_m": 1.0},
        {"f_number": 1.4, "object_m": 0.3, "sensor_mm": lenses_and_distortion.SENSOR_MIN_MM},
        {"f_number": 32.0, "object_m": 1.0},
        {"f_number": 1.4, "object_m": 2.0, "sensor_mm": 60.0},
    ):
        blur.set(**{"f_number": 2.8, "object_m": 1.5, "sensor_mm": 52.63, **setting})
        largest = max(blur.state["c"], blur.state["airy"], lenses_and_distortion.COC_OK) * 1e6
        assert 0.4 <= largest / (2 * blur.state["half_um"]) <= 5 / 6, setting
        blur.figure.canvas.draw()
        px_per_um = ax.get_window_extent().width / (2 * blur.state["half_um"])
        if setting == {"object_m": 1.0}:
            assert (
                blur.state["c"] < blur.state["airy"] and blur.state["airy"] * 1e6 * px_per_um >= 9
            )
    blur.set(f_number=2.8, object_m=1.5, sensor_mm=lenses_and_distortion.SENSOR_MIN_MM)
    assert (
        blur.state["far"] == np.inf
    )  # the slider's low end focuses beyond every hyperfocal distance
    blur.set(sensor_mm=52.63)
    blur.set(f_number=32.0)
    assert (
        blur.state["airy"] > lenses_and_distortion.COC_OK
    )  # "at f/32 the Airy disc alone is larger than 30 µm"
    dist = lenses_and_distortion.lens_distortion()
    dist.set(k1=-0.35, undistort=True)
    assert dist.state["grid_error"] < 1e-6  # the grid panel straightens with the checkbox
    dist.set(k1=-0.1, k2=0.3, undistort=False)
    assert dist.state["kind"] == "mustache"  # the setting the lesson suggests for it
    # mustache: the top edge's middle moves in, the corner out (the radial profile's sign change)
    assert dist.state["edge_middle_shift"] < -1 and dist.state["corner_shift"] > 7
    assert (
        "mustache" in dist.figure.axes[1].get_title()
    )  # the kind is in the grid's title, not only the readout
    dist.set(k3=0.3)  # the k3 slider reaches the model: r^6 pushes the corner out further
    assert dist.state["corner_shift"] > 8
    # the zoom under the side view shows z_i and z_s apart at the default (0.9 mm on a 2 mm window)
    blur.set(f_number=2.8, object_m=1.5, sensor_mm=52.63)
    assert blur.state["zoom_half_mm"] == 1.0


def test_field_of_view_check_answers_the_prompts_question_and_names_a_one_tuple():
    """Exercise 1 asks how much narrower 0.3 m focus makes a 50 mm view; a passing check answers with the
    student's own function. A 1-tuple answer prints as a tuple, not as a number."""
    from camlab.exercises._core import _fmt
    from camlab.exercises.lenses_and_distortion.fov import field_of_view

    with contextlib.redirect_stdout(io.StringIO()) as out:
        assert check("field_of_view", field_of_view)
    assert "39.6 deg focused at infinity and 33.4 deg focused at 0.3 m" in out.getvalue()
    assert _fmt((0.5829,)) == "(0.5829,)" and _fmt((1.0, 2.0)) == "(1.0, 2.0)"


def test_demosaicing_readout_gives_psnr_per_channel_beside_bilinear_and_the_zoom_error():
    """I11-8: the readout once held only the heading; it now holds what the error maps show, in numbers."""
    demo = digital_sensor.demosaicing()
    demo.set(method="OpenCV VNG")
    text = next(t for t in _texts(demo.widget) if "PSNR" in t)
    vng, bilinear = (
        [float(v) for v in re.search(rf"{name}\s+([\d. ]+)", text).group(1).split()]
        for name in ("OpenCV VNG", "camlab bilinear")
    )
    assert len(vng) == len(bilinear) == 4 and all(
        a > b + 3 for a, b in zip(vng, bilinear, strict=True)
    )
    assert abs(vng[3] - demo.state["psnr"]) < 0.05  # the same score as the title's
    assert "zoom, mean |error| (linear):" in text


def test_bit_depth_demo_keeps_its_noise_field_when_only_the_bit_depth_moves():
    """H11-5: the same setting twice once differed in ~81,000 pixels (new noise on every move)."""
    demo = digital_sensor.bit_depth_and_noise()
    demo.set(bits=8, exposure=0.3, read_noise=5.0)
    first = np.asarray(demo.figure.axes[0].images[0].get_array()).copy()
    snr = demo.state["snr_background"]
    demo.set(bits=12)
    twelve = np.asarray(demo.figure.axes[0].images[0].get_array()).copy()
    demo.set(exposure=0.02)
    demo.set(exposure=0.3, bits=8)
    assert np.array_equal(np.asarray(demo.figure.axes[0].images[0].get_array()), first)
    assert demo.state["snr_background"] == snr
    # 8 to 12 bits: only the rounding moves, at most half an 8-bit step (in sRGB, steepest in the shadows)
    assert 0 < np.abs(twelve - first).mean() < 0.01
    demo.set(read_noise=6.0)  # another noise setting: another field
    assert not np.array_equal(np.asarray(demo.figure.axes[0].images[0].get_array()), first)


def test_bit_depth_readout_says_one_code_where_the_background_has_no_spread():
    """At exposure 1.0 and 4 bits every background pixel has one code: once printed as SNR 7.2e15 (V6).

    At the default 4 bits 96 % of it has one code: once printed as a measured SNR of 448 (W6).
    """
    from camlab.widgets import all_demos

    demo = all_demos()["bit_depth_and_noise"].builder()
    demo.set(exposure=1.0, iso=1.0)
    assert np.isinf(demo.state["snr_background"][1])

    def texts(widget):
        if isinstance(getattr(widget, "value", None), str):
            yield widget.value
        for child in getattr(widget, "children", ()):
            yield from texts(child)

    shown = list(texts(demo.widget))
    assert any("100.00 % on one code" in text for text in shown), shown
    # the default: a few stray pixels of 10^4 leave code 3; the spread they make is no SNR (W6: "measured 448")
    demo.set(exposure=0.3, iso=3.0)
    assert np.isinf(demo.state["snr_background"][1]) and demo.state["background_one_code"] > 0.95
    demo.set(bits=8)  # here the noise spans several codes and the measurement agrees with the model
    model, measured = demo.state["snr_background"]
    assert demo.state["background_one_code"] < 0.5 and abs(measured - model) < 0.5


def test_bit_depth_readout_flags_saturation_and_a_coin_flip_between_codes():
    """N12-2, O12-2: no SNR for levels above full scale, none measured on a clipped background.

    N12-5: none measured where one DN exceeds the background's noise (its pixels toss between two codes).
    """
    demo = digital_sensor.bit_depth_and_noise()

    def readout():
        return "".join(t for t in _texts(demo.widget) if "levels" in t)

    demo.set(bits=8, iso=16.0)  # exposure 0.3: 3000 e- on the white, full scale 625 e-
    assert demo.state["full_scale"] == pytest.approx(625)
    assert 0.1 < demo.state["background_clipped"] < 0.25 and np.isinf(
        demo.state["snr_background"][1]
    )
    assert "saturated (> full scale 625 e-)" in readout()
    assert "clipped at full scale" in readout()
    demo.set(iso=1.0, exposure=0.01)  # 20 e- in the background, 1 DN = 39 e-, noise 6.7 e-
    assert demo.state["noise_background"] == pytest.approx(np.sqrt(20 + 25))
    assert np.isinf(demo.state["snr_background"][1]) and "toss between 2 codes" in readout()
    assert demo.state["background_one_code"] < 0.9  # the 90 % rule alone let this through
    demo.set(iso=16.0)  # 1 DN = 2.45 e-: the measurement is back and agrees with the model
    model, measured = demo.state["snr_background"]
    assert demo.state["background_reason"] is None and abs(measured - model) < 0.2
