"""Lesson 07's browser arithmetic (camlab/widgets/browser/homography.js) equals its numpy twins.

``transformation_hierarchy`` drawn in the browser: the group's matrix, the map drawn, the smallest
group, the mapped grid, diagonal and vanishing line and the tear, on random control values of every
group and at the settings the demo reaches at its edges (v = 0: an affine "projective" map; a tear);
and the picture warped pixel by pixel, compared with camlab.warp.warp_perspective's numpy path.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from test_browser_geometry_parity import CASES, NODE, assert_twins, run_js

from camlab import homography as hg
from camlab import scenes
from camlab.projective import map_polyline, splits_at_infinity
from camlab.warp import warp_perspective
from camlab.widgets.homographies.twins import hierarchy_fixed, hierarchy_view

HOMOGRAPHY = (
    Path(__file__).resolve().parent.parent / "camlab" / "widgets" / "browser" / "homography.js"
)

pytestmark = pytest.mark.skipif(
    NODE is None, reason="node is not installed: the JavaScript twins cannot be run"
)


def _fixed_by_hand() -> dict:
    return hierarchy_fixed((120, 160, 3), (360, 480))


def _settings(rng: np.random.Generator) -> list[dict]:
    """Control values on the sliders' steps, every group, and the edges the demo reaches."""
    out = []
    for k in range(CASES):
        out.append(
            dict(
                group=list(hg.HIERARCHY)[k % 4],
                theta=float(np.round(rng.uniform(-180, 180))),
                scale=float(np.round(rng.uniform(0.3, 2.5) * 20) / 20),
                phi=float(np.round(rng.uniform(-90, 90))),
                aspect=float(np.round(rng.uniform(0.4, 2.5) * 20) / 20),
                tx=float(np.round(rng.uniform(-100, 100))),
                ty=float(np.round(rng.uniform(-80, 80))),
                v1=float(np.round(rng.uniform(-15, 15) * 10) / 10),
                v2=float(np.round(rng.uniform(-15, 15) * 10) / 10),
            )
        )
    base = dict(theta=15.0, scale=1.2, phi=60.0, aspect=1.4, tx=0.0, ty=0.0, v1=1.5, v2=0.0)
    out += [dict(base, group="projective", v1=0.0), dict(base, group="affine", aspect=1.0)]
    out += [dict(base, group="projective", v1=14.0), dict(base, group="similarity", scale=1.0)]
    return out


def _jsonable(fixed: dict) -> dict:
    return {
        k: (
            [np.asarray(x).tolist() for x in v]
            if k == "grid_lines"
            else np.asarray(v, dtype=float).tolist()
        )
        for k, v in fixed.items()
    }


def test_the_hierarchy_view_equals_the_demo():
    rng = np.random.default_rng(71)
    fixed = _fixed_by_hand()
    settings = _settings(rng)
    views = [hierarchy_view(v, fixed) for v in settings]
    out = run_js([("hierarchyView", [v, _jsonable(fixed)]) for v in settings], HOMOGRAPHY)
    worst, kinds, torn = 0.0, set(), 0
    for js, py in zip(out, views, strict=True):
        for key in ("Hg", "H", "grid", "diagonal", "vanishing"):
            worst = max(worst, assert_twins(js[key], getattr(py, key), f"hierarchyView {key}"))
        assert js["kind"] == py.kind, f"classify: JS {js['kind']}, numpy {py.kind}"
        assert js["torn"] == py.torn, "splitsAtInfinity disagrees"
        kinds.add(py.kind)
        torn += py.torn
    assert kinds == set(hg.HIERARCHY), f"not every group was classified: {kinds}"
    assert 0 < torn < len(settings), "no torn picture (or only torn ones) was tried"
    print(f"transformation_hierarchy: worst relative error {worst:.2e}")


def test_classify_map_polyline_and_the_tear_equal_camlab():
    rng = np.random.default_rng(72)
    Hs = [
        np.eye(3) + rng.normal(scale=0.3, size=(3, 3)) * [[1, 1, 50], [1, 1, 50], [2e-2, 2e-2, 0]]
        for _ in range(CASES)
    ]
    Hs += [
        hg.similarity_homography(2.0, 0.3, 5, 1),
        hg.euclidean_homography(0.7, 3, 4),
        np.diag([1.0, -1.0, 1.0]),
    ]
    polyline = np.column_stack([np.linspace(-50, 250, 97), np.linspace(30, -40, 97)])
    square = np.array([[0.0, 0.0], [159.0, 0.0], [159.0, 119.0], [0.0, 119.0]])
    calls = [("classifyHomography", [H.tolist()]) for H in Hs]
    calls += [("mapPolyline", [H.tolist(), polyline.tolist()]) for H in Hs]
    calls += [("splitsAtInfinity", [H.tolist(), square.tolist()]) for H in Hs]
    out = run_js(calls, HOMOGRAPHY)
    n = len(Hs)
    assert out[:n] == [hg.classify(H) for H in Hs]
    worst = max(
        assert_twins(js, map_polyline(H, polyline), "mapPolyline")
        for js, H in zip(out[n : 2 * n], Hs, strict=True)
    )
    assert out[2 * n :] == [splits_at_infinity(H, square) for H in Hs]
    breaks = sum(int(np.isnan(map_polyline(H, polyline)).any()) for H in Hs)
    assert breaks >= 10, f"only {breaks} polylines passed through infinity"
    print(f"mapPolyline: worst relative error {worst:.2e}")


def _image_arg(img: np.ndarray) -> dict:
    h, w = img.shape[:2]
    return dict(
        data=img.reshape(-1).tolist(),
        width=w,
        height=h,
        channels=1 if img.ndim == 2 else img.shape[2],
    )


def _random_maps(rng, tilt: float) -> list:
    """12 random projective maps of a 40 x 30 picture about its centre onto a 70 x 50 canvas's centre."""
    return [
        hg.compose(
            [[1, 0, 35], [0, 1, 25], [0, 0, 1]],
            hg.hierarchy_matrix(
                "projective",
                theta=rng.uniform(-3, 3),
                scale=rng.uniform(0.5, 2.5),
                shear=rng.uniform(-1.5, 1.5),
                aspect=rng.uniform(0.5, 2),
                v=rng.uniform(-tilt, tilt, 2),
            ),
            [[1, 0, -19.5], [0, 1, -14.5], [0, 0, 1]],
        )
        for _ in range(12)
    ]


@pytest.mark.parametrize("mirror", [False, True])
@pytest.mark.parametrize("interpolation", ["bilinear", "nearest"])
def test_the_warp_equals_warp_perspectives_numpy_path(interpolation, mirror):
    """Pixel for pixel: the JavaScript repeats numpy's float32 steps, so the bytes agree exactly."""
    rng = np.random.default_rng(73)
    pic = scenes.house_picture((40, 30))
    shape = (50, 70)
    Hs = _random_maps(rng, tilt=0.12)
    Hs.append(-Hs[0])  # the free sign: the same picture
    torn = sum(splits_at_infinity(H, [[0, 0], [39, 0], [39, 29], [0, 29]]) for H in Hs)
    assert torn >= 3, f"only {torn} of the maps tear the picture (mirror draws their far halves)"
    grey = pic[..., 1]
    calls = [
        (
            "warpPerspective",
            [_image_arg(img), H.tolist(), list(shape), interpolation, fill, None, mirror],
        )
        for H in Hs
        for img, fill in ((pic, 255), (grey, 0))
    ]
    out = iter(run_js(calls, HOMOGRAPHY))
    differing = 0
    for H in Hs:
        for img, fill in ((pic, 255), (grey, 0)):
            js = np.asarray(next(out), dtype=np.uint8).reshape(*shape, 4)
            py = warp_perspective(
                img, H, shape, interpolation=interpolation, fill=fill, mirror=mirror
            )
            py = np.repeat(py[..., None], 3, axis=-1) if py.ndim == 2 else py
            assert (js[..., 3] == 255).all()
            differing += int(np.count_nonzero(js[..., :3] != py))
            assert np.array_equal(js[..., :3], py), (
                f"warpPerspective ({interpolation}): {np.count_nonzero(js[..., :3] != py)} bytes differ, "
                f"at most by {np.abs(js[..., :3].astype(int) - py).max()}"
            )
    print(f"warpPerspective ({interpolation}, mirror={mirror}): {differing} bytes differ")


def test_the_shrink_to_the_shown_size_equals_opencvs_nearest_resize():
    """nearestResize: the live canvas keeps an animated image at its shown size with cv2's INTER_NEAREST."""
    import cv2

    rng = np.random.default_rng(74)
    sizes = [(480, 360, 409, 307), (300, 260, 257, 223), (70, 50, 69, 31), (240, 180, 97, 73)]
    sizes += [
        tuple(int(c) for c in (w, h, rng.integers(2, w), rng.integers(2, h)))
        for w, h in rng.integers(20, 200, (8, 2))
    ]
    images = [rng.integers(0, 256, (sh, sw, 4), dtype=np.uint8) for sw, sh, _, _ in sizes]
    calls = [
        ("nearestResize", [img.reshape(-1).tolist(), sw, sh, dw, dh])
        for img, (sw, sh, dw, dh) in zip(images, sizes, strict=True)
    ]
    for js, img, (_sw, _sh, dw, dh) in zip(run_js(calls, HOMOGRAPHY), images, sizes, strict=True):
        py = cv2.resize(img, (dw, dh), interpolation=cv2.INTER_NEAREST)
        assert np.array_equal(np.asarray(js, dtype=np.uint8).reshape(dh, dw, 4), py), (dw, dh)


# ----------------------------------------------------------------------------- forward vs inverse


def _forward_settings(rng: np.random.Generator) -> list[dict]:
    """The sliders' values on their steps (scale 0.4-3 by 0.05, angle -45-45 by 1), and the sweep's."""
    out = [
        dict(
            scale=float(np.round(rng.uniform(0.4, 3.0) * 20) / 20),
            angle=float(np.round(rng.uniform(-45, 45))),
        )
        for _ in range(40)
    ]
    return out + [
        dict(scale=s, angle=a) for s in (0.6, 1.0, 1.5, 2.0, 2.8, 3.0) for a in (0.0, 15.0)
    ]


def _fixed_json(fixed: dict) -> dict:
    return {k: np.asarray(v).tolist() for k, v in fixed.items()}


def test_the_forward_and_inverse_warps_equal_the_demos_byte_for_byte():
    """forwardInverseView: H and the outline at 1e-9, both warps as shown and the masks exactly."""
    from camlab.widgets.homographies.twins import forward_inverse_fixed, forward_inverse_view

    pic = scenes.house_picture((80, 60))
    fixed = forward_inverse_fixed(pic.shape, (180, 240))
    settings = _forward_settings(np.random.default_rng(75))
    calls = [("forwardInverseView", [v, _image_arg(pic), _fixed_json(fixed)]) for v in settings]
    worst, holes = 0.0, []
    for js, v in zip(run_js(calls, HOMOGRAPHY), settings, strict=True):
        py = forward_inverse_view(v, pic, fixed)
        worst = max(
            worst,
            assert_twins(js["H"], py.H, "H"),
            assert_twins(js["outline"], py.outline, "outline"),
        )
        for key in ("shown", "inverse"):
            img = np.asarray(js[key], dtype=np.uint8).reshape(180, 240, 4)
            assert (img[..., 3] == 255).all()
            differ = np.count_nonzero(img[..., :3] != getattr(py, key))
            assert differ == 0, f"{key} at {v}: {differ} bytes differ"
        for key in ("covered", "reached", "pulled"):
            mask = np.asarray(js[key], dtype=bool).reshape(180, 240)
            assert np.array_equal(mask, getattr(py, key)), f"{key} at {v}"
        holes.append(float(np.mean(py.covered & ~py.reached)))
    assert min(holes) == 0 and max(holes) > 0.5, "no setting without holes, or none with many"
    print(f"forward_vs_inverse: worst relative error {worst:.2e}; images and masks equal")


def test_the_forward_warp_and_the_covered_area_equal_camlab_on_random_maps():
    """forwardWarp against camlab.warp.forward_warp (a one-channel picture too); coveredArea on random quadrilaterals."""
    from camlab.warp import forward_warp
    from camlab.widgets.homographies.twins import covered_area

    rng = np.random.default_rng(76)
    pic = scenes.house_picture((40, 30))
    Hs = _random_maps(rng, tilt=0.05)
    quads = [np.sort(rng.uniform(0, 2 * np.pi, 4)) for _ in range(30)]
    quads = [
        np.column_stack([35 + r * np.cos(t), 25 + r * np.sin(t)])
        for t, r in zip(quads, rng.uniform(5, 40, 30), strict=True)
    ]
    quads.append(
        np.array([[2.0, 3.0], [20.0, 3.0], [20.0, 9.0], [2.0, 9.0]])
    )  # centres on its edges
    calls = [
        ("forwardWarp", [_image_arg(img), H.tolist(), [50, 70], fill])
        for H in Hs
        for img, fill in ((pic, 0), (pic[..., 0], 7))
    ]
    calls += [("coveredArea", [q.tolist(), [50, 70]]) for q in quads]
    out = run_js(calls, HOMOGRAPHY)
    for js, (H, (img, fill)) in zip(
        out, [(H, c) for H in Hs for c in ((pic, 0), (pic[..., 0], 7))], strict=False
    ):
        py = forward_warp(img, H, (50, 70), fill=fill)
        py = np.repeat(py[..., None], 3, axis=-1) if py.ndim == 2 else py
        assert np.array_equal(np.asarray(js, dtype=np.uint8).reshape(50, 70, 4)[..., :3], py)
    areas = out[2 * len(Hs) :]
    for js, q in zip(areas, quads, strict=True):
        assert np.array_equal(np.asarray(js, dtype=bool).reshape(50, 70), covered_area(q, (50, 70)))
    assert covered_area(quads[-1], (50, 70)).sum() == 19 * 7, (
        "the edges' pixel centres count as covered"
    )


def test_the_live_canvas_images_equal_what_the_kernel_blits():
    """liveImage, per panel of the built demo: byte for byte the kernel's live image (``make_image``),
    the forward warp shrunk to its box (cv2's nearest) and the zoomed windows enlarged (nearest at centres)."""
    from camlab.widgets import all_demos
    from camlab.widgets.browser.homography_scenes import forward_inverse_scene
    from camlab.widgets.homographies.twins import forward_inverse_fixed, forward_inverse_view

    setting = dict(scale=1.35, angle=-7.0)
    demo = all_demos()["forward_vs_inverse"].builder()
    demo.set(**setting)
    demo.view.pixels()
    fig = demo.figure
    names = ("forward", "forward_zoom", "inverse_zoom", "inverse")
    images = dict(zip(names, (ax.images[0] for ax in fig.axes), strict=True))
    pic = scenes.house_picture((80, 60))
    fixed = forward_inverse_fixed(pic.shape, (180, 240))
    scene = forward_inverse_scene(images, [], pic, fixed)
    g = forward_inverse_view(setting, pic, fixed)
    top, left, h, w = scene["zoom"]
    data = dict(
        forward=g.shown,
        inverse=g.inverse,
        forward_zoom=g.shown[top : top + h, left : left + w],
        inverse_zoom=g.inverse[top : top + h, left : left + w],
    )
    calls = []
    for panel in scene["panels"]:
        a = data[panel["image"]]
        rgba = np.dstack([a, np.full(a.shape[:2], 255, np.uint8)])
        calls.append(
            ("liveImage", [rgba.reshape(-1).tolist(), a.shape[1], a.shape[0], panel["place"]])
        )
    renderer = fig.canvas.get_renderer()
    for js, panel in zip(run_js(calls, HOMOGRAPHY), scene["panels"], strict=True):
        kernel = images[panel["image"]].make_image(renderer)[0][::-1]  # Agg's rows from the bottom
        shown = np.asarray(js["data"], dtype=np.uint8).reshape(js["height"], js["width"], 4)
        assert shown.shape == kernel.shape, (panel["image"], shown.shape, kernel.shape)
        assert np.array_equal(shown, kernel), (
            f"{panel['image']}: {np.count_nonzero(shown != kernel)} bytes differ"
        )


def test_nearest_at_centres_equals_the_live_canvas():
    """nearestAtCentres against camlab.widgets._transport's, on random boxes and unrounded edges."""
    from camlab.widgets._transport import _nearest_at_centres

    rng = np.random.default_rng(77)
    cases = []
    for _ in range(12):
        sw, sh = (int(c) for c in rng.integers(3, 40, 2))
        left, bottom = (int(c) for c in rng.integers(0, 300, 2))
        dw, dh = int(rng.integers(sw, 5 * sw + 2)), int(rng.integers(sh, 5 * sh + 2))
        us = [left + rng.uniform(-0.5, 0.5), left + dw + rng.uniform(-0.5, 0.5)]
        vs = [bottom + rng.uniform(-0.5, 0.5), bottom + dh + rng.uniform(-0.5, 0.5)]
        cases.append(
            (
                rng.integers(0, 256, (sh, sw, 4), dtype=np.uint8),
                us,
                vs,
                (left, left + dw, bottom, bottom + dh),
            )
        )
    calls = [
        ("nearestAtCentres", [a.reshape(-1).tolist(), a.shape[1], a.shape[0], us, vs, list(box)])
        for a, us, vs, box in cases
    ]
    for js, (a, us, vs, box) in zip(run_js(calls, HOMOGRAPHY), cases, strict=True):
        py = _nearest_at_centres(a, us, vs, box)
        assert np.array_equal(np.asarray(js, dtype=np.uint8).reshape(py.shape), py)
