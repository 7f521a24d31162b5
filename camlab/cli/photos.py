r"""Reading and writing the commands' photos: one reader (upright by EXIF, truncated files refused
by name), shrinking above ``--max-megapixels``, outputs written atomically.
"""

from __future__ import annotations

from .._validate import CamlabInputError

__all__ = []


def expand(patterns: list[str]) -> list[str]:
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
    """The photo (upright, see :func:`camlab._files.read_photo`), or None after a line saying why it is skipped."""
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
    """Image files from folders (their images, sorted), files and quoted glob patterns."""
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
    if not value > 0.05:
        raise CamlabInputError(
            f"--max-megapixels: expected a size above 0.05 (megapixels), got {value}"
        )


def read_photo_or_fail(path: str, name: str):
    from .._files import PhotoReadError, read_photo

    try:
        return read_photo(path, "rgb")
    except PhotoReadError as exc:
        raise CamlabInputError(f"{name}: {exc}") from None
