"""camlab: camera geometry and 2-D projective geometry you can drag and see.

Conventions (full page: docs/conventions.md):

1. Points are rows: (N, 2) image points, (N, 3) world points, (N, 3)/(N, 4) homogeneous;
   a single (2,) point is accepted and the result keeps the input's rank.
2. Inputs are array_like and never modified; outputs are new float64 arrays.
3. Pixels (u, v) = (column, row), origin at the centre of the top-left pixel; img[v, u].
4. Camera frame x right, y down, z forward; X_cam = R @ X_world + t, P = K [R | t].
5. Angles in radians; lengths in metres or pixels, as each docstring says.
6. Homogeneous points with w = 0 are ideal; from_homogeneous gives NaN for them.
7. Homographies map points by H and lines by H^-T; they are compared up to scale.
8. User mistakes raise CamlabInputError (a ValueError) naming the argument and the fix.
9. Random functions take rng: np.random.Generator | None; lessons seed everything.
10. OpenCV is the reference and the workhorse, never the teaching path.

Submodules load on first use (``camlab.homography``...), so ``import camlab`` stays fast
and never imports matplotlib, ipywidgets or cv2.
"""
from __future__ import annotations

import importlib

from . import projective
from ._validate import CamlabInputError, ConvergenceError, DegenerateError
from .projective import (
    cross_ratio,
    from_homogeneous,
    horizon,
    join,
    map_lines,
    map_points,
    meet,
    to_homogeneous,
    vanishing_point,
)

__version__ = "0.1.0"

__all__ = [
    "CamlabInputError", "ConvergenceError", "DegenerateError", "cross_ratio", "from_homogeneous",
    "horizon", "join", "map_lines", "map_points", "meet", "projective", "to_homogeneous",
    "vanishing_point",
]


def __getattr__(name: str):
    # Lazy submodules: camlab.<topic> imports camlab/<topic>.py on first access.
    if name.startswith("_"):
        raise AttributeError(name)
    try:
        module = importlib.import_module(f"{__name__}.{name}")
    except ModuleNotFoundError as exc:
        if exc.name == f"{__name__}.{name}":
            raise AttributeError(f"module 'camlab' has no attribute {name!r}") from None
        raise
    globals()[name] = module
    return module
