r"""``camlab calibrate`` and ``camlab undistort``.

``calibrate`` finds a camera from photos of a chessboard; ``undistort`` corrects photos with the
calibration file it wrote.
"""

from __future__ import annotations

import argparse
import sys

from .._validate import CamlabInputError, ConvergenceError
from .photos import expand, read_or_skip

__all__ = []


def add_calibrate(p: argparse.ArgumentParser) -> None:
    """The arguments of ``camlab calibrate``: the photos, ``--pattern``, ``--square``, ``--out``, ``--report``, ``--no-report``, ``--fix-k3`` and ``--skew``.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The subcommand's parser; its arguments are added in place.
    """
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


def progress(i: int, n: int, name: str, failure: str | None) -> None:
    """One line per image, or a bar redrawn in place on a terminal.

    The ``progress`` callback of :func:`camlab.calibration.calibrate_from_images`.

    Parameters
    ----------
    i : int
        How many images are done (1 to ``n``).
    n : int
        How many images there are.
    name : str
        The image just done.
    failure : str or None
        Why its board was not found, or None if it was.
    """
    verdict = "board found" if failure is None else f"skipped: {failure.split(':')[0]}"
    if sys.stdout.isatty():
        bar = "#" * round(24 * i / n)
        print(f"\r[{bar:<24}] {i}/{n} {name[-40:]:<40}", end="" if i < n else "\n", flush=True)
    else:
        print(f"  [{i}/{n}] {name}: {verdict}", flush=True)


def run_calibrate(args: argparse.Namespace) -> int:
    """Calibrate a camera from chessboard photos: print the result and the coach's advice, write the file and the report.

    The outputs are checked before any work, the report figure is written before the result file
    (so a failed figure leaves no result), and both are written atomically.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed arguments of ``camlab calibrate`` (:func:`add_calibrate`).

    Returns
    -------
    int
        The exit status: 0 (photos without a detected board are skipped, and the report says so).

    Raises
    ------
    CamlabInputError
        On an error the user can fix; :func:`camlab.cli.main` prints it and exits with status 2.
    """
    from .._files import check_not_an_input, check_output_path
    from ..calibration import calibrate_from_images, coach, parse_pattern, save_calibration
    from ..calibration.io import SUFFIXES

    pattern = parse_pattern(args.pattern, "--pattern")
    check_output_path(
        args.out, "--out", SUFFIXES
    )  # before any work: nothing is written if one fails
    if not args.no_report:
        check_output_path(args.report, "--report", (".png", ".pdf", ".svg", ".jpg"))
    files = expand(args.images)
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
        progress=progress,
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
        from .._files import atomic_output
        from ..plotting.calibration import report_figure

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


def add_undistort(p: argparse.ArgumentParser) -> None:
    """The arguments of ``camlab undistort``: the photos, ``--calibration``, ``--out-dir`` and ``--alpha``.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The subcommand's parser; its arguments are added in place.
    """
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


def run_undistort(args: argparse.Namespace) -> int:
    """Undistort each photo with the calibration; exit 1 if some could not be read or written.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed arguments of ``camlab undistort`` (:func:`add_undistort`).

    Returns
    -------
    int
        The exit status: 0 when every photo was written, 1 when some were skipped (unreadable, or of another size than the calibration's).

    Raises
    ------
    CamlabInputError
        On an error the user can fix; :func:`camlab.cli.main` prints it and exits with status 2.
    """
    from pathlib import Path

    import cv2

    from .._files import atomic_output, check_not_an_input, check_output_path, output_folder
    from ..calibration import load_calibration, undistort

    K, dist, size = load_calibration(args.calibration, name="--calibration")
    out_dir = output_folder(args.out_dir, "--out-dir")
    check_output_path(out_dir / "probe.png", "--out-dir")
    files = expand(args.images)
    check_not_an_input(
        [out_dir / Path(f).name for f in files],
        "--out-dir",
        files,
        f"the undistorted photos keep their names, so write them to another folder, e.g. "
        f"--out-dir {str(out_dir / 'undistorted')!r}",
    )
    failed = 0
    for i, name in enumerate(files, 1):
        img = read_or_skip(name, "stored", f"[{i}/{len(files)}] ")
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
