"""Lesson 09's canvas demos.

The panorama's canvas, blending and seams, the full panorama, the canvas projections and parallax
ghosting (sections 3-6). Re-exported by :mod:`camlab.widgets.image_stitching`.
"""

from __future__ import annotations

from types import SimpleNamespace

import ipywidgets as W
import numpy as np
from matplotlib.colors import to_rgb
from matplotlib.patches import Patch, Rectangle

from ... import stitching as st
from ...fixtures import panorama_examples as pe
from ...plotting import palette
from ...plotting.stitching import VIEW_COLOURS
from ...projective import map_points
from ...warp import canvas_bounds
from .._base import Demo, FigureView, build_demo, register
from ..controls import monospace


def _rgba(image: np.ndarray) -> np.ndarray:
    """An image as opaque uint8 RGBA: what Agg draws fastest (no conversion at every redraw)."""
    a = np.asarray(image)
    if a.dtype != np.uint8:
        a = np.clip(np.rint(a * 255), 0, 255).astype(np.uint8)
    out = np.empty((*a.shape[:2], 4), np.uint8)
    out[..., :3] = a[..., :3] if a.ndim == 3 else a[..., None]
    out[..., 3] = 255
    return out


# ----------------------------------------------------------------------------- canvas


def _frame(shape) -> np.ndarray:
    """The closed border polygon of an image of ``shape`` (pixel edges at -0.5 and w - 0.5)."""
    h, w = shape[:2]
    return np.array(
        [[-0.5, -0.5], [w - 0.5, -0.5], [w - 0.5, h - 0.5], [-0.5, h - 0.5], [-0.5, -0.5]]
    )


def _fit(shape, box) -> tuple[float, float, float]:
    r"""Scale and offset that draw an image of ``shape`` as large as fits in ``box``, centred.

    Canvas pixel :math:`(u, v)` is drawn at :math:`(o_x + s u,\ o_y + s v)` in the axes' units,
    whose limits are the box's pixel edges :math:`[-\tfrac12, B_w - \tfrac12] \times [-\tfrac12, B_h - \tfrac12]`.
    The image's edges :math:`u = -\tfrac12` and :math:`u = w - \tfrac12` land at
    :math:`(B_w - s w)/2 - \tfrac12` and :math:`(B_w + s w)/2 - \tfrac12`, so
    :math:`o_x = (B_w - s w)/2 - \tfrac12 + \tfrac{s}{2}` (likewise :math:`o_y`) with
    :math:`s = \min(B_w / w, B_h / h)`.

    The axes' limits stay those of the box whatever is shown (a live frame cannot change
    them: :class:`._base.FigureView`), so every canvas fills the axes instead of sitting in
    the corner of the largest one.

    Parameters
    ----------
    shape : (h, w) or (h, w, c) tuple
        The shown image's shape, pixels.
    box : (height, width) tuple
        The axes' box, in the axes' units.

    Returns
    -------
    s, ox, oy : float
    """
    hh, ww = shape[:2]
    bh, bw = box
    s = min(bw / ww, bh / hh)
    return s, (bw - s * ww) / 2 - 0.5 + s / 2, (bh - s * hh) / 2 - 0.5 + s / 2


def _fitted_extent(shape, box) -> tuple[float, float, float, float]:
    """The ``imshow`` extent (left, right, bottom, top) that :func:`_fit` gives an image of ``shape``."""
    s, ox, oy = _fit(shape, box)
    hh, ww = shape[:2]
    return ox - s / 2, ox + (ww - 0.5) * s, oy + (hh - 0.5) * s, oy - s / 2


def _fitted_points(points: np.ndarray, shape, box) -> np.ndarray:
    """(N, 2) canvas pixels (u, v) in the axes' units of :func:`_fit`."""
    s, ox, oy = _fit(shape, box)
    return np.asarray(points, float) * s + [ox, oy]


CANVAS_PAD = 9.0
"""Axes units of black beyond the box of a panorama's axes: its border outlines stay whole."""


def _outline_figure(box, lw: float, name: str, animate_legend: bool):
    """The figure of a panorama with each image's outline.

    The image, four outline lines keyed below the axes (over the animated panorama a key would be
    hidden by every live frame), no ticks, a title to animate, and the canvas's border (grey). Returns
    (view, ax, im, lines, legend, title, frame).
    """
    view = FigureView(figsize=(9, 3.6))
    ax = view.fig.subplots()
    im = view.animate(ax.imshow(np.zeros((10, 10, 3))))
    # thick colour on a thin dark edge (a white edge as wide as the line read white at display
    # size); view 3 dashed so that it stays apart from view 2 for every colour vision
    lines = [
        view.animate(
            ax.plot(
                [],
                [],
                color=c,
                lw=lw,
                ls=(0, (5, 2)) if k == 3 else "-",
                solid_joinstyle="round",  # no mitred spike past the canvas's frame at a sharp corner
                dash_joinstyle="round",
                path_effects=palette.halo(lw - 1.0, "black"),
                label=f"{name} {k}",
            )[0]
        )
        for k, c in enumerate(VIEW_COLOURS[:4])
    ]
    legend = ax.legend(
        handles=lines,
        loc="upper center",
        bbox_to_anchor=(0.5, 0.0),
        ncols=4,
        fontsize=8,
        title="outline of",
        title_fontsize=8,
    )
    if animate_legend:  # it goes with the outlines when they are switched off
        view.animate(legend)
    # a few units of black round the box: an outline on the canvas border is drawn whole, and the
    # bands beside a fitted canvas read as empty canvas, not as part of the page
    pad = CANVAS_PAD
    # the canvas's own border, grey: its empty (black) pixels stay apart from the black round it
    frame = view.animate(ax.plot([], [], color="0.6", lw=1.0, zorder=1.5)[0])
    ax.set(
        xlim=(-0.5 - pad, box[1] - 0.5 + pad),
        ylim=(box[0] - 0.5 + pad, -0.5 - pad),
        aspect="equal",
        facecolor="black",
    )
    ax.set_xticks([])
    ax.set_yticks([])
    title = view.animate(ax.set_title(" ", fontsize=9))
    return view, ax, im, lines, legend, title, frame


def _set_frame(frame, extent) -> None:
    """Draw the canvas's border 5 axes units outside the fitted image's extent (left, right, bottom, top).

    Outside it, the grey line lies on the black round the canvas, never on the image, and
    outside the thick outlines (with their halo) of photos that reach the canvas's edge.
    """
    x0, x1, y1, y0 = np.add(extent, [-5, 5, 5, -5])
    frame.set_data([x0, x1, x1, x0, x0], [y0, y0, y1, y1, y0])


@register(lesson="09", sweep={"reference": [0, 1, 3]})
def panorama_canvas() -> Demo:
    """Every image warped onto one canvas; the reference image decides the shape (and the stretch).

    Drawn from quarter-size thumbnails (160 x 120) so that even the widest canvas warps quickly;
    the title and the readout give the canvas size for the lesson's 320 x 240 photos (the same
    homographies' corners at full size, as section 4's worked example sizes it), and each canvas
    is scaled to fill the picture. The
    images are painted one after the other (overwrite) onto the canvas of the chosen
    reference (:func:`camlab.fixtures.panorama_examples.reference_canvases`).

    Returns
    -------
    Demo
        The demo: control ``reference`` (the image the others are mapped into; it starts at
        the match graph's best-connected image), the figure (the canvas scaled to fit, each
        image's outline, and a title with the canvas size and the display scale) and
        ``state`` (``reference``, ``canvas`` the canvas's (height, width) in quarter-size
        px, ``canvas_full`` its (height, width) for the 320 x 240 photos, ``T`` the translation into the canvas, ``display_scale`` the factor it is shown
        at).
    """
    graph = pe.panorama_graph()
    small, canvases = pe.reference_canvases()
    box = (300, 800)  # the axes' units: (height, width), about the shape the axes get
    view, ax, im, lines, _, title, frame = _outline_figure(
        box, lw=2.5, name="view", animate_legend=False
    )
    readout = W.HTML()
    shown = {ref: _rgba(c.panorama) for ref, c in canvases.items()}
    full_shapes = [im.shape for im in pe.panorama_example().images]  # the 320 x 240 photos
    full = {
        ref: canvas_bounds(pe.homographies_relative_to(graph, ref), full_shapes)[1]
        for ref in canvases
    }

    def update(v: dict, state: dict) -> None:
        ref = int(v["reference"])
        c = canvases[ref]
        im.set_extent(_fitted_extent(c.shape, box))
        _set_frame(frame, _fitted_extent(c.shape, box))
        im.set_data(shown[ref])
        hh, ww = c.shape
        for k, ln in enumerate(lines):
            p = _fitted_points(map_points(c.homographies[k], _frame(small[k].shape)), c.shape, box)
            ln.set_data(p[:, 0], p[:, 1])
        scale = _fit(c.shape, box)[0]
        fh, fw = full[ref]
        title.set_text(
            f"reference view {ref}: canvas {fw} x {fh} px for the 320 x 240 photos "
            "(drawn from 160 x 120 thumbnails), scaled to fit; grey frame: the canvas"
        )
        state.update(
            reference=ref, canvas=(hh, ww), canvas_full=(fh, fw), T=c.T, display_scale=scale
        )
        readout.value = monospace(
            f"reference view: {ref}\ncanvas for the 320 x 240 photos: {fw} x {fh} px\n"
            f"(the picture: 160 x 120 thumbnails on a {ww} x {hh} px canvas, translation T "
            f"({int(round(c.T[0, 2])):+d}, {int(round(c.T[1, 2])):+d}) px)\n"
            f"best-connected image: {graph.reference}"
        )

    controls = {
        "reference": W.IntSlider(
            value=graph.reference, min=0, max=len(small) - 1, description="reference"
        )
    }
    return build_demo(
        "panorama_canvas", controls, view, update, title="The panorama canvas", extra=[readout]
    )


# ----------------------------------------------------------------------------- blending


def _seam_marks(
    mask: np.ndarray, overlap: np.ndarray, rows: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The seam (where ``mask`` switches in or at ``overlap``) at the top and bottom sixth of ``rows``.

    Returns x and y for one Line2D: each mark's points, the two marks split by a NaN, so the cut between the
    marks (the data the seam's step is measured on) is left uncovered.
    """
    sixth = max(len(rows) // 6, 2)
    xs, ys = [], []
    for part in (rows[:sixth], rows[-sixth:]):
        for r in part:
            cols = np.flatnonzero(
                (mask[r, :-1] != mask[r, 1:]) & (overlap[r, :-1] | overlap[r, 1:])
            )
            if len(cols):
                if (
                    xs and abs(cols[0] + 0.5 - xs[-1]) > 3
                ):  # the seam left this row's run (an image's corner)
                    xs.append(np.nan)
                    ys.append(np.nan)
                xs.append(cols[0] + 0.5)
                ys.append(float(r))
        xs.append(np.nan)
        ys.append(np.nan)
    return np.array(xs), np.array(ys)


def _rows_inside(
    mask: np.ndarray, overlap: np.ndarray, rows: np.ndarray, u0: int, z: int
) -> np.ndarray:
    """The ``rows`` where the seam (``mask`` switching inside ``overlap``) lies in the zoom's columns ``u0 .. u0 + z - 1``.

    A diagonal seam enters and leaves a square zoom through any of its sides; marking the top and bottom sixth of
    these rows puts one mark where it enters and one where it leaves.
    """
    keep = []
    for r in rows:
        cols = np.flatnonzero((mask[r, :-1] != mask[r, 1:]) & (overlap[r, :-1] | overlap[r, 1:]))
        if len(cols) and u0 <= cols[0] < u0 + z - 1:
            keep.append(r)
    return np.array(keep, dtype=int)


def _seam_sharpness(image: np.ndarray, near: np.ndarray) -> float:
    """The RMS luminance gradient of ``image`` on the pixels ``near`` (per pixel, 0-1 units): detail kept."""
    gv, gu = np.gradient(image.mean(axis=2))
    return float(np.sqrt(np.mean((gu**2 + gv**2)[near])))


def _blend_readout(v: dict, gains, jump: float, scene: float, kept: float) -> str:
    """The blending demo's readout: the method, the gains, the seam's own step (grey levels), the detail kept."""
    multiband = v["method"] == "multiband"
    levels = int(v["levels"])
    offset = int(v["offset"])
    return monospace(
        f"registration error: view 2 moved {offset} px right\n"
        f"sharpness within 8 px of the seam: {100 * kept:.0f} % of the aligned blend's\n"
        f"blend: {v['method']}"
        + (
            f", {levels} pyramid level{'s' if levels != 1 else ''}"
            if multiband
            else " (pyramid levels: multiband only)"
        )
        + "\ngains: "
        + (", ".join(f"{g:.3f}" for g in gains) if v["gains"] else "off")
        + f"\nstep across the seam: {jump:.1f} grey levels\n"
        f"the scene's own step there: {scene:.1f}\n"
        + (
            "  (view 1 alone across overwrite's line, no seam)\n"
            if v["method"] == "overwrite"
            else "  (the mean of each view alone across the Voronoi seam, no seam)\n"
        )
        + _own_step_line(jump - scene, bool(v["gains"]))
    )


def _own_step_line(own: float, gains: bool) -> str:
    """The readout's last line: the seam's own step, "none" under half a grey level (noise)."""
    if abs(own) < 0.5:
        return f"the seam's own step: none ({own:+.1f}: under 0.5 grey level, noise)"
    return f"the seam's own step: {own:+.1f} (the step less the scene's" + (
        "; below 0: a step against the scene's, the gains overshoot at this line)"
        if own < 0 and gains
        else ")"
    )


def _blend_zoom(wi, seam: np.ndarray) -> tuple[int, int, int]:
    """(u0, v0, z): the blending demo's square zoom window, its top-left pixel and side.

    Overwrite's seam is the border of the image painted last, the others' the middle seam: one fixed
    window wide enough to hold both, so switching methods compares the same canvas pixels.
    """
    hh, ww = wi.shape
    row, z = hh // 2, 60

    def window(mask: np.ndarray) -> int:
        """The left column of a z-wide window centred where ``mask`` switches in the middle row."""
        cols = np.flatnonzero(np.diff(mask[row].astype(int)) != 0)
        c0 = int(cols[0]) if len(cols) else ww // 2
        return int(np.clip(c0 - z // 2, 0, ww - z))

    u1, u2 = window(wi.masks[1]), window(seam)
    z = int(min(ww, max(z, abs(u1 - u2) + z)))
    return int(np.clip(min(u1, u2), 0, ww - z)), int(np.clip(row - z // 2, 0, hh - z)), z


@register(
    lesson="09",
    sweep={
        "method": list(st.BLENDS),
        "gains": [False, True],
        # no "levels" sweep: the slider is disabled unless the method is multiband, so from the
        # default (overwrite) it would change nothing; the lesson renders method=multiband,levels=1
        "offset": [pe.OFFSETS[0], pe.OFFSETS[-1]],
    },
)
def blending_seams() -> Demo:
    """Overwrite, feather and multi-band blending of two differently exposed views, with a zoom on the seam.

    Images 1 and 2 of the half-size set on their common canvas
    (:func:`camlab.fixtures.panorama_examples.exposure_pair`), every blend the controls
    reach computed once (:func:`camlab.fixtures.panorama_examples.pair_blends`). The zoom
    window is fixed and wide enough to hold both the overwrite seam (the border of the
    image painted last) and the middle seam the other blends use, so switching methods
    compares the same canvas pixels.

    Returns
    -------
    Demo
        The demo: controls ``method`` (a blend of :data:`camlab.stitching.BLENDS`),
        ``gains`` (apply the exposure gains of gain compensation) and ``levels`` (the
        pyramid levels, 1-6; multi-band only, disabled otherwise), ``offset`` (a registration
        error: view 2 moved 0, 2, 4 or 8 px right, :func:`camlab.fixtures.panorama_examples.misregistered_pair`), the figure (the blended
        canvas with the zoom window outlined, and the zoom) and ``state`` (``method``,
        ``seam_jump`` the mean brightness step across the seam in grey levels 0-255,
        ``seam_own`` that step less the scene's own across the same line (one photo alone),
        ``image`` the blended canvas, (h, w, 3) floats in [0, 1], ``kept`` the RMS luminance gradient
        within 8 px of the seam as a fraction of the aligned blend's).

    References
    ----------
    .. [1] P. J. Burt and E. H. Adelson, 1983, "A multiresolution spline with application to
       image mosaics", *ACM Transactions on Graphics* 2(4), 217-236.
    .. [2] M. Brown and D. G. Lowe, 2007, "Automatic panoramic image stitching using invariant
       features", *International Journal of Computer Vision* 74(1), 59-73, sections 6 (gain
       compensation) and 7 (multi-band blending).
    .. [3] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022,
       section 8.4 (compositing).
    """
    wi, gains, seam = pe.exposure_pair()
    hh, ww = wi.shape
    u0, v0, z = _blend_zoom(wi, seam)
    view = FigureView(figsize=(9, 3.4))
    ax, ax_z = view.fig.subplots(1, 2, width_ratios=[2.2, 1])
    im = view.animate(ax.imshow(np.zeros((hh, ww, 3), np.float32), interpolation="nearest"))
    zoom_box = Rectangle((u0 - 0.5, v0 - 0.5), z, z, fill=False, color=palette.YELLOW, lw=1.5)
    view.animate(ax.add_patch(zoom_box))  # over the image
    ax.set_xticks([])
    ax.set_yticks([])
    title = view.animate(ax.set_title(" ", fontsize=9))
    imz = view.animate(ax_z.imshow(np.zeros((z, z, 3), np.float32), interpolation="nearest"))
    ax_z.set_xticks([])
    ax_z.set_yticks([])
    ax_z.set_title("zoom on the seam (white marks)", fontsize=9)
    # the seam each method's step is measured across, marked at both ends in the key's style (white, black edge)
    both = wi.masks[0] & wi.masks[1]
    overlap_rows = np.flatnonzero(both.any(axis=1))
    zoom_rows = np.arange(v0, v0 + z)
    seam_lines = [
        view.animate(
            a.plot([], [], color="white", lw=1.5, path_effects=palette.halo(3.0, "black"))[0]
        )
        for a in (ax, ax_z)
    ]
    seam_marks = {}
    for name, mask in (("overwrite", wi.masks[1]), ("middle", seam)):
        x, y = _seam_marks(mask, both, overlap_rows)
        xz, yz = _seam_marks(mask, both, _rows_inside(mask, both, zoom_rows, u0, z))
        seam_marks[name] = ((x, y), (xz - u0, yz - v0))
    readout = W.HTML()
    # every setting the controls can reach, blended once per registration error (pe.pair_blends)
    near = both & np.any([seam ^ np.roll(seam, k, axis=1) for k in range(-8, 9)], axis=0)
    cache = {}

    def blended(offset: int, key: tuple) -> tuple:
        """(image, rgba, step, scene step, own step, sharpness kept) of one setting, made on first use."""
        if (offset, key) not in cache:
            b, b0 = pe.pair_blends(offset)[key], pe.pair_blends(0)[key]
            kept = _seam_sharpness(b.image, near) / _seam_sharpness(b0.image, near)
            steps = 255 * np.array([b.seam_step, b.scene_step, b.seam_own])
            cache[(offset, key)] = (b.image, _rgba(b.image), *steps, kept)
        return cache[(offset, key)]

    def update(v: dict, state: dict) -> None:
        multiband = v["method"] == "multiband"
        # the pyramid belongs to multi-band blending only
        controls["levels"].disabled = not multiband
        key = (v["method"], bool(v["gains"]), int(v["levels"]) if multiband else 0)
        offset = int(v["offset"])
        out, rgba, jump, scene, own, kept = blended(offset, key)
        im.set_data(rgba)
        title.set_text(
            f"{_blend_name(v['method'], int(v['levels']))}: exposures 30% apart, "
            + (f"gains {gains[0]:.3f}, {gains[1]:.3f}" if v["gains"] else "before gains")
            + (f"; view 2 moved {offset} px" if offset else "")
        )
        imz.set_data(rgba[v0 : v0 + z, u0 : u0 + z])
        marks = seam_marks["overwrite" if v["method"] == "overwrite" else "middle"]
        for line, xy in zip(seam_lines, marks, strict=True):
            line.set_data(*xy)
        # jump: the exposure step across the seam, grey levels (overwrite: the last image's border)
        state.update(method=v["method"], seam_jump=jump, seam_own=own, image=out, kept=kept)
        readout.value = _blend_readout(v, gains, jump, scene, kept)

    controls = {
        "method": W.Dropdown(options=list(st.BLENDS), value="overwrite", description="blend"),
        "gains": W.Checkbox(value=False, description="gain compensation"),
        "levels": W.IntSlider(value=5, min=1, max=6, description="pyramid levels"),
        "offset": W.SelectionSlider(
            options=list(pe.OFFSETS),
            value=0,
            description="registration error (px)",
            style={"description_width": "initial"},
        ),
    }
    return build_demo("blending_seams", controls, view, update, title="Blending", extra=[readout])


# ----------------------------------------------------------------------------- full panorama


@register(
    lesson="09",
    sweep={"projection": ["planar", "cylindrical", "spherical"], "outlines": [True, False]},
)
def full_panorama() -> Demo:
    """The four-image panorama, planar, cylindrical or spherical, multi-band blended, with each image's footprint.

    Each panorama is scaled to fill the picture (the title gives its size in pixels). All three
    are stitched once by :func:`camlab.stitching.stitch`
    (:func:`camlab.fixtures.panorama_examples.stitched_panoramas`); the side panel lists
    every registered pair with its matches, inliers and verdict.

    Returns
    -------
    Demo
        The demo: controls ``projection`` (``"planar"``, ``"cylindrical"`` or ``"spherical"``) and
        ``outlines`` (draw each view's footprint and its key), the figure (the panorama
        scaled to fit, the footprints, and a title with the size, the reference view and
        the display scale) and ``state`` (``projection``, ``shape`` the panorama's
        (height, width) in px, ``reference`` the reference view, ``display_scale``,
        ``outlines_drawn`` the number of footprints drawn, ``legend`` whether their key
        shows).

    References
    ----------
    .. [1] M. Brown and D. G. Lowe, 2007, "Automatic panoramic image stitching using invariant
       features", *International Journal of Computer Vision* 74(1), 59-73.
    .. [2] P. J. Burt and E. H. Adelson, 1983, "A multiresolution spline with application to
       image mosaics", *ACM Transactions on Graphics* 2(4), 217-236.
    """
    pans = pe.stitched_panoramas()
    box = (300, 780)  # the axes' units: (height, width), about the shape the axes get
    view, ax, im, lines, legend, title, frame = _outline_figure(
        box, lw=2.5, name="view", animate_legend=True
    )
    readout = W.HTML()
    shown = {k: _rgba(p.panorama) for k, p in pans.items()}

    def update(v: dict, state: dict) -> None:
        r = pans[v["projection"]]
        hh, ww = r.panorama.shape[:2]
        im.set_extent(_fitted_extent((hh, ww), box))
        _set_frame(frame, _fitted_extent((hh, ww), box))
        im.set_data(shown[v["projection"]])
        for k, ln in enumerate(lines):
            if v["outlines"] and r.outlines[k] is not None:
                p = _fitted_points(np.vstack([r.outlines[k], r.outlines[k][:1]]), (hh, ww), box)
                ln.set_data(p[:, 0], p[:, 1])
            else:
                ln.set_data([], [])
        legend.set_visible(bool(v["outlines"]))
        scale = _fit((hh, ww), box)[0]
        title.set_text(
            f"{v['projection']} canvas: {ww} x {hh} px, reference view {r.reference}, scaled to fit; "
            "grey frame: the canvas"
        )
        state.update(
            projection=v["projection"],
            shape=(hh, ww),
            reference=r.reference,
            display_scale=scale,
            outlines_drawn=sum(len(ln.get_xdata()) > 0 for ln in lines),
            legend=legend.get_visible(),
        )
        rows = "\n".join(
            f"{p.i}-{p.j}: {p.matches:4d} matches {p.inliers:4d} inliers "
            + (
                f"rms {p.residual_rms:.2f} ok"
                if p.accepted
                else "rejected: " + p.reason.split(";")[0]
            )
            for p in r.pairs
        )
        readout.value = monospace(
            f"{v['projection']}: {ww} x {hh} px, reference {r.reference}\n"
            "stitch's own matching (FLANN): a few matches more or fewer\n"
            "than section 4's table (brute force)\n"
            f"{rows}"
        )

    controls = {
        "projection": W.Dropdown(
            options=["planar", "cylindrical", "spherical"], value="planar", description="projection"
        ),
        "outlines": W.Checkbox(value=True, description="image outlines"),
    }
    return build_demo(
        "full_panorama", controls, view, update, title="The panorama", extra=[readout]
    )


# ----------------------------------------------------------------------------- plane, cylinder, sphere

# (height, width) of canvas_projections' picture: within the 810 px of the other demos
BOX = (300, 780)


def _gallery() -> dict:
    """{(views, projection): (RGBA image or None, message)}.

    :func:`camlab.fixtures.panorama_examples.canvas_previews` placed in the demo's picture, with the
    text the demo shows.
    """
    gallery = {}
    for (n, proj), p in pe.canvas_previews(BOX).items():
        if p.image is None:
            gallery[(n, proj)] = (None, f"{n} views, {p.fov_deg:.0f} degrees of view: {p.reason}")
        else:
            gallery[(n, proj)] = (
                _place(_rgba(p.image)),
                f"{n} views, {p.fov_deg:.0f} degrees of view: {proj} canvas "
                f"{p.shape[1]} x {p.shape[0]} px "
                + (
                    "(shown scaled to fit)"
                    if proj == "planar"
                    else "(cylinder and sphere at one scale for 2-6 views)"
                ),
            )
    return gallery


def _place(rgba: np.ndarray) -> np.ndarray:
    """An RGBA image that fits in :data:`BOX`, placed in the middle of a black BOX (the empty canvas's colour).

    A grey frame 2 px wide, 3 px outside it, marks the canvas's border, as in the other canvas demos; where
    the canvas fills the box, that side's frame falls outside the box and is not drawn.
    """
    framed = np.full((rgba.shape[0] + 6, rgba.shape[1] + 6, 4), (0, 0, 0, 255), np.uint8)
    # 2 px wide: the demo shows the picture downsampled, which can drop a 1-px row
    framed[[0, 1, -2, -1], :, :3] = framed[:, [0, 1, -2, -1], :3] = 153
    framed[3:-3, 3:-3] = rgba
    out = np.full((*BOX, 4), (0, 0, 0, 255), np.uint8)
    (y0, x0), (cy, cx) = [
        np.maximum((np.subtract(BOX, framed.shape[:2]) * s) // 2, 0) for s in (1, -1)
    ]
    part = framed[cy : cy + BOX[0], cx : cx + BOX[1]]
    out[y0 : y0 + part.shape[0], x0 : x0 + part.shape[1]] = part
    return out


@register(
    lesson="09",
    sweep={"views": [2, 3, 4, 5, 6], "projection": ["planar", "cylindrical", "spherical"]},
)
def canvas_projections() -> Demo:
    """The same photos on a plane, a cylinder and a sphere as the turn grows (precomputed previews).

    The first 2-6 views of the 200-degree sweep
    (:func:`camlab.fixtures.panorama_examples.canvas_previews`), warped with their
    bundle-adjusted cameras onto each canvas. The cylinder and the sphere are drawn at one
    scale for every number of views (the six views' canvas fits :data:`BOX`), so the slider
    adds width and never changes the magnification; the plane is scaled to fit on its own.
    When the views span too wide a turn for a plane, the figure says so instead of showing
    a canvas.

    Returns
    -------
    Demo
        The demo: controls ``views`` (how many views, 2-6) and ``projection``
        (``"planar"``, ``"cylindrical"`` or ``"spherical"``), the figure (the canvas, or
        why there is none, under a title with the views' field of view and the canvas
        size) and ``state`` (``views``, ``projection``, ``failed`` True when the canvas
        cannot hold the views, ``shape`` the shown picture's (height, width) in px,
        :data:`BOX` with a canvas and None without).

    References
    ----------
    .. [1] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022,
       section 8.2 (image stitching: cylindrical and spherical coordinates).
    """
    gallery = _gallery()
    view = FigureView(figsize=(8.4, 3.4))
    ax = view.fig.subplots()
    blank = np.full((*BOX, 4), 255, np.uint8)
    im = view.animate(ax.imshow(blank, interpolation="nearest"))
    msg = view.animate(
        ax.text(
            0.5,
            0.5,
            "",
            transform=ax.transAxes,
            ha="center",
            va="center",
            fontsize=9,
            color="0.15",
            wrap=True,
        )
    )
    ax.set(xlim=(-0.5, BOX[1] - 0.5), ylim=(BOX[0] - 0.5, -0.5), aspect="equal")
    ax.set_xticks([])
    ax.set_yticks([])
    # the static picture has no side panel: which canvas, how many views and how wide, in the figure itself
    title = view.animate(ax.set_title(" ", fontsize=9))
    readout = W.HTML()

    def update(v: dict, state: dict) -> None:
        img, text = gallery[(v["views"], v["projection"])]
        title.set_text(
            text.split(": ", 1)[0]
            + (f": no {v['projection']} canvas" if img is None else ": " + text.split(": ", 1)[1])
        )
        if img is None:
            im.set_data(blank)
            msg.set_text("the plane cannot hold this turn:\n" + text.split(": ", 1)[1])
        else:
            im.set_data(img)
            msg.set_text("")
        readout.value = monospace(text)
        state.update(
            views=v["views"],
            projection=v["projection"],
            failed=img is None,
            shape=None if img is None else img.shape[:2],
        )

    controls = {
        "views": W.IntSlider(value=3, min=2, max=6, description="views"),
        "projection": W.Dropdown(
            options=["planar", "cylindrical", "spherical"],
            value="cylindrical",
            description="canvas",
        ),
    }
    return build_demo(
        "canvas_projections",
        controls,
        view,
        update,
        title="Plane, cylinder, sphere",
        extra=[readout],
    )


# ----------------------------------------------------------------------------- parallax


EDGE_RGB = tuple(
    tuple(int(round(255 * c)) for c in to_rgb(colour)) for colour in (palette.BLUE, palette.ORANGE)
)
"""The edges of view 0 and view 1 in the parallax demo: the lesson's colours of views 0 and 1."""


def _with_edges(rgba: np.ndarray, edges) -> np.ndarray:
    """Paint view 0's edges blue and view 1's orange (white where both) onto an RGBA image.

    The blend under them is turned to a dimmed grey and every edge gets a one-pixel black rim,
    so blue reads on the portrait's blue backdrop and white on the bright wall (K12).
    """
    if edges is None:
        return rgba
    from scipy import ndimage

    out = rgba.copy()
    e0, e1 = edges
    grey = out[..., :3].astype(float).mean(axis=2, keepdims=True)
    out[..., :3] = np.rint(60 + 0.5 * grey).astype(
        out.dtype
    )  # 60-188: no colour left to hide an edge
    rim = ndimage.binary_dilation(e0 | e1) & ~(e0 | e1)
    out[rim, :3] = 0
    out[e0 & ~e1, :3] = EDGE_RGB[0]
    out[e1 & ~e0, :3] = EDGE_RGB[1]
    out[e0 & e1, :3] = 255
    return out


# the parallax demo's axes in its units, (height, width): every baseline's canvas is scaled to fill it
PARALLAX_BOX = (280, 460)


def _parallax_figure(view: FigureView) -> SimpleNamespace:
    """The figure of :func:`parallax_ghosting`.

    The blend in axes of :data:`PARALLAX_BOX`, its title and the key to the edges' colours beside
    it (a hint in its place while the edges are off); returns ``im``, ``title``, ``legend`` and
    ``hint`` (registered with ``view`` in that order).
    """
    box = PARALLAX_BOX
    ax = view.fig.subplots()
    # the layout ignores the hidden legend: a strip under the picture keeps its room at every
    # setting, and the figure is as wide as the picture (no blank column beside it)
    view.fig.set_layout_engine(None)
    view.fig.subplots_adjust(left=0.01, right=0.99, top=0.9, bottom=0.11)
    ax.set_anchor("N")
    im = view.animate(
        ax.imshow(np.zeros((10, 10, 3)), interpolation="nearest")
    )  # one-pixel edges stay crisp
    # black round the fitted canvas, as the canvas' own empty pixels (no white slivers)
    ax.set(xlim=(-0.5, box[1] - 0.5), ylim=(box[0] - 0.5, -0.5), aspect="equal", facecolor="black")
    ax.set_xticks([])
    ax.set_yticks([])
    title = view.animate(ax.set_title(" ", fontsize=9))
    key = [
        Patch(facecolor=np.array(c) / 255, edgecolor="0.3", label=t)
        for c, t in (
            (EDGE_RGB[0], "edge in view 0 only"),
            (EDGE_RGB[1], "edge in view 1 only"),
            ((255, 255, 255), "edge in both"),
        )
    ]
    # under the picture, not over it; shown only while the edges are painted
    legend = view.animate(
        ax.legend(
            handles=key,
            loc="upper center",
            bbox_to_anchor=(0.5, -0.01),
            ncols=3,
            fontsize=8,
            title="edges",
            title_fontsize=8,
            facecolor="0.55",
        )
    )
    # in the legend's place while the edges are off: what the strip is for
    hint = view.animate(
        ax.text(
            0.5,
            -0.04,
            'tick "both views\' edges" to colour the edges each view sees',
            transform=ax.transAxes,
            ha="center",
            va="top",
            fontsize=8,
            color="0.3",
        )
    )
    return SimpleNamespace(im=im, title=title, legend=legend, hint=hint)


def _blend_name(method: str, levels: int = 5) -> str:
    """The blend ``method`` as a panel title names it, with the pyramid ``levels`` of multi-band."""
    if method == "multiband":
        return f"multi-band, {levels} pyramid level{'s' if levels != 1 else ''}"
    return {"feather": "feathering"}.get(method, method)


def _parallax_texts(
    b: float, n: int, k: int, rms: float, diff: float, edges: bool, method: str = "multiband"
) -> tuple[str, str]:
    """The title and the readout of :func:`parallax_ghosting` for a move of ``b`` m.

    ``k`` of ``n`` matches inliers, their RMS ``rms`` px, the mean misalignment ``diff`` grey
    levels, what the edges mean when they are shown, and the blend ``method`` (multi-band with
    :func:`camlab.stitching.blend`'s default 5 levels).
    """
    title = (
        f"{_blend_name(method)}, camera moved {100 * b:.0f} cm: {k} of {n} matches fit one homography\n"
        f"mean |view 0 - view 1| on the overlap {diff:.1f} grey levels"
    )
    readout = monospace(
        f"camera moved {100 * b:.0f} cm\nmatches: {n}\n"
        f"inliers: {k} ({100 * k / max(n, 1):.0f}%)\noutliers: {n - k} "
        + (
            "(no parallax at 0 cm: wrong matches)\n"
            if b == 0
            else "(wrong matches and parallax:\n  near objects off the wall's H)\n"
        )
        + f"inlier RMS: {rms:.2f} px\n"
        f"mean |view 0 - view 1| on the overlap:\n  {diff:.1f} grey levels\n"
        + (
            "edges of the two warped views (not of the blend):\n"
            "  blue = view 0, orange = view 1, white where they agree"
            if edges
            else "edges: off"
        )
    )
    return title, readout


def _parallax_controls() -> dict:
    """The controls of :func:`parallax_ghosting`: the baseline (m), the blend and the edges' toggle."""
    return {
        "baseline": W.SelectionSlider(
            options=list(pe.BASELINES), value=0.2, description="baseline (m)"
        ),
        "method": W.Dropdown(
            options=["feather", "multiband"], value="feather", description="blend"
        ),
        "edges": W.Checkbox(value=False, description="both views' edges"),
    }


@register(
    lesson="09",
    sweep={
        "baseline": list(pe.BASELINES[::2]),
        "method": ["feather", "multiband"],
        "edges": [True, False],
    },
)
def parallax_ghosting() -> Demo:
    """Move the camera sideways between shots: near objects no longer fit the homography and ghost.

    A room seen by a camera turned -16 degrees and by one turned -4 degrees whose centre
    moved ``baseline`` metres to the right
    (:func:`camlab.fixtures.panorama_examples.parallax_pairs`): view 1 is registered onto
    view 0 by RANSAC, which locks onto the dominant plane (the back wall), and the two are
    blended. The edges of each warped view can be painted over the blend: blue for view 0,
    orange for view 1, white where they agree.

    Returns
    -------
    Demo
        The demo: controls ``baseline`` (the sideways move, m, one of
        :data:`camlab.fixtures.panorama_examples.BASELINES`), ``method`` (``"feather"`` or
        ``"multiband"``) and ``edges`` (paint both views' edges and show their key), the
        figure (the blend scaled to fit, under a title with the inliers and the
        misalignment) and ``state`` (``baseline`` in m, ``edges``, ``inlier_fraction`` the
        share of the matches that fit the homography, ``residual_rms`` the inliers' RMS
        transfer error in px, ``misalignment`` the mean |view 0 - view 1| on the overlap in
        grey levels 0-255, ``method``, ``image`` the blend).
    """
    pairs = pe.parallax_pairs()
    view = FigureView(figsize=(6.4, 4.8))  # the picture fills the width: see _parallax_figure
    art = _parallax_figure(view)
    readout = W.HTML()

    shown = {
        (b, m, e): _with_edges(_rgba(out), p.edges if e else None)
        for b, p in pairs.items()
        for m, out in p.blends.items()
        for e in (False, True)
    }

    def update(v: dict, state: dict) -> None:
        b = float(v["baseline"])
        p = pairs[b]
        wi, reg, out = p.warped, p.registration, p.blends[v["method"]]
        hh, ww = wi.shape
        art.im.set_extent(_fitted_extent((hh, ww), PARALLAX_BOX))
        art.im.set_data(shown[(b, v["method"], bool(v["edges"]))])
        art.legend.set_visible(bool(v["edges"]))
        art.hint.set_visible(not v["edges"])
        n, k = len(reg.matches.src), int(reg.inliers.sum())
        diff = 255 * p.misalignment
        title, readout.value = _parallax_texts(
            b, n, k, reg.residual_rms, diff, bool(v["edges"]), v["method"]
        )
        art.title.set_text(title)
        state.update(
            baseline=b,
            edges=bool(v["edges"]),
            inlier_fraction=k / max(n, 1),
            residual_rms=reg.residual_rms,
            misalignment=diff,
            method=v["method"],
            image=out,
        )

    return build_demo(
        "parallax_ghosting",
        _parallax_controls(),
        view,
        update,
        title="Parallax makes ghosts",
        extra=[readout],
    )
