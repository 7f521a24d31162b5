"""Exercise 4 of lesson 07: mapping a line by a homography (`map_line`)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from .._answers import same_up_to_scale, shape_problem
from .._core import Exercise, Mistake, first_mistake, register_exercise

_L_INF = np.array([0.0, 0.0, 1.0])


def _line_cases():
    H = np.array([[1.1, 0.2, 5.0], [-0.1, 0.9, 12.0], [1e-3, 2e-3, 1.0]])
    tilt = 2.0 * np.array([[1.0, 0.1, 4.0], [0.05, 1.0, -3.0], [-4e-3, 1e-3, 1.0]])
    return [
        (H, np.array([0.3, -1.0, 40.0])),  # a sloping line; H is not symmetric, so H^T and H differ
        (tilt, np.array([1.0, 0.0, -200.0])),  # the vertical line u = 200; h33 = 2
        # the line that tilt sends to infinity, tilt^T l_inf: its image is l_inf = (0, 0, 1)
        (tilt, tilt.T @ _L_INF),
    ]


def _reference(H, line):
    """l' = H^-T l, solved rather than inverted."""
    return np.linalg.solve(np.asarray(H, dtype=float).T, np.asarray(line, dtype=float))


_LINE_MISTAKES = (
    Mistake(
        "mapped like a point",
        lambda c: c.H @ c.line,
        "you mapped the line like a point, H l. A line maps the other way: a point x on l has "
        "l^T x = 0, and with x' = H x that stays true for l' = H^-T l, since l'^T x' = l^T H^-1 H x = 0. "
        "Return np.linalg.inv(H).T @ l (or np.linalg.solve(H.T, l)).",
    ),
    Mistake(
        "H transposed, not inverted",
        lambda c: c.H.T @ c.line,
        "you used H^T l (or l @ H): H^T takes a line of the *second* image back to the first, "
        "l = H^T l' (section 3 sends l_inf back by it). Forward it is the inverse transposed: "
        "np.linalg.inv(H).T @ l.",
    ),
    Mistake(
        "inverted, not transposed",
        lambda c: np.linalg.inv(c.H) @ c.line,
        "you used H^-1 l: inverted, but not transposed. l' = H^-T l = np.linalg.inv(H).T @ l "
        "(with the line as a row: l @ np.linalg.inv(H)).",
    ),
)
"""The slips in l' = H^-T l, in the order they are tested."""


def _line_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return the line as a (3,) array (a, b, c): np.linalg.inv(H).T @ l."
    H, line = (np.asarray(a, dtype=float) for a in args)
    cause = first_mistake(
        _LINE_MISTAKES,
        SimpleNamespace(H=H, line=line),
        got,
        lambda g, wrong: same_up_to_scale(g, wrong, rtol=1e-6),
    )
    return cause or (
        "a line l maps to l' = H^-T l (any non-zero multiple is the same line): "
        "np.linalg.inv(H).T @ l, or np.linalg.solve(H.T, l)."
    )


def map_line(H, line):
    """The image of a line under a homography: l' = H^-T l.

    A point x on l has l^T x = 0. With x' = H x, l'^T x' = l^T H^-1 H x = 0 for l' = H^-T l, so
    l' passes through the image of every point of l.

    Parameters
    ----------
    H : (3, 3) array_like
        The homography, x' ~ H x.
    line : (3,) array_like
        The line (a, b, c): a u + b v + c = 0.

    Returns
    -------
    (3,) ndarray
        The mapped line, up to scale.
    """
    return np.linalg.inv(np.asarray(H, dtype=float)).T @ np.asarray(line, dtype=float)


register_exercise(
    Exercise(
        name="map_line",
        lesson="07",
        reference=_reference,
        cases=_line_cases,
        compare=same_up_to_scale,
        diagnose=_line_diagnosis,
        wrong_variants=(
            (lambda H, ln: np.asarray(H) @ ln, "like a point"),
            (lambda H, ln: np.asarray(H).T @ ln, "H^T l"),
            (lambda H, ln: ln @ np.asarray(H), "H^T l"),
            (lambda H, ln: np.linalg.inv(H) @ ln, "not transposed"),
            (lambda H, ln: (np.linalg.inv(H).T @ ln)[:2], "(3,) array"),
        ),
        teaching=map_line,
    )
)
