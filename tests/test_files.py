"""camlab._files: the one photo reader and the checked, atomic writer."""

from __future__ import annotations

import errno
import os
import re
import shutil
import struct

import cv2
import numpy as np
import pytest

from camlab._files import (
    PhotoReadError,
    atomic_output,
    check_not_an_input,
    damaged_image_file,
    read_photo,
)
from camlab._validate import CamlabInputError
from camlab.data import data_dir

PHOTO = data_dir() / "photos" / "calib_left01.jpg"


def _with_orientation(jpeg: bytes, orientation: int) -> bytes:
    tiff = (
        b"II*\x00"
        + struct.pack("<IH", 8, 1)
        + struct.pack("<HHIHH", 0x0112, 3, 1, orientation, 0)
        + struct.pack("<I", 0)
    )
    app1 = b"Exif\x00\x00" + tiff
    return jpeg[:2] + b"\xff\xe1" + struct.pack(">H", len(app1) + 2) + app1 + jpeg[2:]


def test_read_photo_applies_the_orientation_tag_in_every_mode(tmp_path):
    upright = cv2.imread(str(PHOTO))
    stored = cv2.rotate(
        upright, cv2.ROTATE_90_COUNTERCLOCKWISE
    )  # what a phone held upright may store
    path = tmp_path / "phone.jpg"
    path.write_bytes(
        _with_orientation(
            cv2.imencode(".jpg", stored, [cv2.IMWRITE_JPEG_QUALITY, 98])[1].tobytes(), 6
        )
    )
    assert cv2.imread(str(path), cv2.IMREAD_UNCHANGED).shape == (
        640,
        480,
        3,
    )  # the tag is what makes it upright
    for mode, shape in (("rgb", (480, 640, 3)), ("grey", (480, 640)), ("stored", (480, 640, 3))):
        img = read_photo(path, mode)
        assert img.shape == shape and img.dtype == np.uint8
    assert np.abs(read_photo(path, "stored").astype(int) - upright).mean() < 2
    assert np.abs(read_photo(path, "rgb").astype(int) - upright[..., ::-1]).mean() < 2


def test_read_photo_keeps_16_bits_in_stored_mode(tmp_path):
    img = np.arange(64 * 48, dtype=np.uint16).reshape(48, 64) * 20
    cv2.imwrite(str(tmp_path / "deep.png"), img)
    out = read_photo(tmp_path / "deep.png", "stored")
    assert out.dtype == np.uint16 and np.array_equal(out, img)


@pytest.mark.parametrize(
    "make, reason",
    [
        (lambda p: p.write_bytes(PHOTO.read_bytes()[:9000]), "truncated JPEG"),
        (
            lambda p: p.write_bytes(
                cv2.imencode(".png", np.zeros((40, 40), np.uint8))[1].tobytes()[:-20]
            ),
            "truncated PNG",
        ),
        (lambda p: p.write_bytes(b""), "empty (0 bytes)"),
        (lambda p: p.write_text("not a photo"), "not an image format OpenCV knows"),
        (lambda p: p.mkdir(), "it is a folder"),
        (lambda p: None, "does not exist"),
    ],
)
def test_read_photo_refuses_damaged_files_naming_them(tmp_path, make, reason):
    path = tmp_path / "x.jpg"
    make(path)
    with pytest.raises(PhotoReadError, match=re.escape(reason)) as exc:
        read_photo(path)
    assert "x.jpg" in str(exc.value) and exc.value.reason.endswith(
        str(exc.value).split(": ", 1)[1].split(": ", 1)[-1]
    )


def test_a_jpeg_padded_with_zeros_after_its_end_is_not_truncated():
    assert damaged_image_file(PHOTO.read_bytes() + b"\x00" * 8) is None


def test_check_not_an_input_sees_through_spellings_symlinks_and_hard_links(tmp_path):
    photo = tmp_path / "a.jpg"
    shutil.copy(PHOTO, photo)
    os.symlink(photo, tmp_path / "sym.jpg")
    os.link(photo, tmp_path / "hard.jpg")
    (tmp_path / "sub").mkdir()
    for same in (tmp_path / "sub" / ".." / "a.jpg", tmp_path / "sym.jpg", tmp_path / "hard.jpg"):
        with pytest.raises(
            CamlabInputError,
            match=r"--out: writing .* would overwrite the input photo .*; rename it",
        ):
            check_not_an_input([same], "--out", [photo], "rename it")
    check_not_an_input(
        [tmp_path / "b.jpg", tmp_path / "sub" / "a.jpg"], "--out", [photo], ""
    )  # other files: fine


def test_atomic_output_gives_new_files_the_umask_mode_and_keeps_an_old_files_mode(tmp_path):
    old = os.umask(0o027)
    try:
        with atomic_output(tmp_path / "new.txt") as tmp:
            tmp.write_text("x")
    finally:
        os.umask(old)
    assert (tmp_path / "new.txt").stat().st_mode & 0o777 == 0o640  # mkstemp alone gives 0600
    (tmp_path / "old.txt").write_text("old")
    os.chmod(tmp_path / "old.txt", 0o604)
    with atomic_output(tmp_path / "old.txt") as tmp:
        tmp.write_text("new")
    assert (tmp_path / "old.txt").stat().st_mode & 0o777 == 0o604 and (
        tmp_path / "old.txt"
    ).read_text() == "new"


@pytest.mark.parametrize(
    "write, why",
    [
        (lambda tmp: None, r"nothing was written \(0 bytes\)"),
        (lambda tmp: tmp.write_bytes(PHOTO.read_bytes()[:5000]), "truncated JPEG was written"),
        (lambda tmp: tmp.write_text("x"), "does not read back"),
    ],
)
def test_atomic_output_checks_what_was_written_and_keeps_the_old_file(tmp_path, write, why):
    target = tmp_path / "out.jpg"
    target.write_bytes(PHOTO.read_bytes())
    with pytest.raises(
        CamlabInputError,
        match=rf"--out: could not write .*out.jpg.*{why}.*the previous file is unchanged",
    ):
        with atomic_output(target, "--out", verify=lambda p: "does not read back") as tmp:
            write(tmp)
    assert target.read_bytes() == PHOTO.read_bytes() and [p.name for p in tmp_path.iterdir()] == [
        "out.jpg"
    ]


def test_atomic_output_turns_a_full_disk_into_a_clear_error(tmp_path, monkeypatch):
    def full(fd):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(os, "fsync", full)
    with pytest.raises(
        CamlabInputError,
        match="--report: could not write .*No space left on device; no file was left",
    ):
        with atomic_output(tmp_path / "r.png", "--report") as tmp:
            tmp.write_bytes(b"\x89PNG")
    assert list(tmp_path.iterdir()) == []


def test_find_chessboard_on_a_big_photo_searches_a_small_copy_and_refines_at_full_size():
    from camlab.calibration import find_chessboard

    img = cv2.imread(str(PHOTO), cv2.IMREAD_GRAYSCALE)
    f = 4.0
    big = cv2.resize(img, None, fx=f, fy=f, interpolation=cv2.INTER_CUBIC)  # 2560 x 1920
    ref = find_chessboard(img, (9, 6)).corners
    fast = find_chessboard(big, (9, 6))  # searched at 1600 x 1200
    back = (fast.corners + 0.5) / f - 0.5  # pixel centres: u' = f (u + 1/2) - 1/2
    err = np.linalg.norm(back - ref, axis=1)
    assert fast.found and np.median(err) < 0.25 and err.max() < 1.0
    coarse = find_chessboard(
        big, (9, 6), max_side=400
    )  # squares 11 px wide: the full-size refinement does the work
    assert np.median(np.linalg.norm((coarse.corners + 0.5) / f - 0.5 - ref, axis=1)) < 0.3
    with pytest.raises(CamlabInputError, match="max_side"):
        find_chessboard(big, (9, 6), max_side=0)


def test_calibration_files_from_ros_are_read(tmp_path):
    from camlab.calibration import load_calibration

    (tmp_path / "ros.yaml").write_text(
        "image_width: 640\nimage_height: 480\ncamera_name: cam\ncamera_matrix:\n  rows: 3\n  cols: 3\n"
        "  data: [533.0, 0.0, 341.6, 0.0, 533.3, 234.3, 0.0, 0.0, 1.0]\ndistortion_model: plumb_bob\n"
        "distortion_coefficients:\n  rows: 1\n  cols: 5\n  data: [-0.288, 0.097, 0.001, -0.0003, 0.0]\n"
    )
    K, dist, size = load_calibration(tmp_path / "ros.yaml")
    assert size == (640, 480) and K[0, 2] == 341.6 and K[1, 1] == 533.3 and dist[0] == -0.288
    (tmp_path / "short.yaml").write_text(
        "image_width: 640\nimage_height: 480\ncamera_matrix: {rows: 3, cols: 3, "
        "data: [1, 2]}\ndistortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n"
    )
    with pytest.raises(CamlabInputError, match="--calibration: .*camera_matrix node is neither"):
        load_calibration(tmp_path / "short.yaml", name="--calibration")


def test_match_graph_groups_are_its_connected_parts():
    from types import SimpleNamespace

    from camlab.stitching.registration import MatchGraph

    ok, no = SimpleNamespace(accepted=True), SimpleNamespace(accepted=False)
    g = MatchGraph(
        {(0, 1): ok, (2, 3): ok, (3, 4): ok, (1, 2): no, (0, 5): no}, 0, [None] * 6, [-1] * 6, []
    )
    assert g.groups() == [[2, 3, 4], [0, 1], [5]]
