"""The simulated stereo rig the lesson-11 checks draw their test points from."""

from __future__ import annotations

import numpy as np

from ...camera import Camera


def rig_points(seed: int, noise: float, n: int = 24, baseline=(0.3, 0.02, 0.01)):
    rng = np.random.default_rng(seed)
    c1 = Camera.look_at([0, -3, 0.5], [0, 0, 0.5])
    c2 = Camera.look_at(np.array([0, -3, 0.5]) + baseline, [0.1, 0, 0.5])
    X = rng.uniform(-0.8, 0.8, (n, 3)) + [0, 0, 0.5]
    x1, x2 = c1.project(X), c2.project(X)
    return x1 + rng.normal(0, noise, x1.shape), x2 + rng.normal(0, noise, x2.shape)


def converging_pair(baseline: float, toe_in: float) -> tuple[Camera, Camera]:
    """Two f = 800 px cameras ``baseline`` m apart along x, 1 m up, each turned ``toe_in / 2`` inwards.

    Both look at one point on the y axis (straight along +y when ``toe_in`` is 0), so the total
    convergence angle is ``toe_in`` radians.
    """
    reach = 1e6 if toe_in == 0 else (baseline / 2) / np.tan(toe_in / 2)
    target = [0.0, reach, 1.0]
    return tuple(Camera.look_at([side * baseline / 2, 0.0, 1.0], target) for side in (-1, 1))
