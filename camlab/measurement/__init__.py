r"""Measure the world with a calibrated camera (lesson 12): pose, lengths on a plane, depth.

Three topics, every public name importable from ``camlab.measurement``:

* :mod:`camlab.measurement.pnp`: where is the camera? The pose from known points and their
  pixels (PnP), with its covariance;
* :mod:`camlab.measurement.plane`: lengths and areas on a plane of known scale, with an
  uncertainty propagated from the corner noise;
* :mod:`camlab.measurement.depth`: two views: triangulation from a rectified pair and the depth
  uncertainty law :math:`\sigma_Z = Z^2 \sigma_d / (f B)`.
"""

from .depth import RectifiedCameras, depth_sigma, rectified_cameras, triangulate_rectified
from .plane import PlaneMeasurement, area_on_plane, measure_on_plane, pixels_to_plane
from .pnp import (
    PlaneFrame,
    PnPResult,
    plane_frame,
    pose_covariance,
    pose_jacobian,
    project_pose,
    solve_pnp,
)

__all__ = [
    "PlaneFrame",
    "PlaneMeasurement",
    "PnPResult",
    "RectifiedCameras",
    "area_on_plane",
    "depth_sigma",
    "measure_on_plane",
    "pixels_to_plane",
    "plane_frame",
    "pose_covariance",
    "pose_jacobian",
    "project_pose",
    "rectified_cameras",
    "solve_pnp",
    "triangulate_rectified",
]
