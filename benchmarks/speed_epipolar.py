"""Speed of camlab's two-view geometry, rectification and block matching against OpenCV.

Run: ``python benchmarks/speed_epipolar.py``. Every number is the median of repeated
timings measured in this one run; ratios are camlab time / OpenCV time. camlab's versions
are the readable numpy teaching path. No speed targets were set; the ones below were
chosen for this script after measuring on the loaded 2-core machine (numpy within 15-30x
of OpenCV's C++ for the small geometric solvers, looser for the per-pixel numpy paths, and
the cv2 fast path within 3x). The accuracy of the same calls
is asserted in tests/test_epipolar.py and tests/test_rectification.py.
"""

from __future__ import annotations

import sys
from pathlib import Path

import cv2
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import print_table, ratio_row  # noqa: E402

from camlab import disparity as dp  # noqa: E402
from camlab import epipolar as ep  # noqa: E402
from camlab import rectification as rc  # noqa: E402
from camlab.camera import Camera  # noqa: E402
from camlab.data.stereo import load_stereo_rig  # noqa: E402


def _matches(n: int = 500, outliers: float = 0.3, seed: int = 0):
    rng = np.random.default_rng(seed)
    c1 = Camera.look_at([0, -3, 0.5], [0, 0, 0.5])
    c2 = Camera.look_at([0.3, -3.05, 0.52], [0.05, 0, 0.5])
    X = rng.uniform(-0.8, 0.8, (n, 3)) + [0, 0, 0.5]
    x1 = c1.project(X) + rng.normal(0, 0.5, (n, 2))
    x2 = c2.project(X) + rng.normal(0, 0.5, (n, 2))
    bad = rng.random(n) < outliers
    x2[bad] = rng.uniform([0, 0], [640, 480], (bad.sum(), 2))
    return c1, c2, x1, x2, bad


def rows() -> list[dict]:
    # One thread for OpenCV, like camlab's numpy (these array sizes do not use BLAS threads):
    # ratios then compare algorithms, not the number of free cores on a shared machine.
    threads = cv2.getNumThreads()
    cv2.setNumThreads(1)
    try:
        return _rows()
    finally:
        cv2.setNumThreads(threads)


def _rows() -> list[dict]:
    c1, c2, x1, x2, bad = _matches()
    good1, good2 = x1[~bad], x2[~bad]
    out = [
        ratio_row(
            "8-point F, 350 pairs",
            lambda: ep.estimate_fundamental_matrix(good1, good2),
            lambda: cv2.findFundamentalMat(good1, good2, cv2.FM_8POINT),
            15,
        ),
        ratio_row(
            "RANSAC F, 500 pairs, 30% outliers",
            lambda: ep.ransac_fundamental_matrix(x1, x2, 1.0, 0.999, rng=np.random.default_rng(1)),
            lambda: cv2.findFundamentalMat(x1, x2, cv2.FM_RANSAC, 1.0, 0.999),
            10,
            repeat=10,
        ),
        ratio_row(
            "triangulate 350 points (linear)",
            lambda: ep.triangulate_points(c1, c2, good1, good2),
            lambda: cv2.triangulatePoints(c1.P, c2.P, good1.T, good2.T),
            20,
        ),
    ]
    rig = load_stereo_rig()
    a, b = rig.camera1, rig.camera2
    R, t = ep.relative_pose(a, b)
    dist1, dist2 = np.array(a.dist), np.array(b.dist)

    def cv_calibrated():
        R1, R2, P1, P2, *_ = cv2.stereoRectify(
            a.K, dist1, b.K, dist2, a.image_size, R, t.reshape(3, 1), alpha=0
        )
        return [
            cv2.initUndistortRectifyMap(c.K, d, Rr, P[:3, :3], a.image_size, cv2.CV_32FC1)
            for c, d, Rr, P in ((a, dist1, R1, P1), (b, dist2, R2, P2))
        ]

    out.append(
        ratio_row(
            "calibrated rectification + maps, 640x480 (numpy maps)",
            lambda: rc.rectify_calibrated(a, b, 0.0),
            cv_calibrated,
            40,
            repeat=10,
        )
    )
    out.append(
        ratio_row(
            "calibrated rectification + maps, 640x480 (cv2 maps)",
            lambda: rc.rectify_calibrated(a, b, 0.0, method="cv2"),
            cv_calibrated,
            3,
            repeat=10,
        )
    )
    F = ep.fundamental_from_cameras(a.replace(dist=(0.0,) * 5), b.replace(dist=(0.0,) * 5))
    rng = np.random.default_rng(2)
    X = rng.uniform([-0.6, 1.5, 0.5], [0.6, 3.5, 1.4], (300, 3))
    u1 = a.replace(dist=(0.0,) * 5).project(X) + rng.normal(0, 0.3, (300, 2))
    u2 = b.replace(dist=(0.0,) * 5).project(X) + rng.normal(0, 0.3, (300, 2))
    out.append(
        ratio_row(
            "uncalibrated rectification, 300 matches",
            lambda: rc.rectify_uncalibrated(u1, u2, F, (640, 480)),
            lambda: cv2.stereoRectifyUncalibrated(u1, u2, F, (640, 480)),
            30,
        )
    )
    rect = rc.rectify_calibrated(a, b, 0.0)
    L, Rr = rc.rectify_images(rect, rig.left, rig.right)
    band = slice(150, 330)
    sgbm = cv2.StereoBM_create(numDisparities=80, blockSize=9)
    out.append(
        ratio_row(
            "block matching 640x180, 73 disparities (numpy vs cv2.StereoBM)",
            lambda: dp.block_matching_disparity(L[band], Rr[band], 88, 9, min_disparity=16),
            lambda: sgbm.compute(L[band], Rr[band]),
            60,
            repeat=3,
        )
    )
    return out


if __name__ == "__main__":
    print_table(
        rows(),
        ["case", "camlab_ms", "opencv_ms", "ratio", "target", "ok"],
        title="camlab two-view geometry vs OpenCV (median ms)",
    )
