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
