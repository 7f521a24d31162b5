"""Exercise 3 of lesson 07: how many RANSAC samples (`ransac_samples`)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from ...robust import required_iterations
from .._core import Exercise, Mistake, register_exercise
from .._numbers import is_number as _is_number
from .._numbers import not_one_number, same_number


def _ransac_samples_cases():
    # (confidence p, inlier ratio q); each k has a fraction part that tells ceil from round and floor,
    # and no q is 0.5, where q^4 and (1 - q)^4 are one number and two slips one answer. The last
    # tells log(p) (13) from swapped p and q (1), which give k = 1 on all the others. The last has a
    # whole k: q^4 = 81/256 and 1 - p = (175/256)^2, so k = 2 exactly in every form of the formula
    # (log, log1p, log10), where int(k) + 1 asks for 3
    return [
        (0.99, 0.6),
        (0.95, 0.8),
        (0.995, 0.3),
        (0.999, 0.9),
        (0.9, 0.3),
        # a low p and a high q: the upside-down ratio gives 10, log(p) / log(q^4) 14 and p / 100 gives 1,
        # which all give k = 1 on the inputs above
        (0.2, 0.97),
        (0.5326995849609375, 0.75),
    ]


def _samples_needed(p, q):
    """The whole number of 4-pair samples RANSAC needs: ceil(log(1 - p) / log(1 - q^4))."""
    return int(np.ceil(required_iterations(q, p, 4)))


def _k(numerator, denominator):
    with np.errstate(divide="ignore", invalid="ignore"):
        return numerator / denominator


def _samples_context(p, q, g):
    """The numbers the slips below give on (p, q), and the student's answer g."""
    ln = np.log
    return SimpleNamespace(
        p=p,
        q=q,
        g=g,
        exact=_k(ln(1 - p), ln(1 - q**4)),
        ways=lambda k: {np.ceil(k), np.round(k), np.floor(k), k},
    )


def _is_any(g, values) -> bool:
    return any(np.isfinite(v) and np.isclose(g, v, rtol=1e-9) for v in values)


_SAMPLES_MISTAKES = (
    Mistake(
        "p in per cent",
        # p / 100 rounds k up to 1 on most inputs, as many slips do: 1 alone does not name it (_per_cent_k)
        lambda s: s.g != 1 and _is_any(s.g, s.ways(_k(np.log(1 - s.p / 100), np.log(1 - s.q**4)))),
        "you divided p by 100, as if it came in per cent: p is already a probability in (0, 1) "
        "(0.99 means 99 %), so use it as it is: k = log(1 - p) / log(1 - q^4).",
    ),
    Mistake(
        "p and q in per cent",
        lambda s: _is_any(s.g, s.ways(_k(np.log(1 - s.p / 100), np.log(1 - (s.q / 100) ** 4)))),
        "you divided both p and the inlier ratio by 100, as if they came in per cent: both are "
        "already probabilities in (0, 1) (0.99 means 99 %), so use them as they are: "
        "k = log(1 - p) / log(1 - q^4).",
    ),
    Mistake(
        "q in per cent",
        lambda s: _is_any(s.g, s.ways(_k(np.log(1 - s.p), np.log(1 - (s.q / 100) ** 4)))),
        "you divided the inlier ratio by 100, as if it came in per cent: it is already a fraction in "
        "(0, 1) (0.6 means 60 % inliers), so (q / 100)^4 makes a clean sample millions of times too "
        "rare. Use it as it is: k = log(1 - p) / log(1 - q^4).",
    ),
    Mistake(
        "expected number of trials",
        lambda s: _is_any(s.g, s.ways(1 / s.q**4)) and not _is_any(s.g, {np.ceil(s.exact)}),
        "you returned 1 / q^4, the *expected* number of samples until the first clean one. The "
        "question asks for the k that makes at least one clean sample likely with probability p: "
        "1 - p = (1 - q^4)^k, so k = log(1 - p) / log(1 - q^4), rounded up.",
    ),
    Mistake(
        "negative k",
        lambda s: s.g < 0,
        "your k is negative, but both logs are negative (1 - p and 1 - q^4 lie between 0 and 1), so "
        "their ratio is positive: check for a stray minus sign, or a log missing from one side. "
        "k = log(1 - p) / log(1 - q^4).",
    ),
    Mistake(
        "not rounded up",
        lambda s: np.isclose(s.g, s.exact, rtol=1e-9) and not float(s.g).is_integer(),
        "you returned k itself, a fraction of a sample. RANSAC draws whole samples, and k is the "
        "fewest that reach the confidence p, so round *up*: int(np.ceil(k)).",
    ),
    Mistake(
        "rounded down or to nearest",
        lambda s: _is_any(s.g, {np.round(s.exact), np.floor(s.exact)}) and s.g != np.ceil(s.exact),
        "you rounded down (int() or np.floor) or to the nearest whole number: one sample fewer than k "
        "leaves the chance of a clean sample below p. Round up: int(np.ceil(k)).",
    ),
    Mistake(
        "int(k) + 1",
        # also true for a right answer on a fractional k: so the slip survives narrowing by those inputs
        lambda s: s.g == np.floor(s.exact) + 1,
        "you returned int(k) + 1 (or np.floor(k) + 1), or looped on a strict inequality (adding "
        "samples while (1 - q^4)^k >= 1 - p, i.e. until it is strictly below): both ask for one "
        "more than k when k is a whole number, as here. The fewest samples that reach p are the "
        "first k with (1 - q^4)^k <= 1 - p: int(np.ceil(k)).",
    ),
    Mistake(
        "ceil(k) + 1",
        lambda s: s.g == np.ceil(s.exact) + 1,
        "you returned one sample more than int(np.ceil(k)) (a + 1 after rounding up, or k counted from "
        "0): k samples already reach the confidence p, since (1 - q^4)^k <= 1 - p. Return int(np.ceil(k)).",
    ),
    Mistake(
        "q instead of q^4",
        lambda s: _is_any(s.g, s.ways(_k(np.log(1 - s.p), np.log(1 - s.q)))),
        "you used q where the chance of a clean *sample* belongs: a homography's sample has 4 pairs, "
        "all of which must be inliers, which happens with probability q^4 (independent draws). "
        "k = log(1 - p) / log(1 - q**4).",
    ),
    Mistake(
        "wrong sample size",
        lambda s: any(
            _is_any(s.g, s.ways(_k(np.log(1 - s.p), np.log(1 - s.q**m)))) for m in (2, 3, 5, 8)
        ),
        "your sample size is not 4: a homography has 8 degrees of freedom and each pair gives two "
        "equations, so a minimal sample is 4 pairs, clean with probability q^4.",
    ),
    Mistake(
        "outlier ratio for q",
        lambda s: _is_any(s.g, s.ways(_k(np.log(1 - s.p), np.log(1 - (1 - s.q) ** 4)))),
        "you used (1 - q)^4: q is the *inlier* ratio here (section 7 writes the outlier fraction "
        "epsilon = 1 - q), so a sample is clean with probability q^4.",
    ),
    Mistake(
        "p for 1 - p",
        lambda s: _is_any(s.g, s.ways(_k(np.log(s.p), np.log(1 - s.q**4)))),
        "you took log(p) in the numerator: 1 - p is the chance that *every* one of the k samples is "
        "contaminated, (1 - q^4)^k = 1 - p, so k = log(1 - p) / log(1 - q^4).",
    ),
    Mistake(
        "p for 1 - p and q^4 for 1 - q^4",
        lambda s: _is_any(s.g, s.ways(_k(np.log(s.p), np.log(s.q**4)))),
        "you took log(p) / log(q^4): that sets the chance that *every* sample is clean to p. RANSAC "
        "needs only one clean sample, so it is the chance that every sample is *contaminated*, "
        "(1 - q^4)^k, that must be 1 - p: k = log(1 - p) / log(1 - q^4).",
    ),
    Mistake(
        "ratio upside down",
        lambda s: _is_any(s.g, s.ways(_k(np.log(1 - s.q**4), np.log(1 - s.p)))),
        "your ratio is upside down: log(1 - q^4) / log(1 - p) is 1 / k, below 1 whenever more than one "
        "sample is needed, so it rounds up to 1. From (1 - q^4)^k = 1 - p, take logs: "
        "k log(1 - q^4) = log(1 - p), so k = log(1 - p) / log(1 - q^4).",
    ),
    Mistake(
        "log((1 - q)^4)",
        lambda s: _is_any(s.g, s.ways(_k(np.log(1 - s.p), np.log((1 - s.q) ** 4)))),
        "your denominator is log((1 - q)^4): the 1 - belongs outside the power. A sample is clean with "
        "probability q^4, so it fails with probability 1 - q^4: k = log(1 - p) / log(1 - q**4).",
    ),
    Mistake(
        "q^4 for 1 - q^4",
        lambda s: _is_any(s.g, s.ways(_k(np.log(1 - s.p), np.log(s.q**4)))),
        "your denominator is log(q^4), the log of the chance that a sample is clean; the k samples must "
        "all *fail* for RANSAC to fail, each with probability 1 - q^4: k = log(1 - p) / log(1 - q^4).",
    ),
    Mistake(
        "mixed log bases",
        lambda s: _is_any(s.g, s.ways(s.exact * np.log(10)) | s.ways(s.exact / np.log(10))),
        "your two logarithms have different bases (np.log10 in one, np.log in the other): the ratio "
        "log(1 - p) / log(1 - q^4) is the same in any base, but only if both use the same one.",
    ),
    Mistake(
        "p and q swapped",
        lambda s: _is_any(s.g, s.ways(_k(np.log(1 - s.q), np.log(1 - s.p**4)))),
        "you swapped p and inlier_ratio: the function is called as ransac_samples(p, inlier_ratio), the confidence first.",
    ),
    Mistake(
        "percent",
        lambda s: _is_any(s.g, s.ways(s.exact * 100) | s.ways(s.exact / 100)),
        "your answer is off by a factor 100: p and q are fractions (0.99, not 99 %).",
    ),
)
"""The slips in k = ceil(log(1 - p) / log(1 - q^4)), in the order they are tested (rows give a bool)."""


def _narrowed(tied, args, run) -> list:
    """The slips among ``tied`` that also give the student's answers on the other test inputs."""
    for p, q in _ransac_samples_cases():
        if (p, q) == tuple(args):
            continue
        try:
            g = float(run(p, q))
        except Exception:  # the student's function fails there: that input tells nothing
            continue
        tied = [m for m in tied if m.answer(_samples_context(p, q, g))]
    return tied


_NOT_FINITE = (
    "your k is NaN or infinite: a log of a number <= 0. 1 - p or 1 - q^4 fell to 0 or below. Check the "
    "power, q**4 (q * 4 is 2.4 for q = 0.6, and 1 - 2.4 is negative), and that p and q are probabilities "
    "in (0, 1), not per cent. k = ceil(log(1 - p) / log(1 - q^4))."
)
_ONE_SAMPLE = (
    "your function returns 1 sample where {expected} are needed: its k is below 1 before rounding up. "
    "That happens when the denominator's log is far larger than the numerator's: check the power, "
    "1 - q**4 (not 1 - q * 4, which is negative or 0 for q >= 0.25), that the ratio is not upside "
    "down, and that p is used as it is. k = ceil(log(1 - p) / log(1 - q^4))."
)


def _per_cent_k(run) -> bool:
    """True if the student's k is p / 100's on a test input where that k is not 1."""
    for p, q in _ransac_samples_cases():
        k = int(np.ceil(_k(np.log(1 - p / 100), np.log(1 - q**4))))
        if k != 1:
            try:
                if float(run(p, q)) == k:
                    return True
            except Exception:  # the student's function fails there: that input tells nothing
                continue
    return False


def _samples_diagnosis(args, got, expected, run=None) -> str:
    p, q = args
    if isinstance(got, (float, np.floating)) and not np.isfinite(got):
        return _NOT_FINITE
    if not _is_number(got):
        return not_one_number(got, "the whole number of samples k")
    context = _samples_context(p, q, float(got))
    tied = [m for m in _SAMPLES_MISTAKES if m.answer(context)]
    if run is not None:  # a slip must give the student's answers on the other inputs too
        narrowed = _narrowed(tied, args, run)
        if not narrowed and got == 1:  # no listed slip gives 1 everywhere the student gives 1
            return (
                _SAMPLES_MISTAKES[0].hint
                if _per_cent_k(run)
                else _ONE_SAMPLE.format(expected=expected)
            )
        tied = narrowed or tied
    causes = [m.hint for m in tied]
    if len(causes) > 1:  # small k: several slips round up to the same whole number
        return f"{len(causes)} different slips give this number here; either " + " Or ".join(causes)
    return (
        causes[0]
        if causes
        else (
            "a sample of 4 pairs is clean with probability q^4; k samples all fail with probability "
            "(1 - q^4)^k, which must be at most 1 - p: k = ceil(log(1 - p) / log(1 - q^4))."
        )
    )


def _samples_exception_hint(exc, args) -> str:
    """The cause of a NaN k: the log of a negative number, most often p or q taken as per cent."""
    if isinstance(exc, ValueError) and "NaN" in str(exc):
        return (
            "k came out NaN, the log of a negative number: 1 - p or 1 - q^4 fell below 0. If you "
            "multiplied p (or q) by 100 to turn it into per cent, don't: both are probabilities in "
            "(0, 1), 0.99 means 99 %. k = log(1 - p) / log(1 - q^4)."
        )
    if isinstance(exc, ValueError) and "math domain error" in str(exc):
        return (
            "math.log got a number <= 0 ('math domain error'): 1 - p or 1 - q^4 fell to 0 or below. "
            "Check the power, q**4 (q * 4 is 2.4 for q = 0.6), and that p and q are probabilities in "
            "(0, 1), not per cent. k = log(1 - p) / log(1 - q^4)."
        )
    return ""


def _samples_note(run) -> str:
    """Self-check 4, answered with the student's own function once it passes."""
    k40, k70 = (
        int(run(0.995, 0.6)),
        int(run(0.995, 0.3)),
    )  # an integral float prints as a whole number
    return (
        f"With p = 0.995: {k40} samples at 40 % outliers (q = 0.6), {k70} at 70 % (q = 0.3), "
        f"{k70 / k40:.0f} times more (section 7's cell prints the same)."
    )


def ransac_samples(p, inlier_ratio):
    """The whole number of 4-pair samples that give one clean sample with probability p.

    A sample of 4 pairs is clean (all inliers) with probability q^4; k samples all fail with
    probability (1 - q^4)^k. Setting that to 1 - p and solving for k gives
    k = log(1 - p) / log(1 - q^4), rounded up to whole samples.

    Parameters
    ----------
    p : float
        The confidence, in (0, 1): the probability of at least one clean sample.
    inlier_ratio : float
        q, the fraction of pairs that are inliers, in (0, 1): 1 - epsilon in section 7.

    Returns
    -------
    int
        k, rounded up.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 4.7.1 (how many samples?).
    """
    q = inlier_ratio
    k = np.log(1 - p) / np.log(1 - q**4)
    return int(np.ceil(k))


register_exercise(
    Exercise(
        name="ransac_samples",
        lesson="07",
        reference=_samples_needed,
        cases=_ransac_samples_cases,
        compare=same_number(rtol=1e-9),
        diagnose=_samples_diagnosis,
        diagnosis_runs=True,
        exception_hint=_samples_exception_hint,
        success_note=_samples_note,
        wrong_variants=(
            (lambda p, q: np.log(1 - p) / np.log(1 - q**4), "a fraction of a sample"),
            (
                lambda p, q: int(np.ceil(np.log(1 - p) / np.log(1 - (q / 100) ** 4))),
                "divided the inlier ratio by 100",
            ),
            (lambda p, q: int(np.log(1 - p) / np.log(1 - q**4)) + 1, "int(k) + 1"),
            (
                lambda p, q: next(k for k in range(10**6) if (1 - q**4) ** k < 1 - p),
                "strict inequality",
            ),
            (lambda p, q: math.ceil(math.log(1 - p) / math.log(1 - q * 4)), "math domain"),
            (lambda p, q: int(np.ceil(np.log(1 - p) / np.log(1 - q**4))) + 1, "one sample more"),
            (lambda p, q: round(np.log(1 - p) / np.log(1 - q**4)), "rounded down"),
            (lambda p, q: int(np.log(1 - p) / np.log(1 - q**4)), "rounded down"),
            (lambda p, q: int(np.ceil(np.log(1 - p) / np.log(1 - q))), "probability q^4"),
            (lambda p, q: int(np.ceil(np.log(1 - p) / np.log(1 - q**2))), "sample size is not 4"),
            (
                lambda p, q: int(np.ceil(np.log(1 - p) / np.log(1 - (1 - q) ** 4))),
                "epsilon = 1 - q",
            ),
            (lambda p, q: int(np.ceil(np.log(p) / np.log(1 - q**4))), "log(p)"),
            (lambda p, q: int(np.ceil(np.log(1 - p) / np.log(q**4))), "log(q^4)"),
            (lambda p, q: int(np.ceil(np.log(1 - q**4) / np.log(1 - p))), "upside down"),
            (lambda p, q: int(np.ceil(np.log(1 - p) / np.log((1 - q) ** 4))), "log((1 - q)^4)"),
            (lambda p, q: int(np.ceil(np.log10(1 - p) / np.log(1 - q**4))), "different bases"),
            (
                lambda p, q: int(np.ceil(np.log(1 - q) / np.log(1 - p**4))),
                "swapped p and inlier_ratio",
            ),
            (lambda p, q: int(np.ceil(np.log(p) / np.log(q**4))), "every sample is *contaminated*"),
            (lambda p, q: int(np.ceil(np.log(1 - p / 100) / np.log(1 - q**4))), "per cent"),
            (lambda p, q: int(np.ceil(np.log(1 - 100 * p) / np.log(1 - q**4))), "per cent"),
            (lambda p, q: [int(np.ceil(np.log(1 - p) / np.log(1 - q**4)))], "return one number"),
            (lambda p, q: int(np.ceil(np.log(1 - p) / (1 - q**4))), "your k is negative"),
        ),
        teaching=ransac_samples,
    )
)
