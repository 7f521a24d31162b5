"""Exercises for lesson 09, image stitching: the canvas bounds (canvas_box) and feathering weights."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from .. import stitching as st
from ..camera import rotation_y
from ..homography import rotation_homography
from ..warp import canvas_box
from ._answers import same_array
from ._core import Exercise, Mistake, first_mistake, register_exercise

# ----------------------------------------------------------------------------- canvas bounds


def _canvas_cases():
    K = np.array([[400.0, 0, 159.5], [0, 400.0, 119.5], [0, 0, 1]])

    def yaw(deg):
        return rotation_y(np.radians(deg))

    shift = np.array([[1.0, 0, 50], [0, 1, -30], [0, 0, 1]])
    return [
        ([np.eye(3), shift], [(240, 320), (240, 320)]),  # a translation
        (
            [np.eye(3), rotation_homography(K, yaw(20))],
            [(240, 320), (240, 320)],
        ),  # a turning camera
        (
            [rotation_homography(K, yaw(-15)), np.eye(3), rotation_homography(K, yaw(15))],
            [(240, 320), (200, 300, 3), (240, 320)],
        ),  # three images, sizes differ
    ]


def _corners(
    Hs, shapes, divide: bool = True, last: int = 1, transposed: bool = False, swap: bool = False
) -> np.ndarray:
    """Every image's mapped corners, right or with one typical slip: ``transposed`` maps rows by ``c @ H`` (H^T),
    ``swap`` reads the shape as (w, h)."""
    pts = []
    for H, s in zip(Hs, shapes, strict=True):
        h, w = s[:2][::-1] if swap else s[:2]
        H = np.asarray(H)
        c = np.array(
            [[0, 0, 1], [w - last, 0, 1], [w - last, h - last, 1], [0, h - last, 1]], float
        ) @ (H if transposed else H.T)
        pts.append(c[:, :2] / c[:, 2:] if divide else c[:, :2])
    return np.vstack(pts)


def _box(p: np.ndarray) -> np.ndarray:
    return np.array([np.floor(p.min(axis=0) + 1e-9), np.ceil(p.max(axis=0) - 1e-9)])


def _canvas_diagnosis(args, got, expected) -> str:
    g = np.asarray(got, dtype=float)
    if g.shape != (2, 2):
        return f"return a (2, 2) array [[u_min, v_min], [u_max, v_max]], got shape {g.shape}."
    Hs, shapes = args
    if np.allclose(g, expected[:, ::-1]):
        return (
            "your columns are (v, u); points are (u, v) = (column, row), as everywhere in camlab."
        )
    if np.allclose(g, expected.T):
        return (
            "the rows are the two corners of the box, [[u_min, v_min], [u_max, v_max]]; you returned "
            "[[u_min, u_max], [v_min, v_max]] (its transpose)."
        )
    if np.allclose(g, _box(_corners(Hs, shapes, divide=False))):
        return "you forgot to divide the mapped corners by their third coordinate w (homogeneous to pixels)."
    if np.allclose(g, _box(_corners(Hs, shapes, last=0))):
        return "the last pixel of a w-wide image is at u = w - 1 (pixel centres start at 0), not at u = w."
    if np.allclose(g, _box(_corners(Hs, shapes, transposed=True))) or np.allclose(
        g, _box(_corners(Hs, shapes, transposed=True, divide=False))
    ):
        return (
            "you mapped the corners by H transposed: with points as rows, x' = H x is corners @ H.T, "
            "not corners @ H (which applies H^T: the translation ends up in the third coordinate)."
        )
    if np.allclose(g, _box(_corners(Hs, shapes, swap=True))):
        return (
            "width and height swapped: a shape is (h, w) = (rows, columns), so the corners are (0, 0), "
            "(w-1, 0), (w-1, h-1), (0, h-1) with w = shape[1] and h = shape[0]."
        )
    p = _corners(Hs, shapes)
    if np.allclose(g, [np.ceil(p.min(axis=0)), np.floor(p.max(axis=0))]) or np.allclose(
        g, [p.min(0), p.max(0)]
    ):
        return (
            "round outwards: floor the minimum and ceil the maximum, so no warped pixel is cut off."
        )
    return (
        "map the four corners (0, 0), (w-1, 0), (w-1, h-1), (0, h-1) of every image by its H (divide by w), "
        "take the bounding box of all of them and round it outwards."
    )


register_exercise(
    Exercise(
        name="canvas_box",
        lesson="09",
        reference=canvas_box,
        ndarray_only=True,
        cases=_canvas_cases,
        compare=same_array(atol=1e-9),
        diagnose=_canvas_diagnosis,
        wrong_variants=(
            (lambda Hs, shapes: canvas_box(Hs, shapes)[:, ::-1], "(u, v)"),
            (lambda Hs, shapes: _box(_corners(Hs, shapes, divide=False)), "divide"),
            (lambda Hs, shapes: _box(_corners(Hs, shapes, last=0)), "w - 1"),
            (lambda Hs, shapes: _box(_corners(Hs, shapes, transposed=True)), "H transposed"),
            (lambda Hs, shapes: _box(_corners(Hs, shapes, swap=True)), "width and height swapped"),
            (
                lambda Hs, shapes: np.array(
                    [_corners(Hs, shapes).min(0), _corners(Hs, shapes).max(0)]
                ),
                "round outwards",
            ),
        ),
    )
)


# ----------------------------------------------------------------------------- feather weights


def _feather_cases():
    return [((3, 4),), ((5, 5),), ((6, 9),), ((1, 3),)]


def _feather_diagnosis(args, got, expected) -> str:
    g = np.asarray(got, dtype=float)
    if g.shape != expected.shape:
        return f"the weights should have the image's shape {expected.shape} (rows, columns), got {g.shape}."
    if np.allclose(g, expected - 0.5):
        return (
            "off by half a pixel: pixel centres are at integer u and the border at u = -1/2, so the first "
            "column is 1/2 from the border (u + 1/2), not 0."
        )
    if np.allclose(g, expected + 0.5):
        return "off by half a pixel: the border is at u = -1/2 and u = W - 1/2; use u + 1/2 and W - 1/2 - u."
    h, w = expected.shape
    u = np.arange(w, dtype=float)
    du = np.minimum(u + 0.5, w - 0.5 - u)
    if np.allclose(g, np.broadcast_to(du, (h, w))):
        return "you only used the distance to the left and right borders; take the minimum with the vertical distance too."
    if np.allclose(g, _feather_offsets(expected.shape, 1.5, 1.5)):
        return (
            "you counted pixels from 1: the first column is u = 0 (pixel centres at 0, 1, ..., W - 1), "
            "so use np.arange(W), not np.arange(1, W + 1)."
        )
    for a in (0.0, 0.5, 1.0):
        for b in (0.0, 0.5, 1.0):
            if (a, b) != (0.5, 0.5) and np.allclose(g, _feather_offsets(expected.shape, a, b)):
                near = (
                    ""
                    if a == 0.5
                    else (
                        f"the near border (you used u + {a:g}; the first pixel's centre u = 0 is 1/2 "
                        "from the border at u = -1/2, so u + 1/2)"
                    )
                )
                far = (
                    ""
                    if b == 0.5
                    else (
                        f"the far border (you used W - {b:g} - u; the last pixel's centre u = W - 1 is "
                        "1/2 from the border at u = W - 1/2, so W - 1/2 - u)"
                    )
                )
                return (
                    "off by half a pixel at "
                    + " and at ".join(x for x in (near, far) if x)
                    + "; the same for v."
                )
    return "w(u, v) = min(u + 1/2, W - 1/2 - u, v + 1/2, H - 1/2 - v): the distance to the nearest border."


def _feather_offsets(shape, a: float, b: float) -> np.ndarray:
    """min(u + a, W - b - u, v + a, H - b - v): the feathering weights with the border put elsewhere (a slip)."""
    h, w = shape
    u, v = np.arange(w, dtype=float), np.arange(h, dtype=float)[:, None]
    return np.minimum(np.minimum(u + a, w - b - u), np.minimum(v + a, h - b - v))


register_exercise(
    Exercise(
        name="feather_weights",
        lesson="09",
        reference=st.feather_weights,
        ndarray_only=True,
        cases=_feather_cases,
        compare=same_array(atol=1e-9),
        diagnose=_feather_diagnosis,
        wrong_variants=(
            (lambda shape: st.feather_weights(shape) - 0.5, "half a pixel"),
            (
                lambda shape: _feather_offsets(tuple(shape[:2]), 0.0, 0.0),
                "half a pixel at the near border",
            ),
            (lambda shape: _feather_offsets(tuple(shape[:2]), 1.5, 1.5), "counted pixels from 1"),
            (
                lambda shape: np.broadcast_to(
                    np.minimum(np.arange(shape[1]) + 0.5, shape[1] - 0.5 - np.arange(shape[1])),
                    tuple(shape),
                ).copy(),
                "vertical",
            ),
        ),
    )
)


# ----------------------------------------------------------------------------- focal from a rotation homography


def _focal_reference(H, shape):
    """One focal for both images (the same camera): the median of what H's rows and columns give."""
    from ..stitching.cameras import focal_from_homography

    fs = [f for f in focal_from_homography(H, shape, shape) if np.isfinite(f)]
    return float(np.median(fs)) if fs else float("nan")


def focal_from_rotation_homography(H, shape):
    """Teaching solution: the focal length (pixels) of a camera that turned, from H = K R K^-1.

    Parameters
    ----------
    H : (3, 3) array_like
        The homography between two photos taken by one camera turning about its centre, with the
        principal point at the image centre and square pixels.
    shape : tuple of int
        The photos' shape (height, width[, channels]).

    Returns
    -------
    float
        f in pixels: the median of the estimates from R's columns and R's rows being orthonormal
        (NaN when neither gives a positive f^2).

    References
    ----------
    R. Szeliski and H.-Y. Shum (1997), "Creating full view panoramic image mosaics and environment
    maps", SIGGRAPH.
    """
    h, w = shape[:2]
    # the principal point at the centre
    C = np.array([[1.0, 0, (w - 1) / 2], [0, 1, (h - 1) / 2], [0, 0, 1]])
    Hc = np.linalg.inv(C) @ np.asarray(H, float) @ C  # now H ~ diag(f, f, 1) R diag(1/f, 1/f, 1)
    h0, h1, h2, h3, h4, h5, h6, h7, _ = Hc.ravel() / np.linalg.norm(Hc)
    # R's columns 1 and 2 are orthogonal and equally long: two formulas for f^2, keep the better-conditioned one
    n1, d1 = -(h0 * h1 + h3 * h4), h6 * h7
    n2, d2 = h0**2 + h3**2 - h1**2 - h4**2, h7**2 - h6**2
    f2_cols = n1 / d1 if abs(d1) > abs(d2) else n2 / d2
    # R's rows 1 and 2 likewise
    n1, d1 = -h2 * h5, h0 * h3 + h1 * h4
    n2, d2 = h5**2 - h2**2, h0**2 + h1**2 - h3**2 - h4**2
    f2_rows = n1 / d1 if abs(d1) > abs(d2) else n2 / d2
    good = [np.sqrt(v) for v in (f2_rows, f2_cols) if np.isfinite(v) and v > 0]
    return float(np.median(good)) if good else float("nan")


def _focal_cases():
    from ..camera import rotation_from_axis_angle

    out = []
    # the general case first: a slip that returns a wrong number there is named by its cause; a missing
    # fallback for the 0/0 formula shows as NaN on the pure pan and the pure tilt after it
    for f, (h, w), rvec in (
        (520.0, (660, 900), [0.05, -0.4, 0.03]),  # pan, tilt and roll
        (700.0, (480, 640), [0.0, 0.35, 0.0]),  # a pure pan: h7 = 0
        (1200.0, (600, 800), [0.2, 0.0, 0.0]),
    ):  # a pure tilt
        K = np.array([[f, 0, (w - 1) / 2], [0, f, (h - 1) / 2], [0, 0, 1]])
        out.append((rotation_homography(K, rotation_from_axis_angle(rvec)), (h, w)))
    return out


def _focal_uncentred(H, shape):
    h0, h1, h2, h3, h4, h5, h6, h7, _ = np.asarray(H, float).ravel()
    return float(np.sqrt(abs((h0**2 + h3**2 - h1**2 - h4**2) / (h7**2 - h6**2))))


def _focal_number(got) -> float | None:
    """``got`` as a float if it is one number (a Python or numpy scalar, or a 0-d array), else None."""
    if isinstance(got, (bool, np.bool_)) or not (
        np.isscalar(got) or (isinstance(got, np.ndarray) and got.ndim == 0)
    ):
        return None
    try:
        return float(got)
    except (TypeError, ValueError):
        return None


def _same_focal(got, expected) -> bool:
    g = _focal_number(got)
    return g is not None and np.isfinite(g) and abs(g / expected - 1) < 1e-6


def _focal_centred_at(H, shape, cx: float, cy: float) -> float:
    """The teaching solution with the principal point put at (cx, cy) (a slip when it is not the centre)."""
    C = np.array([[1.0, 0, cx], [0, 1, cy], [0, 0, 1]])
    h, w = shape[:2]
    Cr = np.array([[1.0, 0, (w - 1) / 2], [0, 1, (h - 1) / 2], [0, 0, 1]])
    # move the slipped centre to where the solution expects it: H_c = C^-1 H C, written as the solution's Cr^-1 H' Cr
    return focal_from_rotation_homography(
        Cr @ np.linalg.inv(C) @ np.asarray(H, float) @ C @ np.linalg.inv(Cr), shape
    )


def _slipped_focal(focal):
    """The row answer ``focal(s)`` computed quietly (a slip may divide by 0), None where it is no number or
    equals the right focal length (so that slip cannot show on this input)."""

    def answer(s):
        with np.errstate(all="ignore"):
            f_wrong = focal(s)
        return f_wrong if np.isfinite(f_wrong) and abs(f_wrong / s.expected - 1) > 1e-6 else None

    return answer


def _same_focal(got, f_wrong) -> bool:
    return bool(np.isclose(got, f_wrong, rtol=1e-6))


_FOCAL_SLIPS = (
    Mistake(
        "H transposed",
        _slipped_focal(lambda s: focal_from_rotation_homography(np.asarray(s.H, float).T, s.shape)),
        "you used H transposed: with H[i, j] row-major, h0 h1 h2 is the first row, so take h = H.ravel() "
        "(not H.T.ravel(), nor H.ravel(order='F')).",
    ),
    Mistake(
        "width and height swapped",
        _slipped_focal(lambda s: focal_from_rotation_homography(s.H, (s.w, s.h))),
        "width and height swapped: shape is (h, w) = (rows, columns), so the centre is ((w-1)/2, (h-1)/2) "
        "with w = shape[1] and h = shape[0].",
    ),
    Mistake(
        "centre (w/2, h/2)",
        _slipped_focal(lambda s: _focal_centred_at(s.H, s.shape, s.w / 2, s.h / 2)),
        "a half-pixel slip: pixel centres are at integers 0 ... w-1, so the image centre is ((w-1)/2, (h-1)/2), "
        "not (w/2, h/2).",
    ),
    Mistake(
        "centre's coordinates swapped",
        _slipped_focal(lambda s: _focal_centred_at(s.H, s.shape, (s.h - 1) / 2, (s.w - 1) / 2)),
        "the centre's coordinates are swapped: it is (u, v) = ((w-1)/2, (h-1)/2), column first.",
    ),
)
"""The focal length's slips, as the focal lengths they give (from H, the image ``shape``, ``w`` and ``h``)."""


def _focal_diagnosis(args, got, expected) -> str:
    H, shape = args
    g = _focal_number(got)
    if g is None:
        return (
            f"return one number, the focal length in pixels (a float); got {type(got).__name__}"
            + (f" of shape {np.shape(got)}" if isinstance(got, np.ndarray) else "")
            + "."
        )
    h, w = shape[:2]
    if np.isfinite(g):
        cause = first_mistake(
            _FOCAL_SLIPS,
            SimpleNamespace(H=H, shape=shape, w=w, h=h, expected=expected),
            g,
            _same_focal,
        )
        if cause:
            return cause
    if not np.isfinite(g):
        C = np.array([[1.0, 0, (w - 1) / 2], [0, 1, (h - 1) / 2], [0, 0, 1]])
        Hc = np.linalg.inv(C) @ np.asarray(H, float) @ C
        h6, h7 = Hc[2, :2] / np.linalg.norm(Hc)
        if min(abs(h6), abs(h7)) < 1e-9:
            return (
                "you returned NaN or inf: for a pure pan h6 h7 = 0 (and for a pure tilt h6 = 0), so one formula is "
                "0/0; use the other one (the equal-length condition), whichever denominator is larger."
            )
        with np.errstate(all="ignore"):
            causes = [
                cause
                for f_wrong, cause in (
                    (
                        focal_from_rotation_homography(np.asarray(H, float).T, shape),
                        "H transposed (h = H.T.ravel())",
                    ),
                    (
                        _focal_centred_at(H, shape, 0.0, 0.0),
                        "the principal point not moved to the origin first (H_c = C^-1 H C)",
                    ),
                )
                if not np.isfinite(f_wrong)
            ]
        return (
            "you returned NaN or inf on a general turn (pan, tilt and roll: neither formula is 0/0 here), so f^2 "
            "came out negative or 0/0 by a slip"
            + (": it does with " + " or with ".join(causes) if causes else "")
            + ". Check the indices: h0 ... h8 are H's entries row by row."
        )
    if np.isclose(g, expected**2, rtol=1e-3):
        return "that is f squared: the orthogonality conditions give f^2; take the square root."
    if np.isclose(g, _focal_uncentred(H, shape), rtol=1e-3) or abs(g / expected - 1) > 0.05:
        return (
            "move the principal point to the origin first: H_c = C^-1 H C with C the translation to the image "
            "centre ((w-1)/2, (h-1)/2). The formulas hold for K = diag(f, f, 1) only."
        )
    return "f^2 = -(h0 h1 + h3 h4) / (h6 h7) or (h0^2 + h3^2 - h1^2 - h4^2) / (h7^2 - h6^2) on the centred H."


register_exercise(
    Exercise(
        name="focal_from_rotation_homography",
        lesson="09",
        reference=_focal_reference,
        cases=_focal_cases,
        compare=_same_focal,
        diagnose=_focal_diagnosis,
        wrong_variants=(
            (lambda H, shape: focal_from_rotation_homography(H, shape) ** 2, "square root"),
            (_focal_uncentred, "principal point"),
            (
                lambda H, shape: focal_from_rotation_homography(np.asarray(H, float).T, shape),
                "H transposed",
            ),
            (
                lambda H, shape: focal_from_rotation_homography(H, tuple(shape[:2])[::-1]),
                "width and height swapped",
            ),
            (
                lambda H, shape: _focal_centred_at(H, shape, shape[1] / 2, shape[0] / 2),
                "half-pixel slip",
            ),
        ),
        teaching=focal_from_rotation_homography,
    )
)
