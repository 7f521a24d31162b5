"""Files read and written safely: photos checked as they are read, outputs checked and replaced atomically.

A program that computes for a minute and then fails to write its result, or leaves half a
file behind, wastes the user's time; one that reads half a photo as grey gives a wrong
answer without a word. :func:`read_photo` is the one reader of the user's photos (every
command uses it): it refuses a truncated JPEG or PNG naming the file, and turns the photo
upright by its EXIF orientation tag, so every command sees the same pixels.
:func:`check_output_path` says up front (naming the argument) whether a path can be
written, :func:`check_not_an_input` that it would not overwrite an input; :func:`atomic_output`
gives a temporary name in the same folder, checks what was written (flushed to disk,
not empty, not truncated, and optionally read back) and moves it over the target only
then, with the permissions the user's umask asks for, so the target is either the old
file or the complete new one, never a torn or empty one.
"""

from __future__ import annotations

import contextlib
import datetime
import itertools
import os
import shutil
import tempfile
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path

import numpy as np

from ._validate import CamlabInputError

__all__ = [
    "PhotoReadError",
    "atomic_output",
    "backup_name",
    "check_not_an_input",
    "check_output_path",
    "damaged_image_file",
    "keep_a_copy",
    "output_folder",
    "read_photo",
]

PHOTO_MODES = ("rgb", "grey", "stored")


class PhotoReadError(CamlabInputError):
    """A photo file that cannot be used; ``path`` and ``reason`` (plain words) are attributes."""

    def __init__(self, path, reason: str):
        super().__init__(f"{str(path)!r}: {reason}")
        self.path, self.reason = str(path), reason


def damaged_image_file(data: bytes) -> str | None:
    """Why these bytes are a damaged image file (empty, a JPEG or PNG cut short), or None.

    A JPEG ends with the end-of-image marker FF D9 (some cameras pad with zeros after it),
    a PNG with its IEND chunk; OpenCV decodes a file cut short as a grey lower part without
    an error, so this must be checked first.
    """
    if not data:
        return "could not read the file: it is empty (0 bytes)"
    if data[:2] == b"\xff\xd8" and data.rstrip(b"\x00")[-2:] != b"\xff\xd9":
        return "truncated JPEG: the file ends before its end-of-image marker (copy it again from the camera)"
    if data[:8] == b"\x89PNG\r\n\x1a\n" and b"IEND" not in data[-16:]:
        return "truncated PNG: the file ends before its IEND chunk (copy it again)"
    return None


def read_photo(path: str | os.PathLike, mode: str = "rgb") -> np.ndarray:
    """Read a photo file upright (EXIF orientation applied), refusing damaged files.

    Parameters
    ----------
    path : str or PathLike
    mode : {"rgb", "grey", "stored"}
        ``"rgb"``: (H, W, 3) uint8 RGB; ``"grey"``: (H, W) uint8; ``"stored"``: the file's
        bit depth and channel count (an alpha channel is dropped) in OpenCV's BGR order,
        for writing back with ``cv2.imwrite``.

    Returns
    -------
    ndarray
        Indexed ``img[v, u]``; the orientation tag is applied (OpenCV's ``imdecode`` does
        this for every flag but ``IMREAD_UNCHANGED``), so a photo a phone took upright and
        stored sideways comes out upright, the same in every command.

    Raises
    ------
    PhotoReadError
        Missing, empty, truncated, or not an image format OpenCV knows; the message names
        the file.
    """
    import cv2

    flags = {
        "rgb": cv2.IMREAD_COLOR,
        "grey": cv2.IMREAD_GRAYSCALE,
        "stored": cv2.IMREAD_ANYDEPTH | cv2.IMREAD_ANYCOLOR,
    }
    if mode not in flags:
        raise CamlabInputError(f"mode: expected one of {PHOTO_MODES}, got {mode!r}")
    p = Path(path)
    if not p.is_file():
        raise PhotoReadError(
            p,
            "could not read the file: " + ("it is a folder" if p.is_dir() else "it does not exist"),
        )
    try:
        data = p.read_bytes()
    except OSError as exc:
        raise PhotoReadError(p, f"could not read the file: {exc.strerror}") from None
    why = damaged_image_file(data)
    image = None if why else cv2.imdecode(np.frombuffer(data, np.uint8), flags[mode])
    if image is None:
        raise PhotoReadError(p, why or "could not read the file: not an image format OpenCV knows")
    return cv2.cvtColor(image, cv2.COLOR_BGR2RGB) if mode == "rgb" else image


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
        raise CamlabInputError(
            f"{name}: expected a file name ending in {', '.join(suffixes)}, got {str(path)!r}"
        )
    if p.is_dir():
        raise CamlabInputError(f"{name}: {str(path)!r} is a folder; give a file name inside it")
    folder = p.parent if str(p.parent) else Path(".")
    if not folder.is_dir():
        raise CamlabInputError(
            f"{name}: the folder {str(folder)!r} does not exist; create it first"
        )
    try:
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".camlab-probe-")
    except OSError as exc:
        raise CamlabInputError(
            f"{name}: cannot write in {str(folder)!r} ({exc.strerror}); choose another folder"
        ) from None
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
        raise CamlabInputError(
            f"{name}: {str(path)!r} is a file, not a folder; name a folder (a missing one is "
            f"created)"
        )
    try:
        p.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise CamlabInputError(
            f"{name}: cannot create the folder {str(path)!r} ({exc.strerror}); choose another "
            f"folder"
        ) from None
    return p


def _same_file(a: Path, b: Path) -> bool:
    """Whether two paths name one file: the same resolved path, or (hard links) the same inode."""
    if a.resolve() == b.resolve():
        return True
    try:
        return a.samefile(b)
    except OSError:  # one of them does not exist (yet)
        return False


def check_not_an_input(
    outputs: Iterable[str | os.PathLike], name: str, inputs: Iterable[str | os.PathLike], fix: str
) -> None:
    """Raise, naming ``name``, if writing any of ``outputs`` would overwrite one of ``inputs``.

    Paths are compared resolved (``.``, ``..`` and symbolic links followed) and by inode, so
    ``./a.jpg``, ``photos/../a.jpg`` and a hard link all count as the same file. ``fix``
    finishes the message (what to do instead).
    """
    ins = [Path(x) for x in inputs]
    for out in outputs:
        hit = next((x for x in ins if _same_file(Path(out), x)), None)
        if hit is not None:
            raise CamlabInputError(
                f"{name}: writing {str(out)!r} would overwrite the input photo {str(hit)!r}; {fix}"
            )


def backup_name(target: Path, kind: str) -> Path:
    """``<stem>.<kind>-<YYYY-MM-DD>[-n]<suffix>`` beside ``target``, the first that does not exist yet."""
    stamp = datetime.date.today().isoformat()
    for n in itertools.count(1):
        candidate = target.with_name(
            f"{target.stem}.{kind}-{stamp}{'' if n == 1 else f'-{n}'}{target.suffix}"
        )
        if not candidate.exists():
            return candidate
    raise AssertionError("unreachable")


def keep_a_copy(path: str | os.PathLike, name: str = "path") -> Path | None:
    """Copy an existing file to ``<stem>.previous-<date><suffix>`` beside it before it is replaced.

    Parameters
    ----------
    path : str or PathLike
        The file about to be overwritten.
    name : str
        The argument named in the error message.

    Returns
    -------
    Path or None
        The copy, or None when ``path`` does not exist yet (nothing to keep).

    Raises
    ------
    CamlabInputError
        When the copy cannot be written (then nothing should be overwritten).
    """
    p = Path(path)
    if not p.is_file():
        return None
    copy = backup_name(p, "previous")
    try:
        shutil.copy2(p, copy)
    except OSError as exc:
        raise CamlabInputError(
            f"{name}: could not keep a copy of {str(p)!r} before replacing it ({exc.strerror}); "
            f"choose another file name"
        ) from None
    return copy


def _umask_mode() -> int:
    """The permission bits a new file gets under the current umask (0o666 & ~umask)."""
    mask = os.umask(0o022)  # reading the umask means setting it; put it straight back
    os.umask(mask)
    return 0o666 & ~mask


def _flush_to_disk(path: Path) -> None:
    """fsync a written file: a full disk may only show here (delayed allocation)."""
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _written_problem(tmp: Path, verify: Callable[[Path], str | None] | None) -> str | None:
    """Why the file just written is not a good one (empty, truncated, does not read back), or None."""
    _flush_to_disk(tmp)
    with open(tmp, "rb") as f:
        head = f.read(8)
        size = f.seek(0, os.SEEK_END)
        f.seek(max(0, size - 16))
        tail = f.read()
    if size == 0:
        return "nothing was written (0 bytes)"
    why = damaged_image_file(head + tail if size > 24 else head[:size])
    if why:
        return why.split(":")[0] + " was written"
    return verify(tmp) if verify is not None else None


@contextlib.contextmanager
def atomic_output(
    path: str | os.PathLike, name: str = "path", verify: Callable[[Path], str | None] | None = None
) -> Iterator[Path]:
    """Yield a temporary path beside ``path`` (same suffix); move it over ``path`` once it is checked.

    After the body has written the temporary file it is flushed to disk (``fsync``) and
    checked: not empty, a JPEG or PNG not cut short, and ``verify(tmp)`` (a reason, or None
    when the file reads back) if given. It then gets the mode a new file gets under the
    umask (``mkstemp`` creates files 0600), or the old file's mode when it replaces one, and
    is renamed over ``path``. On any failure the temporary file is removed, ``path`` is
    left as it was, and an ``OSError`` (a full disk, say) becomes a :class:`CamlabInputError`
    naming ``name``.
    """
    p = Path(path)
    fd, tmp_name = tempfile.mkstemp(
        dir=p.parent if str(p.parent) else ".", prefix=f".{p.stem}-", suffix=p.suffix
    )
    os.close(fd)
    tmp = Path(tmp_name)
    kept = "the previous file is unchanged" if p.exists() else "no file was left behind"
    try:
        try:
            yield tmp
            why = _written_problem(tmp, verify)
        except OSError as exc:
            why = exc.strerror or str(exc)
        if why:
            raise CamlabInputError(
                f"{name}: could not write {str(p)!r}: {why}; {kept}. Free some disk space or "
                f"choose another folder"
            ) from None
        os.chmod(tmp, p.stat().st_mode & 0o7777 if p.exists() else _umask_mode())
        os.replace(tmp, p)
    finally:
        if tmp.exists():
            tmp.unlink()
