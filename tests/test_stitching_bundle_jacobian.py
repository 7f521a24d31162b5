"""The analytic Jacobian of bundle adjustment against central differences (issue: compute at library speed)."""

import contextlib

import numpy as np
import pytest

from camlab.camera import rotation_from_axis_angle
from camlab.optimise import huber_jacobian, huber_residuals, numeric_jacobian
from camlab.stitching import bundle_jacobian as bj
from camlab.stitching import cameras as cm


def _rng_cameras(rng, n):
    Ks = [cm.intrinsics(f, (480, 640)) for f in rng.uniform(400, 900, n)]
    Rs = [rotation_from_axis_angle(rng.normal(0, 0.3, 3)) for _ in range(n)]
    return Ks, Rs


@contextlib.contextmanager
def _captured_problem(monkeypatch):
    """The residuals, start and Jacobian an adjustment hands to Levenberg-Marquardt (which never runs)."""
    seen = {}

    def capture(residuals, x0, jacobian, **kw):
        seen.update(residuals=residuals, x0=x0, jacobian=jacobian)
        raise StopIteration

    monkeypatch.setattr(cm, "levenberg_marquardt", capture)
    with pytest.raises(StopIteration):
        yield seen


def _noise_and_outliers(rng, shape):
    """0.3 px noise, and every third match 15 px off: inside and beyond the Huber threshold
    (2 px), none so near it that a difference step straddles its kink."""
    e = rng.normal(0, 0.3, shape)
    e[::3] += 15 * rng.choice([-1, 1], (len(e[::3]), 2))
    return e


def test_left_jacobian_turns_a_change_of_the_rotation_vector_into_a_turn_on_the_left():
    rng = np.random.default_rng(0)
    for w in (rng.normal(0, 1, 3), [1e-7, 0, 2e-7], [0.0, 0.0, 3.0]):
        J = bj.left_jacobian(w)
        for p in range(3):
            dw = np.zeros(3)
            dw[p] = 1e-6
            turn = (
                rotation_from_axis_angle(np.add(w, dw)) @ rotation_from_axis_angle(w).T
                - rotation_from_axis_angle(np.subtract(w, dw)) @ rotation_from_axis_angle(w).T
            ) / 2e-6
            np.testing.assert_allclose([turn[2, 1], turn[0, 2], turn[1, 0]], J[:, p], atol=1e-8)


def test_transfer_error_jacobians_equal_central_differences():
    rng = np.random.default_rng(1)
    (K_i, K_j), (R_i, R_j) = _rng_cameras(rng, 2)
    x_i = rng.uniform([0, 0], [640, 480], (25, 2))
    d_i, d_j = bj.transfer_error_jacobians(K_i, R_i, K_j, R_j, x_i)

    def errors(params):  # f_i, delta_i, f_j, delta_j
        Ki, Kj = K_i.copy(), K_j.copy()
        Ki[0, 0] = Ki[1, 1] = params[0]
        Kj[0, 0] = Kj[1, 1] = params[4]
        Ri = rotation_from_axis_angle(params[1:4]) @ R_i
        Rj = rotation_from_axis_angle(params[5:8]) @ R_j
        return cm.pair_transfer_errors(Ki, Ri, Kj, Rj, x_i, np.zeros_like(x_i)).ravel()

    x0 = np.r_[K_i[0, 0], 0, 0, 0, K_j[0, 0], 0, 0, 0]
    numeric = numeric_jacobian(errors, x0)
    analytic = np.concatenate([d_i, d_j], axis=2).reshape(-1, 8)
    np.testing.assert_allclose(analytic, numeric, rtol=1e-6, atol=1e-6 * np.abs(numeric).max())


def test_huber_jacobian_equals_central_differences_inside_and_beyond_the_threshold():
    e = np.array([[0.3, -0.4], [3.0, 4.0], [-2.5, 0.1]])
    D = huber_jacobian(e, 1.0)
    for n in range(len(e)):
        numeric = numeric_jacobian(lambda v: huber_residuals(v[None], 1.0)[0], e[n])
        np.testing.assert_allclose(D[n], numeric, atol=1e-8)
    with pytest.raises(Exception, match="delta"):
        huber_jacobian(e, 0.0)


@pytest.mark.parametrize("focal", [True, False])
def test_the_assembled_bundle_jacobian_equals_central_differences(monkeypatch, focal):
    """bundle_adjust's own residuals and Jacobian (Huber, left Jacobians, two blocks a row) at a
    point away from the start, where the rotation vectors are not zero and some matches are
    beyond the Huber threshold."""
    rng = np.random.default_rng(2)
    Ks, Rs = _rng_cameras(rng, 3)
    matches = {}
    for i, j in ((0, 1), (1, 2), (0, 2)):
        a = rng.uniform([0, 0], [640, 480], (30, 2))
        b = cm.pair_transfer_errors(Ks[i], Rs[i], Ks[j], Rs[j], a, np.zeros_like(a))
        matches[(i, j)] = (a, b + _noise_and_outliers(rng, b.shape))
    with _captured_problem(monkeypatch) as seen:
        cm.bundle_adjust(Ks, Rs, matches, focal=focal)
    x = seen["x0"] + rng.normal(0, 0.05, len(seen["x0"])) * np.where(seen["x0"] > 100, 100, 1)
    analytic = seen["jacobian"](x)
    numeric = numeric_jacobian(seen["residuals"], x)
    assert analytic.shape == numeric.shape == (4 * 90, (4 if focal else 3) * 3 - 3)
    np.testing.assert_allclose(analytic, numeric, rtol=1e-6, atol=1e-6 * np.abs(numeric).max())


def test_the_assembled_homography_adjustment_jacobian_equals_central_differences(monkeypatch):
    rng = np.random.default_rng(3)
    Hs = [np.eye(3)] + [
        np.array([[1.0, 0.05, 200.0 * k], [-0.03, 1.02, 15.0 * k], [1e-5, -2e-5, 1.0]])
        + rng.normal(0, 1e-3, (3, 3)) * [[1, 1, 100], [1, 1, 100], [1e-3, 1e-3, 0]]
        for k in (1, 2)
    ]
    matches = {}
    for i, j in ((0, 1), (1, 2), (0, 2)):
        a = rng.uniform([0, 0], [640, 480], (30, 2))
        b = cm._project(np.linalg.inv(Hs[j]) @ Hs[i], a)
        matches[(i, j)] = (a, b + _noise_and_outliers(rng, b.shape))
    with _captured_problem(monkeypatch) as seen:
        cm.adjust_homographies(Hs, matches, reference=0)
    x = seen["x0"] * (1 + rng.normal(0, 1e-3, len(seen["x0"])))
    analytic = seen["jacobian"](x)
    # h31, h32 ~ 1e-5 move a pixel by 640 x their step: a step of 1e-8, not the default 1e-6,
    # keeps central differences' own error (h^2 terms) under the 1e-6 the test asks
    numeric = numeric_jacobian(seen["residuals"], x, step=1e-8)
    assert analytic.shape == numeric.shape == (4 * 90, 16)
    scale = np.abs(numeric).max(axis=0)  # columns differ by orders of magnitude (h31 vs h13)
    np.testing.assert_allclose(analytic / scale, numeric / scale, atol=1e-6)
