r"""The ``camlab`` command line: ``camlab <command> ...``.

Commands are registered in :data:`COMMANDS` (name -> (add_arguments, run)); to add one,
write ``add_<name>(parser)`` and ``run_<name>(args) -> int`` in
a module of this package (one per command family) and register them in
:mod:`camlab.cli.main`. Errors a
user can fix (bad pattern, no images, too few detections) are printed as one clear
message with exit status 2, never a traceback.

``camlab lessons [DEST] [--force]`` copies the lessons into a working folder (see
:mod:`camlab.course`); ``camlab --version`` prints the version.

``camlab calibrate "photos/*.jpg" --pattern 9x6 --square 0.025 [--out camera.json]
[--report report.png]`` detects the chessboard in each photo, calibrates, prints the result
and the coach's advice, writes an OpenCV-loadable file (``cv2.FileStorage``: ``.json``,
``.yaml`` or ``.xml``) and saves a report figure.

``camlab undistort``, ``camlab stitch FOLDER --out pano.jpg [--projection ...]`` and
``camlab rectify LEFT RIGHT --out-dir D`` work on real photos: each prints a line per image
or pair, exits 0 when everything was used, 1 when some input was left out (and says which),
2 on an error the user can fix; outputs are checked before any work (never one of the inputs)
and written atomically. Photos are read by one reader (:func:`camlab._files.read_photo`:
upright by their EXIF orientation, truncated files refused by name); ``stitch`` and
``rectify`` shrink photos above ``--max-megapixels``; ``rectify --calibration CAL`` rectifies
from the camera's calibration, which also works where the matches lie on one plane.
"""

from __future__ import annotations

from .main import COMMANDS, build_parser, main

__all__ = [
    "COMMANDS",
    "build_parser",
    "main",
]
