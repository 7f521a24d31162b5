"""The machinery behind every ``check_<name>`` and ``solution(name)``.

An exercise pairs a reference implementation from camlab with test inputs, a
comparison and a diagnosis. ``check`` runs the student's function on every input:

* a stub that raises NotImplementedError prints "not attempted yet" and returns False,
  so a lesson with untouched exercises still runs top to bottom in CI;
* a wrong answer raises AssertionError naming the input, what came out, what was
  expected and the likely cause;
* a right answer prints a congratulation and returns True.

A wrong answer's message stays short: an image-sized array is summarised (shape, dtype,
range, worst entry) instead of printed. ``solution(name)`` prints the exercise's *teaching
solution*: a short, self-contained numpy function written to be read (``Exercise.teaching``),
separate from camlab's optimised implementation (``Exercise.reference``); the test suite
proves the two agree on every test input and that the teaching solution calls nothing but
numpy and builtins.
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
    teaching: Callable[..., Any] | None = None


EXERCISES: dict[str, Exercise] = {}


def register_exercise(exercise: Exercise) -> Exercise:
    EXERCISES[exercise.name] = exercise
    return exercise


_MAX_PRINTED = 24  # arrays with more entries are summarised, not printed


def _fmt(value: Any) -> str:
    if isinstance(value, np.ndarray):
        if value.size > _MAX_PRINTED:
            finite = value[np.isfinite(value)] if np.issubdtype(value.dtype, np.number) else value.ravel()
            span = f", values {finite.min():.4g} .. {finite.max():.4g}" if finite.size else ""
            return f"<array of shape {value.shape}, dtype {value.dtype}{span}>"
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
                f"  on input {_fmt(args)}" + _exception_hint(exc)
            ) from exc
        if got is None:
            raise AssertionError(f"{name}: your function returned None on test input {i + 1}\n"
                                 f"  likely cause: did you forget `return`? The last line should be `return <result>`.")
        if not exercise.compare(got, expected):
            raise AssertionError(
                f"{name}: wrong answer on test input {i + 1} of {len(cases)}\n"
                f"  input    {_fmt(args)}\n"
                f"  got      {_fmt(_as_array(got))}\n"
                f"  expected {_fmt(expected)}\n"
                + worst_mismatch(got, expected)
                + f"  likely cause: {exercise.diagnose(args, got, expected)}"
            )
    print(f"{name}: correct on all {len(cases)} test inputs. Well done!")
    return True


def _exception_hint(exc: Exception) -> str:
    """A likely cause for the errors students meet most ('' for the others)."""
    if isinstance(exc, ValueError) and "broadcast" in str(exc):
        return ("\n  likely cause: a broadcasting slip. Dividing an (N, 2) array by an (N,) column such as X[:, 2]"
                " lines the column up with the last axis; keep it 2-D: X[:, 2:3], X[:, 2, None] or keepdims=True")
    return ""


def _as_array(value: Any) -> Any:
    """Lists of numbers print like arrays (and get summarised when large)."""
    if isinstance(value, list):
        try:
            return np.asarray(value)
        except ValueError:
            return value
    return value


def worst_mismatch(got: Any, expected: Any) -> str:
    """One line naming the worst entry of two same-shape arrays ('' if that makes no sense)."""
    try:
        g = np.asarray(got, dtype=float)
        e = np.asarray(expected, dtype=float)
    except (TypeError, ValueError):
        return ""
    if g.shape != e.shape or e.size <= 1:
        return ""
    err = np.abs(g - e)
    err[~np.isfinite(err)] = np.inf
    if not np.any(err > 0):
        return ""
    index = np.unravel_index(int(np.argmax(err)), e.shape)
    where = {2: "(row, column)", 3: "(row, column, channel)"}.get(e.ndim, "index")
    wrong = int(np.sum(~np.isclose(g, e)))
    return (f"  worst    {where} {tuple(int(i) for i in index)}: got {g[index]:.6g}, expected {e[index]:.6g}"
            f" ({wrong} of {e.size} entries differ)\n")


def solution(name: str) -> str:
    """Print (and return) the teaching solution of ``name`` (the library's source if it has none)."""
    exercise = EXERCISES[name]
    reference = exercise.reference
    where = f"{reference.__module__}.{reference.__qualname__}"
    if exercise.teaching is None:
        source = inspect.getsource(reference)
    else:
        source = (inspect.getsource(exercise.teaching)
                  + f"\n# camlab's own, tested implementation: {where} (read it with {where}??)\n")
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


def unit_slip(got: Any, expected: Any) -> str | None:
    """A diagnosis when ``got`` is ``expected`` times 1000 or / 1000 (millimetres vs metres), else None."""
    try:
        g = np.asarray(got, dtype=float)
        e = np.asarray(expected, dtype=float)
    except (TypeError, ValueError):
        return None
    if g.shape != e.shape or not np.any(e):
        return None
    for factor, unit in ((1e3, "millimetres"), (1e-3, "kilometres (or you divided by 1000)")):
        if np.allclose(g, factor * e, rtol=1e-6, atol=0):
            return (f"your answer is {factor:g} times the expected one: you worked in {unit}; "
                    f"the inputs and the answer are in metres")
    return None
