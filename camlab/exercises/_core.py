"""The machinery behind every ``check_<name>`` and ``solution(name)``.

An exercise pairs a reference implementation from camlab with test inputs, a
comparison and a diagnosis. ``check`` runs the student's function on every input:

* a stub that raises NotImplementedError prints "not attempted yet" and returns False,
  so a lesson with untouched exercises still runs top to bottom in CI;
* a wrong answer raises AssertionError naming the input, what came out, what was
  expected and the likely cause;
* a right answer prints a congratulation and returns True.
"""
from __future__ import annotations

import inspect
from dataclasses import dataclass, field
from typing import Any, Callable, Sequence

import numpy as np


@dataclass(frozen=True)
class Exercise:
    """One exercise. ``diagnose(args, got, expected)`` returns the likely cause of a mismatch.

    ``wrong_variants`` are plausible student mistakes with a phrase their diagnosis must
    contain; the test suite proves each one is caught and explained.
    """

    name: str
    lesson: str
    reference: Callable[..., Any]
    cases: Callable[[], Sequence[tuple]]
    compare: Callable[[Any, Any], bool]
    diagnose: Callable[[tuple, Any, Any], str]
    wrong_variants: Sequence[tuple[Callable[..., Any], str]] = field(default_factory=tuple)


EXERCISES: dict[str, Exercise] = {}


def register_exercise(exercise: Exercise) -> Exercise:
    EXERCISES[exercise.name] = exercise
    return exercise


def _fmt(value: Any) -> str:
    if isinstance(value, np.ndarray):
        return np.array2string(value, precision=4, suppress_small=True, separator=", ")
    if isinstance(value, (tuple, list)):
        return "(" + ", ".join(_fmt(v) for v in value) + ")"
    return repr(value)


def _copy(args: tuple) -> tuple:
    # Students must not be able to corrupt the reference's inputs by editing in place.
    return tuple(np.array(a) if isinstance(a, np.ndarray) else a for a in args)


def check(name: str, student_function: Callable[..., Any]) -> bool:
    """Check ``student_function`` against exercise ``name`` (see the module docstring)."""
    exercise = EXERCISES[name]
    cases = list(exercise.cases())
    for i, args in enumerate(cases):
        expected = exercise.reference(*_copy(args))
        try:
            got = student_function(*_copy(args))
        except NotImplementedError:
            print(f"{name}: not attempted yet. Fill in the function above, run its cell, then this one.")
            return False
        except Exception as exc:
            raise AssertionError(
                f"{name}: your function raised {type(exc).__name__}: {exc}\n"
                f"  on input {_fmt(args)}"
            ) from exc
        if not exercise.compare(got, expected):
            raise AssertionError(
                f"{name}: wrong answer on test input {i + 1} of {len(cases)}\n"
                f"  input    {_fmt(args)}\n"
                f"  got      {_fmt(got)}\n"
                f"  expected {_fmt(expected)}\n"
                f"  likely cause: {exercise.diagnose(args, got, expected)}"
            )
    print(f"{name}: correct on all {len(cases)} test inputs. Well done!")
    return True


def solution(name: str) -> str:
    """Print (and return) the source of the library's own implementation of ``name``."""
    source = inspect.getsource(EXERCISES[name].reference)
    print(source)
    return source


def same_up_to_scale(got: Any, expected: np.ndarray, rtol: float = 1e-6) -> bool:
    """True if ``got`` equals ``expected`` times some non-zero scalar (homogeneous equality)."""
    g = np.asarray(got, dtype=float)
    e = np.asarray(expected, dtype=float)
    if g.shape != e.shape or not np.isfinite(g).all() or not np.any(g):
        return False
    g = g / np.linalg.norm(g)
    e = e / np.linalg.norm(e)
    return bool(min(np.linalg.norm(g - e), np.linalg.norm(g + e)) <= rtol)


def same_array(rtol: float = 1e-5, atol: float = 1e-8) -> Callable[[Any, Any], bool]:
    """A comparison for ``Exercise.compare``: same shape and ``np.allclose`` with these tolerances."""

    def compare(got: Any, expected: Any) -> bool:
        try:
            g = np.asarray(got, dtype=float)
        except (TypeError, ValueError):
            return False
        return g.shape == np.shape(expected) and bool(np.allclose(g, expected, rtol=rtol, atol=atol))

    return compare


def shape_problem(got: Any, expected: np.ndarray) -> str | None:
    """A diagnosis for the commonest mistakes (wrong shape, NaN), or None."""
    g = np.asarray(got, dtype=float) if got is not None else None
    if g is None:
        return "the function returned None: did you forget `return`?"
    if g.shape != np.shape(expected):
        return f"expected an array of shape {np.shape(expected)}, got shape {g.shape}"
    if not np.isfinite(g).all():
        return "the result holds NaN or inf: did you divide by a coordinate that can be 0?"
    return None
