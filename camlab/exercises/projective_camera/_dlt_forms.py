"""The DLT built in its right and wrong forms.

The normalisers (Hartley's [1]_ and the RMS one), the two rows per point of u x P X = 0, and the
half-normalised or wrongly undone fits students write.

References
----------
.. [1] R. I. Hartley, 1997, "In defense of the eight-point algorithm", *IEEE Transactions on Pattern
   Analysis and Machine Intelligence* 19(6), 580-593.
"""

from __future__ import annotations

import numpy as np

from ... import camera as cm
from ...projective import hartley_normalise


def dlt_p34(X, uv):
    """The classic DLT (Abdel-Aziz and Karara): p34 = 1, the other 11 entries by least squares, no normalisation."""
    A = dlt_rows(np.asarray(X, dtype=float), np.asarray(uv, dtype=float))
    p = np.linalg.lstsq(A[:, :11], -A[:, 11], rcond=None)[0]
    return np.append(p, 1.0).reshape(3, 4)


def dlt_partial(X, uv, world=(True, True), pixels=(True, True)):
    """A DLT whose normalisers only centre, only scale, or both, per side: (centre, scale)."""
    X, uv = np.asarray(X, dtype=float), np.asarray(uv, dtype=float)

    def normaliser(p, centre, scale):
        c = p.mean(axis=0) if centre else np.zeros(p.shape[1])
        s = np.sqrt(p.shape[1]) / np.mean(np.linalg.norm(p - c, axis=1)) if scale else 1.0
        N = s * np.eye(p.shape[1] + 1)
        N[:-1, -1], N[-1, -1] = -s * c, 1.0
        return N

    U, T = normaliser(X, *world), normaliser(uv, *pixels)
    P_hat = np.linalg.svd(dlt_rows(in_frame(U, X), in_frame(T, uv)))[2][-1].reshape(3, 4)
    return np.linalg.inv(T) @ P_hat @ U


NORMALISER_SLIPS = ("unscaled shift", "origin scale")
"""Two normalisers students build: the translation -c where it must be -s c (p goes to s p - c, not centred),
and the scale from the mean distance to the origin, |p|, where it must be |p - c| (centred, scaled wrongly)."""


def slipped_normaliser(p, slip):
    """Hartley's normaliser of the points ``p`` (N, D), built right (``slip=None``) or with one of NORMALISER_SLIPS."""
    c = p.mean(axis=0)
    spread = np.linalg.norm(p if slip == "origin scale" else p - c, axis=1).mean()
    s = np.sqrt(p.shape[1]) / spread
    N = s * np.eye(p.shape[1] + 1)
    N[:-1, -1], N[-1, -1] = (-c if slip == "unscaled shift" else -s * c), 1.0
    return N


def dlt_slipped(X, uv, world=None, pixels=None):
    """A normalised DLT whose world and pixel normalisers carry the slips ``world`` and ``pixels`` (None: right)."""
    X, uv = np.asarray(X, dtype=float), np.asarray(uv, dtype=float)
    U, T = slipped_normaliser(X, world), slipped_normaliser(uv, pixels)
    P_hat = np.linalg.svd(dlt_rows(in_frame(U, X), in_frame(T, uv)))[2][-1].reshape(3, 4)
    return np.linalg.inv(T) @ P_hat @ U


def normalisers(X, uv):
    """Hartley's U (world, 4 x 4) and T (pixels, 3 x 3)."""
    return hartley_normalise(X).T, hartley_normalise(uv).T


def rms_normalisers(X, uv):
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


def in_frame(T, points):
    return (np.column_stack([points, np.ones(len(points))]) @ T.T)[:, :-1]


def dlt_rows(X, uv, sign=-1.0):
    """The 2N x 12 DLT matrix (two rows of u x P X = 0 per point); sign=+1 is the sign slip in -u, -v."""
    Xh = np.column_stack([X, np.ones(len(X))])
    zero = np.zeros_like(Xh)
    return np.vstack(
        [np.hstack([Xh, zero, sign * uv[:, :1] * Xh]), np.hstack([zero, Xh, sign * uv[:, 1:] * Xh])]
    )


def dlt_unnormalised(X, uv):
    """The plain DLT in metres and pixels (a plausible student answer)."""
    return np.linalg.svd(dlt_rows(X, uv))[2][-1].reshape(3, 4)


def dlt_half(
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
    """Normalised DLT variants, right and wrong.

    Which sides are normalised and undone, the sign in A, Vt's row or column, A's rows stacked (u
    rows, then v rows) or interleaved per point, the null vector read row by row or not.
    """
    X, uv = np.asarray(X, dtype=float), np.asarray(uv, dtype=float)
    U, T = normalisers(X, uv)
    U, T = (U if world else np.eye(4)), (T if pixels else np.eye(3))
    A = dlt_rows(in_frame(U, X), in_frame(T, uv), sign)
    if interleave:
        A = (
            A.reshape(2, -1, 12).transpose(1, 0, 2).reshape(-1, 12)
        )  # u row, v row of point 0, then point 1, ...
    Vt = np.linalg.svd(A)[2]
    P_hat = (Vt[:, -1] if column else Vt[-1]).reshape((3, 4), order=order)
    return {"both": np.linalg.inv(T) @ P_hat @ U, "T": np.linalg.inv(T) @ P_hat, "U": P_hat @ U}[
        undo
    ]


def dlt_not_undone(X, uv):
    U, T = normalisers(X, uv)
    return T @ cm.estimate_projection_matrix(X, uv) @ np.linalg.inv(U)  # P_hat itself


def dlt_undone_wrong_order(X, uv):
    U, T = normalisers(X, uv)
    return T @ dlt_not_undone(X, uv) @ np.linalg.inv(U)  # T P_hat U^-1


def dlt_mismatched(X, uv, pixels="full", world="full"):
    """A DLT that applies part of a normaliser ("scale", "centre" or "none") to one side, then undoes the full one."""
    X, uv = np.asarray(X, dtype=float), np.asarray(uv, dtype=float)
    U, T = normalisers(X, uv)

    def part(N, kind):
        d = len(N) - 1
        if kind == "scale":
            return np.diag([*np.diag(N)[:d], 1.0])
        if kind == "centre":
            return np.block([[np.eye(d), N[:d, d:] / N[0, 0]], [np.zeros((1, d)), np.ones((1, 1))]])
        return np.eye(d + 1) if kind == "none" else N

    P_hat = np.linalg.svd(dlt_rows(in_frame(part(U, world), X), in_frame(part(T, pixels), uv)))[2][
        -1
    ]
    return np.linalg.inv(T) @ P_hat.reshape(3, 4) @ U


def dlt_u_not_a_column(X, uv):
    """The broadcasting slip -uv[:, 0] * X_h (u as an (N,) vector against (N, 4) rows): raises ValueError."""
    X, uv = np.asarray(X, dtype=float), np.asarray(uv, dtype=float)
    Xh, zero = np.column_stack([X, np.ones(len(X))]), np.zeros((len(X), 4))
    return np.vstack([np.hstack([Xh, zero, -uv[:, 0] * Xh]), np.hstack([zero, Xh, -uv[:, 1] * Xh])])
