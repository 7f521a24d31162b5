"""Figures of the calibration quality coach (lesson 08): each helper draws on a given Axes.

``report_figure(result)`` puts them all on one page (what ``camlab calibrate --report`` saves).
Pixels (u, v) = (column, row), origin at the centre of the top-left pixel, v down.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np
from matplotlib.colors import to_rgba

from ..calibration import CalibrationResult, CoachReport, coach, projection_uncertainty
from . import palette

__all__ = [
    "CappedArrows",
    "arrow_colours",
    "cap_arrows",
    "image_frame",
    "plot_cost_history",
    "plot_extrinsics",
    "plot_coverage",
    "plot_per_view_errors",
    "plot_residual_field",
    "plot_uncertainty_map",
    "report_figure",
]


def image_frame(ax, image_size: tuple[int, int], title: str = "") -> None:
    """Axes showing the image area: equal aspect, v down, a thin frame.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to set up (changed in place).
    image_size : (width, height)
        Image size in pixels; the limits are the image's outer pixel edges.
    title : str
        The axes' title (none if empty).
    """
    w, h = image_size
    ax.set_xlim(-0.5, w - 0.5)
    ax.set_ylim(h - 0.5, -0.5)
    ax.set_aspect("equal")
    ax.plot(
        [-0.5, w - 0.5, w - 0.5, -0.5, -0.5],
        [-0.5, -0.5, h - 0.5, h - 0.5, -0.5],
        color="0.5",
        lw=0.8,
        gid="grid",
    )
    ax.set_xlabel("u (px)")
    ax.set_ylabel("v (px)")
    if title:
        ax.set_title(title, fontsize=10)


def plot_per_view_errors(ax, result: CalibrationResult, highlight_ratio: float = 2.0):
    """Bar chart of each view's rms (px) with the overall rms; outlying views in red.

    A view is black (the others grey) when its rms is at least ``highlight_ratio`` times the median and over 0.1 px.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in.
    result : CalibrationResult
        A calibration (:func:`camlab.calibration.calibrate_camera`).
    highlight_ratio : float
        How many times the median rms makes a view stand out.

    Returns
    -------
    matplotlib.container.BarContainer
        One bar per view, height its rms reprojection error (px).
    """
    err = result.per_view_rms
    med = np.median(err)
    bad = [e >= highlight_ratio * med and e > 0.1 for e in err]
    colors = ["k" if b else palette.GREY for b in bad]  # no red: red + is a detection
    bars = ax.bar(np.arange(len(err)), err, color=colors)
    for bar in (b for b, flagged in zip(bars, bad, strict=True) if flagged):
        bar.set_label(f"over {highlight_ratio:g} × the median")  # one legend entry for all of them
        break
    ax.axhline(result.rms, color="k", ls="--", lw=1, label=f"overall rms {result.rms:.2f} px")
    ax.set(xlabel="view", ylabel="rms error (px)")
    ax.set_title("Error per view", fontsize=10)
    ax.set_xticks(np.arange(len(err)))
    ax.tick_params(axis="x", labelsize=7)
    ax.legend(fontsize=8, loc="upper right")
    return bars


class CappedArrows(NamedTuple):
    """The arrows :func:`cap_arrows` draws.

    Attributes
    ----------
    arrows : (N, 2) ndarray
        The arrows drawn, pixels, each along its own direction.
    capped : (N,) bool ndarray
        True where an arrow was shortened (drawn black by the lesson's convention).
    """

    arrows: np.ndarray
    capped: np.ndarray


def cap_arrows(tails, arrows, cap: float, image_size) -> CappedArrows:
    """Arrows shortened to at most ``cap`` px and to end inside the image; which were shortened.

    Parameters
    ----------
    tails : (N, 2) array
        Where the arrows start, pixels (inside the image).
    arrows : (N, 2) array
        The arrows, pixels.
    cap : float
        The longest arrow drawn, pixels.
    image_size : (width, height)
        The image's size: a tip beyond its outer pixel edges is pulled back onto them.

    Returns
    -------
    CappedArrows
        ``arrows``, the arrows drawn, and ``capped``, which of them were shortened.
    """
    tails, arrows = np.asarray(tails, dtype=float), np.array(arrows, dtype=float)
    length = np.linalg.norm(arrows, axis=1)
    capped = length > cap
    arrows[capped] *= (cap / length[capped])[:, None]
    lo, hi = np.array([-0.5, -0.5]), np.array(image_size, dtype=float) - 0.5
    with np.errstate(divide="ignore", invalid="ignore"):  # the fraction of each arrow that fits
        room = np.where(
            arrows > 0, (hi - tails) / arrows, np.where(arrows < 0, (lo - tails) / arrows, np.inf)
        )
    fits = np.clip(room.min(axis=1), 0.0, 1.0)
    arrows *= fits[:, None]
    return CappedArrows(arrows, capped | (fits < 1))


def arrow_colours(capped) -> np.ndarray:
    """RGBA per arrow: magenta (the lesson's residual colour), black where ``capped``.

    Parameters
    ----------
    capped : (N,) bool array
        Which arrows were shortened (:func:`cap_arrows`).

    Returns
    -------
    (N, 4) ndarray
        One RGBA row per arrow, for a quiver's ``color``.
    """
    return np.where(
        np.asarray(capped)[:, None],
        np.array([to_rgba("k")]),
        np.array([to_rgba(palette.MAGENTA)]),
    )


def plot_residual_field(
    ax, result: CalibrationResult, scale: float | None = None, cap: float = 60.0
):
    """Every corner's residual (observed - reprojected) as an arrow at its position, magnified.

    Random arrows mean noise; a pattern (swirls, arrows pointing out at the edges) means
    the model is missing something (more distortion terms, a bad view). All arrows are one
    colour (:data:`palette.MAGENTA`, the lesson's residual colour); an arrow that the
    magnification would draw longer than ``cap`` pixels is drawn ``cap`` long in black, so one
    spoiled view cannot cross the frame and bury the others.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in.
    result : CalibrationResult
        A calibration (:func:`camlab.calibration.calibrate_camera`).
    scale : float or None
        Magnification of the arrows; None takes the round value (1, 2 or 5 x a power of ten) that
        draws the 90th percentile residual at most 25 px long.
    cap : float
        The longest arrow drawn, image pixels; longer ones are shortened to it and drawn black.

    Returns
    -------
    matplotlib.quiver.Quiver
        The arrows, in image pixels (the residuals times ``scale``, capped at ``cap``).
    """
    pts = np.concatenate(result.image_points)
    res = np.concatenate(result.residuals)
    if scale is None:
        typical = np.percentile(np.linalg.norm(res, axis=1), 90)
        raw = 25.0 / max(typical, 1e-9)
        decade = 10.0 ** np.floor(np.log10(raw))  # rounded down to 1, 2 or 5 x a power of ten
        scale = decade * max(m for m in (1.0, 2.0, 5.0) if m * decade <= raw)
    arrows, capped = cap_arrows(pts, res * scale, cap, result.image_size)
    title = f"Residuals ×{scale:.0f}"
    if capped.any():  # which views the black arrows belong to, so black is not read as one view's
        views = np.repeat(np.arange(len(result.residuals)), [len(r) for r in result.residuals])
        counts = sorted(
            ((int(np.sum(capped & (views == v))), int(v)) for v in set(views[capped])), reverse=True
        )
        listed = ", ".join(f"{c} in view {v}" for c, v in counts[:3]) + (
            ", ..." if len(counts) > 3 else ""
        )
        title += f"\nblack: {capped.sum()} capped at {cap:.0f} px or the frame ({listed})"
    image_frame(ax, result.image_size, title)
    colours = arrow_colours(capped)
    q = ax.quiver(
        pts[:, 0],
        pts[:, 1],
        arrows[:, 0],
        arrows[:, 1],
        color=colours,
        angles="xy",
        scale_units="xy",
        scale=1,
        width=0.004,
    )
    return q


def plot_coverage(ax, result: CalibrationResult, report: CoachReport | None = None):
    """Where the detected corners fall in the image, over the coach's coverage grid (empty cells red).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in.
    result : CalibrationResult
        A calibration (:func:`camlab.calibration.calibrate_camera`).
    report : CoachReport or None
        The coach's report on ``result``; None computes it (:func:`camlab.calibration.coach`).

    Returns
    -------
    matplotlib.collections.PathCollection
        The corners of every view, black dots.
    """
    report = coach(result) if report is None else report
    w, h = result.image_size
    rows, cols = report.coverage_grid.shape
    image_frame(
        ax, result.image_size, f"Coverage {100 * report.coverage:.0f}% of cells (grey: no corner)"
    )
    empty = np.ma.masked_where(report.coverage_grid > 0, np.ones_like(report.coverage_grid, float))
    ax.imshow(
        empty,
        extent=(-0.5, w - 0.5, h - 0.5, -0.5),
        cmap="Greys",
        vmin=0,
        vmax=2.5,
        alpha=0.6,
        interpolation="nearest",
    )
    for c in np.linspace(-0.5, w - 0.5, cols + 1)[1:-1]:
        ax.axvline(c, color="0.8", lw=0.5, gid="grid")
    for r in np.linspace(-0.5, h - 0.5, rows + 1)[1:-1]:
        ax.axhline(r, color="0.8", lw=0.5, gid="grid")
    return ax.scatter(
        *np.concatenate(result.image_points).T, color="k", s=2, lw=0
    )  # one colour, every view: no red, red + is a detection


def plot_uncertainty_map(
    ax,
    result: CalibrationResult,
    step: int = 16,
    hatch_empty: bool = False,
    title: str | None = None,
):
    """1-sigma projection uncertainty (px) from the intrinsics' covariance, across the image.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in.
    result : CalibrationResult
        A calibration (:func:`camlab.calibration.calibrate_camera`).
    step : int
        Spacing of the sample grid, pixels (:func:`camlab.calibration.projection_uncertainty`).
    hatch_empty : bool
        Hatch the coverage cells that no corner reached (:func:`plot_coverage`'s grey cells).
    title : str or None
        The panel's title; None gives "Projection uncertainty (px, 1σ)".

    Returns
    -------
    matplotlib.image.AxesImage
        The uncertainty map (px), with a colour bar added to the figure (log colours when the
        map spans more than a factor of 5).
    """
    us, vs, sig = projection_uncertainty(result, step)
    image_frame(ax, result.image_size, title or "Projection uncertainty (px, 1σ)")
    w, h = result.image_size
    from matplotlib.colors import LogNorm

    im = ax.imshow(
        sig,
        extent=(-0.5, w - 0.5, h - 0.5, -0.5),
        cmap="viridis",
        interpolation="bilinear",
        norm=LogNorm() if sig.max() > 5 * sig.min() else None,  # a wide range: log colours
    )
    if hatch_empty:
        from matplotlib.patches import Rectangle

        grid = coach(result).coverage_grid
        gh, gw = grid.shape
        for i, j in zip(*np.nonzero(grid == 0), strict=True):
            ax.add_patch(
                Rectangle(
                    (j * w / gw - 0.5, i * h / gh - 0.5),
                    w / gw,
                    h / gh,
                    fill=False,
                    hatch="//",
                    ec="w",
                    lw=0,
                )
            )
    bar = ax.figure.colorbar(
        im, ax=ax, shrink=0.8, label="1σ (px)"
    )  # the label keeps the ticks off the edge
    if isinstance(im.norm, LogNorm):  # 0.5, 1, 2, 5 rather than 5 x 10^-1
        from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

        bar.ax.yaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
        bar.ax.yaxis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
        bar.ax.yaxis.set_minor_formatter(NullFormatter())
    return im


def plot_cost_history(ax, result: CalibrationResult):
    """rms (px) after each Levenberg-Marquardt iteration, log scale.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in.
    result : CalibrationResult
        A calibration (:func:`camlab.calibration.calibrate_camera`).

    Returns
    -------
    matplotlib.lines.Line2D
        The rms per iteration (floored at 1e-16 for the log scale).
    """
    (line,) = ax.semilogy(
        np.arange(len(result.rms_history)), np.maximum(result.rms_history, 1e-16), "o-", ms=3
    )
    ax.set(xlabel="LM iteration", ylabel="rms (px)")
    ax.set_title("Levenberg-Marquardt: rms per iteration", fontsize=10)
    ax.grid(True, which="both", color="0.92")
    return line


# The camera frame (x right, y down, z forward) drawn with matplotlib's Z up: world X = x,
# world Y = z (forward), world Z = -y (up), i.e. X_cam = R_CAM_FROM_VIEW @ X_view.
R_CAM_FROM_VIEW = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])


def _label_boards(ax, view: np.ndarray, ring: list[int]) -> None:
    """Write each board's view number at the point of its outline farthest, on screen, from the others' numbers.

    The candidates are the outline's four corners and the points 1/4, 1/2, 3/4 along its edges; boards are
    labelled greedily, in view order, so 14 overlapping boards still get 14 readable numbers.
    """
    from mpl_toolkits.mplot3d import proj3d

    corners = view[:, ring[:4]]  # (V, 4, 3)
    nxt = np.roll(corners, -1, axis=1)  # each corner and the points 1/4, 1/2, 3/4 along each edge
    candidates = np.concatenate(
        [corners + f * (nxt - corners) for f in (0.0, 0.25, 0.5, 0.75)], axis=1
    )
    flat = candidates.reshape(-1, 3)
    sx, sy, _ = proj3d.proj_transform(*flat.T, ax.get_proj())
    screen = np.column_stack([sx, sy]).reshape(len(view), -1, 2)
    outward = np.linalg.norm(
        screen - screen.reshape(-1, 2).mean(axis=0), axis=2
    )  # off the crowd's middle
    placed: list[np.ndarray] = []
    for v in range(len(view)):
        gaps = (
            np.linalg.norm(screen[v][:, None] - np.array(placed)[None], axis=2).min(axis=1)
            if placed
            else np.zeros(len(screen[v]))
        )
        k = int(np.argmax(gaps + 0.5 * outward[v]))
        placed.append(screen[v][k])
        colour = palette.VIEWS[v % len(palette.VIEWS)]
        colour = (
            palette.DARK_ORANGE if colour == palette.ORANGE else colour
        )  # orange is too light for text
        ax.text(
            *candidates[v, k],
            f"{v}",
            color=colour,
            fontsize=8,
            ha="center",
            va="center",
            fontweight="bold",
            path_effects=palette.halo(),  # readable where it sits on another board's outline
        )


def plot_extrinsics(ax, result: CalibrationResult, size: float | None = None):
    r"""The calibration's extrinsics, camera-centred: every view's board where it stood in front of the camera.

    Each view's board corners in the camera frame, :math:`X_{cam} = R_v X_{board} + t_v`, are drawn as
    the board's outline with its view number (0-based, as in the per-view plots; each number at the
    point of its outline farthest from the numbers already placed), the colours
    repeating every four views; the camera sits at the origin, drawn as a frustum
    with its x (right), y (down), z (forward) axes. The axes show the camera frame with "up" up
    (matplotlib's Z is :math:`-y`), so the picture reads like Bouguet's and MATLAB's extrinsics view.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        A 3-D axes (:func:`camlab.plotting.scene3d.axes3d`).
    result : CalibrationResult
        The calibration (its ``object_points``, ``rvecs``, ``tvecs``, ``K``, ``image_size``).
    size : float, optional
        The drawn frustum's depth, in the board's units (default: a third of the nearest board's distance).

    Returns
    -------
    (V, N, 3) ndarray
        Every view's corners in the camera frame, in the board's units.

    References
    ----------
    J.-Y. Bouguet, *Camera Calibration Toolbox for Matlab*, Caltech (the extrinsics view).
    """
    from ..camera import Camera, rotation_from_axis_angle
    from .scene3d import CameraArtist, set_equal_aspect

    boards = np.stack(
        [
            result.object_points[v] @ rotation_from_axis_angle(result.rvecs[v]).T + result.tvecs[v]
            for v in range(result.n_views)
        ]
    )
    view = boards @ R_CAM_FROM_VIEW  # X_view = R^T X_cam, rows
    obj = result.object_points[0]
    cols = int(np.sum(obj[:, 1] == obj[0, 1]))
    ring = [0, cols - 1, len(obj) - 1, len(obj) - cols, 0]  # the outer corners, in a loop
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    for v, b in enumerate(view):
        colour = palette.VIEWS[v % len(palette.VIEWS)]
        # a faint fill tells the overlapping boards apart (a static figure: no redraw loses it)
        ax.add_collection3d(Poly3DCollection([b[ring[:4]]], facecolor=colour, alpha=0.07, lw=0))
        ax.plot(*b[ring].T, color=colour, lw=1.0)
        ax.plot(
            *b[0], "o", color=colour, ms=4, mec="k", mew=0.5
        )  # the first corner: how it is turned
    depth = float(np.min(boards[:, :, 2]))
    cam = Camera(K=result.K, R=R_CAM_FROM_VIEW, t=np.zeros(3), image_size=result.image_size)
    CameraArtist(ax, cam, size=size or depth / 3, color=palette.GREY)
    # a wider margin than the default: a board near the box's front-bottom edge is drawn in front of
    # the back panes and would seem to poke out of the box
    set_equal_aspect(ax, [view.reshape(-1, 3), np.zeros((1, 3))], tight=True, margin=0.15)
    _label_boards(ax, view, ring)
    ax.set_xlabel("x (right, m)", labelpad=10)
    ax.set_ylabel("z (forward, m)", labelpad=10)  # clear of its own tick labels
    ax.set_zlabel("−y (up, m)", labelpad=4)
    return boards


def _pm(value: float, std: float) -> str:
    """``value ± std``: the std to 2 significant digits, the value to its decimal place, no "-0"."""
    if not np.isfinite(std) or std <= 0:  # a fixed parameter
        return f"{value + 0.0:g} (fixed)"
    decimals = max(0, 1 - int(np.floor(np.log10(std))))
    return f"{round(value, decimals) + 0.0:+.{decimals}f} ± {std:.{decimals}f}"


def report_figure(
    result: CalibrationResult, report: CoachReport | None = None, figsize=(13, 8.5)
) -> Any:
    """One page: per-view errors, residual field, coverage, uncertainty map, LM cost and the advice.

    Parameters
    ----------
    result : CalibrationResult
        A calibration (:func:`camlab.calibration.calibrate_camera`).
    report : CoachReport or None
        The coach's report on ``result``; None computes it (:func:`camlab.calibration.coach`).
    figsize : (width, height)
        Figure size in inches.

    Returns
    -------
    matplotlib.figure.Figure
        A 2 x 3 grid of panels (not attached to pyplot; save it with ``savefig``).
    """
    from matplotlib.figure import Figure

    report = coach(result) if report is None else report
    fig = Figure(figsize=figsize, layout="constrained")
    axes = fig.subplots(2, 3)
    plot_per_view_errors(axes[0, 0], result)
    plot_residual_field(axes[0, 1], result)
    plot_coverage(axes[0, 2], result, report)
    plot_uncertainty_map(axes[1, 0], result)
    plot_cost_history(axes[1, 1], result)
    ax = axes[1, 2]
    ax.axis("off")
    p, s = result.intrinsics, result.std
    lines = [
        f"fx = {p['fx']:.2f} ± {s['fx']:.2f}",
        f"fy = {p['fy']:.2f} ± {s['fy']:.2f}",
        f"cx = {p['cx']:.2f} ± {s['cx']:.2f}",
        f"cy = {p['cy']:.2f} ± {s['cy']:.2f}",
        *(f"{k} = {_pm(p[k], s[k])}" for k in ("k1", "k2", "p1", "p2", "k3")),
        f"rms = {result.rms:.3f} px",
        "",
        "Advice:",
    ]
    import textwrap

    for a in report.advice[:6]:
        lines += textwrap.wrap("• " + a, 48)
    ax.text(
        0,
        1,
        "\n".join(lines),
        va="top",
        ha="left",
        fontsize=8.5,
        family="monospace",
        transform=ax.transAxes,
    )
    fig.suptitle(f"Calibration report: {result.n_views} views, {result.n_points} corners")
    return fig
