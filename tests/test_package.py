"""Packaging promises: a light import and lazy topic modules."""

import re
import subprocess
import sys
from pathlib import Path

import pytest

import camlab

REPO = Path(__file__).resolve().parent.parent


def test_import_camlab_is_light():
    code = (
        "import sys, camlab; heavy = [m for m in ('matplotlib', 'ipywidgets', 'cv2', 'scipy') "
        "if m in sys.modules]; print(','.join(heavy))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "", f"import camlab pulled in {out.stdout.strip()}"


def test_submodules_load_lazily_and_unknown_names_fail_clearly():
    assert camlab.projective.join is camlab.join
    with pytest.raises(AttributeError, match="no attribute 'nonexistent'"):
        camlab.nonexistent  # noqa: B018


def test_errors_are_value_errors():
    assert issubclass(camlab.CamlabInputError, ValueError)
    assert issubclass(camlab.DegenerateError, camlab.CamlabInputError)


def _project() -> dict:
    import tomllib

    return tomllib.loads((REPO / "pyproject.toml").read_text())["project"]


def _pins(path: Path) -> dict[str, str]:
    """``{name: version}`` of the ``name==version`` lines of a requirements file (first one wins)."""
    pins: dict[str, str] = {}
    for line in path.read_text().splitlines():
        m = re.match(r"^([A-Za-z0-9_.-]+)==([^\s;]+)", line)
        if m:
            pins.setdefault(m.group(1).lower(), m.group(2))
    return pins


def test_oldest_pins_are_the_declared_lower_bounds():
    """requirements/oldest.txt (make test-oldest) installs exactly the floors pyproject.toml declares."""
    floors = {}
    for dep in _project()["dependencies"]:
        m = re.fullmatch(r"([A-Za-z0-9_.-]+)>=([0-9][^,;\s]*)", dep.replace(" ", ""))
        assert m, f"dependency {dep!r}: declare a plain lower bound 'name>=X'"
        floors[m.group(1).lower()] = m.group(2)
    assert _pins(REPO / "requirements" / "oldest.txt") == floors


@pytest.mark.parametrize("lock", ["lock.txt", "students.txt"])
def test_lock_pins_every_dependency_within_its_bounds(lock):
    from packaging.requirements import Requirement

    pins = _pins(REPO / "requirements" / lock)
    for dep in _project()["dependencies"]:
        req = Requirement(dep)
        assert req.name.lower() in pins, (
            f"requirements/{lock} does not pin {req.name}: run `make lock`"
        )
        assert req.specifier.contains(pins[req.name.lower()]), (
            f"{req.name}=={pins[req.name.lower()]} outside {dep}"
        )


def _pinned_versions(path: Path) -> set[tuple[str, str]]:
    """``(name, version)`` of every pin of a universal lock: a package may have one per Python version
    (its environment marker, which may be wider in the full lock, is left out)."""
    return set(re.findall(r"^([A-Za-z0-9_.-]+)==([^\s;]+)", path.read_text().lower(), flags=re.M))


def test_students_lock_is_the_full_locks_pins_for_the_course_alone():
    """requirements/students.txt (Binder, hub/Dockerfile) shares every version with lock.txt (CI,
    developers) and carries none of the extras' tools: `make lock` writes both."""
    students = _pinned_versions(REPO / "requirements" / "students.txt")
    full = _pinned_versions(REPO / "requirements" / "lock.txt")
    assert students, "requirements/students.txt pins nothing"
    differ = sorted(students - full)
    assert not differ, (
        f"students.txt pins {differ} where lock.txt has another version: run `make lock`"
    )
    from packaging.requirements import Requirement

    names = {name for name, _ in students}
    tools = {
        Requirement(dep).name.lower()
        for deps in _project()["optional-dependencies"].values()
        for dep in deps
    }
    assert not names & tools, (
        f"students.txt installs the extras' tools {sorted(names & tools)} for every student"
    )
