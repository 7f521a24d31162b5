"""Lesson 11's browser arithmetic (camlab/widgets/browser/geometry.js) equals its numpy twins.

``epipolar_lines`` drawn in the browser: the camera pairs, F, the epipolar lines and their
polylines across the image, the depth marks and the epipoles, on random control values and the
settings the demo reaches at its edges (toe-in 0: epipoles at infinity; forward motion: the centre
pixel at the left epipole), compared at 1e-9 relative with camlab.
"""

from __future__ import annotations

import numpy as np
import pytest
from test_browser_geometry_parity import CASES, NODE, assert_twins, run_js

from camlab import epipolar as ep
from camlab.fixtures import forward_pair, stereo_pair
from camlab.widgets import epipolar_twins as twins
from camlab.widgets.stereo_rectification import REF_PIXELS

pytestmark = pytest.mark.skipif(
    NODE is None, reason="node is not installed: the JavaScript twins cannot be run"
)


def _cam(c) -> dict:
    return dict(K=c.K.tolist(), R=c.R.tolist(), t=c.t.tolist())


def _settings(rng: np.random.Generator) -> list[tuple[str, float, float, list[float]]]:
    """Control values on the sliders' steps, both motions, and the edges (toe-in 0, the centre)."""
    out = []
    for k in range(CASES):
        motion = list(twins.MOTIONS)[k % 2]
        baseline = float(np.round(rng.uniform(0.02, 0.5) * 100) / 100)
        toe = float(np.round(rng.uniform(-20, 20) * 2) / 2)
        point = [float(np.round(rng.uniform(10, 629))), float(np.round(rng.uniform(10, 469)))]
        out.append((motion, baseline, toe, point))
    out += [(m, 0.2, 0.0, [420.0, 300.0]) for m in twins.MOTIONS]
    out += [
        ("forward (driving)", 0.3, 0.0, [320.0, 240.0]),
        ("sideways (stereo rig)", 0.5, -20.0, [10.0, 469.0]),
    ]
    return out


def test_the_camera_pairs_and_f_equal_camlab():
    rng = np.random.default_rng(111)
    pairs = [
        (float(b), float(t))
        for b, t in zip(rng.uniform(0.02, 0.5, CASES), rng.uniform(-0.35, 0.35, CASES), strict=True)
    ]
    pairs += [(0.2, 0.0), (0.5, 0.0)]
    calls = [("stereoPair", [b, t]) for b, t in pairs] + [("forwardPair", [b, t]) for b, t in pairs]
    out = run_js(calls)
    py = [stereo_pair(b, t) for b, t in pairs] + [forward_pair(b, t) for b, t in pairs]
    worst = 0.0
    for js, cams in zip(out, py, strict=True):
        for j, c in zip(js, cams, strict=True):
            for key in ("K", "R", "t"):
                worst = max(worst, assert_twins(j[key], getattr(c, key), f"camera pair {key}"))
    calls = [("fundamentalFromCameras", [_cam(a), _cam(b)]) for a, b in py]
    calls += [("cameraCentre", [_cam(c)]) for pair in py for c in pair]
    out = iter(run_js(calls))
    for a, b in py:
        F, js = ep.fundamental_from_cameras(a, b), np.asarray(next(out))
        worst = max(worst, assert_twins(js * np.sign(np.sum(js * F)), F, "fundamentalFromCameras"))
    for c in (c for pair in py for c in pair):
        worst = max(worst, assert_twins(next(out), c.centre, "cameraCentre"))
    print(f"camera pairs and F: worst relative error {worst:.2e}")


def test_the_epipolar_view_and_its_polylines_equal_the_demo():
    rng = np.random.default_rng(112)
    settings = _settings(rng)
    ref = REF_PIXELS
    views = [twins.epipolar_view(m, b, t, np.array(x), ref) for m, b, t, x in settings]
    out = run_js([("epipolarView", [m, b, t, x, ref.tolist()]) for m, b, t, x in settings])
    worst, nan_rows, ideal = 0.0, 0, 0
    keys = {
        "lineRight": "line_right",
        "pencilRight": "pencil_right",
        "depthPoints": "depth_points",
    }
    for js, py in zip(out, views, strict=True):
        for jk, pk in keys.items():
            worst = max(worst, assert_twins(js[jk], getattr(py, pk), f"epipolarView {jk}"))
        # lines and epipoles are homogeneous: the demo draws them through scale-free polylines and
        # arrow placements; the twins compute the same vectors
        for jk, pk in (
            ("lineLeft", "line_left"),
            ("pencilLeft", "pencil_left"),
            ("epipoles", "epipoles"),
        ):
            worst = max(worst, assert_twins(js[jk], getattr(py, pk), f"epipolarView {jk}"))
        nan_rows += int(np.isnan(py.pencil_right[:, 0]).sum())
        ideal += int(abs(py.epipoles[1][2]) < 1e-9 * np.linalg.norm(py.epipoles[1]))
    assert nan_rows >= 1, "no reference pixel at the left epipole (forward motion) was tried"
    assert ideal >= 1, "no epipole at infinity (toe-in 0) was tried"
    lines = [np.vstack([g.line_right, g.line_left, g.pencil_right, g.pencil_left]) for g in views]
    lines = [ln[np.isfinite(ln).all(axis=1)] for ln in lines]  # the drawer skips a pixel's NaN line
    wired = views[::10]
    calls = [("linePolyline", [ln.tolist(), [640, 480]]) for ln in lines]
    calls += [("projectedSegments", [_cam(c), SEGMENTS.tolist()]) for g in wired for c in g.cameras]
    out = iter(run_js(calls))
    for ln in lines:
        worst = max(worst, assert_twins(next(out), twins.line_polyline(ln), "linePolyline"))
    for c in (c for g in wired for c in g.cameras):
        py = twins.projected_segments(c, SEGMENTS)
        worst = max(worst, assert_twins(next(out), py, "projectedSegments"))
    print(f"epipolar_lines: worst relative error {worst:.2e}")


def _segments() -> np.ndarray:
    from camlab import scenes
    from camlab.fixtures.stereo import stereo_scene

    return scenes.plane_outlines(stereo_scene())


SEGMENTS = _segments()
