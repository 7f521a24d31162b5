r"""Lesson 05's fourth exercise: Tomasi-Kanade factorisation.

From N points tracked through m views, return the tracks as the best rank-3 affine model reprojects
them: centre each view's points, stack them into the 2m x N measurement matrix, keep three terms of
its SVD, and add each view's mean back ([1]_, algorithm 18.1). The cameras and points are fixed only
up to an affine map of space; their reprojection is unique, so that is what the check compares, and
any layout of the measurement matrix (u and v rows interleaved or stacked, or its transpose) passes.

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 18.2 (algorithm 18.1).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import camera as cm
from ...factorization import rank3_reprojection
from .._answers import same_array, shape_problem
from .._core import Exercise, Mistake, first_mistake, mistake_variant, register_exercise


def _factorisation_cases():
    """Three perspective orbits of a 1 m cube (2.5 to 6 m away, 0.5 px noise): not exactly rank 3."""
    rng = np.random.default_rng(18)
    out = []
    for views, count, distance in ((4, 12, 2.5), (6, 20, 4.0), (8, 30, 6.0)):
        X = rng.uniform(-0.5, 0.5, (count, 3))
        K = cm.intrinsic_matrix(200 * distance, 200 * distance, 319.5, 239.5)
        cams = [
            cm.Camera.look_at(
                cm.orbit_eye(np.radians(6.0 * k), np.radians(15.0), distance), [0.0] * 3, K=K
            )
            for k in range(views)
        ]
        tracks = np.stack([c.project(X) for c in cams]) + rng.normal(0.0, 0.5, (views, count, 2))
        out.append((tracks,))
    return out


def _rank_k(C, k, weighted=True):
    """The rank-k truncation of C by its SVD (without the singular values when not ``weighted``)."""
    U, s, Vt = np.linalg.svd(C, full_matrices=False)
    return (U[:, :k] * (s[:k] if weighted else 1.0)) @ Vt[:k]


def _measurement(W):
    """(m, N, 2) tracks -> the 2m x N measurement matrix, rows u1, v1, u2, v2, ..."""
    return W.transpose(0, 2, 1).reshape(-1, W.shape[1])


def _tracks(C, m):
    """The 2m x N measurement matrix back to (m, N, 2) tracks."""
    return C.reshape(m, 2, -1).transpose(0, 2, 1)


def _fit(W, means, k=3, weighted=True):
    """Tracks reprojected through a rank-k fit of W minus ``means`` (broadcast), the means added back."""
    return _tracks(_rank_k(_measurement(W - means), k, weighted), len(W)) + means


def _context(tracks):
    W = np.asarray(tracks, dtype=float)
    return SimpleNamespace(W=W, m=len(W), N=W.shape[1], view_means=W.mean(axis=1, keepdims=True))


def _scrambled(s):
    C = s.W.reshape(2 * s.m, s.N)  # a reshape without the transpose: each row mixes points and u, v
    means = C.mean(axis=1, keepdims=True)
    return (_rank_k(C - means, 3) + means).reshape(s.m, s.N, 2)


def _straight_reshape(s, forward, back):
    """Centred by view, reshaped to (2m, N) and back with or without the transpose through (m, 2, N)."""
    W = s.W - s.view_means
    C = _rank_k(W.reshape(2 * s.m, s.N) if forward else _measurement(W), 3)
    return (C.reshape(s.m, s.N, 2) if back else _tracks(C, s.m)) + s.view_means


_UV_MIXED = (
    "so each row mixes u and v: row 2i holds the u, v of half of view i's points, interleaved, "
    "instead of view i's u of every point. Go through (m, 2, N): W.transpose(0, 2, 1).reshape(2 * m, N), "
    "and back with W3.reshape(m, 2, N).transpose(0, 2, 1)."
)


_MISTAKES = (
    Mistake(
        "input returned",
        lambda s: s.W,
        "you returned the tracks themselves; return what the rank-3 fit (three terms of the SVD) reprojects.",
    ),
    Mistake(
        "not centred",
        lambda s: _tracks(_rank_k(_measurement(s.W), 3), s.m),
        "you factorised the tracks without centring them: subtract each view's mean point first "
        "(W.mean(axis=1, keepdims=True), the image of the centroid). Uncentred, a fourth dimension holds "
        "the translations, and rank 3 cannot hold them and the shape.",
    ),
    Mistake(
        "uncentred rank 4",
        lambda s: _tracks(_rank_k(_measurement(s.W), 4), s.m),
        "you kept four terms of the SVD of the uncentred tracks: that fits a fourth dimension freely, "
        "where the translations need only a constant one. Subtract each view's mean "
        "(W.mean(axis=1, keepdims=True)), keep three terms, and add the means back.",
    ),
    Mistake(
        "means not added back",
        lambda s: _fit(s.W, s.view_means) - s.view_means,
        "the rank-3 part is right, but you did not add each view's mean back: the answer is in the "
        "centred frame; add W.mean(axis=1, keepdims=True) to return pixels.",
    ),
    Mistake(
        "centred per point",
        lambda s: _fit(s.W, s.W.mean(axis=0, keepdims=True)),
        "you subtracted each point's mean over the views (axis=0); the translation is per view: subtract "
        "each view's mean over its points, W.mean(axis=1, keepdims=True).",
    ),
    Mistake(
        "one mean",
        lambda s: _fit(s.W, s.W.mean()),
        "you subtracted one number, the mean of all coordinates (W.mean() with no axis); u and v of each "
        "view have their own mean: W.mean(axis=1, keepdims=True), shape (m, 1, 2).",
    ),
    Mistake(
        "no singular values",
        lambda s: _fit(s.W, s.view_means, weighted=False),
        "you multiplied U[:, :3] by Vt[:3] without the singular values between them: the rank-3 fit is "
        "U[:, :3] @ np.diag(s[:3]) @ Vt[:3] (or (U[:, :3] * s[:3]) @ Vt[:3]).",
    ),
    Mistake(
        "rank 2",
        lambda s: _fit(s.W, s.view_means, k=2),
        "you kept two singular values: an affine camera images 3-D points, so the centred measurement "
        "matrix has rank 3; keep s[:3].",
    ),
    Mistake(
        "rank 4",
        lambda s: _fit(s.W, s.view_means, k=4),
        "you kept four singular values: the centred measurement matrix of affine views has rank 3 (a 2m x 3 "
        "times a 3 x N matrix); the fourth value is what no affine camera explains. Keep s[:3].",
    ),
    Mistake(
        "scrambled reshape",
        _scrambled,
        "your measurement matrix is scrambled: W.reshape(2 * m, N) on the (m, N, 2) tracks puts half the "
        "points' interleaved u, v in one row. Transpose each view to (2, N) first: "
        "W.transpose(0, 2, 1).reshape(2 * m, N), and undo it the same way.",
    ),
    Mistake(
        "reshaped without transpose",
        lambda s: _straight_reshape(s, True, True),
        "you kept three terms, but of a scrambled matrix: you reshaped the (m, N, 2) tracks straight to "
        "(2m, N) without transposing each view to (2, N), " + _UV_MIXED,
    ),
    Mistake(
        "reshaped in without transpose",
        lambda s: _straight_reshape(s, True, False),
        "you kept three terms, but of a scrambled matrix: you reshaped the (m, N, 2) tracks straight to "
        "(2m, N) without transposing each view to (2, N), " + _UV_MIXED,
    ),
    Mistake(
        "reshaped back without transpose",
        lambda s: _straight_reshape(s, False, True),
        "your rank-3 matrix is right, but you reshaped it straight back to (m, N, 2): its rows are "
        "u1, v1, u2, v2, ... over all N points, so that reshape mixes u and v (a point's (u, v) becomes "
        "two neighbouring u's of one row). Go back through (m, 2, N): W3.reshape(m, 2, N).transpose(0, 2, 1).",
    ),
    Mistake(
        "u and v swapped",
        lambda s: _fit(s.W, s.view_means)[..., ::-1],
        "u and v are swapped in your answer: keep (u, v) = (column, row) in the last axis, as in the input.",
    ),
)


def _diagnosis(args, got, expected) -> str:
    (W,) = args
    W = np.asarray(W, dtype=float)
    m, N = W.shape[:2]
    g_shape = np.shape(got) if got is not None else None
    if g_shape in ((m, 2, N), (2 * m, N), (N, 2 * m)):
        return (
            f"expected the reprojected tracks in the input's shape {W.shape} (m views, N points, (u, v)), "
            f"got shape {g_shape}: reshape the 2m x N measurement matrix back to (m, 2, N), then "
            f"transpose to (m, N, 2)."
        )
    problem = shape_problem(got, expected)
    if problem:
        return problem + f". Return an (m, N, 2) array like the input, here {W.shape}."
    g = np.asarray(got, dtype=float)
    cause = first_mistake(
        _MISTAKES, _context(W), g, lambda a, b: np.allclose(a, b, rtol=1e-7, atol=1e-6)
    )
    if cause:
        return cause
    centred = _measurement(g - g.mean(axis=1, keepdims=True))
    s = np.linalg.svd(centred, compute_uv=False)
    rms = float(np.sqrt(np.mean(np.sum((g - expected) ** 2, axis=-1))))
    if s[3] > 1e-6 * s[0]:
        return (
            f"your answer is not a rank-3 model: its centred measurement matrix has a fourth singular value "
            f"{s[3]:.3g} px (expected 0 to rounding). Keep three terms of the SVD of the centred tracks."
        )
    return (
        f"your answer is a rank-3 model, but not the best one: it is {rms:.3g} px RMS per point from the "
        f"least-squares reprojection. Centre each view (W.mean(axis=1, keepdims=True)), take the SVD of the "
        f"2m x N matrix and keep its three largest terms (Eckart-Young)."
    )


def reproject_rank3(tracks):
    """Tomasi-Kanade (H&Z algorithm 18.1): the tracks as the best rank-3 affine model reprojects them.

    Parameters
    ----------
    tracks : (m, N, 2) ndarray
        Pixel (u, v) of point j in view i.

    Returns
    -------
    (m, N, 2) ndarray
        Every point reprojected by every fitted affine camera: the rank-3 part of the centred
        measurement matrix, each view's mean added back.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 18.2 (algorithm 18.1).
    """
    m, N, _ = tracks.shape
    t = tracks.mean(axis=1, keepdims=True)  # (m, 1, 2): each view's image of the centroid
    W = (tracks - t).transpose(0, 2, 1).reshape(2 * m, N)  # rows u1, v1, u2, v2, ...
    U, s, Vt = np.linalg.svd(W, full_matrices=False)
    W3 = U[:, :3] @ np.diag(s[:3]) @ Vt[:3]  # the closest rank-3 matrix: cameras times points
    return W3.reshape(m, 2, N).transpose(0, 2, 1) + t


def _variant(name):
    return mistake_variant(_MISTAKES, name, _context)


register_exercise(
    Exercise(
        name="reproject_rank3",
        lesson="05",
        reference=rank3_reprojection,
        cases=_factorisation_cases,
        compare=same_array(rtol=1e-7, atol=1e-6),
        diagnose=_diagnosis,
        ndarray_only=True,
        wrong_variants=(
            (_variant("input returned"), "tracks themselves"),
            (_variant("not centred"), "without centring"),
            (_variant("uncentred rank 4"), "four terms of the SVD of the uncentred"),
            (_variant("means not added back"), "did not add each view's mean back"),
            (_variant("centred per point"), "each point's mean over the views"),
            (_variant("one mean"), "no axis"),
            (_variant("no singular values"), "without the singular values"),
            (_variant("rank 2"), "kept two singular values"),
            (_variant("rank 4"), "kept four singular values"),
            (_variant("scrambled reshape"), "scrambled"),
            (_variant("reshaped without transpose"), "mixes u and v"),
            (_variant("reshaped in without transpose"), "mixes u and v"),
            (_variant("reshaped back without transpose"), "reshaped it straight back"),
            (_variant("u and v swapped"), "u and v are swapped"),
            (lambda W: rank3_reprojection(W).transpose(0, 2, 1), "reshape the 2m x N"),
            (lambda W: rank3_reprojection(W) + 0.5, "not the best one"),
            (lambda W: rank3_reprojection(W).tolist(), "list"),
        ),
        teaching=reproject_rank3,
    )
)
