"""Input validation shared by every camlab module.

Errors name the argument, what was expected, what arrived, and how to fix it, so a
learner sees the mistake instead of a bare numpy traceback.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike


class CamlabInputError(ValueError):
    """An argument has the wrong shape, type, or value."""


class DegenerateError(CamlabInputError):
    """The input is well formed but geometrically degenerate (collinear, coincident...)."""


class ConvergenceError(ArithmeticError):
    """An iterative method did not converge; the message says how far it got."""


class Points(NamedTuple):
    """Points as an (N, dim) float array and whether the caller passed a single point."""

    array: np.ndarray
    single: bool

    def restore(self, result: np.ndarray) -> np.ndarray:
        """Give ``result`` (one row per point) the rank of the caller's input."""
        return result[0] if self.single else result


def _as_float(x: ArrayLike, name: str) -> np.ndarray:
    try:
        return np.array(x, dtype=float)  # a copy: inputs are never modified
    except (TypeError, ValueError) as exc:
        raise CamlabInputError(
            f"{name}: expected numbers convertible to a float array, got {type(x).__name__} ({exc})"
        ) from None


def check_finite(a: np.ndarray, name: str) -> np.ndarray:
    """Raise if ``a`` holds NaN or inf, saying where the first one is."""
    bad = ~np.isfinite(a)
    if bad.any():
        where = tuple(int(i) for i in np.argwhere(bad)[0])
        raise CamlabInputError(
            f"{name}: expected finite values, found {a[where]} at index {where} "
            f"({int(bad.sum())} non-finite in all); remove or fix those entries"
        )
    return a


def as_points(
    x: ArrayLike,
    dim: int | tuple[int, ...],
    name: str,
    *,
    min_count: int = 1,
    finite: bool = True,
) -> Points:
    """Convert ``x`` to an (N, dim) float array of points, one per row.

    Parameters
    ----------
    x : (N, dim) or (dim,) array_like
        One point or a batch of points.
    dim : int or tuple of int
        The allowed point dimension(s), e.g. ``2`` or ``(2, 3)`` for Euclidean or
        homogeneous image points.
    name : str
        The argument's name, used in error messages.
    min_count : int
        The fewest points the caller needs.
    finite : bool
        Reject NaN and inf.

    Returns
    -------
    Points
        ``(array, single)``; ``Points.restore`` gives results the input's rank.

    Examples
    --------
    >>> as_points([1, 2], 2, "p")
    Points(array=array([[1., 2.]]), single=True)
    >>> as_points([[1, 2, 3]], 2, "p")
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: p: expected (N, 2) points (one per row) or a single (2,) point, got shape (1, 3)
    """
    dims = (dim,) if isinstance(dim, int) else tuple(dim)
    a = _as_float(x, name)
    single = a.ndim == 1
    if single:
        a = a[None, :]
    if a.ndim != 2 or a.shape[1] not in dims:
        want = " or ".join(f"(N, {d})" for d in dims)
        one = " or ".join(f"({d},)" for d in dims)
        raise CamlabInputError(
            f"{name}: expected {want} points (one per row) or a single {one} point, "
            f"got shape {np.shape(x)}"
        )
    if len(a) < min_count:
        raise CamlabInputError(
            f"{name}: expected at least {min_count} points, got {len(a)}; "
            f"supply more points"
        )
    if finite:
        check_finite(a, name)
    return Points(a, single)


def check_matrix(x: ArrayLike, shape: tuple[int, ...], name: str, *, finite: bool = True) -> np.ndarray:
    """Return ``x`` as a float array of exactly ``shape`` or raise a clear error.

    >>> check_matrix(np.eye(3), (3, 3), "H").shape
    (3, 3)
    >>> check_matrix(np.eye(2), (3, 3), "H")
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: H: expected a (3, 3) matrix, got shape (2, 2)
    """
    a = _as_float(x, name)
    if a.shape != tuple(shape):
        raise CamlabInputError(f"{name}: expected a {tuple(shape)} matrix, got shape {a.shape}")
    if finite:
        check_finite(a, name)
    return a


def check_positive(value: float, name: str, unit: str = "") -> float:
    """Return ``value`` as a float if it is finite and > 0, else raise."""
    v = float(value)
    if not np.isfinite(v) or v <= 0:
        unit = f" {unit}" if unit else ""
        raise CamlabInputError(f"{name}: expected a positive finite number{unit}, got {value!r}")
    return v


def check_image_size(size, name: str = "size") -> tuple[int, int]:
    """Return ``size`` as integer ``(width, height)`` in pixels, or raise a clear error.

    >>> check_image_size((640, 480))
    (640, 480)
    """
    try:
        w, h = (int(s) for s in size)
    except (TypeError, ValueError):
        raise CamlabInputError(f"{name}: expected (width, height) in pixels, got {size!r}") from None
    if w < 1 or h < 1:
        raise CamlabInputError(f"{name}: expected positive (width, height) in pixels, got {size!r}")
    return w, h
