"""A battery of faults a user meets with the photo commands (calibrate, undistort, stitch, rectify).

Grown from a fault battery run by hand: outputs that would overwrite the inputs, a full disk, a
calibration from ROS, truncated photos, photos a phone stored sideways with an EXIF
orientation tag, phone-size photos, a flat scene given to ``rectify``, two panoramas in one
folder. Each case drives ``camlab.cli.main`` as a user would and is classified:

* ``clear``: refused with a clear message (exit 2 with one line naming the argument, or
  a photo skipped with a line naming it and why, exit 1), and nothing of the user's lost;
* ``handled``: it works, and the result is checked;

anything else is what went wrong (``traceback: ...``, ``exit 0, ...``), and fails the test.
Run ``python tests/test_fault_battery.py`` for the counts.

(The generated bad-argument battery over the library's functions is ``tests/test_battery.py``.)
"""

from __future__ import annotations

import collections
import contextlib
import errno
import io
import os
import shutil
import struct
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import NamedTuple

import cv2
import numpy as np
import pytest

from camlab.cli import main as camlab_main
from camlab.data import data_dir

PHOTOS = data_dir() / "photos"
CASES: dict[str, tuple[str, Callable[[Path], str]]] = {}


def case(expected: str):
    """Register a case (a function of a fresh folder returning its classification)."""

    def register(fn):
        CASES[fn.__name__] = (expected, fn)
        return fn

    return register


# --------------------------------------------------------------------------- running and judging


class Run(NamedTuple):
    code: int | None
    out: str
    err: str
    exc: BaseException | None


def run(*argv) -> Run:
    """``camlab ARGV`` in this process, with its output captured (and any exception kept)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code, exc = camlab_main([str(a) for a in argv]), None
        except BaseException as e:  # noqa: BLE001 - a traceback is one of the outcomes we classify
            code, exc = None, e
    return Run(code, out.getvalue(), err.getvalue(), exc)


def clear(r: Run, argument: str, *phrases: str) -> str:
    """``clear`` if the run stopped with exit 2 and one line ``camlab CMD: error: ARGUMENT: ...`` holding the phrases."""
    if r.exc is not None:
        return f"traceback: {type(r.exc).__name__}: {r.exc}"
    lines = r.err.strip().splitlines()
    if r.code != 2 or len(lines) != 1 or f": error: {argument}" not in lines[0]:
        return f"exit {r.code}, stderr {r.err.strip()[:300]!r}"
    missing = [p for p in phrases if p not in lines[0]]
    return "clear" if not missing else f"vague: {lines[0]!r} lacks {missing}"


def skipped(r: Run, name: str, reason: str) -> str:
    """``clear`` if the run went on without the photo ``name``, saying why, and exited 1."""
    if r.exc is not None:
        return f"traceback: {type(r.exc).__name__}: {r.exc}"
    said = any(name in ln and "skipped" in ln and reason in ln for ln in r.out.splitlines())
    if r.code != 1 or not said:
        return f"exit {r.code}, no line 'skipped: {reason}' for {name}: {r.out[-300:]!r}"
    return "clear"


def handled(r: Run, *checks: tuple[bool, str]) -> str:
    """``handled`` if the run ended without a traceback and every (ok, what) check holds."""
    if r.exc is not None:
        return f"traceback: {type(r.exc).__name__}: {r.exc}"
    failed = [what for ok, what in checks if not ok]
    return (
        "handled"
        if not failed
        else f"exit {r.code}, wrong: {failed}; stderr {r.err.strip()[:200]!r}"
    )


def also(outcome: str, ok: bool, what: str) -> str:
    """The outcome, unless a further check (e.g. the user's file is intact) fails."""
    return outcome if ok or outcome not in ("clear", "handled") else f"{outcome} but {what}"


# --------------------------------------------------------------------------- inputs


def copy_photos(folder: Path, *names: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    for n in names:
        shutil.copy(PHOTOS / n, folder / n)
    return folder


def calibration_file(
    path: Path, size=(640, 480), fmt: str = "opencv", model: str = "plumb_bob"
) -> Path:
    """A calibration of OpenCV's sample camera (the calib_left photos): OpenCV's FileStorage or ROS's camera_info."""
    K = np.array([[532.8, 0, 341.8], [0, 533.0, 234.1], [0, 0, 1]])
    d = np.array([-0.282, 0.044, 0.0011, -0.0003, 0.127])
    if fmt == "opencv":
        fs = cv2.FileStorage(str(path), cv2.FILE_STORAGE_WRITE)
        fs.write("image_width", size[0])
        fs.write("image_height", size[1])
        fs.write("camera_matrix", K)
        fs.write("distortion_coefficients", d.reshape(1, 5))
        fs.release()
    else:
        nums = lambda a: ", ".join(f"{v:g}" for v in np.ravel(a))  # noqa: E731
        path.write_text(
            f"image_width: {size[0]}\nimage_height: {size[1]}\ncamera_name: narrow_stereo\n"
            f"camera_matrix:\n  rows: 3\n  cols: 3\n  data: [{nums(K)}]\n"
            f"distortion_model: {model}\ndistortion_coefficients:\n  rows: 1\n  cols: 5\n  data: [{nums(d)}]\n"
            f"rectification_matrix:\n  rows: 3\n  cols: 3\n  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]\n"
        )
    return path


def with_orientation(jpeg: bytes, orientation: int) -> bytes:
    """The JPEG with an APP1 Exif segment holding only the orientation tag (0x0112) inserted after SOI."""
    tiff = (
        b"II*\x00"
        + struct.pack("<IH", 8, 1)
        + struct.pack("<HHIHH", 0x0112, 3, 1, orientation, 0)
        + struct.pack("<I", 0)
    )
    app1 = b"Exif\x00\x00" + tiff
    return jpeg[:2] + b"\xff\xe1" + struct.pack(">H", len(app1) + 2) + app1 + jpeg[2:]


def sideways(src: Path, dst: Path) -> Path:
    """``src`` stored turned 90 degrees anticlockwise, with orientation 6 (turn clockwise to view): as a phone does."""
    turned = cv2.rotate(cv2.imread(str(src)), cv2.ROTATE_90_COUNTERCLOCKWISE)
    dst.write_bytes(
        with_orientation(
            cv2.imencode(".jpg", turned, [cv2.IMWRITE_JPEG_QUALITY, 95])[1].tobytes(), 6
        )
    )
    return dst


def truncated(src: Path, dst: Path) -> Path:
    data = src.read_bytes()
    dst.write_bytes(data[: len(data) * 2 // 3])  # the end-of-image marker is lost
    return dst


def planar_pair(folder: Path, baseline: float = 0.0) -> tuple[Path, Path]:
    """A photo of a flat sign and the view of that plane from a camera moved ``baseline`` (plane distance 1) sideways and turned."""
    img = cv2.imread(str(PHOTOS / "castle_sign.jpg"))
    h, w = img.shape[:2]
    K = np.array([[700.0, 0, (w - 1) / 2], [0, 700.0, (h - 1) / 2], [0, 0, 1]])
    a = 0.08
    R = np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])
    t, n = np.array([-baseline, 0, 0]), np.array([0, 0, 1.0])  # plane z = 1 in camera 1
    H = K @ (R + np.outer(t, n)) @ np.linalg.inv(K)
    folder.mkdir(parents=True, exist_ok=True)
    left, right = folder / "left.png", folder / "right.png"
    cv2.imwrite(str(left), img)
    cv2.imwrite(str(right), cv2.warpPerspective(img, H, (w, h)))
    return left, right


@contextlib.contextmanager
def patched(obj, name: str, value):
    old = getattr(obj, name)
    setattr(obj, name, value)
    try:
        yield
    finally:
        setattr(obj, name, old)


def disk_full(*args, **kwargs):
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


CALIBRATE = ("--pattern", "9x6", "--square", "0.025")
THREE = ("calib_left01.jpg", "calib_left02.jpg", "calib_left03.jpg")


# --------------------------------------------------------------------------- outputs that would overwrite inputs


@case("clear")
def undistort_into_the_photo_folder(d: Path) -> str:
    photos = copy_photos(d / "photos", "calib_left01.jpg")
    before = (photos / "calib_left01.jpg").read_bytes()
    r = run(
        "undistort",
        photos / "calib_left01.jpg",
        "--calibration",
        calibration_file(d / "cal.yaml"),
        "--out-dir",
        photos / ".." / "photos",
    )  # the same folder, spelt differently
    return also(
        clear(r, "--out-dir", "would overwrite the input photo", "--out-dir"),
        (photos / "calib_left01.jpg").read_bytes() == before,
        "the photo changed",
    )


@case("clear")
def stitch_out_names_a_photo(d: Path) -> str:
    photos = copy_photos(d / "photos", "aerial_1.jpg", "aerial_2.jpg")
    before = (photos / "aerial_2.jpg").read_bytes()
    r = run("stitch", photos, "--out", photos / "aerial_2.jpg")
    return also(
        clear(r, "--out", "would overwrite the input photo"),
        (photos / "aerial_2.jpg").read_bytes() == before,
        "the photo changed",
    )


@case("clear")
def stitch_out_is_last_runs_panorama_in_the_folder(d: Path) -> str:
    photos = copy_photos(d / "photos", "aerial_1.jpg", "aerial_2.jpg")
    shutil.copy(
        photos / "aerial_1.jpg", photos / "pano.jpg"
    )  # a panorama from an earlier run, now an input
    return clear(run("stitch", photos, "--out", photos / "pano.jpg"), "--out", "pano.jpg")


@case("clear")
def calibrate_report_names_a_photo(d: Path) -> str:
    photos = copy_photos(d / "photos", *THREE)
    before = (photos / THREE[0]).read_bytes()
    os.link(photos / THREE[0], d / "link.jpg")  # a hard link is the same file under another name
    r = run(
        "calibrate",
        *(photos / n for n in THREE),
        *CALIBRATE,
        "--out",
        d / "cal.json",
        "--report",
        d / "link.jpg",
    )
    return also(
        clear(r, "--report", "would overwrite the input photo"),
        (photos / THREE[0]).read_bytes() == before and not (d / "cal.json").exists(),
        "a file changed",
    )


@case("clear")
def rectify_out_dir_holds_the_inputs_names(d: Path) -> str:
    shutil.copy(PHOTOS / "walls_left.jpg", d / "left_rectified.png")
    return clear(
        run("rectify", d / "left_rectified.png", PHOTOS / "walls_right.jpg", "--out-dir", d),
        "--out-dir",
        "would overwrite",
    )


# --------------------------------------------------------------------------- a full disk


def _calibrate_over_a_good_file(d: Path, *patches) -> tuple[Run, bytes, Path]:
    photos = copy_photos(d / "photos", *THREE)
    out = d / "cal.yaml"
    calibration_file(out)
    good = out.read_bytes()
    with contextlib.ExitStack() as stack:
        for p in patches:
            stack.enter_context(p)
        r = run("calibrate", photos / "*.jpg", *CALIBRATE, "--out", out, "--no-report")
    return r, good, out


@case("clear")
def calibrate_out_disk_full_on_fsync(d: Path) -> str:
    r, good, out = _calibrate_over_a_good_file(d, patched(os, "fsync", disk_full))
    return also(
        clear(r, "--out", "No space left on device", "unchanged"),
        out.read_bytes() == good and "wrote" not in r.out,
        "the old calibration was replaced",
    )


@case("clear")
def calibrate_out_disk_full_opencv_writes_an_empty_file(d: Path) -> str:
    import camlab.calibration.io as cio

    r, good, out = _calibrate_over_a_good_file(
        d, patched(cio, "_write", lambda fs, result: fs.release())
    )
    return also(
        clear(r, "--out", "does not read back", "unchanged"),
        out.read_bytes() == good,
        "the old calibration was replaced",
    )


@case("clear")
def calibrate_out_disk_full_leaves_zero_bytes(d: Path) -> str:
    import camlab.calibration.io as cio

    def nothing(fs, result):
        fs.release()
        Path(fs_path[0]).write_bytes(b"")

    fs_path = []
    real = cv2.FileStorage
    keep = lambda path, mode: (fs_path.append(path), real(path, mode))[1]  # noqa: E731
    r, good, out = _calibrate_over_a_good_file(
        d, patched(cio, "_write", nothing), patched(cv2, "FileStorage", keep)
    )
    return also(
        clear(r, "--out", "0 bytes", "unchanged"),
        out.read_bytes() == good and not [p for p in d.iterdir() if p.name.startswith(".cal")],
        "a file was replaced or left behind",
    )


@case("clear")
def calibrate_report_disk_full(d: Path) -> str:
    from matplotlib.figure import Figure

    photos = copy_photos(d / "photos", *THREE)
    with patched(Figure, "savefig", disk_full):
        r = run(
            "calibrate",
            photos / "*.jpg",
            *CALIBRATE,
            "--out",
            d / "cal.json",
            "--report",
            d / "r.png",
        )
    return also(
        clear(r, "--report", "No space left on device"),
        not (d / "cal.json").exists() and not (d / "r.png").exists(),
        "files were left behind",
    )


@case("clear")
def undistort_disk_full(d: Path) -> str:
    (d / "out").mkdir()
    with patched(os, "fsync", disk_full):
        r = run(
            "undistort",
            PHOTOS / "calib_left01.jpg",
            "--calibration",
            calibration_file(d / "cal.yaml"),
            "--out-dir",
            d / "out",
        )
    return also(
        clear(r, "--out-dir", "No space left"),
        not list((d / "out").iterdir()),
        "a file was left behind",
    )


@case("handled")
def written_files_respect_the_umask(d: Path) -> str:
    photos = copy_photos(d / "photos", *THREE)
    old = os.umask(0o002)  # a shared folder: group may write
    try:
        r = run(
            "calibrate",
            photos / "*.jpg",
            *CALIBRATE,
            "--out",
            d / "cal.json",
            "--report",
            d / "r.png",
        )
    finally:
        os.umask(old)
    modes = {p.name: p.stat().st_mode & 0o777 for p in (d / "cal.json", d / "r.png") if p.exists()}
    return handled(
        r, (modes == {"cal.json": 0o664, "r.png": 0o664}, f"modes {modes}, expected 0o664")
    )


# --------------------------------------------------------------------------- calibration files


@case("handled")
def undistort_with_a_ros_calibration(d: Path) -> str:
    for fmt in ("opencv", "ros"):
        (d / fmt).mkdir()
        r = run(
            "undistort",
            PHOTOS / "calib_left01.jpg",
            "--calibration",
            calibration_file(d / f"{fmt}.yaml", fmt=fmt),
            "--out-dir",
            d / fmt,
        )
        if r.code != 0:
            return handled(r, (False, "exit 0"))
    a, b = (cv2.imread(str(d / f / "calib_left01.jpg")) for f in ("opencv", "ros"))
    return handled(
        r,
        (
            a is not None and b is not None and np.array_equal(a, b),
            "the same image as with OpenCV's file",
        ),
    )


@case("clear")
def undistort_with_a_fisheye_ros_calibration(d: Path) -> str:
    r = run(
        "undistort",
        PHOTOS / "calib_left01.jpg",
        "--calibration",
        calibration_file(d / "ros.yaml", fmt="ros", model="equidistant"),
        "--out-dir",
        d,
    )
    return clear(r, "--calibration", "'equidistant' distortion model")


@case("clear")
def undistort_with_a_yaml_that_is_no_calibration(d: Path) -> str:
    (d / "cal.yaml").write_text("camera_matrix: {a: 1}\n")
    r = run(
        "undistort", PHOTOS / "calib_left01.jpg", "--calibration", d / "cal.yaml", "--out-dir", d
    )
    return clear(r, "--calibration", "camera_matrix", "ROS")


# --------------------------------------------------------------------------- truncated photos


@case("clear")
def undistort_a_truncated_jpeg(d: Path) -> str:
    bad = truncated(PHOTOS / "calib_left01.jpg", d / "cut.jpg")
    (d / "out").mkdir()
    r = run(
        "undistort",
        bad,
        PHOTOS / "calib_left02.jpg",
        "--calibration",
        calibration_file(d / "cal.yaml"),
        "--out-dir",
        d / "out",
    )
    return also(
        skipped(r, "cut.jpg", "truncated JPEG"),
        not (d / "out" / "cut.jpg").exists() and (d / "out" / "calib_left02.jpg").exists(),
        "the wrong files were written",
    )


@case("clear")
def stitch_a_truncated_jpeg(d: Path) -> str:
    photos = copy_photos(d / "photos", "aerial_1.jpg", "aerial_2.jpg")
    truncated(PHOTOS / "aerial_3.jpg", photos / "aerial_3.jpg")
    r = run("stitch", photos, "--out", d / "pano.jpg", "--max-megapixels", "0.3")
    return also(
        skipped(r, "aerial_3.jpg", "truncated JPEG"),
        "left out: aerial_3.jpg" in r.out,
        "not listed as left out",
    )


@case("clear")
def rectify_a_truncated_jpeg(d: Path) -> str:
    bad = truncated(PHOTOS / "walls_right.jpg", d / "right.jpg")
    return clear(
        run("rectify", PHOTOS / "walls_left.jpg", bad, "--out-dir", d),
        "right",
        "right.jpg",
        "truncated JPEG",
    )


@case("clear")
def calibrate_an_empty_file_and_a_folder(d: Path) -> str:
    photos = copy_photos(d / "photos", *THREE)
    (photos / "empty.jpg").write_bytes(b"")
    (photos / "folder.jpg").mkdir()
    r = run("calibrate", photos / "*.jpg", *CALIBRATE, "--out", d / "cal.json", "--no-report")
    return also(
        skipped(r._replace(code=1), "empty.jpg", "empty (0 bytes)"),
        r.code == 0 and "folder.jpg: skipped: could not read the file" in r.out,
        "the folder was not named",
    )


# --------------------------------------------------------------------------- EXIF orientation


@case("handled")
def calibrate_and_undistort_photos_stored_sideways(d: Path) -> str:
    """Calibrated from photos a phone stored sideways, undistort takes them and writes them upright."""
    names = ["calib_left01.jpg", "calib_left02.jpg", "calib_left03.jpg", "calib_left04.jpg"]
    for n in names:
        sideways(PHOTOS / n, copy_photos(d / "phone").joinpath(n))
    (d / "out").mkdir()
    r = run(
        "calibrate",
        d / "phone" / "*.jpg",
        *CALIBRATE,
        "--fix-k3",
        "--out",
        d / "cal.yaml",
        "--no-report",
    )
    if r.code != 0:
        return handled(r, (False, "calibrate exit 0"))
    r = run(
        "undistort", d / "phone" / "*.jpg", "--calibration", d / "cal.yaml", "--out-dir", d / "out"
    )
    (d / "ref").mkdir()
    run("undistort", PHOTOS / names[0], "--calibration", d / "cal.yaml", "--out-dir", d / "ref")
    out = cv2.imread(
        str(d / "out" / names[0]), cv2.IMREAD_UNCHANGED
    )  # UNCHANGED: it must not need a tag to show upright
    ref = cv2.imread(str(d / "ref" / names[0]))  # the upright original, undistorted the same way
    like = out is not None and out.shape == ref.shape and np.abs(out.astype(int) - ref).mean() < 3
    return handled(r, (r.code == 0, "exit 0"), (like, "the undistorted photo is upright"))


@case("clear")
def undistort_with_a_calibration_from_too_few_views(d: Path) -> str:
    """Four views without --fix-k3: k3 is wild, and the model cannot be inverted at the photo's corners."""
    photos = copy_photos(d / "photos", *THREE, "calib_left04.jpg")
    run("calibrate", photos / "*.jpg", *CALIBRATE, "--out", d / "cal.yaml", "--no-report")
    r = run(
        "undistort", photos / "calib_left01.jpg", "--calibration", d / "cal.yaml", "--out-dir", d
    )
    return clear(r, "--calibration", "cannot be undone", "--fix-k3")


@case("handled")
def stitch_a_photo_stored_sideways(d: Path) -> str:
    photos = copy_photos(d / "photos", "aerial_1.jpg")
    sideways(PHOTOS / "aerial_2.jpg", photos / "aerial_2.jpg")
    r = run("stitch", photos, "--out", d / "pano.jpg", "--projection", "planar")
    return handled(r, (r.code == 0 and "2 of 2 photos used" in r.out, "both photos stitched"))


@case("handled")
def rectify_photos_stored_sideways(d: Path) -> str:
    left, right = (
        sideways(PHOTOS / "walls_left.jpg", d / "l.jpg"),
        sideways(PHOTOS / "walls_right.jpg", d / "r.jpg"),
    )
    (d / "out").mkdir()
    r = run("rectify", left, right, "--out-dir", d / "out")
    out = cv2.imread(str(d / "out" / "left_rectified.png"))
    return handled(
        r,
        (r.code == 0, "exit 0"),
        (
            out is not None and out.shape == cv2.imread(str(PHOTOS / "walls_left.jpg")).shape,
            "rectified photos upright (816 x 612)",
        ),
    )


# --------------------------------------------------------------------------- phone-size photos


@case("handled")
def calibrate_24_megapixel_photos(d: Path) -> str:
    """Three photos upscaled 7.5 times (4800 x 3600): OpenCV alone searches one for two minutes and misses the board."""
    f = 7.5
    (d / "big").mkdir()
    for n in THREE:
        big = cv2.resize(
            cv2.imread(str(PHOTOS / n), cv2.IMREAD_GRAYSCALE),
            None,
            fx=f,
            fy=f,
            interpolation=cv2.INTER_CUBIC,
        )
        cv2.imwrite(str(d / "big" / n), big)
    r = run("calibrate", d / "big" / "*.jpg", *CALIBRATE, "--out", d / "big.json", "--no-report")
    small = run(
        "calibrate",
        *(PHOTOS / n for n in THREE),
        *CALIBRATE,
        "--out",
        d / "small.json",
        "--no-report",
    )
    if r.code != 0 or small.code != 0:
        return handled(r, (False, f"exit 0 (got {r.code}, {small.code})"))
    from camlab.calibration import load_calibration

    K_big, K_small = load_calibration(d / "big.json")[0], load_calibration(d / "small.json")[0]
    fx_back = (K_big[0, 0]) / f  # focal lengths scale with the image
    return handled(
        r,
        (r.out.count("board found") == 3, "the board found in 3 of 3"),
        (
            abs(fx_back / K_small[0, 0] - 1) < 0.01,
            f"fx {K_big[0, 0]:.1f} = 7.5 x {K_small[0, 0]:.1f} within 1%",
        ),
    )


@case("handled")
def stitch_photos_above_the_work_size(d: Path) -> str:
    photos = copy_photos(d / "photos", "aerial_1.jpg", "aerial_2.jpg")
    r = run(
        "stitch",
        photos,
        "--out",
        d / "pano.jpg",
        "--max-megapixels",
        "0.3",
        "--projection",
        "planar",
    )
    pano = cv2.imread(str(d / "pano.jpg"))
    return handled(
        r,
        (
            r.code == 0
            and r.out.count("worked on at") == 2
            and "900 x 720 px (1 MP), worked on at 612 x 490" in r.out,
            "both photos shrunk, saying so",
        ),
        (
            pano is not None and 1.2 * 0.3e6 < pano.shape[0] * pano.shape[1] < 2 * 0.3e6,
            "a panorama at the work size",
        ),
    )


# --------------------------------------------------------------------------- scenes the geometry cannot handle


@case("clear")
def rectify_a_flat_scene(d: Path) -> str:
    left, right = planar_pair(d, baseline=0.2)
    return also(
        clear(
            run("rectify", left, right, "--out-dir", d), "left, right", "one plane", "--calibration"
        ),
        not (d / "left_rectified.png").exists(),
        "an output was written",
    )


@case("handled")
def rectify_a_flat_scene_with_its_calibration(d: Path) -> str:
    left, right = planar_pair(d, baseline=0.2)
    h, w = cv2.imread(str(left)).shape[:2]
    fs = cv2.FileStorage(str(d / "cal.yaml"), cv2.FILE_STORAGE_WRITE)
    for k, v in (
        ("image_width", w),
        ("image_height", h),
        ("camera_matrix", np.array([[700.0, 0, (w - 1) / 2], [0, 700.0, (h - 1) / 2], [0, 0, 1]])),
        ("distortion_coefficients", np.zeros((1, 5))),
    ):
        fs.write(k, v)
    fs.release()
    (d / "out").mkdir()
    r = run("rectify", left, right, "--calibration", d / "cal.yaml", "--out-dir", d / "out")
    after = float(r.out.split(" px after")[0].split()[-1]) if " px after" in r.out else np.inf
    return handled(
        r, (r.code == 0, "exit 0"), (after < 0.5, f"vertical disparity after {after} px < 0.5")
    )


@case("handled")
def stitch_a_folder_of_two_panoramas(d: Path) -> str:
    photos = copy_photos(
        d / "photos", "aerial_1.jpg", "aerial_2.jpg", "rocks_left.jpg", "rocks_right.jpg"
    )
    r = run("stitch", photos, "--out", d / "pano.jpg", "--max-megapixels", "0.3")
    return handled(
        r,
        (r.code == 1, "exit 1 (photos left out)"),
        (
            "2 separate groups of overlapping photos" in r.out
            and "overlap each other" in r.out
            and "overlaps none" not in r.out,
            "both groups named",
        ),
    )


# --------------------------------------------------------------------------- the battery


@pytest.mark.parametrize("name", sorted(CASES))
def test_fault(name, tmp_path):
    expected, fn = CASES[name]
    assert fn(tmp_path) == expected


def main() -> int:
    """Run every case; print each outcome and the counts by outcome."""
    counts: collections.Counter = collections.Counter()
    for name in sorted(CASES):
        expected, fn = CASES[name]
        with tempfile.TemporaryDirectory() as d:
            outcome = fn(Path(d))
        kind = outcome if outcome in ("clear", "handled") else "wrong"
        counts[kind] += 1
        print(
            f"{kind:8} {name}"
            + ("" if kind != "wrong" else f": {outcome}")
            + ("" if outcome == expected or kind == "wrong" else f" (expected {expected})")
        )
    print(", ".join(f"{k}: {v}" for k, v in sorted(counts.items())), f"(of {len(CASES)} cases)")
    return 0 if counts["wrong"] == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
