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
    assert tuple(int(v) for v in matplotlib.__version__.split(".")[:2]) >= (3, 10)
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
        calls.append(["fitView", [np.where(np.isnan(pts), None, pts).tolist(), elev, azim, box, fill]])
        want.append((lims, ax.M))
    got = run_js(calls, VIEW3D)
    for js, (lims, M) in zip(got, want, strict=True):
        assert_twins(js["lims"], lims, "fitView limits")
        assert_twins(js["M"], M, "fitView projection")
