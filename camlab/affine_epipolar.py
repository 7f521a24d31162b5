r"""Affine epipolar geometry: whether two views of a 3-D scene come from affine cameras.

Two affine cameras (last row :math:`(0, 0, 0, 1)`, lesson 05) have parallel rays, so
their epipolar lines are parallel in each image and their epipoles are at infinity.
The fundamental matrix then has the form (H&Z section 14.1)

.. math::

    F_A = \begin{pmatrix} 0 & 0 & a \\ 0 & 0 & b \\ c & d & e \end{pmatrix},
    \qquad
    \tilde x'^\top F_A \tilde x = a u' + b v' + c u + d v + e = 0 ,

a constraint *linear* in the four pixel coordinates of a match. Each match is a point
:math:`y = (u', v', u, v)` of :math:`\mathbb R^4`, and the matches of two affine views lie
on one hyperplane :math:`n^\top y + e = 0`, :math:`n = (a, b, c, d)`. This is what a 3-D
scene allows and a 2-D map does not: the second image of a point is not a function of
the first (depth moves it along the epipolar line), yet every match still satisfies
one linear equation.

The test this module makes: fit the 4-number :math:`F_A` and the 7-number general
:math:`F` to the same matches and ask whether the general one's extra freedom buys more
than noise would. If it does, at least one camera is not affine (perspective shows).
Unlike comparing an affinity with a homography, parallax between depths cannot fake
this: :math:`F_A` models it.

Conventions (docs/conventions.md): pixels (u, v) = (column, row), points are rows,
``x2_h @ F @ x1_h == 0``. See lesson 05.

References
----------
R. Hartley and A. Zisserman, *Multiple View Geometry in Computer Vision*, 2nd ed., 2003:
chapter 14 (affine epipolar geometry), algorithm 14.1 (the Gold Standard :math:`F_A`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._validate import DegenerateError, as_point_pairs
from .epipolar import estimate_fundamental_matrix, sampson_distance
from .optimise import levenberg_marquardt
from .projective import hartley_normalise

__all__ = [
    "AffineEpipolarTest",
    "AffineFundamental",
    "affine_epipolar_test",
    "estimate_affine_fundamental",
]


class AffineFundamental(NamedTuple):
    """The Gold Standard affine fundamental matrix and how far each match is from it."""

    F: np.ndarray
    """(3, 3) :math:`F_A`, zero upper-left 2 x 2 block, :math:`a^2 + b^2 + c^2 + d^2 = 1`."""
    residuals: np.ndarray
    """(N,) signed geometric error of each match, pixels."""
    rms: float
    """Root mean square of ``residuals``, pixels."""


class AffineEpipolarTest(NamedTuple):
    """The affine F against the general F on the same matches (:func:`affine_epipolar_test`)."""

    rms_affine: float
    """RMS geometric error of the Gold Standard :math:`F_A` (4 degrees of freedom), pixels."""
    rms_general: float
    """RMS Sampson distance of the general F (7 degrees of freedom) that minimises it, pixels."""
    statistic: float
    """F statistic of the nested models, :math:`F(3, N - 7)` distributed if both cameras are affine."""
    level: float
    """The statistic's 1 % critical value: above it, reject "both cameras affine"."""
    count: int
    """Number of matches N."""


def estimate_affine_fundamental(x1: ArrayLike, x2: ArrayLike) -> AffineFundamental:
    r"""Estimate the affine fundamental matrix from N >= 4 matches (H&Z algorithm 14.1).

    Derivation. The constraint :math:`n^\top y_i + e = 0` with :math:`y_i = (u_i', v_i',
    u_i, v_i)` and :math:`\lVert n \rVert = 1` says that :math:`n^\top y_i + e` is the signed
    distance of :math:`y_i` from the hyperplane: the shortest joint move of the four
    coordinates that satisfies the constraint, i.e. the geometric (reprojection) error of
    the match. Under isotropic Gaussian pixel noise the maximum-likelihood :math:`F_A`
    minimises :math:`\sum_i (n^\top y_i + e)^2`, an orthogonal regression:

    1. the best hyperplane passes through the centroid :math:`\bar y`, so
       :math:`e = -n^\top \bar y` (set the derivative with respect to :math:`e` to 0);
    2. with the centred points as the rows of :math:`Y`, :math:`\sum_i (n^\top (y_i - \bar
       y))^2 = \lVert Y n \rVert^2`, smallest for :math:`n` = the right singular vector of
       :math:`Y`'s smallest singular value.

    No iteration and no normalisation are needed: unlike the 8-point algorithm's algebraic
    error, this is the geometric error itself, and centring is part of the solution.

    Parameters
    ----------
    x1, x2 : (N, 2) array_like
        Corresponding pixels in image 1 and image 2, N >= 4.

    Returns
    -------
    AffineFundamental
        ``F`` with ``x2_h @ F @ x1_h == 0`` for exact matches, the signed residuals (px) and
        their RMS.

    Raises
    ------
    CamlabInputError
        If the pairs are not two (N, 2) arrays of the same N >= 4 finite pixels.
    DegenerateError
        If the matches span fewer than three directions of :math:`\mathbb R^4` (for example
        exact matches of one plane, related by an affinity): the hyperplane is then not
        unique.

    References
    ----------
    Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., section 14.2 and algorithm 14.1.

    Examples
    --------
    >>> x1 = np.array([[0.0, 0], [1, 0], [0, 1], [1, 1], [2, 3]])
    >>> x2 = x1 + [[0.0, 0], [0, 1], [0, 2], [0, 3], [0, 5]]   # parallax along v only
    >>> fit = estimate_affine_fundamental(x1, x2)
    >>> fit.rms < 1e-12, np.allclose(fit.F[:2, :2], 0)
    (True, True)
    """
    a, b, _ = as_point_pairs(x1, x2, min_count=4, why="the affine F has 4 degrees of freedom")
    y = np.c_[b, a]  # (u', v', u, v): x2 first, as in x2^T F x1
    centroid = y.mean(axis=0)
    _, s, vt = np.linalg.svd(y - centroid, full_matrices=False)
    if s[-2] <= 1e-9 * s[0]:
        raise DegenerateError(
            "estimate_affine_fundamental: the matches (u', v', u, v) span fewer than three "
            f"directions (singular values {np.array2string(s, precision=3)}), so no unique F_A "
            "fits them: an affinity maps every x1 to its x2 (one plane, or no parallax). Use "
            "matches at several depths"
        )
    n = vt[-1]
    F = np.zeros((3, 3))
    F[0, 2], F[1, 2], F[2, 0], F[2, 1] = n
    F[2, 2] = -n @ centroid
    residuals = (y - centroid) @ n
    return AffineFundamental(F, residuals, float(np.sqrt(np.mean(residuals**2))))


def _rotations(rvecs: np.ndarray) -> np.ndarray:
    r"""(B, 3, 3) rotations from (B, 3) rotation vectors, Rodrigues' formula batched.

    :math:`R = I + \sin\theta\,[k]_\times + (1 - \cos\theta)\,[k]_\times^2`, as
    :func:`camlab.camera.rotation_from_axis_angle` for one vector; at :math:`\theta = 0` the
    identity.
    """
    theta = np.linalg.norm(rvecs, axis=1)
    k = rvecs / np.where(theta > 0, theta, 1.0)[:, None]
    K = np.zeros((len(rvecs), 3, 3))
    K[:, 0, 1], K[:, 0, 2], K[:, 1, 2] = -k[:, 2], k[:, 1], -k[:, 0]
    K -= np.transpose(K, (0, 2, 1))
    s, c = np.sin(theta)[:, None, None], np.cos(theta)[:, None, None]
    return np.eye(3) + s * K + (1 - c) * K @ K


def _least_sampson_fundamental(F0: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    r"""The rank-2 F downhill from ``F0`` that minimises the summed squared Sampson distance (pixels).

    F is searched in Hartley-normalised coordinates, :math:`F = T_2^\top F_n T_1`, where pixel
    coordinates in the hundreds would make the parameters' effects differ by orders of
    magnitude and the search stall; the residuals stay in pixels. :math:`F_n` is kept rank 2 by
    its SVD, :math:`F_n = U R(\omega)\,\mathrm{diag}(1, s, 0)\,(V R(\eta))^\top` with :math:`U, V`
    from the start: 7 parameters :math:`(\omega, \eta, s)`, F's 7 degrees of freedom, refined by
    Levenberg-Marquardt. Its Jacobian is :func:`camlab.optimise.numeric_jacobian`'s central
    differences (the same steps), evaluated for all 14 shifted parameter vectors at once.
    """
    T1, T2 = hartley_normalise(a, "x1").T, hartley_normalise(b, "x2").T
    U, sv, Vt = np.linalg.svd(np.linalg.inv(T2).T @ F0 @ np.linalg.inv(T1))
    ah, bh = np.c_[a, np.ones(len(a))], np.c_[b, np.ones(len(b))]

    def compose(x):  # (B, 7) parameters -> (B, 3, 3) F in pixels
        left, right = U @ _rotations(x[:, :3]), Vt.T @ _rotations(x[:, 3:6])
        middle = np.zeros((len(x), 3, 3))
        middle[:, 0, 0], middle[:, 1, 1] = 1.0, x[:, 6]
        return T2.T @ (left @ middle @ np.transpose(right, (0, 2, 1))) @ T1

    def sampson(
        F,
    ):  # (B, 3, 3) -> (B, N), epipolar.sampson_distance for a stack, inputs known valid
        Fx, Ftx = ah @ np.transpose(F, (0, 2, 1)), bh @ F  # lines in image 2, in image 1
        den = Fx[..., 0] ** 2 + Fx[..., 1] ** 2 + Ftx[..., 0] ** 2 + Ftx[..., 1] ** 2
        return np.abs(np.sum(Fx * bh, axis=2)) / np.sqrt(den)

    def jacobian(x):  # central differences, h_k = 1e-6 max(1, |x_k|), as numeric_jacobian
        h = 1e-6 * np.maximum(1.0, np.abs(x))
        shifts = np.diag(h)
        r = sampson(compose(np.r_[x + shifts, x - shifts]))
        return ((r[:7] - r[7:]) / (2 * h[:, None])).T

    fit = levenberg_marquardt(
        lambda x: sampson(compose(x[None]))[0], np.r_[np.zeros(6), sv[1] / sv[0]], jacobian
    )
    return compose(fit.x[None])[0]


def affine_epipolar_test(x1: ArrayLike, x2: ArrayLike) -> AffineEpipolarTest:
    r"""Whether N >= 9 matches need a general F, or two affine cameras explain them.

    Both models give each match one residual, its geometric error (exact for
    :math:`F_A`, Sampson's first-order value for F). :math:`F_A` has 4 degrees of freedom
    (5 numbers up to scale), F has 7 (9 up to scale, rank 2), and :math:`F_A` is the special
    case of F, so under the hypothesis "both cameras affine" and Gaussian noise

    .. math:: \frac{(\mathrm{RSS}_A - \mathrm{RSS}_F)/3}{\mathrm{RSS}_F / (N - 7)} \sim F(3, N - 7),

    about 1; a value above the 1 % critical value rejects it. The general F minimises the
    summed squared Sampson distance by Levenberg-Marquardt in Hartley-normalised coordinates
    from three starts (:math:`F_A`, which is an F of rank 2 too, and the 8-point F with and
    without Sampson weighting), keeping the best: never worse than :math:`F_A`, so the statistic
    is never negative. Each start finds a local minimum; if all of them miss the global one,
    :math:`\mathrm{RSS}_F` is too large and the statistic too small, so the test can only err
    towards "affine". On affine synthetic data the statistic scatters about 1
    (tests/test_affine_epipolar.py).
    (Sampson's distance is first order; for matches a few pixels from their epipolar lines it
    equals the geometric error to a fraction of a percent.)

    Parameters
    ----------
    x1, x2 : (N, 2) array_like
        Corresponding pixels, N >= 9, not all on one plane.

    Returns
    -------
    AffineEpipolarTest
        Both RMS errors (px), the statistic, its 1 % level and N.

    Raises
    ------
    CamlabInputError
        If the pairs are not two (N, 2) arrays of the same N >= 9 finite pixels.
    DegenerateError
        If the matches are degenerate for either fit (one plane, no parallax).

    References
    ----------
    Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., chapter 14 (:math:`F_A`) and
    section 11.4.3 (the Sampson distance).
    """
    from scipy import stats  # scipy.stats takes 0.3 s to import: only when a test runs

    a, b, _ = as_point_pairs(
        x1, x2, min_count=9, why="the general F needs 8 pairs and one more to test"
    )
    affine = estimate_affine_fundamental(a, b)
    # three starts, each refined: F_A itself (an F of rank 2), the 8-point F and its Sampson-weighted
    # version; on near-affine matches they can end in different local minima, so keep the best
    starts = (
        affine.F,
        estimate_fundamental_matrix(a, b),
        estimate_fundamental_matrix(a, b, sampson_iterations=10),
    )
    rss_affine = float(np.sum(affine.residuals**2))
    refined = [_least_sampson_fundamental(F0, a, b) for F0 in starts]
    rss_general = min(rss_affine, *(float(np.sum(sampson_distance(F, a, b) ** 2)) for F in refined))
    n = len(a)
    statistic = ((rss_affine - rss_general) / 3) / (rss_general / (n - 7))
    return AffineEpipolarTest(
        affine.rms,
        float(np.sqrt(rss_general / n)),
        float(statistic),
        float(stats.f.ppf(0.99, 3, n - 7)),
        n,
    )
