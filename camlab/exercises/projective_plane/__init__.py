"""Exercises for lesson 06, the projective plane.

Points and lines (:mod:`.lines`: the join, the meet; :mod:`.vanishing`: a vanishing point), the horizon
(:mod:`.horizon`), the cross-ratio of four collinear points (:mod:`.cross_ratio`), a conic moved by a homography (:mod:`.conic`) and an angle measured through the
image of the dual conic of the circular points (:mod:`.angles`).
"""

from __future__ import annotations

# each module registers its exercises when imported: keep the lesson's order
# isort: off
from . import lines
from . import vanishing
from . import horizon
from . import cross_ratio
from . import conic
from . import angles

# isort: on

__all__ = ["angles", "conic", "cross_ratio", "horizon", "lines", "vanishing"]
