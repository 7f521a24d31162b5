"""The CLI and chessboard detection on the real calibration photos (data/photos/calib_left*.jpg, 9x6)."""

from __future__ import annotations

import shutil

import cv2
import numpy as np
import pytest

from camlab.calibration import find_chessboard, load_calibration
from camlab.cli import main
from camlab.data import data_dir, load_photo


@pytest.fixture(scope="module")
def photos(tmp_path_factory):
    """The 14 real views, plus a truncated JPEG, a text file named .jpg and a photo of another size."""
    d = tmp_path_factory.mktemp("photos")
    for p in sorted((data_dir() / "photos").glob("calib_left*.jpg")):
        shutil.copy(p, d / p.name)
    (d / "truncated.jpg").write_bytes((d / "calib_left03.jpg").read_bytes()[:15000])
    (d / "notes.jpg").write_text("not a photo\n")
    shutil.copy(data_dir() / "photos" / "street.jpg", d / "zz_street.jpg")
    return d


def test_calibrate_real_photos_names_each_failure(photos, tmp_path, capsys):
    out, rep = tmp_path / "cam.json", tmp_path / "report.png"
    assert (
        main(
            [
                "calibrate",
                str(photos / "*.jpg"),
                "--pattern",
                "9x6",
                "--square",
                "0.025",
                "--out",
                str(out),
                "--report",
                str(rep),
            ]
        )
        == 0
    )
    text = capsys.readouterr().out
    assert (
        text.count("board found") == 14 and "[17/17]" in text
    )  # a line per image (not a terminal)
    assert (
        "truncated JPEG" in text
        and "not an image format" in text
        and "differs from the other images" in text
    )
    K, _, size = load_calibration(out)
    assert size == (640, 480)
    assert 520 < K[0, 0] < 545 and 520 < K[1, 1] < 545  # OpenCV's sample camera: fx ~ 533 px
    assert rep.stat().st_size > 10_000


@pytest.mark.parametrize("flag", ["--out", "--report"])
def test_unwritable_output_fails_first_with_one_line_and_writes_nothing(
    photos, tmp_path, capsys, flag
):
    paths = {"--out": str(tmp_path / "cam.json"), "--report": str(tmp_path / "r.png")}
    paths[flag] = (
        "/proc/camlab-no-such-dir/x.json" if flag == "--out" else "/proc/camlab-no-such-dir/x.png"
    )
    code = main(
        [
            "calibrate",
            str(photos / "calib_left0*.jpg"),
            "--pattern",
            "9x6",
            "--square",
            "0.025",
            "--out",
            paths["--out"],
            "--report",
            paths["--report"],
        ]
    )
    cap = capsys.readouterr()
    assert (
        code == 2
        and cap.err.count("\n") == 1
        and cap.err.startswith(f"camlab calibrate: error: {flag}:")
    )
    assert "board found" not in cap.out and list(tmp_path.iterdir()) == []


def test_undistort_real_photos(photos, tmp_path, capsys):
    cal = tmp_path / "cam.json"
    assert (
        main(
            [
                "calibrate",
                str(photos / "calib_left*.jpg"),
                "--pattern",
                "9x6",
                "--square",
                "0.025",
                "--out",
                str(cal),
                "--no-report",
            ]
        )
        == 0
    )
    out = tmp_path / "und"
    out.mkdir()
    assert (
        main(
            [
                "undistort",
                str(photos / "calib_left01.jpg"),
                "--calibration",
                str(cal),
                "--out-dir",
                str(out),
            ]
        )
        == 0
    )
    und = cv2.imread(str(out / "calib_left01.jpg"), cv2.IMREAD_GRAYSCALE)
    src = load_photo("calib_left01", gray=True)
    assert und.shape == src.shape and np.abs(und.astype(int) - src).mean() > 2  # the image changed

    # The board's corners lie closer to straight lines after undistortion.
    def straightness(img):
        c = find_chessboard(img, (9, 6)).corners.reshape(6, 9, 2)
        res = []
        for row in c:
            A = np.c_[row[:, 0], np.ones(9)]
            res.append(np.abs(A @ np.linalg.lstsq(A, row[:, 1], rcond=None)[0] - row[:, 1]).max())
        return max(res)

    assert straightness(und) < 0.5 * straightness(src)
    # A photo of another size is skipped and reported: exit status 1.
    assert (
        main(
            [
                "undistort",
                str(photos / "zz_street.jpg"),
                "--calibration",
                str(cal),
                "--out-dir",
                str(out),
            ]
        )
        == 1
    )
    assert "calibration is for 640 x 480" in capsys.readouterr().out
    # A calibration file that is not one: exit 2, one line.
    (tmp_path / "bad.json").write_text("hello\n")
    assert (
        main(
            [
                "undistort",
                str(photos / "calib_left01.jpg"),
                "--calibration",
                str(tmp_path / "bad.json"),
                "--out-dir",
                str(out),
            ]
        )
        == 2
    )


def test_undistort_help_exits_0(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["undistort", "--help"])
    assert exc.value.code == 0 and "--calibration" in capsys.readouterr().out


@pytest.mark.parametrize(
    "view, change, detector",
    [
        (
            "calib_left01",
            lambda a: cv2.resize(a, None, fx=0.35, fy=0.35, interpolation=cv2.INTER_AREA),
            "classic",
        ),
        ("calib_left09", lambda a: cv2.GaussianBlur(a, (0, 0), 3), "SB"),
    ],
)
def test_a_board_opencv_finds_is_never_rejected(view, change, detector):
    img = change(load_photo(view, gray=True))
    flags = cv2.CALIB_CB_ADAPTIVE_THRESH | cv2.CALIB_CB_NORMALIZE_IMAGE | cv2.CALIB_CB_FAST_CHECK
    assert not cv2.findChessboardCorners(img, (9, 6), flags=flags)[
        0
    ]  # the fast check alone rejects it
    det = find_chessboard(img, (9, 6))
    assert det.found and det.detector == detector and det.corners.shape == (54, 2)


def test_no_board_is_not_called_a_cut_off_board():
    for name in ("street", "building_1", "church"):
        reason = find_chessboard(load_photo(name), (9, 6)).reason
        assert reason.startswith("no ") and "cut off" not in reason, (name, reason)


def _real(name):
    return str(data_dir() / "photos" / name)


def test_stitch_a_folder_of_real_photos_names_the_photo_left_out(tmp_path, capsys):
    folder = tmp_path / "trip"
    folder.mkdir()
    for name in ("aerial_1.jpg", "aerial_2.jpg", "church.jpg"):
        shutil.copy(_real(name), folder / name)
    (folder / "notes.txt").write_text("not a photo")  # ignored: not an image file
    out = tmp_path / "pano.jpg"
    assert (
        main(["stitch", str(folder), "--out", str(out), "--projection", "planar"]) == 1
    )  # one photo left out
    text = capsys.readouterr().out
    assert "aerial_1.jpg - aerial_2.jpg" in text and "'church.jpg' overlaps none" in text
    assert "2 of 3 photos used; left out: church.jpg" in text and "planar canvas" in text
    pano, one = cv2.imread(str(out)), cv2.imread(_real("aerial_1.jpg"))
    # The ground is flat, so the plane's homography is the model, with aerial_1 as the reference
    # at its own scale; aerial_2 was taken from higher up (its ground is 0.88 times as large) and
    # adds a band along two sides: the canvas outgrows the photo both ways, and more is covered.
    assert pano.shape[0] > 1.05 * one.shape[0] and pano.shape[1] > 1.05 * one.shape[1]
    covered = np.count_nonzero(pano.max(axis=2) > 8)
    assert covered > 1.03 * one.shape[0] * one.shape[1]  # more ground than one photo


def test_stitch_checks_out_before_work_and_needs_two_photos(tmp_path, capsys):
    assert (
        main(
            [
                "stitch",
                _real("aerial_1.jpg"),
                _real("aerial_2.jpg"),
                "--out",
                str(tmp_path / "no" / "p.jpg"),
            ]
        )
        == 2
    )
    assert main(["stitch", _real("aerial_1.jpg"), "--out", str(tmp_path / "p.jpg")]) == 2
    err = capsys.readouterr().err
    assert "--out: the folder" in err and "need at least two readable photos, got 1" in err
    assert not list(tmp_path.iterdir())


def test_rectify_a_real_stereo_pair(tmp_path, capsys):
    assert (
        main(
            [
                "rectify",
                _real("walls_left.jpg"),
                _real("walls_right.jpg"),
                "--out-dir",
                str(tmp_path),
            ]
        )
        == 0
    )
    text = capsys.readouterr().out
    before, after = (
        float(x)
        for x in text.split("vertical disparity median ")[1]
        .split(" px after")[0]
        .split(" px before, ")
    )
    assert before > 5 and after < 0.5  # rows line up after rectification
    left, right = (cv2.imread(str(tmp_path / f"{k}_rectified.png")) for k in ("left", "right"))
    assert left.shape == right.shape == cv2.imread(_real("walls_left.jpg")).shape
    assert (tmp_path / "vertical_disparity.png").stat().st_size > 5_000


def test_rectify_names_bad_input(tmp_path, capsys):
    assert (
        main(["rectify", _real("walls_left.jpg"), _real("church.jpg"), "--out-dir", str(tmp_path)])
        == 2
    )
    (tmp_path / "x").write_text("")  # a missing --out-dir is created; a file is not a folder
    assert (
        main(
            [
                "rectify",
                _real("walls_left.jpg"),
                _real("walls_right.jpg"),
                "--out-dir",
                str(tmp_path / "x"),
            ]
        )
        == 2
    )
    err = capsys.readouterr().err
    assert (
        "right: expected the left photo's size 816 x 612, got 800 x 532" in err
        and "is a file, not a folder" in err
    )
    assert [p.name for p in tmp_path.iterdir()] == ["x"]


@pytest.mark.parametrize("command", ["stitch", "rectify"])
def test_help(command, capsys):
    with pytest.raises(SystemExit) as exit_:
        main([command, "--help"])
    assert exit_.value.code == 0 and "usage: camlab " + command in capsys.readouterr().out
