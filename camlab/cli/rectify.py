r"""``camlab rectify LEFT RIGHT --out-dir D``.

A stereo pair rectified from its matches (or from a calibration), with a vertical-disparity figure.
"""

from __future__ import annotations

import argparse

from .._validate import CamlabInputError
from .photos import check_positive_megapixels, read_photo_or_fail, within_work_size, write_image

__all__ = []


def add_rectify(p: argparse.ArgumentParser) -> None:
    """The arguments of ``camlab rectify``: the two photos, ``--out-dir``, ``--threshold``, ``--calibration`` and ``--max-megapixels``.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The subcommand's parser; its arguments are added in place.
    """
    p.add_argument("left", help="left photo")
    p.add_argument("right", help="right photo (same size)")
    p.add_argument(
        "--out-dir",
        required=True,
        help="folder for left_rectified.png, right_rectified.png and "
        "vertical_disparity.png (created if missing)",
    )
    p.add_argument(
        "--threshold", type=float, default=1.0, help="RANSAC threshold for F, pixels (default 1)"
    )
    p.add_argument(
        "--calibration",
        help="calibration of the camera that took both photos (from `camlab calibrate`): "
        "rectify from its intrinsics and the relative pose (works on flat scenes too)",
    )
    p.add_argument(
        "--max-megapixels",
        type=float,
        default=4.0,
        help="shrink larger photos to this size first (default 4; phone photos are 12-50)",
    )


def run_rectify(args: argparse.Namespace) -> int:
    """Rectify a stereo pair from its matches (SIFT, F by RANSAC, Hartley), or with the camera's calibration.

    Writes ``left_rectified.png``, ``right_rectified.png`` and ``vertical_disparity.png`` (the
    histograms of |v1 - v2| of the inliers before and after) into ``--out-dir``. Without a
    calibration, matches that one homography explains (a flat scene) are refused: F is not
    determined by them.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed arguments of ``camlab rectify`` (:func:`add_rectify`).

    Returns
    -------
    int
        The exit status: 0.

    Raises
    ------
    CamlabInputError
        On an error the user can fix; :func:`camlab.cli.main` prints it and exits with status 2.

    References
    ----------
    .. [1] R. Hartley, 1999, "Theory and practice of projective rectification", International
       Journal of Computer Vision 35(2).
    """
    import numpy as np

    from .. import epipolar, features
    from .. import rectification as rc
    from .._files import check_not_an_input, check_output_path, output_folder
    from ..calibration import load_calibration
    from ..projective import map_points

    out_dir = output_folder(args.out_dir, "--out-dir")
    outputs = {
        k: check_output_path(out_dir / f"{k}.png", "--out-dir")
        for k in ("left_rectified", "right_rectified", "vertical_disparity")
    }
    check_not_an_input(
        outputs.values(), "--out-dir", [args.left, args.right], "choose another folder"
    )
    check_positive_megapixels(args.max_megapixels)
    calibration = (
        None
        if args.calibration is None
        else load_calibration(args.calibration, name="--calibration")
    )
    pair = [
        read_photo_or_fail(path, name)
        for name, path in (("left", args.left), ("right", args.right))
    ]
    if pair[0].shape != pair[1].shape:
        raise CamlabInputError(
            f"right: expected the left photo's size {pair[0].shape[1]} x {pair[0].shape[0]}, "
            f"got {pair[1].shape[1]} x {pair[1].shape[0]}"
        )
    full_width = pair[0].shape[1]
    pair = [
        within_work_size(im, args.max_megapixels, path)
        for im, path in zip(pair, (args.left, args.right), strict=True)
    ]
    m = features.match_features(*(features.detect_features(im) for im in pair))
    fit = epipolar.ransac_fundamental_matrix(
        m.src, m.dst, threshold=args.threshold, rng=np.random.default_rng(0)
    )
    x1, x2 = m.src[fit.inliers], m.dst[fit.inliers]
    size = (pair[0].shape[1], pair[0].shape[0])
    if calibration is None:
        _refuse_a_plane(x1, x2, args.threshold)
        rect = rc.rectify_uncalibrated(x1, x2, fit.F, size)
        moved = (map_points(rect.H1, x1), map_points(rect.H2, x2))
    else:
        rect, x1, x2, moved = _rectify_calibrated_pair(
            calibration, size[0] / full_width, m.src, m.dst, size
        )
    before = rc.vertical_disparity(x1, x2)
    after = rc.vertical_disparity(*moved)
    left, right = rc.rectify_images(rect, *pair)
    write_image(outputs["left_rectified"], left, "--out-dir")
    write_image(outputs["right_rectified"], right, "--out-dir")
    _vertical_disparity_figure(before, after, outputs["vertical_disparity"])
    model = "F" if calibration is None else "the pose"
    print(
        f"camlab rectify: {len(m.src)} matches, {len(x1)} consistent with {model}; vertical disparity median "
        f"{before.median:.2f} px before, {after.median:.2f} px after (95th percentile {after.p95:.2f} px)"
    )
    print(f"wrote {', '.join(str(p) for p in outputs.values())}")
    return 0


PLANE_SHARE = (
    0.9  # a real scene with depth: 40-75 % of the bundled pairs' matches fit one homography
)


def _refuse_a_plane(x1, x2, threshold: float) -> None:
    """Refuse matches that one homography explains: F is not determined by points on one plane.

    For points on a plane every F = [e']x H with any e' fits, so RANSAC returns one of a
    family and the rectification built from it is rotated or squashed at random.
    """
    import numpy as np

    from .._validate import DegenerateError
    from ..homography import ransac_homography

    try:
        fit = ransac_homography(x1, x2, 2 * threshold, 0.999, 2000, np.random.default_rng(0))
    except DegenerateError:
        return
    k = int(fit.inliers.sum())
    if k > PLANE_SHARE * len(x1):
        raise DegenerateError(
            f"left, right: {k} of the {len(x1)} matches ({100 * k / len(x1):.0f}%) fit one homography within "
            f"{2 * threshold:g} px: they lie on one plane (a flat board, a wall, the ground seen from far away), and "
            f"points on one plane do not determine the epipolar geometry, so a rectification from the matches alone "
            f"would be arbitrary. Rectify with the camera's calibration instead: --calibration cal.yaml (from "
            f"`camlab calibrate`), or photograph a scene with depth"
        )


def _rectify_calibrated_pair(calibration, scale: float, src, dst, size):
    """Rectification from the camera's K and dist and the relative pose found from the matches.

    Also the matches the pose explains, and where they land in the rectified pair.

    The essential matrix comes from the five-point algorithm (``cv2.findEssentialMat``),
    which, unlike the eight-point F, is determined by points on one plane; the pose is the
    decomposition that puts the points in front of both cameras (:func:`camlab.epipolar.recover_pose`).
    """
    import cv2
    import numpy as np

    from .. import rectification as rc
    from ..camera import Camera, scale_intrinsics
    from ..distortion import undistort_pixels
    from ..epipolar import recover_pose

    K, dist, cal_size = calibration
    if round(cal_size[0] * scale) != size[0] or round(cal_size[1] * scale) != size[1]:
        raise CamlabInputError(
            f"--calibration: it is for {cal_size[0]} x {cal_size[1]} photos, but these are "
            f"{round(size[0] / scale)} x {round(size[1] / scale)}; calibrate this camera at this size"
        )
    K = scale_intrinsics(K, scale) if scale != 1 else K
    u1, u2 = undistort_pixels(src, K, dist), undistort_pixels(dst, K, dist)
    E, inl = cv2.findEssentialMat(u1, u2, K, cv2.RANSAC, 0.999, 1.0)
    if E is None or E.shape != (3, 3):
        raise CamlabInputError(
            "left, right: no relative pose fits the matches; are these two views of one scene?"
        )
    keep = inl.ravel() > 0
    pose = recover_pose(E, u1[keep], u2[keep], K)
    cams = [
        Camera(K, np.eye(3), np.zeros(3), tuple(dist), size),
        Camera(K, pose.R, pose.t, tuple(dist), size),
    ]
    rect = rc.rectify_calibrated(*cams, alpha=0.0, image_size=size)
    x1, x2 = src[keep], dst[keep]
    return (
        rect,
        x1,
        x2,
        (rc.rectify_points(rect, cams[0], x1, 1), rc.rectify_points(rect, cams[1], x2, 2)),
    )


def _vertical_disparity_figure(before, after, path) -> None:
    """Histograms of |v1 - v2| of the inlier matches before and after rectification."""
    import numpy as np
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from .._files import atomic_output
    from ..plotting import palette

    fig = Figure(figsize=(6, 3), dpi=100, layout="constrained")
    FigureCanvasAgg(fig)
    ax = fig.subplots()
    top = max(float(np.percentile(before.values, 99)), 1.0)
    bins = np.linspace(0, top, 40)
    ax.hist(
        np.clip(before.values, 0, top),
        bins=bins,
        color=palette.BEFORE,
        alpha=0.6,
        label=f"before (median {before.median:.1f} px)",
    )
    ax.hist(
        np.clip(after.values, 0, top),
        bins=bins,
        color=palette.AFTER,
        alpha=0.8,
        hatch="//",
        label=f"after (median {after.median:.2f} px)",
    )
    ax.set(xlabel="vertical disparity |v1 - v2| of inlier matches (px)", ylabel="matches")
    ax.legend()
    with atomic_output(path, "--out-dir") as tmp:
        fig.savefig(tmp)
