"""Find lesson notebooks by number (``07``), stem (``07_homographies``) or file name."""
from __future__ import annotations

from pathlib import Path

from .._validate import CamlabInputError

__all__ = ["find_lesson", "lesson_files"]


def lesson_files() -> list[Path]:
    """Every lesson notebook ``NN_slug.ipynb``, in course order."""
    folder = Path(__file__).resolve().parent.parent.parent / "lessons"
    return sorted(folder.glob("[0-9][0-9]_*.ipynb"))


def find_lesson(spec: str) -> Path:
    """The lesson named by ``spec``: ``"7"``, ``"07"``, ``"07_homographies"`` or ``"07_homographies.ipynb"``.

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
        raise CamlabInputError(f"lesson: no lesson {spec!r}; expected a number or name, one of {known}")
    return matches[0]
