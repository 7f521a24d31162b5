"""Exercise 6 of lesson 11: depth from disparity (`disparity_to_depth`)."""

from __future__ import annotations

import numpy as np

from ... import disparity
from .._answers import same_array, shape_problem
from .._core import Exercise, register_exercise

# --------------------------------------------------------------------------- depth from disparity


def _depth_cases():
    """Two rigs with one principal point (doffs 0), then Middlebury's Motorcycle (doffs 31.086 px)."""
    return [
        (np.array([80.0, 40.0, 16.0]), 800.0, 0.12, 0.0),
        (np.array([[10.5, 64.0], [33.0, 7.25]]), 1200.0, 0.3, 0.0),
        (np.array([[12.0, 55.5], [30.25, 7.0]]), 994.978, 0.193001, 31.086),
    ]


def _reference(d, f, B, doffs=0.0):
    """camlab's depth with the principal-point offset: Z = f B / (d + doffs)."""
    return disparity.disparity_to_depth(np.asarray(d, dtype=float) + doffs, f, B)


def _depth_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    d, f, B, doffs = args
    g = np.asarray(got, dtype=float)
    if doffs and np.allclose(g, f * B / d):
        return (
            f"you left out doffs = {doffs:g} px: the right camera's principal point sits doffs px to the "
            "right (c_x' = c_x + doffs), so d = f B / Z - doffs and Z = f B / (d + doffs)"
        )
    if doffs and np.allclose(g, f * B / (d - doffs)):
        return (
            "you subtracted doffs: d = u1 - u2 = f B / Z - doffs, since the right principal point sits "
            "doffs px to the right; solve for Z: Z = f B / (d + doffs)"
        )
    if doffs and np.allclose(g, f * B / (d + 2 * doffs)):
        return (
            f"you added doffs = {doffs:g} px twice (d + 2 doffs): add it once, Z = f B / (d + doffs). "
            "If you did d = d + doffs and then used d + doffs, keep only one of the two"
        )
    if doffs and np.allclose(g, f * B / d + doffs):
        return "you added doffs to the depth: it is a disparity (pixels), so it goes into the denominator, Z = f B / (d + doffs)"
    d_in, d = (
        d,
        d + doffs,
    )  # d + doffs, the effective disparity: every slip below is about f, B and d
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
    if np.asarray(got).dtype.kind in "iub" and np.allclose(g, np.trunc(f * B / d)):
        return (
            "your depths are whole numbers of integer type: a cast to int (.astype(int), int(...)) or an integer array "
            "cut off the fraction. Keep floats: Z = f B / (d + doffs) in float64"
        )
    if np.allclose(g, f * B // d):
        return "you used floor division (//), which rounds the depth down: Z = f B / d with true division"
    for off in (0.5, 1.0, -0.5, -1.0):
        if np.allclose(g, f * B / (d + off)):
            return (
                f"your depths are f B / (d{' + doffs' if doffs else ''} {off:+g}): the disparity is a difference of two pixel columns, "
                "so no half-pixel or 1-based offset belongs in it; Z = f B / (d + doffs)"
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
        f"at d = {d_in[i]:g} px (f = {f:g} px, B = {B:g} m, doffs = {doffs:g} px) you give Z = {g[i]:.4g} m; "
        f"f B / (d + doffs) = {expected[i]:.4g} m: check each term of Z = f B / (d + doffs)"
    )


def disparity_to_depth(d, f, B, doffs=0.0):
    """Similar triangles: d + doffs = f B / Z, so Z = f B / (d + doffs) (metres when B is in metres).

    Parameters
    ----------
    d : float or array_like
        Disparities, pixels (> 0).
    f : float
        The rectified cameras' focal length, pixels.
    B : float
        The baseline, m.
    doffs : float
        How far right the right camera's principal point sits, pixels (c_x' = c_x + doffs; 0 when
        both rectified cameras share one K, as in the rendered rig).

    Returns
    -------
    ndarray
        The depths Z = f B / (d + doffs), m, of ``d``'s shape.
    """
    return f * B / (np.asarray(d, dtype=float) + doffs)


register_exercise(
    Exercise(
        name="disparity_to_depth",
        lesson="11",
        reference=_reference,
        cases=_depth_cases,
        compare=same_array(rtol=1e-9),
        diagnose=_depth_diagnosis,
        wrong_variants=(
            (lambda d, f, B, o=0.0: f * (d + o) / B, "Z = f B / d"),
            (lambda d, f, B, o=0.0: B / (d + o), "focal length"),
            (lambda d, f, B, o=0.0: f * B / (d + 2 * o), "doffs = "),
            (lambda d, f, B, o=0.0: 1000 * f * B / (d + o), "unit slip"),
            (lambda d, f, B, o=0.0: f * B / (d + o + 1.0), "1-based offset"),
            (lambda d, f, B, o=0.0: f * B // (d + o), "floor division"),
            (lambda d, f, B, o=0.0: (f * B / (d + o)).astype(int), "cast to int"),
            (lambda d, f, B, o=0.0: f / (B * (d + o)), "divided by the baseline"),
            (lambda d, f, B, o=0.0: -f * B / (d + o), "depths are negative"),
            (lambda d, f, B, o=0.0: f * B / d, "left out doffs"),
            (lambda d, f, B, o=0.0: f * B / (d - o), "subtracted doffs"),
        ),
        teaching=disparity_to_depth,
        ndarray_only=True,  # the prompt asks for "an array of d's shape"
    )
)
