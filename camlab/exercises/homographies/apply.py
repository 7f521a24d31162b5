"""Exercise 1 of lesson 07: applying a homography to points (`apply_homography`)."""

from __future__ import annotations

import numpy as np

from ...projective import map_points
from .._answers import same_array, shape_problem
from .._core import Exercise, register_exercise


def _apply_cases():
    H = np.array([[1.1, 0.2, 5.0], [-0.1, 0.9, 12.0], [1e-3, 2e-3, 1.0]])
    rng = np.random.default_rng(3)
    return [
        # h33 = 2: the scale of H is arbitrary, so w is never 1 here (a missing division shows);
        # h12 = 1 makes H non-symmetric, so X @ H (H transposed) is told apart already here
        (
            np.array([[4.0, 1.0, 0.0], [0.0, 6.0, 0.0], [0.0, 0.0, 2.0]]),
            np.array([[1.0, 1.0], [2.0, -1.0]]),
        ),
        (0.5 * H, rng.uniform(0, 400, (5, 2))),  # h33 = 0.5 and w varies from point to point
        (3.0 * H, np.array([[0.0, 0.0]])),
        # w < 0 at the second point: it lies beyond the line that H sends to infinity (section 3),
        # so dividing by |w| instead of w puts its image on the wrong side
        (
            2.0 * np.array([[1.0, 0.1, 4.0], [0.05, 1.0, -3.0], [-4e-3, 1e-3, 1.0]]),
            np.array([[50.0, 20.0], [400.0, 100.0], [120.0, 300.0]]),
        ),
    ]


def _apply_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return (
            problem
            + ". Lift to (u, v, 1), multiply, divide by the third coordinate, return (N, 2)."
        )
    H, pts = args
    x = np.column_stack([pts, np.ones(len(pts))])
    y = x @ H.T
    g = np.asarray(got, dtype=float)
    if np.allclose(g, y[:, :2] / H[2, 2], rtol=1e-6) and not np.allclose(y[:, 2], H[2, 2]):
        return (
            "you divided by h33, but w is the third coordinate of each mapped point, "
            "w = h31 u + h32 v + h33, which changes from point to point: divide by Y[:, 2:3]."
        )
    w_no_h33 = y[:, 2:] - H[2, 2] + 1.0  # h31 u + h32 v + 1: the textbook form assuming h33 = 1
    if not np.allclose(w_no_h33, 1.0) and np.allclose(g, y[:, :2] / w_no_h33, rtol=1e-6):
        return (
            "you divided by h31 u + h32 v + 1, the form that assumes h33 = 1. These test matrices are not "
            "scaled to h33 = 1, so w = h31 u + h32 v + h33: divide by Y[:, 2:3], the whole third coordinate."
        )
    if np.allclose(g, y[:, :2], rtol=1e-6):
        also = (
            f" (Or you divided by h31 u + h32 v + 1, which assumes h33 = 1; here h33 = {H[2, 2]:g}.)"
            if not np.isclose(H[2, 2], 1.0)
            else ""
        )
        return "you forgot to divide by w, the third homogeneous coordinate: (x/w, y/w)." + also
    z = x @ H
    if np.allclose(g, z[:, :2] / z[:, 2:], rtol=1e-6):
        return "you multiplied by H transposed: with points as rows, x' = X @ H.T."
    if g.T.shape == np.shape(expected) and np.allclose(g.T, expected, rtol=1e-6):
        return (
            "your result is transposed: its columns are the points, as in the column form H @ X.T. "
            "With points as rows return (N, 2): (H @ X.T).T, or X @ H.T directly."
        )
    if np.allclose(g, np.asarray(expected)[:, ::-1], rtol=1e-6):
        return "you returned (v', u'): the columns are swapped. Return u' first, then v'."
    swapped = x[:, [1, 0, 2]] @ H.T
    if np.allclose(g, swapped[:, :2] / swapped[:, 2:], rtol=1e-6):
        return "you lifted (v, u, 1): points[:, 0] is u (the column) and points[:, 1] is v, so lift (u, v, 1)."
    cause = (
        _shift_slip(g, x, H, expected) or _conjugated_slip(g, pts, H) or _rounded_slip(g, expected)
    )
    if cause:
        return cause
    if (y[:, 2] < 0).any() and np.allclose(g, y[:, :2] / np.abs(y[:, 2:]), rtol=1e-6):
        return (
            "you divided by |w| (or took the sign away): w is negative for a point beyond the line that H "
            "sends to infinity (here "
            + ", ".join(_fmt_point(q) for q in pts[y[:, 2] < 0])
            + "), and (u', v') = (x/w, y/w) needs w's sign, or its image lands on the wrong side. "
            "Divide by Y[:, 2:3] itself."
        )
    for factor in (1e3, 1e-3):
        if np.allclose(g, factor * np.asarray(expected), rtol=1e-6):
            return (
                f"your points are {factor:g} times the expected ones: a unit slip (mm for m, or a scale "
                "applied twice). The points and H are in pixels; the result is in pixels too."
            )
    if np.allclose(g, -np.asarray(expected), rtol=1e-6):
        return (
            "your points have the wrong sign: you divided by -w (or negated the result). "
            "w is the third coordinate itself, Y[:, 2:3]; (u', v') = (Y[:, 0] / w, Y[:, 1] / w)."
        )
    inverse = x @ np.linalg.inv(H).T
    if np.allclose(g, inverse[:, :2] / inverse[:, 2:], rtol=1e-6):
        return "you applied the inverse, H^-1: the prompt maps points by H itself, x' ~ H x."
    if np.allclose(g, expected, rtol=1e-5, atol=1e-6):  # right method, float32 arithmetic
        return (
            "your answer agrees to about 7 digits: the method is right, but the arithmetic ran in float32 "
            "(float32 inputs, or np.float32 somewhere). Compute in float64: np.asarray(H, dtype=float)."
        )
    return (
        "check the three steps: lift to (u, v, 1), multiply by H (X @ H.T for rows), divide by w."
    )


def _rounded_slip(g, expected) -> str:
    """The answer is the right one rounded to whole pixels (np.round, astype(int)): say so ("" if not)."""
    e = np.asarray(expected, dtype=float)
    if np.allclose(e, np.round(e)) or not (
        np.array_equal(g, np.round(e)) or np.array_equal(g, np.trunc(e))
    ):
        return ""
    return (
        "your points are the right ones rounded to whole pixels (np.round, astype(int) or an integer "
        "array): a mapped point lands between pixel centres, and rounding throws away up to half a "
        "pixel. Return the float64 quotients x / w unrounded."
    )


def _shift_slip(g, x, H, expected) -> str:
    """Name a shift of the points or of the result by half a pixel or a whole one ("" if none)."""
    for shift in (0.5, -0.5, 1.0, -1.0):
        moved_in = (x + [shift, shift, 0]) @ H.T
        if np.allclose(g, np.asarray(expected) + shift, rtol=1e-6, atol=1e-9) or np.allclose(
            g, moved_in[:, :2] / moved_in[:, 2:], rtol=1e-6, atol=1e-9
        ):
            if abs(shift) == 0.5:
                return (
                    f"you shifted the points (or the result) by {shift:+g} px: a half-pixel offset. The course "
                    "puts pixel centres at integers, so map the points as given: no +0.5 or -0.5 anywhere."
                )
            return (
                f"you shifted the points (or the result) by {shift:+g} px: counting pixels from 1? The course "
                "counts from 0 (pixel (0, 0) is the top-left one), so map the points as given."
            )
    return ""


def _conjugated_slip(g, pts, H) -> str:
    """Name a change of coordinates made on the way in and undone on the way out ("" if none).

    H is not invariant under such a change (H' = S^-1 H S is another matrix), so swapping u and v,
    shifting by half a pixel or changing the unit on both sides maps the points by the wrong H.
    """
    pts = np.asarray(pts, dtype=float)
    changes = (
        (
            lambda q: q[:, ::-1],
            lambda q: q[:, ::-1],
            "you swapped u and v on the way in and back on the way out, as if the points were "
            "(row, column) = (v, u): here they are (u, v), and H is written for (u, v, 1). "
            "Lift the points as given, (points[:, 0], points[:, 1], 1).",
        ),
        (
            lambda q: q + 0.5,
            lambda q: q - 0.5,
            "you added half a pixel before mapping and took it off after (pixel corners at integers): "
            "the course puts pixel centres at integers, and H is written for those coordinates, so a "
            "projective map does not commute with the shift. Map the points as given.",
        ),
        (
            lambda q: q - 0.5,
            lambda q: q + 0.5,
            "you took half a pixel off before mapping and added it back after: the course puts pixel "
            "centres at integers, and H is written for those coordinates. Map the points as given.",
        ),
    ) + tuple(
        (
            lambda q, f=f: q * f,
            lambda q, f=f: q / f,
            f"you changed the unit of the points (x {f:g}) before mapping and back after: H is written "
            "for pixels (its third row carries 1/pixel), so it needs the points in pixels. "
            "Map the points as given.",
        )
        for f in (1e3, 1e-3)
    )
    for into, back, hint in changes:
        with np.errstate(all="ignore"):
            moved = np.column_stack([into(pts), np.ones(len(pts))]) @ np.asarray(H).T
            candidate = back(moved[:, :2] / moved[:, 2:])
        if g.shape == candidate.shape and np.allclose(g, candidate, rtol=1e-6, atol=1e-9):
            return hint
    return ""


def _h33_is_one(H, points):
    """The textbook formula that assumes h33 = 1: divide by h31 u + h32 v + 1."""
    x = np.column_stack([points, np.ones(len(points))])
    y = x @ np.asarray(H).T
    return y[:, :2] / (y[:, 2:] - H[2, 2] + 1.0)


def _fmt_point(q) -> str:
    return "(" + ", ".join(f"{c:g}" for c in q) + ")"


def apply_homography(H, points):
    """Lift to (u, v, 1), multiply (rows: X @ H.T), divide by w.

    Parameters
    ----------
    H : (3, 3) array_like
        The homography.
    points : (N, 2) array_like
        Points (u, v), pixels.

    Returns
    -------
    (N, 2) ndarray
        The mapped points, H (u, v, 1) divided by its third coordinate.
    """
    X = np.column_stack([points, np.ones(len(points))])
    Y = X @ np.asarray(H, dtype=float).T
    return Y[:, :2] / Y[:, 2:3]


register_exercise(
    Exercise(
        name="apply_homography",
        lesson="07",
        reference=map_points,
        cases=_apply_cases,
        compare=same_array(rtol=1e-9, atol=1e-9),
        diagnose=_apply_diagnosis,
        wrong_variants=(
            (lambda H, p: (np.column_stack([p, np.ones(len(p))]) @ H.T)[:, :2], "divide by w"),
            (lambda H, p: map_points(np.asarray(H).T, p), "transposed"),
            (lambda H, p: map_points(H, p).T, "result is transposed"),
            (lambda H, p: map_points(H, p)[:, ::-1], "columns are swapped"),
            (lambda H, p: map_points(H, np.asarray(p)[:, ::-1]), "you lifted"),
            (lambda H, p: map_points(np.linalg.inv(H), p), "the inverse"),
            (lambda H, p: _h33_is_one(H, p), "assumes h33 = 1"),
            (lambda H, p: map_points(H, np.asarray(p) + 0.5), "half-pixel offset"),
            (lambda H, p: map_points(H, p) + 0.5, "half-pixel offset"),
            (lambda H, p: -map_points(H, p), "wrong sign"),
            (
                lambda H, p: (np.column_stack([p, np.ones(len(p))]) @ H.T)[:, :2] / H[2, 2],
                "divided by h33",
            ),
            (
                lambda H, p: (lambda Y: Y[:, :2] / np.abs(Y[:, 2:]))(
                    np.column_stack([p, np.ones(len(p))]) @ np.asarray(H).T
                ),
                "took the sign away",
            ),
            (lambda H, p: map_points(H, p).tolist(), "you returned a list"),
            (lambda H, p: map_points(H, np.asarray(p) + 1.0), "counting pixels from 1"),
            (lambda H, p: 1000 * map_points(H, p), "a unit slip"),
            (lambda H, p: map_points(H, np.asarray(p)[:, ::-1])[:, ::-1], "(row, column)"),
            (
                lambda H, p: map_points(H, np.asarray(p) + 0.5) - 0.5,
                "before mapping and took it off",
            ),
            (lambda H, p: 1000 * map_points(H, np.asarray(p) / 1000), "changed the unit"),
            (
                lambda H, p: map_points(np.float32(H), np.float32(p)).astype(np.float64),
                "ran in float32",
            ),
        ),
        ndarray_only=True,
        teaching=apply_homography,
    )
)


# ---------------------------------------------------------------- exercise 3: RANSAC's number of samples
