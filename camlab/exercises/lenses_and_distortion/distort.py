"""Lesson 02's exercise distort_pixels: section 4's distortion model applied in pixels, between K^-1 and K."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import distortion
from .._answers import same_array, shape_problem
from .._core import Exercise, Mistake, first_mistake, register_exercise
from ._distort_causes import (
    ROUNDED_HINT,
    back_with,
    brown_variant,
    distort_cases,
    in_place_distortion,
    model_diagnosis,
    normalised_with,
    pixel_variant,
    rounded_positions,
    tangential_terms,
    transposed_k,
)

_PIXEL_MISTAKES = (
    Mistake(
        "uv returned",
        lambda s: np.any(s.d) and np.allclose(s.g, s.uv),
        (
            "you returned uv itself, unchanged: the model was never applied (or you left out the radial factor, "
            "when the case has no tangential terms); normalise, x_d = x L + (tangential terms) with "
            "L = 1 + k1 r^2 + k2 r^4 + k3 r^6, then back to pixels: u_d = f_x x_d + c_x, v_d = f_y y_d + c_y"
        ),
    ),
    Mistake(
        "row 0 skipped",
        lambda s: (
            len(s.g) > 1
            and np.allclose(s.g[1:], s.expected[1:])
            and not np.allclose(s.g[0], s.expected[0])
        ),
        "every row is right but the first: a loop over the points that skipped point 0 (range(1, N)? Python "
        "counts from 0); or drop the loop, the array formulas handle all N rows at once",
    ),
    Mistake(
        "one f on the way back",
        lambda s: back_with(s, s.f[[0, 0]]) or back_with(s, s.f[[1, 1]]),
        "the way in is right, but back to pixels you used one focal length for both: u_d = f_x x_d + c_x with "
        "f_x = K[0, 0], v_d = f_y y_d + c_y with f_y = K[1, 1]",
    ),
    Mistake("rounded", rounded_positions, ROUNDED_HINT),
    Mistake(
        "model on pixels",
        lambda s: np.allclose(s.g, distortion.distort_points(s.uv, s.d)),
        (
            "you applied the model to pixel coordinates; it works on normalised ones: x = (u - c_x) / f_x, "
            "y = (v - c_y) / f_y first, then u_d = f_x x_d + c_x, v_d = f_y y_d + c_y"
        ),
    ),
    Mistake(
        "normalised coordinates returned",
        lambda s: np.allclose(s.g, s.x_d),
        (
            "you returned normalised coordinates; map them back to pixels: u_d = f_x x_d + c_x, v_d = f_y y_d + c_y"
        ),
    ),
    Mistake(
        "undistorted",
        lambda s: (
            np.any(s.d) and np.allclose(s.g, distortion.undistort_pixels(s.uv, s.K, s.d), atol=1e-6)
        ),
        (
            "you undistorted: that maps a distorted pixel to the ideal one. This function goes forward, ideal "
            "uv in, distorted out: normalise, apply x_d = x L + (tangential terms) as section 4 writes it, "
            "back to pixels (no inverse, no iteration)"
        ),
    ),
    Mistake(
        "tangential terms in pixels",
        lambda s: (
            s.tangential.any()
            and np.allclose(s.g, (s.x_d - s.tangential) * s.f + s.c + s.tangential)
        ),
        (
            "your tangential terms are in normalised units but were added to pixels (so they shrink to "
            "~1e-3 px): add them to x L before scaling, u_d = f_x (x L + 2 p1 x y + p2 (r^2 + 2 x^2)) + c_x"
        ),
    ),
    *(
        Mistake(name, normalised_with(f_wrong, c_wrong), hint)
        for name, f_wrong, c_wrong, hint in (
            (
                "no principal point",
                lambda s: s.f,
                lambda s: 0 * s.c,
                "subtract the principal point before dividing by the focal length, x = (u - c_x) / f_x, "
                "and add it back afterwards: distortion grows from the optical axis, not from pixel (0, 0). "
                "(With matrices on row points: np.c_[uv, ones] @ np.linalg.inv(K) without .T, its first two "
                "columns taken, drops c just so; use @ np.linalg.inv(K).T, then @ K.T, and divide by w)",
            ),
            (
                "f_x for v",
                lambda s: s.f[[0, 0]],
                lambda s: s.c,
                "v goes with f_y = K[1, 1], not f_x: x = (u - c_x) / f_x, y = (v - c_y) / f_y",
            ),
            (
                "f_x and f_y swapped",
                lambda s: s.f[::-1],
                lambda s: s.c,
                "f_x = K[0, 0] goes with u and f_y = K[1, 1] with v: you swapped them",
            ),
            (
                "c_x and c_y swapped",
                lambda s: s.f,
                lambda s: s.c[::-1],
                "c_x = K[0, 2] and c_y = K[1, 2]: you swapped them",
            ),
            (
                "image centre (319.5, 239.5)",
                lambda s: s.f,
                lambda s: np.array([319.5, 239.5]),
                "you used the image centre as the principal point; take it from K, "
                "c_x = K[0, 2], c_y = K[1, 2]: a calibrated camera's is off the centre",
            ),
            (
                "image centre (320, 240)",
                lambda s: s.f,
                lambda s: np.array([320.0, 240.0]),
                "you used the image centre as the principal point; take it from K, "
                "c_x = K[0, 2], c_y = K[1, 2]: a calibrated camera's is off the centre",
            ),
            (
                "no division by f",
                lambda s: np.ones(2),
                lambda s: s.c,
                "you subtracted c but did not divide by f: the model works on normalised coordinates, "
                "x = (u - c_x) / f_x, y = (v - c_y) / f_y, and maps back with u_d = f_x x_d + c_x",
            ),
            *(
                (
                    f"c {k:+d}",
                    lambda s: s.f,
                    lambda s, k=k: s.c + k,
                    "a one-pixel shift of the principal point (1-based pixels?): take c_x = K[0, 2], "
                    "c_y = K[1, 2] as they are; pixel centres sit at integers counted from 0",
                )
                for k in (1, -1)
            ),
            (
                "c + 0.5",
                lambda s: s.f,
                lambda s: s.c + 0.5,
                "a half-pixel shift: the principal point is K[0, 2], K[1, 2] as it is (pixel centres sit at "
                "integers)",
            ),
            (
                "c - 0.5",
                lambda s: s.f,
                lambda s: s.c - 0.5,
                "a half-pixel shift: the principal point is K[0, 2], K[1, 2] as it is (pixel centres sit at "
                "integers)",
            ),
        )
    ),
    Mistake(
        "no principal point after",
        lambda s: np.allclose(s.g, s.x_d * s.f),
        (
            "your u_d, v_d lack the principal point: after scaling by f, add c back, u_d = f_x x_d + c_x, "
            "v_d = f_y y_d + c_y. (With a matrix on row points, np.c_[x_d, ones] @ K without .T puts c_x into "
            "the third coordinate, which [:, :2] then drops: use @ K.T)"
        ),
    ),
    Mistake(
        "(v, u) columns",
        lambda s: np.allclose(s.g, s.expected[:, ::-1]),
        (
            "your columns come out as (v, u); return (u, v), the column u first, as uv came in: "
            "np.column_stack([u_d, v_d])"
        ),
    ),
    Mistake(
        "uv read as (v, u)",
        lambda s: (
            np.allclose(s.g, distortion.distort_pixels(s.uv[:, ::-1], s.K, s.d))
            or np.allclose(s.g, distortion.distort_pixels(s.uv[:, ::-1], s.K, s.d)[:, ::-1])
        ),
        (
            "you read uv as (v, u), width and height swapped: uv[:, 0] is u, the column (with f_x and c_x), "
            "uv[:, 1] is v, the row (with f_y and c_y)"
        ),
    ),
    Mistake(
        "normalised in the wrong order",
        lambda s: any(
            np.allclose(s.g, (back + s.c) * s.f if way_out == "wrong" else back * s.f + s.c)
            for way_in, way_out in (("wrong", "wrong"), ("wrong", "right"), ("right", "wrong"))
            for back in [
                distortion.distort_points(s.uv / s.f - s.c if way_in == "wrong" else s.x, s.d)
            ]
        ),
        (
            "normalising is subtract, then divide: x = (u - c_x) / f_x (u / f_x - c_x takes a pixel offset "
            "from a normalised number); undo it in the reverse order, multiply, then add: "
            "u_d = f_x x_d + c_x"
        ),
    ),
    Mistake(
        "K without .T",
        lambda s: transposed_k(s.uv, s.K, s.d, s.g),
        (
            "points are rows, so a matrix acts from the right transposed: normalise with "
            "np.c_[uv, ones] @ np.linalg.inv(K).T and map back with np.c_[x_d, ones] @ K.T (or write "
            "x = (u - c_x) / f_x, y = (v - c_y) / f_y out); K without .T mixes c_x into the third coordinate"
        ),
    ),
    Mistake(
        "the shift returned",
        lambda s: np.allclose(s.g, (s.x_d - s.x) * s.f) or np.allclose(s.g, (s.x - s.x_d) * s.f),
        (
            "you returned the shift in pixels; return where the point lands: u_d = f_x x_d + c_x, v_d = f_y y_d + c_y"
        ),
    ),
    Mistake(
        "half a pixel added to the result",
        lambda s: np.allclose(np.abs(s.g - s.expected), 0.5),
        (
            "every point is off by exactly half a pixel: pixel centres sit at integers here (the centre of a "
            "w-pixel row is (w - 1) / 2), so nothing adds or subtracts 0.5: u_d = f_x x_d + c_x, v_d = f_y y_d + c_y"
        ),
    ),
)
"""Slips in the way to pixels and back (the model's own slips are :func:`._distort_causes.model_diagnosis`),
in the order they are tested, each a test of the answer ``s.g``."""


def _distort_pixels_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    uv, K, d = args
    g = np.asarray(got, dtype=float)
    f, c = np.array([K[0, 0], K[1, 1]]), np.array([K[0, 2], K[1, 2]])
    x = (uv - c) / f  # the ideal points, normalised
    x_d = distortion.distort_points(x, d)
    with np.errstate(all="ignore"):
        tangential = tangential_terms(x, d).sum(axis=0)
        context = SimpleNamespace(
            uv=uv, K=K, d=d, g=g, f=f, c=c, x=x, x_d=x_d, expected=expected, tangential=tangential
        )
        cause = first_mistake(_PIXEL_MISTAKES, context)
        if cause:
            return cause
        g_normalised = (g - c) / f
    model = model_diagnosis(x, np.asarray(d, dtype=float), g_normalised, x_d)
    if model:
        return model
    return (
        "normalise with K (x = (u - c_x) / f_x, y = (v - c_y) / f_y), apply the model of section 4 term by term "
        "(radial factor, then the two tangential terms), then back to pixels"
    )


def distort_pixels(uv, K, dist):
    """Where a lens with Brown-Conrady coefficients dist (OpenCV's order) moves (N, 2) ideal pixel positions.

    Parameters
    ----------
    uv : (N, 2) ndarray
        Ideal (undistorted) pixel positions (u, v).
    K : (3, 3) ndarray
        The intrinsic matrix: f_x, f_y, c_x, c_y in pixels.
    dist : (5,) array_like
        The coefficients (k1, k2, p1, p2, k3), OpenCV's order.

    Returns
    -------
    (N, 2) ndarray
        The distorted pixel positions: normalised x = (u - c_x) / f_x, y likewise; x_d = x L + 2 p1 x y
        + p2 (r^2 + 2 x^2), y_d = y L + p1 (r^2 + 2 y^2) + 2 p2 x y with L = 1 + k1 r^2 + k2 r^4 + k3 r^6;
        back to pixels with K.

    References
    ----------
    D. C. Brown (1966), "Decentering distortion of lenses", Photogrammetric Engineering 32(3);
    A. E. Conrady (1919), "Decentred lens-systems", Monthly Notices of the RAS 79.
    """
    k1, k2, p1, p2, k3 = dist  # note: k3 comes last
    fx, fy, cx, cy = K[0, 0], K[1, 1], K[0, 2], K[1, 2]
    # normalised: the model works at f = 1, from the optical axis
    x = (uv[:, 0] - cx) / fx
    y = (uv[:, 1] - cy) / fy
    r2 = x**2 + y**2
    radial = 1 + k1 * r2 + k2 * r2**2 + k3 * r2**3  # even powers of r
    xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x**2)
    yd = y * radial + p1 * (r2 + 2 * y**2) + 2 * p2 * x * y
    return np.column_stack([fx * xd + cx, fy * yd + cy])  # back to pixels


register_exercise(
    Exercise(
        name="distort_pixels",
        lesson="02",
        reference=distortion.distort_pixels,
        cases=distort_cases,
        compare=same_array(rtol=0, atol=1e-9),
        diagnose=_distort_pixels_diagnosis,
        ndarray_only=True,
        wrong_variants=(
            (lambda uv, K, d: distortion.distort_points(uv, d), "pixel coordinates"),
            (
                lambda uv, K, d: distortion.distort_points((uv - K[:2, 2]) / K[[0, 1], [0, 1]], d),
                "normalised coordinates",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points(uv / K[[0, 1], [0, 1]], d) * K[[0, 1], [0, 1]]
                ),
                "principal point",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points((uv - K[:2, 2]) / K[0, 0], d) * K[0, 0] + K[:2, 2]
                ),
                "f_y",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points((uv - K[:2, 2][::-1]) / K[[0, 1], [0, 1]], d)
                    * K[[0, 1], [0, 1]]
                    + K[:2, 2][::-1]
                ),
                "and c_y = K",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points((uv - K[:2, 2]) / K[[1, 0], [1, 0]], d)
                    * K[[1, 0], [1, 0]]
                    + K[:2, 2]
                ),
                "goes with u and f_y",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points((uv - K[:2, 2] - 0.5) / K[[0, 1], [0, 1]], d)
                    * K[[0, 1], [0, 1]]
                    + K[:2, 2]
                    + 0.5
                ),
                "half-pixel",
            ),
            (lambda uv, K, d: distortion.distort_pixels(uv, K, d) - uv, "shift in pixels"),
            (lambda uv, K, d: uv.copy(), "you returned uv itself"),
            (
                lambda uv, K, d: np.r_[uv[:1], distortion.distort_pixels(uv, K, d)[1:]],
                "skipped point 0",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points((uv - K[:2, 2]) / K[[0, 1], [0, 1]], d) * K[1, 1]
                    + K[:2, 2]
                ),
                "one focal length for both",
            ),
            (
                lambda uv, K, d: distortion.distort_points(uv - K[:2, 2], d) + K[:2, 2],
                "did not divide by f",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points((uv - K[:2, 2] - 1) / K[[0, 1], [0, 1]], d)
                    * K[[0, 1], [0, 1]]
                    + K[:2, 2]
                    + 1
                ),
                "one-pixel shift",
            ),
            (lambda uv, K, d: distortion.distort_pixels(uv, K, d) + 0.5, "exactly half a pixel"),
            (
                lambda uv, K, d: (
                    distortion.distort_points((uv - [319.5, 239.5]) / K[[0, 1], [0, 1]], d)
                    * K[[0, 1], [0, 1]]
                    + [319.5, 239.5]
                ),
                "image centre as the principal point",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points((uv - K[:2, 2]) / K[[0, 1], [0, 1]], d)
                    * K[[0, 1], [0, 1]]
                ),
                "lack the principal point",
            ),
            (lambda uv, K, d: distortion.distort_pixels(uv, K, d)[:, ::-1], "come out as"),
            (
                lambda uv, K, d: distortion.distort_pixels(uv[:, ::-1], K, d),
                "width and height swapped",
            ),
            (
                lambda uv, K, d: (
                    (distortion.distort_points(uv / K[[0, 1], [0, 1]] - K[:2, 2], d) + K[:2, 2])
                    * K[[0, 1], [0, 1]]
                ),
                "subtract, then divide",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_points(uv / K[[0, 1], [0, 1]] - K[:2, 2], d)
                    * K[[0, 1], [0, 1]]
                    + K[:2, 2]
                ),
                "subtract, then divide",
            ),
            (
                lambda uv, K, d: (
                    np.c_[
                        distortion.distort_points(
                            np.c_[uv, np.ones(len(uv))] @ np.linalg.inv(K).T[:, :2], d
                        ),
                        np.ones(len(uv)),
                    ]
                    @ K
                )[:, :2],
                "without .T puts c_x into",
            ),
            (
                pixel_variant(
                    lambda x, d: distortion.distort_points(x, [d[0], d[1], d[3], d[2], d[4]])
                ),
                "p1 and p2 are swapped",
            ),
            (
                pixel_variant(lambda x, d: distortion.distort_points(x, [d[0], d[1], 0, 0, d[4]])),
                "tangential",
            ),
            (
                pixel_variant(
                    lambda x, d: distortion.distort_points(x, [d[0], d[1], d[3], d[4], d[2]])
                ),
                "k3 comes last",
            ),
            (
                pixel_variant(
                    lambda x, d: (
                        x
                        * (
                            1
                            + d[0] * np.hypot(*x.T)
                            + d[1] * np.hypot(*x.T) ** 2
                            + d[4] * np.hypot(*x.T) ** 3
                        )[:, None]
                    )
                ),
                "even powers",
            ),
            (pixel_variant(lambda x, d: brown_variant(x, d, cross=1.0)), "factor 2"),
            (
                pixel_variant(lambda x, d: brown_variant(x, d, squares_swapped=True)),
                "swapped in the tangential terms",
            ),
            (
                pixel_variant(
                    lambda x, d: (
                        distortion.distort_points(x, [d[0], d[1], 0, 0, d[4]])
                        + np.column_stack(
                            [
                                2 * d[2] * x[:, 0] * x[:, 1]
                                + d[3] * (np.hypot(*x.T) + 2 * x[:, 0] ** 2),
                                d[2] * (np.hypot(*x.T) + 2 * x[:, 1] ** 2)
                                + 2 * d[3] * x[:, 0] * x[:, 1],
                            ]
                        )
                    )
                ),
                "take r^2, not r",
            ),
            (
                pixel_variant(lambda x, d: brown_variant(x, d, y_copied=True)),
                "copied from x_d's p2 term",
            ),
            (
                pixel_variant(lambda x, d: brown_variant(x, d, divide=True)),
                "divided by the radial factor",
            ),
            (pixel_variant(lambda x, d: brown_variant(x, d, no_one=True)), "lacks its 1"),
            (
                pixel_variant(
                    lambda x, d: distortion.distort_points(x, [-d[0], -d[1], d[2], d[3], -d[4]])
                ),
                "radial terms have the wrong sign",
            ),
            (
                pixel_variant(
                    lambda x, d: distortion.distort_points(x, [d[0], d[1], -d[2], -d[3], d[4]])
                ),
                "tangential terms have the wrong",
            ),
            (
                pixel_variant(
                    lambda x, d: distortion.distort_points(x, [d[0], d[1], d[2], d[3], 0])
                ),
                "dropped k3",
            ),
            (
                lambda uv, K, d: distortion.distort_pixels(uv, K, d).tolist(),
                "wrap the values in np.array",
            ),
            (lambda uv, K, d: distortion.distort_pixels(uv, K, d).T, "expected an array of shape"),
            (in_place_distortion, "in place"),
            (lambda uv, K, d: distortion.undistort_pixels(uv, K, d), "you undistorted"),
            (
                pixel_variant(lambda x, d: distortion.distort_points(x, [d[0], 0, 0, 0, 0])),
                "you used k1 alone",
            ),
            (
                pixel_variant(
                    lambda x, d: (
                        distortion.distort_points(x, d)
                        + x * (d[4] * ((x**2).sum(1) ** 2 - (x**2).sum(1) ** 3))[:, None]
                    )
                ),
                "yours gives k3 r",
            ),
            (
                pixel_variant(
                    lambda x, d: (
                        distortion.distort_points(x, d)
                        + x * (d[1] * ((x**2).sum(1) ** 1.5 - (x**2).sum(1) ** 2))[:, None]
                    )
                ),
                "yours gives k2 r",
            ),
            (
                pixel_variant(
                    lambda x, d: np.column_stack(
                        [
                            distortion.distort_points(x, d)[:, 0],
                            distortion.distort_points(x, [d[0], d[1], d[3], d[2], d[4]])[:, 1],
                        ]
                    )
                ),
                "y_d has p1 and p2 swapped",
            ),
            (
                lambda uv, K, d: np.round(distortion.distort_pixels(uv, K, d)),
                "you rounded the positions",
            ),
            (
                lambda uv, K, d: np.round(distortion.distort_pixels(uv, K, d), 1),
                "you rounded the positions",
            ),
            (
                lambda uv, K, d: distortion.distort_pixels(uv, K, [d[1], d[0], d[2], d[3], d[4]]),
                "k1 and k2 are swapped",
            ),
            (
                lambda uv, K, d: distortion.distort_pixels(uv, K, [0, 0, d[2], d[3], 0]),
                "left out the radial factor",
            ),
            (
                pixel_variant(
                    lambda x, d: distortion.distort_points(x, d) - 2 * tangential_terms(x, d)[3]
                ),
                "y_d's 2 p2 x y enters with a plus sign",
            ),
            (
                pixel_variant(
                    lambda x, d: distortion.distort_points(x, d) - 2 * tangential_terms(x, d)[0]
                ),
                "x_d's 2 p1 x y enters with a plus sign",
            ),
            (
                lambda uv, K, d: (
                    distortion.distort_pixels(uv, K, [d[0], d[1], 0, 0, d[4]])
                    + tangential_terms((uv - K[:2, 2]) / K[[0, 1], [0, 1]], d).sum(axis=0)
                ),
                "in normalised units but were added to pixels",
            ),
            (
                lambda uv, K, d: (
                    np.c_[
                        distortion.distort_points(
                            (np.c_[uv, np.ones(len(uv))] @ np.linalg.inv(K))[:, :2], d
                        ),
                        np.ones(len(uv)),
                    ]
                    @ K
                )[:, :2],
                "without .T, its first two",
            ),
        ),
        teaching=distort_pixels,
    )
)
