"""A generated battery of bad inputs over camlab's public functions.

For each function a *baseline* call with valid arguments is listed below (``BASELINES``).
The battery checks the baseline runs, then replaces one argument at a time with values
generated from the baseline value's kind (points, matrix, image, scalar, size, text, path,
object): wrong shapes, transposes, NaN and inf, strings, None, empty arrays, zero, negative
and fractional sizes, singular matrices, object-dtype images, unwritable paths. Every case
must end in a ``CamlabInputError`` (or ``DegenerateError``) whose message names the
argument; anything else is classified as

* ``bare``: another exception (a traceback from numpy, OpenCV or Python);
* ``vague``: a camlab error whose message does not name the argument;
* ``silent``: no error at all (a wrong answer returned without a word).

Some generated values are legitimate for some arguments (``inf`` as a focus distance,
``-1`` as a coordinate); those are listed in ``ALLOWED_RULES`` with the reason, and
must then work. Degenerate
geometry that cannot be generated from a value's kind (zero baseline, points behind the
camera, all-wrong matches...) is tested beside each estimator (``tests/test_epipolar.py``, ``tests/test_rectification.py``) and fuzzed by ``tests/test_fuzz_estimators.py``.

Run ``python tests/test_battery.py`` for the counts by outcome.
"""

from __future__ import annotations

import collections
import importlib
import os
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from camlab._validate import CamlabInputError

# --------------------------------------------------------------------------- valid values

RNG = np.random.default_rng(0)
K = np.array([[800.0, 0, 320], [0, 800, 240], [0, 0, 1]])
R = np.array(
    [[0.9950042, 0.0, 0.0998334], [0.0, 1.0, 0.0], [-0.0998334, 0.0, 0.9950042]]
)  # 0.1 rad about y
T = np.array([0.1, -0.05, 2.0])
DIST = np.array([-0.1, 0.01, 0.001, -0.001, 0.0])
H = np.array([[1.1, 0.05, 30.0], [-0.03, 0.95, -20.0], [2e-4, -1e-4, 1.0]])
X3 = RNG.uniform([-0.5, -0.5, 1.5], [0.5, 0.5, 2.5], (20, 3))
UV = RNG.uniform([50, 50], [590, 430], (20, 2))
IMG = RNG.integers(0, 256, (60, 80, 3), dtype=np.uint8)
GRAY = RNG.integers(0, 256, (60, 80), dtype=np.uint8)


def _lazy() -> dict[str, Any]:
    """Values that need camlab itself (built once, on first use)."""
    from camlab.camera import Camera
    from camlab.epipolar import essential_matrix, fundamental_from_cameras
    from camlab.features import detect_features
    from camlab.projective import map_points

    cam1 = Camera(K, np.eye(3), np.zeros(3), image_size=(640, 480))
    cam2 = Camera(K, R, np.array([-0.2, 0.0, 0.0]), image_size=(640, 480))
    X = RNG.uniform([-0.5, -0.5, 2.0], [0.5, 0.5, 4.0], (30, 3))
    board = np.array([[i * 0.03, j * 0.03, 0.0] for j in range(6) for i in range(9)])
    return {
        "cam1": cam1,
        "cam2": cam2,
        "X": X,
        "x1": cam1.project(X),
        "x2": cam2.project(X),
        "F": fundamental_from_cameras(cam1, cam2),
        "E": essential_matrix(R, np.array([-0.2, 0.0, 0.0])),
        "src": UV,
        "dst": map_points(H, UV),
        "board": board,
        "feat": detect_features(_textured()),
    }


def _textured() -> np.ndarray:
    y, x = np.mgrid[0:120, 0:160]
    return ((np.sin(x / 3.0) * np.cos(y / 5.0) * 0.5 + 0.5) * 255).astype(np.uint8)


# Baselines: "module.function": kwargs (a callable taking the lazy values for those that need them).
BASELINES: dict[str, Callable[[dict], dict]] = {
    # projective
    "projective.to_homogeneous": lambda v: {"points": UV},
    "projective.from_homogeneous": lambda v: {"points_h": np.c_[UV, np.ones(20)]},
    "projective.join": lambda v: {"p": [0.0, 0, 1], "q": [1.0, 1, 1]},
    "projective.meet": lambda v: {"l": [1.0, 0, -1], "m": [0.0, 1, -2]},
    "projective.map_points": lambda v: {"H": H, "points": UV},
    "projective.map_lines": lambda v: {"H": H, "lines": [[1.0, 0, -1]]},
    "projective.cross_ratio": lambda v: {"points": [[0.0, 0], [1, 1], [2, 2], [4, 4]]},
    "projective.vanishing_point": lambda v: {
        "segments": [[[0.0, 0], [10, 1]], [[0, 10], [10, 10.5]]]
    },
    "projective.horizon": lambda v: {"vp1": [1000.0, 100, 1], "vp2": [-800.0, 120, 1]},
    "projective.ideal_point": lambda v: {"direction": [1.0, 2.0]},
    "projective.point_line_distance": lambda v: {"points": UV, "line": [1.0, 1, -300]},
    "projective.clip_line": lambda v: {"line": [1.0, 1, -300], "xlim": (0, 640), "ylim": (0, 480)},
    # camera
    "camera.intrinsic_matrix": lambda v: {"fx": 800.0, "fy": 800.0, "cx": 320.0, "cy": 240.0},
    "camera.rotation_from_axis_angle": lambda v: {"rvec": [0.1, 0.2, 0.3]},
    "camera.axis_angle_from_rotation": lambda v: {"R": R},
    "camera.euler_from_rotation": lambda v: {"R": R},
    "camera.rotation_x": lambda v: {"angle": 0.3},
    "camera.look_at_rotation": lambda v: {"eye": [0.0, -3, 1], "target": [0.0, 0, 0]},
    "camera.project_points": lambda v: {"P": K @ np.c_[R, T], "points_world": X3},
    "camera.camera_centre": lambda v: {"P": K @ np.c_[R, T]},
    "camera.decompose_projection_matrix": lambda v: {"P": K @ np.c_[R, T]},
    "camera.rq_decomposition": lambda v: {"M": K @ R},
    "camera.estimate_projection_matrix": lambda v: {
        "points_world": v["X"],
        "points_image": v["x2"],
    },
    "camera.reprojection_errors": lambda v: {
        "P": v["cam2"].P,
        "points_world": v["X"],
        "points_image": v["x2"],
    },
    "camera.opengl_from_opencv": lambda v: {"R": R, "t": T},
    "camera.project_segments": lambda v: {
        "camera": v["cam1"],
        "segments": [[[0.0, 0, 2], [0.1, 0, 2]]],
    },
    "camera.orbit_eye": lambda v: {
        "azimuth": 0.3,
        "elevation": 0.2,
        "distance": 4.0,
        "target": [0.0, 0, 0.5],
    },
    # affine
    "affine.orthographic_matrix": lambda v: {"R": R, "t": T},
    "affine.weak_perspective_matrix": lambda v: {"R": R, "t": T, "ax": 400.0, "ay": 400.0},
    "affine.affine_approximation": lambda v: {"camera": v["cam2"], "reference_point": [0.0, 0, 3]},
    "affine.paraperspective_approximation": lambda v: {
        "camera": v["cam2"],
        "reference_point": [0.0, 0, 3],
    },
    "affine.dolly_zoom_camera": lambda v: {
        "distance": 6.0,
        "azimuth": -0.7,
        "elevation": 0.35,
        "target": [0.0, 0, 0.5],
    },
    "affine.dolly_zoom_errors": lambda v: {
        "points_world": X3,
        "distances": [4.0, 8.0],
        "azimuth": -0.7,
        "elevation": 0.35,
        "target": [0.0, 0, 0.5],
    },
    "affine.three_images": lambda v: {
        "camera": v["cam1"],
        "segments": [[[0.0, 0, 2], [0.1, 0, 2]], [[0.0, 0.1, 2.2], [0.1, 0.1, 2.2]]],
    },
    "affine.estimate_affine_camera": lambda v: {"points_world": v["X"], "points_image": v["x1"]},
    "affine.dolly_zoom_focal": lambda v: {"f0": 0.05, "d0": 2.0, "d": 3.0},
    "affine.weak_perspective_error": lambda v: {"camera": v["cam1"], "points_world": v["X"]},
    # homography
    "homography.estimate_homography": lambda v: {"src": v["src"], "dst": v["dst"]},
    "homography.ransac_homography": lambda v: {
        "src": v["src"],
        "dst": v["dst"],
        "threshold": 3.0,
        "max_iters": 200,
        "rng": 0,
    },
    "homography.refine_homography": lambda v: {"H": H, "src": v["src"], "dst": v["dst"]},
    "homography.transfer_error": lambda v: {"H": H, "src": v["src"], "dst": v["dst"]},
    "homography.symmetric_transfer_error": lambda v: {"H": H, "src": v["src"], "dst": v["dst"]},
    "homography.sampson_distance": lambda v: {"H": H, "src": v["src"], "dst": v["dst"]},
    "projective.hartley_normalise": lambda v: {"points": UV},
    "homography.invert": lambda v: {"H": H},
    "homography.normalise_homography": lambda v: {"H": H},
    "homography.decompose_homography": lambda v: {"H": H},
    "homography.classify": lambda v: {"H": H},
    "homography.similarity_homography": lambda v: {"scale": 2.0, "theta": 0.1},
    "homography.rotation_homography": lambda v: {"K": K, "R": R},
    "homography.pose_homography": lambda v: {"K": K, "R": R, "t": T},
    "homography.plane_homography": lambda v: {"K": K, "R": R, "t": T, "n": [0.0, 0, 1], "d": 2.0},
    # epipolar
    "epipolar.estimate_fundamental_matrix": lambda v: {"x1": v["x1"], "x2": v["x2"]},
    "epipolar.ransac_fundamental_matrix": lambda v: {
        "x1": v["x1"],
        "x2": v["x2"],
        "threshold": 1.0,
        "rng": 0,
    },
    "epipolar.epipolar_lines": lambda v: {"F": v["F"], "points": v["x1"]},
    "epipolar.epipoles": lambda v: {"F": v["F"]},
    "epipolar.sampson_distance": lambda v: {"F": v["F"], "x1": v["x1"], "x2": v["x2"]},
    "epipolar.epipolar_distance": lambda v: {"F": v["F"], "x1": v["x1"], "x2": v["x2"]},
    "epipolar.essential_matrix": lambda v: {"R": R, "t": [-0.2, 0.0, 0.0]},
    "epipolar.essential_from_fundamental": lambda v: {"F": v["F"], "K1": K},
    "epipolar.fundamental_from_essential": lambda v: {"E": v["E"], "K1": K},
    "epipolar.decompose_essential_matrix": lambda v: {"E": v["E"]},
    "epipolar.recover_pose": lambda v: {"E": v["E"], "x1": v["x1"], "x2": v["x2"], "K1": K},
    "epipolar.triangulate_points": lambda v: {
        "P1": v["cam1"].P,
        "P2": v["cam2"].P,
        "x1": v["x1"],
        "x2": v["x2"],
    },
    "epipolar.skew": lambda v: {"v": [1.0, 2, 3]},
    "epipolar.normalise_fundamental": lambda v: {"F": v["F"]},
    # distortion
    "distortion.distort_points": lambda v: {"points": UV / 1000, "dist": DIST},
    "distortion.undistort_points": lambda v: {"points": UV / 1000, "dist": DIST},
    "distortion.distort_pixels": lambda v: {"pixels": UV, "K": K, "dist": DIST},
    "distortion.undistort_pixels": lambda v: {"pixels": UV, "K": K, "dist": DIST},
    "distortion.undistort_map": lambda v: {"K": K, "dist": DIST, "size": (80, 60)},
    "distortion.undistort_image": lambda v: {
        "image": IMG,
        "K": K / 8 + np.diag([0, 0, 7 / 8]),
        "dist": DIST,
    },
    "distortion.max_valid_radius": lambda v: {"dist": DIST},
    "distortion.radial_scale": lambda v: {"r": [0.1, 0.2], "dist": DIST},
    # lens, pinhole, sensor
    "lens.image_distance": lambda v: {"focal_length": 0.05, "object_distance": 2.0},
    "lens.aperture_diameter": lambda v: {"focal_length": 0.05, "f_number": 2.8},
    "lens.hyperfocal_distance": lambda v: {"focal_length": 0.05, "f_number": 2.8, "coc": 3e-5},
    "lens.angle_of_view": lambda v: {
        "focal_length": 0.05,
        "sensor_size": 0.036,
        "focus_distance": 0.5,
    },
    "lens.aperture_for_depth_of_field": lambda v: {
        "focal_length": 0.05,
        "coc": 3e-5,
        "near": 2.0,
        "far": 4.0,
    },
    "lens.depth_of_field": lambda v: {
        "focal_length": 0.05,
        "f_number": 2.8,
        "focus_distance": 3.0,
        "coc": 3e-5,
    },
    "lens.circle_of_confusion": lambda v: {
        "focal_length": 0.05,
        "f_number": 2.8,
        "focus_distance": 3.0,
        "depth": 4.0,
    },
    "pinhole.project_pinhole": lambda v: {"points": X3, "focal_length": 0.05},
    "pinhole.pinhole_blur": lambda v: {"diameter": 3e-4, "focal_length": 0.05},
    "pinhole.optimal_pinhole_diameter": lambda v: {"focal_length": 0.05},
    "sensor.intrinsics_from_sensor": lambda v: {
        "focal_length": 0.005,
        "pitch": (2e-6, 2e-6),
        "size": (640, 480),
    },
    "sensor.metric_to_pixels": lambda v: {
        "points": UV * 1e-6,
        "pitch": (2e-6, 2e-6),
        "principal_point": (320, 240),
    },
    "sensor.pixels_to_metric": lambda v: {
        "pixels": UV,
        "pitch": (2e-6, 2e-6),
        "principal_point": (320, 240),
    },
    "sensor.quantise": lambda v: {"image": IMG / 255.0, "bits": 8},
    "sensor.dequantise": lambda v: {"dn": IMG, "bits": 8},
    "sensor.psnr": lambda v: {"reference": IMG, "test": IMG // 2 * 2},
    "sensor.sample": lambda v: {"image": IMG / 255.0, "factor": 2},
    "sensor.mosaic": lambda v: {"rgb": IMG / 255.0},
    "sensor.demosaic_bilinear": lambda v: {"raw": GRAY / 255.0},
    "sensor.add_noise": lambda v: {"image": IMG / 255.0, "rng": 0},
    "sensor.bayer_masks": lambda v: {"shape": (60, 80)},
    # calibration
    "calibration.parse_pattern": lambda v: {"pattern": "9x6"},
    "calibration.board_points": lambda v: {"pattern_size": (9, 6), "square_size": 0.025},
    "camera.nearest_rotation": lambda v: {"M": R * 1.01},
    "calibration.find_chessboard": lambda v: {"image": GRAY, "pattern_size": (9, 6)},
    "calibration.extrinsics_from_homography": lambda v: {"K": K, "H": K @ np.c_[R[:, :2], T]},
    "calibration.zhang_v": lambda v: {"H": H, "i": 0, "j": 1},
    "calibration.reproject": lambda v: {
        "object_points": v["board"],
        "K": K,
        "dist": DIST,
        "rvec": [0.1, 0, 0],
        "tvec": [0.0, 0, 1],
    },
    "calibration.optimal_new_camera_matrix": lambda v: {
        "K": K,
        "dist": DIST,
        "image_size": (640, 480),
        "alpha": 0.0,
    },
    "calibration.load_calibration": lambda v: {"path": _calibration_file()},
    "calibration.save_calibration": lambda v: {
        "result": _calibration_result(),
        "path": os.path.join(tempfile.mkdtemp(), "c.json"),
    },
    "calibration.calibrate_camera": lambda v: _calibration_views(),
    # features, stitching, warp
    "features.to_gray_uint8": lambda v: {"image": IMG},
    "features.detect_features": lambda v: {"image": _textured(), "max_features": 100},
    "features.match_features": lambda v: {
        "features1": v["feat"],
        "features2": v["feat"],
        "ratio": 0.8,
    },
    "stitching.laplacian_blend": lambda v: {
        "images": [IMG / 255.0, IMG / 255.0],
        "masks": [np.ones((60, 80), bool), np.zeros((60, 80), bool)],
        "levels": 3,
    },
    "stitching.feather_weights": lambda v: {"shape": (60, 80)},
    "warp.warp_perspective": lambda v: {"image": IMG, "H": H, "output_shape": (60, 80)},
    "warp.forward_warp": lambda v: {"image": IMG, "H": H, "output_shape": (60, 80)},
    # perspective, rectification, disparity
    "perspective.order_corners": lambda v: {
        "corners": [[10.0, 10], [200, 20], [210, 150], [5, 160]]
    },
    "perspective.estimate_aspect_ratio": lambda v: {
        "corners": [[10.0, 10], [200, 20], [210, 150], [5, 160]],
        "image_shape": (240, 320),
    },
    "perspective.rectangle_homography": lambda v: {
        "corners": [[10.0, 10], [200, 20], [210, 150], [5, 160]],
        "size": (100, 80),
    },
    "perspective.rectify_quadrilateral": lambda v: {
        "image": IMG,
        "corners": [[5.0, 5], [70, 6], [72, 50], [4, 55]],
    },
    "perspective.find_document": lambda v: {"image": _document()},
    "rectification.rectify_calibrated": lambda v: {"camera1": v["cam1"], "camera2": v["cam2"]},
    "rectification.rectify_uncalibrated": lambda v: {
        "x1": v["x1"],
        "x2": v["x2"],
        "F": v["F"],
        "image_size": (640, 480),
    },
    "rectification.vertical_disparity": lambda v: {"x1": v["x1"], "x2": v["x2"]},
    "disparity.disparity_to_depth": lambda v: {
        "disparity": np.full((4, 4), 8.0),
        "focal_length": 800.0,
        "baseline": 0.1,
    },
    "disparity.block_matching_disparity": lambda v: {
        "left": GRAY,
        "right": GRAY,
        "max_disparity": 16,
        "block_size": 5,
    },
}

# Generated values that are legitimate for some arguments: (functions, arguments, cases, reason).
# Each rule says why the value is not a mistake there; everything else must fail clearly.
ALLOWED_RULES: list[tuple[set[str], set[str], set[str], str]] = [
    (
        {"projective.join", "projective.horizon"},
        {"p", "q", "vp1", "vp2"},
        {"one short"},
        "a (2,) point is a Euclidean point",
    ),
    (
        {"camera.project_points", "camera.reprojection_errors", "camera.project_segments"},
        {"points_world", "segments"},
        {"NaN entry", "inf entry"},
        "projection works point by point: a NaN point gives a NaN pixel, the others are unaffected",
    ),
    (
        {
            "homography.pose_homography",
            "homography.plane_homography",
            "epipolar.essential_matrix",
            "calibration.reproject",
        },
        {"t", "n", "rvec", "tvec"},
        {"extra axis"},
        "3-vectors are accepted in any shape with 3 entries, like OpenCV's (3, 1) rvec and tvec",
    ),
    ({"homography.plane_homography"}, {"d"}, {"negative"}, "the plane offset d has a sign"),
    (
        {
            "distortion.distort_points",
            "distortion.undistort_points",
            "distortion.distort_pixels",
            "distortion.undistort_pixels",
            "distortion.undistort_map",
            "distortion.undistort_image",
            "distortion.max_valid_radius",
            "distortion.radial_scale",
            "calibration.reproject",
            "calibration.optimal_new_camera_matrix",
        },
        {"dist"},
        {"None", "one short", "extra axis"},
        "None means no distortion; 4 coefficients (k1, k2, p1, p2) are OpenCV's short form, in any shape",
    ),
    (
        {
            "distortion.radial_scale",
            "lens.image_distance",
            "lens.circle_of_confusion",
            "pinhole.pinhole_blur",
        },
        {"r", "object_distance", "depth", "diameter"},
        {"empty", "extra axis", "one short", "list"},
        "element-wise over an array of any shape (curves for plots)",
    ),
    (
        {"affine.dolly_zoom_errors"},
        {"distances"},
        {"one short"},
        "any number of distances (one value each)",
    ),
    ({"lens.angle_of_view"}, {"focus_distance"}, {"inf"}, "focused at infinity: the default"),
    (
        {"sensor.intrinsics_from_sensor", "sensor.metric_to_pixels", "sensor.pixels_to_metric"},
        {"pitch", "principal_point"},
        {"fractional size"},
        "a pitch (metres) and a principal point (pixels) are real numbers",
    ),
    (
        {"sensor.metric_to_pixels", "sensor.pixels_to_metric"},
        {"principal_point"},
        {"zero size", "negative size"},
        "a principal point may lie anywhere, even outside the image",
    ),
    (
        {"sensor.quantise", "sensor.dequantise", "disparity.disparity_to_depth"},
        {"image", "dn", "disparity"},
        {"empty", "extra axis", "1-D", "4-D", "wrong shape"},
        "element-wise over an array of any shape",
    ),
    (
        {"disparity.disparity_to_depth"},
        {"disparity"},
        {"NaN entry", "inf entry", "zeros"},
        "NaN and 0 mean 'no match' in a disparity map and give NaN depth (documented)",
    ),
    ({"sensor.demosaic_bilinear"}, {"raw"}, {"transposed"}, "a transposed image is still an image"),
    (
        {"calibration.board_points", "calibration.find_chessboard"},
        {"pattern_size"},
        {"text size"},
        "'9x6' is the documented string form of the pattern",
    ),
    (
        {"calibration.save_calibration"},
        {"path"},
        {"text file"},
        "saving replaces an existing file (atomically)",
    ),
    (
        {"rectification.vertical_disparity"},
        {"x1", "x2"},
        {"NaN entry", "inf entry"},
        "pairs that left the rectified image (NaN) are skipped by design",
    ),
]


def allowed(qualname: str, name: str, label: str) -> str | None:
    """The reason a generated value is legitimate here, or None if it must fail clearly."""
    for functions, names, labels, reason in ALLOWED_RULES:
        if qualname in functions and name in names and label in labels:
            return reason
    return None


# Names of arguments that must be strictly positive (zero and negative values are bad input).
POSITIVE = {
    "focal_length",
    "f_number",
    "coc",
    "object_distance",
    "focus_distance",
    "depth",
    "diameter",
    "threshold",
    "max_iters",
    "square_size",
    "scale",
    "ax",
    "ay",
    "f0",
    "d0",
    "d",
    "fx",
    "fy",
    "bits",
    "factor",
    "levels",
    "max_features",
    "ratio",
    "width",
    "height",
    "baseline",
    "max_disparity",
    "block_size",
    "peak",
    "sensor_size",
    "near",
    "far",
}
SIZES = {
    "size",
    "image_size",
    "pattern_size",
    "shape",
    "output_shape",
    "pitch",
    "principal_point",
    "image_shape",
}
PATHS = {"path"}


def _calibration_views() -> dict:
    from camlab.calibration import make_synthetic_views

    views = make_synthetic_views()
    return {
        "object_points": views.object_points,
        "image_points": views.image_points,
        "image_size": views.image_size,
    }


def _calibration_result():
    from camlab.calibration import calibrate_camera

    return calibrate_camera(**_calibration_views())


def _calibration_file() -> str:
    from camlab.calibration import save_calibration

    return str(save_calibration(_calibration_result(), os.path.join(tempfile.mkdtemp(), "c.json")))


def _document() -> np.ndarray:
    img = np.full((120, 160, 3), 40, np.uint8)
    img[20:100, 40:120] = 230
    return img


# --------------------------------------------------------------------------- generated bad values


def bad_values(name: str, value: Any) -> list[tuple[str, Any]]:
    """Bad replacements for one argument, generated from its name and its valid value's kind."""
    cases: list[tuple[str, Any]] = [("None", None), ("string", "abc")]
    if name in PATHS:
        return [
            ("None", None),
            ("directory", tempfile.gettempdir()),
            ("unwritable", "/proc/camlab-no-such-dir/out.json"),
            ("missing", "/nonexistent/c.json"),
            ("text file", _text_file()),
        ]
    if name in SIZES:
        w = value[0] if len(value) else 1
        cases += [
            ("zero size", (0, value[1])),
            ("negative size", (-w, value[1])),
            ("fractional size", (w + 0.5, value[1])),
            ("scalar size", w),
            ("NaN size", (np.nan, value[1])),
            ("text size", f"{value[0]}x{value[1]}"),
        ]
        return cases
    if isinstance(value, str):
        return [
            ("None", None),
            ("number", 3),
            ("unknown text", "9.5x6" if name == "pattern" else "no-such-option"),
        ]
    if isinstance(value, (bool, np.bool_)):
        return cases
    if isinstance(value, (int, float, np.integer, np.floating)):
        cases += [("NaN", np.nan), ("inf", np.inf), ("list", [value, value])]
        if name in POSITIVE:
            cases += [("zero", 0), ("negative", -abs(value) - 1)]
        if isinstance(value, (int, np.integer)) and name in POSITIVE:
            cases += [("fractional", value + 0.5)]
        return cases
    if (
        isinstance(value, list)
        and value
        and all(isinstance(a, np.ndarray) and a.ndim == 2 for a in value)
    ):
        return cases + [
            ("empty list", []),
            ("transposed views", [a.T for a in value]),
            ("NaN in a view", [_with(value[0], np.nan)] + list(value[1:])),
            ("one view", value[:1]),
        ]
    arr = np.asarray(value) if not _is_object(value) else None
    if arr is None:
        return cases + [("number", 3.0)]
    if arr.dtype.kind in "ui" and arr.ndim >= 2:  # an image
        return cases + [
            ("object dtype", arr.astype(object)),
            ("1-D", arr.ravel()),
            ("empty", arr[:0]),
            ("4-D", arr[None]),
            ("complex", arr.astype(complex)),
        ]
    if arr.dtype == object or arr.size == 0:
        return cases
    cases += [
        ("NaN entry", _with(arr, np.nan)),
        ("inf entry", _with(arr, np.inf)),
        ("empty", arr.reshape(-1)[:0]),
        ("extra axis", arr[None, None]),
    ]
    if arr.ndim == 2 and arr.shape[0] != arr.shape[1]:
        cases.append(("transposed", arr.T))
    if arr.ndim == 2 and arr.shape[0] == arr.shape[1]:
        cases += [("zeros", np.zeros_like(arr, dtype=float)), ("wrong shape", arr[:-1, :-1])]
    if arr.ndim == 1:
        cases.append(("one short", arr[:-1]))
    return cases


def _is_object(value: Any) -> bool:
    """Not a plain numeric array (a Camera, a NamedTuple of results, a list of images...)."""
    if isinstance(value, tuple) and hasattr(value, "_fields"):
        return True
    if not isinstance(value, (np.ndarray, list, tuple)):
        return True
    try:
        return np.asarray(value).dtype == object
    except ValueError:  # ragged
        return True


def _with(arr: np.ndarray, x: float) -> np.ndarray:
    out = np.array(arr, dtype=float)
    out.reshape(-1)[0] = x
    return out


def _text_file() -> str:
    path = Path(tempfile.mkdtemp()) / "notes.json"
    path.write_text("this is not a calibration\n")
    return str(path)


# --------------------------------------------------------------------------- running and classifying

_LAZY: dict[str, Any] = {}


def lazy() -> dict[str, Any]:
    if not _LAZY:
        _LAZY.update(_lazy())
    return _LAZY


def resolve(qualname: str) -> Callable:
    module, name = qualname.rsplit(".", 1)
    return getattr(importlib.import_module(f"camlab.{module}"), name)


def classify(fn: Callable, kwargs: dict, name: str) -> tuple[str, str]:
    """Run one case: ("clear" | "vague" | "bare" | "silent", detail)."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            fn(**kwargs)
        except CamlabInputError as exc:
            return ("clear" if name in str(exc) else "vague"), str(exc)[:200]
        except Exception as exc:  # noqa: BLE001 - classifying every failure is the point
            return "bare", f"{type(exc).__name__}: {str(exc)[:200]}"
    return "silent", "returned without an error"


def cases() -> list[tuple[str, str, str]]:
    out = []
    for qualname, make in BASELINES.items():
        for name, value in make(lazy()).items():
            if name == "rng":
                continue
            for label, _ in bad_values(name, value):
                out.append((qualname, name, label))
    return out


def run_case(qualname: str, name: str, label: str) -> tuple[str, str]:
    kwargs = BASELINES[qualname](lazy())
    bad = dict(bad_values(name, kwargs[name]))[label]
    return classify(resolve(qualname), {**kwargs, name: bad}, name)


@pytest.mark.parametrize("qualname", list(BASELINES))
def test_every_baseline_works(qualname):
    resolve(qualname)(**BASELINES[qualname](lazy()))


@pytest.mark.parametrize("qualname, name, label", cases() if "pytest" in sys.modules else [])
def test_bad_input_gives_a_clear_error(qualname, name, label):
    reason = allowed(qualname, name, label)
    outcome, detail = run_case(qualname, name, label)
    if reason is not None:
        # Legitimate here: it must work (no exception), or the rule is stale.
        assert outcome == "silent", (
            f"{qualname}({name}={label}) is allowed ({reason}) but gave {outcome}: {detail}"
        )
        return
    assert outcome == "clear", f"{qualname}({name}={label}): {outcome}: {detail}"


def main() -> int:
    counts: collections.Counter = collections.Counter()
    rows = []
    for qualname, name, label in cases():
        outcome, detail = run_case(qualname, name, label)
        if outcome == "silent" and allowed(qualname, name, label):
            outcome, detail = "allowed", allowed(qualname, name, label)
        counts[outcome] += 1
        if outcome != "clear":
            rows.append(f"{outcome:7s} {qualname}({name}={label}): {detail}")
    print("\n".join(rows))
    print(
        f"\n{sum(counts.values())} cases over {len(BASELINES)} functions: "
        + ", ".join(f"{k} {v}" for k, v in counts.most_common())
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
