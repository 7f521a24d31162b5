r"""Dense matching of a rectified pair with its warp border masked, and a hand-held pair's warnings.

:func:`masked_disparity` matches; :func:`pair_warnings` says, before rectifying, when a pair is
unfit for Hartley's method. A rectifying warp leaves a black border in each image. A disparity there means nothing, and a
left pixel whose match lands in the *right* image's border has matched black, not the photo:
both are masked (NaN). See lesson 11, sections 7 and 8.

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 11.12 (image
   rectification).
.. [2] H. Hirschmüller, 2008, "Stereo processing by semiglobal matching and mutual information",
   *IEEE PAMI* 30(2), 328-341.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError
from ..disparity import sgbm_disparity
from ..epipolar import epipoles
from .calibrated import rectify_images

__all__ = [
    "MaskedDisparity",
    "masked_disparity",
    "pair_warnings",
]


class MaskedDisparity(NamedTuple):
    """A rectified pair's SGBM disparity at the matching scale, its warp border masked.

    Attributes
    ----------
    left, right : (h, w) ndarray
        The rectified pair, resized to the matching scale (``img[v, u]``).
    disparity : (h, w) ndarray
        SGBM's disparity, pixels of the matching scale; NaN where there is no match, on the
        left image's warp border, and in ``wedge``.
    inside_left, inside_right : (h, w) bool ndarray
        The pixels that the photo fully covers (the rest is warp border).
    wedge : (h, w) bool ndarray
        Left pixels dropped because their match ``u - d`` lies in the right image's border.
    """

    left: np.ndarray
    right: np.ndarray
    disparity: np.ndarray
    inside_left: np.ndarray
    inside_right: np.ndarray
    wedge: np.ndarray


def masked_disparity(
    rect,
    left: np.ndarray,
    right: np.ndarray,
    *,
    scale: float = 0.5,
    max_disparity: int = 96,
    min_disparity: int = 16,
    block_size: int = 5,
) -> MaskedDisparity:
    """Rectify a grey pair, shrink it by ``scale``, match it by SGBM and mask the warp border.

    The border is found by warping two all-white images the same way: a pixel the white does
    not fully reach after the resize (``INTER_AREA``) is border. A left pixel whose match
    ``u - d`` (rounded) is border in the right image is dropped too (the *wedge*).

    Parameters
    ----------
    rect : CalibratedRectification or UncalibratedRectification
        The rectification, as :func:`rectify_images` takes it.
    left, right : (H, W) uint8 ndarray
        The grey pair as photographed (undistorted if ``rect`` is uncalibrated).
    scale : float, optional
        The matching scale, 0 < scale <= 1 (0.5: half size).
    max_disparity, min_disparity : int, optional
        SGBM's search range, pixels of the matching scale (see
        :func:`camlab.disparity.sgbm_disparity`).
    block_size : int, optional
        SGBM's odd matching window, pixels.

    Returns
    -------
    MaskedDisparity
        The resized pair, the masked disparity, both images' photo masks and the wedge.

    Raises
    ------
    CamlabInputError
        A ``scale`` outside (0, 1], or images that are not 2-D.

    References
    ----------
    Hirschmüller (2008), "Stereo processing by semiglobal matching and mutual information",
    IEEE PAMI 30(2); Szeliski, Computer Vision, 2nd ed., section 12.5.
    """
    import cv2

    if not 0 < scale <= 1:
        raise CamlabInputError(f"scale: expected 0 < scale <= 1, got {scale!r}; 0.5 is half size")
    left, right = np.asarray(left), np.asarray(right)
    if left.ndim != 2 or right.ndim != 2:
        raise CamlabInputError(
            f"left, right: expected grey (H, W) images, got shapes {left.shape} and {right.shape}; "
            "convert with cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)"
        )
    small = (int(rect.image_size[0] * scale), int(rect.image_size[1] * scale))

    def shrink(image):
        return cv2.resize(image, small, interpolation=cv2.INTER_AREA)

    L, R = (shrink(im) for im in rectify_images(rect, left, right))
    white = rectify_images(rect, np.full_like(left, 255), np.full_like(right, 255))
    inside_l, inside_r = (shrink(im) == 255 for im in white)
    d = sgbm_disparity(L, R, max_disparity, block_size, min_disparity=min_disparity)
    d[~inside_l] = np.nan
    vv, uu = np.nonzero(np.isfinite(d))
    u_right = np.round(uu - d[vv, uu]).astype(int)
    off = ~inside_r[vv, np.clip(u_right, 0, None)] | (u_right < 0)
    wedge = np.zeros(d.shape, bool)
    wedge[vv[off], uu[off]] = True
    d[wedge] = np.nan
    return MaskedDisparity(L, R, d, inside_l, inside_r, wedge)


def pair_warnings(F: ArrayLike, n_inliers: int, image_size: tuple[int, int]) -> list[str]:
    """What makes a hand-held pair unfit for Hartley's rectification, as sentences (none: ``[]``).

    Two causes: an epipole inside either image (the camera moved forwards, towards the
    scene: a homography that sends it to infinity tears the image in two, H&Z 11.12), and
    fewer than 50 RANSAC inliers (too few to trust F: more texture, a smaller step).

    Parameters
    ----------
    F : (3, 3) array_like
        The fundamental matrix, ``x2_h @ F @ x1_h = 0``.
    n_inliers : int
        How many matches RANSAC kept.
    image_size : (width, height)
        Both images' size, pixels.

    Returns
    -------
    list of str
        One sentence per problem found.

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 11.12.
    """
    F = np.asarray(F, dtype=float)
    w, h = image_size
    found = []
    ends = epipoles(F)
    for name, e in (("left", ends.e1), ("right", ends.e2)):
        if abs(e[2]) > 1e-12 * np.linalg.norm(e):
            u, v = e[:2] / e[2]
            if -0.5 <= u <= w - 0.5 and -0.5 <= v <= h - 0.5:
                found.append(
                    f"the {name} epipole ({u:.0f}, {v:.0f}) lies inside the image: the camera moved "
                    "towards the scene, and Hartley's homographies tear the image there "
                    "(pitfall 4); step sideways between the photos"
                )
    if n_inliers < 50:
        found.append(
            f"only {n_inliers} matches fit F (fewer than 50): F is unreliable; photograph "
            "more texture, or take a smaller step between the photos"
        )
    return found
