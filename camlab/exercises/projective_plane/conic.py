"""Lesson 06, exercise 6: move a conic by a homography."""

from __future__ import annotations

import numpy as np

from ... import projective
from .._answers import same_up_to_scale, shape_problem
from .._core import Exercise, Mistake, first_mistake, mistake_variant, register_exercise

# --- Exercise 6: move a conic by a homography -------------------------------------------


def _conic_cases():
    H_projective = np.array([[1.2, 0.3, 5.0], [-0.1, 0.9, 2.0], [0.02, 0.01, 1.0]])
    H_affine = np.array([[2.0, 0.5, -3.0], [0.2, 1.5, 4.0], [0.0, 0.0, 1.0]])
    c, s = 2.0 * np.cos(0.6), 2.0 * np.sin(0.6)
    H_similarity = np.array([[c, -s, 10.0], [s, c, -5.0], [0.0, 0.0, 1.0]])
    return [
        # off-centre, so C^-1 is no multiple of C and inverting the whole product is told apart
        (H_projective, projective.circle_conic([0.5, -0.3], 1.2)),
        (H_affine, projective.conic_matrix(2.0, 0.5, 1.0, -1.0, 0.3, -4.0)),
        (H_similarity, projective.circle_conic([3.0, -2.0], 2.5)),
    ]


def _inv(H):
    return np.linalg.inv(H)


_CONIC_RULE = (
    "a point x' of the image comes from x = H^-1 x', and x^T C x = (H^-1 x')^T C (H^-1 x') "
    "= x'^T (H^-T C H^-1) x': the matrix between x'^T and x' is C'"
)

_CONIC_RULE_SENTENCE = _CONIC_RULE[0].upper() + _CONIC_RULE[1:]  # the rule after a full stop

_CONIC_MISTAKES = (
    Mistake(
        "H for H^-1",
        lambda a: a.H.T @ a.C @ a.H,
        "you used H where its inverse belongs (H.T @ C @ H). Points move forward by H, so the conic must "
        "undo it: " + _CONIC_RULE,
    ),
    Mistake(
        "the dual-conic rule",
        lambda a: a.H @ a.C @ a.H.T,
        "H @ C @ H.T is how a *dual* conic (a conic of lines, C*) moves. A conic of points moves by the "
        "inverse: " + _CONIC_RULE,
    ),
    Mistake(
        "transposes on the wrong side",
        lambda a: _inv(a.H) @ a.C @ _inv(a.H).T,
        "the transpose is on the wrong factor (inv(H) @ C @ inv(H).T): " + _CONIC_RULE,
    ),
    Mistake(
        "transpose forgotten",
        lambda a: _inv(a.H) @ a.C @ _inv(a.H),
        "inv(H) @ C @ inv(H) drops a transpose, so your C' is not symmetric, and a conic's matrix always "
        "is (x^T C x only sees its symmetric part): the left factor is the transpose of the right one. "
        + _CONIC_RULE_SENTENCE,
    ),
    Mistake(
        "one factor, like a line",
        lambda a: _inv(a.H).T @ a.C,
        "only one factor of H^-1: that is how a line moves (l' = H^-T l). A conic is quadratic in the "
        "point, so H^-1 appears on both sides: " + _CONIC_RULE,
    ),
    Mistake(
        "entrywise products",
        lambda a: _inv(a.H).T * a.C * _inv(a.H),
        "`*` multiplies entry by entry; a product of matrices needs `@` (or np.matmul) between every two "
        "factors",
    ),
    Mistake(
        "the whole product inverted",
        lambda a: _inv(a.H.T @ a.C @ a.H),
        "you inverted the whole product, inv(H.T @ C @ H) = inv(H) @ inv(C) @ inv(H).T: that is the dual "
        "conic's rule applied to C's inverse, not C moved. Invert H only, not C: " + _CONIC_RULE,
    ),
    Mistake(
        "the moved dual conic",
        lambda a: a.H @ np.linalg.inv(a.C) @ a.H.T,
        "you returned the moved *dual* conic C*' = H C* H^T (C* = inv(C) or adj C): its tangent lines "
        "touch the image, but the question asks for the point conic C', on which the moved points lie: "
        + _CONIC_RULE,
    ),
    Mistake("C unchanged", lambda a: a.C, "you returned C unchanged; apply H: " + _CONIC_RULE),
)


def _conic_context(H, C):
    from types import SimpleNamespace

    return SimpleNamespace(H=np.asarray(H, dtype=float), C=np.asarray(C, dtype=float))


def _conic_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". A conic is a symmetric (3, 3) matrix."
    g = np.asarray(got, dtype=float)
    named = first_mistake(_CONIC_MISTAKES, _conic_context(*args), g, same_up_to_scale)
    if named:
        return named
    if np.abs(g - g.T).max() > 1e-9 * np.abs(g).max():
        return (
            f"your C' is not symmetric (C'[0, 1] = {g[0, 1]:.4g}, C'[1, 0] = {g[1, 0]:.4g}), and a conic's "
            "matrix always is: the left factor must be the transpose of the right one. "
            + _CONIC_RULE_SENTENCE
        )
    H, C = (np.asarray(a, dtype=float) for a in args)
    x = projective.to_homogeneous(projective.map_points(H, projective.conic_points(C, 12)[:-1]))
    off = np.abs(np.einsum("ni,ij,nj->n", x, g, x)) / (np.linalg.norm(g) * np.sum(x**2, axis=1))
    return (
        f"the images H x of points x on C do not lie on your C' (normalised |x'^T C' x'| up to {off.max():.3g}). "
        + _CONIC_RULE_SENTENCE
    )


def map_conic(H, C):
    """A point x' of the image comes from x = H^-1 x'; put that into x^T C x = 0.

    Parameters
    ----------
    H : (3, 3) array_like
        The homography; points move by x' = H x.
    C : (3, 3) array_like
        A symmetric conic matrix, x^T C x = 0.

    Returns
    -------
    (3, 3) ndarray
        C' = H^-T C H^-1, up to scale: the conic through the moved points.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 2.3.1 (result 2.13).
    """
    H_inv = np.linalg.inv(H)
    return H_inv.T @ C @ H_inv


register_exercise(
    Exercise(
        name="map_conic",
        lesson="06",
        reference=projective.map_conic,
        cases=_conic_cases,
        compare=same_up_to_scale,
        diagnose=_conic_diagnosis,
        wrong_variants=(
            *(
                (mistake_variant(_CONIC_MISTAKES, row.name, _conic_context), hint_start)
                for row, hint_start in zip(
                    _CONIC_MISTAKES,
                    (
                        "where its inverse belongs",
                        "*dual* conic",
                        "wrong factor",
                        "drops a transpose",
                        "how a line moves",
                        "entry by entry",
                        "inverted the whole product",
                        "*dual* conic C*'",
                        "unchanged",
                    ),
                    strict=True,
                )
            ),
            (lambda H, C: np.linalg.inv(H).T @ C @ H, "not symmetric"),
            (
                lambda H, C: np.linalg.inv(H).T @ np.linalg.inv(C) @ np.linalg.inv(H),
                "do not lie on your C'",
            ),
        ),
        teaching=map_conic,
    )
)
