"""Exercises for lesson 05, affine cameras.

The weak-perspective (P_inf, :mod:`.weak_perspective`) and para-perspective
(:mod:`.paraperspective`) approximations of a perspective camera, which share their test cameras and
typical slips (:mod:`._approx_common`), and the least-squares affine camera (:mod:`.estimation`).

Every diagnosis either names a cause it has tested (the answer equals exactly what that mistake
gives) or says what differs (which entries, by how much), never a guess.
"""

from __future__ import annotations

# each module registers its exercises when imported: keep the lesson's order
# isort: off
from . import weak_perspective
from . import paraperspective
from . import estimation

# isort: on

__all__ = ["estimation", "paraperspective", "weak_perspective"]
