"""The shared validators in camlab._validate: one home per check, each message pinned."""

import numpy as np
import pytest

from camlab._validate import (
    CamlabInputError,
    PointPairs,
    as_point_pairs,
    check_intrinsics,
    check_pose,
    check_positive,
    check_rotation,
    check_size,
)
from camlab.camera import Camera, rotation_from_axis_angle

K = np.array([[800.0, 0.0, 320.0], [0.0, 780.0, 240.0], [0.0, 0.0, 1.0]])


# ------------------------------------------------------------------ check_intrinsics


def test_intrinsics_accepts_a_calibration_matrix_and_copies_it():
    out = check_intrinsics(K)
    assert np.array_equal(out, K) and out is not K
    out[0, 0] = 1.0
    assert K[0, 0] == 800.0


@pytest.mark.parametrize(
    "bad, match",
    [
        (
            np.diag([-800.0, 780.0, 1.0]),
            r"K: expected an intrinsic matrix .* got fx = -800, fy = 780 \(a mirrored or singular K\)",
        ),
        (np.diag([800.0, -780.0, 1.0]), r"fy = -780 \(a mirrored"),
        (np.diag([0.0, 780.0, 1.0]), r"fx = 0, fy = 780"),
        (
            [[800, 0, 320], [0, 780, 240], [0, 1e-3, 1]],
            r"not upper triangular with last row \(0, 0, 1\)",
        ),
        ([[800, 0, 320], [5, 780, 240], [0, 0, 1]], r"not upper triangular"),
        ([[800, 0, 320], [0, 780, 240], [0, 0, 0]], r"not upper triangular"),
        (
            2 * K,
            r"got \[\[1600.0, 0.0, 640.0\], \[0.0, 1560.0, 480.0\], \[0.0, 0.0, 2.0\]\] \(not upper triangular",
        ),
        (-K, r"not upper triangular with last row \(0, 0, 1\)"),
        (
            [[800, 0, np.nan], [0, 780, 240], [0, 0, 1]],
            r"K: expected finite values, found nan at index \(0, 2\)",
        ),
        (np.eye(2), r"K: expected a \(3, 3\) matrix, got shape \(2, 2\)"),
        ("K", r"K: expected numbers convertible to a float array"),
    ],
)
def test_intrinsics_rejects(bad, match):
    with pytest.raises(CamlabInputError, match=match):
        check_intrinsics(bad)


def test_intrinsics_names_the_argument():
    with pytest.raises(CamlabInputError, match=r"^new_K: expected an intrinsic matrix"):
        check_intrinsics(np.diag([-1.0, 1.0, 1.0]), "new_K")


def test_every_module_rejects_a_mirrored_k():
    """The homography helpers used to accept a mirrored K (they only checked det K != 0)."""
    from camlab import distortion, homography
    from camlab.calibration import optimal_new_camera_matrix

    mirrored = np.diag([-800.0, 800.0, 1.0])
    calls = [
        lambda: homography.rotation_homography(mirrored, np.eye(3)),
        lambda: homography.pose_homography(mirrored, np.eye(3), [0, 0, 1]),
        lambda: distortion.undistort_pixels([[1.0, 2.0]], mirrored, (0.1, 0, 0, 0, 0)),
        lambda: optimal_new_camera_matrix(mirrored, None, (640, 480), 0.0),
        lambda: Camera(mirrored),
    ]
    for call in calls:
        with pytest.raises(CamlabInputError, match="a mirrored or singular K"):
            call()


# ------------------------------------------------------------------ check_rotation / check_pose


def test_rotation_accepts_a_rotation():
    R = rotation_from_axis_angle([0.1, -0.2, 0.3])
    np.testing.assert_array_equal(check_rotation(R), R)


@pytest.mark.parametrize(
    "bad, match",
    [
        (
            np.diag([1.0, 1.0, -1.0]),
            r"R: expected a rotation matrix \(R\^T R = I, det R = \+1\), got det R = -1 \(a reflection\)",
        ),
        (np.diag([1.0, 2.0, 1.0]), r"R: expected a rotation matrix .* max \|R\^T R - I\| = 3"),
        (np.eye(2), r"R: expected a \(3, 3\) matrix"),
    ],
)
def test_rotation_rejects(bad, match):
    with pytest.raises(CamlabInputError, match=match):
        check_rotation(bad)


def test_rotation_tolerance():
    R = np.eye(3) + 1e-7
    assert check_rotation(R).shape == (3, 3)
    with pytest.raises(CamlabInputError, match="max"):
        check_rotation(R, tol=1e-9)


def test_pose_names_both_parts():
    R, t = check_pose(np.eye(3), [[0.0], [0.0], [2.0]], "camera")  # OpenCV 5's (3, 1) t is fine
    np.testing.assert_array_equal(t, [0.0, 0.0, 2.0])
    with pytest.raises(CamlabInputError, match=r"^camera R: expected a rotation matrix"):
        check_pose(2 * np.eye(3), [0, 0, 1], "camera")
    with pytest.raises(
        CamlabInputError, match=r"^camera t: expected a \(3,\) matrix, got shape \(2,\)"
    ):
        check_pose(np.eye(3), [0, 1], "camera")
    with pytest.raises(CamlabInputError, match=r"^t: expected finite values"):
        check_pose(np.eye(3), [0, np.inf, 1])


# ------------------------------------------------------------------ check_size


def test_size_accepts_whole_numbers():
    assert check_size((640, 480)) == (640, 480)
    assert check_size(np.array([640.0, 480.0])) == (640, 480)
    assert isinstance(check_size((np.int64(3), 2))[0], int)


@pytest.mark.parametrize(
    "bad, match",
    [
        (
            (640.7, 480),
            r"size: expected \(width, height\) as whole numbers of pixels, got \(640.7, 480\); round it first",
        ),
        ((0, 480), r"size: expected \(width, height\) of at least 1 x 1 pixels, got \(0, 480\)"),
        ((640, -1), r"at least 1 x 1 pixels, got \(640, -1\)"),
        (("640", "480"), r"size: expected \(width, height\) in pixels, got \('640', '480'\)"),
        ("640x480", r"size: expected \(width, height\) in pixels, got '640x480'"),
        ((640,), r"size: expected \(width, height\) in pixels, got \(640,\)"),
        ((640, 480, 3), r"got \(640, 480, 3\)"),
        (None, r"size: expected \(width, height\) in pixels, got None"),
        ((np.nan, 480), r"size: expected \(width, height\) in pixels"),
    ],
)
def test_size_rejects(bad, match):
    with pytest.raises(CamlabInputError, match=match):
        check_size(bad)


def test_size_minimum_and_name():
    with pytest.raises(
        CamlabInputError,
        match=r"^out: expected \(width, height\) of at least 2 x 2 pixels, got \(1, 5\)",
    ):
        check_size((1, 5), "out", minimum=2)


def test_camera_image_size_is_not_truncated():
    with pytest.raises(
        CamlabInputError, match=r"image_size: expected \(width, height\) as whole numbers"
    ):
        Camera(K, image_size=(640.7, 480))
    assert Camera(K, image_size=(640.0, 480)).image_size == (640, 480)


# ------------------------------------------------------------------ check_positive


def test_positive():
    assert check_positive(2, "f") == 2.0 and isinstance(check_positive(np.float32(2), "f"), float)


@pytest.mark.parametrize(
    "bad, match",
    [
        (0, r"f: expected a positive finite number metres, got 0"),
        (-1.5, r"got -1.5"),
        (np.inf, r"got inf"),
        (np.nan, r"got nan"),
        ("0.05", r"f: expected a positive finite number metres, got str '0.05'; pass a number"),
        (None, r"f: expected a positive finite number metres, got NoneType None; pass a number"),
        (True, r"got bool True"),
        ([1, 2], r"got list \[1, 2\]"),
    ],
)
def test_positive_rejects(bad, match):
    with pytest.raises(CamlabInputError, match=match):
        check_positive(bad, "f", "metres")


# ------------------------------------------------------------------ as_point_pairs


def test_point_pairs_are_a_named_tuple_of_float_copies():
    a = [[1, 2], [3, 4]]
    pairs = as_point_pairs(a, np.array([[5.0, 6.0], [7.0, 8.0]]))
    assert isinstance(pairs, PointPairs) and pairs.single is False
    np.testing.assert_array_equal(pairs.first, [[1.0, 2.0], [3.0, 4.0]])
    assert pairs.first.dtype == float and pairs.second[1, 1] == 8.0
    one = as_point_pairs([1, 2, 3], [4, 5], ("points_world", "points_image"), (3, 2))
    assert one.single and one.first.shape == (1, 3) and one.second.shape == (1, 2)


@pytest.mark.parametrize(
    "a, b, kwargs, match",
    [
        (
            np.zeros((3, 2)),
            np.zeros((4, 2)),
            {"names": ("src", "dst")},
            r"src, dst: expected the same number of points \(row i of src pairs with row i of dst\), got 3 and 4; pass",
        ),
        (
            np.zeros((3, 2)),
            np.zeros((3, 2)),
            {"min_count": 4, "why": "H has 8 degrees of freedom"},
            r"x1: expected \(N, 2\) with N >= 4 point pairs, got shape \(3, 2\); H has 8 degrees of freedom",
        ),
        (np.zeros((5, 3)), np.zeros((5, 2)), {"dims": (2, 2)}, r"x1: expected \(N, 2\) points"),
        (
            np.zeros((5, 2)),
            [[0, 0]] * 4 + [[np.nan, 0]],
            {},
            r"x2: expected finite values, found nan at index \(4, 0\)",
        ),
    ],
)
def test_point_pairs_reject(a, b, kwargs, match):
    with pytest.raises(CamlabInputError, match=match):
        as_point_pairs(a, b, **kwargs)


def test_point_pairs_can_let_non_finite_pairs_through():
    pairs = as_point_pairs([[0, 0], [np.nan, 1]], [[1, 1], [2, 2]], finite=False)
    assert np.isnan(pairs.first[1, 0])


def test_every_pair_check_is_the_shared_one():
    """Homographies, F, rectification, the affine camera and resectioning give the same message."""
    from camlab import affine, camera, epipolar, homography, rectification

    short = np.zeros((3, 2))
    for call in (
        lambda: homography.estimate_homography(short, np.zeros((2, 2))),
        lambda: epipolar.estimate_fundamental_matrix(short, np.zeros((2, 2))),
        lambda: rectification.vertical_disparity(short, np.zeros((2, 2))),
        lambda: affine.estimate_affine_camera(np.zeros((3, 3)), np.zeros((2, 2))),
        lambda: camera.estimate_projection_matrix(np.zeros((3, 3)), np.zeros((2, 2))),
    ):
        with pytest.raises(
            CamlabInputError, match=r"expected the same number of points \(row i of .* got 3 and 2"
        ):
            call()
