"""Exercises for lesson 11, epipolar geometry and stereo rectification.

The 8-point algorithm (:mod:`.eight_point`), the epipoles (:mod:`.epipoles`), the essential matrix's
pose (:mod:`.essential`), linear triangulation (:mod:`.triangulate`), the rectifying rotation
(:mod:`.rectifying`), depth from disparity
(:mod:`.depth`), the bad-pixel rate (:mod:`.bad_pixels`) and block matching's sub-pixel
disparity (:mod:`.subpixel`), Hartley's rectifying homography (:mod:`.hartley`).
"""

from __future__ import annotations

# each module registers its exercise when imported: keep the registration order
# isort: off
from . import eight_point
from . import epipoles
from . import depth
from . import essential
from . import triangulate
from . import rectifying
from . import bad_pixels
from . import subpixel
from . import hartley

# isort: on

__all__ = [
    "bad_pixels",
    "depth",
    "eight_point",
    "epipoles",
    "essential",
    "hartley",
    "rectifying",
    "subpixel",
    "triangulate",
]
