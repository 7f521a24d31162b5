r"""A rendered stereo rig with full ground truth: ``data/stereo/`` (lesson 11).

``python -m camlab.data`` rewrites ``data/stereo/`` (with the other data sets) deterministically from
:data:`STEREO_PARAMS` with :mod:`camlab.render` (the virtual camera):

``left.jpg``, ``right.jpg``
    The raw pair, 640 x 480, 8-bit grey, with lens distortion, a slight toe-in, a small
    vertical offset and roll between the cameras (so rectification has work to do), a
    little sensor noise, stored as JPEG (quality ``jpeg_quality``) as a camera would: the
    random textures cost about 225 kB per image as PNG, and all of ``data/`` must stay
    within its budget (tests/test_data.py). The ground truth is exact; the compression noise is part of the matching
    problem (depth accuracy is tested on these very files). The scene: a textured back wall, three textured planes at
    different depths (one showing a photograph), and two boxes with noise-textured faces.
``disparity.png``
    The true disparity of the *calibrated rectification* of the pair (``alpha = 0``), for
    every pixel of the rectified left image, stored KITTI-style: uint16 = round(256 d),
    0 = no surface. Load with :func:`load_stereo_rig`.
``calib_left_NN.png``, ``calib_right_NN.png``
    Chessboard views seen by both cameras (9 x 6 inner corners, 25 mm squares), for
    stereo calibration; noise-free 8-bit (keeps them about 10 kB each; the whole of
    ``data/`` must stay within its budget).
``truth.json``
    Both cameras (K, dist, R, t cam_from_world), the rectified cameras, the exact corner
    pixels of every calibration view in both images, and the generator's parameters.
``data/MANIFEST.txt`` lists the SHA-256 and size of every file.

Conventions: pixels (u, v) = (column, row), origin at the centre of the top-left pixel;
world z up, metres; the left camera looks along world +y.
"""

from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path
from typing import NamedTuple

import numpy as np

from ..camera import Camera, look_at_rotation, rotation_from_axis_angle
from ..scenes import CameraPair, noise_texture, portrait
from ._resources import encode_image, read_only, read_truth

__all__ = [
    "HALF_SIZE",
    "STEREO_PARAMS",
    "HalfSizeRectification",
    "PreparedRig",
    "RigCalibration",
    "StereoMatches",
    "StereoRig",
    "bundled_rig",
    "bundled_rig_calibration",
    "calibrate_rig",
    "half_size_rectification",
    "load_stereo_rig",
    "make_stereo_rig",
    "rig_cameras",
    "stereo_scene",
    "true_disparity",
    "true_matches",
]

STEREO_PARAMS = {
    "seed": 11,
    "image_size": [640, 480],
    "K_left": [[800.0, 0.0, 321.3], [0.0, 801.5, 238.2], [0.0, 0.0, 1.0]],
    "K_right": [[806.0, 0.0, 317.9], [0.0, 805.0, 243.6], [0.0, 0.0, 1.0]],
    "dist_left": [-0.08, 0.03, 0.0004, -0.0003, 0.0],
    "dist_right": [-0.07, 0.025, -0.0003, 0.0002, 0.0],
    "left_eye": [-0.06, 0.0, 1.0],
    "baseline": 0.12,
    "right_offset": [0.0, 0.004, 0.006],  # extra displacement of the right camera, metres
    "toe_in": 0.02,  # radians each camera turns towards the middle
    "right_roll": 0.01,  # radians, about the right camera's optical axis
    "target": [0.0, 3.0, 1.0],
    "full_well": 20000.0,
    "read_noise": 1.5,
    "supersample": 2,
    "n_calib": 4,
    "jpeg_quality": 85,
    "pattern_size": [9, 6],
    "square": 0.025,
    "rectify_alpha": 0.0,
}


def _facing() -> np.ndarray:
    """world_from_plane rotation for a plane whose texture is upright seen from -y (the cameras)."""
    return np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])


def stereo_scene(params: dict = STEREO_PARAMS) -> list:
    """The planes of the scene (a list of :class:`camlab.render.Plane`), deterministic."""
    from .. import render

    s = int(params["seed"])
    Rf = _facing()
    turn = rotation_from_axis_angle(
        [0.0, 0.0, 0.35]
    )  # a plane turned 20 degrees about the vertical
    scene = [
        render.textured_plane(
            noise_texture((512, 768), s), 6.0, R=Rf, t=(0.0, 4.2, 1.4), height=4.0, name="wall"
        ),
        render.textured_plane(
            noise_texture((384, 384), s + 1, 0.6),
            0.9,
            R=turn @ Rf,
            t=(-0.75, 2.6, 1.15),
            name="panel_far",
        ),
        render.textured_plane(
            portrait().mean(axis=2), 0.55, R=Rf, t=(0.45, 1.9, 1.2), name="photo"
        ),
        render.textured_plane(
            noise_texture((256, 256), s + 2, 0.45),
            0.35,
            R=Rf,
            t=(-0.2, 1.35, 0.9),
            name="panel_near",
        ),
        render.box(
            (0.35, 2.2, 0.55),
            (0.3, 0.3, 0.3),
            R=rotation_from_axis_angle([0, 0, 0.5]),
            rng=s + 3,
            name="box_a",
        ),
        render.box(
            (-0.45, 1.75, 0.62),
            (0.18, 0.18, 0.25),
            R=rotation_from_axis_angle([0, 0, -0.4]),
            rng=s + 4,
            name="box_b",
        ),
    ]
    return scene


def rig_cameras(params: dict = STEREO_PARAMS, distortion: bool = True) -> CameraPair:
    """The left and right cameras (cam_from_world), with a small toe-in, offset and roll."""
    size = tuple(params["image_size"])
    eye1 = np.array(params["left_eye"], dtype=float)
    eye2 = eye1 + [params["baseline"], 0.0, 0.0] + np.array(params["right_offset"])
    target = np.array(params["target"], dtype=float)
    ahead = target + [eye1[0], 0.0, 0.0]  # straight ahead of the left camera (world +y)
    R1 = look_at_rotation(eye1, ahead)
    R2 = look_at_rotation(eye2, ahead + (eye2 - eye1) * [1.0, 0.0, 0.0])
    # Toe-in: a rotation about the camera's own y axis (pointing down); a negative angle turns
    # the camera to its right. The left camera turns right, the right one left: they converge.
    R1 = rotation_from_axis_angle([0.0, -params["toe_in"], 0.0]) @ R1
    R2 = (
        rotation_from_axis_angle([0.0, 0.0, params["right_roll"]])
        @ rotation_from_axis_angle([0.0, params["toe_in"], 0.0])
        @ R2
    )
    d1 = tuple(params["dist_left"]) if distortion else (0.0,) * 5
    d2 = tuple(params["dist_right"]) if distortion else (0.0,) * 5
    c1 = Camera(np.array(params["K_left"]), R1, -R1 @ eye1, d1, size)
    c2 = Camera(np.array(params["K_right"]), R2, -R2 @ eye2, d2, size)
    return CameraPair(c1, c2)


def _calib_poses(params: dict, c1: Camera, c2: Camera):
    """Board poses (world_from_board R, t) that both cameras see whole."""
    rng = np.random.default_rng(int(params["seed"]) + 100)
    cols, rows = params["pattern_size"]
    sq = params["square"]
    centre_board = np.array([(cols - 1) * sq / 2, (rows - 1) * sq / 2, 0.0])
    mid = (c1.centre + c2.centre) / 2
    out = []
    while len(out) < int(params["n_calib"]):
        dist = rng.uniform(0.55, 0.9)
        aim = (
            mid
            + dist * np.array([0.0, 1.0, 0.0])
            + [rng.uniform(-0.1, 0.1), 0.0, rng.uniform(-0.07, 0.07)]
        )
        tilt = rotation_from_axis_angle(rng.uniform(-0.45, 0.45, 3) * [1.0, 0.4, 1.0])
        R = tilt @ _facing()
        t = aim - R @ centre_board
        corners = (
            np.array(
                [
                    [0, 0, 0],
                    [(cols - 1) * sq, 0, 0],
                    [0, (rows - 1) * sq, 0],
                    [(cols - 1) * sq, (rows - 1) * sq, 0],
                ]
            )
            @ R.T
            + t
        )
        ok = True
        for c in (c1, c2):
            uv = c.project(corners)
            w, h = c.image_size
            ok &= bool(
                np.all(np.isfinite(uv))
                and np.all(uv > 40)
                and np.all(uv[:, 0] < w - 40)
                and np.all(uv[:, 1] < h - 40)
            )
        if ok:
            out.append((R, t))
    return out


class StereoRig(NamedTuple):
    """The bundled stereo rig: raw images, cameras, true rectified disparity, calibration views."""

    left: np.ndarray  # (480, 640) uint8
    right: np.ndarray
    camera1: Camera  # left camera (with distortion)
    camera2: Camera
    disparity: (
        np.ndarray
    )  # (480, 640) float, true disparity of the alpha=0 calibrated rectification; NaN = none
    calib_left: list[np.ndarray]
    calib_right: list[np.ndarray]
    calib_corners_left: np.ndarray  # (n, 54, 2) exact pixels
    calib_corners_right: np.ndarray
    object_points: np.ndarray  # (54, 3) board frame
    pattern_size: tuple[int, int]
    params: dict


class StereoMatches(NamedTuple):
    """True correspondences of the rig's pair, one scene point per row.

    Attributes
    ----------
    raw1, raw2 : (N, 2) ndarray
        Pixels (u, v) in the raw (distorted) left and right images.
    ideal1, ideal2 : (N, 2) ndarray
        The same points undistorted (pixels of the distortion-free cameras, which F relates).
    """

    raw1: np.ndarray
    raw2: np.ndarray
    ideal1: np.ndarray
    ideal2: np.ndarray


def true_matches(rig: StereoRig, step: int = 30, start: int = 20) -> StereoMatches:
    """Exact correspondences in the raw (distorted) images, from the true disparity, and undistorted.

    A grid of pixels of the rectified left image (every ``step`` pixels from ``start``) with
    their true disparity ``d`` gives rectified pairs ``(u, v)`` and ``(u - d, v)``; the
    calibrated rectification (``alpha`` as stored) carries both back to the raw images, and
    :func:`camlab.distortion.undistort_pixels` removes each camera's lens distortion.
    Pairs that land outside either image, or on no surface, are dropped.
    """
    from ..distortion import undistort_pixels
    from ..rectification import rectify_calibrated, unrectify_points

    rect = rectify_calibrated(
        rig.camera1, rig.camera2, alpha=rig.params["rectify_alpha"], maps=False
    )
    h, w = rig.disparity.shape
    v, u = np.mgrid[start : h - 10 : step, start : w - 10 : step]
    p1 = np.column_stack([u.ravel(), v.ravel()]).astype(float)
    d = rig.disparity[v.ravel(), u.ravel()]
    ok = np.isfinite(d)
    x1 = unrectify_points(rect, rig.camera1, p1[ok], 1)
    x2 = unrectify_points(
        rect, rig.camera2, p1[ok] - np.column_stack([d[ok], np.zeros(ok.sum())]), 2
    )
    inside = np.all((x1 > 0) & (x1 < [w - 1, h - 1]) & (x2 > 0) & (x2 < [w - 1, h - 1]), axis=1)
    x1, x2 = x1[inside], x2[inside]
    c1, c2 = rig.camera1, rig.camera2
    return StereoMatches(
        x1, x2, undistort_pixels(x1, c1.K, c1.dist), undistort_pixels(x2, c2.K, c2.dist)
    )


def true_disparity(rig: StereoRig, rect) -> np.ndarray:
    """The true disparity (pixels, NaN = no surface) of another calibrated rectification of the rig.

    ``rect`` is :func:`camlab.rectification.rectify_calibrated` of the rig's true cameras at
    any resolution or ``alpha`` (e.g. of ``camera.resized(0.5)``): it has the same rectifying
    rotation as the stored one, so its pixel p' sees the surface of the stored rectified pixel
    :math:`K K'^{-1} p'` at the same depth Z (nearest pixel), and its disparity is
    :math:`d' = f' B / Z` (:func:`camlab.disparity.disparity_to_depth` is its own inverse).
    """
    import cv2

    from ..disparity import disparity_to_depth
    from ..rectification import rectify_calibrated

    stored = rectify_calibrated(
        rig.camera1, rig.camera2, alpha=rig.params["rectify_alpha"], maps=False
    )
    Z = disparity_to_depth(rig.disparity, stored.K[0, 0], stored.baseline).astype(np.float32)
    M = stored.K @ np.linalg.inv(rect.K)
    w, h = rect.camera1.image_size
    v, u = np.mgrid[0:h, 0:w].astype(np.float32)
    Zr = cv2.remap(
        Z,
        (M[0, 0] * u + M[0, 2]).astype(np.float32),
        (M[1, 1] * v + M[1, 2]).astype(np.float32),
        cv2.INTER_NEAREST,
        borderValue=np.nan,
    )
    return disparity_to_depth(Zr, rect.K[0, 0], rect.baseline)


class RigCalibration(NamedTuple):
    """The rig as a stereo calibration sees it.

    Attributes
    ----------
    camera1, camera2 : Camera
        The calibrated cameras in camera 1's frame (camera 1 has R = I, t = 0), with the
        estimated distortion.
    rms : float
        The calibration's joint RMS reprojection error, pixels.
    """

    camera1: Camera
    camera2: Camera
    rms: float


def calibrate_rig(rig: StereoRig) -> RigCalibration:
    """Calibrate the rig from its chessboard pairs, as one would a real rig (not its true cameras).

    Corners by :func:`camlab.calibration.find_chessboard` in every calibration image, then
    :func:`camlab.rectification.stereo_calibrate`. Rectifying with these cameras leaves a
    small vertical disparity: the calibration's own error, which the true cameras would hide.
    """
    from ..calibration import find_chessboard
    from ..rectification import stereo_calibrate

    size = rig.camera1.image_size
    c1 = [find_chessboard(im, rig.pattern_size).corners for im in rig.calib_left]
    c2 = [find_chessboard(im, rig.pattern_size).corners for im in rig.calib_right]
    sc = stereo_calibrate(rig.object_points, c1, c2, size)
    cam1 = Camera(sc.K1, np.eye(3), np.zeros(3), dist=tuple(sc.dist1), image_size=size)
    cam2 = Camera(sc.K2, sc.R, sc.t, dist=tuple(sc.dist2), image_size=size)
    return RigCalibration(cam1, cam2, float(sc.rms))


# ----------------------------------------------------------------------------- the rig as lesson 11 uses it

HALF_SIZE = (320, 240)  # (width, height) the demos show the pair at, so that re-warping stays fast


def _halved(image: np.ndarray) -> np.ndarray:
    import cv2

    return cv2.resize(image, HALF_SIZE, interpolation=cv2.INTER_AREA)


class PreparedRig(NamedTuple):
    """The bundled rig prepared once for lesson 11's demos (:func:`bundled_rig`); arrays are read-only.

    Attributes
    ----------
    rig : StereoRig
        The rig as :func:`load_stereo_rig` reads it.
    matches : StereoMatches
        Its true matches every 30 pixels (:func:`true_matches`).
    half : tuple of two (240, 320) uint8 arrays
        The raw left and right images at :data:`HALF_SIZE`.
    undistorted : tuple of two (480, 640) uint8 arrays
        The full-size pair with each camera's lens distortion removed.
    uncalibrated
        :func:`camlab.rectification.rectify_uncalibrated` (Hartley's method) from F that
        RANSAC estimates on the undistorted matches with 0.3 px of noise added (seeded): what
        section 4 of the lesson computes, with a denser grid of matches.
    """

    rig: StereoRig
    matches: StereoMatches
    half: tuple
    undistorted: tuple
    uncalibrated: object


@lru_cache(maxsize=1)
def bundled_rig() -> PreparedRig:
    """The bundled rig with its true matches, half-size and undistorted pair, and uncalibrated rectification (cached)."""
    from ..distortion import undistort_image
    from ..epipolar import ransac_fundamental_matrix
    from ..rectification import rectify_uncalibrated

    rig = load_stereo_rig()
    matches = true_matches(rig, step=30, start=20)
    half = (_halved(rig.left), _halved(rig.right))
    undistorted = (
        undistort_image(rig.left, rig.camera1.K, rig.camera1.dist),
        undistort_image(rig.right, rig.camera2.K, rig.camera2.dist),
    )
    rng = np.random.default_rng(0)
    n1 = matches.ideal1 + rng.normal(0, 0.3, matches.ideal1.shape)
    n2 = matches.ideal2 + rng.normal(0, 0.3, matches.ideal2.shape)
    F = ransac_fundamental_matrix(n1, n2, 1.0, rng=np.random.default_rng(1)).F
    uncalibrated = rectify_uncalibrated(n1, n2, F, rig.camera1.image_size)
    return read_only(PreparedRig(rig, matches, half, undistorted, uncalibrated))


@lru_cache(maxsize=1)
def bundled_rig_calibration() -> RigCalibration:
    """:func:`calibrate_rig` of the bundled rig, computed once (read-only)."""
    return read_only(calibrate_rig(bundled_rig().rig))


class HalfSizeRectification(NamedTuple):
    """The rig's calibrated rectification at half size (:func:`half_size_rectification`); arrays are read-only.

    Attributes
    ----------
    rect
        :func:`camlab.rectification.rectify_calibrated` of the true cameras resized by 0.5,
        with the stored ``rectify_alpha``.
    left, right : (240, 320) uint8 ndarray
        The rectified half-size pair.
    disparity : (240, 320) float ndarray
        Its true disparity (:func:`true_disparity`), NaN where no surface is seen.
    smooth : (240, 320) bool ndarray
        Pixels whose true disparity varies by less than 0.5 px over their 9 x 9 neighbourhood:
        the textured surfaces, away from depth edges, where a matcher's depth error is fair to score.
    """

    rect: object
    left: np.ndarray
    right: np.ndarray
    disparity: np.ndarray
    smooth: np.ndarray


@lru_cache(maxsize=1)
def half_size_rectification() -> HalfSizeRectification:
    """The alpha = 0 calibrated rectification of the bundled rig at half size, with the true disparity (cached)."""
    import scipy.ndimage as ndi

    from ..rectification import rectify_calibrated, rectify_images

    prepared = bundled_rig()
    rig = prepared.rig
    rect = rectify_calibrated(
        rig.camera1.resized(0.5),
        rig.camera2.resized(0.5),
        alpha=rig.params["rectify_alpha"],
        method="cv2",
    )
    left, right = rectify_images(rect, *prepared.half)
    disparity = true_disparity(rig, rect)
    g = np.nan_to_num(disparity, nan=-100.0)
    smooth = np.isfinite(disparity) & (ndi.maximum_filter(g, 9) - ndi.minimum_filter(g, 9) < 0.5)
    return read_only(HalfSizeRectification(rect, left, right, disparity, smooth))


def _png(path: Path, img: np.ndarray) -> Path:
    import cv2

    path.write_bytes(encode_image(img, ".png", (cv2.IMWRITE_PNG_COMPRESSION, 9)))
    return path


def _jpg(path: Path, img: np.ndarray, quality: int) -> Path:
    import cv2

    path.write_bytes(encode_image(img, ".jpg", (cv2.IMWRITE_JPEG_QUALITY, int(quality))))
    return path


def _camera_json(c: Camera) -> dict:
    return {
        "K": np.round(c.K, 12).tolist(),
        "dist": list(c.dist),
        "R": np.round(c.R, 12).tolist(),
        "t": np.round(c.t, 12).tolist(),
        "image_size": list(c.image_size),
    }


def make_stereo_rig(out_dir: Path | str, params: dict = STEREO_PARAMS) -> list[Path]:
    """Render the stereo rig into ``out_dir``; return the files written."""
    from .. import render
    from ..rectification import rectify_calibrated
    from ..sensor import NoiseModel

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    c1, c2 = rig_cameras(params)
    size = tuple(params["image_size"])
    sensor = render.Sensor(bits=8, noise=NoiseModel(params["full_well"], params["read_noise"]))
    rng = np.random.default_rng(int(params["seed"]) + 1)
    scene = stereo_scene(params)
    files = []
    for name, c in (("left", c1), ("right", c2)):
        res = render.render(
            scene,
            c.K,
            size,
            R=c.R,
            t=c.t,
            dist=c.dist,
            sensor=sensor,
            supersample=params["supersample"],
            rng=rng,
            color=False,
        )
        files.append(_jpg(out / f"{name}.jpg", res.image, params["jpeg_quality"]))
    rect = rectify_calibrated(c1, c2, alpha=params["rectify_alpha"], maps=False)
    r1 = rect.camera1
    gt = render.render(
        scene, r1.K, size, R=r1.R, t=r1.t, supersample=1, depth=True, color=False
    ).truth
    with np.errstate(divide="ignore", invalid="ignore"):
        disp = rect.K[0, 0] * rect.baseline / gt.depth
    enc = np.where(
        np.isfinite(disp) & (disp > 0), np.clip(np.round(disp * 256), 1, 65535), 0
    ).astype(np.uint16)
    files.append(_png(out / "disparity.png", enc))
    cols, rows = params["pattern_size"]
    # Calibration views without sensor noise (8-bit quantisation only): noisy PNGs are ~15x larger,
    # and data/ must stay small. Add noise with camlab.sensor.add_noise to study its effect.
    quiet = render.Sensor(bits=8)
    views = []
    for i, (R, t) in enumerate(_calib_poses(params, c1, c2)):
        board = render.checkerboard((cols, rows), params["square"], R=R, t=t)
        corners = {}
        for name, c in (("left", c1), ("right", c2)):
            res = render.render(
                board,
                c.K,
                size,
                R=c.R,
                t=c.t,
                dist=c.dist,
                sensor=quiet,
                supersample=params["supersample"],
                color=False,
            )
            files.append(_png(out / f"calib_{name}_{i:02d}.png", res.image))
            corners[name] = np.round(res.truth.corners(), 9).tolist()
        views.append(
            {
                "left": f"calib_left_{i:02d}.png",
                "right": f"calib_right_{i:02d}.png",
                "R_world_from_board": np.round(R, 12).tolist(),
                "t_world_from_board": np.round(t, 12).tolist(),
                "corners_left": corners["left"],
                "corners_right": corners["right"],
            }
        )
    truth = {
        "description": "Stereo rig rendered by camlab.render; regenerate with `python -m camlab.data`.",
        "generator": "camlab.data.stereo.make_stereo_rig",
        "params": params,
        "conventions": "pixels (u, v) = (column, row), origin at the centre of the top-left pixel; X_cam = R X_world + t; "
        "dist = (k1, k2, p1, p2, k3); disparity.png = round(256 * d) of the alpha=0 calibrated "
        "rectification (camlab.rectification.rectify_calibrated), 0 = no surface",
        "camera_left": _camera_json(c1),
        "camera_right": _camera_json(c2),
        "rectified": {
            "K": np.round(rect.K, 12).tolist(),
            "R1": np.round(rect.R1, 12).tolist(),
            "R2": np.round(rect.R2, 12).tolist(),
            "baseline": rect.baseline,
        },
        "pattern_size": [cols, rows],
        "square": params["square"],
        "object_points": np.round(
            render.checkerboard((cols, rows), params["square"]).object_points, 12
        ).tolist(),
        "calibration_views": views,
    }
    (out / "truth.json").write_text(json.dumps(truth, separators=(",", ":")) + "\n")
    files.append(out / "truth.json")
    return files


def load_stereo_rig(directory: Path | str | None = None) -> StereoRig:
    """Load ``data/stereo`` (or ``directory``) as a :class:`StereoRig`."""
    import cv2

    d, truth = read_truth(directory, "stereo")

    def cam(j):
        return Camera(
            np.array(j["K"]),
            np.array(j["R"]),
            np.array(j["t"]),
            tuple(j["dist"]),
            tuple(j["image_size"]),
        )

    def grey(name):
        return cv2.imread(str(d / name), cv2.IMREAD_GRAYSCALE)

    disp = cv2.imread(str(d / "disparity.png"), cv2.IMREAD_UNCHANGED).astype(float) / 256.0
    disp[disp == 0] = np.nan
    views = truth["calibration_views"]
    return StereoRig(
        left=grey("left.jpg"),
        right=grey("right.jpg"),
        camera1=cam(truth["camera_left"]),
        camera2=cam(truth["camera_right"]),
        disparity=disp,
        calib_left=[grey(v["left"]) for v in views],
        calib_right=[grey(v["right"]) for v in views],
        calib_corners_left=np.array([v["corners_left"] for v in views]),
        calib_corners_right=np.array([v["corners_right"] for v in views]),
        object_points=np.array(truth["object_points"]),
        pattern_size=tuple(truth["pattern_size"]),
        params=truth["params"],
    )
