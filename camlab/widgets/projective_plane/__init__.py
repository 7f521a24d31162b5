"""Demos for lesson 06, the projective plane.

Each demo draws once and then only moves artists; the geometry comes from
``camlab.projective``. Points, lines, vanishing points and the cross-ratio are in
:mod:`.points_and_lines`; the conic of section 7 is in :mod:`.conics`.
"""

from __future__ import annotations

# the registration order is the lesson's order
# isort: off
from .points_and_lines import (
    cross_ratio_invariance,
    lift_to_plane,
    parallel_lines,
    point_line_duality,
    vanishing_points,
)
from .conics import conic_under_homography

# isort: on

__all__ = [
    "conic_under_homography",
    "cross_ratio_invariance",
    "lift_to_plane",
    "parallel_lines",
    "point_line_duality",
    "vanishing_points",
]
