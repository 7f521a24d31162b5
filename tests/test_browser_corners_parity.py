"""drag_homography's browser arithmetic (camlab/widgets/browser/corners.js) equals its numpy twins.

The corners text (parse and format, with parse_corners' messages), the corner sliders' convex clamp,
the homography of four corners (against camlab.homography.estimate_homography, at 1e-9 relative, and
its DegenerateError messages) and the table of what H keeps, on random corners under node.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from test_browser_geometry_parity import CASES, NODE, assert_twins, run_js

from camlab import homography as hg
from camlab._validate import DegenerateError
from camlab.widgets.controls import convex_clamp, convex_margin, format_corners, parse_corners
from camlab.widgets.homographies.corner_twins import drag_measures
from camlab.widgets.homographies.geometry import SLIDER_MARGIN_PX, SQUARE

CORNERS = Path(__file__).resolve().parent.parent / "camlab" / "widgets" / "browser" / "corners.js"

pytestmark = pytest.mark.skipif(
    NODE is None, reason="node is not installed: the JavaScript twins cannot be run"
)

LINE = np.array([[10.0, 10.0], [50.0, 40.0], [90.0, 70.0], [140.0, 107.5]])


def _corners(rng: np.random.Generator) -> list[np.ndarray]:
    """Corners on the sliders' whole pixels and dragged ones anywhere: convex, dented, bow ties, torn."""
    out = [np.round(rng.uniform([0, 0], [299, 259], (4, 2))) for _ in range(CASES // 2)]
    out += [rng.uniform([-50, -50], [350, 300], (4, 2)) for _ in range(CASES // 2)]
    return out + [
        np.array([[40.0, 30.0], [250.0, 60.0], [230.0, 200.0], [60.0, 230.0]]),
        np.array([[20.0, 20.0], [280.0, 20.0], [280.0, 230.0], [20.0, 230.0]]),
        np.array([[100.0, 40.0], [200.0, 40.0], [280.0, 230.0], [20.0, 230.0]]),
    ]


def _parsed(text: str) -> dict:
    try:
        return {"corners": parse_corners(text).tolist()}
    except ValueError as exc:
        return {"error": str(exc)}


def test_the_corners_text_reads_and_writes_as_the_controls_do():
    rng = np.random.default_rng(81)
    pts = _corners(rng)
    texts = [format_corners(p) for p in pts]
    texts += [
        "1, 2; 3, 4; 5, 6",  # three corners
        "1, 2; 3, 4; 5, 6; 7, x",  # a word
        " 1.5 ,2; 3e2, 4; +.5, 60; 7_0, 8 ;",  # Python's float forms, a trailing ';'
        "1, 2; 3, 4; 5, 6; 1.3, 2.4",  # two corners less than 1 px apart
        "1, 2; 3, 4; 5, 6; 2e6, -7",  # far off
        "1, 2; 3, 4; nan, 6; 7, 8",
        "1, 2, 3; 4, 5; 6, 7; 8, 9",
    ]
    out = run_js(
        [("formatCorners", [p.tolist()]) for p in pts] + [("parseCorners", [t]) for t in texts],
        CORNERS,
    )
    assert out[: len(pts)] == texts[: len(pts)]
    for js, text in zip(out[len(pts) :], texts, strict=True):
        py = _parsed(text)
        assert js.keys() == py.keys(), (text, js, py)
        if "error" in py:
            assert js["error"] == py["error"]
        else:
            assert_twins(js["corners"], py["corners"], f"parseCorners({text!r})")
    assert sum("error" in _parsed(t) for t in texts) >= 6, "not every kind of slip was tried"


def test_the_convex_clamp_stops_a_slider_as_the_kernel_does():
    rng = np.random.default_rng(82)
    clamp = convex_clamp(SLIDER_MARGIN_PX)
    cases = [
        (p, int(rng.integers(4)), np.round(rng.uniform([0, 0], [299, 259]))) for p in _corners(rng)
    ]
    calls = [("convexMargin", [p.tolist()]) for p, _, _ in cases]
    calls += [("convexClamp", [SLIDER_MARGIN_PX, p.tolist(), k, w.tolist()]) for p, k, w in cases]
    out = run_js(calls, CORNERS)
    n = len(cases)
    stopped = 0
    for js_margin, js_clamp, (p, k, w) in zip(out[:n], out[n:], cases, strict=True):
        margin = convex_margin(p)
        assert js_margin == margin or abs(js_margin - margin) <= 1e-9 * abs(margin)
        py = clamp(p, k, w)
        assert np.array_equal(js_clamp, py), (p, k, w, js_clamp, py)
        stopped += not np.array_equal(py, w)
    assert stopped >= 5, f"only {stopped} slider moves were stopped short of a dent"


def test_four_corners_give_estimate_homographys_h_and_its_errors():
    rng = np.random.default_rng(83)
    pts = _corners(rng)
    pts += [
        np.array([[0.0, 0.0], [100.0, 100.0], [200.0, 200.0], [50.0, 220.0]]),  # 3 collinear
        np.array([[0.0, 0.0], [100.0, 0.0], [200.0, 0.0], [300.0, 0.0]]),  # all collinear
    ]
    out = run_js([("homographyFromCorners", [SQUARE.tolist(), p.tolist()]) for p in pts], CORNERS)
    worst, errors = 0.0, 0
    for js, p in zip(out, pts, strict=True):
        try:
            H = hg.estimate_homography(SQUARE, p)
        except DegenerateError as exc:
            assert js == {"error": str(exc)}
            errors += 1
            continue
        worst = max(worst, assert_twins(js["H"], H, f"homographyFromCorners({p.tolist()})"))
    assert errors >= 2
    print(f"homographyFromCorners: worst relative error {worst:.2e}")


def test_the_table_of_what_h_keeps_equals_the_demos():
    rng = np.random.default_rng(84)
    calls, expected = [], []
    for p in _corners(rng):
        try:
            H = hg.estimate_homography(SQUARE, p)
        except DegenerateError:
            continue
        m = (np.c_[LINE, np.ones(4)] @ H.T)[:, :2] / (np.c_[LINE, np.ones(4)] @ H[2])[:, None]
        expected.append(drag_measures(LINE, m, H, SQUARE))
        calls.append(("dragMeasures", [LINE.tolist(), m.tolist(), H.tolist(), SQUARE.tolist()]))
    worst, verdicts = 0.0, set()
    for js, (measures, rows) in zip(run_js(calls, CORNERS), expected, strict=True):
        assert [tuple(r) for r in js["rows"]] == rows
        for key, value in measures.items():
            if np.isinf(value):  # a segment through infinity
                assert float(js["measures"][key]) == value, key
                continue
            worst = max(worst, assert_twins([float(js["measures"][key])], [value], key))
        verdicts.update(r[3] + r[0] for r in rows)
    assert {
        "keptcross-ratio",
        "changes|AD| (px)",
        "kept|AB| / |CD|",
        "changes|AB| / |CD|",
    } <= verdicts
    print(f"dragMeasures: worst relative error {worst:.2e}")


def _drag_fixed() -> dict:
    from camlab.widgets.homographies.geometry import _drag_fixed

    return _drag_fixed((120, 160, 3), (260, 300))


def test_the_drag_view_equals_the_demos():
    """dragView: H, the tear, the line sent to infinity, A'..D', the mapped line and outline at 1e-9,
    the table's rows and the names' places exactly, and the error of corners that cannot be used."""
    from camlab.widgets.homographies.corner_twins import drag_view

    rng = np.random.default_rng(85)
    fixed = _drag_fixed()
    texts = [format_corners(p) for p in _corners(rng)]
    texts += [
        "1, 2; 3, 4; 5, 6",
        "0, 0; 100, 100; 200, 200; 50, 220",
        "40, 30; 40.5, 30; 230, 200; 60, 230",
    ]
    jsfixed = {k: np.asarray(v).tolist() for k, v in fixed.items()}
    out = run_js([("dragView", [{"corners": t}, jsfixed]) for t in texts], CORNERS)
    worst, torn, hidden, errors = 0.0, 0, 0, 0
    for js, text in zip(out, texts, strict=True):
        py = drag_view({"corners": text}, fixed)
        if py.error is not None:
            assert js["error"] == py.error
            errors += 1
            continue
        for key in ("corners", "H", "away", "mapped", "dense", "outline"):
            worst = max(worst, assert_twins(js[key], getattr(py, key), f"dragView {key}"))
        assert js["torn"] == py.torn
        assert [tuple(r) for r in js["measures"]["rows"]] == py.measures.rows
        assert js["names"]["visible"] == py.names.visible.tolist(), text
        worst = max(worst, assert_twins(js["names"]["offsets"], py.names.offsets, "name offsets"))
        torn += py.torn
        hidden += int((~py.names.visible).sum())
    assert errors == 3 and torn >= 5 and hidden >= 5, (errors, torn, hidden)
    print(f"dragView: worst relative error {worst:.2e}")


def test_a_corner_slider_writes_the_corners_as_the_kernel_does():
    """cornerSlid: the corners text a slider move gives (the kernel's corner_keys with convex_clamp),
    and the text and table of the error note wrapped as textwrap wraps them."""
    import textwrap

    from camlab.widgets.controls import corner_keys, corner_text
    from camlab.widgets.homographies.corner_twins import drag_table_text, drag_view

    rng = np.random.default_rng(86)
    control = corner_text(format_corners(SQUARE), "corners")
    keys = corner_keys(control, "abcd", 299, 259, clamp=convex_clamp(SLIDER_MARGIN_PX))
    calls, expected = [], []
    for p in _corners(rng)[:60]:
        k, name = int(rng.integers(4)), ("corner_u", "corner_v")[int(rng.integers(2))]
        value = float(np.round(rng.uniform(0, 259)))
        control.value = format_corners(p)
        keys["corner"].value = k
        before = control.value
        keys[name].value = value
        calls.append(("cornerSlid", [before, k, name, value, SLIDER_MARGIN_PX]))
        expected.append(None if control.value == before else control.value)
    messages = [
        drag_view({"corners": t}, _drag_fixed()).error
        for t in ("1, 2; 3", "0, 0; 100, 100; 200, 200; 9, 9")
    ]
    messages.append("x" * 70 + " and then some more words to wrap at fifty-five, the width")
    calls += [("wrapText", [m, 55]) for m in messages]
    rows = [
        drag_view({"corners": format_corners(p)}, _drag_fixed()).measures.rows
        for p in _corners(rng)[:5]
    ]
    calls += [("dragTableText", [r]) for r in rows]
    out = run_js(calls, CORNERS)
    n, m = len(expected), len(messages)
    assert out[:n] == expected
    assert sum(e is not None for e in expected) >= 30
    assert out[n : n + m] == [textwrap.wrap(msg, 55) for msg in messages]
    assert out[n + m :] == [drag_table_text(r) for r in rows]


def test_the_browser_keeps_the_corner_controls_in_step_as_the_kernel_does():
    """followDrag (drag.js; the kernel's sync is off when the browser draws the demo): after a slider
    move, a new text or another corner picked, the text and the two sliders equal corner_keys'."""
    from camlab.widgets.controls import corner_keys, corner_text

    drag = CORNERS.with_name("drag.js")
    rng = np.random.default_rng(87)
    control = corner_text(format_corners(SQUARE), "corners")
    keys = corner_keys(control, "abcd", 299, 259, clamp=convex_clamp(SLIDER_MARGIN_PX))
    u, v, pick = keys["corner_u"], keys["corner_v"], keys["corner"]
    scene = {"margin": SLIDER_MARGIN_PX}
    calls, expected = [], []
    corners = _corners(rng)
    for i, p in enumerate(corners[:90]):
        control.value = format_corners(p)
        pick.value = int(rng.integers(4))
        before = dict(corners=control.value, corner=pick.value, corner_u=u.value, corner_v=v.value)
        kind = ("corner_u", "corner_v", "corners", "corner")[i % 4]
        new = {
            "corners": format_corners(corners[i + 1]),
            "corner": (pick.value + 1 + int(rng.integers(3))) % 4,
        }.get(kind, float(np.round(rng.uniform(0, 259))))
        moved = dict(before, **{kind: new})  # what the browser has when the control moved
        keys.get(kind, control).value = new  # the kernel's sync (a stopped slider snaps back)
        calls.append(("followDrag", [scene, kind, moved]))
        expected.append((moved, dict(corners=control.value, corner_u=u.value, corner_v=v.value)))
    out = run_js(calls, drag)
    changed = 0
    for js, (moved, kernel) in zip(out, expected, strict=True):
        after = dict(moved, **(js or {}))
        assert {k: after[k] for k in kernel} == kernel, (moved, js, kernel)
        changed += js is not None
    assert changed >= 60, f"only {changed} of {len(out)} changes moved another control"
