"""Exercises for lesson 01, the pinhole camera."""
from __future__ import annotations

import numpy as np

from .. import pinhole
from ._numbers import is_number
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
    for variant, cause in _PROJECTION_SLIPS:
        if np.allclose(g, variant(X, f, expected)):
            return cause
    return "check the similar triangles: x / f = X / Z and y / f = Y / Z"


_PROJECTION_SLIPS = (  # (what the slip returns, given X, f and the right answer; its likely cause)
    (lambda X, f, e: -e, "your image is inverted: that is the real image behind the pinhole; use the virtual plane,"
                         " x = f X / Z"),
    (lambda X, f, e: e * [1, -1], "you negated y only: in the camera frame y points down, and the virtual image keeps"
                                  " that, y = f Y / Z with no minus sign (a y-up habit from maths plots?)"),
    (lambda X, f, e: e * [-1, 1], "you negated x only: x = f X / Z, with no minus sign"),
    (lambda X, f, e: e[:, ::-1], "x and y are swapped: column 0 is x = f X / Z, column 1 is y = f Y / Z"),
    (lambda X, f, e: f * X[:, 1:3] / X[:, 2:3], "you took columns 1 and 2 (y and Z) for x and y: Python counts from 0,"
                                                " so X is column 0, Y column 1 and Z column 2"),
    (lambda X, f, e: f * X[:, :2], "you did not divide by the depth Z: x = f X / Z"),
    (lambda X, f, e: X[:, :2] / X[:, 2:3], "you forgot to multiply by the focal length f"),
    (lambda X, f, e: X[:, :2] / X[:, 2:3] / f, "you divided by f: x / f = X / Z, so x = f X / Z (multiply by f)"),
    (lambda X, f, e: X[:, :2] * X[:, 2:3] / f, "you multiplied by Z and divided by f: the other way round, x = f X / Z"),
    (lambda X, f, e: f * X[:, :2] / (X[:, 2:3] + f), "you divided by Z + f: the similar triangles meet at the pinhole,"
                                                     " so the legs are Z and f, x = f X / Z"),
    (lambda X, f, e: f * X[:, :2] / np.linalg.norm(X, axis=1, keepdims=True),
     "you divided by the distance to the point; divide by its depth Z (the third coordinate): x = f X / Z"),
)


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
        (lambda X, f: f * X[:, :2] / X[:, 2:3] * [1, -1], "negated y only"),
        (lambda X, f: (f * X[:, :2] / X[:, 2:3])[:, ::-1], "swapped"),
        (lambda X, f: X[:, :2] / X[:, 2:3] / f, "divided by f"),
        (lambda X, f: f * X[:, 1:3] / X[:, 2:3], "counts from 0"),
        (lambda X, f: f * X[:, 1:3] / X[:, 3:4], "counting columns from 1"),
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
    for wrong, cause in (
        (np.sqrt(1.22 * lam * f), "you used the Airy disc's radius 1.22 lambda f / d; the blur to minimise adds"
                                  " diameters: d + 2.44 lambda f / d"),
        (np.sqrt(lam * f), "you dropped the 2.44 of the Airy disc: minimise d + 2.44 lambda f / d"),
        (1.9 * np.sqrt(lam * f), "that is Rayleigh's 1.9 sqrt(lambda f), from another blur criterion; this exercise"
                                 " minimises the summed diameters d + 2.44 lambda f / d"),
        (2.44 * lam * f, "you forgot the square root: setting the derivative 1 - 2.44 lambda f / d^2 to zero gives"
                         " d^2 = 2.44 lambda f"),
        (2 * expected, "you returned the blur at the best hole, b(d*) = 2 d*; return the diameter d* itself"),
        (expected / 2, "you returned a radius, d*/2; return the hole's diameter"),
        (np.sqrt(2.44 * lam / f), "f belongs in the numerator: d^2 = 2.44 lambda f"),
        (np.sqrt(2.44 * 550e-9 * f), "you used 550 nm; use the `wavelength` argument (this test input is"
                                     f" {lam * 1e9:.0f} nm)"),
    ):
        if np.isclose(g, wrong, rtol=1e-3, atol=0):
            return cause
    return "minimise the total blur d + 2.44 lambda f / d over d (a distant object)"


class NearMinimumBlur:
    """``Exercise.compare`` for the best diameter: one number whose total blur is within :attr:`excess` of the least.

    b(d) = d + 2.44 lambda f / d = d + d*^2 / d, so b(r d*) / b(d*) = (r + 1/r) / 2 depends only on
    r = got / expected. A numerical minimiser's answer (scipy's bounded ``minimize_scalar`` stops
    within a few tenths of a percent of d*, where the curve is flat) passes; an answer off by
    4.5 % or more does not, nor does any mistake the diagnosis names (the nearest, 550 nm for
    450 nm, is 10 % off).
    """

    excess = 1e-3

    def __call__(self, got, expected) -> bool:
        if not is_number(got) or not float(got) > 0:
            return False
        r = float(got) / float(expected)
        return (r + 1 / r) / 2 - 1 <= self.excess


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
    compare=NearMinimumBlur(),
    diagnose=_best_diagnosis,
    wrong_variants=(
        (lambda f, lam: float(np.sqrt(lam * f)), "2.44"),
        (lambda f, lam: 2.44 * lam * f, "square root"),
        (lambda f, lam: 1e3 * float(np.sqrt(2.44 * lam * f)), "millimetres"),
        (lambda f, lam: float(np.sqrt(2.44 * lam * f * 1e3)), "f in mm"),
        (lambda f, lam: float(np.sqrt(2.44 * lam * 1e-9 * f)), "nm"),
        (lambda f, lam: float(np.sqrt(1.22 * lam * f)), "radius"),
        (lambda f, lam: 1.9 * float(np.sqrt(lam * f)), "Rayleigh"),
        (lambda f, lam: 2 * float(np.sqrt(2.44 * lam * f)), "blur at the best hole"),
        (lambda f, lam: float(np.sqrt(2.44 * lam * f)) / 2, "a radius"),
        (lambda f, lam: float(np.sqrt(2.44 * 550e-9 * f)), "wavelength"),
    ),
    teaching=best_pinhole_diameter,
))
