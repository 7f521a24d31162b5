"""Lesson 04's exercise rq_decomposition: M = K R with K upper triangular (positive diagonal) and R a rotation."""

from __future__ import annotations

import numpy as np

from ... import camera as cm
from .._core import Exercise, register_exercise
from ._scenes import cameras

# -- rq_decomposition ----------------------------------------------------------------------
# (The whole decomposition returns four arrays of different shapes, which the checker cannot
# print; the exercise is its heart, M = K R, and the lesson derives t and C from it.)


def _rq_cases():
    cams = cameras()
    return [
        (cams[0].P[:, :3],),
        (2.5 * cams[1].P[:, :3],),
        (0.003 * cams[2].P[:, :3],),
        (
            cm.intrinsic_matrix(700, 650, 300, 200, 5.0)
            @ cm.rotation_from_axis_angle([0.3, -2.0, 0.5]),
        ),
        (-2.5 * cams[0].P[:, :3],),
    ]  # det M < 0 (lesson 04, section 4): K R = M still, so det R = -1


def _rq_compare(got, expected) -> bool:
    try:
        K, R = (np.asarray(g, dtype=float) for g in got)
    except (TypeError, ValueError):
        return False
    return K.shape == R.shape == (3, 3) and bool(
        np.allclose(K, expected[0], rtol=1e-7, atol=1e-7)
        and np.allclose(R, expected[1], rtol=1e-7, atol=1e-7)
    )


def _rq_diagnosis(args, got, expected) -> str:
    (M,) = args
    raw = _raw_opencv_cause(got)
    if raw:
        return raw
    try:
        K, R = (np.asarray(g, dtype=float) for g in got)
        assert K.shape == R.shape == (3, 3)
    except (TypeError, ValueError, AssertionError):
        return "return a pair (K, R) of (3, 3) arrays"
    scale = 1e-6 * np.abs(M).max()
    if np.linalg.det(M) < 0 and np.allclose(K @ R, -M, rtol=1e-6, atol=scale):
        return (
            "K R = -M: you made det R = +1 by a sign change, either negating R after the sign fix or factoring "
            "-M instead of M (step 1 of section 4); both give this same pair. Flipping the sign belongs to "
            "decomposing a camera, where -P is the same camera; here M must come back as K R exactly. For "
            "det M < 0 a K with a positive diagonal forces det R = -1, a reflection: the sign that tells the "
            "camera decomposition to flip P first."
        )
    reproduces = np.allclose(K @ R, M, rtol=1e-6, atol=1e-6 * np.abs(M).max())
    orthogonal = np.allclose(R @ R.T, np.eye(3), atol=1e-6)
    k_orthogonal = np.allclose(K @ K.T, np.eye(3), atol=1e-6)
    r_triangular = np.abs(np.tril(R, -1)).max() <= 1e-9 * np.abs(R).max()
    if reproduces and not orthogonal and k_orthogonal and r_triangular:
        return (
            "your pair is a QR factorisation, M = Q U: the orthogonal factor comes first, the triangular one "
            "second (np.linalg.qr(M) returned as it is). RQ is the other order, M = K R with the triangular K "
            "first; M = Q U cannot be rearranged into it. Use scipy.linalg.rq, or the exchange-matrix trick of "
            "the prompt: the QR of (E M)^T, then K = E U^T E and R = E Q^T."
        )
    if reproduces and not orthogonal:
        gram = np.diag(R @ R.T)
        if np.allclose(gram, gram[0], rtol=1e-6):
            return (
                f"K R = M, but R is not orthogonal: R R^T = {gram[0]:.4g} I, so R carries a scale (did you divide "
                f"K by K[2, 2] and multiply R by it?). R must be a rotation or reflection, R R^T = I; the scale of M "
                f"stays in K (K[2, 2] carries it)."
            )
        return (
            "K R = M, but R is not orthogonal (R R^T != I): R must be a rotation or a reflection."
        )
    if np.isclose(K[2, 2], 1.0) and not reproduces and not np.isclose(abs(M[2] @ M[2]), 1.0):
        if np.all(np.diag(K) > 0):  # the signs were fixed first: only the scale is wrong
            return (
                f"you divided K by K[2, 2], so K R = M / {np.sqrt(abs(M[2] @ M[2])):.4g} and no longer M. Your "
                f"signs are right; keep K unnormalised: here K[2, 2] carries M's scale (a camera's K is divided "
                f"by K[2, 2] only after t = K^-1 p4, section 4 step 3, not in the RQ decomposition)."
            )
        return (
            "you divided K by K[2, 2], so K R = M / K[2, 2] and no longer M; and a negative K[2, 2] "
            "does not fix the signs. Keep K unnormalised (K[2, 2] carries M's scale) and fix the signs "
            "with D = diag(sign(diag(K))): K D and D R."
        )
    if not reproduces:
        return _unreproduced_cause(K, R, M)
    if np.abs(np.tril(K, -1)).max() > 1e-9 * np.abs(K).max():
        if np.abs(np.triu(K, 1)).max() <= 1e-9 * np.abs(K).max():
            return (
                "K R = M, but your K is lower triangular: that is an LQ factorisation (the QR of M^T, transposed: "
                "M^T = Q U gives M = U^T Q^T). A camera's K is upper triangular: use scipy.linalg.rq, or the "
                "exchange-matrix trick of the prompt, E U^T E and E Q^T from the QR of (E M)^T."
            )
        return "K must be upper triangular."
    if np.any(np.diag(K) < 0) and np.linalg.det(M) < 0 and np.linalg.det(R) > 0:
        return _opencv_k33_note(K) + (
            "det M < 0 here, and your R is a rotation (det R = +1), so K must carry the minus sign: K R = M with "
            "a positive-diagonal K forces det K > 0 and so det R = det M / det K < 0, a reflection. Do not "
            "negate K and R (or K's last column and R's last row) to make det R = +1; fix only the signs of "
            "diag(K) with D = diag(sign(diag(K))), K D and D R, and let det R = -1. Making det R = +1 by "
            "flipping P belongs to decomposing a camera (section 4, step 1), not to the RQ decomposition."
        )
    if np.any(np.diag(K) < 0):
        return (
            "K has a negative diagonal entry: fix the signs. RQ is unique only up to D = diag(+-1); "
            "use K D and D R with D = diag(sign(diag(K)))."
        )
    return "K R = M with K positive upper triangular, but the factors differ; is R orthogonal?"


def _opencv_k33_note(K) -> str:
    """A note naming cv2.RQDecomp3x3 when K has a positive fx, fy and K[2, 2] < 0, as it returns."""
    if np.all(np.diag(K)[:2] > 0) and K[2, 2] < 0:
        return "This is what cv2.RQDecomp3x3 returns: it keeps det R = +1 and leaves the minus sign in K[2, 2]. "
    return ""


def _raw_opencv_cause(got) -> str | None:
    """The cause when ``got`` is cv2.RQDecomp3x3's output, or its first two items, rather than (K, R)."""
    if not isinstance(got, (tuple, list)) or len(got) not in (2, 6):
        return None
    try:
        first = np.asarray(got[0], dtype=float)
    except (TypeError, ValueError):
        return None
    if first.shape != (3,):
        return None
    what = "all six of its outputs" if len(got) == 6 else "its first two outputs"
    return (
        f"you returned {what} of cv2.RQDecomp3x3: it returns the Euler angles (degrees) first, then K, R and "
        f"the three rotations Qx, Qy, Qz. Take K, R = cv2.RQDecomp3x3(M)[1:3], then fix the signs as section 4 "
        f"does (OpenCV keeps det R = +1 and leaves a minus sign of M in K[2, 2])."
    )


def _unreproduced_cause(K, R, M) -> str:
    """The cause when K R does not give M back.

    Swapped, QR instead of RQ, a misplaced or partial sign fix, a transposed factor.
    """
    if np.allclose(R @ K, M, rtol=1e-6, atol=1e-6 * np.abs(M).max()):
        if np.abs(np.tril(K, -1)).max() > 1e-6 * np.abs(K).max() and np.allclose(
            K @ K.T, np.eye(3), atol=1e-6
        ):
            return (
                "you returned (R, K): the order is swapped. Return K first, then R: `return K, R`."
            )
        return "you computed M = Q K (a QR decomposition); the camera needs M = K R with K on the left (RQ)."
    misplaced = _sign_fix_misplaced(K, R, M)
    if misplaced:
        return misplaced
    if np.allclose(K @ R.T, M, rtol=1e-6, atol=1e-6 * np.abs(M).max()):
        return "R is transposed: M = K R."
    if np.allclose(K.T @ R, M, rtol=1e-6, atol=1e-6 * np.abs(M).max()):
        return "K is transposed (lower triangular): M = K R with K upper triangular; return K itself, not K.T."
    if _signs_fixed_in_k_only(K, R, M):
        return (
            "you fixed the signs of K (K D) but not of R: K R = (K D)(D R), so apply the same "
            "D = diag(sign(diag(K))) to R's rows too (D R), or K R no longer equals M."
        )
    if _diagonal_made_positive(K, R, M):
        return (
            "you made the entries of K's diagonal positive one by one (abs() of the diagonal, or a sign flip of the "
            "diagonal entries alone), and left R as RQ gave it: the off-diagonal entries of K and the rows of R "
            "kept their old signs, so K R is no longer M. Flip whole columns of K and the same rows of R: "
            "D = diag(sign(diag(K))), K D and D R."
        )
    return "K R does not reproduce M; an RQ decomposition must satisfy M = K R exactly."


def sign_flips():
    """The seven D = diag(+-1) other than I.

    Returns
    -------
    list of (3, 3) ndarray
        Every diagonal matrix of +1 and -1 except the identity.
    """
    return [
        np.diag(signs) for signs in np.array(np.meshgrid(*[[1.0, -1.0]] * 3)).reshape(3, -1).T[1:]
    ]


def _sign_fix_misplaced(K, R, M) -> str | None:
    """The cause when D was applied on the wrong side: R @ D (R's columns) or D @ K (K's rows)."""
    scale = 1e-6 * np.abs(M).max()
    for D in sign_flips():
        if np.allclose(K @ D @ R @ D, M, rtol=1e-6, atol=scale):
            return (
                "you applied D to R's columns (R @ D). K R = (K D)(D R): D flips K's columns (K @ D) "
                "and R's rows (D @ R), so that D D = I cancels between them."
            )
        if np.allclose(D @ K @ R @ D, M, rtol=1e-6, atol=scale):
            return (
                "you applied D on the wrong side of both factors: D @ K flips K's rows and R @ D flips R's "
                "columns. K R = (K D)(D R): D flips K's columns (K @ D) and R's rows (D @ R), so that D D = I "
                "cancels between them."
            )
        if np.allclose(D @ K @ D @ R, M, rtol=1e-6, atol=scale):
            return (
                "you applied D to K's rows (D @ K). K R = (K D)(D R): D flips K's columns (K @ D) "
                "and R's rows (D @ R), so that D D = I cancels between them."
            )
    return None


def _diagonal_made_positive(K, R, M) -> bool:
    """True if K is the raw RQ's K with only its diagonal made positive and R the raw R (up to D).

    The raw factors are (K0 D, D R0) for some D, where (K0, R0) is the sign-fixed RQ of M; a diagonal made
    positive entry by entry leaves diag(K) = diag(K0) but K's other entries and R's rows with D's signs.
    """
    from scipy.linalg import rq

    K0, R0 = rq(M)
    fix = np.diag(np.sign(np.diag(K0)))
    K0, R0 = K0 @ fix, fix @ R0
    if not np.allclose(np.diag(K), np.diag(K0), rtol=1e-6):
        return False
    for D in sign_flips():
        if np.allclose(R, D @ R0, atol=1e-6):
            K_raw = K0 @ D
            return bool(
                np.allclose(
                    K - np.diag(np.diag(K)),
                    K_raw - np.diag(np.diag(K_raw)),
                    rtol=1e-6,
                    atol=1e-6 * np.abs(M).max(),
                )
            )
    return False


def _signs_fixed_in_k_only(K, R, M) -> bool:
    """True if K D R = M for some D = diag(+-1) other than I (K's columns flipped, R's rows not)."""
    scale = 1e-6 * np.abs(M).max()
    for D in sign_flips():
        if np.allclose(K @ D @ R, M, rtol=1e-6, atol=scale):
            return True
    return False


def _rq_signs_of_k_only(M):
    from scipy.linalg import rq

    K, R = rq(M)
    return K @ np.diag(np.sign(np.diag(K))), R


def _rq_no_sign_fix(M):
    from scipy.linalg import rq

    return rq(M)


def _rq_normalised_no_sign_fix(M):
    from scipy.linalg import rq

    K, R = rq(M)
    return K / K[2, 2], R


def _rq_sign_fix_on_columns_of_r(M):
    from scipy.linalg import rq

    K, R = rq(M)
    D = np.diag(np.sign(np.diag(K)))
    return K @ D, R @ D


def _rq_sign_fix_on_rows_of_k(M):
    from scipy.linalg import rq

    K, R = rq(M)
    D = np.diag(np.sign(np.diag(K)))
    return D @ K, D @ R


def _rq_forced_rotation(M):
    """Signs fixed, then K and R negated to make det R = +1 (K R = M still, but diag K < 0 when det M < 0)."""
    K, R = cm.rq_decomposition(M)
    return (-K, -R) if np.linalg.det(R) < 0 else (K, R)


def _rq_qr(M):
    Q, U = np.linalg.qr(M)
    return U, Q


def _rq_qr_as_is(M):
    return tuple(np.linalg.qr(M))  # (Q, U): QR's order, orthogonal first


def rq_decomposition(M):
    """M = K R with K upper triangular (positive diagonal) and R orthogonal, from numpy's QR.

    Parameters
    ----------
    M : (3, 3) array_like
        An invertible matrix (the left 3 x 3 block of a camera matrix).

    Returns
    -------
    K : (3, 3) ndarray
        Upper triangular, with a positive diagonal.
    R : (3, 3) ndarray
        Orthogonal (det R = sign of det M), with K R = M.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 6.2.4 and appendix A4.1.1.
    """
    E = np.eye(3)[::-1]  # the exchange matrix reverses row order; E = E^T = E^-1
    Q, U = np.linalg.qr((E @ M).T)  # (E M)^T = Q U, so M = (E U^T E)(E Q^T)
    K, R = E @ U.T @ E, E @ Q.T  # E U^T E is upper triangular
    D = np.diag(np.sign(np.diag(K)))  # K R = (K D)(D R): flip signs so diag(K) > 0
    return K @ D, D @ R


register_exercise(
    Exercise(
        name="rq_decomposition",
        lesson="04",
        reference=cm.rq_decomposition,
        cases=_rq_cases,
        compare=_rq_compare,
        diagnose=_rq_diagnosis,
        wrong_variants=(
            (_rq_no_sign_fix, "fix the signs"),
            (_rq_normalised_no_sign_fix, "divided K by K[2, 2]"),
            (
                lambda M: (lambda K, R: (K / K[2, 2], R))(*cm.rq_decomposition(M)),
                "Your signs are right",
            ),
            (_rq_qr, "QR decomposition"),
            (_rq_qr_as_is, "your pair is a QR factorisation"),
            (
                lambda M: (lambda Q, U: (U.T, Q.T))(*np.linalg.qr(np.asarray(M).T)),
                "lower triangular",
            ),
            (_rq_signs_of_k_only, "apply the same"),
            (lambda M: (lambda K, R: (K, R.T))(*cm.rq_decomposition(M)), "transposed"),
            (lambda M: (lambda K, R: (K.T, R))(*cm.rq_decomposition(M)), "K is transposed"),
            (lambda M: cm.rq_decomposition(M)[::-1], "order is swapped"),
            (_rq_sign_fix_on_columns_of_r, "R's columns"),
            (_rq_sign_fix_on_rows_of_k, "K's rows"),
            (
                lambda M: cm.rq_decomposition(np.sign(np.linalg.det(M)) * np.asarray(M)),
                "factoring -M instead of M",
            ),
            (
                lambda M: (lambda K, R: (K, np.sign(np.linalg.det(R)) * R))(
                    *cm.rq_decomposition(M)
                ),
                "negating R",
            ),
            (_rq_forced_rotation, "R is a rotation (det R = +1)"),
            (
                lambda M: (lambda K, R: (K / K[2, 2], R * K[2, 2]))(*cm.rq_decomposition(M)),
                "R is not orthogonal",
            ),
        ),
        teaching=rq_decomposition,
    )
)
