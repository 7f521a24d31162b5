r"""Vanishing points from image segments.

The least-squares point most segments' lines pass near, which segments point at a point, and a
RANSAC fit robust to segments that point elsewhere.

Lessons 05, 06 and 10 find vanishing points in photographs with these.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, DegenerateError, check_finite
from ..robust import MinimalModels, PairModel, ransac
from .conditioning import hartley_normalise
from .plane import normalise_lines, normalise_points, to_homogeneous

__all__ = [
    "SegmentsModel",
    "pointing_angles",
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

    Coordinates are centred and scaled first (the conditioning of [1]_), because pixel
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

    References
    ----------
    .. [1] R. I. Hartley, 1997, "In defense of the eight-point algorithm", *IEEE Transactions
       on Pattern Analysis and Machine Intelligence* 19(6), 580-593.
    .. [2] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 8.6.1 (vanishing
       points).
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
    T = hartley_normalise(s.reshape(-1, 2), "segments").T
    ends = [to_homogeneous(s[:, k]) @ T.T for k in (0, 1)]
    lines = normalise_lines(np.cross(ends[0], ends[1]))
    _, sv, vt = np.linalg.svd(lines)
    if sv[1] < 1e-9 * sv[0]:
        raise DegenerateError(
            "segments: all segments lie on one line, so they do not fix a vanishing point"
        )
    v = np.linalg.solve(T, vt[-1])  # undo the conditioning: v = T^-1 v_n
    if abs(v[2]) <= 1e-12 * np.linalg.norm(v[:2]):
        v[2] = 0.0  # parallel to round-off: the vanishing point is ideal, not at 1e16 px
    return normalise_points(v)


def pointing_angles(points_h: ArrayLike, starts: ArrayLike, ends: ArrayLike) -> np.ndarray:
    r"""Angles in degrees, in [0, 90], between segments and the directions from their midpoints to points.

    For a segment from a to b with midpoint :math:`m = (a + b) / 2` and a homogeneous point
    :math:`v = (x, y, w)`, the direction towards v is :math:`(x - m w, y - m w)`, which stays
    valid for an ideal point (w = 0); the angle is
    :math:`\arccos \frac{|d \cdot (v_{xy} - m w)|}{\|d\| \|v_{xy} - m w\|}` with
    :math:`d = b - a` (a segment has no arrow, so the angle is at most 90 degrees). Where it is
    undefined (a segment of zero length, or v at the midpoint) it is 180, so no threshold
    accepts it.

    Parameters
    ----------
    points_h : (B, 3) array_like
        Homogeneous points (proposed vanishing points).
    starts, ends : (M, 2) array_like
        The segments' end points, pixels.

    Returns
    -------
    (B, M) ndarray
    """
    v = np.asarray(points_h, dtype=float)
    a, b = np.asarray(starts, dtype=float), np.asarray(ends, dtype=float)
    mid, d = (a + b) / 2, b - a
    to_v = v[:, None, :2] - mid[None] * v[:, None, 2:]
    with np.errstate(invalid="ignore", divide="ignore"):
        cos = np.abs(np.sum(d * to_v, axis=-1)) / (
            np.linalg.norm(d, axis=-1) * np.linalg.norm(to_v, axis=-1)
        )
    return np.nan_to_num(np.degrees(np.arccos(np.clip(cos, 0, 1))), nan=180.0)


def segments_pointing_at(
    segments: ArrayLike, point_h: ArrayLike, tol_deg: float = 1.5
) -> np.ndarray:
    """Which segments point at the (possibly ideal) point, within ``tol_deg`` degrees.

    The angle is measured at each segment's midpoint m, between the segment's direction
    and the direction from m to the point, :math:`(x - m w, y - m w)`, which stays valid
    for an ideal point (w = 0): :func:`pointing_angles`.

    Parameters
    ----------
    segments : (N, 2, 2) array_like
        Segments ``[[u1, v1], [u2, v2]]``, pixels.
    point_h : (3,) array_like
        A homogeneous point (w = 0 for an ideal point).
    tol_deg : float, optional
        Angle tolerance, degrees.

    Returns
    -------
    (N,) bool ndarray
        True for the segments within ``tol_deg``.
    """
    segs = np.asarray(segments, dtype=float)
    v = np.asarray(point_h, dtype=float)
    return pointing_angles(v[None], segs[:, 0], segs[:, 1])[0] < tol_deg


class VanishingPointFit(NamedTuple):
    """What :func:`vanishing_point_ransac` found: ``point`` (3,) homogeneous, ``inliers`` (N,) bool."""

    point: np.ndarray
    inliers: np.ndarray


class SegmentsModel(PairModel):
    """A vanishing point as a model for :func:`camlab.robust.ransac`: the pairs are the segments' ends.

    A minimal sample is two segments, whose lines meet in the proposal; the least-squares fit
    is :func:`vanishing_point`; a segment's residual is its :func:`pointing_angles`, degrees.
    """

    sample_size = 2
    name = "vanishing_point_ransac"

    def __init__(self, segments: np.ndarray):
        super().__init__(segments[:, 0], segments[:, 1])
        ones = np.ones((len(segments), 1))
        self.lines = np.cross(np.hstack([self.x1, ones]), np.hstack([self.x2, ones]))

    def minimal(self, idx: np.ndarray) -> MinimalModels:
        """The meet of the two segments' lines in each sample (see :meth:`PairModel.minimal`).

        Parameters
        ----------
        idx : (B, 2) int ndarray
            B samples of two segment indices.

        Returns
        -------
        MinimalModels
            ``models`` (B, 3), homogeneous proposals, and ``usable`` (B,), False where the two
            lines coincide.
        """
        proposals = np.cross(self.lines[idx[:, 0]], self.lines[idx[:, 1]])
        return MinimalModels(proposals, np.any(proposals != 0, axis=1))

    def fit(self, idx: np.ndarray) -> np.ndarray:
        """The least-squares vanishing point of the segments ``idx`` (:func:`vanishing_point`).

        Parameters
        ----------
        idx : (K,) int ndarray
            Indices of the segments.

        Returns
        -------
        (3,) ndarray
            The homogeneous vanishing point.
        """
        return vanishing_point(np.stack([self.x1[idx], self.x2[idx]], axis=1))

    def residuals(
        self, models: np.ndarray, i1: np.ndarray | None = None, i2: np.ndarray | None = None
    ) -> np.ndarray:
        """Each segment's :func:`pointing_angles` to each proposal, degrees (see :meth:`PairModel.residuals`).

        Parameters
        ----------
        models : (B, 3) ndarray
            Homogeneous points.
        i1, i2 : (M,) int ndarray, optional
            Indices of the segments' start and end points; None for all.

        Returns
        -------
        (B, M) ndarray
            Angles, degrees, in [0, 90].
        """
        a = self.x1 if i1 is None else self.x1[i1]
        b = self.x2 if i2 is None else self.x2[i2]
        return pointing_angles(models, a, b)


def vanishing_point_ransac(
    segments: ArrayLike,
    tol_deg: float = 1.5,
    samples: int = 300,
    rng: np.random.Generator | int | None = None,
) -> VanishingPointFit:
    """The vanishing point most segments point at, robust to segments that belong to none.

    RANSAC [1]_ by :func:`camlab.robust.ransac`, the driver the homography
    and the fundamental matrix use (lesson 07): two random segments propose the meet of their
    lines; every segment is scored by the angle at which it misses the proposal
    (:func:`pointing_angles`), capped at ``tol_deg`` (MSAC), so the proposal most segments
    point at wins; it is polished on its inliers and must beat what segments joining
    unrelated end points reach by chance. The winner is re-estimated from the segments that
    point at it within ``tol_deg`` (:func:`segments_pointing_at`) by :func:`vanishing_point`
    (least squares over unit vectors, so it may be ideal).

    Parameters
    ----------
    segments : (N, 2, 2) array_like
        Image segments (pixels), N >= 3: two segments always meet, so a consensus needs a
        third.
    tol_deg : float
        Inlier threshold on the angle, degrees.
    samples : int
        Most pairs of segments drawn (fewer once the consensus is certain).
    rng : numpy.random.Generator, int or None
        Random generator or seed.

    Returns
    -------
    VanishingPointFit
        ``point`` (3,), homogeneous (ideal if the segments are parallel in the image), and
        ``inliers`` (N,) bool, the segments pointing at it.

    Raises
    ------
    DegenerateError
        If no proposal is supported beyond chance: no vanishing point here.

    References
    ----------
    .. [1] M. A. Fischler and R. C. Bolles, 1981, "Random sample consensus: a paradigm for model
       fitting with applications to image analysis and automated cartography",
       *Communications of the ACM* 24(6), 381-395.
    """
    segs = np.asarray(segments, dtype=float)
    if segs.ndim != 3 or segs.shape[1:] != (2, 2) or len(segs) < 3:
        raise CamlabInputError(
            f"segments: expected (N, 2, 2) with N >= 3 segments, got shape {segs.shape}; two "
            f"segments always meet, so it takes a third to agree on a vanishing point"
        )
    check_finite(segs, "segments")
    fit = ransac(SegmentsModel(segs), tol_deg, max_iters=samples, rng=rng)
    return VanishingPointFit(vanishing_point(segs[fit.inliers]), fit.inliers)
