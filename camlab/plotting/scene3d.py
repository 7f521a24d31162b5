"""3-D views of cameras and scenes: frustums, camera and world axes, image planes.

Used by lessons 04-05 and later by calibration and stereo. The cameras and scene views are
here; the 3-D axes (:mod:`.view3d`) and the wireframe primitives (:mod:`.wireframes`) are
re-exported, so ``scene3d.<name>`` reaches them all. Everything here draws once
and returns handles whose ``update`` methods MOVE the existing artists
(``Line3D.set_data_3d``, ``Poly3DCollection.set_verts``, ``Text3D.set_position_3d``),
so a slider callback stays within the latency budget.

Conventions (docs/conventions.md): a camera is drawn in the OpenCV frame, its axes
labelled x (right, red), y (down, green), z (forward, blue); its image plane is drawn in
front of the centre at depth ``size`` metres (the *positive*, non-inverted image: the
real sensor sits behind the pinhole, upside down), pixel (0, 0) at the top-left corner of
the plane. World axes are X, Y, Z in the same colours. 3-D axes get equal aspect.

Blitting (``FigureView.animate``): a 3-D axes' projection depends on its limits, so in a
demo register *every* artist of the 3-D axes as animated (``SceneView.artists()``,
``CameraArtist.artists()``) and keep the 3-D axes' own decorations off; ``SceneView.update``
and :func:`refresh_projection` recompute the projection so blitted artists land right.

Typical use::

    from camlab.plotting import scene3d
    ax = scene3d.axes3d(fig, 121)
    scene3d.draw_world_axes(ax)
    segs = scene3d.draw_segments(ax, house)             # world wireframe
    cam_art = scene3d.CameraArtist(ax, camera, size=0.6, image_lines=camera_pixels)
    scene3d.set_equal_aspect(ax, [house.reshape(-1, 3), camera.centre])
    ...
    cam_art.update(new_camera, image_lines=new_pixels)    # in a slider callback
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ..camera import Camera, project_segments
from . import palette
from .view3d import align_away, axes3d, fit_view, refresh_projection, set_equal_aspect
from .wireframes import (
    axis_artists,
    clip_segments,
    draw_points,
    draw_segments,
    draw_world_axes,
    image_axes,
    polyline_data,
    update_segments,
)

AXIS_COLOURS = (
    palette.AXIS_COLOURS
)  # x red, y green, z blue: defined once, in palette (docs/conventions.md)

__all__ = [
    "AXIS_COLOURS",
    "CameraArtist",
    "SceneView",
    "align_away",
    "axes3d",
    "clip_segments",
    "draw_points",
    "draw_segments",
    "draw_world_axes",
    "fit_view",
    "image_axes",
    "polyline_data",
    "refresh_projection",
    "set_equal_aspect",
    "update_segments",
]


def _plane_points(camera: Camera, uv: np.ndarray, size: float) -> np.ndarray:
    """Pixels (N, 2) lifted to the plane z_c = size in front of the camera, world coordinates.

    NaN pixels stay NaN (segments that leave the picture break there).
    """
    ones = np.ones((len(uv), 1))
    rays_c = np.linalg.solve(camera.K, np.hstack([uv, ones]).T).T  # z = 1 in camera frame
    return (rays_c * size - camera.t) @ camera.R


class CameraArtist:
    """A camera drawn in a 3-D axes: frustum, image plane, camera axes and optional image.

    Parameters
    ----------
    ax : Axes3D
        The 3-D axes to draw in.
    camera : Camera
        The camera to draw (its pose, intrinsics and image size).
    size : float
        Depth of the drawn image plane in metres (the frustum's length).
    color : str
        Frustum colour.
    label : str
        Text at the camera centre (e.g. "C" or "left").
    label_offset : (float, float) or (float, float, float)
        Where the label sits, in image-plane depths along the camera's x (right) and y (down)
        axes from the centre: up-left by default; give two cameras drawn close together
        different offsets so their labels do not overprint. A third entry moves it along the
        camera's z (negative: behind the centre, where no frustum is drawn).
    image : (H, W) or (H, W, 3) array, optional
        A raster image drawn on the image plane as a coarse textured mesh of
        ``image_grid`` quads (block means), fast enough for sliders.
    image_lines : (M, 2, 2) array, optional
        Pixel segments (e.g. the projected wireframe) drawn on the image plane.
    show_axes : bool
        Draw the camera's x (right), y (down), z (forward) axes, labelled.
    axis_length : float, optional
        Length of those axes in metres (default: 0.6 ``size``).
    image_grid : (int, int)
        Quads of the image mesh across and down.
    line_color : str
        Colour of ``image_lines``.
    """

    def __init__(
        self,
        ax,
        camera: Camera,
        size: float = 0.5,
        color: str = palette.PURPLE,
        label: str = "",
        image: np.ndarray | None = None,
        image_lines: ArrayLike | None = None,
        show_axes: bool = True,
        image_grid: tuple[int, int] = (24, 18),
        line_color: str = "0.15",
        label_offset: tuple[float, float] = (-0.15, -0.25),
        axis_length: float | None = None,
    ):
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection

        self.ax, self.size, self.image_grid = ax, float(size), image_grid
        self.axis_length = axis_length
        self.camera, self.label_offset = camera, label_offset
        (self.frustum,) = ax.plot([], [], [], color=color, lw=1.2, path_effects=palette.halo(1.2))
        self.plane = Poly3DCollection(
            [np.zeros((4, 3))], facecolor=color, alpha=0.12, edgecolor=color, lw=1.0
        )
        ax.add_collection3d(self.plane)
        self.axes_lines, self.axes_text = [], []
        if show_axes:
            for c, name in zip(palette.AXIS_COLOURS, ("x", "y", "z"), strict=True):
                ln, text = axis_artists(ax, c, name)
                self.axes_lines.append(ln)
                self.axes_text.append(text)
        (self.centre_marker,) = ax.plot([], [], [], "o", color=color, ms=4)
        self.label = ax.text(0, 0, 0, label, color=color, fontsize=9) if label else None
        (self.lines,) = ax.plot(
            [], [], [], color=line_color, lw=1.3, gid="thumbnail"
        )  # the image panel, in small
        self.mesh, self._pixels = None, None
        if image is not None:
            self.mesh = Poly3DCollection([np.zeros((4, 3))], lw=0.0)
            ax.add_collection3d(self.mesh)
        self.update(camera, image=image, image_lines=image_lines)

    def artists(self) -> list:
        """Every artist this camera drew (register them with ``FigureView.animate``).

        Returns
        -------
        list of matplotlib.artist.Artist
            Frustum, image plane, camera axes and their labels, centre marker, image lines, and the
            label and image mesh when drawn.
        """
        out = [
            self.frustum,
            self.plane,
            *self.axes_lines,
            *self.axes_text,
            self.centre_marker,
            self.lines,
        ]
        return out + [a for a in (self.label, self.mesh) if a is not None]

    def corners(self, camera: Camera | None = None) -> np.ndarray:
        """The image plane's four corners (top-left, top-right, bottom-right, bottom-left), world (4, 3).

        Parameters
        ----------
        camera : Camera or None
            The camera; None for the one last drawn.

        Returns
        -------
        (4, 3) ndarray
            The corners' outer pixel edges lifted to depth ``size`` in front of the camera, metres.
        """
        cam = camera or self.camera
        w, h = cam.image_size
        uv = np.array([[-0.5, -0.5], [w - 0.5, -0.5], [w - 0.5, h - 0.5], [-0.5, h - 0.5]])
        return _plane_points(cam, uv, self.size)

    def _axis_tips(self, camera: Camera) -> np.ndarray:
        """Where the camera's axis labels sit (3, 3): 1.2 axis lengths from the centre along x, y, z."""
        L = self.axis_length if self.axis_length is not None else self.size * 0.6
        return camera.centre + 1.2 * L * camera.R

    def extent_points(self, camera: Camera | None = None) -> np.ndarray:
        """Points to include when setting equal-aspect limits: centre, plane corners and axis labels.

        Parameters
        ----------
        camera : Camera or None
            The camera; None for the one last drawn.

        Returns
        -------
        (N, 3) ndarray
            World points, metres: the centre, the four corners, the axis labels' positions (when the
            axes are drawn) and the label's (when there is one).
        """
        cam = camera or self.camera
        tips = [self._axis_tips(cam)] if self.axes_text else []
        if self.label is not None:
            tips.append(self._label_position(cam))
        return np.vstack([cam.centre, self.corners(cam), *tips])

    def _label_position(self, camera: Camera) -> np.ndarray:
        # in image-plane depths, at least 0.5 m: a tiny frustum's label clears it; an optional third
        # entry moves it along the optical axis (negative: behind the centre, off the frustum on screen)
        right, down, forward = (*self.label_offset, 0.0)[:3]
        offset = right * camera.R[0] + down * camera.R[1] + forward * camera.R[2]
        return camera.centre + max(self.size, 0.5) * offset

    def update(
        self, camera: Camera, image: np.ndarray | None = None, image_lines: ArrayLike | None = None
    ) -> None:
        """Move every artist to ``camera``; redraw the image content if given.

        Parameters
        ----------
        camera : Camera
            The camera's new intrinsics, pose and image size.
        image : (H, W) or (H, W, 3) ndarray or None
            A new image for the mesh (uint8 or float in [0, 1]); None keeps the old colours.
        image_lines : (M, 2, 2) array_like or None
            New pixel segments for the image plane (clipped to the image); None moves the old ones
            with the camera.
        """
        self.camera = camera
        C = camera.centre
        corners = self.corners(camera)
        f = np.full((4 * 3 + 5, 3), np.nan)
        for i, k in enumerate(corners):  # centre-to-corner rays, NaN-separated
            f[3 * i], f[3 * i + 1] = C, k
        f[12:17] = np.vstack([corners, corners[:1]])
        self.frustum.set_data_3d(f[:, 0], f[:, 1], f[:, 2])
        self.plane.set_verts([corners])
        if (
            getattr(self.ax, "M", None) is not None
        ):  # blitting draws polygons from their last projection
            self.plane.do_3d_projection()
        tips = self._axis_tips(camera)
        for i, (ln, tx) in enumerate(zip(self.axes_lines, self.axes_text, strict=True)):
            e = C + (tips[i] - C) / 1.2  # camera axis i in world coordinates is row i of R
            ln.set_data_3d([C[0], e[0]], [C[1], e[1]], [C[2], e[2]])
            tx.set_position_3d(tips[i])
        self.centre_marker.set_data_3d([C[0]], [C[1]], [C[2]])
        if self.label is not None:
            self.label.set_position_3d(self._label_position(camera))
        if image_lines is not None:  # only what the camera sees is drawn on its image plane
            self._pixels = clip_segments(image_lines, camera.image_size)
        if self._pixels is not None:  # without new pixels, the old ones move with the camera
            d = polyline_data(self._pixels) if len(self._pixels) else np.empty((0, 2))
            P3 = _plane_points(camera, d, self.size) if len(d) else np.empty((0, 3))
            self.lines.set_data_3d(P3[:, 0], P3[:, 1], P3[:, 2])
        if self.mesh is not None:
            self._update_mesh(camera, image)

    def _update_mesh(self, camera: Camera, image: np.ndarray | None) -> None:
        gw, gh = self.image_grid
        w, h = camera.image_size
        us = np.linspace(-0.5, w - 0.5, gw + 1)
        vs = np.linspace(-0.5, h - 0.5, gh + 1)
        U, V = np.meshgrid(us, vs)
        G = _plane_points(camera, np.column_stack([U.ravel(), V.ravel()]), self.size).reshape(
            gh + 1, gw + 1, 3
        )
        quads = np.stack([G[:-1, :-1], G[:-1, 1:], G[1:, 1:], G[1:, :-1]], axis=2).reshape(-1, 4, 3)
        if image is not None:
            img = np.asarray(image, dtype=float)
            if img.max() > 1.0:
                img = img / 255.0
            if img.ndim == 2:
                img = np.repeat(img[..., None], 3, axis=2)
            # Block means over the grid cells (area interpolation), one colour per quad.
            import cv2

            colours = cv2.resize(
                img[..., :3].astype(np.float32), (gw, gh), interpolation=cv2.INTER_AREA
            )
            colours = colours.reshape(-1, 3).astype(float)
            self.mesh_colours = np.clip(
                colours, 0.0, 1.0
            )  # row-major over the grid, top-left first
            self.mesh.set_facecolor(self.mesh_colours)
        self.mesh.set_verts(quads)
        if getattr(self.ax, "M", None) is not None:
            self.mesh.do_3d_projection()


class SceneView:
    """A wireframe scene photographed by one camera: a 3-D view beside the camera's image.

    ``SceneView(fig, camera, segments)`` adds two axes to ``fig`` (3-D on the left, the
    image on the right), draws the world wireframe, world axes and the camera (with the
    projected wireframe on its image plane), and ``update(camera)`` moves everything.
    The 3-D limits fit the scene, the camera and ``extent`` (more world points to keep in view)
    with :func:`fit_view`, at construction and after every update, so nothing leaves the view;
    :meth:`fit` refits them to include more points (a second camera).
    ``thumbnail``: the segments drawn small on the image plane (default: all); pick the main
    object, as a whole scene is a tangle at that size.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure the two axes are added to (unless ``axes`` gives them).
    camera : Camera
        The camera photographing the scene.
    segments : (M, 2, 3) array_like
        The world wireframe, metres.
    extent : (N, 3) array_like or None
        More world points to keep in view (m).
    axes : (Axes3D, Axes) or None
        Existing 3-D and image axes to draw in; None adds them side by side.
    plane_size : float
        Depth of the camera's drawn image plane, metres (:class:`CameraArtist`'s ``size``).
    world_axes : float
        Length of the world axes, metres; 0 draws none.
    image_title : str
        The image panel's title.
    elev, azim : float
        The 3-D viewpoint, degrees.
    axis_off : bool
        Hide the 3-D panes, ticks and labels (the world axes carry the frame; 5x faster).
    thumbnail : (K, 2, 3) array_like or None
        The segments drawn small on the image plane; None: all of ``segments``.
    camera_axes : bool
        Draw the camera's x, y, z axes.
    camera_axis_length : float or None
        Their length, metres (None: 0.6 ``plane_size``).
    width_ratios : (float, float)
        Widths of the 3-D and image panels, when this adds them.
    """

    def __init__(
        self,
        fig,
        camera: Camera,
        segments: ArrayLike,
        extent: ArrayLike | None = None,
        axes: tuple | None = None,
        plane_size: float = 0.8,
        world_axes: float = 0.8,
        image_title: str = "camera image",
        elev: float = 24.0,
        azim: float = 15.0,
        axis_off: bool = True,
        thumbnail: ArrayLike | None = None,
        camera_axes: bool = True,
        camera_axis_length: float | None = None,
        width_ratios: tuple[float, float] = (1.15, 1.0),
    ):
        self.segments = np.asarray(segments, dtype=float)
        # what the small picture on the image plane shows: a whole scene is a tangle at that size
        self.thumbnail = self.segments if thumbnail is None else np.asarray(thumbnail, dtype=float)
        if axes is None:
            gs = fig.add_gridspec(1, 2, width_ratios=width_ratios)
            ax3 = axes3d(fig, gs[0, 0], elev=elev, azim=azim)
            ax2 = fig.add_subplot(gs[0, 1])
        else:
            ax3, ax2 = axes
        self.ax3d, self.ax_image = ax3, ax2
        if axis_off:  # no panes, ticks or tick labels: the world axes carry the frame; 5x faster
            ax3.set_axis_off()
        # Created in the order artists() lists them, so a full draw and a live frame stack them alike
        # (the world axes over the ground grid in both).
        self.world = draw_segments(ax3, self.segments)
        self.world_axes = draw_world_axes(ax3, world_axes) if world_axes else []
        pix = project_segments(camera, self.segments)
        self.camera_artist = CameraArtist(
            ax3,
            camera,
            size=plane_size,
            image_lines=self._thumbnail_pixels(camera, pix),
            label="C",
            show_axes=camera_axes,
            axis_length=camera_axis_length,
        )
        self.extent = (
            None if extent is None else np.reshape(np.asarray(extent, dtype=float), (-1, 3))
        )
        self.axis_off = axis_off
        self.fit()
        image_axes(ax2, camera.image_size, image_title, labels=not axis_off)
        d = polyline_data(pix)
        (self.image_lines,) = ax2.plot(d[:, 0], d[:, 1], color="k", lw=1.2)
        self.camera = camera

    def _thumbnail_pixels(self, camera: Camera, pix: np.ndarray) -> np.ndarray:
        return pix if self.thumbnail is self.segments else project_segments(camera, self.thumbnail)

    def fit(self, camera: Camera | None = None, extra: ArrayLike | None = None) -> None:
        """Refit the 3-D limits to the scene, the camera (default: the current one), ``extent`` and ``extra``.

        Parameters
        ----------
        camera : Camera or None
            The camera to keep in view; None for the one last drawn.
        extra : (N, 3) array_like or None
            More world points to keep in view (m), e.g. a second camera's.
        """
        pts = [self.segments.reshape(-1, 3), self.camera_artist.extent_points(camera)]
        pts += [
            np.reshape(np.asarray(p, dtype=float), (-1, 3))
            for p in (self.extent, extra)
            if p is not None
        ]
        if self.world_axes:
            pts.append(
                1.15 * np.eye(3) * max(np.linalg.norm(self.world_axes[0].get_data_3d(), axis=0))
            )
        if self.axis_off:
            fit_view(
                self.ax3d, pts, fill=0.85
            )  # a margin for the labels, which extend beyond their anchors
        else:  # with panes and ticks, the labels need the margin a fitted view would take
            set_equal_aspect(self.ax3d, pts)
            refresh_projection(self.ax3d)

    def artists(self) -> list:
        """The artists that move: everything in the 3-D axes and the image's lines.

        The 3-D axes' projection follows the camera, so all of it moves. Register them with
        ``FigureView.animate``.

        Returns
        -------
        list of matplotlib.artist.Artist
            The wireframe, world axes, the camera's artists and the image's polyline.
        """
        return [self.world, *self.world_axes, *self.camera_artist.artists(), self.image_lines]

    def update(self, camera: Camera) -> np.ndarray:
        """Re-photograph the scene with ``camera``; returns the (M, 2, 2) pixel segments.

        The 3-D limits follow the camera so it never leaves the view.

        Parameters
        ----------
        camera : Camera
            The new camera.

        Returns
        -------
        (M, 2, 2) ndarray
            The scene's segments projected by ``camera``, pixels (:func:`camlab.camera.project_segments`).
        """
        pix = project_segments(camera, self.segments)
        self.fit(camera)
        self.camera_artist.update(camera, image_lines=self._thumbnail_pixels(camera, pix))
        update_segments(self.image_lines, pix)
        w, h = camera.image_size
        if (w, h) != tuple(self.camera.image_size):
            image_axes(self.ax_image, (w, h), labels=False)
        self.camera = camera
        return pix
