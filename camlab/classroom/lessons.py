"""Find lesson notebooks by number (``07``), stem (``07_homographies``) or file name, and read their cells."""

from __future__ import annotations

import ast
from pathlib import Path
from typing import NamedTuple

from .._validate import CamlabInputError

__all__ = [
    "Call",
    "called",
    "code_statements",
    "find_lesson",
    "lesson_files",
    "only_statement",
    "stub_name",
]


def lesson_files() -> list[Path]:
    """Every lesson notebook ``NN_slug.ipynb``, in course order.

    Returns
    -------
    list of pathlib.Path
        The notebooks of :func:`camlab.data.lessons_dir` (a clone's ``lessons/`` or the wheel's
        copy), sorted by name.
    """
    from ..data import lessons_dir  # the clone's lessons/ or the wheel's camlab/lessons

    return sorted(lessons_dir().glob("[0-9][0-9]_*.ipynb"))


def find_lesson(spec: str) -> Path:
    """The lesson named by ``spec``: ``"7"``, ``"07"``, ``"07_homographies"`` or ``"07_homographies.ipynb"``.

    Parameters
    ----------
    spec : str
        The lesson's number, stem or file name (a leading folder is ignored).

    Returns
    -------
    pathlib.Path
        The lesson's notebook.

    Raises
    ------
    CamlabInputError
        If no lesson, or more than one, matches.
    """
    files = lesson_files()
    key = Path(str(spec)).name.removesuffix(".ipynb")
    if key.isdigit():
        key = f"{int(key):02d}"
    matches = [f for f in files if f.stem == key or f.stem.split("_", 1)[0] == key]
    if len(matches) != 1:
        known = ", ".join(f.stem for f in files)
        raise CamlabInputError(
            f"lesson: no lesson {spec!r}; expected a number or name, one of {known}"
        )
    return matches[0]


def code_statements(cell: dict) -> list[ast.stmt] | None:
    """The Python statements of a code cell, or None (markdown, or a cell that does not parse).

    Parameters
    ----------
    cell : dict
        A notebook cell as nbformat's JSON holds it (``cell_type``, ``source``...).

    Returns
    -------
    list of ast.stmt or None
        The cell's top-level statements; None for a markdown cell or one that does not parse
        (a magic, a syntax error).
    """
    if cell["cell_type"] != "code":
        return None
    try:
        return ast.parse("".join(cell["source"])).body
    except SyntaxError:
        return None


def only_statement(cell: dict) -> ast.stmt | None:
    """The single Python statement of a code cell, or None (markdown, magics, several statements).

    Parameters
    ----------
    cell : dict
        A notebook cell as nbformat's JSON holds it (``cell_type``, ``source``...).

    Returns
    -------
    ast.stmt or None
        The statement; None for a markdown cell, a cell that does not parse, or one of more
        (or no) statements.
    """
    body = code_statements(cell)
    return body[0] if body is not None and len(body) == 1 else None


def stub_name(stmt: ast.stmt | None) -> str | None:
    """``name`` if ``stmt`` is ``def name(...): ... raise NotImplementedError``.

    Parameters
    ----------
    stmt : ast.stmt or None
        A statement (:func:`only_statement` of a cell), or None.

    Returns
    -------
    str or None
        The stub's function name (an exercise the student fills in), else None.
    """
    if isinstance(stmt, ast.FunctionDef) and isinstance(stmt.body[-1], ast.Raise):
        raised = stmt.body[-1].exc
        if isinstance(raised, ast.Call):
            raised = raised.func
        if isinstance(raised, ast.Name) and raised.id == "NotImplementedError":
            return stmt.name
    return None


class Call(NamedTuple):
    """A bare call ``f(...)`` found by :func:`called`: the function's ``name`` and its positional ``args``."""

    name: str
    args: list[ast.expr]


def called(stmt: ast.stmt | None) -> Call | None:
    """``(function name, arguments)`` if ``stmt`` is a bare call ``f(...)``.

    Parameters
    ----------
    stmt : ast.stmt or None
        A statement (:func:`only_statement` of a cell), or None.

    Returns
    -------
    Call or None
        The call's ``name`` and positional ``args``; None for anything else (including
        ``obj.f(...)`` and assignments).
    """
    if (
        isinstance(stmt, ast.Expr)
        and isinstance(stmt.value, ast.Call)
        and isinstance(stmt.value.func, ast.Name)
    ):
        return Call(stmt.value.func.id, stmt.value.args)
    return None
