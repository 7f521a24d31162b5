"""Exercise 2 of lesson 07: a normalised DLT's fit mapped back wrongly, and the h33 slips; the slips its check names."""

from __future__ import annotations

import numpy as np

from ...projective import map_points
from .._core import Mistake


def _wrong_way_round(how, undo):
    return Mistake(
        how,
        undo,
        f"you undid the normalisation the wrong way round ({how}). H_n maps normalised points: "
        f"T_dst x' ~ H_n T_src x, so x' ~ inv(T_dst) H_n T_src x and H = inv(T_dst) @ H_n @ T_src.",
    )


UNDO_MISTAKES = (
    Mistake(
        "not undone",
        lambda s: s.Hn,
        "you returned H_n, the homography of the normalised points: the normalisation is not "
        "undone. H_n maps T_src x to T_dst x', so H = inv(T_dst) @ H_n @ T_src.",
    ),
    _wrong_way_round("T_dst @ H_n @ inv(T_src)", lambda s: s.Td @ s.Hn @ np.linalg.inv(s.Ts)),
    _wrong_way_round(
        "inv(T_dst) @ H_n @ inv(T_src)", lambda s: np.linalg.inv(s.Td) @ s.Hn @ np.linalg.inv(s.Ts)
    ),
    _wrong_way_round("T_dst @ H_n @ T_src", lambda s: s.Td @ s.Hn @ s.Ts),
    _wrong_way_round("inv(T_src) @ H_n @ T_dst", lambda s: np.linalg.inv(s.Ts) @ s.Hn @ s.Td),
    _wrong_way_round("T_src @ H_n @ inv(T_dst)", lambda s: s.Ts @ s.Hn @ np.linalg.inv(s.Td)),
    Mistake(
        "T_src on both sides",
        lambda s: np.linalg.inv(s.Ts) @ s.Hn @ s.Ts,
        "you undid the normalisation with T_src on both sides (inv(T_src) @ H_n @ T_src): the left "
        "factor must undo the *destination's* normalisation. H = inv(T_dst) @ H_n @ T_src.",
    ),
    Mistake(
        "T_dst on both sides",
        lambda s: np.linalg.inv(s.Td) @ s.Hn @ s.Td,
        "you undid the normalisation with T_dst on both sides (inv(T_dst) @ H_n @ T_dst): the right "
        "factor must apply the *source's* normalisation. H = inv(T_dst) @ H_n @ T_src.",
    ),
    Mistake(
        "T transposed in the undo",
        lambda s: np.linalg.inv(s.Td.T) @ s.Hn @ s.Ts.T,
        "you undid the normalisation with T transposed (inv(T_dst.T) @ H_n @ T_src.T): the translation "
        "of T sits in its last column, so T.T puts it in the bottom row and makes T projective. With "
        "points as rows you normalise by X @ T.T, but the undo is a product of the matrices themselves: "
        "H = inv(T_dst) @ H_n @ T_src.",
    ),
    Mistake(
        "elementwise products",
        lambda s: np.linalg.inv(s.Td) * s.Hn * s.Ts,
        "you multiplied the matrices element by element (inv(T_dst) * H_n * T_src): on numpy arrays * "
        "is the entrywise product. Use the matrix product: H = inv(T_dst) @ H_n @ T_src.",
    ),
    Mistake(
        "H_n transposed",
        lambda s: np.linalg.inv(s.Td) @ s.Hn.T @ s.Ts,
        "your H_n is transposed (the normalisation itself is undone right): h lists H row by row, so "
        "reshape it with h.reshape(3, 3), not order='F' or .T, before undoing the normalisation.",
    ),
    Mistake(
        "only src normalised, undone on both sides",
        lambda s: np.linalg.inv(s.Td) @ s.H,
        "you built A from normalised src but raw dst, then undid both (inv(T_dst) @ H_n @ T_src): "
        "inv(T_dst) undoes a normalisation dst never had. Normalise both sets before building A "
        "(or leave dst raw and return H_n @ T_src).",
    ),
    Mistake(
        "only dst normalised, undone on both sides",
        lambda s: s.H @ s.Ts,
        "you built A from raw src but normalised dst, then undid both (inv(T_dst) @ H_n @ T_src): "
        "T_src applies a normalisation src never had. Normalise both sets before building A.",
    ),
    Mistake(
        "raw pixels, normalisation undone",
        lambda s: np.linalg.inv(s.Td) @ s.H @ s.Ts,
        "you built A from the raw pixels, yet undid a normalisation (inv(T_dst) @ H @ T_src): the "
        "points that went into A were never normalised, so the undo applies a T they never had. "
        "Normalise first (src_n = T_src x, dst_n = T_dst x'), build A from src_n and dst_n, then undo.",
    ),
    Mistake(
        "destination's normalisation only undone",
        lambda s: np.linalg.inv(s.Td) @ s.Hn,
        "you undid only the destination's normalisation (inv(T_dst) @ H_n): the result still "
        "expects normalised source points T_src x. Undo both: H = inv(T_dst) @ H_n @ T_src.",
    ),
    Mistake(
        "source's normalisation only undone",
        lambda s: s.Hn @ s.Ts,
        "you undid only the source's normalisation (H_n @ T_src): the result still gives "
        "normalised destination points T_dst x'. Undo both: H = inv(T_dst) @ H_n @ T_src.",
    ),
)
"""A normalised DLT's fit H_n = T_dst H inv(T_src) mapped back wrongly, in the order the diagnosis tests them."""


def divided_by_noise(got, expected) -> bool:
    """True for an H divided by its h33 where the true h33 is 0: h33 comes back 1, the rest ~1e9 to 1e18.

    The SVD's h33 there is rounding noise (~1e-17); dividing keeps h's direction, so it passes with a
    note. OpenCV's h33 = 1 is solved for (entries ~1e9): no note, hence the bar 1e12.
    """
    g, e = np.asarray(got, dtype=float), np.asarray(expected, dtype=float)
    if g.shape != (3, 3) or abs(e[2, 2]) > 1e-9 * np.linalg.norm(e) or not np.isfinite(g).all():
        return False
    return bool(abs(abs(g[2, 2]) - 1.0) < 1e-6 and np.linalg.norm(g) > 1e12)


def h33_slip(g, src, dst, expected) -> str:
    """Name an H forced to h33 = 1, or divided by h33, on the input whose true h33 is 0 ("" otherwise)."""
    e = np.asarray(expected, dtype=float)
    if abs(e[2, 2]) > 1e-9 * np.linalg.norm(e):
        return ""
    if g.shape == (3, 3) and not np.isfinite(g).all():
        return (
            "your H holds inf or nan: you divided H by its h33, which is exactly 0 here. This input's "
            "true h33 is 0 (H sends the pixel origin to infinity), so H has no h33 = 1 form. Return the "
            "SVD's unit-norm h as it is (h.reshape(3, 3), any scale)."
        )
    if not np.isfinite(g).all() or abs(g[2, 2]) < 1e-6 * np.linalg.norm(g):
        return ""
    with np.errstate(divide="ignore", invalid="ignore"):
        off = np.nanmax(np.linalg.norm(map_points(g, src) - dst, axis=1))
    return (
        f"you fixed h33 = 1 (least squares for the other 8 entries, section 5's aside). "
        f"That assumes H does not send the pixel origin (0, 0) to infinity, but this H does: its true "
        f"h33 is 0, so no H with h33 = 1 fits and yours lands up to {off:.3g} px off these exact pairs. "
        f"Solve A h = 0 for the unit-norm h by SVD (the last row of Vt), which assumes nothing about h33."
    )
