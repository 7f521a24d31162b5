"""Speed of camlab's panorama pipeline against OpenCV's Stitcher, measured in one run.

Run: ``python benchmarks/speed_stitching.py``. Medians of repeated timings; ratios are
camlab time / OpenCV time.

Cases (issue 7), on the rendered rotation set (4 views, 640 x 480, and at half size):

* the whole ``camlab.stitching.stitch`` (SIFT, pairwise RANSAC over all pairs, gain
  compensation, multi-band blending) against ``cv2.Stitcher`` in PANORAMA mode, which
  does more (bundle adjustment, seam finding, wave correction) and less (it matches
  only nearby pairs) and projects onto a sphere;
* warping plus multi-band blending alone (camlab ``warp_images`` + ``blend``) against
  ``cv2.warpPerspective`` + ``cv2.detail_MultiBandBlender`` with the same homographies,
  canvas, masks and number of bands.

The Stitcher row is only reported where the Stitcher succeeds (status OK). The issue
sets no speed target; the whole stitch is reported, warping plus blending should stay
within 8x of OpenCV's C++ (camlab blends float32 pyramids in numpy, OpenCV int16 in C++).
"""
from __future__ import annotations

import sys
from pathlib import Path

import cv2
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _timing import median_ms, print_table  # noqa: E402

from camlab import stitching as st  # noqa: E402
from camlab.data import panorama as sd  # noqa: E402

LEVELS = 5


def _cv_stitcher(images_bgr):
    stitcher = cv2.Stitcher_create(cv2.Stitcher_PANORAMA)
    status, pano = stitcher.stitch(images_bgr)
    return status, pano


def _cv_warp_blend(images, homographies, shape, seams):
    """cv2.warpPerspective every image onto the canvas, then OpenCV's multi-band blender."""
    h, w = shape
    blender = cv2.detail_MultiBandBlender(0, LEVELS)
    blender.prepare((0, 0, w, h))
    for img, H, seam in zip(images, homographies, seams):
        warped = cv2.warpPerspective(img, H, (w, h), flags=cv2.INTER_LINEAR)
        blender.feed(warped.astype(np.int16), seam.astype(np.uint8) * 255, (0, 0))
    out, _ = blender.blend(None, None)
    return out


def rows(repeat_stitch: int = 3, repeat_blend: int = 5) -> list[dict]:
    out = []
    for scale in (1.0, 0.5):
        s = sd.load_panorama_set(scale=scale)
        label = f"{s.images[0].shape[1]}x{s.images[0].shape[0]} x4"
        bgr = [np.ascontiguousarray(im[..., ::-1]) for im in s.images]
        status, _ = _cv_stitcher(bgr)
        cam = median_ms(lambda: st.stitch(s.images), repeat_stitch, 1)
        if status == cv2.Stitcher_OK:
            ocv = median_ms(lambda: _cv_stitcher(bgr), repeat_stitch, 1)
            out.append({"case": f"whole stitch {label} vs cv2.Stitcher", "camlab_ms": cam, "opencv_ms": ocv,
                        "ratio": cam / ocv, "target": "report", "ok": True})
        else:
            out.append({"case": f"whole stitch {label} (cv2.Stitcher failed: status {status})", "camlab_ms": cam,
                        "opencv_ms": float("nan"), "ratio": float("nan"), "target": "report", "ok": True})
        # warping + blending alone, same homographies and seams
        r = st.stitch(s.images)
        imgs = st.prepare_images(s.images)
        Hs_ref = [np.linalg.inv(r.homographies[r.reference]) @ H for H in r.homographies]

        def camlab_wb():
            wi = st.warp_images(imgs, Hs_ref)
            return st.blend(wi, "multiband", levels=LEVELS)

        wi = st.warp_images(imgs, Hs_ref)
        seams = st.seam_masks(wi.weights)
        u8 = [im for im in s.images]
        cam_wb = median_ms(camlab_wb, repeat_blend, 1)
        ocv_wb = median_ms(lambda: _cv_warp_blend(u8, wi.homographies, wi.shape, seams), repeat_blend, 1)
        out.append({"case": f"warp + multi-band blend {label}", "camlab_ms": cam_wb, "opencv_ms": ocv_wb,
                    "ratio": cam_wb / ocv_wb, "target": "<= 8x", "ok": cam_wb / ocv_wb <= 8})
    return out


if __name__ == "__main__":
    print_table(rows(), ["case", "camlab_ms", "opencv_ms", "ratio", "target", "ok"],
                title="Stitching speed (median ms; ratio = camlab / OpenCV)")
