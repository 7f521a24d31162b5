"""Lesson 01's exercise best_pinhole_exposure: the light a best pinhole costs, against a lens."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import pinhole
from .._core import Exercise, Mistake, first_mistake, register_exercise
from .._numbers import is_number
from .focal_length import one_number

# ---------------------------------------------------------------- best_pinhole_exposure


def _exposure_reference(f, wavelength, t_lens, N_lens):
    """t_lens (f / d* / N_lens)^2 with d* = camlab.pinhole.optimal_pinhole_diameter(f, wavelength), in seconds."""
    d_star = pinhole.optimal_pinhole_diameter(f, wavelength)
    return float(t_lens * (f / d_star / N_lens) ** 2)


class NearMinimumExposure:
    """``Exercise.compare`` for the exposure time: the time of a hole whose blur is within 0.05 % of the least.

    The time goes as 1 / d^2, so a time t against the right t* means a hole r = sqrt(t* / t) times d*,
    whose blur is (r + 1/r) / 2 times the least (:class:`NearMinimumBlur`). Within 0.05 % is r within
    3.2 % of 1, a time within about 6.5 %: a hole found numerically on the flat minimum passes (scipy's
    bounded ``minimize_scalar`` with its default xatol of 1e-5 m stops up to 3 % from a 0.23 mm d*, so
    1 % on the time, 0.5 % on d, was too tight); Rayleigh's hole (22 % wider), a 550 nm hole for 450 nm
    (10 % wider) and the best hole for an object 1 m away (5 % narrower at f = 0.1 m) do not.
    """

    excess = 5e-4

    def __call__(self, got, expected) -> bool:
        """Whether the hole behind ``got`` blurs at most ``excess`` more than the best one does.

        Parameters
        ----------
        got : object
            The student's exposure time, s.
        expected : float
            The exposure time with the best hole, s.

        Returns
        -------
        bool
            True for a positive number whose hole (d ~ 1 / sqrt(t)), relative to the best,
            r = sqrt(expected / got), blurs (r + 1/r)/2 - 1 <= ``excess`` more.
        """
        if not is_number(got) or not float(got) > 0:
            return False
        r = np.sqrt(float(expected) / float(got))
        return (r + 1 / r) / 2 - 1 <= self.excess


def _exposure_cases():
    return [(0.1, 550e-9, 1 / 100, 2.8), (0.05, 450e-9, 1 / 250, 4.0), (0.3, 650e-9, 1 / 60, 8.0)]


_EXPOSURE_SLIPS = (
    Mistake(
        "f-number ratio not squared",
        lambda s: s.t * s.Np / s.N,
        ("light goes as the hole's area, (d / f)^2: square the ratio of the f-numbers"),
    ),
    Mistake(
        "upside down",
        lambda s: s.t * (s.N / s.Np) ** 2,
        (
            "upside down: the pinhole gathers less light than the lens, so it needs the longer"
            " exposure, t (N_pinhole / N_lens)^2"
        ),
    ),
    Mistake(
        "d / f",
        lambda s: s.t * (s.d / s.f / s.N) ** 2,
        ("the f-number is f / d (a large number for a pinhole), not d / f"),
    ),
    Mistake(
        "d / N",
        lambda s: s.t * (s.d / s.N) ** 2,
        ("the f-number is f / d, a ratio of lengths: divide f by the hole's diameter"),
    ),
    Mistake(
        "no 2.44",
        lambda s: s.t * (s.f / np.sqrt(s.lam * s.f) / s.N) ** 2,
        ("you dropped the 2.44 from d* = sqrt(2.44 lambda f)"),
    ),
    Mistake(
        "Airy radius",
        lambda s: s.t * (s.f / np.sqrt(1.22 * s.lam * s.f) / s.N) ** 2,
        ("you used the Airy radius's 1.22; the best hole (section 3) is d* = sqrt(2.44 lambda f)"),
    ),
    Mistake(
        "Rayleigh",
        lambda s: s.t * (s.f / (1.9 * np.sqrt(s.lam * s.f)) / s.N) ** 2,
        (
            "that is Rayleigh's hole, 1.9 sqrt(lambda f); this lesson's best"
            " hole is d* = sqrt(2.44 lambda f)"
        ),
    ),
    Mistake(
        "no square root",
        lambda s: s.t * (s.f / (2.44 * s.lam * s.f) / s.N) ** 2,
        ("d* needs the square root: d* = sqrt(2.44 lambda f)"),
    ),
    Mistake(
        "radius",
        lambda s: s.t * (s.f / (s.d / 2) / s.N) ** 2,
        ("you used the hole's radius; the f-number is f over the diameter d*"),
    ),
    Mistake(
        "sign flip",
        lambda s: -s.expected,
        (
            "a sign flip: an exposure time is a positive number of seconds, t_lens (N / N_lens)^2; look for a"
            " stray minus sign"
        ),
    ),
    Mistake(
        "f left out of the root",
        lambda s: s.t * (s.f / np.sqrt(2.44 * s.lam) / s.N) ** 2,
        (
            "f is missing under the square root: the best hole is d* = sqrt(2.44 lambda f), not sqrt(2.44 lambda)"
        ),
    ),
    Mistake(
        "sqrt(f) for f",
        lambda s: s.t * (np.sqrt(s.f) / s.d / s.N) ** 2,
        (
            "the f-number is f / d*, with f itself on top (a length over a length); you used sqrt(f), which"
            " belongs only inside d* = sqrt(2.44 lambda f)"
        ),
    ),
    Mistake(
        "2.44 outside the root",
        lambda s: s.t * (s.f / (2.44 * np.sqrt(s.lam * s.f)) / s.N) ** 2,
        (
            "the 2.44 belongs under the square root: d* = sqrt(2.44 lambda f), about 1.56 sqrt(lambda f), not"
            " 2.44 sqrt(lambda f)"
        ),
    ),
    Mistake(
        "divided by the lens's time",
        lambda s: (s.Np / s.N) ** 2 / s.t,
        (
            "you divided by t_lens: the pinhole needs (N / N_lens)^2 times the lens's time, so multiply,"
            " t_lens (N / N_lens)^2"
        ),
    ),
    Mistake(
        "the pinhole's f-number",
        lambda s: s.Np,
        ("you returned the pinhole's f-number f / d*; return the exposure time in seconds"),
    ),
    Mistake(
        "the best diameter",
        lambda s: s.d,
        ("you returned the best diameter d*; return the exposure time in seconds"),
    ),
    Mistake(
        "N_lens squared too",
        lambda s: s.t * s.Np**2 / s.N,
        (
            "square N_lens too: the light goes as 1 / N^2 for the lens as for the pinhole, so the"
            " time is t_lens (N / N_lens)^2 = t_lens N^2 / N_lens^2"
        ),
    ),
    Mistake(
        "N squared only",
        lambda s: s.t * s.Np / s.N**2,
        (
            "square the pinhole's f-number too: the time is t_lens (N / N_lens)^2 = t_lens N^2 / N_lens^2"
        ),
    ),
    Mistake(
        "square root of the ratio",
        lambda s: s.t * np.sqrt(s.Np / s.N),
        (
            "square the ratio, do not take its root: light goes as the hole's area, (d / f)^2, so"
            " the time is t_lens (N / N_lens)^2"
        ),
    ),
    Mistake(
        "the best blur as the hole",
        lambda s: s.t * (s.f / (2 * s.d) / s.N) ** 2,
        (
            "you used the best blur, 2 d*, as the hole: b(d*) = d* + d* = 2 d* is the blur"
            " at the best hole; the hole itself is d* = sqrt(2.44 lambda f)"
        ),
    ),
    Mistake(
        "the ratio only",
        lambda s: (s.Np / s.N) ** 2,
        (
            "you returned the ratio of the exposure times, (N / N_lens)^2; multiply by the lens's time"
            " t_lens for the pinhole's time in seconds"
        ),
    ),
    Mistake(
        "milliseconds",
        lambda s: 1e3 * s.expected,
        (
            "your answer is 1000 times the expected one: milliseconds, or f in millimetres (the time"
            " goes as N^2 = f / (2.44 lambda), so it grows with f)? The answer is in seconds, with f and"
            " the wavelength in metres"
        ),
    ),
    Mistake(
        "minutes",
        lambda s: s.expected / 60,
        ("you answered in minutes; the answer is in seconds"),
    ),
    Mistake(
        "hours",
        lambda s: s.expected / 3600,
        ("you answered in hours; the answer is in seconds"),
    ),
    Mistake(
        "550 nm",
        lambda s: s.t * (s.f / np.sqrt(2.44 * 550e-9 * s.f) / s.N) ** 2,
        lambda s: (
            "you used 550 nm; use the `wavelength` argument (this test"
            f" input is {s.lam * 1e9:.0f} nm)"
        ),
    ),
    Mistake(
        "object 1 m away",
        lambda s: s.t * (s.f / np.sqrt(2.44 * s.lam * s.f / (1 + s.f / 1.0)) / s.N) ** 2,
        (
            "you used the best hole for an object 1 m away, sqrt(2.44 lambda f / (1 + f/Z)); this camera looks at a"
            " distant object (Z -> infinity): d* = sqrt(2.44 lambda f)"
        ),
    ),
)
"""Slips in the exposure time: each row's answer from the lens's time ``s.t`` and f-number ``s.N``, the focal
length ``s.f``, the wavelength ``s.lam``, the best hole ``s.d``, its f-number ``s.Np`` and the right answer."""


def _exposure_diagnosis(args, got, expected) -> str:
    f, lam, t, N = args
    problem = one_number(got, "the exposure time in seconds")
    if problem:
        return problem
    g = float(got)
    d = np.sqrt(2.44 * lam * f)
    Np = f / d
    context = SimpleNamespace(t=t, N=N, f=f, lam=lam, d=d, Np=Np, expected=expected)
    cause = first_mistake(  # atol=0: a tiny variant must not match an answer of 0
        _EXPOSURE_SLIPS, context, g, lambda got, wrong: np.isclose(got, wrong, rtol=1e-3, atol=0)
    )
    if cause:
        return cause
    if g < 0:
        return (
            f"an exposure time is a positive number of seconds, but you returned {g:g}: look for a stray minus"
            " sign, t_lens (N / N_lens)^2 with N = f / d* is positive"
        )
    if np.isnan(g):
        return (
            "you returned NaN (not a number): a square root of a negative number (2.44 lambda f must be"
            " positive, every length in metres) or a 0 / 0 somewhere"
        )
    if np.isinf(g):
        return "you returned infinity: a division by zero somewhere (a d* that came out 0?)"
    if g == 0:
        return (
            "you returned 0 s: a product with a factor of 0, or an integer result rounded down (int(), //)?"
            " The time is t_lens (N / N_lens)^2, seconds to minutes"
        )
    ratio = g / expected
    k = np.log10(ratio) / 3
    if (
        abs(k - round(k)) < 1.5e-4 and round(k) != 0
    ):  # within 0.1 % of a power of 1000: true unit slips are exact
        return (
            f"your answer is {ratio:.3g} times the expected one: a unit slip (the wavelength in nm or um, or f in"
            " mm?); keep every length in metres, and the time in seconds"
        )
    return "exposure time t_lens (N / N_lens)^2, with the pinhole's f-number N = f / d* and d* = sqrt(2.44 lambda f)"


def best_pinhole_exposure(f, wavelength, t_lens, N_lens):
    """Exposure time (s) of a pinhole camera of length f with its best hole, matching a lens at N_lens for t_lens.

    The light on the image goes as (d / f)^2 = 1 / N^2, so the exposure time goes as N^2.

    Parameters
    ----------
    f : float
        The pinhole camera's length, m.
    wavelength : float
        The light's wavelength, m.
    t_lens : float
        The lens's exposure time, s.
    N_lens : float
        The lens's f-number.

    Returns
    -------
    float
        t_lens (N / N_lens)^2, s, with N = f / d* the f-number of the best hole d* = sqrt(2.44 wavelength f).
    """
    d_star = np.sqrt(2.44 * wavelength * f)  # the best hole for a distant object (section 3)
    N = f / d_star  # its f-number
    return float(t_lens * (N / N_lens) ** 2)


register_exercise(
    Exercise(
        name="best_pinhole_exposure",
        lesson="01",
        reference=_exposure_reference,
        cases=_exposure_cases,
        compare=NearMinimumExposure(),
        diagnose=_exposure_diagnosis,
        wrong_variants=(
            (lambda f, lam, t, N: t * f / np.sqrt(2.44 * lam * f) / N, "square the ratio"),
            (lambda f, lam, t, N: t * (N * np.sqrt(2.44 * lam * f) / f) ** 2, "upside down"),
            (lambda f, lam, t, N: t * (np.sqrt(2.44 * lam * f) / f / N) ** 2, "not d / f"),
            (lambda f, lam, t, N: t * (f / np.sqrt(lam * f) / N) ** 2, "2.44"),
            (lambda f, lam, t, N: t * (f / (1.9 * np.sqrt(lam * f)) / N) ** 2, "Rayleigh"),
            (lambda f, lam, t, N: t * (f / np.sqrt(2.44 * lam * 1e-9 * f) / N) ** 2, "unit slip"),
            (lambda f, lam, t, N: f / np.sqrt(2.44 * lam * f), "f-number"),
            (lambda f, lam, t, N: 1e3 * t * (f / np.sqrt(2.44 * lam * f) / N) ** 2, "milliseconds"),
            (
                lambda f, lam, t, N: (f / np.sqrt(2.44 * lam * f) / N) ** 2,
                "multiply by the lens's time",
            ),
            (lambda f, lam, t, N: t * (f / np.sqrt(2.44 * 550e-9 * f) / N) ** 2, "you used 550 nm"),
            (
                lambda f, lam, t, N: t * (f / np.sqrt(2.44 * lam * f / (1 + f)) / N) ** 2,
                "distant object",
            ),
            (lambda f, lam, t, N: t * (f / np.sqrt(2.44 * lam * f) / N) ** 2 / 60, "minutes"),
            (lambda f, lam, t, N: -t * (f / np.sqrt(2.44 * lam * f) / N) ** 2, "a sign flip"),
            (lambda f, lam, t, N: t * (f / np.sqrt(2.44 * lam) / N) ** 2, "f is missing under"),
            (
                lambda f, lam, t, N: t * (f / (2.44 * np.sqrt(lam * f)) / N) ** 2,
                "belongs under the square root",
            ),
            (
                lambda f, lam, t, N: (f / np.sqrt(2.44 * lam * f) / N) ** 2 / t,
                "you divided by t_lens",
            ),
            (lambda f, lam, t, N: float("nan"), "NaN"),
            (lambda f, lam, t, N: 0.0, "you returned 0 s"),
            (lambda f, lam, t, N: t * (f / np.sqrt(2.44 * lam * f)) ** 2 / N, "square N_lens too"),
            (
                lambda f, lam, t, N: t * np.sqrt(f / np.sqrt(2.44 * lam * f) / N),
                "do not take its root",
            ),
            (
                lambda f, lam, t, N: t * (f / (2 * np.sqrt(2.44 * lam * f)) / N) ** 2,
                "the best blur, 2 d*, as the hole",
            ),
            (lambda f, lam, t, N: [t * (f / np.sqrt(2.44 * lam * f) / N) ** 2], "brackets"),
            (
                lambda f, lam, t, N: f"{t * (f / np.sqrt(2.44 * lam * f) / N) ** 2:.0f} s",
                "you returned a str",
            ),
        ),
        teaching=best_pinhole_exposure,
    )
)
