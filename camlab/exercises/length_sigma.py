r"""Exercise for lesson 12, measure the world: the first-order sigma of a length on the board's plane.

A length between the pixels :math:`a` and :math:`b` on the plane is
:math:`L = \|\pi(H^{-1}\tilde a) - \pi(H^{-1}\tilde b)\|`, with :math:`H = K[r_1\ r_2\ t]` the pose's
homography of the plane. It depends on the six pose parameters p (covariance :math:`\Sigma_p`) and on
the four picked coordinates (independent, variance :math:`\sigma_u^2` each), so to first order

.. math:: \sigma_L^2 = g_p^\top \Sigma_p\, g_p + \sigma_u^2 \|g_u\|^2,
          \qquad g_p = \partial L / \partial p,\quad g_u = \partial L / \partial (a, b),

the gradients by central differences, as :func:`camlab.measurement.measure_on_plane` takes them.

References
----------
Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 5.2 (forward propagation of covariance).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ._core import Exercise, Mistake, first_mistake, mistake_variant, register_exercise
from ._numbers import is_number, not_one_number, same_number

_K = np.array([[532.8, 0.0, 341.8], [0.0, 533.0, 234.1], [0.0, 0.0, 1.0]])
_BOARD = np.array([[0.025 * i, 0.025 * j, 0.0] for j in range(6) for i in range(9)])


def _exp(w) -> np.ndarray:
    """Rodrigues' formula, exp([w]x), the identity at w = 0."""
    w = np.asarray(w, dtype=float)
    th = np.linalg.norm(w)
    if th < 1e-15:
        return np.eye(3)
    k = w / th
    S = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + np.sin(th) * S + (1 - np.cos(th)) * S @ S


def _pose_jacobian(K, R, t, X) -> np.ndarray:
    """One point's (2, 6) pixel Jacobian for the left update (dw, dt), as lesson 12's Exercise 1."""
    Xc = R @ X + t
    P = K @ Xc
    dpix = (K[:2] - np.outer(P[:2] / P[2], K[2])) / P[2]
    return dpix @ np.hstack([np.cross(np.eye(3), R @ X).T, np.eye(3)])


def _homography_of(K, R, t):
    """H_of(p): the plane's homography K [r1 r2 t] of the pose moved by p = (dw, dt), left update."""

    def H_of(p):
        p = np.asarray(p, dtype=float)
        R_p, t_p = _exp(p[:3]) @ R, t + p[3:]
        return K @ np.column_stack([R_p[:, 0], R_p[:, 1], t_p])

    return H_of


def _cases():
    """(H_of, Sigma_p, a, b, sigma_u): a 9 x 6 board of 25 mm at two poses, ends picked or detected."""
    cases = []
    for w, t, (i, j), sigma_u in (
        (
            [0.3, -0.2, 0.1],
            [-0.1, -0.05, 0.45],
            ((0, 0), (8, 0)),
            0.4,
        ),  # not 0.5: 2 * 0.5**2 == 0.5
        ([-0.4, 0.25, 1.2], [-0.08, 0.02, 0.6], ((1, 5), (7, 1)), 0.14),
    ):
        R, t = _exp(w), np.array(t)
        J = np.vstack(
            [_pose_jacobian(_K, R, t, X) for X in _BOARD]
        )  # (108, 6), left update (dw, dt)
        Sigma_p = 0.14**2 * np.linalg.inv(J.T @ J)
        H_of = _homography_of(_K, R, t)
        ends = [H_of(np.zeros(6)) @ np.array([0.025 * i, 0.025 * j, 1.0]) for i, j in (i, j)]
        a, b = (e[:2] / e[2] for e in ends)
        cases.append((H_of, Sigma_p, a, b, sigma_u))
    return cases


def _parts(H_of, Sigma_p, a, b, slip=None):
    """The gradients g_p (6,) and g_u (4,) of the length, by central differences.

    ``slip`` is a student's slip in mapping the pixels back: "forward" (by H instead of
    H^-1), "transposed" (by H^-T) or "no w" (no division by the third coordinate).
    """

    def length(p, u):
        ends, H = np.vstack([u.reshape(2, 2).T, np.ones(2)]), H_of(p)
        if slip == "forward":
            q = H @ ends
        else:
            q = np.linalg.solve(H.T if slip == "transposed" else H, ends)
        q = q[:2] if slip == "no w" else q[:2] / q[2]
        return np.linalg.norm(q[:, 0] - q[:, 1])

    p0, u0 = np.zeros(6), np.concatenate([a, b]).astype(float)
    g_p = np.array([(length(p0 + h, u0) - length(p0 - h, u0)) / 2e-6 for h in 1e-6 * np.eye(6)])
    g_u = np.array([(length(p0, u0 + h) - length(p0, u0 - h)) / 2e-4 for h in 1e-4 * np.eye(4)])
    return g_p, g_u


def length_sigma(H_of, Sigma_p, a, b, sigma_u):
    """The first-order one-sigma of the length between pixels a and b on the plane, metres.

    Parameters
    ----------
    H_of : callable
        ``H_of(p)``: the (3, 3) homography plane (metres) -> pixels of the pose moved by
        p = (dw, dt), six numbers; ``H_of(np.zeros(6))`` is the solved pose's.
    Sigma_p : (6, 6) ndarray
        The pose's covariance, in the order (dw, dt) of p.
    a, b : (2,) ndarray
        The two ends, pixels (u, v).
    sigma_u : float
        The picking noise of each pixel coordinate, px.

    Returns
    -------
    float
        sigma_L, metres.
    """

    def length(p, u):  # the length on the plane for pose update p and the ends' pixels u = (a, b)
        H = H_of(p)
        q = np.linalg.solve(H, np.vstack([u.reshape(2, 2).T, np.ones(2)]))  # H^-1 [a b; 1 1]
        q = q[:2] / q[2]  # dehomogenise each column
        return np.linalg.norm(q[:, 0] - q[:, 1])

    p0, u0 = np.zeros(6), np.concatenate([a, b]).astype(float)
    h, k = 1e-6, 1e-4  # steps: radians and metres; pixels
    g_p = np.array([(length(p0 + d, u0) - length(p0 - d, u0)) / (2 * h) for d in h * np.eye(6)])
    g_u = np.array([(length(p0, u0 + d) - length(p0, u0 - d)) / (2 * k) for d in k * np.eye(4)])
    return float(np.sqrt(g_p @ Sigma_p @ g_p + sigma_u**2 * g_u @ g_u))


def _context(H_of, Sigma_p, a, b, sigma_u):
    g_p, g_u = _parts(H_of, Sigma_p, a, b)
    pose2 = float(g_p @ Sigma_p @ g_p)
    w_p, w_u = _parts(
        H_of, Sigma_p, np.asarray(a)[::-1], np.asarray(b)[::-1]
    )  # (v, u) read as (u, v)
    g_deg = np.r_[
        np.radians(g_p[:3]), g_p[3:]
    ]  # rotation gradients per degree, Sigma_p per radian^2
    pix2 = float(sigma_u**2 * g_u @ g_u)
    slipped = {}
    for slip in ("forward", "transposed", "no w"):
        s_p, s_u = _parts(H_of, Sigma_p, a, b, slip)
        slipped[slip] = np.sqrt(s_p @ Sigma_p @ s_p + sigma_u**2 * s_u @ s_u)
    return SimpleNamespace(
        right=np.sqrt(pose2 + pix2),
        variance=pose2 + pix2,
        sigma_u_once=np.sqrt(pose2 + sigma_u * g_u @ g_u),
        picking_twice=np.sqrt(pose2 + 2 * pix2),
        doubled=2 * np.sqrt(pose2 + pix2),
        diagonal=np.sqrt(g_p**2 @ np.diag(Sigma_p) + pix2),
        forward=slipped["forward"],
        transposed=slipped["transposed"],
        no_w=slipped["no w"],
        per_end=np.sqrt(pose2 + pix2 / 2),
        no_pose=np.sqrt(pix2),
        no_pixels=np.sqrt(pose2),
        one_end=np.sqrt(pose2 + sigma_u**2 * g_u[:2] @ g_u[:2]),
        squared_sum=np.sqrt(pose2 + sigma_u**2 * np.sum(g_u) ** 2),
        sigmas_added=np.sqrt(pose2) + np.sqrt(pix2),
        inverse=np.sqrt(g_p @ np.linalg.inv(Sigma_p) @ g_p + pix2),
        swapped_order=np.sqrt(np.r_[g_p[3:], g_p[:3]] @ Sigma_p @ np.r_[g_p[3:], g_p[:3]] + pix2),
        mm=1000 * np.sqrt(pose2 + pix2),
        uv_swapped=np.sqrt(w_p @ Sigma_p @ w_p + sigma_u**2 * w_u @ w_u),
        per_degree=np.sqrt(g_deg @ Sigma_p @ g_deg + pix2),
        per_degree_inv=np.sqrt(
            np.r_[np.degrees(g_p[:3]), g_p[3:]] @ Sigma_p @ np.r_[np.degrees(g_p[:3]), g_p[3:]]
            + pix2
        ),
        absolute=np.sqrt(np.abs(g_p) @ np.abs(Sigma_p) @ np.abs(g_p) + pix2),
        translation_only=np.sqrt(g_p[3:] @ Sigma_p[3:, 3:] @ g_p[3:] + pix2),
        rotation_only=np.sqrt(g_p[:3] @ Sigma_p[:3, :3] @ g_p[:3] + pix2),
        half_pixel={d: _shifted(H_of, Sigma_p, a, b, sigma_u, d) for d in (0.5, -0.5)},
    )


def _shifted(H_of, Sigma_p, a, b, sigma_u, d):
    """The right sigma with both ends moved by d px in u and v (a half-pixel slip)."""
    g_p, g_u = _parts(H_of, Sigma_p, np.asarray(a) + d, np.asarray(b) + d)
    return np.sqrt(g_p @ Sigma_p @ g_p + sigma_u**2 * g_u @ g_u)


_MISTAKES = (
    Mistake(
        "variance",
        lambda c: c.variance,
        "you returned the variance sigma_L^2: g_p^T Sigma_p g_p + sigma_u^2 |g_u|^2 is in metres squared; "
        "take its square root.",
    ),
    Mistake(
        "sigma_u not squared",
        lambda c: c.sigma_u_once,
        "you multiplied |g_u|^2 by sigma_u where the variance sigma_u^2 belongs: each picked coordinate "
        "adds sigma_u^2 (dL/du)^2, so the pixel term is sigma_u**2 * g_u @ g_u.",
    ),
    Mistake(
        "picking counted twice",
        lambda c: c.picking_twice,
        "you counted the picking twice (2 sigma_u^2 |g_u|^2, 'two ends, so twice'): g_u already holds "
        "both ends' four coordinates, so sigma_u^2 |g_u|^2 = sigma_u^2 (g_u @ g_u) covers both ends once.",
    ),
    Mistake(
        "central difference not halved",
        lambda c: c.doubled,
        "your sigma is exactly twice the answer: either you returned a 2-sigma band (2 * sigma_L; the "
        "prompt asks for one sigma), or every gradient is doubled, as when a central difference "
        "(L(p + h) - L(p - h)) is divided by h instead of 2h, the distance between its two points.",
    ),
    Mistake(
        "diagonal of Sigma_p only",
        lambda c: c.diagonal,
        "you used only the diagonal of Sigma_p (g_p**2 @ np.diag(Sigma_p)): the pose's six parameters are "
        "correlated (section 1's Mahalanobis test), so the pose term is the full quadratic form "
        "g_p @ Sigma_p @ g_p.",
    ),
    Mistake(
        "forward H",
        lambda c: c.forward,
        "you mapped the pixels with H, which goes board -> image: pixels go back to the board with H^-1, "
        "np.linalg.solve(H_of(p), (u, v, 1)) (as in Exercise 3), before the length and its gradients.",
    ),
    Mistake(
        "no division by w",
        lambda c: c.no_w,
        "you forgot to divide by w: H^-1 (u, v, 1) is a homogeneous point (x w, y w, w); the board point "
        "is its first two entries divided by the third, before the length (as in Exercise 3).",
    ),
    Mistake(
        "transposed",
        lambda c: c.transposed,
        "you mapped the pixels with H^-T (np.linalg.solve(H_of(p).T, ...), or a row vector x @ inv(H)): "
        "points go back to the board by H^-1 itself, np.linalg.solve(H_of(p), (u, v, 1)); H^-T maps lines.",
    ),
    Mistake(
        "sigma_u per end",
        lambda c: c.per_end,
        "your picking term is half the right variance, as if sigma_u were the noise of a whole end split "
        "over its two coordinates: sigma_u is the noise of EACH pixel coordinate, so every one of the four "
        "coordinates adds sigma_u^2 (dL/du)^2, sigma_u**2 * g_u @ g_u.",
    ),
    Mistake(
        "no pose term",
        lambda c: c.no_pose,
        "you left out the pose's part, g_p^T Sigma_p g_p: the homography itself is uncertain (Sigma_p), "
        "and moving the pose by p moves every length.",
    ),
    Mistake(
        "no pixel term",
        lambda c: c.no_pixels,
        "you left out the picking: the two ends are picked with noise sigma_u per coordinate, which adds "
        "sigma_u^2 |g_u|^2, g_u the length's gradient with respect to the ends' four coordinates.",
    ),
    Mistake(
        "square of the sum",
        lambda c: c.squared_sum,
        "your pixel term squares the SUM of g_u: each of the four picked coordinates adds its own "
        "sigma_u^2 g^2 (they are independent), so the term is sigma_u**2 * (g_u @ g_u), the sum of squares.",
    ),
    Mistake(
        "one end only",
        lambda c: c.one_end,
        "your pixel term has only one end: both a and b are picked, so g_u has four entries (a's u, v "
        "and b's u, v), and sigma_u^2 |g_u|^2 sums all four.",
    ),
    Mistake(
        "sigmas added",
        lambda c: c.sigmas_added,
        "you added the two sigmas: independent errors add in variance, sigma_L = "
        "sqrt(g_p^T Sigma_p g_p + sigma_u^2 |g_u|^2), not sigma_pose + sigma_pixels.",
    ),
    Mistake(
        "inverse covariance",
        lambda c: c.inverse,
        "you used the inverse of Sigma_p (the information matrix): forward propagation takes the "
        "covariance itself, g_p^T Sigma_p g_p.",
    ),
    Mistake(
        "parameter order",
        lambda c: c.swapped_order,
        "your g_p is in the order (dt, dw) while Sigma_p is in (dw, dt): perturb p[0:3] (the rotation) "
        "first, as H_of expects, so g_p and Sigma_p index the same parameters.",
    ),
    Mistake(
        "u and v swapped",
        lambda c: c.uv_swapped,
        "you swapped u and v (row, column, as an array index reads them): a and b are (u, v) = (column, "
        "row), the order H expects, so map (a[0], a[1], 1) as it is.",
    ),
    Mistake(
        "rotation per degree",
        lambda c: c.per_degree,
        "your rotation gradients are per degree (pi / 180 times too small): Sigma_p is in radians^2 and "
        "H_of takes p[0:3] in radians, so step p[0:3] by h radians and divide by 2h, with no degree conversion.",
    ),
    Mistake(
        "rotation degrees inverted",
        lambda c: c.per_degree_inv,
        "your rotation gradients are 180 / pi = 57.3 times too large: you converted them to degrees where "
        "none is needed; p[0:3] and Sigma_p are both in radians.",
    ),
    Mistake(
        "absolute values",
        lambda c: c.absolute,
        "you took absolute values (of g_p or of Sigma_p): the pose's parameters are correlated, with "
        "negative as well as positive covariances, and those signs partly cancel in g_p @ Sigma_p @ g_p; "
        "use the signed gradient and the signed covariance.",
    ),
    Mistake(
        "rotation left out",
        lambda c: c.translation_only,
        "you perturbed only the translation (p[3:6]): the rotation's three parameters p[0:3] move the "
        "homography too, and are correlated with the translation, so g_p has six entries and the pose term "
        "is the full g_p @ Sigma_p @ g_p.",
    ),
    Mistake(
        "translation left out",
        lambda c: c.rotation_only,
        "you perturbed only the rotation (p[0:3]): the translation p[3:6] moves the homography too, so "
        "g_p has six entries and the pose term is the full g_p @ Sigma_p @ g_p.",
    ),
    Mistake(
        "half pixel +",
        lambda c: c.half_pixel[0.5],
        "your ends are shifted by half a pixel: pixel centres are at integers (docs/conventions.md), so "
        "a and b are already the points to measure; do not add or subtract 0.5.",
    ),
    Mistake(
        "half pixel -",
        lambda c: c.half_pixel[-0.5],
        "your ends are shifted by half a pixel: pixel centres are at integers (docs/conventions.md), so "
        "a and b are already the points to measure; do not add or subtract 0.5.",
    ),
    Mistake(
        "millimetres",
        lambda c: c.mm,
        "your sigma is 1000 times too big: the plane is in metres, so sigma_L comes out in metres.",
    ),
)


def _diagnosis(args, got, expected) -> str:
    try:
        nan = bool(np.isnan(float(got)))
    except (TypeError, ValueError):
        nan = False
    if nan:
        return (
            "your sigma is NaN, the square root of a negative number: np.sqrt(Sigma_p) elementwise takes "
            "roots of the negative covariances. Use Sigma_p itself in g_p @ Sigma_p @ g_p, add "
            "sigma_u**2 * g_u @ g_u, and take one square root of the sum at the end."
        )
    if not is_number(got):
        return not_one_number(got, "sigma_L in metres")
    hint = first_mistake(
        _MISTAKES, _context(*args), float(got), lambda a, b: np.isclose(a, b, rtol=1e-4, atol=0)
    )
    if not hint and abs(float(got) / expected - 1) < 2e-3:
        return (
            f"nearly right: sigma_L = {1000 * float(got):.4f} mm, expected {1000 * expected:.4f} mm. A difference "
            "this small is the error of the gradients' steps: a step far too large (0.1 rad or m, 1 px) "
            "bends each difference with the curvature of the length. Use central differences with "
            "h about 1e-6 (radians, metres) for g_p and 1e-4 px for g_u."
        )
    return hint or (
        f"expected sigma_L = {1000 * expected:.4f} mm, got {1000 * float(got):.4f} mm: take g_p (6) and "
        "g_u (4) by central differences of the length, then sqrt(g_p @ Sigma_p @ g_p + sigma_u**2 * g_u @ g_u)."
    )


def _elementwise_root(H_of, Sigma_p, a, b, sigma_u):
    """A slip: np.sqrt(Sigma_p) elementwise in the pose term (NaN where a covariance is negative)."""
    g_p, g_u = _parts(H_of, Sigma_p, a, b)
    with np.errstate(invalid="ignore"):
        return float(np.sqrt(g_p @ np.sqrt(Sigma_p) @ g_p + sigma_u**2 * g_u @ g_u))


def _variant(name):
    return mistake_variant(_MISTAKES, name, _context)


def _describe(args) -> str:
    """The test input in one line: H_of is a function, shown by what it returns, never by its address."""
    H_of, Sigma_p, a, b, sigma_u = args
    H0 = np.asarray(H_of(np.zeros(6)), dtype=float)
    S = np.asarray(Sigma_p, dtype=float)

    def row(v):
        return "[" + ", ".join(f"{x:.4f}" for x in np.ravel(v)) + "]"

    return (
        f"(H_of, a function: H_of(np.zeros(6)) = [{', '.join(row(r) for r in H0)}]; Sigma_p (6, 6), "
        f"entries {S.min():.3g} .. {S.max():.3g}; a = {row(a)}, b = {row(b)}, sigma_u = {sigma_u:g})"
    )


register_exercise(
    Exercise(
        name="length_sigma",
        lesson="12",
        reference=length_sigma,
        cases=_cases,
        compare=same_number(rtol=1e-4),
        diagnose=_diagnosis,
        describe_input=_describe,
        wrong_variants=(
            (_variant("variance"), "square root"),
            (_variant("sigma_u not squared"), "sigma_u^2 belongs"),
            (_variant("picking counted twice"), "counted the picking twice"),
            (_variant("central difference not halved"), "instead of 2h"),
            (_variant("diagonal of Sigma_p only"), "only the diagonal"),
            (_variant("forward H"), "board -> image"),
            (_variant("no division by w"), "divide by w"),
            (_variant("transposed"), "H^-T"),
            (_variant("sigma_u per end"), "EACH pixel coordinate"),
            (_variant("no pose term"), "pose's part"),
            (_variant("no pixel term"), "left out the picking"),
            (_variant("one end only"), "only one end"),
            (_variant("square of the sum"), "sum of squares"),
            (_variant("sigmas added"), "add in variance"),
            (_variant("inverse covariance"), "information matrix"),
            (_variant("parameter order"), "(dt, dw)"),
            (_variant("millimetres"), "1000 times"),
            (_variant("u and v swapped"), "swapped u and v"),
            (_variant("rotation per degree"), "per degree"),
            (_variant("rotation degrees inverted"), "57.3"),
            (_variant("absolute values"), "absolute values"),
            (_variant("rotation left out"), "only the translation"),
            (_variant("translation left out"), "only the rotation"),
            (_variant("half pixel +"), "half a pixel"),
            (_variant("half pixel -"), "half a pixel"),
            (_elementwise_root, "NaN"),
        ),
        teaching=length_sigma,
        solution_note=(
            "# camlab: camlab.measurement.measure_on_plane(pose, K, a, b, dist, pixel_sigma) takes the same "
            "gradients\n# (with the distortion) and returns the length, its sigma and the two parts."
        ),
    )
)
