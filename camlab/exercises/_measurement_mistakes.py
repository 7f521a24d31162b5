"""More rows of the lesson-12 ``pose_from_homography`` diagnosis (measurement.py is near its size limit).

Each row reads the context that ``measurement._pose_context`` builds: ``A = K^-1 H``, the right
``R`` and ``t``.
"""

from __future__ import annotations

import numpy as np

from ._core import Mistake


def _rows_pose(A):
    """The pose built from the ROWS of A (A.T), scaled as the prompt says."""
    B = np.asarray(A).T
    lam = np.sign(B[2, 2]) / np.linalg.norm(B[:, 0])
    r1, r2, t = lam * B[:, 0], lam * B[:, 1], lam * B[:, 2]
    return np.column_stack([r1, r2, np.cross(r1, r2), t])


POSE_MISTAKES_MORE = (
    Mistake(
        "rows of K^-1 H",
        lambda c: _rows_pose(c.A),
        "you took the ROWS of A = K^-1 H (A[0], A[1], A[2], or A.T): r1, r2 and t are its COLUMNS, "
        "A[:, 0], A[:, 1], A[:, 2], because H = K [r1 r2 t] stacks them side by side.",
    ),
    Mistake(
        "the inverse pose",
        lambda c: np.column_stack([c.R.T, -c.R.T @ c.t]),
        "you returned the inverse pose [R^T | -R^T t] (board_from_cam, where the camera sits and how it "
        "is turned in board coordinates): the prompt asks for cam_from_board, X_cam = R X + t, which is "
        "what lambda K^-1 H gives directly, [r1 r2 r1 x r2 | t], no transpose.",
    ),
)
