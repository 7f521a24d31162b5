"""Copy the course (lessons and the conventions page) into a working folder: ``camlab lessons``.

The lessons travel inside the package (:func:`camlab.data.lessons_dir`); a student works on
copies. ``DEST/lessons/*.ipynb`` and ``DEST/docs/*.md`` mirror the repository, so the
lessons' links (``../docs/conventions.md``) work. ``DEST/.camlab-course.json`` records the
SHA-256 of every file as copied: on a later run (a new camlab version) an untouched lesson
is updated, and a lesson the student edited is kept unless ``force`` is given.
"""
from __future__ import annotations

import hashlib
import json
from pathlib import Path
from typing import NamedTuple

__all__ = ["MANIFEST_NAME", "CopyReport", "copy_course", "course_files"]

MANIFEST_NAME = ".camlab-course.json"


class CopyReport(NamedTuple):
    """What :func:`copy_course` did, file paths relative to ``dest``."""

    dest: Path
    copied: list[str]      # new in dest
    updated: list[str]     # replaced: unedited since camlab copied them, or ``force``
    unchanged: list[str]   # already identical
    kept: list[str]        # edited by the student (or not made by camlab): left alone

    def text(self) -> str:
        lines = [f"camlab lessons: {len(self.copied)} copied, {len(self.updated)} updated, "
                 f"{len(self.unchanged)} unchanged, {len(self.kept)} kept in {self.dest}"]
        lines += [f"  kept your edited {name} (it differs from the copy camlab made); --force overwrites it"
                  for name in self.kept]
        lines.append(f"next: cd {self.dest} && jupyter lab lessons/00_start_here.ipynb")
        return "\n".join(lines)


def _sha(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def course_files() -> dict[str, Path]:
    """``{path in the working folder: source file}`` for every lesson and doc page camlab ships."""
    from .data import docs_dir, lessons_dir

    files = {f"lessons/{p.name}": p for p in sorted(lessons_dir().iterdir()) if p.suffix in (".ipynb", ".md")}
    files.update({f"docs/{p.name}": p for p in sorted(docs_dir().glob("*.md"))})
    return files


def copy_course(dest: Path | str, force: bool = False) -> CopyReport:
    """Copy the course into ``dest``; never overwrite a file the student edited unless ``force``.

    A file in ``dest`` counts as edited when its SHA-256 differs both from the new version
    and from the one recorded in ``dest/.camlab-course.json`` when camlab copied it.
    """
    dest = Path(dest).expanduser()
    manifest_path = dest / MANIFEST_NAME
    recorded = json.loads(manifest_path.read_text())["files"] if manifest_path.exists() else {}
    copied, updated, unchanged, kept = [], [], [], []
    for rel, src in course_files().items():
        target, new = dest / rel, src.read_bytes()
        if target.exists():
            have = _sha(target.read_bytes())
            if have == _sha(new):
                unchanged.append(rel)
                recorded[rel] = have
                continue
            if have != recorded.get(rel) and not force:
                kept.append(rel)
                continue
            updated.append(rel)
        else:
            copied.append(rel)
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(new)
        recorded[rel] = _sha(new)
    from . import __version__

    manifest_path.write_text(json.dumps({"camlab": __version__, "files": dict(sorted(recorded.items()))}, indent=1) + "\n")
    return CopyReport(dest, copied, updated, unchanged, kept)
