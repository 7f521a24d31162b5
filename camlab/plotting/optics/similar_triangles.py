"""The similar triangles of pinhole projection, x = f X / Z, drawn in 2-D (lesson 01).

A side view: depth z to the right, height -y upwards, the real and the virtual image planes
either side of the pinhole, and dimension lines for f, Z, Y and y. :func:`draw_similar_triangles`
draws once and returns a dict of artists; :func:`update_similar_triangles` moves them, so
widgets can redraw in place.
"""

from __future__ import annotations

import numpy as np

from .. import palette

__all__ = [
    "F_LABEL_ROOM",
    "SHORTEST_ARROW",
    "Z_LABEL_ROOM",
    "draw_similar_triangles",
    "similar_triangles_layout",
    "update_similar_triangles",
]


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


def _dimension_layout(
    a,
    b,
    text: str,
    offset=(0.0, 0.0),
    ha: str = "center",
    va: str = "center",
    label_at=None,
    min_arrow: float = 0.0,
) -> dict:
    """A dimension line from ``a`` to ``b`` and its label (at the middle plus ``offset``, or at ``label_at``).

    An arrow shorter than ``min_arrow`` (data units) is not shown: its two heads would overlap into a star.
    """
    at = (
        label_at
        if label_at is not None
        else ((a[0] + b[0]) / 2 + offset[0], (a[1] + b[1]) / 2 + offset[1])
    )
    shown = bool(np.hypot(b[0] - a[0], b[1] - a[1]) >= min_arrow)
    return dict(
        a=[float(a[0]), float(a[1])],
        b=[float(b[0]), float(b[1])],
        shown=shown,
        text=text,
        at=[float(at[0]), float(at[1])],
        ha=ha,
        va=va,
    )


def _set_dimension(dim: dict, a, b, shown: bool, text: str, at, ha: str, va: str) -> None:
    """Place a dimension line's arrow and label as :func:`_dimension_layout` laid them out."""
    dim["arrow"].xy, dim["arrow"].xyann = tuple(b), tuple(a)
    dim["arrow"].set_visible(shown)
    dim["label"].set_position(tuple(at))
    dim["label"].set_text(text)
    dim["label"].set_horizontalalignment(ha)
    dim["label"].set_verticalalignment(va)


def _signed(value: float, digits: int = 1) -> str:
    """``value`` with a sign and ``digits`` decimals.

    A value that rounds to zero prints a plain "0.0" (never "-0.0" or "+0.0", as the demo's title
    prints it).
    """
    rounded = round(value, digits) + 0.0
    return f"{rounded:+.{digits}f}" if rounded != 0 else f"{0:.{digits}f}"


def draw_similar_triangles(ax, z_max: float, h_max: float) -> dict:
    """A 2-D side view of pinhole projection: depth z to the right, height (-y, up) upwards.

    The pinhole sits at the origin, the real image plane at z = -f and the virtual one at
    z = +f. Two shaded similar triangles share the ray through the hole: (0, 0)-(Z, 0)-(Z, Y)
    and (0, 0)-(f, 0)-(f, y); dimension lines label f, Z, Y and y. Y and y are signed in the
    camera frame (y down), so a point drawn above the axis has a negative Y. Nothing is placed
    until :func:`update_similar_triangles`.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in (equal aspect).
    z_max : float
        The largest depth to show, metres.
    h_max : float
        The largest height to show either side of the axis, metres.

    Returns
    -------
    dict
        The artists for :func:`update_similar_triangles`: ``"big"`` and ``"small"`` (the
        triangles), ``"object"``, ``"point"``, ``"ray"``, ``"planes"``, ``"virtual"``, ``"real"``,
        ``"pinhole"`` and ``"pinhole_dot"``, and ``"dims"`` (the dimension lines ``"f"``, ``"Z"``,
        ``"Y"``, ``"y"``, ``"y_real"``, each an arrow and a label).
    """
    # the optical axis; "0.4" measured 2.75:1 against the fills under matplotlib 3.9.4
    ax.axhline(0, color="0.2", lw=0.8, zorder=0)
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
    # room for the real plane's label at f = 1 m, and for Y's beyond the object at the largest Z (z_max - 0.6)
    ax.set_xlim(-0.28 * z_max, z_max + 0.5)
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


def similar_triangles_layout(f: float, Z: float, Y: float, h: float) -> dict:
    """Where every moving part of the side view goes for ``f``, ``Z`` and ``Y``, and its label text.

    The arithmetic of :func:`update_similar_triangles`, apart from matplotlib, so the browser's
    twin (``similarTrianglesLayout`` in ``camlab/widgets/browser/geometry.js``) can be tested
    against it. The figure's vertical axis is -y (up), so the object point is at height -Y.

    Parameters
    ----------
    f : float
        Focal length (pinhole to image plane), metres.
    Z : float
        The object point's depth, metres (> 0).
    Y : float
        The object point's camera y, metres.
    h : float
        Half the height of the dashed image planes, metres (0.85 of the axes' top).

    Returns
    -------
    dict
        ``y`` (= f Y / Z, metres); the polylines ``big``, ``small`` (the triangles), ``object``,
        ``ray``, ``planes`` (a NaN row between the two planes), ``virtual``, ``real``, as
        (N, 2) lists of (z, -y) rows; ``point`` (z, -y); ``pinhole`` (where the pinhole's label
        sits); ``dims``: per dimension line (``f``, ``Z``, ``Y``, ``y``, ``y_real``) its ends
        ``a`` and ``b``, ``shown`` (False for an arrow shorter than :data:`SHORTEST_ARROW`), its
        label's ``text``, position ``at`` and alignments ``ha`` and ``va``.
    """
    y = f * Y / Z
    up, up_img = -Y, -y  # heights on the page
    away = -0.12 * h if up >= 0 else 0.12 * h  # dimension lines go on the side away from the object
    # the Z label inside its arrow when the arrow is long enough to hold it, else just beyond its end
    inside = Z >= Z_LABEL_ROOM
    f_inside = f >= F_LABEL_ROOM
    # at Y near 0 the label would sit on the axis line: lift it clear (above, or below for an object below)
    lift = 0.0 if abs(up) >= 0.3 else (0.15 if away < 0 else -0.15) - up / 2
    dims = {
        "Z": _dimension_layout(
            (0, 3 * away),
            (Z, 3 * away),
            f"Z = {Z:.2f} m",
            ha="center" if inside else "left",
            label_at=None if inside else (Z + 0.08, 3 * away),
        ),
        # the f label inside its arrow when there is room, else just beyond its end (clear of the virtual plane)
        "f": _dimension_layout(
            (0, away),
            (f, away),
            f"f = {f:.2f} m",
            offset=(0, away),
            ha="center" if f_inside else "left",
            label_at=None if f_inside else (f + 0.06, away),
        ),
        "Y": _dimension_layout(
            (Z + 0.1, 0),
            (Z + 0.1, up),
            f" Y = {_signed(Y, 2)} m",
            offset=(0.05, lift),
            ha="left",
            min_arrow=SHORTEST_ARROW,
        ),
        # each image's label at the far end of its plane's dashed line (virtual at the top, real at the
        # bottom): outside both triangles and off the ray at every setting, never between two close planes
        "y": _dimension_layout(
            (f + 0.06, 0),
            (f + 0.06, up_img),
            f"virtual: y = {_signed(y * 100)} cm",
            va="bottom",
            label_at=(f, h + 0.02),
            min_arrow=SHORTEST_ARROW,
        ),
        "y_real": _dimension_layout(
            (-f - 0.06, 0),
            (-f - 0.06, -up_img),
            f"real: {_signed(-y * 100)} cm",
            va="top",
            label_at=(-f, -h - 0.02),
            min_arrow=SHORTEST_ARROW,
        ),
    }
    nan = float("nan")
    return dict(
        y=y,
        big=[[0.0, 0.0], [Z, 0.0], [Z, up]],
        small=[[0.0, 0.0], [f, 0.0], [f, up_img]],
        object=[[Z, 0.0], [Z, up]],
        point=[Z, up],
        ray=[[-f, y], [Z, up]],
        planes=[[-f, -h], [-f, h], [nan, nan], [f, -h], [f, h]],
        virtual=[[f, 0.0], [f, up_img]],
        real=[[-f, 0.0], [-f, y]],
        pinhole=[0.0, 4.6 * away],
        dims=dims,
    )


def update_similar_triangles(art: dict, f: float, Z: float, Y: float) -> float:
    """Redraw for focal length ``f``, object depth ``Z`` and ``Y`` (metres, camera frame: y down); returns y.

    The figure's vertical axis is -y (up), so the object point is drawn at height -Y; the
    positions are :func:`similar_triangles_layout`'s.

    Parameters
    ----------
    art : dict
        What :func:`draw_similar_triangles` returned (moved in place).
    f : float
        Focal length (pinhole to image plane), metres.
    Z : float
        The object point's depth, metres (> 0).
    Y : float
        The object point's camera y, metres.

    Returns
    -------
    float
        The image height ``y = f Y / Z`` on the virtual plane, metres.
    """
    h = art["planes"].axes.get_ylim()[1] * 0.85
    lay = similar_triangles_layout(f, Z, Y, h)
    art["big"].set_xy(lay["big"])
    art["small"].set_xy(lay["small"])
    for key in ("object", "ray", "planes", "virtual", "real"):
        art[key].set_data(*np.transpose(lay[key]))
    art["point"].set_data([lay["point"][0]], [lay["point"][1]])
    for key, dim in lay["dims"].items():
        _set_dimension(art["dims"][key], **dim)
    art["pinhole"].xyann = tuple(lay["pinhole"])
    return lay["y"]
