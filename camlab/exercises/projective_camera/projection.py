"""Lesson 04's exercise project_points: pixels of world points, x = P (X, 1), divided by its third coordinate."""

from __future__ import annotations

import numpy as np

from ... import camera as cm
from .._answers import same_array, same_up_to_scale, shape_problem
from .._core import Exercise, register_exercise
from ._scenes import cameras, world_points

# -- project_points -------------------------------------------------------------------


def _project_cases():
    X = world_points()
    return [(c.P, X) for c in cameras()] + [(-3.0 * cameras()[0].P, X)]


def _project_diagnosis(args, got, expected) -> str:
    P, X = args
    behind = _masked_by_w(P, X, got, expected)
    if behind:
        return behind
    if isinstance(got, (tuple, list)) and len(got) == 2 and np.shape(got[0]) == (len(X),):
        return (
            f"you returned u and v as two separate arrays of {len(X)} numbers (`return u, v`). Return one "
            f"(N, 2) array with a row (u, v) per point: np.column_stack([u, v]), or slice x[:, :2] / x[:, 2:3] "
            f"from x = X_h @ P.T directly."
        )
    problem = shape_problem(got, expected)
    if problem:
        if np.shape(got) == (len(X), 3):
            return (
                problem
                + ". You returned homogeneous pixels: divide by the third coordinate and drop it."
            )
        if np.shape(got) == (3, len(X)):
            return problem + ". Points are rows: compute X_h @ P.T, not P @ X_h."
        if np.shape(got) == (2, len(X)):
            return (
                problem
                + ": your pixels are columns (you projected P @ X_h.T). Points are rows here: "
                "compute X_h @ P.T, whose rows are the (u, v, w) of each point, or transpose your result."
            )
        return problem
    g = np.asarray(got, dtype=float)
    Xh = np.hstack([X, np.ones((len(X), 1))])
    x = Xh @ P.T
    if np.allclose(g, x[:, :2], rtol=1e-6, atol=1e-6):
        return "you kept (x, y) without dividing by the third coordinate w = depth: u = x / w, v = y / w."
    if same_up_to_scale(g, x[:, :2], rtol=1e-6):
        return (
            "you kept (x, y) of a rescaled P (P / P[2, 3] or similar) without dividing by w. Rescaling P cannot "
            "make w = 1 for every point: w is each point's own depth (times P's scale). Divide per point: "
            "u = x / w, v = y / w."
        )
    if np.allclose(g[:, 1], 1.0) and np.allclose(g[:, 0], x[:, 1] / x[:, 2], rtol=1e-6, atol=1e-6):
        return (
            "your second column is all 1 and your first is v: you sliced x[:, 1:3] / x[:, 2:3], counting the columns "
            "from 1. Python counts from 0: u and v are columns 0 and 1, x[:, 0:2] / x[:, 2:3] (or x[:, :2])."
        )
    if np.allclose(g, (X @ P[:, :3].T)[:, :2] / (X @ P[:, :3].T)[:, 2:], rtol=1e-6):
        return "you ignored the fourth column of P (the translation): lift X to (X, Y, Z, 1) first."
    if np.all(x[:, 2] < 0) and np.allclose(g, x[:, :2] / np.abs(x[:, 2:]), rtol=1e-6, atol=1e-6):
        return (
            "you divided by |w|. This P is -3 times a camera, the same camera at another scale, so w is "
            "negative for points in front of it; (x / w, y / w) gives the same pixels for P and -3 P, "
            "(x / |w|, y / |w|) does not. Divide by w itself."
        )
    for factor, unit in ((1e3, "millimetres"), (1e-3, "kilometres")):
        x_other = np.hstack([factor * X, np.ones((len(X), 1))]) @ P.T
        with np.errstate(divide="ignore", invalid="ignore"):
            if np.allclose(g, x_other[:, :2] / x_other[:, 2:], rtol=1e-6, atol=1e-6):
                return (
                    f"you projected the world points in {unit} (X times {factor:g}); this P maps metres to pixels "
                    f"(its last column, the translation, is in metres), so lift X as it is: (X, Y, Z, 1)."
                )
    if np.allclose(g, -np.asarray(expected, dtype=float), rtol=1e-6, atol=1e-6):
        return (
            "every pixel has the wrong sign: (u, v) = (x / w, y / w) with x = P (X, Y, Z, 1)^T, no minus sign "
            "(the pinhole's image inversion is already in K: v grows downwards)."
        )
    return _pixel_slip(g, np.asarray(expected, dtype=float), P)


def _masked_by_w(P, X, got, expected) -> str | None:
    """The cause when the answer puts NaN exactly where w <= 0: "behind the camera" tested as w > 0."""
    try:
        g = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        return None
    if g.shape != np.shape(expected) or not np.isnan(g).any():
        return None
    w = np.hstack([X, np.ones((len(X), 1))]) @ np.asarray(P, dtype=float)[2]
    nan_rows = np.isnan(g).any(axis=1)
    if not np.array_equal(nan_rows, w <= 0):
        return None
    return (
        "you set the pixels of points with w <= 0 to NaN, as behind the camera. But this P is -3 times a "
        "camera (the same camera at another scale and sign), so w < 0 for points in front of it: w is the depth "
        "z_c only for P = K [R | t]. A point is in front when sign(det M) w > 0, M = P[:, :3] (section 4b, "
        "the depth of a point); or simply return x / w for every point."
    )


def _pixel_slip(got, expected, P=None) -> str:
    """The cause when right pixels were then rounded, shifted, swapped or flipped."""
    shift = got - expected
    if np.allclose(got, np.round(expected), atol=1e-9) and not np.allclose(
        got, expected, atol=1e-6
    ):
        return (
            "you rounded to whole pixels. A projection lands between pixel centres (sub-pixel positions are "
            "what calibration and matching measure), so return x / w as it is: no np.round, no .astype(int)."
        )
    if P is not None:
        M = np.asarray(P, dtype=float)[:, :3]
        x0 = M @ M[2]  # the principal point M m3 (section 4b)
        for sign, how in ((-1.0, "subtracted"), (1.0, "added")):
            if np.allclose(shift, sign * x0[:2] / x0[2], atol=1e-6):
                return (
                    f"you {how} the principal point (c_x, c_y). P = K [R | t] already contains it (K's last "
                    f"column), so x / w is the pixel itself, counted from the top-left pixel's centre: return "
                    f"x / w with nothing {how}."
                )
    same_shift = np.allclose(shift, shift[0], atol=1e-6)  # every pixel moved by the same (du, dv)
    if same_shift and np.allclose(np.abs(shift[0]), 0.5, atol=1e-6):
        return (
            "every pixel is off by half a pixel: P already puts pixel centres at integers (the principal "
            "point is in P), so return x / w as it is, with no +-0.5."
        )
    for axis, name, other in ((0, "u", "v"), (1, "v", "u")):
        if (
            same_shift
            and np.isclose(abs(shift[0, axis]), 0.5, atol=1e-6)
            and np.isclose(shift[0, 1 - axis], 0.0, atol=1e-6)
        ):
            return (
                f"every {name} is off by {shift[0, axis]:+.1f} px while {other} is right: a half-pixel shift on one "
                f"coordinate only, as from a pixel-edge convention (the image's left edge at 0) on {name}. P already "
                f"puts pixel centres at integers on both axes (the principal point is in P): return x / w as it is."
            )
    if same_shift and np.allclose(np.abs(shift[0]), 1.0, atol=1e-6):
        return (
            "every pixel is off by one: pixel indices start at 0 (the top-left pixel's centre is (0, 0), in numpy "
            "as in camlab and OpenCV), and P already puts them there; return x / w as it is, with no +-1."
        )
    if same_shift and np.abs(shift[0]).max() > 1.0:
        return (
            f"every pixel is shifted by the same ({shift[0, 0]:.4g}, {shift[0, 1]:.4g}) px: did you subtract an image "
            f"centre such as (320, 240)? Pixels count from the top-left pixel's centre, and P already puts them "
            f"there (the principal point is inside P): return x / w with nothing added or subtracted."
        )
    for factor in (1e3, 1e-3):
        if np.allclose(got, factor * expected, rtol=1e-6, atol=1e-9):
            return (
                f"every pixel is {factor:g} times the right one: a unit conversion slipped in (pixels in "
                f"thousands, or a factor of 1000 for millimetres). P maps metres to pixels: return x / w as it is."
            )
    if np.allclose(got, expected[:, ::-1], rtol=1e-6, atol=1e-6):
        return "u and v are swapped: column 0 is u = x / w (right), column 1 is v = y / w (down)."
    flipped = got[:, 1] + expected[:, 1]
    if np.allclose(got[:, 0], expected[:, 0], rtol=1e-6, atol=1e-6) and np.allclose(
        flipped, flipped[0], atol=1e-6
    ):
        return (
            "v is flipped (v measured upwards): in pixels v grows downwards and P already says so; "
            "return v = y / w without negating it or subtracting it from the height."
        )
    return "project with x = P (X, Y, Z, 1)^T, then (u, v) = (x / w, y / w)."


def _project_exception_hint(exc, args) -> str:
    """The cause of a broadcasting error: p4 added as a row to the (3, N) product, or w without keepdims."""
    message = str(exc)
    if not (isinstance(exc, ValueError) and "broadcast" in message):
        return ""
    n = len(np.asarray(args[1]))
    if f"(3,{n}) (3,)" in message:
        return (
            f"a broadcasting slip: you added p4 = P[:, 3], shape (3,), to a (3, {n}) array (M X^T, one column per "
            f"point). Broadcasting lines a (3,) vector up with the LAST axis, the {n} points, not the 3 rows. Make it "
            f"a column, P[:, 3:4] or P[:, 3, None], or lift X to (X, Y, Z, 1) and use one product, X_h @ P.T."
        )
    for k in (2, 3):
        if f"({n},{k}) ({n},)" in message:
            return (
                f"a broadcasting slip: you divided a ({n}, {k}) array by w of shape ({n},), which broadcasting "
                f"lines up with the last axis (the {k} columns), not with the {n} rows (points). Keep w 2-D: "
                f"x[:, 2:3], x[:, 2, None] or keepdims=True."
            )
    return ""


def project_points(P, X):
    """Pixels of (N, 3) world points: x = P (X, 1), then divide by the third coordinate.

    Parameters
    ----------
    P : (3, 4) array_like
        The camera matrix.
    X : (N, 3) array_like
        World points.

    Returns
    -------
    (N, 2) ndarray
        Their pixels (u, v).

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 6.2.
    """
    X = np.asarray(X, dtype=float)
    Xh = np.hstack([X, np.ones((len(X), 1))])  # (N, 4) homogeneous world points
    x = Xh @ np.asarray(P).T  # points are rows: (P Xh^T)^T = Xh P^T
    return x[:, :2] / x[:, 2:3]


register_exercise(
    Exercise(
        name="project_points",
        lesson="04",
        reference=cm.project_points,
        cases=_project_cases,
        compare=same_array(rtol=1e-8, atol=1e-6),
        diagnose=_project_diagnosis,
        wrong_variants=(
            (lambda P, X: (np.hstack([X, np.ones((len(X), 1))]) @ P.T)[:, :2], "without dividing"),
            (lambda P, X: (X @ P[:, :3].T)[:, :2] / (X @ P[:, :3].T)[:, 2:], "fourth column"),
            (lambda P, X: np.hstack([X, np.ones((len(X), 1))]) @ P.T, "homogeneous pixels"),
            (lambda P, X: cm.project_points(P, X).T, "pixels are columns"),
            (lambda P, X: cm.project_points(P, X) + 0.5, "half a pixel"),
            (lambda P, X: cm.project_points(P, X)[:, ::-1], "swapped"),
            (lambda P, X: cm.project_points(P, X) * [1.0, -1.0] + [0.0, 479.0], "v is flipped"),
            (lambda P, X: np.hstack([X, np.ones((len(X), 1))]) @ P, "X @ M.T"),
            (
                lambda P, X: (lambda x: x[:, :2] / np.abs(x[:, 2:]))(
                    np.hstack([X, np.ones((len(X), 1))]) @ P.T
                ),
                "|w|",
            ),
            (lambda P, X: -cm.project_points(P, X), "wrong sign"),
            (lambda P, X: cm.project_points(P, X) + 1.0, "off by one"),
            (lambda P, X: cm.project_points(P, X) / 1000.0, "0.001 times the right one"),
            (lambda P, X: project_points(P, 1000.0 * np.asarray(X)), "in millimetres"),
            (
                lambda P, X: (lambda x: np.where(x[:, 2:] > 0, x[:, :2] / x[:, 2:], np.nan))(
                    np.hstack([X, np.ones((len(X), 1))]) @ P.T
                ),
                "sign(det M) w > 0",
            ),
            (
                lambda P, X: (P[:, :3] @ np.asarray(X).T + P[:, 3]).T,
                "P[:, 3:4]",
            ),  # p4 added as a row
            (lambda P, X: np.round(cm.project_points(P, X)).astype(int), "rounded to whole pixels"),
            (
                lambda P, X: (
                    cm.project_points(P, X) - (lambda x0: x0[:2] / x0[2])(P[:, :3] @ P[2, :3])
                ),
                "subtracted the principal point",
            ),
            (lambda P, X: cm.project_points(P, X) - [320.0, 240.0], "shifted by the same"),
            (lambda P, X: tuple(cm.project_points(P, X).T), "two separate arrays"),  # return u, v
            (
                lambda P, X: (lambda x: x[:, 1:3] / x[:, 2:3])(
                    np.hstack([X, np.ones((len(X), 1))]) @ P.T
                ),
                "counting the columns",
            ),
            (
                lambda P, X: (np.hstack([X, np.ones((len(X), 1))]) @ (P / P[2, 3]).T)[:, :2],
                "rescaled P",
            ),
        ),
        exception_hint=lambda exc, args: _project_exception_hint(exc, args),
        teaching=project_points,
    )
)
