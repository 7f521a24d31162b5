"""Lesson 09, exercise 4: the focal lengths from a rotation-only homography (focal_from_rotation_homography).

H maps a photo taken with focal f_from to one taken with f_to after the camera turned (Brown & Lowe's
setting: each photo its own focal). The rows of the centred H give f_from, the columns f_to, so every one
of the four formulas decides an answer on some test input, and a slip in any one of them shows. Each
typical slip is tried with every way of combining the two formulas of a pair (one, a median or a mean,
the larger denominator), so the diagnosis names the slip whichever formulas the student used.
"""

from __future__ import annotations

import itertools
from types import SimpleNamespace

import numpy as np

from .._core import Exercise, Mistake, first_mistake, register_exercise
from .focal_denominators import (
    FORMULAS,
    decides,
    denominators,
    zero_over_zero,
    zero_over_zero_hint,
)

# ----------------------------------------------------------------------------- focal from a rotation homography


def _focal_reference(H, shape):
    """(f_from, f_to): what H's rows and its columns give, as an array.

    camlab's ``stitching.cameras.focal_from_homography`` gives the same numbers on every test input:
    it evaluates the formulas on H in units of the image diagonal and calls a denominator under
    1e-12 of that normalised matrix undetermined (round-off: an affine pair). On the centred H in
    pixels, as here, no such cut-off is right: its entries differ by f^2, and at f = 1020 px
    (input 4) the genuine h7^2 - h6^2 of the normalised matrix is 6.7e-13 (:func:`_cut_off_hint`).
    """
    return np.array(focal_from_rotation_homography(H, shape), dtype=float)


def focal_from_rotation_homography(H, shape):
    """Teaching solution: the focal lengths (f_from, f_to), pixels, from H = K_to R K_from^-1.

    Parameters
    ----------
    H : (3, 3) array_like
        Maps a photo taken with focal f_from to one taken with f_to after the camera turned about
        its centre; both photos have the principal point at the image centre and square pixels.
    shape : tuple of int
        The photos' shape (height, width[, channels]).

    Returns
    -------
    tuple of float
        (f_from, f_to) in pixels: R's rows being orthonormal give f_from, its columns f_to, each by
        the formula of its pair with the larger denominator (NaN where that f^2 is not positive).

    References
    ----------
    R. Szeliski and H.-Y. Shum (1997), "Creating full view panoramic image mosaics and environment
    maps", SIGGRAPH.
    """
    h, w = shape[:2]
    # the principal point at the centre
    C = np.array([[1.0, 0, (w - 1) / 2], [0, 1, (h - 1) / 2], [0, 0, 1]])
    Hc = (
        np.linalg.inv(C) @ np.asarray(H, float) @ C
    )  # now H ~ diag(f_to, f_to, 1) R diag(1/f_from, 1/f_from, 1)
    h0, h1, h2, h3, h4, h5, h6, h7, _ = Hc.ravel() / np.linalg.norm(Hc)
    # R's first two columns (0 and 1) are orthogonal and equally long: f_to^2, the better-conditioned formula
    n1, d1 = -(h0 * h1 + h3 * h4), h6 * h7
    n2, d2 = h0**2 + h3**2 - h1**2 - h4**2, h7**2 - h6**2
    f2_to = n1 / d1 if abs(d1) > abs(d2) else n2 / d2
    # R's first two rows (0 and 1) likewise: f_from^2
    n1, d1 = -h2 * h5, h0 * h3 + h1 * h4
    n2, d2 = h5**2 - h2**2, h0**2 + h1**2 - h3**2 - h4**2
    f2_from = n1 / d1 if abs(d1) > abs(d2) else n2 / d2
    f_from, f_to = (float(np.sqrt(v)) if v > 0 else float("nan") for v in (f2_from, f2_to))
    return f_from, f_to


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
    # The second photo's focal differs from the first's (a zoom between shots),
    # so the rows (f_from) and the columns (f_to) are two answers: each pair's formula with the larger
    # denominator decides one of them, and over the turns every one of the four formulas decides one.
    for f, zoom, (h, w), R, seed in (
        (520.0, 1.15, (660, 900), [-0.523, 0.041, -0.054], None),  # a tilt, a little pan and roll
        (520.0, 0.9, (660, 900), [0.05, -0.4, 0.03], None),  # pan, tilt and roll
        (700.0, 1.2, (480, 640), [0.0, 0.35, 0.0], 1),  # a pure pan: h7 = 0
        (1200.0, 0.85, (600, 800), [0.2, 0.0, 0.0], 2),  # a pure tilt: h6 = 0
        (600.0, 1.1, (480, 640), tilt_after_roll, 103),  # h6 = h7 and h2 = 0
        (800.0, 1.25, (600, 900), [0.3, 0.3, 0.1], 4),  # pan about as large as tilt
        (640.0, 1.05, (480, 640), diagonal, 2),  # about a diagonal axis: h6 = -h7 and h2 = -h5
    ):
        K_from, K_to = (
            np.array([[fk, 0, (w - 1) / 2], [0, fk, (h - 1) / 2], [0, 0, 1]])
            for fk in (f, f * zoom)
        )
        R = np.asarray(R, float)
        R = R if R.shape == (3, 3) else rotation_from_axis_angle(R)
        H = K_to @ R @ np.linalg.inv(K_from)
        if seed is not None:
            H = H * (1 + 1e-9 * np.random.default_rng(seed).standard_normal((3, 3)))
        out.append((H * (-3.7 if len(out) == 1 else 1.0), (h, w)))
    out.append((_not_a_rotation(), (480, 640)))
    return out


def _not_a_rotation():
    """The last test input: a shift over a flat map with a little shear and perspective, no camera turn.

    On its centred H all four formulas give f^2 < 0 (-3.6e5 to -2.4e6 px^2), so the right answer is
    (NaN, NaN), as section 8's near-translations must cast no vote. A student who silences NaN with
    sqrt(|f^2|) returns finite numbers here, and that ``abs`` can hide a sign flip on the turns above.
    """
    C = np.array([[1.0, 0, 319.5], [0, 1, 239.5], [0, 0, 1]])
    Hc = np.array([[1.01, 0.06, -55.0], [-0.07, 1.01, 66.0], [7e-5, -6e-5, 1.0]])
    return C @ Hc @ np.linalg.inv(C)


def _focal_uncentred(H, shape):
    h0, h1, h2, h3, h4, h5, h6, h7, _ = np.asarray(H, float).ravel()
    with np.errstate(all="ignore"):
        f_to = np.sqrt(abs((h0**2 + h3**2 - h1**2 - h4**2) / (h7**2 - h6**2)))
        f_from = np.sqrt(abs((h5**2 - h2**2) / (h0**2 + h1**2 - h3**2 - h4**2)))
    return float(f_from), float(f_to)


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
    (h = H.T.ravel()), "sign" (the orthogonality formulas without their minus), "sign, equal length"
    (the equal-length formulas' numerator or denominator the wrong way round), "rows as H^T" (the column
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
    flip = -1.0 if slip == "sign, equal length" else 1.0
    with np.errstate(all="ignore"):
        f2 = {
            "c1": -sign * (h0 * h1 + h3 * h4) / (h6 * h7),
            "c2": flip * (h0**2 + h3**2 - h1**2 - h4**2) / (h7**2 - h6**2),
        }
        if slip == "rows as H^T":
            f2["r1"] = -(h0 * h3 + h1 * h4) / (h2 * h5)
            f2["r2"] = (h0**2 + h1**2 - h3**2 - h4**2) / (h2**2 - h5**2)
        else:
            f2["r1"] = -sign * h2 * h5 / (h0 * h3 + h1 * h4)
            f2["r2"] = flip * (h5**2 - h2**2) / (h0**2 + h1**2 - h3**2 - h4**2)
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


_ROWS, _COLUMNS = ("r1", "r2"), ("c1", "c2")
"""The formulas that give f_from (R's rows) and f_to (R's columns)."""


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


def _focal_pair(got) -> tuple[float, float] | None:
    """``got`` as (f_from, f_to) if it is two numbers (a tuple, a list or a (2,) array), else None."""
    if isinstance(got, np.ndarray):
        got = list(got) if got.shape == (2,) else None
    if not isinstance(got, (tuple, list)) or len(got) != 2:
        return None
    pair = [_focal_number(v) for v in got]
    return None if None in pair else (pair[0], pair[1])


def _same_focal(got, expected) -> bool:
    """The comparison of the check: two finite numbers, each within 1e-5 of its focal length.

    The test turns' round-off-size noise moves a right answer by up to about 1e-8 (relative), more for a
    method that weighs every condition (a search for the f's that make K_to^-1 H K_from a rotation).
    """
    pair = _focal_pair(got)
    return pair is not None and all(_same_one(g, e) for g, e in zip(pair, expected, strict=True))


def _same_one(g: float, e: float) -> bool:
    """One focal: NaN where the right answer is NaN (no rotation fits), else within 1e-5."""
    if np.isnan(e):
        return bool(np.isnan(g))
    return bool(np.isfinite(g) and abs(g / e - 1) < 1e-5)


def _no_rotation_hint(H, shape, g: float, which: str, keys) -> str:
    """The cause of a number where no rotation fits (every formula's f^2 < 0), so NaN is right."""
    f2 = _focal_formulas(H, shape, squared=True)
    f2 = {k: f2[k] for k in keys}
    listed = ", ".join(f"{k} {v:.3g}" for k, v in f2.items())
    start = (
        f"{which}: this H is not a rotation (a shift over a flat map with a little shear and perspective): every formula on H "
        f"gives f^2 <= 0 ({listed} px^2), so no focal fits: return NaN (float('nan')), not {g:.6g}. "
    )
    inverse = _focal_formulas(np.linalg.inv(np.asarray(H, float)), shape)
    if np.isfinite(g) and any(np.isclose(g, v, rtol=1e-6) for v in inverse.values()):
        return start + (
            f"{g:.6g} is what the formulas give on H^-1 (its columns give f_from, its rows f_to). On a rotation "
            "that route agrees with the formulas on H itself (it passes the seven turns), but this H is no "
            "rotation, and there the four conditions on H and those on H^-1 disagree: H^-1 gives some f^2 > 0 "
            "while H gives none. Use the formulas on the centred H itself, as the prompt says, and return NaN."
        )
    absolute = _focal_formulas(H, shape, absolute=True)
    if np.isfinite(g) and any(np.isclose(g, absolute[k], rtol=1e-6) for k in keys):
        return start + (
            "You took sqrt(|f^2|): abs() silences the NaN, and on a rotation it also hides a sign flip (a formula "
            "without its minus gives -f^2, and abs turns it back). Return NaN where f^2 <= 0, and check the minus "
            "in -(h0 h1 + h3 h4) / (h6 h7) and -h2 h5 / (h0 h3 + h1 h4)."
        )
    sentinel = (
        "0 is what sqrt(f^2 + 0j).real or a clamp max(f^2, 0) gives"
        if g == 0
        else "infinity is no focal length either"
        if np.isinf(g)
        else "a negative focal is what -sqrt(-f^2) gives"
        if g < 0
        else "that number is no focal this H implies"
    )
    return start + (
        f"{sentinel[:1].upper() + sentinel[1:]}; a sentinel such as 0, inf or -1 is a number that section 8's "
        "median of the pairs' focals would count as a vote, while NaN is the one value np.nanmedian skips."
    )


def _nan_expected_hint(H, shape, got, expected) -> str | None:
    """The cause when H is no rotation (the right answer is NaN) and ``got`` is not NaN; else None.

    Tested before every other cause: a sentinel returned twice must not read as "the same number twice",
    nor (None, None) as an answer of the wrong type.
    """
    if not np.isnan(np.asarray(expected, float)).any():
        return None
    items = list(got) if isinstance(got, (tuple, list)) else [got]
    if any(v is None for v in items):
        return (
            "this H is not a rotation: every formula gives f^2 <= 0, so no focal fits; return float('nan') for "
            "each focal (a tuple (nan, nan)), not None: NaN is a float, so the answer keeps its type, and "
            "np.nanmedian skips it where section 8 takes the median of the pairs' focals."
        )
    pair = _focal_pair(got)
    if pair is None:
        return None
    for j, (which, keys) in enumerate(
        ((("f_from (the rows)"), _ROWS), ("f_to (the columns)", _COLUMNS))
    ):
        if not _same_one(pair[j], float(expected[j])):
            return _no_rotation_hint(H, shape, pair[j], which, keys)
    return None


def _focal_slip(slip: str):
    """A diagnosis row's answer.

    The focal lengths a student who made ``slip`` can return for the focal ``s.keys`` give (the rows'
    or the columns'), or None where the slip changes no formula there (it cannot show).
    """

    def pick(values):
        return {k: v for k, v in values.items() if k in s_keys[0]}

    s_keys = [()]

    def answer(s):
        s_keys[0] = s.keys
        right_answers = np.array(
            _focal_answers(pick(_focal_formulas(s.H, s.shape)))
            + _focal_answers(pick(_focal_formulas(s.H, s.shape, squared=True)), squared=True)
        )
        right_answers = right_answers[np.isfinite(right_answers)]
        wrong = [
            a
            for absolute in (False, True)
            for squared in (False, True)
            for a in _focal_answers(
                pick(_focal_formulas(s.H, s.shape, slip, absolute, squared)), squared
            )
            if not np.isclose(a, right_answers, rtol=1e-6).any()  # one call: the test ran minutes
        ]
        return wrong or None

    return answer


def _slipped_student(slip: str, formulas=("c1", "c2", "r1", "r2")):
    """A student with ``slip`` who returns, per focal, the median of the defined ones among ``formulas``."""

    def student(H, shape):
        values = _focal_formulas(H, shape, slip)
        out = []
        for keys in (_ROWS, _COLUMNS):
            v = [values[k] for k in keys if k in formulas and np.isfinite(values[k])]
            out.append(float(np.median(v)) if v else float("nan"))
        return tuple(out)

    return student


def _zero_over_zero_answers(H, shape, zz: list[str], keys) -> list[float]:
    """What a student gets whose 0/0 formulas came out as 0 or inf (their own round-off), combined as usual.

    A student who takes the 0/0 formula anyway divides round-off by round-off; when the numerator is an exact
    0 and the denominator is not, that is f^2 = 0 (or inf the other way round), and the median with the
    other formula lands between them.
    """
    out = []
    for fill in (0.0, np.inf):
        for squared in (False, True):
            values = {
                k: v for k, v in _focal_formulas(H, shape, squared=squared).items() if k in keys
            }
            values.update(dict.fromkeys(zz, fill))
            out += [a for a in _focal_answers(values, squared) if np.isfinite(a)]
    return out


def _cut_off_hint(H, shape, g: float, e: float, keys, which: str) -> str | None:
    """The cause of a NaN where the deciding formula is defined but its denominator is tiny; else None.

    A student who guards the division with a fixed cut-off (``abs(d) > 1e-12``) returns NaN here: the
    centred H's entries in pixels differ by f^2 (h2 and h5 grow like f, h6 and h7 shrink like 1/f), so
    for a long lens a genuine denominator of the normalised matrix is that small. A cut-off fails first
    on the input with the smallest denominator so far; if the deciding formula decides here for the first
    time, a sign flip in it gives the same NaN, and the hint names both.
    """
    if not (np.isnan(g) and np.isfinite(e)):
        return None
    k = decides(H, shape, keys)
    d = denominators(H, shape)[k]
    earlier = _earlier_inputs(H)
    if earlier is None or not 0 < abs(d) < 1e-9:
        return None
    if any(
        min(abs(dk[decides(Hk, sk, ks)]) for ks in (_ROWS, _COLUMNS)) <= abs(d)
        for Hk, sk, dk in earlier
    ):
        return None  # a cut-off would have failed on an earlier input
    cut_off = (
        f"the formula with the larger denominator, {FORMULAS[k][0]}, is defined here: its denominator "
        f"is {d:.2g} (on the centred H divided by its norm) and it gives f = {e:.1f} px. If you guard the division "
        "with a fixed cut-off such as abs(d) > 1e-12, drop it: in pixels the centred H's entries differ by f^2 "
        "(h2, h5 grow like f; h6, h7 shrink like 1/f), so for focal lengths of several hundred pixels a genuine "
        "denominator is that small. Return NaN only where f^2 <= 0 (camlab's library first measures H in units of "
        "the image diagonal, where a cut-off means round-off)."
    )
    if any(decides(Hk, sk, keys) == k for Hk, sk, _ in earlier):
        return f"you returned NaN for {which}, but {cut_off}"
    # a denominator this small makes the cut-off the likelier slip: it leads
    return f"you returned NaN for {which}, but {cut_off} If you use no cut-off: {_SIGN_HINT}"


def _earlier_inputs(H):
    """(H, shape, denominators) of the check's inputs before H; None if H is not one of them."""
    out = []
    for Hk, shape in _focal_cases():
        if np.array_equal(Hk, np.asarray(H, float)):
            return out
        out.append((Hk, shape, denominators(Hk, shape)))
    return None


def _larger_denominator_student(slip: str, orthogonality_only=False, equal_length_only=False):
    """A student who follows the prompt with ``slip``, or uses one kind of formula.

    Following the prompt is, per pair, the formula with the larger denominator (NaN where its f^2 is
    not positive); one kind of formula only is for the tests.
    """

    def student(H, shape):
        f2 = _focal_formulas(H, shape, slip, squared=True)
        if orthogonality_only or equal_length_only:  # one kind of formula, whichever decides
            f2 = {
                k: f2[keys[0] if orthogonality_only else keys[1]]
                for keys in (_ROWS, _COLUMNS)
                for k in keys
            }
        return _focals_from_squares(f2, H, shape)

    return student


def _shows_slip(got: float, answers: list[float]) -> bool:
    if np.isnan(got):
        return any(np.isnan(a) for a in answers)
    return any(np.isfinite(a) and np.isclose(got, a, rtol=1e-6) for a in answers)


_SIGN_HINT = (
    "a sign flip: with the minus where it belongs, the columns give f_to^2 = -(h0 h1 + h3 h4) / (h6 h7) or "
    "(h0^2 + h3^2 - h1^2 - h4^2) / (h7^2 - h6^2), the rows f_from^2 = -h2 h5 / (h0 h3 + h1 h4) or "
    "(h5^2 - h2^2) / (h0^2 + h1^2 - h3^2 - h4^2) (a flipped sign makes f^2 negative and its square root NaN)."
)

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
        "homography is H_c = C^-1 H C (read right to left: C takes a centred point to pixels, H maps the pixels, C^-1 takes "
        "them back to centred coordinates), not C H C^-1.",
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
        "diag(1/f_from, 1/f_from, 1) R^T diag(f_to, f_to, 1)). Rows 0 and 1 of R give f_from^2 = "
        "-h2 h5 / (h0 h3 + h1 h4) or (h5^2 - h2^2) / (h0^2 + h1^2 - h3^2 - h4^2).",
    ),
    Mistake("sign flip", _focal_slip("sign"), _SIGN_HINT),
    Mistake("sign flip (equal length)", _focal_slip("sign, equal length"), _SIGN_HINT),
)
"""The focal length's slips, as the focal lengths they give for one of the two focals (``keys``: the rows'
or the columns' formulas), checked in this order; each row tries every way of combining the pair's formulas."""

_FOCAL_SHORT = {
    "H transposed": "H transposed: h = H.ravel(), row by row, not H.T.ravel()",
    "width and height swapped": "width and height swapped: the centre is ((w-1)/2, (h-1)/2) with (h, w) = shape[:2]",
    "centre (w/2, h/2)": "a half-pixel slip: the centre is ((w-1)/2, (h-1)/2), not (w/2, h/2)",
    "1-based centre": "pixels counted from 1: the centre is ((w-1)/2, (h-1)/2)",
    "C H C^-1": "the normalisation the wrong way round: H_c = C^-1 H C, not C H C^-1",
    "principal point not moved": "the principal point not moved to the origin: H_c = C^-1 H C",
    "rows as the columns of H^T": (
        "the rows' formulas taken as the columns' on H^T (that gives 1/f^2): f_from^2 = -h2 h5 / (h0 h3 + h1 h4) "
        "or (h5^2 - h2^2) / (h0^2 + h1^2 - h3^2 - h4^2)"
    ),
    "sign flip": "a sign flip in an orthogonality formula: f^2 = -(h0 h1 + h3 h4) / (h6 h7), with the minus",
    "sign flip (equal length)": (
        "a sign flip in an equal-length formula: f_to^2 = (h0^2 + h3^2 - h1^2 - h4^2) / (h7^2 - h6^2), "
        "f_from^2 = (h5^2 - h2^2) / (h0^2 + h1^2 - h3^2 - h4^2)"
    ),
}
"""Each slip in a few words, for a NaN that more than one slip explains."""


def _pair_shape_hint(got, expected) -> str | None:
    """The cause when the answer is not two numbers, or is the two focals mixed up; else None."""
    pair = _focal_pair(got)
    f_from, f_to = (float(v) for v in expected)
    if pair is None:
        g = _focal_number(got)
        kind = type(got).__name__ + (
            f" of shape {np.shape(got)}" if isinstance(got, np.ndarray) else ""
        )
        if g is not None:
            return (
                "you returned one number; return two, (f_from, f_to): the photos here were taken at different "
                f"zooms ({f_from:.1f} and {f_to:.1f} px), so R's rows give f_from and its columns f_to (the median "
                "of all four formulas mixes the two)."
            )
        return f"return two numbers, (f_from, f_to) in pixels (a tuple, a list or a (2,) array); got {kind}."
    a, b = pair
    if np.isclose(a, f_to, rtol=1e-5) and np.isclose(b, f_from, rtol=1e-5):
        return (
            "the two are swapped: R's rows give the focal of the image H maps FROM (f_from), its columns the "
            "focal of the image it maps TO (f_to); return (f_from, f_to). If your formulas are right, you may have "
            "used H^-1 (it maps to -> from, so the rows and columns trade roles): use H as given."
        )
    if np.isclose(a, b, rtol=1e-9) and np.isfinite([f_from, f_to]).all() and f_from != f_to:
        return (
            "you returned the same number twice: the photos here have different focal lengths "
            f"({f_from:.1f} and {f_to:.1f} px), so keep the rows' answer (f_from) and the columns' (f_to) apart, "
            "and do not take a median or mean across the two pairs."
        )
    if all(
        np.isfinite(v) and np.isclose(v, e**2, rtol=1e-3)
        for v, e in zip(pair, expected, strict=True)
    ):
        return "those are f squared: the formulas give f^2; take the square roots."
    if np.isfinite([f_from, f_to]).all() and np.allclose(pair, (1 / f_to, 1 / f_from), rtol=1e-5):
        return (
            f"you returned (1/f_to, 1/f_from) = ({pair[0]:.6g}, {pair[1]:.6g}) = (1/{f_to:.1f}, 1/{f_from:.1f}): the "
            "formulas ran on the centred H transposed. H_c^T = diag(1/f_from, 1/f_from, 1) R^T diag(f_to, f_to, 1) has "
            "the focal lengths inverted and their roles swapped; take h0 ... h8 from H_c itself, row by row "
            "(h = H_c.ravel(), not H_c.T.ravel() nor H_c.ravel(order='F'))."
        )
    return None


def _nan_hint(context, pair, j: int, expected, which: str) -> str | None:
    """The cause of a NaN focal (``pair[j]``) where the larger-denominator formula is defined; else None."""
    g = pair[j]
    # NaN does not tell the slips apart by value: name every slip that gives NaN here with some formula
    causes = [m for m in _FOCAL_SLIPS if (a := m.answer(context)) is not None and _shows_slip(g, a)]
    signs = [m for m in causes if m.name.startswith("sign flip")]
    other = pair[1 - j]
    other_right = np.isfinite(other) and abs(other / expected[1 - j] - 1) < 1e-5
    if len(causes) > 1 and signs and other_right:
        # a sign flip spoils one formula, so the other focal can stay right; the other slips (H transposed,
        # the centre) spoil both
        causes = signs[:1]
    elif len(causes) > 1:
        # the other focal tells them apart (width and height swapped leaves it finite, H.T does not)
        ctx = SimpleNamespace(**{**vars(context), "expected": float(expected[1 - j])})
        ctx.keys = _COLUMNS if j == 0 else _ROWS
        causes = [
            m for m in causes if (a := m.answer(ctx)) is not None and _shows_slip(other, a)
        ] or causes
        if np.isnan(other) and causes[0].name == "H transposed":  # one slip that spoils both focals
            return (
                f"{which}: both focals came out NaN (f^2 negative) on a turn where the formulas are defined: "
                f"{causes[0].hint} (If you did not, a sign flip in both formulas does this too.)"
            )
    if causes:
        return (
            f"{which}: f^2 came out negative (its square root is NaN) on a turn where the formula with the "
            "larger denominator is defined. "
            + (
                causes[0].hint[:1].upper() + causes[0].hint[1:]
                if len(causes) == 1
                else "Depending on the formulas you used, that is one of these slips: "
                + "; ".join(f"({k}) {_FOCAL_SHORT[m.name]}" for k, m in enumerate(causes, 1))
                + "."
            )
        )
    return None


def _focal_diagnosis(args, got, expected) -> str:
    H, shape = args
    shape_hint = _nan_expected_hint(H, shape, got, expected) or _pair_shape_hint(got, expected)
    if shape_hint:
        return shape_hint
    pair = _focal_pair(got)
    j = 0 if not _same_one(pair[0], float(expected[0])) else 1
    keys, which = (_ROWS, "f_from (the rows)") if j == 0 else (_COLUMNS, "f_to (the columns)")
    g, e = pair[j], float(expected[j])
    if np.isfinite(g) and np.isclose(g, e**2, rtol=1e-3):
        return f"{which} is f squared: the formulas give f^2; take the square root."
    h, w = shape[:2]
    if np.isfinite(g) and np.isclose(g * np.hypot(w, h), e, rtol=1e-5):  # camlab's library's units
        return (
            f"{which} = {g:.6g} is the focal in units of the image diagonal; multiply by sqrt(w^2 + h^2) = "
            f"{np.hypot(w, h):.1f} for pixels ({e:.1f} px)."
        )
    context = SimpleNamespace(H=H, shape=shape, w=w, h=h, expected=e, keys=keys)
    cut = _cut_off_hint(H, shape, g, e, keys, which)
    if cut:
        return cut
    zz = zero_over_zero(H, shape, keys)
    if zz:
        values = {k: v for k, v in _focal_formulas(H, shape).items() if k in keys}
        with_zz = [
            a
            for squared in (False, True)
            for a in _focal_answers(
                {k: v for k, v in _focal_formulas(H, shape, squared=squared).items() if k in keys},
                squared,
            )
        ]
        far = np.isfinite(g) and g > 0 and abs(np.log(g / e)) > np.log(10)
        if (
            not np.isfinite(g)
            and not (decides(H, shape, keys) not in zz and np.isnan(g))
            or far
            or (
                _shows_slip(g, with_zz)
                and not _shows_slip(g, [v for k, v in values.items() if k not in zz])
            )
            or _shows_slip(g, _zero_over_zero_answers(H, shape, zz, keys))
        ):
            return zero_over_zero_hint(zz, g, which)
    if np.isnan(g):
        hint = _nan_hint(context, pair, j, expected, which)
        if hint:
            return hint
    cause = first_mistake(_FOCAL_SLIPS, context, g, _shows_slip)
    if cause:
        # a slip in the centring spoils both focals alike: name both, not the first one alone
        other = SimpleNamespace(**vars(context))
        other.expected, other.keys = float(expected[1 - j]), (_COLUMNS, _ROWS)[j]
        again = first_mistake(_FOCAL_SLIPS, other, pair[1 - j], _shows_slip)
        both = again == cause and not _same_one(pair[1 - j], other.expected)
        return f"{'both focals, f_from and f_to' if both else which}: {cause}"
    if not np.isfinite(g):
        return (
            f"you returned NaN or inf for {which} on a turn where its formula is defined, so f^2 came out negative "
            "or divided by zero through a slip. Check the indices and the signs: h0 ... h8 are H's entries row by row."
        )
    return (
        "f_to^2 = -(h0 h1 + h3 h4) / (h6 h7) or (h0^2 + h3^2 - h1^2 - h4^2) / (h7^2 - h6^2) (columns), "
        "f_from^2 = -h2 h5 / (h0 h3 + h1 h4) or (h5^2 - h2^2) / (h0^2 + h1^2 - h3^2 - h4^2) (rows), on the "
        "centred H."
    )


def _one_focal(H, shape):
    """A student who keeps the old single-focal answer: the median of both f's."""
    return float(np.nanmedian(focal_from_rotation_homography(H, shape)))


def _focals_from_squares(f2: dict, H, shape) -> tuple:
    """(f_from, f_to) from the squared formulas ``f2``: each group's deciding formula, NaN if <= 0."""
    deciding = (f2[decides(H, shape, keys)] for keys in (_ROWS, _COLUMNS))
    return tuple(float(np.sqrt(v)) if np.isfinite(v) and v > 0 else float("nan") for v in deciding)


def _abs_student(slip: str = ""):
    """The prompt's rule with sqrt(|f^2|) where f^2 < 0 (K12's student), with an optional ``slip``."""

    def student(H, shape):
        return _focals_from_squares(
            _focal_formulas(H, shape, slip, absolute=True, squared=True), H, shape
        )

    return student


def _edited_student(edit):
    """The prompt's rule with its squared formulas changed by ``edit(f2, H, shape)`` (a slip)."""

    def student(H, shape):
        return _focals_from_squares(
            edit(_focal_formulas(H, shape, squared=True), H, shape), H, shape
        )

    return student


def _cut_off_student(cut: float = 1e-9):
    """The prompt's rule with the division guarded by a fixed cut-off, abs(d) > ``cut`` (P14's student)."""
    return _edited_student(
        lambda f2, H, shape: {
            k: v if abs(denominators(H, shape)[k]) > cut else np.nan for k, v in f2.items()
        }
    )


def _flipped(formula: str):
    """The prompt's rule with the sign of one ``formula`` flipped (I9's student)."""
    return _edited_student(lambda f2, H, shape: {**f2, formula: -f2[formula]})


def _sentinel_student(value):
    """The prompt's rule, but ``value`` (0, inf, -1, None, or "complex": sqrt(f^2 + 0j).real) where f^2 <= 0."""

    def student(H, shape):
        f2 = _focal_formulas(H, shape, squared=True)
        out = []
        for keys in (_ROWS, _COLUMNS):
            v = f2[decides(H, shape, keys)]
            if v > 0:
                out.append(float(np.sqrt(v)))
            else:
                out.append(float(np.sqrt(v + 0j).real) if value == "complex" else value)
        return tuple(out)

    return student


register_exercise(
    Exercise(
        name="focal_from_rotation_homography",
        lesson="09",
        reference=_focal_reference,
        cases=_focal_cases,
        compare=_same_focal,
        diagnose=_focal_diagnosis,
        wrong_variants=(
            (
                lambda H, shape: tuple(v**2 for v in focal_from_rotation_homography(H, shape)),
                "square root",
            ),
            (_focal_uncentred, "both focals, f_from and f_to: move the principal point"),
            (
                lambda H, shape: focal_from_rotation_homography(np.asarray(H, float).T, shape),
                "H transposed",
            ),
            (
                lambda H, shape: focal_from_rotation_homography(H, tuple(shape[:2])[::-1]),
                "idth and height swapped",  # W when it starts the sentence
            ),
            (lambda H, shape: focal_from_rotation_homography(H, shape)[::-1], "swapped"),
            (
                lambda H, shape: focal_from_rotation_homography(np.linalg.inv(H), shape),
                "used H^-1",
            ),
            (  # the H^-1 route: right on every turn, not on the last input (no rotation)
                lambda H, shape: focal_from_rotation_homography(np.linalg.inv(H), shape)[::-1],
                "formulas give on H^-1",
            ),
            (_one_focal, "you returned one number"),
            (
                lambda H, shape: tuple(
                    f / np.hypot(*shape[:2]) for f in focal_from_rotation_homography(H, shape)
                ),
                "in units of the image diagonal",
            ),
            (lambda H, shape: (_one_focal(H, shape),) * 2, "same number twice"),
            (_slipped_student("half"), "half-pixel slip"),
            (_slipped_student("one-based"), "counted pixels from 1"),
            (_slipped_student("C H C^-1"), "wrong way round"),
            (_slipped_student("swap"), "width and height swapped"),
            (_slipped_student("rows as H^T", ("c1", "r1")), "1/f^2"),
            (_larger_denominator_student("sign"), "sign flip"),
            (_larger_denominator_student("sign, equal length"), "sign flip"),
            *((_flipped(k), "sign flip") for k in ("c1", "c2", "r1", "r2")),
            (_larger_denominator_student("", orthogonality_only=True), "0/0"),
            (_larger_denominator_student("", equal_length_only=True), "0/0"),
            (_slipped_student(""), "f^2 > 0"),  # median of both formulas of each pair
            (_abs_student(), "abs() silences the NaN"),
            (
                _cut_off_student(),
                "but the formula with the larger denominator",
            ),  # the cut-off leads
            *((_sentinel_student(v), "not a rotation") for v in (0.0, np.inf, -1.0, None)),
            (_sentinel_student("complex"), "sqrt(f^2 + 0j).real"),
            (
                _abs_student("sign"),
                "hides a sign flip",
            ),  # passes every rotation: only the last input shows it
        ),
        teaching=focal_from_rotation_homography,
    )
)
