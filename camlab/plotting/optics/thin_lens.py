"""Thin lenses drawn (lesson 02).

The ray diagram, the focus cone of depth of field and the blur disc seen face on.

Each ``draw_*`` function draws once and returns a dict of artists; its ``update_*`` partner
moves those artists, so widgets can redraw in place.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ... import lens as _lens
from .. import palette

__all__ = [
    "draw_thin_lens",
    "update_thin_lens",
    "draw_focus_cone",
    "update_focus_cone",
    "draw_blur_disc",
    "update_blur_disc",
]


THIN_LENS_X = (-12.0, 7.0)  # the ray diagram's horizontal range, in units of f
IMAGE_HEAD_MIN = 0.25  # object heights: a shorter image arrow is drawn without its head
THIN_LENS_Y = (
    -5.6,
    1.4,
)  # ... and its vertical range, in object heights: a real image is inverted (m < 0), so
# the room is below the axis, down to m = -5.6 (z_o = 1.18 f, z_i = 6.6 f: the x range)


def draw_thin_lens(ax, focal_length: float, object_distance: float) -> dict:
    """A thin-lens ray diagram: object arrow, lens, foci F and F', the three principal rays, image arrow.

    Distances are drawn in units of f (the diagram depends only on z_o / f) and heights in
    units of the object's height, on fixed axes: as the object nears F the image runs off to
    the right and grows. The axes reach down to m = -5.6 (an object at 1.18 f), since a real
    image is inverted. An object or image beyond the axes is not drawn (its rays still are);
    the title, above the axes and off the rays, gives the numbers and says where it is. The
    legend sits under the axes, never over a ray. Fixed axes also keep the diagram blittable.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in.
    focal_length : float
        The lens's focal length f, metres.
    object_distance : float
        Distance z_o of the object from the lens, metres (> f for a real image).

    Returns
    -------
    dict
        The artists for :func:`update_thin_lens`: ``"lens"``, ``"axis"``, ``"foci"``, ``"object"``
        and ``"image"`` (annotation arrows), ``"image_dot"``, ``"rays"`` (three Line2D) and
        ``"text"`` (the title with the numbers), ``"F"`` (the label of F, moved clear of a near object),
        and the zoom on F': ``"zoom_rays"``, ``"zoom_image"``, ``"zoom_dot"``, ``"zoom_focus"``, ``"zoom_spines"``.
    """
    styles = (
        "-",
        "--",
        "-.",
    )  # one colour for light (orange), three line styles for the three rays
    names = (
        "parallel, then through F'",
        "through the centre, straight",
        "through F, then parallel",
    )
    arrow = dict(
        arrowstyle="-|>", lw=2, shrinkA=0, shrinkB=0
    )  # the tip exactly where the rays meet
    art = {
        "lens": ax.axvline(0, color=palette.BLUE, lw=2),
        "axis": ax.axhline(0, color="0.5", lw=0.8),
        # over the arrows (an image at F' in the pinhole limit, an object at 1.05 f): animated with them
        "foci": ax.plot([-1, 1], [0, 0], "k+", ms=10, mew=1.5, zorder=4)[0],
        "object": ax.annotate(
            "", xy=(0, 0), xytext=(0, 0), arrowprops=dict(arrow, color=palette.GREEN)
        ),
        # over the foci: far away the image is a short tick just beyond F', which the cross must not hide
        "image": ax.annotate(
            "", xy=(0, 0), xytext=(0, 0), arrowprops=dict(arrow, color=palette.RED), zorder=5
        ),
        # a headless (short) image also gets a dot where the rays meet, so a tick a few pixels tall still shows
        "image_dot": ax.plot([], [], "o", color=palette.RED, ms=4, zorder=5)[0],
        "rays": [
            ax.plot([], [], color=palette.ORANGE, ls=ls, lw=1.3, label=n)[0]
            for ls, n in zip(styles, names, strict=True)
        ],
        "text": ax.set_title(" \n ", fontsize=9, family="monospace"),
    }
    # F below the axis, left of its cross (on the object side every ray and the object arrow stay above the
    # axis); F' above it, right of its cross (on the image side the rays and a real image stay below it)
    art["F"] = ax.annotate(
        "F", (-1, 0), xytext=(-4, -4), textcoords="offset points", ha="right", va="top", fontsize=10
    )
    ax.annotate(
        "F'", (1, 0), xytext=(5, 4), textcoords="offset points", ha="left", va="bottom", fontsize=10
    )
    lo, hi = THIN_LENS_X
    ax.set(
        xlim=THIN_LENS_X,
        ylim=THIN_LENS_Y,
        yticks=range(int(np.ceil(THIN_LENS_Y[0])), int(THIN_LENS_Y[1]) + 1),
        xticks=[t for t in range(int(lo), int(hi) + 1) if t % 2 == 0],
    )
    ax.set_xlabel("distance from the lens, in units of f (object side left, image side right)")
    ax.set_ylabel("height / object height")
    ax.legend(
        loc="upper center",
        bbox_to_anchor=(0.5, -0.16),
        ncols=3,
        fontsize=8,
        title="principal rays",
        title_fontsize=8,
    )
    art.update(_draw_focus_zoom(ax, styles))
    update_thin_lens(art, focal_length, object_distance)
    return art


ZOOM_X, ZOOM_Y = (
    (0.9, 1.35),
    (-0.28, 0.05),
)  # the zoom on F' (units of f, object heights): every headless image


def _draw_focus_zoom(ax, styles) -> dict:
    """An inset magnifying the region around F', bottom left, where no ray or arrow goes at any setting.

    A far object's image is a tick a few screen pixels tall just beyond F' (z_i = (1 + |m|) f); the
    inset shows it and the rays meeting there at about ten times the scale. The object side's rays
    stay above -1.5 object heights left of x = -0.8 f, so the inset covers none of them.
    """
    zoom = ax.inset_axes([0.075, 0.06, 0.27, 0.4])
    zoom.set(
        xlim=ZOOM_X,
        ylim=ZOOM_Y,
        aspect="equal",
        xticks=[1.0, 1.1, 1.2, 1.3],
        yticks=[-0.2, -0.1, 0],
    )
    zoom.set_anchor("SW")
    zoom.tick_params(labelsize=7, pad=2, left=False, bottom=False)  # labels only, no tick marks
    zoom.axhline(0, color="0.5", lw=0.8)
    zoom.set_title("around F', magnified", fontsize=8, pad=2)
    return {
        "zoom_rays": [zoom.plot([], [], color=palette.ORANGE, ls=ls, lw=1.3)[0] for ls in styles],
        "zoom_image": zoom.plot([], [], color=palette.RED, lw=2.5, solid_capstyle="butt", zorder=5)[
            0
        ],
        "zoom_dot": zoom.plot([], [], "o", color=palette.RED, ms=4, zorder=5)[0],
        "zoom_focus": zoom.plot([1], [0], "k+", ms=9, mew=1.5, zorder=4)[0],
        "zoom_spines": list(zoom.spines.values()),
    }


def _thin_lens_note(xo: float, xi: float, m: float) -> str:
    """Where the object or image is when it lies beyond the axes ('' when both are on them)."""
    lo, hi = THIN_LENS_X
    notes = [f"object at {-xo:.1f} f, beyond the left edge" if xo < lo else ""]
    if xi > hi or not THIN_LENS_Y[0] <= m <= THIN_LENS_Y[1]:  # its numbers are on the line above
        notes.append("the image is beyond the axes")  # its rays may leave through the bottom first
    return "; ".join(n for n in notes if n)


def update_thin_lens(art: dict, f: float, zo: float, requested: float | None = None) -> dict:
    """Move the diagram to focal length ``f`` and object distance ``zo``; returns the computed values.

    ``requested``: the object distance the control asked for, when the caller held the object
    at ``zo`` instead (a control inside the focal length, where no real image forms); the
    readout then says so, so the numbers never disagree silently with the control.

    Parameters
    ----------
    art : dict
        What :func:`draw_thin_lens` returned (moved in place).
    f : float
        Focal length, metres.
    zo : float
        Object distance drawn, metres.
    requested : float or None
        The object distance asked for, metres, when it differs from ``zo``.

    Returns
    -------
    dict
        ``"image_distance"`` z_i (m, the thin-lens equation, :func:`camlab.lens.image_distance`),
        ``"magnification"`` m (:func:`camlab.lens.magnification`) and ``"image_head"`` (whether the
        image arrow is long enough to carry its head).
    """
    zi = float(_lens.image_distance(f, zo))
    m = float(_lens.magnification(f, zo))
    xo, xi = -zo / f, zi / f  # units of f
    lo, hi = THIN_LENS_X
    art["object"].xy, art["object"].xyann = (xo, 1.0), (xo, 0)
    art["image"].xy, art["image"].xyann = (xi, m), (xi, 0)
    # to scale: an image shorter than IMAGE_HEAD_MIN object heights (~9 screen px) has no room for a head, whose
    # base would rise above the axis onto the upright side; it is drawn as a plain red tick, from the axis to
    # where the rays meet
    headless = abs(m) < IMAGE_HEAD_MIN
    art["image"].arrow_patch.set_arrowstyle("-" if headless else "-|>")
    art["image"].arrow_patch.set_mutation_scale(10 * min(1.0, abs(m) / 0.3) + 1)
    art["object"].set_visible(xo >= lo)  # an arrow at the edge would not meet its rays
    # an object within 0.3 f of F: its label goes left of the arrow's foot, clear of the arrow and the cross
    art["F"].xy = (min(xo, -1.0), 0) if xo > -1.3 else (-1.0, 0)
    art["image"].set_visible(xi <= hi)
    art["image_dot"].set_data(*(([xi], [m]) if headless and xi <= hi else ([], [])))
    # parallel ray -> through F'; central ray undeviated; ray through F -> parallel (exact lines, clipped by the axes)
    art["rays"][0].set_data([xo, 0, xi], [1, 1, m])
    art["rays"][1].set_data([xo, xi], [1, m])
    art["rays"][2].set_data([xo, 0, xi], [1, m, m])
    for ray, zoomed in zip(art["rays"], art.get("zoom_rays", ()), strict=False):
        zoomed.set_data(*ray.get_data())
    if "zoom_image" in art:
        art["zoom_image"].set_data([xi, xi], [0, m])
        art["zoom_dot"].set_data([xi], [m])
    note = _thin_lens_note(xo, xi, m)
    if requested is not None and not np.isclose(requested, zo):
        inside = "inside f (no real image)" if requested <= f else "inside 1.05 f"
        held = f"z_o = {requested:.3f} m is {inside}: held at {zo:.3f} m"
        note = f"{held}; {note}" if note else held
    hint = "the object (green) and its image (red), where the rays meet"
    # distances with their unit, then in f; the magnification named in full (m is also metres)
    art["text"].set_text(
        f"f = {f * 1e3:.0f} mm   z_o = {zo:.3f} m ({-xo:.2f} f)   z_i = {zi:.3f} m ({xi:.2f} f)"
        f"   magnification {m:.3f}\n{note or hint}"
    )
    return {"image_distance": zi, "magnification": m, "image_head": not headless}


# The focus-cone diagram has two horizontal scales: the object side in metres, the image side
# in millimetres (a true-scale drawing would squeeze the image side into a few pixels).
CONE_OBJECT_MAX = 2.0  # metres drawn on [-1, 0]
CONE_IMAGE_MAX = 0.09  # metres drawn on [0, 1]


GREEN_LIGHT = 550e-9  # wavelength (m) for the diffraction blur


def _cone_x(z):
    """Signed distance from the lens (object side negative) -> plot x."""
    z = np.asarray(z, dtype=float)
    return np.where(z < 0, z / CONE_OBJECT_MAX, z / CONE_IMAGE_MAX)


def draw_focus_cone(ax, half_height_mm: float = 20.0, sensor_height_mm: float = 24.0) -> dict:
    """A point on the axis, the aperture, the cone of light behind the lens and a movable sensor.

    Vertical positions are millimetres; horizontally the object side is in metres and the
    image side in millimetres (marked on the axis), so both fit. The light stops at the
    sensor: where the rays would meet behind it, their continuation is dotted. The sensor is
    ``sensor_height_mm`` tall (24 mm: full frame). Colours: the object green, the lens blue,
    light orange, the image (where the rays meet, and the blur on the sensor) red.
    :func:`update_focus_cone` moves everything and returns the blur circle on the sensor.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in.
    half_height_mm : float
        Half the axes' height, millimetres (the aperture stop reaches it).
    sensor_height_mm : float
        The sensor's height, millimetres.

    Returns
    -------
    dict
        The artists for :func:`update_focus_cone` (``"stop"``, ``"lens"``, ``"cone_in"``,
        ``"cone_out"``, ``"rays"``, ``"beyond"``, ``"point"``, ``"sensor"``, ``"focus"``,
        ``"blur"``, ``"text"``) and the half-heights ``"half"`` and ``"sensor_half"`` (mm).
    """
    # the optical axis (dark enough to read through the cone), under the cone: live frames paint the cone over
    # the cached background, so a full draw must too
    ax.axhline(0, color="0.4", lw=0.8, zorder=0.5)
    art = {
        "stop": ax.plot([], [], color="k", lw=4, solid_capstyle="butt", label="aperture stop")[0],
        # a white halo: over the orange cone the blue fell to 2.98:1 with matplotlib 3.9's antialiasing
        "lens": ax.plot(
            [],
            [],
            color=palette.BLUE,
            lw=3,
            label="lens, aperture A = f/N",
            path_effects=palette.halo(3),
        )[0],
        "cone_in": ax.fill(
            [0, 0, 0], [0, 0, 0], color=palette.ORANGE, alpha=0.22, lw=0, label="cone of light"
        )[0],
        "cone_out": ax.fill([0, 0, 0, 0], [0, 0, 0, 0], color=palette.ORANGE, alpha=0.22, lw=0)[0],
        "rays": ax.plot([], [], color=palette.ORANGE, lw=1, path_effects=palette.halo(1))[0],
        "beyond": ax.plot(
            [],
            [],
            color=palette.ORANGE,
            lw=1,
            ls=":",
            path_effects=palette.halo(1),
            label="rays beyond the sensor (blocked)",
        )[0],
        "point": ax.plot(
            [], [], "o", color=palette.GREEN, ms=7, label="object point", clip_on=False
        )[0],  # whole at 2 m, on the left spine
        "sensor": ax.plot(
            [], [], color="0.3", lw=2, label=f"sensor ({sensor_height_mm:g} mm tall)"
        )[0],
        "focus": ax.plot(
            [], [], "x", color=palette.RED, ms=8, mew=2, label="image point z_i (rays meet)"
        )[0],
        "blur": ax.plot(
            [],
            [],
            color=palette.RED,
            lw=6,
            solid_capstyle="butt",
            label="blur circle c (on the sensor)",
        )[0],
        "text": ax.set_title(
            " \n ", fontsize=8.5, family="monospace"
        ),  # above the axes: never over the cone
        "half": half_height_mm,
        "sensor_half": sensor_height_mm / 2,
    }
    ticks_m = [-2.0, -1.0]
    ticks_mm = [40, 80]
    ax.set_xticks(
        [float(_cone_x(t)) for t in ticks_m] + [0.0] + [float(_cone_x(t * 1e-3)) for t in ticks_mm]
    )
    ax.set_xticklabels([f"{-t:g} m" for t in ticks_m] + ["lens"] + [f"{t} mm" for t in ticks_mm])
    ax.set_xlim(-1.06, 1.0)  # room for the object dot at the left end (2 m)
    ax.set_ylim(-half_height_mm, half_height_mm)
    ax.set_xlabel("distance from the lens\n(object side in metres, image side in millimetres)")
    ax.set_ylabel("height (mm)")
    return art


def update_focus_cone(art: dict, f: float, N: float, z_o: float, z_s: float) -> dict:
    r"""Object point at ``z_o`` (m), sensor ``z_s`` (m) behind a lens ``f`` (m) at f-number ``N``.

    The cone from the aperture (diameter A = f / N) converges to the image point at
    :math:`z_i` and cuts the sensor in a disc of diameter :math:`c = A\,|z_s - z_i| / z_i`
    (similar triangles). The cone is drawn up to the sensor, where the light stops.

    Parameters
    ----------
    art : dict
        What :func:`draw_focus_cone` returned (moved in place).
    f : float
        Focal length, metres.
    N : float
        f-number (dimensionless).
    z_o : float
        Object distance, metres (> f).
    z_s : float
        Lens-to-sensor distance, metres.

    Returns
    -------
    dict
        ``"z_i"`` (image distance), ``"A"`` (aperture diameter), ``"c"`` (blur-circle diameter)
        and ``"airy"`` (the Airy disc :math:`2.44 \lambda N` in green light), all metres.
    """
    A = _lens.aperture_diameter(f, N)
    z_i = float(_lens.image_distance(f, z_o))
    a = A / 2 * 1e3  # mm
    c = A * abs(z_s - z_i) / z_i
    xo, xi, xs = float(_cone_x(-z_o)), float(_cone_x(z_i)), float(_cone_x(z_s))
    y_s = a * (1 - z_s / z_i)  # the upper ray at the sensor (it crosses the axis at z_i)
    art["stop"].set_data([0, 0, np.nan, 0, 0], [art["half"], a, np.nan, -a, -art["half"]])
    art["lens"].set_data([0, 0], [-a, a])
    art["cone_in"].set_xy([[xo, 0], [0, a], [0, -a]])
    art["cone_out"].set_xy(
        [[0, a], [xs, y_s], [xs, -y_s], [0, -a]]
    )  # a bow tie when the rays cross before z_s
    art["rays"].set_data([xo, 0, xs, np.nan, xo, 0, xs], [0, a, y_s, np.nan, 0, -a, -y_s])
    art["beyond"].set_data(
        *(([xs, xi, np.nan, xs, xi], [y_s, 0, np.nan, -y_s, 0]) if z_i > z_s else ([], []))
    )
    art["point"].set_data([xo], [0])
    art["focus"].set_data([xi], [0])
    art["sensor"].set_data([xs, xs], [-art["sensor_half"], art["sensor_half"]])
    half_c = c / 2 * 1e3
    art["blur"].set_data([xs, xs], [-max(half_c, 0.15), max(half_c, 0.15)])
    airy = 2.44 * GREEN_LIGHT * N  # the diffraction blur, which stopping down makes worse
    art["text"].set_text(
        f"A = f/N = {A * 1e3:.3g} mm   z_i = {z_i * 1e3:.2f} mm\n"
        f"z_s = {z_s * 1e3:.2f} mm   c = A |z_s - z_i| / z_i"
    )
    return {"z_i": z_i, "A": A, "c": c, "airy": airy}


# The face-on view zooms in steps so the largest of the three discs (blur, Airy, acceptable) fills at most
# 5/6 of it: (half-width, scale bar) in µm, and the pixel grid's spacing in pixels.
BLUR_VIEWS = (
    (25, 10),
    (50, 20),
    (100, 40),
    (250, 100),
    (500, 200),
    (1000, 400),
    (2500, 1000),
    (5000, 2000),
)


class BlurView(NamedTuple):
    """The face-on view :func:`blur_view` picks: its ``half_width`` and ``scale_bar`` length, µm."""

    half_width: float
    scale_bar: float


def blur_view(diameter_um: float) -> BlurView:
    """(half-width, scale-bar length) in µm of the face-on view for the largest disc ``diameter_um``.

    The first of :data:`BLUR_VIEWS` in which the disc fills at most 5/6 of the view's width; the
    widest view if none does.

    Parameters
    ----------
    diameter_um : float
        Diameter of the largest disc to show, µm.

    Returns
    -------
    BlurView
        ``half_width`` and ``scale_bar``, µm.
    """
    for half, bar in BLUR_VIEWS:
        if diameter_um <= 2 * half * 5 / 6:
            return BlurView(half, bar)
    return BlurView(*BLUR_VIEWS[-1])


def draw_blur_disc(ax, coc_um: float = 30.0) -> dict:
    """The sensor seen face on around the image point: the blur disc, the acceptable blur and the Airy disc.

    The blur disc is red, the acceptable blur ``coc_um`` purple dashes and the Airy disc brown
    dots, to scale with each other and with a grid of the sensor's pixels.
    The view zooms (:data:`BLUR_VIEWS`) so that the largest disc fills at most 5/6 of it: a
    1 µm disc beside a 4 µm Airy ring is as visible as a 6 mm disc. The axes run from -1 to
    1 in units of the view's half-width, so the zoom needs no new axis limits (the demo stays
    blittable); a scale bar and the title give the scale. :func:`update_blur_disc` sets it all.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in (equal aspect, no ticks).
    coc_um : float
        The acceptable circle of confusion's diameter, µm.

    Returns
    -------
    dict
        The artists for :func:`update_blur_disc` (``"grid"``, ``"blur"``, ``"ok"``, ``"airy"``,
        ``"bar"``, ``"bar_text"``, ``"text"``) and ``"coc"``, the acceptable diameter (µm).
    """
    from matplotlib.collections import LineCollection
    from matplotlib.colors import to_rgba
    from matplotlib.patches import Circle

    art = {
        "grid": ax.add_collection(
            LineCollection([], colors="0.82", linewidths=0.6, zorder=0.5, gid="grid")
        ),
        # a pale face and an opaque edge: a disc a pixel wide still reads as a red dot
        "blur": ax.add_patch(
            Circle((0, 0), 1, facecolor=to_rgba(palette.RED, 0.45), edgecolor=palette.RED, lw=1.2)
        ),
        "ok": ax.add_patch(
            Circle(
                (0, 0),
                1,
                fill=False,
                edgecolor=palette.PURPLE,
                ls="--",
                lw=1.2,
                label=f"acceptable c = {coc_um:g} µm",
            )
        ),
        "airy": ax.add_patch(
            Circle(
                (0, 0),
                1,
                fill=False,
                edgecolor=palette.BROWN,
                ls=":",
                lw=1.8,
                label="Airy disc 2.44 λN",
            )
        ),
        "bar": ax.plot([], [], color="k", lw=2.5, solid_capstyle="butt")[0],
        "bar_text": ax.text(-0.92, -0.84, "", fontsize=8, ha="left", va="bottom"),
        "text": ax.set_title(" \n \n ", fontsize=8.5, family="monospace"),
        "coc": coc_um,
    }
    ax.set_xlim(-1, 1)
    ax.set_ylim(-1, 1)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_xlabel("on the sensor, face on\n(grey grid: pixels, see the title)")
    return art


def update_blur_disc(art: dict, c: float, airy: float, pixel: float) -> dict:
    """Blur circle ``c`` and Airy disc ``airy`` (diameters, metres) on pixels of ``pixel`` m, zoomed to fit.

    The title gives c in µm and in pixels, the Airy disc, and the view's width.

    Parameters
    ----------
    art : dict
        What :func:`draw_blur_disc` returned (moved in place).
    c : float
        Blur-circle diameter, metres.
    airy : float
        Airy-disc diameter, metres.
    pixel : float
        Pixel pitch, metres.

    Returns
    -------
    dict
        ``"half_um"``: the view's half-width (µm); ``"grid_px"``: the grid's spacing (pixels).
    """
    c_um, airy_um, pixel_um = c * 1e6, airy * 1e6, pixel * 1e6
    half, bar = blur_view(max(c_um, airy_um, art["coc"]))
    grid_px = 1 if half <= 50 else (10 if half <= 500 else 100)  # at most 20 lines across
    step = grid_px * pixel_um / half
    ticks = np.arange(step / 2, 1, step)  # the image point sits at a pixel's centre
    ticks = np.concatenate([-ticks[::-1], ticks])
    end = 0.99  # short of the frame: a live frame paints the grid over the cached spines, a full draw under them
    art["grid"].set_segments(
        [[(t, -end), (t, end)] for t in ticks] + [[(-end, t), (end, t)] for t in ticks]
    )
    art["blur"].set_radius(
        max(c_um / 2, 0.006 * half) / half
    )  # a dot at least ~2 screen pixels wide
    art["airy"].set_radius(airy_um / 2 / half)
    art["ok"].set_radius(art["coc"] / 2 / half)
    art["bar"].set_data([-0.92, -0.92 + bar / half], [-0.9, -0.9])
    art["bar_text"].set_text(f"{bar:g} µm = {bar / pixel_um:g} px")
    width = f"{2 * half / 1000:g} mm" if half >= 500 else f"{2 * half:g} µm"

    def short(
        value: float, whole_from: float = np.inf
    ) -> str:  # two decimals below 0.1: a 0.04 µm blur is not "0.0"
        return (
            f"{value:.0f}"
            if value >= whole_from
            else f"{value:.1f}"
            if value >= 0.1 or value == 0
            else f"{value:.2f}"
        )

    # µm: one decimal below 10 (a 0.5 µm disc is not "1 µm")
    art["text"].set_text(
        f"c = {short(c_um, 10)} µm = {short(c / pixel, 10)} px\nAiry disc {short(airy_um, 10)} µm\n"
        f"view {width} wide, grid {grid_px} px"
    )
    return {"half_um": half, "grid_px": grid_px}
