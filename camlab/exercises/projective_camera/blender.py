"""Lesson 04's exercise blender_matrix_world: an OpenCV pose (R, t) as Blender's matrix_world (OpenGL axes)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import camera as cm
from .._answers import same_array, shape_problem
from .._core import Exercise, Mistake, first_mistake, register_exercise
from ._scenes import cameras
from .rq import sign_flips

# -- blender_matrix_world (OpenCV pose -> Blender camera) -----------------------------------------

_F = np.diag([1.0, -1.0, -1.0])


def _blender_cases():
    # the camera with t_x != 0 first: a look-at camera aimed above the origin has t_x = 0, where
    # -R^T F t (t not flipped) equals R^T t (a sign slip), so its diagnosis could not tell them apart
    cams = cameras()[::-1]
    # ... and the last one as OpenCV returns it: cv2.solvePnP's tvec is a (3, 1) column
    return [(c.R, c.t) for c in cams] + [(cams[0].R, cams[0].t.reshape(3, 1))]


def _blender_exception_hint(exc: Exception, args: tuple) -> str:
    """The cause when the answer fails on OpenCV's (3, 1) tvec (a broadcast or a shape error)."""
    t = np.asarray(args[1])
    if t.shape == (3, 1) and isinstance(exc, (ValueError, IndexError)):
        return (
            "this test passes t as a (3, 1) column, as OpenCV's tvec is (cv2.solvePnP, cv2.calibrateCamera): "
            "R @ t is then (3, 1) and does not fit M[:3, 3], which is (3,). Flatten t first: "
            "t = np.ravel(t) (or np.asarray(t).reshape(3))."
        )
    return ""


def _flipped_axes(s):
    """The sign flip G (other than F) with the rotation block R^T G and the centre right, else None."""
    for G in sign_flips():
        if (
            not np.allclose(G, _F)
            and np.allclose(s.A, s.R.T @ G, atol=1e-9)
            and np.allclose(s.c, s.C, atol=1e-9)
        ):
            return G
    return None


def _flipped_axes_hint(s) -> str:
    G = _flipped_axes(s)
    flipped = " and ".join("xyz"[i] for i in range(3) if G[i, i] < 0)
    if np.linalg.det(G) < 0:
        return (
            f"you flipped only the camera's {flipped} axis: one flipped axis is a mirror (det = -1), "
            f"no rotation, and Blender would render a mirrored picture. The OpenGL frame flips two axes, "
            f"y and z: F = diag(1, -1, -1), so R_gl^T = R^T F."
        )
    return (
        f"you flipped the camera's {flipped} axes; OpenGL keeps x right and flips y (up) and z (backward): "
        f"F = diag(1, -1, -1), so R_gl^T = R^T F."
    )


_MISTAKES = (
    Mistake(
        "R flipped, t not",
        lambda s: s.rotation_right and np.allclose(s.c, -s.R.T @ _F @ s.t, atol=1e-9),
        (
            "you flipped R but not t: t_gl = F t as well, so the last column is -R_gl^T t_gl = -R^T F F t = "
            "-R^T t = C (or write C = -R^T t directly); -R^T F t is not the camera centre."
        ),
    ),
    Mistake(
        "F on the world's side",
        lambda s: np.allclose(s.A, _F @ s.R.T, atol=1e-9) and np.allclose(s.c, _F @ s.C, atol=1e-9),
        (
            "you flipped the world's Y and Z (diag(1, -1, -1, 1) @ world_from_cam): F multiplies on the wrong "
            "side. R_gl = F R flips the camera's axes, the columns of R^T (R^T F), and leaves the world alone, so "
            "the last column stays the camera centre C = -R^T t, not F C."
        ),
    ),
    Mistake("other axes flipped", lambda s: _flipped_axes(s) is not None, _flipped_axes_hint),
    Mistake(
        "the OpenGL pose",
        lambda s: np.allclose(s.A, _F @ s.R, atol=1e-9) and np.allclose(s.c, _F @ s.t, atol=1e-9),
        (
            "you returned the OpenGL pose (R_gl, t_gl) = (F R, F t) itself: that is still cam_from_world. "
            "matrix_world is world_from_cam, its inverse: [[R_gl^T, -R_gl^T t_gl], [0, 1]]."
        ),
    ),
    Mistake(
        "no axis flip",
        lambda s: np.allclose(s.A, s.R.T, atol=1e-9),
        (
            "your rotation block is R^T: the inverse without the axis flip, so the camera would look along +z "
            "with y down, the OpenCV way. Flip first, R_gl = F R with F = diag(1, -1, -1), then R_gl^T = R^T F."
        ),
    ),
    Mistake(
        "F on the wrong side",
        lambda s: (
            np.allclose(s.A, _F @ s.R.T, atol=1e-9) or np.allclose(s.A, _F @ s.R.T @ _F, atol=1e-9)
        ),
        (
            "F multiplies on the wrong side: R_gl = F R flips the camera's axes (R's rows), so R_gl^T = R^T F "
            "flips the columns of R^T. F R^T flips the world's Y and Z instead."
        ),
    ),
    Mistake(
        "R_gl, not its transpose",
        lambda s: np.allclose(s.A, _F @ s.R, atol=1e-9),
        ("your rotation block is R_gl, not its transpose: world_from_cam needs R_gl^T = R^T F."),
    ),
    Mistake(
        "last column t",
        lambda s: s.rotation_right and np.allclose(s.c, s.t, atol=1e-9),
        (
            "the last column is t, the world origin in camera coordinates; matrix_world's is the camera centre C = -R^T t."
        ),
    ),
    Mistake(
        "last column t_gl",
        lambda s: s.rotation_right and np.allclose(s.c, _F @ s.t, atol=1e-9),
        (
            "the last column is t_gl = F t, the world origin in the OpenGL camera's coordinates; matrix_world's "
            "last column is the camera centre in the world, -R_gl^T t_gl = -R^T t = C."
        ),
    ),
    Mistake(
        "last column F C",
        lambda s: s.rotation_right and np.allclose(s.c, _F @ s.C, atol=1e-9),
        (
            "the last column is F C: you flipped the centre. F flips the camera's own axes; the centre is a point "
            "of the world, the same in both conventions, so F does not touch it: C = -R^T t."
        ),
    ),
    Mistake(
        "last column -t",
        lambda s: s.rotation_right and np.allclose(s.c, -s.t, atol=1e-9),
        (
            "the last column is -t, but t negated is not the camera's position (Pitfall 1). t is the world origin "
            "in camera coordinates, so -t runs from the origin to the camera written along the camera's axes; "
            "turn it onto the world's axes with R^T: C = -R^T t."
        ),
    ),
    Mistake(
        "last column -R t",
        lambda s: s.rotation_right and np.allclose(s.c, -s.R @ s.t, atol=1e-9),
        (
            "the last column is -R t: R maps world to camera, so the way back is its inverse, R^T: "
            "R C + t = 0 gives C = -R^T t."
        ),
    ),
    Mistake(
        "last column -t_gl",
        lambda s: s.rotation_right and np.allclose(s.c, -_F @ s.t, atol=1e-9),
        (
            "the last column is -t_gl = -F t: t_gl negated is not the camera's position. Turn it onto the world's "
            "axes with R_gl^T: C = -R_gl^T t_gl (= -R^T t)."
        ),
    ),
    Mistake(
        "last column -R_gl t_gl",
        lambda s: s.rotation_right and np.allclose(s.c, -_F @ s.R @ _F @ s.t, atol=1e-9),
        (
            "the last column is -R_gl t_gl: R_gl maps world to the camera, so the way back is its inverse, "
            "R_gl^T: C = -R_gl^T t_gl (= -R^T t)."
        ),
    ),
    Mistake(
        "last column -C",
        lambda s: s.rotation_right and np.allclose(s.c, -s.C, atol=1e-9),
        (
            "the last column has the wrong sign: it is R^T t = -C. The centre solves R C + t = 0, so "
            "C = -R^T t (= -R_gl^T t_gl), with the minus sign."
        ),
    ),
)
"""The pose slips, in the order they are tested: each a test of the answer's rotation block ``s.A`` and last
column ``s.c`` against the pose (``s.R``, ``s.t``), its centre ``s.C`` and ``s.rotation_right`` (A = R^T F)."""


def _blender_diagnosis(args, got, expected) -> str:
    R, t = np.asarray(args[0], dtype=float), np.ravel(np.asarray(args[1], dtype=float))
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return the 4 x 4 matrix [[R_gl^T, C], [0, 0, 0, 1]]."
    g = np.asarray(got, dtype=float)
    if not np.allclose(g[3], [0.0, 0.0, 0.0, 1.0]):
        if np.allclose(g[:, 3], [0.0, 0.0, 0.0, 1.0]) and np.allclose(g.T, expected, atol=1e-9):
            return (
                "your matrix is transposed: its last row holds C, its last column (0, 0, 0, 1). matrix_world "
                "is [[R_gl^T, C], [0, 0, 0, 1]]: the centre is the last column."
            )
        return "the last row of a rigid motion in homogeneous form is (0, 0, 0, 1)."
    A, c = g[:3, :3], g[:3, 3]
    C = -R.T @ t
    rotation_right = np.allclose(A, R.T @ _F, atol=1e-9)
    context = SimpleNamespace(R=R, t=t, A=A, c=c, C=C, rotation_right=rotation_right)
    return first_mistake(_MISTAKES, context) or (
        "matrix_world = [[R_gl^T, -R_gl^T t_gl], [0, 0, 0, 1]] with R_gl = F R, t_gl = F t, F = diag(1, -1, -1)."
    )


def blender_matrix_world(R, t):
    """Blender's matrix_world (world_from_cam, OpenGL axes) for the OpenCV pose cam_from_world (R, t).

    Parameters
    ----------
    R : (3, 3) array_like
        The rotation of cam_from_world, OpenCV's camera axes (x right, y down, z forward).
    t : (3,) or (3, 1) array_like
        The translation of cam_from_world, world units (OpenCV's tvec is a (3, 1) column).

    Returns
    -------
    (4, 4) ndarray
        [[R_gl^T, -R_gl^T t_gl], [0, 1]] with (R_gl, t_gl) = (F R, F t), F = diag(1, -1, -1): the camera's
        axes in the world (y up, z backward), its last column the camera centre C = -R^T t.
    """
    F = np.diag([1.0, -1.0, -1.0])  # flip the camera's y and z: y up, z backward
    R_gl, t_gl = F @ np.asarray(R), F @ np.ravel(t)  # ravel: OpenCV's tvec is (3, 1)
    M = np.eye(4)
    M[:3, :3] = R_gl.T  # invert the rigid motion: world_from_cam
    M[:3, 3] = -R_gl.T @ t_gl  # = -R^T t, the camera centre C
    return M


register_exercise(
    Exercise(
        name="blender_matrix_world",
        lesson="04",
        reference=cm.blender_matrix_world,
        cases=_blender_cases,
        compare=same_array(rtol=1e-8, atol=1e-9),
        diagnose=_blender_diagnosis,
        exception_hint=_blender_exception_hint,
        wrong_variants=(
            (
                lambda R, t: np.block(
                    [[_F @ R, (_F @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "OpenGL pose",
            ),
            (
                lambda R, t: np.block(
                    [[R.T, (-R.T @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "without the axis flip",
            ),
            (
                lambda R, t: np.block(
                    [[_F @ R.T, (-R.T @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "wrong side",
            ),
            (
                lambda R, t: np.block(
                    [[R.T @ _F, t[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "the last column is t",
            ),
            (
                lambda R, t: np.block(
                    [[R.T @ _F, (_F @ -R.T @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "F does not touch it",
            ),
            (
                lambda R, t: np.block(
                    [[R.T @ _F, (_F @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "t_gl = F t, the",
            ),
            (
                lambda R, t: np.block(
                    [[R.T @ _F, (R.T @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "wrong sign",
            ),
            (lambda R, t: cm.blender_matrix_world(R, t).T, "transposed"),
            (
                lambda R, t: np.block(
                    [[R.T @ _F, (-_F @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "the last column is -t_gl",
            ),
            (
                lambda R, t: np.block(
                    [[R.T @ _F, (-_F @ R @ _F @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "the last column is -R_gl t_gl",
            ),
            (
                lambda R, t: np.block(
                    [[R.T @ _F, -t[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "the last column is -t",
            ),
            (
                lambda R, t: np.block(
                    [[R.T @ _F, (-R @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "the last column is -R t",
            ),
            (
                lambda R, t: np.block(
                    [[_F @ R, (-R.T @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "not its transpose",
            ),
            (
                lambda R, t: np.block(
                    [[R.T @ _F, (-R.T @ _F @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]
                ),
                "flipped R but not t",
            ),
            (
                lambda R, t: (
                    np.diag([1.0, -1.0, -1.0, 1.0])
                    @ np.block([[R.T, (-R.T @ t)[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]])
                ),
                "not F C",
            ),
            (
                lambda R, t: np.block(
                    [
                        [R.T @ np.diag([1.0, 1.0, -1.0]), (-R.T @ t)[:, None]],
                        [np.zeros((1, 3)), np.ones((1, 1))],
                    ]
                ),
                "a mirror",
            ),
        ),
        teaching=blender_matrix_world,
    )
)
