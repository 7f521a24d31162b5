r"""What every homography function uses.

Checking H and point pairs, normalising H to H[2, 2] = 1, comparing up to scale, composing and
inverting.

Homographies are equal up to scale (docs/conventions.md), so every result is normalised.
Part of :mod:`camlab.homography` (every name here is importable from there).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    CamlabInputError,
    DegenerateError,
    as_point_pairs,
    check_matrix,
)

__all__ = [
    "check_homography",
    "Correspondences",
    "check_correspondences",
    "compose",
    "invert",
    "normalise_homography",
    "same_homography",
]


class Correspondences(NamedTuple):
    """Corresponding points checked by :func:`check_correspondences`: ``src`` and ``dst``, (N, 2) each."""

    src: np.ndarray
    dst: np.ndarray


def check_correspondences(src: ArrayLike, dst: ArrayLike, min_count: int = 4) -> Correspondences:
    """Two (N, 2) arrays of corresponding points, at least ``min_count`` of them, or a clear error.

    :func:`camlab._validate.as_point_pairs`, naming the arguments ``src`` and ``dst`` and why
    four pairs are the minimum.

    Parameters
    ----------
    src, dst : (N, 2) array_like
        Corresponding points (u, v), pixels.
    min_count : int, optional
        The fewest pairs accepted (default 4, a homography's minimum).

    Returns
    -------
    Correspondences
        ``src`` and ``dst``, (N, 2) float arrays.
    """
    pairs = as_point_pairs(
        src,
        dst,
        ("src", "dst"),
        min_count=min_count,
        why="a homography has 8 degrees of freedom and each pair fixes 2",
    )
    return Correspondences(pairs.first, pairs.second)


def check_homography(H: ArrayLike, name: str = "H") -> np.ndarray:
    """Return H as a float (3, 3) array, or raise if it is malformed, non-finite or singular.

    Parameters
    ----------
    H : (3, 3) array_like
        A homography.
    name : str, optional
        The argument's name in error messages.

    Returns
    -------
    (3, 3) float ndarray
        H, unscaled.
    """
    Hm = check_matrix(H, (3, 3), name)
    s = np.linalg.svd(Hm, compute_uv=False)
    if s[0] == 0 or s[-1] < 1e-12 * s[0]:
        raise DegenerateError(
            f"{name}: singular (singular values {np.array2string(s, precision=3)}); a homography must be "
            f"invertible, it cannot collapse the plane onto a line or a point"
        )
    return Hm


def normalise_homography(H: ArrayLike) -> np.ndarray:
    """Scale H so that H[2, 2] = 1, or to unit Frobenius norm when H[2, 2] is (nearly) 0.

    Homographies are defined up to scale; this picks H[2, 2] = 1 when H[2, 2] is not
    tiny (the usual textbook form) and unit norm with a non-negative H[2, 2] otherwise.

    Parameters
    ----------
    H : (3, 3) array_like
        A homography. (not zero).

    Returns
    -------
    (3, 3) ndarray
        H / H[2, 2], or H / ||H||_F with H[2, 2] >= 0.

    Examples
    --------
    >>> normalise_homography(2 * np.eye(3))
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    Hm = check_matrix(H, (3, 3), "H")
    n = np.linalg.norm(Hm)
    if n == 0:
        raise DegenerateError("H: the zero matrix is not a homography")
    if abs(Hm[2, 2]) > 1e-8 * n:
        return Hm / Hm[2, 2]
    return Hm / n


def same_homography(H1: ArrayLike, H2: ArrayLike, tol: float = 1e-9) -> bool:
    """True if H1 and H2 are equal up to a non-zero scale (relative Frobenius tolerance).

    Parameters
    ----------
    H1, H2 : (3, 3) array_like
        The two homographies.
    tol : float, optional
        Tolerance on the Frobenius distance of the unit-norm matrices (either sign).

    Returns
    -------
    bool
        True when they are equal up to scale.

    Examples
    --------
    >>> same_homography(np.eye(3), -5 * np.eye(3))
    True
    """
    a = check_matrix(H1, (3, 3), "H1")
    b = check_matrix(H2, (3, 3), "H2")
    a = a / np.linalg.norm(a)
    b = b / np.linalg.norm(b)
    return bool(min(np.linalg.norm(a - b), np.linalg.norm(a + b)) <= tol)


def compose(*Hs: ArrayLike) -> np.ndarray:
    r"""The product :math:`H_1 H_2 \cdots H_k`: apply :math:`H_k` first, :math:`H_1` last.

    ``compose(H2, H1)`` maps a point by H1 and then by H2, like the matrix product
    (a composition of homographies is a homography: the group property).

    Parameters
    ----------
    *Hs : (3, 3) array_like
        One or more non-singular homographies, applied last to first.

    Returns
    -------
    (3, 3) ndarray
        The product, normalised (:func:`normalise_homography`).

    Examples
    --------
    >>> compose(np.diag([2.0, 2.0, 1.0]), [[1, 0, 5], [0, 1, 0], [0, 0, 1]])  # shift, then scale
    array([[ 2.,  0., 10.],
           [ 0.,  2.,  0.],
           [ 0.,  0.,  1.]])
    """
    if not Hs:
        raise CamlabInputError("compose: expected at least one (3, 3) homography, got none")
    out = np.eye(3)
    for i, H in enumerate(Hs):
        out = out @ check_homography(H, f"Hs[{i}]")
    return normalise_homography(out)


def invert(H: ArrayLike) -> np.ndarray:
    """The inverse homography (maps dst back to src), normalised; raises if H is singular.

    Parameters
    ----------
    H : (3, 3) array_like
        A homography. (non-singular).

    Returns
    -------
    (3, 3) ndarray
        H^-1, normalised (:func:`normalise_homography`).

    Examples
    --------
    >>> invert([[2, 0, 0], [0, 2, 0], [0, 0, 1]])
    array([[0.5, 0. , 0. ],
           [0. , 0.5, 0. ],
           [0. , 0. , 1. ]])
    """
    return normalise_homography(np.linalg.inv(check_homography(H)))
