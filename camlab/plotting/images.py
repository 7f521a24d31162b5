"""Image panels: grey or RGB images shown pixel-exact, with zoomed crops (lessons 01-03)."""

from __future__ import annotations

import numpy as np

from . import palette

__all__ = ["show_image", "zoom_box"]


def show_image(
    ax,
    image: np.ndarray,
    title: str = "",
    *,
    vmin: float = 0.0,
    vmax: float | None = None,
    interpolation: str = "nearest",
):
    """Show ``image`` (H, W) or (H, W, 3) with pixel centres at integer (u, v), no ticks; returns the AxesImage.

    ``interpolation="nearest"`` shows pixels as crisp blocks, right when the image is drawn
    larger than its size; an image drawn *smaller* than its size (a detailed scene in a
    small panel) needs ``"antialiased"``, or the display itself aliases (moire).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in.
    image : (H, W) or (H, W, 3) ndarray
        A grey image (drawn with the ``gray`` colormap) or an RGB one (drawn as is).
    title : str
        The axes' title (fontsize 10).
    vmin, vmax : float
        The grey image's display range; ``vmax=None`` picks 255 for uint8, the dtype's maximum
        for other integers and 1.0 for floats. Ignored for RGB images.
    interpolation : str
        matplotlib's ``imshow`` interpolation.

    Returns
    -------
    matplotlib.image.AxesImage
        The image artist (update it with ``set_data``).
    """
    img = np.asarray(image)
    if vmax is None:
        vmax = (
            255
            if img.dtype == np.uint8
            else (np.iinfo(img.dtype).max if np.issubdtype(img.dtype, np.integer) else 1.0)
        )
    kw = {} if img.ndim == 3 else {"cmap": "gray", "vmin": vmin, "vmax": vmax}
    art = ax.imshow(img, interpolation=interpolation, **kw)
    ax.set_title(title, fontsize=10)
    ax.set_xticks([])
    ax.set_yticks([])
    return art


def zoom_box(ax, u0: int, v0: int, size: int, color: str = palette.TAB_RED):
    """Outline the crop ``[v0:v0+size, u0:u0+size]`` on an image axes; returns the Rectangle.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The image axes (pixel centres at integer coordinates, as :func:`show_image` draws).
    u0, v0 : int
        Column and row of the crop's top-left pixel.
    size : int
        The crop's side, pixels.
    color : str
        The outline's colour (a palette colour).

    Returns
    -------
    matplotlib.patches.Rectangle
        The outline, added to ``ax``.
    """
    from matplotlib.patches import Rectangle

    rect = Rectangle((u0 - 0.5, v0 - 0.5), size, size, fill=False, color=color, lw=1.5)
    ax.add_patch(rect)
    return rect
