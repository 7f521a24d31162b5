"""Comparisons shared by exercises whose answer is one number."""
from __future__ import annotations

import numpy as np

from ._core import SameArray, Tolerance


def is_number(x) -> bool:
    """True for a finite real scalar (a Python float, a 0-d array...); never a string such as "0.37"."""
    if isinstance(x, (str, bytes)) or (isinstance(x, np.ndarray) and x.dtype.kind in "USO"):
        return False
    try:
        return np.ndim(x) == 0 and bool(np.isfinite(float(x)))
    except (TypeError, ValueError):
        return False


class SameNumber(SameArray):
    """``Exercise.compare`` for a one-number answer: finite, and within ``tolerance`` of the expected one."""

    def __call__(self, got, expected) -> bool:
        return is_number(got) and super().__call__(got, expected)


def same_number(rtol: float = 1e-9) -> SameNumber:
    """A comparison for ``Exercise.compare``: one finite number, equal to the expected one within ``rtol``."""
    return SameNumber(Tolerance(rtol, 1e-8))
