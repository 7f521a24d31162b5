"""Exercises for lesson 04, the projective camera P = K [R | t]."""

from __future__ import annotations

import numpy as np

from .. import camera as cm
from ..projective import hartley_normalization
from ._answers import same_array, same_up_to_scale, shape_problem
from ._core import Exercise, register_exercise


def _cameras():
    """Realistic cameras (fx about 800, 640x480) in varied poses, one with skew."""
    return [
        cm.Camera.look_at([4.0, -3.0, 2.0], [0.0, 0.0, 0.5]),
        cm.Camera.look_at(
            [-2.0, -5.0, 1.5], [0.3, 0.2, 0.8], K=cm.intrinsic_matrix(760, 820, 300, 250, 3.0)
        ),
        cm.Camera(
            cm.intrinsic_matrix(900, 900, 330, 230),
            cm.rotation_from_euler(0.1, -0.2, 0.3),
            [0.2, -0.1, 6.0],
        ),
    ]


def _world_points():
    rng = np.random.default_rng(4)
    return rng.uniform(-1.0, 1.0, (6, 3)) + [0.0, 0.0, 0.5]


# -- project_points -------------------------------------------------------------------


def _project_cases():
    X = _world_points()
    return [(c.P, X) for c in _cameras()] + [(-3.0 * _cameras()[0].P, X)]


def _project_diagnosis(args, got, expected) -> str:
    P, X = args
    behind = _masked_by_w(P, X, got, expected)
    if behind:
        return behind
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
    if np.allclose(shift, shift[0], atol=1e-6) and np.allclose(np.abs(shift[0]), 0.5, atol=1e-6):
        return (
            "every pixel is off by half a pixel: P already puts pixel centres at integers (the principal "
            "point is in P), so return x / w as it is, with no +-0.5."
        )
    if np.allclose(shift, shift[0], atol=1e-6) and np.allclose(np.abs(shift[0]), 1.0, atol=1e-6):
        return (
            "every pixel is off by one: pixel indices start at 0 (the top-left pixel's centre is (0, 0), in numpy "
            "as in camlab and OpenCV), and P already puts them there; return x / w as it is, with no +-1."
        )
    if np.allclose(shift, shift[0], atol=1e-6) and np.abs(shift[0]).max() > 1.0:
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
    """Pixels of (N, 3) world points: x = P (X, 1), then divide by the third coordinate."""
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


# -- camera_centre ----------------------------------------------------------------------


def _centre_cases():
    # P at other scales (|m3| != 1 in all but the first): a centre scaled by the wrong number fails early
    return [(s * c.P,) for s, c in zip((1.0, 2.5, 0.02), _cameras(), strict=True)] + [
        (-0.01 * _cameras()[1].P,)
    ]


def _flat_centre(got):
    """A (4, 1) column or (1, 4) row as the 4-vector it holds (H&Z writes C as a column; scipy's null_space
    returns one); anything else unchanged."""
    try:
        g = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        return got
    return g.ravel() if g.shape in ((4, 1), (1, 4)) else got


_same_centre = same_array(rtol=1e-8, atol=1e-10)  # the prompt fixes the scale: last entry 1


def _centre_compare(got, expected) -> bool:
    return _same_centre(_flat_centre(got), expected)


def _centre_diagnosis(args, got, expected) -> str:
    (P,) = args
    got = _flat_centre(got)
    g = np.asarray(got, dtype=float) if got is not None else None
    if g is not None and g.shape == (3,):
        if same_up_to_scale(g, np.linalg.svd(P)[0][:, -1], rtol=1e-6):
            return (
                "you returned a left singular vector (3 numbers, on the image side): the SVD of P.T, or U of "
                "np.linalg.svd(P). The centre is P's right null vector, 4 numbers: U, S, Vt = np.linalg.svd(P), "
                "C = Vt[-1], then divide it by C[3]."
            )
        return (
            "you returned a 3-vector; return the homogeneous centre (X, Y, Z, 1), "
            "the null vector of P (P C = 0)."
        )
    problem = shape_problem(got, expected)
    if problem:
        return problem
    residual = np.linalg.norm(P @ g) / (np.linalg.norm(P) * max(np.linalg.norm(g), 1e-300))
    if residual > 1e-8:
        slip = _centre_slip(P, g, np.asarray(expected, dtype=float))
        if slip:
            return slip
        return (
            f"P C is not 0 (relative |P C| = {residual:.3g}). The centre is the null space of P: "
            f"the last right singular vector of np.linalg.svd(P), or (-M^-1 p4, 1)."
        )
    return (
        f"P C = 0, but your last coordinate is {g[3]:.4g}: the null vector is defined only up to scale; "
        f"divide it by its last entry so that its last coordinate is 1 (C = (X, Y, Z, 1))."
    )


def _centre_slip(P, got, expected) -> str | None:
    """The cause when the 4-vector is a known wrong one: V's column for its row, U's, a sign, p4."""
    U, _, Vt = np.linalg.svd(P)
    if same_up_to_scale(got, Vt[:, -1], rtol=1e-6):
        return (
            "you took the last column of Vt. np.linalg.svd returns Vt, V transposed: the right singular "
            "vectors are its rows, so the null vector is the last row, Vt[-1], not Vt[:, -1]."
        )
    reduced = np.linalg.svd(P, full_matrices=False)[2][-1]
    if same_up_to_scale(got, reduced, rtol=1e-6) or same_up_to_scale(
        got, reduced / reduced[3], rtol=1e-6
    ):
        return (
            "you called np.linalg.svd(P, full_matrices=False): for a 3 x 4 P it returns only three right singular "
            "vectors, those of the three non-zero singular values, so its last row is not the null vector. Use the "
            "full SVD, np.linalg.svd(P), whose Vt is 4 x 4: the centre is Vt[-1]."
        )
    if same_up_to_scale(got[:3], U[:, -1], rtol=1e-6):
        return (
            "you took the last column of U, a left singular vector (3 numbers, on the image side). "
            "The centre is a right singular vector, a 4-vector: the last row of Vt, Vt[-1]."
        )
    if np.allclose(got[:3], -expected[:3], rtol=1e-6) and np.isclose(got[3], 1.0):
        return "the sign is flipped: P C = M C + p4 = 0 gives C = -M^-1 p4 (with the minus)."
    M, p4 = P[:, :3], P[:, 3]
    if np.allclose(got[:3], -M.T @ p4, rtol=1e-6):
        return (
            "you used M^T for M^-1 (C = -M^T p4, as in C = -R^T t). M = K R is not a rotation, so its inverse "
            "is not its transpose: C = -M^-1 p4, np.linalg.solve(M, -p4), or the last row of Vt."
        )
    if np.isclose(got[3], 1.0) and same_up_to_scale(got[:3], expected[:3], rtol=1e-6):
        if same_up_to_scale(np.abs(got[:3]), np.abs(Vt[-1, :3]), rtol=1e-6) and np.allclose(
            np.abs(got[:3]), np.abs(Vt[-1, :3]), rtol=1e-6
        ):
            return (
                "your (X, Y, Z) are the first three entries of the unit null vector: you set the last entry to 1 "
                "instead of dividing the whole null vector by it. C = v / v[3]."
            )
        ratio = float(np.dot(got[:3], expected[:3]) / np.dot(expected[:3], expected[:3]))
        return (
            f"your (X, Y, Z) points the right way but is {ratio:.4g} times the centre: it was divided (or "
            f"multiplied) by a number other than the null vector's last entry, such as P's scale or |m3|. "
            f"The centre solves M C + p4 = 0 whatever P's scale: C = -M^-1 p4 exactly, or v / v[3] for the "
            f"null vector v."
        )
    if same_up_to_scale(got[:3], P[:, 3], rtol=1e-6):
        return (
            "p4 (P's last column) is the image of the world origin, not the centre. The centre solves "
            "M C + p4 = 0: C = -M^-1 p4, or the last row of Vt."
        )
    return None


def _centre_exception_hint(exc, args) -> str:
    """The cause when indexing entry 3 of a 3-vector fails: the SVD of P.T, or -M^-1 p4 without its 1."""
    if isinstance(exc, IndexError) and "index 4" in str(exc) and "size 4" in str(exc):
        return (
            "you indexed entry 4 of the null vector, which has 4 entries, indices 0 .. 3 (Python counts from 0): "
            "its last entry is v[3], or v[-1], so C = v / v[3]."
        )
    if isinstance(exc, IndexError) and "size 3" in str(exc):
        return (
            "you indexed entry 3 (the fourth) of a vector with 3 entries. If it came from np.linalg.svd(P.T): "
            "that SVD's Vt is 3 x 3 and holds the image-side (left) singular vectors of P; the centre is P's "
            "right null vector, 4 numbers: U, S, Vt = np.linalg.svd(P), v = Vt[-1], C = v / v[3]. If it came "
            "from C = -M^-1 p4, it has no fourth entry to divide by: return np.append(C, 1.0)."
        )
    return ""


def camera_centre(P):
    """The homogeneous centre C with P C = 0: P's right null vector, scaled to w = 1."""
    _, _, Vt = np.linalg.svd(P)
    C = Vt[
        -1
    ]  # the null vector: the full SVD's 4th right singular vector (its singular value, 0, is not in S)
    return C / C[3]


register_exercise(
    Exercise(
        name="camera_centre",
        lesson="04",
        reference=cm.camera_centre,
        cases=_centre_cases,
        compare=_centre_compare,  # a flat 4-vector, or a (4, 1) column, with last entry 1
        diagnose=_centre_diagnosis,
        wrong_variants=(
            (lambda P: -np.linalg.solve(P[:, :3], P[:, 3]), "returned a 3-vector"),
            (
                lambda P: np.append(-P[:, 3], 1.0),
                "image of the world origin",
            ),  # confuses t with the centre
            (lambda P: (lambda v: v / v[3])(np.linalg.svd(P)[2][:, -1]), "last row"),
            (lambda P: np.append(np.linalg.svd(P)[0][:, -1], 1.0), "left singular vector"),
            (lambda P: np.append(np.linalg.solve(P[:, :3], P[:, 3]), 1.0), "sign is flipped"),
            (
                lambda P: np.linalg.svd(P)[2][-1],
                "last coordinate is 1",
            ),  # the unit null vector, not scaled
            (lambda P: np.append(-P[:, :3].T @ P[:, 3], 1.0), "not a rotation"),
            (lambda P: np.append(np.linalg.svd(P)[2][-1][:3], 1.0), "instead of dividing"),
            (
                lambda P: np.append(
                    -np.linalg.solve(P[:, :3], P[:, 3]) / np.linalg.norm(P[2, :3]), 1.0
                ),
                "times the centre",
            ),
            (lambda P: np.linalg.svd(np.asarray(P).T)[2][-1], "left singular vector"),
            (
                lambda P: (lambda v: v / v[3])(np.linalg.svd(np.asarray(P).T)[2][-1]),
                "np.linalg.svd(P.T)",
            ),
            (
                lambda P: (lambda v: v / v[3])(np.linalg.svd(P, full_matrices=False)[2][-1]),
                "full_matrices=False",
            ),
            (lambda P: (lambda v: v / v[4])(np.linalg.svd(P)[2][-1]), "indices 0 .. 3"),
            (
                lambda P: np.linalg.svd(P)[2][-1][:, None],
                "last coordinate is 1",
            ),  # a column, unscaled
        ),
        exception_hint=lambda exc, args: _centre_exception_hint(exc, args),
        teaching=camera_centre,
    )
)


# -- rq_decomposition ----------------------------------------------------------------------
# (The whole decomposition returns four arrays of different shapes, which the checker cannot
# print; the exercise is its heart, M = K R, and the lesson derives t and C from it.)


def _rq_cases():
    cams = _cameras()
    return [
        (cams[0].P[:, :3],),
        (2.5 * cams[1].P[:, :3],),
        (0.003 * cams[2].P[:, :3],),
        (
            cm.intrinsic_matrix(700, 650, 300, 200, 5.0)
            @ cm.rotation_from_axis_angle([0.3, -2.0, 0.5]),
        ),
        (-2.5 * cams[0].P[:, :3],),
    ]  # det M < 0 (lesson 04, section 4): K R = M still, so det R = -1


def _rq_compare(got, expected) -> bool:
    try:
        K, R = (np.asarray(g, dtype=float) for g in got)
    except (TypeError, ValueError):
        return False
    return K.shape == R.shape == (3, 3) and bool(
        np.allclose(K, expected[0], rtol=1e-7, atol=1e-7)
        and np.allclose(R, expected[1], rtol=1e-7, atol=1e-7)
    )


def _rq_diagnosis(args, got, expected) -> str:
    (M,) = args
    try:
        K, R = (np.asarray(g, dtype=float) for g in got)
        assert K.shape == R.shape == (3, 3)
    except (TypeError, ValueError, AssertionError):
        return "return a pair (K, R) of (3, 3) arrays"
    scale = 1e-6 * np.abs(M).max()
    if np.linalg.det(M) < 0 and np.allclose(K @ R, -M, rtol=1e-6, atol=scale):
        return (
            "K R = -M: you made det R = +1 by a sign change, either negating R after the sign fix or factoring "
            "-M instead of M (step 1 of section 4); both give this same pair. Flipping the sign belongs to "
            "decomposing a camera, where -P is the same camera; here M must come back as K R exactly. For "
            "det M < 0 a K with a positive diagonal forces det R = -1, a reflection: the sign that tells the "
            "camera decomposition to flip P first."
        )
    reproduces = np.allclose(K @ R, M, rtol=1e-6, atol=1e-6 * np.abs(M).max())
    orthogonal = np.allclose(R @ R.T, np.eye(3), atol=1e-6)
    if reproduces and not orthogonal:
        gram = np.diag(R @ R.T)
        if np.allclose(gram, gram[0], rtol=1e-6):
            return (
                f"K R = M, but R is not orthogonal: R R^T = {gram[0]:.4g} I, so R carries a scale (did you divide "
                f"K by K[2, 2] and multiply R by it?). R must be a rotation or reflection, R R^T = I; the scale of M "
                f"stays in K (K[2, 2] carries it)."
            )
        return (
            "K R = M, but R is not orthogonal (R R^T != I): R must be a rotation or a reflection."
        )
    if np.isclose(K[2, 2], 1.0) and not reproduces and not np.isclose(abs(M[2] @ M[2]), 1.0):
        return (
            "you divided K by K[2, 2], so K R = M / K[2, 2] and no longer M; and a negative K[2, 2] "
            "does not fix the signs. Keep K unnormalised (K[2, 2] carries M's scale) and fix the signs "
            "with D = diag(sign(diag(K))): K D and D R."
        )
    if not reproduces:
        if np.allclose(R @ K, M, rtol=1e-6, atol=1e-6 * np.abs(M).max()):
            if np.abs(np.tril(K, -1)).max() > 1e-6 * np.abs(K).max() and np.allclose(
                K @ K.T, np.eye(3), atol=1e-6
            ):
                return "you returned (R, K): the order is swapped. Return K first, then R: `return K, R`."
            return "you computed M = Q K (a QR decomposition); the camera needs M = K R with K on the left (RQ)."
        misplaced = _sign_fix_misplaced(K, R, M)
        if misplaced:
            return misplaced
        if np.allclose(K @ R.T, M, rtol=1e-6, atol=1e-6 * np.abs(M).max()):
            return "R is transposed: M = K R."
        if np.allclose(K.T @ R, M, rtol=1e-6, atol=1e-6 * np.abs(M).max()):
            return "K is transposed (lower triangular): M = K R with K upper triangular; return K itself, not K.T."
        if _signs_fixed_in_k_only(K, R, M):
            return (
                "you fixed the signs of K (K D) but not of R: K R = (K D)(D R), so apply the same "
                "D = diag(sign(diag(K))) to R's rows too (D R), or K R no longer equals M."
            )
        return "K R does not reproduce M; an RQ decomposition must satisfy M = K R exactly."
    if np.abs(np.tril(K, -1)).max() > 1e-9 * np.abs(K).max():
        return "K must be upper triangular."
    if np.any(np.diag(K) < 0) and np.linalg.det(M) < 0 and np.linalg.det(R) > 0:
        return (
            "det M < 0 here, and your R is a rotation (det R = +1), so K must carry the minus sign: K R = M with "
            "a positive-diagonal K forces det K > 0 and so det R = det M / det K < 0, a reflection. Do not "
            "negate K and R (or K's last column and R's last row) to make det R = +1; fix only the signs of "
            "diag(K) with D = diag(sign(diag(K))), K D and D R, and let det R = -1. Making det R = +1 by "
            "flipping P belongs to decomposing a camera (section 4, step 1), not to the RQ decomposition."
        )
    if np.any(np.diag(K) < 0):
        return (
            "K has a negative diagonal entry: fix the signs. RQ is unique only up to D = diag(+-1); "
            "use K D and D R with D = diag(sign(diag(K)))."
        )
    return "K R = M with K positive upper triangular, but the factors differ; is R orthogonal?"


def _sign_flips():
    """The seven D = diag(+-1) other than I."""
    return [
        np.diag(signs) for signs in np.array(np.meshgrid(*[[1.0, -1.0]] * 3)).reshape(3, -1).T[1:]
    ]


def _sign_fix_misplaced(K, R, M) -> str | None:
    """The cause when D was applied on the wrong side: R @ D (R's columns) or D @ K (K's rows)."""
    scale = 1e-6 * np.abs(M).max()
    for D in _sign_flips():
        if np.allclose(K @ D @ R @ D, M, rtol=1e-6, atol=scale):
            return (
                "you applied D to R's columns (R @ D). K R = (K D)(D R): D flips K's columns (K @ D) "
                "and R's rows (D @ R), so that D D = I cancels between them."
            )
        if np.allclose(D @ K @ D @ R, M, rtol=1e-6, atol=scale):
            return (
                "you applied D to K's rows (D @ K). K R = (K D)(D R): D flips K's columns (K @ D) "
                "and R's rows (D @ R), so that D D = I cancels between them."
            )
    return None


def _signs_fixed_in_k_only(K, R, M) -> bool:
    """True if K D R = M for some D = diag(+-1) other than I (K's columns flipped, R's rows not)."""
    scale = 1e-6 * np.abs(M).max()
    for D in _sign_flips():
        if np.allclose(K @ D @ R, M, rtol=1e-6, atol=scale):
            return True
    return False


def _rq_signs_of_k_only(M):
    from scipy.linalg import rq

    K, R = rq(M)
    return K @ np.diag(np.sign(np.diag(K))), R


def _rq_no_sign_fix(M):
    from scipy.linalg import rq

    return rq(M)


def _rq_normalised_no_sign_fix(M):
    from scipy.linalg import rq

    K, R = rq(M)
    return K / K[2, 2], R


def _rq_sign_fix_on_columns_of_r(M):
    from scipy.linalg import rq

    K, R = rq(M)
    D = np.diag(np.sign(np.diag(K)))
    return K @ D, R @ D


def _rq_sign_fix_on_rows_of_k(M):
    from scipy.linalg import rq

    K, R = rq(M)
    D = np.diag(np.sign(np.diag(K)))
    return D @ K, D @ R


def _rq_forced_rotation(M):
    """Signs fixed, then K and R negated to make det R = +1 (K R = M still, but diag K < 0 when det M < 0)."""
    K, R = cm.rq_decomposition(M)
    return (-K, -R) if np.linalg.det(R) < 0 else (K, R)


def _rq_qr(M):
    Q, U = np.linalg.qr(M)
    return U, Q


def rq_decomposition(M):
    """M = K R with K upper triangular (positive diagonal) and R orthogonal, from numpy's QR."""
    E = np.eye(3)[::-1]  # the exchange matrix reverses row order; E = E^T = E^-1
    Q, U = np.linalg.qr((E @ M).T)  # (E M)^T = Q U, so M = (E U^T E)(E Q^T)
    K, R = E @ U.T @ E, E @ Q.T  # E U^T E is upper triangular
    D = np.diag(np.sign(np.diag(K)))  # K R = (K D)(D R): flip signs so diag(K) > 0
    return K @ D, D @ R


register_exercise(
    Exercise(
        name="rq_decomposition",
        lesson="04",
        reference=cm.rq_decomposition,
        cases=_rq_cases,
        compare=_rq_compare,
        diagnose=_rq_diagnosis,
        wrong_variants=(
            (_rq_no_sign_fix, "fix the signs"),
            (_rq_normalised_no_sign_fix, "divided K by K[2, 2]"),
            (_rq_qr, "QR decomposition"),
            (_rq_signs_of_k_only, "apply the same"),
            (lambda M: (lambda K, R: (K, R.T))(*cm.rq_decomposition(M)), "transposed"),
            (lambda M: (lambda K, R: (K.T, R))(*cm.rq_decomposition(M)), "K is transposed"),
            (lambda M: cm.rq_decomposition(M)[::-1], "order is swapped"),
            (_rq_sign_fix_on_columns_of_r, "R's columns"),
            (_rq_sign_fix_on_rows_of_k, "K's rows"),
            (
                lambda M: cm.rq_decomposition(np.sign(np.linalg.det(M)) * np.asarray(M)),
                "factoring -M instead of M",
            ),
            (
                lambda M: (lambda K, R: (K, np.sign(np.linalg.det(R)) * R))(
                    *cm.rq_decomposition(M)
                ),
                "negating R",
            ),
            (_rq_forced_rotation, "R is a rotation (det R = +1)"),
            (
                lambda M: (lambda K, R: (K / K[2, 2], R * K[2, 2]))(*cm.rq_decomposition(M)),
                "R is not orthogonal",
            ),
        ),
        teaching=rq_decomposition,
    )
)


# -- estimate_projection_matrix (the normalised DLT) -------------------------------------------
# The test inputs are exact pixels, where any correct DLT (normalised or not, two or three rows of
# the cross product, refined or not) gives the true camera up to scale. What normalisation buys
# shows only with noise, and there no single answer is "the" right one. So once those pass, the
# follow-up (_dlt_follow_up) runs the student's function on a noisy survey:
#   1. accuracy against the TRUE camera, within a tolerance derived from the noise (first-order
#      covariance propagation, H&Z 5.2): catches answers that exact data cannot tell apart;
#   2. the same survey in other units and origins, one change at a time (world origin at the site's
#      corner; world in millimetres and in kilometres; pixel origin at the image centre; pixels as fractions of the width). A normalised DLT is invariant to such
#      changes (the normalised coordinates are the same numbers, H&Z 4.4.4), a refined one too;
#      an unnormalised or half-normalised one is not, and which half changes names the cause.


def _survey_camera():
    K = cm.intrinsic_matrix(3200.0, 3200.0, 1999.5, 1499.5)
    return cm.Camera.look_at(
        [74.0, 18.0, 12.0], [50.0, 50.0, 1.0], K=K, image_size=(4000, 3000)
    )  # 40 m away


def _survey_points(n, rng):
    return rng.uniform(
        [48.0, 48.0, 0.0], [52.0, 52.0, 2.0], (n, 3)
    )  # a 4 m site, 70 m from the origin


SURVEY_NOISE_PX = 1.0  # pixel noise per coordinate
SURVEY_TOLERANCE = 5.0  # times the predicted RMS error
_SURVEY_TEST_POINTS = _survey_points(50, np.random.default_rng(12))  # where cameras are compared
# Other units and origins for the same survey, one change at a time, as 4 x 4 and 3 x 3 maps of homogeneous
# points: the world origin moved to the site's corner (48, 48, 0) m, the world in millimetres or kilometres, the pixel origin
# moved to the image centre, the pixels as fractions of the image width. A DLT that centres a side is unmoved by its shift, one
# that scales a side is unmoved by its change of units; so which change moves the camera names what is missing.
_WORLD_SHIFT = np.array([[1.0, 0, 0, -48.0], [0, 1.0, 0, -48.0], [0, 0, 1.0, 0], [0, 0, 0, 1.0]])
_WORLD_IN_MM = np.diag(
    [1e3, 1e3, 1e3, 1.0]
)  # one scale-up and one scale-down: either alone can move a
_WORLD_IN_KM = np.diag([1e-3, 1e-3, 1e-3, 1.0])  # half-normalised DLT too little to see
_PIXEL_SHIFT = np.array([[1.0, 0, -1999.5], [0, 1.0, -1499.5], [0, 0, 1.0]])
_PIXELS_HALF = np.diag(
    [1 / 4000, 1 / 4000, 1.0]
)  # fractions of the image width (a 0.5 scale moves too little)
_INVARIANCE_PX = 1e-3  # a normalised DLT gives 1e-11 px, a refined one 1e-6; half-normalised ones 0.02 px and more
# (LM on P's raw entries moves by up to 0.06 px between frames: it passes as a refinement, see _refinement)


def _dlt_cases():
    rng = np.random.default_rng(11)
    cases = []
    for cam, n in zip(_cameras(), (6, 10, 14), strict=True):  # exact pixels, six or more points
        X = rng.uniform(-1.0, 1.0, (n, 3)) + [0.0, 0.0, 0.5]
        cases.append((X, cm.project_points(cam.P, X)))
    X = _survey_points(12, rng)  # exact pixels far from the world origin
    cases.append((X, cm.project_points(_survey_camera().P, X)))
    return cases


def _noisy_survey():
    """20 survey points and their pixels with 1 px noise (seeded)."""
    rng = np.random.default_rng(3)
    X = _survey_points(20, rng)
    return X, cm.project_points(_survey_camera().P, X) + rng.normal(0.0, SURVEY_NOISE_PX, (20, 2))


def _pixels_of(P, X):
    x = np.column_stack([X, np.ones(len(X))]) @ np.asarray(P, dtype=float).T
    with np.errstate(divide="ignore", invalid="ignore"):
        return x[:, :2] / x[:, 2:3]


def _pixel_gap(got, expected, X) -> float:
    """The largest distance (px) between the pixels of X under the two matrices."""
    return float(np.nanmax(np.linalg.norm(_pixels_of(got, X) - _pixels_of(expected, X), axis=1)))


def _rms_gap(got, expected, X) -> float:
    """The RMS distance (px) between the pixels of X under the two matrices."""
    return float(
        np.sqrt(np.mean(np.sum((_pixels_of(got, X) - _pixels_of(expected, X)) ** 2, axis=1)))
    )


def predicted_rms_error(P, X, sigma, X_test) -> float:
    r"""The RMS pixel error at ``X_test`` expected of a least-squares camera fitted to ``X`` with noise ``sigma``.

    First-order covariance propagation (H&Z 5.2): with J the Jacobian of the fitted pixels with
    respect to P's 12 entries (P normalised to unit norm), the estimate's covariance is
    :math:`\Sigma_p = \sigma^2 (J^\top J)^+` (the pseudo-inverse drops the scale direction), and a test
    point's pixels have covariance :math:`J_t \Sigma_p J_t^\top`. Returns the square root of the mean trace.
    """
    p0 = np.asarray(P, dtype=float).ravel() / np.linalg.norm(P)

    def jacobian(points):
        J, h = np.zeros((2 * len(points), 12)), 1e-7
        for k in range(12):
            d = np.zeros(12)
            d[k] = h
            J[:, k] = (
                _pixels_of((p0 + d).reshape(3, 4), points)
                - _pixels_of((p0 - d).reshape(3, 4), points)
            ).ravel() / (2 * h)
        return J

    J, J_test = jacobian(np.asarray(X, dtype=float)), jacobian(np.asarray(X_test, dtype=float))
    cov = sigma**2 * np.linalg.pinv(J.T @ J, rcond=1e-10)
    return float(np.sqrt(np.trace(J_test @ cov @ J_test.T) / len(X_test)))


def _as_camera_matrix(got):
    """``got`` as a finite (3, 4) float array, or None."""
    try:
        g = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        return None
    return g if g.shape == (3, 4) and np.isfinite(g).all() and np.any(g) else None


def _dlt_follow_up(run) -> str | None:
    """Accuracy against the true camera on a noisy survey, then invariance to units and origins."""
    X, uv = _noisy_survey()
    truth = _survey_camera().P
    where = "on a noisy survey (20 points, 1 px noise, a 4000 x 3000 photo of a site 70 m from the world origin)"
    P = _as_camera_matrix(run(X, uv))
    if P is None:
        return f"{where} your function did not return a finite, non-zero (3, 4) array."
    allowed = SURVEY_TOLERANCE * predicted_rms_error(truth, X, SURVEY_NOISE_PX, _SURVEY_TEST_POINTS)
    error = _rms_gap(P, truth, _SURVEY_TEST_POINTS)
    accurate = error <= allowed
    moved, answers = {}, [P]
    for key, S in (
        ("world shift", _WORLD_SHIFT),
        ("world units", _WORLD_IN_MM),
        ("world units", _WORLD_IN_KM),
    ):
        P_other = _as_camera_matrix(run(X @ S[:3, :3].T + S[:3, 3], uv))
        if P_other is None:
            return f"{where}, given the same points in other units, your function did not return a finite (3, 4) array."
        answers.append(P_other @ S)  # back in metres
        moved[key] = (
            moved.get(key, False)
            or _pixel_gap(answers[-1], P, _SURVEY_TEST_POINTS) > _INVARIANCE_PX
        )
    for key, S in (("pixel shift", _PIXEL_SHIFT), ("pixel units", _PIXELS_HALF)):
        P_other = _as_camera_matrix(run(X, uv @ S[:2, :2].T + S[:2, 2]))
        if P_other is None:
            return f"{where}, given the same pixels in other units, your function did not return a finite (3, 4) array."
        answers.append(np.linalg.inv(S) @ P_other)  # back in pixels
        moved[key] = _pixel_gap(answers[-1], P, _SURVEY_TEST_POINTS) > _INVARIANCE_PX
    refinement = _refinement(answers, X, uv)
    if (
        refinement == "converged"
    ):  # the maximum-likelihood camera, in every frame: it depends on no units or origin
        moved = dict.fromkeys(moved, False)
    if accurate and not any(moved.values()):
        return None
    findings = []
    if not accurate:
        findings.append(
            f"your P images the site {error:.3g} px (RMS) from the true camera: 1 px of noise moves a "
            f"least-squares camera by about {allowed / SURVEY_TOLERANCE:.2g} px (first-order error "
            f"propagation, H&Z 5.2), and the check allows {SURVEY_TOLERANCE:g} times that, {allowed:.2g} px"
        )
    changes = {
        "world shift": "with the world origin moved to the site's corner",
        "world units": "with the world points in millimetres or kilometres",
        "pixel shift": "with the pixel origin moved to the image centre",
        "pixel units": "with the pixels as fractions of the image width",
    }
    moved_by = [changes[k] for k in changes if moved[k]]
    if moved_by:
        findings.append(
            "given the same survey "
            + " or ".join(moved_by)
            + ", your function finds a different camera"
        )
    invariance = (
        " A normalised DLT finds the same camera in any units and origins: the normalised coordinates are "
        "the same numbers."
        if moved_by
        else ""
    )
    cause = (
        _REFINED_BUT_MOVED if refinement == "partial" and moved_by else _dlt_cause(moved, X, uv, P)
    )
    return f"{where}: " + "; ".join(findings) + "." + invariance + f"\n  likely cause: {cause}."


_REFINED_BUT_MOVED = (
    "your P fits the measured pixels better than a linear DLT, so you refined it; but in other units the "
    "refinement stops short of that fit, or never leaves its start: Levenberg-Marquardt on P's raw entries "
    "(metres against pixels, entries from 1e-3 to 1e3) is badly conditioned, like the unnormalised DLT. Refine in the normalised coordinates (T u and "
    "U X, starting from P_hat), then undo: P = inv(T) @ P_hat_refined @ U (H&Z's Gold Standard, Algorithm 7.1); "
    "the reprojection error in pixels is then minimised exactly, in any units"
)


def _residual_rms(P, X, uv) -> float:
    return float(np.sqrt(np.mean(np.sum((_pixels_of(P, X) - uv) ** 2, axis=1))))


def _refinement(answers, X, uv) -> str | None:
    """'converged' if every answer (one per units and origins, mapped back) is a refined camera, 'partial' if the
    first is and another is not, else None.

    The maximum-likelihood camera minimises the reprojection error in pixels, which no change of world units
    or origin, and no similarity of the pixels, alters. A linear DLT leaves an RMS residual a little above its
    floor (0.2 mpx on the survey); "refined" means less than half of that excess. LM on P's raw entries reaches
    it in every frame, though its path moves the camera by up to 0.06 px between frames (0.43 of the excess at
    worst); every half-normalised DLT leaves 0.76 of it or more in some frame (1.06 at least in its worst),
    so it is not mistaken for a refinement.
    """
    floor = _residual_rms(cm.estimate_projection_matrix(X, uv, refine=True), X, uv)
    linear = _residual_rms(cm.estimate_projection_matrix(X, uv), X, uv) - floor
    refined = [_residual_rms(A, X, uv) - floor <= 0.5 * linear for A in answers]
    if all(refined):
        return "converged"
    return "partial" if refined[0] else None


def _dlt_cause(moved, X, uv, P) -> str:
    """Name what is missing from the normalisation, side by side: the centroid shift, the scale, or both."""
    if same_up_to_scale(P, _dlt_p34(X, uv), rtol=1e-4):
        return (
            "you fixed p34 = 1 and solved the rest by least squares on raw metres and pixels (the classic DLT). "
            "That is unmoved by the pixels' units and origin and by the world's units, but p34 = 1 ties the "
            "answer to the world origin (p34 is the depth of the origin, and the fit fails if the origin lies "
            "near the camera's principal plane). Normalise both sides (centroid 0, mean distance sqrt(3) and "
            "sqrt(2)), take the last row of Vt as P_hat, then P = inv(T) @ P_hat @ U"
        )
    if all(moved.values()):
        return (
            "no normalisation: A's columns range from 1 to u X ~ 1e5, and which equations dominate depends "
            "on the units. Normalise both sides: T for the pixels (centroid 0, mean distance sqrt(2)), U for "
            "the world points (centroid 0, mean distance sqrt(3)); solve for P_hat; then P = inv(T) @ P_hat @ U"
        )
    missing = []
    for side, shift, units, norm, dist in (
        ("world points", "world shift", "world units", "U", "sqrt(3)"),
        ("pixels", "pixel shift", "pixel units", "T", "sqrt(2)"),
    ):
        if moved[shift] and moved[units]:
            missing.append(
                f"the {side} are not normalised at all (neither centred nor scaled): normalise them "
                f"with {norm} (centroid 0, mean distance {dist})"
            )
        elif moved[shift]:
            missing.append(
                f"the {side} are scaled but not centred: subtract their centroid before scaling "
                f"(moving the origin must not change the normalised {side})"
            )
        elif moved[units]:
            missing.append(
                f"the {side} are centred but not scaled, so A still depends on their units: divide by "
                f"the mean distance to the centroid and multiply by {dist}"
            )
    if not missing:
        return (
            "the estimate is not a least-squares fit of the DLT equations: two rows of u x P X = 0 per "
            "point from normalised coordinates, the last row of Vt, then P = inv(T) @ P_hat @ U"
        )
    return "; ".join(missing) + "; and undo both: P = inv(T) @ P_hat @ U"


def _dlt_p34(X, uv):
    """The classic DLT (Abdel-Aziz and Karara): p34 = 1, the other 11 entries by least squares, no normalisation."""
    A = _dlt_rows(np.asarray(X, dtype=float), np.asarray(uv, dtype=float))
    p = np.linalg.lstsq(A[:, :11], -A[:, 11], rcond=None)[0]
    return np.append(p, 1.0).reshape(3, 4)


def _dlt_partial(X, uv, world=(True, True), pixels=(True, True)):
    """A DLT whose normalisers only centre, only scale, or both, per side: (centre, scale)."""
    X, uv = np.asarray(X, dtype=float), np.asarray(uv, dtype=float)

    def normaliser(p, centre, scale):
        c = p.mean(axis=0) if centre else np.zeros(p.shape[1])
        s = np.sqrt(p.shape[1]) / np.mean(np.linalg.norm(p - c, axis=1)) if scale else 1.0
        N = s * np.eye(p.shape[1] + 1)
        N[:-1, -1], N[-1, -1] = -s * c, 1.0
        return N

    U, T = normaliser(X, *world), normaliser(uv, *pixels)
    P_hat = np.linalg.svd(_dlt_rows(_in_frame(U, X), _in_frame(T, uv)))[2][-1].reshape(3, 4)
    return np.linalg.inv(T) @ P_hat @ U


def _normalisers(X, uv):
    """Hartley's U (world, 4 x 4) and T (pixels, 3 x 3)."""
    return hartley_normalization(X), hartley_normalization(uv)


def _rms_normalisers(X, uv):
    """U and T with H&Z's RMS distances (sqrt(3), sqrt(2)) instead of mean distances."""

    def normaliser(p):
        c = p.mean(axis=0)
        s = np.sqrt(p.shape[1] / np.mean(np.sum((p - c) ** 2, axis=1)))
        return np.block(
            [
                [s * np.eye(p.shape[1]), -s * c[:, None]],
                [np.zeros((1, p.shape[1])), np.ones((1, 1))],
            ]
        )

    return normaliser(X), normaliser(uv)


def _in_frame(T, points):
    return (np.column_stack([points, np.ones(len(points))]) @ T.T)[:, :-1]


def _dlt_rows(X, uv, sign=-1.0):
    """The 2N x 12 DLT matrix (two rows of u x P X = 0 per point); sign=+1 is the sign slip in -u, -v."""
    Xh = np.column_stack([X, np.ones(len(X))])
    zero = np.zeros_like(Xh)
    return np.vstack(
        [np.hstack([Xh, zero, sign * uv[:, :1] * Xh]), np.hstack([zero, Xh, sign * uv[:, 1:] * Xh])]
    )


def _dlt_unnormalised(X, uv):
    """The plain DLT in metres and pixels (a plausible student answer)."""
    return np.linalg.svd(_dlt_rows(X, uv))[2][-1].reshape(3, 4)


def _dlt_half(
    X,
    uv,
    world=True,
    pixels=True,
    undo="both",
    sign=-1.0,
    column=False,
    interleave=False,
    order="C",
):
    """Normalised DLT variants, right and wrong: which sides are normalised and undone, the sign in A, Vt's row or
    column, A's rows stacked (u rows, then v rows) or interleaved per point, the null vector read row by row or not."""
    X, uv = np.asarray(X, dtype=float), np.asarray(uv, dtype=float)
    U, T = _normalisers(X, uv)
    U, T = (U if world else np.eye(4)), (T if pixels else np.eye(3))
    A = _dlt_rows(_in_frame(U, X), _in_frame(T, uv), sign)
    if interleave:
        A = (
            A.reshape(2, -1, 12).transpose(1, 0, 2).reshape(-1, 12)
        )  # u row, v row of point 0, then point 1, ...
    Vt = np.linalg.svd(A)[2]
    P_hat = (Vt[:, -1] if column else Vt[-1]).reshape((3, 4), order=order)
    return {"both": np.linalg.inv(T) @ P_hat @ U, "T": np.linalg.inv(T) @ P_hat, "U": P_hat @ U}[
        undo
    ]


def _dlt_not_undone(X, uv):
    U, T = _normalisers(X, uv)
    return T @ cm.estimate_projection_matrix(X, uv) @ np.linalg.inv(U)  # P_hat itself


def _dlt_undone_wrong_order(X, uv):
    U, T = _normalisers(X, uv)
    return T @ _dlt_not_undone(X, uv) @ np.linalg.inv(U)  # T P_hat U^-1


def _dlt_diagnosis(args, got, expected) -> str:
    X, uv = args
    g = np.asarray(got, dtype=float) if got is not None else None
    if g is not None and g.shape == (4, 3):
        return (
            "your P is (4, 3): transposed. P maps (X, Y, Z, 1) to (u, v, w), so it is (3, 4); "
            "A's columns list P row by row, so read the null vector back with p.reshape(3, 4)."
        )
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return P as a (3, 4) array: p.reshape(3, 4)."
    frames = (
        _normalisers(X, uv),
        _rms_normalisers(X, uv),
        (np.eye(4), np.eye(3)),
    )  # mean, RMS or none
    for (
        U,
        T,
    ) in (
        frames
    ):  # the null vector read column by column, before or without undoing the normalisation
        P_hat_got = T @ g @ np.linalg.inv(U)
        if same_up_to_scale(
            P_hat_got.ravel(order="F").reshape(3, 4), T @ expected @ np.linalg.inv(U), rtol=1e-5
        ):
            return (
                "your 12 numbers are P's entries in the wrong order (column by column, reshape(..., order='F') "
                "or reshape(4, 3).T): A's columns list P row by row (p^1, p^2, p^3), so read the null vector "
                "back with p.reshape(3, 4), before undoing the normalisation."
            )
    for U, T in frames[:2]:  # mean or RMS distances: either is right
        P_hat = T @ expected @ np.linalg.inv(U)
        if same_up_to_scale(g, P_hat, rtol=1e-5):
            return (
                "you returned P_hat, the camera of the normalised points: the normalisation is not undone. "
                "P_hat maps U X to T u, so P = inv(T) @ P_hat @ U."
            )
        for wrong, how in (
            (T @ P_hat @ np.linalg.inv(U), "T @ P_hat @ inv(U)"),
            (np.linalg.inv(T) @ P_hat @ np.linalg.inv(U), "inv(T) @ P_hat @ inv(U)"),
            (T @ P_hat @ U, "T @ P_hat @ U"),
        ):
            if same_up_to_scale(g, wrong, rtol=1e-5):
                return (
                    f"you undid the normalisation the wrong way round ({how}). P_hat maps U X to T u: "
                    f"T u ~ P_hat U X, so u ~ inv(T) P_hat U X and P = inv(T) @ P_hat @ U."
                )
        if same_up_to_scale(g, np.linalg.inv(T) @ P_hat, rtol=1e-5):
            return (
                "you undid only the pixels' normalisation (inv(T) @ P_hat): P_hat still expects normalised "
                "world points U X. Undo both: P = inv(T) @ P_hat @ U."
            )
        if same_up_to_scale(g, P_hat @ U, rtol=1e-5):
            return (
                "you undid only the world points' normalisation (P_hat @ U): the result still gives "
                "normalised pixels T u. Undo both: P = inv(T) @ P_hat @ U."
            )
    pixels = _pixels_of(g, X)
    for reflected in (
        -uv,
        2 * uv.mean(axis=0) - uv,
    ):  # +u, +v in A: the camera of the mirrored pixels
        if np.allclose(pixels, reflected, atol=1e-4 * max(1.0, np.abs(uv).max())):
            return (
                "your P images every point at the pixels mirrored through the origin of the (normalised) pixel "
                "coordinates: a sign slip in A. u x P X = 0 gives the rows (X^T, 0, -u X^T) and (0, X^T, -v X^T), "
                "with minus signs."
            )
    if _is_vt_column(g, X, uv):
        return (
            "you took a column of Vt. np.linalg.svd returns Vt, V transposed: the right singular vectors "
            "are its rows, so the null vector is the last row, Vt[-1], not Vt[:, -1]."
        )
    gap = _pixel_gap(g, expected, X)
    return (
        f"P does not image X at uv (exact pixels here, and your P is up to {gap:.3g} px off). Build two rows "
        f"of u x P X = 0 per point, (X^T, 0, -u X^T) and (0, X^T, -v X^T), take the right singular vector of A "
        f"with the smallest singular value (the last row of Vt, Vt[-1]) and reshape it row by row to (3, 4)."
    )


def _is_vt_column(got, X, uv) -> bool:
    """True if ``got`` is Vt[:, -1] (the last entry of every right singular vector) in place of Vt[-1].

    Each singular vector's sign is LAPACK's choice, and it changes with A's row order (all u rows, then
    all v rows, or interleaved per point), so compare magnitudes entry by entry, in each normalised frame.
    """
    for U, T in (_normalisers(X, uv), _rms_normalisers(X, uv), (np.eye(4), np.eye(3))):
        column = np.abs(np.linalg.svd(_dlt_rows(_in_frame(U, X), _in_frame(T, uv)))[2][:, -1])
        P_hat = np.abs(T @ got @ np.linalg.inv(U)).ravel()
        if np.abs(P_hat).max() > 0 and np.allclose(
            P_hat / np.abs(P_hat).max(), column / column.max(), atol=1e-6
        ):
            return True
    return False


def estimate_projection_matrix(X, uv):
    """The normalised DLT: normalise, two rows of u x P X = 0 per point, SVD, undo."""
    X, uv = np.asarray(X, dtype=float), np.asarray(uv, dtype=float)

    def normaliser(p):  # centroid to 0, mean distance to the centroid sqrt(D), D = 2 or 3
        c = p.mean(axis=0)
        s = np.sqrt(p.shape[1]) / np.mean(np.linalg.norm(p - c, axis=1))
        T = s * np.eye(p.shape[1] + 1)
        T[:-1, -1], T[-1, -1] = -s * c, 1.0
        return T

    U, T = normaliser(X), normaliser(uv)
    Xn = np.column_stack([X, np.ones(len(X))]) @ U.T  # normalised homogeneous points, as rows
    un = np.column_stack([uv, np.ones(len(uv))]) @ T.T
    rows = []
    for Xh, (u, v, w) in zip(Xn, un, strict=True):  # u x P X = 0: two independent rows per point
        rows.append(np.concatenate([w * Xh, np.zeros(4), -u * Xh]))
        rows.append(np.concatenate([np.zeros(4), w * Xh, -v * Xh]))
    P_hat = np.linalg.svd(np.array(rows))[2][-1].reshape(
        3, 4
    )  # smallest singular value's right vector
    return np.linalg.inv(T) @ P_hat @ U  # T u ~ P_hat U X, so u ~ T^-1 P_hat U X


register_exercise(
    Exercise(
        name="estimate_projection_matrix",
        lesson="04",
        reference=cm.estimate_projection_matrix,
        cases=_dlt_cases,
        compare=lambda got, expected: same_up_to_scale(
            got, expected, rtol=1e-6
        ),  # exact pixels: P up to scale
        diagnose=_dlt_diagnosis,
        follow_up=_dlt_follow_up,
        wrong_variants=(
            (_dlt_not_undone, "not undone"),
            (_dlt_undone_wrong_order, "wrong way round"),
            (lambda X, uv: _dlt_unnormalised(np.asarray(X), np.asarray(uv)), "no normalisation"),
            (lambda X, uv: _dlt_half(X, uv, world=False), "world points are not normalised at all"),
            (lambda X, uv: _dlt_half(X, uv, pixels=False), "pixels are not normalised at all"),
            (
                lambda X, uv: _dlt_partial(X, uv, world=(True, False), pixels=(True, False)),
                "centred but not scaled",
            ),
            (
                lambda X, uv: _dlt_partial(X, uv, world=(True, False)),
                "world points are centred but not scaled",
            ),
            (
                lambda X, uv: _dlt_partial(X, uv, world=(False, True), pixels=(False, True)),
                "scaled but not centred",
            ),
            (
                lambda X, uv: _dlt_partial(X, uv, pixels=(False, True)),
                "pixels are scaled but not centred",
            ),
            (_dlt_p34, "p34 = 1"),
            (lambda X, uv: _dlt_half(X, uv, undo="T"), "undid only the pixels'"),
            (lambda X, uv: _dlt_half(X, uv, undo="U"), "undid only the world points'"),
            (lambda X, uv: _dlt_half(X, uv, sign=1.0), "sign slip in A"),
            (lambda X, uv: _dlt_half(X, uv, column=True), "Vt[-1], not Vt[:, -1]"),
            (lambda X, uv: _dlt_half(X, uv, column=True, interleave=True), "Vt[-1], not Vt[:, -1]"),
            (lambda X, uv: _dlt_half(X, uv, order="F"), "column by column"),
            (lambda X, uv: _dlt_half(X, uv, order="F", interleave=True), "column by column"),
            (lambda X, uv: cm.estimate_projection_matrix(X, uv).T, "transposed"),
            (
                lambda X, uv: (
                    cm.estimate_projection_matrix(X, uv).ravel().reshape((3, 4), order="F")
                ),
                "wrong order",
            ),
        ),
        teaching=estimate_projection_matrix,
    )
)


# -- blender_matrix_world (OpenCV pose -> Blender camera) -----------------------------------------

_F = np.diag([1.0, -1.0, -1.0])


def _blender_cases():
    # the camera with t_x != 0 first: a look-at camera aimed above the origin has t_x = 0, where
    # -R^T F t (t not flipped) equals R^T t (a sign slip), so its diagnosis could not tell them apart
    return [(c.R, c.t) for c in _cameras()[::-1]]


def _blender_diagnosis(args, got, expected) -> str:
    R, t = (np.asarray(a, dtype=float) for a in args)
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return the 4 x 4 matrix [[R_gl^T, C], [0, 0, 0, 1]]."
    g = np.asarray(got, dtype=float)
    if not np.allclose(g[3], [0.0, 0.0, 0.0, 1.0]):
        if np.allclose(g[:, 3], [0.0, 0.0, 0.0, 1.0]) and np.allclose(g.T, expected, atol=1e-9):
            return (
                "your matrix is transposed: its last row holds C, its last column (0, 0, 0, 1). matrix_world "
                "is [[R_gl^T, C], [0, 0, 0, 1]]: the centre is the last column."
            )
        return "the last row of a rigid motion in homogeneous form is (0, 0, 0, 1)."
    A, c = g[:3, :3], g[:3, 3]
    C = -R.T @ t
    rotation_right = np.allclose(A, R.T @ _F, atol=1e-9)
    if rotation_right and np.allclose(c, -R.T @ _F @ t, atol=1e-9):
        return (
            "you flipped R but not t: t_gl = F t as well, so the last column is -R_gl^T t_gl = -R^T F F t = "
            "-R^T t = C (or write C = -R^T t directly); -R^T F t is not the camera centre."
        )
    if np.allclose(A, _F @ R.T, atol=1e-9) and np.allclose(c, _F @ C, atol=1e-9):
        return (
            "you flipped the world's Y and Z (diag(1, -1, -1, 1) @ world_from_cam): F multiplies on the wrong "
            "side. R_gl = F R flips the camera's axes, the columns of R^T (R^T F), and leaves the world alone, so "
            "the last column stays the camera centre C = -R^T t, not F C."
        )
    for G in _sign_flips():
        if (
            not np.allclose(G, _F)
            and np.allclose(A, R.T @ G, atol=1e-9)
            and np.allclose(c, C, atol=1e-9)
        ):
            flipped = " and ".join("xyz"[i] for i in range(3) if G[i, i] < 0)
            if np.linalg.det(G) < 0:
                return (
                    f"you flipped only the camera's {flipped} axis: one flipped axis is a mirror (det = -1), "
                    f"no rotation, and Blender would render a mirrored picture. The OpenGL frame flips two axes, "
                    f"y and z: F = diag(1, -1, -1), so R_gl^T = R^T F."
                )
            return (
                f"you flipped the camera's {flipped} axes; OpenGL keeps x right and flips y (up) and z (backward): "
                f"F = diag(1, -1, -1), so R_gl^T = R^T F."
            )
    if np.allclose(A, _F @ R, atol=1e-9) and np.allclose(c, _F @ t, atol=1e-9):
        return (
            "you returned the OpenGL pose (R_gl, t_gl) = (F R, F t) itself: that is still cam_from_world. "
            "matrix_world is world_from_cam, its inverse: [[R_gl^T, -R_gl^T t_gl], [0, 1]]."
        )
    if np.allclose(A, R.T, atol=1e-9):
        return (
            "your rotation block is R^T: the inverse without the axis flip, so the camera would look along +z "
            "with y down, the OpenCV way. Flip first, R_gl = F R with F = diag(1, -1, -1), then R_gl^T = R^T F."
        )
    if np.allclose(A, _F @ R.T, atol=1e-9) or np.allclose(A, _F @ R.T @ _F, atol=1e-9):
        return (
            "F multiplies on the wrong side: R_gl = F R flips the camera's axes (R's rows), so R_gl^T = R^T F "
            "flips the columns of R^T. F R^T flips the world's Y and Z instead."
        )
    if np.allclose(A, _F @ R, atol=1e-9):
        return (
            "your rotation block is R_gl, not its transpose: world_from_cam needs R_gl^T = R^T F."
        )
    if rotation_right and np.allclose(c, t, atol=1e-9):
        return "the last column is t, the world origin in camera coordinates; matrix_world's is the camera centre C = -R^T t."
    if rotation_right and np.allclose(c, _F @ t, atol=1e-9):
        return (
            "the last column is t_gl = F t, the world origin in the OpenGL camera's coordinates; matrix_world's "
            "last column is the camera centre in the world, -R_gl^T t_gl = -R^T t = C."
        )
    if rotation_right and np.allclose(c, _F @ C, atol=1e-9):
        return (
            "the last column is F C: you flipped the centre. F flips the camera's own axes; the centre is a point "
            "of the world, the same in both conventions, so F does not touch it: C = -R^T t."
        )
    if rotation_right and np.allclose(c, -C, atol=1e-9):
        return (
            "the last column has the wrong sign: it is R^T t = -C. The centre solves R C + t = 0, so "
            "C = -R^T t (= -R_gl^T t_gl), with the minus sign."
        )
    return "matrix_world = [[R_gl^T, -R_gl^T t_gl], [0, 0, 0, 1]] with R_gl = F R, t_gl = F t, F = diag(1, -1, -1)."


def blender_matrix_world(R, t):
    """Blender's matrix_world (world_from_cam, OpenGL axes) for the OpenCV pose cam_from_world (R, t)."""
    F = np.diag([1.0, -1.0, -1.0])  # flip the camera's y and z: y up, z backward
    R_gl, t_gl = F @ np.asarray(R), F @ np.asarray(t)
    M = np.eye(4)
    M[:3, :3] = R_gl.T  # invert the rigid motion: world_from_cam
    M[:3, 3] = -R_gl.T @ t_gl  # = -R^T t, the camera centre C
    return M


register_exercise(
    Exercise(
        name="blender_matrix_world",
        lesson="04",
        reference=cm.blender_matrix_world,
        cases=_blender_cases,
        compare=same_array(rtol=1e-8, atol=1e-9),
        diagnose=_blender_diagnosis,
        wrong_variants=(
            (
                lambda R, t: np.block(
                    [[_F @ R, (_F @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "OpenGL pose",
            ),
            (
                lambda R, t: np.block(
                    [[R.T, (-R.T @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "without the axis flip",
            ),
            (
                lambda R, t: np.block(
                    [[_F @ R.T, (-R.T @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "wrong side",
            ),
            (
                lambda R, t: np.block(
                    [[R.T @ _F, t[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "the last column is t",
            ),
            (
                lambda R, t: np.block(
                    [[R.T @ _F, (_F @ -R.T @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "F does not touch it",
            ),
            (
                lambda R, t: np.block(
                    [[R.T @ _F, (_F @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "t_gl = F t, the",
            ),
            (
                lambda R, t: np.block(
                    [[R.T @ _F, (R.T @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "wrong sign",
            ),
            (lambda R, t: cm.blender_matrix_world(R, t).T, "transposed"),
            (
                lambda R, t: np.block(
                    [[_F @ R, (-R.T @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "not its transpose",
            ),
            (
                lambda R, t: np.block(
                    [[R.T @ _F, (-R.T @ _F @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "flipped R but not t",
            ),
            (
                lambda R, t: (
                    np.diag([1.0, -1.0, -1.0, 1.0])
                    @ np.block([[R.T, (-R.T @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]])
                ),
                "not F C",
            ),
            (
                lambda R, t: np.block(
                    [
                        [R.T @ np.diag([1.0, 1.0, -1.0]), (-R.T @ t)[:, None]],
                        [np.zeros((1, 3)), np.ones((1, 1))],
                    ]
                ),
                "a mirror",
            ),
        ),
        teaching=blender_matrix_world,
    )
)
