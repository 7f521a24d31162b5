"""Comparisons shared by exercises whose answer is one number."""
from __future__ import annotations

import numpy as np


def is_number(x) -> bool:
    """True for a finite real scalar (a Python float, a 0-d array...)."""
    try:
        return np.ndim(x) == 0 and bool(np.isfinite(float(x)))
    except (TypeError, ValueError):
        return False
