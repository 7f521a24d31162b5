"""Lesson 05's third exercise: the least-squares affine camera from noisy correspondences
(see the package docstring)."""

from __future__ import annotations

import numpy as np

from ... import affine as af
from ... import camera as cm
from .._core import Exercise, register_exercise, same_array, shape_problem

# -- estimate_affine_camera -------------------------------------------------------------------

_LSQ = (
    "centre both point sets, M2^T = lstsq(X - mean(X), uv - mean(uv)), t2 = mean(uv) - M2 @ mean(X)"
)


def _estimate_cases():
    rng = np.random.default_rng(5)
    out = []
    for k in range(3):
        R = cm.rotation_from_euler(*rng.uniform(-0.5, 0.5, 3))
        P = af.weak_perspective_matrix(R, [0.1 * k, -0.2, 5.0], 160 + 20 * k, 150, 0.0, (320, 240))
        X = rng.uniform(-1.0, 1.0, (10 + 5 * k, 3))
        uv = cm.project_points(P, X) + rng.normal(
            0.0, 1.0, (len(X), 2)
        )  # noisy: least squares matters
        out.append((X, uv))
    return out


def _rms(X, P2, uv) -> float:
    """RMS pixel residual of the top rows P2 = [M2 | t2] over the points."""
    return float(np.sqrt(np.mean(np.sum((X @ P2[:, :3].T + P2[:, 3] - uv) ** 2, axis=1))))


def _algebraic_fit(X, uv):
    """The homogeneous system [X 1 0 -u; 0 X 1 -v] h = 0 with a 9th unknown (the scale) solved by SVD, as for
    the DLT: it minimises an algebraic error, not the pixel error."""
    n = len(X)
    A = np.zeros((2 * n, 9))
    A[0::2, :3], A[0::2, 3], A[0::2, 8] = X, 1.0, -uv[:, 0]
    A[1::2, 4:7], A[1::2, 7], A[1::2, 8] = X, 1.0, -uv[:, 1]
    h = np.linalg.svd(A)[2][-1]
    return h[:8].reshape(2, 4) / h[8]


def _similarity(points, scale):
    """The normalising similarity T = [[s I, -s mean], [0, 1]] of (N, D) points for scale s."""
    D = points.shape[1]
    T = np.eye(D + 1)
    T[:D, :D] *= scale
    T[:D, D] = -scale * points.mean(axis=0)
    return T


def _normalisation_scales(points):
    """Scales s a student may normalise (N, D) points with: H&Z's isotropic sqrt(D) / mean distance
    (and sqrt(2) for 3-D points, copied from the 2-D DLT), sqrt(D) / RMS distance, 1 / std."""
    D = points.shape[1]
    c = points - points.mean(axis=0)
    dist = np.linalg.norm(c, axis=1)
    return {
        f"sqrt({D}) / mean distance": np.sqrt(D) / dist.mean(),
        "sqrt(2) / mean distance": np.sqrt(2.0) / dist.mean(),
        f"sqrt({D}) / RMS distance": np.sqrt(D) / np.sqrt(np.mean(dist**2)),
        "1 / std": 1.0 / points.std(),
    }


# How a normalised fit P_n = T_uv P inv(T_X) may be mapped back: what the student wrote, and the result as
# T_uv^a P T_X^b in terms of the least-squares camera P (the right way, inv(T_uv) @ P_n @ T_X, gives a = b = 0).
_UNDO = (
    ("T_uv @ P_n @ inv(T_X)", 2, -2),
    ("P_n", 1, -1),
    ("inv(T_uv) @ P_n", 0, -1),
    ("P_n @ T_X", 1, 0),
    ("inv(T_uv) @ P_n @ inv(T_X)", 0, -2),
    ("T_uv @ P_n @ T_X", 2, 0),
)


def _normalisation_slip(g, expected, X, uv) -> str | None:
    """The cause when ``g`` is the least-squares camera with a similarity normalisation (of a kind in
    :func:`_normalisation_scales`) left in it, or undone in the wrong order."""

    def power(T, k):
        return (
            np.linalg.matrix_power(T, k) if k >= 0 else np.linalg.matrix_power(np.linalg.inv(T), -k)
        )

    undo = "P = inv(T_uv) @ P_n @ T_X"
    for name_x, s_x in _normalisation_scales(X).items():
        T_x = _similarity(X, s_x)
        for name_u, s_u in _normalisation_scales(uv).items():
            T_u = _similarity(uv, s_u)
            both = f"(T_X scaling by {name_x}, T_uv by {name_u})"
            for written, a, b in _UNDO:
                candidate = power(T_u, a) @ expected @ power(T_x, b)
                if not np.allclose(g, candidate, rtol=1e-6, atol=1e-9 * np.abs(candidate).max()):
                    continue
                return {
                    "T_uv @ P_n @ inv(T_X)": f"you normalised the points {both} and undid it in the wrong order: {written} applies the "
                    f"normalisation a second time. The fit P_n = T_uv P inv(T_X) maps normalised points to "
                    f"normalised pixels, so {undo}.",
                    "P_n": f"you normalised the points {both} and did not undo it: your camera maps normalised "
                    f"points to normalised pixels. Map it back: {undo}.",
                    "inv(T_uv) @ P_n": f"the points' normalisation T_X (scaling by {name_x}) is still in your "
                    f"camera: you did not undo it (or undid only T_uv); {undo}.",
                    "P_n @ T_X": f"the pixels' normalisation T_uv (scaling by {name_u}) is still in your camera: "
                    f"you did not undo it (or undid only T_X); {undo}.",
                    "inv(T_uv) @ P_n @ inv(T_X)": f"you normalised the points {both} and undid it as {written}: "
                    f"that undoes T_uv but applies T_X a second time; {undo}.",
                    "T_uv @ P_n @ T_X": f"you normalised the points {both} and undid it as {written}: that undoes "
                    f"T_X but applies T_uv a second time; {undo}.",
                }[written]
    return None


def _unscaled_null_vector(g, X, uv) -> str | None:
    """The cause when g's top rows are the homogeneous system's null vector h[:8] not divided by h[8]."""
    A = _algebraic_fit(X, uv)
    k = float(np.sum(g[:2] * A) / np.sum(A * A))
    if (
        not np.isclose(k, 1.0, rtol=1e-6)
        and k != 0
        and np.allclose(g[:2], k * A, rtol=1e-6, atol=1e-9 * np.abs(g[:2]).max())
    ):
        return (
            f"your top rows are the SVD null vector h of [X, 1, 0, -u; 0, X, 1, -v] h = 0 as it comes (a unit "
            f"vector), {k:.4g} times the camera's: a null vector is fixed only up to scale, so divide by its "
            f"9th entry (the scale) first, P[:2] = (h[:8] / h[8]).reshape(2, 4). Better still, solve the "
            f"inhomogeneous system [X, 1] m = u by least squares: that minimises the pixel error itself "
            f"(the homogeneous one minimises an algebraic error)."
        )
    return None


def _estimate_forms(X, uv, expected):
    """(top rows, cause) for answers that are the least-squares numbers, rearranged or from a wrong fit."""
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    M2, t2 = expected[:2, :3], expected[:2, 3]
    ones_last = expected[:2].T  # lstsq(np.c_[X, ones], uv)[0]: (4, 2), rows M2^T then t2
    ones_first = np.vstack([t2, M2.T])
    centred_pixels_only = np.linalg.lstsq(X, uv - um, rcond=None)[0].T
    n = len(X)
    interleaved, stacked = np.zeros((2 * n, 8)), np.zeros((2 * n, 8))
    interleaved[0::2, :3], interleaved[0::2, 3], interleaved[1::2, 4:7], interleaved[1::2, 7] = (
        X,
        1.0,
        X,
        1.0,
    )
    stacked[:n, :3], stacked[:n, 3], stacked[n:, 4:7], stacked[n:, 7] = X, 1.0, X, 1.0
    order = (
        "the rows of your design matrix and of its right-hand side are in different orders: {a} rows "
        "with {b} right-hand side. Build both the same way: interleaved rows (u1, v1, u2, v2, ...) go with "
        "uv.ravel(), stacked rows (all u, then all v) with np.r_[uv[:, 0], uv[:, 1]] (uv.T.ravel())."
    )
    return [
        (
            np.linalg.lstsq(interleaved, uv.T.ravel(), rcond=None)[0].reshape(2, 4),
            order.format(a="interleaved (u1, v1, u2, v2, ...)", b="a stacked (all u, then all v)"),
        ),
        (
            np.linalg.lstsq(stacked, uv.ravel(), rcond=None)[0].reshape(2, 4),
            order.format(a="stacked (all u, then all v)", b="an interleaved (u1, v1, u2, v2, ...)"),
        ),
        (
            ones_last.reshape(2, 4),
            "P's top rows are scrambled: lstsq with a column of ones returns the (4, 2) "
            "matrix [M2 | t2]^T; transpose it (.T), do not reshape it to (2, 4).",
        ),
        (
            np.c_[t2, M2],
            "your first column holds t2: with the column of ones first, np.c_[ones, X], lstsq's first "
            "row is the translation; put the ones last (np.c_[X, ones]), or move that row: "
            "P[:2] = np.c_[A[1:].T, A[0]].",
        ),
        (
            ones_first.reshape(2, 4),
            "P's top rows are scrambled twice: with the column of ones first, lstsq's first "
            "row is t2, and its (4, 2) result needs a transpose (.T), not a reshape.",
        ),
        (
            np.c_[centred_pixels_only, um - centred_pixels_only @ Xm],
            "you centred the pixels but not the world points: with no constant term, regressing uv - mean(uv) on the "
            "raw X makes M2 absorb X's mean; centre X too (X - mean(X)), or append a column of ones to X.",
        ),
        (
            np.c_[centred_pixels_only, np.zeros(2)],
            "you centred the pixels but not the world points, and left t2 at 0: centre X too, then "
            "t2 = mean(uv) - M2 @ mean(X).",
        ),
        (
            np.c_[centred_pixels_only, um],
            "you centred the pixels but not the world points: centre X too (X - mean(X)); then "
            "t2 = mean(uv) - M2 @ mean(X).",
        ),
        (
            _algebraic_fit(X, uv),
            "you minimised an algebraic error: the homogeneous system [X, 1, 0, -u; 0, X, 1, -v] h = 0 with the scale "
            "as a 9th unknown, solved by SVD as for the DLT, is close to the least-squares camera but not it. An "
            "affine camera's pixels are linear in its 8 entries, so solve the inhomogeneous system [X, 1] m = u by "
            "least squares (np.linalg.lstsq) for the pixel error itself.",
        ),
    ]


def _estimate_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return the 3x4 affine camera with last row (0, 0, 0, 1)."
    X, uv = args
    g = np.asarray(got, dtype=float)
    if not np.allclose(g[2], [0.0, 0.0, 0.0, 1.0], atol=1e-9):
        k = g[2, 3]
        if (
            np.allclose(g[2, :3], 0.0, atol=1e-9)
            and abs(k) > 1e-12
            and np.allclose(g / k, expected, atol=1e-6)
        ):
            return (
                f"your camera is {k:.4g} times the least-squares one: the same camera projectively, but an "
                f"affine camera's last row is fixed to (0, 0, 0, 1); divide by its last entry."
            )
        return "the last row of an affine camera is (0, 0, 0, 1); estimate only the top 2x4 block (8 numbers)."
    for top, cause in _estimate_forms(X, uv, expected):
        if np.allclose(
            g[:2], top, rtol=1e-9, atol=1e-7
        ):  # strict: the algebraic fit is within 1e-5 of the answer
            return cause
    for slip in (_unscaled_null_vector(g, X, uv), _normalisation_slip(g, expected, X, uv)):
        if slip:
            return slip
    M2, t2 = g[:2, :3], g[:2, 3]
    M2_expected, t2_expected = expected[:2, :3], expected[:2, 3]
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    slip = _wrong_mean_cause(M2, X, uv)
    if slip:
        return slip
    if np.linalg.matrix_rank(M2, tol=1e-9 * max(np.abs(M2).max(), 1e-300)) < 2:
        return (
            "M2 has rank < 2 (its rows are parallel or zero), so every point would image onto one line: each "
            "row of M2 is fitted to its own pixel coordinate; did you fit the same column of uv twice, or "
            "broadcast one row?"
        )
    if np.allclose(M2, M2_expected.T.reshape(2, 3), atol=1e-6):
        return "M2 is scrambled: lstsq returns the (3, 2) matrix M2^T; transpose it (.T), do not reshape it to (2, 3)."
    if np.allclose(g[:2], expected[1::-1], atol=1e-6):
        return "u and v are swapped: uv[:, 0] is u (the column), uv[:, 1] is v (the row), and row 1 of P predicts u."
    if np.allclose(M2, np.linalg.lstsq(uv - um, X - Xm, rcond=None)[0], atol=1e-6):
        return (
            "you regressed the world points on the pixels (lstsq(uv, X)); the camera predicts pixels from "
            "points: lstsq(X - mean(X), uv - mean(uv)) gives M2^T."
        )
    if np.allclose(M2, np.linalg.lstsq(X, uv, rcond=None)[0].T, atol=1e-6):
        return (
            "you regressed the pixels on the raw world points, so the fit had no constant term and M2 absorbed "
            "the offset: centre both point sets first (or append a column of ones to X)."
        )
    if np.allclose(M2, M2_expected, atol=1e-6):
        return _translation_cause(t2, t2_expected, um, M2 @ Xm)
    return _estimate_other_cause(g, expected, X, uv)


def _estimate_other_cause(g, expected, X, uv) -> str:
    """Unit slips, a lost normalisation, a DLT, an exact fit to a few points, rounding; else what differs."""
    scale = _image_scaling(g, expected, X)
    if scale is not None and (
        np.isclose(scale, 1e-3, rtol=1e-4) or np.isclose(scale, 1e3, rtol=1e-4)
    ):
        small = scale < 1
        return (
            f"your camera's image is {scale:g} times the size of the least-squares one: a unit slip by 1000 "
            f"(metres and millimetres). The world points X are in metres and the pixels uv in pixels; fit them "
            f"as they are ({'X * 1000 or uv / 1000' if small else 'X / 1000 or uv * 1000'} gives this)."
        )
    if scale is not None:
        return (
            f"your camera's image is the least-squares one scaled by {scale:.4g} (and shifted): a "
            f"normalisation of the points left in it. If you normalised X and uv (x_n = T x), the fit "
            f"P_n maps normalised points to normalised pixels; undo each transform once, on its own side "
            f"and in this order: P = inv(T_uv) @ P_n @ T_X (T_uv @ P_n @ inv(T_X) normalises a second time)."
        )
    if _same_up_to_scale(g[:2], cm.estimate_projection_matrix(X, uv)[:2]):
        return (
            "this is a projective camera (DLT) with its last row overwritten: it does not minimise the pixel "
            "error of an affine camera; fit the 8 affine parameters directly by linear least squares."
        )
    exact = np.linalg.norm(X @ g[:2, :3].T + g[:2, 3] - uv, axis=1) < 1e-6
    if exact.sum() >= 4:
        return (
            f"your camera passes exactly through {int(exact.sum())} of the {len(X)} noisy points: an exact solve "
            f"on a few of them (np.linalg.solve on 4 points?) fits their noise too. Use all the points in one "
            f"least-squares solve: {_LSQ}."
        )
    for decimals in range(5):
        if np.allclose(g, np.round(expected, decimals), rtol=0, atol=1e-9):
            step = "whole numbers" if decimals == 0 else f"{decimals} decimals"
            return (
                f"your entries are the least-squares ones rounded to {step}; return them unrounded: rounding "
                f"an entry of M2 by up to {0.5 * 10.0**-decimals:g} moves the image of a point 1 m from the "
                f"centroid by as many pixels."
            )
    for name, cut in (
        ("truncated towards zero (.astype(int) or int())", np.trunc),
        ("rounded down (np.floor or //)", np.floor),
    ):
        if np.allclose(g, cut(expected), rtol=0, atol=1e-9):
            return (
                f"your entries are whole numbers, the least-squares ones {name}: return the float array "
                f"as it is: dropping up to 1 from each entry moves every image point by up to a pixel through "
                f"t2, and by more through M2 for points far from the world origin."
            )
    for order in ((0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)):
        if np.allclose(g[:2, :3][:, order], expected[:2, :3], rtol=1e-9, atol=1e-7):
            return (
                f"the columns of M2 are in the order {order} of the right ones: column j of M2 multiplies "
                f"coordinate j of X (x, y, z); keep X's columns in that order in the fit and in P."
            )
    r_got, r_exp = _rms(X, g[:2], uv), _rms(X, expected[:2], uv)
    dM = np.abs(g[:2, :3] - expected[:2, :3])
    r, c = np.unravel_index(int(np.argmax(dM)), dM.shape)
    du, dv = g[:2, 3] - expected[:2, 3]
    return (
        f"M2 differs from the least-squares one by up to {dM[r, c]:.4g} (entry ({r}, {c}): {g[r, c]:.6g} for "
        f"{expected[r, c]:.6g}), t2 by ({du:+.4g}, {dv:+.4g}) px. Over the {len(X)} points your camera's RMS "
        f"residual is {r_got:.6f} px against the least-squares minimum {r_exp:.6f} px ({r_got - r_exp:.2g} px "
        f"more): the least-squares camera is the one with the smallest residual, and yours is not it. "
        f"Compare your steps with: {_LSQ}."
    )


def _translation_cause(t2, t2_expected, um, M2Xm) -> str:
    """Why t2 is wrong when M2 is right."""
    if np.allclose(t2, um + M2Xm, atol=1e-6):
        return "t2 has a sign flipped: the centroids correspond, mean(uv) = M2 @ mean(X) + t2, so t2 = mean(uv) - M2 @ mean(X)."
    if np.allclose(t2, um, atol=1e-6):
        return (
            "t2 = mean(uv) is the translation column for the centred points X - mean(X); for the world points "
            "themselves subtract M2's image of their centroid: t2 = mean(uv) - M2 @ mean(X)."
        )
    if np.allclose(t2, 0.0, atol=1e-9):
        return (
            "the translation column is zero: after fitting M2 on centred points, the centroids must "
            "correspond, t2 = mean(uv) - M2 @ mean(X)."
        )
    offset = t2 - t2_expected
    if np.allclose(np.abs(offset), 0.5, atol=1e-6):
        return (
            "t2 is off by half a pixel: pixel centres are at integers (docs/conventions.md), so no 0.5 "
            "belongs in the fit; t2 = mean(uv) - M2 @ mean(X)."
        )
    if np.allclose(np.abs(offset), 1.0, atol=1e-6):
        return (
            "t2 is off by one pixel: pixels count from 0 in numpy and this course, not from 1 (a 1-based "
            "index?); fit the pixels as given, t2 = mean(uv) - M2 @ mean(X)."
        )
    return (
        f"M2 is right but the translation column is off by ({offset[0]:+.4g}, {offset[1]:+.4g}) px: after "
        f"fitting M2 on centred points, the centroids must correspond, t2 = mean(uv) - M2 @ mean(X)."
    )


def _estimate_exception_hint(exc, args) -> str:
    if isinstance(exc, np.linalg.LinAlgError) and "square" in str(exc):
        X = np.asarray(args[0])
        return (
            f"np.linalg.solve (and np.linalg.inv) need a square system, but {len(X)} points give "
            f"{2 * len(X)} equations for 8 unknowns (or {len(X)} rows per pixel coordinate): the system is "
            f"over-determined. Solve it by least squares, np.linalg.lstsq(A, b, rcond=None)[0] (or the normal "
            f"equations np.linalg.solve(A.T @ A, A.T @ b))."
        )
    if isinstance(exc, ValueError) and "broadcast" in str(exc):
        n = len(np.asarray(args[0]))
        if f"({n},)" in str(exc).replace(" ", ""):
            return (
                f"a mean along the wrong axis: X.mean(axis=1) (or uv.mean(axis=1)) is one number per point, "
                f"shape ({n},), and cannot be subtracted from the ({n}, 3) points. The centroid is "
                f"X.mean(axis=0), shape (3,), one mean per coordinate (and uv.mean(axis=0), shape (2,))."
            )
        return (
            "a broadcasting slip: X is (N, 3) and uv (N, 2); X - X.mean(axis=0) and uv - uv.mean(axis=0) "
            "broadcast their centroids over the rows, M2 is (2, 3) and t2 (2,), so t2 = mean(uv) - M2 @ mean(X)."
        )
    return ""


def _wrong_mean_cause(M2, X, uv) -> str | None:
    """The cause when M2 is the fit after centring X or uv (or both) with a wrong mean: along axis=1 (each
    point's own coordinates) or over every entry (no axis)."""
    means = {
        "axis=0": lambda A: A.mean(axis=0),
        "axis=1": lambda A: A.mean(axis=1, keepdims=True),
        "none": lambda A: A.mean(),
    }
    why = {
        "axis=1": "averaged along axis=1, each point's own coordinates, where the centroid of N points is "
        "{name}.mean(axis=0), one mean per coordinate",
        "none": "took the mean of every entry together ({name}.mean() with no axis), a single number, where the "
        "centroid is {name}.mean(axis=0), one mean per coordinate",
    }
    if np.allclose(M2, _fit_centred(X, uv, X.mean(axis=0), uv.mean(axis=0)), atol=1e-6):
        return None  # a constant taken from uv leaves M2 as it is: the cause is elsewhere (t2)
    for how_X, mean_X in means.items():
        for how_uv, mean_uv in means.items():
            if how_X == how_uv == "axis=0" or not np.allclose(
                M2, _fit_centred(X, uv, mean_X(X), mean_uv(uv)), atol=1e-6
            ):
                continue
            if how_X == how_uv:
                return (
                    f"you {why[how_X].format(name='X')} (and the same for uv); then "
                    f"t2 = mean(uv) - M2 @ mean(X)."
                )
            wrong = [(name, how) for name, how in (("X", how_X), ("uv", how_uv)) if how != "axis=0"]
            return (
                "; ".join(f"for {name} you {why[how].format(name=name)}" for name, how in wrong)
                + "; centre both with axis=0, then t2 = mean(uv) - M2 @ mean(X)."
            )
    return None


def _fit_centred(X, uv, X_mean, uv_mean):
    """M2 fitted after subtracting the given (possibly wrong) means."""
    return np.linalg.lstsq(X - X_mean, uv - uv_mean, rcond=None)[0].T


def _image_scaling(got, expected, X):
    """s if ``got`` images every point at s (expected's image) + b for one scalar s != 1, else None."""
    a, b = X @ got[:2, :3].T + got[:2, 3], X @ expected[:2, :3].T + expected[:2, 3]
    A = np.column_stack([b.ravel(), np.tile(np.eye(2), (len(X), 1))])
    sol, *_ = np.linalg.lstsq(A, a.ravel(), rcond=None)
    if np.allclose(A @ sol, a.ravel(), atol=1e-6) and not np.isclose(sol[0], 1.0, rtol=1e-6):
        return float(sol[0])
    return None


def _same_up_to_scale(a, b) -> bool:
    a, b = np.ravel(a), np.ravel(b)
    k = (a @ b) / (b @ b) if b @ b > 0 else 0.0
    return bool(k != 0 and np.allclose(a, k * b, atol=1e-6 * np.abs(a).max()))


def _as_camera(top):
    return np.vstack([top, [0.0, 0.0, 0.0, 1.0]])


def _estimate_with_ones(X, uv):
    """A right answer in another form: one lstsq with a column of ones, no centring."""
    return _as_camera(np.linalg.lstsq(np.c_[X, np.ones(len(X))], uv, rcond=None)[0].T)


def _estimate_ones_reshaped(X, uv):
    return _as_camera(np.linalg.lstsq(np.c_[X, np.ones(len(X))], uv, rcond=None)[0].reshape(2, 4))


def _estimate_ones_first(X, uv):
    return _as_camera(np.linalg.lstsq(np.c_[np.ones(len(X)), X], uv, rcond=None)[0].T)


def _estimate_centred_pixels_only(X, uv):
    um = uv.mean(axis=0)
    M2 = np.linalg.lstsq(X, uv - um, rcond=None)[0].T
    return _as_camera(np.c_[M2, um - M2 @ X.mean(axis=0)])


def _estimate_centred_points_only(X, uv):
    """lstsq(np.c_[X - mean(X), ones], uv): M2 right, t2 = mean(uv), the translation for centred points."""
    A = np.linalg.lstsq(np.c_[X - X.mean(axis=0), np.ones(len(X))], uv, rcond=None)[0].T
    return _as_camera(A)


def _estimate_solve(X, uv):
    A = np.c_[X, np.ones(len(X))]
    return _as_camera(np.linalg.solve(A, uv).T)


def _estimate_reshaped(X, uv):
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    M2 = np.linalg.lstsq(X - Xm, uv - um, rcond=None)[0].reshape(2, 3)
    return _as_camera(np.c_[M2, um - M2 @ Xm])


def _estimate_uncentred(X, uv):
    M2 = np.linalg.lstsq(X, uv, rcond=None)[0].T
    return _as_camera(np.c_[M2, uv.mean(axis=0) - M2 @ X.mean(axis=0)])


def _estimate_no_translation(X, uv):
    return _as_camera(np.c_[af.estimate_affine_camera(X, uv)[:2, :3], np.zeros(2)])


def _estimate_dlt_last_row_forced(X, uv):
    P = cm.estimate_projection_matrix(X, uv)
    P[2] = [0.0, 0.0, 0.0, 1.0]
    return P


def _estimate_t2_sign(X, uv):
    P = af.estimate_affine_camera(X, uv)
    P[:2, 3] = uv.mean(axis=0) + P[:2, :3] @ X.mean(axis=0)
    return P


def _estimate_shifted(shift):
    return lambda X, uv: (
        af.estimate_affine_camera(X, uv) + np.c_[np.zeros((3, 3)), [shift, shift, 0.0]]
    )


def _estimate_normalised(how):
    """H&Z algorithm 7.2 with similarity normalisation, undone ``how``: "right", "wrong order" (T_uv @ P_n @
    inv(T_X)), "not undone", "pixels only" (inv(T_uv) @ P_n), or "std" (the wrong order, with 1/std scales)."""

    def fit(X, uv):
        if how == "std":
            T_x, T_u = _similarity(X, 1.0 / X.std()), _similarity(uv, 1.0 / uv.std())
        else:
            T_x = _similarity(X, np.sqrt(3.0) / np.linalg.norm(X - X.mean(axis=0), axis=1).mean())
            T_u = _similarity(
                uv, np.sqrt(2.0) / np.linalg.norm(uv - uv.mean(axis=0), axis=1).mean()
            )
        Xn = X @ T_x[:3, :3].T + T_x[:3, 3]
        un = uv @ T_u[:2, :2].T + T_u[:2, 2]
        P_n = _as_camera(np.linalg.lstsq(np.c_[Xn, np.ones(len(X))], un, rcond=None)[0].T)
        return {
            "right": np.linalg.inv(T_u) @ P_n @ T_x,
            "not undone": P_n,
            "pixels only": np.linalg.inv(T_u) @ P_n,
            "wrong order": T_u @ P_n @ np.linalg.inv(T_x),
            "std": T_u @ P_n @ np.linalg.inv(T_x),
        }[how]

    return fit


def _estimate_rows_mismatched(interleaved_rows):
    """The 2N x 8 system with its rows interleaved and its right-hand side stacked, or the other way round."""

    def fit(X, uv):
        n = len(X)
        A = np.zeros((2 * n, 8))
        if interleaved_rows:
            A[0::2, :3], A[0::2, 3], A[1::2, 4:7], A[1::2, 7] = X, 1.0, X, 1.0
            b = uv.T.ravel()
        else:
            A[:n, :3], A[:n, 3], A[n:, 4:7], A[n:, 7] = X, 1.0, X, 1.0
            b = uv.ravel()
        return _as_camera(np.linalg.lstsq(A, b, rcond=None)[0].reshape(2, 4))

    return fit


def _estimate_null_vector_unscaled(X, uv):
    """The homogeneous system solved by SVD, its null vector used without dividing by its 9th entry."""
    n = len(X)
    A = np.zeros((2 * n, 9))
    A[0::2, :3], A[0::2, 3], A[0::2, 8] = X, 1.0, -uv[:, 0]
    A[1::2, 4:7], A[1::2, 7], A[1::2, 8] = X, 1.0, -uv[:, 1]
    h = np.linalg.svd(A)[2][-1]
    return _as_camera(h[:8].reshape(2, 4))


def _estimate_scaling_not_undone(X, uv):
    um, s = uv.mean(axis=0), uv.std()
    return af.estimate_affine_camera(X, (uv - um) / s)


def _estimate_points_on_pixels(X, uv):
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    M2 = np.linalg.lstsq(uv - um, X - Xm, rcond=None)[0]
    return _as_camera(np.c_[M2, um - M2 @ Xm])


def _estimate_rank_two(X, uv):
    P = af.estimate_affine_camera(X, uv)
    P[1, :3] = P[0, :3]  # the same row fitted twice
    return P


def _estimate_centred_in_place(X, uv):
    """Right numbers, but centres the caller's arrays in place (X -= ..., uv -= ...)."""
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    X -= Xm
    uv -= um
    M2 = np.linalg.lstsq(X, uv, rcond=None)[0].T
    return _as_camera(np.c_[M2, um - M2 @ Xm])


def _estimate_mean_axis_1(X, uv):
    Xm, um = X.mean(axis=1, keepdims=True), uv.mean(axis=1, keepdims=True)
    M2 = np.linalg.lstsq(X - Xm, uv - um, rcond=None)[0].T
    return _as_camera(np.c_[M2, uv.mean(axis=0) - M2 @ X.mean(axis=0)])


def _estimate_mean_axis_1_points_only(X, uv):
    """Only the world points centred with axis=1 (keepdims), the pixels right."""
    um = uv.mean(axis=0)
    M2 = np.linalg.lstsq(X - X.mean(axis=1, keepdims=True), uv - um, rcond=None)[0].T
    return _as_camera(np.c_[M2, um - M2 @ X.mean(axis=0)])


def _estimate_mean_axis_1_no_keepdims(X, uv):
    """X - X.mean(axis=1): an (N, 3) minus an (N,) raises a broadcasting ValueError."""
    M2 = np.linalg.lstsq(X - X.mean(axis=1), uv - uv.mean(axis=0), rcond=None)[0].T
    return _as_camera(np.c_[M2, uv.mean(axis=0) - M2 @ X.mean(axis=0)])


def _estimate_mean_of_everything(X, uv):
    Xm, um = X.mean(), uv.mean()
    M2 = np.linalg.lstsq(X - Xm, uv - um, rcond=None)[0].T
    return _as_camera(np.c_[M2, um - M2 @ np.full(3, Xm)])


def _estimate_scaled_orthographic(X, uv):
    """M2 forced to equal-length orthogonal rows (another camera model): the fallback says what differs."""
    P = af.estimate_affine_camera(X, uv)
    U, s, Vt = np.linalg.svd(P[:2, :3], full_matrices=False)
    P[:2, :3] = s.mean() * U @ Vt
    return P


def estimate_affine_camera(X, uv):
    """Least-squares affine camera (H&Z algorithm 7.2): centre both point sets, then solve for M2."""
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    M2 = np.linalg.lstsq(X - Xm, uv - um, rcond=None)[0].T  # (2, 3): uv - um = M2 (X - Xm)
    P = np.zeros((3, 4))
    P[:2, :3], P[:2, 3] = M2, um - M2 @ Xm  # the centroids correspond
    P[2, 3] = 1.0
    return P


register_exercise(
    Exercise(
        name="estimate_affine_camera",
        lesson="05",
        reference=af.estimate_affine_camera,
        cases=_estimate_cases,
        compare=same_array(rtol=1e-7, atol=1e-7),
        diagnose=_estimate_diagnosis,
        exception_hint=_estimate_exception_hint,
        ndarray_only=True,
        wrong_variants=(
            (lambda X, uv: af.estimate_affine_camera(X[:4], uv[:4]), "passes exactly through 4"),
            (lambda X, uv: cm.estimate_projection_matrix(X, uv), "last row of an affine camera"),
            (_estimate_reshaped, "transpose it"),
            (_estimate_ones_reshaped, "do not reshape it to (2, 4)"),
            (_estimate_ones_first, "your first column holds t2"),
            (
                lambda X, uv: _as_camera(
                    np.linalg.lstsq(np.c_[np.ones(len(X)), X], uv, rcond=None)[0].reshape(2, 4)
                ),
                "scrambled twice",
            ),
            (_estimate_centred_pixels_only, "centred the pixels but not the world points"),
            (_estimate_centred_points_only, "translation column for the centred points"),
            (_estimate_solve, "over-determined"),
            (lambda X, uv: _as_camera(_algebraic_fit(X, uv)), "algebraic error"),
            (_estimate_uncentred, "centre both point sets"),
            (_estimate_no_translation, "translation column is zero"),
            (_estimate_dlt_last_row_forced, "last row overwritten"),
            (lambda X, uv: af.estimate_affine_camera(X, uv[:, ::-1]), "u and v are swapped"),
            (_estimate_t2_sign, "sign flipped"),
            (_estimate_shifted(0.5), "half a pixel"),
            (_estimate_scaling_not_undone, "not undo it"),
            (_estimate_normalised("wrong order"), "undid it in the wrong order"),
            (_estimate_normalised("not undone"), "did not undo it"),
            (_estimate_normalised("pixels only"), "points' normalisation T_X"),
            (_estimate_normalised("std"), "undid it in the wrong order"),
            (_estimate_null_vector_unscaled, "divide by its 9th entry"),
            (
                _estimate_rows_mismatched(True),
                "interleaved (u1, v1, u2, v2, ...) rows with a stacked",
            ),
            (
                _estimate_rows_mismatched(False),
                "stacked (all u, then all v) rows with an interleaved",
            ),
            (lambda X, uv: af.estimate_affine_camera(X, uv).astype(int), "truncated towards zero"),
            (_estimate_points_on_pixels, "regressed the world points on the pixels"),
            (_estimate_rank_two, "rank < 2"),
            (_estimate_centred_in_place, "changed its input `X`, `uv` in place"),
            (lambda X, uv: af.estimate_affine_camera(1000 * X, uv), "unit slip by 1000"),
            (lambda X, uv: af.estimate_affine_camera(X, 1000 * uv), "unit slip by 1000"),
            (lambda X, uv: af.estimate_affine_camera(X, uv + 1), "off by one pixel"),
            (lambda X, uv: -af.estimate_affine_camera(X, uv), "-1 times the least-squares one"),
            (_estimate_mean_axis_1, "axis=1"),
            (_estimate_mean_of_everything, "no axis"),
            (_estimate_mean_axis_1_points_only, "for X you averaged along axis=1"),
            (_estimate_mean_axis_1_no_keepdims, "a mean along the wrong axis"),
            (lambda X, uv: np.round(af.estimate_affine_camera(X, uv), 2), "rounded to 2 decimals"),
            (
                lambda X, uv: af.estimate_affine_camera(X, uv)[:, [1, 0, 2, 3]],
                "columns of M2 are in the order",
            ),
            (_estimate_scaled_orthographic, "RMS residual is"),
            (lambda X, uv: af.estimate_affine_camera(X, uv).tolist(), "you returned a list"),
        ),
        teaching=estimate_affine_camera,
    )
)
