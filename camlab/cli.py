"""The ``camlab`` command line: ``camlab <command> ...``.

Commands are registered in :data:`COMMANDS` (name -> (add_arguments, run)); to add one,
write ``_add_<name>(parser)`` and ``_run_<name>(args) -> int`` and register them. Errors a
user can fix (bad pattern, no images, too few detections) are printed as one clear
message with exit status 2, never a traceback.

``camlab lessons [DEST] [--force]`` copies the lessons into a working folder (see
:mod:`camlab.course`); ``camlab --version`` prints the version.

``camlab calibrate "photos/*.jpg" --pattern 9x6 --square 0.025 [--out camera.json]
[--report report.png]`` detects the chessboard in each photo, calibrates, prints the result
and the coach's advice, writes an OpenCV-loadable file (``cv2.FileStorage``: ``.json``,
``.yaml`` or ``.xml``) and saves a report figure.

``camlab undistort``, ``camlab stitch FOLDER --out pano.jpg [--projection ...]`` and
``camlab rectify LEFT RIGHT --out-dir D`` work on real photos: each prints a line per image
or pair, exits 0 when everything was used, 1 when some input was left out (and says which),
2 on an error the user can fix; outputs are checked before any work (never one of the inputs)
and written atomically. Photos are read by one reader (:func:`camlab._files.read_photo`:
upright by their EXIF orientation, truncated files refused by name); ``stitch`` and
``rectify`` shrink photos above ``--max-megapixels``; ``rectify --calibration CAL`` rectifies
from the camera's calibration, which also works where the matches lie on one plane.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable

from ._validate import CamlabInputError, ConvergenceError

__all__ = ["COMMANDS", "build_parser", "main"]


def _add_calibrate(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "images", nargs="+", help='image files or a quoted glob pattern, e.g. "photos/*.jpg"'
    )
    p.add_argument(
        "--pattern",
        required=True,
        help="inner corners COLSxROWS, e.g. 9x6 for a board of 10 x 7 squares",
    )
    p.add_argument(
        "--square", required=True, type=float, help="side of one square in metres, e.g. 0.025"
    )
    p.add_argument(
        "--out",
        default="calibration.json",
        help="result file (.json, .yaml or .xml; default calibration.json)",
    )
    p.add_argument(
        "--report",
        default="calibration_report.png",
        help="report figure (default calibration_report.png)",
    )
    p.add_argument("--no-report", action="store_true", help="do not save a report figure")
    p.add_argument(
        "--fix-k3",
        action="store_true",
        help="keep k3 = 0 (recommended for ordinary lenses with few views)",
    )
    p.add_argument("--skew", action="store_true", help="also estimate the skew (OpenCV never does)")


def _expand(patterns: list[str]) -> list[str]:
    import glob

    files: list[str] = []
    for pat in patterns:
        if any(ch in pat for ch in "*?["):
            matched = sorted(glob.glob(pat))
            if not matched:
                raise CamlabInputError(f"images: no files match {pat!r}")
            files += matched
        else:
            files.append(pat)
    return files


def _progress(i: int, n: int, name: str, failure: str | None) -> None:
    """One line per image, or a bar redrawn in place on a terminal."""
    verdict = "board found" if failure is None else f"skipped: {failure.split(':')[0]}"
    if sys.stdout.isatty():
        bar = "#" * round(24 * i / n)
        print(f"\r[{bar:<24}] {i}/{n} {name[-40:]:<40}", end="" if i < n else "\n", flush=True)
    else:
        print(f"  [{i}/{n}] {name}: {verdict}", flush=True)


def _run_calibrate(args: argparse.Namespace) -> int:
    from ._files import check_not_an_input, check_output_path
    from .calibration import calibrate_from_images, coach, parse_pattern, save_calibration
    from .calibration.io import SUFFIXES

    pattern = parse_pattern(args.pattern, "--pattern")
    check_output_path(
        args.out, "--out", SUFFIXES
    )  # before any work: nothing is written if one fails
    if not args.no_report:
        check_output_path(args.report, "--report", (".png", ".pdf", ".svg", ".jpg"))
    files = _expand(args.images)
    outputs = {"--out": args.out} | ({} if args.no_report else {"--report": args.report})
    for flag, path in outputs.items():
        check_not_an_input([path], flag, files, "give the result another name")
    print(
        f"camlab calibrate: {len(files)} images, pattern {pattern[0]}x{pattern[1]} inner corners, "
        f"square {args.square} m"
    )
    out = calibrate_from_images(
        files,
        pattern,
        args.square,
        skew=args.skew,
        fix=("k3",) if args.fix_k3 else (),
        progress=_progress,
    )
    print(out.report())
    result = out.result
    print(result.summary())
    report = coach(result)
    worst = ", ".join(
        f"view {v} ({files[out.used[v]]}) {result.per_view_rms[v]:.2f} px"
        for v in report.worst_views[:3]
    )
    print(f"worst views: {worst}")
    print("advice:")
    print(report.text())
    if not args.no_report:  # the figure first: if it fails, no result file is left behind
        from ._files import atomic_output
        from .plotting.calibration import report_figure

        fig = report_figure(result, report)
        with atomic_output(args.report, "--report") as tmp:
            fig.savefig(tmp, dpi=90)
    path = save_calibration(result, args.out, name="--out")
    print(
        f"wrote {path} (load in OpenCV: cv2.FileStorage(path, cv2.FILE_STORAGE_READ).getNode('camera_matrix').mat())"
    )
    if not args.no_report:
        print(f"saved report figure {args.report}")
    return 0


def _add_undistort(p: argparse.ArgumentParser) -> None:
    p.add_argument("images", nargs="+", help='photos or a quoted glob pattern, e.g. "photos/*.jpg"')
    p.add_argument(
        "--calibration",
        required=True,
        help="calibration file from `camlab calibrate` (.json/.yaml/.xml)",
    )
    p.add_argument(
        "--out-dir",
        required=True,
        help="folder for the undistorted images (same file names; created if missing)",
    )
    p.add_argument(
        "--alpha",
        type=float,
        default=0.0,
        help="0: crop to valid pixels (no black corners, default); 1: keep every source pixel",
    )


def _run_undistort(args: argparse.Namespace) -> int:
    """Undistort each photo with the calibration; exit 1 if some could not be read or written."""
    from pathlib import Path

    import cv2

    from ._files import atomic_output, check_not_an_input, check_output_path, output_folder
    from .calibration import load_calibration, undistort

    K, dist, size = load_calibration(args.calibration, name="--calibration")
    out_dir = output_folder(args.out_dir, "--out-dir")
    check_output_path(out_dir / "probe.png", "--out-dir")
    files = _expand(args.images)
    check_not_an_input(
        [out_dir / Path(f).name for f in files],
        "--out-dir",
        files,
        f"the undistorted photos keep their names, so write them to another folder, e.g. "
        f"--out-dir {str(out_dir / 'undistorted')!r}",
    )
    failed = 0
    for i, name in enumerate(files, 1):
        img = _read_or_skip(name, "stored", f"[{i}/{len(files)}] ")
        if img is None:
            failed += 1
            continue
        if (img.shape[1], img.shape[0]) != size:
            print(
                f"  [{i}/{len(files)}] {name}: skipped: {img.shape[1]} x {img.shape[0]} pixels (upright), but the "
                f"calibration is for {size[0]} x {size[1]}",
                flush=True,
            )
            failed += 1
            continue
        try:
            res = undistort(img, K=K, dist=dist, alpha=args.alpha)
        except (
            ConvergenceError
        ) as exc:  # the lens model folds back inside the photo: no inverse there
            raise CamlabInputError(
                f"--calibration: the distortion in {args.calibration!r} cannot be undone over the "
                f"whole photo ({str(exc).split(';')[0]}); calibrate again with more views that "
                f"reach the photo's corners, or with --fix-k3"
            ) from None
        target = out_dir / Path(name).name
        with atomic_output(target, "--out-dir") as tmp:
            if not cv2.imwrite(str(tmp), res.image):
                raise CamlabInputError(f"--out-dir: could not write {str(target)!r}")
        print(
            f"  [{i}/{len(files)}] {name} -> {target} ({100 * res.black_fraction:.1f}% black, "
            f"{100 * res.lost_fraction:.1f}% of the photo cropped)",
            flush=True,
        )
    print(f"camlab undistort: {len(files) - failed} of {len(files)} images written to {out_dir}")
    return 1 if failed else 0


def _read_or_skip(path: str, mode: str, prefix: str = ""):
    """The photo (upright, see :func:`camlab._files.read_photo`), or None after a line saying why it is skipped."""
    from ._files import PhotoReadError, read_photo

    try:
        return read_photo(path, mode)
    except PhotoReadError as exc:
        print(f"  {prefix}{path}: skipped: {exc.reason}", flush=True)
        return None


def _within_work_size(image, max_megapixels: float, name: str):
    """``image`` shrunk (area averaging) to at most ``max_megapixels``, saying so; else ``image`` itself.

    Phone photos of 40 megapixels would take minutes and gigabytes to register and blend;
    the geometry needs far fewer pixels.
    """
    import cv2

    h, w = image.shape[:2]
    s = (max_megapixels * 1e6 / (h * w)) ** 0.5
    if s >= 1:
        return image
    size = (max(16, round(w * s)), max(16, round(h * s)))
    print(
        f"  {name}: {w} x {h} px ({w * h / 1e6:.0f} MP), worked on at {size[0]} x {size[1]} "
        f"(--max-megapixels {max_megapixels:g})",
        flush=True,
    )
    return cv2.resize(image, size, interpolation=cv2.INTER_AREA)


IMAGE_SUFFIXES = (".jpg", ".jpeg", ".png", ".tif", ".tiff", ".bmp")


def _photos(args_images: list[str]) -> list[str]:
    """Image files from folders (their images, sorted), files and quoted glob patterns."""
    from pathlib import Path

    files: list[str] = []
    for item in args_images:
        if Path(item).is_dir():
            found = sorted(
                str(p) for p in Path(item).iterdir() if p.suffix.lower() in IMAGE_SUFFIXES
            )
            if not found:
                raise CamlabInputError(
                    f"images: the folder {item!r} holds no {'/'.join(IMAGE_SUFFIXES)} files"
                )
            files += found
        else:
            files += _expand([item])
    return files


def _write_image(path, image_rgb_or_gray, name: str) -> None:
    import cv2

    from ._files import atomic_output

    image = (
        image_rgb_or_gray
        if image_rgb_or_gray.ndim == 2
        else cv2.cvtColor(image_rgb_or_gray, cv2.COLOR_RGB2BGR)
    )
    with atomic_output(path, name) as tmp:
        if not cv2.imwrite(str(tmp), image):
            raise CamlabInputError(f"{name}: could not write {str(path)!r}")


def _add_stitch(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "images", nargs="+", help="a folder of photos, photo files, or a quoted glob pattern"
    )
    p.add_argument("--out", required=True, help="the panorama (.jpg or .png)")
    p.add_argument(
        "--projection",
        choices=["auto", "planar", "cylindrical", "spherical"],
        default="auto",
        help="canvas: planar for a flat scene or a narrow turn, spherical for wide turns (default auto)",
    )
    p.add_argument(
        "--crop", action="store_true", help="crop to the largest rectangle without empty canvas"
    )
    p.add_argument(
        "--max-megapixels",
        type=float,
        default=4.0,
        help="shrink larger photos to this size first (default 4; phone photos are 12-50)",
    )


def _run_stitch(args: argparse.Namespace) -> int:
    """Stitch the photos; exit 1 if some could not be read or overlap nothing (named)."""
    import warnings
    from pathlib import Path

    from ._files import check_not_an_input, check_output_path
    from .stitching import stitch

    check_output_path(args.out, "--out", (".jpg", ".jpeg", ".png"))
    _check_positive_megapixels(args.max_megapixels)
    files = _photos(args.images)
    check_not_an_input([args.out], "--out", files, "give the panorama a name of its own")
    images, names, unreadable = [], [], []
    for name in files:
        img = _read_or_skip(name, "rgb")
        if img is None:
            unreadable.append(Path(name).name)
            continue
        images.append(_within_work_size(img, args.max_megapixels, name))
        names.append(Path(name).name)
    if len(images) < 2:
        raise CamlabInputError(f"images: need at least two readable photos, got {len(images)}")
    print(f"camlab stitch: {len(images)} photos, projection {args.projection}", flush=True)
    with warnings.catch_warnings(
        record=True
    ) as caught:  # one line each, not Python's warning format
        warnings.simplefilter("always")
        res = stitch(images, projection=args.projection, crop=args.crop, names=names)
    for w in caught:
        print(f"  warning: {w.message}")
    for pair in res.pairs:
        if pair.accepted:
            print(
                f"  {names[pair.i]} - {names[pair.j]}: {pair.inliers} of {pair.matches} matches agree, "
                f"rms {pair.residual_rms:.2f} px"
            )
    groups = [g for g in res.graph.groups() if len(g) > 1]
    if len(groups) > 1:
        print(
            f"  {len(groups)} separate groups of overlapping photos (stitch each on its own): "
            + "; ".join(" + ".join(names[k] for k in g) for g in groups)
        )
    left_out = [names[i] for i in res.unconnected]
    _write_image(args.out, res.panorama, "--out")
    h, w = res.panorama.shape[:2]
    print(
        f"wrote {args.out}: {w} x {h} px, {res.projection} canvas, {len(images) - len(left_out)} of "
        f"{len(images) + len(unreadable)} photos used"
        + (f"; left out: {', '.join(unreadable + left_out)}" if unreadable or left_out else "")
    )
    return 1 if unreadable or left_out else 0


def _check_positive_megapixels(value: float) -> None:
    if not value > 0.05:
        raise CamlabInputError(
            f"--max-megapixels: expected a size above 0.05 (megapixels), got {value}"
        )


def _add_rectify(p: argparse.ArgumentParser) -> None:
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


def _run_rectify(args: argparse.Namespace) -> int:
    """Rectify a stereo pair from its matches (SIFT, F by RANSAC, Hartley), or with the camera's calibration."""

    import numpy as np

    from . import epipolar, features
    from . import rectification as rc
    from ._files import check_not_an_input, check_output_path, output_folder
    from .calibration import load_calibration
    from .homography import map_points

    out_dir = output_folder(args.out_dir, "--out-dir")
    outputs = {
        k: check_output_path(out_dir / f"{k}.png", "--out-dir")
        for k in ("left_rectified", "right_rectified", "vertical_disparity")
    }
    check_not_an_input(
        outputs.values(), "--out-dir", [args.left, args.right], "choose another folder"
    )
    _check_positive_megapixels(args.max_megapixels)
    calibration = (
        None
        if args.calibration is None
        else load_calibration(args.calibration, name="--calibration")
    )
    pair = [
        _read_photo_or_fail(path, name)
        for name, path in (("left", args.left), ("right", args.right))
    ]
    if pair[0].shape != pair[1].shape:
        raise CamlabInputError(
            f"right: expected the left photo's size {pair[0].shape[1]} x {pair[0].shape[0]}, "
            f"got {pair[1].shape[1]} x {pair[1].shape[0]}"
        )
    full_width = pair[0].shape[1]
    pair = [
        _within_work_size(im, args.max_megapixels, path)
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
    _write_image(outputs["left_rectified"], left, "--out-dir")
    _write_image(outputs["right_rectified"], right, "--out-dir")
    _vertical_disparity_figure(before, after, outputs["vertical_disparity"])
    model = "F" if calibration is None else "the pose"
    print(
        f"camlab rectify: {len(m.src)} matches, {len(x1)} consistent with {model}; vertical disparity median "
        f"{before.median:.2f} px before, {after.median:.2f} px after (95th percentile {after.p95:.2f} px)"
    )
    print(f"wrote {', '.join(str(p) for p in outputs.values())}")
    return 0


def _read_photo_or_fail(path: str, name: str):
    from ._files import PhotoReadError, read_photo

    try:
        return read_photo(path, "rgb")
    except PhotoReadError as exc:
        raise CamlabInputError(f"{name}: {exc}") from None


PLANE_SHARE = (
    0.9  # a real scene with depth: 40-75 % of the bundled pairs' matches fit one homography
)


def _refuse_a_plane(x1, x2, threshold: float) -> None:
    """Refuse matches that one homography explains: F is not determined by points on one plane.

    For points on a plane every F = [e']x H with any e' fits, so RANSAC returns one of a
    family and the rectification built from it is rotated or squashed at random.
    """
    import numpy as np

    from ._validate import DegenerateError
    from .homography import ransac_homography

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
    """Rectification from the camera's K and dist and the relative pose found from the matches;
    also the matches the pose explains, and where they land in the rectified pair.

    The essential matrix comes from the five-point algorithm (``cv2.findEssentialMat``),
    which, unlike the eight-point F, is determined by points on one plane; the pose is the
    decomposition that puts the points in front of both cameras (:func:`camlab.epipolar.recover_pose`).
    """
    import cv2
    import numpy as np

    from . import rectification as rc
    from .camera import Camera, scale_intrinsics
    from .distortion import undistort_pixels
    from .epipolar import recover_pose

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

    from ._files import atomic_output

    fig = Figure(figsize=(6, 3), dpi=100, layout="constrained")
    FigureCanvasAgg(fig)
    ax = fig.subplots()
    top = max(float(np.percentile(before.values, 99)), 1.0)
    bins = np.linspace(0, top, 40)
    ax.hist(
        np.clip(before.values, 0, top),
        bins=bins,
        color="#BB5566",
        alpha=0.6,
        label=f"before (median {before.median:.1f} px)",
    )
    ax.hist(
        np.clip(after.values, 0, top),
        bins=bins,
        color="#004488",
        alpha=0.8,
        hatch="//",
        label=f"after (median {after.median:.2f} px)",
    )
    ax.set(xlabel="vertical disparity |v1 - v2| of inlier matches (px)", ylabel="matches")
    ax.legend()
    with atomic_output(path, "--out-dir") as tmp:
        fig.savefig(tmp)


def _add_lessons(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "dest",
        nargs="?",
        default="camlab-course",
        help="working folder (default ./camlab-course); lessons go to DEST/lessons, docs to DEST/docs",
    )
    p.add_argument(
        "--force",
        action="store_true",
        help="also replace lessons you have edited (yours are kept beside them as NN_name.mine-<date>.ipynb)",
    )


def _run_lessons(args: argparse.Namespace) -> int:
    from .course import copy_course

    print(copy_course(args.dest, force=args.force).text())
    return 0


def _add_assignments(p: argparse.ArgumentParser) -> None:
    p.add_argument("dest", help="a new (or empty) folder for the nbgrader course directory")
    p.add_argument(
        "lessons",
        nargs="*",
        metavar="LESSON",
        help="lesson numbers or names, e.g. 06 07 (default: all)",
    )


def _run_assignments(args: argparse.Namespace) -> int:
    from .classroom.assignments import write_course

    for stem, names in write_course(args.dest, args.lessons).items():
        print(
            f"{args.dest}/source/{stem}/{stem}.ipynb: exercises graded: {len(names)} ({', '.join(names)})"
        )
    print(f"next: cd {args.dest} && nbgrader generate_assignment <lesson>   (see docs/teaching.md)")
    return 0


def _add_present(p: argparse.ArgumentParser) -> None:
    p.add_argument("lesson", help="lesson number or name, e.g. 07")
    p.add_argument("--port", type=int, default=8866, help="port on 127.0.0.1 (default 8866)")
    p.add_argument("--no-browser", action="store_true", help="do not open a browser")


def _run_present(args: argparse.Namespace) -> int:
    from .classroom.present import serve

    return serve(args.lesson, port=args.port, open_browser=not args.no_browser)


COMMANDS: dict[
    str, tuple[str, Callable[[argparse.ArgumentParser], None], Callable[[argparse.Namespace], int]]
] = {
    "calibrate": ("calibrate a camera from photos of a chessboard", _add_calibrate, _run_calibrate),
    "undistort": ("undistort photos with a calibration file", _add_undistort, _run_undistort),
    "stitch": ("stitch overlapping photos into a panorama", _add_stitch, _run_stitch),
    "rectify": (
        "rectify a stereo pair from its matches, with a vertical-disparity figure",
        _add_rectify,
        _run_rectify,
    ),
    "lessons": (
        "copy the lessons into a working folder (keeps lessons you edited)",
        _add_lessons,
        _run_lessons,
    ),
    "present": (
        "lecture mode: serve one lesson's demos without code (Voila)",
        _add_present,
        _run_present,
    ),
    "assignments": (
        "write an nbgrader course directory of graded lessons",
        _add_assignments,
        _run_assignments,
    ),
}


def build_parser() -> argparse.ArgumentParser:
    from . import __version__

    parser = argparse.ArgumentParser(prog="camlab", description="camlab: camera geometry tools")
    parser.add_argument("--version", action="version", version=f"camlab {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, (help_text, add, run) in COMMANDS.items():
        p = sub.add_parser(name, help=help_text, description=help_text)
        add(p)
        p.set_defaults(run=run)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``camlab`` console script; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if getattr(args, "run", None) is None:
        parser.print_help()
        return 2
    try:
        return args.run(args)
    except (CamlabInputError, ConvergenceError) as exc:
        print(f"camlab {args.command}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
