"""Optics diagrams: a 3-D pinhole camera, thin-lens ray diagrams, blur curves (lessons 01-02).

Each ``draw_*`` function draws once and returns a dict of artists; its ``update_*``
partner moves those artists, so widgets can redraw in place. The diagrams live in one
module per topic: :mod:`.pinhole_camera` (the camera in 3-D), :mod:`.similar_triangles`
(x = f X / Z in 2-D), :mod:`.pinhole_blur` (blur against the pinhole's size, its cones of
light) and :mod:`.thin_lens` (the ray diagram, the focus cone, the blur disc); every name is
importable from here.
"""

from __future__ import annotations

from .band_heights import draw_band_heights
from .pinhole_blur import (
    CONE_BEFORE,
    CONE_COLOURS,
    draw_pinhole_blur,
    draw_pinhole_cones,
    update_pinhole_blur,
)
from .pinhole_camera import (
    PINHOLE_VIEW,
    PlaneFaces,
    axis_scales,
    box_edges,
    draw_pinhole_3d,
    label_camera_axes,
    pinhole_view,
    plane_faces,
    update_pinhole_3d,
)
from .similar_triangles import (
    F_LABEL_ROOM,
    SHORTEST_ARROW,
    Z_LABEL_ROOM,
    draw_similar_triangles,
    similar_triangles_layout,
    update_similar_triangles,
)
from .thin_lens import (
    BLUR_VIEWS,
    CONE_IMAGE_MAX,
    CONE_OBJECT_MAX,
    GREEN_LIGHT,
    IMAGE_HEAD_MIN,
    THIN_LENS_X,
    THIN_LENS_Y,
    BlurView,
    blur_view,
    draw_blur_disc,
    draw_focus_cone,
    draw_thin_lens,
    update_blur_disc,
    update_focus_cone,
    update_thin_lens,
)

__all__ = [
    "draw_band_heights",
    "SHORTEST_ARROW",
    "F_LABEL_ROOM",
    "Z_LABEL_ROOM",
    "THIN_LENS_X",
    "IMAGE_HEAD_MIN",
    "THIN_LENS_Y",
    "CONE_OBJECT_MAX",
    "CONE_IMAGE_MAX",
    "GREEN_LIGHT",
    "BLUR_VIEWS",
    "CONE_COLOURS",
    "CONE_BEFORE",
    "axis_scales",
    "box_edges",
    "label_camera_axes",
    "PINHOLE_VIEW",
    "PlaneFaces",
    "plane_faces",
    "pinhole_view",
    "draw_pinhole_3d",
    "update_pinhole_3d",
    "draw_similar_triangles",
    "similar_triangles_layout",
    "update_similar_triangles",
    "draw_thin_lens",
    "update_thin_lens",
    "draw_focus_cone",
    "update_focus_cone",
    "draw_blur_disc",
    "update_blur_disc",
    "draw_pinhole_blur",
    "update_pinhole_blur",
    "blur_view",
    "BlurView",
    "draw_pinhole_cones",
]
