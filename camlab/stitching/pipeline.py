r"""The whole panorama: :func:`stitch` runs every stage and says what it chose and why.

1. Features (SIFT) on every image; the same photo given twice is reported and left out.
2. :func:`camlab.stitching.match_graph`: pairwise RANSAC, reference image, spanning tree.
3. The model. A **rotation** (:func:`camlab.stitching.cameras.estimate_cameras`: focal from
   the homographies, spanning-tree rotations, bundle adjustment, wave correction) explains
   a camera turning about its centre. If its residual is large, or the focal comes out
   longer than 2 image diagonals (views under about 30 degrees wide, where a flat scene
   passes for a rotation), the **plane** model is tried: the images are taken as views of a plane (a map, a document, a facade from several positions) and every
   homography is refined together (:func:`camlab.stitching.cameras.adjust_homographies`), and
   wins if its residual is below 0.7 times the rotation's. If neither fits, the camera moved in front of a 3-D scene: a warning gives both residuals.
4. The canvas (:mod:`camlab.stitching.projections`): planar, cylindrical or spherical;
   ``"auto"`` takes the plane for planar scenes and fields of view up to 100 degrees, the
   sphere beyond.
5. Exposure gains, seams and multi-band blending (:func:`camlab.stitching.blend`), then
   optionally a crop to the largest rectangle without empty canvas.
"""

from __future__ import annotations

import time
import warnings
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .. import features as _feat
from .._validate import CamlabInputError, DegenerateError, check_intrinsics
from .blending import BLENDS, blend, dp_seam_masks, gain_compensation
from .cameras import adjust_homographies, estimate_cameras, estimate_focal, inlier_matches
from .projections import PROJECTIONS, canvas_points, make_canvas, warp_to_canvas
from .registration import match_graph, prepare_images
from .warping import WarpedImages, feather_weights, warp_images

__all__ = ["PROJECTION_CHOICES", "Rectangle", "StitchResult", "largest_rectangle", "stitch"]

PROJECTION_CHOICES = ("auto",) + PROJECTIONS


class StitchResult(NamedTuple):
    """What :func:`stitch` made.

    Attributes
    ----------
    panorama : (h, w, 3) ndarray
        uint8 if every input was uint8, else float32 in [0, 1].
    mask : (h, w) bool ndarray
        Canvas pixels covered by at least one image.
    homographies : list of (3, 3) ndarray or None
        canvas_from_image for every input image on a planar canvas (None for images left
        out, and for every image on a cylinder or sphere: see ``cameras``).
    masks : list of (h, w) bool ndarray or None
        Each image's footprint on the canvas.
    pairs : list of PairReport
        Every registered pair: matches, inliers, residual RMS, accepted, reason.
    reference : int
        The reference image (its camera fixes the world frame before wave correction).
    unconnected : list of int
        Images left out (overlapping nothing, or a repeated photo), and reported.
    gains : (n,) ndarray
        Exposure gains applied (NaN for images left out).
    graph : MatchGraph
        The full pairwise registration.
    cameras : list of (K, R) or None
        Per image: intrinsics and cam_from_world rotation (``x_j ~ K_j R_j R_i^T K_i^-1 x_i``)
        from bundle adjustment; None for images left out, and for all if ``model`` is
        ``"homography"``.
    projection : str
        The canvas used (what ``"auto"`` chose).
    model : str
        ``"rotation"`` or ``"homography"`` (a planar scene).
    residual_rms : float
        RMS transfer error of the model over all inlier matches, pixels.
    outlines : list of (N, 2) ndarray or None
        Each image's border on the canvas (for drawing which image went where).
    names : list of str
    timings : dict
        Seconds per stage: features, matching, estimation (focal, rotations, model choice),
        bundle_adjustment (of the cameras, or of the homographies of a flat scene), warping,
        exposure, seams, compositing (gains applied and blending).
    """

    panorama: np.ndarray
    mask: np.ndarray
    homographies: list
    masks: list
    pairs: list
    reference: int
    unconnected: list
    gains: np.ndarray
    graph: object
    cameras: list
    projection: str
    model: str
    residual_rms: float
    outlines: list
    names: list
    timings: dict


def _duplicates(imgs: list) -> dict:
    """{later: earlier} for images that are the same photo (same size, mean difference < 1 grey level)."""
    small = [im[::8, ::8] for im in imgs]
    out = {}
    for j in range(len(imgs)):
        for i in range(j):
            if (
                i not in out
                and small[i].shape == small[j].shape
                and float(np.abs(small[i] - small[j]).mean()) < 1 / 255
            ):
                out[j] = i
                break
    return out


def _detect(im: np.ndarray, method: str, max_features: int, mask, megapixels) -> _feat.Features:
    """Features of ``im`` found on a copy of at most ``megapixels``, positions in ``im``'s pixels.

    Resizing by s maps pixel centres u to s (u + 1/2) - 1/2, so back is (u' + 1/2)/s - 1/2.
    """
    import cv2

    h, w = im.shape[:2]
    s = 1.0 if megapixels is None else min(1.0, float(np.sqrt(megapixels * 1e6 / (h * w))))
    if s > 0.95:
        return _feat.detect_features(im, method, max_features, mask=mask)
    size = (max(16, int(round(w * s))), max(16, int(round(h * s))))
    small = cv2.resize(im, size, interpolation=cv2.INTER_AREA)
    m = (
        None
        if mask is None
        else cv2.resize(mask.astype(np.uint8), size, interpolation=cv2.INTER_NEAREST) > 0
    )
    f = _feat.detect_features(small, method, max_features, mask=m)
    sx, sy = size[0] / w, size[1] / h
    pts = np.c_[(f.points[:, 0] + 0.5) / sx - 0.5, (f.points[:, 1] + 0.5) / sy - 0.5]
    return f._replace(points=pts, sizes=f.sizes / s)


def _names(names, n: int) -> list:
    if names is None:
        return [f"image {k}" for k in range(n)]
    out = [str(x) for x in names]
    if len(out) != n:
        raise CamlabInputError(f"names: expected one name per image ({n}), got {len(out)}")
    return out


def _field_of_view(Ks: list, Rs: list, shapes: list) -> tuple[float, float]:
    """Horizontal and vertical extent (degrees) of all images on the sphere."""
    from .projections import footprint

    boxes = np.array(
        [footprint(K, R, sh, "spherical", 1.0) for K, R, sh in zip(Ks, Rs, shapes, strict=True)]
    )
    return (
        float(np.degrees(boxes[:, 1, 0].max() - boxes[:, 0, 0].min())),
        float(np.degrees(boxes[:, 1, 1].max() - boxes[:, 0, 1].min())),
    )


def _outline_curved(K, R, shape, canvas) -> np.ndarray:
    u, v = canvas_points(_ring(shape), K, R, canvas.projection, canvas.s)
    return np.c_[u - canvas.origin[0], v - canvas.origin[1]]


def _warp_curved(imgs: list, Ks: list, Rs: list, canvas) -> WarpedImages:
    """Every image warped into its own box of a curved canvas; a box that wraps around a
    full-turn canvas (columns modulo w) becomes a full-width one."""
    h, w = canvas.shape
    out_i, out_m, out_w, boxes = [], [], [], []
    for im, K, R, box in zip(imgs, Ks, Rs, canvas.boxes, strict=True):
        patch, mask, wgt = warp_to_canvas(
            im, K, R, canvas, box, feather_weights(im.shape).astype(np.float32)
        )
        wgt = np.where(mask, np.maximum(wgt, 1e-3), 0).astype(np.float32)
        r0, r1, c0, c1 = box
        if c0 < 0 or c1 > w:
            cols = np.arange(c0, c1) % w
            parts = []
            for a in (patch, mask, wgt):
                full = np.zeros((r1 - r0, w) + a.shape[2:], a.dtype)
                full[:, cols] = a
                parts.append(full)
            (patch, mask, wgt), (c0, c1) = parts, (0, w)
        out_i.append(patch)
        out_m.append(mask)
        out_w.append(wgt)
        boxes.append((r0, r1, c0, c1))
    return WarpedImages(out_i, out_m, out_w, boxes, (h, w), [None] * len(imgs), np.eye(3))


def _warn_left_out(graph, lost: list, label: list) -> None:
    """Warn, naming them, about images left out: alone (overlapping nothing) or in a separate group."""
    if not lost:
        return
    reasons = []
    for group in graph.groups():
        if not set(group) & set(lost):
            continue
        if len(group) == 1:
            k = group[0]
            best = max((r.inliers for r in graph.report() if k in (r.i, r.j)), default=0)
            reasons.append(f"{label[k]!r} overlaps none of the others (best pair: {best} inliers)")
        else:
            reasons.append(
                f"{', '.join(repr(label[k]) for k in group)} overlap each other but none of the "
                f"panorama's photos: a separate panorama; stitch them on their own"
            )
    warnings.warn(
        f"stitch: left out of the panorama: {'; '.join(reasons)}", UserWarning, stacklevel=3
    )


def _warn_second_plane(graph, names: list, rng) -> None:
    """Warn if an accepted pair's outliers follow a second homography: two planes, so the camera moved (parallax).

    A camera that only turns maps every scene point by one homography; if the matches that
    the first homography rejects agree on another one (at least 10 of them, and more than
    8 + 0.3 of the outliers, the Brown & Lowe test), the scene has depth and the centre moved.
    """
    from ..homography import ransac_homography, transfer_error

    rng = np.random.default_rng(1) if rng is None else rng
    for (i, j), p in sorted(graph.pairs.items()):
        out = ~p.inliers
        n = int(out.sum())
        if not p.accepted or n < 10:
            continue
        try:
            r2 = ransac_homography(p.matches.src[out], p.matches.dst[out], 3.0, 0.99, 300, rng)
        except (DegenerateError, CamlabInputError):
            continue
        k2 = int(r2.inliers.sum())
        if k2 >= max(10, 8 + 0.3 * n):
            off = float(
                np.median(
                    transfer_error(
                        p.H, p.matches.src[out][r2.inliers], p.matches.dst[out][r2.inliers]
                    )
                )
            )
            warnings.warn(
                f"stitch: {names[i]!r}-{names[j]!r}: {k2} matches follow a second plane, {off:.1f} px "
                f"(median) off the first homography: the camera moved between the photos (parallax), "
                f"so no single homography or rotation aligns everything; expect ghosts of near objects",
                UserWarning,
                stacklevel=3,
            )


def _warn_full_turn(Rs: list, names: list) -> None:
    """Warn, naming the photos, if the camera turned through more than 360 degrees (in input order)."""
    yaw = np.unwrap([np.arctan2(R[2, 0], R[2, 2]) for R in Rs])
    turn = np.degrees(yaw - yaw[0])
    if np.abs(turn).max() > 365:
        again = [nm for nm, t in zip(names, turn, strict=True) if abs(t) > 350]
        warnings.warn(
            f"stitch: the photos turn through {np.abs(turn).max():.0f} degrees, more than a full circle: "
            f"{', '.join(repr(x) for x in again)} show again what the first photos showed; the canvas is "
            f"one full turn and the repeated views are blended in",
            UserWarning,
            stacklevel=3,
        )


class Rectangle(NamedTuple):
    """An axis-aligned block of pixels ``mask[row0:row1, col0:col1]`` (ends exclusive)."""

    row0: int
    row1: int
    col0: int
    col1: int


def largest_rectangle(mask: np.ndarray) -> Rectangle:
    """The largest axis-aligned rectangle of True pixels: (row0, row1, col0, col1), end exclusive.

    Row by row, ``heights[c]`` counts the True pixels ending at this row in column c; the
    largest rectangle under that histogram (a stack of increasing heights) is the best one
    whose bottom edge is this row. O(h w).
    """
    m = np.asarray(mask, bool)
    h, w = m.shape
    heights = np.zeros(w, int)
    best, out = 0, (0, 0, 0, 0)
    for r in range(h):
        heights = np.where(m[r], heights + 1, 0)
        stack: list = []
        for c in range(w + 1):
            hc = heights[c] if c < w else 0
            start = c
            while stack and stack[-1][1] >= hc:
                start, hs = stack.pop()
                if hs * (c - start) > best:
                    best, out = hs * (c - start), (r + 1 - hs, r + 1, start, c)
            stack.append((start, hc))
    return Rectangle(*out)


def stitch(
    images: Sequence[ArrayLike],
    *,
    blend_method: str = "multiband",
    method: str = "sift",
    max_features: int = 1500,
    ratio: float = 0.75,
    mutual: bool = False,
    threshold: float = 3.0,
    min_inliers: int = 15,
    compensate_gains: bool = True,
    levels: int = 5,
    projection: str = "auto",
    K: ArrayLike | None = None,
    reference: int | None = None,
    rng: np.random.Generator | None = None,
    max_pixels: int = 40_000_000,
    names: Sequence[str] | None = None,
    crop: bool = False,
    rotation_tol: float = 1.0,
    plane_tol: float = 1.5,
    registration_megapixels: float | None = 0.15,
) -> StitchResult:
    """Stitch overlapping photos of a turning camera, or of a flat scene, into a panorama.

    See the module docstring for the stages.

    Parameters
    ----------
    images : sequence of (H, W[, C]) array_like
        At least two images; sizes and channel counts may differ (:func:`prepare_images`).
    blend_method : {"overwrite", "feather", "multiband"}
    method : {"sift", "orb"}
    max_features, ratio, mutual, threshold, min_inliers
        See :func:`camlab.features.detect_features` and :func:`camlab.stitching.register_pair`.
    compensate_gains : bool
        Equalise exposures (:func:`camlab.stitching.gain_compensation`).
    levels : int
        Multi-band pyramid levels.
    projection : {"auto", "planar", "cylindrical", "spherical"}
        The canvas; ``"auto"`` chooses (``result.projection`` says what).
    K : (3, 3) array_like, optional
        Known intrinsics shared by all images: the focal is then not estimated.
    reference : int, optional
        Force the reference image.
    names : sequence of str, optional
        Image names for messages (default "image 0", ...).
    crop : bool
        Crop to the largest rectangle that holds no empty canvas.
    registration_megapixels : float
        Find features on copies at most this large (SIFT's cost grows with the area; its
        finest octave mostly adds noise-level keypoints); their positions are mapped back,
        so every later stage works in full-resolution pixels. ``None``: full resolution.
    rotation_tol, plane_tol : float
        RMS residuals (pixels at the registration resolution) above which the rotation
        model, then the plane model, is judged not to fit. The plane replaces the rotation
        only if it fits clearly better (residual below 0.7 times the rotation's).

    Returns
    -------
    StitchResult

    Raises
    ------
    CamlabInputError
        Fewer than two images, bad shapes or options.
    DegenerateError
        Fewer than two images could be connected; the message names them and every pair.

    Warns
    -----
    UserWarning
        Images left out (named), a repeated photo, a model that does not fit (parallax),
        a turn of more than 360 degrees.
    """
    if blend_method not in BLENDS:
        raise CamlabInputError(f"blend_method: expected one of {BLENDS}, got {blend_method!r}")
    if projection not in PROJECTION_CHOICES:
        raise CamlabInputError(
            f"projection: expected one of {PROJECTION_CHOICES}, got {projection!r}"
        )
    times: dict = {}
    t0 = time.perf_counter()
    imgs = prepare_images(images)
    all_uint8 = all(np.asarray(im).dtype == np.uint8 for im in images)
    # all grey: stitch one channel (a third of the warping and blending) and repeat it at the end
    grey = all(np.ndim(im) == 2 or np.shape(im)[2] == 1 for im in images)
    if grey:
        imgs = [np.ascontiguousarray(im[..., :1]) for im in imgs]
    n = len(imgs)
    label = _names(names, n)
    Kfix = None if K is None else check_intrinsics(K, "K")
    dup = _duplicates(imgs)
    if dup:
        warnings.warn(
            "stitch: "
            + "; ".join(f"{label[j]!r} is the same photo as {label[i]!r}" for j, i in dup.items())
            + "; the repeat is left out",
            UserWarning,
            stacklevel=2,
        )
    masks_feat = [
        None if k not in dup else np.zeros(im.shape[:2], bool) for k, im in enumerate(imgs)
    ]
    feats = [
        _detect(im, method, max_features, masks_feat[k], registration_megapixels)
        for k, im in enumerate(imgs)
    ]
    times["features"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    # refine=False: bundle adjustment refines every pair together afterwards. 500 samples, as Brown &
    # Lowe: a pair that passes the inlier test (over 30% inliers) is found with probability
    # 1 - (1 - 0.3^4)^500 > 98% even at that limit, and real overlaps have far more inliers; pairs
    # that do not overlap (which never stop early) cost half as much.
    graph = match_graph(
        feats,
        ratio=ratio,
        mutual=mutual,
        threshold=threshold,
        min_inliers=min_inliers,
        rng=rng,
        reference=reference,
        approximate=True,
        refine=False,
        confidence=0.995,
        max_iters=500,
    )
    times["matching"] = time.perf_counter() - t0
    keep = [k for k in range(n) if graph.homographies[k] is not None]
    if len(keep) < 2:
        rows = "; ".join(
            f"{label[r.i]!r}-{label[r.j]!r}: {r.matches} matches, {r.inliers} inliers ({r.reason})"
            for r in graph.report()
        )
        raise DegenerateError(
            f"stitch: no two images could be registered (at most one usable image), nothing to "
            f"stitch. Pairs: {rows}"
        )
    _warn_left_out(graph, [k for k in graph.unconnected if k not in dup], label)

    t0 = time.perf_counter()
    shapes = [im.shape for im in imgs]
    diag = float(np.median([np.hypot(*sh[:2]) for sh in shapes]))
    f0 = estimate_focal({key: p.H for key, p in graph.pairs.items() if p.accepted}, shapes)
    # views under about 30 degrees wide: a flat scene passes for a rotation (and its adjustment crawls)
    telephoto = Kfix is None and f0 > 2 * diag and projection in ("auto", "planar")
    est = None if telephoto else estimate_cameras(graph, shapes, K=Kfix)
    rot_rms = np.inf if est is None else est.bundle.rms_after
    # residuals are in full-resolution pixels; features found on smaller copies are that much less precise
    coarse = (
        float(
            np.median(
                [
                    np.sqrt(im.shape[0] * im.shape[1] / (registration_megapixels * 1e6))
                    for im in imgs
                ]
            )
        )
        if registration_megapixels
        else 1.0
    )
    rot_tol, pl_tol = rotation_tol * max(1.0, coarse), plane_tol * max(1.0, coarse)
    model, resid, adj = "rotation", rot_rms, None
    if (telephoto or rot_rms > rot_tol) and projection in ("auto", "planar"):
        adj = adjust_homographies(
            graph.homographies, inlier_matches(graph, 100), reference=graph.reference
        )
        if (
            telephoto or adj.rms_after < 0.7 * rot_rms
        ):  # a plane explains the matches clearly better
            model, Hs_plane, resid = "homography", adj.homographies, adj.rms_after
        if adj.rms_after > pl_tol and rot_rms > rot_tol:
            warnings.warn(
                f"stitch: neither a turning camera (rotation model residual {rot_rms:.2f} px) nor a flat "
                f"scene (homography residual {adj.rms_after:.2f} px) explains the matches: the camera "
                f"moved in front of a 3-D scene (parallax); expect ghosts and misaligned seams",
                UserWarning,
                stacklevel=2,
            )
    elif rot_rms > rot_tol:
        warnings.warn(
            f"stitch: the rotation model leaves {rot_rms:.2f} px RMS (more than {rot_tol:.2f} px): the "
            f"camera moved (parallax) or the scene is flat; try projection='planar'",
            UserWarning,
            stacklevel=2,
        )
    if model == "homography":
        Ks = Rs = [None] * len(keep)
    else:
        Ks = [est.Ks[k] for k in keep]
        Rs = [est.Rs[k] for k in keep]
    sub_shapes = [shapes[k] for k in keep]
    _warn_second_plane(graph, label, rng)
    if model == "rotation":
        _warn_full_turn(Rs, [label[k] for k in keep])
    chosen = projection
    if projection == "auto":
        chosen = (
            "planar"
            if model == "homography" or max(_field_of_view(Ks, Rs, sub_shapes)) <= 100
            else "spherical"
        )
    ba_seconds = (0.0 if est is None else est.bundle.seconds) + (
        0.0 if adj is None else adj.seconds
    )
    times["estimation"] = time.perf_counter() - t0 - ba_seconds
    times["bundle_adjustment"] = ba_seconds

    t0 = time.perf_counter()
    sub = [imgs[k] for k in keep]
    if chosen == "planar":
        if model == "homography":
            H_list = [Hs_plane[k] for k in keep]
        else:
            s = float(np.median([Kk[0, 0] for Kk in Ks]))
            Kc = np.diag([s, s, 1.0])
            H_list = [Kc @ R.T @ np.linalg.inv(Kk) for Kk, R in zip(Ks, Rs, strict=True)]
        try:
            warped = warp_images(sub, H_list, max_pixels=max_pixels)
        except DegenerateError as exc:
            raise DegenerateError(
                f"stitch: the images turn too far for a plane ({exc}); "
                "use projection='cylindrical' or 'spherical'"
            ) from None
        outlines_sub = [
            _hg_border(H, sh) for H, sh in zip(warped.homographies, sub_shapes, strict=True)
        ]
    else:
        s = float(np.median([Kk[0, 0] for Kk in Ks]))
        canvas = make_canvas(Ks, Rs, sub_shapes, chosen, s, max_pixels=max_pixels)
        warped = _warp_curved(sub, Ks, Rs, canvas)
        outlines_sub = [
            _outline_curved(Kk, R, sh, canvas) for Kk, R, sh in zip(Ks, Rs, sub_shapes, strict=True)
        ]
    times["warping"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    ref_local = keep.index(graph.reference)
    g_sub = (
        gain_compensation(warped, reference=ref_local) if compensate_gains else np.ones(len(keep))
    )
    times["exposure"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    seams = dp_seam_masks(warped) if blend_method == "multiband" else None
    times["seams"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    pano = blend(warped, blend_method, gains=g_sub, levels=levels, seams=seams)
    times["compositing"] = time.perf_counter() - t0
    union = np.zeros(warped.shape, bool)
    for m, (r0, r1, c0, c1) in zip(warped.patch_masks, warped.boxes, strict=True):
        union[r0:r1, c0:c1] |= m
    masks_out = list(warped.masks)
    if crop:
        r0, r1, c0, c1 = largest_rectangle(union)
        pano, union = pano[r0:r1, c0:c1], union[r0:r1, c0:c1]
        masks_out = [m[r0:r1, c0:c1] for m in masks_out]
        outlines_sub = [o - [c0, r0] for o in outlines_sub]
    gains = np.full(n, np.nan)
    gains[keep] = g_sub
    H_out: list = [None] * n
    M_out: list = [None] * n
    O_out: list = [None] * n
    C_out: list = [None] * n
    for idx, k in enumerate(keep):
        H_out[k] = warped.homographies[idx]
        M_out[k] = masks_out[idx]
        O_out[k] = outlines_sub[idx]
        if model == "rotation":
            C_out[k] = (est.Ks[k], est.Rs[k])
    if crop and chosen == "planar":
        Tc = np.array([[1.0, 0, -c0], [0, 1, -r0], [0, 0, 1]])
        H_out = [None if H is None else Tc @ H for H in H_out]
    if all_uint8:
        pano = np.rint(np.multiply(pano, 255, out=pano), out=pano).astype(
            np.uint8
        )  # pano is in [0, 1]
    if grey:
        pano = np.repeat(pano, 3, axis=2)
    unconnected = sorted(set(graph.unconnected) | set(dup))
    return StitchResult(
        pano,
        union,
        H_out,
        M_out,
        graph.report(),
        graph.reference,
        unconnected,
        gains,
        graph,
        C_out,
        chosen,
        model,
        float(resid),
        O_out,
        label,
        times,
    )


def _hg_border(H: np.ndarray, shape) -> np.ndarray:
    from ..projective import map_points

    return map_points(H, _ring(shape))


def _ring(shape) -> np.ndarray:
    """40 points per side around an image's border, in order (top, right, bottom, left)."""
    from .projections import border_points

    p = border_points(shape, 40)[:-1]
    return np.vstack([p[:40], p[120:160], p[40:80][::-1], p[80:120][::-1]])
