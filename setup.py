"""Build glue: the repository's top-level ``data/``, ``lessons/`` and ``docs/`` travel inside the wheel.

They are the one copy of each asset; this maps them to the package resources
``camlab/data/files/``, ``camlab/lessons/`` and ``camlab/docs/`` that :mod:`camlab.data._resources` finds with
importlib.resources. Each of their folders is listed as a (resource-only) package so
setuptools copies its files. Everything else about the package is in pyproject.toml.
"""

from pathlib import Path

from setuptools import find_packages, setup

# resource package -> (repository folder, file patterns, include subfolders)
RESOURCES = {
    "camlab.data.files": ("data", ["*"], True),
    "camlab.lessons": ("lessons", ["*.ipynb", "*.md"], False),
    "camlab.docs": ("docs", ["*.md"], False),
}


def resource_packages() -> dict[str, list[str]]:
    """``{package: patterns}`` for each resource root and (where asked) its folders, hidden ones skipped."""
    found = {}
    for package, (root, patterns, deep) in RESOURCES.items():
        folders = [Path(root), *sorted(p for p in Path(root).rglob("*") if p.is_dir() and deep)]
        for folder in folders:
            parts = folder.relative_to(root).parts
            if not any(part.startswith((".", "_")) for part in parts):
                found[".".join((package, *parts))] = patterns
    return found


RESOURCE_DATA = resource_packages()

setup(
    packages=find_packages(include=["camlab", "camlab.*"]) + list(RESOURCE_DATA),
    package_dir={package: root for package, (root, _, _) in RESOURCES.items()},
    package_data={
        "camlab": ["py.typed"],
        "camlab.classroom": ["jupyter_data/voila/templates/camlab/*"],  # present.py
        "camlab.widgets.browser": ["*.js"],  # the browser-drawn demos' ES modules (no build step)
        **RESOURCE_DATA,
    },
)
