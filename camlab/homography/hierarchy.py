r"""The hierarchy of plane transformations.

Euclidean, similarity, affine and projective homographies ([1]_, table 2.1), which group a matrix
belongs to, and the decomposition :math:`H = H_S H_A H_P` ([1]_, section 2.4.6).

Part of :mod:`camlab.homography` (every name here is importable from there).

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 2.4 (a hierarchy of
   transformations), table 2.1.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    CamlabInputError,
    DegenerateError,
    check_matrix,
    check_number,
    check_positive,
)
from .core import check_homography, compose, normalise_homography

__all__ = [
    "HIERARCHY",
    "HomographyFactors",
    "affine_homography",
    "classify",
    "decompose_homography",
    "euclidean_homography",
    "hierarchy_matrix",
    "projective_homography",
    "similarity_homography",
]


_OWN_INVARIANTS = {  # what each group keeps beyond the larger group above it (H&Z table 2.1)
    "projective": ["collinearity", "incidence", "tangency", "cross-ratio"],
    "affine": [
        "parallelism",
        "ratio of areas",
        "ratio of lengths on collinear or parallel lines",
        "the line at infinity",
    ],
    "similarity": ["angle", "ratio of lengths", "the circular points (H&Z 2.7.3)"],
    "euclidean": ["length", "area"],
}
_LARGER = {"euclidean": "similarity", "similarity": "affine", "affine": "projective"}


def _all_invariants(group: str) -> list[str]:
    """The group's own invariants, then everything the larger groups keep (a subgroup keeps all of it)."""
    own = list(_OWN_INVARIANTS[group])
    return own + _all_invariants(_LARGER[group]) if group in _LARGER else own


HIERARCHY: dict[str, dict] = {
    group: {
        "dof": dof,
        "matrix": matrix,
        "own": list(_OWN_INVARIANTS[group]),
        "larger": _LARGER.get(group),
        "invariants": _all_invariants(group),
    }
    for group, dof, matrix in (
        ("euclidean", 3, "[[R, t], [0, 1]]"),
        ("similarity", 4, "[[sR, t], [0, 1]]"),
        ("affine", 6, "[[A, t], [0, 1]]"),
        ("projective", 8, "[[A, t], [v^T, w]]"),
    )
}
"""The four groups of plane transformations (H&Z table 2.1): ``dof``, ``matrix``, ``own`` (the
invariants a group adds to those of ``larger``, the next larger group) and ``invariants`` (all
it keeps: its own and, since it is a subgroup, everything ``larger`` keeps)."""


def _rot(theta: float, name: str = "theta") -> np.ndarray:
    theta = check_number(theta, name, "radians")
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[c, -s], [s, c]])


def euclidean_homography(theta: float = 0.0, tx: float = 0.0, ty: float = 0.0) -> np.ndarray:
    """A rotation by ``theta`` radians followed by a translation (tx, ty). 3 dof.

    The rotation is counter-clockwise in x-right, y-up axes (clockwise on screen, where v
    points down).

    Parameters
    ----------
    theta : float, optional
        Rotation angle, radians.
    tx, ty : float, optional
        Translation, pixels.

    Returns
    -------
    (3, 3) ndarray
        ``[[R, t], [0, 1]]``.

    Examples
    --------
    >>> euclidean_homography(0.0, 2.0, 3.0)[:2, 2]
    array([2., 3.])
    """
    H = np.eye(3)
    H[:2, :2] = _rot(theta)
    H[:2, 2] = check_number(tx, "tx", "pixels"), check_number(ty, "ty", "pixels")
    return H


def similarity_homography(
    scale: float = 1.0, theta: float = 0.0, tx: float = 0.0, ty: float = 0.0
) -> np.ndarray:
    """Isotropic scaling, rotation and translation: ``[[s R, t], [0, 1]]``. 4 dof.

    Parameters
    ----------
    scale : float, optional
        Isotropic scale s (> 0).
    theta : float, optional
        Rotation angle, radians.
    tx, ty : float, optional
        Translation, pixels.

    Returns
    -------
    (3, 3) ndarray
        ``[[s R, t], [0, 1]]``.
    """
    check_positive(scale, "scale")
    H = euclidean_homography(theta, tx, ty)
    H[:2, :2] *= scale
    return H


def affine_homography(
    theta: float = 0.0,
    phi: float = 0.0,
    sx: float = 1.0,
    sy: float = 1.0,
    tx: float = 0.0,
    ty: float = 0.0,
) -> np.ndarray:
    r"""An affinity from the decomposition :math:`A = R(\theta) R(-\phi) D R(\phi)` [1]_. 6 dof.

    :math:`D = \mathrm{diag}(s_x, s_y)` scales along axes rotated by :math:`\phi`, then
    :math:`R(\theta)` rotates; (tx, ty) translates. Parallel lines stay parallel.

    Parameters
    ----------
    theta : float, optional
        Rotation angle, radians.
    phi : float, optional
        Angle of the scaling axes, radians.
    sx, sy : float, optional
        Scales along those axes (not zero; negative reflects).
    tx, ty : float, optional
        Translation, pixels.

    Returns
    -------
    (3, 3) ndarray
        ``[[A, t], [0, 1]]``.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 2.4.3
       (affinities, eq. 2.12).
    """
    sx, sy = check_number(sx, "sx"), check_number(sy, "sy")
    if sx == 0 or sy == 0:
        raise DegenerateError(f"sx, sy: a zero scale collapses the plane; got sx={sx}, sy={sy}")
    H = np.eye(3)
    H[:2, :2] = (
        _rot(theta)
        @ _rot(-check_number(phi, "phi", "radians"), "phi")
        @ np.diag([sx, sy])
        @ _rot(phi, "phi")
    )
    H[:2, 2] = check_number(tx, "tx", "pixels"), check_number(ty, "ty", "pixels")
    return H


def projective_homography(
    A: ArrayLike | None = None, t: ArrayLike = (0.0, 0.0), v: ArrayLike = (0.0, 0.0), w: float = 1.0
) -> np.ndarray:
    r"""A general homography ``[[A, t], [v^T, w]]``; v != 0 moves the line at infinity. 8 dof.

    Parameters
    ----------
    A : (2, 2) array_like, optional
        The upper-left block (default identity).
    t : (2,) array_like, optional
        Translation, pixels.
    v : (2,) array_like, optional
        The bottom row's first two entries.
    w : float, optional
        H[2, 2].

    Returns
    -------
    (3, 3) ndarray
        ``[[A, t], [v^T, w]]``, checked non-singular.

    Examples
    --------
    >>> projective_homography(v=[0.001, 0.0])[2]
    array([0.001, 0.   , 1.   ])
    """
    H = np.eye(3)
    H[:2, :2] = np.eye(2) if A is None else check_matrix(A, (2, 2), "A")
    H[:2, 2] = check_matrix(t, (2,), "t")
    H[2, :2] = check_matrix(v, (2,), "v")
    H[2, 2] = check_number(w, "w")
    return check_homography(H)


def hierarchy_matrix(
    group: str,
    *,
    theta: float = 0.0,
    scale: float = 1.0,
    shear: float = 0.0,
    aspect: float = 1.0,
    tx: float = 0.0,
    ty: float = 0.0,
    v: ArrayLike = (0.0, 0.0),
) -> np.ndarray:
    r"""One matrix of ``group`` (a key of :data:`HIERARCHY`) from one set of parameters.

    Each group uses only the parameters it has and ignores the rest, which is what lesson
    07's demo shows when the group changes under fixed sliders:

    * euclidean: rotation ``theta`` (radians) and translation (tx, ty);
    * similarity: adds the isotropic ``scale``;
    * affine: scales ``scale * aspect`` and ``scale / aspect`` along axes turned by ``shear``
      (:func:`affine_homography` with :math:`\phi` = ``shear``);
    * projective: that affinity followed by ``v``, the bottom row that moves the line at
      infinity: :math:`H = H_A H_P` (:func:`compose`, :func:`projective_homography`).

    Parameters
    ----------
    group : {"euclidean", "similarity", "affine", "projective"}
        The group.
    theta : float, optional
        Rotation, radians.
    scale : float, optional
        Isotropic scale.
    shear : float, optional
        Angle of the affine scaling axes, radians.
    aspect : float, optional
        The affine scales are ``scale * aspect`` and ``scale / aspect`` (> 0).
    tx, ty : float, optional
        Translation, pixels.
    v : (2,) array_like, optional
        The projective bottom row's first two entries.

    Returns
    -------
    (3, 3) ndarray
        The group's matrix.

    Examples
    --------
    >>> classify(hierarchy_matrix("similarity", theta=0.3, scale=2.0, shear=0.5))
    'similarity'
    """
    if group not in HIERARCHY:
        raise CamlabInputError(f"group: expected one of {', '.join(HIERARCHY)}, got {group!r}")
    if group == "euclidean":
        return euclidean_homography(theta, tx, ty)
    if group == "similarity":
        return similarity_homography(scale, theta, tx, ty)
    aspect = check_positive(aspect, "aspect")
    A = affine_homography(theta, shear, scale * aspect, scale / aspect, tx, ty)
    if group == "affine":
        return A
    return compose(A, projective_homography(v=v))


def classify(H: ArrayLike, tol: float = 1e-9) -> str:
    """The smallest group of the hierarchy that contains H.

    Parameters
    ----------
    H : (3, 3) array_like
        A homography.
    tol : float, optional
        Tolerance of the tests, relative to H's entries.

    Returns
    -------
    str
        "euclidean", "similarity", "affine" or "projective" (reflections count as affine).

    Examples
    --------
    >>> classify(similarity_homography(2.0, 0.3, 1, 1)), classify(affine_homography(sx=2.0)), classify(projective_homography(v=[1e-3, 0]))
    ('similarity', 'affine', 'projective')
    """
    Hm = normalise_homography(check_homography(H))
    if abs(Hm[2, 2]) < tol or np.abs(Hm[2, :2]).max() > tol * abs(Hm[2, 2]):
        return "projective"
    A = Hm[:2, :2] / Hm[2, 2]
    AtA = A.T @ A
    s2 = AtA[0, 0]
    if np.abs(AtA - s2 * np.eye(2)).max() > tol * max(s2, 1.0) or np.linalg.det(A) <= 0:
        return "affine"  # not a scaled rotation (reflections count as affine here)
    if abs(s2 - 1.0) > tol:
        return "similarity"
    return "euclidean"


class HomographyFactors(NamedTuple):
    """:func:`decompose_homography`'s factors, :math:`H = H_S H_A H_P` (each (3, 3)).

    Attributes
    ----------
    H_S : (3, 3) ndarray
        The similarity part (rotation, uniform scale, translation).
    H_A : (3, 3) ndarray
        The affine part (upper-triangular K, det K = 1).
    H_P : (3, 3) ndarray
        The projective part (the bottom row that moves the line at infinity).
    """

    H_S: np.ndarray
    H_A: np.ndarray
    H_P: np.ndarray


def decompose_homography(H: ArrayLike) -> HomographyFactors:
    r"""Split :math:`H = H_S H_A H_P` into similarity, affine and projective parts [1]_.

    .. math::
        H_S = \begin{pmatrix} sR & t/v \\ 0^T & 1 \end{pmatrix},\quad
        H_A = \begin{pmatrix} K & 0 \\ 0^T & 1 \end{pmatrix},\quad
        H_P = \begin{pmatrix} I & 0 \\ v^T & v \end{pmatrix}

    with K upper triangular, det K = 1. Requires H[2, 2] != 0 (the origin does not map
    to infinity).

    Returns
    -------
    HomographyFactors
        ``(H_S, H_A, H_P)``: three (3, 3) ndarrays whose product equals ``normalise_homography(H)``.

    Parameters
    ----------
    H : (3, 3) array_like
        A homography with H[2, 2] != 0.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 2.4.6
       (decomposition of a projective transformation).
    """
    Hm = normalise_homography(check_homography(H))
    if abs(Hm[2, 2]) < 1e-12:
        raise DegenerateError(
            "decompose_homography: H[2, 2] = 0 (the origin maps to infinity); translate first"
        )
    vvec, vs = Hm[2, :2], Hm[2, 2]
    t = Hm[:2, 2]
    Aeff = Hm[:2, :2] - np.outer(t, vvec) / vs  # sRK = A - t v^T / v
    # QR-like split sR K with K upper triangular, det K = 1, s > 0.
    Q, Rq = np.linalg.qr(Aeff)
    signs = np.sign(np.diag(Rq))
    signs[signs == 0] = 1
    Q, Rq = Q * signs, signs[:, None] * Rq
    s = np.sqrt(abs(np.linalg.det(Rq)))
    K = Rq / s
    HS = np.eye(3)
    HS[:2, :2] = s * Q
    HS[:2, 2] = t / vs
    HA = np.eye(3)
    HA[:2, :2] = K
    HP = np.eye(3)
    HP[2, :2] = vvec / vs * 1.0
    HP[2, 2] = 1.0
    return HomographyFactors(HS, HA, HP)
