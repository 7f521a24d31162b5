"""Causes of lesson 05's least-squares affine camera beyond the first checks.

What its diagnosis names after the first checks: a normalisation left in or undone in the wrong
order, a fit of the wrong system (algebraic, unscaled null vector, rearranged lstsq output:
:data:`FORMS`), a wrong mean, a wrong translation, unit slips and rounding; else what differs,
measured.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import affine as af
from ... import camera as cm
from .._core import Mistake, first_mistake

# -- estimate_affine_camera -------------------------------------------------------------------

_LSQ = (
    "centre both point sets, M2^T = lstsq(X - mean(X), uv - mean(uv)), t2 = mean(uv) - M2 @ mean(X)"
)


def _rms(X, P2, uv) -> float:
    """RMS pixel residual of the top rows P2 = [M2 | t2] over the points."""
    return float(np.sqrt(np.mean(np.sum((X @ P2[:, :3].T + P2[:, 3] - uv) ** 2, axis=1))))


def algebraic_fit(X, uv):
    """The homogeneous system [X 1 0 -u; 0 X 1 -v] h = 0 solved by SVD, as for the DLT.

    It has a 9th unknown (the scale) and minimises an algebraic error, not the pixel error.
    """
    h = algebraic_null_vector(X, uv)
    return h[:8].reshape(2, 4) / h[8]


def algebraic_null_vector(X, uv):
    """The unit null vector h of [X, 1, 0, -u; 0, X, 1, -v] h = 0 (9 unknowns: the camera's 8 and a scale)."""
    n = len(X)
    A = np.zeros((2 * n, 9))
    A[0::2, :3], A[0::2, 3], A[0::2, 8] = X, 1.0, -uv[:, 0]
    A[1::2, 4:7], A[1::2, 7], A[1::2, 8] = X, 1.0, -uv[:, 1]
    return np.linalg.svd(A)[2][-1]


def similarity(points, scale):
    """The normalising similarity T = [[s I, -s mean], [0, 1]] of (N, D) points for scale s."""
    D = points.shape[1]
    T = np.eye(D + 1)
    T[:D, :D] *= scale
    T[:D, D] = -scale * points.mean(axis=0)
    return T


def _normalisation_scales(points):
    """Scales s a student may normalise (N, D) points with.

    H&Z's isotropic sqrt(D) / mean distance (and sqrt(2) for 3-D points, copied from the 2-D DLT),
    sqrt(D) / RMS distance, 1 / std.
    """
    D = points.shape[1]
    c = points - points.mean(axis=0)
    dist = np.linalg.norm(c, axis=1)
    return {
        f"sqrt({D}) / mean distance": np.sqrt(D) / dist.mean(),
        "sqrt(2) / mean distance": np.sqrt(2.0) / dist.mean(),
        f"sqrt({D}) / RMS distance": np.sqrt(D) / np.sqrt(np.mean(dist**2)),
        "1 / std": 1.0 / points.std(),
    }


def _power(T, k):
    """T to the integer power k (negative: of inv(T))."""
    return np.linalg.matrix_power(T, k) if k >= 0 else np.linalg.matrix_power(np.linalg.inv(T), -k)


def _undone(a, b):
    """The answer T_uv^a P T_X^b of a normalised fit undone some way, in terms of the least-squares P."""
    return lambda s: _power(s.T_u, a) @ s.expected @ _power(s.T_x, b)


_RIGHT_UNDO = "P = inv(T_uv) @ P_n @ T_X"

# How a normalised fit P_n = T_uv P inv(T_X) may be mapped back, named as the student wrote it, and the result
# as T_uv^a P T_X^b in terms of the least-squares camera P (the right way, inv(T_uv) @ P_n @ T_X: a = b = 0).
_UNDO = (
    Mistake(
        "T_uv @ P_n @ inv(T_X)",
        _undone(2, -2),
        lambda s: (
            f"you normalised the points {s.both} and undid it in the wrong order: T_uv @ P_n @ inv(T_X) "
            f"applies the normalisation a second time. The fit P_n = T_uv P inv(T_X) maps normalised points to "
            f"normalised pixels, so {_RIGHT_UNDO}."
        ),
    ),
    Mistake(
        "P_n",
        _undone(1, -1),
        lambda s: (
            f"you normalised the points {s.both} and did not undo it: your camera maps normalised "
            f"points to normalised pixels. Map it back: {_RIGHT_UNDO}."
        ),
    ),
    Mistake(
        "inv(T_uv) @ P_n",
        _undone(0, -1),
        lambda s: (
            f"the points' normalisation T_X (scaling by {s.name_x}) is still in your "
            f"camera: you did not undo it (or undid only T_uv); {_RIGHT_UNDO}."
        ),
    ),
    Mistake(
        "P_n @ T_X",
        _undone(1, 0),
        lambda s: (
            f"the pixels' normalisation T_uv (scaling by {s.name_u}) is still in your camera: "
            f"you did not undo it (or undid only T_X); {_RIGHT_UNDO}."
        ),
    ),
    Mistake(
        "inv(T_uv) @ P_n @ inv(T_X)",
        _undone(0, -2),
        lambda s: (
            f"you normalised the points {s.both} and undid it as inv(T_uv) @ P_n @ inv(T_X): "
            f"that undoes T_uv but applies T_X a second time; {_RIGHT_UNDO}."
        ),
    ),
    Mistake(
        "T_uv @ P_n @ T_X",
        _undone(2, 0),
        lambda s: (
            f"you normalised the points {s.both} and undid it as T_uv @ P_n @ T_X: that undoes "
            f"T_X but applies T_uv a second time; {_RIGHT_UNDO}."
        ),
    ),
)


def _same_camera(got, candidate) -> bool:
    return np.allclose(got, candidate, rtol=1e-6, atol=1e-9 * np.abs(candidate).max())


def normalisation_slip(g, expected, X, uv) -> str | None:
    """The cause when ``g`` keeps a similarity normalisation.

    ``g`` is the least-squares camera with a similarity normalisation (of a kind in
    :func:`_normalisation_scales`) left in it, or undone in the wrong order.
    """
    for name_x, s_x in _normalisation_scales(X).items():
        for name_u, s_u in _normalisation_scales(uv).items():
            context = SimpleNamespace(
                expected=expected,
                T_x=similarity(X, s_x),
                T_u=similarity(uv, s_u),
                name_x=name_x,
                name_u=name_u,
                both=f"(T_X scaling by {name_x}, T_uv by {name_u})",
            )
            hint = first_mistake(_UNDO, context, g, _same_camera)
            if hint:
                return hint
    return None


def unscaled_null_vector(g, X, uv) -> str | None:
    """The cause when g's top rows are the homogeneous system's null vector h[:8] not divided by h[8]."""
    A = algebraic_fit(X, uv)
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


def forms_context(X, uv, expected):
    """What the rows of :data:`FORMS` read: the points, the pixels, the answer and the fit on centred pixels."""
    return SimpleNamespace(
        X=X,
        uv=uv,
        Xm=X.mean(axis=0),
        um=uv.mean(axis=0),
        M2=expected[:2, :3],
        t2=expected[:2, 3],
        expected=expected,
        centred_pixels_only=np.linalg.lstsq(X, uv - uv.mean(axis=0), rcond=None)[0].T,
    )


def design_matrix(X, interleaved):
    """The 2N x 8 system of the affine camera: rows per point interleaved (u1, v1, ...) or stacked (all u)."""
    n = len(X)
    A = np.zeros((2 * n, 8))
    if interleaved:
        A[0::2, :3], A[0::2, 3], A[1::2, 4:7], A[1::2, 7] = X, 1.0, X, 1.0
    else:
        A[:n, :3], A[:n, 3], A[n:, 4:7], A[n:, 7] = X, 1.0, X, 1.0
    return A


_ORDER = (
    "the rows of your design matrix and of its right-hand side are in different orders: {a} rows "
    "with {b} right-hand side. Build both the same way: interleaved rows (u1, v1, u2, v2, ...) go with "
    "uv.ravel(), stacked rows (all u, then all v) with np.r_[uv[:, 0], uv[:, 1]] (uv.T.ravel())."
)

FORMS = (
    Mistake(
        "interleaved rows, stacked right-hand side",
        lambda s: np.linalg.lstsq(design_matrix(s.X, True), s.uv.T.ravel(), rcond=None)[0].reshape(
            2, 4
        ),
        _ORDER.format(a="interleaved (u1, v1, u2, v2, ...)", b="a stacked (all u, then all v)"),
    ),
    Mistake(
        "stacked rows, interleaved right-hand side",
        lambda s: np.linalg.lstsq(design_matrix(s.X, False), s.uv.ravel(), rcond=None)[0].reshape(
            2, 4
        ),
        _ORDER.format(a="stacked (all u, then all v)", b="an interleaved (u1, v1, u2, v2, ...)"),
    ),
    Mistake(
        "lstsq with ones, reshaped",
        lambda s: s.expected[:2].T.reshape(
            2, 4
        ),  # lstsq(np.c_[X, ones], uv)[0]: (4, 2), rows M2^T then t2
        "P's top rows are scrambled: lstsq with a column of ones returns the (4, 2) "
        "matrix [M2 | t2]^T; transpose it (.T), do not reshape it to (2, 4).",
    ),
    Mistake(
        "ones first",
        lambda s: np.c_[s.t2, s.M2],
        "your first column holds t2: with the column of ones first, np.c_[ones, X], lstsq's first "
        "row is the translation; put the ones last (np.c_[X, ones]), or move that row: "
        "P[:2] = np.c_[A[1:].T, A[0]].",
    ),
    Mistake(
        "ones first, reshaped",
        lambda s: np.vstack([s.t2, s.M2.T]).reshape(2, 4),
        "P's top rows are scrambled twice: with the column of ones first, lstsq's first "
        "row is t2, and its (4, 2) result needs a transpose (.T), not a reshape.",
    ),
    Mistake(
        "pixels centred, points not",
        lambda s: np.c_[s.centred_pixels_only, s.um - s.centred_pixels_only @ s.Xm],
        "you centred the pixels but not the world points: with no constant term, regressing uv - mean(uv) on the "
        "raw X makes M2 absorb X's mean; centre X too (X - mean(X)), or append a column of ones to X.",
    ),
    Mistake(
        "pixels centred, points not, t2 = 0",
        lambda s: np.c_[s.centred_pixels_only, np.zeros(2)],
        "you centred the pixels but not the world points, and left t2 at 0: centre X too, then "
        "t2 = mean(uv) - M2 @ mean(X).",
    ),
    Mistake(
        "pixels centred, points not, t2 = mean(uv)",
        lambda s: np.c_[s.centred_pixels_only, s.um],
        "you centred the pixels but not the world points: centre X too (X - mean(X)); then "
        "t2 = mean(uv) - M2 @ mean(X).",
    ),
    Mistake(
        "algebraic error",
        lambda s: algebraic_fit(s.X, s.uv),
        "you minimised an algebraic error: the homogeneous system [X, 1, 0, -u; 0, X, 1, -v] h = 0 with the scale "
        "as a 9th unknown, solved by SVD as for the DLT, is close to the least-squares camera but not it. An "
        "affine camera's pixels are linear in its 8 entries, so solve the inhomogeneous system [X, 1] m = u by "
        "least squares (np.linalg.lstsq) for the pixel error itself.",
    ),
)
"""Answers that are the least-squares numbers rearranged, or from a wrong fit, as the top rows they give."""


def estimate_other_cause(g, expected, X, uv) -> str:
    """The named causes of a wrong least-squares affine camera, else what differs.

    A flipped v, a point left out, unit slips, a lost normalisation, a DLT, an exact fit to a few
    points, rounding.
    """
    slip = _v_flip_cause(g, expected) or _point_left_out(g, X, uv)
    if slip:
        return slip
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
    rounded = rounded_cause(g, expected)
    if rounded:
        return rounded
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


def rounded_cause(g, expected) -> str | None:
    """The cause when every entry is the least-squares one rounded to 0 to 8 decimals."""
    for decimals in range(9):
        if np.allclose(g, np.round(expected, decimals), rtol=0, atol=1e-9):
            step = "whole numbers" if decimals == 0 else f"{decimals} decimals"
            return (
                f"your entries are the least-squares ones rounded to {step}; return them unrounded: rounding "
                f"an entry of M2 by up to {0.5 * 10.0**-decimals:g} moves the image of a point 1 m from the "
                f"centroid by as many pixels."
            )
    return None


def nearly_right_cause(g, expected, X, uv) -> str | None:
    """The cause when the answer is the least-squares camera to within its digits.

    Rounded entries, or points cast to float32 (about 7 significant digits), leave every entry within
    1e-4 px (plus 1e-6 relative) of the answer; a different solver (total least squares, a stopped
    iteration) misses by far more, so it is not named here. No slip of the steps is named.
    """
    rounded = rounded_cause(g, expected)
    if rounded:
        return rounded
    if not np.allclose(g, expected, rtol=1e-6, atol=1e-4):
        return None
    gap = float(np.abs(g - expected).max())
    more = _rms(X, g[:2], uv) - _rms(X, expected[:2], uv)
    return (
        f"every entry is within {gap:.1g} of the least-squares camera (your RMS residual is {more:.1g} px "
        f"above the minimum), so your steps are right and only the digits differ, which the check's 1e-7 "
        f"does not allow: were numbers rounded or typed in from a printout, or X and uv cast to float32 "
        f"(about 7 significant digits)? Fit the float64 arrays as given and return the result unrounded."
    )


def _v_flip_cause(g, expected) -> str | None:
    """The cause when row 1 (u) is the least-squares one and row 2 predicts c - v.

    The fit to -v (y up) or to c - v (rows counted from the bottom of the image).
    """
    if not (
        np.allclose(g[0], expected[0], rtol=1e-9, atol=1e-7)
        and np.allclose(g[1, :3], -expected[1, :3], rtol=1e-9, atol=1e-7)
    ):
        return None
    c = float(g[1, 3] + expected[1, 3])
    how = "-v" if abs(c) < 1e-6 else f"{c:.4g} - v"
    return (
        f"the first row (u) is the least-squares one, but the second predicts {how} instead of v: the v axis "
        f"is flipped. uv[:, 1] is v as given, the row index, growing downwards (docs/conventions.md); fit it as "
        f"it is, without negating it or counting rows from the bottom of the image."
    )


def _point_left_out(g, X, uv) -> str | None:
    """The cause when ``g`` is the least-squares camera of all the points but one (an off-by-one slice)."""
    n = len(X)
    for i in (n - 1, 0, *range(1, n - 1)):  # X[:-1] and X[1:] first, the likely slices
        keep = np.arange(n) != i
        if np.allclose(g, af.estimate_affine_camera(X[keep], uv[keep]), rtol=1e-9, atol=1e-7):
            which = {0: "the first (X[1:]?)", n - 1: "the last (X[:-1] or range(N - 1)?)"}.get(
                i, f"point {i}"
            )
            return (
                f"your camera is the least-squares fit to {n - 1} of the {n} points: {which} was left out, an "
                f"off-by-one in a slice or a loop. Use all N points: {_LSQ}."
            )
    return None


def translation_cause(t2, t2_expected, um, M2Xm) -> str:
    """Why t2 is wrong when M2 is right."""
    if np.allclose(t2, um + M2Xm, atol=1e-6):
        return (
            "t2 has a sign flipped on its M2 @ mean(X) term: the centroids correspond, mean(uv) = M2 @ mean(X) + t2, "
            "so t2 = mean(uv) - M2 @ mean(X)."
        )
    if np.allclose(t2, -t2_expected, atol=1e-6):
        return (
            "t2 has the wrong sign as a whole: you computed M2 @ mean(X) - mean(uv). The centroids correspond, "
            "mean(uv) = M2 @ mean(X) + t2, so t2 = mean(uv) - M2 @ mean(X)."
        )
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


def wrong_mean_cause(M2, X, uv) -> str | None:
    """The cause when M2 is the fit after centring X or uv (or both) with a wrong mean.

    Along axis=1 (each point's own coordinates) or over every entry (no axis).
    """
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
