r"""The dolly zoom (Hitchcock's vertigo shot).

A camera that backs away while it zooms keeps its subject's size and tends to an affine camera; the
errors and gaps it shows on the way.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    CamlabInputError,
    as_float,
    check_finite,
    check_positive,
)
from ..camera import Camera, intrinsic_matrix, orbit_eye, project_points, project_segments
from .cameras import affine_approximation, orthographic_matrix, weak_perspective_error

__all__ = [
    "dolly_zoom_camera",
    "dolly_zoom_errors",
    "dolly_zoom_focal",
    "largest_gap_in_frame",
    "matched_points_in_frame",
    "MatchedPoints",
    "ThreeImages",
    "three_images",
]


def dolly_zoom_camera(
    distance: float,
    azimuth: float,
    elevation: float,
    target: ArrayLike,
    f0: float = 800.0,
    d0: float = 4.0,
    principal_point: tuple[float, float] = (319.5, 239.5),
    image_offset: float = 0.0,
) -> Camera:
    r"""A camera on a dolly zoom towards ``target``: at depth ``distance``, zoomed to keep its size.

    The camera is ``distance`` metres from the target (its depth), zoomed to
    :func:`dolly_zoom_focal` ``(f0, d0, distance)`` so the target keeps the size it has at depth
    ``d0`` with focal length ``f0`` (pixels). See lesson 05, section 2.

    The camera keeps one orientation R at every distance: that of a camera on the orbit (``azimuth``,
    ``elevation``, radians: :func:`camlab.camera.orbit_eye`) looking at the target. It moves along its own
    principal axis, as in H&Z [1]_: :math:`C = X_T - s\,r_1 - d\,r_3`, so the target has camera
    coordinates :math:`(s, 0, d)`, depth ``distance`` = d. ``image_offset`` (pixels) sets the sideways
    shift :math:`s = \text{image\_offset}\; d_0 / f_0` metres, which images the target exactly
    ``image_offset`` px right of the principal point at every distance (:math:`f s / d = f_0 s / d_0`, as
    f grows like d). With ``image_offset = 0`` the camera looks straight at the target from ``distance``
    metres on the orbit.

    As the camera keeps R and moves along r3, every point's lateral camera coordinates (x, y) stay fixed
    and its depth grows by the same amount, while f / d stays f0 / d0: the affine approximation
    :math:`P_\infty` about the target is the same matrix at every distance, the fixed image the
    perspective one converges to.

    Parameters
    ----------
    distance : float
        The target's depth in the camera, metres (> 0).
    azimuth, elevation : float
        The orbit direction the camera looks from, radians (:func:`camlab.camera.orbit_eye`).
    target : (3,) array_like
        The world point the camera looks at, metres.
    f0 : float
        The focal length at depth ``d0``, pixels.
    d0 : float
        The reference depth, metres.
    principal_point : (2,) tuple of float
        (cx, cy), pixels.
    image_offset : float
        Where the target is imaged, pixels right of the principal point.

    Returns
    -------
    Camera
        The camera, focal :math:`f_0\, d / d_0`, no distortion.

    Raises
    ------
    CamlabInputError
        A non-positive ``distance``, ``f0`` or ``d0``, or ``target`` not a 3-D point.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 6.3.1
       (moving the camera centre back along the principal axis while zooming).
    """
    distance = check_positive(distance, "distance", "metres")
    f = dolly_zoom_focal(f0, d0, distance)
    eye = orbit_eye(azimuth, elevation, distance, target)  # checks target: a 3-D point
    target = np.asarray(target, dtype=float)
    R = Camera.look_at(eye, target).R
    shift = float(image_offset) * d0 / f0  # metres right of the principal axis (camera x)
    centre = target - shift * R[0] - distance * R[2]
    return Camera(intrinsic_matrix(f, f, *principal_point), R, -R @ centre)


def dolly_zoom_errors(
    points_world: ArrayLike,
    distances: ArrayLike,
    azimuth: float,
    elevation: float,
    target: ArrayLike,
    f0: float = 800.0,
    d0: float = 4.0,
    approximation: Callable[[Camera, ArrayLike], np.ndarray] | None = None,
    image_offset: float = 0.0,
) -> np.ndarray:
    """RMS pixel distance between perspective and weak-perspective images along a dolly zoom.

    One value per distance of :func:`dolly_zoom_camera`: the perspective and weak-perspective
    images of ``points_world``, weak perspective about ``target`` (or
    ``approximation(camera, target)``, e.g. :func:`paraperspective_approximation`).

    The object keeps its image size while the depth range shrinks relative to the distance, so
    the error falls like 1 / d (lesson 05, section 2).

    Parameters
    ----------
    points_world : (N, 3) array_like
        The object's points, metres.
    distances : (D,) array_like
        The target depths along the dolly zoom, metres (positive).
    azimuth, elevation, target, f0, d0, image_offset
        As for :func:`dolly_zoom_camera`.
    approximation : callable, optional
        ``approximation(camera, target) -> (3, 4)`` affine camera; default
        :func:`affine_approximation`.

    Returns
    -------
    (D,) ndarray
        The RMS image distance at each distance, pixels.

    Raises
    ------
    CamlabInputError
        ``distances`` empty, not 1-D, or not all positive and finite.
    """
    ds = as_float(distances, "distances")
    if ds.ndim != 1 or len(ds) == 0 or not np.all(np.isfinite(ds) & (ds > 0)):
        raise CamlabInputError(
            f"distances: expected a non-empty 1-D array of positive distances in metres, got "
            f"{np.array2string(ds, precision=3, threshold=6)} (shape {ds.shape})"
        )
    out = []
    for d in ds:
        cam = dolly_zoom_camera(d, azimuth, elevation, target, f0, d0, image_offset=image_offset)
        out.append(
            np.sqrt(np.mean(weak_perspective_error(cam, points_world, target, approximation) ** 2))
        )
    return np.array(out)


class ThreeImages(NamedTuple):
    """One scene seen by a perspective camera and by its two affine simplifications.

    Attributes
    ----------
    perspective, weak, orthographic : (M, 2, 2) ndarray
        The segments' images, pixels for the first two, metres (camera x, y) for the orthographic one.
    P_weak, P_orth : (3, 4) ndarray
        The weak-perspective and orthographic matrices used.
    """

    perspective: np.ndarray
    weak: np.ndarray
    orthographic: np.ndarray
    P_weak: np.ndarray
    P_orth: np.ndarray


def three_images(camera: Camera, segments: ArrayLike) -> ThreeImages:
    """Segments seen by a camera, by its weak-perspective approximation and by orthography.

    The weak-perspective camera is :func:`affine_approximation` about the segments' centroid;
    the orthographic one (:func:`orthographic_matrix`) has ``camera``'s pose. See lesson 05,
    section 1.

    Parameters
    ----------
    camera : Camera
        The perspective camera.
    segments : (M, 2, 3) array_like
        World segments (two end points each), metres.

    Returns
    -------
    ThreeImages
        ``perspective``, ``weak`` (pixels) and ``orthographic`` (metres) images, (M, 2, 2)
        each, and the matrices ``P_weak`` and ``P_orth`` used.

    Raises
    ------
    CamlabInputError
        Segments not (M, 2, 3) or not finite.
    """
    perspective = project_segments(camera, segments)  # validates the segments
    segs = check_finite(
        np.asarray(segments, dtype=float), "segments"
    )  # the centroid needs every end point
    P_weak = affine_approximation(camera, segs.reshape(-1, 3).mean(axis=0))
    P_orth = orthographic_matrix(camera.R, camera.t)
    return ThreeImages(
        perspective, project_segments(P_weak, segs), project_segments(P_orth, segs), P_weak, P_orth
    )


class MatchedPoints(NamedTuple):
    """The two images of the same world points, where both fall inside the frame.

    Attributes
    ----------
    perspective, affine : (K, 2) ndarray
        The perspective and affine images, pixels; row k of each images the same world point.
    """

    perspective: np.ndarray
    affine: np.ndarray


def matched_points_in_frame(
    camera: Camera,
    P_affine: ArrayLike,
    segments: ArrayLike,
    size: tuple[int, int] = (640, 480),
    samples: int = 41,
) -> MatchedPoints:
    """The perspective and affine images of points along segments, where both are in the frame.

    Parameters
    ----------
    camera : Camera
        The perspective camera (its distortion is ignored).
    P_affine : (3, 4) array_like
        The affine camera compared with it.
    segments : (M, 2, 3) array_like
        World segments, metres.
    size : (2,) tuple of int
        The frame (width, height), pixels.
    samples : int
        Points sampled evenly along each segment, end points included (7 on a 6 m rail: one a
        metre).

    Returns
    -------
    MatchedPoints
        ``perspective`` and ``affine``, (K, 2) pixels each: the images of the K samples whose two
        images both fall inside the frame.

    Raises
    ------
    CamlabInputError
        Segments not (M, 2, 3) or not finite.
    """
    segs = check_finite(np.asarray(segments, dtype=float), "segments")
    if segs.ndim != 3 or segs.shape[1:] != (2, 3):
        raise CamlabInputError(
            f"segments: expected (M, 2, 3) pairs of world points, got shape {segs.shape}"
        )
    s = np.linspace(0.0, 1.0, samples)[None, :, None]
    X = (segs[:, :1] + s * (segs[:, 1:] - segs[:, :1])).reshape(-1, 3)
    a, b = camera.replace(dist=(0.0,) * 5).project(X), project_points(P_affine, X)
    w, h = size
    inside = np.all(
        [
            (p[:, 0] >= -0.5) & (p[:, 0] <= w - 0.5) & (p[:, 1] >= -0.5) & (p[:, 1] <= h - 0.5)
            for p in (a, b)
        ],
        axis=0,
    )
    return MatchedPoints(a[inside], b[inside])


def largest_gap_in_frame(
    camera: Camera,
    P_affine: ArrayLike,
    segments: ArrayLike,
    size: tuple[int, int] = (640, 480),
    samples: int = 41,
) -> float:
    """The largest pixel gap between the perspective and affine images of one point in the frame.

    Over ``samples`` points along each segment whose two images both fall inside the frame
    (:func:`matched_points_in_frame`): what a reader can see in the picture.

    Parameters
    ----------
    camera : Camera
        The perspective camera (its distortion is ignored).
    P_affine : (3, 4) array_like
        The affine camera compared with it.
    segments : (M, 2, 3) array_like
        World segments, metres.
    size : (2,) tuple of int
        The frame (width, height), pixels.
    samples : int
        Points sampled along each segment, end points included.

    Returns
    -------
    float
        The largest distance, pixels; NaN if no sample has both images in the frame.

    Raises
    ------
    CamlabInputError
        Segments not (M, 2, 3) or not finite.
    """
    a, b = matched_points_in_frame(camera, P_affine, segments, size, samples)
    return float(np.linalg.norm(a - b, axis=1).max()) if len(a) else float("nan")


def dolly_zoom_focal(f0: float, d0: float, d: float) -> float:
    r"""The focal length that keeps an object's image size fixed as the camera moves.

    Moving from distance ``d0`` to ``d``: the image size is :math:`\propto f / d`, so
    :math:`f = f_0 \, d / d_0` (the "Vertigo" dolly zoom).

    Parameters
    ----------
    f0 : float
        The focal length at distance ``d0``, pixels (> 0).
    d0 : float
        The starting distance, metres (> 0).
    d : float
        The new distance, metres (> 0).

    Returns
    -------
    float
        The focal length at ``d``, pixels.

    Raises
    ------
    CamlabInputError
        A non-positive argument.
    """
    return (
        check_positive(f0, "f0", "pixels")
        * check_positive(d, "d", "metres")
        / check_positive(d0, "d0", "metres")
    )
