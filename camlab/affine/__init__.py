r"""Affine cameras: orthographic, weak perspective and the general affine camera.

An affine camera is a 3x4 matrix whose last row is :math:`(0, 0, 0, 1)`:

.. math::

    P_A = \begin{pmatrix} m_{11} & m_{12} & m_{13} & m_{14} \\
                          m_{21} & m_{22} & m_{23} & m_{24} \\
                          0 & 0 & 0 & 1 \end{pmatrix},
    \qquad u = M_2 X + t_2 ,

so projection is linear (no division by depth). Its centre is at infinity (all rays
are parallel), parallel world lines stay parallel in the image, and the midpoint of
a segment images to the midpoint of its image. The family, from special to general
([1]_, section 6.3):

* **orthographic**: drop the camera z coordinate, :math:`u = (r_1 \cdot X + t_1,\ r_2 \cdot X + t_2)`;
* **scaled orthographic**: the same times a scale k (pixels per metre);
* **weak perspective**: different scales :math:`\alpha_x, \alpha_y` (and skew);
* **general affine**: any :math:`M_2` of rank 2, 8 degrees of freedom.

A perspective camera looking at an object of depth range :math:`\Delta` at distance
:math:`d_0` is close to affine when :math:`\Delta \ll d_0`: the weak-perspective
image of a point differs from its perspective image by the factor
:math:`\Delta / d_0` times its distance from the principal point ([1]_, section 6.3.2).

Conventions (docs/conventions.md): R, t are cam_from_world, camera frame x right,
y down, z forward; pixels (u, v) = (column, row); points are rows. See lesson 05.

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 6.3 (cameras at
   infinity).
"""

from __future__ import annotations

from .cameras import (
    PROJECTION_MODELS,
    affine_approximation,
    image_of_direction,
    is_affine,
    orthographic_matrix,
    paraperspective_approximation,
    projection_rays,
    scaled_orthographic_matrix,
    weak_perspective_error,
    weak_perspective_matrix,
)
from .dolly_zoom import (
    MatchedPoints,
    ThreeImages,
    dolly_zoom_camera,
    dolly_zoom_errors,
    dolly_zoom_focal,
    largest_gap_in_frame,
    matched_points_in_frame,
    three_images,
)
from .estimation import (
    AffineDeparture,
    affine_departure,
    affine_fit_departure,
    estimate_affine_camera,
)

__all__ = [
    "AffineDeparture",
    "affine_approximation",
    "affine_departure",
    "affine_fit_departure",
    "dolly_zoom_camera",
    "dolly_zoom_errors",
    "dolly_zoom_focal",
    "estimate_affine_camera",
    "image_of_direction",
    "is_affine",
    "largest_gap_in_frame",
    "matched_points_in_frame",
    "MatchedPoints",
    "orthographic_matrix",
    "paraperspective_approximation",
    "projection_rays",
    "PROJECTION_MODELS",
    "scaled_orthographic_matrix",
    "ThreeImages",
    "three_images",
    "weak_perspective_error",
    "weak_perspective_matrix",
]
