r"""Synthetic scenes and textures: everything the virtual camera and the lessons photograph.

One home for the made-up world of the course, so lessons, widgets, benchmarks and the
data-set generators (:mod:`camlab.fixtures`) build the same scenes:

- **textures** (read-only arrays, cached where they are pure functions of their
  arguments): :func:`as_texture`, :func:`portrait` (the one bundled sample photograph),
  :func:`page_texture`, :func:`facade_texture`, :func:`painting_texture`,
  :func:`desk_background`, :func:`wall_texture` (panoramas), :func:`noise_texture` (stereo),
  and one fresh uint8 picture to warp, :func:`house_picture` (lesson 07);
- **planes for** :func:`camlab.render.render`: :class:`Plane`, :func:`textured_plane`,
  :func:`checkerboard`, :func:`photo_plane`, :func:`text_page`, :func:`box`;
- **plane photos** made by one homography (lesson 10): :func:`photograph_plane`,
  :func:`sample_photo`;
- **wireframes** (M, 2, 3) segments (lessons 04-05): :func:`box_wireframe`,
  :func:`house_wireframe`, :func:`ground_grid`, :func:`plane_outlines`.

The lessons' own scenes and synthetic data, built from these pieces, are fixtures:
:mod:`camlab.fixtures` (``fixtures.house_scene()``, ``fixtures.stereo_pair(...)`` ...).

Conventions (docs/conventions.md): metres; a plane's frame has x along texture columns,
y along texture rows, z = x cross y; poses say their direction (``world_from_plane``).
This package depends on no data set, so the data generators can build on it. One module per
kind: :mod:`.textures`, :mod:`.planes`, :mod:`.photos`, :mod:`.wireframes`.
"""

from __future__ import annotations

from .photos import (
    PlanePhoto,
    look_at_plane,
    photograph_plane,
    sample_photo,
)
from .planes import (
    Plane,
    box,
    checkerboard,
    letter_chart,
    photo_plane,
    text_page,
    textured_plane,
)
from .textures import (
    as_texture,
    desk_background,
    facade_texture,
    house_picture,
    noise_texture,
    page_texture,
    painting_texture,
    portrait,
    wall_texture,
)
from .wireframes import (
    box_wireframe,
    ground_grid,
    house_wireframe,
    plane_outlines,
)

__all__ = [
    "as_texture",
    "box",
    "box_wireframe",
    "checkerboard",
    "desk_background",
    "facade_texture",
    "ground_grid",
    "house_picture",
    "house_wireframe",
    "letter_chart",
    "look_at_plane",
    "noise_texture",
    "page_texture",
    "painting_texture",
    "photo_plane",
    "photograph_plane",
    "Plane",
    "plane_outlines",
    "PlanePhoto",
    "portrait",
    "sample_photo",
    "text_page",
    "textured_plane",
    "wall_texture",
]
