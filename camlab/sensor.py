r"""The digital sensor: metric image plane to pixels, sampling, quantisation, noise, Bayer.

Pixels (u, v) = (column, row) with the origin at the centre of the top-left pixel; images
are indexed ``img[v, u]``. A point :math:`(x, y)` on the image plane (metres, origin on
the optical axis, y down) lands at

.. math:: u = x / s_x + c_x, \qquad v = y / s_y + c_y

for pixel pitch :math:`(s_x, s_y)` and principal point :math:`(c_x, c_y)` in pixels, so a
lens of focal length :math:`f` gives :math:`f_x = f / s_x,\ f_y = f / s_y`.

Images handled here are float arrays in [0, 1] (irradiance relative to saturation) or
integer digital numbers after :func:`quantise`. See lesson 03.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._validate import (
    CamlabInputError,
    as_points,
    check_finite,
    check_image,
    check_pair,
    check_positive,
    check_shape,
    check_size,
)

__all__ = [
    "BAYER_PATTERNS",
    "DarkAndFlatFrames",
    "NoiseModel",
    "add_noise",
    "alias_frequency",
    "bayer_masks",
    "check_bayer_pattern",
    "check_bits",
    "dark_and_flat_frames",
    "demosaic_bilinear",
    "demosaic_opencv",
    "dequantise",
    "gamma_decode",
    "gamma_encode",
    "intrinsics_from_sensor",
    "metric_to_pixels",
    "mosaic",
    "pixels_to_metric",
    "psnr",
    "quantise",
    "sample",
    "white_balance",
    "zone_plate",
]

BAYER_PATTERNS = ("RGGB", "BGGR", "GRBG", "GBRG")


def metric_to_pixels(
    points: ArrayLike, pitch: tuple[float, float], principal_point: tuple[float, float]
) -> np.ndarray:
    """Image-plane points (x, y) in metres to pixel coordinates (u, v) (see the module docstring).

    Parameters
    ----------
    points : (N, 2) or (2,) array_like
        Image-plane points (x, y), metres (origin on the optical axis, y down).
    pitch : (2,) tuple of float
        Pixel pitch (s_x, s_y), metres per pixel (> 0).
    principal_point : (2,) tuple of float
        Principal point (c_x, c_y), pixels.

    Returns
    -------
    (N, 2) or (2,) ndarray
        Pixel coordinates (u, v), the input's rank.

    Examples
    --------
    >>> metric_to_pixels([1e-3, -0.5e-3], (5e-6, 5e-6), (319.5, 239.5))
    array([519.5, 139.5])
    """
    pts = as_points(points, 2, "points")
    sx, sy = check_pair(pitch, "pitch", "metres", positive=True)
    uv = pts.array / [sx, sy] + check_pair(principal_point, "principal_point", "pixels")
    return pts.restore(uv)


def pixels_to_metric(
    pixels: ArrayLike, pitch: tuple[float, float], principal_point: tuple[float, float]
) -> np.ndarray:
    """Inverse of :func:`metric_to_pixels`: pixels (u, v) to image-plane metres (x, y).

    Parameters
    ----------
    pixels : (N, 2) or (2,) array_like
        Pixel coordinates (u, v).
    pitch : (2,) tuple of float
        Pixel pitch (s_x, s_y), metres per pixel (> 0).
    principal_point : (2,) tuple of float
        Principal point (c_x, c_y), pixels.

    Returns
    -------
    (N, 2) or (2,) ndarray
        Image-plane points (x, y), metres, the input's rank.
    """
    pts = as_points(pixels, 2, "pixels")
    sx, sy = check_pair(pitch, "pitch", "metres", positive=True)
    return pts.restore(
        (pts.array - check_pair(principal_point, "principal_point", "pixels")) * [sx, sy]
    )


def intrinsics_from_sensor(
    focal_length: float,
    pitch: tuple[float, float],
    size: tuple[int, int],
    principal_offset: tuple[float, float] = (0.0, 0.0),
) -> np.ndarray:
    r"""The intrinsic matrix K of a lens on a sensor.

    :math:`f_x = f / s_x`, :math:`f_y = f / s_y`; the principal point is the image centre
    :math:`((W - 1)/2, (H - 1)/2)` (pixel-centre origin) plus ``principal_offset`` pixels.

    Parameters
    ----------
    focal_length : float
        Focal length f of the lens, metres (> 0).
    pitch : (2,) tuple of float
        Pixel pitch (s_x, s_y), metres per pixel (> 0).
    size : (2,) tuple of int
        Image size (width, height), pixels.
    principal_offset : (2,) tuple of float, optional
        Offset of the principal point from the image centre, pixels (default none).

    Returns
    -------
    (3, 3) ndarray
        K, with f_x = f / s_x and f_y = f / s_y in pixels, zero skew.

    Examples
    --------
    >>> intrinsics_from_sensor(4e-3, (5e-6, 5e-6), (640, 480))
    array([[800. ,   0. , 319.5],
           [  0. , 800. , 239.5],
           [  0. ,   0. ,   1. ]])
    """
    f = check_positive(focal_length, "focal_length", "metres")
    sx, sy = check_pair(pitch, "pitch", "metres", positive=True)
    w, h = check_size(size)
    ox, oy = check_pair(principal_offset, "principal_offset", "pixels")
    return np.array(
        [[f / sx, 0.0, (w - 1) / 2 + ox], [0.0, f / sy, (h - 1) / 2 + oy], [0.0, 0.0, 1.0]]
    )


def check_bits(bits: int) -> int:
    """Return ``bits`` as an int if it is a bit depth from 1 to 16, else raise.

    Parameters
    ----------
    bits : int
        A bit depth.

    Returns
    -------
    int
        ``bits`` as a Python int.

    Raises
    ------
    CamlabInputError
        When ``bits`` is not an integer from 1 to 16.
    """
    if not isinstance(bits, (int, np.integer)) or not 1 <= bits <= 16:
        raise CamlabInputError(f"bits: expected an integer bit depth from 1 to 16, got {bits!r}")
    return int(bits)


def quantise(image: ArrayLike, bits: int = 8) -> np.ndarray:
    r"""Quantise a float image in [0, 1] to ``bits``-bit digital numbers (round to nearest, clip).

    :math:`DN = \mathrm{round}(I (2^b - 1))`; uint8 for ``bits <= 8``, else uint16.

    Parameters
    ----------
    image : array_like
        Float image, values in [0, 1] (outside is clipped); any shape.
    bits : int, optional
        Bit depth b, 1 to 16 (default 8).

    Returns
    -------
    ndarray
        Digital numbers DN in [0, 2^b - 1], the image's shape; uint8 for ``bits <= 8``, else
        uint16.

    Examples
    --------
    >>> quantise(np.array([0.0, 0.5, 1.0, 1.2]), 2)
    array([0, 2, 3, 3], dtype=uint8)
    """
    b = check_bits(bits)
    a = np.asarray(image)
    if a.dtype.kind == "f":
        check_finite(a, "image")
    if not np.issubdtype(a.dtype, np.floating):
        raise CamlabInputError(
            f"image: expected a float image with values in [0, 1], got dtype {a.dtype}"
        )
    levels = (1 << b) - 1
    dn = np.clip(np.rint(a * levels), 0, levels)
    return dn.astype(np.uint8 if b <= 8 else np.uint16)


def dequantise(dn: ArrayLike, bits: int = 8) -> np.ndarray:
    """Digital numbers back to float [0, 1]: ``dn / (2**bits - 1)``.

    Parameters
    ----------
    dn : array_like of int
        Digital numbers in [0, 2^bits - 1].
    bits : int, optional
        The bit depth they were quantised with (default 8).

    Returns
    -------
    ndarray
        Float values in [0, 1], the input's shape.
    """
    b = check_bits(bits)
    a = np.asarray(dn)
    if not np.issubdtype(a.dtype, np.integer):
        raise CamlabInputError(f"dn: expected integer digital numbers, got dtype {a.dtype}")
    levels = (1 << b) - 1
    if a.size and (a.min() < 0 or a.max() > levels):
        raise CamlabInputError(
            f"dn: {b}-bit digital numbers lie in [0, {levels}], got {a.min()} to {a.max()}; "
            f"pass the bit depth they were quantised with (bits=...)"
        )
    return a.astype(float) / levels


class NoiseModel(NamedTuple):
    """Sensor noise: ``full_well`` electrons at saturation (shot noise) and ``read_noise`` electrons RMS."""

    full_well: float = 10000.0
    read_noise: float = 5.0


def add_noise(
    image: ArrayLike, noise: NoiseModel | None = None, rng: np.random.Generator | int | None = None
) -> np.ndarray:
    r"""Add photon shot noise and read noise to a float image in [0, 1].

    Electrons :math:`e \sim \mathrm{Poisson}(I \cdot FW)`, plus Gaussian read noise of
    ``read_noise`` electrons; returned as :math:`e / FW` (float, may leave [0, 1] slightly).
    Shot noise grows as :math:`\sqrt{I}`, so SNR :math:`\approx \sqrt{I \cdot FW}` in bright areas.
    Pixels expecting more than 100 electrons draw :math:`\mathcal{N}(\lambda, \lambda)`
    instead of the Poisson law (indistinguishable there, and 10x faster for slider demos).
    ``noise=None`` is ``NoiseModel()``: 10000 electrons full well, 5 electrons read noise.

    Parameters
    ----------
    image : array_like
        Float image in [0, 1] (irradiance relative to saturation); grey or RGB.
    noise : NoiseModel, optional
        ``full_well`` (electrons at saturation) and ``read_noise`` (electrons RMS); None is
        ``NoiseModel()``.
    rng : numpy.random.Generator, int or None, optional
        Random generator or seed (None: a fresh unseeded generator).

    Returns
    -------
    ndarray
        The noisy image, float, the input's shape; values may leave [0, 1] slightly.
    """
    a = check_image(image)
    noise = NoiseModel() if noise is None else noise
    fw = check_positive(noise.full_well, "full_well", "electrons")
    if not noise.read_noise >= 0:
        raise CamlabInputError(f"read_noise: expected >= 0 electrons RMS, got {noise.read_noise!r}")
    rng = np.random.default_rng(rng)
    lam = np.clip(a.astype(float), 0, None) * fw
    electrons = lam + np.sqrt(lam) * rng.standard_normal(size=lam.shape)
    low = lam < 100
    if low.any():
        electrons[low] = rng.poisson(lam[low])
    if noise.read_noise > 0:
        electrons += rng.normal(0.0, noise.read_noise, size=a.shape)
    return electrons / fw


class DarkAndFlatFrames(NamedTuple):
    """What :func:`dark_and_flat_frames` returns.

    ``darks``, a pair of frames taken with the lens capped, and ``flats``, a list of pairs ``(a,
    b)`` of frames of an evenly lit white card, one pair per light level.
    """

    darks: tuple[np.ndarray, np.ndarray]
    flats: list[tuple[np.ndarray, np.ndarray]]


def dark_and_flat_frames(
    full_well: float,
    read_noise: float,
    black_level: int,
    levels: ArrayLike = (0.01, 0.05, 0.21, 0.37, 0.53, 0.69, 0.85),
    shape: tuple[int, int] = (96, 96),
    rng: np.random.Generator | int | None = None,
    bits: int = 12,
) -> DarkAndFlatFrames:
    r"""A dark pair and pairs of flat frames (uint16 DN) of a simulated sensor, as a camera gives them.

    .. math:: DN = \operatorname{round}(\text{black} + o + e / g), \qquad g = \frac{FW}{2^b - 1 - \text{black}}

    with electrons :math:`e \sim \mathrm{Poisson}(L \cdot FW \cdot p) + \mathcal N(0, \sigma_r^2)` at the light
    level ``L`` (a fraction of full well), clipped to the converter's range. Like a real sensor's, each pixel has
    its own gain :math:`p` (PRNU, 1 %) and dark offset :math:`o` (DSNU, 1.5 DN), the same in every frame; the
    black level ``black_level`` (DN) is the offset every pixel shares. Lesson 03's photon-transfer curve and
    exercise 3 measure ``g`` and ``read_noise`` back from such frames.

    Parameters
    ----------
    full_well : float
        Electrons FW that fill the converter's range above the black level (> 0).
    read_noise : float
        Read noise sigma_r, electrons RMS (>= 0).
    black_level : int
        The offset every pixel shares, DN, in [0, 2^bits - 1).
    levels : array_like of float, optional
        Light levels L of the flat pairs, fractions of full well.
    shape : (2,) tuple of int, optional
        Frame shape (height, width), pixels.
    rng : numpy.random.Generator, int or None, optional
        Random generator or seed (None: a fresh unseeded generator).
    bits : int, optional
        Bit depth b of the converter (default 12).

    Returns
    -------
    DarkAndFlatFrames
        ``darks``, a pair of (H, W) uint16 frames with the lens capped, and ``flats``, a list of
        pairs of (H, W) uint16 frames, one pair per level in ``levels``.
    """
    fw = check_positive(full_well, "full_well", "electrons")
    top = 2 ** check_bits(bits) - 1
    if not 0 <= black_level < top:
        raise CamlabInputError(
            f"black_level: expected a whole number of DN in [0, {top}), got {black_level!r}"
        )
    if not read_noise >= 0:
        raise CamlabInputError(f"read_noise: expected >= 0 electrons RMS, got {read_noise!r}")
    rng = np.random.default_rng(rng)
    # electrons per DN: the full well fills the converter's range above the black level
    g = fw / (top - black_level)
    prnu = 1 + 0.01 * rng.standard_normal(shape)
    dsnu = 1.5 * rng.standard_normal(shape)

    def frame(level: float) -> np.ndarray:
        electrons = rng.poisson(level * fw * prnu) + rng.normal(0, read_noise, shape)
        return np.clip(np.rint(black_level + dsnu + electrons / g), 0, top).astype(np.uint16)

    darks = (frame(0.0), frame(0.0))
    return DarkAndFlatFrames(
        darks, [(frame(level), frame(level)) for level in np.asarray(levels, float)]
    )


def alias_frequency(f: ArrayLike) -> np.ndarray:
    r"""The frequency that a cosine of ``f`` cycles per pixel shows once sampled at every pixel.

    Sampled at the integers, :math:`\cos 2\pi f n` equals :math:`\cos 2\pi (f + m) n` and
    :math:`\cos 2\pi (m - f) n` for every integer :math:`m` (lesson 03, section 2): the samples hold
    only the one of these frequencies in :math:`[0, \tfrac12]`, the band below the Nyquist limit,
    :math:`|f - \operatorname{round}(f)|`. Detail above the limit folds back about it (0.8 shows as 0.2).

    Parameters
    ----------
    f : array_like
        Frequencies, cycles per pixel: any real numbers (a cosine at :math:`-f` is the one at :math:`f`).

    Returns
    -------
    ndarray
        The frequencies the samples show, in :math:`[0, \tfrac12]`, float, ``f``'s shape.
    """
    f = np.asarray(f, dtype=float)
    return np.abs(f - np.round(f))  # the nearest whole cycle per pixel is the copy f aliases with


def sample(image: ArrayLike, factor: int, prefilter: bool = False, blur: float = 0.0) -> np.ndarray:
    r"""Sample a fine image with a coarser pixel grid ``factor`` times larger.

    ``prefilter=False`` takes one fine pixel per coarse pixel (an ideal point sampler:
    frequencies above Nyquist alias), the one at index ``(factor - 1) // 2`` in each block:
    exactly the block's centre for an odd ``factor``; for an even one the centre falls between
    fine pixels and the sample sits half a fine pixel up and left of it. ``True`` averages the
    ``factor x factor`` area each pixel covers (a real pixel's box filter, which suppresses
    most aliasing); its value belongs to the block's true centre.

    ``blur`` is the standard deviation, in coarse pixels, of a Gaussian blur applied to the
    fine image first: the lens's own blur (or, roughly, an optical low-pass filter). Its
    frequency response is :math:`e^{-2\pi^2 \sigma^2 f^2}` (f in cycles per coarse pixel): at
    ``blur=0.5`` it keeps 29 % of the contrast at the Nyquist limit, 0.7 % at 1 cycle per pixel.
    Only the first ``(H // factor) * factor`` rows and columns are sampled.

    Parameters
    ----------
    image : (H, W) or (H, W, C) array_like
        The fine image.
    factor : int
        Coarse pixel size in fine pixels (>= 1).
    prefilter : bool, optional
        False (the default): point sampling; True: the box average of each coarse pixel.
    blur : float, optional
        Standard deviation of a Gaussian blur applied first, coarse pixels (default 0: none).

    Returns
    -------
    (H // factor, W // factor) or (H // factor, W // factor, C) float ndarray
        The coarse image.
    """
    a = check_image(image).astype(float)
    if not isinstance(factor, (int, np.integer)) or factor < 1:
        raise CamlabInputError(f"factor: expected an integer >= 1, got {factor!r}")
    if not (np.isfinite(blur) and blur >= 0):
        raise CamlabInputError(
            f"blur: expected a standard deviation >= 0 in coarse pixels, got {blur!r}; use 0 "
            f"for no blur"
        )
    if blur > 0:
        from scipy.ndimage import gaussian_filter

        sigma = (blur * factor, blur * factor) + (0,) * (
            a.ndim - 2
        )  # no blur across colour channels
        a = gaussian_filter(a, sigma, mode="reflect")
    h, w = (a.shape[0] // factor) * factor, (a.shape[1] // factor) * factor
    a = a[:h, :w]
    if not prefilter:
        # the fine pixel at the coarse pixel's centre (odd factor), or half a fine pixel before it (even)
        c = (factor - 1) // 2
        return a[c::factor, c::factor].copy()
    return a.reshape(h // factor, factor, w // factor, factor, *a.shape[2:]).mean(axis=(1, 3))


def zone_plate(size: int = 512, k: float | None = None) -> np.ndarray:
    r"""A zone plate :math:`\frac12(1 + \cos(k r^2))`: local frequency grows linearly with radius.

    With the default ``k = pi / size`` the frequency reaches the Nyquist limit (0.5
    cycle/pixel) at the image edge, so any coarser sampling aliases into visible rings.

    Parameters
    ----------
    size : int, optional
        Side of the square image, pixels (>= 2; default 512).
    k : float, optional
        Chirp rate k, radians per pixel squared (> 0); None: pi / size.

    Returns
    -------
    (size, size) float ndarray
        The zone plate, values in [0, 1], centred on the image centre.
    """
    if not isinstance(size, (int, np.integer)) or size < 2:
        raise CamlabInputError(f"size: expected an integer >= 2, got {size!r}")
    k = np.pi / size if k is None else check_positive(k, "k")
    c = (size - 1) / 2
    y, x = np.mgrid[0:size, 0:size] - c
    return 0.5 * (1 + np.cos(k * (x * x + y * y)))


def check_bayer_pattern(pattern: str) -> str:
    """Return a Bayer pattern name in upper case (one of ``BAYER_PATTERNS``), else raise.

    Parameters
    ----------
    pattern : str
        A Bayer pattern name, any case.

    Returns
    -------
    str
        The name in upper case, one of ``BAYER_PATTERNS``.

    Raises
    ------
    CamlabInputError
        When ``pattern`` is not one of ``BAYER_PATTERNS``.
    """
    p = str(pattern).upper()
    if p not in BAYER_PATTERNS:
        raise CamlabInputError(
            f"pattern: expected one of {', '.join(BAYER_PATTERNS)}, got {pattern!r}"
        )
    return p


def bayer_masks(shape: tuple[int, int], pattern: str = "RGGB") -> np.ndarray:
    """(H, W, 3) boolean masks of which pixels see red, green and blue.

    The pattern names the top-left 2x2 block in reading order: RGGB has R at (0, 0),
    G at (0, 1) and (1, 0), B at (1, 1).

    Parameters
    ----------
    shape : (2,) tuple of int
        Image shape (height, width), pixels.
    pattern : {"RGGB", "BGGR", "GRBG", "GBRG"}, optional
        The Bayer pattern, named by its top-left 2x2 block in reading order (any case).

    Returns
    -------
    (H, W, 3) bool ndarray
        True where the pixel's filter passes red, green, blue (channels 0, 1, 2).

    Examples
    --------
    >>> bayer_masks((2, 2), "GRBG")[..., 0].astype(int)   # red at row 0, column 1
    array([[0, 1],
           [0, 0]])
    """
    p = check_bayer_pattern(pattern)
    h, w = check_shape(shape)
    masks = np.zeros((h, w, 3), dtype=bool)
    for (dy, dx), ch in zip([(0, 0), (0, 1), (1, 0), (1, 1)], p, strict=True):
        masks[dy::2, dx::2, "RGB".index(ch)] = True
    return masks


def mosaic(rgb: ArrayLike, pattern: str = "RGGB") -> np.ndarray:
    """Keep one colour per pixel as a Bayer colour-filter array does: (H, W, 3) -> (H, W), same dtype.

    Parameters
    ----------
    rgb : (H, W, 3) array_like
        The full-colour image.
    pattern : {"RGGB", "BGGR", "GRBG", "GBRG"}, optional
        The Bayer pattern, named by its top-left 2x2 block in reading order (any case).

    Returns
    -------
    (H, W) ndarray
        The raw mosaic: each pixel keeps the channel its filter passes; ``rgb``'s dtype.
    """
    a = check_image(rgb, "rgb", channels=(3,))
    m = bayer_masks(a.shape[:2], pattern)
    return (a * m).sum(axis=2).astype(a.dtype)


def _convolve3(a: np.ndarray, k: np.ndarray) -> np.ndarray:
    """3x3 correlation with zero padding, written as nine shifted sums."""
    p = np.pad(a, 1)
    h, w = a.shape
    out = np.zeros_like(a, dtype=float)
    for dy in range(3):
        for dx in range(3):
            if k[dy, dx]:
                out += k[dy, dx] * p[dy : dy + h, dx : dx + w]
    return out


def demosaic_bilinear(raw: ArrayLike, pattern: str = "RGGB") -> np.ndarray:
    r"""Bilinear demosaicing: fill each colour's missing pixels with the mean of its neighbours.

    For each channel, :math:`\hat c = (k * (m \cdot r)) / (k * m)` with the channel's
    mask :math:`m`, the raw image :math:`r` and the tent kernel
    :math:`k = \frac14 [1, 2, 1]^T [1, 2, 1]`. Dividing by :math:`k * m` (normalised
    convolution) averages exactly the available neighbours: 2 or 4 for green, 1, 2 or 4 for
    red and blue, and stays right at the image border where a plain convolution darkens.
    Measured pixels are kept as they are.

    Parameters
    ----------
    raw : (H, W) array_like
        Mosaic (float or integer).
    pattern : {"RGGB", "BGGR", "GRBG", "GBRG"}, optional
        The Bayer pattern of ``raw`` (default "RGGB").

    Returns
    -------
    (H, W, 3) float ndarray
        RGB, in the units of ``raw``.

    References
    ----------
    .. [1] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022, section
       2.3.2 (colour filter arrays and demosaicing).
    """
    r = check_image(raw, "raw", channels=(1,)).astype(float)
    masks = bayer_masks(r.shape, pattern)
    k = np.array([[1.0, 2.0, 1.0], [2.0, 4.0, 2.0], [1.0, 2.0, 1.0]]) / 4.0
    out = np.empty(r.shape + (3,))
    for c in range(3):
        m = masks[..., c].astype(float)
        est = _convolve3(r * m, k) / _convolve3(m, k)
        out[..., c] = np.where(masks[..., c], r, est)
    return out


# OpenCV's four-letter codes name a Bayer pattern as camlab does, by its top-left 2x2 block
# (COLOR_BayerRGGB2RGB); the older two-letter ones (COLOR_BayerBG2RGB, the same constant) by the
# 2nd and 3rd pixels of its 2nd row, so COLOR_BayerRG2RGB is BGGR. Both exist in OpenCV >= 4.12.


def demosaic_opencv(raw: ArrayLike, pattern: str = "RGGB", method: str = "bilinear") -> np.ndarray:
    """OpenCV's demosaicing (``method`` = "bilinear", "vng" or "ea" edge-aware) of a uint8/uint16 mosaic, as RGB.

    VNG accepts 8-bit input only. A thin adapter for comparisons; the method taught is
    :func:`demosaic_bilinear`.

    Parameters
    ----------
    raw : (H, W) array_like of uint8 or uint16
        The raw mosaic.
    pattern : {"RGGB", "BGGR", "GRBG", "GBRG"}, optional
        The Bayer pattern, named by its top-left 2x2 block in reading order (any case).
    method : {"bilinear", "vng", "ea"}, optional
        OpenCV's bilinear, variable number of gradients (8-bit only) or edge-aware method.

    Returns
    -------
    (H, W, 3) ndarray
        RGB, ``raw``'s dtype.
    """
    import cv2

    r = check_image(raw, "raw", channels=(1,))
    if r.dtype not in (np.uint8, np.uint16):
        raise CamlabInputError(
            f"raw: OpenCV demosaicing needs uint8 or uint16, got dtype {r.dtype}"
        )
    suffix = {"bilinear": "", "vng": "_VNG", "ea": "_EA"}
    if method not in suffix:
        raise CamlabInputError(f"method: expected 'bilinear', 'vng' or 'ea', got {method!r}")
    if method == "vng" and r.dtype != np.uint8:
        raise CamlabInputError(
            "raw: OpenCV's VNG demosaicing accepts uint8 only; quantise to 8 bits first"
        )
    code = getattr(cv2, f"COLOR_Bayer{check_bayer_pattern(pattern)}2RGB{suffix[method]}")
    return cv2.cvtColor(np.ascontiguousarray(r), code)


def psnr(
    reference: ArrayLike, test: ArrayLike, peak: float | None = None, border: int = 0
) -> float:
    r"""Peak signal-to-noise ratio :math:`10 \log_{10}(peak^2 / MSE)` in dB, ignoring ``border`` pixels.

    ``peak`` defaults to the largest value of the reference's integer type (255 for uint8)
    and to 1.0 for float images in [0, 1].

    Parameters
    ----------
    reference, test : array_like
        Two images of the same shape.
    peak : float, optional
        The largest possible value; None: the reference integer type's maximum, or 1.0 for
        floats.
    border : int, optional
        Pixels left out at each edge (default 0).

    Returns
    -------
    float
        PSNR in dB; inf for identical images.

    Examples
    --------
    >>> ref = np.full((4, 4), 100, np.uint8)
    >>> round(psnr(ref, ref + 1), 2)  # an error of 1 grey level of 255
    48.13
    """
    ref, tst = check_image(reference, "reference"), check_image(test, "test")
    if peak is None:
        peak = float(np.iinfo(ref.dtype).max) if ref.dtype.kind in "ui" else 1.0
    peak = check_positive(peak, "peak")
    a, b = ref.astype(float), tst.astype(float)
    if a.shape != b.shape:
        raise CamlabInputError(f"test: expected the reference's shape {a.shape}, got {b.shape}")
    if border:
        a, b = a[border:-border, border:-border], b[border:-border, border:-border]
    mse = np.mean((a - b) ** 2)
    return float("inf") if mse == 0 else float(10 * np.log10(peak * peak / mse))


def gamma_encode(linear: ArrayLike) -> np.ndarray:
    r"""sRGB encoding of linear values in [0, 1]: what a camera does before it saves a JPEG.

    A sensor's numbers are proportional to light, but we see brightness roughly as its cube
    root, so linear 8-bit values waste codes on the highlights and band in the shadows. sRGB
    stores :math:`V = 1.055\,L^{1/2.4} - 0.055` (a straight segment :math:`12.92\,L` below
    :math:`L = 0.0031308`); a display undoes it. Mid-grey, 18 % of white, is stored near 0.46.

    Parameters
    ----------
    linear : array_like
        Linear values in [0, 1] (outside is clipped).

    Returns
    -------
    float ndarray
        sRGB-encoded values in [0, 1], the input's shape.

    References
    ----------
    .. [1] IEC 61966-2-1:1999, Multimedia systems and equipment - Colour measurement and
       management - Part 2-1: Default RGB colour space - sRGB.

    Examples
    --------
    >>> np.round(gamma_encode(np.array([0.0, 0.18, 1.0])), 3)
    array([0.   , 0.461, 1.   ])
    """
    L = np.clip(np.asarray(linear, dtype=float), 0.0, 1.0)
    return np.where(L <= 0.0031308, 12.92 * L, 1.055 * L ** (1 / 2.4) - 0.055)


def gamma_decode(encoded: ArrayLike) -> np.ndarray:
    r"""Inverse of :func:`gamma_encode`: sRGB-encoded values in [0, 1] (a JPEG's) back to linear light.

    :math:`L = ((V + 0.055) / 1.055)^{2.4}`, and :math:`V / 12.92` below :math:`V = 0.04045`:
    what a display does, and what a photometric computation must do first to a JPEG's values.

    Parameters
    ----------
    encoded : array_like
        sRGB-encoded values in [0, 1] (outside is clipped).

    Returns
    -------
    float ndarray
        Linear values in [0, 1], the input's shape.

    References
    ----------
    .. [1] IEC 61966-2-1:1999, Multimedia systems and equipment - Colour measurement and
       management - Part 2-1: Default RGB colour space - sRGB.

    Examples
    --------
    >>> np.round(gamma_decode(np.array([0.0, 0.5, 1.0])), 3)  # half the code is a fifth of the light
    array([0.   , 0.214, 1.   ])
    """
    V = np.clip(np.asarray(encoded, dtype=float), 0.0, 1.0)
    return np.where(V <= 0.04045, V / 12.92, ((V + 0.055) / 1.055) ** 2.4)


def white_balance(rgb: ArrayLike, white: ArrayLike | None = None) -> np.ndarray:
    r"""Scale each channel so that ``white`` (an RGB triple seen on a white or grey surface) becomes grey.

    Under warm light a white wall records as, say, (1.0, 0.8, 0.55). Dividing every pixel by
    that triple (von Kries scaling, then normalising to the green channel) makes the wall
    neutral again. With ``white=None`` the *grey-world* assumption estimates it as the mean
    colour of the whole image. Works on linear (not gamma-encoded) values; clipped to [0, 1].

    Parameters
    ----------
    rgb : (H, W, 3) array_like
        Linear RGB image.
    white : (3,) array_like, optional
        The RGB a white or grey surface records (all > 0); None: the image's mean colour
        (grey world).

    Returns
    -------
    (H, W, 3) float ndarray
        The balanced image, green channel unchanged, clipped to [0, 1].

    Examples
    --------
    >>> white_balance(np.array([[[0.5, 0.4, 0.275]]]), white=[1.0, 0.8, 0.55])
    array([[[0.4, 0.4, 0.4]]])
    """
    img = check_image(rgb, "rgb", channels=(3,)).astype(float)
    w = img.reshape(-1, 3).mean(axis=0) if white is None else np.asarray(white, dtype=float)
    if w.shape != (3,) or not np.all(w > 0):
        raise CamlabInputError(
            f"white: expected three positive channel values (R, G, B), got {np.asarray(w).tolist()}"
        )
    return np.clip(img * (w[1] / w), 0.0, 1.0)
