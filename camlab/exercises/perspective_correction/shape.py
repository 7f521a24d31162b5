"""Exercise 2 of lesson 10: a rectangle's aspect ratio and the focal length from its four corners (`rectangle_shape`)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import perspective as pp
from .._answers import SameArray, Tolerance
from .._core import Exercise, Mistake, first_mistake, register_exercise


def _shape_cases():
    """Rectangles photographed by cameras of known f (not whole pixels) and principal point (not the image centre)."""

    def photo(w, h, f, c, yaw, pitch, roll, distance):
        cy, sy, cp, sp, cr, sr = (
            np.cos(yaw),
            np.sin(yaw),
            np.cos(pitch),
            np.sin(pitch),
            np.cos(roll),
            np.sin(roll),
        )
        R = (
            np.array([[cr, -sr, 0], [sr, cr, 0], [0, 0, 1]])
            @ np.array([[1, 0, 0], [0, cp, -sp], [0, sp, cp]])
            @ np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
        )
        K = np.array([[f, 0, c[0]], [0, f, c[1]], [0, 0, 1.0]])
        plane = np.array([[-w, -h], [w, -h], [w, h], [-w, h]]) / 2  # TL, TR, BR, BL, y down
        X = np.column_stack([plane, np.zeros(4)]) @ R.T + [0, 0, distance]
        x = X @ K.T
        return x[:, :2] / x[:, 2:]

    return [
        (photo(2.97, 2.10, 812.7, (331.0, 226.5), 0.5, 0.35, 0.1, 5.0), (331.0, 226.5)),
        (photo(1.0, 1.6, 1187.3, (700.0, 380.0), -0.3, -0.45, -0.05, 4.0), (700.0, 380.0)),
        (photo(3.0, 1.0, 653.4, (330.0, 250.0), 0.25, 0.6, 0.0, 9.0), (330.0, 250.0)),
    ]


def _shape_reference(corners, principal_point):
    est = pp.estimate_aspect_ratio(corners, principal_point=principal_point)
    return est.ratio, est.focal_length


# (ratio, f) within a relative 1e-6: the closed form in float64, nothing rounded. A SameArray,
# so that a failed check names this tolerance.
_shape_compare = SameArray(Tolerance(1e-6, 0.0))


def _zhang_he(
    corners, principal_point, order=(0, 1, 3, 2), centre=True, minus=True, swap=False, at=None
):
    """Section 3 with the corners taken as m1..m4 in ``order`` (Zhang & He's: TL, TR, BL, BR).

    ``minus=False``: f^2 without its minus sign; ``swap=True``: the principal point as (c_v, c_u);
    ``at``: another centre used in place of the principal point.
    """
    c = np.asarray(principal_point, float)[::-1] if swap else np.asarray(principal_point, float)
    c = c if at is None else np.asarray(at, float)
    q = np.asarray(corners, dtype=float) - (c if centre else 0.0)
    m1, m2, m3, m4 = np.column_stack([q, np.ones(4)])[list(order)]
    k2 = np.cross(m1, m4) @ m3 / (np.cross(m2, m4) @ m3)
    k3 = np.cross(m1, m4) @ m2 / (np.cross(m3, m4) @ m2)
    n2, n3 = k2 * m2 - m1, k3 * m3 - m1
    f2 = (-1 if minus else 1) * (n2[0] * n3[0] + n2[1] * n3[1]) / (n2[2] * n3[2])
    return n2, n3, f2


def _shape_from(n2, n3, f2):
    ratio2 = ((n2[0] ** 2 + n2[1] ** 2) / f2 + n2[2] ** 2) / (
        (n3[0] ** 2 + n3[1] ** 2) / f2 + n3[2] ** 2
    )
    return ratio2, f2


_SHAPE_MISTAKES = (
    Mistake(
        "(f, ratio)",
        lambda s: (s.f, s.ratio),
        "you returned (f, ratio); return them as (ratio, f), w/h first.",
    ),
    Mistake(
        "h/w",
        lambda s: (1 / s.ratio, s.f),
        "your ratio is h/w (your f is right): either you inverted it (the edge TL-TR, n2 along e1, is "
        "the width, so w/h = |A^-1 n2| / |A^-1 n3|), or your m1 is not the top-left corner (TR or BL "
        "taken as TL turns the rectangle by 90 degrees and swaps width and height): m1, m2, m3, m4 = "
        "corners[[0, 1, 3, 2]], TL, TR, BL, BR.",
    ),
    Mistake(
        "squares",
        lambda s: (s.ratio**2, s.f**2),
        "you returned (w/h)^2 and f^2: take the square roots of both formulas.",
    ),
    Mistake(
        "ratio squared",
        lambda s: (s.ratio**2, s.f),
        "your ratio is (w/h)^2: section 3's formula gives the square; take np.sqrt.",
    ),
    Mistake(
        "f squared",
        lambda s: (s.ratio, s.f**2),
        "your f is f^2: section 3's formula gives the square; take np.sqrt.",
    ),
    Mistake(
        "section 2's order as m1..m4",
        lambda s: s.wrong(order=(0, 1, 2, 3)),
        "you took the corners TL, TR, BR, BL as m1, m2, m3, m4, but in section 3 (Zhang & He's numbering) "
        "m3 is the bottom-LEFT corner and m4 the bottom-right: m1, m2, m3, m4 = corners[[0, 1, 3, 2]].",
    ),
    Mistake(
        "principal point not subtracted",
        lambda s: s.wrong(centre=False),
        "the corners must be taken relative to the principal point (m_i = (u_i - c_u, v_i - c_v, 1)): the "
        "formula assumes A = diag(f, f, 1), a camera whose principal point is the origin.",
    ),
    Mistake(
        "principal point swapped",
        lambda s: s.wrong(swap=True),
        "you subtracted the principal point as (c_v, c_u): it comes as (c_u, c_v), column first like the "
        "corners (u, v), so m_i = (u_i - c_u, v_i - c_v, 1).",
    ),
    Mistake(
        "minus dropped in f^2",
        lambda s: s.wrong(minus=False),
        "your f^2 has lost its minus sign: e1 . e2 = 0 gives f^2 = -(n21 n31 + n22 n32) / (n23 n33), "
        "and for a real rectangle that is positive; without the minus it is negative (np.sqrt gives NaN, "
        "np.abs hides it but the ratio then divides by -f^2).",
    ),
)
"""Ex 'rectangle_shape''s typical mistakes, each the (ratio, f) it gives."""


def _other_centre(corners, principal_point, g, wrong) -> str | None:
    """The hint when ``g`` is the answer for corners taken relative to another centre than the given one."""
    c = np.asarray(principal_point, float)
    others = (
        ("the centroid of the corners", np.asarray(corners, float).mean(axis=0)),
        ("the centre of a 640 x 480 image, (319.5, 239.5)", (319.5, 239.5)),
        ("(320, 240), half a pixel off the centre of a 640 x 480 image", (320.0, 240.0)),
        (
            "a point half a pixel off the principal point (the corners or it shifted by 0.5 px: pixel edges for centres?)",
            c + 0.5,
        ),
        (
            "a point half a pixel off the principal point (the corners or it shifted by 0.5 px: pixel edges for centres?)",
            c - 0.5,
        ),
        ("the principal point counted from 1 (1-based)", c + 1),
        ("the principal point moved by -1 (a 1-based conversion done on a 0-based value)", c - 1),
    )
    for name, at in others:
        if not np.allclose(at, c) and np.allclose(g, wrong(at=at), rtol=1e-6):
            return (
                f"your answer matches the corners taken relative to {name}, not to the principal_point "
                "given: use principal_point as it comes, m_i = (u_i - c_u, v_i - c_v, 1); the test photos' "
                "principal points are off the image centre."
            )
    return None


def _shape_diagnosis(args, got, expected) -> str:
    try:
        g = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        g = None
    if g is None or g.shape != (2,):
        shape = f"a {type(got).__name__}" if g is None else f"shape {g.shape}"
        if isinstance(got, dict):
            shape = f"a dict with keys {sorted(map(str, got))}; return a tuple, (ratio, f)"
        return f"return two numbers, (ratio, f): w/h and the focal length in pixels; got {shape}."
    corners, principal_point = args
    ratio, f = expected

    def plain(**how):  # the slip with a plain np.sqrt: NaN where the square came out negative
        with np.errstate(invalid="ignore"):
            return np.sqrt(_shape_from(*_zhang_he(corners, principal_point, **how)))

    if not np.isfinite(g).all():
        for how, cause in (
            ({"minus": False}, _SHAPE_MISTAKES[-1].hint),
            ({"swap": True}, _SHAPE_MISTAKES[-2].hint),
            ({"centre": False}, _SHAPE_MISTAKES[-3].hint),
            ({"order": (0, 1, 2, 3)}, _SHAPE_MISTAKES[-4].hint),
        ):
            if np.allclose(g, plain(**how), rtol=1e-6, equal_nan=True):
                return "NaN: " + cause
        return (
            "NaN: f^2 (or (w/h)^2) came out negative, so np.sqrt gave NaN; a rectangle's true corners never do "
            "that. Check the corner order (section 3, Zhang & He, numbers them m1 = TL, m2 = TR, m3 = BL, m4 = BR, "
            "while the input is TL, TR, BR, BL, so m1, m2, m3, m4 = corners[[0, 1, 3, 2]]) and that the corners "
            "are taken relative to the principal_point given (not the image centre, not the origin)."
        )

    def wrong(**how):  # what a student who made this slip returns (np.sqrt of abs, so no NaN)
        ratio2, f2 = _shape_from(*_zhang_he(corners, principal_point, **how))
        return np.sqrt(abs(ratio2)), np.sqrt(abs(f2))

    centre_slip = _other_centre(corners, principal_point, g, wrong)
    if centre_slip:
        return centre_slip
    context = SimpleNamespace(ratio=ratio, f=f, wrong=wrong)
    cause = first_mistake(
        _SHAPE_MISTAKES, context, g, lambda mine, theirs: bool(np.allclose(mine, theirs, rtol=1e-6))
    )
    if cause:
        return cause
    if slip := _assumed_f_or_edges(corners, principal_point, g, ratio, f):
        return slip
    rounded = [  # only the right answer rounded (within 1%), not any wrong whole number
        name
        for name, mine, right in (("w/h", g[0], ratio), ("f", g[1], f))
        if not np.isclose(mine, right, rtol=1e-6)
        and np.isclose(mine, right, rtol=1e-2)
        and any(np.isclose(mine, round(right, d), rtol=1e-12) for d in range(5))
    ]
    if rounded and all(
        np.isclose(g[k], expected[k], rtol=1e-6) or n in rounded for k, n in enumerate(("w/h", "f"))
    ):
        return (
            f"your {' and '.join(rounded)} {'is' if len(rounded) == 1 else 'are'} rounded: return the "
            "numbers unrounded (the test cameras' f are not whole pixels, e.g. 812.7 px); round only "
            "when you print."
        )
    if slip := _units_or_precision(g, expected, f):
        return slip
    if np.isclose(g[1], f, rtol=1e-6):
        return (
            "your f is right but the ratio is not: w/h squared is ((n21^2 + n22^2)/f^2 + n23^2) over the same "
            "with n3; check that both n_ij are divided by f^2 on their first two entries only."
        )
    if np.isclose(g[0], ratio, rtol=1e-6):
        return (
            "your ratio is right but f is not: f^2 = -(n21 n31 + n22 n32) / (n23 n33), in pixels."
        )
    return (
        "check k2 and k3 (both use m1 x m4, dotted with m3 and m2), then n2 = k2 m2 - m1 and n3 = k3 m3 - m1, "
        "with m_i the corners relative to the principal point in Zhang & He's order TL, TR, BL, BR."
    )


def _units_or_precision(g, expected, f) -> str | None:
    """The hint for f off by a factor of 1000 (units), or an answer close but not within 1e-6."""
    for factor in (1e3, 1e-3):
        if np.isclose(g[1] * factor, f, rtol=1e-6):
            return (
                f"your f is off by a factor of {factor:g}: the prompt asks for pixels, from the "
                "corners in pixels; no mm or m."
            )
    if np.allclose(g, expected, rtol=1e-3) and not np.allclose(g, expected, rtol=1e-6):
        return (
            "your numbers are within 0.1% but the check wants them within a relative 1e-6: use section "
            "3's closed form in float64, and round or approximate nothing (no fitted or iterated f)."
        )
    return None


def _edge_ratios(corners):
    """w/h read off the photo's edge lengths: TL-TR over TL-BL, and the opposite edges' means."""
    tl, tr, br, bl = np.asarray(corners, dtype=float)
    top, bottom = np.linalg.norm(tr - tl), np.linalg.norm(br - bl)
    left, right = np.linalg.norm(bl - tl), np.linalg.norm(br - tr)
    return top / left, (top + bottom) / (left + right), np.sqrt(top * bottom / (left * right))


def _assumed_f_or_edges(corners, principal_point, g, ratio, f) -> str | None:
    """The hint for f assumed rather than solved, or w/h measured on the photo's edges."""
    n2, n3, _ = _zhang_he(corners, principal_point)
    fallback = 2 * max(principal_point)  # max(width, height) for a centred principal point
    for assumed in (640.0, fallback, g[1]):
        if np.isclose(assumed, f, rtol=1e-6):
            continue
        with np.errstate(invalid="ignore", divide="ignore"):
            mine = np.sqrt(_shape_from(n2, n3, assumed**2)[0])
        if np.isclose(g[0], mine, rtol=1e-6) and np.isclose(g[1], assumed, rtol=1e-6):
            named = (
                " (camlab's fallback when f is unknown: max(width, height) of the image)"
                if assumed in (640.0, fallback)
                else ""
            )
            return (
                f"your ratio follows from an assumed f = {assumed:.6g} px{named}, not from the corners: "
                f"solve f from e1 . e2 = 0, f^2 = -(n21 n31 + n22 n32) / (n23 n33) (here {f:.6g} px), "
                "then use that f in the ratio. A fallback f is only for when the corners fix none."
            )
    if any(np.isclose(g[0], r, rtol=1e-6) for r in _edge_ratios(corners)):
        return (
            "your w/h is read off the photo's edge lengths (|TR - TL| / |BL - TL|, or the opposite edges' "
            "means): in a perspective photo the edges are foreshortened by different amounts, so their "
            "lengths are not the rectangle's. Use section 3's formula, w/h = |A^-1 n2| / |A^-1 n3|."
        )
    return None


def rectangle_shape(corners, principal_point):
    """Zhang & He (section 3): k2, k3 from triple products, n2, n3, then f^2 and (w/h)^2.

    Parameters
    ----------
    corners : (4, 2) array_like
        The rectangle's corners in the photo (u, v), pixels, TL, TR, BR, BL; no edge pair parallel.
    principal_point : (2,) array_like
        (c_u, c_v), pixels.

    Returns
    -------
    ratio : float
        The rectangle's width / height (width = the TL-TR edge).
    f : float
        The focal length in pixels.

    References
    ----------
    Z. Zhang and L.-W. He, "Whiteboard scanning and image enhancement", Digital Signal Processing
    17(2), 2007.
    """
    q = np.asarray(corners, dtype=float) - np.asarray(principal_point, dtype=float)
    m1, m2, m4, m3 = np.column_stack([q, np.ones(4)])  # TL, TR, BR, BL in; Zhang & He's m3 is BL
    k2 = np.cross(m1, m4) @ m3 / (np.cross(m2, m4) @ m3)
    k3 = np.cross(m1, m4) @ m2 / (np.cross(m3, m4) @ m2)
    n2, n3 = k2 * m2 - m1, k3 * m3 - m1  # along w e1 and h e2, through A = diag(f, f, 1)
    f2 = -(n2[0] * n3[0] + n2[1] * n3[1]) / (n2[2] * n3[2])  # from e1 . e2 = 0
    ratio2 = ((n2[0] ** 2 + n2[1] ** 2) / f2 + n2[2] ** 2) / (
        (n3[0] ** 2 + n3[1] ** 2) / f2 + n3[2] ** 2
    )
    return float(np.sqrt(ratio2)), float(np.sqrt(f2))


def _shape_wrong(order=(0, 1, 3, 2), centre=True, plain=False, **how):
    """A student's ``rectangle_shape`` with one slip; ``plain``: np.sqrt without abs (NaN allowed)."""

    def student(corners, principal_point):
        ratio2, f2 = _shape_from(*_zhang_he(corners, principal_point, order, centre, **how))
        if plain:
            with np.errstate(invalid="ignore"):
                return float(np.sqrt(ratio2)), float(np.sqrt(f2))
        return float(np.sqrt(abs(ratio2))), float(np.sqrt(abs(f2)))

    return student


register_exercise(
    Exercise(
        name="rectangle_shape",
        lesson="10",
        reference=_shape_reference,
        cases=_shape_cases,
        compare=_shape_compare,
        diagnose=_shape_diagnosis,
        wrong_variants=(
            (lambda c, p: (1 / _shape_reference(c, p)[0], _shape_reference(c, p)[1]), "h/w"),
            (lambda c, p: _shape_reference(c, p)[::-1], "(ratio, f), w/h first"),
            (
                lambda c, p: (_shape_reference(c, p)[0], _shape_reference(c, p)[1] / 1000),
                "off by a factor of 1000",
            ),
            (
                lambda c, p: np.array(_shape_reference(c, p)) * (1 + 3e-6),
                "within a relative 1e-6",
            ),
            (
                lambda c, p: (_shape_reference(c, p)[0] ** 2, _shape_reference(c, p)[1]),
                "take np.sqrt",
            ),
            (_shape_wrong(order=(0, 1, 2, 3)), "Zhang & He's numbering"),
            (
                lambda c, p: tuple(np.sqrt(_shape_from(*_zhang_he(c, p, order=(0, 1, 2, 3))))),
                "corners[[0, 1, 3, 2]]",
            ),
            (_shape_wrong(centre=False), "relative to the principal point"),
            (_shape_wrong(at=(319.5, 239.5)), "not to the principal_point"),
            (
                lambda c, p: _shape_wrong(at=np.asarray(p, float) - 1)(c, p),
                "moved by -1",
            ),
            (
                lambda c, p: _shape_wrong(at=np.asarray(c, float).mean(axis=0))(c, p),
                "relative to the centroid of the corners",
            ),
            (_shape_wrong(swap=True), "(c_v, c_u)"),
            (_shape_wrong(swap=True, plain=True), "(c_v, c_u)"),
            (_shape_wrong(minus=False), "lost its minus sign"),
            (_shape_wrong(minus=False, plain=True), "lost its minus sign"),
            (
                lambda c, p: (_shape_reference(c, p)[0], round(_shape_reference(c, p)[1])),
                "f is rounded",
            ),
            (
                lambda c, p: (
                    np.sqrt(_shape_from(*_zhang_he(c, p)[:2], 640.0**2)[0]),
                    640.0,
                ),
                "camlab's fallback",
            ),
            (
                lambda c, p: (_edge_ratios(c)[0], _shape_reference(c, p)[1]),
                "the photo's edge lengths",
            ),
            (lambda c, p: (1.0, _shape_reference(c, p)[1]), "your f is right but the ratio"),
            (
                lambda c, p: dict(zip(("ratio", "f"), _shape_reference(c, p), strict=True)),
                "a dict with keys ['f', 'ratio']",
            ),
            (
                lambda c, p: (round(_shape_reference(c, p)[0], 3), _shape_reference(c, p)[1]),
                "w/h is rounded",
            ),
        ),
        teaching=rectangle_shape,
        solution_note=(
            "# camlab's own, tested route: camlab.perspective.estimate_aspect_ratio(corners,\n"
            "# principal_point=...) returns .ratio and .focal_length (read it with pp.estimate_aspect_ratio??)"
        ),
    )
)
