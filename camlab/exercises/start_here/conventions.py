"""Lesson 00's exercise read_and_turn: section 3's conventions at work.

The image's centre ((W - 1)/2, (H - 1)/2), the pixel values img[v, u] under the points X, and X turned
about the centre by a 2 x 2 matrix A. The diagnosis judges each of the three parts on its own, by the
tables of :mod:`._turn_causes` (and :mod:`._turn_raised` for errors raised).
"""

from __future__ import annotations

from itertools import permutations

import numpy as np

from ... import projective
from .._answers import same_array
from .._core import Exercise, register_exercise
from ._turn_causes import centre_cause, numbers, turned_cause, values_cause
from ._turn_raised import exception_hint

# Every test image holds img[v, u] = 10 v + u, so a value read names the pixel it came from (at most 10
# columns), and a wrong read can be traced to its cause: img[u, v], a 1-based index, the wrong point.
# Input 1 is wider than tall (6 x 4) with even sides, so W / 2 = W // 2 differs from (W - 1) / 2, W and H
# cannot be confused, and img[u, v] raises for u >= 4; its A is a shear with a scale, not a turn (A.T is
# neither A nor its inverse, so X @ A, A's inverse and a sign flip each show as themselves, and A - I is
# invertible, so a wrong centre can be read back from the moved points); input 2 is square and odd (5 x 5), where
# img[u, v] raises nothing and silently reads the transposed pixel (the lesson's warning), with a quarter
# turn; input 3 is 7 x 3 with a turn and a scale; input 4 is taller
# than wide (4 x 6), where img[u, v] raises for v >= 4, and its X is computed, as points in a program are:
# whole numbers up to floating-point rounding, some a unit in the last place below (2.9999999999999996),
# so that .astype(int) alone truncates them to the pixel before.


def _pixel_image(size: tuple[int, int]) -> np.ndarray:
    """A ``size = (W, H)`` test image whose value at img[v, u] is 10 v + u: it names its own pixel."""
    W, H = size
    v, u = np.mgrid[0:H, 0:W]
    return 10 * v + u


def _turn(deg: float, scale: float = 1.0) -> np.ndarray:
    t = np.radians(deg)
    return scale * np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])


def _computed(X: np.ndarray, below: np.ndarray) -> np.ndarray:
    """``X`` nudged one unit in the last place off its whole numbers.

    Entries where ``below`` is True go one ulp under, the others one above (a computed 3 can be
    2.9999999999999996 or 3.0000000000000004).
    """
    X = np.asarray(X, dtype=float)
    return np.where(below, np.nextafter(X, -np.inf), np.where(X > 0, np.nextafter(X, np.inf), X))


def _rt_cases() -> list[tuple]:
    return [
        (
            _pixel_image((6, 4)),
            np.array([[5.0, 0.0], [0.0, 3.0], [2.0, 2.0]]),
            np.array([[0.8, 0.5], [0.0, 1.2]]),
        ),
        (
            _pixel_image((5, 5)),
            np.array([[4.0, 0.0], [1.0, 3.0], [2.0, 2.0], [0.0, 4.0]]),
            _turn(90.0).round(12),
        ),
        (_pixel_image((7, 3)), np.array([[6.0, 2.0], [0.0, 0.0], [3.0, 1.0]]), _turn(30.0, 2.0)),
        (
            _pixel_image((4, 6)),
            _computed(
                [[3.0, 5.0], [0.0, 2.0], [2.0, 1.0], [1.0, 4.0]],
                below=np.array([[True, False], [False, True], [False, False], [False, True]]),
            ),
            _turn(-60.0),
        ),
    ]


def _rt_describe(args: tuple) -> str:
    img, X, A = args
    H, W = img.shape
    return f"img of shape ({H}, {W}), W = {W}, H = {H}, with img[v, u] = 10 v + u; X = {numbers(X)}; A = {numbers(A)}"


def _read_and_turn_reference(img, X, A):
    """Returns the centre ((W - 1)/2, (H - 1)/2), the values img[v, u] at the rows of X, and X turned about it by A.

    The turn is one 3 x 3 matrix, translate(c) A translate(-c), applied by :func:`camlab.map_points`: a route
    other than the teaching solution's ``(X - c) @ A.T + c``.
    """
    H, W = np.shape(img)[:2]
    c = np.array([(W - 1) / 2, (H - 1) / 2])
    X = np.asarray(X, dtype=float)
    u, v = np.rint(X).astype(int).T
    M = np.eye(3)
    M[:2, :2] = A
    M[:2, 2] = c - np.asarray(A) @ c
    return c, np.asarray(img)[v, u], projective.map_points(M, X)


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
    return all(
        isinstance(g, np.ndarray) and _as_floats(g) is not None and same(g, e)
        for g, e in zip(got, expected, strict=True)
    )


def _not_arrays(got, parts, names) -> str:
    """The parts returned as lists or tuples: the prompt asks for numpy arrays, as ``lift`` does."""
    shapes = ("(2,)", "(N,)", "(N, 2)")
    return "; ".join(
        f"{name} came back as a {type(g).__name__}: return a numpy array of shape {shape} (np.array(...))"
        for name, part, g, shape in zip(names, parts, got, shapes, strict=True)
        if not isinstance(g, np.ndarray)
    )


def _rt_diagnose(args, got, expected) -> str:
    img, X, A = args
    H, W = img.shape
    order = "return three things, in this order: the centre c, shape (2,); the values, shape (N,); the moved points, shape (N, 2): `return c, values, moved`"
    if not isinstance(got, (tuple, list)):
        a = _as_floats(got)
        if a is not None and a.shape == (2,) and np.allclose(a, expected[0]):
            return f"you returned only the centre (it is right); {order}"
        return f"you returned {type(got).__name__ if not isinstance(got, np.ndarray) else 'one array'}; {order}"
    if len(got) != 3:
        return f"you returned {len(got)} things; {order}"
    names = ("the centre c", "the values", "the moved points")
    parts = [_as_floats(g) for g in got]
    for name, part, g in zip(names, parts, got, strict=True):
        if part is None:
            return f"{name} is not numbers (a {type(g).__name__}); {order}"
        if not np.isfinite(part).all():
            return f"{name} holds NaN or inf"
    c, values, turned = parts
    same = same_array(rtol=1e-9, atol=1e-9)
    if all(same(part, e) for part, e in zip(parts, expected, strict=True)):
        return _not_arrays(got, parts, names)  # the right numbers, not all as arrays
    for order in permutations(range(3)):
        if order != (0, 1, 2) and all(
            same(parts[k], e) for k, e in zip(order, expected, strict=True)
        ):
            yours = ", ".join(("c", "values", "moved")[order.index(k)] for k in range(3))
            return f"the three parts are right but came back in the wrong order, ({yours}): `return c, values, moved`"
    causes = []
    if not same(c, expected[0]):
        if c.shape != (2,):
            causes.append(
                f"the centre c is one point (u, v), shape (2,); got shape {c.shape}: build it as "
                "np.array([(W - 1) / 2, (H - 1) / 2]) (or flatten yours, c.ravel())"
            )
        else:
            causes.append(f"the centre: {centre_cause(c, W, H, X)}")
    if not same(values, expected[1]):
        causes.append(f"the values: {values_cause(values, img, X, expected[2])}")
    if not same(turned, expected[2]):
        wrong_c = not same(c, expected[0])
        cause = turned_cause(turned, X, np.asarray(A, dtype=float), expected[0], W, H, wrong_c)
        yours = (X - c) @ A.T + c if c.shape == (2,) else None
        if yours is not None and wrong_c and turned.shape == yours.shape:
            if np.allclose(turned, yours):
                cause = "right for your centre c: fix c, and they follow"
        causes.append(f"the moved points: {cause}")
    return ("\n" + " " * 16).join(causes) if causes else "compare each part with the expected one"


def read_and_turn(img, X, A):
    """Section 3's conventions: the image's centre, the pixels under the points X, and X moved by A about the centre.

    Parameters
    ----------
    img : (H, W) ndarray
        A grey image.
    X : (N, 2) ndarray
        Points (u, v) at pixel centres inside the image: whole numbers, up to floating-point
        rounding.
    A : (2, 2) ndarray
        Any linear map (a rotation, a scale, a shear), applied about the centre.

    Returns
    -------
    c : (2,) ndarray
        The centre ((W - 1)/2, (H - 1)/2).
    values : (N,) ndarray
        img[v, u] at each point.
    moved : (N, 2) ndarray
        c + A (x - c) for each point x.
    """
    H, W = img.shape[:2]  # numpy's shape: rows (H) first, then columns (W)
    c = np.array([(W - 1) / 2, (H - 1) / 2])  # halfway between the first and last pixel centres
    # round, then convert: .astype(int) alone truncates 2.9999999999999996 to 2
    u, v = np.rint(X).astype(int).T
    values = img[v, u]  # row v, column u
    # x' = c + A (x - c): move c to the origin, apply A, move back; every row at once
    moved = (X - c) @ A.T + c
    return c, values, moved


def _rt_wrong(centre=None, read=None, turn=None):
    """A wrong read_and_turn for the tests: the teaching solution with one step replaced."""

    def wrong(img, X, A):
        H, W = img.shape
        c = (
            np.array([(W - 1) / 2, (H - 1) / 2])
            if centre is None
            else np.asarray(centre(W, H), dtype=float)
        )
        u, v = np.rint(X).astype(int).T
        values = img[v, u] if read is None else read(img, u, v)
        turned = (X - c) @ A.T + c if turn is None else turn(X, A, c)
        return c, values, turned

    return wrong


def _interpolated_read(img, X, A):
    """A read that gives 0 a hair outside the pixel centres, as map_coordinates does (a wrong variant for the tests)."""
    H, W = img.shape
    c, values, turned = read_and_turn(img, X, A)
    inside = np.all((X >= 0) & (X <= [W - 1, H - 1]), axis=1)
    return c, np.where(inside, values, 0), turned


def _float_index(img, X, A):
    """Indexing with the float coordinates of X (a wrong variant for the tests)."""
    return read_and_turn(img, X, A)[0], img[X[:, 1], X[:, 0]], read_and_turn(img, X, A)[2]


def _colour_shape(img, X, A):
    """``H, W, C = img.shape``, a colour habit, on a grey image (a wrong variant for the tests)."""
    H, W, _ = img.shape
    return read_and_turn(img, X, A)


def _rows_unpacked(img, X, A):
    """``u, v = X``: the rows unpacked, not the columns (a wrong variant for the tests)."""
    u, v = X
    return read_and_turn(img, X, A)


def _pillow_size(img, X, A):
    """``W, H = img.size``, Pillow's habit, on a numpy array (a wrong variant for the tests)."""
    W, H = img.size
    return read_and_turn(img, X, A)


def _int_of_column(img, X, A):
    """``int(X[:, 0])``: int() of an array (a wrong variant for the tests)."""
    u, v = int(X[:, 0]), int(X[:, 1])
    return read_and_turn(img, X, A)[0], img[v, u], read_and_turn(img, X, A)[2]


def _ceil_read(img, X, A):
    """``np.ceil(X)`` as the pixel index: a computed 5.000000000000001 reads pixel 6 (a wrong variant for the tests)."""
    u, v = np.ceil(X).astype(int).T
    c, _, turned = read_and_turn(img, X, A)
    return c, img[v, u], turned


def _two_parameters(img, X):
    """A def that leaves out A (a wrong variant for the tests)."""
    return read_and_turn(img, X, np.eye(2))


register_exercise(
    Exercise(
        name="read_and_turn",
        lesson="00",
        reference=_read_and_turn_reference,
        cases=_rt_cases,
        compare=_same_triple,
        diagnose=_rt_diagnose,
        describe_input=_rt_describe,
        exception_hint=exception_hint,
        wrong_variants=(
            (
                lambda img, X, A: tuple(p.tolist() for p in read_and_turn(img, X, A)),
                "the centre c came back as a list: return a numpy array of shape (2,)",
            ),
            (
                lambda img, X, A: (
                    *read_and_turn(img, X, A)[:2],
                    read_and_turn(img, X, A)[2].tolist(),
                ),
                "the moved points came back as a list: return a numpy array of shape (N, 2)",
            ),
            (_rt_wrong(centre=lambda W, H: (W / 2, H / 2)), "you used (W / 2, H / 2)"),
            (
                _rt_wrong(turn=lambda X, A, c: ((X - c) @ A.T + c).round(2)),
                "right, then rounded to 2 decimals",
            ),
            (
                _rt_wrong(turn=lambda X, A, c: (X - X.mean(0)) @ A.T + X.mean(0)),
                "you moved the points about their mean",
            ),
            (_interpolated_read, "an interpolating read (scipy's map_coordinates, cv2.remap)"),
            (_rt_wrong(centre=lambda W, H: (W // 2, H // 2)), "W // 2"),
            (_rt_wrong(centre=lambda W, H: ((W + 1) / 2, (H + 1) / 2)), "counted from 1"),
            (
                _rt_wrong(centre=lambda W, H: ((W - 1) // 2, (H - 1) // 2)),
                "rounded the centre down",
            ),
            (_rt_wrong(centre=lambda W, H: ((H - 1) / 2, (W - 1) / 2)), "width and height swapped"),
            (_rt_wrong(centre=lambda W, H: (W, H)), "that is the size"),
            (  # two slips at once, points as columns: the hint names the centre, no numpy error
                _rt_wrong(
                    centre=lambda W, H: (W / 2, H / 2),
                    turn=lambda X, A, c: ((X - c) @ A.T + c).T,
                ),
                "you used (W / 2, H / 2)",
            ),
            (_rt_wrong(read=lambda img, u, v: img[u, v]), "u = 5 was used as the row"),
            (_rt_wrong(read=lambda img, u, v: img.T[v, u]), "the image was transposed"),
            (_rt_wrong(read=lambda img, u, v: img[v + 3, u]), "its rows (axis 0, v) run 0 .. 3"),
            (  # img[u, v] where it raises nothing: the square image reads the transposed pixel
                _rt_wrong(
                    read=lambda img, u, v: img[u, v] if img.shape[0] == img.shape[1] else img[v, u]
                ),
                "img[u, v] reads row u, column v",
            ),
            (
                _rt_wrong(read=lambda img, u, v: img[v - 1, u - 1]),
                "you read img[v - 1, u - 1], the pixel one row up and one column left",
            ),
            (_rt_wrong(read=lambda img, u, v: img[v, u - 1]), "you read img[v, u - 1]"),
            (_rt_wrong(read=lambda img, u, v: img[v - 1, u]), "silently reads the last row"),
            (
                _rt_wrong(read=lambda img, u, v: img[img.shape[0] - 1 - v, u]),
                "counting v from the bottom",
            ),
            (
                lambda img, X, A: (
                    lambda c, values, turned: (
                        c,
                        img[tuple(np.rint(turned).astype(int).T[::-1])],
                        turned,
                    )
                )(*read_and_turn(img, X, A)),
                "you read the values at the moved points",
            ),
            (
                _rt_wrong(turn=lambda X, A, c: np.round((X - c) @ A.T + c)),
                "right, then rounded to whole pixels",
            ),
            (
                _rt_wrong(turn=lambda X, A, c: ((X - c) @ A.T + c).astype(int)),
                "right, then cast to int",
            ),
            (_rt_wrong(turn=lambda X, A, c: X), "you returned X unchanged"),
            (_rt_wrong(turn=lambda X, A, c: X @ A.T + c), "never subtracted it before"),
            (
                _rt_wrong(turn=lambda X, A, c: (X - c) @ A.T + c + 0.5),
                "every point is off by [0.5, 0.5], half a pixel: the move by A is right, but done in Pillow's",
            ),
            (
                _rt_wrong(turn=lambda X, A, c: (X - c) @ A.T + c + np.array([0.25, -1.0])),
                "every point is off by the same shift, [0.25, -1]",
            ),
            (
                _rt_wrong(turn=lambda X, A, c: (X + 0.5 - c) @ A.T + c - 0.5),
                "you moved the points about [2, 1], half a pixel left of and above the centre c = [2.5, 1.5] you returned",
            ),
            (
                _rt_wrong(
                    turn=lambda X, A, c: (X - np.floor(c)) @ A.T + np.floor(c) if c[0] % 1 else X
                ),
                "you moved the points about [2, 1], half a pixel left of and above",
            ),
            (
                _rt_wrong(turn=lambda X, A, c: (X - 2 * c) @ A.T + 2 * c),
                "you moved the points about [5, 3], not about the centre c = [2.5, 1.5] you returned (it is right); in the "
                "move, that is the last pixel",
            ),
            (_rt_wrong(read=lambda img, u, v: img[v, u] / 255), "every value divided by 255"),
            (
                lambda img, X, A: (
                    read_and_turn(img, X, A)[0],
                    img[tuple(np.rint(X - 0.5).astype(int).T[::-1])],
                    read_and_turn(img, X, A)[2],
                ),
                "you added -0.5 before rounding, np.rint(X - 0.5): X[0] = (5, 0) read pixel (4, 0)",
            ),
            (
                lambda img, X, A: (
                    read_and_turn(img, X, A)[0],
                    img[tuple(np.rint(X + 0.5).astype(int).T[::-1])],
                    read_and_turn(img, X, A)[2],
                ),
                "Or half a pixel added before rounding? np.rint(X + 0.5) sends 3 to 3.5",
            ),
            (
                _rt_wrong(turn=lambda X, A, c: X - c),
                "you moved the centre to the origin, X - c, and stopped",
            ),
            (
                lambda img, X, A: (lambda c, values, turned: (values, c, turned))(
                    *read_and_turn(img, X, A)
                ),
                "came back in the wrong order, (values, c, moved)",
            ),
            (
                lambda img, X, A: (lambda c, values, turned: (c, turned, values))(
                    *read_and_turn(img, X, A)
                ),
                "came back in the wrong order, (c, moved, values)",
            ),
            (  # a y-up habit: A with y flipped
                _rt_wrong(
                    turn=lambda X, A, c: (
                        (X - c) @ (np.diag([1.0, -1.0]) @ A @ np.diag([1.0, -1.0])).T + c
                    )
                ),
                "as a y-up habit does",
            ),
            (_rt_wrong(read=lambda img, u, v: img[v + 1, u + 1]), "counting from 1?"),
            (_rt_wrong(read=lambda img, u, v: img[v][:, u]), "every combination"),
            (
                lambda img, X, A: (
                    read_and_turn(img, X, A)[0],
                    img[X.astype(int)],
                    read_and_turn(img, X, A)[2],
                ),
                "img[X] fails the same way: it reads every number of X as a row",
            ),
            (_float_index, "numpy indexes with integers"),
            (
                lambda img, X, A: (
                    read_and_turn(img, X, A)[0],
                    img[X[:, 1].astype(int), X[:, 0].astype(int)],
                    read_and_turn(img, X, A)[2],
                ),
                "truncates: X[0, 0] = 2.9999999999999996 became 2",
            ),
            (  # img[u, v] as it fails on a taller image (on the others it fails first, naming the rows)
                _rt_wrong(
                    read=lambda img, u, v: img[u, v] if img.shape[0] > img.shape[1] else img[v, u]
                ),
                "v = 5 was used as the column, and this image, taller than wide, has 4 columns",
            ),
            (
                _rt_wrong(turn=lambda X, A, c: ((X - c) @ A.T + c)[:, ::-1]),
                "each of your moved points is (v, u)",
            ),
            (_rt_wrong(turn=lambda X, A, c: (X - c) @ A + c), "X @ A applies A's transpose"),
            (
                _rt_wrong(turn=lambda X, A, c: (A @ X.T).T * 0 + A @ X),
                "A @ X treats X as one column per point",
            ),
            (_rt_wrong(turn=lambda X, A, c: A @ (X - c).T + c[:, None]), "(A @ X.T).T"),
            (_rt_wrong(turn=lambda X, A, c: X @ A.T), "you moved the points about the origin"),
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
                _rt_wrong(turn=lambda X, A, c: (X - (c + 0.5)) @ A.T + (c + 0.5)),
                "you moved the points about [3, 2], half a pixel right of and below the centre c = [2.5, 1.5]",
            ),
            (
                _rt_wrong(
                    centre=lambda W, H: (W / 2, H / 2), turn=lambda X, A, c: (X - c) @ A.T + c
                ),
                "right for your centre c",
            ),
            (_colour_shape, "H, W = img.shape[:2]"),
            (_rows_unpacked, "u, v = X takes its rows"),
            (_pillow_size, "numpy's img.size is the number of pixels"),
            (_int_of_column, "int() converts one number"),
            (_two_parameters, "calls your function as read_and_turn(img, X, A)"),
            (_ceil_read, "np.ceil rounds up: X[0, 1] = 5.000000000000001"),
            (
                _rt_wrong(turn=lambda X, A, c: (X - c) @ np.linalg.inv(A) + c),
                "you applied inv(A) where A itself is to be applied",
            ),
            (lambda img, X, A: read_and_turn(img, X, A)[:2], "you returned 2 things"),
            (lambda img, X, A: read_and_turn(img, X, A)[0], "you returned only the centre"),
        ),
        teaching=read_and_turn,
        in_place_examples={
            "X": ("`X -= c`, `X[:, 0] = ...`, `X @= A.T`", "`X - c`, `(X - c) @ A.T + c`"),
            "img": ("`img[v, u] = ...`, `img -= m`", "`img - m`"),
            "A": ("`A *= s`, `A[0, 1] = ...`", "`A * s`"),
        },
        solution_note=(
            "# camlab's own, tested route to the turn: one 3 x 3 matrix M = [[A, c - A c], [0, 0, 1]] applied\n"
            "# by camlab.map_points(M, X) (lesson 06; read it with camlab.map_points??)"
        ),
    )
)
