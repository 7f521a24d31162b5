"""The demo of lesson 00: proof that sliders, figures and readouts work in your browser."""

from __future__ import annotations

import html

import ipywidgets as W
import numpy as np
from ipywidgets import HTML
from matplotlib.colors import to_hex, to_rgba
from matplotlib.markers import MarkerStyle
from matplotlib.path import Path
from matplotlib.transforms import Affine2D

from ..plotting import palette
from ..plotting.plane import plane_axes
from ._base import Demo, FigureView, build_demo, display_mode, register, slider
from .browser import BrowserView, canvas_height, line_style, to_canvas_pixels
from .controls import int_slider

# A little house outline, in plot units: the course's running example of a shape. y points down, as in
# every image of the course, so the roof (drawn on top) has the most negative y.
HOUSE = np.array([[-1, 1], [1, 1], [1, -0.6], [0, -1.4], [-1, -0.6], [-1, 1]], dtype=float)
ROOF_TIP = 3  # HOUSE[3] is the roof tip, (0, -1.4)
DEFAULT_ANGLE = 40.0  # degrees: a turn whose arc (0.98 plot units) shows the path on both sides of its arrowhead
ARC_SAMPLES = 61  # points on the arc of the roof tip's turn
# The one cut-off for a short turn: under it the arc (1.4 θ, under 0.49 plot units) is too short to carry
# the arrowhead (a dart there read as the tip moving on), so none is drawn and the readout points to the arrow
# about the origin (turn_way), drawn at every angle; the browser's twin (stack_check.js) gets both in the scene.
SHORT_TURN_DEG = 20.0
SHORT_TURN_NOTE = f"  (θ under {SHORT_TURN_DEG:g}°: see the arrow about (0, 0))"
# Where the readout starts (figure fraction): its label ends there, the numbers and a note follow, so the longest
# line, a short turn's, fits inside the figure (tests/test_widgets.py measures it at every sweep point).
READOUT_X = 0.36
# The way of the turn at every angle, short ones too: an arrow on a fixed arc about the origin, the centre of
# the turn, on the side away from the roof tip's start (below it on y-down axes), clear of the dot on a short turn.
WAY_RADIUS = 0.5  # plot units at scale 1, times the scale: half the house's inradius, so never on its outline
# Under WAY_INSIDE_MIN_SCALE the house is too small to hold a readable arrow (at s = 0.3 it was 10 px long): the
# arrow goes outside the original house instead, on a circle of WAY_OUTSIDE_RADIUS, which nothing else crosses
# when s < 1 (both houses reach radius 1.42 at most, the roof tip's path 1.4).
WAY_INSIDE_MIN_SCALE = 0.8
WAY_OUTSIDE_RADIUS = 1.8
WAY_SWEEP_DEG = 80.0
MOVED = (
    "0.15"  # the moved house: near-black, so colour stays for the points the lesson reads (orange)
)
# The arrowhead on the roof tip's path: a slim dart pointing along +x (apex 39°, notched back), so it reads
# one way at every rotation; matplotlib's ">" is nearly equilateral and, turned by 60°, seems to point elsewhere.
ARROWHEAD = Path(
    [(1.0, 0.0), (-0.7, 0.6), (-0.3, 0.0), (-0.7, -0.6), (1.0, 0.0)],
    [Path.MOVETO, Path.LINETO, Path.LINETO, Path.LINETO, Path.CLOSEPOLY],
)


def turn_path(angle_deg: float, scale: float, start: np.ndarray, samples: int = 61) -> np.ndarray:
    r"""The path of ``start`` as the house turns by ``angle_deg``, then scales by ``scale``.

    The first ``samples`` points are the turn, :math:`R(t \theta)\, x_0` for t from 0 to 1: an arc of the
    circle through ``start`` about the origin, clockwise on y-down axes for θ > 0 and anticlockwise on
    y-up axes. The last point is :math:`s R(\theta)\, x_0`, so the scaling is the straight step out
    (s > 1) or in (s < 1) along the radius, where the roof tip ends. The order is immaterial, since
    :math:`s R = R s`; turning first keeps the arc at the house's own size, where the turn shows.

    Parameters
    ----------
    angle_deg : float
        The turn θ, degrees.
    scale : float
        The scale s.
    start : (2,) ndarray
        The point's starting position, plot units.
    samples : int
        Points along the arc, both ends included.

    Returns
    -------
    (samples + 1, 2) ndarray
        The arc, then the scaled end point.
    """
    t = np.linspace(0.0, 1.0, samples)[:, None]
    theta = np.radians(angle_deg) * t
    x, y = start
    arc = np.hstack([x * np.cos(theta) - y * np.sin(theta), x * np.sin(theta) + y * np.cos(theta)])
    return np.vstack([arc, scale * arc[-1]])


def way_radius(scale: float) -> float:
    """The radius of the arrow about the origin for the house's scale ``scale``, plot units.

    :data:`WAY_RADIUS` times ``scale`` (half the moved house's inradius, ``scale``) while that is at least
    0.4 plot units (``scale`` >= :data:`WAY_INSIDE_MIN_SCALE`); below it, :data:`WAY_OUTSIDE_RADIUS`,
    outside both houses and the roof tip's path, so the arrow never shrinks below a readable size. The
    browser's twin is in ``widgets/browser/stack_check.js``.

    Parameters
    ----------
    scale : float
        The house's scale s.

    Returns
    -------
    float
        The radius, plot units.
    """
    return WAY_RADIUS * scale if scale >= WAY_INSIDE_MIN_SCALE else WAY_OUTSIDE_RADIUS


def turn_way(angle_deg: float, samples: int = 25, scale: float = 1.0) -> np.ndarray:
    r"""The arc of the arrow that shows which way the house turns, at any angle: fixed sweep, about the origin.

    An arc of :data:`WAY_SWEEP_DEG` on the circle of radius :func:`way_radius` about the origin (inside
    the moved house, or outside both houses when the house is too small to hold it), centred on
    the direction opposite the roof tip's start, (0, 1), and running the way :math:`R(\theta)` turns for the
    sign of ``angle_deg``; its arrowhead goes at the last point. Its length does not grow with the angle, so
    a turn of 5° shows its way as clearly as one of 90°.

    Parameters
    ----------
    angle_deg : float
        The turn θ, degrees; only its sign matters.
    samples : int
        Points along the arc, both ends included.
    scale : float
        The house's scale s; the arc's radius is :func:`way_radius` of it.

    Returns
    -------
    (samples, 2) ndarray
        The arc, plot units; an empty (0, 2) array at θ = 0 (no turn, no way).
    """
    if angle_deg == 0:
        return np.zeros((0, 2))
    phi = np.radians(90.0 + np.sign(angle_deg) * WAY_SWEEP_DEG * np.linspace(-0.5, 0.5, samples))
    return way_radius(scale) * np.column_stack([np.cos(phi), np.sin(phi)])


def turn_and_scale(angle_deg: float, scale: float) -> np.ndarray:
    r"""The 3x3 homogeneous map of :math:`x' = s R(\theta)\, x`: the turn by ``angle_deg``, then the scale.

    :math:`R(\theta) = \begin{pmatrix} \cos\theta & -\sin\theta \\ \sin\theta & \cos\theta
    \end{pmatrix}` turns x towards y; its upper 2x2 block is the demo's ``A``. The browser's
    twin is ``turnAndScale`` in ``widgets/browser/geometry.js``.

    Parameters
    ----------
    angle_deg : float
        The turn θ, degrees.
    scale : float
        The scale s.

    Returns
    -------
    (3, 3) ndarray
        ``[[s cos θ, -s sin θ, 0], [s sin θ, s cos θ, 0], [0, 0, 1]]``.
    """
    t = np.radians(angle_deg)
    return np.array(
        [
            [scale * np.cos(t), -scale * np.sin(t), 0.0],
            [scale * np.sin(t), scale * np.cos(t), 0.0],
            [0.0, 0.0, 1.0],
        ]
    )


def tip_readout(point: np.ndarray) -> str:
    """The readout of a point, ``"(+x.xx, -y.yy)"``: two decimals, a sign always, never ``-0.00``.

    The browser's twin is ``tipReadout`` in ``widgets/browser/geometry.js``.

    Parameters
    ----------
    point : (2,) array_like
        The point, plot units.

    Returns
    -------
    str
        The two coordinates rounded to 2 decimals (``round`` then ``+ 0.0`` turns a rounded -0.0 into 0.0).
    """
    x, y = (round(float(c), 2) + 0.0 for c in point)
    return f"({x:+.2f}, {y:+.2f})"


def turn_words(angle_deg: float, y_down: bool) -> str:
    """How R(angle) turns a shape, from angle 0, as drawn on y-down or y-up axes.

    A positive angle turns x towards y: clockwise on screen when y points down, anticlockwise when it
    points up. At ±180° both ways end at the same place; the words name the way the angle went.

    Parameters
    ----------
    angle_deg : float
        The angle, degrees.
    y_down : bool
        True for image axes (y down), False for textbook axes (y up).

    Returns
    -------
    str
        ``"clockwise"`` or ``"anticlockwise"`` (with ``", half a turn"`` at ±180°), or
        ``"no turn"`` at 0.
    """
    if angle_deg == 0:
        return "no turn"
    way = "clockwise" if (angle_deg > 0) == y_down else "anticlockwise"
    return f"{way}, half a turn" if abs(angle_deg) == 180 else way


def _house_panel(ax, y_down: bool, view: FigureView) -> dict:
    """One panel: the original house, the moved one, the roof tip and its path; returns the animated artists."""
    plane_axes(
        ax,
        3,
        xlabel="x, right (plot units)",
        ylabel=f"y, {'down' if y_down else 'up'} (plot units)",
    )
    ax.xaxis.label.set_color(palette.RED)  # x red, y green: the axis colours of every lesson
    ax.yaxis.label.set_color(palette.GREEN)
    if y_down:
        ax.invert_yaxis()  # y down, as in images and in the camera frame
    # A light fill keeps the original visible where the moved outline covers its edge (angle 0, scale 1).
    ax.fill(
        HOUSE[:, 0],
        HOUSE[:, 1],
        facecolor=to_rgba(palette.GREY, 0.2),
        edgecolor=palette.GREY,
        lw=1,
        ls="--",
        label="original",
    )
    # A white outline keeps the dotted path apart from the original's dashed edge it starts on.
    path = view.animate(
        ax.plot(
            [],
            [],
            ":",
            color=palette.ORANGE,
            lw=1.6,
            label="roof tip's path: rotation, then scaling",
            path_effects=palette.halo(1.6),
        )[0]
    )
    arrow = view.animate(
        ax.plot(
            [],
            [],
            ls="none",
            marker=ARROWHEAD,
            ms=15,
            color=palette.ORANGE,
            mec="white",
            mew=0.6,
            label="_the way",
        )[0]
    )
    way = view.animate(
        ax.plot([], [], color=MOVED, lw=1.5, label="direction of rotation, about (0, 0)")[0]
    )
    way_head = view.animate(
        ax.plot([], [], ls="none", marker=ARROWHEAD, ms=10, color=MOVED, mec="white", mew=0.5)[0]
    )
    way_head.set_label("_the way's arrowhead")
    house = view.animate(ax.plot([], [], color=MOVED, lw=2, label="rotated and scaled")[0])
    tip = view.animate(ax.plot([], [], "o", color=palette.ORANGE, ms=7, label="roof tip")[0])
    # Static titles (a text redrawn in every frame costs more than all the lines): the rule, both signs.
    ax.set_title(
        f"y {'down, as in images' if y_down else 'up, as in maths textbooks'}:\n"
        f"θ > 0 {turn_words(1.0, y_down)}, θ < 0 {turn_words(-1.0, y_down)}",
        fontsize=10,
    )
    return dict(
        ax=ax,
        path=path,
        arrow=arrow,
        way=way,
        way_head=way_head,
        house=house,
        tip=tip,
        y_down=y_down,
    )


def screen_turn(ax, path: np.ndarray) -> str:
    """Which way ``path`` turns as ``ax`` draws it on screen.

    Measured on the drawing, not taken from the sign of the angle: the path is mapped to display
    coordinates by the axes' own transform (which includes a flipped y axis), and the sign of the sum
    of the cross products of successive steps says which way it bends (display y runs up, so a
    positive sum is anticlockwise on screen).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes that draw the path.
    path : (N, 2) array_like
        The path in data coordinates, N >= 3.

    Returns
    -------
    str
        ``"clockwise"``, ``"anticlockwise"`` or ``"no turn"`` (a bend under 1e-9 of the squared
        length).
    """
    screen = ax.transData.transform(np.asarray(path, dtype=float))
    steps = np.diff(screen, axis=0)
    bend = float(np.sum(steps[:-1, 0] * steps[1:, 1] - steps[:-1, 1] * steps[1:, 0]))
    scale = float(np.sum(np.hypot(*steps.T)) ** 2) or 1.0
    if abs(bend) < 1e-9 * scale:
        return "no turn"
    return "anticlockwise" if bend > 0 else "clockwise"


def path_note(angle_deg: float, scale: float) -> str:
    """What the readout adds when the legend's path or arrowhead is not drawn: none, no path, or too short.

    At 0° and scale 1 nothing moves; under :data:`SHORT_TURN_DEG` (at any scale) the turn draws no
    arrowhead, the same test as the demo's. The browser's twin is in ``widgets/browser/stack_check.js``,
    which gets the cut-off and the note in the scene.

    Parameters
    ----------
    angle_deg : float
        The turn θ, degrees.
    scale : float
        The scale s.

    Returns
    -------
    str
        '' when the path shows, else a note starting with two spaces.
    """
    if angle_deg == 0:
        return "  (unmoved: no path)" if scale == 1 else ""
    return SHORT_TURN_NOTE if abs(angle_deg) < SHORT_TURN_DEG else ""


def arrowhead_size(angle_deg: float, radius: float = 1.4) -> float:
    """The arrowhead's marker size for a turn of ``angle_deg`` on a circle of ``radius``.

    15 points (about 0.5 plot units at the demo's size) for turns of 40° and more, where the arc is
    about twice as long as the dart; shorter arcs get a smaller dart, down to 7 points, so that the
    arc still shows on both sides of it (at 30° the arc is 0.73 plot units long).

    Parameters
    ----------
    angle_deg : float
        The turn, degrees (its sign does not matter).
    radius : float
        The circle's radius, plot units.

    Returns
    -------
    float
        The marker size, points, in [7, 15].
    """
    arc = abs(np.radians(angle_deg)) * radius  # plot units
    return float(np.clip(15.0 * arc / 0.98, 7.0, 15.0))


def _point_arrow(arrow, at: np.ndarray, way: np.ndarray, y_down: bool) -> float | None:
    """Put the arrowhead marker at ``at``, pointing along ``way`` as drawn; returns its angle on screen.

    The angle is in degrees, anticlockwise from screen-right (None, and no marker, for a path of
    length 0). The axes have equal aspect, so a direction in plot units keeps its angle on screen,
    with y mirrored on y-down axes; :data:`ARROWHEAD` points right before it is turned.
    """
    if np.hypot(*way) < 1e-9:
        arrow.set_data([], [])
        return None
    angle = float(np.degrees(np.arctan2(-way[1] if y_down else way[1], way[0])))
    arrow.set_marker(MarkerStyle(ARROWHEAD, transform=Affine2D().rotate_deg(angle)))
    arrow.set_data([at[0]], [at[1]])
    return angle


def _browser_scene(panels: list[dict], readout, dpi: float) -> dict:
    """What ``stack_check.js`` needs to draw the moving artists as matplotlib draws them (sizes in canvas pixels)."""
    pt = dpi / 72.0
    first = panels[0]
    path, arrow, house, tip = (first[k] for k in ("path", "arrow", "house", "tip"))
    way_head = first["way_head"]
    fig_h = canvas_height(readout.figure)
    x, y = readout.get_transform().transform(readout.get_position())
    return dict(
        house=HOUSE.tolist(),
        roofTip=ROOF_TIP,
        arcSamples=ARC_SAMPLES,
        shortTurnDeg=SHORT_TURN_DEG,
        shortTurnNote=SHORT_TURN_NOTE,
        wayRadius=WAY_RADIUS,
        wayInsideMinScale=WAY_INSIDE_MIN_SCALE,
        wayOutsideRadius=WAY_OUTSIDE_RADIUS,
        waySweepDeg=WAY_SWEEP_DEG,
        arrowhead=ARROWHEAD.vertices[:-1].tolist(),
        panels=[dict(toPixels=to_canvas_pixels(p["ax"]), yDown=p["y_down"]) for p in panels],
        styles=dict(
            path=line_style(path, pt, halo="#ffffff", haloWidth=(path.get_linewidth() + 2.0) * pt),
            house=line_style(house, pt),
            way=line_style(first["way"], pt),
            wayHead=dict(
                color=to_hex(way_head.get_color()),
                edge=to_hex(way_head.get_markeredgecolor()),
                edgeWidth=way_head.get_markeredgewidth() * pt,
                size=way_head.get_markersize() * pt,
            ),
            arrow=dict(
                color=to_hex(arrow.get_color()),
                edge=to_hex(arrow.get_markeredgecolor()),
                edgeWidth=arrow.get_markeredgewidth() * pt,
            ),
            tip=dict(
                color=to_hex(tip.get_color()),
                edge=to_hex(tip.get_markeredgecolor()),
                size=tip.get_markersize() * pt,
                edgeWidth=tip.get_markeredgewidth() * pt,
            ),
        ),
        readout=dict(
            x=float(x),
            y=float(fig_h - y),
            font=f"{readout.get_fontsize() * pt:.2f}px 'DejaVu Sans', sans-serif",
            color=to_hex(readout.get_color()),
        ),
    )


@register(
    lesson="00",
    sweep={
        "angle": [-180.0, -90.0, -30.0, -15.0, -5.0, 0.0, 5.0, 15.0, 90.0, 135.0, 180.0],
        "scale": [0.3, 0.5, 1.5, 2.0],
    },
)
def stack_check() -> Demo:
    """Rotate and scale a house with two sliders, drawn on y-down axes (images) and y-up axes (textbooks).

    Both panels draw the same numbers, x' = s R(angle) x: on y-down axes a positive angle turns the
    house clockwise, on y-up axes anticlockwise. The dotted path of the roof tip is the turn (an arc,
    whose arrowhead shows the way), then the scaling (a straight step along the radius); a small arrow about
    the origin shows the way of the turn at every angle, the short turns whose arc has no arrowhead too. The
    readout above the panels gives the roof tip's coordinates; the legend sits under the axes, since
    at scale 2 the house reaches every corner of them.

    Returns
    -------
    Demo
        The demo: controls ``angle`` (θ, degrees, -180 to 180) and ``scale`` (s, 0.3 to 2), the
        figure (the two panels) and ``state`` (``A`` = s R(θ), ``house``, ``tip``, ``path``,
        ``readout``, ``arrow`` (where the arrowhead sits and its screen angle per panel) and
        ``turns`` (the way each panel's arc turns on screen) and ``way`` (the way each panel's arrow about
        the origin turns on screen)).
    """
    view = BrowserView(("angle", "scale"), figsize=(7.0, 4.55))
    ax_down, ax_up = view.fig.subplots(1, 2)
    panels = [_house_panel(ax_down, True, view), _house_panel(ax_up, False, view)]
    # The readout over both panels: a static label, and the numbers (few glyphs: each costs time in every
    # frame). An axes' animated text is drawn when the figure is saved (the static picture a notebook keeps),
    # a figure's is not; the blank title keeps the room for the readout in the layout.
    view.fig.suptitle(" ", fontsize=18)  # a little taller than the readout: a gap above the titles
    where = dict(
        transform=view.fig.transFigure, va="top", fontsize=11, in_layout=False, gid="readout"
    )
    ax_down.text(READOUT_X, 0.98, "roof tip (orange dot) at ", ha="right", **where)
    readout = view.animate(ax_down.text(READOUT_X, 0.98, "", ha="left", **where))
    view.fig.legend(
        *ax_down.get_legend_handles_labels(), loc="outside lower center", ncols=3, fontsize=9
    )

    def update(v: dict, state: dict) -> None:
        angle, s = v["angle"], v["scale"]
        A = turn_and_scale(angle, s)[:2, :2]  # x' = s R(angle) x
        moved = HOUSE @ A.T  # points are rows: the textbook's A x for every corner at once
        path = turn_path(angle, s, HOUSE[ROOF_TIP], samples=ARC_SAMPLES)
        middle = ARC_SAMPLES // 2  # the arrowhead sits half-way along the turn
        way = path[middle + 1] - path[middle - 1]  # the turn's direction there, in plot units
        arrows, turns, way_turns = {}, {}, {}
        # An arc too short to carry the dart (a turn under SHORT_TURN_DEG): no dart (one drawn past the
        # dot read as the tip moving on); the readout says so, and cell 7 of the lesson names the turn.
        if abs(angle) < SHORT_TURN_DEG:
            way = np.zeros(2)
        arc = turn_way(angle, scale=s)  # the way of the turn, at every angle but 0: see way_radius
        for panel in panels:
            panel["way"].set_data(arc[:, 0], arc[:, 1])
            ends = arc[-2:] if len(arc) else np.zeros((2, 2))
            _point_arrow(panel["way_head"], ends[-1], ends[-1] - ends[0], panel["y_down"])
            panel["house"].set_data(moved[:, 0], moved[:, 1])
            panel["tip"].set_data(
                moved[ROOF_TIP : ROOF_TIP + 1, 0], moved[ROOF_TIP : ROOF_TIP + 1, 1]
            )
            panel["path"].set_data(path[:, 0], path[:, 1])
            key = "y down" if panel["y_down"] else "y up"
            arrows[key] = _point_arrow(panel["arrow"], path[middle], way, panel["y_down"])
            panel["arrow"].set_markersize(arrowhead_size(angle))
            # the way the drawn arc turns on screen, measured through the panel's own axes
            way_on_screen = screen_turn(panel["ax"], path[:-1]) if angle else "no turn"
            turns[key] = (
                f"{way_on_screen}, half a turn"
                if abs(angle) == 180 and way_on_screen != "no turn"
                else way_on_screen
            )
            way_turns[key] = screen_turn(panel["ax"], arc) if len(arc) >= 3 else "no turn"
        numbers = tip_readout(moved[ROOF_TIP])
        readout.set_text(
            numbers + path_note(angle, s)
        )  # at 0°, scale 1 the moved house hides the original
        text.value = (
            f"roof tip (orange dot) at {numbers}{path_note(angle, s)}"  # as text beside the sliders
        )
        # tip: where the orange dot is drawn (lesson 00 recomputes it by hand); readout: the numbers shown
        # arrow: where the arrowhead sits, and its angle on screen in each panel (None: no dart drawn)
        # turns: the way each panel's drawn arc turns on screen (screen_turn), measured, not read off the angle
        state.update(
            A=A,
            house=moved,
            tip=moved[ROOF_TIP].copy(),
            path=path,
            readout=numbers,
            arrow=dict(at=np.array(path[middle], dtype=float), **arrows),
            turns=turns,
            way=way_turns,
        )

    controls = {
        "angle": slider(DEFAULT_ANGLE, -180.0, 180.0, 1.0, "angle θ (°)", readout_format=".0f"),
        "scale": slider(1.0, 0.3, 2.0, 0.05, "scale s"),
    }
    text = HTML()  # the readout beside the sliders too: selectable, and read by a screen reader
    demo = build_demo(
        "stack_check", controls, view, update, title="Is everything working?", extra=[text]
    )
    view.publish(demo, _browser_scene(panels, readout, view.fig.dpi))  # the browser draws the moves
    return demo


def stack_report() -> str:
    """What the kernel can see of the interactive stack: the versions, and whether demos will be live figures.

    The browser's half (JupyterLab's ipywidgets, anywidget and ipympl extensions) is out of the
    kernel's sight: the demo below tests anywidget (it is drawn in the browser), and the figures
    from section 3 on, the pixel explorer among them, test ipympl.

    Returns
    -------
    str
        Two lines: the versions of camlab, numpy, matplotlib, ipywidgets, anywidget and ipympl, then
        whether figures will be live (``%matplotlib widget``) or still pictures (naming the
        backend).
    """
    from importlib.metadata import PackageNotFoundError, version

    import matplotlib

    from .. import __version__

    found = {}
    for name in ("anywidget", "ipympl"):
        try:
            found[name] = version(name)
        except PackageNotFoundError:
            found[name] = "missing"
    versions = (
        f"camlab {__version__}, numpy {np.__version__}, matplotlib {matplotlib.__version__}, "
        f"ipywidgets {W.__version__}, anywidget {found['anywidget']}, ipympl {found['ipympl']}"
    )
    if display_mode() == "ipympl":
        return (
            versions
            + "\nfigures: live (%matplotlib widget is on); in the browser, the demo below tests anywidget, "
            "section 3's figures ipympl"
        )
    return (
        versions
        + f"\nfigures: still pictures, not live: the matplotlib backend is {matplotlib.get_backend()!r}; "
        "run `%matplotlib widget` first (the setup cell's first line)"
    )


EXPLORER_SIZE = (
    6,
    4,
)  # (W, H) of the pixel explorer's image: wider than tall, so img[u, v] can fail
TOOLS = ("camlab, OpenCV", "MATLAB", "Pillow, COLMAP", "OpenGL window")


def tool_pixel(u: int, v: int, size: tuple[int, int]) -> dict[str, tuple[tuple[float, float], str]]:
    """Where each tool of lesson 00's table puts the centre of the course's pixel (u, v), and how it reads it.

    The course (camlab, OpenCV): centre (u, v), read ``img[v, u]``. MATLAB counts from 1: centre
    (u + 1, v + 1), read ``img(v + 1, u + 1)``. Pillow and COLMAP put whole numbers on pixel corners:
    centre (u + 0.5, v + 0.5); Pillow reads the pixel as ``getpixel((u, v))``. OpenGL's window
    coordinates count rows from the bottom, y up: centre (u + 0.5, H - 0.5 - v), read by
    ``glReadPixels(u, H - 1 - v, ...)``.

    Parameters
    ----------
    u, v : int
        The pixel, column and row in the course's convention (0-based, from the top-left).
    size : (W, H)
        The image's size, pixels.

    Returns
    -------
    dict
        Tool name (:data:`TOOLS`) -> ((x, y) of the pixel's centre in that tool, the read as code).
    """
    H = size[1]
    return {
        "camlab, OpenCV": ((float(u), float(v)), f"img[{v}, {u}]"),
        "MATLAB": ((u + 1.0, v + 1.0), f"img({v + 1}, {u + 1})"),
        "Pillow, COLMAP": ((u + 0.5, v + 0.5), f"getpixel(({u}, {v}))"),
        "OpenGL window": ((u + 0.5, H - 0.5 - v), f"glReadPixels({u}, {H - 1 - v}, …)"),
    }


def _explorer_text(u: int, v: int, img: np.ndarray) -> str:
    """The explorer's readout: the value read both ways, then each tool's centre and read (monospace lines)."""
    H, W = img.shape
    if u < H and v < W:
        which = "the same pixel, since u = v" if u == v else f"pixel ({v}, {u}), the wrong one"
        swapped = f"img[u, v] = img[{u}, {v}] = {img[u, v]}:\n  {which}"
    else:
        missing = f"no row {u}" if u >= H else f"no column {v}"
        swapped = f"img[u, v] = img[{u}, {v}]:\n  IndexError ({missing}: H = {H})"
    lines = [
        f"img[v, u] = img[{v}, {u}] = {img[v, u]}",
        swapped,
        "",
        "its centre in each tool, and its read:",
    ]
    short = {
        "camlab, OpenCV": "camlab/OpenCV",
        "Pillow, COLMAP": "Pillow/COLMAP",
        "OpenGL window": "OpenGL",
    }
    for tool, ((x, y), read) in tool_pixel(u, v, (W, H)).items():
        read = f"Pillow: {read}" if tool == "Pillow, COLMAP" else read  # COLMAP reads no pixels
        lines.append(f"{short.get(tool, tool):13s} {f'({x:g}, {y:g})':11s} {read}")
    return "\n".join(lines)


def _explorer_image(ax, img: np.ndarray) -> None:
    """Draw the explorer's image: light greys, each pixel's value, its centre dot, u and v axes.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The image axes.
    img : (H, W) ndarray
        The image, each pixel holding 10 v + u.
    """
    H, W = img.shape
    rows, cols = np.mgrid[0:H, 0:W]
    ax.imshow(
        img, cmap="gray", vmin=-120, vmax=40
    )  # light greys: dark numbers and marks read on all
    for (r, q), value in np.ndenumerate(img):
        ax.text(q, r + 0.3, f"{value}", ha="center", va="center", fontsize=10, color="0.1")
    ax.plot(cols.ravel(), rows.ravel(), ".", color="0.25", ms=3)
    ax.set_xticks(range(W))
    ax.set_yticks(range(H))
    ax.set_xlabel("u (px): column", color=palette.RED)
    ax.set_ylabel("v (px): row", color=palette.GREEN)
    ax.set_title(
        f"a {W} x {H} image holding 10 v + u at img[v, u]", fontsize=10, pad=10
    )  # clear of the +


def _pixel_square(ax, colour: str, lw: float, ls, label: str):
    """An unfilled one-pixel square for the pixel explorer, drawn over the spines.

    Parameters
    ----------
    ax : matplotlib Axes
        The image axes.
    colour : str
        Its edge colour (from the palette).
    lw : float
        Its line width in points.
    ls : str or tuple
        Its line style.
    label : str
        Its legend entry.

    Returns
    -------
    matplotlib.patches.Rectangle
        The square, at (0, 0) until the demo moves it.
    """
    from matplotlib.patches import Rectangle

    return ax.add_patch(
        Rectangle(
            (0, 0),
            1,
            1,
            fill=False,
            ec=colour,
            lw=lw,
            ls=ls,
            clip_on=False,
            zorder=3,  # over the spines (2.5) on every draw, the first as the live ones
            label=label,
        )
    )


def _explorer_figure(view: FigureView, img: np.ndarray) -> tuple:
    """The pixel explorer's image with its values, its key and its animated marks.

    Parameters
    ----------
    view : FigureView
        The demo's figure.
    img : (H, W) ndarray
        The image, each pixel holding 10 v + u.

    Returns
    -------
    tuple
        The image axes, then the animated pixel square, swapped-read square, centre dot,
        top-left corner marker and readout text.
    """
    ax, ax_text = view.fig.subplots(1, 2, width_ratios=[1.0, 1.0])
    _explorer_image(ax, img)
    square = view.animate(_pixel_square(ax, palette.ORANGE, 2.8, "-", "pixel (u, v)"))
    swapped = view.animate(
        _pixel_square(
            ax,
            palette.PURPLE,
            2.0,
            (0, (4, 2)),
            "the pixel img[u, v] reads\n(none for u ≥ H: an IndexError)",
        )
    )
    centre = view.animate(
        ax.plot(
            [],
            [],
            "o",
            color=palette.ORANGE,
            ms=8,
            mec="black",
            mew=0.8,
            label="its centre, (u, v)",
        )[0]
    )
    corner = view.animate(
        ax.plot(
            [],
            [],
            "P",
            color="white",  # not blue: blue is the z axis in every lesson
            ms=9,
            mec="black",
            mew=0.8,
            clip_on=False,
            zorder=4,  # over the squares (3): the + sits on their corner
            label="Pillow's and COLMAP's (u, v):\nthe pixel's top-left corner",
        )[0]
    )
    # A margin of 0.25 px round the image: the squares and the + on an edge pixel stay clear of the spines.
    ax.set_xlim(-0.75, img.shape[1] - 0.25)
    ax.set_ylim(img.shape[0] - 0.25, -0.75)
    ax_text.axis("off")
    ax_text.legend(  # under the readout (up to 10 lines), not at the bottom: one block to read
        *ax.get_legend_handles_labels(),
        loc="upper left",
        bbox_to_anchor=(0.0, 0.56),
        fontsize=8.5,
        frameon=False,
    )
    readout = view.animate(
        ax_text.text(
            0.0,
            0.96,  # a little below the figure's top edge
            "",
            va="top",
            ha="left",
            family="monospace",
            fontsize=8.5,
            transform=ax_text.transAxes,
        )
    )

    return ax, square, swapped, centre, corner, readout


@register(lesson="00", sweep={"u": [0, 5], "v": [0, 3]})
def pixel_explorer() -> Demo:
    """A pixel (u, v) of a 6 x 4 image, picked with the sliders or a click.

    The figure shows the pixel's square, its centre, its value img[v, u], and where each tool's
    convention puts its centre.

    Every pixel shows its value, 10 v + u, so the value names the pixel. The orange square is the
    pixel, the orange dot its centre at the whole numbers (u, v); the white + is the point Pillow and
    COLMAP call (u, v), the pixel's top-left corner (their centre is half a pixel further on). The
    purple dashed square is the pixel that the swapped read img[u, v] returns, where it exists (for
    u >= H it raises an IndexError instead). The readout lists each tool's centre of the pixel.

    Returns
    -------
    Demo
        The demo: controls ``u`` (column, 0 to W - 1) and ``v`` (row, 0 to H - 1); the figure (the
        image, and the readout beside it); ``handlers["button_press_event"]`` (a click picks the
        pixel under it); and ``state`` (``u``, ``v``, ``value`` = img[v, u], ``swapped`` =
        img[u, v] or None where it raises, ``tools``: :func:`tool_pixel`).
    """
    W, H = EXPLORER_SIZE
    rows, cols = np.mgrid[0:H, 0:W]
    img = 10 * rows + cols
    view = FigureView(figsize=(8.2, 3.9))
    ax, square, swapped, centre, corner, readout = _explorer_figure(view, img)
    text = HTML()  # the readout beside the sliders too, as text a screen reader reads

    def update(values: dict, state: dict) -> None:
        u, v = int(values["u"]), int(values["v"])
        square.set_xy((u - 0.5, v - 0.5))
        centre.set_data([u], [v])
        corner.set_data([u - 0.5], [v - 0.5])
        inside = u < H and v < W  # img[u, v] exists: row u, column v
        swapped.set_visible(inside)
        if inside:
            swapped.set_xy((v - 0.5, u - 0.5))  # row u, column v: the pixel (v, u)
        readout.set_text(_explorer_text(u, v, img))
        text.value = (
            f"<pre>{html.escape(readout.get_text())}</pre>"  # the same, selectable and read aloud
        )
        state.update(
            u=u,
            v=v,
            value=int(img[v, u]),
            swapped=int(img[u, v]) if inside else None,
            tools=tool_pixel(u, v, (W, H)),
            readout=readout.get_text(),
        )

    controls = {
        "u": int_slider(3, 0, W - 1, "u (column)"),
        "v": int_slider(1, 0, H - 1, "v (row)"),
    }
    demo = build_demo(
        "pixel_explorer", controls, view, update, title="Which pixel is (u, v)?", extra=[text]
    )

    def on_click(event) -> None:
        if event.inaxes is not ax or event.xdata is None:
            return
        u, v = (
            int(np.clip(np.rint(event.xdata), 0, W - 1)),
            int(np.clip(np.rint(event.ydata), 0, H - 1)),
        )
        demo.set(u=u, v=v)

    view.fig.canvas.mpl_connect("button_press_event", on_click)
    demo.handlers["button_press_event"] = (
        on_click  # tests call it with an object carrying inaxes, xdata, ydata
    )
    return demo
