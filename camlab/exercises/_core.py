"""The machinery behind every ``check_<name>`` and ``solution(name)``.

An exercise pairs a reference implementation from camlab with test inputs, a
comparison and a diagnosis. ``check`` runs the student's function on every input:

* a stub that raises NotImplementedError prints "not attempted yet" and returns a false
  :class:`CheckResult`, so a lesson with untouched exercises still runs top to bottom in CI;
* a wrong answer raises :class:`CheckFailed` (an AssertionError) naming the input, what came out, what was
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

This module holds the machinery (:class:`Exercise`, the registry, :func:`check`, :func:`solution`)
and the table every diagnosis uses for its typical mistakes: rows of :class:`Mistake` (a name, the
answer that mistake gives, its hint), checked in order by :func:`first_mistake`. What an answer must
be before any exercise looks at it (its type, precision and shape; the comparisons within a
tolerance) lives in :mod:`._answers`, the time limit in :mod:`._timer`.
"""

from __future__ import annotations

import inspect
import re
import sys
import traceback
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from .._validate import CamlabInputError
from ._answers import (
    JOIN_HINT,
    SCALE_FREE_RTOL,
    SameArray,
    Tolerance,
    as_array,
    precision_problem,
    rescaled_to,
    returned_none,
    same_up_to_scale,
    type_problem,
    with_article,
    worst_mismatch,
)
from ._timer import TIME_LIMIT_S, OutOfTime, time_limit

_CAMLAB = str(Path(__file__).resolve().parents[1])


class CheckFailed(AssertionError):
    """A wrong answer.

    An AssertionError (so ``assert``-based grading and pytest see it) that Jupyter shows as its
    message alone.

    IPython displays an exception through its ``_render_traceback_`` method when it has one.
    Here that leaves out the check's own frames in camlab, which tell a student nothing and
    bury the message under the library's source; when the student's function crashed, the
    frames of the student's code are kept, so they see where.
    """

    def _render_traceback_(self) -> list[str]:
        lines = []
        cause = self.__cause__
        if cause is not None and cause.__traceback__ is not None:
            theirs = [
                frame
                for frame in traceback.extract_tb(cause.__traceback__)
                if not str(Path(frame.filename).resolve()).startswith(_CAMLAB)
            ]
            if theirs:
                lines += ["Your function raised this, here:"]
                lines += "".join(traceback.format_list(theirs)).rstrip("\n").splitlines()
                lines += [f"{type(cause).__name__}: {cause}", ""]
        return lines + f"{type(self).__name__}: {self}".splitlines()


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
    solution_note: str | None = None
    """What :func:`solution` prints under the teaching solution, as comment lines, in place of the name of a
    private reference: the public camlab functions that compute the same answer another way."""
    diagnosis_runs: bool = False
    """``diagnose`` takes a fourth argument, ``run(*args)``, the student's function: slips that tie on
    one test input (several round up to k = 1, say) are told apart on the others."""
    up_to_scale: bool = False
    """The answer is homogeneous though ``compare`` is not :func:`same_up_to_scale`: a failed check
    shows the expected answer at the student's scale, as it does for that comparison."""
    describe_input: Callable[[tuple], str] | None = None
    """``describe_input(args)``: the test input summarised in one line for messages, where printing it
    (stacks of frames, say) would bury the likely cause under hundreds of characters."""
    in_place_examples: dict[str, tuple[str, str]] = field(default_factory=dict)
    """{parameter: (in-place slips, their new-array forms)} for an input changed in place, written for this
    exercise (``h /= h[:, 2:]`` and ``h[:, :2] / h[:, 2:]``), in place of the shared examples by shape."""


EXERCISES: dict[str, Exercise] = {}


def register_exercise(exercise: Exercise) -> Exercise:
    old = EXERCISES.get(exercise.name)
    if (
        old is not None and old.lesson != exercise.lesson
    ):  # one name, one check: the later would win
        raise ValueError(
            f"exercise {exercise.name!r} of lesson {exercise.lesson} is already registered by lesson "
            f"{old.lesson}: give it another name"
        )
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
        finite = value[np.isfinite(value)] if value.dtype.kind == "f" else value[:0]
        if (
            finite.size and 0 < np.abs(finite).max() < 1e-3
        ):  # tiny, not zero: 3 digits, never all 0.0
            text = np.array2string(
                value, separator=", ", formatter={"float_kind": lambda x: f"{x:.3g}"}
            )
            return (
                text
                if value.ndim != 1
                else "[" + ", ".join(t.strip() for t in text[1:-1].split(",")) + "]"
            )
        if value.dtype.kind == "f":  # what prints as zero prints as 0, never -0.0000
            with np.errstate(over="ignore"):  # rounding 1e308 overflows on the way; it is not 0
                value = np.where(np.round(value.astype(float), 4) == 0, 0.0, value)
        text = np.array2string(
            value, precision=4, suppress_small=True, separator=", ", floatmode="maxprec_equal"
        )
        text = re.sub(r"(\d)\.(?=[,\]\s]|$)", r"\1.0", text)  # [2.0, 2.0], not numpy's [2., 2.]
        if (
            value.ndim == 1
        ):  # one line: no padding to align columns, [4, 31, 22, 40], not [ 4, 31, 22, 40]
            text = "[" + ", ".join(item.strip() for item in text[1:-1].split(",")) + "]"
        return text
    if isinstance(value, np.generic):
        value = value.item()  # 2.5, not np.float64(2.5)
    if isinstance(value, float) and np.isfinite(value):
        return repr(float(f"{value:.12g}"))  # 35.3, not 35.300000000000004
    if isinstance(value, (tuple, list)):
        try:  # a long list of numbers (an image's .tolist()): summarised as an array would be
            numbers = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            numbers = None
        if numbers is not None and numbers.size > _MAX_PRINTED:
            finite = numbers[np.isfinite(numbers)]
            span = f", values {finite.min():.4g} .. {finite.max():.4g}" if finite.size else ""
            return f"<{type(value).__name__} of shape {numbers.shape}{span}>"
        inner = ", ".join(_fmt(v) for v in value)
        return (
            f"[{inner}]"
            if isinstance(value, list)
            else f"({inner},)"
            if len(value) == 1
            else f"({inner})"
        )
    return repr(value)


def _decimals(*arrays: np.ndarray) -> int | None:
    """The decimals that print every entry of ``arrays`` exactly (0 .. 6), 4 if none do, None if not real arrays.

    None too if every entry of one array is tiny (below 1e-3): :func:`_fmt` then prints 3 significant digits, so a
    covariance of 1e-7 m^2 never shows as 0.0000. A wrong answer's got and expected lines use the same number, so 8.5 is not printed beside 4.25 as
    [8.5] against [4.25] with another precision, nor 0.00425 rounded to 0.0043.
    """
    if not all(
        isinstance(a, np.ndarray)
        and a.dtype.kind in "biuf"
        and 0 < a.size <= _MAX_PRINTED
        and np.isfinite(a).all()
        for a in arrays
    ):
        return None
    values = np.concatenate([a.astype(float).ravel() for a in arrays])
    for d in range(7):
        if np.allclose(values, np.round(values, d), rtol=1e-12, atol=0):
            return d
    if any(
        0 < np.abs(a).max() < 1e-3 for a in arrays
    ):  # tiny, as a covariance in m^2 (even beside a wrong answer 1e6 larger, in mm^2): 3 significant digits
        return None
    return 4


def _fixed(value: np.ndarray, decimals: int) -> str:
    """An array with ``decimals`` decimals on every entry: [5.00, 8.50, 2.00] beside [2.50, 4.25, 1.00]."""
    value = np.where(np.round(value.astype(float), decimals) == 0, 0.0, value.astype(float))
    text = np.array2string(
        value, precision=decimals, floatmode="fixed", suppress_small=True, separator=", "
    )
    text = re.sub(
        r"(\d)\.(?=[,\]\s]|$)", r"\1", text
    )  # 0 decimals: [5, 30, 22], not [5., 30., 22.]
    if value.ndim == 1:
        text = "[" + ", ".join(item.strip() for item in text[1:-1].split(",")) + "]"
    return text


def _fmt_like(value: Any, like: Any) -> str:
    """``_fmt`` of ``value``, with as many decimals as ``like`` (its got or expected partner) needs."""
    if isinstance(value, (tuple, list)) and isinstance(like, (tuple, list)):
        if len(value) == len(like):
            inner = [_fmt_like(v, w) for v, w in zip(value, like, strict=True)]
            opening, closing = ("[", "]") if isinstance(value, list) else ("(", ")")
            return opening + ", ".join(inner) + closing
    if isinstance(value, np.ndarray) and value.dtype.kind in "biu":
        return _fmt(
            value
        )  # an integer answer prints as integers, 0 not 0.0: its dtype may be the slip
    if isinstance(value, np.ndarray) and isinstance(like, np.ndarray) and value.shape == like.shape:
        decimals = _decimals(value, like)
        if decimals is not None:
            return _fixed(value, decimals)
    return _fmt(value)


def _shown(value: Any, like: Any = None) -> str:
    """``_fmt`` for a message's got/expected line: a multi-line array continues under its first line.

    A tuple or list with a multi-line part shows one part per line, each continuing under its own
    first line, so the rows of an array stay under the ``[[`` they belong to. With ``like`` (the
    answer it is printed beside) each array gets the decimals both need, so the two lines compare
    digit by digit.
    """

    def fmt(v, w=None):
        return _fmt(v) if like is None else _fmt_like(v, w)

    text = fmt(value, like)
    if isinstance(value, (tuple, list)) and "\n" in text and len(value) > 1:
        opening, closing = ("[", "]") if isinstance(value, list) else ("(", ")")
        partners = (
            like
            if isinstance(like, (tuple, list)) and len(like) == len(value)
            else [None] * len(value)
        )
        parts = [
            fmt(v, w).replace("\n", "\n" + " " * 12) for v, w in zip(value, partners, strict=True)
        ]
        return opening + (",\n" + " " * 12).join(parts) + closing  # each part under the first one
    return text.replace("\n", "\n" + " " * 11)


def _input_text(name: str, args: tuple) -> str:
    """The test input as a message shows it: the exercise's own summary, else each argument printed."""
    exercise = EXERCISES.get(name)
    if exercise is not None and exercise.describe_input is not None:
        return exercise.describe_input(args)
    return _fmt(args)


def _copy_one(a: Any) -> Any:
    """``a`` with every array in it copied, also inside tuples and lists (a pair of frames, a list of pairs)."""
    if isinstance(a, np.ndarray):
        return np.array(a)
    if isinstance(a, (tuple, list)):
        return type(a)(_copy_one(x) for x in a)
    return a


def _copy(args: tuple) -> tuple:
    """A copy of every argument: students must not corrupt the reference's inputs by editing in place."""
    return tuple(_copy_one(a) for a in args)


def _same_input(before: Any, after: Any) -> bool:
    """Whether ``after`` still holds ``before``'s arrays unchanged, also inside tuples and lists."""
    if isinstance(before, np.ndarray):
        return before.shape == np.shape(after) and np.array_equal(
            before, after, equal_nan=before.dtype.kind in "fc"
        )
    if isinstance(before, (tuple, list)):
        return (
            isinstance(after, (tuple, list))
            and len(before) == len(after)
            and all(_same_input(b, a) for b, a in zip(before, after, strict=True))
        )
    return True


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


def _inputs_changed(original: tuple, passed: tuple) -> list[int]:
    """Positions of the array arguments that differ, after the student's call, from the originals."""
    return [
        k
        for k, (before, after) in enumerate(zip(original, passed, strict=True))
        if not _same_input(before, after)
    ]


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
    names = [_parameter_name(student_function, k) for k in changed]
    what = names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]
    inputs, arrays, it = (
        ("input", "array", "it") if len(names) == 1 else ("inputs", "arrays", "they")
    )
    first = _parameter_name(student_function, changed[0]).strip("`")
    a = first if first.isidentifier() else "x"
    taken = {n.strip("`") for n in names}
    k = "c" if a == "d" else "d"  # the added constant's name must not be the argument's own
    sc = next(c for c in ("L", "s", "t") if c != a and c not in taken)  # nor the scale's
    # arrays inside a tuple or a list (a pair of frames, a list of pairs) get examples of their own
    if not isinstance(args[changed[0]], np.ndarray):
        examples, new = (
            f"`a /= a[2, 2]`, `a -= m` or `a[0, 0] = 0` on one of the arrays in `{a}`",
            "`a / a[2, 2]`, `a - m`",
        )
        copy = "convert each array to a new one first (`a = np.array(a, dtype=float)` always copies; np.asarray returns the same array, not a copy, when it is float64 already)"
    elif np.ndim(args[changed[0]]) == 1 and a in (
        "image",
        "img",
        "raw",
        "frame",
    ):  # an image, flattened
        examples, new = (
            f"`np.clip({a}, 0, 1, out={a})`, `{a} *= {sc}`, `{a}[{a} > 1] = 1`",
            f"`np.clip({a}, 0, 1)`, `{a} * {sc}`",
        )
    elif np.ndim(args[changed[0]]) == 1:
        examples, new = (
            f"`{a}[1] = -{a}[1]`, `{a} += {k}`, `{a}.sort()`",
            f"`{a} + {k}`, `np.append({a}, 1.0)`",
        )
    elif np.shape(args[changed[0]]) == (
        3,
        3,
    ):  # a matrix: its normalisation is the usual in-place slip
        matrix = np.asarray(args[changed[0]], dtype=float)
        # a homography is normalised by its (2, 2) entry; a conic or a dual conic (C*inf's image has
        # a (2, 2) entry of 0, or nearly) by its norm, so the hint never suggests a division by 0
        by = f"{a}[2, 2]" if not np.allclose(matrix, matrix.T) else f"np.linalg.norm({a})"
        examples, new = f"`{a} /= {by}`, `{a}[:, 0] = ...`, `{a} += {k}`", f"`{a} / {by}`"
    else:
        examples, new = f"`{a} *= {sc}`, `{a}[:, 0] = ...`, `{a} += {k}`", f"`{a} * {sc}`"
    exercise = EXERCISES.get(name)
    if exercise is not None and first in exercise.in_place_examples:
        examples, new = exercise.in_place_examples[first]
    if isinstance(args[changed[0]], np.ndarray):
        copies = [
            f"`{x} = np.array({x}, dtype=float)`"
            for x, c in zip((n.strip("`") for n in names), changed, strict=True)
            if x.isidentifier() and isinstance(args[c], np.ndarray)
        ] or [f"`{a} = np.array({a}, dtype=float)`"]
        copy = f"work on a copy first ({', '.join(copies)})"
    return (
        f"{name}: your function changed its {inputs} {what} in place (test input {i + 1} of {n}); the caller's "
        f"{arrays} must come back as {it} went in\n"
        f"  likely cause: an in-place operation on an argument ({examples}); "
        f"build a new array instead ({new}), or {copy}"
    )


def _run_student(
    name: str, student_function: Callable[..., Any], args: tuple, i: int, n: int, seconds: float
) -> Any:
    """The student's answer on test input ``i`` of ``n``.

    AssertionError on a crash, a run longer than ``seconds`` or an input changed in place.
    """
    passed = _copy(args)
    try:
        with time_limit(seconds):
            got = student_function(*passed)
    except NotImplementedError:
        raise
    except OutOfTime:
        raise CheckFailed(
            f"{name}: your function was still running after {seconds:g} s on test input {i + 1} of {n}, "
            f"so the check stopped it\n"
            f"  input    {_input_text(name, args)}\n"
            f"  likely cause: a loop that never ends (a `while` whose condition stays true?)"
        ) from None
    except Exception as exc:
        raise CheckFailed(
            f"{name}: your function raised {type(exc).__name__}: {exc}\n"
            f"  on input {_input_text(name, args)}" + _exercise_exception_hint(name, exc, args)
        ) from exc
    changed = _inputs_changed(args, passed)
    if changed:
        raise CheckFailed(_in_place_message(name, student_function, changed, i, n, args))
    return got


def _hidden_by_rounding(vector: np.ndarray) -> bool:
    """True when an entry that is not zero (above 1e-9 of the largest) prints as 0.0000."""
    v = np.abs(np.asarray(vector, dtype=float))
    return bool(np.any((v > 1e-9 * v.max()) & (np.round(v, 4) == 0)))


def _expected_shown(exercise: Exercise, got: Any, expected: Any) -> tuple[Any, str]:
    """The expected answer as a failed check shows it, and a note on its scale.

    A scale-free answer is shown at the student's scale when theirs points nearly the same way,
    else at unit length: stretching it to a far-off answer's scale would only confuse, and so
    would a rescaled vector whose small entries print as 0.0000 (a horizon read as l_inf).
    """
    if exercise.compare is not same_up_to_scale and not exercise.up_to_scale:
        return expected, ""
    shown = rescaled_to(got, expected)  # compare after fixing the free scale
    if shown is not None and not _hidden_by_rounding(shown):
        return shown, "  (rescaled to your answer's scale)"
    e = np.asarray(expected, dtype=float)
    if np.any(e) and np.isfinite(e).all():
        return e / np.linalg.norm(e), "  (unit length; any non-zero scale is accepted)"
    return expected, ""


def _got_at_unit_length(got: Any, shown: Any) -> Any:
    """The student's scale-free answer at unit length, signed like ``shown``: both print at one scale.

    Returned unchanged when it cannot be (not a finite non-zero array of ``shown``'s shape).
    """
    try:
        g = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        return got
    if g.shape != np.shape(shown) or not np.isfinite(g).all() or not np.any(g):
        return got
    g = g / np.linalg.norm(g)
    return -g if np.sum(g * np.asarray(shown, dtype=float)) < 0 else g


def _shown_with_tolerance(exercise: Exercise, got: Any, expected: Any) -> tuple[Any, str, Any]:
    """:func:`_expected_shown`, and the tolerance a failed check names beside it.

    A scale-free answer is compared as a unit vector (:func:`same_up_to_scale`), so each entry's
    allowance is a share of the vector's length, not numpy's default ``rtol``.
    """
    tolerance = exercise.compare.tolerance if isinstance(exercise.compare, SameArray) else None
    shown, scaled = _expected_shown(exercise, got, expected)
    if scaled:
        tolerance = Tolerance(
            0.0,
            SCALE_FREE_RTOL * float(np.linalg.norm(shown)),
            f"{SCALE_FREE_RTOL:g} of the vector's length, after fixing the scale",
        )
    return shown, scaled, tolerance


def _likely_cause(exercise: Exercise, args: tuple, got: Any, expected: Any, run=None) -> str:
    """The exercise's diagnosis of a wrong answer; a plain hint if the answer's form defeats it.

    A diagnosis is written for the slips its table names; an answer of an unforeseen form (a
    (1,) array where a number belongs, a nested list) must still get a wrong-answer report, not a
    traceback from inside the check.
    """
    try:
        if exercise.diagnosis_runs:
            return exercise.diagnose(args, got, expected, lambda *again: run(again))
        return exercise.diagnose(args, got, expected)
    except Exception:  # a failure of the diagnosis itself, never of the student's code
        return (
            f"the check could not diagnose this answer ({with_article(got)}): return it in the form "
            "of the expected value above, then compare the two term by term"
        )


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
            # one write, text and newline together: print's two writes could reach the notebook as two
            # stream outputs, the second a lone newline
            print(
                f"{name}: not attempted yet. Fill in the function above, run its cell, then this one.\n",
                end="",
            )
            return CheckResult(name, False)
        if got is None:
            raise CheckFailed(returned_none(name, i + 1, expected))
        wrong_type = type_problem(got, expected, exercise.ndarray_only)
        if wrong_type:
            raise CheckFailed(
                f"{name}: wrong type of answer on test input {i + 1} of {len(cases)}\n"
                f"  input    {_input_text(name, args)}\n"
                f"  got      {_shown(got)}  ({with_article(got)})\n"
                f"  expected {_shown(expected)}\n"
                f"  likely cause: {wrong_type}"
            )
        too_coarse = precision_problem(got, expected)
        if too_coarse:
            raise CheckFailed(
                f"{name}: answer too imprecise on test input {i + 1} of {len(cases)}\n"
                f"  input    {_input_text(name, args)}\n"
                f"  got      {_shown(as_array(got))}\n"
                f"  likely cause: {too_coarse}"
            )
        if not exercise.compare(got, expected):
            shown, scaled, tolerance = _shown_with_tolerance(exercise, got, expected)
            got_shown = _got_at_unit_length(got, shown) if "unit length" in scaled else got
            run_again = partial(
                _run_student, name, student_function, i=i, n=len(cases), seconds=seconds
            )
            raise CheckFailed(
                f"{name}: wrong answer on test input {i + 1} of {len(cases)}\n"
                f"  input    {_input_text(name, args)}\n"
                f"  got      {_shown(as_array(got_shown), shown)}"
                + ("  (unit length, sign of the expected)" if got_shown is not got else "")
                + f"\n  expected {_shown(shown, as_array(got_shown))}{scaled}\n"
                + worst_mismatch(got_shown, shown, tolerance)
                + f"  likely cause: {_likely_cause(exercise, args, got, expected, run_again)}"
            )
    if exercise.follow_up is not None:
        problem = exercise.follow_up(
            lambda *args: _run_student(
                name, student_function, args, len(cases), len(cases) + 1, seconds
            )
        )
        if problem:
            raise CheckFailed(
                f"{name}: wrong answer on a further test (all {len(cases)} test inputs passed): {problem}"
            )
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
    own = _call_hint(name, exc, args) if exercise is not None else ""
    if not own and exercise is not None and exercise.exception_hint:
        own = exercise.exception_hint(exc, args)
    return f"\n  likely cause: {own}" if own else _exception_hint(exc)


def _call_hint(name: str, exc: Exception, args: tuple) -> str:
    """The cause when the call itself failed: the student's function takes another number of arguments.

    Python raises that TypeError at the call, so its traceback holds no frame of the student's code.
    """
    at_call = exc.__traceback__ is not None and exc.__traceback__.tb_next is None
    if not (isinstance(exc, TypeError) and at_call and "argument" in str(exc)):
        return ""
    exercise = EXERCISES[name]
    try:
        wanted = ", ".join(inspect.signature(exercise.teaching or exercise.reference).parameters)
    except (TypeError, ValueError):
        wanted = ""
    n = len(args)
    return (
        f"the wrong number of parameters: the check calls your function as {name}({wanted}), {n} "
        f"argument{'s' * (n != 1)}, as the prompt's def line has them; give your def exactly those parameters"
    )


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
        return (
            "\n  likely cause: an index past the end of an axis (the error names the axis and its size)."
            " Python counts from 0: an axis of size n has indices 0 .. n - 1, so counting columns from 1"
            " fails at the last one (the columns of an (N, 3) array are 0, 1 and 2), and so does k + 1"
            " when k is already the last index"
        )
    if isinstance(exc, TypeError) and "converted to Python scalars" in str(exc):
        return (
            "\n  likely cause: int() or float() of an array: they convert one number, and the array holds several;"
            " convert every entry at once (np.rint(a).astype(int), a.astype(float)) or take one entry, a[k]"
        )
    if (
        isinstance(exc, ValueError)
        and "broadcast" in str(exc)
        and re.search(r"\(\d+,0\)|\(0,", str(exc))
    ):
        return one_based + " (a slice past the last column, X[:, 3:4], is empty)"
    if isinstance(exc, ValueError) and "broadcast" in str(exc):
        return "\n  likely cause: " + _broadcast_hint(str(exc))
    if isinstance(exc, ValueError) and "inhomogeneous" in str(exc):
        return f"\n  likely cause: an array beside numbers, as in np.array([p, 1]), makes no array of numbers: {JOIN_HINT}"
    if isinstance(exc, ValueError) and "matmul" in str(exc):
        return (
            "\n  likely cause: the sizes of a matrix product do not fit (A @ B needs A's columns = B's rows)."
            " With points as rows, a matrix M acts as X @ M.T, not X @ M; and lift points to homogeneous"
            " coordinates (append a column of ones) before a 3 x 4 or 3 x 3 projective matrix"
        )
    return ""


def _broadcast_hint(text: str) -> str:
    """The shared cause of a broadcasting ValueError, naming the two shapes numpy could not pair up.

    numpy pairs shapes from the last axis, and each pair of sizes must be equal or 1. An (N,) array
    beside an (N, k) one, N != k, is the flat column ``X[:, 2]`` divided into ``X[:, :2]``: that case
    gets its fix; any other pair gets the rule and the two shapes, never a cause it cannot know.
    """
    tail = text.split("shapes", 1)[-1]
    shapes = re.findall(r"\(([\d,]*)\)->" if "->" in tail else r"\(([\d,]*)\)", tail)
    sizes = [tuple(int(n) for n in shape.split(",") if n) for shape in shapes[:2]]
    named = " and ".join(f"({', '.join(map(str, s))}{',' * (len(s) == 1)})" for s in sizes)
    flat_column = (
        len(sizes) == 2
        and sorted(map(len, sizes)) == [1, 2]
        and max(sizes, key=len)[0] == min(sizes, key=len)[0] != max(sizes, key=len)[1]
    )
    if flat_column:
        return (
            f"a broadcasting slip: shapes {named} do not pair up. An (N,) column such as X[:, 2] divided into"
            " an (N, 2) array lines up with its last axis, not its rows; keep it 2-D: X[:, 2:3], X[:, 2, None]"
            " or keepdims=True"
        )
    matrix = len(sizes) == 2 and any(len(s) == 2 and s[0] == s[1] for s in sizes)
    return (
        f"a broadcasting slip: numpy cannot pair up the shapes {named or 'of the two arrays'}. Entry-by-entry"
        " operations (+, -, *, /) match shapes from the last axis, and each pair of sizes must be equal or 1;"
        " print the shapes of the arrays on that line"
        + (" (a square matrix acts on points with @, not *: X @ A.T)" if matrix else "")
    )


def _public_name(function: Callable[..., Any]) -> str:
    """The shortest dotted name a student can type for ``function``.

    Camlab.to_homogeneous, not camlab.projective.plane.to_homogeneous, when the package re-exports
    it (the same object).
    """
    parts = function.__module__.split(".")
    for k in range(1, len(parts) + 1):
        module = sys.modules.get(".".join(parts[:k]))
        if module is not None and getattr(module, function.__qualname__, None) is function:
            return f"{'.'.join(parts[:k])}.{function.__qualname__}"
    return f"{function.__module__}.{function.__qualname__}"


def solution_source(name: str) -> str:
    """The text :func:`solution` prints: the teaching solution of ``name`` (the library's source if it has none)."""
    exercise = EXERCISES[name]
    reference = exercise.reference
    where = _public_name(reference)
    if exercise.teaching is None:
        return inspect.getsource(reference)
    if exercise.solution_note:
        return inspect.getsource(exercise.teaching) + "\n" + exercise.solution_note.rstrip() + "\n"
    if reference.__name__.startswith("_"):  # a private helper: name it, and say what it computes
        summary = (inspect.getdoc(reference) or "").split("\n")[0]
        return (  # a private helper is no place to send a student: say what it computes, in public names
            inspect.getsource(exercise.teaching)
            + f"\n# the check compares your answer with camlab's own, tested reference.\n# {summary}\n"
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


class Mistake(NamedTuple):
    """One row of a diagnosis table: a typical mistake, the answer it gives, and the hint that names it.

    A diagnosis that asks "is the answer exactly what this mistake gives?" for many mistakes lists
    them as rows, checked in order by :func:`first_mistake`, instead of a chain of ``if``.

    ``answer(context)`` is what a student who made this mistake returns on the test input that
    ``context`` describes (the exercise's own record of the input and the numbers derived from it),
    or None where the mistake cannot show on that input (it would give the right answer). In a table
    checked with ``same=None`` it is instead the test itself: whether the answer shows the mistake.
    ``hint`` is the likely cause, or ``hint(context)`` when it quotes this input's numbers.
    ``name`` identifies the row, for :func:`mistake_variant` and for readers.
    """

    name: str
    answer: Callable[[Any], Any]
    hint: str | Callable[[Any], str]


def first_mistake(
    mistakes: Sequence[Mistake],
    context: Any,
    got: Any = None,
    same: Callable[[Any, Any], bool] | None = None,
) -> str | None:
    """The hint of the first of ``mistakes`` (in table order) that the answer ``got`` shows, else None.

    A row matches when ``same(got, row.answer(context))`` is true, or, with ``same=None``, when
    ``row.answer(context)`` itself is. Rows are built only until one matches, and a row whose answer
    is None is passed over.
    """
    for mistake in mistakes:
        answer = mistake.answer(context)
        if answer is None:
            continue
        if same(got, answer) if same is not None else bool(answer):
            return mistake.hint(context) if callable(mistake.hint) else mistake.hint
    return None


def mistake_variant(
    mistakes: Sequence[Mistake], name: str, context: Callable[..., Any]
) -> Callable[..., Any]:
    """The row ``name`` of ``mistakes`` as a student's wrong function, for ``Exercise.wrong_variants``.

    ``context(*args)`` builds the table's context from the function's arguments, as the diagnosis does;
    the test suite then proves that the diagnosis names the mistake the row describes.
    """
    rows = [m for m in mistakes if m.name == name]
    if len(rows) != 1:
        raise KeyError(f"mistake_variant: {len(rows)} rows named {name!r}; expected exactly one")
    answer = rows[0].answer
    return lambda *args: answer(context(*args))
