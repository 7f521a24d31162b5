r"""Conics and dual conics of the projective plane.

How a homography moves them, and the circular points with their dual conic :math:`C^*_\infty`.

A **conic** is the curve :math:`a x^2 + b x y + c y^2 + d x + e y + f = 0`. In homogeneous
coordinates (multiply through by :math:`w^2`) it is a quadratic form, :math:`x^T C x = 0`, with
the *symmetric* matrix

.. math::

    C = \begin{pmatrix} a & b/2 & d/2 \\ b/2 & c & e/2 \\ d/2 & e/2 & f \end{pmatrix}

(the cross terms are halved because :math:`x^T C x` counts each off-diagonal entry twice).
Like points and lines, C is defined up to scale: five degrees of freedom.

The **dual conic** :math:`C^*` is the same curve described by its tangent lines:
:math:`l^T C^* l = 0`. The tangent at a point x of C is :math:`l = C x`, and substituting
:math:`x = C^{-1} l` into :math:`x^T C x = 0` gives :math:`l^T C^{-1} l = 0`, so
:math:`C^* = C^{-1}` up to scale; the adjugate :math:`\operatorname{adj} C = \det(C)\,C^{-1}` is
the form that also exists for a degenerate C.

The **circular points** :math:`I, J = (1, \pm i, 0)` are the two complex ideal points that
every circle passes through (put w = 0 in a circle's equation: :math:`x^2 + y^2 = 0`). A
homography fixes both exactly when it is a similarity, so they, or their dual conic
:math:`C^*_\infty = I J^T + J I^T \propto \operatorname{diag}(1, 1, 0)`, carry everything
metric: angles and ratios of lengths ([1]_, section 2.7.3). Lesson 08 finds the image of
the absolute conic through the images of a board's circular points (Zhang's method [2]_); lesson 10
rectifies a plane metrically with :math:`C^*_\infty`.

Conventions as in :mod:`camlab.projective`: points map by ``x' = H x``, so point conics map by
:math:`H^{-T} C H^{-1}` and dual conics by :math:`H C^* H^T`. See lesson 06, section 7.

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 2.7 (recovery of affine
   and metric properties from images).
.. [2] Z. Zhang, 2000, "A flexible new technique for camera calibration", *IEEE Transactions on
   Pattern Analysis and Machine Intelligence* 22(11), 1330-1334.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, DegenerateError, as_points, check_matrix

__all__ = [
    "CIRCULAR_POINTS",
    "DUAL_CONIC_AT_INFINITY",
    "circle_conic",
    "conic_matrix",
    "conic_points",
    "dual_conic",
    "map_conic",
    "map_dual_conic",
]

CIRCULAR_POINTS = np.array([[1.0, 1.0j, 0.0], [1.0, -1.0j, 0.0]])
"""The circular points I = (1, i, 0) and J = (1, -i, 0), one per row (complex)."""

DUAL_CONIC_AT_INFINITY = np.diag([1.0, 1.0, 0.0])
r""":math:`C^*_\infty = I J^T + J I^T = \operatorname{diag}(2, 2, 0) \propto \operatorname{diag}(1, 1, 0)`."""


def _symmetric(C: ArrayLike, name: str) -> np.ndarray:
    """``C`` as a (3, 3) float array, refusing one that is not symmetric (scale-free test)."""
    Cm = check_matrix(C, (3, 3), name)
    if not Cm.any():
        raise CamlabInputError(
            f"{name}: all zeros, which is no conic; pass a (3, 3) symmetric matrix"
        )
    if np.abs(Cm - Cm.T).max() > 1e-9 * np.abs(Cm).max():
        raise CamlabInputError(
            f"{name}: expected a symmetric (3, 3) matrix (a conic's x^T C x = 0 uses only its symmetric "
            f"part), got C[0, 1] = {Cm[0, 1]:.4g} but C[1, 0] = {Cm[1, 0]:.4g}; halve the cross terms "
            f"(b/2, d/2, e/2) into both places, or symmetrise with (C + C.T) / 2"
        )
    return Cm


def _invertible(H: ArrayLike) -> np.ndarray:
    Hm = check_matrix(H, (3, 3), "H")
    if not Hm.any() or np.linalg.cond(Hm) > 1e12:
        raise DegenerateError(
            "H: singular, so it collapses the plane and has no inverse; a homography must be invertible"
        )
    return Hm


def conic_matrix(a: float, b: float, c: float, d: float, e: float, f: float) -> np.ndarray:
    r"""The symmetric matrix C of the conic :math:`a x^2 + b x y + c y^2 + d x + e y + f = 0`.

    Derivation: with :math:`x = (x, y, 1)`, :math:`x^T C x = C_{11} x^2 + 2 C_{12} x y + C_{22} y^2
    + 2 C_{13} x + 2 C_{23} y + C_{33}`, so the off-diagonal entries are *half* the coefficients.

    Parameters
    ----------
    a, b, c, d, e, f : float
        The coefficients of the conic's equation, in that order.

    Returns
    -------
    (3, 3) ndarray
        Symmetric.

    Examples
    --------
    >>> conic_matrix(1, 0, 1, 0, 0, -1)  # the unit circle x^2 + y^2 = 1
    array([[ 1.,  0.,  0.],
           [ 0.,  1.,  0.],
           [ 0.,  0., -1.]])
    """
    C = np.array([[a, b / 2, d / 2], [b / 2, c, e / 2], [d / 2, e / 2, f]], dtype=float)
    return _symmetric(C, "conic_matrix")


def circle_conic(centre: ArrayLike, radius: float) -> np.ndarray:
    r"""The conic of the circle :math:`(x - x_0)^2 + (y - y_0)^2 = r^2`.

    Expanded, :math:`x^2 + y^2 - 2 x_0 x - 2 y_0 y + (x_0^2 + y_0^2 - r^2) = 0`.

    Parameters
    ----------
    centre : (2,) array_like
        The centre (x0, y0).
    radius : float
        The radius, > 0, in the centre's units.

    Returns
    -------
    (3, 3) ndarray
        The symmetric conic matrix.
    """
    x0, y0 = as_points(centre, 2, "centre").array[0]
    if not np.isfinite(radius) or radius <= 0:
        raise CamlabInputError(f"radius: expected a positive number, got {radius!r}")
    return conic_matrix(1.0, 0.0, 1.0, -2 * x0, -2 * y0, x0**2 + y0**2 - radius**2)


def dual_conic(C: ArrayLike) -> np.ndarray:
    r"""The dual conic :math:`C^* = \operatorname{adj} C`: the lines tangent to C, :math:`l^T C^* l = 0`.

    Derivation: the tangent at a point x of C is :math:`l = C x`; then :math:`x = C^{-1} l`, and
    :math:`x^T C x = l^T C^{-1} l = 0`. Up to scale :math:`C^{-1} \propto \operatorname{adj} C`,
    whose rows are the cross products of C's columns :math:`c_k` (so :math:`\operatorname{adj}(C)\,C =
    \det(C)\, I`); unlike the inverse, it exists for a degenerate conic too.

    Parameters
    ----------
    C : (3, 3) array_like
        A symmetric conic matrix.

    Returns
    -------
    (3, 3) ndarray
        The adjugate, symmetric.
    """
    Cm = _symmetric(C, "C")
    c1, c2, c3 = Cm.T  # the columns
    return np.array([np.cross(c2, c3), np.cross(c3, c1), np.cross(c1, c2)])


def map_conic(H: ArrayLike, C: ArrayLike) -> np.ndarray:
    r"""Move a point conic by a homography: :math:`C' = H^{-T} C H^{-1}`.

    Derivation: a point x' of the image comes from :math:`x = H^{-1} x'`, and x lies on C:
    :math:`x^T C x = (H^{-1} x')^T C (H^{-1} x') = x'^T (H^{-T} C H^{-1}) x' = 0`. Compare lines,
    :math:`l' = H^{-T} l` (:func:`map_lines`): a conic needs :math:`H^{-1}` on both sides because it
    is quadratic in the point.

    Parameters
    ----------
    H : (3, 3) array_like
        The homography mapping points, ``x' = H x``.
    C : (3, 3) array_like
        A symmetric conic matrix.

    Returns
    -------
    (3, 3) ndarray
        The mapped conic, symmetric (re-symmetrised against rounding), unscaled.

    Examples
    --------
    >>> map_conic(np.diag([2.0, 2.0, 1.0]), np.diag([1.0, 1.0, -1.0]))  # the unit circle, doubled
    array([[ 0.25,  0.  ,  0.  ],
           [ 0.  ,  0.25,  0.  ],
           [ 0.  ,  0.  , -1.  ]])
    """
    Hinv = np.linalg.inv(_invertible(H))
    Cp = Hinv.T @ _symmetric(C, "C") @ Hinv
    return (Cp + Cp.T) / 2


def map_dual_conic(H: ArrayLike, C_star: ArrayLike) -> np.ndarray:
    r"""Move a dual (line) conic by a homography: :math:`C^{*\prime} = H C^* H^T`.

    Derivation: lines map by :math:`l' = H^{-T} l`, so :math:`l = H^T l'`, and
    :math:`l^T C^* l = l'^T (H C^* H^T) l' = 0`. It is the rule for point conics with H and
    :math:`H^{-T}` swapping roles, as they do for points and lines.

    Parameters
    ----------
    H : (3, 3) array_like
        The homography mapping points, ``x' = H x``.
    C_star : (3, 3) array_like
        A symmetric dual conic, e.g. :data:`DUAL_CONIC_AT_INFINITY`.

    Returns
    -------
    (3, 3) ndarray
        The mapped dual conic, symmetric, unscaled.
    """
    Hm = _invertible(H)
    Cp = Hm @ _symmetric(C_star, "C_star") @ Hm.T
    return (Cp + Cp.T) / 2


def conic_points(C: ArrayLike, n: int = 100) -> np.ndarray:
    r"""``n`` points around a real ellipse (for drawing), the last equal to the first.

    Write :math:`C = \begin{pmatrix} A & b \\ b^T & c \end{pmatrix}`. The centre solves
    :math:`A x_0 = -b`, and about it :math:`x^T C x = (x - x_0)^T A (x - x_0) - k` with
    :math:`k = b^T A^{-1} b - c`. With :math:`S` the symmetric square root of :math:`A` (positive
    definite, :math:`S^2 = A`), the points :math:`x_0 + \sqrt{k}\, S^{-1} (\cos t, \sin t)` lie on
    it: :math:`(x - x_0)^T A (x - x_0) = k\, u^T S^{-1} S^2 S^{-1} u = k`. For a 2 x 2 matrix
    Cayley-Hamilton gives :math:`S` in closed form: :math:`S^2 - \operatorname{tr}(S) S + \det(S) I = 0`
    with :math:`\det S = \sqrt{\det A} = s` and :math:`\operatorname{tr}(S)^2 = \operatorname{tr} A + 2 s`,
    so :math:`S = (A + s I) / \sqrt{\operatorname{tr} A + 2 s}`. Unlike the principal axes (an
    eigenvector's sign is free, and a circle has no axes at all), :math:`S` is a smooth function of
    C: the same C gives the same points wherever it is computed (the browser's twin,
    ``conicPoints`` in camlab/widgets/browser/geometry.js, draws the very same points).

    Parameters
    ----------
    C : (3, 3) array_like
        A symmetric conic matrix of a real ellipse (any scale or sign).
    n : int
        How many points.

    Returns
    -------
    (n, 2) ndarray
        Points on the ellipse.

    Raises
    ------
    DegenerateError
        If C is not a real ellipse (a hyperbola, parabola, an imaginary or degenerate conic).
    """
    Cm = _symmetric(C, "C")
    A, b, c = Cm[:2, :2], Cm[:2, 2], Cm[2, 2]
    if np.linalg.det(A) <= 1e-12 * np.abs(A).max() ** 2:
        raise DegenerateError(
            "C: not an ellipse (det of its top-left 2 x 2 block <= 0: a hyperbola or a parabola, "
            "which meets the line at infinity); conic_points draws ellipses only"
        )
    if np.trace(A) < 0:  # the same conic with a positive definite A
        A, b, c = -A, -b, -c
    x0 = np.linalg.solve(A, -b)
    k = b @ np.linalg.solve(A, b) - c
    if k <= 0:
        raise DegenerateError("C: an imaginary or a point ellipse, with no real points to draw")
    s = np.sqrt(np.linalg.det(A))
    S = (A + s * np.eye(2)) / np.sqrt(np.trace(A) + 2 * s)  # S @ S = A
    t = np.linspace(0, 2 * np.pi, n)
    return x0 + np.sqrt(k) * np.linalg.solve(S, np.stack([np.cos(t), np.sin(t)])).T


def line_angle(l1: ArrayLike, l2: ArrayLike, C_star: ArrayLike = DUAL_CONIC_AT_INFINITY) -> float:
    r"""The angle between two lines, measured through a dual conic of the circular points.

    For lines of the plane itself :math:`l^T C^*_\infty m = l_1 m_1 + l_2 m_2` (lines l, m) is the dot
    product of their normals, so

    .. math:: \cos\theta = \frac{|l^T C^* m|}{\sqrt{(l^T C^* l)(m^T C^* m)}} ,

    with the absolute value because a line's sign is free. Every factor is invariant: in a photo
    through H, lines are :math:`H^{-T} l` and :math:`C^{*\prime}_\infty = H C^*_\infty H^T`, so the
    same formula with the image's lines and :math:`C^{*\prime}_\infty` gives the angle *on the
    plane*. The square root is of the product, so a negative scale of ``C_star`` cancels.

    Parameters
    ----------
    l1, l2 : (3,) array_like
        The two lines (a, b, c), any scale and sign.
    C_star : (3, 3) array_like
        The dual conic of the circular points, or its image :math:`H C^*_\infty H^T`, any
        non-zero scale (default :data:`DUAL_CONIC_AT_INFINITY`, the plane's own).

    Returns
    -------
    float
        The acute angle between the lines, radians, in [0, pi/2].

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 2.7.4 (the angle formula).
    """
    Cs = _symmetric(C_star, "C_star")
    lv, mv = (np.asarray(v, dtype=float) for v in (l1, l2))
    for name, v in (("l1", lv), ("l2", mv)):
        if v.shape != (3,):
            raise CamlabInputError(
                f"{name}: expected a line (a, b, c) of shape (3,), got shape {v.shape}; pass one line as a 3-vector"
            )
    cos = abs(lv @ Cs @ mv) / np.sqrt((lv @ Cs @ lv) * (mv @ Cs @ mv))
    return float(np.arccos(min(1.0, cos)))
