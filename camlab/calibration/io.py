"""Save and load a calibration in OpenCV's ``cv2.FileStorage`` format (.json, .yaml, .xml)."""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from .._validate import CamlabInputError
from .calibrate import CalibrationResult
from .refinement import PARAM_NAMES


def save_calibration(result: CalibrationResult, path: str | os.PathLike) -> Path:
    """Write K, dist and the quality numbers with ``cv2.FileStorage`` (``.json``, ``.yaml``/``.yml`` or ``.xml``).

    OpenCV users load it with ``fs = cv2.FileStorage(path, cv2.FILE_STORAGE_READ);
    K = fs.getNode("camera_matrix").mat(); dist = fs.getNode("distortion_coefficients").mat()``.
    """
    import cv2

    p = Path(path)
    if p.suffix.lower() not in (".json", ".yaml", ".yml", ".xml"):
        raise CamlabInputError(f"path: expected a .json, .yaml, .yml or .xml file name, got {str(path)!r}")
    fs = cv2.FileStorage(str(p), cv2.FILE_STORAGE_WRITE)
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
    return p


def load_calibration(path: str | os.PathLike) -> tuple[np.ndarray, np.ndarray, tuple[int, int]]:
    """Read ``(K, dist, image_size)`` from a file written by :func:`save_calibration` (or by OpenCV
    with the same node names)."""
    import cv2

    if not Path(path).is_file():
        raise CamlabInputError(f"path: no file {str(path)!r}")
    fs = cv2.FileStorage(str(path), cv2.FILE_STORAGE_READ)
    try:
        K = fs.getNode("camera_matrix").mat()
        dist = fs.getNode("distortion_coefficients").mat()
        size = (int(fs.getNode("image_width").real()), int(fs.getNode("image_height").real()))
    finally:
        fs.release()
    if K is None or dist is None:
        raise CamlabInputError(f"path: {str(path)!r} has no camera_matrix / distortion_coefficients nodes")
    return np.asarray(K, dtype=float), np.asarray(dist, dtype=float).ravel(), size
