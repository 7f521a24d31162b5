"""Cheap frames: images drawn at the resolution they are shown, PNG diffs encoded fast.

A slider update should reach the browser within two frames (33 ms at 60 Hz). Two costs
that do not teach anything are removed here, for every demo at once:

* An image artist whose array is larger than its on-screen size makes Agg colour-map and
  resample every source pixel on each redraw. :func:`show_at_display_resolution` makes its
  ``set_data`` keep the array area-averaged to the pixels it covers (what matplotlib's
  antialiased resampling shows anyway; nearest-neighbour views stay nearest), so a redraw costs what the screen can show.
* Under ``%matplotlib widget`` every redraw ends in ``canvas.get_diff_image()``: the pixels
that changed since the last frame, PNG-encoded and sent to the front end. Matplotlib
encodes that PNG with Pillow's default zlib level 6, which on the course machine costs
3-5x more than the whole Agg update for an image demo (about 150 ms against 30 ms for a
720 x 360 photo-like frame). :func:`encode_png` uses zlib level 1 and one fixed row filter:
a file about 15 % larger, encoded about ten times faster; on a local or campus network the
extra bytes cost far less than the encode saves.
"""

from __future__ import annotations

import struct
import types
import zlib
from typing import Any

import numpy as np

PNG_COMPRESS_LEVEL = 1  # zlib level for frames sent to the browser (Pillow's default is 6)


def _fast_diff_image(canvas: Any) -> bytes | None:
    """``FigureCanvasWebAggCore.get_diff_image`` with a fast PNG encode (same protocol)."""
    if not canvas._png_is_old:
        return None
    pixels = np.asarray(canvas.get_renderer().buffer_rgba())
    buff = pixels.view(np.uint32).squeeze(2)  # one uint32 per pixel: compare whole pixels at once
    if (
        canvas._force_full
        or buff.shape != canvas._last_buff.shape
        or (pixels[:, :, 3] != 255).any()
    ):
        canvas.set_image_mode("full")
        output = buff
    else:
        canvas.set_image_mode("diff")  # unchanged pixels go as transparent zeros
        output = np.where(buff != canvas._last_buff, buff, 0)
    canvas._last_buff = buff.copy()
    canvas._force_full = False
    canvas._png_is_old = False
    return encode_png(output.view(np.uint8).reshape((*output.shape, 4)))


def _png_chunk(tag: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))


def encode_png(rgba: np.ndarray) -> bytes:
    """An (H, W, 4) uint8 image as PNG: every row "Up"-filtered, zlib level :data:`PNG_COMPRESS_LEVEL`.

    A PNG row may be stored as its difference from the row above (filter type 2). Demo
    frames are mostly unchanged (zero) pixels, flat fills and images shown with repeated
    rows, so that difference is mostly zeros and deflates well; computing it is one numpy
    subtraction, where Pillow tries all five filters on every row (about twice the time).
    """
    h, w, _ = rgba.shape
    rows = rgba.reshape(h, 4 * w)
    filtered = np.empty((h, 4 * w + 1), np.uint8)
    filtered[:, 0] = 2  # the filter type byte that starts each row
    filtered[0, 1:] = rows[0]  # the row above the first is zeros
    np.subtract(rows[1:], rows[:-1], out=filtered[1:, 1:])  # modulo 256, as PNG defines it
    header = struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)  # 8-bit RGBA, no interlace
    return (
        b"\x89PNG\r\n\x1a\n"
        + _png_chunk(b"IHDR", header)
        + _png_chunk(b"IDAT", zlib.compress(filtered.tobytes(), PNG_COMPRESS_LEVEL))
        + _png_chunk(b"IEND", b"")
    )


def use_fast_png(canvas: Any) -> None:
    """Make an ipympl canvas encode its browser frames with :data:`PNG_COMPRESS_LEVEL`."""
    canvas.get_diff_image = types.MethodType(_fast_diff_image, canvas)


def _pixel_box(image: Any) -> tuple[int, int, int, int]:
    """(left, right, bottom, top): the canvas pixels ``image``'s extent covers, edges rounded."""
    x0, x1, y0, y1 = image.get_extent()
    (u0, v0), (u1, v1) = image.get_transform().transform([(x0, y0), (x1, y1)])
    return round(min(u0, u1)), round(max(u0, u1)), round(min(v0, v1)), round(max(v0, v1))


def _resize(image: Any, a: np.ndarray, width: int, height: int) -> np.ndarray:
    """``a`` resized to width x height as ``image`` displays it.

    A pixelated view ('nearest') stays crisp; anything else is area-averaged when shrunk (as
    antialiasing would) and interpolated when enlarged.
    """
    import cv2

    if image.get_interpolation() in ("nearest", "none"):
        mode = cv2.INTER_NEAREST
    else:
        mode = cv2.INTER_AREA if a.shape[1] > width else cv2.INTER_LINEAR
    return cv2.resize(a, (width, height), interpolation=mode)


def _display_size(image: Any, array: Any) -> tuple[int, int] | None:
    """(width, height) that ``array`` is kept at for ``image``'s current on-screen box, or None: keep it as it is."""
    if array is None or np.ma.isMaskedArray(array):
        return None
    a = np.asarray(array)
    if a.ndim not in (2, 3) or a.dtype.kind not in "uif" or (a.ndim == 3 and a.shape[2] > 4):
        return None
    left, right, bottom, top = _pixel_box(
        image
    )  # the box _screen_image draws into: no second resize there
    width, height = min(a.shape[1], right - left), min(a.shape[0], top - bottom)
    if width < 2 or height < 2:
        return None
    return width, height


def _fit_to_display(image: Any, array: Any) -> Any:
    """``array`` area-averaged to the canvas pixels ``image``'s extent covers, if it is larger."""
    size = _display_size(image, array)
    a = np.asarray(array) if size is not None else None
    if size is None or size == (a.shape[1], a.shape[0]):
        return array
    width, height = size
    if a.dtype not in (np.uint8, np.uint16, np.float32, np.float64):
        a = a.astype(np.float64)
    return _resize(image, a, width, height)


def _nearest_at_centres(
    a: np.ndarray, us: list[float], vs: list[float], box: tuple[int, int, int, int]
) -> np.ndarray:
    """``a`` (row 0 at the bottom) sampled at the centres of the canvas pixels ``box`` covers.

    ``us`` and ``vs`` are the unrounded canvas edges of the image's extent, (left, right) and
    (bottom, top): canvas pixel ``x`` shows data column ``floor((x + 0.5 - left) / (right -
    left) * width)``, as matplotlib's nearest-neighbour resampler picks it. OpenCV's
    ``INTER_NEAREST`` on the rounded box picks from the pixel's corner instead, which moves
    the picked columns of a 1.4x enlargement by one here and there: a different moiré of a
    one-pixel pattern live than in a saved figure.
    """
    left, right, bottom, top = box
    cols = np.floor((np.arange(left, right) + 0.5 - us[0]) / (us[1] - us[0]) * a.shape[1])
    rows = np.floor((np.arange(bottom, top) + 0.5 - vs[0]) / (vs[1] - vs[0]) * a.shape[0])
    cols = np.clip(cols.astype(int), 0, a.shape[1] - 1)
    rows = np.clip(rows.astype(int), 0, a.shape[0] - 1)
    return a[rows[:, None], cols[None, :]]


def _screen_image(image: Any) -> tuple[np.ndarray, int, int] | None:
    """``image``'s RGBA pixels as they land on the canvas, and their lower-left corner; None: use matplotlib.

    The data is already at about screen size, so matplotlib's general resampler (built for
    any affine transform) does work that teaches nothing: here the few cases the demos use,
    an axis-aligned image on the canvas' own renderer, are placed by rounding the extent to
    whole pixels (at most half a pixel from matplotlib's placement) and resized with OpenCV.
    """
    a = image.get_array()
    alpha = image.get_alpha()
    canvas = image.figure.canvas  # (a subfigure's canvas is its root figure's)
    transform = image.get_transform()
    if (
        (np.ma.isMaskedArray(a) and np.ma.getmaskarray(a).any())
        or (alpha is not None and np.ndim(alpha) > 0)
        or getattr(canvas, "is_saving", lambda: False)()
        or image.get_clip_path() is not None
        or not transform.is_affine
        or np.any(transform.get_affine().get_matrix()[[0, 1], [1, 0]] != 0)
    ):
        return None  # masked, per-pixel alpha, a clip path, or a rotated or sheared image: matplotlib's way
    a = np.ma.getdata(a)
    x0, x1, y0, y1 = image.get_extent()
    row0_y = y1 if image.origin == "upper" else y0  # the data row 0 sits at this edge of the extent
    (u_left, v_row0), (u_right, v_rowN) = transform.transform(
        [(x0, row0_y), (x1, y0 + y1 - row0_y)]
    )
    if u_right < u_left:
        a = a[:, ::-1]
    if v_row0 > v_rowN:  # row 0 at the top on screen: Agg's draw_image takes the bottom row first
        a = a[::-1]
    left, right, bottom, top = _pixel_box(image)
    clip = (
        (image.get_clip_box() or image.axes.bbox)
        if image.get_clip_on()
        else image.figure.canvas.figure.bbox
    )
    cl, cr, cb, ct = round(clip.x0), round(clip.x1), round(clip.y0), round(clip.y1)
    if min(right, cr) - max(left, cl) < 1 or min(top, ct) - max(bottom, cb) < 1:
        return np.zeros((0, 0, 4), np.uint8), 0, 0
    if a.shape[:2] != (top - bottom, right - left) and image.get_interpolation() in (
        "nearest",
        "none",
    ):
        # pixelated and enlarged: pick the data pixel under each canvas pixel's centre, as
        # matplotlib's resampler does from the unrounded extent, so a live frame equals a full draw
        a = _nearest_at_centres(
            a, sorted((u_left, u_right)), sorted((v_row0, v_rowN)), (left, right, bottom, top)
        )
    elif a.shape[:2] != (
        top - bottom,
        right - left,
    ):  # smaller than shown (set_data already shrank larger ones)
        a = _resize(
            image,
            np.asarray(a, np.float32) if a.dtype not in (np.uint8, np.float32) else a,
            right - left,
            top - bottom,
        )
    # crop to the clip box (rows count up from the bottom edge)
    a = a[
        max(0, cb - bottom) : (top - bottom) - max(0, top - ct),
        max(0, cl - left) : (right - left) - max(0, right - cr),
    ]
    rgba = image.to_rgba(a, bytes=True)
    return np.ascontiguousarray(rgba), max(left, cl), max(bottom, cb)


def show_at_display_resolution(image: Any) -> None:
    """Make an ``AxesImage`` keep its data at the resolution it is shown (its extent stays).

    On the live canvas it is then also drawn by :func:`_screen_image` rather than by
    matplotlib's general resampler (about 2 ms instead of 5-10 ms per frame for a photo).
    """
    set_data, set_extent, make_image = image.set_data, image.set_extent, image.make_image
    source: list[Any] = [None]  # the caller's full array, to refit when the extent changes

    def fitted_data(array: Any) -> None:  # set_array calls it too
        source[0] = array
        set_data(_fit_to_display(image, array))

    def fitted_extent(extent: Any, **kwargs: Any) -> None:
        set_extent(extent, **kwargs)
        if source[0] is not None:
            set_data(_fit_to_display(image, source[0]))

    def screen_image(renderer: Any, magnification: float = 1.0, unsampled: bool = False):
        # The box may have changed since set_data: the first draw runs the figure's layout (an
        # array fitted to the pre-layout axes would be stretched, resampled twice), a resize, a
        # savefig at another dpi. Refit from the caller's array, which costs nothing when it has not.
        wanted, shown = _display_size(image, source[0]), np.shape(image.get_array())
        if wanted is not None and wanted != (shown[1], shown[0]):
            set_data(_fit_to_display(image, source[0]))
        fast = None if unsampled or magnification != 1.0 else _screen_image(image)
        if fast is None:
            return make_image(renderer, magnification, unsampled)
        rgba, left, bottom = fast
        return (rgba, left, bottom, None) if rgba.size else (None, 0, 0, None)

    image.set_data, image.set_extent, image.make_image = fitted_data, fitted_extent, screen_image


def halo_in_two_passes(artist: Any) -> None:
    """Draw a line's :func:`camlab.plotting.palette.halo` as a second plain pass, not a path effect.

    A path effect makes matplotlib draw markers and collections one path at a time: 68 ms
    per frame for the 2 x 300 haloed inlier dots of ``ransac_registration``, against about
    1 ms for two plain passes. The artist keeps its declared path effect (what it looks
    like); its ``draw`` first strokes it in the halo colour at the halo's width, then draws
    it as itself. Artists without exactly one ``withStroke`` effect are left alone.
    """
    from matplotlib import patheffects
    from matplotlib.collections import LineCollection
    from matplotlib.lines import Line2D

    effects = artist.get_path_effects() if hasattr(artist, "get_path_effects") else None
    if (
        not effects
        or len(effects) != 1
        or not isinstance(effects[0], patheffects.withStroke)
        or not isinstance(artist, (Line2D, LineCollection))
    ):
        return
    halo, width = effects[0]._gc.get("foreground", "white"), effects[0]._gc.get("linewidth", 2.0)

    def draw(renderer: Any) -> None:
        type(artist).draw(artist, renderer)  # the class's draw, looked up at each frame

    # The stored style, not the getters' resolved one: a marker colour "auto" must stay "auto",
    # and a collection's colours must not take in its alpha (its RGBA arrays already do).
    stored = (
        {"color": "_original_edgecolor", "linewidth": "_us_lw"}
        if isinstance(artist, LineCollection)
        else {
            key: "_" + key
            for key in (
                "color",
                "linewidth",
                "markeredgewidth",
                "markeredgecolor",
                "markerfacecolor",
            )
        }
    )

    def halo_pass(renderer: Any) -> None:
        plain = {key: getattr(artist, attr) for key, attr in stored.items()}
        style = {"color": halo, "linewidth": width}
        if isinstance(artist, Line2D):
            hollow = (
                isinstance(plain["markerfacecolor"], str) and plain["markerfacecolor"] == "none"
            )
            style.update(
                markeredgewidth=width,
                markeredgecolor=halo,
                markerfacecolor="none" if hollow else halo,
            )
        artist.set(**style)
        draw(renderer)
        artist.set(**plain)

    def two_passes(renderer: Any) -> None:
        callback, artist.stale_callback = (
            artist.stale_callback,
            None,
        )  # restyling for a pass is no change
        try:
            artist.set_path_effects([])
            halo_pass(renderer)
            draw(renderer)
        finally:
            artist.set_path_effects(effects)
            artist.stale_callback = callback

    artist.draw = two_passes
