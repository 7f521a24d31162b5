"""Exercises for lesson 05, affine cameras.

The weak-perspective (P_inf, :mod:`.weak_perspective`) and para-perspective
(:mod:`.paraperspective`) approximations of a perspective camera, which share their test cameras and
typical slips (:mod:`._approx_common`), the least-squares affine camera (:mod:`.estimation`), and the
rank-3 reprojection of Tomasi-Kanade factorisation (:mod:`.factorization`).

Every diagnosis either names a cause it has tested (the answer equals exactly what that mistake
gives) or says what differs (which entries, by how much), never a guess.
"""

from __future__ import annotations

# each module registers its exercises when imported: keep the lesson's order
# isort: off
from . import weak_perspective
from . import paraperspective
from . import estimation
from . import factorization

# isort: on

__all__ = ["estimation", "factorization", "paraperspective", "weak_perspective"]
