"""Tests for camlab.course and `camlab lessons`: copy the course, never clobber a student's edits."""

import hashlib
import json
import subprocess
import sys
from pathlib import Path

import pytest

import camlab
from camlab import cli
from camlab.course import MANIFEST_NAME, copy_course, course_files
from camlab.data import lessons_dir


def test_course_files_are_every_lesson_and_the_conventions_page():
    files = course_files()
    lessons = sorted(p.name for p in lessons_dir().glob("[0-9][0-9]_*.ipynb"))
    assert len(lessons) >= 12
    assert all(f"lessons/{name}" in files for name in lessons)
    assert "lessons/README.md" in files and "docs/conventions.md" in files


def test_copy_then_update_keeps_edited_lessons(tmp_path):
    first = copy_course(tmp_path)
    assert sorted(first.copied) == sorted(course_files()) and not (first.updated or first.kept)
    lesson = tmp_path / "lessons" / "06_projective_plane.ipynb"
    assert lesson.read_bytes() == (lessons_dir() / lesson.name).read_bytes()

    # the student edits one lesson (a cell, not just its bytes); a new camlab version changes another one
    nb = json.loads(lesson.read_text())
    nb["cells"][1]["source"] = "".join(nb["cells"][1]["source"]) + " "
    lesson.write_text(json.dumps(nb))
    stale = tmp_path / "lessons" / "00_start_here.ipynb"
    stale.write_text("{}")
    manifest = json.loads((tmp_path / MANIFEST_NAME).read_text())
    manifest["files"]["lessons/00_start_here.ipynb"] = hashlib.sha256(b"{}").hexdigest()
    (tmp_path / MANIFEST_NAME).write_text(json.dumps(manifest))

    again = copy_course(tmp_path)
    assert again.kept == ["lessons/06_projective_plane.ipynb"]  # edited: left alone
    assert again.updated == [
        "lessons/00_start_here.ipynb"
    ]  # untouched copy of an old version: updated
    assert (
        json.loads(lesson.read_text())["cells"][1]["source"].endswith(" ")
        and stale.read_bytes() == (lessons_dir() / stale.name).read_bytes()
    )
    assert (
        "kept your edited lessons/06_projective_plane.ipynb" in again.text()
        and "--force" in again.text()
    )

    # the edit is still recognised as an edit next time, and --force overwrites it
    assert copy_course(tmp_path).kept == ["lessons/06_projective_plane.ipynb"]
    forced = copy_course(tmp_path, force=True)
    assert forced.updated == ["lessons/06_projective_plane.ipynb"] and not forced.kept
    assert list(forced.backups) == ["lessons/06_projective_plane.ipynb"]  # the edit is kept beside
    assert lesson.read_bytes() == (lessons_dir() / lesson.name).read_bytes()


def test_a_file_camlab_did_not_copy_is_not_overwritten(tmp_path):
    (tmp_path / "lessons").mkdir()
    mine = tmp_path / "lessons" / "01_pinhole_camera.ipynb"
    mine.write_text("my own notes")
    report = copy_course(tmp_path)
    assert report.kept == ["lessons/01_pinhole_camera.ipynb"] and mine.read_text() == "my own notes"


def test_cli_lessons_and_version(tmp_path, capsys):
    assert cli.main(["lessons", str(tmp_path / "course")]) == 0
    out = capsys.readouterr().out
    assert "copied" in out and "jupyter lab lessons/00_start_here.ipynb" in out
    assert (tmp_path / "course" / "lessons" / "00_start_here.ipynb").exists()
    with pytest.raises(SystemExit) as exc:
        cli.main(["--version"])
    assert exc.value.code == 0 and capsys.readouterr().out.strip() == f"camlab {camlab.__version__}"


def test_version_is_single_sourced():
    from importlib.metadata import version

    assert version("camlab-course") == camlab.__version__
    out = subprocess.run(
        [sys.executable, "-m", "camlab.cli", "--version"],
        capture_output=True,
        text=True,
        check=True,
    )
    assert out.stdout.strip() == f"camlab {camlab.__version__}"


def test_lessons_link_no_page_outside_lessons_but_the_conventions():
    """Every page a lesson links is pulled into the course website (tools/site/build.py), whose
    tests check only the lessons and docs/conventions.md for anchors and accessibility: a link to
    ../docs/teaching.md failed four site tests. Name other docs in plain text instead."""
    import re

    import nbformat

    allowed = set(course_files()) - {p for p in course_files() if p.startswith("docs/")} | {
        "docs/conventions.md"
    }
    outside = []
    for lesson in sorted(lessons_dir().glob("[0-9][0-9]_*.ipynb")):
        nb = nbformat.read(lesson, as_version=4)
        text = "\n".join(c.source for c in nb.cells if c.cell_type == "markdown")
        for target in re.findall(r"\]\(([^)\s]+)\)|href=\"([^\"]+)\"", text):
            target = (target[0] or target[1]).split("#")[0]
            if not target or "://" in target or target.startswith("mailto:"):
                continue
            if str(Path("lessons", target)).replace("lessons/../", "") not in allowed:
                outside.append(f"{lesson.name} -> {target}")
    assert not outside, (
        f"lessons link pages the site does not check (name them without a link): {outside}"
    )
