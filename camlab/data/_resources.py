"""Where camlab's data sets and lessons live, in a clone and in an installed wheel.

The repository keeps one copy of each asset: the top-level ``data/``, ``lessons/`` and
``docs/`` folders. The build maps them into the wheel as package resources (``setup.py``:
``camlab/data/files/``, ``camlab/lessons/``, ``camlab/docs/``), found here with
:mod:`importlib.resources`.
In a clone (editable install or plain ``PYTHONPATH``) those package folders do not exist
and the top-level folders are used instead.

``$CAMLAB_DATA`` names a folder of regenerated data sets: a set found there
(``$CAMLAB_DATA/stereo/`` ...) is loaded instead of the bundled one, and ``python -m
camlab.data`` writes there. Without it, regeneration writes into a clone's ``data/`` or, for
an installed package, into the user cache (:func:`cache_dir`), never into site-packages.
"""

from __future__ import annotations

import json
import os
import sys
from importlib.resources import files
from pathlib import Path

import numpy as np

from .._validate import CamlabInputError

__all__ = [
    "cache_dir",
    "data_dir",
    "dataset_dir",
    "docs_dir",
    "lessons_dir",
    "read_only",
    "read_truth",
    "regeneration_dir",
]

_REPO = Path(__file__).resolve().parents[2]


def _resource_dir(package: str, inside: str, repo_folder: str) -> Path:
    """``package``'s resource folder ``inside`` (a wheel), else the clone's ``repo_folder``."""
    packaged = files(package) / inside
    if isinstance(packaged, Path) and packaged.is_dir():
        return packaged
    clone = _REPO / repo_folder
    if clone.is_dir() and (_REPO / "pyproject.toml").is_file():
        return clone
    raise CamlabInputError(
        f"camlab: the bundled {repo_folder}/ folder is missing (looked in {packaged} and {clone}); "
        "reinstall the package (pip install --force-reinstall camlab-course) or work in a full clone"
    )


def data_dir() -> Path:
    """The data shipped with camlab: ``camlab/data/files`` in a wheel, ``data/`` in a clone."""
    return _resource_dir("camlab.data", "files", "data")


def lessons_dir() -> Path:
    """The lesson notebooks shipped with camlab: ``camlab/lessons`` in a wheel, ``lessons/`` in a clone."""
    return _resource_dir("camlab", "lessons", "lessons")


def docs_dir() -> Path:
    """The documentation the lessons link to (``conventions.md``): ``camlab/docs`` in a wheel, ``docs/`` in a clone."""
    return _resource_dir("camlab", "docs", "docs")


def dataset_dir(name: str) -> Path:
    """The folder of data set ``name`` (``calib_chessboard``, ``stereo``, ``panorama``, ``photos``).

    ``$CAMLAB_DATA/<name>`` when it exists (a regenerated set), else the bundled one.
    """
    override = os.environ.get("CAMLAB_DATA")
    if override and (Path(override).expanduser() / name).is_dir():
        return Path(override).expanduser() / name
    return data_dir() / name


def read_truth(directory: Path | str | None, name: str) -> tuple[Path, dict]:
    """The folder of set ``name`` (``directory`` if given, else :func:`dataset_dir`) and its parsed ``truth.json``."""
    d = Path(directory) if directory is not None else dataset_dir(name)
    path = d / "truth.json"
    if not path.exists():
        raise CamlabInputError(
            f"directory: no truth.json in {d}; run `python -m camlab.data` to generate it"
        )
    return d, json.loads(path.read_text())


def cache_dir() -> Path:
    """The user cache for regenerated data: ``$CAMLAB_DATA``, else the platform's cache folder + ``camlab``."""
    override = os.environ.get("CAMLAB_DATA")
    if override:
        return Path(override).expanduser()
    if sys.platform == "win32":
        base = Path(os.environ.get("LOCALAPPDATA", Path.home() / "AppData" / "Local"))
    elif sys.platform == "darwin":
        base = Path.home() / "Library" / "Caches"
    else:
        base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    return base / "camlab" / "data"


def regeneration_dir() -> Path:
    """Where ``python -m camlab.data`` writes by default: ``$CAMLAB_DATA``, a clone's ``data/``, else the cache.

    An installed package is never written to: its data folder sits inside site-packages.
    """
    if os.environ.get("CAMLAB_DATA"):
        return cache_dir()
    bundled = data_dir()
    return bundled if bundled == _REPO / "data" else cache_dir()


def encode_image(image, ext: str, params: tuple[int, ...] = ()) -> bytes:
    """The bytes of ``image`` encoded by ``cv2.imencode`` as ``ext`` (".png", ".jpg"), or raise.

    ``cv2.imencode`` reports failure with a flag, not an exception; ignoring the flag would
    write an empty or stale file into a data set.
    """
    import cv2

    ok, buf = cv2.imencode(ext, image, list(params))
    if not ok or buf is None:
        raise OSError(
            f"cv2.imencode could not encode a {getattr(image, 'shape', '?')} "
            f"{getattr(image, 'dtype', '?')} image as {ext}"
        )
    return buf.tobytes()


def read_only(obj):
    """Freeze every ndarray in ``obj`` and return ``obj``.

    Arrays, and the NamedTuples, lists, tuples, dicts and objects (their attributes) that hold them,
    all the way down.

    A cache hands the same object to every caller, so one caller's in-place edit would
    otherwise change what the next one gets; copy an array (``a.copy()``) to change it.
    """
    if isinstance(obj, np.ndarray):
        obj.setflags(write=False)
    elif isinstance(obj, dict):
        for value in obj.values():
            read_only(value)
    elif isinstance(obj, (list, tuple)):
        for value in obj:
            read_only(value)
    elif hasattr(obj, "__dict__") and not isinstance(obj, type):
        for value in vars(obj).values():
            read_only(value)
    return obj
