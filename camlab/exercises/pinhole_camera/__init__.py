"""Exercises for lesson 01, the pinhole camera.

The lesson asks for three: ``project_to_pixels`` (the pinhole projection in pixels),
``focal_length_pixels`` (f_x from a field of view) and ``best_pinhole_exposure`` (the light a
best pinhole costs). ``pinhole_projection`` and ``best_pinhole_diameter``, the lesson's first
two exercises (their answers are printed in the lesson itself), stay registered: the course's
tests of the check machinery use them.

One module per exercise: :mod:`.projection`, :mod:`.diameter`, :mod:`.pixels`, :mod:`.focal_length`,
:mod:`.exposure`.
"""

from __future__ import annotations

# each module registers its exercise when imported: keep the lesson's order
# isort: off
from . import projection
from . import diameter
from . import pixels
from . import focal_length
from . import exposure

# isort: on

__all__ = ["diameter", "exposure", "focal_length", "pixels", "projection"]
