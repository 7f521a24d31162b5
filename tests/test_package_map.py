"""The package map in camlab/__init__.py: topics and their main functions, lazy and in one place."""

import ast
import importlib
import subprocess
import sys
from pathlib import Path

import pytest

import camlab


@pytest.mark.parametrize("topic", camlab._TOPICS)
def test_every_topic_imports_and_is_listed_by_dir(topic):
    assert topic in dir(camlab)
    assert getattr(camlab, topic) is importlib.import_module(f"camlab.{topic}")


@pytest.mark.parametrize("name,topic", sorted(camlab._HOME.items()))
def test_every_main_function_is_public_where_it_is_defined(name, topic):
    module = importlib.import_module(f"camlab.{topic}")
    value = getattr(camlab, name)
    assert name in dir(camlab) and name in module.__all__
    assert value is getattr(module, name)
    assert value.__module__.startswith(f"camlab.{topic}"), (
        f"{name} is only re-exported by camlab.{topic}"
    )
    assert (value.__doc__ or "").strip(), f"camlab.{name} has no docstring"


def test_the_docstring_table_lists_every_main_function():
    table = camlab.__doc__
    missing = [name for name in camlab._HOME if name not in table]
    assert not missing, f"add these to the table in camlab/__init__.py: {missing}"


def test_import_camlab_loads_no_topic_and_no_heavy_library():
    code = (
        "import sys, camlab; "
        "print(sorted(m for m in sys.modules if m.startswith('camlab.') or m in ('cv2', 'matplotlib', 'ipywidgets', 'scipy')))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout
    assert out.strip() == (
        "['camlab._validate', 'camlab.projective', 'camlab.projective.conditioning', "
        "'camlab.projective.conics', 'camlab.projective.plane', 'camlab.projective.vanishing', 'camlab.robust']"
    )


def test_an_unknown_name_is_an_attribute_error_that_names_it():
    with pytest.raises(AttributeError, match="no attribute 'estimate_homograpy'"):
        camlab.estimate_homograpy  # noqa: B018


# docs/architecture.md's table: a module imports only from floors below its own.
FLOORS = {
    0: ["_validate", "_access", "_notebook"],
    1: ["_files", "_recent", "optimise", "robust"],
    2: ["pinhole", "lens", "distortion", "sensor", "features", "disparity", "factorization"],
    3: ["projective"],
    4: ["camera", "homography"],
    5: ["affine", "epipolar", "warp", "data"],
    6: ["affine_epipolar", "scenes", "stitching"],
    7: ["render", "perspective"],
    8: ["calibration"],
    9: ["rectification", "measurement", "plotting"],
    10: ["exercises"],
    11: ["fixtures"],
    12: ["widgets", "classroom"],
    13: ["course"],
    14: ["cli"],
}


def _is_module(root: Path, name: str) -> bool:
    return (root / f"{name}.py").is_file() or (root / name / "__init__.py").is_file()


def camlab_imports(root: Path) -> dict[str, set[str]]:
    """{top-level camlab module or package: the top-level camlab modules it imports anywhere in its code}.

    A ``__main__.py`` is left out: it is an entry point that is run (``python -m camlab.data``),
    never imported, so it may call code above its package."""
    graph: dict[str, set[str]] = {}
    for path in sorted(root.rglob("*.py")):
        parts = path.relative_to(root).with_suffix("").parts
        if parts[0] == "__init__" or parts[-1] == "__main__":
            continue
        found = graph.setdefault(parts[0], set())
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.ImportFrom) and node.level:
                base = list(parts[:-1])[: len(parts) - node.level]
                target = [*base, *(node.module.split(".") if node.module else [])]
                found.update(
                    [target[0]]
                    if target
                    else [a.name for a in node.names if _is_module(root, a.name)]
                )
            elif isinstance(node, ast.ImportFrom) and node.module == "camlab":
                found.update(a.name for a in node.names if _is_module(root, a.name))
            elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("camlab."):
                found.add(node.module.split(".")[1])
            elif isinstance(node, ast.Import):
                found.update(
                    a.name.split(".")[1] for a in node.names if a.name.startswith("camlab.")
                )
        found.discard(parts[0])
    return graph


def upward_imports(root: Path, floors: dict[int, list[str]]) -> list[str]:
    floor = {module: level for level, modules in floors.items() for module in modules}
    graph = camlab_imports(root)
    unplaced = sorted(set(graph) - set(floor))
    wrong = [
        f"{m} (floor {floor[m]}) imports {d} (floor {floor.get(d, '?')})"
        for m, deps in sorted(graph.items())
        if m in floor
        for d in sorted(deps)
        if floor.get(d, 99) >= floor[m]
    ]
    return [f"{m} has no floor in docs/architecture.md" for m in unplaced] + wrong


def test_every_module_imports_only_from_lower_floors():
    assert upward_imports(Path(camlab.__file__).parent, FLOORS) == []


def test_the_floor_check_can_fail(tmp_path):
    pkg = tmp_path / "camlab"
    (pkg / "data").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "data" / "__init__.py").write_text("")
    (pkg / "camera.py").write_text(
        "def f():\n    from .data import load_photo\n"
    )  # an algorithm reaching up
    (pkg / "data" / "photos.py").write_text("from ..camera import f\nfrom camlab import widgets\n")
    (pkg / "newtopic.py").write_text("")
    (pkg / "widgets.py").write_text("from . import __version__\n")
    assert upward_imports(pkg, {2: ["camera"], 8: ["data"], 9: ["widgets"]}) == [
        "newtopic has no floor in docs/architecture.md",
        "camera (floor 2) imports data (floor 8)",
        "data (floor 8) imports widgets (floor 9)",
    ]


def test_the_algorithms_never_import_data():
    """data sits at floor 3 (loaders on the camera model), but a lesson passes data in: only the
    fixtures and what stands on them load it (docs/architecture.md)."""
    graph = camlab_imports(Path(camlab.__file__).parent)
    importers = sorted(m for m, deps in graph.items() if "data" in deps)
    assert set(importers) <= {"fixtures", "widgets", "classroom", "course", "cli"}, importers
