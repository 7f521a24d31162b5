"""Exercises for lesson 07, homographies.

Applying a homography (:mod:`.apply`), the normalised DLT (:mod:`.dlt`), the number of RANSAC
samples (:mod:`.ransac`), the homography of a plane (:mod:`.plane`) and the inverse warp
(:mod:`.inverse_warp`).
"""

from __future__ import annotations

# each module registers its exercise when imported: keep the registration order
# isort: off
from . import dlt
from . import apply
from . import ransac
from . import plane
from . import inverse_warp

# isort: on

__all__ = ["apply", "dlt", "inverse_warp", "plane", "ransac"]
