"""Exercises for lesson 04, the projective camera P = K [R | t].

Projecting points (:mod:`.projection`), the camera centre (:mod:`.centre`), the RQ decomposition
(:mod:`.rq`), the normalised DLT (:mod:`.dlt`, with :mod:`._dlt_forms` and :mod:`._dlt_survey`) and
a pose for Blender (:mod:`.blender`); the test cameras are in :mod:`._scenes`.
"""

from __future__ import annotations

# each module registers its exercise when imported: keep the lesson's order
# isort: off
from . import projection
from . import centre
from . import rq
from . import dlt
from . import blender

# isort: on

__all__ = ["blender", "centre", "dlt", "projection", "rq"]
