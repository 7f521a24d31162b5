"""The size rule: a module a reader finishes in one sitting, a function that does one job.

No camlab module over 600 lines of code; no function (or method, or nested function) over 80
lines of code. A function's lines of code are its physical lines from its first decorator to its
last line, less its docstring, its blank lines and its comment-only lines; a module's are its
physical lines less its docstrings (the module's, its classes' and its functions': the numpydoc
sections every public function carries, docs/conventions.md, must not force a split), blank
lines and comment-only lines. Anything over either
limit is listed in ``EXCEPTIONS`` with the reason it stays long; an exception that no longer
applies fails too, so the list only shrinks.
"""

import ast
from pathlib import Path

import camlab

ROOT = Path(camlab.__file__).parent
MAX_MODULE_LINES = 600
MAX_FUNCTION_LINES = 80

# {qualified name: why it is still over the limit}. A module is keyed by its dotted name
# (camlab.projective), a function by module, classes and enclosing functions
# (camlab.optimise.levenberg_marquardt, camlab.widgets.projective_camera.resectioning.update).
EXCEPTIONS = {}


def _module_name(path: Path, root: Path) -> str:
    parts = path.relative_to(root.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def function_code_lines(lines: list[str], node: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    """Lines of code of one function: from its first decorator to its end, less the docstring,
    blank lines and comment-only lines (a nested function's lines count in its parent too)."""
    start = min([node.lineno] + [d.lineno for d in node.decorator_list])
    first = node.body[0]
    docstring = (
        range(first.lineno, first.end_lineno + 1)
        if isinstance(first, ast.Expr)
        and isinstance(first.value, ast.Constant)
        and isinstance(first.value.value, str)
        else range(0)
    )
    return sum(
        1
        for number in range(start, node.end_lineno + 1)
        if number not in docstring
        and lines[number - 1].strip()
        and not lines[number - 1].strip().startswith("#")
    )


def _docstring_lines(tree: ast.AST) -> set[int]:
    """The line numbers of every docstring in a module: its own, its classes' and functions'."""
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef):
            first = node.body[0] if node.body else None
            if (
                isinstance(first, ast.Expr)
                and isinstance(first.value, ast.Constant)
                and isinstance(first.value.value, str)
            ):
                found.update(range(first.lineno, first.end_lineno + 1))
    return found


def module_code_lines(lines: list[str], tree: ast.AST) -> int:
    """Lines of code of one module: its lines less docstrings, blank and comment-only lines."""
    docstrings = _docstring_lines(tree)
    return sum(
        1
        for number, line in enumerate(lines, start=1)
        if number not in docstrings and line.strip() and not line.strip().startswith("#")
    )


def _oversized_functions(node: ast.AST, prefix: str, lines: list[str], found: dict) -> None:
    for child in ast.iter_child_nodes(node):
        if isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef):
            name = f"{prefix}.{child.name}"
            size = function_code_lines(lines, child)
            if size > MAX_FUNCTION_LINES:
                found[name] = size
            _oversized_functions(child, name, lines, found)
        elif isinstance(child, ast.ClassDef):
            _oversized_functions(child, f"{prefix}.{child.name}", lines, found)
        else:
            _oversized_functions(child, prefix, lines, found)


def oversized(root: Path = ROOT) -> dict[str, int]:
    """{qualified name: size} of every module over MAX_MODULE_LINES lines of code and every
    function over MAX_FUNCTION_LINES lines of code below ``root``."""
    found = {}
    for path in sorted(root.rglob("*.py")):
        source = path.read_text()
        lines = source.splitlines()
        module = _module_name(path, root)
        tree = ast.parse(source, str(path))
        size = module_code_lines(lines, tree)
        if size > MAX_MODULE_LINES:
            found[module] = size
        _oversized_functions(tree, module, lines, found)
    return found


def test_no_module_or_function_is_over_the_size_limits():
    over = {name: size for name, size in oversized().items() if name not in EXCEPTIONS}
    assert not over, (
        f"over {MAX_MODULE_LINES} lines (module) or {MAX_FUNCTION_LINES} lines of code "
        f"(function): {over}. Split by topic (a module) or by step (a function); if it must "
        "stay long, add it to EXCEPTIONS in tests/test_sizes.py with the reason."
    )


def test_every_exception_is_still_needed_and_says_why():
    over = oversized()
    stale = sorted(name for name in EXCEPTIONS if name not in over)
    assert not stale, f"now within the limits: delete these from EXCEPTIONS: {stale}"
    assert all(reason.strip() for reason in EXCEPTIONS.values())


def test_the_scan_finds_a_long_module_and_a_long_function(tmp_path):
    """The rule can fail: a long module and a long nested function are caught; docstrings,
    blank lines and comments do not count in either."""
    pkg = tmp_path / "camlab"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "big.py").write_text("x = 1\n" * (MAX_MODULE_LINES + 1))
    (pkg / "documented.py").write_text(
        '"""A module."""\n' + "x = 1\n" * (MAX_MODULE_LINES - 1) + 'def f():\n    """Doc.\n\n"""\n'
    )
    body = "    y = 1\n" * MAX_FUNCTION_LINES
    doc = '    """' + "\n" * 50 + '    """\n'
    (pkg / "fits.py").write_text(
        "def f():\n" + doc + "\n    # note\n" * 30 + body[: -len("    y = 1\n")]
    )
    (pkg / "sub.py").write_text(
        "class A:\n    def outer(self):\n        def inner():\n"
        + "            y = 1\n" * MAX_FUNCTION_LINES
        + "        return inner\n"
    )
    assert oversized(pkg) == {
        "camlab.big": MAX_MODULE_LINES + 1,
        "camlab.sub.A.outer": MAX_FUNCTION_LINES + 3,
        "camlab.sub.A.outer.inner": MAX_FUNCTION_LINES + 1,
    }
