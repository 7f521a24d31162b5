"""Judge a calibration: coverage, outlier views, tilts, uncertainties, in plain-language advice."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .._validate import ConvergenceError
from ..distortion import pixels_to_normalised, undistort_points
from .calibrate import CalibrationResult
from .refinement import PARAM_NAMES, project_views


class UncertaintyMap(NamedTuple):
    """:func:`projection_uncertainty` on a grid of pixels.

    Attributes
    ----------
    us : (W',) ndarray
        The grid's columns, pixels.
    vs : (H',) ndarray
        The grid's rows, pixels.
    sigma : (H', W') ndarray
        The projection's 1-sigma uncertainty at each grid pixel, pixels.
    """

    us: np.ndarray
    vs: np.ndarray
    sigma: np.ndarray


def projection_uncertainty(result: CalibrationResult, step: int = 20) -> UncertaintyMap:
    r"""How uncertain the calibrated projection is across the image (pixels, 1 sigma).

    For a grid of pixels, take the ray the calibrated camera assigns to each, and ask how
    far its projection would move if the intrinsics and distortion varied within their
    covariance :math:`\Sigma`: with :math:`J_g` = d pixel / d (free global parameters) at that
    ray (the same analytic Jacobian as the refinement), the pixel covariance is
    :math:`J_g \Sigma J_g^\top`; we report the square root of its largest eigenvalue.

    Parameters
    ----------
    result : CalibrationResult
        The calibration (its K, distortion, free parameters and covariance are used).
    step : int
        Grid spacing, pixels; the grid starts half a step in from the image's top-left.

    Returns
    -------
    UncertaintyMap
        ``(us, vs, sigma)``: ``us`` (W',), ``vs`` (H',) grid coordinates and ``sigma`` (H', W').
    """
    w, h = result.image_size
    us = np.arange(step / 2, w, step, dtype=float)
    vs = np.arange(step / 2, h, step, dtype=float)
    U, Vv = np.meshgrid(us, vs)
    pix = np.column_stack([U.ravel(), Vv.ravel()])
    K = result.K
    xd = pixels_to_normalised(pix, K)
    try:
        x = undistort_points(xd, result.dist)
    except ConvergenceError:
        x = xd
    Xc = np.column_stack([x, np.ones(len(x))])
    g = np.array([K[0, 0], K[1, 1], K[0, 2], K[1, 2], K[0, 1], *result.dist])
    _, Jg, _ = project_views(g, np.zeros((1, 6)), Xc[None], jac=True)
    free = np.array([n in result.free_params for n in PARAM_NAMES])
    J = Jg[0][..., free]  # (N, 2, n_free)
    C = J @ result.covariance @ J.transpose(0, 2, 1)
    sigma = np.sqrt(np.maximum(np.linalg.eigvalsh(C)[:, -1], 0.0))
    return UncertaintyMap(us, vs, sigma.reshape(U.shape))


class CoachReport(NamedTuple):
    """The quality coach's verdict on a calibration (see :func:`coach`).

    ``coverage`` (rows, cols) fraction of grid cells of the image with at least one corner
    (``coverage_grid`` holds the counts); ``worst_views`` view indices, worst first, with
    ``error_ratio`` each view's rms over the median; ``relative_std`` {param: std / |value|}
    for fx, fy and std in pixels for cx, cy; ``tilt_degrees`` each view's angle between the
    board normal and the optical axis; ``uncertainty`` max projection sigma over the image (px);
    ``advice`` plain-language sentences, most important first.
    """

    coverage: float
    coverage_grid: np.ndarray
    worst_views: list
    error_ratio: np.ndarray
    relative_std: dict
    tilt_degrees: np.ndarray
    uncertainty: float
    advice: list

    def text(self) -> str:
        """The advice as a bulleted list, one ``- `` line per sentence.

        Returns
        -------
        str
            The lines of ``advice``, most important first.
        """
        return "\n".join(f"- {a}" for a in self.advice)


def _coverage_advice(covered: np.ndarray) -> list[str]:
    """Advice on the image's edges and corners that no (or few) detected corners reached.

    Where distortion is strongest, so where the calibration needs data.
    """
    advice = []
    regions = {
        "left edge": covered[:, 0],
        "right edge": covered[:, -1],
        "top edge": covered[0, :],
        "bottom edge": covered[-1, :],
    }
    for name, cells in regions.items():
        if not cells.any():
            advice.append(f"no corners near the {name}: add views with the board there")
        elif cells.mean() < 0.5:
            advice.append(f"few corners near the {name}: add views with the board there")
    for name, cell in {
        "top-left": covered[0, 0],
        "top-right": covered[0, -1],
        "bottom-left": covered[-1, 0],
        "bottom-right": covered[-1, -1],
    }.items():
        if not cell:
            advice.append(
                f"no corners in the {name} corner of the image, where distortion is strongest: "
                f"add a view with the board there"
            )
    return advice


def coach(result: CalibrationResult, grid: tuple[int, int] = (4, 6)) -> CoachReport:
    """Judge a calibration and give plain-language advice.

    Checks: corner coverage of the image (edges and corners are where distortion is
    largest, so they must be sampled), views whose rms is >= 2x the median (bad detection
    or blur), the spread of board tilts (Zhang needs tilted views; tilts under about 10
    degrees add little), parameter uncertainties, the overall rms, the number of views, and
    whether the optimiser converged.

    Parameters
    ----------
    result : CalibrationResult
        The calibration to judge.
    grid : (rows, cols)
        Cells for the coverage check.

    Returns
    -------
    CoachReport
        ``coverage`` (fraction of grid cells with a corner) and ``coverage_grid`` (the
        counts), ``worst_views`` and ``error_ratio``, ``relative_std``, ``tilt_degrees``,
        ``uncertainty`` (the largest projection sigma, pixels) and ``advice`` (sentences,
        most important first).
    """
    w, h = result.image_size
    rows, cols = grid
    pts = np.concatenate(result.image_points)
    ci = np.clip((pts[:, 0] / w * cols).astype(int), 0, cols - 1)
    ri = np.clip((pts[:, 1] / h * rows).astype(int), 0, rows - 1)
    counts = np.zeros((rows, cols), int)
    np.add.at(counts, (ri, ci), 1)
    covered = counts > 0
    coverage = float(covered.mean())
    med = float(np.median(result.per_view_rms))
    ratio = result.per_view_rms / max(med, 1e-12)
    worst = [int(i) for i in np.argsort(-result.per_view_rms)]
    normals = result.R[:, :, 2]
    tilt = np.degrees(np.arccos(np.clip(np.abs(normals[:, 2]), 0, 1)))
    p = result.intrinsics
    rel = {
        "fx": result.std["fx"] / abs(p["fx"]),
        "fy": result.std["fy"] / abs(p["fy"]),
        "cx": result.std["cx"],
        "cy": result.std["cy"],
    }
    _, _, sig = projection_uncertainty(result, step=max(8, min(w, h) // 12))
    advice = []
    if not result.converged:
        advice.append(
            "the optimiser did not converge: the result may be poor; add views or check the detections"
        )
    for v in worst:
        if ratio[v] >= 2.0 and result.per_view_rms[v] > 0.1:
            advice.append(
                f"view {v} has {ratio[v]:.1f}x the median error ({result.per_view_rms[v]:.2f} px vs "
                f"{med:.2f} px): check its focus and detection, or drop it"
            )
    advice += _coverage_advice(covered)
    if np.ptp(tilt) < 10 or tilt.max() < 15:
        advice.append(
            f"the board tilts are all similar ({tilt.min():.0f}-{tilt.max():.0f} degrees): tilt it "
            f"by 20-45 degrees towards different sides for a better focal length"
        )
    if result.n_views < 10:
        advice.append(f"only {result.n_views} views: 10-20 give a more stable result")
    if rel["fx"] > 0.01 or rel["fy"] > 0.01:
        advice.append(
            f"the focal length is uncertain (±{100 * max(rel['fx'], rel['fy']):.1f}%): add tilted views"
        )
    if max(rel["cx"], rel["cy"]) > 5:
        advice.append(
            f"the principal point is uncertain (±{max(rel['cx'], rel['cy']):.1f} px): add views "
            f"tilted in different directions and near the image corners"
        )
    if result.rms > 1.0:
        advice.append(
            f"the rms error is high ({result.rms:.2f} px): check for motion blur, a non-flat board, "
            f"or the wrong pattern size"
        )
    if not advice:
        advice.append(
            f"looks good: rms {result.rms:.2f} px, coverage {100 * coverage:.0f}% of the image, "
            f"projection uncertainty below {sig.max():.2f} px everywhere"
        )
    return CoachReport(coverage, counts, worst, ratio, rel, tilt, float(sig.max()), advice)
