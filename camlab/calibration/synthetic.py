"""Synthetic calibration data: random well-spread chessboard views through a known camera."""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, check_intrinsics
from ..camera import rotation_from_axis_angle
from ..distortion import as_dist
from .detection import board_points


class SyntheticSet(NamedTuple):
    """Views of a board with known truth.

    ``object_points`` (N, 3), ``image_points`` list of (N, 2) (noisy), ``exact`` list of (N, 2)
    (noise-free), ``K``, ``dist``, ``R`` (V, 3, 3), ``t`` (V, 3), ``image_size``, ``noise`` (sigma,
    pixels).
    """

    object_points: np.ndarray
    image_points: list
    exact: list
    K: np.ndarray
    dist: np.ndarray
    R: np.ndarray
    t: np.ndarray
    image_size: tuple
    noise: float


DEFAULT_K = np.array([[820.0, 0.0, 322.4], [0.0, 818.0, 236.8], [0.0, 0.0, 1.0]])


DEFAULT_DIST = np.array([-0.21, 0.09, 0.0006, -0.0004, -0.02])


def make_synthetic_views(
    n_views: int = 15,
    noise: float = 0.0,
    *,
    K: ArrayLike = DEFAULT_K,
    dist: ArrayLike | None = DEFAULT_DIST,
    pattern_size: Sequence[int] = (9, 6),
    square: float = 0.025,
    image_size: Sequence[int] = (640, 480),
    margin: float = 20.0,
    tilt: Sequence[float] | None = None,
    rng: np.random.Generator | None = None,
) -> SyntheticSet:
    """Random well-spread views of a chessboard through a known camera (corners only, no images).

    Each view tilts the board by 15-50 degrees (or ``tilt``) about a random in-plane axis, spins it,
    places it 0.3-0.6 m away at a random spot so that every corner lands at least
    ``margin`` pixels inside the image, and adds Gaussian noise of ``noise`` pixels to the
    exact corners (projected with :func:`camlab.render.project`).

    Parameters
    ----------
    n_views : int
        How many views.
    noise : float
        Standard deviation of the Gaussian corner noise, pixels (0: exact corners).
    K : (3, 3) array_like
        The camera's intrinsics, pixels.
    dist : array_like or None
        Its distortion coefficients, OpenCV's order (None: none).
    pattern_size : (cols, rows) or str
        Inner corners of the board.
    square : float
        Square size, metres.
    image_size : (width, height)
        Pixels.
    margin : float
        Least distance of every corner from the image border, pixels.
    tilt : (lo, hi) sequence of float, optional
        The range the tilt is drawn from, radians (``(a, a)``: every view tilted by ``a``);
        None (the default) is 15-50 degrees.
    rng : numpy.random.Generator, optional
        The random source (default a fresh, unseeded one).

    Returns
    -------
    SyntheticSet
        ``object_points`` (N, 3), noisy ``image_points`` and noise-free ``exact`` (V lists of
        (N, 2)), the truth ``K``, ``dist``, ``R`` (V, 3, 3), ``t`` (V, 3), ``image_size`` and
        ``noise``.

    Raises
    ------
    CamlabInputError
        Bad intrinsics, coefficients or pattern, or no placement found inside the image in
        200 tries per view.
    """
    from ..camera import rotation_from_euler
    from ..render import project

    rng = np.random.default_rng() if rng is None else rng
    Km = check_intrinsics(K)
    d = as_dist(dist)
    obj = board_points(pattern_size, square)
    centre = obj.mean(axis=0)
    w, h = (int(v) for v in image_size)
    Rs, ts, exact = [], [], []
    tries = 0
    while len(Rs) < n_views:
        tries += 1
        if tries > 200 * max(n_views, 1):
            raise CamlabInputError(
                "make_synthetic_views: could not place the board inside the image; "
                "use a smaller board or a wider camera"
            )
        axis = rng.uniform(0, 2 * np.pi)
        angle = np.radians(rng.uniform(15, 50)) if tilt is None else rng.uniform(*tilt)
        R_tilt = rotation_from_axis_angle(angle * np.array([np.cos(axis), np.sin(axis), 0.0]))
        R = R_tilt @ rotation_from_euler(0, 0, rng.uniform(-0.5, 0.5))
        depth = rng.uniform(0.3, 0.6)
        target = np.array([rng.uniform(-0.35, 0.35), rng.uniform(-0.3, 0.3), 1.0]) * depth
        t = target - R @ centre
        uv = project(obj, Km, R, t, d)
        if (
            np.all(np.isfinite(uv))
            and uv[:, 0].min() >= margin
            and uv[:, 1].min() >= margin
            and uv[:, 0].max() <= w - 1 - margin
            and uv[:, 1].max() <= h - 1 - margin
        ):
            Rs.append(R)
            ts.append(t)
            exact.append(uv)
    noisy = [e + rng.normal(0, noise, e.shape) if noise > 0 else e.copy() for e in exact]
    return SyntheticSet(obj, noisy, exact, Km, d, np.array(Rs), np.array(ts), (w, h), float(noise))
