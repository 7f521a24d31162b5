"""Exercises for lesson 09, image stitching.

The canvas bounds (:mod:`.canvas_box`), feathering weights (:mod:`.feather_weights`), the focal
length from a rotation-only homography (:mod:`.focal`, its formulas' denominators in
:mod:`.focal_denominators`) and gain compensation's normal equations
(:mod:`.gains`).
"""

from __future__ import annotations

# each module registers its exercise when imported: keep the lesson's order
# isort: off
from . import canvas_box
from . import feather_weights
from . import focal
from . import gains

# isort: on

__all__ = ["canvas_box", "feather_weights", "focal", "gains"]
