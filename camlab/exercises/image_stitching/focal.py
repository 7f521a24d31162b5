"""Lesson 09, exercise 3: the focal length from a rotation-only homography (focal_from_rotation_homography).

Each typical slip is tried with every way of combining the four formulas (columns and rows, one, a
median or a mean), so the diagnosis names the slip whichever formulas the student used.
"""

from __future__ import annotations

import itertools
from types import SimpleNamespace

import numpy as np

from ...homography import rotation_homography
from .._core import Exercise, Mistake, first_mistake, register_exercise

# ----------------------------------------------------------------------------- focal from a rotation homography


def _focal_reference(H, shape):
    """One focal for both images (the same camera): the median of what H's rows and columns give."""
    from ...stitching.cameras import focal_from_homography

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
        f in pixels: the mean (median of two) of the estimates from R's columns and from its rows
        being orthonormal, each by the better-conditioned of its two formulas (NaN when neither
        gives a positive f^2).

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
    # R's first two columns (0 and 1) are orthogonal and equally long: two formulas for f^2, keep the better-conditioned one
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
    from ...camera import rotation_from_axis_angle

    out = []
    # The first turn is chosen so that every typical slip (C H C^-1, no centring, width and height swapped,
    # a half-pixel or 1-based centre, the rows read as the columns of H^T) gives a finite, distinct focal
    # length with each formula: the diagnosis then names the slip by its number, whichever formulas the
    # student combined (only H transposed gives NaN with all four). Then a general turn and the two 0/0
    # cases of the prompt (a pure pan: h7 = 0; a pure tilt: h6 = 0), exact zeros that stay exact.
    # Turn 5 is a tilt after a 45-degree roll: h6 = h7 and h2 = 0, so the columns' equal-length formula and
    # the rows' orthogonality formula are 0/0. Turn 7 is a turn about an axis at 45 degrees in the image plane
    # (h6 = -h7 and h2 = -h5): both equal-length formulas are 0/0 at once. On turn 6 both orthogonality formulas
    # have the larger denominator. Turns 3 to 7 carry round-off-size noise (each entry times 1 + 1e-9 n, as an
    # estimated H has): a 0/0 formula then gives a finite, arbitrary f^2 (not an exact 0 or NaN a student's
    # `f2 > 0` filter would drop) whatever H's scale, and the seeds are chosen so that it shows: the median of all
    # four is 3.1 f on turn 5 (both arbitrary values above f), the equal-length formulas alone 0.15 f on turn 7.
    # A sign flip or a wrong numerator in an orthogonality formula, the mean or median of all four formulas, and
    # the equal-length formulas alone therefore fail; the larger-denominator rule passes within 1e-5.
    tilt_after_roll = rotation_from_axis_angle([0.3, 0.0, 0.0]) @ rotation_from_axis_angle(
        [0.0, 0.0, np.pi / 4]
    )
    diagonal = 0.3 * np.array([1.0, 1.0, 0.0]) / np.sqrt(2)
    # Turn 2 is given at another scale (times -3.7), as a homography from an estimator is: only the
    # ratios of H's entries carry f, and an in-place `H /= H[2, 2]` then changes the caller's array.
    for f, (h, w), R, seed in (
        (520.0, (660, 900), [-0.523, 0.041, -0.054], None),  # a tilt, a little pan and roll
        (520.0, (660, 900), [0.05, -0.4, 0.03], None),  # pan, tilt and roll
        (700.0, (480, 640), [0.0, 0.35, 0.0], 1),  # a pure pan: h7 = 0
        (1200.0, (600, 800), [0.2, 0.0, 0.0], 2),  # a pure tilt: h6 = 0
        (600.0, (480, 640), tilt_after_roll, 103),  # h6 = h7 and h2 = 0
        (800.0, (600, 900), [0.3, 0.3, 0.1], 4),  # pan about as large as tilt
        (640.0, (480, 640), diagonal, 2),  # about a diagonal axis: h6 = -h7 and h2 = -h5
    ):
        K = np.array([[f, 0, (w - 1) / 2], [0, f, (h - 1) / 2], [0, 0, 1]])
        R = np.asarray(R, float)
        H = rotation_homography(K, R if R.shape == (3, 3) else rotation_from_axis_angle(R))
        if seed is not None:
            H = H * (1 + 1e-9 * np.random.default_rng(seed).standard_normal((3, 3)))
        out.append((H * (-3.7 if len(out) == 1 else 1.0), (h, w)))
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
    """The comparison of the check: one finite number within 1e-5 of the focal length.

    The test turns' round-off-size noise moves a right answer by up to about 1e-8 (relative), more for a
    method that weighs every condition (a search for the f that makes K^-1 H K a rotation).
    """
    g = _focal_number(got)
    return g is not None and np.isfinite(g) and abs(g / expected - 1) < 1e-5


_SLIP_CENTRES = {
    # the principal point each slip puts the origin at, from (w, h)
    "swap": lambda w, h: ((h - 1) / 2, (w - 1) / 2),
    "half": lambda w, h: (w / 2, h / 2),
    "one-based": lambda w, h: ((w + 1) / 2, (h + 1) / 2),
    "uncentred": lambda w, h: (0.0, 0.0),
}


def _focal_formulas(
    H, shape, slip: str = "", absolute: bool = False, squared: bool = False
) -> dict[str, float]:
    """The four focal lengths of the prompt's formulas, right or with one ``slip``.

    Columns: c1 orthogonal, c2 equally long; rows: r1, r2. Computed right or with one typical
    ``slip``; NaN where f^2 is 0/0 or negative.

    Slips: "swap" (centre ((h-1)/2, (w-1)/2)), "half" ((w/2, h/2)), "one-based" (((w+1)/2, (h+1)/2)),
    "uncentred" (no C at all), "C H C^-1" (the translation applied the wrong way round), "transposed"
    (h = H.T.ravel()), "sign" (the orthogonality formulas without their minus), "rows as H^T" (the column
    formulas applied to H^T for the rows: they give 1/f^2 there). ``absolute`` takes sqrt(|f^2|), as a
    student who silences the NaN does. ``squared`` returns the four f^2 themselves (negative ones kept, NaN
    where not finite), for a student who takes the median of f^2 and then its square root.
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
            f2["r1"] = -sign * h2 * h5 / (h0 * h3 + h1 * h4)
            f2["r2"] = (h5**2 - h2**2) / (h0**2 + h1**2 - h3**2 - h4**2)
    if absolute:
        f2 = {k: abs(v) for k, v in f2.items()}
    if squared:
        return {k: float(v) if np.isfinite(v) else float("nan") for k, v in f2.items()}
    return {
        k: float(np.sqrt(v)) if np.isfinite(v) and v >= 0 else float("nan") for k, v in f2.items()
    }


def _focal_answers(values: dict[str, float], squared: bool = False) -> list[float]:
    """What a student's combination of the formulas returns.

    One formula, the median or mean of any of them (NaN dropped, as the prompt's "where both are
    defined" invites, or kept), and per pair the one with the larger denominator (a subset too).
    With ``squared`` the values are f^2 and the combination is sqrt(median or mean of f^2), negative
    f^2 dropped with the NaN or kept (giving NaN).
    """
    if squared:
        kept = _focal_answers(values)
        dropped = _focal_answers({k: v if v > 0 else float("nan") for k, v in values.items()})
        with np.errstate(invalid="ignore"):
            return [
                float(np.sqrt(a)) if np.isfinite(a) and a >= 0 else float("nan")
                for a in kept + dropped
            ]
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
    """A diagnosis row's answer.

    The focal lengths a student who made ``slip`` can return on this input, or None where the slip
    changes no formula (it cannot show here).
    """

    def answer(s):
        right_answers = np.array(
            _focal_answers(_focal_formulas(s.H, s.shape))
            + _focal_answers(_focal_formulas(s.H, s.shape, squared=True), squared=True)
        )
        right_answers = right_answers[np.isfinite(right_answers)]
        wrong = [
            a
            for absolute in (False, True)
            for squared in (False, True)
            for a in _focal_answers(_focal_formulas(s.H, s.shape, slip, absolute, squared), squared)
            if not np.isclose(a, right_answers, rtol=1e-6).any()  # one call: the test ran minutes
        ]
        return wrong or None

    return answer


def _slipped_student(slip: str, H, shape, formulas=("c1", "c2", "r1", "r2")) -> float:
    """A student's answer with ``slip``: the median of the defined ones among ``formulas`` (for the tests)."""
    values = [
        v for k, v in _focal_formulas(H, shape, slip).items() if k in formulas and np.isfinite(v)
    ]
    return float(np.median(values)) if values else float("nan")


_FOCAL_ZERO_OVER_ZERO = {
    "c1": ("-(h0 h1 + h3 h4) / (h6 h7) (columns orthogonal)", "h6 or h7 is 0"),
    "c2": ("(h0^2 + h3^2 - h1^2 - h4^2) / (h7^2 - h6^2) (columns equally long)", "h6 = +-h7"),
    "r1": ("-h2 h5 / (h0 h3 + h1 h4) (rows orthogonal)", "h2 or h5 is 0"),
    "r2": ("(h5^2 - h2^2) / (h0^2 + h1^2 - h3^2 - h4^2) (rows equally long)", "h2 = +-h5"),
}
"""Each formula and when it is 0/0 on a rotation (numerator and denominator both exactly 0)."""


def _zero_over_zero(H, shape) -> list[str]:
    """The formulas that are 0/0 on this H: a denominator at round-off level next to its pair's other one."""
    h, w = shape[:2]
    C = np.array([[1.0, 0, (w - 1) / 2], [0, 1, (h - 1) / 2], [0, 0, 1]])
    Hc = np.linalg.inv(C) @ np.asarray(H, float) @ C
    h0, h1, h2, h3, h4, h5, h6, h7, _ = (Hc / np.linalg.norm(Hc)).ravel()
    d = {
        "c1": h6 * h7,
        "c2": h7**2 - h6**2,
        "r1": h0 * h3 + h1 * h4,
        "r2": h0**2 + h1**2 - h3**2 - h4**2,
    }
    pair = {"c1": "c2", "c2": "c1", "r1": "r2", "r2": "r1"}
    return [k for k in d if abs(d[k]) < 1e-6 * abs(d[pair[k]])]  # noise of 1e-9 leaves ~1e-8


def _orthogonality_decides(H, shape) -> bool:
    """Whether an orthogonality formula has the larger denominator in its pair (columns or rows) on this H."""
    h, w = shape[:2]
    C = np.array([[1.0, 0, (w - 1) / 2], [0, 1, (h - 1) / 2], [0, 0, 1]])
    h0, h1, h2, h3, h4, h5, h6, h7, _ = (np.linalg.inv(C) @ np.asarray(H, float) @ C).ravel()
    return abs(h6 * h7) > abs(h7**2 - h6**2) or abs(h0 * h3 + h1 * h4) > abs(
        h0**2 + h1**2 - h3**2 - h4**2
    )


def _zero_over_zero_answers(H, shape, zz: list[str]) -> list[float]:
    """What a student gets whose 0/0 formulas came out as 0 or inf (their own round-off), combined as usual.

    A student who takes the 0/0 formula anyway divides round-off by round-off; when the numerator is an exact
    0 and the denominator is not, that is f^2 = 0 (or inf the other way round), and the median with the
    other formulas lands between them (300 px for a truth of 600).
    """
    out = []
    for fill in (0.0, np.inf):
        for squared in (False, True):
            values = _focal_formulas(H, shape, squared=squared)
            values.update(dict.fromkeys(zz, fill))
            out += [a for a in _focal_answers(values, squared) if np.isfinite(a)]
    return out


def _zero_over_zero_hint(zz: list[str], got: float) -> str:
    what = "NaN" if np.isnan(got) else ("inf" if np.isinf(got) else f"{got:.6g}")
    listed = "; ".join(
        f"{_FOCAL_ZERO_OVER_ZERO[k][0]} is 0/0 because {_FOCAL_ZERO_OVER_ZERO[k][1]}" for k in zz
    )
    return (
        f"you returned {what} on a turn where {listed}. 0/0 is round-off divided by round-off (NaN, inf or any "
        "number), not a slip in your indices: in each pair use the formula whose denominator is larger in "
        "magnitude, and drop neither by a filter such as f^2 > 0: on an estimated H a 0/0 is a finite, "
        "arbitrary number (a pure pan has h7 = 0, a pure tilt h6 = 0, a turn about a diagonal axis h6 = +-h7)."
    )


def _larger_denominator_student(slip: str, orthogonality_only=False, equal_length_only=False):
    """A student who follows the prompt with ``slip``, or uses one kind of formula.

    Following the prompt is, per pair, the formula with the larger denominator, then the median of
    the positive ones; one kind of formula only is for the tests.
    """

    def student(H, shape):
        h, w = shape[:2]
        C = np.array([[1.0, 0, (w - 1) / 2], [0, 1, (h - 1) / 2], [0, 0, 1]])
        h0, h1, h2, h3, h4, h5, h6, h7, _ = (np.linalg.inv(C) @ np.asarray(H, float) @ C).ravel()
        f2 = _focal_formulas(H, shape, slip, squared=True)
        cols = abs(h6 * h7) > abs(h7**2 - h6**2)
        rows = abs(h0 * h3 + h1 * h4) > abs(h0**2 + h1**2 - h3**2 - h4**2)
        if orthogonality_only or equal_length_only:
            cols = rows = orthogonality_only
        with np.errstate(all="ignore"):
            raw = -(h0 * h1 + h3 * h4) / (h6 * h7) if orthogonality_only else None
        picked = [f2["c1"] if cols else f2["c2"], f2["r1"] if rows else f2["r2"]]
        if orthogonality_only and not np.isfinite(raw):
            return float(raw)  # inf on a pure pan, as the student's own division gives
        good = [np.sqrt(v) for v in picked if np.isfinite(v) and v > 0]
        return float(np.median(good)) if good else float("nan")

    return student


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
        "a sign flip: the orthogonality of the first two columns (0 and 1) gives f^2 = -(h0 h1 + h3 h4) / (h6 h7), and that of "
        "the first two rows f^2 = -h2 h5 / (h0 h3 + h1 h4), each with the minus (without it f^2 comes out negative and "
        "its square root NaN).",
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
    zz = _zero_over_zero(H, shape)
    if zz:
        # the student used a 0/0 formula if the answer is not finite, far off, or what the 0/0 values give
        raw = _focal_formulas(H, shape)
        with_zz = [
            a
            for squared in (False, True)
            for a in _focal_answers(_focal_formulas(H, shape, squared=squared), squared)
        ]
        far = np.isfinite(g) and g > 0 and abs(np.log(g / expected)) > np.log(10)
        sign_nan = any(np.isnan(a) for a in _focal_answers(_focal_formulas(H, shape, "sign")))
        if (
            not np.isfinite(g)
            or far
            or (
                _shows_slip(g, with_zz)
                and not _shows_slip(g, [v for k, v in raw.items() if k not in zz])
            )
            or _shows_slip(g, _zero_over_zero_answers(H, shape, zz))
        ):
            hint = _zero_over_zero_hint(zz, g)
            if np.isnan(g) and sign_nan:
                hint += (
                    " Or, if you used an orthogonality formula here, check its sign: f^2 = -(h0 h1 + h3 h4) / "
                    "(h6 h7) and -h2 h5 / (h0 h3 + h1 h4), with the minus."
                )
            return hint
    if np.isnan(g):
        # NaN does not tell the slips apart by value: name every slip that gives NaN here with some formula
        causes = [
            m for m in _FOCAL_SLIPS if (a := m.answer(context)) is not None and _shows_slip(g, a)
        ]
        if (
            len(causes) > 1
            and any(m.name == "sign flip" for m in causes)
            and _orthogonality_decides(H, shape)
        ):
            # every other slip gives a wrong number on test input 1 already; here the minus is what is left
            causes = [m for m in causes if m.name == "sign flip"]
        if causes:
            return (
                "f^2 came out negative (its square root is NaN) on a turn where every formula is defined. "
                + (
                    causes[0].hint[:1].upper() + causes[0].hint[1:]
                    if len(causes) == 1
                    else "Depending on the formulas you used, that is one of these slips: "
                    + "; ".join(f"({k}) {_FOCAL_SHORT[m.name]}" for k, m in enumerate(causes, 1))
                    + "."
                )
            )
    cause = first_mistake(_FOCAL_SLIPS, context, g, _shows_slip)
    if cause:
        return cause
    if not np.isfinite(g):
        return (
            "you returned NaN or inf on a turn where every formula is defined, so f^2 came out negative or divided "
            "by zero through a slip. Check the indices: h0 ... h8 are H's entries row by row."
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
            (_larger_denominator_student("sign"), "sign flip"),
            (_larger_denominator_student("", orthogonality_only=True), "0/0"),
            (_larger_denominator_student("", equal_length_only=True), "0/0"),
            (lambda H, shape: _slipped_student("", H, shape), "f^2 > 0"),  # median of all four
            (
                lambda H, shape: float(np.nanmean(list(_focal_formulas(H, shape).values()))),
                "f^2 > 0",
            ),  # mean of all four
        ),
        teaching=focal_from_rotation_homography,
    )
)
