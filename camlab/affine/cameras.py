r"""The affine cameras and the affine approximations of a perspective camera.

The orthographic, scaled orthographic, weak perspective and general affine cameras, and the affine
and para-perspective approximations of a perspective camera, with their errors.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    CamlabInputError,
    as_points,
    check_matrix,
    check_positive,
    check_rotation,
)
from ..camera import Camera, project_points

__all__ = [
    "affine_approximation",
    "image_of_direction",
    "is_affine",
    "orthographic_matrix",
    "paraperspective_approximation",
    "projection_rays",
    "PROJECTION_MODELS",
    "scaled_orthographic_matrix",
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
    r"""The orthographic camera matrix: keep the camera x, y coordinates and forget depth.

    .. math:: P = \begin{pmatrix} 1&0&0&0 \\ 0&1&0&0 \\ 0&0&0&1\end{pmatrix}
              \begin{pmatrix} R & t \\ 0^\top & 1\end{pmatrix}

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
        The camera; it gives image coordinates in metres.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 6.3.4
       (a hierarchy of affine cameras: orthographic projection).

    Examples
    --------
    >>> orthographic_matrix(np.eye(3), [0.0, 0.0, 5.0]) @ [1.0, 2.0, 3.0, 1.0]
    array([1., 2., 1.])
    """
    return scaled_orthographic_matrix(R, t, 1.0, (0.0, 0.0))


def scaled_orthographic_matrix(
    R: ArrayLike, t: ArrayLike, k: float, principal_point: ArrayLike = (0.0, 0.0)
) -> np.ndarray:
    r"""The scaled orthographic camera: orthographic projection, ``k`` pixels per metre.

    :math:`u = k (r_1 \cdot X + t_1) + c_x`, likewise v: :func:`weak_perspective_matrix` with
    equal scales and no skew.

    Parameters
    ----------
    R : (3, 3) array_like
        cam_from_world rotation.
    t : (3,) array_like
        cam_from_world translation (metres); only t[0], t[1] matter.
    k : float
        The scale, pixels per metre (> 0).
    principal_point : (2,) array_like
        The pixel offset (cx, cy) added to every image point.

    Returns
    -------
    (3, 4) ndarray
        An affine camera (last row (0, 0, 0, 1)) giving pixels.

    Raises
    ------
    CamlabInputError
        ``R`` not a rotation, ``t`` or ``principal_point`` of the wrong shape, ``k <= 0``.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 6.3.4
       (a hierarchy of affine cameras: scaled orthographic projection).
    """
    return weak_perspective_matrix(R, t, k, k, 0.0, principal_point)


def weak_perspective_matrix(
    R: ArrayLike,
    t: ArrayLike,
    ax: float,
    ay: float,
    skew: float = 0.0,
    principal_point: ArrayLike = (0.0, 0.0),
) -> np.ndarray:
    r"""A weak-perspective camera, or with ``skew`` a general affine camera.

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
    R : (3, 3) array_like
        cam_from_world rotation.
    t : (3,) array_like
        cam_from_world translation (metres); only t[0], t[1] matter.
    ax, ay : float
        Scales in pixels per metre (> 0): a perspective camera's :math:`f / d_0`.
    skew : float
        Pixels per metre of the second camera axis added to u (0 for weak perspective).
    principal_point : (2,) array_like
        A constant pixel offset (redundant with ``t``; see above).

    Returns
    -------
    (3, 4) ndarray
        An affine camera (last row (0, 0, 0, 1)) giving pixels.

    Raises
    ------
    CamlabInputError
        ``R`` not a rotation, ``t`` or ``principal_point`` of the wrong shape, ``ax`` or
        ``ay`` not positive.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 6.3.4
       (a hierarchy of affine cameras: weak perspective, the general affine camera).

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
    """Whether a camera matrix is affine: its centre is at infinity.

    Parameters
    ----------
    P : (3, 4) array_like
        A camera matrix.
    tol : float
        Relative tolerance: the first three entries of the last row may be up to ``tol``
        times the largest of ``|P[2, 3]|`` and ``P``'s largest entry.

    Returns
    -------
    bool
        True if P's last row is proportional to (0, 0, 0, 1) with ``P[2, 3] != 0``.

    Raises
    ------
    CamlabInputError
        ``P`` not a finite (3, 4) matrix.
    """
    a = check_matrix(P, (3, 4), "P")
    last = a[2]
    return bool(
        abs(last[3]) > 0 and np.abs(last[:3]).max() <= tol * max(abs(last[3]), np.abs(a).max())
    )


def affine_approximation(camera: Camera, reference_point: ArrayLike) -> np.ndarray:
    r"""The weak-perspective approximation of a perspective camera about a point.

    Every point's depth is replaced by the reference point's depth (zeroth order in depth;
    :func:`paraperspective_approximation` is the first-order one). With :math:`d_0 = r_3 \cdot X_0 + t_3` the depth of the reference point
    :math:`X_0`, replacing every point's depth by :math:`d_0` gives

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

    Raises
    ------
    CamlabInputError
        ``camera`` not a :class:`~camlab.camera.Camera`, or ``reference_point`` not a 3-vector
        in front of it.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, sections 6.3.1
       (the affine camera :math:`P_\infty` about a reference point) and 6.3.2 (its error).
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
    divides by :math:`d_0`. Para-perspective (Ohta, Maenobu and Sakai [2]_; Aloimonos [3]_;
    Szeliski [4]_) projects along
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
    length, so it is a general affine camera (8 degrees of freedom [1]_).

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

    Raises
    ------
    CamlabInputError
        ``camera`` not a :class:`~camlab.camera.Camera`, or ``reference_point`` not a 3-vector
        in front of it.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 6.3.4
       (the general affine camera).
    .. [2] Y. Ohta, K. Maenobu and T. Sakai, 1981, "Obtaining surface orientation from texels
       under perspective projection", *Proc. IJCAI*, 746-751.
    .. [3] J. Aloimonos, 1990, "Perspective approximations", *Image and Vision Computing* 8(3),
       179-192.
    .. [4] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022, section
       2.1.4 (3D to 2D projections: para-perspective).
    """
    X0, d0 = _reference_depth(camera, reference_point)
    ab = (camera.R[:2] @ X0 + camera.t[:2]) / d0  # normalised image coordinates of X0
    E = np.zeros((3, 4))
    E[:2, :3] = camera.R[:2] - np.outer(ab, camera.R[2])
    E[:2, 3] = camera.t[:2] - ab * (camera.t[2] - d0)
    E[2, 3] = d0
    return camera.K @ E / d0


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

    Parameters
    ----------
    camera : Camera
        The perspective camera (its distortion is ignored).
    points_world : (N, 3) array_like
        World points, metres.
    reference_point : (3,) array_like, optional
        The point the approximation is taken about; default the points' centroid.
    approximation : callable, optional
        ``approximation(camera, reference_point) -> (3, 4)`` affine camera; default
        :func:`affine_approximation`.

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


def image_of_direction(P: ArrayLike, direction: ArrayLike) -> np.ndarray:
    r"""Where a family of parallel world lines with direction d meets in the image.

    :math:`v = P (d, 0)^\top`. For a finite camera this is the vanishing point :math:`K R d`.
    For an affine camera its last coordinate is 0: an ideal point, so the image lines are
    parallel too (with direction v[:2]).

    Parameters
    ----------
    P : (3, 4) array_like
        A camera matrix.
    direction : (3,) array_like
        The lines' direction in world coordinates (non-zero; its length does not matter).

    Returns
    -------
    (3,) ndarray
        The homogeneous image point :math:`P_{:, :3}\, d` (last coordinate 0 for an affine
        camera).

    Raises
    ------
    CamlabInputError
        ``P`` not (3, 4), ``direction`` not a non-zero 3-vector.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 8.6.1
       (vanishing points, :math:`v = K R d`), and section 6.3 (affine cameras).
    """
    Pm = check_matrix(P, (3, 4), "P")
    d = check_matrix(direction, (3,), "direction")
    if not np.any(d):
        raise CamlabInputError("direction: expected a non-zero 3-vector, got (0, 0, 0)")
    return Pm[:, :3] @ d


PROJECTION_MODELS = ("orthographic", "weak perspective", "para-perspective", "perspective")


def projection_rays(
    points_xz: ArrayLike, reference_xz: ArrayLike, model: str, image_depth: float = 1.0
) -> np.ndarray:
    r"""The rays of one camera model in a top view (camera x across, z forward; centre at the origin).

    Each point travels to its image on the line :math:`z =` ``image_depth`` ([1]_, [2]_):
    **perspective** straight towards the centre; **orthographic** parallel to the optical
    axis (image x in metres); **weak perspective** parallel to the axis onto the plane :math:`z = d_0`
    through the reference point, then towards the centre; **para-perspective** parallel to the ray
    through the reference point onto that plane, then towards the centre.

    Parameters
    ----------
    points_xz : (N, 2) array_like
        Points (x, z) in metres, in front of the camera (z > 0).
    reference_xz : (2,) array_like
        The reference point :math:`X_0 = (x_0, d_0)`, :math:`d_0 > 0`.
    model : str
        One of :data:`PROJECTION_MODELS`.
    image_depth : float
        Where the image line is drawn (z, metres).

    Returns
    -------
    (N, 3, 2) ndarray
        Per point: the point, where its ray bends (on :math:`z = d_0`; the point itself for the
        perspective and orthographic models) and its image on :math:`z =` ``image_depth``.

    Raises
    ------
    CamlabInputError
        Points not (N, 2), a non-positive reference depth or ``image_depth``, an unknown model.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 6.3
       (cameras at infinity, affine cameras).
    .. [2] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022, section
       2.1.4 (3D to 2D projections, the figure of the projection models).
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
