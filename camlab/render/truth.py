r"""The ground truth of a rendered image, computed analytically (never measured on the image).

The pixel of every named plane point, and the depth map.
"""

from __future__ import annotations

import numpy as np

from .. import distortion as _dist
from .. import lens as _lens
from .._validate import (
    CamlabInputError,
    check_positive,
)
from ..scenes import Plane
from .model import CameraPlane, Defocus, GroundTruth, PlanePoints, project

__all__ = []


def ground_truth(
    planes: list[Plane],
    geo: list[CameraPlane],
    K: np.ndarray,
    d: np.ndarray,
    R: np.ndarray,
    t: np.ndarray,
    size: tuple[int, int],
    depth: bool,
) -> GroundTruth:
    """Stage 6: exact pixels of every named point (projected, never measured), visibility, depth map.

    A point is visible when it is in front of the camera, inside the image and no plane of the
    scene meets its ray nearer. Planes that were culled (behind the camera, back faces) still get
    an entry, all invisible.

    Parameters
    ----------
    planes : list of Plane
        The whole scene, flattened.
    geo : list of CameraPlane
        Its visible planes (:func:`~camlab.render.canvas.visible_planes`).
    K : (3, 3) ndarray
        Intrinsics, pixels.
    d : (5,) ndarray
        Distortion ``(k1, k2, p1, p2, k3)``.
    R : (3, 3) ndarray
        cam_from_world rotation.
    t : (3,) ndarray
        cam_from_world translation, metres.
    size : (width, height)
        Image size, pixels.
    depth : bool
        Compute the depth map (z_cam of the nearest plane through each pixel centre).

    Returns
    -------
    GroundTruth
        The camera, and each named plane's :class:`PlanePoints`; ``depth`` None unless asked.
    """
    w, h = size
    truth = GroundTruth(
        K=K,
        dist=d,
        R=R,
        t=t,
        size=(w, h),
        points={},
        depth=_depth_map(geo, K, d, w, h) if depth else None,
    )
    for g in geo:
        p = g.plane
        if len(p.points):
            wp = p.world_points
            px = project(wp, K, R, t, d)
            zc = (wp @ R.T + t)[:, 2]
            inside = (
                (zc > 0)
                & (px[:, 0] >= -0.5)
                & (px[:, 0] <= w - 0.5)
                & (px[:, 1] >= -0.5)
                & (px[:, 1] <= h - 0.5)
            )
            vis = inside.copy()
            if inside.any():  # occluded if another plane meets the point's ray in front of it
                Xc = wp[inside] @ R.T + t
                vis[inside] = _nearest_hit(Xc / Xc[:, 2:3], geo) >= Xc[:, 2] * (1 - 1e-6)
            truth.points[p.name] = PlanePoints(p.object_points, wp, px, vis, p.pattern_size)
    for (
        p
    ) in planes:  # culled planes (behind the camera, back faces) still get an entry, all invisible
        if len(p.points) and p.name not in truth.points:
            wp = p.world_points
            truth.points[p.name] = PlanePoints(
                p.object_points,
                wp,
                project(wp, K, R, t, d),
                np.zeros(len(wp), bool),
                p.pattern_size,
            )
    return truth


def flatten(scene) -> list[Plane]:
    """The planes of a scene: a Plane, or nested lists of them, as one flat list.

    Parameters
    ----------
    scene : Plane or iterable
        A plane, or an iterable of planes and of such iterables (e.g. a :func:`camlab.scenes.box`).

    Returns
    -------
    list of Plane
        The planes in order.

    Raises
    ------
    CamlabInputError
        If something in ``scene`` is neither a Plane nor iterable, or there is no plane at all.
    """
    if isinstance(scene, Plane):
        return [scene]
    out: list[Plane] = []
    try:
        items = list(scene)
    except TypeError:
        raise CamlabInputError(
            f"scene: expected a Plane or a list of Planes, got {type(scene).__name__}"
        ) from None
    for item in items:
        out += flatten(item)
    if not out:
        raise CamlabInputError("scene: expected at least one Plane, got an empty scene")
    return out


def coc_pixels(defocus: Defocus, K: np.ndarray, depth: float) -> float:
    """Diameter of the circle of confusion of a plane at ``depth``, in pixels.

    The thin-lens circle of confusion (:func:`camlab.lens.circle_of_confusion`) for the lens of
    ``defocus`` focused at its ``focus_distance``, divided by the pixel pitch.

    Parameters
    ----------
    defocus : Defocus
        f-number, focus distance and pixel pitch (m); its focal length, or ``K[0, 0]`` times the
        pitch when None.
    K : (3, 3) ndarray
        Intrinsics, pixels.
    depth : float
        Depth of the plane, metres.

    Returns
    -------
    float
        The blur's diameter, pixels.

    Raises
    ------
    CamlabInputError
        If the pixel pitch is not positive.
    """
    pitch = check_positive(defocus.pixel_pitch, "pixel_pitch", "metres")
    f = defocus.focal_length if defocus.focal_length is not None else K[0, 0] * pitch
    return (
        float(_lens.circle_of_confusion(f, defocus.f_number, defocus.focus_distance, depth)) / pitch
    )


def _nearest_hit(rays: np.ndarray, geo) -> np.ndarray:
    """Depth z_cam where each ray ``(x, y, 1)`` first meets a plane of the scene (inf: none)."""
    depth = np.full(len(rays), np.inf)
    for p, Rc, tc, *_ in geo:  # CameraPlane rows
        n = Rc[:, 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            z = (n @ tc) / (rays @ n)  # the plane n . X = n . tc meets the ray z * (x, y, 1) here
            loc = (rays * z[:, None] - tc) @ Rc[:, :2]  # hit point in plane coordinates
        x0, y0, x1, y1 = p.extent
        hit = (
            (z > 0) & (loc[:, 0] >= x0) & (loc[:, 0] <= x1) & (loc[:, 1] >= y0) & (loc[:, 1] <= y1)
        )
        depth = np.where(hit & (z < depth), z, depth)
    return depth


def _depth_map(geo, K, d, w, h) -> np.ndarray:
    """z_cam of the nearest plane through each pixel centre (inf for background)."""
    if d.any():
        maps = _dist.distort_map(K, d, (w, h), step=4)
        ideal = np.stack([maps.map_u.ravel(), maps.map_v.ravel()], axis=1).astype(float)
    else:
        u, v = np.meshgrid(np.arange(w, dtype=float), np.arange(h, dtype=float))
        ideal = np.stack([u.ravel(), v.ravel()], axis=1)
    xy = _dist.pixels_to_normalised(ideal, K)
    return _nearest_hit(np.column_stack([xy, np.ones(len(xy))]), geo).reshape(h, w)
