r"""The projective plane P^2: homogeneous points, lines, duality, and invariants.

A point (x, y) of the image plane is the homogeneous 3-vector (x, y, 1), and every
non-zero multiple (wx, wy, w) names the same point. A line ax + by + c = 0 is the
3-vector l = (a, b, c), also up to scale, and a point x lies on l exactly when
l . x = 0. Because incidence is a dot product, the line through two points and the
point on two lines are both cross products, and parallel lines meet at an *ideal
point* (x, y, 0) on the *line at infinity* (0, 0, 1).

Conventions (docs/conventions.md): points are rows, ``(N, 2)`` Euclidean or
``(N, 3)`` homogeneous, a single ``(2,)``/``(3,)`` point keeps its rank; lines are
rows ``(N, 3)``; homographies map points by ``x' = H x`` (``X @ H.T`` for rows) and
lines by ``l' = H^{-T} l``; conics are symmetric (3, 3) matrices mapping by ``H^{-T} C H^{-1}``,
dual conics by ``H C* H^T`` (:mod:`.conics`, with the circular points). See lesson 06.
"""

# the errors the functions raise, as pj.CamlabInputError and pj.DegenerateError
from .._validate import CamlabInputError as CamlabInputError
from .._validate import DegenerateError as DegenerateError
from .conditioning import HartleyNormalised, hartley_normalise
from .conics import (
    CIRCULAR_POINTS,
    DUAL_CONIC_AT_INFINITY,
    circle_conic,
    conic_matrix,
    conic_points,
    dual_conic,
    line_angle,
    map_conic,
    map_dual_conic,
)
from .plane import (
    LINE_AT_INFINITY,
    clip_line,
    cross_ratio,
    from_homogeneous,
    horizon,
    ideal_point,
    is_ideal,
    is_on_line,
    join,
    map_lines,
    map_points,
    map_polyline,
    meet,
    normalise_lines,
    normalise_points,
    point_line_distance,
    splits_at_infinity,
    to_homogeneous,
)
from .vanishing import (
    VanishingPointFit,
    segments_pointing_at,
    vanishing_point,
    vanishing_point_ransac,
)

__all__ = [
    "CIRCULAR_POINTS",
    "DUAL_CONIC_AT_INFINITY",
    "circle_conic",
    "conic_matrix",
    "conic_points",
    "dual_conic",
    "line_angle",
    "map_conic",
    "map_dual_conic",
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
    "map_polyline",
    "meet",
    "normalise_lines",
    "splits_at_infinity",
    "VanishingPointFit",
    "segments_pointing_at",
    "vanishing_point_ransac",
    "normalise_points",
    "point_line_distance",
    "to_homogeneous",
    "vanishing_point",
    "HartleyNormalised",
    "hartley_normalise",
]
