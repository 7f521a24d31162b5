r"""Exercise for lesson 12, measure the world: the height of a segment above the board, from one photo.

One photo measures a segment as if it lay on the board's plane. A segment parallel to the plane,
:math:`h` above it (toward the camera), is projected from the camera's centre :math:`C` onto the
plane, which scales it by exactly :math:`Z/(Z - h)`, :math:`Z` the camera's distance from the
plane (section 2). So a segment of known true length :math:`L` that reads :math:`L_\text{read}`
stands at

.. math:: h = Z \left(1 - \frac{L}{L_\text{read}}\right), \qquad Z = |C_z|, \quad C = -R^\top t ,

with :math:`L_\text{read} = \|p_a - p_b\|`, :math:`\tilde p \simeq H^{-1} \tilde u`, :math:`H = K [r_1\ r_2\ t]`.

References
----------
Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 2.7 (measuring on a rectified plane)
and section 8.6 (single-view metrology: heights from one photo need more than the plane).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ._answers import Tolerance
from ._core import Exercise, Mistake, first_mistake, mistake_variant, register_exercise
from ._numbers import SameNumber, is_number, not_one_number

ATOL_M = 1e-6
"""How close h must be, metres (1 um), absolute: h = Z (1 - L / L_read) is a small difference of two
near-equal numbers, so a relative tolerance on h would reject float32's rounding (0.1 um here,
cv2.perspectiveTransform); the nearest slip below (a half-pixel shift) is 166 um off."""

_K = np.array([[532.8, 0.0, 341.8], [0.0, 533.0, 234.1], [0.0, 0.0, 1.0]])


def _pose(axis, centre):
    """cam_from_board (R, t) of a camera at ``centre`` (board frame, z into the board) looking at the board's middle."""
    from ..camera import rotation_from_axis_angle

    target = np.array([0.1, 0.0625, 0.0])
    z = (target - centre) / np.linalg.norm(target - centre)
    x = np.cross([0.0, 1.0, 0.0], z)
    x /= np.linalg.norm(x)
    R = rotation_from_axis_angle(np.asarray(axis, dtype=float)) @ np.vstack([x, np.cross(z, x), z])
    return R, -R @ centre


def _cases():
    """(K, R, t, a, b, length): a segment h above the board, its ends' ideal pixels, its true length.

    Cameras 0.26 to 1.2 m from the plane, tilted 15-40 degrees; segments 3 mm below the plane (a
    mounted board's table) to 50 mm above it; the board's origin is never below the camera, so
    t_z, |t| and the distance to the plane all differ.
    """
    out = []
    for centre, axis, ends, h in (
        ((0.05, -0.10, -0.245), (0.0, 0.0, 0.3), ((0.0, 0.0), (0.2, 0.0)), 0.05),
        ((0.25, 0.20, -0.40), (0.0, 0.0, -0.5), ((0.0, 0.125), (0.2, 0.125)), 0.008),
        ((-0.10, 0.05, -0.60), (0.0, 0.0, 1.2), ((0.05, 0.0), (0.05, 0.125)), -0.003),
        ((0.30, -0.40, -1.10), (0.0, 0.0, 0.1), ((0.0, 0.0), (0.2, 0.125)), 0.03),
    ):
        R, t = _pose(axis, np.array(centre))
        X = np.array([[*ends[0], -h], [*ends[1], -h]])  # h above the plane: toward the camera, -z
        x = (X @ R.T + t) @ _K.T
        uv = x[:, :2] / x[:, 2:]
        out.append((_K.copy(), R, t, uv[0], uv[1], float(np.linalg.norm(X[1] - X[0]))))
    return out


def height_above_plane(K, R, t, a, b, length):
    """The height h (metres, toward the camera) of a segment parallel to the board, from one photo.

    Parameters
    ----------
    K : (3, 3) ndarray
        Intrinsics, pixels.
    R, t : (3, 3), (3,) ndarray
        The board's pose, cam_from_board (board z points into the board, away from the camera).
    a, b : (2,) ndarray
        The segment's two ends, ideal pixels (u, v).
    length : float
        Its true length, metres.

    Returns
    -------
    float
        h in metres: positive toward the camera, negative below the board's plane.
    """
    H = K @ np.column_stack([R[:, 0], R[:, 1], t])  # the board's plane -> pixels (section 2)
    p = np.linalg.solve(H, np.array([[*a, 1.0], [*b, 1.0]]).T)  # the two pixels, back on the plane
    p = p[:2] / p[2]
    L_read = np.linalg.norm(p[:, 1] - p[:, 0])  # what one photo reads: too long if h > 0
    Z = abs((-R.T @ t)[2])  # the camera's distance from the plane: |z| of its centre C = -R^T t
    return float(Z * (1 - length / L_read))  # Z / (Z - h) = L_read / L, solved for h


def _context(K, R, t, a, b, length):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)

    def H_of(r1, r2):
        return K @ np.column_stack([r1, r2, t])

    def read(H_used, a=a, b=b, divide=True):
        p = np.linalg.solve(H_used, np.array([[*a, 1.0], [*b, 1.0]]).T)
        p = p[:2] / p[2] if divide else p[:2]
        return np.linalg.norm(p[:, 1] - p[:, 0])

    H = H_of(R[:, 0], R[:, 1])
    L_read, Z = read(H), abs((-R.T @ t)[2])
    Z_rt = abs((-R @ t)[2])  # C = -R t: R where R^T belongs

    def h(L_r=L_read, Z=Z):
        return Z * (1 - length / L_r)

    forward = [(H @ [*p, 1.0])[:2] / (H @ [*p, 1.0])[2] for p in (a, b)]
    on_plane = np.linalg.solve(H, np.array([[*a, 1.0], [*b, 1.0]]).T)
    mid = np.r_[
        (on_plane[:2] / on_plane[2]).mean(axis=1), 0.0
    ]  # the segment's midpoint as read on the plane
    return SimpleNamespace(
        right=h(),
        first_order=Z * (L_read / length - 1),
        t_z=h(Z=t[2]),
        t_norm=h(Z=np.linalg.norm(t)),
        sign=-h(),
        mm=1000 * h(),
        inverted=Z * (1 - L_read / length),
        distance=Z * length / L_read,
        no_K=h(read(np.column_stack([R[:, 0], R[:, 1], t]))),
        no_w=h(read(H, divide=False)),
        H_not_inverted=h(np.linalg.norm(forward[1] - forward[0])),
        length_error=L_read - length,
        half=h(read(H, a + 0.5, b + 0.5)),
        minus_half=h(read(H, a - 0.5, b - 0.5)),
        swapped=h(read(H, a[::-1], b[::-1])),
        transposed=h(read(H.T)),  # x @ H^-1 with x a row: H^-T
        C_R=h(Z=Z_rt),
        rows=h(read(H_of(R[0], R[1]))),
        R_T=h(read(H_of(R[0], R[1])), Z_rt),
        depth_mid=h(Z=(R @ mid + t)[2]),
        depth_centre=h(Z=(R @ [0.1, 0.0625, 0.0] + t)[2]),
        K_T=h(read(K.T @ np.column_stack([R[:, 0], R[:, 1], t]))),
    )


_DEPTH_HINT = (
    "you took Z as a board point's depth along the optical axis, z_c of R X + t: that is not the "
    "distance to the PLANE unless the camera looks straight down. Take Z = |C_z|, the camera centre "
    "C = -R^T t in the board frame."
)

_MISTAKES = (
    Mistake("depth of the segment", lambda c: c.depth_mid, _DEPTH_HINT),
    Mistake("depth of the board centre", lambda c: c.depth_centre, _DEPTH_HINT),
    Mistake(
        "K transposed",
        lambda c: c.K_T,
        "you built H with K.T: the plane maps to the pixels by H = K [r1 r2 t], K on the left, untransposed.",
    ),
    Mistake(
        "first order",
        lambda c: c.first_order,
        "you inverted the first-order law, L_read / L = 1 + h / Z: the law is exact, Z / (Z - h) = "
        "L_read / L, so h = Z (1 - L / L_read) (the first-order h is 23 % too large at a reading 23 % long).",
    ),
    Mistake(
        "t_z for Z",
        lambda c: c.t_z,
        "you took Z = t_z: that is the board origin's depth along the camera's optical axis. The law needs "
        "the camera's distance from the board's PLANE, measured along the plane's normal: the z of the "
        "camera centre C = -R^T t in the board frame, |C_z|.",
    ),
    Mistake(
        "|t| for Z",
        lambda c: c.t_norm,
        "you took Z = |t|, the camera's distance from the board's origin: the law needs its distance from "
        "the board's plane, along the plane's normal, |C_z| with C = -R^T t.",
    ),
    Mistake(
        "sign",
        lambda c: c.sign,
        "your height has the wrong sign. Did you drop the abs on C_z? The camera is on the board's -z "
        "side (the board's z points away from it), so C_z < 0 and Z = |C_z|. Else: a segment that reads "
        "LONG stands toward the camera, and the prompt counts that as positive.",
    ),
    Mistake(
        "millimetres",
        lambda c: c.mm,
        "your height is 1000 times too big, in mm: with the board in metres, h comes out in metres.",
    ),
    Mistake(
        "ratio inverted",
        lambda c: c.inverted,
        "you used L_read / L where L / L_read belongs: from Z / (Z - h) = L_read / L, "
        "Z - h = Z L / L_read, so h = Z (1 - L / L_read).",
    ),
    Mistake(
        "Z - h",
        lambda c: c.distance,
        "you returned Z L / L_read = Z - h, the segment's distance from the camera: the height above the "
        "plane is Z minus that, h = Z (1 - L / L_read).",
    ),
    Mistake(
        "no K",
        lambda c: c.no_K,
        "you left out K: the plane maps to the pixels by H = K [r1 r2 t], so a pixel goes back by H^-1 "
        "with that K in it (pixels are not metres).",
    ),
    Mistake(
        "no division by w",
        lambda c: c.no_w,
        "your length on the plane skips the division by w: H^-1 (u, v, 1) is homogeneous, so divide by "
        "its third entry before measuring (section 2: p = (p1 / p3, p2 / p3)).",
    ),
    Mistake(
        "H not inverted",
        lambda c: c.H_not_inverted,
        "you mapped the pixels with H itself: H takes the board's plane to the pixels, so a pixel goes "
        "back to the plane by H^-1 (np.linalg.solve(H, ...)).",
    ),
    Mistake(
        "length error",
        lambda c: c.length_error,
        "you returned L_read - L, how much too long the reading is: the question is the height h at which "
        "the segment stands, h = Z (1 - L / L_read).",
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
        "you shifted the pixels by -0.5: camlab's pixel (u, v) is already the pixel's centre, so there "
        "is no corner-to-centre shift; map (u, v, 1) as it is.",
    ),
    Mistake(
        "u and v swapped",
        lambda c: c.swapped,
        "you swapped u and v (row, column order, as an array index reads them): a pixel here is (u, v) = "
        "(column, row), the order H expects; map (a[0], a[1], 1).",
    ),
    Mistake(
        "transposed",
        lambda c: c.transposed,
        "you applied the transpose H^-T: x @ H^-1 with x a row (or inv(H).T @ x) is the rule for LINES. "
        "A point goes back by H^-1 itself: np.linalg.solve(H, x) for a column, x @ inv(H).T for rows.",
    ),
    Mistake(
        "C = -R t",
        lambda c: c.C_R,
        "you took C = -R t: the camera centre in the board frame is C = -R^T t (from 0 = R C + t), so "
        "Z = |(-R.T @ t)[2]|.",
    ),
    Mistake(
        "rows of R",
        lambda c: c.rows,
        "you built H from the ROWS of R: r1, r2 are its first two COLUMNS, R[:, 0] and R[:, 1] (the board's "
        "x and y axes in the camera frame), so H = K [R[:, 0] R[:, 1] t].",
    ),
    Mistake(
        "R.T for R",
        lambda c: c.R_T,
        "you used R.T where R belongs (both in H and in C): R is cam_from_board, X_cam = R X + t, so "
        "H = K [R[:, 0] R[:, 1] t] and C = -R.T @ t.",
    ),
)


def _diagnosis(args, got, expected) -> str:
    if not is_number(got):
        return not_one_number(got, "the height in metres")
    hint = first_mistake(
        _MISTAKES, _context(*args), float(got), lambda a, b: np.isclose(a, b, rtol=0, atol=ATOL_M)
    )
    off = 1e6 * (float(got) - expected)
    return hint or (
        f"the answer is {1000 * expected:.4f} mm, not {1000 * float(got):.4f} mm ({off:+.1f} um off, "
        f"tolerance {1e6 * ATOL_M:.0f} um): read the segment on "
        "the plane (H^-1), take Z = |C_z| with C = -R^T t, and solve Z / (Z - h) = L_read / L for h."
    )


def _variant(name):
    return mistake_variant(_MISTAKES, name, _context)


register_exercise(
    Exercise(
        name="height_above_plane",
        lesson="12",
        reference=height_above_plane,
        cases=_cases,
        compare=SameNumber(Tolerance(0.0, ATOL_M)),
        diagnose=_diagnosis,
        wrong_variants=(
            (_variant("first order"), "first-order law"),
            (_variant("t_z for Z"), "optical axis"),
            (_variant("depth of the segment"), "not the distance to the PLANE"),
            (_variant("K transposed"), "with K.T"),
            (_variant("|t| for Z"), "board's origin"),
            (_variant("sign"), "abs on C_z"),
            (_variant("millimetres"), "1000 times"),
            (_variant("ratio inverted"), "L_read / L where"),
            (_variant("Z - h"), "distance from the camera"),
            (_variant("no K"), "left out K"),
            (_variant("no division by w"), "division by w"),
            (_variant("H not inverted"), "with H itself"),
            (_variant("length error"), "how much too long"),
            (_variant("half pixel"), "half a pixel"),
            (_variant("minus half pixel"), "-0.5"),
            (_variant("u and v swapped"), "swapped u and v"),
            (_variant("transposed"), "rule for LINES"),
            (_variant("C = -R t"), "C = -R t"),
            (_variant("rows of R"), "ROWS of R"),
            (_variant("R.T for R"), "R.T where R belongs"),
        ),
        teaching=height_above_plane,
        solution_note=(
            "# camlab: camlab.measurement.measure_on_plane(pose, K, a, b) reads the segment on the plane "
            "(with its sigma);\n# pose.centre is C = -R^T t, so Z = abs(pose.centre[2]) (lesson 12, section 2)."
        ),
    )
)
