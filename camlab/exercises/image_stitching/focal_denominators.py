"""Exercise 4's denominators: which of the four focal formulas decides, and when one is 0/0.

Each pair of formulas (the rows' two, the columns' two) is evaluated on the centred H divided by its
norm; the formula with the larger denominator decides. On an exact rotation a denominator can be
exactly 0 together with its numerator (a pure pan, a pure tilt, a turn about a diagonal axis), and on
an estimated H that 0/0 is round-off over round-off: any number at all.
"""

from __future__ import annotations

import numpy as np

FORMULAS = {
    "c1": ("-(h0 h1 + h3 h4) / (h6 h7) (columns orthogonal)", "h6 or h7 is 0"),
    "c2": ("(h0^2 + h3^2 - h1^2 - h4^2) / (h7^2 - h6^2) (columns equally long)", "h6 = +-h7"),
    "r1": ("-h2 h5 / (h0 h3 + h1 h4) (rows orthogonal)", "h2 or h5 is 0"),
    "r2": ("(h5^2 - h2^2) / (h0^2 + h1^2 - h3^2 - h4^2) (rows equally long)", "h2 = +-h5"),
}
"""Each formula and when it is 0/0 on a rotation (numerator and denominator both exactly 0)."""


def _centred_entries(H, shape):
    h, w = shape[:2]
    C = np.array([[1.0, 0, (w - 1) / 2], [0, 1, (h - 1) / 2], [0, 0, 1]])
    Hc = np.linalg.inv(C) @ np.asarray(H, float) @ C
    return (Hc / np.linalg.norm(Hc)).ravel()


def denominators(H, shape) -> dict[str, float]:
    """The four formulas' denominators on the centred H divided by its norm (scale-free).

    Parameters
    ----------
    H : (3, 3) array_like
        The homography, pixels.
    shape : tuple
        The image's shape, (h, w, ...): its centre ((w - 1) / 2, (h - 1) / 2) is the origin.

    Returns
    -------
    dict
        ``{"c1": h6 h7, "c2": h7^2 - h6^2, "r1": h0 h3 + h1 h4, "r2": h0^2 + h1^2 - h3^2 - h4^2}``.
    """
    h0, h1, h2, h3, h4, h5, h6, h7, _ = _centred_entries(H, shape)
    return {
        "c1": h6 * h7,
        "c2": h7**2 - h6**2,
        "r1": h0 * h3 + h1 * h4,
        "r2": h0**2 + h1**2 - h3**2 - h4**2,
    }


_PARTNER = {"c1": "c2", "c2": "c1", "r1": "r2", "r2": "r1"}


def zero_over_zero(H, shape, keys=("c1", "c2", "r1", "r2")) -> list[str]:
    """The formulas among ``keys`` that are 0/0 on this H: a denominator at round-off level next to its partner's.

    Parameters
    ----------
    H, shape
        As in :func:`denominators`.
    keys : sequence of str
        The formulas to test, among ``"c1", "c2", "r1", "r2"``.

    Returns
    -------
    list of str
        The 0/0 formulas, in the order of ``keys``.
    """
    d = denominators(H, shape)
    return [k for k in keys if abs(d[k]) < 1e-6 * abs(d[_PARTNER[k]])]  # noise of 1e-9 leaves ~1e-8


def decides(H, shape, keys) -> str:
    """Which formula of the pair ``keys`` has the larger denominator on this H (the one the rule uses).

    Parameters
    ----------
    H, shape
        As in :func:`denominators`.
    keys : tuple of str
        A pair: ``("r1", "r2")`` (the rows') or ``("c1", "c2")`` (the columns').

    Returns
    -------
    str
        The key of the formula with the larger denominator in magnitude.
    """
    d = denominators(H, shape)
    return keys[0] if abs(d[keys[0]]) > abs(d[keys[1]]) else keys[1]


def zero_over_zero_hint(zz: list[str], got: float, which: str) -> str:
    """The feedback for a student whose answer came from a 0/0 formula (the ones in ``zz``).

    Parameters
    ----------
    zz : list of str
        The 0/0 formulas (:func:`zero_over_zero`).
    got : float
        The student's answer.
    which : str
        Which answer it is, for the message (``"f_from"`` or ``"f_to"``, with its input).

    Returns
    -------
    str
        The hint: why 0/0 is no slip in the indices, and the larger-denominator rule.
    """
    what = "NaN" if np.isnan(got) else ("inf" if np.isinf(got) else f"{got:.6g}")
    listed = "; ".join(f"{FORMULAS[k][0]} is 0/0 because {FORMULAS[k][1]}" for k in zz)
    return (
        f"you returned {what} for {which} on a turn where {listed}. 0/0 is round-off divided by round-off (NaN, "
        "inf or any number), not a slip in your indices: in each pair use the formula whose denominator is larger "
        "in magnitude, and drop neither by a filter such as f^2 > 0: on an estimated H a 0/0 is a finite, "
        "arbitrary number (a pure pan has h7 = 0, a pure tilt h6 = 0, a turn about a diagonal axis h6 = +-h7)."
    )
