r"""Uncalibrated rectification from F and matches only.

Hartley's method [1]_ [2]_ with Loop & Zhang's shear against distortion [3]_.

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 11.12
   (image rectification).
.. [2] R. I. Hartley, 1999, "Theory and practice of projective rectification",
   *International Journal of Computer Vision* 35(2), 115-127.
.. [3] C. Loop and Z. Zhang, 1999, "Computing rectifying homographies for stereo vision",
   *Proc. IEEE CVPR*, 125-131.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import DegenerateError, as_point_pairs, check_size
from ..camera import rotation_z
from ..epipolar import EIGHT_POINT_REASON, check_fundamental, epipoles, sampson_distance, skew
from ..homography import compose
from ..projective import map_points

__all__ = [
    "UncalibratedRectification",
    "rectify_uncalibrated",
]


_FIT_PX = 3.0  # Sampson distance (pixels) within which a pair counts as consistent with F


class UncalibratedRectification(NamedTuple):
    """What :func:`rectify_uncalibrated` computed.

    ``H1``, ``H2`` (3, 3) homographies taking image i's pixels to rectified image i's pixels, and
    the output ``image_size``.
    """

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

    Algorithm ([1]_, algorithm 11.9; [2]_):

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
    3. **Less distortion.** ``shear``: apply Loop & Zhang's shear [3]_ to each image (it only
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
        ``H1``, ``H2`` ((3, 3), original to rectified pixels) and ``image_size``.

    Raises
    ------
    CamlabInputError
        ``F`` not a fundamental matrix, fewer than 8 matches, or a bad ``image_size``.
    DegenerateError
        Fewer than half the matches lie within 3 px (Sampson distance) of their epipolar lines;
        the epipole lies inside image 2 (forward motion): no homography sends it to
        infinity without tearing the image; use a polar rectification instead; or an image
        corner maps to infinity.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 11.12
       (image rectification), algorithm 11.9.
    .. [2] R. I. Hartley, 1999, "Theory and practice of projective rectification",
       *International Journal of Computer Vision* 35(2), 115-127.
    .. [3] C. Loop and Z. Zhang, 1999, "Computing rectifying homographies for stereo vision",
       *Proc. IEEE CVPR*, 125-131.
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
