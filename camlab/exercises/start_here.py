"""The warm-up exercise of lesson 00: how exercises and checks work."""
from __future__ import annotations

import numpy as np

from .. import projective
from ._core import Exercise, register_exercise, same_array, shape_problem


def _diagnose(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ": append one coordinate, w = 1, to the 2 you were given"
    g = np.asarray(got, dtype=float)
    if g[-1] == 0:
        return "w = 0 makes an ideal point (a direction), not the point itself: append 1"
    p = np.asarray(args[0], dtype=float)
    if np.allclose(g[1:], p):
        return "you put the 1 first; by convention w is the last coordinate: (x, y, 1)"
    if np.allclose(g[:2], p[::-1]):
        return "x and y are swapped: keep the point's order, (u, v) = (column, row), and append 1"
    if np.allclose(g[:2], np.trunc(p)) or np.allclose(g[:2], np.round(p)):
        return ("the coordinates lost their fractions: you cast to int, but image points are real numbers "
                "(sub-pixel positions such as -1.5); keep floats")
    return "append 1 to the point, keeping x and y as they are"


def lift(p):
    """Homogeneous coordinates of one image point: append w = 1."""
    return np.append(np.asarray(p, dtype=float), 1.0)


register_exercise(Exercise(
    name="lift",
    lesson="00",
    reference=projective.to_homogeneous,
    cases=lambda: [(np.array([3.0, 4.0]),), (np.array([-1.5, 0.0]),), (np.array([640.0, 480.0]),)],
    compare=same_array(),
    diagnose=_diagnose,
    wrong_variants=(
        (lambda p: np.append(p, 0.0), "ideal point"),
        (lambda p: np.insert(p, 0, 1.0), "w is the last coordinate"),
        (lambda p: p, "shape (3,)"),
        (lambda p: np.array([p[1], p[0], 1.0]), "swapped"),
        (lambda p: np.append(np.asarray(p).astype(int), 1), "cast to int"),
    ),
    teaching=lift,
))
