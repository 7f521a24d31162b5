"""The cameras and world points lesson 04's exercises are tested on."""

from __future__ import annotations

import numpy as np

from ... import camera as cm


def cameras():
    """Realistic cameras (fx about 800, 640x480) in varied poses, one with skew."""
    return [
        cm.Camera.look_at([4.0, -3.0, 2.0], [0.0, 0.0, 0.5]),
        cm.Camera.look_at(
            [-2.0, -5.0, 1.5], [0.3, 0.2, 0.8], K=cm.intrinsic_matrix(760, 820, 300, 250, 3.0)
        ),
        cm.Camera(
            cm.intrinsic_matrix(900, 900, 330, 230),
            cm.rotation_from_euler(0.1, -0.2, 0.3),
            [0.2, -0.1, 6.0],
        ),
    ]


def world_points():
    rng = np.random.default_rng(4)
    return rng.uniform(-1.0, 1.0, (6, 3)) + [0.0, 0.0, 0.5]
