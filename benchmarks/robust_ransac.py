"""camlab's robust estimation (LO-RANSAC, MSAC scoring) against OpenCV on real photo pairs, across seeds.

Run: ``python benchmarks/robust_ransac.py [--seeds 20]``. For each shipped pair of real
photographs (``data/photos/building_*.jpg``: one building from three viewpoints, two
facades at an angle, so several planes compete) SIFT matches are computed once, then

* ``ransac_homography`` runs with ``seeds`` different seeds (threshold 3 px, confidence
  0.995, at most 2000 samples: OpenCV's defaults);
* ``cv2.findHomography`` runs with RANSAC and USAC_MAGSAC at the same threshold, each
  time after ``cv2.setRNGSeed(seed)``.

Columns: inlier counts (min / median / max over seeds), the RMS symmetric transfer error
of each method's own inliers (median over seeds, px), the MSAC cost
sum(min(e, 3 px)^2) of each method's model on all pairs (lower is better; the same
measure for all three), and median times with camlab's ratio to OpenCV's RANSAC (calls
timed alternately, so both see the same load on a shared machine).

"few" cases keep only the 300 strongest SIFT keypoints and a loose ratio test (0.9): few
matches, many of them wrong, the hard case. The last table runs
``ransac_fundamental_matrix`` on the real stereo pairs and on the same matches with
``x2`` shuffled (all wrong), where it must raise ``DegenerateError``.
"""

from __future__ import annotations

import argparse
import sys
from functools import partial
from pathlib import Path

import cv2
import numpy as np

sys.path.insert(0, str(Path(__file__).parent))

from _timing import print_table, timed  # noqa: E402

from camlab._validate import DegenerateError
from camlab.data import load_photo
from camlab.epipolar import ransac_fundamental_matrix
from camlab.features import detect_features, match_features
from camlab.homography import ransac_homography, symmetric_transfer_error

THRESHOLD = 3.0
PAIRS = [("building_1", "building_2"), ("building_1", "building_3"), ("building_2", "building_3")]
SETTINGS = {"all": (2500, 0.8), "few": (300, 0.9)}


def matches(a: str, b: str, max_features: int, ratio: float) -> tuple[np.ndarray, np.ndarray]:
    m = match_features(
        detect_features(load_photo(a), max_features=max_features),
        detect_features(load_photo(b), max_features=max_features),
        ratio,
    )
    return m.src, m.dst


def _quality(H: np.ndarray, src: np.ndarray, dst: np.ndarray) -> tuple[int, float, float]:
    """(inliers, RMS error of the inliers in px, MSAC cost on all pairs) of one model, one measure for all."""
    e = symmetric_transfer_error(H, src, dst)
    inl = e < THRESHOLD
    return (
        int(inl.sum()),
        float(np.sqrt(np.mean(e[inl] ** 2))),
        float(np.sum(np.minimum(e, THRESHOLD) ** 2)),
    )


def homography_row(case: str, src: np.ndarray, dst: np.ndarray, seeds: int) -> dict:
    runs = {"camlab": [], "RANSAC": [], "MAGSAC": []}
    times = {"camlab": [], "RANSAC": []}
    for seed in range(seeds):
        fit, seconds = timed(partial(ransac_homography, src, dst, THRESHOLD, rng=seed))
        times["camlab"].append(seconds)
        runs["camlab"].append(_quality(fit.H, src, dst))
        for name, method in (("RANSAC", cv2.RANSAC), ("MAGSAC", cv2.USAC_MAGSAC)):
            cv2.setRNGSeed(seed)
            (H, _), seconds = timed(partial(cv2.findHomography, src, dst, method, THRESHOLD))
            if name == "RANSAC":
                times[name].append(seconds)
            runs[name].append(_quality(H, src, dst))
    row = {"case": case, "N": len(src)}
    for name, q in runs.items():
        q = np.array(q)
        row[f"{name} inliers"] = (
            f"{q[:, 0].min():.0f} / {np.median(q[:, 0]):.0f} / {q[:, 0].max():.0f}"
        )
        row[f"{name} rms px"] = f"{np.median(q[:, 1]):.2f}"
        row[f"{name} MSAC"] = f"{np.median(q[:, 2]):.0f}"
    ratio = np.array(times["camlab"]) / np.array(times["RANSAC"])
    row["camlab ms"] = f"{1e3 * np.median(times['camlab']):.1f}"
    row["RANSAC ms"] = f"{1e3 * np.median(times['RANSAC']):.2f}"
    row["ratio"] = f"{np.median(ratio):.1f}x"
    return row


def fundamental_rows(seeds: int) -> list[dict]:
    rows = []
    for a, b in (("walls_left", "walls_right"), ("rocks_left", "rocks_right")):
        x1, x2 = matches(a, b, 2500, 0.8)
        counts, times, cv_times = [], [], []
        for seed in range(seeds):
            fit, seconds = timed(partial(ransac_fundamental_matrix, x1, x2, 1.0, rng=seed))
            counts.append(int(fit.inliers.sum()))
            times.append(seconds)
            (_, mask), seconds = timed(
                partial(cv2.findFundamentalMat, x1, x2, cv2.FM_RANSAC, 1.0, 0.999)
            )
            cv_times.append(seconds)
        magsac = cv2.findFundamentalMat(x1, x2, cv2.USAC_MAGSAC, 1.0, 0.999)[1]
        wrong = x2[np.random.default_rng(0).permutation(len(x2))]
        try:
            ransac_fundamental_matrix(x1, wrong, 1.0, rng=0)
            shuffled = "returned a model (wrong)"
        except DegenerateError as exc:
            shuffled = "DegenerateError: " + str(exc).split(": ")[1]
        cv_wrong = cv2.findFundamentalMat(x1, wrong, cv2.FM_RANSAC, 1.0, 0.999)[1]
        rows.append(
            {
                "pair": f"{a}/{b}",
                "N": len(x1),
                "camlab inliers": f"{min(counts)} / {np.median(counts):.0f} / {max(counts)}",
                "cv RANSAC": int(mask.sum()),
                "cv MAGSAC": int(magsac.sum()),
                "camlab ms": f"{1e3 * np.median(times):.1f}",
                "cv ms": f"{1e3 * np.median(cv_times):.1f}",
                "all wrong: camlab": shuffled,
                "all wrong: cv RANSAC": "no model"
                if cv_wrong is None
                else f"{int(cv_wrong.sum())} inliers",
            }
        )
    return rows


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=20)
    args = parser.parse_args(argv)
    rows = []
    for a, b in PAIRS:
        for label, (nf, ratio) in SETTINGS.items():
            src, dst = matches(a, b, nf, ratio)
            rows.append(homography_row(f"{a[-1]}->{b[-1]} {label}", src, dst, args.seeds))
    print_table(
        rows,
        title=f"Homography on real photo pairs, {args.seeds} seeds, threshold {THRESHOLD} px "
        f"(inliers min / median / max)",
    )
    print_table(
        fundamental_rows(args.seeds),
        title=f"Fundamental matrix on real stereo pairs, {args.seeds} seeds, 1 px",
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
