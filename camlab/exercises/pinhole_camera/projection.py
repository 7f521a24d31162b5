"""Lesson 01's first exercise: the pinhole projection x = f X / Z of camera-frame points (similar triangles)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import pinhole
from .._answers import same_array, shape_problem, unit_slip
from .._core import Exercise, Mistake, first_mistake, register_exercise


def _projection_cases():
    rng = np.random.default_rng(1)
    pts = np.column_stack([rng.uniform(-1, 1, (6, 2)), rng.uniform(1, 5, 6)])
    return [
        (np.array([[0.5, -0.25, 2.0]]), 0.05),
        (
            np.array([[0.0, 0.0, 1.0], [0.2, 0.4, 4.0]]),
            0.1,
        ),  # (2, 2) / (2,) broadcasts: a silent slip
        (pts, 0.035),
    ]


def _projection_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return one (x, y) row per point."
    slip = unit_slip(got, expected)
    if slip:
        return slip
    g = np.asarray(got, dtype=float)
    X, f = args
    if np.allclose(g, f * X[:, :2] / X[:, 2]):
        return (
            "a broadcasting slip: X[:, :2] / X[:, 2] divides column j by the depth of point j; "
            "keep the depth column 2-D, X[:, 2:3], so each row is divided by its own Z"
        )
    cause = first_mistake(_PROJECTION_SLIPS, SimpleNamespace(X=X, f=f, e=expected), g, np.allclose)
    return cause or "check the similar triangles: x / f = X / Z and y / f = Y / Z"


_PROJECTION_SLIPS = (
    Mistake(
        "inverted",
        lambda s: -s.e,
        (
            "your image is inverted: that is the real image behind the pinhole; use the virtual plane,"
            " x = f X / Z"
        ),
    ),
    Mistake(
        "y negated",
        lambda s: s.e * [1, -1],
        (
            "you negated y only: in the camera frame y points down, and the virtual image keeps"
            " that, y = f Y / Z with no minus sign (a y-up habit from maths plots?)"
        ),
    ),
    Mistake(
        "x negated",
        lambda s: s.e * [-1, 1],
        ("you negated x only: x = f X / Z, with no minus sign"),
    ),
    Mistake(
        "x and y swapped",
        lambda s: s.e[:, ::-1],
        ("x and y are swapped: column 0 is x = f X / Z, column 1 is y = f Y / Z"),
    ),
    Mistake(
        "columns 1 and 2",
        lambda s: s.f * s.X[:, 1:3] / s.X[:, 2:3],
        (
            "you took columns 1 and 2 (y and Z) for x and y: Python counts from 0,"
            " so X is column 0, Y column 1 and Z column 2"
        ),
    ),
    Mistake(
        "no division by Z",
        lambda s: s.f * s.X[:, :2],
        ("you did not divide by the depth Z: x = f X / Z"),
    ),
    Mistake(
        "no f",
        lambda s: s.X[:, :2] / s.X[:, 2:3],
        ("you forgot to multiply by the focal length f"),
    ),
    Mistake(
        "divided by f",
        lambda s: s.X[:, :2] / s.X[:, 2:3] / s.f,
        ("you divided by f: x / f = X / Z, so x = f X / Z (multiply by f)"),
    ),
    Mistake(
        "times Z over f",
        lambda s: s.X[:, :2] * s.X[:, 2:3] / s.f,
        ("you multiplied by Z and divided by f: the other way round, x = f X / Z"),
    ),
    Mistake(
        "over Z + f",
        lambda s: s.f * s.X[:, :2] / (s.X[:, 2:3] + s.f),
        (
            "you divided by Z + f: the similar triangles meet at the pinhole,"
            " so the legs are Z and f, x = f X / Z"
        ),
    ),
    Mistake(
        "over the distance",
        lambda s: s.f * s.X[:, :2] / np.linalg.norm(s.X, axis=1, keepdims=True),
        (
            "you divided by the distance to the point; divide by its depth Z (the third coordinate): x = f X / Z"
        ),
    ),
)
"""The projection slips: each row's answer from the points ``s.X``, the focal length ``s.f`` and the right
answer ``s.e``."""


def pinhole_projection(X, f):
    """Virtual image of camera-frame points: x = f X / Z, y = f Y / Z (similar triangles).

    Parameters
    ----------
    X : (N, 3) array_like
        Points in the camera frame, m, with Z > 0.
    f : float
        The focal length (pinhole to image plane), m.

    Returns
    -------
    (N, 2) ndarray
        (x, y) on the virtual image plane, m.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 6.1 (the basic pinhole model).
    """
    X = np.asarray(X, dtype=float)
    Z = X[:, 2:3]  # (N, 1), so one division scales both columns
    return f * X[:, :2] / Z


register_exercise(
    Exercise(
        name="pinhole_projection",
        lesson="01",
        reference=pinhole.project_pinhole,
        cases=_projection_cases,
        compare=same_array(rtol=1e-9, atol=1e-12),
        diagnose=_projection_diagnosis,
        wrong_variants=(
            (lambda X, f: -f * X[:, :2] / X[:, 2:3], "inverted"),
            (lambda X, f: f * X[:, :2], "divide by the depth"),
            (lambda X, f: X[:, :2] / X[:, 2:3], "multiply by the focal length"),
            (lambda X, f: 1e3 * f * X[:, :2] / X[:, 2:3], "millimetres"),
            (lambda X, f: f * X[:, :2] / X[:, 2], "broadcasting"),
            (lambda X, f: f * X[:, :2] / X[:, 2:3] * [1, -1], "negated y only"),
            (lambda X, f: (f * X[:, :2] / X[:, 2:3])[:, ::-1], "swapped"),
            (lambda X, f: X[:, :2] / X[:, 2:3] / f, "divided by f"),
            (lambda X, f: f * X[:, 1:3] / X[:, 2:3], "counts from 0"),
            (lambda X, f: f * X[:, 1:3] / X[:, 3:4], "counting columns from 1"),
        ),
        teaching=pinhole_projection,
    )
)
