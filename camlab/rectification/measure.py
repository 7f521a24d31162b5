r"""How well a pair is rectified: the vertical disparity of its matches (:func:`vertical_disparity`)."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import CamlabInputError, as_point_pairs

__all__ = [
    "VerticalDisparity",
    "vertical_disparity",
]


class VerticalDisparity(NamedTuple):
    """Vertical disparity :math:`|v_1 - v_2|` of corresponding points, pixels.

    ``median``, ``p95`` (95th percentile), ``max``, and ``values`` (N,) per pair.
    """

    median: float
    p95: float
    max: float
    values: np.ndarray


def vertical_disparity(x1: ArrayLike, x2: ArrayLike) -> VerticalDisparity:
    r"""How well a pair is rectified: :math:`|v_1 - v_2|` for corresponding pixels (u, v).

    In a perfectly rectified pair every match lies on the same row, so all values are 0.
    Pass the *rectified* pixels of true correspondences (e.g. from :func:`rectify_points`).
    Pairs with a non-finite coordinate are ignored.

    Parameters
    ----------
    x1, x2 : (N, 2) array_like
        Corresponding rectified pixels (u, v) in the left and right images.

    Returns
    -------
    VerticalDisparity
        ``median``, ``p95`` (95th percentile) and ``max`` of :math:`|v_1 - v_2|`, pixels,
        and ``values``, one per finite pair.

    Raises
    ------
    CamlabInputError
        Mismatched point sets, or no pair with finite coordinates.

    Examples
    --------
    >>> vertical_disparity([[10, 5], [20, 7]], [[3, 5.5], [1, 7]]).median
    0.25
    """
    a, b = _finite_pairs(x1, x2)
    if len(a) == 0:
        raise CamlabInputError("x1, x2: no pair has finite coordinates; nothing to measure")
    d = np.abs(a[:, 1] - b[:, 1])
    return VerticalDisparity(float(np.median(d)), float(np.percentile(d, 95)), float(d.max()), d)


def _finite_pairs(x1: ArrayLike, x2: ArrayLike):
    p1, p2, _ = as_point_pairs(x1, x2, finite=False)
    ok = np.all(np.isfinite(p1), axis=1) & np.all(np.isfinite(p2), axis=1)
    return p1[ok], p2[ok]
