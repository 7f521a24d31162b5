"""A class on one machine: N students run lessons at once through a real JupyterHub.

Prints the sizing table of docs/teaching.md. Per lesson, over the students: the kernel's peak
memory (``getrusage`` max RSS, MB) and CPU-seconds (user + system, all threads and child
processes) to run the lesson top to bottom, and the wall seconds it took with N students at
once. ``--drag DEMO`` then has every student drag DEMO's controls at the same moment, inside
their own kernel (benchmarks/latency.py's sweep: compute, Agg draw and ipympl's PNG encode per
update), and prints the update latency against the course target (median <= 33 ms).

Usage: python benchmarks/class_load.py [--students N] [--drag DEMO] [--rounds R] [--no-lessons] [LESSON ...]
(``make class-load N=8 LESSONS="06 07"``). Needs configurable-http-proxy: ``make hub-deps``.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "tools"))
import classhub  # noqa: E402
from _timing import print_table  # noqa: E402
from latency import TARGET_MEDIAN_MS, TARGET_P95_MS  # noqa: E402

DRAG = """import json, sys
sys.path.insert(0, {bench!r})
import latency
from camlab.widgets import all_demos
print("camlab-hub-drag", json.dumps(latency.demo_latency(all_demos()[{demo!r}], {rounds})))
"""


def lesson_table(rows: list[dict]) -> list[dict]:
    table = []
    for lesson in dict.fromkeys(r["lesson"] for r in rows):
        mine = [r for r in rows if r["lesson"] == lesson]
        ok = [r for r in mine if not r["errors"]]
        peak, cpu, wall = (
            np.array([r.get(k, np.nan) for r in ok]) for k in ("peak_mb", "cpu_s", "wall_s")
        )
        table.append(
            {
                "lesson": lesson,
                "students": len(mine),
                "ran_ok": len(ok),
                "peak_MB_median": np.median(peak),
                "peak_MB_max": peak.max(),
                "cpu_s_median": np.median(cpu),
                "wall_s_median": np.median(wall),
                "wall_s_max": wall.max(),
            }
        )
    return table


async def drag_all(hub, tokens: dict[str, str], demo: str, rounds: int) -> list[dict]:
    """Every student drags ``demo`` at once, each in their own kernel; one latency row per student."""

    async def one(name: str) -> dict:
        await classhub.api(
            f"{hub.url}/user/{name}/api/contents/drag.ipynb",
            tokens[name],
            "PUT",
            {
                "type": "notebook",
                "content": {"cells": [], "metadata": {}, "nbformat": 4, "nbformat_minor": 5},
            },
        )
        async with classhub.kernel(hub, name, tokens[name], "drag.ipynb") as run:
            await run("%matplotlib widget")
            status, out = await run(DRAG.format(bench=str(HERE), demo=demo, rounds=rounds))
        found = classhub.printed(out, "camlab-hub-drag")
        if status != "ok" or found is None:
            raise RuntimeError(f"{name}: the drag sweep failed: {out}")
        return {"student": name, **json.loads(found)}

    return await asyncio.gather(*(one(n) for n in tokens))


async def session(hub, n: int, lessons: list[Path], demo: str | None, rounds: int):
    names = [f"student{i:02d}" for i in range(1, n + 1)]
    t0 = time.perf_counter()
    tokens, rows = await classhub.run_class(hub, names, lessons)
    t_lessons = time.perf_counter() - t0
    servers = classhub.server_rss_mb(hub)
    drags = await drag_all(hub, tokens, demo, rounds) if demo else []
    return rows, t_lessons, servers, drags


def main(argv: list[str] | None = None) -> int:
    from camlab.classroom.lessons import find_lesson, lesson_files

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--students", type=int, default=8)
    parser.add_argument(
        "--drag",
        metavar="DEMO",
        help="then every student drags this demo at once, e.g. transformation_hierarchy",
    )
    parser.add_argument(
        "--rounds", type=int, default=2, help="sweeps of the demo's controls per student"
    )
    parser.add_argument(
        "--no-lessons", action="store_true", help="skip running lessons (only --drag)"
    )
    parser.add_argument("lessons", nargs="*", help="lesson numbers (default: all)")
    args = parser.parse_args(argv)
    lessons = [] if args.no_lessons else [find_lesson(s) for s in args.lessons] or lesson_files()
    with tempfile.TemporaryDirectory(prefix="camlab-class-") as base:
        t0 = time.perf_counter()
        with classhub.class_hub(Path(base) / "hub") as hub:
            t_hub = time.perf_counter() - t0
            rows, t_lessons, servers, drags = asyncio.run(
                session(hub, args.students, lessons, args.drag, args.rounds)
            )
    print(
        f"{args.students} students on one hub (JupyterHub, SimpleLocalProcessSpawner, loopback); hub up in "
        f"{t_hub:.1f} s; servers started and {len(lessons)} lesson(s) run by every student in {t_lessons:.1f} s"
    )
    print(
        f"single-user server (without kernels): median {np.median(list(servers.values())):.0f} MB resident "
        f"({len(servers)} servers)"
    )
    failed = [r for r in rows if r["errors"]]
    if rows:
        print_table(
            lesson_table(rows),
            [
                "lesson",
                "students",
                "ran_ok",
                "peak_MB_median",
                "peak_MB_max",
                "cpu_s_median",
                "wall_s_median",
                "wall_s_max",
            ],
            f"Per lesson, {args.students} students at once: kernel peak memory, CPU-seconds, wall time",
        )
        total_cpu = sum(
            np.median([r["cpu_s"] for r in rows if r["lesson"] == lesson and "cpu_s" in r])
            for lesson in dict.fromkeys(r["lesson"] for r in rows)
        )
        print(f"\nwhole course, one student: {total_cpu:.0f} CPU-seconds (sum of lesson medians)")
    if drags:
        med = np.median([d["median_ms"] for d in drags])
        p95 = np.median([d["p95_ms"] for d in drags])
        cpu = np.median([d["cpu_median_ms"] for d in drags])
        ok = med <= TARGET_MEDIAN_MS and p95 <= TARGET_P95_MS
        print(
            f"\n{args.students} students dragging {args.drag} at once: update latency median {med:.1f} ms, "
            f"p95 {p95:.1f} ms (medians over students), CPU {cpu:.1f} ms per update; target median <= "
            f"{TARGET_MEDIAN_MS:g} ms, p95 <= {TARGET_P95_MS:g} ms: {'ok' if ok else 'MISSED'}"
        )
    for r in failed:
        print(f"FAILED: {r['student']} {r['lesson']}: {r['errors']}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
