"""Demos for lesson 09, image stitching: matches, RANSAC, the canvas, blending, the panorama, parallax.

All demos use the rendered panorama set at half size (320 x 240, f = 400 px). Features,
nearest neighbours, warps and blends are computed once and cached by
:mod:`camlab.fixtures.panorama_examples`; sliders only re-filter, re-score or choose among
precomputed images, so every update stays fast.
"""

from __future__ import annotations

from .canvas import (
    BOX,
    blending_seams,
    canvas_projections,
    full_panorama,
    panorama_canvas,
    parallax_ghosting,
)
from .matching import MATCH_STRIDE, feature_matches, ransac_registration

__all__ = [
    "BOX",
    "MATCH_STRIDE",
    "blending_seams",
    "canvas_projections",
    "feature_matches",
    "full_panorama",
    "panorama_canvas",
    "parallax_ghosting",
    "ransac_registration",
]
