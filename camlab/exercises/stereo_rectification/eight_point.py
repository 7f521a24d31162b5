"""Exercise 1 of lesson 11: the normalised 8-point algorithm (`eight_point`)."""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ... import epipolar
from ...projective import hartley_normalise
from .._answers import same_up_to_scale, shape_problem
from .._core import Exercise, register_exercise
from ._rig import rig_points

# --------------------------------------------------------------------------- the 8-point algorithm


def _eight_point_cases():
    return [
        rig_points(0, 0.0),
        rig_points(1, 0.5),
        rig_points(2, 1.0, n=40, baseline=(0.5, -0.05, 0.1)),
    ]


@lru_cache(maxsize=1)
def _cases_with_reference():
    return [(args, epipolar.estimate_fundamental_matrix(*args)) for args in _eight_point_cases()]


def _fits_as_well(got, expected) -> bool:
    """Right: the reference up to scale, or a rank-2 F that fits the test pairs as well as it does.

    Hartley's mean distance sqrt(2) is one choice: centring and scaling to mean distance 0.5, RMS
    sqrt(2) or the box [-1, 1] is as valid when it is undone correctly, and moves F on noisy pairs by
    up to ~3e-3. Such an F is judged on the original points: rank 2 (in normalised coordinates) and
    a mean squared Sampson distance within 2 % of the reference's (other normalisations: within
    0.7 %; rank 2 enforced in pixels: 4-23 % worse; no normalisation: 7-22 times worse).
    """
    if same_up_to_scale(got, expected, rtol=1e-3):
        return True
    g = np.asarray(got, dtype=float)
    found = [a for a, ref in _cases_with_reference() if np.array_equal(ref, expected)]
    if not found or g.shape != (3, 3) or not np.all(np.isfinite(g)) or not np.any(g):
        return False
    x1, x2 = found[0]
    T1, T2 = hartley_normalise(x1).T, hartley_normalise(x2).T
    s = np.linalg.svd(np.linalg.inv(T2).T @ g @ np.linalg.inv(T1), compute_uv=False)
    if s[2] > 1e-8 * s[0]:
        return False
    mine = np.mean(epipolar.sampson_distance(g, x1, x2) ** 2)
    best = np.mean(epipolar.sampson_distance(expected, x1, x2) ** 2)
    return bool(mine <= 1.02 * best + 1e-12)


def _eight_point_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". F is the (3, 3) matrix with x2_h @ F @ x1_h = 0."
    x1, x2 = args
    g = np.asarray(got, dtype=float)
    # judge the rank in normalised coordinates, where F's entries are all of order 1
    T1, T2 = hartley_normalise(x1).T, hartley_normalise(x2).T
    s = np.linalg.svd(np.linalg.inv(T2).T @ g @ np.linalg.inv(T1), compute_uv=False)
    if s[2] > 1e-8 * s[0]:
        return (
            "your F has rank 3 (smallest singular value "
            f"{s[2] / s[0]:.2g} of the largest): enforce rank 2 by zeroing the smallest singular value, "
            "U diag(s1, s2, 0) V^T, so all epipolar lines meet in one epipole"
        )
    if same_up_to_scale(g.T, expected, rtol=1e-5):
        return "your F is transposed: with rows (u'u, u'v, u', v'u, v'v, v', u, v, 1) the constraint is x2^T F x1 = 0"
    hint = _unnormalisation_slip(g, x1, x2, expected, T1, T2)
    if hint:
        return hint
    swapped = epipolar.estimate_fundamental_matrix(x1[:, ::-1], x2[:, ::-1])
    if same_up_to_scale(g, swapped, rtol=1e-4):
        return (
            "your F is right for the points with u and v swapped, (v, u) as in img[v, u]: each row of x1, "
            "x2 is (u, v) = (column, row), and the equation's row is (u'u, u'v, u', v'u, v'v, v', u, v, 1)"
        )
    raw = epipolar.estimate_fundamental_matrix(x1, x2, normalise=False, plane_tol=0)
    if same_up_to_scale(g, raw, rtol=1e-4):
        return (
            "your F matches the 8-point algorithm without normalisation: normalise each image's points "
            "(centroid to 0, mean distance sqrt(2)) first, then undo it with F = T2^T F_n T1"
        )
    for off, what in (
        (0.5, "a half-pixel"),
        (-0.5, "a half-pixel"),
        (1.0, "a 1-based"),
        (-1.0, "a 1-based"),
    ):
        shifted = epipolar.estimate_fundamental_matrix(x1 + off, x2 + off)
        if same_up_to_scale(g, shifted, rtol=1e-4):
            return (
                f"your F is the right F for every point moved by {off:+g} px: {what} offset. The points are "
                "already pixel coordinates with the origin at the centre of the top-left pixel; use them as given"
            )
    for undo in (False, True):
        if same_up_to_scale(g, _row_times_t(x1, x2, undo), rtol=1e-3):
            return (
                "you normalised the points with x_h @ T, which applies T^T (its translation lands in the "
                "third column and never moves them): with points as rows, T x is x_h @ T.T"
            )
    top = np.vstack([x1, x2]).max(axis=0)  # the image size, as a student might take it
    for scale in (None, (1 / 640, 1 / 480), (2 / 640, 2 / 480), tuple(1 / top)):
        if same_up_to_scale(g, _scaled_not_centred(x1, x2, scale), rtol=1e-3):
            return (
                "you scaled the points but did not centre them"
                + ("" if scale is None else " (divided by the image size)")
                + ": Hartley's T first moves the centroid to the origin, then scales to mean distance "
                "sqrt(2); without the translation A stays badly conditioned"
            )
    if same_up_to_scale(g, _scaled_not_centred(x1, x2, centre=True), rtol=1e-3):
        return (
            "you centred the points but did not scale them: products like u'u are still ~1e5 next to the "
            "1s, so A stays badly conditioned. Hartley's T also scales each image to mean distance sqrt(2)"
        )
    err = np.median(epipolar.sampson_distance(g, x1, x2)) if np.any(g) else np.inf
    return (
        f"median Sampson error of your F on the input pairs is {err:.3g} px; check the row of the linear "
        "system (u'u, u'v, u', v'u, v'v, v', u, v, 1), the SVD (last row of V^T) and the un-normalisation. "
        "If you fixed F33 = 1 and solved by least squares: that fails when F33 is near 0 (as for these "
        "rigs); take f as the null vector with |f| = 1 instead"
    )


def _unnormalisation_slip(g, x1, x2, expected, T1, T2) -> str:
    """The hint for an F whose normalisation went wrong; '' if none fits.

    Its largest singular value zeroed, F_n reshaped column-major, its normalisation not undone or
    undone the wrong way, or its rank 2 enforced after undoing it; '' if ``g`` is none of these
    (up to scale).
    """
    iT1, iT2 = np.linalg.inv(T1), np.linalg.inv(T2)
    Fn = iT2.T @ expected @ iT1  # the reference in normalised coordinates
    right = "F = T2^T F_n T1, from x2^T F x1 = (T2 x2)^T F_n (T1 x1)"
    U, S, Vt = np.linalg.svd(_no_rank2(x1, x2))
    Un, Sn, Vnt = np.linalg.svd(iT2.T @ _no_rank2(x1, x2) @ iT1)  # F_n before its rank-2 step
    forms = [
        (
            T2.T @ Un @ np.diag([0.0, Sn[1], Sn[2]]) @ Vnt @ T1,
            "you zeroed the LARGEST singular value of F_n: rank 2 keeps the two largest, "
            "U diag(s1, s2, 0) V^T (numpy's svd sorts them in decreasing order, so zero S[2])",
        ),
        (
            T2.T @ (Un @ np.diag([Sn[0], Sn[1], 0.0]) @ Vnt).T @ T1,
            "your F_n is transposed: either you reshaped f column by column (order='F'), or you built each "
            "row for x1^T F x2, with image 1's and image 2's coordinates swapped inside the products. "
            "The row for x2^T F x1 is (u'u, u'v, u', v'u, v'v, v', u, v, 1), (u', v') from x2, and "
            "f = (F11, F12, F13, F21, ...) is row-major: f.reshape(3, 3)",
        ),
        (Fn, "you returned F_n, the F of the normalised points: undo the normalisation, " + right),
        (
            iT2 @ Fn @ T1,
            "you undid the normalisation as for a homography (T2^-1 F_n T1): a homography maps points, "
            "but F sits between two points, so each side takes its own T transposed: " + right,
        ),
        (
            iT2 @ Fn @ iT1,
            "you undid the normalisation with the inverses, untransposed (T2^-1 F_n T1^-1): F_n was "
            "fitted to the normalised points T x, so substitute them: " + right,
        ),
        (T2 @ Fn @ T1, "you undid the normalisation with T2 where T2^T belongs: " + right),
        (
            T2.T @ Fn,
            "you undid only image 2's normalisation (T2^T F_n): T1 goes on the right, " + right,
        ),
        (
            Fn @ T1,
            "you undid only image 1's normalisation (F_n T1): T2^T goes on the left, " + right,
        ),
        (
            T1.T @ Fn @ T2,
            "you swapped T1 and T2 when undoing the normalisation: T1 (image 1) goes on the right, "
            + right,
        ),
        (
            iT2.T @ Fn @ iT1,
            "you undid the normalisation with the inverse matrices: F_n was fitted to T x, so "
            + right,
        ),
        (
            U @ np.diag([S[0], S[1], 0.0]) @ Vt,
            "you enforced rank 2 after undoing the normalisation: zero the smallest singular value of "
            "F_n first, in normalised coordinates (in pixels the entries span many orders of magnitude, "
            "and the nearest rank-2 matrix there is a worse F), then F = T2^T F_n T1",
        ),
    ]
    for F_wrong, hint in forms:
        if same_up_to_scale(g, F_wrong, rtol=1e-3):
            return hint
    return ""


def _forgot_unnormalising(x1, x2):
    T1, T2 = hartley_normalise(x1).T, hartley_normalise(x2).T
    F = epipolar.estimate_fundamental_matrix(x1, x2)
    return np.linalg.inv(T2).T @ F @ np.linalg.inv(T1)


def _homography_style(x1, x2):
    T1, T2 = hartley_normalise(x1).T, hartley_normalise(x2).T
    return np.linalg.inv(T2) @ _forgot_unnormalising(x1, x2) @ T1


def _swapped_t(x1, x2):
    T1, T2 = hartley_normalise(x1).T, hartley_normalise(x2).T
    return T1.T @ _forgot_unnormalising(x1, x2) @ T2


def _rank_after(x1, x2):
    U, S, Vt = np.linalg.svd(_no_rank2(x1, x2))
    return U @ np.diag([S[0], S[1], 0.0]) @ Vt


def _largest_zeroed(x1, x2):
    T1, T2 = hartley_normalise(x1).T, hartley_normalise(x2).T
    U, S, Vt = np.linalg.svd(np.linalg.inv(T2).T @ _no_rank2(x1, x2) @ np.linalg.inv(T1))
    return T2.T @ U @ np.diag([0.0, S[1], S[2]]) @ Vt @ T1


def _column_major(x1, x2):
    T1, T2 = hartley_normalise(x1).T, hartley_normalise(x2).T
    U, S, Vt = np.linalg.svd((np.linalg.inv(T2).T @ _no_rank2(x1, x2) @ np.linalg.inv(T1)).T)
    return T2.T @ U @ np.diag([S[0], S[1], 0.0]) @ Vt @ T1


def _rms_normalised(x1, x2):
    """A right answer in another valid form: scale to RMS distance sqrt(2), not the mean (tests)."""
    x1, x2 = np.asarray(x1, dtype=float), np.asarray(x2, dtype=float)

    def normaliser(p):
        c = p.mean(axis=0)
        s = np.sqrt(2) / np.sqrt(np.mean(np.sum((p - c) ** 2, axis=1)))
        return np.array([[s, 0, -s * c[0]], [0, s, -s * c[1]], [0, 0, 1]])

    T1, T2 = normaliser(x1), normaliser(x2)
    a = np.column_stack([x1, np.ones(len(x1))]) @ T1.T
    b = np.column_stack([x2, np.ones(len(x2))]) @ T2.T
    A = np.column_stack([b[:, [0]] * a, b[:, [1]] * a, a])
    U, S, Vt = np.linalg.svd(np.linalg.svd(A)[2][-1].reshape(3, 3))
    return T2.T @ U @ np.diag([S[0], S[1], 0.0]) @ Vt @ T1


def _scaled_not_centred(x1, x2, scale=None, centre=False):
    """The 8-point algorithm with the points scaled but not centred (or, ``centre``, the reverse).

    ``scale`` None: each image to mean distance sqrt(2) from 0 (Hartley's scale without his
    translation); ``scale`` (su, sv): both images by diag(su, sv, 1), e.g. (1/640, 1/480), the
    image size. ``centre`` True: each image's centroid moved to 0 and no scaling.
    """
    a, b = np.asarray(x1, float), np.asarray(x2, float)
    T1, T2 = (
        np.diag([s, s, 1.0]) if scale is None else np.diag([scale[0], scale[1], 1.0])
        for s in (np.sqrt(2) / np.linalg.norm(p, axis=1).mean() for p in (a, b))
    )
    if centre:
        T1, T2 = (
            np.array([[1.0, 0, -p[:, 0].mean()], [0, 1, -p[:, 1].mean()], [0, 0, 1]])
            for p in (a, b)
        )
    ah, bh = np.c_[a, np.ones(len(a))] @ T1.T, np.c_[b, np.ones(len(b))] @ T2.T
    A = np.column_stack([bh[:, [0]] * ah, bh[:, [1]] * ah, ah])
    U, S, Vt = np.linalg.svd(np.linalg.svd(A)[2][-1].reshape(3, 3))
    return T2.T @ U @ np.diag([S[0], S[1], 0.0]) @ Vt @ T1


def _row_times_t(x1, x2, undo_transposed=False):
    """The 8-point algorithm with rows normalised as x_h @ T (T^T applied), undone as T2^T F_n T1 or transposed."""
    a, b = np.asarray(x1, float), np.asarray(x2, float)
    T1, T2 = hartley_normalise(a).T, hartley_normalise(b).T
    ah, bh = np.c_[a, np.ones(len(a))] @ T1, np.c_[b, np.ones(len(b))] @ T2
    A = np.column_stack([bh[:, [0]] * ah, bh[:, [1]] * ah, ah])  # as the teaching rows
    U, S, Vt = np.linalg.svd(np.linalg.svd(A)[2][-1].reshape(3, 3))
    F = U @ np.diag([S[0], S[1], 0.0]) @ Vt
    return T2 @ F @ T1.T if undo_transposed else T2.T @ F @ T1


def _only_t2(x1, x2):
    """The normalised F with only image 2's normalisation undone, T2^T F_n (tests)."""
    T1 = hartley_normalise(np.asarray(x1, float)).T
    return epipolar.estimate_fundamental_matrix(x1, x2) @ np.linalg.inv(T1)


def _no_rank2(x1, x2):
    a, b = np.asarray(x1, float), np.asarray(x2, float)
    T1, T2 = hartley_normalise(a).T, hartley_normalise(b).T
    an = a @ T1[:2, :2].T + T1[:2, 2]
    bn = b @ T2[:2, :2].T + T2[:2, 2]
    A = np.column_stack(
        [
            bn[:, 0] * an[:, 0],
            bn[:, 0] * an[:, 1],
            bn[:, 0],
            bn[:, 1] * an[:, 0],
            bn[:, 1] * an[:, 1],
            bn[:, 1],
            an[:, 0],
            an[:, 1],
            np.ones(len(a)),
        ]
    )
    F = np.linalg.svd(A)[2][-1].reshape(3, 3)
    return T2.T @ F @ T1


def eight_point(x1, x2):
    """Normalise, one row (u'u, u'v, u', v'u, v'v, v', u, v, 1) per match, SVD, rank 2, un-normalise.

    Parameters
    ----------
    x1, x2 : (N, 2) array_like
        Matching pixels in image 1 and image 2, N >= 8.

    Returns
    -------
    (3, 3) ndarray
        The fundamental matrix F, rank 2, up to scale, with x2^T F x1 = 0.

    References
    ----------
    R. I. Hartley (1997), "In defense of the eight-point algorithm", IEEE TPAMI 19(6);
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 11.2 and algorithm 11.1.
    """
    x1, x2 = np.asarray(x1, dtype=float), np.asarray(x2, dtype=float)

    def normaliser(p):  # centroid to 0, mean distance sqrt(2)
        c = p.mean(axis=0)
        s = np.sqrt(2) / np.mean(np.linalg.norm(p - c, axis=1))
        return np.array([[s, 0, -s * c[0]], [0, s, -s * c[1]], [0, 0, 1]])

    T1, T2 = normaliser(x1), normaliser(x2)
    a = np.column_stack([x1, np.ones(len(x1))]) @ T1.T
    b = np.column_stack([x2, np.ones(len(x2))]) @ T2.T
    A = np.column_stack([b[:, [0]] * a, b[:, [1]] * a, a])  # x2^T F x1 = 0, F row by row
    F = np.linalg.svd(A)[2][-1].reshape(3, 3)
    U, S, Vt = np.linalg.svd(F)
    F = U @ np.diag([S[0], S[1], 0.0]) @ Vt  # rank 2: one epipole
    return T2.T @ F @ T1


register_exercise(
    Exercise(
        name="eight_point",
        lesson="11",
        reference=epipolar.estimate_fundamental_matrix,
        cases=_eight_point_cases,
        compare=_fits_as_well,
        diagnose=_eight_point_diagnosis,
        up_to_scale=True,  # got and expected printed at one scale, not F at ~1e-5 beside unit norm
        wrong_variants=(
            (_no_rank2, "rank 2"),
            (lambda x1, x2: epipolar.estimate_fundamental_matrix(x1, x2).T, "transposed"),
            (
                lambda x1, x2: epipolar.estimate_fundamental_matrix(
                    x1, x2, normalise=False, plane_tol=0
                ),
                "normalis",
            ),
            (_forgot_unnormalising, "you returned F_n"),
            (_homography_style, "as for a homography"),
            (_swapped_t, "swapped T1 and T2"),
            (_rank_after, "rank 2 after undoing"),
            (_largest_zeroed, "LARGEST singular value"),
            (_column_major, "order='F'"),
            (
                lambda x1, x2: epipolar.estimate_fundamental_matrix(
                    np.asarray(x1)[:, ::-1], np.asarray(x2)[:, ::-1]
                ),
                "u and v swapped",
            ),
            (
                lambda x1, x2: _scaled_not_centred(x1, x2, centre=True),
                "centred the points but did not scale",
            ),
            (_only_t2, "only image 2's normalisation"),
            (_row_times_t, "x_h @ T.T"),
            (
                lambda x1, x2: (
                    np.linalg.inv(hartley_normalise(np.asarray(x2, float)).T)
                    @ _forgot_unnormalising(x1, x2)
                    @ np.linalg.inv(hartley_normalise(np.asarray(x1, float)).T)
                ),
                "inverses, untransposed",
            ),
        ),
        teaching=eight_point,
    )
)
