"""Lesson 11's exercise checks: the rectifying rotation and the triangulation's accepted forms."""

import numpy as np
import pytest

import camlab.exercises.stereo_rectification  # noqa: F401  (registers the lesson's exercises)
from camlab.exercises import EXERCISES, check


def _skew(x):
    u, v = x
    return np.array([[0, -1, v], [1, 0, -u], [-v, u, 0]], dtype=float)


def _six_rows(P1, P2, x1, x2, scaled):
    A = np.vstack([_skew(x1) @ np.asarray(P1), _skew(x2) @ np.asarray(P2)])
    if scaled:
        A /= np.linalg.norm(A, axis=1, keepdims=True)
    Xh = np.linalg.svd(A)[2][-1]
    return Xh[:3] / Xh[3]


def _midpoint(P1, P2, x1, x2):
    rays = []
    for P, x in ((np.asarray(P1), x1), (np.asarray(P2), x2)):
        M = P[:, :3]
        d = np.linalg.solve(M, np.append(x, 1.0))
        rays.append((-np.linalg.solve(M, P[:, 3]), d / np.linalg.norm(d)))
    (C1, d1), (C2, d2) = rays
    s = np.linalg.lstsq(np.c_[d1, -d2], C2 - C1, rcond=None)[0]
    return (C1 + s[0] * d1 + C2 + s[1] * d2) / 2


@pytest.mark.parametrize(
    "answer",
    [lambda *a: _six_rows(*a, scaled=True), _midpoint],
    ids=["six rows scaled (H&Z 12.2)", "midpoint of the rays"],
)
def test_triangulate_point_accepts_other_least_squares_forms(answer, capsys):
    assert check("triangulate_point", answer).passed


def test_triangulate_point_names_the_unscaled_six_row_form():
    with pytest.raises(AssertionError, match=r"likely cause: you kept all three rows"):
        check("triangulate_point", lambda *a: _six_rows(*a, scaled=False))


def test_rectifying_rotation_reference_aligns_rows_and_accepts_another_form(capsys):
    ex = EXERCISES["rectifying_rotation"]
    assert ex.lesson == "11" and check("rectifying_rotation", ex.reference).passed
    for C1, C2, R1 in ex.cases():
        R = ex.reference(C1, C2, R1)
        np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-12)
        assert np.linalg.det(R) > 0 and R[2] @ R1[2] > 0  # a rotation that still looks forward
        # the baseline in the new frame is (B, 0, 0): both centres on one row, epipoles at (1, 0, 0)
        b = R @ (np.asarray(C2) - C1)
        np.testing.assert_allclose(b[1:], 0, atol=1e-12)
        assert b[0] > 0

    def z_first(C1, C2, R1):  # the old axis made orthogonal to x first, then y = z × x: as valid
        x = np.subtract(C2, C1) / np.linalg.norm(np.subtract(C2, C1))
        z = np.asarray(R1)[2] - (np.asarray(R1)[2] @ x) * x
        z /= np.linalg.norm(z)
        return [list(x), list(np.cross(z, x)), list(z)]

    assert check("rectifying_rotation", z_first).passed


@pytest.mark.parametrize("index", range(6))
def test_rectifying_rotation_names_each_typical_slip(index):
    wrong, needle = EXERCISES["rectifying_rotation"].wrong_variants[index]
    with pytest.raises(AssertionError, match=r"likely cause: .*" + needle):
        check("rectifying_rotation", wrong)


def test_eight_point_names_division_by_the_image_size_without_centring():
    from camlab.exercises.stereo_rectification.eight_point import _scaled_not_centred

    with pytest.raises(AssertionError, match=r"did not centre them \(divided by the image size\)"):
        check("eight_point", lambda x1, x2: _scaled_not_centred(x1, x2, (1 / 640, 1 / 480)))


def _polyfit_vertex(ds, cost):  # the same parabola by least squares through the three samples
    k = int(np.argmin(cost))
    a, b, _ = np.polyfit(np.asarray(ds[k - 1 : k + 2], float), cost[k - 1 : k + 2], 2)
    return -b / (2 * a)


def _gradient_step(
    ds, cost
):  # Newton's step on finite differences: d - c'(d) / c''(d), the same vertex
    c = np.asarray(cost, float)
    k = int(np.argmin(c))
    return np.float32(ds[k] - (c[k + 1] - c[k - 1]) / 2 / (c[k + 1] - 2 * c[k] + c[k - 1]))


@pytest.mark.parametrize(
    "answer", [_polyfit_vertex, _gradient_step], ids=["np.polyfit", "Newton step, float32"]
)
def test_subpixel_disparity_accepts_other_forms(answer, capsys):
    assert check("subpixel_disparity", answer).passed


@pytest.mark.parametrize(
    "slip, needle",
    [
        (lambda ds, c: ds[np.argmax(c[1:-1]) + 1], "largest cost"),
        (
            lambda ds, c: (
                ds[np.argmin(c)]
                + (c[np.argmin(c) - 1] - c[np.argmin(c) + 1])
                / (2 * (c[np.argmin(c) - 1] + 2 * c[np.argmin(c)] + c[np.argmin(c) + 1]))
            ),
            "denominator",
        ),
        (lambda ds, c: float(np.argmin(c)), "index"),
    ],
    ids=["argmax", "denominator sign", "index, no refinement"],
)
def test_subpixel_disparity_names_each_typical_slip(slip, needle):
    with pytest.raises(AssertionError, match=r"likely cause: .*" + needle):
        check("subpixel_disparity", slip)


def test_index_errors_get_each_exercises_own_cause():
    """argmax in subpixel_disparity and P's columns in triangulate_point raise IndexError: name those slips."""

    def argmax_winner(ds, cost):
        ds, c = np.asarray(ds, float), np.asarray(cost, float)
        k = int(np.argmax(c))
        return float(ds[k] + (c[k - 1] - c[k + 1]) / (2 * (c[k - 1] - 2 * c[k] + c[k + 1])))

    def columns_of_p(P1, P2, x1, x2):
        P1, P2 = np.asarray(P1), np.asarray(P2)
        (u1, v1), (u2, v2) = x1, x2
        A = np.array(
            [
                u1 * P1[:, 2] - P1[:, 0],
                v1 * P1[:, 2] - P1[:, 1],
                u2 * P2[:, 2] - P2[:, 0],
                v2 * P2[:, 2] - P2[:, 1],
            ]
        )
        Xh = np.linalg.svd(A)[2][-1]
        return Xh[:3] / Xh[3]

    for name, wrong, needle in (
        ("subpixel_disparity", argmax_winner, "did you take argmax"),
        ("triangulate_point", columns_of_p, "ROWS of P"),
    ):
        with pytest.raises(AssertionError) as info:
            check(name, wrong)
        message = str(info.value)
        assert needle in message and "(N, 3) array of points" not in message, message


def test_prompts_that_ask_for_an_array_reject_a_list():
    """triangulate_point and disparity_to_depth ask for an array: a list is named, as in the rest of the course."""
    reference = EXERCISES["triangulate_point"].teaching
    with pytest.raises(AssertionError, match=r"you returned a list(.|\n)*np\.array"):
        check("triangulate_point", lambda *a: list(reference(*a)))


def test_hartley_H2_accepts_another_scale_and_a_rotation_built_from_the_direction(capsys):
    """Any scale passes, and so does R built from the epipole's unit direction (no angle)."""
    from camlab.exercises.stereo_rectification.hartley import hartley_H2

    def from_direction(e2, image_size):
        w, h = image_size
        T = np.array([[1, 0, -(w - 1) / 2], [0, 1, -(h - 1) / 2], [0, 0, 1.0]])
        eT = T @ np.asarray(e2, float)
        d = eT[:2] / eT[2]
        d = d / np.linalg.norm(d) * np.sign(d[0])  # the smaller turn: the direction with u > 0
        R = np.array([[d[0], d[1], 0], [-d[1], d[0], 0], [0, 0, 1.0]])
        f = (R @ eT)[0] / (R @ eT)[2]
        return -2.5 * np.array([[1, 0, 0], [0, 1, 0], [-1 / f, 0, 1]]) @ R @ T

    assert check("hartley_H2", from_direction).passed
    assert check("hartley_H2", lambda e, s: 7 * hartley_H2(e, s)).passed


def test_hartley_H2_names_an_unsigned_f_apart_from_a_wrong_G31_sign():
    """f = |e| (cell 19's old word 'distance') and G31 = +1/f tie when f < 0: each gets its own cause."""
    from camlab.exercises.stereo_rectification.hartley import _h2

    with pytest.raises(AssertionError) as info:
        check("hartley_H2", lambda e, s: _h2(e, s, signed_f=False))
    assert "f is signed" in str(info.value) and "G31 = +1/f" not in str(info.value), str(info.value)
    with pytest.raises(AssertionError) as info:
        check("hartley_H2", lambda e, s: _h2(e, s, g_sign=1.0))
    assert "G31 = +1/f" in str(info.value) and "f is signed" not in str(info.value), str(info.value)


@pytest.mark.parametrize(
    "keywords, needle",
    [
        (dict(degrees=True), "in degrees"),
        (dict(g_is_f=True), "G31 = -f"),
        (dict(transpose=True), "transposed"),
        (dict(t_in_product=False), "left T out of the product"),
    ],
)
def test_hartley_H2_names_degrees_transpose_g_is_f_and_a_dropped_t(keywords, needle):
    """Each slip a reviewer fed the check gets its own cause, not the generic fallback."""
    from camlab.exercises.stereo_rectification.hartley import _h2

    with pytest.raises(AssertionError) as info:
        check("hartley_H2", lambda e, s: _h2(e, s, **keywords))
    assert needle in str(info.value) and "check T (centre" not in str(info.value), str(info.value)


def test_hartley_H2_wrong_sign_t_is_named_and_the_fallback_never_shows_the_target():
    """T by +c sends the epipole to infinity too: named; an unnamed such H2 never prints [1, -0, 0]."""
    from camlab.exercises.stereo_rectification.hartley import _h2

    def plus_c(e, s):
        return _h2(e, s, centre=(-(s[0] - 1) / 2, -(s[1] - 1) / 2))

    with pytest.raises(AssertionError) as info:
        check("hartley_H2", plus_c)
    assert "translates by +c" in str(info.value), str(info.value)

    def off_centre(e, s):  # an unnamed centre: the epipole still goes to infinity
        return _h2(e, s, centre=((s[0] - 1) / 2 + 37, (s[1] - 1) / 2 - 11))

    with pytest.raises(AssertionError) as info:
        check("hartley_H2", off_centre)
    cause = str(info.value).split("likely cause:")[1]
    assert "does send the epipole to infinity" in cause and "-0" not in cause, cause
