"""Check a built wheel and sdist carry the course: ``python tools/check_dist.py dist/``.

The wheel must hold the package, every lesson, every data file, the conventions page, both
licence files and ``py.typed``; the sdist must hold the top-level folders they come from.
Prints a summary (file counts and sizes per part) and exits non-zero naming what is missing.
"""

from __future__ import annotations

import sys
import tarfile
import zipfile
from collections import Counter
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


def _expected_wheel_files() -> set[str]:
    files = {
        f"camlab/data/files/{p.relative_to(REPO / 'data').as_posix()}"
        for p in (REPO / "data").rglob("*")
        if p.is_file() and not any(s.startswith(".") for s in p.parts)
    }
    files |= {f"camlab/lessons/{p.name}" for p in (REPO / "lessons").glob("*.ipynb")}
    files |= {
        "camlab/lessons/README.md",
        "camlab/docs/conventions.md",
        "camlab/py.typed",
        "camlab/__init__.py",
        "camlab/data/_resources.py",
        "camlab/cli/__init__.py",
        "camlab/cli/main.py",
        "camlab/classroom/jupyter_data/voila/templates/camlab/index.html.j2",  # the lecture view's template
        "camlab/classroom/jupyter_data/voila/templates/camlab/conf.json",
    }
    return files


def check_wheel(path: Path) -> list[str]:
    names = set(zipfile.ZipFile(path).namelist())
    problems = [f"wheel lacks {name}" for name in sorted(_expected_wheel_files() - names)]
    for licence in ("LICENSE", "LICENSE-CONTENT"):
        if not any(n.endswith(f".dist-info/licenses/{licence}") for n in names):
            problems.append(f"wheel lacks the licence file {licence}")
    metadata = next((n for n in names if n.endswith(".dist-info/METADATA")), None)
    text = zipfile.ZipFile(path).read(metadata).decode() if metadata else ""
    if "License-Expression: MIT AND CC-BY-4.0" not in text:
        problems.append("wheel METADATA lacks 'License-Expression: MIT AND CC-BY-4.0'")
    return problems


def check_sdist(path: Path) -> list[str]:
    names = {n.split("/", 1)[1] for n in tarfile.open(path).getnames() if "/" in n}
    wanted = {
        "setup.py",
        "pyproject.toml",
        "LICENSE",
        "LICENSE-CONTENT",
        "README.md",
        "docs/conventions.md",
        "data/ATTRIBUTION.md",
        "lessons/README.md",
    }
    wanted |= {f"lessons/{p.name}" for p in (REPO / "lessons").glob("*.ipynb")}
    return [f"sdist lacks {name}" for name in sorted(wanted - names)]


def summary(wheel: Path) -> str:
    z = zipfile.ZipFile(wheel)
    parts: Counter = Counter()
    sizes: Counter = Counter()
    for info in z.infolist():
        n = info.filename
        part = (
            "data"
            if n.startswith("camlab/data/files/")
            else "lessons"
            if n.startswith("camlab/lessons/")
            else "docs"
            if n.startswith("camlab/docs/")
            else "metadata"
            if ".dist-info/" in n
            else "code"
        )
        parts[part] += 1
        sizes[part] += info.file_size
    rows = [
        f"  {part:9s} {parts[part]:4d} files {sizes[part] / 1e6:6.2f} MB uncompressed"
        for part in sorted(parts)
    ]
    return f"{wheel.name}: {wheel.stat().st_size / 1e6:.2f} MB\n" + "\n".join(rows)


def main(argv: list[str]) -> int:
    dist = Path(argv[0]) if argv else REPO / "dist"
    wheels, sdists = sorted(dist.glob("*.whl")), sorted(dist.glob("*.tar.gz"))
    if len(wheels) != 1 or len(sdists) != 1:
        print(f"check_dist: expected one wheel and one sdist in {dist}, found {wheels + sdists}")
        return 1
    problems = check_wheel(wheels[0]) + check_sdist(sdists[0])
    print(summary(wheels[0]))
    print(f"{sdists[0].name}: {sdists[0].stat().st_size / 1e6:.2f} MB")
    for p in problems:
        print(f"check_dist: {p}")
    return 1 if problems else 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
