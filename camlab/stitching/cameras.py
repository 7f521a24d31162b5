r"""The rotation model of a panorama: focal lengths, rotations, bundle adjustment, wave correction.

A camera that turns about its centre maps image i to image j by

.. math:: x_j \sim K_j R_j R_i^\top K_i^{-1} x_i, \qquad
          K_k = \begin{pmatrix} f_k & 0 & c_x \\ 0 & f_k & c_y \\ 0 & 0 & 1 \end{pmatrix},

with :math:`R_k` cam_from_world (docs/conventions.md) and the principal point at the image
centre. Pairwise registration (:func:`camlab.stitching.match_graph`) gives one homography
per overlapping pair; this module turns them into one camera per image, as Brown & Lowe
[1]_ and Szeliski [2]_ do:

1. :func:`focal_from_homography`: a rotation-only homography constrains f (derivation
   there); :func:`estimate_focal` takes the median over all accepted pairs.
2. :func:`initial_rotations`: rotations along the maximum spanning tree of the match graph,
   :math:`R_{r \leftarrow k} = \mathrm{nearest\ rotation}(K^{-1} H_{r \leftarrow k} K)`.
3. :func:`bundle_adjust`: every focal and rotation refined together over all inlier
   matches of all pairs (Huber loss, :func:`camlab.optimise.levenberg_marquardt`): errors no
   longer accumulate along a chain, and a loop of photos closes.
4. :func:`wave_correct`: turn the world so the cameras' x axes lie in one horizontal plane
   (the horizon is straight instead of a wave).

:func:`estimate_cameras` runs the four steps; :func:`adjust_homographies` refines the
homographies of a flat scene instead (:mod:`camlab.stitching.model` chooses between them).

References
----------
.. [1] M. Brown and D. G. Lowe, 2007, "Automatic panoramic image stitching using invariant
   features", *International Journal of Computer Vision* 74(1), 59-73, sections 4 (bundle
   adjustment) and 5 (automatic panorama straightening).
.. [2] R. Szeliski, 2006, "Image alignment and stitching: a tutorial", *Foundations and
   Trends in Computer Graphics and Vision* 2(1), 1-104, sections 5-6.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import DegenerateError, check_matrix
from ..camera import centred_intrinsics, nearest_rotation, rotation_from_axis_angle
from ..optimise import huber_jacobian, huber_residuals, levenberg_marquardt
from .bundle_jacobian import (
    homography_transfer_jacobians,
    left_jacobian,
    transfer_error_jacobians,
)

__all__ = [
    "BundleResult",
    "CameraEstimate",
    "Focals",
    "HomographyAdjustment",
    "adjust_homographies",
    "bundle_adjust",
    "estimate_cameras",
    "estimate_focal",
    "focal_from_homography",
    "initial_rotations",
    "inlier_matches",
    "intrinsics",
    "pair_transfer_errors",
    "wave_correct",
]


def intrinsics(f: float, shape: Sequence[int]) -> np.ndarray:
    """K with focal ``f`` (pixels), square pixels and the principal point at the centre of an image of ``shape``.

    The centre of an (h, w) image is ((w - 1)/2, (h - 1)/2) with the pixel-centre convention.

    Parameters
    ----------
    f : float
        Focal length, pixels.
    shape : (h, w) or (h, w, C)
        The image's shape (only h and w are used).

    Returns
    -------
    (3, 3) ndarray
        :math:`[[f, 0, (w-1)/2], [0, f, (h-1)/2], [0, 0, 1]]`.
    """
    h, w = shape[:2]
    return centred_intrinsics(f, (w, h))


class Focals(NamedTuple):
    """The focal lengths :func:`focal_from_homography` finds, pixels (NaN where undetermined).

    Attributes
    ----------
    f_src : float
        The source image's focal length.
    f_dst : float
        The destination image's focal length.
    """

    f_src: float
    f_dst: float


def focal_from_homography(
    H: ArrayLike, shape_src: Sequence[int], shape_dst: Sequence[int]
) -> Focals:
    r"""Focal lengths (f_src, f_dst) implied by a rotation-only homography; NaN where undetermined.

    Move both principal points to the origin, :math:`\hat H = C_d^{-1} H C_s`. Then
    :math:`\hat H \sim \mathrm{diag}(f_d, f_d, 1)\, R\, \mathrm{diag}(1/f_s, 1/f_s, 1)`, so

    .. math:: R \sim \begin{pmatrix} h_0 & h_1 & h_2/f_s \\ h_3 & h_4 & h_5/f_s \\
              h_6 f_d & h_7 f_d & h_8 f_d/f_s \end{pmatrix}
              \quad (\text{scaled by } f_d/f_s),

    and R's columns 1 and 2 are orthogonal and of equal length:

    .. math:: f_d^2 = -\frac{h_0 h_1 + h_3 h_4}{h_6 h_7}
              \quad\text{or}\quad f_d^2 = \frac{h_0^2 + h_3^2 - h_1^2 - h_4^2}{h_7^2 - h_6^2};

    R's rows 1 and 2 likewise give

    .. math:: f_s^2 = -\frac{h_2 h_5}{h_0 h_3 + h_1 h_4}
              \quad\text{or}\quad f_s^2 = \frac{h_5^2 - h_2^2}{h_0^2 + h_1^2 - h_3^2 - h_4^2}.

    Of each pair of formulas the one with the larger denominator is used (the other can be
    0/0: a pure pan has :math:`h_7 = 0`); a negative value means this pair does not
    constrain that focal (NaN). The method of Szeliski & Shum [1]_, as OpenCV's
    ``detail::focalsFromHomography`` has it.

    *Units.* In pixels the entries of :math:`\hat H` differ by :math:`f^2` (:math:`h_2 \sim f`,
    :math:`h_6 \sim 1/f`), so a test "denominator near 0" on them would depend on f: at
    f = 1000 px a genuine :math:`h_6 h_7` of the Frobenius-normalised :math:`\hat H` is
    under :math:`10^{-12}`. The formulas are therefore evaluated on
    :math:`\hat H` in units of a nominal focal length, each image's diagonal
    :math:`s` (:math:`\hat H = K_{0,d}^{-1} H K_{0,s}` with :math:`K_0` = ``intrinsics(s, shape)``),
    which gives :math:`(f/s)^2`; for any plausible lens (f within 0.1 to 10 diagonals) its
    entries are of one size. On that normalised matrix a chosen denominator under
    :math:`10^{-12}` is round-off, not perspective: the pair is affine to working precision
    (:math:`f \to \infty`), undetermined (NaN).

    Parameters
    ----------
    H : (3, 3) array_like
        Maps the source image's pixels to the destination image's.
    shape_src, shape_dst : (h, w)
        Image shapes (their centres are taken as principal points).

    Returns
    -------
    Focals
        ``f_src``, ``f_dst``, pixels; NaN where this homography does not determine one.

    Raises
    ------
    CamlabInputError
        ``H`` not a finite (3, 3) matrix.

    References
    ----------
    .. [1] R. Szeliski and H.-Y. Shum, 1997, "Creating full view panoramic image mosaics and
       environment maps", *Proc. SIGGRAPH 97*, 251-258.
    .. [2] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022,
       section 8.2 (image stitching: rotational panoramas).

    Examples
    --------
    >>> from camlab.homography import rotation_homography
    >>> from camlab.camera import rotation_from_axis_angle
    >>> K = intrinsics(700.0, (480, 640))
    >>> H = rotation_homography(K, rotation_from_axis_angle([0.05, 0.3, 0.02]))
    >>> [round(f, 6) for f in focal_from_homography(H, (480, 640), (480, 640))]
    [700.0, 700.0]
    """
    Hm = check_matrix(H, (3, 3), "H")
    s_src, s_dst = (float(np.hypot(*shape[:2])) for shape in (shape_src, shape_dst))
    h = (np.linalg.inv(intrinsics(s_dst, shape_dst)) @ Hm @ intrinsics(s_src, shape_src)).ravel()
    h = h / np.linalg.norm(h)

    def pick(n1, d1, n2, d2):
        n, d = (n1, d1) if abs(d1) > abs(d2) else (n2, d2)
        v = n / d if abs(d) > 1e-12 else float("nan")
        return float(np.sqrt(v)) if np.isfinite(v) and v > 0 else float("nan")

    f_dst = s_dst * pick(
        -(h[0] * h[1] + h[3] * h[4]),
        h[6] * h[7],
        h[0] ** 2 + h[3] ** 2 - h[1] ** 2 - h[4] ** 2,
        h[7] ** 2 - h[6] ** 2,
    )
    f_src = s_src * pick(
        -h[2] * h[5],
        h[0] * h[3] + h[1] * h[4],
        h[5] ** 2 - h[2] ** 2,
        h[0] ** 2 + h[1] ** 2 - h[3] ** 2 - h[4] ** 2,
    )
    return Focals(f_src, f_dst)


def estimate_focal(homographies: dict, shapes: Sequence[Sequence[int]]) -> float:
    """The median of every focal that the pairwise homographies determine (one f for all images).

    Falls back to the image diagonal (a 53-degree diagonal field of view, a typical phone)
    when no pair constrains f (every pair a pure translation or a near-identity), as OpenCV
    does.

    Parameters
    ----------
    homographies : dict
        (i, j) -> the (3, 3) H from image i to image j, for the accepted pairs.
    shapes : sequence of (h, w)
        Every image's shape, pixels (their centres are the principal points).

    Returns
    -------
    float
        The focal length, pixels: the median of the finite per-pair focals, or the mean
        image diagonal.
    """
    fs = []
    for (i, j), H in homographies.items():
        fs.extend(f for f in focal_from_homography(H, shapes[i], shapes[j]) if np.isfinite(f))
    if fs:
        return float(np.median(fs))
    return float(np.mean([np.hypot(*s[:2]) for s in shapes]))


def _nearest_rotation(M: np.ndarray) -> np.ndarray:
    """The rotation closest to M / cbrt(det M) (a homography's scale and sign removed)."""
    d = np.linalg.det(M)
    if not np.isfinite(d) or abs(d) < 1e-300:
        raise DegenerateError(
            "initial_rotations: a homography is singular; it cannot come from a rotation"
        )
    return nearest_rotation(M / np.cbrt(d))


def initial_rotations(
    ref_from_k: Sequence[np.ndarray | None], Ks: Sequence[np.ndarray | None]
) -> list:
    r"""cam_from_world rotations from the spanning tree's chained homographies (world = reference camera).

    :math:`H_{r \leftarrow k} \sim K_r R_r R_k^\top K_k^{-1}` with :math:`R_r = I`, so
    :math:`R_k = (K_r^{-1} H_{r \leftarrow k} K_k)^\top`, made an exact rotation by the SVD
    (after dividing by the cube root of the determinant). None stays None (an image not in
    the panorama).

    Parameters
    ----------
    ref_from_k : sequence of (3, 3) ndarray or None
        Each image's homography onto the reference image (the reference's is the identity).
    Ks : sequence of (3, 3) ndarray or None
        Each image's intrinsics.

    Returns
    -------
    list of (3, 3) ndarray or None
        One rotation per image, the reference's the identity.

    Raises
    ------
    DegenerateError
        A singular homography.
    """
    ref = next(k for k, H in enumerate(ref_from_k) if H is not None and np.allclose(H, np.eye(3)))
    Kr_inv = np.linalg.inv(Ks[ref])
    return [
        None if H is None else _nearest_rotation(Kr_inv @ np.asarray(H, float) @ Ks[k]).T
        for k, H in enumerate(ref_from_k)
    ]


class BundleResult(NamedTuple):
    """The outcome of :func:`bundle_adjust`.

    ``Ks``, ``Rs``: refined intrinsics and cam_from_world rotations (None for images left
    out); ``rms_before``/``rms_after``: RMS reprojection error of all matches, pixels;
    ``cost_history``: Huber cost per LM iteration; ``iterations``; ``message``; ``seconds``: the
    adjustment's wall time.
    """

    Ks: list
    Rs: list
    rms_before: float
    rms_after: float
    cost_history: np.ndarray
    iterations: int
    message: str
    seconds: float


def _project(H: np.ndarray, x: np.ndarray) -> np.ndarray:
    p = x @ H[:, :2].T + H[:, 2]
    return p[:, :2] / p[:, 2:3]


def pair_transfer_errors(K_i, R_i, K_j, R_j, x_i: np.ndarray, x_j: np.ndarray) -> np.ndarray:
    r"""The transfer errors of matches x_i <-> x_j under the rotation model, pixels.

    :math:`\pi(K_j R_j R_i^\top K_i^{-1} x_i) - x_j`.

    Parameters
    ----------
    K_i, K_j : (3, 3) ndarray
        The two images' intrinsics.
    R_i, R_j : (3, 3) ndarray
        Their cam_from_world rotations.
    x_i, x_j : (N, 2) ndarray
        The matches, pixels in images i and j.

    Returns
    -------
    (N, 2) ndarray
        The errors in image j, pixels.
    """
    return _project(K_j @ R_j @ R_i.T @ np.linalg.inv(K_i), x_i) - x_j


def _adjust(
    blocks: dict, build, pair_errors, pairs: list, huber: float, max_iter: int, pair_jacobians=None
):
    """Levenberg-Marquardt over per-image parameter blocks and pairwise match errors.

    ``blocks[k] = (x0_k, steps_k)``: image k's starting parameters and forward-difference
    steps; ``build(k, x_k)`` makes image k's model from them; ``pair_errors(m_i, m_j, a, b)``
    gives the (N, 2) errors of matches a (image i) <-> b (image j). The residuals are every
    pair's errors both ways through the Huber loss. ``pair_jacobians(m_i, m_j, a)``, when
    given, returns the errors' (N, 2, n_i) and (N, 2, n_j) derivatives with respect to the
    two images' parameters, and the Jacobian is assembled from them (two blocks per row);
    otherwise it is by forward differences, one image's block at a time over only the pairs
    that see that image.
    """
    layout, n = {}, 0
    for k, (x0k, _) in blocks.items():
        layout[k] = slice(n, n + len(x0k))
        n += len(x0k)
    x0 = np.concatenate([np.asarray(blocks[k][0], float) for k in blocks]) if n else np.zeros(0)
    steps = np.concatenate([np.asarray(blocks[k][1], float) for k in blocks]) if n else np.zeros(0)
    rows, start = [], 0
    for _, _, a, _ in pairs:
        rows.append(slice(start, start + 4 * len(a)))
        start += 4 * len(a)

    def models(x):
        return {k: build(k, x[layout[k]]) for k in blocks}

    def block(m, i, j, a, b):
        e = np.vstack([pair_errors(m[i], m[j], a, b), pair_errors(m[j], m[i], b, a)])
        return huber_residuals(e, huber).ravel()

    def residuals(x):
        m = models(x)
        return np.concatenate([block(m, i, j, a, b) for i, j, a, b in pairs])

    def jacobian(x):
        m = models(x)
        J = np.zeros((start, n))
        base = [block(m, i, j, a, b) for i, j, a, b in pairs]
        for k, sl in layout.items():
            for p in range(sl.start, sl.stop):
                xk = x[sl].copy()
                xk[p - sl.start] += steps[p]
                mp = dict(m)
                mp[k] = build(k, xk)
                for q, (i, j, a, b) in enumerate(pairs):
                    if k in (i, j):
                        J[rows[q], p] = (block(mp, i, j, a, b) - base[q]) / steps[p]
        return J

    def analytic_jacobian(x):
        m = models(x)
        J = np.zeros((start, n))
        for q, (i, j, a, b) in enumerate(pairs):
            e = np.vstack([pair_errors(m[i], m[j], a, b), pair_errors(m[j], m[i], b, a)])
            forward, backward = pair_jacobians(m[i], m[j], a), pair_jacobians(m[j], m[i], b)
            d_i = np.concatenate([forward[0], backward[1]])  # (2N, 2, n_i): both error sets
            d_j = np.concatenate([forward[1], backward[0]])
            robust = huber_jacobian(e, huber)
            J[rows[q], layout[i]] = (robust @ d_i).reshape(2 * len(e), d_i.shape[2])
            J[rows[q], layout[j]] = (robust @ d_j).reshape(2 * len(e), d_j.shape[2])
        return J

    def rms(x):
        m = models(x)
        e = np.vstack([pair_errors(m[i], m[j], a, b) for i, j, a, b in pairs])
        return float(np.sqrt(np.mean(np.sum(e**2, axis=1))))

    if n == 0:
        return models(x0), rms(x0), rms(x0), np.zeros(1), 0, "nothing to adjust", 0.0
    t0 = time.perf_counter()
    res = levenberg_marquardt(
        residuals,
        x0,
        analytic_jacobian if pair_jacobians else jacobian,
        max_iter=max_iter,
        ftol=1e-8,
    )
    return (
        models(res.x),
        rms(x0),
        rms(res.x),
        res.cost_history,
        res.iterations,
        res.message,
        time.perf_counter() - t0,
    )


def _pairs(matches: dict, present) -> list:
    pairs = [
        (i, j, np.asarray(a, float), np.asarray(b, float))
        for (i, j), (a, b) in sorted(matches.items())
        if present(i) and present(j) and len(a)
    ]
    if not pairs:
        raise DegenerateError("bundle_adjust: no matches between the images to adjust")
    return pairs


def bundle_adjust(
    Ks: Sequence,
    Rs: Sequence,
    matches: dict,
    *,
    fixed: int | None = None,
    huber: float = 2.0,
    max_iter: int = 30,
    focal: bool = True,
) -> BundleResult:
    r"""Refine every camera's focal and rotation over all matches (bundle adjustment).

    Minimises the symmetric reprojection error of every match of every pair, through a
    Huber loss (:func:`camlab.optimise.huber_residuals`, quadratic up to ``huber`` pixels)
    so a surviving wrong match cannot drag the cameras:

    .. math:: \min_{f_k, R_k} \sum_{(i,j)} \sum_m \rho\big(\|\pi(K_j R_j R_i^\top K_i^{-1} x_i^m) - x_j^m\|\big)
              + \rho\big(\|\pi(K_i R_i R_j^\top K_j^{-1} x_j^m) - x_i^m\|\big).

    Parameters are, per camera, f and a rotation vector :math:`\omega` applied on the left,
    :math:`R_k = \exp([\omega_k]_\times) R_k^{(0)}` (no singularity near the start). Camera
    ``fixed`` keeps its rotation (the world frame is otherwise free: turning every camera
    together changes no error). The Jacobian is analytic, two blocks per match
    (:mod:`camlab.stitching.bundle_jacobian` derives it);
    :func:`camlab.optimise.levenberg_marquardt` does the rest.

    Parameters
    ----------
    Ks, Rs : sequences of (3, 3) ndarray or None
        Initial intrinsics and cam_from_world rotations; None for images left out.
    matches : dict
        (i, j) -> (x_i, x_j), two (M, 2) arrays of inlier matches in images i and j.
    fixed : int, optional
        The camera whose rotation is held (default: the first one present).
    huber : float
        Huber threshold, pixels.
    max_iter : int
        Most Levenberg-Marquardt iterations.
    focal : bool
        Refine the focal lengths (False: keep the given K, e.g. a calibrated camera).

    Returns
    -------
    BundleResult
        ``Ks``, ``Rs`` (refined; None for images left out), ``rms_before`` and ``rms_after``
        (all matches, pixels), ``cost_history``, ``iterations``, ``message`` and ``seconds``.

    Raises
    ------
    DegenerateError
        No matches between the cameras present.

    References
    ----------
    .. [1] M. Brown and D. G. Lowe, 2007, "Automatic panoramic image stitching using invariant
       features", *International Journal of Computer Vision* 74(1), 59-73, section 4 (bundle adjustment).
    .. [2] R. Szeliski, *Computer Vision: Algorithms and Applications*, 2nd ed., 2022,
       section 8.3 (global alignment: bundle adjustment).
    """
    cams = [k for k, R in enumerate(Rs) if R is not None]
    fixed = cams[0] if fixed is None else fixed
    pairs = _pairs(matches, lambda k: Rs[k] is not None)
    blocks = {}
    for k in cams:
        f0 = [Ks[k][0, 0]] if focal else []
        n_rot = 0 if k == fixed else 3
        blocks[k] = (f0 + [0.0] * n_rot, [1e-4 * Ks[k][0, 0]] * len(f0) + [1e-7] * n_rot)

    def build(k, xk):
        K = np.asarray(Ks[k], float).copy()
        if focal:
            K[0, 0] = K[1, 1] = xk[0]
        w = xk[1:] if focal else xk
        if not len(w):
            return K, np.asarray(Rs[k], float), None
        return K, rotation_from_axis_angle(w) @ Rs[k], left_jacobian(w)

    def errors(ci, cj, a, b):
        return pair_transfer_errors(ci[0], ci[1], cj[0], cj[1], a, b)

    def jacobians(ci, cj, a):
        """d errors / d (f, w) of both cameras, only the columns each camera's block has."""
        out = []
        for d, c in zip(
            transfer_error_jacobians(ci[0], ci[1], cj[0], cj[1], a), (ci, cj), strict=True
        ):
            parts = ([d[:, :, :1]] if focal else []) + (
                [d[:, :, 1:] @ c[2]] if c[2] is not None else []
            )
            out.append(np.concatenate(parts, axis=2) if parts else d[:, :, :0])
        return out

    m, before, after, costs, its, msg, secs = _adjust(
        blocks, build, errors, pairs, huber, max_iter, jacobians
    )
    return BundleResult(
        [m[k][0] if k in m else None for k in range(len(Rs))],
        [m[k][1] if k in m else None for k in range(len(Rs))],
        before,
        after,
        costs,
        its,
        msg,
        secs,
    )


class HomographyAdjustment(NamedTuple):
    """The outcome of :func:`adjust_homographies`.

    ``homographies`` ref_from_k (None for images left out), ``rms_before``/``rms_after`` (pixels),
    ``iterations``, ``message``, ``seconds`` (wall time).
    """

    homographies: list
    rms_before: float
    rms_after: float
    iterations: int
    message: str
    seconds: float


def adjust_homographies(
    ref_from_k: Sequence, matches: dict, *, reference: int, huber: float = 2.0, max_iter: int = 30
) -> HomographyAdjustment:
    r"""Refine every image's homography onto the reference together, over all matches (planar scenes).

    A flat scene seen from several positions has no common centre, so no rotation model;
    each image k keeps its own :math:`H_k = H_{r \leftarrow k}` (8 parameters,
    :math:`h_{33} = 1`; the reference's is I) and all are fitted to every pair's matches:

    .. math:: \min \sum_{(i,j)} \sum_m \rho\big(\|\pi(H_j^{-1} H_i x_i^m) - x_j^m\|\big)
              + \rho\big(\|\pi(H_i^{-1} H_j x_j^m) - x_i^m\|\big),

    the planar counterpart of :func:`bundle_adjust` (same Huber loss, same
    :func:`camlab.optimise.levenberg_marquardt`). The chain along the spanning tree only
    used the tree's pairs; this uses the pairs that close loops too.

    Parameters
    ----------
    ref_from_k : sequence of (3, 3) ndarray or None
        Each image's starting homography onto the reference (None for images left out).
    matches : dict
        (i, j) -> (x_i, x_j), two (M, 2) arrays of inlier matches, pixels.
    reference : int
        The image whose homography stays fixed.
    huber : float
        Huber threshold, pixels.
    max_iter : int
        Most Levenberg-Marquardt iterations.

    Returns
    -------
    HomographyAdjustment
        ``homographies`` (ref_from_k, :math:`h_{33} = 1`; None for images left out),
        ``rms_before``, ``rms_after`` (pixels), ``iterations``, ``message`` and ``seconds``.

    Raises
    ------
    DegenerateError
        No matches between the images present.
    """
    imgs = [k for k, H in enumerate(ref_from_k) if H is not None]
    pairs = _pairs(matches, lambda k: ref_from_k[k] is not None)
    H0 = {k: np.asarray(ref_from_k[k], float) / ref_from_k[k][2, 2] for k in imgs}
    scale = {k: np.abs(H0[k].ravel()[:8]) * 1e-7 + 1e-9 for k in imgs}
    blocks = {
        k: (([] if k == reference else H0[k].ravel()[:8]), ([] if k == reference else scale[k]))
        for k in imgs
    }

    def build(k, xk):
        H = np.append(xk, 1.0).reshape(3, 3) if len(xk) else H0[k]
        return H, np.linalg.inv(H), bool(len(xk))

    def errors(hi, hj, a, b):
        return _project(hj[1] @ hi[0], a) - b

    def jacobians(hi, hj, a):
        """d errors / d H entries of both images; none for the reference, which stays."""
        d = homography_transfer_jacobians(hi[0], hj[0], a)
        return [dk if h[2] else dk[:, :, :0] for dk, h in zip(d, (hi, hj), strict=True)]

    m, before, after, _, its, msg, secs = _adjust(
        blocks, build, errors, pairs, huber, max_iter, jacobians
    )
    return HomographyAdjustment(
        [m[k][0] if k in m else None for k in range(len(ref_from_k))], before, after, its, msg, secs
    )


def wave_correct(Rs: Sequence[np.ndarray | None]) -> list:
    r"""Turn the world so the panorama's horizon is straight (wave correction).

    People turn the camera about a vertical axis, so every camera's x axis (its row
    :math:`r_{k,0}` of the cam_from_world R) is nearly horizontal: the world's vertical
    :math:`u` minimises :math:`\sum_k (r_{k,0}^\top u)^2`, the eigenvector of
    :math:`\sum_k r_{k,0} r_{k,0}^\top` with the smallest eigenvalue (signed to point like
    the cameras' y axes, down). The new world z is the mean viewing direction made
    orthogonal to u, x completes the right-handed frame, and every
    :math:`R_k \leftarrow R_k W^\top` with :math:`W` = (x; u; z) stacked as rows. If the x
    axes hardly spread (second eigenvalue below 1% of the largest: a turn of less than
    about 10 degrees) the smallest eigenvector is noise, and the mean y axis is u.

    Parameters
    ----------
    Rs : sequence of (3, 3) ndarray or None
        cam_from_world rotations (None for images left out).

    Returns
    -------
    list of (3, 3) ndarray or None
        The turned rotations, None where given None; unchanged with fewer than two cameras.

    References
    ----------
    .. [1] M. Brown and D. G. Lowe, 2007, "Automatic panoramic image stitching using invariant
       features", *International Journal of Computer Vision* 74(1), 59-73, section 5 (automatic panorama straightening).
    """
    cams = [np.asarray(R, float) for R in Rs if R is not None]
    if len(cams) < 2:
        return [None if R is None else np.asarray(R, float) for R in Rs]
    X = np.array([R[0] for R in cams])
    Y = np.array([R[1] for R in cams])
    Z = np.array([R[2] for R in cams])
    w, V = np.linalg.eigh(X.T @ X)
    u = V[:, 0] if w[1] > 1e-2 * w[2] else Y.mean(axis=0)
    u = u / np.linalg.norm(u)
    if u @ Y.mean(axis=0) < 0:
        u = -u
    z = Z.sum(axis=0)
    z = z - (z @ u) * u
    if np.linalg.norm(z) < 1e-6 * len(
        cams
    ):  # a full turn: the mean direction vanishes; take the first camera's
        z = Z[0] - (Z[0] @ u) * u
    z = z / np.linalg.norm(z)
    W = np.array([np.cross(u, z), u, z])
    return [None if R is None else np.asarray(R, float) @ W.T for R in Rs]


class CameraEstimate(NamedTuple):
    r"""One camera per image from :func:`estimate_cameras`.

    Attributes
    ----------
    Ks, Rs : lists of (3, 3) ndarray or None
        Intrinsics and cam_from_world rotations after bundle adjustment and wave correction
        (None for images left out), so :math:`x_j \sim K_j R_j R_i^\top K_i^{-1} x_i`.
    focal_init : float
        The median focal from the pairwise homographies.
    Rs_init : list
        The spanning-tree rotations (before bundle adjustment).
    bundle : BundleResult
    """

    Ks: list
    Rs: list
    focal_init: float
    Rs_init: list
    bundle: BundleResult


def inlier_matches(graph, max_matches: int = 200) -> dict:
    """The inlier matches of every accepted pair, at most ``max_matches`` each.

    Parameters
    ----------
    graph : MatchGraph
        The pairwise registrations (:func:`match_graph`).
    max_matches : int
        Keep the first this many inliers of each pair (in the matches' order: the most
        distinctive first).

    Returns
    -------
    dict
        (i, j) -> (x_i, x_j), two (M, 2) arrays of pixels.
    """
    out = {}
    for (i, j), p in graph.pairs.items():
        if p.accepted:
            idx = np.flatnonzero(p.inliers)[:max_matches]
            out[(i, j)] = (p.matches.src[idx], p.matches.dst[idx])
    return out


def estimate_cameras(
    graph,
    shapes: Sequence[Sequence[int]],
    *,
    K: ArrayLike | None = None,
    huber: float = 2.0,
    max_matches: int = 200,
    wave: bool = True,
) -> CameraEstimate:
    """Focal, spanning-tree rotations, bundle adjustment, wave correction (the module docstring's steps).

    Parameters
    ----------
    graph : camlab.stitching.MatchGraph
        Pairwise registrations and the spanning tree (homographies ref_from_k).
    shapes : sequence of (h, w)
        Image shapes at the resolution the features were found.
    K : (3, 3) array_like, optional
        Known intrinsics of every image: then the focal is neither estimated nor adjusted.
    huber : float
        Huber threshold of the bundle adjustment, pixels.
    max_matches : int
        Use at most this many inliers per pair (the most distinctive) in the adjustment.
    wave : bool
        Apply :func:`wave_correct`.

    Returns
    -------
    CameraEstimate
        ``Ks``, ``Rs`` (after bundle adjustment and wave correction; None for images left
        out), ``focal_init``, ``Rs_init`` and the :class:`BundleResult` ``bundle``.

    Raises
    ------
    DegenerateError
        A singular homography in the tree, or no matches to adjust.
    """
    accepted = {key: p.H for key, p in graph.pairs.items() if p.accepted}
    if K is None:
        f0 = estimate_focal(accepted, shapes)
        Ks = [
            intrinsics(f0, s) if H is not None else None
            for H, s in zip(graph.homographies, shapes, strict=True)
        ]
    else:
        f0 = float(np.asarray(K, float)[0, 0])
        Ks = [np.asarray(K, float) if H is not None else None for H in graph.homographies]
    R_init = initial_rotations(graph.homographies, Ks)
    matches = {
        key: m
        for key, m in inlier_matches(graph, max_matches).items()
        if R_init[key[0]] is not None and R_init[key[1]] is not None
    }
    ba = bundle_adjust(Ks, R_init, matches, fixed=graph.reference, huber=huber, focal=K is None)
    Rs = wave_correct(ba.Rs) if wave else ba.Rs
    return CameraEstimate(ba.Ks, Rs, f0, R_init, ba)
