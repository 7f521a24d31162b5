"""Lesson 05's first exercise.

The weak-perspective camera P_inf about a reference point X0 ([1]_, section 6.3.1), every depth
replaced by the constant d0 of X0.

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 6.3.1 (affine cameras).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import affine as af
from .._answers import same_array, shape_problem
from .._core import Exercise, Mistake, first_mistake, mistake_variant, register_exercise
from ._approx_common import (
    P_INF,
    approx_cases,
    common_slip,
    image_of_X0_as_translation,
    last_row_cause,
    match_mistake,
    nearly_right_cause,
    p_inf,
    principal_point_cause,
    proportional,
    same_to_rounding,
    transposed_cause,
    v_flip_cause,
    what_differs,
    without_skew,
)


def _context(camera, X0):
    """What the rows of :data:`_MISTAKES` read: the camera, X0 and its depth d0."""
    K, R, t = camera.K, camera.R, camera.t
    return SimpleNamespace(camera=camera, X0=X0, K=K, R=R, t=t, d0=R[2] @ X0 + t[2])


def _last_column_undivided(s):
    P = p_inf(s.K, s.R, s.t, s.d0)
    P[:2, 3] *= s.d0
    return P


def _only_row3(s):
    P = s.camera.P / s.d0
    P[2] = [0.0, 0.0, 0.0, 1.0]
    return P


def _no_division(s):
    P = p_inf(s.K, s.R, s.t, s.d0) * s.d0
    P[2] = [0.0, 0.0, 0.0, 1.0]
    return P


def _translation_not_through_K(s):
    """The last column written as (t1, t2) / d0 + (cx, cy): the principal point added, the focal lengths not."""
    P = p_inf(s.K, s.R, s.t, s.d0)
    P[:2, 3] = s.t[:2] / s.d0 + s.K[:2, 2]
    return P


def _depth_in_mm(s):
    """The depth of X0 scaled by 1000, as r3 . (1000 X0) + t3 gives it."""
    return s.R[2] @ (1000 * np.asarray(s.X0, dtype=float)) + s.t[2]


_MISTAKES = (
    Mistake(
        "last column undivided",
        _last_column_undivided,
        "the 2x3 block is right, but the last column is K (t1, t2, d0) undivided: divide "
        f"all of K E by d0, its last column too: that column is K (t1, t2, d0) / d0; {P_INF}.",
    ),
    Mistake(
        "only P's third row",
        _only_row3,
        "you replaced only P's third row: P's first two rows also hold the depth, through K's third "
        f"column times r3 . X + t3. Replace the depth inside [R | t] before K multiplies: {P_INF}.",
    ),
    Mistake(
        "top rows undivided",
        _no_division,
        "you set the last row to (0, 0, 0, 1) but did not divide the top two rows by d0, so the image "
        f"is d0 times too large about the origin: divide the whole matrix, {P_INF}.",
    ),
    Mistake(
        "principal point divided",
        lambda s: (
            p_inf(s.K, s.R, s.t, s.d0)
            - np.c_[np.zeros((3, 3)), np.r_[s.K[:2, 2], 0.0]] * (s.d0 - 1) / s.d0
        ),
        "the principal point is divided by d0: in K [[r1, t1], [r2, t2], [0, d0]] the (3, 4) entry is d0, so after "
        f"dividing by d0 K's third column (cx, cy) is added as it is; {P_INF}.",
    ),
    Mistake(
        "translation not through K",
        _translation_not_through_K,
        "the last column is (t1, t2) / d0 + (cx, cy): K's focal lengths (and skew) must scale (t1, t2) too, "
        f"since the column is K (t1, t2, d0) / d0; {P_INF}.",
    ),
    Mistake(
        "para-perspective",
        lambda s: af.paraperspective_approximation(s.camera, s.X0),
        "this is the para-perspective camera (section 2, the next exercise), which projects along the line of "
        f"sight to X0; this exercise asks for P_inf, every depth replaced by d0 with no r3 terms in M2: {P_INF}.",
    ),
    Mistake(
        "X0 in millimetres",
        lambda s: p_inf(s.K, s.R, s.t, _depth_in_mm(s)),
        lambda s: (
            f"X0 was scaled by 1000 (millimetres?): its depth came out as r3 . (1000 X0) + t3 = "
            f"{_depth_in_mm(s):.4g} m where X0 is {s.d0:.4g} m deep. The camera's t and X0 are both in metres; use X0 "
            f"as given: {P_INF}."
        ),
    ),
)
"""Mistakes only this exercise meets (the shared ones are :data:`COMMON_MISTAKES`), as the matrices they give."""


def _approx_diagnosis(args, got, expected) -> str:
    problem = transposed_cause(got, expected) or shape_problem(got, expected)
    if problem:
        return problem + ". Return the 3x4 affine camera."
    camera, X0 = args
    g = np.asarray(got, dtype=float)
    d0 = float(camera.R[2] @ X0 + camera.t[2])
    cause = first_mistake(_MISTAKES, _context(camera, X0), g, same_to_rounding) or match_mistake(
        g, camera, X0, lambda d: (0.0, 0.0), P_INF
    )
    cause = cause or nearly_right_cause(g, expected, P_INF)
    if cause:
        return cause
    if not np.allclose(g[2], [0.0, 0.0, 0.0, 1.0], atol=1e-9):
        if proportional(g, camera.P):
            return (
                "this is the perspective camera P = K [R | t] itself (up to scale): its last row (r3, t3) gives "
                f"every point its own depth. The affine camera replaces that row by the constant depth d0: {P_INF}."
            )
        return last_row_cause(g, d0, expected, P_INF, camera.R[2], name="P_inf")
    return _approx_top_rows_cause(g, expected, camera, X0, d0)


def _approx_top_rows_cause(g, expected, camera, X0, d0) -> str:
    """Why the top two rows are wrong when the last row is right.

    A cause only where the answer is exactly what that mistake gives, else what differs.
    """
    M, m = g[:2, :3], g[:2, 3]
    M_e, m_e = expected[:2, :3], expected[:2, 3]
    c = camera.K[:2, 2]
    k = float(np.sum(M * M_e) / np.sum(M_e * M_e))  # the best scalar with M = k M_e
    if (
        not np.isclose(k, 1.0, rtol=1e-6)
        and k != 0
        and same_to_rounding(M, k * M_e)
        and same_to_rounding(m, c + k * (m_e - c))
    ):
        used = d0 / k
        unit = {1000.0: " (millimetres?)", 0.001: " (kilometres?)"}.get(round(used / d0, 6), "")
        sign = (
            " (negative: a point in front of the camera has a positive depth)" if used < 0 else ""
        )
        return (
            f"your matrix is P_inf for the depth d0 = {used:.4g} m{unit}{sign}, but X0 is {d0:.4g} m deep: "
            f"d0 = r3 . X0 + t3, the depth of the reference point along the optical axis."
        )
    if same_to_rounding(g[[1, 0]], expected[:2]):
        return "the two rows are swapped: row 1 gives u (from r1 and fx), row 2 gives v (from r2 and fy)."
    slip = v_flip_cause(g, expected) or image_of_X0_as_translation(g, expected, camera, X0)
    if slip:
        return slip
    if same_to_rounding(M, M_e):
        if same_to_rounding(m, m_e - c):
            return (
                f"the principal point is missing from the last column: K's third column (cx, cy, 1) times d0, "
                f"divided by d0, adds (cx, cy); {P_INF}."
            )
        if same_to_rounding(m, c):
            return f"the last column holds only (cx, cy): t1 and t2 are missing from it; {P_INF}."
        offset = m - m_e
        slip = principal_point_cause(offset, c)
        if slip:
            return slip
    return f"{what_differs(g, expected, camera, X0)}. Compare each block with {P_INF}."


def _mistake(name):
    """The shared slip ``name`` (a row of COMMON_MISTAKES), built for weak perspective, as a student's function."""
    return common_slip(name, lambda camera, X0, K, R, t, d0: p_inf(K, R, t, d0))


def _approx_unnormalised(camera, X0):
    d0 = camera.R[2] @ X0 + camera.t[2]
    return p_inf(camera.K, camera.R, camera.t, d0) * d0


def _approx_only_block_divided(camera, X0):
    """K E with only its 2x3 block divided by d0 (P[:, :3] /= d0), then the last row set to (0, 0, 0, 1)."""
    K, R, t = camera.K, camera.R, camera.t
    E = np.zeros((3, 4))
    E[:2, :3], E[:2, 3], E[2, 3] = R[:2], t[:2], R[2] @ X0 + t[2]
    P = K @ E
    P[:, :3] /= E[2, 3]
    P[2] = [0.0, 0.0, 0.0, 1.0]
    return P


def _approx_r3_kept(camera, X0):
    """E = [R | t] with only its (3, 4) entry set to d0: the third row keeps r3."""
    d0 = camera.R[2] @ X0 + camera.t[2]
    E = np.c_[camera.R, camera.t]
    E[2, 3] = d0
    return camera.K @ E / d0


def _approx_e_last_one(camera, X0):
    """E's (3, 4) entry 1 instead of d0, then divided by d0: last row (0, 0, 0, 1/d0)."""
    E = np.zeros((3, 4))
    E[:2, :3], E[:2, 3], E[2, 3] = camera.R[:2], camera.t[:2], 1.0
    return camera.K @ E / (camera.R[2] @ X0 + camera.t[2])


def _approx_fx_fy_only(camera, X0):
    """Built entry by entry from fx, fy, cx, cy: the skew K[0, 1] is lost."""
    K, R, t = camera.K, camera.R, camera.t
    d0 = R[2] @ X0 + t[2]
    P = np.zeros((3, 4))
    P[0, :3], P[0, 3] = K[0, 0] * R[0] / d0, K[0, 0] * t[0] / d0 + K[0, 2]
    P[1, :3], P[1, 3] = K[1, 1] * R[1] / d0, K[1, 1] * t[1] / d0 + K[1, 2]
    P[2, 3] = 1.0
    return P


def _approx_no_skew(camera, X0):
    return p_inf(without_skew(camera.K), camera.R, camera.t, camera.R[2] @ X0 + camera.t[2])


def _approx_image_centre(centre):
    """The principal point replaced by a fixed image centre (320, 240) or (319.5, 239.5)."""

    def wrong(camera, X0):
        K = camera.K.copy()
        K[:2, 2] = centre
        return p_inf(K, camera.R, camera.t, camera.R[2] @ X0 + camera.t[2])

    return wrong


def _approx_shifted(shift):
    return lambda camera, X0: (
        af.affine_approximation(camera, X0) + np.c_[np.zeros((3, 3)), [shift, shift, 0.0]]
    )


def _approx_no_t(camera, X0):
    """t1, t2 left out of the last column."""
    t = np.array([0.0, 0.0, camera.t[2]])
    return p_inf(camera.K, camera.R, t, camera.R[2] @ X0 + camera.t[2])


def _approx_centred_in_place(camera, X0):
    """Works relative to the camera centre by changing the caller's X0 in place."""
    X0 -= camera.centre
    return p_inf(camera.K, camera.R, camera.t, camera.R[2] @ X0)


def _approx_K_in_place(camera, X0):
    """Divides camera.K in place (camlab's cameras keep their arrays read-only)."""
    K = camera.K
    K /= camera.R[2] @ X0 + camera.t[2]
    return p_inf(K, camera.R, camera.t, 1.0)


def affine_approximation(camera, X0):
    """Give every point the depth d0 of the reference point X0 (H&Z §6.3.1), last row (0, 0, 0, 1).

    Parameters
    ----------
    camera : camlab.camera.Camera
        The perspective camera (K, R, t).
    X0 : (3,) ndarray
        The reference point, world coordinates, in front of the camera.

    Returns
    -------
    (3, 4) ndarray
        The affine (weak-perspective) camera K [[R's first two rows, t's first two], [0, 0, 0, d0]] / d0.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 6.3.1.
    """
    K, R, t = camera.K, camera.R, camera.t
    d0 = R[2] @ X0 + t[2]  # depth of X0 in the camera frame
    E = np.zeros((3, 4))
    E[:2, :3], E[:2, 3] = R[:2], t[:2]
    E[2, 3] = d0  # the third row no longer depends on the point
    return K @ E / d0


register_exercise(
    Exercise(
        name="affine_approximation",
        lesson="05",
        reference=af.affine_approximation,
        cases=approx_cases,
        compare=same_array(rtol=1e-7, atol=1e-7),
        diagnose=_approx_diagnosis,
        ndarray_only=True,
        wrong_variants=(
            (_approx_unnormalised, "did not divide by d0"),
            (
                mistake_variant(_MISTAKES, "translation not through K", _context),
                "must scale (t1, t2) too",
            ),
            (_mistake("fx for both focal lengths"), "pixels need not be square"),
            (_mistake("fx and fy swapped"), "fx and fy are swapped"),
            (_mistake("cx and cy swapped"), "cx and cy are swapped"),
            (_mistake("fx, fy and cx, cy swapped"), "width and height are swapped"),
            (
                lambda camera, X0: np.round(af.affine_approximation(camera, X0), 6),
                "the formula is right",
            ),
            (lambda camera, X0: camera.P, "perspective camera P = K [R | t] itself"),
            (lambda camera, X0: -af.affine_approximation(camera, X0), "minus the answer"),
            (_mistake("d0 = t3"), "depth of the world origin"),
            (_mistake("d0 lacks t3"), "lacks t3"),
            (_mistake("d0 = r3 . X0 - t3"), "t3 has the wrong sign"),
            (_mistake("d0 = world z"), "world z"),
            (_mistake("d0 = distance"), "Euclidean distance"),
            (_mistake("d0 = |t|"), "|t|"),
            (_mistake("d0 = -d0"), "wrong sign: a point in front"),
            (_mistake("no K"), "left out K"),
            (_mistake("K^-1"), "K^-1"),
            (_mistake("no principal point"), "principal point is missing"),
            (_mistake("K.T"), "K.T"),
            (_mistake("R.T"), "R.T"),
            (_mistake("R.T, in d0 too"), "R.T"),
            (_mistake("t1, t2 sign"), "t1 and t2 have the wrong sign"),
            (_mistake("t in millimetres"), "millimetres"),
            (_approx_no_skew, "skew K[0, 1] is missing"),
            (_mistake("d0 = world z of X0 - C"), "world z of X0 - C"),
            (_mistake("t sign everywhere"), "t has the wrong sign everywhere"),
            (_mistake("t as the centre"), "t as the camera centre"),
            (
                mistake_variant(_MISTAKES, "last column undivided", _context),
                "last column is K (t1, t2, d0) undivided",
            ),
            (_approx_only_block_divided, "last column is K (t1, t2, d0) undivided"),
            (
                lambda camera, X0: p_inf(
                    camera.K, camera.R, camera.t, -0.5 * (camera.R[2] @ X0 + camera.t[2])
                ),
                "negative: a point in front",
            ),
            (mistake_variant(_MISTAKES, "only P's third row", _context), "only P's third row"),
            (
                mistake_variant(_MISTAKES, "top rows undivided", _context),
                "did not divide the top two rows",
            ),
            (
                mistake_variant(_MISTAKES, "principal point divided", _context),
                "principal point is divided by d0",
            ),
            (
                lambda camera, X0: p_inf(
                    camera.K, camera.R, camera.t, 1000 * (camera.R[2] @ X0 + camera.t[2])
                ),
                "millimetres?",
            ),
            (
                lambda camera, X0: p_inf(
                    camera.K, camera.R, camera.t, camera.R[2] @ X0 + camera.t[2] + 0.5
                ),
                "is P_inf for the depth",
            ),
            (_approx_e_last_one, "the (3, 4) entry"),
            (_approx_r3_kept, "the last row still holds r3"),
            (_approx_fx_fy_only, "skew K[0, 1] is missing"),
            (
                lambda camera, X0: af.paraperspective_approximation(camera, X0),
                "para-perspective camera",
            ),
            (lambda camera, X0: af.affine_approximation(camera, X0)[[1, 0, 2]], "rows are swapped"),
            (
                lambda camera, X0: af.affine_approximation(camera, X0) * [[1], [-1], [1]],
                "gives -v instead",
            ),
            (
                lambda camera, X0: (
                    np.diag([1.0, -1.0, 1.0]) @ af.affine_approximation(camera, X0)
                    + [[0, 0, 0, 0], [0, 0, 0, 479], [0, 0, 0, 0]]
                ),
                "gives 479 - v instead",
            ),
            (_approx_no_t, "t1 and t2 are missing"),
            (_approx_image_centre((320.0, 240.0)), "or you used (320, 240), half the image size"),
            (
                _approx_image_centre((319.5, 239.5)),
                "(319.5, 239.5), the centre of a 640 x 480 image as the principal",
            ),
            (_approx_shifted(0.5), "half a pixel"),
            (_approx_shifted(-1.0), "one pixel"),
            (
                lambda camera, X0: np.round(af.affine_approximation(camera, X0), 1),
                "entries of the 2x3 block differ",
            ),
            (
                lambda camera, X0: af.affine_approximation(camera, X0).tolist(),
                "you returned a list",
            ),
            (
                lambda camera, X0: affine_approximation(camera, 1000 * np.asarray(X0)),
                "scaled by 1000 (millimetres?)",
            ),
            (_approx_centred_in_place, "changed its input `X0` in place"),
            (_approx_K_in_place, "camera.K.copy()"),
        ),
        teaching=affine_approximation,
    )
)
