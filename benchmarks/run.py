"""Every benchmark in one run: demo latency (ipympl path and real browser), import time,
camlab-versus-OpenCV speed ratios, robust estimation on hard real pairs against OpenCV's
RANSAC and MAGSAC (robust_ransac.py, 10 seeds: issue 32's worst-seed row), and the lessons'
wall time under nbval (lesson_times.py).

Each `benchmarks/speed_<topic>.py` provides `rows()` returning dicts with case, camlab_ms,
opencv_ms, ratio, target and ok; this script prints them all as tables.
"""

from __future__ import annotations

import importlib
import sys
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))

import latency  # noqa: E402
import lesson_times  # noqa: E402
import robust_ransac  # noqa: E402
from _timing import print_table  # noqa: E402


def main() -> int:
    latency.main(["--browser"])  # the ipympl table with the real-browser columns
    failed = []
    for path in sorted(HERE.glob("speed_*.py")):
        module = importlib.import_module(path.stem)
        rows = module.rows()
        print_table(
            rows,
            ["case", "camlab_ms", "opencv_ms", "ratio", "target", "ok"],
            f"{path.stem}: camlab vs OpenCV",
        )
        failed += [f"{path.stem}: {r['case']}" for r in rows if not r["ok"]]
    if failed:
        print("\nMissed targets:\n- " + "\n- ".join(failed))
    robust_ransac.main(["--only", "hard", "--seeds", "10"])  # issue 32: the worst of 10 seeds
    lesson_times.main([])  # last: 3 runs of every lesson, a few minutes
    return 0


if __name__ == "__main__":
    sys.exit(main())
