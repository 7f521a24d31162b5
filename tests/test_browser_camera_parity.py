"""Lesson 04's browser arithmetic (view3d.js, projective_camera.js) equals its twins.

The 3-D axes' projection and fit (view3d.js) against matplotlib's own Axes3D.get_proj and
camlab.plotting.view3d.fit_view; the camera explorer's camera, image plane and frame
(projective_camera.js) against camlab.widgets.projective_camera and camlab.plotting.scene3d. Each
runs under node on random inputs (1e-9 relative).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib
import numpy as np
import pytest
from matplotlib.figure import Figure
from test_browser_geometry_parity import CASES, NODE, assert_twins, run_js

from camlab.plotting import scene3d

BROWSER = Path(__file__).resolve().parent.parent / "camlab" / "widgets" / "browser"
VIEW3D = BROWSER / "view3d.js"

pytestmark = pytest.mark.skipif(
    NODE is None, reason="node is not installed: the JavaScript twins cannot be run"
)


def _axes3d():
    fig = Figure(figsize=(4, 4), dpi=90)
    return scene3d.axes3d(fig, 1, 1, 1)


def test_the_3d_projection_equals_matplotlibs_get_proj():
    if tuple(int(v) for v in matplotlib.__version__.split(".")[:2]) < (3, 10):
        pytest.skip(
            "view3d.js's axesProjection twins matplotlib 3.10's Axes3D.get_proj; 3.9's differs"
        )
    rng = np.random.default_rng(40)
    ax = _axes3d()
    calls, want = [], []
    for _ in range(CASES):
        lo = rng.uniform(-5, 5, 3)
        lims = np.column_stack([lo, lo + rng.uniform(0.5, 9, 3)])
        aspect = rng.uniform(0.3, 2.0, 3)
        zoom, elev, azim = rng.uniform(0.2, 3), rng.uniform(-89, 89), rng.uniform(-400, 400)
        ax.set_xlim3d(*lims[0])
        ax.set_ylim3d(*lims[1])
        ax.set_zlim3d(*lims[2])
        ax.set_box_aspect(aspect, zoom=zoom)
        ax.view_init(elev=elev, azim=azim)
        M = ax.get_proj()
        X = rng.uniform(lo - 1, lo + 10, (5, 3))
        calls.append(["axesProjection", [lims.tolist(), aspect.tolist(), zoom, elev, azim]])
        want.append(M)
        calls.append(["project3d", [M.tolist(), X.tolist()]])
        from mpl_toolkits.mplot3d import proj3d

        want.append(np.column_stack(proj3d.proj_transform(*X.T, M)))
    got = run_js(calls, VIEW3D)
    for k, (js, py) in enumerate(zip(got, want, strict=True)):
        assert_twins(js, py, calls[k][0])


def test_the_fitted_view_equals_camlabs_fit_view():
    rng = np.random.default_rng(41)
    ax = _axes3d()
    view = ax.viewLim
    box = [view.x0, view.y0, view.x1, view.y1]
    calls, want = [], []
    for k in range(60):
        pts = rng.normal(scale=rng.uniform(0.5, 4), size=(int(rng.integers(4, 40)), 3))
        pts += rng.uniform(-3, 3, 3)
        if k % 5 == 0:
            pts[0] = np.nan
        elev, azim = rng.uniform(-60, 80), rng.uniform(-200, 200)
        fill = rng.uniform(0.6, 0.95)
        ax.view_init(elev=elev, azim=azim)
        scene3d.fit_view(ax, pts, fill=fill)
        lims = np.array([ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()])
        calls.append(["fitView", [_nan_as_text(pts), elev, azim, box, fill]])
        want.append((lims, ax.M))
    got = run_js(calls, VIEW3D)
    for js, (lims, M) in zip(got, want, strict=True):
        assert_twins(js["lims"], lims, "fitView limits")
        assert_twins(js["M"], M, "fitView projection")


CAMERA = BROWSER / "projective_camera.js"


def _explorer_values(rng: np.random.Generator) -> dict:
    """Random camera_explorer settings over the sliders' whole ranges."""
    from camlab.widgets.projective_camera import EXPLORER_SWEEP

    return {k: float(rng.uniform(min(v), max(v))) for k, v in EXPLORER_SWEEP.items()}


def _nan_as_text(a) -> list:
    """An array as JSON for run_js: NaN as "NaN" (JSON has no NaN; the runner turns it back)."""
    a = np.asarray(a, dtype=float)
    return np.where(np.isnan(a), "NaN", a.astype(object)).tolist()


def test_the_explorer_camera_and_its_plane_size_equal_camlab():
    from camlab.widgets.projective_camera import TARGET, explorer_camera, explorer_plane_size

    rng = np.random.default_rng(42)
    calls, want = [], []
    for k in range(CASES):
        v = _explorer_values(rng)
        if k < 4:  # the default, and the sliders' corners
            v = [{}, dict(fx=200, fy=1600, skew=-300, cx=-0.5, cy=479.5)][k % 2] | (
                {} if k < 2 else dict(roll=90, pan=-30, slide=-1.0, elevation=-4, distance=2.5)
            )
        cam = explorer_camera(**v)
        full = {
            n: float(c.default)
            for n, c in __import__("inspect").signature(explorer_camera).parameters.items()
        } | v
        calls.append(["explorerCamera", [full, TARGET.tolist()]])
        want.append(dict(K=cam.K, R=cam.R, t=cam.t, centre=cam.centre))
        calls.append(["explorerPlaneSize", [full["distance"], cam.K.tolist()]])
        want.append(explorer_plane_size(full["distance"], cam.K))
    got = run_js(calls, CAMERA)
    for js, py in zip(got[0::2], want[0::2], strict=True):
        for key in ("K", "R", "t", "centre"):
            assert_twins(js[key], py[key], f"explorerCamera {key}")
    assert_twins(got[1::2], want[1::2], "explorerPlaneSize")


def test_plane_points_and_clipped_segments_equal_scene3d():
    from camlab.plotting.scene3d import _plane_points

    rng = np.random.default_rng(43)
    from test_browser_geometry_parity import random_camera

    calls, want = [], []
    for _ in range(CASES):
        cam = random_camera(rng)
        uv = rng.uniform(-200, 1200, (6, 2))
        uv[rng.integers(0, 6)] = np.nan  # a break between segments stays a break
        size = float(rng.uniform(0.1, 3))
        js_cam = dict(K=cam.K.tolist(), R=cam.R.tolist(), t=cam.t.tolist())
        calls.append(["planePoints", [js_cam, _nan_as_text(uv), size]])
        want.append(_plane_points(cam, uv, size))
        segs = rng.uniform(-400, 1400, (8, 2, 2))
        segs[0] = [[-10.0, 5.0], [20.0, 5.0]]  # along an edge's line, through the image
        segs[1] = [[-10.0, -3.0], [700.0, -3.0]]  # wholly above it
        segs[2, 1] = np.nan
        calls.append(["clipSegments", [_nan_as_text(segs), [640, 480]]])
        want.append(scene3d.clip_segments(segs, (640, 480)))
    got = run_js(calls, CAMERA)
    for k, (js, py) in enumerate(zip(got, want, strict=True)):
        assert_twins(js, py, calls[k][0])


def test_the_camera_figure_equals_the_camera_artist():
    from test_browser_geometry_parity import random_camera

    rng = np.random.default_rng(44)
    ax = _axes3d()
    calls, want = [], []
    for _ in range(40):
        cam = random_camera(rng)
        size, length = float(rng.uniform(0.1, 3)), float(rng.uniform(0.1, 1))
        offset = rng.uniform(-0.5, 0.5, 3)
        art = scene3d.CameraArtist(ax, cam, size=size, label="C", axis_length=length)
        art.label_offset = tuple(offset)
        art.update(cam)
        js_cam = dict(
            K=cam.K.tolist(), R=cam.R.tolist(), t=cam.t.tolist(), centre=cam.centre.tolist()
        )
        calls.append(
            ["cameraFigure", [js_cam, size, length, offset.tolist(), list(cam.image_size)]]
        )
        want.append(
            dict(
                frustum=np.column_stack(art.frustum.get_data_3d()),
                corners=art.corners(cam),
                axes=[np.column_stack(ln.get_data_3d()) for ln in art.axes_lines],
                tips=[tx.get_position_3d() for tx in art.axes_text],
                labelAt=art.label.get_position_3d(),
                extent=art.extent_points(cam),
            )
        )
    got = run_js(calls, CAMERA)
    for js, py in zip(got, want, strict=True):
        for key, value in py.items():
            assert_twins(js[key], value, f"cameraFigure {key}")


def test_the_explorer_frame_equals_the_demo(monkeypatch):
    """explorerFrame at random settings: the 3-D view's projection and limits, the frustum, the
    thumbnail on the image plane and the image, as the demo's update leaves its artists."""
    monkeypatch.setenv("CAMLAB_FIGURE_MODE", "ipympl")
    monkeypatch.delenv("CAMLAB_BROWSER_DRAWING", raising=False)
    from camlab.widgets.projective_camera import camera_explorer

    demo = camera_explorer()
    scene = {k: v for k, v in demo.view.canvas.scene.items() if k != "background"}
    ax3, ax2 = demo.figure.axes
    rng = np.random.default_rng(45)
    calls, want = [], []
    for k in range(40):
        v = {} if k == 0 else _explorer_values(rng)
        demo.set(**v)
        values = {n: float(c.value) for n, c in demo.controls.items()}
        calls.append(["explorerFrame", [scene, values]])
        world, frustum = ax3.lines[0], ax3.lines[4]
        assert len(world.get_data_3d()[0]) == 3 * len(scene["segments"])
        want.append(
            dict(
                M=ax3.M,
                lims=[ax3.get_xlim3d(), ax3.get_ylim3d(), ax3.get_zlim3d()],
                frustum=np.column_stack(frustum.get_data_3d()),
                thumbnail=np.column_stack(ax3.lines[9].get_data_3d()),
                image=ax2.lines[0].get_xydata(),
                azim=ax3.azim,
            )
        )
    got = run_js(calls, CAMERA)
    for js, py in zip(got, want, strict=True):
        assert_twins(js["view"]["M"], py["M"], "explorerFrame projection")
        assert_twins(js["view"]["lims"], py["lims"], "explorerFrame limits")
        assert_twins(js["figure"]["frustum"], py["frustum"], "explorerFrame frustum")
        assert_twins(js["thumbnail"], py["thumbnail"], "explorerFrame thumbnail")
        assert_twins(js["image"], py["image"], "explorerFrame image")
        assert_twins(js["azim"], py["azim"], "explorerFrame viewer azimuth")


def test_the_opencv_vs_opengl_frame_equals_the_demo(monkeypatch):
    """opencvFrame at random orbits in both frames: the projection and limits, the camera's axes,
    their labels' places, words and alignment (align_away), as the demo's update leaves them."""
    monkeypatch.setenv("CAMLAB_FIGURE_MODE", "ipympl")
    monkeypatch.delenv("CAMLAB_BROWSER_DRAWING", raising=False)
    from camlab.widgets.projective_camera import opencv_vs_opengl

    demo = opencv_vs_opengl()
    scene = {k: v for k, v in demo.view.canvas.scene.items() if k != "background"}
    (ax,) = demo.figure.axes
    rng = np.random.default_rng(46)
    orbits = [-90.0, 90.0, 0.0, *rng.uniform(-90, 90, 37)]
    calls, want = [], []
    for k, orbit in enumerate(orbits):
        frame = ("OpenCV", "OpenGL / Blender")[k % 2]
        demo.set(orbit=float(orbit), frame=frame)
        calls.append(["opencvFrame", [scene, {"orbit": float(orbit), "frame": frame}]])
        lines, texts = ax.lines[-3:], ax.texts[-3:]
        want.append(
            dict(
                M=ax.M,
                lims=[ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()],
                axes=[np.column_stack(ln.get_data_3d()) for ln in lines],
                labels=[
                    (tx.get_position_3d(), tx.get_text(), tx.get_ha(), tx.get_va()) for tx in texts
                ],
                R_axes=demo.state["R_axes"],
            )
        )
    got = run_js(calls, CAMERA)
    for js, py in zip(got, want, strict=True):
        assert_twins(js["view"]["M"], py["M"], "opencvFrame projection")
        assert_twins(js["view"]["lims"], py["lims"], "opencvFrame limits")
        assert_twins(js["axesR"], py["R_axes"], "opencvFrame axes")
        assert_twins([a["line"] for a in js["axes"]], py["axes"], "opencvFrame axis lines")
        for a, (at, text, ha, va) in zip(js["axes"], py["labels"], strict=True):
            assert_twins(a["label"]["at"], at, "opencvFrame label place")
            assert (a["label"]["text"], a["label"]["ha"], a["label"]["va"]) == (text, ha, va)
