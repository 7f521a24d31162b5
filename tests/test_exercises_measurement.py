"""Lesson 12's exercises accept a right answer in another valid form, and name each typical mistake."""

import numpy as np
import pytest

from camlab.exercises import all_exercises, check

all_exercises()  # registers lesson 12's exercises (a lesson reaches them through check_<name>)


def test_pose_from_homography_accepts_other_valid_forms(capsys):
    def by_h2_and_svd(K, H):  # scale from h2, then the nearest rotation by SVD (Zhang's appendix C)
        A = np.linalg.inv(K) @ H
        lam = 1 / np.linalg.norm(A[:, 1]) * np.sign(A[2, 2])
        r1, r2, t = lam * A[:, 0], lam * A[:, 1], lam * A[:, 2]
        U, _, Vt = np.linalg.svd(np.column_stack([r1, r2, np.cross(r1, r2)]))
        return np.hstack([U @ Vt, t[:, None]])

    assert check("pose_from_homography", by_h2_and_svd).passed is True


def test_length_on_plane_accepts_rows_and_a_solve(capsys):
    def rows(H, a, b):  # points as rows: x @ inv(H).T, then the norm
        p = np.array([[*a, 1.0], [*b, 1.0]]) @ np.linalg.inv(H).T
        p = p[:, :2] / p[:, 2:]
        return float(np.hypot(*(p[0] - p[1])))

    def solved(H, a, b):  # np.linalg.solve instead of an inverse
        pa, pb = (np.linalg.solve(H, np.append(x, 1.0)) for x in (a, b))
        return np.linalg.norm(pa[:2] / pa[2] - pb[:2] / pb[2])

    assert check("length_on_plane", rows).passed is True
    assert check("length_on_plane", solved).passed is True


def test_max_depth_accepts_a_numerical_root(capsys):
    def bisect(f, B, sigma_d, max_error):
        lo, hi = 0.0, 1e4
        for _ in range(200):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if mid**2 * sigma_d / (f * B) < max_error else (lo, mid)
        return lo

    assert check("max_depth", bisect).passed is True


@pytest.mark.parametrize(
    ("wrong", "phrase"),
    [
        (lambda K, H: np.hstack([np.eye(3), np.ones((3, 1))]).tolist(), ""),
        (lambda K, H: None, "return"),
    ],
)
def test_pose_from_homography_rejects_a_list_and_none(wrong, phrase):
    with pytest.raises(AssertionError) as info:
        check("pose_from_homography", wrong)
    assert phrase in str(info.value)
