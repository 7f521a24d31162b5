r"""Affine cameras: orthographic, weak perspective and the general affine camera.

An affine camera is a 3x4 matrix whose last row is :math:`(0, 0, 0, 1)`:

.. math::

    P_A = \begin{pmatrix} m_{11} & m_{12} & m_{13} & m_{14} \\
                          m_{21} & m_{22} & m_{23} & m_{24} \\
                          0 & 0 & 0 & 1 \end{pmatrix},
    \qquad u = M_2 X + t_2 ,

so projection is linear (no division by depth). Its centre is at infinity (all rays
are parallel), parallel world lines stay parallel in the image, and the midpoint of
a segment images to the midpoint of its image. The family, from special to general
(H&Z section 6.3):

* **orthographic**: drop the camera z coordinate, :math:`u = (r_1 \cdot X + t_1,\ r_2 \cdot X + t_2)`;
* **scaled orthographic**: the same times a scale k (pixels per metre);
* **weak perspective**: different scales :math:`\alpha_x, \alpha_y` (and skew);
* **general affine**: any :math:`M_2` of rank 2, 8 degrees of freedom.

A perspective camera looking at an object of depth range :math:`\Delta` at distance
:math:`d_0` is close to affine when :math:`\Delta \ll d_0`: the weak-perspective
image of a point differs from its perspective image by the factor
:math:`\Delta / d_0` times its distance from the principal point (H&Z §6.3.2).

Conventions (docs/conventions.md): R, t are cam_from_world, camera frame x right,
y down, z forward; pixels (u, v) = (column, row); points are rows. See lesson 05.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._validate import (
    CamlabInputError,
    DegenerateError,
    as_float,
    as_point_pairs,
    as_points,
    check_finite,
    check_matrix,
    check_positive,
    check_rotation,
)
from .camera import Camera, intrinsic_matrix, orbit_eye, project_points, project_segments

__all__ = [
    "AffineDeparture",
    "affine_approximation",
    "affine_departure",
    "affine_fit_departure",
    "dolly_zoom_camera",
    "dolly_zoom_errors",
    "dolly_zoom_focal",
    "estimate_affine_camera",
    "image_of_direction",
    "is_affine",
    "largest_gap_in_frame",
    "orthographic_matrix",
    "paraperspective_approximation",
    "projection_rays",
    "PROJECTION_MODELS",
    "scaled_orthographic_matrix",
    "ThreeImages",
    "three_images",
    "weak_perspective_error",
    "weak_perspective_matrix",
]


def _affine_from(A2: np.ndarray, R: np.ndarray, t: np.ndarray) -> np.ndarray:
    """[[A2 @ [r1; r2], A2 @ t[:2] + offset]; [0 0 0 1]] with A2 a (2, 3) [K2 | c] block."""
    P = np.zeros((3, 4))
    P[:2, :3] = A2[:, :2] @ R[:2]
    P[:2, 3] = A2[:, :2] @ t[:2] + A2[:, 2]
    P[2, 3] = 1.0
    return P


def orthographic_matrix(R: ArrayLike, t: ArrayLike) -> np.ndarray:
    r"""The orthographic camera: :math:`P = \begin{pmatrix} 1&0&0&0 \\ 0&1&0&0 \\ 0&0&0&1\end{pmatrix}
    \begin{pmatrix} R & t \\ 0^\top & 1\end{pmatrix}`.

    It keeps the camera x, y coordinates (metres) and forgets depth.

    Parameters
    ----------
    R : (3, 3) array_like
        cam_from_world rotation.
    t : (3,) array_like
        cam_from_world translation (metres); only t[0], t[1] matter.

    Returns
    -------
    (3, 4) ndarray
        Image coordinates in metres.

    Examples
    --------
    >>> orthographic_matrix(np.eye(3), [0.0, 0.0, 5.0]) @ [1.0, 2.0, 3.0, 1.0]
    array([1., 2., 1.])
    """
    return scaled_orthographic_matrix(R, t, 1.0, (0.0, 0.0))


def scaled_orthographic_matrix(
    R: ArrayLike, t: ArrayLike, k: float, principal_point: ArrayLike = (0.0, 0.0)
) -> np.ndarray:
    r"""Scaled orthographic: orthographic projection times ``k`` pixels per metre, plus the
    principal point (cx, cy): :math:`u = k (r_1 \cdot X + t_1) + c_x`, likewise v."""
    return weak_perspective_matrix(R, t, k, k, 0.0, principal_point)


def weak_perspective_matrix(
    R: ArrayLike,
    t: ArrayLike,
    ax: float,
    ay: float,
    skew: float = 0.0,
    principal_point: ArrayLike = (0.0, 0.0),
) -> np.ndarray:
    r"""A weak-perspective camera, or with ``skew`` a general affine camera (H&Z §6.3.4):

    .. math:: P = \begin{pmatrix} \alpha_x & s & c_x \\ 0 & \alpha_y & c_y \\ 0 & 0 & 1 \end{pmatrix}
              \begin{pmatrix} r_1^\top & t_1 \\ r_2^\top & t_2 \\ 0^\top & 1 \end{pmatrix}

    In Hartley & Zisserman's terms, ``skew = 0`` gives **weak perspective**,
    :math:`\mathrm{diag}(\alpha_x, \alpha_y, 1)` times the orthographic camera: 7 degrees of
    freedom (3 rotation, 2 translation, 2 scales); ``ax == ay`` is scaled orthographic (6);
    a non-zero ``skew`` gives the **general affine camera** (8). The principal point adds no
    degree of freedom: :math:`c_x` shifts every image point exactly as changing :math:`t_1` by
    :math:`c_x / \alpha_x` (and :math:`c_y` as :math:`t_2`, after the skew) does, so H&Z absorb
    it into the translation. It is accepted here only to place the picture in pixel
    coordinates, e.g. about the image centre.

    Parameters
    ----------
    R, t : cam_from_world pose.
    ax, ay : float
        Scales in pixels per metre (> 0): a perspective camera's :math:`f / d_0`.
    skew : float
        Pixels per metre of the second camera axis added to u (0 for weak perspective).
    principal_point : (2,) array_like
        A constant pixel offset (redundant with ``t``; see above).

    Examples
    --------
    >>> R, t = np.eye(3), np.array([0.1, 0.0, 5.0])
    >>> P_pp = weak_perspective_matrix(R, t, 100.0, 100.0, principal_point=(320, 240))
    >>> P_t = weak_perspective_matrix(R, t + [3.2, 2.4, 0.0], 100.0, 100.0)
    >>> bool(np.allclose(P_pp, P_t))   # the principal point is a translation in disguise
    True
    """
    Rm = check_rotation(R)
    tv = check_matrix(t, (3,), "t")
    ax = check_positive(ax, "ax", "pixels per metre")
    ay = check_positive(ay, "ay", "pixels per metre")
    c = check_matrix(principal_point, (2,), "principal_point")
    A2 = np.array([[ax, float(skew), c[0]], [0.0, ay, c[1]]])
    return _affine_from(A2, Rm, tv)


def is_affine(P: ArrayLike, tol: float = 1e-12) -> bool:
    """True if P's last row is proportional to (0, 0, 0, 1) (its centre is at infinity)."""
    a = check_matrix(P, (3, 4), "P")
    last = a[2]
    return bool(
        abs(last[3]) > 0 and np.abs(last[:3]).max() <= tol * max(abs(last[3]), np.abs(a).max())
    )


def affine_approximation(camera: Camera, reference_point: ArrayLike) -> np.ndarray:
    r"""The weak-perspective approximation of a perspective camera about a point (H&Z §6.3.1).

    Every point's depth is replaced by the reference point's depth (zeroth order in depth;
    :func:`paraperspective_approximation` is the first-order one). With :math:`d_0 = r_3 \cdot X_0 + t_3` the depth of the reference point
    :math:`X_0`, replacing every point's depth by :math:`d_0` gives (H&Z §6.3.1)

    .. math:: P_\infty = K \begin{pmatrix} r_1^\top & t_1 \\ r_2^\top & t_2 \\ 0^\top & d_0 \end{pmatrix},

    normalised here so that the last row is (0, 0, 0, 1). It images X_0 exactly where the
    perspective camera does; a point at depth :math:`d_0 + \Delta` lands at
    :math:`x_{\text{affine}}` with :math:`x_{\text{proj}} - x_0 = \frac{d_0}{d_0 + \Delta}
    (x_{\text{affine}} - x_0)` where :math:`x_0` is the principal point.

    Parameters
    ----------
    camera : Camera
        The perspective camera (its distortion is ignored).
    reference_point : (3,) array_like
        A world point in front of the camera, e.g. the object's centroid.

    Returns
    -------
    (3, 4) ndarray
        An affine camera (last row (0, 0, 0, 1)).
    """
    d0 = _reference_depth(camera, reference_point)[1]
    E = np.zeros((3, 4))
    E[:2, :3] = camera.R[:2]
    E[:2, 3] = camera.t[:2]
    E[2, 3] = d0
    return camera.K @ E / d0


def _reference_depth(camera: Camera, reference_point: ArrayLike) -> tuple[np.ndarray, float]:
    """The reference point as a (3,) array and its depth d0 > 0 in ``camera``."""
    if not isinstance(camera, Camera):
        raise CamlabInputError(
            f"camera: expected a camlab.camera.Camera, got {type(camera).__name__}"
        )
    X0 = check_matrix(reference_point, (3,), "reference_point")
    d0 = float(camera.R[2] @ X0 + camera.t[2])
    if d0 <= 0:
        raise CamlabInputError(
            f"reference_point: expected a point in front of the camera, but its depth is {d0:.3g} m; "
            f"pick a point the camera sees (e.g. the object's centroid)"
        )
    return X0, d0


def paraperspective_approximation(camera: Camera, reference_point: ArrayLike) -> np.ndarray:
    r"""The para-perspective camera about a point: perspective linearised at the point (first order).

    Weak perspective (:func:`affine_approximation`) projects every point onto the plane
    :math:`z = d_0` through the reference point :math:`X_0` **along the optical axis**, then
    divides by :math:`d_0`. Para-perspective (Ohta, Maenobu and Sakai 1981; Aloimonos 1990; Szeliski §2.1.4)
    projects along
    the **ray through** :math:`X_0` instead, so its rays, and its centre at infinity
    :math:`(d, 0)`, point along the line of sight to :math:`X_0`, not along :math:`r_3`. In camera coordinates, with
    :math:`(a, b) = (x_0 / d_0, y_0 / d_0)` the reference point's normalised image position,

    .. math:: x_n = \frac{x - a\,(z - d_0)}{d_0}, \qquad y_n = \frac{y - b\,(z - d_0)}{d_0},

    which is the first-order Taylor expansion of :math:`(x / z, y / z)` about :math:`X_0`. Its error is
    exact and simple: a point at depth :math:`d_0 + \Delta` lands at

    .. math:: x_{\text{para}} - x_{\text{proj}} = \frac{\Delta}{d_0}\,(x_{\text{proj}} - x_{X_0}),

    :math:`\Delta / d_0` times its perspective image's distance from the image of :math:`X_0`, where weak
    perspective has the distance from the principal point (:func:`affine_approximation`). So the two
    coincide when :math:`X_0` is on the optical axis, and para-perspective is the closer one for points imaged
    nearer :math:`x_{X_0}` than the principal point (most points of a compact object seen off-centre); at the
    principal point weak perspective is exact. It is still an affine camera (last row (0, 0, 0, 1)), but not a weak-perspective
    one: in general (:math:`a b \neq 0`) the rows of its :math:`M_2` are neither orthogonal nor of equal
    length, so it is a general affine camera (8 degrees of freedom, H&Z §6.3.4).

    Parameters
    ----------
    camera : Camera
        The perspective camera (its distortion is ignored).
    reference_point : (3,) array_like
        A world point in front of the camera, e.g. the object's centroid (metres).

    Returns
    -------
    (3, 4) ndarray
        An affine camera (last row (0, 0, 0, 1)) that images ``reference_point`` exactly where
        ``camera`` does, with the same first derivatives there.
    """
    X0, d0 = _reference_depth(camera, reference_point)
    ab = (camera.R[:2] @ X0 + camera.t[:2]) / d0  # normalised image coordinates of X0
    E = np.zeros((3, 4))
    E[:2, :3] = camera.R[:2] - np.outer(ab, camera.R[2])
    E[:2, 3] = camera.t[:2] - ab * (camera.t[2] - d0)
    E[2, 3] = d0
    return camera.K @ E / d0


def dolly_zoom_camera(
    distance: float,
    azimuth: float,
    elevation: float,
    target: ArrayLike,
    f0: float = 800.0,
    d0: float = 4.0,
    principal_point: tuple[float, float] = (319.5, 239.5),
    image_offset: float = 0.0,
) -> Camera:
    r"""A camera on a dolly zoom towards ``target``, its depth ``distance`` metres, zoomed to
    :func:`dolly_zoom_focal` ``(f0, d0, distance)`` so the target keeps the size it has at depth ``d0`` with
    focal length ``f0`` (pixels). See lesson 05, section 2.

    The camera keeps one orientation R at every distance: that of a camera on the orbit (``azimuth``,
    ``elevation``, radians: :func:`camlab.camera.orbit_eye`) looking at the target. It moves along its own
    principal axis, as in H&Z §6.3.1: :math:`C = X_T - s\,r_1 - d\,r_3`, so the target has camera
    coordinates :math:`(s, 0, d)`, depth ``distance`` = d. ``image_offset`` (pixels) sets the sideways
    shift :math:`s = \text{image\_offset}\; d_0 / f_0` metres, which images the target exactly
    ``image_offset`` px right of the principal point at every distance (:math:`f s / d = f_0 s / d_0`, as
    f grows like d). With ``image_offset = 0`` the camera looks straight at the target from ``distance``
    metres on the orbit.

    As the camera keeps R and moves along r3, every point's lateral camera coordinates (x, y) stay fixed
    and its depth grows by the same amount, while f / d stays f0 / d0: the affine approximation
    :math:`P_\infty` about the target is the same matrix at every distance, the fixed image the
    perspective one converges to.
    """
    distance = check_positive(distance, "distance", "metres")
    f = dolly_zoom_focal(f0, d0, distance)
    eye = orbit_eye(azimuth, elevation, distance, target)  # checks target: a 3-D point
    target = np.asarray(target, dtype=float)
    R = Camera.look_at(eye, target).R
    shift = float(image_offset) * d0 / f0  # metres right of the principal axis (camera x)
    centre = target - shift * R[0] - distance * R[2]
    return Camera(intrinsic_matrix(f, f, *principal_point), R, -R @ centre)


def dolly_zoom_errors(
    points_world: ArrayLike,
    distances: ArrayLike,
    azimuth: float,
    elevation: float,
    target: ArrayLike,
    f0: float = 800.0,
    d0: float = 4.0,
    approximation: Callable[[Camera, ArrayLike], np.ndarray] | None = None,
    image_offset: float = 0.0,
) -> np.ndarray:
    """RMS pixel distance between the perspective and weak-perspective images of ``points_world`` along a
    dolly zoom: one value per distance of :func:`dolly_zoom_camera`, weak perspective about ``target``
    (or ``approximation(camera, target)``, e.g. :func:`paraperspective_approximation`).

    The object keeps its image size while the depth range shrinks relative to the distance, so
    the error falls like 1 / d (lesson 05, section 2). ``image_offset`` is :func:`dolly_zoom_camera`'s.
    """
    ds = as_float(distances, "distances")
    if ds.ndim != 1 or len(ds) == 0 or not np.all(np.isfinite(ds) & (ds > 0)):
        raise CamlabInputError(
            f"distances: expected a non-empty 1-D array of positive distances in metres, got "
            f"{np.array2string(ds, precision=3, threshold=6)} (shape {ds.shape})"
        )
    out = []
    for d in ds:
        cam = dolly_zoom_camera(d, azimuth, elevation, target, f0, d0, image_offset=image_offset)
        out.append(
            np.sqrt(np.mean(weak_perspective_error(cam, points_world, target, approximation) ** 2))
        )
    return np.array(out)


class ThreeImages(NamedTuple):
    """One scene seen by a perspective camera and by its two affine simplifications.

    Attributes
    ----------
    perspective, weak, orthographic : (M, 2, 2) ndarray
        The segments' images, pixels for the first two, metres (camera x, y) for the orthographic one.
    P_weak, P_orth : (3, 4) ndarray
        The weak-perspective and orthographic matrices used.
    """

    perspective: np.ndarray
    weak: np.ndarray
    orthographic: np.ndarray
    P_weak: np.ndarray
    P_orth: np.ndarray


def three_images(camera: Camera, segments: ArrayLike) -> ThreeImages:
    """Segments (M, 2, 3), metres, seen by ``camera``, by its weak-perspective approximation about
    the segments' centroid (:func:`affine_approximation`), and by the orthographic camera with
    the same pose (:func:`orthographic_matrix`). See lesson 05, section 1.
    """
    perspective = project_segments(camera, segments)  # validates the segments
    segs = check_finite(
        np.asarray(segments, dtype=float), "segments"
    )  # the centroid needs every end point
    P_weak = affine_approximation(camera, segs.reshape(-1, 3).mean(axis=0))
    P_orth = orthographic_matrix(camera.R, camera.t)
    return ThreeImages(
        perspective, project_segments(P_weak, segs), project_segments(P_orth, segs), P_weak, P_orth
    )


def largest_gap_in_frame(
    camera: Camera,
    P_affine: ArrayLike,
    segments: ArrayLike,
    size: tuple[int, int] = (640, 480),
    samples: int = 41,
) -> float:
    """The largest distance (pixels) between the perspective and the affine image of the same world point,
    over ``samples`` points along each (M, 2, 3) segment whose two images both fall inside the
    ``size`` = (width, height) frame (NaN if none does): what a reader can see in the picture."""
    segs = check_finite(np.asarray(segments, dtype=float), "segments")
    if segs.ndim != 3 or segs.shape[1:] != (2, 3):
        raise CamlabInputError(
            f"segments: expected (M, 2, 3) pairs of world points, got shape {segs.shape}"
        )
    s = np.linspace(0.0, 1.0, samples)[None, :, None]
    X = (segs[:, :1] + s * (segs[:, 1:] - segs[:, :1])).reshape(-1, 3)
    a, b = camera.replace(dist=(0.0,) * 5).project(X), project_points(P_affine, X)
    w, h = size
    inside = np.all(
        [
            (p[:, 0] >= -0.5) & (p[:, 0] <= w - 0.5) & (p[:, 1] >= -0.5) & (p[:, 1] <= h - 0.5)
            for p in (a, b)
        ],
        axis=0,
    )
    return (
        float(np.linalg.norm(a[inside] - b[inside], axis=1).max()) if inside.any() else float("nan")
    )


def weak_perspective_error(
    camera: Camera,
    points_world: ArrayLike,
    reference_point: ArrayLike | None = None,
    approximation: Callable[[Camera, ArrayLike], np.ndarray] | None = None,
) -> np.ndarray:
    r"""Per-point pixel distance between perspective and weak-perspective images.

    The weak-perspective camera is :func:`affine_approximation` about ``reference_point``
    (default: the centroid of the points). The error grows with :math:`\Delta / d_0`,
    the point's depth offset relative to the reference depth. Pass
    ``approximation=paraperspective_approximation`` to measure that camera instead.

    Returns
    -------
    (N,) ndarray
        Pixels; NaN for points behind the camera.
    """
    X = as_points(points_world, 3, "points_world").array
    X0 = X.mean(axis=0) if reference_point is None else reference_point
    PA = (approximation or affine_approximation)(camera, X0)
    return np.linalg.norm(
        camera.replace(dist=(0.0,) * 5).project(X) - project_points(PA, X), axis=1
    )


def dolly_zoom_focal(f0: float, d0: float, d: float) -> float:
    r"""The focal length that keeps an object's image size fixed when the camera moves
    from distance ``d0`` to ``d``: the image size is :math:`\propto f / d`, so
    :math:`f = f_0 \, d / d_0` (the "Vertigo" dolly zoom)."""
    return (
        check_positive(f0, "f0", "pixels")
        * check_positive(d, "d", "metres")
        / check_positive(d0, "d0", "metres")
    )


def estimate_affine_camera(points_world: ArrayLike, points_image: ArrayLike) -> np.ndarray:
    r"""The gold-standard affine camera from N >= 4 correspondences (H&Z algorithm 7.2).

    An affine camera is linear, :math:`u_i = M_2 X_i + t_2`, so the image error is linear
    in its 8 entries and the least-squares solution *is* the maximum-likelihood estimate
    under Gaussian pixel noise; no iteration is needed. Centring both point sets
    (:math:`\bar X`, :math:`\bar u`) removes :math:`t_2 = \bar u - M_2 \bar X`, and
    :math:`M_2` solves :math:`\min \sum_i \|(u_i - \bar u) - M_2 (X_i - \bar X)\|^2`,
    i.e. :math:`M_2^\top = (X_c^\top X_c)^{-1} X_c^\top U_c`.

    Parameters
    ----------
    points_world : (N, 3) array_like
        World points (metres), N >= 4, not coplanar.
    points_image : (N, 2) array_like

    Returns
    -------
    (3, 4) ndarray
        Affine camera with last row (0, 0, 0, 1).

    Raises
    ------
    CamlabInputError
        Fewer than 4 points or mismatched counts.
    DegenerateError
        Coplanar world points (M_2 is then not determined).
    """
    X, uv, _ = as_point_pairs(
        points_world,
        points_image,
        ("points_world", "points_image"),
        (3, 2),
        min_count=4,
        why="an affine camera has 8 degrees of freedom and each point gives 2 equations; "
        "add more points",
    )
    Xm, um = X.mean(axis=0), uv.mean(axis=0)
    Xc, uc = X - Xm, uv - um
    sv = np.linalg.svd(Xc, compute_uv=False)
    if sv[2] <= 1e-9 * sv[0]:
        raise DegenerateError(
            "estimate_affine_camera: the world points are coplanar, so the affine camera is not determined; "
            "use points off a single plane"
        )
    M2 = np.linalg.lstsq(Xc, uc, rcond=None)[0].T
    P = np.zeros((3, 4))
    P[:2, :3] = M2
    P[:2, 3] = um - M2 @ Xm
    P[2, 3] = 1.0
    return P


def image_of_direction(P: ArrayLike, direction: ArrayLike) -> np.ndarray:
    r"""Where a family of parallel world lines with ``direction`` d meets in the image:
    :math:`v = P (d, 0)^\top`, homogeneous (3,).

    For a finite camera this is the vanishing point :math:`K R d`. For an affine camera
    its last coordinate is 0: an ideal point, so the image lines are parallel too (with
    direction v[:2]).
    """
    Pm = check_matrix(P, (3, 4), "P")
    d = check_matrix(direction, (3,), "direction")
    if not np.any(d):
        raise CamlabInputError("direction: expected a non-zero 3-vector, got (0, 0, 0)")
    return Pm[:, :3] @ d


class AffineDeparture(NamedTuple):
    """How far a homography is from its best affine fit, over an image (:func:`affine_departure`).

    Attributes
    ----------
    u, v : (S, S) ndarray
        The grid of pixel centres spanning the image (pixels).
    distance : (S, S) ndarray
        At each grid point, the distance (pixels) between the homography's and the affine fit's images.
    at_points : (N,) ndarray
        The same distance at the given points (empty without points).
    """

    u: np.ndarray
    v: np.ndarray
    distance: np.ndarray
    at_points: np.ndarray


def affine_departure(
    H: ArrayLike, size: tuple[int, int], samples: int = 30, points: ArrayLike | None = None
) -> AffineDeparture:
    r"""The distance between the homography ``H`` and its least-squares affine fit, everywhere on a
    ``samples`` x ``samples`` grid of pixel centres spanning a ``size`` = (width, height) image, and at
    ``points`` ((N, 2) pixels, e.g. the matches ``H`` was fitted to, where it is not extrapolated).

    The affine fit minimises the squared distance over the grid. See :func:`affine_fit_departure`
    (the largest of these distances) and lesson 05, section 3.
    """
    Hm = check_matrix(H, (3, 3), "H")
    width, height = (int(check_positive(n, "size", "pixels")) for n in size)
    u, v = np.meshgrid(np.linspace(0, width - 1, samples), np.linspace(0, height - 1, samples))

    def lifted(uv):
        return np.column_stack([uv, np.ones(len(uv))])

    def mapped(g):
        m = g @ Hm.T
        return m[:, :2] / m[:, 2:]

    grid = lifted(np.column_stack([u.ravel(), v.ravel()]))
    A = np.linalg.lstsq(grid, mapped(grid), rcond=None)[0]
    distance = np.linalg.norm(grid @ A - mapped(grid), axis=1).reshape(u.shape)
    if points is None:
        return AffineDeparture(u, v, distance, np.empty(0))
    pts = lifted(as_points(points, 2, "points").array)
    return AffineDeparture(u, v, distance, np.linalg.norm(pts @ A - mapped(pts), axis=1))


def affine_fit_departure(H: ArrayLike, size: tuple[int, int], samples: int = 30) -> float:
    r"""How far the homography ``H`` is from an affine map over a ``size`` = (width, height) image: the
    largest distance (pixels) between ``H`` and its least-squares affine fit on a ``samples`` x ``samples``
    grid of pixel centres spanning the image (:func:`affine_departure`).

    Two affine cameras see a plane through affine maps, so two views of a plane are related by an
    affinity; for perspective cameras the map is a homography. It is affine exactly when it keeps the
    line at infinity (H&Z §2.7.1): when the plane meets both cameras' principal planes in the same
    line. That holds when both views see the plane face-on (its depth nearly constant across each
    picture), but also, exactly, for one perspective camera slid within its principal plane without
    turning. So a large departure proves perspective matters for the plane in at least one view; a
    small one does not prove affine cameras. See lesson 05, section 3.
    """
    return float(affine_departure(H, size, samples).distance.max())


PROJECTION_MODELS = ("orthographic", "weak perspective", "para-perspective", "perspective")


def projection_rays(
    points_xz: ArrayLike, reference_xz: ArrayLike, model: str, image_depth: float = 1.0
) -> np.ndarray:
    r"""The rays of one camera model in a top view (camera x across, z forward; centre at the origin).

    Each point travels to its image on the line :math:`z =` ``image_depth`` (H&Z §6.3; Szeliski
    fig. 2.7): **perspective** straight towards the centre; **orthographic** parallel to the optical
    axis (image x in metres); **weak perspective** parallel to the axis onto the plane :math:`z = d_0`
    through the reference point, then towards the centre; **para-perspective** parallel to the ray
    through the reference point onto that plane, then towards the centre.

    Parameters
    ----------
    points_xz : (N, 2) array_like
        Points (x, z) in metres, in front of the camera (z > 0).
    reference_xz : (2,) array_like
        The reference point :math:`X_0 = (x_0, d_0)`, :math:`d_0 > 0`.
    model : one of :data:`PROJECTION_MODELS`
    image_depth : float
        Where the image line is drawn (z, metres).

    Returns
    -------
    (N, 3, 2) ndarray
        Per point: the point, where its ray bends (on :math:`z = d_0`; the point itself for the
        perspective and orthographic models) and its image on :math:`z =` ``image_depth``.
    """
    p = as_points(points_xz, 2, "points_xz").array
    x0, d0 = check_matrix(reference_xz, (2,), "reference_xz")
    d0 = check_positive(d0, "reference_xz[1]", "metres (the reference depth)")
    f = check_positive(image_depth, "image_depth", "metres")
    if model not in PROJECTION_MODELS:
        raise CamlabInputError(f"model: expected one of {PROJECTION_MODELS}, got {model!r}")
    x, z = p[:, 0], p[:, 1]
    if model in ("orthographic", "perspective"):
        bend = p
        image_x = x if model == "orthographic" else f * x / z
    else:
        slope = 0.0 if model == "weak perspective" else x0 / d0  # dx/dz of the projection direction
        bend = np.column_stack([x - slope * (z - d0), np.full(len(p), d0)])
        image_x = f * bend[:, 0] / d0
    image = np.column_stack([image_x, np.full(len(p), f)])
    return np.stack([p, bend, image], axis=1)
