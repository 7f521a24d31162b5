r"""Exercise for lesson 12, measure the world: the covariance of a point triangulated from two posed photos.

A point triangulated from two photos depends on both poses (six parameters each, covariances
:math:`\Sigma_A`, :math:`\Sigma_B`) and on the four picked pixel coordinates (independent, variance
:math:`\sigma_u^2` each). With :math:`J_A`, :math:`J_B` (3 x 6) and :math:`J_u` (3 x 4) its Jacobians,
forward propagation to first order gives

.. math:: \Sigma_X = J_A \Sigma_A J_A^\top + J_B \Sigma_B J_B^\top + \sigma_u^2 J_u J_u^\top .

References
----------
Hartley & Zisserman, Multiple View Geometry, 2nd ed., sections 5.2.1 and 12.6.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ._answers import same_array, shape_problem
from ._core import Exercise, Mistake, first_mistake, mistake_variant, register_exercise


def _cases():
    """(J_A, Sigma_A, J_B, Sigma_B, J_u, sigma_u): two random but realistic cases (metres, radians, px)."""
    rng = np.random.default_rng(31)
    cases = []
    for sigma_u in (0.4, 0.3):
        J_A, J_B = (rng.normal(0, 0.3, (3, 6)) for _ in range(2))
        Sigma_A, Sigma_B = (
            (lambda M: 1e-7 * (M @ M.T + 0.5 * np.eye(6)))(rng.normal(size=(6, 6)))
            for _ in range(2)
        )
        J_u = rng.normal(0, 4e-4, (3, 4))
        cases.append((J_A, Sigma_A, J_B, Sigma_B, J_u, sigma_u))
    return cases


def point_covariance(J_A, Sigma_A, J_B, Sigma_B, J_u, sigma_u):
    """Sigma_X = J_A Sigma_A J_A^T + J_B Sigma_B J_B^T + sigma_u^2 J_u J_u^T.

    Parameters
    ----------
    J_A, J_B : (3, 6) ndarray
        The triangulated point's Jacobians with respect to each pose's six parameters (dw, dt).
    Sigma_A, Sigma_B : (6, 6) ndarray
        The two poses' covariances.
    J_u : (3, 4) ndarray
        Its Jacobian with respect to the four picked pixel coordinates (photo A's u, v, then B's).
    sigma_u : float
        The picking noise of each pixel coordinate, px.

    Returns
    -------
    (3, 3) ndarray
        The point's covariance (metres squared).
    """
    poses = J_A @ Sigma_A @ J_A.T + J_B @ Sigma_B @ J_B.T  # each pose's part, forward propagation
    return poses + sigma_u**2 * J_u @ J_u.T  # the four picks, independent, sigma_u^2 each


def _context(J_A, Sigma_A, J_B, Sigma_B, J_u, sigma_u):
    a, b = J_A @ Sigma_A @ J_A.T, J_B @ Sigma_B @ J_B.T
    u = J_u @ J_u.T
    return SimpleNamespace(
        right=a + b + sigma_u**2 * u,
        not_squared=a + b + sigma_u * u,
        no_picks=a + b,
        no_poses=sigma_u**2 * u,
        only_A=a + sigma_u**2 * u,
        inverse=J_A @ np.linalg.inv(Sigma_A) @ J_A.T
        + J_B @ np.linalg.inv(Sigma_B) @ J_B.T
        + sigma_u**2 * u,
        picks_per_end=a + b + sigma_u**2 * u / 2,
        mm=1e6 * (a + b + sigma_u**2 * u),
    )


_MISTAKES = (
    Mistake(
        "sigma_u not squared",
        lambda c: c.not_squared,
        "your picking term uses sigma_u where its variance belongs: each picked coordinate adds "
        "sigma_u^2 times its column's outer product, so the term is sigma_u**2 * J_u @ J_u.T.",
    ),
    Mistake(
        "no picking term",
        lambda c: c.no_picks,
        "you left out the picking: the four picked coordinates carry noise sigma_u each, which adds "
        "sigma_u**2 * J_u @ J_u.T (section 3: the part that dominates).",
    ),
    Mistake(
        "no pose terms",
        lambda c: c.no_poses,
        "you left out the poses: each photo's pose is uncertain (Sigma_A, Sigma_B), and moving a pose "
        "moves the triangulated point, which adds J_A @ Sigma_A @ J_A.T and J_B @ Sigma_B @ J_B.T.",
    ),
    Mistake(
        "one pose only",
        lambda c: c.only_A,
        "you propagated only photo A's pose: photo B's pose is just as uncertain, so add "
        "J_B @ Sigma_B @ J_B.T too.",
    ),
    Mistake(
        "inverse covariance",
        lambda c: c.inverse,
        "you used the inverse of Sigma_A and Sigma_B (the information matrices): forward propagation "
        "takes the covariances themselves, J @ Sigma @ J.T.",
    ),
    Mistake(
        "picking per end",
        lambda c: c.picks_per_end,
        "your picking term is half the right one, as if sigma_u were an end's noise split over its two "
        "coordinates: sigma_u is the noise of EACH of the four coordinates, so the term is "
        "sigma_u**2 * J_u @ J_u.T.",
    ),
    Mistake(
        "millimetres",
        lambda c: c.mm,
        "your covariance is 10^6 times too big, in mm^2: the Jacobians are in metres, so Sigma_X is "
        "in metres squared.",
    ),
)


def _diagnosis(args, got, expected) -> str:
    g = np.asarray(got) if got is not None else None
    if g is not None and g.shape in ((6, 6), (4, 4)):
        return (
            f"you returned a {g.shape} matrix: J.T @ Sigma @ J (or J_u.T @ J_u) is in the inputs' space; "
            "forward propagation maps into the point's, J @ Sigma @ J.T, a (3, 3) matrix."
        )
    if g is not None and g.shape == (3,):
        return (
            "you returned 3 numbers, the variances alone (the diagonal): return the whole (3, 3) "
            "covariance, whose off-diagonal terms carry the correlations (the ellipsoid's tilt)."
        )
    hint = None
    if g is not None and g.shape == np.shape(expected) and g.dtype.kind in "fiu":
        hint = first_mistake(
            _MISTAKES,
            _context(*args),
            g.astype(float),
            lambda a, b: np.allclose(a, b, rtol=1e-6, atol=0),
        )
    return (
        hint
        or shape_problem(got, expected)
        or (
            "your covariance differs from J_A Sigma_A J_A^T + J_B Sigma_B J_B^T + sigma_u^2 J_u J_u^T: "
            "check each of the three terms (with @, not *)."
        )
    )


def _variant(name):
    return mistake_variant(_MISTAKES, name, _context)


register_exercise(
    Exercise(
        name="point_covariance",
        lesson="12",
        reference=point_covariance,
        cases=_cases,
        compare=same_array(rtol=1e-6, atol=0),
        diagnose=_diagnosis,
        wrong_variants=(
            (_variant("sigma_u not squared"), "variance belongs"),
            (_variant("no picking term"), "left out the picking"),
            (_variant("no pose terms"), "left out the poses"),
            (_variant("one pose only"), "only photo A"),
            (_variant("inverse covariance"), "information matrices"),
            (_variant("picking per end"), "EACH of the four"),
            (_variant("millimetres"), "mm^2"),
            ((lambda J_A, S_A, J_B, S_B, J_u, s: J_u.T @ J_u), "inputs' space"),
            ((lambda *a: np.diag(point_covariance(*a))), "the variances alone"),
            (
                (lambda J_A, S_A, J_B, S_B, J_u, s: (J_A * J_A) @ np.diag(S_A)),
                "the variances alone",
            ),
        ),
        teaching=point_covariance,
        ndarray_only=True,
        solution_note=(
            "# section 3 builds the same sum in one step: Sigma_X = J @ Sigma_in @ J.T, with J (6, 20) the "
            "Jacobian of both ends\n# and Sigma_in the block-diagonal covariance of the 20 inputs."
        ),
    )
)
