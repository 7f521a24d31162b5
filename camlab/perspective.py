r"""Perspective correction: rectify a photographed rectangle (page, painting, facade).

Four image corners of a planar rectangle fix the homography to an upright rectangle,
but not the rectangle's true shape: any w x h target gives a valid rectifying H. The
shape is recovered from the quadrilateral itself (:func:`estimate_aspect_ratio`):
the two pairs of opposite edges give two vanishing directions that must be orthogonal
in 3-D, which fixes the focal length, and then the ratio of the edge directions' 3-D
lengths is the aspect ratio (Zhang and He, "Whiteboard scanning and image
enhancement", 2007).

Also here: corner ordering and validation (:func:`order_corners`,
:func:`check_quadrilateral`) and an automatic document finder (:func:`find_document`).
Lesson 10's synthetic photographs of textured planes with known ground truth live with the
other scenes: :func:`camlab.scenes.photograph_plane` with :func:`camlab.scenes.page_texture`,
:func:`camlab.scenes.facade_texture`, :func:`camlab.scenes.painting_texture`.

Corners are (u, v) pixels, (column, row), origin at the centre of the top-left pixel,
in the order top-left, top-right, bottom-right, bottom-left (clockwise on screen).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._validate import (
    CamlabInputError,
    DegenerateError,
    as_points,
    check_image,
    check_positive,
    check_shape,
    check_size,
)
from .homography import estimate_homography
from .warp import warp_perspective

__all__ = [
    "AspectRatio",
    "ConicRows",
    "DocumentNotFoundError",
    "NULL_GAP",
    "Rectified",
    "affine_rectification",
    "check_quadrilateral",
    "estimate_aspect_ratio",
    "MetricRectification",
    "dual_conic_from_orthogonal_lines",
    "dual_conic_rows",
    "find_document",
    "metric_rectification",
    "order_corners",
    "rectangle_homography",
    "rectify_quadrilateral",
    "OrthogonalLinePairs",
    "square_grid_right_angles",
]


class DocumentNotFoundError(DegenerateError):
    """:func:`find_document` found no convex quadrilateral large enough to be a document."""


# --------------------------------------------------------------------------- corners


def _quad(corners: ArrayLike) -> np.ndarray:
    q = as_points(corners, 2, "corners").array
    if len(q) != 4:
        raise CamlabInputError(
            f"corners: expected 4 corners (top-left, top-right, bottom-right, bottom-left), got {len(q)}"
        )
    return q


def _signed_area(q: np.ndarray) -> float:
    """Shoelace area in (u, v) pixels; positive for clockwise-on-screen order (v points down)."""
    (u, v), (u1, v1) = q.T, np.roll(q, -1, axis=0).T  # each corner and the next
    return 0.5 * float(np.sum(u * v1 - u1 * v))


def _segments_cross(p1, p2, p3, p4) -> bool:
    def orient(a, b, c):
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])

    d1, d2 = orient(p3, p4, p1), orient(p3, p4, p2)
    d3, d4 = orient(p1, p2, p3), orient(p1, p2, p4)
    return (d1 * d2 < 0) and (d3 * d4 < 0)


def order_corners(corners: ArrayLike) -> np.ndarray:
    """Put four corners in the order top-left, top-right, bottom-right, bottom-left.

    Sorts by angle around the centroid (clockwise on screen, because v points down) and
    starts at the corner with the smallest u + v. This also untangles a bow-tie
    (self-intersecting) order.

    Parameters
    ----------
    corners : (4, 2) array_like
        Four corner pixels (u, v), in any order.

    Returns
    -------
    (4, 2) ndarray
        The corners TL, TR, BR, BL.

    Examples
    --------
    >>> order_corners([[10, 0], [0, 0], [0, 10], [10, 10]])
    array([[ 0.,  0.],
           [10.,  0.],
           [10., 10.],
           [ 0., 10.]])
    """
    q = _quad(corners)
    c = q.mean(axis=0)
    q = q[np.argsort(np.arctan2(q[:, 1] - c[1], q[:, 0] - c[0]))]
    start = int(np.argmin(q.sum(axis=1)))
    return np.roll(q, -start, axis=0)


def check_quadrilateral(corners: ArrayLike) -> np.ndarray:
    """Validate four corners as a convex quadrilateral in TL, TR, BR, BL order; return them.

    Parameters
    ----------
    corners : (4, 2) array_like
        Four corner pixels (u, v), meant as TL, TR, BR, BL.

    Returns
    -------
    (4, 2) ndarray
        The corners, as floats.

    Raises
    ------
    DegenerateError
        Corners coincide, three are collinear, the order is self-intersecting (a bow
        tie), counter-clockwise (the rectified view would be mirrored), or the
        quadrilateral is not convex (no photograph of a rectangle is).
    """
    q = _quad(corners)
    scale = max(np.ptp(q, axis=0).max(), 1e-300)
    edges = q[[1, 2, 3, 0]] - q  # edge i runs from corner i to corner i + 1
    nxt = edges[[1, 2, 3, 0]]
    turns = edges[:, 0] * nxt[:, 1] - edges[:, 1] * nxt[:, 0]  # the turn at corner i + 1
    for i, cross in enumerate(turns.tolist()):
        if abs(cross) < 1e-9 * scale**2:
            a, b, c = q[i], q[(i + 1) % 4], q[(i + 2) % 4]
            raise DegenerateError(
                f"corners: corners {i}, {(i + 1) % 4}, {(i + 2) % 4} are collinear or coincide "
                f"({a}, {b}, {c}); the four corners must form a quadrilateral"
            )
    p = q.tolist()  # Python floats: the orientation tests below are scalar arithmetic
    if _segments_cross(p[0], p[1], p[2], p[3]) or _segments_cross(p[1], p[2], p[3], p[0]):
        raise DegenerateError(
            "corners: the quadrilateral is self-intersecting (a bow tie), so the corners are out of order; "
            "give them as top-left, top-right, bottom-right, bottom-left, or pass reorder=True "
            "(see order_corners)"
        )
    if _signed_area(q) < 0:
        raise DegenerateError(
            "corners: the corners go counter-clockwise on screen, so the rectified view would be mirrored; "
            "give them as top-left, top-right, bottom-right, bottom-left, or pass reorder=True"
        )
    if turns.min() < 0:
        raise DegenerateError(
            "corners: the quadrilateral is not convex, and no photograph of a rectangle is; check the corners"
        )
    return q


# --------------------------------------------------------------------------- aspect ratio


class AspectRatio(NamedTuple):
    """The rectangle's shape recovered from its image.

    Attributes
    ----------
    ratio : float
        Width / height of the real rectangle (width = the TL-TR edge).
    focal_length : float or None
        Focal length in pixels used (given, estimated, or None when not needed:
        the image is an affine view with both edge pairs parallel).
    focal_source : str
        ``"given"``, ``"estimated"`` (from the quadrilateral), ``"not needed"``, or
        ``"assumed"`` (it could not be estimated because one edge pair is parallel in the
        image, so the default ``max(image width, height)`` was used).
    """

    ratio: float
    focal_length: float | None
    focal_source: str


_RIGHT_ANGLE_TOL_DEG = 0.5
"""How far from 90 degrees a parallelogram's corners may be when both edge pairs are parallel."""


def estimate_aspect_ratio(
    corners: ArrayLike,
    image_shape: Sequence[int] | None = None,
    *,
    focal_length: float | None = None,
    principal_point: ArrayLike | None = None,
) -> AspectRatio:
    r"""Estimate the true width/height ratio of a rectangle from its four image corners.

    Derivation (Zhang and He 2007). Let the rectangle's corners be :math:`P_1` (TL),
    :math:`P_2 = P_1 + w e_1` (TR), :math:`P_3 = P_1 + h e_2` (BL),
    :math:`P_4 = P_1 + w e_1 + h e_2` (BR), with unit :math:`e_1 \perp e_2`, and
    :math:`\lambda_i m_i = A P_i` their images (pixel coordinates taken relative to the
    principal point, so :math:`A = \mathrm{diag}(f, f, 1)`). Since
    :math:`P_4 - P_3 = P_2 - P_1`, :math:`\lambda_4 m_4 = \lambda_2 m_2 + \lambda_3 m_3 - \lambda_1 m_1`;
    crossing with :math:`m_4` and dotting with :math:`m_3` or :math:`m_2` gives

    .. math::
        k_2 = \frac{\lambda_2}{\lambda_1} = \frac{(m_1 \times m_4) \cdot m_3}{(m_2 \times m_4) \cdot m_3},\qquad
        k_3 = \frac{\lambda_3}{\lambda_1} = \frac{(m_1 \times m_4) \cdot m_2}{(m_3 \times m_4) \cdot m_2}.

    Then :math:`n_2 = k_2 m_2 - m_1 \propto w A e_1` and :math:`n_3 = k_3 m_3 - m_1 \propto h A e_2`.
    Orthogonality :math:`e_1 \cdot e_2 = 0` gives the focal length

    .. math:: f^2 = -\frac{n_{21} n_{31} + n_{22} n_{32}}{n_{23} n_{33}},

    and the ratio of lengths :math:`\|A^{-1} n_2\| / \|A^{-1} n_3\|` is :math:`w / h`:

    .. math:: \left(\frac{w}{h}\right)^2 = \frac{(n_{21}^2 + n_{22}^2)/f^2 + n_{23}^2}{(n_{31}^2 + n_{32}^2)/f^2 + n_{33}^2}.

    When a pair of opposite edges is parallel in the image (:math:`n_{23} n_{33} = 0`)
    f cannot be estimated; then it is taken from ``focal_length`` or assumed to be
    ``max(width, height)`` of the image (about a 53 degree field of view), and the
    result says so. When both pairs are parallel f cancels: under a pinhole camera the
    rectangle then faces the camera and its photo is a similarity of it, so the corners must
    meet at right angles (within ``_RIGHT_ANGLE_TOL_DEG``); a sheared parallelogram is refused
    (:class:`DegenerateError`), as no rectangle projects to it.

    Parameters
    ----------
    corners : (4, 2) array_like
        TL, TR, BR, BL pixels.
    image_shape : (height, width[, C]), optional
        Gives the default principal point (the image centre) and assumed focal length.
    focal_length : float, optional
        Known focal length in pixels (skips the estimate; better when it is known).
    principal_point : (2,) array_like, optional
        Default: the image centre ((width - 1) / 2, (height - 1) / 2).

    Returns
    -------
    AspectRatio
        ``ratio`` (width / height), ``focal_length``, ``focal_source``.

    Raises
    ------
    DegenerateError
        Both edge pairs parallel but not at right angles (no rectangle's photo), or no f
        from the corners and no ``image_shape`` to assume one from.

    Examples
    --------
    >>> round(estimate_aspect_ratio([[0, 0], [400, 0], [400, 200], [0, 200]], (480, 640)).ratio, 12)
    2.0
    """
    q = check_quadrilateral(corners)
    if principal_point is not None:
        pp = as_points(principal_point, 2, "principal_point").array[0]
    elif image_shape is not None:
        image_shape = check_shape(
            tuple(image_shape)[:2] if isinstance(image_shape, (tuple, list)) else image_shape,
            "image_shape",
        )
        pp = np.array([(image_shape[1] - 1) / 2, (image_shape[0] - 1) / 2])
    else:
        raise CamlabInputError(
            "estimate_aspect_ratio: expected image_shape or principal_point (the principal point is needed "
            "to relate the corners to viewing directions); pass image.shape"
        )
    if focal_length is not None:
        focal_length = check_positive(focal_length, "focal_length", "pixels")
    # Pixel coordinates relative to the principal point, scaled to order 1 for conditioning.
    scale = float(np.abs(q - pp).max()) or 1.0
    m = np.column_stack([(q - pp) / scale, np.ones(4)])
    m1, m2, m4, m3 = m  # input order TL, TR, BR, BL; the paper's m1..m4 are TL, TR, BL, BR
    c14, c24, c34 = np.cross([m1, m2, m3], m4)  # m_i x m4, in one call
    k2 = np.dot(c14, m3) / np.dot(c24, m3)
    k3 = np.dot(c14, m2) / np.dot(c34, m2)
    n2 = k2 * m2 - m1
    n3 = k3 * m3 - m1
    par2 = abs(n2[2]) < 1e-9 * np.linalg.norm(n2)
    par3 = abs(n3[2]) < 1e-9 * np.linalg.norm(n3)
    if par2 and par3:  # a fronto-parallel rectangle: its photo is a similarity, so a right angle
        cos = abs(n2[:2] @ n3[:2]) / (np.linalg.norm(n2[:2]) * np.linalg.norm(n3[:2]))
        if cos > np.sin(np.radians(_RIGHT_ANGLE_TOL_DEG)):
            raise DegenerateError(
                "estimate_aspect_ratio: both edge pairs are parallel in the image (an affine view), so "
                "the rectangle must face the camera and its photo keep right angles, but these corners "
                f"meet at {np.degrees(np.arccos(cos)):.1f} deg, not 90 (tolerance "
                f"{_RIGHT_ANGLE_TOL_DEG} deg): no rectangle projects to this parallelogram. Check the "
                "corners, or give the target size yourself (rectify_quadrilateral(..., size=(w, h)))"
            )
        return AspectRatio(
            float(np.linalg.norm(n2[:2]) / np.linalg.norm(n3[:2])), focal_length, "not needed"
        )
    if focal_length is not None:
        f, source = focal_length / scale, "given"
    else:
        f2 = -(n2[0] * n3[0] + n2[1] * n3[1]) / (n2[2] * n3[2]) if not (par2 or par3) else np.nan
        if np.isfinite(f2) and f2 > 0:
            f, source = np.sqrt(f2), "estimated"
        else:
            if image_shape is None:
                raise DegenerateError(
                    "estimate_aspect_ratio: the focal length cannot be estimated from these corners (an edge "
                    "pair is parallel in the image, or the corners are inconsistent with a rectangle); pass "
                    "focal_length or image_shape"
                )
            f, source = max(image_shape[0], image_shape[1]) / scale, "assumed"
    num = (n2[0] ** 2 + n2[1] ** 2) / f**2 + n2[2] ** 2
    den = (n3[0] ** 2 + n3[1] ** 2) / f**2 + n3[2] ** 2
    return AspectRatio(float(np.sqrt(num / den)), float(f * scale), source)


# --------------------------------------------------------------------------- rectification


class Rectified(NamedTuple):
    """A rectified view.

    Attributes
    ----------
    image : (height, width[, C]) ndarray
        The upright rectangle.
    H : (3, 3) ndarray
        rectified_from_image: maps the photo's corners to (0, 0), (w-1, 0), (w-1, h-1), (0, h-1).
    corners : (4, 2) ndarray
        The (possibly reordered) photo corners used, TL, TR, BR, BL.
    aspect : AspectRatio or None
        The estimate used to size the output (None when ``size`` was given).
    """

    image: np.ndarray
    H: np.ndarray
    corners: np.ndarray
    aspect: AspectRatio | None


def affine_rectification(corners: ArrayLike) -> np.ndarray:
    r"""H_P, the homography that sends a photographed rectangle's vanishing line back to infinity.

    The top and bottom edges meet at one vanishing point, the left and right edges at another
    (meets of joins, lesson 06); their join is the plane's vanishing line
    :math:`l = (l_1, l_2, l_3)`, and

    .. math:: H_P = \begin{pmatrix} 1 & 0 & 0 \\ 0 & 1 & 0 \\ l_1 & l_2 & l_3 \end{pmatrix},
              \qquad H_P^{-T} l \sim (0, 0, 1)^T,

    so lines parallel on the plane are parallel again: what remains is an affinity (lesson 10,
    section 7). Everything stays homogeneous, so a vanishing point at infinity (an edge pair
    parallel in the photo) needs no special case.

    Parameters
    ----------
    corners : (4, 2) array_like
        The rectangle's corners (u, v) in the photo, pixels: top-left, top-right, bottom-right,
        bottom-left.

    Returns
    -------
    (3, 3) ndarray
        H_P, with l scaled to unit length and its sign chosen so that the corners keep a
        positive w = l . (u, v, 1) (the affine view is not turned by 180 degrees).

    References
    ----------
    Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., §2.7.2 (affine rectification) and
    §2.4.6 (H_P, the projective factor of a homography).
    """
    q = np.c_[check_quadrilateral(corners), np.ones(4)]
    v_across = np.cross(np.cross(q[0], q[1]), np.cross(q[3], q[2]))  # top and bottom edges meet
    v_up = np.cross(np.cross(q[0], q[3]), np.cross(q[1], q[2]))  # left and right edges meet
    line = np.cross(v_across, v_up)
    line = line / np.linalg.norm(line) * np.sign(line @ q.mean(axis=0))
    return np.vstack([np.eye(3)[:2], line])


def rectangle_homography(corners: ArrayLike, size: tuple[int, int]) -> np.ndarray:
    """The homography taking corners TL, TR, BR, BL to the upright rectangle of ``size`` pixels.

    The target corners are the centres of the rectangle's corner pixels:
    (0, 0), (width - 1, 0), (width - 1, height - 1), (0, height - 1).

    Parameters
    ----------
    corners : (4, 2) array_like
        Corner pixels (u, v), TL, TR, BR, BL.
    size : (2,) tuple of int
        The rectangle's (width, height), pixels (each >= 2).

    Returns
    -------
    (3, 3) ndarray
        H, rectified_from_image, estimated from the four correspondences
        (:func:`camlab.homography.estimate_homography`).

    Examples
    --------
    >>> H = rectangle_homography([[10, 10], [110, 10], [110, 60], [10, 60]], (101, 51))
    >>> from camlab.projective import map_points
    >>> map_points(H, [110.0, 60.0]).round(9) + 0.0
    array([100.,  50.])
    """
    q = _quad(corners)
    width, height = check_size(size, "size", minimum=2)
    target = np.array(
        [[0, 0], [width - 1, 0], [width - 1, height - 1], [0, height - 1]], dtype=float
    )
    return estimate_homography(q, target)


def rectify_quadrilateral(
    image: ArrayLike,
    corners: ArrayLike,
    size: Sequence[int] | None = None,
    *,
    focal_length: float | None = None,
    principal_point: ArrayLike | None = None,
    reorder: bool = False,
    interpolation: str = "bilinear",
    method: str = "numpy",
) -> Rectified:
    r"""Map the quadrilateral ``corners`` of ``image`` to an upright rectangle.

    H is the homography from the four corners to the output rectangle's corners
    (:func:`camlab.homography.estimate_homography`), and the output is
    :func:`camlab.warp.warp_perspective` of the image by H. Without ``size`` the
    rectangle's true aspect ratio is estimated (:func:`estimate_aspect_ratio`) and the
    width is the longer of the top and bottom edges, so no guess at the shape is made.

    Parameters
    ----------
    image : (h, w[, C]) array_like
    corners : (4, 2) array_like
        TL, TR, BR, BL pixels (u, v).
    size : (width, height), optional
        Output size in pixels; default from the estimated aspect ratio.
    focal_length, principal_point : optional
        Camera knowledge passed to :func:`estimate_aspect_ratio`.
    reorder : bool
        Put the corners in order first (:func:`order_corners`) instead of raising when
        they are out of order.
    interpolation, method : str
        As in :func:`camlab.warp.warp_perspective` (``method="cv2"`` for live demos).

    Returns
    -------
    Rectified
        ``image``, ``H``, ``corners``, ``aspect``.

    Raises
    ------
    DegenerateError
        Corners self-intersecting, counter-clockwise or non-convex (unless ``reorder``).
    """
    img = check_image(image)
    q = order_corners(corners) if reorder else _quad(corners)
    q = check_quadrilateral(q)
    aspect = None
    if size is None:
        aspect = estimate_aspect_ratio(
            q, img.shape, focal_length=focal_length, principal_point=principal_point
        )
        width = max(np.linalg.norm(q[1] - q[0]), np.linalg.norm(q[2] - q[3]))
        w_out, h_out = int(round(width)), int(round(width / aspect.ratio))
    else:
        w_out, h_out = check_size(size, "size", minimum=2)
    if w_out < 2 or h_out < 2 or w_out * h_out > 40_000_000:
        raise CamlabInputError(
            f"size: expected a (width, height) of at least 2 x 2 pixels, got ({w_out}, {h_out})"
        )
    H = rectangle_homography(q, (w_out, h_out))
    out = warp_perspective(img, H, (h_out, w_out), interpolation=interpolation, method=method)
    return Rectified(out, H, q, aspect)


# --------------------------------------------------------------------------- document finder


def find_document(image: ArrayLike, min_area_fraction: float = 0.1) -> np.ndarray:
    """Find the largest convex quadrilateral (a page) in a photo: "scan this page".

    Steps: grey, blur, Canny edges with thresholds from the median intensity, close
    small gaps (dilate), outer contours, and for each contour from the largest down its
    convex hull simplified by ``cv2.approxPolyDP`` (2% of the perimeter); the first
    simplification with 4 vertices, convex, covering at least ``min_area_fraction`` of
    the image, wins.

    Parameters
    ----------
    image : (h, w[, C]) uint8 array_like
    min_area_fraction : float
        Smallest accepted page area as a fraction of the image.

    Returns
    -------
    (4, 2) ndarray
        Corners TL, TR, BR, BL in pixels.

    Raises
    ------
    DocumentNotFoundError
        When no such quadrilateral exists; the message says what was found instead.
    """
    import cv2

    img = check_image(image)
    if not 0 < min_area_fraction < 1:
        raise CamlabInputError(
            f"min_area_fraction: expected a number in (0, 1), got {min_area_fraction!r}"
        )
    grey = img if img.ndim == 2 else cv2.cvtColor(img[..., :3].astype(np.uint8), cv2.COLOR_RGB2GRAY)
    grey = cv2.GaussianBlur(grey.astype(np.uint8), (5, 5), 0)
    med = float(np.median(grey))
    edges = cv2.Canny(grey, max(10.0, 0.5 * med), max(30.0, 1.2 * med))
    edges = cv2.dilate(edges, np.ones((3, 3), np.uint8))
    found = cv2.findContours(edges, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_SIMPLE)
    contours = found[0] if len(found) == 2 else found[1]
    area_img = float(grey.shape[0] * grey.shape[1])
    best_vertices, best_area = 0, 0.0
    for c in sorted(contours, key=cv2.contourArea, reverse=True)[:10]:
        hull = cv2.convexHull(c)
        approx = cv2.approxPolyDP(hull, 0.02 * cv2.arcLength(hull, True), True).reshape(-1, 2)
        area = cv2.contourArea(approx.astype(np.float32)) / area_img
        if best_area == 0:
            best_vertices, best_area = len(approx), area
        # The image frame itself (edges everywhere, as in noise or texture) is not a page.
        frame = np.all(
            (approx.min(axis=1) <= 2)
            | (approx[:, 0] >= grey.shape[1] - 3)
            | (approx[:, 1] >= grey.shape[0] - 3)
        )
        if (
            len(approx) == 4
            and area >= min_area_fraction
            and cv2.isContourConvex(approx)
            and not frame
        ):
            return order_corners(approx.astype(float))
    if not contours:
        why = "no edges formed a closed outline"
    else:
        why = (
            f"the largest outline simplifies to {best_vertices} vertices and covers "
            f"{100 * best_area:.0f}% of the image"
        )
    raise DocumentNotFoundError(
        f"find_document: no convex quadrilateral covering at least {100 * min_area_fraction:.0f}% of the image "
        f"({why}); photograph the page against a contrasting background, or give the corners by hand"
    )


# --------------------------------------------------------------------------- synthetic photos


# --------------------------------------------------------------------------- metric rectification from right angles


class ConicRows(NamedTuple):
    r"""The stacked, conditioned rows of :math:`l_i^T C^* m_i = 0` (:func:`dual_conic_rows`).

    Attributes
    ----------
    A : (N, 6) ndarray
        One row per pair, against (a, b, c, d, e, f) of the conditioned :math:`C^*_n`.
    T : (3, 3) ndarray
        The conditioning similarity: :math:`C^{*\prime} = T^{-1} C^*_n T^{-T}`.
    """

    A: np.ndarray
    T: np.ndarray


class MetricRectification(NamedTuple):
    r"""The image of :math:`C^*_\infty` found from right angles, and the homography it gives.

    Attributes
    ----------
    C_star : (3, 3) ndarray
        The image of the dual conic :math:`C^*_\infty`, symmetric, rank 2, positive
        semi-definite, scaled to unit Frobenius norm.
    H : (3, 3) ndarray
        ``metric_from_image``: maps the photo to a view of the plane that is right up to a
        similarity (rotation, uniform scale, translation); :math:`H C^* H^T \propto
        \operatorname{diag}(1, 1, 0)`. Its sign keeps the photo's handedness (no mirror).
    residual : float
        The largest :math:`|\cos\theta|` left between a rectified pair (0 for exact right angles).
    """

    C_star: np.ndarray
    H: np.ndarray
    residual: float


def _line_rows(lines: ArrayLike, name: str) -> np.ndarray:
    L = np.asarray(lines, dtype=float)
    if L.ndim != 2 or L.shape[1] != 3 or not np.isfinite(L).all():
        raise CamlabInputError(
            f"{name}: expected (N, 3) homogeneous lines (a, b, c) of au + bv + c = 0, one per row, "
            f"got shape {L.shape}; join two points with camlab.projective.join"
        )
    if (np.linalg.norm(L[:, :2], axis=1) == 0).any():
        raise CamlabInputError(
            f"{name}: a line (0, 0, c) is the line at infinity, which has no direction to be orthogonal to"
        )
    return L


def dual_conic_rows(lines_l: ArrayLike, lines_m: ArrayLike) -> ConicRows:
    r"""The stacked rows :math:`A` of :math:`l_i^T C^* m_i = 0`, on Hartley-conditioned lines.

    A similarity :math:`T` puts the lines' feet (their points nearest the origin) at mean
    distance :math:`\sqrt 2` about 0; lines move by :math:`T^{-T}` and are scaled to unit norm, so
    all six columns of :math:`A` are of order 1 and its singular values can be compared.

    Parameters
    ----------
    lines_l, lines_m : (N, 3) array_like
        Image lines (a, b, c), pixels, N >= 5; ``lines_l[i]`` is orthogonal to ``lines_m[i]`` on the plane.

    Returns
    -------
    ConicRows
        ``A`` (N, 6), one row per pair, and ``T`` (3, 3), the conditioning similarity.

    References
    ----------
    R. Hartley, "In defense of the eight-point algorithm", IEEE PAMI 19(6), 1997 (the conditioning).
    """
    L = _line_rows(lines_l, "lines_l")
    M = _line_rows(lines_m, "lines_m")
    if L.shape != M.shape or len(L) < 5:
        raise CamlabInputError(
            f"lines_l, lines_m: expected two (N, 3) arrays of the same N >= 5 (one orthogonal pair per "
            f"row; C* has 5 degrees of freedom), got {L.shape} and {M.shape}"
        )
    # condition: a similarity T on the points, lines move by T^{-T}
    feet = np.concatenate(
        [-(X[:, 2] / (X[:, 0] ** 2 + X[:, 1] ** 2))[:, None] * X[:, :2] for X in (L, M)]
    )
    centre = feet.mean(axis=0)
    scale = np.sqrt(2) / max(np.linalg.norm(feet - centre, axis=1).mean(), 1e-12)
    T = np.array([[scale, 0, -scale * centre[0]], [0, scale, -scale * centre[1]], [0, 0, 1]])
    Ln, Mn = L @ np.linalg.inv(T), M @ np.linalg.inv(T)  # rows: (T^{-T} l)^T = l^T T^{-1}
    Ln /= np.linalg.norm(Ln, axis=1, keepdims=True)
    Mn /= np.linalg.norm(Mn, axis=1, keepdims=True)
    (l1, l2, l3), (m1, m2, m3) = Ln.T, Mn.T
    A = np.stack(
        [
            l1 * m1,
            (l1 * m2 + l2 * m1) / 2,
            l2 * m2,
            (l1 * m3 + l3 * m1) / 2,
            (l2 * m3 + l3 * m2) / 2,
            l3 * m3,
        ],
        axis=1,
    )
    return ConicRows(A=A, T=T)


NULL_GAP = 0.1
"""Largest ratio of the 6th to the 5th singular value for which the null vector counts as determined."""


def dual_conic_from_orthogonal_lines(lines_l: ArrayLike, lines_m: ArrayLike) -> np.ndarray:
    r"""The image of :math:`C^*_\infty` from N >= 5 pairs of lines orthogonal on the plane: :math:`l_i'^T C^{*\prime} m_i' = 0`.

    Each pair gives one linear equation in the six entries of the symmetric :math:`C^{*\prime}`
    (the cross terms appear as :math:`\tfrac12 (l_1 m_2 + l_2 m_1)` because :math:`b/2` sits in two
    places); the stacked rows' null vector is the answer, found on Hartley-conditioned lines and
    moved back. The full derivation is in :func:`metric_rectification`.

    Parameters
    ----------
    lines_l, lines_m : (N, 3) array_like
        Image lines (a, b, c) of au + bv + c = 0, pixels, N >= 5; ``lines_l[i]`` is orthogonal to
        ``lines_m[i]`` on the plane.

    Returns
    -------
    (3, 3) ndarray
        :math:`C^{*\prime}`, symmetric, with a positive trace, unit Frobenius norm (not yet forced to rank 2).

    Raises
    ------
    DegenerateError
        If the pairs fix fewer than 5 degrees of freedom: exactly (5th singular value of the stacked,
        conditioned rows 0), or up to noise (the 6th above ``NULL_GAP`` times the 5th, so no null
        vector stands out, e.g. a noisy grid's rows against its columns only).

    References
    ----------
    Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., §2.7.5 (example 2.27).
    R. Hartley, "In defense of the eight-point algorithm", IEEE PAMI 19(6), 1997 (the conditioning).
    """
    A, T = dual_conic_rows(lines_l, lines_m)
    _, s, Vt = np.linalg.svd(A)
    # Exact pairs in too few directions leave s[4] = 0; measured ones leave s[4] ~ s[5], both noise
    # (the null vector is then whatever the noise picks). A well-posed set has s[5] << s[4]: on
    # noisy chessboards s[5] / s[4] < 0.003 with the diagonals, > 0.25 with rows and columns only.
    if s[4] < 1e-8 * s[0] or s[5] > NULL_GAP * s[4]:
        raise DegenerateError(
            "lines_l, lines_m: the pairs fix fewer than 5 of C*'s degrees of freedom, they point in too "
            "few directions (the 5th and 6th "
            f"singular values of the stacked rows are {s[4] / s[0]:.2g} and {s[5] / s[0]:.2g} of the "
            "largest, so noise would pick the answer). Right angles all between the same two "
            "directions (a rectangle's edges, however many pairs) fix only 4: every alpha v1 v1^T + "
            "beta v2 v2^T satisfies them (v1, v2 their vanishing points), and the free beta / alpha is the "
            "unknown aspect ratio; add pairs in another direction, e.g. a square's diagonals"
        )
    a, b, c, d, e, f = Vt[-1]
    Cn = np.array([[a, b / 2, d / 2], [b / 2, c, e / 2], [d / 2, e / 2, f]])
    Tinv = np.linalg.inv(T)
    C_star = Tinv @ Cn @ Tinv.T
    C_star = (C_star + C_star.T) / 2
    if np.trace(C_star) < 0:
        C_star = -C_star
    return C_star / np.linalg.norm(C_star)


def metric_rectification(lines_l: ArrayLike, lines_m: ArrayLike) -> MetricRectification:
    r"""Rectify a plane up to a similarity from N >= 5 pairs of lines that are orthogonal on it.

    Derivation (Hartley & Zisserman, 2nd ed., §2.7.4-2.7.5, example 2.27). On the plane, the angle
    between lines l and m satisfies :math:`\cos\theta \propto l^T C^*_\infty m` with
    :math:`C^*_\infty = \operatorname{diag}(1, 1, 0)` (:data:`camlab.projective.DUAL_CONIC_AT_INFINITY`),
    so orthogonal lines obey :math:`l^T C^*_\infty m = 0`. A photo ``x' = G x`` moves lines by
    :math:`l' = G^{-T} l` and the dual conic by :math:`C^{*\prime} = G C^*_\infty G^T`
    (:func:`camlab.projective.map_dual_conic`), and the product survives:
    :math:`l'^T C^{*\prime} m' = l^T G^{-1} G C^*_\infty G^T G^{-T} m = l^T C^*_\infty m = 0`.
    With :math:`C^{*\prime} = \begin{pmatrix} a & b/2 & d/2 \\ b/2 & c & e/2 \\ d/2 & e/2 & f \end{pmatrix}`
    each imaged pair gives one linear equation in :math:`(a, b, c, d, e, f)`:

    .. math::
        l_1 m_1\, a + \tfrac12 (l_1 m_2 + l_2 m_1)\, b + l_2 m_2\, c
        + \tfrac12 (l_1 m_3 + l_3 m_1)\, d + \tfrac12 (l_2 m_3 + l_3 m_2)\, e + l_3 m_3\, f = 0 .

    Five independent pairs fix the 5 degrees of freedom; with more, the null vector of the stacked
    rows (the last right singular vector) is the least-squares answer. The lines are first
    conditioned (Hartley): a similarity T moves their feet (the points nearest the origin) to mean
    distance :math:`\sqrt 2` about 0, lines become :math:`T^{-T} l`, and the dual conic found there,
    :math:`C^*_n`, is moved back by :math:`C^{*\prime} = T^{-1} C^*_n T^{-T}`.

    :math:`C^{*\prime}` is symmetric, positive semi-definite and of rank 2 (for exact data), so its
    eigen-decomposition (here equal to its SVD) is :math:`C^{*\prime} = U \operatorname{diag}(s_1, s_2, 0) U^T`,
    and :math:`G_0 = U \operatorname{diag}(\sqrt{s_1}, \sqrt{s_2}, 1)` satisfies
    :math:`G_0 C^*_\infty G_0^T = C^{*\prime}`: it is the photo up to a similarity, and its inverse
    :math:`H = \operatorname{diag}(1/\sqrt{s_1}, 1/\sqrt{s_2}, 1)\, U^T` rectifies. Two pairs of
    parallel right angles (a rectangle's edges) are only *one* constraint on an affinity: the pairs
    must point in at least two different directions (a square's edges and its diagonals).

    Parameters
    ----------
    lines_l, lines_m : (N, 3) array_like
        Image lines (a, b, c), pixels, N >= 5; ``lines_l[i]`` is orthogonal to ``lines_m[i]`` on the plane.

    Returns
    -------
    MetricRectification
        ``C_star``, ``H`` (metric_from_image) and the largest ``|cos|`` left.

    Raises
    ------
    DegenerateError
        If the pairs do not fix :math:`C^{*\prime}` (fewer than 5 independent, e.g. every pair in
        the same two directions), or the estimate is not a real rank-2 conic (inconsistent pairs).

    References
    ----------
    Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., §2.7.5, examples 2.26 and 2.27;
    Liebowitz & Zisserman, "Metric rectification for perspective images of planes", CVPR 1998.
    """
    C_star = dual_conic_from_orthogonal_lines(lines_l, lines_m)
    vals, U = np.linalg.eigh(C_star)
    vals, U = vals[::-1], U[:, ::-1]  # s1 >= s2 >= s3
    if vals[1] <= 1e-9 * vals[0]:
        raise DegenerateError(
            "lines_l, lines_m: the estimated C*' has fewer than two positive eigenvalues, so it is no image "
            "of the circular points; the pairs are inconsistent (not orthogonal on one plane) or too noisy"
        )
    C_star = U[:, :2] @ np.diag(vals[:2]) @ U[:, :2].T  # the nearest rank-2 conic
    C_star /= np.linalg.norm(C_star)
    H = np.diag([1 / np.sqrt(vals[0]), 1 / np.sqrt(vals[1]), 1.0]) @ U.T
    L, M = np.asarray(lines_l, dtype=float), np.asarray(lines_m, dtype=float)
    feet = np.concatenate(
        [-(X[:, 2] / (X[:, 0] ** 2 + X[:, 1] ** 2))[:, None] * X[:, :2] for X in (L, M)]
    )
    if H[2] @ np.append(feet.mean(axis=0), 1.0) < 0:  # the lines' points in front: w > 0
        H = -H
    if np.linalg.det(H) < 0:  # keep the photo's handedness: no mirror image
        H[1] = -H[1]
    lr, mr = L @ np.linalg.inv(H), M @ np.linalg.inv(H)  # rectified lines H^{-T} l, as rows
    cos = np.abs((lr[:, :2] * mr[:, :2]).sum(1)) / (
        np.linalg.norm(lr[:, :2], axis=1) * np.linalg.norm(mr[:, :2], axis=1)
    )
    return MetricRectification(C_star=C_star, H=H, residual=float(cos.max()))


class OrthogonalLinePairs(NamedTuple):
    """Pairs of image lines that are orthogonal on the plane.

    Attributes
    ----------
    lines_l : (N, 3) ndarray
        Image lines (a, b, c) of au + bv + c = 0, pixels.
    lines_m : (N, 3) ndarray
        The line orthogonal on the plane to ``lines_l[i]``, same form.
    """

    lines_l: np.ndarray
    lines_m: np.ndarray


def square_grid_right_angles(grid: ArrayLike) -> OrthogonalLinePairs:
    r"""Pairs of lines that are orthogonal on a grid of squares (a chessboard), from its image corners.

    A grid of squares has right angles in two directions: its rows meet its columns, and the two
    diagonals of any square block cross at 90°. Rows against columns alone, however many, give only 4
    independent linear constraints on :math:`C^{*\prime}` (its 5 degrees of freedom less the
    aspect ratio: they all share two vanishing points); the diagonals add the second direction. Each line is fitted through all its corners (total least squares), so a
    pixel of noise on one corner moves it little.

    Parameters
    ----------
    grid : (rows, cols, 2) array_like
        Image corners (u, v), pixels, of a grid of squares, row by row, rows >= 2 and cols >= 2
        (rows, cols >= 3 when they are equal).

    Returns
    -------
    OrthogonalLinePairs
        ``lines_l`` and ``lines_m``, each (6, 3): the first and last rows against the first and last columns (4 pairs), then the two
        diagonals of the largest square block at each end of the grid (2 pairs; for a square grid,
        of the two overlapping blocks one square smaller).
    """
    g = np.asarray(grid, dtype=float)
    if g.ndim != 3 or g.shape[2] != 2 or min(g.shape[:2]) < 2 or not np.isfinite(g).all():
        raise CamlabInputError(
            f"grid: expected (rows, cols, 2) corners with rows, cols >= 2 (e.g. cv2.findChessboardCorners' "
            f"output reshaped to (rows, cols, 2)), got shape {g.shape}"
        )

    def fit(p: np.ndarray) -> np.ndarray:
        """The line through points p in total least squares: normal = the smallest singular direction."""
        c = p.mean(axis=0)
        n = np.linalg.svd(p - c)[2][1]
        return np.array([n[0], n[1], -n @ c])

    rows, cols = g.shape[:2]
    k = min(rows, cols)  # the largest square block is (k - 1) x (k - 1) squares
    blocks = [(0, 0), (rows - k, cols - k)]
    if rows == cols:  # one block only: take two overlapping smaller ones
        k, blocks = k - 1, [(0, 0), (1, 1)]
    if k < 2:
        raise CamlabInputError(
            f"grid: a square grid needs rows, cols >= 3 for two diagonal pairs, got shape {g.shape}"
        )
    L, M = [], []
    for r in (0, rows - 1):
        for c in (0, cols - 1):
            L.append(fit(g[r]))
            M.append(fit(g[:, c]))
    for r0, c0 in blocks:
        steps = np.arange(k)
        L.append(fit(g[r0 + steps, c0 + steps]))
        M.append(fit(g[r0 + k - 1 - steps, c0 + steps]))
    return OrthogonalLinePairs(np.array(L), np.array(M))
