r"""Calibration from photographs.

Find the chessboard in every image, report the ones that fail, calibrate from the rest
(:func:`calibrate_from_images`).
"""

from __future__ import annotations

import glob as _glob
import os
from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

import numpy as np

from .._files import PhotoReadError, read_photo
from .._validate import CamlabInputError
from .calibrate import CalibrationResult, calibrate_camera
from .detection import board_points, find_chessboard, grey_uint8, parse_pattern


class ImageCalibration(NamedTuple):
    """The outcome of :func:`calibrate_from_images`.

    ``result`` the :class:`CalibrationResult` over the good views; ``names`` every input's
    name (file path or ``image[i]``); ``used`` the indices that went into ``result`` (view v
    of ``result`` is input ``used[v]``); ``failed`` {index: reason} for the rest;
    ``detections`` (N, 2) corners or None per input.
    """

    result: CalibrationResult
    names: list
    used: list
    failed: dict
    detections: list

    def report(self) -> str:
        """Which images were used, which failed and why.

        Returns
        -------
        str
            "U of N images used", then one line per skipped image naming it and the reason.
        """
        lines = [f"{len(self.used)} of {len(self.names)} images used"]
        for i, why in sorted(self.failed.items()):
            lines.append(f"  skipped {self.names[i]}: {why}")
        return "\n".join(lines)


def _inputs(images_or_paths) -> list:
    """The images or file paths to calibrate from (a glob pattern expanded), not yet read."""
    if isinstance(images_or_paths, (str, os.PathLike)):
        pattern = str(images_or_paths)
        paths = sorted(_glob.glob(pattern)) if any(ch in pattern for ch in "*?[") else [pattern]
        if not paths:
            raise CamlabInputError(
                f"images_or_paths: no files match {pattern!r}; check the path and quote the pattern"
            )
        images_or_paths = paths
    items = list(images_or_paths)
    if not items:
        raise CamlabInputError("images_or_paths: expected images or file paths, got an empty list")
    return items


def _grey(item, i: int) -> np.ndarray:
    """Input i as a grey uint8 image: a file read upright (:func:`camlab._files.read_photo`) or an array."""
    if isinstance(item, (str, os.PathLike)):
        try:
            return read_photo(item, "grey")
        except PhotoReadError as exc:
            raise CamlabInputError(exc.reason) from None
    return grey_uint8(item, f"images[{i}]")


def calibrate_from_images(
    images_or_paths,
    pattern_size: Sequence[int] | str,
    square_size: float,
    progress: Callable[[int, int, str, str | None], None] | None = None,
    **kwargs: Any,
) -> ImageCalibration:
    """Detect the chessboard in every image, report failures, calibrate from the rest.

    Parameters
    ----------
    images_or_paths : sequence of images or paths, or a glob pattern like ``"photos/*.png"``
    pattern_size : (cols, rows) or "COLSxROWS"
        Inner corners.
    square_size : float
        Side of one square, metres (sets the units of the translations).
    progress : callable, optional
        Called after each image as ``progress(i, n, name, failure)`` (i from 1; failure is
        the reason the image is skipped, None when its board was found).
    **kwargs
        Passed to :func:`calibrate_camera` (``skew``, ``fix``, ...).

    Returns
    -------
    ImageCalibration

    Raises
    ------
    CamlabInputError
        Fewer than 3 images with a detected board (the message lists each failure).
    """
    pattern = parse_pattern(pattern_size)
    obj = board_points(pattern, square_size)
    items = _inputs(images_or_paths)
    names = [
        str(x) if isinstance(x, (str, os.PathLike)) else f"image[{i}]" for i, x in enumerate(items)
    ]
    failed, sizes = {}, {}
    # One image in memory at a time (a phone photo is 40 MB in grey): a first pass learns the sizes (so
    # an odd one is reported as such), a second reads again the images of the common size, one by one.
    for i, item in enumerate(items):
        try:
            sizes.setdefault(_grey(item, i).shape[::-1], []).append(i)
        except CamlabInputError as exc:
            failed[i] = str(exc)
    size = max(sizes, key=lambda s: len(sizes[s])) if sizes else None
    for s, idx in sizes.items():
        if s != size:
            for i in idx:
                failed[i] = (
                    f"image size {s[0]} x {s[1]} differs from the other images' {size[0]} x {size[1]}; "
                    f"calibrate each camera/resolution separately"
                )
    detections: list = [None] * len(items)
    for i, item in enumerate(items):
        if i not in failed:
            det = find_chessboard(_grey(item, i), pattern)
            if det.found:
                detections[i] = det.corners
            else:
                failed[i] = det.reason
        if progress is not None:
            progress(i + 1, len(items), names[i], failed.get(i))
    used = [i for i in range(len(items)) if detections[i] is not None]
    if len(used) < 3:
        why = "\n".join(f"  {names[i]}: {r}" for i, r in sorted(failed.items()))
        raise CamlabInputError(
            f"calibrate_from_images: need at least 3 images with the board detected, got {len(used)} of "
            f"{len(items)}:\n{why}"
        )
    result = calibrate_camera(obj, [detections[i] for i in used], size, **kwargs)
    return ImageCalibration(result, names, used, dict(sorted(failed.items())), detections)
