"""Timing and table helpers shared by the benchmark scripts."""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np


def timed(fn: Callable[[], Any]) -> tuple[Any, float]:
    """``(fn(), seconds)``: one timed call that keeps its result (interleaved comparisons that also score it)."""
    t0 = time.perf_counter()
    value = fn()
    return value, time.perf_counter() - t0


def time_calls(fn: Callable[[], Any], repeat: int = 20, warmup: int = 2) -> np.ndarray:
    """Wall-clock seconds of ``repeat`` calls of ``fn`` after ``warmup`` untimed calls."""
    for _ in range(warmup):
        fn()
    out = np.empty(repeat)
    for i in range(repeat):
        t0 = time.perf_counter()
        fn()
        out[i] = time.perf_counter() - t0
    return out


def median_ms(fn: Callable[[], Any], repeat: int = 20, warmup: int = 2) -> float:
    """Median wall-clock milliseconds of ``repeat`` calls of ``fn`` (after ``warmup`` untimed calls)."""
    return float(np.median(time_calls(fn, repeat, warmup)) * 1e3)


def paired_ms(
    ours: Callable[[], Any], ref: Callable[[], Any], repeat: int = 25
) -> tuple[float, float]:
    """Median milliseconds of two functions timed alternately, so both see the same machine load
    (the 2-core machines these run on are shared; sequential blocks drift apart)."""
    ours(), ref()
    a, b = [], []
    for _ in range(repeat):
        t = time.perf_counter()
        ours()
        a.append(time.perf_counter() - t)
        t = time.perf_counter()
        ref()
        b.append(time.perf_counter() - t)
    return float(np.median(a) * 1e3), float(np.median(b) * 1e3)


def ratio_row(
    case: str,
    camlab_fn: Callable[[], Any],
    opencv_fn: Callable[[], Any],
    target: float,
    repeat: int = 20,
) -> dict:
    """Time camlab against OpenCV in one run; ``ok`` if camlab is within ``target`` x OpenCV."""
    c, o = median_ms(camlab_fn, repeat), median_ms(opencv_fn, repeat)
    return {
        "case": case,
        "camlab_ms": c,
        "opencv_ms": o,
        "ratio": c / o,
        "target": f"<= {target:g}x",
        "ok": c / o <= target,
    }


def print_table(
    rows: Sequence[dict], columns: Sequence[str] | None = None, title: str = ""
) -> None:
    """Print rows as a Markdown table (floats with 2 decimals); ``columns`` default to the first row's keys."""
    columns = list(rows[0]) if columns is None else columns

    def fmt(v: Any) -> str:
        if isinstance(v, (bool, np.bool_)):
            return "yes" if v else "NO"
        if isinstance(v, (float, np.floating)):
            return f"{v:.2f}"
        return str(v)

    if title:
        print(f"\n### {title}\n")
    print("| " + " | ".join(columns) + " |")
    print("|" + "---|" * len(columns))
    for row in rows:
        print("| " + " | ".join(fmt(row.get(c, "")) for c in columns) + " |")
