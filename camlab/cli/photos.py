r"""Reading and writing the commands' photos.

One reader (upright by EXIF, truncated files refused by name), shrinking above ``--max-megapixels``,
outputs written atomically.
"""

from __future__ import annotations

from .._validate import CamlabInputError

__all__ = []


def expand(patterns: list[str]) -> list[str]:
    """The files a command line names: glob patterns expanded (sorted), other names kept as given.

    Parameters
    ----------
    patterns : list of str
        File names and quoted glob patterns (``*``, ``?``, ``[``).

    Returns
    -------
    list of str
        The paths, in the order given, each pattern's matches sorted.

    Raises
    ------
    CamlabInputError
        If a pattern matches no file.
    """
    import glob

    files: list[str] = []
    for pat in patterns:
        if any(ch in pat for ch in "*?["):
            matched = sorted(glob.glob(pat))
            if not matched:
                raise CamlabInputError(f"images: no files match {pat!r}")
            files += matched
        else:
            files.append(pat)
    return files


def read_or_skip(path: str, mode: str, prefix: str = ""):
    """The photo (upright, see :func:`camlab._files.read_photo`), or None after a line saying why it is skipped.

    Parameters
    ----------
    path : str
        The photo's file.
    mode : str
        ``"rgb"``, ``"grey"`` or ``"stored"`` (:func:`camlab._files.read_photo`).
    prefix : str
        Text printed before the path on the skip line (an indent, a pair's side).

    Returns
    -------
    ndarray or None
        The image, or None when the file is missing, damaged or not an image.
    """
    from .._files import PhotoReadError, read_photo

    try:
        return read_photo(path, mode)
    except PhotoReadError as exc:
        print(f"  {prefix}{path}: skipped: {exc.reason}", flush=True)
        return None


def within_work_size(image, max_megapixels: float, name: str):
    """``image`` shrunk (area averaging) to at most ``max_megapixels``, saying so; else ``image`` itself.

    Phone photos of 40 megapixels would take minutes and gigabytes to register and blend;
    the geometry needs far fewer pixels.

    Parameters
    ----------
    image : (H, W) or (H, W, 3) ndarray
        The photo.
    max_megapixels : float
        The largest size worked on, megapixels.
    name : str
        The photo's name in the printed line.

    Returns
    -------
    ndarray
        ``image`` itself if small enough, else a copy resized with ``cv2.INTER_AREA`` (at least
        16 px a side).
    """
    import cv2

    h, w = image.shape[:2]
    s = (max_megapixels * 1e6 / (h * w)) ** 0.5
    if s >= 1:
        return image
    size = (max(16, round(w * s)), max(16, round(h * s)))
    print(
        f"  {name}: {w} x {h} px ({w * h / 1e6:.0f} MP), worked on at {size[0]} x {size[1]} "
        f"(--max-megapixels {max_megapixels:g})",
        flush=True,
    )
    return cv2.resize(image, size, interpolation=cv2.INTER_AREA)


IMAGE_SUFFIXES = (".jpg", ".jpeg", ".png", ".tif", ".tiff", ".bmp")


def photo_paths(args_images: list[str]) -> list[str]:
    """Image files from folders (their images, sorted), files and quoted glob patterns.

    Parameters
    ----------
    args_images : list of str
        The command's image arguments: folders, files or glob patterns.

    Returns
    -------
    list of str
        The image paths; a folder contributes its :data:`IMAGE_SUFFIXES` files, sorted.

    Raises
    ------
    CamlabInputError
        If a folder holds no image or a pattern matches no file.
    """
    from pathlib import Path

    files: list[str] = []
    for item in args_images:
        if Path(item).is_dir():
            found = sorted(
                str(p) for p in Path(item).iterdir() if p.suffix.lower() in IMAGE_SUFFIXES
            )
            if not found:
                raise CamlabInputError(
                    f"images: the folder {item!r} holds no {'/'.join(IMAGE_SUFFIXES)} files"
                )
            files += found
        else:
            files += expand([item])
    return files


def write_image(path, image_rgb_or_gray, name: str) -> None:
    """Write an RGB or grey image to ``path`` atomically (:func:`camlab._files.atomic_output`).

    Parameters
    ----------
    path : str or path-like
        The output file; its suffix picks the format.
    image_rgb_or_gray : (H, W) or (H, W, 3) ndarray
        The image, RGB (converted to OpenCV's BGR to write) or grey.
    name : str
        The argument's name in error messages (e.g. ``"--out"``).

    Raises
    ------
    CamlabInputError
        If OpenCV cannot write the file, or the file fails its check.
    """
    import cv2

    from .._files import atomic_output

    image = (
        image_rgb_or_gray
        if image_rgb_or_gray.ndim == 2
        else cv2.cvtColor(image_rgb_or_gray, cv2.COLOR_RGB2BGR)
    )
    with atomic_output(path, name) as tmp:
        if not cv2.imwrite(str(tmp), image):
            raise CamlabInputError(f"{name}: could not write {str(path)!r}")


def check_positive_megapixels(value: float) -> None:
    """Refuse a ``--max-megapixels`` of 0.05 or less (or NaN).

    Parameters
    ----------
    value : float
        The option's value, megapixels.

    Raises
    ------
    CamlabInputError
        If ``value`` is not above 0.05.
    """
    if not value > 0.05:
        raise CamlabInputError(
            f"--max-megapixels: expected a size above 0.05 (megapixels), got {value}"
        )


def read_photo_or_fail(path: str, name: str):
    """The photo at ``path`` as RGB, upright; a file that cannot be read is a user's error.

    Parameters
    ----------
    path : str
        The photo's file.
    name : str
        The argument's name in the error message (e.g. ``"left"``).

    Returns
    -------
    (H, W, 3) uint8 ndarray
        The photo (:func:`camlab._files.read_photo`).

    Raises
    ------
    CamlabInputError
        If the file is missing, damaged or not an image.
    """
    from .._files import PhotoReadError, read_photo

    try:
        return read_photo(path, "rgb")
    except PhotoReadError as exc:
        raise CamlabInputError(f"{name}: {exc}") from None
