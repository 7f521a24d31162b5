"""The kernel's half of a browser-drawn demo (camlab/widgets/browser): the scene it sends, the links, the fallbacks.

The browser's half is tested by tests/test_browser_geometry_parity.py (the arithmetic, under node)
and tests/test_browser_drawing.py (the canvas in JupyterLab and Voila).
"""

import base64
import io

import numpy as np
import pytest
from matplotlib.image import imread

from camlab.widgets.browser import BACKGROUND_SCALE, BrowserCanvas
from camlab.widgets.start_here import HOUSE, stack_check


@pytest.fixture
def in_a_kernel(monkeypatch):
    """Build demos as `%matplotlib widget` in a kernel would (the display mode "ipympl")."""
    monkeypatch.setenv("CAMLAB_FIGURE_MODE", "ipympl")
    monkeypatch.delenv("CAMLAB_BROWSER_DRAWING", raising=False)


def test_in_a_kernel_the_demo_shows_a_browser_canvas_with_the_scene(in_a_kernel):
    demo = stack_check()
    canvas = demo.view.canvas
    assert isinstance(canvas, BrowserCanvas) and demo.view.widget is canvas
    assert canvas in demo.widget.children[1:], "the canvas is not where the figure goes"
    scene = canvas.scene
    assert scene["kind"] == "stack_check" and scene["params"] == ["angle", "scale"]
    assert (canvas.angle, canvas.scale) == (40.0, 1.0)  # the sliders' values when it was built
    png = imread(io.BytesIO(base64.b64decode(scene["background"].split(",", 1)[1])))
    bbox = demo.figure.bbox
    assert png.shape[:2] == (
        round(bbox.height * BACKGROUND_SCALE),
        round(bbox.width * BACKGROUND_SCALE),
    )
    assert scene["backgroundScale"] == BACKGROUND_SCALE
    assert "house" in canvas.alt.lower()
    links = {link.target[1]: link.source for link in demo.view.links}
    assert links == {
        "angle": (demo.controls["angle"], "value"),
        "scale": (demo.controls["scale"], "value"),
    }
    assert all(link.target[0] is canvas for link in demo.view.links)


def test_a_choice_is_linked_by_its_index_and_the_scene_names_its_options(in_a_kernel):
    """epipolar_lines' motion buttons: ToggleButtons sync their index, not their value."""
    from camlab.widgets.stereo_rectification import epipolar_lines

    demo = epipolar_lines()
    canvas, buttons = demo.view.canvas, demo.controls["motion"]
    links = {link.target[1]: link.source for link in demo.view.links}
    assert links["motion"] == (buttons, "index") and links["u"] == (demo.controls["u"], "value")
    assert canvas.scene["choices"] == {"motion": list(buttons.options)}
    assert canvas.motion == 0 and canvas.scene["choices"]["motion"][0] == buttons.value


def test_the_scene_maps_data_to_the_pixels_matplotlib_draws(in_a_kernel):
    demo = stack_check()
    for panel, ax in zip(demo.view.canvas.scene["panels"], demo.figure.axes, strict=True):
        T = np.array(panel["toPixels"])
        data = HOUSE
        ours = np.c_[data, np.ones(len(data))] @ T.T
        x, y = ax.transData.transform(data).T
        # Agg's buffer has int(height) rows (409 for a 409.5 px figure) and flips y about that
        assert np.allclose(ours[:, 0], x) and np.allclose(
            ours[:, 1], int(demo.figure.bbox.height) - y
        )


def test_pixels_in_a_kernel_equal_the_headless_drawing(in_a_kernel, monkeypatch):
    demo = stack_check()
    demo.set(angle=-135.0, scale=1.7)
    live = demo.view.pixels()
    monkeypatch.setenv("CAMLAB_FIGURE_MODE", "agg")
    headless = stack_check()
    headless.set(angle=-135.0, scale=1.7)
    assert np.array_equal(live, headless.view.pixels())
    assert demo.state["readout"] == headless.state["readout"]


def test_switched_off_the_demo_is_drawn_in_the_kernel(in_a_kernel, monkeypatch):
    import matplotlib.pyplot as plt

    monkeypatch.setenv("CAMLAB_BROWSER_DRAWING", "0")
    backend = plt.get_backend()
    plt.switch_backend("module://ipympl.backend_nbagg")
    try:
        demo = stack_check()
        plt.close(demo.figure)
    finally:
        plt.switch_backend(backend)
    assert demo.view.canvas is None and demo.view.mode == "ipympl"
    assert type(demo.view.widget).__name__ == "Canvas"  # ipympl's


def test_similar_triangles_sends_its_scene_links_its_three_sliders_and_draws_as_headless(
    in_a_kernel, monkeypatch
):
    from camlab.plotting import optics
    from camlab.widgets.pinhole_camera import similar_triangles

    demo = similar_triangles()
    canvas = demo.view.canvas
    scene = canvas.scene
    assert scene["kind"] == "similar_triangles" and scene["params"] == ["f", "Z", "Y"]
    assert (canvas.f, canvas.Z, canvas.Y) == (0.8, 3.0, -0.8)
    links = {link.target[1]: link.source for link in demo.view.links}
    assert links == {k: (demo.controls[k], "value") for k in ("f", "Z", "Y")}
    # the layout's h is the kernel's: 0.85 of the axes' top
    assert scene["h"] == demo.figure.axes[0].get_ylim()[1] * 0.85
    assert scene["rooms"]["zRoom"] == optics.Z_LABEL_ROOM
    assert scene["ranges"]["Z"] == dict(min=1.2, max=5.0, step=0.05)
    title = scene["styles"]["title"]
    assert len(title["baselines"]) == 2 and title["baselines"][0] < title["baselines"][1]
    demo.set(f=0.45, Z=1.6, Y=0.35)
    live = demo.view.pixels()
    monkeypatch.setenv("CAMLAB_FIGURE_MODE", "agg")
    headless = similar_triangles()
    headless.set(f=0.45, Z=1.6, Y=0.35)
    assert np.array_equal(live, headless.view.pixels())
    assert demo.state == headless.state


def test_three_cameras_sends_its_world_and_draws_as_headless(in_a_kernel, monkeypatch):
    from camlab.fixtures import box_and_rails
    from camlab.widgets.affine_cameras import three_cameras

    demo = three_cameras()
    scene = demo.view.canvas.scene
    assert scene["kind"] == "three_cameras"
    assert scene["params"] == ["azimuth", "elevation", "distance"]
    assert np.array_equal(scene["segments"], box_and_rails())
    assert scene["parts"] == {"cube": [0, 12, 2], "rails": [12, 16, 7]}
    assert scene["principalPoint"] == [319.5, 239.5] and scene["size"] == [640, 480]
    assert len(scene["panels"]) == 3
    demo.set(azimuth=60, elevation=70, distance=2.5)
    live = demo.view.pixels()
    monkeypatch.setenv("CAMLAB_FIGURE_MODE", "agg")
    headless = three_cameras()
    headless.set(azimuth=60, elevation=70, distance=2.5)
    assert np.array_equal(live, headless.view.pixels())
    assert demo.state["gaps"] == headless.state["gaps"]


def test_dolly_zoom_sends_its_panels_and_draws_as_headless(in_a_kernel, monkeypatch):
    from camlab.widgets.affine_cameras import dolly_zoom

    demo = dolly_zoom()
    scene = demo.view.canvas.scene
    assert scene["kind"] == "dolly_zoom" and scene["params"] == ["distance", "offset"]
    assert [p["model"] for p in scene["images"]] == ["weak perspective", "para-perspective"]
    assert len(scene["distances"]) == 60 and scene["principalPoint"] == [319.5, 239.5]
    # the error panel's map takes log10 of the data: its corners land on the axes' box
    ax = demo.figure.axes[2]
    T = np.array(scene["error"]["toPixels"])
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    corners = np.c_[np.log10([[x0, y0], [x1, y1]]), np.ones(2)] @ T.T
    box = scene["error"]["box"]
    assert np.allclose(corners[:, :2], [[box["left"], box["bottom"]], [box["right"], box["top"]]])
    demo.set(distance=30.0, offset=40)
    live = demo.view.pixels()
    monkeypatch.setenv("CAMLAB_FIGURE_MODE", "agg")
    headless = dolly_zoom()
    headless.set(distance=30.0, offset=40)
    assert np.array_equal(live, headless.view.pixels())
    assert demo.state["rms_error"] == headless.state["rms_error"]


def test_pinhole_projection_links_its_checkbox_as_a_flag_and_sends_its_textured_planes(
    in_a_kernel, monkeypatch
):
    """The real-plane checkbox reaches the canvas as a boolean; the scene holds the box's six faces
    (float32 textures) and the wall as its 16 x 12 squares; pixels equal the headless drawing."""
    import traitlets

    from camlab.fixtures.lessons import WALL_TEXELS
    from camlab.widgets.pinhole_camera import pinhole_projection

    demo = pinhole_projection()
    canvas = demo.view.canvas
    links = {link.target[1]: link.source for link in demo.view.links}
    assert links["real_plane"] == (demo.controls["real_plane"], "value")
    assert isinstance(canvas.traits()["real_plane"], traitlets.Bool) and canvas.real_plane is False
    planes = canvas.scene["planes"]
    assert [p["box"] for p in planes] == [True] * 6 + [False]
    wall = planes[-1]["texture"]
    assert (wall["width"], wall["height"], wall["texels"]) == (16, 12, WALL_TEXELS)
    face = planes[0]["texture"]
    assert len(base64.b64decode(face["data"])) == 4 * face["width"] * face["height"]
    demo.set(focal_mm=83.0, distance=1.1, real_plane=True)
    live = demo.view.pixels()
    monkeypatch.setenv("CAMLAB_FIGURE_MODE", "agg")
    headless = pinhole_projection()
    headless.set(focal_mm=83.0, distance=1.1, real_plane=True)
    assert np.array_equal(live, headless.view.pixels())


def test_camera_explorer_sends_its_world_and_3d_panel_and_draws_as_headless(
    in_a_kernel, monkeypatch
):
    from camlab.fixtures import house_scene
    from camlab.widgets.projective_camera import camera_explorer

    demo = camera_explorer()
    scene = demo.view.canvas.scene
    assert scene["kind"] == "camera_explorer" and scene["params"] == list(demo.controls)
    links = {link.target[1]: link.source for link in demo.view.links}
    assert links == {k: (c, "value") for k, c in demo.controls.items()}
    assert np.array_equal(scene["segments"], house_scene())
    # every animated artist is drawn, once, in the order a frame paints it: lines, the plane, texts
    order = scene["order"]
    assert len(order) == len(demo.view._animated) == len(set(order)) == 20
    assert order.index("plane") > order.index("thumbnail") and order[-2:] == [
        "image",
        "principalPoint",
    ]
    assert (
        scene["styles"]["worldLabel2"]["text"] == "Z"
        and "700" in scene["styles"]["worldLabel2"]["font"]
    )
    assert scene["styles"]["frustum"]["halo"] == "#ffffff"
    # the 3-D axes' 2-D view box lands on its box in the canvas
    p3 = scene["panel3d"]
    x0, y0, x1, y1 = p3["viewBox"]
    corners = np.array([[x0, y0, 1.0], [x1, y1, 1.0]]) @ np.array(p3["toPixels"]).T
    box = p3["box"]
    assert np.allclose(corners[:, :2], [[box["left"], box["bottom"]], [box["right"], box["top"]]])
    demo.set(azimuth=100, roll=40, fx=300, slide=0.5)
    live = demo.view.pixels()
    monkeypatch.setenv("CAMLAB_FIGURE_MODE", "agg")
    headless = camera_explorer()
    headless.set(azimuth=100, roll=40, fx=300, slide=0.5)
    assert np.array_equal(live, headless.view.pixels())
    assert np.array_equal(demo.state["P"], headless.state["P"])


def test_opencv_vs_opengl_links_its_orbit_and_frame_and_draws_as_headless(in_a_kernel, monkeypatch):
    from camlab.widgets.projective_camera import GL_NAMES, opencv_vs_opengl

    demo = opencv_vs_opengl()
    scene = demo.view.canvas.scene
    assert scene["kind"] == "opencv_vs_opengl" and scene["params"] == ["orbit", "frame"]
    assert scene["choices"] == {"frame": ["OpenCV", "OpenGL / Blender"]}
    links = {link.target[1]: link.source for link in demo.view.links}
    assert links == {
        "orbit": (demo.controls["orbit"], "value"),
        "frame": (demo.controls["frame"], "index"),
    }
    assert scene["names"] == {k: list(v) for k, v in GL_NAMES.items()}
    # every animated artist but the empty thumbnail (no image lines on the plane here)
    assert len(scene["order"]) == len(set(scene["order"])) == len(demo.view._animated) - 1 == 16
    demo.set(orbit=-70, frame="OpenGL / Blender")
    live = demo.view.pixels()
    monkeypatch.setenv("CAMLAB_FIGURE_MODE", "agg")
    headless = opencv_vs_opengl()
    headless.set(orbit=-70, frame="OpenGL / Blender")
    assert np.array_equal(live, headless.view.pixels())
    assert np.array_equal(demo.state["matrix_world"], headless.state["matrix_world"])


def test_a_drag_sent_from_the_browser_turns_lift_to_plane_as_matplotlib_turns_it(
    in_a_kernel, monkeypatch
):
    """The browser cannot redraw a 3-D box: it sends a press, moves and the release on it (the scene's
    ``turn`` boxes) to the kernel. There mplot3d turns it as a headless drag does; each move sends
    the scene again, with the new 3-D map and a background at the figure's size (the release: sharp),
    answers ``turned``, and the kernel's pixels equal the headless drawing at that view."""
    from matplotlib.backend_bases import MouseButton, MouseEvent

    from camlab.widgets.browser import axes_box, canvas_height
    from camlab.widgets.projective_plane import lift_to_plane

    demo = lift_to_plane()
    view, canvas = demo.view, demo.view.canvas
    box = axes_box(demo.figure.axes[0])
    assert canvas.scene["turn"] == [box]
    answers = []
    monkeypatch.setattr(canvas, "send", lambda content, buffers=None: answers.append(content))
    u, v = (box["left"] + box["right"]) / 2, (box["top"] + box["bottom"]) / 2
    path = [("pointerdown", u, v), ("pointermove", u + 30, v + 10), ("pointermove", u + 60, v + 20)]
    path.append(("pointerup", u + 60, v + 20))
    maps, scales = [canvas.scene["space"]["toPixels"]], []
    for kind, x, y in path:
        canvas._handle_custom_msg({"type": kind, "u": x, "v": y, "button": 1}, [])
        maps.append(canvas.scene["space"]["toPixels"])
        scales.append(canvas.scene["backgroundScale"])
    assert answers == [{"turned": True}] * 4
    assert maps[1] == maps[0] and maps[2] != maps[1] and maps[3] != maps[2] and maps[4] == maps[3]
    assert scales == [BACKGROUND_SCALE, 1, 1, BACKGROUND_SCALE]
    monkeypatch.setenv("CAMLAB_FIGURE_MODE", "agg")
    headless = lift_to_plane()
    fig_canvas, height = headless.figure.canvas, canvas_height(headless.figure)
    for event, x, y in (
        ("button_press_event", u, v),
        ("motion_notify_event", u + 60, v + 20),
        ("button_release_event", u + 60, v + 20),
    ):
        button = None if event == "motion_notify_event" else MouseButton.LEFT
        fig_canvas.callbacks.process(
            event, MouseEvent(event, fig_canvas, x, height - y, button=button)
        )
    turned, ax3 = demo.figure.axes[0], headless.figure.axes[0]
    assert np.allclose([turned.azim, turned.elev], [ax3.azim, ax3.elev])
    assert (ax3.azim, ax3.elev) != (-60, 16)
    demo.set(x=-1.2, w=0.4)
    headless.set(x=-1.2, w=0.4)
    assert np.abs(view.pixels().astype(int) - headless.view.pixels()).max() <= 1
