"""Exercises for lesson 10, perspective correction."""

from __future__ import annotations

import itertools
from types import SimpleNamespace

import numpy as np

from .. import perspective as pp
from .. import scenes
from ..homography import estimate_homography
from ..projective import map_points
from ._answers import same_array, same_up_to_scale, shape_problem
from ._core import Exercise, Mistake, first_mistake, register_exercise


def _rect_cases():
    return [
        (np.array([[10.0, 10.0], [110.0, 10.0], [110.0, 60.0], [10.0, 60.0]]), (101, 51)),
        (scenes.sample_photo("page").corners, (210, 297)),
        (scenes.sample_photo("facade").corners, (400, 300)),
    ]


def _rect_target(w, h, order=(0, 1, 2, 3), offset=0.0, extent=None):
    """The target corners TL, TR, BR, BL of a w x h image (``extent``: the far corner), in ``order``."""
    x1, y1 = (w - 1, h - 1) if extent is None else extent
    target = np.array([[0, 0], [x1, 0], [x1, y1], [0, y1]], dtype=float) + offset
    return target[list(order)]


_PIXEL_CENTRES = (
    "camlab's pixel coordinates put the centre of the top-left pixel at (0, 0) (docs/conventions.md), "
    "so the corners go to the corner pixels' centres (0, 0), (w - 1, 0), (w - 1, h - 1), (0, h - 1)."
)

_RECT_MISTAKES = (
    # mistakes in H itself: compared with the right H, up to scale
    Mistake(
        "inverse",
        lambda s: np.linalg.inv(s.expected),
        "your H maps the rectangle into the photo; the rectifying H goes from the photo corners to the "
        "rectangle (estimate_homography(corners, target), not (target, corners)).",
    ),
    Mistake(
        "transposed",
        lambda s: s.expected.T,
        "your H is the transpose of the right one: with points as rows a homography maps them by "
        "x @ H.T, and the DLT's null vector fills H row by row (h.reshape(3, 3), not order='F' or .T).",
    ),
    Mistake(
        "corners as (v, u)",
        lambda s: s.fit(s.corners[:, ::-1], s.target()),
        "you swapped u and v of the photo corners (read them as (row, column)?): a point is (u, v), "
        "column first, and corners[:, 0] is u.",
    ),
    # mistakes in the target rectangle
    Mistake(
        "size read as (height, width)",
        lambda s: s.fit(s.corners, _rect_target(s.h, s.w)),
        lambda s: (
            f"you read size as (height, width): your target is {s.h - 1} wide and {s.w - 1} tall. A size "
            f"is (width, height) (docs/conventions.md), so width, height = size, here {s.w} and {s.h}."
        ),
    ),
    Mistake(
        "target as (v, u)",
        lambda s: s.fit(s.corners, s.target()[:, ::-1]),
        "your target corners are (row, column) = (v, u): a point is (u, v), so the top-right corner is "
        "(w - 1, 0), not (0, w - 1).",
    ),
    Mistake(
        "off by one",
        lambda s: s.fit(s.corners, _rect_target(s.w, s.h, extent=(s.w, s.h))),
        "off by one: the last pixel centre of a width-w image is at u = w - 1, so map to "
        "(w - 1, 0), (w - 1, h - 1), (0, h - 1).",
    ),
    Mistake(
        "1-based",
        lambda s: s.fit(s.corners, _rect_target(s.w, s.h, offset=1.0)),
        "your target is 1-based, (1, 1) to (w, h): numpy and camlab count pixels from 0; "
        + _PIXEL_CENTRES,
    ),
    Mistake(
        "pixel edges",
        lambda s: s.fit(s.corners, _rect_target(s.w, s.h, offset=-0.5, extent=(s.w, s.h))),
        "half a pixel: you mapped to the outer edges of the corner pixels, (-0.5, -0.5) to (w - 0.5, "
        "h - 0.5); " + _PIXEL_CENTRES,
    ),
    Mistake(
        "half a pixel in",
        lambda s: s.fit(s.corners, _rect_target(s.w, s.h, offset=0.5, extent=(s.w - 2, s.h - 2))),
        "half a pixel: you mapped to (0.5, 0.5) to (w - 1.5, h - 1.5); " + _PIXEL_CENTRES,
    ),
    Mistake(
        "shifted by half a pixel",
        lambda s: next(
            (
                H
                for d in (-0.5, 0.5)
                if s.same(H := s.fit(s.corners, _rect_target(s.w, s.h, offset=d)))
            ),
            None,
        ),
        "every corner is off by half a pixel (a +-0.5 shift of the whole target): "
        + _PIXEL_CENTRES,
    ),
    Mistake(
        "Z order",
        lambda s: s.fit(s.corners, s.target((0, 1, 3, 2))),
        "your target corners are in Z order (TL, TR, BL, BR): they must go round the rectangle in the "
        "corners' order, TL, TR, BR, BL = (0, 0), (w - 1, 0), (w - 1, h - 1), (0, h - 1).",
    ),
    Mistake(
        "counter-clockwise",
        lambda s: s.fit(s.corners, s.target((0, 3, 2, 1))),
        "your target goes counter-clockwise (TL, BL, BR, TR): pair TL, TR, BR, BL with (0, 0), "
        "(w - 1, 0), (w - 1, h - 1), (0, h - 1) in that order.",
    ),
)
"""Ex 1's typical mistakes, each the H it gives, in the order the diagnosis tries them."""


def _fit_or_none(src, dst):
    """The homography taking src to dst, or None where the four pairs fix none (a mistake that cannot show here)."""
    try:
        return estimate_homography(src, dst)
    except ValueError:
        return None


def _rect_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    corners, (w, h) = args
    g = np.asarray(got, dtype=float)
    corners = np.asarray(corners, dtype=float)

    def same(wrong):
        return same_up_to_scale(g, wrong, rtol=1e-6)

    context = SimpleNamespace(
        expected=np.asarray(expected, dtype=float),
        corners=corners,
        w=int(w),
        h=int(h),
        target=lambda order=(0, 1, 2, 3): _rect_target(w, h, order),
        fit=_fit_or_none,
        same=same,
    )
    cause = first_mistake(_RECT_MISTAKES, context, g, lambda got_, wrong: same(wrong))
    if cause:
        return cause
    moved = map_points(g, corners)
    want = _rect_target(w, h)
    k = int(np.argmax(np.linalg.norm(moved - want, axis=1)))
    return (
        f"corner {k} ({'TL TR BR BL'.split()[k]}) goes to {np.round(moved[k], 2)}, expected {want[k]}: check "
        "that H maps each photo corner (u, v) to its target pixel, TL, TR, BR, BL to (0, 0), (w - 1, 0), "
        "(w - 1, h - 1), (0, h - 1)."
    )


def rectangle_homography(corners, size):
    """Four pairs fix H: with h33 = 1 each pair gives two linear equations in the other 8 entries.

    Parameters
    ----------
    corners : (4, 2) array_like
        The quadrilateral's corners in the photo (u, v), pixels, in the order top-left, top-right,
        bottom-right, bottom-left.
    size : (2,) array_like of int
        The rectified image's (width, height), pixels.

    Returns
    -------
    (3, 3) ndarray
        H with h33 = 1 mapping the corners to (0, 0), (width - 1, 0), (width - 1, height - 1),
        (0, height - 1).

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 4.1.2 (inhomogeneous solution).
    """
    width, height = size
    target = np.array(
        [[0, 0], [width - 1, 0], [width - 1, height - 1], [0, height - 1]], dtype=float
    )
    A, b = [], []
    for (u, v), (x, y) in zip(np.asarray(corners, dtype=float), target, strict=True):
        A.append([u, v, 1, 0, 0, 0, -x * u, -x * v])  # x (h31 u + h32 v + 1) = h11 u + h12 v + h13
        A.append([0, 0, 0, u, v, 1, -y * u, -y * v])  # y (h31 u + h32 v + 1) = h21 u + h22 v + h23
        b += [x, y]
    h = np.linalg.solve(np.array(A), np.array(b))
    return np.append(h, 1.0).reshape(3, 3)


register_exercise(
    Exercise(
        name="rectangle_homography",
        lesson="10",
        reference=pp.rectangle_homography,
        cases=_rect_cases,
        compare=lambda got, expected: same_up_to_scale(got, expected, rtol=1e-6),
        diagnose=_rect_diagnosis,
        wrong_variants=(
            (
                lambda c, size: np.linalg.inv(pp.rectangle_homography(c, size)),
                "maps the rectangle into the photo",
            ),
            (lambda c, size: pp.rectangle_homography(c, size).T, "transpose"),
            (lambda c, size: pp.rectangle_homography(c, size[::-1]), "(height, width)"),
            (
                lambda c, size: estimate_homography(np.asarray(c)[:, ::-1], _rect_target(*size)),
                "swapped u and v",
            ),
            (
                lambda c, size: estimate_homography(c, _rect_target(*size, extent=size)),
                "off by one",
            ),
            (
                lambda c, size: estimate_homography(c, _rect_target(*size, offset=1.0)),
                "1-based",
            ),
            (
                lambda c, size: estimate_homography(
                    c, _rect_target(*size, offset=-0.5, extent=size)
                ),
                "outer edges of the corner pixels",
            ),
            (
                lambda c, size: estimate_homography(c, _rect_target(*size, offset=0.5)),
                "off by half a pixel",
            ),
            (
                lambda c, size: estimate_homography(c, _rect_target(*size, order=(0, 1, 3, 2))),
                "Z order",
            ),
            (
                lambda c, size: estimate_homography(
                    c, [[0, 0], [0, size[1] - 1], np.subtract(size, 1), [size[0] - 1, 0]]
                ),
                "counter-clockwise",
            ),
        ),
        ndarray_only=True,
        teaching=rectangle_homography,
    )
)


def _rotated_rectangle(angle_deg: float, centre=(320.0, 240.0), size=(260.0, 150.0)) -> np.ndarray:
    """Corners of a w x h rectangle turned by angle_deg on screen, in TL, TR, BR, BL order of the unturned one."""
    t = np.radians(angle_deg)
    R = np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])
    w, h = size
    return np.array([[-w, -h], [w, -h], [w, h], [-w, h]]) / 2 @ R.T + centre


def _order_cases():
    page = scenes.sample_photo("page").corners
    return [
        (np.array([[10.0, 0.0], [0.0, 0.0], [0.0, 10.0], [10.0, 10.0]]),),
        (page[[2, 0, 3, 1]],),
        (page[[3, 2, 1, 0]],),
        (
            np.array([[300.0, 50.0], [520.0, 120.0], [90.0, 300.0], [480.0, 420.0]]),
        ),  # bow-tie order
        # turned quadrilaterals: the corner with the smallest angle around the centroid is
        # then not the top-left one, so sorting by angle alone starts in the wrong place
        (_rotated_rectangle(25.0)[[1, 3, 0, 2]],),
        (_rotated_rectangle(-35.0)[[2, 1, 3, 0]],),
        (_rotated_rectangle(40.0, size=(200.0, 300.0))[[3, 0, 2, 1]],),
        # pages seen in perspective and turned: convex, but no rectangle, so the "u + v, v - u"
        # trick (TL = argmin u + v, TR = argmin v - u, ...) picks one corner twice
        (np.array([[482.0, 344.0], [194.0, 290.0], [352.0, 18.0], [211.0, 505.0]]),),
        (np.array([[150.0, 60.0], [600.0, 180.0], [420.0, 300.0], [60.0, 250.0]]),),
    ]


def _sum_difference_trick(corners):
    """A popular shortcut that holds for rectangles only: TL, TR, BR, BL by the extremes of u + v and v - u."""
    q = np.asarray(corners, dtype=float)
    s, d = q.sum(axis=1), q[:, 1] - q[:, 0]
    return q[[np.argmin(s), np.argmin(d), np.argmax(s), np.argmax(d)]]


def _order_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    g = np.asarray(got, dtype=float)
    corners = np.asarray(args[0], dtype=float)
    which = [np.flatnonzero(np.all(np.isclose(corners, p), axis=1)) for p in g]
    if any(len(k) == 0 for k in which):
        return (
            "your four points are not the input corners: return the same four points (u, v), reordered "
            "(not indices, not moved, not (v, u))."
        )
    if len({int(k[0]) for k in which}) < 4:
        twice = (
            "the u + v / v - u shortcut"
            if np.allclose(g, _sum_difference_trick(corners))
            else "your method"
        )
        return (
            f"one input corner comes back twice and another is missing: {twice} (TL = argmin u + v, TR = argmin "
            "v - u, ...) holds for upright rectangles only; a page seen in perspective can have one corner "
            "extreme in both sums. Sort by the angle around the centroid (np.arctan2(v - v_c, u - u_c)), then "
            "start at the smallest u + v."
        )
    for shift in (1, 2, 3):
        if np.allclose(g, np.roll(expected, shift, axis=0)):
            return "the cyclic order is right but it does not start at the top-left corner (smallest u + v)."
    if np.allclose(g[:, ::-1], expected):
        return (
            "your points come back as (v, u), row first: return each corner as it came in, (u, v), column first "
            "(on a square this also looks like counter-clockwise order)."
        )
    if any(np.allclose(g, np.roll(expected[::-1], s, axis=0)) for s in range(4)):
        return "your corners go counter-clockwise on screen; remember v points down, so sort by increasing angle."
    if np.allclose(g, expected[[0, 1, 3, 2]]):
        return (
            "your corners are in Z order (TL, TR, BL, BR, what sorting by v, then u, gives): it zig-zags "
            "across the page, and a homography fed that order makes a bow tie. Go round the quadrilateral: "
            "sort by the angle around the centroid (np.arctan2(v - v_c, u - u_c)), then start at the "
            "smallest u + v."
        )
    return (
        "your order crosses itself or does not go round the quadrilateral; sort by the angle around the "
        "centroid (np.arctan2(v - v_c, u - u_c)), which works for any convex quadrilateral, then start at "
        "the top-left corner (smallest u + v)."
    )


def order_corners(corners):
    """Sort by angle around the centroid (clockwise on screen, v down), then start at min u + v.

    Parameters
    ----------
    corners : (4, 2) array_like
        A convex quadrilateral's corners (u, v), pixels, in any order.

    Returns
    -------
    (4, 2) ndarray
        The corners clockwise on screen, starting at the top-left one (smallest u + v).
    """
    q = np.asarray(corners, dtype=float)
    c = q.mean(axis=0)
    q = q[np.argsort(np.arctan2(q[:, 1] - c[1], q[:, 0] - c[0]))]
    return np.roll(q, -np.argmin(q.sum(axis=1)), axis=0)


def _sorted_by_angle(corners):
    """A plausible mistake: sort by angle around the centroid, but never rotate to the top-left."""
    q = np.asarray(corners, dtype=float)
    c = q.mean(axis=0)
    return q[np.argsort(np.arctan2(q[:, 1] - c[1], q[:, 0] - c[0]))]


register_exercise(
    Exercise(
        name="order_corners",
        lesson="10",
        reference=pp.order_corners,
        cases=_order_cases,
        compare=same_array(),
        diagnose=_order_diagnosis,
        wrong_variants=(
            (lambda c: np.roll(pp.order_corners(c), 1, axis=0), "does not start at the top-left"),
            (lambda c: pp.order_corners(c)[::-1], "counter-clockwise"),
            (
                lambda c: np.asarray(c, float)[
                    np.lexsort((np.asarray(c)[:, 0], np.asarray(c)[:, 1]))
                ],
                "sort by the angle",
            ),
            (_sorted_by_angle, "does not start at the top-left"),
            (lambda c: pp.order_corners(c)[[0, 1, 3, 2]], "Z order"),
            (lambda c: pp.order_corners(c)[:, ::-1], "(v, u)"),
            (_sum_difference_trick, "holds for upright rectangles only"),
        ),
        ndarray_only=True,
        teaching=order_corners,
    )
)


def _grid_photo(G) -> np.ndarray:
    """The image corners of a 6 x 9 grid of unit squares seen through the plane homography G."""
    plane = np.stack(np.meshgrid(np.arange(9.0), np.arange(6.0)), axis=-1).reshape(-1, 2)
    return map_points(np.asarray(G, dtype=float), plane).reshape(6, 9, 2)


def _conic_cases():
    Gs = [
        [[40.0, 8.0, 150.0], [-5.0, 32.0, 90.0], [0.03, 0.02, 1.0]],
        [[30.0, -12.0, 300.0], [10.0, 35.0, 60.0], [-0.02, 0.045, 1.0]],
        [
            [25.0, 0.0, 200.0],
            [0.0, 25.0, 100.0],
            [0.0, 0.06, 1.0],
        ],  # tilt only, like a keystone photo
    ]
    return [pp.square_grid_right_angles(_grid_photo(G)) for G in Gs]


def _conic_rows(lines_l, lines_m, half=True):
    """The rows of section 8, one per pair; ``half=False``: the cross terms without their 1/2."""
    (l1, l2, l3), (m1, m2, m3) = np.asarray(lines_l, float).T, np.asarray(lines_m, float).T
    k = 0.5 if half else 1.0
    cols = [
        l1 * m1,
        k * (l1 * m2 + l2 * m1),
        l2 * m2,
        k * (l1 * m3 + l3 * m1),
        k * (l2 * m3 + l3 * m2),
        l3 * m3,
    ]
    return np.stack(cols, axis=1)


def _conic_matrix(x, half=True):
    """(a, b, c, d, e, f) arranged as the symmetric matrix, b/2, d/2, e/2 off the diagonal (``half=False``: b, d, e)."""
    a, b, c, d, e, f = x
    k = 0.5 if half else 1.0
    return np.array([[a, k * b, k * d], [k * b, c, k * e], [k * d, k * e, f]])


def _conic_vector(C):
    """The matrix's (a, b, c, d, e, f), as section 8 names them."""
    return np.array([C[0, 0], 2 * C[0, 1], C[1, 1], 2 * C[0, 2], 2 * C[1, 2], C[2, 2]])


_UNKNOWNS = "a b c d e f".split()


def _same_dual_conic(got, expected, rtol=1e-3) -> bool:
    """Equal up to scale, after rescaling the image axes so that expected's diagonal is 1.

    In pixels the entries of C*' span many orders of magnitude (a ~ 1, f ~ 1e5), so a plain relative
    comparison weighs f alone; D C D with D = diag(|expected_ii|^-1/2) is the same conic in other
    pixel units (a change of coordinates, x -> D x), where every entry counts. rtol 1e-3 passes any
    sound solver of the stacked rows (an SVD of the rows, with or without Hartley conditioning, or the
    smallest eigenvector of A^T A, which squares the rows' condition number and lands about 1e-4 away on
    these pixel lines) and rejects each typical slip by orders of magnitude more.
    """
    e = np.asarray(expected, dtype=float)
    D = np.diag(1 / np.sqrt(np.abs(np.diag(e))))
    g = np.asarray(got, dtype=float)
    if g.shape != e.shape:
        return False
    return same_up_to_scale(D @ g @ D, D @ e @ D, rtol=rtol)


def _conic_diagnosis(args, got, expected) -> str:
    g = np.asarray(got, dtype=float) if np.size(got) else np.asarray(got)
    if g.shape == (6,):
        return (
            "you returned the null vector (a, b, c, d, e, f); arrange it as the symmetric 3 x 3 matrix "
            "[[a, b/2, d/2], [b/2, c, e/2], [d/2, e/2, f]]."
        )
    problem = shape_problem(got, expected)
    if problem:
        return problem
    if not np.allclose(g, g.T, rtol=1e-6, atol=1e-9 * np.abs(g).max()):
        return (
            "your matrix is not symmetric: a dual conic is; put b/2 at [0, 1] and [1, 0], d/2 at [0, 2] "
            "and [2, 0], e/2 at [1, 2] and [2, 1]."
        )
    lines_l, lines_m = args
    e = np.asarray(expected, dtype=float)
    off = np.ones((3, 3)) - np.eye(3)
    if _same_dual_conic(g * (1 - off / 2), e):
        return (
            "the off-diagonal entries are twice too big: the row's cross terms (l1 m2 + l2 m1) multiply b, "
            "and the matrix holds b/2 (as in a conic's matrix); either halve the cross terms in each row or "
            "put b/2, d/2, e/2 into the matrix."
        )
    if _same_dual_conic(g * (1 + off), e):
        return (
            "the off-diagonal entries are half what they should be: your rows have the full cross terms "
            "(l1 m2 + l2 m1, no 1/2), so the unknown they multiply is already the matrix entry, and you "
            "halved it again. Halve once: the 1/2 in the rows (as in section 8) or b/2 in the matrix, not both."
        )
    want = _conic_vector(e)
    mine = _conic_vector(g)
    for perm in itertools.permutations(range(6)):
        if perm != tuple(range(6)) and same_up_to_scale(mine, want[list(perm)], rtol=1e-4):
            moved = [
                f"{_UNKNOWNS[i]} where {_UNKNOWNS[p]} belongs" for i, p in enumerate(perm) if i != p
            ]
            return (
                "your entries are the right numbers in the wrong places ("
                + ", ".join(moved)
                + "): the "
                "columns of your rows and the unknowns you arrange into the matrix must be in the same order, "
                "(a, b, c, d, e, f) for l1 m1, (l1 m2 + l2 m1)/2, l2 m2, (l1 m3 + l3 m1)/2, (l2 m3 + l3 m2)/2, "
                "l3 m3, and the matrix [[a, b/2, d/2], [b/2, c, e/2], [d/2, e/2, f]]."
            )
    for half in (True, False):
        Vt = np.linalg.svd(_conic_rows(lines_l, lines_m, half))[2]
        if same_up_to_scale(g, _conic_matrix(Vt[:, -1], half), rtol=1e-5):
            return (
                "you took a column of Vt. np.linalg.svd returns Vt, V transposed: the right singular "
                "vectors are its rows, so the null vector is the last row, Vt[-1], not Vt[:, -1]."
            )
        if same_up_to_scale(g, _conic_matrix(Vt[0], half), rtol=1e-5):
            return (
                "you took the FIRST row of Vt, the direction of the largest singular value; the null vector "
                "(the smallest singular value, 0 here) is the LAST row of Vt, Vt[-1]."
            )
    rows = _conic_rows(lines_l, lines_m)
    residual = np.linalg.norm(rows @ mine) / (np.linalg.norm(rows, 2) * np.linalg.norm(mine))
    if residual > 1e-6:
        return (
            f"your matrix does not make the pairs orthogonal: the rows times your (a, b, c, d, e, f) reach "
            f"{residual:.2g} (relative), where the answer gives 0. Check each row against section 8 (one row "
            "per pair, the 1/2 on the cross terms) and take the null vector, the last row of Vt."
        )
    return (
        "every pair satisfies l^T C m = 0 but only roughly (your matrix is close to the answer, not within "
        "1e-3 of it): a solver that squares the rows' condition number (np.linalg.eigh(A.T @ A), np.linalg.inv "
        "of normal equations) loses digits on pixel lines; take the SVD of the rows themselves, or normalise "
        "the lines first (lesson 07, section 6)."
    )


def dual_conic_from_orthogonal_lines(lines_l, lines_m):
    """Each orthogonal pair gives l^T C* m = 0, one linear equation in (a, b, c, d, e, f); take the null vector.

    Parameters
    ----------
    lines_l, lines_m : (N, 3) array_like
        Image lines (a, b, c), N >= 5; ``lines_l[i]`` is orthogonal to ``lines_m[i]`` on the plane.

    Returns
    -------
    (3, 3) ndarray
        The image of the dual conic C*inf, symmetric, up to scale.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 2.7.5, example 2.27.
    """
    (l1, l2, l3), (m1, m2, m3) = np.asarray(lines_l, float).T, np.asarray(lines_m, float).T
    rows = np.stack(
        [
            l1 * m1,
            (l1 * m2 + l2 * m1) / 2,
            l2 * m2,
            (l1 * m3 + l3 * m1) / 2,
            (l2 * m3 + l3 * m2) / 2,
            l3 * m3,
        ],
        axis=1,
    )
    a, b, c, d, e, f = np.linalg.svd(rows)[2][-1]  # the null vector: the last row of Vt
    return np.array([[a, b / 2, d / 2], [b / 2, c, e / 2], [d / 2, e / 2, f]])


def _full_cross_terms(lines_l, lines_m):
    """A typical slip: b, d, e (not b/2, d/2, e/2) off the diagonal."""
    C = pp.dual_conic_from_orthogonal_lines(lines_l, lines_m)
    return C * (1 + (np.ones((3, 3)) - np.eye(3)))


def _first_singular_vector(lines_l, lines_m):
    """A typical slip: the first row of Vt (the largest singular value) instead of the last."""
    (l1, l2, l3), (m1, m2, m3) = np.asarray(lines_l, float).T, np.asarray(lines_m, float).T
    rows = np.stack(
        [
            l1 * m1,
            (l1 * m2 + l2 * m1) / 2,
            l2 * m2,
            (l1 * m3 + l3 * m1) / 2,
            (l2 * m3 + l3 * m2) / 2,
            l3 * m3,
        ],
        1,
    )
    a, b, c, d, e, f = np.linalg.svd(rows)[2][0]
    return np.array([[a, b / 2, d / 2], [b / 2, c, e / 2], [d / 2, e / 2, f]])


def _upper_triangle_only(lines_l, lines_m):
    """A typical slip: the coefficients written into the upper triangle only."""
    return np.triu(_full_cross_terms(lines_l, lines_m))


register_exercise(
    Exercise(
        name="dual_conic_from_orthogonal_lines",
        lesson="10",
        reference=pp.dual_conic_from_orthogonal_lines,
        cases=_conic_cases,
        compare=_same_dual_conic,
        diagnose=_conic_diagnosis,
        wrong_variants=(
            (_full_cross_terms, "twice too big"),
            (_first_singular_vector, "LAST row of Vt"),
            (_upper_triangle_only, "not symmetric"),
            (
                lambda L, M: np.linalg.svd(
                    np.stack(
                        [
                            L[:, 0] * M[:, 0],
                            (L[:, 0] * M[:, 1] + L[:, 1] * M[:, 0]) / 2,
                            L[:, 1] * M[:, 1],
                            (L[:, 0] * M[:, 2] + L[:, 2] * M[:, 0]) / 2,
                            (L[:, 1] * M[:, 2] + L[:, 2] * M[:, 1]) / 2,
                            L[:, 2] * M[:, 2],
                        ],
                        1,
                    )
                )[2][-1],
                "null vector (a, b, c, d, e, f)",
            ),
            (
                lambda L, M: _conic_matrix(np.linalg.svd(_conic_rows(L, M, half=False))[2][-1]),
                "half what they should be",
            ),
            (
                lambda L, M: _conic_matrix(
                    _conic_vector(pp.dual_conic_from_orthogonal_lines(L, M))[[0, 1, 2, 4, 3, 5]]
                ),
                "d where e belongs",
            ),
            (
                lambda L, M: _conic_matrix(np.linalg.svd(_conic_rows(L, M))[2][:, -1]),
                "column of Vt",
            ),
        ),
        ndarray_only=True,
        teaching=dual_conic_from_orthogonal_lines,
    )
)


# --------------------------------------------------------------------------- aspect ratio and f from four corners


def _shape_cases():
    """Rectangles photographed by cameras of known f and principal point (not the image centre)."""

    def photo(w, h, f, c, yaw, pitch, roll, distance):
        cy, sy, cp, sp, cr, sr = (
            np.cos(yaw),
            np.sin(yaw),
            np.cos(pitch),
            np.sin(pitch),
            np.cos(roll),
            np.sin(roll),
        )
        R = (
            np.array([[cr, -sr, 0], [sr, cr, 0], [0, 0, 1]])
            @ np.array([[1, 0, 0], [0, cp, -sp], [0, sp, cp]])
            @ np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
        )
        K = np.array([[f, 0, c[0]], [0, f, c[1]], [0, 0, 1.0]])
        plane = np.array([[-w, -h], [w, -h], [w, h], [-w, h]]) / 2  # TL, TR, BR, BL, y down
        X = np.column_stack([plane, np.zeros(4)]) @ R.T + [0, 0, distance]
        x = X @ K.T
        return x[:, :2] / x[:, 2:]

    return [
        (photo(2.97, 2.10, 800.0, (319.5, 239.5), 0.5, 0.35, 0.1, 5.0), (319.5, 239.5)),
        (photo(1.0, 1.6, 1200.0, (700.0, 380.0), -0.3, -0.45, -0.05, 4.0), (700.0, 380.0)),
        (photo(3.0, 1.0, 650.0, (330.0, 250.0), 0.25, 0.6, 0.0, 9.0), (330.0, 250.0)),
    ]


def _shape_reference(corners, principal_point):
    est = pp.estimate_aspect_ratio(corners, principal_point=principal_point)
    return est.ratio, est.focal_length


def _shape_compare(got, expected) -> bool:
    try:
        g = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        return False
    return g.shape == (2,) and bool(np.allclose(g, expected, rtol=1e-6, atol=0))


def _zhang_he(corners, principal_point, order=(0, 1, 3, 2), centre=True):
    """Section 3 with the corners taken as m1..m4 in ``order`` (Zhang & He's: TL, TR, BL, BR)."""
    q = np.asarray(corners, dtype=float) - (np.asarray(principal_point, float) if centre else 0.0)
    m1, m2, m3, m4 = np.column_stack([q, np.ones(4)])[list(order)]
    k2 = np.cross(m1, m4) @ m3 / (np.cross(m2, m4) @ m3)
    k3 = np.cross(m1, m4) @ m2 / (np.cross(m3, m4) @ m2)
    n2, n3 = k2 * m2 - m1, k3 * m3 - m1
    f2 = -(n2[0] * n3[0] + n2[1] * n3[1]) / (n2[2] * n3[2])
    return n2, n3, f2


def _shape_from(n2, n3, f2):
    ratio2 = ((n2[0] ** 2 + n2[1] ** 2) / f2 + n2[2] ** 2) / (
        (n3[0] ** 2 + n3[1] ** 2) / f2 + n3[2] ** 2
    )
    return ratio2, f2


_SHAPE_MISTAKES = (
    Mistake(
        "(f, ratio)",
        lambda s: (s.f, s.ratio),
        "you returned (f, ratio); return them as (ratio, f), w/h first.",
    ),
    Mistake(
        "h/w",
        lambda s: (1 / s.ratio, s.f),
        "your ratio is h/w: the edge TL-TR (n2, along e1) is the width, so w/h = |A^-1 n2| / |A^-1 n3|, "
        "not its inverse.",
    ),
    Mistake(
        "squares",
        lambda s: (s.ratio**2, s.f**2),
        "you returned (w/h)^2 and f^2: take the square roots of both formulas.",
    ),
    Mistake(
        "ratio squared",
        lambda s: (s.ratio**2, s.f),
        "your ratio is (w/h)^2: section 3's formula gives the square; take np.sqrt.",
    ),
    Mistake(
        "f squared",
        lambda s: (s.ratio, s.f**2),
        "your f is f^2: section 3's formula gives the square; take np.sqrt.",
    ),
    Mistake(
        "section 2's order as m1..m4",
        lambda s: s.wrong(order=(0, 1, 2, 3)),
        "you took the corners TL, TR, BR, BL as m1, m2, m3, m4, but in section 3 (Zhang & He's numbering) "
        "m3 is the bottom-LEFT corner and m4 the bottom-right: m1, m2, m3, m4 = corners[[0, 1, 3, 2]].",
    ),
    Mistake(
        "principal point not subtracted",
        lambda s: s.wrong(centre=False),
        "the corners must be taken relative to the principal point (m_i = (u_i - c_u, v_i - c_v, 1)): the "
        "formula assumes A = diag(f, f, 1), a camera whose principal point is the origin.",
    ),
)
"""Ex 'rectangle_shape''s typical mistakes, each the (ratio, f) it gives."""


def _shape_diagnosis(args, got, expected) -> str:
    try:
        g = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        g = None
    if g is None or g.shape != (2,):
        shape = "nothing" if g is None else f"shape {g.shape}"
        return f"return two numbers, (ratio, f): w/h and the focal length in pixels; got {shape}."
    corners, principal_point = args
    ratio, f = expected
    if not np.isfinite(g).all():
        return (
            "NaN: f^2 (or (w/h)^2) came out negative, so np.sqrt gave NaN; a rectangle's true corners never do "
            "that. Check the corner order (section 3, Zhang & He, numbers them m1 = TL, m2 = TR, m3 = BL, m4 = BR, "
            "while the input is TL, TR, BR, BL, so m1, m2, m3, m4 = corners[[0, 1, 3, 2]]) and that the corners "
            "are taken relative to the principal_point given (not the image centre, not the origin)."
        )

    def wrong(**how):  # what a student who made this slip returns (np.sqrt of abs, so no NaN)
        ratio2, f2 = _shape_from(*_zhang_he(corners, principal_point, **how))
        return np.sqrt(abs(ratio2)), np.sqrt(abs(f2))

    context = SimpleNamespace(ratio=ratio, f=f, wrong=wrong)
    cause = first_mistake(
        _SHAPE_MISTAKES, context, g, lambda mine, theirs: bool(np.allclose(mine, theirs, rtol=1e-6))
    )
    if cause:
        return cause
    if np.isclose(g[1], f, rtol=1e-6):
        return (
            "your f is right but the ratio is not: w/h squared is ((n21^2 + n22^2)/f^2 + n23^2) over the same "
            "with n3; check that both n_ij are divided by f^2 on their first two entries only."
        )
    if np.isclose(g[0], ratio, rtol=1e-6):
        return (
            "your ratio is right but f is not: f^2 = -(n21 n31 + n22 n32) / (n23 n33), in pixels."
        )
    return (
        "check k2 and k3 (both use m1 x m4, dotted with m3 and m2), then n2 = k2 m2 - m1 and n3 = k3 m3 - m1, "
        "with m_i the corners relative to the principal point in Zhang & He's order TL, TR, BL, BR."
    )


def rectangle_shape(corners, principal_point):
    """Zhang & He (section 3): k2, k3 from triple products, n2, n3, then f^2 and (w/h)^2.

    Parameters
    ----------
    corners : (4, 2) array_like
        The rectangle's corners in the photo (u, v), pixels, TL, TR, BR, BL; no edge pair parallel.
    principal_point : (2,) array_like
        (c_u, c_v), pixels.

    Returns
    -------
    ratio : float
        The rectangle's width / height (width = the TL-TR edge).
    f : float
        The focal length in pixels.

    References
    ----------
    Z. Zhang and L.-W. He, "Whiteboard scanning and image enhancement", Digital Signal Processing
    17(2), 2007.
    """
    q = np.asarray(corners, dtype=float) - np.asarray(principal_point, dtype=float)
    m1, m2, m4, m3 = np.column_stack([q, np.ones(4)])  # TL, TR, BR, BL in; Zhang & He's m3 is BL
    k2 = np.cross(m1, m4) @ m3 / (np.cross(m2, m4) @ m3)
    k3 = np.cross(m1, m4) @ m2 / (np.cross(m3, m4) @ m2)
    n2, n3 = k2 * m2 - m1, k3 * m3 - m1  # along w e1 and h e2, through A = diag(f, f, 1)
    f2 = -(n2[0] * n3[0] + n2[1] * n3[1]) / (n2[2] * n3[2])  # from e1 . e2 = 0
    ratio2 = ((n2[0] ** 2 + n2[1] ** 2) / f2 + n2[2] ** 2) / (
        (n3[0] ** 2 + n3[1] ** 2) / f2 + n3[2] ** 2
    )
    return float(np.sqrt(ratio2)), float(np.sqrt(f2))


def _shape_wrong(order=(0, 1, 3, 2), centre=True):
    def student(corners, principal_point):
        ratio2, f2 = _shape_from(*_zhang_he(corners, principal_point, order, centre))
        return float(np.sqrt(abs(ratio2))), float(np.sqrt(abs(f2)))

    return student


register_exercise(
    Exercise(
        name="rectangle_shape",
        lesson="10",
        reference=_shape_reference,
        cases=_shape_cases,
        compare=_shape_compare,
        diagnose=_shape_diagnosis,
        wrong_variants=(
            (lambda c, p: (1 / _shape_reference(c, p)[0], _shape_reference(c, p)[1]), "h/w"),
            (lambda c, p: _shape_reference(c, p)[::-1], "(ratio, f), w/h first"),
            (
                lambda c, p: (_shape_reference(c, p)[0] ** 2, _shape_reference(c, p)[1]),
                "take np.sqrt",
            ),
            (_shape_wrong(order=(0, 1, 2, 3)), "Zhang & He's numbering"),
            (
                lambda c, p: tuple(np.sqrt(_shape_from(*_zhang_he(c, p, order=(0, 1, 2, 3))))),
                "corners[[0, 1, 3, 2]]",
            ),
            (_shape_wrong(centre=False), "relative to the principal point"),
        ),
        teaching=rectangle_shape,
        solution_note=(
            "# camlab's own, tested route: camlab.perspective.estimate_aspect_ratio(corners,\n"
            "# principal_point=...) returns .ratio and .focal_length (read it with pp.estimate_aspect_ratio??)"
        ),
    )
)
