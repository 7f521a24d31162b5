"""The chessboard calibration set of lesson 08, rendered by the virtual camera with full ground truth.

``python -m camlab.data`` rewrites it (with the other data sets) from fixed parameters
recorded beside the files:

``data/calib_chessboard/``
    ``view_00.png`` ... ``view_15.png``: a 9 x 6 inner-corner chessboard (25 mm squares)
    rendered by :mod:`camlab.render` from 16 poses through a camera with barrel distortion,
    640 x 480, 8-bit grey, with a little sensor noise; ``truth.json`` holds the generator's
    parameters and the ground truth (K, dist, each view's pose and exact corner pixels).

Load with :func:`load_calibration_set`; :func:`bundled_calibration` is its calibration, computed once.
"""

from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path
from typing import NamedTuple

import numpy as np

from ._resources import encode_image, read_only, read_truth

__all__ = [
    "CalibrationSet",
    "CALIBRATION_PARAMS",
    "bundled_calibration",
    "load_calibration_set",
    "make_calibration_set",
]

CALIBRATION_PARAMS = {
    "seed": 2026,
    "n_views": 16,
    "image_size": [640, 480],
    "K": [[820.0, 0.0, 322.4], [0.0, 818.0, 236.8], [0.0, 0.0, 1.0]],
    "dist": [-0.21, 0.09, 0.0006, -0.0004, -0.02],
    "pattern_size": [9, 6],
    "square": 0.025,
    "full_well": 40000.0,
    "read_noise": 2.0,
    "bits": 8,
    "supersample": 2,
    "min_margin_px": 25,
}


def _views(params: dict):
    """Yield ``(R, t)`` camera poses (cam_from_world) that keep the whole board in view."""
    from .. import render

    rng = np.random.default_rng(params["seed"])
    cols, rows = params["pattern_size"]
    s = params["square"]
    board = render.checkerboard((cols, rows), s)
    centre = np.array([(cols - 1) * s / 2, (rows - 1) * s / 2, 0.0])
    K, d = np.array(params["K"]), np.array(params["dist"])
    w, h = params["image_size"]
    m = params["min_margin_px"]
    found = 0
    while found < params["n_views"]:
        # the camera on a cap of directions in front of the board (the board faces -z)
        tilt = rng.uniform(0.1, 0.75)
        azimuth = rng.uniform(0, 2 * np.pi)
        dist = rng.uniform(0.32, 0.55)
        eye = centre + dist * np.array(
            [np.sin(tilt) * np.cos(azimuth), np.sin(tilt) * np.sin(azimuth), -np.cos(tilt)]
        )
        target = centre + np.append(rng.normal(0, 0.02, 2), 0.0)
        roll = rng.uniform(-0.4, 0.4)
        R, t = render.look_at(eye, target, up=(0.0, -1.0, 0.0))  # the board's frame: y down
        Rz = render.rotation_from_euler(0, 0, roll)
        R, t = Rz @ R, Rz @ t
        px = render.project(board.world_points, K, R, t, d)
        corners = render.project(board.corners_world, K, R, t, d)
        inside = np.all((px >= m) & (px <= [w - 1 - m, h - 1 - m]))
        if inside and np.all(np.isfinite(corners)):
            found += 1
            yield R, t


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


def make_calibration_set(out_dir: Path | str, params: dict = CALIBRATION_PARAMS) -> list[Path]:
    """Render the calibration set into ``out_dir``; return the files written."""
    import cv2

    from .. import render
    from ..sensor import NoiseModel

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    cols, rows = params["pattern_size"]
    board = render.checkerboard((cols, rows), params["square"])
    K, d = np.array(params["K"]), np.array(params["dist"])
    sensor = render.Sensor(
        bits=params["bits"], noise=NoiseModel(params["full_well"], params["read_noise"])
    )
    rng = np.random.default_rng(params["seed"] + 1)
    views, files = [], []
    for i, (R, t) in enumerate(_views(params)):
        res = render.render(
            board,
            K,
            tuple(params["image_size"]),
            R=R,
            t=t,
            dist=d,
            sensor=sensor,
            supersample=params["supersample"],
            rng=rng,
        )
        name = f"view_{i:02d}.png"
        (out / name).write_bytes(encode_image(res.image, ".png", (cv2.IMWRITE_PNG_COMPRESSION, 9)))
        files.append(out / name)
        rvec = cv2.Rodrigues(R)[0].ravel()
        views.append(
            {
                "file": name,
                "R": np.round(R, 12).tolist(),
                "t": np.round(t, 12).tolist(),
                "rvec": np.round(rvec, 12).tolist(),
                "corners": np.round(res.truth.corners(), 9).tolist(),
            }
        )
    truth = {
        "description": "Chessboard calibration set rendered by camlab.render; regenerate with `python -m camlab.data`.",
        "generator": "camlab.data.make_calibration_set",
        "params": params,
        "conventions": "pixels (u, v) = (column, row), origin at the centre of the top-left pixel; "
        "X_cam = R X_board + t; dist = (k1, k2, p1, p2, k3); corners in cv2.findChessboardCorners order",
        "K": params["K"],
        "dist": params["dist"],
        "image_size": params["image_size"],
        "pattern_size": params["pattern_size"],
        "square": params["square"],
        "object_points": np.round(board.object_points, 12).tolist(),
        "views": views,
    }
    (out / "truth.json").write_text(json.dumps(truth, indent=1) + "\n")
    files.append(out / "truth.json")
    return files


def load_calibration_set(directory: Path | str | None = None) -> CalibrationSet:
    """Load ``data/calib_chessboard`` (or ``directory``) as a :class:`CalibrationSet`."""
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


@lru_cache(maxsize=1)
def bundled_calibration():
    """:func:`camlab.calibration.calibrate_from_images` of the bundled set (detected corners), computed once.

    Lesson 08's ``view_inspector`` shows it. All its arrays are read-only: the result is
    shared by every caller.
    """
    from ..calibration import calibrate_from_images

    cs = load_calibration_set()
    return read_only(calibrate_from_images(cs.images, cs.pattern_size, cs.square))
