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
"""
from __future__ import annotations

import argparse
import sys
from typing import Callable

from ._validate import CamlabInputError, ConvergenceError

__all__ = ["COMMANDS", "build_parser", "main"]


def _add_calibrate(p: argparse.ArgumentParser) -> None:
    p.add_argument("images", nargs="+", help='image files or a quoted glob pattern, e.g. "photos/*.jpg"')
    p.add_argument("--pattern", required=True, help="inner corners COLSxROWS, e.g. 9x6 for a board of 10 x 7 squares")
    p.add_argument("--square", required=True, type=float, help="side of one square in metres, e.g. 0.025")
    p.add_argument("--out", default="calibration.json", help="result file (.json, .yaml or .xml; default calibration.json)")
    p.add_argument("--report", default="calibration_report.png", help="report figure (default calibration_report.png)")
    p.add_argument("--no-report", action="store_true", help="do not save a report figure")
    p.add_argument("--fix-k3", action="store_true", help="keep k3 = 0 (recommended for ordinary lenses with few views)")
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
    from ._files import check_output_path
    from .calibration import calibrate_from_images, coach, parse_pattern, save_calibration
    from .calibration.io import SUFFIXES

    pattern = parse_pattern(args.pattern, "--pattern")
    check_output_path(args.out, "--out", SUFFIXES)  # before any work: nothing is written if one fails
    if not args.no_report:
        check_output_path(args.report, "--report", (".png", ".pdf", ".svg", ".jpg"))
    files = _expand(args.images)
    print(f"camlab calibrate: {len(files)} images, pattern {pattern[0]}x{pattern[1]} inner corners, "
          f"square {args.square} m")
    out = calibrate_from_images(files, pattern, args.square, skew=args.skew, fix=("k3",) if args.fix_k3 else (),
                                progress=_progress)
    print(out.report())
    result = out.result
    print(result.summary())
    report = coach(result)
    worst = ", ".join(f"view {v} ({files[out.used[v]]}) {result.per_view_rms[v]:.2f} px" for v in report.worst_views[:3])
    print(f"worst views: {worst}")
    print("advice:")
    print(report.text())
    if not args.no_report:  # the figure first: if it fails, no result file is left behind
        from ._files import atomic_output
        from .plotting.calibration import report_figure

        fig = report_figure(result, report)
        with atomic_output(args.report) as tmp:
            fig.savefig(tmp, dpi=90)
    path = save_calibration(result, args.out)
    print(f"wrote {path} (load in OpenCV: cv2.FileStorage(path, cv2.FILE_STORAGE_READ).getNode('camera_matrix').mat())")
    if not args.no_report:
        print(f"saved report figure {args.report}")
    return 0


def _add_undistort(p: argparse.ArgumentParser) -> None:
    p.add_argument("images", nargs="+", help='photos or a quoted glob pattern, e.g. "photos/*.jpg"')
    p.add_argument("--calibration", required=True, help="calibration file from `camlab calibrate` (.json/.yaml/.xml)")
    p.add_argument("--out-dir", required=True, help="folder for the undistorted images (same file names)")
    p.add_argument("--alpha", type=float, default=0.0,
                   help="0: crop to valid pixels (no black corners, default); 1: keep every source pixel")


def _run_undistort(args: argparse.Namespace) -> int:
    """Undistort each photo with the calibration; exit 1 if some could not be read or written."""
    from pathlib import Path

    import cv2

    from ._files import atomic_output, check_output_path
    from .calibration import load_calibration, undistort

    K, dist, size = load_calibration(args.calibration)
    out_dir = Path(args.out_dir)
    if not out_dir.is_dir():
        raise CamlabInputError(f"--out-dir: no folder {str(out_dir)!r}; create it first")
    check_output_path(out_dir / "probe.png", "--out-dir")
    files = _expand(args.images)
    failed = 0
    for i, name in enumerate(files, 1):
        img = cv2.imread(name, cv2.IMREAD_UNCHANGED)
        if img is None:
            print(f"  [{i}/{len(files)}] {name}: skipped: not an image OpenCV can read", flush=True)
            failed += 1
            continue
        if (img.shape[1], img.shape[0]) != size:
            print(f"  [{i}/{len(files)}] {name}: skipped: {img.shape[1]} x {img.shape[0]} pixels, but the calibration "
                  f"is for {size[0]} x {size[1]}", flush=True)
            failed += 1
            continue
        res = undistort(img, K=K, dist=dist, alpha=args.alpha)
        target = out_dir / Path(name).name
        with atomic_output(target) as tmp:
            if not cv2.imwrite(str(tmp), res.image):
                raise CamlabInputError(f"--out-dir: could not write {str(target)!r}")
        print(f"  [{i}/{len(files)}] {name} -> {target} ({100 * res.black_fraction:.1f}% black, "
              f"{100 * res.lost_fraction:.1f}% of the photo cropped)", flush=True)
    print(f"camlab undistort: {len(files) - failed} of {len(files)} images written to {out_dir}")
    return 1 if failed else 0


def _add_lessons(p: argparse.ArgumentParser) -> None:
    p.add_argument("dest", nargs="?", default="camlab-course",
                   help="working folder (default ./camlab-course); lessons go to DEST/lessons, docs to DEST/docs")
    p.add_argument("--force", action="store_true", help="also overwrite lessons you have edited")


def _run_lessons(args: argparse.Namespace) -> int:
    from .course import copy_course

    print(copy_course(args.dest, force=args.force).text())
    return 0


def _add_assignments(p: argparse.ArgumentParser) -> None:
    p.add_argument("dest", help="a new (or empty) folder for the nbgrader course directory")
    p.add_argument("lessons", nargs="*", metavar="LESSON", help="lesson numbers or names, e.g. 06 07 (default: all)")


def _run_assignments(args: argparse.Namespace) -> int:
    from .classroom.assignments import write_course

    for stem, names in write_course(args.dest, args.lessons).items():
        print(f"{args.dest}/source/{stem}/{stem}.ipynb: exercises graded: {len(names)} ({', '.join(names)})")
    print(f"next: cd {args.dest} && nbgrader generate_assignment <lesson>   (see docs/teaching.md)")
    return 0


def _add_present(p: argparse.ArgumentParser) -> None:
    p.add_argument("lesson", help="lesson number or name, e.g. 07")
    p.add_argument("--port", type=int, default=8866, help="port on 127.0.0.1 (default 8866)")
    p.add_argument("--no-browser", action="store_true", help="do not open a browser")


def _run_present(args: argparse.Namespace) -> int:
    from .classroom.present import serve

    return serve(args.lesson, port=args.port, open_browser=not args.no_browser)


COMMANDS: dict[str, tuple[str, Callable[[argparse.ArgumentParser], None], Callable[[argparse.Namespace], int]]] = {
    "calibrate": ("calibrate a camera from photos of a chessboard", _add_calibrate, _run_calibrate),
    "undistort": ("undistort photos with a calibration file", _add_undistort, _run_undistort),
    "lessons": ("copy the lessons into a working folder (keeps lessons you edited)", _add_lessons, _run_lessons),
    "present": ("lecture mode: serve one lesson's demos without code (Voila)", _add_present, _run_present),
    "assignments": ("write an nbgrader course directory of graded lessons", _add_assignments, _run_assignments),
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
