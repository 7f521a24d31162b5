r"""The thin lens: focusing, magnification, aperture, blur circles and depth of field.

A thin lens of focal length :math:`f` images a point at distance :math:`z_o` in front of it
sharply at distance :math:`z_i` behind it, where

.. math:: \frac{1}{f} = \frac{1}{z_o} + \frac{1}{z_i}.

With the sensor at the image distance of the *focus distance* :math:`s`, a point at any
other depth :math:`z` spreads into a blur disc (circle of confusion) of diameter

.. math:: c(z) = A \, \frac{f}{s - f} \, \frac{|z - s|}{z}, \qquad A = f / N,

and everything whose blur stays below an acceptable :math:`c` lies in the depth of field
:math:`[z_{near}, z_{far}]`. All lengths are in metres (any one unit works if used
consistently). See lesson 02, sections 1-2.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._validate import CamlabInputError, as_float, check_positive

__all__ = [
    "DepthOfField",
    "FocusSetting",
    "angle_of_view",
    "aperture_diameter",
    "aperture_for_depth_of_field",
    "aperture_kernel",
    "circle_of_confusion",
    "depth_of_field",
    "hyperfocal_distance",
    "image_distance",
    "magnification",
    "object_distance",
]


def _distances(z: ArrayLike, name: str) -> np.ndarray:
    a = as_float(z, name)
    if not np.all(np.isfinite(a)) or np.any(a <= 0):
        raise CamlabInputError(f"{name}: expected positive finite distances in metres, got {z!r}")
    return a


def _outside_focal_length(z_o: np.ndarray, f: float, name: str) -> None:
    if np.any(z_o <= f):
        raise CamlabInputError(
            f"{name}: object at {float(np.min(z_o))!r} m is inside the focal length f = {f!r} m, so the "
            f"lens forms no real image (a virtual, magnifying-glass image instead); move it beyond f"
        )


def _conjugate(focal_length: float, z: ArrayLike, name: str) -> np.ndarray | float:
    """The other distance of a thin lens.

    :math:`1/f = 1/z_o + 1/z_i` is symmetric in the two, so either one follows from the other by
    :math:`f z / (z - f)`.
    """
    f = check_positive(focal_length, "focal_length", "metres")
    z = _distances(z, name)
    if name == "image_distance" and np.any(z <= f):
        raise CamlabInputError(
            f"image_distance: a sensor {float(np.min(z))!r} m behind the lens is not beyond the "
            f"focal length f = {f!r} m, so no real object is in focus there; place it beyond f"
        )
    _outside_focal_length(z, f, name)
    out = f * z / (z - f)
    return float(out) if out.ndim == 0 else out


def image_distance(focal_length: float, object_distance: ArrayLike) -> np.ndarray | float:
    r"""Where a thin lens focuses an object: :math:`z_i = f z_o / (z_o - f)`.

    Parameters
    ----------
    focal_length : float
        Focal length f of the thin lens, metres (> 0).
    object_distance : float or array_like
        Distance z_o of the object in front of the lens, metres (> f).

    Returns
    -------
    float or ndarray
        Image distance z_i behind the lens, metres: a float for a scalar distance, else an array
        of its shape.

    References
    ----------
    .. [1] E. Hecht, *Optics*, 5th ed., 2017, chapter 5 (the thin-lens equation).

    Examples
    --------
    >>> round(float(image_distance(0.05, 2.0)), 6)      # 50 mm lens, object 2 m away
    0.051282
    >>> image_distance(0.05, 0.03)
    Traceback (most recent call last):
    ...
    camlab._validate.CamlabInputError: object_distance: object at 0.03 m is inside the focal length f = 0.05 m, so the lens forms no real image (a virtual, magnifying-glass image instead); move it beyond f
    """
    return _conjugate(focal_length, object_distance, "object_distance")


def object_distance(focal_length: float, image_distance_: ArrayLike) -> np.ndarray | float:
    r"""The object distance that a sensor at ``image_distance_`` behind the lens has in focus.

    Parameters
    ----------
    focal_length : float
        Focal length f of the thin lens, metres (> 0).
    image_distance_ : float or array_like
        Distance z_i of the sensor behind the lens, metres (> f); the trailing underscore keeps
        the function :func:`image_distance` visible in this module.

    Returns
    -------
    float or ndarray
        Object distance z_o in focus, metres: a float for a scalar distance, else an array of
        its shape.

    Examples
    --------
    >>> round(float(object_distance(0.05, 0.0512820513)), 6)
    2.0
    """
    return _conjugate(focal_length, image_distance_, "image_distance")


def magnification(focal_length: float, object_distance_: ArrayLike) -> np.ndarray | float:
    r"""Lateral magnification :math:`m = -z_i / z_o = f / (f - z_o)`; negative means inverted.

    Parameters
    ----------
    focal_length : float
        Focal length f of the thin lens, metres (> 0).
    object_distance_ : float or array_like
        Distance z_o of the object in front of the lens, metres (> f).

    Returns
    -------
    float or ndarray
        Lateral magnification m (image size over object size; negative: inverted), a float for
        a scalar distance, else an array of its shape.

    Examples
    --------
    >>> float(magnification(0.05, 0.1))     # object at 2f: life size, inverted
    -1.0
    """
    f = check_positive(focal_length, "focal_length", "metres")
    z = _distances(object_distance_, "object_distance")
    _outside_focal_length(z, f, "object_distance")
    out = f / (f - z)
    return float(out) if out.ndim == 0 else out


def angle_of_view(focal_length: float, sensor_size: float, focus_distance: float = np.inf) -> float:
    r"""The angle (radians) a sensor dimension ``sensor_size`` spans through a lens focused at ``focus_distance``.

    Focused at :math:`s` the sensor sits at :math:`z_i = f s / (s - f)` behind the lens, so
    the pinhole model's focal length is :math:`z_i`, not :math:`f`, and

    .. math:: \theta = 2 \arctan \frac{w}{2 z_i},

    which is :math:`2 \arctan(w / 2f)` focused at infinity (the default) and narrower
    focused closer (*focus breathing*). All lengths in metres.

    Parameters
    ----------
    focal_length : float
        Focal length f of the thin lens, metres (> 0).
    sensor_size : float
        The sensor dimension w the angle spans (width, height or diagonal), metres (> 0).
    focus_distance : float, optional
        Distance s the lens is focused at, metres (> f); ``np.inf`` (the default) for infinity.

    Returns
    -------
    float
        Angle of view theta, radians.

    Examples
    --------
    >>> round(float(np.degrees(angle_of_view(0.05, 0.036))), 2)          # 50 mm, full-frame width
    39.6
    >>> round(float(np.degrees(angle_of_view(0.05, 0.036, 0.5))), 2)     # focused at 0.5 m
    35.9
    """
    f = check_positive(focal_length, "focal_length", "metres")
    w = check_positive(sensor_size, "sensor_size", "metres")
    focused_at_infinity = (
        isinstance(focus_distance, (int, float, np.floating)) and focus_distance == np.inf
    )
    if focused_at_infinity:
        z_i = f
    else:
        s = check_positive(focus_distance, "focus_distance", "metres (or np.inf)")
        _outside_focal_length(np.asarray(s), f, "focus_distance")
        z_i = f * s / (s - f)
    return float(2.0 * np.arctan(w / (2.0 * z_i)))


class FocusSetting(NamedTuple):
    """Where to focus (metres) and at which f-number: the result of :func:`aperture_for_depth_of_field`."""

    focus_distance: float
    f_number: float


def aperture_for_depth_of_field(
    focal_length: float, coc: float, near: float, far: float
) -> FocusSetting:
    r"""The focus distance and f-number whose depth of field is exactly ``[near, far]`` for acceptable blur ``coc``.

    The blur :math:`c(z) = \frac{f}{N} \frac{f}{s - f} \frac{|z - s|}{z}` must equal ``coc``
    at both ends. Equal blur at ``near`` and ``far`` needs :math:`(s - n)/n = (r - s)/r`
    (writing :math:`n, r` for near and far), so the focus is their harmonic mean,

    .. math:: s = \frac{2 n r}{n + r}, \qquad
              N = \frac{f^2}{c\,(s - f)} \frac{s - n}{n} = \frac{f^2}{c\,(s - f)} \frac{r - n}{r + n}.

    A lens offers a discrete set of f-numbers: take the next larger one. All lengths in metres.

    Parameters
    ----------
    focal_length : float
        Focal length f of the thin lens, metres (> 0).
    coc : float
        Acceptable circle of confusion c on the sensor, metres (> 0).
    near, far : float
        The nearest and farthest depths that must be sharp, metres (f < near < far).

    Returns
    -------
    FocusSetting
        ``focus_distance`` s (metres, the harmonic mean of near and far) and ``f_number`` N
        (the exact value; round it up to the lens's next stop).

    Examples
    --------
    >>> setting = aperture_for_depth_of_field(0.05, 0.03e-3, 2.0, 4.0)   # 50 mm, sharp from 2 m to 4 m
    >>> round(setting.focus_distance, 3), round(setting.f_number, 2)
    (2.667, 10.62)
    """
    f = check_positive(focal_length, "focal_length", "metres")
    c = check_positive(coc, "coc", "metres")
    n = check_positive(near, "near", "metres")
    r = check_positive(far, "far", "metres")
    if not n < r:
        raise CamlabInputError(
            f"near, far: expected near < far (metres), got near = {near!r}, far = {far!r}; swap them"
        )
    _outside_focal_length(np.asarray(n), f, "near")
    s = 2.0 * n * r / (n + r)
    return FocusSetting(float(s), float(f * f / (c * (s - f)) * (r - n) / (r + n)))


def aperture_diameter(focal_length: float, f_number: float) -> float:
    """Entrance pupil diameter :math:`A = f / N` (metres).

    Parameters
    ----------
    focal_length : float
        Focal length f of the thin lens, metres (> 0).
    f_number : float
        f-number N (> 0).

    Returns
    -------
    float
        Entrance pupil diameter A, metres.

    Examples
    --------
    >>> aperture_diameter(0.05, 2.0)
    0.025
    """
    return check_positive(focal_length, "focal_length", "metres") / check_positive(
        f_number, "f_number"
    )


def circle_of_confusion(
    focal_length: float, f_number: float, focus_distance: float, depth: ArrayLike
) -> np.ndarray | float:
    r"""Blur-disc diameter on the sensor (metres) for points at ``depth`` when focused at ``focus_distance``.

    .. math:: c = \frac{f}{N} \frac{f}{s - f} \frac{|z - s|}{z}

    Derivation: the sensor sits at :math:`s_i = f s / (s - f)`; a point at depth :math:`z`
    focuses at :math:`z_i = f z / (z - f)`, and its cone of light (base :math:`A`) cuts
    the sensor in a disc of diameter :math:`A |s_i - z_i| / z_i`, which simplifies to the
    formula above. Points beyond the focus (:math:`z \to \infty`) tend to
    :math:`A f / (s - f)`.

    Parameters
    ----------
    focal_length : float
        Focal length f of the thin lens, metres (> 0).
    f_number : float
        f-number N (> 0).
    focus_distance : float
        Distance s the lens is focused at, metres (> f).
    depth : float or array_like
        Depths z of the points, metres (> 0).

    Returns
    -------
    float or ndarray
        Blur-disc diameter c on the sensor, metres: a float for a scalar ``depth``, else an
        array of its shape.

    Examples
    --------
    >>> round(float(circle_of_confusion(0.05, 2.0, 2.0, 4.0)) * 1e3, 4)   # mm
    0.3205
    """
    f = check_positive(focal_length, "focal_length", "metres")
    N = check_positive(f_number, "f_number")
    s = check_positive(focus_distance, "focus_distance", "metres")
    _outside_focal_length(np.asarray(s), f, "focus_distance")
    z = _distances(depth, "depth")
    out = (f / N) * f / (s - f) * np.abs(z - s) / z
    return float(out) if out.ndim == 0 else out


def hyperfocal_distance(focal_length: float, f_number: float, coc: float) -> float:
    r"""Focus distance whose depth of field reaches infinity: :math:`H = f^2 / (N c) + f`.

    Textbook value: 50 mm at f/8 with c = 0.03 mm gives H = 10.47 m.

    Parameters
    ----------
    focal_length : float
        Focal length f of the thin lens, metres (> 0).
    f_number : float
        f-number N (> 0).
    coc : float
        Acceptable circle of confusion c, metres (> 0).

    Returns
    -------
    float
        Hyperfocal distance H, metres.

    Examples
    --------
    >>> round(hyperfocal_distance(0.05, 8, 0.03e-3), 2)
    10.47
    """
    f = check_positive(focal_length, "focal_length", "metres")
    N = check_positive(f_number, "f_number")
    c = check_positive(coc, "coc", "metres")
    return f * f / (N * c) + f


class DepthOfField(NamedTuple):
    """Near and far limits of acceptable sharpness (metres; ``far`` may be inf) and the hyperfocal distance."""

    near: float
    far: float
    hyperfocal: float

    @property
    def total(self) -> float:
        """The depth of field, ``far - near`` (metres)."""
        return self.far - self.near


def depth_of_field(
    focal_length: float, f_number: float, focus_distance: float, coc: float
) -> DepthOfField:
    r"""Depth of field of a thin lens focused at :math:`s`, for acceptable blur :math:`c`.

    .. math::

        z_{near} = \frac{s (H - f)}{H + s - 2f}, \qquad
        z_{far} = \frac{s (H - f)}{H - s}\ (s < H), \text{ else } \infty

    These are the depths where :func:`circle_of_confusion` equals ``coc``.

    Parameters
    ----------
    focal_length : float
        Focal length f of the thin lens, metres (> 0).
    f_number : float
        f-number N (> 0).
    focus_distance : float
        Distance s the lens is focused at, metres (> f).
    coc : float
        Acceptable circle of confusion c, metres (> 0).

    Returns
    -------
    DepthOfField
        ``near`` and ``far``, the limits of acceptable sharpness (metres; ``far`` is inf when
        s >= H), and ``hyperfocal``, H (metres); ``total`` is far - near.

    References
    ----------
    .. [1] S. F. Ray, *Applied Photographic Optics*, 3rd ed., 2002, chapter 15 (depth of field
       and the hyperfocal distance).

    Examples
    --------
    >>> dof = depth_of_field(0.05, 8, 5.0, 0.03e-3)   # 50 mm f/8 focused at 5 m
    >>> round(dof.near, 3), round(dof.far, 3)
    (3.389, 9.527)
    """
    f = check_positive(focal_length, "focal_length", "metres")
    s = check_positive(focus_distance, "focus_distance", "metres")
    _outside_focal_length(np.asarray(s), f, "focus_distance")
    H = hyperfocal_distance(f, f_number, coc)
    near = s * (H - f) / (H + s - 2 * f)
    far = s * (H - f) / (H - s) if s < H else float("inf")
    return DepthOfField(float(near), float(far), float(H))


def aperture_kernel(diameter_px: float, blades: int = 0) -> np.ndarray:
    r"""The blur of a defocused point: the aperture's shape scaled to the blur diameter (bokeh).

    Every ray from one object point passes the aperture and reaches the sensor inside the
    cone's cross-section there, a copy of the aperture scaled by :math:`c / A`. So the point
    spreads into the aperture's shape: a disc for a round stop, a regular polygon for a
    diaphragm of ``blades`` straight blades (its corners on the circle of diameter ``c``).
    Each pixel's weight is its area covered by the shape (4 x 4 samples), normalised to sum 1.

    Parameters
    ----------
    diameter_px : float
        The blur's diameter c in pixels (> 0), corner to corner for a polygon.
    blades : int, optional
        0 for a round aperture (the default), else the number of straight blades (>= 3).

    Returns
    -------
    (n, n) ndarray
        The kernel, n odd, summing to 1, centred on its middle pixel.

    Examples
    --------
    >>> round(float(aperture_kernel(20, blades=6).sum()), 6)
    1.0
    """
    r = check_positive(diameter_px, "diameter_px", "pixels") / 2
    if not isinstance(blades, (int, np.integer)) or (blades != 0 and blades < 3):
        raise CamlabInputError(
            f"blades: expected 0 (a round aperture) or a whole number of blades >= 3, got {blades!r}; "
            "pass e.g. 6 for a hexagonal diaphragm"
        )
    n = int(np.ceil(r)) + 1
    s = (np.arange(4) + 0.5) / 4 - 0.5  # 4 x 4 samples in each pixel
    y, x = np.mgrid[-n : n + 1, -n : n + 1].astype(float)
    y, x = np.broadcast_arrays(y[..., None, None] + s[:, None], x[..., None, None] + s[None, :])
    y, x = y.reshape(*y.shape[:2], 16), x.reshape(*x.shape[:2], 16)
    if blades == 0:
        inside = x**2 + y**2 <= r * r
    else:  # a regular polygon: inside every edge's half-plane, the edges at r cos(pi / blades)
        angles = (np.arange(blades) + 0.5) * 2 * np.pi / blades - np.pi / 2
        apothem = r * np.cos(np.pi / blades)
        inside = np.all([x * np.cos(a) + y * np.sin(a) <= apothem for a in angles], axis=0)
    cover = inside.mean(axis=-1)
    if cover.sum() == 0:  # smaller than a sample: all in the middle pixel
        cover[n, n] = 1
    return cover / cover.sum()
