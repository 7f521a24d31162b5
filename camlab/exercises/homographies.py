"""Exercises for lesson 07, homographies."""
from __future__ import annotations

import numpy as np

from .. import homography as hg
from ..projective import map_points
from ._core import Exercise, register_exercise, same_array, same_up_to_scale, shape_problem


def _dlt_cases():
    rng = np.random.default_rng(7)
    H1 = np.array([[1.2, 0.1, 15.0], [-0.05, 0.9, 30.0], [5e-4, -2e-4, 1.0]])
    H2 = np.array([[0.8, -0.3, 200.0], [0.25, 1.1, -40.0], [-1e-3, 4e-4, 1.0]])
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    quad = np.array([[100.0, 80.0], [520.0, 60.0], [560.0, 400.0], [90.0, 430.0]])
    pts = rng.uniform([0, 0], [640, 480], (8, 2))
    return [
        (square, 2.0 * square + [3.0, 1.0]),   # a similarity
        (square * 300, quad),                  # the unit-square trick, in pixels
        (quad, map_points(H1, quad)),
        (pts, map_points(H2, pts)),            # more than 4 pairs (noise free)
    ]


def _dlt_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return H as a (3, 3) array: h.reshape(3, 3)."
    src, dst = args
    g = np.asarray(got, dtype=float)
    if same_up_to_scale(g, np.linalg.inv(expected), rtol=1e-5):
        return "your H maps dst to src: it is the inverse. Did you swap src and dst when building A?"
    if same_up_to_scale(g.T, expected, rtol=1e-5):
        return "your H is transposed: h lists H row by row, so use h.reshape(3, 3), not column by column."
    try:
        moved = map_points(g, src[0])
    except Exception:  # a singular H
        moved = np.array([np.nan, np.nan])
    return (f"H maps src[0] = {np.round(src[0], 2)} to {np.round(moved, 2)}; expected {np.round(dst[0], 2)}. "
            f"Take the right singular vector with the smallest singular value (the last row of Vt).")


register_exercise(Exercise(
    name="dlt_homography",
    lesson="07",
    reference=hg.estimate_homography,
    cases=_dlt_cases,
    compare=lambda got, expected: same_up_to_scale(got, expected, rtol=1e-6),
    diagnose=_dlt_diagnosis,
    wrong_variants=(
        (lambda s, d: hg.estimate_homography(d, s), "inverse"),
        (lambda s, d: hg.estimate_homography(s, d).T, "transposed"),
        (lambda s, d: np.linalg.svd(hg._dlt_rows(np.asarray(s, float), np.asarray(d, float)))[2][0].reshape(3, 3),
         "smallest singular value"),
    ),
))


def _apply_cases():
    H = np.array([[1.1, 0.2, 5.0], [-0.1, 0.9, 12.0], [1e-3, 2e-3, 1.0]])
    rng = np.random.default_rng(3)
    return [
        (np.diag([2.0, 3.0, 1.0]), np.array([[1.0, 1.0], [2.0, -1.0]])),
        (H, rng.uniform(0, 400, (5, 2))),
        (H, np.array([[0.0, 0.0]])),
    ]


def _apply_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Lift to (u, v, 1), multiply, divide by the third coordinate, return (N, 2)."
    H, pts = args
    x = np.column_stack([pts, np.ones(len(pts))])
    y = x @ H.T
    g = np.asarray(got, dtype=float)
    if np.allclose(g, y[:, :2], rtol=1e-6):
        return "you forgot to divide by w, the third homogeneous coordinate: (x/w, y/w)."
    z = x @ H
    if np.allclose(g, z[:, :2] / z[:, 2:], rtol=1e-6):
        return "you multiplied by H transposed: with points as rows, x' = X @ H.T."
    return "check the three steps: lift to (u, v, 1), multiply by H (X @ H.T for rows), divide by w."


register_exercise(Exercise(
    name="apply_homography",
    lesson="07",
    reference=map_points,
    cases=_apply_cases,
    compare=same_array(rtol=1e-9, atol=1e-9),
    diagnose=_apply_diagnosis,
    wrong_variants=(
        (lambda H, p: (np.column_stack([p, np.ones(len(p))]) @ H.T)[:, :2], "divide by w"),
        (lambda H, p: map_points(np.asarray(H).T, p), "transposed"),
    ),
))
