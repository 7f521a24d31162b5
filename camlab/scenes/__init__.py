r"""Synthetic scenes and textures: everything the virtual camera and the lessons photograph.

One home for the made-up world of the course, so lessons, widgets, benchmarks and the
data generators (:mod:`camlab.data`) build the same scenes:

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
  :func:`house_wireframe`, :func:`ground_grid`, :func:`plane_outlines`;
- **the lessons' scenes and synthetic data**, built here once for the lesson and its demos:
  :func:`box_before_wall` (01), :func:`depth_of_field_scene` (02), :func:`photo_and_page` (03),
  :func:`house_scene`, :func:`resection_set`, :func:`resection_trial` (04), :func:`box_and_rails`, :func:`rail_track`,
  :func:`sleeper_gaps` (05), :func:`ground_plane_view` (06), :func:`outlier_matches` (07),
  :func:`stereo_pair`, :func:`forward_pair` (11).

Conventions (docs/conventions.md): metres; a plane's frame has x along texture columns,
y along texture rows, z = x cross y; poses say their direction (``world_from_plane``).
This package depends on no data set, so the data generators can build on it. One module per
kind: :mod:`.textures`, :mod:`.planes`, :mod:`.photos`, :mod:`.wireframes`, :mod:`.lessons`.
"""

from __future__ import annotations

from .lessons import (
    WALL_DISTANCE,
    CameraPair,
    GroundView,
    OutlierMatches,
    ResectionSet,
    ResectionTrial,
    box_and_rails,
    box_before_wall,
    depth_of_field_scene,
    forward_pair,
    ground_plane_view,
    house_scene,
    outlier_matches,
    photo_and_page,
    rail_track,
    resection_set,
    resection_trial,
    sleeper_gaps,
    stereo_pair,
)
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
    "box_and_rails",
    "box_before_wall",
    "box_wireframe",
    "CameraPair",
    "checkerboard",
    "depth_of_field_scene",
    "desk_background",
    "facade_texture",
    "forward_pair",
    "ground_grid",
    "ground_plane_view",
    "GroundView",
    "house_picture",
    "house_scene",
    "house_wireframe",
    "letter_chart",
    "look_at_plane",
    "noise_texture",
    "outlier_matches",
    "OutlierMatches",
    "page_texture",
    "painting_texture",
    "photo_and_page",
    "photo_plane",
    "photograph_plane",
    "Plane",
    "plane_outlines",
    "PlanePhoto",
    "portrait",
    "rail_track",
    "resection_set",
    "ResectionSet",
    "resection_trial",
    "ResectionTrial",
    "sample_photo",
    "sleeper_gaps",
    "stereo_pair",
    "text_page",
    "textured_plane",
    "wall_texture",
    "WALL_DISTANCE",
]
