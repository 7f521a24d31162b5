"""Tests for the camlab command line (camlab.cli)."""

import shutil
import subprocess
import sys
from pathlib import Path

import cv2
import numpy as np
import pytest

from camlab import cli
from camlab.data import data_dir

DATA = data_dir() / "calib_chessboard"


@pytest.fixture(scope="module")
def photos(tmp_path_factory):
    """A folder of 6 rendered chessboard photos, one blank photo and one of another size."""
    d = tmp_path_factory.mktemp("photos")
    for i in range(6):
        shutil.copy(DATA / f"view_{i:02d}.png", d / f"img_{i}.png")
    cv2.imwrite(str(d / "img_blank.png"), np.full((480, 640), 200, np.uint8))
    cv2.imwrite(str(d / "img_small.png"), cv2.imread(str(DATA / "view_07.png"))[:240, :320])
    return d


def test_calibrate_writes_an_opencv_file_and_a_report(photos, tmp_path, capsys):
    out, rep = tmp_path / "cam.json", tmp_path / "report.png"
    code = cli.main(
        [
            "calibrate",
            str(photos / "*.png"),
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
    text = capsys.readouterr().out
    assert code == 0
    assert "6 of 8 images used" in text
    assert (
        "img_blank.png: no chessboard found" in text
        and "img_small.png: image size 320 x 240" in text
    )
    assert "rms reprojection error" in text and "advice:" in text
    fs = cv2.FileStorage(str(out), cv2.FILE_STORAGE_READ)
    K = fs.getNode("camera_matrix").mat()
    dist = fs.getNode("distortion_coefficients").mat().ravel()
    fs.release()
    assert (
        abs(K[0, 0] / 820.0 - 1) < 0.01 and abs(K[1, 2] - 236.8) < 3 and abs(dist[0] + 0.21) < 0.03
    )
    img = cv2.imread(str(rep))
    assert img is not None and img.shape[0] > 400 and img.std() > 10


def test_yaml_output_and_no_report(photos, tmp_path, capsys):
    out = tmp_path / "cam.yaml"
    code = cli.main(
        [
            "calibrate",
            *sorted(str(p) for p in photos.glob("img_[0-4].png")),
            "--pattern",
            "9x6",
            "--square",
            "0.025",
            "--out",
            str(out),
            "--no-report",
            "--fix-k3",
        ]
    )
    assert code == 0 and out.read_text().startswith("%YAML")
    assert "saved report" not in capsys.readouterr().out
    fs = cv2.FileStorage(str(out), cv2.FILE_STORAGE_READ)
    assert fs.getNode("distortion_coefficients").mat().ravel()[4] == 0.0
    fs.release()


@pytest.mark.parametrize(
    "args, message",
    [
        (["--pattern", "10x7"], "need at least 3 images"),
        (["--pattern", "9by6"], "--pattern: expected inner corners"),
    ],
)
def test_user_errors_exit_2_with_a_message_not_a_traceback(photos, tmp_path, capsys, args, message):
    code = cli.main(
        [
            "calibrate",
            str(photos / "img_[0-3].png"),
            "--square",
            "0.025",
            "--out",
            str(tmp_path / "x.json"),
            "--no-report",
            *args,
        ]
    )
    err = capsys.readouterr().err
    assert code == 2 and message in err and "Traceback" not in err


def test_wrong_pattern_size_is_explained(photos, tmp_path, capsys):
    cli.main(
        [
            "calibrate",
            str(photos / "img_[0-3].png"),
            "--pattern",
            "10x7",
            "--square",
            "0.025",
            "--no-report",
        ]
    )
    assert "(on the command line, --pattern 9x6)" in capsys.readouterr().err


def test_no_matching_files_and_no_command(capsys):
    assert (
        cli.main(["calibrate", "/nonexistent/*.jpg", "--pattern", "9x6", "--square", "0.02"]) == 2
    )
    assert "no files match" in capsys.readouterr().err
    assert cli.main([]) == 2
    assert "calibrate" in capsys.readouterr().out


def test_subcommands_are_registered_for_extension():
    parser = cli.build_parser()
    assert "calibrate" in cli.COMMANDS
    args = parser.parse_args(["calibrate", "a.png", "--pattern", "9x6", "--square", "0.03"])
    assert args.run is cli.COMMANDS["calibrate"][2] and args.square == 0.03


def test_console_script_runs():
    exe = Path(sys.executable).with_name("camlab")
    cmd = [str(exe)] if exe.exists() else [sys.executable, "-m", "camlab.cli"]
    out = subprocess.run([*cmd, "calibrate", "--help"], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0 and "--pattern" in out.stdout
