"""Lesson 10, section 6: the keystone camera seen from the side, following its tilt.

A camera at the origin tilts up by ``tilt`` at a vertical facade. The facade's verticals are
parallel to one ray through the camera centre, the vertical one; where that ray meets the
(tilted) image plane is their vanishing point, ``f / tan(tilt)`` above the principal point. At
tilt 0 the image plane is vertical too, parallel to the ray, and the verticals stay parallel in
the photo. The image plane is drawn 2 m out (schematic); the pixel numbers are the facade
scene's (f = 800 px, principal point v = 239.5 px).
"""

from __future__ import annotations

from types import SimpleNamespace

import ipywidgets as W
import numpy as np

from ..plotting import palette
from ._base import Demo, FigureView, build_demo, register, slider
from .controls import monospace

F_PX = 800.0  # the facade scene's focal length, px
CV_PX = 239.5  # its principal point's row, px
_PLANE_M = 2.0  # the image plane is drawn this far out, m (schematic)
_HALF_M = _PLANE_M * 240.0 / F_PX  # the photo's half height at that distance (240 px of 800)
_TOP = 6.0  # the drawing's upper limit, m
# The facade scene: 1 m wide, a 480 x 360 px texture (corner centres 359/480 m apart in
# height), its centre 1.8 m out on the optical axis; drawn scaled so that it lies 5 m out.
_FACADE_M = 5.0
_FACADE_HALF_M = _FACADE_M * (359 / 480) / 2 / 1.8


def vanishing_point_px(tilt: float) -> float:
    """How far above the principal point the verticals' vanishing point lies, px (inf at tilt 0).

    Parameters
    ----------
    tilt : float
        The camera's tilt up, rad, in [0, pi/2).

    Returns
    -------
    float
        ``F_PX / tan(tilt)``, pixels above the principal point; ``inf`` at tilt 0, where the
        verticals stay parallel in the photo.
    """
    return float("inf") if tilt <= 0 else F_PX / np.tan(tilt)


def facade_ends(tilt: float) -> np.ndarray:
    """The facade's top and bottom as drawn, m (schematic): aimed at as the facade scene is.

    ``scenes.sample_photo("facade", pitch=-tilt, yaw=0)`` centres the facade on the optical
    axis, so the facade moves with the tilt and fills the same part of the photo at every tilt.

    Parameters
    ----------
    tilt : float
        The camera's tilt up, rad.

    Returns
    -------
    (2, 2) ndarray
        (depth, height) of the facade's top and bottom, m (schematic).
    """
    centre = _FACADE_M * np.array([np.cos(tilt), np.sin(tilt)])
    return centre + np.array([[0.0, _FACADE_HALF_M], [0.0, -_FACADE_HALF_M]])


def facade_rows_px(tilt: float) -> np.ndarray:
    """The rows (v, px) at which the drawn facade's top and bottom appear in the photo.

    Parameters
    ----------
    tilt : float
        The camera's tilt up, rad.

    Returns
    -------
    (2,) ndarray
        v of the facade's top and bottom, px: ``CV_PX - F_PX * height / depth`` in the camera's
        tilted frame.
    """
    along, up = np.array([np.cos(tilt), np.sin(tilt)]), np.array([-np.sin(tilt), np.cos(tilt)])
    ends = facade_ends(tilt)
    return CV_PX - F_PX * (ends @ up) / (ends @ along)


def _static_scene(ax) -> None:
    """The camera centre and the axes' labels, limits and title."""
    ax.plot(0, 0, "ko", ms=5)
    ax.annotate(
        "camera centre",
        (0, 0),
        xytext=(0, -8),
        textcoords="offset points",
        ha="center",
        va="top",
        fontsize=9,
    )
    ax.set(
        aspect="equal",
        xlim=(-3.2, 7.6),
        ylim=(-1.6, _TOP),
        xlabel="depth in front of the camera (m, schematic)",
        ylabel="height above the camera (m, schematic)",
    )
    ax.set_title(
        "side view (yaw 0): the facade's horizontals run out of the page,\n"
        "parallel to the photo, so they stay parallel in it",
        fontsize=9,
    )


def _label_vanishing_point(label, tilt: float, height: float) -> None:
    """Say where the vertical ray meets the image plane: at the point drawn, off the top, or never."""
    if height < _TOP - 0.5:
        label.xy = (0, height)
        label.set_ha("right")
        label.set_va("center")
        label.set_text(
            "the verticals'\nvanishing point:\nthe vertical ray\n(purple) meets the\n"
            "image plane (dotted)"
        )
        return
    label.xy = (2.2, _TOP - 0.35)  # right of the image plane, left of the rays
    label.set_ha("left")
    label.set_va("top")
    label.set_text(
        "the vertical ray (purple)\n"
        + (
            "never meets the image\nplane: both are vertical"
            if tilt <= 0
            else f"meets the image plane\n{height:.0f} m up, off the top"
        )
    )


def _facade_artists(view: FigureView, ax) -> SimpleNamespace:
    """The facade, the rays to its ends and the field of view's bounds, animated."""
    return SimpleNamespace(
        fov=[view.animate(ax.plot([], [], color=palette.GREY, lw=1, ls="-.")[0]) for _ in "ab"],
        rays=[view.animate(ax.plot([], [], color=palette.GREY, lw=1)[0]) for _ in "ab"],
        line=view.animate(ax.plot([], [], color=palette.PURPLE, lw=4, solid_capstyle="butt")[0]),
        label=view.animate(
            ax.annotate(
                "facade, centred\non the optical\naxis: all of it\nin the photo",
                (0, 0),
                xytext=(8, 0),
                textcoords="offset points",
                va="center",
                fontsize=9,
            )
        ),
    )


def _draw_facade(art: SimpleNamespace, t: float, centre: np.ndarray, up: np.ndarray) -> None:
    """Place the facade at tilt ``t``, the rays to its ends, and the field of view through the photo."""
    ends = facade_ends(t)
    art.line.set_data(*ends.T)
    art.label.xy = ends.mean(axis=0)
    for line, end in zip(art.rays, ends, strict=True):  # camera centre to the facade's top, bottom
        line.set_data([0, end[0]], [0, end[1]])
    for line, sign in zip(art.fov, (1, -1), strict=True):  # the field of view: the photo's ends
        edge = centre + sign * _HALF_M * up
        reach = (ends[0, 0] + 1.2) / edge[0]  # on to just past the facade
        line.set_data([0, reach * edge[0]], [0, reach * edge[1]])


def _principal_point_artists(view: FigureView, ax) -> SimpleNamespace:
    """The principal point c, a black + where the optical axis meets the photo, and its label."""
    mark = view.animate(ax.plot([], [], "k+", ms=10, mew=2)[0])
    label = ax.annotate(
        "c",
        (0, 0),
        xytext=(7, 2),
        textcoords="offset points",
        va="bottom",
        fontsize=10,
        path_effects=palette.halo(3),
    )
    return SimpleNamespace(mark=mark, label=view.animate(label))


@register(lesson="10", sweep={"tilt": [0.0, 0.15, 0.8]})
def keystone_side_view() -> Demo:
    """The keystone camera from the side: tilt it and watch the verticals' vanishing point move.

    Returns
    -------
    Demo
        The demo: control ``tilt`` (the camera's tilt up, rad), the figure (the facade, aimed
        at as the facade scene is, the rays to its ends, the field of view, the camera, optical
        axis, principal point c, image plane and the vertical ray meeting it) and ``state``
        (``vanishing_px``, the vanishing point's height above the principal point in px, inf
        at tilt 0; ``facade_rows_px``, the rows of the facade's top and bottom in the photo).
    """
    view = FigureView(figsize=(6.4, 4.9))
    ax = view.fig.subplots()
    _static_scene(ax)
    facade = _facade_artists(view, ax)
    axis = view.animate(ax.plot([], [], color=palette.GREY, lw=1, ls="--")[0])
    axis_label = view.animate(  # in the empty corner, off every ray at any tilt
        ax.text(-3.1, -1.5, "", ha="left", va="bottom", fontsize=9)
    )
    plane = view.animate(ax.plot([], [], color="k", lw=1, ls=":")[0])
    photo = view.animate(ax.plot([], [], color="k", lw=3)[0])
    photo_label = view.animate(
        ax.annotate(
            "the photo", (0, 0), xytext=(8, -8), textcoords="offset points", va="top", fontsize=9
        )
    )
    pp_mark = _principal_point_artists(view, ax)
    ray = view.animate(ax.plot([], [], color=palette.PURPLE, lw=1.5)[0])
    vp = view.animate(ax.plot([], [], "o", color=palette.PURPLE, ms=6)[0])
    vp_label = view.animate(
        ax.annotate(
            "",
            (0, 0),
            xytext=(-8, 0),
            textcoords="offset points",
            ha="right",
            va="center",
            fontsize=9,
        )
    )
    readout = W.HTML()

    def update(v: dict, state: dict) -> None:
        t = v["tilt"]
        along, up = np.array([np.cos(t), np.sin(t)]), np.array([-np.sin(t), np.cos(t)])
        centre = _PLANE_M * along
        axis.set_data(*np.c_[[0, 0], 3.2 * along])
        axis_label.set_text(f"dashed: the optical axis,\ntilted up {t:.2f} rad")
        height = _PLANE_M / np.sin(t) if t > 0 else np.inf  # the vertical ray meets the plane here
        reach = min(_PLANE_M / np.tan(t) + 0.1, 12.0) if t > 0 else 12.0
        plane.set_data(*(centre + np.outer([-1.4, reach], up)).T)
        photo.set_data(*(centre + np.outer([-_HALF_M, _HALF_M], up)).T)
        photo_label.xy = centre - _HALF_M * up
        pp_mark.mark.set_data([centre[0]], [centre[1]])  # where the optical axis meets the photo
        pp_mark.label.xy = centre
        _draw_facade(facade, t, centre, up)
        ray.set_data([0, 0], [0, min(height + 0.6, _TOP)])
        px = vanishing_point_px(t)
        vp.set_data(*(([0], [height]) if height < _TOP - 0.5 else ([], [])))
        _label_vanishing_point(vp_label, t, height)
        state.update(vanishing_px=px, facade_rows_px=facade_rows_px(t))
        readout.value = monospace(
            f"tilt {t:.2f} rad: "
            + (
                "the verticals stay parallel in the photo (vanishing point at infinity)"
                if not np.isfinite(px)
                else f"the verticals meet f / tan(tilt) = {px:.0f} px above the principal point, "
                f"v = {CV_PX - px:.0f} px"
            )
        )

    return build_demo(
        "keystone_side_view",
        {"tilt": slider(0.5, 0.0, 0.8, 0.05, "camera tilt up (rad)")},
        view,
        update,
        title="The keystone camera from the side",
        extra=[readout],
    )
