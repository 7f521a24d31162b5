"""Lesson 11 demos and exercises: specific behaviour beyond the generic sweeps."""

import os

os.environ.setdefault("CAMLAB_FIGURE_MODE", "agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from camlab import epipolar as ep  # noqa: E402
from camlab import (
    fixtures,  # noqa: E402
)
from camlab.exercises import EXERCISES, all_exercises, check, solution  # noqa: E402
from camlab.widgets import stereo_rectification as demos  # noqa: E402

all_exercises()


class _Click:
    def __init__(self, ax, x, y):
        self.inaxes, self.xdata, self.ydata = ax, x, y


def test_epipolar_lines_click_moves_point_and_line_passes_through_true_match():
    demo = demos.epipolar_lines()
    before = demo.view.pixels()
    demo.handlers["button_press_event"](_Click(demo.figure.axes[0], 150.0, 120.0))
    assert demo.controls["u"].value == 150.0 and demo.controls["v"].value == 120.0
    assert not np.array_equal(before, demo.view.pixels())
    # every depth along the ray images onto the right epipolar line
    l2, uv = demo.state["line_right"], demo.state["depth_points"]
    assert np.nanmax(np.abs(uv @ l2[:2] + l2[2])) < 1e-6
    demo.handlers["button_press_event"](
        _Click(demo.figure.axes[1], 10.0, 10.0)
    )  # clicks in the right image are ignored
    assert demo.controls["u"].value == 150.0


def test_epipolar_lines_parallel_cameras_put_epipole_at_infinity():
    demo = demos.epipolar_lines()
    demo.set(toe_in=0.0)
    e = demo.state["epipoles"]
    assert abs(e.e2[2]) < 1e-9 and abs(e.e1[2]) < 1e-9
    line = demo.state["line_right"]
    assert abs(line[0]) < 1e-9  # a horizontal row
    demo.set(toe_in=15.0)
    assert abs(demo.state["epipoles"].e2[2]) > 1e-6


def test_rectify_pair_vertical_disparity_drops():
    demo = demos.rectify_pair()
    demo.set(method="original")
    raw = demo.state["vertical_median"]
    demo.set(method="calibrated")
    cal = demo.state["vertical_median"]
    demo.set(method="uncalibrated")
    unc = demo.state["vertical_median"]
    assert raw > 5 and cal < 0.1 and unc < 0.5
    # the calibrated route uses the stereo-calibrated cameras, so it is not exact: its error is
    # the calibration's (true cameras would give ~1e-10 px, a spike that teaches nothing)
    assert cal > 1e-3


def test_rectify_pair_zoom_shows_the_raw_vertical_disparity():
    """The raw pair's few pixels of vertical disparity are invisible at half size: the zoom panel
    enlarges one match whose offset is large, and it vanishes after rectification."""
    demo = demos.rectify_pair()
    demo.set(method="original")
    assert demo.state["zoom_offset"] > 3  # half-size px, drawn about 8 screen px each
    for method in ("calibrated", "uncalibrated"):
        demo.set(method=method)
        assert abs(demo.state["zoom_offset"]) < 0.1


def test_epipolar_lines_forward_motion_puts_the_epipole_in_the_image():
    demo = demos.epipolar_lines()
    assert not demo.state["epipole_inside"]  # the side-by-side rig: far outside
    demo.set(motion="forward (driving)", toe_in=5.0)
    assert demo.state["epipole_inside"]
    e2 = demo.state["epipoles"].e2
    u, v = e2[:2] / e2[2]
    assert 0 < u < 639 and 0 < v < 479
    # every epipolar line passes through it
    assert abs(demo.state["line_right"] @ e2) < 1e-9 * np.linalg.norm(
        demo.state["line_right"]
    ) * np.linalg.norm(e2)
    # the centre reference pixel is the left epipole: skipped, not drawn as rounding noise
    np.testing.assert_allclose(demo.state["pencil_skipped"], [[319.5, 239.5]])
    demo.set(motion="sideways (stereo rig)")
    assert len(demo.state["pencil_skipped"]) == 0


def test_disparity_demo_depth_accuracy_and_block_size():
    demo = demos.disparity_depth()
    demo.set(block_size=9)
    assert demo.state["median_error_percent"] < 2 and demo.state["coverage"] > 0.6
    d9 = demo.state["disparity"]
    demo.set(method="SGBM (OpenCV)")
    assert demo.state["median_error_percent"] < 2
    assert not np.array_equal(np.isnan(d9), np.isnan(demo.state["disparity"]))


def test_rig_pair_geometry():
    c1, c2 = fixtures.stereo_pair(0.3, 0.0)
    assert np.isclose(np.linalg.norm(c2.centre - c1.centre), 0.3)
    assert np.allclose(c1.R, c2.R)
    c1, c2 = fixtures.stereo_pair(0.3, np.deg2rad(10))
    assert np.isclose(np.degrees(np.arccos(c1.R[2] @ c2.R[2])), 10)


@pytest.mark.parametrize("name", ["eight_point", "epipoles", "disparity_to_depth"])
def test_lesson_11_exercises_accept_the_reference(name, capsys):
    assert EXERCISES[name].lesson == "11"
    assert check(name, EXERCISES[name].reference)
    assert solution(name) is None and "def " in capsys.readouterr().out


def test_eight_point_exercise_accepts_a_student_style_solution():
    def eight_point(x1, x2):  # what a student writes: normalise, solve, rank 2, un-normalise
        def T(p):
            c = p.mean(0)
            s = np.sqrt(2) / np.mean(np.linalg.norm(p - c, axis=1))
            return np.array([[s, 0, -s * c[0]], [0, s, -s * c[1]], [0, 0, 1]])

        T1, T2 = T(x1), T(x2)
        a = np.c_[x1, np.ones(len(x1))] @ T1.T
        b = np.c_[x2, np.ones(len(x2))] @ T2.T
        A = np.einsum("ni,nj->nij", b, a).reshape(len(a), 9)
        F = np.linalg.svd(A)[2][-1].reshape(3, 3)
        U, S, Vt = np.linalg.svd(F)
        return T2.T @ U @ np.diag([S[0], S[1], 0]) @ Vt @ T1

    assert check("eight_point", eight_point)


def test_epipole_exercise_rejects_euclidean_answer():
    def euclid(F):
        e = ep.epipoles(F)
        return e.e1[:2] / e.e1[2], e.e2[:2] / e.e2[2]

    with pytest.raises(AssertionError, match="homogeneous 3-vectors"):
        check("epipoles", euclid)


def test_epipolar_lines_real_mouse_event_through_the_canvas():
    """A matplotlib MouseEvent dispatched by the canvas (what ipympl sends on a click) moves the point."""
    from matplotlib.backend_bases import MouseEvent

    demo = demos.epipolar_lines()
    fig = demo.figure
    fig.canvas.draw()
    x, y = demo.figure.axes[0].transData.transform((200.0, 150.0))
    fig.canvas.callbacks.process(
        "button_press_event", MouseEvent("button_press_event", fig.canvas, x, y, button=1)
    )
    assert np.allclose([demo.controls["u"].value, demo.controls["v"].value], [200, 150], atol=1e-6)
    assert np.allclose(demo.state["point"], [200, 150], atol=1e-6)
