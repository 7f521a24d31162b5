"""The scene lesson 01's ``pinhole_projection`` sends once to ``pinhole.js``.

The box's faces and the wall as textured planes (``textured.js`` renders the recorded image from
them at each move), the 3-D view's projection (mplot3d's 4x4 map and the axes' map to canvas
pixels), the image panels' places and the look of every moving artist, read off the matplotlib
artists.
"""

from __future__ import annotations

import base64
from collections.abc import Sequence
from typing import Any

import numpy as np
from matplotlib import colormaps
from matplotlib.colors import to_hex

from . import line_style, marker_style, text_lines, text_style, to_canvas_pixels
from .homography_scenes import image_place
from .scenes import spine_lines

__all__ = ["pinhole_projection_scene", "texture_data", "textured_planes"]


def texture_data(texture: np.ndarray) -> dict:
    """A grey float32 texture as ``textured.js`` takes it: base64 bytes, the squares of a flat-squared one.

    A texture made of flat n x n squares (a checkered wall: ``numpy.kron`` of its squares) is sent
    as its squares and ``texels`` = n, the largest power of two that rebuilds it exactly; the
    browser repeats each square (the wall's 2048 x 1536 texels are 192 squares).

    Parameters
    ----------
    texture : (H, W) float32 ndarray
        The plane's texture.

    Returns
    -------
    dict
        ``data`` (base64 of the float32 values, rows first), ``width`` and ``height`` (of what is
        sent), and ``texels`` when the texture is squares.
    """
    tex = np.ascontiguousarray(texture, dtype=np.float32)
    h, w = tex.shape
    n = 1 << min(h & -h, w & -w).bit_length() - 1  # the largest power of two dividing both sides
    while n > 1 and not np.array_equal(np.kron(tex[::n, ::n], np.ones((n, n), np.float32)), tex):
        n //= 2
    small = np.ascontiguousarray(tex[::n, ::n])
    out = dict(
        data=base64.b64encode(small.tobytes()).decode("ascii"),
        width=int(small.shape[1]),
        height=int(small.shape[0]),
    )
    return dict(out, texels=n) if n > 1 else out


def textured_planes(planes: Sequence[Any], moving: Sequence[bool]) -> list[dict]:
    """Grey planes as ``textured.js``'s ``renderPlanes`` takes them (a camera at the origin).

    Parameters
    ----------
    planes : sequence of camlab.scenes.Plane
        The planes, camera frame.
    moving : sequence of bool
        Per plane, whether the browser moves it along z by the demo's distance (``box``).

    Returns
    -------
    list of dict
        ``R``, ``t``, ``extent``, ``twoSided``, ``box`` and ``texture`` (:func:`texture_data`).
    """
    return [
        dict(
            R=np.asarray(p.R, float).tolist(),
            t=np.asarray(p.t, float).tolist(),
            extent=[float(c) for c in p.extent],
            twoSided=bool(p.two_sided),
            box=bool(m),
            texture=texture_data(p.texture),
        )
        for p, m in zip(planes, moving, strict=True)
    ]


def pinhole_projection_scene(parts: Any, constants: dict) -> dict:
    """What ``pinhole.js`` needs to draw ``pinhole_projection`` as matplotlib draws it.

    Parameters
    ----------
    parts : SimpleNamespace
        The demo's figure (``_projection_figure``: ``art``, ``ax3``, ``ax_img``, ``im``, ``planes``,
        ``width_bar``, ``bar_ends``, ``scale_note``), after the first draw.
    constants : dict
        ``faces`` (the box's planes at ``boxDistance`` metres), ``boxDistance``, ``wall``, ``size``, ``pitch``, ``sensor``,
        ``planeScale``, ``planeRoom``, ``planeMax`` and ``barRow`` (the bar's image row).

    Returns
    -------
    dict
        The scene (JSON).
    """
    from ...plotting import optics

    art, ax3, ax_img = parts.art, parts.ax3, parts.ax_img
    pt = ax3.figure.dpi / 72.0
    faces = constants["faces"]
    corners, greys = optics.plane_faces(faces)

    def haloed(line: Any) -> dict:  # palette.halo: 1 point of white each side
        return line_style(line, pt, halo="#ffffff", haloWidth=(line.get_linewidth() + 2.0) * pt)

    ends = parts.bar_ends
    lut = (colormaps["gray"](np.linspace(0, 1, 256), bytes=True)[:, 0]).tolist()
    return dict(
        planes=textured_planes([*faces, constants["wall"]], [True] * len(faces) + [False]),
        faces=np.asarray(corners, float).tolist(),
        greys=[float(g) for g in greys],
        boxDistance=constants["boxDistance"],
        size=list(constants["size"]),
        pitch=constants["pitch"],
        sensor=list(constants["sensor"]),
        planeScale=constants["planeScale"],
        planeRoom=constants["planeRoom"],
        planeMax=constants["planeMax"],
        supersample=2,
        irradianceWhereEmpty=0.5,  # render.render's background ("background" is the figure's PNG)
        lut=lut,
        M=np.asarray(ax3.get_proj(), float).tolist(),
        toPixels=to_canvas_pixels(ax3),
        imageToPixels=to_canvas_pixels(ax_img),
        barRow=constants["barRow"],
        panels=[
            dict(image="image", place=image_place(parts.im), spines=spine_lines(ax_img)),
            *(
                dict(image=name, place=image_place(im), spines=spine_lines(im.axes))
                for name, im in parts.planes.items()
            ),
        ],
        styles=dict(
            box=haloed(art["box"]),
            rays=haloed(art["rays"]),
            frames={name: line_style(line, pt) for name, line in art["planes"].items()},
            pinhole=marker_style(art["pinhole"], pt),
            bar=haloed(parts.width_bar),
            end=dict(
                color=to_hex(ends.get_markeredgecolor()),
                width=ends.get_markeredgewidth() * pt,
                size=ends.get_markersize() * pt,
                halo="#ffffff",
                haloWidth=(ends.get_markeredgewidth() + 2.0) * pt,
                cap="butt",
                dash=[],
            ),
            title=dict(text_style(ax_img.title), **text_lines(ax_img.title)),
            note=dict(text_style(parts.scale_note), **text_lines(parts.scale_note)),
        ),
    )
