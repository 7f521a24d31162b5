"""The browser's arithmetic (camlab/widgets/browser/geometry.js) equals its numpy twins.

Each JavaScript function runs under node on random inputs and is compared with the camlab
function named as its twin in geometry.js, at 1e-9 relative (of the result's magnitude). Skipped,
with the reason, where node is not installed.
"""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from camlab.camera import Camera, project_points
from camlab.projective import from_homogeneous, join, map_points, meet
from camlab.widgets.start_here import (
    WAY_SWEEP_DEG,
    arrowhead_size,
    tip_readout,
    turn_and_scale,
    turn_path,
    turn_way,
    way_radius,
)

GEOMETRY = Path(__file__).resolve().parent.parent / "camlab" / "widgets" / "browser" / "geometry.js"
NODE = shutil.which("node")
RTOL = 1e-9
CASES = 200

pytestmark = pytest.mark.skipif(
    NODE is None, reason="node is not installed: the JavaScript twins cannot be run"
)

RUNNER = """
import * as G from %s;
let input = "";
process.stdin.on("data", (d) => (input += d));
process.stdin.on("end", () => {
  const calls = JSON.parse(input, (k, v) => (v === "NaN" ? NaN : v)); // NaN is sent as "NaN" (JSON has none)
  const out = calls.map(([name, args]) => G[name](...args));
  process.stdout.write(JSON.stringify(out, (k, v) => (ArrayBuffer.isView(v) ? Array.from(v) : typeof v === "number" && !Number.isFinite(v) ? String(v) : v)));
});
"""


def run_js(calls: list[tuple[str, list]], module: Path = GEOMETRY) -> list:
    """Call a module's functions under node (geometry.js by default): ``[(name, args), ...]`` -> their results (NaN kept)."""
    script = RUNNER % json.dumps(module.as_uri())
    done = subprocess.run(
        [NODE, "--input-type=module", "-e", script],
        input=json.dumps(calls),
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert done.returncode == 0, done.stderr

    def undo(v):
        if isinstance(v, list):
            return [undo(x) for x in v]
        return float(v) if isinstance(v, str) and v in ("NaN", "Infinity", "-Infinity") else v

    return undo(json.loads(done.stdout))


def assert_twins(js, py, what: str) -> float:
    """Assert equal at RTOL of the result's magnitude (NaN where NaN); return the worst relative error."""
    js, py = np.asarray(js, dtype=float), np.asarray(py, dtype=float)
    assert js.shape == py.shape, f"{what}: JS shape {js.shape}, numpy {py.shape}"
    assert np.array_equal(np.isnan(js), np.isnan(py)), f"{what}: NaN in different places"
    ok = ~np.isnan(py)
    scale = max(float(np.abs(py[ok]).max(initial=0.0)), 1e-300)
    err = float(np.abs(js[ok] - py[ok]).max(initial=0.0)) / scale
    assert err <= RTOL, f"{what}: relative error {err:.3g} > {RTOL}"
    return err


def random_rotation(rng: np.random.Generator) -> np.ndarray:
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def random_camera(rng: np.random.Generator) -> Camera:
    f = rng.uniform(200, 2000)
    K = np.array(
        [
            [f, rng.uniform(-5, 5), rng.uniform(100, 900)],
            [0, f * rng.uniform(0.8, 1.2), rng.uniform(100, 700)],
            [0, 0, 1],
        ]
    )
    return Camera(
        K=K, R=random_rotation(rng), t=rng.normal(scale=3, size=3), image_size=(1000, 800)
    )


def test_compose_and_project_equal_the_camera_model():
    rng = np.random.default_rng(31)
    cams = [random_camera(rng) for _ in range(CASES)]
    points = [rng.normal(scale=4, size=(20, 3)) for _ in cams]
    calls = [("composeP", [c.K.tolist(), c.R.tolist(), c.t.tolist()]) for c in cams]
    calls += [
        ("projectPoints", [c.P.tolist(), X.tolist()]) for c, X in zip(cams, points, strict=True)
    ]
    out = run_js(calls)
    worst = max(assert_twins(o, c.P, "composeP") for o, c in zip(out[:CASES], cams, strict=True))
    projected = out[CASES:]
    worst = max(
        worst,
        *(
            assert_twins(o, project_points(c.P, X), "projectPoints")
            for o, c, X in zip(projected, cams, points, strict=True)
        ),
    )
    assert any(np.isnan(np.asarray(o, dtype=float)).any() for o in projected), (
        "no point behind a camera was tried"
    )
    print(f"composeP/projectPoints: worst relative error {worst:.2e}")


def test_join_meet_and_maps_equal_the_projective_plane():
    rng = np.random.default_rng(6)
    p, q = rng.normal(size=(CASES, 2)) * 100, rng.normal(size=(CASES, 3))
    lines = rng.normal(size=(2, CASES, 3))
    H = rng.normal(size=(CASES, 3, 3))
    pts = [rng.normal(scale=50, size=(15, 2)) for _ in range(CASES)]
    H[0][2], pts[0][0] = (
        [1.0, 0.0, -2.0],
        [2.0, 5.0],
    )  # w = 2 - 2 = 0 exactly: a point mapped to infinity
    calls = [("join", [a.tolist(), b.tolist()]) for a, b in zip(p, q, strict=True)]
    calls += [("meet", [a.tolist(), b.tolist()]) for a, b in zip(*lines, strict=True)]
    calls += [("mapPoints", [h.tolist(), x.tolist()]) for h, x in zip(H, pts, strict=True)]
    calls += [("fromHomogeneous", [b.tolist()]) for b in q] + [
        ("fromHomogeneous", [[1.0, 2.0, 0.0]])
    ]
    out = run_js(calls)
    n = CASES
    worst = max(assert_twins(o, join(a, b), "join") for o, a, b in zip(out[:n], p, q, strict=True))
    worst = max(
        worst,
        *(
            assert_twins(o, meet(a, b), "meet")
            for o, a, b in zip(out[n : 2 * n], *lines, strict=True)
        ),
    )
    assert np.isnan(np.asarray(out[2 * n][0], dtype=float)).all(), (
        "a point at infinity came back finite"
    )
    worst = max(
        worst,
        *(
            assert_twins(o, map_points(h, x), "mapPoints")
            for o, h, x in zip(out[2 * n : 3 * n], H, pts, strict=True)
        ),
    )
    worst = max(
        worst,
        *(
            assert_twins(o, from_homogeneous(b), "fromHomogeneous")
            for o, b in zip(out[3 * n :], [*q, [1.0, 2.0, 0.0]], strict=True)
        ),
    )
    print(f"join/meet/mapPoints/fromHomogeneous: worst relative error {worst:.2e}")


def test_the_stack_check_arithmetic_equals_the_demo():
    rng = np.random.default_rng(0)
    angles = np.concatenate([rng.uniform(-180, 180, CASES), [-180.0, -90.0, 0.0, 5.0, 90.0, 180.0]])
    scales = rng.uniform(0.3, 2.0, len(angles))
    starts = rng.normal(size=(len(angles), 2))
    n = len(angles)
    calls = [("turnAndScale", [a, s]) for a, s in zip(angles, scales, strict=True)]
    calls += [
        ("turnPath", [a, s, x0.tolist(), 61])
        for a, s, x0 in zip(angles, scales, starts, strict=True)
    ]
    calls += [("arrowheadSize", [a]) for a in angles]
    calls += [
        ("turnWay", [a, way_radius(s), WAY_SWEEP_DEG, 25])
        for a, s in zip(angles, scales, strict=True)
    ]
    out = run_js(calls)
    worst = max(
        assert_twins(o, turn_and_scale(a, s), "turnAndScale")
        for o, a, s in zip(out[:n], angles, scales, strict=True)
    )
    worst = max(
        worst,
        *(
            assert_twins(o, turn_path(a, s, x0, 61), "turnPath")
            for o, a, s, x0 in zip(out[n : 2 * n], angles, scales, starts, strict=True)
        ),
    )
    worst = max(
        worst,
        *(
            assert_twins(o, arrowhead_size(a), "arrowheadSize")
            for o, a in zip(out[2 * n : 3 * n], angles, strict=True)
        ),
        *(
            assert_twins(o, turn_way(a, 25, s), "turnWay") if a else 0.0
            for o, a, s in zip(out[3 * n :], angles, scales, strict=True)
        ),
    )
    assert out[3 * n + list(angles).index(0.0)] == []  # no turn, no way
    print(f"stack_check arithmetic: worst relative error {worst:.2e}")


def test_the_readout_text_is_the_same_string():
    rng = np.random.default_rng(1)
    values = np.concatenate(
        [
            [
                round(float(v), int(d))
                for v, d in zip(rng.uniform(-3, 3, 400), rng.integers(1, 5, 400), strict=True)
            ],
            [0.125, -0.125, 0.375, -0.375, 1.625, -2.875, 0.005, -0.005, -0.001, 0.0, -0.0, 2.675],
        ]
    )
    points = values.reshape(-1, 2)
    out = run_js([("tipReadout", [p.tolist()]) for p in points])
    wrong = [
        (p.tolist(), o, tip_readout(p))
        for o, p in zip(out, points, strict=True)
        if o != tip_readout(p)
    ]
    assert not wrong, f"JS and Python readouts differ: {wrong[:5]}"


def _signed_cases(rng: np.random.Generator) -> np.ndarray:
    """Values to format: random, on the sliders' 0.05 grid, exact ties at 0 to 3 decimals, zeros."""
    grid = np.round(rng.integers(-40, 41, 200) * 0.05, 10) * rng.choice([1.0, 100.0, 0.01], 200)
    ties = np.array([k / 2 ** (d + 1) for d in range(4) for k in (-7, -3, -1, 1, 3, 5, 11)])
    cases = np.concatenate([rng.uniform(-300, 300, 200), grid, ties, [0.0, -0.0, 1e-4, -1e-4]])
    return [float(v) for v in cases]  # the demos format Python floats (numpy rounds otherwise)


def test_numbers_are_formatted_as_python_formats_them():
    from camlab.plotting.optics.similar_triangles import _signed

    values = _signed_cases(np.random.default_rng(11))
    calls = [("formatFixed", [v, d]) for d in range(4) for v in values]
    calls += [("signed", [v, d]) for d in range(4) for v in values]
    out = run_js(calls)  # JSON keeps -0.0's sign
    expected = [f"{v:.{d}f}" for d in range(4) for v in values]
    expected += [_signed(v, d) for d in range(4) for v in values]
    wrong = [(c, o, e) for c, o, e in zip(calls, out, expected, strict=True) if o != e]
    assert not wrong, f"JS and Python format differently: {wrong[:5]}"


def _layout_numbers(layout: dict) -> list[float]:
    """Every number of a similar-triangles layout, in one order (its dims' texts and alignments apart)."""
    keys = ("big", "small", "object", "point", "ray", "planes", "virtual", "real", "pinhole")
    numbers = [layout["y"]] + [float(x) for k in keys for x in np.ravel(layout[k])]
    for key in sorted(layout["dims"]):
        d = layout["dims"][key]
        numbers += [*d["a"], *d["b"], *d["at"], float(d["shown"])]
    return numbers


def test_the_similar_triangles_layout_and_title_equal_the_demo():
    from camlab.plotting import optics
    from camlab.widgets.pinhole_camera import ratios_title

    rng = np.random.default_rng(1)
    f = np.concatenate([rng.uniform(0.3, 1.0, CASES), [0.3, 0.85, 0.9, 1.0, 0.5, 0.8]])
    Z = np.concatenate([rng.uniform(1.2, 5.0, CASES), [1.2, 2.2, 2.15, 5.0, 3.0, 3.0]])
    Y = np.concatenate([rng.uniform(-1.0, 1.0, CASES), [0.0, -0.0, 0.25, -0.3, 1.0, -0.8]])
    f, Z, Y = ([float(v) for v in a] for a in (f, Z, Y))  # as the sliders give them
    rooms = dict(
        shortest=optics.SHORTEST_ARROW, fRoom=optics.F_LABEL_ROOM, zRoom=optics.Z_LABEL_ROOM
    )
    h = 1.3 * 0.85
    n = len(f)
    calls = [
        ("similarTrianglesLayout", [a, b, c, h, rooms]) for a, b, c in zip(f, Z, Y, strict=True)
    ]
    calls += [("ratiosTitle", [a, b, c]) for a, b, c in zip(f, Z, Y, strict=True)]
    out = run_js(calls)
    worst = 0.0
    for js, a, b, c in zip(out[:n], f, Z, Y, strict=True):
        py = optics.similar_triangles_layout(a, b, c, h)
        worst = max(worst, assert_twins(_layout_numbers(js), _layout_numbers(py), "layout"))
        for key, d in py["dims"].items():
            got = js["dims"][key]
            assert (got["text"], got["ha"], got["va"]) == (d["text"], d["ha"], d["va"]), (
                f"similarTrianglesLayout({a}, {b}, {c}) label {key}: {got} != {d}"
            )
    titles = [(o, ratios_title(a, b, c)) for o, a, b, c in zip(out[n:], f, Z, Y, strict=True)]
    wrong = [t for t in titles if t[0] != t[1]]
    assert not wrong, f"JS and Python titles differ: {wrong[:3]}"
    print(f"similar_triangles layout: worst relative error {worst:.2e}")


def _as_js_camera(cam: Camera) -> dict:
    return dict(K=cam.K.tolist(), R=cam.R.tolist(), t=cam.t.tolist())


def test_the_dolly_zoom_camera_and_its_affine_images_equal_camlab():
    from camlab import affine as af
    from camlab.camera import look_at_rotation, orbit_eye, project_segments
    from camlab.plotting.wireframes import polyline_data

    rng = np.random.default_rng(5)
    n = 60
    az, el = rng.uniform(-np.pi, np.pi, n), rng.uniform(0, 1.4, n)
    dist, offset = rng.uniform(2, 150, n), rng.uniform(0, 100, n)
    targets = rng.normal(size=(n, 3))
    cams = [
        af.dolly_zoom_camera(d, a, e, g, 800.0, 4.0, image_offset=o)
        for d, a, e, g, o in zip(dist, az, el, targets, offset, strict=True)
    ]
    # segments around the target, some reaching behind the camera (clipped, or NaN when wholly behind)
    segs = [
        g + rng.normal(scale=3 * d / 4, size=(12, 2, 3)) for g, d in zip(targets, dist, strict=True)
    ]
    X0 = [s.reshape(-1, 3).mean(axis=0) for s in segs]
    eyes = [orbit_eye(a, e, d, g) for a, e, d, g in zip(az, el, dist, targets, strict=True)]
    P_weak = [af.affine_approximation(c, x) for c, x in zip(cams, X0, strict=True)]
    expected = {
        "orbitEye": (
            [[a, e, d, g.tolist()] for a, e, d, g in zip(az, el, dist, targets, strict=True)],
            eyes,
        ),
        "lookAt": (
            [[y.tolist(), g.tolist()] for y, g in zip(eyes, targets, strict=True)],
            [look_at_rotation(y, g) for y, g in zip(eyes, targets, strict=True)],
        ),
        "dollyZoomCamera": (
            [
                [d, a, e, g.tolist(), 800.0, 4.0, [319.5, 239.5], o]
                for d, a, e, g, o in zip(dist, az, el, targets, offset, strict=True)
            ],
            [[c.K, c.R, c.t] for c in cams],
        ),
        "cameraProject": (
            [
                [_as_js_camera(c), s.reshape(-1, 3).tolist()]
                for c, s in zip(cams, segs, strict=True)
            ],
            [c.project(s.reshape(-1, 3)) for c, s in zip(cams, segs, strict=True)],
        ),
        "affineApproximation": (
            [[_as_js_camera(c), x.tolist()] for c, x in zip(cams, X0, strict=True)],
            P_weak,
        ),
        "orthographicMatrix": (
            [[c.R.tolist(), c.t.tolist()] for c in cams],
            [af.orthographic_matrix(c.R, c.t) for c in cams],
        ),
        "projectSegments": (
            [[_as_js_camera(c), s.tolist()] for c, s in zip(cams, segs, strict=True)]
            + [[P.tolist(), s.tolist()] for P, s in zip(P_weak, segs, strict=True)],
            [project_segments(c, s) for c, s in zip(cams, segs, strict=True)]
            + [project_segments(P, s) for P, s in zip(P_weak, segs, strict=True)],
        ),
        "polylineData": (
            [[project_segments(P, s).tolist()] for P, s in zip(P_weak, segs, strict=True)],
            [polyline_data(project_segments(P, s)) for P, s in zip(P_weak, segs, strict=True)],
        ),
    }
    calls = [(name, args) for name, (argss, _) in expected.items() for args in argss]
    out = iter(run_js(calls))
    worst, nan_seen = 0.0, False
    for name, (_, results) in expected.items():
        for py in results:
            js = next(out)
            if name == "dollyZoomCamera":
                js, py = [js["K"], js["R"], js["t"]], py
                for j, p in zip(js, py, strict=True):
                    worst = max(worst, assert_twins(j, p, name))
                continue
            nan_seen |= name == "projectSegments" and bool(np.isnan(np.asarray(py)).any())
            worst = max(worst, assert_twins(js, py, name))
    assert nan_seen, "no segment wholly behind a camera was tried"
    print(f"dolly zoom cameras and affine images: worst relative error {worst:.2e}")


def test_the_matched_points_in_the_frame_equal_camlab():
    from camlab import affine as af
    from camlab.fixtures import box_and_rails

    rng = np.random.default_rng(9)
    scene = box_and_rails()
    X0 = scene.reshape(-1, 3).mean(axis=0)
    cases = []
    for d, a, e in zip(
        rng.uniform(2, 20, 40), rng.uniform(-90, 90, 40), rng.uniform(0, 80, 40), strict=True
    ):
        cam = af.dolly_zoom_camera(d, *np.radians([a, e]), (0.0, 0.0, 0.5), 800.0, 4.0)
        cases.append((cam, af.affine_approximation(cam, X0), int(rng.integers(2, 9))))
    calls = [
        ("matchedPointsInFrame", [_as_js_camera(c), P.tolist(), scene.tolist(), [640, 480], k])
        for c, P, k in cases
    ]
    worst, dropped = 0.0, 0
    for js, (cam, P, k) in zip(run_js(calls), cases, strict=True):
        py = af.matched_points_in_frame(cam, P, scene, samples=k)
        worst = max(
            worst,
            assert_twins(js["perspective"], py.perspective.reshape(-1, 2), "matched perspective"),
            assert_twins(js["affine"], py.affine.reshape(-1, 2), "matched affine"),
        )
        dropped += len(scene) * k - len(py.perspective)
    assert dropped > 0, "no sample fell outside the frame"
    print(f"matchedPointsInFrame: worst relative error {worst:.2e}")


def test_the_dolly_zoom_errors_and_readout_equal_camlab():
    from camlab import affine as af
    from camlab.scenes import box_wireframe
    from camlab.widgets.affine_cameras.views import APPROXIMATIONS, _rms_text, dolly_curves

    rng = np.random.default_rng(7)
    n = 40
    cams = [
        af.dolly_zoom_camera(d, a, e, g, 800.0, 4.0, image_offset=o)
        for d, a, e, g, o in zip(
            rng.uniform(2, 150, n),
            rng.uniform(-np.pi, np.pi, n),
            rng.uniform(0, 1.4, n),
            rng.normal(size=(n, 3)),
            rng.uniform(0, 100, n),
            strict=True,
        )
    ]
    X = [c.centre + c.R[2] * 5 + rng.normal(size=(8, 3)) for c in cams]
    X0 = [x.mean(axis=0) for x in X]
    distances = np.geomspace(2, 150, 60)
    offsets = [0.0, 50.0, 100.0, float(rng.uniform(0, 100))]
    calls = [
        ("paraperspectiveApproximation", [_as_js_camera(c), x.tolist()])
        for c, x in zip(cams, X0, strict=True)
    ]
    calls += [
        ("approximationError", [_as_js_camera(c), x.tolist(), x0.tolist(), m])
        for m in APPROXIMATIONS
        for c, x, x0 in zip(cams, X, X0, strict=True)
    ]
    cube = box_wireframe((0.0, 0.0, 0.5), (1.0, 1.0, 1.0)).reshape(-1, 3)  # dolly_curves' cube
    view = np.radians([-40.0, 20.0])
    calls += [
        (
            "dollyZoomErrors",
            [
                cube.tolist(),
                distances.tolist(),
                *view,
                [0.0, 0.0, 0.5],
                800.0,
                4.0,
                m,
                o,
                [319.5, 239.5],
            ],
        )
        for o in offsets
        for m in APPROXIMATIONS
    ]
    rms = np.concatenate([rng.uniform(0.2, 60, 200), [0.994, 0.995, 0.996, 0.125, 1.25, 17.25]])
    rms = [float(r) for r in rms]
    calls += [("rmsText", [r]) for r in rms]
    out = iter(run_js(calls))
    worst = max(
        assert_twins(next(out), af.paraperspective_approximation(c, x), "paraperspective")
        for c, x in zip(cams, X0, strict=True)
    )
    for m, approximate in APPROXIMATIONS.items():
        for c, x, x0 in zip(cams, X, X0, strict=True):
            py = af.weak_perspective_error(c, x, x0, approximate)
            worst = max(worst, assert_twins(next(out), py, f"approximationError {m}"))
    for o in offsets:
        curves = dolly_curves(o, distances)
        for m in APPROXIMATIONS:
            worst = max(worst, assert_twins(next(out), curves[m], f"dollyZoomErrors {m} {o}"))
    wrong = [(r, t, _rms_text(r)) for r, t in zip(rms, out, strict=True) if t != _rms_text(r)]
    assert not wrong, f"JS and Python RMS readouts differ: {wrong[:5]}"
    print(f"dolly zoom errors: worst relative error {worst:.2e}")


def test_the_joined_module_the_canvas_loads_parses(tmp_path):
    """esm_source joins every module into one: two modules declaring the same top-level name make it
    a SyntaxError, and then no browser-drawn demo shows (every browser test waits out its timeout)."""
    from camlab.widgets.browser import esm_source

    joined = tmp_path / "camlab_canvas.mjs"
    joined.write_text(esm_source(), encoding="utf-8")
    run = subprocess.run([NODE, "--check", str(joined)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, f"the joined ES module does not parse:\n{run.stderr[-1500:]}"
