r"""Two-view geometry: the fundamental and essential matrices, epipoles, epipolar lines, triangulation.

Two cameras see the same world point :math:`X` at pixels :math:`x` (image 1) and
:math:`x'` (image 2). The two rays and the baseline joining the camera centres lie in one
plane, the *epipolar plane*, so :math:`x'` must lie on the line where that plane cuts
image 2. Algebraically, for homogeneous pixels,

.. math:: \tilde x'^\top F\, \tilde x = 0, \qquad l' = F \tilde x, \qquad l = F^\top \tilde x',

with the (3, 3) *fundamental matrix* F of rank 2 (7 degrees of freedom). Its null vectors
are the *epipoles* :math:`F e = 0`, :math:`F^\top e' = 0`: the image of the other camera's
centre, through which every epipolar line passes. With calibrated cameras
(:math:`\hat x = K^{-1} \tilde x`) the same constraint reads
:math:`\hat x'^\top E \hat x = 0` with the *essential matrix*
:math:`E = [t]_\times R = K'^\top F K`, where ``(R, t)`` is camera 2's pose relative to
camera 1 (``X_2 = R X_1 + t``).

Conventions (docs/conventions.md): points are rows, pixels (u, v) = (column, row) with the
origin at the centre of the top-left pixel; ``x1`` are pixels in image 1 and ``x2`` the
corresponding pixels in image 2, so ``x2_h @ F @ x1_h == 0``; poses are cam_from_world;
metres. See lesson 11 and Hartley & Zisserman chapters 9-12.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._validate import (
    CamlabInputError,
    DegenerateError,
    as_float,
    as_point_pairs,
    as_points,
    check_intrinsics,
    check_matrix,
    check_rotation,
)
from .camera import Camera, Pose, camera_centre, check_camera_matrix
from .homography import estimate_homography, symmetric_transfer_error
from .optimize import block_damped_solve, block_normal_equations, levenberg_marquardt
from .projective import from_homogeneous, hartley_normalise, normalise_lines, to_homogeneous
from .robust import MinimalModels, PairModel, ransac

__all__ = [
    "EssentialDecomposition",
    "FundamentalModel",
    "FundamentalRansacResult",
    "RelativePose",
    "decompose_essential_matrix",
    "epipolar_distance",
    "epipolar_lines",
    "epipoles",
    "essential_from_fundamental",
    "essential_matrix",
    "estimate_fundamental_matrix",
    "fundamental_from_cameras",
    "fundamental_from_essential",
    "normalise_fundamental",
    "ransac_fundamental_matrix",
    "recover_pose",
    "relative_pose",
    "sampson_distance",
    "skew",
    "triangulate_points",
]

_PLANE_TOL = (
    1e-3  # px: a homography explaining every pair this well means "all points on one plane"
)
_BAD_FIT = 0.05  # a least-squares F with median Sampson distance above this fraction of the spread: wrong pairs
_RANK_TOL = 1e-9  # second-smallest singular value of the normalised 8-point system, relative


# --------------------------------------------------------------------------- helpers


def skew(v: ArrayLike) -> np.ndarray:
    r"""The cross-product matrix :math:`[v]_\times` with :math:`[v]_\times w = v \times w`.

    >>> skew([1, 2, 3]) @ np.array([4, 5, 6]), np.cross([1, 2, 3], [4, 5, 6])
    (array([-3.,  6., -3.]), array([-3,  6, -3]))
    """
    a = check_matrix(v, (3,), "v")
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


EIGHT_POINT_REASON = (
    "the fundamental matrix has 7 degrees of freedom and the linear 8-point algorithm needs 8 pairs"
)


def check_fundamental(F: ArrayLike, name: str = "F") -> np.ndarray:
    """Return F as a float (3, 3) array, or raise if it is malformed or all zeros."""
    a = check_matrix(F, (3, 3), name)
    if not np.any(a):
        raise CamlabInputError(
            f"{name}: expected a non-zero (3, 3) fundamental matrix, got all zeros"
        )
    return a


def normalise_fundamental(F: ArrayLike) -> np.ndarray:
    """Scale F to unit Frobenius norm with its largest-magnitude entry positive (compare F's up to scale).

    >>> normalise_fundamental(-2 * np.eye(3)).round(4)
    array([[0.5774, 0.    , 0.    ],
           [0.    , 0.5774, 0.    ],
           [0.    , 0.    , 0.5774]])
    """
    a = check_fundamental(F)
    a = a / np.linalg.norm(a)
    k = np.argmax(
        np.round(np.abs(a), 9)
    )  # ties (e.g. a skew-symmetric F): the first in row-major order
    return a * np.sign(a.flat[k])


# --------------------------------------------------------------------------- from known cameras


def relative_pose(camera1: Camera, camera2: Camera) -> Pose:
    r"""Camera 2's pose relative to camera 1: ``(R, t)`` with :math:`X_2 = R X_1 + t`.

    With cam_from_world poses :math:`X_i = R_i X + t_i`:
    :math:`R = R_2 R_1^\top`, :math:`t = t_2 - R t_1`. The baseline length is
    :math:`\|t\| = \|C_2 - C_1\|` (metres).
    """
    for c, n in ((camera1, "camera1"), (camera2, "camera2")):
        if not isinstance(c, Camera):
            raise CamlabInputError(f"{n}: expected a camlab.camera.Camera, got {type(c).__name__}")
    R = camera2.R @ camera1.R.T
    return Pose(R, camera2.t - R @ camera1.t)


def essential_matrix(R: ArrayLike, t: ArrayLike) -> np.ndarray:
    r""":math:`E = [t]_\times R` for the relative pose :math:`X_2 = R X_1 + t`.

    Derivation: :math:`X_2 = R X_1 + t` and :math:`t`, :math:`X_2` and :math:`R X_1` are
    coplanar (the epipolar plane), so :math:`X_2 \cdot (t \times R X_1) = 0`, i.e.
    :math:`X_2^\top [t]_\times R X_1 = 0`; dividing by the depths gives
    :math:`\hat x_2^\top E \hat x_1 = 0` for normalised image points.
    """
    Rm = check_rotation(R, "R")
    tv = check_matrix(np.ravel(as_float(t, "t")), (3,), "t")
    if not tv.any():
        raise DegenerateError(
            "t: zero translation gives E = 0: with no baseline the two views share one centre and "
            "there is no epipolar geometry (use a rotation homography instead)"
        )
    return skew(tv) @ Rm


def fundamental_from_cameras(
    camera1: Camera | ArrayLike, camera2: Camera | ArrayLike
) -> np.ndarray:
    r"""The fundamental matrix of two known cameras, unit Frobenius norm.

    Parameters
    ----------
    camera1, camera2 : Camera or (3, 4) array_like
        The cameras (distortion is ignored: F relates *undistorted* pixels), or their
        projection matrices.

    Returns
    -------
    (3, 3) ndarray
        F with ``x2_h @ F @ x1_h == 0`` for corresponding pixels.

    Notes
    -----
    For two :class:`~camlab.camera.Camera` objects,
    :math:`F = K_2^{-\top} [t]_\times R\, K_1^{-1}` with the relative pose from
    :func:`relative_pose`. For general projection matrices (H&Z result 9.1),

    .. math:: F = [e']_\times P_2 P_1^+, \qquad e' = P_2 C_1,

    where :math:`C_1` is camera 1's centre (the null vector of :math:`P_1`) and
    :math:`P_1^+` its pseudo-inverse: :math:`P_1^+ x` is a point on the ray of :math:`x`,
    its image is :math:`P_2 P_1^+ x`, and the epipolar line joins it to the epipole.

    Raises
    ------
    DegenerateError
        If both cameras have the same centre (no baseline: no epipolar geometry).
    """
    if isinstance(camera1, Camera) and isinstance(camera2, Camera):
        R, t = relative_pose(camera1, camera2)
        base = np.linalg.norm(t)
        scale = max(np.linalg.norm(camera1.centre), np.linalg.norm(camera2.centre), 1.0)
        if base <= 1e-12 * scale:
            raise DegenerateError(
                "fundamental_from_cameras: the two cameras have the same centre (baseline 0 m); "
                "a pure rotation has no epipolar geometry (the images are related by a homography). "
                "Move one camera"
            )
        F = np.linalg.inv(camera2.K).T @ essential_matrix(R, t) @ np.linalg.inv(camera1.K)
        return normalise_fundamental(F)
    P1, P2 = check_camera_matrix(camera1, "camera1"), check_camera_matrix(camera2, "camera2")
    C1h = camera_centre(P1)  # (4,) homogeneous
    e2 = P2 @ C1h
    if np.linalg.norm(e2) <= 1e-12 * np.linalg.norm(P2) * np.linalg.norm(C1h):
        raise DegenerateError(
            "fundamental_from_cameras: camera 1's centre projects to 0 in camera 2, so both cameras have "
            "the same centre (no baseline); move one camera"
        )
    return normalise_fundamental(skew(e2) @ P2 @ np.linalg.pinv(P1))


def essential_from_fundamental(
    F: ArrayLike, K1: ArrayLike, K2: ArrayLike | None = None
) -> np.ndarray:
    r""":math:`E = K_2^\top F K_1`, projected onto the essential matrices (singular values (1, 1, 0)).

    A true essential matrix has two equal singular values and one zero (H&Z result 9.17);
    an F estimated from noisy points gives an E that is close, and the closest one in the
    Frobenius norm replaces the singular values by their mean.
    """
    F = check_fundamental(F)
    K1 = check_intrinsics(K1, "K1")
    K2 = K1 if K2 is None else check_intrinsics(K2, "K2")
    U, s, Vt = np.linalg.svd(K2.T @ F @ K1)
    return U @ np.diag([1.0, 1.0, 0.0]) @ Vt


def fundamental_from_essential(
    E: ArrayLike, K1: ArrayLike, K2: ArrayLike | None = None
) -> np.ndarray:
    r""":math:`F = K_2^{-\top} E K_1^{-1}`, unit Frobenius norm."""
    E = check_fundamental(E, "E")
    K1 = check_intrinsics(K1, "K1")
    K2 = K1 if K2 is None else check_intrinsics(K2, "K2")
    return normalise_fundamental(np.linalg.inv(K2).T @ E @ np.linalg.inv(K1))


# --------------------------------------------------------------------------- epipoles and lines


class Epipoles(NamedTuple):
    """Homogeneous epipoles, unit norm: ``e1`` in image 1 (F e1 = 0), ``e2`` in image 2 (F^T e2 = 0).

    An epipole with third coordinate 0 is an ideal point: the epipolar lines are parallel
    (the baseline is parallel to that image plane). ``from_homogeneous`` gives its pixel
    (NaN when ideal).
    """

    e1: np.ndarray
    e2: np.ndarray


def epipoles(F: ArrayLike) -> Epipoles:
    r"""The epipoles: the right and left null vectors of F (last singular vectors).

    ``e1`` is the image of camera 2's centre in image 1 and ``e2`` the image of camera 1's
    centre in image 2. Signs are chosen so the last non-zero coordinate is positive.

    >>> F = np.array([[0, 0, 0], [0, 0, -1], [0, 1, 0]])  # a pure x-translation: rows match
    >>> epipoles(F).e1
    array([1., 0., 0.])
    """
    F = check_fundamental(F)
    U, s, Vt = np.linalg.svd(F)
    out = []
    for e in (Vt[-1], U[:, -1]):
        nz = np.flatnonzero(np.abs(e) > 1e-12)
        out.append(e * np.sign(e[nz[-1]]) if len(nz) else e)
    return Epipoles(*out)


def epipolar_lines(F: ArrayLike, points: ArrayLike, image: int = 1) -> np.ndarray:
    r"""Epipolar lines in the *other* image for points in image ``image``.

    Parameters
    ----------
    F : (3, 3) array_like
        Fundamental matrix with ``x2_h @ F @ x1_h == 0``.
    points : (N, 2) or (2,) array_like
        Pixels (u, v) in image ``image``.
    image : {1, 2}
        1: points are in image 1, lines :math:`l' = F \tilde x` are in image 2;
        2: points are in image 2, lines :math:`l = F^\top \tilde x'` are in image 1.

    Returns
    -------
    (N, 3) or (3,) ndarray
        Lines (a, b, c) with :math:`a^2 + b^2 = 1`, so :math:`a u + b v + c` is the signed
        distance in pixels of (u, v) from the line.

    >>> F = np.array([[0, 0, 0], [0, 0, -1], [0, 1, 0]])
    >>> epipolar_lines(F, [10, 20])  # the row v = 20
    array([ 0., -1., 20.])
    """
    F = check_fundamental(F)
    if image not in (1, 2):
        raise CamlabInputError(
            f"image: expected 1 or 2 (the image the points are in), got {image!r}"
        )
    p = as_points(points, 2, "points")
    M = F if image == 1 else F.T
    lines = to_homogeneous(p.array) @ M.T
    if np.any(np.linalg.norm(lines[:, :2], axis=1) == 0):
        raise DegenerateError(
            "epipolar_lines: a point is the epipole itself, whose epipolar line is undefined"
        )
    return p.restore(normalise_lines(lines))


def epipolar_distance(F: ArrayLike, x1: ArrayLike, x2: ArrayLike) -> np.ndarray:
    r"""Symmetric epipolar distance per pair, RMS in pixels.

    .. math:: d_i = \sqrt{\tfrac12\left(d(x'_i, F x_i)^2 + d(x_i, F^\top x'_i)^2\right)}
    """
    F = check_fundamental(F)
    a, b, single = as_point_pairs(x1, x2)
    d2 = np.sum(to_homogeneous(b) * epipolar_lines(F, a, 1), axis=1)
    d1 = np.sum(to_homogeneous(a) * epipolar_lines(F, b, 2), axis=1)
    out = np.sqrt(0.5 * (d1**2 + d2**2))
    return out[0] if single else out


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
    linearised constraint (H&Z section 11.4.3), close to the gold-standard reprojection
    error without triangulating. Compare with OpenCV's inlier thresholds in pixels.

    >>> F = np.array([[0, 0, 0], [0, 0, -1], [0, 1, 0]])
    >>> sampson_distance(F, [[0, 0]], [[5, 2]])  # 2 px vertical offset, shared by both images
    array([1.41421356])
    """
    F = check_fundamental(F)
    a, b, single = as_point_pairs(x1, x2)
    out = _sampson_batch(F[None], a, b)[0]
    return out[0] if single else out


# --------------------------------------------------------------------------- estimation


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

    Derivation (H&Z algorithm 11.1). Each pair gives one linear equation in the nine
    entries :math:`f` of F (row-major):

    .. math:: \tilde x'^\top F \tilde x = 0 \iff
              (u'u,\ u'v,\ u',\ v'u,\ v'v,\ v',\ u,\ v,\ 1)\, f = 0 .

    1. Normalise each image's points with a similarity T (centroid to 0, mean distance
       :math:`\sqrt 2`): pixel coordinates in the hundreds make the columns of A differ by
       :math:`10^5` in size and the unnormalised solution is poor (Hartley 1997).
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

    Examples
    --------
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
        _, s, Vt = np.linalg.svd(_eight_point_rows(self.an[idx], self.bn[idx]))
        ok = s[:, 7] > 1e-8 * s[:, 0]  # rank-deficient samples give no unique F
        return MinimalModels(self.T2.T @ _rank2(Vt[:, -1].reshape(-1, 3, 3)) @ self.T1, ok)

    def fit(self, idx: np.ndarray) -> np.ndarray:
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

    1. Normalise both point sets once (Hartley).
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

    Raises
    ------
    DegenerateError
        Too few inliers: no hypothesis is supported by more pairs than wrong matches would
        support by chance (all matches wrong, or the threshold too small).
    """
    a, b, _ = as_point_pairs(x1, x2, min_count=8, why=EIGHT_POINT_REASON)
    fit = ransac(FundamentalModel(a, b), threshold, confidence, max_iters, rng, batch=batch)
    return FundamentalRansacResult(
        normalise_fundamental(fit.model), fit.inliers, fit.iterations, fit.residuals
    )


# --------------------------------------------------------------------------- essential matrix and pose


class EssentialDecomposition(NamedTuple):
    """The four poses an essential matrix allows: ``R`` (4, 3, 3), ``t`` (4, 3) unit vectors.

    Candidates are ``(R_a, t), (R_a, -t), (R_b, t), (R_b, -t)``; only one puts the points in
    front of both cameras (see :func:`recover_pose`).
    """

    R: np.ndarray
    t: np.ndarray


def decompose_essential_matrix(E: ArrayLike) -> EssentialDecomposition:
    r"""The four (R, t) with :math:`E \sim [t]_\times R` (H&Z result 9.19).

    With :math:`E = U\,\mathrm{diag}(1, 1, 0)\,V^\top` (U, V rotations) and
    :math:`W = \begin{pmatrix}0&-1&0\\1&0&0\\0&0&1\end{pmatrix}`:
    :math:`R \in \{U W V^\top,\ U W^\top V^\top\}` and :math:`t = \pm u_3` (the last column
    of U, the left null vector of E: the baseline direction, its length unknown).
    """
    E = check_matrix(E, (3, 3), "E")
    U, s, Vt = np.linalg.svd(E)
    if s[0] <= 0 or s[1] < 0.5 * s[0] or s[2] > 0.1 * s[0]:
        raise DegenerateError(
            f"E: singular values {np.round(s / max(s[0], 1e-300), 4).tolist()} "
            f"(relative) are far from (1, 1, 0); this is not an essential matrix. Did you pass F instead of "
            f"K2^T F K1?"
        )
    if np.linalg.det(U) < 0:
        U = -U
    if np.linalg.det(Vt) < 0:
        Vt = -Vt
    W = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    Ra, Rb = U @ W @ Vt, U @ W.T @ Vt
    t = U[:, 2]
    return EssentialDecomposition(np.stack([Ra, Ra, Rb, Rb]), np.stack([t, -t, t, -t]))


class RelativePose(NamedTuple):
    """What :func:`recover_pose` chose.

    ``R`` (3, 3), ``t`` (3,) unit: camera 2's pose relative to camera 1 (``X_2 = R X_1 + t``,
    baseline length unknown: scale t by it); ``points`` (N, 3) triangulated in camera 1's
    frame (units of the baseline); ``in_front`` (N,) bool: in front of both cameras;
    ``counts`` (4,): points in front for each candidate of :func:`decompose_essential_matrix`.
    """

    R: np.ndarray
    t: np.ndarray
    points: np.ndarray
    in_front: np.ndarray
    counts: np.ndarray


def recover_pose(
    E: ArrayLike, x1: ArrayLike, x2: ArrayLike, K1: ArrayLike, K2: ArrayLike | None = None
) -> RelativePose:
    r"""Pick the one (R, t) of the four from E that puts the points in front of both cameras.

    The cheirality test: triangulate every pair with :math:`P_1 = K_1 [I \mid 0]` and
    each candidate :math:`P_2 = K_2 [R \mid t]`; a point is valid if its depth is positive
    in both cameras. Three of the candidates put (almost) every point behind a camera.
    """
    K1 = check_intrinsics(K1, "K1")
    K2 = K1 if K2 is None else check_intrinsics(K2, "K2")
    a, b, _ = as_point_pairs(x1, x2)
    cands = decompose_essential_matrix(E)
    P1 = K1 @ np.eye(3, 4)
    best = None
    counts = np.zeros(4, dtype=int)
    for i, (R, t) in enumerate(zip(cands.R, cands.t, strict=True)):
        X = triangulate_points(P1, K2 @ np.column_stack([R, t]), a, b)
        front = (X[:, 2] > 0) & ((X @ R.T + t)[:, 2] > 0)
        counts[i] = int(front.sum())
        if best is None or counts[i] > counts[best[0]]:
            best = (i, X, front)
    i, X, front = best
    return RelativePose(cands.R[i], cands.t[i], X, front, counts)


# --------------------------------------------------------------------------- triangulation


def _refine_points(Ps: list[np.ndarray], uvs: list[np.ndarray], X: np.ndarray) -> np.ndarray:
    """Minimise the summed squared reprojection error over each point independently:
    Levenberg-Marquardt (:func:`camlab.optimize.levenberg_marquardt`) on the block-diagonal
    problem, 3 unknowns and 2 residuals per camera for each point. A point on a camera's
    principal plane (depth 0) has no reprojection error and stays where it is."""
    X = X.copy()
    ok = np.all([(X @ P[2, :3] + P[2, 3]) != 0 for P in Ps], axis=0)
    obs = [uv[ok] for uv in uvs]

    def residuals(x):
        Xs = x.reshape(-1, 3)
        r = []
        for P, uv in zip(Ps, obs, strict=True):
            h = Xs @ P[:, :3].T + P[:, 3]
            r.append(h[:, :2] / h[:, 2:3] - uv)
        return np.concatenate(r, axis=1).ravel()  # point by point: 2 per camera

    def jacobian(x):
        Xs = x.reshape(-1, 3)
        J = []
        for P in Ps:
            h = Xs @ P[:, :3].T + P[:, 3]
            w = h[:, 2:3]
            # d(h_xy / w)/dX = (P_xy - (h_xy / w) P_w) / w
            J.append(
                (P[None, :2, :3] - (h[:, :2] / w)[:, :, None] * P[None, 2:3, :3]) / w[:, :, None]
            )
        return np.concatenate(J, axis=1)  # (N, 2 per camera, 3) blocks

    if ok.any():
        fit = levenberg_marquardt(
            residuals,
            X[ok].ravel(),
            jacobian,
            normal_equations=block_normal_equations,
            damped_solve=block_damped_solve,
            max_iter=50,
        )
        X[ok] = fit.x.reshape(-1, 3)
    return X


def triangulate_points(
    P1: Camera | ArrayLike,
    P2: Camera | ArrayLike,
    x1: ArrayLike,
    x2: ArrayLike,
    refine: bool = False,
) -> np.ndarray:
    r"""World points from their pixels in two cameras: linear (DLT), optionally refined.

    Linear triangulation (H&Z section 12.2). :math:`\tilde x \sim P X` means
    :math:`\tilde x \times P X = 0`, two independent equations per image:

    .. math::
        \begin{pmatrix} u\, p^{3\top} - p^{1\top} \\ v\, p^{3\top} - p^{2\top} \\
        u'\, p'^{3\top} - p'^{1\top} \\ v'\, p'^{3\top} - p'^{2\top} \end{pmatrix} \tilde X = 0,

    solved for each point by the smallest right singular vector of this 4x4 matrix
    (rows scaled to unit norm for conditioning). It minimises an algebraic error; with
    ``refine=True`` each point then moves to minimise the geometric error
    :math:`\|x - \pi(P X)\|^2 + \|x' - \pi(P' X)\|^2` by damped Gauss-Newton (3 unknowns per
    point, all points at once), the maximum-likelihood estimate under Gaussian pixel noise.

    Parameters
    ----------
    P1, P2 : Camera or (3, 4) array_like
        The two cameras (undistorted pixels).
    x1, x2 : (N, 2) or (2,) array_like
        Corresponding pixels.
    refine : bool
        Minimise reprojection error after the linear solution.

    Returns
    -------
    (N, 3) or (3,) ndarray
        World points (NaN for points at infinity, e.g. parallel rays).

    >>> cam1 = Camera.look_at([0, -3, 0], [0, 0, 0]); cam2 = Camera.look_at([0.5, -3, 0], [0, 0, 0])
    >>> X = np.array([0.1, 0.2, -0.1])
    >>> triangulate_points(cam1, cam2, cam1.project(X), cam2.project(X)).round(9) + 0.0
    array([ 0.1,  0.2, -0.1])
    """
    A1, A2 = check_camera_matrix(P1, "P1"), check_camera_matrix(P2, "P2")
    a, b, single = as_point_pairs(x1, x2)
    C1, C2 = camera_centre(A1), camera_centre(A2)
    if np.linalg.norm(C1 - C2) <= 1e-9 * max(
        np.linalg.norm(C1[:3]), np.linalg.norm(C2[:3]), 1e-300
    ):
        raise DegenerateError(
            "P1, P2: both cameras have the same centre (zero baseline), so the rays of "
            "corresponding pixels meet only there and depth is undetermined; move one camera"
        )
    rows = np.stack(
        [
            a[:, 0:1] * A1[2] - A1[0],
            a[:, 1:2] * A1[2] - A1[1],
            b[:, 0:1] * A2[2] - A2[0],
            b[:, 1:2] * A2[2] - A2[1],
        ],
        axis=1,
    )  # (N, 4, 4)
    rows /= np.linalg.norm(rows, axis=2, keepdims=True)
    _, _, Vt = np.linalg.svd(rows)
    X = from_homogeneous(Vt[:, -1, :])
    if refine:
        ok = np.all(np.isfinite(X), axis=1)
        X[ok] = _refine_points([A1, A2], [a[ok], b[ok]], X[ok])
    return X[0] if single else X
