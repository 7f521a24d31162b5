"""Real photographs shipped with camlab: ``data/photos/``.

A few photographs from the MIT-licensed mvtb-data package by Peter Corke (facades, a street,
a sign on a wall, stereo pairs), downscaled and re-encoded, and 14 chessboard views
(``calib_left01`` ... ``calib_left14``, unchanged): 13 of them OpenCV's sample images
(Apache-2.0), ``calib_left10`` from mvtb-data only; shipped, not generated, and listed with
their source and licence in ``data/photos/ATTRIBUTION.md``.
"""

from __future__ import annotations

import numpy as np

from .._validate import CamlabInputError
from ._resources import dataset_dir

__all__ = ["PHOTO_SUFFIXES", "load_photo", "photo_names"]

PHOTO_SUFFIXES = (".jpg", ".png")


def photo_names() -> list[str]:
    """Names of the shipped real photographs (``data/photos/``), without extension, sorted.

    Returns
    -------
    list of str
        The names :func:`load_photo` accepts.
    """
    return sorted(p.stem for p in dataset_dir("photos").iterdir() if p.suffix in PHOTO_SUFFIXES)


def load_photo(name: str, gray: bool = False) -> np.ndarray:
    """Load a shipped real photograph by name.

    Parameters
    ----------
    name : str
        One of :func:`photo_names`, e.g. ``"calib_left01"``, ``"street"``, ``"walls_left"``.
    gray : bool
        Return a single-channel image instead of RGB.

    Returns
    -------
    (H, W, 3) or (H, W) uint8 ndarray
        RGB (not OpenCV's BGR) or grey, indexed ``img[v, u]``.
    """
    import cv2

    names = photo_names()
    if not isinstance(name, str) or name not in names:
        raise CamlabInputError(f"name: expected one of {names}, got {name!r}")
    path = next(
        p for p in dataset_dir("photos").iterdir() if p.stem == name and p.suffix in PHOTO_SUFFIXES
    )
    image = cv2.imread(str(path), cv2.IMREAD_GRAYSCALE if gray else cv2.IMREAD_COLOR)
    return image if gray else cv2.cvtColor(image, cv2.COLOR_BGR2RGB)
