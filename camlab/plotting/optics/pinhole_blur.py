"""Pinhole blur drawn (lesson 01).

Blur against the pinhole's diameter, and the cones of light through pinholes of several sizes.

Each ``draw_*`` function draws once and returns a dict of artists; its ``update_*`` partner
moves those artists, so widgets can redraw in place.
"""

from __future__ import annotations

import numpy as np

from ... import pinhole as _pinhole
from .. import palette

__all__ = [
    "draw_pinhole_blur",
    "update_pinhole_blur",
    "draw_pinhole_cones",
]


def draw_pinhole_blur(
    ax, focal_length: float, wavelength: float = 550e-9, object_distance: float = np.inf
) -> dict:
    """Geometric, diffraction and total blur (mm) against pinhole diameter (mm), log axes, with a marker.

    ``object_distance`` (metres) is the Z of the geometric term d (1 + f/Z); infinite by default.
    The curves span diameters from 0.02 to 3 mm (:func:`camlab.pinhole.pinhole_blur`); the
    marker starts at d = 1 mm.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in (set to log-log, legend below it).
    focal_length : float
        Pinhole-to-image distance f, metres.
    wavelength : float
        Wavelength of the light, metres (550 nm: green).
    object_distance : float
        Distance Z of the object, metres; ``np.inf`` for a distant one.

    Returns
    -------
    dict
        The artists ``"geometric"``, ``"diffraction"``, ``"total"`` (Line2D curves), ``"marker"``
        (the vertical line at the chosen diameter), ``"best"`` (the star at the optimum) and
        ``"d"``, the (300,) diameters sampled (metres), for :func:`update_pinhole_blur`.
    """
    d = np.geomspace(0.02e-3, 3e-3, 300)
    art = {
        # black and grey only: lesson 01 keeps blue and brown for objects (its two object points), orange for rays,
        # red and green for the image planes
        "geometric": ax.plot(
            d * 1e3, d * 1e3, color="0.35", ls="--", label="geometric  d (1 + f/Z)"
        )[0],
        "diffraction": ax.plot(
            d * 1e3,
            d * 1e3,
            color="0.35",
            ls=":",
            lw=2,
            label=r"diffraction  $2.44\lambda f/d$",
        )[0],
        "total": ax.plot(d * 1e3, d * 1e3, "k", lw=2, label="total")[0],
        "marker": ax.axvline(1, color=palette.GREY, lw=1.5, label="your d"),
        "best": ax.plot([], [], "k*", ms=12, label="best diameter")[0],
        "d": d,
    }
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("pinhole diameter d (mm)")
    ax.set_ylabel("blur diameter (mm)")
    # below the axes, where the moving curves and marker never cross it: it need not be redrawn per update
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.17), ncols=2)
    update_pinhole_blur(art, focal_length, 1e-3, wavelength, object_distance)
    return art


def update_pinhole_blur(
    art: dict,
    focal_length: float,
    diameter: float,
    wavelength: float = 550e-9,
    object_distance: float = np.inf,
) -> None:
    """Redraw the curves for ``focal_length`` and ``object_distance``, the marker at ``diameter`` (metres).

    The star moves to :func:`camlab.pinhole.optimal_pinhole_diameter` and its total blur.

    Parameters
    ----------
    art : dict
        What :func:`draw_pinhole_blur` returned (its artists are moved in place).
    focal_length : float
        Pinhole-to-image distance f, metres.
    diameter : float
        The pinhole's diameter d, metres, where the marker goes.
    wavelength : float
        Wavelength of the light, metres.
    object_distance : float
        Distance Z of the object, metres; ``np.inf`` for a distant one.
    """
    d = art["d"]
    b = _pinhole.pinhole_blur(d, focal_length, object_distance, wavelength)
    art["geometric"].set_ydata(b.geometric * 1e3)
    art["diffraction"].set_ydata(b.diffraction * 1e3)
    art["total"].set_ydata(b.total * 1e3)
    art["marker"].set_xdata([diameter * 1e3, diameter * 1e3])
    best = _pinhole.optimal_pinhole_diameter(focal_length, wavelength, object_distance)
    best_blur = _pinhole.pinhole_blur(best, focal_length, object_distance, wavelength).total
    art["best"].set_data([best * 1e3], [float(best_blur) * 1e3])


CONE_COLOURS = (
    palette.ORANGE,
    palette.DARK_ORANGE,
)  # the two object points' rays: lesson 01's ray orange, in two shades (blue is its object, red its real plane)
CONE_BEFORE = 3.0  # the cone figure shows the last 3 f of the rays before the pinhole (units of f)


def _draw_cones(ax, heights, Z, f, b, a, x_in, x_img):
    """Each object point's cone of rays through the hole and on to the image plane.

    With its disc and the diffraction band around it; returns, per point, its height, where its rays
    enter at the right edge, and its colour.
    """
    entry = []
    for Y, colour in zip(
        heights, CONE_COLOURS, strict=True
    ):  # objects: blue and brown (green is the virtual plane, red the real one)
        y_obj = -Y * 1e3  # mm, drawn up
        y_img = Y * f / Z * 1e3  # the real image is inverted: -f Y / Z, drawn up as +
        top, bottom = y_img + b.geometric / 2 * 1e3, y_img - b.geometric / 2 * 1e3
        halo = b.total / 2 * 1e3
        s_in = (
            1 - x_in * 1e-3 / Z
        )  # where the right edge sits along the ray, from the point (0) to the hole (1)
        upper, lower = y_obj + (a - y_obj) * s_in, y_obj + (-a - y_obj) * s_in
        ax.fill(
            [0, x_img, x_img, 0],
            [a, y_img + halo, y_img - halo, -a],
            color=colour,
            alpha=0.12,
            lw=0,
        )  # diffraction
        ax.fill([x_in, 0, 0, x_in], [upper, a, -a, lower], color=colour, alpha=0.35, lw=0)
        ax.fill([0, x_img, x_img, 0], [a, top, bottom, -a], color=colour, alpha=0.35, lw=0)
        ax.plot(
            [x_img, x_img],
            [y_img - halo, y_img + halo],
            color=colour,
            lw=8,
            alpha=0.3,
            solid_capstyle="butt",
        )
        ax.plot([x_img, x_img], [bottom, top], color=colour, lw=4, solid_capstyle="butt")
        entry.append((y_obj, (upper + lower) / 2, colour))
    return entry


def _label_cones(ax, entry, Z, f, a, x_in, x_img, wall):
    """Name where each point's rays come in; draw and name the screen and image plane."""
    for (
        y_obj,
        y_in,
        colour,
    ) in entry:  # the points lie off the right edge: say which ray comes from where
        side = 1 if y_in > 0 else -1
        where = "above" if y_obj > 0 else "below"
        ax.annotate(
            f"from a point {abs(y_obj):.0f} mm {where}\nthe axis, {Z:g} m away",
            (x_in, y_in),
            xytext=(x_in - 0.25 * f * 1e3, side * 0.97 * wall),
            ha="right",
            va="top" if side > 0 else "bottom",
            fontsize=8,
            color="k",  # black text (orange is too light for text); the arrow carries the point's colour
            arrowprops=dict(arrowstyle="->", color=colour, lw=1.5, shrinkA=1, shrinkB=0),
        )
    ax.plot(
        [0, 0, np.nan, 0, 0], [wall, a, np.nan, -a, -wall], color="k", lw=3, solid_capstyle="butt"
    )
    # between the image plane and the screen, above the cones: the screen, whose gap on the axis is the hole
    ax.annotate(
        "screen,\nhole d",
        (0, 0.75 * wall),
        xytext=(0.5 * x_img, 0.75 * wall),
        ha="center",
        va="center",
        fontsize=8,
        arrowprops=dict(arrowstyle="->", color="k", lw=0.8, shrinkA=1, shrinkB=2),
    )
    ax.annotate(
        "image\nplane",
        (x_img, -0.75 * wall),
        xytext=(0.5 * x_img, -0.75 * wall),
        ha="center",
        va="center",
        fontsize=8,
        arrowprops=dict(arrowstyle="->", color="k", lw=0.8, shrinkA=1, shrinkB=1),
    )


def draw_pinhole_cones(
    ax,
    diameter: float,
    focal_length: float,
    object_distance: float,
    heights=(-0.02, 0.02),
    wavelength: float = 550e-9,
) -> dict:
    """Side view of pinhole blur, to scale: each object point's cone of rays through a hole of ``diameter``.

    Drawn as lesson 01's other side view (:func:`draw_similar_triangles`): depth z to the right, the
    objects on the +z side, the real image plane at z = -f on the left, height -y upwards. Two points
    at ``heights`` (metres, camera y) and distance ``object_distance`` send cones through the hole in
    the screen; each cone cuts the image plane ``focal_length`` behind it in a disc of diameter
    d (1 + f/Z) (drawn in the point's colour), widened by diffraction to the Airy disc
    2.44 lambda f / d (the pale band). Both axes are millimetres, each with one scale, so every ray is
    straight: the figure shows the last :data:`CONE_BEFORE` f of the rays before the hole, and the
    points themselves, further right, are named where their rays come in.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in.
    diameter : float
        The pinhole's diameter d, metres.
    focal_length : float
        Pinhole-to-image distance f, metres.
    object_distance : float
        Distance Z of the two points, metres.
    heights : (float, float)
        The points' camera y, metres (y down: negative is above the axis).
    wavelength : float
        Wavelength of the light, metres.

    Returns
    -------
    dict
        The blur terms in metres: ``"geometric"`` d (1 + f/Z), ``"diffraction"`` 2.44 lambda f / d
        and ``"total"`` (:func:`camlab.pinhole.pinhole_blur`).
    """
    Z, f, d = object_distance, focal_length, diameter
    b = _pinhole.pinhole_blur(d, f, Z, wavelength)
    a = d / 2 * 1e3
    x_in, x_img = (
        CONE_BEFORE * f * 1e3,
        -f * 1e3,
    )  # plot x = depth z, mm: the right edge and the image plane
    entry = _draw_cones(ax, heights, Z, f, b, a, x_in, x_img)
    wall = 1.6 * max(
        abs(e[1]) for e in entry
    )  # the same for every d: panels can share the height axis
    _label_cones(ax, entry, Z, f, a, x_in, x_img, wall)
    ax.axhline(0, color=palette.GREY, lw=0.6, zorder=0)
    ax.axvline(x_img, color="0.3", lw=1, ls="--")
    ax.set_xlim(x_img * 1.12, x_in)
    ax.set_ylim(-wall, wall)
    ax.set_xticks(np.arange(x_img, x_in + 1, 100))
    ax.set_xlabel(
        f"depth z (mm), pinhole at 0;\nreal image plane (dashed) at z = {x_img:.0f} mm", fontsize=9
    )
    ax.set_ylabel("height -y, up (mm)")
    ax.set_title(
        f"d = {d * 1e3:g} mm\ndisc of rays {b.geometric * 1e3:.2f} mm + diffraction {b.diffraction * 1e3:.2f} mm",
        fontsize=9,
    )
    return {"geometric": b.geometric, "diffraction": b.diffraction, "total": b.total}
