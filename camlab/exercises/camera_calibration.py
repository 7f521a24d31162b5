"""Exercises for lesson 08, camera calibration."""

from __future__ import annotations

import numpy as np

from .. import calibration, camera, optimise
from ..camera import rotation_from_axis_angle
from ._answers import SameArray, Tolerance, same_array, shape_problem
from ._core import Exercise, register_exercise

# ------------------------------------------------------------------ V from one homography


def _zhang_cases():
    K = np.array([[820.0, 0.0, 322.4], [0.0, 818.0, 236.8], [0.0, 0.0, 1.0]])
    rng = np.random.default_rng(8)
    out = []
    for _ in range(3):
        r = rng.normal(0, 0.4, 3)
        R = rotation_from_axis_angle(r)
        H = K @ np.column_stack([R[:, 0], R[:, 1], [0.02, -0.01, 0.5]])
        out.append(
            (H,)
        )  # H[2, 2] = 0.5 t_z-ish, not 1: an in-place H /= H[2, 2] changes the caller's H
    out.append((np.array([[2.0, 0.3, 5.0], [-0.1, 1.5, 2.0], [0.01, 0.02, 3.0]]),))
    return out


def _common_scale(got, expected) -> float:
    """The factor s minimising ||got - s expected|| (0 when either is 0)."""
    g, e = np.ravel(np.asarray(got, dtype=float)), np.ravel(np.asarray(expected, dtype=float))
    return float(g @ e / (e @ e)) if e @ e > 0 else 0.0


class _SameUpToScale(SameArray):
    """Same (2, 6) rows up to a non-zero factor per row: each row is one equation of V b = 0.

    Rescaling H first (H / H[2, 2], H / ||H||) multiplies both rows by s**2; normalising each
    row (a conditioning step), negating one (v22 - v11) or halving one leaves its equation,
    and so the null vector b, unchanged. All of these pass.
    """

    def __call__(self, got, expected) -> bool:
        try:
            g = np.asarray(got, dtype=float)
        except (TypeError, ValueError):
            return False
        if g.shape != np.shape(expected) or not np.isfinite(g).all():
            return False
        e = np.asarray(expected, dtype=float)
        scales = np.array([_common_scale(gi, ei) for gi, ei in zip(g, e, strict=True)])
        return bool(np.all(scales != 0)) and super().__call__(g / scales[:, None], e)


def _undoubled(g, e, scales) -> bool:
    """Row 0 right and row 1's B12, B13, B23 entries half the truth: v_ii's cross terms not doubled."""
    tol = 1e-6 * np.abs(e).max()
    row0 = np.allclose(g[0] / scales[0], e[0], rtol=1e-6, atol=tol)
    return row0 and np.allclose(
        g[1, [1, 3, 4]] / scales[1], e[1, [1, 3, 4]] / 2, rtol=1e-6, atol=tol
    )


def _zhang_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return a (2, 6) array: the rows v12 and v11 - v22."
    (H,) = args
    g = np.asarray(got, dtype=float)
    if np.allclose(g, calibration.zhang_constraints(H.T)):
        return "you used the rows of H; h_i is the i-th column, H[:, i]"
    if _SameUpToScale(Tolerance(1e-6, 1e-12))(g[::-1], expected):
        return (
            "the two rows are swapped: row 0 is v12 (h1^T B h2 = 0, orthogonal columns), "
            "row 1 is v11 - v22 (equal lengths)"
        )
    e = np.asarray(expected, dtype=float)
    if _SameUpToScale(Tolerance(1e-6, 1e-12))(g, calibration.zhang_constraints(np.linalg.inv(H))):
        return (
            "you used inv(H), the map from the image to the board; Zhang's H maps the board (X, Y, 1) "
            "to the image, h_i ∝ K r_i, and that is the H the function receives"
        )
    zhang = "Zhang's b = (B11, B12, B22, B13, B23, B33), in that order"
    for order, cause in (
        ([0, 1, 3, 2, 4, 5], "you ordered b row by row of B, (B11, B12, B13, B22, B23, B33)"),
        ([0, 1, 2, 4, 3, 5], "the entries for B13 and B23 are swapped"),
        ([0, 2, 1, 3, 4, 5], "the entries for B12 and B22 are swapped"),
    ):
        if _SameUpToScale(Tolerance(1e-6, 1e-12))(g[:, order], e):
            return f"{cause}; {zhang}"
    names = ["B11", "B12", "B22", "B13", "B23", "B33"]
    scales = [_common_scale(g[r, [0, 2, 5]], e[r, [0, 2, 5]]) for r in range(2)]
    if all(scales) and np.allclose(
        g[:, [0, 2, 5]] / np.c_[scales], e[:, [0, 2, 5]], rtol=1e-6, atol=1e-12 * np.abs(e).max()
    ):
        tol = 1e-6 * np.abs(e).max()
        wrong = [
            names[k]
            for k in (1, 3, 4)
            if not np.allclose(g[:, k] / np.array(scales), e[:, k], rtol=1e-6, atol=tol)
        ]
        if _undoubled(g, e, scales):
            return (
                "row 0 (v12) is right, but in row 1 the entries for B12, B13, B23 are half the truth: for i = j "
                "the two products of hi3 hj1 + hi1 hj3 are equal, so v_ii's entry is 2 hi1 hi3 (likewise "
                "2 hi1 hi2 and 2 hi2 hi3); you kept only one of them"
            )
        return (
            f"the entries for B11, B22, B33 are right, those for {', '.join(wrong)} are not: each of these appears "
            "twice in h_i^T B h_j (B is symmetric), so its entry is a sum of two products, "
            "e.g. hi3 hj1 + hi1 hj3 for B13 (for i = j the two are equal: 2 hi1 hi3)"
        )
    one_based = np.stack(
        [calibration.zhang_v(H, 1, 2), calibration.zhang_v(H, 1, 1) - calibration.zhang_v(H, 2, 2)]
    )
    if np.allclose(g, one_based):
        return (
            "you used columns 1 and 2 (h2 and h3): numpy counts from 0, so the paper's h1, h2 are "
            "H[:, 0] and H[:, 1] (v12 = v(0, 1), v11 - v22 = v(0, 0) - v(1, 1))"
        )
    if np.allclose(g[1], calibration.zhang_v(H, 0, 0) + calibration.zhang_v(H, 1, 1)):
        return "the second row is v11 - v22 (equal lengths: h1^T B h1 = h2^T B h2), not the sum"
    s0 = _common_scale(g[0], expected[0])
    if s0 != 0 and np.allclose(
        g[0] / s0, expected[0], rtol=1e-6, atol=1e-12 * np.abs(expected).max()
    ):
        return (
            "the first row (v12) is right (any non-zero factor per row is accepted); the second is not a "
            "multiple of v11 - v22"
        )
    return (
        "v_ij = (hi1 hj1, hi1 hj2 + hi2 hj1, hi2 hj2, hi3 hj1 + hi1 hj3, hi3 hj2 + hi2 hj3, hi3 hj3) "
        "with h_i = H[:, i]; check the order of the six entries"
    )


def zhang_constraints(H):
    """Zhang's two constraints on the image of the absolute conic from one homography H.

    Rows v12 and v11 - v22, with h_i = H[:, i]: h_i^T B h_j = v_ij . b, b = (B11, B12, B22, B13, B23, B33).

    Parameters
    ----------
    H : (3, 3) array_like
        The homography from the calibration plane (Z = 0, in its own units) to the image (pixels).

    Returns
    -------
    (2, 6) ndarray
        The rows v12 and v11 - v22: each times b is 0 for the image of the absolute conic B.

    References
    ----------
    Z. Zhang (2000), "A flexible new technique for camera calibration", IEEE TPAMI 22(11), section 3.1.
    """
    H = np.asarray(H, dtype=float)

    def v(i, j):
        a, b = H[:, i], H[:, j]
        return np.array(
            [
                a[0] * b[0],
                a[0] * b[1] + a[1] * b[0],
                a[1] * b[1],
                a[2] * b[0] + a[0] * b[2],
                a[2] * b[1] + a[1] * b[2],
                a[2] * b[2],
            ]
        )

    return np.stack([v(0, 1), v(0, 0) - v(1, 1)])


def _v_undoubled(H):
    """Rows v12 and v11 - v22 with v_ii's cross terms not doubled (hi1 hi2 for 2 hi1 hi2)."""

    def v(i, j):
        a, b = H[:, i], H[:, j]
        return np.array(
            [a[0] * b[0], a[0] * b[1], a[1] * b[1], a[2] * b[0], a[2] * b[1], a[2] * b[2]]
        )

    return np.stack([calibration.zhang_v(H, 0, 1), v(0, 0) - v(1, 1)])


register_exercise(
    Exercise(
        name="zhang_constraints",
        lesson="08",
        reference=calibration.zhang_constraints,
        cases=_zhang_cases,
        compare=_SameUpToScale(Tolerance(rtol=1e-7, atol=1e-12)),
        diagnose=_zhang_diagnosis,
        ndarray_only=True,
        wrong_variants=(
            (lambda H: calibration.zhang_constraints(H.T), "rows of H"),
            (
                lambda H: np.stack(
                    [
                        calibration.zhang_v(H, 0, 1),
                        calibration.zhang_v(H, 0, 0) + calibration.zhang_v(H, 1, 1),
                    ]
                ),
                "not the sum",
            ),
            (
                lambda H: np.stack(
                    [
                        calibration.zhang_v(H, 1, 2),
                        calibration.zhang_v(H, 1, 1) - calibration.zhang_v(H, 2, 2),
                    ]
                ),
                "numpy counts from 0",
            ),
            (lambda H: calibration.zhang_constraints(H)[::-1], "rows are swapped"),
            (lambda H: calibration.zhang_constraints(H)[:, [0, 1, 3, 2, 4, 5]], "row by row of B"),
            (lambda H: calibration.zhang_constraints(np.linalg.inv(H)), "inv(H)"),
            (
                lambda H: np.stack(
                    [
                        np.array(
                            [
                                H[0, i] * H[0, j],
                                H[0, i] * H[1, j],
                                H[1, i] * H[1, j],
                                H[2, i] * H[0, j],
                                H[2, i] * H[1, j],
                                H[2, i] * H[2, j],
                            ]
                        )
                        for i, j in [(0, 1)]
                    ]
                    + [calibration.zhang_v(H, 0, 0) - calibration.zhang_v(H, 1, 1)]
                ),
                "appears twice",
            ),
            (lambda H: _v_undoubled(H), "you kept only one"),
        ),
        teaching=zhang_constraints,
    )
)


# ------------------------------------------------------------------ one LM step


def _lm_cases():
    rng = np.random.default_rng(9)
    return [(rng.normal(size=(8, 3)), rng.normal(size=8), mu) for mu in (0.0, 0.01, 1.0, 100.0)] + [
        (np.array([[1.0, 0.0], [0.0, 100.0], [1.0, 1.0]]), np.array([1.0, -2.0, 0.5]), 0.5)
    ]


def _lm_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return the step delta with one entry per parameter (J has n columns)."
    J, r, mu = args
    g = np.asarray(got, dtype=float)
    A, grad = J.T @ J, J.T @ r
    if np.allclose(g, -expected):
        return "wrong sign: the step solves (A + mu D) delta = -J^T r, A = J^T J, D = diag(J^T J) (it must go downhill)"
    if mu > 0 and np.allclose(g, np.linalg.solve(A + mu * np.diag(A)[None, :], -grad)):
        return (
            "broadcasting slip: np.diag(A) of a matrix is the (n,) vector of its diagonal, so A + mu * np.diag(A) "
            "adds mu * A_jj to every entry of column j, not only to the diagonal; build the matrix with "
            "np.diag(np.diag(A)) (or add mu * np.diag(A) to A[np.diag_indices_from(A)] on a copy)"
        )
    if np.allclose(g, np.linalg.solve(A + mu * np.eye(len(A)), -grad)):
        return "you damped with mu * I; Marquardt scales by D = diag(J^T J) so every parameter's units cancel"
    if mu > 0 and np.allclose(g, np.linalg.solve((1 + mu) * A, -grad)):
        return (
            "you damped with mu * J^T J (the whole matrix), which only shrinks the Gauss-Newton step by 1 + mu "
            "without turning it: the damping is mu * diag(J^T J), the diagonal only"
        )
    if np.allclose(g, np.linalg.solve(A, -grad)):
        return "that is the Gauss-Newton step: add the damping mu * diag(J^T J) to J^T J"
    if mu > 0 and np.allclose(g, np.linalg.solve(A + mu * np.diag(np.sqrt(np.diag(A))), -grad)):
        return (
            "you damped with the square root of diag(J^T J) (the column norms of J); Marquardt's D is "
            "diag(J^T J) itself, so that mu D has the units of J^T J"
        )
    for factor in (0.5, 2.0):
        if np.allclose(g, factor * expected):
            return (
                f"your step is {factor:g} times the right one: the right-hand side is -J^T r, the gradient of "
                "(1/2)|r|^2 (without the 1/2 the gradient is 2 J^T r, but the 2 also multiplies J^T J and cancels)"
            )
    return "solve (J^T J + mu diag(J^T J)) delta = -J^T r with np.linalg.solve"


def _lm_exception_hint(exc: Exception, args: tuple) -> str:
    """J @ J.T for J.T @ J: the shapes clash inside np.linalg.solve."""
    J = np.asarray(args[0])
    if isinstance(exc, ValueError) and J.ndim == 2 and J.shape[0] != J.shape[1]:
        m, n = J.shape
        return (
            f"J is ({m}, {n}): one row per residual, one column per parameter. The normal matrix is "
            f"J.T @ J ({n} x {n}), not J @ J.T ({m} x {m}), and the right-hand side is -J.T @ r ({n},)"
        )
    return ""


def _lm_gauss_newton_note(run) -> str:
    """The prompt's question, whether mu = 0 is the Gauss-Newton step, answered with the student's function."""
    J, r, _ = _lm_cases()[0]
    gauss_newton = np.linalg.lstsq(J, -r, rcond=None)[0]  # minimises ||J delta + r||: Gauss-Newton
    gap = np.max(np.abs(np.asarray(run(J, r, 0.0), dtype=float) - gauss_newton))
    return (
        f"  mu = 0: your step equals the Gauss-Newton step np.linalg.lstsq(J, -r) to {gap:.0e}: "
        "with no damping, LM is Gauss-Newton"
    )


def lm_step(J, r, mu):
    """One Levenberg-Marquardt step: solve (J^T J + mu diag(J^T J)) delta = -J^T r.

    Gauss-Newton for mu = 0, damped (towards a scaled gradient step) otherwise.

    Parameters
    ----------
    J : (M, N) ndarray
        The Jacobian of the residuals with respect to the N parameters.
    r : (M,) ndarray
        The residuals at the current parameters.
    mu : float
        The damping, >= 0.

    Returns
    -------
    (N,) ndarray
        The step delta to add to the parameters.

    References
    ----------
    D. W. Marquardt (1963), "An algorithm for least-squares estimation of nonlinear parameters",
    SIAM J. Appl. Math. 11(2); Hartley & Zisserman, Multiple View Geometry, 2nd ed., appendix A6.2.
    """
    A = J.T @ J
    return np.linalg.solve(A + mu * np.diag(np.diag(A)), -J.T @ r)


register_exercise(
    Exercise(
        name="lm_step",
        lesson="08",
        reference=optimise.lm_step,
        cases=_lm_cases,
        compare=same_array(rtol=1e-8, atol=1e-10),
        diagnose=_lm_diagnosis,
        wrong_variants=(
            (
                lambda J, r, mu: np.linalg.solve(J.T @ J + mu * np.diag(np.diag(J.T @ J)), J.T @ r),
                "wrong sign",
            ),
            (
                lambda J, r, mu: np.linalg.solve(J.T @ J + mu * np.eye(J.shape[1]), -J.T @ r),
                "mu * I",
            ),
            (lambda J, r, mu: np.linalg.solve(J.T @ J, -J.T @ r), "Gauss-Newton"),
            (
                lambda J, r, mu: np.linalg.solve(J.T @ J + mu * np.diag(J.T @ J), -J.T @ r),
                "broadcasting slip",
            ),
            (lambda J, r, mu: np.linalg.solve((1 + mu) * (J.T @ J), -J.T @ r), "the whole matrix"),
            (
                lambda J, r, mu: np.linalg.solve(
                    J.T @ J + mu * np.diag(np.sqrt(np.diag(J.T @ J))), -J.T @ r
                ),
                "square root of diag",
            ),
        ),
        teaching=lm_step,
        exception_hint=_lm_exception_hint,
        success_note=_lm_gauss_newton_note,
        ndarray_only=True,
    )
)


# ------------------------------------------------------------------ nearest rotation


def _rotation_cases():
    rng = np.random.default_rng(10)
    out = []
    for scale in (0.02, 0.2, 1.0):
        R = rotation_from_axis_angle(rng.normal(0, 1, 3))
        out.append((R + scale * rng.normal(size=(3, 3)),))
    out.append((np.diag([1.0, 1.0, -1.0]) + 0.1 * rng.normal(size=(3, 3)),))  # needs the det fix
    return out


def _rotation_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    g = np.asarray(got, dtype=float)
    (M,) = args
    U, _, Vt = np.linalg.svd(M)
    for candidate in (U @ Vt.T, U @ np.diag([1, 1, np.sign(np.linalg.det(U @ Vt.T))]) @ Vt.T):
        if np.allclose(g, candidate, atol=1e-8):
            return (
                "np.linalg.svd returns V^T as its third output (Vt), not V: U V^T is U @ Vt; "
                "U @ Vt.T is U V"
            )
    if np.allclose(g, np.asarray(expected).T, atol=1e-8):
        return (
            "you returned the transpose, V U^T = R^T (the inverse rotation): the nearest rotation to M is "
            "U @ Vt, in that order (with the last column of U flipped if det < 0)"
        )
    if not np.allclose(g.T @ g, np.eye(3), atol=1e-8):
        return "your matrix is not orthonormal (R^T R != I): use the SVD M = U S V^T and drop S"
    if np.linalg.det(U @ Vt) > 0 and np.allclose(g, U @ np.diag([1, 1, -1]) @ Vt, atol=1e-8):
        return (
            "you flipped U's last column although det(U V^T) was already +1, which makes it a reflection: "
            "flip only when det(U V^T) < 0, e.g. U @ np.diag([1, 1, np.linalg.det(U @ Vt)]) @ Vt"
        )
    if np.linalg.det(g) < 0:
        return "det R = -1, a reflection: flip the sign of the last column of U when det(U V^T) < 0"
    if np.linalg.det(U @ Vt) < 0:
        if np.allclose(g, -(U @ Vt), atol=1e-8):
            return (
                "you negated the whole matrix: -U V^T has det +1 but flips all three directions, far from M; "
                "flip only the direction of the smallest singular value, U[:, -1] *= -1"
            )
        for k in (0, 1):
            flip = np.ones(3)
            flip[k] = -1
            if np.allclose(g, U @ np.diag(flip) @ Vt, atol=1e-8):
                return (
                    f"you flipped column {k} of U; flip the last one, U[:, -1], the direction of the smallest "
                    "singular value: flipping it changes M the least"
                )
        flip_col = Vt.copy()
        flip_col[:, -1] *= -1
        if np.allclose(g, U @ flip_col, atol=1e-8):
            return (
                "you flipped the last column of Vt; V's last column is Vt's last row: Vt[-1, :] *= -1 "
                "(or U[:, -1] *= -1)"
            )
    return "a rotation, but not the closest one to M: take U V^T from the SVD of M"


def _gram_schmidt(M):
    Q, Rr = np.linalg.qr(M)
    return Q * np.sign(np.diag(Rr))


def nearest_rotation(M):
    """The rotation nearest to M in the Frobenius norm.

    U V^T from the SVD M = U S V^T, with the last column of U flipped if det(U V^T) = -1.

    Parameters
    ----------
    M : (3, 3) ndarray
        A matrix close to a rotation (r1, r2, r1 x r2 from one homography, say).

    Returns
    -------
    (3, 3) ndarray
        The rotation R (R^T R = I, det R = 1) that minimises ||R - M||_F.

    References
    ----------
    Z. Zhang (2000), "A flexible new technique for camera calibration", IEEE TPAMI 22(11), appendix C.
    """
    U, _, Vt = np.linalg.svd(M)
    if np.linalg.det(U @ Vt) < 0:
        U[:, -1] *= -1
    return U @ Vt


register_exercise(
    Exercise(
        name="nearest_rotation",
        lesson="08",
        reference=camera.nearest_rotation,
        cases=_rotation_cases,
        compare=same_array(rtol=1e-8, atol=1e-10),
        diagnose=_rotation_diagnosis,
        wrong_variants=(
            (lambda M: (lambda U, S, Vt: U @ Vt)(*np.linalg.svd(M)), "det R = -1"),
            (lambda M: M / np.linalg.norm(M, axis=0), "not orthonormal"),
            (_gram_schmidt, "not the closest"),
            (
                lambda M: (lambda U, S, Vt: U @ np.diag([1.0, 1.0, -1.0]) @ Vt)(*np.linalg.svd(M)),
                "already +1",
            ),
            (lambda M: (lambda U, S, Vt: U @ Vt.T)(*np.linalg.svd(M)), "third output"),
            (lambda M: camera.nearest_rotation(M).T, "transpose"),
            (
                lambda M: (lambda U, S, Vt: -(U @ Vt) if np.linalg.det(U @ Vt) < 0 else U @ Vt)(
                    *np.linalg.svd(M)
                ),
                "negated the whole matrix",
            ),
        ),
        teaching=nearest_rotation,
        ndarray_only=True,
    )
)
