"""Lesson 05's parallel rails.

Parallel lines vanish in a perspective image and stay parallel in an affine one.
"""

from __future__ import annotations

from types import SimpleNamespace
from typing import NamedTuple

import numpy as np
from matplotlib.lines import Line2D

from ... import affine as af
from ... import camera as cm
from ... import fixtures
from ...plotting import palette, scene3d
from .._base import FigureView, build_demo, register
from ..controls import int_slider
from .common import (
    COLOURS,
    STYLES,
    model_legend,
    model_line,
    place_reference,
    reference_marker,
)

RAIL_EYE = np.array([0.0, 0.0, 2.0])  # the camera, 2 m above the ground at y = 0 (metres)
RAIL_TRACK = (2.0, 22.0)  # where the track starts and ends along +y (metres from the camera)
RAIL_REFERENCE = np.array(
    [0.0, 12.0, 0.0]
)  # the middle of the track: the affine camera's reference point
RAIL_SAMPLES = (
    4.0,
    20.0,
)  # the metres of track the readouts measure, from y to y + 1 (in view at every setting)


class RailCameras(NamedTuple):
    """The rail demo's cameras (:func:`rail_cameras`).

    Attributes
    ----------
    camera : Camera
        The perspective camera looking along the track.
    affine : (3, 4) ndarray
        Its weak-perspective approximation about :data:`RAIL_REFERENCE`.
    """

    camera: cm.Camera
    affine: np.ndarray


def rail_cameras(yaw: float, pitch: float) -> RailCameras:
    """The rail demo's perspective camera looking along the track, and its weak-perspective approximation.

    The camera looks along the track (+y) from :data:`RAIL_EYE`, f = 500 px, 640 x 480; the
    approximation is about :data:`RAIL_REFERENCE`.

    Parameters
    ----------
    yaw : float
        The turn about the vertical, radians.
    pitch : float
        The tilt down, radians.

    Returns
    -------
    RailCameras
        ``camera`` and its weak-perspective ``affine`` (3, 4) matrix.
    """
    direction = cm.rotation_z(-yaw) @ np.array([0.0, np.cos(pitch), -np.sin(pitch)])
    cam = cm.Camera.look_at(
        RAIL_EYE, RAIL_EYE + direction, K=cm.intrinsic_matrix(500, 500, 319.5, 239.5)
    )
    return RailCameras(cam, af.affine_approximation(cam, RAIL_REFERENCE))


def _rails_legend(fig) -> None:
    """The figure legend of :func:`parallel_rails`.

    The two models, X0, the measured metres, the ring, the vanishing point and the horizon.
    """
    model_legend(
        fig,
        (),
        reference=True,
        extra=(
            Line2D(
                [],
                [],
                color=COLOURS["para-perspective"],
                ls=STYLES["para-perspective"],
                lw=1.6,
                label="para-perspective: the track's centre line",
            ),
            Line2D(
                [],
                [],
                color="0.1",
                lw=3.5,
                label=f"the metres the readouts measure ({RAIL_SAMPLES[0]:.0f} and "
                f"{RAIL_SAMPLES[1]:.0f} m along the track)",
            ),
            Line2D(
                [],
                [],
                marker="o",
                ms=12,
                mfc="none",
                mec="0.1",
                mew=1.1,
                ls="none",
                label=f"ring: the tiny {RAIL_SAMPLES[1]:.0f} m one",
            ),
            Line2D(
                [],
                [],
                marker="o",
                color=COLOURS["perspective"],
                ms=8,
                mfc="white",
                mew=2,
                ls="none",
                label="vanishing point",
            ),
            Line2D([], [], color=palette.GREY, lw=0.8, ls="--", label="horizon"),
        ),
        ncols=4,
    )


def _rails_panels(ax_p, ax_a) -> tuple[list, list]:
    """The two image panels of :func:`parallel_rails`.

    Each one's track line and its readout text, placed where no rail runs at any yaw and pitch;
    returns (lines, texts), perspective first.
    """
    ax_p.set_title("perspective: rails meet, far sleepers crowd", fontsize=9)
    ax_a.set_title("weak perspective: rails stay parallel, sleepers evenly spaced", fontsize=9)
    lines, texts = [], []
    for ax, model in ((ax_p, "perspective"), (ax_a, "weak perspective")):
        scene3d.image_axes(ax, (640, 480))
        ax.tick_params(labelleft=ax is ax_p)
        lines.append(model_line(ax, model, lw=1.0))
        lines[-1].set_linestyle("-")  # dashes would break up sleepers a few pixels apart
        # Each readout sits where no rail runs at any yaw and pitch: above the horizon (>= 75 px below the
        # top) in perspective, below the affine track (which ends above v = 310) in weak perspective.
        at = (
            (0.02, 0.975, "left", "top")
            if model == "perspective"
            else (0.5, 0.025, "center", "bottom")
        )
        texts.append(
            ax.text(
                at[0],
                at[1],
                "",
                transform=ax.transAxes,
                fontsize=8,
                family="monospace",
                ha=at[2],
                va=at[3],
            )
        )
    ax_a.set_ylabel("")
    return lines, texts


def _rails_figure(view: FigureView) -> SimpleNamespace:
    """The figure of :func:`parallel_rails`.

    The perspective and weak-perspective images of the track, the vanishing point and horizon, the
    two measured metres, the ring round the far one, the readouts, X0 in both and the legend;
    returns its moving artists by name.
    """
    ax_p, ax_a = view.fig.subplots(1, 2)
    lines, texts = _rails_panels(ax_p, ax_a)
    (vp,) = ax_p.plot([], [], "o", color=COLOURS["perspective"], ms=8, mfc="white", mew=2)
    (horizon,) = ax_p.plot([], [], color=palette.GREY, lw=0.8, ls="--")
    # The two metres of track the readouts measure (x = 0, from y to y + 1), thick and dark in both panels.
    measured = [
        ax.plot([], [], color="0.1", lw=3.5, solid_capstyle="butt", zorder=3)[0]
        for ax in (ax_p, ax_a)
    ]
    # The far metre images only a few pixels long in perspective: a ring shows where it is.
    (ring,) = ax_p.plot([], [], "o", ms=15, mfc="none", mec="0.1", mew=1.1, zorder=3)
    # Para-perspective's image of the track's centre line: through X0 in perspective's direction there.
    para = model_line(ax_a, "para-perspective", lw=1.6, zorder=3)
    view.animate(*lines, vp, horizon, *measured, ring, para, *texts)
    references = [
        (view.animate(*reference_marker(ax)),) for ax in (ax_p, ax_a)
    ]  # where the two images agree
    _rails_legend(view.fig)
    return SimpleNamespace(
        lines=lines,
        texts=texts,
        vp=vp,
        horizon=horizon,
        measured=measured,
        ring=ring,
        para=para,
        references=references,
    )


def _rails_readout(near: float, far: float) -> str:
    """One panel's readout in :func:`parallel_rails`.

    The pixels one metre of track spans ``near`` (at the first of :data:`RAIL_SAMPLES`) and ``far``
    (at the second).
    """
    return f"1 m of track: {near:5.1f} px at {RAIL_SAMPLES[0]:.0f} m, {far:5.1f} px at {RAIL_SAMPLES[1]:.0f} m"


def _rails_controls() -> dict:
    """The controls of :func:`parallel_rails`: the camera's yaw and pitch (degrees)."""
    return {
        "yaw": int_slider(0, -15, 15, "yaw (deg, + turns right)"),
        "pitch": int_slider(15, 10, 18, "pitch down (deg)"),
    }


def _horizon_data(l_h: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The horizon ``l_h`` (homogeneous line) across the image, u from -1 to 641.

    V = -(a u + c) / b (NaN for a vertical line).
    """
    us = np.array([-1.0, 641.0])
    return us, -(l_h[0] * us + l_h[2]) / l_h[1] if abs(l_h[1]) > 1e-12 else [np.nan, np.nan]


# Measured over the whole range (f = 500 px): yaw within +-15 and pitch 10 to 18 degrees keep the vanishing
# point and every point of the affine track at least 13 px inside the 640 x 480 frame
# (tests/test_affine.py::test_parallel_rails_keeps_everything_in_frame), and the affine sleepers at
# least 7 px apart.
@register(lesson="05", sweep={"yaw": [-15, 15], "pitch": [10, 18]})
def parallel_rails():
    """Parallel rails meet at a vanishing point in perspective; an affine image keeps them parallel.

    The affine image also keeps equal sleepers equal at every depth (no shrinking with
    distance).

    Returns
    -------
    Demo
        The demo: controls ``yaw`` (degrees, + turns right) and ``pitch`` (degrees down), the
        figure (the perspective and weak-perspective images of the track, each with the pixels
        one metre of track spans near and far) and ``state`` (``vanishing_point``,
        ``affine_direction``, ``camera``, ``P_affine``, ``horizon``, ``sleeper_gaps``,
        ``reference_image``, ``P_para``: para-perspective about X0, whose image of the track's
        centre line the right panel draws green, dotted).
    """
    view = FigureView(figsize=(10, 4.6))
    scene = fixtures.rail_track(*RAIL_TRACK)
    art = _rails_figure(view)
    lines, texts, measured, references = art.lines, art.texts, art.measured, art.references

    def update(v, state):
        cam, P_aff = rail_cameras(*np.deg2rad([v["yaw"], v["pitch"]]))
        lines[0].set_data(*scene3d.polyline_data(cm.project_segments(cam, scene)).T)
        lines[1].set_data(*scene3d.polyline_data(cm.project_segments(P_aff, scene)).T)
        v_p = af.image_of_direction(cam.P, [0.0, 1.0, 0.0])
        v_a = af.image_of_direction(P_aff, [0.0, 1.0, 0.0])
        vpt = v_p[:2] / v_p[2]
        art.vp.set_data([vpt[0]], [vpt[1]])
        # the horizon: the line through the vanishing points of two ground directions
        l_h = np.cross(af.image_of_direction(cam.P, [1.0, 0.0, 0.0]), v_p)
        art.horizon.set_data(*_horizon_data(l_h))
        x0 = cm.project_points(P_aff, RAIL_REFERENCE)
        centre_line = np.array([[0.0, RAIL_TRACK[0], 0.0], [0.0, RAIL_TRACK[1], 0.0]])
        P_para = af.paraperspective_approximation(cam, RAIL_REFERENCE)
        art.para.set_data(*cm.project_points(P_para, centre_line).T)
        for artists, xy in zip(references, (cam.project(RAIL_REFERENCE), x0), strict=True):
            place_reference(artists, xy)
        ys = np.repeat(RAIL_SAMPLES, 2) + [0.0, 1.0, 0.0, 1.0]
        ground = np.column_stack([np.zeros(4), ys, np.zeros(4)])
        for line, P_ in zip(measured, (cam.P, P_aff), strict=True):
            ends = cm.project_points(P_, ground)
            line.set_data(*np.insert(ends, 2, np.nan, axis=0).T)
        far_metre = cm.project_points(cam.P, ground[2:]).mean(axis=0)
        art.ring.set_data([far_metre[0]], [far_metre[1]])
        gaps = {
            "perspective": fixtures.sleeper_gaps(cam.P, RAIL_SAMPLES),
            "affine": fixtures.sleeper_gaps(P_aff, RAIL_SAMPLES),
        }
        for text, (near, far) in zip(texts, gaps.values(), strict=True):
            text.set_text(_rails_readout(near, far))
        state.update(
            vanishing_point=vpt,
            affine_direction=v_a,
            camera=cam,
            P_affine=P_aff,
            horizon=l_h,
            sleeper_gaps=gaps,
            reference_image=x0,
            P_para=P_para,
        )

    return build_demo(
        "parallel_rails",
        _rails_controls(),
        view,
        update,
        title="Parallel lines: vanishing versus parallel",
    )
