r"""Bring your own photos: one upload control for every lesson that runs on photographs.

In a lesson (the control in its own cell, displayed on the cell's last line)::

    from camlab.widgets.upload import PhotoUpload
    up = PhotoUpload("Your board photos", multiple=True)
    up

and in a later cell ``photos = up.photos_or(shipped)``: the student's photos once they have
uploaded some, else the lesson's own, so the lesson runs the same with none.

Each uploaded file is checked and decoded in the kernel, in memory:

- a file that is empty, a JPEG or PNG cut short (OpenCV would decode its missing part as
  grey without a word: :func:`camlab._files.damaged_image_file`), or not an image format
  OpenCV knows is refused, and :attr:`PhotoUpload.problems` says which file and why;
- ``cv2.imdecode`` with ``IMREAD_COLOR`` turns the photo upright by its EXIF orientation
  tag (OpenCV does for JPEG and PNG with every flag but ``IMREAD_UNCHANGED``), as
  :func:`camlab._files.read_photo` does for the command line, and gives 3-channel 8-bit BGR
  whatever the file held (grey, 16-bit, an alpha channel);
- a photo above ``max_pixels`` is shrunk (``cv2.INTER_AREA``, which averages the pixels it
  merges) and the status line says from what size to what.

Nothing is written to disk unless ``save_to`` names a folder; then each decoded photo is
written inside that folder only (a name with a folder part, ``..`` or an absolute path is refused), and a file already
there is kept as ``<name>.previous-<date>`` first.

The uploads live in the kernel. A page without one (the course website, a saved HTML copy)
shows a picture of one sentence instead, :data:`camlab._notebook.UPLOAD_NEEDS_KERNEL`, and
lecture mode (``camlab present``) shows that sentence as text.
"""

from __future__ import annotations

import html
import math
import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, NamedTuple

import ipywidgets as W
import numpy as np

from .._files import atomic_output, damaged_image_file, keep_a_copy, output_folder
from .._notebook import UPLOAD_NEEDS_KERNEL
from .._validate import CamlabInputError
from ..plotting.static import figure_png, static_bundle

__all__ = ["DecodedPhoto", "PhotoUpload", "decode_photo"]

Photo = tuple[str, np.ndarray]
WRITABLE = (".jpg", ".jpeg", ".png", ".bmp", ".tif", ".tiff", ".webp")


def _size_text(n_bytes: int) -> str:
    """A file size as people read it: 812 bytes, 45.3 kB, 3.1 MB."""
    if n_bytes < 1000:
        return f"{n_bytes} bytes"
    return f"{n_bytes / 1e3:.1f} kB" if n_bytes < 1e6 else f"{n_bytes / 1e6:.1f} MB"


class DecodedPhoto(NamedTuple):
    """A photo decoded by :func:`decode_photo`.

    Attributes
    ----------
    image : ndarray
        (H, W, 3) uint8 in OpenCV's BGR order, indexed ``image[v, u]``, upright.
    note : str
        What was received: name, file size, pixel size and any downscaling.
    """

    image: np.ndarray
    note: str


def decode_photo(data: bytes, name: str, max_pixels: int | None = None) -> DecodedPhoto:
    """Decode an image file's bytes upright and within a pixel budget.

    Parameters
    ----------
    data : bytes
        The file's content.
    name : str
        The file's name, for the messages.
    max_pixels : int or None
        Largest width x height kept; a larger photo is shrunk with ``cv2.INTER_AREA`` to fit,
        keeping its aspect ratio. None keeps every photo at its size.

    Returns
    -------
    DecodedPhoto
        ``image``: (H, W, 3) uint8 in OpenCV's BGR order, indexed ``image[v, u]``, turned
        upright by the EXIF orientation tag; ``note``: what was received, e.g.
        ``"IMG_1.jpg (2.4 MB): 4000 x 3000 px, downscaled to 1632 x 1224 px (budget
        2,000,000 pixels)"``.

    Raises
    ------
    CamlabInputError
        The file is empty, truncated or not an image; the message names it and says what to do.
    """
    import cv2

    if not isinstance(data, (bytes, bytearray, memoryview)):
        raise CamlabInputError(
            f"data: expected the file's content as bytes (e.g. open(path, 'rb').read()), "
            f"got {type(data).__name__}"
        )
    if max_pixels is not None and (
        isinstance(max_pixels, bool)
        or not isinstance(max_pixels, (int, np.integer))
        or max_pixels < 1
    ):
        raise CamlabInputError(
            f"max_pixels: expected a positive whole number of pixels or None, got {max_pixels!r}"
        )
    data = bytes(data)
    why = damaged_image_file(data)
    image = None if why else cv2.imdecode(np.frombuffer(data, np.uint8), cv2.IMREAD_COLOR)
    if image is None:
        why = why or (
            "not an image OpenCV can read (is it a photo? JPEG and PNG work; HEIC photos "
            "need converting to JPEG first)"
        )
        raise CamlabInputError(f"{name!r}: {why}")
    h, w = image.shape[:2]
    note = f"{name} ({_size_text(len(data))}): {w} x {h} px"
    if max_pixels is not None and w * h > max_pixels:
        scale = math.sqrt(max_pixels / (w * h))
        new_w, new_h = max(1, math.floor(w * scale)), max(1, math.floor(h * scale))
        image = cv2.resize(image, (new_w, new_h), interpolation=cv2.INTER_AREA)
        note += f", downscaled to {new_w} x {new_h} px (budget {max_pixels:,} pixels)"
    return DecodedPhoto(image, note)


def _inside(folder: Path, name: str) -> Path | None:
    """``folder / name`` for a plain file name (no folder, no ``..``, not absolute), else None."""
    if not name or os.path.isabs(name) or Path(name).drive or "/" in name or "\\" in name:
        return None
    target = (folder / name).resolve()
    root = folder.resolve()
    return target if target != root and root in target.parents else None


def _static_png() -> bytes:
    """A small picture of :data:`UPLOAD_NEEDS_KERNEL`, for pages without a kernel."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.4, 0.5), dpi=100)
    FigureCanvasAgg(fig)
    fig.text(0.01, 0.5, UPLOAD_NEEDS_KERNEL, va="center", ha="left", fontsize=11)
    return figure_png(fig)


class PhotoUpload:
    """An upload button for photos and a status line; the photos decoded in the kernel.

    Parameters
    ----------
    description : str
        The button's label, e.g. ``"Your board photos"``.
    multiple : bool
        Whether several files can be chosen at once (each new choice replaces the last).
    max_pixels : int
        Largest width x height kept; larger photos are shrunk to fit (default 2,000,000:
        a 12 MP phone photo becomes 1632 x 1224 px).
    save_to : str, PathLike or None
        A folder to write the decoded photos into (created when the first one arrives);
        None (the default) writes nothing.

    Attributes
    ----------
    photos : list of (str, ndarray)
        The accepted photos of the last upload, in the order chosen: file name and
        (H, W, 3) uint8 BGR image.
    problems : list of str
        One sentence per refused file, naming it and saying why.
    notes : list of str
        One line per accepted photo: its name, file size, pixel size and any downscaling.
    upload : ipywidgets.FileUpload
        The button (``accept="image/*"``); setting its ``value`` is what a browser upload does.
    status : ipywidgets.HTML
        The status line under the button.
    """

    def __init__(
        self,
        description: str = "Your photos",
        *,
        multiple: bool = True,
        max_pixels: int = 2_000_000,
        save_to: str | os.PathLike | None = None,
    ):
        if not isinstance(description, str):
            raise CamlabInputError(
                f"description: expected the button's label as a string, got {description!r}"
            )
        if isinstance(max_pixels, bool) or not isinstance(max_pixels, (int, np.integer)):
            raise CamlabInputError(
                f"max_pixels: expected a whole number of pixels such as 2_000_000, got {max_pixels!r}"
            )
        if max_pixels < 10_000:
            raise CamlabInputError(
                f"max_pixels: expected at least 10,000 pixels (100 x 100), got {max_pixels}; "
                f"2_000_000 keeps a phone photo sharp enough for every lesson"
            )
        if save_to is not None and not isinstance(save_to, (str, os.PathLike)):
            raise CamlabInputError(f"save_to: expected a folder path or None, got {save_to!r}")
        self.max_pixels = int(max_pixels)
        self.save_to = None if save_to is None else Path(save_to)
        self.photos: list[Photo] = []
        self.problems: list[str] = []
        self.notes: list[str] = []
        self._callbacks: list[Callable[[PhotoUpload], Any]] = []
        self.upload = W.FileUpload(
            accept="image/*", multiple=bool(multiple), description=description
        )
        self.status = W.HTML(self._status_html())
        self.widget = W.VBox([self.upload, self.status])
        self.widget.add_class("camlab-photo-upload")
        self.upload.observe(self._on_value, names="value")

    def photos_or(self, default: Sequence[Photo]) -> list[Photo]:
        """The uploaded photos if any were accepted, else ``default`` (the lesson's own).

        Parameters
        ----------
        default : sequence of (str, ndarray)
            What the lesson uses when nothing was uploaded.

        Returns
        -------
        list of (str, ndarray)
            ``photos`` or ``list(default)``.
        """
        return list(self.photos) if self.photos else list(default)

    def observe(self, callback: Callable[[PhotoUpload], Any]) -> None:
        """Call ``callback(self)`` after each upload has been decoded (photos, problems, status set).

        Parameters
        ----------
        callback : callable
            Takes the control; its return value is ignored.
        """
        if not callable(callback):
            raise CamlabInputError(
                f"callback: expected a function taking the control, got {callback!r}"
            )
        self._callbacks.append(callback)

    def _on_value(self, change: dict) -> None:
        """Decode the files of a new upload; set photos, problems, notes and the status line."""
        photos, problems, notes = [], [], []
        for entry in change["new"]:
            name = str(entry.get("name", "") or "(no name)")
            content = entry.get("content", b"")
            data = content.tobytes() if isinstance(content, memoryview) else bytes(content)
            try:
                image, note = decode_photo(data, name, self.max_pixels)
                if self.save_to is not None:
                    note += self._save(name, image)
            except OSError as exc:  # the folder vanished or became read-only after the check
                problems.append(f"{name!r}: not saved in {str(self.save_to)!r}: {exc.strerror}")
                continue
            except CamlabInputError as exc:
                problems.append(str(exc))
                continue
            photos.append((name, image))
            notes.append(note)
        self.photos, self.problems, self.notes = photos, problems, notes
        self.status.value = self._status_html()
        for callback in self._callbacks:
            callback(self)

    def _save(self, name: str, image: np.ndarray) -> str:
        """Write one decoded photo inside :attr:`save_to`; returns what the status line adds."""
        import cv2

        folder = output_folder(self.save_to, "save_to")
        target = _inside(folder, name)
        if target is None:
            raise CamlabInputError(
                f"{name!r}: not saved: only a plain file name is written inside the folder "
                f"{str(self.save_to)!r} (no folders, no '..', not absolute); rename the file, "
                f"e.g. photo_1.jpg"
            )
        if target.suffix.lower() not in WRITABLE:
            target = target.with_name(target.name + ".png")
        copy = keep_a_copy(target, "save_to")
        with atomic_output(target, "save_to") as tmp:
            ok, buf = cv2.imencode(tmp.suffix, image)
            if not ok:
                raise CamlabInputError(f"{name!r}: OpenCV could not encode it as {tmp.suffix}")
            tmp.write_bytes(buf.tobytes())
        kept = f" (the old file is kept as {copy.name})" if copy is not None else ""
        return f", saved as {target.relative_to(folder.resolve())}{kept}"

    def _status_html(self) -> str:
        """The status line: what was received, what was refused and why."""
        if not self.photos and not self.problems:
            lines = ["No photos uploaded: the lesson uses its own photos."]
        else:
            n = len(self.photos)
            lines = [f"Received {n} photo{'s' if n != 1 else ''}" + (":" if n else ".")]
            lines += [f"&nbsp;&nbsp;{html.escape(note)}" for note in self.notes]
            lines += [f"&nbsp;&nbsp;Refused {html.escape(p)}" for p in self.problems]
        return '<div class="camlab-upload-status">' + "<br>".join(lines) + "</div>"

    def _repr_mimebundle_(self, **kwargs: Any):
        """The live control, plus a picture of one sentence for pages without a kernel."""
        bundle = self.widget._repr_mimebundle_(**kwargs)
        return static_bundle(bundle, None, UPLOAD_NEEDS_KERNEL, _static_png())
