"""The lessons headless, as the test suite runs them: nbval with 2 workers, wall time per run.

Run: ``python benchmarks/lesson_times.py [--runs 3] [--workers 2] [--slowest 15] [--repo DIR]
[lessons ...]``. Each run is ``pytest -n 2 --dist loadfile --nbval-lax lessons/ --durations=0``
in a fresh process (one lesson per worker at a time, as ``make test`` runs them), with the
checkout's camlab first on ``PYTHONPATH`` and one BLAS thread per process (as the Makefile
sets). ``--repo`` runs another checkout's lessons with its camlab: alternate two branches to
compare them under the same machine load. The script prints the load average before each run
(the machine is shared: a busy machine slows every cell), each run's wall time and their
median against issue 32's target, and the CPU seconds of all the run's processes (less moved
by the load); then, as medians over the runs, each lesson's sum of cell times and the slowest
cells (nbval's "Cell N" counts code cells only). Not a timed test: a benchmark to read.
"""

from __future__ import annotations

import argparse
import os
import re
import resource
import subprocess
import sys
import time
from collections import defaultdict
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(HERE))

from _timing import print_table  # noqa: E402

TARGET_S = 60.0  # issue 32: the 13 lessons under nbval with 2 workers in <= 60 s
# pytest's --durations lines: "1.23s call     lessons/09_image_stitching.ipynb::Cell 20"
DURATION = re.compile(r"^([\d.]+)s (setup|call|teardown)\s+(\S+\.ipynb)::(Cell \d+)")


def one_run(lessons: list[str], workers: int, repo: Path = REPO) -> tuple[float, float, dict, str]:
    """One nbval run: wall and CPU seconds, {(lesson, cell): seconds of setup + call + teardown}, pytest's summary.

    The CPU seconds are every process's of the run (pytest, its workers, their kernels: all
    waited for, so counted in RUSAGE_CHILDREN): less moved by other processes than the wall time.
    """
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(repo), env.get("PYTHONPATH")]))
    cmd = [sys.executable, "-m", "pytest", "-q", "-n", str(workers), "--dist", "loadfile",
           "-p", "no:randomly", "-p", "no:cacheprovider", "--nbval-lax", "--durations=0", *lessons]  # fmt: skip
    t0, c0 = time.perf_counter(), _children_cpu()
    out = subprocess.run(cmd, cwd=repo, env=env, capture_output=True, text=True).stdout
    wall, cpu = time.perf_counter() - t0, _children_cpu() - c0
    cells: dict = defaultdict(float)
    for line in out.splitlines():
        if m := DURATION.match(line):
            cells[(Path(m[3]).stem, m[4])] += float(m[1])
    summary = next(
        (ln.strip("= ") for ln in reversed(out.splitlines()) if " in " in ln), "no summary"
    )
    return wall, cpu, dict(cells), summary


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument(
        "lessons", nargs="*", default=["lessons"], help="notebooks or folders (default: lessons)"
    )
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--slowest", type=int, default=15, help="how many of the slowest cells to list")
    ap.add_argument(
        "--repo", type=Path, default=REPO, help="the checkout to run (default: this one)"
    )
    args = ap.parse_args(argv)

    walls, runs, rows = [], [], []
    for k in range(args.runs):
        load = os.getloadavg()[0]
        wall, cpu, cells, summary = one_run(args.lessons, args.workers, args.repo.resolve())
        walls.append(wall)
        runs.append(cells)
        rows.append(
            {"run": k + 1, "load_before": load, "wall_s": wall, "cpu_s": cpu, "pytest": summary}
        )
    med = float(np.median(walls))
    rows.append(
        {
            "run": "median",
            "wall_s": med,
            "cpu_s": float(np.median([r["cpu_s"] for r in rows])),
            "pytest": f"target <= {TARGET_S:g} s: {'ok' if med <= TARGET_S else 'MISSED'}",
        }
    )
    print_table(
        rows,
        ["run", "load_before", "wall_s", "cpu_s", "pytest"],
        f"{args.repo.resolve().name}: the lessons under nbval, {args.workers} workers",
    )

    keys = sorted(set().union(*runs))
    cell_med = {key: float(np.median([r.get(key, 0.0) for r in runs])) for key in keys}
    per_lesson: dict = defaultdict(float)
    for (lesson, _), s in cell_med.items():
        per_lesson[lesson] += s
    print_table(
        [{"lesson": n, "cells_s": s} for n, s in sorted(per_lesson.items(), key=lambda x: -x[1])],
        title=f"each lesson's sum of cell times (median of {args.runs} runs; {args.workers} workers share the cores)",
    )
    if args.slowest > 0:  # --slowest 0 leaves the table out
        print_table(
            [
                {"lesson": n, "cell": c, "s": s}
                for (n, c), s in sorted(cell_med.items(), key=lambda x: -x[1])[: args.slowest]
            ],
            title=f"the {args.slowest} slowest cells (median of {args.runs} runs)",
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
