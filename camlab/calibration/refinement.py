r"""Stage 7: the projection model of calibration with its analytic Jacobian, and the block normal equations.

:func:`project_views` projects every view's board points with the global parameters
``g = (fx, fy, cx, cy, skew, k1, k2, p1, p2, k3)`` (``PARAM_NAMES``) and per-view poses
(rvec, t), and differentiates the projection; :class:`BlockNormal` solves Levenberg-Marquardt's
damped normal equations by eliminating the poses (Schur complement).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import as_float, as_points, check_intrinsics, check_matrix
from ..camera import cross_matrix, division_jacobian, rotation_from_axis_angle
from ..distortion import (
    as_dist,
    beyond_valid_radius,
    distort_xy,
    distortion_jacobian_unchecked,
)
from ..optimise import NormalEquations

PARAM_NAMES = ("fx", "fy", "cx", "cy", "skew", "k1", "k2", "p1", "p2", "k3")
"""The global (per-camera) parameters in the order camlab refines them."""


def _rotations_and_left_jacobians(rvecs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r"""Rotations :math:`R(r)` and left Jacobians :math:`J_l(r)` of V axis-angle vectors at once, (V, 3, 3) each.

    The batched form of :func:`camlab.camera.rotation_from_axis_angle` (Rodrigues,
    :math:`R = I + \frac{\sin\theta}{\theta}[r]_\times + \frac{1 - \cos\theta}{\theta^2}[r]_\times^2`),
    vectorised because the refinement evaluates every view's rotation at every iteration. The
    derivative of a rotated point is :math:`\partial (R(r) X) / \partial r = -[R X]_\times J_l(r)` with
    :math:`J_l = I + \frac{1 - \cos\theta}{\theta^2} [r]_\times + \frac{\theta - \sin\theta}{\theta^3} [r]_\times^2`.
    Near :math:`\theta = 0` the coefficients use their Taylor limits (1, 1/2, 1/6).
    """
    theta = np.linalg.norm(rvecs, axis=1)
    S = cross_matrix(rvecs)
    S2 = S @ S
    small = theta < 1e-6
    th = np.where(small, 1.0, theta)
    a = np.where(small, 1.0 - theta**2 / 6, np.sin(th) / th)  # sin(t) / t
    b = np.where(small, 0.5 - theta**2 / 24, (1 - np.cos(th)) / th**2)  # (1 - cos t) / t^2
    c = np.where(small, 1.0 / 6 - theta**2 / 120, (th - np.sin(th)) / th**3)
    eye = np.eye(3)
    R = eye + a[:, None, None] * S + b[:, None, None] * S2
    Jl = eye + b[:, None, None] * S + c[:, None, None] * S2
    return R, Jl


class ViewProjection(NamedTuple):
    """:func:`project_views` with its Jacobians.

    Attributes
    ----------
    uv : (V, M, 2) ndarray
        Projected board points, pixels.
    d_global : (V, M, 2, 10) ndarray
        d uv / d g (fx, fy, cx, cy, s, k1, k2, p1, p2, k3).
    d_pose : (V, M, 2, 6) ndarray
        d uv / d pose (rvec, t).
    """

    uv: np.ndarray
    d_global: np.ndarray
    d_pose: np.ndarray


class SchurComplement(NamedTuple):
    """:meth:`BlockNormal.schur`: the reduced system of the intrinsics and its pieces.

    Attributes
    ----------
    S : (n, n) ndarray
        ``U' - sum_v W_v V'_v^-1 W_v^T``: the intrinsics' normal matrix with the poses eliminated.
    V_inv : (V, 6, 6) ndarray
        ``V'^-1``: each view's damped pose block, inverted.
    Y : (V, n, 6) ndarray
        ``W V'^-1``.
    """

    S: np.ndarray
    V_inv: np.ndarray
    Y: np.ndarray


class CalibrationUnknowns(NamedTuple):
    """The unknowns of :class:`CalibrationProblem` unpacked from one vector.

    Attributes
    ----------
    g : (10,) ndarray
        Global parameters (fx, fy, cx, cy, s, k1, k2, p1, p2, k3); fixed ones keep their start value.
    poses : (V, 6) ndarray
        Each view's pose (rvec, t).
    """

    g: np.ndarray
    poses: np.ndarray


class JacobianBlocks(NamedTuple):
    """The residuals' Jacobian of :class:`CalibrationProblem`, by block.

    Attributes
    ----------
    intrinsic : (V, 2M, n) ndarray
        d r / d (free global parameters), view by view.
    pose : (V, 2M, 6) ndarray
        d r / d (each view's own pose).
    """

    intrinsic: np.ndarray
    pose: np.ndarray


def project_views(
    g: np.ndarray, poses: np.ndarray, X: np.ndarray, jac: bool = False
) -> np.ndarray | ViewProjection:
    r"""Project every view's board points with the global parameters and per-view poses.

    The chain rule, point by point: :math:`u = K_p\,\mathrm{distort}(\pi(R X + t)) + c` with
    :math:`K_p = [[f_x, s], [0, f_y]]`.

    Parameters
    ----------
    g : (10,) ndarray
        Global parameters in ``PARAM_NAMES`` order (fx, fy, cx, cy, skew in pixels; k1, k2,
        p1, p2, k3).
    poses : (V, 6) ndarray
        Each view's (rvec, t), cam_from_board: axis-angle (radians) and translation.
    X : (V, M, 3) ndarray
        Each view's (padded) board points.
    jac : bool
        Also return the Jacobians.

    Returns
    -------
    (V, M, 2) ndarray or ViewProjection
        The pixels ``uv``; with ``jac`` a :class:`ViewProjection`: ``uv``, ``d_global``
        (d uv / d g, (V, M, 2, 10)) and ``d_pose`` (d uv / d (rvec, t), (V, M, 2, 6)).
    """
    fx, fy, cx, cy, s, k1, k2, p1, p2, k3 = g
    R, Jl = _rotations_and_left_jacobians(poses[:, :3])
    RX = np.einsum("vij,vmj->vmi", R, X)
    Xc = RX + poses[:, None, 3:]
    z = Xc[..., 2]
    x, y = Xc[..., 0] / z, Xc[..., 1] / z
    xd, yd = distort_xy(x, y, g[5:])
    r2 = x * x + y * y
    uv = np.stack([fx * xd + s * yd + cx, fy * yd + cy], axis=-1)
    if not jac:
        return uv
    V, M = x.shape
    Jg = np.zeros((V, M, 2, 10))
    Jg[..., 0, 0], Jg[..., 0, 2], Jg[..., 0, 4] = xd, 1.0, yd
    Jg[..., 1, 1], Jg[..., 1, 3] = yd, 1.0
    r4 = r2 * r2
    dxd = np.stack(
        [x * r2, x * r4, 2 * x * y, r2 + 2 * x * x, x * r4 * r2], axis=-1
    )  # d xd / d(k1 k2 p1 p2 k3)
    dyd = np.stack([y * r2, y * r4, r2 + 2 * y * y, 2 * x * y, y * r4 * r2], axis=-1)
    Jg[..., 0, 5:] = fx * dxd + s * dyd
    Jg[..., 1, 5:] = fy * dyd
    Jd = distortion_jacobian_unchecked(np.stack([x, y], axis=-1), g[5:])  # (V, M, 2, 2)
    A = np.empty_like(Jd)  # d uv / d (x, y) = K_p @ Jd
    A[..., 0, :] = fx * Jd[..., 0, :] + s * Jd[..., 1, :]
    A[..., 1, :] = fy * Jd[..., 1, :]
    dXc = A @ division_jacobian(Xc)  # (V, M, 2, 3): d uv / d Xc = d uv / d t
    # d (R X) / d rvec = -[RX]x Jl, (V, M, 3, 3): each view's M matrices stacked, one product per view
    dR = (-cross_matrix(RX).reshape(V, 3 * M, 3) @ Jl).reshape(V, M, 3, 3)
    Jp = np.concatenate([dXc @ dR, dXc], axis=-1)
    return ViewProjection(uv, Jg, Jp)


class BlockNormal:
    r"""The normal equations of calibration in block form.

    Parameters are ``[intrinsics (n_i), pose_1 (6), ..., pose_V (6)]``. Each view's pose only
    touches that view's residuals, so

    .. math::
        J^\top J = \begin{pmatrix} U & W_1 & \cdots & W_V \\ W_1^\top & V_1 & & \\
                   \vdots & & \ddots & \\ W_V^\top & & & V_V \end{pmatrix},\quad
        U = \sum_v J_{i,v}^\top J_{i,v},\ W_v = J_{i,v}^\top J_{p,v},\ V_v = J_{p,v}^\top J_{p,v}.

    The damped system is solved by eliminating the poses (the Schur complement): with
    :math:`V'_v = V_v + \mu\,\mathrm{diag}(V_v)`,
    :math:`S = U' - \sum_v W_v V_v'^{-1} W_v^\top`,
    :math:`S \delta_i = -g_i + \sum_v W_v V_v'^{-1} g_v` and then
    :math:`\delta_v = V_v'^{-1}(-g_v - W_v^\top \delta_i)`: one n_i x n_i solve and V 6 x 6
    inverses instead of a dense (n_i + 6V)-square solve.
    """

    def __init__(self, Ji: np.ndarray, Jp: np.ndarray, r: np.ndarray):
        JiT = Ji.transpose(0, 2, 1)
        self.U = (JiT @ Ji).sum(axis=0)
        self.W = JiT @ Jp
        self.Vb = Jp.transpose(0, 2, 1) @ Jp
        self.gi = np.einsum("vki,vk->i", Ji, r)
        self.gp = np.einsum("vki,vk->vi", Jp, r)

    def gradient(self) -> np.ndarray:
        r"""The gradient :math:`J^\top r` of the cost, in the order of the unknowns.

        Returns
        -------
        (n_i + 6V,) ndarray
            The intrinsics' block, then each view's pose block.
        """
        return np.concatenate([self.gi, self.gp.ravel()])

    def diagonal(self) -> np.ndarray:
        r"""The diagonal of :math:`J^\top J` (of U and of every :math:`V_v`).

        Returns
        -------
        (n_i + 6V,) ndarray
            In the order of the unknowns.
        """
        return np.concatenate([np.diag(self.U), np.diagonal(self.Vb, axis1=1, axis2=2).ravel()])

    def schur(self, mu: float = 0.0) -> SchurComplement:
        """The Schur complement of the damped system, with the pieces :meth:`solve` reuses.

        The diagonal of U is clamped to at least 1e-12 times its largest entry before it is
        damped, so a parameter the data hardly touch still gets a positive damping.

        Parameters
        ----------
        mu : float
            The damping; 0 gives the undamped S (for the covariance).

        Returns
        -------
        SchurComplement
            ``S`` (n_i, n_i), ``V_inv`` (V, 6, 6) and ``Y`` = W V'^-1 (V, n_i, 6).
        """
        dU = np.diag(self.U)
        Ud = self.U + mu * np.diag(np.maximum(dU, 1e-12 * max(dU.max(initial=0.0), 1e-300)))
        dV = np.diagonal(self.Vb, axis1=1, axis2=2)
        Vd = self.Vb + mu * dV[:, :, None] * np.eye(6)
        Vinv = np.linalg.inv(Vd)
        Y = self.W @ Vinv
        S = Ud - (Y @ self.W.transpose(0, 2, 1)).sum(axis=0)
        return SchurComplement(S, Vinv, Y)

    def solve(self, mu: float) -> np.ndarray:
        r"""The damped Levenberg-Marquardt step, by eliminating the poses (see the class).

        Parameters
        ----------
        mu : float
            The damping, relative to the diagonal.

        Returns
        -------
        (n_i + 6V,) ndarray
            The step :math:`(\delta_i, \delta_1, \ldots, \delta_V)`.
        """
        S, Vinv, Y = self.schur(mu)
        di = np.linalg.solve(S, -self.gi + np.einsum("vij,vj->i", Y, self.gp))
        dp = np.einsum("vij,vj->vi", Vinv, -self.gp - np.einsum("vij,i->vj", self.W, di))
        return np.concatenate([di, dp.ravel()])


class CalibrationProblem:
    """Packs the calibration unknowns into one vector and evaluates residuals and Jacobians."""

    def __init__(
        self, X: np.ndarray, obs: np.ndarray, mask: np.ndarray, g0: np.ndarray, free: np.ndarray
    ):
        self.X, self.obs, self.mask = X, obs, mask
        self.g0, self.free = g0, free
        self.ni = int(free.sum())
        self.V = X.shape[0]
        self._last = None

    def pack(self, g: np.ndarray, poses: np.ndarray) -> np.ndarray:
        """The unknowns as one vector: the free global parameters, then every pose.

        Parameters
        ----------
        g : (10,) ndarray
            Global parameters in ``PARAM_NAMES`` order (only the free ones are kept).
        poses : (V, 6) ndarray
            Each view's (rvec, t).

        Returns
        -------
        (n_i + 6V,) ndarray
            The packed vector.
        """
        return np.concatenate([g[self.free], poses.ravel()])

    def unpack(self, x: np.ndarray) -> CalibrationUnknowns:
        """The inverse of :meth:`pack`; fixed global parameters keep their start value.

        Parameters
        ----------
        x : (n_i + 6V,) ndarray
            The packed unknowns.

        Returns
        -------
        CalibrationUnknowns
            ``g`` (10,) and ``poses`` (V, 6).
        """
        g = self.g0.copy()
        g[self.free] = x[: self.ni]
        return CalibrationUnknowns(g, x[self.ni :].reshape(self.V, 6))

    def _evaluate(self, x: np.ndarray):
        """Residuals and Jacobian blocks at x, computed together and kept for the next call.

        LM asks for r(x) at a trial point and then, if the step is accepted, for J(x) at the
        same point: one projection pass serves both.
        """
        if self._last is not None and np.array_equal(self._last[0], x):
            return self._last[1]
        g, poses = self.unpack(x)
        uv, Jg, Jp = project_views(g, poses, self.X, jac=True)
        m = self.mask[..., None]
        V, M = self.mask.shape
        r = ((uv - self.obs) * m).ravel()
        J = JacobianBlocks(
            (Jg[..., self.free] * m[..., None]).reshape(V, 2 * M, self.ni),
            (Jp * m[..., None]).reshape(V, 2 * M, 6),
        )
        self._last = (x.copy(), (r, J))
        return r, J

    def residuals(self, x: np.ndarray) -> np.ndarray:
        """Reprojected minus observed corners, zero on padded rows.

        Parameters
        ----------
        x : (n_i + 6V,) ndarray
            The packed unknowns.

        Returns
        -------
        (2VM,) ndarray
            The residuals, pixels, view by view, (u, v) per point.
        """
        return self._evaluate(x)[0]

    def jacobian(self, x: np.ndarray) -> JacobianBlocks:
        """The residuals' Jacobian at ``x``, by block (shared with :meth:`residuals`' pass).

        Parameters
        ----------
        x : (n_i + 6V,) ndarray
            The packed unknowns.

        Returns
        -------
        JacobianBlocks
            ``intrinsic`` (V, 2M, n_i) and ``pose`` (V, 2M, 6).
        """
        return self._evaluate(x)[1]

    def normal_equations(self, J: JacobianBlocks, r: np.ndarray) -> NormalEquations:
        """The normal equations in block form, for :func:`camlab.optimise.levenberg_marquardt`.

        Parameters
        ----------
        J : JacobianBlocks
            From :meth:`jacobian`.
        r : (2VM,) ndarray
            From :meth:`residuals`.

        Returns
        -------
        NormalEquations
            A :class:`BlockNormal` and its gradient.
        """
        A = BlockNormal(J.intrinsic, J.pose, r.reshape(self.V, -1))
        return NormalEquations(A, A.gradient())


def reproject(
    object_points: ArrayLike, K: ArrayLike, dist: ArrayLike | None, rvec: ArrayLike, tvec: ArrayLike
) -> np.ndarray:
    r"""Project (N, 3) board points with intrinsics, distortion and an axis-angle pose (like cv2.projectPoints).

    NaN for points behind the camera (:math:`z_c \le 0`) and beyond the distortion model's
    valid radius, where cv2.projectPoints returns a mirrored pixel.

    Parameters
    ----------
    object_points : (N, 3) array_like
        Board points, metres.
    K : (3, 3) array_like
        Intrinsics, pixels.
    dist : array_like or None
        Distortion coefficients, OpenCV's order (None: none).
    rvec : (3,) array_like
        Axis-angle rotation, cam_from_board, radians.
    tvec : (3,) array_like
        Translation, cam_from_board, metres.

    Returns
    -------
    (N, 2) ndarray
        Pixels; NaN where described above.

    Raises
    ------
    CamlabInputError
        Points not (N, 3), ``K`` not intrinsics, bad coefficients, or a pose that is not two
        3-vectors.
    """
    X = as_points(object_points, 3, "object_points").array
    Km = check_intrinsics(K, "K")
    d = as_dist(dist)
    rv = check_matrix(np.ravel(as_float(rvec, "rvec")), (3,), "rvec")
    tv = check_matrix(np.ravel(as_float(tvec, "tvec")), (3,), "tvec")
    g = np.array([Km[0, 0], Km[1, 1], Km[0, 2], Km[1, 2], Km[0, 1], *d])
    uv = project_views(g, np.concatenate([rv, tv])[None], X[None])[0]
    # No pixel behind the camera, nor beyond the distortion model's valid radius (it folds back there).
    Xc = X @ rotation_from_axis_angle(rv).T + tv
    with np.errstate(divide="ignore", invalid="ignore"):
        xn = Xc[:, :2] / Xc[:, 2:]
    uv[(Xc[:, 2] <= 0) | beyond_valid_radius(xn, d)] = np.nan
    return uv
