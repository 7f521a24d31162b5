"""The per-move arithmetic of lesson 07's browser-drawn demos: the numpy twins of ``homography.js``.

Each demo's ``update`` calls these, and the browser (``camlab/widgets/browser/homography.js``)
runs a JavaScript function of the same name in camelCase on every slider move;
``tests/test_browser_homography_parity.py`` runs both on random inputs and compares them. The
picture the browser warps pixel by pixel is :func:`camlab.warp.warp_perspective`'s numpy path
(its twin ``warpPerspective``), whose float32 arithmetic the JavaScript repeats step for step.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, NamedTuple

import numpy as np

from ... import homography as hg
from ...projective import LINE_AT_INFINITY, clip_line, map_lines, map_points, map_polyline
from ...projective import splits_at_infinity as _splits

__all__ = ["HierarchyView", "diagonal_points", "hierarchy_fixed", "hierarchy_view"]


def diagonal_points(picture_shape: tuple[int, ...]) -> np.ndarray:
    """The four points whose cross-ratio the hierarchy demo measures (on the picture's diagonal).

    They lie 0, 1/3, 2/3 and 1 of the way from its top-left pixel centre to its bottom-right one:
    none at the middle, which H (acting about the picture's centre) never moves, so each point's
    open "before" ring shows beside or around its filled "after" dot.

    Parameters
    ----------
    picture_shape : tuple of int
        The picture's shape (height, width, ...).

    Returns
    -------
    (4, 2) ndarray
        The points, source px.
    """
    ph, pw = picture_shape[:2]
    return np.array([[0.0], [1 / 3], [2 / 3], [1.0]]) * [pw - 1.0, ph - 1.0]


def hierarchy_fixed(picture_shape: tuple[int, ...], canvas_hw: tuple[int, int]) -> dict:
    """The constants of ``transformation_hierarchy`` that :func:`hierarchy_view` needs (its ``fixed``).

    Parameters
    ----------
    picture_shape : tuple of int
        The picture's shape (height, width, ...).
    canvas_hw : tuple of int
        The canvas (height, width), px.

    Returns
    -------
    dict
        ``C`` (the origin to the canvas's centre) and ``P`` (the picture's centre to the origin),
        pixel centres at integers; ``grid_lines``: the picture's 40-pixel tile edges (at -0.5 + 40 k),
        60 samples each, dense so the mapped polylines follow the picture up to its tear;
        ``diagonal`` (:func:`diagonal_points`); ``corners``: the picture's corner pixels; ``xlim``
        and ``ylim``: the canvas's edges.
    """
    ph, pw = picture_shape[:2]
    C = np.array([[1.0, 0, (canvas_hw[1] - 1) / 2], [0, 1, (canvas_hw[0] - 1) / 2], [0, 0, 1]])
    P = np.array([[1.0, 0, -(pw - 1) / 2], [0, 1, -(ph - 1) / 2], [0, 0, 1]])
    samples = np.linspace(0, 1, 60)
    xs_edge, ys_edge = np.linspace(-0.5, pw - 0.5, 5), np.linspace(-0.5, ph - 0.5, 4)
    grid_lines = [np.column_stack([np.full(60, x), -0.5 + samples * ph]) for x in xs_edge]
    grid_lines += [np.column_stack([-0.5 + samples * pw, np.full(60, y)]) for y in ys_edge]
    return dict(
        C=C,
        P=P,
        grid_lines=grid_lines,
        diagonal=diagonal_points(picture_shape),
        corners=np.array([[0, 0], [pw - 1, 0], [pw - 1, ph - 1], [0, ph - 1]], float),
        xlim=(-0.5, canvas_hw[1] - 0.5),
        ylim=(-0.5, canvas_hw[0] - 0.5),
    )


class HierarchyView(NamedTuple):
    r"""What ``transformation_hierarchy`` draws at one setting of its controls.

    Attributes
    ----------
    Hg : (3, 3) ndarray
        The group's matrix, in coordinates centred on the picture and on the canvas.
    H : (3, 3) ndarray
        The map drawn, source pixels to canvas pixels: C Hg P (normalised, h33 = 1).
    kind : str
        The smallest group holding ``Hg`` (:func:`camlab.homography.classify`).
    grid : (M, 2) ndarray
        The picture's tile edges mapped by H, one polyline with a NaN row after each edge (and
        where an edge passes through infinity, :func:`camlab.projective.map_polyline`).
    diagonal : (4, 2) ndarray
        The four points of the cross-ratio, mapped by H.
    vanishing : (2, 2) ndarray
        The vanishing line :math:`H^{-T} l_\infty` clipped to the canvas (NaN rows when it
        misses it).
    torn : bool
        Whether the line H sends to infinity crosses the picture.
    """

    Hg: np.ndarray
    H: np.ndarray
    kind: str
    grid: np.ndarray
    diagonal: np.ndarray
    vanishing: np.ndarray
    torn: bool


def hierarchy_view(values: Mapping[str, Any], fixed: Mapping[str, Any]) -> HierarchyView:
    r"""The moving geometry of ``transformation_hierarchy`` at one setting of its controls.

    :math:`H_g` is :func:`camlab.homography.hierarchy_matrix` of the chosen group (angles in
    degrees on the sliders, the projective row in units of 1e-3 per pixel); the map drawn is
    :math:`H = C H_g P` (:func:`camlab.homography.compose`), P moving the picture's centre to the
    origin and C the origin to the canvas's centre. Lines map by :math:`H^{-T}`, so the image of
    the line at infinity is the vanishing line :math:`H^{-T} (0, 0, 1)^T`.

    Parameters
    ----------
    values : mapping
        The controls: ``group`` (str), ``theta``, ``phi`` (degrees), ``scale``, ``aspect``,
        ``tx``, ``ty`` (px), ``v1``, ``v2`` (1e-3 / px).
    fixed : mapping
        The scene: ``C``, ``P`` ((3, 3)), ``grid_lines`` (sequence of (K, 2) polylines, source
        px), ``diagonal`` ((4, 2) source px), ``corners`` ((4, 2) the picture's corners, px),
        ``xlim``, ``ylim`` (the canvas, px, low first).

    Returns
    -------
    HierarchyView
        The matrices, the smallest group, the mapped grid, diagonal and vanishing line, and
        whether the picture is torn.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 2.4 (a
       hierarchy of transformations) and result 2.17 (the line at infinity under H).
    """
    Hg = hg.hierarchy_matrix(
        values["group"],
        theta=np.radians(values["theta"]),
        scale=values["scale"],
        shear=np.radians(values["phi"]),
        aspect=values["aspect"],
        tx=values["tx"],
        ty=values["ty"],
        v=(values["v1"] * 1e-3, values["v2"] * 1e-3),
    )
    H = hg.compose(fixed["C"], Hg, fixed["P"])
    pieces = [
        np.vstack([map_polyline(H, line), [[np.nan, np.nan]]]) for line in fixed["grid_lines"]
    ]
    vanishing = clip_line(map_lines(H, LINE_AT_INFINITY), fixed["xlim"], fixed["ylim"])
    return HierarchyView(
        Hg=Hg,
        H=H,
        kind=hg.classify(Hg),
        grid=np.vstack(pieces),
        diagonal=map_points(H, fixed["diagonal"]),
        vanishing=vanishing,
        torn=_splits(H, fixed["corners"]),
    )
