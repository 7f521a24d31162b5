"""The machinery behind every ``check_<name>`` and ``solution(name)``.

An exercise pairs a reference implementation from camlab with test inputs, a
comparison and a diagnosis. ``check`` runs the student's function on every input:

* a stub that raises NotImplementedError prints "not attempted yet" and returns a false
  :class:`CheckResult`, so a lesson with untouched exercises still runs top to bottom in CI;
* a wrong answer raises AssertionError naming the input, what came out, what was
  expected and the likely cause; so does an answer of the wrong type (a string, an array of
  strings or of complex numbers, a list of an array and a number, or, where the prompt asks
  for a numpy array, any list), named by :func:`type_problem`;
* a function that changes an input array in place fails, naming the argument (the
  caller's data must come back as it went in), even if its answer is right;
* an exercise may name the likely cause of an exception its typical mistakes raise
  (``Exercise.exception_hint``); the shared hints cover the rest;
* a function still running after :data:`TIME_LIMIT_S` seconds on one input is stopped,
  and the AssertionError names that input, where a timer can interrupt it (Linux and macOS,
  in the main thread: :func:`time_limit_applies`; see :func:`time_limit`);
* a right answer prints a congratulation and returns a true :class:`CheckResult`.

The result prints nothing when it ends a cell (the verdict is already printed), and
``assert check_<name>(<name>)`` works as with a bool (graded assignments use that).
Float answers are compared in float64 within the exercise's :class:`Tolerance`; an
answer computed in float32 is held to what float32 can represent, and one in float16 (about
3 significant digits: it cannot tell 2015.5 from 2016) is rejected, naming its type
(:func:`precision_problem`), since no tolerance wide enough for it would still catch a
half-pixel slip.

A wrong answer's message stays short: an image-sized array is summarised (shape, dtype,
range, worst entry) instead of printed. ``solution(name)`` prints the exercise's *teaching
solution*: a short, self-contained numpy function written to be read (``Exercise.teaching``),
separate from camlab's optimised implementation (``Exercise.reference``); the test suite
proves the two agree on every test input and that the teaching solution calls nothing but
numpy and builtins.
"""

from __future__ import annotations

import inspect
import re
import signal
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._validate import CamlabInputError


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
    ndarray_only: bool = False
    """The prompt asks for a numpy array: a list or tuple of the right numbers is rejected too."""
    exception_hint: Callable[[Exception, tuple], str] | None = None
    """``exception_hint(exc, args)``: the likely cause, as plain text, when the student's function raises
    ``exc`` on ``args`` and only this exercise can name it (an np.tile mask one row short on an odd-sized
    mosaic is no 'broadcasting slip'), or '' to fall back on the hints every check shares."""
    follow_up: Callable[[Callable[..., Any]], str | None] | None = None
    """Checks beyond answer-against-answer, run once every test input has passed: called with a
    function that runs the student's function on given arguments (under the same time limit and
    in-place check), it returns what is wrong or None. For properties a single input cannot show,
    such as an estimate that must not depend on the units of its input."""
    success_note: Callable[[Callable[..., Any]], str] | None = None
    """Called like ``follow_up`` once the function has passed, it returns a line printed under the congratulation:
    the answer to a question the prompt asked, computed with the student's own function."""
    describe_input: Callable[[tuple], str] | None = None
    """``describe_input(args)``: the test input summarised in one line for messages, where printing it
    (stacks of frames, say) would bury the likely cause under hundreds of characters."""


EXERCISES: dict[str, Exercise] = {}


def register_exercise(exercise: Exercise) -> Exercise:
    EXERCISES[exercise.name] = exercise
    return exercise


_MAX_PRINTED = 24  # arrays with more entries are summarised, not printed


def _fmt(value: Any) -> str:
    if isinstance(value, np.ndarray):
        if value.size > _MAX_PRINTED:
            real = value.dtype.kind in "biuf"  # text, complex or objects have no range to print
            finite = value[np.isfinite(value)] if real else value[:0]
            span = f", values {finite.min():.4g} .. {finite.max():.4g}" if finite.size else ""
            return f"<array of shape {value.shape}, dtype {value.dtype}{span}>"
        return np.array2string(
            value, precision=4, suppress_small=True, separator=", ", floatmode="maxprec_equal"
        )
    if isinstance(value, np.generic):
        return repr(value.item())  # 2.5, not np.float64(2.5)
    if isinstance(value, (tuple, list)):
        inner = ", ".join(_fmt(v) for v in value)
        return (
            f"[{inner}]"
            if isinstance(value, list)
            else f"({inner},)"
            if len(value) == 1
            else f"({inner})"
        )
    return repr(value)


def _shown(value: Any) -> str:
    """``_fmt`` for a message's got/expected line: a multi-line array continues under its first line."""
    return _fmt(value).replace("\n", "\n" + " " * 11)


def _input_text(name: str, args: tuple) -> str:
    """The test input as a message shows it: the exercise's own summary, else each argument printed."""
    exercise = EXERCISES.get(name)
    if exercise is not None and exercise.describe_input is not None:
        return exercise.describe_input(args)
    return _fmt(args)


def _copy(args: tuple) -> tuple:
    # Students must not be able to corrupt the reference's inputs by editing in place.
    return tuple(np.array(a) if isinstance(a, np.ndarray) else a for a in args)


class CheckResult:
    """What :func:`check` found: true when the function passed every test input.

    Shows nothing when it ends a cell, where a bool would print a stray ``False`` under
    "not attempted yet" (the check has printed its verdict already).
    """

    __slots__ = ("name", "passed")

    def __init__(self, name: str, passed: bool):
        self.name, self.passed = name, bool(passed)

    def __bool__(self) -> bool:
        return self.passed

    def __repr__(self) -> str:
        return f"CheckResult({self.name!r}, passed={self.passed})"

    def _ipython_display_(self) -> None:
        """IPython's display hook: the check's printed verdict says it all."""


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


def _inputs_changed(original: tuple, passed: tuple) -> list[int]:
    """Positions of the array arguments that differ, after the student's call, from the originals."""
    changed = []
    for k, (before, after) in enumerate(zip(original, passed, strict=True)):
        if isinstance(before, np.ndarray):
            same = before.shape == np.shape(after) and np.array_equal(
                before, after, equal_nan=before.dtype.kind in "fc"
            )
            if not same:
                changed.append(k)
    return changed


def _parameter_name(function: Callable[..., Any], position: int) -> str:
    """The name of ``function``'s parameter at ``position`` (for messages), or 'argument k'."""
    try:
        names = list(inspect.signature(function).parameters)
    except (TypeError, ValueError):
        names = []
    return f"`{names[position]}`" if position < len(names) else f"argument {position + 1}"


def _in_place_message(
    name: str, student_function: Callable[..., Any], changed: list[int], i: int, n: int, args: tuple
) -> str:
    """The diagnosis of an input changed in place, with examples written for the first changed argument.

    The examples use that argument's own name and shape: ``p[1] = -p[1]`` for one point (a 1-D array),
    ``X[:, 0] = ...`` for a batch, so a warm-up on one point does not read batch code in its hint.
    """
    what = ", ".join(_parameter_name(student_function, k) for k in changed)
    first = _parameter_name(student_function, changed[0]).strip("`")
    a = first if first.isidentifier() else "x"
    if np.ndim(args[changed[0]]) == 1:
        examples, new = (
            f"`{a}[1] = -{a}[1]`, `{a} += d`, `{a}.sort()`",
            f"`{a} + d`, `np.append({a}, 1.0)`",
        )
    else:
        examples, new = f"`{a} *= L`, `{a}[:, 0] = ...`, `{a} += d`", f"`{a} * L`"
    return (
        f"{name}: your function changed its input {what} in place (test input {i + 1} of {n}); the caller's "
        f"array must come back as it went in\n"
        f"  likely cause: an in-place operation on an argument ({examples}); "
        f"build a new array instead ({new}), or work on a copy first (`{a} = np.array({a}, dtype=float)`)"
    )


def _run_student(
    name: str, student_function: Callable[..., Any], args: tuple, i: int, n: int, seconds: float
) -> Any:
    """The student's answer on test input ``i`` of ``n``; AssertionError on a crash, a run longer than
    ``seconds`` or an input changed in place."""
    passed = _copy(args)
    try:
        with time_limit(seconds):
            got = student_function(*passed)
    except NotImplementedError:
        raise
    except OutOfTime:
        raise AssertionError(
            f"{name}: your function was still running after {seconds:g} s on test input {i + 1} of {n}, "
            f"so the check stopped it\n"
            f"  input    {_input_text(name, args)}\n"
            f"  likely cause: a loop that never ends (a `while` whose condition stays true?)"
        ) from None
    except Exception as exc:
        raise AssertionError(
            f"{name}: your function raised {type(exc).__name__}: {exc}\n"
            f"  on input {_input_text(name, args)}" + _exercise_exception_hint(name, exc, args)
        ) from exc
    changed = _inputs_changed(args, passed)
    if changed:
        raise AssertionError(_in_place_message(name, student_function, changed, i, n, args))
    return got


def check(
    name: str, student_function: Callable[..., Any], *, time_limit_s: float | None = None
) -> CheckResult:
    """Check ``student_function`` against exercise ``name`` (see the module docstring).

    ``time_limit_s`` replaces :data:`TIME_LIMIT_S`, the seconds allowed per test input (lesson 00
    shows the limit at work with a short one); it applies only where :func:`time_limit_applies`.
    """
    if time_limit_s is not None and not time_limit_s > 0:
        raise CamlabInputError(
            f"check: time_limit_s: expected a positive number of seconds, got {time_limit_s!r}; "
            f"leave it out for the usual {TIME_LIMIT_S:g} s"
        )
    seconds = TIME_LIMIT_S if time_limit_s is None else float(time_limit_s)
    exercise = EXERCISES[name]
    cases = list(exercise.cases())
    for i, args in enumerate(cases):
        expected = exercise.reference(*_copy(args))
        _leave_nan_in_freed_memory(expected)
        try:
            got = _run_student(name, student_function, args, i, len(cases), seconds)
        except NotImplementedError:
            print(
                f"{name}: not attempted yet. Fill in the function above, run its cell, then this one."
            )
            return CheckResult(name, False)
        if got is None:
            raise AssertionError(
                f"{name}: your function returned None on test input {i + 1}\n"
                f"  likely cause: did you forget `return`? The last line should be `return <result>`."
            )
        wrong_type = type_problem(got, expected, exercise.ndarray_only)
        if wrong_type:
            raise AssertionError(
                f"{name}: wrong type of answer on test input {i + 1} of {len(cases)}\n"
                f"  input    {_input_text(name, args)}\n"
                f"  got      {_shown(got)}  ({_a(got)})\n"
                f"  expected {_shown(expected)}\n"
                f"  likely cause: {wrong_type}"
            )
        too_coarse = precision_problem(got, expected)
        if too_coarse:
            raise AssertionError(
                f"{name}: answer too imprecise on test input {i + 1} of {len(cases)}\n"
                f"  input    {_input_text(name, args)}\n"
                f"  got      {_shown(_as_array(got))}\n"
                f"  likely cause: {too_coarse}"
            )
        if not exercise.compare(got, expected):
            tolerance = (
                exercise.compare.tolerance if isinstance(exercise.compare, SameArray) else None
            )
            raise AssertionError(
                f"{name}: wrong answer on test input {i + 1} of {len(cases)}\n"
                f"  input    {_input_text(name, args)}\n"
                f"  got      {_shown(_as_array(got))}\n"
                f"  expected {_shown(expected)}\n"
                + worst_mismatch(got, expected, tolerance)
                + f"  likely cause: {exercise.diagnose(args, got, expected)}"
            )
    if exercise.follow_up is not None:
        problem = exercise.follow_up(
            lambda *args: _run_student(
                name, student_function, args, len(cases), len(cases) + 1, seconds
            )
        )
        if problem:
            raise AssertionError(f"{name}: correct on all {len(cases)} test inputs, but {problem}")
    print(f"{name}: correct on all {len(cases)} test inputs. Well done!")
    if exercise.success_note is not None:
        print(
            exercise.success_note(
                lambda *args: _run_student(
                    name, student_function, args, len(cases), len(cases) + 1, seconds
                )
            )
        )
    return CheckResult(name, True)


def _leave_nan_in_freed_memory(expected: Any) -> None:
    """Free a NaN-filled array of the answer's size just before the student's function runs.

    numpy reuses the memory of small arrays it has just freed, so an answer built with
    ``np.empty(3)`` and left partly unfilled would otherwise hold the numbers of the reference
    answer (the array the check just computed) and pass by luck. After this it holds NaN, and the
    check fails, naming it.
    """
    if (
        isinstance(expected, np.ndarray)
        and expected.dtype.kind == "f"
        and 0 < expected.nbytes <= 1024
    ):
        np.full(expected.shape, np.nan, dtype=expected.dtype)  # made and freed at once


def _exercise_exception_hint(name: str, exc: Exception, args: tuple) -> str:
    """The exercise's own hint for ``exc`` (its ``exception_hint``) as a 'likely cause' line, else the shared one."""
    exercise = EXERCISES.get(name)
    own = (
        exercise.exception_hint(exc, args)
        if exercise is not None and exercise.exception_hint
        else ""
    )
    return f"\n  likely cause: {own}" if own else _exception_hint(exc)


def _exception_hint(exc: Exception) -> str:
    """A likely cause for the errors students meet most ('' for the others)."""
    one_based = (
        "\n  likely cause: counting columns from 1. Python counts from 0: an axis of size n has indices"
        " 0 .. n - 1, so the columns of an (N, 3) array of points are 0, 1 and 2 (z is X[:, 2] or X[:, 2:3])"
    )
    if isinstance(exc, ValueError) and "read-only" in str(exc):
        return (
            "\n  likely cause: an in-place change (K /= d, K[0, 2] = ...) of an array you were given read-only,"
            " such as a camlab Camera's K, R or t (cameras are immutable): build a new array (K / d) or change"
            " a copy (K = camera.K.copy())"
        )
    if isinstance(exc, IndexError) and "out of bounds" in str(exc):
        return one_based
    if (
        isinstance(exc, ValueError)
        and "broadcast" in str(exc)
        and re.search(r"\(\d+,0\)|\(0,", str(exc))
    ):
        return one_based + " (a slice past the last column, X[:, 3:4], is empty)"
    if isinstance(exc, ValueError) and "broadcast" in str(exc):
        return (
            "\n  likely cause: a broadcasting slip. Dividing an (N, 2) array by an (N,) column such as X[:, 2]"
            " lines the column up with the last axis; keep it 2-D: X[:, 2:3], X[:, 2, None] or keepdims=True"
        )
    if isinstance(exc, ValueError) and "inhomogeneous" in str(exc):
        return f"\n  likely cause: an array beside numbers, as in np.array([p, 1]), makes no array of numbers: {_JOIN}"
    if isinstance(exc, ValueError) and "matmul" in str(exc):
        return (
            "\n  likely cause: the sizes of a matrix product do not fit (A @ B needs A's columns = B's rows)."
            " With points as rows, a matrix M acts as X @ M.T, not X @ M; and lift points to homogeneous"
            " coordinates (append a column of ones) before a 3 x 4 or 3 x 3 projective matrix"
        )
    return ""


_JOIN = "join an array and numbers with np.append(p, 1.0), np.concatenate or np.hstack"


def type_problem(got: Any, expected: Any, ndarray_only: bool = False) -> str | None:
    """Why ``got`` is the wrong type of answer for an array or a number ``expected``, or None.

    Catches what numpy cannot turn into numbers (a string, a list holding an array and a
    number), what it would turn into numbers only by reading text or dropping an imaginary
    part (arrays of strings, complex arrays: :func:`_not_real_numbers`) and, with
    ``ndarray_only``, a list or tuple where the prompt asks for an array.
    Answers of other kinds (pairs of arrays...) are left to the exercise's compare and diagnose.
    """
    if isinstance(expected, np.ndarray):
        wanted = f"return a numpy array of shape {expected.shape}"
    elif isinstance(expected, (float, int, np.number)):
        wanted = "return one number"
    else:
        return None
    kind = type(got).__name__
    if (
        isinstance(got, (tuple, list))
        and len(got) == 1
        and isinstance(got[0], np.ndarray)
        and isinstance(expected, np.ndarray)
        and got[0].shape == expected.shape
    ):
        made = (
            "a trailing comma, `return x,`, makes a tuple"
            if isinstance(got, tuple)
            else "brackets, `[x]`, make a list"
        )
        return f"you returned a {kind} holding your array: {made}; return the array itself"
    if (
        isinstance(got, (tuple, list))
        and len(got) == 1
        and isinstance(expected, (float, int, np.number))
        and np.ndim(got[0]) == 0
        and not isinstance(got[0], (str, bytes))
    ):
        made = (
            "a trailing comma, `return x,`, makes a tuple"
            if isinstance(got, tuple)
            else "brackets, `[x]`, make a list"
        )
        return f"you returned a {kind} of shape (1,); return one number: {made}; return the number itself"
    not_real = _not_real_numbers(got, kind, wanted)
    if not_real:
        return not_real
    try:
        np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        if isinstance(got, (list, tuple)):
            return (
                f"you returned a {kind} that numpy cannot turn into one array of numbers (an array beside "
                f"numbers, such as [p, 1]?); {wanted}: {_JOIN}"
            )
        return f"you returned a {kind}, which is not numbers; {wanted}"
    if ndarray_only and not isinstance(got, np.ndarray):
        return f"you returned a {kind}; {wanted}: wrap the values in np.array(...)"
    return None


def precision_problem(got: Any, expected: Any) -> str | None:
    """Why a float answer is too coarse to judge (float16 and shorter), or None.

    float16 keeps 11 significant bits, about 3 decimal digits: between 1024 and 2048 it steps by
    whole numbers, so c_x = 2015.5 and the half-pixel slip W / 2 = 2016 are the same float16
    number. A tolerance wide enough for it would pass real mistakes, so such an answer is
    rejected (float32, 7 digits, is held to its own precision instead: :class:`Tolerance`).
    """
    if not _holds_floats(expected):  # integer answers (digital numbers) have their own dtype checks
        return None
    if _coarsest_eps(got) <= np.finfo(np.float32).eps:
        return None
    coarse = _coarsest_dtype(got)
    return (
        f"your answer is {coarse}, which keeps only about {np.finfo(coarse).precision} significant digits "
        f"(between 1024 and 2048 it steps by whole numbers: 2015.5 and 2016 are the same {coarse} number), too "
        f"coarse to tell a right answer from a slip; compute in float64, numpy's default (float32 also "
        f"passes), and leave out .astype(np.{coarse})"
    )


def _holds_floats(value: Any) -> bool:
    """Whether ``value`` (an array, a number, or a tuple or list of them) holds floats."""
    if isinstance(value, (tuple, list)):
        return any(_holds_floats(v) for v in value)
    try:
        return np.asarray(value).dtype.kind == "f"
    except (TypeError, ValueError):
        return False


def _coarsest_dtype(value: Any) -> np.dtype:
    """The float dtype with the largest epsilon in ``value`` (float64 if there is none)."""
    if isinstance(value, (tuple, list)):
        return max(
            (_coarsest_dtype(v) for v in value),
            key=lambda d: np.finfo(d).eps,
            default=np.dtype(np.float64),
        )
    dtype = getattr(value, "dtype", None)
    return (
        np.dtype(dtype)
        if dtype is not None and np.issubdtype(dtype, np.floating)
        else np.dtype(np.float64)
    )


def _a(value: Any) -> str:
    """'a list', 'an ndarray': the value's type with its article."""
    kind = type(value).__name__
    return f"an {kind}" if kind[0] in "aeiou" or kind == "ndarray" else f"a {kind}"


def _not_real_numbers(got: Any, kind: str, wanted: str) -> str | None:
    """Why an answer is not real numbers although numpy could cast it to float, or None.

    ``np.asarray(x, dtype=float)`` reads text such as '2.5' and drops an imaginary part (with
    only a warning), so without this check an array of strings or of complex numbers would
    pass as the right answer.
    """
    if isinstance(got, str):
        return f"you returned a str, which is not numbers; {wanted}"
    a_kind = _a(got)
    try:
        dtype = np.asarray(got).dtype
    except (TypeError, ValueError):
        return None  # a ragged list: the float cast in type_problem names it
    if dtype.kind in "US":
        return (
            f"you returned {a_kind} of text (dtype {dtype}), not of numbers: the values were turned into "
            f"strings (str(), an f-string, or np.array of numbers mixed with text); {wanted} built from the "
            f"numbers themselves"
        )
    if dtype.kind == "c":
        what = f"{a_kind} of complex numbers" if np.ndim(got) else "a complex number"
        return (
            f"you returned {what} (dtype {dtype}), but the answer is real, and "
            f"comparing it as real would silently drop the imaginary part: a complex value crept in "
            f"(a 1j, or a result of np.linalg.eig or np.roots); keep the computation real, or take .real once "
            f"you have checked that the imaginary part is 0; {wanted}"
        )
    if dtype.kind == "O" and isinstance(
        got, np.ndarray
    ):  # other objects (a dict) fail the float cast
        return (
            f"you returned {a_kind} of Python objects (dtype object), not an array of numbers (dtype=object, "
            f"or arrays mixed with numbers?); {wanted}: {_JOIN}"
        )
    return None


def _as_array(value: Any) -> Any:
    """Lists of numbers print like arrays (and get summarised when large)."""
    if isinstance(value, list):
        try:
            return np.asarray(value)
        except ValueError:
            return value
    return value


def worst_mismatch(got: Any, expected: Any, tolerance: Tolerance | None = None) -> str:
    """One line naming the worst entry of two same-shape arrays ('' if that makes no sense).

    Entries count as differing by ``tolerance`` (the exercise's; numpy's default otherwise),
    so the count agrees with the verdict. Values that print alike at 6 digits are shown in full.
    """
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
    if isinstance(expected, (tuple, list)) and e.ndim == 3:  # a pair of matrices, e.g. (K, R)
        where = "(matrix, row, column)"
    else:
        where = {2: "(row, column)", 3: "(row, column, channel)"}.get(e.ndim, "index")
    tol = (tolerance or Tolerance()).for_answer(got, expected)
    wrong = int(np.sum(~tol.close(g, e)))
    shown_got, shown_expected = f"{g[index] + 0.0:.6g}", f"{e[index] + 0.0:.6g}"  # + 0.0: no "-0"
    if shown_got == shown_expected:
        shown_got, shown_expected = repr(float(g[index])), repr(float(e[index]))
    return (
        f"  worst    {where} {tuple(int(i) for i in index)}: got {shown_got}, expected {shown_expected}"
        f" ({wrong} of {e.size} entries differ by more than {tol})\n"
    )


def solution_source(name: str) -> str:
    """The text :func:`solution` prints: the teaching solution of ``name`` (the library's source if it has none)."""
    exercise = EXERCISES[name]
    reference = exercise.reference
    where = f"{reference.__module__}.{reference.__qualname__}"
    if exercise.teaching is None:
        return inspect.getsource(reference)
    if reference.__name__.startswith(
        "_"
    ):  # a private helper is no place to send a student: say what it computes
        summary = (inspect.getdoc(reference) or "").split("\n")[0]
        return (
            inspect.getsource(exercise.teaching)
            + f"\n# camlab's own, tested reference: {summary}\n"
        )
    return (
        inspect.getsource(exercise.teaching)
        + f"\n# camlab's own, tested implementation: {where} (read it with {where}??)\n"
    )


def solution(name: str) -> None:
    """Print the teaching solution of ``name``; returns None.

    None, so that a bare ``solution("name")`` ending a cell shows the code once: a returned
    string would also be echoed as the cell's ``Out[]``, escaped, on one line. Tools that need
    the text call :func:`solution_source`.
    """
    print(solution_source(name))


def same_up_to_scale(got: Any, expected: np.ndarray, rtol: float = 1e-6) -> bool:
    """True if ``got`` equals ``expected`` times some non-zero scalar (homogeneous equality)."""
    g = np.asarray(got, dtype=float)
    e = np.asarray(expected, dtype=float)
    if g.shape != e.shape or not np.isfinite(g).all() or not np.any(g):
        return False
    g = g / np.linalg.norm(g)
    e = e / np.linalg.norm(e)
    return bool(min(np.linalg.norm(g - e), np.linalg.norm(g + e)) <= rtol)


REDUCED_PRECISION_SLACK = 100
"""An answer in a shorter float type is held to this many of its epsilons (float32: 1.2e-5)."""


def _coarsest_eps(value: Any) -> float:
    """The largest machine epsilon among the floats in ``value`` (arrays, numpy scalars, tuples, lists)."""
    if isinstance(value, (tuple, list)):
        return max((_coarsest_eps(v) for v in value), default=float(np.finfo(np.float64).eps))
    dtype = getattr(value, "dtype", None)
    if dtype is not None and np.issubdtype(dtype, np.floating):
        return float(np.finfo(dtype).eps)
    return float(np.finfo(np.float64).eps)


@dataclass(frozen=True)
class Tolerance:
    """How close a float answer must be, entry by entry: ``|got - expected| <= atol + rtol |expected|``.

    Compared in float64. An answer computed in float32 cannot come closer than its own
    rounding, so :meth:`for_answer` widens both tolerances to :data:`REDUCED_PRECISION_SLACK`
    of its epsilons (``atol`` relative to the largest expected entry). Coarser floats (float16)
    never get here: :func:`check` rejects them (:func:`precision_problem`), since 100 of their
    epsilons, about 0.1 relative, would pass a half-pixel slip.
    """

    rtol: float = 1e-5
    atol: float = 1e-8

    def for_answer(self, got: Any, expected: Any) -> Tolerance:
        eps = _coarsest_eps(got)
        if eps <= np.finfo(np.float64).eps:
            return self
        slack = REDUCED_PRECISION_SLACK * eps
        e = np.abs(np.asarray(expected, dtype=float))
        scale = float(e[np.isfinite(e)].max(initial=0.0))
        return Tolerance(max(self.rtol, slack), max(self.atol, slack * scale))

    def close(self, got: Any, expected: Any) -> np.ndarray:
        """Per entry: within the tolerance (in float64)."""
        return np.isclose(
            np.asarray(got, dtype=float),
            np.asarray(expected, dtype=float),
            rtol=self.rtol,
            atol=self.atol,
        )

    def __str__(self) -> str:
        return f"rtol {self.rtol:.1g}, atol {self.atol:.1g}"


@dataclass(frozen=True)
class SameArray:
    """``Exercise.compare`` for float answers: same shape, every entry within ``tolerance``."""

    tolerance: Tolerance

    def __call__(self, got: Any, expected: Any) -> bool:
        try:
            g = np.asarray(got, dtype=float)
        except (TypeError, ValueError):
            return False
        tol = self.tolerance.for_answer(got, expected)
        return g.shape == np.shape(expected) and bool(np.all(tol.close(g, expected)))


def same_array(rtol: float = 1e-5, atol: float = 1e-8) -> SameArray:
    """A comparison for ``Exercise.compare``: same shape and ``np.allclose`` with these tolerances (float64)."""
    return SameArray(Tolerance(rtol, atol))


def shape_problem(got: Any, expected: np.ndarray) -> str | None:
    """A diagnosis for the commonest mistakes (wrong shape, NaN), or None."""
    if got is None:
        return "the function returned None: did you forget `return`?"
    wrong_type = type_problem(got, expected)
    if wrong_type:
        return wrong_type
    g = np.asarray(got, dtype=float)
    if g.shape != np.shape(expected):
        return f"expected an array of shape {np.shape(expected)}, got shape {g.shape}"
    if not np.isfinite(g).all():
        return (
            "the result holds NaN or inf: did you divide by a coordinate that can be 0, or leave entries of an "
            "array made with np.empty unfilled (np.empty keeps whatever was in memory)?"
        )
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
            return (
                f"your answer is {factor:g} times the expected one: you worked in {unit}; "
                f"the inputs and the answer are in metres"
            )
    return None
