r"""Stereo rectification: warp two views so that epipolar lines become the same image rows.

After rectification a world point appears in both images on the same row, at columns
:math:`u_1` and :math:`u_2`; the *disparity* :math:`d = u_1 - u_2` gives its depth
:math:`Z = f B / d` (focal length f in pixels, baseline B in metres). Matching becomes a
1-D search along rows.

Two routes, both warping each image by a homography (plus undistortion):

* **calibrated** (:func:`rectify_calibrated`, Fusiello, Trucco & Verri 2000; Bouguet's
  method in OpenCV): with both cameras known, rotate both about their centres to a common
  orientation whose x axis is the baseline, and give both the same intrinsics. A rotation
  about the centre is the homography :math:`K_{new} R_{rect} K^{-1}`.
* **uncalibrated** (:func:`rectify_uncalibrated`, Hartley 1999, H&Z section 11.12): only
  F and matches are known. Send image 2's epipole to infinity along x with a homography
  :math:`H_2` close to a rigid motion near the image centre, then choose :math:`H_1`
  compatible with F that minimises the horizontal disparity of the matches; finally shear
  (Loop & Zhang 1999) and scale both to reduce distortion.

:func:`vertical_disparity` measures how well a pair is rectified.

Conventions (docs/conventions.md): pixels (u, v) = (column, row), origin at the centre of
the top-left pixel, ``img[v, u]``; cameras are :class:`camlab.camera.Camera` with
cam_from_world poses; ``dist = (k1, k2, p1, p2, k3)``; metres; remap tables follow
``cv2.remap``: output pixel (u, v) samples the source at ``(map_u[v, u], map_v[v, u])``.
See lesson 11.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._validate import CamlabInputError, DegenerateError, as_point_pairs, as_points, check_size
from .camera import Camera, CameraPair, intrinsic_matrix, rotation_z
from .distortion import DistortionMaps, distort_points, undistort_pixels
from .epipolar import EIGHT_POINT_REASON, check_fundamental, epipoles, sampson_distance, skew
from .homography import compose
from .projective import map_points

__all__ = [
    "RectifiedImages",
    "CalibratedRectification",
    "UncalibratedRectification",
    "VerticalDisparity",
    "rectify_calibrated",
    "rectify_images",
    "rectify_points",
    "unrectify_points",
    "rectification_coverage",
    "StereoCalibration",
    "rectify_uncalibrated",
    "stereo_calibrate",
    "vertical_disparity",
]

_FIT_PX = 3.0  # Sampson distance (pixels) within which a pair counts as consistent with F


# --------------------------------------------------------------------------- measuring


class VerticalDisparity(NamedTuple):
    """Vertical disparity :math:`|v_1 - v_2|` of corresponding points, pixels.

    ``median``, ``p95`` (95th percentile), ``max``, and ``values`` (N,) per pair.
    """

    median: float
    p95: float
    max: float
    values: np.ndarray


def vertical_disparity(x1: ArrayLike, x2: ArrayLike) -> VerticalDisparity:
    r"""How well a pair is rectified: :math:`|v_1 - v_2|` for corresponding pixels (u, v).

    In a perfectly rectified pair every match lies on the same row, so all values are 0.
    Pass the *rectified* pixels of true correspondences (e.g. from :func:`rectify_points`).
    Pairs with a non-finite coordinate are ignored.

    >>> vertical_disparity([[10, 5], [20, 7]], [[3, 5.5], [1, 7]]).median
    0.25
    """
    a, b = _finite_pairs(x1, x2)
    if len(a) == 0:
        raise CamlabInputError("x1, x2: no pair has finite coordinates; nothing to measure")
    d = np.abs(a[:, 1] - b[:, 1])
    return VerticalDisparity(float(np.median(d)), float(np.percentile(d, 95)), float(d.max()), d)


def _finite_pairs(x1: ArrayLike, x2: ArrayLike):
    p1, p2, _ = as_point_pairs(x1, x2, finite=False)
    ok = np.all(np.isfinite(p1), axis=1) & np.all(np.isfinite(p2), axis=1)
    return p1[ok], p2[ok]


# --------------------------------------------------------------------------- calibrated


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
    r"""Output pixel p of the rectified image samples the original image at
    :math:`K\,\mathrm{distort}(\pi(R_{rect}^\top K_{new}^{-1} p))`: no iteration needed."""
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


def rectify_calibrated(
    camera1: Camera,
    camera2: Camera,
    alpha: float = 0.0,
    image_size: tuple[int, int] | None = None,
    maps: bool = True,
    method: str = "numpy",
) -> CalibratedRectification:
    r"""Rectify a calibrated stereo pair: rotate both cameras so the baseline is their x axis.

    Algorithm (Fusiello, Trucco & Verri 2000, with Bouguet's choice of orientation):

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

    Raises
    ------
    DegenerateError
        The cameras share a centre (no baseline), or the baseline is closer to the
        cameras' y axes than to their x axes (a vertical rig: rotate both images by 90
        degrees first), or they look in opposite directions.
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
    R1, R2 = R_new @ camera1.R.T, R_new @ camera2.R.T

    # Where the image borders land, in rectified normalised coordinates.
    w, h = size
    inner = [-np.inf, -np.inf, np.inf, np.inf]  # intersection of the per-image inner boxes
    outer = [np.inf, np.inf, -np.inf, -np.inf]  # union of the images' bounding boxes
    for cam, Rr in ((camera1, R1), (camera2, R2)):
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
    f_in = max((w - 1) / (inner[2] - inner[0]), (h - 1) / (inner[3] - inner[1]))
    f_out = min((w - 1) / (outer[2] - outer[0]), (h - 1) / (outer[3] - outer[1]))
    f = (1 - alpha) * f_in + alpha * f_out
    mid = (1 - alpha) * np.array([inner[0] + inner[2], inner[1] + inner[3]]) / 2 + alpha * np.array(
        [outer[0] + outer[2], outer[1] + outer[3]]
    ) / 2
    cx, cy = (w - 1) / 2 - f * mid[0], (h - 1) / 2 - f * mid[1]
    K = intrinsic_matrix(f, f, cx, cy)
    P1 = K @ np.eye(3, 4)
    P2 = K @ np.column_stack([np.eye(3), [-B, 0.0, 0.0]])
    Q = np.array([[1, 0, 0, -cx], [0, 1, 0, -cy], [0, 0, 0, f], [0, 0, 1 / B, 0]], dtype=float)
    cam1 = Camera(K, R_new, -R_new @ camera1.centre, image_size=size)
    cam2 = Camera(K, R_new, -R_new @ camera2.centre, image_size=size)
    build = _remap_tables if method == "numpy" else _remap_tables_cv2
    m1 = build(camera1, R1, K, size) if maps else None
    m2 = build(camera2, R2, K, size) if maps else None
    return CalibratedRectification(R1, R2, P1, P2, Q, K, cam1, cam2, B, m1, m2, size, alpha)


def rectify_points(
    rect: CalibratedRectification, camera: Camera, pixels: ArrayLike, which: int
) -> np.ndarray:
    """Original (distorted) pixels of ``camera`` to pixels in rectified image ``which`` (1 or 2).

    Undistorts (iteratively), rotates by R1 or R2 and projects with the new K. NaN for
    points that rotate behind the rectified camera.
    """
    if which not in (1, 2):
        raise CamlabInputError(
            f"which: expected 1 or 2 (the camera the pixels belong to), got {which!r}"
        )
    p = as_points(pixels, 2, "pixels")
    q = _rectified_normalised(camera, rect.R1 if which == 1 else rect.R2, p.array)
    return p.restore(q @ rect.K[:2, :2].T + rect.K[:2, 2])


def unrectify_points(
    rect: CalibratedRectification, camera: Camera, pixels: ArrayLike, which: int
) -> np.ndarray:
    r"""The inverse of :func:`rectify_points`: rectified pixels to original (distorted) pixels of ``camera``.

    :math:`p \mapsto K\,\mathrm{distort}(\pi(R_i^\top K_{new}^{-1} \tilde p))`, exactly what the
    remap tables store. Use it to carry true matches from the rectified pair (e.g. from
    the true disparity) back to the raw images.
    """
    if which not in (1, 2):
        raise CamlabInputError(
            f"which: expected 1 or 2 (the camera the pixels belong to), got {which!r}"
        )
    p = as_points(pixels, 2, "pixels")
    rays = (
        np.column_stack([p.array, np.ones(len(p.array))])
        @ np.linalg.inv(rect.K).T
        @ (rect.R1 if which == 1 else rect.R2)
    )
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

    ``valid1``, ``valid2``: share of rectified pixels that have a source pixel (1 - black
    border); ``kept1``, ``kept2``: share of source pixels that land inside the rectified
    image (1 - lost pixels). Measured on a grid every ``step`` pixels.
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


# --------------------------------------------------------------------------- uncalibrated


class UncalibratedRectification(NamedTuple):
    """What :func:`rectify_uncalibrated` computed: ``H1``, ``H2`` (3, 3) homographies taking
    image i's pixels to rectified image i's pixels, and the output ``image_size``."""

    H1: np.ndarray
    H2: np.ndarray
    image_size: tuple[int, int]


def _shear_to_reduce_distortion(H: np.ndarray, size: tuple[int, int]) -> np.ndarray:
    r"""Loop & Zhang's shear :math:`S = [[k_1, k_2, 0], [0, 1, 0], [0, 0, 1]]` applied after H.

    It changes only u (rows stay rows) and makes the images of the two lines joining
    opposite edge midpoints perpendicular again, with their original length ratio.
    """
    w, h = size
    mids = np.array(
        [[(w - 1) / 2, 0], [w - 1, (h - 1) / 2], [(w - 1) / 2, h - 1], [0, (h - 1) / 2]],
        dtype=float,
    )
    a, b, c, d = map_points(H, mids)
    xu, xv = b - d
    yu, yv = c - a
    den = h * w * (xu * yv - xv * yu)
    if abs(den) < 1e-12:
        return np.eye(3)
    k1 = (h * h * xv * xv + w * w * yv * yv) / den
    k2 = (h * h * xu * xv + w * w * yu * yv) / -den
    if k1 < 0:
        k1, k2 = -k1, -k2
    return np.array([[k1, k2, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])


def rectify_uncalibrated(
    x1: ArrayLike, x2: ArrayLike, F: ArrayLike, image_size: tuple[int, int], shear: bool = True
) -> UncalibratedRectification:
    r"""Rectifying homographies (H1, H2) from F and matches alone (Hartley's method).

    Algorithm (H&Z algorithm 11.9):

    1. **Epipole to infinity.** Translate image 2's centre to the origin (T), rotate the
       epipole :math:`e'` onto the u axis at :math:`(f, 0, 1)` (R, the smaller of the two
       rotations, so the image is not turned upside down), and apply
       :math:`G = \begin{pmatrix}1&0&0\\0&1&0\\-1/f&0&1\end{pmatrix}`, which sends
       :math:`(f, 0, 1)` to the ideal point :math:`(f, 0, 0)`: all epipolar lines become
       horizontal. :math:`H_2 = G R T` is close to a rigid motion near the image centre.
       An epipole already at infinity needs only the rotation.
    2. **Matching transform.** Any :math:`H_1` with :math:`H_2^{-\top} F H_1^{-1} \sim [i]_\times`
       (the F of a rectified pair) maps epipolar lines to the same rows. With
       :math:`F = [e']_\times M`, :math:`M = [e']_\times F + e' v^\top` (invertible), these are
       :math:`H_1 = H_A H_2 M`, :math:`H_A = \begin{pmatrix}a&b&c\\0&1&0\\0&0&1\end{pmatrix}`.
       Choose a, b, c by linear least squares to minimise
       :math:`\sum_i (a \hat u_i + b \hat v_i + c - \hat u'_i)^2` over the matches
       (:math:`\hat x = H_2 M x`, :math:`\hat x' = H_2 x'`): the horizontal disparities.
    3. **Less distortion.** ``shear``: apply Loop & Zhang's shear to each image (it only
       changes u, so rows stay aligned) to restore right angles and aspect ratio. Then one
       common scale and vertical shift (and a horizontal shift per image) fit both
       rectified images into ``image_size``.

    Parameters
    ----------
    x1, x2 : (N, 2) array_like
        Matches (pixels), N >= 8, ideally the inliers used to estimate F.
    F : (3, 3) array_like
        Fundamental matrix with ``x2_h @ F @ x1_h == 0``.
    image_size : (width, height)
        Size of both input images and of the outputs.
    shear : bool
        Apply the distortion-reducing shear (step 3).

    Returns
    -------
    UncalibratedRectification

    Raises
    ------
    DegenerateError
        The epipole lies inside image 2 (forward motion): no homography sends it to
        infinity without tearing the image; use a polar rectification instead.
    """
    F = check_fundamental(F)
    a, b, _ = as_point_pairs(x1, x2, min_count=8, why=EIGHT_POINT_REASON)
    w, h = check_size(image_size, "image_size")
    fits = sampson_distance(F, a, b) < _FIT_PX
    if fits.mean() < 0.5:  # the row alignment below is a least-squares fit to these pairs
        raise DegenerateError(
            f"x1, x2: only {int(fits.sum())} of {len(a)} pairs lie within {_FIT_PX} px of their epipolar lines "
            f"under F, so the matches are mostly wrong or F belongs to other images; estimate F with "
            f"ransac_fundamental_matrix and pass its inliers"
        )
    e2 = epipoles(F).e2
    centre = np.array([(w - 1) / 2, (h - 1) / 2])
    if abs(e2[2]) > 1e-12 * np.linalg.norm(e2[:2]):
        ep2 = e2[:2] / e2[2]
        if -0.5 <= ep2[0] <= w - 0.5 and -0.5 <= ep2[1] <= h - 0.5:
            raise DegenerateError(
                f"rectify_uncalibrated: the epipole of image 2 is inside the image at ({ep2[0]:.1f}, {ep2[1]:.1f}): "
                f"the camera moved towards the scene, and no homography can make the epipolar lines parallel "
                f"without sending part of the image to infinity"
            )
    T = np.array([[1.0, 0.0, -centre[0]], [0.0, 1.0, -centre[1]], [0.0, 0.0, 1.0]])
    e = T @ e2
    theta = np.arctan2(e[1], e[0])
    theta = (theta + np.pi / 2) % np.pi - np.pi / 2  # the smaller rotation: keep images upright
    Rm = rotation_z(-theta)  # turns the epipole onto the x axis
    e = Rm @ e
    G = np.eye(3)
    if abs(e[2]) > 1e-12 * abs(e[0]):
        G[2, 0] = -e[2] / e[0]  # -1/f with f = e_u / e_w
    H2 = G @ Rm @ T
    M = skew(e2) @ F + np.outer(e2, [1.0, 1.0, 1.0])
    H0 = H2 @ M
    ha, hb = map_points(H0, a), map_points(H2, b)
    A = np.column_stack([ha, np.ones(len(ha))])
    abc, *_ = np.linalg.lstsq(A, hb[:, 0], rcond=None)
    HA = np.array([[abc[0], abc[1], abc[2]], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    H1 = HA @ H0
    if shear:
        H1 = _shear_to_reduce_distortion(H1, (w, h)) @ H1
        H2 = _shear_to_reduce_distortion(H2, (w, h)) @ H2
    # Fit both into the output: one scale and vertical offset for both, a horizontal offset each.
    corners = np.array([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]], dtype=float)
    c1, c2 = map_points(H1, corners), map_points(H2, corners)
    if not (np.all(np.isfinite(c1)) and np.all(np.isfinite(c2))):
        raise DegenerateError(
            "rectify_uncalibrated: an image corner maps to infinity; the epipole is too close to the image"
        )
    vlo, vhi = min(c1[:, 1].min(), c2[:, 1].min()), max(c1[:, 1].max(), c2[:, 1].max())
    ulen = max(np.ptp(c1[:, 0]), np.ptp(c2[:, 0]))
    k = min((w - 1) / ulen, (h - 1) / (vhi - vlo))
    out = []
    for H, cc in ((H1, c1), (H2, c2)):
        S = np.array(
            [
                [k, 0.0, (w - 1) / 2 - k * (cc[:, 0].min() + cc[:, 0].max()) / 2],
                [0.0, k, (h - 1) / 2 - k * (vlo + vhi) / 2],
                [0.0, 0.0, 1.0],
            ]
        )
        out.append(compose(S, H))  # H first, then S
    return UncalibratedRectification(out[0], out[1], (w, h))


# --------------------------------------------------------------------------- stereo calibration


class StereoCalibration(NamedTuple):
    """What :func:`stereo_calibrate` found.

    ``K1, dist1, K2, dist2``: each camera's intrinsics (pixels) and distortion;
    ``R`` (3, 3), ``t`` (3,): camera 2's pose relative to camera 1 (``X_2 = R X_1 + t``,
    metres, the unit of the board); ``rms``: the joint RMS reprojection error over both
    images, pixels (``cv2.stereoCalibrate``'s number); ``rms1``, ``rms2``: each camera's
    single calibration; ``rvecs, tvecs`` (V, 3): the board's pose in camera 1 per view;
    ``iterations``, ``converged``: of the joint LM refinement.
    """

    K1: np.ndarray
    dist1: np.ndarray
    K2: np.ndarray
    dist2: np.ndarray
    R: np.ndarray
    t: np.ndarray
    rms: float
    rms1: float
    rms2: float
    rvecs: np.ndarray
    tvecs: np.ndarray
    iterations: int
    converged: bool

    def cameras(self, image_size: tuple[int, int] = (640, 480)) -> CameraPair:
        """The rig as two :class:`Camera` objects, camera 1 at the world origin."""
        return CameraPair(
            Camera(self.K1, np.eye(3), np.zeros(3), tuple(self.dist1), image_size),
            Camera(self.K2, self.R, self.t, tuple(self.dist2), image_size),
        )


def _g(K: np.ndarray, dist: np.ndarray) -> np.ndarray:
    return np.array([K[0, 0], K[1, 1], K[0, 2], K[1, 2], K[0, 1], *dist], dtype=float)


def stereo_calibrate(
    object_points: ArrayLike,
    image_points1,
    image_points2,
    image_size: tuple[int, int],
    *,
    refine_intrinsics: bool = False,
    max_iter: int = 50,
) -> StereoCalibration:
    r"""Calibrate a two-camera rig from V >= 3 chessboard views seen by both cameras.

    1. Calibrate each camera alone (:func:`camlab.calibration.calibrate_camera`: Zhang's
       closed form, then Levenberg-Marquardt). Each view gives the board's pose in both
       cameras, :math:`(R_{1v}, t_{1v})` and :math:`(R_{2v}, t_{2v})`.
    2. Each view then gives an estimate of the rig, :math:`R_v = R_{2v} R_{1v}^\top`,
       :math:`t_v = t_{2v} - R_v t_{1v}`; start from the rotation nearest to their mean and
       the median translation.
    3. Refine jointly with :func:`camlab.optimize.levenberg_marquardt`: unknowns are the
       rig (R, t) and every board pose in camera 1 (and, with ``refine_intrinsics``, both
       cameras' intrinsics and distortion); residuals are the reprojection errors of every
       corner in *both* images, camera 2 seeing the board at
       :math:`(R R_{1v},\ R t_{1v} + t)`. The rig is then consistent across all views, not
       one per view. The Jacobian is taken by central differences (about 6V + 6 unknowns).

    Parameters
    ----------
    object_points : (N, 3) array_like
        The board's points in its own frame, metres, Z = 0 (the same for every view).
    image_points1, image_points2 : sequence of V (N, 2) array_like
        The detected corners in camera 1 and camera 2, in the same order.
    image_size : (width, height)
        Pixels.
    refine_intrinsics : bool
        Also refine K and distortion of both cameras in the joint step (OpenCV's default
        ``CALIB_FIX_INTRINSIC`` keeps them, like the default False here).

    Returns
    -------
    StereoCalibration
    """
    from . import calibration as cal
    from .calibration.refinement import project_views
    from .camera import axis_angle_from_rotation, rotation_from_axis_angle
    from .optimize import levenberg_marquardt

    X = as_points(object_points, 3, "object_points", min_count=4).array
    views1 = [as_points(p, 2, f"image_points1[{i}]").array for i, p in enumerate(image_points1)]
    views2 = [as_points(p, 2, f"image_points2[{i}]").array for i, p in enumerate(image_points2)]
    if len(views1) != len(views2) or len(views1) < 3:
        raise CamlabInputError(
            f"image_points1, image_points2: expected the same number (>= 3) of views seen by "
            f"both cameras, got {len(views1)} and {len(views2)}"
        )
    for i, (a, b) in enumerate(zip(views1, views2, strict=True)):
        if len(a) != len(X) or len(b) != len(X):
            raise CamlabInputError(
                f"image_points[{i}]: expected {len(X)} corners per view (one per object point), "
                f"got {len(a)} and {len(b)}"
            )
    c1 = cal.calibrate_camera(X, views1, image_size)
    c2 = cal.calibrate_camera(X, views2, image_size)
    Rs = [R2 @ R1.T for R1, R2 in zip(c1.R, c2.R, strict=True)]
    ts = np.array([t2 - Rv @ t1 for Rv, t1, t2 in zip(Rs, c1.tvecs, c2.tvecs, strict=True)])
    R0 = cal.nearest_rotation(np.mean(Rs, axis=0))
    t0 = np.median(ts, axis=0)
    V = len(views1)
    Xv = np.broadcast_to(X, (V,) + X.shape)
    obs = np.concatenate([np.stack(views1), np.stack(views2)])  # (2V, N, 2)

    def unpack(p):
        rig_r, rig_t, poses = p[:3], p[3:6], p[6 : 6 + 6 * V].reshape(V, 6)
        if refine_intrinsics:
            g1, g2 = p[6 + 6 * V : 16 + 6 * V], p[16 + 6 * V :]
        else:
            g1, g2 = _g(c1.K, c1.dist), _g(c2.K, c2.dist)
        return rotation_from_axis_angle(rig_r), rig_t, poses, g1, g2

    def residuals(p):
        Rr, tr, poses, g1, g2 = unpack(p)
        R1 = np.stack([rotation_from_axis_angle(r) for r in poses[:, :3]])
        R2 = Rr @ R1
        poses2 = np.column_stack(
            [[axis_angle_from_rotation(R) for R in R2], poses[:, 3:] @ Rr.T + tr]
        )
        uv = np.concatenate([project_views(g1, poses, Xv), project_views(g2, poses2, Xv)])
        return (uv - obs).ravel()

    def jacobian(p):
        J = np.empty((obs.size, len(p)))
        for k in range(len(p)):
            h = 1e-6 * max(1.0, abs(p[k]))
            e = np.zeros(len(p))
            e[k] = h
            J[:, k] = (residuals(p + e) - residuals(p - e)) / (2 * h)
        return J

    p0 = np.concatenate(
        [axis_angle_from_rotation(R0), t0, np.column_stack([c1.rvecs, c1.tvecs]).ravel()]
    )
    if refine_intrinsics:
        p0 = np.concatenate([p0, _g(c1.K, c1.dist), _g(c2.K, c2.dist)])
    res = levenberg_marquardt(residuals, p0, jacobian, max_iter=max_iter)
    Rr, tr, poses, g1, g2 = unpack(res.x)

    def K_of(g):
        return np.array([[g[0], g[4], g[2]], [0.0, g[1], g[3]], [0.0, 0.0, 1.0]])

    rms = float(np.sqrt(np.sum(res.residuals**2) / (obs.size / 2)))
    return StereoCalibration(
        K_of(g1),
        np.array(g1[5:]),
        K_of(g2),
        np.array(g2[5:]),
        Rr,
        tr,
        rms,
        float(c1.rms),
        float(c2.rms),
        poses[:, :3].copy(),
        poses[:, 3:].copy(),
        int(res.iterations),
        bool(res.converged),
    )
