"""The pinhole camera drawn in 3-D (lesson 01): its box, rays and image planes.

The similar triangles of x = f X / Z, in 2-D, are :mod:`.similar_triangles`.

Each ``draw_*`` function draws once and returns a dict of artists; its ``update_*`` partner
moves those artists, so widgets can redraw in place.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ... import pinhole as _pinhole
from .. import palette

__all__ = [
    "axis_scales",
    "box_edges",
    "label_camera_axes",
    "PINHOLE_VIEW",
    "PlaneFaces",
    "plane_faces",
    "pinhole_view",
    "draw_pinhole_3d",
    "update_pinhole_3d",
]


_EDGES = [
    (0, 1),
    (1, 3),
    (3, 2),
    (2, 0),
    (4, 5),
    (5, 7),
    (7, 6),
    (6, 4),
    (0, 4),
    (1, 5),
    (2, 6),
    (3, 7),
]


def box_edges(center, size) -> np.ndarray:
    """(12, 2, 3) end points of an axis-aligned box's edges (camera frame, metres).

    Parameters
    ----------
    center : (3,) array_like
        The box's centre, camera frame, metres.
    size : (3,) array_like
        Its extent along x, y and z, metres.

    Returns
    -------
    (12, 2, 3) ndarray
        The twelve edges, each its two ends.
    """
    c, s = np.asarray(center, float), np.asarray(size, float) / 2
    v = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * s + c
    return np.array([[v[i], v[j]] for i, j in _EDGES])


def _to_plot(p):
    """Camera frame (x right, y down, z forward) -> plot axes (z, -x, -y): depth to the right, up is up.

    The map is a rotation (determinant +1), so the plot is the camera frame seen from outside,
    not its mirror image: with depth running right and y down, x comes out of the screen.
    :func:`label_camera_axes` labels the ticks in camera coordinates.
    """
    p = np.asarray(p, float)
    return p[..., 2], -p[..., 0], -p[..., 1]


def label_camera_axes(ax, labelpad: float = 8) -> None:
    """Label a 3-D axes drawn through ``_to_plot`` in camera coordinates: z forward, x right, y down.

    The plot's second and third axes hold -x and -y; their tick labels show x and y themselves.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        The 3-D axes (formatters, locators and labels set in place).
    labelpad : float
        Space between the axes' labels and their tick labels, points.
    """
    from matplotlib.ticker import FuncFormatter, MaxNLocator

    negated = FuncFormatter(lambda v, _pos: f"{-v + 0.0:g}")  # + 0.0: no "-0"
    ax.yaxis.set_major_formatter(negated)
    ax.zaxis.set_major_formatter(negated)
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(3))
    ax.set_xlabel("z, forward (m)", labelpad=labelpad)
    ax.set_ylabel("x, right (m)", labelpad=labelpad)
    ax.set_zlabel("y, down (m)", labelpad=labelpad)


class PlaneFaces(NamedTuple):
    """Scene planes as :func:`draw_pinhole_3d` draws them (its ``faces``).

    Attributes
    ----------
    corners : (F, 4, 3) ndarray
        Each plane's corners in the camera frame, metres.
    greys : (F,) ndarray
        Each plane's mean grey in [0, 1].
    """

    corners: np.ndarray
    greys: np.ndarray


def plane_faces(planes) -> PlaneFaces:
    """(F, 4, 3) camera-frame corners and F mean greys of scene planes: the ``faces`` of :func:`draw_pinhole_3d`.

    Parameters
    ----------
    planes : sequence of camlab.scenes.Plane
        The scene's planes (e.g. :func:`camlab.scenes.box`), in the camera frame.

    Returns
    -------
    PlaneFaces
        ``corners`` (F, 4, 3), metres, and ``greys`` (F,), each texture's mean in [0, 1].
    """
    return PlaneFaces(
        np.array([p.corners_world for p in planes]),
        np.array([float(np.mean(p.texture)) for p in planes]),
    )


def _unique_segments(segments: np.ndarray) -> np.ndarray:
    """(K, 2, 3) segments with each one kept once, whichever way round it runs (first occurrences, in order)."""
    seg = np.asarray(segments, float)
    seen, kept = set(), []
    for k, (a, b) in enumerate(np.round(seg, 9)):
        key = tuple(sorted((tuple(a), tuple(b))))  # the same key for a -> b and b -> a
        if key not in seen:
            seen.add(key)
            kept.append(k)
    return seg[kept]


def _polyline(segments: np.ndarray) -> tuple:
    """(K, 2, 3) segments -> plot-axes coordinates of one polyline with NaN breaks (one artist, fast)."""
    seg = np.asarray(segments, float)
    pts = np.concatenate([seg, np.full((len(seg), 1, 3), np.nan)], axis=1).reshape(-1, 3)
    return _to_plot(pts)


# The 3-D pinhole view looks over the camera's right shoulder, from behind and above: the image planes
# are seen from behind, as the camera records them (the virtual plane's picture upright, the real
# plane's rotated 180 degrees, as on a ground-glass screen seen from behind), and the box from the side
# the pinhole sees. Drawing order is fixed (not by depth), nearest the viewer last: box, rays, virtual
# plane, pinhole, real plane. A live frame that redraws the moving artists in zorder then shows what a
# full draw shows.
PINHOLE_VIEW = {"elev": 20, "azim": -125}
_Z_BOX_FILL, _Z_BOX, _Z_RAYS, _Z_PINHOLE = 1.0, 1.1, 1.5, 3.0
_Z_PLANE = {"virtual": 2.0, "real": 4.0}  # + 0.1 for the picture, + 0.2 for its outline


def axis_scales(ax) -> np.ndarray:
    """Drawn length per metre along a 3-D axes' plot x, y and z (box aspect over data range), for captions.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        The 3-D axes, its limits and box aspect set.

    Returns
    -------
    (3,) ndarray
        Box-aspect units per metre along the plot's x (depth), y and z; equal when drawn to scale.
    """
    ranges = np.array([np.ptp(ax.get_xlim()), np.ptp(ax.get_ylim()), np.ptp(ax.get_zlim())])
    return np.asarray(ax.get_box_aspect(), float) / ranges


def draw_pinhole_3d(
    ax,
    edges: np.ndarray,
    f_draw: float,
    plane_half: float | None = None,
    faces: tuple[np.ndarray, np.ndarray] | None = None,
    to_scale: bool = False,
) -> dict:
    """Box edges, the pinhole, the real (behind) and virtual (in front) image planes and the rays.

    ``edges`` is (K, 2, 3) camera-frame segments (metres); the image planes are drawn at
    distance ``f_draw`` behind and in front of the pinhole at the origin, ``plane_half``
    metres half-wide (None: 1.25 times the image, so the picture fills its frame). ``faces``,
    if given, is ``(polygons, shades)`` (see :func:`plane_faces`): (F, 4, 3) camera-frame face
    corners and F greys in [0, 1]; the faces the camera sees are then filled on the box and,
    projected, on both image planes, so each plane shows a picture of the box rather than its
    wire frame. The axes are labelled in camera coordinates (:func:`label_camera_axes`) and
    seen from :data:`PINHOLE_VIEW`. ``to_scale``: one length per metre on all three axes
    (otherwise depth is drawn shorter; :func:`axis_scales` says by how much).

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        The 3-D axes to draw in.
    edges : (K, 2, 3) ndarray
        The box's edges, camera frame, metres.
    f_draw : float
        Pinhole-to-image-plane distance as drawn, metres (both planes).
    plane_half : float or None
        The image planes' half-width, metres (their height is 0.75 of it); None: fitted to the image.
    faces : (polygons, shades) or None
        Faces to fill, as :func:`plane_faces` returns them; None draws wire frames only.
    to_scale : bool
        Draw all three axes at one length per metre.

    Returns
    -------
    dict
        The artists for :func:`update_pinhole_3d`: ``"box"``, ``"pinhole"``, ``"rays"``, ``"real"``
        and ``"virtual"`` (the images' edges), ``"planes"`` (``{"real", "virtual"}``: the frames),
        ``"fills"`` (``{"box", "real", "virtual"}`` when ``faces`` is given, else empty), and
        ``"plane_half"``, ``"plane_half_drawn"`` (metres).
    """
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    ax.computed_zorder = False  # the fixed order above, in full draws and live frames alike
    art = {
        "box": ax.plot(
            *_polyline(edges),
            color=palette.BLUE,
            lw=1.5,
            path_effects=palette.halo(1.5),
            zorder=_Z_BOX,
        )[0],
        "pinhole": ax.plot(
            [0],
            [0],
            [0],
            "o",
            color="k",
            ms=6,
            mec="white",
            mew=1,
            zorder=_Z_PINHOLE,
            gid="pinhole",
        )[0],
    }
    art["planes"] = {}
    art["fills"] = {}
    for name, color in (("real", palette.RED), ("virtual", palette.GREEN)):
        z = _Z_PLANE[name]
        art["planes"][name] = ax.plot([], [], [], color=color, lw=1.2, zorder=z + 0.15)[
            0
        ]  # the frame over the picture
        # the image's edges: the picture when no faces are given; the filled faces are the picture otherwise
        art[name] = ax.plot([], [], [], color=color, lw=2.0, zorder=z + 0.2, visible=faces is None)[
            0
        ]
    if faces is not None:
        for name, z in (
            ("box", _Z_BOX_FILL),
            ("real", _Z_PLANE["real"] + 0.1),
            ("virtual", _Z_PLANE["virtual"] + 0.1),
        ):
            art["fills"][name] = ax.add_collection3d(
                Poly3DCollection([], edgecolor="none", shade=False, zorder=z)
            )
    art["rays"] = ax.plot(
        [], [], [], color=palette.ORANGE, lw=0.6, path_effects=palette.halo(0.6), zorder=_Z_RAYS
    )[0]
    # a 3-D axes' clip box is its 2-D box, which a box aspect narrows: an image plane near the view's end
    # would lose the edge that projects outside it
    for artist in (
        art["box"],
        art["pinhole"],
        art["rays"],
        *art["planes"].values(),
        *art["fills"].values(),
        art["real"],
        art["virtual"],
    ):
        artist.set_clip_on(False)
    label_camera_axes(ax)
    ax.view_init(**PINHOLE_VIEW)
    art["plane_half"] = plane_half
    update_pinhole_3d(art, edges, f_draw, faces)
    pts = edges.reshape(-1, 3)
    half = max(art["plane_half_drawn"], np.abs(pts[:, :2]).max()) * 1.15
    ax.set_xlim(-1.3 * f_draw, pts[:, 2].max() * 1.05)
    ax.set_ylim(-half, half)
    ax.set_zlim(-half, half)
    ax.set_box_aspect((np.ptp(ax.get_xlim()), 2 * half, 2 * half) if to_scale else (3, 1.2, 1.2))
    return art


def _clip_to_frame(polygon: np.ndarray, half_width: float, half_height: float) -> np.ndarray:
    """The part of a convex (K, 2) ``polygon`` inside the frame |x| <= half_width, |y| <= half_height.

    Sutherland-Hodgman: cut by each of the frame's four edges in turn, keeping the inside part
    (an edge that crosses the line contributes the crossing). Returns (M, 2), M = 0 if nothing is inside.
    """
    points = [tuple(p) for p in np.asarray(polygon, float)]
    for axis, limit in ((0, half_width), (0, -half_width), (1, half_height), (1, -half_height)):
        inside = (
            (lambda p, a=axis, b=limit: p[a] <= b)
            if limit > 0
            else (lambda p, a=axis, b=limit: p[a] >= b)
        )
        kept = []
        for k, current in enumerate(points):
            previous = points[k - 1]
            if inside(current) != inside(previous):  # the edge crosses the line: keep the crossing
                t = (limit - previous[axis]) / (current[axis] - previous[axis])
                kept.append(
                    tuple(np.asarray(previous) + t * (np.asarray(current) - np.asarray(previous)))
                )
            if inside(current):
                kept.append(current)
        points = kept
        if not points:
            break
    return np.array(points, float).reshape(-1, 2)


def pinhole_view(
    edges: np.ndarray,
    f_draw: float,
    faces: tuple[np.ndarray, np.ndarray] | None = None,
    plane_half: float | None = None,
) -> dict:
    """What :func:`update_pinhole_3d` draws, camera frame (metres): the numpy twin of ``pinholeView``.

    ``pinholeView`` in ``camlab/widgets/browser/pinhole.js`` computes the same for the browser
    (with ``faces`` given); ``tests/test_browser_pinhole_parity.py`` runs both.

    Parameters
    ----------
    edges : (K, 2, 3) ndarray
        The box's edges, camera frame, metres.
    f_draw : float
        Pinhole-to-image-plane distance as drawn, metres (both planes).
    faces : (polygons, shades) or None
        Faces to fill (:func:`plane_faces`); None draws the wire frame only.
    plane_half : float or None
        The planes' half-width, metres; None fits the image (1.25 times its widest point).

    Returns
    -------
    dict
        ``plane_half`` (m); ``edges`` (K', 2, 3): the edges drawn (with faces, those of the faces
        the pinhole sees, each once); ``rays`` (N, 2, 3): from each corner through the pinhole to
        the real plane; ``frames`` and ``images`` by plane ("real", "virtual"): the (5, 3) frame and
        the edges' pictures (K', 2, 3) at z = -f_draw and +f_draw; with faces, ``fills``: by "box",
        "real" and "virtual" a list of (polygon (M, 3), grey), the box's seen faces far to near
        and their pictures cut at each frame (Sutherland-Hodgman), as the sensor cuts the image.
    """
    corners = np.unique(edges.reshape(-1, 3), axis=0)
    h = plane_half or 1.25 * float(np.abs(_pinhole.project_pinhole(corners, f_draw)).max())
    out: dict = {"plane_half": h, "frames": {}, "images": {}}
    if faces is not None:
        polygons, shades = (np.asarray(a, float) for a in faces)
        centres = polygons.mean(axis=1)
        normals = np.cross(polygons[:, 1] - polygons[:, 0], polygons[:, 2] - polygons[:, 1])
        seen = np.einsum("ij,ij->i", normals, -centres) > 0  # the face turns towards the pinhole
        # far faces first: nearer ones paint over them
        order = np.argsort(-centres[:, 2], kind="stable")
        seen_faces = [k for k in order if seen[k]]
        out["fills"] = {"box": [(polygons[k], float(shades[k])) for k in seen_faces]}
        # the view looks from the pinhole's side: draw the seen faces' edges (not the hidden ones through the
        # fills) and the rays from their corners
        edges = np.concatenate(
            [np.stack([polygons[k], np.roll(polygons[k], -1, axis=0)], axis=1) for k in seen_faces]
        )
        corners = np.unique(np.round(polygons[seen_faces].reshape(-1, 3), 12), axis=0)
        edges = _unique_segments(
            edges
        )  # an edge two seen faces share, drawn once: halos drawn twice split it
    out["edges"] = edges
    for name, sign in (("real", -1), ("virtual", 1)):
        z = sign * f_draw
        out["frames"][name] = np.array(
            [
                [-h, -h * 0.75, z],
                [h, -h * 0.75, z],
                [h, h * 0.75, z],
                [-h, h * 0.75, z],
                [-h, -h * 0.75, z],
            ]
        )
        img = _pinhole.project_pinhole(edges.reshape(-1, 3), f_draw, plane=name).reshape(-1, 2, 2)
        out["images"][name] = np.concatenate([img, np.full(img.shape[:2] + (1,), z)], axis=2)
        if faces is not None:
            # each face's picture, cut at the frame as the sensor cuts the image: what falls outside is not recorded
            cut = [
                (_clip_to_frame(_pinhole.project_pinhole(p, f_draw, plane=name), h, 0.75 * h), grey)
                for p, grey in out["fills"]["box"]
            ]
            out["fills"][name] = [
                (np.column_stack([p, np.full(len(p), z)]), grey) for p, grey in cut if len(p) >= 3
            ]
    ends = -corners * f_draw / corners[:, 2:3]  # through the pinhole to the real plane
    out["rays"] = np.stack([corners, ends], axis=1)
    return out


def update_pinhole_3d(
    art: dict,
    edges: np.ndarray,
    f_draw: float,
    faces: tuple[np.ndarray, np.ndarray] | None = None,
    plane_half: float | None = None,
) -> None:
    """Move the box to ``edges`` (and its ``faces``) and the image planes to ``f_draw``.

    See :func:`draw_pinhole_3d` for ``faces`` and :func:`pinhole_view` for what is drawn.

    Parameters
    ----------
    art : dict
        What :func:`draw_pinhole_3d` returned (moved in place; ``"plane_half_drawn"`` is updated).
    edges : (K, 2, 3) ndarray
        The box's edges, camera frame, metres.
    f_draw : float
        Pinhole-to-image-plane distance as drawn, metres (both planes).
    faces : (polygons, shades) or None
        Faces to fill (:func:`plane_faces`); ignored unless the drawing was made with faces.
    plane_half : float or None
        The planes' half-width this time, metres (e.g. the sensor's, scaled like ``f_draw``);
        None keeps the one given to :func:`draw_pinhole_3d`, or fits the image.
    """
    view = pinhole_view(
        edges, f_draw, faces if art["fills"] else None, plane_half or art["plane_half"]
    )
    art["plane_half_drawn"] = view["plane_half"]
    art["box"].set_data_3d(*_polyline(view["edges"]))
    for name in ("box", "real", "virtual"):
        if "fills" in view:
            fills = view["fills"][name]
            art["fills"][name].set_verts([np.column_stack(_to_plot(p)) for p, _ in fills])
            art["fills"][name].set_facecolor([(grey,) * 3 for _, grey in fills])
        if name != "box":
            art["planes"][name].set_data_3d(*_to_plot(view["frames"][name]))
            art[name].set_data_3d(*_polyline(view["images"][name]))
    art["rays"].set_data_3d(*_polyline(view["rays"]))
