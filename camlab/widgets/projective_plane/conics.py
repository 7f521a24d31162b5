"""The demo of lesson 06, section 7: a conic and its image under a homography."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import projective as pj
from ...plotting import palette
from ...plotting.plane import plane_axes, set_line
from .._base import Demo, FigureView, build_demo, register, slider
from ..browser import BrowserView
from ..browser.plane_scenes import conic_scene
from .twins import conic_caption, conic_geometry


def _conic_figure(view: FigureView) -> SimpleNamespace:
    """The figure of :func:`conic_under_homography`.

    The unit circle with its tangent square and the line H sends to infinity (left), their images (right), legends under both and a
    text strip for the circular points (in the figure, so a static copy shows it too); returns its
    axes and artists by name.
    """
    axes = view.fig.subplot_mosaic([["before", "after"], ["text", "text"]], height_ratios=[1, 0.13])
    ax_b, ax_a, ax_t = axes["before"], axes["after"], axes["text"]
    plane_axes(ax_b, 3.0, "before: a circle C and 4 tangents")
    plane_axes(ax_a, 3.0, "after H: C' = H^-T C H^-1 (same scale)")
    ax_t.set_axis_off()
    t = np.linspace(0, 2 * np.pi, 9)[:-1]
    samples = np.stack([np.cos(t), np.sin(t)], axis=1)  # 8 points on the unit circle
    circle = pj.conic_points(pj.circle_conic([0.0, 0.0], 1.0), 200)
    ax_b.plot(*circle.T, color=palette.TAB_BLUE, lw=2, label="C (x² + y² = 1)")
    ax_b.scatter(  # blue: the object given (lesson 06); white edges keep them visible on C
        *samples.T,
        color=palette.TAB_BLUE,
        edgecolors="white",
        linewidths=1,
        s=36,
        zorder=3,
        label="8 points on C",
    )
    for k, line in enumerate(([1, 0, -1], [1, 0, 1], [0, 1, -1], [0, 1, 1])):
        ends = pj.clip_line(line, (-3, 3), (-3, 3))
        ax_b.plot(*ends.T, color=palette.GREEN, lw=1, label="tangent lines" if k == 0 else None)
    ax_b.plot([0], [0], "k+", ms=10, mew=2, label="centre of C")
    (to_infinity,) = ax_b.plot(  # h31 x + h32 y + 1 = 0, moved by update
        [], [], "--", color=palette.TAB_RED, lw=2, label="the line H sends to ∞"
    )
    (conic,) = ax_a.plot([], [], color=palette.TAB_BLUE, lw=2, label="C' from the formula")
    mapped = ax_a.scatter(
        *samples.T, color=palette.ORANGE, s=25, zorder=3, label="H x (the 8 points)"
    )
    tangents = [ax_a.plot([], [], color=palette.GREEN, lw=1)[0] for _ in range(4)]
    (centre_image,) = ax_a.plot([], [], "k+", ms=10, mew=2, label="H (centre of C)")
    (centre_conic,) = ax_a.plot(
        [], [], "x", color=palette.TAB_RED, ms=8, mew=2, label="centre of C'"
    )
    for a in (ax_b, ax_a):
        a.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2, fontsize=8)
    text = ax_t.text(
        0.0, 1.0, "", transform=ax_t.transAxes, va="top", ha="left", family="monospace", fontsize=8
    )
    return SimpleNamespace(
        samples=samples,
        to_infinity=to_infinity,
        conic=conic,
        mapped=mapped,
        tangents=tangents,
        centre_image=centre_image,
        centre_conic=centre_conic,
        text=text,
        ax_b=ax_b,
        ax_a=ax_a,
    )


@register(
    lesson="06",
    sweep={
        "angle": [-45.0, 45.0],
        "aspect": [0.6, 1.4],
        "h31": [0.0, -0.35, 0.35],
        "h32": [0.0, 0.35],
    },
)
def conic_under_homography() -> Demo:
    """A circle under a homography becomes an ellipse C' = H^-T C H^-1; its tangents map by H^-T.

    H rotates by ``angle``, stretches x by ``aspect`` and has the perspective row (h31, h32, 1).
    The text under the plots says where H sends the circular point I = (1, i, 0): back to itself
    exactly when H is a similarity (aspect 1, h31 = h32 = 0), and then the circle stays a circle.

    Returns
    -------
    Demo
        The demo: controls ``angle`` (degrees), ``aspect``, ``h31``, ``h32``, the figure and ``state``
        (``H``, ``C_mapped`` the conic H^-T C H^-1, ``residual`` the largest |x'^T C' x'| over the 8
        mapped points (C' scaled to unit norm, the points to w = 1), ``tangent_residual`` the same for
        the 4 mapped tangents against the dual conic H C* H^T, ``I_mapped`` H I scaled to a first
        entry 1, ``fixes_circular_points``, ``axis_ratio`` the ellipse's minor / major axis).
    """
    view = BrowserView(("angle", "aspect", "h31", "h32"), figsize=(9, 6.0))
    parts = _conic_figure(view)
    view.animate(
        parts.to_infinity,
        parts.conic,
        parts.mapped,
        *parts.tangents,
        parts.centre_image,
        parts.centre_conic,
        parts.text,
    )

    def update(v: dict, state: dict) -> None:
        g = conic_geometry(v["angle"], v["aspect"], v["h31"], v["h32"], parts.samples)
        state.update(
            H=g.H,
            C_mapped=g.C_mapped,
            residual=g.residual,
            tangent_residual=g.tangent_residual,
            I_mapped=g.I_mapped,
            fixes_circular_points=g.fixed,
            axis_ratio=g.axis_ratio,
        )
        parts.conic.set_data(*pj.conic_points(g.C_mapped, 200).T)
        parts.mapped.set_offsets(g.mapped)
        for artist, line in zip(parts.tangents, g.tangents, strict=True):
            set_line(artist, line, parts.ax_a)
        parts.centre_image.set_data([0.0], [0.0])  # H keeps the origin: no translation
        parts.centre_conic.set_data([g.centre[0]], [g.centre[1]])
        parts.text.set_text(conic_caption(g, v["h31"], v["h32"]))
        if v["h31"] == 0 and v["h32"] == 0:  # H keeps l_inf: no finite line goes to infinity
            parts.to_infinity.set_data([], [])
        else:
            set_line(parts.to_infinity, np.array([v["h31"], v["h32"], 1.0]), parts.ax_b)

    controls = {
        "angle": slider(20.0, -45.0, 45.0, 1.0, "rotation (°)"),
        "aspect": slider(1.4, 0.6, 1.4, 0.05, "stretch x"),
        "h31": slider(0.3, -0.35, 0.35, 0.01, "h31 (perspective x)"),
        "h32": slider(0.15, -0.35, 0.35, 0.01, "h32 (perspective y)"),
    }
    demo = build_demo(
        "conic_under_homography",
        controls,
        view,
        update,
        title="A circle under a homography: conics map by H^-T C H^-1",
    )
    view.publish(demo, conic_scene(parts))  # the browser draws the moves
    return demo
