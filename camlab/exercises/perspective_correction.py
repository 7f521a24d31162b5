"""Exercises for lesson 10, perspective correction."""

from __future__ import annotations

import numpy as np

from .. import perspective as pp
from .. import scenes
from ..homography import estimate_homography
from ..projective import map_points
from ._answers import same_array, same_up_to_scale, shape_problem
from ._core import Exercise, register_exercise


def _rect_cases():
    return [
        (np.array([[10.0, 10.0], [110.0, 10.0], [110.0, 60.0], [10.0, 60.0]]), (101, 51)),
        (scenes.sample_photo("page").corners, (210, 297)),
        (scenes.sample_photo("facade").corners, (400, 300)),
    ]


def _rect_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    corners, (w, h) = args
    g = np.asarray(got, dtype=float)
    if same_up_to_scale(g, np.linalg.inv(expected), rtol=1e-5):
        return "your H maps the rectangle into the photo; the rectifying H goes from the photo corners to the rectangle."
    moved = map_points(g, corners)
    want = np.array([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]], dtype=float)
    if np.allclose(moved, want * [w / (w - 1), h / (h - 1)], atol=1e-6):
        return (
            "off by one: the last pixel centre of a width-w image is at u = w - 1, so map to "
            "(w - 1, 0), (w - 1, h - 1), (0, h - 1)."
        )
    k = int(np.argmax(np.linalg.norm(moved - want, axis=1)))
    return (
        f"corner {k} ({'TL TR BR BL'.split()[k]}) goes to {np.round(moved[k], 2)}, expected {want[k]}; "
        f"pair TL, TR, BR, BL with (0, 0), (w - 1, 0), (w - 1, h - 1), (0, h - 1) in that order."
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
            (
                lambda c, size: estimate_homography(c, [[0, 0], [size[0], 0], size, [0, size[1]]]),
                "off by one",
            ),
            (
                lambda c, size: estimate_homography(
                    c, [[0, 0], [0, size[1] - 1], np.subtract(size, 1), [size[0] - 1, 0]]
                ),
                "pair TL, TR",
            ),
        ),
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
    ]


def _order_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    g = np.asarray(got, dtype=float)
    for shift in (1, 2, 3):
        if np.allclose(g, np.roll(expected, shift, axis=0)):
            return "the cyclic order is right but it does not start at the top-left corner (smallest u + v)."
    if np.allclose(g, expected[::-1]) or any(
        np.allclose(g, np.roll(expected[::-1], s, axis=0)) for s in range(4)
    ):
        return "your corners go counter-clockwise on screen; remember v points down, so sort by increasing angle."
    return (
        "sorting by coordinates alone fails for tilted quadrilaterals; sort by the angle around the "
        "centroid (np.arctan2(v - v_c, u - u_c)), then start at the top-left corner."
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
        ),
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
    off = np.ones((3, 3)) - np.eye(3)
    halved = g * (1 - off / 2)  # a full b where b/2 belongs: halve the off-diagonal entries
    if same_up_to_scale(halved, expected, rtol=1e-5):
        return (
            "the off-diagonal entries are twice too big: the row's cross terms (l1 m2 + l2 m1) multiply b, "
            "and the matrix holds b/2 (as in a conic's matrix); either halve the cross terms in each row or "
            "put b/2, d/2, e/2 into the matrix."
        )
    r = np.abs(np.einsum("ni,ij,nj->n", np.asarray(lines_l), g, np.asarray(lines_m)))
    scale = np.linalg.norm(g) * np.linalg.norm(lines_l, axis=1) * np.linalg.norm(lines_m, axis=1)
    if np.max(r / scale) > 1e-6:
        return (
            f"your matrix does not make the pairs orthogonal: |l_i^T C m_i| reaches {np.max(r / scale):.2g} "
            "(relative); the answer is the null vector of the stacked rows, the LAST row of Vt from "
            "np.linalg.svd (the smallest singular value), not the first."
        )
    return (
        "every pair satisfies l^T C m = 0 but the matrix is not the one wanted: use all the pairs (at "
        "least 5 independent ones) and one equation per pair."
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
        compare=lambda got, expected: same_up_to_scale(got, expected, rtol=1e-5),
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
        ),
        teaching=dual_conic_from_orthogonal_lines,
    )
)
