"""The per-move arithmetic of lesson 07's ``drag_homography``: the numpy twins of ``corners.js``.

The demo's ``update`` calls :func:`drag_view`; in a kernel the browser runs its twin ``dragView``
(``camlab/widgets/browser/corners.js``) on every move of a corner, and
``tests/test_browser_corners_parity.py`` runs both on random corners. The homography is
:func:`camlab.homography.estimate_homography`; the corners text is read as
:func:`camlab.widgets.controls.parse_corners` reads it.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, NamedTuple

import numpy as np

from ... import homography as hg
from ..._validate import DegenerateError
from ...projective import clip_line, cross_ratio, map_points, map_polyline, splits_at_infinity
from ..controls import parse_corners

__all__ = [
    "DragMeasures",
    "DragView",
    "NamePlaces",
    "across_line",
    "drag_measures",
    "drag_table_rows",
    "drag_table_text",
    "drag_view",
    "length_ratio",
    "name_places",
    "shown_measure",
]


def length_ratio(a: float, b: float) -> float:
    """Two lengths' ratio, either possibly infinite: inf / finite is inf, finite / inf is 0, inf / inf NaN.

    One rule for both lesson 07 demos (the hierarchy's readout and the drag demo's table), which
    show the NaN as *undefined*: two infinite lengths have no ratio.

    Parameters
    ----------
    a, b : float
        The lengths, px (inf for a segment through infinity).

    Returns
    -------
    float
        a / b.
    """
    with np.errstate(invalid="ignore", divide="ignore"):
        return float(np.divide(a, b))


def shown_measure(x: float, spec: str) -> str:
    """A measured value as the lesson 07 readouts print it: ∞ for an infinite length, *undefined* for ∞ / ∞.

    Parameters
    ----------
    x : float
        The value.
    spec : str
        Its format (".1f").

    Returns
    -------
    str
        The value printed.
    """
    return f"{x:{spec}}" if np.isfinite(x) else ("∞" if x == np.inf else "undefined")


def across_line(points: np.ndarray) -> np.ndarray:
    """The unit offset (points, y up) across the line through ``points``, on its upper side (up for none).

    Parameters
    ----------
    points : (N, 2) ndarray
        Points along a line, px (v down); non-finite ones are skipped.

    Returns
    -------
    (2,) ndarray
        The offset, y up.
    """
    finite = points[np.isfinite(points).all(axis=1)]
    if len(finite) < 2:
        return np.array([0.0, 1.0])
    d = finite[-1] - finite[0]
    e = np.array([d[0], -d[1]]) / max(np.linalg.norm(d), 1e-9)  # on screen: v down, offsets up
    perp = np.array([-e[1], e[0]])
    return perp if perp[1] > 0 or (perp[1] == 0 and perp[0] > 0) else -perp


class NamePlaces(NamedTuple):
    """Where the names A'..D' go (:func:`name_places`).

    Attributes
    ----------
    offsets : (4, 2) ndarray
        Each name's offset from its point, points (y up).
    visible : (4,) bool ndarray
        Whether each name is shown.
    """

    offsets: np.ndarray
    visible: np.ndarray


def name_places(points: np.ndarray, corners: np.ndarray, out_hw: tuple[int, int]) -> NamePlaces:
    """Where to put the names A'..D' beside their points, clear of the corner markers and of each other.

    A name sits across the line A'D' from its point, on the side away from the nearest corner
    marker (centred 13 points off, 20 across a vertical line, where the text is widest), or 17
    points off a corner marker within 20 px, diagonally away from it and from the line. It is hidden where its text would run off the canvas, where its
    point lies under a marker (within 4 px of a corner), or within 14 px of a name already shown.

    Parameters
    ----------
    points : (4, 2) ndarray
        The mapped points A'..D' (pixels; NaN or inf where mapped to infinity).
    corners : (4, 2) ndarray
        The corner markers (pixels).
    out_hw : tuple of int
        The canvas (height, width) in pixels.

    Returns
    -------
    NamePlaces
        The names' offsets (points) and visibility.
    """
    shown, offsets, visible = [], [], []
    across = across_line(points)
    for p in points:
        gap = np.linalg.norm(corners - p, axis=1) if np.isfinite(p).all() else np.full(4, np.inf)
        away = p - corners[np.argmin(gap)]
        side = 1.0 if across @ (away[0], -away[1]) >= 0 else -1.0  # across, away from the marker
        offset = (
            side * (13 + 7 * abs(across[0])) * across
        )  # wider across a steep line: text is wide
        if gap.min() < 20:  # away from the nearest marker (v points down, offsets up), off the line
            d = np.array([away[0], -away[1]]) / max(np.linalg.norm(away), 1e-9) + side * across
            offset = d / max(np.linalg.norm(d), 1e-9) * 17
        seen = bool(
            np.isfinite(p).all()
            and 12 <= p[0] <= out_hw[1] - 12
            and 12 <= p[1] <= out_hw[0] - 4
            and gap.min() >= 4
            and all(np.linalg.norm(p - q) >= 14 for q in shown)
        )
        offsets.append(offset)
        visible.append(seen)
        if seen:
            shown.append(p)
    return NamePlaces(np.array(offsets, dtype=float), np.array(visible))


class DragMeasures(NamedTuple):
    """What the drag demo's table compares (:func:`drag_measures`).

    Attributes
    ----------
    measures : dict
        ``cross_ratio_source``, ``cross_ratio_image``, ``length_source``, ``length_image``
        (|AD|, px), ``length_ratio_source``, ``length_ratio_image`` (|AB| / |CD|) and
        ``corner_angle`` (the top-left angle, degrees).
    rows : list of tuple of str
        The table's rows (:func:`drag_table_rows`).
    """

    measures: dict
    rows: list


def drag_table_rows(cr0, cr1, length0, length1, ratio0, ratio1, angle0, angle1) -> list:
    """The drag demo's table: (quantity, source, image, verdict) with the verdict computed.

    "kept" when the two numbers agree within 0.1 % (0.1° for the angle), else "changes":
    the cross-ratio is always kept; an affine H (a parallelogram target) also keeps the
    ratio of lengths along the line, and the top-left angle stays 90° when the target's corner
    there is a right angle (a rectangle, for one, whatever its H).

    Parameters
    ----------
    cr0, cr1 : float
        The cross-ratio of the four points on the line, in the source and in the image.
    length0, length1 : float
        |AD| in pixels, in the source and in the image (inf where the image of AD runs
        through infinity, shown as ∞).
    ratio0, ratio1 : float
        |AB| / |CD|, in the source and in the image (:func:`length_ratio`: inf or 0 where one of the two
        segments runs through infinity, NaN, shown as *undefined*, where both do).
    angle0, angle1 : float
        The top-left corner's angle in degrees, in the source and in the image.

    Returns
    -------
    list of tuple of str
        One row per quantity: (name, source value, image value, "kept" or "changes").
    """

    def verdict(same: bool) -> str:
        return "kept" if same else "changes"

    return [
        ("cross-ratio", f"{cr0:.4f}", f"{cr1:.4f}", verdict(np.isclose(cr0, cr1, rtol=1e-3))),
        (
            "|AD| (px)",
            f"{length0:.1f}",
            shown_measure(length1, ".1f"),
            verdict(np.isclose(length0, length1, rtol=1e-3)),
        ),
        (
            "|AB| / |CD|",
            f"{ratio0:.4f}",
            shown_measure(ratio1, ".4f"),
            verdict(np.isclose(ratio0, ratio1, rtol=1e-3)),
        ),
        ("top-left angle", f"{angle0:.1f}°", f"{angle1:.1f}°", verdict(abs(angle0 - angle1) < 0.1)),
    ]


def drag_measures(
    line_pts: np.ndarray, m: np.ndarray, H: np.ndarray, square: np.ndarray
) -> DragMeasures:
    """What the drag demo's table compares: cross-ratio, |AD|, |AB| / |CD| and the top-left angle.

    A segment whose ends H sends to opposite sides of the line at infinity (w of opposite signs)
    maps through infinity: its image is infinitely long, not the finite segment between the two
    mapped ends.

    Parameters
    ----------
    line_pts : (4, 2) ndarray
        The four collinear points A..D, source px.
    m : (4, 2) ndarray
        Their images, target px.
    H : (3, 3) ndarray
        Source to target.
    square : (4, 2) ndarray
        The source picture's corners (the top-left angle is measured at the first).

    Returns
    -------
    DragMeasures
        The measures (for the demo's state) and the table's rows (:func:`drag_table_rows`).
    """
    w = np.c_[line_pts, np.ones(4)] @ H[2]

    def image_length(i: int, j: int) -> float:
        return float(np.linalg.norm(m[j] - m[i])) if w[i] * w[j] > 0 else np.inf

    cr0, cr1 = cross_ratio(line_pts), cross_ratio(m)
    length0, length1 = float(np.linalg.norm(line_pts[3] - line_pts[0])), image_length(0, 3)  # |AD|
    ratio0 = np.linalg.norm(line_pts[1] - line_pts[0]) / np.linalg.norm(line_pts[3] - line_pts[2])
    ratio1 = length_ratio(image_length(0, 1), image_length(2, 3))
    # the angle between the mapped edges' tangents at the mapped corner (not the chords to the
    # target corners, which point backwards along an edge that passes through infinity)
    angle = hg.mapped_angle(H, square[0], square[1] - square[0], square[3] - square[0])
    rows = drag_table_rows(cr0, cr1, length0, length1, ratio0, ratio1, 90.0, angle)
    measures = dict(
        cross_ratio_source=cr0,
        cross_ratio_image=cr1,
        length_source=length0,
        length_image=length1,
        length_ratio_source=ratio0,
        length_ratio_image=ratio1,
        corner_angle=angle,
    )
    return DragMeasures(measures, rows)


def drag_table_text(rows: list) -> str:
    """The drag demo's table as the figure and the readout print it: a header and one row per quantity.

    Parameters
    ----------
    rows : list of tuple of str
        :func:`drag_table_rows`.

    Returns
    -------
    str
        The table, monospace.
    """
    return f"{'measured':15s}  source    image\n" + "\n".join(
        f"{name:15s} {a:>7s}  {b:>7s}  {verdict}" for name, a, b, verdict in rows
    )


class DragView(NamedTuple):
    """What ``drag_homography`` draws at one setting of its corners (:func:`drag_view`).

    Attributes
    ----------
    error : str or None
        Why the corners cannot be used (the text's or the DLT's message); the other fields are
        then None.
    corners : (4, 2) ndarray
        The target corners, px.
    H : (3, 3) ndarray
        Source to target, h33 = 1.
    torn : bool
        Whether the line H sends to infinity crosses the picture.
    away : (2, 2) ndarray
        That line in the source picture, clipped to it (NaN rows when it misses it).
    mapped : (4, 2) ndarray
        A'..D', target px.
    dense : (M, 2) ndarray
        The line A'D' sampled densely (NaN where it passes through infinity).
    outline : (M, 2) ndarray
        The picture's outline mapped likewise.
    measures : DragMeasures
        The table's measures and rows.
    names : NamePlaces
        Where the names A'..D' go.
    """

    error: str | None
    corners: np.ndarray | None = None
    H: np.ndarray | None = None
    torn: bool | None = None
    away: np.ndarray | None = None
    mapped: np.ndarray | None = None
    dense: np.ndarray | None = None
    outline: np.ndarray | None = None
    measures: DragMeasures | None = None
    names: NamePlaces | None = None


def drag_view(values: Mapping[str, Any], fixed: Mapping[str, Any]) -> DragView:
    r"""The moving geometry of ``drag_homography`` at one setting of its corners.

    H maps the picture's corners to the four target corners
    (:func:`camlab.homography.estimate_homography`); the source line that H sends to infinity is
    :math:`H^T l_\infty = (h_{31}, h_{32}, h_{33})`.

    Parameters
    ----------
    values : mapping
        The controls: ``corners`` (the text ``"u0, v0; ..."``).
    fixed : mapping
        ``square`` (the picture's corners), ``line`` (A..D), ``line_dense`` and ``square_dense``
        (the line and the outline sampled densely), ``xlim``, ``ylim`` (the picture's edges) and
        ``out_hw`` (the target canvas).

    Returns
    -------
    DragView
        The view, or only its ``error``.
    """
    try:
        corners = parse_corners(values["corners"])
        H = hg.estimate_homography(fixed["square"], corners)
    except (ValueError, DegenerateError) as exc:
        return DragView(error=str(exc))
    mapped = map_points(H, fixed["line"])
    return DragView(
        error=None,
        corners=corners,
        H=H,
        torn=splits_at_infinity(H, fixed["square"]),
        away=clip_line(H[2], fixed["xlim"], fixed["ylim"]),
        mapped=mapped,
        dense=map_polyline(H, fixed["line_dense"]),  # broken where it passes through infinity
        outline=map_polyline(H, fixed["square_dense"]),
        measures=drag_measures(fixed["line"], mapped, H, fixed["square"]),
        names=name_places(mapped, corners, fixed["out_hw"]),
    )
