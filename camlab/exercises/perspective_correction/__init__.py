"""Exercises for lesson 10, perspective correction.

The rectangle's homography (:mod:`.rectangle`), its shape and the focal length from four corners
(:mod:`.shape`), the corners' order (:mod:`.order`), the image of C*inf from right angles
(:mod:`.conic`) and the affine-rectifying H_P (:mod:`.affine`).
"""

from __future__ import annotations

# each module registers its exercise when imported: keep the registration order
# isort: off
from . import rectangle
from . import order
from . import conic
from . import shape
from . import affine

# isort: on

__all__ = ["affine", "conic", "order", "rectangle", "shape"]
