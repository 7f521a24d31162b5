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


def as_float(x: ArrayLike, name: str) -> np.ndarray:
    """A float copy of ``x`` (any shape); strings, None and ragged lists raise naming ``name``."""
    if x is None:
        raise CamlabInputError(f"{name}: expected numbers, got None")
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
    a = as_float(x, name)
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
            f"{name}: expected at least {min_count} points, got {len(a)}; supply more points"
        )
    if finite:
        check_finite(a, name)
    return Points(a, single)


class PointPairs(NamedTuple):
    """Matched points: row i of ``first`` corresponds to row i of ``second``.

    Attributes
    ----------
    first : (N, D1) float64 ndarray
        The first set, e.g. source pixels or world points.
    second : (N, D2) float64 ndarray
        The matching points.
    single : bool
        Both were passed as one point each (``(D1,)`` and ``(D2,)``): results should drop the batch axis.
    """

    first: np.ndarray
    second: np.ndarray
    single: bool


def as_point_pairs(
    a: ArrayLike,
    b: ArrayLike,
    names: tuple[str, str] = ("x1", "x2"),
    dims: tuple[int, int] = (2, 2),
    *,
    min_count: int = 1,
    why: str = "",
    finite: bool = True,
) -> PointPairs:
    """Validate corresponding points ``a`` (N, dims[0]) and ``b`` (N, dims[1]), one pair per row.

    The one pair check of camlab (homographies, F, rectification, camera resectioning).
    ``names`` are the arguments' names for the messages; ``why`` says why ``min_count``
    pairs are needed (degrees of freedom); ``finite=False`` lets NaN through (callers
    that drop non-finite pairs themselves).

    Examples
    --------
    >>> as_point_pairs([[0, 0], [1, 2]], [[3, 4]], ("src", "dst"))
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: src, dst: expected the same number of points (row i of src pairs with row i of dst), got 2 and 1; pass matched pairs
    """
    n1, n2 = names
    p1 = as_points(a, dims[0], n1, finite=False)
    p2 = as_points(b, dims[1], n2, finite=False)
    if len(p1.array) != len(p2.array):
        raise CamlabInputError(
            f"{n1}, {n2}: expected the same number of points (row i of {n1} pairs with row i of {n2}), "
            f"got {len(p1.array)} and {len(p2.array)}; pass matched pairs"
        )
    if len(p1.array) < min_count:
        raise CamlabInputError(
            f"{n1}: expected (N, {dims[0]}) with N >= {min_count} point pairs, got shape {p1.array.shape}"
            + (f"; {why}" if why else "")
        )
    if finite:
        check_finite(p1.array, n1)
        check_finite(p2.array, n2)
    return PointPairs(p1.array, p2.array, p1.single and p2.single)


def check_matrix(
    x: ArrayLike, shape: tuple[int, ...], name: str, *, finite: bool = True
) -> np.ndarray:
    """Return ``x`` as a float array of exactly ``shape`` or raise a clear error.

    >>> check_matrix(np.eye(3), (3, 3), "H").shape
    (3, 3)
    >>> check_matrix(np.eye(2), (3, 3), "H")
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: H: expected a (3, 3) matrix, got shape (2, 2)
    """
    a = as_float(x, name)
    if a.shape != tuple(shape):
        raise CamlabInputError(f"{name}: expected a {tuple(shape)} matrix, got shape {a.shape}")
    if finite:
        check_finite(a, name)
    return a


def _number(value, name: str, what: str) -> float:
    """``value`` as a float; strings, None and other non-numbers raise naming ``name``."""
    if isinstance(value, (str, bytes, bool)) or value is None:
        raise CamlabInputError(
            f"{name}: expected {what}, got {type(value).__name__} {value!r}; pass a number"
        )
    try:
        return float(value)
    except (TypeError, ValueError):
        raise CamlabInputError(
            f"{name}: expected {what}, got {type(value).__name__} {value!r}; pass a number"
        ) from None


def check_positive(value: float, name: str, unit: str = "") -> float:
    """Return ``value`` as a float if it is finite and > 0, else raise naming ``name``.

    >>> check_positive(0.05, "focal_length", "metres")
    0.05
    >>> check_positive("0.05", "focal_length", "metres")
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: focal_length: expected a positive finite number metres, got str '0.05'; pass a number
    """
    unit = f" {unit}" if unit else ""
    v = _number(value, name, f"a positive finite number{unit}")
    if not np.isfinite(v) or v <= 0:
        raise CamlabInputError(f"{name}: expected a positive finite number{unit}, got {value!r}")
    return v


def check_size(size, name: str = "size", *, minimum: int = 1) -> tuple[int, int]:
    """Return an image ``size`` as integer ``(width, height)`` in pixels, or raise a clear error.

    ``size`` is (width, height) and ``shape`` is (height, width) throughout camlab (see
    docs/conventions.md). Whole numbers written as floats (``640.0``) are accepted; a
    fraction (``640.7``), a string, zero or a negative number is a mistake, not something
    to truncate.

    >>> check_size((640, 480))
    (640, 480)
    >>> check_size((640.7, 480))
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: size: expected (width, height) as whole numbers of pixels, got (640.7, 480); round it first
    """
    try:
        vals = [v for v in size] if not isinstance(size, (str, bytes)) else None
    except TypeError:
        vals = None
    if (
        vals is None
        or len(vals) != 2
        or any(isinstance(v, (str, bytes, bool)) or v is None for v in vals)
    ):
        raise CamlabInputError(f"{name}: expected (width, height) in pixels, got {size!r}")
    try:
        f = np.array(vals, dtype=float)
    except (TypeError, ValueError):
        raise CamlabInputError(
            f"{name}: expected (width, height) in pixels, got {size!r}"
        ) from None
    if f.shape != (2,) or not np.isfinite(f).all():
        raise CamlabInputError(f"{name}: expected (width, height) in pixels, got {size!r}")
    if np.any(f != np.round(f)):
        raise CamlabInputError(
            f"{name}: expected (width, height) as whole numbers of pixels, got {size!r}; round it first"
        )
    w, h = int(f[0]), int(f[1])
    if w < minimum or h < minimum:
        raise CamlabInputError(
            f"{name}: expected (width, height) of at least {minimum} x {minimum} pixels, got ({w}, {h})"
        )
    return w, h


ROTATION_TOL = 1e-6


def check_rotation(R: ArrayLike, name: str = "R", tol: float = ROTATION_TOL) -> np.ndarray:
    r"""Return ``R`` as a float (3, 3) array if it is a rotation, else raise saying why.

    A rotation has :math:`R^\top R = I` (to ``tol``) and :math:`\det R = +1`.

    >>> check_rotation(np.diag([1.0, 1.0, -1.0]))
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: R: expected a rotation matrix (R^T R = I, det R = +1), got det R = -1 (a reflection); flip the sign of one axis
    """
    a = check_matrix(R, (3, 3), name)
    err = float(np.abs(a.T @ a - np.eye(3)).max())
    if err > tol:
        raise CamlabInputError(
            f"{name}: expected a rotation matrix (R^T R = I, det R = +1), but max |R^T R - I| = {err:.3g}; "
            f"build R with rotation_from_axis_angle / rotation_from_euler, or orthonormalise it"
        )
    det = float(np.linalg.det(a))
    if abs(det - 1.0) > tol:
        raise CamlabInputError(
            f"{name}: expected a rotation matrix (R^T R = I, det R = +1), got det R = {det:.3g} (a reflection); "
            f"flip the sign of one axis"
        )
    return a


def check_pose(R: ArrayLike | None, t: ArrayLike, name: str = "") -> tuple[np.ndarray, np.ndarray]:
    """Return a pose ``(R, t)`` as a (3, 3) rotation and a (3,) translation, or raise.

    ``R=None`` is the identity (no turn): the default of every ``R`` keyword that takes a pose.
    ``name`` prefixes the argument names in messages (``"camera"`` gives ``"camera R"``).

    >>> R, t = check_pose(np.eye(3), [0, 0, 2])
    >>> t
    array([0., 0., 2.])
    """
    prefix = f"{name} " if name else ""
    Rm = np.eye(3) if R is None else check_rotation(R, f"{prefix}R")
    tv = check_matrix(np.ravel(as_float(t, f"{prefix}t")), (3,), f"{prefix}t")
    return Rm, tv


def check_intrinsics(K: ArrayLike, name: str = "K") -> np.ndarray:
    r"""Return an intrinsic matrix as a float (3, 3) array with last row (0, 0, 1), or raise.

    .. math:: K = \begin{bmatrix} f_x & s & c_x \\ 0 & f_y & c_y \\ 0 & 0 & 1 \end{bmatrix},
              \quad f_x, f_y > 0

    The last row must be exactly ``(0, 0, 1)``: divide a K known only up to scale by its
    last entry before passing it. A K with a negative
    focal length (a mirrored image), a non-zero below-diagonal entry, or NaN/inf is
    rejected.

    >>> check_intrinsics([[800, 0, 320], [0, 800, 240], [0, 0, 1]])[0]
    array([800.,   0., 320.])
    >>> check_intrinsics([[-800, 0, 320], [0, 800, 240], [0, 0, 1]])
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: K: expected an intrinsic matrix [[fx, s, cx], [0, fy, cy], [0, 0, 1]] with fx, fy > 0, got fx = -800, fy = 800 (a mirrored or singular K); focal lengths are in pixels and > 0
    """
    a = check_matrix(K, (3, 3), name)
    want = f"{name}: expected an intrinsic matrix [[fx, s, cx], [0, fy, cy], [0, 0, 1]] with fx, fy > 0"
    if a[2, 0] != 0.0 or a[2, 1] != 0.0 or a[2, 2] != 1.0 or a[1, 0] != 0.0:
        raise CamlabInputError(
            f"{want}, got {a.tolist()} (not upper triangular with last row (0, 0, 1)); "
            f"build it with intrinsic_matrix(fx, fy, cx, cy, skew)"
        )
    if a[0, 0] <= 0 or a[1, 1] <= 0:
        raise CamlabInputError(
            f"{want}, got fx = {a[0, 0]:g}, fy = {a[1, 1]:g} (a mirrored or singular K); "
            f"focal lengths are in pixels and > 0"
        )
    return a


def check_number(value, name: str, unit: str = "") -> float:
    """Return ``value`` as a finite float (any sign), or raise naming ``name``.

    >>> check_number(-0.5, "theta", "radians")
    -0.5
    >>> check_number(float("nan"), "theta", "radians")
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: theta: expected a finite number radians, got nan
    """
    unit = f" {unit}" if unit else ""
    v = _number(value, name, f"a finite number{unit}")
    if not np.isfinite(v):
        raise CamlabInputError(f"{name}: expected a finite number{unit}, got {value!r}")
    return v


def check_integer(value, name: str, minimum: int = 1) -> int:
    """Return ``value`` as an int >= ``minimum``; fractions, strings, None, NaN raise naming ``name``.

    >>> check_integer(3.0, "levels")
    3
    >>> check_integer(2.5, "levels")
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: levels: expected a whole number >= 1, got 2.5; round it first
    """
    v = _number(value, name, f"a whole number >= {minimum}")
    if not np.isfinite(v) or v != round(v):
        raise CamlabInputError(
            f"{name}: expected a whole number >= {minimum}, got {value!r}; round it first"
        )
    if v < minimum:
        raise CamlabInputError(f"{name}: expected a whole number >= {minimum}, got {value!r}")
    return int(v)


def check_image(image, name: str = "image", *, channels: tuple[int, ...] = (1, 3, 4)) -> np.ndarray:
    """Return ``image`` as an array if it is a non-empty (H, W) or (H, W, C) real image, or raise.

    Pixels may be integers or floats (NaN or inf in a float image is an error); object,
    complex, bool and string arrays are rejected. The array is returned without a copy.
    Images are indexed ``img[v, u]``.

    >>> check_image(np.zeros((4, 5), np.uint8)).shape
    (4, 5)
    >>> check_image(np.zeros((4, 5), object))
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: image: expected an image of integer or float pixels, got dtype object; convert with np.asarray(image, dtype=np.uint8) or float
    """
    if image is None or isinstance(image, (str, bytes)):
        raise CamlabInputError(
            f"{name}: expected an image array (H, W) or (H, W, C), got {type(image).__name__}; "
            f"load a file with cv2.imread or camlab.data.load_photo first"
        )
    a = np.asarray(image)
    if a.dtype.kind not in "uif" or a.dtype == np.float16:
        raise CamlabInputError(
            f"{name}: expected an image of integer or float pixels, got dtype {a.dtype}; "
            f"convert with np.asarray(image, dtype=np.uint8) or float"
        )
    if (
        not ((a.ndim == 2 and 1 in channels) or (a.ndim == 3 and a.shape[2] in channels))
        or a.size == 0
    ):
        want = " or ".join(
            ["(H, W)"] * (1 in channels) + [f"(H, W, {c})" for c in channels if c != 1]
        )
        raise CamlabInputError(f"{name}: expected an image of shape {want}, got shape {a.shape}")
    if a.dtype.kind == "f":
        check_finite(a, name)
    return a


def check_shape(shape, name: str = "shape", *, minimum: int = 1) -> tuple[int, int]:
    """Return an array ``shape`` as integer ``(height, width)``, or raise (the transpose of :func:`check_size`).

    >>> check_shape((480, 640))
    (480, 640)
    >>> check_shape((480, 0.5))
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: shape: expected (height, width) as whole numbers of pixels >= 1, got (480, 0.5)
    """
    try:
        w, h = check_size(
            tuple(shape)[::-1] if isinstance(shape, (tuple, list, np.ndarray)) else shape,
            name,
            minimum=minimum,
        )
    except CamlabInputError:
        raise CamlabInputError(
            f"{name}: expected (height, width) as whole numbers of pixels >= {minimum}, got {shape!r}"
        ) from None
    return h, w


def check_pair(value, name: str, unit: str = "", *, positive: bool = False) -> tuple[float, float]:
    """Return two finite numbers (e.g. a pixel pitch (sx, sy) or a point (u, v)), or raise naming ``name``.

    >>> check_pair(5e-6, "pitch", "metres", positive=True)
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: pitch: expected a pair of positive numbers metres, got 5e-06; for equal values pass (5e-06, 5e-06)
    """
    what = f"a pair of {'positive ' if positive else ''}numbers{' ' + unit if unit else ''}"
    if isinstance(value, (str, bytes)) or np.ndim(value) == 0:
        fix = (
            f"; for equal values pass ({value!r}, {value!r})"
            if isinstance(value, (int, float))
            else ""
        )
        raise CamlabInputError(f"{name}: expected {what}, got {value!r}{fix}")
    a = check_matrix(np.ravel(as_float(value, name)), (2,), name)
    if positive and np.any(a <= 0):
        raise CamlabInputError(f"{name}: expected {what}, got {value!r}")
    return float(a[0]), float(a[1])
