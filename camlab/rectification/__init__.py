r"""Stereo rectification: warp two views so that epipolar lines become the same image rows.

After rectification a world point appears in both images on the same row, at columns
:math:`u_1` and :math:`u_2`; the *disparity* :math:`d = u_1 - u_2` gives its depth
:math:`Z = f B / d` (focal length f in pixels, baseline B in metres). Matching becomes a
1-D search along rows.

Two routes, both warping each image by a homography (plus undistortion):

* **calibrated** (:func:`rectify_calibrated`: Fusiello, Trucco & Verri's algorithm [1]_,
  Bouguet's method in OpenCV [2]_): with both cameras known, rotate both about their
  centres to a common orientation whose x axis is the baseline, and give both the same
  intrinsics. A rotation about the centre is the homography :math:`K_{new} R_{rect} K^{-1}`.
* **uncalibrated** (:func:`rectify_uncalibrated`: Hartley's method [3]_ [4]_): only
  F and matches are known. Send image 2's epipole to infinity along x with a homography
  :math:`H_2` close to a rigid motion near the image centre, then choose :math:`H_1`
  compatible with F that minimises the horizontal disparity of the matches; finally shear
  (Loop & Zhang [5]_) and scale both to reduce distortion.

:func:`vertical_disparity` measures how well a pair is rectified; :func:`masked_disparity`
matches a rectified pair by SGBM with its warp border masked, and :func:`pair_warnings` says
when a hand-held pair is unfit for Hartley's method.

Conventions (docs/conventions.md): pixels (u, v) = (column, row), origin at the centre of
the top-left pixel, ``img[v, u]``; cameras are :class:`camlab.camera.Camera` with
cam_from_world poses; ``dist = (k1, k2, p1, p2, k3)``; metres; remap tables follow
``cv2.remap``: output pixel (u, v) samples the source at ``(map_u[v, u], map_v[v, u])``.
See lesson 11.

References
----------
.. [1] A. Fusiello, E. Trucco and A. Verri, 2000, "A compact algorithm for rectification
   of stereo pairs", *Machine Vision and Applications* 12(1), 16-22.
.. [2] G. Bradski and A. Kaehler, 2008, *Learning OpenCV*, chapter 12 (Bouguet's stereo
   rectification, ``cv2.stereoRectify``).
.. [3] R. I. Hartley, 1999, "Theory and practice of projective rectification",
   *International Journal of Computer Vision* 35(2), 115-127.
.. [4] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 11.12
   (image rectification), algorithm 11.9.
.. [5] C. Loop and Z. Zhang, 1999, "Computing rectifying homographies for stereo vision",
   *Proc. IEEE CVPR*, 125-131.
"""

from __future__ import annotations

from .calibrated import (
    CalibratedRectification,
    RectifiedImages,
    rectification_coverage,
    rectify_calibrated,
    rectify_images,
    rectify_points,
    unrectify_points,
)
from .dense import MaskedDisparity, masked_disparity, pair_warnings
from .measure import VerticalDisparity, vertical_disparity
from .stereo_calibration import StereoCalibration, stereo_calibrate
from .uncalibrated import UncalibratedRectification, rectify_uncalibrated

__all__ = [
    "RectifiedImages",
    "CalibratedRectification",
    "UncalibratedRectification",
    "VerticalDisparity",
    "rectify_calibrated",
    "rectify_images",
    "rectify_points",
    "unrectify_points",
    "rectification_coverage",
    "StereoCalibration",
    "rectify_uncalibrated",
    "stereo_calibrate",
    "vertical_disparity",
    "MaskedDisparity",
    "masked_disparity",
    "pair_warnings",
]
