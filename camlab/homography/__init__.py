r"""Homographies: estimation (DLT, RANSAC, Levenberg-Marquardt), algebra and geometry.

A homography is an invertible 3x3 matrix H acting on homogeneous image points,
:math:`x' \sim H x` (rows: ``X @ H.T``), and on lines by :math:`l' \sim H^{-T} l`.
It has 8 degrees of freedom (9 entries up to scale), so four point pairs in general
position fix it. Applying H to points and lines is :func:`camlab.projective.map_points`
and :func:`camlab.projective.map_lines`.

The package holds five topics, every public name importable from ``camlab.homography``:

* :mod:`camlab.homography.core`: checking, normalising, comparing, composing and inverting
  homographies (:func:`check_homography`, :func:`normalise_homography`,
  :func:`same_homography`, :func:`compose`, :func:`invert`);
* :mod:`camlab.homography.estimation`: :func:`estimate_homography` (normalised DLT),
  :func:`ransac_homography` (vectorised adaptive RANSAC) and the error measures
  :func:`transfer_error`, :func:`symmetric_transfer_error`, :func:`sampson_distance`;
* :mod:`camlab.homography.refinement`: :func:`refine_homography` (LM on the symmetric
  transfer error) and :func:`gold_standard_homography` (the maximum-likelihood estimate [1]_:
  LM on the reprojection error over H and corrected points);
* :mod:`camlab.homography.hierarchy`: the transformation hierarchy,
  :func:`euclidean_homography`, :func:`similarity_homography`, :func:`affine_homography`,
  :func:`projective_homography`, :data:`HIERARCHY`, :func:`classify`,
  :func:`decompose_homography`;
* :mod:`camlab.homography.geometry`: homographies from cameras and planes,
  :func:`plane_homography` (:math:`K'(R - t n^T/d)K^{-1}`), :func:`rotation_homography`
  (:math:`K' R K^{-1}`) and :func:`pose_homography` (the world plane Z = 0 to the image,
  :math:`K [r_1\ r_2\ t]`).

Pixel coordinates (u, v) = (column, row), origin at the centre of the top-left pixel
(docs/conventions.md). See lesson 07.

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 4.5 and algorithm 4.3
   (the Gold Standard algorithm).
"""

from __future__ import annotations

from .core import (
    Correspondences,
    check_correspondences,
    check_homography,
    compose,
    invert,
    normalise_homography,
    same_homography,
)
from .estimation import (
    HomographyModel,
    RansacResult,
    estimate_homography,
    ransac_homography,
    sampson_distance,
    symmetric_transfer_error,
    transfer_error,
)
from .geometry import (
    mapped_angle,
    plane_homography,
    pose_homography,
    rotation_homography,
)
from .hierarchy import (
    HIERARCHY,
    HomographyFactors,
    affine_homography,
    classify,
    decompose_homography,
    euclidean_homography,
    hierarchy_matrix,
    projective_homography,
    similarity_homography,
)
from .refinement import (
    GoldStandardResult,
    RefineResult,
    correct_points,
    gold_standard_homography,
    refine_homography,
)

__all__ = [
    "check_homography",
    "Correspondences",
    "GoldStandardResult",
    "check_correspondences",
    "HIERARCHY",
    "HomographyFactors",
    "HomographyModel",
    "RansacResult",
    "RefineResult",
    "affine_homography",
    "classify",
    "compose",
    "correct_points",
    "decompose_homography",
    "estimate_homography",
    "euclidean_homography",
    "gold_standard_homography",
    "hierarchy_matrix",
    "invert",
    "mapped_angle",
    "normalise_homography",
    "plane_homography",
    "pose_homography",
    "projective_homography",
    "ransac_homography",
    "refine_homography",
    "rotation_homography",
    "same_homography",
    "sampson_distance",
    "similarity_homography",
    "symmetric_transfer_error",
    "transfer_error",
]
