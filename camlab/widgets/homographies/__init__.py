"""Demos for lesson 07, homographies.

Every demo draws once and then moves artists; the geometry comes from
``camlab.homography`` and ``camlab.warp`` (the cv2 fast path warps pictures live).
Corners can be dragged with the mouse under ipympl; the same corners are a text
control ``"u0, v0; u1, v1; u2, v2; u3, v3"`` so tests and static pages drive them too.
"""

from __future__ import annotations

from ..controls import format_corners
from .estimation import CONFIDENCE, MAX_SAMPLES, forward_vs_inverse, ransac_outliers
from .geometry import CORNER_NAMES, SQUARE, drag_homography, transformation_hierarchy
from .parallax import plane_parallax

__all__ = [
    "CONFIDENCE",
    "CORNER_NAMES",
    "MAX_SAMPLES",
    "SQUARE",
    "drag_homography",
    "format_corners",
    "forward_vs_inverse",
    "plane_parallax",
    "ransac_outliers",
    "transformation_hierarchy",
]
