"""A student's work is never lost, and a classroom run never leaves a torn folder.

`camlab lessons` judges a lesson by its cells (JupyterLab's save is not an edit), keeps what
it replaces, copies atomically, survives a torn manifest, a torn notebook, a full disk and a
read-only folder; `camlab assignments` builds beside DEST and renames, so concurrent and
killed runs leave a folder complete or absent; a students' release has no way to print a
solution; the lessons are valid, normalised nbformat 4.5.
"""

from __future__ import annotations

import ast
import contextlib
import datetime
import errno
import importlib.util
import io
import json
import multiprocessing
import os
import subprocess
import sys
import time
from pathlib import Path

import nbformat
import numpy as np
import pytest

import camlab
from camlab import cli
from camlab import course as course_mod
from camlab.classroom import assignments, lessons
from camlab.course import MANIFEST_NAME, copy_course, course_files
from camlab.data import lessons_dir

REPO = Path(__file__).resolve().parent.parent
LESSON = "lessons/07_homographies.ipynb"
TODAY = datetime.date.today().isoformat()


def _strip_tool():
    spec = importlib.util.spec_from_file_location(
        "strip_notebooks", REPO / "tools" / "strip_notebooks.py"
    )
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _edit_first_code_cell(path: Path, text: str = "\n# my note") -> None:
    nb = json.loads(path.read_text(encoding="utf-8"))
    cell = next(c for c in nb["cells"] if c["cell_type"] == "code")
    cell["source"] = "".join(cell["source"]) + text
    path.write_text(json.dumps(nb, indent=1), encoding="utf-8")


@pytest.fixture
def ship_new_version(tmp_path, monkeypatch):
    """Call it to make camlab ship a new version of LESSON (its first cell changed); returns the new bytes."""

    def ship() -> bytes:
        files = dict(course_files())
        changed = tmp_path / "shipped" / Path(LESSON).name
        changed.parent.mkdir()
        nb = json.loads(files[LESSON].read_text(encoding="utf-8"))
        nb["cells"][0]["source"] = "".join(nb["cells"][0]["source"]) + "\n\nNew in this version."
        changed.write_text(json.dumps(nb, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
        monkeypatch.setattr(course_mod, "course_files", lambda: {**files, LESSON: changed})
        return changed.read_bytes()

    return ship


def _jupyterlab_save(path: Path) -> None:
    """What JupyterLab does to a lesson the student only ran and saved: the real server's save of a model
    with outputs, execution counts, the kernel's language_info and fresh cell ids."""
    from jupyter_server.services.contents.filemanager import FileContentsManager

    manager = FileContentsManager(root_dir=str(path.parent))
    model = manager.get(path.name)
    nb = model["content"]
    nb.metadata["language_info"] = {
        "name": "python",
        "version": "3.13.1",
        "mimetype": "text/x-python",
    }
    for n, cell in enumerate(nb.cells):
        cell["id"] = f"jlab-{n}"
        if cell.cell_type == "code":
            cell.execution_count = n + 1
            cell.outputs = [nbformat.v4.new_output("stream", text=f"ran {n}\n")]
    manager.save({"type": "notebook", "format": "json", "content": nb}, path.name)


# --- camlab lessons: edits are the cells, not the bytes ---------------------------------------------------


def test_a_lesson_jupyterlab_only_saved_is_not_an_edit_and_is_updated(tmp_path, ship_new_version):
    dest = tmp_path / "course"
    copy_course(dest)
    lesson = dest / LESSON
    before = lesson.read_bytes()
    _jupyterlab_save(lesson)
    assert lesson.read_bytes() != before  # the save changed the bytes, not the cells
    assert sorted(copy_course(dest).unchanged) == sorted(course_files())  # not "your edited lesson"
    new = ship_new_version()
    again = copy_course(dest)
    assert again.updated == [LESSON] and not again.kept and not again.backups
    assert lesson.read_bytes() == new


def test_an_edited_lesson_is_kept_and_force_keeps_it_beside_under_a_dated_name(
    tmp_path, ship_new_version, capsys
):
    dest = tmp_path / "course"
    copy_course(dest)
    lesson = dest / LESSON
    _edit_first_code_cell(lesson)
    mine = lesson.read_bytes()
    new_version = ship_new_version()
    kept = copy_course(dest)
    assert kept.kept == [LESSON] and lesson.read_bytes() == mine
    assert (
        f"kept your edited {LESSON} (you changed its cells)" in kept.text()
        and "--force" in kept.text()
    )

    assert cli.main(["lessons", str(dest), "--force"]) == 0
    out = capsys.readouterr().out
    backup = dest / "lessons" / f"07_homographies.mine-{TODAY}.ipynb"
    assert backup.read_bytes() == mine and lesson.read_bytes() == new_version
    assert (
        f"replaced your edited {LESSON} (--force); your version is kept as lessons/{backup.name}"
        in out
    )

    _edit_first_code_cell(
        lesson, "\n# a second edit"
    )  # the same day again: a second, numbered backup
    second = copy_course(dest, force=True)
    assert second.backups == {LESSON: f"lessons/07_homographies.mine-{TODAY}-2.ipynb"}
    assert (
        backup.read_bytes() == mine
        and "# a second edit" in (dest / second.backups[LESSON]).read_text()
    )


def test_changing_a_cell_type_or_the_order_is_an_edit(tmp_path):
    dest = tmp_path / "course"
    copy_course(dest)
    lesson = dest / LESSON
    nb = json.loads(lesson.read_text())
    nb["cells"][0]["cell_type"] = "raw"
    lesson.write_text(json.dumps(nb))
    fingerprint = course_mod.student_fingerprint
    assert fingerprint(lesson.read_bytes(), lesson.name) != fingerprint(
        (lessons_dir() / lesson.name).read_bytes(), lesson.name
    )
    nb = json.loads((lessons_dir() / lesson.name).read_text())
    nb["cells"][1], nb["cells"][2] = nb["cells"][2], nb["cells"][1]
    assert fingerprint(json.dumps(nb).encode(), lesson.name) != fingerprint(
        (lessons_dir() / lesson.name).read_bytes(), lesson.name
    )


# --- torn files, torn manifest ----------------------------------------------------------------------------


@pytest.mark.parametrize("record", ["kept", "lost"])
def test_a_torn_notebook_is_told_from_an_edit_kept_beside_and_replaced(tmp_path, record):
    dest = tmp_path / "course"
    copy_course(dest)
    lesson = dest / LESSON
    torn = lesson.read_bytes()[:5000]
    lesson.write_bytes(torn)
    if record == "lost":
        (dest / MANIFEST_NAME).unlink()
    report = copy_course(dest)
    backup = dest / "lessons" / f"07_homographies.torn-{TODAY}.ipynb"
    assert report.torn == [LESSON] and report.updated == [LESSON] and not report.kept
    assert (
        backup.read_bytes() == torn
        and lesson.read_bytes() == (lessons_dir() / lesson.name).read_bytes()
    )
    assert f"replaced {LESSON}: it was not a readable notebook" in report.text()


@pytest.mark.parametrize(
    "manifest", ['{"camlab": "0.1.0", "fi', "[]", '{"files": {"a": 3}}', "\xff\xfe"]
)
def test_a_torn_manifest_counts_as_missing_with_a_note(tmp_path, manifest, capsys):
    dest = tmp_path / "course"
    copy_course(dest)
    _edit_first_code_cell(dest / LESSON)
    (dest / MANIFEST_NAME).write_text(manifest, encoding="latin-1")
    assert cli.main(["lessons", str(dest)]) == 0
    out = capsys.readouterr().out
    assert (
        "could not be read" in out
        and "so it was ignored" in out
        and f"kept your edited {LESSON}" in out
    )
    assert json.loads((dest / MANIFEST_NAME).read_text())["files"][
        "lessons/00_start_here.ipynb"
    ]  # rewritten


# --- faults while writing: full disk, read-only DEST, a file as DEST --------------------------------------


def _failing_replace(after: int, error: int):
    real, calls = os.replace, []

    def replace(src, dst, *args, **kwargs):
        calls.append(dst)
        if len(calls) > after:
            raise OSError(error, os.strerror(error))
        return real(src, dst, *args, **kwargs)

    return replace


def test_a_full_disk_stops_with_a_message_and_never_leaves_a_torn_lesson(
    tmp_path, monkeypatch, capsys
):
    dest = tmp_path / "course"
    with monkeypatch.context() as m:
        m.setattr(os, "replace", _failing_replace(3, errno.ENOSPC))
        assert cli.main(["lessons", str(dest)]) == 2
    cap = capsys.readouterr()
    assert (
        "Traceback" not in cap.err
        and "the disk is full" in cap.err
        and "No file is half-written" in cap.err
    )
    written = sorted(p for p in dest.rglob("*") if p.is_file())
    assert len(written) == 3 and not list(
        dest.rglob(".*-*")
    )  # three complete files, no temporary left
    for path in written:
        assert path.read_bytes() == course_files()[path.relative_to(dest).as_posix()].read_bytes()
    report = copy_course(dest)  # the rerun finishes the job
    assert len(report.unchanged) == 3 and len(report.copied) == len(course_files()) - 3


@contextlib.contextmanager
def _read_only(dest: Path, monkeypatch):
    """DEST made read-only: by chmod when that stops us; as root (it does not), by every rename failing EACCES."""
    folders = [dest, *(p for p in dest.rglob("*") if p.is_dir())]
    if os.geteuid() != 0:
        for folder in folders:
            folder.chmod(0o555)
    try:
        with monkeypatch.context() as m:
            if os.geteuid() == 0:
                m.setattr(os, "replace", _failing_replace(0, errno.EACCES))
            yield
    finally:
        for folder in folders:
            folder.chmod(0o755)


def test_a_read_only_dest_up_to_date_succeeds_and_one_to_update_says_why_not(
    tmp_path, monkeypatch, capsys, ship_new_version
):
    dest = tmp_path / "course"
    copy_course(dest)
    capsys.readouterr()
    with _read_only(dest, monkeypatch):
        assert cli.main(["lessons", str(dest)]) == 0
        assert (
            "is up to date (16 files unchanged, 0 kept)".replace("16", str(len(course_files())))
            in capsys.readouterr().out
        )
        ship_new_version()
        assert cli.main(["lessons", str(dest)]) == 2
    err = capsys.readouterr().err
    assert (
        f"could not write {LESSON}" in err
        and "DEST is not writable" in err
        and "Traceback" not in err
    )


def test_dest_that_is_a_file_a_lesson_number_or_inside_a_course_is_explained(
    tmp_path, monkeypatch, capsys
):
    (tmp_path / "notes.txt").write_text("mine")
    monkeypatch.chdir(tmp_path)
    assert cli.main(["lessons", "notes.txt"]) == 2
    assert "'notes.txt' is a file, not a folder" in capsys.readouterr().err
    assert cli.main(["lessons", "07"]) == 2
    err = capsys.readouterr().err
    assert "'07' looks like a lesson" in err and "open lessons/07_homographies.ipynb" in err
    assert "camlab present 07" in err and "write ./07" in err and not (tmp_path / "07").exists()
    assert (
        cli.main(["lessons", "07_homographies.ipynb"]) == 2
        and "looks like a lesson" in capsys.readouterr().err
    )

    assert cli.main(["lessons"]) == 0 and (tmp_path / "camlab-course" / MANIFEST_NAME).is_file()
    monkeypatch.chdir(
        tmp_path / "camlab-course"
    )  # the student cd'd into the course, then ran it again
    assert cli.main(["lessons"]) == 2
    err = capsys.readouterr().err
    assert "inside the course folder" in err and "`camlab lessons .`" in err
    assert not (tmp_path / "camlab-course" / "camlab-course").exists()
    assert cli.main(["lessons", "."]) == 0 and "is up to date" in capsys.readouterr().out
    monkeypatch.chdir(tmp_path)
    assert (
        cli.main(["lessons", "./07"]) == 0 and (tmp_path / "07" / LESSON).is_file()
    )  # on purpose: allowed


# --- camlab assignments: a folder is complete or absent ---------------------------------------------------


def _complete(course: Path, stems: list[str]) -> bool:
    return (
        (course / "nbgrader_config.py").read_text() == assignments.NBGRADER_CONFIG
        and sorted(p.name for p in (course / "source").iterdir()) == stems
        and all(
            json.loads((course / "source" / s / f"{s}.ipynb").read_text())["cells"] for s in stems
        )
    )


def _run_cli(args: list[str], results) -> None:
    """In a child process: `camlab ARGS`, reporting (exit status, stderr) or the exception that escaped."""
    err = io.StringIO()
    try:
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            code = cli.main(args)
        results.put((code, err.getvalue()))
    except BaseException as exc:  # what the issue saw: a raw FileExistsError
        results.put((None, f"{type(exc).__name__}: {exc}"))


def test_concurrent_runs_into_one_new_folder_one_wins_the_others_say_so(tmp_path, monkeypatch):
    dest, ctx, runs = tmp_path / "course", multiprocessing.get_context("fork"), 4
    barrier, results = ctx.Barrier(runs), ctx.Queue()
    real_move = assignments._move_into_place

    def move_together(building, target):  # every run has built its course before any renames it
        barrier.wait(timeout=30)
        real_move(building, target)

    monkeypatch.setattr(assignments, "_move_into_place", move_together)
    procs = [
        ctx.Process(target=_run_cli, args=(["assignments", str(dest), "06"], results))
        for _ in range(runs)
    ]
    for p in procs:
        p.start()
    outcomes = [results.get(timeout=60) for _ in procs]
    for p in procs:
        p.join(timeout=10)
    codes = sorted(code for code, _ in outcomes)
    assert codes == [0] + [2] * (runs - 1), outcomes
    for code, err in outcomes:
        if code == 2:
            assert "now exists and is not empty: another run" in err and err.count("\n") == 1
    assert _complete(dest, ["06_projective_plane"])
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "course"
    ]  # no building folder left behind


def _build_forever(folder, built):
    (folder / "source").mkdir()
    (folder / "source" / "started").write_text("")
    time.sleep(60)


def test_a_killed_run_leaves_no_course_and_the_rerun_builds_it(tmp_path, monkeypatch, capsys):
    dest, ctx = tmp_path / "course", multiprocessing.get_context("fork")
    with monkeypatch.context() as m:
        m.setattr(assignments, "_write_files", _build_forever)
        child = ctx.Process(target=assignments.write_course, args=(dest, ["06"]))
        child.start()
        deadline = time.monotonic() + 30
        while (
            not list(tmp_path.glob(".course.building-*/source/started"))
            and time.monotonic() < deadline
        ):
            time.sleep(0.05)
        child.kill()
        child.join(timeout=10)
    assert list(tmp_path.glob(".course.building-*/source/started")) and not dest.exists()
    assert cli.main(["assignments", str(dest), "06"]) == 0
    assert _complete(dest, ["06_projective_plane"])
    capsys.readouterr()


def test_a_full_disk_writes_nothing_and_says_so(tmp_path, monkeypatch, capsys):
    dest = tmp_path / "course"
    real_write = Path.write_text

    def write_then_fill(self, *args, **kwargs):
        real_write(self, "{", encoding="utf-8")  # a torn first notebook, then the disk is full
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(Path, "write_text", write_then_fill)
    assert cli.main(["assignments", str(dest), "06", "07"]) == 2
    err = capsys.readouterr().err
    assert (
        "No space left on device" in err and "nothing was written" in err and "Traceback" not in err
    )
    assert list(tmp_path.iterdir()) == []


def test_an_existing_empty_folder_such_as_the_current_one_gets_the_course(
    tmp_path, monkeypatch, capsys
):
    (tmp_path / "course").mkdir()
    monkeypatch.chdir(tmp_path / "course")
    inode = os.stat(".").st_ino
    assert cli.main(["assignments", ".", "06"]) == 0
    assert os.stat(".").st_ino == inode and _complete(
        Path("."), ["06_projective_plane"]
    )  # not replaced
    (tmp_path / "afile").write_text("")
    assert cli.main(["assignments", str(tmp_path / "afile"), "06"]) == 2
    assert "is a file" in capsys.readouterr().err


# --- the students' release has no way to print a solution -------------------------------------------------


def _release(stem: str) -> dict:
    """The students' version of the lesson's assignment, as `nbgrader generate_assignment` makes it."""
    from nbgrader.preprocessors import ClearSolutions

    source, _ = assignments.assignment_notebook(
        json.loads(lessons.find_lesson(stem).read_text()), stem
    )
    nb = nbformat.reads(json.dumps(source), as_version=4)  # sources joined, as nbgrader reads them
    released, _ = ClearSolutions(code_stub={"python": assignments.STUB}).preprocess(nb, {})
    return released


def _imports(cells: list[dict]) -> list[ast.stmt]:
    statements = []
    for cell in cells:
        if cell["cell_type"] == "code":
            tree = ast.parse(assignments._masked_magics("".join(cell["source"])))
            statements += [n for n in tree.body if isinstance(n, (ast.Import, ast.ImportFrom))]
    return statements


@pytest.mark.parametrize("stem", [p.stem for p in lessons.lesson_files()])
def test_a_release_notebook_has_no_way_to_print_a_solution(stem):
    pytest.importorskip("nbgrader")
    released = _release(stem)
    for cell in released.cells:
        source = "".join(cell["source"])
        assert "solution(" not in source and "BEGIN SOLUTION" not in source, (stem, source[:300])
        if cell["cell_type"] == "code":
            names = {
                n.id
                for n in ast.walk(ast.parse(assignments._masked_magics(source)))
                if isinstance(n, ast.Name)
            }
            assert "solution" not in names
    namespace: dict = {}
    exec(
        compile(ast.Module(_imports(released.cells), type_ignores=[]), stem, "exec"), namespace
    )  # the setup's imports
    assert "solution" not in namespace and any(name.startswith("check_") for name in namespace)


def test_solution_leaves_every_kind_of_import_and_sentence():
    strip = assignments._without_solution_import
    assert (
        strip("%matplotlib widget\nfrom camlab.exercises import check_a, solution\nx = 1\n")
        == "%matplotlib widget\nfrom camlab.exercises import check_a\nx = 1\n"
    )
    assert (
        strip("from camlab.exercises import (\n    solution,\n    check_b,\n)\n")
        == "from camlab.exercises import check_b\n"
    )
    assert (
        strip("import numpy as np\nfrom camlab.exercises import solution\n")
        == "import numpy as np\n\n"
    )
    assert (
        strip("if True:\n    from camlab.exercises import solution as s\n")
        == "if True:\n    pass\n"
    )
    sentences = assignments._without_solution_sentences
    assert (
        sentences(
            'Write `f(x)`, e.g. `f(2)`. `solution("f")` prints one.\n- a\n- `solution("x")` too'
        )
        == "Write `f(x)`, e.g. `f(2)`.\n- a"
    )
    assert sentences('Stuck? `solution("lift")` prints it:') == ""


# --- the lessons are valid, normalised notebooks ----------------------------------------------------------


@pytest.mark.parametrize("path", lessons.lesson_files(), ids=lambda p: p.stem)
def test_every_lesson_is_valid_nbformat_45_with_ids_and_normalised(path):
    text = path.read_text(encoding="utf-8")
    nb = nbformat.reads(text, as_version=nbformat.NO_CONVERT)
    nbformat.validate(nb)  # raises on 4.4 with ids, or 4.5 without
    assert (nb.nbformat, nb.nbformat_minor) == (4, 5) and all(cell.get("id") for cell in nb.cells)
    assert _strip_tool().normalised(text, path.name) == text, "run `make strip`"


def test_strip_tool_gives_stable_ids_strips_and_is_what_the_server_writes(tmp_path):
    tool = _strip_tool()
    nb = nbformat.v4.new_notebook(
        cells=[nbformat.v4.new_code_cell("x = 1\ny = 2"), nbformat.v4.new_markdown_cell("é")]
    )
    nb.nbformat_minor = 4
    for cell in nb.cells:
        del cell["id"]
    nb.cells[0].outputs = [nbformat.v4.new_output("stream", text="1\n")]
    nb.cells[0].execution_count = 3
    nb.cells[0].metadata["execution"] = {"iopub.status.busy": "2026"}
    nb.metadata["widgets"] = {"state": {}}
    text = json.dumps(nb)
    once = tool.normalised(text, "99_x.ipynb")
    assert (
        once == tool.normalised(text, "99_x.ipynb") == tool.normalised(once, "99_x.ipynb")
    )  # stable, idempotent
    out = json.loads(once)
    assert out["nbformat_minor"] == 5 and len({c["id"] for c in out["cells"]}) == 2
    assert out["cells"][0]["outputs"] == [] and out["cells"][0]["execution_count"] is None
    assert out["cells"][0]["metadata"] == {} and "widgets" not in out["metadata"] and "é" in once
    # The Jupyter server's own save of that notebook (what JupyterLab's Ctrl+S ends in) changes no byte.
    from jupyter_server.services.contents.filemanager import FileContentsManager

    (tmp_path / "n.ipynb").write_text(once, encoding="utf-8")
    manager = FileContentsManager(root_dir=str(tmp_path))
    manager.save(
        {"type": "notebook", "format": "json", "content": manager.get("n.ipynb")["content"]},
        "n.ipynb",
    )
    assert (tmp_path / "n.ipynb").read_text(encoding="utf-8") == once


# --- the command line: present without voila, --out-dir, python -m camlab ---------------------------------


def test_present_without_voila_says_what_to_install_before_any_url(monkeypatch, capsys):
    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "voila" else real(name, *a)
    )
    assert cli.main(["present", "07", "--no-browser"]) == 2
    cap = capsys.readouterr()
    assert (
        'pip install "camlab-course[class]"' in cap.err
        and "http" not in cap.out
        and "Traceback" not in cap.err
    )


def test_undistort_creates_a_missing_out_dir(tmp_path, capsys):
    import cv2

    cal = tmp_path / "cam.json"
    fs = cv2.FileStorage(str(cal), cv2.FILE_STORAGE_WRITE)
    fs.write("image_width", 64)
    fs.write("image_height", 48)
    fs.write("camera_matrix", np.array([[60.0, 0, 31.5], [0, 60, 23.5], [0, 0, 1]]))
    fs.write("distortion_coefficients", np.array([[-0.2, 0.05, 0, 0, 0]]))
    fs.release()
    photo = tmp_path / "p.png"
    cv2.imwrite(str(photo), np.random.default_rng(0).integers(0, 255, (48, 64, 3), dtype=np.uint8))
    out = tmp_path / "new" / "undistorted"
    assert (
        cli.main(["undistort", str(photo), "--calibration", str(cal), "--out-dir", str(out)]) == 0
    )
    assert cv2.imread(str(out / "p.png")).shape == (48, 64, 3)
    assert (
        cli.main(["undistort", str(photo), "--calibration", str(cal), "--out-dir", str(photo)]) == 2
    )
    assert "--out-dir: " in capsys.readouterr().err


def test_python_dash_m_camlab_is_the_cli():
    out = subprocess.run(
        [sys.executable, "-m", "camlab", "--version"],
        capture_output=True,
        text=True,
        timeout=60,
        env={**os.environ, "PYTHONPATH": str(REPO)},
    )
    assert out.returncode == 0 and out.stdout.strip() == f"camlab {camlab.__version__}"
    bad = subprocess.run(
        [sys.executable, "-m", "camlab", "lessons", "07"],
        capture_output=True,
        text=True,
        timeout=60,
        env={**os.environ, "PYTHONPATH": str(REPO)},
    )
    assert bad.returncode == 2 and "looks like a lesson" in bad.stderr
