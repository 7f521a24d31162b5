"""Optics diagrams: a 3-D pinhole camera, thin-lens ray diagrams, blur curves (lessons 01-02).

Each ``draw_*`` function draws once and returns a dict of artists; its ``update_*``
partner moves those artists, so widgets can redraw in place.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .. import lens as _lens
from .. import pinhole as _pinhole
from . import palette

__all__ = [
    "axis_scales",
    "box_edges",
    "label_camera_axes",
    "PINHOLE_VIEW",
    "PlaneFaces",
    "plane_faces",
    "draw_pinhole_3d",
    "update_pinhole_3d",
    "draw_similar_triangles",
    "update_similar_triangles",
    "draw_thin_lens",
    "update_thin_lens",
    "draw_focus_cone",
    "update_focus_cone",
    "draw_blur_disc",
    "update_blur_disc",
    "draw_pinhole_blur",
    "update_pinhole_blur",
    "draw_pinhole_cones",
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
    """(12, 2, 3) end points of an axis-aligned box's edges (camera frame, metres)."""
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
    """Label a 3-D axes drawn through :func:`_to_plot` in camera coordinates: z forward, x right, y down.

    The plot's second and third axes hold -x and -y; their tick labels show x and y themselves.
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
    """(F, 4, 3) camera-frame corners and F mean greys of scene planes: the ``faces`` of :func:`draw_pinhole_3d`."""
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
    """Drawn length per metre along a 3-D axes' plot x, y and z (box aspect over data range), for captions."""
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


def update_pinhole_3d(
    art: dict,
    edges: np.ndarray,
    f_draw: float,
    faces: tuple[np.ndarray, np.ndarray] | None = None,
    plane_half: float | None = None,
) -> None:
    """Move the box to ``edges`` (and its ``faces``, see :func:`draw_pinhole_3d`) and the image planes to ``f_draw``.

    ``plane_half``: the planes' half-width this time (metres; e.g. the sensor's, scaled like ``f_draw``).
    """
    corners = np.unique(edges.reshape(-1, 3), axis=0)
    h = (
        plane_half
        or art["plane_half"]
        or 1.25 * float(np.abs(_pinhole.project_pinhole(corners, f_draw)).max())
    )
    art["plane_half_drawn"] = h
    if faces is not None and art["fills"]:
        polygons, shades = (np.asarray(a, float) for a in faces)
        centres = polygons.mean(axis=1)
        normals = np.cross(polygons[:, 1] - polygons[:, 0], polygons[:, 2] - polygons[:, 1])
        seen = np.einsum("ij,ij->i", normals, -centres) > 0  # the face turns towards the pinhole
        order = np.argsort(-centres[:, 2])  # far faces first: nearer ones paint over them
        seen_faces = [k for k in order if seen[k]]
        colours = [(shades[k],) * 3 for k in seen_faces]
        art["fills"]["box"].set_verts([np.column_stack(_to_plot(polygons[k])) for k in seen_faces])
        art["fills"]["box"].set_facecolor(colours)
        # the view looks from the pinhole's side: draw the seen faces' edges (not the hidden ones through the
        # fills) and the rays from their corners
        edges = np.concatenate(
            [np.stack([polygons[k], np.roll(polygons[k], -1, axis=0)], axis=1) for k in seen_faces]
        )
        corners = np.unique(np.round(polygons[seen_faces].reshape(-1, 3), 12), axis=0)
        edges = _unique_segments(
            edges
        )  # an edge two seen faces share, drawn once: halos drawn twice split it
    art["box"].set_data_3d(*_polyline(edges))
    for name, sign in (("real", -1), ("virtual", 1)):
        z = sign * f_draw
        sq = np.array(
            [
                [-h, -h * 0.75, z],
                [h, -h * 0.75, z],
                [h, h * 0.75, z],
                [-h, h * 0.75, z],
                [-h, -h * 0.75, z],
            ]
        )
        art["planes"][name].set_data_3d(*_to_plot(sq))
        img = _pinhole.project_pinhole(edges.reshape(-1, 3), f_draw, plane=name).reshape(-1, 2, 2)
        art[name].set_data_3d(
            *_polyline(np.concatenate([img, np.full(img.shape[:2] + (1,), z)], axis=2))
        )
        if faces is not None and art["fills"]:
            # each face's picture, cut at the frame as the sensor cuts the image: what falls outside is not recorded
            cut = [
                (
                    _clip_to_frame(
                        _pinhole.project_pinhole(polygons[k], f_draw, plane=name), h, 0.75 * h
                    ),
                    colour,
                )
                for k, colour in zip(seen_faces, colours, strict=True)
            ]
            cut = [(p, colour) for p, colour in cut if len(p) >= 3]
            art["fills"][name].set_verts(
                [
                    np.column_stack(_to_plot(np.column_stack([p, np.full(len(p), z)])))
                    for p, _ in cut
                ]
            )
            art["fills"][name].set_facecolor([colour for _, colour in cut])
    ends = -corners * f_draw / corners[:, 2:3]  # through the pinhole to the real plane
    art["rays"].set_data_3d(*_polyline(np.stack([corners, ends], axis=1)))


def _dimension(ax, color: str) -> dict:
    """A dimension line (double arrow) with a label, drawn empty; :func:`_set_dimension` places it."""
    arrow = ax.annotate(
        "",
        xy=(0, 0),
        xytext=(0, 0),
        arrowprops=dict(arrowstyle="<->", color=color, lw=1.2, shrinkA=0, shrinkB=0),
    )
    label = ax.text(
        0,
        0,
        "",
        color=color,
        fontsize=10,
        ha="center",
        va="center",
        bbox=dict(fc="white", ec="none", pad=1),
    )
    return {"arrow": arrow, "label": label}


def _set_dimension(
    dim: dict,
    a,
    b,
    text: str,
    offset=(0.0, 0.0),
    ha: str = "center",
    va: str = "center",
    label_at=None,
    min_arrow: float = 0.0,
) -> None:
    """Place a dimension line from ``a`` to ``b`` and its label (at the middle plus ``offset``, or at ``label_at``).

    An arrow shorter than ``min_arrow`` (data units) is hidden: its two heads would overlap into a star.
    """
    dim["arrow"].xy, dim["arrow"].xyann = tuple(b), tuple(a)
    dim["arrow"].set_visible(bool(np.hypot(b[0] - a[0], b[1] - a[1]) >= min_arrow))
    at = (
        label_at
        if label_at is not None
        else ((a[0] + b[0]) / 2 + offset[0], (a[1] + b[1]) / 2 + offset[1])
    )
    dim["label"].set_position(at)
    dim["label"].set_text(text)
    dim["label"].set_horizontalalignment(ha)
    dim["label"].set_verticalalignment(va)


def _signed(value: float, digits: int = 1) -> str:
    """``value`` with a sign and ``digits`` decimals; a value that rounds to zero prints a plain "0.0" (never
    "-0.0" or "+0.0", as the demo's title prints it)."""
    rounded = round(value, digits) + 0.0
    return f"{rounded:+.{digits}f}" if rounded != 0 else f"{0:.{digits}f}"


def draw_similar_triangles(ax, z_max: float, h_max: float) -> dict:
    """A 2-D side view of pinhole projection: depth z to the right, height (-y, up) upwards.

    The pinhole sits at the origin, the real image plane at z = -f and the virtual one at
    z = +f. Two shaded similar triangles share the ray through the hole: (0, 0)-(Z, 0)-(Z, Y)
    and (0, 0)-(f, 0)-(f, y); dimension lines label f, Z, Y and y. Y and y are signed in the
    camera frame (y down), so a point drawn above the axis has a negative Y.
    """
    ax.axhline(0, color="0.4", lw=0.8, zorder=0)
    art = {
        # returned with the moving artists: a ray passes over the hole, and the dot must stay on top
        "pinhole_dot": ax.plot(
            [0], [0], "o", color="k", ms=6, mec="white", mew=1, zorder=5, gid="pinhole"
        )[0],
        "big": ax.fill([0, 1, 1], [0, 0, 1], color=palette.BLUE, alpha=0.15, lw=0)[0],
        "small": ax.fill([0, 1, 1], [0, 0, 1], color=palette.GREEN, alpha=0.3, lw=0)[0],
        "object": ax.plot([], [], color=palette.BLUE, lw=3, solid_capstyle="butt")[0],
        "point": ax.plot([], [], "o", color=palette.BLUE, ms=8)[0],
        "ray": ax.plot([], [], color=palette.ORANGE, lw=1.5, path_effects=palette.halo(1.5))[0],
        "planes": ax.plot([], [], color="0.3", lw=1, ls="--")[0],
        "virtual": ax.plot([], [], color=palette.GREEN, lw=3, solid_capstyle="butt")[0],
        "real": ax.plot([], [], color=palette.RED, lw=3, solid_capstyle="butt")[0],
        # below (or above) the pinhole, under the f and Z dimension lines, where no other label goes
        "pinhole": ax.annotate(
            "pinhole",
            (0, 0),
            xytext=(0, 0),
            ha="center",
            va="center",
            fontsize=9,
            arrowprops=dict(arrowstyle="-", color="0.3", lw=0.8, shrinkA=2, shrinkB=3),
        ),
        "dims": {
            k: _dimension(ax, c)
            for k, c in (
                ("f", "k"),
                ("Z", "k"),
                ("Y", palette.BLUE),
                ("y", palette.GREEN),
                ("y_real", palette.RED),
            )
        },
    }
    for key in ("y", "y_real"):
        art["dims"][key]["label"].set_fontsize(9)
    ax.set_xlim(
        -0.28 * z_max, 1.14 * z_max
    )  # room for the real plane's label at f = 1 m and for Y's at Z = 5 m
    ax.set_ylim(-h_max, h_max)
    ax.set_aspect("equal")  # similar triangles look similar only at equal scales
    ax.set_xlabel("depth z (m)")
    ax.set_ylabel("height -y, up (m)")
    return art


SHORTEST_ARROW = 0.15  # metres: a shorter dimension arrow is hidden (its heads would overlap)
F_LABEL_ROOM = 0.9  # metres: a shorter f arrow cannot hold "f = 0.80 m" clear of the pinhole's tick and the plane
Z_LABEL_ROOM = (
    2.2  # metres: a Z arrow shorter than this cannot hold its label "Z = 1.20 m" between its heads
)


def update_similar_triangles(art: dict, f: float, Z: float, Y: float) -> float:
    """Redraw for focal length ``f``, object depth ``Z`` and ``Y`` (metres, camera frame: y down); returns y.

    The figure's vertical axis is -y (up), so the object point is drawn at height -Y.
    """
    y = f * Y / Z
    up, up_img = -Y, -y  # heights on the page
    art["big"].set_xy([[0, 0], [Z, 0], [Z, up]])
    art["small"].set_xy([[0, 0], [f, 0], [f, up_img]])
    art["object"].set_data([Z, Z], [0, up])
    art["point"].set_data([Z], [up])
    art["ray"].set_data([-f, Z], [y, up])
    h = art["planes"].axes.get_ylim()[1] * 0.85
    art["planes"].set_data([-f, -f, np.nan, f, f], [-h, h, np.nan, -h, h])
    art["virtual"].set_data([f, f], [0, up_img])
    art["real"].set_data([-f, -f], [0, y])
    away = -0.12 * h if up >= 0 else 0.12 * h  # dimension lines go on the side away from the object
    d = art["dims"]
    # the Z label inside its arrow when the arrow is long enough to hold it, else just beyond its end
    inside = Z >= Z_LABEL_ROOM
    _set_dimension(
        d["Z"],
        (0, 3 * away),
        (Z, 3 * away),
        f"Z = {Z:.2f} m",
        ha="center" if inside else "left",
        label_at=None if inside else (Z + 0.08, 3 * away),
    )
    # the f label inside its arrow when there is room, else just beyond its end (clear of the dashed virtual plane)
    f_inside = f >= F_LABEL_ROOM
    _set_dimension(
        d["f"],
        (0, away),
        (f, away),
        f"f = {f:.2f} m",
        offset=(0, away),
        ha="center" if f_inside else "left",
        label_at=None if f_inside else (f + 0.06, away),
    )
    # at Y near 0 the label would sit on the axis line: lift it clear (above, or below for an object below)
    lift = 0.0 if abs(up) >= 0.3 else (0.15 if away < 0 else -0.15) - up / 2
    _set_dimension(
        d["Y"],
        (Z + 0.1, 0),
        (Z + 0.1, up),
        f" Y = {_signed(Y, 2)} m",
        offset=(0.05, lift),
        ha="left",
        min_arrow=SHORTEST_ARROW,
    )
    # each image's label at the far end of its plane's dashed line (virtual at the top, real at the bottom):
    # outside both triangles and off the ray at every setting, and never between two planes a short f puts close
    _set_dimension(
        d["y"],
        (f + 0.06, 0),
        (f + 0.06, up_img),
        f"virtual: y = {_signed(y * 100)} cm",
        va="bottom",
        label_at=(f, h + 0.02),
        min_arrow=SHORTEST_ARROW,
    )
    _set_dimension(
        d["y_real"],
        (-f - 0.06, 0),
        (-f - 0.06, -up_img),
        f"real: {_signed(-y * 100)} cm",
        va="top",
        label_at=(-f, -h - 0.02),
        min_arrow=SHORTEST_ARROW,
    )
    art["pinhole"].xyann = (0, 4.6 * away)
    return y


THIN_LENS_X = (-12.0, 7.0)  # the ray diagram's horizontal range, in units of f
IMAGE_HEAD_MIN = 0.25  # object heights: a shorter image arrow is drawn without its head
THIN_LENS_Y = (
    -5.6,
    1.4,
)  # ... and its vertical range, in object heights: a real image is inverted (m < 0), so
# the room is below the axis, down to m = -5.6 (z_o = 1.18 f, z_i = 6.6 f: the x range)


def draw_thin_lens(ax, focal_length: float, object_distance: float) -> dict:
    """A thin-lens ray diagram: object arrow, lens, foci F and F', the three principal rays, image arrow.

    Distances are drawn in units of f (the diagram depends only on z_o / f) and heights in
    units of the object's height, on fixed axes: as the object nears F the image runs off to
    the right and grows. The axes reach down to m = -5.6 (an object at 1.18 f), since a real
    image is inverted. An object or image beyond the axes is not drawn (its rays still are);
    the title, above the axes and off the rays, gives the numbers and says where it is. The
    legend sits under the axes, never over a ray. Fixed axes also keep the diagram blittable.
    """
    styles = (
        "-",
        "--",
        "-.",
    )  # one colour for light (orange), three line styles for the three rays
    names = (
        "parallel, then through F'",
        "through the centre, straight",
        "through F, then parallel",
    )
    arrow = dict(
        arrowstyle="-|>", lw=2, shrinkA=0, shrinkB=0
    )  # the tip exactly where the rays meet
    art = {
        "lens": ax.axvline(0, color=palette.BLUE, lw=2),
        "axis": ax.axhline(0, color="0.5", lw=0.8),
        # over the arrows (an image at F' in the pinhole limit, an object at 1.05 f): animated with them
        "foci": ax.plot([-1, 1], [0, 0], "k+", ms=10, mew=1.5, zorder=4)[0],
        "object": ax.annotate(
            "", xy=(0, 0), xytext=(0, 0), arrowprops=dict(arrow, color=palette.GREEN)
        ),
        # over the foci: far away the image is a short tick just beyond F', which the cross must not hide
        "image": ax.annotate(
            "", xy=(0, 0), xytext=(0, 0), arrowprops=dict(arrow, color=palette.RED), zorder=5
        ),
        # a headless (short) image also gets a dot where the rays meet, so a tick a few pixels tall still shows
        "image_dot": ax.plot([], [], "o", color=palette.RED, ms=4, zorder=5)[0],
        "rays": [
            ax.plot([], [], color=palette.ORANGE, ls=ls, lw=1.3, label=n)[0]
            for ls, n in zip(styles, names, strict=True)
        ],
        "text": ax.set_title(" \n ", fontsize=9, family="monospace"),
    }
    # F below the axis, left of its cross (on the object side every ray and the object arrow stay above the
    # axis); F' above it, right of its cross (on the image side the rays and a real image stay below it)
    ax.annotate(
        "F", (-1, 0), xytext=(-4, -4), textcoords="offset points", ha="right", va="top", fontsize=10
    )
    ax.annotate(
        "F'", (1, 0), xytext=(5, 4), textcoords="offset points", ha="left", va="bottom", fontsize=10
    )
    lo, hi = THIN_LENS_X
    ax.set(
        xlim=THIN_LENS_X,
        ylim=THIN_LENS_Y,
        yticks=range(int(np.ceil(THIN_LENS_Y[0])), int(THIN_LENS_Y[1]) + 1),
        xticks=[t for t in range(int(lo), int(hi) + 1) if t % 2 == 0],
    )
    ax.set_xlabel("distance from the lens, in units of f (object side left, image side right)")
    ax.set_ylabel("height / object height")
    ax.legend(
        loc="upper center",
        bbox_to_anchor=(0.5, -0.16),
        ncols=3,
        fontsize=8,
        title="principal rays",
        title_fontsize=8,
    )
    update_thin_lens(art, focal_length, object_distance)
    return art


def _thin_lens_note(xo: float, xi: float, m: float) -> str:
    """Where the object or image is when it lies beyond the axes ('' when both are on them)."""
    lo, hi = THIN_LENS_X
    notes = [f"object at {-xo:.1f} f, beyond the left edge" if xo < lo else ""]
    if xi > hi or not THIN_LENS_Y[0] <= m <= THIN_LENS_Y[1]:  # its numbers are on the line above
        notes.append(f"the image is beyond the {'right edge' if xi > hi else 'axes'}")
    return "; ".join(n for n in notes if n)


def update_thin_lens(art: dict, f: float, zo: float, requested: float | None = None) -> dict:
    """Move the diagram to focal length ``f`` and object distance ``zo``; returns the computed values.

    ``requested``: the object distance the control asked for, when the caller held the object
    at ``zo`` instead (a control inside the focal length, where no real image forms); the
    readout then says so, so the numbers never disagree silently with the control.
    """
    zi = float(_lens.image_distance(f, zo))
    m = float(_lens.magnification(f, zo))
    xo, xi = -zo / f, zi / f  # units of f
    lo, hi = THIN_LENS_X
    art["object"].xy, art["object"].xyann = (xo, 1.0), (xo, 0)
    art["image"].xy, art["image"].xyann = (xi, m), (xi, 0)
    # to scale: an image shorter than IMAGE_HEAD_MIN object heights (~9 screen px) has no room for a head, whose
    # base would rise above the axis onto the upright side; it is drawn as a plain red tick, from the axis to
    # where the rays meet
    headless = abs(m) < IMAGE_HEAD_MIN
    art["image"].arrow_patch.set_arrowstyle("-" if headless else "-|>")
    art["image"].arrow_patch.set_mutation_scale(10 * min(1.0, abs(m) / 0.3) + 1)
    art["object"].set_visible(xo >= lo)  # an arrow at the edge would not meet its rays
    art["image"].set_visible(xi <= hi)
    art["image_dot"].set_data(*(([xi], [m]) if headless and xi <= hi else ([], [])))
    # parallel ray -> through F'; central ray undeviated; ray through F -> parallel (exact lines, clipped by the axes)
    art["rays"][0].set_data([xo, 0, xi], [1, 1, m])
    art["rays"][1].set_data([xo, xi], [1, m])
    art["rays"][2].set_data([xo, 0, xi], [1, m, m])
    note = _thin_lens_note(xo, xi, m)
    if requested is not None and not np.isclose(requested, zo):
        inside = "inside f (no real image)" if requested <= f else "inside 1.05 f"
        held = f"z_o = {requested:.3f} m is {inside}: held at {zo:.3f} m"
        note = f"{held}; {note}" if note else held
    hint = "the object (green) and its image (red), where the rays meet"
    # distances with their unit, then in f; the magnification named in full (m is also metres)
    art["text"].set_text(
        f"f = {f * 1e3:.0f} mm   z_o = {zo:.3f} m ({-xo:.2f} f)   z_i = {zi:.3f} m ({xi:.2f} f)"
        f"   magnification {m:.3f}\n{note or hint}"
    )
    return {"image_distance": zi, "magnification": m, "image_head": not headless}


# The focus-cone diagram has two horizontal scales: the object side in metres, the image side
# in millimetres (a true-scale drawing would squeeze the image side into a few pixels).
CONE_OBJECT_MAX = 2.0  # metres drawn on [-1, 0]
CONE_IMAGE_MAX = 0.09  # metres drawn on [0, 1]


GREEN_LIGHT = 550e-9  # wavelength (m) for the diffraction blur


def _cone_x(z):
    """Signed distance from the lens (object side negative) -> plot x."""
    z = np.asarray(z, dtype=float)
    return np.where(z < 0, z / CONE_OBJECT_MAX, z / CONE_IMAGE_MAX)


def draw_focus_cone(ax, half_height_mm: float = 20.0, sensor_height_mm: float = 24.0) -> dict:
    """A point on the axis, the aperture, the cone of light behind the lens and a movable sensor.

    Vertical positions are millimetres; horizontally the object side is in metres and the
    image side in millimetres (marked on the axis), so both fit. The light stops at the
    sensor: where the rays would meet behind it, their continuation is dotted. The sensor is
    ``sensor_height_mm`` tall (24 mm: full frame). Colours: the object green, the lens blue,
    light orange, the image (where the rays meet, and the blur on the sensor) red.
    :func:`update_focus_cone` moves everything and returns the blur circle on the sensor.
    """
    # the optical axis (dark enough to read through the cone), under the cone: live frames paint the cone over
    # the cached background, so a full draw must too
    ax.axhline(0, color="0.4", lw=0.8, zorder=0.5)
    art = {
        "stop": ax.plot([], [], color="k", lw=4, solid_capstyle="butt", label="aperture stop")[0],
        # a white halo: over the orange cone the blue fell to 2.98:1 with matplotlib 3.9's antialiasing
        "lens": ax.plot(
            [],
            [],
            color=palette.BLUE,
            lw=3,
            label="lens, aperture A = f/N",
            path_effects=palette.halo(3),
        )[0],
        "cone_in": ax.fill(
            [0, 0, 0], [0, 0, 0], color=palette.ORANGE, alpha=0.22, lw=0, label="cone of light"
        )[0],
        "cone_out": ax.fill([0, 0, 0, 0], [0, 0, 0, 0], color=palette.ORANGE, alpha=0.22, lw=0)[0],
        "rays": ax.plot([], [], color=palette.ORANGE, lw=1, path_effects=palette.halo(1))[0],
        "beyond": ax.plot(
            [],
            [],
            color=palette.ORANGE,
            lw=1,
            ls=":",
            path_effects=palette.halo(1),
            label="rays beyond the sensor (blocked)",
        )[0],
        "point": ax.plot(
            [], [], "o", color=palette.GREEN, ms=7, label="object point", clip_on=False
        )[0],  # whole at 2 m, on the left spine
        "sensor": ax.plot(
            [], [], color="0.3", lw=2, label=f"sensor ({sensor_height_mm:g} mm tall)"
        )[0],
        "focus": ax.plot(
            [], [], "x", color=palette.RED, ms=8, mew=2, label="image point z_i (rays meet)"
        )[0],
        "blur": ax.plot(
            [],
            [],
            color=palette.RED,
            lw=6,
            solid_capstyle="butt",
            label="blur circle c (on the sensor)",
        )[0],
        "text": ax.set_title(
            " \n ", fontsize=8.5, family="monospace"
        ),  # above the axes: never over the cone
        "half": half_height_mm,
        "sensor_half": sensor_height_mm / 2,
    }
    ticks_m = [-2.0, -1.0]
    ticks_mm = [40, 80]
    ax.set_xticks(
        [float(_cone_x(t)) for t in ticks_m] + [0.0] + [float(_cone_x(t * 1e-3)) for t in ticks_mm]
    )
    ax.set_xticklabels([f"{-t:g} m" for t in ticks_m] + ["lens"] + [f"{t} mm" for t in ticks_mm])
    ax.set_xlim(-1.06, 1.0)  # room for the object dot at the left end (2 m)
    ax.set_ylim(-half_height_mm, half_height_mm)
    ax.set_xlabel("distance from the lens\n(object side in metres, image side in millimetres)")
    ax.set_ylabel("height (mm)")
    return art


def update_focus_cone(art: dict, f: float, N: float, z_o: float, z_s: float) -> dict:
    r"""Object point at ``z_o`` (m), sensor ``z_s`` (m) behind a lens ``f`` (m) at f-number ``N``.

    The cone from the aperture (diameter A = f / N) converges to the image point at
    :math:`z_i` and cuts the sensor in a disc of diameter :math:`c = A\,|z_s - z_i| / z_i`
    (similar triangles). The cone is drawn up to the sensor, where the light stops.
    Returns ``{"z_i", "A", "c", "airy"}`` in metres (``airy``: the Airy disc
    :math:`2.44 \lambda N` in green light).
    """
    A = _lens.aperture_diameter(f, N)
    z_i = float(_lens.image_distance(f, z_o))
    a = A / 2 * 1e3  # mm
    c = A * abs(z_s - z_i) / z_i
    xo, xi, xs = float(_cone_x(-z_o)), float(_cone_x(z_i)), float(_cone_x(z_s))
    y_s = a * (1 - z_s / z_i)  # the upper ray at the sensor (it crosses the axis at z_i)
    art["stop"].set_data([0, 0, np.nan, 0, 0], [art["half"], a, np.nan, -a, -art["half"]])
    art["lens"].set_data([0, 0], [-a, a])
    art["cone_in"].set_xy([[xo, 0], [0, a], [0, -a]])
    art["cone_out"].set_xy(
        [[0, a], [xs, y_s], [xs, -y_s], [0, -a]]
    )  # a bow tie when the rays cross before z_s
    art["rays"].set_data([xo, 0, xs, np.nan, xo, 0, xs], [0, a, y_s, np.nan, 0, -a, -y_s])
    art["beyond"].set_data(
        *(([xs, xi, np.nan, xs, xi], [y_s, 0, np.nan, -y_s, 0]) if z_i > z_s else ([], []))
    )
    art["point"].set_data([xo], [0])
    art["focus"].set_data([xi], [0])
    art["sensor"].set_data([xs, xs], [-art["sensor_half"], art["sensor_half"]])
    half_c = c / 2 * 1e3
    art["blur"].set_data([xs, xs], [-max(half_c, 0.15), max(half_c, 0.15)])
    airy = 2.44 * GREEN_LIGHT * N  # the diffraction blur, which stopping down makes worse
    art["text"].set_text(
        f"A = f/N = {A * 1e3:.3g} mm   z_i = {z_i * 1e3:.2f} mm\n"
        f"z_s = {z_s * 1e3:.2f} mm   c = A |z_s - z_i| / z_i"
    )
    return {"z_i": z_i, "A": A, "c": c, "airy": airy}


# The face-on view zooms in steps so the largest of the three discs (blur, Airy, acceptable) fills at most
# 5/6 of it: (half-width, scale bar) in µm, and the pixel grid's spacing in pixels.
BLUR_VIEWS = (
    (25, 10),
    (50, 20),
    (100, 40),
    (250, 100),
    (500, 200),
    (1000, 400),
    (2500, 1000),
    (5000, 2000),
)


class BlurView(NamedTuple):
    """The face-on view :func:`blur_view` picks: its ``half_width`` and ``scale_bar`` length, µm."""

    half_width: float
    scale_bar: float


def blur_view(diameter_um: float) -> BlurView:
    """(half-width, scale-bar length) in µm of the face-on view for the largest disc ``diameter_um``."""
    for half, bar in BLUR_VIEWS:
        if diameter_um <= 2 * half * 5 / 6:
            return BlurView(half, bar)
    return BlurView(*BLUR_VIEWS[-1])


def draw_blur_disc(ax, coc_um: float = 30.0) -> dict:
    """The sensor seen face on around the image point: the blur disc (red), the acceptable blur
    ``coc_um`` (purple dashes) and the Airy disc (brown dots), to scale with each other and
    with a grid of the sensor's pixels.

    The view zooms (:data:`BLUR_VIEWS`) so that the largest disc fills at most 5/6 of it: a
    1 µm disc beside a 4 µm Airy ring is as visible as a 6 mm disc. The axes run from -1 to
    1 in units of the view's half-width, so the zoom needs no new axis limits (the demo stays
    blittable); a scale bar and the title give the scale. :func:`update_blur_disc` sets it all.
    """
    from matplotlib.collections import LineCollection
    from matplotlib.colors import to_rgba
    from matplotlib.patches import Circle

    art = {
        "grid": ax.add_collection(
            LineCollection([], colors="0.82", linewidths=0.6, zorder=0.5, gid="grid")
        ),
        # a pale face and an opaque edge: a disc a pixel wide still reads as a red dot
        "blur": ax.add_patch(
            Circle((0, 0), 1, facecolor=to_rgba(palette.RED, 0.45), edgecolor=palette.RED, lw=1.2)
        ),
        "ok": ax.add_patch(
            Circle(
                (0, 0),
                1,
                fill=False,
                edgecolor=palette.PURPLE,
                ls="--",
                lw=1.2,
                label=f"acceptable c = {coc_um:g} µm",
            )
        ),
        "airy": ax.add_patch(
            Circle(
                (0, 0),
                1,
                fill=False,
                edgecolor=palette.BROWN,
                ls=":",
                lw=1.8,
                label="Airy disc 2.44 λN",
            )
        ),
        "bar": ax.plot([], [], color="k", lw=2.5, solid_capstyle="butt")[0],
        "bar_text": ax.text(-0.92, -0.84, "", fontsize=8, ha="left", va="bottom"),
        "text": ax.set_title(" \n \n ", fontsize=8.5, family="monospace"),
        "coc": coc_um,
    }
    ax.set_xlim(-1, 1)
    ax.set_ylim(-1, 1)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_xlabel("on the sensor, face on\n(grey grid: pixels, see the title)")
    return art


def update_blur_disc(art: dict, c: float, airy: float, pixel: float) -> dict:
    """Blur circle ``c`` and Airy disc ``airy`` (diameters, metres) on pixels of ``pixel`` m, zoomed to fit.

    The title gives c in µm and in pixels, the Airy disc, and the view's width; returns
    ``{"half_um", "grid_px"}``: the view's half-width (µm) and the grid's spacing (pixels).
    """
    c_um, airy_um, pixel_um = c * 1e6, airy * 1e6, pixel * 1e6
    half, bar = blur_view(max(c_um, airy_um, art["coc"]))
    grid_px = 1 if half <= 50 else (10 if half <= 500 else 100)  # at most 20 lines across
    step = grid_px * pixel_um / half
    ticks = np.arange(step / 2, 1, step)  # the image point sits at a pixel's centre
    ticks = np.concatenate([-ticks[::-1], ticks])
    end = 0.99  # short of the frame: a live frame paints the grid over the cached spines, a full draw under them
    art["grid"].set_segments(
        [[(t, -end), (t, end)] for t in ticks] + [[(-end, t), (end, t)] for t in ticks]
    )
    art["blur"].set_radius(
        max(c_um / 2, 0.006 * half) / half
    )  # a dot at least ~2 screen pixels wide
    art["airy"].set_radius(airy_um / 2 / half)
    art["ok"].set_radius(art["coc"] / 2 / half)
    art["bar"].set_data([-0.92, -0.92 + bar / half], [-0.9, -0.9])
    art["bar_text"].set_text(f"{bar:g} µm = {bar / pixel_um:g} px")
    width = f"{2 * half / 1000:g} mm" if half >= 500 else f"{2 * half:g} µm"

    def short(
        value: float, whole_from: float = np.inf
    ) -> str:  # two decimals below 0.1: a 0.04 µm blur is not "0.0"
        return (
            f"{value:.0f}"
            if value >= whole_from
            else f"{value:.1f}"
            if value >= 0.1 or value == 0
            else f"{value:.2f}"
        )

    # µm: one decimal below 10 (a 0.5 µm disc is not "1 µm")
    art["text"].set_text(
        f"c = {short(c_um, 10)} µm = {short(c / pixel, 10)} px\nAiry disc {short(airy_um, 10)} µm\n"
        f"view {width} wide, grid {grid_px} px"
    )
    return {"half_um": half, "grid_px": grid_px}


def draw_pinhole_blur(
    ax, focal_length: float, wavelength: float = 550e-9, object_distance: float = np.inf
) -> dict:
    """Geometric, diffraction and total blur (mm) against pinhole diameter (mm), log axes, with a marker.

    ``object_distance`` (metres) is the Z of the geometric term d (1 + f/Z); infinite by default.
    """
    d = np.geomspace(0.02e-3, 3e-3, 300)
    art = {
        # brown and black: lesson 01 keeps blue for objects, orange for rays, red and green for the image planes
        "geometric": ax.plot(
            d * 1e3, d * 1e3, color=palette.BROWN, ls="--", label="geometric  d (1 + f/Z)"
        )[0],
        "diffraction": ax.plot(
            d * 1e3,
            d * 1e3,
            color=palette.BROWN,
            ls=":",
            lw=2,
            label=r"diffraction  $2.44\lambda f/d$",
        )[0],
        "total": ax.plot(d * 1e3, d * 1e3, "k", lw=2, label="total")[0],
        "marker": ax.axvline(1, color=palette.GREY, lw=1.5, label="your d"),
        "best": ax.plot([], [], "k*", ms=12, label="best diameter")[0],
        "d": d,
    }
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("pinhole diameter d (mm)")
    ax.set_ylabel("blur diameter (mm)")
    # below the axes, where the moving curves and marker never cross it: it need not be redrawn per update
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.17), ncols=2)
    update_pinhole_blur(art, focal_length, 1e-3, wavelength, object_distance)
    return art


def update_pinhole_blur(
    art: dict,
    focal_length: float,
    diameter: float,
    wavelength: float = 550e-9,
    object_distance: float = np.inf,
) -> None:
    """Redraw the curves for ``focal_length`` and ``object_distance``, the marker at ``diameter`` (metres)."""
    d = art["d"]
    b = _pinhole.pinhole_blur(d, focal_length, object_distance, wavelength)
    art["geometric"].set_ydata(b.geometric * 1e3)
    art["diffraction"].set_ydata(b.diffraction * 1e3)
    art["total"].set_ydata(b.total * 1e3)
    art["marker"].set_xdata([diameter * 1e3, diameter * 1e3])
    best = _pinhole.optimal_pinhole_diameter(focal_length, wavelength, object_distance)
    best_blur = _pinhole.pinhole_blur(best, focal_length, object_distance, wavelength).total
    art["best"].set_data([best * 1e3], [float(best_blur) * 1e3])


CONE_COLOURS = (
    palette.BLUE,
    palette.BROWN,
)  # the two object points (purple read as the real plane's red)
CONE_BEFORE = 3.0  # the cone figure shows the last 3 f of the rays before the pinhole (units of f)


def draw_pinhole_cones(
    ax,
    diameter: float,
    focal_length: float,
    object_distance: float,
    heights=(-0.02, 0.02),
    wavelength: float = 550e-9,
) -> dict:
    """Side view of pinhole blur, to scale: each object point's cone of rays through a hole of ``diameter``.

    Drawn as lesson 01's other side view (:func:`draw_similar_triangles`): depth z to the right, the
    objects on the +z side, the real image plane at z = -f on the left, height -y upwards. Two points
    at ``heights`` (metres, camera y) and distance ``object_distance`` send cones through the hole in
    the screen; each cone cuts the image plane ``focal_length`` behind it in a disc of diameter
    d (1 + f/Z) (drawn in the point's colour), widened by diffraction to the Airy disc
    2.44 lambda f / d (the pale band). Both axes are millimetres, each with one scale, so every ray is
    straight: the figure shows the last :data:`CONE_BEFORE` f of the rays before the hole, and the
    points themselves, further right, are named where their rays come in. Returns the blur terms in metres.
    """
    Z, f, d = object_distance, focal_length, diameter
    b = _pinhole.pinhole_blur(d, f, Z, wavelength)
    a = d / 2 * 1e3
    x_in, x_img = (
        CONE_BEFORE * f * 1e3,
        -f * 1e3,
    )  # plot x = depth z, mm: the right edge and the image plane
    entry = []
    for Y, colour in zip(
        heights, CONE_COLOURS, strict=True
    ):  # objects: blue and brown (green is the virtual plane, red the real one)
        y_obj = -Y * 1e3  # mm, drawn up
        y_img = Y * f / Z * 1e3  # the real image is inverted: -f Y / Z, drawn up as +
        top, bottom = y_img + b.geometric / 2 * 1e3, y_img - b.geometric / 2 * 1e3
        halo = b.total / 2 * 1e3
        s_in = (
            1 - x_in * 1e-3 / Z
        )  # where the right edge sits along the ray, from the point (0) to the hole (1)
        upper, lower = y_obj + (a - y_obj) * s_in, y_obj + (-a - y_obj) * s_in
        ax.fill(
            [0, x_img, x_img, 0],
            [a, y_img + halo, y_img - halo, -a],
            color=colour,
            alpha=0.12,
            lw=0,
        )  # diffraction
        ax.fill([x_in, 0, 0, x_in], [upper, a, -a, lower], color=colour, alpha=0.35, lw=0)
        ax.fill([0, x_img, x_img, 0], [a, top, bottom, -a], color=colour, alpha=0.35, lw=0)
        ax.plot(
            [x_img, x_img],
            [y_img - halo, y_img + halo],
            color=colour,
            lw=8,
            alpha=0.3,
            solid_capstyle="butt",
        )
        ax.plot([x_img, x_img], [bottom, top], color=colour, lw=4, solid_capstyle="butt")
        entry.append((y_obj, (upper + lower) / 2, colour))
    wall = 1.6 * max(
        abs(e[1]) for e in entry
    )  # the same for every d: panels can share the height axis
    for (
        y_obj,
        y_in,
        colour,
    ) in entry:  # the points lie off the right edge: say which ray comes from where
        side = 1 if y_in > 0 else -1
        where = "above" if y_obj > 0 else "below"
        ax.annotate(
            f"from a point {abs(y_obj):.0f} mm {where}\nthe axis, {Z:g} m away",
            (x_in, y_in),
            xytext=(x_in - 0.25 * f * 1e3, side * 0.97 * wall),
            ha="right",
            va="top" if side > 0 else "bottom",
            fontsize=8,
            color=colour,
            arrowprops=dict(arrowstyle="->", color=colour, lw=1, shrinkA=1, shrinkB=0),
        )
    ax.plot(
        [0, 0, np.nan, 0, 0], [wall, a, np.nan, -a, -wall], color="k", lw=3, solid_capstyle="butt"
    )
    # between the image plane and the screen, above the cones: the screen, whose gap on the axis is the hole
    ax.annotate(
        "screen,\nhole d",
        (0, 0.75 * wall),
        xytext=(0.5 * x_img, 0.75 * wall),
        ha="center",
        va="center",
        fontsize=8,
        arrowprops=dict(arrowstyle="->", color="k", lw=0.8, shrinkA=1, shrinkB=2),
    )
    ax.annotate(
        "image\nplane",
        (x_img, -0.75 * wall),
        xytext=(0.5 * x_img, -0.75 * wall),
        ha="center",
        va="center",
        fontsize=8,
        arrowprops=dict(arrowstyle="->", color="k", lw=0.8, shrinkA=1, shrinkB=1),
    )
    ax.axhline(0, color=palette.GREY, lw=0.6, zorder=0)
    ax.axvline(x_img, color="0.3", lw=1, ls="--")
    ax.set_xlim(x_img * 1.12, x_in)
    ax.set_ylim(-wall, wall)
    ax.set_xticks(np.arange(x_img, x_in + 1, 100))
    ax.set_xlabel(
        f"depth z (mm), pinhole at 0;\nreal image plane (dashed) at z = {x_img:.0f} mm", fontsize=9
    )
    ax.set_ylabel("height -y, up (mm)")
    ax.set_title(
        f"d = {d * 1e3:g} mm\ndisc of rays {b.geometric * 1e3:.2f} mm + diffraction {b.diffraction * 1e3:.2f} mm",
        fontsize=9,
    )
    return {"geometric": b.geometric, "diffraction": b.diffraction, "total": b.total}
