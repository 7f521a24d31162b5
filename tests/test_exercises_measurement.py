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


def test_pose_covariance_accepts_a_solve_and_a_pseudo_inverse(capsys):
    def solved(J, r):
        return (r @ r) / (len(r) - 6) * np.linalg.solve(J.T @ J, np.eye(6))

    def pseudo(J, r):
        return np.linalg.pinv(J) @ np.linalg.pinv(J).T * np.sum(r**2) / (len(r) - 6)

    assert check("pose_covariance", solved).passed is True
    assert check("pose_covariance", pseudo).passed is True


def test_pose_from_homography_names_a_returned_pair_and_accepts_averaged_norms(capsys):
    def averaged(K, H):  # 1 / lambda as the mean of ||K^-1 h1|| and ||K^-1 h2|| (lesson 12, cell 4)
        A = np.linalg.solve(K, H)
        lam = 2 / (np.linalg.norm(A[:, 0]) + np.linalg.norm(A[:, 1])) * np.sign(A[2, 2])
        r1, r2, t = lam * A[:, 0], lam * A[:, 1], lam * A[:, 2]
        return np.column_stack([r1, r2, np.cross(r1, r2), t])

    def pair(K, H):
        Rt = averaged(K, H)
        return Rt[:, :3], Rt[:, 3]

    assert check("pose_from_homography", averaged).passed is True
    with pytest.raises(AssertionError) as info:
        check("pose_from_homography", pair)
    assert "np.column_stack([R, t])" in str(info.value)
