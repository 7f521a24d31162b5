r"""Synthetic scenes and textures: everything the virtual camera and the lessons photograph.

One home for the made-up world of the course, so lessons, widgets, benchmarks and the
data generators (:mod:`camlab.data`) build the same scenes:

- **textures** (read-only arrays, cached where they are pure functions of their
  arguments): :func:`as_texture`, :func:`portrait` (the one bundled sample photograph),
  :func:`page_texture`, :func:`facade_texture`, :func:`painting_texture`,
  :func:`desk_background`, :func:`wall_texture` (panoramas), :func:`noise_texture` (stereo),
  and one fresh uint8 picture to warp, :func:`house_picture` (lesson 07);
- **planes for** :func:`camlab.render.render`: :class:`Plane`, :func:`textured_plane`,
  :func:`checkerboard`, :func:`photo_plane`, :func:`text_page`, :func:`box`;
- **plane photos** made by one homography (lesson 10): :func:`photograph_plane`,
  :func:`sample_photo`;
- **wireframes** (M, 2, 3) segments (lessons 04-05): :func:`box_wireframe`,
  :func:`house_wireframe`, :func:`ground_grid`, :func:`plane_outlines`;
- **the lessons' scenes and synthetic data**, built here once for the lesson and its demos:
  :func:`box_before_wall` (01), :func:`depth_of_field_scene` (02), :func:`photo_and_page` (03),
  :func:`house_scene`, :func:`resection_set` (04), :func:`box_and_rails`, :func:`rail_track`,
  :func:`sleeper_gaps` (05), :func:`ground_plane_view` (06), :func:`outlier_matches` (07),
  :func:`stereo_pair`, :func:`forward_pair` (11).

Conventions (docs/conventions.md): metres; a plane's frame has x along texture columns,
y along texture rows, z = x cross y; poses say their direction (``world_from_plane``).
This module depends on no data set, so the data generators can build on it.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from typing import NamedTuple, Sequence

import numpy as np
from numpy.typing import ArrayLike

from ._validate import (
    CamlabInputError, check_integer, check_matrix, check_number, check_pose, check_positive, check_rotation, check_shape,
    check_size,
)
from .camera import Camera, look_at_rotation, orbit_eye, project_points, rotation_from_axis_angle, rotation_from_euler
from .homography import pose_homography
from .projective import map_points
from .warp import warp_perspective

__all__ = [
    "as_texture", "box", "box_and_rails", "box_before_wall", "box_wireframe", "CameraPair", "checkerboard",
    "depth_of_field_scene", "desk_background", "facade_texture", "forward_pair", "ground_grid",
    "ground_plane_view", "GroundView", "house_picture", "house_scene", "house_wireframe", "look_at_plane",
    "noise_texture", "outlier_matches", "OutlierMatches", "page_texture", "painting_texture", "photo_and_page",
    "photo_plane", "photograph_plane", "Plane", "plane_outlines", "PlanePhoto", "portrait", "rail_track",
    "resection_set", "ResectionSet", "sample_photo", "sleeper_gaps", "stereo_pair", "text_page", "textured_plane",
    "wall_texture",
]


# --------------------------------------------------------------------------- textures

def as_texture(texture: ArrayLike) -> np.ndarray:
    """``texture`` as a read-only float32 (H, W) or (H, W, 3) array in [0, 1]: integers are divided by their
    maximum, an alpha channel is dropped."""
    a = np.asarray(texture)
    if a.ndim == 3 and a.shape[2] == 4:
        a = a[..., :3]
    if not (a.ndim == 2 or (a.ndim == 3 and a.shape[2] == 3)) or min(a.shape[:2]) < 1:
        raise CamlabInputError(f"texture: expected an (H, W) or (H, W, 3) image, got shape {a.shape}")
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
    """
    import matplotlib.image as mpimg
    from matplotlib import cbook

    with cbook.get_sample_data("grace_hopper.jpg") as f:
        img = mpimg.imread(f, format="jpg")
    return as_texture(img)


@lru_cache(maxsize=4)
def _text_texture(width_px: int, seed: int) -> np.ndarray:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    rng = np.random.default_rng(seed)
    words = ("camera lens pixel sensor light ray focus image plane point line matrix projective "
             "geometry calibration homography epipolar depth field aperture distortion").split()
    h_px = int(width_px * 1.414)
    fig = Figure(figsize=(width_px / 100, h_px / 100), dpi=100)
    FigureCanvasAgg(fig)
    fig.text(0.08, 0.94, "Chapter 1. Image formation", fontsize=width_px / 28, weight="bold", va="top")
    for i in range(34):
        line = " ".join(rng.choice(words, size=7))
        fig.text(0.08, 0.88 - i * 0.024, line.capitalize() + ".", fontsize=width_px / 50, va="top")
    fig.canvas.draw()
    rgba = np.asarray(fig.canvas.buffer_rgba())
    grey = rgba[..., :3].mean(axis=2) / 255.0
    return as_texture(grey)


def page_texture(size: tuple[int, int] = (420, 594), seed: int = 0) -> np.ndarray:
    """A printed page (A4 proportions, 1 : sqrt 2): title, paragraphs of text, a figure box.

    ``size`` is (width, height) in pixels. Returns a (height, width, 3) uint8 RGB image
    drawn with ``cv2.putText`` (cached and read-only, like the other textures).
    """
    return _page_texture(*check_size(size), int(seed))


@lru_cache(maxsize=8)
def _page_texture(width: int, height: int, seed: int) -> np.ndarray:
    import cv2

    rng = np.random.default_rng(seed)
    page = np.full((height, width, 3), 250, np.uint8)
    cv2.putText(page, "Projective Geometry", (int(0.08 * width), int(0.09 * height)),
                cv2.FONT_HERSHEY_DUPLEX, width / 560, (20, 20, 20), 2, cv2.LINE_AA)
    words = ["camera", "plane", "homography", "line", "point", "image", "ray", "scale", "view", "map"]
    y = int(0.16 * height)
    line_h = max(12, height // 34)
    box_top = int(0.55 * height)
    while y < height - int(0.06 * height):
        if box_top <= y < box_top + int(0.2 * height):
            y = box_top + int(0.2 * height) + line_h
            continue
        text = " ".join(rng.choice(words, size=5))
        cv2.putText(page, text, (int(0.08 * width), y), cv2.FONT_HERSHEY_SIMPLEX, width / 1100,
                    (40, 40, 40), 1, cv2.LINE_AA)
        y += line_h
    x0, x1 = int(0.2 * width), int(0.8 * width)
    y0, y1 = box_top, box_top + int(0.18 * height)
    cv2.rectangle(page, (x0, y0), (x1, y1), (60, 90, 160), 2)
    cv2.line(page, (x0, y1), (x1, y0), (200, 60, 40), 2, cv2.LINE_AA)
    cv2.circle(page, ((x0 + x1) // 2, (y0 + y1) // 2), (y1 - y0) // 4, (40, 140, 60), 2, cv2.LINE_AA)
    page.flags.writeable = False  # cached: copy before drawing on it
    return page


def facade_texture(size: tuple[int, int] = (480, 360), floors: int = 4, bays: int = 6) -> np.ndarray:
    """A building facade: brick-coloured wall, a grid of ``floors`` x ``bays`` windows, a door.

    ``size`` is (width, height) in pixels; returns a (height, width, 3) uint8 RGB image,
    cached and read-only.
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
    """A framed painting: :func:`portrait` inside a gold frame. (h, w, 3) uint8, read-only."""
    import cv2

    art = np.round(portrait() * 255).astype(np.uint8)  # the JPEG's own uint8 values
    scale = (width - 40) / art.shape[1]
    art = cv2.resize(art, (width - 40, int(round(art.shape[0] * scale))), interpolation=cv2.INTER_AREA)
    frame = np.empty((art.shape[0] + 40, width, 3), np.uint8)
    frame[:] = (170, 130, 50)
    cv2.rectangle(frame, (6, 6), (width - 7, frame.shape[0] - 7), (210, 170, 80), 4)
    frame[20:-20, 20:-20] = art
    frame.flags.writeable = False  # cached: copy before drawing on it
    return frame


def desk_background(shape: tuple[int, int] = (480, 640), seed: int = 0) -> np.ndarray:
    """A dark wooden-desk background, (height, width, 3) uint8 for ``shape`` = (height, width).

    Cached and read-only: demos re-photograph on every slider move.
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

    ``size`` is (width, height) in pixels; the result is (height, width, 3). Made with a
    seeded generator, so it is the same every time: smooth multi-scale colour noise, then a
    few hundred random rectangles, discs, triangles and strokes in random colours (corners
    and blobs for the feature detector at every scale).
    """
    return _wall_texture(*check_size(size), int(seed))


@lru_cache(maxsize=2)
def _wall_texture(width: int, height: int, seed: int) -> np.ndarray:
    import cv2

    rng = np.random.default_rng(seed)
    tex = np.zeros((height, width, 3), np.float32)
    for scale, amp, chroma in ((120, 0.16, 0.5), (30, 0.10, 0.3), (6, 0.05, 0.2)):
        small = rng.normal(0, 1, (height // scale + 2, width // scale + 2, 3)).astype(np.float32)
        small = (1 - chroma) * small.mean(axis=2, keepdims=True) + chroma * small  # mostly luminance
        tex += amp * cv2.resize(small, (width, height), interpolation=cv2.INTER_CUBIC)
    tex = 0.55 + tex
    for _ in range(520):
        kind = rng.integers(0, 4)
        colour = tuple(float(c) for c in 0.6 * rng.uniform(0.05, 0.95) + 0.4 * rng.uniform(0.05, 0.95, 3))
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
            cv2.line(tex, (int(cx * 16), int(cy * 16)), (int(p2[0] * 16), int(p2[1] * 16)), colour,
                     int(rng.integers(1, 4)), cv2.LINE_AA, 4)
    tex = np.clip(tex, 0.0, 1.0)
    tex.setflags(write=False)  # cached: a caller's edit must not change later renders
    return tex


def house_picture(size: tuple[int, int] = (160, 120)) -> np.ndarray:
    """A small test picture (lesson 07): a checkerboard with a house, a sun and a frame.

    ``size`` is (width, height) in pixels; returns a (height, width, 3) uint8 RGB image,
    a new writable array each call. Drawn for 160 x 120 and scaled with the width.
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
    cv2.rectangle(img, (1, 1), (width - 2, height - 2), (30, 60, 140), 2)
    return img


def noise_texture(shape: tuple[int, int], seed: int, base: float = 0.5) -> np.ndarray:
    """Smooth multi-scale random texture in [0, 1] (good for matching at several depths)."""
    import cv2

    rng = np.random.default_rng(seed)
    h, w = shape
    tex = np.zeros((h, w), np.float32)
    for k, amp in ((4, 0.3), (16, 0.25), (64, 0.25), (256, 0.25), (512, 0.15)):
        small = rng.normal(0, 1, (max(2, h * k // 512), max(2, w * k // 512))).astype(np.float32)
        tex += amp * cv2.resize(small, (w, h), interpolation=cv2.INTER_CUBIC)
    return np.clip(base + 0.5 * tex / 1.2, 0, 1)


# --------------------------------------------------------------------------- planes for the renderer

@dataclass(frozen=True, eq=False)
class Plane:
    """A flat textured rectangle in the world.

    Attributes
    ----------
    texture : (Ht, Wt) or (Ht, Wt, 3) float32 ndarray
        Reflectance in [0, 1], grey or RGB; texel (c, r) covers the rectangle's cell in
        column c, row r.
    extent : (x0, y0, x1, y1)
        The rectangle in the plane's own frame, metres; the texture spans it exactly.
    R, t : (3, 3), (3,) ndarray
        world_from_plane: ``X_world = R @ [x, y, 0] + t``.
    points : (M, 2) ndarray
        Named points of interest in plane coordinates (checkerboard inner corners); their
        exact pixels are returned in the ground truth.
    name : str
        Key of this plane's points in ``GroundTruth.points``.
    pattern_size : (cols, rows) or None
        Inner-corner count of a checkerboard, in ``cv2.findChessboardCorners`` order.
    two_sided : bool
        Seen from both sides (default); box faces are one-sided and culled from behind.
    """

    texture: np.ndarray
    extent: tuple[float, float, float, float]
    R: np.ndarray
    t: np.ndarray
    points: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    name: str = "plane"
    pattern_size: tuple[int, int] | None = None
    two_sided: bool = True

    @property
    def object_points(self) -> np.ndarray:
        """(M, 3) points in the plane frame with z = 0 (``cv2.calibrateCamera``'s objectPoints)."""
        return np.column_stack([self.points, np.zeros(len(self.points))])

    @property
    def world_points(self) -> np.ndarray:
        """(M, 3) named points in the world frame."""
        return self.object_points @ self.R.T + self.t

    @property
    def corners_world(self) -> np.ndarray:
        """(4, 3) world positions of the rectangle's corners (top-left, top-right, bottom-right, bottom-left)."""
        x0, y0, x1, y1 = self.extent
        c = np.array([[x0, y0, 0], [x1, y0, 0], [x1, y1, 0], [x0, y1, 0]], dtype=float)
        return c @ self.R.T + self.t

    @property
    def is_color(self) -> bool:
        return self.texture.ndim == 3


def textured_plane(texture: ArrayLike, width: float, *, R: ArrayLike = np.eye(3), t: ArrayLike = (0, 0, 0),
                   height: float | None = None, centered: bool = True, name: str = "plane") -> Plane:
    """A rectangle ``width`` metres wide showing ``texture``; height from the texture's aspect by default.

    ``centered``: the plane frame's origin is the rectangle's centre (else its top-left corner).
    """
    tex = as_texture(texture)
    w = check_positive(width, "width", "metres")
    h = check_positive(height, "height", "metres") if height is not None else w * tex.shape[0] / tex.shape[1]
    R, t = check_pose(R, t, name)
    extent = (-w / 2, -h / 2, w / 2, h / 2) if centered else (0.0, 0.0, w, h)
    return Plane(tex, extent, R, t, name=name)


def checkerboard(pattern_size: tuple[int, int] = (9, 6), square: float = 0.025, *, R: ArrayLike = np.eye(3),
                 t: ArrayLike = (0, 0, 0), margin: float = 1.0, px_per_square: int = 48,
                 colors: tuple[float, float] = (0.05, 0.95), name: str = "board") -> Plane:
    """A checkerboard with ``pattern_size = (cols, rows)`` inner corners and ``square`` metres per square.

    It has ``cols + 1`` by ``rows + 1`` squares (the top-left one dark) inside a light
    border ``margin`` squares wide (the quiet zone detectors need). The plane's origin is
    the first inner corner; ``points`` are the inner corners row by row, ``(i * square,
    j * square)`` for ``j`` in rows, ``i`` in cols: the order and the object points of
    ``cv2.findChessboardCorners(img, pattern_size)`` for an upright board.

    >>> b = checkerboard((4, 3), 0.03)
    >>> b.points.shape, b.points[1], b.texture.shape
    ((12, 2), array([0.03, 0.  ]), (288, 336))
    """
    try:
        cols, rows = (int(v) for v in pattern_size)
    except (TypeError, ValueError):
        raise CamlabInputError(f"pattern_size: expected (cols, rows) inner corners, got {pattern_size!r}") from None
    if cols < 2 or rows < 2:
        raise CamlabInputError(f"pattern_size: expected at least (2, 2) inner corners, got {pattern_size!r}")
    s = check_positive(square, "square", "metres")
    if not margin >= 0:
        raise CamlabInputError(f"margin: expected >= 0 squares, got {margin!r}")
    R, t = check_pose(R, t, name)
    n = int(px_per_square)
    m = int(round(margin * n))
    dark, light = colors
    sq = (np.add.outer(np.arange(rows + 1), np.arange(cols + 1)) % 2).astype(np.float32)  # 0 = dark at (0, 0)
    board = np.where(sq == 0, dark, light).astype(np.float32)
    tex = np.full(((rows + 1) * n + 2 * m, (cols + 1) * n + 2 * m), light, dtype=np.float32)
    tex[m:m + (rows + 1) * n, m:m + (cols + 1) * n] = np.kron(board, np.ones((n, n), dtype=np.float32))
    tex.setflags(write=False)
    off = s + m * s / n  # first inner corner, measured from the texture's top-left edge
    extent = (-off, -off, tex.shape[1] * s / n - off, tex.shape[0] * s / n - off)
    jj, ii = np.mgrid[0:rows, 0:cols]
    pts = np.column_stack([ii.ravel() * s, jj.ravel() * s])
    return Plane(tex, extent, R, t, pts, name, (cols, rows))


def photo_plane(width: float = 0.4, *, R: ArrayLike = np.eye(3), t: ArrayLike = (0, 0, 0), name: str = "photo") -> Plane:
    """A centred rectangle showing matplotlib's bundled Grace Hopper photograph."""
    return textured_plane(portrait(), width, R=R, t=t, name=name)


def text_page(width: float = 0.21, *, R: ArrayLike = np.eye(3), t: ArrayLike = (0, 0, 0), seed: int = 0,
              name: str = "page") -> Plane:
    """A printed page (A4 proportions) of deterministic pseudo-text, rendered with matplotlib's Agg."""
    return textured_plane(_text_texture(600, int(seed)), width, R=R, t=t, name=name)


def box(center: ArrayLike, size: ArrayLike, *, R: ArrayLike = np.eye(3), colors: Sequence[float] | None = None,
        texture: str = "noise", texels: int = 64, rng: np.random.Generator | int | None = 0,
        name: str = "box") -> list[Plane]:
    """The six faces of a box, as planes with outward normals (z = x cross y points out).

    Parameters
    ----------
    center : (3,) world position, metres.
    size : (3,) edge lengths along the box's own x, y, z axes, metres.
    R : (3, 3) world_from_box rotation.
    colors : six greys in [0, 1] (faces +x, -x, +y, -y, +z, -z); distinct shades by default.
    texture : "noise" (random texture on each face: good for stereo matching) or "flat".
    rng : seed or Generator for the noise texture (deterministic by default).

    Faces get names ``f"{name}+x"`` ... and their 4 corners as named points.
    """
    c = check_matrix(center, (3,), "center")
    sz = check_matrix(size, (3,), "size")
    if np.any(sz <= 0):
        raise CamlabInputError(f"size: expected three positive edge lengths in metres, got {sz.tolist()}")
    Rb = check_rotation(R, f"{name} R")
    if texture not in ("noise", "flat"):
        raise CamlabInputError(f"texture: expected 'noise' or 'flat', got {texture!r}")
    shades = list(colors) if colors is not None else [0.75, 0.45, 0.6, 0.3, 0.85, 0.55]
    rng = np.random.default_rng(rng)
    half = sz / 2
    faces = []
    # (outward axis index, sign, in-face x axis, in-face y axis)
    spec = [(0, 1, 2, 1), (0, -1, 2, 1), (1, 1, 0, 2), (1, -1, 0, 2), (2, 1, 0, 1), (2, -1, 0, 1)]
    for k, (ax, sign, ix, iy) in enumerate(spec):
        n = np.zeros(3)
        n[ax] = sign
        ex = np.zeros(3)
        ex[ix] = 1.0
        ey = np.zeros(3)
        ey[iy] = 1.0
        if np.dot(np.cross(ex, ey), n) < 0:
            ex = -ex
        Rf = Rb @ np.column_stack([ex, ey, n])
        tf = c + Rb @ (n * half[ax])
        w, h = 2 * half[ix], 2 * half[iy]
        th = max(2, int(round(texels * h / max(w, h))))
        tw = max(2, int(round(texels * w / max(w, h))))
        base = np.full((th, tw), shades[k % len(shades)], dtype=np.float32)
        if texture == "noise":
            base = np.clip(base + rng.normal(0, 0.12, size=(th, tw)).astype(np.float32), 0, 1)
        label = f"{name}{'+' if sign > 0 else '-'}{'xyz'[ax]}"
        pts = np.array([[-w / 2, -h / 2], [w / 2, -h / 2], [w / 2, h / 2], [-w / 2, h / 2]])
        faces.append(Plane(as_texture(base), (-w / 2, -h / 2, w / 2, h / 2), Rf, tf, pts, label, two_sided=False))
    return faces


# --------------------------------------------------------------------------- photos of a plane (lesson 10)

class PlanePhoto(NamedTuple):
    """A synthetic photo of a flat rectangle with its ground truth.

    Attributes
    ----------
    image : (h, w, 3) uint8 ndarray
        The photo.
    corners : (4, 2) ndarray
        True image positions of the rectangle's corners, TL, TR, BR, BL.
    aspect : float
        True width / height of the rectangle.
    H : (3, 3) ndarray
        image_from_texture: maps texture pixels into the photo.
    K : (3, 3) ndarray
        The camera intrinsics used (focal length ``K[0, 0]`` pixels).
    """

    image: np.ndarray
    corners: np.ndarray
    aspect: float
    H: np.ndarray
    K: np.ndarray


def look_at_plane(yaw: float, pitch: float, roll: float = 0.0) -> np.ndarray:
    """Rotation cam_from_plane turning a plane about its own centre: yaw about the
    vertical (v) axis, pitch about the horizontal (u) axis, roll about the view axis,
    in radians. With all angles 0 the plane faces the camera squarely."""
    cy, sy = np.cos(yaw), np.sin(yaw)
    cp, sp = np.cos(pitch), np.sin(pitch)
    cr, sr = np.cos(roll), np.sin(roll)
    Ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    Rx = np.array([[1, 0, 0], [0, cp, -sp], [0, sp, cp]])
    Rz = np.array([[cr, -sr, 0], [sr, cr, 0], [0, 0, 1]])
    return Rz @ Rx @ Ry


def photograph_plane(
    texture: ArrayLike,
    *,
    yaw: float = 0.5,
    pitch: float = 0.3,
    roll: float = 0.0,
    distance: float = 2.2,
    width_m: float = 1.0,
    offset: ArrayLike = (0.0, 0.0),
    focal: float = 800.0,
    image_shape: tuple[int, int] = (480, 640),
    background: ArrayLike | None = None,
    seed: int = 0,
    method: str = "cv2",
) -> PlanePhoto:
    r"""Photograph a flat textured rectangle at an angle: a plane-induced homography.

    The texture is a rectangle ``width_m`` metres wide (its height follows from the
    texture's pixel aspect), centred on the optical axis at ``distance`` metres (plus
    ``offset`` metres in x and y), turned by :func:`look_at_plane`. The camera is
    :math:`K = [[f, 0, c_x], [0, f, c_y], [0, 0, 1]]`; a plane point (X, Y, 0) projects by
    :func:`camlab.homography.pose_homography`, and a texture pixel (u, v) is the plane
    point :math:`s (u - (W-1)/2,\ v - (H-1)/2)` with :math:`s` = metres per texture
    pixel. The photo is the texture warped by the product onto a background;
    ``image_shape`` is the photo's (height, width), numpy's order.

    Returns
    -------
    PlanePhoto
        ``image``, true ``corners``, true ``aspect``, ``H`` (image_from_texture), ``K``.
    """
    tex = np.asarray(texture)
    if tex.ndim != 3 or tex.shape[2] != 3:
        raise CamlabInputError(f"texture: expected an (H, W, 3) RGB image, got shape {tex.shape}")
    th, tw = tex.shape[:2]
    h, w = image_shape
    K = np.array([[focal, 0, (w - 1) / 2], [0, focal, (h - 1) / 2], [0, 0, 1.0]])
    R = look_at_plane(yaw, pitch, roll)
    off = np.asarray(offset, dtype=float)
    t = np.array([off[0], off[1], check_positive(distance, "distance", "metres")])
    s = check_positive(width_m, "width_m", "metres") / tw
    S = np.array([[s, 0, -s * (tw - 1) / 2], [0, s, -s * (th - 1) / 2], [0, 0, 1]])
    H = pose_homography(K, R, t) @ S
    H = H / H[2, 2]
    corners_tex = np.array([[0, 0], [tw - 1, 0], [tw - 1, th - 1], [0, th - 1]], dtype=float)
    corners = map_points(H, corners_tex)
    if background is None:
        bg = desk_background((h, w), seed)
    else:
        bg = np.asarray(background, dtype=np.uint8)
    if method == "cv2":
        import cv2

        # Warp straight onto a copy of the background: BORDER_TRANSPARENT leaves the
        # pixels outside the texture untouched (one call, fast enough for live demos).
        image = np.array(bg, dtype=np.uint8, copy=True)
        cv2.warpPerspective(np.ascontiguousarray(tex, dtype=np.uint8), H, (w, h), dst=image,
                            flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_TRANSPARENT)
    else:
        photo = warp_perspective(tex, H, (h, w), method=method)
        mask = warp_perspective(np.full((th, tw), 255, np.uint8), H, (h, w), method=method).astype(np.float32) / 255
        out = photo.astype(np.float32) + bg.astype(np.float32) * (1 - mask[..., None])
        image = np.clip(out, 0, 255).astype(np.uint8)
    # The corners are the centres of the texture's corner pixels: (tw - 1) x (th - 1) apart.
    return PlanePhoto(image, corners, (tw - 1) / (th - 1), H, K)


_SCENES = {
    "page": dict(yaw=0.45, pitch=0.35, roll=0.1, distance=2.2, width_m=0.75),
    "painting": dict(yaw=-0.6, pitch=0.1, roll=0.0, distance=2.4, width_m=0.8),
    "facade": dict(yaw=0.2, pitch=-0.5, roll=0.0, distance=1.8, width_m=1.0),
}


def sample_photo(kind: str = "page", **pose) -> PlanePhoto:
    """A ready-made synthetic photo for lesson 10: ``"page"``, ``"painting"`` or ``"facade"``.

    Keyword arguments override the scene's pose (see :func:`photograph_plane`).

    >>> p = sample_photo("page")
    >>> p.image.shape, round(p.aspect, 3)
    ((480, 640, 3), 0.707)
    """
    if kind not in _SCENES:
        raise CamlabInputError(f"kind: expected one of {sorted(_SCENES)}, got {kind!r}")
    texture = {"page": page_texture, "painting": painting_texture, "facade": facade_texture}[kind]()
    return photograph_plane(texture, **{**_SCENES[kind], **pose})


# --------------------------------------------------------------------------- wireframes (lessons 04-05)

def box_wireframe(centre: ArrayLike = (0.0, 0.0, 0.5), size: ArrayLike = (1.0, 1.0, 1.0)) -> np.ndarray:
    """The 12 edges of an axis-aligned box as (12, 2, 3) segments (metres)."""
    c = check_matrix(centre, (3,), "centre")
    s = check_matrix(size, (3,), "size")
    corners = np.array([[i, j, k] for i in (-0.5, 0.5) for j in (-0.5, 0.5) for k in (-0.5, 0.5)]) * s + c
    edges = [(a, b) for a in range(8) for b in range(a + 1, 8) if bin(a ^ b).count("1") == 1]
    return corners[np.array(edges)]


def house_wireframe(centre: ArrayLike = (0.0, 0.0, 0.0), size: float = 1.0) -> np.ndarray:
    """A house (box body, gable roof, door) standing on z = 0 at ``centre``, as (M, 2, 3) segments."""
    c = check_matrix(centre, (3,), "centre")
    s = check_positive(size, "size", "metres")
    body = box_wireframe((0.0, 0.0, 0.5), (1.0, 1.4, 1.0))
    r0, r1 = np.array([0.0, -0.7, 1.55]), np.array([0.0, 0.7, 1.55])
    top = [(-0.5, 1.0), (0.5, 1.0)]
    roof = [[r0, r1]]
    for y, r in ((-0.7, r0), (0.7, r1)):
        for x, z in top:
            roof.append([[x, y, z], r])
    door = [[[-0.5, -0.15, 0.0], [-0.5, -0.15, 0.6]], [[-0.5, -0.15, 0.6], [-0.5, 0.15, 0.6]],
            [[-0.5, 0.15, 0.6], [-0.5, 0.15, 0.0]]]
    segs = np.concatenate([body, np.array(roof, dtype=float), np.array(door, dtype=float)])
    return segs * s + c


def ground_grid(extent: float = 2.0, step: float = 0.5, z: float = 0.0) -> np.ndarray:
    """Grid lines on the plane z = ``z`` covering [-extent, extent]^2, as (M, 2, 3) segments."""
    e = check_positive(extent, "extent", "metres")
    st = check_positive(step, "step", "metres")
    ticks = np.arange(-e, e + 1e-9, st)
    segs = [[[x, -e, z], [x, e, z]] for x in ticks] + [[[-e, y, z], [e, y, z]] for y in ticks]
    return np.array(segs, dtype=float)


def plane_outlines(planes: Sequence[Plane | Sequence[Plane]]) -> np.ndarray:
    """The four edges of every plane's rectangle as (4 M, 2, 3) segments, metres.

    ``planes`` may nest lists (a :func:`box` is a list of six faces), like a scene for
    :func:`camlab.render.render`. Edges run top-left, top-right, bottom-right, bottom-left.
    """
    segments = []
    for item in planes:
        for plane in (item if isinstance(item, (list, tuple)) else [item]):
            c = plane.corners_world
            segments += [(c[i], c[(i + 1) % 4]) for i in range(4)]
    return np.array(segments, dtype=float).reshape(-1, 2, 3)


# --------------------------------------------------------------------------- the lessons' scenes

def box_before_wall(distance: float) -> list:
    """Lesson 01: a turned 0.3 m box ``distance`` metres in front of the pinhole and a wall 3x further.

    Returns ``[faces, wall]``: the box's six faces (a list of :class:`Plane`) and a flat grey
    wall (a :class:`Plane`) 3 ``distance`` wide at z = 3 ``distance``, a scene for
    :func:`camlab.render.render`. :func:`plane_outlines` of ``faces`` gives the (24, 2, 3)
    box edges the 3-D view draws.
    """
    d = check_positive(distance, "distance", "metres")
    return [box([0.0, 0.0, d], (0.3, 0.3, 0.3), R=rotation_from_euler(0.35, 0.6, 0.0), rng=0),
            textured_plane(np.full((4, 4), 0.35), 3.0 * d, t=(0, 0, 3.0 * d), name="wall")]


def depth_of_field_scene() -> list[Plane]:
    """Lesson 02: four planes at 0.6, 1.2, 2.4 and 4 m (near board, text page, far board, portrait wall).

    Seen by a camera at the origin looking along +z; a list of :class:`Plane` for
    :func:`camlab.render.render`, named ``"near"``, ``"page"``, ``"far"``, ``"wall"``.
    """
    return [checkerboard((5, 4), 0.04, t=(-0.33, -0.02, 0.6), name="near", px_per_square=32),
            text_page(0.3, t=(0.0, -0.02, 1.2)),
            checkerboard((7, 5), 0.12, t=(0.1, -0.55, 2.4), name="far", px_per_square=32),
            textured_plane(portrait(), 3.2, t=(0, 0, 4.0), name="wall")]


def photo_and_page() -> list[Plane]:
    """Lesson 03: a colour photograph 1 m ahead and a slightly turned text page beside it, at 1.1 m.

    A list of two :class:`Plane` (``"photo"``, ``"page"``) for :func:`camlab.render.render`,
    framed by a camera at the origin looking along +z with f = 900 px on 320 x 240 pixels.
    """
    return [photo_plane(0.3, t=(0.05, 0.02, 1.0)),
            text_page(0.2, t=(-0.2, 0.0, 1.1), R=rotation_from_euler(0, 0.2, 0.05))]


def house_scene() -> np.ndarray:
    """Lesson 04: a house on a 4 m x 4 m ground grid (z = 0), as (M, 2, 3) segments, metres."""
    return np.concatenate([house_wireframe(), ground_grid(2.0, 0.5)])


def box_and_rails() -> np.ndarray:
    """Lesson 05: a 1 m cube on four long parallel rails along x, as (M, 2, 3) segments, metres."""
    rails = np.array([[[-3.0, y, 0.0], [3.0, y, 0.0]] for y in (-0.8, -0.6, 0.6, 0.8)])
    return np.concatenate([box_wireframe((0.0, 0.0, 0.5), (1.0, 1.0, 1.0)), rails])


def rail_track(start: float = -3.0, end: float = 40.0) -> np.ndarray:
    """Lesson 05: four parallel rails along +y and a sleeper every metre on the ground, (M, 2, 3) metres.

    The rails run from y = ``start`` to ``end`` metres at x = -1.5, -0.5, 0.5, 1.5 m.
    """
    rails = np.array([[[x, start, 0.0], [x, end, 0.0]] for x in (-1.5, -0.5, 0.5, 1.5)])
    sleepers = np.array([[[-1.7, y, 0.0], [1.7, y, 0.0]] for y in np.arange(start, end, 1.0)])
    return np.concatenate([rails, sleepers])


def sleeper_gaps(P: ArrayLike, at: Sequence[float] = (-2.0, 20.0)) -> np.ndarray:
    """Lesson 05: the image length (pixels) under the camera matrix ``P`` of one metre of :func:`rail_track`
    (the ground line x = 0 from y to y + 1) for each y in ``at`` metres: equal for an affine
    camera, shrinking with distance for a perspective one (foreshortening)."""
    ys = np.atleast_1d(np.asarray(at, dtype=float))
    zero = np.zeros_like(ys)
    near_end = project_points(P, np.column_stack([zero, ys, zero]))
    far_end = project_points(P, np.column_stack([zero, ys + 1.0, zero]))
    return np.linalg.norm(far_end - near_end, axis=1)


class CameraPair(NamedTuple):
    """Two views of one scene (cam_from_world poses)."""

    camera1: Camera
    camera2: Camera


def _camera_800(R: np.ndarray, eye: np.ndarray) -> Camera:
    """A 640 x 480 camera with f = 800 px at ``eye`` (metres) turned by cam_from_world ``R``."""
    return Camera(np.array([[800.0, 0, 319.5], [0, 800.0, 239.5], [0, 0, 1]]), R, -R @ eye, image_size=(640, 480))


def stereo_pair(baseline: float, toe_in: float, height: float = 0.0) -> CameraPair:
    """Lesson 11: two cameras ``baseline`` metres apart along world x at 1 m, looking along +y, each turned
    ``toe_in / 2`` radians towards the other (converging for toe_in > 0), the right one raised by ``height`` m.

    640 x 480 pixels, f = 800 px. With ``toe_in = 0`` the epipoles are at infinity (parallel cameras).
    """
    eye1 = np.array([-baseline / 2, 0.0, 1.0])
    eye2 = np.array([baseline / 2, 0.0, 1.0 + height])
    cams = []
    for eye, turn in ((eye1, -toe_in / 2), (eye2, toe_in / 2)):
        R = look_at_rotation(eye, eye + [0.0, 1.0, 0.0])
        R = rotation_from_axis_angle([0.0, turn, 0.0]) @ R  # about the camera's (downward) y axis
        cams.append(_camera_800(R, eye))
    return CameraPair(*cams)


def forward_pair(baseline: float, turn: float) -> CameraPair:
    """Lesson 11: the second camera ``baseline`` metres straight ahead of the first (forward motion, like a
    car's camera between two frames), turned by ``turn`` radians about its vertical axis.

    Its epipole is the image of the first centre: near the principal point, inside the image,
    and every epipolar line fans out from it. 640 x 480 pixels, f = 800 px.
    """
    eye1, eye2 = np.array([0.0, -1.0, 1.0]), np.array([0.0, -1.0 + baseline, 1.0])
    R1 = look_at_rotation(eye1, eye1 + [0.0, 1.0, 0.0])
    R2 = rotation_from_axis_angle([0.0, turn, 0.0]) @ look_at_rotation(eye2, eye2 + [0.0, 1.0, 0.0])
    return CameraPair(_camera_800(R1, eye1), _camera_800(R2, eye2))

class OutlierMatches(NamedTuple):
    """Point pairs related by a known homography, a known fraction of them replaced by random points (lesson 07).

    Attributes
    ----------
    H : (3, 3) ndarray
        The true dst_from_src homography.
    src, dst : (N, 2) ndarray
        The pairs, pixels in a 400 x 300 image; the inliers' ``dst`` carry Gaussian noise.
    is_outlier : (N,) bool ndarray
        Which pairs are random (wrong matches).
    """

    H: np.ndarray
    src: np.ndarray
    dst: np.ndarray
    is_outlier: np.ndarray


def outlier_matches(outlier_fraction: float, seed: int | None = 0, n: int = 200, noise: float = 1.0) -> OutlierMatches:
    """``n`` matches of a fixed homography with ``noise`` pixels of noise, ``round(outlier_fraction n)`` of them wrong."""
    if not 0 <= check_number(outlier_fraction, "outlier_fraction") <= 1:
        raise CamlabInputError(f"outlier_fraction: expected a fraction in [0, 1], got {outlier_fraction!r}")
    n = check_integer(n, "n", minimum=4)
    rng = np.random.default_rng(seed)
    H = np.array([[0.9, 0.15, 40.0], [-0.1, 0.85, 30.0], [4e-4, 2e-4, 1.0]])
    src = rng.uniform([0, 0], [400, 300], (n, 2))
    dst = map_points(H, src) + rng.normal(0, noise, (n, 2))
    out = np.zeros(n, bool)
    out[rng.choice(n, int(round(outlier_fraction * n)), replace=False)] = True
    dst[out] = rng.uniform([0, 0], [400, 300], (out.sum(), 2))
    return OutlierMatches(H, src, dst, out)

class ResectionSet(NamedTuple):
    """A true camera and noisy world-to-pixel correspondences (lesson 04, resectioning).

    Attributes
    ----------
    camera : Camera
        The true camera (640 x 480, f = 800 px), 5 m from (0, 0, 0.7) m.
    points_world : (N, 3) ndarray
        Points on two faces of a 2 m cube (x = 1 and y = -1): not coplanar, like a calibration rig.
    points_image : (N, 2) ndarray
        Their pixels with Gaussian noise.
    """

    camera: Camera
    points_world: np.ndarray
    points_image: np.ndarray


def resection_set(n_points: int, noise_px: float, seed: int | None = 0) -> ResectionSet:
    """``n_points`` world points on two faces of a cube, seen by a known camera with ``noise_px`` pixels of noise."""
    n_points = check_integer(n_points, "n_points", minimum=1)
    sigma = check_number(noise_px, "noise_px", "pixels")
    if sigma < 0:
        raise CamlabInputError(f"noise_px: expected a standard deviation >= 0 pixels, got {noise_px!r}")
    rng = np.random.default_rng(seed)
    target = np.array([0.0, 0.0, 0.7])
    cam = Camera.look_at(orbit_eye(np.radians(-55), np.radians(25), 5.0, target), target)
    n1 = n_points // 2
    a = rng.uniform(-1, 1, (n_points, 2))
    X = np.empty((n_points, 3))
    X[:n1] = np.column_stack([np.full(n1, 1.0), a[:n1, 0], 1.0 + a[:n1, 1]])
    X[n1:] = np.column_stack([a[n1:, 0], np.full(n_points - n1, -1.0), 1.0 + a[n1:, 1]])
    uv = cam.project(X) + rng.normal(0.0, sigma, (n_points, 2))
    return ResectionSet(cam, X, uv)

class GroundView(NamedTuple):
    """A ground grid seen by a tilted camera (lesson 06), with its exact vanishing geometry.

    Attributes
    ----------
    K, R : (3, 3) ndarray
        Intrinsics and the cam_from_world rotation (the camera sits at the world origin).
    segments : (M, 2, 2) ndarray
        The grid lines' images (pixels), clipped to the part in front of the camera: first the
        ``n_along_z`` lines running ahead (along z), then the lines across (along x).
    n_along_z : int
        How many of ``segments`` run ahead.
    vp_z, vp_x : (3,) ndarray
        Homogeneous vanishing points of the world directions z and x, :math:`K R d`.
    horizon : (3,) ndarray
        The ground's horizon line :math:`K^{-T} R n` (n = (0, 1, 0), the ground's normal).
    """

    K: np.ndarray
    R: np.ndarray
    segments: np.ndarray
    n_along_z: int
    vp_z: np.ndarray
    vp_x: np.ndarray
    horizon: np.ndarray


def ground_plane_view(pitch: float, yaw: float, focal: float, size: tuple[int, int] = (640, 480),
                      height: float = 1.5) -> GroundView:
    """A camera ``height`` metres over a ground grid, tilted down by ``pitch`` and turned by ``yaw`` (radians).

    ``focal`` in pixels, ``size`` (width, height) in pixels. This scene's world frame is the
    camera's before it turns: x right, y down (the ground is the plane y = ``height``), z
    ahead. A world direction d vanishes at :math:`K R d`, and the ground's horizon is
    :math:`K^{-T} R n`. Lines are clipped at 5 cm in front of the camera, so none flips
    through the pinhole.
    """
    w, h = check_size(size)
    f = check_positive(focal, "focal", "pixels")
    cam_height = check_positive(height, "height", "metres")
    K = np.array([[f, 0, (w - 1) / 2], [0, f, (h - 1) / 2], [0, 0, 1.0]])
    cp, sp, cy, sy = np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    Rx = np.array([[1, 0, 0], [0, cp, -sp], [0, sp, cp]])  # optical axis tilted down by +pitch
    Ry = np.array([[cy, 0, -sy], [0, 1, 0], [sy, 0, cy]])
    R = Rx @ Ry  # cam_from_world (the camera sits at the world origin)
    ticks = np.arange(-12.0, 12.1, 2.0)
    along_z = [np.array([[x, cam_height, 0.5], [x, cam_height, 2000.0]]) for x in ticks]
    along_x = [np.array([[-60.0, cam_height, z], [60.0, cam_height, z]]) for z in 2.0 * 1.4 ** np.arange(12)]
    near = 0.05
    segments = []
    for seg in along_z + along_x:
        a, b = seg @ R.T
        if a[2] < near and b[2] < near:
            continue  # wholly behind the camera
        if a[2] < near or b[2] < near:  # clip at the near plane so nothing flips through the pinhole
            s = (near - a[2]) / (b[2] - a[2])
            a, b = (a + s * (b - a), b) if a[2] < near else (a, a + s * (b - a))
        uv = np.stack([a, b]) @ K.T
        segments.append(uv[:, :2] / uv[:, 2:])
    return GroundView(K, R, np.array(segments).reshape(-1, 2, 2), len(along_z), K @ R @ np.array([0, 0, 1.0]),
                      K @ R @ np.array([1.0, 0, 0]), np.linalg.inv(K).T @ R @ np.array([0, 1.0, 0]))
