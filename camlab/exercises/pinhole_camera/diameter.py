"""Lesson 01's second exercise: the best pinhole diameter, where geometric blur and diffraction balance."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import pinhole
from .._answers import unit_slip
from .._core import Exercise, Mistake, first_mistake, register_exercise
from .._numbers import is_number


def _best_cases():
    return [(0.1, 550e-9), (0.05, 450e-9), (0.25, 650e-9)]


_DIAMETER_SLIPS = (
    Mistake(
        "Airy radius",
        lambda s: np.sqrt(1.22 * s.lam * s.f),
        (
            "you used the Airy disc's radius 1.22 lambda f / d; the blur to minimise adds"
            " diameters: d + 2.44 lambda f / d"
        ),
    ),
    Mistake(
        "no 2.44",
        lambda s: np.sqrt(s.lam * s.f),
        ("you dropped the 2.44 of the Airy disc: minimise d + 2.44 lambda f / d"),
    ),
    Mistake(
        "Rayleigh",
        lambda s: 1.9 * np.sqrt(s.lam * s.f),
        (
            "that is Rayleigh's 1.9 sqrt(lambda f), from another blur criterion; this exercise"
            " minimises the summed diameters d + 2.44 lambda f / d"
        ),
    ),
    Mistake(
        "no square root",
        lambda s: 2.44 * s.lam * s.f,
        (
            "you forgot the square root: setting the derivative 1 - 2.44 lambda f / d^2 to zero gives"
            " d^2 = 2.44 lambda f"
        ),
    ),
    Mistake(
        "the blur",
        lambda s: 2 * s.expected,
        ("you returned the blur at the best hole, b(d*) = 2 d*; return the diameter d* itself"),
    ),
    Mistake(
        "a radius",
        lambda s: s.expected / 2,
        ("you returned a radius, d*/2; return the hole's diameter"),
    ),
    Mistake(
        "f in the denominator",
        lambda s: np.sqrt(2.44 * s.lam / s.f),
        ("f belongs in the numerator: d^2 = 2.44 lambda f"),
    ),
    Mistake(
        "550 nm",
        lambda s: np.sqrt(2.44 * 550e-9 * s.f),
        lambda s: (
            "you used 550 nm; use the `wavelength` argument (this test input is"
            f" {s.lam * 1e9:.0f} nm)"
        ),
    ),
)
"""Slips in the best diameter: each row's answer from the focal length ``s.f``, the wavelength ``s.lam`` and
the right answer ``s.expected``."""


def _best_diagnosis(args, got, expected) -> str:
    f, lam = args
    try:
        g = float(got)
    except (TypeError, ValueError):
        return "return a single number: the diameter in metres"
    slip = unit_slip(got, expected) or _slip_under_root(g / expected)
    if slip:
        return slip
    cause = first_mistake(
        _DIAMETER_SLIPS,
        SimpleNamespace(f=f, lam=lam, expected=expected),
        g,
        lambda got, wrong: np.isclose(got, wrong, rtol=1e-3, atol=0),
    )
    if cause:
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
        """Whether ``got`` blurs at most ``excess`` more than the best diameter ``expected`` does.

        Parameters
        ----------
        got : object
            The student's diameter, m.
        expected : float
            The best diameter, m.

        Returns
        -------
        bool
            True for a positive number whose blur, relative to the minimum, (r + 1/r)/2 - 1 with
            r = got / expected, is at most ``excess``.
        """
        if not is_number(got) or not float(got) > 0:
            return False
        r = float(got) / float(expected)
        return (r + 1 / r) / 2 - 1 <= self.excess


def _slip_under_root(ratio: float) -> str | None:
    """A unit slip inside the square root: the answer off by sqrt(1000^k), e.g. f in mm or lambda in nm."""
    k = np.log10(ratio**2) / 3
    if abs(k - round(k)) > 0.01 or round(k) == 0:
        return None
    return (
        f"your answer is {ratio:.3g} times the expected one, sqrt(1000^{round(k)}): a unit slipped inside the"
        " square root (f in mm, or lambda in nm or um?); keep f and the wavelength in metres"
    )


def best_pinhole_diameter(f, wavelength):
    """Minimise b(d) = d + 2.44 wavelength f / d: b'(d) = 1 - 2.44 wavelength f / d**2 = 0.

    Parameters
    ----------
    f : float
        The pinhole camera's length (hole to image), m.
    wavelength : float
        The light's wavelength, m.

    Returns
    -------
    float
        d* = sqrt(2.44 wavelength f), m: the diameter of least blur for a distant object.
    """
    return float(np.sqrt(2.44 * wavelength * f))


register_exercise(
    Exercise(
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
    )
)
