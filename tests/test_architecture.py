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
    "camlab.exercises.projective_camera.rq.rq_decomposition": "an exercise's teaching solution",
    "camlab.exercises.sensor_noise.gain_and_read_noise": "an exercise's teaching solution",
    "camlab.exercises.start_here.conventions.read_and_turn": "an exercise's teaching solution",
    "camlab.exercises.stereo_rectification.epipoles.epipoles": "an exercise's teaching solution",
    "camlab.exercises.stereo_rectification.essential.decompose_essential": "an exercise's teaching solution",
    "camlab.exercises.perspective_correction.shape.rectangle_shape": "an exercise's teaching solution",
    "camlab.exercises.image_stitching.focal.focal_from_rotation_homography": "an exercise's teaching solution",
    # a sequence of artists splatted into view.animate(*...), not a record of named values
    "camlab.widgets.affine_cameras.common.reference_marker": "a sequence of artists, not a record",
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


# camlab.data is the bottom of the course's data: loaders that read the shipped files and build
# the camera model from their ground truth (Camera, scale_intrinsics, the homography of a
# rotation). Whatever runs an algorithm to make or prepare data (the generators, the pipelines
# cached for the demos) is a fixture: camlab.fixtures, above the algorithms (docs/architecture.md).
DATA_MAY_IMPORT = {"_validate", "_files", "camera", "homography"}


def data_imports(root: Path) -> list[str]:
    """The camlab modules that camlab.data imports beyond :data:`DATA_MAY_IMPORT`, as 'file: module'.

    Every import counts, at module level or inside a function; ``data/__main__.py`` (the
    ``python -m camlab.data`` entry point, run and never imported) is left out."""
    found = []
    for path in sorted((root / "data").rglob("*.py")):
        if path.name == "__main__.py":
            continue
        rel = path.relative_to(root)
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.ImportFrom) and node.level:
                base = list(rel.with_suffix("").parts[:-1])[: len(rel.parts) - node.level]
                target = [*base, *(node.module.split(".") if node.module else [])]
                modules = [target[0]] if target else [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("camlab."):
                modules = [node.module.split(".")[1]]
            elif isinstance(node, ast.ImportFrom) and node.module == "camlab":
                modules = [a.name for a in node.names]
            elif isinstance(node, ast.Import):
                modules = [a.name.split(".")[1] for a in node.names if a.name.startswith("camlab.")]
            else:
                continue
            found += [
                f"{rel.as_posix()}: {m}" for m in modules if m not in DATA_MAY_IMPORT | {"data"}
            ]
    return found


def test_data_imports_no_algorithm_module():
    """Loaders only: what renders, calibrates, stitches or rectifies belongs in camlab.fixtures."""
    assert data_imports(ROOT) == []


def test_the_data_rule_can_fail(tmp_path):
    pkg = tmp_path / "camlab"
    (pkg / "data").mkdir(parents=True)
    (pkg / "data" / "__init__.py").write_text("from .sets import load\n")
    (pkg / "data" / "__main__.py").write_text("from ..fixtures import main\n")  # an entry point
    (pkg / "data" / "sets.py").write_text(
        "from .._validate import check_size\nfrom ..camera import Camera\n"
        "def load():\n    from .. import render\n    from camlab.stitching import stitch\n"
        "    from camlab import rectification\n"
    )
    assert data_imports(pkg) == [
        "data/sets.py: render",
        "data/sets.py: stitching",
        "data/sets.py: rectification",
    ]


def _module_of(path: Path, root: Path) -> str:
    parts = path.relative_to(root.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def stray_reexports(root: Path) -> list[str]:
    """Public names importable from three places or more: where they are defined, the curated
    map, and more than one other module.

    The curated map is ``camlab`` itself together with the package that presents the name's
    module (a package's ``__init__`` is the face of its modules, and ``camlab``'s lazy map reads
    through it: ``camlab.calibrate_camera`` is ``camlab.calibration.calibrate_camera``). A module
    re-exports a name when its ``__all__`` lists an imported name (or, without ``__all__``, when
    it is a package ``__init__`` importing it). One more home beside those two is allowed; a
    third is not."""
    defined: dict[str, set[str]] = {}
    imported: dict[str, dict[str, str]] = {}  # module -> {local name: module it comes from}
    exported: dict[str, set[str]] = {}
    for path in sorted(root.rglob("*.py")):
        module = _module_of(path, root)
        is_package = path.name == "__init__.py"
        tree = ast.parse(path.read_text(), str(path))
        names, sources, public = set(), {}, None
        for node in tree.body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                names.add(node.name)
            elif isinstance(node, ast.Assign):
                targets = [t.id for t in node.targets if isinstance(t, ast.Name)]
                if targets == ["__all__"]:
                    public = set(ast.literal_eval(node.value))
                names.update(targets)
            elif isinstance(node, ast.ImportFrom):
                source = (
                    _resolve(module, is_package, node.level, node.module)
                    if node.level
                    else (node.module or "")
                )
                if source.startswith(root.name):
                    for a in node.names:
                        sources[a.asname or a.name] = f"{source}.{a.name}"
        defined[module], imported[module] = names, sources
        if public is None:
            public = set(sources) if is_package else set()
        exported[module] = {n for n in public if n in sources and not _private(n)}

    def home(dotted: str) -> str | None:
        """The module that defines ``dotted`` (``module.name``), following re-exports."""
        for _ in range(10):
            module, _, name = dotted.rpartition(".")
            if name in defined.get(module, ()):
                return module
            if name not in imported.get(module, {}):
                return None  # a module, or a name from outside the scan
            dotted = imported[module][name]
        return None

    mapped: dict[tuple[str, str], bool] = {}  # (name, home) -> in the curated map
    strays: dict[tuple[str, str], list[str]] = {}
    for module in sorted(exported):
        for name in sorted(exported[module]):
            where = home(imported[module][name])
            if where is None:
                continue
            if module == root.name or where.startswith(module + "."):
                mapped[name, where] = True
            else:
                strays.setdefault((name, where), []).append(module)
    return [
        f"{name} (defined in {where}) is re-exported by {', '.join(modules)}"
        for (name, where), modules in sorted(strays.items())
        if 1 + mapped.get((name, where), False) + len(modules) >= 3
    ]


def test_no_name_is_importable_from_a_third_place():
    """One home per name (its module, and the package that presents it) plus camlab's map."""
    assert stray_reexports(ROOT) == []


def test_the_reexport_scan_can_fail(tmp_path):
    pkg = tmp_path / "camlab"
    (pkg / "scenes").mkdir(parents=True)
    (pkg / "__init__.py").write_text("from .scenes.planes import box\n")  # the map: fine
    (pkg / "scenes" / "__init__.py").write_text("from .planes import box\n")  # its package: fine
    (pkg / "scenes" / "planes.py").write_text("def box():\n    pass\n\ndef _helper():\n    pass\n")
    (pkg / "render.py").write_text(  # a sibling: a third place
        "from .scenes import box\nfrom .scenes.planes import _helper\n"
        "__all__ = ['box', '_helper', 'render']\n\ndef render():\n    box()\n"
    )
    (pkg / "perspective.py").write_text("from .scenes import box\n")  # used, not re-exported
    (pkg / "camera.py").write_text("def turn():\n    pass\n")
    (pkg / "calibration.py").write_text("from .camera import turn\n__all__ = ['turn']\n")
    assert stray_reexports(pkg) == [
        "box (defined in camlab.scenes.planes) is re-exported by camlab.render"
    ]  # camera.turn has one more home, calibration: two places, allowed
    (pkg / "stitching.py").write_text("from .camera import turn\n__all__ = ['turn']\n")
    assert stray_reexports(pkg) == [
        "box (defined in camlab.scenes.planes) is re-exported by camlab.render",
        "turn (defined in camlab.camera) is re-exported by camlab.calibration, camlab.stitching",
    ]
