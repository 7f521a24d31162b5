r"""``camlab lessons``, ``camlab present`` and ``camlab assignments``.

The course for students, the lecture view and nbgrader.
"""

from __future__ import annotations

import argparse

__all__ = []


def add_lessons(p: argparse.ArgumentParser) -> None:
    """The arguments of ``camlab lessons``: ``dest`` and ``--force``.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The subcommand's parser; its arguments are added in place.
    """
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


def run_lessons(args: argparse.Namespace) -> int:
    """Copy the course into ``args.dest`` and print what was copied, kept or replaced.

    :func:`camlab.course.copy_course`; lessons a student edited are kept unless ``--force``.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed arguments of ``camlab lessons`` (:func:`add_lessons`).

    Returns
    -------
    int
        The exit status: 0.

    Raises
    ------
    CamlabInputError
        On an error the user can fix; :func:`camlab.cli.main` prints it and exits with status 2.
    """
    from ..course import copy_course

    print(copy_course(args.dest, force=args.force).text())
    return 0


def add_assignments(p: argparse.ArgumentParser) -> None:
    """The arguments of ``camlab assignments``: ``dest`` and the lessons.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The subcommand's parser; its arguments are added in place.
    """
    p.add_argument("dest", help="a new (or empty) folder for the nbgrader course directory")
    p.add_argument(
        "lessons",
        nargs="*",
        metavar="LESSON",
        help="lesson numbers or names, e.g. 06 07 (default: all)",
    )


def run_assignments(args: argparse.Namespace) -> int:
    """Write the nbgrader course directory and print each lesson's graded exercises.

    :func:`camlab.classroom.assignments.write_course`.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed arguments of ``camlab assignments`` (:func:`add_assignments`).

    Returns
    -------
    int
        The exit status: 0.

    Raises
    ------
    CamlabInputError
        On an error the user can fix; :func:`camlab.cli.main` prints it and exits with status 2.
    """
    from ..classroom.assignments import write_course

    for stem, names in write_course(args.dest, args.lessons).items():
        print(
            f"{args.dest}/source/{stem}/{stem}.ipynb: exercises graded: {len(names)} ({', '.join(names)})"
        )
    print(f"next: cd {args.dest} && nbgrader generate_assignment <lesson>   (see docs/teaching.md)")
    return 0


def add_present(p: argparse.ArgumentParser) -> None:
    """The arguments of ``camlab present``: the lesson, ``--port`` and ``--no-browser``.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The subcommand's parser; its arguments are added in place.
    """
    p.add_argument("lesson", help="lesson number or name, e.g. 07")
    p.add_argument("--port", type=int, default=8866, help="port on 127.0.0.1 (default 8866)")
    p.add_argument("--no-browser", action="store_true", help="do not open a browser")


def run_present(args: argparse.Namespace) -> int:
    """Serve one lesson's demos without code with Voila until Ctrl-C.

    :func:`camlab.classroom.present.serve`.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed arguments of ``camlab present`` (:func:`add_present`).

    Returns
    -------
    int
        The exit status: Voila's own (0 after Ctrl-C).

    Raises
    ------
    CamlabInputError
        On an error the user can fix; :func:`camlab.cli.main` prints it and exits with status 2.
    """
    from ..classroom.present import serve

    return serve(args.lesson, port=args.port, open_browser=not args.no_browser)
