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
    if (
        got_shape == (2,)
        and np.isclose(g[-1], 1.0)
        and np.isclose(g[0], p[0])
        and not np.isclose(p[1], 1.0)
    ):
        return (
            "y went missing: you appended w = 1 to x alone. A slice stops before its end index, so p[:1] "
            f"keeps only p[0]; p[:2], or p itself, keeps x and y: {_APPEND}"
        )
    if (
        got_shape == (2,)
        and np.isclose(g[-1], 1.0)
        and np.isclose(g[0], p[1])
        and not np.isclose(p[0], 1.0)
    ):
        return (
            "x went missing: you appended w = 1 to y alone (p[1:] starts at index 1, which is y); keep both "
            f"coordinates: {_APPEND}"
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
    offset = g - np.append(p, 1.0)
    if not np.isclose(offset[0], 0.0) and np.allclose(offset, offset[0]):
        return (
            f"every entry, w included, is off by {offset[0]:+g}: the {offset[0]:+g} went onto the whole array "
            f"(np.append(p, 1.0) {'+' if offset[0] > 0 else '-'} {abs(offset[0]):g}?); lifting only appends w = 1, "
            "and no pixel convention shifts a point here (pixel centres sit at whole numbers, counted from 0)"
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
    clipped = _clip_slip(xy, p)
    if clipped:
        return clipped
    if np.allclose(xy, 0.0) and np.all(p != 0):
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
    whole = (np.trunc(p), np.round(p), np.floor(p + 0.5), np.floor(p), np.ceil(p))
    if fractional and any(np.allclose(xy, k) for k in whole):
        return (
            "the coordinates lost their fractions: you cast to int or rounded to whole pixels (int, np.round, "
            "np.floor(p + 0.5)), but image points are real numbers (sub-pixel positions, such as this input's "
            f"({p[0]:g}, {p[1]:g})); keep floats"
        )
    for short in (np.float16,):
        if np.array_equal(xy, p.astype(short).astype(float)):
            return (
                f"x and y went through {np.dtype(short).name} (.astype(np.{np.dtype(short).name})), which keeps about "
                f"{np.finfo(short).precision} significant digits: ({p[0]:g}, {p[1]:g}) came back as "
                f"({xy[0]:.6g}, {xy[1]:.6g}); keep numpy's float64"
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


def _clip_slip(xy: np.ndarray, p: np.ndarray) -> str:
    """A point clipped to the image (np.clip, np.maximum(p, 0)): every changed coordinate now sits on an edge.

    Test input 2, (-1.5, 0), lies left of the image; clipped, it becomes (0, 0), which is not "an
    array never filled" (its y was 0 already).
    """
    changed = ~np.isclose(xy, p)
    edges = [(0.0, _SIZE[0] - 1, _SIZE[0]), (0.0, _SIZE[1] - 1, _SIZE[1])]
    if not changed.any() or not all(
        any(np.isclose(xy[k], e) for e in edges[k]) for k in np.flatnonzero(changed)
    ):
        return ""
    outside = (p < 0) | (p > _SIZE - 1)
    if not np.array_equal(changed, changed & outside):
        return ""
    names = " and ".join(f"{'xy'[k]} = {p[k]:g}" for k in np.flatnonzero(changed))
    return (
        f"{names} became {', '.join(f'{xy[k]:g}' for k in np.flatnonzero(changed))}: clipped to the image (np.clip, "
        "np.maximum)? This point lies outside the 640 x 480 image, and it is still a point: lifting keeps "
        f"every coordinate as it is: {_APPEND}"
    )


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
    """The check's test inputs: the first has fractions, so an int cast shows at once; the second lies outside
    the image (left of it, on the top row); the third is the bottom-right pixel of 640 x 480; the last has
    decimals no binary float holds exactly, so a detour through float16 (3 digits) shows."""
    return [
        (np.array([2.5, 4.25]),),
        (np.array([-1.5, 0.0]),),
        (np.array([639.0, 479.0]),),
        (np.array([100.1, 0.7]),),
    ]


def _describe_point(args: tuple) -> str:
    """The test input as the student could type it: ``p = np.array([2.5, 4.25])``."""
    p = np.asarray(args[0], dtype=float)
    return "p = np.array([" + ", ".join(repr(float(c)) for c in p) + "])"


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
            (lambda p: np.append(p[:1], 1.0), "y went missing"),
            (lambda p: np.append(p, 1.0) + 0.5, "every entry, w included, is off by +0.5"),
            (lambda p: np.append(np.clip(p, 0, [639, 479]), 1.0), "clipped to the image"),
            (lambda p: np.append(np.maximum(p, 0), 1.0), "clipped to the image"),
            (lambda p: np.append(np.floor(p + 0.5), 1.0), "rounded to whole pixels"),
            (lambda p: np.append(p.astype(np.float16), 1.0), "went through float16"),
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
        describe_input=_describe_point,
        teaching=lift,
    )
)


# -- read_and_turn: section 3's conventions at work ---------------------------------------------------
# Every test image holds img[v, u] = 10 v + u, so a value read names the pixel it came from (at most 10
# columns), and a wrong read can be traced to its cause: img[u, v], a 1-based index, the wrong point.
# Input 1 is square and odd (5 x 5), where img[u, v] raises nothing and silently reads the transposed pixel
# (the lesson's warning), and A is a shear (A.T is neither A nor its inverse); input 2 is wider than tall
# (6 x 4) with even sides, so W / 2 = W // 2 differs from (W - 1) / 2 and img[u, v] would raise for u >= 4;
# input 3 is 7 x 3 with a turn and a scale.


def _pixel_image(size: tuple[int, int]) -> np.ndarray:
    """A ``size = (W, H)`` test image whose value at img[v, u] is 10 v + u: it names its own pixel."""
    W, H = size
    v, u = np.mgrid[0:H, 0:W]
    return 10 * v + u


def _turn(deg: float, scale: float = 1.0) -> np.ndarray:
    t = np.radians(deg)
    return scale * np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])


def _rt_cases() -> list[tuple]:
    return [
        (
            _pixel_image((5, 5)),
            np.array([[4.0, 0.0], [1.0, 3.0], [2.0, 2.0], [0.0, 4.0]]),
            np.array([[1.0, 0.5], [0.0, 1.0]]),
        ),
        (
            _pixel_image((6, 4)),
            np.array([[5.0, 1.0], [0.0, 3.0], [2.0, 2.0]]),
            _turn(90.0).round(12),
        ),
        (_pixel_image((7, 3)), np.array([[6.0, 2.0], [0.0, 0.0], [3.0, 1.0]]), _turn(30.0, 2.0)),
    ]


def _numbers(a) -> str:
    """A small array as the student could type it: [[5, 1], [0, 3]] (whole numbers without '.0')."""
    a = np.asarray(a, dtype=float)
    if a.ndim == 0:
        return f"{float(a):.4g}"
    return "[" + ", ".join(_numbers(x) for x in a) + "]"


def _rt_describe(args: tuple) -> str:
    img, X, A = args
    H, W = img.shape
    return f"img of shape ({H}, {W}), W = {W}, H = {H}, with img[v, u] = 10 v + u; X = {_numbers(X)}; A = {_numbers(A)}"


def _read_and_turn_reference(img, X, A):
    """The centre ((W - 1)/2, (H - 1)/2), img[v, u] at the rows of X, and X turned about the centre by A.

    The turn is one homography, translate(c) A translate(-c), applied with camlab's homogeneous
    coordinates: a route other than the teaching solution's ``(X - c) @ A.T + c``.
    """
    H, W = np.shape(img)[:2]
    c = np.array([(W - 1) / 2, (H - 1) / 2])
    X = np.asarray(X, dtype=float)
    u, v = np.rint(X).astype(int).T
    M = np.eye(3)
    M[:2, :2] = A
    M[:2, 2] = c - np.asarray(A) @ c
    turned = projective.from_homogeneous(projective.to_homogeneous(X) @ M.T)
    return c, np.asarray(img)[v, u], turned


def _as_floats(part) -> np.ndarray | None:
    try:
        a = np.asarray(part, dtype=float)
    except (TypeError, ValueError):
        return None
    return None if np.asarray(part).dtype.kind in "USOc" else a


def _same_triple(got, expected) -> bool:
    if not isinstance(got, (tuple, list)) or len(got) != 3:
        return False
    same = same_array(rtol=1e-9, atol=1e-9)
    return all(_as_floats(g) is not None and same(g, e) for g, e in zip(got, expected, strict=True))


def _centre_slips(W: int, H: int) -> list[tuple[tuple[float, float], str]]:
    """Centres students compute instead of ((W - 1)/2, (H - 1)/2), each with its cause (first match wins)."""
    half = (
        "half a pixel off: pixel centres sit at whole numbers, 0 .. W - 1, so the centre is halfway between the "
        "first and the last, ((W - 1)/2, (H - 1)/2); W / 2 is the centre where whole numbers are pixel corners "
        "(Pillow, COLMAP)"
    )
    return [
        (
            (W / 2, H / 2),
            f"you used (W / 2, H / 2) (or W // 2): {half}. W // 2 agrees with (W - 1)/2 only for odd W",
        ),
        (
            (W // 2, H // 2),
            f"you used (W // 2, H // 2): {half}. W // 2 agrees with (W - 1)/2 only for odd W",
        ),
        (
            ((W + 1) / 2, (H + 1) / 2),
            "you used (W + 1)/2: the centre counted from 1 (MATLAB's); here pixels count from 0, so ((W - 1)/2, (H - 1)/2)",
        ),
        (
            ((W - 1) // 2, (H - 1) // 2),
            "you rounded the centre down to a whole pixel ((W - 1) // 2): an even side's centre lies between two pixels; keep (W - 1) / 2",
        ),
        (
            ((H - 1) / 2, (W - 1) / 2),
            "width and height swapped: numpy's img.shape is (H, W), rows first, so write H, W = img.shape; the centre is ((W - 1)/2, (H - 1)/2), u first",
        ),
        (
            (H / 2, W / 2),
            "width and height swapped (img.shape is (H, W): H, W = img.shape), and half a pixel off: the centre is ((W - 1)/2, (H - 1)/2)",
        ),
        (
            (W - 1, H - 1),
            "that is the last pixel, (W - 1, H - 1); the centre is halfway to it: ((W - 1)/2, (H - 1)/2)",
        ),
        ((W, H), "that is the size (W, H); the centre is ((W - 1)/2, (H - 1)/2)"),
        ((H, W), "that is img.shape, (H, W); the centre is ((W - 1)/2, (H - 1)/2)"),
    ]


def _centre_cause(c: np.ndarray, W: int, H: int) -> str:
    for slip, cause in _centre_slips(W, H):
        if c.shape == (2,) and np.allclose(c, slip):
            return cause
    return f"the centre of a W x H = {W} x {H} image is ((W - 1)/2, (H - 1)/2) = ({(W - 1) / 2:g}, {(H - 1) / 2:g})"


def _values_cause(values: np.ndarray, img: np.ndarray, X: np.ndarray) -> str:
    H, W = img.shape
    u, v = np.rint(X).astype(int).T
    n = len(X)
    if values.shape == (n, 2, W):
        return "img[X] indexes rows with every number of X: take one row and one column per point, img[v, u] with u, v = X[:, 0], X[:, 1]"
    if values.shape == (n, n):
        return "you got every combination of the rows v and the columns u (img[v][:, u], or np.ix_): pair them, img[v, u], one value per point"
    if values.shape != (n,):
        return f"one value per point: shape ({n},), got {values.shape}; img[v, u] with u, v = X[:, 0], X[:, 1] gives it"
    if H == W and np.allclose(values, img[u, v]):
        return "img[u, v] reads row u, column v: the transposed pixel. numpy indexes the row first, and the row is v: img[v, u]"
    for du, dv, cause in (
        (
            -1,
            -1,
            "counting from 1 (u - 1, v - 1)? numpy counts from 0, and so do pixel coordinates",
        ),
        (
            1,
            1,
            "an index one too far (u + 1, v + 1): pixel coordinates and numpy both count from 0",
        ),
    ):
        uu, vv = u + du, v + dv
        if np.all((0 <= uu) & (uu < W) & (0 <= vv) & (vv < H)) and np.allclose(values, img[vv, uu]):
            return cause
    k = int(np.argmax(~np.isclose(values, img[v, u])))
    q = values[k]
    where = ""
    if q == int(q) and 0 <= q < 10 * H and int(q) % 10 < W:
        where = f", the value of pixel (u, v) = ({int(q) % 10}, {int(q) // 10})"
    return (
        f"X[{k}] = ({u[k]}, {v[k]}) is pixel img[{v[k]}, {u[k]}] = {img[v[k], u[k]]}, but you returned {q:g}{where}: "
        "read row v, column u, img[v, u]"
    )


def _turned_cause(
    t: np.ndarray, X: np.ndarray, A: np.ndarray, c: np.ndarray, W: int, H: int
) -> str:
    n = len(X)
    if t.shape == (2, n) and n != 2:
        return "one row per point: A @ X.T gives the points as columns; transpose back, (A @ X.T).T, or write X @ A.T"
    if t.shape != (n, 2):
        return f"the turned points are rows, shape ({n}, 2), like X; got {t.shape}"
    candidates = [
        (
            (X - c) @ A + c,
            "X @ A applies A's transpose (for a rotation, the opposite turn): with points as rows, the textbook's A x is X @ A.T",
        ),
        (
            X @ A.T,
            "you turned about the origin (0, 0), the top-left pixel's centre: turn about the image's centre, c + A (x - c): (X - c) @ A.T + c",
        ),
        (
            X @ A,
            "you turned about the origin, and X @ A applies A's transpose: subtract the centre, turn with X @ A.T, add it back: (X - c) @ A.T + c",
        ),
        (
            (X - c) @ A.T,
            "you forgot to add the centre back after the turn: c + A (x - c), so (X - c) @ A.T + c",
        ),
        (
            (X - c) @ A.T - c,
            "add the centre back after the turn (you subtracted it twice): (X - c) @ A.T + c",
        ),
        (
            c - (X - c) @ A.T,
            "a sign flip: c - A (x - c) turns and mirrors through the centre; the move is c + A (x - c), (X - c) @ A.T + c",
        ),
        (
            (X + c) @ A.T - c,
            "the signs are swapped: move the centre to the origin first, X - c, then turn, then add c back: (X - c) @ A.T + c",
        ),
    ]
    if abs(np.linalg.det(A)) > 1e-12:
        candidates.append(
            (
                (X - c) @ np.linalg.inv(A).T + c,
                "you applied A's inverse, the move undone: x' = c + A (x - c) uses A itself, (X - c) @ A.T + c",
            )
        )
    for variant, cause in candidates:
        if np.allclose(t, variant):
            return cause
    for slip, cause in _centre_slips(W, H):
        s = np.asarray(slip, dtype=float)
        for variant in ((X - s) @ A.T + s, (X - s) @ A + s):
            if np.allclose(t, variant):
                return f"you turned about the wrong centre, {_numbers(s)}: {cause}"
    return "turn each row about the centre: x' = c + A (x - c), for rows (X - c) @ A.T + c"


def _rt_diagnose(args, got, expected) -> str:
    img, X, A = args
    H, W = img.shape
    order = "return three things, in this order: the centre c, shape (2,); the values, shape (N,); the turned points, shape (N, 2): `return c, values, turned`"
    if not isinstance(got, (tuple, list)):
        a = _as_floats(got)
        if a is not None and a.shape == (2,) and np.allclose(a, expected[0]):
            return f"you returned only the centre (it is right); {order}"
        return f"you returned {type(got).__name__ if not isinstance(got, np.ndarray) else 'one array'}; {order}"
    if len(got) != 3:
        return f"you returned {len(got)} things; {order}"
    names = ("the centre c", "the values", "the turned points")
    parts = [_as_floats(g) for g in got]
    for name, part, g in zip(names, parts, got, strict=True):
        if part is None:
            return f"{name} is not numbers (a {type(g).__name__}); {order}"
        if not np.isfinite(part).all():
            return f"{name} holds NaN or inf"
    c, values, turned = parts
    same = same_array(rtol=1e-9, atol=1e-9)
    causes = []
    if not same(c, expected[0]):
        if c.shape != (2,):
            causes.append(f"the centre c is one point (u, v), shape (2,); got shape {c.shape}")
        else:
            causes.append(f"the centre: {_centre_cause(c, W, H)}")
    if not same(values, expected[1]):
        causes.append(f"the values: {_values_cause(values, img, X)}")
    if not same(turned, expected[2]):
        cause = _turned_cause(turned, X, np.asarray(A, dtype=float), expected[0], W, H)
        if c.shape == (2,) and not same(c, expected[0]) and np.allclose(turned, (X - c) @ A.T + c):
            cause = "right for your centre c: fix c, and they follow"
        causes.append(f"the turned points: {cause}")
    return ("\n" + " " * 16).join(causes) if causes else "compare each part with the expected one"


def _rt_exception_hint(exc: Exception, args: tuple) -> str:
    img, X, A = args
    H, W = img.shape
    text = str(exc)
    match = re.search(r"index (-?\d+) is out of bounds for axis (\d) with size (\d+)", text)
    if isinstance(exc, IndexError) and match:
        index, axis, size = (int(g) for g in match.groups())
        if axis == 0 and index in np.rint(X[:, 0]).astype(int) and index >= H:
            return (
                f"img[u, v]: u = {index} was used as the row, and this image has {H} rows (shape ({H}, {W})). "
                "numpy indexes the row first, and the row is v: img[v, u]"
            )
        if index == size:
            return (
                f"an index {size} on an axis of size {size}: counting from 1? numpy and pixel coordinates count from 0 "
                "(the last row is H - 1, the last column W - 1): img[v, u]"
            )
    if isinstance(exc, IndexError) and ("integer" in text or "only integers" in text):
        return (
            "X holds floats (points are float arrays in this course) and numpy indexes with integers: "
            "convert the whole-number coordinates first, u, v = X[:, 0].astype(int), X[:, 1].astype(int)"
        )
    if isinstance(exc, ValueError) and "matmul" in text:
        return (
            "A @ X treats X as one column per point, but points are rows, shape (N, 2): the textbook's A x is "
            "X @ A.T for every row at once (or (A @ X.T).T)"
        )
    n = len(X)
    if isinstance(exc, ValueError) and "broadcast" in text and f"(2,{n})" in text.replace(" ", ""):
        return (
            f"A @ (X - c).T gives the points as columns, shape (2, {n}), and c is one (u, v) row: transpose back "
            "before adding c, (A @ (X - c).T).T + c, or keep points as rows throughout: (X - c) @ A.T + c"
        )
    if isinstance(exc, ValueError) and "broadcast" in text and "(2,1)" in text.replace(" ", ""):
        return (
            "the centre is a (2, 1) column, and points are rows: make c a (2,) array, "
            "np.array([(W - 1) / 2, (H - 1) / 2]), so that X - c subtracts it from every row"
        )
    if isinstance(exc, ValueError) and "unpack" in text:
        return "img.shape is (H, W): two numbers, rows first: H, W = img.shape"
    return ""


def read_and_turn(img, X, A):
    """Section 3's conventions: the image's centre, the pixels under the points X, and X turned about the centre."""
    H, W = img.shape[:2]  # numpy's shape: rows (H) first, then columns (W)
    c = np.array([(W - 1) / 2, (H - 1) / 2])  # halfway between the first and the last pixel centres
    u, v = X[:, 0].astype(int), X[:, 1].astype(int)
    values = img[v, u]  # row v, column u
    turned = (X - c) @ A.T + c  # x' = c + A (x - c), for every row at once
    return c, values, turned


def _rt_wrong(centre=None, read=None, turn=None):
    """A wrong read_and_turn for the tests: the teaching solution with one step replaced."""

    def wrong(img, X, A):
        H, W = img.shape
        c = (
            np.array([(W - 1) / 2, (H - 1) / 2])
            if centre is None
            else np.asarray(centre(W, H), dtype=float)
        )
        u, v = X[:, 0].astype(int), X[:, 1].astype(int)
        values = img[v, u] if read is None else read(img, u, v)
        turned = (X - c) @ A.T + c if turn is None else turn(X, A, c)
        return c, values, turned

    return wrong


def _float_index(img, X, A):
    """Indexing with the float coordinates of X (a wrong variant for the tests)."""
    return read_and_turn(img, X, A)[0], img[X[:, 1], X[:, 0]], read_and_turn(img, X, A)[2]


register_exercise(
    Exercise(
        name="read_and_turn",
        lesson="00",
        reference=_read_and_turn_reference,
        cases=_rt_cases,
        compare=_same_triple,
        diagnose=_rt_diagnose,
        describe_input=_rt_describe,
        exception_hint=_rt_exception_hint,
        wrong_variants=(
            (_rt_wrong(centre=lambda W, H: (W / 2, H / 2)), "you used (W / 2, H / 2)"),
            (_rt_wrong(centre=lambda W, H: (W // 2, H // 2)), "W // 2"),
            (_rt_wrong(centre=lambda W, H: ((W + 1) / 2, (H + 1) / 2)), "counted from 1"),
            (
                _rt_wrong(centre=lambda W, H: ((W - 1) // 2, (H - 1) // 2)),
                "rounded the centre down",
            ),
            (_rt_wrong(centre=lambda W, H: ((H - 1) / 2, (W - 1) / 2)), "width and height swapped"),
            (_rt_wrong(centre=lambda W, H: (W, H)), "that is the size"),
            (_rt_wrong(read=lambda img, u, v: img[u, v]), "img[u, v] reads row u, column v"),
            (
                _rt_wrong(read=lambda img, u, v: img[v - 1, u - 1]),
                "X[0] = (4, 0) is pixel img[0, 4] = 4",
            ),
            (_rt_wrong(read=lambda img, u, v: img[v + 1, u + 1]), "counting from 1?"),
            (_rt_wrong(read=lambda img, u, v: img[v][:, u]), "every combination"),
            (
                lambda img, X, A: (
                    read_and_turn(img, X, A)[0],
                    img[X.astype(int)],
                    read_and_turn(img, X, A)[2],
                ),
                "img[X] indexes rows",
            ),
            (_float_index, "numpy indexes with integers"),
            (_rt_wrong(turn=lambda X, A, c: (X - c) @ A + c), "X @ A applies A's transpose"),
            (
                _rt_wrong(turn=lambda X, A, c: (A @ X.T).T * 0 + A @ X),
                "A @ X treats X as one column per point",
            ),
            (_rt_wrong(turn=lambda X, A, c: A @ (X - c).T + c[:, None]), "(A @ X.T).T"),
            (_rt_wrong(turn=lambda X, A, c: X @ A.T), "you turned about the origin"),
            (_rt_wrong(turn=lambda X, A, c: A @ (X - c).T + c), "transpose back before adding c"),
            (_rt_wrong(turn=lambda X, A, c: c - (X - c) @ A.T), "a sign flip"),
            (
                lambda img, X, A: (
                    read_and_turn(img, X - np.array([[2.0], [2.0]]).T * 0, A)[:2]
                    + ((X - np.array([[2.0], [2.0]])) @ A.T,)
                ),
                "the centre is a (2, 1) column",
            ),
            (
                _rt_wrong(turn=lambda X, A, c: (X - c) @ np.linalg.inv(A).T + c),
                "you applied A's inverse",
            ),
            (_rt_wrong(turn=lambda X, A, c: (X - c) @ A.T), "forgot to add the centre back"),
            (
                _rt_wrong(turn=lambda X, A, c: (X - [2.5, 2.5]) @ A.T + [2.5, 2.5]),
                "you turned about the wrong centre, [2.5, 2.5]",
            ),
            (
                _rt_wrong(
                    centre=lambda W, H: (W / 2, H / 2), turn=lambda X, A, c: (X - c) @ A.T + c
                ),
                "right for your centre c",
            ),
            (lambda img, X, A: read_and_turn(img, X, A)[:2], "you returned 2 things"),
            (lambda img, X, A: read_and_turn(img, X, A)[0], "you returned only the centre"),
        ),
        teaching=read_and_turn,
    )
)
