r"""Lesson 12's flipped-pose demo: a flat target's two IPPE poses, and how far apart their corners are.

A flat target has a second pose that nearly explains its corners: the target tilted the other
way about a line in its plane (the planar-pose ambiguity; Schweighofer & Pinz 2006, Collins &
Bartoli 2014). OpenCV's ``SOLVEPNP_IPPE`` returns both. The flipped pose fits noisy corners
better only if the noise, in the one direction that separates the two reprojections, reaches
their midpoint: the gap, half their distance over all :math:`2N` coordinates, in units of the
corner noise :math:`\sigma`, and the chance of a flip is about :math:`\Phi(-\text{gap})`
(lesson 12, section 2b).

In a lesson::

    %matplotlib widget
    from camlab.widgets import flip_pose
    flip_pose.flip_pose()
"""

from __future__ import annotations

from math import erfc, sqrt
from types import SimpleNamespace

import ipywidgets as W
import numpy as np
from matplotlib.ticker import FuncFormatter

from ..plotting import palette
from ._base import Demo, FigureView, build_demo, register, slider
from .controls import monospace
from .measure_the_world import BOARD, CENTRE, K_DEMO, SIGMA_PX, geometry

__all__ = ["TARGETS", "flip_poses", "flip_pose"]


def _tag(side: float) -> np.ndarray:
    """A square tag's 4 corners (metres), centred where the board's centre is."""
    h = side / 2
    return CENTRE + np.array([[-h, -h, 0.0], [h, -h, 0.0], [h, h, 0.0], [-h, h, 0.0]])


TARGETS = {"board (54 corners)": BOARD, "tag 10 cm": _tag(0.10), "tag 5 cm": _tag(0.05)}
"""The targets of section 2b: the 9 x 6 board (25 mm squares) and two square tags of 4 corners."""
TILT_CURVE = np.arange(1.0, 41.0, 1.0)
GAP_LIM = (0.01, 1000.0)


def flip_poses(points: np.ndarray, tilt_deg: float, distance: float) -> SimpleNamespace:
    r"""Both IPPE poses of a flat target seen by the demo's camera, and the gap between them.

    Parameters
    ----------
    points : (N, 3) ndarray
        The target's corners on the plane z = 0, metres.
    tilt_deg : float
        The viewing direction's angle from the target's normal, degrees.
    distance : float
        From the camera to the board's centre, metres.

    Returns
    -------
    SimpleNamespace
        ``eye`` and ``eye2`` (the true and the flipped camera centres, board frame, m);
        ``clean`` and ``second`` (their noise-free reprojections, px); ``gap`` (in sigma),
        ``rule`` (:math:`\Phi(-\text{gap})`), ``dR`` (deg), ``dC`` (mm) and ``largest`` (px).
    """
    import cv2

    g = geometry(tilt_deg, distance)
    clean = (points @ g.R.T + g.t) @ K_DEMO.T
    clean = clean[:, :2] / clean[:, 2:]
    _, rv, tv, _ = cv2.solvePnPGeneric(points, clean, K_DEMO, None, flags=cv2.SOLVEPNP_IPPE)
    Rs = [cv2.Rodrigues(r)[0] for r in rv]
    k = max(
        range(len(Rs)), key=lambda i: np.linalg.norm(Rs[i] - g.R)
    )  # the one farther from the truth
    R2, t2 = Rs[k], tv[k].ravel()
    second = (points @ R2.T + t2) @ K_DEMO.T
    second = second[:, :2] / second[:, 2:]
    gap = float(np.linalg.norm(second - clean) / 2 / SIGMA_PX)
    dR = np.degrees(np.arccos(np.clip((np.trace(R2 @ g.R.T) - 1) / 2, -1, 1)))
    eye2 = -R2.T @ t2
    return SimpleNamespace(
        eye=g.eye,
        eye2=eye2,
        clean=clean,
        second=second,
        gap=gap,
        rule=0.5 * erfc(gap / sqrt(2)),
        dR=float(dR),
        dC=float(1000 * np.linalg.norm(eye2 - g.eye)),
        largest=float(np.linalg.norm(second - clean, axis=1).max()),
    )


def _figure() -> SimpleNamespace:
    """The side view to scale (left) and the gap against the tilt (right)."""
    view = FigureView(figsize=(9.6, 4.4))
    ax, ax_gap = view.fig.subplots(1, 2, width_ratios=[1.0, 1.0])
    ax.set(xlim=(-1.5, 1.6), ylim=(-0.1, 2.1), aspect="equal")
    ax.set_xlabel("board y (m)", fontsize=8)
    ax.set_ylabel("height above the board (m)", fontsize=8)
    ax_gap.set(xlim=(0, 41), ylim=GAP_LIM, yscale="log")
    ax_gap.yaxis.set_major_formatter(FuncFormatter(lambda y, _: f"{y:g}"))
    ax_gap.set_xlabel("tilt from the target's normal (deg)", fontsize=8)
    ax_gap.set_ylabel("gap (σ, log scale)", fontsize=8)
    for a in (ax, ax_gap):
        a.tick_params(labelsize=7)
        a.grid(alpha=0.3)
        a.set_title(" ", fontsize=9)  # set by update
    f = SimpleNamespace(view=view, ax=ax, ax_gap=ax_gap)
    (f.target,) = ax.plot([], [], "-", color="0.1", lw=3, zorder=4, label="the target (side on)")
    (f.true,) = ax.plot(
        [],
        [],
        "-o",
        color=palette.ORANGE,
        lw=1.5,
        ms=7,
        markevery=[1],
        label="the camera at its true pose",
    )
    (f.flip,) = ax.plot(
        [],
        [],
        "--o",
        color=palette.RED,
        mfc="none",
        lw=1.5,
        ms=7,
        markevery=[1],
        label="the flipped pose's camera",
    )
    ax_gap.axhline(
        2.0, color="0.4", lw=1, ls=":", label="gap 2 σ: the rule Φ(−2) = 2.3 % of photos"
    )
    (f.curve,) = ax_gap.plot(
        [], [], "-", color=palette.BLUE, lw=1.8, label="gap σ at this distance"
    )
    (f.here,) = ax_gap.plot([], [], "o", mfc="none", mec="0.1", mew=1.5, ms=8, label="this tilt")
    handles = sum((a.get_legend_handles_labels()[0] for a in (ax, ax_gap)), [])
    view.fig.legend(handles=handles, loc="outside lower center", ncols=3, fontsize=7)
    view.animate(f.target, f.true, f.flip, ax.title)
    view.animate(f.curve, f.here, ax_gap.title)
    return f


def _readout(p: SimpleNamespace, name: str, n: int) -> str:
    # never "0.0%" (the chance is never zero), and no "<": the readout is HTML
    chance = f"≈ {p.rule:.1%}" if p.rule >= 0.0005 else "below 0.05%"
    return monospace(
        f"{name}: {2 * n} coordinates, noise {SIGMA_PX} px each\n"
        f"gap = half the two reprojections' distance = {p.gap:.1f} σ\n"
        f"the flipped pose fits better with chance {chance} by the rule Φ(−gap)\n"
        "  (the rule's estimate; optimistic near head-on, section 2b)\n"
        f"the two poses differ by a rotation of {p.dR:.0f}° and put the camera {p.dC:.0f} mm apart,\n"
        f"while the target's corners in the image move by at most {p.largest:.2f} px"
    )


@register(
    lesson="12",
    sweep={"tilt": [2.0, 40.0], "distance": [0.4, 2.0], "target": ["tag 10 cm", "tag 5 cm"]},
)
def flip_pose() -> Demo:
    r"""A flat target's true and flipped poses, side on, and the gap between them against the tilt.

    The camera of the shipped photos (``measure_the_world.K_DEMO``) looks at the target's centre
    from ``distance`` metres, ``tilt`` degrees off its normal. OpenCV's ``SOLVEPNP_IPPE`` gives the
    flipped pose from the noise-free corners (:func:`flip_poses`); the left panel draws both
    camera centres to scale in the board's y-z plane, the right one the gap against the tilt.

    Returns
    -------
    Demo
        Controls ``tilt`` (degrees), ``distance`` (metres) and ``target``; ``state`` holds
        ``gap`` (sigma), ``rule`` (:math:`\Phi(-\text{gap})`), ``dR_deg``, ``dC_mm``,
        ``largest_px`` and the ``readout`` text.
    """
    fig = _figure()
    readout = W.HTML()

    def update(v, state):
        pts = TARGETS[v["target"]]
        p = flip_poses(pts, v["tilt"], v["distance"])
        ys = pts[:, 1]
        fig.target.set_data([ys.min(), ys.max()], [0.0, 0.0])
        fig.true.set_data([CENTRE[1], p.eye[1]], [0.0, -p.eye[2]])
        fig.flip.set_data([CENTRE[1], p.eye2[1]], [0.0, -p.eye2[2]])
        gaps = [flip_poses(pts, a, v["distance"]).gap for a in TILT_CURVE]
        fig.curve.set_data(TILT_CURVE, np.clip(gaps, *GAP_LIM))
        fig.here.set_data([v["tilt"]], [np.clip(p.gap, *GAP_LIM)])
        fig.ax.title.set_text(f"to scale: the two cameras {p.dC:.0f} mm apart")
        fig.ax_gap.title.set_text(f"{v['target']} at {v['distance']:.1f} m: gap {p.gap:.1f} σ here")
        readout.value = _readout(p, v["target"], len(pts))
        state.update(
            gap=p.gap,
            rule=p.rule,
            dR_deg=p.dR,
            dC_mm=p.dC,
            largest_px=p.largest,
            readout=readout.value,
        )

    controls = {
        "tilt": slider(20.0, 1.0, 40.0, 1.0, "tilt (deg)"),
        "distance": slider(1.5, 0.4, 2.0, 0.1, "distance (m)"),
        "target": W.Dropdown(options=list(TARGETS), value="tag 5 cm", description="target"),
    }
    return build_demo(
        "flip_pose",
        controls,
        fig.view,
        update,
        title="The flipped pose of a flat target",
        extra=[readout],
    )
