"""Demos for lesson 02: the thin lens, depth of field, and lens distortion."""

from __future__ import annotations

from types import SimpleNamespace

import ipywidgets as W
import numpy as np
from matplotlib.transforms import offset_copy

from .. import distortion, fixtures, lens, render, scenes
from ..plotting import images, optics, palette
from ._base import FigureView, build_demo, register, slider
from ._sensor_zoom import ZOOM_ARTISTS, ZOOM_LABELS, draw_sensor_zoom, update_sensor_zoom
from ._sensor_zoom import ZOOM_HALF_MM as ZOOM_HALF_MM  # re-exported: it lived here
from ._sensor_zoom import ZOOM_Y as ZOOM_Y  # re-exported: it lived here
from .controls import choice_slider, monospace

SIZE = (480, 360)
K_DOF = np.array([[560.0, 0.0, 239.5], [0.0, 560.0, 179.5], [0.0, 0.0, 1.0]])
PITCH = 5e-6
F_DOF = (
    K_DOF[0, 0] * PITCH * 10
)  # 28 mm lens on a 50 um-pitch sensor: K above, strong, visible blur
PITCH_DOF = F_DOF / K_DOF[0, 0]


THIN_LENS_DEFAULT_M = 0.075  # the thin-lens demo's object distance: 1.5 f for its 50 mm lens


@register(lesson="02", sweep={"focal_mm": [30, 50, 90], "object_m": [0.06, 0.3, 0.8]})
def thin_lens():
    """Principal rays through a thin lens: where the image forms and how large it is.

    Returns
    -------
    Demo
        The demo: controls ``focal_mm`` (f, mm) and ``object_m`` (the object's distance z_o, m;
        held at 1.05 f when asked closer than that), the ray diagram and ``state``
        (``image_distance`` in m, ``magnification``, ``image_head``, ``object_held``).
    """
    controls = {
        "focal_mm": slider(50, 20, 100, 1, "focal length f (mm)"),
        # default 1.5 f: an image twice the object's size, using the axes that m = -5 needs
        "object_m": slider(
            THIN_LENS_DEFAULT_M, 0.06, 1.0, 0.005, "object distance z_o (m)", readout_format=".3f"
        ),
    }
    view = FigureView(figsize=(8.6, 4))
    ax = view.fig.subplots()
    art = optics.draw_thin_lens(ax, 0.05, THIN_LENS_DEFAULT_M)
    # the foci over the object arrow, the image (and its dot) over the foci
    view.animate(
        art["object"],
        art["image"],
        art["image_dot"],
        *art["rays"],
        art["foci"],
        art["text"],
        art["F"],
        *art["zoom_rays"],
        art["zoom_image"],
        art["zoom_dot"],
        art["zoom_focus"],
        *art["zoom_spines"],
    )

    readout = W.HTML()  # the numbers beside the sliders, as in the other demos

    def update(values, state):
        f, asked = values["focal_mm"] * 1e-3, values["object_m"]
        zo = max(
            asked, f * 1.05
        )  # slider corner (f > 57 mm): keep the object outside the focal length, and say so
        state.update(optics.update_thin_lens(art, f, zo, requested=asked), object_held=zo != asked)
        zi, m = state["image_distance"], state["magnification"]
        readout.value = monospace(
            f"object  z_o = {zo:.3f} m = {zo / f:.2f} f\nimage   z_i = {zi:.3f} m = {zi / f:.2f} f\n"
            f"magnification m = {m:.3f}\n(inverted, {abs(m):.3g} x the object's height)"
        )

    return build_demo("thin_lens", controls, view, update, title="Thin lens", extra=[readout])


F_CONE = 0.05  # the focus-and-blur demo's 50 mm lens
COC_OK = 0.03e-3  # acceptable blur circle, 0.03 mm (a 35 mm camera viewed as a print)
PIXEL = 5e-6  # a pixel pitch to count the blur in (a 36 x 24 mm sensor of 7200 x 4800 pixels)
F_NUMBERS = [1.4, 2.0, 2.8, 4.0, 5.6, 8.0, 11.0, 16.0, 22.0, 32.0]
C_AXIS_UM = (0.1, 1e4)  # the c(z) panel's blur axis (µm, log): a 0.5 µm blur drawn at its value
SENSOR_MIN_MM = 50.04  # focuses at 62.6 m: beyond the hyperfocal distance of every f-number (f/1.4: 59.6 m at 30 µm)


def blur_curve_depths(focus: float) -> np.ndarray:
    """Depths (m) for the c(z) curve: 0.2-5 m, dense near ``focus`` where its V is narrower than 1 cm.

    Parameters
    ----------
    focus : float
        The distance the lens focuses (m).

    Returns
    -------
    (N,) array
        Sorted, unique depths (m): 300 from 0.2 to 5 m, 61 within ±3 % of ``focus``, and
        ``focus`` itself (where the curve's V touches zero).
    """
    near_focus = focus * (1 + np.linspace(-0.03, 0.03, 61))
    return np.unique(np.concatenate([np.linspace(0.2, 5.0, 300), near_focus, [focus]]))


def _focus_controls() -> dict:
    """The controls of :func:`focus_and_blur`: the f-number, the object's distance and the sensor's."""
    return {
        "f_number": choice_slider(F_NUMBERS, 2.8, "f-number N"),
        "object_m": slider(1.5, 0.3, 2.0, 0.01, "object distance z (m)"),
        "sensor_mm": slider(52.63, SENSOR_MIN_MM, 60.0, 0.01, "sensor behind lens z_s (mm)"),
    }


def _focus_figure(view: FigureView) -> SimpleNamespace:
    """The figure of :func:`focus_and_blur`.

    The cone through the lens with its zoom near the sensor, the blur disc face on and the blur
    circle c(z); returns its animated artists by name.
    """
    grid = view.fig.add_gridspec(2, 3, width_ratios=[1.5, 0.85, 1.1], height_ratios=[2.1, 1])
    ax_cone = view.fig.add_subplot(grid[0, 0])
    ax_disc = view.fig.add_subplot(grid[:, 1])
    ax_c = view.fig.add_subplot(grid[:, 2])
    ax_zoom = view.fig.add_subplot(grid[1, 0])  # last: fig.axes[1] stays the face-on view
    art = optics.draw_focus_cone(ax_cone)
    zoom = draw_sensor_zoom(ax_zoom)
    disc = optics.draw_blur_disc(ax_disc, coc_um=COC_OK * 1e6)
    (curve,) = ax_c.plot([], [], "k", label="c(z), this sensor position")
    band = ax_c.axvspan(
        1, 2, color=palette.PURPLE, alpha=0.3, lw=0, label="depth of field (c < 30 µm)"
    )
    # animated below: over the band; zorder 2.6, over the spines in a full draw as in a live frame
    coc_line = ax_c.axhline(COC_OK * 1e6, color=palette.PURPLE, ls="--", lw=1.2, zorder=2.6)
    airy = ax_c.axhline(1, color=palette.BROWN, ls=":", lw=1.8, zorder=2.6)
    (marker,) = ax_c.plot([], [], "o", color=palette.GREEN, mec="k", ms=7, zorder=3, clip_on=False)
    ax_c.set_title(" \n \n ", fontsize=9)  # room for the three lines update writes
    # when the band is off the axis or thinner than a pixel, a note says where the sharp zone is
    off_band = ax_c.text(0.97, 0.03, "", transform=ax_c.transAxes, ha="right", fontsize=8)
    off_band.set(color=palette.PURPLE, path_effects=palette.halo())
    ax_c.set(
        xlim=(0.2, 5.0),
        yscale="log",
        ylim=C_AXIS_UM,
        xlabel="object distance z (m)",
        ylabel="blur circle c (µm, log scale)",
    )
    # one legend for the three panels, under them: never over the cone, the discs, the band or the curve
    handles = {}
    for ax in (ax_cone, ax_disc, ax_c):
        for h, label in zip(*ax.get_legend_handles_labels(), strict=True):
            handles.setdefault(label, h)
    view.fig.legend(
        handles.values(), handles.keys(), loc="outside lower center", ncol=4, fontsize=8
    )
    view.animate(
        *[
            art[k]
            for k in (
                "stop",
                "lens",
                "cone_in",
                "cone_out",
                "rays",
                "beyond",
                "point",
                "sensor",
                "focus",
                "blur",
                "text",
            )
        ],
        *[disc[k] for k in ("grid", "blur", "ok", "airy", "bar", "bar_text", "text")],
        *[zoom[k] for k in ZOOM_ARTISTS + ZOOM_LABELS],
        *zoom["cone"].axes.spines.values(),  # over the moving cone, as a full draw paints them
        curve,
        band,
        coc_line,
        airy,
        marker,
        ax_c.title,
        off_band,
    )
    return SimpleNamespace(
        art=art,
        zoom=zoom,
        disc=disc,
        curve=curve,
        band=band,
        airy=airy,
        marker=marker,
        ax_c=ax_c,
        off_band=off_band,
    )


@register(
    lesson="02",
    sweep={
        "f_number": [1.4, 8.0, 16.0, 32.0],
        "object_m": [0.3, 1.0, 2.0],
        "sensor_mm": [SENSOR_MIN_MM, 52.63, 60.0],
    },
)
def focus_and_blur():
    """The cone of light from a point through the aperture, a movable sensor and the blur it cuts.

    The blur disc the sensor cuts (face on, zoomed to fit, over the sensor's pixels) and the
    blur circle c(z) of every depth.

    Returns
    -------
    Demo
        The demo: controls ``f_number`` (N), ``object_m`` (the point's distance, m) and
        ``sensor_mm`` (the sensor's distance behind the 50 mm lens, mm), the figure (side
        view with its true-scale zoom, blur disc, c(z) curve with the depth of field) and
        ``state`` (``z_i``, ``A``, ``c``, ``airy`` in m; ``half_um``, ``grid_px``,
        ``zoom_half_mm``; ``focus``, ``near``, ``far`` in m; ``c_px``; ``marker_off_scale``).
    """
    controls = _focus_controls()
    view = FigureView(figsize=(9.8, 6.2))
    parts = _focus_figure(view)
    art, zoom, disc, curve, band = parts.art, parts.zoom, parts.disc, parts.curve, parts.band
    airy, marker, ax_c = parts.airy, parts.marker, parts.ax_c
    readout = W.HTML()  # the numbers beside the sliders, as in the other demos

    def update(values, state):
        N, z_o, z_s = float(values["f_number"]), values["object_m"], values["sensor_mm"] * 1e-3
        state.update(optics.update_focus_cone(art, F_CONE, N, z_o, z_s))
        state.update(optics.update_blur_disc(disc, state["c"], state["airy"], PIXEL))
        state.update(update_sensor_zoom(zoom, state["A"], state["z_i"], z_s, state["c"]))
        s = float(lens.object_distance(F_CONE, z_s))  # the distance this sensor position focuses
        z = blur_curve_depths(s)
        # c = 0 at s: a floor below the axis, so the V runs off its bottom there
        curve.set_data(
            z, np.maximum(lens.circle_of_confusion(F_CONE, N, s, z) * 1e6, C_AXIS_UM[0] / 2)
        )
        airy.set_ydata([state["airy"] * 1e6] * 2)
        dof = lens.depth_of_field(F_CONE, N, s, COC_OK)
        band.set_x(dof.near)
        band.set_width(
            max(min(dof.far, 10.0) - dof.near, 0.0)
        )  # focused far, the band may start beyond the view
        # the marker at its value; below the axis's floor, a down-pointing triangle on the bottom edge (off scale)
        c_um = state["c"] * 1e6
        below = c_um < C_AXIS_UM[0]
        marker.set_data([z_o], [C_AXIS_UM[0] if below else c_um])
        marker.set_marker("v" if below else "o")
        far = f"{dof.far:.3f} m" if np.isfinite(dof.far) else "infinity"
        # the band beyond the axis, or under a pixel: a note at the edge it is near says where it is
        beyond, thin = dof.near > 5.0, min(dof.far, 5.0) - dof.near < 0.03
        note = (
            f"sharp zone {dof.near:.3g} m to {far} →"
            if beyond
            else f"← sharp {dof.near:.3f} to {far}: too thin"
        )
        parts.off_band.set(text=note if thin else "", x=0.97 if beyond else 0.06)
        parts.off_band.set_ha("right" if beyond else "left")
        soft = (
            "but the Airy disc alone > 30 µm" if state["airy"] > COC_OK else " "
        )  # 3 lines always: the layout
        ax_c.set_title(
            f"focused at {s:.3f} m; geometrically sharp\nfrom {dof.near:.3f} m to {far}\n{soft}",
            fontsize=9,
        )
        state.update(
            focus=s,
            near=dof.near,
            far=dof.far,
            c_px=state["c"] / PIXEL,
            marker_off_scale=bool(below),
        )
        readout.value = monospace(
            f"f/{N:g}, sensor at {z_s * 1e3:.2f} mm: focused at {s:.3f} m\n"
            f"point at {z_o:.2f} m: image at {state['z_i'] * 1e3:.2f} mm\n"
            f"blur c = {c_um:.3g} µm = {_px_text(state['c'] / PIXEL)} px of 5 µm\n"
            f"Airy disc {state['airy'] * 1e6:.3g} µm\nsharp (c &lt; 30 µm) {dof.near:.3f} m to {far}"
        )

    return build_demo(
        "focus_and_blur",
        controls,
        view,
        update,
        title="Focus, aperture and the blur circle",
        extra=[readout],
    )


def _px_text(px: float) -> str:
    """A blur in pixels as the lesson quotes it: whole pixels from 10 up (63), two digits below (0.1)."""
    return f"{px:.0f}" if px >= 10 else f"{px:.2g}"


def _dof_controls() -> dict:
    """The controls of :func:`depth_of_field`: the f-number and the focus distance."""
    return {
        "f_number": choice_slider([1.4, 2.0, 2.8, 4.0, 5.6, 8.0, 11.0, 16.0], 2.8, "f-number N"),
        "focus_m": slider(1.2, 0.5, 4.0, 0.05, "focus distance (m)"),
    }


def _dof_figure(view: FigureView) -> SimpleNamespace:
    """The figure of :func:`depth_of_field`.

    The rendered scene 1:1 on canvas pixels above its blur curve with the sharp band and the planes;
    returns the scene, the curve's depths, the planes and the animated artists by name.
    """
    width, height = view.fig.bbox.width, view.fig.bbox.height
    # canvas pixels: room for the curve's y label, and for the curve under the image
    left, bottom = 64, 300
    ax_img = view.fig.add_axes((left / width, bottom / height, SIZE[0] / width, SIZE[1] / height))
    ax_c = view.fig.add_axes((left / width, 68 / height, SIZE[0] / width, 194 / height))
    view.fig.set_layout_engine("none")  # fixed pixel boxes, not constrained layout
    scene = fixtures.depth_of_field_scene()
    im = images.show_image(ax_img, np.zeros((SIZE[1], SIZE[0], 3)))
    z = np.linspace(0.3, 5, 400)
    (curve,) = ax_c.plot(
        z, np.full_like(z, 100.0), "k", zorder=3
    )  # over the plane markers, live and redrawn
    band = ax_c.axvspan(1, 2, color=palette.PURPLE, alpha=0.15, lw=0)
    # zorder 2.6: over the spines in a full draw too, as a live frame paints them over the cached background
    lines = [ax_c.axhline(2 * PITCH_DOF * 1e6, color=palette.PURPLE, ls="--", lw=1.2, zorder=2.6)]
    planes = {"small board": 0.6, "chart": 1.2, "large board": 2.4, "wall": 4.0}
    for zp in planes.values():  # dark enough on the purple band (WCAG 1.4.11)
        lines.append(ax_c.axvline(zp, color="0.4", lw=1.2, ls=(0, (4, 2)), zorder=2.6))
    # the planes named on a top axis, each above its line: no legend over the band or the curve
    top = ax_c.secondary_xaxis("top")
    top.set_xticks(list(planes.values()), list(planes), fontsize=8)
    ax_c.set_xlim(0.3, 5)
    ax_c.set_ylim(5, 5000)
    ax_c.set_yscale("log")  # from the 2-px line to the blur at f/16 and f/1.4 on one readable scale
    ax_c.set_xlabel(
        "depth z (m); purple band: sharp, c < 2 px (purple dashes: 2 px = "
        f"{2 * PITCH_DOF * 1e6:.0f} µm)",
        fontsize=9,
    )
    ax_c.set_ylabel("blur circle c (µm, log scale)")
    ax_img.set_title(
        f"f = {F_DOF * 1e3:.0f} mm thin lens; planes at 0.6, 1.2, 2.4 and 4 m", fontsize=10
    )
    ax_img.set_xlabel(
        f"sensor: {SIZE[0]} x {SIZE[1]} pixels of {PITCH_DOF * 1e6:.0f} µm "
        f"({SIZE[0] * PITCH_DOF * 1e3:.0f} x {SIZE[1] * PITCH_DOF * 1e3:.0f} mm)",
        fontsize=9,
    )
    # the limits in the figure too (a screenshot keeps them), under the curve's x label: never over the band (an
    # axes' text, 62 px under it: a saved figure draws an axes' animated artists, not the figure's)
    limits = ax_c.text(
        0.5,
        0,
        "",
        ha="center",
        va="bottom",
        fontsize=9,
        clip_on=False,
        transform=offset_copy(ax_c.transAxes, fig=view.fig, y=-62, units="dots"),
    )
    view.animate(
        im, curve, band, limits, *lines
    )  # the lines too: over the moving band, live as in a full draw
    return SimpleNamespace(
        scene=scene, im=im, z=z, curve=curve, band=band, planes=planes, limits=limits
    )


@register(
    lesson="02", sweep={"f_number": [1.4, 4.0, 16.0], "focus_m": [0.5, 0.55, 0.6, 1.2, 2.4, 4.0]}
)
def depth_of_field():
    """A scene of planes at 0.6, 1.2, 2.4 and 4 m rendered with thin-lens blur, above its blur curve.

    Returns
    -------
    Demo
        The demo: controls ``f_number`` (N) and ``focus_m`` (the focus distance, m), the
        figure (the rendered scene 1:1 above c(z) with the sharp band, c < 2 px) and ``state``
        (``near`` and ``far`` limits in m, ``coc_px`` the blur circle in px of each plane by
        its depth).
    """
    controls = _dof_controls()
    # 6.5 in at 90 dpi, 585 px wide: it fits beside the 300 px controls in JupyterLab's 968 px output area. The
    # 480 x 360 image is drawn exactly 1:1 on whole canvas pixels (so 2 px of blur is what you see, and the live
    # frame and a full draw place the same pixels: no resampling either way), the blur curve under it
    view = FigureView(figsize=(6.5, 7.8))
    parts = _dof_figure(view)
    scene, im, z, curve, band = parts.scene, parts.im, parts.z, parts.curve, parts.band
    planes, limits = parts.planes, parts.limits
    # the blur of each plane beside the sliders: canvas text costs ~4 ms per line per redraw
    readout = W.HTML()

    def update(values, state):
        N, s = float(values["f_number"]), values["focus_m"]
        # supersample=1: the blur itself anti-aliases, and it halves the update time
        out = render.render(
            scene, K_DOF, SIZE, defocus=render.Defocus(N, s, PITCH_DOF, F_DOF), supersample=1
        )
        im.set_data(out.irradiance)
        c = lens.circle_of_confusion(F_DOF, N, s, z)
        curve.set_ydata(c * 1e6)
        dof = lens.depth_of_field(F_DOF, N, s, 2 * PITCH_DOF)
        far = min(dof.far, 5.0)
        band.set_x(dof.near)
        band.set_width(max(far - dof.near, 0.0))
        state.update(
            near=dof.near,
            far=dof.far,
            coc_px={
                zp: float(lens.circle_of_confusion(F_DOF, N, s, zp)) / PITCH_DOF
                for zp in (0.6, 1.2, 2.4, 4.0)
            },
        )
        far_text = f"{dof.far:.2f} m" if np.isfinite(dof.far) else "infinity"
        limits.set_text(
            f"f/{N:g}, focused at {s:.2f} m: sharp (purple band) from {dof.near:.2f} m to {far_text}"
        )
        blurs = "\n".join(
            f"  {name:<12}{f'{zp:g} m':>5}: {state['coc_px'][zp]:5.1f}"
            for name, zp in planes.items()
        )
        readout.value = monospace(
            f"N = {N}, focused at {s:.2f} m\nsharp (c &lt; 2 px) from {dof.near:.2f} m to {far_text}\n"
            f"blur circle (px):\n{blurs}"
        )

    return build_demo(
        "depth_of_field", controls, view, update, title="Depth of field", extra=[readout]
    )


K_D = np.array([[420.0, 0.0, 239.5], [0.0, 420.0, 179.5], [0.0, 0.0, 1.0]])
# each pixel's normalised radius, and the purple that marks pixels beyond the fold (no ideal ray reaches them)
R_PIX = np.hypot(
    *np.meshgrid((np.arange(SIZE[0]) - 239.5) / 420, (np.arange(SIZE[1]) - 179.5) / 420)
)
FOLD_RGBA = np.array([0xAA, 0x33, 0x77, 0xD9]) / 255  # palette.PURPLE at alpha 0.85


def _grid_lines(n: int = 9, samples: int = 60) -> np.ndarray:
    """(2n, samples, 2) ideal pixel polylines of a grid covering the image."""
    us = np.linspace(0, SIZE[0] - 1, n)
    vs = np.linspace(0, SIZE[1] - 1, n)
    t = np.linspace(0, 1, samples)
    lines = [np.column_stack([np.full(samples, u), t * (SIZE[1] - 1)]) for u in us]
    lines += [np.column_stack([t * (SIZE[0] - 1), np.full(samples, v)]) for v in vs]
    return np.array(lines)


def _shifts(d: np.ndarray, ideal: np.ndarray) -> dict:
    """The radial shifts (px, + outwards) of the frame's corner and top edge's middle, the longest shift.

    The longest shift is the length of the largest displacement of a grid point, not its
    largest x or y component.
    """
    probe = np.array([[0.0, 0.0], [K_D[0, 2], 0.0]])
    shift = np.linalg.norm(distortion.distort_pixels(probe, K_D, d) - K_D[:2, 2], axis=1)
    shift -= np.linalg.norm(probe - K_D[:2, 2], axis=1)
    points = ideal.reshape(-1, 2)
    moved = np.linalg.norm(distortion.distort_pixels(points, K_D, d) - points, axis=1)
    return {
        "corner_shift": float(shift[0]),
        "edge_middle_shift": float(shift[1]),
        "max_shift": float(moved.max()),
    }


def _distortion_controls() -> dict:
    """The controls of :func:`lens_distortion`: the five coefficients and the undistort box."""
    return {
        "k1": slider(-0.25, -0.4, 0.3, 0.01, "k1 (radial)"),
        "k2": slider(0.05, -0.1, 0.3, 0.005, "k2 (radial)"),
        "k3": slider(0.0, -0.2, 0.3, 0.01, "k3 (radial, r^6)"),
        "p1": slider(0.0, -0.04, 0.04, 0.002, "p1 (tangential)", readout_format=".3f"),
        "p2": slider(0.0, -0.04, 0.04, 0.002, "p2 (tangential)", readout_format=".3f"),
        "undistort": W.Checkbox(value=False, description="undistort (cv2.remap with our map)"),
    }


def _distortion_figure(view: FigureView) -> SimpleNamespace:
    """The figure of :func:`lens_distortion`.

    The rendered board with its true corners and a grid through the lens over the straight one;
    returns the board, the ideal grid and the animated artists by name.
    """
    ax_img, ax_grid = view.fig.subplots(1, 2)
    board = scenes.checkerboard((11, 8), 0.04, t=(-0.2, -0.14, 0.45), px_per_square=32)
    # drawn smaller than its 480 x 360 pixels: area-averaged, or the square edges alias
    im = images.show_image(ax_img, np.zeros(SIZE[::-1]), vmax=255, interpolation="antialiased")
    fold = ax_img.imshow(
        np.zeros((SIZE[1], SIZE[0], 4)), interpolation="nearest"
    )  # beyond the fold
    (dots,) = ax_img.plot([], [], "o", color=palette.RED, ms=3.5, path_effects=palette.halo())
    ideal = _grid_lines()
    for k, ln in enumerate(ideal):  # the undistorted grid, drawn once in grey behind the bent one
        ax_grid.plot(
            *ln.T, color=palette.GREY, lw=0.8, ls="--", label="no lens" if k == 0 else None
        )
    bent = [
        ax_grid.plot(
            *ln.T, color=palette.BLUE, lw=1.2, label="through the lens" if k == 0 else None
        )[0]
        for k, ln in enumerate(ideal)
    ]
    ax_grid.set_xlim(-60, SIZE[0] + 60)
    ax_grid.set_ylim(SIZE[1] + 60, -60)
    ax_grid.set_aspect("equal")
    ax_grid.plot(
        [-0.5, SIZE[0] - 0.5, SIZE[0] - 0.5, -0.5, -0.5],
        [-0.5, -0.5, SIZE[1] - 0.5, SIZE[1] - 0.5, -0.5],
        "k",
        lw=1,
        label="image frame",
    )
    ax_grid.set_xlabel("u (px)")
    ax_grid.set_ylabel("v (px)")
    legend = ax_grid.legend(  # below the grid, inside the figure: constrained layout makes room
        fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=3, borderaxespad=0.3
    )  # animated: update names the blue grid per mode
    img_title = ax_img.set_title(" \n ", fontsize=10)  # two lines, as update writes
    grid_title = ax_grid.set_title(" \n ", fontsize=10)  # two lines, as update writes
    view.animate(im, fold, dots, *bent, img_title, grid_title, legend)
    return SimpleNamespace(
        legend=legend,
        board=board,
        im=im,
        fold=fold,
        dots=dots,
        ideal=ideal,
        bent=bent,
        img_title=img_title,
        grid_title=grid_title,
    )


@register(
    lesson="02",
    sweep={
        "k1": [-0.4, -0.35, 0.0, 0.25, 0.3],
        "k2": [-0.1, 0.1, 0.3],
        "k3": [-0.2, 0.3],
        "p1": [-0.04, 0.03],
        "p2": [-0.03, 0.04],
        "undistort": [True, False],
    },
)
def lens_distortion():
    """Distortion sliders warp a rendered checkerboard and a grid; tick 'undistort' to undo it in both.

    Returns
    -------
    Demo
        The demo: controls ``k1``, ``k2``, ``k3`` (radial), ``p1``, ``p2`` (tangential) and
        ``undistort``, the figure (the rendered board with its true corners, a grid through
        the lens over the straight one) and ``state`` (``kind`` of distortion,
        ``corner_shift`` and ``edge_middle_shift`` radial shifts in px, ``corner0``,
        ``max_shift`` in px (the longest shift's length), ``beyond_fold`` (pixels past the fold,
        painted purple), ``grid_error`` in px after undistorting).
    """
    controls = _distortion_controls()
    view = FigureView(figsize=(8.6, 4.5))
    parts = _distortion_figure(view)
    board, im, dots, ideal, bent = parts.board, parts.im, parts.dots, parts.ideal, parts.bent
    img_title, grid_title = parts.img_title, parts.grid_title
    readout = W.HTML()  # numbers beside the sliders: canvas text costs ~4 ms per line per redraw

    def update(values, state):
        d = np.array([values["k1"], values["k2"], values["p1"], values["p2"], values["k3"]])
        # supersample=1: every k change rebuilds the inverse-distortion map, 4x cheaper at 1x
        out = render.render(board, K_D, SIZE, dist=d, supersample=1)
        img = out.image
        corners = out.truth.corners()
        through = [distortion.distort_pixels(ln, K_D, d) for ln in ideal]
        if values["undistort"]:
            img = distortion.undistort_image(img, K_D, d)
            corners = distortion.undistort_pixels(corners, K_D, d)
            through = [
                distortion.undistort_pixels(ln, K_D, d) for ln in through
            ]  # back onto the straight grid
        im.set_data(img)
        r_fold = distortion.max_valid_radius(d)  # radial terms only: 3.0 when there is no fold
        beyond = (R_PIX > r_fold * distortion.radial_scale(r_fold, d)) & (not values["undistort"])
        parts.fold.set_data(np.where(beyond[..., None], FOLD_RGBA, 0.0))
        dots.set_data(corners[:, 0], corners[:, 1])
        for line, ln in zip(bent, through, strict=True):
            line.set_data(*ln.T)
        img_title.set_text(
            "the rendered board, undistorted\n(red: the true corners, undistorted)"
            if values["undistort"]
            else "the rendered board, as the lens\nrecords it (red: the true corners)"
        )
        parts.legend.get_texts()[1].set_text(
            "lens, then undistorted" if values["undistort"] else "through the lens"
        )
        kind = distortion.classify_distortion(d, r_max=float(np.hypot(*SIZE) / 2 / K_D[0, 0]))
        grid_title.set_text(
            f"the grid through the lens ({kind}),\nthen undistorted: straight again"
            if values["undistort"]
            else f"a straight grid through the lens: {kind}\n(grey: the same grid without it)"
        )
        state.update(
            _shifts(d, ideal),
            kind=kind,
            corner0=corners[0],
            beyond_fold=int(beyond.sum()),
            grid_error=float(
                max(np.abs(ln - i).max() for ln, i in zip(through, ideal, strict=True))
            ),
        )
        readout.value = monospace(
            f"distortion: {kind}\nlargest shift |Δ| {state['max_shift']:.1f} px\n"
            + (
                "left: undistorted, lines straight again"
                if values["undistort"]
                else "left: as the lens records it"
            )
        )

    return build_demo(
        "lens_distortion",
        controls,
        view,
        update,
        title="Lens distortion (k1, k2, p1, p2, k3)",
        extra=[readout],
    )
