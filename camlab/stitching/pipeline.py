r"""The whole panorama: :func:`stitch` runs every stage and says what it chose and why.

Each stage is one function below, called in this order by :func:`stitch`:

1. ``_prepare``: the images as float32; the same photo given twice is reported and left out.
2. ``_features``: SIFT on every image, on a copy of ``registration_megapixels``.
3. ``_register``: :func:`camlab.stitching.match_graph`, pairwise RANSAC, reference image,
   spanning tree; images no accepted pair reaches are named in a warning.
4. :func:`camlab.stitching.model.choose_model`: a **rotation** (:func:`camlab.stitching.cameras.estimate_cameras`: focal
   from the homographies, spanning-tree rotations, bundle adjustment, wave correction)
   explains a camera turning about its centre. If its residual is large, or the focal comes
   out longer than 2 image diagonals (views under 2 atan(1/4) = 28 degrees across the
   diagonal, where a flat scene passes for a rotation), the **plane** model is tried: the
   images are views of a plane (a map, a document, a facade from several positions) and
   every homography is refined together
   (:func:`camlab.stitching.cameras.adjust_homographies`); it wins if its residual is below
   0.7 times the rotation's. If neither fits, the camera moved in front of a 3-D
   scene: a warning gives both residuals.
5. ``_choose_projection``: the canvas (:mod:`camlab.stitching.projections`), planar,
   cylindrical or spherical; ``"auto"`` takes the plane for planar scenes and fields of view
   up to 100 degrees, the sphere beyond.
6. ``_warp``: every image onto the canvas (:mod:`camlab.stitching.warping`), with its outline.
7. ``_composite``: exposure gains, seams and multi-band blending (:func:`camlab.stitching.blend`).
8. ``_result``: optionally a crop to the largest rectangle without empty canvas
   (:func:`largest_rectangle`), and the per-image lists of :class:`StitchResult`.
"""

from __future__ import annotations

import time
import warnings
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, DegenerateError, check_intrinsics
from ..projective import map_points
from .blending import BLENDS, blend, dp_seam_masks, gain_compensation
from .model import ModelChoice, choose_model
from .projections import (
    PROJECTIONS,
    border_ring,
    field_of_view,
    make_canvas,
    outline_on_canvas,
)
from .registration import (
    MatchGraph,
    detect_at_resolution,
    match_graph,
    prepare_images,
    repeated_photos,
    second_planes,
)
from .warping import WarpedImages, warp_images, warp_images_by_rotation

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
    adjustments : list of str
        One line per bundle adjustment run: which model, Levenberg-Marquardt iterations, why it
        stopped, RMS before and after, seconds.
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
    adjustments: list


def _names(names, n: int) -> list:
    if names is None:
        return [f"image {k}" for k in range(n)]
    out = [str(x) for x in names]
    if len(out) != n:
        raise CamlabInputError(f"names: expected one name per image ({n}), got {len(out)}")
    return out


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
        f"stitch: left out of the panorama: {'; '.join(reasons)}", UserWarning, stacklevel=4
    )


def _warn_second_plane(graph: MatchGraph, names: list, rng) -> None:
    """Warn about each accepted pair whose outliers follow a second plane (:func:`second_planes`)."""
    for p in second_planes(graph, rng):
        warnings.warn(
            f"stitch: {names[p.i]!r}-{names[p.j]!r}: {p.matches} matches follow a second plane, "
            f"{p.offset:.1f} px (median) off the first homography: the camera moved between the "
            f"photos (parallax), so no single homography or rotation aligns everything; expect "
            f"ghosts of near objects",
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

    Parameters
    ----------
    mask : (h, w) array_like of bool
        The pixels that may be kept (e.g. the panorama's covered canvas).

    Returns
    -------
    Rectangle
        (row0, row1, col0, col1), end exclusive; (0, 0, 0, 0) if no pixel is True.
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
        How the warped images are combined (:func:`camlab.stitching.blend`).
    method : {"sift", "orb"}
        The feature detector.
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
    rng : numpy.random.Generator, optional
        Random source of the RANSAC runs (registration, and the search for a second plane);
        default fixed seeds, so a run is repeatable.
    max_pixels : int
        The largest canvas (pixels) the warping may allocate; a larger one raises.
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
        The ``panorama`` and its ``mask``, each image's ``homographies``, ``masks`` and
        ``outlines`` on the canvas, the registration (``pairs``, ``graph``, ``reference``,
        ``unconnected``), ``gains``, ``cameras``, the ``projection`` and ``model`` used, its
        ``residual_rms`` and the stage ``timings`` (see :class:`StitchResult`).

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
    Kfix = None if K is None else check_intrinsics(K, "K")
    times: dict = {}
    t0 = time.perf_counter()
    photos = _prepare(images, names)
    feats = _features(photos, method, max_features, registration_megapixels)
    times["features"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    graph = _register(feats, photos, ratio, mutual, threshold, min_inliers, rng, reference)
    times["matching"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    fit = choose_model(
        graph,
        [im.shape for im in photos.images],
        Kfix,
        projection,
        (rotation_tol, plane_tol),
        _coarseness(photos.images, registration_megapixels),
    )
    _warn_second_plane(graph, photos.names, rng)
    if fit.model == "rotation":
        _warn_full_turn(fit.Rs, [photos.names[k] for k in fit.keep])
    chosen = _choose_projection(projection, fit, [photos.images[k].shape for k in fit.keep])
    times["estimation"] = time.perf_counter() - t0 - fit.bundle_seconds
    times["bundle_adjustment"] = fit.bundle_seconds
    t0 = time.perf_counter()
    warped, outlines = _warp(photos, fit, chosen, max_pixels)
    times["warping"] = time.perf_counter() - t0
    pano, gains = _composite(
        warped, fit.keep.index(graph.reference), blend_method, compensate_gains, levels, times
    )
    return _result(photos, graph, fit, chosen, warped, outlines, pano, gains, crop, times)


# --------------------------------------------------------------------------- the stages of stitch


class _Photos(NamedTuple):
    """The inputs as :func:`prepare_images` makes them, and what stitch must remember about them."""

    images: list  # float32 (h, w, 3), or (h, w, 1) if every input is grey
    names: list  # for messages
    all_uint8: bool  # the panorama comes back as uint8
    grey: bool  # stitched on one channel, repeated at the end
    repeats: dict  # {later: earlier} for the same photo given twice (left out)


def _prepare(images: Sequence[ArrayLike], names: Sequence[str] | None) -> _Photos:
    """Stage 1: the images as float32 (one channel if all are grey); a repeat is named, left out."""
    imgs = prepare_images(images)
    all_uint8 = all(np.asarray(im).dtype == np.uint8 for im in images)
    # all grey: stitch one channel (a third of the warping and blending) and repeat it at the end
    grey = all(np.ndim(im) == 2 or np.shape(im)[2] == 1 for im in images)
    if grey:
        imgs = [np.ascontiguousarray(im[..., :1]) for im in imgs]
    label = _names(names, len(imgs))
    dup = repeated_photos(imgs)
    if dup:
        warnings.warn(
            "stitch: "
            + "; ".join(f"{label[j]!r} is the same photo as {label[i]!r}" for j, i in dup.items())
            + "; the repeat is left out",
            UserWarning,
            stacklevel=3,
        )
    return _Photos(imgs, label, all_uint8, grey, dup)


def _features(photos: _Photos, method: str, max_features: int, megapixels: float | None) -> list:
    """Stage 2: features of every image (none for a repeat), found on copies of ``megapixels``."""
    return [
        detect_at_resolution(
            im,
            method,
            max_features,
            None if k not in photos.repeats else np.zeros(im.shape[:2], bool),
            megapixels,
        )
        for k, im in enumerate(photos.images)
    ]


def _register(
    feats: list, photos: _Photos, ratio, mutual, threshold, min_inliers, rng, reference
) -> MatchGraph:
    """Stage 3: the match graph; raises if under two images connect, warns about those left out.

    refine=False: bundle adjustment refines every pair together afterwards. 500 samples, as
    Brown & Lowe: a pair that passes the inlier test (over 30% inliers) is found with
    probability 1 - (1 - 0.3^4)^500 > 98% even at that limit, and real overlaps have far more
    inliers; pairs that do not overlap (which never stop early) cost half as much.
    """
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
    label = photos.names
    if sum(H is not None for H in graph.homographies) < 2:
        rows = "; ".join(
            f"{label[r.i]!r}-{label[r.j]!r}: {r.matches} matches, {r.inliers} inliers ({r.reason})"
            for r in graph.report()
        )
        raise DegenerateError(
            f"stitch: no two images could be registered (at most one usable image), nothing to "
            f"stitch. Pairs: {rows}"
        )
    _warn_left_out(graph, [k for k in graph.unconnected if k not in photos.repeats], label)
    return graph


def _coarseness(imgs: list, megapixels: float | None) -> float:
    """How much coarser than full resolution the features were found (1.0 at full resolution)."""
    if not megapixels:
        return 1.0
    return float(
        np.median([np.sqrt(im.shape[0] * im.shape[1] / (megapixels * 1e6)) for im in imgs])
    )


def _choose_projection(projection: str, fit: ModelChoice, shapes: list) -> str:
    """Stage 5.

    The canvas; ``"auto"`` takes the plane for a flat scene and for fields of view up to 100
    degrees, the sphere beyond.
    """
    if projection != "auto":
        return projection
    if fit.model == "homography" or max(field_of_view(fit.Ks, fit.Rs, shapes)) <= 100:
        return "planar"
    return "spherical"


def _warp(
    photos: _Photos, fit: ModelChoice, chosen: str, max_pixels: int
) -> tuple[WarpedImages, list]:
    """Stage 6: the kept images on the canvas, and each one's outline there (canvas pixels)."""
    sub = [photos.images[k] for k in fit.keep]
    shapes = [im.shape for im in sub]
    if chosen != "planar":
        s = float(np.median([Kk[0, 0] for Kk in fit.Ks]))
        canvas = make_canvas(fit.Ks, fit.Rs, shapes, chosen, s, max_pixels=max_pixels)
        outlines = [
            outline_on_canvas(K, R, sh, canvas)
            for K, R, sh in zip(fit.Ks, fit.Rs, shapes, strict=True)
        ]
        return warp_images_by_rotation(sub, fit.Ks, fit.Rs, canvas), outlines
    if fit.model == "homography":
        H_list = [fit.plane[k] for k in fit.keep]
    else:
        s = float(np.median([Kk[0, 0] for Kk in fit.Ks]))
        Kc = np.diag([s, s, 1.0])
        H_list = [Kc @ R.T @ np.linalg.inv(Kk) for Kk, R in zip(fit.Ks, fit.Rs, strict=True)]
    try:
        warped = warp_images(sub, H_list, max_pixels=max_pixels)
    except DegenerateError as exc:
        raise DegenerateError(
            f"stitch: the images turn too far for a plane ({exc}); "
            "use projection='cylindrical' or 'spherical'"
        ) from None
    outlines = [
        map_points(H, border_ring(sh)) for H, sh in zip(warped.homographies, shapes, strict=True)
    ]
    return warped, outlines


def _composite(
    warped: WarpedImages,
    reference: int,
    blend_method: str,
    compensate_gains: bool,
    levels: int,
    times: dict,
) -> tuple[np.ndarray, np.ndarray]:
    """Stage 7: exposure gains, seams and blending (timed into ``times``); a panorama in [0, 1]."""
    t0 = time.perf_counter()
    n = len(warped.patches)
    gains = gain_compensation(warped, reference=reference) if compensate_gains else np.ones(n)
    times["exposure"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    seams = dp_seam_masks(warped) if blend_method == "multiband" else None
    times["seams"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    pano = blend(warped, blend_method, gains=gains, levels=levels, seams=seams)
    times["compositing"] = time.perf_counter() - t0
    return pano, gains


def _result(
    photos: _Photos,
    graph: MatchGraph,
    fit: ModelChoice,
    chosen: str,
    warped: WarpedImages,
    outlines: list,
    pano: np.ndarray,
    gains: np.ndarray,
    crop: bool,
    times: dict,
) -> StitchResult:
    """Stage 8.

    The optional crop, per-image lists over all inputs (None for those left out), and the panorama
    in the inputs' type.
    """
    union = np.zeros(warped.shape, bool)
    for m, (r0, r1, c0, c1) in zip(warped.patch_masks, warped.boxes, strict=True):
        union[r0:r1, c0:c1] |= m
    masks = list(warped.masks)
    homographies = list(warped.homographies)
    if crop:
        r0, r1, c0, c1 = largest_rectangle(union)
        pano, union = pano[r0:r1, c0:c1], union[r0:r1, c0:c1]
        masks = [m[r0:r1, c0:c1] for m in masks]
        outlines = [o - [c0, r0] for o in outlines]
        if chosen == "planar":
            Tc = np.array([[1.0, 0, -c0], [0, 1, -r0], [0, 0, 1]])
            homographies = [None if H is None else Tc @ H for H in homographies]
    n = len(photos.images)
    all_gains = np.full(n, np.nan)
    all_gains[fit.keep] = gains
    cameras = (
        [(fit.cameras.Ks[k], fit.cameras.Rs[k]) for k in fit.keep]
        if fit.model == "rotation"
        else None
    )
    per_image = [
        _spread(values, fit.keep, n) for values in (homographies, masks, outlines, cameras)
    ]
    if photos.all_uint8:
        pano = np.rint(np.multiply(pano, 255, out=pano), out=pano).astype(
            np.uint8
        )  # pano is in [0, 1]
    if photos.grey:
        pano = np.repeat(pano, 3, axis=2)
    unconnected = sorted(set(graph.unconnected) | set(photos.repeats))
    H_out, M_out, O_out, C_out = per_image
    return StitchResult(
        pano,
        union,
        H_out,
        M_out,
        graph.report(),
        graph.reference,
        unconnected,
        all_gains,
        graph,
        C_out,
        chosen,
        fit.model,
        fit.residual,
        O_out,
        photos.names,
        times,
        list(fit.adjustments),
    )


def _spread(values: list | None, keep: list, n: int) -> list:
    """A list over all n inputs: ``values[i]`` at ``keep[i]``, None elsewhere (or everywhere)."""
    out: list = [None] * n
    for idx, k in enumerate(keep if values is not None else []):
        out[k] = values[idx]
    return out
