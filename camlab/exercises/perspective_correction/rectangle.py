"""Exercise 1 of lesson 10: the homography that maps four corners to a w x h rectangle (`rectangle_homography`)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import perspective as pp
from ... import scenes
from ...homography import estimate_homography
from ...projective import hartley_normalise, map_points
from .._answers import same_up_to_scale, shape_problem
from .._core import Exercise, Mistake, register_exercise


def _rect_cases():
    return [
        # offset by (10, 20), not equally: with equal offsets, photo corners read as (v, u) and a
        # target written as (v, u) give the same H, and the check could not say which slip it was;
        # 150 x 50 onto 101 x 51, another shape: a translated copy would make a normalised DLT's
        # H_hat the identity, and a normalisation undone the wrong way would read as the inverse
        (np.array([[10.0, 20.0], [160.0, 20.0], [160.0, 70.0], [10.0, 70.0]]), (101, 51)),
        (scenes.sample_photo("page").corners, (210, 297)),
        (scenes.sample_photo("facade").corners, (400, 300)),
    ]


def _rect_target(w, h, order=(0, 1, 2, 3), offset=0.0, extent=None):
    """The target corners TL, TR, BR, BL of a w x h image (``extent``: the far corner), in ``order``."""
    x1, y1 = (w - 1, h - 1) if extent is None else extent
    target = np.array([[0, 0], [x1, 0], [x1, y1], [0, y1]], dtype=float) + offset
    return target[list(order)]


_PIXEL_CENTRES = (
    "camlab's pixel coordinates put the centre of the top-left pixel at (0, 0) (docs/conventions.md), "
    "so the corners go to the corner pixels' centres (0, 0), (w - 1, 0), (w - 1, h - 1), (0, h - 1)."
)

_RECT_MISTAKES = (
    # mistakes in H itself: compared with the right H, up to scale
    Mistake(
        "inverse",
        lambda s: np.linalg.inv(s.expected),
        "your H maps the rectangle into the photo; the rectifying H goes from the photo corners to the "
        "rectangle: write each pair's equations with the photo corner (u, v) as the source and the "
        "target corner (x, y) as the result, not the other way round.",
    ),
    Mistake(
        "transposed",
        lambda s: s.expected.T,
        "your H is the transpose of the right one: with points as rows a homography maps them by "
        "x @ H.T, and the DLT's null vector fills H row by row (h.reshape(3, 3), not order='F' or .T).",
    ),
    Mistake(
        "corners as (v, u)",
        lambda s: s.fit(s.corners[:, ::-1], s.target()),
        "you swapped u and v of the photo corners (read them as (row, column)?): a point is (u, v), "
        "column first, and corners[:, 0] is u.",
    ),
    # mistakes in the target rectangle
    Mistake(
        "size read as (height, width)",
        lambda s: s.fit(s.corners, _rect_target(s.h, s.w)),
        lambda s: (
            f"you read size as (height, width): your target is {s.h - 1} wide and {s.w - 1} tall. A size "
            f"is (width, height) (docs/conventions.md), so width, height = size, here {s.w} and {s.h}."
        ),
    ),
    Mistake(
        "target as (v, u)",
        lambda s: s.fit(s.corners, s.target()[:, ::-1]),
        "your target corners are (row, column) = (v, u): a point is (u, v), so the top-right corner is "
        "(w - 1, 0), not (0, w - 1).",
    ),
    Mistake(
        "both as (v, u)",
        lambda s: s.fit(s.corners[:, ::-1], s.target()[:, ::-1]),
        "both your photo corners and your target corners are (row, column) = (v, u): a point is "
        "(u, v), column first, so corners[:, 0] is u and the top-right target is (w - 1, 0).",
    ),
    Mistake(
        "off by one",
        lambda s: s.fit(s.corners, _rect_target(s.w, s.h, extent=(s.w, s.h))),
        "off by one: the last pixel centre of a width-w image is at u = w - 1, so map to "
        "(w - 1, 0), (w - 1, h - 1), (0, h - 1).",
    ),
    Mistake(
        "1-based",
        lambda s: s.fit(s.corners, _rect_target(s.w, s.h, offset=1.0)),
        "your target is 1-based, (1, 1) to (w, h): numpy and camlab count pixels from 0; "
        + _PIXEL_CENTRES,
    ),
    Mistake(
        "pixel edges",
        lambda s: s.fit(s.corners, _rect_target(s.w, s.h, offset=-0.5, extent=(s.w, s.h))),
        "half a pixel: you mapped to the outer edges of the corner pixels, (-0.5, -0.5) to (w - 0.5, "
        "h - 0.5); " + _PIXEL_CENTRES,
    ),
    Mistake(
        "half a pixel in",
        lambda s: s.fit(s.corners, _rect_target(s.w, s.h, offset=0.5, extent=(s.w - 2, s.h - 2))),
        "half a pixel: you mapped to (0.5, 0.5) to (w - 1.5, h - 1.5); " + _PIXEL_CENTRES,
    ),
    Mistake(
        "shifted by half a pixel",
        lambda s: next(
            (
                H
                for d in (-0.5, 0.5)
                if s.same(H := s.fit(s.corners, _rect_target(s.w, s.h, offset=d)))
            ),
            None,
        ),
        "every corner is off by half a pixel (a +-0.5 shift of the whole target): "
        + _PIXEL_CENTRES,
    ),
    Mistake(
        "Z order",
        lambda s: s.fit(s.corners, s.target((0, 1, 3, 2))),
        "your target corners are in Z order (TL, TR, BL, BR): they must go round the rectangle in the "
        "corners' order, TL, TR, BR, BL = (0, 0), (w - 1, 0), (w - 1, h - 1), (0, h - 1).",
    ),
    Mistake(
        "third row's sign",
        lambda s: _sign_slip(s.corners, (s.w, s.h)),
        "the third row of H has the wrong sign: x (h31 u + h32 v + 1) = h11 u + h12 v + h13 moves "
        "x h31 u and x h32 v to the left as -x u and -x v (and -y u, -y v in the y row); you wrote +x u, "
        "+x v. (An axis-aligned rectangle, h31 = h32 = 0, hides this slip.)",
    ),
    Mistake(
        "third row's sign in the y row only",
        lambda s: _sign_slip(s.corners, (s.w, s.h), rows="y"),
        "the y row of your 8 x 8 system has the wrong sign on its last two entries: y (h31 u + h32 v + 1) "
        "= h21 u + h22 v + h23 moves y h31 u and y h32 v to the left as -y u and -y v; you wrote +y u, +y v "
        "(your x row is right).",
    ),
    Mistake(
        "third row's sign in the x row only",
        lambda s: _sign_slip(s.corners, (s.w, s.h), rows="x"),
        "the x row of your 8 x 8 system has the wrong sign on its last two entries: x (h31 u + h32 v + 1) "
        "= h11 u + h12 v + h13 moves x h31 u and x h32 v to the left as -x u and -x v; you wrote +x u, +x v "
        "(your y row is right).",
    ),
    # lesson 07's normalised DLT (Hartley's T1 for the photo corners, T2 for the target), undone wrongly
    Mistake(
        "normalisation not undone",
        lambda s: next((H for H in _normalised(s) if s.same(H)), None),
        "your H is H_hat, the homography between the NORMALISED points: you conditioned the corners "
        "(lesson 07's T, centroid at 0, mean distance sqrt 2) and did not undo it. Undo it: "
        "H = T2^-1 H_hat T1 (T1 for the photo corners, T2 for the target; T2 = I if you normalised "
        "the photo corners only).",
    ),
    Mistake(
        "normalisation undone on the wrong side",
        lambda s: next((H for H in _normalised(s, undone_wrongly=True) if s.same(H)), None),
        "you normalised the corners (lesson 07's T) and undid it on the wrong side or with T1 and T2 "
        "swapped: H_hat maps T1 x to T2 x', so H = T2^-1 H_hat T1 (the photo's T1 on the right, where "
        "the photo corners go in; the target's T2 inverted on the left).",
    ),
    Mistake(
        "rounded",
        lambda s: next(
            (H for k in range(7) if s.same(H := np.round(s.expected / s.expected[2, 2], k))), None
        ),
        "your H is the right one rounded (np.round, or printed and copied): the third row's h31 and "
        "h32 are about 1e-3 per pixel or less, and multiplied by u, v in the hundreds their lost digits "
        "move the corners; return H at full precision.",
    ),
    Mistake(
        "counter-clockwise",
        lambda s: next(  # (0, 3, 2, 1) and its rolls: corners[::-1] is one of them
            (
                H
                for k in range(4)
                if (H := s.fit(s.corners, s.target(np.roll([0, 3, 2, 1], -k)))) is not None
                and s.same(H)
            ),
            None,
        ),
        "your corners and target go round in opposite senses (one counter-clockwise, e.g. the "
        "corners reversed, or a target TL, BL, BR, TR): the result is mirrored (section 4). Pair TL, "
        "TR, BR, BL with (0, 0), (w - 1, 0), (w - 1, h - 1), (0, h - 1) in that order.",
    ),
    Mistake(
        "target starts elsewhere",
        lambda s: next(
            (
                H
                for k in (1, 2, 3)
                if (H := s.fit(s.corners, s.target(np.roll(range(4), -k)))) is not None
                and s.same(H)
            ),
            None,
        ),
        "your target corners go round the right way but start at the wrong corner: the photo's TL "
        "goes to (0, 0), so the target list is (0, 0), (w - 1, 0), (w - 1, h - 1), (0, h - 1), in "
        "that order.",
    ),
)
"""Ex 1's typical mistakes, each the H it gives, in the order the diagnosis tries them."""


def _normalised(s, undone_wrongly=False):
    """The H of lesson 07's normalised DLT not undone (or, ``undone_wrongly``, undone wrongly).

    Both point sets conditioned (T1, T2), or the photo corners only (T2 = I).
    """
    T1 = hartley_normalise(s.corners).T
    found = []
    for T2 in (hartley_normalise(s.target()).T, np.eye(3)):
        H_hat = T2 @ s.expected @ np.linalg.inv(T1)
        if not undone_wrongly:
            found.append(H_hat)
            continue
        i1, i2 = np.linalg.inv(T1), np.linalg.inv(T2)
        found += [i1 @ H_hat @ T2, T2 @ H_hat @ i1, T1 @ H_hat, H_hat @ i2, i2 @ H_hat @ i1]
        found += [T2 @ H_hat @ T1, i1 @ H_hat @ i2]
    return found


def _sign_slip(corners, size, rows="xy"):
    """A typical slip: the 8 x 8 system with +x u, +x v (and +y u, +y v) where -x u, -x v belong.

    ``rows``: the rows that carry the slip ("xy" both, "x" or "y" one only).
    """
    sx, sy = (1 if "x" in rows else -1), (1 if "y" in rows else -1)
    A, b = [], []
    for (u, v), (x, y) in zip(np.asarray(corners, dtype=float), _rect_target(*size), strict=True):
        A += [
            [u, v, 1, 0, 0, 0, sx * x * u, sx * x * v],
            [0, 0, 0, u, v, 1, sy * y * u, sy * y * v],
        ]
        b += [x, y]
    try:
        return np.append(np.linalg.solve(np.array(A), np.array(b)), 1.0).reshape(3, 3)
    except np.linalg.LinAlgError:
        return None


def _fit_or_none(src, dst):
    """The homography taking src to dst, or None where the four pairs fix none (a mistake that cannot show here)."""
    try:
        return estimate_homography(src, dst)
    except ValueError:
        return None


def _rect_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    corners, (w, h) = args
    g = np.asarray(got, dtype=float)
    corners = np.asarray(corners, dtype=float)

    def same(wrong):
        return same_up_to_scale(g, wrong, rtol=1e-6)

    context = SimpleNamespace(
        expected=np.asarray(expected, dtype=float),
        corners=corners,
        w=int(w),
        h=int(h),
        target=lambda order=(0, 1, 2, 3): _rect_target(w, h, order),
        fit=_fit_or_none,
        same=same,
    )
    causes = [
        m.hint(context) if callable(m.hint) else m.hint
        for m in _RECT_MISTAKES
        if (wrong := m.answer(context)) is not None and same(wrong)
    ]
    if len(causes) == 1:
        return causes[0]
    if causes:  # several slips give this same H on this input: name them all, not the first
        return "on this input these slips give the same H, so it is one of them: " + "; or ".join(
            causes
        )
    moved = map_points(g, corners)
    want = _rect_target(w, h)
    k = int(np.argmax(np.linalg.norm(moved - want, axis=1)))
    return (
        f"corner {k} ({'TL TR BR BL'.split()[k]}) goes to {np.round(moved[k], 2) + 0.0}, expected {want[k]}: check "
        "that H maps each photo corner (u, v) to its target pixel, TL, TR, BR, BL to (0, 0), (w - 1, 0), "
        "(w - 1, h - 1), (0, h - 1)."
    )


def rectangle_homography(corners, size):
    """Four pairs fix H: with h33 = 1 each pair gives two linear equations in the other 8 entries.

    Parameters
    ----------
    corners : (4, 2) array_like
        The quadrilateral's corners in the photo (u, v), pixels, in the order top-left, top-right,
        bottom-right, bottom-left.
    size : (2,) array_like of int
        The rectified image's (width, height), pixels.

    Returns
    -------
    (3, 3) ndarray
        H with h33 = 1 mapping the corners to (0, 0), (width - 1, 0), (width - 1, height - 1),
        (0, height - 1).

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 4.1.2 (inhomogeneous solution).
    """
    width, height = size
    target = np.array(
        [[0, 0], [width - 1, 0], [width - 1, height - 1], [0, height - 1]], dtype=float
    )
    A, b = [], []
    for (u, v), (x, y) in zip(np.asarray(corners, dtype=float), target, strict=True):
        A.append([u, v, 1, 0, 0, 0, -x * u, -x * v])  # x (h31 u + h32 v + 1) = h11 u + h12 v + h13
        A.append([0, 0, 0, u, v, 1, -y * u, -y * v])  # y (h31 u + h32 v + 1) = h21 u + h22 v + h23
        b += [x, y]
    h = np.linalg.solve(np.array(A), np.array(b))
    return np.append(h, 1.0).reshape(3, 3)


def _normalised_dlt(corners, size, slip):
    """A student's lesson-07 normalised DLT, with one ``slip`` in undoing the normalisation.

    "not undone" (H_hat returned), "swapped" (T1^-1 H_hat T2) or "one side" (only the photo corners
    normalised, undone as T1 H_hat).
    """
    target = _rect_target(*size)
    T1 = hartley_normalise(corners).T
    T2 = np.eye(3) if slip == "one side" else hartley_normalise(target).T
    H_hat = estimate_homography(map_points(T1, corners), map_points(T2, target), normalise=False)
    return {
        "not undone": H_hat,
        "swapped": np.linalg.inv(T1) @ H_hat @ T2,
        "one side": T1 @ H_hat,
    }[slip]


register_exercise(
    Exercise(
        name="rectangle_homography",
        lesson="10",
        reference=pp.rectangle_homography,
        cases=_rect_cases,
        compare=lambda got, expected: same_up_to_scale(got, expected, rtol=1e-6),
        diagnose=_rect_diagnosis,
        wrong_variants=(
            (
                lambda c, size: np.linalg.inv(pp.rectangle_homography(c, size)),
                "maps the rectangle into the photo",
            ),
            (lambda c, size: pp.rectangle_homography(c, size).T, "transpose"),
            (lambda c, size: pp.rectangle_homography(c, size[::-1]), "(height, width)"),
            (
                lambda c, size: estimate_homography(np.asarray(c)[:, ::-1], _rect_target(*size)),
                "swapped u and v",
            ),
            (
                lambda c, size: estimate_homography(c, _rect_target(*size, extent=size)),
                "off by one",
            ),
            (
                lambda c, size: estimate_homography(c, _rect_target(*size, offset=1.0)),
                "1-based",
            ),
            (
                lambda c, size: estimate_homography(
                    c, _rect_target(*size, offset=-0.5, extent=size)
                ),
                "outer edges of the corner pixels",
            ),
            (
                lambda c, size: estimate_homography(c, _rect_target(*size, offset=0.5)),
                "off by half a pixel",
            ),
            (
                lambda c, size: estimate_homography(c, _rect_target(*size, order=(0, 1, 3, 2))),
                "Z order",
            ),
            (_sign_slip, "third row of H has the wrong sign"),
            (lambda c, s: _sign_slip(c, s, rows="y"), "the y row of your 8 x 8 system"),
            (lambda c, s: _sign_slip(c, s, rows="x"), "the x row of your 8 x 8 system"),
            (
                lambda c, size: estimate_homography(c, _rect_target(*size)[:, ::-1]),
                "your target corners are",
            ),
            (
                lambda c, size: estimate_homography(
                    np.asarray(c)[:, ::-1], _rect_target(*size)[:, ::-1]
                ),
                "both your photo corners and your target corners",
            ),
            (
                lambda c, size: estimate_homography(c, _rect_target(*size, order=(1, 2, 3, 0))),
                "start at the wrong corner",
            ),
            (lambda c, size: _normalised_dlt(c, size, "not undone"), "did not undo it"),
            (lambda c, size: _normalised_dlt(c, size, "swapped"), "wrong side"),
            (lambda c, size: _normalised_dlt(c, size, "one side"), "wrong side"),
            (
                lambda c, size: estimate_homography(
                    c, [[0, 0], [0, size[1] - 1], np.subtract(size, 1), [size[0] - 1, 0]]
                ),
                "counter-clockwise",
            ),
        ),
        ndarray_only=True,
        up_to_scale=True,  # a failed check shows the expected H at the student's scale
        teaching=rectangle_homography,
    )
)
