"""The 3-D epipolar figure of lesson 11 (camlab.plotting.epipolar3d)."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np

from camlab import fixtures
from camlab.plotting import epipolar3d, palette, scene3d


def test_epipolar_line_ends_pass_through_the_image_of_x_and_the_epipole():
    c1, c2 = fixtures.stereo_pair(0.5, np.deg2rad(40))
    X = np.array([0.05, 1.2, 1.25])
    for cam, other in ((c1, c2), (c2, c1)):
        ends = epipolar3d.epipolar_line_ends(cam, other, X)
        line = np.cross(*np.c_[ends, np.ones(2)])
        x = np.append(cam.project(X[None])[0], 1.0)
        e = cam.P @ np.append(other.centre, 1.0)
        assert abs(line @ x) / np.linalg.norm(line[:2]) < 1e-9
        assert abs(line @ e) / np.linalg.norm(line[:2]) / abs(e[2]) < 1e-6


def test_image_plane_corners_lie_at_the_given_depth_and_project_to_the_pixel_corners():
    c1, _ = fixtures.stereo_pair(0.2, 0.1)
    corners = epipolar3d.image_plane_corners(c1, 0.3)
    assert np.allclose(c1.depth(corners), 0.3)
    w, h = c1.image_size
    assert np.allclose(
        c1.project(corners), [[-0.5, -0.5], [w - 0.5, -0.5], [w - 0.5, h - 0.5], [-0.5, h - 0.5]]
    )


def test_draw_epipolar_geometry_draws_without_error():
    fig = plt.figure()
    ax = scene3d.axes3d(fig, 111)
    pair = fixtures.stereo_pair(0.5, np.deg2rad(40))
    epipolar3d.draw_epipolar_geometry(ax, *pair, [0.05, 1.2, 1.25], ghosts=pair)
    assert len(ax.lines) > 8
    plt.close(fig)


def test_lesson_11_figures_keep_both_camera_centres_inside_the_axes():
    """Cells 6 and 20 zoom the scene (1.2); at 1.4 mplot3d clipped camera C out of the panel."""
    from mpl_toolkits.mplot3d import proj3d

    pair = fixtures.stereo_pair(0.5, np.deg2rad(40))
    for figsize, cols in (((10.5, 3.9), 2), ((10.5, 4.2), 2)):  # cells 6 and 20 (two panels each)
        fig = plt.figure(figsize=figsize, layout="constrained")
        axes = []
        for k in range(cols):
            ax = scene3d.axes3d(fig, 100 + 10 * cols + k + 1, elev=20, azim=-58)
            epipolar3d.draw_epipolar_geometry(ax, *pair, [0.05, 1.2, 1.25], also=[0.0, 0.7, 1.1])
            ax.set_box_aspect(ax.get_box_aspect(), zoom=1.2)
            axes.append(ax)
        fig.canvas.draw()
        for ax in axes:
            for C in (pair[0].centre, pair[1].centre):
                x, y, _ = proj3d.proj_transform(*C, ax.get_proj())
                assert ax.bbox.contains(*ax.transData.transform((x, y))), C
        plt.close(fig)


def test_image_planes_and_centres_take_their_cameras_colours():
    """Lesson 11 (cells 5 and 19) calls C and its plane blue, C' and its plane orange."""
    from matplotlib.colors import to_hex

    fig = plt.figure()
    ax = scene3d.axes3d(fig, 111)
    pair = fixtures.stereo_pair(0.5, np.deg2rad(40))
    epipolar3d.draw_epipolar_geometry(ax, *pair, [0.05, 1.2, 1.25], ghosts=pair)
    solid = [
        to_hex(ln.get_color())
        for ln in ax.lines
        if ln.get_linestyle() == "-" and len(ln.get_xdata()) == 5
    ]
    assert solid == [to_hex(palette.BLUE), to_hex(palette.ORANGE)]
    dots = {t.get_text(): to_hex(t.get_color()) for t in ax.texts if t.get_text() in ("C", "C'")}
    assert dots == {"C": to_hex(palette.BLUE), "C'": to_hex(palette.ORANGE)}
    plt.close(fig)
