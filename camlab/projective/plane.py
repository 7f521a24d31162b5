r"""Points and lines of the projective plane.

Homogeneous coordinates, join and meet, incidence, ideal points, maps by homographies, the cross
ratio, and a line clipped to a window.

The conventions are in the package docstring (:mod:`camlab.projective`); see lesson 06.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, DegenerateError, as_points, check_matrix

__all__ = [
    "LINE_AT_INFINITY",
    "clip_line",
    "cross_ratio",
    "from_homogeneous",
    "horizon",
    "ideal_point",
    "is_ideal",
    "is_on_line",
    "join",
    "map_lines",
    "map_points",
    "meet",
    "normalise_lines",
    "splits_at_infinity",
    "normalise_points",
    "point_line_distance",
    "to_homogeneous",
]


LINE_AT_INFINITY = np.array([0.0, 0.0, 1.0])
"""The line (0, 0, 1) on which every ideal point (x, y, 0) lies."""

_REL_TOL = 1e-9  # relative tolerance for "zero" after scale-free normalisation


def to_homogeneous(points: ArrayLike) -> np.ndarray:
    """Append w = 1: ``(N, d)`` Euclidean points become ``(N, d + 1)`` homogeneous.

    Parameters
    ----------
    points : (N, d) or (d,) array_like
        Euclidean points, one per row (d is 2 for image points, 3 for world points).

    Returns
    -------
    (N, d + 1) or (d + 1,) ndarray

    Examples
    --------
    >>> to_homogeneous([3.0, 4.0])
    array([3., 4., 1.])
    """
    p = as_points(points, (1, 2, 3), "points")
    a = p.array
    return p.restore(np.hstack([a, np.ones((len(a), 1))]))


def from_homogeneous(points_h: ArrayLike) -> np.ndarray:
    r"""Divide by the last coordinate: ``(N, d + 1)`` homogeneous to ``(N, d)`` Euclidean.

    Ideal points (w exactly 0) have no Euclidean position and come back as NaN; there is
    no epsilon division that would turn them into huge but finite numbers.

    .. math:: (x, y, w) \mapsto (x / w,\ y / w)

    Parameters
    ----------
    points_h : (N, d + 1) or (d + 1,) array_like
        Homogeneous points, one per row.

    Returns
    -------
    (N, d) or (d,) ndarray
        Euclidean coordinates; NaN rows for ideal points.

    Examples
    --------
    >>> from_homogeneous([6.0, 8.0, 2.0])
    array([3., 4.])
    >>> from_homogeneous([1.0, 0.0, 0.0])
    array([nan, nan])
    """
    p = as_points(points_h, (2, 3, 4), "points_h")
    a = p.array
    w = a[:, -1:]
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(w == 0, np.nan, a[:, :-1] / np.where(w == 0, 1.0, w))
    return p.restore(out)


def _as_homogeneous_2d(x: ArrayLike, name: str) -> tuple[np.ndarray, bool]:
    """Image points as (N, 3) homogeneous rows; (N, 2) input is lifted to w = 1."""
    p = as_points(x, (2, 3), name)
    a = p.array
    if a.shape[1] == 2:
        a = np.hstack([a, np.ones((len(a), 1))])
    if np.any(np.all(a == 0, axis=1)):
        raise CamlabInputError(
            f"{name}: (0, 0, 0) is not a point or a line of the projective plane"
        )
    return a, p.single


def _as_lines(x: ArrayLike, name: str) -> tuple[np.ndarray, bool]:
    p = as_points(x, 3, name)
    if np.any(np.all(p.array == 0, axis=1)):
        raise CamlabInputError(
            f"{name}: (0, 0, 0) is not a line; a line is (a, b, c) with ax + by + c = 0"
        )
    return p.array, p.single


def _check_nonzero_H(H: ArrayLike) -> np.ndarray:
    Hm = check_matrix(H, (3, 3), "H")
    if not Hm.any():
        raise DegenerateError(
            "H: all zeros, which maps every point to (0, 0, 0), not a point; pass a homography"
        )
    return Hm


def _unit_rows(a: np.ndarray) -> np.ndarray:
    return a / np.linalg.norm(a, axis=1, keepdims=True)


def _cross(
    a: np.ndarray, b: np.ndarray, sa: bool, sb: bool, what: str, same_message: str
) -> np.ndarray:
    """Row-wise a x b for join and meet, refusing inputs that are equal up to scale."""
    if len(a) != len(b) and not (sa or sb):
        raise CamlabInputError(
            f"{what}: expected equally many rows or a single one, got {len(a)} and {len(b)}"
        )
    c = np.cross(a, b)
    # Scale-free test for a zero cross product: the inputs were equal up to scale.
    same = (
        np.linalg.norm(c, axis=1) / (np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1))
        < _REL_TOL
    )
    if same.any():
        i = int(np.argmax(same))
        raise DegenerateError(
            f"{what}: {same_message} (row {i}: {a[min(i, len(a) - 1)]} and {b[min(i, len(b) - 1)]})"
        )
    return c[0] if sa and sb else c


def join(p: ArrayLike, q: ArrayLike) -> np.ndarray:
    r"""The line through two points: :math:`l = p \times q`.

    Both points lie on l because a vector is orthogonal to a cross product it is part
    of: :math:`(p \times q) \cdot p = 0`.

    Parameters
    ----------
    p, q : (N, 2 or 3) or (2 or 3,) array_like
        Euclidean or homogeneous image points (a single point broadcasts).

    Returns
    -------
    (N, 3) or (3,) ndarray
        The line(s) (a, b, c), not normalised.

    Raises
    ------
    DegenerateError
        If the two points coincide (no unique line).

    Examples
    --------
    >>> join([0, 0], [1, 1])  # the line y = x, i.e. -x + y = 0
    array([-1.,  1.,  0.])
    """
    a, sa = _as_homogeneous_2d(p, "p")
    b, sb = _as_homogeneous_2d(q, "q")
    return _cross(
        a,
        b,
        sa,
        sb,
        "join",
        "p and q coincide, so no unique line passes through them; pick two distinct points",
    )


def meet(l: ArrayLike, m: ArrayLike) -> np.ndarray:  # noqa: E741 (l, m: the book's names for two lines, public keywords)
    r"""The point where two lines cross: :math:`x = l \times m` (the dual of :func:`join`).

    Parallel lines give an ideal point (x, y, 0): their common direction.

    Parameters
    ----------
    l, m : (N, 3) or (3,) array_like
        Lines (a, b, c) meaning ax + by + c = 0.

    Returns
    -------
    (N, 3) or (3,) ndarray
        Homogeneous intersection point(s); use :func:`from_homogeneous` for pixels.

    Raises
    ------
    DegenerateError
        If the two lines are the same line.

    Examples
    --------
    >>> meet([1, 0, -2], [0, 1, -3])  # x = 2 and y = 3
    array([2., 3., 1.])
    >>> meet([0, 1, 0], [0, 1, -1])  # y = 0 and y = 1 meet at infinity along x
    array([-1.,  0.,  0.])
    """
    a, sa = _as_lines(l, "l")
    b, sb = _as_lines(m, "m")
    return _cross(
        a,
        b,
        sa,
        sb,
        "meet",
        "l and m are the same line, so they share every point; pick two distinct lines",
    )


def is_on_line(points: ArrayLike, line: ArrayLike, tol: float = 1e-9) -> np.ndarray:
    r"""Test incidence :math:`l \cdot x = 0` with a tolerance that ignores scale.

    The test is :math:`|l \cdot x| \le \text{tol}\, \|l\| \|x\|`, so multiplying the
    point or the line by any non-zero number never changes the answer.

    Parameters
    ----------
    points : (N, 2 or 3) or (2 or 3,) array_like
    line : (3,) or (N, 3) array_like
    tol : float
        Relative tolerance (the sine of the angle between x and the plane l . x = 0).

    Returns
    -------
    (N,) bool ndarray, or a bool for a single point and line

    Examples
    --------
    >>> bool(is_on_line([1e6, 1e6, 1e6], [-1, 1, 0]))
    True
    """
    x, sx = _as_homogeneous_2d(points, "points")
    ln, sl = _as_lines(line, "line")
    dots = np.abs(np.sum(x * ln, axis=1))
    ok = dots <= tol * np.linalg.norm(x, axis=1) * np.linalg.norm(ln, axis=1)
    return bool(ok[0]) if sx and sl else ok


def ideal_point(direction: ArrayLike) -> np.ndarray:
    """The point at infinity in a 2-D direction: (dx, dy) becomes (dx, dy, 0).

    Every line with this direction passes through it.

    Parameters
    ----------
    direction : (N, 2) or (2,) array_like
        Non-zero directions (dx, dy).

    Returns
    -------
    (N, 3) or (3,) ndarray
        The ideal points (dx, dy, 0), the input's rank.

    Examples
    --------
    >>> ideal_point([1, 2])
    array([1., 2., 0.])
    """
    p = as_points(direction, 2, "direction")
    if np.any(np.all(p.array == 0, axis=1)):
        raise CamlabInputError("direction: (0, 0) has no direction; give a non-zero vector")
    return p.restore(np.hstack([p.array, np.zeros((len(p.array), 1))]))


def is_ideal(points_h: ArrayLike, tol: float = 1e-12) -> np.ndarray:
    """True where a homogeneous point lies on the line at infinity (|w| <= tol * |x|).

    Parameters
    ----------
    points_h : (N, 3) or (3,) array_like
        Homogeneous points.
    tol : float, optional
        Relative tolerance on w.

    Returns
    -------
    (N,) bool ndarray or bool
        True for ideal points (a bool for one point).
    """
    x, single = _as_homogeneous_2d(points_h, "points_h")
    ok = np.abs(x[:, 2]) <= tol * np.linalg.norm(x, axis=1)
    return bool(ok[0]) if single else ok


def normalise_points(points_h: ArrayLike) -> np.ndarray:
    """Scale homogeneous points to w = 1, and ideal points to a unit (x, y) with w = 0.

    Parameters
    ----------
    points_h : (N, 3) or (3,) array_like
        Homogeneous points, not (0, 0, 0).

    Returns
    -------
    (N, 3) or (3,) ndarray
        The scaled points, the input's rank.

    Examples
    --------
    >>> normalise_points([[2, 4, 2], [3, 4, 0]])
    array([[1. , 2. , 1. ],
           [0.6, 0.8, 0. ]])
    """
    x, single = _as_homogeneous_2d(points_h, "points_h")
    w = x[:, 2:]
    xy_norm = np.linalg.norm(x[:, :2], axis=1, keepdims=True)
    scale = np.where(w == 0, xy_norm, w)
    out = x / scale
    return out[0] if single else out


def normalise_lines(lines: ArrayLike) -> np.ndarray:
    r"""Scale lines so :math:`a^2 + b^2 = 1`; then :math:`l \cdot (x, y, 1)` is the signed distance.

    The line at infinity (0, 0, c) becomes (0, 0, 1).

    Parameters
    ----------
    lines : (N, 3) or (3,) array_like
        Lines (a, b, c), not (0, 0, 0).

    Returns
    -------
    (N, 3) or (3,) ndarray
        The scaled lines, the input's rank.

    Examples
    --------
    >>> normalise_lines([3, 4, 10])
    array([0.6, 0.8, 2. ])
    """
    ln, single = _as_lines(lines, "lines")
    ab = np.linalg.norm(ln[:, :2], axis=1, keepdims=True)
    out = ln / np.where(ab == 0, ln[:, 2:], ab)
    return out[0] if single else out


def point_line_distance(points: ArrayLike, line: ArrayLike) -> np.ndarray:
    """Signed Euclidean distance from finite points to a finite line, in pixels.

    Parameters
    ----------
    points : (N, 2), (N, 3), (2,) or (3,) array_like
        Points, Euclidean or homogeneous (ideal points give NaN).
    line : (3,) or (N, 3) array_like
        A finite line (a, b, c), or one per point.

    Returns
    -------
    (N,) ndarray or float
        Signed distances, pixels (positive on the side a x + b y + c > 0); a float for one
        point and one line.

    Examples
    --------
    >>> float(point_line_distance([0, 5], [0, 1, -2]))  # y = 2
    3.0
    """
    x, sx = _as_homogeneous_2d(points, "points")
    ln, sl = _as_lines(line, "line")
    if np.any(np.all(ln[:, :2] == 0, axis=1)):
        raise DegenerateError("line: the line at infinity has no Euclidean distance to a point")
    with np.errstate(divide="ignore", invalid="ignore"):
        d = np.sum(x * ln, axis=1) / (x[:, 2] * np.linalg.norm(ln[:, :2], axis=1))
    d = np.where(x[:, 2] == 0, np.nan, d)
    return float(d[0]) if sx and sl else d


def map_points(H: ArrayLike, points: ArrayLike) -> np.ndarray:
    r"""Apply a homography to points: :math:`x' \sim H x`, i.e. ``X @ H.T`` for rows.

    Parameters
    ----------
    H : (3, 3) array_like
    points : (N, 2) or (N, 3) array_like
        Euclidean points give Euclidean results (NaN where a point maps to infinity);
        homogeneous points give homogeneous results, so ideal points stay representable.

    Returns
    -------
    ndarray of the same shape as ``points``

    Examples
    --------
    >>> map_points(np.diag([2.0, 3.0, 1.0]), [1.0, 1.0])
    array([2., 3.])
    """
    Hm = _check_nonzero_H(H)
    p = as_points(points, (2, 3), "points")
    euclidean = p.array.shape[1] == 2
    x = np.hstack([p.array, np.ones((len(p.array), 1))]) if euclidean else p.array
    y = x @ Hm.T
    return p.restore(from_homogeneous(y) if euclidean else y)


def map_lines(H: ArrayLike, lines: ArrayLike) -> np.ndarray:
    r"""Apply a homography to lines: :math:`l' \sim H^{-T} l` (``L @ inv(H)`` for rows).

    Derivation: a point x on l satisfies :math:`l^T x = 0`. Its image is
    :math:`x' = H x`, and :math:`(H^{-T} l)^T (H x) = l^T H^{-1} H x = 0`, so
    :math:`H^{-T} l` is the line through every image point.

    Parameters
    ----------
    H : (3, 3) array_like
        The homography mapping points.
    lines : (N, 3) or (3,) array_like
        Lines (a, b, c).

    Returns
    -------
    (N, 3) or (3,) ndarray
        The mapped lines, the input's rank (unscaled).

    Raises
    ------
    DegenerateError
        If H is singular (it then collapses the plane and has no inverse).
    """
    Hm = _check_nonzero_H(H)
    ln, single = _as_lines(lines, "lines")
    if np.linalg.cond(Hm) > 1e12:
        raise DegenerateError(
            f"H: singular (condition number {np.linalg.cond(Hm):.2g}); a homography must be invertible"
        )
    out = ln @ np.linalg.inv(Hm)
    return out[0] if single else out


def splits_at_infinity(H: ArrayLike, points: ArrayLike) -> bool:
    r"""True when H sends part of the polygon ``points`` through infinity.

    H maps the line :math:`H^T l_\infty = (h_{31}, h_{32}, h_{33})` to the line at infinity:
    a point on it gets :math:`w = h_{31} x + h_{32} y + h_{33} = 0`. If w has different signs
    at the polygon's corners, that line crosses the polygon, and its image is torn in two
    pieces that leave through infinity on one side and come back on the other (the "bow
    tie" of four corners dragged past each other).

    Parameters
    ----------
    H : (3, 3) array_like
        The homography.
    points : (N, 2) array_like
        Corners of a convex polygon (e.g. an image's four corners).

    Returns
    -------
    bool
        True when w changes sign across the corners.

    Examples
    --------
    >>> square = [[0, 0], [1, 0], [1, 1], [0, 1]]
    >>> splits_at_infinity(np.eye(3), square), splits_at_infinity([[1, 0, 0], [0, 1, 0], [-2, 0, 1]], square)
    (False, True)
    """
    Hm = _check_nonzero_H(H)
    p = as_points(points, (2,), "points").array
    w = p @ Hm[2, :2] + Hm[2, 2]
    return bool(w.min() <= 0 <= w.max())


def map_polyline(H: ArrayLike, points: ArrayLike) -> np.ndarray:
    r"""Map a sampled polyline by H, broken (a NaN row) wherever it passes through infinity.

    Joining mapped samples by straight segments is right only while the samples stay on one
    side of the line :math:`H^T l_\infty`, which H sends to infinity. Where two consecutive
    samples have third coordinates :math:`w = h_3^T x` of opposite signs, the image of the
    segment between them leaves through infinity and comes back from the other side: the
    chord between the two mapped samples is the image of *no* point of the segment. A NaN row
    there makes matplotlib lift the pen.

    Parameters
    ----------
    H : (3, 3) array_like
    points : (N, 2) array_like
        Consecutive samples of a polyline (sample densely: only the samples are mapped).

    Returns
    -------
    (N + K, 2) ndarray
        The mapped samples, with a NaN row inserted at each of the K sign changes of w.

    Examples
    --------
    >>> map_polyline([[1, 0, 0], [0, 1, 0], [-1, 0, 1]], [[0, 0], [0.5, 0], [2, 0], [3, 0]])
    array([[ 0. ,  0. ],
           [ 1. ,  0. ],
           [ nan,  nan],
           [-2. ,  0. ],
           [-1.5,  0. ]])
    """
    Hm = _check_nonzero_H(H)
    p = as_points(points, (2,), "points").array
    mapped = map_points(Hm, p)
    w = p @ Hm[2, :2] + Hm[2, 2]
    breaks = np.flatnonzero(np.sign(w[1:]) != np.sign(w[:-1])) + 1
    return np.insert(mapped, breaks, np.nan, axis=0) + 0.0  # + 0.0 turns -0.0 into 0.0


def cross_ratio(points: ArrayLike) -> float:
    r"""Cross-ratio (A, B; C, D) of four collinear points, invariant under homographies.

    .. math:: (A, B; C, D) = \frac{\overline{AC}\;\overline{BD}}{\overline{BC}\;\overline{AD}}

    with signed lengths along the line. It is computed with determinants
    :math:`|o\,a\,c|\,|o\,b\,d| / (|o\,b\,c|\,|o\,a\,d|)` for any point o off the line
    (here o = l, which has :math:`l \cdot l > 0`). Each point appears once above and
    once below, so the homogeneous scale cancels and ideal points are allowed.

    Parameters
    ----------
    points : (4, 2) or (4, 3) array_like
        A, B, C, D in order, Euclidean or homogeneous.

    Returns
    -------
    float

    Raises
    ------
    DegenerateError
        If the points are not collinear or a pair of them coincides.

    Examples
    --------
    >>> cross_ratio([[0, 0], [1, 0], [2, 0], [3, 0]])  # (2 * 2) / (1 * 3)
    1.3333333333333333
    """
    pts = as_points(points, (2, 3), "points", min_count=4).array
    if len(pts) != 4:
        raise CamlabInputError(
            f"points: expected exactly 4 collinear points A, B, C, D, got {len(pts)}"
        )
    x, _ = _as_homogeneous_2d(pts, "points")
    xu = _unit_rows(x)
    # The line through the two points farthest apart (in the unit-sphere sense).
    pairs = [(i, j) for i in range(4) for j in range(i + 1, 4)]
    i, j = max(pairs, key=lambda ij: np.linalg.norm(np.cross(xu[ij[0]], xu[ij[1]])))
    line = np.cross(xu[i], xu[j])
    if np.linalg.norm(line) < _REL_TOL:
        raise DegenerateError(
            "points: all four points coincide; the cross-ratio needs distinct points"
        )
    line /= np.linalg.norm(line)
    off = np.abs(xu @ line)
    if off.max() > 1e-7:
        k = int(np.argmax(off))
        raise DegenerateError(
            f"points: expected four collinear points, but point {'ABCD'[k]} = {pts[k]} is off the line "
            f"through {'ABCD'[i]} and {'ABCD'[j]}"
        )
    a, b, c, d = xu

    def det(u: np.ndarray, v: np.ndarray) -> float:
        return float(np.linalg.det(np.stack([line, u, v])))

    den = det(b, c) * det(a, d)
    if abs(den) < 1e-12:
        raise DegenerateError(
            "points: B = C or A = D, so the cross-ratio is undefined; use distinct points"
        )
    return det(a, c) * det(b, d) / den


def horizon(vp1: ArrayLike, vp2: ArrayLike) -> np.ndarray:
    """The vanishing line through two vanishing points of one plane (its horizon).

    Returns the line normalised so that a^2 + b^2 = 1 (or (0, 0, 1) when both points are
    ideal, i.e. the plane is parallel to the image). See :func:`join`.

    Parameters
    ----------
    vp1, vp2 : (3,) array_like
        Two homogeneous vanishing points of the plane.

    Returns
    -------
    (3,) ndarray
        The vanishing line (a, b, c), a^2 + b^2 = 1, or (0, 0, 1).

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 8.6.2 (vanishing
       lines).
    """
    a, sa = _as_homogeneous_2d(vp1, "vp1")
    b, sb = _as_homogeneous_2d(vp2, "vp2")
    return normalise_lines(
        _cross(
            a,
            b,
            sa,
            sb,
            "horizon",
            "vp1 and vp2 coincide, so they do not fix a line; "
            "use the vanishing points of two different directions",
        )
    )


def _interval(lim: ArrayLike, name: str) -> tuple[float, float]:
    lo, hi = check_matrix(lim, (2,), name)
    if not lo < hi:
        raise CamlabInputError(f"{name}: expected (lo, hi) with lo < hi, got {lim!r}")
    return float(lo), float(hi)


def clip_line(line: ArrayLike, xlim: tuple[float, float], ylim: tuple[float, float]) -> np.ndarray:
    """The visible piece of an infinite line inside a box, for drawing.

    Intersects the line with the four box edges (each a line itself) and keeps the two
    crossings that lie on the box.

    Parameters
    ----------
    line : (3,) array_like
    xlim, ylim : (lo, hi)
        The box, in the same units as the line (pixels or plot units).

    Returns
    -------
    (2, 2) ndarray
        Two endpoints ``[[x1, y1], [x2, y2]]``; all NaN when the line misses the box
        (including the line at infinity).

    Examples
    --------
    >>> clip_line([0, 1, -2], (0, 10), (0, 5))  # y = 2 across the box
    array([[ 0.,  2.],
           [10.,  2.]])
    """
    ln, _ = _as_lines(line, "line")
    ln = ln[0]
    (x0, x1), (y0, y1) = _interval(xlim, "xlim"), _interval(ylim, "ylim")
    edges = np.array([[1, 0, -x0], [1, 0, -x1], [0, 1, -y0], [0, 1, -y1]], dtype=float)
    hits = from_homogeneous(np.cross(ln, edges))  # NaN where the line is parallel to an edge
    span = max(x1 - x0, y1 - y0)
    eps = 1e-9 * span
    inside = (
        np.isfinite(hits).all(axis=1)
        & (hits[:, 0] >= x0 - eps)
        & (hits[:, 0] <= x1 + eps)
        & (hits[:, 1] >= y0 - eps)
        & (hits[:, 1] <= y1 + eps)
    )
    pts = hits[inside]
    if len(pts) < 2:
        return np.full((2, 2), np.nan)
    # A line through a corner hits two edges there; take the two crossings farthest apart.
    d = np.linalg.norm(pts[:, None] - pts[None], axis=2)
    i, j = np.unravel_index(np.argmax(d), d.shape)
    if d[i, j] <= eps:
        return np.full((2, 2), np.nan)
    return np.array([pts[i], pts[j]]) + 0.0  # + 0.0 turns -0.0 into 0.0
