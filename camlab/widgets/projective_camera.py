"""Demos for lesson 04, the projective camera P = K [R | t].

In a lesson::

    %matplotlib widget
    from camlab.widgets import projective_camera as demos
    demos.camera_explorer()
"""

from __future__ import annotations

from types import SimpleNamespace

import ipywidgets as W
import numpy as np

from .. import camera as cm
from .. import fixtures, scenes
from ..plotting import palette, scene3d
from ._base import FigureView, build_demo, register, slider
from ._resection import k_readout as k_readout  # re-exported: it lived here
from ._resection import (
    place_camera_labels,
    resection_readout,
    residual_bars,
    show_residual_bars,
)
from .browser import BrowserView
from .browser.camera_scenes import camera_explorer_scene, opencv_vs_opengl_scene
from .controls import int_slider

TARGET = np.array([0.0, 0.0, 0.7])
# The explorer's 3-D viewer orbits with the camera, this many degrees round from it (anticlockwise seen from
# above: behind the camera and to its right), so the frustum keeps its place on screen. From this side all three world axes show (from -35 deg, the
# old side, world Y pointed into the screen) and the camera's x, y and z each stand clear of the frustum; straight
# behind the camera the viewer would look down its axis and pile everything up.
VIEWER_OFFSET = 30.0
# ... and looks down from 45 deg: from level with the camera (18 deg, the old height) its x (right) and z (forward)
# both ran to the right on screen, one over the other, with both labels on the image plane's picture; from
# above, x runs down-right, y down and z up-right, 40 to 140 deg apart, and the labels clear the picture.
VIEWER_ELEV = 45.0
# The viewer turns with the pan by this fraction: a fixed viewer saw the frustum end-on at one end of the pan,
# one that followed fully would hide the turn; at 0.3 both ends show the frustum turned from the default.
PAN_FOLLOW = 0.3
# The resectioning viewer looks at the box's corner between its two faces of points (x = +1 and y = -1), so both
# faces open up; the true camera (azimuth -55 deg) stands to the viewer's right, its frustum pointing at the box.
RESECTION_AZIM, RESECTION_ELEV = -20.0, 24.0
# The true camera's view of the scene is drawn thin and dark grey *over* the estimate's wider dashed orange one:
# a wide grey line under orange dashes read as one tan-brown line where the two coincide (brown means a
# construction in lesson 04); a thin dark line on an orange band reads as two lines, one on the other.
TRUE_VIEW_GREY = "0.3"
TRUE_VIEW_LW, EST_VIEW_LW = 0.9, 2.2
MOVED_FROM_GREY = "0.55"  # the moved pixel's first spot and its dotted move
FAR_M = 6.0  # an estimated camera farther than this from the true one is shown by an arrow, not fitted into view
RESECTION_FRUSTUM_M = 1.8  # the cameras' image planes, drawn 1.8 m in front: large enough that the dashed estimate reads over the truth
EYE_GL = np.array(
    [2.6, -2.6, 1.0]
)  # opencv_vs_opengl's camera, far enough from the house that "z forward" clears it


# opencv_vs_opengl's viewer turns half as fast as the camera orbits. The camera's horizontal x axis points
# at azimuth orbit + 45 deg, so it stays 30 to 120 deg from the line of sight (orbit in [-90, 90]) and never
# folds onto y down; a fixed viewer would see x point at it, drawn straight down over y, at some orbit angle.
# From this side "z forward" points away from the house, up the screen.
VIEW_GL_ELEV = 30.0
VIEW_GL_AZIM0, VIEW_GL_FOLLOW = -30.0, 0.5
GL_TARGET = np.array([0.0, 0.0, 0.4])  # where opencv_vs_opengl's camera looks
# its axes 0.9 m long, labelled 1.05 m out; the view keeps both frames' labels (1.3 m out) in sight
GL_AXIS_M, GL_LABEL_M, GL_TIPS_M = 0.9, 1.05, 1.3
GL_FILL = 0.8  # the share of the 3-D panel the fitted view spans
GL_NAMES = {
    "opencv": ("x right", "y down", "z forward"),
    "opengl": ("x right", "y up", "z backward"),
}


def _view_gl_azim(orbit: float) -> float:
    return VIEW_GL_AZIM0 + VIEW_GL_FOLLOW * orbit


def _fmt(v: np.ndarray) -> str:
    return "(" + ", ".join(f"{x + 0.0:+.2f}" for x in np.round(v, 2)) + ")"  # + 0.0: no "-0.00"


def _matrix(name: str, A: np.ndarray, digits: int) -> str:
    """A small matrix as aligned text rows, for a readout."""
    rows = [" ".join(f"{x + 0.0:9.{digits}f}" for x in np.round(row, digits)) for row in A]
    pad = " " * (len(name) + 3)
    return "\n".join((f"{name} = [" if i == 0 else pad + "[") + r + "]" for i, r in enumerate(rows))


def explorer_camera(
    fx=800.0,
    fy=800.0,
    cx=319.5,
    cy=239.5,
    skew=0.0,
    azimuth=-60.0,
    elevation=25.0,
    distance=5.0,
    pan=0.0,
    roll=0.0,
    slide=0.0,
) -> cm.Camera:
    """The camera explorer's camera: K from the intrinsics, then a pose in three steps.

    1. ``look_at`` from the orbit position (``azimuth``, ``elevation`` in degrees, ``distance`` in
       metres about the house's centre): the camera's z axis points from the eye to the target,
       x = z x up (up = world Z), y = z x x (lesson 04, section 3);
    2. turn in place (the centre C stays), both right-handed: ``pan`` degrees about the world's vertical
       Z through C, a tripod's pan (positive turns the camera to its left, anticlockwise seen from above,
       and keeps the horizon level), then ``roll`` degrees about the camera's own z axis (positive turns
       its x towards its y: clockwise seen from behind, so the picture turns anticlockwise).
       The camera's pose in the world, world_from_cam = R^T, turns as R^T <- R_Z(pan) R^T R_z(roll),
       so R <- R_z(-roll) R R_Z(-pan);
    3. ``slide`` metres along the camera's own x axis with R fixed: C <- C + slide r1 (r1 = R's first row).
    Finally t = -R C.

    Parameters
    ----------
    fx, fy, cx, cy, skew : float
        The intrinsics, pixels.
    azimuth, elevation : float
        The orbit position about the house's centre, degrees.
    distance : float
        The orbit's radius, metres.
    pan, roll : float
        The turns in place, degrees.
    slide : float
        The slide along the camera's x axis, metres.

    Returns
    -------
    camlab.camera.Camera
        The camera (no distortion).
    """
    K = cm.intrinsic_matrix(fx, fy, cx, cy, skew)
    base = cm.Camera.look_at(
        cm.orbit_eye(*np.radians([azimuth, elevation]), distance, TARGET), TARGET, K=K
    )
    R = (
        cm.rotation_z(-np.radians(roll)) @ base.R @ cm.rotation_z(-np.radians(pan))
    )  # pan about world Z, roll about z
    C = base.centre + slide * R[0]
    return cm.Camera(K, R, -R @ C)


# The lowest elevation keeps the eye above the ground at every distance: 0.7 m - 9 m sin 4 deg = 0.07 m.
ELEVATION_MIN = -4.0
# The slide is symmetric: at +-1 m the house stays whole in the image (near its right or left edge), so the
# parallax shows at both ends.
SLIDE_MIN, SLIDE_MAX = -1.0, 1.0
WORLD_AXES_M = 1.25  # the world axes reach out of the house (1.0 x 1.4 m, 1.55 m high), so their labels clear it


def explorer_plane_size(distance: float, K=None) -> float:
    """The explorer's image-plane depth: 0.4 of the distance, or less for a wide or shifted camera.

    0.4 of the distance, so the plane always stands between the camera and the house and the
    small picture on it keeps its size on screen as the camera backs off.

    With ``K``, the plane is never larger than the default camera's (f = 800 px, principal point at the centre):
    a corner of the image lies r = |K^-1 (u, v, 1)|'s (x, y) from the axis per metre of depth (0.5 by default),
    and a short focal length or a shifted principal point raises r, so the depth shrinks by 0.5 / r: at
    f = 200 px the plane would otherwise be 6.4 m wide and cover the house on screen.

    Parameters
    ----------
    distance : float
        The camera's orbit distance, metres.
    K : (3, 3) array_like, optional
        The camera's intrinsics (a 640 x 480 image).

    Returns
    -------
    float
        The depth of the drawn image plane, metres.
    """
    depth = 0.4 * float(distance)
    if K is None:
        return depth
    corners = np.array(
        [[-0.5, -0.5, 1.0], [639.5, -0.5, 1.0], [-0.5, 479.5, 1.0], [639.5, 479.5, 1.0]]
    )
    reach = np.linalg.norm(np.linalg.solve(np.asarray(K, dtype=float), corners.T)[:2], axis=0).max()
    return depth * min(1.0, 0.5 / reach)


EXPLORER_SWEEP = {
    "fx": [200, 1600],
    "fy": [200, 1600],
    "cx": [-0.5, 639.5],
    "cy": [-0.5, 479.5],
    "skew": [-300, 300],
    "azimuth": [-180, 100, 180],
    "elevation": [ELEVATION_MIN, 80],
    "distance": [2.5, 9.0],
    "pan": [-30, 30],
    "roll": [-90, 90],
    "slide": [SLIDE_MIN, SLIDE_MAX],
}  # every control, each at its ends (and the azimuth where the view turns most)


@register(lesson="04", sweep=EXPLORER_SWEEP)
def camera_explorer():
    """Intrinsics and pose sliders beside a live 3-D frustum view and the camera's image.

    The pose moves three ways: orbit (the camera looks at the house from anywhere on a sphere),
    turn in place (pan, roll: R changes, C stays) and slide (C moves along the camera's x axis,
    R stays). The text beside the figure shows K, R, t, the centre C = -R^T t and P = K [R | t].

    Returns
    -------
    Demo
        The demo: controls ``fx``, ``fy``, ``cx``, ``cy``, ``skew`` (pixels), ``azimuth``,
        ``elevation`` (degrees), ``distance`` (m), ``pan``, ``roll`` (degrees) and ``slide`` (m)
        (:func:`explorer_camera`), the figure (the 3-D view and the camera's image, with the
        principal point), the matrices beside it and ``state`` (``camera``, ``K``, ``R``,
        ``t``, ``centre``, ``P``).
    """
    view = BrowserView(tuple(EXPLORER_SWEEP), figsize=(9, 4.2))
    scene = fixtures.house_scene()
    cam0 = explorer_camera()
    # Seen from behind the camera's shoulder, with only the house on the image plane: the small picture
    # stays readable (the whole grid, seen edge-on, was a tangle).
    sv = scene3d.SceneView(
        view.fig,
        cam0,
        scene,
        plane_size=explorer_plane_size(5.0),
        thumbnail=scenes.house_wireframe(),
        azim=-60 + VIEWER_OFFSET,  # update() follows the azimuth and part of the pan
        elev=VIEWER_ELEV,
        camera_axis_length=0.8,
        width_ratios=(1.3, 1.0),
        world_axes=WORLD_AXES_M,
    )
    # "C" hangs just above-left of the centre dot and a little behind it, so that it never sits inside
    # the frustum, whatever the pan or distance
    sv.camera_artist.label.set(ha="right", va="bottom", path_effects=palette.halo())  # on the plane
    sv.camera_artist.label_offset = (-0.02, -0.04, -0.06)
    info = W.HTML()  # numbers beside the figure: text outside the canvas costs no redraw time
    # not clipped: at cx or cy = -0.5 the principal point sits on the image's edge, and the whole + shows it
    (pp,) = sv.ax_image.plot(
        [], [], "+", color=palette.PURPLE, ms=10, mew=2, clip_on=False, zorder=3
    )
    view.animate(*sv.artists(), pp)
    controls = {
        "fx": slider(800, 200, 1600, 10, "fx (px)", readout_format=".0f"),
        "fy": slider(800, 200, 1600, 10, "fy (px)", readout_format=".0f"),
        # The image centre is ((W - 1) / 2, (H - 1) / 2) with pixel centres at integers (docs/conventions.md).
        "cx": slider(319.5, -0.5, 639.5, 5, "cx (px)", readout_format=".1f"),
        "cy": slider(239.5, -0.5, 479.5, 5, "cy (px)", readout_format=".1f"),
        "skew": slider(0, -300, 300, 10, "skew s (px)", readout_format=".0f"),
        "azimuth": slider(-60, -180, 180, 2, "orbit: azimuth (deg)", readout_format=".0f"),
        "elevation": slider(
            25, ELEVATION_MIN, 80, 1, "orbit: elevation (deg)", readout_format=".0f"
        ),
        "distance": slider(5.0, 2.5, 9.0, 0.1, "orbit: distance (m)", readout_format=".1f"),
        "pan": slider(0, -30, 30, 1, "turn in place: pan (deg, + left)", readout_format=".0f"),
        "roll": slider(0, -90, 90, 1, "turn in place: roll (deg)", readout_format=".0f"),
        "slide": slider(
            0.0, SLIDE_MIN, SLIDE_MAX, 0.1, "slide along camera x (m)", readout_format=".1f"
        ),
    }

    def update(v, state):
        cam = explorer_camera(**v)
        sv.camera_artist.size = explorer_plane_size(v["distance"], cam.K)
        # the camera's axes a third of the way to the image plane: their labels stay near the centre,
        # clear of the small picture on the plane
        sv.camera_artist.axis_length = min(0.8, max(0.35, 0.3 * sv.camera_artist.size))
        # sv.update refreshes the projection
        azim = v["azimuth"] + VIEWER_OFFSET + PAN_FOLLOW * v["pan"]
        sv.ax3d.view_init(elev=VIEWER_ELEV, azim=azim)
        sv.update(cam)
        pp.set_data([cam.principal_point[0]], [cam.principal_point[1]])
        info.value = (
            "<pre>" + _matrix("K", cam.K, 1) + "\n" + _matrix("R", cam.R, 3) + "\n"
            f"t = {_fmt(cam.t)} m  (world origin in camera frame)\n"
            f"C = -R^T t = {_fmt(cam.centre)} m  (camera in world)\n"
            + _matrix("P", cam.P, 3)
            + "\n(K33 = 1, so row 3 of P = K [R | t] is (r3, t_z):\n the principal axis and the world origin's depth)</pre>"
        )
        state.update(camera=cam, K=cam.K, R=cam.R, t=cam.t, centre=cam.centre, P=cam.P)

    demo = build_demo(
        "camera_explorer",
        controls,
        view,
        update,
        title="Drag the intrinsics and the pose: P = K [R | t]",
        extra=[info],
    )
    # the browser draws the moves (projective_camera.js); the kernel keeps the matrices and state
    world = dict(
        target=TARGET,
        viewer_offset=VIEWER_OFFSET,
        pan_follow=PAN_FOLLOW,
        elev=VIEWER_ELEV,
        fill=0.85,
    )
    view.publish(demo, camera_explorer_scene(view, sv, pp, world))
    return demo


def _show_estimate(art, trial, K, R, t, C, ringed, first_pixels):
    """Draw the points, their pixels and reprojections, and the estimated camera.

    Pairs ``ringed`` are ringed. The estimated camera K [R | t] (centre C) or, when it is more than
    FAR_M from the truth, a pointer towards it; a ringed pixel that moved also shows where it was
    first (``first_pixels``). Returns the centre's error (m) and whether it is that far.
    """
    cam_true, Xw, uvn, P = trial.camera, trial.points_world, trial.points_image, trial.P
    est = cm.Camera(K, R, t)
    est_art, sv, pointer, pointer_text = art.est_art, art.sv, art.pointer, art.pointer_text
    art.moved_img.set_data(uvn[ringed, 0], uvn[ringed, 1])
    moved = [i for i in ringed if np.linalg.norm(uvn[i] - first_pixels[i]) > 1e-9]
    first = np.asarray(first_pixels)[moved]
    art.first_spot.set_data(first[:, 0], first[:, 1])
    art.move_lines.set_data(*_segments_xy(first, uvn[moved]))
    art.moved_3d.set_data_3d(Xw[ringed, 0], Xw[ringed, 1], Xw[ringed, 2])
    # A wild fit (N = 6 with an outlier) can have a focal length of a few tens of pixels; its frustum at
    # the usual depth would be metres wide and cover the view, so shorten it to at most 1.5 m across (the true camera's is 1.44 m).
    w, h = est.image_size
    est_art.size = min(RESECTION_FRUSTUM_M, 0.75 / max(w / 2 / abs(K[0, 0]), h / 2 / abs(K[1, 1])))
    est_art.update(est)
    centre_err = float(np.linalg.norm(C - cam_true.centre))
    far = centre_err > FAR_M
    d = (C - cam_true.centre) / max(centre_err, 1e-12)
    tip = (
        cam_true.centre + 1.5 * d
    )  # far: a 1.5 m pointer from the true camera towards the estimate
    # The view stays put while the estimate stays in the default view's room (a box 0.25 m round the scene and
    # the true camera), so the box and the true camera keep their places on screen; it widens only for an
    # estimate outside that room.
    room = art.room
    shown = np.vstack([tip, tip + 0.3 * d]) if far else est_art.extent_points(est)
    inside = np.all((shown >= room.min(axis=0)) & (shown <= room.max(axis=0)))
    sv.fit(extra=room if inside else np.vstack([room, shown]))
    for artist in est_art.artists():
        artist.set_visible(not far)
    place_camera_labels(sv.ax3d, sv.camera_artist, est_art)
    if far:
        pointer.set_data_3d(*np.c_[cam_true.centre, tip])
        pointer_text.set_position_3d(tip)  # centred over the pointer's tip, inside the view
        pointer_text.set_text(f"est. camera:\n{centre_err:.1f} m this way")
    else:
        pointer.set_data_3d([], [], [])
        pointer_text.set_text("")
    art.pts3d.set_data_3d(Xw[:, 0], Xw[:, 1], Xw[:, 2])
    art.meas.set_data(uvn[:, 0], uvn[:, 1])
    r = cm.project_points(P, Xw)
    art.reproj.set_data(r[:, 0], r[:, 1])
    art.residuals.set_data(*_segments_xy(uvn, r))
    scene3d.update_segments(art.est_lines, cm.project_segments(P, art.frame))
    show_residual_bars(art.bars, trial.errors, ringed)
    return centre_err, far


def held_out_rms(P) -> float:
    """The RMS error (px) of the camera matrix ``P`` on 30 fresh points of the resectioning box, not fitted.

    The test a practitioner can run on a resection: points it did not fit (here on the same two faces of the
    box, seed 1), measured without noise, against the pixels ``P`` gives them. NaN if one lies behind ``P``.

    Parameters
    ----------
    P : (3, 4) array_like
        An estimated camera matrix.

    Returns
    -------
    float
        The RMS distance, pixels.
    """
    fresh = fixtures.resection_set(30, 0.0, seed=1)
    errors = cm.reprojection_errors(P, fresh.points_world, fresh.points_image)
    return float(np.sqrt(np.mean(errors**2)))


def _segments_xy(start, end):
    """x and y of the segments start[i] -> end[i] as one polyline broken by NaNs (one artist, cheap to redraw)."""
    start, end = (
        np.asarray(start, dtype=float).reshape(-1, 2),
        np.asarray(end, dtype=float).reshape(-1, 2),
    )
    xy = np.stack([start, end, np.full_like(start, np.nan)], axis=1).reshape(-1, 2)
    return xy[:, 0], xy[:, 1]


def _resectioning_key(view):
    """What the line styles of :func:`resectioning` mean, below the axes.

    Drawn once, where it covers no data.
    """
    from matplotlib.lines import Line2D

    # What the line styles mean, on the figure: true camera solid (purple in 3-D, its view black-grey in
    # the image), the estimate dashed orange; drawn once, outside the axes, so it covers no data.
    keys = [
        Line2D([], [], color=palette.PURPLE, lw=1.2),
        Line2D([], [], color=palette.ORANGE, lw=1.2, ls=(0, (4, 2))),
        Line2D([], [], color=TRUE_VIEW_GREY, lw=TRUE_VIEW_LW),
        Line2D([], [], color=palette.ORANGE, lw=EST_VIEW_LW, ls=(0, (3, 2))),
        Line2D([], [], marker="o", mfc="none", color="k", ls="none"),
        Line2D([], [], marker="+", color=palette.ORANGE, mew=1.5, ls="none"),
        Line2D([], [], color=palette.ORANGE, lw=1.2, marker="|", ms=4),
        Line2D([], [], marker="o", ms=10, mfc="none", mec="k", mew=2.0, ls="none"),
        Line2D([], [], marker="o", ms=5, color=MOVED_FROM_GREY, ls=":", lw=1.2),
        Line2D([], [], color="k", lw=4.0, solid_capstyle="butt"),
    ]
    view.fig.legend(
        keys,
        [
            "true camera",
            "estimated camera",
            "scene seen by the true camera",
            "seen by the estimate",
            "measured pixel",
            "reprojected by the estimate",
            "residual (measured o to its +)",
            "pair k, or a clicked pixel, where it is now",
            "where it was before the move",
            "residual bar of pair k or a moved pixel",
        ],
        loc="outside lower center",
        ncols=4,
        fontsize=8,
        frameon=False,
    )


def _resectioning_cameras(view, cam, frame):
    """The 3-D and image panels of :func:`resectioning` with the true and the estimated camera.

    Returns
    -------
    sv : SceneView
        The true camera's scene view (3-D axes and image panel).
    est_art : CameraArtist
        The estimated camera, dashed orange.
    ax_bars : Axes
        The third panel, for the residual bars.
    """
    # No world or camera axes here: red, green and blue would mean axes in one place and data in another.
    # Three panels: the 3-D scene, the image, and each pair's residual as a bar (at 0.55 screen px per image
    # px a 17.5 px residual is 10 screen px, no longer than its + marker: the bars make the lengths comparable).
    gs = view.fig.add_gridspec(1, 3, width_ratios=(1.0, 1.05, 0.42))
    ax3 = scene3d.axes3d(view.fig, gs[0, 0], elev=RESECTION_ELEV, azim=RESECTION_AZIM)
    ax_image = view.fig.add_subplot(gs[0, 1])
    ax_bars = view.fig.add_subplot(gs[0, 2])
    sv = scene3d.SceneView(
        view.fig,
        cam,
        frame,
        axes=(ax3, ax_image),
        plane_size=RESECTION_FRUSTUM_M,
        image_title="measured (o) vs reprojected (+)",
        world_axes=0.0,
        camera_axes=False,
        azim=RESECTION_AZIM,
        elev=RESECTION_ELEV,
    )
    # The labels hang off each centre on screen, "true" above-left and "est." below-left (the frustums
    # point right, towards the box), so they clear each other and their own lines at any zoom.
    sv.camera_artist.label.set(text="true ", ha="right", va="bottom")
    sv.camera_artist.label_offset = (0.0, 0.0)
    sv.camera_artist.lines.set_alpha(0.4)
    est_art = scene3d.CameraArtist(
        sv.ax3d,
        cam,
        size=RESECTION_FRUSTUM_M,
        color=palette.ORANGE,
        show_axes=False,
        label="est. ",
        label_offset=(0.0, 0.0),
    )
    est_art.label.set(ha="right", va="top")
    # The estimate is drawn dashed and unfilled, as its view is in the image: near the truth it lies over the
    # true camera, which must still show through it.
    est_art.frustum.set_linestyle((0, (4, 2)))
    # a transparent colour, not "none": matplotlib 3.9 projects an empty colour array and fails
    est_art.plane.set_facecolor((1.0, 1.0, 1.0, 0.0))
    return sv, est_art, ax_bars


def _resectioning_marks(sv, X):
    """The points and the marks of :func:`resectioning`, in the order a full draw stacks them.

    Returns
    -------
    SimpleNamespace
        ``faces`` and ``pts3d`` (the box's two faces of points), ``moved_3d``, ``pointer`` and
        ``pointer_text`` in 3-D; ``moved_img``, ``meas``, ``reproj``, ``residuals``,
        ``first_spot``, ``move_lines`` and ``est_lines`` in the image.
    """
    # the two faces that hold the points, lightly shaded so the points read as lying on them
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    faces = Poly3DCollection(
        [
            [[1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [1.0, 1.0, 2.0], [1.0, -1.0, 2.0]],
            [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, -1.0, 2.0], [-1.0, -1.0, 2.0]],
        ],
        facecolor=(0.0, 0.0, 0.0, 0.07),
        edgecolor="none",
    )
    sv.ax3d.add_collection3d(faces)
    pts3d = scene3d.draw_points(sv.ax3d, X, color="k", ms=3)
    # the moved correspondence(s), ringed in both panels: after the fit every residual grows, so
    # without a mark the mismatch is hard to find
    ring = dict(marker="o", ms=14, mfc="none", mec="k", mew=2.0, ls="none")
    (moved_3d,) = sv.ax3d.plot([], [], [], **ring)
    (pointer,) = sv.ax3d.plot(
        [], [], [], color=palette.ORANGE, lw=2.0, ls=(0, (4, 2))
    )  # towards a far estimate
    pointer_text = sv.ax3d.text(
        0, 0, 0, "", color=palette.ORANGE, fontsize=9, fontweight="bold", ha="center", va="bottom"
    )
    (moved_img,) = sv.ax_image.plot([], [], **ring)
    (meas,) = sv.ax_image.plot([], [], "o", mfc="none", color="k", ms=6)
    (reproj,) = sv.ax_image.plot([], [], "+", color=palette.ORANGE, ms=8, mew=1.5)
    (residuals,) = sv.ax_image.plot([], [], color=palette.ORANGE, lw=1.2)  # each o to its +
    # where a moved pixel was measured first, and its move (dotted) to where it is now
    (first_spot,) = sv.ax_image.plot([], [], "o", ms=5, color=MOVED_FROM_GREY, ls="none")
    (move_lines,) = sv.ax_image.plot([], [], color=MOVED_FROM_GREY, lw=1.2, ls=":")
    (est_lines,) = sv.ax_image.plot(
        [], [], color=palette.ORANGE, lw=EST_VIEW_LW, ls=(0, (3, 2)), zorder=1.9
    )
    sv.image_lines.set(
        color=TRUE_VIEW_GREY, linewidth=TRUE_VIEW_LW, zorder=2.0
    )  # over the estimate's band
    return SimpleNamespace(
        faces=faces,
        pts3d=pts3d,
        moved_3d=moved_3d,
        pointer=pointer,
        pointer_text=pointer_text,
        moved_img=moved_img,
        meas=meas,
        reproj=reproj,
        residuals=residuals,
        first_spot=first_spot,
        move_lines=move_lines,
        est_lines=est_lines,
    )


def _resectioning_figure(view):
    """The figure of :func:`resectioning`.

    The 3-D scene with the true and the estimated camera, the image panel with the measured and
    reprojected pixels, the key below; returns its artists by name.
    """
    cam, X, uv = fixtures.resection_set(12, 0.5)
    box = scenes.box_wireframe((0.0, 0.0, 1.0), (2.0, 2.0, 2.0))
    # The box's bottom edges lie on grid lines: drawn twice, two dash patterns interleave into a solid line.
    frame = np.concatenate([box[np.any(box[:, :, 2] > 0, axis=1)], scenes.ground_grid(2.0, 1.0)])
    sv, est_art, ax_bars = _resectioning_cameras(view, cam, frame)
    m = _resectioning_marks(sv, X)
    # The image's frame over the lines that run off its edges, live as in a full draw (a live frame drew the
    # box's lines over a static top spine: 113 pixels differed from the first draw)
    frame_spines = list(sv.ax_image.spines.values())
    bars = residual_bars(ax_bars)
    _resectioning_key(view)
    info = W.HTML()  # numbers beside the figure: text outside the canvas costs no redraw time
    # Registered in the order they were created (the true camera's view first), so a live frame stacks
    # them as a full draw does; the 3-D limits follow the estimate, so everything in the 3-D axes moves.
    view.animate(
        *sv.artists(),
        *est_art.artists(),
        m.faces,
        m.pts3d,
        m.moved_3d,
        m.pointer,
        m.pointer_text,
        m.first_spot,
        m.move_lines,
        m.moved_img,
        m.meas,
        m.residuals,
        m.reproj,
        m.est_lines,
        *frame_spines,
        *bars.artists,
    )
    pts = np.vstack([frame.reshape(-1, 3), sv.camera_artist.extent_points(cam)])
    lo, hi = pts.min(axis=0) - 0.25, pts.max(axis=0) + 0.25
    room = np.array(
        [[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    )
    return SimpleNamespace(
        room=room, bars=bars, frame=frame, sv=sv, est_art=est_art, info=info, **vars(m)
    )


def _resectioning_controls():
    """The controls of :func:`resectioning`: the noise, N, and which pair to shift how far."""
    controls = {
        "noise": slider(0.5, 0.0, 5.0, 0.1, "pixel noise sigma (px)"),
        "n_points": int_slider(12, 6, 60, "correspondences N"),
        "outlier": slider(
            0.0, -100.0, 100.0, 2.0, "shift pair k along u (px)", readout_format=".0f"
        ),
        "outlier_v": slider(
            0.0, -100.0, 100.0, 2.0, "shift pair k along v (px)", readout_format=".0f"
        ),
        "pair": int_slider(0, 0, 5, "pair k (0-5) to shift"),
        "refine": W.Checkbox(value=False, description="refine (minimise reprojection error)"),
    }
    return controls


@register(
    lesson="04",
    sweep={
        "noise": [0.0, 5.0],
        "n_points": [6, 60],
        "outlier": [-100.0, 60.0, 100.0],
        "refine": [True, False],
        "pair": [0, 5],
        "outlier_v": [-100.0, 40.0, 100.0],
    },
)
def resectioning():
    """Estimate P from noisy correspondences (DLT, optionally refined) and compare to the truth.

    Click in the image to move the nearest measured pixel there (a mismatched
    correspondence); without a mouse, the ``outlier`` and ``outlier_v`` sliders shift the
    pixel of correspondence ``pair`` along u and v. Changing N or the noise starts from
    fresh measurements. The 3-D view fits both cameras; an estimate more than FAR_M metres
    from the truth is shown by an arrow towards it, labelled with its distance.

    Returns
    -------
    Demo
        The demo: controls ``noise`` (pixel noise sigma, px), ``n_points`` (N), ``outlier``
        and ``outlier_v`` (the shift of pair k along u and v, px), ``pair`` (k) and
        ``refine``; the figure (the 3-D view of the true and estimated cameras and the
        image); the readout; ``handlers["button_press_event"]`` (the click); and ``state``
        (``P``, ``K``, ``R``, ``t``, ``centre``, ``rms``, ``focal_error``, ``centre_error``,
        ``points_image``, ``redundancy``, ``expected_rms``, ``behind``, ``moved``,
        ``errors``, ``far``, ``held_out_rms``: the RMS error on 30 fresh points of the box, not fitted,
        against their true pixels; NaN if one is behind the estimate).
    """
    view = FigureView(figsize=(10.4, 4.6))  # 936 px: the residual panel beside the image
    art = _resectioning_figure(view)
    controls = _resectioning_controls()
    clicked: dict[int, np.ndarray] = {}  # correspondence index -> clicked pixel
    last_data: dict[str, tuple] = {}

    def update(v, state):
        key = (int(v["n_points"]), float(v["noise"]))
        if last_data.get("key") != key:
            clicked.clear()
            last_data["key"] = key
        trial = fixtures.resection_trial(
            *key,
            pair=int(v["pair"]),
            shift=(float(v["outlier"]), float(v["outlier_v"])),
            refine=bool(v["refine"]),
            moved=clicked,
        )
        cam_true, Xw, uvn, P = trial.camera, trial.points_world, trial.points_image, trial.P
        moved = sorted(
            set(clicked) | ({int(v["pair"])} if v["outlier"] or v["outlier_v"] else set())
        )
        ringed = sorted(
            set(moved) | {int(v["pair"])}
        )  # pair k is ringed before it moves, so you see which it is
        K, R, t, C = cm.decompose_projection_matrix(P)
        err = trial.errors
        first_pixels = fixtures.resection_set(*key).points_image  # before any move
        centre_err, far = _show_estimate(art, trial, K, R, t, C, ringed, first_pixels)
        held_out = held_out_rms(P)
        behind, rms, focal_err, redundancy, expected = resection_readout(
            err, K, cam_true, Xw, v, moved, art.info, centre_err, held_out
        )
        state.update(
            P=P,
            K=K,
            R=R,
            t=t,
            centre=C,
            rms=rms,
            focal_error=focal_err,
            centre_error=centre_err,
            points_image=uvn,
            redundancy=redundancy,
            expected_rms=expected,
            behind=behind,
            moved=moved,
            errors=err,
            far=far,
            held_out_rms=held_out,
        )

    demo = build_demo(
        "resectioning",
        controls,
        view,
        update,
        title="Resection: estimate P from N point pairs (DLT); click the image (or use the shift sliders) to move a pixel",
        extra=[art.info],
    )
    _connect_resectioning_click(demo, art.sv.ax_image, clicked, update)
    return demo


def _connect_resectioning_click(demo, ax_image, clicked, update):
    """Connect :func:`resectioning`'s click: move the nearest measured pixel to where you clicked.

    Parameters
    ----------
    demo : Demo
        The demo; its handler is stored as ``demo.handlers["button_press_event"]`` (tests call
        it with an object carrying ``inaxes``, ``xdata``, ``ydata``).
    ax_image : Axes
        The image panel; clicks elsewhere are ignored.
    clicked : dict
        {correspondence index: clicked pixel}, shared with the demo's ``update``.
    update : callable
        The demo's ``update(values, state)``, run after each click.
    """

    def on_click(event):
        if event.inaxes is not ax_image or event.xdata is None:
            return
        uvn = demo.state["points_image"]
        i = int(np.argmin(np.linalg.norm(uvn - [event.xdata, event.ydata], axis=1)))
        clicked[i] = np.array([event.xdata, event.ydata])
        update({k: c.value for k, c in demo.controls.items()}, demo.state)
        demo.view.refresh()

    demo.view.fig.canvas.mpl_connect("button_press_event", on_click)
    demo.handlers["button_press_event"] = on_click


@register(lesson="04", sweep={"orbit": [-90, -60, 60, 90], "frame": ["OpenGL / Blender", "OpenCV"]})
def opencv_vs_opengl():
    """The same camera with OpenCV axes or OpenGL/Blender axes: its y and z axes flip direction and are relabelled.

    OpenCV: x right, y down, z forward; OpenGL/Blender: x right, y up, z backward. The camera
    stays put, its y and z axes flip (R_gl = F R, F = diag(1, -1, -1)) and are relabelled.

    Returns
    -------
    Demo
        The demo: controls ``orbit`` (degrees about the world's vertical) and ``frame``
        (``"OpenCV"`` or ``"OpenGL / Blender"``), the figure (the camera and its three labelled
        axes in 3-D), the formula and the matrices beside it (R, t and C in OpenCV; R_gl, t_gl and
        Blender's ``matrix_world`` in OpenGL) and ``state`` (``R_axes``, the axes drawn as rows;
        ``frame``; ``camera``; ``matrix_world``).
    """
    # 600 px: the axes and their labels readable beside the matrices
    view = BrowserView(("orbit", "frame"), figsize=(6.0, 4.0), choices=("frame",))
    ax, house_segments, art, lines, texts, (world_axes, house) = _opengl_figure(view)
    title = W.HTML()  # the formula beside the figure: long canvas text costs ~7 ms per redraw
    controls = {
        "orbit": slider(0, -90, 90, 2, "orbit (deg)"),
        "frame": W.ToggleButtons(
            options=["OpenCV", "OpenGL / Blender"], value="OpenCV", description="frame"
        ),
    }

    def update(v, state):
        eye = cm.rotation_z(np.deg2rad(v["orbit"])) @ EYE_GL
        cam = cm.Camera.look_at(eye, GL_TARGET)
        ax.view_init(
            elev=VIEW_GL_ELEV, azim=_view_gl_azim(v["orbit"])
        )  # before fit_view, which refreshes
        art.update(cam)
        gl = v["frame"] != "OpenCV"
        R_axes = cm.opengl_from_opencv(cam.R, cam.t)[0] if gl else cam.R
        names = GL_NAMES["opengl" if gl else "opencv"]
        C = cam.centre
        # The limits fit both frames' label tips, so toggling the frame changes only the labels
        label_tips = C + GL_TIPS_M * np.vstack([cam.R, -cam.R[1:]])
        scene3d.fit_view(
            ax, [house_segments, np.zeros(3), label_tips, art.extent_points(cam)], fill=GL_FILL
        )
        for i, (ln, tx) in enumerate(zip(lines, texts, strict=True)):
            e = C + GL_AXIS_M * R_axes[i]  # row i of R = camera axis i in world coordinates
            ln.set_data_3d([C[0], e[0]], [C[1], e[1]], [C[2], e[2]])
            tx.set_position_3d(C + GL_LABEL_M * R_axes[i])
            tx.set_text(names[i])
            scene3d.align_away(ax, tx, C, e)
        R_gl, t_gl = cm.opengl_from_opencv(cam.R, cam.t)
        matrix_world = np.eye(4)  # Blender's world_from_cam: the inverse of [R_gl | t_gl]
        matrix_world[:3, :3], matrix_world[:3, 3] = R_gl.T, C
        title.value = _opengl_text(gl, cam, R_gl, t_gl, matrix_world)
        state.update(R_axes=R_axes, frame=v["frame"], camera=cam, matrix_world=matrix_world)

    demo = build_demo(
        "opencv_vs_opengl",
        controls,
        view,
        update,
        title="Same camera, two axis conventions",
        extra=[title],
    )
    # the browser draws the moves (projective_camera.js); the kernel keeps the matrices and state
    world = dict(
        house=house_segments,
        eye=EYE_GL,
        target=GL_TARGET,
        camera=art.camera,
        elev=VIEW_GL_ELEV,
        azim0=VIEW_GL_AZIM0,
        follow=VIEW_GL_FOLLOW,
        fill=GL_FILL,
        axis=GL_AXIS_M,
        label=GL_LABEL_M,
        tips=GL_TIPS_M,
        names=GL_NAMES,
    )
    parts = dict(world=world_axes, house=house, camera=art, lines=lines, texts=texts)
    view.publish(demo, opencv_vs_opengl_scene(view, ax, parts, world))
    return demo


def _opengl_text(gl, cam, R_gl, t_gl, matrix_world):
    """The formula and the matrices :func:`opencv_vs_opengl` shows beside its figure (HTML).

    Parameters
    ----------
    gl : bool
        True for the OpenGL/Blender frame, False for OpenCV.
    cam : Camera
        The camera (OpenCV frame).
    R_gl, t_gl : ndarray
        Its pose in the OpenGL frame.
    matrix_world : (4, 4) ndarray
        Blender's ``matrix_world``.

    Returns
    -------
    str
        The ``<pre>`` block.
    """
    C = cam.centre
    numbers = (
        _matrix("R_gl", R_gl, 3) + "\n" + f"t_gl = {_fmt(t_gl)} m\n"
        "matrix_world = [[R_gl^T, C], [0, 1]] (exercise 5):\n"
        + _matrix("matrix_world", matrix_world, 3)
        if gl
        else _matrix("R", cam.R, 3) + "\n" + f"t = {_fmt(cam.t)} m\nC = -R^T t = {_fmt(C)} m"
    )
    return (
        (
            "<pre>OpenGL/Blender: R_gl = diag(1,-1,-1) R, t_gl = diag(1,-1,-1) t\n"
            "camera looks along its -z axis (rows 2 and 3 of R flipped)\n"
            if gl
            else "<pre>OpenCV / H&amp;Z: X_cam = R X + t\ncamera looks along its +z axis\n"
        )
        + (
            "rows of R_gl = the drawn axes, in world coordinates\n"
            if gl
            else "rows of R = the drawn axes, in world coordinates\n"
        )
        + numbers
        + "\nin the figure: world axes 0.6 m, camera axes 0.9 m, house 0.6 m wide</pre>"
    )


def _opengl_figure(view):
    """The 3-D figure of :func:`opencv_vs_opengl`: world axes, the house, the camera, its axes.

    Returns
    -------
    ax : Axes3D
        The 3-D axes.
    house_segments : (M, 2, 3) ndarray
        The house, metres.
    art : CameraArtist
        The camera.
    lines, texts : list
        The camera's three axes and their labels, in the order x, y, z.
    world, house
        The world axes' artists (:func:`~camlab.plotting.wireframes.draw_world_axes`) and the house's line.
    """
    from mpl_toolkits.mplot3d import Axes3D  # noqa: F401  (registers the 3-D projection)

    ax = scene3d.axes3d(view.fig, 1, 1, 1, elev=VIEW_GL_ELEV, azim=_view_gl_azim(0.0))
    ax.set_axis_off()
    ax.set_position(
        (0.0, -0.12, 1.0, 1.2)
    )  # 3-D axes keep a square box: let it fill the wide canvas
    world = scene3d.draw_world_axes(ax, 0.6)
    house_segments = scenes.house_wireframe((0.0, 0.0, 0.0), 0.6)
    house = scene3d.draw_segments(ax, house_segments, color=palette.GREY)
    cam0 = cm.Camera.look_at(EYE_GL, GL_TARGET)
    art = scene3d.CameraArtist(
        ax, cam0, size=0.5, show_axes=False
    )  # about half the axes' length, so "z forward" clears the frustum's far edge
    lines, texts = [], []
    for c in palette.AXIS_COLOURS:
        (ln,) = ax.plot([], [], [], color=c, lw=2.5)
        lines.append(ln)
        texts.append(ax.text(0, 0, 0, "", color=c, fontsize=9, fontweight="bold"))
    # The limits follow the orbiting camera (house, axes and labels fill the canvas at every angle), so
    # everything in the 3-D axes moves with the projection and is animated.
    view.animate(*world, house, *art.artists(), *lines, *texts)
    return ax, house_segments, art, lines, texts, (world, house)
