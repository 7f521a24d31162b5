r"""The bundled panorama sets as lesson 09 uses them, computed once and cached.

Lesson 09's demonstrations (:mod:`camlab.widgets.image_stitching`) all start from the
same few computations on the sets of :mod:`camlab.data.panorama`; they live here, with
public names, so the widgets hold only controls, artists and ``update``:

:func:`panorama_example`
    The rotation set at half size (320 x 240, f = 400 px), prepared for stitching, with
    SIFT features and the nearest neighbours of every adjacent pair.
:func:`panorama_graph`
    Its match graph (every pair registered, the reference image, the chains).
:func:`reference_canvases`
    Every image warped onto the canvas of each possible reference image (quarter size).
:func:`exposure_pair` and :func:`pair_blends`
    Views 1 and 2 on their common canvas with their exposure gains, blended every way the
    blending demo offers, with the visible step across the seam.
:func:`stitched_panoramas`
    The four-image panorama, planar and cylindrical.
:func:`wide_sweep` and :func:`canvas_previews`
    A 200-degree sweep stitched with bundle-adjusted cameras, and previews of its first
    2-6 views pasted onto a plane, a cylinder and a sphere.
:func:`parallax_pairs`
    Two views of the room from cameras that turn *and* move sideways by each of
    :data:`BASELINES`: registered, warped, blended, with their edges.

Every result is cached (``functools.lru_cache``): the first call computes, later calls
return the same object. Every array in a cached result is read-only, so a caller's edit
cannot change what the next caller gets; copy an array (``a.copy()``) to change it.
Every random choice is seeded (FLANN's trees too, :func:`camlab.features.flann_index`): the
same arrays on every run with the same library versions.
"""

from __future__ import annotations

from functools import lru_cache
from typing import NamedTuple

import numpy as np

from .. import features as ft
from .. import stitching as st
from .._validate import CamlabInputError, DegenerateError, check_shape
from ..camera import scale_intrinsics
from ..homography import normalize_homography, transfer_error
from ._resources import read_only
from .panorama import (
    PanoramaSet,
    TurningSet,
    cam_from_world,
    load_panorama_set,
    render_view,
    room_scene,
    turning_set,
)

__all__ = [
    "BASELINES",
    "SCALE",
    "BlendedPair",
    "CanvasPreview",
    "ExposurePair",
    "PanoramaExample",
    "ParallaxPair",
    "ReferenceCanvas",
    "ReferenceCanvases",
    "WideSweep",
    "canvas_previews",
    "correct_matches",
    "EdgeMasks",
    "edge_masks",
    "exposure_pair",
    "homographies_relative_to",
    "pair_blends",
    "panorama_example",
    "panorama_graph",
    "parallax_pairs",
    "reference_canvases",
    "stitched_panoramas",
    "wide_sweep",
]

#: The scale of the rotation set the demonstrations use (half size: 320 x 240, f = 400 px).
SCALE = 0.5
#: Sideways moves of the second camera in :func:`parallax_pairs`, metres.
BASELINES = (0.0, 0.05, 0.1, 0.2, 0.4)


def _with_canvases(warped: st.WarpedImages) -> st.WarpedImages:
    """Build ``warped``'s full-canvas images, masks and weights (made on first use) now, so that
    :func:`read_only` freezes them with the rest."""
    for name in ("images", "masks", "weights"):  # cached properties: the first read builds them
        getattr(warped, name)
    return warped


# --------------------------------------------------------------------------- the rotation set at half size


class PanoramaExample(NamedTuple):
    """The half-size rotation set with what lesson 09 computes from it first.

    Attributes
    ----------
    data : PanoramaSet
        The set as loaded (uint8 ``images``, ``K``, true rotations) at :data:`SCALE`.
    images : list of (240, 320, 3) float32 ndarray
        The images prepared for stitching (:func:`camlab.stitching.prepare_images`).
    features : list of camlab.features.Features
        SIFT features of every image (at most 1500).
    knn : dict[(i, i + 1), camlab.features.KnnMatches]
        The two nearest neighbours of every feature between adjacent images, ready for
        :func:`camlab.features.filter_matches`.
    """

    data: PanoramaSet
    images: list
    features: list
    knn: dict


@lru_cache(maxsize=1)
def panorama_example() -> PanoramaExample:
    """The half-size panorama set with its features and adjacent-pair nearest neighbours (cached, read-only)."""
    s = load_panorama_set(scale=SCALE)
    imgs = st.prepare_images(s.images)
    feats = [ft.detect_features(im, max_features=1500) for im in imgs]
    knn = {(i, i + 1): ft.knn_match(feats[i], feats[i + 1]) for i in range(len(imgs) - 1)}
    return read_only(PanoramaExample(s, imgs, feats, knn))


@lru_cache(maxsize=1)
def panorama_graph() -> st.MatchGraph:
    """The match graph of :func:`panorama_example` (every pair registered, the reference, the chains; cached)."""
    return read_only(st.match_graph(panorama_example().features))


def correct_matches(
    data: PanoramaSet, i: int, j: int, src: np.ndarray, dst: np.ndarray, tol: float = 2.0
) -> np.ndarray:
    """Which matches from view ``i`` to view ``j`` the ground truth confirms: a bool mask.

    A match (``src[k]`` in view i, ``dst[k]`` in view j) is correct when the true homography
    (:meth:`PanoramaSet.true_homography`) maps ``src[k]`` to within ``tol`` pixels of
    ``dst[k]`` (:func:`camlab.homography.transfer_error`).
    """
    if len(src) == 0:
        return np.zeros(0, bool)
    return transfer_error(data.true_homography(i, j), src, dst) < tol


def homographies_relative_to(graph: st.MatchGraph, reference: int) -> list:
    r"""The graph's homographies re-expressed relative to another reference image.

    ``graph.homographies[k]`` maps image k into the graph's reference;
    :math:`H_{r \leftarrow k} = H_{\text{ref} \leftarrow r}^{-1} H_{\text{ref} \leftarrow k}`,
    normalised to :math:`H_{33} = 1`.
    """
    to_ref = np.linalg.inv(graph.homographies[reference])
    return [normalize_homography(to_ref @ H) for H in graph.homographies]


# --------------------------------------------------------------------------- the canvas of each reference


class ReferenceCanvas(NamedTuple):
    """The quarter-size images warped onto the canvas of one reference image.

    Attributes
    ----------
    shape : (height, width)
        The canvas (:func:`camlab.warp.canvas_bounds`).
    T : (3, 3) ndarray
        The translation that moves the warped images into the canvas.
    homographies : list of (3, 3) ndarray
        canvas_from_image for every image: ``T`` times :func:`homographies_relative_to`
        (reference) in quarter-size pixels.
    panorama : (h, w, 3) float32 ndarray
        The images painted one after the other (``"overwrite"`` blend).
    """

    shape: tuple
    T: np.ndarray
    homographies: list
    panorama: np.ndarray


class ReferenceCanvases(NamedTuple):
    """Every image warped onto the canvas of each possible reference image, at quarter size.

    Attributes
    ----------
    images : list of (120, 160, 3) float32 ndarray
        The prepared images of :func:`panorama_example` at half their size (``cv2.INTER_AREA``).
    canvases : dict[int, ReferenceCanvas]
        The canvas of each reference image.
    """

    images: list
    canvases: dict


@lru_cache(maxsize=1)
def reference_canvases() -> ReferenceCanvases:
    """The panorama canvas for every choice of reference image (cached, read-only; see :class:`ReferenceCanvases`).

    Quarter size (160 x 120 images) so that even the widest canvas is small.
    """
    import cv2

    imgs = panorama_example().images
    graph = panorama_graph()
    small = [
        cv2.resize(im, (im.shape[1] // 2, im.shape[0] // 2), interpolation=cv2.INTER_AREA)
        for im in imgs
    ]
    S = scale_intrinsics(np.eye(3), 0.5)  # quarter-size pixels from half-size pixels
    canvases = {}
    for ref in range(len(imgs)):
        chain = [S @ H @ np.linalg.inv(S) for H in homographies_relative_to(graph, ref)]
        wi = st.warp_images(small, chain, max_pixels=3_000_000)
        canvases[ref] = ReferenceCanvas(
            tuple(wi.shape), wi.T, wi.homographies, st.blend(wi, "overwrite")
        )
    return read_only(ReferenceCanvases(small, canvases))


# --------------------------------------------------------------------------- blending two exposures


class ExposurePair(NamedTuple):
    """Views 1 and 2 of :func:`panorama_example` (exposures differ by 30%) on their common canvas.

    Attributes
    ----------
    warped : camlab.stitching.WarpedImages
        Both views warped relative to view 1 (:func:`homographies_relative_to`).
    gains : (2,) ndarray
        Their exposure gains (:func:`camlab.stitching.gain_compensation`, view 1 fixed).
    seam : (h, w) bool ndarray
        View 1's Voronoi seam mask (:func:`camlab.stitching.seam_masks`): the middle of the overlap.
    """

    warped: st.WarpedImages
    gains: np.ndarray
    seam: np.ndarray


@lru_cache(maxsize=1)
def exposure_pair() -> ExposurePair:
    """Images 1 and 2 (half size) warped onto their common canvas, their gains and seam (cached, read-only)."""
    imgs = panorama_example().images
    Hs = homographies_relative_to(panorama_graph(), 1)
    wi = _with_canvases(st.warp_images([imgs[1], imgs[2]], [Hs[1], Hs[2]]))
    return read_only(
        ExposurePair(wi, st.gain_compensation(wi, reference=0), st.seam_masks(wi.weights)[0])
    )


class BlendedPair(NamedTuple):
    """One blend of :func:`exposure_pair`.

    Attributes
    ----------
    image : (h, w, 3) float32 ndarray
        The blended canvas, in [0, 1].
    seam_step : float
        The mean brightness step across the seam (:func:`camlab.stitching.seam_step`), in
        the image's units: across the border of the image painted last for
        ``"overwrite"``, across the middle seam otherwise.
    """

    image: np.ndarray
    seam_step: float


@lru_cache(maxsize=1)
def pair_blends() -> dict:
    """Every blend of :func:`exposure_pair` the blending demo offers (cached, read-only).

    Returns
    -------
    dict[(method, gains, levels), BlendedPair]
        ``method`` in :data:`camlab.stitching.BLENDS`, ``gains`` whether the exposure gains
        are applied, ``levels`` the pyramid levels (1-6) for ``"multiband"`` and 0 otherwise.
    """
    wi, gains, seam = exposure_pair()
    both = wi.masks[0] & wi.masks[1]
    out = {}
    for m in st.BLENDS:
        for g in (False, True):
            for lv in range(1, 7) if m == "multiband" else (5,):
                image = st.blend(wi, m, gains=gains if g else None, levels=lv)
                step = (
                    st.seam_step(image, wi.masks[1], wi.masks[0])
                    if m == "overwrite"
                    else st.seam_step(image, seam, both)
                )
                out[(m, g, lv if m == "multiband" else 0)] = BlendedPair(image, step)
    return read_only(out)


# --------------------------------------------------------------------------- full panoramas


@lru_cache(maxsize=1)
def stitched_panoramas() -> dict:
    """{"planar" | "cylindrical": :class:`camlab.stitching.StitchResult`} of the half-size set, multi-band blended (cached, read-only)."""
    s = panorama_example().data
    return read_only(
        {
            proj: st.stitch(s.images, projection=proj, blend_method="multiband", max_features=1500)
            for proj in ("planar", "cylindrical")
        }
    )


class WideSweep(NamedTuple):
    """The 200-degree sweep and its panorama.

    Attributes
    ----------
    data : TurningSet
        Six views of :func:`camlab.data.panorama.turning_set` ``"wide"``, 360 x 264, f = 200 px.
    result : camlab.stitching.StitchResult
        The spherical stitch (overwrite blend), whose ``cameras`` are bundle-adjusted.
    """

    data: TurningSet
    result: st.StitchResult


@lru_cache(maxsize=1)
def wide_sweep() -> WideSweep:
    """The 200-degree sweep (six views, 360 x 264, f = 200 px) with its bundle-adjusted cameras (cached, read-only)."""
    s = turning_set("wide", size=(360, 264), f=200.0)
    return read_only(
        WideSweep(s, st.stitch(s.images, projection="spherical", blend_method="overwrite"))
    )


class CanvasPreview(NamedTuple):
    """The first ``views`` images of :func:`wide_sweep` pasted onto one kind of canvas.

    Attributes
    ----------
    image : (h, w, 3) uint8 ndarray or None
        The canvas (overwrite, at 3/4 of the focal length), scaled down to fit the
        ``max_shape`` asked for; None if the canvas cannot hold the views.
    shape : (height, width) or None
        The canvas before scaling.
    fov_deg : float
        The horizontal field of view the views span, degrees.
    reason : str
        Why the canvas cannot hold the views ("" if it can).
    """

    image: np.ndarray | None
    shape: tuple | None
    fov_deg: float
    reason: str


def canvas_previews(max_shape: tuple[int, int] = (220, 560)) -> dict:
    """{(views, projection): CanvasPreview} for the first 2-6 views of :func:`wide_sweep` on every canvas (cached, read-only).

    Every image is warped with the estimated cameras (:mod:`camlab.stitching.projections`),
    on a canvas centred on those views (:func:`camlab.stitching.cameras.wave_correct`),
    and pasted over the previous ones. A preview is for looking at: each canvas is kept
    as 8-bit RGB scaled down (``cv2.INTER_AREA``) to fit ``max_shape`` (height, width),
    not at full resolution (the plane under three views is 1067 x 2316 pixels).
    """
    return _canvas_previews(check_shape(max_shape, "max_shape"))


@lru_cache(maxsize=4)
def _canvas_previews(max_shape: tuple[int, int]) -> dict:
    import cv2

    from ..stitching import projections as pj
    from ..stitching.cameras import wave_correct

    s, r = wide_sweep()
    imgs = st.prepare_images(s.images)
    out = {}
    for n in range(2, 7):
        Ks = [r.cameras[k][0] for k in range(n)]
        Rs = wave_correct(
            [r.cameras[k][1] for k in range(n)]
        )  # the canvas centred on these n views
        scale = 0.75 * float(np.median([K[0, 0] for K in Ks]))
        # the yaws the views span, plus one view's own width: 2 atan((w / 2) / f)
        fov = float(
            np.ptp(s.angles_deg[:n, 0])
            + np.degrees(2 * np.arctan(imgs[0].shape[1] / 2 / s.K[0, 0]))
        )
        for proj in pj.PROJECTIONS:
            try:
                canvas = pj.make_canvas(
                    Ks, Rs, [im.shape for im in imgs[:n]], proj, scale, max_pixels=3_000_000
                )
            except (DegenerateError, CamlabInputError) as exc:
                out[(n, proj)] = CanvasPreview(
                    None, None, fov, str(exc).split(";")[0].replace("footprint: ", "")
                )
                continue
            pano = np.zeros((*canvas.shape, 3), np.float32)
            for im, K, R, box in zip(imgs[:n], Ks, Rs, canvas.boxes, strict=True):
                patch, mask, _ = pj.warp_to_canvas(im, K, R, canvas, box)
                r0, r1, c0, c1 = box
                pano[r0:r1, c0:c1][mask] = patch[mask]
            h, w = canvas.shape
            k = min(max_shape[0] / h, max_shape[1] / w)
            small = cv2.resize(
                np.clip(np.rint(pano * 255), 0, 255).astype(np.uint8),
                (max(1, int(w * k)), max(1, int(h * k))),
                interpolation=cv2.INTER_AREA,
            )
            out[(n, proj)] = CanvasPreview(small, (h, w), fov, "")
    return read_only(out)


# --------------------------------------------------------------------------- parallax


class ParallaxPair(NamedTuple):
    """Two views of the room, the second camera turned 12 degrees and moved sideways.

    Attributes
    ----------
    warped : camlab.stitching.WarpedImages
        Both views on one canvas, view 1 mapped onto view 0 by the estimated homography.
    registration : camlab.stitching.PairRegistration
        View 1 registered onto view 0 (RANSAC locks onto the dominant plane, the back wall).
    blends : dict[str, (h, w, 3) float32 ndarray]
        The ``"feather"`` and ``"multiband"`` blends of ``warped``.
    edges : tuple of two (h, w) bool ndarray
        :func:`edge_masks` of ``warped``.
    misalignment : float
        Mean absolute difference of the views where both cover the canvas
        (:func:`camlab.stitching.overlap_difference`), in [0, 1] units.
    """

    warped: st.WarpedImages
    registration: st.PairRegistration
    blends: dict
    edges: tuple
    misalignment: float


class EdgeMasks(NamedTuple):
    """:func:`edge_masks`: bool (h, w) canvas masks of the edges of warped views ``first`` and ``second``."""

    first: np.ndarray
    second: np.ndarray


def edge_masks(warped: st.WarpedImages) -> EdgeMasks:
    """Canny edges (``cv2.Canny``, thresholds 60 and 140 on the grey levels) of the first two warped views, bool masks on the canvas."""
    import cv2

    return EdgeMasks(
        *(
            cv2.Canny(np.clip(im.mean(axis=2) * 255, 0, 255).astype(np.uint8), 60, 140) > 0
            for im in warped.images[:2]
        )
    )


@lru_cache(maxsize=1)
def parallax_pairs() -> dict:
    """{baseline: ParallaxPair} for every baseline of :data:`BASELINES` (cached, read-only).

    The room (:func:`camlab.data.panorama.room_scene`) rendered without noise at the size
    and ``K`` of :func:`panorama_example` by a camera at the origin turned -16 degrees and
    one turned -4 degrees whose centre moved ``baseline`` metres to the right. The
    homography is estimated from the matches (threshold 2 px).
    """
    s = panorama_example().data
    K = s.K
    size = (s.images[0].shape[1], s.images[0].shape[0])
    scene = room_scene()
    R0 = cam_from_world(np.radians(-16.0))
    R1 = cam_from_world(np.radians(-4.0))
    # the second camera's centre moves b metres to the right: t = -R1 c1 with c1 = (b, 0, 0)
    views = [render_view(R0, K=K, size=size, noise=False, scene=scene)]
    views += [
        render_view(R1, t=-R1 @ np.array([b, 0.0, 0.0]), K=K, size=size, noise=False, scene=scene)
        for b in BASELINES
    ]
    img0, *moved = st.prepare_images(views)
    f0 = ft.detect_features(img0, max_features=1500)
    out = {}
    for b, img1 in zip(BASELINES, moved, strict=True):
        f1 = ft.detect_features(img1, max_features=1500)
        reg = st.register_pair(f1, f0, threshold=2.0)
        wi = _with_canvases(st.warp_images([img0, img1], [np.eye(3), reg.H]))
        blends = {m: st.blend(wi, m) for m in ("feather", "multiband")}
        out[b] = ParallaxPair(wi, reg, blends, edge_masks(wi), st.overlap_difference(wi))
    return read_only(out)
