r"""Vanishing points from image segments: the least-squares point most segments' lines pass
near, which segments point at a point, and a RANSAC fit robust to segments that point elsewhere.

Lessons 05, 06 and 10 find vanishing points in photographs with these.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, DegenerateError
from .conditioning import hartley_normalization
from .plane import normalize_lines, normalize_points, to_homogeneous

__all__ = [
    "VanishingPointFit",
    "segments_pointing_at",
    "vanishing_point_ransac",
    "vanishing_point",
]


def vanishing_point(segments: ArrayLike) -> np.ndarray:
    r"""The common point of the lines through image segments that are parallel in 3-D.

    With two segments it is :func:`meet` of their lines. With more, noisy lines rarely
    share a point exactly, so take the v that minimises :math:`\sum_i (l_i \cdot v)^2`
    over unit vectors, with each line scaled so that :math:`a^2 + b^2 = 1`. That is the
    right singular vector of the stacked lines with the smallest singular value; working
    in homogeneous form keeps the answer valid when the vanishing point is at infinity.

    Coordinates are centred and scaled first (Hartley's conditioning), because pixel
    values in the hundreds make the stacked system badly conditioned.

    Parameters
    ----------
    segments : (N, 2, 2) array_like
        N >= 2 segments, each ``[[u1, v1], [u2, v2]]`` in pixels.

    Returns
    -------
    (3,) ndarray
        Homogeneous vanishing point, normalised (w = 1, or unit (x, y) if ideal).

    Raises
    ------
    DegenerateError
        For a zero-length segment or segments that all lie on one line.
    """
    s = np.asarray(segments, dtype=float) if np.ndim(segments) else None
    if s is None or s.ndim != 3 or s.shape[1:] != (2, 2) or len(s) < 2:
        raise CamlabInputError(
            f"segments: expected (N, 2, 2) endpoints [[u1, v1], [u2, v2]] with N >= 2, "
            f"got shape {np.shape(segments)}"
        )
    if not np.isfinite(s).all():
        raise CamlabInputError("segments: expected finite coordinates, found NaN or inf")
    lengths = np.linalg.norm(s[:, 1] - s[:, 0], axis=1)
    if np.any(lengths == 0):
        raise DegenerateError(
            f"segments: segment {int(np.argmin(lengths))} has zero length; it defines no line"
        )
    T = hartley_normalization(s.reshape(-1, 2), "segments")
    ends = [to_homogeneous(s[:, k]) @ T.T for k in (0, 1)]
    lines = normalize_lines(np.cross(ends[0], ends[1]))
    _, sv, vt = np.linalg.svd(lines)
    if sv[1] < 1e-9 * sv[0]:
        raise DegenerateError(
            "segments: all segments lie on one line, so they do not fix a vanishing point"
        )
    v = np.linalg.solve(T, vt[-1])  # undo the conditioning: v = T^-1 v_n
    if abs(v[2]) <= 1e-12 * np.linalg.norm(v[:2]):
        v[2] = 0.0  # parallel to round-off: the vanishing point is ideal, not at 1e16 px
    return normalize_points(v)


def segments_pointing_at(
    segments: ArrayLike, point_h: ArrayLike, tol_deg: float = 1.5
) -> np.ndarray:
    """Which segments point at the (possibly ideal) point, within ``tol_deg`` degrees.

    The angle is measured at each segment's midpoint m, between the segment's direction
    and the direction from m to the point, :math:`(x - m w, y - m w)`, which stays valid
    for an ideal point (w = 0). Returns an (N,) bool array.
    """
    segs = np.asarray(segments, dtype=float)
    v = np.asarray(point_h, dtype=float)
    mid, d = segs.mean(axis=1), segs[:, 1] - segs[:, 0]
    to_v = v[:2] - mid * v[2]
    with np.errstate(invalid="ignore", divide="ignore"):
        cos = np.abs(np.sum(d * to_v, axis=1)) / (
            np.linalg.norm(d, axis=1) * np.linalg.norm(to_v, axis=1)
        )
    return np.nan_to_num(np.degrees(np.arccos(np.clip(cos, 0, 1))), nan=180.0) < tol_deg


class VanishingPointFit(NamedTuple):
    """What :func:`vanishing_point_ransac` found: ``point`` (3,) homogeneous, ``inliers`` (N,) bool."""

    point: np.ndarray
    inliers: np.ndarray


def vanishing_point_ransac(
    segments: ArrayLike,
    tol_deg: float = 1.5,
    samples: int = 300,
    rng: np.random.Generator | int | None = None,
) -> VanishingPointFit:
    """The vanishing point most segments point at, robust to segments that belong to none.

    RANSAC (Fischler & Bolles): two random segments propose the meet of their lines; every
    segment pointing at it within ``tol_deg`` (:func:`segments_pointing_at`) votes; the
    proposal with the most votes wins and is re-estimated from its voters by
    :func:`vanishing_point` (least squares over unit vectors, so it may be ideal).

    Parameters
    ----------
    segments : (N, 2, 2) array_like
        Image segments (pixels), N >= 2.
    tol_deg : float
    samples : int
    rng : numpy Generator, int or None

    Returns
    -------
    VanishingPointFit
    """
    segs = np.asarray(segments, dtype=float)
    if segs.ndim != 3 or segs.shape[1:] != (2, 2) or len(segs) < 2:
        raise CamlabInputError(
            f"segments: expected (N, 2, 2) with N >= 2 segments, got shape {segs.shape}"
        )
    rng = np.random.default_rng(rng)
    ones = np.ones((len(segs), 1))
    lines = np.cross(np.hstack([segs[:, 0], ones]), np.hstack([segs[:, 1], ones]))
    best = np.zeros(len(segs), bool)
    for _ in range(int(samples)):
        i, j = rng.choice(len(segs), 2, replace=False)
        proposal = np.cross(lines[i], lines[j])
        if not np.any(proposal):
            continue
        votes = segments_pointing_at(segs, proposal, tol_deg)
        if votes.sum() > best.sum():
            best = votes
    if best.sum() < 2:
        raise DegenerateError(
            "segments: no two segments point at a common point; there is no vanishing point here"
        )
    return VanishingPointFit(vanishing_point(segs[best]), best)
