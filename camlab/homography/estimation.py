r"""Estimating a homography from point pairs: the normalised DLT, the error measures, RANSAC.

:func:`estimate_homography` solves :math:`x' \times H x = 0` by SVD after Hartley's
normalisation [1]_ [2]_; :func:`transfer_error`, :func:`symmetric_transfer_error`
and :func:`sampson_distance` measure a fit; :func:`ransac_homography` finds H among outliers
(:func:`camlab.robust.ransac` with :class:`HomographyModel`).
Part of :mod:`camlab.homography` (every name here is importable from there).

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 4.4 and algorithm 4.2
   (the normalised DLT).
.. [2] R. I. Hartley, 1997, "In defense of the eight-point algorithm", *IEEE Transactions on Pattern
   Analysis and Machine Intelligence* 19(6), 580-593.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    CamlabInputError,
    DegenerateError,
)
from ..projective import hartley_normalise, map_points
from ..robust import MinimalModels, PairModel, ransac
from .core import check_correspondences, check_homography, normalise_homography

__all__ = [
    "HomographyModel",
    "RansacResult",
    "estimate_homography",
    "ransac_homography",
    "sampson_distance",
    "symmetric_transfer_error",
    "transfer_error",
]


_COLLINEAR_TOL = 1e-9  # |det| of three Hartley-normalised points below this: collinear


_RANK_TOL = 1e-10  # second-smallest singular value of the DLT system relative to the largest


def _dlt_rows(s: np.ndarray, d: np.ndarray) -> np.ndarray:
    r"""The 2N x 9 DLT matrix A with :math:`A h = 0` for :math:`h` = H row-major.

    Works on stacked batches: s, d of shape (..., N, 2) give (..., 2N, 9).
    """
    u, v = s[..., 0], s[..., 1]
    up, vp = d[..., 0], d[..., 1]
    one, zero = np.ones_like(u), np.zeros_like(u)
    r1 = np.stack([zero, zero, zero, -u, -v, -one, vp * u, vp * v, vp], axis=-1)
    r2 = np.stack([u, v, one, zero, zero, zero, -up * u, -up * v, -up], axis=-1)
    A = np.stack([r1, r2], axis=-2)  # (..., N, 2, 9)
    return A.reshape(*A.shape[:-3], -1, 9)


def _collinear_triples(p: np.ndarray) -> np.ndarray:
    """For (..., 4, 2) normalised points, |det| of the 4 triples: (..., 4)."""
    idx = np.array([[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]])
    t = p[..., idx, :]  # (..., 4, 3, 2)
    a = t[..., 1, :] - t[..., 0, :]
    b = t[..., 2, :] - t[..., 0, :]
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _check_general_position(sn: np.ndarray, name: str) -> None:
    """Raise DegenerateError for collinear configurations of Hartley-normalised points."""
    centred = sn - sn.mean(axis=0)
    # The spread across the best-fit line relative to the spread along it: the square
    # roots of the 2x2 scatter matrix's eigenvalues (its eigenvalues carry ~1e-16
    # relative error, hence the looser 1e-7 on their square roots).
    ev = np.linalg.eigvalsh(np.einsum("ni,nj->ij", centred, centred))
    if np.sqrt(max(ev[0], 0.0)) < 1e-7 * np.sqrt(max(ev[1], 1e-300)):
        raise DegenerateError(
            f"estimate_homography: all {len(sn)} points in {name} are collinear, so they do not fix a "
            f"homography; pick points spread over the plane (at least 4, no 3 on a line)"
        )
    if len(sn) == 4:
        dets = np.abs(_collinear_triples(sn))
        if dets.min() < _COLLINEAR_TOL * 4:
            k = int(np.argmin(dets))
            triple = [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]][k]
            raise DegenerateError(
                f"estimate_homography: 3 of the 4 points in {name} are collinear (points {triple}); "
                f"pick points in general position"
            )


def estimate_homography(src: ArrayLike, dst: ArrayLike, normalise: bool = True) -> np.ndarray:
    r"""Estimate H with dst ~ H src from N >= 4 point pairs by the direct linear transform.

    Derivation. :math:`x' \sim H x` means :math:`x' \times H x = 0`. Writing
    :math:`h` for the 9 entries of H (row-major), each pair gives two independent
    linear equations

    .. math::
        \begin{pmatrix} 0^T & -x^T & v' x^T \\ x^T & 0^T & -u' x^T \end{pmatrix} h = 0,

    with :math:`x = (u, v, 1)`. Stacking the pairs gives :math:`A h = 0`, and the unit
    vector minimising :math:`\|A h\|` is the right singular vector of A with the smallest
    singular value (equivalently the eigenvector of :math:`A^T A` with the smallest
    eigenvalue, which is what the normalised path computes). With pixel coordinates the columns of A differ in size by factors up
    to :math:`u u' \approx 10^5`, so noise is amplified; Hartley's normalisation [2]_ first
    maps each point set with a similarity T (:func:`hartley_normalise`), solves for
    :math:`\hat H` there, and returns :math:`H = T'^{-1} \hat H T`.

    Parameters
    ----------
    src, dst : (N, 2) array_like
        Corresponding pixel coordinates (u, v), N >= 4.
    normalise : bool
        Apply Hartley normalisation (default). ``False`` solves in raw pixel coordinates,
        to show why normalising matters (lesson 07, section 6).

    Returns
    -------
    (3, 3) ndarray
        H scaled so that H[2, 2] = 1 where possible (see :func:`normalise_homography`).

    Raises
    ------
    CamlabInputError
        Fewer than 4 pairs, mismatched lengths, NaN or inf.
    DegenerateError
        All points collinear, 3 of a minimal set of 4 collinear, or any set that leaves
        the solution non-unique (the DLT system has a null space of dimension > 1).

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 4.1 and
       algorithm 4.2 (the DLT, normalised).
    .. [2] R. I. Hartley, 1997, "In defense of the eight-point algorithm", *IEEE Transactions
       on Pattern Analysis and Machine Intelligence* 19(6), 580-593.

    Examples
    --------
    >>> src = [[0, 0], [1, 0], [1, 1], [0, 1]]
    >>> estimate_homography(src, [[0, 0], [2, 0], [2, 2], [0, 2]]).round(12) + 0.0
    array([[2., 0., 0.],
           [0., 2., 0.],
           [0., 0., 1.]])
    """
    s, d = check_correspondences(src, dst)
    sn, Ts = hartley_normalise(s)
    dn, Td = hartley_normalise(d)
    _check_general_position(sn, "src")
    _check_general_position(dn, "dst")
    if normalise and len(s) > 4:
        # In normalised coordinates A is well conditioned, so the eigenvector of the 9x9
        # A^T A with the smallest eigenvalue (= sigma^2) is as accurate as the SVD of A
        # (1e-12 in the tests) and avoids a LAPACK factorisation of the tall A, which is
        # slow under multithreaded BLAS on a busy machine.
        A = _dlt_rows(sn, dn)
        ev, V = np.linalg.eigh(np.einsum("ni,nj->ij", A, A))
        sv = np.sqrt(np.clip(ev[::-1], 0, None))
        h, rank_tol = V[:, 0], 1e-7
    else:
        A = _dlt_rows(sn, dn) if normalise else _dlt_rows(s, d)
        _, sv, vt = np.linalg.svd(A)
        if len(sv) < 9:  # exactly 4 pairs: 8 equations, the null space is the 9th vector
            sv = np.append(sv, 0.0)
        h, rank_tol = vt[-1], _RANK_TOL
    if sv[-2] < rank_tol * sv[0]:
        raise DegenerateError(
            "estimate_homography: the point pairs do not fix a unique homography (the DLT system has "
            "more than one null vector); pick at least 4 points in general position, no 3 on a line"
        )
    H = h.reshape(3, 3)
    if normalise:
        H = np.linalg.solve(Td, H @ Ts)  # H = Td^-1 Hn Ts
    return normalise_homography(H)


def transfer_error(H: ArrayLike, src: ArrayLike, dst: ArrayLike) -> np.ndarray:
    r"""One-way transfer error :math:`\| x'_i - \pi(H x_i) \|` in pixels, one per pair.

    Parameters
    ----------
    H : (3, 3) array_like
        The homography, dst ~ H src.
    src, dst : (N, 2) or (2,) array_like
        Corresponding pixels (u, v).

    Returns
    -------
    (N,) ndarray
        Distances in the destination image, pixels.

    Examples
    --------
    >>> transfer_error(np.eye(3), [[0, 0], [1, 1]], [[3, 4], [1, 1]])
    array([5., 0.])
    """
    Hm = check_homography(H)
    s, d = check_correspondences(src, dst, min_count=1)
    return np.linalg.norm(map_points(Hm, s) - d, axis=1)


def symmetric_transfer_error(H: ArrayLike, src: ArrayLike, dst: ArrayLike) -> np.ndarray:
    r"""Symmetric transfer error per pair, as an RMS distance in pixels.

    .. math:: e_i = \sqrt{\tfrac12 \left( \| x'_i - \pi(H x_i) \|^2 + \| x_i - \pi(H^{-1} x'_i) \|^2 \right)}

    The :math:`\tfrac12` makes :math:`e_i` a distance comparable with a pixel threshold:
    a pair off by 1 px in each image has :math:`e_i \approx 1`.

    Parameters
    ----------
    H : (3, 3) array_like
        The homography, dst ~ H src.
    src, dst : (N, 2) or (2,) array_like
        Corresponding pixels (u, v).

    Returns
    -------
    (N,) ndarray
        e_i, pixels.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 4.2.2
       (symmetric transfer error).

    Examples
    --------
    >>> float(symmetric_transfer_error(np.eye(3), [0, 0], [3, 4])[0])
    5.0
    """
    Hm = check_homography(H)
    s, d = check_correspondences(src, dst, min_count=1)
    return _sym_err_batch(Hm[None], np.linalg.inv(Hm)[None], _columns(s), _columns(d))[0]


def _columns(points: np.ndarray) -> np.ndarray:
    """Points (N, 2) as homogeneous columns (3, N): what :func:`_sq_transfer_batch` multiplies."""
    return np.vstack([points.T, np.ones(len(points))])


def _sq_transfer_batch(H: np.ndarray, p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """(B, N) squared distances |q - pi(H p)|^2 for a stack of homographies (B, 3, 3).

    ``p`` and ``q`` are homogeneous columns (3, N) (:func:`_columns`), so mapping all points
    by each H is one (3, 3) @ (3, N) product per homography. A point mapped to infinity
    divides by zero: the caller silences that (:func:`_sym_err_batch`, once for both ways).
    """
    y = H @ p  # (B, 3, N)
    e = y[:, :2]  # (B, 2, N), computed in place: e = pi(H p) - q
    e /= y[:, 2:]
    e -= q[:2]
    e *= e
    return e[:, 0] + e[:, 1]


def _sym_err_batch(
    H: np.ndarray, Hinv: np.ndarray | None, s: np.ndarray, d: np.ndarray
) -> np.ndarray:
    """(B, N) symmetric transfer RMS errors for B homographies; inf where a point maps to infinity.

    ``s`` and ``d`` are homogeneous columns (3, N) (:func:`_columns`); ``Hinv`` None inverts
    ``H`` here. One ``errstate`` for all of it: RANSAC calls this hundreds of times a run.
    """
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        if Hinv is None:
            Hinv = np.linalg.inv(H)
        e = _sq_transfer_batch(H, s, d)
        e += _sq_transfer_batch(Hinv, d, s)
        e *= 0.5
        np.sqrt(e, out=e)
    e[np.isnan(e)] = np.inf  # 0/0 or inf - inf: the error is undefined
    return e


def _sampson_batch(H: np.ndarray, s: np.ndarray, d: np.ndarray) -> np.ndarray:
    r"""(B, N) Sampson distances (first-order geometric error) for B homographies."""
    u, v = s[:, 0], s[:, 1]
    up, vp = d[:, 0], d[:, 1]
    h = H.reshape(len(H), 9)[:, None, :]  # (B, 1, 9)
    # Algebraic residuals e = A_i h (two rows of the DLT matrix) ...
    Hx = np.einsum("bij,nj->bni", H, np.stack([u, v, np.ones_like(u)], axis=1))  # (B, N, 3)
    e1 = -Hx[..., 1] + vp * Hx[..., 2]
    e2 = Hx[..., 0] - up * Hx[..., 2]
    # ... and their Jacobian with respect to (u, v, u', v').
    h = h[:, 0, :]
    j11 = -h[:, None, 3] + vp * h[:, None, 6]
    j12 = -h[:, None, 4] + vp * h[:, None, 7]
    j14 = Hx[..., 2]
    j21 = h[:, None, 0] - up * h[:, None, 6]
    j22 = h[:, None, 1] - up * h[:, None, 7]
    j23 = -Hx[..., 2]
    a = j11**2 + j12**2 + j14**2  # J J^T = [[a, b], [b, c]]
    b = j11 * j21 + j12 * j22
    c = j21**2 + j22**2 + j23**2
    det = a * c - b * b
    with np.errstate(divide="ignore", invalid="ignore"):
        q = (c * e1**2 - 2 * b * e1 * e2 + a * e2**2) / det  # e^T (J J^T)^-1 e
    q = np.where(np.isfinite(q) & (q >= 0), q, np.inf)
    return np.sqrt(q)


def sampson_distance(H: ArrayLike, src: ArrayLike, dst: ArrayLike) -> np.ndarray:
    r"""Sampson distance per pair: the first-order approximation of the geometric error.

    With :math:`e = A_i h` the two algebraic residuals of pair i and J their 2x4
    Jacobian with respect to :math:`(u, v, u', v')`, the smallest correction of the four
    coordinates that zeroes the linearised residual has squared length
    :math:`e^T (J J^T)^{-1} e` [1]_. It is close to the reprojection error
    of the gold-standard estimate, in pixels, without any iteration.

    Parameters
    ----------
    H : (3, 3) array_like
        The homography, dst ~ H src.
    src, dst : (N, 2) or (2,) array_like
        Corresponding pixels (u, v).

    Returns
    -------
    (N,) ndarray
        The Sampson distance of each pair, pixels.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 4.2.6 (the
       Sampson error).
    .. [2] P. D. Sampson, 1982, "Fitting conic sections to 'very scattered' data: an iterative
       refinement of the Bookstein algorithm", *Computer Graphics and Image Processing* 18(1),
       97-108.

    Examples
    --------
    >>> float(sampson_distance(np.eye(3), [0, 0], [0, 2])[0]).__round__(6)  # 2 px, split over both images
    1.414214
    """
    Hm = check_homography(H)
    s, d = check_correspondences(src, dst, min_count=1)
    return _sampson_batch(Hm[None], s, d)[0]


class RansacResult(NamedTuple):
    """What :func:`ransac_homography` found.

    Attributes
    ----------
    H : (3, 3) ndarray
        The locally optimised homography (least squares on its inliers), H[2, 2] = 1.
    inliers : (N,) bool ndarray
        Pairs whose residual under ``H`` is below the threshold.
    iterations : int
        Minimal samples drawn (hypotheses tried, degenerate ones included).
    residuals : (N,) ndarray
        Each pair's error under the final ``H`` in pixels (the chosen ``score``).
    sample : (4,) int ndarray
        The minimal sample whose hypothesis, locally optimised, became ``H``.
    """

    H: np.ndarray
    inliers: np.ndarray
    iterations: int
    residuals: np.ndarray
    sample: np.ndarray | None = None


def _minimal_solve(sn: np.ndarray, dn: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Solve B minimal 4-point DLTs at once; returns (B, 3, 3) H and a (B,) validity mask."""
    # Reject samples with 3 collinear points in either image, and samples whose triangle
    # orientations flip inconsistently (no homography that keeps all 4 points in front
    # can map them so; H&Z; OpenCV's HomographyEstimatorCallback::checkSubset, after
    # Marquez-Neila et al., J. Real-Time Image Processing 2016).
    ds = _collinear_triples(sn)
    dd = _collinear_triples(dn)
    ok = (np.abs(ds).min(axis=1) > 1e-6) & (np.abs(dd).min(axis=1) > 1e-6)
    prod = np.sign(ds * dd)
    ok &= np.all(prod == prod[:, :1], axis=1)
    H = np.full((len(sn), 3, 3), np.nan)  # NaN where the sample is skipped
    keep = np.flatnonzero(ok)
    if len(keep):
        h, ok[keep] = _null_vectors(_dlt_rows(sn[keep], dn[keep]))  # (K, 8, 9) systems
        H[keep] = h.reshape(-1, 3, 3)
    return H, ok


def _null_vectors(A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r"""Unit null vectors h (B, 9) of B systems A (B, 8, 9), and a (B,) mask of those that have one.

    Fixing :math:`h_9 = 1` turns :math:`A h = 0` into the 8 x 8 system
    ``A[:, :, :8] @ h[:8] = -A[:, :, 8]``: one batched LU solve, many times faster than
    an SVD per sample. It fails only where the null vector has :math:`h_9 = 0` (the
    normalised origin mapped to infinity) or A has rank below 8: those samples are marked
    unusable (:math:`|h_9| < 10^{-8} \|h\|`), and a batch with an exactly singular system
    takes the SVD instead (the last right singular vector, as :func:`estimate_homography`).
    """
    try:
        with np.errstate(all="ignore"):
            h = np.linalg.solve(A[:, :, :8], -A[:, :, 8:])[:, :, 0]
    except np.linalg.LinAlgError:
        _, sv, vt = np.linalg.svd(A)
        return vt[:, -1], sv[:, -1] > 1e-10 * sv[:, 0]
    h = np.column_stack([h, np.ones(len(h))])
    norm = np.sqrt(np.einsum("bi,bi->b", h, h))
    with np.errstate(invalid="ignore"):
        return h / norm[:, None], np.isfinite(norm) & (norm < 1e8)


def _pair_normal_shares(sn: np.ndarray, dn: np.ndarray) -> np.ndarray:
    r"""Each pair's share of :math:`A^T A` (the DLT's normal matrix), stored so that sums are cheap: (N, 36).

    Pair i's two DLT rows (:func:`_dlt_rows`) are :math:`(0^T, -x^T, v' x^T)` and
    :math:`(x^T, 0^T, -u' x^T)` with :math:`x = (u, v, 1)`, so its share
    :math:`r_1 r_1^T + r_2 r_2^T` is the Kronecker product :math:`K \otimes x x^T` with

    .. math:: K = \begin{pmatrix} 1 & 0 & -u' \\ 0 & 1 & -v' \\ -u' & -v' & u'^2 + v'^2 \end{pmatrix}.

    So four 3 x 3 matrices per pair hold it: :math:`x x^T` times 1, :math:`u'`, :math:`v'`
    and :math:`u'^2 + v'^2`, flattened into a row of 36. A subset's :math:`A^T A` is built
    from the sum of its rows (one (S, N) @ (N, 36) product for S subsets) by
    :func:`_normal_matrices`.
    """
    up, vp = dn[:, :1], dn[:, 1:]
    x = np.column_stack([sn, np.ones(len(sn))])
    xxT = (x[:, :, None] * x[:, None, :]).reshape(-1, 9)
    return np.hstack([xxT, up * xxT, vp * xxT, (up * up + vp * vp) * xxT])


def _normal_matrices(sums: np.ndarray) -> np.ndarray:
    r"""(S, 9, 9) normal matrices :math:`A^T A = K \otimes x x^T` summed, from sums of :func:`_pair_normal_shares` (S, 36)."""
    X, Xu, Xv, Xw = sums.reshape(-1, 4, 3, 3).transpose(1, 0, 2, 3)
    M = np.zeros(
        (len(sums), 9, 9)
    )  # the 3 x 3 blocks K_ab X: [[X, 0, -Xu], [0, X, -Xv], [-Xu, -Xv, Xw]]
    M[:, 0:3, 0:3] = M[:, 3:6, 3:6] = X
    M[:, 0:3, 6:9] = M[:, 6:9, 0:3] = -Xu
    M[:, 3:6, 6:9] = M[:, 6:9, 3:6] = -Xv
    M[:, 6:9, 6:9] = Xw
    return M


class HomographyModel(PairModel):
    """Homographies ``dst ~ H src`` for the robust driver :func:`camlab.robust.ransac`.

    Minimal samples of 4 pairs are solved by the 4-point DLT (one batched 8 x 8 solve), larger sets
    by the normalised DLT (the smallest eigenvector of :math:`A^T A`), both in Hartley-
    normalised coordinates computed once; residuals are the symmetric transfer error or
    the Sampson error in pixels.
    """

    sample_size = 4
    name = "ransac_homography"

    def __init__(self, src: np.ndarray, dst: np.ndarray, score: str = "transfer"):
        super().__init__(src, dst)
        self.score = score
        self.sn, self.Ts = hartley_normalise(src)
        self.dn, self.Td = hartley_normalise(dst)
        self.Td_inv = np.linalg.inv(self.Td)
        self.AtA = _pair_normal_shares(self.sn, self.dn)  # a subset's A^T A: one sum
        self.c1, self.c2 = _columns(self.x1), _columns(self.x2)  # homogeneous columns, once

    def normalised_to_pixels(self, Hn: np.ndarray) -> np.ndarray:
        """A homography of the normalised points (:func:`hartley_normalise`) back in pixels: H = Td^-1 Hn Ts.

        Parameters
        ----------
        Hn : (..., 3, 3) ndarray
            Homographies between the normalised point sets.

        Returns
        -------
        (..., 3, 3) ndarray
            The same homographies between the pixel point sets (unscaled).
        """
        return self.Td_inv @ Hn @ self.Ts  # H = Td^-1 Hn Ts

    def minimal(self, idx: np.ndarray) -> MinimalModels:
        """The 4-point DLT of each minimal sample, in one batched solve (see :meth:`PairModel.minimal`).

        Parameters
        ----------
        idx : (B, 4) int ndarray
            B samples of four pair indices.

        Returns
        -------
        MinimalModels
            ``models`` (B, 3, 3) in pixels and ``usable`` (B,), False for degenerate samples.
        """
        Hn, ok = _minimal_solve(self.sn[idx], self.dn[idx])
        return MinimalModels(self.normalised_to_pixels(Hn), ok)

    def fit(self, idx: np.ndarray) -> np.ndarray:
        """The normalised DLT on the pairs ``idx`` (see :meth:`PairModel.fit`).

        Parameters
        ----------
        idx : (K,) int ndarray
            Indices of the pairs to fit.

        Returns
        -------
        (3, 3) ndarray
            H in pixels, unit Frobenius norm.

        Raises
        ------
        DegenerateError
            When the pairs do not fix a unique homography.
        """
        ev, V = np.linalg.eigh(_normal_matrices(self.AtA[idx].sum(axis=0)[None])[0])
        if ev[1] <= 1e-12 * ev[-1]:
            raise DegenerateError("ransac_homography: the inliers do not fix a unique homography")
        H = self.normalised_to_pixels(V[:, 0].reshape(3, 3))
        return H / np.linalg.norm(H)

    def fit_many(self, masks: np.ndarray) -> MinimalModels:
        """The normalised DLT of several pair sets in one batched solve (see :meth:`PairModel.fit_many`).

        Parameters
        ----------
        masks : (S, N) bool ndarray
            One row per pair set.

        Returns
        -------
        MinimalModels
            ``models`` (S, 3, 3) in pixels, unit Frobenius norm, and ``usable`` (S,), False
            where the set does not fix a unique homography (as :meth:`fit` would raise).
        """
        ev, V = np.linalg.eigh(_normal_matrices(masks.astype(float) @ self.AtA))
        H = self.normalised_to_pixels(V[:, :, 0].reshape(-1, 3, 3))
        return MinimalModels(
            H / np.linalg.norm(H, axis=(1, 2), keepdims=True), ev[:, 1] > 1e-12 * ev[:, -1]
        )

    def residuals(
        self, models: np.ndarray, i1: np.ndarray | None = None, i2: np.ndarray | None = None
    ) -> np.ndarray:
        """Each pair's error under each model, pixels: symmetric transfer or Sampson (see :meth:`PairModel.residuals`).

        Parameters
        ----------
        models : (B, 3, 3) ndarray
            Homographies in pixels.
        i1, i2 : (M,) int ndarray, optional
            Indices into the source and destination points; None for the model's own pairs.

        Returns
        -------
        (B, M) ndarray
            Errors, pixels (inf or NaN where a model is singular).
        """
        if self.score == "sampson":
            s = self.x1 if i1 is None else self.x1[i1]
            d = self.x2 if i1 is None else self.x2[i1 if i2 is None else i2]
            return _sampson_batch(models, s, d)
        if i1 is not None and len(i1) > len(self):  # more pairs than points: map each point once
            return self._paired_transfer_errors(models, i1, i1 if i2 is None else i2)
        s = self.c1 if i1 is None else self.c1[:, i1]
        d = self.c2 if i1 is None else self.c2[:, i1 if i2 is None else i2]
        return _sym_err_batch(models, None, s, d)

    def _paired_transfer_errors(self, models: np.ndarray, i1: np.ndarray, i2: np.ndarray):
        """(B, M) symmetric transfer errors of the pairs (x1[i1], x2[i2]), every point mapped once.

        The chance test (:func:`camlab.robust.ransac`, step 5) pairs each point with three
        others: mapping the N points by H and H^-1 once and pairing the images up costs a
        third of mapping the 3N pairs' points.
        """
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            fwd, bwd = models @ self.c1, np.linalg.inv(models) @ self.c2  # (B, 3, N)
            fwd, bwd = fwd[:, :2] / fwd[:, 2:], bwd[:, :2] / bwd[:, 2:]
            e = ((fwd[:, :, i1] - self.c2[:2, i2]) ** 2).sum(axis=1)
            e += ((bwd[:, :, i2] - self.c1[:2, i1]) ** 2).sum(axis=1)
            e *= 0.5
            np.sqrt(e, out=e)
        e[np.isnan(e)] = np.inf
        return e


def ransac_homography(
    src: ArrayLike,
    dst: ArrayLike,
    threshold: float = 3.0,
    confidence: float = 0.995,
    max_iters: int = 2000,
    rng: np.random.Generator | int | None = None,
    *,
    score: str = "transfer",
    batch: int = 64,
    loss: str = "msac",
) -> RansacResult:
    r"""Robustly estimate H from pairs with outliers: LO-RANSAC with an MSAC score.

    :class:`HomographyModel` plugged into the driver :func:`camlab.robust.ransac`
    (its docstring derives each step; H&Z algorithm 4.6 [1]_, Fischler & Bolles [2]_):

    1. Normalise both point sets once (Hartley), so minimal solves are well conditioned.
    2. Draw random 4-pair samples in batches; reject degenerate ones (3 collinear points
       in either image, or inconsistent triangle orientations); solve all their 4-point
       DLTs in one batched solve (the 8 x 8 system with :math:`h_9 = 1`).
    3. Score every hypothesis by the truncated quadratic (MSAC) loss of its ``score``
       errors, :math:`\sum_i \min(e_i, t)^2` (:func:`camlab.robust.msac_cost`); with
       ``loss="marginal"`` by that loss averaged over cuts uniform on :math:`(0, 2t]`,
       :math:`\rho(e) = e^2 - e^3 / (3t)` below :math:`2t`
       (:func:`camlab.robust.marginal_msac_cost`): a pair at the threshold costs half an
       outlier, so a model that explains more pairs wins over a tight fit to fewer.
    4. Each time a hypothesis beats the best so far, re-fit it on its inliers by the
       normalised DLT (local optimisation), so the kept model is a least-squares fit to
       its consensus, not to 4 noisy points.
    5. Stop after :math:`k = \log(1 - p) / \log(1 - w^4)` samples for the best inlier
       ratio w so far (or ``max_iters``), and refuse a consensus that random pairs could
       reach by chance.

    Parameters
    ----------
    src, dst : (N, 2) array_like
        Corresponding pixel coordinates, N >= 4.
    threshold : float
        Inlier threshold in pixels on the ``score`` error.
    confidence : float
        Probability in (0, 1) of having drawn at least one all-inlier sample.
    max_iters : int
        Upper bound on samples drawn.
    rng : np.random.Generator, int or None
        Source of randomness (seed it for reproducible results).
    score : {"transfer", "sampson"}
        ``"transfer"``: :func:`symmetric_transfer_error`; ``"sampson"``:
        :func:`sampson_distance`.
    batch : int
        Samples solved and scored per vectorised step.
    loss : {"msac", "marginal"}
        Step 3's score (see :func:`camlab.robust.ransac`).

    Returns
    -------
    RansacResult
        ``H``, ``inliers`` (bool mask), ``iterations``, ``residuals`` (pixels).

    Raises
    ------
    DegenerateError
        If no sample gives a homography, or the best has no more inliers than random
        pairs would reach by chance (the matches are wrong, or the threshold too small).

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 4.7 and
       algorithm 4.6 (robust estimation of a homography).
    .. [2] M. A. Fischler and R. C. Bolles, 1981, "Random sample consensus: a paradigm for model
       fitting with applications to image analysis and automated cartography",
       *Communications of the ACM* 24(6), 381-395.
    """
    s, d = check_correspondences(src, dst)
    if score not in ("transfer", "sampson"):
        raise CamlabInputError(f"score: expected 'transfer' or 'sampson', got {score!r}")
    fit = ransac(
        HomographyModel(s, d, score), threshold, confidence, max_iters, rng, batch=batch, loss=loss
    )
    return RansacResult(
        normalise_homography(fit.model), fit.inliers, fit.iterations, fit.residuals, fit.sample
    )
