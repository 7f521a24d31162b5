"""Lesson 03's fifth exercise: the frequency a sampled cosine shows, f folded into [0, 1/2]."""

from __future__ import annotations

import numpy as np

from ... import sensor
from .._answers import same_array, shape_problem
from .._core import Exercise, Mistake, first_mistake, register_exercise


def _alias_cases():
    return [
        (np.array([0.2, 0.55, 0.8, 1.3]),),  # below the limit, above it, and beyond 1
        (np.array([1.0, 1.3, 1.75, 2.2, 3.6]),),  # beyond 1 cycle per pixel
        (np.array([-0.2, -0.7, -1.4, 0.5]),),  # negative: a cosine at -f is the one at f
        (np.array([[0.2, 0.8], [1.3, -0.7]]),),  # 2-D: a loop over np.ravel(f) loses the shape
        (
            np.random.default_rng(3).uniform(-3, 3, 7),
        ),  # any real: an answer rounded to a few decimals fails
        (np.float64(0.8),),  # one number (0-d): the answer is one number too
    ]


_ALIAS_SLIPS = (
    Mistake(
        "folded without wrapping",
        lambda f: np.minimum(f, 1 - f),
        (
            "you folded about the limit (1 - f above 1/2) but did not wrap first: f and f + 1 give the same "
            "samples too, so 1.3 shows as 0.3, not 1 - 1.3 = -0.3; take a = f % 1 first, then min(a, 1 - a)"
        ),
    ),
    Mistake(
        "1 - f everywhere",
        lambda f: 1 - f,
        (
            "you returned 1 - f for every frequency: below the limit, 1/2, a frequency is recorded as it is "
            "(0.2 shows as 0.2); only what lies above the limit folds back"
        ),
    ),
    Mistake(
        "wrapped without folding",
        lambda f: f % 1,
        (
            "you wrapped into [0, 1) (f % 1) but did not fold: f and 1 - f give the same samples, so 0.8 "
            "shows as 0.2; fold the upper half down, min(a, 1 - a) with a = f % 1"
        ),
    ),
    Mistake(
        "wrapped about the limit",
        lambda f: f % 0.5,
        (
            "you wrapped about the limit (f % 0.5): aliasing mirrors about it instead, so 0.55 shows as "
            "1 - 0.55 = 0.45, not 0.05; wrap by a whole cycle (f % 1), then fold, min(a, 1 - a)"
        ),
    ),
    Mistake(
        "the sign of fmod",
        lambda f: np.minimum(np.fmod(f, 1), 1 - np.fmod(f, 1)),
        (
            "np.fmod (and math.fmod) keep the sign of f, so -0.2 stays -0.2: use Python's % (np.mod), "
            "which returns a value in [0, 1) for any f, or fold abs(f)"
        ),
    ),
    Mistake(
        "no absolute value",
        lambda f: f - np.round(f),
        (
            "f - round(f) is the right distance to the nearest whole cycle per pixel, but signed: a cosine at "
            "-0.2 is the one at 0.2, so return its absolute value"
        ),
    ),
    Mistake(
        "clipped at the limit",
        lambda f: np.minimum(np.abs(f) % 1, 0.5),
        (
            "you clipped at the limit (min(a, 1/2)) instead of folding about it: a frequency above 1/2 is "
            "not stopped there but mirrored, so 0.8 shows as 1 - 0.8 = 0.2, not 0.5; take min(a, 1 - a)"
        ),
    ),
    Mistake(
        "the distance to the limit",
        lambda f: np.abs(np.asarray(f) % 1 - 0.5),
        (
            "you returned the distance to the limit, |a - 1/2| with a = f % 1, which is 1/2 minus the answer "
            "(0.2 gives 0.3): the answer is the distance to the nearest whole cycle, min(a, 1 - a)"
        ),
    ),
    Mistake(
        "radians",
        lambda f: 2 * np.pi * sensor.alias_frequency(f),
        (
            "you returned radians per pixel, 2 pi times the answer: the prompt counts cycles per pixel, as "
            "section 2 does (the limit is 1/2 cycle per pixel, pi radians)"
        ),
    ),
    Mistake(
        "the limit at 1",
        lambda f: np.minimum(f % 2, 2 - f % 2),
        (
            "you folded about 1 cycle per pixel: sampling once per pixel copies the spectrum every 1 cycle per "
            "pixel, so the limit is half of that, 1/2; wrap by 1 (f % 1), then fold, min(a, 1 - a)"
        ),
    ),
)
"""The folding slips: each row's answer from the frequencies ``f``."""


def _alias_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ": return one frequency per entry of f, as a numpy array of f's shape"
    (f,) = args
    if np.issubdtype(np.asarray(got).dtype, np.integer):
        return (
            f"your answer is integer ({np.asarray(got).dtype}): the frequencies are fractions of a cycle per "
            "pixel, from 0 to 1/2; drop the astype(int) (or int(...), np.round) and keep floats"
        )
    g = np.asarray(got, dtype=float)
    with np.errstate(invalid="ignore"):
        cause = first_mistake(_ALIAS_SLIPS, f, g, lambda a, b: np.allclose(a, b, atol=1e-9))
    if cause:
        return cause
    rounded = [k for k in (1, 2, 3) if np.allclose(g, np.round(expected, k), rtol=0, atol=1e-9)]
    if rounded:
        return (
            f"right, but rounded to {rounded[0]} decimals: the folded frequency is a real number (f = 1.2345 "
            f"shows 0.2345); return it unrounded"
        )
    if np.any(g < -1e-9) or np.any(g > 0.5 + 1e-9):
        return (
            "the samples can only show frequencies from 0 to 1/2 cycle per pixel: f + m and m - f (m whole) "
            "give the same samples, so wrap (f % 1) and fold (min(a, 1 - a))"
        )
    return "f and f + 1 give the same samples, and so do f and 1 - f: a = f % 1, then min(a, 1 - a)"


def _alias_exception_hint(exc: Exception, args: tuple) -> str:
    """The likely cause when the student's function raises: scalar code (``if f > 0.5``) on an array."""
    if isinstance(exc, ValueError) and "truth value of an array" in str(exc):
        return (
            "f is an array, and `if`/`while` on a comparison of an array (f > 0.5) has no one "
            "answer; use element-wise numpy (`%`, `np.abs`, `np.minimum`, `np.where`), or wrap your "
            "one-number function in np.vectorize"
        )
    return ""


def alias_frequency(f):
    """The frequency in [0, 1/2] that a cosine of f cycles per pixel shows once sampled at every pixel.

    Parameters
    ----------
    f : array_like
        Frequencies, cycles per pixel (any real numbers).

    Returns
    -------
    ndarray
        The frequencies the samples show, in [0, 1/2], f's shape.
    """
    wrapped = np.asarray(f, dtype=float) % 1.0  # f + 1 gives the same samples: into [0, 1)
    return np.minimum(
        wrapped, 1.0 - wrapped
    )  # and so does 1 - f: fold the upper half down about 1/2


register_exercise(
    Exercise(
        name="alias_frequency",
        lesson="03",
        reference=sensor.alias_frequency,
        cases=_alias_cases,
        compare=same_array(rtol=0, atol=1e-9),
        diagnose=_alias_diagnosis,
        wrong_variants=(
            (lambda f: 1 - np.asarray(f), "1 - f for every frequency"),
            (lambda f: np.minimum(f, 1 - np.asarray(f)), "did not wrap first"),
            (lambda f: np.asarray(f) % 1, "did not fold"),
            (lambda f: np.asarray(f) % 0.5, "aliasing mirrors about it"),
            (lambda f: np.minimum(np.abs(f) % 1, 0.5), "instead of folding about it"),
            (lambda f: np.abs(np.asarray(f) % 1 - 0.5), "the distance to the limit"),
            (lambda f: np.minimum(np.fmod(f, 1), 1 - np.fmod(f, 1)), "keep the sign of f"),
            (lambda f: np.asarray(f) - np.round(f), "its absolute value"),
            (lambda f: np.minimum(np.asarray(f) % 2, 2 - np.asarray(f) % 2), "the limit is half"),
            (lambda f: 2 * np.pi * sensor.alias_frequency(f), "radians per pixel"),
            (lambda f: np.abs(np.asarray(f) - np.floor(f)), "did not fold"),
            (lambda f: np.asarray(f)[:2], "one frequency per entry"),
            (lambda f: sensor.alias_frequency(f).tolist(), "wrap the values in np.array"),
            (lambda f: tuple(np.ravel(sensor.alias_frequency(f))), "wrap the values in np.array"),
            (lambda f: sensor.alias_frequency(f).astype(int), "your answer is integer"),
            (lambda f: np.array([min(x % 1, 1 - x % 1) for x in np.ravel(f)]), "f's shape"),
            (lambda f: np.round(sensor.alias_frequency(f), 2), "rounded to 2 decimals"),
        ),
        teaching=alias_frequency,
        exception_hint=_alias_exception_hint,
        ndarray_only=True,  # the prompt asks for a numpy array, as exercises 1 and 2 do
    )
)
