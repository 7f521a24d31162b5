"""Exercise 2 of lesson 11: the epipoles from F (`epipoles`)."""

from __future__ import annotations

import numpy as np

from ... import epipolar
from ...camera import Camera
from .._answers import same_up_to_scale
from .._core import Exercise, register_exercise
from ._rig import rig_points

# --------------------------------------------------------------------------- epipoles from F


def _epipole_cases():
    F1 = epipolar.estimate_fundamental_matrix(*rig_points(3, 0.0))
    c1 = Camera.look_at([0, -3, 0.5], [0, 0, 0.5])
    c2 = c1.replace(t=c1.t - np.array([0.2, 0.0, 0.0]))  # parallel cameras: epipoles at infinity
    F3 = epipolar.fundamental_from_cameras(c1, Camera.look_at([0.4, -2.5, 0.9], [0, 0, 0.5]))
    return [(F1,), (epipolar.fundamental_from_cameras(c1, c2),), (F3,)]


def _epipole_compare(got, expected) -> bool:
    try:
        e1, e2 = got
    except (TypeError, ValueError):
        return False
    return same_up_to_scale(e1, expected.e1, rtol=1e-6) and same_up_to_scale(
        e2, expected.e2, rtol=1e-6
    )


def _epipole_diagnosis(args, got, expected) -> str:
    (F,) = args
    try:
        e1, e2 = (np.asarray(e, dtype=float) for e in got)
    except (TypeError, ValueError):
        return "return two homogeneous 3-vectors (e1, e2): e1 in image 1 and e2 in image 2"
    for e, name in ((e1, "e1"), (e2, "e2")):
        if e.shape != (3,):
            return (
                f"{name} has shape {e.shape}; return homogeneous 3-vectors: an epipole can be at infinity "
                f"(w = 0), which has no (u, v)"
            )
    ideal = abs(expected.e1[2]) < 1e-12 * np.linalg.norm(expected.e1)
    if ideal and not (np.isfinite(e1).all() and np.isfinite(e2).all()):
        return (
            "your epipoles hold inf or NaN: these cameras are parallel, so the epipoles are ideal points "
            "(w = 0, at infinity). Do not divide by w: return the null vectors of F as they are, "
            "homogeneous 3-vectors"
        )
    if same_up_to_scale(e1, expected.e2) and same_up_to_scale(e2, expected.e1):
        return (
            "you swapped them: e1 is the right null vector (F e1 = 0), e2 the left one (F^T e2 = 0)"
        )
    for e, name in ((e1, "e1"), (e2, "e2")):
        if not np.linalg.norm(e) > 1e-12:
            return (
                f"your {name} is the zero vector, which is no point at all (every vector is its multiple). "
                "A cross product of two rows (or columns) of F vanishes when they are parallel or zero, as "
                "they are here; take the null vector from the SVD F = U S V^T instead: e1 = last row of V^T, "
                "e2 = last column of U"
            )
    if same_up_to_scale(e2, expected.e1) and not same_up_to_scale(e1, expected.e2):
        return (
            "your e2 is e1, the null vector of F: e2 is the null vector of F^T (F^T e2 = 0), the last "
            "column of U in F = U S V^T, not the last row of V^T again"
        )
    if same_up_to_scale(e1, expected.e2) and not same_up_to_scale(e2, expected.e1):
        return (
            "your e1 is e2, the null vector of F^T: e1 is the null vector of F itself (F e1 = 0), the "
            "last row of V^T in F = U S V^T; only e2 comes from F^T (its last column of U)"
        )
    U, _, Vt = np.linalg.svd(F)
    if same_up_to_scale(e1, Vt[0]) or same_up_to_scale(e2, U[:, 0]):
        return (
            "you took the singular vector of the LARGEST singular value: numpy's svd sorts them in "
            "decreasing order, so the null vectors (singular value 0) are the LAST row of V^T (e1) and "
            "the LAST column of U (e2)"
        )
    if same_up_to_scale(e1, Vt[:, -1]) or same_up_to_scale(e2, U[-1]):
        return (
            "you took a column of V^T (or a row of U): numpy returns V^T, whose ROWS are the right "
            "singular vectors, so e1 = Vt[-1]; U's COLUMNS are the left ones, so e2 = U[:, -1]"
        )
    r1 = np.linalg.norm(F @ e1) / max(np.linalg.norm(e1), 1e-300)
    r2 = np.linalg.norm(F.T @ e2) / max(np.linalg.norm(e2), 1e-300)
    bad = " and ".join(
        f"|{m}| / |{n}| = {r:.2g}"
        for r, m, n in ((r1, "F e1", "e1"), (r2, "F^T e2", "e2"))
        if r > 1e-9
    )
    return (
        f"{bad} (should be 0 up to rounding, about 1e-15): take the last row of V^T "
        f"(for e1) and the last column of U (for e2) from the SVD F = U S V^T"
    )


def _divided_by_w(F):
    with np.errstate(divide="ignore", invalid="ignore"):
        return tuple(e / e[2] for e in epipolar.epipoles(F))


def epipoles(F):
    """F e1 = 0 and F^T e2 = 0: the right and left singular vectors of F's zero singular value.

    Parameters
    ----------
    F : (3, 3) array_like
        A fundamental matrix (rank 2), x2^T F x1 = 0.

    Returns
    -------
    e1 : (3,) ndarray
        The epipole in image 1, homogeneous, unit length (w may be 0: an epipole at infinity).
    e2 : (3,) ndarray
        The epipole in image 2, likewise.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 9.2.4 (table 9.1).
    """
    U, _, Vt = np.linalg.svd(np.asarray(F, dtype=float))
    return Vt[-1], U[:, -1]  # homogeneous; w may be 0 (an epipole at infinity)


register_exercise(
    Exercise(
        name="epipoles",
        lesson="11",
        reference=epipolar.epipoles,
        cases=_epipole_cases,
        compare=_epipole_compare,
        diagnose=_epipole_diagnosis,
        wrong_variants=(
            (lambda F: tuple(reversed(epipolar.epipoles(F))), "swapped"),
            (
                lambda F: (np.linalg.svd(F)[2][0], np.linalg.svd(F)[0][:, 0]),
                "LARGEST singular value",
            ),
            (lambda F: (np.linalg.svd(F)[2][:, -1], np.linalg.svd(F)[0][-1]), "a column of V^T"),
            (lambda F: (np.linalg.svd(F)[0][:, -1], np.linalg.svd(F)[0][:, -1]), "your e1 is e2"),
            (lambda F: (np.cross(F[0], F[1]), np.cross(F[:, 0], F[:, 1])), "zero vector"),
            (lambda F: (np.linalg.svd(F)[2][-1], np.linalg.svd(F)[2][-1]), "null vector of F^T"),
            (_divided_by_w, "Do not divide by w"),
        ),
        teaching=epipoles,
    )
)
