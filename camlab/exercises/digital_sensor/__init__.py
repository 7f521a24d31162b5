"""Exercises for lesson 03, the digital sensor.

The intrinsic matrix from a datasheet (:mod:`.datasheet`, exercise 1), quantisation
(:mod:`.quantize`, 2), demosaicking (:mod:`.demosaic`, 4) and where a frequency folds to (:mod:`.alias`, 5).
The lesson's third, the sensor's gain and read noise, is :mod:`camlab.exercises.sensor_noise`.
"""

from __future__ import annotations

# each module registers its exercise when imported: keep the lesson's order
# isort: off
from . import quantize
from . import demosaic
from . import datasheet
from . import alias

# isort: on

__all__ = ["alias", "datasheet", "demosaic", "quantize"]
