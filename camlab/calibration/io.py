"""Save and load a calibration in OpenCV's ``cv2.FileStorage`` format (.json, .yaml, .xml)."""

from __future__ import annotations

import os
from pathlib import Path
from typing import NamedTuple

import numpy as np

from .._files import atomic_output, check_output_path
from .._validate import CamlabInputError
from .calibrate import CalibrationResult
from .refinement import PARAM_NAMES

SUFFIXES = (".json", ".yaml", ".yml", ".xml")


def save_calibration(
    result: CalibrationResult, path: str | os.PathLike, *, name: str = "path"
) -> Path:
    """Write K, dist and the quality numbers with ``cv2.FileStorage`` (``.json``, ``.yaml``/``.yml`` or ``.xml``).

    OpenCV users load it with ``fs = cv2.FileStorage(path, cv2.FILE_STORAGE_READ);
    K = fs.getNode("camera_matrix").mat(); dist = fs.getNode("distortion_coefficients").mat()``.
    The file is read back before it replaces an old one (OpenCV writes a short or empty
    file on a full disk without an error).

    Parameters
    ----------
    result : CalibrationResult
        From :func:`calibrate_camera`: its image size, K, dist, rms, per-view rms, standard
        deviations and poses are written.
    path : str or os.PathLike
        The file; its suffix (.json, .yaml, .yml, .xml) picks the format.
    name : str
        The argument named in errors.

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    CamlabInputError
        ``result`` not a :class:`CalibrationResult`, a path that cannot be written or has
        another suffix, or a file that does not read back.
    """
    import cv2

    if not isinstance(result, CalibrationResult):
        raise CamlabInputError(
            f"result: expected the CalibrationResult of calibrate_camera, got {type(result).__name__}"
        )
    p = check_output_path(path, name, SUFFIXES)
    with atomic_output(
        p, name, verify=_reads_back
    ) as tmp:  # the old file stays intact until the new one is checked
        _write(cv2.FileStorage(str(tmp), cv2.FILE_STORAGE_WRITE), result)
    return p


def _reads_back(path: Path) -> str | None:
    """None if ``path`` loads as a calibration, else why not (for :func:`atomic_output`)."""
    try:
        load_calibration(path)
    except CamlabInputError:
        return "the file written does not read back as a calibration (a full disk?)"
    return None


def _write(fs, result: CalibrationResult) -> None:
    try:
        fs.write("image_width", int(result.image_size[0]))
        fs.write("image_height", int(result.image_size[1]))
        fs.write("camera_matrix", np.asarray(result.K, dtype=np.float64))
        fs.write("distortion_coefficients", np.asarray(result.dist, dtype=np.float64).reshape(1, 5))
        fs.write("rms", float(result.rms))
        fs.write("n_views", int(result.n_views))
        fs.write("per_view_rms", np.asarray(result.per_view_rms, dtype=np.float64).reshape(1, -1))
        fs.write(
            "std_intrinsics",
            np.array([result.std[k] for k in PARAM_NAMES], dtype=np.float64).reshape(1, -1),
        )
        fs.write("std_names", " ".join(PARAM_NAMES))
        fs.write("rvecs", np.asarray(result.rvecs, dtype=np.float64))
        fs.write("tvecs", np.asarray(result.tvecs, dtype=np.float64))
    finally:
        fs.release()


class SavedCalibration(NamedTuple):
    """A camera read back by :func:`load_calibration`.

    Attributes
    ----------
    K : (3, 3) ndarray
        Intrinsics, pixels.
    dist : (4,) or (5,) ndarray
        Distortion coefficients in OpenCV's order ``(k1, k2, p1, p2[, k3])``.
    image_size : (width, height)
        The calibrated image size, pixels.
    """

    K: np.ndarray
    dist: np.ndarray
    image_size: tuple[int, int]


def load_calibration(path: str | os.PathLike, *, name: str = "path") -> SavedCalibration:
    """Read ``(K, dist, image_size)`` from a calibration file: camlab's, OpenCV's or ROS's.

    The file was written by :func:`save_calibration`, by OpenCV with the same node names, or
    by ROS's camera calibrator (``camera_info`` YAML, whose matrices are
    ``rows``/``cols``/``data`` maps; ``distortion_model: plumb_bob``).

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    name : str
        The argument named in errors.

    Returns
    -------
    SavedCalibration
        ``K`` (3, 3), ``dist`` (4,) or (5,) in OpenCV's order, and ``image_size`` (width,
        height), pixels.

    Raises
    ------
    CamlabInputError
        No such file, a file OpenCV cannot parse, another distortion model, missing or
        malformed nodes, or sizes that are not a 3 x 3 K, 4 or 5 coefficients and a positive
        image size.
    """
    if not isinstance(path, (str, os.PathLike)):
        raise CamlabInputError(f"{name}: expected a file path, got {type(path).__name__}")
    if not Path(path).is_file():
        raise CamlabInputError(f"{name}: no file {str(path)!r}")
    expected = (
        "pass a .json/.yaml/.xml written by `camlab calibrate` (or save_calibration), OpenCV's "
        "FileStorage, or ROS's camera calibrator"
    )
    fs = _open_storage(Path(path))
    if fs is None:
        raise CamlabInputError(
            f"{name}: {str(path)!r} is not a file OpenCV's FileStorage can parse; {expected}"
        )
    try:
        if not fs.isOpened():
            raise CamlabInputError(
                f"{name}: {str(path)!r} is not a file OpenCV's FileStorage can parse; {expected}"
            )
        model = fs.getNode("distortion_model")
        if not model.empty() and model.string() not in ("plumb_bob", "radtan"):
            raise CamlabInputError(
                f"{name}: {str(path)!r} uses the {model.string()!r} distortion model; camlab "
                f"undistorts with OpenCV's standard model (ROS 'plumb_bob': k1, k2, p1, p2, k3)"
            )
        K = _matrix(fs.getNode("camera_matrix"), path, name, expected)
        dist = _matrix(fs.getNode("distortion_coefficients"), path, name, expected)
        size = (int(fs.getNode("image_width").real()), int(fs.getNode("image_height").real()))
    finally:
        fs.release()
    if K.shape != (3, 3) or dist.size not in (4, 5) or min(size) <= 0:
        raise CamlabInputError(
            f"{name}: {str(path)!r} holds camera_matrix {K.shape[0]} x {K.shape[1]}, {dist.size} "
            f"distortion coefficients and image size {size[0]} x {size[1]}; expected 3 x 3, 4 or 5 "
            f"(k1, k2, p1, p2[, k3]) and a positive image_width and image_height"
        )
    return SavedCalibration(K, dist.ravel(), size)


def _open_storage(path: Path):
    """``cv2.FileStorage`` for reading ``path``, or None if OpenCV cannot parse it.

    OpenCV 4 reads YAML only after a ``%YAML:1.0`` directive, which ROS's files lack (OpenCV 5
    reads them as they are), so a YAML file without one is read again from memory with it.
    """
    import cv2

    try:
        return cv2.FileStorage(str(path), cv2.FILE_STORAGE_READ)
    except (cv2.error, SystemError):
        if path.suffix.lower() not in (".yaml", ".yml"):
            return None
    text = path.read_text(encoding="utf-8", errors="replace")
    if text.lstrip().startswith("%YAML"):
        return None
    flags = cv2.FILE_STORAGE_READ | cv2.FILE_STORAGE_MEMORY | cv2.FILE_STORAGE_FORMAT_YAML
    try:
        return cv2.FileStorage("%YAML:1.0\n---\n" + text, flags)
    except (cv2.error, SystemError):
        return None


def _matrix(node, path, name: str, expected: str) -> np.ndarray:
    """A matrix node as a float array.

    OpenCV's ``!!opencv-matrix`` (with ``dt``), or ROS's map of ``rows``, ``cols`` and ``data`` (no
    ``dt``: ``node.mat()`` fails on it with ``!dt.empty()``).
    """
    if node.empty():
        raise CamlabInputError(
            f"{name}: {str(path)!r} has no camera_matrix / distortion_coefficients nodes; {expected}"
        )
    if node.isMap() and node.getNode("dt").empty():
        rows, cols, data = (node.getNode(k) for k in ("rows", "cols", "data"))
        values = [data.at(i).real() for i in range(data.size())] if data.isSeq() else []
        if rows.empty() or cols.empty() or len(values) != int(rows.real()) * int(cols.real()):
            raise CamlabInputError(
                f"{name}: {str(path)!r}: the {node.name()} node is neither an OpenCV matrix nor a "
                f"ROS rows/cols/data map; {expected}"
            )
        return np.array(values, dtype=float).reshape(int(rows.real()), int(cols.real()))
    import cv2

    try:
        m = node.mat()
    except cv2.error:  # a scalar, string or map that is not a matrix
        m = None
    if m is None:
        raise CamlabInputError(
            f"{name}: {str(path)!r}: the {node.name()} node is not a matrix; {expected}"
        )
    return np.asarray(m, dtype=float)
