"""Stitching stage 4: which model explains the matches, a turning camera or a flat scene.

A camera that turns about its centre is explained by rotations
(:func:`camlab.stitching.cameras.estimate_cameras`); a plane seen from several places (a map,
a document, a facade) by homographies refined together
(:func:`camlab.stitching.cameras.adjust_homographies`). :func:`choose_model` tries the first,
then the second when the first fits badly, and warns when neither fits (parallax).

See :mod:`camlab.stitching` for the whole pipeline.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from .cameras import adjust_homographies, estimate_cameras, estimate_focal, inlier_matches

__all__ = ["ModelChoice", "choose_model"]


class ModelChoice(NamedTuple):
    """The model :func:`choose_model` chose for the images in the panorama.

    Attributes
    ----------
    keep : list of int
        The images in the panorama (those the match graph connects).
    model : str
        ``"rotation"`` (a turning camera) or ``"homography"`` (a plane seen from several places).
    residual : float
        The chosen model's RMS transfer error over the inlier matches, pixels.
    cameras : CameraEstimate or None
        The rotation model's cameras (None when the views were too narrow to try it).
    Ks, Rs : lists of (3, 3) ndarray or None
        Intrinsics and cam_from_world rotations of the kept images (None each for the plane).
    plane : list of (3, 3) ndarray or None
        reference_from_image homographies of every image, for the plane model only.
    bundle_seconds : float
        Time spent in bundle adjustment (of the cameras and of the homographies).
    adjustments : tuple of str
        One line per adjustment run (model, iterations, stopping rule, RMS, seconds).
    """

    keep: list
    model: str
    residual: float
    cameras: object
    Ks: list
    Rs: list
    plane: list | None
    bundle_seconds: float
    adjustments: tuple


def choose_model(
    graph,
    shapes: Sequence[Sequence[int]],
    K: np.ndarray | None,
    projection: str,
    tolerances: tuple[float, float],
    coarse: float = 1.0,
) -> ModelChoice:
    """A turning camera (rotations), or a plane seen from several places (homographies).

    The plane replaces the rotation when the rotation fits badly and the plane clearly better
    (residual below 0.7 times the rotation's), or when the focal length the pairs imply (their
    median) is over 2 image diagonals (the median image's), that is, the views are under
    2 atan(1/4) = 28.1 degrees across the diagonal, where a flat scene passes for a rotation and
    its adjustment crawls (only without a known ``K``, and for ``"auto"`` or ``"planar"``).
    ``tolerances`` are the RMS residuals (pixels) above which the rotation, then the plane, is
    judged not to fit; residuals are in full-resolution pixels and features found on
    copies ``coarse`` times smaller are that much less precise, so the tolerances grow with it.
    Warns (for :func:`camlab.stitching.stitch`) when neither model fits.

    Parameters
    ----------
    graph : MatchGraph
        The pairwise registrations and the spanning tree (:func:`match_graph`).
    shapes : sequence of (h, w)
        Every image's shape, full-resolution pixels.
    K : (3, 3) ndarray or None
        Known intrinsics shared by all images (the focal is then not estimated).
    projection : {"auto", "planar", "cylindrical", "spherical"}
        The canvas asked for: only ``"auto"`` and ``"planar"`` let the plane model be tried.
    tolerances : (2,) tuple of float
        (rotation, plane): RMS residuals, pixels, above which each model is judged not to fit.
    coarse : float
        How many times smaller the copies the features were found on are (>= 1 scales the
        tolerances).

    Returns
    -------
    ModelChoice
        ``keep``, ``model`` (``"rotation"`` or ``"homography"``), ``residual`` (pixels),
        ``cameras``, ``Ks``, ``Rs``, ``plane`` and ``bundle_seconds``.

    Warns
    -----
    UserWarning
        Neither model fits, or the rotation model does not fit and the plane was not tried.
    """
    keep = [k for k in range(len(shapes)) if graph.homographies[k] is not None]
    diag = float(np.median([np.hypot(*sh[:2]) for sh in shapes]))
    f0 = estimate_focal({key: p.H for key, p in graph.pairs.items() if p.accepted}, shapes)
    telephoto = K is None and f0 > 2 * diag and projection in ("auto", "planar")
    est = None if telephoto else estimate_cameras(graph, shapes, K=K)
    rot_rms = np.inf if est is None else est.bundle.rms_after
    rot_tol, pl_tol = (tol * max(1.0, coarse) for tol in tolerances)
    model, resid, adj, plane = "rotation", rot_rms, None, None
    if (telephoto or rot_rms > rot_tol) and projection in ("auto", "planar"):
        adj = adjust_homographies(
            graph.homographies, inlier_matches(graph, 100), reference=graph.reference
        )
        if (
            telephoto or adj.rms_after < 0.7 * rot_rms
        ):  # a plane explains the matches clearly better
            model, plane, resid = "homography", adj.homographies, adj.rms_after
        if adj.rms_after > pl_tol and rot_rms > rot_tol:
            warnings.warn(
                f"stitch: neither a turning camera (rotation model residual {rot_rms:.2f} px) nor a flat "
                f"scene (homography residual {adj.rms_after:.2f} px) explains the matches: the camera "
                f"moved in front of a 3-D scene (parallax); expect ghosts and misaligned seams",
                UserWarning,
                stacklevel=3,
            )
    elif rot_rms > rot_tol:
        warnings.warn(
            f"stitch: the rotation model leaves {rot_rms:.2f} px RMS (more than {rot_tol:.2f} px): the "
            f"camera moved (parallax) or the scene is flat; try projection='planar'",
            UserWarning,
            stacklevel=3,
        )
    rotation = model == "rotation"
    Ks = [est.Ks[k] for k in keep] if rotation else [None] * len(keep)
    Rs = [est.Rs[k] for k in keep] if rotation else [None] * len(keep)
    seconds = (0.0 if est is None else est.bundle.seconds) + (0.0 if adj is None else adj.seconds)
    runs = [("rotation model", est.bundle)] if est is not None else []
    runs += [("homographies", adj)] if adj is not None else []
    adjustments = tuple(
        f"{what}: {r.iterations} Levenberg-Marquardt iterations, stopped: {r.message}; "
        f"RMS {r.rms_before:.3f} -> {r.rms_after:.3f} px in {r.seconds:.3f} s"
        for what, r in runs
    )
    return ModelChoice(keep, model, float(resid), est, Ks, Rs, plane, seconds, adjustments)
