"""Lesson 03's fourth exercise: bilinear demosaicking of a Bayer mosaic by normalised convolution."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import sensor
from .._answers import SameArray, Tolerance, shape_problem
from .._core import Exercise, Mistake, first_mistake, register_exercise
from ._demosaic_slips import (
    cross_kernel_demosaic,
    one_based_masks_demosaic,
    opencv_demosaic,
    opencv_ring_demosaic,
    tiled_masks_demosaic,
    uncast_demosaic,
)
from .quantize import not_an_array


def _demosaic_cases():
    """The test mosaics, random colours first.

    Random colours first (every interpolation direction matters), then odd sizes, all four patterns,
    a smooth ramp, and a uint8 mosaic as the lesson's own raw is.
    """
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
            sensor.quantise(sensor.mosaic(rng.uniform(size=(7, 9, 3)), "RGGB")),
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
    if "CV_8U" in str(exc) and "demosaic" in str(exc).lower():
        return (
            "cv2.cvtColor demosaics only uint8 and uint16 mosaics, and it fills the outermost ring of pixels its "
            "own way (the Pitfalls); this exercise asks for section 4's normalised convolution, "
            "c = k * (m r) / (k * m) with zeros beyond the border, written in numpy on the float mosaic"
        )
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
    rows, cols = np.nonzero(bad.any(axis=2))
    if np.all((rows == 0) | (cols == 0)):
        return (
            "NaN only on row 0 and column 0: your masks start at 1 (m[1::2, 1::2], m[1::2, 2::2], ... as in "
            "1-based MATLAB), so no mask covers row 0 or column 0 and some of their pixels see no sample of a "
            f"colour (0 / 0). Python counts from 0: {pattern}'s {pattern[0]} is at row 0, column 0, m[0::2, 0::2]"
        )
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


_IMAGE_MISTAKES = (
    Mistake(
        "pattern ignored",
        lambda s: s.pattern != "RGGB" and np.allclose(s.g, sensor.demosaic_bilinear(s.raw, "RGGB")),
        lambda s: (
            f"your image is the RGGB one, but this mosaic's pattern is {s.pattern}: you ignored `pattern` "
            f"(masks built for RGGB whatever it says); build each colour's mask from the letters, "
            f"the colour of pattern[0] at m[0::2, 0::2], pattern[1] at m[0::2, 1::2], and so on"
        ),
    ),
    Mistake(
        "pattern read column by column",
        lambda s: (
            s.column_major != s.pattern
            and np.allclose(s.g, sensor.demosaic_bilinear(s.raw, s.column_major))
        ),
        lambda s: (
            f"you read the pattern column by column, as {s.column_major}: its letters go row by row, top-left, "
            f"top-right, bottom-left, bottom-right, so {s.pattern} has {s.pattern[0]} {s.pattern[1]} on row 0 and "
            f"{s.pattern[2]} {s.pattern[3]} on row 1 (for {s.pattern} that swaps red and blue)"
        ),
    ),
    Mistake(
        "BGR, or masks one row and one column off",
        lambda s: np.allclose(s.g[..., ::-1], s.e),
        lambda s: (
            f"red and blue are swapped, which either of two slips gives: masks started at 1 on both axes "
            f"(m[1::2, 1::2] for {s.pattern}'s first letter, as in 1-based MATLAB), which reads the pattern as "
            f"{s.pattern[::-1]}; Python counts from 0: {s.pattern}'s {s.pattern[0]} is at row 0, column 0, "
            f"m[0::2, 0::2]. Or the channels returned as B, G, R (OpenCV's order): return R, G, B"
        ),
    ),
    Mistake(
        "transposed",
        lambda s: (
            s.g.shape[0] == s.g.shape[1]
            and np.allclose(s.g, s.e.transpose(1, 0, 2))
            and (not np.allclose(s.e, s.e.transpose(1, 0, 2)))
        ),
        (
            "your image is transposed: rows and columns swapped (a .T, or an index [u, v] where the image is "
            "img[v, u]: row v first, then column u)"
        ),
    ),
    *(
        Mistake(
            f"masks {how} off",
            lambda s, shift=shift: (
                shift(s.pattern) != s.pattern
                and np.allclose(s.g, sensor.demosaic_bilinear(s.raw, shift(s.pattern)))
            ),
            lambda s, how=how, shift=shift: (
                f"your masks sit {how} off, as if the pattern were {shift(s.pattern)}: started at 1 (m[1::2, ...]), "
                f"as in 1-based MATLAB? Python counts from 0: {s.pattern}'s {s.pattern[0]} is at row 0, column 0, "
                f"m[0::2, 0::2]"
            ),
        )
        for how, shift in (
            ("one column", lambda p: p[1] + p[0] + p[3] + p[2]),
            ("one row", lambda p: p[2] + p[3] + p[0] + p[1]),
        )
    ),
    Mistake(
        "scaled by 255",
        lambda s: np.allclose(s.g * 255, s.e) or np.allclose(s.g, s.e * 255),
        (
            "the values are scaled by 255: keep the units of the mosaic (do not divide or multiply by 255)"
        ),
    ),
)
"""Slips that change the whole image (the pattern misread, the channels or axes swapped, a scale), in the
order they are tested; each row's test reads the answer ``s.g`` against the right image ``s.e``."""


def _demosaic_diagnosis(args, got, expected) -> str:
    raw, pattern = args
    nan = isinstance(got, np.ndarray) and _nan_hint(raw, pattern, got)
    if nan:
        return nan
    problem = not_an_array(got) or shape_problem(got, expected)
    ring = not problem and (
        _legacy_opencv_name(raw, pattern, got, expected) or _ring_only(raw, got, expected)
    )
    if ring:
        return ring
    if problem:
        H, W = np.shape(raw)
        if (H % 2 or W % 2) and np.shape(got)[:2] == (H // 2 * 2, W // 2 * 2):
            return _tile_hint((H, W))
        return problem + ". Return an (H, W, 3) RGB image."
    g = np.asarray(got, dtype=float)
    e = np.asarray(expected)
    context = SimpleNamespace(
        raw=raw,
        pattern=pattern,
        g=g,
        e=e,
        column_major=pattern[0] + pattern[2] + pattern[1] + pattern[3],
    )
    cause = first_mistake(_IMAGE_MISTAKES, context)
    if cause:
        return cause
    if not np.issubdtype(np.asarray(raw).dtype, np.integer) and not g.any() and np.abs(e).max() > 0:
        return (
            "every value you returned is 0: this mosaic holds fractions 0 to 1, and casting it to uint8 "
            "(as cv2.cvtColor needs) turns them all into 0; work on the float mosaic, c = k * (m r) / (k * m)"
        )
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
    return _interpolation_cause(raw, pattern, g, e)


def _legacy_opencv_name(raw, pattern, got, expected) -> str | None:
    """The hint for OpenCV's old Bayer name: red and blue swapped inside, to the rounding of its codes.

    The old ``COLOR_BayerRG2RGB`` names a pattern by its 2nd row's 2nd and 3rd pixels, so it reads the
    pattern turned by 180 degrees: RGGB as BGGR, which swaps red and blue.
    """
    g, e = np.asarray(got, dtype=float), np.asarray(expected)
    if min(e.shape[:2]) < 3 or not np.isfinite(g).all():
        return None
    integer = np.issubdtype(np.asarray(raw).dtype, np.integer)
    tol = 0.5 + 1e-9 if integer else 1.01 * max(1.0, float(np.abs(e).max())) / 255
    inner = (slice(1, -1), slice(1, -1))
    swapped = g[..., ::-1]
    if np.allclose(swapped, e, rtol=0, atol=tol) or not np.allclose(
        swapped[inner], e[inner], rtol=0, atol=tol
    ):  # swapped everywhere is BGR or 1-based masks (the image slips); OpenCV's ring differs
        return None
    return (
        f"red and blue are swapped, and the outermost ring is filled OpenCV's way: cv2.cvtColor with an old "
        f"Bayer name? COLOR_Bayer{pattern[:2]}2RGB names the pattern by its 2nd row's 2nd and 3rd pixels, so it "
        f"means {pattern[::-1]}, not {pattern} (the Pitfalls); the four-letter COLOR_Bayer{pattern}2RGB reads it "
        f"right, but OpenCV still fills the ring its own way: write the normalised convolution yourself, "
        f"c = k * (m r) / (k * m)"
    )


def _ring_only(raw, got, expected) -> str | None:
    """The hint for an answer right inside, to the rounding of OpenCV's codes, but wrong on the outermost ring.

    cv2.cvtColor demosaics only uint8 and uint16 mosaics and rounds its result: 0.5 DN on an integer
    mosaic. A float mosaic must first be turned into codes, so inside the answer is then off by up to
    one 8-bit code, 1/255 of the values' range, yet not exact (an exact inside with a wrong ring is a
    border mode, named by :func:`_interpolation_cause`).
    """
    g, e = np.asarray(got, dtype=float), np.asarray(expected)
    inner = (slice(1, -1), slice(1, -1))
    if min(e.shape[:2]) < 3:
        return None
    integer = np.issubdtype(np.asarray(raw).dtype, np.integer)
    scale = max(1.0, float(np.abs(e).max()))
    off = np.abs(g[inner] - e[inner]).max() if np.isfinite(g).all() else np.inf
    if integer and not off <= 0.5 + 1e-9:
        return None
    if not integer and not 1e-6 * scale < off <= 1.01 * scale / 255:
        return None
    if np.allclose(g, e, rtol=0, atol=0.5 + 1e-9 if integer else 1.01 * scale / 255):
        return None
    codes = (
        ""
        if integer
        else ", on uint8 or uint16 codes as it takes no floats (their rounding is the small error inside)"
    )
    return (
        f"right inside, wrong only on the outermost ring of pixels: this is OpenCV's cv2.cvtColor "
        f"with a COLOR_Bayer code{codes}, which fills that ring its own way (the Pitfalls measure how far off it lies on the "
        f"lesson's photo). Write the normalised convolution yourself, on the float mosaic, c = k * (m r) / (k * m) "
        f"with zeros beyond the border, so the edge pixels average only the neighbours that exist"
    )


def _samples_changed_hint(g, e, m) -> str:
    """The hint for measured samples that changed: a plain tent convolution's double slip, or the samples alone."""
    filled = ~m[1:-1, 1:-1, 1]  # green's interpolated sites inside the border
    if filled.any() and np.allclose(g[1:-1, 1:-1, 1][filled], 2 * e[1:-1, 1:-1, 1][filled]):
        return (
            "the measured samples changed, and green at red and blue sites is twice the mean: a plain "
            "convolution with the tent kernel, not normalised (its 4 cross weights of 1/2 sum to 2, and at a "
            "green site it adds the 4 diagonal greens to the sample); divide by the weights actually used, "
            "c = k * (m r) / (k * m), then keep each measured sample"
        )
    return (
        "the measured samples changed: keep each pixel's own colour as measured, and check which "
        "colour sits where in the pattern (RGGB: R at row 0, column 0)"
    )


def _interpolation_cause(raw, pattern, g, e) -> str:
    """Why the image is wrong when the whole-image slips are ruled out.

    The samples, the dtype, the neighbours averaged at each kind of site, or the border.
    """
    m = sensor.bayer_masks(raw.shape, pattern)
    if not np.allclose(g[m], e[m]):
        bad = (~np.isclose(g, e) & m).any(axis=2)
        H, W = raw.shape
        edge = np.zeros_like(bad)
        edge[H - 1 :, :] |= H % 2 == 1
        edge[:, W - 1 :] |= W % 2 == 1
        if edge.any() and not (bad & ~edge).any():
            return (
                f"the last row or column of this {H} x {W} mosaic (an odd size) lost its measured samples: a loop "
                "over 2 x 2 blocks, range(0, H - 1, 2), or masks for H // 2 blocks stop one short; fill the "
                "last row and column too"
            )
        return _samples_changed_hint(g, e, m)
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
    for mode, what, why in (
        (
            "reflect",
            "mode='reflect', scipy.ndimage.convolve's default (or mode='nearest', the same "
            "one pixel out)",
            "repeats the edge pixel beyond the frame, where the pattern has the other colour, so a copy of "
            "the edge's colour stands where none was measured",
        ),
        (
            "mirror",
            "mode='mirror' (cv2.filter2D's default border, BORDER_REFLECT_101)",
            "reflects about the edge pixel: the pattern is kept, but the sample just inside the edge is "
            "counted twice (green at a bottom-edge site becomes (2 above + left + right) / 4, not the mean "
            "of its 3 neighbours)",
        ),
        (
            "wrap",
            "mode='wrap' (or np.roll)",
            "copies samples from the opposite side of the frame, which are not this pixel's neighbours",
        ),
    ):
        if np.allclose(g, _padded_demosaic(raw, pattern, mode)):
            return (
                f"right inside, wrong at the border: {what} {why}, and both k * (m r) and k * m count it; use "
                f"mode='constant' (zeros outside; cv2.BORDER_CONSTANT) for both, so the ratio averages only "
                f"the samples that exist"
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


def _unnormalised_tent_unkept_demosaic(raw, pattern):
    """The plain tent convolution with no sample kept: two slips, one cause (no normalisation)."""
    from scipy.ndimage import convolve

    raw = np.asarray(raw, dtype=float)
    m = sensor.bayer_masks(raw.shape, pattern)
    k = np.array([[1, 2, 1], [2, 4, 2], [1, 2, 1]]) / 4.0
    return np.stack([convolve(raw * m[..., c], k, mode="constant") for c in range(3)], axis=2)


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


def demosaic_bilinear(raw, pattern):
    """Section 4's formula, c = k * (m r) / (k * m) at the missing sites; measured samples kept.

    Parameters
    ----------
    raw : (H, W) array_like
        The mosaic: one colour sample per pixel (uint8, uint16 or float).
    pattern : str
        The colours of the 2 x 2 tile, row by row: ``"RGGB"``, ``"BGGR"``, ``"GRBG"`` or ``"GBRG"``.

    Returns
    -------
    (H, W, 3) ndarray of float
        The RGB image: each pixel's measured colour as it was, the two others interpolated from the
        neighbours that measured them (k the 3 x 3 tent kernel, m the colour's mask, zeros beyond the
        border).
    """
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
            (lambda raw, pattern: sensor.demosaic_bilinear(raw, "RGGB"), "you ignored `pattern`"),
            (
                lambda raw, pattern: sensor.demosaic_bilinear(
                    np.asarray(raw).astype(np.uint8), pattern
                ),
                "casting it to uint8",
            ),
            (_zero_padded_demosaic, "border"),
            (lambda raw, pattern: opencv_demosaic(raw, pattern[::-1]), "an old Bayer name"),
            (
                lambda raw, pattern: sensor.demosaic_bilinear(
                    raw, "GRBG" if pattern == "RGGB" else "RGGB"
                ),
                "off, as if the pattern were",
            ),
            (
                lambda raw, pattern: sensor.demosaic_bilinear(raw, pattern)[..., ::-1],
                "B, G, R (OpenCV's order)",
            ),
            (
                lambda raw, pattern: sensor.demosaic_bilinear(raw, pattern[::-1]),
                "masks started at 1 on both axes",
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
            (uncast_demosaic, "convert first: raw.astype"),
            (tiled_masks_demosaic, "a mask built with np.tile"),
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
            (cross_kernel_demosaic, "are all green"),
            (_unnormalised_tent_demosaic, "twice the mean"),
            (_unnormalised_tent_unkept_demosaic, "twice the mean: a plain convolution"),
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
            (lambda raw, pattern: _padded_demosaic(raw, pattern, "mirror"), "counted twice"),
            (one_based_masks_demosaic, "NaN only on row 0 and column 0"),
            (opencv_ring_demosaic, "outermost ring"),
            (opencv_demosaic, "on uint8 or uint16 codes as it takes no floats"),
            (
                lambda raw, pattern: opencv_demosaic(raw, pattern, via_codes=False),
                "cv2.cvtColor demosaics only uint8 and uint16",
            ),
            (lambda raw, pattern: _padded_demosaic(raw, pattern, "nearest"), "or mode='nearest'"),
        ),
        teaching=demosaic_bilinear,
    )
)
