"""Exercises for lesson 08, camera calibration: a view's pose from its homography.

The exercise is ``view_pose``; lesson 12 builds on it with the pose's Jacobian (``point_jacobian``).
"""

from __future__ import annotations

import numpy as np

from .. import calibration
from ..camera import rotation_from_axis_angle
from ._answers import same_array, shape_problem
from ._core import Exercise, register_exercise

_K = np.array([[820.0, 0.0, 322.4], [0.0, 818.0, 236.8], [0.0, 0.0, 1.0]])


def _pose_reference(K, H):
    pose = calibration.extrinsics_from_homography(K, H)
    return np.column_stack([pose.R, pose.t])


def _skewed(K, R, t, angle):
    """H = K [r1' r2' t] with r2 turned by ``angle`` towards r1 in their plane: noise-like, |r1'| = |r2'| = 1."""
    r1, r2 = R[:, 0], R[:, 1]
    c, s = np.cos(angle / 2), np.sin(angle / 2)
    return K @ np.column_stack([c * r1 + s * r2, s * r1 + c * r2, t])


def _pose_cases():
    # a DLT returns H only up to scale and sign: every case is scaled, two of them by a negative
    # factor (the board would come out behind the camera), and two have columns r1, r2 that are
    # 3 degrees from orthogonal, as noise leaves them (equal lengths, so every normalisation agrees)
    rng = np.random.default_rng(12)
    out = []
    for scale, skew in ((0.004, 0.0), (-2.5, 0.0), (1.3, np.radians(3)), (-0.02, np.radians(3))):
        R = rotation_from_axis_angle(rng.normal(0, 0.5, 3))
        t = np.array([rng.normal(0, 0.05), rng.normal(0, 0.05), 0.45 + 0.1 * rng.random()])
        out.append((_K.copy(), scale * _skewed(_K, R, t, skew)))
    # the board turned about 162 degrees in its own plane (OpenCV may start the corners at the other
    # end): r11 < 0, so a sign chosen by "r11 > 0" puts this board behind the camera
    R = rotation_from_axis_angle(np.array([0.2, 0.1, 0.9 * np.pi]))
    out.append((_K.copy(), 0.7 * _skewed(_K, R, np.array([0.03, -0.02, 0.5]), 0.0)))
    return out


def _pose_slips(K, H, e):
    """(wrong answer, cause) pairs: the pose each typical slip returns on this input."""
    R, t = e[:, :3], e[:, 3]
    return (
        (
            _raw(K, H, flip=False),
            "the board is behind the camera (t_z < 0): H is known only up to sign, so K^-1 H = s "
            "[r1 r2 t] holds for -s too; when t_z < 0 flip the signs of r1, r2 and t",
        ),
        (
            _raw(K, H, flip=False, sign_from=(0, 0)),
            "you chose the sign so that r11 > 0: that fails when the board is turned more than 90 "
            "degrees in its own plane (here r11 < 0); the sign is fixed by t_z > 0 (board in front "
            "of the camera), not by any entry of R",
        ),
        (
            np.column_stack([R.T, -R.T @ t]),
            "you returned the inverse pose board_from_cam, [R^T | -R^T t]; return cam_from_board, "
            "X_cam = R X_board + t, with R = [r1 r2 r3] and t = s K^-1 h3",
        ),
        (
            np.column_stack([R, 1000.0 * t]),
            "t is 1000 times too long: t comes out in the board's units (here metres, as K^-1 h3 "
            "is scaled by the same s as r1); do not convert it to millimetres",
        ),
        (
            _raw(K, H, right=True),
            "you multiplied H @ K^-1: K^-1 multiplies H from the left, K^-1 H = s [r1 r2 t] "
            "(np.linalg.solve(K, H))",
        ),
        (
            _t_only(K, H),
            "you flipped t but not r1, r2: the whole of K^-1 H changes sign, so flip r1, r2 and t together",
        ),
        (
            np.column_stack([R.T, t]),
            "you returned R^T (board_from_cam); return cam_from_board, X_cam = R X_board + t: R = [r1 r2 r3]",
        ),
        (
            np.column_stack([R, -R.T @ t]),
            "t is the camera's centre -R^T t in board coordinates; return t itself, s K^-1 h3",
        ),
        (
            _whole_flip(K, H),
            "det R = -1: you negated all of R when t_z < 0, which flips r3 too (r3 = r1 x r2 does not "
            "change sign when r1 and r2 both do); flip r1, r2 and t before forming r3 = r1 x r2",
        ),
        (
            _raw(K.T, H),
            "you used K^T: r_k and t are proportional to K^-1 h_k with K itself (np.linalg.solve(K, H)), "
            "K is upper triangular",
        ),
        (
            _raw(K, H, gram_schmidt=True),
            "your R is a rotation, but not the nearest one to [r1 r2 r1 x r2]: Gram-Schmidt (or QR) "
            "keeps r1 exactly and bends only r2; the nearest rotation U V^T (exercise 3) shares the "
            "correction between them",
        ),
        (
            _raw(K, H.T),
            "you used the rows of H; h_i is the i-th column, H[:, i]",
        ),
        (
            _raw(np.eye(3), H),
            "you left out K: r_k and t are proportional to K^-1 h_k, not to h_k (np.linalg.solve(K, H))",
        ),
        (
            _raw(np.eye(3), H, fix=False),
            "you left out K: r_k and t are proportional to K^-1 h_k, not to h_k (np.linalg.solve(K, H))",
        ),
    )


def _pose_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ": return the (3, 4) matrix [R | t], np.column_stack([R, t])"
    K, H = args
    g, e = np.asarray(got, dtype=float), np.asarray(expected, dtype=float)
    for wrong, cause in _pose_slips(K, H, e):
        if np.allclose(g, wrong, atol=1e-6):
            return cause
    R, t = g[:, :3], g[:, 3]
    if not np.allclose(R.T @ R, np.eye(3), atol=1e-6):
        off = np.abs(R.T @ R - np.eye(3)).max()
        return (
            f"your R is not a rotation (R^T R differs from I by up to {off:.2g}): with noise r1 and r2 "
            "are not quite orthogonal, so replace [r1 r2 r3] by its nearest rotation U V^T (exercise 3)"
        )
    if np.linalg.det(R) < 0:
        return (
            "det R = -1, a reflection: r3 = r1 x r2, in that order (r2 x r1 makes a reflection); and if you flip signs "
            "when t_z < 0, flip r1, r2 and t before forming r3 (negating all of R flips r3 too)"
        )
    if np.isclose(np.linalg.norm(t), 1.0, atol=1e-6):
        return (
            "your t has length 1: it shares the factor s = 1 / ||K^-1 h1|| with r1 and r2 "
            "(t = s K^-1 h3), it is not normalised by its own length"
        )
    if t[2] < 0:
        return "t_z < 0 puts the board behind the camera: flip the signs of r1, r2 and t when it comes out negative"
    if np.allclose(R, e[:, :3], atol=1e-6):
        return "R is right, t is not: t = s K^-1 h3 with the same s = 1 / ||K^-1 h1|| as r1 (and the same sign)"
    return (
        "R = [r1 r2 r1 x r2] and t from s K^-1 [h1 h2 h3], s = 1 / ||K^-1 h1||, signed so that "
        "t_z > 0, then R replaced by its nearest rotation"
    )


def view_pose(K, H):
    """A view's pose [R | t], cam_from_board, from the intrinsics K and its homography H.

    K^-1 H = s [r1 r2 t] up to an unknown factor s (and sign): s = 1 / ||K^-1 h1||,
    signed so that the board is in front of the camera (t_z > 0); r3 = r1 x r2, and noise is
    removed by replacing [r1 r2 r3] with its nearest rotation U V^T.

    Parameters
    ----------
    K : (3, 3) ndarray
        Intrinsics, pixels.
    H : (3, 3) ndarray
        The board -> image homography, known up to a non-zero factor.

    Returns
    -------
    (3, 4) ndarray
        [R | t] with X_cam = R X_board + t, t in the board's units.

    References
    ----------
    Z. Zhang (2000), "A flexible new technique for camera calibration", IEEE TPAMI 22(11),
    section 3.1 and appendix C.
    """
    A = np.linalg.solve(K, H)  # s [r1 r2 t]
    s = 1.0 / np.linalg.norm(A[:, 0])
    if A[2, 2] * s < 0:  # the board must be in front: t_z > 0
        s = -s
    r1, r2, t = s * A[:, 0], s * A[:, 1], s * A[:, 2]
    U, _, Vt = np.linalg.svd(np.column_stack([r1, r2, np.cross(r1, r2)]))
    R = U @ np.diag([1.0, 1.0, np.linalg.det(U @ Vt)]) @ Vt
    return np.column_stack([R, t])


def _raw(K, H, flip=True, fix=True, own_t=False, cross=np.cross, gram_schmidt=False, **slip):
    """A pose with one step changed, for the wrong variants.

    ``sign_from=(i, j)`` signs the scale so that entry (i, j) of R is positive (the "r11 > 0" slip);
    ``right=True`` forms H K^-1 instead of K^-1 H.
    """
    A = H @ np.linalg.inv(K) if slip.get("right") else np.linalg.solve(K, H)
    lam = 1.0 / np.linalg.norm(A[:, 0])
    if flip and A[2, 2] * lam < 0:
        lam = -lam
    if "sign_from" in slip and A[slip["sign_from"]] * lam < 0:
        lam = -lam
    r1, r2, t = lam * A[:, 0], lam * A[:, 1], lam * A[:, 2]
    if own_t:
        t = t / np.linalg.norm(t)
    if gram_schmidt:  # a rotation, but not the nearest: r1 kept, r2 made orthogonal to it
        q1 = r1 / np.linalg.norm(r1)
        q2 = r2 - (q1 @ r2) * q1
        q2 /= np.linalg.norm(q2)
        return np.column_stack([q1, q2, np.cross(q1, q2), t])
    M = np.column_stack([r1, r2, cross(r1, r2)])
    if fix:
        U, _, Vt = np.linalg.svd(M)
        M = U @ np.diag([1.0, 1.0, np.sign(np.linalg.det(U @ Vt))]) @ Vt
    return np.column_stack([M, t])


def _whole_flip(K, H):
    """[R | t] built without the sign fix, then all of it negated when t_z < 0: det R = -1."""
    g = _raw(K, H, flip=False)
    return -g if g[2, 3] < 0 else g


def _t_only(K, H):
    g = _raw(K, H, flip=False)
    return np.column_stack([g[:, :3], np.sign(g[2, 3]) * g[:, 3]])


register_exercise(
    Exercise(
        name="view_pose",
        lesson="08",
        reference=_pose_reference,
        cases=_pose_cases,
        compare=same_array(rtol=1e-6, atol=1e-9),
        diagnose=_pose_diagnosis,
        ndarray_only=True,
        wrong_variants=(
            (lambda K, H: _raw(K, H, flip=False), "behind the camera"),
            (_t_only, "flipped t but not"),
            (_whole_flip, "flips r3 too"),
            (lambda K, H: _raw(K.T, H), "K^T"),
            (lambda K, H: _raw(K, H, gram_schmidt=True), "not the nearest one"),
            (lambda K, H: (_raw(K, H)[:, :3], _raw(K, H)[:, 3]), "np.column_stack([R, t])"),
            (lambda K, H: _raw(K, H, flip=False, sign_from=(0, 0)), "r11 > 0"),
            (
                lambda K, H: (lambda g: np.column_stack([g[:, :3].T, -g[:, :3].T @ g[:, 3]]))(
                    _raw(K, H)
                ),
                "inverse pose",
            ),
            (
                lambda K, H: (lambda g: np.column_stack([g[:, :3], 1000 * g[:, 3]]))(_raw(K, H)),
                "1000 times",
            ),
            (lambda K, H: _raw(K, H, right=True), "from the left"),
            (lambda K, H: _raw(K, H, fix=False), "nearest rotation"),
            (lambda K, H: _raw(K, H, own_t=True), "length 1"),
            (lambda K, H: _raw(K, H, cross=lambda a, b: np.cross(b, a), fix=False), "r2 x r1"),
            (lambda K, H: _raw(K, H.T), "rows of H"),
            (lambda K, H: _raw(np.eye(3), H), "left out K"),
            (lambda K, H: np.column_stack([_raw(K, H)[:, :3].T, _raw(K, H)[:, 3]]), "R^T"),
            (lambda K, H: (lambda g: -g[:, :3].T @ g[:, 3])(_raw(K, H)), "(3, 4)"),
            (
                lambda K, H: (lambda g: np.column_stack([g[:, :3], -g[:, :3].T @ g[:, 3]]))(
                    _raw(K, H)
                ),
                "centre",
            ),
        ),
        teaching=view_pose,
        solution_note=(
            "# camlab's version: camlab.calibration.extrinsics_from_homography(K, H) returns a (R, t) "
            "pair; this exercise joins them, np.column_stack([R, t])"
        ),
    )
)
