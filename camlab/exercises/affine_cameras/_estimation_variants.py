"""Lesson 05's least-squares affine camera done wrong, as a student would.

The wrong variants the test suite feeds the check (each must be named by its diagnosis), and one
right answer in another form.
"""

from __future__ import annotations

import numpy as np

from ... import affine as af
from ... import camera as cm
from ._estimation_causes import algebraic_null_vector, design_matrix, similarity


def as_camera(top):
    return np.vstack([top, [0.0, 0.0, 0.0, 1.0]])


def _estimate_with_ones(X, uv):
    """A right answer in another form: one lstsq with a column of ones, no centring."""
    return as_camera(np.linalg.lstsq(np.c_[X, np.ones(len(X))], uv, rcond=None)[0].T)


def estimate_ones_reshaped(X, uv):
    return as_camera(np.linalg.lstsq(np.c_[X, np.ones(len(X))], uv, rcond=None)[0].reshape(2, 4))


def estimate_ones_first(X, uv):
    return as_camera(np.linalg.lstsq(np.c_[np.ones(len(X)), X], uv, rcond=None)[0].T)


def estimate_centred_pixels_only(X, uv):
    um = uv.mean(axis=0)
    M2 = np.linalg.lstsq(X, uv - um, rcond=None)[0].T
    return as_camera(np.c_[M2, um - M2 @ X.mean(axis=0)])


def estimate_centred_points_only(X, uv):
    """lstsq(np.c_[X - mean(X), ones], uv): M2 right, t2 = mean(uv), the translation for centred points."""
    A = np.linalg.lstsq(np.c_[X - X.mean(axis=0), np.ones(len(X))], uv, rcond=None)[0].T
    return as_camera(A)


def estimate_solve(X, uv):
    A = np.c_[X, np.ones(len(X))]
    return as_camera(np.linalg.solve(A, uv).T)


def estimate_reshaped(X, uv):
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    M2 = np.linalg.lstsq(X - Xm, uv - um, rcond=None)[0].reshape(2, 3)
    return as_camera(np.c_[M2, um - M2 @ Xm])


def estimate_uncentred(X, uv):
    M2 = np.linalg.lstsq(X, uv, rcond=None)[0].T
    return as_camera(np.c_[M2, uv.mean(axis=0) - M2 @ X.mean(axis=0)])


def estimate_no_translation(X, uv):
    return as_camera(np.c_[af.estimate_affine_camera(X, uv)[:2, :3], np.zeros(2)])


def estimate_dlt_last_row_forced(X, uv):
    P = cm.estimate_projection_matrix(X, uv)
    P[2] = [0.0, 0.0, 0.0, 1.0]
    return P


def estimate_t2_sign(X, uv):
    P = af.estimate_affine_camera(X, uv)
    P[:2, 3] = uv.mean(axis=0) + P[:2, :3] @ X.mean(axis=0)
    return P


def estimate_t2_sign_whole(X, uv):
    P = af.estimate_affine_camera(X, uv)
    P[:2, 3] = P[:2, :3] @ X.mean(axis=0) - uv.mean(axis=0)
    return P


def estimate_shifted(shift):
    return lambda X, uv: (
        af.estimate_affine_camera(X, uv) + np.c_[np.zeros((3, 3)), [shift, shift, 0.0]]
    )


def estimate_normalised(how):
    """H&Z algorithm 7.2 with similarity normalisation, undone ``how``.

    "right", "wrong order" (T_uv @ P_n @ inv(T_X)), "not undone", "pixels only" (inv(T_uv) @ P_n),
    or "std" (the wrong order, with 1/std scales).
    """

    def fit(X, uv):
        if how == "std":
            T_x, T_u = similarity(X, 1.0 / X.std()), similarity(uv, 1.0 / uv.std())
        else:
            T_x = similarity(X, np.sqrt(3.0) / np.linalg.norm(X - X.mean(axis=0), axis=1).mean())
            T_u = similarity(uv, np.sqrt(2.0) / np.linalg.norm(uv - uv.mean(axis=0), axis=1).mean())
        Xn = X @ T_x[:3, :3].T + T_x[:3, 3]
        un = uv @ T_u[:2, :2].T + T_u[:2, 2]
        P_n = as_camera(np.linalg.lstsq(np.c_[Xn, np.ones(len(X))], un, rcond=None)[0].T)
        return {
            "right": np.linalg.inv(T_u) @ P_n @ T_x,
            "not undone": P_n,
            "pixels only": np.linalg.inv(T_u) @ P_n,
            "wrong order": T_u @ P_n @ np.linalg.inv(T_x),
            "std": T_u @ P_n @ np.linalg.inv(T_x),
        }[how]

    return fit


def estimate_rows_mismatched(interleaved_rows):
    """The 2N x 8 system with its rows interleaved and its right-hand side stacked, or the other way round."""

    def fit(X, uv):
        b = uv.T.ravel() if interleaved_rows else uv.ravel()
        A = design_matrix(X, interleaved_rows)
        return as_camera(np.linalg.lstsq(A, b, rcond=None)[0].reshape(2, 4))

    return fit


def estimate_null_vector_unscaled(X, uv):
    """The homogeneous system solved by SVD, its null vector used without dividing by its 9th entry."""
    return as_camera(algebraic_null_vector(X, uv)[:8].reshape(2, 4))


def estimate_scaling_not_undone(X, uv):
    um, s = uv.mean(axis=0), uv.std()
    return af.estimate_affine_camera(X, (uv - um) / s)


def estimate_points_on_pixels(X, uv):
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    M2 = np.linalg.lstsq(uv - um, X - Xm, rcond=None)[0]
    return as_camera(np.c_[M2, um - M2 @ Xm])


def estimate_rank_two(X, uv):
    P = af.estimate_affine_camera(X, uv)
    P[1, :3] = P[0, :3]  # the same row fitted twice
    return P


def estimate_centred_in_place(X, uv):
    """Right numbers, but centres the caller's arrays in place (X -= ..., uv -= ...)."""
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    X -= Xm
    uv -= um
    M2 = np.linalg.lstsq(X, uv, rcond=None)[0].T
    return as_camera(np.c_[M2, um - M2 @ Xm])


def estimate_mean_axis_1(X, uv):
    Xm, um = X.mean(axis=1, keepdims=True), uv.mean(axis=1, keepdims=True)
    M2 = np.linalg.lstsq(X - Xm, uv - um, rcond=None)[0].T
    return as_camera(np.c_[M2, uv.mean(axis=0) - M2 @ X.mean(axis=0)])


def estimate_mean_axis_1_points_only(X, uv):
    """Only the world points centred with axis=1 (keepdims), the pixels right."""
    um = uv.mean(axis=0)
    M2 = np.linalg.lstsq(X - X.mean(axis=1, keepdims=True), uv - um, rcond=None)[0].T
    return as_camera(np.c_[M2, um - M2 @ X.mean(axis=0)])


def estimate_mean_axis_1_no_keepdims(X, uv):
    """X - X.mean(axis=1): an (N, 3) minus an (N,) raises a broadcasting ValueError."""
    M2 = np.linalg.lstsq(X - X.mean(axis=1), uv - uv.mean(axis=0), rcond=None)[0].T
    return as_camera(np.c_[M2, uv.mean(axis=0) - M2 @ X.mean(axis=0)])


def estimate_mean_of_everything(X, uv):
    Xm, um = X.mean(), uv.mean()
    M2 = np.linalg.lstsq(X - Xm, uv - um, rcond=None)[0].T
    return as_camera(np.c_[M2, um - M2 @ np.full(3, Xm)])


def estimate_scaled_orthographic(X, uv):
    """M2 forced to equal-length orthogonal rows (another camera model): the fallback says what differs."""
    P = af.estimate_affine_camera(X, uv)
    U, s, Vt = np.linalg.svd(P[:2, :3], full_matrices=False)
    P[:2, :3] = s.mean() * U @ Vt
    return P
