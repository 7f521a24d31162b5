"""camlab: camera geometry and 2-D projective geometry you can drag and see.

Conventions (full page: docs/conventions.md):

1. Points are rows: (N, 2) image points, (N, 3) world points, (N, 3)/(N, 4) homogeneous;
   a single (2,) point is accepted and the result keeps the input's rank.
2. Inputs are array_like and never modified; outputs are new float64 arrays.
3. Pixels (u, v) = (column, row), origin at the centre of the top-left pixel; img[v, u].
4. Camera frame x right, y down, z forward; X_cam = R @ X_world + t, P = K [R | t].
5. Angles in radians; lengths in metres or pixels, as each docstring says.
6. Homogeneous points with w = 0 are ideal; from_homogeneous gives NaN for them.
7. Homographies map points by H and lines by H^-T; they are compared up to scale.
8. User mistakes raise CamlabInputError (a ValueError) naming the argument and the fix.
9. Random functions take rng: np.random.Generator | None; lessons seed everything.
10. OpenCV is the reference and the workhorse, never the teaching path.

The package map (``dir(camlab)`` and tab completion show it): one module per topic, in the
order the lessons teach them, and the main function of each topic by its bare name
(``camlab.estimate_homography`` is ``camlab.homography.estimate_homography``). Topics load on
first use, so ``import camlab`` stays fast and never imports matplotlib, ipywidgets or cv2.

========================  ==================================================================
topic                     main functions
========================  ==================================================================
``pinhole`` (01)          project_pinhole, pinhole_blur, optimal_pinhole_diameter
``lens`` (02)             depth_of_field, circle_of_confusion, angle_of_view
``distortion`` (02)       distort_points, undistort_points, undistort_image
``sensor`` (03)           mosaic, demosaic_bilinear, intrinsics_from_sensor, add_noise
``camera`` (04)           Camera, intrinsic_matrix, project_points, estimate_projection_matrix,
                          decompose_projection_matrix, rq_decomposition
``affine`` (05)           affine_approximation, estimate_affine_camera
``affine_epipolar`` (05)  estimate_affine_fundamental, affine_epipolar_test
``factorization`` (05)    affine_factorization
``projective`` (06)       join, meet, vanishing_point, horizon, cross_ratio (imported eagerly)
``homography`` (07)       estimate_homography, ransac_homography, refine_homography
``warp`` (07)             warp_perspective, forward_warp
``calibration`` (08)      calibrate_camera, calibrate_from_images, find_chessboard
``stitching`` (09)        stitch, register_pair, match_graph, blend
``features`` (09)         detect_features, match_features
``perspective`` (10)      rectify_quadrilateral, estimate_aspect_ratio, find_document
``epipolar`` (11)         estimate_fundamental_matrix, ransac_fundamental_matrix,
                          essential_matrix, recover_pose, triangulate_points
``rectification`` (11)    rectify_calibrated, rectify_uncalibrated
``disparity`` (11)        block_matching_disparity, sgbm_disparity, disparity_to_depth
``measurement`` (12)      solve_pnp, measure_on_plane, area_on_plane, depth_sigma,
                          triangulate_rectified
``robust``, ``optimise``  the shared engines: ransac, levenberg_marquardt
``render``, ``scenes``    the virtual camera with ground truth, and what it photographs
``data``                  the shipped photographs and data sets, loaded (load_photo ...)
``fixtures``              the lessons' scenes, the data sets' generators, the demos' cached pipelines
``plotting``,             figures, the demos behind the lessons, the checked exercises
``widgets``,
``exercises``
========================  ==================================================================

docs/architecture.md says which module may import which, and where new code goes.
"""

from __future__ import annotations

import importlib

from . import projective
from ._validate import CamlabInputError, ConvergenceError, DegenerateError
from .projective import (
    cross_ratio,
    from_homogeneous,
    horizon,
    join,
    map_lines,
    map_points,
    meet,
    to_homogeneous,
    vanishing_point,
)

__version__ = "0.1.0"

__all__ = [
    "CamlabInputError",
    "ConvergenceError",
    "DegenerateError",
    "cross_ratio",
    "from_homogeneous",
    "horizon",
    "join",
    "map_lines",
    "map_points",
    "meet",
    "projective",
    "to_homogeneous",
    "vanishing_point",
]


# The main function(s) of each topic, importable as camlab.<name>; resolved on first access.
# One home per name: the module that defines it (tests/test_package_map.py).
_MAIN: dict[str, tuple[str, ...]] = {
    "pinhole": ("project_pinhole", "pinhole_blur", "optimal_pinhole_diameter"),
    "lens": ("depth_of_field", "circle_of_confusion", "angle_of_view"),
    "distortion": ("distort_points", "undistort_points", "undistort_image"),
    "sensor": ("mosaic", "demosaic_bilinear", "intrinsics_from_sensor", "add_noise"),
    "camera": (
        "Camera",
        "intrinsic_matrix",
        "project_points",
        "estimate_projection_matrix",
        "decompose_projection_matrix",
        "rq_decomposition",
    ),
    "affine": ("affine_approximation", "estimate_affine_camera"),
    "affine_epipolar": ("estimate_affine_fundamental", "affine_epipolar_test"),
    "factorization": ("affine_factorization",),
    "homography": ("estimate_homography", "ransac_homography", "refine_homography"),
    "warp": ("warp_perspective", "forward_warp"),
    "calibration": ("calibrate_camera", "calibrate_from_images", "find_chessboard"),
    "stitching": ("stitch", "register_pair", "match_graph", "blend"),
    "features": ("detect_features", "match_features"),
    "perspective": ("rectify_quadrilateral", "estimate_aspect_ratio", "find_document"),
    "epipolar": (
        "estimate_fundamental_matrix",
        "ransac_fundamental_matrix",
        "essential_matrix",
        "recover_pose",
        "triangulate_points",
    ),
    "rectification": ("rectify_calibrated", "rectify_uncalibrated"),
    "disparity": ("block_matching_disparity", "sgbm_disparity", "disparity_to_depth"),
    "measurement": (
        "solve_pnp",
        "measure_on_plane",
        "area_on_plane",
        "depth_sigma",
        "triangulate_rectified",
    ),
    "robust": ("ransac",),
    "optimise": ("levenberg_marquardt",),
    "data": ("load_photo",),
}
_HOME = {name: topic for topic, names in _MAIN.items() for name in names}
_TOPICS = (*_MAIN, "projective", "render", "scenes", "fixtures", "plotting", "widgets", "exercises")


def __dir__() -> list[str]:
    return sorted({*__all__, *_TOPICS, *_HOME, "__version__"})


def __getattr__(name: str):
    # camlab.<main function> and camlab.<topic>, imported on first access and then cached.
    if name.startswith("_"):
        raise AttributeError(name)
    if name in _HOME:
        value = getattr(importlib.import_module(f"{__name__}.{_HOME[name]}"), name)
        globals()[name] = value
        return value
    try:
        module = importlib.import_module(f"{__name__}.{name}")
    except ModuleNotFoundError as exc:
        if exc.name == f"{__name__}.{name}":
            raise AttributeError(f"module 'camlab' has no attribute {name!r}") from None
        raise
    globals()[name] = module
    return module
