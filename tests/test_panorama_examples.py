"""camlab.fixtures.panorama_examples: lesson 09's data, computed once, cached and read-only.

Each result is checked against the ground truth of the rendered sets and against the
public stages it is made of (recomputed live), and every cached array must refuse edits.
"""

import dataclasses
from itertools import pairwise

import numpy as np
import pytest

from camlab import stitching as st
from camlab._validate import CamlabInputError
from camlab.fixtures import panorama_examples as pe
from camlab.projective import map_points
from camlab.warp import canvas_bounds

CACHED = [
    pe.panorama_example,
    pe.panorama_graph,
    pe.reference_canvases,
    pe.exposure_pair,
    pe.pair_blends,
    pe.stitched_panoramas,
    pe.wide_sweep,
    pe.canvas_previews,
    pe.parallax_pairs,
]


def arrays(obj) -> list:
    """Every ndarray inside obj (NamedTuples, lists, tuples, dicts, WarpedImages with their canvases)."""
    if isinstance(obj, np.ndarray):
        return [obj]
    if isinstance(obj, dict):
        return [a for v in obj.values() for a in arrays(v)]
    if isinstance(obj, (list, tuple)):
        return [a for v in obj for a in arrays(v)]
    if isinstance(obj, st.WarpedImages):
        parts = [getattr(obj, f.name) for f in dataclasses.fields(obj)] + [
            obj.images,
            obj.masks,
            obj.weights,
        ]
        return arrays(parts)
    return []


@pytest.mark.parametrize("make", CACHED, ids=lambda f: f.__name__)
def test_cached_results_are_read_only(make):
    result = make()
    assert make() is result  # cached: computed once
    found = arrays(result)
    assert len(found) >= 3
    writable = [a.shape for a in found if a.flags.writeable]
    assert not writable, f"{len(writable)} of {len(found)} arrays are writable: {writable[:5]}"
    biggest = max(found, key=lambda a: a.size)
    with pytest.raises(ValueError, match="read-only"):
        biggest.flat[0] = 0
    with pytest.raises(ValueError, match="read-only"):
        np.add(biggest, 1, out=biggest, casting="unsafe")


def test_an_edit_cannot_reach_the_next_caller():
    img = pe.panorama_example().images[0]
    before = img.copy()
    with pytest.raises(ValueError):
        img[:10] = 0
    np.testing.assert_array_equal(pe.panorama_example().images[0], before)


def test_panorama_example_shapes():
    ex = pe.panorama_example()
    assert len(ex.data.images) == len(ex.images) == len(ex.features) == 4
    assert ex.data.images[0].shape == (240, 320, 3) and ex.data.images[0].dtype == np.uint8
    assert float(ex.data.K[0, 0]) == 400.0
    assert all(im.shape == (240, 320, 3) and im.dtype == np.float32 for im in ex.images)
    assert all(500 < len(f.points) <= 1500 for f in ex.features)
    assert sorted(ex.knn) == [(0, 1), (1, 2), (2, 3)]


def test_graph_reference_and_relative_homographies_agree_with_the_truth():
    ex, graph = pe.panorama_example(), pe.panorama_graph()
    assert (
        graph.reference in (1, 2) and graph.unconnected == []
    )  # a middle view: it overlaps two others
    np.testing.assert_allclose(graph.homographies[graph.reference], np.eye(3), atol=1e-9)
    h, w = ex.images[0].shape[:2]
    corners = np.array([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]], float)
    for ref in range(4):
        Hs = pe.homographies_relative_to(graph, ref)
        np.testing.assert_allclose(Hs[ref], np.eye(3), atol=1e-9)
        for k in range(
            max(0, ref - 1), min(4, ref + 2)
        ):  # the neighbours: corners within 1.5 px of the truth
            err = np.abs(
                map_points(Hs[k], corners) - map_points(ex.data.true_homography(k, ref), corners)
            ).max()
            assert err < 1.5, (ref, k, err)


def test_correct_matches_uses_the_true_homography():
    ex = pe.panorama_example()
    src = np.array([[50.0, 60.0], [200.0, 120.0], [300.0, 30.0]])
    dst = map_points(ex.data.true_homography(0, 1), src)
    assert pe.correct_matches(ex.data, 0, 1, src, dst).all()
    assert not pe.correct_matches(ex.data, 0, 1, src, dst + [3.0, 0.0]).any()
    assert pe.correct_matches(ex.data, 0, 1, src, dst + [1.0, 1.0], tol=2.0).all()  # 1.41 px < 2 px
    empty = pe.correct_matches(ex.data, 0, 1, np.zeros((0, 2)), np.zeros((0, 2)))
    assert empty.shape == (0,) and empty.dtype == bool


def test_reference_canvases_are_the_warps_of_the_relative_homographies():
    small, canvases = pe.reference_canvases()
    assert sorted(canvases) == [0, 1, 2, 3] and all(im.shape == (120, 160, 3) for im in small)
    graph = pe.panorama_graph()
    S = np.diag([0.5, 0.5, 1.0])
    S[:2, 2] = -0.25  # half-size pixel centres -> quarter-size pixel centres
    for ref, c in canvases.items():
        chain = [S @ H @ np.linalg.inv(S) for H in pe.homographies_relative_to(graph, ref)]
        T, shape = canvas_bounds(chain, [im.shape for im in small], max_pixels=3_000_000)
        assert c.shape == tuple(shape) and c.panorama.shape == (*shape, 3)
        np.testing.assert_allclose(c.T, T)
        np.testing.assert_allclose(
            c.homographies[ref], T, atol=1e-9
        )  # the reference is only translated
    wi = st.warp_images(
        small,
        [np.linalg.inv(canvases[1].T) @ H for H in canvases[1].homographies],
        max_pixels=3_000_000,
    )
    np.testing.assert_array_equal(st.blend(wi, "overwrite"), canvases[1].panorama)
    middle, end = canvases[1].shape, canvases[3].shape
    assert (
        end[0] * end[1] > 1.3 * middle[0] * middle[1]
    )  # an end reference stretches the far images


def test_pair_blends_cover_every_setting_and_gains_hide_the_seam():
    wi, gains, seam = pe.exposure_pair()
    assert seam.dtype == bool and seam.shape == wi.shape and not (seam & ~wi.masks[0]).any()
    assert gains.shape == (2,) and gains[0] == 1.0 and abs(gains[1] - 1) > 0.1  # exposures differ
    blends = pe.pair_blends()
    assert sorted(blends) == sorted(
        [(m, g, 0) for m in ("overwrite", "feather") for g in (False, True)]
        + [("multiband", g, lv) for g in (False, True) for lv in range(1, 7)]
    )
    over = blends[("overwrite", False, 0)].seam_step
    assert over > 15 / 255
    assert blends[("overwrite", True, 0)].seam_step < over / 4
    assert blends[("multiband", True, 5)].seam_step < over / 4
    b = blends[("multiband", True, 3)]
    again = st.blend(wi, "multiband", gains=gains, levels=3)
    np.testing.assert_array_equal(b.image, again)
    assert b.seam_step == st.seam_step(again, seam, wi.masks[0] & wi.masks[1])


def test_misregistered_pair_moves_view_2_only():
    aligned, moved = pe.exposure_pair().warped, pe.misregistered_pair(4)
    assert pe.misregistered_pair(0) is aligned
    np.testing.assert_array_equal(moved.masks[0], aligned.masks[0])
    np.testing.assert_array_equal(moved.masks[1], aligned.masks[1])  # the footprint stays
    np.testing.assert_array_equal(moved.images[0], aligned.images[0])
    assert not np.array_equal(moved.images[1], aligned.images[1])
    with pytest.raises(CamlabInputError, match="offset: expected one of"):
        pe.misregistered_pair(3)


def test_parallax_grows_with_the_baseline():
    pairs = pe.parallax_pairs()
    assert tuple(pairs) == pe.BASELINES
    mis = [p.misalignment for p in pairs.values()]
    assert mis[0] < 4 / 255 and all(
        a < b for a, b in pairwise(mis)
    )  # only noise when the camera turns
    for p in pairs.values():
        assert p.registration.accepted and sorted(p.blends) == ["feather", "multiband"]
        assert p.misalignment == st.overlap_difference(p.warped)
        assert all(e.dtype == bool and e.shape == p.warped.shape and e.any() for e in p.edges)
        for e, again in zip(p.edges, pe.edge_masks(p.warped), strict=True):
            np.testing.assert_array_equal(e, again)


def test_canvas_previews_the_plane_cannot_hold_a_wide_turn():
    previews = pe.canvas_previews()
    assert sorted(previews) == sorted(
        (n, p) for n in range(2, 7) for p in ("planar", "cylindrical", "spherical")
    )
    for (n, proj), p in previews.items():
        assert p.fov_deg == pytest.approx(40 * (n - 1) + np.degrees(2 * np.arctan(0.9)))
        if proj == "planar" and n >= 4:  # beyond 180 degrees
            assert p.image is None and p.shape is None and "90 degrees" in p.reason
            continue
        assert p.reason == "" and p.image.dtype == np.uint8 and p.image.max() > 50
        h, w = p.image.shape[:2]
        assert h <= 220 and w <= 560  # within the box
        # the plane fits on its own; the widest cylinder (six views) sets the curved scale
        if proj == "planar" or (n, proj) == (6, "cylindrical"):
            assert h >= 216 or w >= 556  # touching one side, to the canvas's whole-pixel rounding
        assert abs(w / h - p.shape[1] / p.shape[0]) < 0.02 * w / h  # the canvas' aspect ratio kept
    for n in range(2, 7):  # the cylinder and the sphere at one scale: the same px per canvas px
        cyl, sph = previews[(n, "cylindrical")], previews[(n, "spherical")]
        assert cyl.image.shape[0] / cyl.shape[0] == pytest.approx(
            sph.image.shape[0] / sph.shape[0], rel=0.02
        )
        assert cyl.image.shape[0] > 1.1 * sph.image.shape[0]  # so the cylinder shows taller
    widths = [previews[(n, "cylindrical")].shape[1] for n in range(2, 7)]
    assert all(a < b for a, b in pairwise(widths))  # every view adds width
    assert (
        previews[(3, "planar")].shape[1] > 4 * previews[(3, "cylindrical")].shape[1]
    )  # the plane stretches


@pytest.mark.parametrize("box", [(220, 560), (300, 780)])  # reduced from 3/4 f; rendered larger
def test_canvas_previews_draw_the_curved_canvases_at_one_scale_for_every_view_count(box):
    """The views slider changes the turn, not the magnification: the same cylinder, equally high."""
    previews = pe.canvas_previews(box)
    curved = [previews[(n, p)] for n in range(2, 7) for p in ("cylindrical", "spherical")]
    assert len({p.scale for p in curved}) == 1  # one scale ...
    k = curved[0].scale
    cylinders = [previews[(n, "cylindrical")] for n in range(2, 7)]
    assert {c.shape[0] for c in cylinders} == {215}  # ... for one 215 px high cylinder
    assert len({c.image.shape[0] for c in cylinders}) == 1  # drawn equally high at every view count
    assert abs(cylinders[0].image.shape[0] - k * 215) <= 3
    # the widest (six views) fits the box: that sets the scale, and no fewer views are drawn larger
    assert box[1] - 4 <= cylinders[-1].image.shape[1] <= box[1]
    assert [c.image.shape[1] for c in cylinders] == sorted(c.image.shape[1] for c in cylinders)


def test_canvas_previews_other_sizes_and_bad_sizes():
    small = pe.canvas_previews((50, 100))
    assert small[(2, "spherical")].shape == pe.canvas_previews()[(2, "spherical")].shape
    assert max(small[(2, "spherical")].image.shape[:2]) <= 100
    with pytest.raises(CamlabInputError, match="max_shape"):
        pe.canvas_previews((0, 100))


def test_stitched_panoramas():
    pans = pe.stitched_panoramas()
    assert sorted(pans) == ["cylindrical", "planar", "spherical"]
    assert pans["cylindrical"].panorama.shape[1] < pans["planar"].panorama.shape[1]
    assert all(r.unconnected == [] and r.panorama.shape[2] == 3 for r in pans.values())
