"""Pictures of the course's conventions (lesson 00): points as rows, pixels, and the camera frame."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.image import AxesImage
from matplotlib.patches import Rectangle

from . import palette
from .plane import image_axes
from .static import alt_text

# The camera frame's axes, here and wherever lesson 00 ties u and v to them (one home for the three).
X_COLOUR, Y_COLOUR, Z_COLOUR = palette.AXIS_COLOURS  # x red, y green, z blue, as every 3-D camera
POINT_COLOUR = palette.ORANGE  # the points lesson 00 reads: the demo's roof tip, the rows of X here
DIRECTION_COLOUR = (
    "0.3"  # a direction, w = 0, dark grey: purple stays "the wrong read" in lesson 00
)


def draw_pixel_grid(ax: Axes, size: tuple[int, int], points: np.ndarray, marked: int) -> AxesImage:
    """A tiny ``size = (W, H)`` image: pixel centres at whole (u, v), edges at half-integers, and ``points``.

    ``imshow``'s own extent for an (H, W) array is (-0.5, W - 0.5, H - 0.5, -0.5), the course's
    convention, so the returned image's extent shows it. Each row ``points[k]`` = (u, v) is a dot
    labelled ``X[k]``; the pixel under ``points[marked]`` is outlined and labelled with how numpy
    reads it, ``img[v, u]``. The u and v labels take the colours of the camera's x and y, which
    they run along.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in.
    size : (width, height)
        The image's size in pixels (a few pixels: every centre is ticked).
    points : (N, 2) ndarray
        Points (u, v), pixels, one per row.
    marked : int
        Index of the point whose pixel is outlined and labelled ``img[v, u]``.

    Returns
    -------
    matplotlib.image.AxesImage
        The light checkerboard of pixels.
    """
    width, height = size
    u, v = np.meshgrid(np.arange(width), np.arange(height))
    image = ax.imshow(
        (u + v) % 2, cmap="Greys", vmin=0, vmax=8
    )  # a light checkerboard: one square per pixel
    image_axes(ax, size)
    ax.set_title(f"a {width} x {height} image:\npixel centres at whole numbers", fontsize=10)
    ax.set_anchor("N")  # the top of its slot, like the panels beside it, so their titles line up
    ax.set_xlabel("u (px): column, along the camera's x", color=X_COLOUR)
    ax.set_ylabel("v (px): row, along y", color=Y_COLOUR)
    for axis, n in (
        (ax.xaxis, width),
        (ax.yaxis, height),
    ):  # the centres, and the edges -0.5 and n - 0.5
        axis.set_ticks(range(n))
        axis.set_ticks([-0.5, n - 0.5], [f"{t:g}" for t in (-0.5, n - 0.5)], minor=True)
    # The image's edges, half a pixel out, in small grey type on long ticks: their labels sit a row beyond
    # the centres' (below u's, left of v's), centred on their ticks, so "-0.5" never reads as part of "0".
    ax.tick_params(
        which="minor", length=15, width=1, labelsize=8.5, labelcolor="0.35", color="0.35"
    )
    ax.plot(u.ravel(), v.ravel(), ".", color="0.45", ms=3)
    points = np.asarray(points, dtype=float)
    ax.plot(points[:, 0], points[:, 1], "o", color=POINT_COLOUR, ms=7)
    for k, (pu, pv) in enumerate(points):
        ax.annotate(
            f"X[{k}]",
            (pu, pv),
            xytext=(0, 7),
            textcoords="offset points",
            ha="center",
            va="bottom",
            fontsize=9,
            fontweight="bold",
        )
    mu, mv = points[marked]
    ax.add_patch(
        Rectangle(
            (mu - 0.5, mv - 0.5),
            1.0,
            1.0,
            fill=False,
            edgecolor=POINT_COLOUR,
            lw=2.5,
            clip_on=False,
        )
    )
    ax.annotate(
        f"img[{mv:g}, {mu:g}]",
        (mu, mv),
        xytext=(0, -7),
        textcoords="offset points",
        ha="center",
        va="top",
        fontsize=9,
    )
    return image


def draw_point_rows(ax: Axes, points: np.ndarray, notes: Sequence[str]) -> None:
    """The array ``points`` as numpy holds it: one row per point, the columns u and v, each with a note.

    The axes box has the 4:3 shape of :func:`draw_pixel_grid`'s image and :func:`draw_camera_frame`,
    and all three sit at the top of their slots, so the panels' titles line up in one row.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to write in (its axis is turned off).
    points : (N, 2) ndarray
        Points (u, v), pixels, one per row.
    notes : sequence of str
        One note per point, printed at the end of its row (as many as ``points`` has rows).
    """
    points = np.asarray(points, dtype=float)
    ax.set_axis_off()
    ax.set_box_aspect(0.75)
    ax.set_anchor("N")
    ax.set_xlim(0, 1)
    ax.set_ylim(1, 0)
    ax.set_title(f"points are rows:\nX, shape {points.shape}", fontsize=10)
    mono = dict(family="monospace", fontsize=9.5, va="center")
    rows = [
        f"X[{k}]  {pu:4.1f} {pv:4.1f}  {note}"
        for k, ((pu, pv), note) in enumerate(zip(points, notes, strict=True))
    ]
    top, step = 0.12, 0.13
    # The column names over the last digit of each column (characters 9 and 14): spaces keep a monospace text aligned.
    ax.text(0, top, " " * 9 + "u", color=X_COLOUR, fontweight="bold", **mono)
    ax.text(0, top, " " * 14 + "v", color=Y_COLOUR, fontweight="bold", **mono)
    for k, row in enumerate(rows):
        ax.text(0, top + step * (k + 1), row, **mono)
    ax.text(
        0,
        top + step * (len(rows) + 1.5),
        "X[k]     point k, a (2,) row\nX[:, 0]  every u\nX[:, 1]  every v",
        linespacing=1.6,
        **(mono | dict(va="top")),
    )


def draw_camera_frame(ax: Axes, size: tuple[int, int] = (4, 3)) -> None:
    """The camera frame seen from behind the camera: x right, y down, z into the page.

    The image plane (in front of the camera, where the virtual image of lesson 01 forms) is the
    rectangle around the principal axis, divided into the ``size = (W, H)`` pixels of
    :func:`draw_pixel_grid`'s image (faint lines). Its u runs along x and v along y
    from (u, v) = (0, 0), the centre of the top-left pixel, half a pixel in from the plane's corner;
    the image's centre ((W - 1)/2, (H - 1)/2) is on the principal axis.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in (its axis is turned off).
    size : (width, height)
        The pixels dividing the image plane.
    """
    width, height = size
    ax.set_xlim(-1.45, 2.55)
    ax.set_ylim(1.75, -1.25)  # y down; the box is 4:3 like the image beside it
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title("the camera frame,\nseen from behind", fontsize=10)
    ax.set_anchor("N")
    w = 1.0  # half the image plane's width; a pixel is 2 w / W wide and as tall
    pixel = 2 * w / width
    h = pixel * height / 2
    ax.add_patch(Rectangle((-w, -h), 2 * w, 2 * h, facecolor="0.95", edgecolor="0.45", lw=1))
    for k in range(1, width):
        ax.plot([-w + k * pixel] * 2, [-h, h], color="0.62", lw=0.8)
    for k in range(1, height):
        ax.plot([-w, w], [-h + k * pixel] * 2, color="0.62", lw=0.8)
    ax.text(
        0.12, h + 0.06, "image plane", color="0.25", ha="left", va="top", fontsize=9
    )  # right of the y axis
    # (u, v) = (0, 0): the centre of the top-left pixel, half a pixel in from the corner.
    u0, v0 = -w + pixel / 2, -h + pixel / 2
    thin = dict(arrowstyle="-|>", lw=1.5, mutation_scale=12, shrinkA=0, shrinkB=0)
    ax.annotate(
        "", (u0 + pixel, v0), (u0, v0), arrowprops=dict(color=X_COLOUR, **thin)
    )  # one pixel along u ...
    ax.annotate(
        "", (u0, v0 + pixel), (u0, v0), arrowprops=dict(color=Y_COLOUR, **thin)
    )  # ... and along v
    ax.text(
        u0 + pixel + 0.05,
        v0,
        "u",
        color=X_COLOUR,
        ha="left",
        va="center",
        fontsize=10,
        fontweight="bold",
    )
    ax.text(  # right of its arrow, clear of the plane's left edge
        u0 + 0.07,
        v0 + 0.8 * pixel,
        "v",
        color=Y_COLOUR,
        ha="left",
        va="center",
        fontsize=10,
        fontweight="bold",
    )
    ax.plot(u0, v0, "o", color="0.2", ms=5)
    ax.annotate(
        "(0, 0): the top-left pixel's centre,\nhalf a pixel in from the corner",
        (u0, v0),
        xytext=(-w - 0.4, -h - 0.12),
        color="0.2",
        ha="left",
        va="bottom",
        fontsize=9,
        linespacing=1.1,
        arrowprops=dict(arrowstyle="-", color="0.4", lw=0.8, shrinkA=1, shrinkB=3),
    )
    # x and y start at the circled cross's edge (its 16-point circle), so they never cover z's mark
    thick = dict(arrowstyle="-|>", lw=2, mutation_scale=18, shrinkA=9, shrinkB=0)
    ax.annotate("", (1.5, 0), (0, 0), arrowprops=dict(color=X_COLOUR, **thick))
    ax.annotate("", (0, 1.3), (0, 0), arrowprops=dict(color=Y_COLOUR, **thick))
    ax.text(1.55, 0, "x, right", color=X_COLOUR, va="center", fontsize=10)
    ax.text(0, 1.37, "y, down", color=Y_COLOUR, ha="center", va="top", fontsize=10)
    ax.plot(0, 0, "o", ms=16, mfc="white", mec=Z_COLOUR, mew=2, zorder=4)
    ax.plot(0, 0, "x", ms=9, color=Z_COLOUR, mew=2, zorder=5)
    ax.annotate(  # tied to the circled cross by a leader, so it is not read as a caption of the plane's edge
        "z, forward: the principal\naxis, into the page",
        (0, 0),
        xytext=(w + 0.12, 0.2),
        color=Z_COLOUR,
        va="top",
        fontsize=9,
        arrowprops=dict(arrowstyle="-", color=Z_COLOUR, lw=0.8, shrinkA=2, shrinkB=9),
    )


WRONG_COLOUR = (
    palette.PURPLE
)  # the pixel a transposed read returns: no axis's colour, and not the orange of the right one


def draw_transposed_read(
    ax: Axes, photo: np.ndarray, pixel: tuple[int, int], crop_left: int
) -> None:
    """A photo with one pixel read the right way, ``photo[v, u]``, and the wrong way in a square crop.

    The crop is ``photo[:, crop_left:]``, square when ``crop_left = W - H``: the part left of it is
    veiled and its edge drawn as a dark dashed line with a white halo, so it shows on light and dark
    parts of the photo alike. The orange circle is pixel ``(u, v)``; the purple square is what
    ``square[u', v]`` reads with ``u' = u - crop_left``: row ``u'``, column ``v`` of the crop, which is
    pixel ``(crop_left + v, u')`` of the photo. ``imshow`` puts pixel (u, v) at x = u, y = v. The figure
    gets its alt text here (:func:`~camlab.plotting.static.alt_text`), naming these pixels.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in.
    photo : (H, W) ndarray
        A grey uint8 photo, wider than tall (lesson 00 uses ``left01``).
    pixel : (u, v)
        The pixel to read, column and row; it must lie in the crop.
    crop_left : int
        First column of the crop, pixels.
    """
    H, W = photo.shape[:2]
    u, v = pixel
    u_sq = u - crop_left
    ax.imshow(photo, cmap="gray", vmin=0, vmax=255)
    ax.add_patch(
        Rectangle((-0.5, -0.5), crop_left, H, facecolor="white", alpha=0.45, edgecolor="none")
    )
    ax.plot(
        [crop_left - 0.5] * 2,
        [-0.5, H - 0.5],
        color="0.1",
        ls=(0, (6, 4)),
        lw=1.6,
        path_effects=palette.halo(1.6),
    )
    ax.set_xlim(-0.5, W - 0.5)
    ax.set_ylim(H - 0.5, -0.5)
    ring = dict(ms=14, mfc="none", mew=2.8, ls="none", path_effects=palette.halo(0))
    ax.plot(
        u,
        v,
        "o",
        mec=POINT_COLOUR,
        **ring,
        label=f"photo[v, u] = photo[{v}, {u}]: pixel (u, v) = ({u}, {v}), the one we want",
    )
    ax.plot(
        crop_left + v,
        u_sq,
        "s",
        mec=WRONG_COLOUR,
        **ring,
        label=f"square[u, v] = square[{u_sq}, {v}] reads pixel ({crop_left + v}, {u_sq}) of the photo: "
        f"row {u_sq}, not {v}",
    )
    ax.set_title(
        f"left01 ({W} x {H}): the crop photo[:, {crop_left}:] is right of the dashed line",
        fontsize=10,
    )
    ax.set_xlabel("u (px)", color=X_COLOUR)
    ax.set_ylabel("v (px)", color=Y_COLOUR)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.1), fontsize=9, frameon=False)
    alt_text(
        ax.figure,
        f"The grey photo, {W} x {H} pixels, u and v in pixels. The left {crop_left} columns are veiled; a dashed "
        f"line at u = {crop_left - 0.5:g} marks the left edge of the {H} x {W - crop_left} crop photo[:, {crop_left}:]. "
        f"An orange ring marks pixel ({u}, {v}), read as photo[{v}, {u}]; a purple square at ({crop_left + v}, "
        f"{u_sq}) marks the pixel the swapped read square[{u_sq}, {v}] returns: row {u_sq}, not {v}. A key under "
        "the photo names both marks.",
    )


def draw_turn_about(
    ax: Axes, size: tuple[int, int], A: np.ndarray, centre: np.ndarray, title: str
) -> np.ndarray:
    """A ``size = (W, H)`` image's pixel centres moved by ``A`` about ``centre``: x' = c + A (x - c).

    The image's outline and pixel centres stay in grey; the moved outline and centres are drawn in
    black. The top-right pixel (W - 1, 0), the one point the lesson follows, is orange before and
    after, with an orange arrow to where it goes along its true path (for a turn, the arc of the circle about ``centre``), and ``centre``, the
    one point that does not move, is ringed in black. Every artist is labelled, so ``ax.legend()``
    gives the figure its key. The axes are v down, like every image in the course.

    Derivation: a 2 x 2 matrix only moves points about the origin (A 0 = 0). To move them about c,
    shift c to the origin (x - c), apply A there, and shift back (+ c). With points as rows that
    is ``(X - c) @ A.T + c``: the (2,) row c is subtracted from, and added to, every row of X.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in.
    size : (W, H)
        The image's width and height in pixels.
    A : (2, 2) array_like
        The linear map (a turn, a scaling, ...).
    centre : (2,) array_like
        c, the point A turns about, in pixels (u, v).
    title : str
        The axes' title.

    Returns
    -------
    (W * H, 2) ndarray
        The moved pixel centres, row by row of the image (pixel (u, v) is row v * W + u).
    """
    width, height = size
    c = np.asarray(centre, dtype=float)
    v, u = np.mgrid[0:height, 0:width]
    X = np.column_stack([u.ravel(), v.ravel()]).astype(float)  # (W * H, 2), row by row
    corners = np.array(
        [
            [-0.5, -0.5],
            [width - 0.5, -0.5],
            [width - 0.5, height - 0.5],
            [-0.5, height - 0.5],
            [-0.5, -0.5],
        ]
    )
    moved, moved_corners = (X - c) @ A.T + c, (corners - c) @ A.T + c
    ax.plot(*corners.T, color="0.6", lw=1.2, ls="--", zorder=1, label="before (grey)")
    ax.plot(*X.T, "o", color="0.6", ms=4, zorder=2)
    ax.plot(*moved_corners.T, color="black", lw=1.5, zorder=3, label="after: outline")
    ax.plot(*moved.T, "o", color="black", ms=4, zorder=4, label="after: pixel centres")
    k = (
        width - 1
    )  # the top-right pixel, (W - 1, 0): the one point in orange, as in the rest of lesson 00
    ax.plot(*X[k], "o", color=POINT_COLOUR, ms=6, zorder=6, ls="none")
    ax.plot(*moved[k], "o", color=POINT_COLOUR, ms=7, mec="black", mew=0.8, zorder=7, ls="none")
    # Its path: for a turn (A = s R), the true arc about c, c + s^t R(t theta) (x - c) for t in [0, 1];
    # for any other A, the straight segment from x to where it goes.
    scale = np.sqrt(abs(np.linalg.det(A)))
    turn = A / scale if scale > 0 else A
    if scale > 0 and np.allclose(turn.T @ turn, np.eye(2)) and np.linalg.det(turn) > 0:
        theta = np.arctan2(turn[1, 0], turn[0, 0])
        t = np.linspace(0.0, 1.0, 60)[:, None]
        cos, sin = np.cos(t * theta), np.sin(t * theta)
        d = X[k] - c
        path = c + scale**t * np.hstack([cos * d[0] - sin * d[1], sin * d[0] + cos * d[1]])
    else:
        path = np.array([X[k], moved[k]])
    ax.plot(
        *path[:-4].T, color=POINT_COLOUR, lw=1.5, zorder=5, label=f"pixel ({k}, 0) and its path"
    )
    ax.annotate(
        "",
        xy=path[-1],
        xytext=path[-5],
        zorder=5,
        arrowprops={
            "arrowstyle": "-|>",
            "color": POINT_COLOUR,
            "lw": 1.5,
            "shrinkA": 0,
            "shrinkB": 4,
        },
    )
    ax.plot(
        *c,
        "o",
        mfc="none",
        mec="black",
        ms=13,
        mew=1.6,
        zorder=6,
        ls="none",
        label="the fixed point the image turns about",
    )  # a ring: the dot inside stays visible
    ax.set_aspect("equal")
    ax.invert_yaxis()  # v points down
    ax.set_title(title, fontsize=10)
    ax.set_xlabel("u (px)", color=X_COLOUR)
    ax.set_ylabel("v (px)", color=Y_COLOUR)
    ax.grid(True, color="0.9", lw=0.6, zorder=0)
    return moved


def draw_channel_order(axes: Sequence[Axes], bgr: np.ndarray, pixel: tuple[int, int]) -> None:
    """A colour photo as ``cv2.imread`` returns it, shown as it is (left) and flipped to R, G, B (right).

    ``cv2.imread`` stores each pixel's channels as B, G, R; matplotlib's ``imshow`` reads the three
    numbers as R, G, B, so the unflipped picture swaps red and blue: a red-orange spot turns blue.
    ``bgr[..., ::-1]`` reverses the last axis and gives the true colours. A white box marks the 31 x 31
    pixels about ``(u, v)``, and an inset in the top-right corner shows them enlarged, the pixel itself
    outlined by a thin square, so the spot's colour is seen, not covered by a marker. The figure gets
    its alt text here.

    Parameters
    ----------
    axes : two matplotlib.axes.Axes
        Left: the photo as read; right: the photo flipped to R, G, B.
    bgr : (H, W, 3) ndarray
        A uint8 colour photo in ``cv2.imread``'s B, G, R order.
    pixel : (u, v)
        The pixel to ring, column and row.
    """
    u, v = pixel
    titles = (
        "cv2.imread shown as it is:\nB, G, R read as R, G, B",
        "flipped to R, G, B:\nimg[..., ::-1]",
    )
    for ax, image, title in zip(axes, (bgr, bgr[..., ::-1]), titles, strict=True):
        ax.imshow(image)
        half = 15  # the zoomed crop: 31 x 31 pixels about (u, v)
        box = dict(fill=False, lw=1.2)
        ax.add_patch(
            Rectangle(
                (u - half - 0.5, v - half - 0.5), 2 * half + 1, 2 * half + 1, ec="white", **box
            )
        )
        zoom = ax.inset_axes((0.71, 0.6, 0.29, 0.4))
        zoom.imshow(image)
        zoom.set_xlim(u - half - 0.5, u + half + 0.5)
        zoom.set_ylim(v + half + 0.5, v - half - 0.5)
        zoom.add_patch(Rectangle((u - 0.5, v - 0.5), 1, 1, ec="white", **box))  # the pixel itself
        zoom.set_xticks([])
        zoom.set_yticks([])
        for spine in zoom.spines.values():
            spine.set_edgecolor("white")
            spine.set_linewidth(1.5)
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("u (px)", color=X_COLOUR)
        ax.set_ylabel("v (px)", color=Y_COLOUR)
    H, W = bgr.shape[:2]
    alt_text(
        axes[0].figure,
        f"Two panels of the same colour photo, {W} x {H} pixels, u and v in pixels. Left: cv2.imread's array "
        "shown as it is, red and blue swapped (a red-orange eyespot turns blue, yellow-green leaves turquoise). "
        f"Right: the array flipped to R, G, B, with the true colours. In both, a white box marks the 31 x 31 "
        f"pixels about pixel ({u}, {v}), on the eyespot, and an inset in the top-right corner shows them "
        "enlarged, the pixel outlined by a thin white square: blue on the left, red-orange on the right.",
    )


def _mark_multiples(ax: Axes, marks: np.ndarray) -> None:
    """Each (wx, wy, w) of ``marks`` (w = 1 included): a dot (but at w = 1), its drop line to w = 0, its label.

    Marks below the plane w = 1 are drawn first (zorder 0) and faded, so the plane's fill covers them.
    """
    for wx, wy, w in marks:
        below = w < 1
        ax.plot(
            [wx, wx],
            [wy, wy],
            [0, w],
            color="0.2",
            lw=1.0,
            ls=(0, (2, 2)),
            zorder=0 if below else 3,
        )
        if w != 1.0:
            ax.plot(
                [wx],
                [wy],
                [w],
                "o",
                color="black",
                ms=5,
                alpha=0.6 if below else 1.0,
                zorder=0 if below else 6,
            )
        left = (
            w != 1
        )  # above w = 1 on the left, clear of the w axis's ticks; below it too, off the w = 0 edge
        ax.text(
            wx + (-0.12 if left else 0.12),
            wy,
            w + 0.15 * below,  # a little up: clear of the w = 0 plane's back edge behind it
            f"w = {w:g}  " if left else f"  w = {w:g}",
            ha="right" if left else "left",
            fontsize=9,
            zorder=0 if below else 8,
            alpha=0.75 if below else 1.0,
            path_effects=palette.halo(2),
        )


def draw_homogeneous_rays(
    ax: Axes, point: np.ndarray, scales: Sequence[float], direction: np.ndarray
) -> np.ndarray:
    """Homogeneous coordinates as rays through the origin (the model of H&Z Fig. 2.1), on 3-D axes.

    The point (x, y) is the ray through the origin and (x, y, 1), which crosses the plane w = 1
    (grey) at the point itself (orange). Its multiples (wx, wy, w), one per ``scales`` entry (black
    dots, each labelled with its w and dropped to w = 0 by a dotted line, so its height reads), lie
    on the same ray (dashed below the plane w = 1, solid above; what lies below is drawn under the
    plane's fill and faded, so it reads as below), and dividing by w slides each back
    to (x, y, 1). A vector (dx, dy, 0) (dark grey arrow) lies in the plane w = 0 (dashed outline): its
    ray runs parallel to the plane w = 1 and never meets it, so it names a direction, an ideal
    point, not a point of the image. The figure gets its alt text here, naming these coordinates.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        3-D axes to draw in.
    point : (2,) array_like
        (x, y), the point on the plane w = 1.
    scales : sequence of float
        The w of each multiple drawn, nonzero.
    direction : (2,) array_like
        (dx, dy), drawn as the ideal point (dx, dy, 0).

    Returns
    -------
    (len(scales), 3) ndarray
        The multiples (wx, wy, w) drawn, one per row.

    References
    ----------
    R. Hartley and A. Zisserman, *Multiple View Geometry in Computer Vision*, 2nd ed., Cambridge
    University Press, 2004: Fig. 2.1, a model for the projective plane.
    """
    x, y = np.asarray(point, dtype=float)
    dx, dy = np.asarray(direction, dtype=float)
    multiples = np.array([[w * x, w * y, w] for w in scales])
    top = max(max(scales), 1.0) * 1.15
    square = np.array([[-1, -1], [2.5, -1], [2.5, 2], [-1, 2], [-1, -1]], dtype=float)
    ax.computed_zorder = False  # draw in the order given: the marks over the translucent plane
    ax.plot_surface(
        np.array([[-1, 2.5], [-1, 2.5]]),
        np.array([[-1, -1], [2, 2]]),
        np.ones((2, 2)),
        color="0.75",
        alpha=0.3,
        shade=False,
        zorder=1,
    )
    ax.plot(*square.T, np.ones(5), color="0.45", lw=1, label="the plane w = 1: the image", zorder=2)
    ax.plot(*square.T, np.zeros(5), color="0.2", lw=1.4, ls="--", label="the plane w = 0", zorder=2)
    # What lies below the plane w = 1 is drawn first (zorder 0) and faded, so its fill covers it: below, not on.
    ax.plot([0, x], [0, y], [0, 1], color=POINT_COLOUR, lw=1.4, ls=(0, (3, 2)), alpha=0.7, zorder=0)
    ax.plot(
        [x, top * x],
        [y, top * y],
        [1, top],
        color=POINT_COLOUR,
        lw=2,
        label="the ray of (x, y)",
        zorder=5,
    )
    _mark_multiples(ax, np.vstack([multiples, [x, y, 1.0]]))
    ax.plot([], [], "o", color="black", ms=5, ls="none", label="(wx, wy, w) on the ray")
    ax.plot(
        [x],
        [y],
        [1.0],
        "o",
        color=POINT_COLOUR,
        ms=8,
        mec="black",
        mew=0.8,
        ls="none",
        label="(x, y, 1): divided by w",
        zorder=7,
    )
    ax.quiver(0, 0, 0, dx, dy, 0, color=DIRECTION_COLOUR, lw=2.2, arrow_length_ratio=0.15, zorder=4)
    ax.plot([], [], color=DIRECTION_COLOUR, lw=2.2, label="(dx, dy, 0): w = 0, a direction")
    ax.plot([0], [0], [0], "k+", ms=9, ls="none", label="the origin (0, 0, 0)", zorder=8)
    ax.set_xticks([-1, 0, 1, 2, 3])
    ax.set_yticks([-1, 0, 1, 2])
    ax.set_zticks([0, 1, 2])
    ax.set_xlabel("x", color=X_COLOUR)
    ax.set_ylabel("y", color=Y_COLOUR)
    ax.set_zlabel("w", color=Z_COLOUR, labelpad=-3)
    ax.view_init(elev=22, azim=-58)
    ax.set_box_aspect(None, zoom=1.2)  # fill the figure: mplot3d leaves a wide margin
    marks = " and ".join(f"({wx:g}, {wy:g}, {w:g}), labelled w = {w:g}" for wx, wy, w in multiples)
    alt_text(
        ax.figure,
        "A 3-D sketch with axes x, y and w. A grey square is the plane w = 1, the image; a dashed square below "
        "it is the plane w = 0 through the origin. An orange ray from the origin, dashed below the plane and "
        f"solid above, pierces the plane w = 1 at the orange dot ({x:g}, {y:g}, 1), labelled w = 1; black dots "
        f"on the same ray mark {marks} (those below the plane faded, seen through it); a dashed line drops from each dot to the plane w = 0. A dark grey "
        f"arrow from the origin lies in the plane w = 0: the direction ({dx:g}, {dy:g}, 0), whose ray never "
        "meets the plane w = 1.",
    )
    return multiples


def describe_pixel_panels(fig: Figure) -> None:
    """Give lesson 00's figure of section 3.1 its alt text: the pixel grid, the rows of X, the camera frame.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure drawn by :func:`draw_pixel_grid`, :func:`draw_point_rows` and :func:`draw_camera_frame`.
    """
    alt_text(
        fig,
        "Three panels. Left: a 4 x 3 checkerboard image with pixel centres at whole numbers, u from -0.5 to 3.5 "
        "and v from -0.5 to 2.5 at the edges; orange dots X[0] at (0, 0), X[2] at the centre (1.5, 1) and X[1] at "
        "(3, 1), whose pixel is outlined and labelled img[1, 3]. Middle: the array X, one row (u, v) per point. "
        "Right: the camera frame seen from behind: x right (red), y down (green), z into the page (blue, a circled "
        "cross at the principal axis); the image plane divided into the same 4 x 3 pixels, with u (red) and v "
        "(green) running along x and y from (0, 0), the top-left pixel's centre, half a pixel in from the plane's "
        "corner.",
    )


def describe_rotation_about(fig: Figure) -> None:
    """Give lesson 00's figure of section 3.3 its alt text: a quarter rotation about the origin and about the centre.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure of two :func:`draw_turn_about` panels, about (0, 0) and about (1.5, 1).
    """
    alt_text(
        fig,
        "Two panels, v down. Grey: the outline and 12 pixel centres of a 4 x 3 image. Black: the same rotated a "
        "quarter turn clockwise by R(90 degrees); orange: the top-right pixel (3, 0) before and after. Left, about "
        "the origin (0, 0), ringed at the top-left pixel: the image swings out to negative u, and an orange arc "
        "about the origin takes the top-right pixel (3, 0) to (0, 3). Right, about the centre (1.5, 1), ringed: "
        "the image rotates in place, 3 wide and 4 tall, and an arc about the centre takes (3, 0) to (2.5, 2.5). "
        "A key under the panels names each mark.",
    )


def draw_uint8_wrap(axes: Sequence[Axes], wrapped: np.ndarray, clipped: np.ndarray) -> None:
    """A grey photo brightened by 60 in uint8 (left: the white wraps round to dark) and in float, clipped (right).

    Parameters
    ----------
    axes : two matplotlib.axes.Axes
        Left: ``wrapped``; right: ``clipped``.
    wrapped : (H, W) ndarray
        ``photo + 60`` in uint8.
    clipped : (H, W) ndarray
        ``np.clip(photo.astype(float) + 60, 0, 255)``.
    """
    titles = (
        "photo + 60 in uint8: the white wraps round to dark",
        "np.clip(photo.astype(float) + 60, 0, 255)",
    )
    for ax, image, title in zip(axes, (wrapped, clipped), titles, strict=True):
        ax.imshow(image, cmap="gray", vmin=0, vmax=255)
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("u (px)", color=X_COLOUR)
        ax.set_ylabel("v (px)", color=Y_COLOUR)
    H, W = wrapped.shape[:2]
    alt_text(
        axes[0].figure,
        f"Two panels of the grey chessboard photo, {W} x {H} pixels, brightened by 60. Left, in uint8: the white "
        "squares and other bright parts wrap round to dark grey. Right, in float and clipped at 255: the photo "
        "brighter, with everything above 195 clipped to white.",
    )
