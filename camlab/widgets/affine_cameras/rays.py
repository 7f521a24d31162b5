"""Lesson 05's projection rays.

Seen from above, the rays of each camera model, converging on the centre or parallel.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
from matplotlib.legend_handler import HandlerTuple
from matplotlib.lines import Line2D

from ... import affine as af
from ...plotting import palette
from .._base import FigureView, build_demo, register, slider
from .common import (
    COLOURS,
    REFERENCE_LABEL,
    REFERENCE_MARKER,
)

CENTRE_MARKER = dict(marker="o", color="0.1", ms=5, ls="none")  # the camera centre in the top views
SCALING_STYLE = (
    0,
    (1.5, 2),
)  # the uniform scaling f / d0 of weak and para-perspective, after their rays
SIGHT_STYLE = dict(
    color="0.2", lw=1.0, ls="-."
)  # the line of sight to X0: dash-dot, unlike every other line

RAY_DEPTH = 6.0  # d0: depth of the object's centre in the ray diagram (metres)
RAY_IMAGE = 3.0  # where the ray diagram draws the image line (z, metres)
_TURN = np.radians(
    12.0
)  # the block is turned, so rays parallel to the axis do not run along its sides
RAY_OBJECT = np.array([[-0.8, -1.0], [0.8, -1.0], [0.8, 1.0], [-0.8, 1.0]]) @ np.array(
    [[np.cos(_TURN), np.sin(_TURN)], [-np.sin(_TURN), np.cos(_TURN)]]
)  # a 1.6 m x 2 m block about X0 (x, z), metres


def _joined(*polylines):
    """Polylines (each (K, 2)) as one (x, y) pair separated by NaN, for one Line2D."""
    rows = [np.vstack([p, [np.nan, np.nan]]) for p in polylines]
    return np.vstack(rows).T if rows else np.empty((2, 0))


def _rays_panel(ax, model: str) -> tuple:
    """One top view of :func:`projection_rays`.

    ``model``'s axes with the optical axis, the image line, the centre and the plane z = d0 where
    the model has them; returns its moving artists (block, rays, scaling, images, truth, x0).
    """
    ax.set_xlim(-1.3, 4.0)  # the turned block reaches x = -0.99 m at offset 0
    ax.set_ylim(-0.4, 7.4)
    ax.set_aspect("equal")
    ax.set_title(model, fontsize=9, color=COLOURS[model])
    ax.set_xlabel("x (m)", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.axvline(0.0, color=palette.GREY, lw=0.6, ls=":")  # the optical axis
    ax.axhline(RAY_IMAGE, color="0.3", lw=1.0)  # the image line
    if model != "orthographic":  # an orthographic camera has no centre (it is at infinity)
        ax.plot([0], [0], **CENTRE_MARKER)
    if model in ("weak perspective", "para-perspective"):
        ax.axhline(
            RAY_DEPTH, color="0.4", lw=0.8, ls="--"
        )  # the plane z = d0 (dark enough over the block)
    block = ax.fill([], [], color=palette.GREY, alpha=0.18, lw=0)[
        0
    ]  # light: rays and the plane z = d0 cross it
    rays = ax.plot([], [], color=COLOURS[model], lw=1.0)[0]
    scaling = ax.plot([], [], color=COLOURS[model], lw=0.7, ls=SCALING_STYLE)[0]
    images = ax.plot([], [], "o", color=COLOURS[model], ms=4)[0]
    truth = ax.plot([], [], "|", color=COLOURS["perspective"], ms=10, mew=1.5)[
        0
    ]  # perspective, to compare
    x0 = ax.plot([], [], zorder=4, **REFERENCE_MARKER)[0]
    return block, rays, scaling, images, truth, x0


def _rays_legend(fig) -> None:
    """The figure legend of :func:`projection_rays`, above the four views.

    The ray styles, the plane z = d0, the optical axis, the centre, the corner images, the line of
    sight and X0.
    """
    corner_images = tuple(
        Line2D([], [], marker="o", color=COLOURS[m], ms=4, ls="none") for m in af.PROJECTION_MODELS
    )
    fig.legend(
        handles=[
            Line2D(
                [],
                [],
                color="0.25",
                lw=1.0,
                label="ray (solid; weak and para-perspective: up to z = d0)",
            ),
            Line2D(
                [],
                [],
                color="0.25",
                lw=0.7,
                ls=SCALING_STYLE,
                label="then the scaling f / d0 towards the centre",
            ),
            Line2D([], [], color="0.4", lw=0.8, ls="--", label="the plane z = d0"),
            Line2D([], [], color=palette.GREY, lw=0.8, ls=":", label="optical axis"),
            Line2D([], [], label="camera centre", **CENTRE_MARKER),
            corner_images,
            Line2D(
                [],
                [],
                marker="|",
                color=COLOURS["perspective"],
                ms=10,
                mew=1.5,
                ls="none",
                label="perspective image, to compare",
            ),
            Line2D([], [], label="line of sight to $X_0$", **SIGHT_STYLE),
            Line2D([], [], label=REFERENCE_LABEL, **REFERENCE_MARKER),
        ],
        labels=[
            "ray (solid; weak and para-perspective: up to $z = d_0$)",
            "then the scaling $f / d_0$ towards the centre",
            "the plane $z = d_0$",
            "optical axis",
            "camera centre",
            "image of a corner (each camera's colour)",
            "perspective image, to compare",
            "line of sight to $X_0$",
            REFERENCE_LABEL,
        ],
        handler_map={tuple: HandlerTuple(ndivide=None, pad=0.1)},
        loc="outside upper center",
        ncols=3,
        fontsize=8,
        frameon=False,
    )


def _rays_figure(view: FigureView) -> SimpleNamespace:
    """The figure of :func:`projection_rays`.

    One top view per model of :data:`camlab.affine.PROJECTION_MODELS`, the line of sight to X0 in
    para-perspective's and the legend; returns ``artists`` ({model: its moving artists}) and
    ``sight``.
    """
    axes = view.fig.subplots(1, 4, sharey=True)
    artists = {}
    for ax, model in zip(axes, af.PROJECTION_MODELS, strict=True):
        artists[model] = _rays_panel(ax, model)
        view.animate(*artists[model])
    # Para-perspective's rays are parallel to the line of sight to X0 (its viewing direction), as weak
    # perspective's are to the optical axis (the dotted vertical).
    sight = view.animate(axes[2].plot([], [], zorder=1.8, **SIGHT_STYLE)[0])
    _rays_legend(view.fig)
    axes[0].set_ylabel("depth z (m)", fontsize=8)
    axes[0].set_yticks(
        [0, RAY_IMAGE, RAY_DEPTH],
        labels=["0: centre", f"{RAY_IMAGE:g}: image", f"{RAY_DEPTH:g}: d0"],
    )
    return SimpleNamespace(artists=artists, sight=sight)


def _rays_controls() -> dict:
    """The controls of :func:`projection_rays`: the block's x offset (m)."""
    return {"offset": slider(2.0, 0.0, 2.5, 0.25, "block's x offset (m)")}


def _show_model(model: str, artists: tuple, r: np.ndarray, perspective: np.ndarray, reference):
    """Move one top view of :func:`projection_rays`.

    ``model``'s ``artists`` (block, rays, scaling, images, truth, x0) to its rays ``r``
    (:func:`camlab.affine.projection_rays`), with the ``perspective`` corner images to compare and
    X0 at ``reference``.
    """
    block, rays, scaling, images, truth, x0 = artists
    block.set_xy(RAY_OBJECT + reference)
    if model == "perspective":  # the ray runs on through the image line to the centre
        rays.set_data(*_joined(*([p, [0.0, 0.0]] for p in r[:, 0])))
    elif model == "orthographic":  # parallel to the axis, straight onto the image line
        rays.set_data(*_joined(*r[:, [0, 2]]))
    else:  # parallel onto z = d0, then only the uniform scaling f / d0
        rays.set_data(*_joined(*r[:, :2]))
    scaled = model in ("weak perspective", "para-perspective")
    scaling.set_data(*_joined(*([p, [0.0, 0.0]] for p in r[:, 1])) if scaled else ([], []))
    images.set_data(*r[:, 2].T)
    compare = model in (
        "weak perspective",
        "para-perspective",
    )  # same image scale as perspective
    truth.set_data(*(perspective.T if compare else ([], [])))
    x0.set_data([reference[0]], [reference[1]])


@register(lesson="05", sweep={"offset": [0.0, 1.0, 2.5]})
def projection_rays():
    """A top view of four camera models: how each sends the corners of a block to the image line.

    After Szeliski's figure of the projection models [1]_. Move the block sideways: on the
    optical axis weak and para-perspective coincide; off it, para-perspective's rays run
    parallel to the line of sight to X0 (drawn dash-dot), its viewing direction, as weak
    perspective's run parallel to the optical axis.

    Returns
    -------
    Demo
        The demo: control ``offset`` (the block's x offset, m), the figure (one top view per
        model of :data:`camlab.affine.PROJECTION_MODELS`) and ``state`` (``reference``, X0 as
        (x, z) in m; ``image_x``, each model's corner images on the image line, m).

    References
    ----------
    .. [1] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022, section
       2.1.4 (3D to 2D projections), fig. 2.7.
    """
    view = FigureView(figsize=(10, 4.75))
    art = _rays_figure(view)

    def update(v, state):
        reference = np.array([float(v["offset"]), RAY_DEPTH])
        corners = RAY_OBJECT + reference
        perspective = af.projection_rays(corners, reference, "perspective", RAY_IMAGE)[:, 2]
        images_x = {}
        for model, artists in art.artists.items():
            r = af.projection_rays(corners, reference, model, RAY_IMAGE)
            _show_model(model, artists, r, perspective, reference)
            images_x[model] = r[:, 2, 0]
        top = 7.4 / RAY_DEPTH  # the line of sight from the centre through X0 to the top of the axes
        art.sight.set_data([0.0, top * reference[0]], [0.0, top * reference[1]])
        state.update(reference=reference, image_x=images_x)

    return build_demo(
        "projection_rays",
        _rays_controls(),
        view,
        update,
        title="Four cameras from above: where each sends the block's corners",
    )
