"""Lesson 00's exercise divide_by_w: homogeneous rows back to points, each row divided by its own w.

``h`` is an ``(N, 3)`` array of rows (wx, wy, w); the answer is the ``(N, 2)`` array of (x, y). The slip
the lesson warns about is the flat ``h[:, 2]``, shape ``(N,)``: numpy pairs it with the last axis, the
columns, so it raises for N >= 3, silently divides each column by one row's w for N = 2, and happens to
be right for N = 1. The test inputs are N = 3, N = 2 and N = 1 in that order, so the slip raises first,
is named on the second input if the student works round the error, and the third shows why a one-point
test would not catch it. The rows have varied w, one negative, so dividing by |w| shows. A follow-up
feeds a row with w = 0 (a direction, no point): it must come back as no finite point (inf or NaN, as
numpy's x / 0 gives, or a ZeroDivisionError from Python floats), not as the huge finite
numbers of a division by w + eps.
"""

from __future__ import annotations

import re
from types import SimpleNamespace

import numpy as np

from ... import projective
from .._answers import same_array, shape_problem
from .._core import Exercise, Mistake, first_mistake, register_exercise

KEEPDIMS = "h[:, :2] / h[:, 2:] (h[:, 2:] is an (N, 1) column: each row divided by its own w)"


def cases() -> list[tuple[np.ndarray]]:
    """The check's test inputs: three rows, two rows, one row; every w different, one negative.

    Returns
    -------
    list of tuple
        One ``(h,)`` per test input, ``h`` of shape (N, 3).
    """
    return [
        (np.array([[5.0, 8.5, 2.0], [-0.6, 0.3, -0.3], [1279.0, 958.0, 4.0]]),),
        (np.array([[2.0, 4.0, 2.0], [3.0, 5.0, 0.7]]),),  # 3 / 0.7 = 4.2857...: a rounding shows
        (np.array([[7.5, -3.0, 2.5]]),),
    ]


def _flat(s) -> np.ndarray:
    return s.h[:, :2] / s.h[:, 2]


def _same(s, candidate) -> bool:
    candidate = np.asarray(candidate, dtype=float)
    return candidate.shape == s.g.shape and np.allclose(s.g, candidate)


# Checked in order on an (N, 2) answer with the wrong numbers; ``s.h`` is the input, ``s.g`` the answer.
DIVIDE_MISTAKES = (
    Mistake(
        "the flat w",
        lambda s: len(s.h) == 2 and _same(s, _flat(s)),
        (
            "you divided by the flat h[:, 2], shape (N,): numpy lines it up with the last axis, the columns, so "
            "for two points column 0 is divided by row 0's w and column 1 by row 1's (for three points numpy "
            f"raises, for one it happens to be right); keep w a column: {KEEPDIMS}"
        ),
    ),
    Mistake(
        "not divided",
        lambda s: _same(s, s.h[:, :2]),
        f"you dropped w without dividing by it: (wx, wy) is not (x, y) unless w = 1; {KEEPDIMS}",
    ),
    Mistake(
        "multiplied by w",
        lambda s: _same(s, s.h[:, :2] * s.h[:, 2:]),
        f"you multiplied by w; the way back divides: {KEEPDIMS}",
    ),
    Mistake(
        "w over x and y",
        lambda s: _same(s, s.h[:, 2:] / s.h[:, :2]),
        f"the division is upside down, w / x: x = (wx) / w; {KEEPDIMS}",
    ),
    Mistake(
        "one w for every row",
        lambda s: any(_same(s, s.h[:, :2] / s.h[k, 2]) for k in (0, -1)),
        (
            "every row was divided by the same w (h[0, 2] or h[-1, 2], one number): each row has its own w; "
            f"{KEEPDIMS}"
        ),
    ),
    Mistake(
        "divided by x or y",
        lambda s: any(_same(s, s.h[:, :2] / s.h[:, k : k + 1]) for k in (0, 1)),
        (
            "you divided by x or y (column 0 or 1): w is the last column, index 2, since numpy counts "
            f"from 0: {KEEPDIMS}"
        ),
    ),
    Mistake(
        "columns counted from 1",
        lambda s: any(_same(s, s.h[:, 1:3] / s.h[:, k : k + 1]) for k in (0, 2)),
        (
            "you took x and y from columns 1 and 2: columns count from 0, so x is h[:, 0], y is h[:, 1] and w "
            f"is h[:, 2:]: {KEEPDIMS}"
        ),
    ),
    Mistake(
        "divided by the row's length",
        lambda s: _same(s, s.h[:, :2] / np.linalg.norm(s.h, axis=1, keepdims=True)),
        (
            "you divided by each row's length (np.linalg.norm): that scales (wx, wy, w) to a unit vector, not "
            f"to w = 1; the point is where w = 1, so divide by w itself: {KEEPDIMS}"
        ),
    ),
    Mistake(
        "divided by |w|",
        lambda s: _same(s, s.h[:, :2] / np.abs(s.h[:, 2:])),
        (
            "you divided by |w|: a negative w is allowed ((-0.6, 0.3, -0.3) is the point (2, -1)), and its "
            f"sign must divide too: {KEEPDIMS}"
        ),
    ),
    Mistake(
        "x and y swapped",
        lambda s: _same(s, (s.h[:, :2] / s.h[:, 2:])[:, ::-1]),
        "x and y came out swapped: keep the columns in order, (x, y)",
    ),
    Mistake(
        "rounded",
        lambda s: (
            _same(s, np.rint(s.h[:, :2] / s.h[:, 2:]))
            or _same(s, np.trunc(s.h[:, :2] / s.h[:, 2:]))
        ),
        (
            "the points were rounded to whole numbers (np.rint, //, or an int array): dividing by w gives "
            "fractions (-0.6 / -0.3 is 2, but 8.5 / 2 is 4.25); keep floats"
        ),
    ),
    Mistake(
        "rounded to decimals",
        lambda s: _decimals(s) is not None,
        lambda s: (
            f"you rounded the result to {_decimals(s)} decimal{'s' * (_decimals(s) > 1)} (np.round(..., {_decimals(s)})): a quotient "
            "such as 5 / 0.7 = 7.142857... has endless decimals; return the full floats, round only to print"
        ),
    ),
    Mistake(
        "half a pixel added",
        lambda s: any(_same(s, s.h[:, :2] / s.h[:, 2:] + d) for d in (0.5, -0.5)),
        (
            "you divided right, then added or subtracted 0.5: (x, y) is (wx / w, wy / w) exactly. A half pixel "
            "belongs to a change of pixel convention (Pillow's and COLMAP's corners, section 3.4), not to the "
            f"division: {KEEPDIMS}"
        ),
    ),
    Mistake(
        "rescaled",
        lambda s: _rescaled(s) is not None,
        lambda s: (
            f"you divided right, then scaled every point by the same factor, {_rescaled(s):.6g} (units, or a "
            f"normalisation?): the point is (wx / w, wy / w) itself: {KEEPDIMS}"
        ),
    ),
)


def _decimals(s) -> int | None:
    """The k in 1..6 with answer = np.round(h[:, :2] / h[:, 2:], k), if there is one."""
    right = s.h[:, :2] / s.h[:, 2:]
    return next((k for k in range(1, 7) if _same(s, np.round(right, k))), None)


def _rescaled(s) -> float | None:
    """The one factor k != 1 with answer = k (h[:, :2] / h[:, 2:]), if there is one."""
    right = (s.h[:, :2] / s.h[:, 2:]).ravel()
    k = float(s.g.ravel() @ right / (right @ right))
    return k if not np.isclose(k, 1.0) and _same(s, k * right.reshape(-1, 2)) else None


def _diagnose(args, got, expected) -> str:
    """The likely cause of a wrong answer: its shape, then a row of :data:`DIVIDE_MISTAKES`."""
    h = np.asarray(args[0], dtype=float)
    problem = shape_problem(got, expected)
    shape = np.shape(got)
    if problem and shape == (len(h), 3):
        g = np.asarray(got, dtype=float)
        if np.allclose(g, h):
            return f"{problem}: you returned h as it came in; divide x and y by w and drop w: {KEEPDIMS}"
        return (
            f"{problem}: you kept all three columns (h / h[:, 2:] also divides w by itself, a column of 1s); "
            f"return x and y only: {KEEPDIMS}"
        )
    if problem and shape == (len(h), 1, 2):
        return (
            f"{problem}: (N, 1, 2) is OpenCV's layout for point lists (cv2.convertPointsFromHomogeneous "
            "returns it); points here are (N, 2) rows: add .reshape(-1, 2)"
        )
    if problem and shape == (2, len(h)) and len(h) != 2:
        return (
            f"{problem}: a (2, N) array, one column per point; points are rows: return (N, 2) (.T)"
        )
    if problem:
        return problem
    context = SimpleNamespace(h=h, g=np.asarray(got, dtype=float))
    return (
        first_mistake(DIVIDE_MISTAKES, context)
        or f"divide x and y of each row by that row's w: {KEEPDIMS}"
    )


def _exception_hint(exc: Exception, args: tuple) -> str:
    """The flat w on three points, and w looked for at index 3 (counted from 1)."""
    text = str(exc)
    if (
        isinstance(exc, ValueError)
        and "broadcast" in text
        and re.search(r"\(3,\s?2\)\s+\(3,\)", text)
    ):
        return (
            "you divided by the flat h[:, 2], shape (3,), which numpy lines up with the last axis, the columns "
            "(there are 2): w must stay an (N, 1) column. With two points it would raise nothing and divide the wrong entries, "
            f"with one it would be right by luck; keep w a column: {KEEPDIMS}"
        )
    one_based = (
        "counting from 1: numpy counts from 0, so the columns of h are 0 (wx), 1 (wy) and 2 (w), and there "
        "is no column 3"
    )
    if isinstance(exc, IndexError) and "axis 1 with size 3" in text:
        return f"{one_based}: {KEEPDIMS}"
    if isinstance(exc, ValueError) and "broadcast" in text and re.search(r"\(\d+,\s?0\)", text):
        return f"{one_based}, so h[:, 3:4] is an empty (N, 0) slice; w is h[:, 2:]: {KEEPDIMS}"
    return ""


_WITH_DIRECTION = np.array([[2.0, 4.0, 2.0], [3.0, -1.5, 0.0], [1.0, 1.0, 1.0]])


def _follow_up(run) -> str | None:
    """A row with w = 0 names a direction, no point: it must not come back as a finite point."""
    try:
        with np.errstate(divide="ignore", invalid="ignore"):
            got = np.asarray(run(_WITH_DIRECTION.copy()), dtype=float)
    except AssertionError as failed:  # Python's own x / 0.0 raises: that too says 'no point'
        if isinstance(failed.__cause__, ZeroDivisionError):
            return None
        raise
    if got.shape != (3, 2):
        return (
            f"on h = {_WITH_DIRECTION.tolist()} it returned shape {got.shape}, not (3, 2)\n"
            f"  likely cause: a row with w = 0 dropped or added; keep one row per point: {KEEPDIMS}"
        )
    if not np.allclose(got[[0, 2]], [[1.0, 2.0], [1.0, 1.0]]):
        return (
            f"on h = {_WITH_DIRECTION.tolist()}, whose row 1 has w = 0, rows 0 and 2 came back as "
            f"{got[[0, 2]].tolist()}, not [[1.0, 2.0], [1.0, 1.0]]\n"
            "  likely cause: the w = 0 row changed the others; divide each row by its own w: "
            + KEEPDIMS
        )
    if np.isfinite(got[1]).any():
        shown = ", ".join(f"{v:.3g}" for v in got[1])
        if np.isclose(
            np.abs(got[1]), np.finfo(float).max
        ).any():  # inf turned into the largest float
            cause = (
                "np.nan_to_num after the division: the division gave inf, which says 'no point', and "
                "np.nan_to_num turned it into the largest float, 1.8e308, a finite point"
            )
        elif np.allclose(got[1], _WITH_DIRECTION[1, :2]):  # x and y left as they came
            cause = (
                "x and y of the w = 0 row were left undivided, as cv2.convertPointsFromHomogeneous (or a guard "
                "that skips the division where w = 0) does: (3, -1.5) is a real point of the image, and the row "
                "names a direction"
            )
        elif np.abs(got[1]).max() > 1e6:  # x / (w + eps), or a w clipped away from 0
            cause = (
                "dividing by w + eps (or by a w clipped away from 0). With w = 0 the row is a direction, no "
                "point of the image (section 4), and a huge finite point hides that"
            )
        else:  # np.where(w == 0, 0, ...), np.divide(..., out=zeros, where=w != 0), a masked row
            cause = (
                "a guard that replaced the w = 0 row by a finite value (np.where, or np.divide's out= and "
                f"where=). A point at infinity has no finite position: ({shown}) is a real point "
                f"{'(the origin, the top-left pixel) ' if np.allclose(got[1], 0) else ''}of the image, "
                "so the guard turns 'no point' into a point"
            )
        return (
            f"the test with a row of w = 0 (a direction: the prompt asks for inf or nan there), h = "
            f"{_WITH_DIRECTION.tolist()}: row 1, (3, -1.5, 0), "
            f"came back as the finite point ({shown}).\n"
            f"  likely cause: {cause}; divide by w itself: numpy's x / 0 gives inf (or NaN), which says "
            "'no point'"
        )
    return None


def _success_note(run) -> str:
    """The line under the congratulation: the w = 0 test passed too, and what its row came back as."""
    try:
        with np.errstate(divide="ignore", invalid="ignore"):
            row = np.asarray(run(_WITH_DIRECTION.copy()), dtype=float)[1]
        shown = "[" + ", ".join(f"{v:g}" for v in row) + "]"
    except AssertionError:  # Python's x / 0.0: a ZeroDivisionError, which also says 'no point'
        shown = "a ZeroDivisionError"
    return f"and on the w = 0 row: (3, -1.5, 0) came back as {shown}, no finite point, as a direction should"


def divide_by_w(h):
    """Homogeneous rows back to points: divide each row's x and y by its own w.

    Parameters
    ----------
    h : (N, 3) array_like
        Rows (wx, wy, w); w may be 0 (a direction, no point).

    Returns
    -------
    (N, 2) ndarray
        Rows (x, y). ``h[:, 2:]`` keeps w an (N, 1) column, so each row is divided by its own w; the
        flat ``h[:, 2]``, shape (N,), would line up with the columns. A row with w = 0 (a direction)
        comes back as inf or NaN.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 2.2.1.
    """
    h = np.asarray(h, dtype=float)
    return h[:, :2] / h[:, 2:]


def _describe_h(args: tuple) -> str:
    """The test input as the student could type it, one row a line: ``h = np.array([[5.0, 8.5, 2.0], ...])``."""
    h = np.asarray(args[0], dtype=float)
    rows = ["[" + ", ".join(repr(float(c)) for c in row) + "]" for row in h]
    # a message prints it after 11 characters ("  input    "), so the rows line up under the first
    return "h = np.array([" + (",\n" + " " * 25).join(rows) + "])"


def _guarded(h):
    """A wrong answer: a w = 0 row sent to (0, 0) by a guarded division."""
    w = h[:, 2:]
    return np.where(w == 0, 0.0, h[:, :2] / np.where(w == 0, 1.0, w))


def _nan_to_num(h):
    """A wrong answer: the right division, then np.nan_to_num, which makes inf the largest float."""
    h = np.asarray(h, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.nan_to_num(h[:, :2] / h[:, 2:])


def _opencv_way(h):
    """A wrong answer: OpenCV's convertPointsFromHomogeneous, which leaves a w = 0 row undivided."""
    h = np.asarray(h, dtype=float)
    w = h[:, 2:]
    return np.where(w == 0, h[:, :2], h[:, :2] / np.where(w == 0, 1.0, w))


def _variant(form):
    return lambda h: form(np.asarray(h, dtype=float))


register_exercise(
    Exercise(
        name="divide_by_w",
        lesson="00",
        reference=projective.from_homogeneous,
        cases=cases,
        compare=same_array(),
        diagnose=_diagnose,
        exception_hint=_exception_hint,
        describe_input=_describe_h,
        follow_up=_follow_up,
        success_note=_success_note,
        teaching=divide_by_w,
        ndarray_only=True,  # as lift and read_and_turn: the prompt asks for a numpy array
        wrong_variants=(
            (_variant(lambda h: h[:, :2] / h[:, 2]), "you divided by the flat h[:, 2], shape (3,)"),
            (
                _variant(lambda h: h[:, :2] / (h[:, 2] if len(h) != 3 else h[:, 2:])),
                "column 0 is divided by row 0's w",
            ),
            (_variant(lambda h: h[:, :2]), "you dropped w without dividing"),
            (_variant(lambda h: h[:, :2] * h[:, 2:]), "you multiplied by w"),
            (_variant(lambda h: h / h[:, 2:]), "you kept all three columns"),
            (_variant(lambda h: h), "you returned h as it came in"),
            (_variant(lambda h: h[:, :2] / h[0, 2]), "the same w"),
            (_variant(lambda h: h[:, :2] / h[:, 1:2]), "you divided by x or y"),
            (
                _variant(lambda h: h[:, :2] / h[:, 3:4]),
                "h[:, 3:4] is an empty (N, 0) slice; w is h[:, 2:]",
            ),
            (_variant(lambda h: h[:, :2] / h[:, 3, None]), "no column 3"),
            (_variant(lambda h: h[:, :2] / np.abs(h[:, 2:])), "you divided by |w|"),
            (_variant(lambda h: h[:, 2:] / h[:, :2]), "upside down"),
            (_variant(lambda h: (h[:, :2] / h[:, 2:]).T), "(2, N)"),
            (_variant(lambda h: np.rint(h[:, :2] / h[:, 2:])), "rounded"),
            (
                _variant(lambda h: (h[:, :2] / h[:, 2:]).round(2)),
                "you rounded the result to 2 decimals",
            ),
            (
                _variant(lambda h: (h[:, :2] / h[:, 2:]).round(3)),
                "you rounded the result to 3 decimals",
            ),
            (_variant(lambda h: h[:, :2] / (h[:, 2:] + 1e-12)), "w + eps"),
            (
                _variant(_guarded),
                "A point at infinity has no finite position: (0, 0) is a real point (the origin",
            ),
            (_variant(lambda h: h[:, 1::-1] / h[:, 2:]), "swapped"),
            (_variant(lambda h: (h[:, :2] / h[:, 2:]).tolist()), "you returned a list"),
            (_variant(lambda h: h[:, 1:3] / h[:, :1]), "columns count from 0"),
            (
                _variant(lambda h: h[:, :2] / np.linalg.norm(h, axis=1, keepdims=True)),
                "np.linalg.norm",
            ),
            (
                _variant(lambda h: (h[:, :2] / h[:, 2:])[:, None, :]),
                "OpenCV's layout for point lists",
            ),
            (_nan_to_num, "np.nan_to_num"),
            (_opencv_way, "cv2.convertPointsFromHomogeneous"),
            (_variant(lambda h: h[:, :2] / h[:, 2:] + 0.5), "then added or subtracted 0.5"),
            (_variant(lambda h: h[:, :2] / h[:, 2:] / 1000), "the same factor, 0.001"),
        ),
        in_place_examples={
            "h": ("`h /= h[:, 2:]`, `h[:, :2] /= h[:, 2:]`", "`h[:, :2] / h[:, 2:]`"),
        },
    )
)
