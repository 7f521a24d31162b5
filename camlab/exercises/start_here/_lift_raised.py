"""Lesson 00's lift when the student's code raises: where it raised, and the likely cause of each error.

Students who lift one point reach for list habits (``p.append``, ``q[2] = 1.0``), count from 1, or copy
the worked example's batch code (``np.hstack([p, np.ones((len(p), 1))])``) for a single point; each
raises, and the hints every check shares would blame something else. :data:`RAISED` lists those errors
as :class:`~camlab.exercises._core.Mistake` rows, read in order by :func:`batch_code_hint`.
"""

from __future__ import annotations

import dis
import re
from types import SimpleNamespace, TracebackType

from .._core import Mistake, first_mistake
from ._lift_causes import APPEND, ONE_POINT


def raised_where(exc: BaseException) -> tuple[str, str]:
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


def unpacked_from(exc: BaseException) -> str:
    """What the student's line unpacked when ``exc`` was raised: '.shape' for ``H, W, C = img.shape``, 'X' for ``u, v = X``.

    Read from the bytecode before the failing ``UNPACK_SEQUENCE``: an attribute as '.name', a variable as its
    name, '' for anything else (a call's result).
    """
    tb = exc.__traceback__
    while tb is not None and tb.tb_next is not None:
        tb = tb.tb_next
    if tb is None:
        return ""
    code = [i for i in dis.get_instructions(tb.tb_frame.f_code) if i.opname != "CACHE"]
    at = next((k for k, i in enumerate(code) if i.offset == tb.tb_lasti), 0)
    if at == 0 or code[at].opname != "UNPACK_SEQUENCE":
        return ""
    before = code[at - 1]
    if before.opname == "LOAD_ATTR":
        return f".{before.argval}"
    return (
        str(before.argval)
        if before.opname.startswith(("LOAD_FAST", "LOAD_NAME", "LOAD_GLOBAL", "LOAD_DEREF"))
        else ""
    )


def index_hint(exc: Exception) -> str:
    """An index past the end of the point: writing p[2] (growing the array) or reading it (1-based)."""
    called, operation = raised_where(exc)
    match = re.search(r"index (-?\d+) is out of bounds for axis 0 with size (\d+)", str(exc))
    index = match.group(1) if match else "2"
    if called == "np.insert":
        return (
            "np.insert's position counts from 0 and can be at most len(p) = 2, which inserts after y: "
            f"np.insert(p, 2, 1.0), or simply {APPEND}"
        )
    if called:
        return ""
    if operation == "STORE_SUBSCR":
        return (
            f"assigning p[{index}] = ... cannot grow an array: a numpy array has a fixed size, and a (2,) point has "
            f"only the indices 0 and 1 (a Python list cannot grow this way either); build a new, longer array: "
            f"{APPEND}"
        )
    return (
        f"counting from 1: numpy counts from 0, so the point's coordinates are p[0] (x) and p[1] (y), and there "
        f"is no p[{index}]; then append the 1: {APPEND}"
    )


def _joined(s) -> str:
    """The joining function a 1-D point met a 2-D column in (np.concatenate behind the others)."""
    return s.called if s.called in ("np.hstack", "np.vstack") else "np.concatenate"


def _concatenation_axis(s) -> bool:
    return "except for the concatenation axis" in s.text


# Each row's test reads the error ``s.exc``, its text ``s.text`` and the numpy function the student's code
# called, ``s.called`` (:func:`raised_where`); checked in order, the first that matches names the cause.
RAISED = (
    Mistake(
        "p plus a 3-vector",
        lambda s: (
            isinstance(s.exc, ValueError)
            and "broadcast" in s.text
            and {"(2,)", "(3,)"} <= set(re.findall(r"\(\d+,\)", s.text))
        ),
        (
            "numpy's + and * act entry by entry and need equal lengths: p has 2 entries and your array 3 "
            "(p + [0, 0, 1], p * np.ones(3)), so they cannot pair up, and arithmetic cannot add a coordinate; "
            f"make a new array with one more entry: {APPEND}"
        ),
    ),
    Mistake(
        "int() of the point",
        lambda s: isinstance(s.exc, TypeError) and "converted to Python scalars" in s.text,
        (
            "int() (or float()) converts one number, and p holds two, x and y: lifting keeps them as they are, "
            f"floats, and appends w: {APPEND}"
        ),
    ),
    Mistake(
        "p unpacked into three",
        lambda s: isinstance(s.exc, ValueError) and "expected 3, got 2" in s.text,
        (
            "p holds two numbers, x and y, and you unpacked it into three names (x, y, w = p): the point has "
            f"no w yet; x, y = p, or build the answer from p at once: {APPEND}"
        ),
    ),
    Mistake(
        "an index past the end of the point",
        lambda s: isinstance(s.exc, IndexError) and "out of bounds for axis 0" in s.text,
        lambda s: index_hint(s.exc),
    ),
    Mistake(
        "a list grown by assignment",
        lambda s: isinstance(s.exc, IndexError) and "list assignment index out of range" in s.text,
        (
            "assigning q[2] = ... cannot grow a Python list (nor a numpy array): a list grows with "
            f"q.append(1.0); for the array this exercise wants, {APPEND}"
        ),
    ),
    Mistake(
        "a list indexed from 1",
        lambda s: isinstance(s.exc, IndexError) and "list index out of range" in s.text,
        (
            f"counting from 1: Python counts from 0, so the point's coordinates are p[0] (x) and p[1] (y); "
            f"then append the 1: {APPEND}"
        ),
    ),
    Mistake(
        "p reshaped to 3",
        lambda s: "cannot reshape array of size 2" in s.text,
        (
            "reshape rearranges the numbers an array holds, and p holds 2: it cannot make a third; "
            f"append it: {APPEND}"
        ),
    ),
    Mistake(
        "p.append",
        lambda s: "has no attribute 'append'" in s.text,
        (
            "p.append(1.0) is how a Python list grows; a numpy array has no .append method "
            f"(its size is fixed): {APPEND} returns a new, longer array"
        ),
    ),
    Mistake(
        "p.resize",
        lambda s: "cannot resize" in s.text,
        (
            "p.resize(3) changes the caller's array in place (numpy refuses while another name refers to it), "
            f"and the caller's point must come back as it went in; build a new array: {APPEND}"
        ),
    ),
    Mistake(
        "np.concatenate(p, 1)",
        lambda s: "zero-dimensional arrays cannot be concatenated" in s.text,
        (
            "np.concatenate takes one sequence of arrays, and its second argument is the "
            "axis: np.concatenate([p, [1.0]]), or simply np.append(p, 1.0)"
        ),
    ),
    Mistake(
        "np.concatenate([p, 1.0])",
        lambda s: "same number of dimensions" in s.text and "0 dimension(s)" in s.text,
        (
            "np.concatenate joins arrays, and the 1 is a bare number (0-D): write it as "
            "[1.0], np.concatenate([p, [1.0]]), or use np.append(p, 1.0) or np.hstack([p, 1.0]), which accept it"
        ),
    ),
    Mistake(
        "a column of ones joined to one point",
        lambda s: "same number of dimensions" in s.text,
        lambda s: (
            f"batch code on one point: {ONE_POINT}, so {_joined(s)} joins a 1-D array to a 2-D one (a column "
            f"such as np.ones((len(p), 1)) or [[1.0]]); for one point append one number: {APPEND}"
        ),
    ),
    Mistake(
        "a second axis indexed on one point",
        lambda s: (
            "too many indices" in s.text or "out of bounds for array of dimension 1" in s.text
        ),
        (
            f"batch code on one point: {ONE_POINT}, so it has no second axis (p[:, :2], "
            f"axis=1); its coordinates are p[0] and p[1], and {APPEND} lifts it"
        ),
    ),
    Mistake(
        "np.vstack",
        lambda s: _concatenation_axis(s) and s.called == "np.vstack",
        (
            "np.vstack stacks its arguments as rows, one under the other, and p (2 numbers) and the 1 "
            f"(1 number) are rows of different lengths; to add a coordinate, append it: {APPEND} or np.r_[p, 1.0]"
        ),
    ),
    Mistake(
        "np.c_ or np.column_stack",
        lambda s: _concatenation_axis(s) and s.called in ("np.c_", "np.column_stack"),
        lambda s: (
            f"{s.called} joins columns, so it treats x and y as two rows: "
            f"{ONE_POINT}; append one number instead: {APPEND} or np.r_[p, 1.0]"
        ),
    ),
    Mistake(
        "arrays of different lengths joined",
        _concatenation_axis,
        (
            f"the arrays you joined differ in length along the other axis; {ONE_POINT}: "
            f"append one number: {APPEND}"
        ),
    ),
    Mistake(
        "np.stack",
        lambda s: s.called == "np.stack" and "same shape" in s.text,
        (
            "np.stack puts arrays of the same shape side by side along a new axis, and p (2 numbers) and [1.0] "
            f"differ; to add a coordinate, append it: {APPEND}"
        ),
    ),
)


def batch_code_hint(exc: Exception, args: tuple) -> str:
    """The likely cause when the student's code raises: list habits, index slips, the wrong joining function.

    ``np.hstack([p, np.ones((len(p), 1))])`` joins a 1-D and a 2-D array, ``p[:, :2]`` indexes a
    second axis that one point lacks, ``np.c_[p, 1]`` / ``np.column_stack`` treat x and y as two
    rows, ``np.vstack`` stacks rows of different lengths, ``p[2] = 1.0`` tries to grow the array,
    ``p[1], p[2]`` counts from 1: each raises, and the shared hints would blame something else (a
    1-based column of an (N, 3) array). The causes are the rows of :data:`RAISED`; '' when none
    matches (``args``, the test input, is part of ``Exercise.exception_hint``'s signature).
    """
    context = SimpleNamespace(exc=exc, text=str(exc), called=raised_where(exc)[0])
    return first_mistake(RAISED, context) or ""
