"""Exercises for lesson 12, measure the world: a length on a plane, how far stereo sees.

Each diagnosis is a table of :class:`Mistake` rows (``first_mistake``): what a typical slip returns
on the test input, and the hint that names its cause.

References
----------
Hartley & Zisserman, Multiple View Geometry, 2nd ed., sections 2.7 and 12.6.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ._core import Exercise, Mistake, first_mistake, mistake_variant, register_exercise
from ._numbers import is_number, not_one_number, same_number

_K = np.array([[532.8, 0.0, 341.8], [0.0, 533.0, 234.1], [0.0, 0.0, 1.0]])


def _rodrigues(r) -> np.ndarray:
    r = np.asarray(r, dtype=float)
    th = np.linalg.norm(r)
    k = r / th
    S = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(th) * S + (1 - np.cos(th)) * S @ S


# --------------------------------------------------------------------------- exercise 3: a length on the plane


def _length_cases():
    """A board at two poses: (H, a, b) with the pixels of two board points 0.1-0.3 m apart."""
    cases = []
    for rvec, t, pa, pb in (
        ([0.5, -0.2, 0.1], [-0.1, -0.05, 0.6], [0.02, 0.03], [0.17, 0.11]),
        ([-0.7, 0.3, 2.9], [0.1, 0.08, 0.9], [0.0, 0.0], [0.2, 0.125]),
    ):
        R = _rodrigues(rvec)
        H = 1.7 * _K @ np.column_stack([R[:, 0], R[:, 1], t])
        a, b = (_apply(H, np.array(p)) for p in (pa, pb))
        cases.append((H, a, b))
    return cases


def _apply(H, p):
    x = H @ np.append(p, 1.0)
    return x[:2] / x[2]


def _length_context(H, a, b):
    Hi = np.linalg.inv(H)

    def back(M, p):
        x = M @ np.append(p, 1.0)
        return x[:2] / x[2]

    def raw(M, p):
        return (M @ np.append(p, 1.0))[:2]

    def right_mult(M, p):
        x = np.append(p, 1.0) @ M
        return x[:2] / x[2]

    dist = float(np.linalg.norm(back(Hi, a) - back(Hi, b)))
    return SimpleNamespace(
        right=dist,
        forward=float(np.linalg.norm(back(H, a) - back(H, b))),
        no_w=float(np.linalg.norm(raw(Hi, a) - raw(Hi, b))),
        no_w_scaled=float(np.linalg.norm(raw(Hi / Hi[2, 2], a) - raw(Hi / Hi[2, 2], b))),
        no_w_H_scaled=float(
            np.linalg.norm(raw(np.linalg.inv(H / H[2, 2]), a) - raw(np.linalg.inv(H / H[2, 2]), b))
        ),
        transposed=float(np.linalg.norm(right_mult(Hi, a) - right_mult(Hi, b))),
        pixels=float(np.linalg.norm(np.asarray(a) - b)),
        mm=1000 * dist,
        cm=100 * dist,
        one_w=_one_w(Hi, a, b),
        manhattan=float(np.abs(back(Hi, a) - back(Hi, b)).sum()),
        squared=dist**2,
        half=float(np.linalg.norm(back(Hi, np.asarray(a) + 0.5) - back(Hi, np.asarray(b) + 0.5))),
        minus_half=float(
            np.linalg.norm(back(Hi, np.asarray(a) - 0.5) - back(Hi, np.asarray(b) - 0.5))
        ),
        one_based=float(np.linalg.norm(back(Hi, np.asarray(a) - 1) - back(Hi, np.asarray(b) - 1))),
        swapped=float(
            np.linalg.norm(back(Hi, np.asarray(a)[::-1]) - back(Hi, np.asarray(b)[::-1]))
        ),
        no_keepdims=_no_keepdims(Hi, a, b),
    )


def _no_keepdims(Hi, a, b) -> float:
    """Both pixels as rows, divided by w without keepdims: column j is divided by row j's w."""
    P = np.column_stack([np.vstack([a, b]), np.ones(2)]) @ Hi.T
    q = P[:, :2] / P[:, 2]
    return float(np.linalg.norm(q[0] - q[1]))


def _one_w(Hi, a, b) -> float:
    """Both pixels mapped by H^-1, both divided by the FIRST point's w."""
    pa, pb = (Hi @ np.append(p, 1.0) for p in (a, b))
    return float(np.linalg.norm((pa[:2] - pb[:2]) / pa[2]))


_LENGTH_MISTAKES = (
    Mistake(
        "pixels",
        lambda c: c.pixels,
        "you returned the distance in pixels: map both pixels to the board's plane first, "
        "p = H^-1 (u, v, 1), then divide by p's third coordinate.",
    ),
    Mistake(
        "forward H",
        lambda c: c.forward,
        "you mapped the pixels with H, which goes board -> image; pixels go back to the board with "
        "np.linalg.inv(H).",
    ),
    Mistake(
        "no division by w",
        lambda c: c.no_w,
        "you forgot to divide by w: H^-1 (u, v, 1) is a homogeneous point (x w, y w, w); the board "
        "point is its first two entries divided by the third.",
    ),
    Mistake(
        "H^-1 scaled, no w",
        lambda c: c.no_w_scaled,
        "you scaled H so that its [2, 2] entry is 1 and then skipped the division by w: that fixes "
        "the scale of the MATRIX, not each point's w, which still varies across the plane (the "
        "perspective). Divide H^-1 (u, v, 1) by its own third entry for every pixel.",
    ),
    Mistake(
        "H scaled, no w",
        lambda c: c.no_w_H_scaled,
        "you scaled H so that its [2, 2] entry is 1 and then skipped the division by w: that fixes "
        "the scale of the MATRIX, not each point's w, which still varies across the plane (the "
        "perspective). Divide H^-1 (u, v, 1) by its own third entry for every pixel.",
    ),
    Mistake(
        "transposed",
        lambda c: c.transposed,
        "you applied the transpose H^-T: either x @ H^-1 (a row vector on the left) or inv(H).T @ x, the "
        "rule for LINES (l' = H^-T l). A point goes back by H^-1 itself: with points as rows, "
        "x @ np.linalg.inv(H).T, or np.linalg.inv(H) @ x for a column.",
    ),
    Mistake(
        "millimetres",
        lambda c: c.mm,
        "your length is 1000 times too big: H maps metres on the board, so the answer is in metres.",
    ),
    Mistake(
        "centimetres",
        lambda c: c.cm,
        "your length is 100 times too big (centimetres): H maps metres on the board, so the answer is "
        "in metres; return it as it comes out.",
    ),
    Mistake(
        "one w for both",
        lambda c: c.one_w,
        "you divided both mapped points by the first one's w: each homogeneous point has its own third "
        "coordinate (the plane is seen in perspective, so w differs from point to point); divide pa by "
        "pa[2] and pb by pb[2].",
    ),
    Mistake(
        "Manhattan distance",
        lambda c: c.manhattan,
        "you added |dx| + |dy| (a Manhattan distance): a length is the Euclidean norm, "
        "np.hypot(dx, dy) or np.linalg.norm(pa - pb).",
    ),
    Mistake(
        "squared",
        lambda c: c.squared,
        "you returned the squared distance: take np.sqrt (or np.linalg.norm of the difference).",
    ),
    Mistake(
        "half pixel",
        lambda c: c.half,
        "you shifted the pixels by half a pixel: camlab's pixel (u, v) is already the pixel's centre "
        "(origin at the centre of the top-left pixel), so map (u, v, 1) as it is.",
    ),
    Mistake(
        "minus half pixel",
        lambda c: c.minus_half,
        "you shifted the pixels by -0.5: camlab's pixel (u, v) is already the pixel's centre (origin at "
        "the centre of the top-left pixel), so there is no corner-to-centre shift; map (u, v, 1) as it is.",
    ),
    Mistake(
        "one-based",
        lambda c: c.one_based,
        "you subtracted 1 from the pixels (1-based indices): camlab's pixels start at 0, the centre of "
        "the top-left pixel, so map (u, v, 1) as it is.",
    ),
    Mistake(
        "u and v swapped",
        lambda c: c.swapped,
        "you swapped u and v (row, column order, as an array index reads them): a pixel here is (u, v) = "
        "(column, row), the order H expects; map (a[0], a[1], 1).",
    ),
    Mistake(
        "no keepdims",
        lambda c: c.no_keepdims,
        "you divided by w without keepdims: with both points as rows, P[:, :2] / P[:, 2] divides column j "
        "by row j's w (broadcasting). Use P[:, :2] / P[:, 2:] (or P[:, 2, None]).",
    ),
)


def _length_diagnosis(args, got, expected) -> str:
    if not is_number(got):
        return not_one_number(got, "the length in metres")
    hint = first_mistake(
        _LENGTH_MISTAKES,
        _length_context(*args),
        float(got),
        lambda a, b: np.isclose(a, b, rtol=1e-6, atol=0),
    )
    return hint or (
        f"the two points are {expected:.9f} m apart on the board, not {float(got):.9f} (off by "
        f"{abs(float(got) / expected - 1):.1e} of the length; the check allows 1e-5, float32's rounding "
        "passes): map each pixel by H^-1, divide by the third coordinate, then take the distance."
    )


def length_on_plane(H, a, b):
    """The distance on the board (metres) between the board points seen at pixels a and b.

    Parameters
    ----------
    H : (3, 3) ndarray
        Board (metres) -> image (pixels) homography.
    a, b : (2,) ndarray
        Pixels (u, v).

    Returns
    -------
    float
        Metres.
    """
    Hi = np.linalg.inv(H)
    pa = Hi @ np.append(a, 1.0)
    pb = Hi @ np.append(b, 1.0)
    return float(np.linalg.norm(pa[:2] / pa[2] - pb[:2] / pb[2]))


def _length_variant(name):
    return mistake_variant(_LENGTH_MISTAKES, name, _length_context)


register_exercise(
    Exercise(
        name="length_on_plane",
        lesson="12",
        reference=length_on_plane,
        cases=_length_cases,
        compare=same_number(
            rtol=1e-5
        ),  # float32 (cv2.perspectiveTransform) passes; the half pixel, 6e-4, does not
        diagnose=_length_diagnosis,
        wrong_variants=(
            (_length_variant("pixels"), "in pixels"),
            (_length_variant("forward H"), "board -> image"),
            (_length_variant("no division by w"), "divide by w"),
            (_length_variant("H^-1 scaled, no w"), "fixes the scale of the MATRIX"),
            (_length_variant("H scaled, no w"), "fixes the scale of the MATRIX"),
            (_length_variant("transposed"), "rule for LINES"),
            (_length_variant("millimetres"), "1000 times"),
            (_length_variant("centimetres"), "centimetres"),
            (_length_variant("one w for both"), "first one's w"),
            (_length_variant("Manhattan distance"), "Manhattan"),
            (_length_variant("squared"), "squared"),
            (_length_variant("half pixel"), "half a pixel"),
            (_length_variant("minus half pixel"), "-0.5"),
            (_length_variant("one-based"), "1-based"),
            (_length_variant("u and v swapped"), "swapped u and v"),
            (_length_variant("no keepdims"), "keepdims"),
        ),
        teaching=length_on_plane,
        solution_note=(
            "# camlab: camlab.measurement.pixels_to_plane(pose, K, pixels, dist) maps pixels to the board's plane "
            "(undistorting first);\n# camlab.measurement.measure_on_plane(pose, K, a, b, dist) gives the length "
            "with its sigma (section 2)."
        ),
    )
)


# --------------------------------------------------------------------------- exercise 4: how far can stereo see


def _reach_cases():
    """(f px, B m, sigma_d px, max_error m): Middlebury's rig, a phone pair, a car's rig."""
    return [(994.978, 0.193, 0.3, 0.01), (1500.0, 0.012, 0.5, 0.05), (1200.0, 0.54, 0.25, 0.1)]


REACH_RTOL = 1e-6
"""Exercise 7's relative tolerance (max_depth): 2.5 um on 2.5 m passes a bisection or float32 answer; the nearest
slip (sqrt(2) sigma_d) is 19 % off."""


def _reach_context(f, B, s, e):
    right = float(np.sqrt(e * f * B / s))
    return SimpleNamespace(
        right=right,
        linear=e * f * B / s,
        inverted=float(np.sqrt(s / (e * f * B))),
        fraction_inverted=float(np.sqrt(e * s / (f * B))),
        error_outside=float(np.sqrt(f * B / s) * e),
        tolerance_inverted=float(np.sqrt(f * B / (s * e))),
        doubled=float(np.sqrt(2 * e * f * B / s)),
        negative=-right,
        half=right / 2,
        sigma_outside=float(np.sqrt(e * f * B) / s),
        no_f=float(np.sqrt(e * B / s)),
        mm=1000 * right,
        swapped=float(np.sqrt(s * f * B / e)),
        cube=float(np.cbrt(e * f * B / s)),
        one_input_mm=float(np.sqrt(1000) * right),
        no_sigma=float(np.sqrt(e * f * B)) if not np.isclose(s, 1) else None,
        two_sigma=float(np.sqrt(e * f * B / (2 * s))),
        disparity_depth=f * B / s,
        sigma_times=float(np.sqrt(e * f * B * s)),
        no_B=float(np.sqrt(e * f / s)),
        root2_sigma=float(np.sqrt(e * f * B / (np.sqrt(2) * s))),
        f_outside=float(np.sqrt(e * B / s) * f),
        plane_law=e * f / s,  # sigma = Z sigma_d / f solved for Z: the on-plane law, no B
        truncated=float(int(right)) if right % 1 > 1e-3 else None,
        rounded=float(round(right)) if abs(right - round(right)) > 1e-3 else None,
    )


_REACH_MISTAKES = (
    Mistake(
        "truncated",
        lambda c: c.truncated,
        "you truncated the depth to whole metres (int(...)): return the float itself, sqrt(max_error f B / sigma_d).",
    ),
    Mistake(
        "rounded",
        lambda c: c.rounded,
        "you rounded the depth to whole metres: return the float itself, sqrt(max_error f B / sigma_d).",
    ),
    Mistake(
        "no root",
        lambda c: c.linear,
        "you returned max_error f B / sigma_d, which is Z^2, not Z. Either you stopped at Z^2 and forgot "
        "the square root, or you solved sigma_Z = Z sigma_d / (f B), a law linear in Z, where the depth "
        "error grows with Z^2 (dZ/dd = -Z^2 / (f B)). Z_max = sqrt(max_error f B / sigma_d).",
    ),
    Mistake(
        "plane law",
        lambda c: c.plane_law,
        "you returned max_error f / sigma_d: that solves sigma = Z sigma_d / f, the ON-PLANE law of "
        "section 2 (one pixel covers Z / f metres sideways), linear in Z and without the baseline. A depth "
        "comes from a disparity d = f B / Z, so its error grows as Z^2: sigma_Z = Z^2 sigma_d / (f B), "
        "and Z_max = sqrt(max_error f B / sigma_d).",
    ),
    Mistake(
        "sigma_d and max_error swapped",
        lambda c: c.swapped,
        "you swapped sigma_d and max_error: the disparity noise sigma_d (pixels) divides and the tolerated "
        "depth error max_error (metres) multiplies, Z_max = sqrt(max_error f B / sigma_d).",
    ),
    Mistake(
        "cube root",
        lambda c: c.cube,
        "you took a cube root: sigma_Z = Z^2 sigma_d / (f B) is quadratic in Z, so take the square root.",
    ),
    Mistake(
        "inverted",
        lambda c: c.inverted,
        "your formula is upside down: a longer focal length, a wider baseline and a larger tolerated "
        "error all let you see further; Z_max = sqrt(max_error f B / sigma_d).",
    ),
    Mistake(
        "fraction inverted",
        lambda c: c.fraction_inverted,
        "you multiplied by sigma_d / (f B) where you should divide by it: from Z^2 sigma_d / (f B) = "
        "max_error, Z^2 = max_error f B / sigma_d (a longer f or a wider B lets you see farther).",
    ),
    Mistake(
        "error outside the root",
        lambda c: c.error_outside,
        "you multiplied by max_error outside the square root: it is part of Z^2 = max_error f B / sigma_d, "
        "so it goes under the root with f B / sigma_d (Z_max grows as its square root).",
    ),
    Mistake(
        "sigma outside the root",
        lambda c: c.sigma_outside,
        "you divided by sigma_d outside the square root, or used a variance sigma_d^2 where the law has "
        "sigma_d: solve Z^2 = max_error f B / sigma_d first, then take the root of the whole right-hand side.",
    ),
    Mistake(
        "one input in millimetres",
        lambda c: c.one_input_mm,
        "your depth is sqrt(1000) = 31.6 times too far: one input was in millimetres (B or max_error). "
        "Pass both in metres; Z_max = sqrt(max_error f B / sigma_d) comes out in metres.",
    ),
    Mistake(
        "no sigma_d",
        lambda c: c.no_sigma,
        "you left out sigma_d: the disparity noise sets the depth noise, sigma_Z = Z^2 sigma_d / (f B), so "
        "Z_max = sqrt(max_error f B / sigma_d).",
    ),
    Mistake(
        "tolerance inverted",
        lambda c: c.tolerance_inverted,
        "you divided by max_error where it multiplies: a LARGER tolerated error lets you see FARTHER. "
        "From Z^2 sigma_d / (f B) = max_error, Z^2 = max_error f B / sigma_d.",
    ),
    Mistake(
        "doubled tolerance",
        lambda c: c.doubled,
        "you doubled the tolerance (a +-max_error band read as 2 max_error): max_error is one sigma, "
        "Z^2 sigma_d / (f B) = max_error.",
    ),
    Mistake(
        "negative root",
        lambda c: c.negative,
        "you returned the negative root: Z^2 = max_error f B / sigma_d has two roots, and only Z > 0 "
        "lies in front of the cameras.",
    ),
    Mistake(
        "half",
        lambda c: c.half,
        "your depth is exactly half the answer: a stray factor 1/2 outside the square root (or 1/4 "
        "inside it, as with 4 sigma_d); nothing is halved in sigma_Z = Z^2 sigma_d / (f B), so "
        "Z = sqrt(max_error f B / sigma_d).",
    ),
    Mistake(
        "two sigma",
        lambda c: c.two_sigma,
        "your depth is the answer / sqrt(2): one factor 2 too many under the root. Either you used "
        "2 sigma_d (the tolerance is one sigma, sigma_Z = Z^2 sigma_d / (f B) = max_error), or half the "
        "baseline B / 2 (B is the whole distance between the two camera centres), or half the tolerance.",
    ),
    Mistake(
        "disparity equals sigma",
        lambda c: c.disparity_depth,
        "you returned f B / sigma_d, the depth where the disparity itself equals its noise: the question "
        "asks where the depth ERROR reaches max_error, Z^2 sigma_d / (f B) = max_error.",
    ),
    Mistake(
        "no focal length",
        lambda c: c.no_f,
        "you left out the focal length: the disparity is in pixels, and f (pixels) turns it into an "
        "angle; Z_max = sqrt(max_error f B / sigma_d).",
    ),
    Mistake(
        "millimetres",
        lambda c: c.mm,
        "your depth is 1000 times too big: with B and max_error in metres, Z comes out in metres.",
    ),
    Mistake(
        "sigma_d multiplied",
        lambda c: c.sigma_times,
        "you multiplied by sigma_d where it divides: more disparity noise lets you see LESS far. From "
        "Z^2 sigma_d / (f B) = max_error, Z^2 = max_error f B / sigma_d.",
    ),
    Mistake(
        "no baseline",
        lambda c: c.no_B,
        "you left out the baseline B: the disparity d = f B / Z grows with B, so sigma_Z = Z^2 sigma_d / "
        "(f B) and Z_max = sqrt(max_error f B / sigma_d).",
    ),
    Mistake(
        "focal length outside the root",
        lambda c: c.f_outside,
        "you multiplied by f outside the square root: f sits under it with B, Z^2 = max_error f B / "
        "sigma_d, so Z_max = sqrt(max_error * f * B / sigma_d), which grows only as sqrt(f).",
    ),
    Mistake(
        "sqrt(2) sigma_d",
        lambda c: c.root2_sigma,
        "you divided by sqrt(2) sigma_d: sigma_d is given already as the DISPARITY's noise (section 3's "
        "sqrt(2) sigma_u is how it follows from one pixel's noise); use it as it is, Z^2 = max_error f B / "
        "sigma_d.",
    ),
)


def _reach_diagnosis(args, got, expected) -> str:
    if not is_number(got):
        return not_one_number(got, "the depth in metres")
    hint = first_mistake(
        _REACH_MISTAKES,
        _reach_context(*args),
        float(got),
        lambda a, b: np.isclose(a, b, rtol=REACH_RTOL, atol=0),
    )
    if hint:
        return hint
    off = float(got) / expected - 1
    if abs(off) < 1e-4:
        return (
            f"nearly right: {float(got):.10f} m against {expected:.10f} m ({off:+.1e} relative, the "
            f"check allows {REACH_RTOL:g}): solve exactly, Z = sqrt(max_error f B / sigma_d), or run "
            "your solver to a tighter tolerance."
        )
    return (
        f"for f = {args[0]:g} px, B = {args[1]:g} m, sigma_d = {args[2]:g} px and a tolerated error of "
        f"{args[3]:g} m the answer is {expected:.7g} m, not {float(got):.7g} ({off:+.2%}): solve "
        "Z^2 sigma_d / (f B) = max_error for Z."
    )


def max_depth(f, B, sigma_d, max_error):
    """The farthest depth whose error sigma_Z = Z^2 sigma_d / (f B) stays within max_error (metres).

    Parameters
    ----------
    f : float
        Focal length, pixels.
    B : float
        Baseline, metres.
    sigma_d : float
        Disparity noise, pixels.
    max_error : float
        The tolerated depth error (one sigma), metres.

    Returns
    -------
    float
        Metres.
    """
    return float(np.sqrt(max_error * f * B / sigma_d))


def _reach_variant(name):
    return mistake_variant(_REACH_MISTAKES, name, _reach_context)


register_exercise(
    Exercise(
        name="max_depth",
        lesson="12",
        reference=max_depth,
        cases=_reach_cases,
        compare=same_number(rtol=REACH_RTOL),
        diagnose=_reach_diagnosis,
        wrong_variants=(
            (_reach_variant("no root"), "forgot the square root"),
            (_reach_variant("no root"), "linear in Z"),
            (_reach_variant("plane law"), "ON-PLANE law"),
            (_reach_variant("truncated"), "truncated the depth"),
            (_reach_variant("sigma_d and max_error swapped"), "swapped sigma_d and max_error"),
            (_reach_variant("cube root"), "cube root"),
            (_reach_variant("inverted"), "upside down"),
            (_reach_variant("sigma outside the root"), "outside the square root"),
            (_reach_variant("fraction inverted"), "where you should divide"),
            (_reach_variant("error outside the root"), "max_error outside the square root"),
            (_reach_variant("no focal length"), "focal length"),
            (_reach_variant("millimetres"), "1000 times"),
            (_reach_variant("one input in millimetres"), "31.6"),
            (_reach_variant("no sigma_d"), "left out sigma_d"),
            (_reach_variant("two sigma"), "2 sigma_d"),
            (_reach_variant("tolerance inverted"), "divided by max_error"),
            (_reach_variant("doubled tolerance"), "doubled the tolerance"),
            (_reach_variant("negative root"), "negative root"),
            (_reach_variant("half"), "half the answer"),
            (_reach_variant("disparity equals sigma"), "disparity itself"),
            (_reach_variant("sigma_d multiplied"), "multiplied by sigma_d"),
            (_reach_variant("no baseline"), "left out the baseline"),
            (_reach_variant("sqrt(2) sigma_d"), "sqrt(2) sigma_d"),
            (_reach_variant("focal length outside the root"), "f outside the square root"),
        ),
        teaching=max_depth,
        solution_note=(
            "# camlab: camlab.measurement.depth_sigma(Z, f, B, sigma_d) is the forward law, sigma_Z = Z^2 sigma_d / (f B),"
            "\n# that this inverts (section 3)."
        ),
    )
)
