"""Demo for lesson 08, section 2: one view's two constraints on K, as lines you can tilt.

* :func:`tilt_constraints`: tilt one chessboard view; its two Zhang equations are two lines in
  the plane of (1/fx^2, 1/fy^2) (zero skew, known principal point). Tilted, they cross at K;
  turned towards fronto-parallel, both swing onto the aspect-ratio line through the origin and
  their crossing, with noise, runs away.

The figure is built once; updates fit the view's homography and move the lines.
"""

from __future__ import annotations

from types import SimpleNamespace

import ipywidgets as W
import numpy as np

from .. import calibration as C
from ..camera import rotation_from_axis_angle
from ..plotting import palette
from ._base import Demo, FigureView, build_demo, register, slider
from .controls import monospace

_K = np.array([[820.0, 0.0, 322.4], [0.0, 818.0, 236.8], [0.0, 0.0, 1.0]])  # section 1's camera
_ROLL = 0.4  # rad: the board turned in its own plane, as section 2's fronto-parallel view
_COINCIDE_DEG = 1e-3  # lines closer than this are one line (they are 0 to rounding when degenerate)
_TRUTH = 1e6 / np.diag(_K)[:2] ** 2  # (1/fx^2, 1/fy^2) in 10^-6 px^-2


def _iac_lines(H: np.ndarray) -> np.ndarray:
    """A view's two equations as rows (p, q, s) of p a + q b + s = 0, (a, b) in 10^-6 px^-2."""
    G = np.array([[1.0, 0, -_K[0, 2]], [0, 1, -_K[1, 2]], [0, 0, 1]]) @ H  # origin at the pp
    h1, h2 = G[:, 0], G[:, 1]
    rows = np.array([h1 * h2, h1**2 - h2**2]) / np.linalg.norm(G) ** 2  # B = diag(a, b, 1)
    return rows * [1.0, 1.0, 1e6]


def _segment(line: np.ndarray, reach: float) -> np.ndarray:
    """Two points of ``line`` (p, q, s), ``reach`` either side of its point nearest the origin."""
    p, q, s = line
    n2 = p * p + q * q
    foot = -s * np.array([p, q]) / n2
    d = np.array([q, -p]) / np.sqrt(n2)
    return np.array([foot - reach * d, foot + reach * d])


def _view(tilt_deg: float, axis_deg: float, noise: float, unit: np.ndarray, obj: np.ndarray):
    """The board tilted by ``tilt_deg`` about an in-plane axis at ``axis_deg``; noisy corners, px."""
    a = np.radians(axis_deg)
    R = rotation_from_axis_angle(np.radians(tilt_deg) * np.array([np.cos(a), np.sin(a), 0.0]))
    R = R @ rotation_from_axis_angle([0.0, 0.0, _ROLL])  # turned in its plane first
    centre = obj.mean(axis=0)
    t = np.array([0.0, 0.0, 0.5]) - R @ centre  # the board's centre 0.5 m in front
    X = obj @ R.T + t
    px = X[:, :2] / X[:, 2:] * np.diag(_K)[:2] + _K[:2, 2]
    return px + noise * unit


def _figure(view: FigureView) -> SimpleNamespace:
    """The (1/fx^2, 1/fy^2) plane with the truth; returns the animated artists by name."""
    ax = view.fig.subplots()
    lim = 2 * _TRUTH
    ax.set(
        xlim=(0, lim[0]),
        ylim=(0, lim[1]),
        xlabel="1/fx² (10⁻⁶ px⁻²)",
        ylabel="1/fy² (10⁻⁶ px⁻²)",
    )
    ax.grid(True, color="0.9")
    ax.set_axisbelow(True)
    ax.plot([0, lim[0]], [0, lim[0] * _TRUTH[1] / _TRUTH[0]], ":", color=palette.GREY, lw=1.2,
            label="aspect-ratio line (fronto-parallel view)")  # fmt: skip
    (solid,) = ax.plot([], [], "-", color=palette.BLUE, lw=1.6, label="h₁ᵀBh₂ = 0")
    (dashed,) = ax.plot([], [], "--", color=palette.BLUE, lw=1.6, label="equal lengths")
    # a hollow ring, so the truth star stays visible inside it; the star is animated too, so the
    # live path (which paints animated artists over a cached background) keeps it on top
    (cross,) = ax.plot(
        [], [], "o", mfc="none", mec=palette.BLUE, mew=2, ms=14, label="where they cross"
    )
    (truth,) = ax.plot(
        *_TRUTH, "*", color="k", mec="w", ms=12, zorder=5, label="truth (1/fx², 1/fy²)"
    )
    view.animate(solid, dashed, cross, truth)
    ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.02, 0.5))  # beside, off the lines
    ax.set_title(" ", fontsize=10)
    view.animate(ax.title)
    return SimpleNamespace(solid=solid, dashed=dashed, cross=cross, title=ax.title)


@register(
    lesson="08",
    sweep={"tilt": [30.0, 0.0, 5.0, 60.0], "axis": [45.0, 0.0, 90.0], "noise": [0.0, 0.5]},
)
def tilt_constraints() -> Demo:
    """Tilt one board view: its two constraint lines on (1/fx^2, 1/fy^2) and where they cross.

    Returns
    -------
    Demo
        The demo: controls ``tilt`` (the board's tilt from facing the camera, degrees),
        ``axis`` (the direction of the tilt axis in the board's plane, degrees) and ``noise``
        (corner noise, px), the figure (the view's two lines, their crossing and the truth) and
        ``state`` (``angle_deg`` between the lines, ``coincide`` when they are one line,
        ``fx``, ``fy`` where they cross, NaN when they do not or coincide, and ``fx_error``
        relative to the truth).
    """
    obj = C.board_points((9, 6), 0.025)
    unit = np.random.default_rng(3).normal(size=(len(obj), 2))  # one fixed draw, scaled by noise
    view = FigureView(figsize=(8.4, 4.2))
    art = _figure(view)
    reach = 4 * float(np.linalg.norm(_TRUTH))
    readout = W.HTML()

    def update(v: dict, state: dict) -> None:
        px = _view(float(v["tilt"]), float(v["axis"]), float(v["noise"]), unit, obj)
        H = C.view_homographies(obj, [px])[0]
        lines = _iac_lines(H)
        for artist, line in zip((art.solid, art.dashed), lines, strict=True):
            artist.set_data(*_segment(line, reach).T)
        normals = lines[:, :2] / np.linalg.norm(lines[:, :2], axis=1, keepdims=True)
        angle = float(np.degrees(np.arccos(min(1.0, abs(normals[0] @ normals[1])))))
        coincide = angle < _COINCIDE_DEG
        with np.errstate(divide="ignore", invalid="ignore"):
            ab = np.full(2, np.nan) if coincide else np.linalg.solve(lines[:, :2], -lines[:, 2])
        f = np.sqrt(1e6 / ab) if np.all(ab > 0) else np.full(2, np.nan)
        art.cross.set_data(ab[:1], ab[1:])
        err = f[0] / _K[0, 0] - 1
        if coincide:
            verdict = "the two lines coincide: any point on them fits"
        elif np.isfinite(err):
            verdict = f"fx {round(100 * err, 1) + 0:+.1f} %"  # + 0: no "-0.0 %"
            verdict += "" if np.all((ab >= 0) & (ab <= 2 * _TRUTH)) else " (off the plot)"
        else:
            verdict = "they cross outside fx², fy² > 0"
        art.title.set_text(
            f"tilt {v['tilt']:.0f}°, noise {v['noise']:.2f} px: lines {angle:.1f}° apart\n{verdict}"
        )
        state.update(
            angle_deg=angle, coincide=coincide, fx=float(f[0]), fy=float(f[1]), fx_error=float(err)
        )
        if coincide:
            found = "the two lines coincide: one equation, a whole line of (fx, fy) fits, K is not determined"
        elif np.all(np.isfinite(f)):
            found = f"they cross at fx = {f[0]:.0f}, fy = {f[1]:.0f} px (truth {_K[0, 0]:.0f}, {_K[1, 1]:.0f})"
        else:
            found = "they cross outside positive 1/fx², 1/fy²: K is not determined"
        readout.value = monospace(f"angle between the two lines: {angle:.2f}°\n" + found)

    controls = {
        "tilt": slider(30.0, 0.0, 60.0, 1.0, "tilt (°)"),
        "axis": slider(45.0, 0.0, 180.0, 5.0, "tilt axis (°)"),
        "noise": slider(0.0, 0.0, 1.0, 0.05, "corner noise σ (px)"),
    }
    return build_demo(
        "tilt_constraints",
        controls,
        view,
        update,
        title="One view, two lines: tilt the board",
        extra=[readout],
    )
