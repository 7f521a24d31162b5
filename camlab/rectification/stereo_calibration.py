r"""Stereo calibration.

Both cameras' intrinsics and the rig's relative pose (R, t) from views of one chessboard seen by
both, refined jointly (``cv2.stereoCalibrate``'s problem).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, as_points
from ..camera import Camera, CameraPair, nearest_rotation

__all__ = [
    "StereoCalibration",
    "stereo_calibrate",
]


class StereoCalibration(NamedTuple):
    """What :func:`stereo_calibrate` found.

    ``K1, dist1, K2, dist2``: each camera's intrinsics (pixels) and distortion;
    ``R`` (3, 3), ``t`` (3,): camera 2's pose relative to camera 1 (``X_2 = R X_1 + t``,
    metres, the unit of the board); ``rms``: the joint RMS reprojection error over both
    images, pixels (``cv2.stereoCalibrate``'s number); ``rms1``, ``rms2``: each camera's
    single calibration; ``rvecs, tvecs`` (V, 3): the board's pose in camera 1 per view;
    ``iterations``, ``converged``: of the joint LM refinement.
    """

    K1: np.ndarray
    dist1: np.ndarray
    K2: np.ndarray
    dist2: np.ndarray
    R: np.ndarray
    t: np.ndarray
    rms: float
    rms1: float
    rms2: float
    rvecs: np.ndarray
    tvecs: np.ndarray
    iterations: int
    converged: bool

    def cameras(self, image_size: tuple[int, int] = (640, 480)) -> CameraPair:
        """The rig as two :class:`Camera` objects, camera 1 at the world origin.

        Parameters
        ----------
        image_size : (width, height)
            Both cameras' image size, pixels.

        Returns
        -------
        CameraPair
            Camera 1 (``K1``, ``dist1``, identity pose) and camera 2 (``K2``, ``dist2``,
            pose ``R``, ``t``).
        """
        return CameraPair(
            Camera(self.K1, np.eye(3), np.zeros(3), tuple(self.dist1), image_size),
            Camera(self.K2, self.R, self.t, tuple(self.dist2), image_size),
        )


def _g(K: np.ndarray, dist: np.ndarray) -> np.ndarray:
    return np.array([K[0, 0], K[1, 1], K[0, 2], K[1, 2], K[0, 1], *dist], dtype=float)


def _check_stereo_views(object_points, image_points1, image_points2):
    """The board points (N, 3) and both cameras' views, V >= 3 lists of (N, 2) corners."""
    X = as_points(object_points, 3, "object_points", min_count=4).array
    views1 = [as_points(p, 2, f"image_points1[{i}]").array for i, p in enumerate(image_points1)]
    views2 = [as_points(p, 2, f"image_points2[{i}]").array for i, p in enumerate(image_points2)]
    if len(views1) != len(views2) or len(views1) < 3:
        raise CamlabInputError(
            f"image_points1, image_points2: expected the same number (>= 3) of views seen by "
            f"both cameras, got {len(views1)} and {len(views2)}"
        )
    for i, (a, b) in enumerate(zip(views1, views2, strict=True)):
        if len(a) != len(X) or len(b) != len(X):
            raise CamlabInputError(
                f"image_points[{i}]: expected {len(X)} corners per view (one per object point), "
                f"got {len(a)} and {len(b)}"
            )
    return X, views1, views2


def stereo_calibrate(
    object_points: ArrayLike,
    image_points1,
    image_points2,
    image_size: tuple[int, int],
    *,
    refine_intrinsics: bool = False,
    max_iter: int = 50,
) -> StereoCalibration:
    r"""Calibrate a two-camera rig from V >= 3 chessboard views seen by both cameras.

    1. Calibrate each camera alone (:func:`camlab.calibration.calibrate_camera`: Zhang's
       closed form, then Levenberg-Marquardt). Each view gives the board's pose in both
       cameras, :math:`(R_{1v}, t_{1v})` and :math:`(R_{2v}, t_{2v})`.
    2. Each view then gives an estimate of the rig, :math:`R_v = R_{2v} R_{1v}^\top`,
       :math:`t_v = t_{2v} - R_v t_{1v}`; start from the rotation nearest to their mean and
       the median translation.
    3. Refine jointly with :func:`camlab.optimise.levenberg_marquardt`: unknowns are the
       rig (R, t) and every board pose in camera 1 (and, with ``refine_intrinsics``, both
       cameras' intrinsics and distortion); residuals are the reprojection errors of every
       corner in *both* images, camera 2 seeing the board at
       :math:`(R R_{1v},\ R t_{1v} + t)`. The rig is then consistent across all views, not
       one per view. The Jacobian is taken by central differences (about 6V + 6 unknowns).

    Parameters
    ----------
    object_points : (N, 3) array_like
        The board's points in its own frame, metres, Z = 0 (the same for every view).
    image_points1, image_points2 : sequence of V (N, 2) array_like
        The detected corners in camera 1 and camera 2, in the same order.
    image_size : (width, height)
        Pixels.
    refine_intrinsics : bool
        Also refine K and distortion of both cameras in the joint step (OpenCV's default
        ``CALIB_FIX_INTRINSIC`` keeps them, like the default False here).
    max_iter : int
        Iteration cap of the joint Levenberg-Marquardt refinement.

    Returns
    -------
    StereoCalibration
        ``K1``, ``dist1``, ``K2``, ``dist2``, the rig ``R``, ``t`` (camera 2 from camera 1),
        ``rms`` (joint, pixels), ``rms1``, ``rms2`` (each camera alone), the board poses
        ``rvecs``, ``tvecs`` in camera 1, ``iterations`` and ``converged``.

    Raises
    ------
    CamlabInputError
        Fewer than 4 object points, fewer than 3 views, different view counts for the two
        cameras, or a view whose corner count differs from the object points'.
    """
    from .. import calibration as cal
    from ..calibration.refinement import project_views
    from ..camera import axis_angle_from_rotation, rotation_from_axis_angle
    from ..optimise import levenberg_marquardt

    X, views1, views2 = _check_stereo_views(object_points, image_points1, image_points2)
    c1 = cal.calibrate_camera(X, views1, image_size)
    c2 = cal.calibrate_camera(X, views2, image_size)
    Rs = [R2 @ R1.T for R1, R2 in zip(c1.R, c2.R, strict=True)]
    ts = np.array([t2 - Rv @ t1 for Rv, t1, t2 in zip(Rs, c1.tvecs, c2.tvecs, strict=True)])
    R0 = nearest_rotation(np.mean(Rs, axis=0))
    t0 = np.median(ts, axis=0)
    V = len(views1)
    Xv = np.broadcast_to(X, (V,) + X.shape)
    obs = np.concatenate([np.stack(views1), np.stack(views2)])  # (2V, N, 2)

    def unpack(p):
        rig_r, rig_t, poses = p[:3], p[3:6], p[6 : 6 + 6 * V].reshape(V, 6)
        if refine_intrinsics:
            g1, g2 = p[6 + 6 * V : 16 + 6 * V], p[16 + 6 * V :]
        else:
            g1, g2 = _g(c1.K, c1.dist), _g(c2.K, c2.dist)
        return rotation_from_axis_angle(rig_r), rig_t, poses, g1, g2

    def residuals(p):
        Rr, tr, poses, g1, g2 = unpack(p)
        R1 = np.stack([rotation_from_axis_angle(r) for r in poses[:, :3]])
        R2 = Rr @ R1
        poses2 = np.column_stack(
            [[axis_angle_from_rotation(R) for R in R2], poses[:, 3:] @ Rr.T + tr]
        )
        uv = np.concatenate([project_views(g1, poses, Xv), project_views(g2, poses2, Xv)])
        return (uv - obs).ravel()

    p0 = np.concatenate(
        [axis_angle_from_rotation(R0), t0, np.column_stack([c1.rvecs, c1.tvecs]).ravel()]
    )
    if refine_intrinsics:
        p0 = np.concatenate([p0, _g(c1.K, c1.dist), _g(c2.K, c2.dist)])
    # no jacobian: levenberg_marquardt differentiates the residuals (numeric_jacobian)
    res = levenberg_marquardt(residuals, p0, max_iter=max_iter)
    Rr, tr, poses, g1, g2 = unpack(res.x)

    def K_of(g):
        return np.array([[g[0], g[4], g[2]], [0.0, g[1], g[3]], [0.0, 0.0, 1.0]])

    rms = float(np.sqrt(np.sum(res.residuals**2) / (obs.size / 2)))
    return StereoCalibration(
        K_of(g1),
        np.array(g1[5:]),
        K_of(g2),
        np.array(g2[5:]),
        Rr,
        tr,
        rms,
        float(c1.rms),
        float(c2.rms),
        poses[:, :3].copy(),
        poses[:, 3:].copy(),
        int(res.iterations),
        bool(res.converged),
    )
