r"""Estimating F from matches.

The normalised 8-point algorithm ([1]_, algorithm 11.1), the Sampson distance, and RANSAC over it
(:func:`camlab.robust.ransac` with :class:`FundamentalModel`).

Part of :mod:`camlab.epipolar` (every name here is importable from there).

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 11.2 and algorithm 11.1
   (the normalised 8-point algorithm).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    CamlabInputError,
    DegenerateError,
    as_point_pairs,
)
from ..homography import estimate_homography, symmetric_transfer_error
from ..projective import hartley_normalise, to_homogeneous
from ..robust import MinimalModels, PairModel, ransac
from .geometry import check_fundamental, normalise_fundamental

__all__ = [
    "EIGHT_POINT_REASON",
    "FundamentalModel",
    "FundamentalRansacResult",
    "estimate_fundamental_matrix",
    "ransac_fundamental_matrix",
    "sampson_distance",
]


_PLANE_TOL = (
    1e-3  # px: a homography explaining every pair this well means "all points on one plane"
)


_BAD_FIT = 0.05  # a least-squares F with median Sampson distance above this fraction of the spread: wrong pairs


_RANK_TOL = 1e-9  # second-smallest singular value of the normalised 8-point system, relative


EIGHT_POINT_REASON = (
    "the fundamental matrix has 7 degrees of freedom and the linear 8-point algorithm needs 8 pairs"
)


def _sampson_batch(F: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(B, N) Sampson distances for a stack of B fundamental matrices."""
    ah, bh = to_homogeneous(a), to_homogeneous(b)
    Fx = np.einsum("bij,nj->bni", F, ah)  # (B, N, 3): lines in image 2
    Ftx = np.einsum("bji,nj->bni", F, bh)  # (B, N, 3): lines in image 1
    alg = np.sum(Fx * bh[None], axis=2)
    den = Fx[..., 0] ** 2 + Fx[..., 1] ** 2 + Ftx[..., 0] ** 2 + Ftx[..., 1] ** 2
    with np.errstate(divide="ignore", invalid="ignore"):
        d = np.abs(alg) / np.sqrt(den)
    return np.where(np.isfinite(d), d, np.inf)


def sampson_distance(F: ArrayLike, x1: ArrayLike, x2: ArrayLike) -> np.ndarray:
    r"""Sampson distance per pair (pixels): the first-order geometric error of :math:`x'^\top F x = 0`.

    .. math:: d_i = \frac{|\tilde x_i'^\top F \tilde x_i|}
              {\sqrt{(F\tilde x_i)_1^2 + (F\tilde x_i)_2^2 + (F^\top\tilde x_i')_1^2 + (F^\top\tilde x_i')_2^2}}

    It is the length of the smallest joint correction of (u, v, u', v') that zeroes the
    linearised constraint [1]_, close to the gold-standard reprojection
    error without triangulating. Compare with OpenCV's inlier thresholds in pixels.

    Parameters
    ----------
    F : (3, 3) array_like
        The fundamental matrix, x2^T F x1 = 0.
    x1, x2 : (N, 2) or (2,) array_like
        Corresponding pixels in images 1 and 2.

    Returns
    -------
    (N,) ndarray
        d_i, pixels.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 11.4.3 (the Sampson
       distance).

    Examples
    --------
    >>> F = np.array([[0, 0, 0], [0, 0, -1], [0, 1, 0]])
    >>> sampson_distance(F, [[0, 0]], [[5, 2]])  # 2 px vertical offset, shared by both images
    array([1.41421356])
    """
    F = check_fundamental(F)
    a, b, single = as_point_pairs(x1, x2)
    out = _sampson_batch(F[None], a, b)[0]
    return out[0] if single else out


def _eight_point_rows(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Rows of the 8-point system A f = 0 (f = F row-major); a, b: (..., N, 2)."""
    u, v = a[..., 0], a[..., 1]
    up, vp = b[..., 0], b[..., 1]
    one = np.ones_like(u)
    return np.stack([up * u, up * v, up, vp * u, vp * v, vp, u, v, one], axis=-1)


def _rank2(F: np.ndarray) -> np.ndarray:
    """Closest rank-2 matrix (Frobenius) to each F in a (..., 3, 3) stack: zero the smallest singular value."""
    U, s, Vt = np.linalg.svd(F)
    s[..., 2] = 0.0
    return (U * s[..., None, :]) @ Vt


def estimate_fundamental_matrix(
    x1: ArrayLike,
    x2: ArrayLike,
    normalise: bool = True,
    plane_tol: float = _PLANE_TOL,
    sampson_iterations: int = 0,
) -> np.ndarray:
    r"""Estimate F from N >= 8 point pairs by the normalised 8-point algorithm.

    Derivation (H&Z algorithm 11.1 [1]_). Each pair gives one linear equation in the nine
    entries :math:`f` of F (row-major):

    .. math:: \tilde x'^\top F \tilde x = 0 \iff
              (u'u,\ u'v,\ u',\ v'u,\ v'v,\ v',\ u,\ v,\ 1)\, f = 0 .

    1. Normalise each image's points with a similarity T (centroid to 0, mean distance
       :math:`\sqrt 2`): pixel coordinates in the hundreds make the columns of A differ by
       :math:`10^5` in size and the unnormalised solution is poor (Hartley [2]_).
    2. Stack the N rows into A and take :math:`f` = the right singular vector of the
       smallest singular value (least squares with :math:`\|f\| = 1`).
    3. Enforce rank 2: replace F by the closest singular matrix, zeroing its smallest
       singular value, so that all epipolar lines meet in one epipole.
    4. Undo the normalisation: :math:`F = T'^\top \hat F T`.

    Parameters
    ----------
    x1, x2 : (N, 2) array_like
        Corresponding pixels in image 1 and image 2, N >= 8.
    normalise : bool
        Hartley normalisation (step 1). ``False`` shows why it matters.
    plane_tol : float
        Pixels. If a single homography maps every ``x1`` to its ``x2`` within this RMS
        symmetric transfer error, the pairs are degenerate (see Raises).
    sampson_iterations : int
        After the linear solution, re-solve this many times with each row of A divided by
        the Sampson denominator of the current F,
        :math:`\sqrt{(F\tilde x)_1^2 + (F\tilde x)_2^2 + (F^\top\tilde x')_1^2 + (F^\top\tilde x')_2^2}`,
        so that the weighted algebraic error becomes the Sampson distance in pixels
        (iteratively reweighted least squares). The plain 8-point algorithm minimises an
        algebraic error that over-weights points far from the epipole; this matters when
        the epipole is far away (a nearly parallel rig). 0 (default) is the classic
        algorithm; :func:`ransac_fundamental_matrix` uses 10 for its final fit.

    Returns
    -------
    (3, 3) ndarray
        F of rank 2, unit Frobenius norm, ``x2_h @ F @ x1_h ~ 0``.

    Raises
    ------
    CamlabInputError
        Fewer than 8 pairs, or different counts.
    DegenerateError
        The 8-point system has more than a one-dimensional null space, or one homography
        explains all pairs (all world points on one plane, or the camera only rotated): F
        is then not determined (a 3-parameter family fits exactly). Noisy near-planar
        scenes pass this test but give an unreliable F; check the residuals.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 11.2 and algorithm
       11.1 (the normalised 8-point algorithm).
    .. [2] R. I. Hartley, 1997, "In defense of the eight-point algorithm", *IEEE Transactions
       on Pattern Analysis and Machine Intelligence* 19(6), 580-593.

    Examples
    --------
    >>> from camlab.camera import Camera
    >>> from camlab.epipolar import fundamental_from_cameras
    >>> cam1 = Camera.look_at([0, -3, 0.5], [0, 0, 0.5])
    >>> cam2 = Camera.look_at([0.4, -3, 0.5], [0, 0, 0.5])
    >>> X = np.random.default_rng(0).uniform(-0.5, 0.5, (20, 3)) + [0, 0, 0.5]
    >>> F = estimate_fundamental_matrix(cam1.project(X), cam2.project(X))
    >>> bool(np.allclose(F, fundamental_from_cameras(cam1, cam2), atol=1e-9))
    True
    """
    a, b, _ = as_point_pairs(x1, x2, min_count=8, why=EIGHT_POINT_REASON)
    if normalise:
        an, T1 = hartley_normalise(a)
        bn, T2 = hartley_normalise(b)
    else:
        an, bn, T1, T2 = a, b, np.eye(3), np.eye(3)
    A = _eight_point_rows(an, bn)
    _, s, Vt = np.linalg.svd(
        A, full_matrices=len(A) < 9
    )  # Vt must hold all 9 right singular vectors
    if s[7] <= _RANK_TOL * s[0]:  # 8 independent rows: a one-dimensional null space
        raise DegenerateError(
            f"estimate_fundamental_matrix: the {len(a)} pairs give an 8-point system of rank < 8, so F is not "
            f"unique; the points are coplanar, collinear or repeated. Use points spread over several depths"
        )
    # Only data that a homography could explain within plane_tol px has a nearly 3-dimensional null
    # space (s[6] tiny); skip the homography fit otherwise (it costs twice the 8-point solve).
    if plane_tol > 0 and s[6] < 1e-4 * s[0]:
        try:
            H = estimate_homography(a, b)
            plane_err = float(np.sqrt(np.mean(symmetric_transfer_error(H, a, b) ** 2)))
        except CamlabInputError:
            plane_err = np.inf
        if plane_err < plane_tol:
            raise DegenerateError(
                f"estimate_fundamental_matrix: one homography maps all {len(a)} points of x1 onto x2 "
                f"(RMS error {plane_err:.2g} px < plane_tol = {plane_tol} px): the world points are all on one "
                f"plane (or the camera only rotated), and F is not determined. Add points off that plane"
            )
    Fn = _rank2(Vt[-1].reshape(3, 3))
    ah, bh = to_homogeneous(an), to_homogeneous(bn)
    for _ in range(int(sampson_iterations)):
        Fx, Ftx = ah @ Fn.T, bh @ Fn
        den = np.sqrt(Fx[:, 0] ** 2 + Fx[:, 1] ** 2 + Ftx[:, 0] ** 2 + Ftx[:, 1] ** 2)
        if not np.all(den > 0):
            break
        Fn = _rank2(np.linalg.svd(A / den[:, None], full_matrices=len(A) < 9)[2][-1].reshape(3, 3))
    F = normalise_fundamental(T2.T @ Fn @ T1)
    if len(a) >= 12:
        # Least squares fits any pairs, right or wrong: refuse a fit that explains them badly.
        med = float(np.median(_sampson_batch(F[None], a, b)[0]))
        spread = float(np.sqrt(np.mean(np.sum((b - b.mean(axis=0)) ** 2, axis=1))))
        if med > _BAD_FIT * spread:
            raise DegenerateError(
                f"x1, x2: no F explains these pairs: the best fit leaves a median Sampson distance of {med:.3g} px "
                f"({100 * med / spread:.0f}% of the points' spread); the matches are mostly wrong. Use "
                f"ransac_fundamental_matrix, which separates right matches from wrong ones"
            )
    return F


class FundamentalRansacResult(NamedTuple):
    """What :func:`ransac_fundamental_matrix` found.

    Attributes
    ----------
    F : (3, 3) ndarray
        The locally optimised F (Sampson-weighted 8-point on its inliers), unit norm.
    inliers : (N,) bool ndarray
        Pairs whose Sampson distance under ``F`` is below the threshold.
    iterations : int
        8-pair samples drawn.
    residuals : (N,) ndarray
        Sampson distance of every pair under ``F``, pixels.
    """

    F: np.ndarray
    inliers: np.ndarray
    iterations: int
    residuals: np.ndarray


class FundamentalModel(PairModel):
    """Fundamental matrices ``x2_h @ F @ x1_h = 0`` for the robust driver :func:`camlab.robust.ransac`.

    Minimal samples of 8 pairs are solved by the 8-point algorithm (batched SVD, rank 2
    enforced), larger sets by the normalised 8-point algorithm with two Sampson-weighted
    re-solves (see ``sampson_iterations`` in :func:`estimate_fundamental_matrix`), both in
    Hartley-normalised coordinates computed once; residuals are Sampson distances in pixels.
    """

    sample_size = 8
    name = "ransac_fundamental_matrix"

    def __init__(self, x1: np.ndarray, x2: np.ndarray):
        super().__init__(x1, x2)
        self.an, self.T1 = hartley_normalise(x1)
        self.bn, self.T2 = hartley_normalise(x2)

    def minimal(self, idx: np.ndarray) -> MinimalModels:
        """The 8-point solutions of B samples, rank 2 enforced (see :meth:`PairModel.minimal`).

        Parameters
        ----------
        idx : (B, 8) int ndarray
            B samples of eight pair indices.

        Returns
        -------
        MinimalModels
            ``models`` (B, 3, 3), F in pixels, and ``usable`` (B,).
        """
        _, s, Vt = np.linalg.svd(_eight_point_rows(self.an[idx], self.bn[idx]))
        ok = s[:, 7] > 1e-8 * s[:, 0]  # rank-deficient samples give no unique F
        return MinimalModels(self.T2.T @ _rank2(Vt[:, -1].reshape(-1, 3, 3)) @ self.T1, ok)

    def fit(self, idx: np.ndarray) -> np.ndarray:
        """The Sampson-weighted normalised 8-point fit of the pairs ``idx`` (see :meth:`PairModel.fit`).

        Parameters
        ----------
        idx : (K,) int ndarray
            Indices of the pairs to fit, K >= 8.

        Returns
        -------
        (3, 3) ndarray
            F in pixels, rank 2.
        """
        A = _eight_point_rows(self.an[idx], self.bn[idx])
        ah, bh = to_homogeneous(self.an[idx]), to_homogeneous(self.bn[idx])
        w = np.ones(len(A))
        for _ in range(3):  # the plain 8-point solve, then two Sampson-weighted ones
            Aw = A / w[:, None]
            ev, V = np.linalg.eigh(Aw.T @ Aw)
            if ev[1] <= 1e-12 * ev[-1]:
                raise DegenerateError(
                    "ransac_fundamental_matrix: the inliers do not fix a unique F"
                )
            Fn = _rank2(V[:, 0].reshape(3, 3))
            Fx, Ftx = ah @ Fn.T, bh @ Fn
            w = np.sqrt(Fx[:, 0] ** 2 + Fx[:, 1] ** 2 + Ftx[:, 0] ** 2 + Ftx[:, 1] ** 2)
            if not np.all(w > 0):
                break
        return normalise_fundamental(self.T2.T @ Fn @ self.T1)

    def residuals(
        self, models: np.ndarray, i1: np.ndarray | None = None, i2: np.ndarray | None = None
    ) -> np.ndarray:
        """The Sampson distance of each pair under each F, pixels (see :meth:`PairModel.residuals`).

        Parameters
        ----------
        models : (B, 3, 3) ndarray
            Fundamental matrices in pixels.
        i1, i2 : (M,) int ndarray, optional
            Indices into the points of images 1 and 2; None for the model's own pairs.

        Returns
        -------
        (B, M) ndarray
            Sampson distances, pixels.
        """
        a = self.x1 if i1 is None else self.x1[i1]
        b = self.x2 if i1 is None else self.x2[i1 if i2 is None else i2]
        return _sampson_batch(models, a, b)


def ransac_fundamental_matrix(
    x1: ArrayLike,
    x2: ArrayLike,
    threshold: float = 1.0,
    confidence: float = 0.999,
    max_iters: int = 5000,
    rng: np.random.Generator | int | None = None,
    *,
    batch: int = 128,
) -> FundamentalRansacResult:
    r"""Robust F from pairs with outliers: LO-RANSAC over 8-point samples, MSAC-scored by Sampson distance.

    :class:`FundamentalModel` plugged into the driver :func:`camlab.robust.ransac` (its
    docstring derives each step):

    1. Normalise both point sets once (Hartley [2]_).
    2. Draw samples of 8 distinct pairs in batches; solve all their 8-point systems with
       one batched SVD and enforce rank 2 on each.
    3. Score every hypothesis by the truncated quadratic (MSAC) cost
       :math:`\sum_i \min(d_i^2, t^2)` of the :func:`sampson_distance` d (pixels).
    4. Each time a hypothesis beats the best so far, re-fit it on its inliers
       (normalised 8-point with Sampson weights; local optimisation).
    5. Stop after :math:`k = \log(1-p) / \log(1-w^8)` samples for the best inlier ratio w
       seen so far, or ``max_iters``; refuse a consensus that wrong matches reach by chance.

    Parameters
    ----------
    x1, x2 : (N, 2) array_like
        Putative matches in pixels, N >= 8.
    threshold : float
        Inlier threshold on the Sampson distance, pixels.
    confidence : float
        Probability in (0, 1) of having drawn at least one all-inlier sample.
    max_iters : int
        Upper bound on samples.
    rng : np.random.Generator, int or None
        Seed it for reproducible results.
    batch : int
        Samples solved and scored per vectorised step.

    Returns
    -------
    FundamentalRansacResult
        ``F`` (3, 3) unit norm, ``inliers`` (N,) bool, ``iterations`` (samples drawn) and
        ``residuals`` (N,), Sampson distances in pixels.

    Raises
    ------
    DegenerateError
        Too few inliers: no hypothesis is supported by more pairs than wrong matches would
        support by chance (all matches wrong, or the threshold too small).

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 11.6 and algorithm
       11.4 (robust estimation of F).
    .. [2] R. I. Hartley, 1997, "In defense of the eight-point algorithm", *IEEE Transactions
       on Pattern Analysis and Machine Intelligence* 19(6), 580-593.
    """
    a, b, _ = as_point_pairs(x1, x2, min_count=8, why=EIGHT_POINT_REASON)
    fit = ransac(FundamentalModel(a, b), threshold, confidence, max_iters, rng, batch=batch)
    return FundamentalRansacResult(
        normalise_fundamental(fit.model), fit.inliers, fit.iterations, fit.residuals
    )
