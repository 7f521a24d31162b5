r"""Decomposing and estimating a camera matrix: RQ, :math:`P = \lambda K [R \mid t]`, and the camera DLT.

:func:`rq_decomposition` and :func:`decompose_projection_matrix` recover K, R, t and the
centre from P; :func:`estimate_projection_matrix` finds P from N >= 6 world-image
correspondences (resectioning [1]_), optionally refined on the
:func:`reprojection_errors`. Part of :mod:`camlab.camera` (every name here is importable
from there).

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, chapter 7 (computation of the
   camera matrix P), algorithm 7.1.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    ConvergenceError,
    DegenerateError,
    as_point_pairs,
    check_finite,
    check_matrix,
)
from ..optimise import levenberg_marquardt, unit_sphere_basis, unit_sphere_update
from ..projective import hartley_normalise
from .model import Camera, check_camera_matrix, project_points

__all__ = [
    "Decomposition",
    "RQ",
    "decompose_projection_matrix",
    "estimate_projection_matrix",
    "reprojection_errors",
    "rq_decomposition",
]


class Decomposition(NamedTuple):
    r"""The factors of :math:`P = \lambda K [R \mid t]`.

    K (K[2, 2] = 1, positive focal lengths), R (det +1), t (cam_from_world) and the camera centre C
    = -R^T t.
    """

    K: np.ndarray
    R: np.ndarray
    t: np.ndarray
    centre: np.ndarray


class RQ(NamedTuple):
    """The factors of :func:`rq_decomposition`: ``K`` upper triangular, ``R`` orthogonal."""

    K: np.ndarray
    R: np.ndarray


def rq_decomposition(M: ArrayLike) -> RQ:
    r"""RQ decomposition :math:`M = K R`: K upper triangular with a positive diagonal, R orthogonal.

    numpy only has QR (orthogonal times triangular), so we reverse the order of rows.
    With the exchange matrix E (ones on the anti-diagonal, :math:`E = E^\top = E^{-1}`),
    QR of :math:`(E M)^\top = Q' U'` gives :math:`M = E U'^\top Q'^\top = (E U'^\top E)(E Q'^\top)`,
    and :math:`E U'^\top E` is upper triangular. The factors are unique only up to
    :math:`D = \operatorname{diag}(\pm 1, \pm 1, \pm 1)` since :math:`K R = (K D)(D R)`;
    choosing D = sign(diag(K)) makes the diagonal of K positive. Then
    :math:`\det R = \operatorname{sign}(\det M)`: R is a rotation exactly when det M > 0.

    Parameters
    ----------
    M : (3, 3) array_like
        Invertible, e.g. the left 3x3 block of a camera matrix.

    Returns
    -------
    RQ
        ``K`` (3, 3): upper triangular, positive diagonal (not normalised: K[2, 2] carries
        M's scale); ``R`` (3, 3): orthogonal.

    Examples
    --------
    >>> K, R = rq_decomposition(np.diag([2.0, -3.0, 4.0]))
    >>> np.diag(K), np.diag(R)
    (array([2., 3., 4.]), array([ 1., -1.,  1.]))
    """
    Mm = check_matrix(M, (3, 3), "M")
    if abs(np.linalg.det(Mm)) <= 1e-12 * max(np.abs(Mm).max(), 1e-300) ** 3:
        raise DegenerateError(
            "rq_decomposition: M is singular, so K would have a zero on its diagonal; "
            "a finite camera has an invertible left 3x3 block"
        )
    E = np.eye(3)[::-1]
    Q, U = np.linalg.qr((E @ Mm).T)
    K, R = E @ U.T @ E, E @ Q.T
    D = np.diag(np.sign(np.diag(K)))
    return RQ(K @ D, D @ R)


def decompose_projection_matrix(P: ArrayLike) -> Decomposition:
    r"""Factor a finite camera :math:`P = \lambda K [R \mid t]` by RQ decomposition.

    Derivation [1]_: the left 3x3 block is :math:`M = \lambda K R`, an
    upper-triangular matrix times a rotation, which is exactly an RQ decomposition.
    RQ is unique only up to signs: :math:`K R = (K D)(D R)` for any
    :math:`D = \operatorname{diag}(\pm 1, \pm 1, \pm 1)`. We

    1. flip the sign of P if :math:`\det M < 0` (P is defined up to scale; now
       :math:`\det(\lambda K R) > 0`);
    2. choose D = sign(diag(K)) so the focal lengths and K[2, 2] are positive; then
       :math:`\det R = \det M / \det K > 0`, so R is a rotation;
    3. read :math:`t = K^{-1} p_4` with the still unnormalised K (it carries
       :math:`\lambda`), then divide K by K[2, 2].

    The centre is :math:`C = -R^\top t`, the null space of P.

    Parameters
    ----------
    P : (3, 4) array_like
        A finite projective camera (left 3x3 block invertible), any scale or sign.

    Returns
    -------
    Decomposition
        ``(K, R, t, centre)``.

    Raises
    ------
    DegenerateError
        If P has rank < 3, or M is singular (an affine camera: use camlab.affine).

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 6.2.4
       (decomposition of the camera matrix).

    Examples
    --------
    >>> cam = Camera.look_at([4, -3, 2], [0, 0, 0])
    >>> K, R, t, C = decompose_projection_matrix(-2.5 * cam.P)
    >>> bool(np.allclose(K, cam.K) and np.allclose(R, cam.R) and np.allclose(C, [4, -3, 2]))
    True
    """
    Pm = check_camera_matrix(P)
    M = Pm[:, :3]
    s = np.linalg.svd(M, compute_uv=False)
    if s[2] <= 1e-10 * s[0]:
        raise DegenerateError(
            "decompose_projection_matrix: P's left 3x3 block M is singular, so the camera centre is at "
            "infinity (an affine camera) and P has no K [R | t] form; see camlab.affine"
        )
    if np.linalg.det(M) < 0:
        Pm = -Pm
        M = Pm[:, :3]
    K, R = rq_decomposition(M)
    t = np.linalg.solve(K, Pm[:, 3])
    K = K / K[2, 2]
    K[1, 0] = K[2, 0] = K[2, 1] = 0.0  # exactly triangular (they are ~1e-17 after RQ)
    return Decomposition(K, R, t, -R.T @ t)


def reprojection_errors(
    P: Camera | ArrayLike, points_world: ArrayLike, points_image: ArrayLike
) -> np.ndarray:
    """(N,) distances in pixels between ``points_image`` and the projections of ``points_world``.

    ``P`` is a :class:`Camera` or a (3, 4) camera matrix (:func:`project_points`); a point
    behind the camera has no projection, and its distance is NaN.

    Parameters
    ----------
    P : Camera or (3, 4) array_like
        The camera.
    points_world : (N, 3) array_like
        World points, metres.
    points_image : (N, 2) array_like
        Their measured pixels (u, v).

    Returns
    -------
    (N,) ndarray
        Distances, pixels; NaN for points behind the camera.
    """
    X, uv, _ = as_point_pairs(
        points_world, points_image, ("points_world", "points_image"), (3, 2), finite=False
    )
    check_finite(uv, "points_image")
    return np.linalg.norm(project_points(P, X) - uv, axis=1)


def _thinnest_spread(sv: np.ndarray) -> str:
    """Words for how flat a point set is, from its singular values (widest first)."""
    ratio = sv[2] / max(sv[0], 1e-300)
    if ratio == 0.0:
        return "they have no spread at all across their thinnest direction"
    return f"their spread across the thinnest direction is only {ratio:.1e} times the widest"


def estimate_projection_matrix(
    points_world: ArrayLike,
    points_image: ArrayLike,
    refine: bool = False,
) -> np.ndarray:
    r"""Estimate P from N >= 6 world-image correspondences (resectioning, the camera DLT).

    Each correspondence :math:`\tilde u_i \simeq P \tilde X_i` gives, from
    :math:`\tilde u_i \times P \tilde X_i = 0`, two linear equations in the 12 entries
    of P (rows :math:`p^{1\top}, p^{2\top}, p^{3\top}`):

    .. math::

        \begin{pmatrix} \tilde X_i^\top & 0^\top & -u_i \tilde X_i^\top \\
                        0^\top & \tilde X_i^\top & -v_i \tilde X_i^\top \end{pmatrix}
        \begin{pmatrix} p^1 \\ p^2 \\ p^3 \end{pmatrix} = 0 .

    Stacking gives :math:`A p = 0` with A of size 2N x 12; P has 11 degrees of freedom, so
    5.5 correspondences are needed and we ask for 6. The least-squares solution with
    :math:`\|p\| = 1` is the right singular vector of A with the smallest singular value.

    Hartley normalisation (H&Z algorithm 7.1 [1]_) makes this well conditioned: the image
    points are moved to centroid 0 and mean distance :math:`\sqrt 2` by T, the world
    points to centroid 0 and mean distance :math:`\sqrt 3` by U, the DLT estimates
    :math:`\hat P` for the normalised points, and :math:`P = T^{-1} \hat P U`.

    With ``refine=True`` the linear estimate seeds Levenberg-Marquardt
    (:func:`camlab.optimise.levenberg_marquardt`, on the unit sphere of P's 12 entries) on the
    reprojection error
    :math:`\sum_i \|u_i - \pi(P, X_i)\|^2`, the maximum-likelihood (gold standard)
    estimate under Gaussian pixel noise.

    Parameters
    ----------
    points_world : (N, 3) array_like
        World points (metres), not all on one plane.
    points_image : (N, 2) array_like
        Their pixels (u, v).
    refine : bool
        Polish the linear estimate by minimising reprojection error.

    Returns
    -------
    (3, 4) ndarray
        P scaled so that its third row's first three entries have unit norm and
        :math:`\det M > 0`; then ``P @ [X, 1]`` has the point's depth as third coordinate.

    Raises
    ------
    CamlabInputError
        Fewer than 6 correspondences, or different counts.
    DegenerateError
        The world points are coplanar (or collinear): P is then not determined, since a
        plane only fixes a homography (8 of P's 11 degrees of freedom). Also raised when
        the solution is not unique for another reason.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 7.1 and
       algorithm 7.1 (the DLT for the camera, normalisation, the Gold Standard algorithm).
    """
    X, uv, _ = as_point_pairs(
        points_world,
        points_image,
        ("points_world", "points_image"),
        (3, 2),
        min_count=6,
        why="P has 11 degrees of freedom and each point gives 2 equations; add more points",
    )
    sv = np.linalg.svd(X - X.mean(axis=0), compute_uv=False)
    if sv[2] <= 1e-9 * sv[0]:
        raise DegenerateError(
            f"estimate_projection_matrix: the {len(X)} world points are coplanar ({_thinnest_spread(sv)}), "
            f"so P is not determined; "
            f"use points on at least two planes (e.g. two faces of a box), or a homography for one plane"
        )
    T = hartley_normalise(uv, "points_image").T
    U = hartley_normalise(X, "points_world").T
    Xn = np.hstack([X, np.ones((len(X), 1))]) @ U.T
    un = (np.hstack([uv, np.ones((len(uv), 1))]) @ T.T)[:, :2]
    n = len(X)
    A = np.zeros((2 * n, 12))
    A[0::2, 0:4] = Xn
    A[0::2, 8:12] = -un[:, :1] * Xn
    A[1::2, 4:8] = Xn
    A[1::2, 8:12] = -un[:, 1:] * Xn
    _, s, Vt = np.linalg.svd(A, full_matrices=False)  # U is never needed: keep it (2N, 12)
    if s[-2] <= 1e-10 * s[0]:
        raise DegenerateError(
            "estimate_projection_matrix: the correspondences do not fix P uniquely (A has a null space of "
            "dimension > 1); the points and camera may lie on a twisted cubic, pick more varied points"
        )
    Pn = Vt[-1].reshape(3, 4)
    P = np.linalg.solve(T, Pn @ U)
    P = _normalise_P(P)
    if refine:
        P = _refine_projection_matrix(P, X, uv)
    return P


def _normalise_P(P: np.ndarray) -> np.ndarray:
    P = P / np.linalg.norm(P[2, :3])
    if np.linalg.det(P[:, :3]) < 0:
        P = -P
    return P


def _refine_projection_matrix(P0: np.ndarray, X: np.ndarray, uv: np.ndarray) -> np.ndarray:
    """Gold-standard P: LM on the reprojection error, stepping on the unit sphere of the 12 entries."""
    Xh = np.hstack([X, np.ones((len(X), 1))])

    def residuals(p: np.ndarray) -> np.ndarray:
        x = Xh @ p.reshape(3, 4).T
        return (x[:, :2] / x[:, 2:] - uv).ravel()

    def jacobian(p: np.ndarray) -> np.ndarray:
        # u = a / w, v = b / w with a = p1 . X, b = p2 . X, w = p3 . X:
        # du/dp1 = X / w, du/dp3 = -u X / w, dv/dp2 = X / w, dv/dp3 = -v X / w.
        x = Xh @ p.reshape(3, 4).T
        w = x[:, 2:]
        u, v = x[:, :1] / w, x[:, 1:2] / w
        J = np.zeros((len(Xh), 2, 12))
        J[:, 0, 0:4] = Xh / w
        J[:, 0, 8:12] = -u * Xh / w
        J[:, 1, 4:8] = Xh / w
        J[:, 1, 8:12] = -v * Xh / w
        return J.reshape(-1, 12) @ unit_sphere_basis(p)

    p0 = P0.ravel() / np.linalg.norm(P0)
    res = levenberg_marquardt(
        residuals,
        p0,
        jacobian,
        update=unit_sphere_update,
        max_iter=200,
        ftol=1e-15,
        xtol=1e-15,
        gtol=1e-12,
    )
    if not np.all(np.isfinite(res.x)):
        raise ConvergenceError(
            f"estimate_projection_matrix: refinement did not converge ({res.message})"
        )
    return _normalise_P(res.x.reshape(3, 4))
