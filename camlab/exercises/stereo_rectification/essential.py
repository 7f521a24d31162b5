"""Exercise 3 of lesson 11: R and t from the essential matrix (`decompose_essential`)."""

from __future__ import annotations

import numpy as np

from ... import epipolar
from ...camera import rotation_from_axis_angle
from .._core import Exercise, register_exercise

# --------------------------------------------------------------------------- E -> (R, t)


def _essential_cases():
    rng = np.random.default_rng(11)
    out = []
    for scale in (1.0, -2.5, 0.01):
        R = rotation_from_axis_angle(rng.normal(0, 0.3, 3))
        t = rng.normal(0, 1, 3)
        out.append((scale * epipolar.essential_matrix(R, t),))
    return out


def _pose_set(Rs, ts) -> list[tuple[np.ndarray, np.ndarray]]:
    return [
        (np.asarray(R, float), np.asarray(t, float) / np.linalg.norm(t))
        for R, t in zip(Rs, ts, strict=True)
    ]


def _essential_compare(got, expected) -> bool:
    try:
        Rs, ts = (np.asarray(a, dtype=float) for a in got)
    except (TypeError, ValueError):
        return False
    if (
        Rs.shape != (4, 3, 3)
        or ts.shape != (4, 3)
        or not (np.isfinite(Rs).all() and np.isfinite(ts).all())
    ):
        return False
    if not np.allclose(np.linalg.norm(ts, axis=1), 1.0, atol=1e-6):
        return False  # the prompt fixes the scale: unit vectors
    mine = _pose_set(Rs, ts)
    return all(
        any(np.allclose(R, Rg, atol=1e-8) and np.allclose(t, tg, atol=1e-8) for Rg, tg in mine)
        for R, t in _pose_set(*expected)
    )


def _centre_hint(Rs, ts, got, expected) -> str:
    """The hint for t returned as camera 2's centre (C = -R^T t, or R^T t); '' if it is not that."""
    exp_set = _pose_set(*expected)
    centres = [(R, -R.T @ t) for R, t in exp_set]  # C = -R^T t (and R^T t, its sign flip)
    if all(
        any(
            np.allclose(R, Re, atol=1e-8) and min(np.abs(t - c).max(), np.abs(t + c).max()) < 1e-8
            for Re, c in centres
        )
        for R, t in _pose_set(Rs, ts)
    ) and not _essential_compare(got, expected):
        return (
            "your t is camera 2's centre C = -R^T t (or R^T t), which is also E's right null vector (last "
            "row of V^T: E C = [t]x R (-R^T t) = -t x t = 0). With X2 = R X1 + t, t is the LEFT null vector "
            "of E, the last column of U (t^T E = 0); C is where camera 2 sits in camera 1's frame"
        )
    return ""


def _reflection_hint(Rs) -> str:
    """The hint for candidates with det R = -1 (-W for W^T, or no det fix); '' if all are rotations."""
    dets = np.linalg.det(Rs)
    if np.any(dets < 0) and any(
        np.allclose(-R, Rp, atol=1e-8) for R in Rs[dets < 0] for Rp in Rs[dets > 0]
    ):
        return (
            "some of your R are minus another of your R (det -1): you used -W where W^T belongs. "
            "det(-W) = -1, so U (-W) V^T is a reflection; R_b = U W^T V^T"
        )
    if np.any(dets < 0):
        return (
            "some of your R have det = -1 (reflections, not rotations): the SVD's U and V can be "
            "reflections; flip the sign of U (or V^T) when its determinant is -1, before forming U W V^T"
        )
    return ""


def _two_rotations(mine, right) -> str:
    """Two 3 x 3 rotations side by side, 4 decimals: the summarised arrays above cannot show a transpose."""
    rows = [
        "    " + " ".join(f"{x:+.4f}" for x in a) + "   |   " + " ".join(f"{x:+.4f}" for x in b)
        for a, b in zip(mine, right, strict=True)
    ]
    return "    yours" + " " * 21 + "|   expected\n" + "\n".join(rows)


_VT_AGAIN = (
    "you wrote U @ W @ Vt.T: numpy's svd already returns V^T (its third output), so R = U W V^T "
    "is U @ W @ Vt, with no further transpose"
)


def _vt_transposed_again(E, Rs) -> bool:
    """True when every R is U W V (or U W^T V), up to the det fix's signs: numpy's V^T transposed again."""
    U, _, Vt = np.linalg.svd(E)
    W = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    return all(np.allclose(np.abs(U.T @ R @ Vt), np.abs(W), atol=1e-8) for R in Rs)


def _essential_diagnosis(args, got, expected) -> str:
    (E,) = args
    try:
        Rs, ts = (np.asarray(a, dtype=float) for a in got)
    except (TypeError, ValueError):
        return "return two arrays (Rs, ts): Rs of shape (4, 3, 3) and ts of shape (4, 3), one row per candidate"
    if Rs.shape != (4, 3, 3) or ts.shape != (4, 3):
        return f"expected Rs (4, 3, 3) and ts (4, 3), got {Rs.shape} and {ts.shape}: four candidates, (R_a, ±t), (R_b, ±t)"
    gram = np.einsum("kji,kjl->kil", Rs, Rs)
    if not np.allclose(gram, np.eye(3), atol=1e-6):
        dets = np.linalg.det(Rs)
        kept_s = np.allclose(dets, 0, atol=1e-9)
        return (
            f"your R are not rotations (R^T R != I; det R = {', '.join(f'{x:.2g}' for x in dets)})"
            + (
                ": you kept the singular values, U diag(s) V^T. E's third singular value is 0, so that "
                "R is singular; R = U W V^T without S"
                if kept_s
                else ": R = U W V^T from the orthogonal U and V^T of the SVD, with no other factor"
            )
        )
    norms = np.linalg.norm(ts, axis=1)
    if not np.allclose(norms, 1.0, atol=1e-6):
        return (
            f"your t have lengths {', '.join(f'{x:.3g}' for x in norms)}: the prompt asks for unit vectors. "
            "E fixes t only up to scale, so return t = ±u3 (the last column of U, already of length 1), "
            "not a multiple of it"
        )
    hint = _reflection_hint(Rs)
    if hint:
        return hint
    hint = _centre_hint(Rs, ts, got, expected)
    if hint:
        return hint
    u3 = np.linalg.svd(E)[0][:, 2]
    v3 = np.linalg.svd(E)[2][2]
    if any(
        abs(abs(t @ v3) / np.linalg.norm(t) - 1) < 1e-8
        and abs(abs(t @ u3) / np.linalg.norm(t) - 1) > 1e-6
        for t in ts
    ):
        expected_Rs = np.asarray(expected[0], dtype=float)
        if all(any(np.allclose(R.T, Re, atol=1e-8) for Re in expected_Rs) for R in Rs):
            return (
                "your t is E's right null vector and your rotations are transposed: you decomposed E^T "
                "(or swapped U and V^T). E = [t]x R = U diag(1, 1, 0) V^T: R = U W V^T or U W^T V^T, "
                "t = ±U[:, 2]. Your first R and the candidate it transposes:\n"
                + _two_rotations(Rs[0], Rs[0].T)
            )
        return (
            "your t is the right null vector of E (last row of V^T); t is the LEFT null vector, the last "
            "column of U: t^T E = t^T [t]x R = 0"
        )
    if any(
        abs(abs(t @ U_row) - 1) < 1e-8 and abs(abs(t @ u3) - 1) > 1e-6
        for t in ts
        for U_row in [np.linalg.svd(E)[0][2]]
    ):
        return "your t is the last ROW of U; t is the last COLUMN, U[:, 2] (t^T E = 0)"
    if np.all(ts @ u3 > 0) or np.all(ts @ u3 < 0):
        return "all your t have the same sign: the four candidates are (R_a, +t), (R_a, -t), (R_b, +t), (R_b, -t)"
    expected_Rs = np.asarray(expected[0], dtype=float)
    if all(any(np.allclose(R.T, Re, atol=1e-8) for Re in expected_Rs) for R in Rs) and not all(
        any(np.allclose(R, Re, atol=1e-8) for Re in expected_Rs) for R in Rs
    ):
        return (
            "your rotations are transposed: V W^T U^T is (U W V^T)^T. E = [t]x R with R = U W V^T or "
            "U W^T V^T takes camera 1's coordinates to camera 2's (X2 = R X1 + t); did you write Vt.T @ W @ U.T, "
            "or decompose E^T? Your first R and the candidate it transposes:\n"
            + _two_rotations(Rs[0], Rs[0].T)
        )
    if _vt_transposed_again(E, Rs):
        return _VT_AGAIN
    if len({tuple(np.round(R, 6).ravel()) for R in Rs}) < 2:
        return "your four candidates hold only one rotation: R_a = U W V^T and R_b = U W^T V^T (note the transpose)"
    return (
        "with E = U diag(1, 1, 0) V^T and W = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]: R in {U W V^T, U W^T V^T} "
        "and t = ±(last column of U)"
    )


def decompose_essential(E):
    """E = [t]x R = U diag(1, 1, 0) V^T gives two rotations U W V^T, U W^T V^T and t = ±u3.

    Parameters
    ----------
    E : (3, 3) array_like
        An essential matrix.

    Returns
    -------
    Rs : (4, 3, 3) ndarray
        The rotations of the four candidate poses: U W V^T twice, then U W^T V^T twice.
    ts : (4, 3) ndarray
        Their translations, unit length: u3, -u3, u3, -u3.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 9.6.2 (result 9.19).
    """
    U, _, Vt = np.linalg.svd(np.asarray(E, dtype=float))
    if np.linalg.det(U) < 0:  # make U and V rotations, so that U W V^T is one too
        U = -U
    if np.linalg.det(Vt) < 0:
        Vt = -Vt
    W = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    Ra, Rb = U @ W @ Vt, U @ W.T @ Vt
    t = U[:, 2]  # the left null vector of E: the baseline direction
    return np.stack([Ra, Ra, Rb, Rb]), np.stack([t, -t, t, -t])


def _no_det_fix(E):
    U, _, Vt = np.linalg.svd(
        E
    )  # numpy returns det(V^T) = -1 on the first test case, det(U) = -1 on the others
    W = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    Ra, Rb = U @ W @ Vt, U @ W.T @ Vt
    return np.stack([Ra, Ra, Rb, Rb]), np.stack([U[:, 2], -U[:, 2], U[:, 2], -U[:, 2]])


def _kept_singular_values(E):
    U, S, Vt = np.linalg.svd(E)
    W = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    Ra, Rb = U @ W @ np.diag(S) @ Vt, U @ W.T @ np.diag(S) @ Vt
    return np.stack([Ra, Ra, Rb, Rb]), np.stack([U[:, 2], -U[:, 2], U[:, 2], -U[:, 2]])


def _vt_transposed(E):
    """Vt transposed once more: U W V, with the det fix (tests)."""
    U, _, Vt = np.linalg.svd(E)
    U, Vt = U * np.sign(np.linalg.det(U)), Vt * np.sign(np.linalg.det(Vt))
    W = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    Ra, Rb = U @ W @ Vt.T, U @ W.T @ Vt.T
    return np.stack([Ra, Ra, Rb, Rb]), np.stack([U[:, 2], -U[:, 2], U[:, 2], -U[:, 2]])


def _camera_centre(E):
    Rs, ts = decompose_essential(E)
    return Rs, -np.einsum("kji,kj->ki", Rs, ts)  # C = -R^T t for each candidate


def _right_null_vector(E):
    Rs, _ = decompose_essential(E)
    v3 = np.linalg.svd(E)[2][2]
    return Rs, np.stack([v3, -v3, v3, -v3])


register_exercise(
    Exercise(
        name="decompose_essential",
        lesson="11",
        reference=epipolar.decompose_essential_matrix,
        cases=_essential_cases,
        compare=_essential_compare,
        diagnose=_essential_diagnosis,
        wrong_variants=(
            (_no_det_fix, "det = -1"),
            (_vt_transposed, "U @ W @ Vt.T"),
            (_right_null_vector, "LEFT null vector"),
            (_camera_centre, "camera 2's centre C"),
            (
                lambda E: (decompose_essential(E)[0], 7.3 * decompose_essential(E)[1]),
                "unit vectors",
            ),
            (_kept_singular_values, "kept the singular values"),
            (
                lambda E: (lambda Rs, ts: (np.stack([Rs[0], Rs[0], -Rs[0], -Rs[0]]), ts))(
                    *decompose_essential(E)
                ),
                "-W where W^T belongs",
            ),
            (lambda E: decompose_essential(np.asarray(E).T), "decomposed E^T"),
            (
                lambda E: (
                    lambda Rs, ts: (
                        Rs,
                        np.abs(ts @ np.linalg.svd(E)[0][:, 2])[:, None] * np.linalg.svd(E)[0][:, 2],
                    )
                )(*decompose_essential(E)),
                "same sign",
            ),
            (
                lambda E: (lambda Rs, ts: (np.stack([Rs[0]] * 4), ts))(*decompose_essential(E)),
                "only one rotation",
            ),
            (
                lambda E: (lambda Rs, ts: (np.transpose(Rs, (0, 2, 1)), ts))(
                    *decompose_essential(E)
                ),
                "rotations are transposed",
            ),
        ),
        teaching=decompose_essential,
    )
)
