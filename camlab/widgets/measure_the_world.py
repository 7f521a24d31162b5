"""Lesson 12's demo: how the tilt and the distance of the camera set the error of a length on a plane.

In a lesson::

    %matplotlib widget
    from camlab.widgets import measure_the_world as demos
    demos.plane_error()
"""

from __future__ import annotations

from functools import lru_cache
from types import SimpleNamespace

import ipywidgets as W
import numpy as np
from matplotlib.ticker import FuncFormatter

from ..calibration import board_points
from ..camera import look_at_rotation
from ..measurement import measure_on_plane, pose_covariance, project_pose
from ..plotting import palette
from ._base import Demo, FigureView, build_demo, register, slider
from .controls import monospace

__all__ = ["OBJECT", "OBJECT_ACROSS", "click_to_measure", "geometry", "length_sigma", "plane_error"]

K_DEMO = np.array([[532.8, 0.0, 341.8], [0.0, 533.0, 234.1], [0.0, 0.0, 1.0]])
"""The intrinsics of the shipped real chessboard photos (lesson 08's calibration, rounded)."""
SIZE = (640, 480)
BOARD = board_points((9, 6), 0.025)
CENTRE = np.array([0.1, 0.0625, 0.0])
OBJECT = np.array([[0.24, -0.0375, 0.0], [0.24, 0.1625, 0.0]])
"""A 0.2 m edge on the table 4 cm beyond the board's last corner column, along the board's y: along the slope."""
OBJECT_ACROSS = np.array([[0.0, 0.165, 0.0], [0.2, 0.165, 0.0]])
"""A 0.2 m edge on the table 4 cm beyond the board's last row, along x: across the slope (the tilt axis).

It is the board's near side: the camera stands on the board's +y side, as a person at a table does."""
SIGMA_PX = 0.14
"""Corner noise per coordinate, pixels: the real photos' (0.137 px on calib_left01, lesson 12 section 1)."""
TILTS = np.linspace(0.0, 75.0, 61)
Y_LIM_MM = (0.03, 20.0)  # log axis, fixed at the first draw: every setting fits
"""The error axis's top, fixed (a live frame redraws only the curves): above the farthest, most tilted setting."""


def geometry(tilt_deg: float, distance: float) -> SimpleNamespace:
    """The camera looking at the board's centre from ``distance`` metres, ``tilt_deg`` off the board's normal.

    Parameters
    ----------
    tilt_deg : float
        Angle between the viewing direction and the board's normal, degrees (0 = straight down).
    distance : float
        From the camera to the board's centre, metres.

    Returns
    -------
    SimpleNamespace
        ``R``, ``t`` (cam_from_board) and ``eye`` (the camera centre, board frame).

    Notes
    -----
    The camera stands on the board's +y side (its last row is the near side) and keeps the board's
    -y up, so the photo looks like one taken standing at a table: the near edge at the bottom of the
    frame, the far rows converging toward the top.
    """
    a = np.radians(tilt_deg)
    eye = CENTRE + distance * np.array([0.0, np.sin(a), -np.cos(a)])
    R = look_at_rotation(eye, CENTRE, up=(0.0, -1.0, 0.0))
    return SimpleNamespace(R=R, t=-R @ eye, eye=eye)


def length_sigma(
    tilt_deg: float, distance: float, pixel_sigma: float = 0.5, across: bool = False
) -> SimpleNamespace:
    """The predicted error of :data:`OBJECT`'s length from one photo at this tilt and distance.

    The camera tilts about the board's x axis (it moves toward +y), so :data:`OBJECT` runs along
    the slope and :data:`OBJECT_ACROSS` (``across=True``) along the tilt axis.

    Parameters
    ----------
    tilt_deg : float
        Degrees off the board's normal.
    distance : float
        Metres to the board's centre.
    pixel_sigma : float
        How precisely the object's ends are picked, pixels.
    across : bool
        Measure :data:`OBJECT_ACROSS` instead of :data:`OBJECT`.

    Returns
    -------
    SimpleNamespace
        ``sigma``, ``pose`` and ``pixels`` (metres), the corner and object pixels ``corners``,
        ``ends``, the board's width in pixels ``board_px`` and ``in_frame`` (the board and the
        edge inside the 640 x 480 photo).
    """
    g = geometry(tilt_deg, distance)
    cov = pose_covariance(K_DEMO, g.R, g.t, BOARD, SIGMA_PX)
    pose = SimpleNamespace(R=g.R, t=g.t, covariance=cov, sigma=SIGMA_PX)
    ends = project_pose(K_DEMO, g.R, g.t, OBJECT_ACROSS if across else OBJECT)
    m = measure_on_plane(pose, K_DEMO, ends[:1], ends[1:], pixel_sigma=pixel_sigma)
    corners = project_pose(K_DEMO, g.R, g.t, BOARD)
    width = np.linalg.norm(corners[8] - corners[0])
    both = np.vstack([corners, ends])
    in_frame = bool(np.all((both >= -0.5) & (both <= np.array(SIZE) - 0.5)))
    return SimpleNamespace(
        sigma=float(m.sigma[0]),
        pose=float(m.sigma_pose[0]),
        pixels=float(m.sigma_pixels[0]),
        corners=corners,
        ends=ends,
        board_px=float(width),
        in_frame=in_frame,
    )


SIDE_LIM = (
    (-0.25, 1.6),
    (-0.15, 1.6),
)  # the side view's y and height limits at the farthest distance, m; nearer, they shrink with it


def _side_limits(distance: float) -> tuple[tuple[float, float], tuple[float, float]]:
    """The side view's limits at ``distance`` (m): :data:`SIDE_LIM` scaled to fit the camera at every tilt.

    Parameters
    ----------
    distance : float
        From the camera to the board's centre, metres (0.4 to 1.5).

    Returns
    -------
    tuple
        ``((y_min, y_max), (height_min, height_max))``, metres, in the same proportions at every distance.
    """
    s = (distance + 0.1) / 1.6  # 1 at the slider's 1.5 m; the camera stays inside at 75 deg
    return tuple((lo * s, hi * s) for lo, hi in SIDE_LIM)


def _side_view(ax) -> SimpleNamespace:
    """The side view (board y across, height above the table up): table, board, camera."""
    ax.set(xlim=SIDE_LIM[0], ylim=SIDE_LIM[1], aspect="equal")
    ax.set_xlabel("board y (m)", fontsize=8)
    ax.set_ylabel("height above the table (m)", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.grid(alpha=0.3)
    ax.set_title("side view: the camera (orange)", fontsize=9)
    ax.axhline(0, color="0.3", lw=1, zorder=1.5)  # the table
    # the board under the animated lines (drawn last in a live frame): a full redraw draws it the same
    ax.plot([-0.0125, 0.1375], [0, 0], "-", color="0.1", lw=3, solid_capstyle="butt", zorder=1.8)
    ax.annotate(
        "board",
        (0.0625, 0.0),
        xytext=(0, -3),
        textcoords="offset points",
        fontsize=6,
        ha="center",
        va="top",
        color="0.1",
    )
    (rays,) = ax.plot([], [], "-", color=palette.ORANGE, lw=1)  # the photo's top and bottom rows
    (axis,) = ax.plot([], [], "--", color="0.4", lw=1)  # the optical axis, to the board's centre
    (eye,) = ax.plot([], [], "o", color=palette.ORANGE, ms=6)
    return SimpleNamespace(rays=rays, axis=axis, eye=eye)


def _plan_view(ax) -> None:
    """The table from above, zoomed on the board, drawn as the photo shows it: board x right, y down."""
    # seen from above (-z, where the camera is), oriented like the photo: board x to the right, board y
    # down (toward the near side, where you stand and toward which the camera tilts)
    ax.set(xlim=(-0.06, 0.3), ylim=(0.24, -0.1), aspect="equal")
    ax.set_xlabel("board x (m)", fontsize=8)
    ax.set_ylabel("board y (m); camera tilts to +y", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.grid(alpha=0.3)
    ax.set_title("the table from above (as in the photo)", fontsize=9)
    ax.plot(BOARD[:, 0], BOARD[:, 1], ".", ms=2, color="0.1")  # the 54 corners
    ax.plot(*OBJECT[:, :2].T, "-", color=palette.PURPLE, lw=3, solid_capstyle="butt")
    ax.plot(*OBJECT_ACROSS[:, :2].T, "-", color=palette.BROWN, lw=3, solid_capstyle="butt")
    ax.plot(
        CENTRE[0], CENTRE[1], "+", color="0.4", ms=8, mew=1.5
    )  # where the optical axis meets it
    text = dict(fontsize=7, path_effects=palette.halo(2))
    ax.text(0.1, -0.045, "board", color="0.1", ha="center", va="bottom", **text)
    ax.text(
        0.255, 0.0625, "along the slope", color=palette.PURPLE, rotation=90, va="center", **text
    )
    ax.text(0.1, 0.18, "across the slope", color=palette.BROWN, ha="center", va="top", **text)


def _side_update(side: SimpleNamespace, g: SimpleNamespace) -> None:
    """Move the side view's camera to ``g`` (from :func:`geometry`)."""
    C = np.array([g.eye[1], -g.eye[2]])  # (board y, height)
    out = []
    for v in (-0.5, SIZE[1] - 0.5):  # the photo's top and bottom rows of pixels, back-projected
        d = g.R.T @ np.linalg.solve(K_DEMO, [K_DEMO[0, 2], v, 1.0])  # a ray in the board frame
        s = g.eye[2] / -d[2] if d[2] > 0 else 2.0  # to the table (z = 0), or 2 m out
        end = g.eye + s * d
        out += [C, [end[1], -end[2]], [np.nan, np.nan]]
    side.rays.set_data(*np.array(out).T)
    side.axis.set_data([C[0], CENTRE[1]], [C[1], 0.0])
    side.eye.set_data([C[0]], [C[1]])


def _figure() -> SimpleNamespace:
    view = FigureView(figsize=(10.4, 5.0))
    axes = view.fig.subplot_mosaic(
        [["img", "side", "plot"], ["img", "plan", "plot"]],
        width_ratios=[1.1, 0.8, 1],
        height_ratios=[1.25, 1],
    )
    ax_img, ax_side, ax_plot = axes["img"], axes["side"], axes["plot"]
    side = _side_view(ax_side)
    _plan_view(axes["plan"])
    ax_img.set(xlim=(-0.5, SIZE[0] - 0.5), ylim=(SIZE[1] - 0.5, -0.5), aspect="equal")
    ax_img.set_xlabel("u (px)", fontsize=8)
    ax_img.set_ylabel("v (px)", fontsize=8)
    ax_img.tick_params(labelsize=7)
    ax_img.set_title(
        "the photo: the board's corners and the edges\nalong (purple) and across (brown) the slope",
        fontsize=9,
    )
    (corners,) = ax_img.plot([], [], ".", ms=3, color=palette.GREY)
    (edge,) = ax_img.plot([], [], "-o", lw=2, ms=4, color=palette.PURPLE)
    (edge_x,) = ax_img.plot([], [], "-s", lw=2, ms=4, color=palette.BROWN)
    ax_plot.set(
        xlim=(-2.5, 78),  # room for the rings at 0 and 75 deg
        yscale="log",
        ylim=Y_LIM_MM,
        xlabel="tilt off the board's normal (deg)",
        ylabel="σ of a 0.2 m edge (mm, log scale)",
    )
    ax_plot.xaxis.label.set_fontsize(8)
    ax_plot.yaxis.label.set_fontsize(8)
    ax_plot.tick_params(labelsize=7)
    ax_plot.grid(alpha=0.3)
    # the purple edge's total (thick) under its two parts (purple, dotted and dashed), which add in
    # quadrature: the picking part nearly coincides with the total, so its dots are outlined in white
    (total,) = ax_plot.plot(
        [], [], "-", color=palette.PURPLE, lw=4.5, label="along the slope (purple): total"
    )
    (picks,) = ax_plot.plot(
        [],
        [],
        ":",
        color=palette.PURPLE,
        lw=2.0,
        path_effects=palette.halo(2.0),
        label="   its part from picking the ends",
    )
    (pose,) = ax_plot.plot(
        [], [], "--", color=palette.PURPLE, lw=1.2, label="   its part from the pose"
    )
    (across,) = ax_plot.plot(
        [], [], "-", color=palette.BROWN, label="across the slope (brown): total"
    )
    (here,) = ax_plot.plot(
        [], [], "o", mfc="none", mec="0.1", mew=1.5, ms=7, label="this tilt (both edges)"
    )
    ax_plot.yaxis.set_major_formatter(FuncFormatter(lambda y, _: f"{y:g}"))  # 0.1, 1, 10, not 10^-1
    view.fig.legend(  # one row across the whole figure, below every panel: never on a curve
        *ax_plot.get_legend_handles_labels(), loc="outside lower center", ncols=5, fontsize=7
    )
    ax_plot.set_title(" ", fontsize=9)  # the distance, set by update
    view.animate(corners, edge, edge_x, total, pose, picks, across, here, ax_plot.title)
    view.animate(side.rays, side.axis, side.eye)
    return SimpleNamespace(
        view=view,
        side=side,
        side_ax=ax_side,
        ax_plot=ax_plot,
        corners=corners,
        edge=edge,
        edge_x=edge_x,
        across=across,
        total=total,
        pose=pose,
        picks=picks,
        here=here,
    )


@register(
    lesson="12",
    sweep={"tilt": [0.0, 40.0, 75.0], "distance": [0.4, 0.6, 1.5], "pick": [0.05, 0.25, 1.0]},
)
def plane_error() -> Demo:
    """The error of two 0.2 m lengths on a table beside a 9 x 6 board, against tilt and distance.

    The camera of the shipped photos looks at the board's centre; the board's 54 corners, found to
    0.14 px, fix the pose (its covariance from the Jacobian), and each edge's two ends are picked
    to ``pick`` px (0.5 by default: by hand). The error, first order
    (``camlab.measurement.measure_on_plane``), is split into what the pose and what the picking
    contribute, and drawn against the tilt at this distance.

    Returns
    -------
    Demo
        Controls ``tilt`` (degrees off the board's normal), ``distance`` (metres to the board's
        centre) and ``pick`` (how precisely the ends are picked, pixels); ``state`` holds
        ``sigma_mm``, ``pose_mm``, ``pixels_mm``, ``board_px``, ``curve_mm`` (sigma at each tilt of
        ``TILTS``) and ``across_mm`` (the edge across the slope).
    """
    fig = _figure()
    readout = W.HTML()

    @lru_cache(
        maxsize=64
    )  # the distance slider revisits settings; the tilt slider only moves the dot
    def curve(distance: float, pick: float) -> tuple:
        """sigma (mm) along the slope: total, from the pose, from the picks; across: total."""
        c = [length_sigma(a, distance, pick) for a in TILTS]
        along = [1000 * np.array([getattr(x, k) for x in c]) for k in ("sigma", "pose", "pixels")]
        return (
            *along,
            1000 * np.array([length_sigma(a, distance, pick, across=True).sigma for a in TILTS]),
        )

    def update(v, state):
        pick = round(float(v["pick"]), 4)
        now = length_sigma(v["tilt"], v["distance"], pick)
        now_x = length_sigma(v["tilt"], v["distance"], pick, across=True)
        total, from_pose, from_picks, across = curve(round(float(v["distance"]), 4), pick)
        fig.corners.set_data(*now.corners.T)
        fig.edge.set_data(*now.ends.T)
        fig.edge_x.set_data(*now_x.ends.T)
        fig.across.set_data(TILTS, across)
        fig.total.set_data(TILTS, total)
        fig.pose.set_data(TILTS, from_pose)
        fig.picks.set_data(TILTS, from_picks)
        fig.here.set_data([v["tilt"]] * 2, [1000 * now.sigma, 1000 * now_x.sigma])
        _side_update(fig.side, geometry(v["tilt"], v["distance"]))
        lim = _side_limits(v["distance"])
        if fig.side_ax.get_xlim() != lim[0]:  # the view follows the distance: a full redraw, once
            fig.side_ax.set(xlim=lim[0], ylim=lim[1])
            fig.view.invalidate()
        fig.ax_plot.title.set_text(f"predicted error at {v['distance']:.2f} m from the board")
        state.update(
            sigma_mm=1000 * now.sigma,
            pose_mm=1000 * now.pose,
            pixels_mm=1000 * now.pixels,
            board_px=now.board_px,
            in_frame=now.in_frame and now_x.in_frame,
            curve_mm=total,
            across_mm=1000 * now_x.sigma,
        )
        readout.value = monospace(
            f"tilt {v['tilt']:.0f} deg, {v['distance']:.2f} m: the board's first row spans {now.board_px:.0f} px, "
            f"the board is {np.ptp(now.corners[:, 1]):.0f} px tall"
            + ("" if now.in_frame and now_x.in_frame else " (part of it is outside the photo!)")
            + "\n"
            f"σ of the 0.2 m edge along the slope (purple):  {1000 * now.sigma:5.2f} mm\n"
            f"  its part from the pose:                      {1000 * now.pose:5.2f} mm\n"
            f"  its part from picking the ends ({pick:4.2f} px):    {1000 * now.pixels:5.2f} mm\n"
            "  (the two parts add in quadrature: total² = pose² + picking²)\n"
            f"σ of the 0.2 m edge across the slope (brown):  {1000 * now_x.sigma:5.2f} mm"
        )

    controls = {
        "tilt": slider(30.0, 0.0, 75.0, 1.0, "tilt (deg)"),
        "distance": slider(0.6, 0.4, 1.5, 0.05, "distance (m)", continuous_update=False),
        "pick": slider(0.5, 0.05, 1.0, 0.05, "picking σ (px)", continuous_update=False),
    }
    return build_demo(
        "plane_error",
        controls,
        fig.view,
        update,
        title="Measure on a plane: tilt, distance and the error",
        extra=[readout],
    )


def click_to_measure(ax, length_text, area_text) -> SimpleNamespace:
    """Measure on a photo by clicking it (ipympl): two clicks give a length, more clicks an area.

    Left-click points on ``ax``: after the second, ``length_text(a, b)`` is shown in the axes'
    title; further left clicks extend the outline, and a right-click closes it and shows
    ``area_text(points)``. The next left click starts again; a right-click with fewer than three
    points clears. Clicks while the toolbar zooms or pans are ignored. Under a static backend
    nothing is clicked and the figure stays as drawn.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes showing the photo in pixel coordinates (u, v).
    length_text : callable
        ``length_text(a, b) -> str`` for two (2,) pixels.
    area_text : callable
        ``area_text(points) -> str`` for (N, 2) pixels, N >= 3, in order around the outline.

    Returns
    -------
    SimpleNamespace
        ``points`` (the clicks so far), ``line`` (the drawn outline), ``click(u, v, button)``
        (what a mouse click does; tests call it) and ``connection`` (the canvas callback id).
    """
    (line,) = ax.plot(
        [], [], "-o", color="white", lw=2, ms=5, path_effects=palette.halo(2, "black")
    )  # white, black-edged: what you measure on a photo (the lesson's colour table)
    state = SimpleNamespace(points=[], closed=False, line=line)

    def show(text: str) -> None:
        pts = np.array(state.points).reshape(-1, 2)
        loop = np.vstack([pts, pts[:1]]) if state.closed else pts
        line.set_data(*loop.T)
        if text:
            ax.set_title(text, fontsize=10)
        ax.figure.canvas.draw_idle()

    def click(u: float, v: float, button: int = 1) -> None:
        if state.closed:
            state.points, state.closed = [], False
        if button == 1:
            state.points.append((float(u), float(v)))
            n = len(state.points)
            show(length_text(*np.array(state.points)) if n == 2 else "")
        elif len(state.points) >= 3:
            state.closed = True
            show(area_text(np.array(state.points)))
        else:
            state.points = []
            show("")

    def on_press(event) -> None:
        toolbar = getattr(ax.figure.canvas, "toolbar", None)
        if event.inaxes is not ax or getattr(toolbar, "mode", "") or event.xdata is None:
            return
        click(event.xdata, event.ydata, 1 if event.button == 1 else 3)

    state.click = click
    state.connection = ax.figure.canvas.mpl_connect("button_press_event", on_press)
    return state


RAY_MM_PER_PX = 0.332
"""Section 3's constant: sigma depth of the triangulated corner = RAY_MM_PER_PX * pick / sin(alpha/2),
0.166 mm / sin(alpha/2) at 0.5 px picking (measured there, asserted in the lesson's cell)."""


ALPHAS = np.linspace(3.0, 120.0, 118)
RAY_HALF = (3.0, 5.0)
"""The zoom panel's half-width and half-height at the corner, mm (fixed: the picking slider grows the ellipse)."""
RAY_RANGE_MM = 303.0
"""Each camera's distance from the corner in the scene panel, mm (section 3's camera A)."""


def _ray_axes(view) -> tuple:
    """The scene to scale (left), the zoom at the corner in mm (middle), the two laws (right)."""
    ax_scene, ax, ax_law = view.fig.subplots(1, 3, width_ratios=[0.95, 0.75, 1.15])
    ax_scene.set(xlim=(-290, 290), ylim=(-40, 340), aspect="equal")
    ax_scene.set_xlabel("across (mm)", fontsize=8)
    ax_scene.set_ylabel("along the bisector (mm)", fontsize=8)
    ax.set(xlim=(-RAY_HALF[0], RAY_HALF[0]), ylim=(-RAY_HALF[1], RAY_HALF[1]), aspect="equal")
    ax.set_xlabel("across, in the rays' plane (mm)", fontsize=8)
    ax.set_ylabel("depth, along the bisector (mm; cameras above)", fontsize=8)
    ax_law.set(xlim=(0, 124), ylim=(0.02, 20), yscale="log")  # room for the ring at 120 deg
    ax_law.set_xlabel("angle α between the rays (deg)", fontsize=8)
    ax_law.set_ylabel("one σ of the point (mm, log scale)", fontsize=8)
    ax_law.yaxis.set_major_formatter(FuncFormatter(lambda y, _: f"{y:g}"))
    for a in (ax_scene, ax, ax_law):
        a.tick_params(labelsize=7)
        a.grid(alpha=0.3)
        a.set_title(" ", fontsize=9)  # set by update
    return ax_scene, ax, ax_law


def _ray_figure() -> SimpleNamespace:
    """The cameras to scale, the two rays and their ellipse at the corner, and the two laws."""
    view = FigureView(figsize=(10.0, 4.9))
    ax_scene, ax, ax_law = _ray_axes(view)
    f = SimpleNamespace(view=view, ax=ax, ax_law=ax_law, ax_scene=ax_scene)
    f.scene_rays = [ax_scene.plot([], [], "-", color=palette.ORANGE, lw=1.2)[0] for _ in range(2)]
    (f.cameras,) = ax_scene.plot([], [], "o", color=palette.ORANGE, ms=7, ls="none")
    (f.baseline,) = ax_scene.plot([], [], "-", color="0.1", lw=2.5, label="the baseline B")
    ax_scene.plot(0, 0, "o", mfc="white", mec="0.1", ms=5, ls="none")  # the corner, static
    f.bands = [ax.fill([], [], color=palette.ORANGE, alpha=0.18, lw=0)[0] for _ in range(2)]
    lift = palette.halo(2.0)  # a white edge: the lines stay readable over the shaded bands
    f.rays = [
        ax.plot([], [], "-", color=palette.ORANGE, lw=1.2, path_effects=lift)[0] for _ in range(2)
    ]
    (f.ellipse,) = ax.plot([], [], "-", color=palette.BLUE, lw=2, path_effects=lift, zorder=3)
    (f.axes_,) = ax.plot([], [], "-", color=palette.BLUE, lw=1, path_effects=lift, zorder=2.9)
    ax.plot(
        [], [], "-o", color=palette.ORANGE, lw=1.2, ms=5, label="the two cameras and their rays"
    )
    ax.fill([], [], color=palette.ORANGE, alpha=0.18, lw=0, label="± e about each ray (one σ)")
    ax.plot([], [], "-", color=palette.BLUE, lw=2, label="95 % ellipse of the point")
    (f.law_depth,) = ax_law.plot(
        [], [], "-", color=palette.BLUE, lw=1.5, label="σ depth = c / sin(α/2)"
    )
    (f.law_across,) = ax_law.plot(
        [], [], "--", color=palette.BLUE, lw=1.5, label="σ across = c / cos(α/2)"
    )
    (f.here,) = ax_law.plot([], [], "o", mfc="none", mec="0.1", mew=1.5, ms=7, label="this α")
    handles = sum((a.get_legend_handles_labels()[0] for a in (ax_scene, ax, ax_law)), [])
    view.fig.legend(handles=handles, loc="outside lower center", ncols=4, fontsize=7)
    view.animate(*f.scene_rays, f.cameras, f.baseline, ax_scene.title)
    view.animate(*f.bands, *f.rays, f.ellipse, f.axes_, ax.title)
    view.animate(f.law_depth, f.law_across, f.here, ax_law.title)
    return f


def _draw_rays(fig: SimpleNamespace, half: float, e: float) -> None:
    """Both rays at +-half from the bisector: to scale in the scene, with their +-e bands at the corner."""
    ends = []
    for sign, ray, band, scene_ray in zip(
        (-1, 1), fig.rays, fig.bands, fig.scene_rays, strict=True
    ):
        d = np.array([sign * np.sin(half), np.cos(half)])  # toward its camera, above the corner
        n = np.array([d[1], -d[0]])
        ray.set_data(*np.outer([-60, 60], d).T)  # mm, far past the zoom's frame
        band.set_xy(np.array([-60 * d - e * n, 60 * d - e * n, 60 * d + e * n, -60 * d + e * n]))
        ends.append(RAY_RANGE_MM * d)
        scene_ray.set_data(*np.array([-0.1 * RAY_RANGE_MM * d, ends[-1]]).T)
    fig.cameras.set_data(*np.array(ends).T)
    fig.baseline.set_data(*np.array(ends).T)
    baseline = 2 * RAY_RANGE_MM * np.sin(half)
    fig.ax_scene.title.set_text(
        f"to scale: baseline B = {baseline:.0f} mm,\ncameras {RAY_RANGE_MM:.0f} mm from the corner"
    )


@register(lesson="12", sweep={"alpha": [5.0, 40.0, 120.0], "pick": [0.1, 1.0]})
def ray_angle() -> Demo:
    r"""Two rays crossing at a corner: the 95 % ellipse of the triangulated point as the angle closes.

    Each ray, moved sideways by its own noise :math:`e` (one sigma), moves the crossing by
    :math:`x = (e_1 + e_2) / (2\cos(\alpha/2))` across and :math:`y = (e_2 - e_1) / (2\sin(\alpha/2))`
    along the bisector (depth), so :math:`\sigma_\text{depth} = e / (\sqrt2 \sin(\alpha/2))` and
    :math:`\sigma_\text{across} = e / (\sqrt2 \cos(\alpha/2))`; :math:`e/\sqrt2` is section 3's
    0.166 mm at 0.5 px picking (:data:`RAY_MM_PER_PX` per pixel of picking). The left panel draws
    the two cameras to scale, :data:`RAY_RANGE_MM` from the corner; the middle one zooms on the
    corner in fixed millimetres, so the picking slider grows the ellipse and the bands.

    Returns
    -------
    Demo
        Controls ``alpha`` (the angle between the rays, degrees) and ``pick`` (picking sigma, px);
        ``state`` holds ``depth_mm`` and ``across_mm`` (one sigma), ``in_frame`` and the
        baseline ``baseline_mm`` of the scene panel.
    """
    fig = _ray_figure()
    readout = W.HTML()
    ring = np.linspace(0, 2 * np.pi, 181)
    k95 = np.sqrt(5.991)  # chi^2 with 2 degrees of freedom, 95 %: the 2-D ellipse, not 1.96
    ax, ax_law = fig.ax, fig.ax_law

    def update(v, state):
        half = np.radians(v["alpha"]) / 2
        c = RAY_MM_PER_PX * v["pick"]  # e / sqrt 2, mm
        e = np.sqrt(2) * c  # one ray's sideways sigma, mm
        depth, across = c / np.sin(half), c / np.cos(half)
        _draw_rays(fig, half, e)
        fig.ellipse.set_data(k95 * across * np.cos(ring), k95 * depth * np.sin(ring))
        fig.axes_.set_data(
            np.array([-across, across, np.nan, 0, 0]) * k95,
            np.array([0, 0, np.nan, -depth, depth]) * k95,
        )
        fig.law_depth.set_data(ALPHAS, c / np.sin(np.radians(ALPHAS) / 2))
        fig.law_across.set_data(ALPHAS, c / np.cos(np.radians(ALPHAS) / 2))
        fig.here.set_data([v["alpha"]] * 2, [depth, across])
        ax.title.set_text(f"at the corner: α = {v['alpha']:.0f}°, e = {e:.3f} mm")
        ax_law.title.set_text(f"the two laws, c = {c:.3f} mm at {v['pick']:.2f} px picks")
        in_frame = bool(k95 * depth <= RAY_HALF[1] and k95 * across <= RAY_HALF[0])
        state.update(
            depth_mm=depth,
            across_mm=across,
            in_frame=in_frame,
            baseline_mm=2 * RAY_RANGE_MM * np.sin(half),
        )
        readout.value = monospace(
            f"σ depth  = {c:.3f} mm / sin(α/2) = {depth:6.3f} mm  (ellipse half-axis {k95 * depth:5.2f} mm)\n"
            f"σ across = {c:.3f} mm / cos(α/2) = {across:6.3f} mm  (ellipse half-axis {k95 * across:5.2f} mm)\n"
            "the 95 % ellipse reaches 2.45 σ along each axis (2-D: √χ²₂(0.95) = √5.991);\n"
            f"one coordinate alone lies within ± 1.96 σ 95 % of the time (depth ± {1.96 * depth:.2f} mm)\n"
            f"depth / across = cot(α/2) = {depth / across:.2f}\n"
            f"{c:.3f} mm = e/√2: a pick off by {v['pick']:.2f} px moves each ray {e:.3f} mm sideways "
            f"at section 3's corner, {RAY_RANGE_MM:.0f} mm from its camera"
            + (
                ""
                if in_frame
                else "\nthe ellipse runs past the zoom's frame: the rays are nearly parallel"
            )
        )

    controls = {
        "alpha": slider(40.0, 5.0, 120.0, 1.0, "angle α (deg)"),
        "pick": slider(0.5, 0.1, 1.0, 0.05, "picking σ (px)"),
    }
    return build_demo(
        "ray_angle",
        controls,
        fig.view,
        update,
        title="Two rays: the ellipse as the angle closes",
        extra=[readout],
    )
