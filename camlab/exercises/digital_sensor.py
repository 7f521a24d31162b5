"""Exercises for lesson 03: the digital sensor."""

from __future__ import annotations

import numpy as np

from .. import sensor
from ._answers import SameArray, Tolerance, shape_problem
from ._core import Exercise, register_exercise


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
    return (
        f"you returned a {type(got).__name__}; return a numpy array (np.array(...) or numpy operations "
        f"on the whole image, without .tolist())"
    )


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
    if np.array_equal(g, expected):  # right numbers, wrong type
        if not np.issubdtype(g.dtype, np.integer):
            return (
                f"the values are right but the dtype is {g.dtype}: digital numbers are integers; "
                f"end with .astype(np.uint8) for <= 8 bits, np.uint16 above"
            )
        return (
            f"the values are right but the dtype is {g.dtype}; the prompt asks for {wanted} at {bits} bits "
            f"(np.uint8 up to 8 bits, np.uint16 above): end with .astype(np.{wanted})"
        )
    if bits > 8 and g.dtype == np.uint8:
        return (
            f"{bits}-bit numbers reach {levels}, but uint8 stops at 255 and wraps around: "
            f"use np.uint16 above 8 bits"
        )
    clipped = np.clip(img, 0, 1)
    right = _right_quantize_numbers(img, bits)
    if np.issubdtype(g.dtype, np.floating) and _same_after_cast(g, right / levels):
        return (
            f"you returned fractions of full scale, DN / (2**bits - 1) (the dequantised values); return the "
            f"digital numbers themselves, whole numbers from 0 to 2**bits - 1 = {levels}"
        )
    with np.errstate(invalid="ignore", over="ignore"):
        wrapped = [np.rint(img * levels).astype(t).astype(g.dtype) for t in (g.dtype, np.int64)]
    if any(_same_after_cast(g, np.clip(w, 0, levels)) for w in wrapped) and not _same_after_cast(
        g, right
    ):
        return (
            "you cast to an unsigned type before clipping: a value below 0 (-0.2 x 7 rounds to -1) wraps around "
            "in uint8 to 255, so the clip sees a bright pixel; clip first (np.clip(..., 0, 2**bits - 1)), "
            "then cast"
        )
    with np.errstate(invalid="ignore", over="ignore"):
        top_only = np.minimum(np.rint(img * levels), levels)
    if (
        np.any(img < 0)
        and g.dtype.kind == "u"
        and _same_after_cast(g, top_only)
        and not _same_after_cast(g, right)
    ):
        return (
            "you clipped only the top: a value below 0 (-0.2 x 7 rounds to -1) wraps around in an unsigned type, "
            "to 255 in uint8, a bright pixel; clip both ends, np.clip(..., 0, 2**bits - 1), before the cast"
        )
    if any(
        _same_after_cast(g, c)
        for c in (
            np.clip(np.rint(img * 2**bits - 1), 0, levels),
            np.rint(img * 2**bits - 1),
            np.clip(np.rint(clipped * 2**bits - 1), 0, levels),
        )
    ):
        return (
            "I * 2**bits - 1 is (I * 2**bits) - 1: Python multiplies before it subtracts, so white lands on "
            "2**bits - 1 but every other code is off; write I * (2**bits - 1), with the brackets"
        )
    if any(
        _same_after_cast(g, np.clip(f(img * levels), 0, 1)) for f in (np.rint, np.floor)
    ) or _same_after_cast(g, np.rint(np.clip(img * levels, 0, 1))):
        return (
            f"you clipped to [0, 1] after scaling: by then the values are digital numbers from 0 to "
            f"{levels}; clip the fraction I to [0, 1] before scaling, or the digital numbers to "
            f"[0, 2**bits - 1] after"
        )
    for top in sorted({2 ** (bits - 1) - 1, 2 ** (bits - 1), 2**bits - 2} - {levels}):
        if top > 0 and any(
            _same_after_cast(g, c)
            for c in (
                np.clip(np.rint(img * top), 0, top),
                np.clip(np.rint(clipped * top), 0, levels),
            )
        ):
            causes = [
                cause
                for value, cause in (
                    (2 ** (bits - 1), "2**(bits - 1), half of the levels (the sign bit's worth)"),
                    (2 ** (bits - 1) - 1, "2**(bits - 1) - 1, half of the levels"),
                    (
                        2**bits - 2,
                        "2**bits - 2, one level too few (an "
                        "off-by-one: 2**bits - 1 is already the top code)",
                    ),
                )
                if value == top
            ]
            return (
                f"your top code is {top}, from {' or from '.join(causes)}: {bits} bits give 2**bits = {2**bits} "
                f"levels, 0 to 2**bits - 1 = {levels}; scale by 2**bits - 1"
            )
    if any(
        _same_after_cast(g, c)
        for c in (
            np.clip(np.rint(img * levels), 1, levels + 1),
            np.clip(np.rint(img * levels) + 1, 1, levels + 1),
        )
    ):
        return (
            f"your codes run from 1 to 2**bits = {levels + 1}: digital numbers count from 0, like Python's "
            f"indices, so black is 0 and white is 2**bits - 1 = {levels}; clip to [0, 2**bits - 1]"
        )
    if _same_after_cast(g, np.floor(clipped * levels)):
        return (
            "you truncated (floor); round to the nearest level so the error is at most half a step"
        )
    if _same_after_cast(g, np.ceil(clipped * levels)) or _same_after_cast(
        g, np.clip(np.rint(img * levels + 0.5), 0, levels)
    ):
        return (
            "you rounded up: np.ceil, or np.round(x + 0.5), which adds a half step that np.round does not need "
            "(the + 0.5 belongs to np.floor(x + 0.5), the other way to round to nearest); round once, "
            "np.round(x) or np.floor(x + 0.5), so the error is at most half a step"
        )
    adc = np.floor(clipped * 2**bits)  # many real converters: 2**bits bins of width 1 / 2**bits
    if _same_after_cast(g, adc) or _same_after_cast(g, np.minimum(adc, levels)):
        return (
            "you used an ADC's floor(I * 2**bits); this lesson's DN = round(I * (2**bits - 1)) maps 0 and 1 "
            "exactly to 0 and 2**bits - 1 with at most half a step of error: scale by 2**bits - 1 and round"
        )
    if any(
        _same_after_cast(g, np.clip(np.rint(img * 2**bits), 0, top)) for top in (levels, 2**bits)
    ):
        return (
            f"you scaled by 2**bits = {2**bits}; white (I = 1) must land on the top code 2**bits - 1 = {levels}: "
            f"scale by 2**bits - 1"
        )
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
    dn = np.clip(np.round(image * levels), 0, levels)  # round to nearest, then saturate
    return dn.astype(np.uint8 if bits <= 8 else np.uint16)


register_exercise(
    Exercise(
        name="quantize_image",
        lesson="03",
        reference=sensor.quantize,
        cases=_quantize_cases,
        # the prompt fixes the type: a numpy array of uint8 up to 8 bits, uint16 above
        compare=lambda got, exp: (
            isinstance(got, np.ndarray) and got.dtype == exp.dtype and np.array_equal(got, exp)
        ),
        diagnose=_quantize_diagnosis,
        wrong_variants=(
            (
                lambda img, bits: np.floor(np.clip(img, 0, 1) * (2**bits - 1)).astype(np.uint16),
                "round to the nearest",
            ),
            (
                lambda img, bits: np.clip(np.rint(img * 2**bits), 0, 2**bits).astype(np.uint16),
                "2**bits",
            ),
            (
                lambda img, bits: np.minimum(
                    np.floor(np.clip(img, 0, 1) * 2**bits), 2**bits - 1
                ).astype(np.uint16),
                "an ADC's floor",
            ),
            (
                lambda img, bits: np.floor(np.clip(img, 0, 1) * 2**bits).astype(np.uint16),
                "an ADC's floor",
            ),
            (lambda img, bits: np.rint(img * (2**bits - 1)).astype(np.int64), "dtype is int64"),
            (
                lambda img, bits: np.clip(np.rint(img * (2**bits - 1)), 0, 2**bits - 1),
                "dtype is float64",
            ),
            (lambda img, bits: _right_quantize_numbers(img, bits).astype(np.uint8), "wraps around"),
            (
                lambda img, bits: _right_quantize_numbers(img, bits).astype(np.uint16),
                "the prompt asks for uint8",
            ),
            (
                lambda img, bits: _right_quantize_numbers(img, bits).astype(np.uint16).tolist(),
                "you returned a list",
            ),
            (
                lambda img, bits: np.clip(np.rint(img * 2**bits), 0, 2**bits - 1).astype(np.uint16),
                "you scaled by 2**bits",
            ),
            (
                lambda img, bits: np.clip(np.ceil(img * (2**bits - 1)), 0, 2**bits - 1).astype(
                    np.uint16
                ),
                "ceil",
            ),
            (
                lambda img, bits: np.clip(
                    np.round(img * (2**bits - 1) + 0.5), 0, 2**bits - 1
                ).astype(np.uint8 if bits <= 8 else np.uint16),
                "adds a half step",
            ),
            (
                lambda img, bits: np.clip(np.rint(img * (2**bits - 2)), 0, 2**bits - 2).astype(
                    np.uint8 if bits <= 8 else np.uint16
                ),
                "2**bits - 2, one level too few",
            ),
            (
                lambda img, bits: np.rint(img * (2**bits - 1)).astype(
                    np.uint8 if bits <= 8 else np.uint16
                ),
                "saturate",
            ),
            (
                lambda img, bits: _right_quantize_numbers(img, bits) / (2**bits - 1),
                "fractions of full scale",
            ),
            (
                lambda img, bits: np.clip(
                    np.rint(img * (2**bits - 1)).astype(np.uint8 if bits <= 8 else np.uint16),
                    0,
                    2**bits - 1,
                ),
                "cast to an unsigned type before clipping",
            ),
            (
                lambda img, bits: np.clip(np.rint(img * (2**bits - 1)), 0, 1).astype(
                    np.uint8 if bits <= 8 else np.uint16
                ),
                "after scaling: by then",
            ),
            (
                lambda img, bits: np.clip(
                    np.rint(img * (2 ** (bits - 1) - 1)), 0, 2 ** (bits - 1) - 1
                ).astype(np.uint8 if bits <= 8 else np.uint16),
                "top code is",
            ),
            (
                lambda img, bits: np.clip(
                    np.rint(img * 2 ** (bits - 1)), 0, 2 ** (bits - 1)
                ).astype(np.uint8 if bits <= 8 else np.uint16),
                "top code is",
            ),
            (
                lambda img, bits: np.clip(np.rint(img * 2**bits - 1), 0, 2**bits - 1).astype(
                    np.uint8 if bits <= 8 else np.uint16
                ),
                "multiplies before it subtracts",
            ),
            (
                lambda img, bits: np.clip(np.rint(img * (2**bits - 1)), 1, 2**bits).astype(
                    np.uint8 if bits <= 8 else np.uint16
                ),
                "count from 0",
            ),
            (
                lambda img, bits: np.minimum(np.rint(img * (2**bits - 1)), 2**bits - 1).astype(
                    np.uint8 if bits <= 8 else np.uint16
                ),
                "clipped only the top",
            ),
        ),
        teaching=quantize_image,
    )
)


def _demosaic_cases():
    """Random colours first (every interpolation direction matters), then odd sizes, all four patterns, a smooth
    ramp, and a uint8 mosaic as the lesson's own raw is."""
    rng = np.random.default_rng(4)
    yy, xx = np.mgrid[0:7, 0:10].astype(float)
    smooth = np.stack([0.05 * xx, 0.04 * yy + 0.1, 0.5 - 0.02 * xx], axis=2)
    return [
        (sensor.mosaic(rng.uniform(size=(6, 6, 3)), "RGGB"), "RGGB"),
        (sensor.mosaic(rng.uniform(size=(6, 8, 3)), "GBRG"), "GBRG"),
        (sensor.mosaic(rng.uniform(size=(5, 7, 3)), "BGGR"), "BGGR"),
        (sensor.mosaic(rng.uniform(size=(7, 6, 3)), "GRBG"), "GRBG"),
        (sensor.mosaic(smooth, "RGGB"), "RGGB"),
        (
            sensor.quantize(sensor.mosaic(rng.uniform(size=(7, 9, 3)), "RGGB")),
            "RGGB",
        ),  # uint8, 0..255
    ]


def _tile_hint(shape) -> str:
    """Why np.tile masks fail on a mosaic of ``shape`` with an odd side."""
    H, W = shape
    odd = " and ".join(what for n, what in ((H, "rows"), (W, "columns")) if n % 2)
    return (
        f"this mosaic is {H} x {W} pixels, an odd number of {odd}: a mask built with np.tile(block, (H // 2, "
        f"W // 2)) comes out {H // 2 * 2} x {W // 2 * 2}, short of the image (a sensor crop may end mid-block). "
        f"Tile ((H + 1) // 2, (W + 1) // 2) times and crop [:H, :W], or build each mask by slicing: "
        f"m = np.zeros((H, W)); m[0::2, 0::2] = 1"
    )


def _demosaic_exception_hint(exc, args) -> str:
    raw = np.asarray(args[0])
    if (
        raw.ndim == 2
        and (raw.shape[0] % 2 or raw.shape[1] % 2)
        and isinstance(exc, (ValueError, IndexError))
        and ("broadcast" in str(exc) or "boolean index" in str(exc) or "shape" in str(exc))
    ):
        return _tile_hint(raw.shape)
    return ""


def _line_mean(values, mask, axis: int) -> np.ndarray:
    """Mean of the available same-colour neighbours on one line (axis 1: left and right; 0: above and below)."""
    total, count = np.zeros(values.shape), np.zeros(values.shape)
    for shift in (-1, 1):
        v, m = np.zeros(values.shape), np.zeros(values.shape)
        src = [slice(None)] * 2
        dst = [slice(None)] * 2
        src[axis], dst[axis] = (
            (slice(1, None), slice(None, -1)) if shift > 0 else (slice(None, -1), slice(1, None))
        )
        v[tuple(dst)], m[tuple(dst)] = (values * mask)[tuple(src)], mask[tuple(src)]
        total, count = total + v, count + m
    with np.errstate(invalid="ignore", divide="ignore"):
        return total / count


def _site_problems(raw, pattern, g, e) -> list[str]:
    """What is wrong where, inside the 1-pixel border: green at red/blue sites, red/blue at each other's and at green."""
    m = sensor.bayer_masks(raw.shape, pattern)
    inner = np.zeros(raw.shape, bool)
    inner[1:-1, 1:-1] = True
    bad = ~np.isclose(g, e, rtol=1e-5, atol=1e-9)
    problems = []
    if np.any(bad[..., 1] & ~m[..., 1] & inner):
        problems.append(
            "green at a red or blue site is the mean of its 4 green neighbours (left, right, above, below)"
        )
    if np.any((bad[..., 0] & m[..., 2] | bad[..., 2] & m[..., 0]) & inner):
        problems.append(
            "red at a blue site (and blue at a red one) is the mean of its 4 diagonal neighbours"
        )
    if np.any((bad[..., 0] | bad[..., 2]) & m[..., 1] & inner):
        problems.append(
            "red or blue at a green site is the mean of its 2 nearest samples of that colour: left and "
            "right, or above and below, whichever line holds that colour"
        )
    return problems


def _nan_hint(raw, pattern, got) -> str | None:
    """Where 0 / 0 struck: red at blue sites (or blue at red ones) means a kernel that misses the diagonals."""
    g = np.asarray(got, dtype=float)
    if g.shape != np.shape(raw) + (3,) or np.isfinite(g).all():
        return None
    m = sensor.bayer_masks(np.shape(raw), pattern)
    bad = ~np.isfinite(g)
    if np.any(bad[..., 0] & m[..., 2]) or np.any(bad[..., 2] & m[..., 0]):
        return (
            "NaN at red's value at blue sites (or blue's at red ones): their 4 cross neighbours (left, right, "
            "above, below) are all green, so a cross kernel such as green's [[0, 1, 0], [1, 4, 1], [0, 1, 0]] "
            "finds no red there, k * m is 0 and 0 / 0 is NaN. Red and blue need the 3 x 3 tent kernel "
            "[[1, 2, 1], [2, 4, 2], [1, 2, 1]] / 4, whose corners reach the 4 diagonal neighbours"
        )
    return (
        "NaN where your kernel reaches no sample of that colour (0 / 0): a missing value needs at least one "
        "same-colour neighbour within the kernel; the 3 x 3 tent kernel reaches one for every colour and site"
    )


def _demosaic_diagnosis(args, got, expected) -> str:
    raw, pattern = args
    nan = isinstance(got, np.ndarray) and _nan_hint(raw, pattern, got)
    if nan:
        return nan
    problem = _not_an_array(got) or shape_problem(got, expected)
    if problem:
        H, W = np.shape(raw)
        if (H % 2 or W % 2) and np.shape(got)[:2] == (H // 2 * 2, W // 2 * 2):
            return _tile_hint((H, W))
        return problem + ". Return an (H, W, 3) RGB image."
    g = np.asarray(got, dtype=float)
    e = np.asarray(expected)
    column_major = pattern[0] + pattern[2] + pattern[1] + pattern[3]
    if column_major != pattern and np.allclose(g, sensor.demosaic_bilinear(raw, column_major)):
        return (
            f"you read the pattern column by column, as {column_major}: its letters go row by row, top-left, "
            f"top-right, bottom-left, bottom-right, so {pattern} has {pattern[0]} {pattern[1]} on row 0 and "
            f"{pattern[2]} {pattern[3]} on row 1 (for {pattern} that swaps red and blue)"
        )
    if np.allclose(g[..., ::-1], e):
        return (
            "red and blue are swapped: return the channels as R, G, B (not OpenCV's BGR order), and check "
            "which colour sits where in the pattern (RGGB: R at row 0, column 0)"
        )
    if (
        g.shape[0] == g.shape[1]
        and np.allclose(g, e.transpose(1, 0, 2))
        and not np.allclose(e, e.transpose(1, 0, 2))
    ):
        return (
            "your image is transposed: rows and columns swapped (a .T, or an index [u, v] where the image is "
            "img[v, u]: row v first, then column u)"
        )
    shifted = {
        "one column": pattern[1] + pattern[0] + pattern[3] + pattern[2],
        "one row": pattern[2] + pattern[3] + pattern[0] + pattern[1],
    }
    for how, wrong in shifted.items():
        if wrong != pattern and np.allclose(g, sensor.demosaic_bilinear(raw, wrong)):
            return (
                f"your masks sit {how} off, as if the pattern were {wrong}: started at 1 (m[1::2, ...]), as in "
                f"1-based MATLAB? Python counts from 0: {pattern}'s {pattern[0]} is at row 0, column 0, "
                f"m[0::2, 0::2]"
            )
    if np.allclose(g * 255, e) or np.allclose(g, e * 255):
        return "the values are scaled by 255: keep the units of the mosaic (do not divide or multiply by 255)"
    whole = "the mean of two samples falls between codes (100 and 101 give 100.5)"
    if np.issubdtype(np.asarray(got).dtype, np.integer):
        return (
            f"you returned integers (dtype {np.asarray(got).dtype}): {whole}, so casting back to the mosaic's "
            f"dtype loses it; return the float image (leave out .astype(np.uint8))"
        )
    if any(np.allclose(g, rounding(e)) for rounding in (np.rint, np.floor)) and not np.allclose(
        np.rint(e), e
    ):
        return f"you rounded the interpolated values to whole numbers: {whole}; return them unrounded, as floats"
    m = sensor.bayer_masks(raw.shape, pattern)
    if not np.allclose(g[m], e[m]):
        return (
            "the measured samples changed: keep each pixel's own colour as measured, and check which "
            "colour sits where in the pattern (RGGB: R at row 0, column 0)"
        )
    if np.issubdtype(raw.dtype, np.integer):
        return (
            f"this mosaic is {raw.dtype}, as a raw file's is: sums of its values wrap around (uint8 stops at 255) "
            f"and scipy's convolve keeps the input's dtype, truncating the means; convert first: raw.astype(float)"
        )
    r = np.asarray(raw, dtype=float)
    inner = (slice(1, -1), slice(1, -1))
    others = ~m[..., 1]
    for axis, line, missing in (
        (1, "on its left and right", "above and below"),
        (0, "above and below", "on the left and right"),
    ):
        one_line = np.where(m[..., 1], r, _line_mean(r, m[..., 1], axis))
        if np.allclose(g[..., 1][inner][others[inner]], one_line[inner][others[inner]]):
            return (
                f"green at a red or blue site averages only the green neighbours {line}; it has 4: add the ones "
                f"{missing} (green is sampled on a checkerboard, so every red or blue site has green on all 4 sides)"
            )
    inner_sites = others[inner]
    if np.allclose(g[..., 1][inner][inner_sites], 2 * e[..., 1][inner][inner_sites]):
        return (
            "green at red and blue sites is twice the mean: there the tent kernel's 4 cross weights are 1/2 each and "
            "sum to 2; divide by the weights actually used (k * m), or use green's cross kernel "
            "[[0, 1, 0], [1, 4, 1], [0, 1, 0]] / 4, whose 4 weights sum to 1"
        )
    problems = _site_problems(raw, pattern, g, e)
    if problems:
        return "; ".join(problems)
    # a 3 x 3 kernel reaches one pixel out, where 'reflect' and 'nearest' both repeat the edge pixel
    for mode, what in (
        (
            "reflect",
            "mode='reflect', scipy.ndimage.convolve's default (or mode='nearest', the same "
            "one pixel out)",
        ),
        ("mirror", "mode='mirror' (cv2.filter2D's default border, BORDER_REFLECT_101)"),
        ("wrap", "mode='wrap'"),
    ):
        if np.allclose(g, _padded_demosaic(raw, pattern, mode)):
            return (
                f"right inside, wrong at the border: with {what} the convolution invents samples beyond the "
                f"frame, mirrored or copied from inside it, and both k * (m r) and k * m count them (and a "
                f"mirrored copy of a Bayer mosaic does not even keep the pattern); use mode='constant' (zeros "
                f"outside; cv2.BORDER_CONSTANT) for both, so the ratio averages only the samples that exist"
            )
    return (
        "right inside, wrong at the border: average only the neighbours that exist "
        "(divide by the sum of the weights of available samples)"
    )


def _padded_demosaic(raw, pattern, mode):
    """Normalised convolution with scipy's border ``mode``: 'constant' is right, the others count invented samples."""
    from scipy.ndimage import convolve

    raw = np.asarray(raw, dtype=float)
    m = sensor.bayer_masks(raw.shape, pattern).astype(float)
    k = np.array([[1, 2, 1], [2, 4, 2], [1, 2, 1]]) / 4.0
    est = np.stack(
        [
            convolve(raw * m[..., c], k, mode=mode) / convolve(m[..., c], k, mode=mode)
            for c in range(3)
        ],
        axis=2,
    )
    return np.where(m == 1, raw[..., None], est)


def _reflect_border_demosaic(raw, pattern):
    """scipy.ndimage.convolve with its default border, mode='reflect': mirrored samples beyond the frame count."""
    return _padded_demosaic(raw, pattern, "reflect")


def _zero_padded_demosaic(raw, pattern):
    from scipy.ndimage import convolve

    raw = np.asarray(raw, dtype=float)
    m = sensor.bayer_masks(raw.shape, pattern)
    kr = np.array([[1, 2, 1], [2, 4, 2], [1, 2, 1]]) / 4.0
    kg = np.array([[0, 1, 0], [1, 4, 1], [0, 1, 0]]) / 4.0
    out = np.empty(raw.shape + (3,))
    for c, k in zip(range(3), (kr, kg, kr), strict=True):
        out[..., c] = convolve(raw * m[..., c], k, mode="constant")
    return out


def _unnormalised_tent_demosaic(raw, pattern):
    """The tent kernel for every colour as a plain convolution: green at red and blue sites comes out doubled."""
    from scipy.ndimage import convolve

    raw = np.asarray(raw, dtype=float)
    m = sensor.bayer_masks(raw.shape, pattern)
    k = np.array([[1, 2, 1], [2, 4, 2], [1, 2, 1]]) / 4.0
    est = np.stack([convolve(raw * m[..., c], k, mode="constant") for c in range(3)], axis=2)
    return np.where(m, raw[..., None], est)


def _uncast_demosaic(raw, pattern):
    """Normalised convolution without converting the mosaic to float: uint8 stays uint8."""
    from scipy.ndimage import convolve

    m = sensor.bayer_masks(raw.shape, pattern)
    k = np.array([[1, 2, 1], [2, 4, 2], [1, 2, 1]]) / 4.0
    est = np.stack(
        [
            convolve(raw * m[..., c], k, mode="constant")
            / convolve(m[..., c] * 1.0, k, mode="constant")
            for c in range(3)
        ],
        axis=2,
    )
    return np.where(m, raw[..., None], est)


def _tiled_masks_demosaic(raw, pattern):
    """Masks from np.tile(block, (H // 2, W // 2)): one row or column short on an odd-sized mosaic."""
    raw = np.asarray(raw, dtype=float)
    H, W = raw.shape
    blocks = [np.array([[pattern[0], pattern[1]], [pattern[2], pattern[3]]]) == c for c in "RGB"]
    masks = np.stack([np.tile(b, (H // 2, W // 2)) for b in blocks], axis=2)
    return np.where(
        masks, raw[..., None], sensor.demosaic_bilinear(raw, pattern)
    )  # crashes: (H, W, 1) vs masks


def _one_line_green_demosaic(raw, pattern, axis=1):
    """Green at red and blue sites from its left and right neighbours only (axis 0: above and below)."""
    out = sensor.demosaic_bilinear(raw, pattern)
    r = np.asarray(raw, dtype=float)
    green = sensor.bayer_masks(r.shape, pattern)[..., 1]
    out[..., 1] = np.where(green, r, _line_mean(r, green, axis))
    return out


def _diagonal_only_demosaic(raw, pattern):
    """Red and blue at green sites from the 4 diagonals (there are none: NaN-free, but the wrong neighbours)."""
    out = sensor.demosaic_bilinear(raw, pattern)
    m = sensor.bayer_masks(np.shape(raw), pattern)
    for c in (0, 2):
        out[..., c] = np.where(
            m[..., 1], out[..., 1], out[..., c]
        )  # a common shortcut: copy green there
    return out


def _cross_kernel_demosaic(raw, pattern):
    """Green's cross kernel used for red and blue too: 0 / 0 (NaN) at red's blue sites and blue's red ones."""
    from scipy.ndimage import convolve

    raw = np.asarray(raw, dtype=float)
    m = sensor.bayer_masks(raw.shape, pattern).astype(float)
    k = np.array([[0, 1, 0], [1, 4, 1], [0, 1, 0]]) / 4.0
    with np.errstate(invalid="ignore", divide="ignore"):
        est = np.stack(
            [
                convolve(raw * m[..., c], k, mode="constant")
                / convolve(m[..., c], k, mode="constant")
                for c in range(3)
            ],
            axis=2,
        )
    return np.where(m == 1, raw[..., None], est)


def demosaic_bilinear(raw, pattern):
    """Section 4's formula, c = k * (m r) / (k * m) at the missing sites; measured samples kept."""
    raw = np.asarray(raw, dtype=float)  # float: uint8 sums would wrap around
    H, W = raw.shape
    m = np.zeros((H, W, 3))  # m[..., c] = 1 where the pixel measured colour c
    for (dy, dx), colour in zip([(0, 0), (0, 1), (1, 0), (1, 1)], pattern, strict=True):
        m[dy::2, dx::2, "RGB".index(colour)] = 1
    k = np.outer([1, 2, 1], [1, 2, 1]) / 4  # the tent kernel

    def conv(a):  # k * a, with zeros beyond the border (k is symmetric)
        p = np.pad(a, ((1, 1), (1, 1), (0, 0)))
        return sum(k[i, j] * p[i : i + H, j : j + W] for i in range(3) for j in range(3))

    return np.where(m == 1, raw[..., None], conv(m * raw[..., None]) / conv(m))


register_exercise(
    Exercise(
        name="demosaic_bilinear",
        lesson="03",
        reference=sensor.demosaic_bilinear,
        cases=_demosaic_cases,
        compare=SameArray(Tolerance(1e-5, 1e-9)),
        diagnose=_demosaic_diagnosis,
        exception_hint=_demosaic_exception_hint,
        ndarray_only=True,
        wrong_variants=(
            (_zero_padded_demosaic, "border"),
            (
                lambda raw, pattern: sensor.demosaic_bilinear(
                    raw, "GRBG" if pattern == "RGGB" else "RGGB"
                ),
                "off, as if the pattern were",
            ),
            (
                lambda raw, pattern: sensor.demosaic_bilinear(raw, pattern)[..., ::-1],
                "not OpenCV's BGR order",
            ),
            (
                lambda raw, pattern: sensor.demosaic_bilinear(
                    raw, pattern[0] + pattern[2] + pattern[1] + pattern[3]
                ),
                "column by column",
            ),
            (lambda raw, pattern: sensor.demosaic_bilinear(raw, pattern) / 255, "scaled by 255"),
            (
                lambda raw, pattern: sensor.demosaic_bilinear(raw, pattern).tolist(),
                "you returned a list",
            ),
            (_uncast_demosaic, "convert first: raw.astype"),
            (_tiled_masks_demosaic, "a mask built with np.tile"),
            (_one_line_green_demosaic, "only the green neighbours on its left and right"),
            (
                lambda raw, pattern: _one_line_green_demosaic(raw, pattern, axis=0),
                "only the green neighbours above",
            ),
            (lambda raw, pattern: np.rint(sensor.demosaic_bilinear(raw, pattern)), "you rounded"),
            (
                lambda raw, pattern: sensor.demosaic_bilinear(raw, pattern).astype(
                    np.asarray(raw).dtype
                ),
                "you returned integers",
            ),
            (_diagonal_only_demosaic, "red or blue at a green site"),
            (_cross_kernel_demosaic, "are all green"),
            (_unnormalised_tent_demosaic, "twice the mean"),
            (_reflect_border_demosaic, "mode='reflect', scipy.ndimage.convolve's default"),
            (
                lambda raw, pattern: sensor.demosaic_bilinear(
                    raw, pattern[1] + pattern[0] + pattern[3] + pattern[2]
                ),
                "one column off",
            ),
            (
                lambda raw, pattern: (
                    sensor.demosaic_bilinear(
                        np.asarray(raw).T, pattern[0] + pattern[2] + pattern[1] + pattern[3]
                    )
                    if np.shape(raw)[0] == np.shape(raw)[1]
                    else sensor.demosaic_bilinear(raw, pattern)[::-1]
                ),
                "transposed",
            ),
            (lambda raw, pattern: _padded_demosaic(raw, pattern, "mirror"), "BORDER_REFLECT_101"),
            (lambda raw, pattern: _padded_demosaic(raw, pattern, "nearest"), "or mode='nearest'"),
        ),
        teaching=demosaic_bilinear,
    )
)


# -- intrinsics_from_datasheet -----------------------------------------------------------------


def _datasheet_cases():
    """A phone, a full-frame camera, a sensor with non-square pixels (10 x 9.375 µm), odd pixel counts."""
    return [
        (4.25, (5.6, 4.2), (4032, 3024)),
        (50.0, (36.0, 24.0), (6000, 4000)),
        (8.0, (6.4, 4.8), (640, 512)),
        (3.6, (4.8, 3.6), (801, 601)),
    ]


def _datasheet_reference(f_mm, sensor_mm, size):
    """camlab.sensor.intrinsics_from_sensor(f, pitch, size), in metres, with pitch = sensor size / pixel count."""
    W, H = size
    return sensor.intrinsics_from_sensor(
        f_mm * 1e-3, (sensor_mm[0] * 1e-3 / W, sensor_mm[1] * 1e-3 / H), size
    )


def _datasheet_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem + " (K is 3 x 3)"
    f_mm, (w_mm, h_mm), (W, H) = args
    g, e = np.asarray(got, dtype=float), np.asarray(expected)
    fx, fy, cx, cy = e[0, 0], e[1, 1], e[0, 2], e[1, 2]

    def near(a, b):
        return np.isclose(a, b, rtol=1e-6, atol=1e-9)

    if np.issubdtype(np.asarray(got).dtype, np.integer):
        named = {"f_x": fx, "f_y": fy, "c_x = (W - 1) / 2": cx, "c_y = (H - 1) / 2": cy}
        cut = [
            f"{what} = {value:.6g}"
            for what, value in named.items()
            if not np.isclose(value, np.round(value))
        ]
        lost = (
            (
                f"it cannot hold {' or '.join(cut)}, so {'they were' if len(cut) > 1 else 'it was'} cut to "
                f"{'whole numbers' if len(cut) > 1 else 'a whole number'}"
            )
            if cut
            else "it holds whole numbers only"
        )
        return (
            f"K is an integer array (dtype {np.asarray(got).dtype}): {lost}. Build K from floats "
            f"(np.array([[...]], dtype=float), or write 0.0 and 1.0) and leave out .astype(int)"
        )

    if np.allclose(g, e.T):
        return (
            "K is transposed: the principal point goes in the last column, K[0, 2] = c_x and K[1, 2] = c_y, "
            "and the bottom row is (0, 0, 1)"
        )
    if not near(g[2], [0, 0, 1]).all():
        return "the bottom row of K is (0, 0, 1): it keeps the homogeneous coordinate, K @ (x, y, 1) = (u, v, 1)"
    if near(g[0, 0], f_mm * H / w_mm) and near(g[1, 1], f_mm * W / h_mm) and near(g[0, 2], cy):
        return (
            "you unpacked size as H, W = size: size is (width, height), as in OpenCV, so W, H = size; with the "
            "two swapped, f_x, f_y, c_x and c_y all come out wrong (an array's shape is (H, W), a size is not)"
        )
    if (
        near(g[0, 0], f_mm * W / h_mm)
        and near(g[1, 1], f_mm * H / w_mm)
        and not near(fx, f_mm * W / h_mm)
    ):
        return (
            "sensor_mm is (width, height), like size: s_x = sensor_mm[0] / W = width / W, "
            "s_y = sensor_mm[1] / H; you divided the height by W and the width by H"
        )
    if near(g[1, 1], -fy) and not near(g[0, 0], -fx):
        return (
            "f_x and f_y are positive here: the course's image plane has y down, like v down the image, so "
            "f_y = f / s_y needs no minus sign (a y-up convention flips it; see docs/conventions.md)"
        )
    if near(g[0, 0], -fx) or near(g[1, 1], -fy):
        return (
            "f_x = f / s_x is positive: a focal length and a pitch are both positive lengths, so there is no "
            "minus sign in K (the course's x points right on the image plane, like u; docs/conventions.md)"
        )
    if near(g[0, 2], (W + 1) / 2) or near(g[1, 2], (H + 1) / 2):
        return (
            "(W + 1) / 2 is the centre when pixels are numbered from 1 (MATLAB's convention); numpy and camlab "
            "number them from 0, so u runs from 0 to W - 1 and the centre is (W - 1) / 2"
        )
    if (W % 2 == 0 and near(g[0, 2], (W - 1) // 2)) or (H % 2 == 0 and near(g[1, 2], (H - 1) // 2)):
        return (
            f"c_x = {(W - 1) // 2} for W = {W} is the centre {(W - 1) / 2} cut short by half a pixel: integer "
            f"division, (W - 1) // 2, or int() drops the .5, and W / 2 - 1 (or (W - 1) / 2 - 0.5) subtracts a whole "
            f"pixel where the centre needs half of one; use (W - 1) / 2 = W / 2 - 0.5 (the centre of an even "
            f"number of pixels lies between two of them)"
        )
    if (W % 2 and near(g[0, 2], W // 2 - 0.5)) or (H % 2 and near(g[1, 2], H // 2 - 0.5)):
        return (
            f"W // 2 - 0.5 is the centre only for an even W: for W = {W} it gives {W // 2 - 0.5}, half a pixel "
            f"short of {(W - 1) / 2} (so does W / 2 - 1, which takes a whole pixel off the half-way point "
            f"W / 2 instead of half of one); (W - 1) / 2 holds for both"
        )
    if near(g[0, 2], cy) and near(g[1, 2], cx) and not near(cx, cy):
        return (
            "c_x and c_y are swapped: c_x = (W - 1) / 2 comes from the width W = size[0], c_y = (H - 1) / 2 from "
            "the height H = size[1] (sizes are (width, height), as in OpenCV; an array's shape is (H, W))"
        )
    if near(g[0, 2], W / 2) or near(g[1, 2], H / 2):
        return (
            "half a pixel off: with pixel centres at integers, u runs from 0 to W - 1, so the centre is "
            "(W - 1) / 2, not W / 2 (that is the centre in a pixel-corner convention), and not (W - 1) / 2 "
            "rounded to a whole pixel: keep the .5, the centre of an even number of pixels lies between two"
        )
    if near(g[0, 2], cy) and not near(cx, cy):
        return (
            f"c_x comes from the width: (W - 1) / 2 with W = size[0] = {W}; you used the height H = {H} "
            f"(size is (width, height), as in OpenCV)"
        )
    if near(g[1, 2], cx) and not near(cx, cy):
        return (
            f"c_y comes from the height: (H - 1) / 2 with H = size[1] = {H}; you used the width W = {W} "
            f"(size is (width, height), as in OpenCV)"
        )
    if near(g[0, 2], W - 1) or near(g[0, 2], W) or near(g[1, 2], H - 1):
        return "the principal point is the image centre, (W - 1) / 2 and (H - 1) / 2, not the image size"
    if near(g[0, 0], f_mm) or near(g[1, 1], f_mm):
        return (
            "f_x is in pixels, not millimetres: divide the focal length by the pixel pitch, f_x = f / s_x with "
            "s_x = sensor width / W (both in mm, so the units cancel)"
        )
    for factor, unit in (
        (1e3, "1000 times too large"),
        (1e-3, "1000 times too small"),
        (1e6, "a million times too large"),
        (1e-6, "a million times too small"),
    ):
        x_off, y_off = near(g[0, 0], fx * factor), near(g[1, 1], fy * factor)
        if x_off or y_off:
            which = "f_x and f_y are" if x_off and y_off else "f_x is" if x_off else "f_y is"
            return (
                f"{which} {unit}: a unit slip between mm, µm and m; keep f and the pitch in the same unit "
                f"(mm: s_x = sensor width / W), so f / s_x is in pixels"
            )
    for factor, unit in ((0.1, "10 times too small"), (10, "10 times too large")):
        if near(g[0, 0], fx * factor) and near(g[1, 1], fy * factor):
            return (
                f"f_x and f_y are {unit}: a centimetre slip? f_mm = {f_mm:g} is already in millimetres, like "
                f"sensor_mm; f / s_x with both in mm is in pixels"
            )
    diagonal = (
        f_mm * np.hypot(W, H) / np.hypot(w_mm, h_mm)
    )  # f over the pitch along the sensor's diagonal
    if near(g[0, 0], diagonal) and near(g[1, 1], diagonal) and not near(fx, fy):
        return (
            f"you took the pitch along the diagonal, sqrt(w**2 + h**2) / sqrt(W**2 + H**2); that is each axis's "
            f"pitch only for square pixels, and here s_x = {w_mm / W * 1e3:.4g} µm, s_y = {h_mm / H * 1e3:.4g} µm: "
            f"s_x = width / W and s_y = height / H, each from its own axis"
        )
    if near(g[1, 1], f_mm * H / w_mm) and not near(fy, f_mm * H / w_mm):
        return "s_y = height / H: you divided the sensor's width by H (sensor_mm = (width, height): height is sensor_mm[1])"
    if near(g[0, 0], f_mm * W / h_mm) and not near(fx, f_mm * W / h_mm):
        return "s_x = width / W: you divided the sensor's height by W (sensor_mm = (width, height): width is sensor_mm[0])"
    if near(g[0, 0], 1 / fx) or near(g[0, 0], w_mm / W / f_mm):
        return "f_x = f / s_x, not s_x / f: the focal length in units of the pixel pitch"
    if near(g[0, 0], f_mm * w_mm / W) or near(g[1, 1], f_mm * h_mm / H):
        return (
            "you multiplied the focal length by the pitch, f * s_x; divide: f_x = f / s_x counts how many pixel "
            "pitches fit in the focal length, so finer pixels give a larger f_x"
        )
    if near(g[0, 0], fx / 2) or near(g[1, 1], fy / 2):
        return (
            "f_x is half the right value: did you use half the sensor (width / 2) or double the pitch? "
            "f_x = f / s_x with s_x = width / W, the pitch of one pixel; the half width belongs to the field "
            "of view, tan(fov / 2) = (width / 2) / f"
        )
    if near(g[0, 0], 2 * fx) or near(g[1, 1], 2 * fy):
        return (
            "f_x is twice the right value: did you halve the pitch (width / 2 / W)? "
            "f_x = f / s_x with s_x = width / W, the pitch of one pixel"
        )
    if near(g[0, 0], f_mm * (W - 1) / w_mm) or near(g[1, 1], f_mm * (H - 1) / h_mm):
        return "the pitch is sensor width / W: W pixels tile the width (W - 1 counts the gaps between centres)"
    if near(g[0, 0], fy) and near(g[1, 1], fx) and not near(fx, fy):
        return (
            "f_x and f_y are swapped: f_x = f / s_x with the horizontal pitch s_x = width / W, f_y = f / s_y with "
            "s_y = height / H"
        )
    if (near(g[1, 1], fx) or near(g[0, 0], fy)) and not near(fx, fy):
        return (
            f"pixels need not be square: here s_x = {w_mm / W * 1e3:.4g} µm and s_y = {h_mm / H * 1e3:.4g} µm, so "
            f"f_x = f / s_x and f_y = f / s_y differ; compute each from its own axis"
        )
    if not near(g[0, 1], 0):
        return "K[0, 1] is the skew, 0 for a sensor with perpendicular rows and columns"
    if np.allclose(g, e, rtol=0.01, atol=0):
        return (
            "within 1 % but not exact: a rounded intermediate value, such as the pitch rounded to a few digits "
            f"({w_mm / W * 1e3:.2f} µm for {w_mm / W * 1e3:.6g} µm)? Keep full precision; the check allows 1e-9"
        )
    return "K = [[f / s_x, 0, (W - 1) / 2], [0, f / s_y, (H - 1) / 2], [0, 0, 1]] with s_x = width / W, s_y = height / H"


def intrinsics_from_datasheet(f_mm, sensor_mm, size):
    """K in pixels from a datasheet: focal length (mm), sensor (width, height) in mm, resolution (W, H) in pixels."""
    W, H = size
    sx, sy = sensor_mm[0] / W, sensor_mm[1] / H  # pixel pitch, mm per pixel (need not be square)
    return np.array(
        [
            [f_mm / sx, 0.0, (W - 1) / 2],  # f in pixels: f / pitch, both in mm
            [0.0, f_mm / sy, (H - 1) / 2],  # pixel centres at integers: the centre is (W - 1) / 2
            [0.0, 0.0, 1.0],
        ]
    )


def _datasheet_variant(f_mm, sensor_mm, size, *, fx=None, fy=None, cx=None, cy=None):
    K = _datasheet_reference(f_mm, sensor_mm, size)
    for (i, j), v in (((0, 0), fx), ((1, 1), fy), ((0, 2), cx), ((1, 2), cy)):
        if v is not None:
            K[i, j] = v
    return K


register_exercise(
    Exercise(
        name="intrinsics_from_datasheet",
        lesson="03",
        reference=_datasheet_reference,
        cases=_datasheet_cases,
        compare=SameArray(Tolerance(1e-9, 1e-9)),
        diagnose=_datasheet_diagnosis,
        ndarray_only=True,  # the prompt asks for a numpy array, as every other matrix exercise does
        wrong_variants=(
            (lambda f, s, n: _datasheet_reference(f, s, n).T, "transposed"),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=(n[1] - 1) / 2, cy=(n[0] - 1) / 2),
                "swapped",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=n[0] / 2, cy=n[1] / 2),
                "half a pixel off",
            ),
            (lambda f, s, n: _datasheet_variant(f, s, n, fx=f, fy=f), "not millimetres"),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f / (s[0] / n[0] * 1e3), fy=f / (s[1] / n[1] * 1e3)
                ),
                "1000 times too small",
            ),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f * 1e-3 / (s[0] / n[0] * 1e-6), fy=f * 1e-3 / (s[1] / n[1] * 1e-6)
                ),
                "1000 times too large",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fx=s[0] / n[0] / f, fy=s[1] / n[1] / f),
                "not s_x / f",
            ),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f * (n[0] - 1) / s[0], fy=f * (n[1] - 1) / s[1]
                ),
                "W pixels tile",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fx=f * n[0] / s[0], fy=f * n[0] / s[0]),
                "need not be square",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fx=f * n[1] / s[1], fy=f * n[0] / s[0]),
                "f_x and f_y are swapped",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=n[0] - 1, cy=n[1] - 1),
                "not the image size",
            ),
            (
                lambda f, s, n: _datasheet_variant(
                    f,
                    s,
                    n,
                    fx=f * n[1] / s[0],
                    fy=f * n[0] / s[1],
                    cx=(n[1] - 1) / 2,
                    cy=(n[0] - 1) / 2,
                ),
                "H, W = size",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fx=f * n[0] / s[1], fy=f * n[1] / s[0]),
                "sensor_mm is (width, height)",
            ),
            (lambda f, s, n: _datasheet_variant(f, s, n, fy=-f * n[1] / s[1]), "no minus sign"),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=(n[0] + 1) / 2, cy=(n[1] + 1) / 2),
                "numbered from 1",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=(n[0] - 1) // 2, cy=(n[1] - 1) // 2),
                "integer division",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=n[0] // 2 - 0.5, cy=n[1] // 2 - 0.5),
                "only for an even W",
            ),
            (lambda f, s, n: _datasheet_reference(f, s, n)[:2], "shape (3, 3)"),
            (lambda f, s, n: _datasheet_reference(f, s, n).astype(int), "integer array"),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, cx=np.round((n[0] - 1) / 2), cy=np.round((n[1] - 1) / 2)
                ),
                "keep the .5",
            ),
            (lambda f, s, n: _datasheet_reference(f, s, n).tolist(), "you returned a list"),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f / 10 * n[0] / s[0], fy=f / 10 * n[1] / s[1]
                ),
                "centimetre",
            ),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f * np.hypot(*n) / np.hypot(*s), fy=f * np.hypot(*n) / np.hypot(*s)
                ),
                "along the diagonal",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fy=f * n[1] / s[0]),
                "divided the sensor's width by H",
            ),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f / round(s[0] / n[0], 5), fy=f / round(s[1] / n[1], 5)
                ),
                "rounded",
            ),
            (lambda f, s, n: None, "return"),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=n[0] / 2 - 1, cy=n[1] / 2 - 1),
                "W / 2 - 1",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fx=f * s[0] / n[0], fy=f * s[1] / n[1]),
                "multiplied the focal",
            ),
            (
                lambda f, s, n: _datasheet_variant(
                    f, s, n, fx=f * n[0] / s[0] / 2, fy=f * n[1] / s[1] / 2
                ),
                "half the sensor",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fx=f * n[0] / s[0] * 1e3),
                "f_x is 1000 times too large",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, cx=(n[1] - 1) / 2),
                "c_x comes from the width",
            ),
            (
                lambda f, s, n: _datasheet_variant(f, s, n, fx=-f * n[0] / s[0]),
                "both positive lengths",
            ),
        ),
        teaching=intrinsics_from_datasheet,
    )
)
