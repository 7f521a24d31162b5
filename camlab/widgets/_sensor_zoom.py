"""The true-scale zoom around the sensor under lesson 02's side view.

Under :func:`camlab.widgets.lenses_and_distortion.focus_and_blur`'s side view: where the cone of
light crosses at z_i and the sensor cuts it in the blur c.
"""

from __future__ import annotations

import numpy as np

from ..plotting import palette

# The zoom under the side view: the last few millimetres before the sensor at true scale (one scale both ways),
# where the cone crosses at z_i and the sensor cuts it in the blur c. Its axes run in units of the window's
# half-width W (fixed limits: the demo stays blittable); W steps so that z_i and z_s both fit, and a scale bar
# gives it in mm.
ZOOM_HALF_MM = (0.2, 0.4, 1.0, 2.0, 4.0, 10.0, 20.0)  # the scale bar is W / 4: 0.05 mm to 5 mm
ZOOM_Y = 0.3  # the zoom's half-height, in units of W: as wide as the side view above it
ZOOM_ARTISTS = ("cone", "cone_out", "rays", "beyond", "sensor", "blur", "focus", "bar", "bar_text")
ZOOM_LABELS = ("z_i", "z_s", "c")


def draw_sensor_zoom(ax) -> dict:
    """Artists of the true-scale zoom around the sensor (see :func:`update_sensor_zoom`)."""
    light = dict(color=palette.ORANGE, alpha=0.22, lw=0)
    zoom = {
        "cone": ax.fill([0, 0, 0], [0, 0, 0], **light)[0],
        "cone_out": ax.fill([0, 0, 0], [0, 0, 0], **light)[0],
        # white halos, as in the side view: the rays run over their own light cone
        "rays": ax.plot([], [], color=palette.ORANGE, lw=1.2, path_effects=palette.halo(1.2))[0],
        "beyond": ax.plot(
            [], [], color=palette.ORANGE, lw=1.2, ls=":", path_effects=palette.halo(1.2)
        )[0],
        "sensor": ax.plot([], [], color="0.3", lw=2)[0],
        "blur": ax.plot([], [], color=palette.RED, lw=5, solid_capstyle="butt")[0],
        "focus": ax.plot([], [], "x", color=palette.RED, ms=7, mew=2)[0],
        "bar": ax.plot(
            [-0.95, -0.7], [-0.9 * ZOOM_Y] * 2, color="k", lw=2.5, solid_capstyle="butt"
        )[0],
        "bar_text": ax.text(-0.68, -0.9 * ZOOM_Y, "", fontsize=8, va="center"),
    }
    for key, (ha, va) in zip(
        ZOOM_LABELS, (("center", "bottom"), ("left", "top"), ("left", "center")), strict=True
    ):
        label = {"z_i": "$z_i$", "z_s": "$z_s$", "c": "$c$"}[
            key
        ]  # mathtext, as the prose typesets them
        zoom[key] = ax.text(0, 0, label, fontsize=9, ha=ha, va=va, path_effects=palette.halo(2))
    ax.axhline(0, color="0.4", lw=0.8, zorder=0.5)
    ax.set(xlim=(-1, 1), ylim=(-ZOOM_Y, ZOOM_Y), xticks=[], yticks=[])
    ax.set_aspect("equal")
    ax.set_title("near the sensor, true scale (zoom)", fontsize=9)
    return zoom


def update_sensor_zoom(zoom: dict, A: float, z_i: float, z_s: float, c: float) -> dict:
    """Redraw the zoom for aperture ``A``, image point ``z_i`` and sensor ``z_s`` (metres); blur ``c`` there.

    The window is centred between z_i and z_s, its half-width W the smallest step with both
    inside 70 % of it and the blur bar inside 60 % of its height (clear of the z_s label above
    it); heights use the same scale, so the cone's angle is true. Returns ``{"zoom_half_mm"}``.
    """
    zi, zs, a = z_i * 1e3, z_s * 1e3, A / 2 * 1e3  # mm
    centre = (zi + zs) / 2
    fits = (  # both points inside 70 % of the width, the blur bar inside 60 % of the height
        w for w in ZOOM_HALF_MM if abs(zs - zi) / 2 <= 0.7 * w and c / 2 * 1e3 <= 0.6 * ZOOM_Y * w
    )
    W = next(fits, ZOOM_HALF_MM[-1])

    def ray(z):  # the upper marginal ray's height (mm): a at the lens, 0 at z_i
        return a * (1 - z / zi)

    x_left, x_s, x_i = -1.0, (zs - centre) / W, (zi - centre) / W
    z_left = centre - W
    y_left, y_s = ray(z_left) / W, ray(zs) / W
    x_meet = min(x_i, x_s)  # the light stops at the sensor
    y_meet = 0.0 if zi < zs else y_s
    zoom["cone"].set_xy([[x_left, y_left], [x_meet, y_meet], [x_meet, -y_meet], [x_left, -y_left]])
    zoom["cone_out"].set_xy(
        [[x_i, 0], [x_s, y_s], [x_s, -y_s]] if zi < zs else [[x_s, 0], [x_s, 0], [x_s, 0]]
    )
    zoom["rays"].set_data(
        [x_left, x_meet, x_s, np.nan, x_left, x_meet, x_s],
        [y_left, y_meet, y_s, np.nan, -y_left, -y_meet, -y_s],
    )
    zoom["beyond"].set_data(
        *(([x_s, x_i, np.nan, x_s, x_i], [y_s, 0, np.nan, -y_s, 0]) if zi > zs else ([], []))
    )
    zoom["sensor"].set_data([x_s, x_s], [-ZOOM_Y, ZOOM_Y])
    half_c = max(c / 2 * 1e3 / W, 0.006)  # a bar at least ~2 screen pixels tall
    zoom["blur"].set_data([x_s, x_s], [-half_c, half_c])
    zoom["focus"].set_data([x_i], [0])
    zoom["bar_text"].set_text(f"{W / 4:g} mm")  # the bar spans a quarter of W (0.25 axis units)
    # z_i and z_s close: both labels go right of the sensor, where no light is, z_i under the
    # axis and c above it, clear of the red x, the marginal rays and each other
    close = abs(x_i - x_s) < 0.15
    zoom["z_i"].set_position((x_s + 0.04, -0.12 * ZOOM_Y) if close else (x_i, 0.15 * ZOOM_Y))
    zoom["z_i"].set_ha("left" if close else "center")
    zoom["z_i"].set_va("top" if close else "bottom")
    zoom["z_s"].set_position((x_s + 0.03, 0.95 * ZOOM_Y))
    zoom["c"].set_position(
        (x_s + 0.04, 0.22 * ZOOM_Y)
        if close
        else (x_s + 0.04, min(half_c, 0.7 * ZOOM_Y) * 0.5 + 0.02)
    )
    return {"zoom_half_mm": W}
