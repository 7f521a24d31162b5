"""Update latency of every registered demo as the browser receives it.

Each demo is built with ipympl's canvas acting as a connected front end (first full draw
done, diffs rather than data URLs) and driven through its registered sweep: every control,
every value, cycled. One update is the whole path a student feels before the browser can
paint: the control's callback (compute), the Agg redraw (draw) and the PNG diff of the
changed pixels that ipympl encodes and sends (encode). The headline column is that total;
the target is the same for every demo: median <= 33 ms and p95 <= 66 ms (two and four
frames at 60 Hz) on the 2-core course machine. ``cpu_median_ms`` is the same update in
this thread's CPU time, which stays honest when other work shares the machine (wall time
then includes waiting for a core). The stage columns say where the
milliseconds go; the Agg column repeats the sweep without a browser (tests' path).

``--browser`` adds the real-browser columns (see ``browser_latency.py``) for one demo per
lesson: slider keydown to changed canvas pixels in JupyterLab under headless Chromium, and
the part of it that is the server round trip every kernel message pays (keydown to the
kernel's first reply), which no demo can make faster.

Usage: python benchmarks/latency.py [--rounds N] [--browser] [demo names...]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time

os.environ["MPLBACKEND"] = "module://ipympl.backend_nbagg"  # pyplot backend for the ipympl path

import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(__file__))
from _timing import print_table  # noqa: E402

TARGET_MEDIAN_MS, TARGET_P95_MS = 33.0, 66.0


def _build(spec, mode: str):
    """Build a demo in ``mode``; for ipympl, act as a connected browser would."""
    os.environ["CAMLAB_FIGURE_MODE"] = mode
    demo = spec.builder()
    if mode == "ipympl":
        canvas = demo.figure.canvas
        canvas.syncing_data_url = False  # a live front end receives diffs, not full data URLs
        canvas.draw()  # the browser's first full draw, which captures the blitting background
    return demo


class _Stages:
    """Wrap a built ipympl demo so each update's compute, draw and encode are timed apart."""

    def __init__(self, demo):
        self.compute, self.draw, self.encode = [], [], []
        view, canvas = demo.view, demo.figure.canvas
        refresh, diff = view.refresh, canvas.get_diff_image
        self._t_refresh = 0.0

        def timed_refresh():
            t0 = time.perf_counter()
            self._t_refresh = t0
            refresh()

        def timed_diff():
            t0 = time.perf_counter()
            out = diff()
            self.encode.append(time.perf_counter() - t0)
            self.draw.append(t0 - self._t_refresh)
            return out

        view.refresh, canvas.get_diff_image = timed_refresh, timed_diff


def _sweep_ms(demo, spec, rounds: int, stages: _Stages | None = None) -> np.ndarray:
    steps = [(k, v) for k, values in spec.sweep.items() for v in values]
    times, cpu = [], []
    for _ in range(rounds):
        for key, value in steps:
            if demo.controls[key].value == value:
                continue
            t0, c0 = time.perf_counter(), time.thread_time()
            demo.set(**{key: value})
            times.append(time.perf_counter() - t0)
            cpu.append(time.thread_time() - c0)
            if stages is not None:
                stages.compute.append(stages._t_refresh - t0)
    return np.array(times) * 1e3, np.array(cpu) * 1e3


def demo_latency(spec, rounds: int) -> dict:
    """Median and p95 per update on the ipympl path, the stage medians, and the Agg-only median."""
    import matplotlib.pyplot as plt

    agg, _ = _sweep_ms(_build(spec, "agg"), spec, rounds)
    web_demo = _build(spec, "ipympl")
    stages = _Stages(web_demo)
    web, cpu = _sweep_ms(web_demo, spec, rounds, stages)
    plt.close(web_demo.figure)  # pyplot keeps ipympl figures alive until closed
    median, p95 = float(np.median(web)), float(np.percentile(web, 95))

    def stage(values):
        return float(np.median(values) * 1e3) if values else float("nan")

    return {
        "lesson": spec.lesson,
        "demo": spec.name,
        "updates": len(web),
        "median_ms": median,
        "p95_ms": p95,
        "ok": median <= TARGET_MEDIAN_MS and p95 <= TARGET_P95_MS,
        "compute_ms": stage(stages.compute),
        "draw_ms": stage(stages.draw),
        "encode_ms": stage(stages.encode),
        "cpu_median_ms": float(np.median(cpu)),
        "agg_median_ms": float(np.median(agg)),
    }


IMPORT_TARGET_S = 0.2  # issue 32: `import camlab` in a fresh interpreter


def import_time(runs: int = 7) -> tuple[float, float]:
    """Seconds for `python -c "import camlab"` in a fresh interpreter: (median, best) of ``runs``.

    The interpreter's own start-up (about 0.03 s here) is included, as a student's first cell pays it.
    """
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", "import camlab"], check=True)
        times.append(time.perf_counter() - t0)
    return float(np.median(times)), float(min(times))


def rows(rounds: int = 5, names: list[str] | None = None) -> list[dict]:
    from camlab.widgets import all_demos

    demos = all_demos()
    return [
        demo_latency(demos[n], rounds)
        for n in sorted(demos, key=lambda n: (demos[n].lesson, n))
        if not names or n in names
    ]


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument(
        "--browser", action="store_true", help="add the real-browser column (headless Chromium)"
    )
    parser.add_argument("names", nargs="*")
    args = parser.parse_args(argv)
    table = rows(args.rounds, args.names)
    columns = [
        "lesson",
        "demo",
        "updates",
        "median_ms",
        "p95_ms",
        "ok",
        "compute_ms",
        "draw_ms",
        "encode_ms",
        "cpu_median_ms",
        "agg_median_ms",
    ]
    if args.browser:
        import browser_latency

        measured = browser_latency.measure()
        for row in table:
            stages = measured.get(row["demo"], {})
            row["browser_ms"] = stages.get("pixels_ms", "")
            row["browser_reply_ms"] = stages.get("reply_ms", "")
        columns += ["browser_ms", "browser_reply_ms"]
    print_table(
        table,
        columns,
        f"Demo update latency as the browser receives it (ipympl path; target median <= "
        f"{TARGET_MEDIAN_MS:g} ms, p95 <= {TARGET_P95_MS:g} ms)",
    )
    missed = [r["demo"] for r in table if not r["ok"]]
    medians = [r["median_ms"] for r in table]
    print(
        f"\n{len(table) - len(missed)} of {len(table)} demos within target; median of medians "
        f"{np.median(medians):.1f} ms" + (f"; missed: {', '.join(missed)}" if missed else "")
    )
    median, best = import_time()
    verdict = "ok" if median <= IMPORT_TARGET_S else "TOO SLOW"
    print(
        f'\n`python -c "import camlab"`: median {median:.3f} s, best {best:.3f} s of 7'
        f" (target <= {IMPORT_TARGET_S} s on the median): {verdict}"
    )


if __name__ == "__main__":
    main()
