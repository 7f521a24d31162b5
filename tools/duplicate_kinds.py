"""Sort the pairs `duplicates` reports for camlab/ into declarations and logic.

Usage (from the repository root)::

    cd camlab && duplicates --most 200 --seconds 150 > /tmp/pairs.txt
    python tools/duplicate_kinds.py /tmp/pairs.txt [--root camlab]

`duplicates` lists pairs of places sharing six or more lines, the same or of the same shape.
Issue 27 asks that what remains be *declarations*: lines alike because they declare different
things in one form (docs/architecture.md, "Repeated shapes that stay"). A side of a pair counts as
declaration when at least 60 % of its lines are

* docstrings, signatures, decorators, imports, blank lines and comments;
* an ``__all__`` list;
* inside a call that declares rather than computes: an exercise's ``register_exercise`` /
  ``Exercise`` / ``Mistake`` tables, a demo's ``build_demo`` / ``slider`` / ``SimpleNamespace``,
  a matplotlib artist (``ax.plot([], [], ...)``, ``ax.text``, patches), an ``argparse`` option,
  a shared validator's call (``as_point_pairs``).

A pair is declaration when both sides are; `duplicates`' own "boilerplate" rows are counted apart.
Everything else is printed as LOGIC: the places to give one home (or to name in the
architecture page with the reason they stay). Exit status 0 always: this sorts, it does not judge.
"""

from __future__ import annotations

import argparse
import ast
import re
from functools import cache
from pathlib import Path

DECLARING_CALLS = frozenset(
    "register_exercise Exercise Mistake register build_demo SimpleNamespace slider animate plot "
    "text add_patch Circle annotate as_point_pairs FloatSlider IntSlider Layout warning_note "
    "legend scatter imshow Rectangle Polygon FancyArrowPatch add_argument _wrong_way_round dict update "
    "FloatLogSlider int_slider".split()
)
ROW = re.compile(r"(D\d+) (\S+):(\d+)-(\d+) ~ (\S+):(\d+)-(\d+)")


def _span(node: ast.AST) -> range:
    return range(node.lineno, node.end_lineno + 1)


def _docstring(node: ast.AST) -> ast.AST | None:
    body = getattr(node, "body", None)
    first = body[0] if body else None
    if isinstance(first, ast.Expr) and isinstance(getattr(first, "value", None), ast.Constant):
        return first if isinstance(first.value.value, str) else None
    return None


def _call_name(call: ast.Call) -> str:
    return getattr(call.func, "id", getattr(call.func, "attr", ""))


@cache
def declaration_lines(path: Path) -> frozenset[int]:
    """The line numbers of ``path`` that declare (see the module docstring); none outside Python."""
    if path.suffix != ".py":
        return frozenset()  # the browser's JavaScript: every duplicated line is logic
    source = path.read_text(encoding="utf-8")
    lines: set[int] = set()
    for node in ast.walk(ast.parse(source)):
        doc = (
            _docstring(node)
            if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef))
            else None
        )
        if doc is not None:
            lines.update(_span(doc))
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            lines.update(range(node.lineno, node.body[0].lineno))
            for decorator in node.decorator_list:
                lines.update(_span(decorator))
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            lines.update(_span(node))
        elif isinstance(node, ast.Assign) and any(
            getattr(t, "id", "") == "__all__" for t in node.targets
        ):
            lines.update(_span(node))
        elif isinstance(node, ast.Call) and _call_name(node) in DECLARING_CALLS:
            lines.update(_span(node))
    for number, line in enumerate(source.splitlines(), 1):
        if not line.strip() or line.strip().startswith("#"):
            lines.add(number)
    return frozenset(lines)


def declared_share(path: Path, first: int, last: int) -> float:
    """The share of lines ``first``..``last`` of ``path`` that declare."""
    span = set(range(first, last + 1))
    return len(span & declaration_lines(path)) / len(span)


def sort_pairs(report: str, root: Path) -> dict[str, list[str]]:
    """Each row of a `duplicates` report under "declaration", "boilerplate" or "logic"."""
    kinds: dict[str, list[str]] = {"declaration": [], "boilerplate": [], "logic": []}
    for row in report.splitlines():
        match = ROW.match(row)
        if not match:
            continue
        _, a, a0, a1, b, b0, b1 = match.groups()
        share = min(
            declared_share(root / a, int(a0), int(a1)), declared_share(root / b, int(b0), int(b1))
        )
        kind = "declaration" if share >= 0.6 else "boilerplate" if "boilerplate" in row else "logic"
        kinds[kind].append(row.strip())
    return kinds


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("report", type=Path, help="the output of `duplicates` run in --root")
    parser.add_argument("--root", type=Path, default=Path("camlab"), help="where duplicates ran")
    args = parser.parse_args()
    kinds = sort_pairs(args.report.read_text(encoding="utf-8"), args.root)
    print(", ".join(f"{len(rows)} {kind}" for kind, rows in kinds.items()))
    for row in kinds["logic"]:
        print("LOGIC", row)


if __name__ == "__main__":
    main()
