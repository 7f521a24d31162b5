"""Update latency of every registered demo: callback plus Agg draw, per slider change.

Each demo is driven through its registered sweep (every control, every value, cycled) with
the Agg backend and the same blitting path the lessons use under ipympl. A second pair of
columns repeats the sweep with ipympl's canvas as a connected browser sees it, so it also
counts encoding the PNG diff that goes to the browser. Targets on the
2-core course machine: median <= 30 ms and p95 <= 60 ms, or the demo's registered
`target_ms` (image demos, set by their issue).

Usage: python benchmarks/latency.py [--rounds N] [demo names...]
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time

os.environ["MPLBACKEND"] = "module://ipympl.backend_nbagg"  # pyplot backend for the ipympl column

import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(__file__))
from _timing import print_table  # noqa: E402

def _build(spec, mode: str):
    """Build a demo in ``mode``; for ipympl, act as a connected browser would."""
    os.environ["CAMLAB_FIGURE_MODE"] = mode
    demo = spec.builder()
    if mode == "ipympl":
        canvas = demo.figure.canvas
        canvas.syncing_data_url = False  # a live front end receives diffs, not full data URLs
        canvas.draw()  # the browser's first full draw, which captures the blitting background
    return demo


def _sweep_ms(demo, spec, rounds: int) -> np.ndarray:
    steps = [(k, v) for k, values in spec.sweep.items() for v in values]
    times = []
    for _ in range(rounds):
        for key, value in steps:
            if demo.controls[key].value == value:
                continue
            t0 = time.perf_counter()
            demo.set(**{key: value})
            times.append(time.perf_counter() - t0)
    return np.array(times) * 1e3


def demo_latency(spec, rounds: int) -> dict:
    """Median and p95 per update: Agg (callback + draw) and ipympl (+ the PNG diff sent to the browser)."""
    agg = _sweep_ms(_build(spec, "agg"), spec, rounds)
    web = _sweep_ms(_build(spec, "ipympl"), spec, rounds)
    target = spec.target_ms
    median, p95 = float(np.median(agg)), float(np.percentile(agg, 95))
    return {"lesson": spec.lesson, "demo": spec.name, "updates": len(agg), "median_ms": median, "p95_ms": p95,
            "ipympl_median_ms": float(np.median(web)), "ipympl_p95_ms": float(np.percentile(web, 95)),
            "target": f"median <= {target:g}, p95 <= {2 * target:g}", "ok": median <= target and p95 <= 2 * target}


def import_time() -> float:
    """Seconds for `python -c "import camlab"` in a fresh interpreter (best of 5)."""
    best = np.inf
    for _ in range(5):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", "import camlab"], check=True)
        best = min(best, time.perf_counter() - t0)
    return best


def rows(rounds: int = 5, names: list[str] | None = None) -> list[dict]:
    from camlab.widgets import all_demos

    demos = all_demos()
    return [demo_latency(demos[n], rounds) for n in sorted(demos, key=lambda n: (demos[n].lesson, n))
            if not names or n in names]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("names", nargs="*")
    args = parser.parse_args()
    print_table(rows(args.rounds, args.names), ["lesson", "demo", "updates", "median_ms", "p95_ms", "target", "ok",
                                        "ipympl_median_ms", "ipympl_p95_ms"],
                "Demo update latency (callback + draw, Agg)")
    t = import_time()
    print(f"\n`python -c \"import camlab\"`: {t:.3f} s (target <= 0.3 s): {'ok' if t <= 0.3 else 'TOO SLOW'}")


if __name__ == "__main__":
    main()
