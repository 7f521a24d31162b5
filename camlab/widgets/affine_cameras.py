"""Demos for lesson 05, affine cameras.

In a lesson::

    %matplotlib widget
    from camlab.widgets import affine_cameras as demos
    demos.three_cameras()
"""
from __future__ import annotations

import numpy as np

from .. import affine as af
from .. import camera as cm
from .. import scenes
from ..plotting import palette, scene3d
from ._base import FigureView, build_demo, register, slider

TARGET = np.array([0.0, 0.0, 0.5])
F0, D0 = 800.0, 4.0  # reference focal length (px) and distance (m) for the dolly zoom
DOLLY_VIEW = np.radians([-40.0, 20.0])  # the dolly zoom demo's azimuth and elevation


def _image_panel(ax, title, size=(640, 480), tick_labels=True):
    # Short titles and few tick labels: every text costs about 1 ms per redraw.
    scene3d.image_axes(ax, size, labels=False)
    ax.set_title(title, fontsize=9)
    ax.tick_params(labelleft=tick_labels, labelbottom=tick_labels)
    (ln,) = ax.plot([], [], color="k", lw=1.1)
    return ln


@register(lesson="05", sweep={"azimuth": [-80, 10], "elevation": [5, 50], "distance": [2.5, 12.0]})
def three_cameras():
    """Perspective, weak-perspective and orthographic images of the same scene side by side."""
    view = FigureView(figsize=(9.5, 3.2))
    axes = view.fig.subplots(1, 3)
    scene = scenes.box_and_rails()
    persp = _image_panel(axes[0], "perspective")
    weak = _image_panel(axes[1], "weak perspective", tick_labels=False)
    axes[2].set_aspect("equal")
    axes[2].set_title("orthographic (metres)", fontsize=9)
    axes[2].set_xlim(-2.2, 2.2)
    axes[2].set_ylim(1.65, -1.65)
    axes[2].set_xticks([-2, 0, 2])
    axes[2].set_yticks([-1, 0, 1])
    axes[2].tick_params(labelsize=7)
    (orth,) = axes[2].plot([], [], color="k", lw=1.1)
    (ghost,) = axes[1].plot([], [], color=palette.RED, lw=0.8, ls="--")
    view.animate(persp, weak, ghost, orth)
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
                      title="One scene, three cameras (red: the perspective image, for comparison)")


@register(lesson="05", sweep={"distance": [1.8, 6.0, 40.0]})
def dolly_zoom():
    """Move the camera away while zooming in (f = f0 d / d0): the object keeps its size, the
    perspective image approaches the weak-perspective one and the error falls like 1/d."""
    view = FigureView(figsize=(9, 3.8))
    ax_img, ax_err = view.fig.subplots(1, 2, width_ratios=(1.25, 1.0))
    cube = scenes.box_wireframe((0.0, 0.0, 0.5), (1.0, 1.0, 1.0))
    pts = cube.reshape(-1, 3)
    _image_panel(ax_img, "black: perspective, orange: weak perspective", tick_labels=False).remove()
    (persp,) = ax_img.plot([], [], color="k", lw=1.3)
    (weak,) = ax_img.plot([], [], color=palette.ORANGE, lw=1.3, ls="--")
    distances = np.geomspace(1.6, 60.0, 60)
    curve = af.dolly_zoom_errors(pts, distances, *DOLLY_VIEW, TARGET, F0, D0)
    depth_ratio = np.sqrt(3.0) / distances  # the cube's depth range (its diagonal) over its distance
    ax_err.loglog(distances, curve, color="tab:blue", lw=1.5)
    ax_err.set_xlabel("distance d (m), focal length f = f0 d / d0", fontsize=8)
    ax_err.set_ylabel("RMS difference (px)", fontsize=8)
    ax_err.tick_params(labelsize=7)
    ax_err.axhline(1.0, color="0.5", lw=0.8, ls=":")
    ax_err.text(distances[-1], 1.05, "1 px", ha="right", va="bottom", fontsize=7, color="0.4")
    ax_err.grid(True, which="major", alpha=0.3)
    # Plain tick labels and no minor ticks: log axes' default mathtext labels cost ~20 ms a redraw.
    from matplotlib.ticker import NullLocator

    for axis, ticks in ((ax_err.xaxis, [2, 5, 10, 20, 50]), (ax_err.yaxis, [0.1, 1, 10, 100])):
        axis.set_minor_locator(NullLocator())
        axis.set_ticks(ticks, labels=[f"{t:g}" for t in ticks])
    (marker,) = ax_err.plot([], [], "o", color="tab:red", ms=7)
    view.animate(persp, weak, marker)
    controls = {"distance": slider(D0, 1.6, 60.0, 0.2, "distance d (m)")}

    def update(v, state):
        d = float(v["distance"])
        cam = af.dolly_zoom_camera(d, *DOLLY_VIEW, TARGET, F0, D0)
        f = float(cam.K[0, 0])
        P_weak = af.affine_approximation(cam, TARGET)
        scene3d.update_segments(persp, cm.project_segments(cam, cube))
        scene3d.update_segments(weak, cm.project_segments(P_weak, cube))
        e = af.weak_perspective_error(cam, pts, TARGET)
        rms = float(np.sqrt(np.mean(e ** 2)))
        marker.set_data([d], [rms])
        state.update(distance=d, focal=f, rms_error=rms, max_error=float(e.max()),
                     depth_ratio=float(np.sqrt(3.0) / d), curve=(distances, curve, depth_ratio))

    return build_demo("dolly_zoom", controls, view, update, title="Dolly zoom: when is weak perspective good enough?")


# Yaw and pitch stay within the field of view (f = 500 px: half-angles 33 and 26 degrees), so
# the perspective image always shows the vanishing point or the track, like the affine one.
@register(lesson="05", sweep={"yaw": [-30, 30], "pitch": [2, 40]})
def parallel_rails():
    """Parallel rails meet at a vanishing point in perspective; an affine image keeps them parallel,
    and keeps equal sleepers equal at every depth (no foreshortening)."""
    view = FigureView(figsize=(10, 4.0))
    ax_p, ax_a = view.fig.subplots(1, 2)
    scene = scenes.rail_track()
    ax_p.set_title("perspective: rails meet, far sleepers crowd", fontsize=9)
    ax_a.set_title("affine: rails stay parallel, sleepers stay evenly spaced", fontsize=9)
    lines, texts = [], []
    for ax in (ax_p, ax_a):
        ax.set_xlim(-0.5, 639.5)
        ax.set_ylim(479.5, -0.5)
        ax.set_aspect("equal")
        ax.set_xticks([0, 320, 640])
        ax.set_yticks([0, 240, 480])
        ax.set_xlabel("u (px)", fontsize=8)
        ax.tick_params(labelsize=7, labelleft=ax is ax_p)
        (ln,) = ax.plot([], [], color="k", lw=1.0)
        lines.append(ln)
        texts.append(ax.text(0.02, 0.97, "", transform=ax.transAxes, fontsize=8, family="monospace", va="top",
                             bbox=dict(fc="white", ec="0.8", alpha=0.9)))
    ax_p.set_ylabel("v (px)", fontsize=8)
    (vp,) = ax_p.plot([], [], "o", color="tab:red", ms=8)
    (horizon,) = ax_p.plot([], [], color="tab:red", lw=0.8, ls="--")
    view.animate(*lines, vp, horizon, *texts)
    controls = {"yaw": slider(0, -30, 30, 1, "yaw (deg)"), "pitch": slider(15, 2, 40, 1, "pitch down (deg)")}

    def update(v, state):
        yaw, pitch = np.deg2rad(v["yaw"]), np.deg2rad(v["pitch"])
        eye = np.array([0.0, -4.0, 2.0])
        # look along the rails (+Y), turned by yaw about Z and tilted down by pitch
        direction = cm.rotation_z(-yaw) @ np.array([0.0, np.cos(pitch), -np.sin(pitch)])
        cam = cm.Camera.look_at(eye, eye + direction, K=cm.intrinsic_matrix(500, 500, 320, 240))
        P_aff = af.affine_approximation(cam, np.array([0.0, 6.0, 0.0]))
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
            text.set_text(f"1 m of track: {near:5.1f} px near\n              {far:5.1f} px at 20 m")
        state.update(vanishing_point=vpt, affine_direction=v_a, camera=cam, P_affine=P_aff, horizon=l_h,
                     sleeper_gaps=gaps)

    return build_demo("parallel_rails", controls, view, update, title="Parallel lines: vanishing versus parallel")
