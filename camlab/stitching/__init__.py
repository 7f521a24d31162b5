r"""Image stitching: a panorama pipeline with every stage exposed.

The stages, each a function you can call, inspect and replace (lesson 09):

1. **Features and matches** (:mod:`camlab.features`): SIFT keypoints, ratio test.
2. **Pairwise registration** :func:`register_pair`: match, then
   :func:`camlab.homography.ransac_homography`; the pair is accepted only if enough
   matches agree (Brown & Lowe's test [1]_:
   :math:`n_\text{inliers} > 8 + 0.3\, n_\text{matches}` and at least ``min_inliers``).
3. **Match graph** :func:`match_graph`: every pair is registered; the **reference** image
   is the one connected to most others (ties: most inliers); a maximum spanning tree
   (edges weighted by inliers) chains every other image to it,
   :math:`H_{\text{ref} \leftarrow k} = H_{\text{ref} \leftarrow p} H_{p \leftarrow k}`.
   Images that no accepted pair reaches are listed in ``unconnected``, never dropped
   silently.
4. **Canvas** (:func:`camlab.warp.canvas_bounds`): map every image's corners by its
   homography, take the bounding box, and prepend one translation T so nothing has a
   negative coordinate. ``T @ H_ref<-k`` maps image k onto the canvas.
5. **Warp** :func:`warp_images`: every image onto the canvas (:func:`camlab.warp.warp_perspective`,
   cv2 path), with its mask and its feather weight.
6. **Exposure** :func:`gain_compensation` (optional): one gain per image so overlaps agree.
7. **Blend** :func:`blend`: ``"overwrite"`` (hard seams), ``"feather"`` (weights falling
   to zero at each image border, :func:`feather_weights`) or ``"multiband"``
   (Burt & Adelson's Laplacian-pyramid blending [2]_: low frequencies blended over wide
   regions, fine detail over narrow ones, so neither seams nor ghosts).

:func:`stitch` runs them all (:mod:`camlab.stitching.pipeline`). For a camera that turns
through a wide angle, ``projection="cylindrical"`` or ``"spherical"`` lays the images on a
cylinder or a sphere instead of a plane (:mod:`camlab.stitching.projections`), where a
turning camera becomes a sliding one.

Why a homography? A camera that only rotates about its centre sees every point along
the same ray whatever its depth, :math:`x_j \sim K R_j R_i^T K^{-1} x_i`; a planar
scene is related by :math:`K (R - t n^T/d) K^{-1}`. Anything else (a camera that
translates in front of a 3-D scene) has parallax, and no single homography aligns it:
ghosts. Pixel convention: (u, v) = (column, row), origin at the centre of the top-left
pixel (docs/conventions.md).

References
----------
.. [1] M. Brown and D. G. Lowe, 2007, "Automatic panoramic image stitching using invariant
   features", *International Journal of Computer Vision* 74(1), 59-73, section 3.2
   (probabilistic model for image match verification), eq. 13.
.. [2] P. J. Burt and E. H. Adelson, 1983, "A multiresolution spline with application to
   image mosaics", *ACM Transactions on Graphics* 2(4), 217-236.
"""

from __future__ import annotations

from .blending import (
    BLENDS,
    blend,
    dp_seam_masks,
    gain_compensation,
    gains_from_overlaps,
    laplacian_blend,
    overlap_difference,
    seam_masks,
    seam_step,
)
from .pipeline import PROJECTION_CHOICES, StitchResult, largest_rectangle, stitch
from .registration import (
    MatchGraph,
    PairRegistration,
    PairReport,
    match_graph,
    prepare_images,
    register_pair,
)
from .warping import WarpedImages, feather_weights, warp_images

__all__ = [
    "BLENDS",
    "PROJECTION_CHOICES",
    "MatchGraph",
    "PairRegistration",
    "PairReport",
    "StitchResult",
    "WarpedImages",
    "blend",
    "dp_seam_masks",
    "feather_weights",
    "largest_rectangle",
    "gain_compensation",
    "gains_from_overlaps",
    "laplacian_blend",
    "match_graph",
    "overlap_difference",
    "prepare_images",
    "register_pair",
    "seam_masks",
    "seam_step",
    "stitch",
    "warp_images",
]
