"""Exercises for lesson 08, camera calibration: the rms a correct calibration reaches."""

from __future__ import annotations

import numpy as np

from ._answers import same_array, shape_problem, type_problem
from ._core import Exercise, register_exercise


def _counts(n_views, corners_per_view, n_camera):
    """N, the corners over all views, and p, the unknowns: the camera's and 6 per view's pose."""
    return n_views * corners_per_view, n_camera + 6 * n_views


def _rms(sigma, n, p):
    with np.errstate(invalid="ignore"):
        return float(np.sqrt(2.0) * sigma * np.sqrt(1.0 - p / (2.0 * n)))


def _rms_reference(sigma, n_views, corners_per_view, n_camera):
    return _rms(sigma, *_counts(n_views, corners_per_view, n_camera))


def _rms_cases():
    # the rendered set of section 5, three views, a small board, two views of a tiny one (little redundancy)
    return [(0.0346, 16, 54, 9), (0.3, 3, 54, 9), (1.0, 4, 25, 4), (0.5, 2, 12, 8)]


def _rms_form_problem(args, got, expected) -> str | None:
    """Why ``got`` is not one finite number (None, a string, an array), or None."""
    if got is None or type_problem(got, expected):
        return shape_problem(got, expected)
    g = np.asarray(got, dtype=float)
    if g.shape != ():
        return (
            f"expected one number, got an array of shape {g.shape}: return a float, e.g. float(x) "
            "or x.item() (np.array([x]) or np.sqrt of a length-1 array keeps the array)"
        )
    if not np.isfinite(g):
        n, p = _counts(*args[1:])
        return (
            "NaN: 1 - p / (2N) came out negative, so your N is too small: N counts corners over all views, "
            f"n_views x corners_per_view = {n}, against p = {p} unknowns"
        )
    return None


def _count_slips(sigma, n_views, corners, n_camera):
    """(value, cause) for the slips in counting N and p."""
    n, p = _counts(n_views, corners, n_camera)
    return (
        (
            _rms(sigma, n, n_camera),
            f"p counts every unknown: the {n_camera} camera parameters and each view's pose, 6 numbers "
            f"(3 rotation, 3 translation): p = n_camera + 6 n_views = {p}, not {n_camera}",
        ),
        (
            _rms(sigma, n, n_camera + 6),
            f"each of the {n_views} views has its own pose: p = n_camera + 6 n_views = {p}, not n_camera + 6",
        ),
        *(
            (
                _rms(sigma, n, n_camera + k * n_views),
                f"a pose has 6 unknowns (3 rotation as an axis-angle vector, 3 translation), not {k}"
                + why
                + f": p = n_camera + 6 n_views = {p}",
            )
            for k, why in (
                (3, " (the rotation or the translation alone)"),
                (7, " (a quaternion's 4 numbers carry only 3 degrees of freedom)"),
                (12, " (a rotation matrix's 9 entries carry only 3 degrees of freedom)"),
            )
        ),
        (
            _rms(sigma, n_views, p),
            f"N counts corners over all views, n_views x corners_per_view = {n}, not the number of views",
        ),
        (
            _rms(sigma, corners, p),
            f"N counts corners over all views, n_views x corners_per_view = {n}, not one view's corners",
        ),
        (
            _rms(sigma, 2 * n, p),
            "you doubled N twice: N is the number of corners (n_views x corners_per_view), and the formula's "
            "2N already counts their two coordinates",
        ),
    )


def _formula_slips(sigma, n, p, expected):
    """(value, cause) for the slips in the formula itself, given the right N and p."""
    return (
        (
            expected / np.sqrt(2),
            "that is the rms per coordinate; camlab's and OpenCV's rms is per corner "
            "point, whose error is a 2-vector: multiply by sqrt(2)",
        ),
        (
            sigma,
            "sigma alone forgets both factors: a point's error is a 2-vector (sqrt(2)), and the fit "
            "absorbs p of the 2N degrees of freedom (sqrt(1 - p / (2N)))",
        ),
        (
            sigma * np.sqrt(1 - p / n),
            "you left out sqrt(2) (per point, not per coordinate) and used "
            "1 - p / N: there are 2N residuals, so it is 1 - p / (2N)",
        ),
        (
            np.sqrt(2) * sigma / np.sqrt(1 - p / (2 * n)),
            "you divided by sqrt(1 - p / (2N)): the fit makes "
            "the residuals smaller than the noise, so multiply",
        ),
        (
            np.sqrt(2) * sigma * np.sqrt(1 - p / n),
            "each corner gives two residuals, so there are 2N of "
            "them: the factor is sqrt(1 - p / (2N)), not sqrt(1 - p / N)",
        ),
        (
            np.sqrt(2) * sigma * (1 - p / (2 * n)),
            "the factor is a square root, sqrt(1 - p / (2N)): it scales a variance, sigma^2",
        ),
        (
            expected**2,
            "that is the mean square error 2 sigma^2 (1 - p / (2N)), a variance in px^2: the rms "
            "is its square root",
        ),
        (
            np.sqrt(2) * sigma,
            "you left out sqrt(1 - p / (2N)), or computed p / (2N) with integer division "
            "(p // (2 * N) is 0): the fit uses up p of the 2N residuals' degrees of freedom, so its "
            "residuals come out smaller than the noise",
        ),
        (
            2 * sigma * np.sqrt(1 - p / (2 * n)),
            "a point's error has two coordinates, each with variance "
            "sigma^2: the variances add, so its rms is sqrt(2) sigma, not 2 sigma",
        ),
        (
            np.sqrt(2) * sigma * np.sqrt(1 + p / (2 * n)),
            "the fit makes the residuals smaller than the noise: 1 - p / (2N), not 1 + p / (2N)",
        ),
    )


def _rms_diagnosis(args, got, expected) -> str:
    problem = _rms_form_problem(args, got, expected)
    if problem:
        return problem
    sigma, n_views, corners, n_camera = args
    n, p = _counts(n_views, corners, n_camera)
    g = float(np.asarray(got, dtype=float))
    for value, cause in (
        *_count_slips(sigma, n_views, corners, n_camera),
        *_formula_slips(sigma, n, p, expected),
    ):
        if np.isclose(g, value, rtol=1e-6):
            return cause
    if any(np.isclose(g, round(expected, d), rtol=0, atol=1e-12) for d in range(1, 5)):
        return (
            f"your {g:g} is the right value rounded ({expected:.6g}): return the unrounded number "
            "and round only when printing, f'{rms:.3f}'"
        )
    if any(np.isclose(g, expected * f, rtol=1e-6) for f in (1e3, 1e-3)):
        return "a factor of 1000 off: sigma is already in pixels and so is the answer; convert no units"
    return (
        "not the rms of section 5, sqrt(2) sigma sqrt(1 - p / (2N)): N counts the corners of all "
        "views, p the camera's unknowns plus 6 per view (3 rotation, 3 translation); recount both "
        "and check each factor"
    )


def expected_rms(sigma, n_views, corners_per_view, n_camera):
    """The rms reprojection error per corner a calibration should reach at corner noise sigma.

    N = n_views * corners_per_view corners; p = n_camera + 6 n_views unknowns (each view's pose
    adds 3 rotation and 3 translation numbers). With noise sigma in each coordinate, the
    maximum-likelihood residual per coordinate is sigma sqrt(1 - p / (2N)) (H&Z 5.1.3: the fit
    absorbs p of the 2N degrees of freedom); a corner's error is a 2-vector, so its rms is
    sqrt(2) times that.

    Parameters
    ----------
    sigma : float
        The corner noise per coordinate, px.
    n_views : int
        The number of views.
    corners_per_view : int
        The corners detected in each view.
    n_camera : int
        The camera's own unknowns: intrinsics and distortion coefficients.

    Returns
    -------
    float
        sqrt(2) sigma sqrt(1 - p / (2N)), px.

    References
    ----------
    R. Hartley and A. Zisserman (2004), *Multiple View Geometry in Computer Vision*, 2nd ed.,
    section 5.1.3.
    """
    n = n_views * corners_per_view
    p = n_camera + 6 * n_views
    return float(np.sqrt(2.0) * sigma * np.sqrt(1.0 - p / (2.0 * n)))


def _with(n_of, p_of, form=_rms):
    """A wrong answer that counts N and p with ``n_of``, ``p_of`` (each from V, C, c)."""
    return lambda s, v, c, k: form(s, n_of(v, c, k), p_of(v, c, k))


_N = lambda v, c, k: v * c  # noqa: E731 - the right counts, for the wrong variants
_P = lambda v, c, k: k + 6 * v  # noqa: E731

register_exercise(
    Exercise(
        name="expected_rms",
        lesson="08",
        reference=_rms_reference,
        cases=_rms_cases,
        compare=same_array(rtol=1e-6, atol=1e-12),
        diagnose=_rms_diagnosis,
        wrong_variants=(
            (_with(_N, lambda v, c, k: k), "and each view's pose"),
            (_with(_N, lambda v, c, k: k + 6), "its own pose"),
            (_with(lambda v, c, k: v, _P), "N is too small"),
            (_with(lambda v, c, k: c, _P), "not one view's corners"),
            (_with(lambda v, c, k: 2 * v * c, _P), "doubled N twice"),
            (_with(_N, _P, lambda s, n, p: s * np.sqrt(1 - p / (2 * n))), "per coordinate"),
            (_with(_N, _P, lambda s, n, p: s), "sigma alone"),
            (_with(_N, _P, lambda s, n, p: s * np.sqrt(1 - p / n)), "left out sqrt(2)"),
            (
                _with(_N, _P, lambda s, n, p: np.sqrt(2) * s / np.sqrt(1 - p / (2 * n))),
                "you divided",
            ),
            (_with(_N, _P, lambda s, n, p: np.sqrt(2) * s * np.sqrt(1 - p / n)), "2N of them"),
            (_with(_N, _P, lambda s, n, p: np.sqrt(2) * s * (1 - p / (2 * n))), "a square root"),
            (
                _with(_N, _P, lambda s, n, p: np.sqrt(2) * s * np.sqrt(1 - p // (2 * n))),
                "integer division",
            ),
            (_with(_N, _P, lambda s, n, p: 2 * s * np.sqrt(1 - p / (2 * n))), "variances add"),
            (_with(_N, _P, lambda s, n, p: np.sqrt(2) * s * np.sqrt(1 + p / (2 * n))), "1 + p"),
            (_with(_N, _P, lambda s, n, p: np.array([_rms(s, n, p)])), "shape (1,)"),
            (_with(_N, _P, lambda s, n, p: round(_rms(s, n, p), 3)), "rounded"),
            (_with(_N, _P, lambda s, n, p: 2 * s**2 * (1 - p / (2 * n))), "mean square"),
        ),
        teaching=expected_rms,
        solution_note=(
            "# camlab has no function for it: lesson 08, section 5, computes the same value beside the\n"
            "# coach, from the detector's noise and the calibration's N and p"
        ),
    )
)
