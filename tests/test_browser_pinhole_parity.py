"""Lesson 01's pinhole_projection drawn in the browser (pinhole.js, textured.js) equals its numpy twins.

The 3-D view (optics.pinhole_view), the demo's numbers and texts (its state and titles), mplot3d's
projection and the renderer's geometry (clip_to_near, metres_per_canvas_px, visible_planes) at
1e-9 relative, under node on random inputs. The recorded image (renderPlanes) is compared with
camlab.render.render, whose warps are OpenCV's: the JavaScript samples as cv2.warpPerspective does
(positions rounded to 1/32 px), but its anti-aliased coverage of a face's edge is the area inside
the edge where cv2.fillConvexPoly(LINE_AA) ramps over about a pixel, so the two differ along the
box's outline: bounded here in grey levels, as the browser test compares pictures.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy.ndimage import gaussian_filter
from test_browser_geometry_parity import CASES, NODE, assert_twins, random_rotation, run_js

from camlab import fixtures, render, scenes
from camlab.plotting import optics
from camlab.plotting.optics.pinhole_camera import _clip_to_frame
from camlab.render.canvas import visible_planes
from camlab.render.model import clip_to_near, metres_per_canvas_px

BROWSER = Path(__file__).resolve().parent.parent / "camlab" / "widgets" / "browser"
PINHOLE, TEXTURED = BROWSER / "pinhole.js", BROWSER / "textured.js"

pytestmark = pytest.mark.skipif(
    NODE is None, reason="node is not installed: the JavaScript twins cannot be run"
)


@pytest.fixture(scope="module")
def demo():
    """pinhole_projection built as in a kernel, so it has the scene the browser gets."""
    mp = pytest.MonkeyPatch()
    mp.setenv("CAMLAB_FIGURE_MODE", "ipympl")
    mp.delenv("CAMLAB_BROWSER_DRAWING", raising=False)
    try:
        from camlab.widgets.pinhole_camera import pinhole_projection

        yield pinhole_projection()
    finally:
        mp.undo()


def _scene(demo) -> dict:
    return {k: v for k, v in demo.view.canvas.scene.items() if k != "background"}


def _settings(rng: np.random.Generator, n: int) -> list[dict]:
    """Slider values on their steps, both planes, and the sweep's ends."""
    out = [
        dict(focal_mm=f, distance=z, real_plane=r)
        for f in (15, 100)
        for z in (0.8, 4.0)
        for r in (False, True)
    ]
    out += [
        dict(
            focal_mm=float(rng.integers(15, 101)),
            distance=float(np.round(rng.uniform(0.8, 4.0), 1)),
            real_plane=bool(rng.integers(2)),
        )
        for _ in range(n)
    ]
    return out


def _box(rng: np.random.Generator) -> tuple:
    """A randomly turned, sized and placed box before the pinhole: its faces for pinhole_view."""
    faces = scenes.box(
        [rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), rng.uniform(0.5, 4)],
        rng.uniform(0.05, 0.6, 3),
        R=random_rotation(rng),
        texels=8,
        rng=0,
    )
    return optics.plane_faces(faces), scenes.plane_outlines(faces)


def test_the_3d_view_equals_optics_pinhole_view():
    rng = np.random.default_rng(1)
    cases = []
    for k in range(CASES // 4):
        faces, edges = _box(rng)
        f_draw = rng.uniform(0.05, 1.2)
        half = rng.uniform(0.05, 0.6) if k % 2 else 0.02  # some pictures cut by the frame
        cases.append((faces, edges, f_draw, half))
    calls = [("pinholeView", [f.corners.tolist(), f.greys.tolist(), d, h]) for f, _e, d, h in cases]
    for js, (faces, edges, f_draw, half) in zip(run_js(calls, PINHOLE), cases, strict=True):
        py = optics.pinhole_view(edges, f_draw, faces, half)
        assert_twins(js["edges"], py["edges"], "edges")
        assert_twins(js["rays"], py["rays"], "rays")
        for name in ("real", "virtual"):
            assert_twins(js["frames"][name], py["frames"][name], "frame")
            assert_twins(js["images"][name], py["images"][name], "picture edges")
        for name in ("box", "real", "virtual"):
            assert len(js["fills"][name]) == len(py["fills"][name]), name
            for (pj, gj), (pp, gp) in zip(js["fills"][name], py["fills"][name], strict=True):
                assert_twins(pj, pp, f"{name} fill")
                assert gj == gp


def test_the_frame_cut_equals_clip_to_frame():
    rng = np.random.default_rng(2)
    polys = [rng.uniform(-1, 1, (int(rng.integers(3, 7)), 2)) for _ in range(CASES)]
    polys = [p[np.argsort(np.arctan2(*(p - p.mean(0)).T[::-1]))] for p in polys]  # convex-ish order
    out = run_js([("clipToFrame", [p.tolist(), 0.5, 0.375]) for p in polys], PINHOLE)
    for js, p in zip(out, polys, strict=True):
        py = _clip_to_frame(p, 0.5, 0.375)
        assert_twins(np.reshape(js, (-1, 2)), py, "cut polygon")


def test_the_frame_numbers_and_texts_equal_the_demo_s(demo):
    """pinholeFrame at the sliders' values: the demo's state, 3-D view, bar and both texts."""
    rng = np.random.default_rng(3)
    settings = _settings(rng, 20)
    scene = {k: v for k, v in _scene(demo).items() if k not in ("planes", "panels")}  # not needed
    out = run_js([("pinholeFrame", [scene, v]) for v in settings], PINHOLE)
    ax_img = demo.figure.axes[1]
    for js, v in zip(out, settings, strict=True):
        demo.set(**v)
        s = demo.state
        for key in ("fx", "box_width_px", "fov_deg", "f_draw", "draw_scale"):
            assert_twins(js[key], s[key], key)
        assert_twins(js["K"], s["K"], "K")
        assert (js["bar_clipped"], js["plane"]) == (s["bar_clipped"], s["plane"])
        assert js["title"] == ax_img.title.get_text()
        note = next(t for t in ax_img.texts if t.get_text().startswith("image planes"))
        assert js["note"] == note.get_text()
        bar, ends = demo.view.fig.axes[1].lines[:2]
        assert_twins(js["bar"], bar.get_xdata(), "bar")
        assert_twins(np.reshape(js["ends"], -1), np.reshape(ends.get_xdata(), -1), "bar ends")


def test_the_3d_projection_is_mplot3d_s(demo):
    from mpl_toolkits.mplot3d import proj3d

    from camlab.widgets.browser import to_canvas_pixels

    scene = _scene(demo)
    rng = np.random.default_rng(4)
    X = np.column_stack(
        [
            rng.uniform(-0.3, 0.3, CASES),
            rng.uniform(-0.3, 0.3, CASES),
            rng.uniform(-1.3, 4.5, CASES),
        ]
    )
    js = run_js(
        [("pinholePixels", [scene["M"], scene["toPixels"], x.tolist()]) for x in X], PINHOLE
    )
    ax3 = demo.figure.axes[0]
    xs, ys, zs = proj3d.proj_transform(X[:, 2], -X[:, 0], -X[:, 1], ax3.get_proj())
    uv = np.column_stack([xs, ys, np.ones(len(xs))]) @ np.asarray(to_canvas_pixels(ax3)).T
    assert_twins(np.asarray(js)[:, :2], uv[:, :2], "canvas px")
    assert_twins(np.asarray(js)[:, 2], zs, "projected depth")


def test_the_renderer_s_geometry_equals_camlab_render_s():
    """clipToNear, metresPerCanvasPx and visiblePlanes (seen, polygon, depth, map) at 1e-9."""
    rng = np.random.default_rng(5)
    Kc = np.array([[900.0, 0, 320], [0, 900, 240], [0, 0, 1]])
    planes = []
    for _ in range(CASES // 4):
        planes.append(
            scenes.textured_plane(
                np.zeros((4, 4), np.float32),
                rng.uniform(0.2, 3),
                R=random_rotation(rng),
                t=(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-0.5, 3)),
            )
        )
    data = [
        dict(
            R=p.R.tolist(), t=p.t.tolist(), extent=list(map(float, p.extent)), twoSided=p.two_sided
        )
        for p in planes
    ]
    calls = [("visiblePlanes", [data, Kc.tolist()])]
    calls += [("clipToNear", [d["extent"], d["R"], d["t"]]) for d in data]
    out = run_js(calls, TEXTURED)
    seen = visible_planes(planes, np.eye(3), np.zeros(3))
    assert [g["index"] for g in out[0]] == [planes.index(g.plane) for g in seen]
    for js, g in zip(out[0], seen, strict=True):
        assert_twins(js["poly"], g.poly, "visible polygon")
        assert_twins(js["depth"], g.depth, "depth")
        H = Kc @ np.column_stack([g.Rc[:, 0], g.Rc[:, 1], g.tc])
        assert_twins(js["Hplane"], H, "canvas_from_plane")
    for js, p in zip(out[1:], planes, strict=True):
        assert_twins(np.reshape(js, (-1, 2)), clip_to_near(p.extent, p.R, p.t), "clipped")
    cases = [(np.asarray(g["Hplane"]), np.asarray(g["poly"])) for g in out[0]]
    mpp = run_js([("metresPerCanvasPx", [H.tolist(), P.tolist()]) for H, P in cases], TEXTURED)
    assert_twins(mpp, [metres_per_canvas_px(H, P) for H, P in cases], "metres per canvas px")


# Measured over the cases below: mean |difference| 0.03-0.43 grey levels, at most 1.3 % of pixels
# more than 4 levels apart (along the box's outline), none more than 40 after a 1 px Gaussian.
MEAN_LEVELS, OFF_SHARE, BLURRED_LEVELS = 1.0, 0.03, 40


def test_the_image_rendered_in_the_browser_is_camlab_render_s(demo):
    rng = np.random.default_rng(6)
    settings = _settings(rng, 4)
    scene = _scene(demo)
    numbers = {k: v for k, v in scene.items() if k not in ("planes", "panels")}
    frames = run_js([("pinholeFrame", [numbers, v]) for v in settings], PINHOLE)
    images = run_js([("pinholeImage", [scene, fr]) for fr in frames], PINHOLE)
    for v, fr, js in zip(settings, frames, images, strict=True):
        ref = render.render(
            fixtures.box_before_wall(v["distance"]), np.asarray(fr["K"]), tuple(scene["size"])
        ).irradiance
        img = np.asarray(js, np.float32).reshape(ref.shape)
        d = np.abs(img - ref) * 255
        blurred = np.abs(gaussian_filter(img * 255.0, 1) - gaussian_filter(ref * 255.0, 1))
        assert d.mean() <= MEAN_LEVELS, f"{v}: mean difference {d.mean():.2f} levels"
        assert (d > 4).mean() <= OFF_SHARE, f"{v}: {(d > 4).mean():.1%} of pixels > 4 levels off"
        assert blurred.max() <= BLURRED_LEVELS, f"{v}: blurred difference {blurred.max():.1f}"
