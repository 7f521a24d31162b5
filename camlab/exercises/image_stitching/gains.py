"""Lesson 09, exercise 3: gain compensation's normal equations (gains_from_overlaps) and the slips its diagnosis names."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ...stitching import gains_from_overlaps as _gains_reference
from .._answers import same_array
from .._core import Exercise, Mistake, first_mistake, register_exercise

SIGMA_N, SIGMA_G = 10.0, 1.0
"""The exercise's noise (grey levels, as the intensities) and prior spread, as in section 5."""

# ----------------------------------------------------------------------------- gains from the overlaps


def gains_from_overlaps(N, I_mean):
    """Teaching solution: one gain per image, from the overlaps' sizes and mean intensities.

    Parameters
    ----------
    N : (n, n) array_like
        ``N[i, j]``: pixels in the overlap of images i and j (symmetric); ``N[i, i]`` is image i's own
        size and is not an overlap.
    I_mean : (n, n) array_like
        ``I_mean[i, j]``: the mean grey level (0-255) of image i on its overlap with image j.

    Returns
    -------
    (n,) ndarray
        The gains g minimising section 5's error with sigma_N = 10 grey levels and sigma_g = 1.
    """
    sigma_n, sigma_g = 10.0, 1.0  # grey levels, as the means; the prior's spread about 1
    N = np.array(N, dtype=float)  # a copy: the input stays as it was
    M = np.asarray(I_mean, dtype=float)
    np.fill_diagonal(N, 0)  # an image does not overlap itself
    n = len(N)
    A, b = np.zeros((n, n)), np.zeros(n)
    for i in range(n):
        for j in range(n):
            # d e / d g_i = 0: the data term pulls g_i I_ij towards g_j I_ji, the prior pulls g_i towards 1
            A[i, i] += N[i, j] * (2 * M[i, j] ** 2 / sigma_n**2 + 1 / sigma_g**2)
            A[i, j] -= N[i, j] * 2 * M[i, j] * M[j, i] / sigma_n**2
            b[i] += N[i, j] / sigma_g**2
    return np.linalg.solve(A, b)


def _reference(N, I_mean):
    """camlab.stitching.gains_from_overlaps on N with its diagonal zeroed, sigma_N = 10 and sigma_g = 1."""
    N = np.array(N, dtype=float)
    np.fill_diagonal(N, 0)
    return _gains_reference(N, I_mean, SIGMA_N, SIGMA_G)


def _scene(exposures, overlaps, size=(240, 320), seed=0, whole=(90, 140)):
    """N and I_mean for images of one scene: overlap (i, j, pixels, scene mean), each image scaled by its exposure.

    ``whole``: the range of each image's own mean (the diagonal, which the equations ignore), drawn like the
    overlaps' so that a night scene's printed input looks like one.
    """
    n = len(exposures)
    rng = np.random.default_rng(seed)
    N = np.diag(np.full(n, float(size[0] * size[1])))
    M = np.diag(rng.uniform(*whole, n) * np.asarray(exposures))
    for i, j, pixels, mean in overlaps:
        N[i, j] = N[j, i] = pixels
        M[i, j] = exposures[i] * mean + rng.normal(
            0, 0.5
        )  # a little noise: the two means never agree exactly
        M[j, i] = exposures[j] * mean + rng.normal(0, 0.5)
    return N, M


def _gains_cases():
    return [
        # night photos first, means near 10 grey levels: the data weigh 2 I^2 / sigma_N^2 = 2 per pixel,
        # the prior 1, so a slip in either's weight moves the gains by percents and the first failure
        # shows it plainly (on the brighter inputs after it, where the prior mainly fixes the overall
        # scale, by parts in ten thousand)
        _scene(
            [1.0, 1.3, 0.9],
            [(0, 1, 6000, 9.0), (1, 2, 5000, 12.0), (0, 2, 3000, 10.0)],
            seed=3,
            whole=(8, 13),
        ),
        _scene([1.0, 1.3], [(0, 1, 9000, 110.0)]),  # two photos, the second 30 % brighter
        _scene(
            [1.1, 1.0, 0.8], [(0, 1, 12000, 120.0), (1, 2, 7000, 95.0)], seed=1
        ),  # a chain: 0 and 2 never meet
        _scene(
            [1.0, 0.9, 1.2, 1.05],
            [(0, 1, 15000, 100.0), (1, 2, 9000, 130.0), (2, 3, 11000, 80.0), (0, 3, 4000, 115.0)],
            seed=2,
        ),  # a loop of four
    ]


def _solve(
    N,
    M,
    *,
    sigma_n=SIGMA_N,
    sigma_g=SIGMA_G,
    square=True,
    factor=2.0,
    prior_a=True,
    prior_b=True,
    sign=-1.0,
    diag=False,
    diag_in_b=False,
    coupling="ij ji",
    prior="N",
    data_n=True,
):
    """Section 5's normal equations with one slip switched on (the keywords' defaults are right).

    ``diag_in_b`` zeroes N_ii in A but leaves it in b; ``coupling`` says which means the coupling
    multiplies: "ij ji" (I * I.T, right), "ij ij" (I * I, I_ij^2) or "ji ji" (I.T * I.T, I_ji^2). ``prior`` weighs the prior (1 - g_i)^2 / sigma_g^2 by
    N_ij ("N", right), by 1 per overlapping image ("count"), by 1 per image ("one") or by N_ij for
    j > i only ("upper": each pair summed once, its prior on the first image only).
    """
    N = np.array(N, dtype=float)
    own = np.diag(N).copy()
    if not diag:  # the slip "diagonal kept" leaves N_ii in: with j = i the data terms cancel, the prior's stay
        np.fill_diagonal(N, 0)
    s2 = sigma_n**2 if square else sigma_n
    D = (
        N if data_n else (N > 0).astype(float)
    )  # the slip "data without N_ij": one data term per overlap
    first, second = {"ij ji": (M, M.T), "ij ij": (M, M), "ji ji": (M.T, M.T)}[coupling]
    A = sign * D * factor * first * second / s2
    weight = {
        "N": N,
        "count": (N > 0).astype(float),
        "one": np.eye(len(N)),
        "upper": np.triu(N, 1),
    }[prior]  # the prior's weight per (i, j)
    A[np.diag_indices(len(N))] = (D * factor * M**2 / s2).sum(axis=1) + (
        weight.sum(axis=1) / sigma_g**2 if prior_a else 0
    )
    if diag:
        A[np.diag_indices(len(N))] -= np.diag(N) * factor * np.diag(M) ** 2 / s2
    b = weight.sum(axis=1) / sigma_g**2 if prior_b else np.zeros(len(N))
    if diag_in_b:
        b = b + own / sigma_g**2
    with np.errstate(all="ignore"):
        try:
            return np.linalg.solve(A, b)
        except np.linalg.LinAlgError:
            return np.full(len(N), np.nan)


def _diagonal_overwritten(N, M, *, in_b=True):
    """A vectorised slip: N's diagonal kept, A's diagonal set (not added to) over the coupling term.

    ``A = -2 N I I^T / sigma_N^2`` then ``fill_diagonal(A, sum_j N_ij (2 I_ij^2 / sigma_N^2 + 1 / sigma_g^2))``
    with j = i in the sum: the j = i data term 2 N_ii I_ii^2 / sigma_N^2 stays on the diagonal (in a loop it
    cancels against the coupling term), and N_ii is in b too unless ``in_b`` is False.
    """
    N = np.array(N, dtype=float)
    A = -2 * N * M * M.T / SIGMA_N**2
    np.fill_diagonal(A, (N * (2 * M**2 / SIGMA_N**2 + 1 / SIGMA_G**2)).sum(axis=1))
    off = N - np.diag(np.diag(N))
    with np.errstate(all="ignore"):
        return np.linalg.solve(A, (N if in_b else off).sum(axis=1) / SIGMA_G**2)


def _context(args, expected):
    N, M = (np.asarray(a, dtype=float) for a in args)
    return SimpleNamespace(N=N, M=M, expected=expected)


_GAIN_SLIPS = (
    Mistake(
        "no prior",
        lambda c: [np.zeros(len(c.N)), _solve(c.N, c.M, prior_a=False, prior_b=False)],
        "all gains 0: without the prior the equations are homogeneous (every term has a g), so g = 0 solves "
        "them (so does any multiple of one solution). Add N_ij / sigma_g^2 on the diagonal and on the right-hand "
        "side b_i = sum_j N_ij / sigma_g^2: the prior keeps the gains near 1.",
    ),
    Mistake(
        "prior only on the right",
        lambda c: _solve(c.N, c.M, prior_a=False),
        "the prior (1 - g_i)^2 / sigma_g^2 gives two terms: N_ij / sigma_g^2 on the right-hand side, and "
        "g_i N_ij / sigma_g^2 on the diagonal. You have the first only.",
    ),
    Mistake(
        "I transposed",
        lambda c: _solve(c.N, c.M.T),
        "I_mean[i, j] is image i's mean on its overlap with j, and the diagonal term of equation i uses it "
        "(2 I_ij^2 / sigma_N^2): you used I_mean[j, i], the other image's mean there. Either you passed I_mean "
        "transposed, or you summed the diagonal term over axis 0: equation i sums over j along row i, axis=1.",
    ),
    Mistake(
        "I * I coupling",
        lambda c: _solve(c.N, c.M, coupling="ij ij"),
        "the coupling term A[i, j] = -2 N_ij I_ij I_ji / sigma_N^2 multiplies image i's mean by image j's on the "
        "same overlap: with arrays that is I_mean * I_mean.T. You wrote I_mean * I_mean (I_ij^2).",
    ),
    Mistake(
        "I.T * I.T coupling",
        lambda c: _solve(c.N, c.M, coupling="ji ji"),
        "the coupling term A[i, j] = -2 N_ij I_ij I_ji / sigma_N^2 multiplies image i's mean by image j's on the "
        "same overlap: with arrays that is I_mean * I_mean.T. You wrote I_mean.T * I_mean.T (I_ji^2).",
    ),
    Mistake(
        "sign",
        lambda c: _solve(c.N, c.M, sign=1.0),
        "a sign flip: differentiating (g_i I_ij - g_j I_ji)^2 by g_i gives 2 I_ij (g_i I_ij - g_j I_ji), so the "
        "coupling term -2 N_ij I_ij I_ji / sigma_N^2 enters A[i, j] with a minus.",
    ),
    Mistake(
        "no factor 2",
        lambda c: _solve(c.N, c.M, factor=1.0),
        "the data term weighs half as much as it should against the prior: either the data terms lost their "
        "factor 2, or the prior gained one (counted for (j, i) too: 2 N_ij / sigma_g^2). In e = 1/2 sum over "
        "i != j, the data term (g_i I_ij - g_j I_ji)^2 appears twice, as (i, j) and as (j, i): that cancels the "
        "1/2, and differentiating the square leaves a 2, 2 I_ij (g_i I_ij - g_j I_ji). The prior (1 - g_i)^2 "
        "appears only in the (i, j) terms, so its 1/2 cancels against the derivative's 2 and it keeps no factor. "
        "Keep 2 I_ij^2 / sigma_N^2 and 2 I_ij I_ji / sigma_N^2 in A, and N_ij / sigma_g^2 (no 2) in A and b.",
    ),
    Mistake(
        "data counted twice",
        lambda c: _solve(c.N, c.M, factor=4.0),
        "the data term weighs twice what it should against the prior: either the data terms carry 4 (the pair "
        "counted as (i, j) and (j, i) and the 1/2 of e dropped too, or the derivative's 2 taken twice), or the "
        "prior kept the 1/2 of e (N_ij / (2 sigma_g^2)). Equation i has 2 I_ij^2 / sigma_N^2 and "
        "2 I_ij I_ji / sigma_N^2 in the data terms and N_ij / sigma_g^2 in the prior.",
    ),
    Mistake(
        "data once, prior twice",
        lambda c: _solve(c.N, c.M, factor=0.5),
        "the data term weighs a quarter of what it should against the prior: the data terms lost their factor 2 "
        "and the prior gained one (or the data carry 1/2). Equation i: 2 N_ij I_ij^2 / sigma_N^2 and "
        "-2 N_ij I_ij I_ji / sigma_N^2 from the data, N_ij / sigma_g^2 (no 2) from the prior.",
    ),
    Mistake(
        "prior without N_ij",
        lambda c: _solve(c.N, c.M, prior="count"),
        "the prior is weighted by the overlap size N_ij, like the data term: e = 1/2 sum N_ij (data + "
        "(1 - g_i)^2 / sigma_g^2), so it adds N_ij / sigma_g^2 to A[i, i] and to b_i for every j != i. You "
        "added 1 / sigma_g^2 per overlap, so the prior is thousands of times too weak.",
    ),
    Mistake(
        "data without N_ij",
        lambda c: _solve(c.N, c.M, data_n=False),
        "the data term is weighted by the overlap size N_ij, like the prior: e = 1/2 sum N_ij ((g_i I_ij - "
        "g_j I_ji)^2 / sigma_N^2 + ...), so each pixel of an overlap counts. You added one data term per overlap, "
        "so the prior outweighs the data thousands of times and every gain stays near 1.",
    ),
    Mistake(
        "no N_ij anywhere",
        lambda c: _solve(c.N, c.M, data_n=False, prior="count"),
        "neither term carries N_ij: you weighted every overlap equally (N as 0 / 1). e = 1/2 sum N_ij (data + "
        "prior): each overlap counts by its number of pixels N_ij, in the data term and the prior alike, so a "
        "sliver of an overlap pulls on the gains as little as it tells about them.",
    ),
    Mistake(
        "pairs once, prior on the first",
        lambda c: _solve(c.N, c.M, prior="upper"),
        "you summed each pair once (j > i) and gave its prior to the first image only, so image i's prior "
        "counts only its overlaps with later images (the last image has none). e sums over i != j: the pair "
        "appears as (i, j) with the prior (1 - g_i)^2 and as (j, i) with (1 - g_j)^2, so every image's "
        "prior is weighted by all its overlaps, j < i included.",
    ),
    Mistake(
        "one prior per image",
        lambda c: _solve(c.N, c.M, prior="one"),
        "the prior is weighted by the overlap size N_ij and summed over j, like the data term: it adds "
        "sum_j N_ij / sigma_g^2 to A[i, i] and to b_i. You added one 1 / sigma_g^2 per image, so the prior is "
        "thousands of times too weak.",
    ),
    Mistake(
        "sigma not squared",
        lambda c: _solve(c.N, c.M, square=False),
        "divide by sigma_N^2 (100 grey levels^2), not sigma_N (10): the error weighs squared differences by the "
        "variance.",
    ),
    Mistake(
        "sigma in 0-1 units",
        lambda c: _solve(c.N, c.M, sigma_n=SIGMA_N / 255),
        "sigma_N = 10/255 is for intensities in [0, 1]; these means are grey levels 0-255, so sigma_N = 10. With "
        "the smaller sigma the prior barely counts.",
    ),
    Mistake(
        "sigmas swapped",
        lambda c: _solve(c.N, c.M, sigma_n=SIGMA_G, sigma_g=SIGMA_N),
        "you swapped the two sigmas: sigma_N = 10 grey levels divides the data term (the overlaps' "
        "differences), sigma_g = 1 the prior (1 - g_i)^2. Swapped, the data term weighs 10 000 times too much "
        "against the prior.",
    ),
    Mistake(
        "sigma_N = 1",
        lambda c: _solve(c.N, c.M, sigma_n=1.0),
        "you took sigma_N = 1: the noise of the means is sigma_N = 10 grey levels (section 5), so the data term "
        "is divided by sigma_N^2 = 100; with 1 it weighs 100 times too much against the prior.",
    ),
    Mistake(
        "sigma_g = 0.1",
        lambda c: _solve(c.N, c.M, sigma_g=0.1),
        "the prior weighs 100 times too much against the data term, and two slips give exactly these gains: "
        "sigma_g = 0.1, Brown & Lowe's value (this exercise and camlab take sigma_g = 1, a weaker prior, so "
        "that exposures 30 % apart are not pulled back towards 1; section 5), or the data term divided by "
        "10 000 instead of sigma_N^2 = 100 (sigma_N = 100, or sigma_N^2 squared again).",
    ),
    Mistake(
        "means in 0-1",
        lambda c: _solve(c.N, c.M / 255),
        "you divided the means by 255 but kept sigma_N = 10 grey levels: the means are grey levels 0-255, as "
        "sigma_N is; use them as they are (or divide sigma_N by 255 too).",
    ),
    Mistake(
        "N_ii in b",
        lambda c: _solve(c.N, c.M, diag_in_b=True),
        "N[i, i] is image i's own size, not an overlap: you left it out of A but kept it in b_i = sum_j N_ij / "
        "sigma_g^2. Skip j = i in every sum.",
    ),
    Mistake(
        "b negated",
        lambda c: -c.expected,
        "every gain has the wrong sign: the right-hand side is b_i = +sum_j N_ij / sigma_g^2 (the prior "
        "(1 - g_i)^2 / sigma_g^2 pulls g_i towards +1; its derivative -2 N_ij (1 - g_i) / sigma_g^2 moves to the "
        "right-hand side with a plus). With b negated, A g = -b gives -g.",
    ),
    Mistake(
        "1/g",
        lambda c: 1 / c.expected,
        "you returned 1/g: g is the gain that multiplies each image (g_i I_ij should match g_j I_ji), not the "
        "exposure it undoes. Return the solution of A g = b itself.",
    ),
    Mistake(
        "diagonal kept",
        lambda c: _solve(c.N, c.M, diag=True),
        "N[i, i] is image i's own size, not an overlap: skip j = i (or zero N's diagonal, on a copy) before "
        "summing over j.",
    ),
    Mistake(
        "diagonal kept, A's diagonal overwritten",
        lambda c: [
            _diagonal_overwritten(c.N, c.M),
            _diagonal_overwritten(c.N, c.M, in_b=False),
        ],
        "N[i, i] is image i's own size, not an overlap, and you kept it in your sums: with j = i, A[i, i] "
        "gains 2 N_ii I_ii^2 / sigma_N^2 (setting A's diagonal after the coupling term, e.g. with fill_diagonal, "
        "keeps it; in a loop it would cancel against -2 N_ii I_ii I_ii / sigma_N^2), which is huge against the "
        "overlaps' terms and drags every gain towards 0. Zero N's diagonal (on a copy) before summing over j.",
    ),
    Mistake(
        "normalised",
        lambda c: (
            [c.expected / c.expected[k] for k in range(len(c.expected))]
            + [c.expected / c.expected.mean()]
        ),
        "you rescaled the gains (divided them by one image's gain, or by their mean); the prompt asks for the "
        "solution g itself, whose prior already fixes the scale near 1 (stitch divides by the reference's gain "
        "afterwards, outside this function).",
    ),
)
"""gains_from_overlaps' slips, as the gains they give on the test input (checked in this order)."""


def _same(got, answer) -> bool:
    answers = answer if isinstance(answer, list) else [answer]
    return any(
        np.shape(a) == np.shape(got) and np.allclose(got, a, rtol=1e-6, atol=1e-9) for a in answers
    )


def _gains_diagnosis(args, got, expected, run=None) -> str:
    g = np.asarray(got, dtype=float)
    if g.shape != expected.shape:
        return (
            f"return one gain per image, an array of shape {expected.shape}, got shape {g.shape}."
        )
    shown = [m for m in _GAIN_SLIPS if first_mistake([m], _context(args, expected), g, _same)]
    for case in _gains_cases() if len(shown) > 1 and run is not None else ():
        # slips that tie here (a prior too weak, whatever the cause, gives the same gains on two
        # photos) are told apart on the other inputs
        try:
            other = np.asarray(run(*case), dtype=float)
        except Exception:  # the student's function fails there: keep what this input showed
            break
        ctx = _context(case, _reference(*case))
        shown = [m for m in shown if first_mistake([m], ctx, other, _same)] or shown
    if shown:
        return shown[0].hint
    N, M = _context(args, expected).N, _context(args, expected).M
    rescaled = _rescaled_means_hint(N, M, g)
    if rescaled:
        return rescaled
    return (
        f"your gains do not minimise section 5's error: e(g) = {_energy(N, M, g):.6g} at your g, "
        f"{_energy(N, M, expected):.6g} at the minimum. Check each term of d e / d g_i = 0 against the "
        "derivative of e = 1/2 sum over i != j of N_ij ((g_i I_ij - g_j I_ji)^2 / sigma_N^2 + (1 - g_i)^2 "
        "/ sigma_g^2): which terms carry g_i, which g_j, and which none (those go to b)."
    )


def _data_weight(N, M, g) -> float | None:
    """The factor t on the data term for which ``g`` solves section 5's equations, or None if no t fits.

    Means rescaled by k (I_mean / 1000, say) scale every data term by k^2 and leave the prior as it
    is, so ``g`` is then the solution of (t D + P) g = p with t = k^2: t is fitted by least squares
    from D g = (p - P g) / t, then checked by solving with it.
    """
    N = np.array(N, dtype=float)
    np.fill_diagonal(N, 0)
    D = -2 * N * M * M.T / SIGMA_N**2
    D[np.diag_indices(len(N))] = (2 * N * M**2).sum(axis=1) / SIGMA_N**2
    p = N.sum(axis=1) / SIGMA_G**2  # the prior's diagonal P = diag(p) and right-hand side p
    if not np.all(np.isfinite(g)) or not (Dg := D @ g).any():
        return None
    t = float(Dg @ (p - p * g) / (Dg @ Dg))
    if t <= 0:
        return None
    with np.errstate(all="ignore"):
        fit = np.linalg.solve(t * D + np.diag(p), p)
    return t if _same(g, fit) else None


def _rescaled_means_hint(N, M, g) -> str | None:
    """Name a units slip: gains that weigh the data term k^2 times, as means rescaled by k do; else None."""
    t = _data_weight(N, M, g)
    if t is None or abs(np.log(t)) < 1e-3:
        return None
    k = float(np.sqrt(t))
    scaled = f"multiplied by {k:.4g}" if k > 1 else f"divided by {1 / k:.4g}"
    return (
        f"your gains are the right ones for means {scaled} (the data term weighs {t:.3g} times what it "
        "should against the prior): a units slip? sigma_N = 10 is in grey levels 0-255, as I_mean is; use the "
        "means as they are, or rescale sigma_N by the same factor."
    )


def _energy(N, M, g) -> float:
    """Section 5's error e(g) (sigma_N = 10, sigma_g = 1), over i != j; N's diagonal is ignored."""
    N = np.array(N, dtype=float)
    np.fill_diagonal(N, 0)
    g = np.asarray(g, dtype=float)
    data = (g[:, None] * M - g[None, :] * M.T) ** 2 / SIGMA_N**2
    return float(0.5 * np.sum(N * (data + (1 - g[:, None]) ** 2 / SIGMA_G**2)))


def _gains_exception_hint(exc: Exception, args: tuple) -> str:
    if isinstance(exc, np.linalg.LinAlgError):
        return (
            "a singular matrix: without the prior's N_ij / sigma_g^2 on the diagonal the data terms alone only fix "
            "the gains' ratios (any multiple of a solution is one), so A has no inverse: add the prior. Or an "
            "equation is empty: equation i sums over every j != i, j < i included; summing over j > i only (each "
            "pair once) leaves the last image's row of A all zeros."
        )
    return ""


def _variant(name: str):
    """The row ``name`` of _GAIN_SLIPS as a student's function (for the tests)."""
    row = next(m for m in _GAIN_SLIPS if m.name == name)

    def wrong(N, I_mean):
        a = row.answer(_context((N, I_mean), _reference(N, I_mean)))
        return np.array(a[-1] if isinstance(a, list) else a)

    return wrong


def _pairs_once(N, I_mean):
    """A student who sums over each pair once (j > i): the last image's equation is empty."""
    N = np.array(N, dtype=float)
    M = np.asarray(I_mean, dtype=float)
    n = len(N)
    A, b = np.zeros((n, n)), np.zeros(n)
    for i in range(n):
        for j in range(i + 1, n):
            A[i, i] += N[i, j] * (2 * M[i, j] ** 2 / SIGMA_N**2 + 1 / SIGMA_G**2)
            A[i, j] -= N[i, j] * 2 * M[i, j] * M[j, i] / SIGMA_N**2
            b[i] += N[i, j] / SIGMA_G**2
    return np.linalg.solve(A, b)


register_exercise(
    Exercise(
        name="gains_from_overlaps",
        lesson="09",
        reference=_reference,
        ndarray_only=True,
        cases=_gains_cases,
        compare=same_array(
            rtol=1e-5, atol=1e-9
        ),  # a right answer from an optimiser that stopped near 1e-6
        diagnose=_gains_diagnosis,
        diagnosis_runs=True,
        teaching=gains_from_overlaps,
        exception_hint=_gains_exception_hint,
        in_place_examples={
            "N": (
                "`np.fill_diagonal(N, 0)`, `N[:, 0] = ...`, `N /= N.sum()`",
                "`N = N.copy()` then `np.fill_diagonal(N, 0)`, or `N * (1 - np.eye(len(N)))`",
            ),
            "I_mean": ("`I_mean /= 255`, `I_mean[I_mean == 0] = ...`", "`I_mean / 255`"),
        },
        wrong_variants=(
            (lambda N, M: np.zeros(len(N)), "without the prior"),
            (_variant("prior only on the right"), "first only"),
            (_variant("I transposed"), "I_mean transposed"),
            (_variant("I * I coupling"), "You wrote I_mean * I_mean (I_ij^2)"),
            (_variant("I.T * I.T coupling"), "You wrote I_mean.T * I_mean.T (I_ji^2)"),
            (_variant("no N_ij anywhere"), "you weighted every overlap equally"),
            (lambda N, M: _reference(N, M) / _reference(N, M).mean(), "or by their mean"),
            (_variant("sign"), "sign flip"),
            (_variant("no factor 2"), "factor 2"),
            (_variant("no factor 2"), "or the prior gained one"),
            (_variant("data counted twice"), "twice what it should"),
            (_variant("data once, prior twice"), "a quarter"),
            (_variant("prior without N_ij"), "added 1 / sigma_g^2 per overlap"),
            (_variant("data without N_ij"), "one data term per overlap"),
            (_variant("one prior per image"), "one 1 / sigma_g^2 per image"),
            (_variant("pairs once, prior on the first"), "summed each pair once"),
            (lambda N, M: np.diag(np.asarray(M, float)) / 100.0, "do not minimise"),
            (_variant("sigma not squared"), "not sigma_N (10)"),
            (_variant("sigma in 0-1 units"), "grey levels 0-255"),
            (_variant("diagonal kept"), "own size, not an overlap"),
            (
                lambda N, M: _diagonal_overwritten(N, np.asarray(M, float)),
                "kept it in your sums",
            ),
            (
                lambda N, M: _diagonal_overwritten(N, np.asarray(M, float), in_b=False),
                "kept it in your sums",
            ),
            (_variant("sigma_g = 0.1"), "Brown & Lowe's value"),
            (_variant("sigmas swapped"), "swapped the two sigmas"),
            (_variant("sigma_N = 1"), "you took sigma_N = 1"),
            (_variant("means in 0-1"), "divided the means by 255"),
            (lambda N, M: _reference(N, np.asarray(M, float) / 1000), "means divided by 1000"),
            (lambda N, M: _reference(N, 3 * np.asarray(M, float)), "means multiplied by 3"),
            (_variant("N_ii in b"), "kept it in b_i"),
            (_pairs_once, "j < i included"),
            (lambda N, M: 1 / _reference(N, M), "you returned 1/g"),
            (
                lambda N, M: _reference(N, M) / _reference(N, M)[0],
                "divided them by one image's gain",
            ),
        ),
    )
)
