r"""The projective camera :math:`P = K [R \mid t]`: project, back-project, decompose, resection.

A pinhole camera maps a world point :math:`X` (metres) to a pixel :math:`(u, v)` in two
steps. The *extrinsics* ``R, t`` move the point into the camera frame
(``cam_from_world``), and the *intrinsics* ``K`` map camera-frame directions to pixels:

.. math::

    X_c = R X + t, \qquad
    \lambda \begin{pmatrix} u \\ v \\ 1 \end{pmatrix} = K X_c, \qquad
    K = \begin{pmatrix} f_x & s & c_x \\ 0 & f_y & c_y \\ 0 & 0 & 1 \end{pmatrix},

so :math:`\lambda \tilde u = P \tilde X` with the 3x4 matrix :math:`P = K [R \mid t]`.
The depth :math:`\lambda = z_c` is positive in front of the camera; points with
:math:`z_c \le 0` have no image and come back as NaN.

The package holds three topics, every public name importable from ``camlab.camera``:

* :mod:`camlab.camera.rotations`: rotations (axis-angle, Euler angles, the nearest rotation),
  look-at, and the OpenCV, OpenGL and Blender camera frames;
* :mod:`camlab.camera.model`: the intrinsics, the :class:`Camera` and any 3x4 camera matrix:
  project, back-project, the camera centre, wireframes;
* :mod:`camlab.camera.resection`: RQ and the decomposition of P, and P estimated from
  world-image correspondences (the camera DLT) with its reprojection errors.

Conventions (docs/conventions.md): camera frame x right, y down, z forward (OpenCV, and
Hartley & Zisserman's [1]_); ``R, t`` are *cam_from_world*; the camera centre is
:math:`C = -R^\top t`; pixels (u, v) = (column, row) with the origin at the centre of the
top-left pixel; points are rows, so the textbook :math:`x = P X` is ``X_h @ P.T``;
angles in radians. See lesson 04.

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, chapter 6 (camera models),
   section 6.1.
"""

from __future__ import annotations

from .derivatives import cross_matrix, division_jacobian
from .dlt_analysis import dlt_conditioning, dlt_matrix, predicted_rms_error, unnormalised_dlt
from .model import (
    Camera,
    CameraPair,
    camera_centre,
    centred_intrinsics,
    check_camera_matrix,
    intrinsic_matrix,
    project_points,
    project_segments,
    scale_intrinsics,
)
from .resection import (
    RQ,
    Decomposition,
    decompose_projection_matrix,
    estimate_projection_matrix,
    reprojection_errors,
    rq_decomposition,
)
from .rotations import (
    CV_FROM_GL,
    Pose,
    axis_angle_from_rotation,
    axis_angle_from_rotation_unchecked,
    blender_matrix_world,
    euler_from_rotation,
    is_rotation,
    look_at_rotation,
    nearest_rotation,
    opencv_from_opengl,
    opengl_from_opencv,
    orbit_eye,
    rotation_from_axis_angle,
    rotation_from_axis_angle_unchecked,
    rotation_from_euler,
    rotation_x,
    rotation_y,
    rotation_z,
)

__all__ = [
    "Camera",
    "CameraPair",
    "Decomposition",
    "CV_FROM_GL",
    "Pose",
    "RQ",
    "axis_angle_from_rotation",
    "axis_angle_from_rotation_unchecked",
    "camera_centre",
    "check_camera_matrix",
    "cross_matrix",
    "decompose_projection_matrix",
    "division_jacobian",
    "dlt_conditioning",
    "dlt_matrix",
    "predicted_rms_error",
    "unnormalised_dlt",
    "estimate_projection_matrix",
    "euler_from_rotation",
    "intrinsic_matrix",
    "centred_intrinsics",
    "is_rotation",
    "look_at_rotation",
    "nearest_rotation",
    "orbit_eye",
    "blender_matrix_world",
    "opencv_from_opengl",
    "opengl_from_opencv",
    "project_points",
    "reprojection_errors",
    "rotation_from_axis_angle",
    "rotation_from_axis_angle_unchecked",
    "rotation_from_euler",
    "rq_decomposition",
    "rotation_x",
    "rotation_y",
    "rotation_z",
    "scale_intrinsics",
    "project_segments",
]
