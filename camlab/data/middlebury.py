r"""A real rectified stereo pair with ground-truth disparity, ``data/middlebury/`` (lesson 11): its loader.

Middlebury's 2014 "Motorcycle" scene [1]_, as scikit-image ships it
(``skimage.data.stereo_motorcycle``, downsampled 4 x to 741 x 500): the only real pair in the
course whose depth is known at (almost) every pixel, measured with structured light.

``motorcycle_left.png``, ``motorcycle_right.png``
    The rectified pair, 741 x 500, 8-bit grey (converted from scikit-image's RGB, lossless).
``motorcycle_disparity.png``
    The true disparity of every left pixel, stored KITTI-style: uint16 = round(256 d),
    0 = no ground truth (7 % of the pixels: occlusions and holes of the structured light).
``calib.json``
    The calibration of the downsampled pair: focal length f, the left principal point
    (``cx_left``, ``cy``), ``doffs`` (the right camera's principal point lies ``doffs`` px
    further right, so a point at depth Z has disparity :math:`d = f B / Z - d_{offs}`) and
    the baseline B (metres).

Sources and licence: ``data/ATTRIBUTION.md``. Conventions: pixels (u, v) = (column, row),
origin at the centre of the top-left pixel; the left pixel (u, v) matches the right pixel
(u - d, v).

References
----------
.. [1] D. Scharstein, H. Hirschmuller, Y. Kitajima, G. Krathwohl, N. Nesic, X. Wang and P. Westling,
   2014, "High-resolution stereo datasets with subpixel-accurate ground truth", *German Conference
   on Pattern Recognition (GCPR)*, LNCS 8753, 31-42.
"""

from __future__ import annotations

import json
from typing import NamedTuple

import numpy as np

from ._resources import dataset_dir

__all__ = ["MiddleburyPair", "load_middlebury"]


class MiddleburyPair(NamedTuple):
    """Middlebury 2014 "Motorcycle" at quarter size: a real rectified pair with true disparity.

    Attributes
    ----------
    left, right : (500, 741) uint8 ndarray
        The rectified grey pair, ``img[v, u]``.
    disparity : (500, 741) float ndarray
        True disparity of each left pixel, pixels (the match is ``right[v, u - d]``); NaN where
        there is no ground truth.
    focal : float
        Focal length, pixels.
    cx, cy : float
        The left camera's principal point, pixels.
    doffs : float
        ``cx_right - cx_left``, pixels: depth is :math:`Z = f B / (d + d_{offs})`.
    baseline : float
        Distance between the camera centres, metres.
    """

    left: np.ndarray
    right: np.ndarray
    disparity: np.ndarray
    focal: float
    cx: float
    cy: float
    doffs: float
    baseline: float


def load_middlebury() -> MiddleburyPair:
    """Load the shipped Middlebury "Motorcycle" pair, its true disparity and its calibration.

    Returns
    -------
    MiddleburyPair
        The grey pair, the true disparity (NaN = unknown), f, cx, cy, doffs (pixels) and the
        baseline (metres).
    """
    import cv2

    d = dataset_dir("middlebury")
    calib = json.loads((d / "calib.json").read_text())
    left, right = (
        cv2.imread(str(d / f"motorcycle_{side}.png"), cv2.IMREAD_GRAYSCALE)
        for side in ("left", "right")
    )
    raw = cv2.imread(str(d / "motorcycle_disparity.png"), cv2.IMREAD_UNCHANGED)
    disparity = np.where(raw > 0, raw / float(calib["disparity_scale"]), np.nan)
    return MiddleburyPair(
        left,
        right,
        disparity,
        float(calib["focal_px"]),
        float(calib["cx_left"]),
        float(calib["cy"]),
        float(calib["doffs_px"]),
        float(calib["baseline_m"]),
    )
