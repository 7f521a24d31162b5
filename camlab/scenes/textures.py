"""Textures: read-only arrays (cached where they are pure functions of hashable arguments).

Sizes are (width, height) and shapes (height, width) (docs/conventions.md).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, check_shape, check_size


def as_texture(texture: ArrayLike) -> np.ndarray:
    """``texture`` as a read-only float32 (H, W) or (H, W, 3) array in [0, 1].

    Integers are divided by their dtype's maximum; an alpha channel is dropped.

    Parameters
    ----------
    texture : (H, W), (H, W, 3) or (H, W, 4) array_like
        A grey, RGB or RGBA image, integer or float (floats are taken as they are).

    Returns
    -------
    (H, W) or (H, W, 3) float32 ndarray
        The texture, C-contiguous and read-only.

    Raises
    ------
    CamlabInputError
        If the shape or dtype is not an image's.
    """
    a = np.asarray(texture)
    if a.ndim == 3 and a.shape[2] == 4:
        a = a[..., :3]
    if not (a.ndim == 2 or (a.ndim == 3 and a.shape[2] == 3)) or min(a.shape[:2]) < 1:
        raise CamlabInputError(
            f"texture: expected an (H, W) or (H, W, 3) image, got shape {a.shape}"
        )
    if np.issubdtype(a.dtype, np.integer):
        a = a / np.iinfo(a.dtype).max
    elif not np.issubdtype(a.dtype, np.floating):
        raise CamlabInputError(f"texture: expected a float or integer image, got dtype {a.dtype}")
    a = np.ascontiguousarray(a, dtype=np.float32)
    a.setflags(write=False)
    return a


@lru_cache(maxsize=1)
def portrait() -> np.ndarray:
    """matplotlib's bundled Grace Hopper photograph (no network): a read-only float32 (H, W, 3) texture in [0, 1].

    The one sample photograph of the synthetic scenes (:func:`photo_plane`,
    :func:`painting_texture`, the stereo scene). Real photographs are in
    :func:`camlab.data.load_photo`.

    Returns
    -------
    (600, 512, 3) float32 ndarray
        The photograph (sRGB-encoded values, as the JPEG holds them), computed once.
    """
    import matplotlib.image as mpimg
    from matplotlib import cbook

    with cbook.get_sample_data("grace_hopper.jpg") as f:
        img = mpimg.imread(f, format="jpg")
    return as_texture(img)


def page_texture(size: tuple[int, int] = (420, 594), seed: int = 0) -> np.ndarray:
    """A printed page (A4 proportions, 1 : sqrt 2): title, paragraphs of text, a figure box.

    Drawn with ``cv2.putText``.

    Parameters
    ----------
    size : (width, height)
        The page's size, pixels.
    seed : int
        Seed of the words' choice.

    Returns
    -------
    (height, width, 3) uint8 ndarray
        RGB, cached and read-only (copy before drawing on it).
    """
    return _page_texture(*check_size(size), int(seed))


@lru_cache(maxsize=8)
def _page_texture(width: int, height: int, seed: int) -> np.ndarray:
    import cv2

    rng = np.random.default_rng(seed)
    page = np.full((height, width, 3), 250, np.uint8)
    cv2.putText(
        page,
        "Projective Geometry",
        (int(0.08 * width), int(0.09 * height)),
        cv2.FONT_HERSHEY_DUPLEX,
        width / 560,
        (20, 20, 20),
        2,
        cv2.LINE_AA,
    )
    words = [
        "camera",
        "plane",
        "homography",
        "line",
        "point",
        "image",
        "ray",
        "scale",
        "view",
        "map",
    ]
    y = int(0.16 * height)
    line_h = max(12, height // 34)
    box_top = int(0.55 * height)
    while y < height - int(0.06 * height):
        if box_top <= y < box_top + int(0.2 * height):
            y = box_top + int(0.2 * height) + line_h
            continue
        text = " ".join(rng.choice(words, size=5))
        cv2.putText(
            page,
            text,
            (int(0.08 * width), y),
            cv2.FONT_HERSHEY_SIMPLEX,
            width / 1100,
            (40, 40, 40),
            1,
            cv2.LINE_AA,
        )
        y += line_h
    x0, x1 = int(0.2 * width), int(0.8 * width)
    y0, y1 = box_top, box_top + int(0.18 * height)
    # a figure in grey ink: the lesson's colours (green truth, red refused, blue across) stay its own
    cv2.rectangle(page, (x0, y0), (x1, y1), (70, 70, 70), 2)
    cv2.line(page, (x0, y1), (x1, y0), (110, 110, 110), 2, cv2.LINE_AA)
    cv2.circle(page, ((x0 + x1) // 2, (y0 + y1) // 2), (y1 - y0) // 4, (90, 90, 90), 2, cv2.LINE_AA)
    page.flags.writeable = False  # cached: copy before drawing on it
    return page


def facade_texture(
    size: tuple[int, int] = (480, 360), floors: int = 4, bays: int = 6
) -> np.ndarray:
    """A building facade: brick-coloured wall, a grid of ``floors`` x ``bays`` windows, a door.

    Parameters
    ----------
    size : (width, height)
        The facade's size, pixels.
    floors, bays : int
        Rows and columns of windows (the door replaces the middle window of the bottom row).

    Returns
    -------
    (height, width, 3) uint8 ndarray
        RGB, cached and read-only.
    """
    return _facade_texture(*check_size(size), int(floors), int(bays))


@lru_cache(maxsize=8)
def _facade_texture(width: int, height: int, floors: int, bays: int) -> np.ndarray:
    import cv2

    wall = np.empty((height, width, 3), np.uint8)
    wall[:] = (178, 102, 76)
    for r in range(0, height, 12):  # brick courses
        cv2.line(wall, (0, r), (width - 1, r), (150, 86, 64), 1)
    cw, ch = width / bays, height / (floors + 0.4)
    for f in range(floors):
        for b in range(bays):
            x0, y0 = int(b * cw + 0.25 * cw), int(0.3 * ch + f * ch)
            x1, y1 = int(x0 + 0.5 * cw), int(y0 + 0.6 * ch)
            if f == floors - 1 and b == bays // 2:
                continue
            cv2.rectangle(wall, (x0, y0), (x1, y1), (235, 235, 225), -1)
            cv2.rectangle(wall, (x0 + 3, y0 + 3), (x1 - 3, y1 - 3), (70, 110, 150), -1)
            cv2.line(wall, ((x0 + x1) // 2, y0), ((x0 + x1) // 2, y1), (235, 235, 225), 2)
    b = bays // 2
    x0, x1 = int(b * cw + 0.25 * cw), int(b * cw + 0.75 * cw)
    cv2.rectangle(wall, (x0, int(height - 0.85 * ch)), (x1, height - 1), (90, 60, 40), -1)
    wall.flags.writeable = False  # cached: copy before drawing on it
    return wall


@lru_cache(maxsize=8)
def painting_texture(width: int = 400) -> np.ndarray:
    """A framed painting: :func:`portrait` inside a gold frame. (h, w, 3) uint8, read-only.

    Parameters
    ----------
    width : int
        The frame's outer width, pixels (the frame is 20 px wide on every side).

    Returns
    -------
    (h, width, 3) uint8 ndarray
        RGB, the portrait's aspect plus the frame; cached and read-only.
    """
    import cv2

    art = np.round(portrait() * 255).astype(np.uint8)  # the JPEG's own uint8 values
    scale = (width - 40) / art.shape[1]
    art = cv2.resize(
        art, (width - 40, int(round(art.shape[0] * scale))), interpolation=cv2.INTER_AREA
    )
    frame = np.empty((art.shape[0] + 40, width, 3), np.uint8)
    frame[:] = (170, 130, 50)
    cv2.rectangle(frame, (6, 6), (width - 7, frame.shape[0] - 7), (210, 170, 80), 4)
    frame[20:-20, 20:-20] = art
    frame.flags.writeable = False  # cached: copy before drawing on it
    return frame


def desk_background(shape: tuple[int, int] = (480, 640), seed: int = 0) -> np.ndarray:
    """A dark wooden-desk background, (height, width, 3) uint8 for ``shape`` = (height, width).

    Cached and read-only: demos re-photograph on every slider move.

    Parameters
    ----------
    shape : (height, width)
        The background's shape, pixels.
    seed : int
        Seed of its grain.

    Returns
    -------
    (height, width, 3) uint8 ndarray
        RGB, cached and read-only.
    """
    return _desk_background(*check_shape(shape), int(seed))


@lru_cache(maxsize=4)
def _desk_background(h: int, w: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    yy, xx = np.mgrid[0:h, 0:w]
    base = 70 + 25 * np.sin(xx / 37.0) * np.cos(yy / 53.0) + rng.normal(0, 4, (h, w))
    bg = np.clip(np.stack([base * 0.9, base * 0.75, base * 0.6], axis=-1), 0, 255).astype(np.uint8)
    bg.flags.writeable = False
    return bg


def wall_texture(size: tuple[int, int] = (2100, 800), seed: int = 909) -> np.ndarray:
    """A feature-rich, non-repeating RGB texture (float32 in [0, 1], read-only): soft colour fields and posters.

    Made with a seeded generator, so it is the same every time: smooth multi-scale colour noise,
    then a few hundred random rectangles, discs, triangles and strokes in random colours (corners
    and blobs for the feature detector at every scale).

    Parameters
    ----------
    size : (width, height)
        The texture's size, pixels.
    seed : int
        Seed of the generator.

    Returns
    -------
    (height, width, 3) float32 ndarray
        RGB in [0, 1], cached and read-only.
    """
    return _wall_texture(*check_size(size), int(seed))


@lru_cache(maxsize=2)
def _wall_texture(width: int, height: int, seed: int) -> np.ndarray:
    import cv2

    rng = np.random.default_rng(seed)
    tex = np.zeros((height, width, 3), np.float32)
    for scale, amp, chroma in ((120, 0.16, 0.5), (30, 0.10, 0.3), (6, 0.05, 0.2)):
        small = rng.normal(0, 1, (height // scale + 2, width // scale + 2, 3)).astype(np.float32)
        small = (1 - chroma) * small.mean(
            axis=2, keepdims=True
        ) + chroma * small  # mostly luminance
        tex += amp * cv2.resize(small, (width, height), interpolation=cv2.INTER_CUBIC)
    tex = 0.55 + tex
    for _ in range(520):
        kind = rng.integers(0, 4)
        colour = tuple(
            float(c) for c in 0.6 * rng.uniform(0.05, 0.95) + 0.4 * rng.uniform(0.05, 0.95, 3)
        )
        cx, cy = rng.uniform(0, width), rng.uniform(0, height)
        size = float(np.exp(rng.uniform(np.log(4), np.log(45))))
        if kind == 0:
            a = rng.uniform(-0.6, 0.6)
            box = cv2.boxPoints(((cx, cy), (size * rng.uniform(0.6, 1.8), size), np.degrees(a)))
            cv2.fillConvexPoly(tex, np.round(box * 16).astype(np.int32), colour, cv2.LINE_AA, 4)
        elif kind == 1:
            cv2.circle(tex, (int(cx * 16), int(cy * 16)), int(size * 8), colour, -1, cv2.LINE_AA, 4)
        elif kind == 2:
            tri = np.array([cx, cy]) + rng.uniform(-size, size, (3, 2))
            cv2.fillConvexPoly(tex, np.round(tri * 16).astype(np.int32), colour, cv2.LINE_AA, 4)
        else:
            p2 = np.array([cx, cy]) + rng.uniform(-2 * size, 2 * size, 2)
            cv2.line(
                tex,
                (int(cx * 16), int(cy * 16)),
                (int(p2[0] * 16), int(p2[1] * 16)),
                colour,
                int(rng.integers(1, 4)),
                cv2.LINE_AA,
                4,
            )
    tex = np.clip(tex, 0.0, 1.0)
    tex.setflags(write=False)  # cached: a caller's edit must not change later renders
    return tex


def house_picture(size: tuple[int, int] = (160, 120)) -> np.ndarray:
    """A small test picture (lesson 07): a checkerboard with a house, a sun and a frame.

    Drawn for 160 x 120 and scaled with the width.

    Parameters
    ----------
    size : (width, height)
        The picture's size, pixels.

    Returns
    -------
    (height, width, 3) uint8 ndarray
        RGB, a new writable array each call.
    """
    import cv2

    width, height = check_size(size)

    v, u = np.mgrid[0:height, 0:width]
    check = ((u // 20 + v // 20) % 2).astype(np.float32)
    img = np.empty((height, width, 3), np.uint8)
    img[:] = (225, 235, 245)
    img[check > 0] = (200, 215, 235)
    s = width / 160
    base = np.array([[40, 110], [40, 65], [80, 35], [120, 65], [120, 110]]) * s
    cv2.fillPoly(img, [base.astype(np.int32)], (200, 80, 60))
    cv2.rectangle(img, (int(70 * s), int(80 * s)), (int(90 * s), int(110 * s)), (90, 60, 40), -1)
    cv2.circle(img, (int(135 * s), int(22 * s)), int(12 * s), (240, 190, 40), -1)
    frame = np.zeros((height, width), bool)  # a 3-pixel frame, its corner pixels included
    frame[:3] = frame[-3:] = True
    frame[:, :3] = frame[:, -3:] = True
    img[frame] = (30, 60, 140)
    return img


def noise_texture(shape: tuple[int, int], seed: int, base: float = 0.5) -> np.ndarray:
    """Smooth multi-scale random texture in [0, 1] (good for matching at several depths).

    Gaussian noise at five scales, resized (bicubic) and summed around ``base``.

    Parameters
    ----------
    shape : (height, width)
        The texture's shape, pixels.
    seed : int
        Seed of the noise.
    base : float
        The mean grey.

    Returns
    -------
    (height, width) float32 ndarray
        Greys clipped to [0, 1], a new array each call.
    """
    import cv2

    rng = np.random.default_rng(seed)
    h, w = shape
    tex = np.zeros((h, w), np.float32)
    for k, amp in ((4, 0.3), (16, 0.25), (64, 0.25), (256, 0.25), (512, 0.15)):
        small = rng.normal(0, 1, (max(2, h * k // 512), max(2, w * k // 512))).astype(np.float32)
        tex += amp * cv2.resize(small, (w, h), interpolation=cv2.INTER_CUBIC)
    return np.clip(base + 0.5 * tex / 1.2, 0, 1)
