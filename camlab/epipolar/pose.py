r"""From E to a pose and 3-D points.

The four poses in E ([1]_, result 9.19), the one with the points in front of both cameras, and
triangulation ([1]_, section 12.2).

Part of :mod:`camlab.epipolar` (every name here is importable from there).

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 9.6 (the essential
   matrix) and section 12.2 (linear triangulation methods).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    DegenerateError,
    as_point_pairs,
    check_intrinsics,
    check_matrix,
)
from ..camera import Camera, camera_centre, check_camera_matrix
from ..optimise import block_damped_solve, block_normal_equations, levenberg_marquardt
from ..projective import from_homogeneous

__all__ = [
    "EssentialDecomposition",
    "RelativePose",
    "decompose_essential_matrix",
    "recover_pose",
    "triangulate_points",
]


class EssentialDecomposition(NamedTuple):
    """The four poses an essential matrix allows: ``R`` (4, 3, 3), ``t`` (4, 3) unit vectors.

    Candidates are ``(R_a, t), (R_a, -t), (R_b, t), (R_b, -t)``; only one puts the points in
    front of both cameras (see :func:`recover_pose`).
    """

    R: np.ndarray
    t: np.ndarray


def decompose_essential_matrix(E: ArrayLike) -> EssentialDecomposition:
    r"""The four (R, t) with :math:`E \sim [t]_\times R` (H&Z result 9.19 [1]_).

    With :math:`E = U\,\mathrm{diag}(1, 1, 0)\,V^\top` (U, V rotations) and
    :math:`W = \begin{pmatrix}0&-1&0\\1&0&0\\0&0&1\end{pmatrix}`:
    :math:`R \in \{U W V^\top,\ U W^\top V^\top\}` and :math:`t = \pm u_3` (the last column
    of U, the left null vector of E: the baseline direction, its length unknown).

    Parameters
    ----------
    E : (3, 3) array_like
        An essential matrix (any scale).

    Returns
    -------
    EssentialDecomposition
        ``R`` (4, 3, 3) and ``t`` (4, 3) unit vectors: the candidates ``(R_a, t), (R_a, -t),
        (R_b, t), (R_b, -t)``.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 9.6.2 (extraction
       of cameras from the essential matrix,
       result 9.19).
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

    Parameters
    ----------
    E : (3, 3) array_like
        The essential matrix.
    x1, x2 : (N, 2) array_like
        Corresponding pixels in images 1 and 2.
    K1 : (3, 3) array_like
        Intrinsics of camera 1, pixels.
    K2 : (3, 3) array_like, optional
        Intrinsics of camera 2 (default K1).

    Returns
    -------
    RelativePose
        ``R`` (3, 3) and ``t`` (3,) unit, cam2_from_cam1; ``points`` (N, 3), triangulated in
        camera 1's frame (baseline units); ``in_front`` (N,) bool; ``counts`` (4,), points in
        front for each candidate.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 9.6.3 (geometrical
       interpretation of the four solutions).
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


def _refine_points(Ps: list[np.ndarray], uvs: list[np.ndarray], X: np.ndarray) -> np.ndarray:
    """Minimise the summed squared reprojection error over each point independently.

    Levenberg-Marquardt (:func:`camlab.optimise.levenberg_marquardt`) on the block-diagonal problem,
    3 unknowns and 2 residuals per camera for each point. A point on a camera's principal plane
    (depth 0) has no reprojection error and stays where it is.
    """
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

    Linear triangulation [1]_. :math:`\tilde x \sim P X` means
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

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 12.2 (linear
       triangulation methods).

    Examples
    --------
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
