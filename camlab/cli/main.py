r"""The command table (:data:`COMMANDS`), the parser and the entry point of the ``camlab`` script."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable

from .._validate import CamlabInputError, ConvergenceError
from .board import add_board, run_board
from .calibrate import add_calibrate, add_undistort, run_calibrate, run_undistort
from .rectify import add_rectify, run_rectify
from .stitch import add_stitch, run_stitch
from .teaching import (
    add_assignments,
    add_lessons,
    add_present,
    run_assignments,
    run_lessons,
    run_present,
)

__all__ = [
    "COMMANDS",
    "build_parser",
    "main",
]


COMMANDS: dict[
    str, tuple[str, Callable[[argparse.ArgumentParser], None], Callable[[argparse.Namespace], int]]
] = {
    "calibrate": ("calibrate a camera from photos of a chessboard", add_calibrate, run_calibrate),
    "board": (
        "write a printable chessboard PDF at true scale, with a 10 cm ruler",
        add_board,
        run_board,
    ),
    "undistort": ("undistort photos with a calibration file", add_undistort, run_undistort),
    "stitch": ("stitch overlapping photos into a panorama", add_stitch, run_stitch),
    "rectify": (
        "rectify a stereo pair from its matches, with a vertical-disparity figure",
        add_rectify,
        run_rectify,
    ),
    "lessons": (
        "copy the lessons into a working folder (keeps lessons you edited)",
        add_lessons,
        run_lessons,
    ),
    "present": (
        "lecture mode: serve one lesson's demos without code (Voila)",
        add_present,
        run_present,
    ),
    "assignments": (
        "write an nbgrader course directory of graded lessons",
        add_assignments,
        run_assignments,
    ),
}


def build_parser() -> argparse.ArgumentParser:
    """The ``camlab`` argument parser: ``--version`` and one subcommand per entry of :data:`COMMANDS`.

    Each subcommand's parser gets its arguments from the entry's ``add_*`` function and its
    ``run_*`` function as the ``run`` default.

    Returns
    -------
    argparse.ArgumentParser
        The parser (``prog="camlab"``).
    """
    from .. import __version__

    parser = argparse.ArgumentParser(prog="camlab", description="camlab: camera geometry tools")
    parser.add_argument("--version", action="version", version=f"camlab {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, (help_text, add, run) in COMMANDS.items():
        p = sub.add_parser(name, help=help_text, description=help_text)
        add(p)
        p.set_defaults(run=run)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``camlab`` console script; returns the exit status.

    Errors a user can fix (:class:`~camlab.CamlabInputError`, :class:`~camlab.ConvergenceError`)
    print one line on stderr and give status 2; no command prints the help and gives 2.

    Parameters
    ----------
    argv : list of str or None
        The arguments after ``camlab``; None reads ``sys.argv``.

    Returns
    -------
    int
        0 on success, 1 when a command left some input out, 2 on an error the user can fix.
    """
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
