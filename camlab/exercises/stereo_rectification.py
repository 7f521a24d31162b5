"""Exercises for lesson 11, epipolar geometry and stereo rectification."""

from __future__ import annotations

import numpy as np

from .. import disparity, epipolar
from ..camera import Camera, rotation_from_axis_angle
from ..projective import hartley_normalise
from ._answers import same_array, same_up_to_scale, shape_problem
from ._core import Exercise, register_exercise


def _rig_points(seed: int, noise: float, n: int = 24, baseline=(0.3, 0.02, 0.01)):
    rng = np.random.default_rng(seed)
    c1 = Camera.look_at([0, -3, 0.5], [0, 0, 0.5])
    c2 = Camera.look_at(np.array([0, -3, 0.5]) + baseline, [0.1, 0, 0.5])
    X = rng.uniform(-0.8, 0.8, (n, 3)) + [0, 0, 0.5]
    x1, x2 = c1.project(X), c2.project(X)
    return x1 + rng.normal(0, noise, x1.shape), x2 + rng.normal(0, noise, x2.shape)


# --------------------------------------------------------------------------- the 8-point algorithm


def _eight_point_cases():
    return [
        _rig_points(0, 0.0),
        _rig_points(1, 0.5),
        _rig_points(2, 1.0, n=40, baseline=(0.5, -0.05, 0.1)),
    ]


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
    if same_up_to_scale(g, _scaled_not_centred(x1, x2), rtol=1e-3):
        return (
            "you scaled the points but did not centre them: Hartley's T first moves the centroid to the "
            "origin, then scales to mean distance sqrt(2); without the translation A stays badly conditioned"
        )
    err = np.median(epipolar.sampson_distance(g, x1, x2)) if np.any(g) else np.inf
    return (
        f"median Sampson error of your F on the input pairs is {err:.3g} px; check the row of the linear "
        "system (u'u, u'v, u', v'u, v'v, v', u, v, 1), the SVD (last row of V^T) and the un-normalisation"
    )


def _unnormalisation_slip(g, x1, x2, expected, T1, T2) -> str:
    """The hint for an F whose normalisation went wrong; '' if none fits.

    Its normalisation not undone, undone the wrong way, or its rank 2 enforced after undoing it; ''
    if ``g`` is none of these (up to scale).
    """
    iT1, iT2 = np.linalg.inv(T1), np.linalg.inv(T2)
    Fn = iT2.T @ expected @ iT1  # the reference in normalised coordinates
    right = "F = T2^T F_n T1, from x2^T F x1 = (T2 x2)^T F_n (T1 x1)"
    U, S, Vt = np.linalg.svd(_no_rank2(x1, x2))
    forms = [
        (Fn, "you returned F_n, the F of the normalised points: undo the normalisation, " + right),
        (
            iT2 @ Fn @ T1,
            "you undid the normalisation as for a homography (T2^-1 F_n T1): a homography maps points, "
            "but F sits between two points, so each side takes its own T transposed: " + right,
        ),
        (T2 @ Fn @ T1, "you undid the normalisation with T2 where T2^T belongs: " + right),
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


def _scaled_not_centred(x1, x2):
    """The 8-point algorithm with each image scaled to mean distance sqrt(2) from 0, not centred."""
    a, b = np.asarray(x1, float), np.asarray(x2, float)
    T1, T2 = (
        np.diag([s, s, 1.0])
        for s in (np.sqrt(2) / np.linalg.norm(p, axis=1).mean() for p in (a, b))
    )
    ah, bh = np.c_[a, np.ones(len(a))] @ T1.T, np.c_[b, np.ones(len(b))] @ T2.T
    A = np.column_stack([bh[:, [0]] * ah, bh[:, [1]] * ah, ah])
    U, S, Vt = np.linalg.svd(np.linalg.svd(A)[2][-1].reshape(3, 3))
    return T2.T @ U @ np.diag([S[0], S[1], 0.0]) @ Vt @ T1


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
        # 1e-3: another normalisation (RMS distance sqrt(2)) moves F by ~4e-5; rank 2 enforced in
        # pixels instead of normalised coordinates moves it by ~1e-2 on the noisy case
        compare=lambda got, expected: same_up_to_scale(got, expected, rtol=1e-3),
        diagnose=_eight_point_diagnosis,
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
        ),
        teaching=eight_point,
    )
)


# --------------------------------------------------------------------------- epipoles from F


def _epipole_cases():
    F1 = epipolar.estimate_fundamental_matrix(*_rig_points(3, 0.0))
    c1 = Camera.look_at([0, -3, 0.5], [0, 0, 0.5])
    c2 = c1.replace(t=c1.t - np.array([0.2, 0.0, 0.0]))  # parallel cameras: epipoles at infinity
    F3 = epipolar.fundamental_from_cameras(c1, Camera.look_at([0.4, -2.5, 0.9], [0, 0, 0.5]))
    return [(F1,), (epipolar.fundamental_from_cameras(c1, c2),), (F3,)]


def _epipole_compare(got, expected) -> bool:
    try:
        e1, e2 = got
    except (TypeError, ValueError):
        return False
    return same_up_to_scale(e1, expected.e1, rtol=1e-6) and same_up_to_scale(
        e2, expected.e2, rtol=1e-6
    )


def _epipole_diagnosis(args, got, expected) -> str:
    (F,) = args
    try:
        e1, e2 = (np.asarray(e, dtype=float) for e in got)
    except (TypeError, ValueError):
        return "return two homogeneous 3-vectors (e1, e2): e1 in image 1 and e2 in image 2"
    for e, name in ((e1, "e1"), (e2, "e2")):
        if e.shape != (3,):
            return (
                f"{name} has shape {e.shape}; return homogeneous 3-vectors: an epipole can be at infinity "
                f"(w = 0), which has no (u, v)"
            )
    ideal = abs(expected.e1[2]) < 1e-12 * np.linalg.norm(expected.e1)
    if ideal and not (np.isfinite(e1).all() and np.isfinite(e2).all()):
        return (
            "your epipoles hold inf or NaN: these cameras are parallel, so the epipoles are ideal points "
            "(w = 0, at infinity). Do not divide by w: return the null vectors of F as they are, "
            "homogeneous 3-vectors"
        )
    if same_up_to_scale(e1, expected.e2) and same_up_to_scale(e2, expected.e1):
        return (
            "you swapped them: e1 is the right null vector (F e1 = 0), e2 the left one (F^T e2 = 0)"
        )
    for e, name in ((e1, "e1"), (e2, "e2")):
        if not np.linalg.norm(e) > 1e-12:
            return (
                f"your {name} is the zero vector, which is no point at all (every vector is its multiple). "
                "A cross product of two rows (or columns) of F vanishes when they are parallel or zero, as "
                "they are here; take the null vector from the SVD F = U S V^T instead: e1 = last row of V^T, "
                "e2 = last column of U"
            )
    if same_up_to_scale(e2, expected.e1) and not same_up_to_scale(e1, expected.e2):
        return (
            "your e2 is e1, the null vector of F: e2 is the null vector of F^T (F^T e2 = 0), the last "
            "column of U in F = U S V^T, not the last row of V^T again"
        )
    r1 = np.linalg.norm(F @ e1) / max(np.linalg.norm(e1), 1e-300)
    r2 = np.linalg.norm(F.T @ e2) / max(np.linalg.norm(e2), 1e-300)
    bad = " and ".join(
        f"|{m}| / |{n}| = {r:.2g}"
        for r, m, n in ((r1, "F e1", "e1"), (r2, "F^T e2", "e2"))
        if r > 1e-9
    )
    return (
        f"{bad} (should be 0 up to rounding, about 1e-15): take the last row of V^T "
        f"(for e1) and the last column of U (for e2) from the SVD F = U S V^T"
    )


def _divided_by_w(F):
    with np.errstate(divide="ignore", invalid="ignore"):
        return tuple(e / e[2] for e in epipolar.epipoles(F))


def epipoles(F):
    """F e1 = 0 and F^T e2 = 0: the right and left singular vectors of F's zero singular value.

    Parameters
    ----------
    F : (3, 3) array_like
        A fundamental matrix (rank 2), x2^T F x1 = 0.

    Returns
    -------
    e1 : (3,) ndarray
        The epipole in image 1, homogeneous, unit length (w may be 0: an epipole at infinity).
    e2 : (3,) ndarray
        The epipole in image 2, likewise.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 9.2.4 (table 9.1).
    """
    U, _, Vt = np.linalg.svd(np.asarray(F, dtype=float))
    return Vt[-1], U[:, -1]  # homogeneous; w may be 0 (an epipole at infinity)


register_exercise(
    Exercise(
        name="epipoles",
        lesson="11",
        reference=epipolar.epipoles,
        cases=_epipole_cases,
        compare=_epipole_compare,
        diagnose=_epipole_diagnosis,
        wrong_variants=(
            (lambda F: tuple(reversed(epipolar.epipoles(F))), "swapped"),
            (lambda F: (np.linalg.svd(F)[2][0], np.linalg.svd(F)[0][:, 0]), "should be 0"),
            (lambda F: (np.cross(F[0], F[1]), np.cross(F[:, 0], F[:, 1])), "zero vector"),
            (lambda F: (np.linalg.svd(F)[2][-1], np.linalg.svd(F)[2][-1]), "null vector of F^T"),
            (_divided_by_w, "Do not divide by w"),
        ),
        teaching=epipoles,
    )
)


# --------------------------------------------------------------------------- depth from disparity


def _depth_cases():
    return [
        (np.array([80.0, 40.0, 16.0]), 800.0, 0.12),
        (np.array([[10.5, 64.0], [33.0, 7.25]]), 1200.0, 0.3),
    ]


def _depth_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    d, f, B = args
    g = np.asarray(got, dtype=float)
    if np.allclose(g, d * B / f) or np.allclose(g, f * d / B):
        return (
            "depth falls as disparity grows: Z = f B / d (similar triangles), not proportional to d"
        )
    if np.allclose(g, B / d):
        return "you forgot the focal length: d is in pixels and B in metres, so Z = f B / d with f in pixels"
    if np.allclose(g, f / d):
        return "you forgot the baseline: Z = f B / d, and B (metres) sets the units of Z"
    if np.allclose(g, f / (B * d)):
        return "you divided by the baseline: Z = f B / d, the baseline multiplies (a wider rig sees deeper)"
    if np.allclose(g, f * B // d):
        return "you used floor division (//), which rounds the depth down: Z = f B / d with true division"
    for off in (0.5, 1.0, -0.5, -1.0):
        if np.allclose(g, f * B / (d + off)):
            return (
                f"your depths are f B / (d {off:+g}): the disparity is a difference of two pixel columns, "
                "so no half-pixel or 1-based offset belongs in it; Z = f B / d"
            )
    ratio = g / expected
    if np.allclose(ratio, ratio.flat[0], rtol=1e-6):
        k = float(ratio.flat[0])
        if np.isclose(k, -1.0):
            return (
                "your depths are negative: the disparity d = u1 - u2 (left column minus right column) is "
                "positive for a point in front of the rig, and so is Z = f B / d; a sign flip (u2 - u1, "
                "or a minus in the formula) gives -Z"
            )
        for factor, hint in ((1000.0, "millimetres"), (100.0, "centimetres")):
            if np.isclose(k, factor) or np.isclose(k, 1 / factor):
                return (
                    f"your depths are {k:.4g} times the true ones: a unit slip ({hint}?). With f in pixels "
                    f"and B in metres, Z = f B / d comes out in metres"
                )
        return (
            f"your depths are {k:.4g} times the true ones at every pixel: the shape Z ~ 1/d is right, "
            f"a constant is wrong. Check the formula Z = f B / d"
        )
    i = np.unravel_index(np.argmax(np.abs(g - expected)), g.shape)
    return (
        f"at d = {d[i]:g} px (f = {f:g} px, B = {B:g} m) you give Z = {g[i]:.4g} m; f B / d = {expected[i]:.4g} m. "
        f"Z must be inversely proportional to d"
    )


def disparity_to_depth(d, f, B):
    """Similar triangles: d = f B / Z, so Z = f B / d (metres when B is in metres, f and d in pixels).

    Parameters
    ----------
    d : float or array_like
        Disparities, pixels (> 0).
    f : float
        The rectified cameras' focal length, pixels.
    B : float
        The baseline, m.

    Returns
    -------
    ndarray
        The depths Z = f B / d, m, of ``d``'s shape.
    """
    return f * B / np.asarray(d, dtype=float)


register_exercise(
    Exercise(
        name="disparity_to_depth",
        lesson="11",
        reference=disparity.disparity_to_depth,
        cases=_depth_cases,
        compare=same_array(rtol=1e-9),
        diagnose=_depth_diagnosis,
        wrong_variants=(
            (lambda d, f, B: f * d / B, "Z = f B / d"),
            (lambda d, f, B: B / d, "focal length"),
            (lambda d, f, B: 1000 * f * B / d, "unit slip"),
            (lambda d, f, B: f * B / (d + 1.0), "1-based offset"),
            (lambda d, f, B: f * B // d, "floor division"),
            (lambda d, f, B: f / (B * d), "divided by the baseline"),
            (lambda d, f, B: -f * B / d, "depths are negative"),
        ),
        teaching=disparity_to_depth,
    )
)


# --------------------------------------------------------------------------- E -> (R, t)


def _essential_cases():
    rng = np.random.default_rng(11)
    out = []
    for scale in (1.0, -2.5, 0.01):
        R = rotation_from_axis_angle(rng.normal(0, 0.3, 3))
        t = rng.normal(0, 1, 3)
        out.append((scale * epipolar.essential_matrix(R, t),))
    return out


def _pose_set(Rs, ts) -> list[tuple[np.ndarray, np.ndarray]]:
    return [
        (np.asarray(R, float), np.asarray(t, float) / np.linalg.norm(t))
        for R, t in zip(Rs, ts, strict=True)
    ]


def _essential_compare(got, expected) -> bool:
    try:
        Rs, ts = (np.asarray(a, dtype=float) for a in got)
    except (TypeError, ValueError):
        return False
    if (
        Rs.shape != (4, 3, 3)
        or ts.shape != (4, 3)
        or not (np.isfinite(Rs).all() and np.isfinite(ts).all())
    ):
        return False
    if not np.allclose(np.linalg.norm(ts, axis=1), 1.0, atol=1e-6):
        return False  # the prompt fixes the scale: unit vectors
    mine = _pose_set(Rs, ts)
    return all(
        any(np.allclose(R, Rg, atol=1e-8) and np.allclose(t, tg, atol=1e-8) for Rg, tg in mine)
        for R, t in _pose_set(*expected)
    )


def _essential_diagnosis(args, got, expected) -> str:
    (E,) = args
    try:
        Rs, ts = (np.asarray(a, dtype=float) for a in got)
    except (TypeError, ValueError):
        return "return two arrays (Rs, ts): Rs of shape (4, 3, 3) and ts of shape (4, 3), one row per candidate"
    if Rs.shape != (4, 3, 3) or ts.shape != (4, 3):
        return f"expected Rs (4, 3, 3) and ts (4, 3), got {Rs.shape} and {ts.shape}: four candidates, (R_a, ±t), (R_b, ±t)"
    gram = np.einsum("kji,kjl->kil", Rs, Rs)
    if not np.allclose(gram, np.eye(3), atol=1e-6):
        dets = np.linalg.det(Rs)
        kept_s = np.allclose(dets, 0, atol=1e-9)
        return (
            f"your R are not rotations (R^T R != I; det R = {', '.join(f'{x:.2g}' for x in dets)})"
            + (
                ": you kept the singular values, U diag(s) V^T. E's third singular value is 0, so that "
                "R is singular; R = U W V^T without S"
                if kept_s
                else ": R = U W V^T from the orthogonal U and V^T of the SVD, with no other factor"
            )
        )
    norms = np.linalg.norm(ts, axis=1)
    if not np.allclose(norms, 1.0, atol=1e-6):
        return (
            f"your t have lengths {', '.join(f'{x:.3g}' for x in norms)}: the prompt asks for unit vectors. "
            "E fixes t only up to scale, so return t = ±u3 (the last column of U, already of length 1), "
            "not a multiple of it"
        )
    dets = np.linalg.det(Rs)
    if np.any(dets < 0):
        return (
            "some of your R have det = -1 (reflections, not rotations): the SVD's U and V can be "
            "reflections; flip the sign of U (or V^T) when its determinant is -1, before forming U W V^T"
        )
    u3 = np.linalg.svd(E)[0][:, 2]
    v3 = np.linalg.svd(E)[2][2]
    if any(
        abs(abs(t @ v3) / np.linalg.norm(t) - 1) < 1e-8
        and abs(abs(t @ u3) / np.linalg.norm(t) - 1) > 1e-6
        for t in ts
    ):
        return (
            "your t is the right null vector of E (last row of V^T); t is the LEFT null vector, the last "
            "column of U: t^T E = t^T [t]x R = 0"
        )
    if any(
        abs(abs(t @ U_row) - 1) < 1e-8 and abs(abs(t @ u3) - 1) > 1e-6
        for t in ts
        for U_row in [np.linalg.svd(E)[0][2]]
    ):
        return "your t is the last ROW of U; t is the last COLUMN, U[:, 2] (t^T E = 0)"
    exp_set = _pose_set(*expected)
    centres = [(R, -R.T @ t) for R, t in exp_set]
    if all(
        any(np.allclose(R, Re, atol=1e-8) and np.allclose(t, c, atol=1e-8) for Re, c in centres)
        for R, t in _pose_set(Rs, ts)
    ) and not _essential_compare(got, expected):
        return (
            "your t is the camera centre C = -R^T t, not t: with X2 = R X1 + t, t is the left null vector "
            "of E (the last column of U), while C is where camera 2 sits in camera 1's frame"
        )
    if np.all(ts @ u3 > 0) or np.all(ts @ u3 < 0):
        return "all your t have the same sign: the four candidates are (R_a, +t), (R_a, -t), (R_b, +t), (R_b, -t)"
    expected_Rs = np.asarray(expected[0], dtype=float)
    if all(any(np.allclose(R.T, Re, atol=1e-8) for Re in expected_Rs) for R in Rs) and not all(
        any(np.allclose(R, Re, atol=1e-8) for Re in expected_Rs) for R in Rs
    ):
        return (
            "your rotations are transposed: V W^T U^T is (U W V^T)^T. E = [t]x R with R = U W V^T or "
            "U W^T V^T takes camera 1's coordinates to camera 2's (X2 = R X1 + t); did you write Vt.T @ W @ U.T, "
            "or decompose E^T?"
        )
    if len({tuple(np.round(R, 6).ravel()) for R in Rs}) < 2:
        return "your four candidates hold only one rotation: R_a = U W V^T and R_b = U W^T V^T (note the transpose)"
    return (
        "with E = U diag(1, 1, 0) V^T and W = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]: R in {U W V^T, U W^T V^T} "
        "and t = ±(last column of U)"
    )


def decompose_essential(E):
    """E = [t]x R = U diag(1, 1, 0) V^T gives two rotations U W V^T, U W^T V^T and t = ±u3.

    Parameters
    ----------
    E : (3, 3) array_like
        An essential matrix.

    Returns
    -------
    Rs : (4, 3, 3) ndarray
        The rotations of the four candidate poses: U W V^T twice, then U W^T V^T twice.
    ts : (4, 3) ndarray
        Their translations, unit length: u3, -u3, u3, -u3.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 9.6.2 (result 9.19).
    """
    U, _, Vt = np.linalg.svd(np.asarray(E, dtype=float))
    if np.linalg.det(U) < 0:  # make U and V rotations, so that U W V^T is one too
        U = -U
    if np.linalg.det(Vt) < 0:
        Vt = -Vt
    W = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    Ra, Rb = U @ W @ Vt, U @ W.T @ Vt
    t = U[:, 2]  # the left null vector of E: the baseline direction
    return np.stack([Ra, Ra, Rb, Rb]), np.stack([t, -t, t, -t])


def _no_det_fix(E):
    U, _, Vt = np.linalg.svd(
        E
    )  # numpy returns det(V^T) = -1 on the first test case, det(U) = -1 on the others
    W = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    Ra, Rb = U @ W @ Vt, U @ W.T @ Vt
    return np.stack([Ra, Ra, Rb, Rb]), np.stack([U[:, 2], -U[:, 2], U[:, 2], -U[:, 2]])


def _kept_singular_values(E):
    U, S, Vt = np.linalg.svd(E)
    W = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    Ra, Rb = U @ W @ np.diag(S) @ Vt, U @ W.T @ np.diag(S) @ Vt
    return np.stack([Ra, Ra, Rb, Rb]), np.stack([U[:, 2], -U[:, 2], U[:, 2], -U[:, 2]])


def _right_null_vector(E):
    Rs, _ = decompose_essential(E)
    v3 = np.linalg.svd(E)[2][2]
    return Rs, np.stack([v3, -v3, v3, -v3])


register_exercise(
    Exercise(
        name="decompose_essential",
        lesson="11",
        reference=epipolar.decompose_essential_matrix,
        cases=_essential_cases,
        compare=_essential_compare,
        diagnose=_essential_diagnosis,
        wrong_variants=(
            (_no_det_fix, "det = -1"),
            (_right_null_vector, "LEFT null vector"),
            (
                lambda E: (decompose_essential(E)[0], 7.3 * decompose_essential(E)[1]),
                "unit vectors",
            ),
            (_kept_singular_values, "kept the singular values"),
            (
                lambda E: (
                    lambda Rs, ts: (
                        Rs,
                        np.abs(ts @ np.linalg.svd(E)[0][:, 2])[:, None] * np.linalg.svd(E)[0][:, 2],
                    )
                )(*decompose_essential(E)),
                "same sign",
            ),
            (
                lambda E: (lambda Rs, ts: (np.stack([Rs[0]] * 4), ts))(*decompose_essential(E)),
                "only one rotation",
            ),
            (
                lambda E: (lambda Rs, ts: (np.transpose(Rs, (0, 2, 1)), ts))(
                    *decompose_essential(E)
                ),
                "rotations are transposed",
            ),
        ),
        teaching=decompose_essential,
    )
)


# --------------------------------------------------------------------------- the bad-pixel rate


def _bad_pixel_cases():
    rng = np.random.default_rng(29)
    truth = rng.uniform(8, 60, (40, 50))
    d = truth + rng.normal(0, 0.6, truth.shape)
    gross = rng.random(truth.shape) < 0.1  # mismatches, too near and too far
    d[gross] += rng.choice([-9.0, 7.0], gross.sum())
    d[:, :6] = np.nan  # no match: the search range's blind band
    truth[rng.random(truth.shape) < 0.07] = np.nan  # no ground truth
    d[5, 10], truth[5, 10] = 21.0, 20.0  # an error of exactly the threshold is not bad
    small = (
        np.array([[10.0, 12.5, np.nan, 30.0], [5.0, 7.5, 9.0, 40.0]]),
        np.array([[10.2, 11.0, 9.0, np.nan], [6.5, 7.0, 11.5, 38.0]]),
    )
    return [(d, truth, 1.0), (d, truth, 2.0), (*small, 1.0)]


def _bad_pixel_diagnosis(args, got, expected) -> str:
    d, truth, tau = (np.asarray(a, dtype=float) for a in args)
    try:
        g = float(got)
    except (TypeError, ValueError):
        return f"return one number, the fraction of bad pixels (a float in [0, 1]); got {type(got).__name__}"
    scored = np.isfinite(d) & np.isfinite(truth)
    with np.errstate(invalid="ignore"):
        err = d - truth
        over_all = np.mean(np.abs(err) > tau)
        known = np.isfinite(truth)
        unmatched_bad = np.sum(known & ((np.abs(err) > tau) | ~np.isfinite(d))) / known.sum()
    if np.isclose(g, 100 * expected):
        return "your rate is in percent: return the fraction in [0, 1] (0.07, not 7)"
    if np.isclose(g, np.mean(err[scored] > tau)):
        return (
            "you counted only the errors d - d_true > threshold: a match too near is as bad as one too "
            "far; use the absolute error |d - d_true|"
        )
    if np.isclose(g, np.mean(np.abs(err[scored]) >= tau)):
        return "an error of exactly the threshold is not bad: the rule is |d - d_true| > threshold, strictly"
    if np.isclose(g, over_all):
        return (
            "you averaged over every pixel: NaN > threshold is False, so the pixels without a match or "
            "without a true disparity counted as good. Score only the pixels where both are finite"
        )
    n_bad = np.sum(np.abs(err[scored]) > tau)
    truth_only = n_bad / known.sum()
    if np.isclose(g, truth_only):
        return (
            "you divided by every pixel with a true disparity, so the pixels without a match counted as "
            "good: that is Middlebury's bad% (section 6), which reports the holes separately. This exercise "
            "asks for the rate over the pixels where both d and d_true are finite"
        )
    if np.isclose(g, 1 - expected):
        return "you returned the fraction of GOOD pixels (|d - d_true| <= threshold): the bad-pixel rate is 1 minus that"
    if np.isclose(g, n_bad):
        return f"you returned the count of bad pixels ({n_bad}): divide by the number of scored pixels for a fraction"
    if np.isclose(g, np.mean((err[scored]) ** 2 > tau)):
        return "you compared the squared error with the threshold: the rule is |d - d_true| > threshold (pixels)"
    if np.isclose(g, unmatched_bad):
        return (
            "you counted the pixels without a match as bad: this rate is over the matched pixels that "
            "have a true disparity (the fraction matched is reported beside it)"
        )
    return (
        f"expected {expected:.4g}, got {g:.4g}: the fraction, among the pixels where both d and d_true "
        "are finite, whose |d - d_true| exceeds the threshold"
    )


def bad_pixel_rate(d, d_true, threshold):
    """Score the pixels with both a match and a truth; bad when the absolute error exceeds the threshold.

    Parameters
    ----------
    d, d_true : (H, W) array_like
        The matcher's and the true disparity, pixels; NaN where there is none.
    threshold : float
        The error, pixels, above which a pixel is bad.

    Returns
    -------
    float
        The fraction of scored pixels with ``|d - d_true| > threshold``.
    """
    d, d_true = np.asarray(d, dtype=float), np.asarray(d_true, dtype=float)
    scored = np.isfinite(d) & np.isfinite(d_true)
    return np.mean(np.abs(d[scored] - d_true[scored]) > threshold)


register_exercise(
    Exercise(
        name="bad_pixel_rate",
        lesson="11",
        reference=disparity.bad_pixel_rate,
        cases=_bad_pixel_cases,
        compare=lambda got, expected: np.ndim(got) == 0 and np.isclose(float(got), expected),
        diagnose=_bad_pixel_diagnosis,
        wrong_variants=(
            (lambda d, t, tau: 100 * disparity.bad_pixel_rate(d, t, tau), "percent"),
            (
                lambda d, t, tau: np.nanmean(np.where(np.isfinite(d - t), d - t > tau, np.nan)),
                "absolute error",
            ),
            (
                lambda d, t, tau: np.mean(np.abs(np.asarray(d) - t) > tau),
                "NaN > threshold is False",
            ),
            (
                lambda d, t, tau: np.mean(np.abs(d - t)[np.isfinite(d - t)] >= tau),
                "exactly the threshold",
            ),
            (
                lambda d, t, tau: (
                    np.sum(np.isfinite(t) & ~(np.abs(d - t) <= tau)) / np.isfinite(t).sum()
                ),
                "without a match as bad",
            ),
            (
                lambda d, t, tau: np.sum(np.abs(d - t) > tau) / np.isfinite(t).sum(),
                "Middlebury's bad%",
            ),
            (lambda d, t, tau: 1 - disparity.bad_pixel_rate(d, t, tau), "GOOD pixels"),
            (
                lambda d, t, tau: float(np.sum(np.abs(d - t)[np.isfinite(d - t)] > tau)),
                "count of bad pixels",
            ),
        ),
        teaching=bad_pixel_rate,
    )
)
