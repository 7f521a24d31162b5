"""camlab.stitch against cv2.Stitcher on 2-, 3- and 6-photo sets: time, per-stage table, accuracy.

Run: ``python benchmarks/speed_stitching.py``. Both run on ONE thread: ``cv2.setNumThreads(1)``
(OpenCV's own thread pool, which camlab's OpenCV calls share), and ``OMP_NUM_THREADS``,
``OPENBLAS_NUM_THREADS``, ``MKL_NUM_THREADS`` = 1 set below before numpy is imported (numpy's
BLAS; from ``benchmarks/run.py``, which imports numpy first, they only hold if set in the shell:
camlab's BLAS work here is 3x3 and 30x30 matrices, so it hardly matters). Same inputs (about
0.6 megapixel), each with its own defaults (the Stitcher in its default PANORAMA mode: ORB
features, spherical canvas, graph-cut seams, block gains, multi-band blending). The two
run alternately ``repeat`` times in one process, so both see the same machine load; the
table gives each run's wall-clock ratio, the ratio of the medians (the target), the ratio of
the median CPU times (``time.process_time``: what each method itself computed, less moved by
other processes), and the load average (the machine is shared: the ratio holds better than
the absolute times).

Sets:

* ``turn3+unrelated``: three photos of a turning camera (rendered from a real photo,
  exact ground truth) with an unrelated photo mixed in as the second image;
* ``exposures``: a pair shot at two exposures (the second clips);
* ``aerial6``: a flat scene (real aerial photos, mvtb-data) from six positions.

Accuracy: the transfer error of each method's model (camlab's cameras or homographies,
the Stitcher's cameras) on *independent* matches: ORB features at full resolution
(neither method used them), ratio test, kept if cv2.findHomography (RANSAC, 3 px) on that
pair keeps them. Median over every overlapping pair, pixels. Focal lengths: camlab's and
the Stitcher's per image, and the truth where it is known.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"  # before numpy is imported: one BLAS thread, like cv2.setNumThreads(1)

import sys  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402
from pathlib import Path  # noqa: E402

import cv2  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _timing import print_table  # noqa: E402

from camlab import stitching as st  # noqa: E402
from camlab.data import panorama as pd  # noqa: E402
from camlab.fixtures import panorama as fp  # noqa: E402

TARGET = 1.5  # issue 32: stitch within 1.5x of cv2.Stitcher


def sets() -> dict:
    t3 = fp.turning_set("turn3", unrelated=True)
    ex = fp.turning_set("exposures")
    aerial = pd.load_aerial_mosaic(6)
    f_true = float(t3.K[0, 0])
    return {
        "turn3+unrelated": (t3.images, t3.names, f_true),
        "exposures": (ex.images, ex.names, f_true),
        "aerial6": (aerial, [f"aerial_{k + 1}" for k in range(6)], None),
    }


def _bgr(img: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(
        cv2.cvtColor(img, cv2.COLOR_GRAY2BGR) if img.ndim == 2 else img[..., ::-1]
    )


def cv_stitch(images, mode: int = cv2.Stitcher_PANORAMA):
    s = cv2.Stitcher_create(mode)
    status, pano = s.stitch([_bgr(im) for im in images])
    return s, status, pano


def cv_features(images) -> None:
    """The Stitcher's first stage alone: its default finder (ORB, 500 features) on copies of its
    registration resolution (0.6 MP, resized as it does), to set beside camlab's ``features`` stage."""
    orb = cv2.ORB_create()
    for im in images:
        bgr = _bgr(im)
        s = min(1.0, np.sqrt(0.6e6 / (bgr.shape[0] * bgr.shape[1])))
        small = cv2.resize(bgr, None, fx=s, fy=s, interpolation=cv2.INTER_LINEAR_EXACT)
        orb.detectAndCompute(small, None)


def cv_mode(images) -> tuple[int, str]:
    """The Stitcher's default PANORAMA mode, or SCANS (affine, for flat scenes) where PANORAMA fails."""
    try:
        _, status, _ = cv_stitch(images)
        if status == cv2.Stitcher_OK:
            return cv2.Stitcher_PANORAMA, "PANORAMA"
        why = f"status {status}"
    except cv2.error as exc:
        why = str(exc).strip().splitlines()[-1][:60]
    return cv2.Stitcher_SCANS, f"SCANS (PANORAMA failed: {why})"


def cv_mappings(stitcher, images) -> dict:
    """image index -> 3x3 M with x_canvas_ray ~ M x (the Stitcher's K R^T inverse), at full resolution."""
    comp = [int(c) for c in np.ravel(stitcher.component())]
    h, w = images[comp[0]].shape[:2]
    ws = min(1.0, np.sqrt(stitcher.registrationResol() * 1e6 / (h * w)))
    out = {}
    for k, cam in zip(comp, stitcher.cameras(), strict=True):
        K = cam.K().astype(float)
        K[:2] /= ws  # the Stitcher's cameras are at its registration scale
        R = np.asarray(cam.R, float)  # world_from_cam
        out[k] = R @ np.linalg.inv(K)  # pixel -> world ray
    return out


def M_inv_focal(M: np.ndarray) -> float:
    """The focal of K from M = R K^-1 (world ray of a pixel): K^-1 = R^T M, f = 1 / (K^-1)[0, 0]."""
    return 1.0 / np.linalg.norm(M[:, 0])


def camlab_mappings(result) -> dict:
    out = {}
    for k in range(len(result.names)):
        if result.cameras[k] is not None:
            K, R = result.cameras[k]
            out[k] = R.T @ np.linalg.inv(K)
        elif result.homographies[k] is not None:
            out[k] = result.homographies[k]
    return out


def independent_matches(images, pairs) -> dict:
    orb = cv2.ORB_create(3000)
    gray = [im if im.ndim == 2 else cv2.cvtColor(im, cv2.COLOR_RGB2GRAY) for im in images]
    kd = [orb.detectAndCompute(g, None) for g in gray]
    bf = cv2.BFMatcher(cv2.NORM_HAMMING)
    out = {}
    for i, j in pairs:
        (ki, di), (kj, dj) = kd[i], kd[j]
        good = [
            m
            for m, n in (p for p in bf.knnMatch(di, dj, k=2) if len(p) == 2)
            if m.distance < 0.75 * n.distance
        ]
        if len(good) < 20:
            continue
        a = np.array([ki[m.queryIdx].pt for m in good])
        b = np.array([kj[m.trainIdx].pt for m in good])
        H, inl = cv2.findHomography(a, b, cv2.RANSAC, 3.0)
        if H is not None and inl.sum() >= 20:
            out[(i, j)] = (a[inl.ravel() > 0], b[inl.ravel() > 0])
    return out


def transfer_median(maps: dict, matches: dict) -> float:
    errs = []
    for (i, j), (a, b) in matches.items():
        if i in maps and j in maps:
            M = np.linalg.inv(maps[j]) @ maps[i]
            p = np.c_[a, np.ones(len(a))] @ M.T
            errs.append(np.linalg.norm(p[:, :2] / p[:, 2:] - b, axis=1))
    return float(np.median(np.concatenate(errs))) if errs else float("nan")


STAGES = [
    "features",
    "matching",
    "estimation",
    "bundle_adjustment",
    "warping",
    "exposure",
    "seams",
    "compositing",
]


def rows(repeat: int = 5) -> list[dict]:
    cv2.setNumThreads(1)
    out, stages = [], []
    rows.load = [os.getloadavg()[0]]
    rows.adjustments = []
    for name, (images, names, f_true) in sets().items():
        mode, mode_name = cv_mode(images)
        tc, to, cc, co, tf, st_runs = [], [], [], [], [], []
        for _ in range(repeat):  # interleaved, so both see the same machine load
            t0, c0 = time.perf_counter(), time.process_time()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                res = st.stitch(images, names=names)
            tc.append(time.perf_counter() - t0)
            cc.append(time.process_time() - c0)
            st_runs.append(res.timings)
            t0, c0 = time.perf_counter(), time.process_time()
            stitcher, status, _ = cv_stitch(images, mode)
            to.append(time.perf_counter() - t0)
            co.append(time.process_time() - c0)
            t0 = time.perf_counter()
            cv_features(images)
            tf.append(time.perf_counter() - t0)
        rows.load.append(os.getloadavg()[0])
        rows.adjustments += [f"{name}: {line}" for line in res.adjustments]  # the last run's
        cam, ocv = 1e3 * float(np.median(tc)), 1e3 * float(np.median(to))
        pairs = [(i, j) for i in range(len(images)) for j in range(i + 1, len(images))]
        indep = independent_matches(images, pairs)
        cv_maps = (
            cv_mappings(stitcher, images)
            if status == cv2.Stitcher_OK and mode == cv2.Stitcher_PANORAMA
            else {}
        )
        e_cam, e_cv = transfer_median(camlab_mappings(res), indep), transfer_median(cv_maps, indep)
        f_cam = [round(float(c[0][0, 0]), 1) for c in res.cameras if c is not None]
        f_cv = [round(float(M_inv_focal(m)), 1) for m in cv_maps.values()]
        out.append(
            {
                "case": f"{name} ({len(images)} photos, {images[0].shape[1]}x{images[0].shape[0]})",
                "camlab_ms": cam,
                "opencv_ms": ocv,
                "ratio": cam / ocv,
                "target": f"<= {TARGET:g}x",
                "ok": cam / ocv <= TARGET and status == cv2.Stitcher_OK,
                "runs": ", ".join(f"{a / b:.2f}" for a, b in zip(tc, to, strict=True)),
                "cpu_ratio": float(np.median(cc) / np.median(co)),
                "camlab_px": e_cam,
                "opencv_px": e_cv,
                "model": f"{res.model}/{res.projection}",
                "opencv_mode": mode_name,
                "left_out": ", ".join(res.names[k] for k in res.unconnected) or "-",
                "f_camlab": f_cam or "-",
                "f_opencv": f_cv or "-",
                "f_true": f_true or "-",
            }
        )
        stages.append(
            {
                "set": name,
                **{k: 1e3 * float(np.median([t.get(k, 0.0) for t in st_runs])) for k in STAGES},
                "total": cam,
                "cv2_features": 1e3 * float(np.median(tf)),
                "cv2_total": ocv,
            }
        )
    rows.stages = stages
    return out


if __name__ == "__main__":
    r = rows()
    load = ", ".join(f"{x:.2f}" for x in rows.load)
    print_table(
        r,
        [
            "case",
            "camlab_ms",
            "opencv_ms",
            "ratio",
            "runs",
            "cpu_ratio",
            "target",
            "ok",
            "model",
            "opencv_mode",
            "left_out",
        ],
        title=f"camlab.stitch vs cv2.Stitcher, one thread (median ms; ratio per run; 1-min load {load})",
    )
    print_table(
        r,
        ["case", "camlab_px", "opencv_px", "f_camlab", "f_opencv", "f_true"],
        title="Transfer error on independent ORB matches (median px) and focal lengths (px)",
    )
    print_table(
        rows.stages,
        ["set"] + STAGES + ["total", "cv2_features", "cv2_total"],
        title="camlab per stage, and the Stitcher's features stage alone (ORB at 0.6 MP) and its total "
        "(median ms over the runs)",
    )
    print("\nBundle adjustment, last run of each set:")
    for line in rows.adjustments:
        print(f"  {line}")
