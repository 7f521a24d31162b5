"""camlab.scenes, the one home of synthetic scenes and textures, and the lessons' scenes built from
them (camlab.fixtures)."""

import subprocess
import sys

import numpy as np
import pytest

from camlab import camera, fixtures, perspective, render, scenes
from camlab.data import panorama


def test_scene_builders_have_one_home():
    """Scene builders are camlab.scenes.* only: render, perspective and the data loaders do not
    re-export them (tests/test_architecture.py checks every name)."""
    for module, names in [
        (render, ["Plane", "box", "checkerboard", "photo_plane", "text_page", "textured_plane"]),
        (
            perspective,
            [
                "PlanePhoto",
                "desk_background",
                "facade_texture",
                "page_texture",
                "painting_texture",
                "photograph_plane",
                "sample_photo",
                "look_at_plane",
            ],
        ),
        (panorama, ["wall_texture"]),
    ]:
        for name in names:
            assert name in scenes.__all__ and name not in module.__all__, (module.__name__, name)
    assert not hasattr(render, "box") and not hasattr(perspective, "sample_photo")
    assert not hasattr(camera, "box_wireframe")  # scenes builds on camera, not the other way round


def test_the_camera_model_does_not_import_the_scenes():
    code = "import sys, camlab.camera; print('camlab.scenes' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_scenes_do_not_depend_on_the_data_sets():
    code = "import sys, camlab.scenes; print(any(m.startswith('camlab.data') for m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


@pytest.mark.parametrize(
    "make",
    [
        lambda: scenes.wall_texture((300, 120), 1),
        scenes.portrait,
        scenes.page_texture,
        scenes.facade_texture,
        scenes.painting_texture,
        scenes.desk_background,
        lambda: scenes.checkerboard((3, 2)).texture,
    ],
)
def test_cached_textures_are_read_only(make):
    tex = make()
    with pytest.raises(ValueError, match="read-only"):
        tex[0, 0] = 0


def test_wall_texture_cannot_be_corrupted_by_a_caller():
    """It is cached: before, an edit by one caller changed every later render of the room."""
    a = scenes.wall_texture((300, 120), 1)
    before = a.copy()
    with pytest.raises(ValueError):
        a[:10] = 0.0
    np.testing.assert_array_equal(scenes.wall_texture((300, 120), 1), before)
    assert a.dtype == np.float32 and a.min() >= 0 and a.max() <= 1


def test_portrait_is_the_bundled_photo_and_painting_uses_its_pixels():
    p = scenes.portrait()
    assert p.shape[2] == 3 and p.dtype == np.float32
    art = np.round(p * 255).astype(np.uint8)
    assert np.array_equal(
        art.astype(np.float32) / 255, p
    )  # the uint8 JPEG values survive the round trip


def test_noise_texture_is_deterministic_and_in_range():
    a, b = scenes.noise_texture((64, 96), 3), scenes.noise_texture((64, 96), 3)
    assert a.shape == (64, 96) and np.array_equal(a, b)
    assert 0 <= a.min() and a.max() <= 1 and a.std() > 0.05
    assert not np.array_equal(a, scenes.noise_texture((64, 96), 4))


def test_plane_outlines_of_a_box_are_its_twelve_edges_each_shared_by_two_faces():
    size = np.array([0.2, 0.3, 0.4])
    faces = scenes.box((1.0, 2.0, 3.0), size)
    segs = scenes.plane_outlines([faces])  # nested like a render scene
    assert segs.shape == (24, 2, 3)
    assert np.allclose(np.abs(segs - [1.0, 2.0, 3.0]), size / 2)  # every end point is a box corner
    lengths = np.sort(np.linalg.norm(segs[:, 1] - segs[:, 0], axis=1))
    assert np.allclose(lengths, np.repeat(size, 8))  # 4 edges per axis, each seen by 2 faces
    board = scenes.checkerboard((3, 2), 0.1)
    np.testing.assert_allclose(scenes.plane_outlines([board])[:, 0], board.corners_world)


def test_the_lessons_scenes_have_the_documented_geometry():
    faces, wall = fixtures.box_before_wall(2.0)
    corners = scenes.plane_outlines(faces).reshape(-1, 3)
    assert (
        np.allclose(corners.mean(axis=0), [0, 0, 2.0]) and corners[:, 2].min() > 1.6
    )  # a 0.3 m box at 2 m
    assert wall.name == "wall" and np.allclose(wall.t, [0, 0, 6.0])
    with pytest.raises(ValueError, match="distance"):
        fixtures.box_before_wall(-1.0)
    depths = [np.mean(p.corners_world[:, 2]) for p in fixtures.depth_of_field_scene()]
    np.testing.assert_allclose(depths, [0.6, 1.2, 2.4, 4.0], atol=0.05)
    assert [p.name for p in fixtures.photo_and_page()] == ["photo", "page"]
    house = fixtures.house_scene()
    assert (
        house.shape[1:] == (2, 3)
        and house[..., 2].min() == 0.0
        and np.isclose(house[..., 2].max(), 1.55)
    )
    cube_rails = fixtures.box_and_rails()
    assert cube_rails.shape == (16, 2, 3)
    rails = fixtures.rail_track(0.0, 10.0)
    assert rails.shape == (4 + 10, 2, 3)
    np.testing.assert_array_equal(
        rails[:4, 1] - rails[:4, 0], [[0, 10, 0]] * 4
    )  # the rails run along +y


@pytest.mark.parametrize(
    "make, size",
    [
        (scenes.page_texture, (210, 297)),
        (scenes.facade_texture, (240, 180)),
        (scenes.wall_texture, (300, 120)),
        (scenes.house_picture, (80, 60)),
    ],
)
def test_textures_take_one_size_width_then_height(make, size):
    """docs/conventions.md: a size is (width, height) and no function takes them as two arguments."""
    assert make(size).shape[:2] == size[::-1]
    with pytest.raises(
        ValueError, match=r"size: expected \(width, height\) as whole numbers of pixels"
    ):
        make((size[0] + 0.7, size[1]))
    assert scenes.desk_background((60, 80)).shape == (60, 80, 3)  # a shape is (height, width)


def test_resection_set_is_noisy_projections_of_non_coplanar_points():
    exact = fixtures.resection_set(20, 0.0, seed=3)
    np.testing.assert_allclose(exact.points_image, exact.camera.project(exact.points_world))
    assert (
        np.linalg.matrix_rank(exact.points_world - exact.points_world.mean(axis=0)) == 3
    )  # two cube faces
    noisy = fixtures.resection_set(20, 2.0, seed=3)
    assert 1.0 < np.std(noisy.points_image - exact.points_image) < 3.0
    with pytest.raises(ValueError, match="noise_px"):
        fixtures.resection_set(10, -1.0)


def test_camera_pairs_for_lesson_11():
    from camlab import epipolar as ep

    pair = fixtures.stereo_pair(0.2, 0.0)
    assert isinstance(pair, camera.CameraPair) and np.isclose(
        np.linalg.norm(pair.camera2.centre - pair.camera1.centre), 0.2
    )
    assert (
        abs(ep.epipoles(ep.fundamental_from_cameras(*pair)).e2[2]) < 1e-12
    )  # parallel: epipole at infinity
    e2 = ep.epipoles(ep.fundamental_from_cameras(*fixtures.forward_pair(0.5, 0.0))).e2
    np.testing.assert_allclose(
        e2[:2] / e2[2], [319.5, 239.5], atol=1e-6
    )  # straight ahead: the image centre


def test_outlier_matches_hold_the_stated_fraction_of_wrong_pairs():
    from camlab.projective import map_points

    m = fixtures.outlier_matches(0.3, seed=2)
    assert m.is_outlier.sum() == 60 and m.src.shape == m.dst.shape == (200, 2)
    err = np.linalg.norm(map_points(m.H, m.src) - m.dst, axis=1)
    assert err[~m.is_outlier].max() < 6 and np.median(err[m.is_outlier]) > 30
    with pytest.raises(ValueError, match="outlier_fraction"):
        fixtures.outlier_matches(1.5)
    near = fixtures.outlier_matches(0.3, seed=2, near_share=0.5)
    assert np.array_equal(near.src, m.src) and np.array_equal(near.is_outlier, m.is_outlier)
    err_near = np.linalg.norm(map_points(m.H, near.src) - near.dst, axis=1)[m.is_outlier]
    assert (
        np.sum((err_near >= 4) & (err_near <= 15)) >= 30
    )  # 30 of the 60 placed near, a few random ones too
    with pytest.raises(ValueError, match="near_share"):
        fixtures.outlier_matches(0.3, near_share=2)


def test_sleeper_gaps_shrink_with_distance_only_in_perspective():
    from camlab import affine, camera

    eye = np.array([0.0, -4.0, 2.0])
    cam = camera.Camera.look_at(
        eye, eye + [0.0, np.cos(0.26), -np.sin(0.26)], K=camera.intrinsic_matrix(500, 500, 320, 240)
    )
    near, far = fixtures.sleeper_gaps(cam.P)
    assert near > 20 * far  # 1 m of track 2 m away against 24 m away
    assert np.isclose(*fixtures.sleeper_gaps(affine.affine_approximation(cam, [0.0, 6.0, 0.0])))
    assert fixtures.sleeper_gaps(cam.P, at=[0.0, 5.0, 10.0]).shape == (3,)
