"""Demos for lesson 05, affine cameras.

In a lesson::

    %matplotlib widget
    from camlab.widgets import affine_cameras as demos
    demos.three_cameras()
"""
from __future__ import annotations

import numpy as np
from matplotlib.lines import Line2D

from .. import affine as af
from .. import camera as cm
from .. import scenes
from ..plotting import palette, scene3d
from ._base import FigureView, build_demo, register, slider

TARGET = np.array([0.0, 0.0, 0.5])
F0, D0 = 800.0, 4.0  # reference focal length (px) and distance (m) for the dolly zoom
DOLLY_VIEW = np.radians([-40.0, 20.0])  # the dolly zoom demo's azimuth and elevation
DOLLY_OFFSET = 150.0  # pixels right of the image centre where the dolly zoom keeps the cube (off axis)

# One colour per camera model in every lesson-05 figure and demo (the lesson's static figures use them too).
COLOURS = {"perspective": palette.RED, "weak perspective": palette.BLUE, "para-perspective": palette.GREEN,
           "orthographic": palette.PURPLE}
STYLES = {"perspective": "-", "weak perspective": "--", "para-perspective": ":", "orthographic": "-"}


def model_line(ax, model, lw=1.1, **kw):
    """An empty line in ``model``'s colour and style, labelled with the model's name (for legends)."""
    (ln,) = ax.plot([], [], color=COLOURS[model], ls=STYLES[model], lw=lw, label=model, **kw)
    return ln


def model_legend(fig, models, **kw):
    """One legend above the figure naming each model's colour (drawn once, outside the data)."""
    handles = [Line2D([], [], color=COLOURS[m], ls=STYLES[m], lw=1.5, label=m) for m in models]
    return fig.legend(handles=handles, loc="outside upper center", ncols=len(handles), fontsize=8, frameon=False, **kw)


def _image_panel(ax, title, model, size=(640, 480), tick_labels=True):
    # Short titles and few tick labels: every text costs about 1 ms per redraw.
    scene3d.image_axes(ax, size, labels=False)
    ax.set_title(title, fontsize=9)
    ax.tick_params(labelleft=tick_labels, labelbottom=tick_labels)
    return model_line(ax, model)


@register(lesson="05", sweep={"azimuth": [-80, 10], "elevation": [5, 50], "distance": [2.5, 12.0]})
def three_cameras():
    """Perspective, weak-perspective and orthographic images of the same scene side by side."""
    view = FigureView(figsize=(9.5, 3.4))
    axes = view.fig.subplots(1, 3)
    scene = scenes.box_and_rails()
    persp = _image_panel(axes[0], "perspective (px)", "perspective")
    weak = _image_panel(axes[1], "weak perspective over perspective (px)", "weak perspective", tick_labels=False)
    axes[2].set_aspect("equal")
    axes[2].set_title("orthographic (metres)", fontsize=9)
    axes[2].set_xlim(-2.2, 2.2)
    axes[2].set_ylim(1.65, -1.65)
    axes[2].set_xticks([-2, 0, 2])
    axes[2].set_yticks([-1, 0, 1])
    axes[2].tick_params(labelsize=7)
    orth = model_line(axes[2], "orthographic")
    ghost = model_line(axes[1], "perspective", lw=0.8)
    model_legend(view.fig, ("perspective", "weak perspective", "orthographic"))
    view.animate(persp, ghost, weak, orth)
    controls = {
        "azimuth": slider(-40, -180, 180, 2, "azimuth (deg)"),
        "elevation": slider(20, 0, 80, 1, "elevation (deg)"),
        "distance": slider(4.0, 2.0, 20.0, 0.25, "distance (m), dolly zoom"),
    }

    def update(v, state):
        cam = af.dolly_zoom_camera(v["distance"], *np.radians([v["azimuth"], v["elevation"]]), TARGET, F0, D0)
        f = float(cam.K[0, 0])
        p, w, o, P_weak, _ = af.three_images(cam, scene)
        scene3d.update_segments(persp, p)
        scene3d.update_segments(weak, w)
        scene3d.update_segments(ghost, p)
        scene3d.update_segments(orth, o)
        diff = np.linalg.norm(p - w, axis=-1)
        state.update(camera=cam, P_weak=P_weak, focal=f, max_difference=float(np.nanmax(diff)))

    return build_demo("three_cameras", controls, view, update,
                      title="One scene, three cameras (the middle panel repeats the perspective image in red)")


@register(lesson="05", sweep={"distance": [1.8, 6.0, 40.0, 150.0]})
def dolly_zoom():
    """Move the camera away while zooming in (f = f0 d / d0): the object keeps its size, the
    perspective image approaches its affine approximations and their error falls like 1/d; off
    the image centre, para-perspective stays closer than weak perspective."""
    view = FigureView(figsize=(9, 4.0))
    ax_img, ax_err = view.fig.subplots(1, 2, width_ratios=(1.25, 1.0))
    cube = scenes.box_wireframe((0.0, 0.0, 0.5), (1.0, 1.0, 1.0))
    pts = cube.reshape(-1, 3)
    models = ("perspective", "weak perspective", "para-perspective")
    approximations = {"weak perspective": af.affine_approximation, "para-perspective": af.paraperspective_approximation}
    scene3d.image_axes(ax_img, (640, 480), labels=False)
    ax_img.set_title("a 1 m cube (px)", fontsize=9)
    ax_img.tick_params(labelleft=False, labelbottom=False)
    lines = {m: model_line(ax_img, m, lw=1.3) for m in models}
    distances = np.geomspace(1.6, 150.0, 60)
    curves = {m: af.dolly_zoom_errors(pts, distances, *DOLLY_VIEW, TARGET, F0, D0, approximation=f,
                                       image_offset=DOLLY_OFFSET)
              for m, f in approximations.items()}
    for m, curve in curves.items():
        ax_err.loglog(distances, curve, color=COLOURS[m], ls=STYLES[m], lw=1.5)
    ax_err.set_title("RMS distance to the perspective image", fontsize=9)
    ax_err.set_xlabel("distance d (m), focal length f = f0 d / d0", fontsize=8)
    ax_err.set_ylabel("RMS difference (px)", fontsize=8)
    ax_err.tick_params(labelsize=7)
    ax_err.axhline(1.0, color="0.5", lw=0.8, ls=":")
    ax_err.text(distances[-1], 1.05, "1 px", ha="right", va="bottom", fontsize=7, color="0.4")
    ax_err.grid(True, which="major", alpha=0.3)
    # Plain tick labels and no minor ticks: log axes' default mathtext labels cost ~20 ms a redraw.
    from matplotlib.ticker import NullLocator

    for axis, ticks in ((ax_err.xaxis, [2, 5, 10, 20, 50, 100]), (ax_err.yaxis, [0.01, 0.1, 1, 10, 100])):
        axis.set_minor_locator(NullLocator())
        axis.set_ticks(ticks, labels=[f"{t:g}" for t in ticks])
    markers = {m: ax_err.plot([], [], "o", color=COLOURS[m], ms=7)[0] for m in approximations}
    model_legend(view.fig, models)
    view.animate(*lines.values(), *markers.values())
    controls = {"distance": slider(D0, 1.6, 150.0, 0.2, "distance d (m)")}

    def update(v, state):
        d = float(v["distance"])
        cam = af.dolly_zoom_camera(d, *DOLLY_VIEW, TARGET, F0, D0, image_offset=DOLLY_OFFSET)
        scene3d.update_segments(lines["perspective"], cm.project_segments(cam, cube))
        rms = {}
        for m, approximate in approximations.items():
            scene3d.update_segments(lines[m], cm.project_segments(approximate(cam, TARGET), cube))
            e = af.weak_perspective_error(cam, pts, TARGET, approximate)
            rms[m] = float(np.sqrt(np.mean(e ** 2)))
            markers[m].set_data([d], [rms[m]])
        state.update(distance=d, focal=float(cam.K[0, 0]), rms_error=rms["weak perspective"],
                     rms_paraperspective=rms["para-perspective"], curve=(distances, curves["weak perspective"]),
                     curves=curves)

    return build_demo("dolly_zoom", controls, view, update, title="Dolly zoom: when is an affine camera good enough?")


RAIL_EYE = np.array([0.0, -4.0, 2.0])  # 2 m above the track, 4 m behind its start (metres)
RAIL_REFERENCE = np.array([0.0, 8.0, 0.0])  # a third of the way along the track: the affine camera's reference point
RAIL_TRACK = (-3.0, 25.0)  # where the track starts and ends along +y (metres)


def rail_cameras(yaw: float, pitch: float):
    """The rail demo's perspective camera looking along the track (+y), turned by ``yaw`` about the
    vertical and tilted down by ``pitch`` (radians; f = 500 px, 640 x 480), and its weak-perspective
    approximation about :data:`RAIL_REFERENCE`."""
    direction = cm.rotation_z(-yaw) @ np.array([0.0, np.cos(pitch), -np.sin(pitch)])
    cam = cm.Camera.look_at(RAIL_EYE, RAIL_EYE + direction, K=cm.intrinsic_matrix(500, 500, 319.5, 239.5))
    return cam, af.affine_approximation(cam, RAIL_REFERENCE)


# Yaw and pitch keep the vanishing point in the field of view (f = 500 px: half-angles 33 and 26
# degrees); 10 to 22 degrees of pitch keep the affine image's sleepers apart (it squashes depth
# along the line of sight) and its far end in the frame.
@register(lesson="05", sweep={"yaw": [-30, 30], "pitch": [10, 22]})
def parallel_rails():
    """Parallel rails meet at a vanishing point in perspective; an affine image keeps them parallel,
    and keeps equal sleepers equal at every depth (no foreshortening)."""
    view = FigureView(figsize=(10, 4.3))
    ax_p, ax_a = view.fig.subplots(1, 2)
    scene = scenes.rail_track(*RAIL_TRACK)
    ax_p.set_title("perspective: rails meet, far sleepers crowd", fontsize=9)
    ax_a.set_title("weak perspective: rails stay parallel, sleepers evenly spaced", fontsize=9)
    lines, texts = [], []
    for ax, model in ((ax_p, "perspective"), (ax_a, "weak perspective")):
        scene3d.image_axes(ax, (640, 480))
        ax.tick_params(labelleft=ax is ax_p)
        lines.append(model_line(ax, model, lw=1.0))
        lines[-1].set_linestyle("-")  # dashes would break up sleepers a few pixels apart
        # The readout sits under the axes, where no rail can run.
        texts.append(ax.text(0.5, -0.11, "", transform=ax.transAxes, fontsize=8, family="monospace",
                             ha="center", va="top"))
    ax_a.set_ylabel("")
    (vp,) = ax_p.plot([], [], "o", color=COLOURS["perspective"], ms=8, mfc="white", mew=2)
    (horizon,) = ax_p.plot([], [], color=palette.GREY, lw=0.8, ls="--")
    view.animate(*lines, vp, horizon, *texts)
    controls = {"yaw": slider(0, -30, 30, 1, "yaw (deg)"), "pitch": slider(15, 10, 22, 1, "pitch down (deg)")}

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
        horizon.set_data(us, -(l_h[0] * us + l_h[2]) / l_h[1] if abs(l_h[1]) > 1e-12 else [np.nan, np.nan])
        gaps = {"perspective": scenes.sleeper_gaps(cam.P), "affine": scenes.sleeper_gaps(P_aff)}
        for text, (near, far) in zip(texts, gaps.values()):
            text.set_text(f"1 m of track: {near:5.1f} px near the camera, {far:5.1f} px at 20 m")
        state.update(vanishing_point=vpt, affine_direction=v_a, camera=cam, P_affine=P_aff, horizon=l_h,
                     sleeper_gaps=gaps)

    return build_demo("parallel_rails", controls, view, update, title="Parallel lines: vanishing versus parallel")
