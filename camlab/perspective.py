r"""Perspective correction: rectify a photographed rectangle (page, painting, facade).

Four image corners of a planar rectangle fix the homography to an upright rectangle,
but not the rectangle's true shape: any w x h target gives a valid rectifying H. The
shape is recovered from the quadrilateral itself (:func:`estimate_aspect_ratio`):
the two pairs of opposite edges give two vanishing directions that must be orthogonal
in 3-D, which fixes the focal length, and then the ratio of the edge directions' 3-D
lengths is the aspect ratio (Zhang and He, "Whiteboard scanning and image
enhancement", 2007).

Also here: corner ordering and validation (:func:`order_corners`,
:func:`check_quadrilateral`), an automatic document finder (:func:`find_document`),
and synthetic photographs of textured planes with known ground truth
(:func:`photograph_plane` with :func:`page_texture`, :func:`facade_texture`,
:func:`painting_texture`) for lesson 10.

Corners are (u, v) pixels, (column, row), origin at the centre of the top-left pixel,
in the order top-left, top-right, bottom-right, bottom-left (clockwise on screen).
"""
from __future__ import annotations

import functools
from typing import NamedTuple, Sequence

import numpy as np
from numpy.typing import ArrayLike

from ._validate import CamlabInputError, DegenerateError, as_points, check_positive, check_size
from .homography import estimate_homography, pose_homography
from .projective import map_points
from .warp import warp_perspective

__all__ = [
    "AspectRatio", "DocumentNotFoundError", "PlanePhoto", "Rectified", "check_quadrilateral", "desk_background",
    "estimate_aspect_ratio", "facade_texture", "find_document", "look_at_plane", "order_corners", "rectangle_homography",
    "page_texture", "painting_texture", "photograph_plane", "rectify_quadrilateral", "sample_photo",
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
    u, v = q[:, 0], q[:, 1]
    return 0.5 * float(np.sum(u * np.roll(v, -1) - np.roll(u, -1) * v))


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

    Raises
    ------
    DegenerateError
        Corners coincide, three are collinear, the order is self-intersecting (a bow
        tie), counter-clockwise (the rectified view would be mirrored), or the
        quadrilateral is not convex (no photograph of a rectangle is).
    """
    q = _quad(corners)
    scale = max(np.ptp(q, axis=0).max(), 1e-300)
    for i in range(4):
        a, b, c = q[i], q[(i + 1) % 4], q[(i + 2) % 4]
        cross = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0])
        if abs(cross) < 1e-9 * scale ** 2:
            raise DegenerateError(
                f"corners: corners {i}, {(i + 1) % 4}, {(i + 2) % 4} are collinear or coincide "
                f"({a}, {b}, {c}); the four corners must form a quadrilateral"
            )
    if _segments_cross(q[0], q[1], q[2], q[3]) or _segments_cross(q[1], q[2], q[3], q[0]):
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
    turns = [np.cross(np.append(q[(i + 1) % 4] - q[i], 0), np.append(q[(i + 2) % 4] - q[(i + 1) % 4], 0))[2]
             for i in range(4)]
    if min(turns) < 0:
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
    result says so. When both pairs are parallel the view is affine and f cancels.

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

    Examples
    --------
    >>> round(estimate_aspect_ratio([[0, 0], [400, 0], [400, 200], [0, 200]], (480, 640)).ratio, 12)
    2.0
    """
    q = check_quadrilateral(corners)
    if principal_point is not None:
        pp = as_points(principal_point, 2, "principal_point").array[0]
    elif image_shape is not None:
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
    k2 = np.dot(np.cross(m1, m4), m3) / np.dot(np.cross(m2, m4), m3)
    k3 = np.dot(np.cross(m1, m4), m2) / np.dot(np.cross(m3, m4), m2)
    n2 = k2 * m2 - m1
    n3 = k3 * m3 - m1
    par2 = abs(n2[2]) < 1e-9 * np.linalg.norm(n2)
    par3 = abs(n3[2]) < 1e-9 * np.linalg.norm(n3)
    if par2 and par3:
        return AspectRatio(float(np.linalg.norm(n2[:2]) / np.linalg.norm(n3[:2])), focal_length, "not needed")
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
    num = (n2[0] ** 2 + n2[1] ** 2) / f ** 2 + n2[2] ** 2
    den = (n3[0] ** 2 + n3[1] ** 2) / f ** 2 + n3[2] ** 2
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


def rectangle_homography(corners: ArrayLike, width: int, height: int) -> np.ndarray:
    """The homography taking corners TL, TR, BR, BL to the upright width x height rectangle.

    The target corners are the centres of the rectangle's corner pixels:
    (0, 0), (width - 1, 0), (width - 1, height - 1), (0, height - 1).

    >>> H = rectangle_homography([[10, 10], [110, 10], [110, 60], [10, 60]], 101, 51)
    >>> map_points(H, [110.0, 60.0]).round(9) + 0.0
    array([100.,  50.])
    """
    q = _quad(corners)
    target = np.array([[0, 0], [width - 1, 0], [width - 1, height - 1], [0, height - 1]], dtype=float)
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
    interpolation, method :
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
    img = np.asarray(image)
    q = order_corners(corners) if reorder else _quad(corners)
    q = check_quadrilateral(q)
    aspect = None
    if size is None:
        aspect = estimate_aspect_ratio(q, img.shape, focal_length=focal_length, principal_point=principal_point)
        width = max(np.linalg.norm(q[1] - q[0]), np.linalg.norm(q[2] - q[3]))
        w_out, h_out = int(round(width)), int(round(width / aspect.ratio))
    else:
        w_out, h_out = check_size(size, "size", minimum=2)
    if w_out < 2 or h_out < 2 or w_out * h_out > 40_000_000:
        raise CamlabInputError(f"size: expected a (width, height) of at least 2 x 2 pixels, got ({w_out}, {h_out})")
    H = rectangle_homography(q, w_out, h_out)
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

    img = np.asarray(image)
    if img.ndim not in (2, 3) or img.size == 0:
        raise CamlabInputError(f"image: expected a (H, W) or (H, W, 3) image, got shape {img.shape}")
    if not 0 < min_area_fraction < 1:
        raise CamlabInputError(f"min_area_fraction: expected a number in (0, 1), got {min_area_fraction!r}")
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
        if len(approx) == 4 and area >= min_area_fraction and cv2.isContourConvex(approx):
            return order_corners(approx.astype(float))
    if not contours:
        why = "no edges formed a closed outline"
    else:
        why = (f"the largest outline simplifies to {best_vertices} vertices and covers "
               f"{100 * best_area:.0f}% of the image")
    raise DocumentNotFoundError(
        f"find_document: no convex quadrilateral covering at least {100 * min_area_fraction:.0f}% of the image "
        f"({why}); photograph the page against a contrasting background, or give the corners by hand"
    )


# --------------------------------------------------------------------------- synthetic photos

@functools.lru_cache(maxsize=8)
def page_texture(width: int = 420, height: int = 594, seed: int = 0) -> np.ndarray:
    """A printed page (A4 proportions, 1 : sqrt 2): title, paragraphs of text, a figure box.

    Returns an (height, width, 3) uint8 RGB image drawn with ``cv2.putText`` (cached and
    read-only, like the other textures).
    """
    import cv2

    rng = np.random.default_rng(seed)
    page = np.full((height, width, 3), 250, np.uint8)
    cv2.putText(page, "Projective Geometry", (int(0.08 * width), int(0.09 * height)),
                cv2.FONT_HERSHEY_DUPLEX, width / 560, (20, 20, 20), 2, cv2.LINE_AA)
    words = ["camera", "plane", "homography", "line", "point", "image", "ray", "scale", "view", "map"]
    y = int(0.16 * height)
    line_h = max(12, height // 34)
    box_top = int(0.55 * height)
    while y < height - int(0.06 * height):
        if box_top <= y < box_top + int(0.2 * height):
            y = box_top + int(0.2 * height) + line_h
            continue
        text = " ".join(rng.choice(words, size=5))
        cv2.putText(page, text, (int(0.08 * width), y), cv2.FONT_HERSHEY_SIMPLEX, width / 1100,
                    (40, 40, 40), 1, cv2.LINE_AA)
        y += line_h
    x0, x1 = int(0.2 * width), int(0.8 * width)
    y0, y1 = box_top, box_top + int(0.18 * height)
    cv2.rectangle(page, (x0, y0), (x1, y1), (60, 90, 160), 2)
    cv2.line(page, (x0, y1), (x1, y0), (200, 60, 40), 2, cv2.LINE_AA)
    cv2.circle(page, ((x0 + x1) // 2, (y0 + y1) // 2), (y1 - y0) // 4, (40, 140, 60), 2, cv2.LINE_AA)
    page.flags.writeable = False  # cached: copy before drawing on it
    return page


@functools.lru_cache(maxsize=8)
def facade_texture(width: int = 480, height: int = 360, floors: int = 4, bays: int = 6) -> np.ndarray:
    """A building facade: brick-coloured wall, a grid of windows, a door. (h, w, 3) uint8."""
    import cv2

    wall = np.empty((height, width, 3), np.uint8)
    wall[:] = (178, 102, 76)
    for r in range(0, height, 12):  # brick courses
        cv2.line(wall, (0, r), (width - 1, r), (150, 86, 64), 1)
    cw, ch = width / bays, height / (floors + 0.4)
    for f in range(floors):
        for b in range(bays):
            x0, y0 = int(b * cw + 0.25 * cw), int(0.3 * ch + f * ch)
            x1, y1 = int(x0 + 0.5 * cw), int(y0 + 0.6 * ch)
            if f == floors - 1 and b == bays // 2:
                continue
            cv2.rectangle(wall, (x0, y0), (x1, y1), (235, 235, 225), -1)
            cv2.rectangle(wall, (x0 + 3, y0 + 3), (x1 - 3, y1 - 3), (70, 110, 150), -1)
            cv2.line(wall, ((x0 + x1) // 2, y0), ((x0 + x1) // 2, y1), (235, 235, 225), 2)
    b = bays // 2
    x0, x1 = int(b * cw + 0.25 * cw), int(b * cw + 0.75 * cw)
    cv2.rectangle(wall, (x0, int(height - 0.85 * ch)), (x1, height - 1), (90, 60, 40), -1)
    wall.flags.writeable = False  # cached: copy before drawing on it
    return wall


@functools.lru_cache(maxsize=8)
def painting_texture(width: int = 400) -> np.ndarray:
    """A framed painting: matplotlib's bundled Grace Hopper portrait inside a gold frame.

    Falls back to a drawn landscape if the sample image is unavailable. (h, w, 3) uint8.
    """
    import cv2

    try:
        import matplotlib.cbook as cbook
        import matplotlib.image as mpimg

        with cbook.get_sample_data("grace_hopper.jpg") as f:
            art = mpimg.imread(f)[..., :3]
        art = np.asarray(art)
        if art.dtype != np.uint8:
            art = (np.clip(art, 0, 1) * 255).astype(np.uint8)
    except Exception:  # pragma: no cover - matplotlib always ships the sample
        art = np.zeros((600, 512, 3), np.uint8)
        art[:300] = (120, 170, 230)
        art[300:] = (60, 140, 70)
        cv2.circle(art, (380, 120), 50, (250, 220, 80), -1)
    scale = (width - 40) / art.shape[1]
    art = cv2.resize(art, (width - 40, int(round(art.shape[0] * scale))), interpolation=cv2.INTER_AREA)
    frame = np.empty((art.shape[0] + 40, width, 3), np.uint8)
    frame[:] = (170, 130, 50)
    cv2.rectangle(frame, (6, 6), (width - 7, frame.shape[0] - 7), (210, 170, 80), 4)
    frame[20:-20, 20:-20] = art
    frame.flags.writeable = False  # cached: copy before drawing on it
    return frame


@functools.lru_cache(maxsize=4)
def desk_background(h: int = 480, w: int = 640, seed: int = 0) -> np.ndarray:
    """A dark wooden-desk background (cached: demos re-photograph on every slider move)."""
    rng = np.random.default_rng(seed)
    yy, xx = np.mgrid[0:h, 0:w]
    base = 70 + 25 * np.sin(xx / 37.0) * np.cos(yy / 53.0) + rng.normal(0, 4, (h, w))
    bg = np.clip(np.stack([base * 0.9, base * 0.75, base * 0.6], axis=-1), 0, 255).astype(np.uint8)
    bg.flags.writeable = False
    return bg


class PlanePhoto(NamedTuple):
    """A synthetic photo of a flat rectangle with its ground truth.

    Attributes
    ----------
    image : (h, w, 3) uint8 ndarray
        The photo.
    corners : (4, 2) ndarray
        True image positions of the rectangle's corners, TL, TR, BR, BL.
    aspect : float
        True width / height of the rectangle.
    H : (3, 3) ndarray
        image_from_texture: maps texture pixels into the photo.
    K : (3, 3) ndarray
        The camera intrinsics used (focal length ``K[0, 0]`` pixels).
    """

    image: np.ndarray
    corners: np.ndarray
    aspect: float
    H: np.ndarray
    K: np.ndarray


def look_at_plane(yaw: float, pitch: float, roll: float = 0.0) -> np.ndarray:
    """Rotation cam_from_plane turning a plane about its own centre: yaw about the
    vertical (v) axis, pitch about the horizontal (u) axis, roll about the view axis,
    in radians. With all angles 0 the plane faces the camera squarely."""
    cy, sy = np.cos(yaw), np.sin(yaw)
    cp, sp = np.cos(pitch), np.sin(pitch)
    cr, sr = np.cos(roll), np.sin(roll)
    Ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    Rx = np.array([[1, 0, 0], [0, cp, -sp], [0, sp, cp]])
    Rz = np.array([[cr, -sr, 0], [sr, cr, 0], [0, 0, 1]])
    return Rz @ Rx @ Ry


def photograph_plane(
    texture: ArrayLike,
    *,
    yaw: float = 0.5,
    pitch: float = 0.3,
    roll: float = 0.0,
    distance: float = 2.2,
    width_m: float = 1.0,
    offset: ArrayLike = (0.0, 0.0),
    focal: float = 800.0,
    image_shape: tuple[int, int] = (480, 640),
    background: ArrayLike | None = None,
    seed: int = 0,
    method: str = "cv2",
) -> PlanePhoto:
    r"""Photograph a flat textured rectangle at an angle: a plane-induced homography.

    The texture is a rectangle ``width_m`` metres wide (its height follows from the
    texture's pixel aspect), centred on the optical axis at ``distance`` metres (plus
    ``offset`` metres in x and y), turned by :func:`look_at_plane`. The camera is
    :math:`K = [[f, 0, c_x], [0, f, c_y], [0, 0, 1]]`; a plane point (X, Y, 0) projects by
    :func:`camlab.homography.pose_homography`, and a texture pixel (u, v) is the plane
    point :math:`s (u - (W-1)/2,\ v - (H-1)/2)` with :math:`s` = metres per texture
    pixel. The photo is the texture warped by the product onto a background.

    Returns
    -------
    PlanePhoto
        ``image``, true ``corners``, true ``aspect``, ``H`` (image_from_texture), ``K``.
    """
    tex = np.asarray(texture)
    if tex.ndim != 3 or tex.shape[2] != 3:
        raise CamlabInputError(f"texture: expected an (H, W, 3) RGB image, got shape {tex.shape}")
    th, tw = tex.shape[:2]
    h, w = image_shape
    K = np.array([[focal, 0, (w - 1) / 2], [0, focal, (h - 1) / 2], [0, 0, 1.0]])
    R = look_at_plane(yaw, pitch, roll)
    off = np.asarray(offset, dtype=float)
    t = np.array([off[0], off[1], check_positive(distance, "distance", "metres")])
    s = check_positive(width_m, "width_m", "metres") / tw
    S = np.array([[s, 0, -s * (tw - 1) / 2], [0, s, -s * (th - 1) / 2], [0, 0, 1]])
    H = pose_homography(K, R, t) @ S
    H = H / H[2, 2]
    corners_tex = np.array([[0, 0], [tw - 1, 0], [tw - 1, th - 1], [0, th - 1]], dtype=float)
    corners = map_points(H, corners_tex)
    if background is None:
        bg = desk_background(h, w, seed)
    else:
        bg = np.asarray(background, dtype=np.uint8)
    if method == "cv2":
        import cv2

        # Warp straight onto a copy of the background: BORDER_TRANSPARENT leaves the
        # pixels outside the texture untouched (one call, fast enough for live demos).
        image = np.array(bg, dtype=np.uint8, copy=True)
        cv2.warpPerspective(np.ascontiguousarray(tex, dtype=np.uint8), H, (w, h), dst=image,
                            flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_TRANSPARENT)
    else:
        photo = warp_perspective(tex, H, (h, w), method=method)
        mask = warp_perspective(np.full((th, tw), 255, np.uint8), H, (h, w), method=method).astype(np.float32) / 255
        out = photo.astype(np.float32) + bg.astype(np.float32) * (1 - mask[..., None])
        image = np.clip(out, 0, 255).astype(np.uint8)
    # The corners are the centres of the texture's corner pixels: (tw - 1) x (th - 1) apart.
    return PlanePhoto(image, corners, (tw - 1) / (th - 1), H, K)


_SCENES = {
    "page": dict(yaw=0.45, pitch=0.35, roll=0.1, distance=2.2, width_m=0.75),
    "painting": dict(yaw=-0.6, pitch=0.1, roll=0.0, distance=2.4, width_m=0.8),
    "facade": dict(yaw=0.2, pitch=-0.5, roll=0.0, distance=1.8, width_m=1.0),
}


def sample_photo(kind: str = "page", **pose) -> PlanePhoto:
    """A ready-made synthetic photo for lesson 10: ``"page"``, ``"painting"`` or ``"facade"``.

    Keyword arguments override the scene's pose (see :func:`photograph_plane`).

    >>> p = sample_photo("page")
    >>> p.image.shape, round(p.aspect, 3)
    ((480, 640, 3), 0.707)
    """
    if kind not in _SCENES:
        raise CamlabInputError(f"kind: expected one of {sorted(_SCENES)}, got {kind!r}")
    texture = {"page": page_texture, "painting": painting_texture, "facade": facade_texture}[kind]()
    return photograph_plane(texture, **{**_SCENES[kind], **pose})
