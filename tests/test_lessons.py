"""Static checks on every lesson notebook (nbval executes them in the same pytest run)."""

import json
import re
from pathlib import Path

import pytest

LESSONS = sorted((Path(__file__).parent.parent / "lessons").glob("[0-9][0-9]_*.ipynb"))


def _cells(path: Path) -> list[dict]:
    return json.loads(path.read_text(encoding="utf-8"))["cells"]


def _source(cell: dict) -> str:
    return "".join(cell["source"])


def test_lessons_exist_and_are_listed_in_the_index():
    assert LESSONS, "no lessons found"
    index = (LESSONS[0].parent / "README.md").read_text(encoding="utf-8")
    for path in LESSONS:
        assert path.name in index, f"lessons/README.md does not list {path.name}"


@pytest.mark.parametrize("path", LESSONS, ids=lambda p: p.name)
def test_committed_stripped(path):
    nb = json.loads(path.read_text(encoding="utf-8"))
    for i, cell in enumerate(nb["cells"]):
        if cell["cell_type"] == "code":
            assert not cell["outputs"], f"{path.name} cell {i} carries outputs: run `make strip`"
            assert cell["execution_count"] is None, (
                f"{path.name} cell {i} has an execution count: run `make strip`"
            )
    assert "widgets" not in nb.get("metadata", {}), (
        f"{path.name} carries widget state: run `make strip`"
    )


@pytest.mark.parametrize("path", LESSONS, ids=lambda p: p.name)
def test_lesson_anatomy(path):
    cells = _cells(path)
    number = path.name[:2]
    first = _source(cells[0])
    assert cells[0]["cell_type"] == "markdown" and re.match(rf"# {number} · \S", first), (
        f"{path.name}: the first cell must be a title '# {number} · Verb ...'"
    )
    markdown = "\n".join(_source(c) for c in cells if c["cell_type"] == "markdown")
    code = [_source(c) for c in cells if c["cell_type"] == "code"]
    for heading in ("## Objectives", "## Summary"):
        assert heading in markdown, f"{path.name}: missing '{heading}'"
    assert "%matplotlib widget" in code[0] and "default_rng" in code[0], (
        f"{path.name}: the first code cell is the setup (%matplotlib widget, imports, rng)"
    )
    assert any(re.search(r"\bcheck_\w+\(", c) for c in code), f"{path.name}: no exercise check"
    for c in code:
        assert "pip install" not in c and "http" not in c, (
            f"{path.name}: no installs or network in lessons"
        )
        assert not re.search(r"['\"]/(home|root|work|tmp)/", c), f"{path.name}: no absolute paths"


# Lessons whose self-check questions must each carry a revealable answer (extend lesson by lesson).
ANSWERED_LESSONS = {"00", "01", "02", "03", "04", "05", "06", "07", "08", "10", "11", "12"}
_QUESTION = re.compile(r"^(?:\d+\.|\*\*\d+\.\*\*)\s", re.MULTILINE)


def self_check_questions(markdown: str) -> list[str]:
    """The self-check section split into one chunk per numbered question (question + what follows)."""
    match = re.search(
        r"^## Self-check questions\s*$(.*?)(?=^## |\Z)", markdown, re.MULTILINE | re.DOTALL
    )
    if not match:
        return []
    section = match.group(1)
    starts = [m.start() for m in _QUESTION.finditer(section)]
    return [section[a:b] for a, b in zip(starts, starts[1:] + [len(section)], strict=True)]


@pytest.mark.parametrize(
    "path", [p for p in LESSONS if p.name[:2] in ANSWERED_LESSONS], ids=lambda p: p.name
)
def test_every_self_check_question_has_a_revealable_answer(path):
    markdown = "\n".join(_source(c) for c in _cells(path) if c["cell_type"] == "markdown")
    questions = self_check_questions(markdown)
    assert len(questions) >= 2, (
        f"{path.name}: '## Self-check questions' needs at least two numbered questions"
    )
    for chunk in questions:
        first = chunk.splitlines()[0]
        answer = re.search(r"<details>\s*<summary>[^<]+</summary>(.*?)</details>", chunk, re.DOTALL)
        assert answer, (
            f"{path.name}: question {first!r} has no <details><summary>Answer</summary> ... </details>"
        )
        assert len(answer.group(1).strip()) >= 20, f"{path.name}: the answer to {first!r} is empty"


def test_self_check_parser_sees_a_missing_answer():
    md = (
        "## Self-check questions\n1. Why?\n<details><summary>Answer</summary>\n\nBecause of this and that.\n"
        "</details>\n\n2. And why not?\n\n## Summary\n"
    )
    chunks = self_check_questions(md)
    assert len(chunks) == 2 and "<details>" in chunks[0] and "<details>" not in chunks[1]
