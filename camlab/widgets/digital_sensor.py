"""Demos for lesson 03: pixels, sampling and aliasing, bit depth and noise, Bayer demosaicing."""

from __future__ import annotations

from types import SimpleNamespace

import ipywidgets as W
import numpy as np
from matplotlib.patches import Rectangle

from .. import fixtures, render, scenes, sensor
from ..plotting import images, palette
from ._base import FigureView, build_demo, register, slider
from .controls import int_slider, log_slider, monospace

SIZE = (320, 240)


def _side_view(fig):
    """A to-scale top view of pinhole, image plane and field of view (mm) beside the image; returns its artists and update.

    Drawn as H&Z's figure 6.1 draws it: the image plane f in front of the centre, upright, so that its left
    edge u = -1/2 is on the left (X < 0), as in the image beside it (the physical sensor, f behind the lens,
    holds the same picture rotated by 180°). The rays from the centre through the plane's two edges bound
    the field of view. Finer pixels at a fixed pixel count: a smaller plane, a narrower view.
    """
    ax = fig.add_axes((0.675, 0.07, 0.315, 0.62))
    ax.set(xlim=(-5, 5), ylim=(-1.2, 6.6), aspect="equal")
    ax.set_xticks([-4, -2, 0, 2, 4])
    ax.set_yticks([0, 3, 6])
    ax.tick_params(labelsize=8)
    ax.set_xlabel("X (mm), right →", fontsize=8)
    ax.set_ylabel("Z (mm), forward ↑", fontsize=8, labelpad=1)
    ax.set_title(
        "top view, to scale: the image plane (black)\nf = 3 mm in front of the pinhole (H&Z 6.1)",
        fontsize=8,
    )
    ax.axvline(0, color=palette.GREY, lw=0.6, ls=":")
    ax.plot([0], [0], "o", color="k", ms=4)  # the pinhole (camera centre), at Z = 0
    ax.text(0.4, -0.3, "pinhole", fontsize=7.5, va="top")
    # the plane thick; the two marks just above it, so a 0.6 mm plane (2 µm pixels) still shows, with leaders down to it
    # one colour per meaning: the plane and its ends black, the field of view green, the × blue, the + orange
    (plane,) = ax.plot([], [], color="k", lw=3.5, solid_capstyle="butt", zorder=3)
    (rays,) = ax.plot([], [], color=palette.GREEN, lw=1)
    (leaders,) = ax.plot([], [], color="k", lw=0.8, zorder=4)
    (centre,) = ax.plot(
        [], [], "x", color=palette.BLUE, ms=6, mew=1.5, path_effects=palette.halo(), zorder=5
    )
    (principal,) = ax.plot(
        [], [], "+", color=palette.ORANGE, ms=8, mew=1.5, path_effects=palette.halo(), zorder=5
    )
    edge_text = dict(fontsize=7.5, va="top", color="k")
    left_label = ax.text(0, 2.6, "u = −½", ha="right", **edge_text)
    right_label = ax.text(0, 2.6, "u = W − ½", ha="left", **edge_text)

    def update(pitch_mm, cx_px, width_px):
        # a pixel u on the virtual plane sits at X = (u - c_x) s, Z = f: left of the axis when u < c_x
        x_left, x_right = (-0.5 - cx_px) * pitch_mm, (width_px - 0.5 - cx_px) * pitch_mm
        plane.set_data([x_left, x_right], [3, 3])
        rays.set_data(
            [0, x_left * 2, np.nan, 0, x_right * 2], [0, 6, np.nan, 0, 6]
        )  # on to Z = 6 mm
        x_centre = ((width_px - 1) / 2 - cx_px) * pitch_mm
        centre.set_data(
            [x_centre], [3.45]
        )  # just above the plane, each on a leader down to its point on it
        principal.set_data([0], [3.45])
        leaders.set_data(  # the × and + up to their marks; each end's label on a short leader from its end
            [
                x_centre,
                x_centre,
                np.nan,
                0,
                0,
                np.nan,
                x_left,
                x_left - 0.3,
                np.nan,
                x_right,
                x_right + 0.3,
            ],
            [3, 3.45, np.nan, 3, 3.45, np.nan, 3, 2.6, np.nan, 3, 2.6],
        )
        left_label.set_position((x_left - 0.3, 2.6))
        right_label.set_position((x_right + 0.3, 2.6))

    return (plane, rays, leaders, centre, principal, left_label, right_label), update


@register(
    lesson="03", sweep={"pitch_um": [2.0, 3.0, 6.0, 12.0, 15.0], "cx_offset": [-60, -40, 0, 40, 60]}
)
def pixel_pitch():
    """The same 3 mm lens on sensors with different pixel pitch and principal point offset.

    Returns
    -------
    Demo
        The demo: controls ``pitch_um`` (pixel pitch, µm) and ``cx_offset`` (principal point's
        offset from the image centre, px), the figure (the rendered 320 x 240 image with the
        image centre and the principal point) and ``state`` (``K``, ``fov_deg`` the horizontal
        field of view in degrees, ``fov_left_right`` its two halves either side of the axis).
    """
    controls = {
        "pitch_um": slider(6.0, 2.0, 15.0, 0.5, "pixel pitch (µm)"),
        "cx_offset": slider(0, -60, 60, 2, "principal point offset (px)"),
    }
    view = FigureView(figsize=(8.6, 4.4))
    view.fig.set_layout_engine(
        "none"
    )  # placed by hand: the image, its legend, and the top view beside them
    ax_img = view.fig.add_axes((0.07, 0.115, 0.56, 0.765), anchor="W")  # room below for "u (px)"
    scene = [
        scenes.checkerboard((9, 6), 0.05, t=(-0.2, -0.125, 1.2)),
        scenes.photo_plane(0.25, t=(0.34, 0.05, 1.3)),
    ]
    # drawn pixel by pixel: 320 px at about 1.35 screen px each, so no resampled grey seam at a checker edge
    im = images.show_image(ax_img, np.zeros(SIZE[::-1]), vmax=1.0, interpolation="nearest")
    centre = ((SIZE[0] - 1) / 2, (SIZE[1] - 1) / 2)
    (mark,) = ax_img.plot(
        *centre,
        "x",
        color=palette.BLUE,
        ms=10,
        mew=2,
        path_effects=palette.halo(),
        label="image centre",
    )
    (pp,) = ax_img.plot(
        [],
        [],
        "+",
        color=palette.ORANGE,
        ms=16,
        mew=2,
        path_effects=palette.halo(),
        label="principal point",
    )
    ax_img.set_xticks(np.arange(0, SIZE[0], 40))
    ax_img.set_yticks(np.arange(0, SIZE[1], 40))
    ax_img.set(xlabel="u (px)", ylabel="v (px)")
    ax_img.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=9, borderaxespad=0)
    ax_img.set_title("f = 3 mm, always 320 x 240 pixels", fontsize=10)
    readout = W.HTML()  # the numbers beside the sliders: canvas text costs ~15 ms per redraw
    side_artists, side_update = _side_view(view.fig)
    view.animate(
        im, mark, pp, ax_img.title, *side_artists
    )  # the centre mark too, or the blitted image covers it

    def update(values, state):
        pitch = values["pitch_um"] * 1e-6
        K = sensor.intrinsics_from_sensor(3e-3, (pitch, pitch), SIZE, (values["cx_offset"], 0.0))
        im.set_data(render.render(scene, K, SIZE).irradiance)
        pp.set_data([K[0, 2]], [K[1, 2]])
        side_update(pitch * 1e3, K[0, 2], SIZE[0])
        # the frame's left and right edges, u = -0.5 and W - 0.5, seen from the principal point: with c_x off
        # centre the two halves differ, and their sum is a little less than 2 atan(W / 2 / f_x)
        left, right = (
            np.degrees(np.arctan(d / K[0, 0])) for d in (K[0, 2] + 0.5, SIZE[0] - 0.5 - K[0, 2])
        )
        fov = left + right
        state.update(K=K, fov_deg=fov, fov_left_right=(left, right))
        # f_x and the field of view in the figure too, so a printed or rendered page shows what the prose asks for
        ax_img.set_title(
            f"f = 3 mm, always 320 x 240 pixels of {values['pitch_um']:g} µm\n"
            f"f_x = f / s_x = {K[0, 0]:.0f} px, horizontal field of view {fov:.1f}°",
            fontsize=10,
        )
        readout.value = monospace(
            f"f_x = f / s_x = {K[0, 0]:.0f} px\nc_x = {K[0, 2]:.1f}, c_y = {K[1, 2]:.1f}\n"
            f"sensor {SIZE[0] * pitch * 1e3:.2f} x {SIZE[1] * pitch * 1e3:.2f} mm\n"
            f"horizontal FOV {fov:.1f}°\n"
            f"  left {left:.2f}°, right {right:.2f}° of the axis"
        )

    return build_demo(
        "pixel_pitch",
        controls,
        view,
        update,
        title="Pixel pitch and principal point",
        extra=[readout],
    )


def _blocks_on_screen(image, samples: np.ndarray, k: int) -> np.ndarray:
    """Each sample as a k x k block of fine pixels, area-averaged to the canvas pixels ``image`` covers.

    Averaged here rather than by the display's resampler, the image is drawn 1:1 ("nearest"), so the
    first draw (a saved figure) and every live frame show the same pixels.
    """
    import cv2

    x0, x1, y0, y1 = (
        image.get_extent()
    )  # the canvas pixels the extent covers, rounded as the live path does
    (u0, v0), (u1, v1) = image.get_transform().transform([(x0, y0), (x1, y1)])
    left, right, bottom, top = (
        round(min(u0, u1)),
        round(max(u0, u1)),
        round(min(v0, v1)),
        round(max(v0, v1)),
    )
    blocks = np.kron(samples, np.ones((k, k), np.float32)).astype(np.float32)
    return cv2.resize(blocks, (right - left, top - bottom), interpolation=cv2.INTER_AREA)


def _sampling_controls() -> dict:
    """The controls of :func:`sampling_aliasing`: the pixel size, the box filter and the lens blur."""
    return {
        # odd: each point sample is its block's centre, so the fold shows on all four sides
        "factor": int_slider(3, 1, 8, "pixel size (fine px)"),
        "prefilter": W.Checkbox(
            value=False, description="average over the pixel area (box filter)"
        ),
        "blur": slider(0.0, 0.0, 1.0, 0.1, "lens blur σ (coarse px)"),
    }


def _ring_contrast(s: np.ndarray, k: int, r: float) -> tuple[float | None, float]:
    """The zone plate's false and true rings' contrast in the samples ``s`` at pixel size ``k``.

    The standard deviation of the samples where the larger local frequency, |f_x| or |f_y|, is 0.55 to
    0.75 cycle per coarse px (one fixed band just beyond the Nyquist square, so every pixel size compares
    like with like; None where the band lies beyond the frame), and below 0.3 (the true rings).
    ``r`` is the square's half side in fine px.
    """
    x, y = np.meshgrid(
        np.arange(s.shape[1]) - (s.shape[1] - 1) / 2,
        np.arange(s.shape[0]) - (s.shape[0] - 1) / 2,
    )
    f = 0.5 * np.maximum(abs(x), abs(y)) * k / r  # cycles per coarse px: 0.5 on the square
    band = (f > 0.55) & (f < 0.75)
    return (float(s[band].std()) if band.any() else None), float(s[f < 0.3].std())


@register(
    lesson="03",
    sweep={"factor": [1, 2, 3, 4, 6, 7, 8], "prefilter": [True, False], "blur": [0.0, 0.5, 1.0]},
)
def sampling_aliasing():
    """A zone plate sampled by coarser pixels: ideal point samples alias, real (box) pixels and a lens blur much less.

    Returns
    -------
    Demo
        The demo: controls ``factor`` (the coarse pixel's size in fine px), ``prefilter``
        (average over the pixel's area instead of a point sample) and ``blur`` (a lens blur's
        sigma, coarse px), the figure (the zone plate beside its samples with the Nyquist
        square) and ``state`` (``samples`` the sampled shape, ``nyquist_half_side`` in fine px,
        ``alias_contrast`` the samples' standard deviation where the local frequency is 0.55 to 0.75
        cycle per coarse px, just beyond the Nyquist square, and ``true_contrast`` theirs below 0.3).
    """
    controls = _sampling_controls()
    view = FigureView(figsize=(9, 4))
    ax_t, ax_s = view.fig.subplots(1, 2)
    zp = sensor.zone_plate(384, k=np.pi / 768)  # 0.25 cycle/px at the edge
    # Both panels are drawn smaller than 384 px: antialiased display, or the screen adds its own moire.
    images.show_image(
        ax_t, zp, "scene: zone plate (frequency grows with radius)", interpolation="antialiased"
    )
    im = images.show_image(
        ax_s, zp, "sampled\n(two lines, as update writes)", interpolation="nearest"
    )
    # A square grid samples each axis separately: the alias-free region is a square (|fx|, |fy| < 1/2 cycle per
    # coarse px), not a circle; the zone plate's local frequency is (x, y) k / pi, so the square is |x|, |y| < r.
    # dashes with a white halo, as section 4's figure draws its limits: visible over the busy point samples at
    # every pixel size, with gaps through which the fold's grey ring systems on the square's sides show
    nyq = ax_s.add_patch(
        Rectangle(
            (0, 0),
            1,
            1,
            fill=False,
            color=palette.RED,
            ls=(0, (4, 3)),
            lw=1.8,
            path_effects=palette.halo(1.8),
        )
    )
    # pixel sizes that do not divide 384 leave a strip unsampled: grey, no sample's black or white
    ax_s.set_facecolor(palette.GREY)
    ax_s.set_xlim(-0.5, zp.shape[1] - 0.5)
    ax_s.set_ylim(zp.shape[0] - 0.5, -0.5)
    ax_s.set_autoscale_on(
        False
    )  # the frame stays the scene's, whatever part of it a pixel size samples
    # the layout fixed now, before the first update: the samples are averaged to the panel's screen pixels
    view.fig.get_layout_engine().execute(view.fig)
    view.fig.set_layout_engine("none")
    for ax in (ax_t, ax_s):
        ax.apply_aspect()  # as a draw does: the image's box on the screen is final from here on
    view.animate(im, nyq, ax_s.title)
    readout = W.HTML()

    def update(values, state):
        k = int(values["factor"])
        s = sensor.sample(zp, k, prefilter=values["prefilter"], blur=float(values["blur"]))
        # the samples cover the whole blocks only: (384 // k) k fine px (378 at k = 7), not stretched to 384
        im.set_extent((-0.5, s.shape[1] * k - 0.5, s.shape[0] * k - 0.5, -0.5))
        # each sample a k x k block, area-averaged to the screen as the scene is: at pixel size 2 a block is
        # 1.65 screen px, which drawn pixel by pixel would beat into a moire of the screen's own
        im.set_data(_blocks_on_screen(im, s, k))
        # the local frequency (pi / 768) x / pi cycles per fine px reaches 0.5 cycle per coarse px at x = 384 / k
        r = zp.shape[0] / k
        cx, cy = (zp.shape[1] - 1) / 2, (zp.shape[0] - 1) / 2
        # at pixel size 2 the square is the frame's own edge: draw it 5 fine px inside, where it shows
        shown = min(r, cx - 5)
        nyq.set_bounds(cx - shown, cy - shown, 2 * shown, 2 * shown)
        nyq.set_visible(
            r <= cx + 1
        )  # at pixel size 1 the limit lies beyond the frame: nothing to draw
        false, true = _ring_contrast(s, k, r)
        state.update(
            samples=s.shape, nyquist_half_side=r, alias_contrast=false or 0.0, true_contrast=true
        )
        readout.value = monospace(
            "contrast (std of the samples); a full-contrast cosine: 0.354\n"
            f"true rings, below 0.3 cycle/px: {true:.2f}\n"
            "false rings, 0.55 to 0.75 cycle/px: "
            + ("-- (beyond the frame)" if false is None else f"{false:.2f}")
        )
        if (
            r > cx + 1
        ):  # pixel size 1: the scene's finest detail, 0.25 cycle per px, is below the limit
            where = "Nyquist limit beyond the frame: no aliasing"
        elif (
            r >= cx
        ):  # pixel size 2: the edges reach 0.5 cycle per px, the fold's half systems show there
            where = "red square: Nyquist limit, at the frame's edge"
        else:  # the number section 2 prints for the static figure (0.35 point, 0.12 box at 6)
            where = f"red square: Nyquist limit; false-ring contrast {state['alias_contrast']:.2f}"
        kind = "box samples" if values["prefilter"] else "point samples"
        blurred = f", blur σ = {values['blur']:.1f} coarse px" if values["blur"] else ""
        ax_s.set_title(f"{kind}, pixel size {k} fine px{blurred}\n({where})", fontsize=10)

    return build_demo(
        "sampling_aliasing", controls, view, update, title="Sampling and aliasing", extra=[readout]
    )


BACKGROUND = 0.2  # the grey around the photo, linear
UNIFORM = slice(100, 140)  # where the profile row crosses the dark uniform


def _noise_controls() -> dict:
    """The controls of :func:`bit_depth_and_noise`: bit depth, exposure, ISO gain and read noise."""
    return {
        "bits": int_slider(4, 1, 12, "bit depth"),
        "exposure": log_slider(0.3, 0.01, 1.0, 0.05, "exposure (x full well)"),
        "iso": log_slider(3.0, 1.0, 16.0, 0.05, "ISO gain (x base)"),
        "read_noise": slider(5.0, 0.0, 40.0, 1.0, "read noise (electrons)"),
    }


def analogue_gain(iso: float, bits: int, full_well: float = 10000.0) -> float:
    """The analogue gain a camera applies before its converter: the ISO gain, capped at 1 e-/DN.

    The converter's full scale is ``full_well / gain`` electrons, so one DN is
    ``full_well / (gain (2**bits - 1))`` electrons. Beyond 1 electron per DN every electron
    already has its own code; in this model, where all the read noise comes before the amplifier,
    more analogue gain adds no information, so it stops there (higher ISOs only multiply the numbers
    afterwards). Real cameras often raise the analogue gain further, because gain before the
    converter lowers the converter's own noise counted in electrons (Janesick; R. N. Clark).

    Parameters
    ----------
    iso : float
        The ISO setting over the base ISO (1 at base).
    bits : int
        The converter's bit depth.
    full_well : float
        The full-well capacity, electrons.

    Returns
    -------
    float
        ``min(iso, full_well / (2**bits - 1))``.
    """
    return float(min(iso, full_well / (2**bits - 1)))


def _noise_figure(view: FigureView) -> SimpleNamespace:
    """The figure of :func:`bit_depth_and_noise`.

    The rendered photo (linear light, shown through sRGB) and the profile of one row against the
    truth; returns the clean photo and the artists.
    """
    ax_img, ax_p = view.fig.subplots(1, 2)
    K = np.array([[330.0, 0, 159.5], [0, 330.0, 119.5], [0, 0, 1]])
    # linear light, as a sensor counts it (the photo's JPEG values decoded), shown through sRGB
    clean = render.render(
        [scenes.photo_plane(0.5, t=(0.0, 0, 1.0), linear=True)],
        K,
        SIZE,
        color=False,
        background=BACKGROUND,
    ).irradiance
    im = images.show_image(
        ax_img, sensor.gamma_encode(clean), "recorded, shown through sRGB", vmax=1.0
    )
    row = 150
    # the row marked by ticks on the image's left and right edges, not by a line over the very row the profile shows
    ax_img.set_yticks([row], [""])  # the profile's title names the row
    # the row marked by ticks outside both edges and short bars inside them (animated: drawn over the image), not by
    # a line over the very row the profile shows
    ax_img.tick_params(
        axis="y", colors=palette.BLUE, length=9, width=2.5, left=True, right=True, labelsize=9
    )
    inside = [-0.5, 24, np.nan, SIZE[0] - 24.5, SIZE[0] - 0.5]
    (row_marks,) = ax_img.plot(
        inside,
        [row] * 5,
        color=palette.BLUE,
        lw=2.5,
        solid_capstyle="butt",
        zorder=3,
        path_effects=palette.halo(2.5),
    )
    # the truth wide and pale beneath, the recording thin on top: both stay visible where they agree;
    # the title names them, so no legend covers the profile
    # both in display (sRGB) values, as the image: a linear axis would squeeze the shadows' bands into its bottom
    ax_p.plot(sensor.gamma_encode(clean[row]), color=palette.GREY, lw=3.5, solid_capstyle="butt")
    (prof,) = ax_p.plot(sensor.gamma_encode(clean[row]), color=palette.BLUE, lw=1)
    ax_p.set_ylim(-0.05, 1.08)
    ax_p.set_xlabel("u (px)")
    ax_p.set_ylabel("sRGB value, as shown (1: the photo's white)")
    ax_p.set_title("", fontsize=9)
    view.animate(im, row_marks, prof, ax_p.title)
    return SimpleNamespace(clean=clean, im=im, prof=prof, ax_p=ax_p, row=row)


def _model_snr(n: float, read_noise: float, step: float, full_scale: float) -> tuple[float, str]:
    """Section 3's SNR model at ``n`` electrons and the readout's words for it.

    ``"saturated"`` where ``n`` reaches the converter's full scale (every such pixel reads the top
    code), ``"--"`` with the reason where one DN exceeds the noise (the Delta^2/12 term treats rounding
    as random noise, which fails there), else the value.
    """
    noise = np.sqrt(n + read_noise**2)
    snr = float(n / np.sqrt(n + read_noise**2 + step**2 / 12))
    if n >= full_scale:
        return snr, f"saturated (> full scale {full_scale:.0f} e-)"
    if step > noise:
        dn = f"{step:.0f}" if step >= 100 else f"{step:.3g}"
        return snr, f"-- (1 DN = {dn} e- > noise {noise:.3g} e-)"
    return snr, f"{snr:.1f}"


def _snr_readout(expo, read_noise, step, full_scale, bg, clipped) -> SimpleNamespace:
    """The bit-depth demo's SNR lines and state: the model at half of white, model and measurement in the background.

    ``bg`` holds the grey background's codes, ``clipped`` the share of it above full scale. No SNR is
    measured where more than 2 % of it is clipped (the clipped pixels narrow the spread), where 90 % or more of it sits on one code (the
    spread rests on a few stray pixels: banding, not noise), or where one DN exceeds its noise (its
    pixels toss between two codes, and the spread measures the rounding).
    """
    full_well = 10000.0
    _, half_text = _model_snr(0.5 * expo * full_well, read_noise, step, full_scale)
    n_bg = BACKGROUND * expo * full_well
    model_bg, model_text = _model_snr(n_bg, read_noise, step, full_scale)
    if (
        clipped > 0.02 and n_bg < full_scale
    ):  # as for the measurement: a clipped level has no model SNR
        model_text = f"-- ({clipped:.0%} of it clips at full scale)"
    noise_bg = float(np.sqrt(n_bg + read_noise**2))
    one_code = float(np.unique(bg, return_counts=True)[1].max() / bg.size)
    if clipped > 0.02:
        why = f"{clipped:.0%} clipped at full scale"
    elif one_code >= 0.9:
        why = f"{np.floor(1e4 * one_code) / 100:.2f} % on one code: banding, not noise"
    elif step > noise_bg:
        why = f"1 DN > noise: pixels toss between {np.unique(bg).size} codes"
    else:
        why = None
    measured = np.inf if why else float(bg.mean() / bg.std())
    text = (
        f"model SNR at half of white: {half_text}\n"
        f"grey background: model SNR {model_text}\n"
        f"  measured SNR " + (f"-- ({why})" if why else f"{measured:.1f}") + "\n"
    )
    state = dict(
        snr=float(
            0.5 * expo * full_well / np.sqrt(0.5 * expo * full_well + read_noise**2 + step**2 / 12)
        ),
        snr_background=(model_bg, measured),
        background_one_code=one_code,
        background_clipped=clipped,
        noise_background=noise_bg,
        background_reason=why,
        background_model=model_text,
    )
    return SimpleNamespace(text=text, state=state)


@register(
    lesson="03",
    sweep={
        "bits": [1, 3, 8, 12],
        "exposure": [0.01, 0.02, 0.3, 1.0],
        "iso": [1.0, 16.0],
        "read_noise": [0.0, 20.0, 40.0],
    },
)
def bit_depth_and_noise():
    """Quantisation and noise on a rendered photo, with a row profile.

    Returns
    -------
    Demo
        The demo: controls ``bits`` (bit depth), ``exposure`` (the light at the photo's white, a
        fraction of the full well), ``iso`` (the gain over base ISO, applied before the converter up
        to 1 e-/DN, :func:`analogue_gain`) and ``read_noise`` (electrons), the figure (the recorded photo and one row's profile against
        the truth) and ``state`` (``levels``, ``snr`` at half of white, ``rms_error`` the recorded
        image's rms difference from the true one, linear, over the whole frame, as a fraction of white, ``electrons`` of the white, the dark uniform and the background,
        ``dn_electrons`` the electrons per digital number, ``clean_row`` the profiled row's truth, linear, ``shown_row`` its recording as the profile shows it (sRGB), ``background_spread`` the std of the whole grey background as shown (sRGB), ``codes`` how many codes the frame uses, ``gain`` the analogue gain, ``full_scale`` the converter's full scale in
        electrons, ``snr_background`` the model's and the measured SNR in the grey background,
        the measurement inf where :func:`_snr_readout` measures none (``background_reason`` says why, ``background_model`` the readout's words for the model),
        ``background_one_code`` the share on its commonest code, ``background_clipped`` the share
        clipped at the top code and ``noise_background`` its noise in electrons).
    """
    controls = _noise_controls()
    view = FigureView(figsize=(9, 4))
    art = _noise_figure(view)
    clean, im, prof, ax_p, row = art.clean, art.im, art.prof, art.ax_p, art.row
    readout = W.HTML()  # numbers beside the sliders: canvas text costs ~4 ms per line per redraw
    full_well = 10000.0

    def update(values, state):
        bits, expo = int(values["bits"]), float(values["exposure"])
        gain = analogue_gain(float(values["iso"]), bits, full_well)
        # one noise field per (exposure, read noise): moving only the bit depth or the ISO changes only the rounding
        rng = np.random.default_rng([round(expo * 1e6), round(float(values["read_noise"]) * 1e3)])
        noisy = sensor.add_noise(
            clean * expo, sensor.NoiseModel(full_well, values["read_noise"]), rng
        )
        # the converter's full scale is full_well / gain electrons; the display then pushes the photo's
        # white to 1 (digitally, after the rounding: it adds no codes), unless the white already saturates
        dn = sensor.quantise(np.clip(noisy * gain, 0, 1), bits)
        shown = np.clip(sensor.dequantise(dn, bits) / min(1.0, gain * expo), 0, 1)
        im.set_data(sensor.gamma_encode(shown))
        prof.set_ydata(sensor.gamma_encode(shown[row]))
        step = full_well / gain / (2**bits - 1)  # one DN in electrons: section 3's g at this gain
        bg = dn[clean == BACKGROUND]
        clipped = float(
            np.mean(noisy[clean == BACKGROUND] * gain >= 1)
        )  # above full scale before the rounding
        electrons = {
            "white": expo * full_well,
            "uniform": float(clean[row, UNIFORM].mean()) * expo * full_well,
            "background": BACKGROUND * expo * full_well,
        }
        snr = _snr_readout(expo, float(values["read_noise"]), step, full_well / gain, bg, clipped)
        state.update(
            levels=2**bits,
            rms_error=float(np.sqrt(np.mean((shown - clean) ** 2))),
            electrons=electrons,
            dn_electrons=step,
            clean_row=clean[row],
            shown_row=sensor.gamma_encode(shown[row]),
            background_spread=float(sensor.gamma_encode(shown[clean == BACKGROUND]).std()),
            codes=int(np.unique(dn).size),
            gain=gain,
            full_scale=full_well / gain,
            **snr.state,
        )
        dn = f"{step:.{max(0, 2 - int(np.floor(np.log10(step))))}f}"  # 3 significant figures: 11.8, 0.733, 3000
        clips = (
            f" > full scale {full_well / gain:.0f}" if electrons["white"] > full_well / gain else ""
        )
        ax_p.set_title(
            f"row {row} (blue ticks): recorded (blue) against true (wide grey)\n"
            f"electrons: white {electrons['white']:.0f}{clips}\n"  # 3 lines: a clipped white's line fits
            f"dark uniform {electrons['uniform']:.1f}, 1 DN = {dn}",
            fontsize=9,
        )
        readout.value = monospace(
            f"{2**bits} levels; analogue gain {gain:.2f}"
            + (" (capped: 1 e-/DN)" if gain < float(values["iso"]) else "")
            + f", full scale {full_well / gain:.0f} e-\n"
            + snr.text
            + f"rms error against the true image {state['rms_error']:.3f}\n(linear, whole frame; 1 = white)"
        )

    return build_demo(
        "bit_depth_and_noise", controls, view, update, title="Bit depth and noise", extra=[readout]
    )


_METHODS = ("truth", "camlab bilinear", "OpenCV bilinear", "OpenCV VNG", "OpenCV edge-aware")


K_DEMOSAIC = np.array([[900.0, 0, 159.5], [0, 900.0, 119.5], [0, 0, 1]])


_SAME = "same as the sensor"
_OPENCV_METHODS = {"OpenCV bilinear": "bilinear", "OpenCV VNG": "vng", "OpenCV edge-aware": "ea"}


def _demosaic_readout(truth, out, reference, crop, method: str) -> str:
    """The readout beside the demosaicing demo's sliders, all on linear values.

    PSNR per channel, against camlab bilinear's, and the zoom's mean |error| per channel (what
    its error map shows).
    """
    rows = []
    for name, img in ((method, out), ("camlab bilinear", reference)):
        scores = [sensor.psnr(truth[..., c], img[..., c], border=2) for c in range(3)]
        scores.append(sensor.psnr(truth, img, border=2))
        shown = (
            "".join(f"{'—':>5}" for _ in scores) + "  (reference)"  # in the columns
            if np.isinf(scores[-1])
            else "".join(f"{v:5.1f}" for v in scores)
        )
        rows.append(f"{name:17s}" + shown)
    error = np.abs(out[crop] - truth[crop]).reshape(-1, 3).mean(axis=0)
    return monospace(
        f"PSNR (dB; linear, less a 2-px border)\n{'':17s}    R    G    B  all\n"
        + "\n".join(rows[: 1 if method == "camlab bilinear" else 2])
        + "\nzoom, mean |error| (linear):\n"
        + "  ".join(f"{c} {v:.3f}" for c, v in zip("RGB", error, strict=True))
    )


CROP = 48
ZOOM_MAX = SIZE[0] - CROP  # the zoom's last column at the frame's last column
ZOOM_V_MAX = SIZE[1] - CROP  # the zoom's bottom row at the frame's last row
ZOOM_U, ZOOM_V = (
    200,
    0,
)  # the default zoom: the cap's badge, where zipper and false colour show at first sight


def _demosaic_controls() -> dict:
    """The controls of :func:`demosaicing`.

    The sensor's pattern, the pattern assumed, the method and the zoom (where, and whether it shows
    the image or its error).
    """
    patterns = ["RGGB", "BGGR", "GRBG", "GBRG"]
    return {
        "pattern": W.Dropdown(options=patterns, value="RGGB", description="sensor's pattern"),
        "assume": W.Dropdown(
            options=[_SAME] + patterns,
            value=_SAME,
            description="demosaic as",
            style={"description_width": "initial"},
        ),
        "method": W.Dropdown(options=list(_METHODS), value="camlab bilinear", description="method"),
        "zoom_u": W.IntSlider(
            value=ZOOM_U, min=0, max=ZOOM_MAX, description="zoom at u", continuous_update=True
        ),
        "zoom_v": W.IntSlider(
            value=ZOOM_V, min=0, max=ZOOM_V_MAX, description="zoom at v", continuous_update=True
        ),
        "zoom_error": W.Checkbox(value=False, description="zoom: |error| x 8 (linear)"),
    }


def _demosaic_figure(view: FigureView) -> SimpleNamespace:
    """The figure of :func:`demosaicing`.

    The mosaic's zoom, the demosaiced frame with the zoom's box, and the zoom; returns the true
    (linear) image and the artists by name.
    """
    ax_raw, ax_full, ax_zoom = view.fig.subplots(1, 3, width_ratios=[0.75, 1, 0.75])
    # linear light (the photo's JPEG values decoded), as a sensor records it; every panel is shown through sRGB
    truth = render.render(
        fixtures.photo_and_page(linear=True, downsample=2),
        K_DEMOSAIC,
        SIZE,
        color=True,
        background=0.2,
    ).irradiance
    im_raw = images.show_image(
        ax_raw, np.zeros((CROP, CROP, 3)), "Bayer mosaic (zoom, through sRGB)"
    )
    im_full = images.show_image(ax_full, sensor.gamma_encode(truth), "method")
    im_zoom = images.show_image(
        ax_zoom, sensor.gamma_encode(truth[:CROP, :CROP]), "zoom (shown through sRGB)"
    )
    box = images.zoom_box(
        ax_full, ZOOM_U, ZOOM_V, CROP, color="white"
    )  # white on a black outline: seen on the red stripes too
    box.set_path_effects(palette.halo(1.5, "black"))
    box.set_clip_on(
        False
    )  # at u = 0 or v = 0 the box lies on the frame's edge: drawn whole, not half clipped
    ax_full.set_title("camlab bilinear: PSNR 00.00 dB (linear)", fontsize=10)
    view.animate(im_raw, im_full, im_zoom, box, ax_full.title, ax_zoom.title)
    return SimpleNamespace(
        truth=truth,
        im_raw=im_raw,
        im_full=im_full,
        im_zoom=im_zoom,
        box=box,
        ax_full=ax_full,
        ax_zoom=ax_zoom,
    )


@register(
    lesson="03",
    sweep={
        "pattern": ["RGGB", "GBRG"],
        "method": list(_METHODS),
        "zoom_u": [0, 40, 200, ZOOM_MAX],
        "zoom_v": [0, 50, ZOOM_V_MAX],
        "zoom_error": [True, False],
        "assume": ["BGGR", _SAME],
    },
)
def demosaicing():
    """A Bayer mosaic demosaiced by one method at a time, with PSNR and a zoom; try the wrong pattern.

    The zoom goes anywhere in the frame (as the image or as its error), with the mosaic
    under it.

    Returns
    -------
    Demo
        The demo: controls ``pattern`` (the sensor's Bayer pattern), ``assume`` (the pattern the
        demosaicing assumes), ``method``, ``zoom_u`` and ``zoom_v`` (the zoom's top-left pixel)
        and ``zoom_error`` (show the zoom's error x 8 instead of the image), the figure (the
        mosaic, the demosaiced frame, the zoom) and ``state`` (``psnr`` in dB over the frame,
        ``zoom``, ``assumed``, ``zoom_psnr``, ``zoom_shows``).
    """
    controls = _demosaic_controls()
    view = FigureView(figsize=(10, 3.9))
    art = _demosaic_figure(view)
    truth, im_raw, im_full, im_zoom = art.truth, art.im_raw, art.im_full, art.im_zoom
    box, ax_full, ax_zoom = art.box, art.ax_full, art.ax_zoom

    demosaiced: dict[tuple[str, str, str], tuple[np.ndarray, np.ndarray, float]] = {}
    readout = W.HTML()

    def develop(pattern: str, assumed: str, method: str):
        """The raw mosaic, its demosaiced image and PSNR; pure, so kept while the zoom slider moves."""
        key = (pattern, assumed, method)
        if key not in demosaiced:
            raw = sensor.quantise(sensor.mosaic(truth, pattern))
            if method == "truth":
                out = truth
            elif method == "camlab bilinear":
                out = sensor.demosaic_bilinear(raw, assumed) / 255
            else:
                out = sensor.demosaic_opencv(raw, assumed, _OPENCV_METHODS[method]) / 255
            out = np.clip(out, 0, 1)
            demosaiced[key] = raw, out, sensor.psnr(truth, out, border=2)
        return demosaiced[key]

    def update(values, state):
        pattern, method = values["pattern"], values["method"]
        u0, v0 = int(values["zoom_u"]), int(values["zoom_v"])
        assumed = (
            pattern if values["assume"] == _SAME else values["assume"]
        )  # a wrong guess is the classic bug
        raw, out, psnr = develop(pattern, assumed, method)
        masks = sensor.bayer_masks(raw.shape, pattern)
        crop = (slice(v0, v0 + CROP), slice(u0, u0 + CROP))
        im_raw.set_data(sensor.gamma_encode(masks[crop] * (raw[crop] / 255.0)[..., None]))
        shown = sensor.gamma_encode(out)
        im_full.set_data(shown)
        if values[
            "zoom_error"
        ]:  # each channel's error in its own colour, as in the worked example's maps
            im_zoom.set_data(np.clip(8 * np.abs(out[crop] - truth[crop]), 0, 1))
            ax_zoom.set_title("zoom: |error| x 8 (linear; black = right)", fontsize=10)
        else:
            im_zoom.set_data(shown[crop])
            ax_zoom.set_title("zoom (shown through sRGB)", fontsize=10)
        box.set_xy((u0 - 0.5, v0 - 0.5))
        state.update(
            psnr=psnr,
            zoom=(u0, v0),
            assumed=assumed,
            zoom_psnr=sensor.psnr(truth[crop], out[crop]),
            zoom_shows="error" if values["zoom_error"] else "image",
        )
        reference = develop(pattern, assumed, "camlab bilinear")[1]
        readout.value = _demosaic_readout(truth, out, reference, crop, method)
        if method == "truth":
            score = ": the reference the PSNRs compare with"
        elif assumed != pattern:  # short: this title sits between two others
            score = f" as {assumed} (wrong): {state['psnr']:.1f} dB"
        else:
            score = f": PSNR {state['psnr']:.1f} dB (linear)"
        ax_full.set_title(method + score, fontsize=10)

    return build_demo(
        "demosaicing",
        controls,
        view,
        update,
        title="Bayer mosaic and demosaicing",
        extra=[readout],
    )
