"""Wrong answers to lesson 03's demosaicking exercise that the check must diagnose (its wrong variants).

Each is a typical slip written out; :mod:`.demosaic` feeds them to its check and expects the hint
named beside each.
"""

from __future__ import annotations

import numpy as np

from ... import sensor


def uncast_demosaic(raw, pattern):
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


def tiled_masks_demosaic(raw, pattern):
    """Masks from np.tile(block, (H // 2, W // 2)): one row or column short on an odd-sized mosaic."""
    raw = np.asarray(raw, dtype=float)
    H, W = raw.shape
    blocks = [np.array([[pattern[0], pattern[1]], [pattern[2], pattern[3]]]) == c for c in "RGB"]
    masks = np.stack([np.tile(b, (H // 2, W // 2)) for b in blocks], axis=2)
    return np.where(
        masks, raw[..., None], sensor.demosaic_bilinear(raw, pattern)
    )  # crashes: (H, W, 1) vs masks


def fill_by_normalised_convolution(raw, m, k):
    """Each channel's missing samples as the k-weighted mean of the channel's samples (masks m)."""
    from scipy.ndimage import convolve

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


def cross_kernel_demosaic(raw, pattern):
    """Green's cross kernel used for red and blue too: 0 / 0 (NaN) at red's blue sites and blue's red ones."""
    raw = np.asarray(raw, dtype=float)
    m = sensor.bayer_masks(raw.shape, pattern).astype(float)
    k = np.array([[0, 1, 0], [1, 4, 1], [0, 1, 0]]) / 4.0
    return fill_by_normalised_convolution(raw, m, k)


def one_based_masks_demosaic(raw, pattern):
    """Masks translated from 1-based MATLAB: m[1::2, 1::2] for the first letter, m[2::2, 2::2] for the last."""
    raw = np.asarray(raw, dtype=float)
    m = np.zeros(raw.shape + (3,))
    for (dy, dx), colour in zip([(1, 1), (1, 2), (2, 1), (2, 2)], pattern, strict=True):
        m[dy::2, dx::2, "RGB".index(colour)] = 1
    k = np.array([[1, 2, 1], [2, 4, 2], [1, 2, 1]]) / 4.0
    return fill_by_normalised_convolution(raw, m, k)


def opencv_ring_demosaic(raw, pattern):
    """cv2.cvtColor on the integer mosaic: the right image inside, rounded, with OpenCV's own outermost ring.

    The ring is imitated by copies of the next ring in; float mosaics (which cvtColor refuses) get the right image.
    """
    out = sensor.demosaic_bilinear(raw, pattern)
    if not np.issubdtype(np.asarray(raw).dtype, np.integer):
        return out
    out = np.rint(out)
    out[0], out[-1], out[:, 0], out[:, -1] = out[1], out[-2], out[:, 1], out[:, -2]
    return out


def opencv_demosaic(raw, pattern, via_codes=True):
    """cv2.cvtColor itself; ``via_codes`` first turns a float mosaic into uint8 codes (it refuses floats)."""
    import cv2

    r = np.asarray(raw)
    code = getattr(cv2, f"COLOR_Bayer{pattern}2RGB")
    if r.dtype.kind == "f" and via_codes:
        codes = np.clip(np.rint(r * 255), 0, 255).astype(np.uint8)
        return cv2.cvtColor(codes, code).astype(float) / 255
    return cv2.cvtColor(r, code).astype(float)
