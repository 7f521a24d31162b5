"""Lesson 05's second exercise.

The para-perspective camera about X0, perspective linearised at X0, which projects along the line of
sight to X0 (section 2).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import affine as af
from .._answers import same_array, shape_problem
from .._core import Exercise, Mistake, first_mistake, mistake_variant, register_exercise
from ._approx_common import (
    P_PARA,
    approx_cases,
    common_slip,
    depth_and_ab,
    image_of_X0_as_translation,
    last_row_cause,
    match_mistake,
    nearly_right_cause,
    p_para,
    principal_point_cause,
    same_to_rounding,
    transposed_cause,
    v_flip_cause,
    what_differs,
    without_skew,
)

# -- paraperspective_approximation -----------------------------------------------------------------


def _para_outer_reshaped(camera, X0):
    """The block of a r3 and b r3 built as np.outer(R[2], ab) (3, 2), reshaped to (2, 3): scrambled."""
    K, R, t = camera.K, camera.R, camera.t
    x_c = R @ X0 + t
    d0, ab = x_c[2], x_c[:2] / x_c[2]
    E = np.zeros((3, 4))
    E[:2, :3], E[:2, 3], E[2, 3] = (
        R[:2] - np.outer(R[2], ab).reshape(2, 3),
        t[:2] - ab * (t[2] - d0),
        d0,
    )
    return K @ E / d0


def _context(camera, X0):
    """What the rows of :data:`_MISTAKES` read.

    The camera, X0, its camera-frame position x_c, depth d0 and normalised position (a, b), its
    pixels, and the numbers the slips take instead.
    """
    K, R, t = camera.K, camera.R, camera.t
    x_c = R @ X0 + t
    return SimpleNamespace(
        camera=camera,
        X0=X0,
        K=K,
        R=R,
        t=t,
        x_c=x_c,
        d0=float(x_c[2]),
        ab=x_c[:2] / x_c[2],
        uv_X0=camera.project(X0),
        x_mm=R @ (1000 * np.asarray(X0, dtype=float)) + t,
        ray=np.asarray(X0, dtype=float)
        - camera.centre,  # the line of sight to X0, in world coordinates
    )


def _para(s, ab, t_term=None):
    """K E / d0 for this input with (a, b) = ``ab`` (the slips below change only (a, b) or the t term)."""
    return p_para(s.K, s.R, s.t, s.d0, ab, t_term=t_term)


_UNROTATED = (
    "you took (a, b) from X0 - C, the line of sight in world coordinates: (a, b) is X0's position in "
    "the camera frame, so rotate the ray first, R (X0 - C) = R X0 + t = x_c, then (a, b) = x_c[:2] / "
    "x_c[2]; the world's axes are not the camera's."
)

_MISTAKES = (
    Mistake(
        "weak perspective",
        lambda s: af.affine_approximation(s.camera, s.X0),
        "this is the weak-perspective camera P_inf (the first exercise): para-perspective's normalised image "
        "(x - a (z - d0)) / d0 also depends on the depth z = r3 . X + t3, so E's first two rows gain r3 terms "
        "and a constant, with (a, b) = (x_c, y_c) / d0 X0's normalised position.",
    ),
    Mistake(
        "(a, b) sign",
        lambda s: _para(s, -s.ab),
        "the a and b terms have the wrong sign: the normalised image is "
        "(x - a (z - d0)) / d0, so E's rows are r1 - a r3 and r2 - b r3.",
    ),
    Mistake(
        "a and b swapped",
        lambda s: _para(s, s.ab[::-1]),
        "a and b are swapped: a = x_c / d0 goes with the first row (u), "
        "b = y_c / d0 with the second (v).",
    ),
    Mistake(
        "no t3 - d0 term",
        lambda s: _para(s, s.ab, t_term=0.0),
        "the last column lacks -(a, b) (t3 - d0): z - d0 = r3 . X + t3 - d0 in camera coordinates, so the "
        "a and b terms carry the constant t3 - d0 into E's last column.",
    ),
    Mistake(
        "t3 term without d0",
        lambda s: _para(s, s.ab, t_term=s.t[2]),
        "the last column has -(a, b) t3 where it needs -(a, b) (t3 - d0): the -d0 of z - d0 is missing there.",
    ),
    Mistake(
        "d0 term without t3",
        lambda s: _para(s, s.ab, t_term=-s.d0),
        "the last column has +(a, b) d0 where it needs -(a, b) (t3 - d0): the t3 of z = r3 . X + t3 is missing.",
    ),
    Mistake(
        "t3 - d0 term sign",
        lambda s: _para(s, s.ab, t_term=s.d0 - s.t[2]),
        "the last column has +(a, b) (t3 - d0) where it needs -(a, b) (t3 - d0): the rows are right, but the sign of "
        "the a and b terms in E's last column is flipped.",
    ),
    Mistake(
        "(a, b) in pixels",
        lambda s: _para(s, s.uv_X0),
        "you used X0's pixel coordinates as (a, b): they are its normalised image "
        "position, (x_c, y_c) / d0 with x_c = R X0 + t (metres over metres), or "
        "K^-1 (u, v, 1).",
    ),
    Mistake(
        "(a, b) as pixel offsets",
        lambda s: _para(s, s.uv_X0 - s.K[:2, 2]),
        "your (a, b) are X0's pixel offsets from the principal point, (u - cx, v - cy): (a, b) are normalised "
        "coordinates, those offsets divided by the focal lengths (K^-1 (u, v, 1)), or simply (x_c, y_c) / d0 "
        "with x_c = R X0 + t.",
    ),
    Mistake(
        "(a, b) not divided by d0",
        lambda s: _para(s, s.x_c[:2]),
        "your (a, b) are (x_c, y_c), X0's camera coordinates in metres: divide them by its depth, "
        "(a, b) = (x_c, y_c) / d0 with d0 = x_c[2].",
    ),
    Mistake(
        "(a, b) from world coordinates over d0",
        lambda s: _para(s, s.X0[:2] / s.d0),
        "you took (a, b) from X0's world coordinates: they come from its camera-frame coordinates, "
        "x_c = R X0 + t, (a, b) = x_c[:2] / x_c[2].",
    ),
    Mistake(
        "(a, b) from R X0 without t",
        lambda s: _para(s, (s.R @ s.X0)[:2] / (s.R @ s.X0)[2]),
        "your (a, b) come from R X0 without the translation: X0's camera coordinates are x_c = R X0 + t, "
        "then (a, b) = x_c[:2] / x_c[2].",
    ),
    Mistake(
        "(a, b) from R X0 without t, over d0",
        lambda s: _para(s, (s.R @ s.X0)[:2] / s.d0),
        "your (a, b) come from R X0 without the translation: X0's camera coordinates are x_c = R X0 + t, "
        "then (a, b) = x_c[:2] / x_c[2].",
    ),
    Mistake(
        "(a, b) without skew",
        lambda s: _para(s, (s.uv_X0 - s.K[:2, 2]) / np.diag(s.K)[:2]) if s.K[0, 1] else None,
        lambda s: (
            f"(a, b) = ((u - cx) / fx, (v - cy) / fy) ignores this camera's skew K[0, 1] = {s.K[0, 1]:g}: "
            "take (a, b) = (x_c, y_c) / d0 from x_c = R X0 + t, or the first two entries of K^-1 (u, v, 1)."
        ),
    ),
    Mistake(
        "(a, b) from world coordinates",
        lambda s: _para(s, s.X0[:2] / s.X0[2]),
        "you took (a, b) from X0's world coordinates: they come from its "
        "camera-frame coordinates, x_c = R X0 + t, (a, b) = x_c[:2] / x_c[2].",
    ),
    Mistake(
        "(a, b) over the distance",
        lambda s: _para(s, s.x_c[:2] / np.linalg.norm(s.x_c)),
        "you divided (x_c, y_c) by X0's distance |x_c|; (a, b) divide by its depth, x_c[2] = d0.",
    ),
    Mistake(
        "(a, b) over fx",
        lambda s: _para(s, (s.uv_X0 - s.K[:2, 2]) / s.K[0, 0]) if s.K[0, 0] != s.K[1, 1] else None,
        lambda s: (
            f"(a, b) = (u - cx, v - cy) / fx divides both offsets by fx, but this camera's fy = "
            f"{s.K[1, 1]:g} px is not fx = {s.K[0, 0]:g} px: b = (v - cy) / fy. Safer: (a, b) = (x_c, y_c) / d0 "
            "from x_c = R X0 + t."
        ),
    ),
    Mistake(
        "(a, b) over d0 twice",
        lambda s: _para(s, s.ab / s.d0),
        "you divided (x_c, y_c) by d0 twice: (a, b) = (x_c, y_c) / d0 once, and "
        "the whole matrix is divided by d0 at the end.",
    ),
    Mistake(
        "pixel form without the principal point",
        lambda s: (
            af.affine_approximation(s.camera, s.X0)
            - np.r_[np.outer(s.uv_X0, np.r_[s.R[2], s.t[2] - s.d0]) / s.d0, np.zeros((1, 4))]
        ),
        "you wrote the pixel form P_inf - x_X0 (r3, t3 - d0) / d0 with X0's pixel position: it needs the offset from "
        "the principal point, P_para = P_inf - (x_X0 - x0) (r3, t3 - d0) / d0 in the top two rows (K (a, b, 0) "
        "is x_X0 - x0).",
    ),
    Mistake(
        "X0 in millimetres",
        lambda s: p_para(s.K, s.R, s.t, s.x_mm[2], s.x_mm[:2] / s.x_mm[2]),
        lambda s: (
            f"X0 was scaled by 1000 (millimetres?): its depth came out as {s.x_mm[2]:.4g} m where X0 is "
            f"{s.d0:.4g} m deep, and (a, b) as {s.x_mm[0] / s.x_mm[2]:.4g}, {s.x_mm[1] / s.x_mm[2]:.4g} for "
            f"{s.ab[0]:.4g}, {s.ab[1]:.4g}. The camera's t and X0 are both in metres; use X0 as given."
        ),
    ),
    Mistake("unrotated ray", lambda s: _para(s, s.ray[:2] / s.ray[2]), _UNROTATED),
    Mistake("unrotated ray over d0", lambda s: _para(s, s.ray[:2] / s.d0), _UNROTATED),
    Mistake(
        "a twice",
        lambda s: _para(s, (s.ab[0], s.ab[0])),
        "both rows use a: the second row is r2 - b r3 with its own "
        "b = y_c / d0 (and t2 - b (t3 - d0)).",
    ),
    Mistake(
        "b twice",
        lambda s: _para(s, (s.ab[1], s.ab[1])),
        "both rows use b: the first row is r1 - a r3 with a = x_c / d0 (and t1 - a (t3 - d0)).",
    ),
    Mistake(
        "outer product reshaped",
        lambda s: _para_outer_reshaped(s.camera, s.X0),
        "np.outer(R[2], ab) is (3, 2), and reshaping it to (2, 3) scrambles its entries: the block of a r3 and "
        "b r3 is np.outer(ab, R[2]) (2, 3), or ab[:, None] * R[2].",
    ),
    Mistake(
        "(a, b) as angles",
        lambda s: _para(s, np.arctan(s.ab)),
        "your (a, b) are angles, arctan(x_c / d0) and arctan(y_c / d0): (a, b) are the tangents themselves, "
        "(x_c, y_c) / d0, X0's normalised image position (no arctan, no degrees).",
    ),
)
"""Mistakes only para-perspective meets (the shared ones are :data:`COMMON_MISTAKES`), as the matrices they give."""


def _para_diagnosis(args, got, expected) -> str:
    problem = transposed_cause(got, expected) or shape_problem(got, expected)
    if problem:
        return problem + ". Return the 3x4 affine camera."
    camera, X0 = args
    g = np.asarray(got, dtype=float)
    d0, ab = depth_and_ab(camera, X0)
    x_c = camera.R @ X0 + camera.t
    cause = first_mistake(_MISTAKES, _context(camera, X0), g, same_to_rounding) or match_mistake(
        g, camera, X0, lambda d: x_c[:2] / d, P_PARA
    )
    cause = cause or nearly_right_cause(g, expected, P_PARA)
    if cause:
        return cause
    if not np.allclose(g[2], [0.0, 0.0, 0.0, 1.0], atol=1e-9):
        return last_row_cause(g, d0, expected, P_PARA, camera.R[2], name="P_para")
    slip = v_flip_cause(g, expected) or image_of_X0_as_translation(g, expected, camera, X0)
    if slip:
        return slip
    if same_to_rounding(g[:2, :3], expected[:2, :3]):
        slip = principal_point_cause(g[:2, 3] - expected[:2, 3], camera.K[:2, 2])
        if slip:
            return slip
    used = _ab_used(g, camera, d0)
    if used is not None:
        return (
            f"your matrix has the para-perspective form with (a, b) = ({used[0]:.4g}, {used[1]:.4g}), but X0's "
            f"normalised image position is (x_c, y_c) / d0 = ({ab[0]:.4g}, {ab[1]:.4g}) with x_c = R X0 + t: "
            "check how you computed (a, b)."
        )
    return (
        f"{what_differs(g, expected, camera, X0)}. Compare each block with what you get by writing "
        "(x - a (z - d0)) / d0 and (y - b (z - d0)) / d0, with (x, y, z) = R X + t, as rows acting on (X, 1)."
    )


def _ab_used(g, camera, d0):
    """The (a, b) that ``g``'s left 2x3 block was built with; None otherwise.

    Found if the block has the para-perspective form d0 K2^-1 M2 = R2 - (a, b)^T r3 (K2 the
    upper-left 2x2 of K).
    """
    block = np.linalg.solve(camera.K[:2, :2], d0 * g[:2, :3])
    used = (camera.R[:2] - block) @ camera.R[2]  # r3 is a unit vector orthogonal to r1 and r2
    if np.allclose(block, camera.R[:2] - np.outer(used, camera.R[2]), atol=1e-6):
        return used
    return None


def _para_mistake(name):
    """The shared slip ``name`` (a row of COMMON_MISTAKES), built for para-perspective, as a student's function."""
    return common_slip(
        name,
        lambda camera, X0, K, R, t, d0: p_para(K, R, t, d0, (camera.R @ X0 + camera.t)[:2] / d0),
    )


def _para_ab_without_skew(camera, X0):
    """(a, b) read off X0's pixels as ((u - cx) / fx, (v - cy) / fy): right unless K has a skew."""
    K, x_c = camera.K, camera.R @ X0 + camera.t
    ab = (camera.project(X0) - K[:2, 2]) / np.diag(K)[:2]
    return p_para(K, camera.R, camera.t, x_c[2], ab)


def _para_ab_over_fx(camera, X0):
    """(a, b) = (u - cx, v - cy) / fx from X0's pixels: right only where fy = fx and there is no skew."""
    K, x_c = camera.K, camera.R @ X0 + camera.t
    return p_para(K, camera.R, camera.t, x_c[2], (camera.project(X0) - K[:2, 2]) / K[0, 0])


def _para_image_of_X0_as_t(camera, X0):
    """The first-order expansion written as x_X0 + M2 X: M2 right, the last column X0's image."""
    P = af.paraperspective_approximation(camera, X0)
    P[:2, 3] = camera.project(X0)
    return P


def _para_no_skew(camera, X0):
    x_c = camera.R @ X0 + camera.t
    return p_para(without_skew(camera.K), camera.R, camera.t, x_c[2], x_c[:2] / x_c[2])


def paraperspective_approximation(camera, X0):
    """Perspective linearised at X0 (section 2): x -> (x - a (z - d0)) / d0, last row (0, 0, 0, 1).

    Parameters
    ----------
    camera : camlab.camera.Camera
        The perspective camera (K, R, t).
    X0 : (3,) ndarray
        The reference point, world coordinates, in front of the camera.

    Returns
    -------
    (3, 4) ndarray
        The paraperspective camera K E / d0, with d0 the depth of X0 and (a, b) its normalised image
        position; it agrees with the camera at X0 to first order.
    """
    K, R, t = camera.K, camera.R, camera.t
    x_c = R @ X0 + t  # X0 in the camera frame
    d0 = x_c[2]  # its depth
    a, b = x_c[:2] / d0  # its normalised image position
    E = np.zeros((3, 4))  # rows act on (X, 1); z - d0 = r3 . X + t3 - d0
    E[0, :3], E[0, 3] = R[0] - a * R[2], t[0] - a * (t[2] - d0)  # x - a (z - d0)
    E[1, :3], E[1, 3] = R[1] - b * R[2], t[1] - b * (t[2] - d0)  # y - b (z - d0)
    E[2, 3] = d0
    return K @ E / d0


def _para_exception_hint(exc, args) -> str:
    """A broadcasting slip in the rows r_i - ab_i r3 (ab is (2,), r3 is (3,))."""
    if isinstance(exc, ValueError) and "broadcast" in str(exc):
        return (
            "a broadcasting slip building the rows r1 - a r3 and r2 - b r3: ab = (a, b) is (2,) and r3 = R[2] is "
            "(3,), so ab * R[2] (or R[:2] - ab * R[2][:2]) cannot line up. Make the (2, 3) block with "
            "np.outer(ab, R[2]) or ab[:, None] * R[2], then R[:2] - that block; the last column takes "
            "ab * (t3 - d0), a (2,) vector."
        )
    return ""


register_exercise(
    Exercise(
        name="paraperspective_approximation",
        lesson="05",
        reference=af.paraperspective_approximation,
        cases=approx_cases,
        compare=same_array(rtol=1e-7, atol=1e-7),
        diagnose=_para_diagnosis,
        exception_hint=_para_exception_hint,
        ndarray_only=True,
        wrong_variants=(
            (
                lambda camera, X0: af.affine_approximation(camera, X0),
                "weak-perspective camera P_inf",
            ),
            (
                lambda camera, X0: af.paraperspective_approximation(camera, X0) * [[1], [-1], [1]],
                "gives -v instead",
            ),
            (
                mistake_variant(_MISTAKES, "(a, b) sign", _context),
                "a and b terms have the wrong sign",
            ),
            (mistake_variant(_MISTAKES, "a and b swapped", _context), "a and b are swapped"),
            (mistake_variant(_MISTAKES, "no t3 - d0 term", _context), "lacks -(a, b) (t3 - d0)"),
            (
                mistake_variant(_MISTAKES, "t3 term without d0", _context),
                "the -d0 of z - d0 is missing",
            ),
            (mistake_variant(_MISTAKES, "d0 term without t3", _context), "the t3 of z"),
            (
                mistake_variant(_MISTAKES, "t3 - d0 term sign", _context),
                "sign of the a and b terms in E's last column",
            ),
            (
                mistake_variant(_MISTAKES, "(a, b) in pixels", _context),
                "pixel coordinates as (a, b)",
            ),
            (_para_ab_without_skew, "ignores this camera's skew"),
            (
                mistake_variant(_MISTAKES, "(a, b) from world coordinates", _context),
                "world coordinates",
            ),
            (mistake_variant(_MISTAKES, "(a, b) as pixel offsets", _context), "pixel offsets"),
            (
                mistake_variant(_MISTAKES, "(a, b) not divided by d0", _context),
                "divide them by its depth",
            ),
            (
                mistake_variant(_MISTAKES, "(a, b) from world coordinates over d0", _context),
                "world coordinates",
            ),
            (
                mistake_variant(_MISTAKES, "(a, b) from R X0 without t", _context),
                "without the translation",
            ),
            (
                mistake_variant(_MISTAKES, "(a, b) from R X0 without t, over d0", _context),
                "without the translation",
            ),
            (
                lambda camera, X0: p_para(
                    camera.K,
                    camera.R,
                    camera.t,
                    (camera.R @ X0 + camera.t)[2],
                    0.9 * (camera.R @ X0 + camera.t)[:2] / (camera.R @ X0 + camera.t)[2],
                ),
                "check how you computed (a, b)",
            ),
            (mistake_variant(_MISTAKES, "(a, b) over the distance", _context), "distance |x_c|"),
            (_para_image_of_X0_as_t, "t2 = x_X0 - M2 X0"),
            (_para_ab_over_fx, "divides both offsets by fx"),
            (mistake_variant(_MISTAKES, "(a, b) over d0 twice", _context), "by d0 twice"),
            (
                mistake_variant(_MISTAKES, "pixel form without the principal point", _context),
                "offset from the principal point",
            ),
            (_para_mistake("t sign everywhere"), "t has the wrong sign everywhere"),
            (_para_mistake("d0 = t3"), "depth of the world origin"),
            (_para_mistake("d0 = r3 . X0 - t3"), "t3 has the wrong sign"),
            (_para_mistake("no K"), "left out K"),
            (_para_mistake("fx and fy swapped"), "fx and fy are swapped"),
            (_para_mistake("cx and cy swapped"), "cx and cy are swapped"),
            (
                lambda camera, X0: np.round(af.paraperspective_approximation(camera, X0), 6),
                "the formula is right",
            ),
            (_para_mistake("K^-1"), "K^-1"),
            (_para_mistake("R.T"), "R.T"),
            (_para_mistake("t1, t2 sign"), "t1 and t2 have the wrong sign"),
            (_para_no_skew, "skew K[0, 1] is missing"),
            (
                lambda camera, X0: (
                    af.paraperspective_approximation(camera, X0) * (camera.R[2] @ X0 + camera.t[2])
                ),
                "where P_para does",
            ),
            (lambda camera, X0: -af.paraperspective_approximation(camera, X0), "minus the answer"),
            (
                lambda camera, X0: (
                    af.paraperspective_approximation(camera, X0)
                    + np.c_[np.zeros((3, 3)), [0.5, 0.5, 0]]
                ),
                "half a pixel",
            ),
            (
                lambda camera, X0: np.round(af.paraperspective_approximation(camera, X0), 2),
                "entries of the 2x3 block differ",
            ),
            (
                mistake_variant(_MISTAKES, "X0 in millimetres", _context),
                "scaled by 1000 (millimetres?)",
            ),
            (
                mistake_variant(_MISTAKES, "unrotated ray", _context),
                "line of sight in world coordinates",
            ),
            (
                mistake_variant(_MISTAKES, "unrotated ray over d0", _context),
                "line of sight in world coordinates",
            ),
            (mistake_variant(_MISTAKES, "a twice", _context), "both rows use a"),
            (mistake_variant(_MISTAKES, "b twice", _context), "both rows use b"),
            (_para_outer_reshaped, "np.outer(ab, R[2])"),
            (mistake_variant(_MISTAKES, "(a, b) as angles", _context), "your (a, b) are angles"),
        ),
        teaching=paraperspective_approximation,
    )
)
