"""Undistort images with a calibration, trading black borders against lost pixels (``alpha``)."""

from __future__ import annotations

from collections.abc import Sequence
from functools import lru_cache
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    CamlabInputError,
    ConvergenceError,
    check_image,
    check_intrinsics,
    check_number,
    check_size,
)
from ..distortion import (
    as_dist,
    distort_points,
    normalised_to_pixels,
    pixels_to_normalised,
    undistort_image,
    undistort_points,
)
from .calibrate import CalibrationResult


def _rectangles(K: np.ndarray, dist: np.ndarray, size: tuple[int, int], n: int = 9):
    """Inner and outer rectangles (x0, y0, x1, y1) of the undistorted image border, normalised coords."""
    w, h = size
    gx, gy = np.meshgrid(np.linspace(0, w - 1, n), np.linspace(0, h - 1, n))
    pix = np.column_stack([gx.ravel(), gy.ravel()])
    x = undistort_points(pixels_to_normalised(pix, K), dist).reshape(n, n, 2)
    outer = (x[..., 0].min(), x[..., 1].min(), x[..., 0].max(), x[..., 1].max())
    inner = (x[:, 0, 0].max(), x[0, :, 1].max(), x[:, -1, 0].min(), x[-1, :, 1].min())
    return inner, outer


def optimal_new_camera_matrix(
    K: ArrayLike, dist: ArrayLike | None, image_size: Sequence[int], alpha: float
) -> np.ndarray:
    r"""The intrinsics of the undistorted image, trading black borders for lost pixels.

    Undistortion bends the image border outwards (barrel) or inwards (pincushion). With
    ``alpha = 0`` the new camera zooms in until every output pixel comes from inside the
    photo (no black borders, but pixels near the edges are lost); with ``alpha = 1`` it
    zooms out until every photo pixel is kept (black borders appear). In between the new
    K is interpolated linearly, as ``cv2.getOptimalNewCameraMatrix`` does: from a 9 x 9 grid
    of border-to-border pixels undistorted to normalised coordinates, the inner rectangle
    (inside all of them) and outer rectangle (around all of them) are mapped onto the image.

    Parameters
    ----------
    K : (3, 3) array_like
        The photo's intrinsics, pixels.
    dist : array_like or None
        Its distortion coefficients, OpenCV's order (None: none).
    image_size : (width, height)
        The photo's size (and the output's), pixels.
    alpha : float
        In [0, 1]: 0 no black borders, 1 no lost pixels.

    Returns
    -------
    (3, 3) ndarray
        New K (zero skew), pixels.

    Raises
    ------
    CamlabInputError
        Bad intrinsics, coefficients or size, or ``alpha`` outside [0, 1].
    """
    Km = check_intrinsics(K)
    d = as_dist(dist)
    a = check_number(alpha, "alpha")
    if not 0.0 <= a <= 1.0:
        raise CamlabInputError(
            f"alpha: expected a number in [0, 1] (0: no black borders, 1: keep all pixels), got {alpha!r}"
        )
    w, h = check_size(image_size, "image_size")
    inner, outer = _rectangles(Km, d, (w, h))

    def fit(r):
        fx, fy = (w - 1) / (r[2] - r[0]), (h - 1) / (r[3] - r[1])
        return np.array([fx, fy, -fx * r[0], -fy * r[1]])

    p = (1 - a) * fit(inner) + a * fit(outer)
    return np.array([[p[0], 0.0, p[2]], [0.0, p[1], p[3]], [0.0, 0.0, 1.0]])


class UndistortionTradeoff(NamedTuple):
    """What undistorting with a new K costs (:func:`undistortion_tradeoff`).

    Attributes
    ----------
    black_fraction : float
        Share of output pixels that sample outside the photo (the black border).
    lost_fraction : float
        Share of photo pixels that land outside the output.
    """

    black_fraction: float
    lost_fraction: float


def undistortion_tradeoff(
    K: ArrayLike, dist: ArrayLike | None, image_size: Sequence[int], new_K: ArrayLike, step: int = 4
) -> UndistortionTradeoff:
    """What undistorting with ``new_K`` costs: the black border and the lost pixels.

    Parameters
    ----------
    K : (3, 3) array_like
        The photo's intrinsics, pixels.
    dist : array_like or None
        Its distortion coefficients, OpenCV's order (None: none).
    image_size : (width, height)
        The photo's size (and the output's), pixels.
    new_K : (3, 3) array_like
        The undistorted image's intrinsics (e.g. :func:`optimal_new_camera_matrix`).
    step : int
        Both shares are measured on a grid every ``step`` pixels.

    Returns
    -------
    UndistortionTradeoff
        ``black_fraction``: share of output pixels that sample outside the photo (black
        border); ``lost_fraction``: share of photo pixels that land outside the output (all
        of them when the distortion cannot be inverted over the photo).

    Raises
    ------
    CamlabInputError
        Bad intrinsics, coefficients or size.
    """
    Km, Kn = check_intrinsics(K), check_intrinsics(new_K, "new_K")
    d = as_dist(dist)
    w, h = check_size(image_size, "image_size")
    U, Vv = np.meshgrid(np.arange(0, w, step, dtype=float), np.arange(0, h, step, dtype=float))
    pix = np.column_stack([U.ravel(), Vv.ravel()])
    # output pixel -> source pixel: K distort(Kn^-1 p); same as distort_pixels with a change of K
    src = normalised_to_pixels(distort_points(pixels_to_normalised(pix, Kn), d), Km)
    inside = (
        (src[:, 0] >= -0.5) & (src[:, 0] <= w - 0.5) & (src[:, 1] >= -0.5) & (src[:, 1] <= h - 0.5)
    )
    ideal = _ideal_grid(Km.tobytes(), d.tobytes(), w, h, step)
    if ideal is None:  # the model has no inverse over the photo: nothing can be kept
        kept = np.zeros(len(pix), bool)
    else:
        dst = normalised_to_pixels(ideal, Kn)
        kept = (
            (dst[:, 0] >= -0.5)
            & (dst[:, 0] <= w - 0.5)
            & (dst[:, 1] >= -0.5)
            & (dst[:, 1] <= h - 0.5)
        )
    return UndistortionTradeoff(float(1 - inside.mean()), float(1 - kept.mean()))


@lru_cache(maxsize=8)
def _ideal_grid(Kb: bytes, db: bytes, w: int, h: int, step: int) -> np.ndarray | None:
    """Ideal normalised coordinates of the photo's pixels every ``step`` (None if the inversion fails).

    The iterative inversion does not depend on the new K, so sweeping ``alpha`` (a slider)
    pays for it once; the cached array is read-only.
    """
    U, Vv = np.meshgrid(np.arange(0, w, step, dtype=float), np.arange(0, h, step, dtype=float))
    pix = np.column_stack([U.ravel(), Vv.ravel()])
    try:
        ideal = undistort_points(
            pixels_to_normalised(pix, np.frombuffer(Kb).reshape(3, 3)), np.frombuffer(db)
        )
    except ConvergenceError:
        return None
    ideal.setflags(write=False)
    return ideal


class Undistorted(NamedTuple):
    """``image`` the undistorted image.

    ``K`` its intrinsics (no distortion); ``black_fraction`` and ``lost_fraction`` as in
    :func:`undistortion_tradeoff`.
    """

    image: np.ndarray
    K: np.ndarray
    black_fraction: float
    lost_fraction: float


def undistort(
    image: ArrayLike,
    result: CalibrationResult | None = None,
    *,
    K: ArrayLike | None = None,
    dist: ArrayLike | None = None,
    alpha: float = 0.0,
) -> Undistorted:
    """Undistort an image with a calibration (or K and dist), choosing the new K with ``alpha``.

    ``alpha`` as in :func:`optimal_new_camera_matrix`: 0 crops to valid pixels, 1 keeps all.
    The remap uses :func:`camlab.distortion.undistort_image` (bilinear, black outside).

    Parameters
    ----------
    image : (H, W) or (H, W, C) array_like
        The photo.
    result : CalibrationResult, optional
        The calibration; its K and dist override ``K`` and ``dist``.
    K : (3, 3) array_like, optional
        Intrinsics, pixels (needed without ``result``).
    dist : array_like, optional
        Distortion coefficients, OpenCV's order.
    alpha : float
        In [0, 1]: 0 no black borders, 1 no lost pixels.

    Returns
    -------
    Undistorted
        ``image`` (same size as the photo), ``K`` (its intrinsics, no distortion),
        ``black_fraction`` and ``lost_fraction`` (:func:`undistortion_tradeoff`).

    Raises
    ------
    CamlabInputError
        Not an image, neither ``result`` nor ``K``, or a bad ``alpha``.
    """
    img = check_image(image)
    if result is not None:
        K, dist = result.K, result.dist
    if K is None:
        raise CamlabInputError("undistort: pass a CalibrationResult or K (and dist)")
    size = (img.shape[1], img.shape[0])
    new_K = optimal_new_camera_matrix(K, dist, size, alpha)
    black, lost = undistortion_tradeoff(K, dist, size, new_K)
    return Undistorted(undistort_image(img, K, dist, new_K), new_K, black, lost)
