"""Exercise 7 of lesson 11: the bad-pixel rate against ground truth (`bad_pixel_rate`)."""

from __future__ import annotations

import numpy as np

from ... import disparity
from .._core import Exercise, register_exercise

# --------------------------------------------------------------------------- the bad-pixel rate


def _bad_pixel_cases():
    rng = np.random.default_rng(29)
    truth = rng.uniform(8, 60, (40, 50))
    d = truth + rng.normal(0, 0.6, truth.shape)
    gross = rng.random(truth.shape) < 0.1  # mismatches, too near and too far
    d[gross] += rng.choice([-9.0, 7.0], gross.sum())
    d[:, :6] = np.nan  # no match: the search range's blind band
    truth[rng.random(truth.shape) < 0.07] = np.nan  # no ground truth
    d[5, 10], truth[5, 10] = 21.0, 20.0  # an error of exactly the threshold is not bad
    small = (
        np.array([[10.0, 12.5, np.nan, 30.0], [5.0, 7.5, 9.0, 40.0]]),
        np.array([[10.2, 11.0, 9.0, np.nan], [6.5, 7.0, 11.5, 38.0]]),
    )
    return [(d, truth, 1.0), (d, truth, 2.0), (*small, 1.0)]


def _bad_pixel_diagnosis(args, got, expected) -> str:
    d, truth, tau = (np.asarray(a, dtype=float) for a in args)
    try:
        g = float(got)
    except (TypeError, ValueError):
        return f"return one number, the fraction of bad pixels (a float in [0, 1]); got {type(got).__name__}"
    scored = np.isfinite(d) & np.isfinite(truth)
    with np.errstate(invalid="ignore"):
        err = d - truth
        over_all = np.mean(np.abs(err) > tau)
        known = np.isfinite(truth)
        unmatched_bad = np.sum(known & ((np.abs(err) > tau) | ~np.isfinite(d))) / known.sum()
    if np.isclose(g, 100 * expected):
        return "your rate is in percent: return the fraction in [0, 1] (0.07, not 7)"
    if np.isclose(g, np.mean(err[scored] > tau)):
        return (
            "you counted only the errors d - d_true > threshold: a match too near is as bad as one too "
            "far; use the absolute error |d - d_true|"
        )
    if np.isclose(g, np.mean(np.abs(err[scored]) >= tau)):
        return "an error of exactly the threshold is not bad: the rule is |d - d_true| > threshold, strictly"
    if np.isclose(g, over_all):
        return (
            "you averaged over every pixel: NaN > threshold is False, so the pixels without a match or "
            "without a true disparity counted as good. Score only the pixels where both are finite"
        )
    if np.isclose(g, np.mean(np.abs(np.nan_to_num(d) - np.nan_to_num(truth)) > tau)):
        return (
            "you set the NaNs to 0 (np.nan_to_num) before scoring: each hole became a disparity of 0 "
            "and counted as a wildly bad match. NaN means no data: score only the pixels where both d "
            "and d_true are finite"
        )
    n_bad = np.sum(np.abs(err[scored]) > tau)
    truth_only = n_bad / known.sum()
    if np.isclose(g, truth_only):
        return (
            "you divided by every pixel with a true disparity, so the pixels without a match counted as "
            "good: that is Middlebury's bad% (section 6), which reports the holes separately. This exercise "
            "asks for the rate over the pixels where both d and d_true are finite"
        )
    matched = np.isfinite(d)
    if np.isclose(g, np.mean(np.abs(err[matched]) > tau)):
        return (
            "you masked only the matcher's NaNs (isfinite(d)): the pixels without a true disparity stayed "
            "in and counted as good (NaN > threshold is False). Score the pixels where both d and d_true "
            "are finite"
        )
    if np.isclose(g, np.mean(np.abs(err[scored]) / np.abs(truth[scored]) > tau)):
        return (
            "you compared the relative error |d - d_true| / d_true with the threshold: the threshold is an "
            "absolute error in pixels, |d - d_true| > threshold"
        )
    if np.isclose(g, 1 - expected):
        return "you returned the fraction of GOOD pixels (|d - d_true| <= threshold): the bad-pixel rate is 1 minus that"
    if np.isclose(g, n_bad):
        return f"you returned the count of bad pixels ({n_bad}): divide by the number of scored pixels for a fraction"
    if np.isclose(g, np.mean((err[scored]) ** 2 > tau)):
        return "you compared the squared error with the threshold: the rule is |d - d_true| > threshold (pixels)"
    if np.isclose(g, unmatched_bad):
        return (
            "you counted the pixels without a match as bad: this rate is over the matched pixels that "
            "have a true disparity (the fraction matched is reported beside it)"
        )
    return (
        f"expected {expected:.4g}, got {g:.4g}: the fraction, among the pixels where both d and d_true "
        "are finite, whose |d - d_true| exceeds the threshold"
    )


def bad_pixel_rate(d, d_true, threshold):
    """Score the pixels with both a match and a truth; bad when the absolute error exceeds the threshold.

    Parameters
    ----------
    d, d_true : (H, W) array_like
        The matcher's and the true disparity, pixels; NaN where there is none.
    threshold : float
        The error, pixels, above which a pixel is bad.

    Returns
    -------
    float
        The fraction of scored pixels with ``|d - d_true| > threshold``.
    """
    d, d_true = np.asarray(d, dtype=float), np.asarray(d_true, dtype=float)
    scored = np.isfinite(d) & np.isfinite(d_true)
    return np.mean(np.abs(d[scored] - d_true[scored]) > threshold)


register_exercise(
    Exercise(
        name="bad_pixel_rate",
        lesson="11",
        reference=disparity.bad_pixel_rate,
        cases=_bad_pixel_cases,
        compare=lambda got, expected: np.ndim(got) == 0 and np.isclose(float(got), expected),
        diagnose=_bad_pixel_diagnosis,
        wrong_variants=(
            (lambda d, t, tau: 100 * disparity.bad_pixel_rate(d, t, tau), "percent"),
            (
                lambda d, t, tau: np.nanmean(np.where(np.isfinite(d - t), d - t > tau, np.nan)),
                "absolute error",
            ),
            (
                lambda d, t, tau: np.mean(np.abs(np.asarray(d) - t) > tau),
                "NaN > threshold is False",
            ),
            (
                lambda d, t, tau: np.mean(np.abs(d - t)[np.isfinite(d - t)] >= tau),
                "exactly the threshold",
            ),
            (
                lambda d, t, tau: (
                    np.sum(np.isfinite(t) & ~(np.abs(d - t) <= tau)) / np.isfinite(t).sum()
                ),
                "without a match as bad",
            ),
            (
                lambda d, t, tau: np.sum(np.abs(d - t) > tau) / np.isfinite(t).sum(),
                "Middlebury's bad%",
            ),
            (
                lambda d, t, tau: np.mean(np.abs(d - t)[np.isfinite(d)] > tau),
                "masked only the matcher's NaNs",
            ),
            (
                lambda d, t, tau: np.mean((np.abs(d - t) / t)[np.isfinite(d - t)] > tau),
                "relative error",
            ),
            (lambda d, t, tau: 1 - disparity.bad_pixel_rate(d, t, tau), "GOOD pixels"),
            (
                lambda d, t, tau: np.mean(np.abs(np.nan_to_num(d) - np.nan_to_num(t)) > tau),
                "np.nan_to_num",
            ),
            (
                lambda d, t, tau: float(np.sum(np.abs(d - t)[np.isfinite(d - t)] > tau)),
                "count of bad pixels",
            ),
        ),
        teaching=bad_pixel_rate,
    )
)
