r"""Exercise for lesson 12, measure the world: the covariance of a pose from its Jacobian and residuals.

The pose's six parameters p are fitted to 2N pixel coordinates; near the minimum the residuals are
linear in p, and independent pixel noise of variance :math:`\sigma^2` gives
:math:`\Sigma_p = \hat\sigma^2 (J^\top J)^{-1}` with :math:`\hat\sigma^2 = \sum r^2 / (2N - 6)`.

References
----------
Hartley & Zisserman, Multiple View Geometry, 2nd ed., sections 5.1 and 5.2.2.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ._answers import same_array, shape_problem
from ._core import Exercise, Mistake, first_mistake, mistake_variant, register_exercise


def _cases():
    """(J, r): a 54-corner board's (108, 6) Jacobian and residuals, and a 5-point one (2N - 6 = 4)."""
    rng = np.random.default_rng(12)
    cases = []
    for n, scale in ((54, 400.0), (5, 900.0)):
        J = scale * rng.normal(size=(2 * n, 6))
        r = rng.normal(0, 0.14, 2 * n)
        cases.append((J, r))
    return cases


def pose_covariance(J, r):
    """Sigma_p = sigma^2 (J^T J)^-1 with sigma^2 = sum(r^2) / (2N - 6), 2N = len(r).

    Parameters
    ----------
    J : (2N, 6) ndarray
        The Jacobian of the 2N residuals with respect to the six pose parameters.
    r : (2N,) ndarray
        The residuals at the minimum, pixels.

    Returns
    -------
    (6, 6) ndarray
        The pose's covariance.
    """
    sigma2 = np.sum(r**2) / (len(r) - 6)  # len(r) = 2N numbers, 6 unknowns
    return sigma2 * np.linalg.inv(J.T @ J)


def _context(J, r):
    rss, m = float(np.sum(np.asarray(r) ** 2)), len(r)
    inv = np.linalg.inv(J.T @ J)
    return SimpleNamespace(rss=rss, m=m, inv=inv, JtJ=J.T @ J, s2=rss / (m - 6))


_MISTAKES = (
    Mistake(
        "divided by 2N",
        lambda c: c.rss / c.m * c.inv,
        "you divided the sum of squared residuals by 2N, the count of numbers: the fit used 6 of them "
        "(the pose), so the unbiased estimate is sigma^2 = sum(r^2) / (2N - 6).",
    ),
    Mistake(
        "divided by N",
        lambda c: c.rss / (c.m / 2) * c.inv,
        "you divided by N, the count of points: each point gives two numbers (u and v), and the pose took "
        "6, so sigma^2 = sum(r^2) / (2N - 6) with 2N = len(r).",
    ),
    Mistake(
        "len(r) taken as N",
        lambda c: c.rss / (2 * c.m - 6) * c.inv,
        "you took len(r) as N and divided by 2 len(r) - 6: r already holds the 2N coordinates, so the "
        "divisor is len(r) - 6.",
    ),
    Mistake(
        "no inverse",
        lambda c: c.s2 * c.JtJ,
        "you multiplied by J^T J instead of its inverse: more corners (a larger J^T J) must make the pose "
        "MORE certain, Sigma = sigma^2 (J^T J)^-1, np.linalg.inv(J.T @ J).",
    ),
    Mistake(
        "sigma not squared",
        lambda c: np.sqrt(c.s2) * c.inv,
        "you scaled by sigma where the formula has the variance sigma^2: Sigma = sigma^2 (J^T J)^-1 "
        "with sigma^2 = sum(r^2) / (2N - 6) (no square root).",
    ),
    Mistake(
        "no sigma",
        lambda c: c.inv,
        "you left out the noise: (J^T J)^-1 is the covariance for 1 px of noise; multiply by "
        "sigma^2 = sum(r^2) / (2N - 6) estimated from the residuals.",
    ),
)


def _diagnosis(args, got, expected) -> str:
    J, r = args
    g = np.asarray(got) if got is not None else None
    if g is not None and g.shape == (len(r), len(r)):
        return (
            f"you returned a ({len(r)}, {len(r)}) matrix: that is J J^T (or J Sigma J^T), one entry per "
            "residual pair; the pose's covariance is 6 x 6, sigma^2 (J^T J)^-1 with J.T @ J."
        )
    problem = shape_problem(got, expected)
    if problem:
        return problem
    hint = first_mistake(
        _MISTAKES,
        _context(*args),
        np.asarray(got, dtype=float),
        lambda a, b: np.allclose(a, b, rtol=1e-6, atol=0),
    )
    return hint or (
        "your covariance differs from sigma^2 (J^T J)^-1 with sigma^2 = sum(r^2) / (2N - 6), 2N = len(r): "
        "check each factor."
    )


def _variant(name):
    return mistake_variant(_MISTAKES, name, _context)


register_exercise(
    Exercise(
        name="pose_covariance",
        lesson="12",
        reference=pose_covariance,
        cases=_cases,
        compare=same_array(rtol=1e-7, atol=0),
        diagnose=_diagnosis,
        wrong_variants=(
            (_variant("divided by 2N"), "2N, the count"),
            (_variant("divided by N"), "count of points"),
            (_variant("len(r) taken as N"), "len(r) - 6"),
            (_variant("no inverse"), "instead of its inverse"),
            (_variant("sigma not squared"), "variance"),
            (_variant("no sigma"), "left out the noise"),
            ((lambda J, r: np.sum(r**2) / (len(r) - 6) * J @ J.T), "J J^T"),
        ),
        teaching=pose_covariance,
        ndarray_only=True,
    )
)
