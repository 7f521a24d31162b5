"""camlab's data sets: small assets the project made itself (or re-encoded), and their loaders.

The files live in the repository's top-level ``data/`` and travel inside the wheel as
package resources (:mod:`camlab.data._resources` finds them with :mod:`importlib.resources`).
One module per set, each with its loader:

:mod:`camlab.data.calibration`
    ``calib_chessboard/``: 16 rendered chessboard views with exact ground truth (lesson 08).
:mod:`camlab.data.panorama`
    ``panorama/``: a camera turning about its centre in a rendered room, and a planar pair (lesson 09).
:mod:`camlab.data.stereo`
    ``stereo/``: a rendered stereo rig with true disparity and calibration views (lesson 11).
:mod:`camlab.data.photos`
    ``photos/``: real photographs (mvtb-data, MIT; the chessboard views are OpenCV's samples, Apache-2.0).
:mod:`camlab.data.middlebury`
    ``middlebury/``: a real rectified stereo pair with true disparity (Middlebury 2014 via scikit-image, BSD).

The loaders sit at the bottom of the import graph: they read files and build the camera
model, and run no algorithm (``tests/test_architecture.py``). What runs camlab to make or
prepare data (the generators, and the pipelines cached for the lessons' demos) lives in
:mod:`camlab.fixtures`. ``python -m camlab.data [DIR]`` regenerates every rendered set
deterministically (:mod:`camlab.fixtures.regenerate`); ``$CAMLAB_DATA`` points the loaders at
regenerated sets. ``data/ATTRIBUTION.md`` lists every shipped file's source and licence.
"""

from ._resources import (
    cache_dir,
    data_dir,
    dataset_dir,
    docs_dir,
    encode_image,
    lessons_dir,
    read_only,
    regeneration_dir,
)
from .calibration import CalibrationSet, load_calibration_set
from .middlebury import MiddleburyPair, load_middlebury
from .panorama import (
    PanoramaSet,
    PlanarPair,
    load_aerial_mosaic,
    load_panorama_set,
    load_planar_pair,
)
from .photos import load_photo, photo_names
from .stereo import StereoRig, load_stereo_rig

__all__ = [
    "CalibrationSet",
    "MiddleburyPair",
    "PanoramaSet",
    "PlanarPair",
    "StereoRig",
    "cache_dir",
    "data_dir",
    "dataset_dir",
    "docs_dir",
    "encode_image",
    "lessons_dir",
    "load_aerial_mosaic",
    "load_calibration_set",
    "load_middlebury",
    "load_panorama_set",
    "load_photo",
    "load_planar_pair",
    "load_stereo_rig",
    "photo_names",
    "read_only",
    "regeneration_dir",
]
