"""Lesson 12's click-to-measure: two clicks give a length, more and a right-click an area."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from camlab.widgets.measure_the_world import SIGMA_PX, click_to_measure  # noqa: E402


def test_clicks_measure_a_length_then_an_area_and_start_again():
    fig, ax = plt.subplots()
    seen = []

    def length(a, b):
        seen.append(("length", np.linalg.norm(b - a)))
        return "L"

    def area(points):
        seen.append(("area", len(points)))
        return "A"

    clicks = click_to_measure(ax, length, area)
    clicks.click(0, 0)
    assert seen == [] and ax.get_title() == ""
    clicks.click(3, 4)
    assert seen == [("length", 5.0)] and ax.get_title() == "L"
    clicks.click(3, 0)
    clicks.click(0, 0, button=3)
    assert seen[-1] == ("area", 3) and ax.get_title() == "A"
    assert len(clicks.line.get_xdata()) == 4  # the outline drawn closed
    clicks.click(1, 1)  # a new measurement starts
    assert clicks.points == [(1.0, 1.0)]
    clicks.click(2, 2, button=3)  # a right-click with fewer than three points clears
    assert clicks.points == []
    plt.close(fig)


def test_ray_angle_follows_the_two_laws():
    from camlab.widgets.measure_the_world import ray_angle

    demo = ray_angle()
    for alpha, pick in ((40.0, 0.5), (10.0, 0.5), (90.0, 1.0)):
        demo.set(alpha=alpha, pick=pick)
        half = np.radians(alpha) / 2
        c = 0.332 * pick  # 0.166 mm at 0.5 px (section 3)
        assert abs(demo.state["depth_mm"] - c / np.sin(half)) < 1e-9
        assert abs(demo.state["across_mm"] - c / np.cos(half)) < 1e-9
    assert abs(demo.state["baseline_mm"] - 2 * 303.0 * np.sin(np.radians(45.0))) < 1e-9
    demo.set(alpha=40.0, pick=0.1)  # the ellipse, in mm: the picking slider scales it
    small = demo.figure.axes[1].lines[2].get_xydata()
    demo.set(alpha=40.0, pick=1.0)
    large = demo.figure.axes[1].lines[2].get_xydata()
    assert np.allclose(large, 10 * small)
    demo.set(alpha=5.0, pick=1.0)
    assert (
        demo.state["in_frame"] is False
    )  # nearly parallel rays: the readout says the ellipse leaves the frame
    # the lesson's claim: on the slider's whole degrees the zoom holds the ellipse from 10 deg at
    # 0.5 px and from 19 deg at 1 px, and at every angle (from 5 deg) at 0.1 px
    for pick, first in ((0.5, 10.0), (1.0, 19.0), (0.1, 5.0)):
        demo.set(alpha=first, pick=pick)
        assert demo.state["in_frame"] is True
        if first > 5.0:
            demo.set(alpha=first - 1, pick=pick)
            assert demo.state["in_frame"] is False


def test_flip_pose_gives_section_2b_gaps():
    from camlab.widgets.flip_pose import flip_pose

    demo = flip_pose()  # the 5 cm tag at 1.5 m and 20 deg: 0.7 sigma, the cameras 1026 mm apart
    assert abs(demo.state["gap"] - 0.72) < 0.01 and abs(demo.state["dC_mm"] - 1026) < 1
    assert demo.state["largest_px"] < SIGMA_PX and abs(demo.state["dR_deg"] - 40) < 0.5
    assert "differ by a rotation of 40° and put the camera 1026 mm apart" in demo.state["readout"]
    assert f"move by at most {demo.state['largest_px']:.2f} px" in demo.state["readout"]
    demo.set(target="board (54 corners)")  # the board there: 13.3 sigma, never flips
    assert abs(demo.state["gap"] - 13.28) < 0.01 and demo.state["rule"] < 1e-30
    assert "chance below 0.05% by the rule" in demo.state["readout"]  # never "0.0%"
    demo.set(tilt=2.0)  # near head-on: the rule's 8.5 %, the camera 105 mm off
    assert abs(demo.state["rule"] - 0.085) < 0.001 and abs(demo.state["dC_mm"] - 105) < 1
    curve = demo.figure.axes[1].lines[1].get_ydata()
    demo.set(distance=0.6)  # closer: the whole curve rises
    assert np.all(demo.figure.axes[1].lines[1].get_ydata() > curve)
