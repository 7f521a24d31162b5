"""Exercise 2 of lesson 07: the normalised DLT for a homography (`dlt_homography`)."""

from __future__ import annotations

import functools
from types import SimpleNamespace

import numpy as np

from ... import homography as hg
from ...projective import hartley_normalise, map_points
from .._answers import same_up_to_scale, shape_problem
from .._core import Exercise, first_mistake, register_exercise
from ._dlt_undo import UNDO_MISTAKES, divided_by_noise, h33_slip

# A patch far from the origin (like a crop of a large photo) with 1 px of noise: there the
# unnormalised DLT is off by tens of pixels, while any Hartley-style normalisation is off by
# what the noise alone explains.
_FAR_PATCH = np.stack(
    np.meshgrid(np.linspace(2000, 2600, 5), np.linspace(2000, 2400, 5)), -1
).reshape(-1, 2)
H_FAR = np.array([[1.0, 0.02, 15.0], [0.01, 0.98, -10.0], [1e-5, 2e-5, 1.0]])
"""The true homography of the noisy test input (the same as section 6's plot)."""
FAR_TOLERANCE_PX = 4.0
"""How far from the *truth* an answer to the noisy input may map the far patch. The noise alone
puts any good normalised DLT 1-2 px off there (camlab's 1.5, per-axis scaling 1.1, three rows
per pair 1.6, OpenCV's refined fit 1.2; 2.7 px at the 99th percentile over noise draws), while
the plain DLT is 27 px off. Comparing with camlab's own noisy estimate instead would reject
valid normalisations for differing from one particular one."""


def _far_error(H) -> float:
    """The largest distance between where H and the truth send the far patch (pixels)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        d = np.linalg.norm(map_points(H, _FAR_PATCH) - map_points(H_FAR, _FAR_PATCH), axis=1)
    return float(np.nanmax(d)) if np.isfinite(d).any() else float("inf")


def _dlt_cases():
    rng = np.random.default_rng(7)
    H1 = np.array([[1.2, 0.1, 15.0], [-0.05, 0.9, 30.0], [5e-4, -2e-4, 1.0]])
    H2 = np.array([[0.8, -0.3, 200.0], [0.25, 1.1, -40.0], [-1e-3, 4e-4, 1.0]])
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    turn = np.array([[np.cos(0.5), -np.sin(0.5)], [np.sin(0.5), np.cos(0.5)]])
    quad = np.array([[100.0, 80.0], [520.0, 60.0], [560.0, 400.0], [90.0, 430.0]])
    pts = rng.uniform([0, 0], [640, 480], (8, 2))
    far = rng.uniform([2000, 2000], [2600, 2400], (30, 2))
    near = rng.uniform([100, 50], [600, 450], (8, 2))
    return [
        (square, 2.0 * square @ turn.T + [3.0, 1.0]),  # a similarity (turned: H_n is not I)
        (square * 300, quad),  # the unit-square trick, in pixels
        (quad, map_points(H1, quad)),
        (pts, map_points(H2, pts)),  # more than 4 pairs (noise free)
        (far, map_points(H_FAR, far) + rng.normal(0, 1.0, far.shape)),  # noisy, far from the origin
        (near, map_points(H_ORIGIN_AT_INFINITY, near)),  # h33 = 0: exact, but no h33 = 1 form
    ]


H_ORIGIN_AT_INFINITY = np.array([[0.0, 0.0, 500.0], [0.0, 1.0, 0.0], [0.002, 0.0, 0.0]])
"""The true H of test input 6: h33 = 0, so it sends the pixel origin (0, 0) to infinity (det -1).
A DLT that fixes h33 = 1 cannot represent it (least squares on raw pixels lands tens of pixels off)."""


FAR_DRAWS = 12
"""How many fresh noise draws of the far patch the follow-up judges (after the six test inputs)."""
FAR_MEDIAN_PX, FAR_WORST_PX = 2.5, 8.0
"""The follow-up's bars: the median over the draws, and the worst draw. A normalised DLT (any of
the valid forms above) is 1.4-1.5 px off at the median over 200 draws and under 5.3 px on every one;
centring without scaling is 5.3 px off at the median (65 % of draws above 4 px), so one lucky draw
cannot let it through."""


def _far_draws():
    """FAR_DRAWS noisy copies of the far test input (fixed seeds): (src, dst) with 1 px of noise."""
    rng = np.random.default_rng(11)
    for _ in range(FAR_DRAWS):
        far = rng.uniform([2000, 2000], [2600, 2400], (30, 2))
        yield far, map_points(H_FAR, far) + rng.normal(0, 1.0, far.shape)


def _similarity(centre, scale):
    return np.array([[scale, 0, -scale * centre[0]], [0, scale, -scale * centre[1]], [0, 0, 1.0]])


def _dlt_with(src, dst, normaliser):
    """The DLT of src, dst after ``normaliser(points) -> T`` on each set, undone (H = T_dst^-1 H_n T_src)."""
    Ts, Td = normaliser(src), normaliser(dst)
    sn = (np.column_stack([src, np.ones(len(src))]) @ Ts.T)[:, :2]
    dn = (np.column_stack([dst, np.ones(len(dst))]) @ Td.T)[:, :2]
    return np.linalg.inv(Td) @ np.linalg.svd(_dlt_rows(sn, dn))[2][-1].reshape(3, 3) @ Ts


def _mean_distance(p):
    return np.mean(np.linalg.norm(p - p.mean(axis=0), axis=1))


_FAR_SLIPS = (
    (
        lambda p: _similarity(p.mean(axis=0), 1.0),
        "you centred each point set but did not scale it: centred, the points are still about 300 px "
        "from 0, so the columns of A range from 1 to about 1e5 and the noise is amplified (less than "
        "without centring, but far more than it should be). Scale too: s = sqrt(2) / (mean distance to "
        "the centroid), so that the mean distance becomes sqrt(2).",
    ),
    (
        lambda p: _similarity(p.mean(axis=0), _mean_distance(p) / np.sqrt(2)),
        "your T scales the wrong way: s = (mean distance) / sqrt(2) puts the points tens of thousands "
        "of units from 0 instead of sqrt(2). Use s = sqrt(2) / (mean distance to the centroid).",
    ),
    (
        lambda p: np.diag([np.sqrt(2) / _mean_distance(p), np.sqrt(2) / _mean_distance(p), 1.0]),
        "your T scales but does not move the centroid to 0 (its third column is (0, 0, 1)): scaled about "
        "the origin, points about 3200 px out end up about 22 units from 0 with a spread of only about 1.4, "
        "so the columns of A still range from 1 to about 300 and the noise is amplified. Put the "
        "translation in: T = [[s, 0, -s cx], [0, s, -s cy], [0, 0, 1]].",
    ),
    (
        lambda p: np.array(
            [
                [np.sqrt(2) / _mean_distance(p), 0, -p.mean(axis=0)[0]],
                [0, np.sqrt(2) / _mean_distance(p), -p.mean(axis=0)[1]],
                [0, 0, 1.0],
            ]
        ),
        "your T's translation is -c, not -s c: T x = s x - c moves the points to s x - c, thousands of "
        "units from 0, not to the centroid. T first subtracts the centroid, then scales, so its last column "
        "is (-s cx, -s cy, 1).",
    ),
    (
        lambda p: np.array([[2 / 640, 0, -1.0], [0, 2 / 480, -1.0], [0, 0, 1.0]]),
        "your T is fixed for a 640 x 480 image, but these points lie 2000 to 2600 px from the origin, "
        "outside any such image, so after it they sit near (6, 8), not around 0. Build T from the points "
        "themselves: their centroid to 0, their mean distance to sqrt(2).",
    ),
    (
        lambda p: np.linalg.inv(hartley_normalise(p).T),
        "you normalised with inv(T), the matrix that maps normalised points back to pixels: it pushes the "
        "points further out instead of to the centroid. Normalise with T itself, x_n = T x, "
        "T = [[s, 0, -s cx], [0, s, -s cy], [0, 0, 1]], and undo with H = inv(T_dst) @ H_n @ T_src.",
    ),
    (
        lambda p: np.eye(3),
        "you did not normalise: the columns of A range from 1 to u u', several million here, so A is badly "
        "conditioned. Exact data hides it, noise does not. Normalise each point set first (Hartley, "
        "section 6: centroid to 0, mean distance sqrt(2)), solve, then undo it with "
        "H = inv(T_dst) @ H_n @ T_src.",
    ),
)


def _patch_distance(H1, H2) -> float:
    """The largest distance between where H1 and H2 send the far patch (pixels)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        d = np.linalg.norm(map_points(H1, _FAR_PATCH) - map_points(H2, _FAR_PATCH), axis=1)
    return float(np.nanmax(d)) if np.isfinite(d).any() else float("inf")


def _far_cause(src, dst, g) -> str:
    """Name the slip behind an H that is too far off on a noisy far input.

    The slip whose own answer lies much closer to g than g lies to the truth; else the usual
    suspects, all named.
    """
    off = _far_error(g)
    slips = [
        (_patch_distance(g, _dlt_with(src, dst, normaliser)), hint)
        for normaliser, hint in _FAR_SLIPS
    ]
    closest, hint = min(slips, key=lambda pair: pair[0])
    if closest < 0.25 * off:
        return hint
    rows = _row_choice(src, dst, g)
    if rows:
        return (
            f"you kept rows {rows} of x' x Hx = 0. They fix H on exact data, but with w' = 1, "
            f"r3 = -(u' r1 + v' r2), so the pair's other equation enters only weighted by "
            f"{'v' if rows == 'r1 and r3' else 'u'}', near 0 for normalised points near the centroid: "
            f"those pairs give almost one equation. Keep r1 and r2 (section 5, H&Z (4.3)), or all three."
        )
    if len(src) > 4:
        four = _patch_distance(g, _dlt_with(src[:4], dst[:4], lambda p: hartley_normalise(p).T))
        if four < 0.25 * off:
            return (
                f"your H fits only the first 4 of the {len(src)} pairs (a loop over range(4)?): four pairs "
                f"fix H exactly, noise and all. Stack two rows for *every* pair, A of shape (2N, 9), so "
                f"the least-squares solution averages the noise out."
            )
    return (
        f"more than the noise explains (a normalised DLT is {_reference_median():.2f} px off at the median "
        f"on these draws). Check how "
        "you build each T: it must move the centroid to 0 and then scale, "
        "T = [[s, 0, -s cx], [0, s, -s cy], [0, 0, 1]] with s = sqrt(2) / (mean distance to the "
        "centroid), built from the point set itself (not from an image size), one for src and one for "
        "dst; and use all N pairs."
    )


@functools.cache
def _reference_median() -> float:
    """camlab's normalised DLT on the FAR_DRAWS draws: its median px off the truth (what hints quote)."""
    return float(np.median([_far_error(hg.estimate_homography(s, d)) for s, d in _far_draws()]))


def _dlt_follow_up(run) -> str:
    """The empty hint when the student's DLT is as accurate as a normalised one.

    Measured over FAR_DRAWS noise draws.
    """
    offs, worst = [], None
    for src, dst in _far_draws():
        try:
            g = np.asarray(run(src.copy(), dst.copy()), dtype=float)
            off = _far_error(g) if g.shape == (3, 3) and np.isfinite(g).all() else float("inf")
        except (ValueError, np.linalg.LinAlgError):
            g, off = None, float("inf")
        offs.append(off)
        if worst is None or off > worst[0]:
            worst = (off, src, dst, g)
    median, largest = float(np.median(offs)), max(offs)
    off, src, dst, g = worst
    if median <= FAR_MEDIAN_PX and largest <= FAR_WORST_PX:
        return ""
    if g is not None and np.isfinite(off) and _row_choice(src, dst, g):
        return ""  # r1, r3 (or r2, r3): valid, noisier; the success note says why
    cause = (
        _far_cause(src, dst, g)
        if g is not None and np.isfinite(off)
        else ("on one draw your H was singular or not finite.")
    )
    return (
        f"on {FAR_DRAWS} fresh noise draws of the far patch (1 px of noise, as in test input 5) your H is "
        f"off the true homography by {median:.3g} px at the median and {largest:.3g} px at worst "
        f"(a normalised DLT: {_reference_median():.2f} px at the median, never above {FAR_WORST_PX:g} px; test input 5 "
        f"alone was a lucky draw).\n  likely cause: {cause}"
    )


def _one_set_only(run) -> str:
    """A note for a DLT that passes although it normalises only one set, or does not centre ("" otherwise)."""
    src, dst = next(iter(_far_draws()))
    g = np.asarray(run(src.copy(), dst.copy()), dtype=float)
    for T in (lambda p: hartley_normalise(p).T, _normalisers_rms):
        for which, only in (("src", (T, lambda p: np.eye(3))), ("dst", (lambda p: np.eye(3), T))):
            if same_up_to_scale(
                g, _dlt_with_each(src, dst, *only), rtol=1e-6
            ) and not same_up_to_scale(g, _dlt_with(src, dst, T), rtol=1e-6):
                return (
                    f"Note: you normalised only {which}. That passes on this patch, but A still mixes the "
                    f"other set's raw pixels (thousands) with entries of order 1; Hartley's recipe gives "
                    f"each set its own T (H&Z §4.4.4)."
                )
    shared = _shared_t(run, src, dst)
    if shared:
        return shared
    moved = _origin_dependence(run, src, dst, g)
    if moved > 1e-6:
        return (
            f"Note: your H depends on where the pixel origin lies. Shifting both point sets by "
            f"({_SHIFT[0]:g}, {_SHIFT[1]:g}) px, solving, and shifting the answer back moves the patch's "
            f"image by {moved:.2g} px; a DLT that centres each set moves it by about 1e-12 px (H&Z §4.4.2's "
            f"invariance). Most likely you scaled each set without first moving its centroid to 0. That "
            f"passes on this patch, but step 1 is: centroid to 0, then scale."
        )
    return ""


_MOVED = np.array([[3.0, 0.0, 1000.0], [0.0, 3.0, 1000.0], [0.0, 0.0, 1.0]])
"""Scale 3 and 1000 px across: the shared-T note's dst, far from src (on the far draw, dst ~ src)."""


def _shared_t(run, src, dst) -> str:
    """A note for a DLT that normalises both sets with one set's T ("" otherwise).

    On the far draw dst lies on top of src, so src's T suits dst too and the slip is invisible:
    the note solves again with dst scaled by 3 and moved 1000 px (:data:`_MOVED`), where one set's
    T leaves the other set about 40 units from 0 with a spread of about 4.
    """
    far_dst = map_points(_MOVED, dst)
    g = np.asarray(run(src.copy(), far_dst.copy()), dtype=float)
    own = _dlt_with(src, far_dst, lambda p: hartley_normalise(p).T)
    for which, fixed in (("src", src), ("dst", far_dst)):
        one = _dlt_with(src, far_dst, lambda p, fixed=fixed: hartley_normalise(fixed).T)
        if same_up_to_scale(g, one, rtol=1e-6) and not same_up_to_scale(g, own, rtol=1e-6):
            return (
                f"Note: you normalised both sets with {which}'s T. That passes here, where dst lies on top "
                f"of src; with dst scaled by 3 and moved 1000 px away, {which}'s T leaves the other set "
                f"tens of units from 0 with a spread of a few units: the poor conditioning normalising "
                f"exists to avoid. Give each set its own T (H&Z §4.4.4), or compute one T from both sets together."
            )
    return ""


_SHIFT = np.array([-2300.0, -2200.0])
"""The shift of both point sets that the centring note tries: it brings the far patch near the origin."""


def _origin_dependence(run, src, dst, g) -> float:
    """How far g's image of the far patch moves when both sets are shifted by _SHIFT, then shifted back.

    0 (to rounding) for any DLT that centres each set, and for OpenCV's refined fit this returns 0
    too: its iterative refinement stops at a tolerance, so it is not exactly invariant, but it centres.
    """
    try:
        import cv2

        if _patch_distance(g, cv2.findHomography(src, dst, 0)[0]) < 1e-6:
            return 0.0
    except ImportError:  # pragma: no cover - OpenCV is a dependency of the course
        pass
    T = np.array([[1.0, 0.0, _SHIFT[0]], [0.0, 1.0, _SHIFT[1]], [0.0, 0.0, 1.0]])
    shifted = np.asarray(run(src + _SHIFT, dst + _SHIFT), dtype=float)
    return _patch_distance(g, np.linalg.inv(T) @ shifted @ T)


def _scale_only(p):
    """A scaling to mean distance sqrt(2) from the origin, without centring (a slip the note names)."""
    k = np.sqrt(2) / np.mean(np.linalg.norm(p, axis=1))
    return np.diag([k, k, 1.0])


def _normalisers_rms(p):
    c = p.mean(axis=0)
    k = np.sqrt(2 / np.mean(np.sum((p - c) ** 2, axis=1)))
    return np.array([[k, 0, -k * c[0]], [0, k, -k * c[1]], [0, 0, 1]])


def _dlt_with_each(src, dst, normalise_src, normalise_dst):
    """The DLT with a different normaliser for each set, undone (H = T_dst^-1 H_n T_src)."""
    Ts, Td = normalise_src(src), normalise_dst(dst)
    sn = (np.column_stack([src, np.ones(len(src))]) @ Ts.T)[:, :2]
    dn = (np.column_stack([dst, np.ones(len(dst))]) @ Td.T)[:, :2]
    return np.linalg.inv(Td) @ np.linalg.svd(_dlt_rows(sn, dn))[2][-1].reshape(3, 3) @ Ts


def _dlt_success_note(run) -> str:
    """What a passing DLT did on the follow-up's draws, and a note if it normalised only one set."""
    offs = [_far_error(np.asarray(run(s.copy(), d.copy()), dtype=float)) for s, d in _far_draws()]
    line = (
        f"On the {FAR_DRAWS} noisy draws of the far patch your H is {np.median(offs):.2f} px off the truth "
        f"at the median (the worst grid point of each), {max(offs):.2f} px at worst."
    )
    note = _one_set_only(run)
    src, dst = next(iter(_far_draws()))
    rows = _row_choice(src, dst, np.asarray(run(src.copy(), dst.copy()), dtype=float))
    if rows:
        note = (note + "\n" if note else "") + (
            f"Note: you kept rows {rows} of x' x Hx = 0 for each pair. That is valid (any two of the three "
            f"fix H on exact data), but with w' = 1, r3 = -(u' r1 + v' r2): the pair's other equation then "
            f"enters weighted by {'v' if rows == 'r1 and r3' else 'u'}', near 0 for normalised points near "
            f"the centroid, so the noise is averaged over fewer equations (a DLT with r1 and r2 is "
            f"{_reference_median():.2f} px off at the median). Section 5 and H&Z (4.3) keep r1 and r2."
        )
    near, image = _dlt_cases()[-1]
    got = np.asarray(run(near.copy(), image.copy()), dtype=float)
    if divided_by_noise(got, H_ORIGIN_AT_INFINITY):
        note = (note + "\n" if note else "") + (
            f"Note: on test input 6 your H has h33 = 1 and entries up to {np.abs(got).max():.2g}: you "
            f"divided by h33. Its true h33 is 0, so the SVD's h33 was rounding noise (about 1e-17); the "
            f"ratios of the entries survive, so H is still right up to scale, but an h33 of exactly 0 "
            f"would have given inf and nan. Return the unit-norm h as it is."
        )
    return line + ("\n" + note if note else "")


def _noisy_case(expected) -> bool:
    """True for the noisy far input: camlab's estimate there is within the noise of H_FAR."""
    return _far_error(expected) < FAR_TOLERANCE_PX


def _same_homography(got, expected) -> bool:
    """Equal up to scale (exact inputs), or, on the noisy input, within FAR_TOLERANCE_PX of the truth."""
    if same_up_to_scale(got, expected, rtol=1e-6):
        return True
    g = np.asarray(got, dtype=float)
    if g.shape != (3, 3) or not np.isfinite(g).all() or abs(np.linalg.det(g)) < 1e-300:
        return False
    return _noisy_case(expected) and _far_error(g) < FAR_TOLERANCE_PX


def _dlt_diagnosis(args, got, expected) -> str:
    if np.shape(got) == (3, 3) and not np.isfinite(np.asarray(got, dtype=float)).all():
        return h33_slip(np.asarray(got, dtype=float), *args, expected) or shape_problem(
            got, expected
        )
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return H as a (3, 3) array: h.reshape(3, 3)."
    src, dst = args
    g = np.asarray(got, dtype=float)
    cause = h33_slip(g, src, dst, expected)
    if cause:
        return cause
    if same_up_to_scale(g, np.linalg.inv(expected), rtol=1e-5):
        return (
            "your H maps dst to src: it is the inverse. Did you swap src and dst when building A?"
        )
    if same_up_to_scale(g.T, expected, rtol=1e-5):
        return "your H is transposed: h lists H row by row, so use h.reshape(3, 3), not column by column."
    flip = np.array([[0.0, 1, 0], [1, 0, 0], [0, 0, 1]])  # (u, v) -> (v, u)
    if same_up_to_scale(g, flip @ expected @ flip, rtol=1e-5):
        return (
            "your H is the homography of the points with u and v swapped: you read each point as (v, u) "
            "(row, column), in src and dst alike. The course's points are (u, v) = (column, row): "
            "src[:, 0] is u."
        )
    cause = _normalisation_slip(g, src, dst, expected)
    if cause:
        return cause
    try:
        moved = map_points(g, src[0])
    except Exception:  # a singular H
        moved = np.array([np.nan, np.nan])
    if _noisy_case(expected):
        off = _far_error(g)
        return (
            f"these are noisy points about 3000 px from the origin, and your H is off the true homography "
            f"by up to {off:.3g} px there (within {FAR_TOLERANCE_PX:g} px passes; the noise alone explains "
            f"1-2 px): " + _far_cause(src, dst, g)
        )
    cause = _row_slip(g, src, dst, expected) or _half_pixel(g, src, dst)
    if cause:
        return cause
    return (
        f"H maps src[0] = {np.round(src[0], 2)} to {np.round(moved, 2)}; expected {np.round(dst[0], 2)}. "
        f"Build two rows of x' x Hx = 0 per pair, (0, -x^T, v' x^T) and (x^T, 0, -u' x^T), take the right "
        f"singular vector with the smallest singular value (the last row of Vt) and reshape it row by row."
    )


def _dlt_h33_fixed(src, dst):
    """The DLT with h33 = 1 fixed, by least squares on the raw pixels (a tutorial's form: no SVD)."""
    A = _dlt_rows(src, dst)
    return np.append(np.linalg.lstsq(A[:, :8], -A[:, 8], rcond=None)[0], 1.0).reshape(3, 3)


def _dlt_divided_by_exact_zero(src, dst):
    """A DLT divided by its h33 where the SVD's h33 came out exactly 0 (inf and nan entries)."""
    H = dlt_homography(src, dst)
    H[2, 2] *= abs(H[2, 2]) > 1e-12 * np.linalg.norm(H)
    with np.errstate(divide="ignore", invalid="ignore"):
        return H / H[2, 2]


def _dlt_raw_then_undone(src, dst):
    """T_src and T_dst computed and "undone", but A built from the raw pixels (a slip)."""
    Ts, Td = _normalisers(np.asarray(src, float), np.asarray(dst, float))[0]
    return np.linalg.inv(Td) @ _dlt_unnormalised(src, dst) @ Ts


def _half_pixel(g, src, dst) -> str:
    """Name a half-pixel shift of src, dst or both ("" if g is not one)."""
    src, dst = np.asarray(src, dtype=float), np.asarray(dst, dtype=float)
    for shift in (0.5, -0.5):
        for which, (s, d) in (
            ("src", (src + shift, dst)),
            ("dst", (src, dst + shift)),
            ("src and dst", (src + shift, dst + shift)),
        ):
            if same_up_to_scale(g, hg.estimate_homography(s, d), rtol=1e-5):
                return (
                    f"you shifted {which} by {shift:+g} px: a half-pixel offset. The course puts pixel "
                    f"centres at integers (docs/conventions.md), so use the coordinates as given."
                )
    return ""


def _row_slip(g, src, dst, expected) -> str:
    """Name a slip in the two rows of A.

    U' and v' swapped, or a sign flipped in one row (in pixels or in normalised coordinates); "" if
    none fits.
    """
    swap = np.array([[0.0, 1, 0], [1, 0, 0], [0, 0, 1]])
    flips = {"first": np.diag([1.0, -1, 1]), "second": np.diag([-1.0, 1, 1])}
    frames = [(np.eye(3), np.eye(3))] + [
        (np.linalg.inv(Td), Td) for _, Td in _normalisers(src, dst)
    ]
    for (
        back,
        forth,
    ) in frames:  # M applied to the (normalised) destination: H = T_dst^-1 M T_dst H_true
        if same_up_to_scale(g, back @ swap @ forth @ expected, rtol=1e-5):
            return (
                "you swapped u' and v' when building the rows: your H sends each point to (v', u'). "
                "The rows are (0^T, -x^T, v' x^T) and (x^T, 0^T, -u' x^T): v' in the first, u' in the second."
            )
        for row, flip in flips.items():
            if same_up_to_scale(g, back @ flip @ forth @ expected, rtol=1e-5):
                coordinate = "v'" if row == "first" else "u'"
                return (
                    f"a sign slip in the {row} row of each pair: your H sends each point to one with "
                    f"{coordinate} negated. The rows are (0^T, -x^T, v' x^T) and (x^T, 0^T, -u' x^T): "
                    f"the minus signs sit on x^T in the first and on u' x^T in the second."
                )
    return ""


def _normalisers(src, dst):
    """Hartley's T_src, T_dst: mean distance sqrt(2) (camlab's, H&Z 4.4.4) and the RMS-sqrt(2) variant."""

    def rms(p):
        c = p.mean(axis=0)
        k = np.sqrt(2 / np.mean(np.sum((p - c) ** 2, axis=1)))
        return np.array([[k, 0, -k * c[0]], [0, k, -k * c[1]], [0, 0, 1]])

    return [(hartley_normalise(src).T, hartley_normalise(dst).T), (rms(src), rms(dst))]


def _normalisation_slip(g, src, dst, expected) -> str:
    """Name a normalised DLT done wrong; "" if none fits.

    Its normalisation not undone, undone the wrong way round or on one side only, or its null vector
    a column of Vt.
    """
    inv = np.linalg.inv
    for Ts, Td in _normalisers(src, dst):
        context = SimpleNamespace(
            Ts=Ts, Td=Td, Hn=Td @ expected @ inv(Ts), H=np.asarray(expected, dtype=float)
        )  # H_n: of the normalised points
        cause = first_mistake(
            UNDO_MISTAKES, context, g, lambda got, wrong: same_up_to_scale(got, wrong, rtol=1e-5)
        )
        if cause:
            return cause
        for Ms, Md, how in (
            (
                Ts * [[1, 1, 0], [1, 1, 0], [1, 1, 1]],
                Td * [[1, 1, 0], [1, 1, 0], [1, 1, 1]],
                "dropped",
            ),
            (Ts.T, Td.T, "divided by"),
        ):  # X @ T normalises the points by T^T: w dropped (only scaled) or divided by (projective)
            if same_up_to_scale(g, inv(Td) @ Md @ expected @ inv(Ms) @ Ts, rtol=1e-5):
                return (
                    f"you normalised the points with X @ T, but with points as rows it is X @ T.T (x_n = T x "
                    f"for a column x). X @ T puts T's translation into the w column, which you {how}, so "
                    f"the points were not centred; the undo inv(T_dst) @ H_n @ T_src then assumes they were."
                )
    for largest in (_dlt_unnormalised(src, dst, pick=0), _dlt_normalised_largest(src, dst)):
        if same_up_to_scale(g, largest, rtol=1e-5):
            return (
                "you took the singular vector of the *largest* singular value (Vt[0], or the last column "
                "of np.linalg.eigh(A.T @ A)[1], which sorts from small to large). The h that makes |A h| "
                "least belongs to the smallest: Vt[-1] of np.linalg.svd (sorted large to small), or "
                "eigh's first column [:, 0]."
            )
    for column in (_dlt_unnormalised(src, dst, column=True), _dlt_normalised_column(src, dst)):
        if same_up_to_scale(g, column, rtol=1e-5):
            return (
                "you took a column of Vt. np.linalg.svd returns Vt, V transposed: the right singular "
                "vectors are its rows, so the null vector is the last row, Vt[-1], not Vt[:, -1]."
            )
    return ""


def _dlt_rows(src, dst):
    rows = []
    for (u, v), (up, vp) in zip(np.asarray(src, float), np.asarray(dst, float), strict=True):
        x = np.array([u, v, 1.0])
        rows += [
            np.concatenate([np.zeros(3), -x, vp * x]),
            np.concatenate([x, np.zeros(3), -up * x]),
        ]
    return np.array(rows)


def _row_choice(src, dst, g) -> str:
    """Return "r1 and r3" or "r2 and r3" if g is the normalised DLT with those rows per pair, else ""."""
    for keep, rows in (((0, 2), "r1 and r3"), ((1, 2), "r2 and r3")):
        if _patch_distance(g, _dlt_two_rows(src, dst, keep)) < 0.05:
            return rows
    return ""


def _dlt_two_rows(src, dst, keep):
    """The normalised DLT with rows ``keep`` of (r1, r2, r3) per pair (a valid-looking choice, noisier)."""
    src, dst = np.asarray(src, dtype=float), np.asarray(dst, dtype=float)
    Ts, Td = hartley_normalise(src).T, hartley_normalise(dst).T
    a = np.column_stack([src, np.ones(len(src))]) @ Ts.T
    b = np.column_stack([dst, np.ones(len(dst))]) @ Td.T
    rows = []
    for x, (up, vp, wp) in zip(a, b, strict=True):
        r = (
            np.r_[np.zeros(3), -wp * x, vp * x],
            np.r_[wp * x, np.zeros(3), -up * x],
            np.r_[-vp * x, up * x, np.zeros(3)],
        )
        rows += [r[keep[0]], r[keep[1]]]
    return np.linalg.inv(Td) @ np.linalg.svd(np.array(rows))[2][-1].reshape(3, 3) @ Ts


def _dlt_points_times_t(src, dst):
    """A normalised DLT whose points were normalised by X @ T (not X @ T.T), w dropped, undone with T."""
    src, dst = np.asarray(src, dtype=float), np.asarray(dst, dtype=float)
    Ts, Td = hartley_normalise(src).T, hartley_normalise(dst).T
    sn = (np.column_stack([src, np.ones(len(src))]) @ Ts)[:, :2]
    dn = (np.column_stack([dst, np.ones(len(dst))]) @ Td)[:, :2]
    return np.linalg.inv(Td) @ np.linalg.svd(_dlt_rows(sn, dn))[2][-1].reshape(3, 3) @ Ts


def _dlt_unnormalised(src, dst, pick=-1, column=False):
    """The plain DLT in pixels (a plausible student answer).

    ``pick`` chooses the singular vector, ``column`` reads it from a column of Vt (a slip).
    """
    Vt = np.linalg.svd(_dlt_rows(src, dst))[2]
    return (Vt[:, pick] if column else Vt[pick]).reshape(3, 3)


def _dlt_normalised_parts(src, dst, column=False):
    """T_src, T_dst and the normalised DLT's H_n (from Vt's last row, or its last column: a slip)."""
    src, dst = np.asarray(src, dtype=float), np.asarray(dst, dtype=float)
    Ts, Td = hartley_normalise(src).T, hartley_normalise(dst).T
    sn = (np.column_stack([src, np.ones(len(src))]) @ Ts.T)[:, :2]
    dn = (np.column_stack([dst, np.ones(len(dst))]) @ Td.T)[:, :2]
    Vt = np.linalg.svd(_dlt_rows(sn, dn))[2]
    return Ts, Td, (Vt[:, -1] if column else Vt[-1]).reshape(3, 3)


def _dlt_normalised_largest(src, dst):
    src, dst = np.asarray(src, dtype=float), np.asarray(dst, dtype=float)
    Ts, Td = hartley_normalise(src).T, hartley_normalise(dst).T
    sn = (np.column_stack([src, np.ones(len(src))]) @ Ts.T)[:, :2]
    dn = (np.column_stack([dst, np.ones(len(dst))]) @ Td.T)[:, :2]
    return np.linalg.inv(Td) @ np.linalg.svd(_dlt_rows(sn, dn))[2][0].reshape(3, 3) @ Ts


def _dlt_normalised_column(src, dst):
    Ts, Td, Hn = _dlt_normalised_parts(src, dst, column=True)
    return np.linalg.inv(Td) @ Hn @ Ts


def _dlt_not_undone(src, dst):
    return _dlt_normalised_parts(src, dst)[2]  # H_n itself


def _dlt_undone_wrong_order(src, dst):
    Ts, Td, Hn = _dlt_normalised_parts(src, dst)
    return Td @ Hn @ np.linalg.inv(Ts)  # T_dst H_n T_src^-1


def _dlt_undone_one_side(src, dst, side):
    Ts, Td, Hn = _dlt_normalised_parts(src, dst)
    return np.linalg.inv(Td) @ Hn if side == "dst" else Hn @ Ts


def _dlt_normalised_variant(src, dst, slip):
    """A normalised DLT with one slip.

    "swap" (u', v' swapped in the rows), "sign" (+u' x^T in the second row), "src both" (undone with
    inv(T_src) @ H_n @ T_src).
    """
    src, dst = np.asarray(src, dtype=float), np.asarray(dst, dtype=float)
    Ts, Td = hartley_normalise(src).T, hartley_normalise(dst).T
    sn = (np.column_stack([src, np.ones(len(src))]) @ Ts.T)[:, :2]
    dn = (np.column_stack([dst, np.ones(len(dst))]) @ Td.T)[:, :2]
    if slip == "swap":
        dn = dn[:, ::-1]
    if slip == "sign":
        dn = dn * [-1.0, 1.0]  # +u' x^T in the second row is the DLT of (-u', v')
    Hn = np.linalg.svd(_dlt_rows(sn, dn))[2][-1].reshape(3, 3)
    return np.linalg.inv(Ts if slip == "src both" else Td) @ Hn @ Ts


def _undo_variant(src, dst, name):
    """The normalised DLT undone by the row ``name`` of UNDO_MISTAKES (a student's wrong answer)."""
    src, dst = np.asarray(src, dtype=float), np.asarray(dst, dtype=float)
    Ts, Td = hartley_normalise(src).T, hartley_normalise(dst).T
    sn = (np.column_stack([src, np.ones(len(src))]) @ Ts.T)[:, :2]
    dn = (np.column_stack([dst, np.ones(len(dst))]) @ Td.T)[:, :2]
    Hn = np.linalg.svd(_dlt_rows(sn, dn))[2][-1].reshape(3, 3)
    row = next(m for m in UNDO_MISTAKES if m.name == name)
    return row.answer(SimpleNamespace(Ts=Ts, Td=Td, Hn=Hn))


def dlt_homography(src, dst):
    """The normalised DLT: normalise, stack two rows of x' x Hx = 0 per pair, SVD, undo.

    Parameters
    ----------
    src, dst : (N, 2) array_like
        Matching points, N >= 4, no three collinear: dst ~ H src.

    Returns
    -------
    (3, 3) ndarray
        H, at an arbitrary scale (not divided by H[2, 2], which may be 0).

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 4.4 (algorithm 4.2).
    """
    src, dst = np.asarray(src, dtype=float), np.asarray(dst, dtype=float)

    def normaliser(p):  # centroid to 0, mean distance to the centroid sqrt(2)
        c = p.mean(axis=0)
        s = np.sqrt(2) / np.mean(np.linalg.norm(p - c, axis=1))
        return np.array([[s, 0, -s * c[0]], [0, s, -s * c[1]], [0, 0, 1]])

    T_src, T_dst = normaliser(src), normaliser(dst)
    a = np.column_stack([src, np.ones(len(src))]) @ T_src.T
    b = np.column_stack([dst, np.ones(len(dst))]) @ T_dst.T
    rows = []
    for x, (u, v, _) in zip(a, b, strict=True):
        rows.append(np.concatenate([np.zeros(3), -x, v * x]))
        rows.append(np.concatenate([x, np.zeros(3), -u * x]))
    h = np.linalg.svd(np.array(rows))[2][-1]  # smallest singular value's right vector
    return np.linalg.inv(T_dst) @ h.reshape(3, 3) @ T_src  # any scale: h33 may be 0


register_exercise(
    Exercise(
        name="dlt_homography",
        lesson="07",
        reference=hg.estimate_homography,
        cases=_dlt_cases,
        compare=_same_homography,
        up_to_scale=True,
        diagnose=_dlt_diagnosis,
        wrong_variants=(
            (lambda s, d: hg.estimate_homography(d, s), "inverse"),
            (lambda s, d: hg.estimate_homography(s, d).T, "transposed"),
            (lambda s, d: _dlt_unnormalised(s, d, pick=0), "sorts from small to large"),
            (_dlt_unnormalised, "Normalise each point set"),
            (_dlt_not_undone, "not undone"),
            (_dlt_undone_wrong_order, "wrong way round"),
            (
                lambda s, d: (lambda Ts, Td, Hn: Ts @ Hn @ np.linalg.inv(Td))(
                    *_dlt_normalised_parts(s, d)
                ),
                "T_src @ H_n @ inv",
            ),
            (lambda s, d: _dlt_undone_one_side(s, d, "dst"), "undid only the destination's"),
            (lambda s, d: _dlt_undone_one_side(s, d, "src"), "undid only the source's"),
            (lambda s, d: _dlt_normalised_column(s, d), "a column of Vt"),
            (lambda s, d: _dlt_unnormalised(s, d, column=True), "a column of Vt"),
            (lambda s, d: _dlt_with(s, d, _FAR_SLIPS[1][0]), "scales the wrong way"),
            (lambda s, d: _dlt_normalised_variant(s, d, "swap"), "swapped u' and v'"),
            (lambda s, d: _dlt_normalised_variant(s, d, "sign"), "sign slip in the second row"),
            (lambda s, d: _dlt_normalised_variant(s, d, "src both"), "T_src on both sides"),
            (lambda s, d: _dlt_with(s, d, _FAR_SLIPS[2][0]), "does not move the centroid"),
            (lambda s, d: _dlt_with(s, d, _FAR_SLIPS[3][0]), "translation is -c, not -s c"),
            (lambda s, d: _dlt_with(s, d, _FAR_SLIPS[4][0]), "fixed for a 640 x 480 image"),
            (lambda s, d: _undo_variant(s, d, "T transposed in the undo"), "T transposed"),
            (lambda s, d: _undo_variant(s, d, "elementwise products"), "element by element"),
            (lambda s, d: _undo_variant(s, d, "H_n transposed"), "H_n is transposed"),
            (_dlt_normalised_largest, "largest"),
            (
                lambda s, d: hg.estimate_homography(
                    np.asarray(s, float)[:, ::-1], np.asarray(d, float)[:, ::-1]
                ),
                "u and v swapped",
            ),
            (
                lambda s, d: (
                    np.linalg.inv(hartley_normalise(np.asarray(d, float)).T)
                    @ hg.estimate_homography(s, d)
                ),
                "dst never had",
            ),
            (
                lambda s, d: _dlt_with(s, d, _FAR_SLIPS[5][0]),
                "maps normalised points back to pixels",
            ),
            (lambda s, d: hg.estimate_homography(np.asarray(s) + 0.5, d), "half-pixel offset"),
            (lambda s, d: hg.estimate_homography(s, d).tolist(), "you returned a list"),
            (_dlt_h33_fixed, "you fixed h33 = 1"),
            (_dlt_raw_then_undone, "you built A from the raw pixels, yet undid"),
            (_dlt_divided_by_exact_zero, "you divided H by its h33, which is exactly 0"),
            (_dlt_points_times_t, "with X @ T, but"),
            (
                lambda s, d: hg.estimate_homography(np.asarray(s)[:4], np.asarray(d)[:4]),
                "first 4 of the 30 pairs",
            ),
        ),
        follow_up=_dlt_follow_up,
        success_note=_dlt_success_note,
        ndarray_only=True,
        teaching=dlt_homography,
    )
)
