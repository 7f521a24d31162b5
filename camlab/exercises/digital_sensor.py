"""Exercises for lesson 03: the digital sensor."""
from __future__ import annotations

import numpy as np

from .. import sensor
from ._core import Exercise, SameArray, Tolerance, register_exercise, shape_problem


def _quantize_cases():
    rng = np.random.default_rng(3)
    return [
        (np.linspace(0, 1, 11), 2),
        (rng.uniform(0, 1, (4, 5)), 8),
        (np.array([0.0, 0.25, 0.5, 0.75, 1.0, 1.3, -0.2]), 3),
        (rng.uniform(0, 1, 20), 12),
    ]


def _not_an_array(got) -> str | None:
    """The hint for an answer that is no numpy array (a list from .tolist() or a comprehension), else None."""
    if isinstance(got, np.ndarray):
        return None
    return (f"you returned a {type(got).__name__}; return a numpy array (np.array(...) or numpy operations "
            f"on the whole image, without .tolist())")


def _same_after_cast(got: np.ndarray, candidate: np.ndarray) -> bool:
    """``got`` equals ``candidate`` cast to got's dtype (so a wrapped-around uint8 still matches its cause)."""
    with np.errstate(invalid="ignore", over="ignore"):
        return np.array_equal(got, np.asarray(candidate).astype(got.dtype))


def _quantize_diagnosis(args, got, expected) -> str:
    problem = _not_an_array(got) or shape_problem(got, expected)
    if problem:
        return problem
    img, bits = args
    g = np.asarray(got)
    levels = 2**bits - 1
    wanted = np.asarray(expected).dtype
    if np.array_equal(g, expected):      # right numbers, wrong type
        if not np.issubdtype(g.dtype, np.integer):
            return (f"the values are right but the dtype is {g.dtype}: digital numbers are integers; "
                    f"end with .astype(np.uint8) for <= 8 bits, np.uint16 above")
        return (f"the values are right but the dtype is {g.dtype}; the prompt asks for {wanted} at {bits} bits "
                f"(np.uint8 up to 8 bits, np.uint16 above): end with .astype(np.{wanted})")
    if bits > 8 and g.dtype == np.uint8:
        return (f"{bits}-bit numbers reach {levels}, but uint8 stops at 255 and wraps around: "
                f"use np.uint16 above 8 bits")
    clipped = np.clip(img, 0, 1)
    if _same_after_cast(g, np.floor(clipped * levels)):
        return "you truncated (floor); round to the nearest level so the error is at most half a step"
    if _same_after_cast(g, np.ceil(clipped * levels)):
        return "you rounded up (ceil); round to the nearest level (np.rint) so the error is at most half a step"
    adc = np.floor(clipped * 2**bits)   # many real converters: 2**bits bins of width 1 / 2**bits
    if _same_after_cast(g, adc) or _same_after_cast(g, np.minimum(adc, levels)):
        return ("you used an ADC's floor(I * 2**bits); this lesson's DN = round(I * (2**bits - 1)) maps 0 and 1 "
                "exactly to 0 and 2**bits - 1 with at most half a step of error: scale by 2**bits - 1 and round")
    if any(_same_after_cast(g, np.clip(np.rint(img * 2**bits), 0, top)) for top in (levels, 2**bits)):
        return (f"you scaled by 2**bits = {2**bits}; white (I = 1) must land on the top code 2**bits - 1 = {levels}: "
                f"scale by 2**bits - 1")
    if _same_after_cast(g, np.rint(img * levels)):
        return "clip to [0, 2**bits - 1]: values outside [0, 1] saturate (the scaling by 2**bits - 1 is right)"
    if g.max() > levels:
        return f"a {bits}-bit number runs from 0 to 2**bits - 1 = {levels}: scale by 2**bits - 1 and clip"
    return "DN = round(I * (2**bits - 1)), clipped to [0, 2**bits - 1]"


def _right_quantize_numbers(img, bits):
    return np.clip(np.rint(img * (2**bits - 1)), 0, 2**bits - 1)


def quantize_image(image, bits):
    """Digital numbers DN = round(I (2**bits - 1)), clipped; uint8 up to 8 bits, uint16 above."""
    levels = 2**bits - 1
    dn = np.clip(np.round(image * levels), 0, levels)   # round to nearest, then saturate
    return dn.astype(np.uint8 if bits <= 8 else np.uint16)


register_exercise(Exercise(
    name="quantize_image",
    lesson="03",
    reference=sensor.quantize,
    cases=_quantize_cases,
    # the prompt fixes the type: a numpy array of uint8 up to 8 bits, uint16 above
    compare=lambda got, exp: isinstance(got, np.ndarray) and got.dtype == exp.dtype and np.array_equal(got, exp),
    diagnose=_quantize_diagnosis,
    wrong_variants=(
        (lambda img, bits: np.floor(np.clip(img, 0, 1) * (2**bits - 1)).astype(np.uint16), "round to the nearest"),
        (lambda img, bits: np.clip(np.rint(img * 2**bits), 0, 2**bits).astype(np.uint16), "2**bits"),
        (lambda img, bits: np.minimum(np.floor(np.clip(img, 0, 1) * 2**bits), 2**bits - 1).astype(np.uint16),
         "an ADC's floor"),
        (lambda img, bits: np.floor(np.clip(img, 0, 1) * 2**bits).astype(np.uint16), "an ADC's floor"),
        (lambda img, bits: np.rint(img * (2**bits - 1)).astype(np.int64), "dtype is int64"),
        (lambda img, bits: np.clip(np.rint(img * (2**bits - 1)), 0, 2**bits - 1), "dtype is float64"),
        (lambda img, bits: _right_quantize_numbers(img, bits).astype(np.uint8), "wraps around"),
        (lambda img, bits: _right_quantize_numbers(img, bits).astype(np.uint16), "the prompt asks for uint8"),
        (lambda img, bits: _right_quantize_numbers(img, bits).astype(np.uint16).tolist(), "you returned a list"),
        (lambda img, bits: np.clip(np.rint(img * 2**bits), 0, 2**bits - 1).astype(np.uint16), "you scaled by 2**bits"),
        (lambda img, bits: np.clip(np.ceil(img * (2**bits - 1)), 0, 2**bits - 1).astype(np.uint16), "ceil"),
        (lambda img, bits: np.rint(img * (2**bits - 1)).astype(np.uint8 if bits <= 8 else np.uint16), "saturate"),
    ),
    teaching=quantize_image,
))


def _demosaic_cases():
    """Odd and even sizes, all four patterns, and a uint8 mosaic as the lesson's own raw is."""
    rng = np.random.default_rng(4)
    yy, xx = np.mgrid[0:7, 0:10].astype(float)
    smooth = np.stack([0.05 * xx, 0.04 * yy + 0.1, 0.5 - 0.02 * xx], axis=2)
    return [
        (sensor.mosaic(smooth, "RGGB"), "RGGB"),
        (sensor.mosaic(rng.uniform(size=(6, 6, 3)), "RGGB"), "RGGB"),
        (sensor.mosaic(rng.uniform(size=(6, 8, 3)), "GBRG"), "GBRG"),
        (sensor.mosaic(rng.uniform(size=(5, 7, 3)), "BGGR"), "BGGR"),
        (sensor.mosaic(rng.uniform(size=(7, 6, 3)), "GRBG"), "GRBG"),
        (sensor.quantize(sensor.mosaic(rng.uniform(size=(7, 9, 3)), "RGGB")), "RGGB"),   # uint8, 0..255
    ]


def _demosaic_diagnosis(args, got, expected) -> str:
    problem = _not_an_array(got) or shape_problem(got, expected)
    if problem:
        return problem + ". Return an (H, W, 3) RGB image."
    raw, pattern = args
    g = np.asarray(got, dtype=float)
    e = np.asarray(expected)
    if np.allclose(g[..., ::-1], e):
        return ("red and blue are swapped: return the channels as R, G, B (not OpenCV's BGR order), and check "
                "which colour sits where in the pattern (RGGB: R at row 0, column 0)")
    if np.allclose(g * 255, e) or np.allclose(g, e * 255):
        return "the values are scaled by 255: keep the units of the mosaic (do not divide or multiply by 255)"
    m = sensor.bayer_masks(raw.shape, pattern)
    if not np.allclose(g[m], e[m]):
        return ("the measured samples changed: keep each pixel's own colour as measured, and check which "
                "colour sits where in the pattern (RGGB: R at row 0, column 0)")
    if np.issubdtype(raw.dtype, np.integer):
        return (f"this mosaic is {raw.dtype}, as a raw file's is: integer arithmetic wraps around (uint8 at 255) and "
                f"scipy's convolve returns the input's dtype, truncating the means; convert first: raw.astype(float)")
    inner = (slice(1, -1), slice(1, -1))
    if np.allclose(g[inner], e[inner]):
        return ("right inside, wrong at the border: average only the neighbours that exist "
                "(divide by the sum of the weights of available samples)")
    return "each missing value is the mean of the nearest samples of that colour (2 or 4 neighbours)"


def _zero_padded_demosaic(raw, pattern):
    from scipy.ndimage import convolve

    raw = np.asarray(raw, dtype=float)
    m = sensor.bayer_masks(raw.shape, pattern)
    kr = np.array([[1, 2, 1], [2, 4, 2], [1, 2, 1]]) / 4.0
    kg = np.array([[0, 1, 0], [1, 4, 1], [0, 1, 0]]) / 4.0
    out = np.empty(raw.shape + (3,))
    for c, k in zip(range(3), (kr, kg, kr)):
        out[..., c] = convolve(raw * m[..., c], k, mode="constant")
    return out


def _uncast_demosaic(raw, pattern):
    """Normalised convolution without converting the mosaic to float: uint8 stays uint8."""
    from scipy.ndimage import convolve

    m = sensor.bayer_masks(raw.shape, pattern)
    k = np.array([[1, 2, 1], [2, 4, 2], [1, 2, 1]]) / 4.0
    est = np.stack([convolve(raw * m[..., c], k, mode="constant") / convolve(m[..., c] * 1.0, k, mode="constant")
                    for c in range(3)], axis=2)
    return np.where(m, raw[..., None], est)


def demosaic_bilinear(raw, pattern):
    """Keep each measured sample; fill the rest with the weighted mean of available neighbours."""
    raw = np.asarray(raw, dtype=float)
    H, W = raw.shape
    masks = np.zeros((H, W, 3))                    # which pixel measured which colour
    for (dy, dx), colour in zip([(0, 0), (0, 1), (1, 0), (1, 1)], pattern):
        masks[dy::2, dx::2, "RGB".index(colour)] = 1
    # a missing site's same-colour neighbours are all equidistant (cross or diagonal), so these weights
    # give their plain mean; they matter only in that one kernel serves every colour and site
    weights = np.array([[1, 2, 1], [2, 4, 2], [1, 2, 1]]) / 4
    out = np.empty((H, W, 3))
    for c in range(3):
        m = masks[..., c]
        padded_values, padded_mask = np.pad(raw * m, 1), np.pad(m, 1)
        total, weight = np.zeros((H, W)), np.zeros((H, W))
        for dy in range(3):
            for dx in range(3):
                total += weights[dy, dx] * padded_values[dy:dy + H, dx:dx + W]
                weight += weights[dy, dx] * padded_mask[dy:dy + H, dx:dx + W]
        out[..., c] = np.where(m == 1, raw, total / weight)   # only existing neighbours count
    return out


register_exercise(Exercise(
    name="demosaic_bilinear",
    lesson="03",
    reference=sensor.demosaic_bilinear,
    cases=_demosaic_cases,
    compare=SameArray(Tolerance(1e-5, 1e-9)),
    diagnose=_demosaic_diagnosis,
    ndarray_only=True,
    wrong_variants=(
        (_zero_padded_demosaic, "border"),
        (lambda raw, pattern: sensor.demosaic_bilinear(raw, "GRBG" if pattern == "RGGB" else "RGGB"), "measured samples"),
        (lambda raw, pattern: sensor.demosaic_bilinear(raw, pattern)[..., ::-1], "not OpenCV's BGR order"),
        (lambda raw, pattern: sensor.demosaic_bilinear(raw, pattern) / 255, "scaled by 255"),
        (lambda raw, pattern: sensor.demosaic_bilinear(raw, pattern).tolist(), "you returned a list"),
        (_uncast_demosaic, "convert first: raw.astype"),
    ),
    teaching=demosaic_bilinear,
))
