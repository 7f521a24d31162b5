"""Lesson 09, exercise 2: feathering weights (feather_weights), each pixel's distance to the image border."""

from __future__ import annotations

import numpy as np

from ... import stitching as st
from .._answers import same_array, shape_unpack_hint
from .._core import Exercise, register_exercise

# ----------------------------------------------------------------------------- feather weights


def feather_weights(shape):
    """Teaching solution: each pixel's distance to the nearest image border (pixel centres at integers).

    Parameters
    ----------
    shape : tuple of int
        The image's shape (height, width[, channels]).

    Returns
    -------
    (height, width) ndarray of float
        The distance in pixels from each pixel centre to the nearest border; the borders lie at
        -1/2 and w - 1/2 (h - 1/2), so the corner pixel's weight is 1/2.
    """
    h, w = shape[:2]
    u = np.arange(w, dtype=float)  # pixel centres 0 ... w-1; the borders at -1/2 and w - 1/2
    v = np.arange(h, dtype=float)[:, None]
    return np.minimum(np.minimum(u + 0.5, w - 0.5 - u), np.minimum(v + 0.5, h - 0.5 - v))


def _feather_cases():
    # the last shape has channels, as an image's shape may (exercise 1 and `stitch` pass image shapes)
    return [((3, 4),), ((5, 5),), ((6, 9),), ((1, 3),), ((4, 7, 3),)]


_FEATHER_GENERIC = (
    "w(u, v) = min(u + 1/2, W - 1/2 - u, v + 1/2, H - 1/2 - v): the distance to the nearest border."
)


def _feather_diagnosis(args, got, expected) -> str:
    g = np.asarray(got, dtype=float)
    if g.shape != expected.shape:
        return _feather_shape_hint(args[0], g.shape, expected.shape)
    dtype = np.asarray(got).dtype
    if dtype.kind not in "iub":
        return _feather_values_hint(g, expected)
    cut = (
        f"your array has an integer dtype ({dtype}), so the half-pixel distances (u + 1/2, ...) "
        "were cut to whole numbers when stored: build it as floats (np.zeros((h, w)), or np.minimum of float "
        "arrays), not np.zeros((h, w), int)."
    )
    # whole numbers that are themselves a named slip (u + 1, the 1-based distance, holds no half
    # to cut): that slip first, the dtype second
    cause = _feather_values_hint(g, expected)
    if cause == _FEATHER_GENERIC or np.array_equal(g, np.trunc(expected)):  # the storing cut
        return cut
    return (
        f"{cause} Then return floats: the right distances (u + 1/2, ...) are half-integers, which your "
        f"integer dtype ({dtype}) cannot hold."
    )


def _feather_values_hint(g: np.ndarray, expected: np.ndarray) -> str:
    """The cause of wrong weight values ``g`` (float, of the right shape) against ``expected``."""
    if g.max() > 0 and np.allclose(g, expected / expected.max()):
        return (
            "you normalised the weights to a maximum of 1; the prompt asks for the distance itself, in pixels "
            "(feathering divides by the sum of the weights later, so the scale must be the same for every image)."
        )
    if g.sum() > 0 and np.allclose(g, expected / expected.sum()):
        return (
            "you normalised the weights to sum to 1; the prompt asks for the distance itself, in pixels "
            "(feathering divides by the sum of all the images' weights at each pixel later, not by one image's total)."
        )
    h, w = expected.shape
    u, v = np.arange(w, dtype=float), np.arange(h, dtype=float)[:, None]
    if np.allclose(g, (np.minimum(u + 0.5, w - 0.5 - u)) * np.minimum(v + 0.5, h - 0.5 - v)):
        return (
            "you multiplied the horizontal and vertical distances; the weight here is their minimum, the distance "
            "to the nearest border (Brown & Lowe's separable w(x) w(y) is a product, but of weights scaled to 1 at "
            "the centre, and this exercise asks for the distance map)."
        )
    du, dv = np.minimum(u + 0.5, w - 0.5 - u), np.minimum(v + 0.5, h - 0.5 - v)
    if np.allclose(g, (du / du.max()) * (dv / dv.max())):
        return (
            "that is Brown & Lowe's separable weight w(x) w(y), each factor scaled to 1 at the centre; this "
            "exercise asks for the distance map itself: the minimum of the four distances, in pixels, not a product."
        )
    if np.allclose(g, _feather_swapped_far((h, w))):
        return (
            "a far border in the wrong place, W and H swapped inside the far terms: the far borders are at u = W - 1/2 (W = shape[1], the columns) "
            "and v = H - 1/2 (H = shape[0], the rows), so the terms are W - 1/2 - u and H - 1/2 - v."
        )
    if np.allclose(g, _feather_flipped_far((h, w))):
        return (
            "the far terms' sign is flipped: you wrote u - (W - 1/2) (and v - (H - 1/2)), which is negative on "
            "every pixel, so the minimum is always the far term. The distance to the far border is "
            "(W - 1/2) - u: the border minus the pixel, as the near one is u - (-1/2)."
        )
    if np.allclose(g, expected - 0.5):
        return (
            "off by half a pixel: pixel centres are at integer u and the border at u = -1/2, so the first "
            "column is 1/2 from the border (u + 1/2), not 0."
        )
    if np.allclose(g, expected + 0.5):
        return "off by half a pixel: the border is at u = -1/2 and u = W - 1/2; use u + 1/2 and W - 1/2 - u."
    if np.allclose(g, 2 * expected):
        return (
            "your weights are twice the distances: 2u + 1 counts half-pixels (whole numbers, no fractions), but "
            "the weight is the distance in pixels, u + 1/2 and W - 1/2 - u (the corner pixel weighs 1/2, not 1)."
        )
    h, w = expected.shape
    u = np.arange(w, dtype=float)
    du = np.minimum(u + 0.5, w - 0.5 - u)
    if np.allclose(g, np.broadcast_to(du, (h, w))):
        return "you only used the distance to the left and right borders; take the minimum with the vertical distance too."
    v = np.arange(h, dtype=float)
    if np.allclose(g, np.broadcast_to(np.minimum(v + 0.5, h - 0.5 - v)[:, None], (h, w))):
        return "you only used the distance to the top and bottom borders; take the minimum with the horizontal distance too."
    if np.allclose(g, _feather_offsets(expected.shape, 1.5, 1.5)):
        return (
            "you counted pixels from 1: the first column is u = 0 (pixel centres at 0, 1, ..., W - 1), "
            "so use np.arange(W), not np.arange(1, W + 1)."
        )
    if np.allclose(g, _feather_offsets(expected.shape, 1.0, 1.0)):
        return (
            "you counted pixels from 1 (u = 1 ... W, as np.arange(1, W + 1) gives) and took min(u, W - u), so the "
            "first column weighs 1 and the last 0. Pixel centres are u = 0 ... W - 1 (np.arange(W)) and the "
            "borders half a pixel outside them: min(u + 1/2, W - 1/2 - u), and the same for v."
        )
    offsets = _offset_hint(g, expected.shape)
    if offsets:
        return offsets
    if g.min() < -1e-9:
        return _negative_hint(g, expected.shape)
    return _FEATHER_GENERIC


def _term(side: str, c: float) -> str:
    """The near (u + c) or far (W - c - u) term as a student wrote it, with c as a fraction: u - 1/2, W - 3/2 - u."""
    frac = {0.0: "0", 0.5: "1/2", 1.0: "1", 1.5: "3/2", -0.5: "1/2"}[c]
    if side == "near":
        return "u" if c == 0 else f"u {'+' if c > 0 else '-'} {frac}"
    return "W - u" if c == 0 else f"W {'-' if c > 0 else '+'} {frac} - u"


def _offset_hint(g: np.ndarray, shape) -> str:
    """Name the border(s) a half-pixel (or whole-pixel) slip put elsewhere: min(u + a, W - b - u, ...)."""
    for a in (-0.5, 0.0, 0.5, 1.0):
        for b in (-0.5, 0.0, 0.5, 1.0, 1.5):
            if (a, b) == (0.5, 0.5) or not np.allclose(g, _feather_offsets(shape, a, b)):
                continue
            near = (
                ""
                if a == 0.5
                else (
                    f"the near border (you used {_term('near', a)}; the first pixel's centre u = 0 is 1/2 "
                    "from the border at u = -1/2, so u + 1/2"
                    + ("; with u - 1/2 the first pixel gets a weight below 0" if a < 0 else "")
                    + ")"
                )
            )
            far = (
                ""
                if b == 0.5
                else (
                    f"the far border (you used {_term('far', b)}; the last pixel's centre u = W - 1 is "
                    "1/2 from the border at u = W - 1/2, so W - 1/2 - u"
                    + (
                        "; with W + 1/2 - u the last pixel weighs 3/2, more than its neighbour"
                        if b < 0
                        else ""
                    )
                    + ")"
                )
            )
            size = "half a pixel" if {abs(a - 0.5), abs(b - 0.5)} <= {0.0, 0.5} else "a whole pixel"
            return (
                f"off by {size} at "
                + " and at ".join(x for x in (near, far) if x)
                + "; the same for v."
            )
    return ""


def _negative_hint(g: np.ndarray, shape) -> str:
    """A weight below 0: say where it is (the first or the last row or column) and so which term went negative."""
    h, w = shape
    r, c = np.unravel_index(np.argmin(g), g.shape)
    where = []
    if c == 0 or r == 0:
        where.append(
            "at the first column or row (u = 0 or v = 0) the near term u + 1/2 (v + 1/2) went below 0"
        )
    if c == w - 1 or r == h - 1:
        where.append(
            "at the last column or row the far term went below 0 (a far border in the wrong place): the far borders are at u = W - 1/2 "
            "(W = shape[1], the columns) and v = H - 1/2 (H = shape[0], the rows); check that W and H are not "
            "swapped inside the terms"
        )
    if not where:
        where.append(
            "inside the image a distance went below 0; each term must be the distance to one border"
        )
    return f"a weight below 0 ({g.min():g} at row {r}, column {c}): " + "; ".join(where) + "."


def _feather_shape_hint(shape, got: tuple, expected: tuple) -> str:
    """The cause of a wrong result shape: a colour shape read from its end, or rows and columns swapped."""
    start = f"the weights should have the image's shape {expected} (rows, columns), got {got}"
    if len(shape) == 3 and got == tuple(shape[-2:]):
        return (
            f"{start}: the shape of a colour image is (h, w, 3) = {tuple(shape)}, so shape[-2:] is (w, 3), not "
            "(h, w): take h, w = shape[:2]."
        )
    if got == expected[::-1]:
        return f"{start}: rows and columns swapped; a shape is (h, w) = (rows, columns), so h, w = shape[:2]."
    if got[:2] == expected and len(got) == 3:  # np.zeros(shape), or a grid of the whole (h, w, 3)
        return (
            f"{start}: one weight per pixel, not one per colour channel, so drop the channel axis. Build an "
            "(h, w) array from h, w = shape[:2] (np.zeros(shape) keeps the channel axis, np.zeros(shape[:2]) "
            "does not)."
        )
    return start + "."


def _feather_flipped_far(shape) -> np.ndarray:
    """min(u + 1/2, u - (W - 1/2), ...): the far terms with their sign flipped (a slip: K12)."""
    h, w = shape[:2]
    u, v = np.arange(w, dtype=float), np.arange(h, dtype=float)[:, None]
    return np.minimum(np.minimum(u + 0.5, u - w + 0.5), np.minimum(v + 0.5, v - h + 0.5))


def _feather_swapped_far(shape) -> np.ndarray:
    """min(u + 1/2, H - 1/2 - u, v + 1/2, W - 1/2 - v): W and H swapped inside the far terms (a slip)."""
    h, w = shape[:2]
    u, v = np.arange(w, dtype=float), np.arange(h, dtype=float)[:, None]
    return np.minimum(np.minimum(u + 0.5, h - 0.5 - u), np.minimum(v + 0.5, w - 0.5 - v))


def _separable(shape) -> np.ndarray:
    """Brown & Lowe's w(x) w(y), each factor the distance to the nearer border scaled to 1 at the centre."""
    h, w = shape[:2]
    u, v = np.arange(w, dtype=float), np.arange(h, dtype=float)[:, None]
    du, dv = np.minimum(u + 0.5, w - 0.5 - u), np.minimum(v + 0.5, h - 0.5 - v)
    return (du / du.max()) * (dv / dv.max())


def _feather_offsets(shape, a: float, b: float) -> np.ndarray:
    """min(u + a, W - b - u, v + a, H - b - v): the feathering weights with the border put elsewhere (a slip)."""
    h, w = shape
    u, v = np.arange(w, dtype=float), np.arange(h, dtype=float)[:, None]
    return np.minimum(np.minimum(u + a, w - b - u), np.minimum(v + a, h - b - v))


def _per_channel(shape) -> np.ndarray:
    """The right weights repeated along a colour shape's channel axis (a slip: np.zeros(shape))."""
    weights = st.feather_weights(shape)
    return np.repeat(weights[..., None], shape[2], axis=2) if len(shape) == 3 else weights


def _feather_exception_hint(exc: Exception, args: tuple) -> str:
    """A broadcasting error here is a row and a column that are not: ``v`` must be an (h, 1) column."""
    if isinstance(exc, ValueError) and "broadcast" in str(exc):
        return (
            "a broadcasting slip: the distances along u (a row, np.arange(w), shape (w,)) and along v must meet in "
            "an (h, w) grid, so make v a column, np.arange(h)[:, None] (shape (h, 1)); two 1-D arrays of "
            "lengths h and w cannot be combined."
        )
    return shape_unpack_hint(exc, "shape")


register_exercise(
    Exercise(
        name="feather_weights",
        exception_hint=_feather_exception_hint,
        lesson="09",
        reference=st.feather_weights,
        ndarray_only=True,
        cases=_feather_cases,
        compare=same_array(atol=1e-9),
        diagnose=_feather_diagnosis,
        teaching=feather_weights,
        wrong_variants=(
            (lambda shape: st.feather_weights(shape) - 0.5, "half a pixel"),
            (lambda shape: _separable(shape), "separable weight w(x) w(y)"),
            (
                lambda shape: _feather_offsets(tuple(shape[:2]), 0.0, 0.0),
                "half a pixel at the near border",
            ),
            (lambda shape: _feather_offsets(tuple(shape[:2]), 1.5, 1.5), "counted pixels from 1"),
            (
                lambda shape: _feather_offsets(tuple(shape[:2]), 1.0, 1.0),
                "counted pixels from 1 (u = 1 ... W",
            ),
            (
                lambda shape: _feather_offsets(tuple(shape[:2]), -0.5, 0.5),
                "near border (you used u - 1/2",
            ),
            (
                lambda shape: _feather_offsets(tuple(shape[:2]), 0.5, -0.5),
                "far border (you used W + 1/2 - u",
            ),
            (
                lambda shape: _feather_offsets(tuple(shape[:2]), 0.5, 1.5),
                "far border (you used W - 3/2 - u",
            ),
            (lambda shape: st.feather_weights(shape) / st.feather_weights(shape).sum(), "sum to 1"),
            (_feather_swapped_far, "far border in the wrong place"),
            (_feather_flipped_far, "far terms' sign is flipped"),
            (
                lambda shape: st.feather_weights(tuple(shape[-2:])),
                "shape[-2:] is (w, 3)",
            ),
            (lambda shape: st.feather_weights(shape).astype(int), "integer dtype"),
            (_per_channel, "per colour channel"),
            (lambda shape: 2 * st.feather_weights(shape), "counts half-pixels"),
            (lambda shape: (2 * st.feather_weights(shape)).astype(int), "counts half-pixels"),
            (
                lambda shape: (st.feather_weights(shape) + 0.5).astype(int),
                "off by half a pixel: the border is at u = -1/2",
            ),
            (
                lambda shape: st.feather_weights(shape) / st.feather_weights(shape).max(),
                "normalised",
            ),
            (
                lambda shape: np.broadcast_to(
                    np.minimum(np.arange(shape[1]) + 0.5, shape[1] - 0.5 - np.arange(shape[1])),
                    tuple(shape),
                ).copy(),
                "vertical",
            ),
        ),
    )
)
