"""The chessboard calibration set of lesson 08, ``data/calib_chessboard/``: its loader.

``view_00.png`` ... ``view_15.png``: a 9 x 6 inner-corner chessboard (25 mm squares)
rendered by :mod:`camlab.render` from 16 poses through a camera with barrel distortion,
640 x 480, 8-bit grey, with a little sensor noise; ``truth.json`` holds the generator's
parameters and the ground truth (K, dist, each view's pose and exact corner pixels).

Load with :func:`load_calibration_set`. The generator (``python -m camlab.data`` rewrites the
set from fixed parameters) and the set's calibration, computed once, are fixtures:
:mod:`camlab.fixtures.calibration`.
"""

from __future__ import annotations

from pathlib import Path
from typing import NamedTuple

import numpy as np

from ._resources import read_truth

__all__ = ["CalibrationSet", "load_calibration_set"]


class CalibrationSet(NamedTuple):
    """The bundled chessboard set: images and ground truth (see ``data/calib_chessboard/truth.json``).

    ``images``: list of (480, 640) uint8; ``K`` (3, 3); ``dist`` (5,) (k1, k2, p1, p2, k3);
    ``R`` (V, 3, 3) and ``t`` (V, 3) cam_from_world per view; ``corners`` (V, 54, 2) exact
    pixels in OpenCV order; ``object_points`` (54, 3) board-frame metres;
    ``pattern_size`` (9, 6); ``square`` metres; ``params`` the generator's parameters.
    """

    images: list
    K: np.ndarray
    dist: np.ndarray
    R: np.ndarray
    t: np.ndarray
    corners: np.ndarray
    object_points: np.ndarray
    pattern_size: tuple[int, int]
    square: float
    params: dict


def load_calibration_set(directory: Path | str | None = None) -> CalibrationSet:
    """Load ``data/calib_chessboard`` (or ``directory``) as a :class:`CalibrationSet`.

    Parameters
    ----------
    directory : str or pathlib.Path, optional
        Where the set is (default: the shipped copy).

    Returns
    -------
    CalibrationSet
        The images and their ground truth (see :class:`CalibrationSet`).
    """
    import cv2

    d, truth = read_truth(directory, "calib_chessboard")
    images = [cv2.imread(str(d / v["file"]), cv2.IMREAD_GRAYSCALE) for v in truth["views"]]
    return CalibrationSet(
        images=images,
        K=np.array(truth["K"]),
        dist=np.array(truth["dist"]),
        R=np.array([v["R"] for v in truth["views"]]),
        t=np.array([v["t"] for v in truth["views"]]),
        corners=np.array([v["corners"] for v in truth["views"]]),
        object_points=np.array(truth["object_points"]),
        pattern_size=tuple(truth["pattern_size"]),
        square=float(truth["square"]),
        params=truth["params"],
    )
