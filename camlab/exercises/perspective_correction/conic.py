"""Exercise 4 of lesson 10: the image of the dual conic C*inf from right angles (`dual_conic_from_orthogonal_lines`)."""

from __future__ import annotations

import itertools

import numpy as np

from ... import perspective as pp
from ...projective import map_points
from .._answers import same_up_to_scale, shape_problem
from .._core import Exercise, register_exercise


def _grid_photo(G) -> np.ndarray:
    """The image corners of a 6 x 9 grid of unit squares seen through the plane homography G."""
    plane = np.stack(np.meshgrid(np.arange(9.0), np.arange(6.0)), axis=-1).reshape(-1, 2)
    return map_points(np.asarray(G, dtype=float), plane).reshape(6, 9, 2)


def _conic_cases():
    Gs = [
        [[40.0, 8.0, 150.0], [-5.0, 32.0, 90.0], [0.03, 0.02, 1.0]],
        [[30.0, -12.0, 300.0], [10.0, 35.0, 60.0], [-0.02, 0.045, 1.0]],
        [
            [25.0, 0.0, 200.0],
            [0.0, 25.0, 100.0],
            [0.0, 0.06, 1.0],
        ],  # tilt only, like a keystone photo
    ]
    cases = [pp.square_grid_right_angles(_grid_photo(G)) for G in Gs]
    return cases + [_over_determined(Gs[0])]


def _line_through(p: np.ndarray) -> np.ndarray:
    """The line (a, b, c) through the first and last of the points ``p`` (exact corners: all on it).

    Scaled to a unit normal (a^2 + b^2 = 1), as ``pp.square_grid_right_angles`` returns its lines.
    """
    line = np.cross([*p[0], 1.0], [*p[-1], 1.0])
    return line / np.linalg.norm(line[:2])


def _over_determined(G):
    """An over-determined case: 56 pairs, every row against every column, the diagonals in the middle.

    The grid's 54 row-against-column pairs, with its blocks' two diagonal pairs after the 27th. Any
    five of the first 27 or the last 27 are right angles between one pair of directions (rank 4), so
    a solver that uses five pairs, not all of them, is caught.
    """
    g = _grid_photo(G)
    rows_cols = [(_line_through(r), _line_through(c)) for r in g for c in g.transpose(1, 0, 2)]
    L, M = pp.square_grid_right_angles(g)
    pairs = rows_cols[:27] + list(zip(L[4:], M[4:], strict=True)) + rows_cols[27:]
    return pp.OrthogonalLinePairs(np.array([p[0] for p in pairs]), np.array([p[1] for p in pairs]))


def _conic_rows(lines_l, lines_m, half=True):
    """The rows of section 8, one per pair; ``half=False``: the cross terms without their 1/2."""
    (l1, l2, l3), (m1, m2, m3) = np.asarray(lines_l, float).T, np.asarray(lines_m, float).T
    k = 0.5 if half else 1.0
    cols = [
        l1 * m1,
        k * (l1 * m2 + l2 * m1),
        l2 * m2,
        k * (l1 * m3 + l3 * m1),
        k * (l2 * m3 + l3 * m2),
        l3 * m3,
    ]
    return np.stack(cols, axis=1)


def _conic_matrix(x, half=True):
    """(a, b, c, d, e, f) arranged as the symmetric matrix, b/2, d/2, e/2 off the diagonal (``half=False``: b, d, e)."""
    a, b, c, d, e, f = x
    k = 0.5 if half else 1.0
    return np.array([[a, k * b, k * d], [k * b, c, k * e], [k * d, k * e, f]])


def _conic_vector(C):
    """The matrix's (a, b, c, d, e, f), as section 8 names them."""
    return np.array([C[0, 0], 2 * C[0, 1], C[1, 1], 2 * C[0, 2], 2 * C[1, 2], C[2, 2]])


_UNKNOWNS = "a b c d e f".split()


def _same_dual_conic(got, expected, rtol=1e-3) -> bool:
    """Equal up to scale, after rescaling the image axes so that expected's diagonal is 1.

    In pixels the entries of C*' span many orders of magnitude (a ~ 1, f ~ 1e5), so a plain relative
    comparison weighs f alone; D C D with D = diag(|expected_ii|^-1/2) is the same conic in other
    pixel units (a change of coordinates, x -> D x), where every entry counts. rtol 1e-3 passes any
    sound solver of the stacked rows (an SVD of the rows, with or without Hartley conditioning, or the
    smallest eigenvector of A^T A, which squares the rows' condition number and lands about 1e-4 away on
    these pixel lines) and rejects each typical slip by orders of magnitude more.
    """
    e = np.asarray(expected, dtype=float)
    D = np.diag(1 / np.sqrt(np.abs(np.diag(e))))
    g = np.asarray(got, dtype=float)
    if g.shape != e.shape:
        return False
    return same_up_to_scale(D @ g @ D, D @ e @ D, rtol=rtol)


_NOT_UNDONE = (
    "your matrix is a dual conic of rank 2, as the image of C*inf is, but not the one of these lines: "
    "the pairs are not orthogonal under it. Did you normalise the lines (l_hat = T^-T l, with T from "
    "lesson 07's point normalisation) and then return C_hat, the conic of the normalised image, or undo "
    "the change of coordinates the wrong way (T C_hat T^T, with T for T^-1; or T^-T C_hat T^-1, "
    "transposed)? A dual conic moves like a point's outer product: C_hat = T C*' T^T, so "
    "C*' = T^-1 C_hat T^-T."
)
"""Ex 4's hint for a rank-2 conic of other coordinates: normalisation not undone, or undone wrongly."""


def _conic_diagnosis(args, got, expected) -> str:
    g = np.asarray(got, dtype=float) if np.size(got) else np.asarray(got)
    if g.shape == (6,):
        return (
            "you returned the null vector (a, b, c, d, e, f); arrange it as the symmetric 3 x 3 matrix "
            "[[a, b/2, d/2], [b/2, c, e/2], [d/2, e/2, f]]."
        )
    problem = shape_problem(got, expected)
    if problem:
        return problem
    if not np.allclose(g, g.T, rtol=1e-6, atol=1e-9 * np.abs(g).max()):
        return (
            "your matrix is not symmetric: a dual conic is; put b/2 at [0, 1] and [1, 0], d/2 at [0, 2] "
            "and [2, 0], e/2 at [1, 2] and [2, 1]."
        )
    lines_l, lines_m = args
    e = np.asarray(expected, dtype=float)
    off = np.ones((3, 3)) - np.eye(3)
    if _same_dual_conic(g * (1 - off / 2), e):
        return (
            "the off-diagonal entries are twice too big: the row's cross terms (l1 m2 + l2 m1) multiply b, "
            "and the matrix holds b/2 (as in a conic's matrix); either halve the cross terms in each row or "
            "put b/2, d/2, e/2 into the matrix."
        )
    if _same_dual_conic(g * (1 + off), e):
        return (
            "the off-diagonal entries are half what they should be: your rows have the full cross terms "
            "(l1 m2 + l2 m1, no 1/2), so the unknown they multiply is already the matrix entry, and you "
            "halved it again. Halve once: the 1/2 in the rows (as in section 8) or b/2 in the matrix, not both."
        )
    want = _conic_vector(e)
    mine = _conic_vector(g)
    for perm in itertools.permutations(range(6)):
        if perm != tuple(range(6)) and same_up_to_scale(mine, want[list(perm)], rtol=1e-4):
            moved = [
                f"{_UNKNOWNS[i]} where {_UNKNOWNS[p]} belongs" for i, p in enumerate(perm) if i != p
            ]
            return (
                "your entries are the right numbers in the wrong places ("
                + ", ".join(moved)
                + "): the "
                "columns of your rows and the unknowns you arrange into the matrix must be in the same order, "
                "(a, b, c, d, e, f) for l1 m1, (l1 m2 + l2 m1)/2, l2 m2, (l1 m3 + l3 m1)/2, (l2 m3 + l3 m2)/2, "
                "l3 m3, and the matrix [[a, b/2, d/2], [b/2, c, e/2], [d/2, e/2, f]]."
            )
    for half in (True, False):
        Vt = np.linalg.svd(_conic_rows(lines_l, lines_m, half))[2]
        if same_up_to_scale(g, _conic_matrix(Vt[:, -1], half), rtol=1e-5):
            return (
                "you took a column of Vt. np.linalg.svd returns Vt, V transposed: the right singular "
                "vectors are its rows, so the null vector is the last row, Vt[-1], not Vt[:, -1]."
            )
        if same_up_to_scale(g, _conic_matrix(Vt[0], half), rtol=1e-5):
            return (
                "you took the direction of the LARGEST singular value (the FIRST row of Vt, or the last "
                "eigenvector of np.linalg.eigh(A.T @ A), whose eigenvalues come in ascending order); the null "
                "vector (the smallest singular value, 0 here) is the LAST row of Vt, Vt[-1]."
            )
    if slip := _sign_or_inverse_slip(g, lines_l, lines_m, e):
        return slip
    residual, _ = _residual_and_eigenvalues(g, e, lines_l, lines_m)
    if residual > 1e-4 and (few := _pairs_used(g, e, lines_l, lines_m)):
        return few
    if residual > 1e-4 and _own_rank(g) == 2:
        return _NOT_UNDONE
    if residual > 1e-4:
        return (
            f"your matrix does not make the pairs orthogonal: the rows times your (a, b, c, d, e, f) reach "
            f"{residual:.2g} (relative), where the answer gives 0. Check each row against section 8 (one row "
            "per pair, the 1/2 on the cross terms) and take the null vector, the last row of Vt."
        )
    return (
        "every pair satisfies l^T C m = 0 but only roughly (your matrix is close to the answer, not within "
        "1e-3 of it): a solver that squares the rows' condition number (np.linalg.eigh(A.T @ A), np.linalg.inv "
        "of normal equations) loses digits on pixel lines; take the SVD of the rows themselves, or normalise "
        "the lines first (lesson 07, section 6)."
    )


def _own_rank(g) -> int:
    """``g``'s rank judged in its own scale: rescaled by its own diagonal, singular values over the largest.

    A badly scaled wrong answer looks singular in the expected matrix's units; in its own it does not.
    """
    d = np.abs(np.diag(g))
    d = np.where(d > 1e-300 * max(d.max(), 1e-300), d, 1.0)
    s = np.linalg.svd(g / np.sqrt(np.outer(d, d)), compute_uv=False)
    return int(np.sum(s > 1e-8 * s[0])) if s[0] > 0 else 0


def _residual_and_eigenvalues(g, e, lines_l, lines_m):
    """The rows' relative residual under ``g`` and ``g``'s |eigenvalues|, in rescaled pixel units.

    Judged where every entry counts (x -> D x, lines by D^-1, dual conics by D C D, D from the
    answer ``e``): in pixels any such matrix has a tiny smallest eigenvalue, right or wrong.
    """
    D = np.diag(1 / np.sqrt(np.abs(np.diag(e))))
    Dinv = np.linalg.inv(D)
    rows = _conic_rows(np.asarray(lines_l, float) @ Dinv, np.asarray(lines_m, float) @ Dinv)
    mine_d = _conic_vector(D @ g @ D)
    residual = np.linalg.norm(rows @ mine_d) / (np.linalg.norm(rows, 2) * np.linalg.norm(mine_d))
    return residual, np.abs(np.linalg.eigvalsh(D @ g @ D))


def _pairs_used(g, e, lines_l, lines_m) -> str | None:
    """The hint for an answer that satisfies the first (or last) five pairs exactly, not all N."""
    D = np.diag(1 / np.sqrt(np.abs(np.diag(e))))
    Dinv = np.linalg.inv(D)
    rows = _conic_rows(np.asarray(lines_l, float) @ Dinv, np.asarray(lines_m, float) @ Dinv)
    rows /= np.linalg.norm(rows, axis=1, keepdims=True)
    mine = _conic_vector(D @ g @ D)
    each = np.abs(rows @ mine) / np.linalg.norm(mine)
    for part, which in (("first", slice(0, 5)), ("last", slice(-5, None))):
        if len(rows) > 5 and each[which].max() < 1e-8 < each.max():
            return (
                f"your matrix satisfies the {part} five pairs exactly but not the other {len(rows) - 5}: "
                "you used five pairs, not all N. Five fix C* only when they are independent; here those "
                "five are all right angles between the grid's rows and columns, one pair of directions, "
                "which fix only 4 of its 5 degrees of freedom (section 8), and with measured lines no "
                "five agree with the rest. Stack one row per pair, all N of them, and take the null "
                "vector of the whole stack (Vt[-1]: the least-squares answer when the rows disagree)."
            )
    return None


def _sign_or_inverse_slip(g, lines_l, lines_m, e) -> str | None:
    """A cross term with the wrong sign (in the matrix or in the rows), or the inverse returned."""
    names, places, cols = ("b", "d", "e"), ((0, 1), (0, 2), (1, 2)), (1, 3, 4)
    (L1, L2, L3), (M1, M2, M3) = np.asarray(lines_l, float).T, np.asarray(lines_m, float).T
    minus = ((L1 * M2 - L2 * M1) / 2, (L1 * M3 - L3 * M1) / 2, (L2 * M3 - L3 * M2) / 2)
    for r in range(1, 4):
        for which in itertools.combinations(range(3), r):
            flipped = g.copy()
            rows = _conic_rows(lines_l, lines_m)
            for k in which:
                i, j = places[k]
                flipped[i, j], flipped[j, i] = -g[i, j], -g[j, i]
                rows[:, cols[k]] = minus[k]
            named = " and ".join(
                [", ".join(names[k] for k in which[:-1]), names[which[-1]]][r == 1 :]
            )
            if _same_dual_conic(flipped, e):
                return (
                    f"{'the sign of ' + named + ' is' if r == 1 else 'the signs of ' + named + ' are'} flipped in "
                    "your matrix (np.abs, or a minus sign): the matrix is "
                    "[[a, b/2, d/2], [b/2, c, e/2], [d/2, e/2, f]] with the null vector's entries as they come."
                )
            if _same_dual_conic(g, _conic_matrix(np.linalg.svd(rows)[2][-1]), rtol=1e-4):
                return (
                    f"a cross term of your rows has the wrong sign (the column of {named}): l^T C m sums "
                    "l_i m_j + l_j m_i for each pair of indices, so the row holds (l1 m2 + l2 m1)/2, "
                    "(l1 m3 + l3 m1)/2 and (l2 m3 + l3 m2)/2, all with a plus."
                )
    if np.all(np.isfinite(g)) and _same_dual_conic(np.linalg.pinv(g), e, rtol=1e-2):
        return (
            "your matrix is the (pseudo-)inverse of the answer, a point conic: the right angles constrain "
            "the DUAL conic itself, l^T C* m = 0, so the null vector arranged as a matrix is the answer; "
            "do not invert it."
        )
    return None


def dual_conic_from_orthogonal_lines(lines_l, lines_m):
    """Each orthogonal pair gives l^T C* m = 0, one linear equation in (a, b, c, d, e, f); take the null vector.

    Parameters
    ----------
    lines_l, lines_m : (N, 3) array_like
        Image lines (a, b, c), N >= 5; ``lines_l[i]`` is orthogonal to ``lines_m[i]`` on the plane.

    Returns
    -------
    (3, 3) ndarray
        The image of the dual conic C*inf, symmetric, up to scale.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 2.7.5, example 2.27.
    """
    (l1, l2, l3), (m1, m2, m3) = np.asarray(lines_l, float).T, np.asarray(lines_m, float).T
    rows = np.stack(
        [
            l1 * m1,
            (l1 * m2 + l2 * m1) / 2,
            l2 * m2,
            (l1 * m3 + l3 * m1) / 2,
            (l2 * m3 + l3 * m2) / 2,
            l3 * m3,
        ],
        axis=1,
    )
    # Unconditioned pixel-scale rows are fine for the exact or mildly noisy lines of this
    # exercise; with real measurements condition first (lesson 07's T, lines moved by T^-T,
    # the conic back by T^-1 C T^-T), as section 8's cell and pp.dual_conic_rows do.
    a, b, c, d, e, f = np.linalg.svd(rows)[2][-1]  # the null vector: the last row of Vt
    return np.array([[a, b / 2, d / 2], [b / 2, c, e / 2], [d / 2, e / 2, f]])


def _full_cross_terms(lines_l, lines_m):
    """A typical slip: b, d, e (not b/2, d/2, e/2) off the diagonal."""
    C = pp.dual_conic_from_orthogonal_lines(lines_l, lines_m)
    return C * (1 + (np.ones((3, 3)) - np.eye(3)))


def _first_singular_vector(lines_l, lines_m):
    """A typical slip: the first row of Vt (the largest singular value) instead of the last."""
    return _conic_matrix(np.linalg.svd(_conic_rows(lines_l, lines_m))[2][0])


def _upper_triangle_only(lines_l, lines_m):
    """A typical slip: the coefficients written into the upper triangle only."""
    return np.triu(_full_cross_terms(lines_l, lines_m))


def _normalised_not_undone(lines_l, lines_m):
    """A typical slip: lines conditioned by l_hat = T^-T l, and C_hat returned without T^-1 C_hat T^-T."""
    T = np.array([[1 / 300, 0, -320 / 300], [0, 1 / 300, -240 / 300], [0, 0, 1]])
    move = np.linalg.inv(T).T  # lines: l_hat = T^-T l; as rows, l @ T^-1
    return pp.dual_conic_from_orthogonal_lines(
        np.asarray(lines_l) @ move.T, np.asarray(lines_m) @ move.T
    )


def _undone_wrong_way(transposed):
    """A typical slip: normalised as in :func:`_normalised_not_undone`, then undone by T (or T^-T) instead of T^-1."""
    T = np.array([[1 / 300, 0, -320 / 300], [0, 1 / 300, -240 / 300], [0, 0, 1]])

    def wrong(lines_l, lines_m):
        C_hat = _normalised_not_undone(lines_l, lines_m)
        U = np.linalg.inv(T).T if transposed else T
        return U @ C_hat @ U.T

    return wrong


register_exercise(
    Exercise(
        name="dual_conic_from_orthogonal_lines",
        lesson="10",
        reference=pp.dual_conic_from_orthogonal_lines,
        cases=_conic_cases,
        compare=_same_dual_conic,
        diagnose=_conic_diagnosis,
        wrong_variants=(
            (_full_cross_terms, "twice too big"),
            (_first_singular_vector, "LAST row of Vt"),
            (_upper_triangle_only, "not symmetric"),
            (
                lambda L, M: np.linalg.svd(_conic_rows(L, M))[2][-1],
                "null vector (a, b, c, d, e, f)",
            ),
            (
                lambda L, M: _conic_matrix(np.linalg.svd(_conic_rows(L, M, half=False))[2][-1]),
                "half what they should be",
            ),
            (
                lambda L, M: _conic_matrix(
                    _conic_vector(pp.dual_conic_from_orthogonal_lines(L, M))[[0, 1, 2, 4, 3, 5]]
                ),
                "d where e belongs",
            ),
            (
                lambda L, M: _conic_matrix(np.linalg.svd(_conic_rows(L, M))[2][:, -1]),
                "column of Vt",
            ),
            (_normalised_not_undone, "T^-1 C_hat T^-T"),
            (_undone_wrong_way(False), "with T for T^-1"),
            (_undone_wrong_way(True), "transposed"),
            (
                lambda L, M: pp.dual_conic_from_orthogonal_lines(L, M) * np.where(np.eye(3), 1, -1),
                "signs of b, d and e are flipped",
            ),
            (
                lambda L, M: np.linalg.pinv(pp.dual_conic_from_orthogonal_lines(L, M)),
                "(pseudo-)inverse",
            ),
            (
                lambda L, M: _conic_matrix(np.linalg.svd(_conic_rows(L[:5], M[:5]))[2][-1]),
                "five pairs, not all N",
            ),
            (  # badly scaled and not rank 2: must not get the "normalisation not undone" hint
                lambda L, M: sum(
                    np.outer(a, b) + np.outer(b, a)
                    for a, b in zip(np.asarray(L, float), np.asarray(M, float), strict=True)
                ),
                "does not make the pairs orthogonal",
            ),
        ),
        ndarray_only=True,
        teaching=dual_conic_from_orthogonal_lines,
    )
)


# --------------------------------------------------------------------------- aspect ratio and f from four corners
