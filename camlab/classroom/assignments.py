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
* the ``solution("<name>")`` cells are dropped.

Then, from ``DEST``: ``nbgrader generate_assignment <lesson>``, collect submissions into
``submitted/<student>/<lesson>/``, ``nbgrader autograde <lesson>``. See docs/teaching.md.
"""
from __future__ import annotations

import ast
import copy
import json
from pathlib import Path

from .._validate import CamlabInputError
from .lessons import called, find_lesson, lesson_files, only_statement, stub_name

__all__ = ["NBGRADER_CONFIG", "POINTS", "STUB", "assignment_notebook", "write_course"]

POINTS = 1
STUB = "# your code here\nraise NotImplementedError"

NBGRADER_CONFIG = f'''\
# nbgrader configuration written by `camlab assignments`; run nbgrader from this folder.
c = get_config()
c.CourseDirectory.course_id = "camlab"
# Students get the lesson's own stub in place of the solution.
c.ClearSolutions.code_stub = {{"python": {STUB!r}}}
# Lessons 08, 09 and 11 compute for tens of seconds; leave room on a busy grading machine.
c.Execute.timeout = 600
'''


def _grade_metadata(grade_id: str, *, solution: bool) -> dict:
    meta = {"grade": not solution, "grade_id": grade_id, "locked": not solution, "schema_version": 3,
            "solution": solution, "task": False}
    if not solution:
        meta["points"] = POINTS
    return meta


def _solution_source(stmt: ast.FunctionDef, reference) -> str:
    args = [a.arg for a in stmt.args.args]
    return "\n".join([
        f"def {stmt.name}({', '.join(args)}):",
        "    ### BEGIN SOLUTION",
        f'    # camlab\'s own implementation; print its source with solution("{stmt.name}")',
        f"    import {reference.__module__}",
        f"    return {reference.__module__}.{reference.__name__}({', '.join(args)})",
        "    ### END SOLUTION",
    ])


def _test_source(name: str) -> str:
    return (f"# Autograded, {POINTS} point: the check explains a wrong answer; an unanswered exercise fails here.\n"
            f'assert check_{name}({name}), "{name}: not attempted yet"')


def assignment_notebook(notebook: dict, lesson: str) -> tuple[dict, list[str]]:
    """The nbgrader source version of a lesson notebook and its exercise names, in order.

    Raises
    ------
    CamlabInputError
        If the lesson has no exercise (no stub with a ``check_<name>(<name>)`` cell).
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
        elif call and call[0].startswith("check_") and call[0][len("check_"):] in stubs:
            name = call[0][len("check_"):]
            cell["source"] = _test_source(name)
            cell.setdefault("metadata", {})["nbgrader"] = _grade_metadata(f"check_{name}", solution=False)
            graded.append(name)
        cells.append(cell)
    if not graded:
        raise CamlabInputError(f"LESSON: {lesson} has no exercises (no stub with a check_<name> cell); "
                               f"pick a lesson with exercises")
    unchecked = sorted(set(stubs) - set(graded))
    if unchecked:
        raise CamlabInputError(f"{lesson}: exercise {unchecked[0]!r} has a stub but no check_{unchecked[0]} cell")
    nb["cells"] = cells
    return nb, graded


def write_course(dest: str | Path, lessons: list[str] | tuple[str, ...] = ()) -> dict[str, list[str]]:
    """Write an nbgrader course directory for ``lessons`` (all when empty) into the new folder ``dest``.

    Returns ``{lesson stem: [exercise names]}``. Everything is checked before anything is
    written: an unknown lesson, a lesson without exercises or a non-empty ``dest`` raises
    :class:`CamlabInputError` and leaves the disk untouched.
    """
    dest = Path(dest)
    if dest.exists() and (not dest.is_dir() or any(dest.iterdir())):
        raise CamlabInputError(f"DEST: {dest} already exists and is not empty; name a new or empty folder "
                               f"(nothing was written)")
    paths = list(dict.fromkeys(find_lesson(s) for s in lessons)) if lessons else lesson_files()
    built = {p.stem: assignment_notebook(json.loads(p.read_text(encoding="utf-8")), p.stem) for p in paths}
    for stem, (nb, _) in built.items():
        folder = dest / "source" / stem
        folder.mkdir(parents=True)
        (folder / f"{stem}.ipynb").write_text(json.dumps(nb, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    (dest / "nbgrader_config.py").write_text(NBGRADER_CONFIG, encoding="utf-8")
    return {stem: names for stem, (_, names) in built.items()}
