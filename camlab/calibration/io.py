"""Save and load a calibration in OpenCV's ``cv2.FileStorage`` format (.json, .yaml, .xml)."""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from .._files import atomic_output, check_output_path
from .._validate import CamlabInputError
from .calibrate import CalibrationResult
from .refinement import PARAM_NAMES

SUFFIXES = (".json", ".yaml", ".yml", ".xml")


def save_calibration(result: CalibrationResult, path: str | os.PathLike) -> Path:
    """Write K, dist and the quality numbers with ``cv2.FileStorage`` (``.json``, ``.yaml``/``.yml`` or ``.xml``).

    OpenCV users load it with ``fs = cv2.FileStorage(path, cv2.FILE_STORAGE_READ);
    K = fs.getNode("camera_matrix").mat(); dist = fs.getNode("distortion_coefficients").mat()``.
    """
    import cv2

    if not isinstance(result, CalibrationResult):
        raise CamlabInputError(f"result: expected the CalibrationResult of calibrate_camera, got {type(result).__name__}")
    p = check_output_path(path, "path", SUFFIXES)
    with atomic_output(p) as tmp:  # the old file stays intact until the new one is complete
        _write(cv2.FileStorage(str(tmp), cv2.FILE_STORAGE_WRITE), result)
    return p


def _write(fs, result: CalibrationResult) -> None:
    try:
        fs.write("image_width", int(result.image_size[0]))
        fs.write("image_height", int(result.image_size[1]))
        fs.write("camera_matrix", np.asarray(result.K, dtype=np.float64))
        fs.write("distortion_coefficients", np.asarray(result.dist, dtype=np.float64).reshape(1, 5))
        fs.write("rms", float(result.rms))
        fs.write("n_views", int(result.n_views))
        fs.write("per_view_rms", np.asarray(result.per_view_rms, dtype=np.float64).reshape(1, -1))
        fs.write("std_intrinsics", np.array([result.std[k] for k in PARAM_NAMES], dtype=np.float64).reshape(1, -1))
        fs.write("std_names", " ".join(PARAM_NAMES))
        fs.write("rvecs", np.asarray(result.rvecs, dtype=np.float64))
        fs.write("tvecs", np.asarray(result.tvecs, dtype=np.float64))
    finally:
        fs.release()


def load_calibration(path: str | os.PathLike) -> tuple[np.ndarray, np.ndarray, tuple[int, int]]:
    """Read ``(K, dist, image_size)`` from a file written by :func:`save_calibration` (or by OpenCV
    with the same node names)."""
    import cv2

    if not isinstance(path, (str, os.PathLike)):
        raise CamlabInputError(f"path: expected a file path, got {type(path).__name__}")
    if not Path(path).is_file():
        raise CamlabInputError(f"path: no file {str(path)!r}")
    try:
        fs = cv2.FileStorage(str(path), cv2.FILE_STORAGE_READ)
    except (cv2.error, SystemError):
        raise CamlabInputError(f"path: {str(path)!r} is not a file OpenCV's FileStorage can parse; "
                               f"pass a .json/.yaml/.xml written by save_calibration or `camlab calibrate`") from None
    try:
        K = fs.getNode("camera_matrix").mat()
        dist = fs.getNode("distortion_coefficients").mat()
        size = (int(fs.getNode("image_width").real()), int(fs.getNode("image_height").real()))
    finally:
        fs.release()
    if K is None or dist is None:
        raise CamlabInputError(f"path: {str(path)!r} has no camera_matrix / distortion_coefficients nodes")
    return np.asarray(K, dtype=float), np.asarray(dist, dtype=float).ravel(), size
