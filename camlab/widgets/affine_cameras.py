"""Demos for lesson 05, affine cameras.

In a lesson::

    %matplotlib widget
    from camlab.widgets import affine_cameras as demos
    demos.three_cameras()
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from matplotlib.legend_handler import HandlerTuple
from matplotlib.lines import Line2D

from .. import affine as af
from .. import camera as cm
from .. import fixtures, scenes
from ..plotting import palette, scene3d
from ._base import FigureView, build_demo, register, slider
from .controls import int_slider, log_slider

TARGET = np.array([0.0, 0.0, 0.5])
F0, D0 = 800.0, 4.0  # reference focal length (px) and distance (m) for the dolly zoom
DOLLY_VIEW = np.radians([-40.0, 20.0])  # the dolly zoom demo's azimuth and elevation
DOLLY_OFFSET = (
    100.0  # pixels right of the image centre where the dolly zoom keeps the cube (off axis)
)
# From 2 m with the cube up to 100 px off centre, every corner of all three images stays in the 640 x 480 frame.
DOLLY_DISTANCES = (2.0, 150.0)

# One colour per camera model in every lesson-05 figure and demo (the lesson's static figures use them too).
COLOURS = {
    "perspective": palette.RED,
    "weak perspective": palette.BLUE,
    "para-perspective": palette.GREEN,
    "orthographic": palette.PURPLE,
}
STYLES = {
    "perspective": "-",
    "weak perspective": "--",
    "para-perspective": ":",
    "orthographic": "-",
}


# The reference point X0 of every affine approximation (or its image), one marker in every lesson-05 figure.
REFERENCE_MARKER = dict(marker="D", ms=6, mfc="white", mec="0.1", mew=1.3, ls="none")
REFERENCE_LABEL = "X0, the reference point"


def reference_marker(ax, zorder=4):
    """The X0 marker on ``ax`` (a figure legend names it: a label beside it would cover the data), as a
    one-artist tuple, empty until :func:`place_reference` moves it."""
    (marker,) = ax.plot([], [], zorder=zorder, **REFERENCE_MARKER)
    return (marker,)


def place_reference(artists, xy):
    """Move the X0 marker made by :func:`reference_marker` to the point ``xy``."""
    artists[0].set_data([xy[0]], [xy[1]])


def model_line(ax, model, lw=1.1, **kw):
    """An empty line in ``model``'s colour and style, labelled with the model's name (for legends)."""
    (ln,) = ax.plot([], [], color=COLOURS[model], ls=STYLES[model], lw=lw, label=model, **kw)
    return ln


# Drawn above the X0 diamond (zorder 4), so the + stays visible where X0 images on the principal point.
PRINCIPAL_POINT_MARKER = dict(marker="+", color="0.3", ms=11, mew=1.2, ls="none", zorder=5)


def model_legend(fig, models, reference=False, principal_point=False, extra=(), **kw):
    """One legend above the figure naming each model's colour (drawn once, outside the data), the
    X0 marker if ``reference``, the principal point's if ``principal_point`` and ``extra`` handles."""
    handles = [Line2D([], [], color=COLOURS[m], ls=STYLES[m], lw=1.5, label=m) for m in models]
    if reference:
        handles.append(Line2D([], [], label=REFERENCE_LABEL, **REFERENCE_MARKER))
    if principal_point:
        handles.append(Line2D([], [], label="principal point", **PRINCIPAL_POINT_MARKER))
    handles += list(extra)
    return fig.legend(
        handles=handles,
        loc="outside upper center",
        ncols=len(handles),
        fontsize=8,
        frameon=False,
        **kw,
    )


def _image_panel(ax, title, model, size=(640, 480), tick_labels=True):
    # Short titles and few tick labels. Axis labels are static (drawn once into the background), so they
    # cost nothing per frame.
    scene3d.image_axes(ax, size)
    ax.set_title(title, fontsize=9)
    ax.tick_params(labelleft=tick_labels, labelbottom=tick_labels)
    return model_line(ax, model)


# The scene (a cube on the target, four rails through it) looks the same after a half turn about the vertical,
# so azimuth -90 .. 90 shows every view once.
@register(
    lesson="05",
    sweep={"azimuth": [-90, 10, 90], "elevation": [0, 50, 80], "distance": [2.0, 12.0, 20.0]},
)
def three_cameras():
    """Perspective, weak-perspective and orthographic images of the same scene side by side."""
    view = FigureView(figsize=(9.5, 3.35))
    axes = view.fig.subplots(1, 3)
    scene = fixtures.box_and_rails()
    persp = _image_panel(axes[0], "perspective (px)", "perspective")
    weak = _image_panel(axes[1], "weak perspective over perspective (px)", "weak perspective")
    axes[1].set_ylabel("")
    axes[2].set_aspect("equal")
    axes[2].set_title("orthographic (m; camera x right, y down)", fontsize=9)
    axes[2].set_xlabel("x (m)", fontsize=8)
    axes[2].set_ylabel("y (m)", fontsize=8)
    axes[2].set_xlim(-2.2, 2.2)
    axes[2].set_ylim(1.65, -1.65)
    axes[2].set_xticks([-2, 0, 2])
    axes[2].set_yticks([-1, 0, 1])
    axes[2].tick_params(labelsize=7)
    orth = model_line(axes[2], "orthographic")
    ghost = model_line(
        axes[1], "perspective", lw=0.8, zorder=1.5
    )  # under the blue dashes, live and redrawn alike
    model_legend(view.fig, ("perspective", "weak perspective", "orthographic"), reference=True)
    view.animate(persp, ghost, weak, orth)
    X0 = scene.reshape(-1, 3).mean(
        axis=0
    )  # the weak-perspective camera's reference point (three_images)
    references = [(view.animate(*reference_marker(ax)),) for ax in axes]  # the legend names it
    controls = {
        "azimuth": int_slider(-40, -90, 90, "azimuth (deg)", step=2),
        "elevation": int_slider(20, 0, 80, "elevation (deg)"),
        "distance": slider(4.0, 2.0, 20.0, 0.25, "distance (m), dolly zoom"),
    }

    def update(v, state):
        cam = af.dolly_zoom_camera(
            v["distance"], *np.radians([v["azimuth"], v["elevation"]]), TARGET, F0, D0
        )
        f = float(cam.K[0, 0])
        p, w, o, P_weak, P_orth = af.three_images(cam, scene)
        scene3d.update_segments(persp, p)
        scene3d.update_segments(weak, w)
        scene3d.update_segments(ghost, p)
        scene3d.update_segments(orth, o)
        images_of_X0 = [
            cam.project(X0),
            cm.project_points(P_weak, X0),
            cm.project_points(P_orth, X0),
        ]
        for artists, xy in zip(references, images_of_X0, strict=True):
            place_reference(artists, xy)
        state.update(
            camera=cam,
            P_weak=P_weak,
            focal=f,
            max_difference=af.largest_gap_in_frame(cam, P_weak, scene),
            reference_point=X0,
            reference_images=images_of_X0,
        )

    return build_demo(
        "three_cameras",
        controls,
        view,
        update,
        title="One scene, three cameras (the middle panel repeats the perspective image in red)",
    )


def dolly_curves(offset: float, distances: np.ndarray) -> dict:
    """RMS error (px) of weak and para-perspective along the dolly zoom with the cube ``offset`` px off centre."""
    pts = scenes.box_wireframe((0.0, 0.0, 0.5), (1.0, 1.0, 1.0)).reshape(-1, 3)
    return {
        m: af.dolly_zoom_errors(
            pts, distances, *DOLLY_VIEW, TARGET, F0, D0, approximation=f, image_offset=offset
        )
        for m, f in APPROXIMATIONS.items()
    }


APPROXIMATIONS = {
    "weak perspective": af.affine_approximation,
    "para-perspective": af.paraperspective_approximation,
}


DOLLY_ERROR_LIMITS = (
    0.2,
    60.0,
)  # px: every curve at every offset lies in 0.30 .. 40 px (tests/test_affine.py)


def _dolly_error_axes(ax, distances):
    """The dolly zoom's log-log error panel: one (empty) curve and one marker per affine model, a slope -1
    guide and the 1 px line."""
    from matplotlib.ticker import NullLocator

    curves = {
        m: ax.loglog(distances, np.ones_like(distances), color=COLOURS[m], ls=STYLES[m], lw=1.5)[0]
        for m in APPROXIMATIONS
    }
    ax.set_xlim(
        distances[0] / 1.15, distances[-1] * 1.15
    )  # room for the whole marker at the slider's ends
    ax.set_ylim(*DOLLY_ERROR_LIMITS)
    ax.set_title("RMS distance to the perspective image", fontsize=9)  # as the axis label says
    ax.set_xlabel(f"distance d (m); focal length f = {F0:.0f} d / {D0:.0f} px", fontsize=8)
    ax.set_ylabel("RMS distance (px)", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.axhline(1.0, color="0.5", lw=0.8, ls=":")
    ax.text(distances[-1], 1.15, "1 px", ha="right", va="bottom", fontsize=7, color="0.4")
    ax.loglog(
        distances, 5.0 * distances[0] / distances, color=palette.GREY, lw=0.8, zorder=1
    )  # below the curves
    ax.text(
        distances[0] * 1.05,
        DOLLY_ERROR_LIMITS[0] * 1.15,
        "grey: slope -1 (error ~ 1/d)",
        fontsize=7,
        color="0.35",
        va="bottom",
    )  # under the guide, which passes 0.3 px only beyond 30 m
    ax.grid(True, which="major", alpha=0.3)
    # Plain tick labels and no minor ticks: log axes' default mathtext labels cost ~20 ms a redraw.
    for axis, ticks in ((ax.xaxis, [2, 5, 10, 20, 50, 100]), (ax.yaxis, [0.3, 1, 3, 10, 30])):
        axis.set_minor_locator(NullLocator())
        axis.set_ticks(ticks, labels=[f"{t:g}" for t in ticks])
    # Weak perspective's marker larger than para-perspective's: on the axis (offset 0) the two coincide,
    # and the blue ring around the green dot shows both.
    sizes = {"weak perspective": 10, "para-perspective": 5}
    markers = {
        m: ax.plot([], [], "o", color=COLOURS[m], ms=sizes[m], clip_on=False, zorder=3)[0]
        for m in APPROXIMATIONS
    }
    return curves, markers


@register(lesson="05", sweep={"distance": [2.0, 6.0, 40.0, 150.0], "offset": [0, 50, 100]})
def dolly_zoom():
    """Move the camera away while zooming in (f = f0 d / D0): the object keeps its size, the
    perspective image approaches its affine approximations and their error falls like 1/d. Off
    the image centre, para-perspective stays closer than weak perspective; on the axis (offset 0)
    the two coincide. Each affine image has its own panel over the perspective one, so neither
    hides the other."""
    view = FigureView(figsize=(10, 3.9))
    ax_weak, ax_para, ax_err = view.fig.subplots(1, 3, width_ratios=(1.0, 1.0, 0.95))
    cube = scenes.box_wireframe((0.0, 0.0, 0.5), (1.0, 1.0, 1.0))
    pts = cube.reshape(-1, 3)
    models = ("perspective", "weak perspective", "para-perspective")
    lines, under, readouts, references = {}, {}, {}, {}
    for ax, m in ((ax_weak, "weak perspective"), (ax_para, "para-perspective")):
        scene3d.image_axes(ax, (640, 480))
        ax.set_title(f"{m} over perspective", fontsize=9)
        ax.tick_params(labelleft=ax is ax_weak)
        if ax is ax_para:
            ax.set_ylabel("")
        under[m] = model_line(
            ax, "perspective", lw=0.9, zorder=1.5
        )  # red under the affine cube, as in three_cameras
        lines[m] = model_line(
            ax, m, lw=1.6 if m == "weak perspective" else 1.9
        )  # the dots thicker, to read
        ax.plot([319.5], [239.5], **PRINCIPAL_POINT_MARKER)
        references[m] = reference_marker(ax)
        # The readout sits in the top-left corner, where no part of the cube comes at any setting (its images
        # stay right of u = 170 px and below v = 95 px).
        readouts[m] = ax.text(
            0.02, 0.975, "", transform=ax.transAxes, fontsize=8, ha="left", va="top"
        )
    distances = np.geomspace(*DOLLY_DISTANCES, 60)
    curves, markers = _dolly_error_axes(ax_err, distances)
    model_legend(view.fig, models, reference=True, principal_point=True)
    view.animate(
        *under.values(), *lines.values(), *readouts.values(), *curves.values(), *markers.values()
    )
    for artists in references.values():
        view.animate(*artists)
    # A log slider, as the error axis: the curves change fastest at a few metres.
    controls = {
        "distance": log_slider(
            D0, DOLLY_DISTANCES[0], DOLLY_DISTANCES[1], 0.01, "distance d (m)", readout_format=".3g"
        ),
        "offset": int_slider(int(DOLLY_OFFSET), 0, 100, "cube right of centre (px)", step=10),
    }
    cache: dict = {}

    def update(v, state):
        d, offset = float(v["distance"]), float(v["offset"])
        if offset not in cache:  # the curves depend on the offset only
            cache[offset] = dolly_curves(offset, distances)
        cam = af.dolly_zoom_camera(d, *DOLLY_VIEW, TARGET, F0, D0, image_offset=offset)
        perspective = cm.project_segments(cam, cube)
        x_X0 = cam.project(
            TARGET
        )  # every affine approximation images X0 where the perspective camera does
        rms = {}
        for m, approximate in APPROXIMATIONS.items():
            scene3d.update_segments(under[m], perspective)
            scene3d.update_segments(lines[m], cm.project_segments(approximate(cam, TARGET), cube))
            place_reference(references[m], x_X0)
            e = af.weak_perspective_error(cam, pts, TARGET, approximate)
            rms[m] = float(np.sqrt(np.mean(e**2)))
            readouts[m].set_text(
                f"RMS {rms[m]:.1f} px"
            )  # short: each glyph costs time in every frame
            markers[m].set_data([d], [rms[m]])
            curves[m].set_ydata(cache[offset][m])
        state.update(
            distance=d,
            offset=offset,
            focal=float(cam.K[0, 0]),
            rms_error=rms["weak perspective"],
            rms_paraperspective=rms["para-perspective"],
            curve=(distances, cache[offset]["weak perspective"]),
            curves=cache[offset],
            camera=cam,
            reference_image=x_X0,
        )

    return build_demo(
        "dolly_zoom",
        controls,
        view,
        update,
        title="Dolly zoom: when is an affine camera good enough?",
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
    """The rail demo's perspective camera looking along the track (+y), turned by ``yaw`` about the
    vertical and tilted down by ``pitch`` (radians; f = 500 px, 640 x 480), and its weak-perspective
    approximation about :data:`RAIL_REFERENCE`."""
    direction = cm.rotation_z(-yaw) @ np.array([0.0, np.cos(pitch), -np.sin(pitch)])
    cam = cm.Camera.look_at(
        RAIL_EYE, RAIL_EYE + direction, K=cm.intrinsic_matrix(500, 500, 319.5, 239.5)
    )
    return RailCameras(cam, af.affine_approximation(cam, RAIL_REFERENCE))


# Measured over the whole range (f = 500 px): yaw within +-15 and pitch 10 to 18 degrees keep the vanishing
# point and every point of the affine track at least 13 px inside the 640 x 480 frame
# (tests/test_affine.py::test_parallel_rails_keeps_everything_in_frame), and the affine sleepers at
# least 7 px apart.
@register(lesson="05", sweep={"yaw": [-15, 15], "pitch": [10, 18]})
def parallel_rails():
    """Parallel rails meet at a vanishing point in perspective; an affine image keeps them parallel,
    and keeps equal sleepers equal at every depth (no shrinking with distance)."""
    view = FigureView(figsize=(10, 4.6))
    ax_p, ax_a = view.fig.subplots(1, 2)
    scene = fixtures.rail_track(*RAIL_TRACK)
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
    (vp,) = ax_p.plot([], [], "o", color=COLOURS["perspective"], ms=8, mfc="white", mew=2)
    (horizon,) = ax_p.plot([], [], color=palette.GREY, lw=0.8, ls="--")
    # The two metres of track the readouts measure (x = 0, from y to y + 1), thick and dark in both panels.
    measured = [
        ax.plot([], [], color="0.1", lw=3.5, solid_capstyle="butt", zorder=3)[0]
        for ax in (ax_p, ax_a)
    ]
    # The far metre images only a few pixels long in perspective: a ring shows where it is.
    (ring,) = ax_p.plot([], [], "o", ms=15, mfc="none", mec="0.1", mew=1.1, zorder=3)
    view.animate(*lines, vp, horizon, *measured, ring, *texts)
    references = [
        (view.animate(*reference_marker(ax)),) for ax in (ax_p, ax_a)
    ]  # where the two images agree
    model_legend(
        view.fig,
        (),
        reference=True,
        extra=(
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
    )
    controls = {
        "yaw": int_slider(0, -15, 15, "yaw (deg, + turns right)"),
        "pitch": int_slider(15, 10, 18, "pitch down (deg)"),
    }

    def update(v, state):
        cam, P_aff = rail_cameras(*np.deg2rad([v["yaw"], v["pitch"]]))
        lines[0].set_data(*scene3d.polyline_data(cm.project_segments(cam, scene)).T)
        lines[1].set_data(*scene3d.polyline_data(cm.project_segments(P_aff, scene)).T)
        v_p = af.image_of_direction(cam.P, [0.0, 1.0, 0.0])
        v_a = af.image_of_direction(P_aff, [0.0, 1.0, 0.0])
        vpt = v_p[:2] / v_p[2]
        vp.set_data([vpt[0]], [vpt[1]])
        # the horizon: the line through the vanishing points of two ground directions
        l_h = np.cross(af.image_of_direction(cam.P, [1.0, 0.0, 0.0]), v_p)
        us = np.array([-1.0, 641.0])
        horizon.set_data(
            us, -(l_h[0] * us + l_h[2]) / l_h[1] if abs(l_h[1]) > 1e-12 else [np.nan, np.nan]
        )
        x0 = cm.project_points(P_aff, RAIL_REFERENCE)
        for artists, xy in zip(references, (cam.project(RAIL_REFERENCE), x0), strict=True):
            place_reference(artists, xy)
        ys = np.repeat(RAIL_SAMPLES, 2) + [0.0, 1.0, 0.0, 1.0]
        ground = np.column_stack([np.zeros(4), ys, np.zeros(4)])
        for line, P_ in zip(measured, (cam.P, P_aff), strict=True):
            ends = cm.project_points(P_, ground)
            line.set_data(*np.insert(ends, 2, np.nan, axis=0).T)
        far_metre = cm.project_points(cam.P, ground[2:]).mean(axis=0)
        ring.set_data([far_metre[0]], [far_metre[1]])
        gaps = {
            "perspective": fixtures.sleeper_gaps(cam.P, RAIL_SAMPLES),
            "affine": fixtures.sleeper_gaps(P_aff, RAIL_SAMPLES),
        }
        for text, (near, far) in zip(texts, gaps.values(), strict=True):
            text.set_text(
                f"1 m of track: {near:5.1f} px at {RAIL_SAMPLES[0]:.0f} m, {far:5.1f} px at {RAIL_SAMPLES[1]:.0f} m"
            )
        state.update(
            vanishing_point=vpt,
            affine_direction=v_a,
            camera=cam,
            P_affine=P_aff,
            horizon=l_h,
            sleeper_gaps=gaps,
            reference_image=x0,
        )

    return build_demo(
        "parallel_rails", controls, view, update, title="Parallel lines: vanishing versus parallel"
    )


CENTRE_MARKER = dict(marker="o", color="0.1", ms=5, ls="none")  # the camera centre in the top views
SCALING_STYLE = (
    0,
    (1.5, 2),
)  # the uniform scaling f / d0 of weak and para-perspective, after their rays
SIGHT_STYLE = dict(
    color="0.2", lw=1.0, ls="-."
)  # the line of sight to X0: dash-dot, unlike every other line

RAY_DEPTH = 6.0  # d0: depth of the object's centre in the ray diagram (metres)
RAY_IMAGE = 3.0  # where the ray diagram draws the image line (z, metres)
_TURN = np.radians(
    12.0
)  # the block is turned, so rays parallel to the axis do not run along its sides
RAY_OBJECT = np.array([[-0.8, -1.0], [0.8, -1.0], [0.8, 1.0], [-0.8, 1.0]]) @ np.array(
    [[np.cos(_TURN), np.sin(_TURN)], [-np.sin(_TURN), np.cos(_TURN)]]
)  # a 1.6 m x 2 m block about X0 (x, z), metres


def _joined(*polylines):
    """Polylines (each (K, 2)) as one (x, y) pair separated by NaN, for one Line2D."""
    rows = [np.vstack([p, [np.nan, np.nan]]) for p in polylines]
    return np.vstack(rows).T if rows else np.empty((2, 0))


@register(lesson="05", sweep={"offset": [0.0, 1.0, 2.5]})
def projection_rays():
    """A top view of four camera models (after Szeliski fig. 2.7): how each sends the
    corners of a block to the image line. Move the block sideways: on the optical axis weak and
    para-perspective coincide; off it, para-perspective's rays run parallel to the line of sight to X0
    (drawn dash-dot), its viewing direction, as weak perspective's run parallel to the optical axis."""
    view = FigureView(figsize=(10, 4.75))
    axes = view.fig.subplots(1, 4, sharey=True)
    artists = {}
    for ax, model in zip(axes, af.PROJECTION_MODELS, strict=True):
        ax.set_xlim(-1.3, 4.0)  # the turned block reaches x = -0.99 m at offset 0
        ax.set_ylim(-0.4, 7.4)
        ax.set_aspect("equal")
        ax.set_title(model, fontsize=9, color=COLOURS[model])
        ax.set_xlabel("x (m)", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.axvline(0.0, color=palette.GREY, lw=0.6, ls=":")  # the optical axis
        ax.axhline(RAY_IMAGE, color="0.3", lw=1.0)  # the image line
        if model != "orthographic":  # an orthographic camera has no centre (it is at infinity)
            ax.plot([0], [0], **CENTRE_MARKER)
        if model in ("weak perspective", "para-perspective"):
            ax.axhline(
                RAY_DEPTH, color="0.4", lw=0.8, ls="--"
            )  # the plane z = d0 (dark enough over the block)
        block = ax.fill([], [], color=palette.GREY, alpha=0.18, lw=0)[
            0
        ]  # light: rays and the plane z = d0 cross it
        rays = ax.plot([], [], color=COLOURS[model], lw=1.0)[0]
        scaling = ax.plot([], [], color=COLOURS[model], lw=0.7, ls=SCALING_STYLE)[0]
        images = ax.plot([], [], "o", color=COLOURS[model], ms=4)[0]
        truth = ax.plot([], [], "|", color=COLOURS["perspective"], ms=10, mew=1.5)[
            0
        ]  # perspective, to compare
        x0 = ax.plot([], [], zorder=4, **REFERENCE_MARKER)[0]
        artists[model] = (block, rays, scaling, images, truth, x0)
        view.animate(*artists[model])
    # Para-perspective's rays are parallel to the line of sight to X0 (its viewing direction), as weak
    # perspective's are to the optical axis (the dotted vertical).
    sight = view.animate(axes[2].plot([], [], zorder=1.8, **SIGHT_STYLE)[0])
    corner_images = tuple(
        Line2D([], [], marker="o", color=COLOURS[m], ms=4, ls="none") for m in af.PROJECTION_MODELS
    )
    view.fig.legend(
        handles=[
            Line2D(
                [],
                [],
                color="0.25",
                lw=1.0,
                label="ray (solid; weak and para-perspective: up to z = d0)",
            ),
            Line2D(
                [],
                [],
                color="0.25",
                lw=0.7,
                ls=SCALING_STYLE,
                label="then the scaling f / d0 towards the centre",
            ),
            Line2D([], [], color="0.4", lw=0.8, ls="--", label="the plane z = d0"),
            Line2D([], [], color=palette.GREY, lw=0.8, ls=":", label="optical axis"),
            Line2D([], [], label="camera centre", **CENTRE_MARKER),
            corner_images,
            Line2D(
                [],
                [],
                marker="|",
                color=COLOURS["perspective"],
                ms=10,
                mew=1.5,
                ls="none",
                label="perspective image, to compare",
            ),
            Line2D([], [], label="line of sight to X0", **SIGHT_STYLE),
            Line2D([], [], label=REFERENCE_LABEL, **REFERENCE_MARKER),
        ],
        labels=[
            "ray (solid; weak and para-perspective: up to z = d0)",
            "then the scaling f / d0 towards the centre",
            "the plane z = d0",
            "optical axis",
            "camera centre",
            "image of a corner (each camera's colour)",
            "perspective image, to compare",
            "line of sight to X0",
            REFERENCE_LABEL,
        ],
        handler_map={tuple: HandlerTuple(ndivide=None, pad=0.1)},
        loc="outside upper center",
        ncols=3,
        fontsize=8,
        frameon=False,
    )
    axes[0].set_ylabel("depth z (m)", fontsize=8)
    axes[0].set_yticks(
        [0, RAY_IMAGE, RAY_DEPTH],
        labels=["0: centre", f"{RAY_IMAGE:g}: image", f"{RAY_DEPTH:g}: d0"],
    )
    controls = {"offset": slider(2.0, 0.0, 2.5, 0.25, "block's x offset (m)")}

    def update(v, state):
        reference = np.array([float(v["offset"]), RAY_DEPTH])
        corners = RAY_OBJECT + reference
        perspective = af.projection_rays(corners, reference, "perspective", RAY_IMAGE)[:, 2]
        images_x = {}
        for model, (block, rays, scaling, images, truth, x0) in artists.items():
            r = af.projection_rays(corners, reference, model, RAY_IMAGE)
            block.set_xy(corners)
            if model == "perspective":  # the ray runs on through the image line to the centre
                rays.set_data(*_joined(*([p, [0.0, 0.0]] for p in r[:, 0])))
            elif model == "orthographic":  # parallel to the axis, straight onto the image line
                rays.set_data(*_joined(*r[:, [0, 2]]))
            else:  # parallel onto z = d0, then only the uniform scaling f / d0
                rays.set_data(*_joined(*r[:, :2]))
            scaled = model in ("weak perspective", "para-perspective")
            scaling.set_data(*_joined(*([p, [0.0, 0.0]] for p in r[:, 1])) if scaled else ([], []))
            images.set_data(*r[:, 2].T)
            compare = model in (
                "weak perspective",
                "para-perspective",
            )  # same image scale as perspective
            truth.set_data(*(perspective.T if compare else ([], [])))
            x0.set_data([reference[0]], [reference[1]])
            images_x[model] = r[:, 2, 0]
        top = 7.4 / RAY_DEPTH  # the line of sight from the centre through X0 to the top of the axes
        sight.set_data([0.0, top * reference[0]], [0.0, top * reference[1]])
        state.update(reference=reference, image_x=images_x)

    return build_demo(
        "projection_rays",
        controls,
        view,
        update,
        title="Four cameras from above: where each sends the block's corners",
    )
