"""Exercises for lesson 09, image stitching: the canvas bounds (canvas_box), feathering weights
(feather_weights) and the focal length from a rotation-only homography (focal_from_rotation_homography)."""

from __future__ import annotations

import itertools
from types import SimpleNamespace

import numpy as np

from .. import stitching as st
from ..camera import rotation_y
from ..homography import rotation_homography
from ..warp import canvas_box as _canvas_box_reference
from ._answers import same_array
from ._core import Exercise, Mistake, first_mistake, register_exercise

# ----------------------------------------------------------------------------- canvas bounds


def canvas_box(homographies, shapes):
    """Teaching solution: the bounding box of every image's corner pixels mapped by its homography."""
    pts = []
    for H, shape in zip(homographies, shapes):
        h, w = shape[:2]
        corners = np.array([[0, 0, 1], [w - 1, 0, 1], [w - 1, h - 1, 1], [0, h - 1, 1]], float)
        c = corners @ np.asarray(H, float).T  # x' = H x for rows: corners @ H^T
        pts.append(c[:, :2] / c[:, 2:])  # divide by the third coordinate
    pts = np.vstack(pts)
    # round outwards (the 1e-9 keeps a corner at -30.000000000000004, round-off of -30, from growing the box)
    return np.array([np.floor(pts.min(axis=0) + 1e-9), np.ceil(pts.max(axis=0) - 1e-9)])


def _canvas_cases():
    K = np.array([[400.0, 0, 159.5], [0, 400.0, 119.5], [0, 0, 1]])

    def yaw(deg):
        return rotation_y(np.radians(deg))

    def shift(du, dv):
        return np.array([[1.0, 0, du], [0, 1, dv], [0, 0, 1]])

    # No box edge falls on a whole pixel (each is at least 0.1 px from one), so floor and ceil give the same
    # box whatever the float round-off of a right answer (H scaled to unit norm first, say). The odd-sized
    # image of the third input decides part of the box, so using shapes[0] for every image shows.
    return [
        ([shift(0.3, 0.4), shift(50.6, -30.3)], [(240, 320), (240, 320)]),  # two translations
        (
            [shift(0.3, 0.4), rotation_homography(K, yaw(20))],
            [(240, 320), (240, 320)],
        ),  # a turning camera
        (
            [shift(0.3, 0.4), rotation_homography(K, yaw(-15)), rotation_homography(K, yaw(15)) @ shift(0.2, 0.1)],
            [(200, 300, 3), (240, 320), (260, 360)],
        ),  # three images, sizes differ
    ]


def _corners(
    Hs,
    shapes,
    divide: bool = True,
    last: float = 1,
    first: float = 0,
    transposed: bool = False,
    swap: bool = False,
    one_shape: bool = False,
) -> np.ndarray:
    """Every image's mapped corners, right or with one typical slip: ``transposed`` maps rows by ``c @ H`` (H^T),
    ``swap`` reads the shape as (w, h), ``one_shape`` uses shapes[0] for every image, ``first`` and ``last``
    put the corners at u = first and u = w - last (right: 0 and w - 1; pixel edges: -1/2 and w - 1/2;
    1-based: 1 and w)."""
    pts = []
    for H, s in zip(Hs, shapes, strict=True):
        s = shapes[0] if one_shape else s
        h, w = s[:2][::-1] if swap else s[:2]
        H = np.asarray(H)
        c = np.array(
            [[first, first, 1], [w - last, first, 1], [w - last, h - last, 1], [first, h - last, 1]], float
        ) @ (H if transposed else H.T)
        pts.append(c[:, :2] / c[:, 2:] if divide else c[:, :2])
    return np.vstack(pts)


def _box(p: np.ndarray) -> np.ndarray:
    return np.array([np.floor(p.min(axis=0) + 1e-9), np.ceil(p.max(axis=0) - 1e-9)])


def _canvas_context(args, expected):
    Hs, shapes = args
    return SimpleNamespace(Hs=Hs, shapes=shapes, expected=expected, corners=_corners(Hs, shapes))


def _one_image_box(s, k: int):
    """The box of image k alone (a `return` inside the loop keeps only the first; `pts = ...` instead of
    `pts.append(...)` keeps only the last); None where that image alone already gives the whole box."""
    box = _box(_corners(s.Hs[k : k + 1 or None], s.shapes[k : k + 1 or None]))
    return None if np.allclose(box, s.expected) else box


_CANVAS_SLIPS = (
    Mistake(
        "(v, u)",
        lambda s: s.expected[:, ::-1],
        "your columns are (v, u); points are (u, v) = (column, row), as everywhere in camlab.",
    ),
    Mistake(
        "transposed box",
        lambda s: s.expected.T,
        "the rows are the two corners of the box, [[u_min, v_min], [u_max, v_max]]; you returned "
        "[[u_min, u_max], [v_min, v_max]] (its transpose).",
    ),
    Mistake(
        "first image only",
        lambda s: _one_image_box(s, 0),
        "that is the box of the first image only: is your `return` indented inside the `for` loop? Collect the "
        "corners of every image (pts.append(...)), and take the box after the loop.",
    ),
    Mistake(
        "last image only",
        lambda s: _one_image_box(s, -1),
        "that is the box of the last image only: each pass of the loop replaced the corners (pts = ...) instead "
        "of adding to them (pts.append(...), then np.vstack(pts) after the loop).",
    ),
    Mistake(
        "shapes[0]",
        lambda s: _box(_corners(s.Hs, s.shapes, one_shape=True)),
        "you used the first image's shape for every image: image k has shape shapes[k] (zip(homographies, "
        "shapes) pairs them up); here the images differ in size.",
    ),
    Mistake(
        "divide",
        lambda s: _box(_corners(s.Hs, s.shapes, divide=False)),
        "you forgot to divide the mapped corners by their third coordinate w (homogeneous to pixels).",
    ),
    Mistake(
        "w - 1",
        lambda s: _box(_corners(s.Hs, s.shapes, last=0)),
        "the last pixel of a w-wide image is at u = w - 1 (pixel centres start at 0), not at u = w.",
    ),
    Mistake(
        "pixel edges",
        lambda s: _box(_corners(s.Hs, s.shapes, first=-0.5, last=0.5)),
        "a half-pixel slip: you mapped the pixel edges (-1/2 and w - 1/2). The box holds the centres of the corner "
        "pixels, (0, 0) to (w-1, h-1): pixel centres are at integers, and the canvas's pixels are too.",
    ),
    Mistake(
        "1-based",
        lambda s: _box(_corners(s.Hs, s.shapes, first=1, last=0)),
        "you counted pixels from 1: the corner pixels are at 0 and w - 1 (not 1 and w), as numpy indexes them.",
    ),
    Mistake(
        "divided by the width",
        lambda s: _box(np.vstack([c / sh[1] for c, sh in zip(np.split(s.corners, len(s.shapes)), s.shapes, strict=True)])),
        "you divided by the image width: 'divide by w' means the third (homogeneous) coordinate of each mapped "
        "corner, c[:, :2] / c[:, 2:], not the width w of shape (h, w).",
    ),
    Mistake(
        "H transposed",
        lambda s: _box(_corners(s.Hs, s.shapes, transposed=True)),
        "you mapped the corners by H transposed: with points as rows, x' = H x is corners @ H.T, "
        "not corners @ H (which applies H^T: the translation ends up in the third coordinate).",
    ),
    Mistake(
        "H transposed, not divided",
        lambda s: _box(_corners(s.Hs, s.shapes, transposed=True, divide=False)),
        "you mapped the corners by H transposed (corners @ H; use corners @ H.T) and did not divide by the third "
        "coordinate.",
    ),
    Mistake(
        "H inverted",
        lambda s: _box(_corners([np.linalg.inv(H) for H in s.Hs], s.shapes)),
        "you mapped the corners by the inverse of H: each H already maps its image onto the canvas "
        "(canvas_from_image), so use it as it is.",
    ),
    Mistake(
        "width and height swapped",
        lambda s: _box(_corners(s.Hs, s.shapes, swap=True)),
        "width and height swapped: a shape is (h, w) = (rows, columns), so the corners are (0, 0), "
        "(w-1, 0), (w-1, h-1), (0, h-1) with w = shape[1] and h = shape[0].",
    ),
    Mistake(
        "truncated",
        lambda s: np.array([np.trunc(s.corners.min(0)), s.expected[1]]),
        "int() and astype(int) truncate towards zero, so a negative minimum moves inwards (int(-30.3) = -30): "
        "use np.floor for the minimum and np.ceil for the maximum.",
    ),
    Mistake(
        "truncated both",
        lambda s: np.array([np.trunc(s.corners.min(0)), np.trunc(s.corners.max(0)) + 1]),
        "int() and astype(int) truncate towards zero, so a negative minimum moves inwards (int(-30.3) = -30): "
        "use np.floor for the minimum and np.ceil for the maximum.",
    ),
    Mistake(
        "round outwards",
        lambda s: [
            np.array([np.ceil(s.corners.min(0)), np.floor(s.corners.max(0))]),
            np.array([s.corners.min(0), s.corners.max(0)]),
            np.round(np.array([s.corners.min(0), s.corners.max(0)])),
        ],
        "round outwards: floor the minimum and ceil the maximum, so no warped pixel is cut off.",
    ),
)
"""canvas_box's slips, as the boxes they give on the test input (checked in this order)."""


def _same_box(got, answer) -> bool:
    answers = answer if isinstance(answer, list) else [answer]
    return any(np.shape(a) == np.shape(got) and np.allclose(got, a) for a in answers)


def _canvas_diagnosis(args, got, expected) -> str:
    g = np.asarray(got, dtype=float)
    if g.shape != (2, 2):
        return f"return a (2, 2) array [[u_min, v_min], [u_max, v_max]], got shape {g.shape}."
    cause = first_mistake(_CANVAS_SLIPS, _canvas_context(args, expected), g, _same_box)
    if cause:
        return cause
    return (
        "map the four corners (0, 0), (w-1, 0), (w-1, h-1), (0, h-1) of every image by its H (divide by the third "
        "coordinate), take the bounding box of all of them and round it outwards."
    )


def _canvas_variant(name: str):
    """The row ``name`` of _CANVAS_SLIPS as a student's function (for the tests)."""
    rows = [m for m in _CANVAS_SLIPS if m.name == name]

    def wrong(Hs, shapes):
        a = rows[0].answer(_canvas_context((Hs, shapes), _canvas_box_reference(Hs, shapes)))
        return np.array(a[0] if isinstance(a, list) else a)

    return wrong


register_exercise(
    Exercise(
        name="canvas_box",
        lesson="09",
        reference=_canvas_box_reference,
        ndarray_only=True,
        cases=_canvas_cases,
        compare=same_array(atol=1e-9),
        diagnose=_canvas_diagnosis,
        teaching=canvas_box,
        wrong_variants=(
            (lambda Hs, shapes: _canvas_box_reference(Hs, shapes)[:, ::-1], "(u, v)"),
            (_canvas_variant("first image only"), "`return` indented inside"),
            (_canvas_variant("last image only"), "instead of adding"),
            (_canvas_variant("shapes[0]"), "first image's shape"),
            (_canvas_variant("divide"), "divide"),
            (_canvas_variant("w - 1"), "w - 1"),
            (_canvas_variant("pixel edges"), "pixel edges"),
            (_canvas_variant("1-based"), "counted pixels from 1"),
            (_canvas_variant("divided by the width"), "divided by the image width"),
            (_canvas_variant("H transposed"), "H transposed"),
            (_canvas_variant("H inverted"), "inverse of H"),
            (_canvas_variant("width and height swapped"), "width and height swapped"),
            (_canvas_variant("truncated"), "truncate towards zero"),
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


def feather_weights(shape):
    """Teaching solution: each pixel's distance to the nearest image border (pixel centres at integers)."""
    h, w = shape[:2]
    u = np.arange(w, dtype=float)  # pixel centres 0 ... w-1; the borders at -1/2 and w - 1/2
    v = np.arange(h, dtype=float)[:, None]
    return np.minimum(np.minimum(u + 0.5, w - 0.5 - u), np.minimum(v + 0.5, h - 0.5 - v))


def _feather_cases():
    return [((3, 4),), ((5, 5),), ((6, 9),), ((1, 3),)]


def _feather_diagnosis(args, got, expected) -> str:
    g = np.asarray(got, dtype=float)
    if g.shape != expected.shape:
        return f"the weights should have the image's shape {expected.shape} (rows, columns), got {g.shape}."
    if np.asarray(got).dtype.kind in "iub":
        return (
            f"your array has an integer dtype ({np.asarray(got).dtype}), so the half-pixel distances (u + 1/2, ...) "
            "were cut to whole numbers when stored: build it as floats (np.zeros((h, w)), or np.minimum of float "
            "arrays), not np.zeros((h, w), int)."
        )
    if g.max() > 0 and np.allclose(g, expected / expected.max()):
        return (
            "you normalised the weights to a maximum of 1; the prompt asks for the distance itself, in pixels "
            "(feathering divides by the sum of the weights later, so the scale must be the same for every image)."
        )
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
        teaching=feather_weights,
        wrong_variants=(
            (lambda shape: st.feather_weights(shape) - 0.5, "half a pixel"),
            (
                lambda shape: _feather_offsets(tuple(shape[:2]), 0.0, 0.0),
                "half a pixel at the near border",
            ),
            (lambda shape: _feather_offsets(tuple(shape[:2]), 1.5, 1.5), "counted pixels from 1"),
            (lambda shape: st.feather_weights(shape).astype(int), "integer dtype"),
            (lambda shape: st.feather_weights(shape) / st.feather_weights(shape).max(), "normalised"),
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
    """Teaching solution: the focal length (pixels) of a camera that turned, from H = K R K^-1."""
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
    # The first turn is chosen so that every typical slip (C H C^-1, no centring, width and height swapped,
    # a half-pixel or 1-based centre, the rows read as the columns of H^T) gives a finite, distinct focal
    # length with each formula: the diagnosis then names the slip by its number, whichever formulas the
    # student combined (only H transposed gives NaN with all four). Then a general turn and the two 0/0
    # cases of the prompt (a pure pan: h7 = 0; a pure tilt: h6 = 0).
    for f, (h, w), rvec in (
        (520.0, (660, 900), [-0.523, 0.041, -0.054]),  # a tilt, a little pan and roll
        (520.0, (660, 900), [0.05, -0.4, 0.03]),  # pan, tilt and roll
        (700.0, (480, 640), [0.0, 0.35, 0.0]),  # a pure pan: h7 = 0
        (1200.0, (600, 800), [0.2, 0.0, 0.0]),  # a pure tilt: h6 = 0
    ):
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
    """The comparison of the check: one finite number within 1e-6 of the focal length."""
    g = _focal_number(got)
    return g is not None and np.isfinite(g) and abs(g / expected - 1) < 1e-6


_SLIP_CENTRES = {
    # the principal point each slip puts the origin at, from (w, h)
    "swap": lambda w, h: ((h - 1) / 2, (w - 1) / 2),
    "half": lambda w, h: (w / 2, h / 2),
    "one-based": lambda w, h: ((w + 1) / 2, (h + 1) / 2),
    "uncentred": lambda w, h: (0.0, 0.0),
}


def _focal_formulas(H, shape, slip: str = "", absolute: bool = False) -> dict[str, float]:
    """The four focal lengths of the prompt's formulas (columns: c1 orthogonal, c2 equally long; rows: r1, r2),
    computed right or with one typical ``slip``; NaN where f^2 is 0/0 or negative.

    Slips: "swap" (centre ((h-1)/2, (w-1)/2)), "half" ((w/2, h/2)), "one-based" (((w+1)/2, (h+1)/2)),
    "uncentred" (no C at all), "C H C^-1" (the translation applied the wrong way round), "transposed"
    (h = H.T.ravel()), "sign" (the orthogonality formula without its minus), "rows as H^T" (the column
    formulas applied to H^T for the rows: they give 1/f^2 there). ``absolute`` takes sqrt(|f^2|), as a
    student who silences the NaN does.
    """
    h, w = shape[:2]
    cx, cy = _SLIP_CENTRES.get(slip, lambda w, h: ((w - 1) / 2, (h - 1) / 2))(w, h)
    C = np.array([[1.0, 0, cx], [0, 1, cy], [0, 0, 1]])
    Hm = np.asarray(H, float).T if slip == "transposed" else np.asarray(H, float)
    Hc = C @ Hm @ np.linalg.inv(C) if slip == "C H C^-1" else np.linalg.inv(C) @ Hm @ C
    h0, h1, h2, h3, h4, h5, h6, h7, _ = (Hc / np.linalg.norm(Hc)).ravel()
    sign = -1.0 if slip == "sign" else 1.0
    with np.errstate(all="ignore"):
        f2 = {
            "c1": -sign * (h0 * h1 + h3 * h4) / (h6 * h7),
            "c2": (h0**2 + h3**2 - h1**2 - h4**2) / (h7**2 - h6**2),
        }
        if slip == "rows as H^T":
            f2["r1"] = -(h0 * h3 + h1 * h4) / (h2 * h5)
            f2["r2"] = (h0**2 + h1**2 - h3**2 - h4**2) / (h2**2 - h5**2)
        else:
            f2["r1"] = -h2 * h5 / (h0 * h3 + h1 * h4)
            f2["r2"] = (h5**2 - h2**2) / (h0**2 + h1**2 - h3**2 - h4**2)
    if absolute:
        f2 = {k: abs(v) for k, v in f2.items()}
    return {k: float(np.sqrt(v)) if np.isfinite(v) and v >= 0 else float("nan") for k, v in f2.items()}


def _focal_answers(values: dict[str, float]) -> list[float]:
    """What a student's combination of the formulas returns: one formula, the median or mean of any of them
    (NaN dropped, as the prompt's "where both are defined" invites, or kept), and per pair the one with the
    larger denominator (approximated by the one that is defined)."""
    out = []
    keys = list(values)
    for n in range(1, len(keys) + 1):
        for subset in itertools.combinations(keys, n):
            vals = np.array([values[k] for k in subset])
            finite = vals[np.isfinite(vals)]
            out += [float(np.median(vals)), float(np.mean(vals))]
            if finite.size:
                out += [float(np.median(finite)), float(np.mean(finite))]
    return out


def _focal_slip(slip: str):
    """A diagnosis row's answer: the focal lengths a student who made ``slip`` can return on this input,
    or None where the slip changes no formula (it cannot show here)."""

    def answer(s):
        right_answers = _focal_answers(_focal_formulas(s.H, s.shape))
        wrong = [
            a
            for absolute in (False, True)
            for a in _focal_answers(_focal_formulas(s.H, s.shape, slip, absolute))
            if not any(np.isclose(a, r, rtol=1e-6) for r in right_answers if np.isfinite(r))
        ]
        return wrong or None

    return answer


def _slipped_student(slip: str, H, shape, formulas=("c1", "c2", "r1", "r2")) -> float:
    """A student's answer with ``slip``: the median of the defined ones among ``formulas`` (for the tests)."""
    values = [v for k, v in _focal_formulas(H, shape, slip).items() if k in formulas and np.isfinite(v)]
    return float(np.median(values)) if values else float("nan")


def _shows_slip(got: float, answers: list[float]) -> bool:
    if np.isnan(got):
        return any(np.isnan(a) for a in answers)
    return any(np.isfinite(a) and np.isclose(got, a, rtol=1e-6) for a in answers)


_FOCAL_SLIPS = (
    Mistake(
        "H transposed",
        _focal_slip("transposed"),
        "you used H transposed: with H[i, j] row-major, h0 h1 h2 is the first row, so take h = H.ravel() "
        "(not H.T.ravel(), nor H.ravel(order='F')).",
    ),
    Mistake(
        "width and height swapped",
        _focal_slip("swap"),
        "width and height swapped: you put the principal point at ((h-1)/2, (w-1)/2). A shape is (h, w) = "
        "(rows, columns), so the centre is (u, v) = ((w-1)/2, (h-1)/2) with w = shape[1] and h = shape[0].",
    ),
    Mistake(
        "centre (w/2, h/2)",
        _focal_slip("half"),
        "a half-pixel slip: pixel centres are at integers 0 ... w-1, so the image centre is ((w-1)/2, (h-1)/2), "
        "not (w/2, h/2).",
    ),
    Mistake(
        "1-based centre",
        _focal_slip("one-based"),
        "you counted pixels from 1: the centre of pixels 0 ... w-1 is (w-1)/2, not (w+1)/2.",
    ),
    Mistake(
        "C H C^-1",
        _focal_slip("C H C^-1"),
        "the normalisation is applied the wrong way round: C maps centred coordinates to pixels, so the centred "
        "homography is H_c = C^-1 H C (undo C on the way in, apply H, move back to centred coordinates), not C H C^-1.",
    ),
    Mistake(
        "principal point not moved",
        _focal_slip("uncentred"),
        "move the principal point to the origin first: H_c = C^-1 H C with C the translation to the image "
        "centre ((w-1)/2, (h-1)/2). The formulas hold for K = diag(f, f, 1) only.",
    ),
    Mistake(
        "rows as the columns of H^T",
        _focal_slip("rows as H^T"),
        "the row conditions are not the column formulas applied to H^T: on H^T those give 1/f^2 (H^T is "
        "diag(1/f, 1/f, 1) R^T diag(f, f, 1)). Rows 1 and 2 of R give f^2 = -h2 h5 / (h0 h3 + h1 h4) or "
        "(h5^2 - h2^2) / (h0^2 + h1^2 - h3^2 - h4^2).",
    ),
    Mistake(
        "sign flip",
        _focal_slip("sign"),
        "a sign flip: the orthogonality of columns 1 and 2 gives f^2 = -(h0 h1 + h3 h4) / (h6 h7), with the "
        "minus (without it f^2 comes out negative and its square root NaN).",
    ),
)
_FOCAL_SHORT = {
    "H transposed": "H transposed: h = H.ravel(), row by row, not H.T.ravel()",
    "width and height swapped": "width and height swapped: the centre is ((w-1)/2, (h-1)/2) with (h, w) = shape[:2]",
    "centre (w/2, h/2)": "a half-pixel slip: the centre is ((w-1)/2, (h-1)/2), not (w/2, h/2)",
    "1-based centre": "pixels counted from 1: the centre is ((w-1)/2, (h-1)/2)",
    "C H C^-1": "the normalisation the wrong way round: H_c = C^-1 H C, not C H C^-1",
    "principal point not moved": "the principal point not moved to the origin: H_c = C^-1 H C",
    "rows as the columns of H^T": (
        "the rows' formulas taken as the columns' on H^T (that gives 1/f^2): f^2 = -h2 h5 / (h0 h3 + h1 h4) "
        "or (h5^2 - h2^2) / (h0^2 + h1^2 - h3^2 - h4^2)"
    ),
    "sign flip": "a sign flip: f^2 = -(h0 h1 + h3 h4) / (h6 h7), with the minus",
}
"""Each slip in a few words, for a NaN that more than one slip explains."""

"""The focal length's slips, as the focal lengths they give (from H, the image ``shape``, ``w`` and ``h``),
checked in this order; each row tries every way of combining the four formulas."""


def _focal_diagnosis(args, got, expected) -> str:
    H, shape = args
    g = _focal_number(got)
    if g is None:
        return (
            f"return one number, the focal length in pixels (a float); got {type(got).__name__}"
            + (f" of shape {np.shape(got)}" if isinstance(got, np.ndarray) else "")
            + "."
        )
    if np.isfinite(g) and np.isclose(g, expected**2, rtol=1e-3):
        return "that is f squared: the orthogonality conditions give f^2; take the square root."
    h, w = shape[:2]
    context = SimpleNamespace(H=H, shape=shape, w=w, h=h, expected=expected)
    right = _focal_formulas(H, shape)
    if np.isnan(g) and (np.isnan(right["c1"]) or np.isnan(right["r1"])) and np.isfinite(right["c2"]):
        return (
            "you returned NaN or inf: for a pure pan h6 h7 = 0 (and for a pure tilt h6 = 0), so the orthogonality "
            "formula is 0/0; use the other one (the equal-length condition), whichever denominator is larger."
        )
    if np.isnan(g):
        # NaN does not tell the slips apart by value: name every slip that gives NaN here with some formula
        causes = [m for m in _FOCAL_SLIPS if (a := m.answer(context)) is not None and _shows_slip(g, a)]
        if causes:
            return (
                "f^2 came out negative (its square root is NaN) on a turn where every formula is defined. "
                + (causes[0].hint if len(causes) == 1 else
                   "Depending on the formulas you used, that is one of these slips: "
                   + "; ".join(f"({k}) {_FOCAL_SHORT[m.name]}" for k, m in enumerate(causes, 1)) + ".")
            )
    cause = first_mistake(_FOCAL_SLIPS, context, g, _shows_slip)
    if cause:
        return cause
    if not np.isfinite(g):
        return (
            "you returned NaN or inf on a turn where every formula is defined, so f^2 came out negative or 0/0 "
            "by a slip. Check the indices: h0 ... h8 are H's entries row by row."
        )
    return (
        "f^2 = -(h0 h1 + h3 h4) / (h6 h7) or (h0^2 + h3^2 - h1^2 - h4^2) / (h7^2 - h6^2) (columns), "
        "-h2 h5 / (h0 h3 + h1 h4) or (h5^2 - h2^2) / (h0^2 + h1^2 - h3^2 - h4^2) (rows), on the centred H."
    )


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
            (lambda H, shape: _slipped_student("half", H, shape), "half-pixel slip"),
            (lambda H, shape: _slipped_student("one-based", H, shape), "counted pixels from 1"),
            (lambda H, shape: _slipped_student("C H C^-1", H, shape), "wrong way round"),
            (lambda H, shape: _slipped_student("swap", H, shape), "width and height swapped"),
            (lambda H, shape: _slipped_student("rows as H^T", H, shape, ("c1", "r1")), "1/f^2"),
            (lambda H, shape: _slipped_student("sign", H, shape, ("c1",)), "sign flip"),
        ),
        teaching=focal_from_rotation_homography,
    )
)
