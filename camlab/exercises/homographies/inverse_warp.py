"""Exercise 5 of lesson 07: warping an image by inverse mapping, nearest neighbour (`warp_nearest`)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from .._answers import shape_problem, type_problem
from .._core import Exercise, Mistake, first_mistake, register_exercise

_MISMATCH_ALLOWED = 0.002
"""The fraction of output pixels that may differ: only sample points within float rounding of a tie
between two pixels (u = k + 0.5), where np.rint, floor(u + 0.5) and cv2 may round either way."""


def _images():
    rng = np.random.default_rng(7)
    return [rng.integers(10, 250, shape).astype(float) for shape in ((24, 32), (30, 40), (20, 36))]


def _warp_cases():
    a, b, c = _images()
    cs, sn = 1.6 * np.cos(0.35), 1.6 * np.sin(0.35)
    similarity = np.array([[cs, -sn, 12.0], [sn, cs, -4.0], [0.0, 0.0, 1.0]])
    tilt = 2.0 * np.array([[0.9, 0.15, 8.0], [-0.1, 1.1, 5.0], [1.2e-3, 2.5e-3, 1.0]])  # h33 = 2
    shrink = np.array([[0.7, 0.12, 3.3], [-0.1, 0.72, 6.1], [0.0, 0.0, 1.0]])
    # each output differs from its image in shape and has height != width: a swapped shape shows
    return [(a, similarity, (50, 64)), (b, tilt, (56, 48)), (c, shrink, (30, 34))]


def _warp(
    image,
    M,
    out_shape,
    *,
    rounding=np.rint,
    shift=0.0,
    divide=True,
    early=False,
    clamp=False,
    lower=True,
    top=1,
    swap=False,
    first=0,
):
    """Nearest-neighbour sampling of ``image`` at M (u', v', 1) for every output pixel, with slips as options.

    ``lower=False`` drops the test iu >= 0 (negative indices wrap to the far side, as numpy's do),
    ``first=1`` tests iu >= 1 (1-based), ``top=2`` tests iu < width - 1, ``swap=True`` reads
    image[u, v] with the bounds swapped to match.
    """
    h, w = np.shape(image)[:2]
    if swap:
        image, h, w = np.asarray(image).T, w, h
    v, u = np.mgrid[0 : out_shape[0], 0 : out_shape[1]]
    X = np.stack([u + shift, v + shift, np.ones_like(u)], axis=-1) @ np.asarray(M, dtype=float).T
    with np.errstate(divide="ignore", invalid="ignore"):
        su, sv = (
            (X[..., 0] / X[..., 2], X[..., 1] / X[..., 2]) if divide else (X[..., 0], X[..., 1])
        )
    iu, iv = rounding(su), rounding(sv)
    low_u, low_v = (iu >= first, iv >= first) if lower else (iu >= -w, iv >= -h)
    inside = (
        (su >= 0) & (su <= w - 1) & (sv >= 0) & (sv <= h - 1)
        if early
        else low_u & (iu <= w - top) & low_v & (iv <= h - top)
    )
    if clamp:
        inside = np.isfinite(iu) & np.isfinite(iv)
    low_w, low_h = (0, 0) if clamp else (-w, -h)  # clamp: np.clip(iu, 0, w - 1), the real slip
    iu = np.clip(np.nan_to_num(iu), low_w, w - 1).astype(int) % w
    iv = np.clip(np.nan_to_num(iv), low_h, h - 1).astype(int) % h
    return np.where(inside, np.asarray(image, dtype=float)[iv, iu], 0.0)


def _reference(image, H, out_shape):
    """Inverse mapping: each output pixel reads the source pixel nearest to H^-1 (u', v', 1)."""
    return _warp(image, np.linalg.inv(np.asarray(H, dtype=float)), out_shape)


def _bilinear(image, H, out_shape):
    """The same warp with bilinear interpolation (cv2.INTER_LINEAR's sample points, no fixed point)."""
    img = np.asarray(image, dtype=float)
    h, w = img.shape
    v, u = np.mgrid[0 : out_shape[0], 0 : out_shape[1]]
    X = np.stack([u, v, np.ones_like(u)], axis=-1) @ np.linalg.inv(H).T
    su, sv = X[..., 0] / X[..., 2], X[..., 1] / X[..., 2]
    u0, v0 = np.floor(su).astype(int), np.floor(sv).astype(int)
    fu, fv = su - u0, sv - v0
    padded = np.pad(img, 1)
    out = np.zeros(su.shape)
    for du, dv in ((0, 0), (1, 0), (0, 1), (1, 1)):
        weight = (fu if du else 1 - fu) * (fv if dv else 1 - fv)
        cu, cv = np.clip(u0 + du + 1, 0, w + 1), np.clip(v0 + dv + 1, 0, h + 1)
        out += weight * padded[cv, cu]
    return out


def _camlab_bilinear(image, H, out_shape):
    """camlab's own warp at its default, bilinear (pixels straddling the border blend with 0)."""
    from ...warp import warp_perspective

    return warp_perspective(np.asarray(image, dtype=float), H, out_shape, interpolation="bilinear")


def _cv2_default(image, H, out_shape):
    """cv2.warpPerspective with its default flags: bilinear, with OpenCV's 1/32-pixel fixed-point weights."""
    import cv2

    return cv2.warpPerspective(
        np.asarray(image, dtype=float), np.asarray(H, dtype=float), tuple(out_shape)[::-1]
    )


def _forward(image, H, out_shape):
    """Forward mapping: push each source pixel to the output pixel nearest to H (u, v, 1)."""
    h, w = np.shape(image)
    v, u = np.mgrid[0:h, 0:w]
    X = np.stack([u, v, np.ones_like(u)], axis=-1) @ np.asarray(H, dtype=float).T
    iu, iv = np.rint(X[..., 0] / X[..., 2]).astype(int), np.rint(X[..., 1] / X[..., 2]).astype(int)
    keep = (iu >= 0) & (iu < out_shape[1]) & (iv >= 0) & (iv < out_shape[0])
    out = np.zeros(out_shape)
    out[iv[keep], iu[keep]] = np.asarray(image, dtype=float)[v[keep], u[keep]]
    return out


def _indexed_image_u_v(image, H, out_shape):
    """The slip image[u, v] (column first), with the range test of image[v, u]: an IndexError."""
    Hinv = np.linalg.inv(H)
    out = np.zeros(out_shape)
    for v_out in range(out_shape[0]):
        for u_out in range(out_shape[1]):
            x, y, w = Hinv @ [u_out, v_out, 1.0]
            u, v = int(np.rint(x / w)), int(np.rint(y / w))
            if 0 <= u < image.shape[1] and 0 <= v < image.shape[0]:
                out[v_out, u_out] = image[u, v]
    return out


def _indexed_u_v_caught(image, H, out_shape, flip=False):
    """The slip image[u, v] with image[v, u]'s bounds, inside try/except IndexError: 0 where it raised.

    ``flip=True`` also lifts the output pixel as (v', u', 1), the compound slip.
    """
    image = np.asarray(image, dtype=float)
    h, w = image.shape[:2]
    v, u = np.mgrid[0 : out_shape[0], 0 : out_shape[1]]
    M = np.linalg.inv(np.asarray(H, dtype=float)) @ (_FLIP if flip else np.eye(3))
    X = np.stack([u, v, np.ones_like(u)], axis=-1) @ M.T
    iu, iv = np.rint(X[..., 0] / X[..., 2]).astype(int), np.rint(X[..., 1] / X[..., 2]).astype(int)
    tested = (iu >= 0) & (iu < w) & (iv >= 0) & (iv < h)
    read = tested & (iu < h) & (iv < w)  # passes the test, no IndexError
    return np.where(read, image[np.clip(iu, 0, h - 1), np.clip(iv, 0, w - 1)], 0.0)


def _bounds_swapped(image, H, out_shape):
    """The slip 0 <= iu < image.shape[0] (the height) and 0 <= iv < image.shape[1], an IndexError caught."""
    image = np.asarray(image, dtype=float)
    h, w = image.shape[:2]
    v, u = np.mgrid[0 : out_shape[0], 0 : out_shape[1]]
    X = np.stack([u, v, np.ones_like(u)], axis=-1) @ np.linalg.inv(np.asarray(H, dtype=float)).T
    iu, iv = np.rint(X[..., 0] / X[..., 2]).astype(int), np.rint(X[..., 1] / X[..., 2]).astype(int)
    tested = (iu >= 0) & (iu < h) & (iv >= 0) & (iv < w)  # the swapped test
    read = tested & (iu < w) & (iv < h)  # beyond the array: IndexError, caught, 0
    return np.where(read, image[np.clip(iv, 0, h - 1), np.clip(iu, 0, w - 1)], 0.0)


def _warp_source_one_based(image, H, out_shape):
    """A loop that counts source pixels from 1: image[v - 1, u - 1] for 1 <= u <= width (a slip)."""
    Hinv = np.linalg.inv(np.asarray(H, dtype=float))
    out = np.zeros(out_shape)
    for v_out in range(out_shape[0]):
        for u_out in range(out_shape[1]):
            x, y, w = Hinv @ [u_out, v_out, 1.0]
            u, v = int(np.rint(x / w)), int(np.rint(y / w))
            if 1 <= u <= image.shape[1] and 1 <= v <= image.shape[0]:
                out[v_out, u_out] = image[v - 1, u - 1]
    return out


_FLIP = np.array([[0.0, 1, 0], [1, 0, 0], [0, 0, 1]])  # (u', v', 1) -> (v', u', 1)


def _third_row_constant(M):
    """M with its third row (0, 0, m33): dividing by it is dividing by m33 instead of by w."""
    return np.vstack([M[:2], [0.0, 0.0, M[2, 2]]])


def _loops_swapped(image, H, out_shape):
    """Loops over range(out_shape[1]) rows and range(out_shape[0]) columns, writes past the array skipped."""
    out, n = np.zeros(out_shape), min(out_shape)
    out[:n, :n] = _reference(image, H, out_shape)[:n, :n]
    return out


def _same_picture(got, expected) -> bool:
    """Same shape, and all but :data:`_MISMATCH_ALLOWED` of the pixels equal (within float32 rounding)."""
    try:
        g = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        return False
    if g.shape != np.shape(expected):
        return False
    return bool(np.mean(~np.isclose(g, expected, rtol=1e-5, atol=1e-3)) <= _MISMATCH_ALLOWED)


_PULL = "each output pixel (u', v') reads image[v, u] at the nearest pixel to H^-1 (u', v', 1), divided by w"

_WARP_MISTAKES = (
    Mistake(
        "H for H^-1",
        lambda c: _warp(c.image, c.H, c.shape),
        "you sampled the source at H (u', v', 1): that pushes the *output* pixel forward. Inverse mapping "
        "pulls from where the output pixel came from, H^-1 (u', v', 1): Hinv = np.linalg.inv(H).",
    ),
    Mistake(
        "H^T",
        lambda c: _warp(c.image, np.linalg.inv(c.H).T, c.shape),
        "you used H^-1 transposed: with pixels as rows, multiply by Hinv.T (X @ Hinv.T), or as columns "
        "by Hinv itself (Hinv @ x), not both transposes at once.",
    ),
    Mistake(
        "no division by w",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, divide=False),
        "you did not divide by w, the third coordinate of H^-1 (u', v', 1): the source point is (x/w, y/w). "
        "H^-1 is not scaled to h33 = 1 here (and has a projective row in test 2), so w is not 1.",
    ),
    Mistake(
        "lifted (v', u', 1)",
        lambda c: _warp(c.image, np.linalg.inv(c.H) @ _FLIP, c.shape),
        "you lifted the output pixel as (v', u', 1): out[v', u'] is the point (u', v') (column first), "
        "so map Hinv @ [u_out, v_out, 1], with the column index first.",
    ),
    Mistake(
        "divided by Hinv[2, 2]",
        lambda c: _warp(c.image, _third_row_constant(np.linalg.inv(c.H)), c.shape),
        "you divided by Hinv[2, 2] (h33 of H^-1), but w is the third coordinate of each mapped point, "
        "w = h31 u' + h32 v' + h33, which changes from pixel to pixel (test 2's H has a projective row): "
        "divide by the w of Hinv @ [u', v', 1] itself (exercise 1's slip, here with H^-1).",
    ),
    Mistake(
        "scaled to h33 = 1, no division",
        lambda c: _warp(c.image, np.linalg.inv(c.H / c.H[2, 2]), c.shape, divide=False),
        "you scaled H to h33 = 1 and then did not divide by w: that fixes only the scale, while w = "
        "h31 u' + h32 v' + h33 of Hinv @ [u', v', 1] still changes from pixel to pixel (test 2's H has a "
        "projective row). Divide x and y by that w.",
    ),
    Mistake(
        "loops over out_shape swapped",
        lambda c: _loops_swapped(c.image, c.H, c.shape),
        "only the top-left square of the output is filled, as if your loops ran v' over "
        "range(out_shape[1]) and u' over range(out_shape[0]). out_shape is (height, width): loop v' in "
        "range(out_shape[0]) and u' in range(out_shape[1]).",
    ),
    Mistake(
        "truncated",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, rounding=np.floor),
        "you rounded the source point down: np.floor(u), or np.rint(u - 0.5), which is the same almost "
        "everywhere (a half-pixel offset, as if pixel centres sat at half-integers). Either way you read "
        "the pixel to the upper left, half a pixel off on average. The course puts pixel centres at "
        "integers, so the nearest pixel is np.rint(u), np.rint(v), with no offset.",
    ),
    Mistake(
        "int() truncation",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, rounding=np.trunc),
        "you rounded with int(u), which truncates toward zero: it takes the pixel to the upper left of "
        "the point (half a pixel off on average), and for -1 < u < 0 it gives 0, so points just left of "
        "or above the picture read its first column or row. Round to the nearest: int(np.rint(u)).",
    ),
    Mistake(
        "image[u, v]",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, swap=True),
        "you read image[u, v] and tested u against the height, v against the width: numpy images are "
        "image[row v, column u], with height = image.shape[0] rows and width = image.shape[1] columns. "
        "Read image[iv, iu] and test 0 <= iu < width, 0 <= iv < height.",
    ),
    Mistake(
        "image[u, v], IndexError caught",
        lambda c: _indexed_u_v_caught(c.image, c.H, c.shape),
        "you read image[u, v] (column first), with a test that kept the index inside the array: numpy "
        "images are image[row v, column u], so read image[iv, iu] and test 0 <= iu < width and "
        "0 <= iv < height (width = image.shape[1]). If you caught an IndexError, drop the try/except: "
        "it hid the slip.",
    ),
    *(
        Mistake(
            f"lifted (v', u', 1) and image[u, v] {how}",
            slip,
            "you swapped u and v twice: you lifted the output pixel as (v', u', 1) and read the source "
            "as image[u, v]. The two swaps do not cancel (H^-1 mixes the coordinates). Lift (u', v', 1), "
            "column first, and read image[iv, iu], row first; drop any try/except that hid an IndexError.",
        )
        for how, slip in (
            (
                "bounds swapped",
                lambda c: _warp(c.image, np.linalg.inv(c.H) @ _FLIP, c.shape, swap=True),
            ),
            ("IndexError caught", lambda c: _indexed_u_v_caught(c.image, c.H, c.shape, flip=True)),
        )
    ),
    Mistake(
        "bounds swapped",
        lambda c: _bounds_swapped(c.image, c.H, c.shape),
        "you read image[iv, iu] but compared iu with image.shape[0] (the height) and iv with "
        "image.shape[1] (the width): shape is (height, width), so width = image.shape[1]. The test "
        "pictures are wider than tall, so columns beyond the height read 0. Test 0 <= iu < "
        "image.shape[1] and 0 <= iv < image.shape[0] (and drop any try/except that hid the IndexError).",
    ),
    Mistake(
        "no lower bound",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, lower=False),
        "you tested only iu < width and iv < height, not iu >= 0 and iv >= 0: numpy reads a negative "
        "index from the far end (image[v, -3] is the third column from the right), so points left of or "
        "above the picture wrap around to its other side. Test 0 <= iu < width and 0 <= iv < height.",
    ),
    Mistake(
        "lower bound -1",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, first=-1),
        "you tested iu >= -1 (and iv >= -1): numpy reads index -1 from the far end (image[v, -1] is the "
        "last column), so points just left of or above the picture read its other side. Valid indices "
        "start at 0: test 0 <= iu < width and 0 <= iv < height.",
    ),
    Mistake(
        "pixel corners, shifted back",
        lambda c: _warp(
            c.image, np.linalg.inv(c.H), c.shape, shift=0.5, rounding=lambda x: np.floor(x - 0.5)
        ),
        "you sampled at H^-1 (u' + 0.5, v' + 0.5, 1) and took np.floor(x - 0.5): two half-pixel shifts "
        "that cancel only where H^-1 is a pure translation; H^-1 scales and turns the first one. The "
        "course puts pixel centres at integers: map the point (u', v') itself and round with np.rint.",
    ),
    Mistake(
        "bound width - 1",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, top=2),
        "you tested iu < width - 1 (and iv < height - 1): off by one, so the last column and row of the "
        "picture are never read. Valid indices run from 0 to width - 1: test 0 <= iu < width "
        "(or iu <= width - 1).",
    ),
    Mistake(
        "bound from 1",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, first=1),
        "you tested iu >= 1 (and iv >= 1), as if pixels were counted from 1: the first column and row "
        "of the picture are never read. Python counts from 0: test 0 <= iu < width and 0 <= iv < height.",
    ),
    Mistake(
        "int(u + 0.5)",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, rounding=lambda x: np.trunc(x + 0.5)),
        "you rounded with int(u + 0.5), which truncates toward zero: for u = -0.7 it gives 0, not -1, so "
        "points just left of or above the picture read its first column or row. Round with np.rint(u) "
        "or np.floor(u + 0.5).",
    ),
    Mistake(
        "rounded up",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, rounding=np.ceil),
        "you rounded the source point up: np.ceil(u), or np.rint(u + 0.5), which is the same almost "
        "everywhere (a half-pixel offset, as if pixel centres sat at half-integers). The course puts "
        "pixel centres at integers, so the nearest pixel is np.rint(u), np.rint(v), with no offset.",
    ),
    *(
        Mistake(
            f"half-pixel offset {sign}",
            lambda c, sign=sign: _warp(
                c.image, np.linalg.inv(c.H), c.shape, shift=float(f"{sign}0.5")
            ),
            f"you mapped (u' {sign} 0.5, v' {sign} 0.5): a half-pixel offset. The course puts pixel centres "
            "at integers, so output pixel (u', v') is the point (u', v') itself.",
        )
        for sign in "+-"
    ),
    Mistake(
        "source counted from 1",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, rounding=lambda x: np.rint(x) - 1),
        "you counted the source pixels from 1 (as MATLAB does): you read image[iv - 1, iu - 1] for "
        "1 <= iu <= width, so every output pixel reads the pixel one up and one left of the right one. "
        "numpy and the course count from 0: the pixel centred at the point (u, v) is image[v, u].",
    ),
    Mistake(
        "output counted from 1",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, shift=1.0),
        "you counted the output pixels from 1 (as MATLAB does): output pixel out[v', u'] was mapped from "
        "the point (u' + 1, v' + 1), so the picture sits one pixel up and left. numpy and the course count "
        "from 0: out[v', u'] is the point (u', v') itself, u' in range(width).",
    ),
    Mistake(
        "output and source counted from 1",
        lambda c: _warp(
            c.image, np.linalg.inv(c.H), c.shape, shift=1.0, rounding=lambda x: np.rint(x) - 1
        ),
        "you counted the pixels from 1 (as MATLAB does), both of them: output pixel out[v', u'] was "
        "mapped from the point (u' + 1, v' + 1) and read image[iv - 1, iu - 1]. The two shifts cancel "
        "only under a pure translation; H^-1 scales and turns the first one. numpy and the course count "
        "from 0: map the point (u', v') itself and read image[iv, iu].",
    ),
    Mistake(
        "pixel corners",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, shift=0.5, rounding=np.floor),
        "you sampled at H^-1 (u' + 0.5, v' + 0.5, 1) and took np.floor: the pixel-*corner* convention, "
        "where pixel k covers [k, k + 1). The course puts pixel centres at integers (pixel k covers "
        "[k - 0.5, k + 0.5)): map the point (u', v') itself and round to the nearest, np.rint.",
    ),
    Mistake(
        "bound width, clamped",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, top=0),
        "you tested iu <= width (and iv <= height) and clamped the index when reading: off by one. Index "
        "width is one past the last column, so output pixels whose source lies just right of or below "
        "the picture repeat its last column or row. Test 0 <= iu < width and 0 <= iv < height.",
    ),
    Mistake(
        "tested before rounding",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, early=True),
        "you tested 0 <= u <= w - 1 before rounding, so source points just outside the pixel centres, such "
        "as u = -0.3, read nothing. Pixel 0 covers -0.5 <= u < 0.5 (extents of ±0.5): round first, then "
        "test the rounded index, 0 <= iu < width.",
    ),
    Mistake(
        "clamped",
        lambda c: _warp(c.image, np.linalg.inv(c.H), c.shape, clamp=True),
        "you clamped the index to the picture (np.clip), so output pixels whose source lies outside the "
        "picture repeat its border pixels. They get 0: keep only 0 <= iu < width and 0 <= iv < height.",
    ),
    Mistake(
        "bilinear",
        lambda c: _bilinear(c.image, c.H, c.shape),
        "you interpolated bilinearly: a fine warp, but the prompt asks for nearest neighbour, one source "
        "pixel per output pixel: image[int(np.rint(v)), int(np.rint(u))].",
    ),
    Mistake(
        "camlab's warp, bilinear",
        lambda c: _camlab_bilinear(c.image, c.H, c.shape),
        "you warped with camlab.warp.warp_perspective at its default, interpolation='bilinear': a fine "
        "warp, but the prompt asks for nearest neighbour, one source pixel per output pixel. Pass "
        "interpolation='nearest', or write the loop: image[int(np.rint(v)), int(np.rint(u))].",
    ),
    Mistake(
        "cv2's default, bilinear",
        lambda c: _cv2_default(c.image, c.H, c.shape),
        "you called cv2.warpPerspective with its default flags, which interpolate bilinearly "
        "(cv2.INTER_LINEAR): a fine warp, but the prompt asks for nearest neighbour. Pass "
        "flags=cv2.INTER_NEAREST, or write the loop: image[int(np.rint(v)), int(np.rint(u))].",
    ),
)
"""The slips of an inverse nearest-neighbour warp, in the order they are tested."""


def _warp_diagnosis(args, got, expected) -> str:
    image, H, out_shape = args
    nan_outside = _nan_outside(got, expected)
    if nan_outside:
        return nan_outside
    problem = shape_problem(got, expected)
    if problem:
        g_shape = (
            np.shape(np.asarray(got, dtype=float)) if not type_problem(got, expected) else None
        )
        if g_shape == tuple(out_shape)[::-1]:
            return (
                f"your output is {g_shape}, (width, height): out_shape is (rows, columns) = (height, width), "
                "as numpy arrays are; make it with np.zeros(out_shape)."
            )
        return problem + ". Return the warped picture, an array of shape out_shape."
    context = SimpleNamespace(image=image, H=np.asarray(H, dtype=float), shape=tuple(out_shape))
    cause = first_mistake(_WARP_MISTAKES, context, got, _same_picture)
    if cause:
        return cause
    g = np.asarray(got, dtype=float)
    holes = (g == 0) & (np.asarray(expected) != 0)
    if (
        holes.mean() > 0.02
        and _same_picture(g, _forward(image, H, out_shape))
        or holes.mean() > 0.2
    ):
        forward = _same_picture(g, _forward(image, H, out_shape))
        return f"{holes.mean():.0%} of the picture's output pixels stayed 0. " + (
            "Those are holes, as forward mapping leaves them (pushing each source pixel to H x): loop "
            "over the *output* pixels instead and pull each one's value from H^-1 (u', v', 1)."
            if forward
            else "If you push source pixels forward, that leaves holes: loop over the *output* pixels. If "
            "you already do, check what each reads: " + _PULL + ", tested 0 <= iu < width and "
            "0 <= iv < height (drop any try/except that hides an IndexError)."
        )
    return _PULL + "; outside the picture, 0 (with cv2.warpPerspective: flags=cv2.INTER_NEAREST)."


def _nan_outside(got, expected) -> str:
    """The cause when the picture is right but the pixels outside it hold NaN ("" otherwise)."""
    try:
        g = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        return ""
    e = np.asarray(expected, dtype=float)
    nan = np.isnan(g) if g.shape == e.shape else np.zeros(0, bool)
    if not nan.any() or not np.allclose(g[~nan], e[~nan]) or np.any(e[nan] != 0):
        return ""
    return (
        f"the picture is right, but {nan.mean():.0%} of the output pixels hold NaN: those whose source "
        "point lies outside the picture. There the output stays 0: start from np.zeros(out_shape) "
        "(not np.full(out_shape, np.nan) or np.empty) and write only the pixels that pass the test."
    )


def _index_hint(exc: Exception, args: tuple) -> str:
    sizes = {f"with size {n}" for n in args[2]} - {f"with size {n}" for n in np.shape(args[0])}
    if isinstance(exc, IndexError) and any(size in str(exc) for size in sizes):
        return (
            "an index ran past the *output* array: out_shape is (height, width), so loop v' over "
            "range(out_shape[0]) and u' over range(out_shape[1]) and write out[v', u']."
        )
    if isinstance(exc, IndexError):
        return (
            "an index ran past the picture. Images are indexed image[v, u] (row v first, column u second), "
            "and the source pixel must pass 0 <= iu < width and 0 <= iv < height (width = image.shape[1]) "
            "before you read it; otherwise the output pixel stays 0."
        )
    return ""


def warp_nearest(image, H, out_shape):
    """Warp ``image`` by H with inverse mapping and nearest-neighbour sampling.

    Every output pixel (u', v') pulls its value from the source point x = H^-1 (u', v', 1), divided
    by its third coordinate, rounded to the nearest pixel centre (centres at integers); if that
    pixel lies outside the picture, the output pixel stays 0. Every output pixel gets exactly one
    value, so there are no holes.

    Parameters
    ----------
    image : (height, width) ndarray
        The source picture, indexed image[v, u].
    H : (3, 3) array_like
        The homography from source pixels to output pixels (w below is the third coordinate).
    out_shape : (height, width)
        The size of the output.

    Returns
    -------
    (height, width) ndarray
        The warped picture, float, 0 where the source point lies outside the picture.

    References
    ----------
    Szeliski, Computer Vision: Algorithms and Applications, 2nd ed., section 3.6.1 (inverse warping).
    """
    Hinv = np.linalg.inv(np.asarray(H, dtype=float))
    out = np.zeros(out_shape)
    for v_out in range(out_shape[0]):
        for u_out in range(out_shape[1]):
            x, y, w = Hinv @ [u_out, v_out, 1.0]
            u, v = int(np.rint(x / w)), int(np.rint(y / w))
            if 0 <= u < image.shape[1] and 0 <= v < image.shape[0]:
                out[v_out, u_out] = image[v, u]
    return out


register_exercise(
    Exercise(
        name="warp_nearest",
        lesson="07",
        reference=_reference,
        cases=_warp_cases,
        compare=_same_picture,
        diagnose=_warp_diagnosis,
        exception_hint=_index_hint,
        solution_note=(
            "# camlab: camlab.warp.warp_perspective(image, H, out_shape, interpolation='nearest'), or\n"
            "# cv2.warpPerspective(image, H, (width, height), flags=cv2.INTER_NEAREST), compute the same"
        ),
        wrong_variants=(
            (lambda im, H, s: _warp(im, H, s), "H (u', v', 1)"),
            (lambda im, H, s: _warp(im, np.linalg.inv(H), s, first=1), "counted from 1"),
            (
                lambda im, H, s: _warp(
                    im, np.linalg.inv(H), s, shift=1.0, rounding=lambda x: np.rint(x) - 1
                ),
                "counted the pixels from 1 (as MATLAB does), both",
            ),
            (
                lambda im, H, s: np.where(_reference(im, H, s) == 0, np.nan, _reference(im, H, s)),
                "hold NaN",
            ),
            (lambda im, H, s: _warp(im, np.linalg.inv(H).T, s), "transposed"),
            (lambda im, H, s: _warp(im, np.linalg.inv(H), s, divide=False), "divide by w"),
            (
                lambda im, H, s: _warp(im, np.linalg.inv(H), s, rounding=np.floor),
                "rounded the source point down",
            ),
            (lambda im, H, s: _warp(im, np.linalg.inv(H), s, shift=0.5), "half-pixel offset"),
            (lambda im, H, s: _warp(im, np.linalg.inv(H), s, shift=-0.5), "u' - 0.5"),
            (
                lambda im, H, s: _warp(
                    im, np.linalg.inv(H), s, rounding=lambda x: np.rint(x + 0.5)
                ),
                "np.rint(u + 0.5)",
            ),
            (
                lambda im, H, s: _warp(
                    im, np.linalg.inv(H), s, rounding=lambda x: np.rint(x - 0.5)
                ),
                "np.rint(u - 0.5)",
            ),
            (_warp_source_one_based, "source pixels from 1"),
            (lambda im, H, s: _warp(im, np.linalg.inv(H), s, shift=1.0), "output pixels from 1"),
            (
                lambda im, H, s: _warp(
                    im, np.linalg.inv(H), s, rounding=lambda x: np.trunc(x + 0.5)
                ),
                "truncates toward zero",
            ),
            (lambda im, H, s: _warp(im, np.linalg.inv(H), s, early=True), "before rounding"),
            (lambda im, H, s: _warp(im, np.linalg.inv(H), s, clamp=True), "clamped"),
            (lambda im, H, s: _bilinear(im, H, s), "bilinearly"),
            (lambda im, H, s: _forward(im, H, s), "forward mapping"),
            (lambda im, H, s: _reference(im, H, s).T, "(rows, columns)"),
            (lambda im, H, s: _reference(im, H, s).tolist(), "list"),
            (_indexed_image_u_v, "image[v, u]"),
            (_indexed_u_v_caught, "If you caught an IndexError"),
            (lambda im, H, s: _warp(im, np.linalg.inv(H), s, rounding=np.trunc), "toward zero"),
            (lambda im, H, s: _warp(im, np.linalg.inv(H), s, swap=True), "image[row v, column u]"),
            (lambda im, H, s: _warp(im, np.linalg.inv(H), s, lower=False), "negative index"),
            (lambda im, H, s: _warp(im, np.linalg.inv(H), s, first=-1), "index -1"),
            (
                lambda im, H, s: _warp(
                    im, np.linalg.inv(H), s, shift=0.5, rounding=lambda x: np.floor(x - 0.5)
                ),
                "two half-pixel shifts",
            ),
            (
                lambda im, H, s: _warp(im, np.linalg.inv(H) @ _FLIP, s, swap=True),
                "swapped u and v twice",
            ),
            (lambda im, H, s: _indexed_u_v_caught(im, H, s, flip=True), "swapped u and v twice"),
            (lambda im, H, s: _warp(im, np.linalg.inv(H), s, top=2), "off by one"),
            (lambda im, H, s: _warp(im, np.linalg.inv(H), s, top=0), "iu <= width"),
            (
                lambda im, H, s: _warp(im, np.linalg.inv(H), s, shift=0.5, rounding=np.floor),
                "pixel-*corner*",
            ),
            (_cv2_default, "cv2.INTER_NEAREST"),
            (lambda im, H, s: _warp(im, np.linalg.inv(H) @ _FLIP, s), "lifted the output pixel"),
            (lambda im, H, s: _warp(im, _third_row_constant(np.linalg.inv(H)), s), "Hinv[2, 2]"),
            (
                lambda im, H, s: _warp(im, np.linalg.inv(H / H[2, 2]), s, divide=False),
                "scaled H to h33 = 1",
            ),
            (_loops_swapped, "range(out_shape[1])"),
        ),
        ndarray_only=True,
        teaching=warp_nearest,
    )
)
