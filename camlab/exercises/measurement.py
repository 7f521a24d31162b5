"""Exercises for lesson 12, measure the world: the pose from a homography, a length on a plane, how far stereo sees.

Each diagnosis is a table of :class:`Mistake` rows (``first_mistake``): what a typical slip returns
on the test input, and the hint that names its cause.

References
----------
Z. Zhang, 2000, "A flexible new technique for camera calibration", IEEE TPAMI 22(11), section 3.1;
Hartley & Zisserman, Multiple View Geometry, 2nd ed., sections 2.7 and 12.6.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ._answers import same_array, shape_problem
from ._core import Exercise, Mistake, first_mistake, mistake_variant, register_exercise
from ._measurement_mistakes import POSE_MISTAKES_MORE
from ._numbers import is_number, not_one_number, same_number

_K = np.array([[532.8, 0.0, 341.8], [0.0, 533.0, 234.1], [0.0, 0.0, 1.0]])


def _rodrigues(r) -> np.ndarray:
    r = np.asarray(r, dtype=float)
    th = np.linalg.norm(r)
    k = r / th
    S = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(th) * S + (1 - np.cos(th)) * S @ S


# --------------------------------------------------------------------------- exercise 1: pose from H


def _pose_cases():
    """Board -> image homographies K [r1 r2 t] at arbitrary scales, one negative (H is up to scale)."""
    cases = []
    for rvec, t, scale in (
        ([0.3, -0.2, 0.1], [-0.1, -0.05, 0.45], 2.7),
        ([0.45, 0.15, -0.3], [0.08, -0.06, 0.6], -0.013),
        ([-0.5, 0.4, 1.2], [-0.05, 0.02, 0.35], 1.0 / 0.35),
    ):
        R = _rodrigues(rvec)
        H = scale * _K @ np.column_stack([R[:, 0], R[:, 1], t])
        cases.append((_K.copy(), H))
    return cases


def _pose_with(A, lam):
    """[r1 r2 r1 x r2 | t] from the columns of A scaled by lam."""
    r1, r2, t = lam * A[:, 0], lam * A[:, 1], lam * A[:, 2]
    return np.column_stack([r1, r2, np.cross(r1, r2), t])


def _pose_context(K, H):
    A = np.linalg.solve(K, H)
    lam = 1 / np.linalg.norm(A[:, 0])
    right = _pose_with(A, np.sign(A[2, 2]) * lam)
    R, t = right[:, :3], right[:, 3]
    negative = A[2, 2] < 0  # H came at a negative scale: a sign fixed late goes wrong only then
    flipped_late = np.column_stack([R[:, 0], R[:, 1], -R[:, 2], t]) if negative else right
    only_t = np.column_stack([-R[:, 0], -R[:, 1], R[:, 2], t]) if negative else right
    return SimpleNamespace(
        K=K, H=H, A=A, lam=lam, right=right, R=R, t=t, flipped_late=flipped_late, only_t=only_t
    )


def _wrong_side(M, A_of):
    """The pose from a wrong K^-1 H (``A_of(M)``), scaled as the prompt says."""
    A = A_of(M)
    return _pose_with(A, np.sign(A[2, 2]) / np.linalg.norm(A[:, 0]))


_POSE_MISTAKES = (
    Mistake(
        "no K inverse",
        lambda c: _pose_with(c.H, np.sign(c.H[2, 2]) / np.linalg.norm(c.H[:, 0])),
        "you read r1, r2, t from the columns of H itself: H = K [r1 r2 t] up to scale, so the "
        "columns of H are in pixels. Undo the intrinsics first: A = np.linalg.solve(K, H) = K^-1 H.",
    ),
    Mistake(
        "transposed H",
        lambda c: _pose_with(
            np.linalg.solve(c.K, c.H.T),
            np.sign(np.linalg.solve(c.K, c.H.T)[2, 2])
            / np.linalg.norm(np.linalg.solve(c.K, c.H.T)[:, 0]),
        ),
        "you used H.T (rows for columns): r1, r2 and t are the COLUMNS of K^-1 H, A[:, 0], A[:, 1], A[:, 2].",
    ),
    Mistake(
        "no scale",
        lambda c: _pose_with(c.A, 1.0),
        "your r1 and r2 are not unit vectors: H is known only up to scale, so [r1 r2 t] = lambda K^-1 H "
        "with lambda = 1 / ||K^-1 h1||. Divide all three columns by ||K^-1 h1|| (a rotation's columns have "
        "length 1).",
    ),
    Mistake(
        "times the norm",
        lambda c: _pose_with(c.A, np.sign(c.A[2, 2]) * np.linalg.norm(c.A[:, 0])),
        "you multiplied K^-1 H by ||K^-1 h1|| instead of dividing by it: [r1 r2 t] = lambda K^-1 H with "
        "lambda = 1 / ||K^-1 h1||, so r1 = K^-1 h1 / ||K^-1 h1|| has length 1 (yours has ||K^-1 h1||^2).",
    ),
    Mistake(
        "H K^-1",
        lambda c: _wrong_side(c.H, lambda M: M @ np.linalg.inv(c.K)),
        "you multiplied on the wrong side, H @ inv(K): H = K [r1 r2 t] up to scale, so K comes off the "
        "LEFT, A = np.linalg.solve(K, H) = K^-1 H.",
    ),
    Mistake(
        "K^-T H",
        lambda c: _wrong_side(c.H, lambda M: np.linalg.solve(c.K.T, M)),
        "you undid K.T instead of K (np.linalg.inv(K.T) @ H): H = K [r1 r2 t], so A = np.linalg.solve(K, H).",
    ),
    Mistake(
        "scale from h3",
        lambda c: _pose_with(c.A, np.sign(c.A[2, 2]) / np.linalg.norm(c.A[:, 2])),
        "you scaled by the length of the third column: t has any length (the distance to the board); the "
        "scale comes from the rotation's columns, lambda = 1 / ||K^-1 h1||.",
    ),
    Mistake(
        "sign not fixed",
        lambda c: _pose_with(c.A, c.lam),
        "your t has t_z < 0: the board would sit behind the camera. H came at a negative scale here "
        "(it is defined only up to scale, sign included), so flip the sign of lambda when (K^-1 H)[2, 2] < 0.",
    ),
    Mistake(
        "negated R",
        lambda c: c.flipped_late,
        "you fixed the sign after building R (R, t = -R, -t when t_z < 0): negating all three columns of "
        "a rotation flips det R to -1 (a reflection), because r3 = r1 x r2 does not change sign when r1 "
        "and r2 both do. Flip lambda first (lambda < 0 when (K^-1 H)[2, 2] < 0), then r1, r2, t = lambda "
        "a1, lambda a2, lambda a3 and r3 = r1 x r2.",
    ),
    Mistake(
        "only t flipped",
        lambda c: c.only_t,
        "you flipped only t to make t_z > 0: the sign belongs to lambda, which multiplies all three "
        "columns, [r1 r2 t] = lambda K^-1 H. Flip lambda, then build r1, r2, t and r3 = r1 x r2.",
    ),
    Mistake(
        "r3 = r2 x r1",
        lambda c: np.column_stack([c.R[:, 0], c.R[:, 1], -c.R[:, 2], c.t]),
        "your third column points the wrong way (det R = -1, a reflection): r3 = r1 x r2, in that "
        "order (np.cross(r1, r2)), so that x, y, z are right-handed.",
    ),
    Mistake(
        "the camera centre",
        lambda c: np.column_stack([c.R, -c.R.T @ c.t]),
        "your last column is the camera centre C = -R^T t (where the camera is, in board coordinates); "
        "the prompt asks for t of X_cam = R X + t, the board's origin in camera coordinates.",
    ),
    Mistake(
        "R transposed",
        lambda c: np.column_stack([c.R.T, c.t]),
        "your R is transposed (board_from_cam): r1 and r2 are COLUMNS of R, np.column_stack([r1, r2, r3]).",
    ),
    *POSE_MISTAKES_MORE,
)


def _pose_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    g = np.asarray(got, dtype=float)
    hint = first_mistake(
        _POSE_MISTAKES, _pose_context(*args), g, lambda a, b: np.allclose(a, b, atol=1e-6)
    )
    if hint:
        return hint
    R = g[:, :3]
    if not np.allclose(R.T @ R, np.eye(3), atol=1e-6):
        return (
            "your R is not a rotation (R^T R != I): [r1 r2 t] = lambda K^-1 H with lambda = 1 / ||K^-1 h1||, "
            "so r1 = lambda a1 has length 1; and r3 = r1 x r2."
        )
    return (
        "your [R | t] projects the board elsewhere: K [r1 r2 t] should equal H up to scale. "
        "Follow A = K^-1 H, lambda = 1 / ||a1|| (sign so that t_z > 0), r1 = lambda a1, r2 = lambda a2, "
        "r3 = r1 x r2, t = lambda a3."
    )


def pose_from_homography(K, H):
    """Zhang's pose: [r1 r2 t] = lambda K^-1 H, lambda = 1 / ||K^-1 h1||, sign so that t_z > 0.

    Parameters
    ----------
    K : (3, 3) ndarray
        Intrinsics, pixels.
    H : (3, 3) ndarray
        The board -> image homography (board in metres), any scale and sign.

    Returns
    -------
    (3, 4) ndarray
        [R | t], cam_from_board.
    """
    A = np.linalg.solve(K, H)
    lam = 1 / np.linalg.norm(A[:, 0])
    if A[2, 2] < 0:  # the board must be in front: t_z > 0
        lam = -lam
    r1, r2, t = lam * A[:, 0], lam * A[:, 1], lam * A[:, 2]
    return np.column_stack([r1, r2, np.cross(r1, r2), t])


def _pose_variant(name):
    return mistake_variant(_POSE_MISTAKES, name, _pose_context)


register_exercise(
    Exercise(
        name="pose_from_homography",
        lesson="12",
        reference=pose_from_homography,
        cases=_pose_cases,
        compare=same_array(rtol=1e-6, atol=1e-8),
        diagnose=_pose_diagnosis,
        wrong_variants=(
            (_pose_variant("no K inverse"), "K^-1 H"),
            (_pose_variant("transposed H"), "H.T"),
            (_pose_variant("no scale"), "unit vectors"),
            (_pose_variant("times the norm"), "instead of dividing"),
            (_pose_variant("H K^-1"), "wrong side"),
            (_pose_variant("K^-T H"), "K.T"),
            (_pose_variant("negated R"), "after building R"),
            (_pose_variant("only t flipped"), "only t"),
            ((lambda K, H: tuple(np.hsplit(pose_from_homography(K, H), [3]))), "np.column_stack"),
            (_pose_variant("scale from h3"), "third column"),
            (_pose_variant("sign not fixed"), "t_z < 0"),
            (_pose_variant("r3 = r2 x r1"), "r3 = r1 x r2"),
            (_pose_variant("the camera centre"), "camera centre"),
            (_pose_variant("R transposed"), "transposed"),
            (_pose_variant("rows of K^-1 H"), "ROWS of A"),
            (_pose_variant("the inverse pose"), "inverse pose"),
        ),
        teaching=pose_from_homography,
        ndarray_only=True,
    )
)


# --------------------------------------------------------------------------- exercise 2: a length on the plane


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
        transposed=float(np.linalg.norm(right_mult(Hi, a) - right_mult(Hi, b))),
        pixels=float(np.linalg.norm(np.asarray(a) - b)),
        mm=1000 * dist,
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
        "transposed",
        lambda c: c.transposed,
        "you multiplied x @ H^-1 (a row vector on the left): that applies the transpose. With points as "
        "rows, use x @ np.linalg.inv(H).T, or np.linalg.inv(H) @ x for a column.",
    ),
    Mistake(
        "millimetres",
        lambda c: c.mm,
        "your length is 1000 times too big: H maps metres on the board, so the answer is in metres.",
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
        f"the two points are {expected:.5f} m apart on the board, not {float(got):.5g}: map each pixel "
        "by H^-1, divide by the third coordinate, then take the distance."
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
        compare=same_number(rtol=1e-7),
        diagnose=_length_diagnosis,
        wrong_variants=(
            (_length_variant("pixels"), "in pixels"),
            (_length_variant("forward H"), "board -> image"),
            (_length_variant("no division by w"), "divide by w"),
            (_length_variant("transposed"), "transpose"),
            (_length_variant("millimetres"), "1000 times"),
            (_length_variant("squared"), "squared"),
            (_length_variant("half pixel"), "half a pixel"),
            (_length_variant("minus half pixel"), "-0.5"),
            (_length_variant("one-based"), "1-based"),
            (_length_variant("u and v swapped"), "swapped u and v"),
            (_length_variant("no keepdims"), "keepdims"),
        ),
        teaching=length_on_plane,
    )
)


# --------------------------------------------------------------------------- exercise 3: how far can stereo see


def _reach_cases():
    """(f px, B m, sigma_d px, max_error m): Middlebury's rig, a phone pair, a car's rig."""
    return [(994.978, 0.193, 0.3, 0.01), (1500.0, 0.012, 0.5, 0.05), (1200.0, 0.54, 0.25, 0.1)]


def _reach_context(f, B, s, e):
    right = float(np.sqrt(e * f * B / s))
    return SimpleNamespace(
        right=right,
        linear=e * f * B / s,
        inverted=float(np.sqrt(s / (e * f * B))),
        sigma_outside=float(np.sqrt(e * f * B) / s),
        no_f=float(np.sqrt(e * B / s)),
        mm=1000 * right,
        squared=e * f * B / s if not np.isclose(right, 1) else None,
        cube=float(np.cbrt(e * f * B / s)),
        one_input_mm=float(np.sqrt(1000) * right),
        no_sigma=float(np.sqrt(e * f * B)) if not np.isclose(s, 1) else None,
        two_sigma=float(np.sqrt(e * f * B / (2 * s))),
        disparity_depth=f * B / s,
    )


_REACH_MISTAKES = (
    Mistake(
        "linear law",
        lambda c: c.linear,
        "you solved sigma_Z = Z sigma_d / (f B), a law linear in Z: the depth error grows with Z^2 "
        "(dZ/dd = -Z^2 / (f B)), so Z_max = sqrt(max_error f B / sigma_d).",
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
        "two sigma",
        lambda c: c.two_sigma,
        "you used 2 sigma_d: the tolerance is one sigma, sigma_Z = Z^2 sigma_d / (f B) = max_error.",
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
)


def _reach_diagnosis(args, got, expected) -> str:
    if not is_number(got):
        return not_one_number(got, "the depth in metres")
    hint = first_mistake(
        _REACH_MISTAKES,
        _reach_context(*args),
        float(got),
        lambda a, b: np.isclose(a, b, rtol=1e-6, atol=0),
    )
    return hint or (
        f"for f = {args[0]:g} px, B = {args[1]:g} m, sigma_d = {args[2]:g} px and a tolerated error of "
        f"{args[3]:g} m the answer is {expected:.7g} m, not {float(got):.7g}: solve "
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
        compare=same_number(rtol=1e-9),
        diagnose=_reach_diagnosis,
        wrong_variants=(
            (_reach_variant("linear law"), "linear in Z"),
            (_reach_variant("cube root"), "cube root"),
            (_reach_variant("inverted"), "upside down"),
            (_reach_variant("sigma outside the root"), "outside the square root"),
            (_reach_variant("no focal length"), "focal length"),
            (_reach_variant("millimetres"), "1000 times"),
            (_reach_variant("one input in millimetres"), "31.6"),
            (_reach_variant("no sigma_d"), "left out sigma_d"),
            (_reach_variant("two sigma"), "2 sigma_d"),
            (_reach_variant("disparity equals sigma"), "disparity itself"),
        ),
        teaching=max_depth,
    )
)
