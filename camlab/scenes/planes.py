"""Flat textured rectangles for :func:`camlab.render.render`: planes, checkerboards, photos, pages, boxes.

A plane's frame has x along texture columns, y along texture rows, z = x cross y;
its pose is world_from_plane, metres.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, check_matrix, check_pose, check_positive, check_rotation
from .textures import as_texture, portrait


@lru_cache(maxsize=4)
def _text_texture(width_px: int, seed: int) -> np.ndarray:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    rng = np.random.default_rng(seed)
    words = (
        "camera lens pixel sensor light ray focus image plane point line matrix projective "
        "geometry calibration homography epipolar depth field aperture distortion"
    ).split()
    h_px = int(width_px * 1.414)
    fig = Figure(figsize=(width_px / 100, h_px / 100), dpi=100)
    FigureCanvasAgg(fig)
    fig.text(
        0.08, 0.94, "Chapter 1. Image formation", fontsize=width_px / 28, weight="bold", va="top"
    )
    for i in range(34):
        line = " ".join(rng.choice(words, size=7))
        fig.text(0.08, 0.88 - i * 0.024, line.capitalize() + ".", fontsize=width_px / 50, va="top")
    fig.canvas.draw()
    rgba = np.asarray(fig.canvas.buffer_rgba())
    grey = rgba[..., :3].mean(axis=2) / 255.0
    return as_texture(grey)


# An optician's chart: cap heights of its rows in texture pixels (600 px across the chart)
CHART_ROW_HEIGHTS = (90, 58, 38, 25, 16)
_CHART_LETTERS = "EFHKLNOPTZ"


@lru_cache(maxsize=4)
def _chart_texture(seed: int, rows: int = len(CHART_ROW_HEIGHTS)) -> np.ndarray:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    rng = np.random.default_rng(seed)
    w_px, h_px = 600, 500
    fig = Figure(figsize=(w_px / 100, h_px / 100), dpi=100)
    FigureCanvasAgg(fig)
    top = 30
    for cap in CHART_ROW_HEIGHTS[:rows]:
        letters = " ".join(rng.choice(list(_CHART_LETTERS), size=int(min(7, 380 // cap))))
        # DejaVu Sans capitals are about 0.73 em tall: a font size of cap / 0.73 pixels (at 100 dpi, 1 pt = 100/72 px)
        fig.text(
            0.5,
            1 - top / h_px,
            letters,
            fontsize=cap / 0.73 * 72 / 100,
            weight="bold",
            ha="center",
            va="top",
        )
        top += 1.6 * cap
    fig.canvas.draw()
    grey = np.asarray(fig.canvas.buffer_rgba())[..., :3].mean(axis=2) / 255.0
    return as_texture(grey)


def letter_chart(
    width: float = 0.3,
    *,
    R: ArrayLike | None = None,
    t: ArrayLike = (0, 0, 0),
    seed: int = 0,
    name: str = "chart",
    rows: int = len(CHART_ROW_HEIGHTS),
) -> Plane:
    """An optician's chart (6 : 5): rows of capitals, each row smaller, for judging blur by eye.

    The rows' cap heights are ``CHART_ROW_HEIGHTS`` / 600 of ``width`` (metres): the smallest row
    is still legible while a flat disc blur is smaller than about 4/5 of its height (lesson 01's
    ``camlab.widgets.pinhole_camera.legible_rows``, calibrated by eye on that demo's pictures).

    Parameters
    ----------
    width : float
        The chart's width, metres.
    R : (3, 3) array_like or None
        world_from_plane rotation; None is the identity.
    t : (3,) array_like
        world_from_plane translation: where the plane's origin is, metres.
    seed : int
        Seed of the letters' choice.
    name : str
        The plane's name.
    rows : int
        How many of the rows to print, largest first (a chart seen small leaves out the rows it
        could not show legibly even in focus).

    Returns
    -------
    Plane
        A centred grey plane, 5/6 as tall as wide.
    """
    if not 1 <= rows <= len(CHART_ROW_HEIGHTS):
        raise ValueError(
            f"letter_chart: rows must be 1 to {len(CHART_ROW_HEIGHTS)}, got {rows}; the chart has "
            f"{len(CHART_ROW_HEIGHTS)} rows"
        )
    return textured_plane(_chart_texture(int(seed), int(rows)), width, R=R, t=t, name=name)


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
        """Whether the texture is RGB (H, W, 3) rather than grey."""
        return self.texture.ndim == 3


def textured_plane(
    texture: ArrayLike,
    width: float,
    *,
    R: ArrayLike | None = None,
    t: ArrayLike = (0, 0, 0),
    height: float | None = None,
    centred: bool = True,
    name: str = "plane",
) -> Plane:
    """A rectangle ``width`` metres wide showing ``texture``; height from the texture's aspect by default.

    Parameters
    ----------
    texture : (H, W) or (H, W, 3) array_like
        Reflectance, grey or RGB (uint8, or float in [0, 1]; :func:`as_texture`).
    width : float
        The rectangle's width, metres (> 0).
    R : (3, 3) array_like or None
        world_from_plane rotation; None is the identity.
    t : (3,) array_like
        world_from_plane translation: where the plane's origin is, metres.
    height : float or None
        Its height, metres; None keeps the texture's aspect.
    centred : bool
        The plane frame's origin is the rectangle's centre (else its top-left corner).
    name : str
        The plane's name.

    Returns
    -------
    Plane
        The rectangle, no named points.
    """
    tex = as_texture(texture)
    w = check_positive(width, "width", "metres")
    h = (
        check_positive(height, "height", "metres")
        if height is not None
        else w * tex.shape[0] / tex.shape[1]
    )
    R, t = check_pose(R, t, name)
    extent = (-w / 2, -h / 2, w / 2, h / 2) if centred else (0.0, 0.0, w, h)
    return Plane(tex, extent, R, t, name=name)


def checkerboard(
    pattern_size: tuple[int, int] = (9, 6),
    square: float = 0.025,
    *,
    R: ArrayLike | None = None,
    t: ArrayLike = (0, 0, 0),
    margin: float = 1.0,
    px_per_square: int = 48,
    colours: tuple[float, float] = (0.05, 0.95),
    name: str = "board",
) -> Plane:
    """A checkerboard with ``pattern_size = (cols, rows)`` inner corners and ``square`` metres per square.

    It has ``cols + 1`` by ``rows + 1`` squares (the top-left one dark) inside a light
    border ``margin`` squares wide (the quiet zone detectors need). The plane's origin is
    the first inner corner; ``points`` are the inner corners row by row, ``(i * square,
    j * square)`` for ``j`` in rows, ``i`` in cols: the order and the object points of
    ``cv2.findChessboardCorners(img, pattern_size)`` for an upright board.

    Parameters
    ----------
    pattern_size : (cols, rows)
        Inner corners across and down, at least (2, 2).
    square : float
        Side of a square, metres (> 0).
    R : (3, 3) array_like or None
        world_from_plane rotation; None is the identity.
    t : (3,) array_like
        world_from_plane translation: where the plane's origin is, metres.
    margin : float
        Width of the light border, in squares (>= 0).
    px_per_square : int
        Texels per square side.
    colours : (float, float)
        The dark and light greys in [0, 1].
    name : str
        The plane's name.

    Returns
    -------
    Plane
        The board, with its inner corners as ``points`` and ``pattern_size`` set.

    Raises
    ------
    CamlabInputError
        If ``pattern_size``, ``square`` or ``margin`` is out of range.

    Examples
    --------
    >>> b = checkerboard((4, 3), 0.03)
    >>> b.points.shape, b.points[1], b.texture.shape
    ((12, 2), array([0.03, 0.  ]), (288, 336))
    """
    try:
        cols, rows = (int(v) for v in pattern_size)
    except (TypeError, ValueError):
        raise CamlabInputError(
            f"pattern_size: expected (cols, rows) inner corners, got {pattern_size!r}"
        ) from None
    if cols < 2 or rows < 2:
        raise CamlabInputError(
            f"pattern_size: expected at least (2, 2) inner corners, got {pattern_size!r}"
        )
    s = check_positive(square, "square", "metres")
    if not margin >= 0:
        raise CamlabInputError(f"margin: expected >= 0 squares, got {margin!r}")
    R, t = check_pose(R, t, name)
    n = int(px_per_square)
    m = int(round(margin * n))
    dark, light = colours
    sq = (np.add.outer(np.arange(rows + 1), np.arange(cols + 1)) % 2).astype(
        np.float32
    )  # 0 = dark at (0, 0)
    board = np.where(sq == 0, dark, light).astype(np.float32)
    tex = np.full(((rows + 1) * n + 2 * m, (cols + 1) * n + 2 * m), light, dtype=np.float32)
    tex[m : m + (rows + 1) * n, m : m + (cols + 1) * n] = np.kron(
        board, np.ones((n, n), dtype=np.float32)
    )
    tex.setflags(write=False)
    off = s + m * s / n  # first inner corner, measured from the texture's top-left edge
    extent = (-off, -off, tex.shape[1] * s / n - off, tex.shape[0] * s / n - off)
    jj, ii = np.mgrid[0:rows, 0:cols]
    pts = np.column_stack([ii.ravel() * s, jj.ravel() * s])
    return Plane(tex, extent, R, t, pts, name, (cols, rows))


def photo_plane(
    width: float = 0.4,
    *,
    R: ArrayLike | None = None,
    t: ArrayLike = (0, 0, 0),
    name: str = "photo",
    linear: bool = False,
    downsample: int = 1,
) -> Plane:
    """A centred rectangle showing matplotlib's bundled Grace Hopper photograph.

    The photograph is a JPEG, so its values are sRGB-encoded; ``linear=True`` decodes them
    to linear reflectance (:func:`camlab.sensor.gamma_decode`) for photometric work (lesson 03).

    Parameters
    ----------
    width : float
        The rectangle's width, metres.
    R : (3, 3) array_like or None
        world_from_plane rotation; None is the identity.
    t : (3,) array_like
        world_from_plane translation: where the plane's origin is, metres.
    name : str
        The plane's name.
    linear : bool
        Decode the photograph to linear reflectance.
    downsample : int
        Average each ``downsample x downsample`` block of the photograph (in linear light when
        ``linear``) into one texel. At 2 this undoes the JPEG's 2 x 2 chroma subsampling and
        averages away its 8 x 8 block artefacts, so a rendered image of the plane can stand as a
        clean full-colour truth (lesson 03's demosaicing).

    Returns
    -------
    Plane
        An RGB plane with the photograph's aspect.
    """
    if not isinstance(downsample, (int, np.integer)) or downsample < 1:
        raise CamlabInputError(
            f"photo_plane: downsample must be a whole number >= 1, got {downsample!r}; "
            "pass 1 for the photograph as it is, 2 to average 2 x 2 blocks"
        )
    return textured_plane(_portrait(bool(linear), int(downsample)), width, R=R, t=t, name=name)


@lru_cache(maxsize=4)
def _portrait(linear: bool, downsample: int) -> np.ndarray:
    img = _linear_portrait() if linear else portrait()
    if downsample == 1:
        return img
    h, w = (n // downsample * downsample for n in img.shape[:2])
    blocks = img[:h, :w].reshape(h // downsample, downsample, w // downsample, downsample, 3)
    return as_texture(blocks.mean(axis=(1, 3)))


@lru_cache(maxsize=1)
def _linear_portrait() -> np.ndarray:
    from ..sensor import gamma_decode

    return as_texture(gamma_decode(portrait()))


def text_page(
    width: float = 0.21,
    *,
    R: ArrayLike | None = None,
    t: ArrayLike = (0, 0, 0),
    seed: int = 0,
    name: str = "page",
) -> Plane:
    """A printed page (A4 proportions) of deterministic pseudo-text, rendered with matplotlib's Agg.

    Parameters
    ----------
    width : float
        The page's width, metres (its height is 1.414 times it).
    R : (3, 3) array_like or None
        world_from_plane rotation; None is the identity.
    t : (3,) array_like
        world_from_plane translation: where the plane's origin is, metres.
    seed : int
        Seed of the words' choice.
    name : str
        The plane's name.

    Returns
    -------
    Plane
        A centred grey plane.
    """
    return textured_plane(_text_texture(600, int(seed)), width, R=R, t=t, name=name)


def box(
    centre: ArrayLike,
    size: ArrayLike,
    *,
    R: ArrayLike | None = None,
    colours: Sequence[float] | None = None,
    texture: str = "noise",
    texels: int = 64,
    rng: np.random.Generator | int | None = 0,
    name: str = "box",
) -> list[Plane]:
    """The six faces of a box, as planes with outward normals (z = x cross y points out).

    Faces get names ``f"{name}+x"`` ... and their 4 corners as named points.

    Parameters
    ----------
    centre : (3,) array_like
        World position, metres.
    size : (3,) array_like
        Edge lengths along the box's own x, y, z axes, metres (> 0).
    R : (3, 3) array_like or None
        world_from_box rotation; None (the default) is the identity.
    colours : sequence of float or None
        Six greys in [0, 1] (faces +x, -x, +y, -y, +z, -z); distinct shades by default.
    texture : str
        ``"noise"`` (random texture on each face: good for stereo matching) or ``"flat"``.
    texels : int
        Texels along each face's longer side.
    rng : numpy.random.Generator, int seed or None
        Randomness of the noise texture (deterministic by default).
    name : str
        Prefix of the faces' names.

    Returns
    -------
    list of Plane
        The faces +x, -x, +y, -y, +z, -z, one-sided (culled from behind).

    Raises
    ------
    CamlabInputError
        If ``size`` has a non-positive length, ``R`` is not a rotation or ``texture`` is unknown.
    """
    c = check_matrix(centre, (3,), "centre")
    sz = check_matrix(size, (3,), "size")
    if np.any(sz <= 0):
        raise CamlabInputError(
            f"size: expected three positive edge lengths in metres, got {sz.tolist()}"
        )
    Rb = np.eye(3) if R is None else check_rotation(R, f"{name} R")
    if texture not in ("noise", "flat"):
        raise CamlabInputError(f"texture: expected 'noise' or 'flat', got {texture!r}")
    shades = list(colours) if colours is not None else [0.75, 0.45, 0.6, 0.3, 0.85, 0.55]
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
        faces.append(
            Plane(
                as_texture(base),
                (-w / 2, -h / 2, w / 2, h / 2),
                Rf,
                tf,
                pts,
                label,
                two_sided=False,
            )
        )
    return faces
