"""Lesson 05's three cameras and dolly zoom.

One scene seen by the perspective camera and its affine approximations, and when an affine camera is
good enough.
"""

from __future__ import annotations

import inspect

import ipywidgets as W
import numpy as np
from matplotlib.lines import Line2D

from ... import affine as af
from ... import camera as cm
from ... import fixtures, scenes
from ...plotting import palette, scene3d
from .._base import build_demo, register, slider
from ..browser import BrowserView
from ..browser.scenes import dolly_zoom_scene, three_cameras_scene
from ..controls import int_slider, log_slider, monospace
from .common import (
    COLOURS,
    D0,
    DOLLY_DISTANCES,
    DOLLY_OFFSET,
    DOLLY_VIEW,
    F0,
    PRINCIPAL_POINT_MARKER,
    STYLES,
    TARGET,
    model_legend,
    model_line,
    place_reference,
    reference_marker,
)

# Where the middle panel joins the two images of one point: the cube's corners (a segment's two end
# points) and the rails' metre marks (7 points along 6 m).
GAP_SAMPLES = {"cube": 2, "rails": 7}
CUBE_EDGES = 12  # fixtures.box_and_rails: 12 cube edges, then 4 rails


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
    """Perspective, weak-perspective and orthographic images of the same scene side by side.

    Returns
    -------
    Demo
        The demo: controls ``azimuth``, ``elevation`` (degrees) and ``distance`` (m, a dolly
        zoom), the figure (the three images, the weak one over the perspective one), the
        readout (the longest orange segment, joining a point's two images, for the cube's
        corners and the rails' metre marks) and ``state``
        (``camera``, ``P_weak``, ``focal`` in px, ``gaps``, ``max_difference`` in px,
        ``reference_point``, ``reference_images``).
    """
    view = BrowserView(("azimuth", "elevation", "distance"), figsize=(9.5, 3.9))
    axes = view.fig.subplots(
        1, 3, width_ratios=(0.7, 1.4, 1.0)
    )  # the middle panel, where the gaps are, larger
    scene = fixtures.box_and_rails()
    persp, ghost, weak, orth, gap_lines = _three_panels(view.fig, axes)
    view.animate(persp, ghost, weak, orth, gap_lines)
    X0 = scene.reshape(-1, 3).mean(
        axis=0
    )  # the weak-perspective camera's reference point (three_images)
    references = [(view.animate(*reference_marker(ax)),) for ax in axes]  # the legend names it
    parts = {"cube": scene[:CUBE_EDGES], "rails": scene[CUBE_EDGES:]}
    readout = W.HTML()
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
        # the orange segments join the two images of each cube corner and each rail metre mark
        segments, gaps = _matched_gaps(cam, P_weak, parts)
        scene3d.update_segments(gap_lines, segments)
        readout.value = monospace(
            "weak perspective against perspective,\nlongest orange segment\n(one point's gap):\n"
            + "\n".join(f"  {part:5s} {_gap_text(g)}" for part, g in gaps.items())
            + f"\nfocal length f = {f:.0f} px"
        )
        state.update(
            camera=cam,
            P_weak=P_weak,
            focal=f,
            gaps=gaps,
            max_difference=max((g for g in gaps.values() if g == g), default=float("nan")),
            reference_point=X0,
            reference_images=images_of_X0,
        )

    demo = build_demo(
        "three_cameras",
        controls,
        view,
        update,
        title="One scene, three cameras (the middle panel repeats the perspective image in red)",
        extra=[readout],
    )
    # the browser draws the moves; the kernel keeps the readout and state
    lines = dict(perspective=persp, ghost=ghost, weak=weak, orthographic=orth, gaps=gap_lines)
    world = dict(
        segments=scene,
        parts={
            "cube": [0, CUBE_EDGES, GAP_SAMPLES["cube"]],
            "rails": [CUBE_EDGES, len(scene), GAP_SAMPLES["rails"]],
        },
        X0=X0,
        target=TARGET,
        f0=F0,
        d0=D0,
        principal_point=demo.state["camera"].K[:2, 2],  # dolly_zoom_camera's
        size=inspect.signature(af.matched_points_in_frame).parameters["size"].default,
    )
    view.publish(demo, three_cameras_scene(axes, lines, references[0][0], world))
    return demo


def _three_panels(fig, axes):
    """The three panels' empty lines (perspective, its ghost, weak, orthographic, the gaps) and the legend."""
    persp = _image_panel(axes[0], "perspective (px)", "perspective")
    weak = _image_panel(axes[1], "weak perspective over perspective (px)", "weak perspective")
    axes[1].set_ylabel("")
    axes[2].set_aspect("equal")
    axes[2].set_title("orthographic (m)", fontsize=9)
    axes[2].set_xlabel("camera x (m), right", fontsize=8)
    axes[2].set_ylabel("camera y (m), down", fontsize=8)
    # the scene reaches 3.14 m from its centre (a rail's end), which images at the origin: limits
    # of +-4.4 x +-3.3 m (4:3, as the pixel panels) hold it at every view
    axes[2].set_xlim(-4.4, 4.4)
    axes[2].set_ylim(3.3, -3.3)
    axes[2].set_xticks([-4, -2, 0, 2, 4])
    axes[2].set_yticks([-3, 0, 3])
    axes[2].tick_params(labelsize=7)
    orth = model_line(axes[2], "orthographic")
    ghost = model_line(
        axes[1], "perspective", lw=0.8, zorder=1.5
    )  # under the blue dashes, live and redrawn alike
    # a dot on each image of a point, a segment for its gap: the slide along a rail shows too
    gap_style = dict(color=palette.ORANGE, lw=1.8, marker="o", ms=2.5, zorder=3.5)
    (gap_lines,) = axes[1].plot([], [], **gap_style)
    gap_key = Line2D([], [], label="one point's two images", **gap_style)
    # the principal point, fixed along the dolly zoom: every orange segment points at it (section 2's law)
    centre = inspect.signature(af.dolly_zoom_camera).parameters["principal_point"].default
    axes[1].plot(*np.transpose([centre]), **PRINCIPAL_POINT_MARKER)
    model_legend(
        fig,
        ("perspective", "weak perspective", "orthographic"),
        reference=True,
        principal_point=True,
        extra=(gap_key,),
    )
    return persp, ghost, weak, orth, gap_lines


def _matched_gaps(cam, P_weak, parts):
    """The orange segments joining each sampled point's two images, and each part's longest, px."""
    matched = {
        part: af.matched_points_in_frame(cam, P_weak, segs, samples=GAP_SAMPLES[part])
        for part, segs in parts.items()
    }
    segments = np.stack([np.vstack(ab) for ab in zip(*matched.values(), strict=True)], axis=1)
    gaps = {
        part: float(np.linalg.norm(a - b, axis=1).max()) if len(a) else float("nan")
        for part, (a, b) in matched.items()
    }
    return segments, gaps


def _gap_text(gap: float) -> str:
    """A readout's gap in pixels, or why there is none (no part of it inside the frame)."""
    return "not in the frame" if np.isnan(gap) else f"{gap:5.1f} px"


def _rms_text(rms: float) -> str:
    """The dolly zoom's readout: the RMS over the cube's 8 corners, to 0.1 px, below 1 px to 0.01 px."""
    return f"RMS {rms:.1f} px" if rms >= 0.995 else f"RMS {rms:.2f} px"


def dolly_curves(offset: float, distances: np.ndarray) -> dict:
    """RMS error of weak and para-perspective along the dolly zoom, the cube ``offset`` px off centre.

    Parameters
    ----------
    offset : float
        Where the cube is imaged, pixels right of the principal point.
    distances : (D,) ndarray
        The dolly zoom's distances, metres.

    Returns
    -------
    dict of str to (D,) ndarray
        ``"weak perspective"`` and ``"para-perspective"``: the RMS error over the cube's 8
        corners at each distance, pixels (:func:`camlab.affine.dolly_zoom_errors`).
    """
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
    """The dolly zoom's log-log error panel.

    One (empty) curve and one marker per affine model, a slope -1 guide and the 1 px line.
    """
    from matplotlib.ticker import NullLocator

    curves = {
        m: ax.loglog(distances, np.ones_like(distances), color=COLOURS[m], ls=STYLES[m], lw=1.5)[0]
        for m in APPROXIMATIONS
    }
    ax.set_xlim(
        distances[0] / 1.3, distances[-1] * 1.3
    )  # room for the whole marker at the slider's ends, clear of the spines
    ax.set_ylim(*DOLLY_ERROR_LIMITS)
    ax.set_title("RMS distance to the perspective image\n(over the cube's 8 corners)", fontsize=9)
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


def _dolly_image_panel(view, ax, model, first):
    """One affine model's image panel of :func:`dolly_zoom`: its lines, markers and readout, empty.

    Returns a dict: ``ax``, ``under`` (the perspective image, red), ``line`` (the model's),
    ``centre`` (the principal point's +), ``reference`` (X0's diamond) and ``readout`` (the RMS text).
    """
    scene3d.image_axes(ax, (640, 480))
    ax.set_title(f"{model} over perspective", fontsize=9)
    ax.tick_params(labelleft=first)
    if not first:
        ax.set_ylabel("")
    under = model_line(
        ax, "perspective", lw=0.9, zorder=1.5
    )  # red under the affine cube, as in three_cameras
    line = model_line(
        ax, model, lw=1.6 if model == "weak perspective" else 1.9
    )  # the dots thicker, to read
    # Animated like the X0 diamond it must stay above (a static + would sit in the cached background,
    # under every live frame's diamond, and vanish at offset 0 where the two coincide).
    centre = view.animate(ax.plot([319.5], [239.5], **PRINCIPAL_POINT_MARKER)[0])
    (reference,) = reference_marker(ax)
    # The readout sits in the top-left corner, where no part of the cube comes at any setting (its images
    # stay right of u = 170 px and below v = 95 px).
    readout = ax.text(0.02, 0.975, "", transform=ax.transAxes, fontsize=8, ha="left", va="top")
    return dict(ax=ax, under=under, line=line, centre=centre, reference=reference, readout=readout)


@register(lesson="05", sweep={"distance": [2.0, 6.0, 40.0, 150.0], "offset": [0, 50, 100]})
def dolly_zoom():
    """Move the camera away while zooming in (f = f0 d / D0): the object keeps its size.

    The perspective image approaches its affine approximations and their error falls like
    1/d. Off the image centre, para-perspective stays closer than weak perspective; on the
    axis (offset 0) the two coincide. Each affine image has its own panel over the
    perspective one, so neither hides the other.

    Returns
    -------
    Demo
        The demo: controls ``distance`` (d, m, a log slider) and ``offset`` (the cube right of
        centre, px), the figure (the two affine images over the perspective one, and the
        log-log error curves) and ``state`` (``distance``, ``offset``, ``focal`` in px,
        ``rms_error`` and ``rms_paraperspective`` in px, ``curve``, ``curves``, ``camera``,
        ``reference_image``).
    """
    view = BrowserView(("distance", "offset"), figsize=(10, 3.9))
    ax_weak, ax_para, ax_err = view.fig.subplots(1, 3, width_ratios=(1.0, 1.0, 0.95))
    cube = scenes.box_wireframe((0.0, 0.0, 0.5), (1.0, 1.0, 1.0))
    pts = cube.reshape(-1, 3)
    models = ("perspective", "weak perspective", "para-perspective")
    panels = {
        m: _dolly_image_panel(view, ax, m, first=ax is ax_weak)
        for ax, m in ((ax_weak, "weak perspective"), (ax_para, "para-perspective"))
    }
    under, lines, readouts = (
        {m: p[k] for m, p in panels.items()} for k in ("under", "line", "readout")
    )
    references = {m: (p["reference"],) for m, p in panels.items()}
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
            readouts[m].set_text(_rms_text(rms[m]))  # short: each glyph costs time in every frame
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

    demo = build_demo(
        "dolly_zoom",
        controls,
        view,
        update,
        title="Dolly zoom: when is an affine camera good enough?",
    )
    world = dict(
        cube=cube,
        view=DOLLY_VIEW,
        target=TARGET,
        f0=F0,
        d0=D0,
        principal_point=demo.state["camera"].K[:2, 2],  # dolly_zoom_camera's
        distances=distances,
    )
    err = dict(ax=ax_err, curves=curves, markers=markers)
    view.publish(demo, dolly_zoom_scene(panels, err, world))  # the browser draws the moves
    return demo
