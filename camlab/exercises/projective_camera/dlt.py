"""Lesson 04's exercise estimate_projection_matrix: the normalised DLT [1]_.

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 7.1 and algorithm 7.1
   (the normalised DLT for P).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import camera as cm
from .._answers import same_up_to_scale, shape_problem
from .._core import Exercise, Mistake, first_mistake, register_exercise
from ._dlt_forms import (
    dlt_half,
    dlt_mismatched,
    dlt_not_undone,
    dlt_p34,
    dlt_partial,
    dlt_rows,
    dlt_slipped,
    dlt_u_not_a_column,
    dlt_undone_wrong_order,
    dlt_unnormalised,
    in_frame,
    normalisers,
    rms_normalisers,
)
from ._dlt_survey import dlt_cases, dlt_follow_up, pixel_gap, pixels_of


def _wrong_way_round(how, undo):
    return Mistake(
        how,
        undo,
        f"you undid the normalisation the wrong way round ({how}). P_hat maps U X to T u: "
        f"T u ~ P_hat U X, so u ~ inv(T) P_hat U X and P = inv(T) @ P_hat @ U.",
    )


_UNDO_MISTAKES = (
    Mistake(
        "not undone",
        lambda s: s.P_hat,
        "you returned P_hat, the camera of the normalised points: the normalisation is not undone. "
        "P_hat maps U X to T u, so P = inv(T) @ P_hat @ U.",
    ),
    _wrong_way_round("T @ P_hat @ inv(U)", lambda s: s.T @ s.P_hat @ np.linalg.inv(s.U)),
    _wrong_way_round(
        "inv(T) @ P_hat @ inv(U)", lambda s: np.linalg.inv(s.T) @ s.P_hat @ np.linalg.inv(s.U)
    ),
    _wrong_way_round("T @ P_hat @ U", lambda s: s.T @ s.P_hat @ s.U),
    Mistake(
        "pixels' normalisation only undone",
        lambda s: np.linalg.inv(s.T) @ s.P_hat,
        "you undid only the pixels' normalisation (inv(T) @ P_hat): P_hat still expects normalised "
        "world points U X. Undo both: P = inv(T) @ P_hat @ U.",
    ),
    Mistake(
        "world points' normalisation only undone",
        lambda s: s.P_hat @ s.U,
        "you undid only the world points' normalisation (P_hat @ U): the result still gives "
        "normalised pixels T u. Undo both: P = inv(T) @ P_hat @ U.",
    ),
)
"""A normalised DLT's fit P_hat = T P inv(U) mapped back wrongly, in the order the diagnosis tests them."""


def _pixels_only_scaled(T):
    return np.diag([T[0, 0], T[1, 1], 1.0])


def _pixels_only_centred(T):
    return np.block([[np.eye(2), T[:2, 2:] / T[0, 0]], [np.zeros((1, 2)), np.ones((1, 1))]])


def _world_only_scaled(U):
    return np.diag([U[0, 0], U[1, 1], U[2, 2], 1.0])


def _world_only_centred(U):
    return np.block([[np.eye(3), U[:3, 3:] / U[0, 0]], [np.zeros((1, 3)), np.ones((1, 1))]])


def _mismatch(side, did, build):
    """A side normalised by part of its normaliser but undone with the full one: inv(T) T' P or P inv(U') U."""
    undone = "inv(T)" if side == "pixels" else "U"
    return Mistake(
        f"{side}: {did}, undone with the full {undone}",
        build,
        f"you {did}, then undid the full normaliser ({undone}): the normalisation you applied and the one you "
        f"undid differ. P = inv(T) @ P_hat @ U holds only for the very T and U applied to the points: build "
        f"each normaliser once, as a matrix, apply it ({'T u' if side == 'pixels' else 'U X'}) and undo that "
        f"same matrix.",
    )


_MISMATCH_MISTAKES = (
    _mismatch(
        "pixels",
        "scaled the pixels but did not centre them",
        lambda s: np.linalg.inv(s.T) @ _pixels_only_scaled(s.T) @ s.P,
    ),
    _mismatch(
        "pixels",
        "centred the pixels but did not scale them",
        lambda s: np.linalg.inv(s.T) @ _pixels_only_centred(s.T) @ s.P,
    ),
    _mismatch("pixels", "left the pixels unnormalised", lambda s: np.linalg.inv(s.T) @ s.P),
    _mismatch(
        "world points",
        "scaled the world points but did not centre them",
        lambda s: s.P @ np.linalg.inv(_world_only_scaled(s.U)) @ s.U,
    ),
    _mismatch(
        "world points",
        "centred the world points but did not scale them",
        lambda s: s.P @ np.linalg.inv(_world_only_centred(s.U)) @ s.U,
    ),
    _mismatch("world points", "left the world points unnormalised", lambda s: s.P @ s.U),
)
"""One side normalised with one matrix and undone with another: on exact pixels the answer is T-side
inv(T) T' P or world-side P inv(U') U, with P the true camera."""


def _same_camera(got, wrong) -> bool:
    return same_up_to_scale(got, wrong, rtol=1e-5)


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
        normalisers(X, uv),
        rms_normalisers(X, uv),
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
        context = SimpleNamespace(U=U, T=T, P_hat=T @ expected @ np.linalg.inv(U), P=expected)
        cause = first_mistake(_UNDO_MISTAKES + _MISMATCH_MISTAKES, context, g, _same_camera)
        if cause:
            return cause
    pixels = pixels_of(g, X)
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
    if np.allclose(pixels, uv[:, ::-1], atol=1e-4 * max(1.0, np.abs(uv).max())):
        return (
            "your P images every point at (v, u): u and v are swapped in A. The first row of each point holds u "
            "= uv[:, 0] (the column), (X^T, 0, -u X^T), the second v = uv[:, 1] (the row), (0, X^T, -v X^T)."
        )
    if _is_vt_column(g, X, uv):
        return (
            "you took a column of Vt. np.linalg.svd returns Vt, V transposed: the right singular vectors "
            "are its rows, so the null vector is the last row, Vt[-1], not Vt[:, -1]."
        )
    gap = pixel_gap(g, expected, X)
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
    for U, T in (normalisers(X, uv), rms_normalisers(X, uv), (np.eye(4), np.eye(3))):
        column = np.abs(np.linalg.svd(dlt_rows(in_frame(U, X), in_frame(T, uv)))[2][:, -1])
        P_hat = np.abs(T @ got @ np.linalg.inv(U)).ravel()
        if np.abs(P_hat).max() > 0 and np.allclose(
            P_hat / np.abs(P_hat).max(), column / column.max(), atol=1e-6
        ):
            return True
    return False


def _dlt_exception_hint(exc, args) -> str:
    """The cause of a broadcasting error while stacking A: u (N,) times the (N, 4) rows X_h, u not a column."""
    message = str(exc)
    n = len(np.asarray(args[0]))
    if isinstance(exc, ValueError) and "broadcast" in message:
        for k in (3, 4):
            if f"({n},) ({n},{k})" in message or f"({n},{k}) ({n},)" in message:
                return (
                    f"a broadcasting slip while building A: u = uv[:, 0] has shape ({n},) and X_h ({n}, {k}); "
                    f"broadcasting lines the {n} u's up with X_h's {k} columns, not with its {n} rows. Keep u a "
                    f"column, one u per point (row): uv[:, :1] * X_h or uv[:, 0, None] * X_h (and the same for v)."
                )
    return ""


def estimate_projection_matrix(X, uv):
    """The normalised DLT: normalise, two rows of u x P X = 0 per point, SVD, undo.

    Parameters
    ----------
    X : (N, 3) array_like
        World points, N >= 6, not all on one plane.
    uv : (N, 2) array_like
        Their pixels.

    Returns
    -------
    (3, 4) ndarray
        P up to scale, with uv ~ P (X, 1): T^-1 P_hat U, where U and T move each point set's centroid to
        0 and its mean distance to sqrt(3) (world) and sqrt(2) (pixels).

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 7.1 and algorithm 7.1.
    """
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
    # the right singular vector of the smallest singular value
    P_hat = np.linalg.svd(np.array(rows))[2][-1].reshape(3, 4)
    return np.linalg.inv(T) @ P_hat @ U  # T u ~ P_hat U X, so u ~ T^-1 P_hat U X


register_exercise(
    Exercise(
        name="estimate_projection_matrix",
        lesson="04",
        reference=cm.estimate_projection_matrix,
        cases=dlt_cases,
        compare=lambda got, expected: same_up_to_scale(
            got, expected, rtol=1e-6
        ),  # exact pixels: P up to scale
        diagnose=_dlt_diagnosis,
        follow_up=dlt_follow_up,
        wrong_variants=(
            (dlt_not_undone, "not undone"),
            (dlt_undone_wrong_order, "wrong way round"),
            (lambda X, uv: dlt_unnormalised(np.asarray(X), np.asarray(uv)), "no normalisation"),
            (lambda X, uv: dlt_half(X, uv, world=False), "world points are not normalised at all"),
            (lambda X, uv: dlt_half(X, uv, pixels=False), "pixels are not normalised at all"),
            (
                lambda X, uv: dlt_partial(X, uv, world=(True, False), pixels=(True, False)),
                "centred but not scaled",
            ),
            (
                lambda X, uv: dlt_partial(X, uv, world=(True, False)),
                "world points are centred but not scaled",
            ),
            (
                lambda X, uv: dlt_partial(X, uv, world=(False, True), pixels=(False, True)),
                "scaled but not centred",
            ),
            (
                lambda X, uv: dlt_partial(X, uv, pixels=(False, True)),
                "pixels are scaled but not centred",
            ),
            (dlt_p34, "p34 = 1"),
            (
                lambda X, uv: dlt_slipped(X, uv, world="unscaled shift", pixels="unscaled shift"),
                "world points and pixels has the translation -c",
            ),
            (
                lambda X, uv: dlt_slipped(X, uv, pixels="unscaled shift"),
                "pixels has the translation -c",
            ),
            (
                lambda X, uv: dlt_slipped(X, uv, world="unscaled shift"),
                "world points has the translation -c",
            ),
            (
                lambda X, uv: dlt_slipped(X, uv, world="origin scale", pixels="origin scale"),
                "world points and pixels are centred, but their scale is measured from the origin",
            ),
            (
                lambda X, uv: dlt_slipped(X, uv, world="origin scale"),
                "world points are centred, but their scale is measured from the origin",
            ),
            (
                lambda X, uv: dlt_slipped(X, uv, pixels="origin scale"),
                "pixels are centred, but their scale is measured from the origin",
            ),
            (
                lambda X, uv: dlt_mismatched(X, uv, pixels="scale"),
                "scaled the pixels but did not centre",
            ),
            (
                lambda X, uv: dlt_mismatched(X, uv, pixels="centre"),
                "centred the pixels but did not scale",
            ),
            (lambda X, uv: dlt_mismatched(X, uv, pixels="none"), "left the pixels unnormalised"),
            (
                lambda X, uv: dlt_mismatched(X, uv, world="scale"),
                "scaled the world points but did not",
            ),
            (
                lambda X, uv: dlt_mismatched(X, uv, world="centre"),
                "centred the world points but did not",
            ),
            (
                lambda X, uv: dlt_mismatched(X, uv, world="none"),
                "left the world points unnormalised",
            ),
            (lambda X, uv: dlt_u_not_a_column(X, uv), "Keep u a column"),
            (
                lambda X, uv: estimate_projection_matrix(X, np.asarray(uv)[:, ::-1]),
                "u and v are swapped",
            ),
            (lambda X, uv: dlt_half(X, uv, undo="T"), "undid only the pixels'"),
            (lambda X, uv: dlt_half(X, uv, undo="U"), "undid only the world points'"),
            (lambda X, uv: dlt_half(X, uv, sign=1.0), "sign slip in A"),
            (lambda X, uv: dlt_half(X, uv, column=True), "Vt[-1], not Vt[:, -1]"),
            (lambda X, uv: dlt_half(X, uv, column=True, interleave=True), "Vt[-1], not Vt[:, -1]"),
            (lambda X, uv: dlt_half(X, uv, order="F"), "column by column"),
            (lambda X, uv: dlt_half(X, uv, order="F", interleave=True), "column by column"),
            (lambda X, uv: cm.estimate_projection_matrix(X, uv).T, "transposed"),
            (
                lambda X, uv: (
                    cm.estimate_projection_matrix(X, uv).ravel().reshape((3, 4), order="F")
                ),
                "wrong order",
            ),
        ),
        exception_hint=_dlt_exception_hint,
        teaching=estimate_projection_matrix,
    )
)
