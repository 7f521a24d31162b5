"""camlab.projective.conics: conics and dual conics, their maps by a homography, the circular
points. Every transformation rule is checked against sampled points (and tangent lines), not
against its own formula."""

import cv2
import numpy as np
import pytest

from camlab import projective as pj


def _random_homography(rng, strength=0.002):
    H = np.eye(3) + rng.normal(0, 0.2, (3, 3))
    H[2, :2] = rng.normal(0, strength, 2)
    H[2, 2] = 1.0
    return H


def _similarity(angle, scale, tx, ty):
    c, s = scale * np.cos(angle), scale * np.sin(angle)
    return np.array([[c, -s, tx], [s, c, ty], [0.0, 0.0, 1.0]])


def _up_to_scale(a, b):
    a, b = np.asarray(a) / np.linalg.norm(a), np.asarray(b) / np.linalg.norm(b)
    return min(np.abs(a - b).max(), np.abs(a + b).max()) < 1e-9


def test_conic_matrix_halves_the_cross_terms():
    C = pj.conic_matrix(1.0, 3.0, 2.0, -4.0, 5.0, -6.0)
    x, y = 0.7, -1.3
    value = 1 * x**2 + 3 * x * y + 2 * y**2 - 4 * x + 5 * y - 6
    assert np.isclose(np.array([x, y, 1.0]) @ C @ np.array([x, y, 1.0]), value)
    assert np.array_equal(C, C.T)


def test_circle_conic_holds_its_points():
    t = np.linspace(0, 2 * np.pi, 17)
    pts = np.stack([3 + 2 * np.cos(t), -1 + 2 * np.sin(t), np.ones_like(t)], axis=1)
    C = pj.circle_conic([3, -1], 2)
    assert np.abs(np.einsum("ni,ij,nj->n", pts, C, pts)).max() < 1e-12


@pytest.mark.parametrize("seed", range(5))
def test_map_conic_holds_the_mapped_sampled_points(seed):
    rng = np.random.default_rng(seed)
    H = _random_homography(rng)
    C = pj.circle_conic(rng.normal(0, 5, 2), 3.0)
    pts = pj.conic_points(C, 50)  # points on C
    mapped = pj.to_homogeneous(pj.map_points(H, pts))
    Cp = pj.map_conic(H, C)
    residual = np.abs(np.einsum("ni,ij,nj->n", mapped, Cp, mapped))
    scale = np.linalg.norm(Cp) * np.linalg.norm(mapped, axis=1) ** 2
    assert (residual / scale).max() < 1e-10
    assert np.array_equal(Cp, Cp.T)
    # the wrong rules do not hold them
    for wrong in (H.T @ C @ H, H @ C @ H.T):
        r = np.abs(np.einsum("ni,ij,nj->n", mapped, wrong, mapped)) / (
            np.linalg.norm(wrong) * np.linalg.norm(mapped, axis=1) ** 2
        )
        assert r.max() > 1e-3


@pytest.mark.parametrize("seed", range(3))
def test_map_dual_conic_holds_the_mapped_tangent_lines(seed):
    rng = np.random.default_rng(seed)
    H = _random_homography(rng)
    C = pj.conic_matrix(2.0, 0.5, 1.0, -1.0, 0.3, -4.0)
    pts = pj.to_homogeneous(pj.conic_points(C, 30))
    tangents = pts @ C  # l = C x at each point (C symmetric)
    mapped_lines = pj.map_lines(H, tangents)
    Cs = pj.map_dual_conic(H, pj.dual_conic(C))
    residual = np.abs(np.einsum("ni,ij,nj->n", mapped_lines, Cs, mapped_lines))
    assert (
        residual / (np.linalg.norm(Cs) * np.linalg.norm(mapped_lines, axis=1) ** 2)
    ).max() < 1e-10
    # and it is the dual of the mapped point conic
    assert _up_to_scale(Cs, pj.dual_conic(pj.map_conic(H, C)))


def test_dual_conic_is_the_inverse_up_to_scale_and_exists_for_a_line_pair():
    C = pj.conic_matrix(2.0, 0.5, 1.0, -1.0, 0.3, -4.0)
    assert np.allclose(pj.dual_conic(C), np.linalg.det(C) * np.linalg.inv(C))
    # a line pair l m^T + m l^T is rank 2: no inverse, but an adjugate (of rank 1: the meet point)
    l, m = np.array([1.0, 0.0, -1.0]), np.array([0.0, 1.0, -2.0])  # noqa: E741 (the book's names)
    pair = np.outer(l, m) + np.outer(m, l)
    adj = pj.dual_conic(pair)
    assert np.linalg.matrix_rank(adj) == 1
    assert _up_to_scale(adj[np.argmax(np.abs(adj).sum(1))], np.cross(l, m))


def test_circular_points_are_fixed_by_similarities_only():
    I, J = pj.CIRCULAR_POINTS  # noqa: E741 (the book's names)
    assert np.allclose(np.outer(I, J) + np.outer(J, I), 2 * pj.DUAL_CONIC_AT_INFINITY)
    S = _similarity(0.7, 2.5, 10.0, -3.0)
    for p in (I, J):
        q = S @ p
        assert np.allclose(q / q[0], p)
    assert _up_to_scale(pj.map_dual_conic(S, pj.DUAL_CONIC_AT_INFINITY), pj.DUAL_CONIC_AT_INFINITY)
    A = np.array([[1.5, 0.2, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])  # an affinity moves them
    q = A @ I
    assert not np.allclose(q / q[0], I)
    assert not _up_to_scale(
        pj.map_dual_conic(A, pj.DUAL_CONIC_AT_INFINITY), pj.DUAL_CONIC_AT_INFINITY
    )
    # every circle passes through I and J
    C = pj.circle_conic([4.0, -2.0], 3.0)
    assert abs(I @ C @ I) < 1e-12 and abs(J @ C @ J) < 1e-12


def test_conic_points_agree_with_opencv_ellipse_fit():
    C = pj.map_conic(
        np.array([[1.2, 0.3, 5.0], [-0.1, 0.9, 2.0], [0.002, 0.001, 1.0]]),
        pj.circle_conic([40, 30], 20),
    )
    pts = pj.conic_points(C, 64)
    (cx, cy), (w, h), _ = cv2.fitEllipse(pts[:-1].astype(np.float32))
    ours_centre = pts[:-1].mean(0)  # uniform in the parameter: the mean is the centre
    assert np.allclose([cx, cy], ours_centre, atol=1e-2)
    assert np.allclose(pts[0], pts[-1])


def test_bad_conics_name_the_fix():
    with pytest.raises(pj.CamlabInputError, match="symmetric.*halve the cross terms"):
        pj.map_conic(np.eye(3), [[1, 2, 0], [0, 1, 0], [0, 0, -1]])
    with pytest.raises(pj.CamlabInputError, match=r"expected a \(3, 3\) matrix"):
        pj.map_conic(np.eye(3), np.eye(2))
    with pytest.raises(pj.DegenerateError, match="singular"):
        pj.map_conic(np.zeros((3, 3)), np.eye(3))
    with pytest.raises(pj.DegenerateError, match="not an ellipse"):
        pj.conic_points(pj.conic_matrix(1, 0, -1, 0, 0, -1))  # x^2 - y^2 = 1
    with pytest.raises(pj.DegenerateError, match="imaginary"):
        pj.conic_points(np.eye(3))  # x^2 + y^2 + 1 = 0
    with pytest.raises(pj.CamlabInputError, match="radius"):
        pj.circle_conic([0, 0], -1)


def test_inputs_are_not_modified():
    H = np.array([[1.2, 0.3, 5.0], [-0.1, 0.9, 2.0], [0.002, 0.001, 1.0]])
    C = pj.circle_conic([1, 2], 3)
    H0, C0 = H.copy(), C.copy()
    pj.map_conic(H, C), pj.map_dual_conic(H, C), pj.dual_conic(C), pj.conic_points(C)
    assert np.array_equal(H, H0) and np.array_equal(C, C0)


def test_line_angle_reads_the_plane_angle_off_a_photo():
    """60 deg on the plane, seen through a projective H: the image's own angle differs, H C*inf H^T gives 60 back."""
    H = np.array([[1.2, 0.3, 5.0], [-0.1, 0.9, 2.0], [0.02, 0.01, 1.0]])
    l60, m = (
        np.array([np.sin(np.radians(60)), -np.cos(np.radians(60)), 0.5]),
        np.array([0.0, 1.0, -1.0]),
    )
    l_img, m_img = pj.map_lines(H, l60), pj.map_lines(H, m)
    C_img = pj.map_dual_conic(H, pj.DUAL_CONIC_AT_INFINITY)
    assert np.isclose(np.degrees(pj.line_angle(l60, m)), 60.0)
    assert np.isclose(
        np.degrees(pj.line_angle(-2 * l_img, m_img, -3 * C_img)), 60.0
    )  # any scale, sign
    assert abs(np.degrees(pj.line_angle(l_img, m_img)) - 60.0) > 5
    with pytest.raises(pj.CamlabInputError, match="l2: expected a line"):
        pj.line_angle(l60, [0.0, 1.0])
