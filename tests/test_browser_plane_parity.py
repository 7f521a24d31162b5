"""Lesson 06's browser arithmetic (camlab/widgets/browser/geometry.js) equals its numpy twins.

The projective plane's demos drawn in the browser (camlab/widgets/projective_plane): each
JavaScript function runs under node on random inputs, with the edge cases each demo reaches, and is
compared with the camlab function named as its twin (1e-9 relative; strings exactly).
"""

from __future__ import annotations

import numpy as np
import pytest
from test_browser_geometry_parity import CASES, NODE, assert_twins, run_js

from camlab import projective as pj
from camlab.plotting.plane import arrow_placement
from camlab.widgets.projective_plane import twins

pytestmark = pytest.mark.skipif(
    NODE is None, reason="node is not installed: the JavaScript twins cannot be run"
)


def _boxes(rng: np.random.Generator, n: int) -> list[tuple[list[float], list[float]]]:
    lo = rng.uniform(-5, 0, (n, 2))
    hi = lo + rng.uniform(0.5, 8, (n, 2))
    return [([a[0], b[0]], [a[1], b[1]]) for a, b in zip(lo, hi, strict=True)]


def test_clip_line_and_arrow_placement_equal_camlab():
    rng = np.random.default_rng(61)
    boxes = _boxes(rng, CASES) + [([-3.0, 3.0], [-3.0, 3.0])] * 6
    lines = [*rng.normal(size=(CASES, 3))]
    # the edge cases: through a corner, along an edge, missing the box, the line at infinity
    lines += [[1.0, -1.0, 0.0], [0.0, 1.0, -3.0], [1.0, 0.0, 3.0], [1.0, 1.0, -9.0], [0, 0, 1.0]]
    lines += [[0.3, 0.2, 1.0]]
    points = [*rng.normal(scale=[4, 4, 1], size=(CASES, 3))]
    points += [[1.0, 2.0, 0.0], [-1.0, 0.5, 0.0], [6.0, 0.0, 1.0], [0.0, -9.0, 2.0], [1, 1, 1.0]]
    points += [[0.0, 1.0, 0.0]]
    anchors = [None if k % 3 == 0 else rng.uniform(-1, 1, 2).tolist() for k in range(len(points))]
    calls = [
        ("clipLine", [list(map(float, ln)), x, y]) for ln, (x, y) in zip(lines, boxes, strict=True)
    ]
    calls += [
        ("arrowPlacement", [list(map(float, p)), x, y, a])
        for p, (x, y), a in zip(points, boxes, anchors, strict=True)
    ]
    out = run_js(calls)
    n = len(lines)
    worst, missed = 0.0, 0
    for js, ln, (x, y) in zip(out[:n], lines, boxes, strict=True):
        py = pj.clip_line(ln, x, y)
        missed += bool(np.isnan(py).all())
        worst = max(worst, assert_twins(js, py, "clipLine"))
    arrows = 0
    for js, p, (x, y), a in zip(out[n:], points, boxes, anchors, strict=True):
        py = arrow_placement(np.asarray(p, dtype=float), x, y, None if a is None else np.array(a))
        arrows += bool(py.direction.any())
        worst = max(
            worst,
            assert_twins(
                [*js["position"], *js["direction"]], [*py.position, *py.direction], "arrowPlacement"
            ),
        )
    assert missed > 0 and 0 < arrows < len(points), (missed, arrows)
    print(f"clipLine/arrowPlacement: worst relative error {worst:.2e}")


def test_the_point_line_duality_arithmetic_and_caption_equal_the_demo():
    rng = np.random.default_rng(62)
    angles = np.concatenate([rng.uniform(0, 359, CASES), [0.0, 90.0, 180.0, 270.0, 45.0]])
    dist = np.concatenate([rng.uniform(0.2, 2.5, CASES), [1.0, 0.2, 2.5, 1.0, 0.35]])
    pts = np.concatenate(
        [
            np.round(rng.uniform(-2.5, 2.5, (CASES, 2)) / 0.05) * 0.05,
            [[1.0, 0.0], [0, -1], [1, 1], [0, 0], [2.5, 2.5]],
        ]
    )
    angles, dist = [float(a) for a in angles], [float(d) for d in dist]  # as the sliders give them
    calls = [("normalLine", [a, d]) for a, d in zip(angles, dist, strict=True)]
    lines = [twins.normal_line(a, d) for a, d in zip(angles, dist, strict=True)]
    homog = [np.array([float(x), float(y), 1.0]) for x, y in pts]
    lim = [-3.0, 3.0]
    calls += [
        ("dualityCaption", [p.tolist(), ln.tolist(), lim, lim])
        for p, ln in zip(homog, lines, strict=True)
    ]
    calls += [("plusFixed", [float(v), d]) for v in rng.uniform(-3, 3, 50) for d in (1, 2, 3)]
    calls += [("plusFixed", [v, 3]) for v in (0.0, -0.0, -0.0004, 0.0625, -0.0625)]
    out = run_js(calls)
    n = len(angles)
    worst = max(assert_twins(js, py, "normalLine") for js, py in zip(out[:n], lines, strict=True))
    captions = [twins.duality_caption(p, ln, lim, lim) for p, ln in zip(homog, lines, strict=True)]
    wrong = [(js, py) for js, py in zip(out[n : 2 * n], captions, strict=True) if js != py]
    assert not wrong, f"JS and Python captions differ: {wrong[:3]}"
    assert any("is on l" in c for c in captions) and any("(arrow)" in c for c in captions)
    formatted = [f"{args[0]:+.{args[1]}f}" for _, args in calls[2 * n :]]
    wrong = [
        (c, js, py)
        for c, js, py in zip(calls[2 * n :], out[2 * n :], formatted, strict=True)
        if js != py
    ]
    assert not wrong, f"JS and Python format differently: {wrong[:3]}"
    print(f"point_line_duality: worst relative error {worst:.2e}")


def test_the_parallel_lines_arithmetic_equals_the_demo():
    rng = np.random.default_rng(63)
    angles = [float(a) for a in np.round(rng.uniform(0, 60, CASES) * 2) / 2] + [30.0, 30.0, 0.0]
    offsets = [float(o) for o in np.round(rng.uniform(-3, 3, CASES) * 10) / 10] + [0.5, -1.0, 0.5]
    l1 = twins.line_at_angle(30.0, 0.5)
    sweep = np.linspace(0, 60, 241)
    calls = [("lineAtAngle", [a, o]) for a, o in zip(angles, offsets, strict=True)]
    lines2 = [twins.line_at_angle(a, o) for a, o in zip(angles, offsets, strict=True)]
    calls += [("meetOrNull", [l1.tolist(), ln.tolist()]) for ln in lines2]
    calls += [("meetWCurve", [l1.tolist(), 30.0, sweep.tolist(), o]) for o in offsets]
    out = run_js(calls)
    n = len(angles)
    worst = max(assert_twins(js, py, "lineAtAngle") for js, py in zip(out[:n], lines2, strict=True))
    nulls = 0
    for js, ln in zip(out[n : 2 * n], lines2, strict=True):
        py = twins.meet_or_none(l1, ln)
        assert (js is None) == (py is None), f"meetOrNull({ln}): JS {js}, numpy {py}"
        nulls += py is None
        if py is not None:
            worst = max(worst, assert_twins(js, py, "meetOrNull"))
    gaps = 0
    for js, o in zip(out[2 * n :], offsets, strict=True):
        py = twins.meet_w_curve(l1, 30.0, sweep, o)
        gaps += bool(np.isnan(py).any())
        worst = max(worst, assert_twins(js, py, "meetWCurve"))
    assert nulls >= 1 and gaps >= 2, "the case l2 = l1 (no meet, a gap in the curve) was not tried"
    print(f"parallel_lines: worst relative error {worst:.2e}")


def test_the_cross_ratio_arithmetic_and_caption_equal_the_demo():
    rng = np.random.default_rng(64)
    h = np.round(rng.uniform(-0.3, 0.3, (CASES, 2)) * 100) / 100
    angles = np.round(rng.uniform(-45, 45, CASES))
    settings = [(float(a), float(b), float(t)) for (a, b), t in zip(h, angles, strict=True)]
    settings += [(0.0, 0.0, 0.0), (0.3, 0.3, 45.0), (-0.3, -0.3, -45.0)]
    points = np.array(
        [[-1.0, -0.5], [-0.3, -0.15], [0.4, 0.2], [1.0, 0.5]]
    )  # the demo's A, B, C, D
    Hs = [twins.cross_ratio_homography(*s) for s in settings]
    mapped = [pj.map_points(H, points) for H in Hs]
    lines = [rng.normal(size=2) for _ in range(CASES)]  # four random collinear points each
    more = [rng.normal(size=2) + np.outer(rng.normal(size=4), d) for d in lines]
    calls = [("crossRatioHomography", list(s)) for s in settings]
    calls += [("crossRatio", [q.tolist()]) for q in mapped + more]
    calls += [("abOverBc", [q.tolist()]) for q in mapped]
    calls += [("labelOffset", [q.tolist()]) for q in mapped + more]
    calls += [("crossRatioCaption", [points.tolist(), q.tolist()]) for q in mapped]
    out = iter(run_js(calls))
    worst = max(assert_twins(next(out), H, "crossRatioHomography") for H in Hs)
    for q in mapped + more:
        worst = max(worst, assert_twins(next(out), pj.cross_ratio(q), "crossRatio"))
    for q in mapped:
        worst = max(worst, assert_twins(next(out), twins.ab_over_bc(q), "abOverBc"))
    for q in mapped + more:
        worst = max(worst, assert_twins(next(out), twins.label_offset(q), "labelOffset"))
    wrong = [
        (js, py)
        for js, py in ((next(out), twins.cross_ratio_caption(points, q)) for q in mapped)
        if js != py
    ]
    assert not wrong, f"JS and Python captions differ: {wrong[:3]}"
    print(f"cross_ratio_invariance: worst relative error {worst:.2e}")


def test_the_vanishing_points_arithmetic_equals_the_demo():
    from camlab.fixtures import ground_plane_view

    rng = np.random.default_rng(65)
    n = 60
    settings = [
        (float(p), float(y), float(r), float(f))
        for p, y, r, f in zip(
            np.round(rng.uniform(0, 40, n) * 2) / 2,
            np.round(rng.uniform(-45, 45, n) * 2) / 2,
            np.round(rng.uniform(-20, 20, n) * 2) / 2,
            np.round(rng.uniform(300, 1200, n) / 10) * 10,
            strict=True,
        )
    ]
    settings += [(12.0, 0.0, 0.0, 600.0), (40.0, 0.0, 0.0, 300.0), (0.0, 45.0, -20.0, 1200.0)]
    size = [640, 480]
    views = [twins.rolled_view(*s, size) for s in settings]
    ground = [ground_plane_view(*np.radians(s[:2]), s[3], size) for s in settings]
    calls = [("groundPlaneView", [*np.radians(s[:2]).tolist(), s[3], size]) for s in settings]
    calls += [("rolledView", [*s, size]) for s in settings]
    families = [f for g in views for f in (g.segments[: g.n_along_z], g.segments[g.n_along_z :])]
    calls += [("drawnVanishingPoint", [f.tolist()]) for f in families]
    drawn = [twins.drawn_vanishing_point(f) for f in families]
    calls += [
        ("horizonLine", [a.tolist(), b.tolist()])
        for a, b in zip(drawn[::2], drawn[1::2], strict=True)
    ]
    Ms = [rng.normal(size=(3, 3)) for _ in range(CASES)]
    calls += [("inv3", [M.tolist()]) for M in Ms]
    out = iter(run_js(calls))
    worst = 0.0
    for py in ground:
        js = next(out)
        assert js["nAlongZ"] == py.n_along_z
        for a, b in (
            (js["segments"], py.segments),
            (js["vpZ"], py.vp_z),
            (js["vpX"], py.vp_x),
            (js["horizon"], py.horizon),
        ):
            worst = max(worst, assert_twins(a, b, "groundPlaneView"))
    for py in views:
        js = next(out)
        for a, b in (
            (js["segments"], py.segments),
            (js["vpZ"], py.vp_z),
            (js["vpX"], py.vp_x),
            (js["horizon"], py.horizon),
        ):
            worst = max(worst, assert_twins(a, b, "rolledView"))
    ideal = 0
    for py in drawn:
        ideal += py[2] == 0
        worst = max(worst, assert_twins(next(out), py, "drawnVanishingPoint"))
    hz = [pj.horizon(a, b) for a, b in zip(drawn[::2], drawn[1::2], strict=True)]
    worst = max(worst, *(assert_twins(next(out), py, "horizonLine") for py in hz))
    worst = max(worst, *(assert_twins(next(out), np.linalg.inv(M), "inv3") for M in Ms))
    assert ideal >= 2, "no ideal vanishing point (yaw 0, roll 0) was tried"
    titles = [
        (h, bool(np.isfinite(pj.clip_line(h, (-0.5, 639.5), (-0.5, 479.5))).all())) for h in hz
    ]
    got = run_js([("horizonNote", [h.tolist(), v, "title"]) for h, v in titles])
    wrong = [
        (g, h)
        for g, (h, v) in zip(got, titles, strict=True)
        if g != twins.horizon_note(h, v, "title")
    ]
    assert not wrong and any(not v for _, v in titles), f"horizon notes differ: {wrong[:3]}"
    print(f"vanishing_points: worst relative error {worst:.2e}")


def _random_ellipses(rng: np.random.Generator, n: int) -> list[np.ndarray]:
    """Conics of real ellipses at any scale and sign, with the circles the demo reaches (exact and turned)."""
    out = []
    for _ in range(n):
        a = rng.normal(size=(2, 2))
        A = a @ a.T + 0.1 * np.eye(2)
        x0 = rng.normal(size=2)
        b = -A @ x0
        C = np.block([[A, b[:, None]], [b[None, :], np.array([[x0 @ A @ x0 - 1.0]])]])
        out.append(C * rng.choice([-1.0, 1.0]) * rng.uniform(0.01, 100))
    for angle in (0.0, 20.0, 45.0, -33.0):  # a circle turned: its 2 x 2 block I up to round-off
        H = twins.conic_homography(angle, 1.0, 0.0, 0.0)
        out.append(pj.map_conic(H, pj.circle_conic([0.0, 0.0], 1.0)))
    return out


def test_the_conic_points_are_canonical_and_equal_camlab():
    rng = np.random.default_rng(66)
    conics = _random_ellipses(rng, CASES)
    hyperbola = pj.conic_matrix(1, 0, -1, 0, 0, -1)
    calls = [("conicPoints", [C.tolist(), 50]) for C in conics]
    calls += [("conicPoints", [hyperbola.tolist(), 5])]
    out = run_js(calls)
    worst = max(
        assert_twins(js, pj.conic_points(C, 50), "conicPoints")
        for js, C in zip(out[:-1], conics, strict=True)
    )
    assert np.isnan(np.asarray(out[-1], dtype=float)).all(), "a hyperbola was drawn as an ellipse"
    print(f"conicPoints: worst relative error {worst:.2e}")


def _conic_settings(rng: np.random.Generator) -> list[tuple[float, float, float, float]]:
    """The demo's slider values: random on its steps, and the settings the lesson names."""
    random = zip(
        np.round(rng.uniform(-45, 45, CASES)),
        np.round(rng.uniform(0.6, 1.4, CASES) * 20) / 20,
        np.round(rng.uniform(-0.35, 0.35, CASES) * 100) / 100,
        np.round(rng.uniform(-0.35, 0.35, CASES) * 100) / 100,
        strict=True,
    )
    named = [
        (20, 1.4, 0.3, 0.15),
        (0, 1, 0, 0),
        (30, 1, 0, 0),
        (0, 0.95, 0.31, 0),
        (-45, 0.6, -0.35, 0.35),
    ]
    return [tuple(float(x) for x in s) for s in [*random, *named]]


def test_the_conic_arithmetic_and_caption_equal_the_demo():
    rng = np.random.default_rng(67)
    settings = _conic_settings(rng)
    t = np.linspace(0, 2 * np.pi, 9)[:-1]
    samples = np.stack([np.cos(t), np.sin(t)], axis=1)  # the demo's 8 points
    Hs = [twins.conic_homography(*s) for s in settings]
    C = pj.circle_conic([0.0, 0.0], 1.0)
    lines = rng.normal(size=(5, 3))
    symmetric = [M + M.T for M in rng.normal(size=(CASES, 3, 3))]
    calls = [("conicHomography", list(s)) for s in settings]
    calls += [("mapConic", [H.tolist(), C.tolist()]) for H in Hs]
    calls += [("mapDualConic", [H.tolist(), pj.dual_conic(C).tolist()]) for H in Hs]
    calls += [("mapLines", [H.tolist(), lines.tolist()]) for H in Hs]
    calls += [("dualConic", [M.tolist()]) for M in symmetric]
    calls += [("conicGeometry", [*s, samples.tolist()]) for s in settings]
    out = iter(run_js(calls))
    worst = max(assert_twins(next(out), H, "conicHomography") for H in Hs)
    for H in Hs:
        worst = max(worst, assert_twins(next(out), pj.map_conic(H, C), "mapConic"))
    for H in Hs:
        py = pj.map_dual_conic(H, pj.dual_conic(C))
        worst = max(worst, assert_twins(next(out), py, "mapDualConic"))
    for H in Hs:
        worst = max(worst, assert_twins(next(out), pj.map_lines(H, lines), "mapLines"))
    for M in symmetric:
        worst = max(worst, assert_twins(next(out), pj.dual_conic(M), "dualConic"))
    captions, fixed = [], 0
    for s in settings:
        js, py = next(out), twins.conic_geometry(*s, samples)
        for key, name in (("H", "H"), ("CMapped", "C_mapped"), ("mapped", "mapped")):
            worst = max(worst, assert_twins(js[key], getattr(py, name), f"conicGeometry {key}"))
        for key, name in (
            ("tangents", "tangents"),
            ("axisRatio", "axis_ratio"),
            ("centre", "centre"),
        ):
            worst = max(worst, assert_twins(js[key], getattr(py, name), f"conicGeometry {key}"))
        worst = max(
            worst,
            assert_twins(js["IMapped"], np.stack([py.I_mapped.real, py.I_mapped.imag], 1), "H I"),
        )
        assert js["fixed"] == py.fixed, (
            f"conicGeometry{s}: fixes I? JS {js['fixed']}, numpy {py.fixed}"
        )
        fixed += py.fixed
        # the residuals are round-off (about 1e-16): equal within 1e-14, not to 1e-9 of themselves
        for key, name in (("residual", "residual"), ("tangentResidual", "tangent_residual")):
            assert abs(js[key] - getattr(py, name)) <= 1e-14, (key, js[key], getattr(py, name))
        mine = py._replace(residual=js["residual"], tangent_residual=js["tangentResidual"])
        captions.append((js, s, twins.conic_caption(mine, s[2], s[3])))
    assert 0 < fixed < len(settings), "both a similarity and a non-similarity must be tried"
    got = run_js([("conicCaption", [js, s[2], s[3]]) for js, s, _ in captions])
    wrong = [(g, e) for g, (_, _, e) in zip(got, captions, strict=True) if g != e]
    assert not wrong, f"JS and Python captions differ: {wrong[:3]}"
    values = [
        float(v) for v in np.concatenate([10.0 ** rng.uniform(-18, 3, 300), [0.0, 1.0, 9.6e-17]])
    ]
    exps = run_js([("formatExp0", [v]) for v in values])
    wrong = [(v, e) for v, e in zip(values, exps, strict=True) if e != f"{v:.0e}"]
    assert not wrong, f"JS and Python format .0e differently: {wrong[:5]}"
    print(f"conic_under_homography: worst relative error {worst:.2e}")


def test_the_lift_to_plane_arithmetic_equals_the_demo():
    """liftView: the ray's ends in the 3-D box, λ(x, y, w), the meet with w = 1, the plane's dot (an
    arrow when off the view or ideal) and the note, at the sliders' steps and their edge cases."""
    from camlab.widgets.projective_plane import lift_to_plane

    rng = np.random.default_rng(66)
    xlim, ylim = [-2.0, 2.0], [-2.0, 2.0]
    box, w_max = 3.0, 2.0
    rays = [*np.round(rng.uniform([-1.5, -1.5, 0.0], [1.5, 1.5, 1.0], (CASES, 3)) / 0.05) * 0.05]
    rays += [*rng.uniform([-1.5, -1.5, 0.0], [1.5, 1.5, 1.0], (CASES, 3))]
    # ideal (w = 0), w = 0 on an axis, the zero vector, a point on the plane's edge, one off it
    rays += [[1.0, 0.5, 0.0], [0.0, -1.5, 0.0], [0.0, 0.0, 0.0], [1.0, 0.5, 0.5], [1.5, 0.1, 0.1]]
    scales = [*np.round(rng.uniform(-2, 2, len(rays)) / 0.05) * 0.05]
    scales[:3] = [0.0, -0.0, 2.0]
    args = [
        [list(map(float, r)), float(s), box, w_max, xlim, ylim]
        for r, s in zip(rays, scales, strict=True)
    ]
    out = run_js([("liftView", [*a, list(twins.LIFT_NOTES)]) for a in args])
    worst, arrows, notes = 0.0, 0, set()
    for js, a in zip(out, args, strict=True):
        py = twins.lift_view(np.array(a[0]), *a[1:])
        for key, value in (("pointH", py.point_h), ("ends", py.ends)):
            worst = max(worst, assert_twins(js[key], value, f"liftView {key} {a}"))
        for key, value in (("point", py.point), ("hit", py.hit)):
            assert (js[key] is None) == (value is None), (key, a, js[key], value)
            if value is not None:
                worst = max(worst, assert_twins(js[key], value, f"liftView {key} {a}"))
        assert (js["dot"] is None) == (py.dot is None), a
        if py.dot is not None:
            worst = max(worst, assert_twins(js["dot"]["position"], py.dot.position, "dot"))
            assert_twins(js["dot"]["direction"], py.dot.direction, "dot direction")
            arrows += bool(py.dot.direction.any())
        assert js["scaledShown"] == py.scaled_shown and js["note"] == py.note, (a, js, py)
        notes.add(py.note)
    assert notes == {"", *twins.LIFT_NOTES}, "not every note was reached"
    assert arrows >= 10, f"only {arrows} arrows"
    # and the demo's update is the twin: its state and artists at a few settings
    demo = lift_to_plane()
    for a in args[-5:]:
        demo.set(x=a[0][0], y=a[0][1], w=a[0][2], scale=a[1])
        py = twins.lift_view(np.array(a[0]), *a[1:])
        assert np.array_equal(demo.state["point_h"], py.point_h)
        assert np.array_equal(np.array(demo.figure.axes[0].lines[0].get_data_3d()).T, py.ends)
    print(f"liftView: worst relative error {worst:.2e}")


def test_a_3d_panel_maps_points_to_the_pixels_mplot3d_draws_them_at():
    """space_panel's 3 x 4 map (projectSpace, twin space_pixels) puts lift_to_plane's 3-D lines where
    matplotlib's Agg canvas draws them, at the default and at another setting."""
    from camlab.widgets.browser import canvas_height
    from camlab.widgets.browser.plane_scenes import space_panel, space_pixels
    from camlab.widgets.projective_plane import lift_to_plane

    rng = np.random.default_rng(67)
    demo = lift_to_plane()
    ax3 = demo.figure.axes[0]
    P = space_panel(ax3)["toPixels"]
    points = rng.uniform([-3.3, -3.3, -2.2], [3.3, 3.3, 2.2], (CASES, 3))
    (js,) = run_js([("projectSpace", [P, points.tolist()])])
    worst = assert_twins(js, space_pixels(P, points), "projectSpace")
    height = canvas_height(demo.figure)
    for setting in ({}, {"x": -1.2, "y": 0.7, "w": 0.4, "scale": -0.6}):
        demo.set(**setting)
        demo.view.pixels()  # drawn: mplot3d has projected the lines
        for line in ax3.lines:
            drawn = line.get_transform().transform(line.get_xydata())
            drawn[:, 1] = height - drawn[:, 1]
            mine = space_pixels(P, np.column_stack(line.get_data_3d()))
            assert np.abs(drawn - mine).max() < 1e-9, (line.get_label(), drawn, mine)
    print(f"projectSpace: worst relative error {worst:.2e}")
