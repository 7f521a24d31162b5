"""Demos for lesson 01, the pinhole camera."""

from __future__ import annotations

from types import SimpleNamespace

import ipywidgets as W
import numpy as np

from .. import fixtures, pinhole, render, scenes, sensor
from ..plotting import images, optics, palette
from ..scenes.planes import CHART_ROW_HEIGHTS
from ._base import FigureView, build_demo, register, slider
from .browser import BrowserView
from .browser.pinhole_scenes import pinhole_projection_scene
from .browser.scenes import similar_triangles_scene
from .controls import monospace

SIZE = (320, 240)
PITCH = 36e-3 / SIZE[0]  # a 36 mm wide sensor with 320 pixels: 112.5 um pixels
SENSOR = (SIZE[0] * PITCH, SIZE[1] * PITCH)  # its width and height, metres (36 mm x 27 mm)
# The 3-D view draws the image planes PLANE_SCALE f from the pinhole, so they move out as f grows, but
# never more than PLANE_ROOM of the way to the box's nearest corner nor beyond PLANE_MAX (the view's
# near end holds the real plane). Each plane's frame is the sensor as seen from the pinhole at that
# distance, w f_draw / f wide: it frames the picture as the sensor frames the image beside it, and
# narrows around the picture as f grows (the field of view) even where the planes stop moving.
PLANE_SCALE = 12.0
PLANE_ROOM = 0.5
PLANE_MAX = 1.2
DEPTH_RANGE = (
    -1.3,
    4.5,
)  # the 3-D view's z limits (metres): the real plane at PLANE_MAX to the box at 4 m
SIDE_RANGE = 0.3  # ...and its x and y half-range


def plane_distance(f: float, box_nearest_z: float) -> float:
    """Where the 3-D view draws the image planes, metres from the pinhole.

    For focal length ``f`` and a box whose nearest corner is ``box_nearest_z`` metres away
    (see PLANE_SCALE).

    Parameters
    ----------
    f : float
        The focal length (m).
    box_nearest_z : float
        The depth of the box's nearest corner (m).

    Returns
    -------
    float
        The planes' distance from the pinhole (m): ``PLANE_SCALE`` f, but at most ``PLANE_ROOM``
        of the way to the box and at most ``PLANE_MAX``.
    """
    return min(PLANE_SCALE * f, PLANE_ROOM * box_nearest_z, PLANE_MAX)


def _box_outline(faces) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray]]:
    """The box's (24, 2, 3) edge segments and (faces (6, 4, 3), mean greys (6,)) for the 3-D view."""
    return scenes.plane_outlines(faces), optics.plane_faces(faces)


def _bar_ends(u_min: float, u_max: float, width: int) -> tuple[list, list]:
    """The width bar clipped to the image, and the end marks that fall inside it (a clipped end has none)."""
    lo, hi = -0.5, width - 0.5
    ends = [u for u in (u_min, u_max) if lo <= u <= hi]
    return [max(u_min, lo), min(u_max, hi)], ends


def _projection_controls() -> dict:
    """The controls of :func:`pinhole_projection`.

    The focal length, the box's distance and which image plane the image shows.
    """
    return {
        "focal_mm": slider(50, 15, 100, 1, "focal length f (mm)", readout_format=".0f"),
        "distance": slider(2.0, 0.8, 4.0, 0.1, "box distance Z (m)"),
        "real_plane": W.Checkbox(
            value=False, description="show the real image (rotated 180 degrees)"
        ),
    }


def _projection_figure(view: FigureView) -> SimpleNamespace:
    """The figure of :func:`pinhole_projection`.

    The box, the pinhole and both image planes in 3-D (depth squeezed by ``squeeze``) beside the
    recorded image with the box's width bar; returns its artists by name.
    """
    # placed by hand: the layout engine does not see the 3-D axis labels
    view.fig.set_layout_engine("none")
    ax3 = view.fig.add_axes((0.1, 0.03, 0.53, 0.84), projection="3d")
    ax_img = view.fig.add_axes((0.685, 0.43, 0.3, 0.42))  # room right for the "319" tick label
    # under it, the two planes' pictures of the 3-D view at a readable size, seen from behind as there
    planes = {}
    for name, x0, colour, title in (
        ("virtual", 0.655, palette.GREEN, "green plane (virtual):\nupright"),
        ("real", 0.825, palette.RED, "red plane (real), from\nbehind: rotated 180 deg"),
    ):
        ax = view.fig.add_axes((x0, 0.035, 0.155, 0.24))
        planes[name] = images.show_image(ax, np.zeros(SIZE[::-1]), vmax=1.0)
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_title(title, fontsize=8, color=colour, pad=3)
        for spine in ax.spines.values():
            spine.set_color(colour)
            spine.set_linewidth(2.5)
    edges, faces = _box_outline(fixtures.box_before_wall(2.0)[0])
    art = optics.draw_pinhole_3d(ax3, edges, 0.6, faces=faces)
    ax3.set_xlim(*DEPTH_RANGE)
    ax3.set_ylim(-SIDE_RANGE, SIDE_RANGE)
    ax3.set_zlim(-SIDE_RANGE, SIDE_RANGE)
    ax3.set_box_aspect((2.6, 1, 1), zoom=1.25)
    optics.label_camera_axes(ax3, labelpad=1)
    ax3.xaxis.labelpad = 8  # clear of the depth axis' tick labels
    # x, y per metre against z per metre
    squeeze = optics.axis_scales(ax3)[1] / optics.axis_scales(ax3)[0]
    im = images.show_image(ax_img, np.zeros(SIZE[::-1]), vmax=1.0)
    # pixels, as the title counts; the middle ticks on the principal point ((W - 1) / 2, (H - 1) / 2)
    ax_img.set_xticks(
        [0, (SIZE[0] - 1) / 2, SIZE[0] - 1], ["0", f"{(SIZE[0] - 1) / 2:g}", f"{SIZE[0] - 1}"]
    )
    ax_img.set_yticks(
        [0, (SIZE[1] - 1) / 2, SIZE[1] - 1], ["0", f"{(SIZE[1] - 1) / 2:g}", f"{SIZE[1] - 1}"]
    )
    ax_img.tick_params(labelsize=8, length=2, pad=1)
    ax_img.set_xlabel("u (px)", fontsize=8.5, labelpad=1)
    ax_img.set_ylabel("v (px)", fontsize=8.5, labelpad=3)  # clear of the "119.5" tick label
    width_bar = ax_img.plot([], [], color="k", lw=2, path_effects=palette.halo(2))[0]
    bar_ends = ax_img.plot(
        [], [], ls="none", color="k", marker="|", ms=10, mew=2, path_effects=palette.halo(2)
    )[0]
    view.fig.text(
        0.01,
        0.985,
        f"not to scale: depth z drawn {squeeze:.1f} x shorter than x and y",
        fontsize=8.5,
        va="top",
    )
    # for readers of the static picture too; an axes' child, since a saved figure leaves out animated figure texts
    scale_note = ax_img.text(
        0.01, 0.935, "", transform=view.fig.transFigure, fontsize=8.5, va="top", clip_on=False
    )
    # everything that moves is blitted over the cached static figure (the pinhole too: a ray passes over it)
    view.animate(
        im,
        *planes.values(),
        width_bar,
        bar_ends,
        ax_img.title,
        scale_note,
        art["box"],
        art["rays"],
        art["real"],
        art["virtual"],
        art["pinhole"],
        *art["planes"].values(),
        *art["fills"].values(),
    )
    return SimpleNamespace(
        art=art,
        ax3=ax3,
        ax_img=ax_img,
        im=im,
        planes=planes,
        width_bar=width_bar,
        bar_ends=bar_ends,
        scale_note=scale_note,
        squeeze=squeeze,
    )


@register(
    lesson="01",
    sweep={"focal_mm": [15, 50, 100], "distance": [0.8, 2.0, 4.0], "real_plane": [True, False]},
)
def pinhole_projection():
    """A box, the pinhole and both image planes in 3-D beside the image the camera records.

    Returns
    -------
    Demo
        The demo: controls ``focal_mm`` (f, mm), ``distance`` (the box's depth Z, m) and
        ``real_plane`` (show the real, rotated image instead of the virtual one), the figure
        and ``state`` (``K``, ``fx`` in px, ``box_width_px``, ``image``, ``centre`` the image
        of the point (0, 0, Z), ``fov_deg``, ``plane``, ``f_draw`` in m, ``draw_scale``,
        ``depth_squeeze``, ``bar_clipped``).
    """
    controls = _projection_controls()
    view = BrowserView(
        ("focal_mm", "distance", "real_plane"), figsize=(8.8, 4.8), flags=("real_plane",)
    )
    parts = _projection_figure(view)
    art, ax_img, im, squeeze = parts.art, parts.ax_img, parts.im, parts.squeeze
    width_bar, bar_ends, scale_note = parts.width_bar, parts.bar_ends, parts.scale_note
    readout = W.HTML()  # numbers beside the sliders: canvas text costs ~4 ms per line per redraw

    def update(values, state):
        f = values["focal_mm"] * 1e-3
        Z = values["distance"]
        scene = fixtures.box_before_wall(Z)
        e, faces = _box_outline(scene[0])
        corners = np.unique(e.reshape(-1, 3), axis=0)
        f_draw = plane_distance(f, corners[:, 2].min())
        scale = f_draw / f
        # the planes drawn as the sensor's frame
        optics.update_pinhole_3d(art, e, f_draw, faces, plane_half=scale * SENSOR[0] / 2)
        K = sensor.intrinsics_from_sensor(f, (PITCH, PITCH), SIZE)
        img = render.render(scene, K, SIZE).irradiance
        parts.planes["virtual"].set_data(img)
        # the real plane seen from behind: rotated 180 degrees
        parts.planes["real"].set_data(img[::-1, ::-1])
        u = K[0, 0] * corners[:, 0] / corners[:, 2] + K[0, 2]  # the corners' columns, x = f X / Z
        v_bar = 0.92 * SIZE[1]
        if values["real_plane"]:
            img = img[::-1, ::-1]  # the real image in the camera's axes: rotated 180 degrees
            u = SIZE[0] - 1 - u
        im.set_data(img)
        bar, ends = _bar_ends(u.min(), u.max(), SIZE[0])
        width_bar.set_data(bar, [v_bar, v_bar])
        bar_ends.set_data(ends, [v_bar] * len(ends))
        centre = pinhole.project_pinhole([0.0, 0.0, Z], f)
        fov = np.degrees(
            2 * np.arctan(SENSOR[0] / (2 * f))
        )  # the sensor's width w from the pinhole
        span = float(u.max() - u.min())
        state.update(
            K=K,
            fx=K[0, 0],
            box_width_px=span,
            image=img,
            centre=centre,
            fov_deg=fov,
            plane="real" if values["real_plane"] else "virtual",
            f_draw=f_draw,
            draw_scale=scale,
            depth_squeeze=squeeze,
            bar_clipped=len(ends) < 2,
        )
        ax_img.set_title(
            ("real image (rotated 180 deg)" if values["real_plane"] else "virtual image (upright)")
            + f"\nfield of view {fov:.1f} deg; box {span:.0f} px wide",
            fontsize=9,
        )
        scale_note.set_text(
            f"image planes at {scale:.1f} f from the pinhole (black dot),"
            f" their sensor frames {scale:.1f} x enlarged"
        )
        readout.value = _projection_readout(K[0, 0], fov, span, scale)

    demo = build_demo(
        "pinhole_projection",
        controls,
        view,
        update,
        title="Pinhole projection x = f X / Z",
        extra=[readout],
    )
    _publish_pinhole_scene(view, demo, parts)
    return demo


def _projection_readout(fx: float, fov: float, span: float, scale: float) -> str:
    """The numbers beside :func:`pinhole_projection`'s sliders (fx px, field of view deg, box px, 3-D scale)."""
    wider = f", wider than the image ({SIZE[0]} px)" if span > SIZE[0] else ""
    return monospace(
        f"fx = f / pixel pitch = {fx:.0f} px\n"
        f"field of view 2 atan(w / 2f) = {fov:.1f} deg (w = 36 mm)\n"
        f"box spans {span:.0f} px (the bar under the box){wider}\n"
        f"3-D view: image planes at {scale:.1f} f, sensor frames {scale:.1f} x enlarged\n"
        f"wall of 1 m squares at {fixtures.WALL_DISTANCE:g} m (beyond the 3-D view)"
    )


def _publish_pinhole_scene(view, demo, parts) -> None:
    """Send :func:`pinhole_projection`'s scene to the browser once.

    The browser draws the moves: the 3-D view from optics.pinhole_view's twin, the image rendered
    from the same textured planes as camlab.render.render renders it.
    """
    faces, wall = fixtures.box_before_wall(1.0)  # the browser moves the box from 1 m to Z
    view.publish(
        demo,
        pinhole_projection_scene(
            parts,
            dict(
                faces=faces,
                boxDistance=1.0,
                wall=wall,
                size=SIZE,
                pitch=PITCH,
                sensor=SENSOR,
                planeScale=PLANE_SCALE,
                planeRoom=PLANE_ROOM,
                planeMax=PLANE_MAX,
                barRow=0.92 * SIZE[1],
            ),
        ),
    )


def _signed(x: float, digits: int) -> str:
    """``x`` with its sign, "+0.133" or "-0.267", and a plain "0.000" where it rounds to zero (never "-0.000")."""
    return f"{x:+.{digits}f}" if round(x, digits) != 0 else f"{0:.{digits}f}"


def ratios_title(f: float, Z: float, Y: float) -> str:
    """The title over :func:`similar_triangles`: y / f and Y / Z, with their numbers, equal.

    The browser's twin is ``ratiosTitle`` in ``widgets/browser/geometry.js``.

    Parameters
    ----------
    f : float
        Focal length, metres.
    Z : float
        The object point's depth, metres.
    Y : float
        The object point's camera y, metres (y down).

    Returns
    -------
    str
        Two lines: the ratios, and how to move the object point.
    """
    y = f * Y / Z
    return (
        f"y / f = {_signed(y * 100, 1)} cm / {f * 100:.0f} cm = {_signed(y / f, 3)}   and   Y / Z ="
        f" {_signed(Y, 2)} m / {Z:.2f} m = {_signed(Y / Z, 3)}\nclick or drag in the figure to move the object"
        " point"
    )


@register(lesson="01", sweep={"f": [0.3, 1.0], "Z": [1.2, 5.0], "Y": [-1.0, 0.0, 0.4, 1.0]})
def similar_triangles():
    """A side view of a room-sized camera obscura: drag the object point and read y / f = Y / Z off the triangles.

    Returns
    -------
    Demo
        The demo: controls ``f`` (the focal length, m), ``Z`` (the object's depth, m) and ``Y``
        (its height, m, y down), the side view (a click or drag moves the object point) and
        ``state`` (``y`` the image height in m, ``ratio_image`` y / f, ``ratio_object`` Y / Z).
    """
    controls = {
        "f": slider(0.8, 0.3, 1.0, 0.05, "focal length f (m)"),
        "Z": slider(3.0, 1.2, 5.0, 0.05, "object depth Z (m)"),
        "Y": slider(-0.8, -1.0, 1.0, 0.05, "object Y (m; y points down)"),
    }
    view = BrowserView(("f", "Z", "Y"), figsize=(8.8, 4))
    ax = view.fig.subplots()
    art = optics.draw_similar_triangles(ax, z_max=5.6, h_max=1.3)
    ax.set_title(
        " \n ", fontsize=9
    )  # the two ratios, set by update: the lesson's equality in the picture itself
    readout = W.HTML()  # beside the sliders, where it never covers the object point
    movers = [ax.title] + [
        art[k]
        for k in (
            "big",
            "small",
            "object",
            "point",
            "ray",
            "planes",
            "virtual",
            "real",
            "pinhole",
            "pinhole_dot",
        )
    ]
    for dim in art["dims"].values():
        movers += [dim["arrow"], dim["label"]]
    view.animate(*movers)

    def update(values, state):
        f, Z, Y = values["f"], values["Z"], values["Y"]
        y = optics.update_similar_triangles(art, f, Z, Y)
        state.update(y=y, ratio_image=y / f, ratio_object=Y / Z)
        ax.set_title(ratios_title(f, Z, Y), fontsize=9)
        readout.value = monospace(
            f"y / f = {_signed(y / f, 3)}\nY / Z = {_signed(Y / Z, 3)}\n=> y = f Y / Z = {_signed(y * 100, 1)} cm"
        )

    demo = build_demo(
        "similar_triangles",
        controls,
        view,
        update,
        title="Similar triangles: y / f = Y / Z",
        extra=[readout],
    )

    def on_mouse(event):
        if event.inaxes is ax and event.button == 1 and event.xdata is not None:
            z = float(np.clip(event.xdata, controls["Z"].min, controls["Z"].max))
            y = float(
                np.clip(-event.ydata, controls["Y"].min, controls["Y"].max)
            )  # the plot shows -y (up)
            demo.set(Z=round(z / 0.05) * 0.05, Y=round(y / 0.05) * 0.05)

    view.fig.canvas.mpl_connect("button_press_event", on_mouse)
    view.fig.canvas.mpl_connect("motion_notify_event", on_mouse)
    # the browser draws the moves, and a click or drag there sets Z and Y as on_mouse does
    view.publish(demo, similar_triangles_scene(ax, art, controls))
    return demo


PAGE_Z = 1.0  # the chart's distance in pinhole_size (metres)
BALANCED = 0.05  # the readout calls the blur "balanced" while its two terms differ by under 5 % of the total
REFERENCE = (
    0.35e-3,
    0.1,
)  # the (d, f) whose exposure time "fixed exposure" keeps: the demo's default


# A chart row counts as legible while the blur passes at least LEGIBLE_CONTRAST of the contrast of every detail
# coarser than LEGIBLE_CYCLES cycles per letter height (no detail washed out or reversed), and, on the picture as
# shown, its pixels still span SHOWN_CONTRAST of black-to-white (a burnt-out or nearly black chart has no legible row).
# For a flat disc blur of diameter D the first rule reads "letters taller than 1.25 D" (2 J1(x)/x = 0.1 at x = 3.4,
# and 3.4 / (pi 1.35) = 0.80): the threshold set by eye on the demo's earlier flat-disc pictures (1.47 D read, 1.07 D not).
LEGIBLE_CYCLES = 1.35
LEGIBLE_CONTRAST = 0.1
SHOWN_CONTRAST = 0.15
WAVELENGTH = 550e-9  # green light, as section 3


def row_heights_px() -> np.ndarray:
    """Each chart row's letter height in the demo's pixels: the same at every f (40, 26, 17, 11 and 7 px).

    The rows are :data:`CHART_ROW_HEIGHTS` tall on a 0.3 m chart of 600 texels; the sensor spans the same
    field of view at every f (0.36 f wide, 320 pixels) with the chart at :data:`PAGE_Z`, so a row is
    H 0.3 / 600 x 320 / (0.36 PAGE_Z) pixels tall.

    Returns
    -------
    (5,) ndarray
        The letter heights in pixels, largest row first.
    """
    return np.array(CHART_ROW_HEIGHTS) * 0.3 / 600 * SIZE[0] / (0.36 * PAGE_Z)


def _row_bands() -> list[tuple[int, int]]:
    """The image rows (v, top to bottom) each chart row's letters occupy.

    As the chart texture lays them out: 600 x 500 texels, rows from texel 30 down, 1.6 row heights
    apart, centred in the image.
    """
    scale = 0.3 / 600 * SIZE[0] / (0.36 * PAGE_Z)  # pixels per texel
    bands, top = [], 30.0
    for cap in CHART_ROW_HEIGHTS:
        v0 = (SIZE[1] - 1) / 2 + (top - 250) * scale
        bands.append((int(np.floor(v0)), int(np.ceil(v0 + cap * scale)) + 1))
        top += 1.6 * cap
    return bands


def pinhole_mtf(rho: np.ndarray, d: float, f: float, pitch: float) -> np.ndarray:
    r"""The pinhole's transfer function (contrast passed) at spatial frequency ``rho`` cycles per pixel.

    The blur is the hole's geometric shadow, a disc of diameter :math:`D = d(1 + f/Z)` (Z = :data:`PAGE_Z`),
    convolved with the Airy pattern of a round hole of diameter d at distance f (Fraunhofer diffraction).
    A convolution multiplies transfer functions:

    * disc: :math:`2 J_1(\pi D \rho) / (\pi D \rho)` (negative between its zeros: contrast reversed);
    * Airy: :math:`\frac{2}{\pi}(\arccos s - s\sqrt{1 - s^2})`, :math:`s = \rho / \rho_c`, zero from the
      cut-off :math:`\rho_c = d / (\lambda f)` on (Hecht 11.3.3; its first dark ring, 2.44 / rho_c wide, is
      section 3's 2.44 lambda f / d).

    Parameters
    ----------
    rho : array_like
        Spatial frequencies, cycles per pixel (>= 0).
    d, f, pitch : float
        The hole's diameter, the focal length and the pixel pitch (m).

    Returns
    -------
    np.ndarray
        The transfer function, shaped like ``rho`` (1 at rho = 0).
    """
    from scipy.special import j1

    rho = np.asarray(rho, dtype=float)
    x = np.pi * d * (1 + f / PAGE_Z) / pitch * rho
    safe = np.where(x > 1e-9, x, 1.0)
    disc = np.where(x > 1e-9, 2 * j1(safe) / safe, 1.0)
    s = np.minimum(rho / (d * pitch / (WAVELENGTH * f)), 1.0)
    airy = 2 / np.pi * (np.arccos(s) - s * np.sqrt(1 - s * s))
    return disc * airy


def blur_through_pinhole(sharp: np.ndarray, d: float, f: float, pitch: float) -> np.ndarray:
    """The ``sharp`` picture as a hole ``d`` at ``f`` records it.

    Multiplied by :func:`pinhole_mtf` in Fourier space (a convolution with disc-plus-Airy), the
    edges mirrored 64 px out so nothing wraps round.

    Parameters
    ----------
    sharp : (H, W) ndarray
        The picture a perfect lens would give, values in [0, 1].
    d, f, pitch : float
        The hole's diameter, the focal length and the pixel pitch (m).

    Returns
    -------
    (H, W) ndarray
        The blurred picture, clipped to [0, 1].
    """
    pad = 64
    a = np.pad(sharp, pad, mode="reflect")
    rho = np.hypot(np.fft.fftfreq(a.shape[0])[:, None], np.fft.rfftfreq(a.shape[1])[None, :])
    out = np.fft.irfft2(np.fft.rfft2(a) * pinhole_mtf(rho, d, f, pitch), s=a.shape)
    return np.clip(out[pad:-pad, pad:-pad], 0.0, 1.0)


def legible_rows(d: float, f: float, shown: np.ndarray | None = None) -> int:
    """How many rows of the demo's letter chart are legible through a hole ``d`` at ``f`` (the readout's count).

    A row is legible while :func:`pinhole_mtf` stays over :data:`LEGIBLE_CONTRAST` at every frequency up to
    :data:`LEGIBLE_CYCLES` cycles per letter height (:func:`row_heights_px`); and, given the picture as
    ``shown`` (after the exposure), while its letters' pixels span at least :data:`SHOWN_CONTRAST` of
    black-to-white (1st to 99th percentile), so a burnt-out or nearly black chart counts no row.

    Parameters
    ----------
    d, f : float
        The hole's diameter and the focal length (m).
    shown : (240, 320) array or None
        The picture as displayed, in [0, 1]; None counts from the blur alone.

    Returns
    -------
    int
        The number of legible rows (rows legible from the top down: a smaller row never reads when a larger does not).
    """
    pitch = f * 0.36 / SIZE[0]
    count = 0
    for h, (v0, v1) in zip(row_heights_px(), _row_bands(), strict=True):
        sharp_enough = np.all(
            pinhole_mtf(np.linspace(0, LEGIBLE_CYCLES / h, 200), d, f, pitch) > LEGIBLE_CONTRAST
        )
        if shown is not None:
            lo, hi = np.percentile(shown[v0:v1, 40:-40], [1, 99])
            sharp_enough = sharp_enough and hi - lo >= SHOWN_CONTRAST
        if not sharp_enough:
            break
        count += 1
    return count


def _times(x: float) -> str:
    """A factor for a title: whole above 10, one decimal from 1 to 10, two significant digits below 1."""
    return f"{x:,.0f}" if x >= 10 else f"{x:.1f}" if x >= 1 else f"{x:.2g}"


def relative_exposure(d: float, f: float) -> float:
    r"""Light on the sensor per unit time through a hole ``d`` at ``f``, relative to :data:`REFERENCE`.

    (d/f)^2 over (d_ref/f_ref)^2 (irradiance goes as the hole's solid angle seen from the
    image, :math:`\propto (d/f)^2`).

    Parameters
    ----------
    d : float
        The pinhole's diameter (m).
    f : float
        The focal length (m).

    Returns
    -------
    float
        The exposure relative to the default pinhole's (1 at :data:`REFERENCE`).
    """
    d_ref, f_ref = REFERENCE
    return (d / f) ** 2 / (d_ref / f_ref) ** 2


# The d slider steps in log10(d) from D_LOG_MIN; the grid runs through the default 0.35 mm, so a drag back lands on
# it, and 0.003 per step puts a stop within 0.3 % of every d the lesson names (0.05, 0.56 and 1.5 mm).
D_LOG_STEP = 0.003
D_LOG_MIN = np.log10(0.35) - 356 * D_LOG_STEP  # 0.0299 mm
D_LOG_MAX = np.log10(0.35) + 285 * D_LOG_STEP  # 2.51 mm


def _size_controls() -> dict:
    """The controls of :func:`pinhole_size`.

    The pinhole's diameter (a log slider), the focal length and whether the exposure time stays the
    default's.
    """
    return {
        "diameter_mm": W.FloatLogSlider(
            value=0.35,
            base=10,
            min=D_LOG_MIN,
            max=D_LOG_MAX,
            step=D_LOG_STEP,
            description="pinhole d (mm)",
            continuous_update=True,
            readout_format=".2f",
            style={"description_width": "initial"},
            layout=W.Layout(width="300px"),
        ),
        "focal_mm": slider(100, 30, 300, 5, "focal length f (mm)", readout_format=".0f"),
        "fixed_exposure": W.Checkbox(
            value=False, description="fixed exposure time (true brightness)"
        ),
    }


def _size_figure(view: FigureView) -> SimpleNamespace:
    """The figure of :func:`pinhole_size`.

    Blur against the pinhole's diameter beside the letter chart it records; returns the artists
    by name.
    """
    ax_plot, ax_img = view.fig.subplots(1, 2)
    art = optics.draw_pinhole_blur(ax_plot, 0.1, object_distance=PAGE_Z)
    ax_plot.set_ylim(0.01, 30)
    ax_plot.minorticks_off()
    ax_plot.set_xticks(
        [0.03, 0.1, 0.3, 1, 3], ["0.03", "0.1", "0.3", "1", "3"]
    )  # plain numbers: read d = 0.35 off
    ax_plot.set_yticks([0.01, 0.1, 1, 10], ["0.01", "0.1", "1", "10"])
    im = images.show_image(ax_img, np.zeros(SIZE[::-1]), vmax=1.0)
    for spine in (
        ax_img.spines.values()
    ):  # a frame that stays visible round a burnt-out (white) or black chart
        spine.set_linewidth(1.5)
        spine.set_color(palette.GREY)
    ax_img.set_title(" \n ", fontsize=9)
    ax_plot.set_title(" \n ", fontsize=9)
    view.animate(
        im,
        ax_img.title,
        ax_plot.title,
        art["geometric"],
        art["diffraction"],
        art["total"],
        art["marker"],
        art["best"],
    )
    return SimpleNamespace(art=art, ax_plot=ax_plot, ax_img=ax_img, im=im)


def sharp_chart() -> np.ndarray:
    """The letter chart of :func:`pinhole_size` before any blur.

    The sensor spans the same field of view at every f, so the sharp picture is the same at
    every f: it is rendered at the default f.

    Returns
    -------
    (240, 320) ndarray
        Irradiance in 0-1, indexed ``[v, u]``.
    """
    f0 = REFERENCE[1]
    pitch0 = f0 * 0.36 / SIZE[0]
    chart = scenes.letter_chart(0.3, t=(0, 0, PAGE_Z))
    return render.render(
        chart, sensor.intrinsics_from_sensor(f0, (pitch0, pitch0), SIZE), SIZE
    ).irradiance


def chart_as_shown(
    d: float, f: float, fixed_exposure: bool = False, sharp: np.ndarray | None = None
) -> SimpleNamespace:
    """The chart :func:`pinhole_size` shows for a hole ``d`` at ``f``, without building the demo.

    Blurred by the hole (:func:`blur_through_pinhole`); with ``fixed_exposure`` the default's
    exposure time, so ``light`` (:func:`relative_exposure`) times as bright and clipped to 1,
    else brightness compensated, as rendered.

    Parameters
    ----------
    d : float
        The pinhole's diameter (m).
    f : float
        The focal length (m).
    fixed_exposure : bool, optional
        Keep the default's exposure time (the demo's checkbox).
    sharp : (240, 320) ndarray, optional
        :func:`sharp_chart`, when the caller has it already (the demo renders it once).

    Returns
    -------
    SimpleNamespace
        ``image`` (240, 320) in 0-1, ``light``, ``legible_rows`` (:func:`legible_rows` on the
        picture as shown) and ``not_white``, the number of pixels below full white.
    """
    img = blur_through_pinhole(sharp_chart() if sharp is None else sharp, d, f, f * 0.36 / SIZE[0])
    light = relative_exposure(d, f)
    if (
        fixed_exposure
    ):  # the reference's exposure time: the image darkens (or burns out) with (d/f)^2
        img = np.clip(img * light, 0.0, 1.0)
    return SimpleNamespace(
        image=img,
        light=light,
        legible_rows=legible_rows(d, f, img),
        not_white=int(np.sum(img < 1.0)),
    )


def _expose_title(ax_img, img: np.ndarray, light: float, fixed: bool) -> None:
    """Title the chart as :func:`pinhole_size` shows it (:func:`chart_as_shown`).

    With the default's exposure time (``fixed``), ``light`` times as bright; else brightness
    compensated.
    """
    default = f"(d = {REFERENCE[0] * 1e3:g} mm, f = {REFERENCE[1] * 1e3:g} mm)"
    if fixed:
        grey = int(np.sum(img < 1.0))  # a count, never a percentage rounded up to "100 %"
        note = (
            ", burnt out: every pixel white"
            if grey == 0
            else f", burnt out: all but {grey} pixels white"
            if grey < 0.5 * img.size
            else ", nearly black"
            if img.max() < 0.1
            else ""
        )
        ax_img.set_title(
            f"the default's exposure time {default}:\n{_times(light)} x the light{note}",
            fontsize=9,
        )
    else:
        ax_img.set_title(
            f"exposure time {_times(1 / light)} x the default's\n{default}: brightness compensated",
            fontsize=9,
        )


def _limited_by(b) -> str:
    """What limits a pinhole's blur ``b`` (:func:`camlab.pinhole.pinhole_blur`).

    "balanced" while its geometric and diffraction terms differ by under :data:`BALANCED` of the
    total, else the larger.
    """
    return (
        "balanced"
        if abs(b.diffraction - b.geometric) < BALANCED * b.total
        else "diffraction-limited"
        if b.diffraction > b.geometric
        else "geometry-limited"
    )


def _size_readout(state: dict, best: float, d: float) -> str:
    """The text beside :func:`pinhole_size`, from its ``state``, the best diameter and this one (m)."""
    ref = f"the default (d = {REFERENCE[0] * 1e3:g} mm, f = {REFERENCE[1] * 1e3:g} mm)"
    return monospace(
        f"best d = {best * 1e3:.2f} mm (star) for Z = {PAGE_Z:g} m\n"
        f"your d = {d * 1e3:.2f} mm (grey line): {state['limited_by']}\n"
        f"blur {state['blur_mm']:.2f} mm = {state['blur_px']:.1f} px;"
        f" blur / f = {state['blur_mrad']:.1f} mrad\n"
        f"rows legible: {state['legible_rows']} of {len(CHART_ROW_HEIGHTS)} (in the picture as shown)\n"
        f"f/d = f/{state['f_number']:.0f}: {state['exposure_vs_f2_8']:,.0f} x the exposure of f/2.8\n"
        f"light per second: {_times(state['light'])} x that of {ref}"
    )


@register(
    lesson="01",
    sweep={
        "diameter_mm": [0.03, 0.05, 0.35, 1.5, 2.5],
        "focal_mm": [30, 100, 300],
        "fixed_exposure": [True, False],
    },
)
def pinhole_size():
    """Blur against pinhole diameter (geometric versus diffraction) and the blurred chart it gives.

    Returns
    -------
    Demo
        The demo: controls ``diameter_mm`` (d, mm, logarithmic), ``focal_mm`` (f, mm) and
        ``fixed_exposure`` (keep the default's exposure time), the figure (blur against d,
        the recorded letter chart) and ``state`` (``blur_mm``, ``blur_px``, ``best_mm`` the
        optimal diameter, ``legible_rows``, ``limited_by``, ``blur_mrad``, ``f_number``,
        ``exposure_vs_f2_8``, ``light`` relative to the default, ``image``).
    """
    controls = _size_controls()
    view = FigureView(figsize=(8.8, 4))
    parts = _size_figure(view)
    art, ax_plot, ax_img, im = parts.art, parts.ax_plot, parts.ax_img, parts.im
    readout = W.HTML()
    sharp = sharp_chart()  # the same at every f: rendered once

    def update(values, state):
        f, d = values["focal_mm"] * 1e-3, values["diameter_mm"] * 1e-3
        optics.update_pinhole_blur(art, f, d, object_distance=PAGE_Z)
        b = pinhole.pinhole_blur(d, f, object_distance=PAGE_Z)
        # a sensor whose 320 pixels span the same field of view at every f
        pitch = f * 0.36 / SIZE[0]
        blur_px = float(b.total) / pitch
        # disc (the hole's shadow) convolved with the Airy pattern, exposed as the checkbox says
        shown = chart_as_shown(d, f, values["fixed_exposure"], sharp)
        img, light, legible = shown.image, shown.light, shown.legible_rows
        _expose_title(ax_img, img, light, values["fixed_exposure"])
        im.set_data(img)
        best = pinhole.optimal_pinhole_diameter(f, object_distance=PAGE_Z)
        limited_by = _limited_by(b)
        f_number = f / d
        ax_plot.set_title(
            f"blur against pinhole size, object at Z = {PAGE_Z:g} m\nd = {d * 1e3:.2f} mm: blur"
            f" {float(b.total) * 1e3:.2f} mm = {blur_px:.1f} px, {limited_by}",
            fontsize=9,
        )
        state.update(
            blur_mm=float(b.total) * 1e3,
            blur_px=blur_px,
            best_mm=best * 1e3,
            legible_rows=legible,
            limited_by=limited_by,
            blur_mrad=float(b.total) / f * 1e3,
            f_number=f_number,
            exposure_vs_f2_8=(f_number / 2.8) ** 2,
            light=light,
            image=img,
        )
        readout.value = _size_readout(state, best, d)

    return build_demo(
        "pinhole_size",
        controls,
        view,
        update,
        title="How big should the pinhole be?",
        extra=[readout],
    )
