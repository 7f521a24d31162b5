r"""Calibrated rectification: Fusiello, Trucco & Verri's algorithm [1]_, Bouguet's in OpenCV [2]_.

Turn both cameras about their centres to a common orientation along the baseline, give them the same
intrinsics, and warp the images (and points) accordingly.

References
----------
.. [1] A. Fusiello, E. Trucco and A. Verri, 2000, "A compact algorithm for rectification of stereo
   pairs", *Machine Vision and Applications* 12(1), 16-22.
.. [2] G. Bradski and A. Kaehler, 2008, *Learning OpenCV*, chapter 12 (Bouguet's stereo
   rectification, ``cv2.stereoRectify``).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, DegenerateError, as_points, check_size
from ..camera import Camera, intrinsic_matrix
from ..distortion import DistortionMaps, distort_points, undistort_pixels
from .uncalibrated import UncalibratedRectification

__all__ = [
    "RectifiedImages",
    "CalibratedRectification",
    "rectify_calibrated",
    "rectify_images",
    "rectify_points",
    "unrectify_points",
    "rectification_coverage",
]


class CalibratedRectification(NamedTuple):
    r"""Everything :func:`rectify_calibrated` computed.

    Attributes
    ----------
    R1, R2 : (3, 3) ndarray
        Rectifying rotations, camera i's frame to rectified camera i's frame (as
        ``cv2.stereoRectify``'s R1, R2): :math:`X_{rect} = R_i X_{cam\,i}`.
    P1, P2 : (3, 4) ndarray
        New projection matrices in rectified camera 1's frame (OpenCV's form):
        :math:`P_1 = K_{new} [I \mid 0]`, :math:`P_2 = K_{new} [I \mid (-B, 0, 0)^\top]`.
    Q : (4, 4) ndarray
        Disparity-to-depth matrix: :math:`(X, Y, Z, W)^\top = Q (u, v, d, 1)^\top` in
        rectified camera 1's frame.
    K : (3, 3) ndarray
        The shared intrinsics of both rectified images.
    camera1, camera2 : Camera
        The rectified cameras in the world frame (no distortion): same K, same rotation,
        the original centres.
    baseline : float
        :math:`B = \|C_2 - C_1\|`, metres.
    maps1, maps2 : DistortionMaps
        ``cv2.remap`` tables (float32, (H, W)) taking each original (distorted) image to
        its rectified image.
    image_size : (width, height)
        Size of the rectified images.
    alpha : float
        The border trade-off used (0: no black border, 1: no source pixel lost).
    """

    R1: np.ndarray
    R2: np.ndarray
    P1: np.ndarray
    P2: np.ndarray
    Q: np.ndarray
    K: np.ndarray
    camera1: Camera
    camera2: Camera
    baseline: float
    maps1: DistortionMaps | None
    maps2: DistortionMaps | None
    image_size: tuple[int, int]
    alpha: float


def _border_pixels(size: tuple[int, int], n: int = 24) -> tuple[np.ndarray, list[slice]]:
    """Pixels along the four image edges (top, right, bottom, left), n per edge."""
    w, h = size
    s = np.linspace(0.0, 1.0, n)
    top = np.column_stack([s * (w - 1), np.zeros(n)])
    right = np.column_stack([np.full(n, w - 1.0), s * (h - 1)])
    bottom = np.column_stack([s * (w - 1), np.full(n, h - 1.0)])
    left = np.column_stack([np.zeros(n), s * (h - 1)])
    return np.vstack([top, right, bottom, left]), [slice(k * n, (k + 1) * n) for k in range(4)]


def _rectified_normalised(camera: Camera, R_rect: np.ndarray, pixels: np.ndarray) -> np.ndarray:
    """Distorted pixels of ``camera`` to normalised coordinates (x/z, y/z) in the rectified frame."""
    ideal = undistort_pixels(pixels, camera.K, camera.dist) if any(camera.dist) else pixels
    rays = np.column_stack([ideal, np.ones(len(ideal))]) @ np.linalg.inv(camera.K).T
    r = rays @ R_rect.T
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(r[:, 2:3] > 0, r[:, :2] / r[:, 2:3], np.nan)


def _remap_tables(
    camera: Camera, R_rect: np.ndarray, K_new: np.ndarray, size: tuple[int, int]
) -> DistortionMaps:
    r"""The rectifying maps, in closed form: no iteration needed.

    Output pixel p of the rectified image samples the original image at
    :math:`K\,\mathrm{distort}(\pi(R_{rect}^\top K_{new}^{-1} p))`.
    """
    w, h = size
    u, v = np.meshgrid(np.arange(w, dtype=np.float64), np.arange(h, dtype=np.float64))
    M = R_rect.T @ np.linalg.inv(K_new)  # rectified pixel -> ray in the original camera frame
    x = M[0, 0] * u + M[0, 1] * v + M[0, 2]
    y = M[1, 0] * u + M[1, 1] * v + M[1, 2]
    z = M[2, 0] * u + M[2, 1] * v + M[2, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        bad = z <= 0
        z = np.where(bad, np.nan, z)
        xn = np.column_stack([(x / z).ravel(), (y / z).ravel()])
    if any(camera.dist):
        xn = distort_points(np.nan_to_num(xn, nan=1e3), camera.dist)
    K = camera.K
    mu = (K[0, 0] * xn[:, 0] + K[0, 1] * xn[:, 1] + K[0, 2]).reshape(h, w)
    mv = (K[1, 1] * xn[:, 1] + K[1, 2]).reshape(h, w)
    mu[bad], mv[bad] = -1e4, -1e4  # behind the camera: sample far outside (border value)
    return DistortionMaps(mu.astype(np.float32), mv.astype(np.float32))


def _remap_tables_cv2(
    camera: Camera, R_rect: np.ndarray, K_new: np.ndarray, size: tuple[int, int]
) -> DistortionMaps:
    import cv2

    mu, mv = cv2.initUndistortRectifyMap(
        camera.K, np.array(camera.dist), R_rect, K_new, size, cv2.CV_32FC1
    )
    return DistortionMaps(mu, mv)


def _common_orientation(camera1: Camera, camera2: Camera) -> tuple[np.ndarray, float]:
    """Step 1.

    The rectified cameras' rotation R_new (rows x, y, z in world coordinates: x along the baseline,
    z the mean viewing direction made orthogonal to it) and the baseline B, metres; or a
    DegenerateError for rigs that cannot be rectified.
    """
    base = camera2.centre - camera1.centre
    B = float(np.linalg.norm(base))
    scale = max(np.linalg.norm(camera1.centre), np.linalg.norm(camera2.centre), 1.0)
    if B <= 1e-9 * scale:
        raise DegenerateError(
            "rectify_calibrated: the two cameras have the same centre (baseline 0 m), so there "
            "is no epipolar geometry and nothing to rectify; move one camera"
        )
    xs = camera1.R[0] + camera2.R[0]  # the cameras' mean x axis in world coordinates
    ys = camera1.R[1] + camera2.R[1]
    if abs(base @ xs) < abs(base @ ys):
        raise DegenerateError(
            "rectify_calibrated: the baseline is closer to the cameras' vertical (y) axes than to their x axes; "
            "this function makes rows match for a horizontal rig. Rotate both images by 90 degrees (and the cameras) first"
        )
    if camera1.R[2] @ camera2.R[2] <= 0:
        raise DegenerateError(
            "rectify_calibrated: the cameras look in opposite directions (no common view); "
            "their images cannot be rectified onto one common image plane"
        )
    x = base / B * np.sign(base @ xs)
    z = camera1.R[2] + camera2.R[2]
    z = z - (z @ x) * x
    z /= np.linalg.norm(z)
    y = np.cross(z, x)
    R_new = np.vstack([x, y, z])

    return R_new, B


def _rectified_boxes(*views: tuple[Camera, np.ndarray]) -> tuple[list, list]:
    """Step 2.

    Where the image borders land in rectified normalised coordinates, for each (camera, rotation):
    the intersection of the images' inner boxes and the union of their bounding boxes, as [left,
    top, right, bottom].
    """
    inner = [-np.inf, -np.inf, np.inf, np.inf]  # intersection of the per-image inner boxes
    outer = [np.inf, np.inf, -np.inf, -np.inf]  # union of the images' bounding boxes
    for cam, Rr in views:
        px, edges = _border_pixels(cam.image_size)
        q = _rectified_normalised(cam, Rr, px)
        if not np.all(np.isfinite(q)):
            raise DegenerateError(
                "rectify_calibrated: part of an image would rotate behind the rectified camera "
                "(the cameras are too far from parallel to rectify onto one plane)"
            )
        top, right, bottom, left = (q[e] for e in edges)
        inner = [
            max(inner[0], left[:, 0].max()),
            max(inner[1], top[:, 1].max()),
            min(inner[2], right[:, 0].min()),
            min(inner[3], bottom[:, 1].min()),
        ]
        outer = [
            min(outer[0], q[:, 0].min()),
            min(outer[1], q[:, 1].min()),
            max(outer[2], q[:, 0].max()),
            max(outer[3], q[:, 1].max()),
        ]
    if inner[2] <= inner[0] or inner[3] <= inner[1]:
        raise DegenerateError(
            "rectify_calibrated: the two rectified images have no region in common (no overlap); "
            "the cameras do not see a common part of the scene"
        )
    return inner, outer


def _shared_intrinsics(inner: list, outer: list, size: tuple[int, int], alpha: float) -> np.ndarray:
    """Step 3.

    The one K of both rectified images: alpha = 0 fills the image with the region both images cover
    (no black border), alpha = 1 keeps every pixel of both.
    """
    w, h = size
    f_in = max((w - 1) / (inner[2] - inner[0]), (h - 1) / (inner[3] - inner[1]))
    f_out = min((w - 1) / (outer[2] - outer[0]), (h - 1) / (outer[3] - outer[1]))
    f = (1 - alpha) * f_in + alpha * f_out
    mid = (1 - alpha) * np.array([inner[0] + inner[2], inner[1] + inner[3]]) / 2 + alpha * np.array(
        [outer[0] + outer[2], outer[1] + outer[3]]
    ) / 2
    cx, cy = (w - 1) / 2 - f * mid[0], (h - 1) / 2 - f * mid[1]
    return intrinsic_matrix(f, f, cx, cy)


def rectify_calibrated(
    camera1: Camera,
    camera2: Camera,
    alpha: float = 0.0,
    image_size: tuple[int, int] | None = None,
    maps: bool = True,
    method: str = "numpy",
) -> CalibratedRectification:
    r"""Rectify a calibrated stereo pair: rotate both cameras so the baseline is their x axis.

    Algorithm (Fusiello, Trucco & Verri [1]_, with Bouguet's choice of orientation [2]_):

    1. The new x axis is the baseline :math:`C_2 - C_1` (flipped if needed so it points
       along the cameras' own x axes, so images are not turned upside down).
    2. The new z axis is the mean of the two optical axes made orthogonal to x (the
       half-way orientation: both images rotate by about the same small angle, which
       keeps distortion low); :math:`y = z \times x`.
    3. Both rectified cameras get this rotation :math:`R_{new}` (rows x, y, z) and the same
       intrinsics :math:`K_{new}`, so a world point has the same row in both:
       :math:`v = f\,Y/Z + c_y` with the same Y and Z (the centres differ only along x).
       The rectifying rotation of camera i is :math:`R_i^{rect} = R_{new} R_i^\top`, and
       image i is warped by :math:`K_{new} R_i^{rect} K_i^{-1}` after undistortion.
    4. :math:`K_{new}` (square pixels, the same principal point in both images, zero
       disparity at infinity) is chosen from where the original image borders land:
       ``alpha = 0`` zooms in until every rectified pixel has a source (no black border,
       some source pixels lost); ``alpha = 1`` zooms out until no source pixel is lost
       (black borders); in between, the focal length and centre interpolate linearly,
       as ``cv2.stereoRectify`` does.

    Parameters
    ----------
    camera1, camera2 : Camera
        The left and right cameras (K, R, t cam_from_world, dist); camera 2 should be
        displaced mostly along camera 1's x axis (a horizontal rig).
    alpha : float
        Border trade-off in [0, 1] (see step 4).
    image_size : (width, height) or None
        Size of the rectified images; default camera1.image_size.
    maps : bool
        Compute the remap tables; ``False`` for the geometry only.
    method : {"numpy", "cv2"}
        How to build the remap tables: camlab's readable numpy (:func:`_remap_tables`) or
        ``cv2.initUndistortRectifyMap`` with the same R and K (faster; same tables to
        float32 precision, which a test checks).

    Returns
    -------
    CalibratedRectification
        ``R1``, ``R2`` (the rectifying rotations), ``P1``, ``P2`` (the new projection
        matrices), ``Q`` (disparity to depth), ``K`` (the shared intrinsics), ``camera1``,
        ``camera2`` (the rectified cameras), ``baseline`` (metres), ``maps1``, ``maps2``
        (the remap tables, None with ``maps=False``), ``image_size`` and ``alpha``.

    Raises
    ------
    CamlabInputError
        A camera that is not a :class:`~camlab.camera.Camera`, ``alpha`` outside [0, 1], an
        unknown ``method`` or a bad ``image_size``.
    DegenerateError
        The cameras share a centre (no baseline), or the baseline is closer to the
        cameras' y axes than to their x axes (a vertical rig: rotate both images by 90
        degrees first), or they look in opposite directions, or part of an image rotates
        behind the rectified camera, or the rectified images have no region in common.

    References
    ----------
    .. [1] A. Fusiello, E. Trucco and A. Verri, 2000, "A compact algorithm for rectification
       of stereo pairs", *Machine Vision and Applications* 12(1), 16-22.
    .. [2] G. Bradski and A. Kaehler, 2008, *Learning OpenCV*, chapter 12 (Bouguet's stereo
       rectification, ``cv2.stereoRectify``).
    .. [3] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022, section
       12.1.1 (rectification).
    """
    for c, n in ((camera1, "camera1"), (camera2, "camera2")):
        if not isinstance(c, Camera):
            raise CamlabInputError(f"{n}: expected a camlab.camera.Camera, got {type(c).__name__}")
    if not 0.0 <= float(alpha) <= 1.0:
        raise CamlabInputError(
            f"alpha: expected a number in [0, 1] (0 = no black border, 1 = keep all pixels), got {alpha!r}"
        )
    alpha = float(alpha)
    if method not in ("numpy", "cv2"):
        raise CamlabInputError(f"method: expected 'numpy' or 'cv2', got {method!r}")
    size = check_size(camera1.image_size if image_size is None else image_size, "image_size")
    R_new, B = _common_orientation(camera1, camera2)
    R1, R2 = R_new @ camera1.R.T, R_new @ camera2.R.T
    K = _shared_intrinsics(*_rectified_boxes((camera1, R1), (camera2, R2)), size, alpha)
    f, cx, cy = K[0, 0], K[0, 2], K[1, 2]
    P1 = K @ np.eye(3, 4)
    P2 = K @ np.column_stack([np.eye(3), [-B, 0.0, 0.0]])
    Q = np.array([[1, 0, 0, -cx], [0, 1, 0, -cy], [0, 0, 0, f], [0, 0, 1 / B, 0]], dtype=float)
    cam1 = Camera(K, R_new, -R_new @ camera1.centre, image_size=size)
    cam2 = Camera(K, R_new, -R_new @ camera2.centre, image_size=size)
    build = _remap_tables if method == "numpy" else _remap_tables_cv2
    m1 = build(camera1, R1, K, size) if maps else None
    m2 = build(camera2, R2, K, size) if maps else None
    return CalibratedRectification(R1, R2, P1, P2, Q, K, cam1, cam2, B, m1, m2, size, alpha)


def _rotation_of(rect: CalibratedRectification, which: int) -> np.ndarray:
    """R1 for ``which`` = 1 (the left camera), R2 for 2; a clear error for anything else."""
    if which not in (1, 2):
        raise CamlabInputError(
            f"which: expected 1 or 2 (the camera the pixels belong to), got {which!r}"
        )
    return rect.R1 if which == 1 else rect.R2


def rectify_points(
    rect: CalibratedRectification, camera: Camera, pixels: ArrayLike, which: int
) -> np.ndarray:
    """Original (distorted) pixels of ``camera`` to pixels in rectified image ``which`` (1 or 2).

    Undistorts (iteratively), rotates by R1 or R2 and projects with the new K. NaN for
    points that rotate behind the rectified camera.

    Parameters
    ----------
    rect : CalibratedRectification
        The rectification (:func:`rectify_calibrated`).
    camera : Camera
        The original camera the pixels belong to (its K and distortion are used).
    pixels : (N, 2) or (2,) array_like
        Original pixels (u, v).
    which : int
        1 for the left camera (R1), 2 for the right (R2).

    Returns
    -------
    (N, 2) or (2,) ndarray
        The rectified pixels, the shape of ``pixels``; NaN behind the rectified camera.

    Raises
    ------
    CamlabInputError
        ``which`` not 1 or 2, or ``pixels`` not 2-D points.
    """
    R = _rotation_of(rect, which)
    p = as_points(pixels, 2, "pixels")
    q = _rectified_normalised(camera, R, p.array)
    return p.restore(q @ rect.K[:2, :2].T + rect.K[:2, 2])


def unrectify_points(
    rect: CalibratedRectification, camera: Camera, pixels: ArrayLike, which: int
) -> np.ndarray:
    r"""Rectified pixels to the original (distorted) pixels of ``camera``: :func:`rectify_points` inverted.

    :math:`p \mapsto K\,\mathrm{distort}(\pi(R_i^\top K_{new}^{-1} \tilde p))`, exactly what the
    remap tables store. Use it to carry true matches from the rectified pair (e.g. from
    the true disparity) back to the raw images.

    Parameters
    ----------
    rect : CalibratedRectification
        The rectification (:func:`rectify_calibrated`).
    camera : Camera
        The original camera (its K and distortion are applied).
    pixels : (N, 2) or (2,) array_like
        Rectified pixels (u, v).
    which : int
        1 for the left camera (R1), 2 for the right (R2).

    Returns
    -------
    (N, 2) or (2,) ndarray
        The original pixels, the shape of ``pixels``; NaN for rays behind the camera.

    Raises
    ------
    CamlabInputError
        ``which`` not 1 or 2, or ``pixels`` not 2-D points.
    """
    R = _rotation_of(rect, which)
    p = as_points(pixels, 2, "pixels")
    rays = np.column_stack([p.array, np.ones(len(p.array))]) @ np.linalg.inv(rect.K).T @ R
    with np.errstate(divide="ignore", invalid="ignore"):
        xn = np.where(rays[:, 2:3] > 0, rays[:, :2] / rays[:, 2:3], np.nan)
    if any(camera.dist):
        ok = np.all(np.isfinite(xn), axis=1)
        xn[ok] = distort_points(xn[ok], camera.dist)
    return p.restore(xn @ camera.K[:2, :2].T + camera.K[:2, 2])


class RectifiedImages(NamedTuple):
    """The rectified pair :func:`rectify_images` warps (pixels without a source are 0).

    Attributes
    ----------
    image1, image2 : ndarray
        The left and right images on the rectified grid, dtype and channels as given.
    """

    image1: np.ndarray
    image2: np.ndarray


def rectify_images(
    rect: CalibratedRectification | UncalibratedRectification,
    image1: np.ndarray,
    image2: np.ndarray,
    interpolation: str = "bilinear",
) -> RectifiedImages:
    """Warp both original images into the rectified pair with ``cv2.remap`` / ``cv2.warpPerspective``.

    Images are (H, W) or (H, W, C) arrays indexed ``img[v, u]``; pixels without a source
    are 0 (the black border). A calibrated ``rect`` takes the raw (distorted) images: its
    remap tables undistort too. An uncalibrated ``rect`` applies H1, H2 as they are, so pass
    images that are already undistorted (F, and so H1, H2, relate ideal pixels).

    Parameters
    ----------
    rect : CalibratedRectification or UncalibratedRectification
        From :func:`rectify_calibrated` (with ``maps=True``) or :func:`rectify_uncalibrated`.
    image1, image2 : (H, W) or (H, W, C) ndarray
        The left and right images.
    interpolation : {"bilinear", "nearest"}
        How to sample the source images.

    Returns
    -------
    RectifiedImages
        ``image1``, ``image2`` on the rectified grid (``rect.image_size``), dtype and
        channels as given.

    Raises
    ------
    CamlabInputError
        An unknown ``interpolation``, an empty or wrongly shaped image, a calibrated ``rect``
        without remap tables, or a ``rect`` of another type.
    """
    import cv2

    flags = {"bilinear": cv2.INTER_LINEAR, "nearest": cv2.INTER_NEAREST}.get(interpolation)
    if flags is None:
        raise CamlabInputError(
            f"interpolation: expected 'bilinear' or 'nearest', got {interpolation!r}"
        )
    out = []
    for img, n in ((image1, "image1"), (image2, "image2")):
        a = np.asarray(img)
        if a.ndim not in (2, 3) or a.size == 0:
            raise CamlabInputError(
                f"{n}: expected an (H, W) or (H, W, C) image, got shape {a.shape}"
            )
        out.append(a)
    if isinstance(rect, CalibratedRectification):
        if rect.maps1 is None:
            raise CamlabInputError(
                "rect: has no remap tables; call rectify_calibrated(..., maps=True)"
            )
        return RectifiedImages(
            *(
                cv2.remap(a, m.map_u, m.map_v, flags, borderMode=cv2.BORDER_CONSTANT)
                for a, m in ((out[0], rect.maps1), (out[1], rect.maps2))
            )
        )
    if isinstance(rect, UncalibratedRectification):
        return RectifiedImages(
            *(
                cv2.warpPerspective(
                    a, H, rect.image_size, flags=flags, borderMode=cv2.BORDER_CONSTANT
                )
                for a, H in ((out[0], rect.H1), (out[1], rect.H2))
            )
        )
    raise CamlabInputError(
        f"rect: expected a rectify_calibrated or rectify_uncalibrated result, got {type(rect).__name__}"
    )


def rectification_coverage(
    rect: CalibratedRectification, camera1: Camera, camera2: Camera, step: int = 8
) -> dict[str, float]:
    """The border / lost-pixel trade-off of a calibrated rectification, as fractions in [0, 1].

    Parameters
    ----------
    rect : CalibratedRectification
        From :func:`rectify_calibrated` with ``maps=True``.
    camera1, camera2 : Camera
        The original cameras (their image sizes bound the source images).
    step : int
        Grid spacing, pixels: both measures sample every ``step``-th pixel.

    Returns
    -------
    dict of str to float
        ``valid1``, ``valid2``: share of rectified pixels that have a source pixel (1 - black
        border); ``kept1``, ``kept2``: share of source pixels that land inside the rectified
        image (1 - lost pixels).

    Raises
    ------
    CamlabInputError
        ``rect`` has no remap tables.
    """
    if rect.maps1 is None:
        raise CamlabInputError("rect: has no remap tables; call rectify_calibrated(..., maps=True)")
    out = {}
    w, h = rect.image_size
    for k, (cam, m, which) in enumerate(
        ((camera1, rect.maps1, 1), (camera2, rect.maps2, 2)), start=1
    ):
        cw, ch = cam.image_size
        mu, mv = m.map_u[::step, ::step], m.map_v[::step, ::step]
        out[f"valid{k}"] = float(
            np.mean((mu >= -0.5) & (mu <= cw - 0.5) & (mv >= -0.5) & (mv <= ch - 0.5))
        )
        gu, gv = np.meshgrid(
            np.arange(0, cw, step, dtype=float), np.arange(0, ch, step, dtype=float)
        )
        q = rectify_points(rect, cam, np.column_stack([gu.ravel(), gv.ravel()]), which)
        out[f"kept{k}"] = float(
            np.mean(
                (q[:, 0] >= -0.5) & (q[:, 0] <= w - 0.5) & (q[:, 1] >= -0.5) & (q[:, 1] <= h - 0.5)
            )
        )
    return out
