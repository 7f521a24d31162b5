"""The epipolar geometry of two cameras in 3-D (lesson 11): a static figure.

Two camera centres C and C', the baseline between them, a world point X, the epipolar plane
through the three, each camera's image plane and the epipolar line where the epipolar plane cuts
it. Drawn for the original cameras, the picture shows why a match lies on a line; drawn for the
rectified cameras (both rotated about their own centres to one orientation whose x axis is the
baseline) it shows why rectified matches share a row: the two image planes become one plane
parallel to the baseline, and the epipolar plane cuts it along one row of both images.

Typical use::

    from camlab.plotting import epipolar3d, scene3d
    ax = scene3d.axes3d(fig, 121)
    epipolar3d.draw_epipolar_geometry(ax, camera1, camera2, X)
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ..camera import Camera
from . import palette
from .view3d import set_equal_aspect

__all__ = [
    "draw_epipolar_geometry",
    "epipolar_line_ends",
    "image_plane_corners",
    "image_plane_points",
]


def image_plane_points(camera: Camera, uv: ArrayLike, size: float) -> np.ndarray:
    """Pixels lifted onto the image plane drawn ``size`` metres in front of ``camera``.

    Parameters
    ----------
    camera : Camera
        The camera (world frame).
    uv : (N, 2) array_like
        Pixels (u, v).
    size : float
        Depth of the drawn image plane, metres (z_c = ``size``).

    Returns
    -------
    (N, 3) ndarray
        The world points on the pixels' rays at depth ``size``.
    """
    uv = np.atleast_2d(np.asarray(uv, dtype=float))
    rays = np.linalg.solve(camera.K, np.column_stack([uv, np.ones(len(uv))]).T).T
    return (rays * size - camera.t) @ camera.R


def image_plane_corners(camera: Camera, size: float) -> np.ndarray:
    """The four corners of ``camera``'s image, ``size`` metres in front of its centre.

    Parameters
    ----------
    camera : Camera
        The camera; its ``image_size`` (width, height) in pixels bounds the image.
    size : float
        Depth of the drawn image plane, metres.

    Returns
    -------
    (4, 3) ndarray
        World points of the pixel corners (-0.5, -0.5), (W - 0.5, -0.5), (W - 0.5, H - 0.5),
        (-0.5, H - 0.5): pixel centres sit at integers, so the image's edge is half a pixel out.
    """
    w, h = camera.image_size
    uv = np.array([[-0.5, -0.5], [w - 0.5, -0.5], [w - 0.5, h - 0.5], [-0.5, h - 0.5]])
    return image_plane_points(camera, uv, size)


def epipolar_line_ends(camera: Camera, other: Camera, X: ArrayLike) -> np.ndarray:
    r"""Where the epipolar plane of ``X`` enters and leaves ``camera``'s image, in pixels.

    The epipolar line joins the image of ``X`` and the epipole (the image of the other centre):
    :math:`l = \tilde x \times \tilde e`, clipped to the image rectangle.

    Parameters
    ----------
    camera, other : Camera
        The camera whose image the line crosses, and the other camera of the pair.
    X : (3,) array_like
        The world point, metres.

    Returns
    -------
    (2, 2) ndarray
        The two ends (u, v) of the line inside the image.
    """
    x = camera.P @ np.append(np.asarray(X, dtype=float), 1.0)
    e = camera.P @ np.append(other.centre, 1.0)
    a, b, c = np.cross(x, e)
    w, h = camera.image_size
    if abs(b) >= abs(a):  # mostly horizontal: evaluate at the left and right edges
        u = np.array([-0.5, w - 0.5])
        return np.column_stack([u, -(a * u + c) / b])
    v = np.array([-0.5, h - 0.5])
    return np.column_stack([-(b * v + c) / a, v])


def draw_epipolar_geometry(
    ax,
    camera1: Camera,
    camera2: Camera,
    X: ArrayLike,
    size: float = 0.3,
    plane_color: str | None = None,
    ghosts: tuple[Camera, Camera] | None = None,
    also: ArrayLike | None = None,
) -> None:
    """Draw two cameras' centres and image planes, the baseline, X, its rays and epipolar plane.

    Parameters
    ----------
    ax : Axes3D
        A 3-D axes (world z up).
    camera1, camera2 : Camera
        The two cameras (world frame, ``image_size`` set).
    X : (3,) array_like
        The world point, metres.
    size : float
        Depth of the drawn image planes in front of the centres, metres.
    plane_color : str or None
        Colour of both image planes' outlines; None (the default) draws each in its camera's
        colour, as the centres: camera 1 (C) blue, camera 2 (C') orange.
    ghosts : (Camera, Camera) or None
        Two more cameras whose image planes are drawn dashed in light grey (the original cameras
        behind a rectified pair).
    also : (N, 3) array_like or None
        More world points, normally on the epipolar plane: each drawn as an open circle with its
        two rays (dotted) and its images (open circles), which then lie on the same red lines.
    """
    X = np.asarray(X, dtype=float)
    C1, C2 = camera1.centre, camera2.centre
    tri = np.array([C1, C2, X])
    ax.plot_trisurf(*tri.T, color=palette.RED, alpha=0.15, linewidth=0)
    ax.plot(*np.array([C1, C2]).T, color="k", lw=2)  # the baseline
    for C in (C1, C2):
        ax.plot(*np.array([C, X]).T, color="0.25", lw=1, ls=(0, (4, 2)))  # the rays
    own = (palette.BLUE, palette.ORANGE) if plane_color is None else (plane_color,) * 2
    for cams, colours, style, lw in (
        (ghosts, ("0.6",) * 2, ":", 1.2),
        ((camera1, camera2), own, "-", 1.6),
    ):
        if cams is None:
            continue
        for cam, colour in zip(cams, colours, strict=True):
            corners = image_plane_corners(cam, size)
            ax.plot(*np.vstack([corners, corners[:1]]).T, color=colour, lw=lw, ls=style)
    for cam, other in ((camera1, camera2), (camera2, camera1)):
        ends = image_plane_points(cam, epipolar_line_ends(cam, other, X), size)
        ax.plot(*ends.T, color=palette.RED, lw=2)
        x = image_plane_points(cam, cam.project(X[None])[:1], size)[0]
        ax.plot(*x, "o", color=palette.RED, ms=4)
    ax.plot(*X, "o", color="k", ms=6)
    ax.text(*X, "  X", fontsize=10)
    for Y in np.zeros((0, 3)) if also is None else np.atleast_2d(np.asarray(also, dtype=float)):
        for cam in (camera1, camera2):
            ax.plot(*np.array([cam.centre, Y]).T, color="0.25", lw=1, ls=":")
            y = image_plane_points(cam, cam.project(Y[None])[:1], size)[0]
            ax.plot(*y, "o", mfc="w", mec=palette.RED, mew=1.5, ms=5)
        ax.plot(*Y, "o", mfc="w", mec="k", mew=1.5, ms=6)
        ax.text(*Y, "  Y", fontsize=10)
    for C, name, colour in ((C1, "C", palette.BLUE), (C2, "C'", palette.ORANGE)):
        ax.plot(*C, "o", color=colour, mec="k", ms=7)
        ax.text(
            C[0],
            C[1],
            C[2] - 0.02,
            name,
            fontsize=10,
            ha="center",
            va="top",
            color=colour,
            fontweight="bold",
            path_effects=palette.halo(),
        )
    pts = [tri] + [image_plane_corners(c, size) for c in (camera1, camera2)]
    set_equal_aspect(ax, pts, tight=True)
    ax.locator_params(nbins=4)
    ax.tick_params(labelsize=8.5, pad=0)
    ax.set_xlabel("x (m)", fontsize=9.5, labelpad=0)
    ax.set_ylabel("y, ahead (m)", fontsize=9.5, labelpad=0)
    ax.set_zlabel("z, up (m)", fontsize=9.5, labelpad=0)
