r"""The virtual camera: render scenes of textured planes with exact ground truth.

Every later lesson needs images whose true camera is known. :func:`render` draws a
scene made of flat textured rectangles (:class:`camlab.scenes.Plane`: checkerboards, photographs,
a text page, the faces of boxes; :mod:`camlab.scenes` builds them) through

1. pinhole projection with intrinsics ``K`` and pose ``(R, t)`` (``X_cam = R X_world + t``),
2. Brown-Conrady lens distortion ``dist = (k1, k2, p1, p2, k3)`` (:mod:`camlab.distortion`),
3. optional defocus from the thin lens' circle of confusion (:mod:`camlab.lens`),
4. the sensor: box-filtered (anti-aliased) pixels, shot and read noise, quantisation and
   an optional Bayer mosaic (:mod:`camlab.sensor`),

and returns the image with its :class:`GroundTruth`: K, dist, pose, image size, the exact
pixel position of every named plane point (all checkerboard inner corners, in OpenCV's
order) and a depth map.

Conventions: pixels (u, v) = (column, row), origin at the centre of the top-left pixel,
``img[v, u]``; camera frame x right, y down, z forward; metres. A plane's own frame has its
x axis along texture columns, y along texture rows and z = x cross y; for a checkerboard
its origin is the first inner corner, so ``board.object_points`` are the
``(i * square, j * square, 0)`` points ``cv2.calibrateCamera`` expects.

How it works (one pass per plane, all with cv2): the texture -> image map of a plane is
the homography :math:`H = K [r_1\ r_2\ t] S` (S maps texels to plane metres); each plane is
warped into an ideal (undistorted) canvas at ``supersample`` times the output resolution,
composited far to near with its anti-aliased coverage, blurred by its circle of
confusion (one disc per plane, at the depth of its centre), remapped through the inverse
distortion (:func:`camlab.distortion.distort_map`) and box-filtered down to the sensor.
Textures are pre-filtered (halved until a texel covers about one canvas pixel) so
photographs do not alias. Ground-truth corners are computed analytically by projecting
the points, never measured on the image.

See lesson 02, section 4, and docs/conventions.md.
"""

from __future__ import annotations

from .model import (
    Defocus,
    GroundTruth,
    PlanePoints,
    RenderResult,
    Sensor,
    align_detected_corners,
    look_at,
    project,
)
from .view import render

__all__ = [
    "Defocus",
    "GroundTruth",
    "align_detected_corners",
    "PlanePoints",
    "RenderResult",
    "Sensor",
    "look_at",
    "project",
    "render",
]
