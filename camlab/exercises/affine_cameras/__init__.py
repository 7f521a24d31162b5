"""Exercises for lesson 05, affine cameras: the weak-perspective (P_inf) and para-perspective
approximations of a perspective camera (:mod:`.approximations`), and the least-squares affine
camera (:mod:`.estimation`).

Every diagnosis either names a cause it has tested (the answer equals exactly what that mistake
gives) or says what differs (which entries, by how much), never a guess.
"""

from __future__ import annotations

from . import approximations, estimation

__all__ = ["approximations", "estimation"]
