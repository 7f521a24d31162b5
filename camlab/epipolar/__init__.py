r"""Two-view geometry: the fundamental and essential matrices, epipoles, epipolar lines, triangulation.

Two cameras see the same world point :math:`X` at pixels :math:`x` (image 1) and
:math:`x'` (image 2). The two rays and the baseline joining the camera centres lie in one
plane, the *epipolar plane*, so :math:`x'` must lie on the line where that plane cuts
image 2. Algebraically, for homogeneous pixels,

.. math:: \tilde x'^\top F\, \tilde x = 0, \qquad l' = F \tilde x, \qquad l = F^\top \tilde x',

with the (3, 3) *fundamental matrix* F of rank 2 (7 degrees of freedom). Its null vectors
are the *epipoles* :math:`F e = 0`, :math:`F^\top e' = 0`: the image of the other camera's
centre, through which every epipolar line passes. With calibrated cameras
(:math:`\hat x = K^{-1} \tilde x`) the same constraint reads
:math:`\hat x'^\top E \hat x = 0` with the *essential matrix*
:math:`E = [t]_\times R = K'^\top F K`, where ``(R, t)`` is camera 2's pose relative to
camera 1 (``X_2 = R X_1 + t``).

Conventions (docs/conventions.md): points are rows, pixels (u, v) = (column, row) with the
origin at the centre of the top-left pixel; ``x1`` are pixels in image 1 and ``x2`` the
corresponding pixels in image 2, so ``x2_h @ F @ x1_h == 0``; poses are cam_from_world;
metres. See lesson 11 and [1]_.

The package holds three topics, every public name importable from ``camlab.epipolar``:

* :mod:`camlab.epipolar.geometry`: F and E from known cameras, the epipoles, epipolar lines
  and the distance of a point from its line;
* :mod:`camlab.epipolar.estimation`: F from matches, the normalised 8-point algorithm and
  RANSAC with the Sampson distance;
* :mod:`camlab.epipolar.pose`: the four poses in E, the one that puts the points in front of
  both cameras, and triangulation.

References
----------
.. [1] Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., 2004, chapters 9-12 (two-view
   geometry).
"""

from __future__ import annotations

from .estimation import (
    EIGHT_POINT_REASON,
    FundamentalModel,
    FundamentalRansacResult,
    estimate_fundamental_matrix,
    ransac_fundamental_matrix,
    sampson_distance,
)
from .geometry import (
    Epipoles,
    check_fundamental,
    epipolar_distance,
    epipolar_lines,
    epipoles,
    essential_from_fundamental,
    essential_matrix,
    fundamental_from_cameras,
    fundamental_from_essential,
    normalise_fundamental,
    relative_pose,
    skew,
)
from .pose import (
    EssentialDecomposition,
    RelativePose,
    decompose_essential_matrix,
    recover_pose,
    triangulate_points,
)

__all__ = [
    "Epipoles",
    "check_fundamental",
    "EIGHT_POINT_REASON",
    "EssentialDecomposition",
    "FundamentalModel",
    "FundamentalRansacResult",
    "RelativePose",
    "decompose_essential_matrix",
    "epipolar_distance",
    "epipolar_lines",
    "epipoles",
    "essential_from_fundamental",
    "essential_matrix",
    "estimate_fundamental_matrix",
    "fundamental_from_cameras",
    "fundamental_from_essential",
    "normalise_fundamental",
    "ransac_fundamental_matrix",
    "recover_pose",
    "relative_pose",
    "sampson_distance",
    "skew",
    "triangulate_points",
]
