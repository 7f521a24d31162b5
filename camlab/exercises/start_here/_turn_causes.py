"""What went wrong in lesson 00's read_and_turn: the tables of its typical mistakes, one per part of the answer.

The answer has three parts: the image's centre (:data:`CENTRE_MISTAKES`, read by :func:`centre_cause`),
the pixel values under the points (:data:`VALUE_MISTAKES`, :func:`values_cause`) and the points turned
about the centre (:data:`TURN_MISTAKES`, :func:`turned_cause`); :mod:`._turn_raised` names the errors the student's code
raises. Each table is a tuple of
:class:`~camlab.exercises._core.Mistake` rows, checked in order by
:func:`~camlab.exercises._core.first_mistake`.
"""

from __future__ import annotations

import sys
from types import SimpleNamespace

import numpy as np

from .._core import Mistake, first_mistake


def numbers(a) -> str:
    """A small array as the student could type it: [[5, 1], [0, 3]] (whole numbers without '.0')."""
    a = np.asarray(a, dtype=float)
    if a.ndim == 0:
        x = float(a)
        near = round(x)
        if (
            x != near and abs(x - near) < 1e-9
        ):  # a computed whole number: show it in full, 2.9999999999999996
            return repr(x)
        return f"{x:.4g}"
    return "[" + ", ".join(numbers(x) for x in a) + "]"


# -- the centre ---------------------------------------------------------------------------------------

_HALF = (
    "half a pixel off: pixel centres sit at whole numbers, 0 .. W - 1, so the centre is halfway between the "
    "first and the last, ((W - 1)/2, (H - 1)/2); W / 2 is the centre where whole numbers are pixel corners "
    "(Pillow, COLMAP)"
)

# Centres students compute instead of ((W - 1)/2, (H - 1)/2) for an image of ``s.W`` x ``s.H`` pixels,
# each with its cause (first match wins).
CENTRE_MISTAKES = (
    Mistake(
        "W / 2",
        lambda s: (s.W / 2, s.H / 2),
        f"you used (W / 2, H / 2) (or W // 2): {_HALF}. W // 2 agrees with (W - 1)/2 only for odd W",
    ),
    Mistake(
        "W // 2",
        lambda s: (s.W // 2, s.H // 2),
        f"you used (W // 2, H // 2): {_HALF}. W // 2 agrees with (W - 1)/2 only for odd W",
    ),
    Mistake(
        "(W + 1) / 2",
        lambda s: ((s.W + 1) / 2, (s.H + 1) / 2),
        "you used (W + 1)/2: the centre counted from 1 (MATLAB's); here pixels count from 0, so ((W - 1)/2, (H - 1)/2)",
    ),
    Mistake(
        "(W - 1) // 2",
        lambda s: ((s.W - 1) // 2, (s.H - 1) // 2),
        "you rounded the centre down to a whole pixel ((W - 1) // 2): an even side's centre lies between two pixels; keep (W - 1) / 2",
    ),
    Mistake(
        "W and H swapped",
        lambda s: ((s.H - 1) / 2, (s.W - 1) / 2),
        "width and height swapped: numpy's img.shape is (H, W), rows first, so write H, W = img.shape; the centre is ((W - 1)/2, (H - 1)/2), u first",
    ),
    Mistake(
        "W and H swapped, half a pixel off",
        lambda s: (s.H / 2, s.W / 2),
        "width and height swapped (img.shape is (H, W): H, W = img.shape), and half a pixel off: the centre is ((W - 1)/2, (H - 1)/2)",
    ),
    Mistake(
        "W - 1/2",
        lambda s: (s.W - 0.5, s.H - 0.5),
        "you computed W - 1/2, which is W - 0.5: / binds before -, as in arithmetic; bracket the difference, "
        "((W - 1) / 2, (H - 1) / 2)",
    ),
    Mistake(
        "the last pixel",
        lambda s: (s.W - 1, s.H - 1),
        "that is the last pixel, (W - 1, H - 1); the centre is halfway to it: ((W - 1)/2, (H - 1)/2)",
    ),
    Mistake(
        "the size",
        lambda s: (s.W, s.H),
        "that is the size (W, H); the centre is ((W - 1)/2, (H - 1)/2)",
    ),
    Mistake(
        "img.shape",
        lambda s: (s.H, s.W),
        "that is img.shape, (H, W); the centre is ((W - 1)/2, (H - 1)/2)",
    ),
)


def _same_centre(c: np.ndarray, slip: tuple) -> bool:
    return c.shape == (2,) and np.allclose(c, slip)


def _whole(x) -> bool:
    return isinstance(x, (int, np.integer)) and not isinstance(x, bool) and x > 0


def notebook_centre(c: np.ndarray, W: int, H: int) -> str:
    """Whether ``c`` comes from the notebook's variables (section 3.4's ``W, H``, section 3.3's ``c``), not ``img``.

    A function that writes ``(W - 1) / 2`` without ``H, W = img.shape`` reads the notebook's ``W, H = 640, 480``
    and returns (319.5, 239.5) for every image; one that never computes ``c`` returns the notebook's ``c``.
    '' when neither explains ``c``.
    """
    names = vars(sys.modules["__main__"]) if "__main__" in sys.modules else {}
    Wn, Hn = names.get("W"), names.get("H")
    if _whole(Wn) and _whole(Hn) and (Wn, Hn) != (W, H):
        if np.allclose(c, ((Wn - 1) / 2, (Hn - 1) / 2)):
            return (
                f"({c[0]:g}, {c[1]:g}) is the centre of a {Wn} x {Hn} image: your function reads the notebook's "
                f"W, H = {Wn}, {Hn} (section 3.4), not this image's {W} x {H}; write H, W = img.shape inside it"
            )
    try:
        cn = np.asarray(names.get("c"), dtype=float)
    except (TypeError, ValueError):
        return ""
    if cn.shape == (2,) and np.allclose(c, cn) and not np.allclose(cn, ((W - 1) / 2, (H - 1) / 2)):
        return (
            f"({c[0]:g}, {c[1]:g}) is the notebook's variable c (section 3.3), not this image's centre: compute "
            "it inside your function, H, W = img.shape; c = ((W - 1)/2, (H - 1)/2)"
        )
    return ""


def centre_cause(c: np.ndarray, W: int, H: int, X: np.ndarray | None = None) -> str:
    """Why ``c`` is not the centre of a ``W`` x ``H`` image: a notebook variable, the mean of the points ``X``, else the first of :data:`CENTRE_MISTAKES`."""
    if X is not None and np.allclose(c, np.mean(X, axis=0)):
        return (
            f"{numbers(c)} is the mean of the points X (X.mean(axis=0)), not the image's centre: the centre comes "
            f"from img.shape, ((W - 1)/2, (H - 1)/2) = ({(W - 1) / 2:g}, {(H - 1) / 2:g}), whatever the points"
        )
    hint = notebook_centre(c, W, H) or first_mistake(
        CENTRE_MISTAKES, SimpleNamespace(W=W, H=H), c, _same_centre
    )
    return (
        hint
        or f"the centre of a W x H = {W} x {H} image is ((W - 1)/2, (H - 1)/2) = ({(W - 1) / 2:g}, {(H - 1) / 2:g})"
    )


# -- the values read ----------------------------------------------------------------------------------


def _read_at(s, vv: np.ndarray, uu: np.ndarray) -> np.ndarray | None:
    """``img[vv, uu]`` as numpy reads it, or None where numpy would raise.

    An index -1 wraps round to the last row or column; where numpy raises, the slip shows as an
    IndexError instead, named by :data:`RAISED`.
    """
    vv, uu = np.asarray(vv), np.asarray(uu)
    if np.all((-s.H <= vv) & (vv < s.H) & (-s.W <= uu) & (uu < s.W)):
        return s.img[vv, uu]
    return None


def _reads(s, vv: np.ndarray, uu: np.ndarray) -> bool:
    """Whether the values are those numpy reads at img[vv, uu] (and differ from the right ones there)."""
    read = _read_at(s, vv, uu)
    return read is not None and np.allclose(s.values, read)


def _wraps(s, vv: np.ndarray, uu: np.ndarray) -> str:
    """The note that an index of -1 read the last row or column without an error, if one did."""
    rows, cols = bool(np.any(np.asarray(vv) < 0)), bool(np.any(np.asarray(uu) < 0))
    if not (rows or cols):
        return ""
    where = "row" if rows and not cols else "column" if cols and not rows else "row or column"
    return f"; at 0 the index -1 silently reads the last {where} (numpy counts -1 from the end), so nothing raised"


def _shift_mistake(dv: int, du: int) -> Mistake:
    """img[v + dv, u + du]: a read off by one row and/or column, named with the index the student wrote."""

    def index(d: int, name: str) -> str:
        return name if d == 0 else f"{name} {'+' if d > 0 else '-'} {abs(d)}"

    read = f"img[{index(dv, 'v')}, {index(du, 'u')}]"
    moved = (
        " and ".join(
            f"one {what} {where}"
            for d, what, where in (
                (dv, "row", "above" if dv < 0 else "below"),
                (du, "column", "left of" if du < 0 else "right of"),
            )
            if d != 0
        )
        .replace("above and", "up and")
        .replace("below and", "down and")
    )
    why = (
        "Counting from 1, as MATLAB does? numpy and pixel coordinates count from 0"
        if dv <= 0 and du <= 0
        else "Pixel coordinates and numpy both count from 0, and pixel (u, v) is img[v, u] itself"
    )
    return Mistake(
        f"read {read}",
        lambda s: _reads(s, s.v + dv, s.u + du),
        lambda s: (
            f"you read {read}, the pixel {moved} each point: an off-by-one. {why}: read img[v, u]"
            + _wraps(s, s.v + dv, s.u + du)
        ),
    )


def _read_turned(s, to_int) -> bool:
    """Whether the values were read at the moved points (rounded by ``to_int``) instead of at X."""
    if s.turned is None:
        return False
    uu, vv = to_int(s.turned).T
    return not np.allclose(s.turned, s.X) and _reads(s, vv, uu)


def rescaled_by(s) -> float | None:
    """The one factor k with values = k img[v, u] (k != 1), if the values are the right pixels rescaled."""
    right = s.img[s.v, s.u].astype(float)
    got = np.asarray(s.values, dtype=float)
    if s.values.shape != right.shape or not right.any():
        return None
    k = float(got @ right / (right @ right))
    return k if not np.isclose(k, 1.0) and np.allclose(got, k * right, rtol=1e-6, atol=0) else None


def _factor_words(k: float) -> str:
    """k as the student probably wrote it: divided by 255 (a 0 .. 1 normalisation), times 255, ..."""
    for n in (255, 256, 65535, 1000, 10, 100):
        if np.isclose(k, 1 / n):
            return f"divided by {n}" + (
                " (a 0 .. 1 normalisation)" if n in (255, 256, 65535) else ""
            )
        if np.isclose(k, n):
            return f"multiplied by {n}"
    return f"multiplied by {k:.4g}"


def _half_read(s, d: float) -> bool:
    """Whether the values were read at np.rint(X + d), half a pixel added before rounding."""
    uu, vv = np.rint(s.X + d).astype(int).T
    moved = not (np.array_equal(uu, s.u) and np.array_equal(vv, s.v))
    return moved and _reads(s, vv, uu)


def _half_read_hint(s, d: float) -> str:
    uu, vv = np.rint(s.X + d).astype(int).T
    k = int(np.argmax((uu != s.u) | (vv != s.v)))
    return (
        f"you added {d:+g} before rounding, np.rint(X {'+' if d > 0 else '-'} 0.5): X[{k}] = ({s.u[k]}, {s.v[k]}) "
        f"read pixel ({uu[k]}, {vv[k]}), and since np.rint rounds halves to the even number, other points read "
        "their own pixel. Half a pixel moves a point from its pixel's centre to a corner (Pillow's and COLMAP's "
        "whole numbers, section 3.4); here pixel centres are whole numbers, so round X itself: "
        "u, v = np.rint(X).astype(int).T"
    )


def _truncated_hint(X: np.ndarray) -> str:
    """The hint for values read at the truncated points, quoting the first entry of X that truncation moved."""
    i, j = np.argwhere(np.trunc(X) != np.rint(X))[0]
    return (
        f"X holds whole numbers only up to floating-point rounding, as computed points do, and .astype(int) "
        f"(or int(), or np.floor) truncates: X[{i}, {j}] = {float(X[i, j])!r} became {int(X[i, j])}, the pixel before. "
        "Round, then convert: u, v = np.rint(X).astype(int).T"
    )


def ceil_moved(X: np.ndarray) -> str | None:
    """How np.ceil moved the first entry of ``X`` it rounds up past its nearest whole number, or None."""
    moved = np.argwhere(np.ceil(X) != np.rint(X))
    if not len(moved):
        return None
    i, j = moved[0]
    return (
        f"np.ceil rounds up: X[{i}, {j}] = {float(X[i, j])!r}, a computed {np.rint(X[i, j]):g}, became "
        f"{np.ceil(X[i, j]):g}, the pixel after"
    )


# Checked in order on the values read, ``s.values``, for the image ``s.img`` (``s.H`` x ``s.W``), the
# points' columns and rows ``s.u``, ``s.v`` (``s.n`` points) and the right turned points ``s.turned``.
VALUE_MISTAKES = (
    Mistake(
        "img[X]",
        lambda s: s.values.shape == (s.n, 2, s.W),
        "img[X] indexes rows with every number of X: take one row and one column per point, img[v, u] with u, v = X[:, 0], X[:, 1]",
    ),
    Mistake(
        "every combination",
        lambda s: s.values.shape == (s.n, s.n),
        "you got every combination of the rows v and the columns u (img[v][:, u], or np.ix_): pair them, img[v, u], one value per point",
    ),
    Mistake(
        "not one value per point",
        lambda s: s.values.shape != (s.n,),
        lambda s: (
            f"one value per point: shape ({s.n},), got {s.values.shape}; img[v, u] with u, v = X[:, 0], X[:, 1] gives it"
        ),
    ),
    Mistake(
        "rescaled",
        lambda s: rescaled_by(s) is not None,
        lambda s: (
            f"the right pixels, but every value {_factor_words(rescaled_by(s))}: return the pixel values as "
            "the image stores them, img[v, u], with no rescaling"
        ),
    ),
    Mistake(
        "img[u, v]",
        lambda s: s.H == s.W and np.allclose(s.values, s.img[s.u, s.v]),
        "img[u, v] reads row u, column v: the transposed pixel. numpy indexes the row first, and the row is v: img[v, u]",
    ),
    Mistake(
        "v counted from the bottom",
        lambda s: _reads(s, s.H - 1 - s.v, s.u),
        "you read row H - 1 - v, counting v from the bottom (OpenGL's rows, y up): the course's rows count from "
        "the top, v = 0 is the top row, so pixel (u, v) is img[v, u]",
    ),
    Mistake(
        "u counted from the right",
        lambda s: _reads(s, s.v, s.W - 1 - s.u),
        "you read column W - 1 - u, counting u from the right: columns count from the left, so pixel (u, v) is img[v, u]",
    ),
    Mistake(
        "truncated",
        lambda s: (
            not np.array_equal(np.trunc(s.X), np.rint(s.X))
            and _reads(s, np.trunc(s.X[:, 1]).astype(int), np.trunc(s.X[:, 0]).astype(int))
        ),
        lambda s: _truncated_hint(s.X),
    ),
    Mistake(
        "rounded up",
        lambda s: (
            ceil_moved(s.X) is not None
            and _reads(s, np.ceil(s.X[:, 1]).astype(int), np.ceil(s.X[:, 0]).astype(int))
        ),
        lambda s: (
            f"{ceil_moved(s.X)}. Round to the nearest, then convert: u, v = np.rint(X).astype(int).T"
        ),
    ),
    *(_shift_mistake(dv, du) for dv, du in ((-1, -1), (0, -1), (-1, 0), (1, 1), (0, 1), (1, 0))),
    *(
        Mistake(
            f"np.rint(X {d:+g})",
            lambda s, d=d: _half_read(s, d),
            lambda s, d=d: _half_read_hint(s, d),
        )
        for d in (0.5, -0.5)
    ),
    Mistake(
        "an interpolated read outside the image",
        lambda s: _outside_read(s) is not None,
        lambda s: _outside_read_hint(s),
    ),
    Mistake(
        "read at the moved points",
        lambda s: (
            _read_turned(s, lambda t: np.rint(t).astype(int))
            or _read_turned(s, lambda t: t.astype(int))
        ),
        "you read the values at the moved points: read them at the points X themselves, before the move, "
        "img[v, u] with u, v = X[:, 0], X[:, 1]",
    ),
)


def _outside_read(s) -> int | None:
    """The first point a hair outside the image that read 0, when every wrong value is such a point (else None).

    An interpolating read (scipy's ``map_coordinates``, ``cv2.remap``) returns its fill value, 0, at a
    computed 5.000000000000001 past the last row H - 1 = 5, though the pixel is there after rounding.
    """
    if s.values.shape != (s.n,):
        return None
    wrong = ~np.isclose(s.values, s.img[s.v, s.u])
    hair = np.any((s.X < 0) | (s.X > [s.W - 1, s.H - 1]), axis=1) & np.all(
        np.abs(s.X - np.rint(s.X)) < 1e-6, axis=1
    )
    if wrong.any() and np.all(hair[wrong]) and np.allclose(s.values[wrong], 0):
        return int(np.argmax(wrong))
    return None


def _outside_read_hint(s) -> str:
    k = _outside_read(s)
    return (
        f"X[{k}] = ({numbers(s.X[k, 0])}, {numbers(s.X[k, 1])}) lies a hair outside the image (its pixel centres run "
        f"0 .. {s.W - 1} by 0 .. {s.H - 1}), and you read 0 there: an interpolating read (scipy's map_coordinates, "
        "cv2.remap) gives its fill value outside. The points sit on pixel centres: round, then index, "
        "img[v, u] with u, v = np.rint(X).astype(int).T"
    )


def _first_wrong_value(s) -> str:
    """The first point whose value is wrong, the pixel it should have read, and the pixel the value names."""
    u, v, img, H, W = s.u, s.v, s.img, s.H, s.W
    k = int(np.argmax(~np.isclose(s.values, img[v, u])))
    q = s.values[k]
    where = ""
    if q == int(q) and 0 <= q < 10 * H and int(q) % 10 < W:
        where = f", the value of pixel (u, v) = ({int(q) % 10}, {int(q) // 10})"
    return (
        f"X[{k}] = ({u[k]}, {v[k]}) is pixel img[{v[k]}, {u[k]}] = {img[v[k], u[k]]}, but you returned {q:g}{where}: "
        "read row v, column u, img[v, u]"
    )


def values_cause(
    values: np.ndarray, img: np.ndarray, X: np.ndarray, turned: np.ndarray | None = None
) -> str:
    """Why ``values`` are not img[v, u] at the rows of ``X``.

    A row of :data:`VALUE_MISTAKES`, else the first wrong value and the pixel it came from (every
    test image names its pixels, img[v, u] = 10 v + u). ``turned``, the right turned points, lets
    the diagnosis tell values read there.
    """
    H, W = img.shape
    u, v = np.rint(X).astype(int).T
    s = SimpleNamespace(values=values, img=img, u=u, v=v, H=H, W=W, n=len(X), X=X, turned=turned)
    return first_mistake(VALUE_MISTAKES, s) or _first_wrong_value(s)


# -- the moved points --------------------------------------------------------------------------------


def _decimals(s) -> int | None:
    """The k in 1..6 with the answer = the right points rounded to k decimals, if there is one."""
    return next((k for k in range(1, 7) if np.allclose(s.got, np.round(s.turned, k))), None)


def _mean_of_points(s) -> np.ndarray:
    return s.X.mean(axis=0)


def _inverse_turn(s):
    """The points moved by A's inverse (None for a singular A, which has none)."""
    if abs(np.linalg.det(s.A)) > 1e-12:
        return (s.X - s.c) @ np.linalg.inv(s.A).T + s.c
    return None


_FLIP = np.diag([1.0, -1.0])


def _y_flip_is_inverse(s) -> bool:
    """Whether A with y flipped, diag(1, -1) A diag(1, -1), is A's inverse (true of rotations and unit shears)."""
    return abs(np.linalg.det(s.A)) > 1e-12 and np.allclose(_FLIP @ s.A @ _FLIP, np.linalg.inv(s.A))


def _about(centre: Mistake, transposed: bool):
    """The points turned about the wrong centre that ``centre`` computes, by A (or by its transpose)."""

    def answer(
        s,
    ):  # (X - w) M + w = X M + w (I - M): w is named only when I - M is invertible, the one fit
        w = np.asarray(centre.answer(s), dtype=float)
        M = s.A if transposed else s.A.T
        if abs(np.linalg.det(np.eye(2) - M)) < 1e-9:
            return None
        return (s.X - w) @ M + w

    return answer


_HALF_STEPS = [
    (du, dv) for du in (-0.5, 0.0, 0.5) for dv in (-0.5, 0.0, 0.5) if (du, dv) != (0.0, 0.0)
]


def _half_off(d) -> str:
    """Where c + d lies from c, for d in half pixels: 'half a pixel left of and above'."""
    words = [
        w
        for x, w in (
            (d[0], "left of" if d[0] < 0 else "right of"),
            (d[1], "above" if d[1] < 0 else "below"),
        )
        if x
    ]
    return "half a pixel " + " and ".join(words)


def _about_half_off(s):
    """X turned about c + d, half a pixel off the (right) centre the student returned, for the d that fits."""
    if s.centre_named or abs(np.linalg.det(np.eye(2) - s.A)) < 1e-9:
        return None
    for d in _HALF_STEPS:
        w = s.c + d
        if np.allclose(s.got, (s.X - w) @ s.A.T + w):
            s.half = d
            return s.got
    return None


# Checked in order (answer against answer, np.allclose) on the moved points, for the points ``s.X``,
# the matrix ``s.A``, the right centre ``s.c`` and the image size ``s.W`` x ``s.H``.
TURN_MISTAKES = (
    Mistake(
        "X unturned",
        lambda s: s.X,
        "you returned X unchanged: A was never applied. Move the points about the centre, x' = c + A (x - c): "
        "(X - c) @ A.T + c",
    ),
    Mistake(
        "only X - c",
        lambda s: s.X - s.c,
        "you moved the centre to the origin, X - c, and stopped: then apply A and move back, (X - c) @ A.T + c",
    ),
    Mistake(
        "u and v swapped",
        lambda s: s.turned[:, ::-1],
        "each of your moved points is (v, u), its two numbers swapped: points are rows (u, v), like X, so keep "
        "the columns in that order: (X - c) @ A.T + c",
    ),
    Mistake(
        "rounded",
        lambda s: np.rint(s.turned),
        "right, then rounded to whole pixels (np.round or np.rint): the moved points are points, not pixel "
        "indices, so keep their fractions; round only to index an image",
    ),
    Mistake(
        "rounded to decimals",
        lambda s: None if _decimals(s) is None else np.round(s.turned, _decimals(s)),
        lambda s: (
            f"right, then rounded to {_decimals(s)} decimal{'s' * (_decimals(s) > 1)} "
            f"(np.round(..., {_decimals(s)})): the moved points have endless decimals (cos 30° = 0.8660...); "
            "return the full floats and round only to print"
        ),
    ),
    Mistake(
        "cast to int",
        lambda s: np.trunc(s.turned),
        "right, then cast to int (.astype(int) or int()), which drops the fractions: the moved points are points, "
        "not pixel indices, so keep them as floats; round only to index an image",
    ),
    Mistake(
        "X @ A",
        lambda s: (s.X - s.c) @ s.A + s.c,
        "X @ A applies A's transpose (for a rotation, the opposite turn): with points as rows, the textbook's A x is X @ A.T",
    ),
    Mistake(
        "* for @, A's diagonal",
        lambda s: (s.X - s.c) * np.diag(s.A) + s.c,
        "* multiplies entry by entry: (X - c) * np.diag(A) scales u and v by A's diagonal alone and drops the "
        "rest of A; a matrix acts on points with @: (X - c) @ A.T + c",
    ),
    Mistake(
        "* for @, one entry of A",
        lambda s: (s.X - s.c) * s.A[0, 0] + s.c,
        "* by one entry of A, A[0, 0], scales the points and drops the rest of A: a matrix acts on points with "
        "@, (X - c) @ A.T + c",
    ),
    Mistake(
        "about the origin",
        lambda s: s.X @ s.A.T,
        "you moved the points about the origin (0, 0), the top-left pixel's centre: move them about the image's centre, c + A (x - c): (X - c) @ A.T + c",
    ),
    Mistake(
        "about the origin, X @ A",
        lambda s: s.X @ s.A,
        "you moved the points about the origin, and X @ A applies A's transpose: subtract the centre, apply A with X @ A.T, add it back: (X - c) @ A.T + c",
    ),
    Mistake(
        "the centre not added back",
        lambda s: (s.X - s.c) @ s.A.T,
        "you forgot to add the centre back after applying A: c + A (x - c), so (X - c) @ A.T + c",
    ),
    Mistake(
        "the centre not subtracted",
        lambda s: s.X @ s.A.T + s.c,
        "you added the centre after applying A but never subtracted it before: move c to the origin first, "
        "c + A (x - c), so (X - c) @ A.T + c",
    ),
    Mistake(
        "the centre subtracted twice",
        lambda s: (s.X - s.c) @ s.A.T - s.c,
        "add the centre back after applying A (you subtracted it twice): (X - c) @ A.T + c",
    ),
    Mistake(
        "a sign flip",
        lambda s: s.c - (s.X - s.c) @ s.A.T,
        "a sign flip: c - A (x - c) maps and mirrors through the centre; the move is c + A (x - c), (X - c) @ A.T + c",
    ),
    Mistake(
        "the signs swapped",
        lambda s: (s.X + s.c) @ s.A.T - s.c,
        "the signs are swapped: move the centre to the origin first, X - c, then apply A, then add c back: (X - c) @ A.T + c",
    ),
    Mistake(
        "y flipped",
        lambda s: None if _y_flip_is_inverse(s) else (s.X - s.c) @ (_FLIP @ s.A @ _FLIP).T + s.c,
        "you applied A with y flipped, diag(1, -1) A diag(1, -1), as a y-up habit does: v already points down, "
        "so use A as given, (X - c) @ A.T + c",
    ),
    Mistake(
        "A's inverse",
        _inverse_turn,
        lambda s: (
            "you applied A's inverse, the move undone: x' = c + A (x - c) uses A itself, (X - c) @ A.T + c"
            + (
                " (for this A the inverse is also A with y flipped, diag(1, -1) A diag(1, -1): a y-up habit gives it too)"
                if _y_flip_is_inverse(s)
                else ""
            )
        ),
    ),
    Mistake(
        "A's inverse transposed",
        lambda s: (
            None if abs(np.linalg.det(s.A)) < 1e-12 else (s.X - s.c) @ np.linalg.inv(s.A) + s.c
        ),
        (
            "you applied inv(A) where A itself is to be applied, (X - c) @ inv(A): for a rotation inv(A) = A.T, so it "
            "passes on a rotation, but for any other A (this one) it is another move: x' = c + A (x - c), (X - c) @ A.T + c"
        ),
    ),
    Mistake(
        "about c, half a pixel off",
        _about_half_off,
        lambda s: (
            f"you moved the points about {numbers(s.c + s.half)}, {_half_off(s.half)} the centre c = {numbers(s.c)} you "
            "returned (it is right): a 0.5 crept into the move, as (X + 0.5 - c) @ A.T + c - 0.5 or Pillow's centre "
            "(W / 2, H / 2) give. Pixel centres are whole numbers here (section 3.4): (X - c) @ A.T + c"
        ),
    ),
    Mistake(
        "about the mean of the points",
        lambda s: (s.X - _mean_of_points(s)) @ s.A.T + _mean_of_points(s),
        lambda s: (
            f"you moved the points about their mean, {numbers(_mean_of_points(s))} (X.mean(axis=0)), not about the "
            "image's centre c: it comes from img.shape, ((W - 1)/2, (H - 1)/2), whatever the points"
        ),
    ),
    *(
        Mistake(
            f"about {centre.name}" + (", X @ A" if transposed else ""),
            _about(centre, transposed),
            lambda s, centre=centre, transposed=transposed: (
                (
                    f"you moved the points about {numbers(centre.answer(s))}, not the image's centre: fix c first "
                    "(above), then check the move"
                    if s.centre_named
                    else f"you moved the points about {numbers(centre.answer(s))}, not about the centre c = {numbers(s.c)} "
                    f"you returned (it is right); in the move, {centre.hint}"
                )
                + ("; and X @ A applies A's transpose: X @ A.T" if transposed else "")
            ),
        )
        for centre in CENTRE_MISTAKES
        for transposed in (False, True)
    ),
)


def turned_cause(
    t: np.ndarray,
    X: np.ndarray,
    A: np.ndarray,
    c: np.ndarray,
    W: int,
    H: int,
    centre_named: bool = False,
) -> str:
    """Why ``t`` is not ``X`` turned by ``A`` about the centre ``c`` of a ``W`` x ``H`` image.

    Its shape, else the first row of :data:`TURN_MISTAKES` it equals. ``centre_named``: the diagnosis has
    named a wrong centre already, so a turn about it refers to that instead of repeating its cause.
    """
    n = len(X)
    if t.shape == (2, n) and n != 2:
        return "one row per point: A @ X.T gives the points as columns; transpose back, (A @ X.T).T, or write X @ A.T"
    if t.shape != (n, 2):
        return f"the moved points are rows, shape ({n}, 2), like X; got {t.shape}"
    s = SimpleNamespace(
        X=X, A=A, c=c, W=W, H=H, turned=(X - c) @ A.T + c, centre_named=centre_named, got=t
    )
    shift = t - s.turned
    if np.allclose(shift, shift[0]) and not np.allclose(
        shift[0], 0
    ):  # every point off by the same (du, dv)
        rest = first_mistake(TURN_MISTAKES, s, t, np.allclose)
        if not rest and np.allclose(np.abs(shift[0]), 0.5):
            return (
                f"every point is off by {numbers(shift[0])}, half a pixel: the move by A is right, but done in Pillow's "
                "or COLMAP's coordinates, (u + 0.5, v + 0.5), where whole numbers are pixel corners (section 3.4), "
                "and not converted back (or a 0.5 was added): here pixel centres are whole numbers, (X - c) @ A.T + c"
            )
        return rest or (
            f"every point is off by the same shift, {numbers(shift[0].round(4))}: the move by A is right, but the centre "
            "subtracted and the one added back differ (or a constant was added): (X - c) @ A.T + c, the same c twice"
        )
    return (
        first_mistake(TURN_MISTAKES, s, t, np.allclose)
        or "move each row about the centre by A: x' = c + A (x - c), for rows (X - c) @ A.T + c"
    )
