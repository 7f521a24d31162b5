"""Demos for lesson 10, perspective correction.

The photos are synthetic (``camlab.scenes.sample_photo``): a textured rectangle
seen at an angle through a plane-induced homography, so the true corners and aspect
ratio are known. Corners are dragged with the mouse under ipympl, moved one at a time with
the keyboard (a corner dropdown and two sliders), or typed into the corners text control
``"u0, v0; u1, v1; u2, v2; u3, v3"`` (TL, TR, BR, BL).
"""

from __future__ import annotations

import textwrap
from types import SimpleNamespace
from typing import Any

import ipywidgets as W
import numpy as np

from .. import perspective as pp
from .. import scenes
from ..plotting import palette
from ._base import Demo, FigureView, build_demo, register, slider
from .controls import (
    connect_corner_drag,
    corner_keys,
    corner_text,
    format_corners,
    monospace,
    parse_corners,
)

_SHOW = 260  # the rectified view is drawn into a _SHOW x _SHOW box


def _fit(size_wh: tuple[int, int]) -> tuple[int, int]:
    """Scale (width, height) to fit in the display box, keeping the ratio."""
    w, h = size_wh
    s = (_SHOW - 1) / max(w, h)
    return max(2, int(round(w * s))), max(2, int(round(h * s)))


def _show_rectified(
    im: Any, image: np.ndarray, quad: np.ndarray, size_wh: tuple[int, int]
) -> np.ndarray:
    """Rectify ``quad`` into a rectangle of ratio size_wh, drawn centred in the display box."""
    w, h = _fit(size_wh)
    r = pp.rectify_quadrilateral(image, quad, size=(w, h), method="cv2")
    box = np.full((_SHOW, _SHOW, 3), 255, np.uint8)
    y0, x0 = (_SHOW - h) // 2, (_SHOW - w) // 2
    box[y0 : y0 + h, x0 : x0 + w] = r.image
    im.set_data(box)
    return r.H


_PHOTO_DISPLAY = (440, 330)  # about the photo axes' size on screen, in pixels


def _set_photo(im: Any, image: np.ndarray) -> None:
    """Show a 640x480 photo, downsampled once to screen size.

    Matplotlib then draws it nearly 1:1, twice as fast; the extent keeps the axes in photo pixel
    coordinates.
    """
    import cv2

    im.set_data(
        cv2.resize(np.ascontiguousarray(image), _PHOTO_DISPLAY, interpolation=cv2.INTER_AREA)
    )


def _photo_demo(photo_title: str, result_title: str, outline: dict):
    """The figure every lesson-10 demo uses: the photo (with an outline artist) and the result."""
    view = FigureView(figsize=(9, 4.2))
    ax_p, ax_r = view.fig.subplots(1, 2, width_ratios=[1.35, 1])
    im_p = view.animate(
        ax_p.imshow(
            np.zeros((_PHOTO_DISPLAY[1], _PHOTO_DISPLAY[0], 3), np.uint8),
            extent=(-0.5, 639.5, 479.5, -0.5),
            interpolation="nearest",
        )
    )
    ax_p.set(xlim=(-0.5, 639.5), ylim=(479.5, -0.5))
    ax_p.set_xlabel("u (px, right)", fontsize=8, labelpad=1)
    ax_p.set_ylabel("v (px, down)", fontsize=8, labelpad=1)
    ax_p.tick_params(labelsize=7)
    im_r = view.animate(
        ax_r.imshow(np.full((_SHOW, _SHOW, 3), 255, np.uint8), interpolation="nearest")
    )
    ax_r.set(xlim=(-8.5, _SHOW + 7.5))  # a margin: the box never touches the figure's edge
    ax_r.set_axis_off()
    ax_p.set_title(photo_title, fontsize=10, pad=3)
    ax_r.set_title(result_title, fontsize=10, pad=3)
    line = view.animate(ax_p.plot([], [], **outline)[0])
    return view, ax_p, ax_r, im_p, im_r, line


def _why_text(view: FigureView, ax: Any) -> Any:
    """A red message centred on ``ax``, animated: why there is no result (a static picture has no readout)."""
    return view.animate(
        ax.text(
            0.5,
            0.5,
            "",
            transform=ax.transAxes,
            ha="center",
            va="center",
            fontsize=9,
            wrap=True,
            color=palette.RED,
        )
    )


_OUTLINE_STYLE = "--"  # the corners' outline on the photo, yellow
_KEY = "brown dashed: the other focal length's shape\ngreen dotted: the true shape"
_KEY_OFF_PAGE = (
    "brown dashed: the other focal length's shape\nno green: these are not the scene's corners"
)


def _key_text(on_page: bool, focal_source: str) -> str:
    """The rectify demo's key: in an affine view (f cancels) the brown outline is the same shape."""
    key = _KEY if on_page else _KEY_OFF_PAGE
    if focal_source == "not needed":  # both focal-length choices give one shape
        key = key.replace("the other focal length's shape", "the same shape (f cancels)")
    return key


_SCAN_KEY = "green dotted: the page's true shape (A4)"
_ON_PAGE_PX = 10.0  # corners this close to the scene's true ones still mark its rectangle


def _rectify_artists(view: FigureView, ax_p: Any, ax_r: Any) -> SimpleNamespace:
    """The artists :func:`rectify_photo` adds to the photo demo's figure.

    The corner handles, the chosen corner's ring, the key, the other focal length's and the true
    shape's outlines.
    """
    handles = view.animate(
        ax_p.plot([], [], "o", color=palette.ORANGE, ms=9, mec="k", path_effects=palette.halo(1))[0]
    )  # the halo keeps them visible on the dark desk and on the white page alike
    chosen = view.animate(
        ax_p.plot(
            [],
            [],
            "o",
            ms=16,
            mfc="none",
            mec="k",
            mew=2,  # the corner the keys move
            path_effects=palette.halo(2),
        )[0]
    )
    # the key (one line, ~4 ms per redraw), animated so that it goes with the outlines it explains
    key = view.animate(
        ax_r.text(
            0.5,
            -0.02,
            _KEY,
            transform=ax_r.transAxes,
            ha="center",
            va="top",
            fontsize=8,
        )
    )
    other = view.animate(
        ax_r.plot([], [], "--", color=palette.BROWN, lw=1.5, path_effects=palette.halo(1.5))[0]
    )
    truth_box = _truth_artist(view, ax_r, None)
    view.animate(ax_r.title)  # says which focal length the rectified view uses
    why = _why_text(view, ax_r)  # why the corners cannot be rectified
    return SimpleNamespace(
        handles=handles, chosen=chosen, other=other, truth_box=truth_box, why=why, key=key
    )


def _show_invalid(
    art: SimpleNamespace, quad: Any, im_r: Any, ax_r: Any, text: str, k: int, exc: Exception
) -> None:
    """Draw corners that cannot be rectified (a bow tie, a dent) in red and blank the rectified view."""
    try:
        corners = parse_corners(text)
    except ValueError:
        corners = None
    if corners is not None:
        _show_corners(quad, art.handles, art.chosen, corners, k)
    quad.set(color=palette.RED, linestyle="-")  # red means refused, in every lesson-10 demo
    art.key.set_text("")  # no outlines to explain
    im_r.set_data(np.full((_SHOW, _SHOW, 3), 255, np.uint8))
    for line in (art.other, art.truth_box):
        line.set_data([], [])
    ax_r.set_title("not rectified", fontsize=10, pad=3)
    art.why.set_text("cannot rectify these corners (red, solid):\n" + textwrap.fill(str(exc), 44))


def _show_shapes(im: Any, photo: Any, corners: np.ndarray, ratio: float, outlines) -> None:
    """The rectified view of ``corners`` at width/height ``ratio``, and ``outlines``.

    The view is as wide as the quadrilateral's wider horizontal side; ``outlines`` ((artist, ratio)
    pairs) are the rectangles other ratios would give, in the display box.
    """
    width = max(np.linalg.norm(corners[1] - corners[0]), np.linalg.norm(corners[2] - corners[3]))
    shown = _size_for(width, ratio)
    _show_rectified(im, photo.image, corners, shown)
    # Outlines, in the display box, of the rectangle the other focal length and the truth would give.
    for artist, other in outlines:
        if other is None:  # not drawn
            artist.set_data([], [])
        else:
            _box_outline(artist, _size_for(width, other), shown)


def _truth_artist(view: FigureView, ax_r: Any, key: str | None) -> Any:
    """The green dotted outline of the true shape on the result panel (and its static ``key`` line)."""
    if key:
        ax_r.text(0.5, -0.02, key, transform=ax_r.transAxes, ha="center", va="top", fontsize=8)
    return view.animate(
        ax_r.plot([], [], ":", color=palette.GREEN, lw=2.2, path_effects=palette.halo(1.5))[0]
    )


def _size_for(width: float, ratio: float) -> tuple[int, int]:
    """(width, height) of ratio w/h between corner-pixel centres: h = round((w - 1) / ratio) + 1."""
    w = max(2, int(round(width)))
    return w, int(round((w - 1) / ratio)) + 1


def _box_outline(artist: Any, size_wh: tuple[int, int], like: tuple[int, int]) -> None:
    """Outline the shape ``size_wh`` over the rectified view drawn at ``like`` (its size_wh).

    The outline shares the view's top-left corner and its longer side, so a wrong ratio shows
    as one gap, at the bottom or the right edge, not split in two halves.
    """
    w, h = _fit(like)
    x0, y0 = (_SHOW - w) // 2 - 0.5, (_SHOW - h) // 2 - 0.5
    ratio = size_wh[0] / size_wh[1]
    if w >= h:
        h = w / ratio
    else:
        w = h * ratio
    artist.set_data([x0, x0 + w, x0 + w, x0, x0], [y0, y0, y0 + h, y0 + h, y0])


def _focal_text(est: Any, true_focal: float) -> str:
    """How the focal length behind a ratio was found, for a readout."""
    f = "" if est.focal_length is None else f"{est.focal_length:.0f} px"
    return {
        "assumed": f"f assumed {f}, the image width (true {true_focal:.0f}): the corners give\n"
        "none (an edge pair parallel in the photo, or f\u00b2 \u2264 0)",
        "estimated": f"f estimated {f} from the corners (true {true_focal:.0f})",
        "given": f"f given {f}",
        "not needed": "f not needed (an affine view)",
    }[est.focal_source]


_SLIP_PX = 5.0  # how far a hand click is off, in the readout's sensitivity line


def _corner_slip_range(corners: np.ndarray, image_shape: tuple, focal_length: float) -> dict:
    """The spread of w/h (and of f from the corners) when one corner slips by 5 px, either axis.

    The 16 quadrilaterals with one corner moved by +-5 px in u or in v; for each, the ratio with f
    from the corners and with ``focal_length`` given. Returns ``ratio_from_quad``, ``ratio_known``
    and ``focal`` as (min, max) pairs; the lesson prints the same numbers (section 3).
    """
    from_quad, known, focal = [], [], []
    for k in range(4):
        for step in ((_SLIP_PX, 0), (-_SLIP_PX, 0), (0, _SLIP_PX), (0, -_SLIP_PX)):
            q = np.array(corners, dtype=float)
            q[k] += step
            est = pp.estimate_aspect_ratio(q, image_shape)
            from_quad.append(est.ratio)
            focal.append(est.focal_length)
            known.append(pp.estimate_aspect_ratio(q, image_shape, focal_length=focal_length).ratio)
    return {
        "ratio_from_quad": (min(from_quad), max(from_quad)),
        "ratio_known": (min(known), max(known)),
        "focal": (min(focal), max(focal)),
    }


def _rectify_readout(
    est: Any, used: str, from_quad: Any, known: Any, photo: Any, slip: dict, on_page: bool = True
) -> str:
    """The text beside :func:`rectify_photo`.

    The ratio shown, the ratios with f from the corners, with f known and the true one, how f was
    found, and how far a 5 px slip of one of the scene's exact corners moves each ratio.
    """
    f_true = photo.K[0, 0]
    quad_f = _focal_used(False, photo, from_quad)
    (a, b), (c, d), (f0, f1) = slip["ratio_from_quad"], slip["ratio_known"], slip["focal"]
    true = (
        f"w/h true:{'':27s} {photo.aspect:.3f}"
        if on_page  # else the scene's rectangle is not the one these corners mark
        else f"w/h true: unknown (the scene's {photo.aspect:.3f} is not these corners' shape)"
    )
    return monospace(
        f"shown: w/h {est.ratio:.3f}, rectified with {used}\n"
        f"w/h with {quad_f + ':':27s} {from_quad.ratio:.3f}\n"
        f"w/h with {f'f known ({f_true:.0f} px):':27s} {known.ratio:.3f}\n"
        f"{true}\n"
        f"{_focal_text(from_quad, f_true)}\n"
        f"this scene, one exact corner {_SLIP_PX:.0f} px off: f from the corners {f0:.0f}-{f1:.0f} px,\n"
        f"  w/h {a:.3f}-{b:.3f} with it, {c:.3f}-{d:.3f} with f known"
    )


def _focal_conditioning(corners: np.ndarray, image_shape: tuple) -> tuple[str, bool]:
    """A readout line: how far f from the corners moves when one corner moves by 1 px.

    Near a degenerate view (an edge pair nearly parallel in the photo, its vanishing point far
    away) f^2 is a ratio of two small numbers, so the scanner's 1-2 px corner errors decide it.
    Returns the line and whether f is then NOT DETERMINED: a 1 px slip gives no f at all
    (f^2 <= 0), or the slips' f span more than half of f.
    Empty when f is not estimated from the corners.
    """
    est = pp.estimate_aspect_ratio(corners, image_shape)
    if est.focal_source != "estimated":
        return "", False
    slipped = [
        pp.estimate_aspect_ratio(corners + np.eye(4)[k][:, None] * step, image_shape)
        for k in range(4)
        for step in ((1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0))
    ]
    # only the slips that still give an f: the others fall back to the assumed f, no estimate
    fs = [e.focal_length for e in slipped if e.focal_source == "estimated"]
    before, after = corners[[1, 3]] - corners[[0, 0]], corners[[2, 2]] - corners[[3, 1]]
    cos = (
        np.abs((before * after).sum(1))
        / np.linalg.norm(before, axis=1)
        / np.linalg.norm(after, axis=1)
    )
    least = float(np.degrees(np.arccos(np.clip(cos, -1, 1))).min())
    none = len(slipped) - len(fs)
    line = "\none corner 1 px off (16 ways): " + (
        f"f from the corners {min(fs):.0f}-{max(fs):.0f} px" if fs else "no f at all"
    )
    if none and fs:
        line += f";\n  {none} of the 16 give no f at all (f\u00b2 \u2264 0)"
    if fs and not none and max(fs) - min(fs) <= 0.5 * est.focal_length:
        return line, False
    assumed = max(image_shape[0], image_shape[1])
    rule = (
        f"{none} of 16 slips give no f"
        if none
        else f"the slips' f span {max(fs) - min(fs):.0f} px > f/2"
    )
    return line + (
        f"\nf NOT DETERMINED ({rule}): an edge pair converges by\n"
        f"only {least:.1f}\u00b0, so the {est.focal_length:.0f} px the corners give is corner noise (section 3);\n"
        f"the scan uses f assumed {assumed} px (the image width) instead"
    ), True


def _scan_estimate(corners: np.ndarray, image_shape: tuple):
    """The scanner's w/h: f from the corners, or the assumed f when the corners do not determine it.

    Returns the estimate, the readout's conditioning line and whether f was NOT DETERMINED.
    """
    est = pp.estimate_aspect_ratio(corners, image_shape)
    conditioning, undetermined = _focal_conditioning(corners, image_shape)
    if undetermined:  # f from the corners is noise: fall back to the assumed f, and say so
        f_assumed = float(max(image_shape[:2]))
        ratio = pp.estimate_aspect_ratio(corners, image_shape, focal_length=f_assumed).ratio
        est = pp.AspectRatio(ratio, f_assumed, "assumed")
    return est, conditioning, undetermined


def _widest_angle(corners: np.ndarray) -> float:
    """The quadrilateral's largest interior angle, degrees (180 when three corners are in a line)."""
    before, after = np.roll(corners, 1, axis=0) - corners, np.roll(corners, -1, axis=0) - corners
    cos = (before * after).sum(1) / np.linalg.norm(before, axis=1) / np.linalg.norm(after, axis=1)
    return float(np.degrees(np.arccos(np.clip(cos, -1, 1))).max())


def _new_photo(current: dict, scene: str, im: Any, control: W.Text) -> str:
    """Switch :func:`rectify_photo` to ``scene``'s photo.

    Show it, put its true corners in the corners control (``current["busy"]`` keeps that from
    starting a second update) and return them as text.
    """
    current["scene"], current["photo"] = scene, scenes.sample_photo(scene)
    _set_photo(im, current["photo"].image)
    text = format_corners(current["photo"].corners)
    if text != control.value:
        current["busy"] = True
        control.value = text
        current["busy"] = False
    return text


def _show_corners(quad: Any, handles: Any, chosen: Any, corners: np.ndarray, k: int) -> None:
    """The quadrilateral's outline, its corner handles and the ring on corner ``k``."""
    closed = np.vstack([corners, corners[:1]])
    quad.set_data(closed[:, 0], closed[:, 1])
    quad.set(
        color=palette.YELLOW, linestyle=_OUTLINE_STYLE
    )  # red, solid when invalid: _show_invalid
    handles.set_data(corners[:, 0], corners[:, 1])
    chosen.set_data(corners[k, :1], corners[k, 1:])


def _rectify_controls(control: W.Text, keys: dict) -> dict:
    """The controls of :func:`rectify_photo`.

    The photo, the corners' text, the known-focal checkbox and the corner the keys move (taken out
    of ``keys``).
    """
    return {
        "scene": W.Dropdown(
            options=["page", "painting", "facade"], value="page", description="photo"
        ),
        "corners": control,
        "use_focal": W.Checkbox(value=False, description="use the known focal length (800 px)"),
        "corner": keys.pop("corner"),
    }


def _focal_used(use_focal: bool, photo, from_quad) -> str:
    """Which f :func:`rectify_photo` rectified with, as its title and readout name it."""
    if use_focal:
        return f"known f ({photo.K[0, 0]:.0f} px)"
    if from_quad.focal_source == "assumed":
        return f"f assumed, {from_quad.focal_length:.0f} px"
    if from_quad.focal_source == "not needed":
        return "no f (affine: f cancels)"
    return "f from the corners"


def _warn_if_skewed(text: str, corners: np.ndarray, from_quad: Any) -> str:
    """The readout ``text``, warned when both edge pairs are parallel but the corners are not right angles.

    Both vanishing points at infinity put the vanishing line at infinity: the plane faces the
    camera, and with square pixels a rectangle then photographs as a rectangle, not a skewed
    parallelogram.
    """
    off = abs(_widest_angle(corners) - 90.0)
    if from_quad.focal_source != "not needed" or off <= 1.0:
        return text
    return (
        f"careful: both edge pairs are parallel, yet the corners are {off:.0f}° off a right\n"
        "angle: a plane facing the camera shows a rectangle as a rectangle, so no\n"
        "rectangle projects to these corners (square pixels); the ratio is meaningless\n" + text
    )


def _warn_if_flat(text: str, corners: np.ndarray) -> str:
    """The readout ``text``, warned when a corner angle over 160° puts three corners nearly in a line."""
    widest = _widest_angle(corners)
    if widest <= 160:
        return text
    return text.replace(
        "shown:",
        f"careful: a corner angle of {widest:.0f}°, three corners nearly in a line;\n"
        "the ratio then means little\nshown:",
        1,
    )


_RECTIFY_SWEEP = {
    "scene": ["page", "painting", "facade"],
    "corners": [
        "250.0, 120.0; 420.0, 140.0; 400.0, 380.0; 230.0, 350.0",
        "250.0, 120.0; 420.0, 140.0; 230.0, 350.0; 400.0, 380.0",  # a bow tie: refused
        "250.0, 120.0; 420.0, 140.0; 300.0, 200.0; 230.0, 350.0",  # a dent: refused
        "200.0, 100.0; 450.0, 100.0; 500.0, 380.0; 250.0, 380.0",  # sheared: no rectangle's photo
        # a valid quad last: the sweeps of the other controls start where this one ends
        "200.0, 100.0; 450.0, 100.0; 450.0, 380.0; 200.0, 380.0",
    ],
    "use_focal": [True, False],
    "corner": [3, 0],
    "corner_u": [100.0, 300.0],
    "corner_v": [50.0, 250.0],
}
"""The settings the review renders: each scene, a few corners (three refused), the checkbox."""


@register(lesson="10", sweep=_RECTIFY_SWEEP)
def rectify_photo() -> Demo:
    """Drag the four corners of a page, painting or facade; the rectified view follows.

    The view is sized by the aspect ratio estimated from the quadrilateral (compared with the
    truth). Without a mouse, pick a corner and move it with its two sliders (or type the
    corners).

    Returns
    -------
    Demo
        The demo: controls ``scene`` (page, painting or facade), ``corners`` (the text
        ``"u0, v0; u1, v1; u2, v2; u3, v3"``, TL, TR, BR, BL, px), ``use_focal`` (rectify with
        the known f instead of f from the corners) and ``corner`` (the corner its linked
        ``corner_u`` and ``corner_v`` sliders move), the figure (the photo with the dragged
        quadrilateral, the rectified view with the other f's and the true shape) and
        ``state`` (``ratio`` w/h shown, ``true_ratio``, ``focal`` in px and ``focal_source``,
        ``ratio_from_quad``, ``ratio_known_focal``, ``focal_from_quad``, ``corners``,
        ``corner``, ``scene``, ``error``: the message when the corners cannot be rectified).
        ``handlers`` holds the mouse handlers of the corner drag.
    """
    view, ax_p, ax_r, im_p, im_r, quad = _photo_demo(
        "photo: drag the orange corners",
        "rectified",
        dict(
            ls=_OUTLINE_STYLE, color=palette.YELLOW, lw=1.5, path_effects=palette.halo(1.5, "black")
        ),
    )
    art = _rectify_artists(view, ax_p, ax_r)
    handles, chosen, other, truth_box = art.handles, art.chosen, art.other, art.truth_box
    readout = W.HTML()
    first = scenes.sample_photo("page")
    control = corner_text(format_corners(first.corners), "corners (TL; TR; BR; BL)")
    keys = corner_keys(control, ("top left", "top right", "bottom right", "bottom left"), 639, 479)
    current: dict[str, Any] = dict(scene=None, photo=None, corners=first.corners, busy=False)
    slips: dict[str, dict] = {}

    def update(v: dict, state: dict) -> None:
        if current["busy"]:
            return
        if v["scene"] != current["scene"]:  # a new photo: start from its true corners
            v = {**v, "corners": _new_photo(current, v["scene"], im_p, control)}
        photo = current["photo"]
        try:
            parsed = parse_corners(v["corners"])
            if v["corners"] == format_corners(photo.corners):  # the text rounds to 0.01 px:
                parsed = photo.corners  # while it shows the scene's own corners, use them exactly
            corners = pp.check_quadrilateral(parsed)
            from_quad = pp.estimate_aspect_ratio(corners, photo.image.shape)
            known = pp.estimate_aspect_ratio(corners, photo.image.shape, focal_length=photo.K[0, 0])
        except (ValueError, pp.DegenerateError) as exc:
            state.update(error=str(exc), ratio=None)
            readout.value = monospace(f"cannot rectify:\n{exc}")
            _show_invalid(art, quad, im_r, ax_r, v["corners"], v["corner"], exc)
            return
        art.why.set_text("")
        est, alt = (known, from_quad) if v["use_focal"] else (from_quad, known)
        current["corners"] = corners
        _show_corners(quad, handles, chosen, corners, v["corner"])
        on_page = bool(np.abs(corners - photo.corners).max() <= _ON_PAGE_PX)
        art.key.set_text(_key_text(on_page, from_quad.focal_source))
        _show_shapes(
            im_r,
            photo,
            corners,
            est.ratio,
            ((other, alt.ratio), (truth_box, photo.aspect if on_page else None)),
        )
        state.update(
            error=None,
            ratio=est.ratio,
            true_ratio=photo.aspect,
            focal=est.focal_length,
            focal_source=est.focal_source,
            corners=corners,
            corner=v["corner"],
            scene=v["scene"],
            ratio_from_quad=from_quad.ratio,
            ratio_known_focal=known.ratio,
            focal_from_quad=from_quad.focal_length,
        )
        used = _focal_used(v["use_focal"], photo, from_quad)
        ax_r.set_title(f"rectified with {used}", fontsize=10, pad=3)
        if v["scene"] not in slips:  # once per scene: 32 estimates
            slips[v["scene"]] = _corner_slip_range(photo.corners, photo.image.shape, photo.K[0, 0])
        text = _rectify_readout(est, used, from_quad, known, photo, slips[v["scene"]], on_page)
        readout.value = _warn_if_flat(_warn_if_skewed(text, corners, from_quad), corners)

    demo = build_demo(
        "rectify_photo",
        _rectify_controls(control, keys),
        view,
        update,
        title="Rectify a photographed rectangle",
        extra=[readout],
        linked=keys,
    )
    demo.handlers.update(connect_corner_drag(view, ax_p, control, lambda: current["corners"]))
    return demo


@register(
    lesson="10",
    sweep={"yaw": [-0.8, 0.0, 0.5, 0.8], "pitch": [0.7, -0.7], "page_present": [False, True]},
)
def document_scanner() -> Demo:
    """The "Scan this page" demo: find the page and rectify it; say so when there is none.

    The page is found by edges, contours and the largest convex quadrilateral.

    Returns
    -------
    Demo
        The demo: controls ``yaw`` and ``pitch`` (the page's turn, rad) and ``page_present``,
        the figure (the photo with the quadrilateral found, the page rectified) and ``state``
        (``found``, ``corner_error`` the worst corner's distance from the truth in px,
        ``ratio`` the estimated w/h, ``focal`` in px and ``focal_source`` behind it, ``message`` why
        no page was found).
    """
    view, ax_p, ax_r, im_p, im_r, found = _photo_demo(
        "photo with the detected outline",
        "scanned page",
        dict(ls="-", color=palette.YELLOW, lw=1, path_effects=palette.halo(1, "black")),
    )
    view.animate(ax_r.title)  # says which f the scan used
    view.animate(ax_p.title)  # says whether an outline was detected
    truth_box = _truth_artist(view, ax_r, None)
    key = view.animate(
        ax_r.text(
            0.5, -0.02, _SCAN_KEY, transform=ax_r.transAxes, ha="center", va="top", fontsize=8
        )
    )
    readout = W.HTML()
    why = _why_text(view, ax_r)  # why no page was found

    def update(v: dict, state: dict) -> None:
        photo = scenes.sample_photo("page", yaw=v["yaw"], pitch=v["pitch"])
        image = photo.image if v["page_present"] else np.asarray(scenes.desk_background())
        _set_photo(im_p, image)
        try:
            corners = pp.find_document(image)
        except pp.DocumentNotFoundError as exc:
            found.set_data([], [])
            truth_box.set_data([], [])
            im_r.set_data(np.full((_SHOW, _SHOW, 3), 255, np.uint8))
            state.update(found=False, corner_error=None, message=str(exc))
            readout.value = monospace("no page found:\n" + str(exc).replace("; ", ";\n"))
            why.set_text("no page found:\n" + textwrap.fill(str(exc), 44))
            key.set_text("")  # no page, no true shape
            ax_r.set_title("scanned page", fontsize=10, pad=3)
            ax_p.set_title("photo: no outline detected", fontsize=10, pad=3)
            return
        why.set_text("")
        ax_p.set_title("photo with the detected outline", fontsize=10, pad=3)
        closed = np.vstack([corners, corners[:1]])
        found.set_data(closed[:, 0], closed[:, 1])
        est, conditioning, undetermined = _scan_estimate(corners, image.shape)
        key.set_text(
            f"{_SCAN_KEY}\nthe scan's w/h: {100 * (est.ratio / photo.aspect - 1):+.1f}% off the truth"
        )
        shown = _size_for(400, est.ratio)
        _show_rectified(im_r, image, corners, shown)
        _box_outline(truth_box, _size_for(400, photo.aspect), shown)
        how = {
            "estimated": "f from the corners",
            "assumed": f"f assumed, {est.focal_length:.0f} px",
        }
        ax_r.set_title(
            f"scanned page ({how.get(est.focal_source, 'no f needed')})", fontsize=10, pad=3
        )
        err = float(np.linalg.norm(corners - photo.corners, axis=1).max())  # a distance, px
        state.update(
            found=True,
            corner_error=err,
            ratio=est.ratio,
            focal=est.focal_length,
            focal_source=est.focal_source,
            message="",
        )
        readout.value = monospace(
            f"page found; worst corner error {err:.1f} px\n"
            f"aspect w/h {est.ratio:.3f} (true {photo.aspect:.3f}, A4 = 0.707)\n"
            + (conditioning[1:] if undetermined else _focal_text(est, photo.K[0, 0]) + conditioning)
        )

    controls = {
        "yaw": slider(0.45, -0.8, 0.8, 0.05, "page yaw (rad)"),
        "pitch": slider(0.35, -0.7, 0.7, 0.05, "page pitch (rad)"),
        "page_present": W.Checkbox(value=True, description="page on the desk"),
    }
    return build_demo(
        "document_scanner", controls, view, update, title="Scan this page", extra=[readout]
    )


@register(
    lesson="10",
    sweep={"tilt": [0.8, 0.0, 0.3], "yaw": [0.3, 0.0, -0.5, 0.5], "use_focal": [False, True]},
)
def keystone_correction() -> Demo:
    """Keystone: a camera tilted up at a facade makes its verticals converge; a homography undoes it.

    The rectifying homography makes them parallel again. With yaw 0 the horizontals stay
    parallel, so the corners cannot tell the focal length: the aspect ratio then rests
    on an assumed f, and the figure says how far off that makes it.

    Returns
    -------
    Demo
        The demo: controls ``tilt`` (the camera's tilt up) and ``yaw`` (rad) and ``use_focal`` (give
        the known f), the figure (the facade with its outline, rectified beside the true
        shape) and ``state`` (``ratio`` estimated and ``true_ratio`` w/h,
        ``ratio_error_percent``, ``convergence`` of the verticals in degrees, ``focal`` in
        px and ``focal_source``).
    """
    view, ax_p, ax_r, im_p, im_r, quad = _photo_demo(
        "photo from the street",
        "keystone-corrected",
        dict(ls="--", color=palette.YELLOW, lw=1.5, path_effects=palette.halo(1.5, "black")),
    )
    # a static key: canvas text costs ~4 ms per line per redraw
    truth_box = _truth_artist(view, ax_r, "green dotted: the true shape (numbers in the readout)")
    readout = W.HTML()
    view.animate(ax_p.title, ax_r.title)  # whether the camera is tilted; which f rectified it

    def update(v: dict, state: dict) -> None:
        photo = scenes.sample_photo("facade", pitch=-v["tilt"], yaw=v["yaw"])  # pitch < 0: up
        turned = " and turned" if v["yaw"] != 0 else ""
        ax_p.set_title(
            f"photo, camera tilted up{turned}"
            if v["tilt"] > 0
            else ("photo, camera level, turned" if turned else "photo, camera level (no tilt)"),
            fontsize=10,
            pad=3,
        )
        _set_photo(im_p, photo.image)
        c = photo.corners
        closed = np.vstack([c, c[:1]])
        quad.set_data(closed[:, 0], closed[:, 1])
        est = pp.estimate_aspect_ratio(
            c, photo.image.shape, focal_length=photo.K[0, 0] if v["use_focal"] else None
        )
        shown = _size_for(400, est.ratio)
        _show_rectified(im_r, photo.image, c, shown)
        how = {"given": "the known f", "estimated": "f from the corners", "assumed": "f assumed"}
        how["not needed"] = "no f (none needed)"
        _box_outline(truth_box, _size_for(400, photo.aspect), shown)
        left, right = c[3] - c[0], c[2] - c[1]
        converge = float(np.degrees(np.arctan2(left[0], left[1]) - np.arctan2(right[0], right[1])))
        off = 100 * (est.ratio / photo.aspect - 1)
        off_text = f"{off:+.1f}%" if round(off, 1) != 0 else "0.0%"  # never -0.0%
        ax_r.set_title(
            f"rectified with {how.get(est.focal_source, 'no f')}\nw/h {off_text} off the true shape",
            fontsize=10,
            pad=3,
        )
        state.update(
            ratio=est.ratio,
            true_ratio=photo.aspect,
            convergence=converge,
            focal_source=est.focal_source,
            focal=est.focal_length,
            ratio_error_percent=off,
        )
        readout.value = monospace(
            f"verticals converge by {abs(converge):.1f}°\n"
            f"aspect w/h estimated {est.ratio:.3f} (true {photo.aspect:.3f}, {off_text})\n"
            f"{_focal_text(est, photo.K[0, 0])}"
        )

    controls = {
        "tilt": slider(0.5, 0.0, 0.8, 0.05, "camera tilt up (rad)"),
        "yaw": slider(0.0, -0.5, 0.5, 0.05, "yaw (rad)"),
        "use_focal": W.Checkbox(value=False, description="use the known focal length (800 px)"),
    }
    return build_demo(
        "keystone_correction", controls, view, update, title="Keystone correction", extra=[readout]
    )
