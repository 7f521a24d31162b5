"""Lesson 07 demo on the homographies that come from geometry: a plane's, and the parallax off it."""

from __future__ import annotations

import cv2
import ipywidgets as W
import numpy as np
from matplotlib.patches import Rectangle

from ... import homography as hg
from ...plotting import palette
from ...projective import map_points
from .._base import Demo, FigureView, build_demo, register, slider
from ..controls import monospace

K_PARALLAX = np.array([[800.0, 0, 320], [0, 800, 240], [0, 0, 1]])
"""Both cameras' intrinsics (640 x 480 images), as in section 9's cells."""
DEPTHS = (1.5, 3.0, 6.0)
"""The depths (metres, along camera 1's axis) of the three points on each ray."""
# One look per depth, as in section 9's static figure: magenta and olive appear nowhere else.
_LOOKS = (("o", palette.MAGENTA, 9), ("s", "k", 5.5), ("D", palette.OLIVE, 6))
_NESTED = dict(zip(DEPTHS, (11, 7, 4), strict=True))
"""Marker sizes when the three depths coincide (no parallax): nested, so all three stay visible."""


def _rays() -> np.ndarray:
    """The 12 rays of camera 1 (directions with z = 1), through pixels left of its centre.

    They are 144 px apart across and 91 px down, so at the default motion the largest parallax (52 px,
    at Z = 1.5 m) stays well under half the spacing: each point lies nearer its own ring than any other.
    """
    uv = np.stack(np.meshgrid(np.linspace(-0.39, -0.03, 3), np.linspace(-0.08, 0.26, 4)), -1)
    return np.column_stack([uv.reshape(-1, 2), np.ones(12)])


def _project(X: np.ndarray, R: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Pixels of points X (camera 1's frame) in a camera K[R | t] (NaN behind it)."""
    x = (X @ R.T + t) @ K_PARALLAX.T
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(x[:, 2:] > 0, x[:, :2] / x[:, 2:], np.nan)


def _inside(x: np.ndarray) -> np.ndarray:
    """True for pixels inside camera 2's 640 x 480 image (False for NaN, behind the camera)."""
    with np.errstate(invalid="ignore"):
        return np.all((x >= -0.5) & (x <= [639.5, 479.5]), axis=1)


def _in_view(x: np.ndarray) -> np.ndarray:
    """The pixels inside camera 2's image; NaN (not drawn) for the others, which the readout counts."""
    return np.where(_inside(x)[:, None], x, np.nan)


def _segments(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Segments a[i] -> b[i] as one polyline broken by NaN rows (for a single Line2D)."""
    gap = np.full_like(a, np.nan)
    return np.stack([a, b, gap], axis=1).reshape(-1, 2)


def _median_parallax(predicted, wheres) -> tuple[dict, dict, int]:
    """The median parallax |x2 - H x1| per depth, over the same rays at every depth.

    Parameters
    ----------
    predicted : (N, 2) ndarray
        Where H sends camera 1's pixel of each ray (pixels).
    wheres : dict
        Depth Z (m) -> (N, 2) ndarray, where camera 2 really sees the ray's point at that depth.

    Returns
    -------
    tuple
        (median parallax per depth in px, rays out of view per depth, the number of rays in view
        at every depth). The medians are over those rays, so the depths compare like for like;
        if none is in view at every depth, each median is over the rays in view at its own depth.
    """
    shown = {Z: _inside(w) & _inside(predicted) for Z, w in wheres.items()}  # both marks in view
    common = np.logical_and.reduce(list(shown.values()))
    parallax, hidden = {}, {}
    for Z, where in wheres.items():
        hidden[Z] = int(np.sum(~shown[Z]))
        gap = np.linalg.norm(where - predicted, axis=1)[common if common.any() else shown[Z]]
        parallax[Z] = float(np.median(gap)) if gap.size else float("nan")
    return parallax, hidden, int(common.sum())


def _parallax_figure():
    """The parallax demo's figure: its view, the rings' artist, and per depth the lines and the points."""
    view = FigureView(figsize=(6.4, 5.0))
    ax = view.fig.subplots()
    ax.add_patch(Rectangle((-0.5, -0.5), 640, 480, fill=False, ec="0.6", lw=1, ls=":"))
    ax.set(
        xlim=(-30, 670), ylim=(505, -25), aspect="equal", xlabel="u (pixels)", ylabel="v (pixels)"
    )
    ax.set_title(
        "camera 2's 640 x 480 image (dotted): a line to a mark outside it stops at its edge",
        fontsize=10,
    )
    # each ring's line to its point is cut at the image's border, so a point whose ring (or a ring
    # whose point) lies outside still shows which way its partner is
    frame = Rectangle((-0.5, -0.5), 640, 480, transform=ax.transData)
    rings = view.animate(
        ax.plot(
            [],
            [],
            "o",
            ms=14,
            mfc="none",
            mec=palette.GREY,
            mew=1.5,
            label="H x: camera 1's pixel, mapped by H",
        )[0]
    )
    gaps, seen = [], []
    for Z, (marker, colour, size) in zip(DEPTHS, _LOOKS, strict=True):
        gaps.append(view.animate(ax.plot([], [], "-", color=colour, lw=1.2)[0]))
        gaps[-1].set_clip_path(frame)  # after plot: add_line keeps the axes' clip box only
        seen.append(
            view.animate(
                ax.plot(
                    [],
                    [],
                    marker,
                    ms=size,
                    color=colour,
                    mec="k",
                    mew=0.6,
                    ls="none",
                    label=f"seen by camera 2, Z = {Z:g} m",
                )[0]
            )
        )
    view.fig.legend(loc="outside lower center", ncols=2, fontsize=8)
    return view, rings, gaps, seen


@register(lesson="07", sweep={"move": [0.0, -0.4, 0.4], "turn": [0.0, 20.0], "plane": [1.5, 6.0]})
def plane_parallax() -> Demo:
    r"""Move and turn camera 2: the plane's homography, and the parallax of points off the plane.

    Camera 1 is :math:`K[I \mid 0]`; camera 2 is :math:`K[R \mid t]`, turned by ``turn``
    degrees about its vertical axis (plus a fixed small tilt) and moved ``move`` metres
    sideways (``t = (move, -move / 4, move / 8)``). The plane is :math:`Z = d` in camera 1
    (``plane``), so :math:`n = (0, 0, -1)` and :math:`H = K(R - t n^T / d)K^{-1}`
    (:func:`camlab.homography.plane_homography`). On 12 rays of camera 1 sit points at
    the depths :data:`DEPTHS`; camera 2 sees each where it really is, and :math:`H` sends
    camera 1's pixel of the ray to where the point *of the plane* on that ray would appear.
    The gap is the parallax: zero on the plane, zero for every depth when camera 2 only turns,
    and otherwise proportional to :math:`|1/Z - 1/d|` to first order.

    Returns
    -------
    Demo
        The demo: controls ``move`` (metres), ``turn`` (degrees) and ``plane`` (d, metres), the
        figure (camera 2's 640 x 480 image: grey rings at :math:`H x`, the points at the three
        depths, each joined to its ring by a line cut at the image's border) and ``state`` (``H``, ``parallax``: depth -> the
        median parallax over the rays whose two marks are both inside camera 2's image, pixels;
        ``outside``: depth -> how many of the 12 rays that leaves out).

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 13.1,
       eq. (13.2).
    """
    rays = _rays()
    x_first = _project(rays, np.eye(3), np.zeros(3))  # camera 1: one pixel per ray
    view, rings, gaps, seen = _parallax_figure()
    readout = W.HTML()

    def update(v: dict, state: dict) -> None:
        R = cv2.Rodrigues(np.array([0.05, np.radians(v["turn"]), 0.02]))[0]
        t = v["move"] * np.array([1.0, -0.25, 0.125])
        H = hg.plane_homography(K_PARALLAX, R, t, np.array([0.0, 0.0, -1.0]), v["plane"])
        predicted = map_points(H, x_first)  # where H sends camera 1's pixel of each ray
        rings.set_data(*_in_view(predicted).T)
        wheres = {
            Z: _project(rays * Z, R, t) for Z in DEPTHS
        }  # where camera 2 really sees each point
        parallax, hidden, common = _median_parallax(predicted, wheres)
        nested = max(parallax.values(), default=0.0) < 1.0  # the three marks coincide: nest them
        for Z, gap_art, seen_art, look in zip(DEPTHS, gaps, seen, _LOOKS, strict=True):
            gap_art.set_data(*_segments(predicted, wheres[Z]).T)  # clipped to the image
            seen_art.set_data(*_in_view(wheres[Z]).T)
            seen_art.set_markersize(_NESTED[Z] if nested else look[2])
        state.update(H=H, parallax=parallax, outside=hidden, common=common)
        over = (
            f"over the {common} rays in view at all three depths"
            if common
            else "over the rays in view at each depth (none is in view at all three)"
        )
        lines = [f"plane Z = {v['plane']:g} m; median parallax |x2 - H x1| {over}:"]
        lines += [
            f"  Z = {Z:>3g} m: {p:6.1f} px   (|1/Z - 1/d| = {abs(1 / Z - 1 / v['plane']):.3f} /m)"
            + (f"  {hidden[Z]} of 12 rays left out (point or ring outside)" if hidden[Z] else "")
            for Z, p in parallax.items()
        ]
        readout.value = monospace("\n".join(lines))

    controls = {
        "move": slider(0.2, -0.4, 0.4, 0.05, "camera 2 moves (m)"),
        "turn": slider(14.3, 0.0, 20.0, 0.1, "camera 2 turns (°)"),
        "plane": slider(3.0, 1.5, 6.0, 0.1, "plane distance d (m)"),
    }
    return build_demo(
        "plane_parallax", controls, view, update, title="Parallax off the plane", extra=[readout]
    )
