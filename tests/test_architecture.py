"""Architecture rules checked on the source: no module reaches into another module's privates."""

import ast
import sys
from pathlib import Path

import camlab

ROOT = Path(camlab.__file__).parent


def _module_name(path: Path) -> str:
    parts = path.relative_to(ROOT.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _resolve(current: str, is_package: bool, level: int, module: str | None) -> str:
    base = current.split(".") if is_package else current.split(".")[:-1]
    if level > 1:
        base = base[: len(base) - (level - 1)]
    return ".".join(base + ([module] if module else []))


def _private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def private_imports() -> list[str]:
    """Every place a camlab module imports, or reads as an attribute, another module's _private name."""
    found = []
    for path in sorted(ROOT.rglob("*.py")):
        name = _module_name(path)
        tree = ast.parse(path.read_text(), str(path))
        aliases: dict[str, str] = {}  # local name -> camlab module it refers to
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                target = (
                    _resolve(name, path.name == "__init__.py", node.level, node.module)
                    if node.level
                    else (node.module or "")
                )
                if not target.startswith("camlab"):
                    continue
                for a in node.names:
                    if _private(a.name) and not _is_module(f"{target}.{a.name}"):
                        if target != name:
                            found.append(f"{name}: from {target} import {a.name}")
                    else:
                        aliases[a.asname or a.name] = (
                            f"{target}.{a.name}" if _is_module(f"{target}.{a.name}") else ""
                        )
            elif isinstance(node, ast.Import):
                for a in node.names:
                    if a.name.startswith("camlab"):
                        aliases[a.asname or a.name.split(".")[0]] = a.name if a.asname else "camlab"
        for node in ast.walk(tree):
            if (
                isinstance(node, ast.Attribute)
                and isinstance(node.value, ast.Name)
                and _private(node.attr)
            ):
                module = aliases.get(node.value.id)
                if module and module != name:
                    found.append(f"{name}: {node.value.id}.{node.attr} ({module})")
    return found


def _is_module(dotted: str) -> bool:
    rel = Path(*dotted.split("."))
    return (ROOT.parent / rel).with_suffix(".py").is_file() or (
        ROOT.parent / rel / "__init__.py"
    ).is_file()


def test_no_module_imports_another_modules_private_names():
    """If two modules need a helper, it becomes a public name (a private name is one module's business)."""
    assert private_imports() == []


def test_the_scan_finds_a_private_import(tmp_path, monkeypatch):
    """The rule can fail: a fake package that imports a private name is caught."""
    pkg = tmp_path / "camlab"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("def _helper():\n    return 1\n")
    (pkg / "b.py").write_text("from .a import _helper\nfrom . import a as _a\nx = _a._helper()\n")
    monkeypatch.setattr(sys.modules[__name__], "ROOT", pkg)
    assert private_imports() == [
        "camlab.b: from camlab.a import _helper",
        "camlab.b: _a._helper (camlab.a)",
    ]


_CACHES = {"lru_cache", "cache"}


def _decorator_name(node: ast.expr) -> str:
    node = node.func if isinstance(node, ast.Call) else node
    return node.attr if isinstance(node, ast.Attribute) else getattr(node, "id", "")


def widget_data_caches(widgets: Path) -> list[str]:
    """Module-level cached functions in the widget modules: data computed once and kept for every demo.

    Widget modules hold controls, artists and ``update``; data sets and the
    pipelines that prepare them are core (camlab.data, camlab.stitching ...), public and
    tested. Every such pipeline found in a widget module was a module-level ``lru_cache``;
    a memo local to one demo's builder (what its sliders revisit) is part of ``update``.
    """
    found = []
    for path in sorted(widgets.glob("*.py")):
        for node in ast.parse(path.read_text(), str(path)).body:
            if isinstance(node, ast.FunctionDef) and any(
                _decorator_name(d) in _CACHES for d in node.decorator_list
            ):
                found.append(f"{path.stem}.{node.name}")
    return found


def test_widget_modules_hold_no_data_pipelines():
    assert widget_data_caches(ROOT / "widgets") == []


def test_the_scan_finds_a_cached_pipeline_in_a_widget_module(tmp_path):
    """The rule can fail: module-level caches are caught, a builder's local memo is not."""
    (tmp_path / "demo.py").write_text(
        "import functools\nfrom functools import lru_cache\n\n"
        "@lru_cache(maxsize=1)\ndef prepared():\n    return 1\n\n"
        "@functools.cache\ndef more():\n    return 2\n\n"
        "def builder():\n    @lru_cache\n    def memo(x):\n        return x\n    return memo\n"
    )
    assert widget_data_caches(tmp_path) == ["demo.prepared", "demo.more"]


BENCHMARKS = ROOT.parent / "benchmarks"


def test_benchmark_scripts_share_one_timing_module(monkeypatch):
    """The timing and table helpers live in benchmarks/_timing.py only."""
    monkeypatch.syspath_prepend(str(BENCHMARKS))
    import _timing

    shared = {
        name
        for name, value in vars(_timing).items()
        if callable(value) and getattr(value, "__module__", "") == "_timing"
    }
    assert {"timed", "time_calls", "median_ms", "paired_ms", "print_table"} <= shared
    twins = []
    for path in sorted(BENCHMARKS.glob("*.py")):
        if path.name == "_timing.py":
            continue
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.FunctionDef) and node.name in shared:
                twins.append(f"{path.name}: def {node.name}")
    assert twins == []
    value, seconds = _timing.timed(lambda: 41 + 1)
    assert value == 42 and 0 <= seconds < 1
    assert len(_timing.time_calls(lambda: None, repeat=3, warmup=0)) == 3


def test_no_unused_function_parameters():
    """A parameter nobody reads is a lie in the signature (pyflakes misses them; ruff's ARG001
    finds them). Exercise checkers are left out: their ``diagnose(args, got, expected)`` and wrong-answer
    variants keep the signature of the function the learner writes."""
    import shutil
    import subprocess

    ruff = shutil.which("ruff", path=str(Path(sys.executable).parent)) or shutil.which("ruff")
    if ruff is None:
        import pytest

        pytest.skip("ruff is not installed (it comes with the [test] extra)")
    out = subprocess.run(
        [
            ruff,
            "check",
            "--no-cache",
            "--select",
            "ARG001",
            "--output-format",
            "concise",
            "--exclude",
            "camlab/exercises",
            str(ROOT),
        ],
        capture_output=True,
        text=True,
        cwd=ROOT.parent,
    )
    assert out.returncode == 0, out.stdout


# Public functions that return several values return a NamedTuple with documented fields
# (docs/conventions.md, "Results"): ``K, R = rq_decomposition(M)`` still unpacks, and
# ``rq_decomposition(M).K`` says what it is. These may stay bare, each for its reason:
BARE_TUPLES_ALLOWED = {
    # the teaching solutions of lesson exercises: the code a student writes for the prompt
    # ("return K, R"), shown as the answer; the exercise's reference is the named camlab result
    "camlab.exercises.projective_camera.rq_decomposition": "an exercise's teaching solution",
    "camlab.exercises.sensor_noise.gain_and_read_noise": "an exercise's teaching solution",
    "camlab.exercises.stereo_rectification.epipoles": "an exercise's teaching solution",
    "camlab.exercises.stereo_rectification.decompose_essential": "an exercise's teaching solution",
    # a sequence of artists splatted into view.animate(*...), not a record of named values
    "camlab.widgets.affine_cameras.reference_marker": "a sequence of artists, not a record",
}


def _returns_a_bare_tuple(fn: ast.FunctionDef) -> bool:
    annotation = ast.unparse(fn.returns) if fn.returns else ""
    if annotation.split("[")[0].strip() in ("tuple", "Tuple", "typing.Tuple"):
        return True
    stack = list(fn.body)
    while stack:
        node = stack.pop()
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef)):
            continue  # a nested function's returns are its own
        if isinstance(node, ast.Return) and (
            isinstance(node.value, ast.Tuple)
            or (
                isinstance(node.value, ast.Call)
                and isinstance(node.value.func, ast.Name)
                and node.value.func.id == "tuple"
            )
        ):
            return True
        stack.extend(ast.iter_child_nodes(node))
    return False


def bare_tuple_returns(root: Path) -> list[str]:
    """Public functions and methods of public classes, in public modules, that return a bare tuple
    (``return a, b``, ``return tuple(...)``, or a ``-> tuple[...]`` annotation)."""
    found = []
    for path in sorted(root.rglob("*.py")):
        parts = path.relative_to(root.parent).with_suffix("").parts
        if any(_private(p) for p in parts):
            continue
        module = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        for node in ast.parse(path.read_text(), str(path)).body:
            functions = [("", node)]
            if isinstance(node, ast.ClassDef) and not _private(node.name):
                functions = [(f"{node.name}.", item) for item in node.body]
            for prefix, fn in functions:
                if (
                    isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef))
                    and not _private(fn.name)
                    and _returns_a_bare_tuple(fn)
                ):
                    found.append(f"{module}.{prefix}{fn.name}")
    return found


def test_public_functions_return_named_results():
    found = bare_tuple_returns(ROOT)
    new = [name for name in found if name not in BARE_TUPLES_ALLOWED]
    assert new == [], (
        f"return a NamedTuple with documented fields (docs/conventions.md, 'Results'): {new}"
    )
    stale = sorted(set(BARE_TUPLES_ALLOWED) - set(found))
    assert stale == [], f"no longer bare: take them off BARE_TUPLES_ALLOWED: {stale}"


def test_the_scan_finds_a_bare_tuple(tmp_path):
    """The rule can fail: every way of returning a bare tuple is caught; named results, private
    functions, private modules and nested helpers are not."""
    pkg = tmp_path / "camlab"
    pkg.mkdir()
    (pkg / "_private.py").write_text("def f():\n    return 1, 2\n")
    (pkg / "a.py").write_text(
        "from typing import NamedTuple\n\n"
        "class Pair(NamedTuple):\n    a: int\n    b: int\n\n"
        "    def swapped(self):\n        return self.b, self.a\n\n"
        "def literal(x):\n    if x:\n        return x, x\n    return Pair(1, 2)\n\n"
        "def made():\n    return tuple(range(2))\n\n"
        "def annotated() -> tuple[int, int]:\n    return divmod(7, 2)\n\n"
        "def named() -> Pair:\n    def helper():\n        return 1, 2\n    return Pair(*helper())\n\n"
        "def _private():\n    return 1, 2\n"
    )
    assert bare_tuple_returns(pkg) == [
        "camlab.a.Pair.swapped",
        "camlab.a.literal",
        "camlab.a.made",
        "camlab.a.annotated",
    ]
