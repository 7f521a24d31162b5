"""Exercise 4 of lesson 11: triangulate one match by the linear DLT (`triangulate_point`)."""

from __future__ import annotations

import numpy as np

from ... import epipolar
from .._answers import same_array, shape_problem
from .._core import Exercise, register_exercise
from ._rig import converging_pair

# --------------------------------------------------------------------------- linear triangulation


def _triangulation_cases():
    """Three exact matches of two rigs, one with 0.3 px of noise, one with P scaled by 1e-3."""
    rng = np.random.default_rng(11)
    cases = []
    for (b, toe), X, noise, scale in (
        ((0.2, 0.0), (0.1, 2.0, 1.2), 0.0, 1.0),
        ((0.5, np.deg2rad(30)), (-0.3, 3.5, 0.6), 0.0, 1.0),
        ((0.3, np.deg2rad(10)), (0.4, 1.5, 1.4), 0.3, 1.0),
        ((0.2, np.deg2rad(5)), (0.0, 2.5, 0.9), 0.0, 1e-3),
    ):
        c1, c2 = converging_pair(b, toe)
        X = np.array(X)
        x1, x2 = (c.project(X[None])[0] + rng.normal(0, noise, 2) for c in (c1, c2))
        cases.append((scale * c1.P, scale * c2.P, x1, x2))
    return cases


def _reference(P1, P2, x1, x2):
    """camlab.epipolar.triangulate_points on one match: the linear DLT, its rows scaled to unit norm."""
    return epipolar.triangulate_points(
        np.asarray(P1), np.asarray(P2), np.reshape(x1, (1, 2)), np.reshape(x2, (1, 2))
    )[0]


def _rows(P1, P2, x1, x2, swap_uv=False):
    (u1, v1), (u2, v2) = (x1[::-1], x2[::-1]) if swap_uv else (x1, x2)
    return np.array(
        [u1 * P1[2] - P1[0], v1 * P1[2] - P1[1], u2 * P2[2] - P2[0], v2 * P2[2] - P2[1]]
    )


def _plain(A, pick=lambda Vt: Vt[-1]):
    Xh = pick(np.linalg.svd(A)[2])
    return Xh[:3] / Xh[3]


def _reprojection_ss(P1, P2, x1, x2, X) -> float:
    """Sum of the squared reprojection errors (px^2) of the world point ``X`` in both images."""
    Xh = np.append(X, 1.0)
    return float(sum(np.sum((P[:2] @ Xh / (P[2] @ Xh) - x) ** 2) for P, x in ((P1, x1), (P2, x2))))


def _answer_args():
    """The test inputs by the reference's answer: the compare sees only (got, expected)."""
    return {_reference(*case).tobytes(): case for case in _triangulation_cases()}


_ARGS = _answer_args()
_NEAR = same_array(rtol=0.0, atol=1e-4)


def _triangulation_compare(got, expected) -> bool:
    """Within 0.1 mm of the reference, or (on the noisy input) reprojecting no worse than it.

    Any linear least-squares form (four rows, six rows scaled to unit norm, inhomogeneous lstsq,
    the midpoint of the rays) lands within about 0.1 mm of the reference on the noisy input and
    reprojects as well; the test is that reprojection error, within 2 % of the reference's.
    """
    if _NEAR(got, expected):
        return True
    g = np.asarray(got, dtype=float) if np.ndim(got) == 1 else None
    case = _ARGS.get(np.asarray(expected, dtype=float).tobytes())
    if g is None or g.shape != (3,) or not np.isfinite(g).all() or case is None:
        return False
    P1, P2, x1, x2 = (np.asarray(a, dtype=float) for a in case)
    if np.linalg.norm(g - expected) > 0.01:  # 1 cm: no linear form of the method lands this far
        return False
    return _reprojection_ss(P1, P2, x1, x2, g) <= 1.02 * _reprojection_ss(P1, P2, x1, x2, expected)


def _six_rows(P1, P2, x1, x2):
    """All three rows of [x]x P per image, unscaled: the third, u p2 - v p1, is ~u times the others."""
    return np.vstack(
        [np.cross(np.append(x, 1.0)[:, None], P, axis=0) for P, x in ((P1, x1), (P2, x2))]
    )


def _triangulation_forms(P1, P2, x1, x2) -> list:
    """Each typical slip's X on this input, with its hint."""
    forms = [
        (
            _plain(_six_rows(P1, P2, x1, x2)),
            "you kept all three rows of x × (P X) = 0 per image, unscaled: the third, u p2 - v p1, is about "
            "u (hundreds of px) times larger than the other two and dominates the least squares on the "
            "noisy match. Drop it (two rows per image, as H&Z 12.2 does) or scale every row to unit norm",
        ),
        (
            _plain(_rows(P1, P2, x1, x2), lambda Vt: Vt[0]),
            "you took the first row of V^T, the direction of the LARGEST singular value: the null "
            "vector of A is the LAST row, Vt[-1]",
        ),
        (
            _plain(_rows(P1, P2, x1, x2), lambda Vt: Vt[:, -1]),
            "you took the last column of V^T (Vt[:, -1]); the right singular vectors are its rows, "
            "so the null vector is Vt[-1]",
        ),
        (
            _plain(_rows(P1, P2, x1, x2, swap_uv=True)),
            "you swapped u and v: u multiplies the third row of P against the FIRST (u p3 - p1), v "
            "against the second (v p3 - p2); pixels are (u, v) = (column, row)",
        ),
        (
            _plain(_rows(P1, P2, x2, x1)),
            "you paired each camera with the other image's pixel: x1 is seen by P1 and x2 by P2",
        ),
        (
            _plain(_rows(P2, P1, x1, x2)),
            "you paired each camera with the other image's pixel: x1 is seen by P1 and x2 by P2",
        ),
        (
            _plain(_rows(P1, P1, x1, x2)),
            "you used P1 for both images: the rows of image 2, u2 p3 - p1 and v2 p3 - p2, come from P2",
        ),
        (
            _plain(_rows(P2, P2, x1, x2)),
            "you used P2 for both images: the rows of image 1, u1 p3 - p1 and v1 p3 - p2, come from P1",
        ),
        (
            (lambda Xh: Xh[:3] / Xh[2])(np.linalg.svd(_rows(P1, P2, x1, x2))[2][-1]),
            "you divided by X_h[2], the homogeneous z: X_h = (X, Y, Z, W) has its scale W in the LAST "
            "entry, index 3, so X = X_h[:3] / X_h[3]",
        ),
    ]
    for off, what in (
        (0.5, "a half-pixel"),
        (-0.5, "a half-pixel"),
        (1.0, "a 1-based"),
        (-1.0, "a 1-based"),
    ):
        forms.append(
            (
                _plain(_rows(P1, P2, x1 + off, x2 + off)),
                f"your point is the right one for pixels moved by {off:+g} px: {what} offset. The "
                "pixels are already in the course's convention (pixel centres at integers); use them as given",
            )
        )
    return forms


def _triangulation_diagnosis(args, got, expected) -> str:
    P1, P2, x1, x2 = (np.asarray(a, dtype=float) for a in args)
    g = np.asarray(got, dtype=float)
    if g.shape in ((4,), (4, 1), (1, 4)):
        return (
            "you returned the homogeneous 4-vector: divide by its last entry and return the first "
            "three, X = X_h[:3] / X_h[3]"
        )
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return the world point X as a (3,) array, metres."
    Xh = np.linalg.svd(_rows(P1, P2, x1, x2))[2][-1]
    if np.allclose(g, Xh[:3], rtol=1e-4) or np.allclose(g, -Xh[:3], rtol=1e-4):
        return (
            "you returned the first three entries of the unit singular vector without dividing by "
            "its fourth: the SVD fixes |X_h| = 1, the world point is X_h[:3] / X_h[3]"
        )
    forms = _triangulation_forms(P1, P2, x1, x2)
    for wrong, hint in forms:
        if np.allclose(g, wrong, rtol=1e-6, atol=1e-9):
            return hint
    if np.allclose(g, -expected, rtol=1e-6):
        return (
            "your X is -X: a de-homogenisation slip. You divided by |X_h[3]| (or by -X_h[3]); the "
            "SVD returns the null vector with an arbitrary sign, so divide by X_h[3] itself, sign "
            "included: X = X_h[:3] / X_h[3]. (A row's sign cannot cause this: flipping a row of A "
            "leaves its null vector unchanged.)"
        )
    for factor, unit in ((1000.0, "millimetres"), (100.0, "centimetres")):
        if np.allclose(g, factor * expected, rtol=1e-6) or np.allclose(
            g, expected / factor, rtol=1e-6
        ):
            return f"your X is off by a factor {factor:g}: a unit slip ({unit}?). P maps metres to pixels"
    reproj = [
        np.linalg.norm(P[:2] @ np.append(g, 1) / (P[2] @ np.append(g, 1)) - x)
        for P, x in ((P1, x1), (P2, x2))
    ]
    return (
        f"your X reprojects {reproj[0]:.3g} px and {reproj[1]:.3g} px from the two pixels; check the four "
        "rows u p3 - p1, v p3 - p2 (p_i the rows of P, for each image), the SVD's last row of V^T and the "
        "division by X_h[3]"
    )


def _triangulation_exception_hint(exc: Exception, args: tuple) -> str:
    """An index past the end of X_h: A was built from P's columns (3 entries), so X_h has no X_h[3]."""
    if isinstance(exc, IndexError) and "index 3" in str(exc) and "size 3" in str(exc):
        return (
            "your X_h has 3 entries, so X_h[3] does not exist: the rows of A come from the ROWS of P, "
            "u P[2] - P[0] and v P[2] - P[1] (4 entries each, one per coordinate of X_h), not from its "
            "columns P[:, 2], P[:, 0]"
        )
    return ""


def triangulate_point(P1, P2, x1, x2):
    r"""Linear (DLT) triangulation: the world point seen at ``x1`` by ``P1`` and ``x2`` by ``P2``.

    :math:`\tilde x \times P \tilde X = 0` gives two independent rows per image,
    :math:`u\,p_3^\top - p_1^\top` and :math:`v\,p_3^\top - p_2^\top` (:math:`p_i^\top` the rows
    of :math:`P`); stacked for both images they make :math:`A \tilde X = 0`, solved by the right
    singular vector of the smallest singular value, then de-homogenised.

    Parameters
    ----------
    P1, P2 : (3, 4) array_like
        The two camera matrices (undistorted pixels from world metres).
    x1, x2 : (2,) array_like
        The pixel (u, v) of the point in image 1 and in image 2.

    Returns
    -------
    (3,) ndarray
        The world point X, metres.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 12.2 (linear triangulation).
    """
    P1, P2 = np.asarray(P1, dtype=float), np.asarray(P2, dtype=float)
    (u1, v1), (u2, v2) = x1, x2
    A = np.array([u1 * P1[2] - P1[0], v1 * P1[2] - P1[1], u2 * P2[2] - P2[0], v2 * P2[2] - P2[1]])
    Xh = np.linalg.svd(A)[2][-1]  # the null vector of A, |X_h| = 1
    return Xh[:3] / Xh[3]


register_exercise(
    Exercise(
        name="triangulate_point",
        lesson="11",
        reference=_reference,
        cases=_triangulation_cases,
        # 1e-4 m, or no worse reprojection on the noisy input: every linear least-squares form
        # passes; every slip below moves X by centimetres or more
        compare=_triangulation_compare,
        diagnose=_triangulation_diagnosis,
        exception_hint=_triangulation_exception_hint,
        ndarray_only=True,  # the prompt asks for "a (3,) array", as disparity_to_depth's does
        wrong_variants=(
            (
                lambda P1, P2, x1, x2: np.append(triangulate_point(P1, P2, x1, x2), 1.0),
                "homogeneous",
            ),
            (
                lambda P1, P2, x1, x2: np.linalg.svd(_rows(P1, P2, x1, x2))[2][-1][:3],
                "without dividing",
            ),
            (lambda P1, P2, x1, x2: _plain(_rows(P1, P2, x1, x2), lambda Vt: Vt[0]), "LARGEST"),
            (lambda P1, P2, x1, x2: _plain(_rows(P1, P2, x1, x2), lambda Vt: Vt[:, -1]), "column"),
            (lambda P1, P2, x1, x2: _plain(_rows(P1, P2, x1, x2, swap_uv=True)), "swapped u and v"),
            (lambda P1, P2, x1, x2: _plain(_rows(P1, P2, x2, x1)), "other image's pixel"),
            (
                lambda P1, P2, x1, x2: triangulate_point(P1, P2, np.add(x1, 1), np.add(x2, 1)),
                "1-based",
            ),
            (lambda P1, P2, x1, x2: 1000 * triangulate_point(P1, P2, x1, x2), "unit slip"),
            (lambda P1, P2, x1, x2: _plain(_six_rows(P1, P2, x1, x2)), "third, u p2 - v p1"),
            (lambda P1, P2, x1, x2: _plain(_rows(P1, P1, x1, x2)), "P1 for both"),
            (
                lambda P1, P2, x1, x2: (lambda Xh: Xh[:3] / Xh[2])(
                    np.linalg.svd(_rows(P1, P2, x1, x2))[2][-1]
                ),
                "divided by X_h[2]",
            ),
            (
                lambda P1, P2, x1, x2: (lambda Xh: Xh[:3] / -abs(Xh[3]))(
                    np.linalg.svd(_rows(P1, P2, x1, x2))[2][-1]
                ),
                "de-homogenisation slip",
            ),
        ),
        teaching=triangulate_point,
    )
)
