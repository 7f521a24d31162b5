r"""Homographies: estimation (DLT, RANSAC, Levenberg-Marquardt), algebra and geometry.

A homography is an invertible 3x3 matrix H acting on homogeneous image points,
:math:`x' \sim H x` (rows: ``X @ H.T``), and on lines by :math:`l' \sim H^{-T} l`.
It has 8 degrees of freedom (9 entries up to scale), so four point pairs in general
position fix it. Applying H to points and lines is :func:`camlab.projective.map_points`
and :func:`camlab.projective.map_lines`; they are re-exported here.

This module holds

* estimation: :func:`estimate_homography` (normalised DLT), :func:`ransac_homography`
  (vectorised adaptive RANSAC), :func:`refine_homography` (LM on the symmetric
  transfer error), :func:`gold_standard_homography` (H&Z's maximum-likelihood estimate:
  LM on the reprojection error over H and corrected points), and the error measures :func:`transfer_error`,
  :func:`symmetric_transfer_error`, :func:`sampson_distance`;
* algebra: :func:`compose`, :func:`invert`, :func:`normalise_homography`,
  :func:`same_homography`;
* the transformation hierarchy: :func:`euclidean_homography`, :func:`similarity_homography`,
  :func:`affine_homography`, :func:`projective_homography`, :data:`HIERARCHY`, :func:`classify`,
  :func:`decompose_homography`;
* homographies from geometry: :func:`plane_homography` (:math:`K'(R - t n^T/d)K^{-1}`),
  :func:`rotation_homography` (:math:`K' R K^{-1}`) and :func:`pose_homography`
  (the world plane Z = 0 to the image, :math:`K [r_1\ r_2\ t]`).

Pixel coordinates (u, v) = (column, row), origin at the centre of the top-left pixel
(docs/conventions.md). See lesson 07.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._validate import (
    CamlabInputError,
    ConvergenceError,
    DegenerateError,
    as_float,
    as_point_pairs,
    check_intrinsics,
    check_matrix,
    check_number,
    check_positive,
    check_rotation,
)
from .optimize import levenberg_marquardt, unit_sphere_basis, unit_sphere_update
from .projective import hartley_normalise, map_points
from .robust import MinimalModels, PairModel, ransac

__all__ = [
    "GoldStandardResult",
    "HIERARCHY",
    "HomographyFactors",
    "HomographyModel",
    "RansacResult",
    "RefineResult",
    "affine_homography",
    "classify",
    "compose",
    "correct_points",
    "decompose_homography",
    "estimate_homography",
    "euclidean_homography",
    "gold_standard_homography",
    "hierarchy_matrix",
    "invert",
    "normalise_homography",
    "plane_homography",
    "pose_homography",
    "projective_homography",
    "ransac_homography",
    "refine_homography",
    "rotation_homography",
    "same_homography",
    "sampson_distance",
    "similarity_homography",
    "symmetric_transfer_error",
    "transfer_error",
]

_COLLINEAR_TOL = 1e-9  # |det| of three Hartley-normalised points below this: collinear
_RANK_TOL = 1e-10  # second-smallest singular value of the DLT system relative to the largest


# --------------------------------------------------------------------------- validation


def _pairs(src: ArrayLike, dst: ArrayLike, min_count: int = 4) -> tuple[np.ndarray, np.ndarray]:
    """Validate two (N, 2) arrays of corresponding points (:func:`camlab._validate.as_point_pairs`)."""
    pairs = as_point_pairs(
        src,
        dst,
        ("src", "dst"),
        min_count=min_count,
        why="a homography has 8 degrees of freedom and each pair fixes 2",
    )
    return pairs.first, pairs.second


def check_homography(H: ArrayLike, name: str = "H") -> np.ndarray:
    """Return H as a float (3, 3) array, or raise if it is malformed, non-finite or singular."""
    Hm = check_matrix(H, (3, 3), name)
    s = np.linalg.svd(Hm, compute_uv=False)
    if s[0] == 0 or s[-1] < 1e-12 * s[0]:
        raise DegenerateError(
            f"{name}: singular (singular values {np.array2string(s, precision=3)}); a homography must be "
            f"invertible, it cannot collapse the plane onto a line or a point"
        )
    return Hm


# --------------------------------------------------------------------------- normalisation


def normalise_homography(H: ArrayLike) -> np.ndarray:
    """Scale H so that H[2, 2] = 1, or to unit Frobenius norm when H[2, 2] is (nearly) 0.

    Homographies are defined up to scale; this picks H[2, 2] = 1 when H[2, 2] is not
    tiny (the usual textbook form) and unit norm with a non-negative H[2, 2] otherwise.

    >>> normalise_homography(2 * np.eye(3))
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    Hm = check_matrix(H, (3, 3), "H")
    n = np.linalg.norm(Hm)
    if n == 0:
        raise DegenerateError("H: the zero matrix is not a homography")
    if abs(Hm[2, 2]) > 1e-8 * n:
        return Hm / Hm[2, 2]
    return Hm / n


def same_homography(H1: ArrayLike, H2: ArrayLike, tol: float = 1e-9) -> bool:
    """True if H1 and H2 are equal up to a non-zero scale (relative Frobenius tolerance).

    >>> same_homography(np.eye(3), -5 * np.eye(3))
    True
    """
    a = check_matrix(H1, (3, 3), "H1")
    b = check_matrix(H2, (3, 3), "H2")
    a = a / np.linalg.norm(a)
    b = b / np.linalg.norm(b)
    return bool(min(np.linalg.norm(a - b), np.linalg.norm(a + b)) <= tol)


# --------------------------------------------------------------------------- DLT


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
    to :math:`u u' \approx 10^5`, so noise is amplified; Hartley's normalisation first
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

    Examples
    --------
    >>> src = [[0, 0], [1, 0], [1, 1], [0, 1]]
    >>> estimate_homography(src, [[0, 0], [2, 0], [2, 2], [0, 2]]).round(12) + 0.0
    array([[2., 0., 0.],
           [0., 2., 0.],
           [0., 0., 1.]])
    """
    s, d = _pairs(src, dst)
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


# --------------------------------------------------------------------------- errors


def transfer_error(H: ArrayLike, src: ArrayLike, dst: ArrayLike) -> np.ndarray:
    r"""One-way transfer error :math:`\| x'_i - \pi(H x_i) \|` in pixels, one per pair.

    >>> transfer_error(np.eye(3), [[0, 0], [1, 1]], [[3, 4], [1, 1]])
    array([5., 0.])
    """
    Hm = check_homography(H)
    s, d = _pairs(src, dst, min_count=1)
    return np.linalg.norm(map_points(Hm, s) - d, axis=1)


def symmetric_transfer_error(H: ArrayLike, src: ArrayLike, dst: ArrayLike) -> np.ndarray:
    r"""Symmetric transfer error per pair, as an RMS distance in pixels.

    .. math:: e_i = \sqrt{\tfrac12 \left( \| x'_i - \pi(H x_i) \|^2 + \| x_i - \pi(H^{-1} x'_i) \|^2 \right)}

    The :math:`\tfrac12` makes :math:`e_i` a distance comparable with a pixel threshold:
    a pair off by 1 px in each image has :math:`e_i \approx 1`.

    >>> float(symmetric_transfer_error(np.eye(3), [0, 0], [3, 4])[0])
    5.0
    """
    Hm = check_homography(H)
    s, d = _pairs(src, dst, min_count=1)
    return _sym_err_batch(Hm[None], np.linalg.inv(Hm)[None], _columns(s), _columns(d))[0]


def _columns(points: np.ndarray) -> np.ndarray:
    """Points (N, 2) as homogeneous columns (3, N): what :func:`_sq_transfer_batch` multiplies."""
    return np.vstack([points.T, np.ones(len(points))])


def _sq_transfer_batch(H: np.ndarray, p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """(B, N) squared distances |q - pi(H p)|^2 for a stack of homographies (B, 3, 3).

    ``p`` and ``q`` are homogeneous columns (3, N) (:func:`_columns`), so mapping all points
    by each H is one (3, 3) @ (3, N) product per homography.
    """
    y = H @ p  # (B, 3, N)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        e = y[:, :2] / y[:, 2:] - q[:2]  # (B, 2, N)
        e *= e
        return e[:, 0] + e[:, 1]


def _sym_err_batch(H: np.ndarray, Hinv: np.ndarray, s: np.ndarray, d: np.ndarray) -> np.ndarray:
    """(B, N) symmetric transfer RMS errors for B homographies; inf where a point maps to infinity.

    ``s`` and ``d`` are homogeneous columns (3, N) (:func:`_columns`)."""
    with np.errstate(invalid="ignore", over="ignore"):
        e = np.sqrt(0.5 * (_sq_transfer_batch(H, s, d) + _sq_transfer_batch(Hinv, d, s)))
    return np.where(np.isfinite(e), e, np.inf)


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
    :math:`e^T (J J^T)^{-1} e` (H&Z section 4.2.6). It is close to the reprojection error
    of the gold-standard estimate, in pixels, without any iteration.

    >>> float(sampson_distance(np.eye(3), [0, 0], [0, 2])[0]).__round__(6)  # 2 px, split over both images
    1.414214
    """
    Hm = check_homography(H)
    s, d = _pairs(src, dst, min_count=1)
    return _sampson_batch(Hm[None], s, d)[0]


# --------------------------------------------------------------------------- RANSAC


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
    # can map them so; H&Z and OpenCV's isMinimalSetConsistent).
    ds = _collinear_triples(sn)
    dd = _collinear_triples(dn)
    ok = (np.abs(ds).min(axis=1) > 1e-6) & (np.abs(dd).min(axis=1) > 1e-6)
    prod = np.sign(ds * dd)
    ok &= np.all(prod == prod[:, :1], axis=1)
    A = _dlt_rows(sn, dn)  # (B, 8, 9)
    # The null vector of an 8x9 system: the last right singular vector.
    _, sv, vt = np.linalg.svd(A)
    H = vt[:, -1, :].reshape(-1, 3, 3)
    ok &= sv[:, -1] > 1e-10 * sv[:, 0]
    return H, ok


class HomographyModel(PairModel):
    """Homographies ``dst ~ H src`` for the robust driver :func:`camlab.robust.ransac`.

    Minimal samples of 4 pairs are solved by the 4-point DLT (batched SVD), larger sets
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
        self.A = _dlt_rows(self.sn, self.dn).reshape(-1, 2, 9)  # each pair's two DLT rows, once
        self.c1, self.c2 = _columns(self.x1), _columns(self.x2)  # homogeneous columns, once

    def normalised_to_pixels(self, Hn: np.ndarray) -> np.ndarray:
        return self.Td_inv @ Hn @ self.Ts  # H = Td^-1 Hn Ts

    def minimal(self, idx: np.ndarray) -> MinimalModels:
        Hn, ok = _minimal_solve(self.sn[idx], self.dn[idx])
        return MinimalModels(self.normalised_to_pixels(Hn), ok)

    def fit(self, idx: np.ndarray) -> np.ndarray:
        A = self.A[idx].reshape(-1, 9)
        ev, V = np.linalg.eigh(A.T @ A)
        if ev[1] <= 1e-12 * ev[-1]:
            raise DegenerateError("ransac_homography: the inliers do not fix a unique homography")
        H = self.normalised_to_pixels(V[:, 0].reshape(3, 3))
        return H / np.linalg.norm(H)

    def residuals(
        self, models: np.ndarray, i1: np.ndarray | None = None, i2: np.ndarray | None = None
    ) -> np.ndarray:
        if self.score == "sampson":
            s = self.x1 if i1 is None else self.x1[i1]
            d = self.x2 if i1 is None else self.x2[i1 if i2 is None else i2]
            return _sampson_batch(models, s, d)
        s = self.c1 if i1 is None else self.c1[:, i1]
        d = self.c2 if i1 is None else self.c2[:, i1 if i2 is None else i2]
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            inv = np.linalg.inv(models)
        return _sym_err_batch(models, inv, s, d)


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
) -> RansacResult:
    r"""Robustly estimate H from pairs with outliers: LO-RANSAC with MSAC scoring.

    :class:`HomographyModel` plugged into the driver :func:`camlab.robust.ransac`
    (its docstring derives each step; H&Z algorithm 4.6, Fischler & Bolles 1981):

    1. Normalise both point sets once (Hartley), so minimal solves are well conditioned.
    2. Draw random 4-pair samples in batches; reject degenerate ones (3 collinear points
       in either image, or inconsistent triangle orientations); solve all their 4-point
       DLTs with one batched SVD.
    3. Score every hypothesis by the truncated quadratic (MSAC) cost
       :math:`\sum_i \min(e_i^2, t^2)` of its ``score`` errors.
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

    Returns
    -------
    RansacResult
        ``H``, ``inliers`` (bool mask), ``iterations``, ``residuals`` (pixels).

    Raises
    ------
    DegenerateError
        If no sample gives a homography, or the best has no more inliers than random
        pairs would reach by chance (the matches are wrong, or the threshold too small).
    """
    s, d = _pairs(src, dst)
    if score not in ("transfer", "sampson"):
        raise CamlabInputError(f"score: expected 'transfer' or 'sampson', got {score!r}")
    fit = ransac(HomographyModel(s, d, score), threshold, confidence, max_iters, rng, batch=batch)
    return RansacResult(
        normalise_homography(fit.model), fit.inliers, fit.iterations, fit.residuals, fit.sample
    )


# --------------------------------------------------------------------------- LM refinement


class RefineResult(NamedTuple):
    """What :func:`refine_homography` did.

    Attributes
    ----------
    H : (3, 3) ndarray
        The refined homography, H[2, 2] = 1.
    rms_initial, rms_final : float
        RMS symmetric transfer error in pixels before and after.
    iterations : int
        Levenberg-Marquardt steps taken (accepted or rejected).
    """

    H: np.ndarray
    rms_initial: float
    rms_final: float
    iterations: int


def _transfer_residuals_and_jacobian(h: np.ndarray, s: np.ndarray, d: np.ndarray):
    """Residual vector (4N,) and its Jacobian (4N, 9) with respect to h = H row-major."""
    H = h.reshape(3, 3)
    G = np.linalg.inv(H)
    n = len(s)
    xs = np.hstack([s, np.ones((n, 1))])
    xd = np.hstack([d, np.ones((n, 1))])
    y = xs @ H.T  # forward: y = H x
    z = xd @ G.T  # backward: z = H^-1 x'
    p = y[:, :2] / y[:, 2:]
    q = z[:, :2] / z[:, 2:]
    r = np.concatenate([(p - d).ravel(), (q - s).ravel()])

    def dproj(w: np.ndarray, proj: np.ndarray) -> np.ndarray:  # d(pi(w))/dw, (N, 2, 3)
        J = np.zeros((len(w), 2, 3))
        J[:, 0, 0] = J[:, 1, 1] = 1 / w[:, 2]
        J[:, :, 2] = -proj / w[:, 2:]
        return J

    # dy/dh = kron(I3, x^T): dy_i/dH_ij = x_j.
    Ky = np.einsum("ik,nj->nikj", np.eye(3), xs).reshape(n, 3, 9)
    Jf = dproj(y, p) @ Ky
    # d(H^-1) = -H^-1 dH H^-1, so dz = -G dH z and dz/dh = -G kron(I3, z^T).
    Kz = np.einsum("ik,nj->nikj", np.eye(3), z).reshape(n, 3, 9)
    Jb = dproj(z, q) @ (-G @ Kz)
    return r, np.concatenate([Jf.reshape(2 * n, 9), Jb.reshape(2 * n, 9)])


def refine_homography(
    H: ArrayLike,
    src: ArrayLike,
    dst: ArrayLike,
    max_iters: int = 50,
    tol: float = 1e-10,
) -> RefineResult:
    r"""Refine H by Levenberg-Marquardt on the symmetric transfer error (the geometric cost).

    Minimises :math:`\sum_i \|x'_i - \pi(H x_i)\|^2 + \|x_i - \pi(H^{-1} x'_i)\|^2` over
    H, starting from ``H`` (typically the DLT). The 9 entries carry one redundant scale,
    so steps are taken in the 8-dimensional space orthogonal to the current :math:`h`
    (a basis B from the SVD of :math:`h^T`), and h is re-normalised after each step.

    The steps are :func:`camlab.optimize.levenberg_marquardt`'s, on the unit sphere
    (:func:`camlab.optimize.unit_sphere_update`), with the analytic Jacobian J: for the
    forward term :math:`\partial (Hx)/\partial h = I_3 \otimes x^T`, and for the backward
    term :math:`d(H^{-1}) = -H^{-1}\, dH\, H^{-1}`.

    Parameters
    ----------
    H : (3, 3) array_like
        Starting homography (invertible).
    src, dst : (N, 2) array_like
        Corresponding pixel coordinates, N >= 4.
    max_iters : int
        Maximum LM steps (accepted or rejected).
    tol : float
        Stop when the relative cost decrease of an accepted step is below ``tol``.

    Returns
    -------
    RefineResult
        ``H``, ``rms_initial``, ``rms_final`` (pixels), ``iterations``.

    Raises
    ------
    ConvergenceError
        If the cost is not finite at the start (a point maps to infinity).
    """
    h = check_homography(H).ravel().copy()
    s, d = _pairs(src, dst)
    h /= np.linalg.norm(h)
    r0 = _transfer_residuals_and_jacobian(h, s, d)[0]
    if not np.all(np.isfinite(r0)):
        raise ConvergenceError(
            "refine_homography: the starting H maps some point to infinity; start from the DLT"
        )
    cache: dict = {}

    def evaluate(x: np.ndarray):
        key = x.tobytes()
        if key not in cache:
            cache.clear()
            try:
                cache[key] = _transfer_residuals_and_jacobian(x, s, d)
            except np.linalg.LinAlgError:  # a singular trial H: reject the step
                cache[key] = (np.full(4 * len(s), np.inf), None)
        return cache[key]

    lm = levenberg_marquardt(
        lambda x: evaluate(x)[0],
        h,
        lambda x: evaluate(x)[1] @ unit_sphere_basis(x),
        update=unit_sphere_update,
        max_iter=int(max_iters),
        ftol=tol,
        xtol=1e-14,
        gtol=0.0,
    )
    return RefineResult(
        normalise_homography(lm.x.reshape(3, 3)),
        float(np.sqrt(r0 @ r0 / (2 * len(s)))),
        float(np.sqrt(2 * lm.cost / (2 * len(s)))),
        lm.iterations,
    )


# --------------------------------------------------------------------------- Gold Standard


class GoldStandardResult(NamedTuple):
    """What :func:`gold_standard_homography` did.

    Attributes
    ----------
    H : (3, 3) ndarray
        The maximum-likelihood homography (H&Z algorithm 4.3), H[2, 2] = 1.
    src_corrected, dst_corrected : (N, 2) ndarray
        The corrected points :math:`\\hat x_i` and :math:`\\hat x'_i = \\pi(H \\hat x_i)`: the
        pairs closest to the measurements that H maps exactly onto each other.
    rms_initial, rms_final : float
        RMS reprojection error in pixels, :math:`\\sqrt{\\sum_i d(x_i, \\hat x_i)^2 + d(x'_i, \\hat x'_i)^2 / 2N}`,
        of the starting H (with its own best corrected points) and of the result.
    iterations : int
        Levenberg-Marquardt steps taken (accepted or rejected).
    """

    H: np.ndarray
    src_corrected: np.ndarray
    dst_corrected: np.ndarray
    rms_initial: float
    rms_final: float
    iterations: int


def _project_with_jacobian(H: np.ndarray, p: np.ndarray):
    """pi(H p) for (N, 2) points p and d pi(y) / d y at y = H p, (N, 2, 3)."""
    y = np.column_stack([p, np.ones(len(p))]) @ H.T
    q = y[:, :2] / y[:, 2:]
    D = np.zeros((len(p), 2, 3))
    D[:, 0, 0] = D[:, 1, 1] = 1 / y[:, 2]
    D[:, :, 2] = -q / y[:, 2:]
    return q, D


def correct_points(
    H: ArrayLike, src: ArrayLike, dst: ArrayLike, iterations: int = 10
) -> np.ndarray:
    r"""The points :math:`\hat x_i` minimising :math:`d(x_i, \hat x_i)^2 + d(x'_i, \pi(H \hat x_i))^2` for a fixed H.

    Each pair is a separate 2-parameter least-squares problem; Gauss-Newton from
    :math:`\hat x_i = x_i`, all pairs at once: with :math:`r_i = (\hat x_i - x_i,\ \pi(H\hat x_i) - x'_i)`
    and :math:`J_i = (I_2;\ D_i H_{:, :2})`, where :math:`D_i = \partial\pi/\partial y`,
    the step is :math:`-(J_i^T J_i)^{-1} J_i^T r_i`. The problem is nearly linear (a
    homography is locally affine), so a few steps reach the minimum to rounding.

    Returns
    -------
    (N, 2) ndarray
        The corrected source points; their images :math:`\pi(H \hat x_i)` are the corrected
        destination points.
    """
    Hm = check_homography(H)
    s, d = _pairs(src, dst, min_count=1)
    p = s.copy()
    for _ in range(int(iterations)):
        q, D = _project_with_jacobian(Hm, p)
        Jq = D @ Hm[:, :2]  # d pi(H p) / d p, (N, 2, 2)
        normal = np.eye(2) + np.einsum("nki,nkj->nij", Jq, Jq)
        grad = (p - s) + np.einsum("nki,nk->ni", Jq, q - d)
        p = p - np.linalg.solve(normal, grad[..., None])[..., 0]
    return p


class _GoldNormal(NamedTuple):
    """The normal equations of the Gold Standard problem in blocks: U (8, 8) for h, V (N, 2, 2)
    for the corrected points (block diagonal), W (N, 8, 2) coupling them."""

    U: np.ndarray
    V: np.ndarray
    W: np.ndarray

    def diagonal(self) -> np.ndarray:
        return np.concatenate([np.diag(self.U), np.einsum("nii->ni", self.V).ravel()])


def _gold_normal_equations(J, r):
    Jh, Jp = J  # d r2 / d h (N, 2, 8) and d r2 / d p (N, 2, 2); d r1 / d p = I
    n = len(Jh)
    r1, r2 = r[: 2 * n].reshape(n, 2), r[2 * n :].reshape(n, 2)
    U = np.einsum("nki,nkj->ij", Jh, Jh)
    V = np.eye(2) + np.einsum("nki,nkj->nij", Jp, Jp)
    W = np.einsum("nki,nkj->nij", Jh, Jp)
    g = np.concatenate(
        [np.einsum("nki,nk->i", Jh, r2), (r1 + np.einsum("nki,nk->ni", Jp, r2)).ravel()]
    )
    return _GoldNormal(U, V, W), g


def _gold_damped_solve(A: _GoldNormal, g: np.ndarray, mu: float) -> np.ndarray:
    r"""Solve the damped normal equations by the Schur complement (H&Z §A6.3): eliminate the
    points' 2 x 2 blocks, solve 8 x 8 for h, back-substitute; O(N) instead of O(N^3)."""
    n = len(A.V)
    U = A.U + mu * np.diag(np.maximum(np.diag(A.U), 1e-300))
    V = A.V + mu * np.einsum("nii->ni", A.V)[..., None] * np.eye(2)
    gh, gp = g[:8], g[8:].reshape(n, 2)
    Vinv = np.linalg.inv(V)
    WVinv = A.W @ Vinv  # (N, 8, 2)
    S = U - np.einsum("nij,nkj->ik", WVinv, A.W)
    dh = np.linalg.solve(S, -gh + np.einsum("nij,nj->i", WVinv, gp))
    dp = -np.einsum("nij,nj->ni", Vinv, gp + np.einsum("nji,j->ni", A.W, dh))
    return np.concatenate([dh, dp.ravel()])


def gold_standard_homography(
    H: ArrayLike, src: ArrayLike, dst: ArrayLike, max_iters: int = 50, tol: float = 1e-10
) -> GoldStandardResult:
    r"""The Gold Standard (maximum-likelihood) homography of Hartley & Zisserman, algorithm 4.3.

    With Gaussian noise on the points of *both* images, the most likely H minimises the
    reprojection error over H and corrected points :math:`\hat x_i`,

    .. math:: \sum_i d(x_i, \hat x_i)^2 + d(x'_i, \hat x'_i)^2, \qquad \hat x'_i = H \hat x_i,

    so 8 + 2N parameters (H&Z §4.2.3, eq. 4.8). This is not the symmetric transfer error of
    :func:`refine_homography`, which compares each measured point with the image of the
    other measured point. Levenberg-Marquardt (:func:`camlab.optimize.levenberg_marquardt`)
    steps h on the unit sphere and each :math:`\hat x_i` in the plane, starting from ``H``
    (typically the normalised DLT) and :func:`correct_points`. Each residual pair touches h
    and one :math:`\hat x_i` only, so the normal equations are solved by eliminating the
    points first (the sparse LM of H&Z §A6.3): 8 x 8 plus N 2 x 2 systems.

    Parameters
    ----------
    H : (3, 3) array_like
        Starting homography (invertible), typically :func:`estimate_homography`.
    src, dst : (N, 2) array_like
        Corresponding pixel coordinates (inliers), N >= 4.
    max_iters : int
        Maximum LM steps (accepted or rejected).
    tol : float
        Stop when the relative cost decrease of an accepted step is below ``tol``.

    Returns
    -------
    GoldStandardResult
        ``H``, ``src_corrected``, ``dst_corrected``, ``rms_initial`` (the starting H with its
        best corrected points) and ``rms_final`` in pixels, ``iterations``.

    Raises
    ------
    ConvergenceError
        If the starting H maps a point to infinity.

    References
    ----------
    Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., §4.2.3 (reprojection error, both
    images), algorithm 4.3 (§4.5, the Gold Standard); the sparse Levenberg-Marquardt of §A6.3.
    """
    h = check_homography(H).ravel().copy()
    h /= np.linalg.norm(h)
    s, d = _pairs(src, dst)
    n = len(s)

    def residuals(x: np.ndarray) -> np.ndarray:
        Hx, p = x[:9].reshape(3, 3), x[9:].reshape(n, 2)
        with np.errstate(divide="ignore", invalid="ignore"):
            q = _project_with_jacobian(Hx, p)[0]
        return np.concatenate([(p - s).ravel(), (q - d).ravel()])

    def jacobian(x: np.ndarray):
        Hx, p = x[:9].reshape(3, 3), x[9:].reshape(n, 2)
        _, D = _project_with_jacobian(Hx, p)
        Ky = np.einsum("ik,nj->nikj", np.eye(3), np.column_stack([p, np.ones(n)])).reshape(n, 3, 9)
        return D @ Ky @ unit_sphere_basis(x[:9]), D @ Hx[:, :2]

    def update(x: np.ndarray, delta: np.ndarray) -> np.ndarray:
        return np.concatenate([unit_sphere_update(x[:9], delta[:8]), x[9:] + delta[8:]])

    x0 = np.concatenate([h, correct_points(h.reshape(3, 3), s, d).ravel()])
    r0 = residuals(x0)
    if not np.all(np.isfinite(r0)):
        raise ConvergenceError(
            "gold_standard_homography: the starting H maps some point to infinity; "
            "start from the DLT"
        )
    lm = levenberg_marquardt(
        residuals,
        x0,
        jacobian,
        update=update,
        normal_equations=_gold_normal_equations,
        damped_solve=_gold_damped_solve,
        max_iter=int(max_iters),
        ftol=tol,
        xtol=1e-14,
        gtol=0.0,
    )
    H_final = lm.x[:9].reshape(3, 3)
    p = lm.x[9:].reshape(n, 2)
    return GoldStandardResult(
        normalise_homography(H_final),
        p,
        map_points(H_final, p),
        float(np.sqrt(r0 @ r0 / (2 * n))),
        float(np.sqrt(2 * lm.cost / (2 * n))),
        lm.iterations,
    )


# --------------------------------------------------------------------------- algebra


def compose(*Hs: ArrayLike) -> np.ndarray:
    r"""The product :math:`H_1 H_2 \cdots H_k`: apply :math:`H_k` first, :math:`H_1` last.

    ``compose(H2, H1)`` maps a point by H1 and then by H2, like the matrix product
    (a composition of homographies is a homography: the group property).

    >>> compose(np.diag([2.0, 2.0, 1.0]), [[1, 0, 5], [0, 1, 0], [0, 0, 1]])  # shift, then scale
    array([[ 2.,  0., 10.],
           [ 0.,  2.,  0.],
           [ 0.,  0.,  1.]])
    """
    if not Hs:
        raise CamlabInputError("compose: expected at least one (3, 3) homography, got none")
    out = np.eye(3)
    for i, H in enumerate(Hs):
        out = out @ check_homography(H, f"Hs[{i}]")
    return normalise_homography(out)


def invert(H: ArrayLike) -> np.ndarray:
    """The inverse homography (maps dst back to src), normalised; raises if H is singular.

    >>> invert([[2, 0, 0], [0, 2, 0], [0, 0, 1]])
    array([[0.5, 0. , 0. ],
           [0. , 0.5, 0. ],
           [0. , 0. , 1. ]])
    """
    return normalise_homography(np.linalg.inv(check_homography(H)))


# --------------------------------------------------------------------------- hierarchy

HIERARCHY: dict[str, dict] = {
    "euclidean": {
        "dof": 3,
        "matrix": "[[R, t], [0, 1]]",
        "invariants": [
            "length",
            "angle",
            "area",
            "parallelism",
            "ratio of lengths",
            "collinearity",
            "cross-ratio",
        ],
    },
    "similarity": {
        "dof": 4,
        "matrix": "[[sR, t], [0, 1]]",
        "invariants": ["angle", "ratio of lengths", "parallelism", "collinearity", "cross-ratio"],
    },
    "affine": {
        "dof": 6,
        "matrix": "[[A, t], [0, 1]]",
        "invariants": [
            "parallelism",
            "ratio of lengths on parallel lines",
            "ratio of areas",
            "collinearity",
            "cross-ratio",
            "line at infinity",
        ],
    },
    "projective": {
        "dof": 8,
        "matrix": "[[A, t], [v^T, w]]",
        "invariants": ["collinearity", "incidence", "tangency", "cross-ratio"],
    },
}
"""The four groups of plane transformations, their degrees of freedom and invariants (H&Z table 2.1)."""


def _rot(theta: float, name: str = "theta") -> np.ndarray:
    theta = check_number(theta, name, "radians")
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[c, -s], [s, c]])


def euclidean_homography(theta: float = 0.0, tx: float = 0.0, ty: float = 0.0) -> np.ndarray:
    """A rotation by ``theta`` radians (counter-clockwise in x-right, y-up axes; clockwise
    on screen, where v points down) followed by a translation (tx, ty). 3 dof.

    >>> euclidean_homography(0.0, 2.0, 3.0)[:2, 2]
    array([2., 3.])
    """
    H = np.eye(3)
    H[:2, :2] = _rot(theta)
    H[:2, 2] = check_number(tx, "tx", "pixels"), check_number(ty, "ty", "pixels")
    return H


def similarity_homography(
    scale: float = 1.0, theta: float = 0.0, tx: float = 0.0, ty: float = 0.0
) -> np.ndarray:
    """Isotropic scaling, rotation and translation: ``[[s R, t], [0, 1]]``. 4 dof."""
    check_positive(scale, "scale")
    H = euclidean_homography(theta, tx, ty)
    H[:2, :2] *= scale
    return H


def affine_homography(
    theta: float = 0.0,
    phi: float = 0.0,
    sx: float = 1.0,
    sy: float = 1.0,
    tx: float = 0.0,
    ty: float = 0.0,
) -> np.ndarray:
    r"""An affinity from H&Z's decomposition :math:`A = R(\theta) R(-\phi) D R(\phi)`. 6 dof.

    :math:`D = \mathrm{diag}(s_x, s_y)` scales along axes rotated by :math:`\phi`, then
    :math:`R(\theta)` rotates; (tx, ty) translates. Parallel lines stay parallel.
    """
    sx, sy = check_number(sx, "sx"), check_number(sy, "sy")
    if sx == 0 or sy == 0:
        raise DegenerateError(f"sx, sy: a zero scale collapses the plane; got sx={sx}, sy={sy}")
    H = np.eye(3)
    H[:2, :2] = (
        _rot(theta)
        @ _rot(-check_number(phi, "phi", "radians"), "phi")
        @ np.diag([sx, sy])
        @ _rot(phi, "phi")
    )
    H[:2, 2] = check_number(tx, "tx", "pixels"), check_number(ty, "ty", "pixels")
    return H


def projective_homography(
    A: ArrayLike | None = None, t: ArrayLike = (0.0, 0.0), v: ArrayLike = (0.0, 0.0), w: float = 1.0
) -> np.ndarray:
    r"""A general homography ``[[A, t], [v^T, w]]``; v != 0 moves the line at infinity. 8 dof.

    >>> projective_homography(v=[0.001, 0.0])[2]
    array([0.001, 0.   , 1.   ])
    """
    H = np.eye(3)
    H[:2, :2] = np.eye(2) if A is None else check_matrix(A, (2, 2), "A")
    H[:2, 2] = check_matrix(t, (2,), "t")
    H[2, :2] = check_matrix(v, (2,), "v")
    H[2, 2] = check_number(w, "w")
    return check_homography(H)


def hierarchy_matrix(
    group: str,
    *,
    theta: float = 0.0,
    scale: float = 1.0,
    shear: float = 0.0,
    aspect: float = 1.0,
    tx: float = 0.0,
    ty: float = 0.0,
    v: ArrayLike = (0.0, 0.0),
) -> np.ndarray:
    r"""One matrix of ``group`` (a key of :data:`HIERARCHY`) from one set of parameters.

    Each group uses only the parameters it has and ignores the rest, which is what lesson
    07's demo shows when the group changes under fixed sliders:

    * euclidean: rotation ``theta`` (radians) and translation (tx, ty);
    * similarity: adds the isotropic ``scale``;
    * affine: scales ``scale * aspect`` and ``scale / aspect`` along axes turned by ``shear``
      (:func:`affine_homography` with :math:`\phi` = ``shear``);
    * projective: that affinity followed by ``v``, the bottom row that moves the line at
      infinity: :math:`H = H_A H_P` (:func:`compose`, :func:`projective_homography`).

    >>> classify(hierarchy_matrix("similarity", theta=0.3, scale=2.0, shear=0.5))
    'similarity'
    """
    if group not in HIERARCHY:
        raise CamlabInputError(f"group: expected one of {', '.join(HIERARCHY)}, got {group!r}")
    if group == "euclidean":
        return euclidean_homography(theta, tx, ty)
    if group == "similarity":
        return similarity_homography(scale, theta, tx, ty)
    aspect = check_positive(aspect, "aspect")
    A = affine_homography(theta, shear, scale * aspect, scale / aspect, tx, ty)
    if group == "affine":
        return A
    return compose(A, projective_homography(v=v))


def classify(H: ArrayLike, tol: float = 1e-9) -> str:
    """The smallest group of the hierarchy that contains H: 'euclidean', 'similarity',
    'affine' or 'projective'.

    >>> classify(similarity_homography(2.0, 0.3, 1, 1)), classify(affine_homography(sx=2.0)), classify(projective_homography(v=[1e-3, 0]))
    ('similarity', 'affine', 'projective')
    """
    Hm = normalise_homography(check_homography(H))
    if abs(Hm[2, 2]) < tol or np.abs(Hm[2, :2]).max() > tol * abs(Hm[2, 2]):
        return "projective"
    A = Hm[:2, :2] / Hm[2, 2]
    AtA = A.T @ A
    s2 = AtA[0, 0]
    if np.abs(AtA - s2 * np.eye(2)).max() > tol * max(s2, 1.0) or np.linalg.det(A) <= 0:
        return "affine"  # not a scaled rotation (reflections count as affine here)
    if abs(s2 - 1.0) > tol:
        return "similarity"
    return "euclidean"


class HomographyFactors(NamedTuple):
    """:func:`decompose_homography`'s factors, :math:`H = H_S H_A H_P` (each (3, 3)).

    Attributes
    ----------
    H_S : (3, 3) ndarray
        The similarity part (rotation, uniform scale, translation).
    H_A : (3, 3) ndarray
        The affine part (upper-triangular K, det K = 1).
    H_P : (3, 3) ndarray
        The projective part (the bottom row that moves the line at infinity).
    """

    H_S: np.ndarray
    H_A: np.ndarray
    H_P: np.ndarray


def decompose_homography(H: ArrayLike) -> HomographyFactors:
    r"""Split :math:`H = H_S H_A H_P` into similarity, affine and projective parts (H&Z 2.4.6).

    .. math::
        H_S = \begin{pmatrix} sR & t/v \\ 0^T & 1 \end{pmatrix},\quad
        H_A = \begin{pmatrix} K & 0 \\ 0^T & 1 \end{pmatrix},\quad
        H_P = \begin{pmatrix} I & 0 \\ v^T & v \end{pmatrix}

    with K upper triangular, det K = 1. Requires H[2, 2] != 0 (the origin does not map
    to infinity).

    Returns
    -------
    HomographyFactors
        ``(H_S, H_A, H_P)``: three (3, 3) ndarrays whose product equals ``normalise_homography(H)``.
    """
    Hm = normalise_homography(check_homography(H))
    if abs(Hm[2, 2]) < 1e-12:
        raise DegenerateError(
            "decompose_homography: H[2, 2] = 0 (the origin maps to infinity); translate first"
        )
    vvec, vs = Hm[2, :2], Hm[2, 2]
    t = Hm[:2, 2]
    Aeff = Hm[:2, :2] - np.outer(t, vvec) / vs  # sRK = A - t v^T / v
    # QR-like split sR K with K upper triangular, det K = 1, s > 0.
    Q, Rq = np.linalg.qr(Aeff)
    signs = np.sign(np.diag(Rq))
    signs[signs == 0] = 1
    Q, Rq = Q * signs, signs[:, None] * Rq
    s = np.sqrt(abs(np.linalg.det(Rq)))
    K = Rq / s
    HS = np.eye(3)
    HS[:2, :2] = s * Q
    HS[:2, 2] = t / vs
    HA = np.eye(3)
    HA[:2, :2] = K
    HP = np.eye(3)
    HP[2, :2] = vvec / vs * 1.0
    HP[2, 2] = 1.0
    return HomographyFactors(HS, HA, HP)


# --------------------------------------------------------------------------- geometry


def rotation_homography(K: ArrayLike, R: ArrayLike, K2: ArrayLike | None = None) -> np.ndarray:
    r"""The homography between two views from one centre: :math:`H = K' R K^{-1}`.

    A camera that only rotates (R maps camera-1 coordinates to camera-2 coordinates)
    sees every scene point along the same ray, whatever its depth, so
    :math:`x_2 \sim K' R K^{-1} x_1`. This is why panoramas need no depth.

    Parameters
    ----------
    K : (3, 3) array_like
        Intrinsics of the first camera.
    R : (3, 3) array_like
        Rotation cam2_from_cam1.
    K2 : (3, 3) array_like, optional
        Intrinsics of the second camera (default: K).
    """
    Km = check_intrinsics(K, "K")
    K2m = Km if K2 is None else check_intrinsics(K2, "K2")
    return normalise_homography(K2m @ check_rotation(R) @ np.linalg.inv(Km))


def plane_homography(
    K: ArrayLike, R: ArrayLike, t: ArrayLike, n: ArrayLike, d: float, K2: ArrayLike | None = None
) -> np.ndarray:
    r"""The homography induced by a plane between two views: :math:`H = K'(R - t n^T / d) K^{-1}`.

    Camera 1 is :math:`K[I \mid 0]`, camera 2 is :math:`K'[R \mid t]` (cam2_from_cam1).
    The plane is :math:`n^T X + d = 0` in camera-1 coordinates (H&Z result 13.1). For X
    on the plane, :math:`-n^T X / d = 1`, so
    :math:`R X + t = R X - t\, n^T X / d = (R - t n^T / d) X`; with
    :math:`X \sim K^{-1} x_1` this gives :math:`x_2 \sim K'(R - t n^T/d) K^{-1} x_1`.

    Parameters
    ----------
    K : (3, 3) array_like
    R : (3, 3) array_like
        Rotation cam2_from_cam1.
    t : (3,) array_like
        Translation cam2_from_cam1, metres.
    n : (3,) array_like
        Plane normal in camera-1 coordinates (need not be unit; d scales with it).
    d : float
        Plane offset: the plane is n . X + d = 0; d != 0 (the plane must not pass
        through camera 1's centre).
    K2 : (3, 3) array_like, optional
        Intrinsics of camera 2 (default: K).
    """
    Km = check_intrinsics(K, "K")
    K2m = Km if K2 is None else check_intrinsics(K2, "K2")
    tv = check_matrix(np.ravel(as_float(t, "t")), (3,), "t")
    nv = check_matrix(np.ravel(as_float(n, "n")), (3,), "n")
    if check_number(d, "d", "metres") == 0:
        raise DegenerateError(
            f"d: the plane n . X + d = 0 must not pass through camera 1's centre; got d={d!r}"
        )
    if not np.any(nv):
        raise CamlabInputError("n: the plane normal must be non-zero")
    H = K2m @ (check_rotation(R) - np.outer(tv, nv) / d) @ np.linalg.inv(Km)
    return normalise_homography(check_homography(H, "plane_homography"))


def pose_homography(K: ArrayLike, R: ArrayLike, t: ArrayLike) -> np.ndarray:
    r"""The homography from the world plane Z = 0 to the image: :math:`H = K [r_1\ r_2\ t]`.

    A point (X, Y, 0) projects to :math:`K (X r_1 + Y r_2 + t)`, linear in (X, Y, 1).
    This is how a flat textured target (a page, a painting, a chessboard) photographed
    by a camera ``K [R | t]`` (cam_from_world) appears: Zhang's calibration and lesson 10
    start from it.

    >>> K = np.array([[800.0, 0, 320], [0, 800, 240], [0, 0, 1]])
    >>> map_points(pose_homography(K, np.eye(3), [0, 0, 2.0]), [0.0, 0.0])
    array([320., 240.])
    """
    Km = check_intrinsics(K, "K")
    Rm = check_rotation(R)
    tv = check_matrix(np.ravel(as_float(t, "t")), (3,), "t")
    H = Km @ np.column_stack([Rm[:, 0], Rm[:, 1], tv])
    return normalise_homography(check_homography(H, "pose_homography"))
