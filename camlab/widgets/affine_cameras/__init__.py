"""Demos for lesson 05, affine cameras.

In a lesson::

    %matplotlib widget
    from camlab.widgets import affine_cameras as demos
    demos.three_cameras()
"""

from __future__ import annotations

from .common import (
    COLOURS,
    D0,
    DOLLY_DISTANCES,
    DOLLY_OFFSET,
    DOLLY_VIEW,
    F0,
    PRINCIPAL_POINT_MARKER,
    REFERENCE_LABEL,
    REFERENCE_MARKER,
    STYLES,
    TARGET,
    model_legend,
    model_line,
    place_reference,
    reference_marker,
)
from .rails import (
    RAIL_EYE,
    RAIL_REFERENCE,
    RAIL_SAMPLES,
    RAIL_TRACK,
    RailCameras,
    parallel_rails,
    rail_cameras,
)
from .rays import (
    CENTRE_MARKER,
    RAY_DEPTH,
    RAY_IMAGE,
    RAY_OBJECT,
    SCALING_STYLE,
    SIGHT_STYLE,
    projection_rays,
)
from .views import (
    APPROXIMATIONS,
    DOLLY_ERROR_LIMITS,
    GAP_SAMPLES,
    dolly_curves,
    dolly_zoom,
    three_cameras,
)

__all__ = [
    "RailCameras",
    "APPROXIMATIONS",
    "CENTRE_MARKER",
    "COLOURS",
    "D0",
    "dolly_curves",
    "DOLLY_DISTANCES",
    "DOLLY_ERROR_LIMITS",
    "DOLLY_OFFSET",
    "DOLLY_VIEW",
    "dolly_zoom",
    "F0",
    "GAP_SAMPLES",
    "model_legend",
    "model_line",
    "parallel_rails",
    "place_reference",
    "PRINCIPAL_POINT_MARKER",
    "projection_rays",
    "rail_cameras",
    "RAIL_EYE",
    "RAIL_REFERENCE",
    "RAIL_SAMPLES",
    "RAIL_TRACK",
    "RAY_DEPTH",
    "RAY_IMAGE",
    "RAY_OBJECT",
    "REFERENCE_LABEL",
    "REFERENCE_MARKER",
    "reference_marker",
    "SCALING_STYLE",
    "SIGHT_STYLE",
    "STYLES",
    "TARGET",
    "three_cameras",
]
