"""Exercise 5 of lesson 10: H_P, the affine-rectifying homography of section 7 (`affine_rectification`)."""

from __future__ import annotations

import itertools

import numpy as np

from ... import perspective as pp
from ... import scenes
from .._answers import shape_problem
from .._core import Exercise, register_exercise


def _affine_cases():
    return [
        (scenes.sample_photo("facade").corners,),
        (scenes.sample_photo("page").corners,),
        # tilted up only: the top and bottom edges are parallel, their vanishing point at infinity
        (scenes.sample_photo("facade", pitch=-0.5, yaw=0.0).corners,),
    ]


def _direction(x) -> np.ndarray:
    """``x`` scaled to unit length (the sign kept)."""
    x = np.asarray(x, dtype=float)
    return x / np.linalg.norm(x)


def _parallel(a, b, tol=1e-6) -> bool:
    """Whether the 3-vectors ``a`` and ``b`` are equal up to a nonzero scale (either sign)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if not (np.isfinite(a).all() and np.linalg.norm(a) > 0 and np.linalg.norm(b) > 0):
        return False
    return bool(np.linalg.norm(np.cross(_direction(a), _direction(b))) < tol)


def _same_affine(got, expected) -> bool:
    """H_P up to scale: identity top rows, and a third row along the vanishing line (any scale)."""
    g = np.asarray(got, dtype=float) if np.size(got) == 9 else None
    if g is None or g.shape != (3, 3) or not np.isfinite(g).all() or g[0, 0] == 0:
        return False
    g = g / g[0, 0]
    return np.allclose(g[:2], np.eye(3)[:2], atol=1e-9) and _parallel(g[2], expected[2])


def _lines_of_corners(corners):
    """The six lines through two of the four corners, named, as a student might join them."""
    q = np.c_[np.asarray(corners, dtype=float), np.ones(4)]
    names = "TL TR BR BL".split()
    return [
        (f"{names[i]}-{names[j]}", np.cross(q[i], q[j]))
        for i, j in itertools.combinations(range(4), 2)
    ]


def _affine_diagnosis(args, got, expected) -> str:
    l_true = np.asarray(expected, dtype=float)[2]
    g = np.asarray(got, dtype=float) if np.size(got) in (3, 9) else np.asarray(got)
    if g.shape == (3,):
        if _parallel(g, l_true):
            return "you returned the vanishing line l itself; return H_P, the 3 x 3 matrix with l as its third row."
        return "return H_P, a (3, 3) matrix: rows (1, 0, 0), (0, 1, 0) and the vanishing line l."
    if g.shape == (3, 3) and not np.isfinite(g).all():
        return (
            "your H_P holds inf or NaN: a vanishing point at infinity (here the top and bottom edges are "
            "parallel in the photo) has w = 0, and dividing by w destroys it. Keep the points homogeneous: "
            "v = (c0 x c1) x (c3 x c2) and l = v_across x v_up need no division. If you scaled l, divide "
            "by l3 or by its norm, not by l1 or l2: l1 = 0 here (a horizontal vanishing line)."
        )
    problem = shape_problem(got, expected)
    if problem:
        return problem
    corners = np.asarray(args[0], dtype=float)
    if _parallel(g[:, 2], l_true) and np.allclose(g[:2, :2] / g[0, 0], np.eye(2)):
        return (
            "your l is in the third COLUMN: H_P = [[1, 0, 0], [0, 1, 0], [l1, l2, l3]] has l as its third "
            "ROW (a point x goes to (u, v, l . x): its new w is proportional to its distance from the vanishing line)."
        )
    invertible = bool(np.all(np.isfinite(g)) and abs(np.linalg.det(g)) > 0)
    if invertible and _same_affine(np.linalg.inv(g).T, expected):
        return (
            "you returned H_P^-T, the matrix that maps LINES (lesson 06: l' = H^-T l sends l to "
            "(0, 0, 1)); return H_P itself, which maps points: l as its third row."
        )
    if g[0, 0] != 0 and _parallel(g[2], l_true) and not np.allclose(g[:2] / g[0, 0], np.eye(3)[:2]):
        return (
            "your third row is the vanishing line, right, but the top two rows must be (1, 0, 0) and "
            "(0, 1, 0): H_P only sends l to infinity; the rest of a full rectification (the metric "
            "step) is section 7's H_M."
        )
    if invertible and _same_affine(np.linalg.inv(g), expected):
        return (
            "you returned H_P^-1, which maps the affine view back to the photo; H_P itself has l as its "
            "third row."
        )
    if g[0, 0] != 0 and np.allclose(g[:2] / g[0, 0], np.eye(3)[:2], atol=1e-9):
        row = g[2]
        for name, line in _lines_of_corners(corners):
            if _parallel(row, line):
                return (
                    f"your third row is the line through the corners {name}, not the vanishing line: "
                    "l joins the two VANISHING points, where opposite edges meet (top with bottom, left "
                    "with right): v = (c0 x c1) x (c3 x c2), then l = v_across x v_up."
                )
        q = np.c_[corners, np.ones(4)]
        v_across = np.cross(np.cross(q[0], q[1]), np.cross(q[3], q[2]))
        v_up = np.cross(np.cross(q[0], q[3]), np.cross(q[1], q[2]))
        if _parallel(row, l_true[[1, 0, 2]]):
            return (
                "your l has l1 and l2 swapped: the corners were read as (v, u) (row, column); take "
                "each corner as (u, v, 1), u the column."
            )
        v_diag = np.cross(np.cross(q[0], q[2]), np.cross(q[1], q[3]))  # the diagonals meet inside
        if _parallel(row, np.cross(v_across, v_diag)) or _parallel(row, np.cross(v_diag, v_up)):
            return (
                "one of your points is where the DIAGONALS meet (TL-BR with TR-BL), inside the "
                "rectangle, not a vanishing point: meet opposite EDGES. The corners come TL, TR, BR, "
                "BL (not Zhang & He's TL, TR, BL, BR): the left edge joins c0 and c3, the right c1 "
                "and c2."
            )
        if _parallel(row, v_across) or _parallel(row, v_up):
            return (
                "your third row is a vanishing POINT; l is the LINE through both: l = v_across x v_up "
                "(the join of two points is their cross product)."
            )
    return (
        "H_P = [[1, 0, 0], [0, 1, 0], [l1, l2, l3]] with l = v_across x v_up, v_across = (c0 x c1) x "
        "(c3 x c2) where the top and bottom edges meet and v_up = (c0 x c3) x (c1 x c2) where the left "
        "and right ones do, every corner as (u, v, 1)."
    )


def affine_rectification(corners):
    """Meet opposite edges for the two vanishing points, join them for l, and put l in H_P's third row.

    Parameters
    ----------
    corners : (4, 2) array_like
        The photographed rectangle's corners (u, v), pixels, TL, TR, BR, BL.

    Returns
    -------
    (3, 3) ndarray
        H_P = [[1, 0, 0], [0, 1, 0], l], which sends the vanishing line l to (0, 0, 1); l is
        scaled to l3 = 1 (H&Z assume l3 != 0), so warping with H_P keeps the image's size.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 2.7.2.
    """
    c0, c1, c2, c3 = np.c_[np.asarray(corners, dtype=float), np.ones(4)]
    v_across = np.cross(np.cross(c0, c1), np.cross(c3, c2))  # top and bottom edges meet here
    v_up = np.cross(np.cross(c0, c3), np.cross(c1, c2))  # left and right edges meet here
    line = np.cross(v_across, v_up)  # the vanishing line l joins them
    line = line / line[2]  # any scale is right; raw cross products are ~1e15, so warp with l3 = 1
    return np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], line])


def _euclidean_points(corners):
    """A typical slip: the vanishing points divided by w (inf where an edge pair is parallel)."""
    c0, c1, c2, c3 = np.c_[np.asarray(corners, dtype=float), np.ones(4)]
    with np.errstate(divide="ignore", invalid="ignore"):
        v1 = np.cross(np.cross(c0, c1), np.cross(c3, c2))
        v2 = np.cross(np.cross(c0, c3), np.cross(c1, c2))
        v1, v2 = v1 / v1[2], v2 / v2[2]
        return np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], np.cross(v1, v2)])


def _diagonals(corners):
    """A typical slip: the corners taken as TL, TR, BL, BR, so one meet is of the diagonals."""
    return affine_rectification(np.asarray(corners, dtype=float)[[0, 1, 3, 2]])


def _full_rectification(corners):
    """A typical slip: a whole rectifying homography, whose third row is along l too."""
    q = np.asarray(corners, dtype=float)
    return pp.rectify_quadrilateral(np.zeros((480, 640), np.uint8), q, size=(300, 200)).H


register_exercise(
    Exercise(
        name="affine_rectification",
        lesson="10",
        reference=pp.affine_rectification,
        cases=_affine_cases,
        compare=_same_affine,
        diagnose=_affine_diagnosis,
        wrong_variants=(
            (lambda c: pp.affine_rectification(c)[2], "the vanishing line l itself"),
            (lambda c: pp.affine_rectification(c).T, "third COLUMN"),
            (lambda c: np.linalg.inv(pp.affine_rectification(c)), "H_P^-1"),
            (
                lambda c: np.vstack(
                    [np.eye(3)[:2], np.cross([*np.asarray(c)[0], 1.0], [*np.asarray(c)[1], 1.0])]
                ),
                "the line through the corners TL-TR",
            ),
            (
                lambda c: np.vstack(
                    [
                        np.eye(3)[:2],
                        np.cross(
                            np.cross([*np.asarray(c)[0], 1.0], [*np.asarray(c)[3], 1.0]),
                            np.cross([*np.asarray(c)[1], 1.0], [*np.asarray(c)[2], 1.0]),
                        ),
                    ]
                ),
                "vanishing POINT",
            ),
            (_euclidean_points, "inf or NaN"),
            (lambda c: np.linalg.inv(pp.affine_rectification(c)).T, "H_P^-T"),
            (lambda c: affine_rectification(np.asarray(c)[:, ::-1]), "read as (v, u)"),
            (_diagonals, "DIAGONALS"),
            (_full_rectification, "top two rows"),
        ),
        ndarray_only=True,
        teaching=affine_rectification,
    )
)
