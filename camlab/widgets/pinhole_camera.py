"""Demos for lesson 01, the pinhole camera."""
from __future__ import annotations

import ipywidgets as W
import numpy as np

from .. import pinhole, render, scenes, sensor
from ..plotting import images, optics

from ._base import FigureView, build_demo, register, slider
from .controls import monospace
from ..plotting import palette
from ..scenes.planes import CHART_ROW_HEIGHTS

SIZE = (320, 240)
PITCH = 36e-3 / SIZE[0]  # a 36 mm wide sensor with 320 pixels: 112.5 um pixels
DRAW_SCALE = 16.0  # the 3-D view draws the image planes up to 16x further from the pinhole than f...
PLANE_ROOM = 0.45  # ...but never beyond 45 % of the way to the box's nearest corner...
PLANE_MAX = 0.95  # ...nor beyond the 3-D view's near end at z = -1.1 m (the real plane's frame)


def _box_outline(faces) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray]]:
    """The box's (24, 2, 3) edge segments and (faces (6, 4, 3), mean greys (6,)) for the 3-D view."""
    return scenes.plane_outlines(faces), optics.plane_faces(faces)


@register(lesson="01", sweep={"focal_mm": [20, 50, 90], "distance": [1.0, 2.0, 3.5], "real_plane": [True, False]})
def pinhole_projection():
    """A box, the pinhole and both image planes in 3-D beside the image the camera records."""
    controls = {
        "focal_mm": slider(50, 15, 100, 1, "focal length f (mm)"),
        "distance": slider(2.0, 0.8, 4.0, 0.1, "box distance Z (m)"),
        "real_plane": W.Checkbox(value=False, description="show the real image (rotated 180 degrees)"),
    }
    view = FigureView(figsize=(8.8, 4.0))
    view.fig.set_layout_engine("none")  # placed by hand: the layout engine does not see the 3-D axis labels
    ax3 = view.fig.add_axes((-0.06, -0.0, 0.7, 1.0), projection="3d")
    ax_img = view.fig.add_axes((0.69, 0.15, 0.3, 0.7))
    edges, faces = _box_outline(scenes.box_before_wall(2.0)[0])
    art = optics.draw_pinhole_3d(ax3, edges, 0.05 * DRAW_SCALE, faces=faces)
    ax3.set_xlim(-1.1, 4.5)
    ax3.set_ylim(-0.3, 0.3)
    ax3.set_zlim(-0.3, 0.3)
    ax3.set_box_aspect((2.6, 1, 1), zoom=1.2)
    optics.label_camera_axes(ax3, labelpad=1)
    ax3.xaxis.labelpad = 9  # below the middle tick label
    im = images.show_image(ax_img, np.zeros(SIZE[::-1]), vmax=1.0)
    width_bar = ax_img.plot([], [], color="k", lw=2, marker="|", ms=10, mew=2, path_effects=palette.halo(2))[0]
    view.fig.text(0.02, 0.97, "pinhole (black dot) at 0; image planes drawn enlarged", fontsize=9, va="top")
    readout = W.HTML()  # numbers beside the sliders: canvas text costs ~4 ms per line per redraw
    # everything that moves is blitted over the cached static figure (the pinhole too: a ray passes over it)
    view.animate(im, width_bar, ax_img.title, art["box"], art["rays"], art["real"], art["virtual"], art["pinhole"],
                 *art["planes"].values(), *art["fills"].values())

    def update(values, state):
        f = values["focal_mm"] * 1e-3
        Z = values["distance"]
        scene = scenes.box_before_wall(Z)
        e, faces = _box_outline(scene[0])
        corners = np.unique(e.reshape(-1, 3), axis=0)
        # the image planes as far out as fits (a big picture of the box), always between pinhole and box
        f_draw = min(DRAW_SCALE * f, PLANE_ROOM * corners[:, 2].min(), PLANE_MAX)
        optics.update_pinhole_3d(art, e, f_draw, faces)
        K = sensor.intrinsics_from_sensor(f, (PITCH, PITCH), SIZE)
        img = render.render(scene, K, SIZE).irradiance
        u = K[0, 0] * corners[:, 0] / corners[:, 2] + K[0, 2]  # the corners' columns, x = f X / Z in pixels
        v_bar = 0.92 * SIZE[1]
        if values["real_plane"]:
            img = img[::-1, ::-1]  # the real image in the camera's axes: rotated 180 degrees
            u = SIZE[0] - 1 - u
        im.set_data(img)
        width_bar.set_data([u.min(), u.max()], [v_bar, v_bar])
        centre = pinhole.project_pinhole([0.0, 0.0, Z], f)
        fov = np.degrees(2 * np.arctan(SIZE[0] * PITCH / (2 * f)))  # the sensor's width w seen from the pinhole
        state.update(K=K, fx=K[0, 0], box_width_px=float(u.max() - u.min()), image=img, centre=centre, fov_deg=fov,
                     plane="real" if values["real_plane"] else "virtual", f_draw=f_draw)
        ax_img.set_title("real image (rotated 180 deg)" if values["real_plane"]
                         else "virtual image (upright)", fontsize=10)
        readout.value = monospace(f"fx = f / pixel pitch = {K[0, 0]:.0f} px\n"
                                  f"field of view 2 atan(w / 2f) = {fov:.1f} deg (w = 36 mm)\n"
                                  f"box spans {state['box_width_px']:.0f} px (black bar)\n"
                                  f"image planes drawn {f_draw / f:.1f} f from the pinhole\n"
                                  f"wall of 1 m squares at {scenes.WALL_DISTANCE:g} m (beyond the 3-D view)")

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
    view = FigureView(figsize=(8.8, 4))
    ax = view.fig.subplots()
    art = optics.draw_similar_triangles(ax, z_max=5.6, h_max=1.3)
    ax.set_title("click or drag in the figure to move the object point", fontsize=9)
    readout = W.HTML()  # beside the sliders, where it never covers the object point
    movers = [art[k] for k in ("big", "small", "object", "point", "ray", "planes", "virtual", "real", "pinhole",
                               "pinhole_dot")]
    for dim in art["dims"].values():
        movers += [dim["arrow"], dim["label"]]
    view.animate(*movers)

    def update(values, state):
        f, Z, Y = values["f"], values["Z"], values["Y"]
        y = optics.update_similar_triangles(art, f, Z, Y)
        state.update(y=y, ratio_image=y / f, ratio_object=Y / Z)
        readout.value = monospace(f"y / f = {y / f:+.3f}\nY / Z = {Y / Z:+.3f}\n=> y = f Y / Z = {y * 100:+.1f} cm")

    demo = build_demo("similar_triangles", controls, view, update, title="Similar triangles: y / f = Y / Z",
                      extra=[readout])

    def on_mouse(event):
        if event.inaxes is ax and event.button == 1 and event.xdata is not None:
            z = float(np.clip(event.xdata, controls["Z"].min, controls["Z"].max))
            y = float(np.clip(-event.ydata, controls["Y"].min, controls["Y"].max))  # the plot shows -y (up)
            demo.set(Z=round(z / 0.05) * 0.05, Y=round(y / 0.05) * 0.05)

    view.fig.canvas.mpl_connect("button_press_event", on_mouse)
    view.fig.canvas.mpl_connect("motion_notify_event", on_mouse)
    return demo


PAGE_Z = 1.0  # the chart's distance in pinhole_size (metres)
BALANCED = 0.05  # the readout calls the blur "balanced" while its two terms differ by under 5 % of the total


@register(lesson="01", sweep={"diameter_mm": [0.05, 0.35, 1.5], "focal_mm": [50, 100, 200]})
def pinhole_size():
    """Blur against pinhole diameter (geometric versus diffraction) and the blurred chart it gives."""
    controls = {
        "diameter_mm": W.FloatLogSlider(value=0.35, base=10, min=np.log10(0.03), max=np.log10(2.5), step=0.02,
                                        description="pinhole d (mm)", continuous_update=True,
                                        style={"description_width": "initial"}, layout=W.Layout(width="300px")),
        "focal_mm": slider(100, 30, 200, 5, "focal length f (mm)"),
    }
    view = FigureView(figsize=(8.8, 4))
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
        limited_by = ("balanced" if abs(b.diffraction - b.geometric) < BALANCED * b.total
                      else "diffraction-limited" if b.diffraction > b.geometric else "geometry-limited")
        f_number = f / d
        state.update(blur_mm=float(b.total) * 1e3, blur_px=blur_px, best_mm=best * 1e3, legible_rows=legible,
                     limited_by=limited_by, blur_mrad=float(b.total) / f * 1e3, f_number=f_number,
                     exposure_vs_f2_8=(f_number / 2.8) ** 2)
        readout.value = monospace(f"best d = {best * 1e3:.2f} mm (star) for Z = {PAGE_Z:g} m\n"
                                  f"your d = {d * 1e3:.2f} mm (grey line): {limited_by}\n"
                                  f"blur {state['blur_mm']:.2f} mm = {blur_px:.1f} px;"
                                  f" blur / f = {state['blur_mrad']:.1f} mrad\n"
                                  f"rows legible: {legible} of {len(rows_px)} (letters over 1.5 x blur)\n"
                                  f"f/d = f/{f_number:.0f}: {state['exposure_vs_f2_8']:,.0f} x the exposure of f/2.8")

    return build_demo("pinhole_size", controls, view, update, title="How big should the pinhole be?",
                      extra=[readout])
