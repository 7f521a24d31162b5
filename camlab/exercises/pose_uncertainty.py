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

from ._answers import diagonal_only_hint, same_array, shape_problem
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
    r = np.asarray(r, dtype=float)
    return SimpleNamespace(
        rss=rss,
        m=m,
        inv=inv,
        JtJ=J.T @ J,
        s2=rss / (m - 6),
        var=np.var(r),
        var6=np.var(r, ddof=6),
        diag_inv=np.diag(1 / np.diag(J.T @ J)),
        mean_abs=float(np.mean(np.abs(r))),
        sum_abs=float(np.sum(np.abs(r))),
    )


def _root(x):
    """Elementwise square root, NaN where x < 0, without the RuntimeWarning (a student's slip)."""
    with np.errstate(invalid="ignore"):
        return np.sqrt(x)


_MEAN_HINT = (
    "np.var / np.std subtract the mean of r first: the residuals at the minimum ARE the noise (its mean "
    "is 0 by assumption), so sigma^2 = np.sum(r**2) / (len(r) - 6), with no mean taken out"
)


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
        "per-corner variance",
        lambda c: 2 * c.s2 * c.inv,
        "your covariance is exactly twice the answer: sum(r^2) / (N - 3) (or 2 sum(r^2) / (2N - 6)) is the "
        "noise per CORNER, u and v together; the formula needs the variance per pixel COORDINATE, "
        "sigma^2 = sum(r^2) / (2N - 6) with 2N = len(r) (section 1: 0.188 px per corner, 0.137 px per coordinate).",
    ),
    Mistake(
        "halved",
        lambda c: c.s2 / 2 * c.inv,
        "your covariance is exactly half the answer: you divided sum(r^2) by 2 (2N - 6), as if len(r) were "
        "N and each point gave two more numbers, or took the mean of u's and v's variances as a sum over both; "
        "r holds the 2N coordinates, so sigma^2 = np.sum(r**2) / (len(r) - 6).",
    ),
    Mistake(
        "divided by 2N - 7",
        lambda c: c.rss / (c.m - 7) * c.inv,
        "you divided by 2N - 7: the pose has 6 unknowns (3 for the rotation, 3 for the translation), "
        "so sigma^2 = sum(r^2) / (2N - 6), 2N = len(r).",
    ),
    Mistake(
        "square of the sum",
        lambda c: c.sum_abs**2 / (c.m - 6) * c.inv,
        "you squared the sum of the residuals' sizes: square each residual first, then add, "
        "sigma^2 = np.sum(r**2) / (len(r) - 6).",
    ),
    Mistake(
        "np.var",
        lambda c: c.var * c.inv,
        _MEAN_HINT + "; np.var(r) also divides by 2N where the pose's 6 unknowns leave 2N - 6.",
    ),
    Mistake(
        "np.var ddof=6", lambda c: c.var6 * c.inv, _MEAN_HINT + " (ddof=6 fixes only the divisor)."
    ),
    Mistake(
        "divided by N - 6",
        lambda c: c.rss / (c.m / 2 - 6) * c.inv,
        "you divided by N - 6 (points minus unknowns): the fit has 2N numbers (u and v of each point), "
        "so the divisor is 2N - 6 = len(r) - 6.",
    ),
    Mistake(
        "elementwise reciprocal",
        lambda c: c.s2 / c.JtJ,
        "you took 1 / (J^T J) entry by entry: the inverse of a matrix is np.linalg.inv(J.T @ J) "
        "(or np.linalg.solve(J.T @ J, np.eye(6))), not the reciprocal of each entry.",
    ),
    Mistake(
        "divided by the inverse",
        lambda c: c.s2 / c.inv,
        "you divided by (J^T J)^-1 entry by entry: multiply by it, sigma^2 * np.linalg.inv(J.T @ J).",
    ),
    Mistake(
        "square root of Sigma",
        lambda c: _root(c.s2 * c.inv),
        "you took an elementwise square root (np.sqrt or ** 0.5) of the covariance: Sigma = sigma^2 "
        "(J^T J)^-1 is a variance, with no root; off-diagonal entries are negative, hence the NaN.",
    ),
    Mistake(
        "square root of the inverse",
        lambda c: c.s2 * _root(c.inv),
        "you took an elementwise square root (** 0.5) of (J^T J)^-1: Sigma = sigma^2 (J^T J)^-1 needs the "
        "matrix inverse itself, np.linalg.inv(J.T @ J); off-diagonal entries are negative, hence the NaN.",
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
        "inverse of the diagonal",
        lambda c: c.s2 * c.diag_inv,
        "you inverted only the diagonal of J^T J (1 / its diagonal entries): the pose's six parameters "
        "are correlated, so J^T J has off-diagonal terms and its inverse is np.linalg.inv(J.T @ J), "
        "whose diagonal is larger than 1 / diag(J^T J).",
    ),
    Mistake(
        "sigma from mean |r|",
        lambda c: c.mean_abs**2 * c.inv,
        "you took sigma as the mean of |r|: for Gaussian noise that is sigma sqrt(2 / pi), about 0.8 "
        "sigma. Use the root of the mean square, sigma^2 = sum(r^2) / (2N - 6).",
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
    hint = diagonal_only_hint(got, expected, "the correlations between the pose's parameters")
    if hint:
        return hint
    hint = None
    if g is not None and g.shape == np.shape(expected) and g.dtype.kind in "fiu":
        hint = first_mistake(  # before shape_problem, whose NaN hint would hide a square root
            _MISTAKES,
            _context(*args),
            g.astype(float),
            lambda a, b: np.allclose(a, b, rtol=1e-6, atol=0, equal_nan=True),
        )
    return (
        hint
        or shape_problem(got, expected)
        or _scale_hint(g, expected)
        or (
            "your covariance differs from sigma^2 (J^T J)^-1 with sigma^2 = sum(r^2) / (2N - 6), 2N = len(r): "
            "check each factor."
        )
    )


def _scale_hint(g, expected) -> str | None:
    """A covariance that is a constant multiple of the answer: (J^T J)^-1 is right, sigma^2 is not."""
    k = float(np.sum(g * expected) / np.sum(expected * expected))
    if np.all(np.isfinite(g)) and np.allclose(g, k * expected, rtol=1e-6, atol=0):
        if abs(k - 1) < 1e-3:
            return (
                f"nearly right: your covariance is (1 {k - 1:+.1e}) times the answer (the check allows 1e-7 "
                "relative). (J^T J)^-1 is right; compute sigma^2 = np.sum(r**2) / (len(r) - 6) in float64, "
                "without rounding."
            )
        return (
            f"your covariance is {k:.6g} times the answer: the matrix (J^T J)^-1 is right, its factor sigma^2 "
            "is not; sigma^2 = np.sum(r**2) / (len(r) - 6), the residuals squared, summed, divided by 2N - 6."
        )
    return None


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
            ((lambda J, r: np.var(r) * np.linalg.inv(J.T @ J)), "subtract the mean"),
            ((lambda J, r: np.std(r) ** 2 * np.linalg.inv(J.T @ J)), "subtract the mean"),
            ((lambda J, r: np.var(r, ddof=6) * np.linalg.inv(J.T @ J)), "ddof=6"),
            (_variant("divided by N - 6"), "N - 6"),
            (_variant("divided by 2N - 7"), "2N - 7"),
            (_variant("per-corner variance"), "per CORNER"),
            (_variant("halved"), "exactly half"),
            ((lambda J, r: 1.5 * pose_covariance(J, r)), "1.5 times the answer"),
            ((lambda J, r: np.sum(r**2) / (len(r) / 2 - 3) * np.linalg.inv(J.T @ J)), "per CORNER"),
            (_variant("square of the sum"), "square each residual first"),
            ((lambda J, r: np.sum(r**2) / (len(r) - 6) / (J.T @ J)), "entry by entry"),
            (_variant("divided by the inverse"), "multiply by it"),
            ((lambda J, r: _root(pose_covariance(J, r))), "elementwise square root"),
            (_variant("square root of the inverse"), "elementwise square root"),
            (_variant("sigma not squared"), "variance"),
            (_variant("no sigma"), "left out the noise"),
            (_variant("inverse of the diagonal"), "only the diagonal"),
            (_variant("sigma from mean |r|"), "mean of |r|"),
            ((lambda J, r: np.sum(r**2) / (len(r) - 6) * J @ J.T), "J J^T"),
            ((lambda J, r: np.diag(pose_covariance(J, r))), "the variances alone"),
            ((lambda J, r: np.sqrt(np.diag(pose_covariance(J, r)))), "one-sigmas"),
        ),
        teaching=pose_covariance,
        ndarray_only=True,
        solution_note=(
            "# camlab: solve_pnp stores this covariance, sigma-hat from the residuals, as pose.covariance;\n"
            "# camlab.measurement.pose_covariance(K, R, t, object_points, sigma_px) gives sigma^2 (J^T J)^-1 "
            "for a\n# planned pose and a chosen noise (section 2's demo)."
        ),
    )
)
