"""Graded assignments: turn lessons into an nbgrader course directory.

``camlab assignments DEST [LESSON ...]`` writes ``DEST/source/<lesson>/<lesson>.ipynb`` for
each lesson (all lessons when none is named) and ``DEST/nbgrader_config.py``. In each notebook

* every exercise stub ``def <name>(...): raise NotImplementedError`` becomes an nbgrader
  *solution cell*: the instructor's copy holds camlab's own implementation between
  ``### BEGIN SOLUTION`` and ``### END SOLUTION``; ``nbgrader generate_assignment`` puts the
  lesson's stub back for students;
* every check cell ``check_<name>(<name>)`` becomes an autograded *test cell* worth
  :data:`POINTS` point(s), ``assert check_<name>(<name>)``: the check prints its diagnosis of a
  wrong answer (students see it in their feedback) and the assert also fails an exercise
  that was not attempted, which the lesson's own check lets pass so lessons run in CI;
* the ``solution("<name>")`` cells are dropped, ``solution`` is taken out of the lesson's
  imports and every sentence that mentions ``solution(...)`` is taken out of its text, so the
  students' release has no way to print an answer.

The course is built in a temporary folder beside ``DEST`` and renamed into place, so ``DEST``
is either complete or absent: an interrupted run leaves no torn course, and of two runs into
the same new folder one wins and the other says so.

Then, from ``DEST``: ``nbgrader generate_assignment <lesson>``, collect submissions into
``submitted/<student>/<lesson>/``, ``nbgrader autograde <lesson>``. See docs/teaching.md.
"""

from __future__ import annotations

import ast
import copy
import errno
import json
import os
import re
import shutil
from pathlib import Path
from typing import NamedTuple

from .._validate import CamlabInputError
from .lessons import called, find_lesson, lesson_files, only_statement, stub_name

__all__ = [
    "NBGRADER_CONFIG",
    "POINTS",
    "STUB",
    "AssignmentNotebook",
    "assignment_notebook",
    "write_course",
]

POINTS = 1
STUB = "# your code here\nraise NotImplementedError"

NBGRADER_CONFIG = f"""\
# nbgrader configuration written by `camlab assignments`; run nbgrader from this folder.
c = get_config()
c.CourseDirectory.course_id = "camlab"
# Students get the lesson's own stub in place of the solution.
c.ClearSolutions.code_stub = {{"python": {STUB!r}}}
# Lessons 08, 09 and 11 compute for tens of seconds; leave room on a busy grading machine.
c.Execute.timeout = 600
"""


def _grade_metadata(grade_id: str, *, solution: bool) -> dict:
    meta = {
        "grade": not solution,
        "grade_id": grade_id,
        "locked": not solution,
        "schema_version": 3,
        "solution": solution,
        "task": False,
    }
    if not solution:
        meta["points"] = POINTS
    return meta


def _solution_source(stmt: ast.FunctionDef, reference) -> str:
    args = [a.arg for a in stmt.args.args]
    return "\n".join(
        [
            f"def {stmt.name}({', '.join(args)}):",
            "    ### BEGIN SOLUTION",
            "    # camlab's own implementation",
            f"    import {reference.__module__}",
            f"    return {reference.__module__}.{reference.__name__}({', '.join(args)})",
            "    ### END SOLUTION",
        ]
    )


def _test_source(name: str) -> str:
    return (
        f"# Autograded, {POINTS} point: the check explains a wrong answer; an unanswered exercise fails here.\n"
        f'assert check_{name}({name}), "{name}: not attempted yet"'
    )


def _masked_magics(source: str) -> str:
    """``source`` with IPython magic and shell lines blanked (same lengths), so ``ast`` can parse the rest."""
    return "".join(
        " " * len(line.rstrip("\r\n")) + line[len(line.rstrip("\r\n")) :]
        if line.lstrip().startswith(("%", "!"))
        else line
        for line in source.splitlines(keepends=True)
    )


def _without_solution_import(source: str) -> str:
    """``source`` with ``solution`` taken out of its ``from ... import`` statements."""
    try:
        tree = ast.parse(_masked_magics(source))
    except SyntaxError:
        return source
    lines = source.splitlines(keepends=True)

    def offset(lineno: int, col: int) -> int:  # ast columns count UTF-8 bytes
        return sum(map(len, lines[: lineno - 1])) + len(lines[lineno - 1].encode()[:col].decode())

    imports = [
        node
        for node in ast.walk(tree)
        if isinstance(node, ast.ImportFrom)
        and any(alias.name == "solution" for alias in node.names)
    ]
    for node in sorted(imports, key=lambda n: (n.lineno, n.col_offset), reverse=True):
        kept = ", ".join(ast.unparse(alias) for alias in node.names if alias.name != "solution")
        text = f"from {'.' * node.level}{node.module or ''} import {kept}" if kept else ""
        start, end = (
            offset(node.lineno, node.col_offset),
            offset(node.end_lineno, node.end_col_offset),
        )
        source = source[:start] + (text or ("pass" if node.col_offset else "")) + source[end:]
    return source


def _without_solution_sentences(text: str) -> str:
    """Markdown ``text`` without the sentences (and list items) that mention ``solution(...)``."""
    lines = []
    for line in text.splitlines():
        sentences = re.split(r"(?<=[.!])\s+", line)
        kept = " ".join(s for s in sentences if "solution(" not in s)
        if kept.strip() or not line.strip():
            lines.append(kept)
    return "\n".join(lines)


def _release_safe(cell: dict) -> dict | None:
    """``cell`` without any way to print a solution, or None when nothing is left of it."""
    source = "".join(cell["source"])
    cleaned = (
        _without_solution_import(source)
        if cell["cell_type"] == "code"
        else _without_solution_sentences(source)
    )
    if cleaned == source:
        return cell
    return dict(cell, source=cleaned) if cleaned.strip() else None


class AssignmentNotebook(NamedTuple):
    """:func:`assignment_notebook`'s result.

    Attributes
    ----------
    notebook : dict
        The nbgrader source version of the lesson (nbformat JSON).
    exercises : list of str
        The graded exercises' names, in the lesson's order.
    """

    notebook: dict
    exercises: list[str]


def assignment_notebook(notebook: dict, lesson: str) -> AssignmentNotebook:
    """The nbgrader source version of a lesson notebook and its exercise names, in order.

    Each exercise stub becomes a graded solution cell (a call of camlab's own implementation
    between nbgrader's markers), each ``check_<name>(<name>)`` cell a graded test cell,
    ``solution(...)`` cells are dropped, and other cells lose what would give the solution away.

    Parameters
    ----------
    notebook : dict
        The lesson notebook's JSON (not modified).
    lesson : str
        The lesson's name, for error messages.

    Returns
    -------
    AssignmentNotebook
        The ``notebook`` for nbgrader and its graded ``exercises``.

    Raises
    ------
    CamlabInputError
        If the lesson has no exercise (no stub with a ``check_<name>(<name>)`` cell), or a stub
        has no check cell.
    """
    from ..exercises import all_exercises

    exercises = all_exercises()
    nb = copy.deepcopy(notebook)
    cells, graded, stubs = [], [], {}
    for cell in nb["cells"]:
        stmt = only_statement(cell)
        name, call = stub_name(stmt), called(stmt)
        if name in exercises:
            stubs[name] = cell
            cell["source"] = _solution_source(stmt, exercises[name].reference)
            cell.setdefault("metadata", {})["nbgrader"] = _grade_metadata(name, solution=True)
        elif call and call[0] == "solution":
            continue
        elif call and call[0].startswith("check_") and call[0][len("check_") :] in stubs:
            name = call[0][len("check_") :]
            cell["source"] = _test_source(name)
            cell.setdefault("metadata", {})["nbgrader"] = _grade_metadata(
                f"check_{name}", solution=False
            )
            graded.append(name)
        else:
            cell = _release_safe(cell)
        if cell is not None:
            cells.append(cell)
    if not graded:
        raise CamlabInputError(
            f"LESSON: {lesson} has no exercises (no stub with a check_<name> cell); "
            f"pick a lesson with exercises"
        )
    unchecked = sorted(set(stubs) - set(graded))
    if unchecked:
        raise CamlabInputError(
            f"{lesson}: exercise {unchecked[0]!r} has a stub but no check_{unchecked[0]} cell"
        )
    nb["cells"] = cells
    return AssignmentNotebook(nb, graded)


def _check_new_folder(dest: Path) -> None:
    if dest.exists() and not dest.is_dir():
        raise CamlabInputError(
            f"DEST: {dest} is a file; name a new or empty folder (nothing was written)"
        )
    if dest.is_dir() and any(dest.iterdir()):
        raise CamlabInputError(
            f"DEST: {dest} already exists and is not empty; name a new or empty folder "
            f"(nothing was written)"
        )


def _write_error(exc: OSError, dest: Path) -> CamlabInputError:
    if exc.errno in (errno.EEXIST, errno.ENOTEMPTY):  # the rename found DEST filled after our check
        return CamlabInputError(
            f"DEST: {dest} now exists and is not empty: another run (or program) made it while "
            f"this one was building the course; this run wrote nothing. Use that folder, or "
            f"name a new one"
        )
    return CamlabInputError(
        f"DEST: could not write the course beside {dest} ({exc.strerror or exc}); nothing was "
        f"written. Free some space or choose a folder you can write to"
    )


def _write_files(folder: Path, built: dict[str, tuple[dict, list[str]]]) -> None:
    for stem, (nb, _) in built.items():
        (folder / "source" / stem).mkdir(parents=True)
        text = json.dumps(nb, indent=1, ensure_ascii=False) + "\n"
        (folder / "source" / stem / f"{stem}.ipynb").write_text(text, encoding="utf-8")
    (folder / "nbgrader_config.py").write_text(NBGRADER_CONFIG, encoding="utf-8")


def _move_into_place(building: Path, dest: Path) -> None:
    """Rename the finished course to ``dest``; raises OSError (EEXIST, ENOTEMPTY) if ``dest`` was filled meanwhile.

    A missing ``dest`` gets the whole folder in one rename. An existing empty one (perhaps the
    shell's current folder, which a rename would replace by a new inode) gets the course's
    two entries moved in, ``source`` first: a rename fails on a non-empty folder it would replace.
    """
    if not dest.exists():
        os.rename(building, dest)
        return
    os.rename(building / "source", dest / "source")
    os.rename(building / "nbgrader_config.py", dest / "nbgrader_config.py")


def write_course(
    dest: str | Path, lessons: list[str] | tuple[str, ...] = ()
) -> dict[str, list[str]]:
    """Write an nbgrader course directory for ``lessons`` (all when empty) into the new folder ``dest``.

    Everything is checked before anything is written: an unknown lesson, a lesson without
    exercises or a non-empty ``dest`` raises :class:`CamlabInputError` and leaves the disk
    untouched. The course is written into a hidden folder beside ``dest`` and renamed to ``dest``
    at the end (which replaces only an empty folder), so ``dest`` is complete or absent even if
    the run is killed or the disk fills; a full disk or a folder another run made meanwhile
    raises CamlabInputError.

    Parameters
    ----------
    dest : str or pathlib.Path
        A new or empty folder; it receives ``source/<lesson>/<lesson>.ipynb`` for each lesson
        and ``nbgrader_config.py``.
    lessons : sequence of str
        Lesson numbers or names (:func:`camlab.classroom.lessons.find_lesson`); empty for all.

    Returns
    -------
    dict of str to list of str
        ``{lesson stem: [exercise names]}``, in course order.

    Raises
    ------
    CamlabInputError
        As above: nothing is written.
    """
    dest = Path(dest).absolute()  # "." has no name to build beside
    _check_new_folder(dest)
    paths = list(dict.fromkeys(find_lesson(s) for s in lessons)) if lessons else lesson_files()
    built = {
        p.stem: assignment_notebook(json.loads(p.read_text(encoding="utf-8")), p.stem)
        for p in paths
    }
    building = dest.with_name(f".{dest.name}.building-{os.getpid()}-{os.urandom(4).hex()}")
    try:
        dest.parent.mkdir(parents=True, exist_ok=True)
        building.mkdir()  # not mkdtemp: a plain mkdir gives the folder the umask's mode, as DEST would get
        _write_files(building, built)
        _move_into_place(building, dest)
    except OSError as exc:
        raise _write_error(exc, dest) from None
    finally:
        shutil.rmtree(
            building, ignore_errors=True
        )  # a failed run's partial course; nothing after the rename
    return {stem: names for stem, (_, names) in built.items()}
