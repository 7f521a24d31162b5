"""Demos for lesson 01, the pinhole camera."""
from __future__ import annotations

import ipywidgets as W
import numpy as np

from .. import pinhole, render, scenes, sensor
from ..plotting import images, optics
from matplotlib.ticker import MaxNLocator

from ._base import FigureView, build_demo, register, slider
from .controls import monospace
from ..plotting import palette
from ..scenes.planes import CHART_ROW_HEIGHTS

SIZE = (320, 240)
PITCH = 36e-3 / SIZE[0]  # a 36 mm wide sensor with 320 pixels: 112.5 um pixels
DRAW_SCALE = 10.0  # the 3-D view draws the image planes up to 10x further from the pinhole than f...
PLANE_ROOM = 0.45  # ...but never beyond 45 % of the way to the box's nearest corner


def _box_outline(faces) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray]]:
    """The box's (24, 2, 3) edge segments and (faces (6, 4, 3), mean greys (6,)) for the 3-D view."""
    return scenes.plane_outlines(faces), (np.array([f.corners_world for f in faces]),
                                          np.array([f.texture.mean() for f in faces]))


@register(lesson="01", sweep={"focal_mm": [20, 50, 90], "distance": [1.0, 2.0, 3.5], "real_plane": [True, False]})
def pinhole_projection():
    """A box, the pinhole and both image planes in 3-D beside the image the camera records."""
    controls = {
        "focal_mm": slider(50, 15, 100, 1, "focal length f (mm)"),
        "distance": slider(2.0, 0.8, 4.0, 0.1, "box distance Z (m)"),
        "real_plane": W.Checkbox(value=False, description="show the real (inverted) image"),
    }
    view = FigureView(figsize=(10.5, 4.6))
    view.fig.get_layout_engine().set(wspace=0.12)  # room for the 3-D z label, which the layout does not see
    grid = view.fig.add_gridspec(1, 2, width_ratios=(1.35, 1))
    ax3 = view.fig.add_subplot(grid[0], projection="3d")
    ax_img = view.fig.add_subplot(grid[1])
    edges, faces = _box_outline(scenes.box_before_wall(2.0)[0])
    art = optics.draw_pinhole_3d(ax3, edges, 0.05 * DRAW_SCALE, plane_half=0.25, faces=faces)
    ax3.set_xlim(-1.1, 4.5)
    ax3.set_ylim(-0.35, 0.35)
    ax3.set_zlim(-0.35, 0.35)
    ax3.set_box_aspect((3, 1, 1), zoom=1.1)
    ax3.set_xlabel("z, forward (m)")
    ax3.set_ylabel("x (m)")
    ax3.set_zlabel("-y, up (m)")
    for axis in (ax3.xaxis, ax3.yaxis, ax3.zaxis):
        axis.set_major_locator(MaxNLocator(3))
    for name in ("real", "virtual"):
        art[name].set_linewidth(1.8)
    im = images.show_image(ax_img, np.zeros(SIZE[::-1]), vmax=1.0)
    width_bar = ax_img.plot([], [], color=palette.ORANGE, lw=2, marker="|", ms=10, path_effects=palette.halo(2))[0]
    ax3.set_title("pinhole at 0; both image planes drawn enlarged (distance in the readout)", fontsize=9)
    readout = W.HTML()  # numbers beside the sliders: canvas text costs ~4 ms per line per redraw
    # everything that moves is blitted over the cached static figure
    view.animate(im, width_bar, ax_img.title, art["box"], art["rays"], art["real"], art["virtual"],
                 *art["planes"].values(), *art["fills"].values())

    def update(values, state):
        f = values["focal_mm"] * 1e-3
        Z = values["distance"]
        scene = scenes.box_before_wall(Z)
        e, faces = _box_outline(scene[0])
        corners = np.unique(e.reshape(-1, 3), axis=0)
        # the image planes: 10 f when that fits, else closer, always between pinhole and box
        f_draw = min(DRAW_SCALE * f, PLANE_ROOM * corners[:, 2].min())
        art["plane_half"] = 1.25 * np.abs(pinhole.project_pinhole(corners, f_draw)).max()
        optics.update_pinhole_3d(art, e, f_draw, faces)
        K = sensor.intrinsics_from_sensor(f, (PITCH, PITCH), SIZE)
        img = render.render(scene, K, SIZE).irradiance
        u = K[0, 0] * corners[:, 0] / corners[:, 2] + K[0, 2]  # the corners' columns, x = f X / Z in pixels
        v_bar = 0.92 * SIZE[1]
        if values["real_plane"]:
            img = img[::-1, ::-1]  # the real image: rotated 180 degrees
            u = SIZE[0] - 1 - u
        im.set_data(img)
        width_bar.set_data([u.min(), u.max()], [v_bar, v_bar])
        centre = pinhole.project_pinhole([0.0, 0.0, Z], f)
        fov = np.degrees(2 * np.arctan(SIZE[0] * PITCH / (2 * f)))  # the sensor's width w seen from the pinhole
        state.update(fx=K[0, 0], box_width_px=float(u.max() - u.min()), image=img, centre=centre, fov_deg=fov,
                     plane="real" if values["real_plane"] else "virtual", f_draw=f_draw)
        ax_img.set_title("real image (inverted)" if values["real_plane"] else "virtual image (upright)", fontsize=10)
        readout.value = monospace(f"fx = f / pixel pitch = {K[0, 0]:.0f} px\n"
                                  f"field of view 2 atan(w / 2f) = {fov:.1f} deg (w = 36 mm)\nbox spans {state['box_width_px']:.0f} px"
                                  f" (orange bar)\nimage planes drawn {f_draw / f:.1f} f from the pinhole")

    return build_demo("pinhole_projection", controls, view, update, title="Pinhole projection x = f X / Z",
                      extra=[readout])


@register(lesson="01", sweep={"f": [0.3, 1.0], "Z": [1.2, 5.0], "Y": [-1.0, 0.4, 1.0]})
def similar_triangles():
    """A side view of a room-sized camera obscura: drag the object point and read x / f = X / Z off the triangles."""
    controls = {
        "f": slider(0.8, 0.3, 1.0, 0.05, "focal length f (m)"),
        "Z": slider(3.0, 1.2, 5.0, 0.05, "object depth Z (m)"),
        "Y": slider(-0.8, -1.0, 1.0, 0.05, "object Y (m; y points down)"),
    }
    view = FigureView(figsize=(9, 4))
    ax = view.fig.subplots()
    art = optics.draw_similar_triangles(ax, z_max=5.6, h_max=1.3)
    ax.set_title("click or drag in the figure to move the object point", fontsize=9)
    readout = ax.text(0.99, 0.02, "", transform=ax.transAxes, ha="right", va="bottom", fontsize=10, family="monospace",
                      bbox=dict(fc="white", ec="0.7", alpha=0.9))
    movers = [art[k] for k in ("big", "small", "object", "point", "ray", "planes", "virtual", "real", "pinhole")]
    for dim in art["dims"].values():
        movers += [dim["arrow"], dim["label"]]
    view.animate(*movers, readout)

    def update(values, state):
        f, Z, Y = values["f"], values["Z"], values["Y"]
        y = optics.update_similar_triangles(art, f, Z, Y)
        state.update(y=y, ratio_image=y / f, ratio_object=Y / Z)
        readout.set_text(f"y / f = {y / f:+.3f}\nY / Z = {Y / Z:+.3f}\n=> y = f Y / Z = {y * 100:+.1f} cm")

    demo = build_demo("similar_triangles", controls, view, update, title="Similar triangles: y / f = Y / Z")

    def on_mouse(event):
        if event.inaxes is ax and event.button == 1 and event.xdata is not None:
            z = float(np.clip(event.xdata, controls["Z"].min, controls["Z"].max))
            y = float(np.clip(-event.ydata, controls["Y"].min, controls["Y"].max))  # the plot shows -y (up)
            demo.set(Z=round(z / 0.05) * 0.05, Y=round(y / 0.05) * 0.05)

    view.fig.canvas.mpl_connect("button_press_event", on_mouse)
    view.fig.canvas.mpl_connect("motion_notify_event", on_mouse)
    return demo


PAGE_Z = 1.0  # the chart's distance in pinhole_size (metres)


@register(lesson="01", sweep={"diameter_mm": [0.05, 0.35, 1.5], "focal_mm": [50, 100, 200]})
def pinhole_size():
    """Blur against pinhole diameter (geometric versus diffraction) and the blurred chart it gives."""
    controls = {
        "diameter_mm": W.FloatLogSlider(value=0.35, base=10, min=np.log10(0.03), max=np.log10(2.5), step=0.02,
                                        description="pinhole d (mm)", continuous_update=True,
                                        style={"description_width": "initial"}, layout=W.Layout(width="300px")),
        "focal_mm": slider(100, 30, 200, 5, "focal length f (mm)"),
    }
    view = FigureView(figsize=(9, 4))
    ax_plot, ax_img = view.fig.subplots(1, 2)
    art = optics.draw_pinhole_blur(ax_plot, 0.1, object_distance=PAGE_Z)
    ax_plot.set_ylim(0.01, 30)
    ax_plot.minorticks_off()
    chart = scenes.letter_chart(0.3, t=(0, 0, PAGE_Z))
    im = images.show_image(ax_img, np.zeros(SIZE[::-1]), vmax=1.0)
    ax_img.set_title(f"a letter chart at Z = {PAGE_Z:g} m, seen through the pinhole", fontsize=10)
    ax_plot.set_title(f"blur against pinhole size, object at Z = {PAGE_Z:g} m", fontsize=10)
    readout = W.HTML()
    view.animate(im, art["geometric"], art["diffraction"], art["total"],
                 art["marker"], art["best"])

    def update(values, state):
        f, d = values["focal_mm"] * 1e-3, values["diameter_mm"] * 1e-3
        optics.update_pinhole_blur(art, f, d, object_distance=PAGE_Z)
        b = pinhole.pinhole_blur(d, f, object_distance=PAGE_Z)
        # a sensor whose 320 pixels span the same field of view at every f
        pitch = f * 0.36 / SIZE[0]
        K = sensor.intrinsics_from_sensor(f, (pitch, pitch), SIZE)
        blur_px = float(b.total) / pitch
        im.set_data(render.render(chart, K, SIZE, blur=blur_px).irradiance)
        best = pinhole.optimal_pinhole_diameter(f, object_distance=PAGE_Z)
        rows_px = np.array(CHART_ROW_HEIGHTS) * 0.3 / 600 * f / PAGE_Z / pitch  # cap heights on the sensor
        legible = int(np.sum(rows_px > 1.5 * blur_px))  # by eye: a letter survives a blur up to 2/3 of its height
        state.update(blur_mm=float(b.total) * 1e3, blur_px=blur_px, best_mm=best * 1e3, legible_rows=legible,
                     limited_by="diffraction" if b.diffraction > b.geometric else "geometry")
        readout.value = monospace(f"best d = {best * 1e3:.2f} mm (star) for Z = {PAGE_Z:g} m\n"
                                  f"your d = {d * 1e3:.2f} mm (red line), {state['limited_by']}-limited\n"
                                  f"blur {state['blur_mm']:.2f} mm = {blur_px:.1f} px\n"
                                  f"rows legible: {legible} of {len(rows_px)} (letters over 1.5 x blur)")

    return build_demo("pinhole_size", controls, view, update, title="How big should the pinhole be?",
                      extra=[readout])
