"""Output files written safely: checked before any work starts, and replaced atomically.

A program that computes for a minute and then fails to write its result, or leaves half a
file behind, wastes the user's time. :func:`check_output_path` says up front (naming the
argument) whether a path can be written; :func:`atomic_output` gives a temporary name in
the same folder and moves it over the target only when writing succeeded, so the target
is either the old file or the complete new one, never a torn one.
"""
from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path
from typing import Iterator

from ._validate import CamlabInputError

__all__ = ["atomic_output", "check_output_path", "output_folder"]


def check_output_path(path, name: str, suffixes: tuple[str, ...] | None = None) -> Path:
    """Return ``path`` as a Path if a file can be written there, else raise naming ``name``.

    Checks the type, the suffix (when ``suffixes`` is given), that the path is not a
    folder, that its folder exists, and that a file can be created in it (by creating and
    removing a temporary one: permission bits alone do not tell, e.g. on a read-only mount).
    """
    if path is None or not isinstance(path, (str, os.PathLike)) or str(path) == "":
        raise CamlabInputError(f"{name}: expected a file path, got {path!r}")
    p = Path(path)
    if suffixes is not None and p.suffix.lower() not in suffixes:
        raise CamlabInputError(f"{name}: expected a file name ending in {', '.join(suffixes)}, got {str(path)!r}")
    if p.is_dir():
        raise CamlabInputError(f"{name}: {str(path)!r} is a folder; give a file name inside it")
    folder = p.parent if str(p.parent) else Path(".")
    if not folder.is_dir():
        raise CamlabInputError(f"{name}: the folder {str(folder)!r} does not exist; create it first")
    try:
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".camlab-probe-")
    except OSError as exc:
        raise CamlabInputError(f"{name}: cannot write in {str(folder)!r} ({exc.strerror}); choose another "
                               f"folder") from None
    os.close(fd)
    os.unlink(probe)
    return p


def output_folder(path, name: str) -> Path:
    """Return ``path`` as a Path to a folder for outputs, creating it (and its parents) if missing.

    Raises :class:`CamlabInputError` naming ``name`` if ``path`` is a file or cannot be created.
    """
    if path is None or not isinstance(path, (str, os.PathLike)) or str(path) == "":
        raise CamlabInputError(f"{name}: expected a folder path, got {path!r}")
    p = Path(path)
    if p.exists() and not p.is_dir():
        raise CamlabInputError(f"{name}: {str(path)!r} is a file, not a folder; name a folder (a missing one is "
                               f"created)")
    try:
        p.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise CamlabInputError(f"{name}: cannot create the folder {str(path)!r} ({exc.strerror}); choose another "
                               f"folder") from None
    return p


@contextlib.contextmanager
def atomic_output(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path beside ``path`` (same suffix); on success move it over ``path``.

    On an exception the temporary file is removed and ``path`` is left untouched.
    """
    p = Path(path)
    fd, tmp = tempfile.mkstemp(dir=p.parent if str(p.parent) else ".", prefix=f".{p.stem}-", suffix=p.suffix)
    os.close(fd)
    try:
        yield Path(tmp)
        os.replace(tmp, p)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
