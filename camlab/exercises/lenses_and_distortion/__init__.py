"""Exercises for lesson 02: focus and field of view, depth of field, and lens distortion.

Each exercise asks for something the lesson has not printed: the field of view of a lens
focused closer than infinity (the thin lens of section 1 with the field of view of
section 3), distortion in pixels (section 4's model between K^-1 and K), the aperture that
makes a given depth range sharp (section 2's c(z) solved the other way), and one Newton
step of undistortion from any current estimate (so the whole 2 x 2 Jacobian matters).

One module per exercise: :mod:`.fov`, :mod:`.distort` (with :mod:`._distort_causes`, the model's own slips),
:mod:`.depth_of_field`, :mod:`.newton`.
"""

from __future__ import annotations

# each module registers its exercise when imported: keep the lesson's order
# isort: off
from . import fov
from . import distort
from . import depth_of_field
from . import newton

# isort: on

__all__ = ["depth_of_field", "distort", "fov", "newton"]
