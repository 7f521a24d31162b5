"""Copy the course (lessons and the conventions page) into a working folder: ``camlab lessons``.

The lessons travel inside the package (:func:`camlab.data.lessons_dir`); a student works on
copies. ``DEST/lessons/*.ipynb`` and ``DEST/docs/*.md`` mirror the repository, so the
lessons' links (``../docs/conventions.md``) work. ``DEST/.camlab-course.json`` records, for
every file as copied, a fingerprint of what a student can change: a notebook's cell types
and sources in order (not ids, metadata, outputs or execution counts, which JupyterLab's
save and running the cells change), other files' bytes. On a later run (a new camlab
version) a lesson whose cells are as camlab copied them is updated; a lesson the student
edited is kept, or with ``force`` replaced after its old version is kept beside it as
``NN_name.mine-<date>.ipynb``. An empty notebook, or one that is not readable JSON (cut short by an
interrupted copy or save) is not mistaken for an edit: it is kept beside as
``NN_name.torn-<date>.ipynb`` and replaced. Every file is written to a temporary name in its
folder and renamed into place, so an interrupted run leaves each file old or new, never torn.
"""

from __future__ import annotations

import errno
import hashlib
import json
from pathlib import Path
from typing import NamedTuple

from ._files import atomic_output
from ._files import backup_name as _backup_name
from ._validate import CamlabInputError

__all__ = [
    "MANIFEST_NAME",
    "CopyReport",
    "check_dest",
    "copy_course",
    "course_files",
    "student_fingerprint",
]

MANIFEST_NAME = ".camlab-course.json"


class CopyReport(NamedTuple):
    """What :func:`copy_course` did, file paths relative to ``dest``.

    Attributes
    ----------
    copied, updated, unchanged, kept : list of str
        New in ``dest``; replaced (camlab's older copy, a torn file, or an edit with
        ``force``); the same cells as this version; edited by the student and left alone.
    backups : dict of str to str
        Each replaced file that held something of the student's (an edit replaced with
        ``force``, a torn notebook) -> where its old content was kept.
    torn : list of str
        The files among ``backups`` that were not readable notebooks.
    notes : list of str
        Anything else the student should know (an unreadable record, a record not updated).
    """

    dest: Path
    copied: list[str]
    updated: list[str]
    unchanged: list[str]
    kept: list[str]
    backups: dict[str, str]
    torn: list[str]
    notes: list[str]

    def text(self) -> str:
        """The report as the student reads it after ``camlab lessons``.

        Returns
        -------
        str
            Lines: a summary (counts and ``dest``), one per replaced file and per kept edit,
            one per note, and the command that opens lesson 00.
        """
        if self.copied or self.updated:
            lines = [
                f"camlab lessons: {len(self.copied)} copied, {len(self.updated)} updated, "
                f"{len(self.unchanged)} unchanged, {len(self.kept)} kept in {self.dest}"
            ]
        else:
            lines = [
                f"camlab lessons: {self.dest} is up to date ({len(self.unchanged)} files unchanged, "
                f"{len(self.kept)} kept)"
            ]
        for name, backup in self.backups.items():
            lines.append(
                f"  replaced {name}: it was not a readable notebook (cut short, e.g. by an interrupted "
                f"copy); the broken file is kept as {backup}"
                if name in self.torn
                else f"  replaced your edited {name} (--force); your version is kept as {backup}"
            )
        lines += [
            f"  kept your edited {name} (you changed its cells); `camlab lessons --force` puts in this "
            f"version and keeps yours beside it as {_backup_pattern(name, 'mine')}"
            for name in self.kept
        ]
        lines += [f"  note: {note}" for note in self.notes]
        cd = "" if self.dest == Path(".") else f"cd {self.dest} && "
        lines.append(f"next: {cd}jupyter lab lessons/00_start_here.ipynb")
        return "\n".join(lines)


def _sha(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def student_fingerprint(data: bytes, name: str) -> str | None:
    """SHA-256 of what a student can change in file ``name``; None for an unreadable notebook.

    For a notebook: the cells' types and sources, in order. Ids, metadata, outputs and
    execution counts are left out, because opening and saving in JupyterLab (or its autosave
    after Run All) changes them without the student changing the lesson. Other files: the bytes.

    Parameters
    ----------
    data : bytes
        The file's content.
    name : str
        Its name; a name ending in ``.ipynb`` is read as a notebook.

    Returns
    -------
    str or None
        The hex digest; None for a notebook that is not valid JSON shaped like a notebook.
    """
    if not name.endswith(".ipynb"):
        return _sha(data)
    try:
        cells = json.loads(data)["cells"]
        content = [[cell["cell_type"], "".join(cell["source"])] for cell in cells]
    except (ValueError, KeyError, TypeError):  # not JSON, not UTF-8, or not shaped like a notebook
        return None
    return _sha(json.dumps(content).encode())


def course_files() -> dict[str, Path]:
    """``{path in the working folder: source file}`` for every lesson and doc page camlab ships.

    Returns
    -------
    dict of str to pathlib.Path
        ``lessons/<name>`` and ``docs/<name>`` paths in the working folder, each mapped to the
        shipped file.
    """
    from .data import docs_dir, lessons_dir

    files = {
        f"lessons/{p.name}": p
        for p in sorted(lessons_dir().iterdir())
        if p.suffix in (".ipynb", ".md")
    }
    files.update({f"docs/{p.name}": p for p in sorted(docs_dir().glob("*.md"))})
    return files


def _names_a_lesson(text: str) -> str | None:
    """The lesson ``text`` names (``"07"`` -> ``"07_homographies"``), ``"?"`` for an unknown number, else None."""
    from .classroom.lessons import find_lesson

    if "/" in text or "\\" in text:
        return None  # an explicit path such as ./07 is a folder on purpose
    try:
        return find_lesson(text).stem
    except CamlabInputError:
        return "?" if text.isdigit() else None


def check_dest(dest: Path | str) -> Path:
    """``dest`` as a Path if it can hold a course, else raise naming what DEST looks like and what to run.

    Refused: a file; a bare lesson number or name (``camlab lessons 07``, by analogy with
    ``camlab present 07``); a new folder inside an existing course folder (``camlab lessons``
    run inside ``camlab-course`` would make ``camlab-course/camlab-course``).

    Parameters
    ----------
    dest : str or pathlib.Path
        The folder ``camlab lessons`` copies the course into.

    Returns
    -------
    pathlib.Path
        ``dest``, user-expanded.

    Raises
    ------
    CamlabInputError
        For each of those, saying what to run instead.
    """
    text = str(dest)
    path = Path(text).expanduser()
    if path.exists() and not path.is_dir():
        raise CamlabInputError(
            f"DEST: {text!r} is a file, not a folder; name a folder for the course "
            f"(default ./camlab-course)"
        )
    if (path / MANIFEST_NAME).is_file():
        return path  # an existing course: update it
    lesson = _names_a_lesson(text)
    if lesson is not None:
        open_it = (
            f"open lessons/{lesson}.ipynb in it"
            if lesson != "?"
            else "open a lesson in its lessons/ folder"
        )
        raise CamlabInputError(
            f"DEST: {text!r} looks like a lesson, but `camlab lessons` copies the whole course into the folder DEST. "
            f"Run `camlab lessons` (into ./camlab-course) and {open_it}; `camlab present {text}` shows a lesson's "
            f"demos. To make a folder named {text!r} anyway, write ./{text}"
        )
    enclosing = next((p for p in path.resolve().parents if (p / MANIFEST_NAME).is_file()), None)
    if enclosing is not None:
        raise CamlabInputError(
            f"DEST: {str(path)!r} would be a new course inside the course folder {str(enclosing)!r}; to update that "
            f"course run `camlab lessons {enclosing}` (or `camlab lessons .` inside it)"
        )
    return path


def _read_manifest(path: Path) -> tuple[dict[str, str], str | None]:
    """The recorded fingerprints, and a note when the record exists but cannot be read (it is then ignored)."""
    if not path.exists():
        return {}, None
    try:
        files = json.loads(path.read_bytes())["files"]
        if isinstance(files, dict) and all(isinstance(v, str) for v in files.values()):
            return files, None
        problem = "its 'files' entry is not a table of fingerprints"
    except (ValueError, KeyError, TypeError) as exc:
        problem = f"{type(exc).__name__}: {exc}"
    except OSError as exc:
        problem = exc.strerror or str(exc)
    return {}, (
        f"the record {path} could not be read ({problem}), so it was ignored: lessons that differ from "
        f"this version count as yours and are kept"
    )


def _backup_pattern(name: str, kind: str) -> str:
    """``lessons/NN_name.<kind>-<date>.ipynb``: what a backup of ``name`` will be called."""
    path = Path(name)
    return str(path.with_name(f"{path.stem}.{kind}-<date>{path.suffix}"))


def _write(target: Path, data: bytes) -> None:
    """Write ``data`` to a temporary file beside ``target`` and rename it into place (never a torn file)."""
    target.parent.mkdir(parents=True, exist_ok=True)
    with atomic_output(target) as tmp:
        tmp.write_bytes(data)


def _decide(target: Path, new: bytes, recorded: str | None, force: bool) -> str:
    """What to do with ``target``: copy, unchanged, update, torn (back up and replace), replace (forced) or keep."""
    if not target.exists():
        return "copy"
    if not target.is_file():
        return "keep"
    have = target.read_bytes()
    mine = student_fingerprint(have, target.name)
    if have == new or (mine is not None and mine == student_fingerprint(new, target.name)):
        return "unchanged"  # also a lesson JupyterLab saved: new ids, metadata or outputs, the same cells
    if recorded is not None and recorded in (
        mine,
        _sha(have),
    ):  # older records hold the bytes' hash
        return "update"  # the student has not changed camlab's copy of an older version
    if mine is None and (not have.strip() or have.lstrip().startswith(b"{")):
        return (
            "torn"  # empty, or a notebook cut short; a file that never was one is the student's own
        )
    return "replace" if force else "keep"


def _write_error(exc: OSError, rel: str, done: CopyReport) -> CamlabInputError:
    """A message for a failed write: which file, why, what to do, and what this run had already done."""
    if exc.errno == errno.ENOSPC:
        fix = "the disk is full: free some space and run `camlab lessons` again"
    elif exc.errno in (errno.EACCES, errno.EPERM, errno.EROFS):
        fix = "DEST is not writable: choose a folder you can write to, e.g. `camlab lessons ~/camlab-course`"
    else:
        fix = "fix that and run `camlab lessons` again"
    earlier = "\n".join(done.text().splitlines()[:-1])
    return CamlabInputError(
        f"DEST: could not write {rel} in {done.dest} ({exc.strerror or exc}); {fix}. "
        f"No file is half-written. Before that:\n{earlier}"
    )


def copy_course(dest: Path | str, force: bool = False) -> CopyReport:
    """Copy the course into ``dest``; never lose a file the student edited (see the module docstring).

    Parameters
    ----------
    dest : str or pathlib.Path
        The course folder, new or one an earlier ``copy_course`` made.
    force : bool, optional
        Replace files the student edited too, keeping their versions beside them.

    Returns
    -------
    CopyReport
        What was copied, updated, left unchanged, kept, and backed up (paths relative to
        ``dest``), and notes.

    Raises
    ------
    CamlabInputError
        If ``dest`` cannot hold a course (:func:`check_dest`) or a file cannot be written
        (a full disk, a read-only folder); a ``dest`` with nothing to write may be read-only.
    """
    dest = check_dest(dest)
    manifest_path = dest / MANIFEST_NAME
    recorded, note = _read_manifest(manifest_path)
    report = CopyReport(dest, [], [], [], [], {}, [], [note] if note else [])
    actions = {
        "copy": report.copied,
        "unchanged": report.unchanged,
        "update": report.updated,
        "torn": report.updated,
        "replace": report.updated,
        "keep": report.kept,
    }
    for rel, src in course_files().items():
        target, new = dest / rel, src.read_bytes()
        try:
            action = _decide(target, new, recorded.get(rel), force)
            if action in ("torn", "replace"):
                backup = _backup_name(target, "torn" if action == "torn" else "mine")
                _write(backup, target.read_bytes())
                report.backups[rel] = str(Path(rel).with_name(backup.name))
                if action == "torn":
                    report.torn.append(rel)
            if action in ("copy", "update", "torn", "replace"):
                _write(target, new)
        except OSError as exc:
            raise _write_error(exc, rel, report) from None
        actions[action].append(rel)
        if action != "keep":
            recorded[rel] = student_fingerprint(new, target.name)
    _update_manifest(manifest_path, recorded, report)
    return report


def _update_manifest(path: Path, recorded: dict[str, str], report: CopyReport) -> None:
    """Write the record if it changed; failing to is only a note (the lessons themselves are in place)."""
    from . import __version__

    text = (
        json.dumps({"camlab": __version__, "files": dict(sorted(recorded.items()))}, indent=1)
        + "\n"
    )
    try:
        if path.is_file() and path.read_text(encoding="utf-8", errors="replace") == text:
            return
        _write(path, text.encode())
    except OSError as exc:
        report.notes.append(
            f"could not update the record {path} ({exc.strerror or exc}); the lessons are in "
            f"place, and a later run treats lessons that differ from its version as yours"
        )
