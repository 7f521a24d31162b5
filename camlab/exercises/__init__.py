"""Exercise checks: ``check_<name>(student_function)`` and ``solution(name)``.

Exercises are defined one module per lesson (``projective_plane.py``...). In a lesson::

    from camlab.exercises import check_intersect_lines, solution
    check_intersect_lines(intersect_lines)   # "not attempted yet" / diagnosis / well done
    solution("intersect_lines")               # prints a short teaching solution in numpy

Each exercise module registers, beside the check, a *teaching solution*: a function named
like the exercise, written in plain numpy to be read (``Exercise(..., teaching=fn)``). It
never calls camlab, let alone a private helper; tests/test_exercises.py proves it passes
the exercise's own check, i.e. agrees with camlab's optimised implementation.
"""

from __future__ import annotations

import functools
import importlib
import pkgutil

from ._answers import (
    same_array,
    same_up_to_scale,
    shape_problem,
    type_problem,
    unit_slip,
    worst_mismatch,
)
from ._core import EXERCISES, Exercise, check, register_exercise
from ._core import solution as _solution
from ._core import solution_source as _solution_source
from ._timer import TIME_LIMIT_S, time_limit_applies

__all__ = [
    "EXERCISES",
    "TIME_LIMIT_S",
    "Exercise",
    "all_exercises",
    "check",
    "register_exercise",
    "same_array",
    "same_up_to_scale",
    "shape_problem",
    "solution",
    "solution_source",
    "time_limit_applies",
    "type_problem",
    "unit_slip",
    "worst_mismatch",
]


def all_exercises() -> dict[str, Exercise]:
    """Import every lesson's exercise module and return the registry, by name.

    Returns
    -------
    dict[str, Exercise]
        Every registered exercise, keyed by its name (``"lift"``, ``"project_points"`` ...): a copy
        of the registry, so changing it changes no check.
    """
    for module in pkgutil.iter_modules(__path__):
        if not module.name.startswith("_"):
            importlib.import_module(f"{__name__}.{module.name}")
    return dict(EXERCISES)


def _known(name: str, caller: str) -> None:
    if name not in all_exercises():
        raise KeyError(f"{caller}: no exercise {name!r}; exercises are {sorted(EXERCISES)}")


def solution(name: str) -> None:
    """Print the teaching solution of exercise ``name`` (numpy only); returns None, so it shows once.

    Parameters
    ----------
    name : str
        The exercise's name, as in ``check_<name>`` (``"lift"``).

    Returns
    -------
    None
        The solution is printed, not returned: a returned string ending a cell would show a second,
        escaped copy.

    Raises
    ------
    KeyError
        No exercise is called ``name``; the message lists the exercises.
    """
    _known(name, "solution")
    _solution(name)


def solution_source(name: str) -> str:
    """The text :func:`solution` prints, for tools and tests.

    Parameters
    ----------
    name : str
        The exercise's name, as in ``check_<name>``.

    Returns
    -------
    str
        The teaching solution's source and a comment naming camlab's own implementation.

    Raises
    ------
    KeyError
        No exercise is called ``name``; the message lists the exercises.
    """
    _known(name, "solution_source")
    return _solution_source(name)


def __getattr__(attr: str):
    """``check_<name>``: the check of exercise ``name``, looked up in the registry on first use.

    A check takes the student's function and runs it on every test input (:func:`check`): it prints
    "not attempted yet" for a stub that raises NotImplementedError, raises AssertionError naming the
    input and the likely cause for a wrong answer, and prints a congratulation for a right one.

    Parameters
    ----------
    attr : str
        The attribute asked for: ``check_<name>``.

    Returns
    -------
    callable
        ``check_<name>(student_function, *, time_limit_s=None) -> CheckResult``, true when the function
        passed every test input.

    Raises
    ------
    AttributeError
        ``attr`` is not ``check_`` followed by the name of an exercise.
    """
    if attr.startswith("check_"):
        name = attr[len("check_") :]
        if name in all_exercises():
            fn = functools.partial(check, name)
            fn.__doc__ = f"Check your `{name}` function; prints 'not attempted yet' for a stub."
            return fn
    raise AttributeError(f"module 'camlab.exercises' has no attribute {attr!r}")
