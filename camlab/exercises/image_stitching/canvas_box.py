"""Lesson 09, exercise 1: the canvas bounds (canvas_box), its test inputs and the slips its diagnosis names."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ...camera import rotation_y, rotation_z
from ...homography import rotation_homography
from ...warp import canvas_box as _canvas_box_reference
from .._answers import same_array, shape_unpack_hint
from .._core import Exercise, Mistake, first_mistake, register_exercise

# ----------------------------------------------------------------------------- canvas bounds


def canvas_box(homographies, shapes):
    """Teaching solution: the bounding box of every image's corner pixels mapped by its homography.

    Parameters
    ----------
    homographies : sequence of (3, 3) array_like
        H_k maps image k's pixels to the canvas, x' ~ H_k x (any scale).
    shapes : sequence of tuple of int
        Each image's shape (height, width[, channels]), in the order of ``homographies``.

    Returns
    -------
    (2, 2) ndarray
        [[u_min, v_min], [u_max, v_max]] in canvas pixels: the mapped corner pixel centres
        (0, 0) ... (w - 1, h - 1), rounded outwards to whole pixels.
    """
    pts = []
    for H, shape in zip(homographies, shapes, strict=True):
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

    # In the first six inputs no box edge falls on a whole pixel (each is at least 0.1 px from one), so floor
    # and ceil give the same box whatever the float round-off of a right answer (H scaled to unit norm first,
    # say). The odd-sized image of the third input decides part of the box, so using shapes[0] for every image
    # shows. The last input is a stitch's usual case: the reference image (H = I, exact in any float maths)
    # decides u_max and v_max on whole pixels, so floor(max) + 1 there is one pixel too large.
    return [
        ([shift(0.3, 0.4), shift(50.6, -30.3)], [(240, 320), (240, 320)]),  # two translations
        (
            [shift(0.3, 0.4), rotation_homography(K, yaw(20))],
            [(240, 320), (240, 320)],
        ),  # a turning camera
        (
            [
                shift(0.3, 0.4),
                rotation_homography(K, yaw(-15)),
                rotation_homography(K, yaw(15)) @ shift(0.2, 0.1),
            ],
            [(200, 300, 3), (240, 320), (260, 360)],
        ),  # three images, sizes differ
        # a roll, then a general homography: each of the four corners alone decides a side of the box
        ([rotation_homography(K, rotation_z(np.radians(25)) @ yaw(15))], [(240, 320)]),
        ([_projective()], [(240, 320, 3)]),
        # the same turn with H scaled by -0.01: a homography's overall sign is arbitrary (a DLT's
        # SVD returns either), so w < 0 at every corner and only a division by w itself is right
        (
            [-0.01 * shift(0.3, 0.4), -0.01 * rotation_homography(K, yaw(20))],
            [(240, 320), (240, 320)],
        ),
        ([np.eye(3), shift(-50.6, -30.3)], [(240, 320), (240, 320)]),  # the reference image, H = I
    ]


def _projective():
    """A general homography (perspective in both directions, a shear): no two corners share an extreme."""
    return np.array([[0.9, 0.25, 410.3], [-0.15, 1.1, 60.6], [0.0004, -0.0006, 1.0]])


def _corners(
    Hs,
    shapes,
    divide: bool = True,
    last: float = 1,
    first: float = 0,
    transposed: bool = False,
    swap: bool = False,
    one_shape: bool = False,
    keep: tuple[int, ...] = (0, 1, 2, 3),
    abs_w: bool = False,
) -> np.ndarray:
    """Every image's mapped corners, right or with one typical slip.

    ``transposed`` maps rows by ``c @ H`` (H^T), ``swap`` reads the shape as (w, h), ``one_shape``
    uses shapes[0] for every image, ``first`` and ``last`` put the corners at u = first and u = w -
    last (right: 0 and w - 1; pixel edges: -1/2 and w - 1/2; 1-based: 1 and w), ``keep`` maps only
    those corners (TL, TR, BR, BL = 0, 1, 2, 3), ``abs_w`` divides by |w| instead of w.
    """
    pts = []
    for H, s in zip(Hs, shapes, strict=True):
        s = shapes[0] if one_shape else s
        h, w = s[:2][::-1] if swap else s[:2]
        H = np.asarray(H)
        c = np.array(
            [
                [first, first, 1],
                [w - last, first, 1],
                [w - last, h - last, 1],
                [first, h - last, 1],
            ],
            float,
        )[list(keep)] @ (H if transposed else H.T)
        w3 = np.abs(c[:, 2:]) if abs_w else c[:, 2:]
        pts.append(c[:, :2] / w3 if divide else c[:, :2])
    return np.vstack(pts)


def _box(p: np.ndarray) -> np.ndarray:
    return np.array([np.floor(p.min(axis=0) + 1e-9), np.ceil(p.max(axis=0) - 1e-9)])


def _missing_corners_box(s, keep: tuple[int, ...]):
    """The box from only the corners ``keep`` of every image; None where it is the right box."""
    box = _box(_corners(s.Hs, s.shapes, keep=keep))
    return None if np.allclose(box, s.expected) else box


def _canvas_context(args, expected):
    Hs, shapes = args
    return SimpleNamespace(Hs=Hs, shapes=shapes, expected=expected, corners=_corners(Hs, shapes))


def _one_image_box(s, k: int):
    """The box of image k alone; None where that image alone gives the whole box.

    A `return` inside the loop keeps only the first image; `pts = ...` instead of `pts.append(...)`
    keeps only the last.
    """
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
    *(
        Mistake(
            f"missing {name}",
            lambda s, k=k: _missing_corners_box(s, tuple(j for j in range(4) if j != k)),
            f"your box leaves out the {name} corner {corner}: map all four corners of every image. With a roll or "
            "perspective (the last test input) each corner alone can decide a side of the box.",
        )
        for k, (name, corner) in enumerate(
            (
                ("top-left", "(0, 0)"),
                ("top-right", "(w-1, 0)"),
                ("bottom-right", "(w-1, h-1)"),
                ("bottom-left", "(0, h-1)"),
            )
        )
    ),
    Mistake(
        "two corners only",
        lambda s: (
            [
                b
                for keep in ((0, 2), (1, 3), (0, 1), (2, 3), (0, 3), (1, 2))
                if (b := _missing_corners_box(s, keep)) is not None
            ]
            or None
        ),
        "your box comes from only two corners of each image: map all four, (0, 0), (w-1, 0), (w-1, h-1) and "
        "(0, h-1). Under a roll or perspective (the last test input) the other two stick out.",
    ),
    Mistake(
        "divide",
        lambda s: _box(_corners(s.Hs, s.shapes, divide=False)),
        "you forgot to divide the mapped corners by their third coordinate w (homogeneous to pixels).",
    ),
    Mistake(
        "divided by |w|",
        lambda s: _box(_corners(s.Hs, s.shapes, abs_w=True)),
        "divide by w itself, not |w|: a homography's overall sign is arbitrary (H and -H are the same "
        "homography; a DLT's SVD returns either), so w can be negative at every corner, and x / |w| then "
        "mirrors the points through the origin.",
    ),
    Mistake(  # before "w - 1": on the last input, where this shows first, both give the same box
        "floor(max) + 1",
        lambda s: (
            [
                b
                for b in (
                    np.array([s.expected[0], np.floor(s.corners.max(0)) + 1]),
                    np.array([s.expected[0], np.trunc(s.corners.max(0)) + 1]),
                )
                if not np.array_equal(b, s.expected)
            ]
            or None
        ),
        "the maximum rounds up with np.ceil: floor(max) + 1 (or int(max) + 1) is one pixel too large where a "
        "corner lands exactly on a pixel, as the reference image's do here (H = I: its corner (w-1, h-1) stays "
        "where it is). Use np.floor for the minimum and np.ceil for the maximum.",
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
        "centres at half-integers",
        lambda s: _box(_corners(s.Hs, s.shapes, first=0.5, last=0.5)),
        "a half-pixel slip: you mapped (1/2, 1/2) to (w - 1/2, h - 1/2), the convention with pixel centres at "
        "half-integers. In camlab (and numpy, OpenCV's warps) pixel centres are at integers: the corner pixels "
        "are (0, 0) and (w - 1, h - 1).",
    ),
    Mistake(
        "1-based",
        lambda s: _box(_corners(s.Hs, s.shapes, first=1, last=0)),
        "you counted pixels from 1: the corner pixels are at 0 and w - 1 (not 1 and w), as numpy indexes them.",
    ),
    Mistake(
        "1-based first corner",
        lambda s: _box(_corners(s.Hs, s.shapes, first=1, last=1)),
        "your first corner is at (1, 1): pixels are counted from 0, so the corner pixels are (0, 0) and "
        "(w - 1, h - 1), as numpy indexes them (img[0, 0] is the top-left pixel). Or you rounded with np.ceil "
        "at both ends, which gives the same box here: the minimum must round down (np.floor).",
    ),
    Mistake(
        "divided by the width",
        lambda s: _box(
            np.vstack(
                [
                    c / sh[1]
                    for c, sh in zip(np.split(s.corners, len(s.shapes)), s.shapes, strict=True)
                ]
            )
        ),
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
        "size for the maximum",
        lambda s: [
            np.array([s.expected[0], s.expected[1] - s.expected[0] + 1]),
            np.array([s.expected[0], s.expected[1] - s.expected[0]]),
        ],
        "the second row is the canvas size, not its corner: return the box's corners [[u_min, v_min], "
        "[u_max, v_max]] (canvas_bounds turns them into a size, u_max - u_min + 1).",
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
        "truncated the whole box",
        lambda s: np.trunc(np.array([s.corners.min(0), s.corners.max(0)])),
        "astype(int) (like int()) truncates towards zero, and on the whole box that cuts both ends: a negative "
        "minimum moves inwards (int(-30.3) = -30) and the maximum down (int(369.6) = 369), so warped pixels are "
        "cut off. Use np.floor for the minimum and np.ceil for the maximum, then convert.",
    ),
    Mistake(
        "floor both",
        lambda s: np.floor(np.array([s.corners.min(0), s.corners.max(0)])),
        "you floored both ends: floor is right for the minimum, but the maximum must round up (np.ceil), "
        "or the last partly covered column and row are cut off.",
    ),
    Mistake(
        "shifted to the origin",
        lambda s: None if np.allclose(s.expected[0], 0) else s.expected - s.expected[0],
        "that is the box after the shift T (its minimum moved to (0, 0)); return the box of the warped corners "
        "themselves, before any shift: a negative u_min or v_min is right (the canvas's T comes later, from it).",
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
        right = _canvas_box_reference(Hs, shapes)
        a = rows[0].answer(_canvas_context((Hs, shapes), right))
        if a is None:  # the slip cannot show on this input: the student's box is the right one
            return right
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
        exception_hint=lambda exc, args: shape_unpack_hint(exc, "s"),
        wrong_variants=(
            (lambda Hs, shapes: _canvas_box_reference(Hs, shapes)[:, ::-1], "(u, v)"),
            (_canvas_variant("first image only"), "`return` indented inside"),
            (_canvas_variant("last image only"), "instead of adding"),
            (_canvas_variant("shapes[0]"), "first image's shape"),
            (_canvas_variant("divide"), "divide"),
            (_canvas_variant("divided by |w|"), "not |w|"),
            (_canvas_variant("w - 1"), "w - 1"),
            (_canvas_variant("pixel edges"), "pixel edges"),
            (_canvas_variant("1-based"), "counted pixels from 1"),
            (_canvas_variant("1-based first corner"), "first corner is at (1, 1)"),
            (_canvas_variant("divided by the width"), "divided by the image width"),
            (_canvas_variant("H transposed"), "H transposed"),
            (_canvas_variant("H inverted"), "inverse of H"),
            (_canvas_variant("width and height swapped"), "width and height swapped"),
            (_canvas_variant("size for the maximum"), "canvas size, not its corner"),
            (_canvas_variant("truncated"), "truncate towards zero"),
            (_canvas_variant("truncated the whole box"), "cuts both ends"),
            (_canvas_variant("floor both"), "floored both ends"),
            (_canvas_variant("floor(max) + 1"), "floor(max) + 1"),
            (_canvas_variant("shifted to the origin"), "after the shift T"),
            *(
                (_canvas_variant(f"missing {c}"), f"leaves out the {c} corner")
                for c in ("top-left", "top-right", "bottom-right", "bottom-left")
            ),
            (_canvas_variant("two corners only"), "only two corners"),
            (
                lambda Hs, shapes: np.ceil(
                    np.array([_corners(Hs, shapes).min(0), _corners(Hs, shapes).max(0)])
                ),
                "np.ceil at both ends",
            ),
            (
                lambda Hs, shapes: np.array(
                    [_corners(Hs, shapes).min(0), _corners(Hs, shapes).max(0)]
                ),
                "round outwards",
            ),
        ),
    )
)
