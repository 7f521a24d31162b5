"""Graded assignments: `camlab assignments` writes an nbgrader course that nbgrader really grades."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from camlab import cli
from camlab.classroom import assignments, lessons
from camlab.exercises import check

BIN = Path(sys.executable).parent


def _cells(path: Path) -> list[dict]:
    return json.loads(path.read_text())["cells"]


def _graded(cells: list[dict]) -> list[dict]:
    return [c for c in cells if "nbgrader" in c["metadata"]]


def test_every_lesson_becomes_a_course_whose_solutions_pass_their_checks(tmp_path, capsys):
    course = assignments.write_course(tmp_path / "course")
    assert list(course) == [p.stem for p in lessons.lesson_files()] and len(course) == 13
    assert (tmp_path / "course" / "nbgrader_config.py").read_text().count("code_stub") == 1
    total = 0
    for stem, names in course.items():
        cells = _cells(tmp_path / "course" / "source" / stem / f"{stem}.ipynb")
        graded = _graded(cells)
        assert [c["metadata"]["nbgrader"]["grade_id"] for c in graded] == [
            g for n in names for g in (n, f"check_{n}")
        ]
        code_lines = [
            ln
            for c in cells
            if c["cell_type"] == "code"
            for ln in "".join(c["source"]).splitlines()
        ]
        assert not any(
            ln.startswith("solution(") for ln in code_lines
        )  # the lesson's solution cells are gone
        for solution_cell, test_cell in zip(graded[::2], graded[1::2], strict=True):
            name = solution_cell["metadata"]["nbgrader"]["grade_id"]
            assert solution_cell["metadata"]["nbgrader"]["solution"] is True
            meta = test_cell["metadata"]["nbgrader"]
            assert (meta["grade"], meta["locked"], meta["points"], meta["solution"]) == (
                True,
                True,
                1,
                False,
            )
            assert (
                "### BEGIN SOLUTION" in solution_cell["source"]
                and "### END SOLUTION" in solution_cell["source"]
            )
            namespace: dict = {}
            exec(
                solution_cell["source"], namespace
            )  # the instructor's solution must pass its own check
            assert check(name, namespace[name]).passed is True
            assert test_cell["source"].endswith(
                f'assert check_{name}({name}), "{name}: not attempted yet"'
            )
            total += 1
    assert total == sum(len(n) for n in course.values()) >= 24
    capsys.readouterr()


@pytest.mark.parametrize(
    "args, message",
    [
        (["99"], "no lesson '99'"),
        (["06", "homographies_typo"], "no lesson 'homographies_typo'"),
    ],
)
def test_unknown_lesson_is_one_line_exit_2_and_writes_nothing(tmp_path, capsys, args, message):
    dest = tmp_path / "course"
    assert cli.main(["assignments", str(dest), *args]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1 and "Traceback" not in err
    assert not dest.exists()


def test_non_empty_dest_is_refused_and_left_alone(tmp_path, capsys):
    dest = tmp_path / "course"
    dest.mkdir()
    (dest / "gradebook.db").write_text("last term's grades")
    assert cli.main(["assignments", str(dest), "06"]) == 2
    err = capsys.readouterr().err
    assert "already exists and is not empty" in err and err.count("\n") == 1
    assert [p.name for p in dest.iterdir()] == ["gradebook.db"] and (
        dest / "gradebook.db"
    ).read_text() == "last term's grades"


def test_lesson_without_exercises_is_refused(tmp_path, capsys, monkeypatch):
    real = lessons.lesson_files()
    plain = tmp_path / "lessons" / "99_no_exercises.ipynb"
    plain.parent.mkdir()
    notebook = json.loads(real[6].read_text())
    notebook["cells"] = [c for c in notebook["cells"] if "check_" not in "".join(c["source"])]
    plain.write_text(json.dumps(notebook))
    monkeypatch.setattr(lessons, "lesson_files", lambda: [*real, plain])
    dest = tmp_path / "course"
    assert cli.main(["assignments", str(dest), "06", "99"]) == 2
    err = capsys.readouterr().err
    assert "99_no_exercises has no exercises" in err and err.count("\n") == 1
    assert not dest.exists()  # lesson 06 was fine, but nothing is written when any lesson fails


# Two ways to answer lesson 06, written from first principles (not by calling camlab).
RIGHT = {
    "line_through_points": "def line_through_points(p, q):\n    return np.cross([*p, 1.0], [*q, 1.0])",
    "intersect_lines": "def intersect_lines(l1, l2):\n    return np.cross(l1, l2)",
    "vanishing_point": (
        "def vanishing_point(segments):\n    (a, b), (c, d) = np.asarray(segments, float)\n"
        "    return np.cross(np.cross([*a, 1], [*b, 1]), np.cross([*c, 1], [*d, 1]))"
    ),
    "cross_ratio": (
        "def cross_ratio(points):\n    x = np.asarray(points, float)\n    xy = x[:, :2] / x[:, 2:]\n"
        "    t = (xy - xy[0]) @ (xy[3] - xy[0])\n"
        "    return (t[2] - t[0]) * (t[3] - t[1]) / ((t[2] - t[1]) * (t[3] - t[0]))"
    ),
    "map_conic": "def map_conic(H, C):\n    G = np.linalg.inv(H)\n    return G.T @ C @ G",
    "horizon_line": "def horizon_line(H):\n    return np.linalg.inv(H).T @ np.array([0.0, 0.0, 1.0])",
    "angle_between_lines": (
        "def angle_between_lines(l1, l2, C_star):\n    C = C_star / np.abs(C_star).max()\n"
        "    c = abs(l1 @ C @ l2) / np.sqrt((l1 @ C @ l1) * (l2 @ C @ l2))\n"
        "    return float(np.degrees(np.arccos(np.clip(c, 0.0, 1.0))))"
    ),
}
ONE_WRONG = dict(
    RIGHT,
    intersect_lines="def intersect_lines(l1, l2):\n    x = np.cross(l1, l2)\n    return x[:2] / x[2]",
)


def _nbgrader(course: Path, *args: str) -> None:
    env = dict(os.environ, PATH=f"{BIN}{os.pathsep}{os.environ['PATH']}")  # nbgrader runs `alembic`
    out = subprocess.run(
        [str(BIN / "nbgrader"), *args],
        cwd=course,
        env=env,
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-4000:]


def test_nbgrader_generates_the_assignment_and_autogrades_submissions(tmp_path):
    pytest.importorskip("nbgrader")
    from nbgrader.api import Gradebook

    course, lesson = tmp_path / "course", "06_projective_plane"
    assert cli.main(["assignments", str(course), "06"]) == 0
    _nbgrader(course, "generate_assignment", lesson)
    released = course / "release" / lesson / f"{lesson}.ipynb"
    student_view = released.read_text()
    assert "BEGIN SOLUTION" not in student_view and "camlab.projective.meet(" not in student_view
    assert (
        student_view.count(json.dumps("    raise NotImplementedError")) == 7
    )  # the lesson's own stubs
    for student, answers in [("alice", RIGHT), ("bob", ONE_WRONG), ("carol", {})]:
        nb = json.loads(student_view)
        for cell in _graded(nb["cells"]):
            cell["source"] = answers.get(cell["metadata"]["nbgrader"]["grade_id"], cell["source"])
        folder = course / "submitted" / student / lesson
        folder.mkdir(parents=True)
        (folder / f"{lesson}.ipynb").write_text(json.dumps(nb))
    _nbgrader(course, "autograde", lesson)

    with Gradebook(f"sqlite:///{course / 'gradebook.db'}") as gb:
        scores = {
            s: (gb.find_submission(lesson, s).score, gb.find_submission(lesson, s).max_score)
            for s in ("alice", "bob", "carol")
        }
    assert scores == {"alice": (7.0, 7.0), "bob": (6.0, 7.0), "carol": (0.0, 7.0)}
    graded = _graded(_cells(course / "autograded" / "bob" / lesson / f"{lesson}.ipynb"))
    errors = {
        c["metadata"]["nbgrader"]["grade_id"]: [
            o for o in c["outputs"] if o["output_type"] == "error"
        ]
        for c in graded
        if c["metadata"]["nbgrader"]["grade"]
    }
    assert [k for k, v in errors.items() if v] == ["check_intersect_lines"]
    assert (
        "return the homogeneous 3-vector" in errors["check_intersect_lines"][0]["evalue"]
    )  # the diagnosis stays
    _nbgrader(course, "generate_feedback", lesson)  # what the student gets back
    feedback = (course / "feedback" / "bob" / lesson / f"{lesson}.html").read_text()
    assert "return the homogeneous 3-vector instead" in feedback and "Score: 6.0 / 7.0" in feedback
