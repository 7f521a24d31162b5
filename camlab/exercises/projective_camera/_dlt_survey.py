"""The test of lesson 04's normalised DLT beyond exact pixels.

A noisy survey whose camera must be as good as the predicted RMS error allows, and units and origins
the answer must not depend on (the follow-up).
"""

from __future__ import annotations

import numpy as np

from ... import camera as cm
from ...camera import predicted_rms_error
from .._answers import same_up_to_scale
from ._dlt_forms import NORMALISER_SLIPS, dlt_p34, dlt_slipped
from ._scenes import cameras

# -- estimate_projection_matrix (the normalised DLT) -------------------------------------------
# The test inputs are exact pixels, where any correct DLT (normalised or not, two or three rows of
# the cross product, refined or not) gives the true camera up to scale. What normalisation buys
# shows only with noise, and there no single answer is "the" right one. So once those pass, the
# follow-up (dlt_follow_up) runs the student's function on a noisy survey:
#   1. accuracy against the TRUE camera, within a tolerance derived from the noise (first-order
#      covariance propagation, H&Z 5.2): catches answers that exact data cannot tell apart;
#   2. the same survey in other units and origins, one change at a time (world origin at the site's
#      corner; world in millimetres and in kilometres; pixel origin at the image centre; pixels as fractions of the width). A normalised DLT is invariant to such
#      changes (the normalised coordinates are the same numbers, H&Z 4.4.4), a refined one too;
#      an unnormalised or half-normalised one is not, and which half changes names the cause.


def _survey_camera():
    K = cm.intrinsic_matrix(3200.0, 3200.0, 1999.5, 1499.5)
    return cm.Camera.look_at(
        [74.0, 18.0, 12.0], [50.0, 50.0, 1.0], K=K, image_size=(4000, 3000)
    )  # 40 m away


def _survey_points(n, rng):
    return rng.uniform(
        [48.0, 48.0, 0.0], [52.0, 52.0, 2.0], (n, 3)
    )  # a 4 m site, 70 m from the origin


SURVEY_NOISE_PX = 1.0  # pixel noise per coordinate


SURVEY_TOLERANCE = 5.0  # times the predicted RMS error


_SURVEY_TEST_POINTS = _survey_points(50, np.random.default_rng(12))  # where cameras are compared


# Other units and origins for the same survey, one change at a time, as 4 x 4 and 3 x 3 maps of homogeneous
# points: the world origin moved to the site's corner (48, 48, 0) m, the world in millimetres or kilometres, the pixel origin
# moved to the image centre, the pixels as fractions of the image width. A DLT that centres a side is unmoved by its shift, one
# that scales a side is unmoved by its change of units; so which change moves the camera names what is missing.
_WORLD_SHIFT = np.array([[1.0, 0, 0, -48.0], [0, 1.0, 0, -48.0], [0, 0, 1.0, 0], [0, 0, 0, 1.0]])


_WORLD_IN_MM = np.diag(
    [1e3, 1e3, 1e3, 1.0]
)  # one scale-up and one scale-down: either alone can move a


_WORLD_IN_KM = np.diag([1e-3, 1e-3, 1e-3, 1.0])  # half-normalised DLT too little to see


_PIXEL_SHIFT = np.array([[1.0, 0, -1999.5], [0, 1.0, -1499.5], [0, 0, 1.0]])


_PIXELS_HALF = np.diag(
    [1 / 4000, 1 / 4000, 1.0]
)  # fractions of the image width (a 0.5 scale moves too little)


_INVARIANCE_PX = 1e-3  # a normalised DLT gives 1e-11 px, a refined one 1e-6; half-normalised ones 0.02 px and more


# (LM on P's raw entries moves by up to 0.06 px between frames: it passes as a refinement, see _refinement)


def dlt_cases():
    rng = np.random.default_rng(11)
    cases = []
    for cam, n in zip(cameras(), (6, 10, 14), strict=True):  # exact pixels, six or more points
        X = rng.uniform(-1.0, 1.0, (n, 3)) + [0.0, 0.0, 0.5]
        cases.append((X, cm.project_points(cam.P, X)))
    X = _survey_points(12, rng)  # exact pixels far from the world origin
    cases.append((X, cm.project_points(_survey_camera().P, X)))
    return cases


def _noisy_survey():
    """20 survey points and their pixels with 1 px noise (seeded)."""
    rng = np.random.default_rng(3)
    X = _survey_points(20, rng)
    return X, cm.project_points(_survey_camera().P, X) + rng.normal(0.0, SURVEY_NOISE_PX, (20, 2))


def pixels_of(P, X):
    x = np.column_stack([X, np.ones(len(X))]) @ np.asarray(P, dtype=float).T
    with np.errstate(divide="ignore", invalid="ignore"):
        return x[:, :2] / x[:, 2:3]


def pixel_gap(got, expected, X) -> float:
    """The largest distance (px) between the pixels of X under the two matrices."""
    return float(np.nanmax(np.linalg.norm(pixels_of(got, X) - pixels_of(expected, X), axis=1)))


def _rms_gap(got, expected, X) -> float:
    """The RMS distance (px) between the pixels of X under the two matrices."""
    return float(
        np.sqrt(np.mean(np.sum((pixels_of(got, X) - pixels_of(expected, X)) ** 2, axis=1)))
    )


def _as_camera_matrix(got):
    """``got`` as a finite (3, 4) float array, or None."""
    try:
        g = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        return None
    return g if g.shape == (3, 4) and np.isfinite(g).all() and np.any(g) else None


def dlt_follow_up(run) -> str | None:
    """Accuracy against the true camera on a noisy survey, then invariance to units and origins."""
    X, uv = _noisy_survey()
    truth = _survey_camera().P
    where = "on a noisy survey (20 points, 1 px noise, a 4000 x 3000 photo of a site 70 m from the world origin)"
    P = _as_camera_matrix(run(X, uv))
    if P is None:
        return f"{where} your function did not return a finite, non-zero (3, 4) array."
    allowed = SURVEY_TOLERANCE * predicted_rms_error(truth, X, SURVEY_NOISE_PX, _SURVEY_TEST_POINTS)
    error = _rms_gap(P, truth, _SURVEY_TEST_POINTS)
    accurate = error <= allowed
    moved, answers = {}, [P]
    for key, S in (
        ("world shift", _WORLD_SHIFT),
        ("world units", _WORLD_IN_MM),
        ("world units", _WORLD_IN_KM),
    ):
        P_other = _as_camera_matrix(run(X @ S[:3, :3].T + S[:3, 3], uv))
        if P_other is None:
            return f"{where}, given the same points in other units, your function did not return a finite (3, 4) array."
        answers.append(P_other @ S)  # back in metres
        moved[key] = (
            moved.get(key, False) or pixel_gap(answers[-1], P, _SURVEY_TEST_POINTS) > _INVARIANCE_PX
        )
    for key, S in (("pixel shift", _PIXEL_SHIFT), ("pixel units", _PIXELS_HALF)):
        P_other = _as_camera_matrix(run(X, uv @ S[:2, :2].T + S[:2, 2]))
        if P_other is None:
            return f"{where}, given the same pixels in other units, your function did not return a finite (3, 4) array."
        answers.append(np.linalg.inv(S) @ P_other)  # back in pixels
        moved[key] = pixel_gap(answers[-1], P, _SURVEY_TEST_POINTS) > _INVARIANCE_PX
    refinement = _refinement(answers, X, uv)
    if (
        refinement == "converged"
    ):  # the maximum-likelihood camera, in every frame: it depends on no units or origin
        moved = dict.fromkeys(moved, False)
    if accurate and not any(moved.values()):
        return None
    findings = []
    if not accurate:
        findings.append(
            f"your P images the site {error:.3g} px (RMS) from the true camera: 1 px of noise moves a "
            f"least-squares camera by about {allowed / SURVEY_TOLERANCE:.2g} px (first-order error "
            f"propagation, H&Z 5.2), and the check allows {SURVEY_TOLERANCE:g} times that, {allowed:.2g} px"
        )
    changes = {
        "world shift": "with the world origin moved to the site's corner",
        "world units": "with the world points in millimetres or kilometres",
        "pixel shift": "with the pixel origin moved to the image centre",
        "pixel units": "with the pixels as fractions of the image width",
    }
    moved_by = [changes[k] for k in changes if moved[k]]
    if moved_by:
        findings.append(
            "given the same survey "
            + " or ".join(moved_by)
            + ", your function finds a different camera"
        )
    invariance = (
        " A normalised DLT finds the same camera in any units and origins: the normalised coordinates are "
        "the same numbers."
        if moved_by
        else ""
    )
    cause = (
        _REFINED_BUT_MOVED if refinement == "partial" and moved_by else _dlt_cause(moved, X, uv, P)
    )
    return f"{where}: " + "; ".join(findings) + "." + invariance + f"\n  likely cause: {cause}."


_REFINED_BUT_MOVED = (
    "your P fits the measured pixels better than a linear DLT, so you refined it; but in other units the "
    "refinement stops short of that fit, or never leaves its start: Levenberg-Marquardt on P's raw entries "
    "(metres against pixels, entries from 1e-3 to 1e3) is badly conditioned, like the unnormalised DLT. Refine in the normalised coordinates (T u and "
    "U X, starting from P_hat), then undo: P = inv(T) @ P_hat_refined @ U (H&Z's Gold Standard, Algorithm 7.1); "
    "the reprojection error in pixels is then minimised exactly, in any units"
)


def _residual_rms(P, X, uv) -> float:
    return float(np.sqrt(np.mean(np.sum((pixels_of(P, X) - uv) ** 2, axis=1))))


def _refinement(answers, X, uv) -> str | None:
    """'converged', 'partial' or None: how many answers are refined cameras.

    'converged' if every answer (one per units and origins, mapped back) is a refined camera,
    'partial' if the first is and another is not, else None.

    The maximum-likelihood camera minimises the reprojection error in pixels, which no change of world units
    or origin, and no similarity of the pixels, alters. A linear DLT leaves an RMS residual a little above its
    floor (0.2 mpx on the survey); "refined" means less than half of that excess. LM on P's raw entries reaches
    it in every frame, though its path moves the camera by up to 0.06 px between frames (0.43 of the excess at
    worst); every half-normalised DLT leaves 0.76 of it or more in some frame (1.06 at least in its worst),
    so it is not mistaken for a refinement.
    """
    floor = _residual_rms(cm.estimate_projection_matrix(X, uv, refine=True), X, uv)
    linear = _residual_rms(cm.estimate_projection_matrix(X, uv), X, uv) - floor
    refined = [_residual_rms(A, X, uv) - floor <= 0.5 * linear for A in answers]
    if all(refined):
        return "converged"
    return "partial" if refined[0] else None


_SLIP_CAUSES = {
    "unscaled shift": (
        "the normaliser of the {side} has the translation -c where it must be -s c: T[:-1, -1] = -c maps p to "
        "s p - c, which is scaled but not centred (its centroid lands at (s - 1) c). The matrix must map p to "
        "s (p - c), so scale the centroid too: T[:-1, -1] = -s * c"
    ),
    "origin scale": (
        "the {side} are centred, but their scale is measured from the origin: s = sqrt(D) / mean |p| "
        "(np.linalg.norm(p)) where it must be sqrt(D) / mean |p - c|, the mean distance to the centroid "
        "(D = 3 for world points, 2 for pixels). "
        "Far from the origin (this site is 70 m from the world origin) the normalised points then huddle near "
        "0 and A is ill-conditioned again"
    ),
}


def _unit_sign(P):
    """P scaled to unit norm, its largest entry positive: one representative of the camera up to scale."""
    P = np.asarray(P, dtype=float) / np.linalg.norm(P)
    return P * np.sign(P.ravel()[np.argmax(np.abs(P.ravel()))])


def _normaliser_slip(X, uv, P) -> str | None:
    """The cause when P is the DLT with a slipped normaliser (NORMALISER_SLIPS) on one side or both.

    On the survey the two pixel slips give cameras only 1e-5 apart (a similarity of the pixels barely
    reweights A's rows), so the nearest slipped DLT is named, and only if P is that camera to 1e-7.
    """
    kinds = (None, *NORMALISER_SLIPS)
    gaps = {
        (w, p): np.abs(_unit_sign(P) - _unit_sign(dlt_slipped(X, uv, world=w, pixels=p))).max()
        for w in kinds
        for p in kinds
        if (w, p) != (None, None)
    }
    (world, pixels), gap = min(gaps.items(), key=lambda item: item[1])
    if gap > 1e-7:
        return None
    if world == pixels:
        return (
            _SLIP_CAUSES[world].format(side="world points and pixels")
            + "; then P = inv(T) @ P_hat @ U"
        )
    causes = [
        _SLIP_CAUSES[slip].format(side=side)
        for side, slip in (("world points", world), ("pixels", pixels))
        if slip
    ]
    return "; and ".join(causes) + "; then P = inv(T) @ P_hat @ U"


def _dlt_cause(moved, X, uv, P) -> str:
    """Name what is missing from the normalisation, side by side: the centroid shift, the scale, or both."""
    if same_up_to_scale(P, dlt_p34(X, uv), rtol=1e-4):
        return (
            "you fixed p34 = 1 and solved the rest by least squares on raw metres and pixels (the classic DLT). "
            "That is unmoved by the pixels' units and origin and by the world's units, but p34 = 1 ties the "
            "answer to the world origin (p34 is the depth of the origin, and the fit fails if the origin lies "
            "near the camera's principal plane). Normalise both sides (centroid 0, mean distance sqrt(3) and "
            "sqrt(2)), take the last row of Vt as P_hat, then P = inv(T) @ P_hat @ U"
        )
    slipped = _normaliser_slip(X, uv, P)
    if slipped:
        return slipped
    if all(moved.values()):
        return (
            "no normalisation: A's columns range from 1 to u X ~ 1e5, and which equations dominate depends "
            "on the units. Normalise both sides: T for the pixels (centroid 0, mean distance sqrt(2)), U for "
            "the world points (centroid 0, mean distance sqrt(3)); solve for P_hat; then P = inv(T) @ P_hat @ U"
        )
    missing = []
    for side, shift, units, norm, dist in (
        ("world points", "world shift", "world units", "U", "sqrt(3)"),
        ("pixels", "pixel shift", "pixel units", "T", "sqrt(2)"),
    ):
        if moved[shift] and moved[units]:
            missing.append(
                f"the {side} are not normalised at all (neither centred nor scaled): normalise them "
                f"with {norm} (centroid 0, mean distance {dist})"
            )
        elif moved[shift]:
            missing.append(
                f"the {side} are scaled but not centred: subtract their centroid before scaling "
                f"(moving the origin must not change the normalised {side})"
            )
        elif moved[units]:
            missing.append(
                f"the {side} are centred but not scaled, so A still depends on their units: divide by "
                f"the mean distance to the centroid and multiply by {dist}"
            )
    if not missing:
        return (
            "the estimate is not a least-squares fit of the DLT equations: two rows of u x P X = 0 per "
            "point from normalised coordinates, the last row of Vt, then P = inv(T) @ P_hat @ U"
        )
    return "; ".join(missing) + "; and undo both: P = inv(T) @ P_hat @ U"
