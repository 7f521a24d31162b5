"""Exercises for lesson 03: the digital sensor."""
from __future__ import annotations

import numpy as np

from .. import sensor
from ._core import Exercise, register_exercise, same_array, shape_problem


def _quantize_cases():
    rng = np.random.default_rng(3)
    return [
        (np.linspace(0, 1, 11), 2),
        (rng.uniform(0, 1, (4, 5)), 8),
        (np.array([0.0, 0.25, 0.5, 0.75, 1.0, 1.3, -0.2]), 3),
        (rng.uniform(0, 1, 20), 12),
    ]


def _quantize_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    img, bits = args
    g = np.asarray(got)
    levels = 2**bits - 1
    if np.array_equal(g, np.floor(np.clip(img, 0, 1) * levels)):
        return "you truncated (floor); round to the nearest level so the error is at most half a step"
    if np.array_equal(g, np.clip(np.rint(img * 2**bits), 0, 2**bits)) or g.max() > levels:
        return f"a {bits}-bit number runs from 0 to 2**bits - 1 = {levels}: scale by 2**bits - 1 and clip"
    if np.array_equal(g, np.rint(img * levels)):
        return "clip to [0, 2**bits - 1]: values outside [0, 1] saturate"
    if not np.issubdtype(g.dtype, np.integer):
        return "return integer digital numbers (uint8 for <= 8 bits, uint16 above)"
    return "DN = round(I * (2**bits - 1)), clipped to [0, 2**bits - 1]"


register_exercise(Exercise(
    name="quantize_image",
    lesson="03",
    reference=sensor.quantize,
    cases=_quantize_cases,
    compare=lambda got, exp: np.shape(got) == np.shape(exp) and np.issubdtype(np.asarray(got).dtype, np.integer)
    and np.array_equal(got, exp),
    diagnose=_quantize_diagnosis,
    wrong_variants=(
        (lambda img, bits: np.floor(np.clip(img, 0, 1) * (2**bits - 1)).astype(np.uint16), "round to the nearest"),
        (lambda img, bits: np.clip(np.rint(img * 2**bits), 0, 2**bits).astype(np.uint16), "2**bits - 1"),
        (lambda img, bits: np.rint(img * (2**bits - 1)).astype(np.int64), "clip"),
    ),
))


def _demosaic_cases():
    rng = np.random.default_rng(4)
    yy, xx = np.mgrid[0:8, 0:10].astype(float)
    smooth = np.stack([0.05 * xx, 0.04 * yy + 0.1, 0.5 - 0.02 * xx], axis=2)
    return [
        (sensor.mosaic(smooth, "RGGB"), "RGGB"),
        (sensor.mosaic(rng.uniform(size=(6, 6, 3)), "RGGB"), "RGGB"),
        (sensor.mosaic(rng.uniform(size=(6, 8, 3)), "GBRG"), "GBRG"),
    ]


def _demosaic_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return an (H, W, 3) RGB image."
    raw, pattern = args
    g = np.asarray(got, dtype=float)
    m = sensor.bayer_masks(raw.shape, pattern)
    if not np.allclose(g[m], np.asarray(expected)[m]):
        return ("the measured samples changed: keep each pixel's own colour as measured, and check which "
                "colour sits where in the pattern (RGGB: R at row 0, column 0)")
    inner = (slice(1, -1), slice(1, -1))
    if np.allclose(g[inner], np.asarray(expected)[inner]):
        return ("right inside, wrong at the border: average only the neighbours that exist "
                "(divide by the sum of the weights of available samples)")
    return "each missing value is the mean of the nearest samples of that colour (2 or 4 neighbours)"


def _zero_padded_demosaic(raw, pattern):
    from scipy.ndimage import convolve

    m = sensor.bayer_masks(raw.shape, pattern)
    kr = np.array([[1, 2, 1], [2, 4, 2], [1, 2, 1]]) / 4.0
    kg = np.array([[0, 1, 0], [1, 4, 1], [0, 1, 0]]) / 4.0
    out = np.empty(raw.shape + (3,))
    for c, k in zip(range(3), (kr, kg, kr)):
        out[..., c] = convolve(raw * m[..., c], k, mode="constant")
    return out


register_exercise(Exercise(
    name="demosaic_bilinear",
    lesson="03",
    reference=sensor.demosaic_bilinear,
    cases=_demosaic_cases,
    compare=same_array(atol=1e-9),
    diagnose=_demosaic_diagnosis,
    wrong_variants=(
        (_zero_padded_demosaic, "border"),
        (lambda raw, pattern: sensor.demosaic_bilinear(raw, "BGGR" if pattern == "RGGB" else "RGGB"), "measured samples"),
    ),
))
