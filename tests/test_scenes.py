"""camlab.scenes: the one home of synthetic scenes and textures."""
import subprocess
import sys

import numpy as np
import pytest

from camlab import camera, perspective, render, scenes
from camlab.data import panorama


def test_scene_builders_have_one_definition_re_exported_for_the_lessons():
    for module, names in [(render, ["Plane", "box", "checkerboard", "photo_plane", "text_page", "textured_plane"]),
                          (perspective, ["PlanePhoto", "desk_background", "facade_texture", "page_texture",
                                         "painting_texture", "photograph_plane", "sample_photo", "look_at_plane"]),
                          (camera, ["box_wireframe", "ground_grid", "house_wireframe"]),
                          (panorama, ["wall_texture"])]:
        for name in names:
            assert getattr(module, name) is getattr(scenes, name), (module.__name__, name)
    assert not hasattr(render, "sample_photo")  # one sample photo: scenes.sample_photo (plus scenes.portrait)


def test_scenes_do_not_depend_on_the_data_sets():
    code = "import sys, camlab.scenes; print(any(m.startswith('camlab.data') for m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


@pytest.mark.parametrize("make", [
    lambda: scenes.wall_texture(300, 120, 1),
    scenes.portrait,
    scenes.page_texture,
    scenes.facade_texture,
    scenes.painting_texture,
    scenes.desk_background,
    lambda: scenes.checkerboard((3, 2)).texture,
])
def test_cached_textures_are_read_only(make):
    tex = make()
    with pytest.raises(ValueError, match="read-only"):
        tex[0, 0] = 0


def test_wall_texture_cannot_be_corrupted_by_a_caller():
    """It is cached: before, an edit by one caller changed every later render of the room."""
    a = scenes.wall_texture(300, 120, 1)
    before = a.copy()
    with pytest.raises(ValueError):
        a[:10] = 0.0
    np.testing.assert_array_equal(scenes.wall_texture(300, 120, 1), before)
    assert a.dtype == np.float32 and a.min() >= 0 and a.max() <= 1


def test_portrait_is_the_bundled_photo_and_painting_uses_its_pixels():
    p = scenes.portrait()
    assert p.shape[2] == 3 and p.dtype == np.float32
    art = np.round(p * 255).astype(np.uint8)
    assert np.array_equal(art.astype(np.float32) / 255, p)  # the uint8 JPEG values survive the round trip


def test_noise_texture_is_deterministic_and_in_range():
    a, b = scenes.noise_texture((64, 96), 3), scenes.noise_texture((64, 96), 3)
    assert a.shape == (64, 96) and np.array_equal(a, b)
    assert 0 <= a.min() and a.max() <= 1 and a.std() > 0.05
    assert not np.array_equal(a, scenes.noise_texture((64, 96), 4))
