"""Exercise 9 of lesson 11: the homography H2 = G R T that sends the right epipole to infinity (`hartley_H2`)."""

from __future__ import annotations

import numpy as np

from .._answers import same_up_to_scale, shape_problem
from .._core import Exercise, register_exercise

# --------------------------------------------------------------------------- H2 = G R T


def _hartley_cases():
    """Epipoles left and right of the image, above and below its centre row, one with w != 1."""
    return [
        (np.array([-823.0, 797.4, 1.0]), (640, 480)),
        (np.array([2400.0, -350.0, 1.0]), (640, 480)),
        (0.5 * np.array([-3100.0, -820.0, 1.0]), (800, 600)),  # homogeneous: w = 0.5
    ]


def _h2(
    e2,
    image_size,
    *,
    g_sign=-1.0,
    turn=-1.0,
    centre=None,
    no_t=False,
    order="GRT",
    dehomogenise=True,
    wrap=True,
    signed_f=True,
    degrees=False,
    g_is_f=False,
    t_in_product=True,
    transpose=False,
):
    """H2 = G R T with the slips the keywords name (the defaults: the right answer)."""
    e2 = np.asarray(e2, dtype=float)
    w, h = image_size
    c = np.array([(w - 1) / 2, (h - 1) / 2]) if centre is None else np.asarray(centre, float)
    T = np.eye(3) if no_t else np.array([[1, 0, -c[0]], [0, 1, -c[1]], [0, 0, 1.0]])
    eT = T @ e2
    theta = np.arctan2(eT[1] * np.sign(eT[2]), eT[0] * np.sign(eT[2]))
    if wrap:
        theta = (theta + np.pi / 2) % np.pi - np.pi / 2
    a = turn * (np.degrees(theta) if degrees else theta)
    R = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1.0]])
    eR = R @ eT
    f = eR[0] / eR[2] if dehomogenise else eR[0]
    f = f if signed_f else abs(f)
    G = np.array([[1, 0, 0], [0, 1, 0], [g_sign * f if g_is_f else g_sign / f, 0, 1.0]])
    H = {"GRT": G @ R @ T if t_in_product else G @ R, "TRG": T @ R @ G}[order]
    return H.T if transpose else H


def hartley_H2(e2, image_size):
    r"""Hartley's :math:`H_2 = G R T`: the right image's epipole sent to infinity along u.

    :math:`T` moves the image centre :math:`((w-1)/2, (h-1)/2)` to the origin; :math:`R` turns the
    translated epipole onto the u axis, by the smaller of the two turns (so the image stays
    upright), where it is :math:`(f, 0, 1)`; :math:`G` with :math:`G_{31} = -1/f` sends it to
    :math:`(f, 0, 0)`, the ideal point of the u axis: every epipolar line becomes a row.

    Parameters
    ----------
    e2 : (3,) array_like
        The right epipole, homogeneous (w != 0), outside the image.
    image_size : (width, height)
        The image size in pixels.

    Returns
    -------
    (3, 3) ndarray
        :math:`H_2`, pixels of image 2 to rectified pixels (up to scale).

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 11.12; R. I. Hartley (1999),
    "Theory and practice of projective rectification", IJCV 35(2).
    """
    e2 = np.asarray(e2, dtype=float)
    w, h = image_size
    T = np.array([[1, 0, -(w - 1) / 2], [0, 1, -(h - 1) / 2], [0, 0, 1.0]])
    eT = T @ e2
    theta = np.arctan2(eT[1] / eT[2], eT[0] / eT[2])  # the epipole's direction from the centre
    theta = (theta + np.pi / 2) % np.pi - np.pi / 2  # the smaller turn: the image stays upright
    R = np.array([[np.cos(theta), np.sin(theta), 0], [-np.sin(theta), np.cos(theta), 0], [0, 0, 1]])
    eR = R @ eT  # on the u axis: (f, 0, 1) up to scale
    f = eR[0] / eR[2]
    G = np.array([[1, 0, 0], [0, 1, 0], [-1 / f, 0, 1]])
    return G @ R @ T


_SLIPS = [
    (
        dict(g_sign=1.0),
        "G31 = +1/f: G must send (f, 0, 1) to (f, 0, 0), so G31 = -1/f (1 - f/f = 0)",
    ),
    (
        dict(turn=1.0),
        "you turned by +theta: the epipole's direction is theta, so R = rotation by -theta brings it "
        "onto the u axis ([[cos, sin, 0], [-sin, cos, 0], [0, 0, 1]])",
    ),
    (
        dict(no_t=True),
        "you left out T: the rotation must turn the epipole about the image centre, so first move "
        "((w - 1)/2, (h - 1)/2) to the origin, then R, then G",
    ),
    (
        dict(order="TRG"),
        "you composed in the wrong order (T R G applies G first): H2 = G R T applies T, then R, then G",
    ),
    (
        dict(dehomogenise=False),
        "your f is the u entry of the homogeneous rotated epipole: f is its Euclidean u, eR[0] / eR[2] "
        "(this epipole has w != 1)",
    ),
    (
        dict(wrap=False),
        "your R turns the image upside down: of the two turns that put the epipole on the u axis "
        "(theta and theta + 180 deg) take the smaller, theta wrapped into [-90, 90) deg",
    ),
    (
        dict(degrees=True),
        "your turn is in degrees: np.cos and np.sin take radians, so build R from theta as "
        "np.arctan2 returns it (do not convert with np.degrees)",
    ),
    (
        dict(g_is_f=True),
        "G31 = -f: G must send (f, 0, 1) to (f, 0, 0), so its third row is (-1/f, 0, 1) (-f * f + 1 != 0)",
    ),
    (
        dict(transpose=True),
        "your H2 is transposed: with points as columns, H2 @ x must apply T, then R, then G; "
        "check the rows of R (and T's translation in its last column, G's -1/f in its last row)",
    ),
    (
        dict(t_in_product=False),
        "you computed R and f from the translated epipole T e but left T out of the product: "
        "H2 = G @ R @ T",
    ),
]


_ABS_F = (
    "your f is a distance, |eR|: f is signed, the rotated epipole's u coordinate eR[0] / eR[2], "
    "negative when the epipole lies left of the centre (as here), and G31 = -1/f needs its sign"
)


def _hartley_diagnosis(args, got, expected, run=None) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". H2 is the (3, 3) homography G R T."
    e2, size = args
    g = np.asarray(got, dtype=float)
    w, h = size
    if same_up_to_scale(g, _h2(e2, size, signed_f=False), rtol=1e-6) and run is not None:
        # f < 0 here, so |f| and G31 = +1/f give the same H2: an epipole right of the centre
        # (f > 0) tells them apart, where |f| is right and +1/f is not
        e_right, s_right = _hartley_cases()[1]
        try:
            right_ok = same_up_to_scale(
                run(e_right, s_right), hartley_H2(e_right, s_right), rtol=1e-6
            )
        except Exception:  # the student's function failing there: fall back on the sign hint
            right_ok = False
        if right_ok:
            return _ABS_F
    for keywords, hint in _SLIPS + [
        (
            dict(centre=(w / 2, h / 2)),
            "your image centre is (w/2, h/2): with pixel centres at "
            "integers it is ((w - 1)/2, (h - 1)/2)",
        ),
        (
            dict(centre=(-(w - 1) / 2, -(h - 1) / 2)),
            "your T translates by +c: T moves the centre c = ((w - 1)/2, (h - 1)/2) to the origin, "
            "so its last column is (-c_u, -c_v, 1)",
        ),
        (
            dict(centre=((h - 1) / 2, (w - 1) / 2)),
            "you swapped width and height in the centre: "
            "image_size is (width, height), the centre ((w - 1)/2, (h - 1)/2)",
        ),
    ]:
        if same_up_to_scale(g, _h2(e2, size, **keywords), rtol=1e-6):
            return hint
    e_out = g @ np.asarray(e2, float)
    e_out = np.round(e_out / np.abs(e_out).max(), 4) + 0.0  # + 0.0: print -0 as 0
    if abs(e_out[1]) < 1e-4 and abs(e_out[2]) < 1e-4:
        return (
            "your H2 does send the epipole to infinity along u, but it is not the G R T of the prompt: "
            "T must move ((w - 1)/2, (h - 1)/2) to the origin, R turn by the smaller angle, G31 = -1/f"
        )
    return (
        f"your H2 sends the epipole to {e_out} (scaled), not to (1, 0, 0), the point at infinity along u: "
        "check T (centre to the origin), R (epipole onto the u axis) and G31 = -1/f"
    )


register_exercise(
    Exercise(
        name="hartley_H2",
        lesson="11",
        reference=hartley_H2,
        cases=_hartley_cases,
        compare=lambda got, expected: same_up_to_scale(got, expected, rtol=1e-6),
        diagnose=_hartley_diagnosis,
        diagnosis_runs=True,
        up_to_scale=True,
        wrong_variants=tuple((lambda e, s, k=k: _h2(e, s, **k), hint[:20]) for k, hint in _SLIPS)
        + ((lambda e, s: _h2(e, s, centre=(s[0] / 2, s[1] / 2)), "(w/2, h/2)"),)
        + ((lambda e, s: _h2(e, s, centre=(-(s[0] - 1) / 2, -(s[1] - 1) / 2)), "translates by +c"),)
        + ((lambda e, s: _h2(e, s, signed_f=False), "your f is a distance"),),
        teaching=hartley_H2,
        solution_note=(
            "# camlab.rectification.rectify_uncalibrated builds the same H2, then adds Loop & Zhang's\n"
            "# shear and one scale and shift that fit both images into the frame"
        ),
    )
)
