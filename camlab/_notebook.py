"""Warnings from a notebook cell read as a sentence, without the kernel's temporary path.

Python prints a warning as ``<file>:<line>: <Category>: <message>`` and then the source line.
Raised from a cell (``stacklevel`` points at the caller, as camlab's warnings do), the file
is the temporary file ipykernel compiles each cell into, so a student reads::

    /tmp/ipykernel_6366/3058451507.py:2: UserWarning: stitch: left out of the panorama: ...
      result3 = st.stitch(turn.images, names=turn.names)

:func:`install_warning_format` makes such a warning print as ``UserWarning: stitch: ...``
(the cell it came from is the one showing it). Warnings attributed to real files keep
Python's format.
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path
from typing import Any, TextIO

UPLOAD_NEEDS_KERNEL = "Uploading photos needs a running kernel: open this lesson in JupyterLab."
"""What a page without a live kernel (the website, lecture mode) shows for a photo upload control."""


def is_cell_file(filename: str) -> bool:
    """True for the file name IPython gives a cell's code (ipykernel's temporary file, or ``<ipython-input-...>``)."""
    return Path(filename).parent.name.startswith("ipykernel_") or filename.startswith(
        "<ipython-input-"
    )


def _show_warning(
    message: Warning | str,
    category: type[Warning],
    filename: str,
    lineno: int,
    file: TextIO | None = None,
    line: str | None = None,
) -> None:
    """``warnings.showwarning`` in a kernel: Python's format, without the path for a cell's warning."""
    if is_cell_file(filename):
        text = f"{category.__name__}: {message}\n"
    else:
        text = warnings.formatwarning(message, category, filename, lineno, line)
    stream = sys.stderr if file is None else file
    try:
        stream.write(text)
    except OSError:  # like Python's own: a closed stderr loses the warning, not the program
        pass


def install_warning_format() -> bool:
    """In an IPython kernel, print warnings from cells without their temporary path; returns whether it did."""
    shell: Any = None
    if "IPython" in sys.modules:
        shell = sys.modules["IPython"].get_ipython()
    if shell is None or getattr(shell, "kernel", None) is None:
        return False
    warnings.showwarning = _show_warning
    return True
