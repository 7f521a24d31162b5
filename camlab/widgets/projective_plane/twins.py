"""The per-move arithmetic and captions of lesson 06's demos: the numpy twins of ``geometry.js``.

Each demo's ``update`` calls these, and the browser (``camlab/widgets/browser/geometry.js``) runs
a JavaScript function of the same name in camelCase on every slider move;
``tests/test_browser_geometry_parity.py`` runs both on random inputs and compares them.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ... import fixtures
from ... import projective as pj
from ...camera import rotation_z
from ...plotting.plane import ArrowPlacement, arrow_placement

__all__ = [
    "CONIC_TANGENTS",
    "ConicGeometry",
    "ab_over_bc",
    "conic_caption",
    "conic_geometry",
    "conic_homography",
    "cross_ratio_caption",
    "cross_ratio_homography",
    "RolledView",
    "drawn_vanishing_point",
    "duality_caption",
    "horizon_note",
    "in_square_view",
    "LiftView",
    "label_offset",
    "lift_view",
    "line_at_angle",
    "meet_or_none",
    "meet_w_curve",
    "normal_line",
    "rolled_view",
]


def normal_line(angle_deg: float, distance: float) -> np.ndarray:
    r"""The line with unit normal :math:`(\cos t, \sin t)` at ``distance`` from the origin.

    Parameters
    ----------
    angle_deg : float
        The normal's angle t to the x axis, degrees.
    distance : float
        The line's distance from the origin (plot units), along the normal.

    Returns
    -------
    (3,) ndarray
        :math:`(\cos t, \sin t, -d)`: the points x with :math:`x \cos t + y \sin t = d`.
    """
    t = np.radians(angle_deg)
    return np.array([np.cos(t), np.sin(t), -distance])


def duality_caption(
    point: np.ndarray, line: np.ndarray, xlim: tuple[float, float], ylim: tuple[float, float]
) -> str:
    """The line of text under :func:`~camlab.widgets.projective_plane.point_line_duality`'s panels.

    Parameters
    ----------
    point, line : (3,) ndarray
        The point p and the line l, homogeneous.
    xlim, ylim : (lo, hi)
        The dual panel's limits: where l* = (a/c, b/c) is drawn, or an arrow to it.

    Returns
    -------
    str
        p . l to three decimals, whether p is on l (and so l* on p*, within 1e-3 relative), and
        where l* is when it is off the dual panel.
    """
    incidence = float(point @ line)
    on_line = bool(pj.is_on_line(point, line, tol=1e-3))
    off = ""
    if arrow_placement(line, xlim, ylim).direction.any():  # l* off the panel: an arrow points to it
        ld = pj.from_homogeneous(line)
        off = f"; l* = ({ld[0] + 0.0:.1f}, {ld[1] + 0.0:.1f}) is off the dual panel (arrow)"
    verdict = "p is on l, and l* is on p*" if on_line else "p is not on l, and l* is not on p*"
    return f"p · l = {incidence:+.3f}: {verdict}{off}"


def line_at_angle(angle_deg: float | np.ndarray, offset: float) -> np.ndarray:
    """The line(s) through (0, offset) at ``angle_deg`` to the x axis.

    Parameters
    ----------
    angle_deg : float or (N,) array_like
        The angle(s), degrees.
    offset : float
        Where the line crosses x = 0.

    Returns
    -------
    (3,) or (N, 3) ndarray
        The line(s) (a, b, c): the join of (0, offset) and (cos t, offset + sin t).
    """
    t = np.radians(angle_deg)
    return pj.join([0.0, offset], np.stack([np.cos(t), offset + np.sin(t)], axis=-1))


def meet_or_none(l1: np.ndarray, l2: np.ndarray) -> np.ndarray | None:
    r"""The meet :math:`l_1 \times l_2`, or None when the two are one line (:func:`camlab.projective.meet` refuses).

    Parameters
    ----------
    l1, l2 : (3,) ndarray
        The lines.

    Returns
    -------
    (3,) ndarray or None
        The homogeneous meet point (w = 0 for parallel lines); None for the same line up to scale.
    """
    try:
        return pj.meet(l1, l2)
    except pj.DegenerateError:
        return None


def meet_w_curve(
    l1: np.ndarray, angle1: float, angles: np.ndarray, offset: float, gap: float = 1.0
) -> np.ndarray:
    """|w| of the unit meet of ``l1`` with each line through (0, offset) at ``angles``.

    Parameters
    ----------
    l1 : (3,) ndarray
        The fixed line, at ``angle1`` degrees.
    angle1 : float
        Its angle, degrees.
    angles : (N,) ndarray
        The other lines' angles, degrees.
    offset : float
        Where the other lines cross x = 0.
    gap : float
        When (0, offset) lies on ``l1`` every line meets it there except ``l1`` itself: the curve
        is left out within ``gap`` degrees of ``angle1`` (a visible gap, not one missing sample).

    Returns
    -------
    (N,) ndarray
        abs(w) / norm((x, y, w)) of each meet; NaN where the lines coincide and in the gap.
    """
    family = np.cross(l1, line_at_angle(angles, offset))
    with np.errstate(invalid="ignore"):  # the family may contain l1 itself (0/0 -> NaN)
        w = np.abs(family[:, 2]) / np.linalg.norm(family, axis=1)
    if np.all(np.abs(np.cross(l1, line_at_angle(angle1, offset))) < 1e-12):
        w = np.where(np.abs(angles - angle1) < gap, np.nan, w)
    return w


def cross_ratio_homography(h31: float, h32: float, angle_deg: float) -> np.ndarray:
    """The homography of :func:`~camlab.widgets.projective_plane.cross_ratio_invariance`: a turn and a perspective row.

    Parameters
    ----------
    h31, h32 : float
        The perspective row (h31, h32, 1).
    angle_deg : float
        The turn, degrees.

    Returns
    -------
    (3, 3) ndarray
        ``[[cos t, -sin t, 0], [sin t, cos t, 0], [h31, h32, 1]]``.
    """
    t = np.radians(angle_deg)
    return np.array([[np.cos(t), -np.sin(t), 0.0], [np.sin(t), np.cos(t), 0.0], [h31, h32, 1.0]])


def label_offset(points: np.ndarray) -> np.ndarray:
    """An offset (points) of 10 along the normal of the line through ``points``, on its upper side.

    Parameters
    ----------
    points : (N, 2) ndarray
        Collinear points; the first and the last give the line.

    Returns
    -------
    (2,) ndarray
        The offset, in points (y up), for an annotation's text.
    """
    d = points[-1] - points[0]
    n = np.array([-d[1], d[0]]) / np.linalg.norm(d)
    return 10.0 * (n if n[1] >= 0 else -n)


def ab_over_bc(points: np.ndarray) -> float:
    """The ratio of lengths AB / BC: an affine invariant only.

    Parameters
    ----------
    points : (4, 2) ndarray
        A, B, C, D.

    Returns
    -------
    float
        |B - A| / |C - B|.
    """
    return float(np.linalg.norm(points[1] - points[0]) / np.linalg.norm(points[2] - points[1]))


def cross_ratio_caption(points: np.ndarray, mapped: np.ndarray) -> str:
    """The line under :func:`~camlab.widgets.projective_plane.cross_ratio_invariance`'s panels.

    Parameters
    ----------
    points, mapped : (4, 2) ndarray
        A, B, C, D before and after the homography.

    Returns
    -------
    str
        The cross-ratio (A, B; C, D) and AB / BC, before and after, to four decimals.
    """
    cr = [pj.cross_ratio(p) for p in (points, mapped)]
    r = [ab_over_bc(p) for p in (points, mapped)]
    return (
        f"(A, B; C, D): before {cr[0]:.4f}, after {cr[1]:.4f}      "
        f"AB / BC: before {r[0]:.4f}, after {r[1]:.4f}"
    )


class RolledView(NamedTuple):
    """What :func:`rolled_view` returns: the ground grid's image by a rolled camera.

    Attributes
    ----------
    segments : (M, 2, 2) ndarray
        The grid's segments in the image, pixels: the lines along z first.
    n_along_z : int
        How many of them run along z (ahead); the rest run along x (across).
    vp_z, vp_x : (3,) ndarray
        The true vanishing points of the two directions, homogeneous.
    horizon : (3,) ndarray
        The true horizon, homogeneous.
    """

    segments: np.ndarray
    n_along_z: int
    vp_z: np.ndarray
    vp_x: np.ndarray
    horizon: np.ndarray


def rolled_view(pitch: float, yaw: float, roll: float, focal: float, size) -> RolledView:
    """:func:`camlab.fixtures.ground_plane_view`, then the camera rolled by ``roll`` degrees.

    Rolling turns the camera about its own centre (about its optical axis), so the whole image
    moves by the homography :math:`M = K R_z K^{-1}`: points (segments, vanishing points) by
    :math:`M`, the horizon by :math:`M^{-T}`. Positive ``roll`` turns the image clockwise on the
    screen (x right, v down), so the horizon falls to the right.

    Parameters
    ----------
    pitch, yaw, roll : float
        The camera's pitch (down), yaw and roll, degrees.
    focal : float
        Focal length, pixels.
    size : (width, height)
        The image, pixels.

    Returns
    -------
    RolledView
        The grid's segments, how many run along z, the vanishing points and the horizon.
    """
    g = fixtures.ground_plane_view(np.radians(pitch), np.radians(yaw), focal, size)
    M = g.K @ rotation_z(np.radians(roll)) @ np.linalg.inv(g.K)
    segments = pj.map_points(M, g.segments.reshape(-1, 2)).reshape(-1, 2, 2)
    return RolledView(segments, g.n_along_z, M @ g.vp_z, M @ g.vp_x, np.linalg.inv(M).T @ g.horizon)


def drawn_vanishing_point(segments: np.ndarray) -> np.ndarray:
    """:func:`camlab.projective.vanishing_point` of the drawn segments, an ideal one pointing right.

    An ideal point lies both ways along its direction; the estimate's sign is the SVD's, which
    no other implementation repeats. Fixing it (x > 0, or y > 0 when x = 0) makes the arrow to it
    point the same way in every drawing of the demo.

    Parameters
    ----------
    segments : (N, 2, 2) ndarray
        N >= 2 segments, pixels.

    Returns
    -------
    (3,) ndarray
        The vanishing point, normalised (w = 1, or a unit (x, y) pointing right if ideal).
    """
    v = pj.vanishing_point(segments)
    if v[2] == 0 and (v[0] < 0 or (v[0] == 0 and v[1] < 0)):
        v = -v
    return v + 0.0


def horizon_note(hz: np.ndarray, visible: bool, title: str) -> str:
    """The title of :func:`~camlab.widgets.projective_plane.vanishing_points`: the note when the horizon is above the image.

    Parameters
    ----------
    hz : (3,) ndarray
        The horizon (a, b, c).
    visible : bool
        Whether it crosses the image.
    title : str
        The title when it does.

    Returns
    -------
    str
        ``title``, or where the horizon crosses u = 0, to the pixel.
    """
    if visible:
        return title
    v_horizon = float(-hz[2] / hz[1]) if abs(hz[1]) > 1e-12 else float("nan")
    return f"horizon above the image: v = {v_horizon:.0f} px at u = 0"


CONIC_TANGENTS = np.array([[1.0, 0, -1], [1, 0, 1], [0, 1, -1], [0, 1, 1]])
"""The four tangents x = 1, x = -1, y = 1, y = -1 of the unit circle (lines (a, b, c))."""


def conic_homography(angle_deg: float, aspect: float, h31: float, h32: float) -> np.ndarray:
    """The homography of :func:`~camlab.widgets.projective_plane.conic_under_homography`.

    Parameters
    ----------
    angle_deg : float
        The turn, degrees.
    aspect : float
        The stretch of x (before the turn).
    h31, h32 : float
        The perspective row (h31, h32, 1).

    Returns
    -------
    (3, 3) ndarray
        ``[[a cos t, -sin t, 0], [a sin t, cos t, 0], [h31, h32, 1]]``.
    """
    t = np.radians(angle_deg)
    return np.array(
        [
            [aspect * np.cos(t), -np.sin(t), 0.0],
            [aspect * np.sin(t), np.cos(t), 0.0],
            [h31, h32, 1.0],
        ]
    )


class ConicGeometry(NamedTuple):
    r"""What :func:`conic_geometry` returns: the unit circle's image and the numbers reported on it.

    Attributes
    ----------
    H : (3, 3) ndarray
        The homography.
    C_mapped : (3, 3) ndarray
        :math:`C' = H^{-T} C H^{-1}`, scaled to unit (Frobenius) norm.
    mapped : (N, 2) ndarray
        The samples after H.
    tangents : (4, 3) ndarray
        :data:`CONIC_TANGENTS` after H (:math:`H^{-T} l`), a^2 + b^2 = 1.
    residual, tangent_residual : float
        The largest :math:`|x'^T C' x'|` over the mapped samples (w = 1), and the largest
        :math:`|l'^T C^{*\prime} l'|` over the mapped tangents against :math:`H C^* H^T` (unit norm).
    I_mapped : (3,) complex ndarray
        :math:`H I`, I = (1, i, 0), scaled to a first entry 1.
    fixed : bool
        Whether H fixes I (``np.allclose(H I, I, atol=1e-9)``, so rtol 1e-5).
    axis_ratio : float
        The ellipse's minor / major axis.
    centre : (2,) ndarray
        The centre of C'.
    """

    H: np.ndarray
    C_mapped: np.ndarray
    mapped: np.ndarray
    tangents: np.ndarray
    residual: float
    tangent_residual: float
    I_mapped: np.ndarray
    fixed: bool
    axis_ratio: float
    centre: np.ndarray


def conic_geometry(
    angle_deg: float, aspect: float, h31: float, h32: float, samples: np.ndarray
) -> ConicGeometry:
    """The unit circle C under :func:`conic_homography`: what the demo draws and reports.

    Parameters
    ----------
    angle_deg, aspect, h31, h32 : float
        The controls (:func:`conic_homography`).
    samples : (N, 2) ndarray
        Points on the unit circle.

    Returns
    -------
    ConicGeometry
        H, C' and its centre and axis ratio, the mapped samples and tangents, the two residuals,
        H I.
    """
    H = conic_homography(angle_deg, aspect, h31, h32)
    C = pj.circle_conic([0.0, 0.0], 1.0)
    Cp = pj.map_conic(H, C)
    Cp = Cp / np.linalg.norm(Cp)
    q = pj.map_points(H, samples)
    q_h = pj.to_homogeneous(q)
    tangents = pj.normalise_lines(pj.map_lines(H, CONIC_TANGENTS))
    Cs = pj.map_dual_conic(H, pj.dual_conic(C))
    Cs = Cs / np.linalg.norm(Cs)
    HI = H @ pj.CIRCULAR_POINTS[0]  # I = (1, i, 0)
    A = Cp[:2, :2] * np.sign(np.trace(Cp[:2, :2]))  # made positive definite
    lam = np.linalg.eigvalsh(A)
    return ConicGeometry(
        H=H,
        C_mapped=Cp,
        mapped=q,
        tangents=tangents,
        residual=float(np.abs(np.einsum("ni,ij,nj->n", q_h, Cp, q_h)).max()),
        tangent_residual=float(np.abs(np.einsum("ni,ij,nj->n", tangents, Cs, tangents)).max()),
        I_mapped=HI / HI[0],
        fixed=bool(np.allclose(HI / HI[0], pj.CIRCULAR_POINTS[0], atol=1e-9)),
        axis_ratio=float(np.sqrt(lam[0] / lam[1])),
        centre=np.linalg.solve(Cp[:2, :2], -Cp[:2, 2]),
    )


def _complex_text(z: complex) -> str:
    """``+a.aa+b.bbi``, each part rounded to 0.01 first, so a rounded zero reads +0.00, never -0.00."""
    return f"{round(z.real, 2) + 0.0:+.2f}{round(z.imag, 2) + 0.0:+.2f}i"


def in_square_view(line: np.ndarray, lim: float = 3.0) -> bool:
    """Whether ``line`` crosses the square view [-lim, lim]^2.

    Parameters
    ----------
    line : (3,) ndarray
        The line (a, b, c).
    lim : float
        The view's half-width.

    Returns
    -------
    bool
        True when :func:`camlab.projective.clip_line` finds two finite ends.
    """
    ends = pj.clip_line(line, (-lim, lim), (-lim, lim))  # NaN rows when it misses the view
    return bool(np.all(np.isfinite(ends)))


def conic_caption(g: ConicGeometry, h31: float, h32: float) -> str:
    """The three lines under :func:`~camlab.widgets.projective_plane.conic_under_homography`'s plots.

    The first judges H (does it fix I?), the second the conic itself (its axis ratio): a
    similarity maps *every* circle to a circle, but a non-similarity can still map *this* one to
    a circle (stretch = sqrt(1 - h31^2) with h32 = 0), so the shape is read from C', not from H.
    The third gives the two residuals (round-off: another machine, or the browser's twin, may
    print another digit).

    Parameters
    ----------
    g : ConicGeometry
        :func:`conic_geometry`'s answer.
    h31, h32 : float
        The perspective row.

    Returns
    -------
    str
        Three lines.
    """
    # H sends the line H^T l_inf = (h31, h32, 1) to infinity; C' is bounded while C stays clear of it
    h = np.hypot(h31, h32)
    verdict = (
        "= I: H is a similarity, so it maps every circle to a circle"
        if g.fixed
        else "≠ I: H is no similarity, so some circles become non-circles"
    )
    if abs(g.axis_ratio - 1.0) < 5e-4:
        shape = "a circle"
    elif g.axis_ratio > 0.99:
        shape = "nearly a circle"
    else:
        shape = "an ellipse"
    if h == 0:  # the legend's dashed line is then l_inf itself, which no view shows
        bounded = "H keeps l∞ (the line it sends to ∞ is l∞ itself), so C' stays bounded"
    else:
        seen = "" if in_square_view(np.array([h31, h32, 1.0])) else ", off the view"
        bounded = f"H sends h31 x + h32 y + 1 = 0 to ∞: {1 / h:.1f} from C's centre (> 1{seen})"
    HI = g.I_mapped
    return (
        f"H I ∝ (1, {_complex_text(HI[1])}, {_complex_text(HI[2])}) {verdict}\n"
        f"C': axis ratio {g.axis_ratio:.3f}, {shape}; {bounded}\n"
        f"max |x'ᵀC'x'| over the 8 points {g.residual:.0e};  "
        f"max |l'ᵀC*'l'| over the 4 tangents {g.tangent_residual:.0e}"
    )


class LiftView(NamedTuple):
    """What :func:`lift_view` gives: the ray of a homogeneous point and where each part is drawn.

    Attributes
    ----------
    point_h : (3,) ndarray
        The scaled homogeneous point λ (x, y, w).
    point : (2,) ndarray or None
        The Euclidean point (x/w, y/w) the ray names; None at w = 0 (an ideal point).
    ends : (2, 3) ndarray
        The ray's two ends, both halves through 0, clipped to the 3-D box.
    scaled_shown : bool
        False at λ = 0: (0, 0, 0) names no point, its marker is hidden.
    hit : (3,) ndarray or None
        Where the ray meets the plane w = 1, (x/w, y/w, 1); None when it does not within the box.
    dot : ArrowPlacement or None
        Where the point is drawn in the plane w = 1 (an arrow at the edge when it is off the view
        or ideal); None for the zero vector, which is no ray.
    note : str
        The note over the plane ("" when there is nothing to say).
    """

    point_h: np.ndarray
    point: np.ndarray | None
    ends: np.ndarray
    scaled_shown: bool
    hit: np.ndarray | None
    dot: ArrowPlacement | None
    note: str


LIFT_NOTES = (
    "w = 0: an ideal point, the direction ±(x, y)\n(no sign: the arrow could point either way)",
    "(x/w, y/w) is off this view: the arrow points to it",
    "(x, y, w) = (0, 0, 0) is no ray: it names no point",
)
"""lift_to_plane's notes over the plane: an ideal point, a point off the view, the zero vector."""


def lift_view(ray: np.ndarray, scale: float, box: float, w_max: float, xlim, ylim) -> LiftView:
    """lift_to_plane's per-move arithmetic: the ray of (x, y, w) in a 3-D box, and its point in w = 1.

    The ray's end is ``reach * (x, y, w)`` with the largest ``reach`` that keeps |x|, |y| <= box
    and |w| <= w_max; the ray meets the plane w = 1 at (x/w, y/w, 1), drawn when that lies in the
    box. The plane's view draws the point as :func:`~camlab.plotting.plane.arrow_placement` places
    it in the limits ``xlim`` x ``ylim``.

    Parameters
    ----------
    ray : (3,) array_like
        The ray's direction (x, y, w).
    scale : float
        λ.
    box, w_max : float
        The 3-D box's half-extents: in x and y, and in w.
    xlim, ylim : (lo, hi)
        The plane's view limits.

    Returns
    -------
    LiftView
        The scaled point, the ray's ends, the hit on w = 1, the plane's dot and its note.
    """
    r = np.asarray(ray, dtype=float)
    xh = scale * r
    ideal = abs(r[2]) < 1e-12
    reach = min(box / max(abs(r[0]), abs(r[1]), 1e-12), w_max / max(abs(r[2]), 1e-12))
    end = reach * r  # the ray, both halves, clipped to the 3-D box
    on_plane = not ideal and np.abs(r[:2] / r[2]).max() <= box
    hit = r / r[2] if on_plane else None
    dot, note = None, LIFT_NOTES[2]
    if r.any():  # x = y = w = 0: the zero vector is no ray
        dot = arrow_placement(r, xlim, ylim)
        note = LIFT_NOTES[0] if ideal else (LIFT_NOTES[1] if dot.direction.any() else "")
    return LiftView(
        point_h=xh,
        point=None if ideal else r[:2] / r[2],
        ends=np.array([-end, end]),
        scaled_shown=abs(scale) > 1e-12,
        hit=hit,
        dot=dot,
        note=note,
    )
