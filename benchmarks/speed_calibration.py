"""Speed of camlab.calibration.calibrate_camera against cv2.calibrateCamera, plus the accuracy table.

Run: ``python benchmarks/speed_calibration.py``. Every number is the median of repeated
timings in this one run; ratio = camlab time / OpenCV time.

Target: ``calibrate_camera`` on 25 views of 54 corners (sigma = 0.2 px) within 5x
of ``cv2.calibrateCamera`` with the same model (fx, fy, cx, cy, k1, k2, p1, p2, k3).
Also printed: camlab versus OpenCV on the same corners and both versus the truth.
"""

from __future__ import annotations

import sys
from functools import partial
from pathlib import Path

import cv2
import numpy as np

sys.path.insert(0, str(Path(__file__).parent))

from _timing import median_ms, print_table  # noqa: E402

from camlab.calibration import calibrate_camera, make_synthetic_views  # noqa: E402


def _opencv(s):
    obj = [s.object_points.astype(np.float32)] * len(s.image_points)
    img = [p.astype(np.float32).reshape(-1, 1, 2) for p in s.image_points]
    return lambda: cv2.calibrateCamera(obj, img, s.image_size, None, None)


def rows(repeat: int = 7) -> list[dict]:
    out = []
    for n_views, target in ((25, 5.0), (10, 5.0)):
        s = make_synthetic_views(n_views, 0.2, rng=np.random.default_rng(2026))
        ours = median_ms(
            partial(calibrate_camera, s.object_points, s.image_points, s.image_size), repeat, 1
        )
        ref = median_ms(_opencv(s), repeat, 1)
        out.append(
            {
                "case": f"calibrate_camera, {n_views} views x 54 corners",
                "camlab_ms": ours,
                "opencv_ms": ref,
                "ratio": ours / ref,
                "target": f"<= {target:g}x",
                "ok": ours / ref <= target,
            }
        )
    return out


def accuracy_rows(n_views: int = 15, noise: float = 0.2, seed: int = 7) -> list[dict]:
    """camlab and OpenCV on the same noisy corners, and both against the true camera."""
    s = make_synthetic_views(n_views, noise, rng=np.random.default_rng(seed))
    res = calibrate_camera(s.object_points, s.image_points, s.image_size)
    rms, K, dist, *_ = _opencv(s)()
    true = dict(
        zip(("fx", "fy", "cx", "cy"), (s.K[0, 0], s.K[1, 1], s.K[0, 2], s.K[1, 2]), strict=True)
    )
    cv = dict(zip(("fx", "fy", "cx", "cy"), (K[0, 0], K[1, 1], K[0, 2], K[1, 2]), strict=True))
    out = []
    for name in ("fx", "fy", "cx", "cy"):
        ours = res.intrinsics[name]
        out.append(
            {
                "param": name,
                "truth": true[name],
                "camlab": ours,
                "opencv": cv[name],
                "camlab - opencv": ours - cv[name],
                "camlab - truth": ours - true[name],
                "camlab std": res.std[name],
            }
        )
    for i, name in enumerate(("k1", "k2", "p1", "p2", "k3")):
        out.append(
            {
                "param": name,
                "truth": s.dist[i],
                "camlab": res.dist[i],
                "opencv": float(dist.ravel()[i]),
                "camlab - opencv": res.dist[i] - float(dist.ravel()[i]),
                "camlab - truth": res.dist[i] - s.dist[i],
                "camlab std": res.std[name],
            }
        )
    out.append(
        {
            "param": "rms (px)",
            "truth": np.nan,
            "camlab": res.rms,
            "opencv": rms,
            "camlab - opencv": res.rms - rms,
            "camlab - truth": np.nan,
            "camlab std": np.nan,
        }
    )
    return out


def main() -> None:
    print_table(
        rows(),
        ["case", "camlab_ms", "opencv_ms", "ratio", "target", "ok"],
        "calibrate_camera vs OpenCV",
    )
    acc = accuracy_rows()
    print("\n### Same corners (15 views, sigma 0.2 px): camlab vs cv2.calibrateCamera vs truth\n")
    cols = ["param", "truth", "camlab", "opencv", "camlab - opencv", "camlab - truth", "camlab std"]
    print("| " + " | ".join(cols) + " |")
    print("|" + "---|" * len(cols))
    for r in acc:
        print(
            "| " + " | ".join(r[c] if isinstance(r[c], str) else f"{r[c]:.6g}" for c in cols) + " |"
        )


if __name__ == "__main__":
    main()
