"""What makes an answer right or wrong before any exercise looks at it.

Its type, its precision, its shape, and the comparisons within a tolerance.

:func:`type_problem` names an answer that is no numbers (text, complex, a list beside an array),
:func:`precision_problem` one too coarse to judge (float16), :func:`shape_problem` and :func:`unit_slip` the
commonest slips; :class:`Tolerance` and :class:`SameArray` compare float answers in float64, holding a
float32 answer to its own precision; :func:`worst_mismatch` names the worst entry for a message.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

JOIN_HINT = "join an array and numbers with np.append(p, 1.0), np.concatenate or np.hstack"


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
    if (
        isinstance(got, tuple)
        and len(got) > 1
        and isinstance(expected, np.ndarray)
        and any(isinstance(x, np.ndarray) and x.shape == expected.shape for x in got)
    ):
        return (
            f"you returned {len(got)} values (`return a, b` makes a tuple); {wanted}, "
            "only the answer itself"
        )
    if _stacks_into(got, expected):
        return (
            f"you returned a pair (matrix, vector), such as (R, t); {wanted}: join them "
            "side by side, np.column_stack([R, t])"
        )
    try:
        np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        if isinstance(got, (list, tuple)):
            return (
                f"you returned a {kind} that numpy cannot turn into one array of numbers (an array beside "
                f"numbers, such as [p, 1]?); {wanted}: {JOIN_HINT}"
            )
        return f"you returned a {kind}, which is not numbers; {wanted}"
    if ndarray_only and isinstance(expected, np.ndarray) and not isinstance(got, np.ndarray):
        return f"you returned a {kind}; {wanted}: wrap the values in np.array(...)"
    return None


def _stacks_into(got: Any, expected: Any) -> bool:
    """Whether ``got`` is a pair (matrix, vector), such as (R, t), that np.column_stack joins into ``expected``."""
    if not (isinstance(got, (tuple, list)) and len(got) == 2 and isinstance(expected, np.ndarray)):
        return False
    try:
        a, b = (np.asarray(x, dtype=float) for x in got)
        return (
            a.ndim == 2 and a.shape != b.shape and np.column_stack([a, b]).shape == expected.shape
        )
    except (TypeError, ValueError):
        return False


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


def returned_none(name: str, case: int, expected: Any) -> str:
    """The message for a function that returned None on test input ``case`` (from 1).

    The usual cause is a forgotten ``return``; where the answer is NaN, None was meant as "no
    answer", and the student is told to return NaN, which keeps the answer's type.
    """
    try:
        numbers = np.asarray(expected, dtype=float)
    except (TypeError, ValueError):  # text or ragged: no NaN to stand for
        numbers = np.zeros(0)
    # a number or a pair (a focal, a focal per image) meant as "none": an array holding a NaN
    # and returned as None is far likelier a forgotten return, and its list would flood the message
    if np.isnan(numbers).any() and numbers.size <= 4:
        cause = (
            f"the answer here is {numbers.tolist()}: NaN marks a value this input does not define. Return "
            f"NaN in its place (float('nan') or np.nan), not None: NaN is a float, so the answer keeps its type"
        )
    else:
        cause = "did you forget `return`? The last line should be `return <result>`."
    return f"{name}: your function returned None on test input {case}\n  likely cause: {cause}"


def with_article(value: Any) -> str:
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
    a_kind = with_article(got)
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
            f"or arrays mixed with numbers?); {wanted}: {JOIN_HINT}"
        )
    return None


def as_array(value: Any) -> Any:
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
    so the count agrees with the verdict. The worst entry is the one that exceeds its own allowance
    ``atol + rtol |expected|`` the most, chosen among the entries that fail: an entry inside the
    tolerance is never named, however large its absolute difference. Values that print alike at
    6 digits are shown in full.
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
    if isinstance(expected, (tuple, list)) and e.ndim == 3:  # a pair of matrices, e.g. (K, R)
        where = "(matrix, row, column)"
    else:
        where = {2: "(row, column)", 3: "(row, column, channel)"}.get(e.ndim, "index")
    tol = (tolerance or Tolerance()).for_answer(got, expected)
    failing = ~tol.close(g, e)
    wrong = int(np.sum(failing))
    if (
        not wrong
    ):  # every entry within the tolerance: the verdict rests on something else (named by the hint)
        return ""
    with np.errstate(
        divide="ignore", invalid="ignore", over="ignore"
    ):  # how many allowances past: 0 allowance -> inf
        excess = np.where(failing, err / (tol.atol + tol.rtol * np.abs(e)), -1.0)
    excess[failing & ~np.isfinite(excess)] = np.inf
    index = np.unravel_index(int(np.argmax(excess)), e.shape)
    shown_got, shown_expected = f"{g[index] + 0.0:.6g}", f"{e[index] + 0.0:.6g}"  # + 0.0: no "-0"
    if shown_got == shown_expected:
        shown_got, shown_expected = repr(float(g[index])), repr(float(e[index]))
    if _entry_is_none(got, index):  # float(None) is NaN: "got nan, expected nan" would confuse
        shown_got = "None"
    at = f"entry {int(index[0])}" if e.ndim == 1 else f"{where} {tuple(int(i) for i in index)}"
    return (
        f"  worst    {at}: got {shown_got}, expected {shown_expected}"
        f" ({wrong} of {e.size} entries differ by more than {tol})\n"
    )


def _entry_is_none(got: Any, index: tuple) -> bool:
    """Whether the entry ``index`` of ``got`` (a nested sequence or an array) is None."""
    try:
        return np.asarray(got, dtype=object)[index] is None
    except (TypeError, ValueError, IndexError):
        return False


SCALE_FREE_RTOL = 1e-6
""":func:`same_up_to_scale`'s default: the two unit vectors may differ by this much (Euclidean norm)."""


def _overflowed(g: np.ndarray) -> bool:
    """True when an entry is within 1e8 of the largest float.

    Such an entry is an overflow, or an inf replaced by np.nan_to_num, never a coordinate: its
    square overflows, and no scale makes it comparable.
    """
    return bool(np.abs(g).max(initial=0.0) > np.finfo(float).max / 1e8)


def same_up_to_scale(got: Any, expected: np.ndarray, rtol: float = SCALE_FREE_RTOL) -> bool:
    """True if ``got`` equals ``expected`` times some non-zero scalar (homogeneous equality)."""
    g = np.asarray(got)
    if np.iscomplexobj(
        g
    ):  # e.g. a null vector from np.linalg.eig: real only if its imaginary part is ~0
        if not np.all(np.abs(g.imag) <= 1e-12 * max(1.0, float(np.abs(g).max()))):
            return False
        g = g.real
    g = np.asarray(g, dtype=float)
    e = np.asarray(expected, dtype=float)
    if g.shape != e.shape or not np.isfinite(g).all() or not np.any(g) or _overflowed(g):
        return False
    g = g / np.linalg.norm(g)
    e = e / np.linalg.norm(e)
    return bool(min(np.linalg.norm(g - e), np.linalg.norm(g + e)) <= rtol)


def rescaled_to(got: Any, expected: Any) -> np.ndarray | None:
    """``expected`` times the scale that best matches ``got`` (least squares), or None if none does.

    A scale-free check compares ``got`` with ``s * expected`` for the best ``s``; showing the raw
    ``expected`` beside ``got`` (and naming its worst raw entry) would report differences that are
    only the scale. None when the shapes differ, ``got`` is not finite, either is all zeros, or
    ``got`` points far from ``expected`` (cosine of their angle below 0.9): a far-off answer
    would stretch ``expected`` to a scale that only confuses. None too when ``got`` is over 1e9
    times longer (a homography divided by an h33 that should be 0): stretched that far, the
    reference's own rounding noise would print as large numbers.
    """
    try:
        g = np.asarray(got, dtype=float)
        e = np.asarray(expected, dtype=float)
    except (TypeError, ValueError):
        return None
    if (
        g.shape != e.shape
        or not np.isfinite(g).all()
        or not np.any(g)
        or not np.any(e)
        or _overflowed(g)
    ):
        return None
    if abs(np.sum(g * e)) < 0.9 * np.linalg.norm(g) * np.linalg.norm(e):
        return None
    if np.linalg.norm(g) > 1e9 * np.linalg.norm(
        e
    ):  # h / h33 with h33 ~ 1e-17: its noise would show
        return None
    return e * float(np.sum(g * e) / np.sum(e * e))


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
    note: str = ""
    """How a failed check words the tolerance, when ``rtol`` and ``atol`` alone would mislead (a
    scale-free comparison of unit vectors); empty: ``rtol ..., atol ...``."""

    def for_answer(self, got: Any, expected: Any) -> Tolerance:
        eps = _coarsest_eps(got)
        if eps <= np.finfo(np.float64).eps:
            return self
        slack = REDUCED_PRECISION_SLACK * eps
        e = np.abs(np.asarray(expected, dtype=float))
        scale = float(e[np.isfinite(e)].max(initial=0.0))
        return Tolerance(max(self.rtol, slack), max(self.atol, slack * scale), self.note)

    def close(self, got: Any, expected: Any) -> np.ndarray:
        """Per entry: within the tolerance (in float64)."""
        return np.isclose(
            np.asarray(got, dtype=float),
            np.asarray(expected, dtype=float),
            rtol=self.rtol,
            atol=self.atol,
        )

    def __str__(self) -> str:
        return self.note or f"rtol {self.rtol:.1g}, atol {self.atol:.1g}"


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


def shape_unpack_hint(exc: Exception, name: str) -> str:
    """``h, w = shape`` on a shape with channels, (h, w, 3): Python says only 'too many values to unpack'."""
    if isinstance(exc, ValueError) and "too many values to unpack" in str(exc):
        return (
            f"a shape may carry channels, (h, w, 3): `h, w = {name}` (a shape) then has three values for two names. "
            f"Take the first two, `h, w = {name}[:2]`."
        )
    return ""


def diagonal_only_hint(got: Any, expected: Any, carries: str) -> str | None:
    """The cause when a covariance comes back as its diagonal: n one-sigmas, or n variances.

    ``carries`` ends the variances' hint: what the off-diagonal terms carry (the correlations
    of ...). None when ``got`` is not n numbers.
    """
    exp = np.asarray(expected, dtype=float)
    n = exp.shape[0]
    g = np.asarray(got) if got is not None else None
    if g is None or g.shape != (n,):
        return None
    if g.dtype.kind in "fiu" and np.allclose(g, np.sqrt(np.abs(np.diag(exp))), rtol=1e-4, atol=0):
        return (
            f"you returned {n} one-sigmas (the square roots of the diagonal): return the whole "
            f"({n}, {n}) covariance, variances on its diagonal, whose off-diagonal terms carry the "
            "correlations."
        )
    return (
        f"you returned {n} numbers, the variances alone (the diagonal): return the whole ({n}, {n}) "
        f"covariance, whose off-diagonal terms carry {carries}."
    )
