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
    """Outline the crop ``[v0:v0+size, u0:u0+size]`` on an image axes; returns the Rectangle."""
    from matplotlib.patches import Rectangle

    rect = Rectangle((u0 - 0.5, v0 - 0.5), size, size, fill=False, color=color, lw=1.5)
    ax.add_patch(rect)
    return rect
