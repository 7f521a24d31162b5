"""Lesson 00's warm-up exercise lift: one image point in homogeneous coordinates, (x, y) -> (x, y, 1).

Its diagnosis reads two tables of :class:`~camlab.exercises._core.Mistake` rows: :data:`SHAPE_MISTAKES`
for an answer of the wrong shape, :data:`LIFT_MISTAKES` for three numbers that are wrong as a whole (w
first, scaled, shifted); what is left is judged coordinate by coordinate, x and y by
:func:`~camlab.exercises.start_here._lift_causes.xy_slip`, w here. An error the student's code raises
is named by :mod:`._lift_raised`.
"""

from __future__ import annotations

from functools import cached_property
from types import SimpleNamespace

import numpy as np

from ... import projective
from .._answers import same_array, shape_problem
from .._core import Exercise, Mistake, first_mistake, register_exercise
from ._lift_causes import APPEND, KEEP, ONE_POINT, cases, xy_slip
from ._lift_raised import batch_code_hint


def _describe_point(args: tuple) -> str:
    """The test input as the student could type it: ``p = np.array([2.5, 4.25])``."""
    p = np.asarray(args[0], dtype=float)
    return "p = np.array([" + ", ".join(repr(float(c)) for c in p) + "])"


def _shape(s) -> tuple:
    return s.shape


def _two(s) -> bool:
    return s.shape == (2,)


# Checked in order on an answer of the wrong shape: ``s.shape`` is its shape, ``s.g`` its numbers
# flattened, ``s.p`` the point; each row's test says whether the answer shows the slip.
SHAPE_MISTAKES = (
    Mistake(
        "the point itself",
        lambda s: _two(s) and np.allclose(s.g, s.p),
        (
            "you returned the 2 coordinates you were given (the point itself, or (x, y, 1) divided back by w); "
            f"lifting adds the third, w = 1: {APPEND}"
        ),
    ),
    Mistake(
        "y missing",
        lambda s: (
            _two(s)
            and np.isclose(s.g[-1], 1.0)
            and np.isclose(s.g[0], s.p[0])
            and not np.isclose(s.p[1], 1.0)
        ),
        (
            "y went missing: you appended w = 1 to x alone. A slice stops before its end index, so p[:1] "
            f"keeps only p[0]; p[:2], or p itself, keeps x and y: {APPEND}"
        ),
    ),
    Mistake(
        "x missing",
        lambda s: (
            _two(s)
            and np.isclose(s.g[-1], 1.0)
            and np.isclose(s.g[0], s.p[1])
            and not np.isclose(s.p[0], 1.0)
        ),
        (
            "x went missing: you appended w = 1 to y alone (p[1:] starts at index 1, which is y); keep both "
            f"coordinates: {APPEND}"
        ),
    ),
    Mistake(
        "p + 1",
        lambda s: _two(s) and np.allclose(s.g, s.p + 1.0),
        (
            "p + [1] (or p + 1) adds 1 to each coordinate: numpy's + is arithmetic, not the list concatenation "
            f"it is for Python lists; append instead: {APPEND}"
        ),
    ),
    Mistake(
        "a column of ones beside one point",
        lambda s: s.shape == (2, 2),
        (
            f"np.column_stack / np.c_ with a column of ones is batch code: on one point it makes each "
            f"coordinate a row. {ONE_POINT}: append one number, {APPEND}"
        ),
    ),
    Mistake(
        "a batch of one point",
        lambda s: s.shape == (1, 3),
        (
            "a batch holding one point; one point in, one point out: return the (3,) array "
            f"({APPEND}, or your result's row [0])"
        ),
    ),
    Mistake(
        "a column",
        lambda s: s.shape == (3, 1),
        "a column; points are rows in this course: return the (3,) array (.ravel())",
    ),
    Mistake(
        "two 1s",
        lambda s: s.shape == (4,) and np.allclose(s.g[2:], 1.0),
        (
            "you appended two 1s: np.ones(len(p)) counts p's coordinates, not points (len(p) is 2 for one point); "
            f"append a single 1: {APPEND}"
        ),
    ),
)


def _shape_slip(got_shape: tuple, g: np.ndarray, p: np.ndarray) -> str:
    """The likely cause of an answer of the wrong shape: the first row of :data:`SHAPE_MISTAKES` it shows."""
    context = SimpleNamespace(shape=got_shape, g=g, p=p)
    return (
        first_mistake(SHAPE_MISTAKES, context)
        or "append one coordinate, w = 1, to the 2 you were given"
    )


class _Lifted:
    """Three numbers ``g`` answered for the point ``p``, and what the rows of :data:`LIFT_MISTAKES` read."""

    def __init__(self, g: np.ndarray, p: np.ndarray):
        self.g, self.p, self.w = g, p, g[-1]

    @cached_property
    def xy(self) -> str:
        """What is wrong with x and y ('' when they are right)."""
        return xy_slip(self.g[:2], self.p)

    @cached_property
    def offset(self) -> np.ndarray:
        """The answer less the right one, (x, y, 1)."""
        return self.g - np.append(self.p, 1.0)


def _scaled_hint(s: _Lifted) -> str:
    shown = ", ".join(f"{c:g}" for c in s.g)
    return (
        f"({shown}) is the same point scaled by {s.w:g} (homogeneous coordinates are defined up to scale), "
        f"but this exercise fixes w = 1: {KEEP}"
    )


def _shifted_hint(s: _Lifted) -> str:
    d = s.offset[0]
    return (
        f"every entry, w included, is off by {d:+g}: the {d:+g} went onto the whole array "
        f"(np.append(p, 1.0) {'+' if d > 0 else '-'} {abs(d):g}?); lifting only appends w = 1, "
        "and no pixel convention shifts a point here (pixel centres sit at whole numbers, counted from 0)"
    )


# Checked in order on three numbers that are wrong as a whole; each row's test reads a ``_Lifted``.
LIFT_MISTAKES = (
    Mistake(
        "w first",
        lambda s: np.allclose(s.g, [1.0, *s.p]),
        "you put the 1 first; by convention w is the last coordinate: (x, y, 1)",
    ),
    Mistake(
        "reversed",
        lambda s: np.allclose(s.g, [1.0, s.p[1], s.p[0]]),
        "the coordinates came out reversed, (1, y, x) ([::-1] or np.flip reverses an array): keep (x, y, 1)",
    ),
    Mistake(
        "1 between x and y",
        lambda s: np.allclose(s.g, [s.p[0], 1.0, s.p[1]]),
        (
            "the 1 landed between x and y: np.insert(p, 1, ...) inserts before index 1; w is the last "
            f"coordinate, at index len(p) = 2: np.insert(p, 2, 1.0), or {APPEND}"
        ),
    ),
    Mistake(
        "scaled",
        lambda s: s.w not in (0.0, 1.0) and np.allclose(s.g[:2] / s.w, s.p),
        _scaled_hint,
    ),
    Mistake(
        "every entry shifted",
        lambda s: not np.isclose(s.offset[0], 0.0) and np.allclose(s.offset, s.offset[0]),
        _shifted_hint,
    ),
    Mistake(
        "w is x again",
        lambda s: not s.xy and s.w == s.p[0] and s.w != 1,
        (
            "w is x again: np.resize (or np.tile) repeats the array to fill the new length; append the 1 "
            f"instead: {APPEND}"
        ),
    ),
)


def _xy_and_w(s: _Lifted) -> str:
    """What is wrong with x and y and with w, one after the other."""
    w, xy = s.w, s.xy
    if w == 0:
        w_slip = "w = 0 makes an ideal point, a direction (lesson 06 §3), not the point itself: w must be 1"
    elif w != 1:
        w_slip = f"w should be 1, not {w:g}"
    else:
        w_slip = ""
    if not xy:
        return f"x and y are right, but {w_slip}" + ("" if w == 0 else ": append exactly 1")
    if not w_slip:
        return xy if APPEND in xy else f"{xy}; {KEEP}"
    return f"{xy}; and {w_slip}"


def _diagnose(args, got, expected) -> str:
    """The likely cause of a wrong answer.

    Its shape (:data:`SHAPE_MISTAKES`), a slip of the three numbers as a whole
    (:data:`LIFT_MISTAKES`), else what is wrong with x and y and with w.
    """
    problem = shape_problem(
        got, expected
    )  # check() has already named an answer that is not numbers
    g = np.asarray(got, dtype=float).ravel() if problem else np.asarray(got, dtype=float)
    p = np.asarray(args[0], dtype=float)
    if problem and np.shape(got) != np.shape(expected):
        return f"{problem}: {_shape_slip(np.shape(got), g, p)}"
    if problem and np.isnan(g[-1]) and np.allclose(g[:2], p):  # x and y filled in, w left as it was
        return (
            "w is NaN and x and y are right: either you appended NaN (np.append(p, np.nan)), or an array made "
            "with np.empty(3) kept whatever was in memory because w was never filled (here NaN, which the check "
            f"leaves there). w is 1: {APPEND}"
        )
    if problem:
        return problem
    lifted = _Lifted(g, p)
    return first_mistake(LIFT_MISTAKES, lifted) or _xy_and_w(lifted)


def _list_append(p):
    """A list's way to grow, tried on an array (a wrong variant for the tests)."""
    p.append(1.0)
    return p


def _unpack_three(p):
    """``x, y, w = p``: a w the point does not have yet (a wrong variant for the tests)."""
    x, y, w = p
    return np.array([x, y, 1.0])


def _list_grow(p):
    """A list grown by assignment (a wrong variant for the tests)."""
    q = list(p)
    q[2] = 1.0
    return np.array(q)


def _grow_by_assignment(p):
    """MATLAB's way to grow, tried on an array (a wrong variant for the tests)."""
    q = p.copy()
    q[2] = 1.0
    return q


def _empty_unfilled(p):
    """np.empty with w never set: it holds whatever the memory held (a wrong variant for the tests)."""
    out = np.empty(3)
    out[:2] = p
    return out


def _zeros_never_filled(p):
    """An array made for the answer and returned before the point was put in (a wrong variant for the tests)."""
    out = np.zeros(3)
    return out


def _resize_in_place(p):
    """ndarray.resize on the caller's point (a wrong variant for the tests)."""
    p.resize(3, refcheck=True)
    p[2] = 1.0
    return p


def lift(p):
    """Homogeneous coordinates of one image point: append w = 1.

    Parameters
    ----------
    p : (2,) array_like
        One point (x, y), pixels.

    Returns
    -------
    (3,) ndarray
        (x, y, 1).

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 2.2.1.
    """
    return np.append(np.asarray(p, dtype=float), 1.0)


register_exercise(
    Exercise(
        name="lift",
        lesson="00",
        reference=projective.to_homogeneous,
        cases=cases,
        compare=same_array(),
        diagnose=_diagnose,
        ndarray_only=True,
        wrong_variants=(
            (lambda p: np.append(p, 0.0), "ideal point"),
            (lambda p: np.insert(p, 0, 1.0), "w is the last coordinate"),
            (lambda p: p, "the 2 coordinates you were given"),
            (lambda p: np.array([p[1], p[0], 1.0]), "swapped"),
            (lambda p: np.append(np.asarray(p).astype(int), 1), "cast to int"),
            (lambda p: np.append(p, -1.0), "w should be 1, not -1"),
            (lambda p: np.append(p, 2.0), "w should be 1, not 2"),
            (lambda p: 2 * np.append(p, 1.0), "fixes w = 1"),
            (lambda p: -np.append(p, 1.0), "fixes w = 1"),
            (lambda p: np.append(p + 0.5, 1.0), "half-pixel shift"),
            (lambda p: np.append(p - 0.5, 1.0), "half-pixel shift"),
            (lambda p: np.append(p + 1, 1.0), "1-based"),
            (lambda p: np.array([p[0], -p[1], 1.0]), "y points down"),
            (lambda p: np.append(1000 * p, 1.0), "1000 times"),
            (lambda p: np.append(-p, 1.0), "sign flip"),
            (lambda p: np.append(p * np.nan, 1.0), "NaN or inf"),
            (
                lambda p: [p[0], p[1], 1.0],
                "you returned a list; return a numpy array of shape (3,)",
            ),
            (
                lambda p: (p[0], p[1], 1.0),
                "you returned a tuple; return a numpy array of shape (3,)",
            ),
            (lambda p: [p, 1], "np.append(p, 1.0)"),
            (lambda p: "x, y, 1", "you returned a str"),
            (lambda p: np.array([p, 1]), "np.append(p, 1.0)"),
            (lambda p: np.append(p, 1.0).astype(str), "of text"),
            (lambda p: np.array([str(p[0]), str(p[1]), "1"]), "of text"),
            (lambda p: np.append(p, 1.0) + 0j, "complex numbers"),
            (lambda p: np.append(p, 1.0).astype(object), "Python objects"),
            # the worked example's batch code, copied for one point
            (
                lambda p: np.hstack([p, np.ones((len(p), 1))]),
                "np.hstack joins a 1-D array to a 2-D one (a column",
            ),
            (lambda p: np.hstack([p[:, :2], np.ones((len(p), 1))]), "p[0] and p[1]"),
            (lambda p: np.concatenate([p, np.ones((len(p), 1))], axis=1), "no second axis"),
            (lambda p: np.column_stack([p, np.ones(len(p))]), "each coordinate a row"),
            (lambda p: np.c_[p, 1.0], "np.c_ joins columns, so it treats x and y as two rows"),
            (lambda p: np.column_stack([p, 1.0]), "np.column_stack joins columns"),
            (lambda p: np.hstack([p[None], [[1.0]]]), "one point in, one point out"),
            (lambda p: np.append(p, 1.0)[:, None], "a column; points are rows"),
            (lambda p: np.append(p[:1], 1.0), "y went missing"),
            (lambda p: np.append(p, 1.0) + 0.5, "every entry, w included, is off by +0.5"),
            (lambda p: np.append(np.clip(p, 0, [639, 479]), 1.0), "clipped to the image"),
            (lambda p: np.append(np.maximum(p, 0), 1.0), "clipped to the image"),
            (lambda p: np.append(np.floor(p + 0.5), 1.0), "rounded to whole pixels"),
            (lambda p: np.append(p.astype(np.float16), 1.0), "went through float16"),
            (lambda p: np.append(p, np.ones(len(p))), "two 1s"),
            (_empty_unfilled, "or an array made with np.empty(3) kept whatever was in memory"),
            (lambda p: np.append(p, np.nan), "either you appended NaN (np.append(p, np.nan))"),
            (lambda p: np.resize(p, 3), "np.resize (or np.tile) repeats the array"),
            (lambda p: p.reshape(3), "reshape rearranges the numbers"),
            (lambda p: np.hstack([p, [[1.0]]]), "np.hstack joins a 1-D array to a 2-D one"),
            (lambda p: (np.append(p, 1.0),), "a trailing comma, `return x,`, makes a tuple"),
            (_list_grow, "cannot grow a Python list"),
            # index slips, and joining functions that do not append
            (_grow_by_assignment, "cannot grow an array"),
            (lambda p: np.array([p[1], p[2], 1.0]), "counting from 1"),
            (lambda p: np.insert(p, 3, 1.0), "np.insert's position counts from 0"),
            (lambda p: np.insert(p, 1, 1.0), "the 1 landed between x and y"),
            (lambda p: np.vstack([p, 1.0]), "np.vstack stacks its arguments as rows"),
            (lambda p: np.stack([p, [1.0]]), "np.stack puts arrays of the same shape"),
            (_resize_in_place, "p.resize(3) changes the caller's array"),
            # x and y wrong, alone or with w
            (_zeros_never_filled, "the point was never put in it"),
            (lambda p: np.ones(3), "an array of ones"),
            (lambda p: np.r_[p[::-1], 0.0], "swapped: keep the point's order"),
            (
                lambda p: np.r_[p[::-1] + 0.5, 1.0],
                "swapped (keep the point's order, (x, y) = (u, v)), and x and y are off by +0.5",
            ),
            (lambda p: np.r_[p, 1.0][::-1], "reversed"),
            (lambda p: np.r_[-p[0], p[1], 1.0], "x changed sign"),
            (lambda p: np.r_[p[0], p[0], 1.0], "it holds x"),
            (lambda p: np.append(p / p[-1], 1.0), "you divided by p[-1], which is y"),
            (lambda p: np.append(p - p.mean(), 1.0), "subtracted the mean"),
            (lambda p: np.append(np.radians(p), 1.0), "converts degrees to radians"),
            (
                lambda p: np.array([2.5, 4.25, 1.0]),
                "test input 1's point, not this input's: the answer does not depend on p",
            ),
            (_list_append, "no .append method"),
            (lambda p: np.append(np.ceil(p), 1.0), "np.ceil rounds up (2.5 became 3)"),
            (lambda p: np.append(p.round(2), 1.0), "you rounded the result to 2 decimals"),
            (lambda p: np.append(np.round(p, 3), 1.0), "you rounded the result to 3 decimals"),
            (lambda p: np.append(int(p), 1.0), "int() (or float()) converts one number"),
            (_unpack_three, "you unpacked it into three names"),
            (lambda p, w: np.append(p, w), "calls your function as lift(p), 1 argument"),
            (lambda p: p + [1.0], "not the list concatenation"),
            (lambda p: np.concatenate(p, 1), "its second argument is the axis"),
            (lambda p: np.concatenate([p, 1.0]), "the 1 is a bare number"),
        ),
        exception_hint=batch_code_hint,
        describe_input=_describe_point,
        teaching=lift,
    )
)
