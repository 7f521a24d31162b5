r"""The panorama data of lesson 09, rendered by the virtual camera with full ground truth.

``python -m camlab.data`` writes ``data/panorama/`` (with the other data sets) (deterministic: the same
bytes on every run with the same library versions):

``rot_00.jpg`` ... ``rot_03.jpg``
    A camera turning about its centre (yaw -27, -9, 9, 27 degrees, a little pitch and roll)
    in a room: a wide textured back wall 6 m away (16 m wide), a photograph, a text page and a box
    closer by. 640 x 480 RGB, fx = 800; each view has its own exposure gain and sensor
    noise, and is stored as a quality-95 JPEG like a camera's (a noisy PNG is 5x larger,
    and ``data/`` must stay small). Because the centre does not move, view i maps to view j by the homography
    :math:`H_{ji} = K R_j R_i^T K^{-1}` whatever the depth (lesson 09, section 1).
``plane_0.jpg``, ``plane_1.jpg``
    A flat poster photographed from two different positions: related by the plane-induced
    homography :math:`K (R - t n^T / d) K^{-1}`.
``truth.json``
    The generator's parameters, K, every view's pose (cam_from_world ``R``, ``t``), gains,
    and the true homographies.

:func:`room_scene` also feeds the ghosting demonstration (a camera that translates in
front of the 3-D room) and the direct render of the panorama view used to measure the
stitch. Load everything with :func:`load_panorama_set`.
"""

from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, check_positive, check_size
from ..camera import scale_intrinsics
from ..scenes import wall_texture
from ._resources import encode_image, read_truth

__all__ = [
    "PANORAMA_PARAMS",
    "TURNING_SETS",
    "PanoramaSet",
    "PlanarPair",
    "TurningSet",
    "environment_map",
    "environment_view",
    "load_aerial_mosaic",
    "load_panorama_set",
    "load_planar_pair",
    "make_panorama_set",
    "render_view",
    "room_scene",
    "scale_intrinsics",
    "turning_set",
    "wall_texture",
]

PANORAMA_PARAMS = {
    "seed": 909,
    "image_size": [640, 480],
    "K": [[800.0, 0.0, 319.5], [0.0, 800.0, 239.5], [0.0, 0.0, 1.0]],
    # (yaw, pitch, roll) in degrees of each view of the rotation set
    "angles_deg": [[-27.0, 1.5, 0.5], [-9.0, -1.0, -0.8], [9.0, 0.5, 1.0], [27.0, -1.5, -0.5]],
    "gains": [1.0, 0.86, 1.12, 0.93],
    "full_well": 20000.0,
    "read_noise": 3.0,
    "supersample": 2,
    "jpeg_quality": 95,
    "wall_texture_px": [2100, 800],
    "plane_pair": {"t1": [0.25, -0.05, 0.0], "angles1_deg": [-6.0, 4.0, 2.0]},
}


def _rot(yaw: float, pitch: float, roll: float) -> np.ndarray:
    """world_from_cam for a camera turned by ``yaw`` about y, ``pitch`` about x, ``roll`` about z (radians).

    Its transpose is :func:`cam_from_world`.
    """
    from ..render import rotation_from_euler

    # world_from_cam = Ry(yaw) Rx(pitch) Rz(roll); cam_from_world is its transpose
    return (
        rotation_from_euler(0, yaw, 0)
        @ rotation_from_euler(pitch, 0, 0)
        @ rotation_from_euler(0, 0, roll)
    )


def cam_from_world(yaw: float, pitch: float = 0.0, roll: float = 0.0) -> np.ndarray:
    """The rotation cam_from_world of a camera at the origin turned by (yaw, pitch, roll) radians."""
    return _rot(yaw, pitch, roll).T


def room_scene(params: dict = PANORAMA_PARAMS) -> list:
    """The 3-D scene of the panorama set: a wide back wall 6 m away and three nearer objects.

    World frame = the camera frame of a camera at the origin with yaw = pitch = roll = 0
    (x right, y down, z forward, metres). The nearer planes (a photograph at 2.6 m, a text
    page at 1.7 m, a box at 3.4 m) sit at other depths than the wall, so a camera that
    translates sees them move against it (parallax, the ghosting demonstration).
    """
    from .. import render

    tex = wall_texture(params["wall_texture_px"], params["seed"])
    wall = render.textured_plane(tex, 16.0, t=(0.0, 0.0, 6.0), name="wall")
    photo = render.photo_plane(
        0.9, R=render.rotation_from_euler(0, np.radians(-15), 0), t=(-0.55, 0.05, 2.6)
    )
    page = render.text_page(
        0.42,
        R=render.rotation_from_euler(0, np.radians(20), 0),
        t=(0.75, 0.1, 1.7),
        seed=params["seed"],
    )
    cube = render.box(
        (-1.9, -0.2, 3.6), (0.6, 0.6, 0.6), R=render.rotation_from_euler(0, np.radians(30), 0)
    )
    return [wall, photo, page, cube]


def render_view(
    R: np.ndarray,
    *,
    t=(0.0, 0.0, 0.0),
    K=None,
    size=None,
    gain: float = 1.0,
    noise: bool = True,
    rng=None,
    params: dict = PANORAMA_PARAMS,
    scene=None,
) -> np.ndarray:
    """Render the room (:func:`room_scene`) from pose ``(R, t)`` (cam_from_world) as a uint8 RGB image.

    ``gain`` scales the irradiance (exposure); ``noise`` adds shot and read noise
    (``params``). ``K``/``size`` default to the set's camera.
    """
    from .. import render
    from ..sensor import NoiseModel, add_noise, quantize

    K = np.array(params["K"]) if K is None else np.asarray(K, dtype=float)
    size = tuple(params["image_size"]) if size is None else tuple(size)
    scene = room_scene(params) if scene is None else scene
    out = render.render(scene, K, size, R=R, t=t, supersample=params["supersample"], color=True)
    signal = out.irradiance * np.float32(gain)
    if noise:
        signal = add_noise(signal, NoiseModel(params["full_well"], params["read_noise"]), rng)
    return quantize(np.clip(signal, 0, 1), 8)


class PanoramaSet(NamedTuple):
    """The rotation set: RGB ``images``, shared ``K``, cam_from_world ``R`` (n, 3, 3), ``gains``,
    ``H_true[j][i]`` = the true homography from view i to view j, and the generator ``params``."""

    images: list
    K: np.ndarray
    R: np.ndarray
    gains: np.ndarray
    params: dict

    def true_homography(self, i: int, j: int) -> np.ndarray:
        """The ground-truth homography mapping view ``i``'s pixels to view ``j``'s: K R_j R_i^T K^-1."""
        from ..homography import rotation_homography

        return rotation_homography(self.K, self.R[j] @ self.R[i].T)


class PlanarPair(NamedTuple):
    """Two views of a flat poster; ``H`` maps view 0's pixels to view 1's."""

    images: list
    K: np.ndarray
    H: np.ndarray
    params: dict


def _encode_jpeg(img: np.ndarray, quality: int) -> bytes:
    """JPEG bytes of an RGB image (what a camera writes; deterministic for one libjpeg version)."""
    import cv2

    return encode_image(img[..., ::-1], ".jpg", (cv2.IMWRITE_JPEG_QUALITY, int(quality)))


def make_panorama_set(out_dir: Path | str, params: dict = PANORAMA_PARAMS) -> list[Path]:
    """Render the panorama set and the planar pair into ``out_dir``; return the files written."""
    from .. import render
    from ..homography import plane_homography

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    K = np.array(params["K"])
    scene = room_scene(params)
    rng = np.random.default_rng(params["seed"])
    files, views = [], []
    for i, ((yaw, pitch, roll), gain) in enumerate(
        zip(params["angles_deg"], params["gains"], strict=True)
    ):
        R = cam_from_world(*np.radians([yaw, pitch, roll]))
        img = render_view(R, gain=gain, rng=rng, params=params, scene=scene)
        name = f"rot_{i:02d}.jpg"
        (out / name).write_bytes(_encode_jpeg(img, params["jpeg_quality"]))
        files.append(out / name)
        views.append({"file": name, "R": np.round(R, 15).tolist(), "gain": gain})

    # the planar pair: a poster (the wall texture) 1.5 m away, seen from two positions
    pp = params["plane_pair"]
    poster = render.textured_plane(
        wall_texture(params["wall_texture_px"], params["seed"])[:, :800],
        2.0,
        t=(0.0, 0.0, 1.5),
        name="poster",
    )
    R1 = cam_from_world(*np.radians(pp["angles1_deg"]))
    t1 = np.asarray(pp["t1"], dtype=float)
    # camera 0 at the origin; camera 1 at centre c1 = t1 (world), so its translation is -R1 c1
    poses = [(np.eye(3), np.zeros(3)), (R1, -R1 @ t1)]
    for i, (R, t) in enumerate(poses):
        res = render.render(
            poster,
            K,
            tuple(params["image_size"]),
            R=R,
            t=t,
            supersample=params["supersample"],
            color=True,
            background=0.3,
        )
        from ..sensor import NoiseModel, add_noise, quantize

        img = quantize(
            np.clip(
                add_noise(
                    res.irradiance, NoiseModel(params["full_well"], params["read_noise"]), rng
                ),
                0,
                1,
            ),
            8,
        )
        name = f"plane_{i}.jpg"
        (out / name).write_bytes(_encode_jpeg(img, params["jpeg_quality"]))
        files.append(out / name)
    # the poster is the plane z = 1.5 in camera 0's frame: n = (0, 0, 1), d = -1.5 (n . X + d = 0)
    Hp = plane_homography(K, poses[1][0], poses[1][1], (0, 0, 1), -1.5)
    truth = {
        "description": "Panorama set rendered by camlab.render; regenerate with `python -m camlab.data`.",
        "generator": "camlab.data.panorama.make_panorama_set",
        "params": params,
        "conventions": "pixels (u, v) = (column, row), origin at the centre of the top-left pixel; R = cam_from_world, "
        "every rotation view has its centre at the world origin; H_ij maps view j's pixels to view i's",
        "K": params["K"],
        "image_size": params["image_size"],
        "views": views,
        "H_true": [
            [np.round(_true_h(K, views, i, j), 12).tolist() for j in range(len(views))]
            for i in range(len(views))
        ],
        "plane_pair": {
            "files": ["plane_0.jpg", "plane_1.jpg"],
            "R1": np.round(poses[1][0], 15).tolist(),
            "t1": np.round(poses[1][1], 15).tolist(),
            "plane_n": [0, 0, 1],
            "plane_d": -1.5,
            "H_10": np.round(Hp, 12).tolist(),
        },
    }
    (out / "truth.json").write_text(json.dumps(truth, indent=1) + "\n")
    files.append(out / "truth.json")
    return files


def _true_h(K: np.ndarray, views: list, i: int, j: int) -> np.ndarray:
    from ..homography import rotation_homography

    return rotation_homography(K, np.array(views[i]["R"]) @ np.array(views[j]["R"]).T)


def _read(path: Path, scale: float) -> np.ndarray:
    import cv2

    img = cv2.imread(str(path), cv2.IMREAD_COLOR)
    if img is None:
        raise CamlabInputError(
            f"directory: cannot read {path}; run `python -m camlab.data` to generate it"
        )
    img = np.ascontiguousarray(img[..., ::-1])
    if scale != 1.0:
        h, w = img.shape[:2]
        img = cv2.resize(
            img, (int(round(w * scale)), int(round(h * scale))), interpolation=cv2.INTER_AREA
        )
    return img


def load_panorama_set(directory: Path | str | None = None, scale: float = 1.0) -> PanoramaSet:
    """Load ``data/panorama`` (or ``directory``); ``scale`` < 1 resizes the images (K follows).

    >>> s = load_panorama_set(scale=0.5)
    >>> len(s.images), s.images[0].shape, float(s.K[0, 0])
    (4, (240, 320, 3), 400.0)
    """
    d, truth = read_truth(directory, "panorama")
    images = [_read(d / v["file"], scale) for v in truth["views"]]
    K = scale_intrinsics(np.array(truth["K"]), scale)
    return PanoramaSet(
        images,
        K,
        np.array([v["R"] for v in truth["views"]]),
        np.array([v["gain"] for v in truth["views"]]),
        truth["params"],
    )


def load_planar_pair(directory: Path | str | None = None, scale: float = 1.0) -> PlanarPair:
    """Load the two views of the flat poster; ``H`` maps view 0's pixels to view 1's (at ``scale``)."""
    d, truth = read_truth(directory, "panorama")
    pp = truth["plane_pair"]
    images = [_read(d / f, scale) for f in pp["files"]]
    S = scale_intrinsics(np.eye(3), scale)
    H = S @ np.array(pp["H_10"]) @ np.linalg.inv(S)
    return PlanarPair(
        images, scale_intrinsics(np.array(truth["K"]), scale), H / H[2, 2], truth["params"]
    )


# --------------------------------------------------------------------------- a real photo as the world


@lru_cache(maxsize=1)
def environment_map() -> np.ndarray:
    r"""A 360-degree world made from a real photograph (read-only uint8 RGB, 1024 x 3072).

    ``lab_scene`` (mvtb-data, MIT; data/photos/ATTRIBUTION.md) next to its mirror image
    (the photo's centre straight ahead, the mirror image behind), read as an equirectangular map: column u is the longitude
    :math:`\theta = 2\pi (u + \tfrac12)/W - \pi` (0 straight ahead, positive to the right),
    row v the latitude :math:`\phi = (v - (H-1)/2)\, 2\pi / W` (positive down), one pixel
    per 0.117 degree in both directions, so latitudes up to +-60 degrees. Mirroring makes
    the world seamless at 360 degrees.
    """
    from .photos import load_photo

    photo = load_photo("lab_scene")
    # the photo's centre straight ahead; its mirror image behind (the seams at +-90 degrees)
    env = np.ascontiguousarray(
        np.roll(np.hstack([photo, photo[:, ::-1]]), photo.shape[1] // 2, axis=1)
    )
    env.setflags(write=False)
    return env


def environment_view(
    R: ArrayLike, K: ArrayLike, size: tuple[int, int], env: np.ndarray | None = None
) -> np.ndarray:
    r"""What a pinhole camera (K, R cam_from_world) at the world's centre sees of :func:`environment_map`.

    Every pixel's ray :math:`d = R^\top K^{-1} (u, v, 1)^\top` is turned into longitude
    :math:`\theta = \operatorname{atan2}(d_x, d_z)` and latitude
    :math:`\phi = \operatorname{atan2}(d_y, \sqrt{d_x^2 + d_z^2})` and looked up (bilinear).
    Any two such views are related exactly by :math:`K R_j R_i^\top K^{-1}`: a turning
    camera with known ground truth, showing a real scene.

    Parameters
    ----------
    R : (3, 3) array_like
        cam_from_world.
    K : (3, 3) array_like
    size : (width, height)
    env : ndarray, optional
        Equirectangular map (default :func:`environment_map`).
    """
    import cv2

    env = environment_map() if env is None else env
    H, W = env.shape[:2]
    w, h = size
    Ki = np.linalg.inv(np.asarray(K, float))
    Rt = np.asarray(R, float).T
    v, u = np.mgrid[0:h, 0:w].astype(np.float32)
    ray = [Ki[r, 0] * u + Ki[r, 1] * v + Ki[r, 2] for r in range(3)]  # K^-1 (u, v, 1)
    dx, dy, dz = (Rt[r, 0] * ray[0] + Rt[r, 1] * ray[1] + Rt[r, 2] * ray[2] for r in range(3))
    theta = np.arctan2(dx, dz)
    phi = np.arctan2(dy, np.hypot(dx, dz))
    scale = W / (2 * np.pi)
    mu = np.mod((theta + np.pi) * scale - 0.5, W).astype(np.float32)
    mv = (phi * scale + (H - 1) / 2).astype(np.float32)
    ext = np.hstack([env, env[:, :1]])  # interpolate across the 360-degree seam
    return cv2.remap(ext, mu, mv, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)


class TurningSet(NamedTuple):
    """Views of :func:`environment_map` from a turning camera: ``images`` (uint8 RGB), the exact
    ``K`` (shared) and ``R`` (n, 3, 3) cam_from_world, the (yaw, pitch, roll) ``angles_deg``
    and exposure ``gains``; ``names`` label the images (an unrelated photo is named as such)."""

    images: list
    K: np.ndarray
    R: np.ndarray
    angles_deg: np.ndarray
    gains: np.ndarray
    names: list


#: The rendered turning-camera sets: (yaw, pitch, roll) per view in degrees, and gains.
TURNING_SETS = {
    # three photos of a turning camera (plus an unrelated photo, see turning_set)
    "turn3": {"angles": [(-40, 2, 0.5), (0, -1, -0.5), (40, 1.5, 1.0)], "gains": [1.0, 0.9, 1.1]},
    # a pair at two exposures (the second over-exposed: bright parts clip)
    "exposures": {"angles": [(-18, 0, 0), (18, 1, 0.5)], "gains": [0.75, 1.6]},
    # a full turn in eight photos: the loop closes only if the errors do not accumulate
    "loop": {
        "angles": [(45 * k, 3 * np.sin(k), 1.0 * np.cos(k)) for k in range(8)],
        "gains": [1.0] * 8,
    },
    # a turn of 405 degrees: the ninth photo shows what the first did
    "over360": {"angles": [(45 * k, 0, 0) for k in range(10)], "gains": [1.0] * 10},
    # a wide 200-degree sweep (a plane cannot hold it)
    "wide": {"angles": [(-100 + 40 * k, 2 * (-1) ** k, 0) for k in range(6)], "gains": [1.0] * 6},
}


@lru_cache(maxsize=8)
def _turning(name: str, f: float, size: tuple[int, int], unrelated: bool) -> TurningSet:
    from .photos import load_photo

    width, height = size

    spec = TURNING_SETS[name]
    K = np.array([[f, 0, (width - 1) / 2], [0, f, (height - 1) / 2], [0, 0, 1.0]])
    rng = np.random.default_rng(2007)
    images, Rs = [], []
    for (yaw, pitch, roll), gain in zip(spec["angles"], spec["gains"], strict=True):
        R = cam_from_world(*np.radians([yaw, pitch, roll]))
        img = environment_view(R, K, (width, height)).astype(float) * gain
        img = np.clip(np.rint(img + rng.normal(0, 1.5, img.shape)), 0, 255).astype(np.uint8)
        img.setflags(write=False)
        images.append(img)
        Rs.append(R)
    names = [f"{name}_{k}" for k in range(len(images))]
    if unrelated:
        import cv2

        church = cv2.resize(load_photo("church"), (width, height), interpolation=cv2.INTER_AREA)
        images.insert(1, church)
        names.insert(1, "church (unrelated)")
    return TurningSet(
        images,
        K,
        np.array(Rs),
        np.array(spec["angles"], float),
        np.array(spec["gains"], float),
        names,
    )


def turning_set(
    name: str = "turn3",
    *,
    f: float = 500.0,
    size: tuple[int, int] = (900, 660),
    unrelated: bool = False,
) -> TurningSet:
    """A rendered turning-camera set with exact ground truth (:data:`TURNING_SETS`, :func:`environment_view`).

    Parameters
    ----------
    name : str
        A key of :data:`TURNING_SETS`.
    f : float
        Focal length in pixels (default 500: a 84-degree horizontal field of view at 900 px).
    size : (width, height)
        Image size (default 900 x 660, about 0.6 megapixel).
    unrelated : bool
        Insert an unrelated photo (``church``) as the second image; it is not in ``R``.

    Returns
    -------
    TurningSet
        Sensor noise (sigma 1.5 grey levels) is added with a fixed seed: the same images every call.
    """
    if name not in TURNING_SETS:
        raise CamlabInputError(f"name: expected one of {sorted(TURNING_SETS)}, got {name!r}")
    return _turning(name, float(check_positive(f, "f")), check_size(size), bool(unrelated))


def load_aerial_mosaic(count: int = 6) -> list:
    """The real planar mosaic: ``count`` (2-6) overlapping aerial photographs (grey, 900 px wide).

    A flat scene seen from six positions (mvtb-data ``mosaic/aerial2-00*``, MIT; see
    data/photos/ATTRIBUTION.md), so consecutive photos are related by homographies.
    """
    from .photos import load_photo

    if not 2 <= int(count) <= 6:
        raise CamlabInputError(f"count: expected 2 to 6 aerial photos, got {count!r}")
    return [load_photo(f"aerial_{k}", gray=True) for k in range(1, int(count) + 1)]
