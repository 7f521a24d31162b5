"""The per-move arithmetic of lesson 07's browser-drawn demos: the numpy twins of ``homography.js``.

Each demo's ``update`` calls these, and the browser (``camlab/widgets/browser/homography.js``)
runs a JavaScript function of the same name in camelCase on every slider move;
``tests/test_browser_homography_parity.py`` runs both on random inputs and compares them. The
picture the browser warps pixel by pixel is :func:`camlab.warp.warp_perspective`'s numpy path
(its twin ``warpPerspective``), whose float32 arithmetic the JavaScript repeats step for step;
the forward warp is :func:`camlab.warp.forward_warp` (its twin ``forwardWarp``).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, NamedTuple

import numpy as np
from matplotlib.colors import to_rgb

from ... import homography as hg
from ...plotting import palette
from ...projective import LINE_AT_INFINITY, clip_line, map_lines, map_points, map_polyline
from ...projective import splits_at_infinity as _splits
from ...warp import forward_warp, warp_perspective

__all__ = [
    "HOLE_COLOUR",
    "OUTSIDE_GREY",
    "ForwardInverseView",
    "HierarchyView",
    "covered_area",
    "diagonal_points",
    "forward_inverse_fixed",
    "forward_inverse_view",
    "hierarchy_fixed",
    "hierarchy_view",
]


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


# ----------------------------------------------------------------------------- forward vs inverse

HOLE_COLOUR = tuple(round(255 * c) for c in to_rgb(palette.HOLE))
"""The forward warp's holes inside the area the picture covers: lime (palette.HOLE), a hue the picture
does not contain, so holes never read as its dark border (outside the picture both panels are a mid
grey, OUTSIDE_GREY)."""
OUTSIDE_GREY = 128
FORWARD_TILT = (1e-3, 0.0)
"""The projective row v of ``forward_vs_inverse``'s fixed slight tilt, per pixel."""


def forward_inverse_fixed(picture_shape: tuple[int, ...], out_hw: tuple[int, int]) -> dict:
    """The constants of ``forward_vs_inverse`` that :func:`forward_inverse_view` needs (its ``fixed``).

    Parameters
    ----------
    picture_shape : tuple of int
        The picture's shape (height, width, ...).
    out_hw : tuple of int
        The output (height, width), px.

    Returns
    -------
    dict
        ``C`` (the origin to the output's centre, (119.5, 89.5) for 240 x 180: pixel centres at
        integers), ``P`` (the picture's centre to the origin), ``tilt`` (the projective row v),
        ``edges`` (the picture's outline, its pixels' outer edges: -0.5 to size - 0.5),
        ``shape`` (``out_hw``), ``hole`` (:data:`HOLE_COLOUR`) and ``outside``
        (:data:`OUTSIDE_GREY`).
    """
    ph, pw = picture_shape[:2]
    return dict(
        C=np.array([[1.0, 0, (out_hw[1] - 1) / 2], [0, 1, (out_hw[0] - 1) / 2], [0, 0, 1]]),
        P=np.array([[1.0, 0, -(pw - 1) / 2], [0, 1, -(ph - 1) / 2], [0, 0, 1]]),
        tilt=np.array(FORWARD_TILT),
        edges=np.array([[-0.5, -0.5], [pw - 0.5, -0.5], [pw - 0.5, ph - 0.5], [-0.5, ph - 0.5]]),
        shape=tuple(int(c) for c in out_hw),
        hole=HOLE_COLOUR,
        outside=OUTSIDE_GREY,
    )


def covered_area(outline: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    r"""The pixels whose centre lies inside a convex polygon (or on its edge): what a picture covers.

    A point p is inside a convex polygon when it lies on the same side of every edge a -> b: the
    cross products :math:`(b - a) \times (p - a)` all have one sign (zero on an edge).

    Parameters
    ----------
    outline : (K, 2) ndarray
        The polygon's corners in order (either way round), px; pixel centres at integers.
    shape : tuple of int
        The output (height, width).

    Returns
    -------
    (height, width) bool ndarray
        True inside; all False where a corner is not finite.
    """
    v, u = np.mgrid[0 : shape[0], 0 : shape[1]].astype(float)
    sides = np.array(
        [
            (b[0] - a[0]) * (v - a[1]) - (b[1] - a[1]) * (u - a[0])
            for a, b in zip(outline, np.roll(outline, -1, axis=0), strict=True)
        ]
    )
    return np.all(sides >= 0, axis=0) | np.all(sides <= 0, axis=0)


def _painted_warps(
    forward: np.ndarray,
    inverse: np.ndarray,
    covered: np.ndarray,
    reached: np.ndarray,
    pulled: np.ndarray,
    hole: tuple[int, int, int] = HOLE_COLOUR,
    outside: int = OUTSIDE_GREY,
) -> tuple[np.ndarray, np.ndarray]:
    """The two warps as ``forward_vs_inverse`` shows them: holes black, outside the picture grey.

    Parameters
    ----------
    forward, inverse : (h, w, 3) uint8 ndarray
        The forward and the inverse warp.
    covered, reached, pulled : (h, w) bool ndarray
        The area the picture covers (:func:`covered_area`), the pixels a source pixel was pushed
        to, the pixels that pulled a source pixel.
    hole : tuple of int
        The holes' colour (RGB).
    outside : int
        The grey level outside the picture.

    Returns
    -------
    tuple of (h, w, 3) uint8 ndarray
        The forward warp with ``hole`` where it covers but was not reached and ``outside``
        beyond the picture; the inverse warp with ``outside`` where it pulled nothing.
    """
    shown = forward.copy()
    shown[covered & ~reached] = hole
    shown[~covered] = outside
    inv = inverse.copy()
    inv[~pulled] = outside
    return shown, inv


class ForwardInverseView(NamedTuple):
    """What ``forward_vs_inverse`` draws at one setting of its controls.

    Attributes
    ----------
    H : (3, 3) ndarray
        Source pixels to output pixels: C S(scale, angle) V P (normalised, h33 = 1).
    outline : (4, 2) ndarray
        The picture's outline mapped by H, output px.
    shown : (h, w, 3) uint8 ndarray
        The forward warp as shown (:func:`_painted_warps`).
    inverse : (h, w, 3) uint8 ndarray
        The inverse warp (nearest) as shown.
    covered, reached, pulled : (h, w) bool ndarray
        The area the picture covers, the pixels the forward warp reached, those the inverse
        warp filled from the picture.
    """

    H: np.ndarray
    outline: np.ndarray
    shown: np.ndarray
    inverse: np.ndarray
    covered: np.ndarray
    reached: np.ndarray
    pulled: np.ndarray


def forward_inverse_view(
    values: Mapping[str, Any], picture: np.ndarray, fixed: Mapping[str, Any]
) -> ForwardInverseView:
    r"""Both warps of ``forward_vs_inverse`` at one setting of its controls, as the demo shows them.

    :math:`H = C\, S\, V\, P`: P moves the picture's centre to the origin, V is the fixed tilt
    (bottom row :math:`(v^T, 1)`), S the similarity of the sliders (``scale``, ``angle`` in
    degrees) and C moves the origin to the output's centre. The forward warp pushes each source
    pixel to the rounded :math:`\pi(H x)` (:func:`camlab.warp.forward_warp`); the inverse warp
    pulls each output pixel from the nearest source pixel to :math:`\pi(H^{-1} x')`
    (:func:`camlab.warp.warp_perspective`, its numpy path, which the browser repeats byte for
    byte). The area the picture covers is the output pixels whose centres lie inside its mapped
    outline (:func:`covered_area`).

    Parameters
    ----------
    values : mapping
        The controls: ``scale`` and ``angle`` (degrees).
    picture : (h, w, 3) uint8 ndarray
        The picture warped.
    fixed : mapping
        :func:`forward_inverse_fixed`'s constants.

    Returns
    -------
    ForwardInverseView
        H, the mapped outline, both warps as shown and the three masks.

    References
    ----------
    .. [1] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022, section
       3.6.1 (forward and inverse warping).
    """
    H = hg.compose(
        fixed["C"],
        hg.similarity_homography(values["scale"], np.radians(values["angle"])),
        hg.projective_homography(v=fixed["tilt"]),
        fixed["P"],
    )
    shape = fixed["shape"]
    ones = np.ones(picture.shape[:2], np.uint8)
    outline = map_points(H, fixed["edges"])
    covered = covered_area(outline, shape)
    reached = forward_warp(ones, H, shape) > 0
    pulled = warp_perspective(ones, H, shape, interpolation="nearest") > 0
    shown, inverse = _painted_warps(
        forward_warp(picture, H, shape),
        warp_perspective(picture, H, shape, interpolation="nearest"),
        covered,
        reached,
        pulled,
        fixed["hole"],
        fixed["outside"],
    )
    return ForwardInverseView(H, outline, shown, inverse, covered, reached, pulled)
