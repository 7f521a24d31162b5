"""The time limit on a student's function: a SIGALRM timer that stops an endless loop (where one can).

Used by :func:`camlab.exercises._core.check` for every test input; lesson 00 shows it at work.
"""

from __future__ import annotations

import signal
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

TIME_LIMIT_S = 30.0
"""Seconds a student's function may run on one test input (a slow loop, not an endless one, fits)."""


def time_limit_applies() -> bool:
    """Whether :func:`time_limit` can stop a running function here: SIGALRM in the main thread.

    True on Linux and macOS in a Jupyter kernel (cells run in its main thread); False on
    Windows, which has no SIGALRM, and in a worker thread.
    """
    return hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()


class OutOfTime(TimeoutError):
    """Raised by :func:`time_limit` when its body ran too long."""


class _Alarm(BaseException):
    """Raised into the running code by the timer; a BaseException, so a student's ``except Exception`` cannot eat it."""


@contextmanager
def time_limit(seconds: float) -> Iterator[None]:
    """Raise :class:`OutOfTime` if the body is still running after ``seconds``.

    Uses a SIGALRM timer, which exists on Unix in the main thread (where a Jupyter kernel
    runs cells). Elsewhere (Windows, a worker thread) the body runs without a limit. A timer
    already running (pytest-timeout's) is put back with its remaining time afterwards, and
    wins if it is due first.
    """
    if not time_limit_applies():
        yield
        return
    outer_delay, outer_interval = signal.getitimer(signal.ITIMER_REAL)
    outer_first = 0 < outer_delay <= seconds
    outer_handler = signal.getsignal(signal.SIGALRM)

    def on_alarm(signum: int, frame: Any) -> None:
        if outer_first and callable(outer_handler):
            outer_handler(signum, frame)  # the outer deadline came first: its handler decides
        raise _Alarm

    start = time.monotonic()
    signal.signal(signal.SIGALRM, on_alarm)
    signal.setitimer(signal.ITIMER_REAL, outer_delay if outer_first else seconds)
    try:
        yield
    except _Alarm:
        raise OutOfTime(f"still running after {seconds:g} s") from None
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, outer_handler)
        if outer_delay and not outer_first:
            signal.setitimer(
                signal.ITIMER_REAL,
                max(outer_delay - (time.monotonic() - start), 1e-3),
                outer_interval,
            )
