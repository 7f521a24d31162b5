"""Contrast inside figures (WCAG 2.1 1.4.3 and 1.4.11): every demo at its default settings.

Text needs 4.5:1 against what lies behind it (3:1 for large text: 24 px, or 18.7 px bold,
as drawn), lines and markers 3:1. "Behind it" is measured, not assumed: the figure is drawn
once more with every text, line and marker hidden, and the colour of each text or line is
compared, pixel by pixel, with that background under the text's box or along the line's
path (alpha blended as drawn; a text's own box, if it has one, is its background). At least
90% of those pixels must reach the ratio, so a line may cross another line or a small
patch of the same colour, but not run over a background it vanishes into.

A marker passes if its face or its edge reaches 3:1. Things that carry no information are
left out, each for a reason in :data:`NOT_INFORMATION`; images are data, not checked here
(value images are checked for a colour bar below).
"""

from __future__ import annotations

from unittest import mock

import numpy as np
import pytest
from matplotlib import patheffects
from matplotlib.collections import Collection, LineCollection, PathCollection
from matplotlib.colors import to_hex, to_rgba, to_rgba_array
from matplotlib.image import AxesImage
from matplotlib.lines import Line2D
from matplotlib.text import Text

from camlab.widgets import all_demos

DEMOS = all_demos()
TEXT, LARGE_TEXT, GRAPHICS = 4.5, 3.0, 3.0
GRID = "grid lines, and frames and guides marked gid='grid': reading aids that carry no data of their own"
THUMBNAIL = (
    "the picture on a 3-D camera's image plane (gid='thumbnail'): a few pixels wide, a copy of "
    "the 2-D image panel beside it, which is checked"
)
MARKED = {"grid": GRID, "thumbnail": THUMBNAIL}
SHARE = 0.9  # of the background pixels under a text or along a line that must reach the ratio


def luminance(rgb: np.ndarray) -> np.ndarray:
    """WCAG relative luminance of sRGB colours (..., 3) in [0, 1]."""
    c = np.where(rgb <= 0.04045, rgb / 12.92, ((rgb + 0.055) / 1.055) ** 2.4)
    return c @ np.array([0.2126, 0.7152, 0.0722])


def contrast(fg: np.ndarray, bg: np.ndarray) -> np.ndarray:
    """WCAG contrast ratio of colours (..., 3) against colours (..., 3), from 1 to 21."""
    a, b = luminance(fg), luminance(bg)
    return (np.maximum(a, b) + 0.05) / (np.minimum(a, b) + 0.05)


def drawn_over(rgba, bg: np.ndarray) -> np.ndarray:
    """The colour an RGBA colour shows over background pixels (N, 3)."""
    r, g, b, a = rgba
    return a * np.array([r, g, b]) + (1 - a) * bg


def _alpha(artist, rgba) -> tuple:
    a = artist.get_alpha()
    return (*rgba[:3], rgba[3] * (1.0 if a is None else a))


def _halo(artist, background: np.ndarray) -> np.ndarray:
    """The outline a ``palette.halo`` path effect draws under the artist is its background."""
    for effect in artist.get_path_effects() or ():
        if isinstance(effect, patheffects.Stroke) and "foreground" in effect._gc:
            outline = to_rgba(effect._gc["foreground"])
            return drawn_over(_alpha(artist, outline), background)  # drawn with the artist's alpha
    return background


def _along(points_px: np.ndarray, step: float = 2.0) -> np.ndarray:
    """Points every ``step`` pixels along a polyline given in display pixels (NaN breaks it)."""
    out = []
    for p, q in zip(points_px[:-1], points_px[1:], strict=True):
        if not (np.isfinite(p).all() and np.isfinite(q).all()):
            continue
        n = max(1, int(np.hypot(*(q - p)) / step))
        out.append(p + (q - p) * np.linspace(0, 1, n + 1)[:, None])
    return np.concatenate(out) if out else np.empty((0, 2))


def _sample(background: np.ndarray, xy: np.ndarray) -> np.ndarray:
    """Background pixels (N, 3) at display points (origin bottom left), inside the figure only."""
    h, w = background.shape[:2]
    col, row = np.round(xy[:, 0]).astype(int), np.round(h - 1 - xy[:, 1]).astype(int)
    keep = (col >= 0) & (col < w) & (row >= 0) & (row < h)
    return background[row[keep], col[keep]]


def _box(background: np.ndarray, bbox) -> np.ndarray:
    h, w = background.shape[:2]
    x0, x1 = int(max(0, np.floor(bbox.x0))), int(min(w, np.ceil(bbox.x1)))
    r0, r1 = int(max(0, np.floor(h - bbox.y1))), int(min(h, np.ceil(h - bbox.y0)))
    return background[r0:r1, x0:x1].reshape(-1, 3)


def _passes(ratios: np.ndarray, need: float) -> tuple[bool, float]:
    if len(ratios) == 0:
        return True, float("inf")
    low = float(np.quantile(ratios, 1 - SHARE))
    return low >= need - 1e-9, low


def _name(artist) -> str:
    label = artist.get_label() if hasattr(artist, "get_label") else ""
    text = artist.get_text() if isinstance(artist, Text) else ""
    return f"{type(artist).__name__} {text or label or ''!r}"[:70]


def _colour_name(artist) -> str:
    if isinstance(artist, (Text, Line2D)):
        return to_hex(artist.get_color())
    colours = artist.get_colors() if isinstance(artist, LineCollection) else artist.get_facecolors()
    return to_hex(colours[0]) if len(colours) else "none"


def not_information(fig) -> dict[int, str]:
    """Artists of ``fig`` left out of the check (by ``id``), each with the reason."""
    reasons: dict[int, str] = {}
    for ax in fig.axes:
        for axis in ax._axis_map.values():
            for tick in axis.majorTicks + axis.minorTicks:
                reasons[id(tick.gridline)] = GRID
                for mark in (tick.tick1line, tick.tick2line):
                    reasons[id(mark)] = (
                        "tick marks: black, on the black frame they cross (sampled as their background)"
                    )
            if getattr(axis, "gridlines", None) is not None:  # a 3-D axis
                reasons[id(axis.gridlines)] = GRID
                reasons[id(axis.line)] = (
                    "3-D axis lines: the edges of the box, a frame like a 2-D axes' spines"
                )
    return reasons


def _text_check(text: Text, background: np.ndarray, renderer, dpi: float):
    if not text.get_text().strip():
        return None
    bbox = text.get_window_extent(renderer)
    if bbox.width < 1 or bbox.height < 1:
        return None
    bg = _halo(text, _box(background, bbox))  # a text's own box stays in the background
    px = text.get_fontsize() * dpi / 72
    bold = str(text.get_fontweight()) in ("bold", "heavy", "black", "semibold", "demibold") or (
        isinstance(text.get_fontweight(), (int, float)) and text.get_fontweight() >= 600
    )
    need = LARGE_TEXT if px >= 24 or (bold and px >= 18.66) else TEXT
    fg = drawn_over(_alpha(text, to_rgba(text.get_color())), bg)
    return need, contrast(fg, bg)


def _line_points(line: Line2D) -> np.ndarray:
    xy = (
        line.get_transform().transform(line.get_path().vertices)
        if len(line.get_xydata())
        else np.empty((0, 2))
    )
    return xy


def _line_check(line: Line2D, background: np.ndarray):
    pts = _line_points(line)
    drawn = line.get_linestyle() not in ("None", "none", "", " ") and line.get_linewidth() > 0
    if len(pts) == 0:
        return None
    ratios = []
    if drawn and len(pts) > 1:
        bg = _halo(line, _sample(background, _along(pts)))
        ratios.append(contrast(drawn_over(_alpha(line, to_rgba(line.get_color())), bg), bg))
    if line.get_marker() not in (None, "None", "none", "", " "):
        bg = _halo(line, _sample(background, pts))
        face, edge = to_rgba(line.get_markerfacecolor()), to_rgba(line.get_markeredgecolor())
        best = np.maximum(
            contrast(drawn_over(_alpha(line, face), bg), bg) if face[3] > 0 else 0,
            contrast(drawn_over(_alpha(line, edge), bg), bg)
            if edge[3] > 0 and line.get_markeredgewidth() > 0
            else 0,
        )
        ratios.append(np.broadcast_to(best, (len(bg),)))
    if not ratios:
        return None
    return GRAPHICS, np.concatenate(ratios)


def _collection_check(coll, background: np.ndarray):
    ratios = []
    if isinstance(coll, LineCollection):
        colours = to_rgba_array(coll.get_colors())
        if np.max(coll.get_linewidth()) <= 0 or len(colours) == 0:
            return None
        for i, seg in enumerate(coll.get_segments()):
            if len(seg) < 2:
                continue
            bg = _halo(coll, _sample(background, _along(coll.get_transform().transform(seg))))
            ratios.append(
                contrast(drawn_over(colours[i % len(colours)], bg), bg)
            )  # alpha is in the colours
    else:  # markers of a scatter plot: at their offsets, face or edge
        offsets = coll.get_offset_transform().transform(coll.get_offsets())
        faces, edges = to_rgba_array(coll.get_facecolors()), to_rgba_array(coll.get_edgecolors())
        widths = coll.get_linewidths()
        for i, p in enumerate(offsets):
            bg = _halo(coll, _sample(background, p[None]))
            best = np.zeros(len(bg))
            if len(faces) and faces[i % len(faces)][3] > 0:
                best = np.maximum(best, contrast(drawn_over(faces[i % len(faces)], bg), bg))
            if len(edges) and edges[i % len(edges)][3] > 0 and widths[i % len(widths)] > 0:
                best = np.maximum(best, contrast(drawn_over(edges[i % len(edges)], bg), bg))
            ratios.append(best)
    if not ratios:
        return None
    return GRAPHICS, np.concatenate(ratios)


def _drawn_artists(fig) -> list:
    """Texts, lines and collections that a full draw of ``fig`` actually draws (visible, on a shown axis...)."""
    drawn: dict[int, object] = {}

    def recording(method):
        def draw(self, renderer, *args, **kwargs):
            if self.get_visible() and self.figure is fig:
                drawn[id(self)] = self
            return method(self, renderer, *args, **kwargs)

        return draw

    with (
        mock.patch.object(Text, "draw", recording(Text.draw)),
        mock.patch.object(Line2D, "draw", recording(Line2D.draw)),
        mock.patch.object(Collection, "draw", recording(Collection.draw)),
    ):
        fig.canvas.draw()
    return [
        a for a in drawn.values() if isinstance(a, (Text, Line2D, LineCollection, PathCollection))
    ]


def check_figure(fig, animated=()) -> tuple[list[str], int, dict[str, int]]:
    """Draw ``fig``; return (every text or line below its ratio, how many were checked, how many left out by reason).

    ``animated`` artists (a FigureView blits them) are drawn like the rest for this check.
    """
    for artist in animated:
        artist.set_animated(False)
    canvas = fig.canvas
    artists = _drawn_artists(fig)
    renderer = canvas.get_renderer()
    left_out: dict[str, int] = {}
    checked_here = []
    reasons = not_information(fig)
    for a in artists:
        reason = reasons.get(id(a)) or MARKED.get(a.get_gid())
        if reason:
            left_out[reason] = left_out.get(reason, 0) + 1
        else:
            checked_here.append(a)
    # The background: the same figure with every text, line and marker transparent (so legends
    # and text boxes keep their size and stay in the picture).
    alphas = [(a, a.get_alpha()) for a in artists]
    for a in artists:
        a.set_alpha(0.0)
    canvas.draw()
    background = np.asarray(canvas.buffer_rgba())[..., :3].astype(float) / 255
    for a, alpha in alphas:
        a.set_alpha(alpha)
    canvas.draw()  # back as it was (3-D lines re-projected)
    failures, checked = [], 0
    for a in checked_here:
        if isinstance(a, Text):
            result = _text_check(a, background, renderer, fig.dpi)
        elif isinstance(a, Line2D):
            result = _line_check(a, background)
        else:
            result = _collection_check(a, background)
        if result is None:
            continue
        need, ratios = result
        ok, low = _passes(np.asarray(ratios, dtype=float).ravel(), need)
        checked += 1
        if not ok:
            failures.append(f"{_name(a)} {_colour_name(a)}: {low:.2f}:1 < {need}:1")
    return failures, checked, left_out


def test_the_check_can_fail():
    """matplotlib's orange fails as a line on white; the palette's passes; a halo rescues a line on black."""
    import matplotlib
    from matplotlib.figure import Figure

    from camlab.plotting import palette

    assert contrast(np.array([0.0, 0, 0]), np.array([1.0, 1, 1])) == pytest.approx(21.0)
    matplotlib.use("agg")
    fig = Figure(figsize=(3, 2), dpi=90)
    ax = fig.subplots()
    ax.plot([0, 1], [0, 1], color="tab:orange", label="tab:orange")
    ax.plot([0, 1], [1, 0], color=palette.ORANGE, label="palette orange")
    ax.imshow(np.zeros((4, 4)), cmap="gray", vmin=0, vmax=1, extent=(0.6, 1.0, 0.6, 1.0))
    ax.plot(
        [0.6, 1.0], [0.7, 0.7], color=palette.BLUE, path_effects=palette.halo(1.5)
    )  # on the black image
    ax.text(0.1, 0.5, "faint", color="0.75")
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    FigureCanvasAgg(fig)
    failures, checked, _ = check_figure(fig)
    assert sorted(f.split(" ")[1] for f in failures) == ["'faint'", "'tab:orange'"], failures
    assert checked >= 4 + 4  # three lines and a text, plus the tick labels


PERCEPTUAL = {"viridis", "cividis", "magma", "inferno", "plasma"}
SIGNED = {
    "coolwarm"
}  # diverging, for signed values (an error): blue and red stay apart for every vision
PHOTO = {
    "gray",
    "Greys",
    "Greys_r",
    "binary",
}  # a greyscale photo or rendering: an image, not a value map


def value_image_problems(fig) -> list[str]:
    """Value images (2-D data shown through a colour map) must use a uniform map and have a colour bar."""
    problems = []
    for ax in fig.axes:
        for im in ax.get_images():
            if not isinstance(im, AxesImage) or im.get_array() is None or im.get_array().ndim != 2:
                continue  # colour pictures are shown as they are
            cmap = im.cmap.name
            if cmap in PHOTO:
                continue
            if cmap not in PERCEPTUAL | SIGNED:
                problems.append(
                    f"'{ax.get_title()}' uses {cmap}: use viridis or cividis (coolwarm for signed values)"
                )
            if im.colorbar is None:
                problems.append(f"'{ax.get_title()}' ({cmap}) has no colour bar")
    return problems


@pytest.mark.parametrize("name", sorted(DEMOS))
def test_demo_text_lines_and_value_images_are_readable(name):
    demo = DEMOS[name].builder()
    images = value_image_problems(demo.figure)
    failures, checked, left_out = check_figure(demo.figure, demo.view._animated)
    print(
        f"{name}: {checked} texts and lines checked, {sum(left_out.values())} left out "
        + "; ".join(f"{n} {reason.split(':')[0]}" for reason, n in left_out.items())
    )
    assert not failures, f"{name}: below WCAG contrast at its defaults:\n" + "\n".join(failures)
    assert not images, f"{name}: " + "; ".join(images)
