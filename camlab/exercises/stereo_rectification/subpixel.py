"""Exercise 8 of lesson 11: block matching's steps 2 and 3 on one cost curve (`subpixel_disparity`)."""

from __future__ import annotations

import numpy as np

from .._core import Exercise, register_exercise

# --------------------------------------------------------------------------- the sub-pixel disparity


def _subpixel_cases():
    """Cost curves over candidates that start at min_disparity (not 0); the minimum never at an end.

    A V-shaped cost (a sum of absolute differences near its minimum), a lopsided one, and a noisy
    curve with a rival minimum far away, as at section 5's pixel B.
    """
    rng = np.random.default_rng(11)
    ds1 = np.arange(8, 45)
    v_cost = 160 + 90 * np.abs(ds1 - 20.3)
    ds2 = np.arange(16, 61)
    lopsided = (
        300 + np.where(ds2 < 31.8, 140, 60) * np.abs(ds2 - 31.8) + rng.uniform(0, 5, ds2.size)
    )
    far = np.abs(ds1 - 12.6) > 2
    noisy = 170 + 40 * np.abs(ds1 - 12.6) + np.where(far, rng.uniform(60, 200, ds1.size), 0.0)
    noisy[ds1 == 43] = 192.0  # a rival 30 px away, 3 % above the best (186)
    return [(ds1, v_cost), (ds2, lopsided), (ds1, noisy)]


_FLOOR = (
    "you divided with // (floor division): it rounds the vertex's offset, a fraction between -0.5 and "
    "0.5, down to 0 or -1. Use true division, /"
)


def _whole_pixel_or_floor(run) -> str:
    """The whole-pixel winner, or floor division, told apart on a cost whose vertex lies below it."""
    ds = np.arange(8, 20)
    try:  # the vertex at 12.7: floor division gives 12, a kept winner 13
        again = float(np.asarray(run(ds, 100 + 10 * np.abs(ds - 12.7)))) if run else np.nan
    except Exception:
        again = np.nan
    if np.isclose(again, 12.0):
        return _FLOOR
    return (
        "you kept the whole-pixel winner: step 3 fits a parabola through the costs at d - 1, d, d + 1 "
        "and moves d to its vertex"
    )


def _vertex(c, k):
    cm, c0, cp = c[k - 1], c[k], c[k + 1]
    return (cm - cp) / (2 * (cm - 2 * c0 + cp))


# an off-by-one triple on a straight stretch of the cost has no vertex: its division by 0 is no error here
@np.errstate(divide="ignore", invalid="ignore")
def _subpixel_diagnosis(args, got, expected, run=None) -> str:
    ds, c = (np.asarray(a, dtype=float) for a in args)
    if np.ndim(got) != 0:
        return f"return one number, the sub-pixel disparity (a float); got shape {np.shape(got)}"
    g = float(np.asarray(got))
    k = int(np.argmin(c))
    off = _vertex(c, k)
    big = int(np.argmax(c[1:-1])) + 1  # the largest cost inside, where a parabola fits
    slips = [
        (
            ds[k] - off,
            "the vertex's sign is flipped: with c- the cost at d - 1 and c+ at d + 1, the parabola's "
            "minimum is at d + (c- - c+) / (2 (c- - 2 c0 + c+)); it moves towards the cheaper neighbour",
        ),
        (
            k + off,
            f"you returned the index k = {k} (plus the offset), not the disparity ds[k] = {ds[k]:g}: the "
            f"candidates start at min_disparity = {ds[0]:g}, so index and disparity differ",
        ),
        (
            ds[k] + 2 * off,
            "your offset is twice the vertex's: the parabola's minimum is (c- - c+) / (2 (c- - 2 c0 + c+)); "
            "the factor 2 in the denominator is missing",
        ),
        (ds[k], _whole_pixel_or_floor(run)),
        (ds[k] + np.floor(off), _FLOOR),
        (
            ds[k] + (c[k - 1] - c[k + 1]) / (2 * (max(c[k - 1], c[k + 1]) - c[k])),
            "you fitted the equiangular line (two lines of opposite slope through the three costs, "
            "Shimizu & Okutomi), exact for a V-shaped cost; step 3 asks for the parabola's vertex, "
            "d + (c- - c+) / (2 (c- - 2 c0 + c+))",
        ),
        (off, "you returned the offset alone: add it to the whole-pixel winner ds[k]"),
        (
            ds[k] + 1 + _vertex(c, k + 1),
            "your three costs are off by one: take c[k - 1], c[k], c[k + 1], "
            "centred on the winner k = argmin(cost), not c[k], c[k + 1], c[k + 2]",
        ),
        (
            ds[k] - 1 + _vertex(c, k - 1),
            "your three costs are off by one: take c[k - 1], c[k], c[k + 1], "
            "centred on the winner k = argmin(cost), not c[k - 2], c[k - 1], c[k]",
        ),
        (
            ds[k] + (c[k - 1] - c[k + 1]) / (2 * (c[k - 1] + 2 * c[k] + c[k + 1])),
            "the denominator is the second "
            "difference c- - 2 c0 + c+ (the parabola's curvature): a + before 2 c0 makes the step far too small",
        ),
    ]
    argmax = (
        "you took the largest cost (argmax): the best match is the smallest cost, k = argmin(cost)"
    )
    slips += [(ds[big] + _vertex(c, big), argmax), (ds[big], argmax)]
    index = f"you returned the index k = {k}, not the disparity ds[k] = {ds[k]:g}: the candidates start at min_disparity = {ds[0]:g}"
    slips += [(k, index + ", and step 3's parabola moves the winner to its vertex")]
    for value, hint in slips:
        if np.isclose(g, value, rtol=0, atol=1e-6):
            return hint
    for shift in (0.5, -0.5, 1.0, -1.0):
        if np.isclose(g, expected + shift, rtol=0, atol=1e-6):
            return f"your disparity is {shift:+g} px off: no half-pixel or 1-based offset belongs in it"
    return (
        f"you give {g:.4g} px; the winner is ds[{k}] = {ds[k]:g} (costs {c[k - 1]:.4g}, {c[k]:.4g}, {c[k + 1]:.4g} "
        f"at d - 1, d, d + 1) and the parabola's vertex is {expected:.4g} px"
    )


def _subpixel_exception_hint(exc: Exception, args: tuple) -> str:
    """An index past the end of the cost: the winner was taken at an end, where c[k + 1] does not exist."""
    if not (isinstance(exc, IndexError) and "out of bounds" in str(exc)):
        return ""
    c = np.asarray(args[1], dtype=float)
    if int(np.argmax(c)) in (0, len(c) - 1):
        return (
            f"c[k + 1] or c[k - 1] past the end of the {len(c)} costs: your winner k sits at an end of ds, "
            "where the LARGEST cost of this curve is. The winner is the lowest cost, k = np.argmin(cost) "
            "(never at an end here); did you take argmax?"
        )
    return (
        f"an index past the end of the {len(c)} costs: the three costs are c[k - 1], c[k], c[k + 1] around "
        "k = np.argmin(cost), an index into cost (0 .. D - 1), not the disparity ds[k]"
    )


def subpixel_disparity(ds, cost):
    """Winner takes all, then the vertex of the parabola through the three costs around the winner.

    Parameters
    ----------
    ds : (D,) array_like
        The candidate disparities, pixels, in steps of 1 from ``min_disparity``.
    cost : (D,) array_like
        The matching cost of each candidate (lower is better); its minimum is not at an end.

    Returns
    -------
    float
        ``ds[k] + (c[k-1] - c[k+1]) / (2 (c[k-1] - 2 c[k] + c[k+1]))`` with ``k = argmin(cost)``.
    """
    ds, c = np.asarray(ds, dtype=float), np.asarray(cost, dtype=float)
    k = int(np.argmin(c))
    return float(ds[k] + (c[k - 1] - c[k + 1]) / (2 * (c[k - 1] - 2 * c[k] + c[k + 1])))


def _reference(ds, cost):
    """The vertex another way: np.polyfit's least-squares parabola through the three samples (exact)."""
    ds, c = np.asarray(ds, dtype=float), np.asarray(cost, dtype=float)
    k = int(np.argmin(c))
    a, b, _ = np.polyfit(ds[k - 1 : k + 2], c[k - 1 : k + 2], 2)
    return float(-b / (2 * a))


def _floor_division(ds, c):
    """The vertex with // where / belongs (tests)."""
    c = np.asarray(c, dtype=float)
    k = int(np.argmin(c))
    return float(ds[k] + (c[k - 1] - c[k + 1]) // (2 * (c[k - 1] - 2 * c[k] + c[k + 1])))


def _equiangular(ds, c):
    """The equiangular-line fit, exact for a V, in place of the parabola (tests)."""
    c = np.asarray(c, dtype=float)
    k = int(np.argmin(c))
    return float(ds[k] + (c[k - 1] - c[k + 1]) / (2 * (max(c[k - 1], c[k + 1]) - c[k])))


def _flip(ds, c):
    k = int(np.argmin(c))
    return ds[k] - _vertex(np.asarray(c, float), k)


register_exercise(
    Exercise(
        name="subpixel_disparity",
        lesson="11",
        reference=_reference,
        cases=_subpixel_cases,
        compare=lambda got, expected: (
            np.ndim(got) == 0 and np.isclose(float(got), expected, rtol=0, atol=1e-6)
        ),
        diagnose=_subpixel_diagnosis,
        diagnosis_runs=True,  # floor division and a kept winner tie where the vertex is above d_k
        exception_hint=_subpixel_exception_hint,
        wrong_variants=(
            (_flip, "sign is flipped"),
            (
                lambda ds, c: np.argmin(c) + _vertex(np.asarray(c, float), int(np.argmin(c))),
                "index",
            ),
            (
                lambda ds, c: (
                    ds[np.argmin(c)] + 2 * _vertex(np.asarray(c, float), int(np.argmin(c)))
                ),
                "factor 2",
            ),
            (lambda ds, c: float(ds[np.argmin(c)]), "whole-pixel winner"),
            (_floor_division, "floor division"),
            (_equiangular, "equiangular line"),
            (lambda ds, c: _vertex(np.asarray(c, float), int(np.argmin(c))), "offset alone"),
            (
                lambda ds, c: (
                    ds[np.argmin(c) + 1] + _vertex(np.asarray(c, float), int(np.argmin(c)) + 1)
                ),
                "off by one",
            ),
            (
                lambda ds, c: (
                    ds[np.argmin(c)] + 0.5 + _vertex(np.asarray(c, float), int(np.argmin(c)))
                ),
                "half-pixel",
            ),
            (lambda ds, c: np.array([subpixel_disparity(ds, c)]), "one number"),
        ),
        teaching=subpixel_disparity,
    )
)
