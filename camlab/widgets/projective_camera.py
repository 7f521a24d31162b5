"""Demos for lesson 04, the projective camera P = K [R | t].

In a lesson::

    %matplotlib widget
    from camlab.widgets import projective_camera as demos
    demos.camera_explorer()
"""
from __future__ import annotations

import ipywidgets as W
import numpy as np

from .. import camera as cm
from .. import scenes
from ..plotting import scene3d
from ._base import FigureView, build_demo, register, slider
from .controls import int_slider
from ..plotting import palette

TARGET = np.array([0.0, 0.0, 0.7])
# The explorer's 3-D viewer orbits with the camera, this many degrees ahead of it: at a fixed viewer
# angle, one orbit position looked straight down the camera's axis and piled everything up.
VIEWER_OFFSET = 40.0


def _fmt(v: np.ndarray) -> str:
    return "(" + ", ".join(f"{x:+.2f}" for x in v) + ")"


@register(lesson="04", sweep={"fx": [400, 1200], "fy": [500, 1100], "cx": [199.5, 419.5], "cy": [159.5, 319.5],
                              "skew": [-150, 150], "azimuth": [-140, -20], "elevation": [5, 60],
                              "distance": [3.5, 8.0]})
def camera_explorer():
    """Intrinsics and pose sliders beside a live 3-D frustum view and the camera's image.

    The text under the image shows t (the world origin in camera coordinates) next to
    the centre C = -R^T t (the camera in world coordinates): two different vectors.
    """
    view = FigureView(figsize=(9, 4.2))
    scene = scenes.house_scene()
    cam0 = cm.Camera.look_at(cm.orbit_eye(np.radians(-60), np.radians(25), 5.0, TARGET), TARGET)
    # Seen from behind the camera's shoulder, with only the house on the image plane: the small picture
    # stays readable (the whole grid, seen edge-on, was a tangle).
    sv = scene3d.SceneView(view.fig, cam0, scene, plane_size=2.0, thumbnail=scenes.house_wireframe(),
                           azim=-60 + VIEWER_OFFSET, elev=16)
    info = W.HTML()  # numbers beside the figure: text outside the canvas costs no redraw time
    (pp,) = sv.ax_image.plot([], [], "+", color="tab:purple", ms=10, mew=2)
    view.animate(*sv.artists(), pp)
    controls = {
        "fx": slider(800, 200, 1600, 10, "fx (px)"),
        "fy": slider(800, 200, 1600, 10, "fy (px)"),
        # The image centre is ((W - 1) / 2, (H - 1) / 2) with pixel centres at integers (docs/conventions.md).
        "cx": slider(319.5, -0.5, 639.5, 5, "cx (px)"),
        "cy": slider(239.5, -0.5, 479.5, 5, "cy (px)"),
        "skew": slider(0, -300, 300, 10, "skew s (px)"),
        "azimuth": slider(-60, -180, 180, 2, "azimuth (deg)"),
        "elevation": slider(25, -10, 80, 1, "elevation (deg)"),
        "distance": slider(5.0, 2.5, 9.0, 0.1, "distance (m)"),
    }

    def update(v, state):
        K = cm.intrinsic_matrix(v["fx"], v["fy"], v["cx"], v["cy"], v["skew"])
        cam = cm.Camera.look_at(cm.orbit_eye(*np.radians([v["azimuth"], v["elevation"]]), v["distance"], TARGET), TARGET,
                                K=K)
        sv.ax3d.view_init(elev=16, azim=v["azimuth"] + VIEWER_OFFSET)   # sv.update refreshes the projection
        sv.update(cam)
        pp.set_data([cam.principal_point[0]], [cam.principal_point[1]])
        info.value = (f"<pre>t = {_fmt(cam.t)} m  (world origin in camera frame)\n"
                      f"C = -R^T t = {_fmt(cam.centre)} m  (camera in world)</pre>")
        state.update(camera=cam, K=K, R=cam.R, t=cam.t, centre=cam.centre, P=cam.P)

    return build_demo("camera_explorer", controls, view, update,
                      title="Drag the intrinsics and the pose: P = K [R | t]", extra=[info])


@register(lesson="04", sweep={"noise": [0.0, 5.0], "n_points": [6, 60], "outlier": [-100.0, 60.0, 100.0],
                              "refine": [True, False], "pair": [0, 5], "outlier_v": [-100.0, 40.0, 100.0]})
def resectioning():
    """Estimate P from noisy correspondences (DLT, optionally refined) and compare to the truth.

    Click in the image to move the nearest measured pixel there (a mismatched
    correspondence); without a mouse, the ``outlier`` and ``outlier_v`` sliders shift the
    pixel of correspondence ``pair`` along u and v. Changing N or the noise starts from
    fresh measurements.
    """
    view = FigureView(figsize=(9, 4.2))
    cam, X, uv = scenes.resection_set(12, 0.5)
    frame = np.concatenate([scenes.box_wireframe((0.0, 0.0, 1.0), (2.0, 2.0, 2.0)), scenes.ground_grid(2.0, 1.0)])
    sv = scene3d.SceneView(view.fig, cam, frame, plane_size=1.0, image_title="measured (o) vs reprojected (+)")
    sv.camera_artist.lines.set_alpha(0.4)
    # "est." below-right of its centre, the true camera's "C" above-left: the two sit close together
    est_art = scene3d.CameraArtist(sv.ax3d, cam, size=1.0, color=palette.ORANGE, show_axes=False, label="est.",
                                   label_offset=(0.1, 0.35))
    pts3d = scene3d.draw_points(sv.ax3d, X, color="tab:blue")
    # the moved correspondence(s), ringed in both panels: after the fit every residual grows, so
    # without a mark the mismatch cannot be found
    ring = dict(marker="o", ms=13, mfc="none", mec=palette.RED, mew=2.0, ls="none")
    (moved_img,) = sv.ax_image.plot([], [], **ring)
    (moved_3d,) = sv.ax3d.plot([], [], [], **ring)
    (meas,) = sv.ax_image.plot([], [], "o", mfc="none", color="tab:blue", ms=6)
    (reproj,) = sv.ax_image.plot([], [], "+", color=palette.ORANGE, ms=8, mew=1.5)
    (est_lines,) = sv.ax_image.plot([], [], color=palette.ORANGE, lw=1.0, ls="--")
    info = W.HTML()  # numbers beside the figure: text outside the canvas costs no redraw time
    view.animate(*est_art.artists(), pts3d, meas, reproj, est_lines, moved_img, moved_3d)
    controls = {
        "noise": slider(0.5, 0.0, 5.0, 0.1, "pixel noise sigma (px)"),
        "n_points": int_slider(12, 6, 60, "correspondences N"),
        "outlier": slider(0.0, -100.0, 100.0, 2.0, "shift pair k along u (px)"),
        "outlier_v": slider(0.0, -100.0, 100.0, 2.0, "shift pair k along v (px)"),
        "pair": int_slider(0, 0, 5, "pair k (0-5) to shift"),
        "refine": W.Checkbox(value=False, description="refine (minimise reprojection error)"),
    }
    clicked: dict[int, np.ndarray] = {}  # correspondence index -> clicked pixel
    last_data: dict[str, tuple] = {}

    def update(v, state):
        key = (int(v["n_points"]), float(v["noise"]))
        if last_data.get("key") != key:
            clicked.clear()
            last_data["key"] = key
        cam_true, Xw, uvn = scenes.resection_set(*key)
        uvn[v["pair"]] += float(v["outlier"]), float(v["outlier_v"])
        for i, uv_click in clicked.items():
            uvn[i] = uv_click
        moved = sorted(set(clicked) | ({int(v["pair"])} if v["outlier"] or v["outlier_v"] else set()))
        moved_img.set_data(uvn[moved, 0], uvn[moved, 1])
        moved_3d.set_data_3d(Xw[moved, 0], Xw[moved, 1], Xw[moved, 2])
        P = cm.estimate_projection_matrix(Xw, uvn, refine=bool(v["refine"]))
        K, R, t, C = cm.decompose_projection_matrix(P)
        est = cm.Camera(K, R, t)
        err = cm.reprojection_errors(P, Xw, uvn)
        # A wild fit (N = 6 with an outlier) can have a focal length of a few tens of pixels; its frustum at
        # the usual depth would be metres wide and cover the view, so shorten it to at most 1.2 m across.
        w, h = est.image_size
        est_art.size = min(1.0, 0.6 / max(w / 2 / abs(K[0, 0]), h / 2 / abs(K[1, 1])))
        est_art.update(est)
        pts3d.set_data_3d(Xw[:, 0], Xw[:, 1], Xw[:, 2])
        meas.set_data(uvn[:, 0], uvn[:, 1])
        r = cm.project_points(P, Xw)
        reproj.set_data(r[:, 0], r[:, 1])
        scene3d.update_segments(est_lines, cm.project_segments(P, frame))
        behind = int(np.count_nonzero(~np.isfinite(err)))  # points behind the estimated camera have no image
        rms = float(np.sqrt(np.mean(err ** 2)))
        focal_err = float(abs(K[0, 0] - cam_true.K[0, 0]))
        centre_err = float(np.linalg.norm(C - cam_true.centre))
        n = len(Xw)
        redundancy = 2 * n - 11  # equations minus unknowns: the noise the residuals can show
        # The expected RMS residual of the maximum-likelihood fit (H&Z 5.1.3); the true camera leaves sigma sqrt(2).
        expected = float(v["noise"]) * np.sqrt(2.0 * redundancy / (2 * n))
        warning = ("\n<b>few spare equations: the fit absorbs the noise, so a small RMS\n"
                   "says little about the camera</b>" if redundancy < 10 and v["noise"] > 0 else "")
        rms_text = (f"RMS reprojection {rms:.2f} px" if not behind else
                    f"<b>{behind} of {n} points lie behind the estimated camera:\n"
                    f"no reprojection error; the fit has failed</b>")
        info.value = (f"<pre>{rms_text}\n|fx - fx_true| = {focal_err:.1f} px\n"
                      f"|C - C_true| = {100 * centre_err:.1f} cm\n\n"
                      f"redundancy 2N - 11 = {redundancy}\n"
                      f"RMS expected of the fitted camera:\n  sigma sqrt(2) sqrt((2N - 11) / 2N) = {expected:.2f} px\n"
                      f"(the true camera leaves sigma sqrt(2) = {float(v['noise']) * np.sqrt(2.0):.2f} px)"
                      f"{warning}</pre>")
        state.update(P=P, K=K, R=R, t=t, centre=C, rms=rms, focal_error=focal_err, centre_error=centre_err,
                     points_image=uvn, redundancy=redundancy, expected_rms=expected, behind=behind, moved=moved)

    demo = build_demo("resectioning", controls, view, update,
                      title="Resection: estimate P from N point pairs (DLT); click the image (or use the shift sliders) to move a pixel",
                      extra=[info])

    def on_click(event):
        if event.inaxes is not sv.ax_image or event.xdata is None:
            return
        uvn = demo.state["points_image"]
        i = int(np.argmin(np.linalg.norm(uvn - [event.xdata, event.ydata], axis=1)))
        clicked[i] = np.array([event.xdata, event.ydata])
        update({k: c.value for k, c in demo.controls.items()}, demo.state)
        demo.view.refresh()

    view.fig.canvas.mpl_connect("button_press_event", on_click)
    demo.handlers["button_press_event"] = on_click  # tests call it with an object carrying inaxes, xdata, ydata
    return demo


@register(lesson="04", sweep={"yaw": [-60, 60], "frame": ["OpenGL / Blender", "OpenCV"]})
def opencv_vs_opengl():
    """The same camera with OpenCV axes (x right, y down, z forward) or OpenGL/Blender axes
    (x right, y up, z backward): only the labels of the camera axes change, R_gl = F R."""
    from mpl_toolkits.mplot3d import Axes3D  # noqa: F401  (registers the 3-D projection)

    view = FigureView(figsize=(5.0, 3.4))
    ax = scene3d.axes3d(view.fig, 1, 1, 1, elev=20, azim=-130)
    ax.set_axis_off()
    ax.set_position((0.0, -0.12, 1.0, 1.2))  # 3-D axes keep a square box: let it fill the wide canvas
    world = scene3d.draw_world_axes(ax, 0.6)
    house_segments = scenes.house_wireframe((0.0, 0.0, 0.0), 0.6)
    house = scene3d.draw_segments(ax, house_segments, color=palette.GREY)
    cam0 = cm.Camera.look_at([2.0, -2.0, 1.0], [0.0, 0.0, 0.4])
    art = scene3d.CameraArtist(ax, cam0, size=0.45, show_axes=False)  # shorter than the axes, so labels clear it
    lines, texts = [], []
    for c in palette.AXIS_COLOURS:
        (ln,) = ax.plot([], [], [], color=c, lw=2.5)
        lines.append(ln)
        texts.append(ax.text(0, 0, 0, "", color=c, fontsize=9, fontweight="bold"))
    title = W.HTML()  # the formula beside the figure: long canvas text costs ~7 ms per redraw
    # The limits follow the orbiting camera (house, axes and labels fill the canvas at every angle), so
    # everything in the 3-D axes moves with the projection and is animated.
    view.animate(*world, house, *art.artists(), *lines, *texts)
    controls = {
        "yaw": slider(0, -90, 90, 2, "orbit (deg)"),
        "frame": W.ToggleButtons(options=["OpenCV", "OpenGL / Blender"], value="OpenCV", description="frame"),
    }

    def update(v, state):
        eye = cm.rotation_z(np.deg2rad(v["yaw"])) @ np.array([2.0, -2.0, 1.0])
        cam = cm.Camera.look_at(eye, [0.0, 0.0, 0.4])
        art.update(cam)
        gl = v["frame"] != "OpenCV"
        R_axes = cm.opengl_from_opencv(cam.R, cam.t)[0] if gl else cam.R
        names = ("x right", "y up", "z backward") if gl else ("x right", "y down", "z forward")
        C = cam.centre
        # The limits fit both frames' label tips, so toggling the frame changes only the labels
        label_tips = C + 1.3 * np.vstack([cam.R, -cam.R[1:]])
        scene3d.set_equal_aspect(ax, [house_segments, np.zeros(3), label_tips, art.extent_points(cam)], zoom=0.95,
                                 tight=True)
        scene3d.refresh_projection(ax)
        for i, (ln, tx) in enumerate(zip(lines, texts)):
            e = C + 0.9 * R_axes[i]  # row i of R = camera axis i in world coordinates
            ln.set_data_3d([C[0], e[0]], [C[1], e[1]], [C[2], e[2]])
            tx.set_position_3d(C + 1.05 * R_axes[i])
            tx.set_text(names[i])
            scene3d.align_away(ax, tx, C, e)
        title.value = ("<pre>OpenGL/Blender: R_gl = diag(1,-1,-1) R, t_gl = diag(1,-1,-1) t\n"
                       "camera looks along its -z axis</pre>" if gl else
                       "<pre>OpenCV / H&amp;Z: X_cam = R X + t\ncamera looks along its +z axis</pre>")
        state.update(R_axes=R_axes, frame=v["frame"], camera=cam)

    return build_demo("opencv_vs_opengl", controls, view, update, title="Same camera, two axis conventions",
                      extra=[title])
