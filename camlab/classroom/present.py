"""Lecture mode: one lesson's demos, full width and without code, served by Voila.

``camlab present 07`` (or ``make present LESSON=07``) builds a *presentation notebook* from
the lesson and serves it with Voila (which hides all code). The presentation keeps the lesson's
title, each demo with the heading of its section, and runs every other cell of the lesson
silently (``%%capture``, and the figures those cells draw are closed), because later demos need
what earlier cells computed. Exercises and their checks are left out: hidden code makes them
unusable, so students do those in JupyterLab.

One more cell, after the title, runs :data:`camlab._access.SCRIPT` in the page (names
for slider handles, Tab out of figures, focus rings): the copy ``import camlab.widgets``
sends runs silently here, like the rest of the lesson's setup.

Voila renders with the ``camlab`` template (:data:`VOILA_DATA`): its lab template without the
Font Awesome links to a CDN, so the lecture view makes no request outside the machine.
"""

from __future__ import annotations

import ast
import copy
import importlib.util
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from .. import _access as access
from .._notebook import UPLOAD_NEEDS_KERNEL
from .._validate import CamlabInputError
from .lessons import called, code_statements, find_lesson, only_statement, stub_name

__all__ = ["is_demo_cell", "presentation_notebook", "serve"]

SILENT = """%%capture
import matplotlib.pyplot as _camlab_plt
_camlab_figures = set(_camlab_plt.get_fignums())
{code}
for _n in set(_camlab_plt.get_fignums()) - _camlab_figures:
    _camlab_plt.close(_n)
"""

ACCESSIBILITY_SCRIPT = "%%javascript\n" + access.SCRIPT  # the import's copy runs silently here
VOILA_DATA = Path(__file__).with_name(
    "jupyter_data"
)  # voila/templates/camlab, found through JUPYTER_PATH


def _is_demo_call(node: ast.AST | None) -> bool:
    func = node.func if isinstance(node, ast.Call) else None
    return (
        isinstance(func, ast.Attribute)
        and isinstance(func.value, ast.Name)
        and func.value.id == "demos"
    )


def is_demo_cell(cell: dict) -> bool:
    """True for a lesson's interactive demo cell.

    The cell is one call ``demos.<name>(...)``, or ``d = demos.<name>(...)`` followed by ``d``
    (the form a lesson uses when a later cell reads the demo's state).

    Parameters
    ----------
    cell : dict
        A notebook cell as nbformat's JSON holds it.

    Returns
    -------
    bool
        Whether the cell shows a demo.
    """
    body = code_statements(cell)
    if body is None:
        return False
    if len(body) == 1:
        return isinstance(body[0], ast.Expr) and _is_demo_call(body[0].value)
    return (
        len(body) == 2
        and isinstance(body[0], ast.Assign)
        and len(body[0].targets) == 1
        and isinstance(body[0].targets[0], ast.Name)
        and _is_demo_call(body[0].value)
        and isinstance(body[1], ast.Expr)
        and isinstance(body[1].value, ast.Name)
        and body[1].value.id == body[0].targets[0].id
    )


def _is_exercise(cell: dict) -> bool:
    stmt = only_statement(cell)
    call = called(stmt)
    return stub_name(stmt) is not None or bool(
        call and (call[0] == "solution" or call[0].startswith("check_"))
    )


def _markdown(text: str) -> dict:
    return {"cell_type": "markdown", "metadata": {}, "source": text}


def _code(text: str) -> dict:
    return {
        "cell_type": "code",
        "metadata": {},
        "source": text,
        "outputs": [],
        "execution_count": None,
    }


def presentation_notebook(notebook: dict) -> dict:
    """The lecture version of a lesson notebook: title, then each demo under its section heading.

    After the title, a cell runs the accessibility script; every other code cell but the
    exercises runs silently (``%%capture``, its new figures closed); markdown other than the
    demos' headings is dropped. A cell that builds a photo upload control is followed by
    :data:`camlab._notebook.UPLOAD_NEEDS_KERNEL` (the lecture runs on the lesson's own photos).

    Parameters
    ----------
    notebook : dict
        The lesson notebook's JSON (not modified).

    Returns
    -------
    dict
        A new notebook, for Voila.
    """
    nb = copy.deepcopy(notebook)
    title = "".join(nb["cells"][0]["source"]).strip().splitlines()[0]
    cells, heading, shown = [_markdown(title), _code(ACCESSIBILITY_SCRIPT)], None, None
    for cell in nb["cells"][1:]:
        if cell["cell_type"] == "markdown":
            lines = "".join(cell["source"]).lstrip().splitlines()
            heading = lines[0] if lines and lines[0].startswith("#") else heading
        elif is_demo_cell(cell):
            if heading and heading != shown:
                cells.append(_markdown(heading))
                shown = heading
            cells.append(dict(cell, source="".join(cell["source"])))
        elif cell["cell_type"] == "code" and not _is_exercise(cell):
            source = "".join(cell["source"])
            cell["source"] = SILENT.format(code=source)
            cells.append(cell)
            if "PhotoUpload(" in source:  # the lesson's own photos are used; say why
                cells.append(_markdown(f"*{UPLOAD_NEEDS_KERNEL}*"))
    nb["cells"] = cells
    return nb


def voila_environment() -> dict[str, str]:
    """The environment of this process with :data:`VOILA_DATA` first on JUPYTER_PATH.

    Voila finds its templates there.

    Returns
    -------
    dict of str to str
        A copy of ``os.environ`` with JUPYTER_PATH set.
    """
    paths = [str(VOILA_DATA), *filter(None, os.environ.get("JUPYTER_PATH", "").split(os.pathsep))]
    return dict(os.environ, JUPYTER_PATH=os.pathsep.join(paths))


def serve(lesson: str, port: int = 8866, open_browser: bool = True) -> int:
    """Write the presentation of ``lesson`` to a temporary folder and serve it with Voila until Ctrl-C.

    Parameters
    ----------
    lesson : str
        The lesson's number or name (:func:`camlab.classroom.lessons.find_lesson`).
    port : int
        The port on 127.0.0.1.
    open_browser : bool
        Let Voila open a browser.

    Returns
    -------
    int
        Voila's exit status; 0 after Ctrl-C.

    Raises
    ------
    CamlabInputError
        If ``lesson`` names no lesson, or Voila (the ``class`` extra) is not installed.
    """
    path = find_lesson(lesson)
    if importlib.util.find_spec("voila") is None:  # before printing a URL nothing will serve
        raise CamlabInputError(
            "camlab present needs Voila, which is not installed; install the class extra: "
            'pip install "camlab-course[class]"'
        )
    presentation = presentation_notebook(json.loads(path.read_text(encoding="utf-8")))
    with tempfile.TemporaryDirectory(prefix="camlab-present-") as folder:
        target = Path(folder) / path.name
        target.write_text(json.dumps(presentation), encoding="utf-8")
        cmd = [
            sys.executable,
            "-m",
            "voila",
            str(target),
            f"--port={port}",
            "--Voila.ip=127.0.0.1",
            "--theme=light",
            "--VoilaConfiguration.show_margins=False",
            "--template=camlab",
        ]
        if not open_browser:
            cmd.append("--no-browser")
        print(
            f"camlab present: serving {path.stem} at http://127.0.0.1:{port}/ (Ctrl-C stops)",
            flush=True,
        )
        try:
            return subprocess.run(cmd, cwd=folder, env=voila_environment()).returncode
        except KeyboardInterrupt:
            return 0
