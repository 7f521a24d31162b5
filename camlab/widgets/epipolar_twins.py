"""The per-move arithmetic of lesson 11's ``epipolar_lines``: the numpy twins of ``geometry.js``.

The demo's ``update`` calls these, and the browser (``camlab/widgets/browser/geometry.js``) runs a
JavaScript function of the same name in camelCase on every move of a control;
``tests/test_browser_epipolar_parity.py`` runs both on random inputs and compares them.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .. import epipolar as ep
from .. import fixtures
from ..camera import Camera

__all__ = [
    "DEPTHS",
    "MOTIONS",
    "EpipolarView",
    "epipolar_view",
    "line_polyline",
    "projected_segments",
]

MOTIONS = {
    "sideways (stereo rig)": fixtures.stereo_pair,
    "forward (driving)": fixtures.forward_pair,
}
"""The demo's two motions by the names its buttons show: the camera pair for (baseline, turn)."""

DEPTHS = np.arange(1.0, 7.0)
"""The depths (m) along the left pixel's ray whose images mark the epipolar line: 1, ..., 6."""


def line_polyline(lines: np.ndarray, size: tuple[int, int] = (640, 480)) -> np.ndarray:
    """Lines (K, 3) as one NaN-separated polyline spanning the image (matplotlib clips the rest).

    Mostly horizontal lines are evaluated at the left and right image edges, mostly vertical ones
    at the top and bottom: v = -(a u + c) / b or u = -(b v + c) / a. The result does not depend on
    a line's scale or sign.

    Parameters
    ----------
    lines : (K, 3) ndarray
        Lines (a, b, c); a NaN row, or (0, 0, c), gives NaN ends.
    size : (width, height)
        The image, pixels.

    Returns
    -------
    (3 K, 2) ndarray
        Each line's two ends and a NaN row.
    """
    w, h = size
    out = np.full((len(lines), 3, 2), np.nan)
    for i, (a, b, c) in enumerate(lines):
        if abs(b) >= abs(a):
            u = np.array([-0.5, w - 0.5])
            out[i, :2] = np.column_stack([u, -(a * u + c) / b])
        elif a != 0:
            v = np.array([-0.5, h - 0.5])
            out[i, :2] = np.column_stack([-(b * v + c) / a, v])
    return out.reshape(-1, 2)


def projected_segments(cam: Camera, segs: np.ndarray) -> np.ndarray:
    """World segments as one NaN-separated polyline in pixels (for a single Line2D).

    Parameters
    ----------
    cam : Camera
        The camera.
    segs : (M, 2, 3) ndarray
        Segments in the world, metres.

    Returns
    -------
    (3 M, 2) ndarray
        Each segment's two pixels (NaN for an end behind the camera) and a NaN row.
    """
    uv = cam.project(segs.reshape(-1, 3)).reshape(-1, 2, 2)
    out = np.full((len(uv), 3, 2), np.nan)
    out[:, :2] = uv
    return out.reshape(-1, 2)


class EpipolarView(NamedTuple):
    """What :func:`epipolar_view` returns: the two cameras and the lines and points the demo draws.

    Attributes
    ----------
    cameras : CameraPair
        The left (first) and the right (second) camera.
    F : (3, 3) ndarray
        :func:`camlab.epipolar.fundamental_from_cameras`: ``x2^T F x1 = 0``, unit norm.
    line_right : (3,) ndarray
        l' = F x, the point's epipolar line in the right image (a^2 + b^2 = 1).
    line_left : (3,) ndarray
        l = x x e, the line through the point and the left epipole (unscaled).
    pencil_right, pencil_left : (K, 3) ndarray
        The same for each reference pixel; NaN rows for a pixel at the left epipole (no line).
    depth_points : (6, 2) ndarray
        The right images of the points at :data:`DEPTHS` along the left pixel's ray, pixels.
    epipoles : (2, 3) ndarray
        The images of the other camera's centre, ``P C'`` and ``P' C``: the epipoles e and e'
        with a sign that says on which side the other camera is (w < 0: behind).
    """

    cameras: fixtures.CameraPair
    F: np.ndarray
    line_right: np.ndarray
    line_left: np.ndarray
    pencil_right: np.ndarray
    pencil_left: np.ndarray
    depth_points: np.ndarray
    epipoles: np.ndarray


def epipolar_view(
    motion: str, baseline: float, toe_in_deg: float, point: np.ndarray, ref: np.ndarray
) -> EpipolarView:
    """The two cameras of ``motion`` and what :func:`~camlab.widgets.stereo_rectification.epipolar_lines` draws.

    Parameters
    ----------
    motion : str
        A key of :data:`MOTIONS`.
    baseline : float
        The baseline, metres.
    toe_in_deg : float
        The toe-in (sideways: in all) or the second camera's turn (forward), degrees.
    point : (2,) ndarray
        The left pixel (u, v).
    ref : (K, 2) ndarray
        The reference pixels whose pencils of lines are drawn.

    Returns
    -------
    EpipolarView
        The cameras, F, the point's two lines, the pencils, the depth marks and the epipoles.
    """
    c1, c2 = cams = MOTIONS[motion](baseline, np.deg2rad(toe_in_deg))
    F = ep.fundamental_from_cameras(c1, c2)
    e1 = c1.P @ np.append(c2.centre, 1.0)
    e2 = c2.P @ np.append(c1.centre, 1.0)
    x = np.asarray(point, dtype=float)
    pencil_right = ep.epipolar_lines(F, ref, image=1)
    pencil_left = np.cross(np.column_stack([ref, np.ones(len(ref))]), e1)
    pencil_left[np.isnan(pencil_right[:, 0])] = np.nan  # no line at the epipole, in either image
    ray = c1.backproject(np.tile(x, (len(DEPTHS), 1)), DEPTHS)  # world points that all image to x
    return EpipolarView(
        cameras=cams,
        F=F,
        line_right=ep.epipolar_lines(F, x, image=1),
        line_left=np.cross(np.append(x, 1.0), e1),
        pencil_right=pencil_right,
        pencil_left=pencil_left,
        depth_points=c2.project(ray),
        epipoles=np.array([e1, e2]),
    )
