r"""Exercise for lesson 12, measure the world: how far a flat target's flipped pose is, in the corners' noise.

A flat target has a second pose that nearly explains its corners (section 2b). The noise must
reach half the distance between the two poses' reprojections, over all :math:`2N` pixel
coordinates together and in that one direction, before the flipped pose fits better:

.. math:: \text{gap} = \frac{\| x_2 - x_1 \|}{2 \sigma}, \qquad
   \| x_2 - x_1 \|^2 = \sum_{i=1}^{N} \| \pi(K (R_2 X_i + t_2)) - \pi(K (R_1 X_i + t_1)) \|^2 ,

in units of the noise :math:`\sigma` of each pixel coordinate; :math:`\Phi(-\text{gap})` is then a
rough guide to how often the flipped pose wins.

References
----------
T. Collins and A. Bartoli, "Infinitesimal plane-based pose estimation", IJCV 109, 2014 (the two
poses of a plane, IPPE); Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 5.1 (least
squares and the noise model).
"""

from __future__ import annotations

from math import erfc, sqrt
from types import SimpleNamespace

import numpy as np

from ._answers import Tolerance
from ._core import Exercise, Mistake, first_mistake, mistake_variant, register_exercise
from ._numbers import SameNumber, is_number, not_one_number

RTOL = 1e-6
"""Relative tolerance: a float32 projection passes (about 1e-7 relative); the nearest slip below
(the largest corner's distance for the rms per corner) is 12 % off."""

_K = np.array([[532.8, 0.0, 341.8], [0.0, 533.0, 234.1], [0.0, 0.0, 1.0]])  # the course's camera


def _target(kind):
    """The board's 54 inner corners (9 x 6, 25 mm) or a square tag's 4, metres, z = 0, centred alike."""
    centre = np.array([0.1, 0.0625, 0.0])
    if kind == "board":
        j, i = np.mgrid[0:6, 0:9]
        return np.column_stack([0.025 * i.ravel(), 0.025 * j.ravel(), np.zeros(54)])
    h = kind / 2  # a tag of side ``kind`` metres
    return centre + np.array([[-h, -h, 0], [h, -h, 0], [h, h, 0], [-h, h, 0]])


def _look(tilt_deg, distance):
    """cam_from_board (R, t) of a camera ``distance`` m from the board's centre, tilted toward +y (section 2's demo)."""
    from ..camera import look_at_rotation

    centre = np.array([0.1, 0.0625, 0.0])
    a = np.radians(tilt_deg)
    eye = centre + distance * np.array([0.0, np.sin(a), -np.cos(a)])  # board z points away from it
    R = look_at_rotation(eye, centre, up=(0.0, -1.0, 0.0))
    return R, -R @ eye


def _cases():
    """(K, R1, t1, R2, t2, X, sigma): a target's true pose, its flipped pose (IPPE), its corners, the noise.

    Section 2b's settings: the board at 1.5 m and 20 deg (13.3 sigma), the 5 cm tag there (0.7 sigma),
    the board at 0.6 m and 20 deg (83 sigma), and the board at 1.5 m and 2 deg with 0.3 px noise.
    """
    import cv2

    out = []
    for kind, tilt, distance, sigma in (
        ("board", 20, 1.5, 0.14),
        (0.05, 20, 1.5, 0.14),
        ("board", 20, 0.6, 0.14),
        ("board", 2, 1.5, 0.3),
    ):
        X, (R, t) = _target(kind), _look(tilt, distance)
        x = (X @ R.T + t) @ _K.T
        _, rv, tv, _ = cv2.solvePnPGeneric(
            X, x[:, :2] / x[:, 2:], _K, None, flags=cv2.SOLVEPNP_IPPE
        )
        flipped = max(range(2), key=lambda k: np.linalg.norm(cv2.Rodrigues(rv[k])[0] - R))
        R2, t2 = cv2.Rodrigues(rv[flipped])[0], tv[flipped].ravel()
        out.append((_K.copy(), R, t.copy(), R2, t2, X, sigma))
    return out


def flip_gap(K, R1, t1, R2, t2, X, sigma):
    """Half the distance between two poses' reprojections of a flat target, in units of the noise.

    Parameters
    ----------
    K : (3, 3) ndarray
        Intrinsics, pixels.
    R1, t1, R2, t2 : (3, 3), (3,) ndarray
        The two poses, cam_from_board (X_c = R X + t).
    X : (N, 3) ndarray
        The target's corners, metres (board frame).
    sigma : float
        The noise of each pixel coordinate, pixels.

    Returns
    -------
    float
        The gap: half the distance between the two reprojections over all 2N coordinates, in sigma.
    """
    x1 = (X @ R1.T + t1) @ K.T  # each corner in pose 1, homogeneous pixels
    x2 = (X @ R2.T + t2) @ K.T
    d = x2[:, :2] / x2[:, 2:] - x1[:, :2] / x1[:, 2:]  # (N, 2): each corner's offset, px
    return float(np.sqrt(np.sum(d**2)) / 2 / sigma)  # all 2N coordinates together, half, in sigma


def _context(K, R1, t1, R2, t2, X, sigma):
    X = np.asarray(X, dtype=float)

    def offsets(K=K, R1=R1, R2=R2, divide=True):
        x1, x2 = ((X @ R.T + t) @ K.T for R, t in ((R1, t1), (R2, t2)))
        if not divide:  # the homogeneous pixels, never divided by w
            return x2[:, :2] - x1[:, :2]
        return x2[:, :2] / x2[:, 2:] - x1[:, :2] / x1[:, 2:]

    d = offsets()
    per_corner = np.linalg.norm(d, axis=1)
    whole = np.sqrt(np.sum(d**2))
    gap = whole / 2 / sigma
    return SimpleNamespace(
        right=gap,
        squared=np.sum(d**2) / 2 / sigma,
        squared_gap=gap**2,
        full=whole / sigma,
        rms_coordinate=np.sqrt(np.mean(d**2)) / 2 / sigma,
        rms_corner=np.sqrt(np.mean(per_corner**2)) / 2 / sigma,
        mean_corner=per_corner.mean() / 2 / sigma,
        largest=per_corner.max() / 2 / sigma,
        summed=per_corner.sum() / 2 / sigma,
        pixels=whole / 2,
        variance=whole / 2 / sigma**2,
        times_sigma=whole / 2 * sigma,
        no_K=np.sqrt(np.sum(offsets(K=np.eye(3)) ** 2)) / 2 / sigma,
        R_T=np.sqrt(np.sum(offsets(R1=R1.T, R2=R2.T) ** 2)) / 2 / sigma,
        probability=0.5 * erfc(gap / sqrt(2)),
        no_divide=np.sqrt(np.sum(offsets(divide=False) ** 2)) / 2 / sigma,
        per_corner_noise=whole / 2 / (sqrt(2) * sigma),
        half_inside=whole / sqrt(2) / sigma,
        K_T=np.sqrt(np.sum(offsets(K=K.T) ** 2)) / 2 / sigma,
    )


_MISTAKES = (
    Mistake(
        "no square root",
        lambda c: c.squared,
        "you left out the square root: the distance between the two reprojections is "
        "sqrt(sum of the squared offsets) over all 2N coordinates; halve that and divide by sigma.",
    ),
    Mistake(
        "gap squared",
        lambda c: c.squared_gap,
        "you returned the gap squared: take the square root of the summed squared offsets before "
        "halving and dividing by sigma.",
    ),
    Mistake(
        "no half",
        lambda c: c.full,
        "you returned the whole distance in sigma: the flipped pose fits better once the noise reaches "
        "the MIDPOINT between the two reprojections, half the distance (section 2b's gap).",
    ),
    Mistake(
        "rms per coordinate",
        lambda c: c.rms_coordinate,
        "you took the rms offset per coordinate (OpenCV's rms): that averages over the 2N coordinates, "
        "while the gap ADDS them up, sqrt(sum of squares) = sqrt(2N) times the rms. More corners make "
        "the gap larger; that is why the 54-corner board hardly flips and a 4-corner tag does.",
    ),
    Mistake(
        "rms per corner",
        lambda c: c.rms_corner,
        "you took the rms offset per corner: the gap adds all N corners' offsets in quadrature, "
        "sqrt(sum over corners of |offset|^2), it does not average them (sqrt(N) times larger).",
    ),
    Mistake(
        "mean per corner",
        lambda c: c.mean_corner,
        "you averaged each corner's distance: the gap is ONE distance in the 2N-dimensional space of all "
        "the coordinates, sqrt(sum of the squared offsets), not a mean per corner.",
    ),
    Mistake(
        "largest corner",
        lambda c: c.largest,
        "you took the largest corner's offset: the noise of every coordinate counts, so the gap is the "
        "distance over all 2N coordinates together, sqrt(sum of the squared offsets).",
    ),
    Mistake(
        "summed distances",
        lambda c: c.summed,
        "you added the corners' distances: independent directions add in quadrature, "
        "sqrt(sum of |offset|^2), not as a plain sum of |offset|.",
    ),
    Mistake(
        "pixels",
        lambda c: c.pixels,
        "your gap is in pixels: divide by sigma, the noise of each pixel coordinate, to say how many "
        "sigmas the noise must reach.",
    ),
    Mistake(
        "sigma squared",
        lambda c: c.variance,
        "you divided by sigma squared: sigma is already the noise's standard deviation in pixels, so "
        "divide the half distance by sigma itself.",
    ),
    Mistake(
        "times sigma",
        lambda c: c.times_sigma,
        "you multiplied by sigma: the gap is the half distance in UNITS of sigma, so divide by it.",
    ),
    Mistake(
        "no K",
        lambda c: c.no_K,
        "you left out K: the offsets must be in pixels, where sigma is, so project with "
        "K (R X + t) and divide by the third coordinate.",
    ),
    Mistake(
        "R.T for R",
        lambda c: c.R_T,
        "you used R.T where R belongs: the poses are cam_from_board, X_c = R X + t, so a corner "
        "X (a row) goes to X @ R.T + t.",
    ),
    Mistake(
        "no divide by w",
        lambda c: c.no_divide,
        "you never divided by the third coordinate: K (R X + t) is a homogeneous pixel, w times "
        "(u, v, 1); divide each by its own w (keepdims) before taking the offsets.",
    ),
    Mistake(
        "noise per corner",
        lambda c: c.per_corner_noise,
        "you divided by sqrt(2) sigma, the noise of a corner's 2-D position: sigma is the noise of EACH "
        "pixel coordinate, and the distance already sums all 2N coordinates, so divide by sigma itself.",
    ),
    Mistake(
        "half inside the root",
        lambda c: c.half_inside,
        "you halved inside the square root, sqrt(sum of squares / 2): the gap is HALF the distance, "
        "sqrt(sum of the squared offsets) / 2, so halve after taking the root.",
    ),
    Mistake(
        "K transposed",
        lambda c: c.K_T,
        "you multiplied by K on the wrong side (X_c @ K): for points as rows the pixels are "
        "X_c @ K.T, the row form of K X_c.",
    ),
    Mistake(
        "the probability",
        lambda c: c.probability,
        "you returned Phi(-gap), the rule's chance of a flip: the question is the gap itself, in sigma.",
    ),
)


def _diagnosis(args, got, expected) -> str:
    if not is_number(got):
        return not_one_number(got, "the gap in units of sigma")
    hint = first_mistake(
        _MISTAKES, _context(*args), float(got), lambda a, b: np.isclose(a, b, rtol=RTOL, atol=0)
    )
    return hint or (
        f"the gap is {expected:.4f} sigma, not {float(got):.4f}: project the corners with both poses "
        "(K (R X + t), divided by its third coordinate), take the distance over all 2N coordinates, "
        "sqrt(sum of the squared offsets), halve it and divide by sigma."
    )


def _variant(name):
    return mistake_variant(_MISTAKES, name, _context)


register_exercise(
    Exercise(
        name="flip_gap",
        lesson="12",
        reference=flip_gap,
        cases=_cases,
        compare=SameNumber(Tolerance(RTOL, 0.0)),
        diagnose=_diagnosis,
        wrong_variants=(
            (_variant("no square root"), "square root"),
            (_variant("gap squared"), "gap squared"),
            (_variant("no half"), "MIDPOINT"),
            (_variant("half inside the root"), "inside the square root"),
            (_variant("K transposed"), "wrong side"),
            (_variant("rms per coordinate"), "OpenCV's rms"),
            (_variant("rms per corner"), "rms offset per corner"),
            (_variant("mean per corner"), "averaged each corner"),
            (_variant("largest corner"), "largest corner"),
            (_variant("summed distances"), "quadrature"),
            (_variant("pixels"), "in pixels"),
            (_variant("sigma squared"), "sigma squared"),
            (_variant("times sigma"), "multiplied by sigma"),
            (_variant("no K"), "left out K"),
            (_variant("R.T for R"), "R.T where R belongs"),
            (_variant("the probability"), "Phi(-gap)"),
            (_variant("no divide by w"), "third coordinate"),
            (_variant("noise per corner"), "sqrt(2) sigma"),
        ),
        teaching=flip_gap,
        solution_note=(
            "# OpenCV: cv2.solvePnPGeneric(X, pixels, K, None, flags=cv2.SOLVEPNP_IPPE) returns both poses;\n"
            "# cv2.projectPoints(X, rvec, tvec, K, None) reprojects each (lesson 12, section 2b)."
        ),
    )
)
