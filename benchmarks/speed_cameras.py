"""Speed and accuracy of camlab's camera algorithms against OpenCV.

Run: python benchmarks/speed_cameras.py

Speed rows (median of repeated timings, one run): projection, RQ decomposition of P
(``cv2.decomposeProjectionMatrix``), Rodrigues (``cv2.Rodrigues``). The DLT resection has no
OpenCV counterpart for a single non-planar view (``cv2.calibrateCamera`` needs a planar
target or an initial K), so its row times camlab alone and records the accuracy instead.
Accuracy table: decomposition error vs OpenCV and vs the truth, DLT recovery with noise.
"""

from __future__ import annotations

import sys
from pathlib import Path

import cv2
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import median_ms  # noqa: E402

from camlab import camera as cm  # noqa: E402


def _setup(seed: int = 0, n: int = 1000):
    rng = np.random.default_rng(seed)
    cam = cm.Camera.look_at(
        [4.0, -3.0, 2.0], [0.0, 0.0, 0.5], K=cm.intrinsic_matrix(810, 790, 330, 235)
    )
    X = rng.uniform(-1, 1, (n, 3)) + [0, 0, 1]
    return rng, cam, X


def rows() -> list[dict]:
    rng, cam, X = _setup()
    rvec = cv2.Rodrigues(cam.R)[0]
    out = []

    def row(case, ours, theirs, max_ms):
        # Targets are absolute: on a single 3x4 matrix OpenCV's C++ wins by a fixed Python
        # overhead (validation, SVD rank check) that no learner will notice; what matters is
        # that a slider callback can afford the call.
        ratio = ours / theirs if theirs else float("nan")
        target = f"camlab <= {max_ms:g} ms" + ("" if theirs else " (no OpenCV counterpart)")
        out.append(
            {
                "case": case,
                "camlab_ms": ours,
                "opencv_ms": theirs,
                "ratio": ratio,
                "target": target,
                "ok": bool(ours <= max_ms),
            }
        )

    row(
        "project 1000 points (Camera.project vs cv2.projectPoints)",
        median_ms(lambda: cam.project(X), 200, 1),
        median_ms(lambda: cv2.projectPoints(X, rvec, cam.t.reshape(3, 1), cam.K, None), 200, 1),
        1.0,
    )
    P = 3.0 * cam.P
    row(
        "decompose P (decompose_projection_matrix vs cv2.decomposeProjectionMatrix)",
        median_ms(lambda: cm.decompose_projection_matrix(P), 200, 1),
        median_ms(lambda: cv2.decomposeProjectionMatrix(P), 200, 1),
        1.0,
    )
    r = rng.normal(size=3)
    row(
        "axis-angle to R (rotation_from_axis_angle vs cv2.Rodrigues)",
        median_ms(lambda: cm.rotation_from_axis_angle(r), 200, 1),
        median_ms(lambda: cv2.Rodrigues(r), 200, 1),
        0.2,
    )
    X50 = X[:50]
    uv50 = cam.project(X50) + rng.normal(0, 0.5, (50, 2))
    row(
        "DLT resection, 50 points (estimate_projection_matrix)",
        median_ms(lambda: cm.estimate_projection_matrix(X50, uv50), 50, 1),
        0.0,
        5.0,
    )
    row(
        "DLT + LM refinement, 50 points (refine=True)",
        median_ms(lambda: cm.estimate_projection_matrix(X50, uv50, refine=True), 10, 1),
        0.0,
        30.0,
    )
    return out


def accuracy_rows(trials: int = 200) -> list[dict]:
    """Cross-check errors: camlab vs OpenCV and vs the truth on random cameras."""
    rng = np.random.default_rng(1)
    dK = dR = dC = dK_truth = 0.0
    for _ in range(trials):
        c = cm.Camera(
            cm.intrinsic_matrix(*rng.uniform([600, 600, 280, 200], [1000, 1000, 360, 280])),
            cm.rotation_from_axis_angle(rng.normal(size=3)),
            rng.normal(size=3) + [0, 0, 6],
        )
        P = rng.uniform(0.01, 100) * c.P
        K_cv, R_cv, C_cv = cv2.decomposeProjectionMatrix(P)[:3]
        d = cm.decompose_projection_matrix(P)
        dK = max(dK, np.abs(d.K - K_cv / K_cv[2, 2]).max())
        dR = max(dR, np.abs(d.R - R_cv).max())
        dC = max(dC, np.abs(d.centre - (C_cv[:3] / C_cv[3]).ravel()).max())
        dK_truth = max(dK_truth, np.abs(d.K - c.K).max())
    out = [
        {"check": "decompose vs cv2.decomposeProjectionMatrix, max |K diff| (px)", "value": dK},
        {"check": "decompose vs cv2.decomposeProjectionMatrix, max |R diff|", "value": dR},
        {"check": "decompose vs cv2.decomposeProjectionMatrix, max |C diff| (m)", "value": dC},
        {"check": "decompose vs truth, max |K diff| (px)", "value": dK_truth},
    ]
    _, cam, X = _setup(2, 100)
    for noise in (0.0, 0.5, 2.0):
        uv = cam.project(X) + rng.normal(0, noise, (100, 2))  # the same data for both rows
        for refine in (False, True):
            P = cm.estimate_projection_matrix(X, uv, refine=refine)
            rms = np.sqrt(np.mean(cm.reprojection_errors(P, X, uv) ** 2))
            d = cm.decompose_projection_matrix(P)
            out.append(
                {
                    "check": f"DLT{' + LM' if refine else ''}, 100 pts, noise {noise} px: RMS (px) / "
                    f"|fx err| (px) / |C err| (cm)",
                    "value": (
                        rms,
                        abs(d.K[0, 0] - cam.K[0, 0]),
                        100 * np.linalg.norm(d.centre - cam.centre),
                    ),
                }
            )
    return out


if __name__ == "__main__":
    print(f"OpenCV {cv2.__version__}, numpy {np.__version__}")
    print(f"{'case':<78} {'camlab ms':>10} {'opencv ms':>10} {'ratio':>7}  target")
    for r in rows():
        print(
            f"{r['case']:<78} {r['camlab_ms']:>10.4f} {r['opencv_ms']:>10.4f} {r['ratio']:>7.2f}  "
            f"{r['target']} {'ok' if r['ok'] else 'MISSED'}"
        )
    print()
    for r in accuracy_rows():
        v = r["value"]
        text = " / ".join(f"{x:.3g}" for x in v) if isinstance(v, tuple) else f"{v:.3g}"
        print(f"{r['check']:<90} {text}")
