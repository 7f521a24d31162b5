"""Image formation: renderer timing, distortion versus OpenCV, demosaicing PSNR.

Run: python benchmarks/speed_image_formation.py   (prints the speed table, then the PSNR table)
"""

from __future__ import annotations

import os
import sys
from functools import partial

import cv2
import numpy as np

from camlab import distortion, render, scenes, sensor
from camlab.camera import rotation_from_euler

sys.path.insert(0, os.path.dirname(__file__))
from _timing import median_ms  # noqa: E402

K = np.array([[800.0, 0.0, 319.5], [0.0, 800.0, 239.5], [0.0, 0.0, 1.0]])
DIST = np.array([-0.28, 0.09, 0.0012, -0.0008, -0.01])


def _median_ms(fn, repeat: int = 15) -> float:
    return median_ms(fn, repeat=repeat, warmup=1)


def _row(case, ours, ref, target, ok):
    return {
        "case": case,
        "camlab_ms": ours,
        "opencv_ms": ref,
        "ratio": ours / ref if ref else float("nan"),
        "target": target,
        "ok": bool(ok),
    }


def rows() -> list[dict]:
    out = []
    board = scenes.checkerboard(
        (9, 6), 0.03, R=rotation_from_euler(0.3, -0.2, 0.1), t=(-0.12, -0.07, 0.7)
    )
    scene = [
        board,
        scenes.box([0.2, 0.05, 0.9], [0.15, 0.15, 0.15], R=rotation_from_euler(0.4, 0.6, 0)),
        scenes.text_page(0.2, t=(-0.25, 0.05, 1.0)),
    ]
    # the renderer has no OpenCV equivalent; its reference is one cv2.warpPerspective of the board texture
    H = K @ np.column_stack([board.R[:, 0], board.R[:, 1], board.t])
    tex = board.texture
    ref_warp = _median_ms(lambda: cv2.warpPerspective(tex, H, (640, 480)))
    for case, kw in [
        ("render 640x480 grey board", {}),
        ("render 640x480 grey board + distortion", {"dist": DIST}),
        (
            "render 640x480 board+box+page, distortion, noise",
            {"dist": DIST, "sensor": render.Sensor(noise=sensor.NoiseModel())},
        ),
        (
            "render 640x480 RGB Bayer scene, defocus",
            {"sensor": render.Sensor(bayer="RGGB"), "defocus": render.Defocus(2.0, 0.8)},
        ),
    ]:
        sc = board if "board" == case.split()[-1] or "grey board" in case else scene
        ms = _median_ms(partial(render.render, sc, K, (640, 480), rng=0, **kw))
        target = "<= 100 ms median" if "grey" in case or "noise" in case else "report only (RGB)"
        out.append(
            _row(
                case + " (vs one cv2.warpPerspective)",
                ms,
                ref_warp,
                target,
                ms <= 100 if target.startswith("<=") else True,
            )
        )

    rng = np.random.default_rng(0)
    px = np.column_stack([rng.uniform(0, 639, 10000), rng.uniform(0, 479, 10000)])
    Xc = np.column_stack([(px - K[:2, 2]) / 800, np.ones(len(px))])
    ours = _median_ms(lambda: distortion.distort_pixels(px, K, DIST))
    ref = _median_ms(
        lambda: cv2.projectPoints(Xc.reshape(-1, 1, 3), np.zeros(3), np.zeros(3), K, DIST)
    )
    err = np.abs(
        distortion.distort_pixels(px, K, DIST)
        - cv2.projectPoints(Xc.reshape(-1, 1, 3), np.zeros(3), np.zeros(3), K, DIST)[0].reshape(
            -1, 2
        )
    ).max()
    out.append(
        _row(
            f"distort 10k points vs projectPoints (max err {err:.1e} px)",
            ours,
            ref,
            "err < 1e-6 px",
            err < 1e-6,
        )
    )

    dpx = distortion.distort_pixels(px, K, DIST)
    ours = _median_ms(lambda: distortion.undistort_pixels(dpx, K, DIST))
    ref = _median_ms(lambda: cv2.undistortPoints(dpx.reshape(-1, 1, 2), K, DIST, None, K))
    e_ours = np.abs(distortion.undistort_pixels(dpx, K, DIST) - px).max()
    e_cv = np.abs(
        cv2.undistortPoints(dpx.reshape(-1, 1, 2), K, DIST, None, K).reshape(-1, 2) - px
    ).max()
    out.append(
        _row(
            f"undistort 10k points (max err ours {e_ours:.1e} px, OpenCV {e_cv:.1e} px)",
            ours,
            ref,
            "err < 1e-6 px",
            e_ours < 1e-6,
        )
    )

    ours = _median_ms(lambda: distortion.undistort_map(K, DIST, (640, 480)))
    ref = _median_ms(
        lambda: cv2.initUndistortRectifyMap(K, DIST, None, K, (640, 480), cv2.CV_32FC1)
    )
    out.append(
        _row(
            "undistort map 640x480 (numpy) vs initUndistortRectifyMap",
            ours,
            ref,
            "<= 60 ms",
            ours <= 60,
        )
    )

    ours = _median_ms(
        lambda: distortion._distort_map_cached.__wrapped__(
            K.tobytes(), DIST.tobytes(), K.tobytes(), 640, 480, 4
        )
    )
    out.append(
        _row(
            "distort (inverse) map 640x480, step 4, uncached vs initUndistortRectifyMap",
            ours,
            ref,
            "<= 60 ms",
            ours <= 60,
        )
    )

    truth = render.render(
        [scenes.photo_plane(0.3, t=(0.05, 0.02, 1.0))],
        K * [[0.5], [0.5], [1]] + [[0, 0, -160], [0, 0, -120], [0, 0, 0]],
        (320, 240),
    ).irradiance
    raw = sensor.quantise(sensor.mosaic(truth, "RGGB"))
    ours = _median_ms(lambda: sensor.demosaic_bilinear(raw, "RGGB"))
    ref = _median_ms(lambda: sensor.demosaic_opencv(raw, "RGGB", "bilinear"))
    out.append(
        _row(
            "demosaic bilinear 320x240 (numpy) vs cv2 bilinear",
            ours,
            ref,
            "<= 50 ms (interactive)",
            ours <= 50,
        )
    )
    return out


def psnr_table() -> list[dict]:
    """PSNR (dB) of every demosaicing method on a rendered colour scene, for each Bayer pattern."""
    K2 = np.array([[900.0, 0, 159.5], [0, 900.0, 119.5], [0, 0, 1]])
    scene = [
        scenes.photo_plane(0.3, t=(0.05, 0.02, 1.0)),
        scenes.text_page(0.2, t=(-0.2, 0.0, 1.1), R=rotation_from_euler(0, 0.2, 0.05)),
    ]
    truth = render.render(scene, K2, (320, 240), color=True).irradiance
    table = []
    for pattern in sensor.BAYER_PATTERNS:
        raw = sensor.quantise(sensor.mosaic(truth, pattern))
        row = {
            "pattern": pattern,
            "camlab bilinear": sensor.psnr(
                truth, sensor.demosaic_bilinear(raw, pattern) / 255, border=2
            ),
        }
        for m in ("bilinear", "vng", "ea"):
            row[f"OpenCV {m}"] = sensor.psnr(
                truth, sensor.demosaic_opencv(raw, pattern, m) / 255, border=2
            )
        table.append(row)
    return table


if __name__ == "__main__":
    r = rows()
    w = max(len(x["case"]) for x in r)
    print(f"{'case':{w}s}  camlab_ms  opencv_ms    ratio  target                ok")
    for x in r:
        print(
            f"{x['case']:{w}s}  {x['camlab_ms']:9.2f}  {x['opencv_ms']:9.2f}  {x['ratio']:7.2f}  {x['target']:20s}  {x['ok']}"
        )
    print()
    t = psnr_table()
    keys = list(t[0])[1:]
    print("PSNR (dB)  " + "  ".join(f"{k:>16s}" for k in keys))
    for row in t:
        print(f"{row['pattern']:9s}  " + "  ".join(f"{row[k]:16.2f}" for k in keys))
