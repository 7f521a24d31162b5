"""Demos for lesson 01, the pinhole camera."""
from __future__ import annotations

import ipywidgets as W
import numpy as np

from .. import pinhole, render, sensor
from ..plotting import images, optics
from matplotlib.ticker import MaxNLocator

from ._base import FigureView, build_demo, register, slider

SIZE = (320, 240)
PITCH = 36e-3 / SIZE[0]  # a 36 mm wide sensor with 320 pixels: 112.5 um pixels
BOX_SIZE = (0.3, 0.3, 0.3)
DRAW_SCALE = 10.0  # the 3-D view draws the image planes 10x further from the pinhole than f


def _box_scene(distance: float):
    return [render.box([0.0, 0.0, distance], BOX_SIZE, R=render.rotation_from_euler(0.35, 0.6, 0.0), rng=0),
            render.textured_plane(np.full((4, 4), 0.35), 3.0 * distance, t=(0, 0, 3.0 * distance), name="wall")]


def _rotated_box_edges(distance: float) -> np.ndarray:
    faces = _box_scene(distance)[0]
    edges = []
    for f in faces:
        c = f.world_points  # the 4 face corners
        edges += [[c[i], c[(i + 1) % 4]] for i in range(4)]
    return np.array(edges)


@register(lesson="01", sweep={"focal_mm": [20, 50, 90], "distance": [1.0, 2.0, 3.5], "real_plane": [True, False]})
def pinhole_projection():
    """A box, the pinhole and both image planes in 3-D beside the image the camera records."""
    controls = {
        "focal_mm": slider(50, 15, 100, 1, "focal length f (mm)"),
        "distance": slider(2.0, 0.8, 4.0, 0.1, "box distance Z (m)"),
        "real_plane": W.Checkbox(value=False, description="show the real (inverted) image"),
    }
    view = FigureView(figsize=(9, 4))
    ax3 = view.fig.add_subplot(1, 2, 1, projection="3d")
    ax_img = view.fig.add_subplot(1, 2, 2)
    edges = _rotated_box_edges(2.0)
    art = optics.draw_pinhole_3d(ax3, edges, 0.05 * DRAW_SCALE, plane_half=0.25)
    ax3.set_title(f"pinhole at 0; image planes drawn {DRAW_SCALE:.0f}x further than f", fontsize=9)
    ax3.set_xlim(-0.8, 4.2)
    ax3.set_ylim(-0.6, 0.6)
    ax3.set_zlim(-0.6, 0.6)
    ax3.set_box_aspect((3, 1.2, 1.2))
    for axis in (ax3.xaxis, ax3.yaxis, ax3.zaxis):
        axis.set_major_locator(MaxNLocator(3))
    im = images.show_image(ax_img, np.zeros(SIZE[::-1]), vmax=1.0)
    label = ax_img.text(4, 14, "", color="w", fontsize=9, va="top", bbox=dict(fc="k", alpha=0.5, lw=0))
    # everything that moves is blitted over the cached static figure
    view.animate(im, label, ax_img.title, art["box"], art["rays"], art["real"], art["virtual"],
                 *art["planes"].values())

    def update(values, state):
        f = values["focal_mm"] * 1e-3
        Z = values["distance"]
        e = _rotated_box_edges(Z)
        optics.update_pinhole_3d(art, e, f * DRAW_SCALE)
        K = sensor.intrinsics_from_sensor(f, (PITCH, PITCH), SIZE)
        img = render.render(_box_scene(Z), K, SIZE).irradiance
        if values["real_plane"]:
            img = img[::-1, ::-1]  # the real image: rotated 180 degrees
        im.set_data(img)
        centre = pinhole.project_pinhole([0.0, 0.0, Z], f)
        state.update(fx=K[0, 0], box_width_px=K[0, 0] * BOX_SIZE[0] / Z, image=img, centre=centre,
                     plane="real" if values["real_plane"] else "virtual")
        ax_img.set_title(("real image (inverted)" if values["real_plane"] else "virtual image (upright)")
                         + f", fx = {K[0, 0]:.0f} px", fontsize=10)
        label.set_text(f"box ~ {state['box_width_px']:.0f} px wide")

    return build_demo("pinhole_projection", controls, view, update, title="Pinhole projection x = f X / Z")


@register(lesson="01", sweep={"diameter_mm": [0.05, 0.3, 1.5], "focal_mm": [50, 100, 200]})
def pinhole_size():
    """Blur against pinhole diameter (geometric versus diffraction) and the blurred image it gives."""
    controls = {
        "diameter_mm": W.FloatLogSlider(value=0.3, base=10, min=np.log10(0.03), max=np.log10(2.5), step=0.02,
                                        description="pinhole d (mm)", continuous_update=True,
                                        style={"description_width": "initial"}, layout=W.Layout(width="300px")),
        "focal_mm": slider(100, 30, 200, 5, "focal length f (mm)"),
    }
    view = FigureView(figsize=(9, 4))
    ax_plot, ax_img = view.fig.subplots(1, 2)
    art = optics.draw_pinhole_blur(ax_plot, 0.1)
    ax_plot.set_ylim(0.01, 30)
    ax_plot.minorticks_off()
    page = render.text_page(0.3, t=(0, 0, 1.0))
    im = images.show_image(ax_img, np.zeros(SIZE[::-1]), vmax=1.0)
    ax_img.set_title("page at 1 m: blur 0.00 mm = 0.0 px", fontsize=10)
    ax_plot.set_title("best d = 0.00 mm; now diffraction-limited", fontsize=10)
    view.animate(im, ax_img.title, ax_plot.title, art["geometric"], art["diffraction"], art["total"],
                 art["marker"], art["best"])

    def update(values, state):
        f, d = values["focal_mm"] * 1e-3, values["diameter_mm"] * 1e-3
        optics.update_pinhole_blur(art, f, d)
        b = pinhole.pinhole_blur(d, f, object_distance=1.0)
        # a sensor whose 320 pixels span the same field of view at every f
        pitch = f * 0.36 / SIZE[0]
        K = sensor.intrinsics_from_sensor(f, (pitch, pitch), SIZE)
        blur_px = float(b.total) / pitch
        im.set_data(render.render(page, K, SIZE, blur=blur_px).irradiance)
        best = pinhole.optimal_pinhole_diameter(f, object_distance=1.0)
        state.update(blur_mm=float(b.total) * 1e3, blur_px=blur_px, best_mm=best * 1e3,
                     limited_by="diffraction" if b.diffraction > b.geometric else "geometry")
        ax_plot.set_title(f"best d = {best * 1e3:.2f} mm; now {state['limited_by']}-limited", fontsize=10)
        ax_img.set_title(f"page at 1 m: blur {state['blur_mm']:.2f} mm = {blur_px:.1f} px", fontsize=10)

    return build_demo("pinhole_size", controls, view, update, title="How big should the pinhole be?")
