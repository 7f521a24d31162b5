r"""Where is the camera? The pose from known 3-D points and their pixels (PnP), with its uncertainty.

Given a calibrated camera K (and its distortion), N world points :math:`X_i` and their pixels
:math:`u_i`, find the pose ``R, t`` (cam_from_world, :math:`X_c = R X + t`) that minimises the
reprojection error

.. math:: E(R, t) = \sum_i \| u_i - \pi(K (R X_i + t)) \|^2 ,

the maximum-likelihood pose under independent Gaussian pixel noise. :math:`E` is not convex,
so :func:`solve_pnp` starts from a closed-form estimate and polishes it:

* **Points on or near one plane** (a chessboard: Z = 0; measured points scattered a little off
  their plane). The plane's points and their pixels are related by a homography
  :math:`H \simeq K [r_1\ r_2\ t]` (Zhang 2000, section 3.1 [1]_), so
  :math:`K^{-1} H = \lambda [r_1\ r_2\ t]` gives the pose
  (:func:`camlab.calibration.extrinsics_from_homography`). The **planarity test** is OpenCV's
  (``cvFindExtrinsicCameraParams2``): the centred points' scatter matrix
  :math:`(X - c)^\top (X - c)` has eigenvalues :math:`w_1 \ge w_2 \ge w_3` (the squared singular
  values of :math:`X - c`), and the points count as planar when :math:`w_3 / w_2 <`
  ``PLANAR_TOL`` = :math:`10^{-3}`, i.e. their rms distance from the best-fit plane is under
  3 % of their spread along the plane's narrower direction. The start then comes from the
  homography of the points *flattened* onto that plane; the refinement below uses the points as
  they are, so flattening costs nothing in the answer.
* **General points**: the camera DLT (:func:`camlab.camera.estimate_projection_matrix`, H&Z
  section 7.1 [2]_) gives :math:`P \simeq K [R \mid t]`; with K known,
  :math:`M = K^{-1} P = s [R \mid t]`. The scale's size is :math:`|s| = |\det M_{3\times3}|^{1/3}`;
  its sign is the one that puts the points in front of the camera, since the third row gives
  each point's depth times s, :math:`m_3^\top (X_i, 1) = s\, z_{c,i}` (H&Z section 6.2.3, the
  depth of a point). The sign of :math:`\det M_{3\times3}` itself is not used: for points near a
  plane :math:`M_{3\times3}` is nearly singular and that sign is noise, which would start from
  the mirror pose :math:`(R\, \mathrm{Rot}_z(180^\circ), -t)` that reprojects the same.
  The nearest rotation to :math:`M_{3\times3} / s` is R.
* **Cheirality.** A pose that puts any point behind the camera (:math:`z_c \le 0`) is refused
  with an error rather than returned: its reprojection can look fine while the answer is wrong.
* **Refinement** by Levenberg-Marquardt (:func:`camlab.optimise.levenberg_marquardt`) over six
  numbers: a small rotation :math:`\delta\omega` applied on the left,
  :math:`R \leftarrow \exp([\delta\omega]_\times) R` (Rodrigues,
  :func:`camlab.camera.rotation_from_axis_angle`), and :math:`t \leftarrow t + \delta t`. In
  the camera frame :math:`X_c = R X + t` moves by
  :math:`\partial X_c / \partial \delta\omega = -[X_c - t]_\times` and
  :math:`\partial X_c / \partial \delta t = I`; the chain rule through
  :math:`u = f_x x_c / z_c + s\,y_c/z_c + c_x`, :math:`v = f_y y_c / z_c + c_y` gives the 2 x 6
  Jacobian of each point (H&Z section 6.1, the finite camera, and appendix A6, iterative estimation).

With distortion the measured pixels are first undistorted (:func:`camlab.distortion.
undistort_pixels`) and the pinhole problem is solved on the ideal pixels; the residuals and the
rms are reported in the measured pixels (the pose reprojected through the distortion), the
numbers OpenCV's ``solvePnP`` minimises. The noise lives in the measured pixels, so the
covariance below uses the Jacobian of the *distorted* projection, :math:`J = D_i J_i^{\text{ideal}}`
with :math:`D_i` the 2 x 2 Jacobian of the distortion at each point (:func:`pixel_distortion_jacobian`).

**Uncertainty.** Near the minimum the residuals are linear in the six parameters,
:math:`r(p) \approx r + J \delta p`, and pixel noise of variance :math:`\sigma^2` per
coordinate gives the pose covariance

.. math:: \Sigma_p = \hat\sigma^2 (J^\top J)^{-1}, \qquad
          \hat\sigma^2 = \frac{\sum_i \|r_i\|^2}{2N - 6},

with :math:`\sigma` estimated from the residuals themselves (2N measurements, 6 unknowns: the
unbiased estimate, the one OpenCV's calibration reports). It says how far the pose moves when
the corners move by their noise; it knows nothing of a wrong K or a wrong board size.

References
----------
.. [1] Z. Zhang, 2000, "A flexible new technique for camera calibration", *IEEE Transactions on
   Pattern Analysis and Machine Intelligence* 22(11), 1330-1334, section 3.1.
.. [2] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, sections 7.1 (the camera
   DLT), 7.2-7.3 (the geometric error and its minimisation) and 5.2 (covariance of an estimate).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    CamlabInputError,
    DegenerateError,
    as_point_pairs,
    as_points,
    check_intrinsics,
    check_number,
)
from ..calibration.zhang import extrinsics_from_homography
from ..camera import (
    axis_angle_from_rotation,
    axis_angle_from_rotation_unchecked,
    cross_matrix,
    division_jacobian,
    estimate_projection_matrix,
    nearest_rotation,
    rotation_from_axis_angle_unchecked,
)
from ..distortion import (
    as_dist,
    distort_xy,
    distortion_jacobian_unchecked,
    normalised_to_pixels,
    pixels_to_normalised,
    undistort_pixels,
)
from ..homography import estimate_homography
from ..optimise import levenberg_marquardt

__all__ = [
    "PlaneFrame",
    "PnPResult",
    "plane_frame",
    "pose_covariance",
    "pixel_distortion_jacobian",
    "pose_jacobian",
    "project_pose",
    "solve_pnp",
]

METHODS = ("auto", "planar", "dlt")
PLANAR_TOL = 1e-3
"""Points are (nearly) planar when their scatter matrix's smallest eigenvalue is below this times
the middle one (OpenCV's test in ``cvFindExtrinsicCameraParams2``)."""


class PlaneFrame(NamedTuple):
    """A frame of a plane: its points are ``centre + basis @ (x, y, 0)``.

    Attributes
    ----------
    centre : (3,) ndarray
        A point of the plane (the points' centroid; 0 for points on Z = 0).
    basis : (3, 3) ndarray
        A rotation whose third column is the plane's normal.
    """

    centre: np.ndarray
    basis: np.ndarray


class PnPResult(NamedTuple):
    r"""The outcome of :func:`solve_pnp`.

    Attributes
    ----------
    R : (3, 3) ndarray
        Rotation, cam_from_world.
    t : (3,) ndarray
        Translation, cam_from_world (the world's units, e.g. metres).
    rvec : (3,) ndarray
        R as an axis-angle vector, radians (OpenCV's ``rvec``).
    rms : float
        :math:`\sqrt{\sum_i \|r_i\|^2 / N}` over the N points, pixels.
    residuals : (N, 2) ndarray
        Reprojected minus measured pixels, in the measured (distorted) pixels.
    iterations : int
        Levenberg-Marquardt iterations.
    covariance : (6, 6) ndarray
        :math:`\hat\sigma^2 (J^\top J)^{-1}` of (:math:`\delta\omega`, :math:`\delta t`): a small
        rotation applied on the left (radians, camera frame) and the translation.
    sigma : float
        :math:`\hat\sigma`, the pixel noise per coordinate estimated from the residuals.
    method : str
        ``"planar"`` (homography start) or ``"dlt"`` (camera DLT start).
    initial : tuple
        ``(R, t)`` of the closed-form start, before refinement.
    """

    R: np.ndarray
    t: np.ndarray
    rvec: np.ndarray
    rms: float
    residuals: np.ndarray
    iterations: int
    covariance: np.ndarray
    sigma: float
    method: str
    initial: tuple

    @property
    def centre(self) -> np.ndarray:
        r"""(3,) ndarray: the camera centre in the world frame, :math:`C = -R^\top t`."""
        return -self.R.T @ self.t

    def centre_covariance(self) -> np.ndarray:
        r"""The (3, 3) covariance of :attr:`centre`, first order.

        With :math:`R' = \exp([\delta\omega]_\times) R` and :math:`t' = t + \delta t`,
        :math:`C' \approx C - R^\top [t]_\times \delta\omega - R^\top \delta t`.

        Returns
        -------
        (3, 3) ndarray
            World units squared.
        """
        Jc = np.hstack([-self.R.T @ cross_matrix(self.t), -self.R.T])
        return Jc @ self.covariance @ Jc.T

    def std(self) -> dict:
        """One-sigma uncertainties: rotation (radians, each camera axis), t and the centre.

        Returns
        -------
        dict
            ``rotation`` (3,), ``t`` (3,), ``centre`` (3,).
        """
        d = np.sqrt(np.diag(self.covariance))
        return {
            "rotation": d[:3],
            "t": d[3:],
            "centre": np.sqrt(np.diag(self.centre_covariance())),
        }


def project_pose(K: np.ndarray, R: np.ndarray, t: np.ndarray, X: np.ndarray) -> np.ndarray:
    r"""Ideal pixels of world points seen from pose (R, t): :math:`\pi(K (R X + t))`.

    Parameters
    ----------
    K : (3, 3) ndarray
        Intrinsics, pixels.
    R : (3, 3) ndarray
        Rotation, cam_from_world.
    t : (3,) ndarray
        Translation, cam_from_world.
    X : (N, 3) ndarray
        World points.

    Returns
    -------
    (N, 2) ndarray
        Pixels (u, v), no distortion.
    """
    x = (X @ R.T + t) @ K.T
    return x[:, :2] / x[:, 2:]


def pose_jacobian(K: np.ndarray, R: np.ndarray, t: np.ndarray, X: np.ndarray) -> np.ndarray:
    r"""The (2N, 6) Jacobian of :func:`project_pose` with respect to (:math:`\delta\omega`, :math:`\delta t`).

    Rows alternate u, v per point; :math:`\delta\omega` is a small rotation applied on the left
    (:math:`R \leftarrow \exp([\delta\omega]_\times) R`), so
    :math:`\partial X_c/\partial\delta\omega = -[X_c - t]_\times` and
    :math:`\partial X_c/\partial\delta t = I`.

    Parameters
    ----------
    K : (3, 3) ndarray
        Intrinsics, pixels.
    R : (3, 3) ndarray
        Rotation, cam_from_world.
    t : (3,) ndarray
        Translation, cam_from_world.
    X : (N, 3) ndarray
        World points.

    Returns
    -------
    (2N, 6) ndarray
        Pixels per radian (first three columns) and per world unit (last three).
    """
    RX = X @ R.T
    dproj = K[:2, :2] @ division_jacobian(RX + t)  # d(u, v)/d Xc
    dXc = np.zeros((len(X), 3, 6))
    dXc[:, :, :3] = -cross_matrix(RX)
    dXc[:, :, 3:] = np.eye(3)
    return (dproj @ dXc).reshape(-1, 6)


def pixel_distortion_jacobian(pixels: np.ndarray, K: np.ndarray, d: np.ndarray) -> np.ndarray:
    r"""The (N, 2, 2) Jacobians of the distortion in pixels, at ideal pixels: d measured / d ideal.

    In normalised coordinates :math:`x = K^{-1} u` the distortion's Jacobian :math:`J(x)` is
    :func:`camlab.distortion.distortion_jacobian`'s; pixels are an affine map of normalised
    coordinates by the upper-left 2 x 2 block :math:`K_2` of K, so by the chain rule
    :math:`D = K_2\, J(x)\, K_2^{-1}`. A pixel noise :math:`\delta u` on the ideal side becomes
    :math:`D\, \delta u` on the measured side; the undistortion's Jacobian, at the measured
    pixel, is :math:`D^{-1}` (the inverse function theorem).

    Parameters
    ----------
    pixels : (N, 2) ndarray
        Ideal (undistorted) pixels where to take the derivatives.
    K : (3, 3) ndarray
        Checked intrinsics.
    d : (5,) ndarray
        ``(k1, k2, p1, p2, k3)`` from :func:`camlab.distortion.as_dist`.

    Returns
    -------
    (N, 2, 2) ndarray
        ``D[k, i, j]`` = d measured_i / d ideal_j at point k.
    """
    K2 = K[:2, :2]
    return (
        K2 @ distortion_jacobian_unchecked(pixels_to_normalised(pixels, K), d) @ np.linalg.inv(K2)
    )


def pose_covariance(
    K: ArrayLike, R: ArrayLike, t: ArrayLike, object_points: ArrayLike, sigma_px: float
) -> np.ndarray:
    r"""The 6 x 6 covariance :math:`\sigma^2 (J^\top J)^{-1}` of a pose seen through N points.

    What the pose's uncertainty *would be* with pixel noise ``sigma_px`` per coordinate: for
    planning a measurement (how far, how tilted) before taking the photo.

    Parameters
    ----------
    K : (3, 3) array_like
        Intrinsics, pixels.
    R : (3, 3) array_like
        Rotation, cam_from_world.
    t : (3,) array_like
        Translation, cam_from_world.
    object_points : (N, 3) array_like
        The points that fix the pose (a board's corners).
    sigma_px : float
        Pixel noise per coordinate, pixels (>= 0).

    Returns
    -------
    (6, 6) ndarray
        Covariance of (:math:`\delta\omega`, :math:`\delta t`), as :attr:`PnPResult.covariance`.
    """
    Km = check_intrinsics(K, "K")
    X = as_points(object_points, 3, "object_points", min_count=4).array
    s = check_number(sigma_px, "sigma_px", "pixels")
    if s < 0:
        raise CamlabInputError(f"sigma_px: expected a noise >= 0 pixels, got {sigma_px!r}")
    J = pose_jacobian(Km, np.asarray(R, dtype=float), np.asarray(t, dtype=float), X)
    return s**2 * np.linalg.pinv(J.T @ J)


class _Rotations:
    """Rodrigues of the last few rotation vectors, unchecked: the refinement's inner loop.

    Levenberg-Marquardt asks for the same pose's R in its residuals, its Jacobian and the next
    step; each is :func:`rotation_from_axis_angle_unchecked` of the same rvec (the same floats),
    computed once. The poses are the refinement's own, so they are not checked again.
    """

    def __init__(self, keep: int = 4):
        self.keep = keep
        self.seen: dict[bytes, np.ndarray] = {}

    def __call__(self, rvec: np.ndarray) -> np.ndarray:
        key = rvec.tobytes()
        R = self.seen.get(key)
        if R is None:
            if len(self.seen) >= self.keep:
                del self.seen[next(iter(self.seen))]  # the oldest
            R = self.seen[key] = rotation_from_axis_angle_unchecked(rvec)
        return R


def _step(rotation: _Rotations):
    """The pose step for Levenberg-Marquardt: (rvec, t) moved by a left rotation delta[:3], t by delta[3:].

    The rotation is updated on the manifold, R <- Rodrigues(delta[:3]) R, not by adding rvecs
    (the Jacobian's rotation columns are derivatives of a small left rotation); the arrays are
    the refinement's own, so nothing is checked again, and R of the current pose comes from
    ``rotation``'s cache.
    """

    def update(x: np.ndarray, delta: np.ndarray) -> np.ndarray:
        R = rotation_from_axis_angle_unchecked(delta[:3]) @ rotation(x[:3])
        return np.concatenate([axis_angle_from_rotation_unchecked(R), x[3:] + delta[3:]])

    return update


def _distorted(pixels: np.ndarray, K: np.ndarray, d: np.ndarray) -> np.ndarray:
    """:func:`camlab.distortion.distort_pixels` of checked (N, 2) pixels, K and dist: the same floats, no re-checks."""
    xd, yd = distort_xy(*pixels_to_normalised(pixels, K).T, d)
    return normalised_to_pixels(np.stack([xd, yd], axis=-1), K)


def plane_frame(X: np.ndarray) -> PlaneFrame | None:
    r"""The best-fit plane of points on or near one plane, or None when they span 3-D.

    The SVD of the centred points :math:`X - c = U S V^\top`: the eigenvalues of the scatter
    matrix are :math:`s_k^2`, and the points pass the planarity test when
    :math:`s_3^2 <` ``PLANAR_TOL`` :math:`s_2^2`; the last right singular vector is then the
    best-fit plane's normal.

    Parameters
    ----------
    X : (N, 3) ndarray
        World points.

    Returns
    -------
    PlaneFrame or None
        ``(centre, basis)``: the points flattened onto the plane are :math:`c + B p` with
        :math:`p = B^\top (X - c)`, :math:`p_z` set to 0; ``B`` a rotation (identity and
        ``c = 0`` for points already on Z = 0).
    """
    if np.all(X[:, 2] == 0):
        return PlaneFrame(np.zeros(3), np.eye(3))
    c = X.mean(axis=0)
    _, s, Vt = np.linalg.svd(X - c)
    if s[2] ** 2 >= PLANAR_TOL * s[1] ** 2:
        return None
    B = Vt.T.copy()
    if np.linalg.det(B) < 0:
        B[:, 2] = -B[:, 2]
    return PlaneFrame(c, B)


def _planar_start(K: np.ndarray, X: np.ndarray, uv: np.ndarray, frame) -> tuple:
    """Zhang's pose from the homography of the points, flattened onto their plane, to the ideal pixels."""
    c, B = frame
    p = (X - c) @ B
    H = estimate_homography(p[:, :2], uv)
    Rp, tp = extrinsics_from_homography(K, H)
    R = Rp @ B.T
    return R, tp - R @ c


def _dlt_start(K: np.ndarray, X: np.ndarray, uv: np.ndarray) -> tuple:
    """The calibrated DLT: K^-1 P = s [R | t], |s| = |det(K^-1 M)|^(1/3), the sign putting the points in front."""
    M = np.linalg.solve(K, estimate_projection_matrix(X, uv))
    s = np.cbrt(abs(np.linalg.det(M[:, :3])))
    depth = X @ M[2, :3] + M[2, 3]  # s times each point's depth z_c
    if np.median(depth) < 0:
        s = -s
    return nearest_rotation(M[:, :3] / s), M[:, 3] / s


def _checked(object_points, image_points, K, dist, method):
    """Validate solve_pnp's arguments; return X, the measured and the ideal pixels, K, dist."""
    if method not in METHODS:
        raise CamlabInputError(
            f"method: expected one of {METHODS}, got {method!r}; use 'auto' to choose by the points"
        )
    X, uv, _ = as_point_pairs(
        object_points,
        image_points,
        ("object_points", "image_points"),
        (3, 2),
        min_count=4,
        why="the pose has 6 degrees of freedom and 4 points are the fewest with one answer; add points",
    )
    Km = check_intrinsics(K, "K")
    d = as_dist(dist)
    ideal = undistort_pixels(uv, Km, d) if np.any(d) else uv
    return X, uv, ideal, Km, d


def _start(K, X, ideal, method) -> tuple:
    """The closed-form start and the method used."""
    frame = plane_frame(X)
    if method == "planar" and frame is None:
        raise DegenerateError(
            "object_points: method='planar' needs points on or near one plane (the smallest "
            "eigenvalue of their scatter below PLANAR_TOL = 1e-3 of the middle one), but these "
            "span 3-D; use method='auto' or 'dlt'"
        )
    if frame is not None and method != "dlt":
        return (*_planar_start(K, X, ideal, frame), "planar")
    if frame is not None:
        raise DegenerateError(
            "object_points: method='dlt' needs points that span 3-D, but these are on or near one "
            "plane (a plane fixes only a homography, and the DLT of nearly planar points is "
            "ill-conditioned); use method='auto' or 'planar'"
        )
    if len(X) < 6:
        raise CamlabInputError(
            f"object_points: the DLT start for non-coplanar points needs N >= 6, got {len(X)}; "
            "add points (P has 11 degrees of freedom, each point gives 2 equations)"
        )
    return (*_dlt_start(K, X, ideal), "dlt")


def solve_pnp(
    object_points: ArrayLike,
    image_points: ArrayLike,
    K: ArrayLike,
    dist: ArrayLike | None = None,
    method: str = "auto",
) -> PnPResult:
    r"""The camera's pose from N >= 4 world points and their pixels (see the module docstring).

    Parameters
    ----------
    object_points : (N, 3) array_like
        World points, e.g. a board's corners in metres (Z = 0 for a flat board).
    image_points : (N, 2) array_like
        Their measured pixels (u, v), origin at the centre of the top-left pixel.
    K : (3, 3) array_like
        Intrinsics, pixels.
    dist : (5,) or (4,) array_like or None
        ``(k1, k2, p1, p2[, k3])``, OpenCV's order; None for an ideal pinhole.
    method : {"auto", "planar", "dlt"}
        The closed-form start: the homography of the points flattened onto their best-fit plane
        (points on or near one plane) or the camera DLT (N >= 6, points spanning 3-D); "auto"
        chooses by the planarity test. Either way the refinement uses the points as given.

    Returns
    -------
    PnPResult
        ``R, t`` (cam_from_world), ``rvec``, ``rms``, ``residuals``, ``iterations``,
        ``covariance`` (6 x 6), ``sigma``, ``method``, ``initial``.

    Raises
    ------
    CamlabInputError
        Fewer than 4 points, different counts, K not intrinsics, an unknown method.
    DegenerateError
        The points are collinear, the method does not fit the points, or the refined pose puts
        points behind the camera.

    Examples
    --------
    >>> K = np.array([[800.0, 0, 320], [0, 800, 240], [0, 0, 1]])
    >>> X = np.array([[0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0.1, 0.1, 0], [0.05, 0.02, 0]])
    >>> uv = project_pose(K, np.eye(3), np.array([0.0, 0.0, 1.0]), X)
    >>> bool(np.allclose(solve_pnp(X, uv, K).t, [0, 0, 1]))
    True
    """
    X, uv, ideal, Km, d = _checked(object_points, image_points, K, dist, method)
    R0, t0, used = _start(Km, X, ideal, method)
    # checked once above: the loop below works on the refinement's own arrays, unchecked
    rotation = _Rotations()

    def residuals(p: np.ndarray) -> np.ndarray:
        return (project_pose(Km, rotation(p[:3]), p[3:], X) - ideal).ravel()

    def jacobian(p: np.ndarray) -> np.ndarray:
        return pose_jacobian(Km, rotation(p[:3]), p[3:], X)

    x0 = np.concatenate([axis_angle_from_rotation(R0), t0])
    # The closed-form start is close: the cost settles in 3-4 steps. The default tolerances
    # (1e-12) stop about 5 steps in; 1e-15 took 11, moving the pose by under 1e-10.
    lm = levenberg_marquardt(residuals, x0, jacobian, update=_step(rotation))
    rvec, t = lm.x[:3], lm.x[3:]
    R = rotation(rvec)
    behind = int(np.sum(X @ R[2] + t[2] <= 0))
    if behind:
        raise DegenerateError(
            f"image_points: no pose in front of the camera fits these points ({used!r} start, "
            f"refined to a pose with {behind} of {len(X)} points behind the camera); check that "
            "object_points and image_points are in the same order and the units agree"
        )
    ideal_reproj = project_pose(Km, R, t, X)
    reproj = _distorted(ideal_reproj, Km, d) if np.any(d) else ideal_reproj
    res = reproj - uv
    n = len(X)
    sigma2 = float(np.sum(res**2)) / max(2 * n - 6, 1)
    J = pose_jacobian(Km, R, t, X)
    if np.any(d):  # the noise is in the measured pixels: chain through the distortion
        D = pixel_distortion_jacobian(ideal_reproj, Km, d)
        J = (D @ J.reshape(n, 2, 6)).reshape(-1, 6)
    cov = sigma2 * np.linalg.pinv(J.T @ J)
    rms = float(np.sqrt(np.sum(res**2) / n))
    return PnPResult(R, t, rvec, rms, res, lm.iterations, cov, np.sqrt(sigma2), used, (R0, t0))
