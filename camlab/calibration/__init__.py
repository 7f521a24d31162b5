r"""Camera calibration: Zhang's method stage by stage, refined by Levenberg-Marquardt.

A flat chessboard with known square size is photographed in several orientations. Each
view gives a homography :math:`H = \lambda K [r_1\ r_2\ t]` from the board plane (Z = 0)
to the image (:func:`camlab.homography.pose_homography`). Zhang's method [1]_ turns those
into the camera:

1. **detect** the inner corners in every image (:func:`find_chessboard`, OpenCV finds them,
   camlab normalises shapes and says why a detection failed);
2. **homographies** board -> image per view (:func:`view_homographies`, the normalised DLT
   of :mod:`camlab.homography`);
3. **constraints** on :math:`B = K^{-\top} K^{-1}`: :math:`r_1 \perp r_2` and
   :math:`\|r_1\| = \|r_2\|` give two linear equations :math:`v_{12}^\top b = 0`,
   :math:`(v_{11} - v_{22})^\top b = 0` per view (:func:`zhang_v`, :func:`zhang_constraints`);
4. **K in closed form** from the null vector b (:func:`intrinsics_from_b`,
   :func:`intrinsics_from_homographies`);
5. **poses** :math:`r_1 = \lambda K^{-1} h_1` ... made a true rotation by the nearest
   rotation (:func:`extrinsics_from_homography`, :func:`camlab.camera.nearest_rotation`);
6. **radial distortion**, linear least squares for k1, k2 (:func:`initial_radial_distortion`), or,
   with the sign and size right, estimated together with the poses and alternated with the
   closed form (:func:`closed_form_with_distortion`);
7. **refinement** of everything by :func:`camlab.optimise.levenberg_marquardt` on the
   reprojection error with an analytic, per-view block Jacobian (:func:`calibrate_camera`).

Then judge the result (:func:`coach`), undistort images (:func:`undistort`,
:func:`optimal_new_camera_matrix`) and save it for OpenCV (:func:`save_calibration`).

Conventions (docs/conventions.md): pixels (u, v) = (column, row), origin at the centre of
the top-left pixel; ``X_cam = R X_board + t`` (cam_from_world); rotations as axis-angle
``rvec`` (cv2.Rodrigues); ``dist = (k1, k2, p1, p2, k3)`` in OpenCV's order
(:mod:`camlab.distortion`); board points in metres. See lesson 08.

The package keeps one module per stage: :mod:`~camlab.calibration.detection` (1),
:mod:`~camlab.calibration.zhang` (2-6), :mod:`~camlab.calibration.refinement` (7: the model
and its Jacobian), :mod:`~camlab.calibration.calibrate` (the pipeline end to end, from corners),
:mod:`~camlab.calibration.images` (from photographs: detect, report, calibrate),
:mod:`~camlab.calibration.coach`, :mod:`~camlab.calibration.undistortion`,
:mod:`~camlab.calibration.io` and :mod:`~camlab.calibration.synthetic` (test data).
Every public name is re-exported here: ``from camlab.calibration import calibrate_camera``.

References
----------
.. [1] Z. Zhang, 2000, "A flexible new technique for camera calibration", *IEEE Transactions on
   Pattern Analysis and Machine Intelligence* 22(11), 1330-1334.
"""

from __future__ import annotations

from .calibrate import (
    CalibrationResult,
    ClosedFormWithDistortion,
    calibrate_camera,
    closed_form_with_distortion,
)
from .coach import CoachReport, UncertaintyMap, coach, projection_uncertainty
from .detection import (
    ChessboardDetection,
    PatternSize,
    board_points,
    find_chessboard,
    parse_pattern,
)
from .images import ImageCalibration, calibrate_from_images
from .io import SavedCalibration, load_calibration, save_calibration
from .refinement import PARAM_NAMES, reproject
from .synthetic import SyntheticSet, make_synthetic_views
from .undistortion import (
    UndistortionTradeoff,
    optimal_new_camera_matrix,
    undistort,
    undistortion_tradeoff,
)
from .zhang import (
    extrinsics_from_homography,
    initial_radial_distortion,
    intrinsics_from_b,
    intrinsics_from_homographies,
    view_homographies,
    zhang_constraints,
    zhang_v,
)

__all__ = [
    "PARAM_NAMES",
    "CalibrationResult",
    "ChessboardDetection",
    "ClosedFormWithDistortion",
    "CoachReport",
    "ImageCalibration",
    "PatternSize",
    "SavedCalibration",
    "SyntheticSet",
    "UncertaintyMap",
    "UndistortionTradeoff",
    "board_points",
    "calibrate_camera",
    "calibrate_from_images",
    "closed_form_with_distortion",
    "coach",
    "extrinsics_from_homography",
    "find_chessboard",
    "initial_radial_distortion",
    "intrinsics_from_b",
    "intrinsics_from_homographies",
    "load_calibration",
    "make_synthetic_views",
    "optimal_new_camera_matrix",
    "parse_pattern",
    "projection_uncertainty",
    "reproject",
    "save_calibration",
    "undistort",
    "undistortion_tradeoff",
    "view_homographies",
    "zhang_constraints",
    "zhang_v",
]
