"""The warm-up exercise of lesson 00: how exercises and checks work."""

from __future__ import annotations

import dis
import re
import sys
from types import TracebackType

import numpy as np

from .. import projective
from ._answers import same_array, shape_problem
from ._core import Exercise, register_exercise

_KEEP = "append 1 to the point, keeping x and y as they are"
_APPEND = "np.append(p, 1.0)"

_ONE_POINT = (
    "p is one point, a 1-D array of shape (2,), not a batch of points (N, 2) like the worked "
    "example's `points`"
)


def _raised_where(exc: BaseException) -> tuple[str, str]:
    """Where ``exc`` was raised: (the numpy function the student's code called, the student's instruction).

    The traceback's innermost frame outside numpy is the student's code; the frame after it, if
    any, is the numpy function it called (``vstack``, ``insert``; ``__getitem__`` of
    ``numpy.lib._index_tricks_impl`` for ``np.c_``), '' when the error came from the student's
    own line or a numpy function written in C (``np.concatenate``). The student's instruction is
    the bytecode operation that raised there: ``STORE_SUBSCR`` for ``p[2] = 1.0``,
    ``BINARY_SUBSCR`` (Python 3.11-3.13) for reading ``p[2]``.
    """
    frames: list[TracebackType] = []
    tb = exc.__traceback__
    while tb is not None:
        frames.append(tb)
        tb = tb.tb_next
    inside_numpy = [
        str(t.tb_frame.f_globals.get("__name__", "")).startswith("numpy") for t in frames
    ]
    own = [k for k, numpy_frame in enumerate(inside_numpy) if not numpy_frame]
    if not own:
        return "", ""
    student = frames[own[-1]]
    called = ""
    if own[-1] + 1 < len(frames):
        entered = frames[own[-1] + 1].tb_frame
        module = str(entered.f_globals.get("__name__", ""))
        called = "np.c_" if "index_tricks" in module else f"np.{entered.f_code.co_name}"
    operation = next(
        (
            i.opname
            for i in dis.get_instructions(student.tb_frame.f_code)
            if i.offset == student.tb_lasti
        ),
        "",
    )
    return called, operation


def _index_hint(exc: Exception) -> str:
    """An index past the end of the point: writing p[2] (growing the array) or reading it (1-based)."""
    called, operation = _raised_where(exc)
    match = re.search(r"index (-?\d+) is out of bounds for axis 0 with size (\d+)", str(exc))
    index = match.group(1) if match else "2"
    if called == "np.insert":
        return (
            "np.insert's position counts from 0 and can be at most len(p) = 2, which inserts after y: "
            f"np.insert(p, 2, 1.0), or simply {_APPEND}"
        )
    if called:
        return ""
    if operation == "STORE_SUBSCR":
        return (
            f"assigning p[{index}] = ... cannot grow an array: a numpy array has a fixed size, and a (2,) point has "
            f"only the indices 0 and 1 (a Python list cannot grow this way either); build a new, longer array: "
            f"{_APPEND}"
        )
    return (
        f"counting from 1: numpy counts from 0, so the point's coordinates are p[0] (x) and p[1] (y), and there "
        f"is no p[{index}]; then append the 1: {_APPEND}"
    )


def _batch_code_hint(exc: Exception, args: tuple) -> str:
    """The likely cause when the student's code raises: list habits, index slips, the wrong joining function.

    ``np.hstack([p, np.ones((len(p), 1))])`` joins a 1-D and a 2-D array, ``p[:, :2]`` indexes a
    second axis that one point lacks, ``np.c_[p, 1]`` / ``np.column_stack`` treat x and y as two
    rows, ``np.vstack`` stacks rows of different lengths, ``p[2] = 1.0`` tries to grow the array,
    ``p[1], p[2]`` counts from 1: each raises, and the shared hints would blame something else (a
    1-based column of an (N, 3) array).
    """
    text = str(exc)
    called, _ = _raised_where(exc)
    if isinstance(exc, IndexError) and "out of bounds for axis 0" in text:
        return _index_hint(exc)
    if isinstance(exc, IndexError) and "list assignment index out of range" in text:
        return (
            "assigning q[2] = ... cannot grow a Python list (nor a numpy array): a list grows with "
            f"q.append(1.0); for the array this exercise wants, {_APPEND}"
        )
    if isinstance(exc, IndexError) and "list index out of range" in text:
        return (
            f"counting from 1: Python counts from 0, so the point's coordinates are p[0] (x) and p[1] (y); "
            f"then append the 1: {_APPEND}"
        )
    if "cannot reshape array of size 2" in text:
        return (
            "reshape rearranges the numbers an array holds, and p holds 2: it cannot make a third; "
            f"append it: {_APPEND}"
        )
    if "has no attribute 'append'" in text:
        return (
            "p.append(1.0) is how a Python list grows; a numpy array has no .append method "
            f"(its size is fixed): {_APPEND} returns a new, longer array"
        )
    if "cannot resize" in text:
        return (
            "p.resize(3) changes the caller's array in place (numpy refuses while another name refers to it), "
            f"and the caller's point must come back as it went in; build a new array: {_APPEND}"
        )
    if "zero-dimensional arrays cannot be concatenated" in text:
        return (
            "np.concatenate takes one sequence of arrays, and its second argument is the "
            "axis: np.concatenate([p, [1.0]]), or simply np.append(p, 1.0)"
        )
    if "same number of dimensions" in text and "0 dimension(s)" in text:
        return (
            "np.concatenate joins arrays, and the 1 is a bare number (0-D): write it as "
            "[1.0], np.concatenate([p, [1.0]]), or use np.append(p, 1.0) or np.hstack([p, 1.0]), which accept it"
        )
    if "same number of dimensions" in text:
        joined = called if called in ("np.hstack", "np.vstack") else "np.concatenate"
        return (
            f"batch code on one point: {_ONE_POINT}, so {joined} joins a 1-D array to a 2-D one (a column "
            f"such as np.ones((len(p), 1)) or [[1.0]]); for one point append one number: {_APPEND}"
        )
    if "too many indices" in text or "out of bounds for array of dimension 1" in text:
        return (
            f"batch code on one point: {_ONE_POINT}, so it has no second axis (p[:, :2], "
            f"axis=1); its coordinates are p[0] and p[1], and {_APPEND} lifts it"
        )
    if "except for the concatenation axis" in text:
        if called == "np.vstack":
            return (
                "np.vstack stacks its arguments as rows, one under the other, and p (2 numbers) and the 1 "
                f"(1 number) are rows of different lengths; to add a coordinate, append it: {_APPEND} or np.r_[p, 1.0]"
            )
        if called in ("np.c_", "np.column_stack"):
            return (
                f"{called} joins columns, so it treats x and y as two rows: "
                f"{_ONE_POINT}; append one number instead: {_APPEND} or np.r_[p, 1.0]"
            )
        return (
            f"the arrays you joined differ in length along the other axis; {_ONE_POINT}: "
            f"append one number: {_APPEND}"
        )
    if called == "np.stack" and "same shape" in text:
        return (
            "np.stack puts arrays of the same shape side by side along a new axis, and p (2 numbers) and [1.0] "
            f"differ; to add a coordinate, append it: {_APPEND}"
        )
    return ""


def _shape_slip(got_shape: tuple, g: np.ndarray, p: np.ndarray) -> str:
    """The likely cause of an answer of the wrong shape."""
    if got_shape == (2,) and np.allclose(g, p):
        return (
            "you returned the 2 coordinates you were given (the point itself, or (x, y, 1) divided back by w); "
            f"lifting adds the third, w = 1: {_APPEND}"
        )
    if got_shape == (2,) and np.allclose(g, p + 1.0):
        return (
            "p + [1] (or p + 1) adds 1 to each coordinate: numpy's + is arithmetic, not the list concatenation "
            f"it is for Python lists; append instead: {_APPEND}"
        )
    if got_shape == (2, 2):
        return (
            f"np.column_stack / np.c_ with a column of ones is batch code: on one point it makes each "
            f"coordinate a row. {_ONE_POINT}: append one number, {_APPEND}"
        )
    if got_shape == (1, 3):
        return (
            "a batch holding one point; one point in, one point out: return the (3,) array "
            f"({_APPEND}, or your result's row [0])"
        )
    if got_shape == (3, 1):
        return "a column; points are rows in this course: return the (3,) array (.ravel())"
    if got_shape == (4,) and np.allclose(g[2:], 1.0):
        return (
            "you appended two 1s: np.ones(len(p)) counts p's coordinates, not points (len(p) is 2 for one point); "
            f"append a single 1: {_APPEND}"
        )
    return "append one coordinate, w = 1, to the 2 you were given"


def _diagnose(args, got, expected) -> str:
    """The likely cause of a (3,) answer with the wrong numbers: what is wrong with x and y, and with w."""
    problem = shape_problem(
        got, expected
    )  # check() has already named an answer that is not numbers
    g = np.asarray(got, dtype=float).ravel() if problem else np.asarray(got, dtype=float)
    p = np.asarray(args[0], dtype=float)
    if problem and np.shape(got) != np.shape(expected):
        return f"{problem}: {_shape_slip(np.shape(got), g, p)}"
    if problem and np.isnan(g[-1]) and np.allclose(g[:2], p):  # x and y filled in, w left as it was
        return (
            "w is NaN and x and y are right: an array made with np.empty(3) keeps whatever was in memory until "
            "you fill it (here NaN, which the check leaves there), so set w too, or build the answer from p: "
            f"{_APPEND}"
        )
    if problem:
        return problem
    w = g[-1]
    if np.allclose(g, [1.0, *p]):
        return "you put the 1 first; by convention w is the last coordinate: (x, y, 1)"
    if np.allclose(g, [1.0, p[1], p[0]]):
        return "the coordinates came out reversed, (1, y, x) ([::-1] or np.flip reverses an array): keep (x, y, 1)"
    if np.allclose(g, [p[0], 1.0, p[1]]):
        return (
            "the 1 landed between x and y: np.insert(p, 1, ...) inserts before index 1; w is the last "
            f"coordinate, at index len(p) = 2: np.insert(p, 2, 1.0), or {_APPEND}"
        )
    if w not in (0.0, 1.0) and np.allclose(g[:2] / w, p):
        shown = ", ".join(f"{c:g}" for c in g)
        return (
            f"({shown}) is the same point scaled by {w:g} (homogeneous coordinates are defined up to scale), "
            f"but this exercise fixes w = 1: {_KEEP}"
        )
    xy = _xy_slip(g[:2], p)
    if not xy and w == p[0] and w != 1:
        return (
            "w is x again: np.resize (or np.tile) repeats the array to fill the new length; append the 1 "
            f"instead: {_APPEND}"
        )
    if w == 0:
        w_slip = "w = 0 makes an ideal point, a direction (lesson 06 §3), not the point itself: w must be 1"
    elif w != 1:
        w_slip = f"w should be 1, not {w:g}"
    else:
        w_slip = ""
    if not xy:
        return f"x and y are right, but {w_slip}" + ("" if w == 0 else ": append exactly 1")
    if not w_slip:
        return xy if _APPEND in xy else f"{xy}; {_KEEP}"
    return f"{xy}; and {w_slip}"


def _xy_slip(xy: np.ndarray, p: np.ndarray, swapped: bool = False) -> str:
    """The likely cause when x and y came out wrong ('' when they are right; w is judged elsewhere)."""
    if np.allclose(xy, p):
        return ""
    if np.allclose(xy, 0.0):
        return (
            "x and y are 0: the array was created (np.zeros, np.empty) but the point was never put in it; "
            f"build it from p: {_APPEND}"
        )
    if np.allclose(xy, 1.0):
        return (
            "x and y are 1: an array of ones (np.ones(3)) that the point was never put in; "
            f"build it from p: {_APPEND}"
        )
    fractional = not np.array_equal(p, np.trunc(p))
    if fractional and (np.allclose(xy, np.trunc(p)) or np.allclose(xy, np.round(p))):
        return (
            "the coordinates lost their fractions: you cast to int or rounded, but image points are real "
            f"numbers (sub-pixel positions, such as this input's ({p[0]:g}, {p[1]:g})); keep floats"
        )
    for shift, cause in (
        (
            0.5,
            "pixel centres sit at whole numbers in this course (section 3), so a point needs no "
            "half-pixel shift",
        ),
        (1.0, "numpy and this course count pixels from 0, not 1 (a 1-based index?)"),
    ):
        for sign in (1, -1):
            if np.allclose(xy, p + sign * shift):
                return f"x and y are off by {sign * shift:+g}: {cause}"
    if np.allclose(xy, [p[0], -p[1]]):
        return "y changed sign: y points down in this course, and lifting keeps its sign"
    if np.allclose(xy, [-p[0], p[1]]):
        return "x changed sign: lifting keeps both coordinates and their signs (x points right)"
    if np.allclose(xy, p - p.mean()):
        return (
            "you subtracted the mean of the point's two coordinates (p - p.mean()): centring belongs to a batch "
            "of points, one mean per column (the normalisation of lesson 04 §5), and lifting changes neither "
            "coordinate"
        )
    image_slip = _image_convention_slip(xy, p)
    if image_slip:
        return image_slip
    nonzero = np.abs(p) > 0
    factor = xy[nonzero] / p[nonzero]
    if np.allclose(factor, factor[0]) and np.allclose(xy, factor[0] * p):
        k = factor[0]
        if p[-1] != 0 and np.isclose(k, 1 / p[-1]):
            return (
                "you divided by p[-1], which is y: the point has no w yet (dividing by w is the way back from "
                "homogeneous coordinates, lesson 04 §0), and lifting divides nothing"
            )
        if np.isclose(k, 1 / np.linalg.norm(p)):
            return "you divided by the point's length: lifting normalises nothing"
        if np.isclose(k, np.pi / 180) or np.isclose(k, 180 / np.pi):
            way = "degrees to radians (np.radians)" if k < 1 else "radians to degrees (np.degrees)"
            return (
                f"x and y are {k:g} times the point's: the factor that converts {way}; a point's coordinates "
                f"are pixels, not angles, and lifting converts nothing"
            )
        if np.isclose(k, 1e-3) or np.isclose(k, 1e3):
            return (
                f"x and y are {k:g} times the point's: a millimetre-metre conversion? A point's coordinates are "
                "pixels, and lifting converts nothing"
            )
        cause = "a sign flip" if k == -1 else "a unit change or a stray factor"
        return f"x and y are {k:g} times the point's ({cause})"
    if not swapped and not np.allclose(p, p[::-1]):
        if np.allclose(xy, p[::-1]):
            return "x and y are swapped: keep the point's order, (x, y) = (u, v) = (column, row)"
        also = _xy_slip(xy[::-1], p, swapped=True)
        if also and not also.startswith(("x is", "y is")):
            return f"x and y are swapped (keep the point's order, (x, y) = (u, v)), and {also}"
    return _one_coordinate_slip(xy, p)


# The 640 x 480 image of the lesson's examples: its size, its centre, and its y-up heights (OpenGL, section 3).
_SIZE = np.array([640.0, 480.0])


def _image_convention_slip(xy: np.ndarray, p: np.ndarray) -> str:
    """Slips that bring in section 3's image conventions: a y-up flip, the centre subtracted, a division by the size."""
    H = _SIZE[1]
    for flipped in (H - 0.5, H - 1.0, H):
        if np.isclose(xy[0], p[0]) and np.isclose(xy[1], flipped - p[1]):
            return (
                f"y is {xy[1]:g} = {flipped:g} - v: you flipped it to a y-up convention (OpenGL's rows count from "
                "the bottom); the course keeps y down, and lifting changes no coordinate"
            )
    for centre in (_SIZE - 1) / 2, _SIZE / 2:
        if np.allclose(xy, p - centre):
            return (
                f"you subtracted the image centre ({centre[0]:g}, {centre[1]:g}): lifting keeps the pixel "
                "coordinates, with the origin at the top-left pixel's centre"
            )
    for size in _SIZE, _SIZE - 1:
        if np.allclose(xy, p / size):
            return (
                f"you divided by the image size ({size[0]:g}, {size[1]:g}): lifting keeps pixels as they are; it "
                "does not rescale them to [0, 1]"
            )
    return ""


def _cases() -> list[tuple[np.ndarray]]:
    """The check's test inputs: the first has fractions, so an int cast shows at once; the last is the
    bottom-right pixel of 640 x 480."""
    return [(np.array([2.5, 4.25]),), (np.array([-1.5, 0.0]),), (np.array([639.0, 479.0]),)]


def _not_from_p(xy: np.ndarray, p: np.ndarray) -> str:
    """Why x and y, both wrong, do not come from ``p`` at all: another test input's point, or a notebook variable.

    A function that returns the same numbers for every point was written for one input (copied from a
    check's message) or reads a variable of the notebook (``points[0]``, ``roof_tip``) instead of its
    argument; '' when neither explains ``xy``.
    """
    for k, (other,) in enumerate(_cases()):
        if not np.allclose(other, p) and np.allclose(xy, other):
            return (
                f"x and y are ({xy[0]:g}, {xy[1]:g}), test input {k + 1}'s point, not this input's: the answer "
                f"does not depend on p; build it from the argument p, not from fixed numbers: {_APPEND}"
            )
    main = sys.modules.get("__main__")
    for name, value in vars(main).items() if main is not None else ():
        if (
            name.startswith("_")
            or not isinstance(value, np.ndarray)
            or value.dtype.kind not in "iuf"
            or value.ndim not in (1, 2)
            or value.shape[-1] not in (2, 3)
            or value.size > 3000
        ):
            continue
        rows = value.reshape(-1, value.shape[-1])
        for k, row in enumerate(rows):
            if np.allclose(row[:2], xy):
                where = name if value.ndim == 1 else f"{name}[{k}]"
                return (
                    f"x and y are ({xy[0]:g}, {xy[1]:g}), those of the notebook's `{where}`, not of p: your "
                    f"function reads a variable of the notebook instead of its argument p; lift p: {_APPEND}"
                )
    return ""


def _one_coordinate_slip(xy: np.ndarray, p: np.ndarray) -> str:
    """Name the coordinate that is wrong, and what it holds when that is recognisable (x twice, a 0)."""
    names = ("x", "y")
    wrong = [k for k in range(2) if not np.isclose(xy[k], p[k])]
    if len(wrong) == 2:
        fixed = _not_from_p(xy, p)
        if fixed:
            return fixed
    parts = []
    for k in wrong:
        holds = ""
        if np.isclose(xy[k], p[1 - k]):
            holds = f" (it holds {names[1 - k]}: p[{1 - k}] where p[{k}] belongs)"
        elif xy[k] == 0:
            holds = " (it is 0: never filled?)"
        elif xy[k] == 1:
            holds = " (it is 1: did the 1 land there?)"
        parts.append(f"{names[k]} is {xy[k]:g}, not p[{k}] = {p[k]:g}{holds}")
    return "; ".join(parts)


def _list_append(p):
    """A list's way to grow, tried on an array (a wrong variant for the tests)."""
    p.append(1.0)
    return p


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
    """Homogeneous coordinates of one image point: append w = 1."""
    return np.append(np.asarray(p, dtype=float), 1.0)


register_exercise(
    Exercise(
        name="lift",
        lesson="00",
        reference=projective.to_homogeneous,
        cases=_cases,
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
            (lambda p: np.append(p, np.ones(len(p))), "two 1s"),
            (_empty_unfilled, "w is NaN and x and y are right: an array made with np.empty(3)"),
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
            (lambda p: p + [1.0], "not the list concatenation"),
            (lambda p: np.concatenate(p, 1), "its second argument is the axis"),
            (lambda p: np.concatenate([p, 1.0]), "the 1 is a bare number"),
        ),
        exception_hint=_batch_code_hint,
        teaching=lift,
    )
)
