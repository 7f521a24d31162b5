"""Lesson 04's exercise camera_centre: the centre C of P = K [R | t], its right null vector (P C = 0)."""

from __future__ import annotations

import numpy as np

from ... import camera as cm
from .._answers import same_array, same_up_to_scale, shape_problem
from .._core import Exercise, register_exercise
from ._scenes import cameras

# -- camera_centre ----------------------------------------------------------------------


def _centre_cases():
    # P at other scales (|m3| != 1 in all but the first): a centre scaled by the wrong number fails early
    return [(s * c.P,) for s, c in zip((1.0, 2.5, 0.02), cameras(), strict=True)] + [
        (-0.01 * cameras()[1].P,)
    ]


def _flat_centre(got):
    """A (4, 1) column or (1, 4) row as the 4-vector it holds.

    H&Z writes C as a column; scipy's null_space returns one. Anything else is returned unchanged.
    """
    try:
        g = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        return got
    return g.ravel() if g.shape in ((4, 1), (1, 4)) else got


_same_centre = same_array(rtol=1e-8, atol=1e-10)  # the prompt fixes the scale: last entry 1


def _centre_compare(got, expected) -> bool:
    return _same_centre(_flat_centre(got), expected)


def _centre_diagnosis(args, got, expected) -> str:
    (P,) = args
    got = _flat_centre(got)
    g = np.asarray(got, dtype=float) if got is not None else None
    if g is not None and g.shape == (3,):
        if same_up_to_scale(g, np.linalg.svd(P)[0][:, -1], rtol=1e-6):
            return (
                "you returned a left singular vector (3 numbers, on the image side): the SVD of P.T, or U of "
                "np.linalg.svd(P). The centre is P's right null vector, 4 numbers: U, S, Vt = np.linalg.svd(P), "
                "C = Vt[-1], then divide it by C[3]."
            )
        return (
            "you returned a 3-vector; return the homogeneous centre (X, Y, Z, 1), "
            "the null vector of P (P C = 0)."
        )
    problem = shape_problem(got, expected)
    if problem:
        return problem
    residual = np.linalg.norm(P @ g) / (np.linalg.norm(P) * max(np.linalg.norm(g), 1e-300))
    if residual > 1e-8:
        slip = _centre_slip(P, g, np.asarray(expected, dtype=float))
        if slip:
            return slip
        return (
            f"P C is not 0 (relative |P C| = {residual:.3g}). The centre is the null space of P: "
            f"the last right singular vector of np.linalg.svd(P), or (-M^-1 p4, 1)."
        )
    if np.isclose(g[3], -1.0):
        return (
            "P C = 0, but your last coordinate is -1: you divided the null vector by -v[3] (or negated the "
            "result). Divide by v[3] itself, so that C = (X, Y, Z, 1); C and -C are the same point, but the "
            "check, like every camlab function, fixes the last entry to +1."
        )
    return (
        f"P C = 0, but your last coordinate is {g[3]:.4g}: the null vector is defined only up to scale; "
        f"divide it by its last entry so that its last coordinate is 1 (C = (X, Y, Z, 1))."
    )


def _centre_slip(P, got, expected) -> str | None:
    """The cause when the 4-vector is a known wrong one: V's column for its row, U's, a sign, p4."""
    U, _, Vt = np.linalg.svd(P)
    if same_up_to_scale(got, Vt[:, -1], rtol=1e-6):
        return (
            "you took the last column of Vt. np.linalg.svd returns Vt, V transposed: the right singular "
            "vectors are its rows, so the null vector is the last row, Vt[-1], not Vt[:, -1]."
        )
    reduced = np.linalg.svd(P, full_matrices=False)[2][-1]
    if same_up_to_scale(got, reduced, rtol=1e-6) or same_up_to_scale(
        got, reduced / reduced[3], rtol=1e-6
    ):
        return (
            "you called np.linalg.svd(P, full_matrices=False): for a 3 x 4 P it returns only three right singular "
            "vectors, those of the three non-zero singular values, so its last row is not the null vector. Use the "
            "full SVD, np.linalg.svd(P), whose Vt is 4 x 4: the centre is Vt[-1]."
        )
    if same_up_to_scale(got[:3], U[:, -1], rtol=1e-6):
        return (
            "you took the last column of U, a left singular vector (3 numbers, on the image side). "
            "The centre is a right singular vector, a 4-vector: the last row of Vt, Vt[-1]."
        )
    if np.allclose(got[:3], -expected[:3], rtol=1e-6) and np.isclose(got[3], 1.0):
        return "the sign is flipped: P C = M C + p4 = 0 gives C = -M^-1 p4 (with the minus)."
    for digits in range(7):
        if np.allclose(got, np.round(expected, digits), rtol=0, atol=1e-12):
            return (
                f"you rounded the centre to {digits} decimal{'s' if digits != 1 else ''}. A rounded centre is "
                f"no longer P's null vector (P C != 0): return v / v[3] as it is, no np.round; round only "
                f"when you print it."
            )
    M, p4 = P[:, :3], P[:, 3]
    if np.allclose(got[:3], -M.T @ p4, rtol=1e-6):
        return (
            "you used M^T for M^-1 (C = -M^T p4, as in C = -R^T t). M = K R is not a rotation, so its inverse "
            "is not its transpose: C = -M^-1 p4, np.linalg.solve(M, -p4), or the last row of Vt."
        )
    if np.isclose(got[3], 1.0) and same_up_to_scale(got[:3], expected[:3], rtol=1e-6):
        if same_up_to_scale(np.abs(got[:3]), np.abs(Vt[-1, :3]), rtol=1e-6) and np.allclose(
            np.abs(got[:3]), np.abs(Vt[-1, :3]), rtol=1e-6
        ):
            return (
                "your (X, Y, Z) are the first three entries of the unit null vector: you set the last entry to 1 "
                "instead of dividing the whole null vector by it. C = v / v[3]."
            )
        ratio = float(np.dot(got[:3], expected[:3]) / np.dot(expected[:3], expected[:3]))
        return (
            f"your (X, Y, Z) points the right way but is {ratio:.4g} times the centre: it was divided (or "
            f"multiplied) by a number other than the null vector's last entry, such as P's scale or |m3|. "
            f"The centre solves M C + p4 = 0 whatever P's scale: C = -M^-1 p4 exactly, or v / v[3] for the "
            f"null vector v."
        )
    if np.allclose(got[:3], -p4 @ np.linalg.inv(M), rtol=1e-6):
        return (
            "you multiplied p4 by M^-1 from the wrong side: p4 @ inv(M) is inv(M)^T p4. The centre solves "
            "M C = -p4, so C = -inv(M) @ p4, or np.linalg.solve(M, -p4)."
        )
    pose = _pose_slip(P, got)
    if pose:
        return pose
    if same_up_to_scale(got[:3], P[:, 3], rtol=1e-6):
        return (
            "p4 (P's last column) is the image of the world origin, not the centre. The centre solves "
            "M C + p4 = 0: C = -M^-1 p4, or the last row of Vt."
        )
    return None


def _pose_slip(P, got) -> str | None:
    """The cause when (X, Y, Z) is t or -R t of P = K [R | t] (up to the sign slips): the pose read as the centre."""
    try:
        _, R, t, _ = cm.decompose_projection_matrix(P)
    except Exception:  # noqa: BLE001 - a degenerate P has no pose to compare with
        return None
    if not np.isclose(got[3], 1.0):
        return None
    if np.allclose(got[:3], t, rtol=1e-6, atol=1e-9) or np.allclose(
        got[:3], -t, rtol=1e-6, atol=1e-9
    ):
        return (
            "your (X, Y, Z) is t (the last column of [R | t], from K^-1 p4), not the centre: t is the world "
            "origin in camera coordinates, where the world origin sits as seen from the camera. The centre is "
            "the point the camera maps to 0, R C + t = 0, so C = -R^T t, or -M^-1 p4, or the last row of Vt."
        )
    if np.allclose(got[:3], -R @ t, rtol=1e-6, atol=1e-9) or np.allclose(
        got[:3], R @ t, rtol=1e-6, atol=1e-9
    ):
        return (
            "your (X, Y, Z) is -R t: R maps world to camera coordinates, so undoing it needs its inverse, R^T. "
            "R C + t = 0 gives C = -R^T t (transpose R), or -M^-1 p4, or the last row of Vt."
        )
    return None


def _centre_exception_hint(exc, args) -> str:
    """The cause when indexing entry 3 of a 3-vector fails: the SVD of P.T, or -M^-1 p4 without its 1."""
    if isinstance(exc, IndexError) and "index 4" in str(exc) and "size 4" in str(exc):
        return (
            "you indexed entry 4 of the null vector, which has 4 entries, indices 0 .. 3 (Python counts from 0): "
            "its last entry is v[3], or v[-1], so C = v / v[3]."
        )
    if isinstance(exc, IndexError) and "size 3" in str(exc):
        return (
            "you indexed entry 3 (the fourth) of a vector with 3 entries. If it came from np.linalg.svd(P.T): "
            "that SVD's Vt is 3 x 3 and holds the image-side (left) singular vectors of P; the centre is P's "
            "right null vector, 4 numbers: U, S, Vt = np.linalg.svd(P), v = Vt[-1], C = v / v[3]. If it came "
            "from C = -M^-1 p4, it has no fourth entry to divide by: return np.append(C, 1.0)."
        )
    return ""


def camera_centre(P):
    """The homogeneous centre C with P C = 0: P's right null vector, scaled to w = 1.

    Parameters
    ----------
    P : (3, 4) ndarray
        A finite projective camera (its left 3 x 3 block invertible).

    Returns
    -------
    (4,) ndarray
        C = (X, Y, Z, 1), the camera centre in world coordinates.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 6.2.1 (camera anatomy).
    """
    _, _, Vt = np.linalg.svd(P)
    # the null vector: the full SVD's 4th right singular vector (its singular value, 0, is not in S)
    C = Vt[-1]
    return C / C[3]


register_exercise(
    Exercise(
        name="camera_centre",
        lesson="04",
        reference=cm.camera_centre,
        cases=_centre_cases,
        compare=_centre_compare,  # a flat 4-vector, or a (4, 1) column, with last entry 1
        diagnose=_centre_diagnosis,
        wrong_variants=(
            (lambda P: -np.linalg.solve(P[:, :3], P[:, 3]), "returned a 3-vector"),
            (
                lambda P: np.append(-P[:, 3], 1.0),
                "image of the world origin",
            ),  # confuses t with the centre
            (lambda P: (lambda v: v / v[3])(np.linalg.svd(P)[2][:, -1]), "last row"),
            (lambda P: np.append(np.linalg.svd(P)[0][:, -1], 1.0), "left singular vector"),
            (lambda P: np.append(np.linalg.solve(P[:, :3], P[:, 3]), 1.0), "sign is flipped"),
            (
                lambda P: np.linalg.svd(P)[2][-1],
                "last coordinate is 1",
            ),  # the unit null vector, not scaled
            (lambda P: np.append(-P[:, :3].T @ P[:, 3], 1.0), "not a rotation"),
            (lambda P: np.append(np.linalg.svd(P)[2][-1][:3], 1.0), "instead of dividing"),
            (
                lambda P: np.append(
                    -np.linalg.solve(P[:, :3], P[:, 3]) / np.linalg.norm(P[2, :3]), 1.0
                ),
                "times the centre",
            ),
            (lambda P: np.linalg.svd(np.asarray(P).T)[2][-1], "left singular vector"),
            (
                lambda P: (lambda v: v / v[3])(np.linalg.svd(np.asarray(P).T)[2][-1]),
                "np.linalg.svd(P.T)",
            ),
            (
                lambda P: (lambda v: v / v[3])(np.linalg.svd(P, full_matrices=False)[2][-1]),
                "full_matrices=False",
            ),
            (lambda P: (lambda v: v / v[4])(np.linalg.svd(P)[2][-1]), "indices 0 .. 3"),
            (lambda P: np.round(cm.camera_centre(P), 2), "you rounded the centre"),
            (
                lambda P: (lambda v: v / -v[3])(np.linalg.svd(P)[2][-1]),
                "divided the null vector by -v[3]",
            ),
            (lambda P: np.append(-P[:, 3] @ np.linalg.inv(P[:, :3]), 1.0), "from the wrong side"),
            (lambda P: np.append(cm.decompose_projection_matrix(P).t, 1.0), "your (X, Y, Z) is t"),
            (
                lambda P: (lambda d: np.append(-d.R @ d.t, 1.0))(cm.decompose_projection_matrix(P)),
                "is -R t",
            ),
            (
                lambda P: np.linalg.svd(P)[2][-1][:, None],
                "last coordinate is 1",
            ),  # a column, unscaled
        ),
        exception_hint=lambda exc, args: _centre_exception_hint(exc, args),
        teaching=camera_centre,
    )
)
