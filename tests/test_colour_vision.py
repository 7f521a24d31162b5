"""Colour-vision safety of every demo: legend entries told apart only by colour stay apart.

For each registered demo at its default settings and at the extremes of its sweep, every
pair of legend entries in one axes that share line style, marker and hatch (so only
colour tells them apart) must differ by CIE76 delta-E >= 12 in normal vision and for
full-severity protanopes, deuteranopes and tritanopes, simulated with the matrices of
Machado, Oliveira & Fernandes (2009) applied in linear RGB. Entries with different line
styles or markers pass on their shape. No rendering is needed: the test reads the
artists the demo's update has just set.

References
----------
G. M. Machado, M. M. Oliveira, L. A. F. Fernandes, "A Physiologically-based Model for
Simulation of Color Vision Deficiency", IEEE TVCG 15(6), 2009 (severity 1.0 matrices).
"""

import itertools

import numpy as np
import pytest
from matplotlib.colors import to_rgba
from matplotlib.lines import Line2D

from camlab.widgets import all_demos

DEMOS = all_demos()
MIN_DELTA_E = 12.0
MACHADO = {
    "protanopia": np.array(
        [
            [0.152286, 1.052583, -0.204868],
            [0.114503, 0.786281, 0.099216],
            [-0.003882, -0.048116, 1.051998],
        ]
    ),
    "deuteranopia": np.array(
        [
            [0.367322, 0.860646, -0.227968],
            [0.280085, 0.672501, 0.047413],
            [-0.011820, 0.042940, 0.968881],
        ]
    ),
    "tritanopia": np.array(
        [
            [1.255528, -0.076749, -0.178779],
            [-0.078411, 0.930809, 0.147602],
            [0.004733, 0.691367, 0.303900],
        ]
    ),
}
VISIONS = {"normal": np.eye(3), **MACHADO}


def _linear(srgb: np.ndarray) -> np.ndarray:
    return np.where(srgb <= 0.04045, srgb / 12.92, ((srgb + 0.055) / 1.055) ** 2.4)


def lab(rgb_linear: np.ndarray) -> np.ndarray:
    """CIELAB (D65) of linear sRGB colours (..., 3)."""
    xyz = (
        np.clip(rgb_linear, 0, 1)
        @ np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]]).T
    )
    t = xyz / np.array([0.95047, 1.0, 1.08883])
    f = np.where(t > (6 / 29) ** 3, np.cbrt(t), t / (3 * (6 / 29) ** 2) + 4 / 29)
    return np.stack(
        [116 * f[..., 1] - 16, 500 * (f[..., 0] - f[..., 1]), 200 * (f[..., 1] - f[..., 2])], -1
    )


def delta_e(c1, c2, vision: str) -> float:
    """CIE76 distance of two colours (drawn over white) as seen with ``vision``."""

    def seen(c):
        r, g, b, a = to_rgba(c)
        over_white = a * np.array([r, g, b]) + (1 - a)
        return lab(VISIONS[vision] @ _linear(over_white))

    return float(np.linalg.norm(seen(c1) - seen(c2)))


def _style(handle) -> tuple:
    """What tells a legend entry apart besides colour: dash pattern, marker and its fill, hatch."""
    if isinstance(handle, Line2D):
        drawn = handle.get_linestyle() not in ("None", "none", " ", "")
        # The effective dash pattern (a legend handle for a solid LineCollection reports '--').
        dashes = getattr(handle, "_unscaled_dash_pattern", (0, handle.get_linestyle()))[1]
        line = str(tuple(dashes) if dashes is not None else "solid") if drawn else "no line"
        hollow = str(handle.get_markerfacecolor()).lower() == "none"
        return line, str(handle.get_marker()), hollow, None
    hatch = handle.get_hatch() if hasattr(handle, "get_hatch") else None
    # An outline's dash pattern tells two unfilled patches apart as a line's does.
    dashes = getattr(handle, "_unscaled_dash_pattern", (0, None))[1]
    outline = str(tuple(dashes)) if dashes is not None else "solid"
    return "patch", type(handle).__name__, outline, hatch


def _colour(handle):
    for getter in ("get_color", "get_facecolor", "get_edgecolor"):
        if hasattr(handle, getter):
            c = getattr(handle, getter)()
            if isinstance(c, np.ndarray) and c.ndim == 2:
                c = c[0] if len(c) else None
            transparent = not isinstance(c, str) and c is not None and len(c) == 4 and c[3] == 0
            if c is not None and not (isinstance(c, str) and c == "none") and not transparent:
                return c
    return None


def colour_only_pairs(fig) -> list[tuple[str, str, object, object]]:
    """Pairs of legend entries in one axes that only colour tells apart."""
    pairs = []
    for ax in fig.axes:
        legend = ax.get_legend()
        if legend is None or not legend.get_visible():
            continue
        entries = [
            (t.get_text(), h)
            for t, h in zip(legend.get_texts(), legend.legend_handles, strict=True)
            if h is not None
        ]
        for (name1, h1), (name2, h2) in itertools.combinations(entries, 2):
            if _style(h1) == _style(h2):
                pairs.append((name1, name2, _colour(h1), _colour(h2)))
    return pairs


def settings(spec) -> list[dict]:
    """The default settings (empty dict) and each sweep control at its extreme values."""
    out = [{}]
    for control, values in spec.sweep.items():
        try:
            ends = [min(values), max(values)]
        except TypeError:  # categorical values: every one is an extreme
            ends = list(values)
        out += [{control: v} for v in dict.fromkeys(ends)]
    return out


def test_simulation_matches_known_confusions():
    """Red and green collapse for a deuteranope; blue and green do not; white stays white."""
    assert delta_e("tab:red", "tab:green", "normal") > 40
    assert (
        delta_e("#ff0000", "#00a000", "deuteranopia") < delta_e("#ff0000", "#00a000", "normal") / 2
    )
    assert delta_e("tab:blue", "tab:orange", "deuteranopia") > 30
    for m in MACHADO.values():
        assert np.allclose(m.sum(axis=1), 1.0, atol=1e-5)


def test_outlines_are_told_apart_by_dashes_and_compared_by_edge_colour():
    """Two unfilled squares: the same dashes make a colour-only pair (compared by edge colour, not
    the transparent face); a dashed outline beside a solid one is told apart by its shape."""
    from matplotlib.figure import Figure
    from matplotlib.patches import Rectangle

    fig = Figure()
    ax = fig.subplots()
    ax.add_patch(Rectangle((0, 0), 1, 1, fill=False, ec="tab:red", label="a"))
    ax.add_patch(Rectangle((0, 0), 1, 1, fill=False, ec="tab:green", label="b"))
    ax.add_patch(Rectangle((0, 0), 1, 1, fill=False, ec="tab:purple", ls="--", label="c"))
    ax.legend()
    pairs = colour_only_pairs(fig)
    assert [(a, b) for a, b, *_ in pairs] == [("a", "b")]
    _, _, c1, c2 = pairs[0]
    assert delta_e(c1, c2, "normal") > 40  # the edges' red and green, not two transparent faces


@pytest.mark.parametrize("name", sorted(DEMOS))
def test_demo_legends_survive_colour_vision_deficiency(name):
    spec = DEMOS[name]
    demo = spec.builder()
    defaults = {k: c.value for k, c in demo.controls.items()}
    failures = []
    for setting in settings(spec):
        demo.set(**defaults)
        demo.set(**setting)
        for label1, label2, c1, c2 in colour_only_pairs(demo.figure):
            for vision in VISIONS:
                d = delta_e(c1, c2, vision)
                if d < MIN_DELTA_E:
                    failures.append(
                        f"{setting or 'defaults'}: '{label1}' vs '{label2}' delta-E {d:.1f} ({vision})"
                    )
    assert not failures, f"{name}: legend entries told apart only by colour merge:\n" + "\n".join(
        sorted(set(failures))
    )


def test_palette_series_stays_apart_for_every_vision():
    from camlab.plotting import palette

    for c1, c2 in itertools.combinations(palette.SERIES, 2):
        for vision in VISIONS:
            assert delta_e(c1, c2, vision) >= MIN_DELTA_E, f"{c1} vs {c2} merge for {vision}"


def test_every_camera_frame_has_one_colour_code():
    """x red, y green, z blue (palette.AXIS_COLOURS) in lesson 00's camera frame, lesson 04's 3-D
    cameras and world axes, and the camera_explorer/opencv_vs_opengl demos: one code for the course,
    and colours that stay apart for every vision (the tab: colours did not, red against green)."""
    import matplotlib.pyplot as plt

    from camlab import camera as cm
    from camlab.plotting import conventions, palette, scene3d

    def axis_colours(texts) -> dict[str, str]:
        return {
            t.get_text().split(",")[0].strip().lower(): to_rgba(t.get_color())
            for t in texts
            if t.get_text().split(",")[0].strip().lower() in ("x", "y", "z")
        }

    want = {name: to_rgba(c) for name, c in zip("xyz", palette.AXIS_COLOURS, strict=True)}
    fig = plt.figure()
    ax2 = fig.add_subplot(1, 2, 1)
    conventions.draw_camera_frame(ax2)
    frame = axis_colours(ax2.texts)  # "x, right", "y, down", "z, forward: into the page ..."
    ax3 = scene3d.axes3d(fig, 1, 2, 2)
    world = scene3d.draw_world_axes(ax3)
    camera = scene3d.CameraArtist(ax3, cm.Camera.look_at([2.0, -2.0, 1.0], [0.0, 0.0, 0.0]))
    plt.close(fig)
    assert frame == want
    assert axis_colours(camera.axes_text) == want
    assert axis_colours([a for a in world if hasattr(a, "get_text")]) == want
    for c1, c2 in itertools.combinations(palette.AXIS_COLOURS, 2):
        for vision in VISIONS:
            assert delta_e(c1, c2, vision) >= MIN_DELTA_E, f"{c1} vs {c2} merge for {vision}"
