r"""One robust estimation driver for models of point pairs: RANSAC with an MSAC score and local optimisation.

Homographies (:func:`camlab.homography.ransac_homography`) and fundamental matrices
(:func:`camlab.epipolar.ransac_fundamental_matrix`) plug into :func:`ransac` by describing
their model as a :class:`PairModel`: how to solve a minimal sample, how to fit many pairs
by least squares, and the residual of a pair in pixels. The driver does the rest.

The algorithm, step by step (each step is a few lines of :func:`ransac`):

1. **Hypothesise.** Draw random minimal samples of ``s`` pairs (4 for H, 8 for F) and
   solve each exactly; degenerate samples (collinear points, rank deficiency) are skipped.
   Samples are drawn and solved in vectorised batches.
2. **Score by truncated squares (optionally with the cut marginalised).** Plain RANSAC counts
   inliers, so every model with the same count ties, however well it fits. MSAC (Torr &
   Zisserman 2000) scores a model by the truncated quadratic loss
   :math:`\sum_i \min(e_i^2, \tau^2)` (:func:`msac_cost`), the negative log-likelihood of
   Gaussian inliers plus uniform outliers with the cut :math:`\tau` at the threshold:
   inliers contribute their squared error, outliers a constant. Lower is better. But the
   noise, and so the right cut, is not known exactly; with a fixed cut a pair just inside
   it costs as much as an outlier, so MSAC can prefer a tight fit to fewer pairs over a
   model that explains more (on a real building pair, 79 pairs at 0.86 px RMS over 94 at
   1.46 px). MAGSAC (Barath, Matas & Noskova 2019) marginalises the noise scale instead;
   its simplest form, the score :func:`ransac` uses with ``loss="marginal"``
   (:func:`marginal_msac_cost`), averages the MSAC loss over cuts :math:`\tau` uniform on
   :math:`(0, T]` with :math:`T = 2t`, whose mean is the threshold :math:`t`:

   .. math:: \rho(e) = \frac{1}{T}\int_0^T \min(e^2, \tau^2)\,d\tau
      = e^2 - \frac{2 e^3}{3 T} \ (e < T), \qquad \frac{T^2}{3} \ (e \ge T),

   since for :math:`e < T` the cuts below :math:`e` give :math:`\tau^2` (integral
   :math:`e^3 / 3`) and those above give :math:`e^2` (integral :math:`e^2 (T - e)`). A pair
   at the threshold now costs half an outlier, not a whole one, and a pair at :math:`t/2`
   0.16 of one (MSAC: 0.25). The default, ``loss="msac"``, is MSAC at :math:`t`, the score
   lesson 07 teaches; ``benchmarks/robust_ransac.py`` compares the two on hard real pairs.
3. **Optimise locally (LO-RANSAC).** A model from a minimal sample is fitted to the noise
   of only ``s`` points, so it is worse than the consensus it found. Each time a
   hypothesis beats the best so far, :func:`local_optimisation` re-fits it on its inliers
   inside the loop (Chum, Matas & Kittler 2003; the "LO+" variant of Lebeda, Matas &
   Chum 2012): a few least-squares fits on random subsets of the inliers, each followed
   by iterated least squares with a threshold shrinking from :math:`3t` to :math:`t`.
   The result is close to the best model the data support, so different seeds agree.
   The final model gets one more local optimisation, on fresh random subsets: more of
   them when the pairs are few (cheap then), since a short search may have settled in
   a poorer basin.
4. **Stop adaptively.** With inlier ratio :math:`w` of the best model so far, one sample
   is all inliers with probability :math:`w^s`, so :math:`k` samples contain one with
   probability :math:`1 - (1 - w^s)^k`. Setting this to the ``confidence`` p gives
   :func:`required_iterations`, :math:`k = \log(1 - p) / \log(1 - w^s)`. Local
   optimisation raises :math:`w` early, which shortens the loop.
5. **Refuse chance.** A consensus must be more than a coincidence. The driver measures
   how often a pair fits the final model by chance (its inlier rate on pairs shuffled so
   that they cannot correspond) and raises :class:`DegenerateError` if the number of
   inliers beyond the minimal sample is not significant: if any of the hypotheses tried
   could plausibly have reached it with random pairs (binomial tail times the number of
   samples drawn above 1 %). Matches that are all wrong give no model.

References
----------
Fischler & Bolles (1981), Random sample consensus. Torr & Zisserman (2000), MLESAC.
Chum, Matas & Kittler (2003), Locally optimized RANSAC. Lebeda, Matas & Chum (2012),
Fixing the locally optimized RANSAC. Barath et al. (2020), MAGSAC++. Hartley & Zisserman,
section 4.7.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ._validate import CamlabInputError, DegenerateError, check_positive

__all__ = [
    "LocalOptimum",
    "MinimalModels",
    "PairModel",
    "RobustFit",
    "local_optimisation",
    "marginal_msac_cost",
    "msac_cost",
    "ransac",
    "required_iterations",
]

_PREVIEW = 100  # with more pairs than 4x this, hypotheses are first scored on this many
_LO_INNER = 2  # least-squares fits on random inlier subsets per local optimisation
_LO_STEPS = 3  # iterated least squares: thresholds from _LO_FACTOR * t down to t
_LO_FACTOR = 3.0
# One more local optimisation of the final model, on more random inlier subsets when the pairs
# are few: each subset's refits are scored on all n pairs, so _LO_FINAL_PAIRS // n subsets cost
# about the same at any n. With few pairs the search stops after some 25 samples, and its one
# basin may be a poorer one: on the hard real pairs (56-232 matches, benchmarks/robust_ransac.py)
# 12-30 subsets took the worst of 10 seeds on building 1 -> 3 (600 keypoints) from an MSAC cost of
# 522 to the other seeds' 452; on 1000 pairs (3 subsets) the speed ratio stayed within its noise.
_LO_FINAL_INNER = 2
_LO_FINAL_MAX_INNER = 30
_LO_FINAL_PAIRS = 3000
_LO_FINAL_STEPS = 3
_ALPHA = 0.01  # significance level of the chance test (step 5)


class MinimalModels(NamedTuple):
    """The hypotheses :meth:`PairModel.minimal` solves from a batch of B minimal samples.

    Attributes
    ----------
    models : (B, ...) ndarray
        One model per sample (e.g. (B, 3, 3) homographies).
    usable : (B,) bool ndarray
        False where a sample is degenerate and its model means nothing.
    """

    models: np.ndarray
    usable: np.ndarray


class LocalOptimum(NamedTuple):
    """What :func:`local_optimisation` kept.

    Attributes
    ----------
    model : ndarray
        The best model found (``start`` if nothing beat it).
    cost : float
        Its cost under the ``loss`` it was optimised for (:func:`msac_cost` by default).
    """

    model: np.ndarray
    cost: float


class PairModel:
    """A model of point pairs ``(x1[i], x2[i])`` that :func:`ransac` can fit robustly.

    Subclasses set :attr:`sample_size` and :attr:`name` and implement :meth:`minimal`,
    :meth:`fit` and :meth:`residuals`; this base class stores the pairs.

    Parameters
    ----------
    x1, x2 : (N, 2) ndarray
        Validated corresponding pixels (the caller checks them).
    """

    sample_size: int = 0
    name: str = "ransac"

    def __init__(self, x1: np.ndarray, x2: np.ndarray):
        self.x1, self.x2 = x1, x2

    def __len__(self) -> int:
        """The number of matches."""
        return len(self.x1)

    def minimal(self, idx: np.ndarray) -> MinimalModels:
        """Solve (B, sample_size) index samples: (B, ...) models and a (B,) mask of usable ones.

        Parameters
        ----------
        idx : (B, sample_size) int ndarray
            B minimal samples, each a row of pair indices.

        Returns
        -------
        MinimalModels
            ``models`` (B, ...), one per sample, and ``usable`` (B,), False for degenerate samples.
        """
        raise NotImplementedError

    def fit(self, idx: np.ndarray) -> np.ndarray:
        """Least-squares model from the pairs ``idx`` (more than a minimal sample); raises DegenerateError.

        Parameters
        ----------
        idx : (K,) int ndarray
            Indices of the pairs to fit, K > ``sample_size``.

        Returns
        -------
        ndarray
            The least-squares model (e.g. a (3, 3) homography).

        Raises
        ------
        DegenerateError
            When the pairs do not determine a model.
        """
        raise NotImplementedError

    def fit_many(self, masks: np.ndarray) -> MinimalModels:
        """Least-squares models of several pair sets at once (local optimisation's refits).

        This default calls :meth:`fit` once per set; a model whose least squares is one
        eigenvector can solve the whole batch in one call instead (HomographyModel does).

        Parameters
        ----------
        masks : (S, N) bool ndarray
            One row per pair set: which pairs it holds.

        Returns
        -------
        MinimalModels
            ``models`` (S, ...) and ``usable`` (S,), False where :meth:`fit` raised
            DegenerateError (that row of ``models`` means nothing).
        """
        fits, usable = [], np.zeros(len(masks), bool)
        for k, mask in enumerate(masks):
            try:
                fits.append(self.fit(np.flatnonzero(mask)))
                usable[k] = True
            except DegenerateError:
                fits.append(None)
        shape = next((f.shape for f in fits if f is not None), ())
        models = np.stack([np.full(shape, np.nan) if f is None else f for f in fits])
        return MinimalModels(models, usable)

    def residuals(
        self, models: np.ndarray, i1: np.ndarray | None = None, i2: np.ndarray | None = None
    ) -> np.ndarray:
        """(B, M) errors in pixels of the pairs ``(x1[i1], x2[i2])`` (all pairs by default).

        Parameters
        ----------
        models : (B, ...) ndarray
            B models, as :meth:`minimal` returns them.
        i1, i2 : (M,) int ndarray, optional
            Indices into the first and second point sets; None for the model's own pairs.

        Returns
        -------
        (B, M) ndarray
            Error of each pair under each model, pixels; inf where undefined.
        """
        raise NotImplementedError


class RobustFit(NamedTuple):
    """What :func:`ransac` found.

    Attributes
    ----------
    model : ndarray
        The locally optimised model with the lowest cost under ``loss``.
    inliers : (N,) bool ndarray
        Pairs whose residual under ``model`` is below the threshold.
    iterations : int
        Minimal samples drawn.
    residuals : (N,) ndarray
        Each pair's error under ``model``, pixels.
    cost : float
        The cost of ``model`` under the driver's ``loss`` (:func:`msac_cost` by default,
        :func:`marginal_msac_cost` with ``loss="marginal"``).
    sample : (s,) int ndarray
        Indices of the minimal sample whose hypothesis became ``model`` (after local
        optimisation), e.g. to show it in a demo.
    """

    model: np.ndarray
    inliers: np.ndarray
    iterations: int
    residuals: np.ndarray
    cost: float
    sample: np.ndarray | None = None


def msac_cost(residuals: np.ndarray, threshold: float) -> np.ndarray:
    r"""Truncated quadratic cost :math:`\sum_i \min(e_i^2, t^2)` along the last axis (lower is better).

    Parameters
    ----------
    residuals : (..., M) ndarray
        Errors e_i, pixels.
    threshold : float
        Inlier threshold t, pixels.

    Returns
    -------
    ndarray
        The cost, ``residuals``' shape without its last axis.

    References
    ----------
    .. [1] P. H. S. Torr and A. Zisserman, 2000, "MLESAC: a new robust estimator with
       application to estimating image geometry", *Computer Vision and Image Understanding*
       78(1), 138-156.

    Examples
    --------
    >>> float(msac_cost(np.array([0.0, 1.0, 10.0]), 2.0))  # 0 + 1 + 4 (the outlier is capped)
    5.0
    """
    return np.sum(np.minimum(residuals, threshold) ** 2, axis=-1)


def marginal_msac_cost(residuals: np.ndarray, threshold: float) -> np.ndarray:
    r"""The MSAC loss averaged over cuts uniform on (0, 2t]: :math:`\sum_i \rho(e_i)` (lower is better).

    .. math:: \rho(e) = e^2 - \frac{2 e^3}{3 T} \ (e < T), \qquad \frac{T^2}{3} \ (e \ge T),
       \qquad T = 2t,

    the mean of :math:`\min(e^2, \tau^2)` over :math:`\tau` uniform on :math:`(0, T]` (the
    module docstring derives it). It rises like :math:`e^2` near 0 and flattens smoothly to
    the outlier's constant at :math:`2t`: a pair at the threshold costs half an outlier.

    Parameters
    ----------
    residuals : (..., M) ndarray
        Errors e_i, pixels.
    threshold : float
        Inlier threshold t, pixels (the mean of the cuts averaged over).

    Returns
    -------
    ndarray
        The cost, ``residuals``' shape without its last axis.

    References
    ----------
    .. [1] D. Barath, J. Matas and J. Noskova, 2019, "MAGSAC: marginalizing sample
       consensus", *IEEE Conference on Computer Vision and Pattern Recognition*, 10197-10205.

    Examples
    --------
    >>> float(marginal_msac_cost(np.array([0.0, 2.0, 10.0]), 2.0))  # 0 + (4 - 16/12) + 16/3
    8.0
    """
    T = 2.0 * threshold
    e = np.minimum(residuals, T)
    return np.sum(e * e * (1.0 - 2.0 * e / (3.0 * T)), axis=-1)


_LOSSES = {"marginal": marginal_msac_cost, "msac": msac_cost}


def required_iterations(inlier_ratio: float, confidence: float, sample_size: int) -> float:
    r"""Samples k needed to draw one all-inlier sample with probability p: log(1 - p) / log(1 - w^s).

    :math:`k = \log(1 - p) / \log(1 - w^s)`.

    Parameters
    ----------
    inlier_ratio : float
        Inlier ratio w of the data, in [0, 1].
    confidence : float
        Probability p of drawing at least one all-inlier sample, in (0, 1).
    sample_size : int
        Pairs s per minimal sample.

    Returns
    -------
    float
        k (not rounded); inf when w = 0, 1 when w = 1.

    References
    ----------
    .. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, section 4.7.1
       (how many samples?).
    .. [2] M. A. Fischler and R. C. Bolles, 1981, "Random sample consensus: a paradigm for model
       fitting with applications to image analysis and automated cartography",
       *Communications of the ACM* 24(6), 381-395.

    Examples
    --------
    >>> round(required_iterations(0.5, 0.99, 4))  # 50 % inliers, 4-point samples
    71
    """
    w_s = inlier_ratio**sample_size
    if w_s <= 0:
        return np.inf
    if w_s >= 1:
        return 1.0
    return float(np.log(1 - confidence) / np.log(1 - w_s))


def _check_settings(threshold, confidence, max_iters) -> tuple[float, float, int]:
    threshold = check_positive(threshold, "threshold", "pixels")
    try:
        confidence = float(confidence)
    except (TypeError, ValueError):
        confidence = np.nan
    if not 0 < confidence < 1:
        raise CamlabInputError(
            f"confidence: expected a probability strictly between 0 and 1, got {confidence!r}; "
            f"0.995 is usual"
        )
    if isinstance(max_iters, bool) or not isinstance(max_iters, (int, np.integer)) or max_iters < 1:
        raise CamlabInputError(
            f"max_iters: expected a positive integer, got {max_iters!r}; 2000 is usual"
        )
    return threshold, confidence, int(max_iters)


def _check_loss(loss):
    if loss not in _LOSSES:
        raise CamlabInputError(
            f"loss: expected one of {sorted(_LOSSES)}, got {loss!r}; 'msac' (the default) "
            f"or 'marginal'"
        )
    return _LOSSES[loss]


def local_optimisation(
    model: PairModel,
    start: np.ndarray,
    threshold: float,
    rng: np.random.Generator,
    inner: int = _LO_INNER,
    steps: int = _LO_STEPS,
    loss: str = "msac",
) -> LocalOptimum:
    r"""Improve a model by re-fitting it on its inliers (LO+); returns the best model and its cost.

    1. Take the inliers :math:`I` of ``start`` at ``threshold`` t.
    2. Fit by least squares on all of :math:`I` and on ``_LO_INNER`` random subsets of
       :math:`I` (half of it, at most 7 minimal samples' worth: subsets escape a model
       that a few bad inliers pulled askew).
    3. Polish each fit by iterated least squares: re-select the pairs within a threshold
       that shrinks geometrically from :math:`3t` to :math:`t` and re-fit on them (a wider
       threshold first lets the model move towards inliers it did not yet explain).
    4. Return the candidate with the lowest cost under ``loss`` (``start`` if nothing beats it).

    Parameters
    ----------
    model : PairModel
        The model kind and its pairs.
    start : ndarray
        The model to improve (e.g. a (3, 3) homography).
    threshold : float
        Inlier threshold t, pixels.
    rng : numpy.random.Generator
        Draws the inlier subsets.
    inner : int, optional
        Least-squares fits on random inlier subsets.
    steps : int, optional
        Thresholds of the iterated least squares, from 3t down to t.
    loss : {"msac", "marginal"}, optional
        The cost candidates are compared by: :func:`msac_cost` (default) or
        :func:`marginal_msac_cost`.

    Returns
    -------
    LocalOptimum
        ``model``, the best model found (``start`` if nothing beats it), and ``cost``, its cost
        under ``loss``.

    References
    ----------
    .. [1] O. Chum, J. Matas and J. Kittler, 2003, "Locally optimized RANSAC", *DAGM
       Symposium on Pattern Recognition*, 236-243.
    .. [2] K. Lebeda, J. Matas and O. Chum, 2012, "Fixing the locally optimized RANSAC",
       *British Machine Vision Conference*.
    """
    cost_of = _check_loss(loss)
    best, cost, _ = _refit_on_inliers(
        model, start, model.residuals(start[None])[0], threshold, rng, inner, steps, cost_of
    )
    return LocalOptimum(best, cost)


def _refit_on_inliers(
    model: PairModel,
    start: np.ndarray,
    res: np.ndarray,
    threshold: float,
    rng: np.random.Generator,
    inner: int,
    steps: int,
    cost_of=msac_cost,
) -> tuple[np.ndarray, float, np.ndarray]:
    """:func:`local_optimisation`'s steps 1-4, given ``start``'s residuals ``res``; also returns the winner's residuals.

    The driver already holds ``res`` from scoring, and needs the winner's residuals to
    count its inliers: passing them in and out saves two evaluations on all pairs per call.
    """
    s = model.sample_size
    best, best_cost, best_res = start, float(cost_of(res, threshold)), res
    inl = np.flatnonzero(res < threshold)
    if len(inl) <= s:
        return best, best_cost, best_res
    size = min(len(inl) // 2, 7 * s)
    subsets = [inl] + (
        [rng.choice(inl, size, replace=False) for _ in range(inner)] if size > s else []
    )
    masks = np.zeros((len(subsets), len(model)), bool)
    for row, sub in zip(masks, subsets, strict=True):
        row[sub] = True
    # Every subset refitted together: one batched solve per threshold instead of one per subset.
    models, alive = model.fit_many(masks)
    errors = model.residuals(models)
    # thresholds shrinking geometrically from _LO_FACTOR * t to t (np.geomspace, without its overhead)
    for thr in threshold * _LO_FACTOR ** np.linspace(1.0, 0.0, steps):
        with np.errstate(invalid="ignore"):
            sel = errors < thr
        # A model whose selection is the set it was fitted on would refit to itself: it keeps its
        # fit and its errors (most do once the outliers are out: 6.7 -> 5.2 ms on 1000 pairs).
        changed = (sel != masks).any(axis=1)
        moving = np.flatnonzero(alive & changed & (sel.sum(axis=1) > s))
        if len(moving) == 0:
            continue  # a smaller threshold may still drop pairs
        refit, ok = model.fit_many(sel[moving])
        models[moving[ok]], masks[moving[ok]] = refit[ok], sel[moving[ok]]
        errors[moving[ok]] = model.residuals(refit[ok])
        alive[moving[~ok]] = False  # a refit that fails drops its subset
    if alive.any():
        errors = errors[alive]
        costs = cost_of(errors, threshold)
        k = int(np.argmin(costs))
        if costs[k] < best_cost:
            best, best_cost, best_res = models[alive][k], float(costs[k]), errors[k]
    return best, best_cost, best_res


def _chance_significant(
    model: PairModel,
    fit: np.ndarray,
    count: int,
    threshold: float,
    drawn: int,
    rng: np.random.Generator,
) -> tuple[bool, float]:
    """Step 5: is ``count`` inliers more than random pairs reach? Returns (significant, chance rate)."""
    from scipy.special import bdtrc  # binomial upper tail P(X > k)

    n, s = len(model), model.sample_size
    i1 = np.tile(np.arange(n), 3)
    i2 = np.concatenate([rng.permutation(n) for _ in range(3)])
    wrong = i1 != i2  # pairs that cannot correspond
    chance = (
        float(np.mean(model.residuals(fit[None], i1[wrong], i2[wrong])[0] < threshold))
        if wrong.any()
        else 0.0
    )
    extra = count - s
    p_any = drawn * bdtrc(extra - 1, n - s, chance)  # P(X >= extra) per hypothesis
    return bool(p_any < _ALPHA), chance


def ransac(
    model: PairModel,
    threshold: float,
    confidence: float = 0.995,
    max_iters: int = 2000,
    rng: np.random.Generator | int | None = None,
    *,
    batch: int = 64,
    local_optimise: bool = True,
    loss: str = "msac",
) -> RobustFit:
    """Fit ``model`` robustly: sample, score (MSAC), optimise locally, stop adaptively, refuse chance.

    See the module docstring for the derivation of each step.

    Parameters
    ----------
    model : PairModel
        The pairs and how to fit them (e.g. ``camlab.homography.HomographyModel``).
    threshold : float
        Inlier threshold on the model's residual, pixels.
    confidence : float
        Probability in (0, 1) of having drawn at least one all-inlier sample.
    max_iters : int
        Upper bound on minimal samples drawn.
    rng : np.random.Generator, int or None
        Randomness (seed it for reproducible results).
    batch : int
        Samples solved and scored per vectorised step.
    local_optimise : bool
        Step 3 (default on); off gives plain MSAC, to compare.
    loss : {"msac", "marginal"}
        Step 2's score: :func:`msac_cost` (default: what lesson 07 teaches) or
        :func:`marginal_msac_cost` (MSAC averaged over cuts up to 2t: a pair at t costs half
        an outlier; better worst seeds on hard wide-baseline pairs).

    Returns
    -------
    RobustFit

    Raises
    ------
    DegenerateError
        If no sample gives a usable model, or the best consensus is no larger than random
        pairs reach by chance (step 5).
    """
    threshold, confidence, max_iters = _check_settings(threshold, confidence, max_iters)
    batch = int(check_positive(batch, "batch"))
    cost_of = _check_loss(loss)
    rng = np.random.default_rng(rng)
    n, s = len(model), model.sample_size
    best, best_cost, best_count, best_raw, best_sample = None, np.inf, 0, np.inf, None
    best_res = np.full(n, np.inf)
    needed, drawn = float(max_iters), 0
    while drawn < min(needed, max_iters):
        b = int(np.clip(min(needed, max_iters) - drawn, 1, batch if drawn else max(batch // 4, 1)))
        idx = rng.integers(0, n, size=(b, s))
        drawn += b
        srt = np.sort(idx, axis=1)
        idx = idx[np.all(srt[:, 1:] != srt[:, :-1], axis=1)]  # s distinct pairs
        if len(idx) == 0:
            continue
        models, ok = model.minimal(idx)
        models, idx = models[ok], idx[ok]
        if len(models) == 0:
            continue
        if len(models) > 4 and n > 4 * _PREVIEW:
            # Score on a random subset first; fully score only the most promising quarter.
            sub = rng.choice(n, _PREVIEW, replace=False)
            pre = cost_of(model.residuals(models, sub, sub), threshold)
            keep = np.argsort(pre, kind="stable")[: max(2, len(models) // 4)]
            models, idx = models[keep], idx[keep]
        errors = model.residuals(models)
        costs = cost_of(errors, threshold)
        k = int(np.argmin(costs))
        # Compare raw hypotheses with raw ones: a polished model would otherwise shut out
        # every raw hypothesis of a better structure (raw fits are noisier than polished).
        if costs[k] >= best_raw:
            continue
        best_raw = float(costs[k])
        candidate, cost, res = models[k], best_raw, errors[k]
        if local_optimise:
            candidate, cost, res = _refit_on_inliers(
                model, candidate, res, threshold, rng, _LO_INNER, _LO_STEPS, cost_of
            )
        if cost >= best_cost:
            continue
        best, best_cost, best_res, best_sample = candidate, cost, res, idx[k].copy()
        best_count = int(np.sum(best_res < threshold))
        needed = required_iterations(best_count / n, confidence, s)
    if best is not None and local_optimise:
        inner = int(np.clip(_LO_FINAL_PAIRS // n, _LO_FINAL_INNER, _LO_FINAL_MAX_INNER))
        best, best_cost, best_res = _refit_on_inliers(
            model, best, best_res, threshold, rng, inner, _LO_FINAL_STEPS, cost_of
        )
        best_count = int(np.sum(best_res < threshold))
    if best is None:
        raise DegenerateError(
            f"{model.name}: none of the {drawn} random samples gave a usable model; the points "
            f"may be collinear or repeated"
        )
    if best_count <= s:
        raise DegenerateError(
            f"{model.name}: too few inliers: no hypothesis from {drawn} samples was supported by any pair beyond its "
            f"own {s} within {threshold} px; the matches may be all wrong, or the threshold too small"
        )
    significant, chance = _chance_significant(model, best, best_count, threshold, drawn, rng)
    if not significant:
        raise DegenerateError(
            f"{model.name}: too few inliers: the best of {drawn} hypotheses explains {best_count} of {n} pairs within "
            f"{threshold} px, but wrong pairs fit it at a rate of {chance:.2g}, so that many could be chance. The "
            f"matches may be mostly wrong (check the matching), or the threshold too small"
        )
    return RobustFit(best, best_res < threshold, int(drawn), best_res, best_cost, best_sample)
