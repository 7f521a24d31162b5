"""Comparisons shared by exercises whose answer is one number."""

from __future__ import annotations

import numpy as np

from ._answers import SameArray, Tolerance


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


def not_one_number(got, what: str) -> str:
    """Why ``got`` is not one number, naming what came instead (a 1-tuple from a trailing comma, a list...)."""
    if isinstance(got, (tuple, list, np.ndarray)) and np.ndim(got) > 0:
        kind = "numpy array" if isinstance(got, np.ndarray) else type(got).__name__
        how = {
            "tuple": " (a trailing comma, `return x,`, makes a tuple)",
            "list": " (brackets, `[x]`, make a list)",
        }
        if np.size(got) == 1:
            return (
                f"you returned a {kind} holding one number{how.get(kind, '')}; return one number, {what}: "
                f"the value itself (float(x) or x[0])"
            )
        return f"you returned a {kind} of shape {np.shape(got)}; return one number, {what}"
    return f"return one number: {what}"
