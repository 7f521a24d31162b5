"""Input to pixels in a real browser: one demo per lesson in JupyterLab, headless Chromium.

For each lesson the first registered demo that has a slider is built in a scratch notebook
under ``%matplotlib widget``. The benchmark focuses the slider's handle, presses an arrow key
and times, inside the page, from the keydown event to the first animation frame in which
the demo's canvas pixels differ: the kernel's callback and draw, ipympl's PNG diff, the
websocket, and the browser's decode and paint, as a student's eye would see it.

Demos drawn in the browser (``camlab/widgets/browser``) are timed the same way; the table says
which path drew each demo ("browser" or "kernel"). ``--demos`` times the named demos and ``--all``
every demo with a slider, instead of one per lesson; ``--kernel-path`` switches browser drawing off
(``CAMLAB_BROWSER_DRAWING=0``), to compare the two paths on the same demo.

Usage: python benchmarks/browser_latency.py [--presses N] [--demos a,b | --all] [--kernel-path]
(``make bench-browser``)
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tools"))
sys.path.insert(0, str(HERE))
import browser  # noqa: E402
from _timing import print_table  # noqa: E402

# Before JupyterLab loads: timestamp every websocket message the page receives while armed.
WATCH_WEBSOCKETS = """(() => {
  window.__camlabFrames = [];
  const add = WebSocket.prototype.addEventListener;
  const watch = (ws) => {
    if (ws.__camlabWatched) return;
    ws.__camlabWatched = true;
    add.call(ws, 'message', (e) => {
      if (window.__camlabArmed) {
        const d = e.data;
        window.__camlabFrames.push([performance.now(), (d && (d.byteLength || d.size || d.length)) || 0]);
      }
    });
  };
  WebSocket.prototype.addEventListener = function (type, fn, opts) { watch(this); return add.call(this, type, fn, opts); };
  const onmessage = Object.getOwnPropertyDescriptor(WebSocket.prototype, 'onmessage');
  Object.defineProperty(WebSocket.prototype, 'onmessage', {
    set(fn) { watch(this); onmessage.set.call(this, fn); }, get() { return onmessage.get.call(this); } });
})();"""


def stages(sample: dict) -> dict[str, float]:
    """Split one press into its path: the server round trip, the figure frame's arrival, its paint.

    ``reply_ms``: keydown to the kernel's first message back (its "busy" status): the
    websocket, Jupyter server and ZMQ round trip that every kernel interaction pays.
    ``frame_ms``: keydown to the largest message before the pixels changed, the PNG diff
    (callback, draw and encode in the kernel happen between reply and frame).
    ``pixels_ms``: keydown to the first animation frame whose canvas pixels differ (the
    browser decoded the PNG and drew it).
    A browser-drawn demo changes its pixels before any message arrives: its reply and frame are
    NaN (nothing waited for the kernel).
    """
    frames = [(t, n) for t, n in sample["frames"] if t <= sample["pixels"]]
    if sample["pixels"] < 0:
        return {"pixels_ms": float("nan"), "reply_ms": float("nan"), "frame_ms": float("nan")}
    if not frames:
        return {"pixels_ms": sample["pixels"], "reply_ms": float("nan"), "frame_ms": float("nan")}
    return {
        "pixels_ms": sample["pixels"],
        "reply_ms": frames[0][0],
        "frame_ms": max(frames, key=lambda f: f[1])[0],
    }


def slider_demos(every: bool = False) -> dict[str, str]:
    """Per lesson, the first registered demo (by name) whose controls include an enabled slider.

    With ``every``, all such demos, keyed by name (``--all``: the per-demo table issue 31 asks for).
    """
    os.environ["CAMLAB_FIGURE_MODE"] = "agg"
    import ipywidgets as W
    import matplotlib.pyplot as plt

    from camlab.widgets import all_demos

    chosen: dict[str, str] = {}
    specs = all_demos()
    for name in sorted(specs, key=lambda n: (specs[n].lesson, n)):
        spec = specs[name]
        if spec.lesson in chosen and not every:
            continue
        demo = spec.builder()
        if any(
            isinstance(c, (W.FloatSlider, W.IntSlider)) and not c.disabled
            for c in demo.controls.values()
        ):
            chosen[name if every else spec.lesson] = name
        plt.close(demo.figure)
    return chosen


def _notebook(names: list[str]) -> dict:
    cells = ["%matplotlib widget\nfrom camlab.widgets import all_demos\nspecs = all_demos()"]
    cells += [f"specs[{n!r}].builder()" for n in names]
    return {
        "nbformat": 4,
        "nbformat_minor": 5,
        "metadata": {
            "kernelspec": {"name": "python3", "display_name": "Python 3", "language": "python"}
        },
        "cells": [
            {
                "cell_type": "code",
                "metadata": {},
                "source": c,
                "outputs": [],
                "execution_count": None,
                "id": f"c{i}",
            }
            for i, c in enumerate(cells)
        ],
    }


def measure(
    presses: int = 7, demos: list[str] | None = None, every: bool = False
) -> dict[str, dict]:
    """Median milliseconds of each stage (see :func:`stages`), the p95 of pixels and the path, per demo.

    ``demos`` names the demos to time; None takes one per lesson, or every slider demo with
    ``every`` (:func:`slider_demos`).
    """
    from playwright.sync_api import sync_playwright

    chosen = {n: n for n in demos} if demos else slider_demos(every)
    with tempfile.TemporaryDirectory() as tmp:
        base = Path(tmp)
        (base / "root").mkdir()
        (base / "root" / "latency.ipynb").write_text(json.dumps(_notebook(list(chosen.values()))))
        results: dict[str, float] = {}
        with browser.jupyterlab(base / "root", base) as lab, sync_playwright() as p:
            context = browser.launch(p, lab["profile"])
            context.add_init_script(WATCH_WEBSOCKETS)
            try:
                page = context.new_page()
                page.set_default_timeout(180_000)
                browser.run_notebook(page, lab, "latency.ipynb")
                page.wait_for_function(browser.ALL_CELLS_RUN, polling=500)
                for name in chosen.values():
                    selector = f".camlab-demo-{name.replace('_', '-')}"
                    demo = page.locator(selector)
                    demo.scroll_into_view_if_needed()
                    demo.locator("canvas").first.wait_for(state="visible")
                    page.wait_for_timeout(1500)  # the first full frame
                    handle = demo.locator(".widget-slider:not(.mod-disabled) .noUi-handle").first
                    samples = []
                    for i in range(presses):
                        handle.focus()
                        page.evaluate(
                            browser.ARM_KEY_TO_CANVAS, f"{selector} canvas"
                        )  # never awaits
                        page.keyboard.press("ArrowRight" if i % 2 == 0 else "ArrowLeft")
                        page.wait_for_function(
                            "() => window.__camlabLatency !== undefined", polling=50
                        )
                        samples.append(stages(page.evaluate("() => window.__camlabLatency")))
                        page.wait_for_timeout(300)
                    results[name] = {
                        k: float(np.nanmedian([s[k] for s in samples])) for k in samples[0]
                    }
                    results[name]["pixels_p95"] = float(
                        np.nanpercentile([s["pixels_ms"] for s in samples], 95)
                    )
                    browser_drawn = demo.locator("canvas.camlab-browser-canvas").count() > 0
                    results[name]["path"] = "browser" if browser_drawn else "kernel"
            finally:
                context.close()
    return results


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--presses", type=int, default=7)
    parser.add_argument(
        "--demos", default="", help="comma-separated demo names (default: one per lesson)"
    )
    parser.add_argument(
        "--all", action="store_true", help="every demo with a slider, not one per lesson"
    )
    parser.add_argument("--kernel-path", action="store_true", help="draw every demo in the kernel")
    args = parser.parse_args()
    if args.kernel_path:
        os.environ["CAMLAB_BROWSER_DRAWING"] = "0"  # the kernel JupyterLab starts inherits it
    from camlab.widgets import all_demos

    specs = all_demos()
    measured = measure(args.presses, [d for d in args.demos.split(",") if d] or None, args.all)
    rows = [{"lesson": specs[n].lesson, "demo": n, **ms} for n, ms in measured.items()]
    print_table(
        rows,
        ["lesson", "demo", "path", "pixels_ms", "pixels_p95", "reply_ms", "frame_ms"],
        "Slider keydown to changed canvas pixels, JupyterLab in headless Chromium (median; see stages())",
    )


if __name__ == "__main__":
    main()
