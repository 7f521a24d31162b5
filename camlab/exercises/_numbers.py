"""Comparisons shared by exercises whose answer is one number."""
from __future__ import annotations

import numpy as np


def is_number(x) -> bool:
    """True for a finite real scalar (a Python float, a 0-d array...)."""
    try:
        return np.ndim(x) == 0 and bool(np.isfinite(float(x)))
    except (TypeError, ValueError):
        return False


def same_number(rtol: float = 1e-9):
    """A comparison for ``Exercise.compare``: one finite number, equal to the expected one within ``rtol``."""

    def compare(got, expected) -> bool:
        return is_number(got) and bool(np.isclose(float(got), expected, rtol=rtol))

    return compare
