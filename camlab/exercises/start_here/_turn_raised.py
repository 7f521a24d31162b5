"""What lesson 00's read_and_turn says about an error the student's code raises: the table :data:`RAISED`.

Each row is a :class:`~camlab.exercises._core.Mistake`, checked in order by
:func:`~camlab.exercises._core.first_mistake` (:func:`exception_hint`); the mistakes in the answers
themselves are in :mod:`._turn_causes`.
"""

from __future__ import annotations

import re
from types import SimpleNamespace

import numpy as np

from .._core import Mistake, first_mistake
from ._lift_raised import unpacked_from
from ._turn_causes import ceil_moved


def _index_error(s) -> bool:
    return isinstance(s.exc, IndexError) and s.index is not None


def _broadcast(s, shape: str) -> bool:
    return (
        isinstance(s.exc, ValueError) and "broadcast" in s.text and shape in s.text.replace(" ", "")
    )


# Checked in order on the error ``s.exc`` (its text ``s.text``; ``s.index``, ``s.axis``, ``s.size`` parsed
# from an index out of bounds, else None) raised on the points ``s.X`` and an ``s.H`` x ``s.W`` image.
RAISED = (
    Mistake(
        "img[u, v] past the last row",
        lambda s: (
            _index_error(s)
            and s.axis == 0
            and s.index in np.rint(s.X[:, 0]).astype(int)
            and s.index >= s.H
        ),
        lambda s: (
            f"img[u, v]: u = {s.index} was used as the row, and this image has {s.H} rows (shape ({s.H}, {s.W})). "
            "numpy indexes the row first, and the row is v: img[v, u] (img[X] fails the same way: it reads every "
            "number of X as a row; take u, v = X[:, 0], X[:, 1])"
        ),
    ),
    Mistake(
        "img[u, v] past the last column",
        lambda s: (
            _index_error(s)
            and s.axis == 1
            and s.index in np.rint(s.X[:, 1]).astype(int)
            and s.index >= s.W
        ),
        lambda s: (
            f"img[u, v]: v = {s.index} was used as the column, and this image, taller than wide, has {s.W} columns "
            f"(shape ({s.H}, {s.W})). numpy indexes the row first, and the row is v: img[v, u]"
        ),
    ),
    Mistake(
        "a transposed image read [v, u]",
        lambda s: (
            _index_error(s)
            and s.H != s.W
            and (
                (s.axis == 1 and s.size == s.H and s.index in np.rint(s.X[:, 0]).astype(int))
                or (s.axis == 0 and s.size == s.W and s.index in np.rint(s.X[:, 1]).astype(int))
            )
        ),
        lambda s: (
            f"the image was transposed: an axis of size {s.size} met "
            f"{'u' if s.axis == 1 else 'v'} = {s.index}, as in img.T[v, u] (or an image built with its axes "
            f"swapped, np.zeros((W, H))). img itself has shape ({s.H}, {s.W}), rows first: read it as it is, "
            "img[v, u], with no .T"
        ),
    ),
    Mistake(
        "rounded up by np.ceil",
        lambda s: _index_error(s) and s.index == s.size and ceil_moved(s.X) is not None,
        lambda s: (
            f"{ceil_moved(s.X)}. Round to the nearest whole number, then convert: u, v = np.rint(X).astype(int).T"
        ),
    ),
    Mistake(
        "half a pixel added before rounding",
        lambda s: (
            _index_error(s)
            and s.index == s.size
            and s.index in np.rint(s.X[:, 1 - s.axis] + 0.5).astype(int)
            and s.index - 1 in np.rint(s.X[:, 1 - s.axis]).astype(int)
        ),
        lambda s: (
            f"an index {s.size} on an axis of size {s.size}, one past the last {('row', 'column')[s.axis]}: counting "
            "from 1? numpy and pixel coordinates count from 0. Or half a pixel added before rounding? np.rint(X + 0.5) "
            f"sends {s.size - 1} to {s.size - 1}.5 and on to {s.size} (np.rint rounds halves to even); pixel centres "
            "are whole numbers here, not Pillow's (u + 0.5, v + 0.5) (section 3.4). Round X itself: "
            "u, v = np.rint(X).astype(int).T; img[v, u]"
        ),
    ),
    Mistake(
        "counted from 1",
        lambda s: _index_error(s) and s.index == s.size,
        lambda s: (
            f"an index {s.size} on an axis of size {s.size}: counting from 1? numpy and pixel coordinates count from 0 "
            "(the last row is H - 1, the last column W - 1): img[v, u]"
        ),
    ),
    Mistake(
        "an index past the image",
        lambda s: _index_error(s),
        lambda s: (
            f"an index {s.index} on axis {s.axis}, of size {s.size}: this image has shape ({s.H}, {s.W}), so its rows "
            f"(axis 0, v) run 0 .. {s.H - 1} and its columns (axis 1, u) 0 .. {s.W - 1}; read img[v, u] with the "
            "points' own u and v, rounded: u, v = np.rint(X).astype(int).T"
        ),
    ),
    Mistake(
        "float indices",
        lambda s: (
            isinstance(s.exc, IndexError) and ("integer" in s.text or "only integers" in s.text)
        ),
        (
            "X holds floats (points are float arrays in this course) and numpy indexes with integers: "
            "round, then convert: u, v = np.rint(X).astype(int).T (.astype(int) alone truncates, and a computed "
            "479 can be 478.99999999999994, which it makes 478)"
        ),
    ),
    Mistake(
        "A @ X",
        lambda s: isinstance(s.exc, ValueError) and "matmul" in s.text,
        (
            "A @ X treats X as one column per point, but points are rows, shape (N, 2): the textbook's A x is "
            "X @ A.T for every row at once (or (A @ X.T).T)"
        ),
    ),
    Mistake(
        "* for @",
        lambda s: _broadcast(s, f"({len(s.X)},2)") and _broadcast(s, "(2,2)"),
        lambda s: (
            f"* multiplies entry by entry, and X - c, shape ({len(s.X)}, 2), and A, shape (2, 2), do not pair up: "
            "a matrix acts on points with @, so (X - c) @ A.T + c"
        ),
    ),
    Mistake(
        "columns plus a row",
        lambda s: _broadcast(s, f"(2,{len(s.X)})"),
        lambda s: (
            f"A @ (X - c).T gives the points as columns, shape (2, {len(s.X)}), and c is one (u, v) row: transpose back "
            "before adding c, (A @ (X - c).T).T + c, or keep points as rows throughout: (X - c) @ A.T + c"
        ),
    ),
    Mistake(
        "a (2, 1) centre",
        lambda s: _broadcast(s, "(2,1)"),
        (
            "the centre is a (2, 1) column, and points are rows: make c a (2,) array, "
            "np.array([(W - 1) / 2, (H - 1) / 2]), so that X - c subtracts it from every row"
        ),
    ),
    Mistake(
        "a colour image's shape unpacked",
        lambda s: _unpack(s, "expected 3, got 2") and s.unpacked in (".shape", ""),
        lambda s: (
            f"H, W, C = img.shape unpacks a colour image's (H, W, 3); this grey image's shape is ({s.H}, {s.W}), "
            "two numbers: H, W = img.shape[:2] reads both kinds"
        ),
    ),
    Mistake(
        "points unpacked as rows",
        lambda s: _unpack(s, "too many values") and s.unpacked != ".shape",
        lambda s: (
            f"{'u, v = ' + s.unpacked if s.unpacked not in ('', '.T') else 'unpacking an (N, 2) array into u, v'} "
            f"takes its rows, one per point, and X has {len(s.X)} points: unpack its two columns, "
            "u, v = np.rint(X).astype(int).T (.T makes the columns rows)"
        ),
    ),
    Mistake(
        "Pillow's img.size",
        lambda s: isinstance(s.exc, TypeError) and "cannot unpack non-iterable int" in s.text,
        lambda s: (
            f"{'numpy' + chr(39) + 's img.size is the number of pixels, one int (H * W = ' + str(s.H * s.W) + ')' if s.unpacked == '.size' else 'you unpacked one number into two names'}"
            "; Pillow's img.size is (W, H), but img here is a numpy array: H, W = img.shape"
        ),
    ),
    Mistake(
        "unpacked into the wrong number of names",
        lambda s: isinstance(s.exc, ValueError) and "unpack" in s.text,
        lambda s: (
            f"{s.unpacked or 'the value'} holds another number of items than the names you unpacked it into: "
            "img.shape is (H, W), and u, v = np.rint(X).astype(int).T gives the two columns of X"
        ),
    ),
    Mistake(
        "int() of an array",
        lambda s: isinstance(s.exc, TypeError) and "converted to Python scalars" in s.text,
        lambda s: (
            f"int() converts one number, and a column of X holds {len(s.X)}: convert the whole array at once, "
            "after rounding: u, v = np.rint(X).astype(int).T"
        ),
    ),
)


def _unpack(s, words: str) -> bool:
    return isinstance(s.exc, ValueError) and "unpack" in s.text and words in s.text


def exception_hint(exc: Exception, args: tuple) -> str:
    """The likely cause of ``exc``, raised by the student's function on ``args`` = (img, X, A).

    The first row of :data:`RAISED` it matches, else '' (the hints every check shares).
    """
    img, X, _ = args
    H, W = img.shape
    text = str(exc)
    match = re.search(r"index (-?\d+) is out of bounds for axis (\d) with size (\d+)", text)
    index, axis, size = (int(g) for g in match.groups()) if match else (None, None, None)
    s = SimpleNamespace(
        exc=exc,
        text=text,
        X=X,
        H=H,
        W=W,
        index=index,
        axis=axis,
        size=size,
        unpacked=unpacked_from(exc),
    )
    return first_mistake(RAISED, s) or ""
