"""Exercises for lesson 01, the pinhole camera."""
from __future__ import annotations

import numpy as np

from .. import pinhole
from ._numbers import same_number
from ._core import Exercise, register_exercise, same_array, shape_problem, unit_slip


def _projection_cases():
    rng = np.random.default_rng(1)
    pts = np.column_stack([rng.uniform(-1, 1, (6, 2)), rng.uniform(1, 5, 6)])
    return [
        (np.array([[0.5, -0.25, 2.0]]), 0.05),
        (np.array([[0.0, 0.0, 1.0], [0.2, 0.4, 4.0]]), 0.1),   # (2, 2) / (2,) broadcasts: a silent slip
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
        return ("a broadcasting slip: X[:, :2] / X[:, 2] divides column j by the depth of point j; "
                "keep the depth column 2-D, X[:, 2:3], so each row is divided by its own Z")
    if np.allclose(g, -expected):
        return "your image is inverted: that is the real image behind the pinhole; use the virtual plane, x = f X / Z"
    if np.allclose(g, f * X[:, :2]):
        return "you did not divide by the depth Z: x = f X / Z"
    if np.allclose(g, X[:, :2] / X[:, 2:3]):
        return "you forgot to multiply by the focal length f"
    return "check the similar triangles: x / f = X / Z and y / f = Y / Z"


def pinhole_projection(X, f):
    """Virtual image of camera-frame points: x = f X / Z, y = f Y / Z (similar triangles)."""
    X = np.asarray(X, dtype=float)
    Z = X[:, 2:3]                 # (N, 1), so one division scales both columns
    return f * X[:, :2] / Z


register_exercise(Exercise(
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
    ),
    teaching=pinhole_projection,
))


def _best_cases():
    return [(0.1, 550e-9), (0.05, 450e-9), (0.25, 650e-9)]


def _best_diagnosis(args, got, expected) -> str:
    f, lam = args
    try:
        g = float(got)
    except (TypeError, ValueError):
        return "return a single number: the diameter in metres"
    slip = unit_slip(got, expected) or _slip_under_root(g / expected)
    if slip:
        return slip
    if np.isclose(g, np.sqrt(1.22 * lam * f)):
        return ("you used the Airy disc's radius 1.22 lambda f / d; the blur to minimise adds diameters: "
                "d + 2.44 lambda f / d")
    if np.isclose(g, np.sqrt(lam * f)):
        return "you dropped the 2.44 of the Airy disc: minimise d + 2.44 lambda f / d"
    if np.isclose(g, 2.44 * lam * f):
        return "you forgot the square root: setting the derivative 1 - 2.44 lambda f / d^2 to zero gives d^2 = 2.44 lambda f"
    return "minimise the total blur d + 2.44 lambda f / d over d (a distant object)"


def _slip_under_root(ratio: float) -> str | None:
    """A unit slip inside the square root: the answer off by sqrt(1000^k), e.g. f in mm or lambda in nm."""
    k = np.log10(ratio ** 2) / 3
    if abs(k - round(k)) > 0.01 or round(k) == 0:
        return None
    return (f"your answer is {ratio:.3g} times the expected one, sqrt(1000^{round(k)}): a unit slipped inside the"
            " square root (f in mm, or lambda in nm or um?); keep f and the wavelength in metres")


def best_pinhole_diameter(f, wavelength):
    """Minimise b(d) = d + 2.44 wavelength f / d: b'(d) = 1 - 2.44 wavelength f / d**2 = 0."""
    return float(np.sqrt(2.44 * wavelength * f))


register_exercise(Exercise(
    name="best_pinhole_diameter",
    lesson="01",
    reference=pinhole.optimal_pinhole_diameter,
    cases=_best_cases,
    compare=same_number(rtol=1e-6),
    diagnose=_best_diagnosis,
    wrong_variants=(
        (lambda f, lam: float(np.sqrt(lam * f)), "2.44"),
        (lambda f, lam: 2.44 * lam * f, "square root"),
        (lambda f, lam: 1e3 * float(np.sqrt(2.44 * lam * f)), "millimetres"),
        (lambda f, lam: float(np.sqrt(2.44 * lam * f * 1e3)), "f in mm"),
        (lambda f, lam: float(np.sqrt(2.44 * lam * 1e-9 * f)), "nm"),
        (lambda f, lam: float(np.sqrt(1.22 * lam * f)), "radius"),
    ),
    teaching=best_pinhole_diameter,
))
