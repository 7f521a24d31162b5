"""Tests for camlab.render, the virtual camera: ground truth checked by OpenCV's detector and projector."""

import cv2
import numpy as np
import pytest

from camlab import camera as cm
from camlab import render as r
from camlab import scenes
from camlab._validate import CamlabInputError
from camlab.camera import rotation_from_euler
from camlab.sensor import NoiseModel

K = np.array([[800.0, 0.0, 319.5], [0.0, 800.0, 239.5], [0.0, 0.0, 1.0]])
BARREL = np.array([-0.25, 0.08, 0.001, -0.0005, 0.0])
PINCUSHION = np.array([0.15, -0.05, 0.0, 0.0, 0.0])


def _poses(n, seed=1):
    rng = np.random.default_rng(seed)
    for _ in range(n):
        yield (
            rotation_from_euler(*rng.uniform(-0.5, 0.5, 3)),
            np.array([-0.12, -0.07, rng.uniform(0.6, 0.9)]),
        )


def _rms(a, b):
    return float(np.sqrt(np.mean(np.sum((a - b) ** 2, axis=1))))


@pytest.mark.parametrize("dist", [None, BARREL, PINCUSHION], ids=["none", "barrel", "pincushion"])
def test_find_chessboard_corners_sb_agrees_with_ground_truth(dist):
    for Rb, tb in _poses(3):
        board = scenes.checkerboard((9, 6), 0.03, R=Rb, t=tb)
        out = r.render(board, K, dist=dist)
        ok, corners = cv2.findChessboardCornersSB(out.image, (9, 6))
        assert ok
        found = r.align_detected_corners(corners, out.truth.corners())
        assert _rms(found, out.truth.corners()) < 0.1


def test_ground_truth_matches_cv2_project_points_with_a_moved_camera():
    board = scenes.checkerboard((7, 5), 0.04, R=rotation_from_euler(0.2, 0.1, 0), t=(0, 0, 0))
    R, t = r.look_at([0.3, -0.2, -0.8], [0.12, 0.08, 0.0], up=(0, -1, 0))
    out = r.render(board, K, R=R, t=t, dist=BARREL)
    pts = out.truth.points["board"]
    rvec, _ = cv2.Rodrigues(R)
    ref, _ = cv2.projectPoints(pts.world.reshape(-1, 1, 3), rvec, t.reshape(3, 1), K, BARREL)
    assert np.abs(pts.pixels - ref.reshape(-1, 2)).max() < 1e-6
    # object points are the usual calibration grid, and world = R_board X + t_board
    assert np.allclose(pts.object_points[:7, 0], np.arange(7) * 0.04)
    assert np.allclose(pts.world, pts.object_points @ board.R.T + board.t)
    assert pts.pattern_size == (7, 5) and pts.visible.all()
    assert np.allclose(out.truth.centre, [0.3, -0.2, -0.8])
    assert np.allclose(
        out.truth.P @ np.append(pts.world[0], 1), out.truth.P @ np.append(pts.world[0], 1)
    )


def test_project_single_point_and_behind_camera():
    assert np.allclose(r.project([0.1, 0.05, 1.0], K), [399.5, 279.5])
    p = r.project([[0, 0, 1.0], [0, 0, -1.0]], K)
    assert np.isnan(p[1]).all() and not np.isnan(p[0]).any()


def test_deterministic_with_a_seed():
    board = scenes.checkerboard((9, 6), 0.03, t=(-0.12, -0.07, 0.7))
    sensor = r.Sensor(noise=NoiseModel(full_well=2000, read_noise=3))
    a = r.render(board, K, sensor=sensor, rng=7).image
    b = r.render(board, K, sensor=sensor, rng=np.random.default_rng(7)).image
    c = r.render(board, K, sensor=sensor, rng=8).image
    assert np.array_equal(a, b) and not np.array_equal(a, c)
    clean = r.render(board, K)
    assert np.array_equal(clean.image, r.render(board, K).image)


def test_noise_has_the_shot_noise_level():
    flat = scenes.textured_plane(np.full((8, 8), 0.5), 4.0, t=(0, 0, 1.0))
    fw = 1000.0
    out = r.render(
        flat, K, sensor=r.Sensor(bits=12, noise=NoiseModel(full_well=fw, read_noise=0)), rng=0
    )
    assert out.image.dtype == np.uint16
    vals = out.image[100:380, 100:540] / 4095.0
    assert vals.mean() == pytest.approx(0.5, abs=0.003)
    assert vals.std() == pytest.approx(np.sqrt(0.5 * fw) / fw, rel=0.05)


def test_bayer_colour_and_photo():
    photo = scenes.photo_plane(0.5, t=(0, 0, 0.8))
    rgb = r.render(photo, K)
    assert rgb.image.shape == (480, 640, 3)
    raw = r.render(photo, K, sensor=r.Sensor(bayer="RGGB"))
    assert raw.image.shape == (480, 640) and raw.irradiance.shape == (480, 640, 3)
    # the red sites of the mosaic hold the red channel
    assert np.array_equal(raw.image[0::2, 0::2], rgb.image[0::2, 0::2, 0])
    grey = r.render(photo, K, color=False)
    assert grey.image.ndim == 2


def test_defocus_blurs_planes_away_from_the_focus_distance():
    near = scenes.checkerboard((5, 4), 0.02, t=(-0.15, -0.03, 0.5), name="near")
    far = scenes.checkerboard((5, 4), 0.04, t=(0.02, -0.06, 1.5), name="far")

    def sharpness(img, x0, x1):
        g = np.abs(np.diff(img[:, x0:x1].astype(float), axis=1))
        return g.max()

    focus_near = r.render(
        [near, far], K, defocus=r.Defocus(f_number=1.4, focus_distance=0.5)
    ).irradiance
    focus_far = r.render(
        [near, far], K, defocus=r.Defocus(f_number=1.4, focus_distance=1.5)
    ).irradiance
    assert sharpness(focus_near, 90, 270) > 2 * sharpness(focus_far, 90, 270)
    assert sharpness(focus_far, 350, 560) > 2 * sharpness(focus_near, 350, 560)


def test_occlusion_visibility_and_depth():
    board = scenes.checkerboard((9, 6), 0.03, t=(-0.12, -0.075, 0.8))
    card = scenes.textured_plane(np.full((4, 4), 0.3), 0.1, t=(-0.1, -0.05, 0.5), name="card")
    out = r.render([board, card], K, depth=True)
    pts = out.truth.points["board"]
    hidden = ~pts.visible
    assert 0 < hidden.sum() < len(hidden)
    # hidden corners are exactly those whose ray passes through the card
    ray = pts.world / pts.world[:, 2:3] * 0.5
    behind = (np.abs(ray[:, 0] + 0.1) <= 0.05) & (np.abs(ray[:, 1] + 0.05) <= 0.05)
    assert np.array_equal(hidden, behind)
    assert out.truth.depth.shape == (480, 640)
    assert out.truth.depth[0, 0] == np.inf
    u, v = np.rint(r.project([-0.1, -0.05, 0.5], K)).astype(int)
    assert out.truth.depth[v, u] == pytest.approx(0.5)
    assert out.truth.depth[240, 620] == np.inf or out.truth.depth[240, 620] == pytest.approx(0.8)


def test_box_faces_and_scene_flattening():
    faces = scenes.box([0, 0, 1.0], [0.2, 0.3, 0.2], R=rotation_from_euler(0.4, 0.6, 0))
    assert len(faces) == 6
    for f in faces:  # outward normals
        assert np.dot(f.R[:, 2], f.t - [0, 0, 1.0]) > 0
    out = r.render([faces, scenes.text_page(0.3, t=(0, 0, 2.0))], K, depth=True)
    # the face turned away from the camera is culled: its corners project but are not visible
    back, front = out.truth.points["box+z"], out.truth.points["box-z"]
    assert np.isfinite(back.pixels).all() and not back.visible.any()
    assert front.visible.all()
    assert out.image.std() > 10
    signs = np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).reshape(3, -1).T
    vertices = (signs * [0.1, 0.15, 0.1]) @ rotation_from_euler(0.4, 0.6, 0).T + [0, 0, 1.0]
    assert out.truth.depth.min() == pytest.approx(
        vertices[:, 2].min(), abs=0.01
    )  # the nearest vertex


def test_a_floor_reaching_behind_the_camera_is_clipped():
    # a 4 m floor 0.3 m below the camera, from 1 m behind it to 3 m ahead, with a board standing on it
    floor = scenes.textured_plane(
        scenes.checkerboard((7, 7), 0.5).texture,
        4.0,
        height=4.0,
        R=rotation_from_euler(np.pi / 2, 0, 0),
        t=(0, 0.3, 1.0),
        name="floor",
    )
    out = r.render([floor, scenes.checkerboard((9, 6), 0.05, t=(-0.2, -0.25, 2.0))], K, depth=True)
    ok, corners = cv2.findChessboardCornersSB(out.image, (9, 6))
    assert (
        ok
        and _rms(
            r.align_detected_corners(corners, out.truth.corners("board")),
            out.truth.corners("board"),
        )
        < 0.1
    )
    # the floor fills the bottom rows up to its horizon; the depth there is 0.3 / y_normalised
    v = 470
    assert out.truth.depth[v, 320] == pytest.approx(0.3 / ((v - 239.5) / 800), rel=1e-6)
    assert out.image[470].std() > 5 and np.isinf(out.truth.depth[10, 320])


def test_look_at_and_rotation():
    R, t = r.look_at([1.0, 0, 0], [0, 0, 0])
    assert np.allclose(R @ [0, 0, 0] + t, [0, 0, 1])  # the target is straight ahead, 1 m away
    assert np.allclose(R @ R.T, np.eye(3)) and np.linalg.det(R) == pytest.approx(1)
    with pytest.raises(CamlabInputError, match="eye and target coincide"):
        r.look_at([0, 0, 0], [0, 0, 0])
    with pytest.raises(CamlabInputError, match="parallel to up"):
        r.look_at([0, 0, 0], [0, 0, 1])


def test_look_at_has_one_default_up_everywhere():
    """render.look_at used up = -y and camera.look_at_rotation up = +z: the same call failed in one."""
    eye, target = [3.0, -4.0, 1.5], [0.0, 0.0, 0.5]
    R, t = r.look_at(eye, target)
    np.testing.assert_allclose(R, cm.look_at_rotation(eye, target), atol=1e-15)
    cam = cm.Camera.look_at(eye, target)
    np.testing.assert_allclose(R, cam.R, atol=1e-15)
    np.testing.assert_allclose(t, cam.t, atol=1e-12)
    assert R[1] @ [0, 0, 1] < 0  # the world's up (+z) points up in the image (camera -y)
    for look in (r.look_at, cm.look_at_rotation):  # looking straight down the up axis fails in both
        with pytest.raises(CamlabInputError, match="parallel to up"):
            look([0, 0, 5.0], [0, 0, 0])


def test_bad_inputs():
    board = scenes.checkerboard((4, 3), 0.03, t=(0, 0, 0.5))
    with pytest.raises(CamlabInputError, match=r"scene: expected at least one Plane"):
        r.render([], K)
    with pytest.raises(CamlabInputError, match=r"bits: expected an integer bit depth from 1 to 16"):
        r.render(board, K, sensor=r.Sensor(bits=17))
    with pytest.raises(CamlabInputError, match=r"pattern: expected one of RGGB"):
        r.render(board, K, sensor=r.Sensor(bayer="RGBG"))
    with pytest.raises(CamlabInputError, match=r"pattern_size: expected at least \(2, 2\)"):
        scenes.checkerboard((1, 5), 0.03)
    with pytest.raises(CamlabInputError, match=r"camera R: expected a rotation matrix"):
        r.render(board, K, R=np.diag([1, 1, -1.0]))
    with pytest.raises(
        CamlabInputError, match=r"texture: expected an \(H, W\) or \(H, W, 3\) image"
    ):
        scenes.textured_plane(np.zeros((4, 4, 2)), 1.0)
    with pytest.raises(CamlabInputError, match=r"supersample: expected an integer from 1 to 8"):
        r.render(board, K, supersample=0)
    with pytest.raises(CamlabInputError, match=r"detected: expected 12 corners"):
        r.align_detected_corners(np.zeros((5, 2)), np.zeros((12, 2)))


def test_align_detected_corners_undoes_reversal_and_opencv4_shape():
    gt = scenes.checkerboard((4, 3), 0.03, t=(0, 0, 0.5)).points * 1000 + 100
    det4 = gt[::-1].reshape(-1, 1, 2) + 0.01  # OpenCV 4 shape, reversed order
    assert np.allclose(r.align_detected_corners(det4, gt), gt + 0.01)
    assert np.allclose(r.align_detected_corners(gt - 0.01, gt), gt - 0.01)
