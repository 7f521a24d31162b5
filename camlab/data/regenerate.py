"""Regenerate every rendered data set: ``python -m camlab.data [DIR]``.

Writes the calibration, panorama and stereo sets into ``DIR`` (default
:func:`~camlab.data.regeneration_dir`: ``$CAMLAB_DATA``, a clone's ``data/``, else the user
cache, never site-packages) and a ``MANIFEST.txt`` of every file's SHA-256 and size. The
output is deterministic; ``tests/test_data.py`` compares it with the bundled sets by decoded
pixels and ground truth (within stated tolerances), so a patch release of OpenCV's image
codecs does not break it.
"""

from __future__ import annotations

import argparse
import hashlib
import sys
from pathlib import Path

from ._resources import data_dir, regeneration_dir

__all__ = ["GENERATED_SETS", "main", "regenerate", "write_manifest"]


GENERATED_SETS = ("calib_chessboard", "panorama", "stereo")


def write_manifest(root: Path) -> Path:
    """``root/MANIFEST.txt``: every generated file (:data:`GENERATED_SETS`) with its SHA-256 and size in bytes."""
    lines = []
    for p in sorted(root.rglob("*")):
        if p.is_file() and p.relative_to(root).parts[0] in GENERATED_SETS:
            lines.append(
                f"{hashlib.sha256(p.read_bytes()).hexdigest()}  {p.stat().st_size:>8}  "
                f"{p.relative_to(root).as_posix()}"
            )
    path = root / "MANIFEST.txt"
    path.write_text(
        "# sha256  bytes  path   (regenerate everything with: python -m camlab.data)\n"
        + "\n".join(lines)
        + "\n"
    )
    return path


def regenerate(root: Path | str) -> list[Path]:
    """Render every data set into ``root`` and write its manifest; return the data files written."""
    from .calibration import make_calibration_set
    from .panorama import make_panorama_set
    from .stereo import make_stereo_rig

    root = Path(root)
    files = (
        make_calibration_set(root / "calib_chessboard")
        + make_panorama_set(root / "panorama")
        + make_stereo_rig(root / "stereo")
    )
    write_manifest(root)
    return files


def main(argv: list[str] | None = None) -> int:
    """Command line: ``python -m camlab.data [DIR]``."""
    parser = argparse.ArgumentParser(
        prog="python -m camlab.data", description="Regenerate camlab's rendered data sets."
    )
    parser.add_argument(
        "dir",
        nargs="?",
        type=Path,
        default=None,
        help="output folder (default: $CAMLAB_DATA, a clone's data/, else the user cache)",
    )
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    root = args.dir if args.dir is not None else regeneration_dir()
    files = regenerate(root)
    total = sum(f.stat().st_size for f in files)
    print(f"wrote {len(files)} files ({total / 1e6:.2f} MB) to {root}")
    if root.resolve() != data_dir().resolve():
        print(f"set CAMLAB_DATA={root} to load these instead of the bundled sets")
    return 0
