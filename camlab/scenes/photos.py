"""Photos of a flat rectangle made by one homography, with their ground truth (lesson 10)."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, check_positive
from ..camera import centred_intrinsics, rotation_x, rotation_y, rotation_z
from ..homography import pose_homography
from ..projective import map_points
from ..warp import warp_perspective
from .textures import desk_background, facade_texture, page_texture, painting_texture


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
    """Rotation cam_from_plane turning a plane about its own centre by yaw, pitch and roll (radians).

    Yaw is about the vertical (v) axis, pitch about the horizontal (u) axis, roll about the view
    axis: ``R = Rz(roll) Rx(pitch) Ry(yaw)``. With all angles 0 the plane faces the camera squarely.

    Parameters
    ----------
    yaw, pitch, roll : float
        The turns, radians.

    Returns
    -------
    (3, 3) ndarray
        The rotation cam_from_plane.
    """
    return rotation_z(roll) @ rotation_x(pitch) @ rotation_y(yaw)


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
    pixel. The photo is the texture warped by the product onto a background;
    ``image_shape`` is the photo's (height, width), numpy's order.

    Parameters
    ----------
    texture : (H, W, 3) array_like
        The rectangle's RGB texture (uint8).
    yaw, pitch, roll : float
        The plane's turn, radians (:func:`look_at_plane`).
    distance : float
        Distance of the plane's centre along the optical axis, metres (> 0).
    width_m : float
        The rectangle's width, metres (> 0).
    offset : (2,) array_like
        Shift of the plane's centre in camera x and y, metres.
    focal : float
        Focal length, pixels; the principal point is the image's centre.
    image_shape : (height, width)
        The photo's shape, pixels.
    background : (height, width, 3) array_like or None
        What lies behind the rectangle (uint8); None draws :func:`desk_background` with ``seed``.
    seed : int
        Seed of the default background.
    method : str
        ``"cv2"`` (OpenCV's warp, fast) or a method of :func:`camlab.warp.warp_perspective`.

    Returns
    -------
    PlanePhoto
        ``image``, true ``corners``, true ``aspect``, ``H`` (image_from_texture), ``K``.

    Raises
    ------
    CamlabInputError
        If ``texture`` is not an (H, W, 3) image, or ``distance`` or ``width_m`` is not positive.

    References
    ----------
    .. [1] R. Hartley and A. Zisserman, *Multiple View Geometry in Computer Vision*, 2nd ed.,
       2004, section 8.1.1 (the homography between a world plane and its image).
    """
    tex = np.asarray(texture)
    if tex.ndim != 3 or tex.shape[2] != 3:
        raise CamlabInputError(f"texture: expected an (H, W, 3) RGB image, got shape {tex.shape}")
    th, tw = tex.shape[:2]
    h, w = image_shape
    K = centred_intrinsics(focal, (w, h))
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
        bg = desk_background((h, w), seed)
    else:
        bg = np.asarray(background, dtype=np.uint8)
    if method == "cv2":
        import cv2

        # Warp straight onto a copy of the background: BORDER_TRANSPARENT leaves the
        # pixels outside the texture untouched (one call, fast enough for live demos).
        image = np.array(bg, dtype=np.uint8, copy=True)
        cv2.warpPerspective(
            np.ascontiguousarray(tex, dtype=np.uint8),
            H,
            (w, h),
            dst=image,
            flags=cv2.INTER_LINEAR,
            borderMode=cv2.BORDER_TRANSPARENT,
        )
    else:
        photo = warp_perspective(tex, H, (h, w), method=method)
        mask = (
            warp_perspective(np.full((th, tw), 255, np.uint8), H, (h, w), method=method).astype(
                np.float32
            )
            / 255
        )
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

    Parameters
    ----------
    kind : str
        Which texture and pose: ``"page"``, ``"painting"`` or ``"facade"``.
    **pose
        Keyword arguments of :func:`photograph_plane` that override the scene's pose.

    Returns
    -------
    PlanePhoto
        The photo and its ground truth.

    Raises
    ------
    CamlabInputError
        If ``kind`` is not one of the three.

    Examples
    --------
    >>> p = sample_photo("page")
    >>> p.image.shape, round(p.aspect, 3)
    ((480, 640, 3), 0.707)
    """
    if kind not in _SCENES:
        raise CamlabInputError(f"kind: expected one of {sorted(_SCENES)}, got {kind!r}")
    texture = {"page": page_texture, "painting": painting_texture, "facade": facade_texture}[kind]()
    return photograph_plane(texture, **{**_SCENES[kind], **pose})
