r"""Exercise for lesson 12, measure the world: the 2 x 6 Jacobian of one point's pixel in PnP.

The pose is refined by a small rotation applied on the left, :math:`R \leftarrow \exp([\delta\omega]_\times) R`,
and a translation step, :math:`t \leftarrow t + \delta t`. The point :math:`X_c = R X + t` then moves by
:math:`\partial X_c / \partial \delta\omega = -[X_c - t]_\times` (since :math:`[\delta\omega]_\times R X =
-[R X]_\times \delta\omega`) and :math:`\partial X_c / \partial \delta t = I`, and the pixel
:math:`u = f_x x/z + c_x`, :math:`v = f_y y/z + c_y` by

.. math:: \frac{\partial (u, v)}{\partial X_c} = \begin{pmatrix} f_x/z & 0 & -f_x x/z^2 \\
          0 & f_y/z & -f_y y/z^2 \end{pmatrix} .

The chain rule gives the 2 x 6 Jacobian, columns :math:`(\delta\omega, \delta t)`, one point's rows of
:func:`camlab.measurement.pose_jacobian` (``tests/test_exercises_measurement.py`` compares them).

References
----------
Hartley & Zisserman, Multiple View Geometry, 2nd ed., sections 6.1 (the finite camera) and 7.2
(resectioning by geometric error, minimised by the iterative methods of appendix A6); Szeliski, Computer Vision, 2nd ed., section 11.2.2 (the left update of a rotation).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ._answers import same_array, shape_problem
from ._core import Exercise, Mistake, first_mistake, mistake_variant, register_exercise

_K = np.array([[532.8, 0.0, 341.8], [0.0, 533.0, 234.1], [0.0, 0.0, 1.0]])


def _rotation(r) -> np.ndarray:
    r = np.asarray(r, dtype=float)
    th = np.linalg.norm(r)
    S = _skew(r / th)
    return np.eye(3) + np.sin(th) * S + (1 - np.cos(th)) * S @ S


def _skew(w) -> np.ndarray:
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def _cases():
    """(K, R, t, X): a board corner (Z = 0) and a point off the board, seen from three poses."""
    return [
        (
            _K.copy(),
            _rotation([0.3, -0.2, 0.1]),
            np.array([-0.1, -0.05, 0.45]),
            np.array([0.15, 0.1, 0.0]),
        ),
        (
            _K.copy(),
            _rotation([0.45, 0.15, -0.3]),
            np.array([0.08, -0.06, 0.6]),
            np.array([0.05, 0.125, 0.0]),
        ),
        (
            _K.copy(),
            _rotation([-0.5, 0.4, 1.2]),
            np.array([-0.05, 0.02, 0.55]),
            np.array([0.1, 0.05, -0.08]),
        ),
    ]


def _reference(K, R, t, X):
    """The (2, 6) Jacobian by columns: d X_c / d dw_k = e_k x (R X), as camlab.measurement.pose_jacobian."""
    K, R, t, X = (np.asarray(v, dtype=float) for v in (K, R, t, X))
    Xc = R @ X + t
    P = K @ Xc
    dpix = (K[:2] - np.outer(P[:2] / P[2], K[2])) / P[2]  # d(P[:2] / P[2]) / d Xc
    dXc = np.hstack([np.cross(np.eye(3), R @ X).T, np.eye(3)])
    return dpix @ dXc


def point_jacobian(K, R, t, X):
    """The (2, 6) Jacobian of the pixel of X under R <- exp([dw]x) R, t <- t + dt.

    Parameters
    ----------
    K : (3, 3) ndarray
        Intrinsics, pixels, no skew.
    R, t : (3, 3), (3,) ndarray
        The pose, cam_from_world (X_c = R X + t).
    X : (3,) ndarray
        One world point.

    Returns
    -------
    (2, 6) ndarray
        Rows u, v; columns dw (pixels per radian), then dt (pixels per world unit).
    """
    Xc = R @ X + t  # the point in the camera frame
    x, y, z = Xc
    fx, fy = K[0, 0], K[1, 1]
    # d(u, v) / d Xc, from u = fx x / z + cx and v = fy y / z + cy
    dpix = np.array([[fx / z, 0.0, -fx * x / z**2], [0.0, fy / z, -fy * y / z**2]])
    # d Xc / d dw = -[Xc - t]x, the skew matrix of R X with a minus; d Xc / d dt = I
    a, b, c = Xc - t
    minus_skew = -np.array([[0.0, -c, b], [c, 0.0, -a], [-b, a, 0.0]])
    return np.hstack([dpix @ minus_skew, dpix])


def _context(K, R, t, X):
    K, R, t, X = (np.asarray(v, dtype=float) for v in (K, R, t, X))
    Xc = R @ X + t
    x, y, z = Xc
    fx, fy = K[0, 0], K[1, 1]
    dpix = np.array([[fx / z, 0.0, -fx * x / z**2], [0.0, fy / z, -fy * y / z**2]])
    right = _reference(K, R, t, X)
    return SimpleNamespace(
        right=right,
        dpix=dpix,
        with_=lambda dw, dp=dpix: np.hstack([dp @ dw, dp]),
        RX=Xc - t,
        X=X,
        Xc=Xc,
        R=R,
        no_cross=np.array([[fx / z, 0.0, 0.0], [0.0, fy / z, 0.0]]),
        at_RX=_dpix(K, R @ X),  # d(u, v)/d X_c taken at R X: t left out of X_c
        z_once=np.array([[fx / z, 0.0, -fx * x / z], [0.0, fy / z, -fy * y / z]]),
        pixel_over_z=np.array(
            [[fx / z, 0.0, -(fx * x / z + K[0, 2]) / z], [0.0, fy / z, -(fy * y / z + K[1, 2]) / z]]
        ),
        z_plus=np.array([[fx / z, 0.0, fx * x / z**2], [0.0, fy / z, fy * y / z**2]]),
        fx_twice=np.array([[fx / z, 0.0, -fx * x / z**2], [0.0, fx / z, -fx * y / z**2]]),
        fx_fy_swapped=np.array([[fy / z, 0.0, -fy * x / z**2], [0.0, fx / z, -fx * y / z**2]]),
        no_division=np.array([[fx, 0.0, 0.0], [0.0, fy, 0.0]]),
        times_z=z * dpix,
        K_rows=K[:2],
        K_rows_over_z=K[:2] / z,
        transposed=_reference(K, R.T, t, X),  # the right formula, R.T used for R throughout
        inverted=_inverted(K, R, t, X),
        K_transposed=_dpix_transposed(K, Xc),
    )


def _dpix_transposed(K, Xc):
    """d(u, v)/d X_c when the pixel is taken as X_c @ K (K^T X_c): K transposed."""
    p = K.T @ Xc
    return (K.T[:2] * p[2] - np.outer(p[:2], K.T[2])) / p[2] ** 2


def _dpix(K, Xc):
    """d(u, v)/d X_c at the camera-frame point ``Xc``."""
    x, y, z = Xc
    return np.array(
        [[K[0, 0] / z, 0.0, -K[0, 0] * x / z**2], [0.0, K[1, 1] / z, -K[1, 1] * y / z**2]]
    )


def _inverted(K, R, t, X):
    """The pose read as world_from_cam, X_c = R^T (X - t), with R, t perturbed as the prompt says.

    R <- exp([dw]x) R gives X_c = R^T exp(-[dw]x) (X - t), so d X_c / d dw = R^T [X - t]x and
    d X_c / d dt = -R^T, taken at X_c = R^T (X - t).
    """
    Xc = R.T @ (X - t)
    P = K @ Xc
    dpix = (K[:2] - np.outer(P[:2] / P[2], K[2])) / P[2]
    return dpix @ np.hstack([R.T @ _skew(X - t), -R.T])


_MISTAKES = (
    Mistake(
        "skew sign",
        lambda c: c.with_(_skew(c.RX)),
        "your rotation columns have the wrong sign: [dw]x (R X) = dw x (R X) = -(R X) x dw, so "
        "d X_c / d dw = -[X_c - t]x, with a minus.",
    ),
    Mistake(
        "X for X_c - t",
        lambda c: c.with_(-_skew(c.X)),
        "you used the world point X in the skew matrix: the small rotation turns R X, the point already "
        "rotated into the camera's axes, so d X_c / d dw = -[R X]x = -[X_c - t]x.",
    ),
    Mistake(
        "X_c for X_c - t",
        lambda c: c.with_(-_skew(c.Xc)),
        "you used X_c in the skew matrix: the left rotation turns R X and not t (t <- t + dt moves "
        "separately), so d X_c / d dw = -[X_c - t]x = -[R X]x.",
    ),
    Mistake(
        "+[X_c]x",
        lambda c: c.with_(_skew(c.Xc)),
        "two slips in the rotation columns: the sign and the vector. [dw]x (R X) = -(R X) x dw gives a "
        "minus, and the left rotation turns R X = X_c - t, not X_c (t moves by dt separately): "
        "d X_c / d dw = -[X_c - t]x.",
    ),
    Mistake(
        "+[X]x",
        lambda c: c.with_(_skew(c.X)),
        "two slips in the rotation columns: the sign and the vector. [dw]x (R X) = -(R X) x dw gives a "
        "minus, and the small rotation turns R X (the point in the camera's axes), not the world point X: "
        "d X_c / d dw = -[R X]x = -[X_c - t]x.",
    ),
    Mistake(
        "right perturbation",
        lambda c: c.with_(-c.R @ _skew(c.X)),
        "you perturbed on the right, R <- R exp([dw]x) (dw in the world's axes): section 1 applies the "
        "small rotation on the LEFT, R <- exp([dw]x) R, so d X_c / d dw = -[R X]x.",
    ),
    Mistake(
        "t forgotten in X_c",
        lambda c: c.with_(-_skew(c.RX), c.at_RX),
        "you took d(u, v)/d X_c at R X, leaving t out of the camera-frame point: the pixel is the "
        "projection of X_c = R X + t, so x, y and z in [[fx/z, 0, -fx x/z^2], [0, fy/z, -fy y/z^2]] are "
        "the entries of R @ X + t (only the skew matrix uses R X = X_c - t).",
    ),
    Mistake(
        "no -x/z^2 term",
        lambda c: c.with_(-_skew(c.RX), c.no_cross),
        "your d(u, v)/d X_c lacks its third column: u = fx x / z + cx depends on z too, "
        "du/dz = -fx x / z^2 and dv/dz = -fy y / z^2.",
    ),
    Mistake(
        "z not squared",
        lambda c: c.with_(-_skew(c.RX), c.z_once),
        "your d(u, v)/dz divides by z once: d(x / z)/dz = -x / z^2, so du/dz = -fx x / z^2.",
    ),
    Mistake(
        "u for u - cx",
        lambda c: c.with_(-_skew(c.RX), c.pixel_over_z),
        "your third column uses the pixel u, which includes cx: du/dz = -fx x / z^2 = -(u - cx) / z, "
        "and dv/dz = -fy y / z^2 = -(v - cy) / z (the principal point does not move with z).",
    ),
    Mistake(
        "z term sign",
        lambda c: c.with_(-_skew(c.RX), c.z_plus),
        "your du/dz and dv/dz have the wrong sign: moving a point away (z up) pulls its pixel toward "
        "the principal point, d(x / z)/dz = -x / z^2, so du/dz = -fx x / z^2.",
    ),
    Mistake(
        "fx for fy",
        lambda c: c.with_(-_skew(c.RX), c.fx_twice),
        "your v row uses fx: v = fy y / z + cy, so the v row's derivatives carry fy = K[1, 1] "
        "(fx and fy differ slightly on a real camera).",
    ),
    Mistake(
        "no perspective division",
        lambda c: c.with_(-_skew(c.RX), c.no_division),
        "you forgot the perspective division: u = fx x / z + cx, not fx x + cx, so d(u, v)/d X_c = "
        "[[fx/z, 0, -fx x/z^2], [0, fy/z, -fy y/z^2]] (dividing by z also brings the third column).",
    ),
    Mistake(
        "X_c @ K",
        lambda c: c.with_(-_skew(c.RX), c.K_transposed),
        "you projected with X_c @ K, which is K^T X_c (K transposed): a point as a row goes to pixels "
        "by X_c @ K.T, so u = fx x / z + cx and d(u, v)/d X_c = [[fx/z, 0, -fx x/z^2], [0, fy/z, -fy y/z^2]].",
    ),
    Mistake(
        "K rows only",
        lambda c: c.with_(-_skew(c.RX), c.K_rows),
        "you took K[:2] as d(u, v)/d X_c: that is the Jacobian of the homogeneous pixel K X_c before the "
        "division by its third entry z. Differentiate u = fx x / z + cx: [[fx/z, 0, -fx x/z^2], "
        "[0, fy/z, -fy y/z^2]].",
    ),
    Mistake(
        "K rows over z",
        lambda c: c.with_(-_skew(c.RX), c.K_rows_over_z),
        "you took K[:2] / z as d(u, v)/d X_c: the homogeneous Jacobian divided once, the quotient rule "
        "dropped. The third column is -(u - c_x)/z = -fx x/z^2 (and -fy y/z^2), not c_x/z: "
        "[[fx/z, 0, -fx x/z^2], [0, fy/z, -fy y/z^2]].",
    ),
    Mistake(
        "quotient rule without the last /z",
        lambda c: c.with_(-_skew(c.RX), c.times_z),
        "your d(u, v)/d X_c is z times too large: the quotient rule gives (fx z - fx x * 0) / z^2 = fx / z "
        "and -fx x / z^2; you left out one division by z (the perspective division's).",
    ),
    Mistake(
        "R.T for R",
        lambda c: c.transposed,
        "you rotated with R.T: the pose is cam_from_world, X_c = R X + t with R itself, not its "
        "transpose (R.T maps the camera's axes back to the world's).",
    ),
    Mistake(
        "fx and fy swapped",
        lambda c: c.with_(-_skew(c.RX), c.fx_fy_swapped),
        "you swapped fx and fy: u = fx x / z + cx uses fx = K[0, 0] and v = fy y / z + cy uses "
        "fy = K[1, 1] (they differ slightly on a real camera).",
    ),
    Mistake(
        "times 180 / pi",
        lambda c: np.hstack([c.right[:, :3] * 180 / np.pi, c.right[:, 3:]]),
        "your rotation columns are 180 / pi = 57.3 times too large: you multiplied by 180 / pi where "
        "a conversion would need pi / 180, and dw is in radians already (the API's unit): do not convert.",
    ),
    Mistake(
        "degrees",
        lambda c: np.hstack([c.right[:, :3] * np.pi / 180, c.right[:, 3:]]),
        "your rotation columns are pi / 180 times too small: per degree, not per radian. dw is in "
        "radians (the API's unit); do not convert.",
    ),
    Mistake(
        "blocks swapped",
        lambda c: np.hstack([c.right[:, 3:], c.right[:, :3]]),
        "your columns are (dt, dw): the prompt orders them (dw, dt), the rotation's three first.",
    ),
    Mistake(
        "residual",
        lambda c: -c.right,
        "every entry has the wrong sign: you differentiated the residual u_measured - pi(...); the "
        "exercise asks for the pixel's own Jacobian, d pi / d(dw, dt).",
    ),
    Mistake(
        "no focal length",
        lambda c: c.right / np.array([[c.dpix[0, 0] * c.Xc[2]], [c.dpix[1, 1] * c.Xc[2]]]),
        "your Jacobian is in normalised coordinates (x / z, y / z): multiply the u row by fx and the v "
        "row by fy, since u = fx x / z + cx.",
    ),
    Mistake(
        "pose inverted",
        lambda c: c.inverted,
        "you read the pose the wrong way round, as world_from_cam, X_c = R^T (X - t): the course's poses "
        "are cam_from_world, X_c = R X + t (docs/conventions.md), so X_c = R @ X + t, and its rotation "
        "columns are -[X_c - t]x = -[R X]x.",
    ),
    Mistake(
        "dt in mm",
        lambda c: np.hstack([c.right[:, :3], c.right[:, 3:] / 1000]),
        "your translation columns are 1000 times too small, per millimetre: t is in metres (the board's "
        "units), so d(u, v)/d dt is in pixels per metre; do not convert.",
    ),
    Mistake(
        "dt times 1000",
        lambda c: np.hstack([c.right[:, :3], c.right[:, 3:] * 1000]),
        "your translation columns are 1000 times too large: t and dt are in metres (the board's units), "
        "so d(u, v)/d dt is in pixels per metre; do not convert to or from millimetres.",
    ),
    Mistake(
        "dt sign",
        lambda c: np.hstack([c.right[:, :3], -c.right[:, 3:]]),
        "your translation columns have the wrong sign: t <- t + dt moves X_c = R X + t by +dt, so "
        "d X_c / d dt = +I (only the rotation block carries a minus, -[X_c - t]x).",
    ),
    Mistake(
        "dt through R",
        lambda c: np.hstack([c.right[:, :3], c.dpix @ c.R]),
        "your translation columns carry R: t is added after the rotation, X_c = R X + t, so dt is already "
        "in the camera's axes and d X_c / d dt = I, not R.",
    ),
    Mistake(
        "rows swapped",
        lambda c: c.right[::-1],
        "your rows are (v, u): row 0 is u (the column), row 1 is v (the row), as pixels are (u, v).",
    ),
)


def _diagnosis(args, got, expected) -> str:
    g = np.asarray(got) if got is not None else None
    if g is not None and g.shape == (6, 2):
        return (
            "you returned a (6, 2) array, the transpose: one row per pixel coordinate (u, v) and one "
            "column per pose parameter (dw, dt), shape (2, 6); build it with np.hstack, not np.vstack."
        )
    problem = shape_problem(got, expected)
    if problem:
        return problem
    hint = first_mistake(
        _MISTAKES,
        _context(*args),
        g.astype(float),
        lambda a, b: np.allclose(a, b, rtol=1e-6, atol=1e-6),
    )
    if hint:
        return hint
    hint = _one_focal(np.asarray(args[0], dtype=float), g.astype(float), expected)
    if hint:
        return hint
    bad = [k for k in range(6) if not np.allclose(g[:, k], expected[:, k], rtol=1e-6, atol=1e-6)]
    worst = float(np.max(np.abs(g - expected)) / np.max(np.abs(expected)))
    if worst < 1e-2:
        return (
            f"nearly right: columns {bad} (0-2: dw, 3-5: dt) differ from the exact Jacobian by up to "
            f"{np.max(np.abs(g - expected)):.1e} px per radian or per metre, more than the check's 1e-6 relative "
            "to each entry: the error of a forward difference, (f(p + h) - f(p)) / h, or of "
            "too large a step. Use central differences, (f(p + h) - f(p - h)) / (2h) with h about 1e-6, or "
            "the chain rule the prompt asks for, which is exact."
        )
    return (
        f"columns {bad} differ (0-2: dw, 3-5: dt): check d(u, v)/d X_c = [[fx/z, 0, -fx x/z^2], "
        "[0, fy/z, -fy y/z^2]], then d X_c / d dw = -[X_c - t]x and d X_c / d dt = I. Central "
        "differences of your projection, one parameter at a time, show which is off."
    )


def _one_focal(K, got, expected) -> str:
    """The hint for rows each scaled by one factor, as if one focal length f served both (or "")."""
    scale = [float(got[k] @ expected[k] / (expected[k] @ expected[k])) for k in (0, 1)]
    if not all(np.allclose(got[k], scale[k] * expected[k], rtol=1e-6, atol=1e-9) for k in (0, 1)):
        return ""
    f_u, f_v = scale[0] * K[0, 0], scale[1] * K[1, 1]  # the focal length each row was built with
    if np.allclose(scale, 1.0, rtol=1e-6) or abs(f_u - f_v) > 1e-6 * K[0, 0]:
        return ""
    return (
        f"both rows are built with one focal length, f = {f_u:.4f} (fx = {K[0, 0]:.4f}, fy = {K[1, 1]:.4f}): "
        "each row carries its own, u = fx x / z + cx with fx = K[0, 0] for the u row and v = fy y / z + cy "
        "with fy = K[1, 1] for the v row. Averaging them, (fx + fy) / 2, is not exact when fx and fy differ."
    )


def _averaged_focal(K, R, t, X):
    """A slip: one focal length, (fx + fy) / 2, for both rows."""
    K1 = np.array(K, dtype=float)
    K1[0, 0] = K1[1, 1] = (K1[0, 0] + K1[1, 1]) / 2
    return point_jacobian(K1, R, t, X)


def _forward_difference(K, R, t, X):
    """A near miss: one-sided differences of the projection, step 1e-6 (off by about 1e-4 px/rad)."""

    def pixel(p):
        Xc = (_rotation(p[:3]) if np.any(p[:3]) else np.eye(3)) @ R @ X + t + p[3:]
        return (K @ Xc)[:2] / (K @ Xc)[2]

    return np.column_stack([(pixel(h) - pixel(np.zeros(6))) / 1e-6 for h in 1e-6 * np.eye(6)])


def _variant(name):
    return mistake_variant(_MISTAKES, name, _context)


register_exercise(
    Exercise(
        name="point_jacobian",
        lesson="12",
        reference=_reference,
        cases=_cases,
        compare=same_array(rtol=1e-6, atol=1e-6),
        diagnose=_diagnosis,
        wrong_variants=(
            (_variant("skew sign"), "wrong sign: [dw]x"),
            (_variant("K rows over z"), "quotient rule"),
            (_variant("X_c @ K"), "K transposed"),
            (_variant("X for X_c - t"), "world point X"),
            (_variant("X_c for X_c - t"), "used X_c"),
            (_variant("right perturbation"), "on the right"),
            (_variant("+[X_c]x"), "the sign and the vector"),
            (_variant("+[X]x"), "not the world point X"),
            (_variant("t forgotten in X_c"), "leaving t out"),
            (_variant("no -x/z^2 term"), "third column"),
            (_variant("z not squared"), "divides by z once"),
            (_variant("u for u - cx"), "includes cx"),
            (_variant("z term sign"), "wrong sign: moving"),
            (_variant("fx for fy"), "uses fx"),
            (_variant("no perspective division"), "perspective division"),
            (_variant("K rows only"), "K[:2]"),
            (_variant("quotient rule without the last /z"), "z times too large"),
            (_variant("R.T for R"), "rotated with R.T"),
            (_variant("fx and fy swapped"), "swapped fx and fy"),
            (_variant("times 180 / pi"), "180 / pi"),
            (_variant("degrees"), "per degree"),
            (_variant("blocks swapped"), "(dt, dw)"),
            (_variant("residual"), "residual"),
            (_variant("no focal length"), "normalised"),
            (_variant("rows swapped"), "(v, u)"),
            (_variant("pose inverted"), "world_from_cam"),
            (_variant("dt in mm"), "per millimetre"),
            (_variant("dt times 1000"), "1000 times too large"),
            (_variant("dt sign"), "d X_c / d dt = +I"),
            (_variant("dt through R"), "carry R"),
            ((lambda K, R, t, X: _forward_difference(K, R, t, X)), "forward difference"),
            ((lambda K, R, t, X: _averaged_focal(K, R, t, X)), "one focal length"),
            ((lambda K, R, t, X: point_jacobian(K, R, t, X).T), "transpose"),
        ),
        teaching=point_jacobian,
        ndarray_only=True,
        solution_note=(
            "# camlab: camlab.measurement.pose_jacobian(K, R, t, X[None]) gives the same for N points, "
            "(2N, 6);\n# solve_pnp uses it in Levenberg-Marquardt and in the pose's covariance."
        ),
    )
)
