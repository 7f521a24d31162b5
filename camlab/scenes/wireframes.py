"""Wireframes: (M, 2, 3) world segments in metres (lessons 04, 05, 11)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

from .._validate import check_matrix, check_positive
from .planes import Plane


def box_wireframe(
    centre: ArrayLike = (0.0, 0.0, 0.5), size: ArrayLike = (1.0, 1.0, 1.0)
) -> np.ndarray:
    """The 12 edges of an axis-aligned box as (12, 2, 3) segments (metres).

    Parameters
    ----------
    centre : (3,) array_like
        The box's centre, metres.
    size : (3,) array_like
        Its extent along x, y and z, metres.

    Returns
    -------
    (12, 2, 3) ndarray
        Each edge's two ends, world metres.
    """
    c = check_matrix(centre, (3,), "centre")
    s = check_matrix(size, (3,), "size")
    corners = (
        np.array([[i, j, k] for i in (-0.5, 0.5) for j in (-0.5, 0.5) for k in (-0.5, 0.5)]) * s + c
    )
    edges = [(a, b) for a in range(8) for b in range(a + 1, 8) if bin(a ^ b).count("1") == 1]
    return corners[np.array(edges)]


def house_wireframe(centre: ArrayLike = (0.0, 0.0, 0.0), size: float = 1.0) -> np.ndarray:
    """A house (box body, gable roof, door) standing on z = 0 at ``centre``, as (M, 2, 3) segments.

    At ``size`` 1 the body is 1.0 m (x) by 1.4 m (y) by 1.0 m high, the ridge 1.55 m up along y,
    the door on the face x = -0.5.

    Parameters
    ----------
    centre : (3,) array_like
        Where the middle of the house's footprint stands, metres.
    size : float
        Scale factor (> 0).

    Returns
    -------
    (20, 2, 3) ndarray
        The body's 12 edges, the roof's 5 and the door's 3, world metres.
    """
    c = check_matrix(centre, (3,), "centre")
    s = check_positive(size, "size", "metres")
    body = box_wireframe((0.0, 0.0, 0.5), (1.0, 1.4, 1.0))
    r0, r1 = np.array([0.0, -0.7, 1.55]), np.array([0.0, 0.7, 1.55])
    top = [(-0.5, 1.0), (0.5, 1.0)]
    roof = [[r0, r1]]
    for y, r in ((-0.7, r0), (0.7, r1)):
        for x, z in top:
            roof.append([[x, y, z], r])
    door = [
        [[-0.5, -0.15, 0.0], [-0.5, -0.15, 0.6]],
        [[-0.5, -0.15, 0.6], [-0.5, 0.15, 0.6]],
        [[-0.5, 0.15, 0.6], [-0.5, 0.15, 0.0]],
    ]
    segs = np.concatenate([body, np.array(roof, dtype=float), np.array(door, dtype=float)])
    return segs * s + c


def ground_grid(extent: float = 2.0, step: float = 0.5, z: float = 0.0) -> np.ndarray:
    """Grid lines on the plane z = ``z`` covering [-extent, extent]^2, as (M, 2, 3) segments.

    Parameters
    ----------
    extent : float
        Half-width of the square grid, metres (> 0).
    step : float
        Spacing of the lines, metres (> 0).
    z : float
        Height of the plane, metres.

    Returns
    -------
    (M, 2, 3) ndarray
        The lines along y (at each x tick), then the lines along x, world metres.
    """
    e = check_positive(extent, "extent", "metres")
    st = check_positive(step, "step", "metres")
    ticks = np.arange(-e, e + 1e-9, st)
    segs = [[[x, -e, z], [x, e, z]] for x in ticks] + [[[-e, y, z], [e, y, z]] for y in ticks]
    return np.array(segs, dtype=float)


def plane_outlines(planes: Sequence[Plane | Sequence[Plane]]) -> np.ndarray:
    """The four edges of every plane's rectangle as (4 M, 2, 3) segments, metres.

    ``planes`` may nest lists (a :func:`box` is a list of six faces), like a scene for
    :func:`camlab.render.render`. Edges run top-left, top-right, bottom-right, bottom-left.

    Parameters
    ----------
    planes : sequence of Plane or of sequences of Plane
        The planes (one level of nesting).

    Returns
    -------
    (4 M, 2, 3) ndarray
        Four edges per plane, world metres.
    """
    segments = []
    for item in planes:
        for plane in item if isinstance(item, (list, tuple)) else [item]:
            c = plane.corners_world
            segments += [(c[i], c[(i + 1) % 4]) for i in range(4)]
    return np.array(segments, dtype=float).reshape(-1, 2, 3)
