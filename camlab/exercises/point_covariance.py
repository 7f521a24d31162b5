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

from ._answers import diagonal_only_hint, same_array, shape_problem
from ._core import Exercise, Mistake, first_mistake, mistake_variant, register_exercise


def _look(centre, target) -> np.ndarray:
    """The rotation cam_from_world of a camera at ``centre`` looking at ``target`` (board y down)."""
    z = (target - centre) / np.linalg.norm(target - centre)
    x = np.cross([0.0, 1.0, 0.0], z)
    x /= np.linalg.norm(x)
    return np.vstack([x, np.cross(z, x), z])


def _cases():
    """(J_A, Sigma_A, J_B, Sigma_B, J_u, sigma_u): a real triangulation, as in section 3 (metres, px).

    A 9 x 6 board of 25 mm squares (z = 0) seen by two cameras 0.45 m from its centre and 60 (then 25)
    degrees apart as seen from that centre (their rays to the box's corner 5 cm above the board meet at
    64.5 and 27.0 degrees); each pose's covariance from its 54
    corners at 0.14 px, and the triangulated corner's Jacobians by central differences of the DLT.
    """
    from ..camera import rotation_from_axis_angle
    from ..epipolar import triangulate_points
    from ..measurement import pose_covariance

    K = np.array([[532.8, 0.0, 341.8], [0.0, 533.0, 234.1], [0.0, 0.0, 1.0]])
    board = np.array([[0.025 * i, 0.025 * j, 0.0] for j in range(6) for i in range(9)])
    corner, middle = np.array([0.05, 0.025, -0.05]), np.array([0.1, 0.0625, 0.0])
    cases = []
    for alpha, sigma_u in ((60, 0.4), (25, 0.3)):  # not 0.5: 2 * 0.5**2 == 0.5
        poses = []
        for side in (-1, 1):
            a = np.radians(side * alpha / 2)
            C = middle + 0.45 * np.array([np.sin(a), -0.3, -np.cos(a)]) / np.linalg.norm(
                [np.sin(a), -0.3, -np.cos(a)]
            )
            R = _look(C, middle)
            poses.append((R, -R @ C))
        pixels = [(K @ (R @ corner + t))[:2] / (K @ (R @ corner + t))[2] for R, t in poses]

        def point(
            d, u, poses=poses, K=K
        ):  # d: both poses' updates (12), u: the four pixel coordinates
            P = [
                K @ np.column_stack([rotation_from_axis_angle(dk[:3]) @ R, t + dk[3:]])
                for (R, t), dk in zip(poses, d.reshape(2, 6), strict=True)
            ]
            return triangulate_points(P[0], P[1], u[:2], u[2:])

        d0, u0 = np.zeros(12), np.concatenate(pixels)
        J = np.column_stack(
            [(point(d0 + h, u0) - point(d0 - h, u0)) / 2e-6 for h in 1e-6 * np.eye(12)]
        )
        J_u = np.column_stack(
            [(point(d0, u0 + h) - point(d0, u0 - h)) / 2e-4 for h in 1e-4 * np.eye(4)]
        )
        Sigma_A, Sigma_B = (pose_covariance(K, R, t, board, 0.14) for R, t in poses)
        cases.append((J[:, :6], Sigma_A, J[:, 6:], Sigma_B, J_u, sigma_u))
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
        mm_linear=1e3 * (a + b + sigma_u**2 * u),
        swapped=J_A @ Sigma_B @ J_A.T + J_B @ Sigma_A @ J_B.T + sigma_u**2 * u,
        identity=a + b + sigma_u**2 * np.eye(3),
        picks_twice=a + b + 2 * sigma_u**2 * u,
        cross=a + b + sigma_u**2 * u + J_A @ Sigma_A @ J_B.T,
        cross_sym=a + b + sigma_u**2 * u + J_A @ Sigma_A @ J_B.T + J_B @ Sigma_A @ J_A.T,
        all_scaled=sigma_u**2 * (a + b + u),
        diagonal=J_A @ np.diag(np.diag(Sigma_A)) @ J_A.T
        + J_B @ np.diag(np.diag(Sigma_B)) @ J_B.T
        + sigma_u**2 * u,
        averaged=(a + b) / 2 + sigma_u**2 * u,
        one_jacobian=a + J_A @ Sigma_B @ J_A.T + sigma_u**2 * u,
        all_averaged=(a + b + sigma_u**2 * u) / 2,
        picks_diagonal=a + b + sigma_u**2 * np.diag(np.diag(u)),
        picks_halved=a + b + (sigma_u / 2) ** 2 * u,
        sigma_A_twice=a + J_B @ Sigma_A @ J_B.T + sigma_u**2 * u,
        cross_own=a + b + sigma_u**2 * u + J_A @ Sigma_A @ J_B.T + J_B @ Sigma_B @ J_A.T,
        picks_A_only=a + b + sigma_u**2 * J_u[:, :2] @ J_u[:, :2].T,
        diagonal_matrix=np.diag(np.diag(a + b + sigma_u**2 * u)),
    )


_MISTAKES = (
    Mistake(
        "Sigma_X diagonal only",
        lambda c: c.diagonal_matrix,
        "you zeroed Sigma_X's off-diagonal terms (np.diag(np.diag(...))): keep the whole (3, 3) sum; its "
        "off-diagonal terms tilt the ellipsoid, whose long axis lies along the view, not along x, y or z.",
    ),
    Mistake(
        "J_A for both poses",
        lambda c: c.one_jacobian,
        "your pose B term uses J_A: each pose moves the point through its own Jacobian, so pose B's "
        "term is J_B @ Sigma_B @ J_B.T (the two cameras see the point from different directions).",
    ),
    Mistake(
        "everything averaged",
        lambda c: c.all_averaged,
        "your covariance is half the answer: the three sources are independent, so their covariances "
        "ADD (J_A Sigma_A J_A^T + J_B Sigma_B J_B^T + sigma_u^2 J_u J_u^T); do not average them.",
    ),
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
        "poses swapped",
        lambda c: c.swapped,
        "you paired each Jacobian with the other photo's covariance (J_A Sigma_B J_A^T): J_A is the point's "
        "sensitivity to pose A, so it carries pose A's covariance, J_A @ Sigma_A @ J_A.T, and J_B carries Sigma_B.",
    ),
    Mistake(
        "sigma_u^2 I",
        lambda c: c.identity,
        "your picking term is sigma_u^2 I, as if the pixel noise landed on the point unchanged: it reaches "
        "the point through the triangulation, sigma_u**2 * J_u @ J_u.T (metres per pixel, squared).",
    ),
    Mistake(
        "picking counted twice",
        lambda c: c.picks_twice,
        "you counted the picking twice ('two photos, so twice'): J_u already holds both photos' four "
        "coordinates, so sigma_u**2 * J_u @ J_u.T covers both picks once.",
    ),
    Mistake(
        "cross term",
        lambda c: c.cross,
        "you added a cross term J_A Sigma_A J_B^T: the two poses are solved from different photos and are "
        "independent of each other and of the picks, so Sigma_X has no cross terms, only the three sums.",
    ),
    Mistake(
        "cross terms, each pose's own",
        lambda c: c.cross_own,
        "you added cross terms between the poses (J_A Sigma_A J_B^T and J_B Sigma_B J_A^T): the two "
        "poses are solved from different photos and are independent, so no cross term: Sigma_X is only "
        "the three J Sigma J^T terms.",
    ),
    Mistake(
        "photo A's picks only",
        lambda c: c.picks_A_only,
        "your picking term uses only J_u's first two columns, photo A's pick: photo B's two picked "
        "coordinates are just as noisy, so use all four columns, sigma_u**2 * J_u @ J_u.T.",
    ),
    Mistake(
        "cross terms",
        lambda c: c.cross_sym,
        "you added cross terms between the poses (J_A Sigma_A J_B^T and its transpose): the two poses are "
        "solved from different photos and are independent, so Sigma_X is only the three J Sigma J^T terms.",
    ),
    Mistake(
        "sigma_u on the poses",
        lambda c: c.all_scaled,
        "you multiplied the pose terms by sigma_u^2 too: Sigma_A and Sigma_B are covariances already "
        "(metres and radians squared); sigma_u^2 belongs to the picking term only.",
    ),
    Mistake(
        "diagonal of Sigma only",
        lambda c: c.diagonal,
        "you used only the diagonal of Sigma_A and Sigma_B: a pose's six parameters are correlated "
        "(section 1's Mahalanobis test), so each pose term is the full J_A @ Sigma_A @ J_A.T.",
    ),
    Mistake(
        "poses averaged",
        lambda c: c.averaged,
        "you averaged the two pose terms: each pose's error moves the point on its own, and independent "
        "errors add in variance, so the two terms add, J_A Sigma_A J_A^T + J_B Sigma_B J_B^T.",
    ),
    Mistake(
        "picking diagonal",
        lambda c: c.picks_diagonal,
        "you kept only the diagonal of the picking term: J_u @ J_u.T has off-diagonal entries (the four "
        "coordinates each move the point along a slanted direction), which give the ellipsoid its tilt.",
    ),
    Mistake(
        "sigma_u halved",
        lambda c: c.picks_halved,
        "your picking term is a quarter of the right one, as if each coordinate's noise were sigma_u / 2 "
        "(a +-sigma_u range taken as 2 sigma?): sigma_u is the one-sigma noise of each coordinate, so the "
        "term is sigma_u**2 * J_u @ J_u.T.",
    ),
    Mistake(
        "millimetres, not squared",
        lambda c: c.mm_linear,
        "your covariance is 1000 times too big: a conversion to mm multiplied it by 1000, but a covariance "
        "is in squared units (mm^2 would be 10^6). Return it in metres squared, as the Jacobians give it.",
    ),
    Mistake(
        "Sigma_A for both",
        lambda c: c.sigma_A_twice,
        "photo B's term uses Sigma_A: each pose has its own covariance, solved from its own photo's "
        "corners, so the second term is J_B @ Sigma_B @ J_B.T.",
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
    if g is not None and g.shape == (3, 3) and np.isnan(g).any():
        return (
            "your covariance has NaN entries, square roots of negative numbers: an elementwise np.sqrt "
            "(of Sigma_A, Sigma_B or the result) breaks the negative covariances. Sigma_X is a sum of "
            "J Sigma J^T terms, with no square root anywhere."
        )
    hint = diagonal_only_hint(got, expected, "the correlations (the ellipsoid's tilt)")
    if hint:
        return hint
    if (
        g is not None
        and g.shape == (3, 3)
        and g.dtype.kind in "fiu"
        and np.allclose(np.abs(g.astype(float)) ** 2, np.abs(expected), rtol=1e-4, atol=0)
    ):
        return (
            "you took an elementwise square root (a 'sigma matrix', np.sqrt of each entry): the square root "
            "of a covariance is not taken entry by entry (sigmas are the roots of its DIAGONAL, "
            "np.sqrt(np.diag(Sigma_X))). Return Sigma_X itself, the sum of the three J Sigma J^T terms."
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


def _exception_hint(exc: Exception, args: tuple) -> str:
    """J.T @ Sigma @ J for J @ Sigma @ J.T: the shapes clash inside the matmul, or in the sum."""
    text = str(exc).replace(" ", "")
    if isinstance(exc, ValueError) and "broadcast" in text and "(4,4)" in text:
        return (
            "a (4, 4) term met the (3, 3) ones in the sum: J_u.T @ J_u is in the four pixel coordinates' "
            "space. The picking term maps them into the point's, sigma_u**2 * J_u @ J_u.T, (3, 4) (4, 3) = (3, 3)."
        )
    if not (isinstance(exc, ValueError) and "matmul" in str(exc)):
        return ""
    return (
        "the shapes do not fit: J_A is (3, 6), one row per coordinate of the point, one column per pose "
        "parameter, so forward propagation is J_A @ Sigma_A @ J_A.T, (3, 6) (6, 6) (6, 3) = (3, 3); "
        "in J_A.T @ Sigma_A @ J_A (a transpose on the wrong side) the (6, 3) J_A.T cannot multiply the "
        "(6, 6) Sigma_A. The same holds for J_B, and the picking term is J_u @ J_u.T, not J_u.T @ J_u."
    )


def _elementwise_root(*args):
    """A slip: an elementwise square root of the covariance (NaN where an entry is negative)."""
    with np.errstate(invalid="ignore"):
        return np.sqrt(point_covariance(*args))


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
        exception_hint=_exception_hint,
        wrong_variants=(
            (_variant("J_A for both poses"), "its own Jacobian"),
            (_variant("cross terms, each pose's own"), "no cross term"),
            (_variant("photo A's picks only"), "all four columns"),
            (_variant("everything averaged"), "do not average"),
            (_variant("sigma_u not squared"), "variance belongs"),
            (_variant("no picking term"), "left out the picking"),
            (_variant("no pose terms"), "left out the poses"),
            (_variant("one pose only"), "only photo A"),
            (_variant("inverse covariance"), "information matrices"),
            (_variant("picking per end"), "EACH of the four"),
            (_variant("millimetres"), "mm^2"),
            (_variant("poses swapped"), "other photo's covariance"),
            (_variant("sigma_u^2 I"), "sigma_u^2 I"),
            (_variant("picking counted twice"), "counted the picking twice"),
            (_variant("cross term"), "a cross term"),
            (_variant("cross terms"), "cross terms between the poses"),
            (_variant("sigma_u on the poses"), "pose terms by sigma_u^2"),
            (_variant("diagonal of Sigma only"), "only the diagonal of Sigma_A"),
            (_variant("poses averaged"), "averaged"),
            (_variant("Sigma_X diagonal only"), "off-diagonal terms tilt"),
            (_variant("picking diagonal"), "only the diagonal of the picking"),
            (_variant("sigma_u halved"), "sigma_u / 2"),
            (_variant("Sigma_A for both"), "photo B's term uses Sigma_A"),
            (_variant("millimetres, not squared"), "squared units"),
            (
                lambda *args: np.sqrt(np.abs(point_covariance(*args))),
                "elementwise square root",
            ),
            (
                (
                    lambda J_A, S_A, J_B, S_B, J_u, s: (
                        J_A.T @ S_A @ J_A + J_B.T @ S_B @ J_B + s**2 * J_u @ J_u.T
                    )
                ),
                "the shapes do not fit",
            ),
            (_elementwise_root, "NaN"),
            ((lambda J_A, S_A, J_B, S_B, J_u, s: J_u.T @ J_u), "inputs' space"),
            ((lambda *a: np.diag(point_covariance(*a))), "the variances alone"),
            ((lambda *a: np.sqrt(np.diag(point_covariance(*a)))), "one-sigmas"),
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
