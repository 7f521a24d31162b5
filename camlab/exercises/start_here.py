"""The warm-up exercise of lesson 00: how exercises and checks work."""
from __future__ import annotations

import numpy as np

from .. import projective
from ._core import Exercise, register_exercise, same_array, shape_problem

_KEEP = "append 1 to the point, keeping x and y as they are"


_ONE_POINT = ("p is one point, a 1-D array of shape (2,), not a batch of points (N, 2) like the worked "
              "example's `points`")


def _batch_code_hint(exc: Exception, args: tuple) -> str:
    """The likely cause when the worked example's batch code, written for (N, 2) points, meets one (2,) point.

    ``np.hstack([p, np.ones((len(p), 1))])`` joins a 1-D and a 2-D array, ``p[:, :2]`` indexes a
    second axis that one point lacks, and ``np.c_[p, 1]`` / ``np.column_stack`` treat x and y as
    two rows: each raises, and the shared hints would blame something else (a 1-based column).
    """
    text = str(exc)
    if "has no attribute 'append'" in text:
        return ("p.append(1.0) is how a Python list grows; a numpy array has no .append method "
                "(its size is fixed): np.append(p, 1.0) returns a new, longer array")
    if "zero-dimensional arrays cannot be concatenated" in text:
        return ("np.concatenate takes one sequence of arrays, and its second argument is the "
                "axis: np.concatenate([p, [1.0]]), or simply np.append(p, 1.0)")
    if "same number of dimensions" in text and "0 dimension(s)" in text:
        return ("np.concatenate joins arrays, and the 1 is a bare number (0-D): write it as "
                "[1.0], np.concatenate([p, [1.0]]), or use np.append(p, 1.0) or np.hstack([p, 1.0]), which accept it")
    if "same number of dimensions" in text:
        return (f"batch code on one point: {_ONE_POINT}, so np.hstack([p, np.ones((len(p), 1))]) "
                f"joins a 1-D array to a 2-D column; for one point append one number: np.append(p, 1.0)")
    if "too many indices" in text or "out of bounds for array of dimension 1" in text:
        return (f"batch code on one point: {_ONE_POINT}, so it has no second axis (p[:, :2], "
                f"axis=1); its coordinates are p[0] and p[1], and np.append(p, 1.0) lifts it")
    if "except for the concatenation axis" in text:
        return (f"np.c_ and np.column_stack join columns, so they treat x and y as two rows: "
                f"{_ONE_POINT}; append one number instead: np.append(p, 1.0) or np.r_[p, 1.0]")
    return ""


def _shape_slip(got_shape: tuple, g: np.ndarray, p: np.ndarray) -> str:
    """The likely cause of an answer of the wrong shape."""
    if got_shape == (2,) and np.allclose(g, p + 1.0):
        return ("p + [1] (or p + 1) adds 1 to each coordinate: numpy's + is arithmetic, not the list concatenation "
                "it is for Python lists; append instead: np.append(p, 1.0)")
    if got_shape == (2, 2):
        return (f"np.column_stack / np.c_ with a column of ones is batch code: on one point it makes each "
                f"coordinate a row. {_ONE_POINT}: append one number, np.append(p, 1.0)")
    if got_shape == (1, 3):
        return ("a batch holding one point; one point in, one point out: return the (3,) array "
                "(np.append(p, 1.0), or your result's row [0])")
    if got_shape == (3, 1):
        return "a column; points are rows in this course: return the (3,) array (.ravel())"
    if got_shape == (4,) and np.allclose(g[2:], 1.0):
        return ("you appended two 1s: np.ones(len(p)) counts p's coordinates, not points (len(p) is 2 for one point); "
                "append a single 1: np.append(p, 1.0)")
    return "append one coordinate, w = 1, to the 2 you were given"


def _diagnose(args, got, expected) -> str:
    problem = shape_problem(got, expected)  # check() has already named an answer that is not numbers
    if problem:
        if np.shape(got) != np.shape(expected):
            return f"{problem}: {_shape_slip(np.shape(got), np.asarray(got, dtype=float).ravel(), args[0])}"
        return problem
    g = np.asarray(got, dtype=float)
    p = np.asarray(args[0], dtype=float)
    if g[-1] == 0:
        return "w = 0 makes an ideal point (a direction), not the point itself: append 1"
    if np.allclose(g[:2], p):
        return f"x and y are right, but w should be 1, not {g[-1]:g}: append exactly 1"
    if np.allclose(g[1:], p) and g[0] == 1:
        return "you put the 1 first; by convention w is the last coordinate: (x, y, 1)"
    if np.allclose(g[:2], p[::-1]):
        return "x and y are swapped: keep the point's order, (u, v) = (column, row), and append 1"
    if np.allclose(g[:2] / g[-1], p):
        shown = ", ".join(f"{c:g}" for c in g)
        return (f"({shown}) is the same point scaled by {g[-1]:g} (homogeneous coordinates are defined up to scale), "
                f"but this exercise fixes w = 1: {_KEEP}")
    return _xy_slip(g[:2], p) + (f" (and w should be 1, not {g[-1]:g})" if g[-1] != 1 else "")


def _xy_slip(xy: np.ndarray, p: np.ndarray) -> str:
    """The likely cause when x and y came out wrong (w aside)."""
    fractional = not np.array_equal(p, np.trunc(p))
    if fractional and (np.allclose(xy, np.trunc(p)) or np.allclose(xy, np.round(p))):
        return ("the coordinates lost their fractions: you cast to int, but image points are real numbers "
                "(sub-pixel positions such as -1.5); keep floats")
    for shift, cause in ((0.5, "pixel centres sit at whole numbers in this course (section 3), so a point needs no "
                               "half-pixel shift"),
                         (1.0, "numpy and this course count pixels from 0, not 1 (a 1-based index?)")):
        for sign in (1, -1):
            if np.allclose(xy, p + sign * shift):
                return f"x and y are off by {sign * shift:+g}: {cause}; {_KEEP}"
    if np.allclose(xy, [p[0], -p[1]]):
        return f"y changed sign: y points down in this course, and lifting keeps its sign; {_KEEP}"
    nonzero = np.abs(p) > 0
    factor = xy[nonzero] / p[nonzero]
    if np.allclose(factor, factor[0]) and np.allclose(xy, factor[0] * p):
        cause = "a sign flip" if factor[0] == -1 else "a unit change or a stray factor"
        return f"x and y are {factor[0]:g} times the point's ({cause}); {_KEEP}"
    return _KEEP


def _list_append(p):
    """A list's way to grow, tried on an array (a wrong variant for the tests)."""
    p.append(1.0)
    return p


def lift(p):
    """Homogeneous coordinates of one image point: append w = 1."""
    return np.append(np.asarray(p, dtype=float), 1.0)


register_exercise(Exercise(
    name="lift",
    lesson="00",
    reference=projective.to_homogeneous,
    # The first input has fractions, so an int cast shows at once; the last is the bottom-right pixel of 640 x 480.
    cases=lambda: [(np.array([2.5, 4.25]),), (np.array([-1.5, 0.0]),), (np.array([639.0, 479.0]),)],
    compare=same_array(),
    diagnose=_diagnose,
    ndarray_only=True,
    wrong_variants=(
        (lambda p: np.append(p, 0.0), "ideal point"),
        (lambda p: np.insert(p, 0, 1.0), "w is the last coordinate"),
        (lambda p: p, "shape (3,)"),
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
        (lambda p: [p[0], p[1], 1.0], "you returned a list; return a numpy array of shape (3,)"),
        (lambda p: (p[0], p[1], 1.0), "you returned a tuple; return a numpy array of shape (3,)"),
        (lambda p: [p, 1], "np.append(p, 1.0)"),
        (lambda p: "x, y, 1", "you returned a str"),
        (lambda p: np.array([p, 1]), "np.append(p, 1.0)"),
        (lambda p: np.append(p, 1.0).astype(str), "of text"),
        (lambda p: np.array([str(p[0]), str(p[1]), "1"]), "of text"),
        (lambda p: np.append(p, 1.0) + 0j, "complex numbers"),
        (lambda p: np.append(p, 1.0).astype(object), "Python objects"),
        # the worked example's batch code, copied for one point
        (lambda p: np.hstack([p, np.ones((len(p), 1))]), "joins a 1-D array to a 2-D column"),
        (lambda p: np.hstack([p[:, :2], np.ones((len(p), 1))]), "p[0] and p[1]"),
        (lambda p: np.concatenate([p, np.ones((len(p), 1))], axis=1), "no second axis"),
        (lambda p: np.column_stack([p, np.ones(len(p))]), "each coordinate a row"),
        (lambda p: np.c_[p, 1.0], "treat x and y as two rows"),
        (lambda p: np.hstack([p[None], [[1.0]]]), "one point in, one point out"),
        (lambda p: np.append(p, 1.0)[:, None], "a column; points are rows"),
        (lambda p: np.append(p, np.ones(len(p))), "two 1s"),
        (_list_append, "no .append method"),
        (lambda p: p + [1.0], "not the list concatenation"),
        (lambda p: np.concatenate(p, 1), "its second argument is the axis"),
        (lambda p: np.concatenate([p, 1.0]), "the 1 is a bare number"),
    ),
    exception_hint=_batch_code_hint,
    teaching=lift,
))
