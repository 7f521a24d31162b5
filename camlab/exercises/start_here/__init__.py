"""Exercises for lesson 00, start here: how exercises and checks work.

Lifting a point to homogeneous coordinates (:mod:`.lifting`; the slips of x and y in
:mod:`._lift_causes`, the errors a student's code raises in :mod:`._lift_raised`), the way back,
each row divided by its own w (:mod:`.dividing`), and section 3's
conventions at work, reading pixels and turning points about the image's centre
(:mod:`.conventions`; its causes in :mod:`._turn_causes` and :mod:`._turn_raised`).
"""

from __future__ import annotations

# each module registers its exercise when imported: keep the lesson's order
# isort: off
from . import lifting
from . import dividing
from . import conventions

# isort: on

__all__ = ["conventions", "dividing", "lifting"]
