"""Lesson 05's third exercise.

The least-squares affine camera from noisy correspondences (see the package docstring).
"""

from __future__ import annotations

import numpy as np

from ... import affine as af
from ... import camera as cm
from .._answers import same_array, shape_problem
from .._core import Exercise, first_mistake, register_exercise
from ._estimation_causes import (
    FORMS,
    algebraic_fit,
    estimate_other_cause,
    forms_context,
    nearly_right_cause,
    normalisation_slip,
    translation_cause,
    unscaled_null_vector,
    wrong_mean_cause,
)
from ._estimation_variants import (
    as_camera,
    estimate_centred_in_place,
    estimate_centred_pixels_only,
    estimate_centred_points_only,
    estimate_dlt_last_row_forced,
    estimate_mean_axis_1,
    estimate_mean_axis_1_no_keepdims,
    estimate_mean_axis_1_points_only,
    estimate_mean_of_everything,
    estimate_no_translation,
    estimate_normalised,
    estimate_null_vector_unscaled,
    estimate_ones_first,
    estimate_ones_reshaped,
    estimate_points_on_pixels,
    estimate_rank_two,
    estimate_reshaped,
    estimate_rows_mismatched,
    estimate_scaled_orthographic,
    estimate_scaling_not_undone,
    estimate_shifted,
    estimate_solve,
    estimate_t2_sign,
    estimate_t2_sign_whole,
    estimate_uncentred,
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
    cause = first_mistake(  # strict: the algebraic fit is within 1e-5 of the answer
        FORMS,
        forms_context(X, uv, expected),
        g[:2],
        lambda top, form: np.allclose(top, form, rtol=1e-9, atol=1e-7),
    )
    if cause:
        return cause
    for slip in (unscaled_null_vector(g, X, uv), normalisation_slip(g, expected, X, uv)):
        if slip:
            return slip
    M2, t2 = g[:2, :3], g[:2, 3]
    M2_expected, t2_expected = expected[:2, :3], expected[:2, 3]
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    slip = wrong_mean_cause(M2, X, uv)
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
    near = nearly_right_cause(
        g, expected, X, uv
    )  # before the slips: a near miss is not one of them
    if near:
        return near
    if np.allclose(M2, M2_expected, atol=1e-6):
        return translation_cause(t2, t2_expected, um, M2 @ Xm)
    return estimate_other_cause(g, expected, X, uv)


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


def estimate_affine_camera(X, uv):
    """Least-squares affine camera (H&Z algorithm 7.2): centre both point sets, then solve for M2.

    Parameters
    ----------
    X : (N, 3) ndarray
        World points, N >= 4, not all on one plane.
    uv : (N, 2) ndarray
        Their pixels.

    Returns
    -------
    (3, 4) ndarray
        The affine camera [[M2, um - M2 Xm], [0, 0, 0, 1]]: M2 the least-squares fit of the centred
        pixels to the centred points (Xm, um the centroids, which correspond).

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 7.2.2 (algorithm 7.2).
    """
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
            (estimate_reshaped, "transpose it"),
            (estimate_ones_reshaped, "do not reshape it to (2, 4)"),
            (estimate_ones_first, "your first column holds t2"),
            (
                lambda X, uv: as_camera(
                    np.linalg.lstsq(np.c_[np.ones(len(X)), X], uv, rcond=None)[0].reshape(2, 4)
                ),
                "scrambled twice",
            ),
            (estimate_centred_pixels_only, "centred the pixels but not the world points"),
            (estimate_centred_points_only, "translation column for the centred points"),
            (estimate_solve, "over-determined"),
            (lambda X, uv: as_camera(algebraic_fit(X, uv)), "algebraic error"),
            (estimate_uncentred, "centre both point sets"),
            (estimate_no_translation, "translation column is zero"),
            (estimate_dlt_last_row_forced, "last row overwritten"),
            (lambda X, uv: af.estimate_affine_camera(X, uv[:, ::-1]), "u and v are swapped"),
            (lambda X, uv: af.estimate_affine_camera(X, uv * [1, -1]), "predicts -v instead"),
            (
                lambda X, uv: af.estimate_affine_camera(X, [0, 479] + uv * [1, -1]),
                "predicts 479 - v",
            ),
            (lambda X, uv: af.estimate_affine_camera(X[:-1], uv[:-1]), "the last (X[:-1]"),
            (lambda X, uv: af.estimate_affine_camera(X[1:], uv[1:]), "the first (X[1:]?)"),
            (estimate_t2_sign, "sign flipped"),
            (estimate_t2_sign_whole, "wrong sign as a whole"),
            (lambda X, uv: np.round(af.estimate_affine_camera(X, uv), 4), "rounded to 4 decimals"),
            (
                lambda X, uv: af.estimate_affine_camera(
                    X.astype(np.float32), uv.astype(np.float32)
                ),
                "float32",
            ),
            (estimate_shifted(0.5), "half a pixel"),
            (estimate_scaling_not_undone, "not undo it"),
            (estimate_normalised("wrong order"), "undid it in the wrong order"),
            (estimate_normalised("not undone"), "did not undo it"),
            (estimate_normalised("pixels only"), "points' normalisation T_X"),
            (estimate_normalised("std"), "undid it in the wrong order"),
            (estimate_null_vector_unscaled, "divide by its 9th entry"),
            (
                estimate_rows_mismatched(True),
                "interleaved (u1, v1, u2, v2, ...) rows with a stacked",
            ),
            (
                estimate_rows_mismatched(False),
                "stacked (all u, then all v) rows with an interleaved",
            ),
            (lambda X, uv: af.estimate_affine_camera(X, uv).astype(int), "truncated towards zero"),
            (estimate_points_on_pixels, "regressed the world points on the pixels"),
            (estimate_rank_two, "rank < 2"),
            (estimate_centred_in_place, "changed its inputs `X` and `uv` in place"),
            (lambda X, uv: af.estimate_affine_camera(1000 * X, uv), "unit slip by 1000"),
            (lambda X, uv: af.estimate_affine_camera(X, 1000 * uv), "unit slip by 1000"),
            (lambda X, uv: af.estimate_affine_camera(X, uv + 1), "off by one pixel"),
            (lambda X, uv: -af.estimate_affine_camera(X, uv), "-1 times the least-squares one"),
            (estimate_mean_axis_1, "axis=1"),
            (estimate_mean_of_everything, "no axis"),
            (estimate_mean_axis_1_points_only, "for X you averaged along axis=1"),
            (estimate_mean_axis_1_no_keepdims, "a mean along the wrong axis"),
            (lambda X, uv: np.round(af.estimate_affine_camera(X, uv), 2), "rounded to 2 decimals"),
            (
                lambda X, uv: af.estimate_affine_camera(X, uv)[:, [1, 0, 2, 3]],
                "columns of M2 are in the order",
            ),
            (estimate_scaled_orthographic, "RMS residual is"),
            (lambda X, uv: af.estimate_affine_camera(X, uv).tolist(), "you returned a list"),
        ),
        teaching=estimate_affine_camera,
    )
)
