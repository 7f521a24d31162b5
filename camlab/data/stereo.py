r"""A rendered stereo rig with full ground truth, ``data/stereo/`` (lesson 11): its loader.

``left.jpg``, ``right.jpg``
    The raw pair, 640 x 480, 8-bit grey, with lens distortion, a slight toe-in, a small
    vertical offset and roll between the cameras (so rectification has work to do), a
    little sensor noise, stored as JPEG (quality ``jpeg_quality``) as a camera would: the
    random textures cost about 225 kB per image as PNG, and all of ``data/`` must stay
    within its budget (tests/test_data.py). The ground truth is exact; the compression noise is part of the matching
    problem (depth accuracy is tested on these very files). The scene: a textured back wall, three textured planes at
    different depths (one showing a photograph), and two boxes with noise-textured faces.
``disparity.png``
    The true disparity of the *calibrated rectification* of the pair (``alpha = 0``), for
    every pixel of the rectified left image, stored KITTI-style: uint16 = round(256 d),
    0 = no surface. Load with :func:`load_stereo_rig`.
``calib_left_NN.png``, ``calib_right_NN.png``
    Chessboard views seen by both cameras (9 x 6 inner corners, 25 mm squares), for
    stereo calibration; noise-free 8-bit (keeps them about 10 kB each; the whole of
    ``data/`` must stay within its budget).
``truth.json``
    Both cameras (K, dist, R, t cam_from_world), the rectified cameras, the exact corner
    pixels of every calibration view in both images, and the generator's parameters.
``data/MANIFEST.txt`` lists the SHA-256 and size of every file.

Conventions: pixels (u, v) = (column, row), origin at the centre of the top-left pixel;
world z up, metres; the left camera looks along world +y.

The generator (``python -m camlab.data`` rewrites the set from ``STEREO_PARAMS`` with
:mod:`camlab.render`) and the pipelines lesson 11's demos run on the rig (true matches,
calibration, rectification at half size) are fixtures: :mod:`camlab.fixtures.stereo`.
"""

from __future__ import annotations

from pathlib import Path
from typing import NamedTuple

import numpy as np

from ..camera import Camera
from ._resources import read_truth

__all__ = ["StereoRig", "load_stereo_rig"]


class StereoRig(NamedTuple):
    """The bundled stereo rig: raw images, cameras, true rectified disparity, calibration views."""

    left: np.ndarray  # (480, 640) uint8
    right: np.ndarray
    camera1: Camera  # left camera (with distortion)
    camera2: Camera
    disparity: (
        np.ndarray
    )  # (480, 640) float, true disparity of the alpha=0 calibrated rectification; NaN = none
    calib_left: list[np.ndarray]
    calib_right: list[np.ndarray]
    calib_corners_left: np.ndarray  # (n, 54, 2) exact pixels
    calib_corners_right: np.ndarray
    object_points: np.ndarray  # (54, 3) board frame
    pattern_size: tuple[int, int]
    params: dict


# ----------------------------------------------------------------------------- the rig as lesson 11 uses it


def load_stereo_rig(directory: Path | str | None = None) -> StereoRig:
    """Load ``data/stereo`` (or ``directory``) as a :class:`StereoRig`.

    Parameters
    ----------
    directory : str or pathlib.Path, optional
        Where the set is (default: the shipped copy).

    Returns
    -------
    StereoRig
        The raw pair, the cameras, the true rectified disparity and the calibration views.
    """
    import cv2

    d, truth = read_truth(directory, "stereo")

    def cam(j):
        return Camera(
            np.array(j["K"]),
            np.array(j["R"]),
            np.array(j["t"]),
            tuple(j["dist"]),
            tuple(j["image_size"]),
        )

    def grey(name):
        return cv2.imread(str(d / name), cv2.IMREAD_GRAYSCALE)

    disp = cv2.imread(str(d / "disparity.png"), cv2.IMREAD_UNCHANGED).astype(float) / 256.0
    disp[disp == 0] = np.nan
    views = truth["calibration_views"]
    return StereoRig(
        left=grey("left.jpg"),
        right=grey("right.jpg"),
        camera1=cam(truth["camera_left"]),
        camera2=cam(truth["camera_right"]),
        disparity=disp,
        calib_left=[grey(v["left"]) for v in views],
        calib_right=[grey(v["right"]) for v in views],
        calib_corners_left=np.array([v["corners_left"] for v in views]),
        calib_corners_right=np.array([v["corners_right"] for v in views]),
        object_points=np.array(truth["object_points"]),
        pattern_size=tuple(truth["pattern_size"]),
        params=truth["params"],
    )
