"""Exercise 4 of lesson 07: the homography a plane induces between two views (`plane_homography`)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import homography as hg
from ...camera import rotation_from_axis_angle
from .._answers import same_up_to_scale, shape_problem
from .._core import Exercise, Mistake, first_mistake, register_exercise


def _rotation(rvec):
    return rotation_from_axis_angle(np.asarray(rvec, dtype=float))  # cv2.Rodrigues's R


def _plane_cases():
    K = np.array([[800.0, 0, 320], [0, 800, 240], [0, 0, 1]])
    K_b = np.array([[900.0, 0, 300], [0, 850, 250], [0, 0, 1]])  # fx != fy: K and K^T differ
    return [
        # section 9's scene: the plane Z = 3 m, n = (0, 0, -1), d = 3
        (
            K,
            _rotation([0.05, 0.25, 0.02]),
            np.array([0.2, -0.05, 0.025]),
            np.array([0, 0, -1.0]),
            3.0,
        ),
        # the same plane written the other way round: n = (0, 0, 1), d = -3 (n^T X + d = Z - 3)
        (
            K,
            _rotation([-0.1, 0.15, 0.05]),
            np.array([-0.3, 0.1, 0.05]),
            np.array([0, 0, 1.0]),
            -3.0,
        ),
        # a tilted plane with a normal of length 2 (d scales with it): 0.6 Y - 0.8 Z + 3.2 = 0, doubled
        (
            K_b,
            _rotation([0.2, -0.1, 0.1]),
            np.array([0.1, 0.25, -0.1]),
            np.array([0, 1.2, -1.6]),
            6.4,
        ),
    ]


def plane_homography(K, R, t, n, d):
    """H = K (R - t n^T / d) K^-1: the homography the plane n^T X + d = 0 induces between two views.

    Camera 1 is K [I | 0], camera 2 is K [R | t]. A point X of the plane has -n^T X / d = 1, so
    camera 2 sees R X + t = R X - t (n^T X) / d = (R - t n^T / d) X, and X ~ K^-1 x1 gives
    x2 ~ K (R - t n^T / d) K^-1 x1.

    Parameters
    ----------
    K : (3, 3) array_like
        The intrinsics of both cameras, pixels.
    R : (3, 3) array_like
        Rotation cam2_from_cam1.
    t : (3,) array_like
        Translation cam2_from_cam1, metres.
    n : (3,) array_like
        The plane's normal in camera 1's frame (any length: d scales with it).
    d : float
        The plane's offset: the plane is n^T X + d = 0 (d != 0).

    Returns
    -------
    (3, 3) ndarray
        H with x2 ~ H x1, at any scale.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 13.1 (result 13.1, eq. (13.2)).
    """
    K, R = np.asarray(K, dtype=float), np.asarray(R, dtype=float)
    t, n = np.asarray(t, dtype=float).reshape(3, 1), np.asarray(n, dtype=float).reshape(1, 3)
    return K @ (R - t @ n / d) @ np.linalg.inv(K)


def _with(c, middle, left=None, right=None):
    """left @ middle @ right, K and K^-1 by default: a slip inside or outside the bracket."""
    return (
        (c.K if left is None else left) @ middle @ (np.linalg.inv(c.K) if right is None else right)
    )


_PLANE_MISTAKES = (
    Mistake(
        "plus sign",
        lambda c: _with(c, c.R + c.t @ c.n / c.d),
        "you wrote R + t n^T / d. That is the homography of the plane n^T X = d (OpenCV's convention, "
        "cv2.decomposeHomographyMat), or of this plane with n or d negated. Here the plane is "
        "n^T X + d = 0, so -n^T X / d = 1 on it: H = K (R - t n^T / d) K^-1.",
    ),
    Mistake(
        "n t^T",
        lambda c: _with(c, c.R - c.n.T @ c.t.T / c.d),
        "you wrote n t^T where the formula has t n^T: t n^T / d is the column t times the row n^T "
        "(np.outer(t, n)), so that (t n^T) X = t (n^T X). np.outer(n, t) is its transpose.",
    ),
    Mistake(
        "t . n",
        lambda c: _with(c, c.R - (c.n @ c.t).item() / c.d * np.eye(3)),
        "you used the dot product n . t (a number) where the formula has the outer product t n^T "
        "(a 3 x 3 matrix): (t n^T) X = t (n^T X). Use np.outer(t, n), or t[:, None] @ n[None, :].",
    ),
    Mistake(
        "t * n",
        lambda c: _with(c, c.R - (c.t.ravel() * c.n.ravel()) / c.d),
        "you wrote t * n, numpy's element-wise product: a 3-vector, which R - t * n / d then subtracts "
        "from every row of R (broadcasting). The formula has the outer product t n^T, a 3 x 3 matrix: "
        "np.outer(t, n), or t[:, None] * n[None, :].",
    ),
    Mistake(
        "np.dot(t, n)",
        lambda c: _with(c, c.R - (c.n @ c.t).item() / c.d),
        "you wrote np.dot(t, n) (or t @ n): the dot product, one number, which R - ... then subtracts "
        "from every entry of R. The formula has the outer product t n^T, a 3 x 3 matrix: np.outer(t, n).",
    ),
    Mistake(
        "t in mm",
        lambda c: _with(c, c.R - 1000 * c.t @ c.n / c.d),
        "your t is 1000 times too long: t in millimetres with d in metres. t / d is a ratio, so both "
        "must be in one unit (the test gives both in metres): H = K (R - t n^T / d) K^-1.",
    ),
    Mistake(
        "d in mm",
        lambda c: _with(c, c.R - c.t @ c.n / (1000 * c.d)),
        "your d is 1000 times too large: d in millimetres with t in metres. t / d is a ratio, so both "
        "must be in one unit (the test gives both in metres): H = K (R - t n^T / d) K^-1.",
    ),
    Mistake(
        "K order",
        lambda c: _with(c, c.R - c.t @ c.n / c.d, np.linalg.inv(c.K), c.K),
        "you wrote K^-1 (R - t n^T / d) K: the K's are the wrong way round. H takes pixels of image 1 "
        "to rays (K^-1 first, on the right), moves them, and takes them back to pixels (K last, on the "
        "left): H = K (R - t n^T / d) K^-1.",
    ),
    Mistake(
        "no K",
        lambda c: c.R - c.t @ c.n / c.d,
        "you returned R - t n^T / d, the homography between *normalised* image coordinates (rays). "
        "For pixels, wrap it in the intrinsics: H = K (R - t n^T / d) K^-1.",
    ),
    Mistake(
        "no K^-1",
        lambda c: c.K @ (c.R - c.t @ c.n / c.d),
        "you left out K^-1 on the right: H first turns a pixel of image 1 into a ray, K^-1 x1, before "
        "R - t n^T / d moves it. H = K (R - t n^T / d) K^-1.",
    ),
    Mistake(
        "K for K^-1",
        lambda c: _with(c, c.R - c.t @ c.n / c.d, right=c.K),
        "you wrote K (R - t n^T / d) K: the right-hand K must be inverted. K^-1 takes the pixels of "
        "image 1 to rays, which R - t n^T / d moves; K then takes them back to pixels: "
        "H = K (R - t n^T / d) K^-1 (np.linalg.inv(K) on the right).",
    ),
    Mistake(
        "K^T for K^-1",
        lambda c: _with(c, c.R - c.t @ c.n / c.d, right=c.K.T),
        "you used K^T where the formula has K^-1 (np.linalg.inv(K)): the transpose of K is not its "
        "inverse (K is upper triangular, not orthogonal).",
    ),
    Mistake(
        "no 1/d",
        lambda c: _with(c, c.R - c.t @ c.n),
        "you left out the division by d: R - t n^T. That is right only for a plane with d = 1 "
        "(and a normal of the same length). H = K (R - t n^T / d) K^-1.",
    ),
    Mistake(
        "times d",
        lambda c: _with(c, c.R - c.t @ c.n * c.d),
        "you multiplied by d where the formula divides: H = K (R - t n^T / d) K^-1.",
    ),
    Mistake(
        "unit n, d kept",
        lambda c: _with(c, c.R - c.t @ c.n / np.linalg.norm(c.n) / c.d),
        "you made n a unit vector but kept d: the plane n^T X + d = 0 then changes whenever |n| != 1 "
        "(test input 3 has |n| = 2, d = 6.4, a plane 3.2 m from camera 1). Use n and d as given, or "
        "divide both by |n|.",
    ),
    Mistake(
        "R transposed",
        lambda c: _with(c, c.R.T - c.t @ c.n / c.d),
        "you used R^T, the rotation cam1_from_cam2. R is cam2_from_cam1 (camera 2 sees R X + t), as "
        "everywhere in the course: H = K (R - t n^T / d) K^-1.",
    ),
    Mistake(
        "rotation only",
        lambda c: _with(c, c.R),
        "you returned K R K^-1, the homography of a camera that only turns: it leaves out the "
        "translation, which the plane's term - t n^T / d brings in. H = K (R - t n^T / d) K^-1.",
    ),
    Mistake(
        "H transposed",
        lambda c: _with(c, c.R - c.t @ c.n / c.d).T,
        "your H is the transpose of the right one. With points as rows the course maps them by "
        "X @ H.T, so a .T slips in easily (or K^-T (R^T - n t^T / d) K^T, each factor transposed); "
        "return H itself, for x2 ~ H x1 with columns: H = K (R - t n^T / d) K^-1.",
    ),
    Mistake(
        "the inverse",
        lambda c: np.linalg.inv(_with(c, c.R - c.t @ c.n / c.d)),
        "your H maps image 2 to image 1: it is the inverse. x2 ~ H x1, with camera 1 = K [I | 0] and "
        "camera 2 = K [R | t]: H = K (R - t n^T / d) K^-1.",
    ),
)
"""The slips of H = K (R - t n^T / d) K^-1, in the order the diagnosis tests them."""


def _plane_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return H as a (3, 3) array."
    K, R, t, n, d = args
    context = SimpleNamespace(
        K=np.asarray(K, dtype=float),
        R=np.asarray(R, dtype=float),
        t=np.asarray(t, dtype=float).reshape(3, 1),
        n=np.asarray(n, dtype=float).reshape(1, 3),
        d=float(d),
    )
    same = lambda g, wrong: same_up_to_scale(g, wrong, rtol=1e-6)  # noqa: E731
    cause = first_mistake(_PLANE_MISTAKES, context, got, same)
    if cause:
        return cause
    return (
        "check each factor of H = K (R - t n^T / d) K^-1: t n^T is the outer product "
        "np.outer(t, n), the plane is n^T X + d = 0 (so the sign is minus), and K^-1 acts first."
    )


register_exercise(
    Exercise(
        name="plane_homography",
        lesson="07",
        reference=hg.plane_homography,
        cases=_plane_cases,
        compare=lambda got, expected: same_up_to_scale(got, expected, rtol=1e-6),
        up_to_scale=True,
        diagnose=_plane_diagnosis,
        wrong_variants=tuple(
            (
                lambda K, R, t, n, d, m=m: m.answer(
                    SimpleNamespace(
                        K=np.asarray(K, float),
                        R=np.asarray(R, float),
                        t=np.asarray(t, float).reshape(3, 1),
                        n=np.asarray(n, float).reshape(1, 3),
                        d=float(d),
                    )
                ),
                m.hint[:30] if isinstance(m.hint, str) else m.name,
            )
            for m in _PLANE_MISTAKES
        )
        + (
            (lambda K, R, t, n, d: hg.plane_homography(K, R, t, n, d).tolist(), "list"),
            (lambda K, R, t, n, d: hg.plane_homography(K, R, t, n, d)[:2], "(3, 3)"),
        ),
        ndarray_only=True,
        teaching=plane_homography,
    )
)
