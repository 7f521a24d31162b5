"""The photo upload control, headless: files made here are set as the FileUpload's value."""

import datetime as dt
import io
import re

import cv2
import numpy as np
import pytest

from camlab import CamlabInputError
from camlab._notebook import UPLOAD_NEEDS_KERNEL
from camlab.widgets.upload import PhotoUpload, decode_photo


def _image(h=40, w=60):
    """A BGR test image with a white block at its top-left corner."""
    img = np.zeros((h, w, 3), np.uint8)
    img[: h // 4, : w // 6] = 255
    img[h // 2 :, w // 2 :, 2] = 200  # red bottom-right quarter (BGR)
    return img


def _encode(img, suffix=".png") -> bytes:
    ok, buf = cv2.imencode(suffix, img)
    assert ok
    return buf.tobytes()


def _jpeg_with_orientation(img, orientation: int) -> bytes:
    pil = pytest.importorskip("PIL.Image")
    exif = pil.Exif()
    exif[0x0112] = orientation  # the Orientation tag
    buf = io.BytesIO()
    pil.fromarray(img[..., ::-1]).save(buf, "JPEG", exif=exif, quality=95)
    return buf.getvalue()


def _entry(name, data: bytes, type_="image/png"):
    """One file as ipywidgets 8 gives it: name, type, size, content (memoryview), last_modified."""
    return {
        "name": name,
        "type": type_,
        "size": len(data),
        "content": memoryview(data),
        "last_modified": dt.datetime(2026, 11, 27, tzinfo=dt.UTC),
    }


def _upload(up: PhotoUpload, *files):
    up.upload.value = tuple(_entry(name, data) for name, data in files)


def _white_corner(img):
    """Mean (row, col) of the white block, as fractions of the height and width."""
    rows, cols = np.nonzero(img.min(axis=2) > 200)
    return rows.mean() / img.shape[0], cols.mean() / img.shape[1]


def test_nothing_uploaded_gives_the_default_and_says_so():
    up = PhotoUpload("Your board photos", multiple=True, max_pixels=2_000_000)
    shipped = [("board_1.png", _image())]
    assert up.photos == [] and up.problems == []
    assert up.photos_or(shipped) == shipped
    assert "No photos uploaded" in up.status.value
    assert up.upload.accept == "image/*" and up.upload.multiple


def test_good_png_and_jpeg_are_decoded_as_bgr_uint8_and_named_in_the_status():
    up = PhotoUpload("Your photos")
    seen = []
    up.observe(lambda control: seen.append(len(control.photos)))
    img = _image()
    _upload(up, ("a.png", _encode(img)), ("b.jpg", _encode(img, ".jpg")))
    assert [name for name, _ in up.photos] == ["a.png", "b.jpg"] and up.problems == []
    png, jpg = up.photos[0][1], up.photos[1][1]
    assert png.dtype == np.uint8 and png.shape == (40, 60, 3)
    np.testing.assert_array_equal(png, img)  # BGR kept, exactly, for a PNG
    assert np.abs(jpg.astype(int) - img).mean() < 3  # a JPEG within its compression error
    assert "a.png" in up.status.value and "60 x 40 px" in up.status.value
    assert f"{len(_encode(img))} bytes" in up.status.value
    assert seen == [2]
    assert up.photos_or([("x", img)]) == up.photos


def test_a_grey_png_comes_out_with_three_channels():
    grey = _image()[..., 0]
    image, _ = decode_photo(_encode(grey), "grey.png")
    assert image.shape == (40, 60, 3)


@pytest.mark.parametrize(
    ("orientation", "corner"),
    [(1, (0.1, 0.1)), (3, (0.9, 0.9)), (6, (0.1, 0.9)), (8, (0.9, 0.1))],
)
def test_exif_orientation_turns_the_photo_upright(orientation, corner):
    """Orientation 6 means 'turn 90 degrees clockwise to view': the stored top-left goes top-right."""
    up = PhotoUpload("Your photos")
    _upload(up, (f"o{orientation}.jpg", _jpeg_with_orientation(_image(), orientation)))
    ((name, img),) = up.photos
    assert img.shape[:2] == ((60, 40) if orientation in (6, 8) else (40, 60))
    np.testing.assert_allclose(_white_corner(img), corner, atol=0.06)


def test_a_huge_photo_is_downscaled_with_a_message():
    big = cv2.resize(_image(), (3000, 2000), interpolation=cv2.INTER_NEAREST)
    up = PhotoUpload("Your photos", max_pixels=2_000_000)
    _upload(up, ("huge.png", _encode(big)))
    ((_, img),) = up.photos
    h, w = img.shape[:2]
    assert h * w <= 2_000_000 and h * w > 1_990_000
    assert abs(w / h - 1.5) < 0.002
    assert "3000 x 2000 px, downscaled to 1732 x 1154 px" in up.status.value
    assert (w, h) == (1732, 1154)


@pytest.mark.parametrize(
    ("name", "data", "reason"),
    [
        ("x.jpg", b"this is a text file, not a photo\n", "not an image OpenCV can read"),
        ("empty.png", b"", "empty (0 bytes)"),
        ("cut.jpg", _encode(_image(), ".jpg")[:-300], "truncated JPEG"),
        ("cut.png", _encode(_image(), ".png")[:-20], "truncated PNG"),
    ],
)
def test_a_bad_file_is_refused_naming_it_and_the_good_ones_are_kept(name, data, reason):
    up = PhotoUpload("Your photos")
    _upload(up, ("good.png", _encode(_image())), (name, data))
    assert [n for n, _ in up.photos] == ["good.png"]
    (problem,) = up.problems
    assert repr(name) in problem and reason in problem
    assert "Refused" in up.status.value and name in up.status.value
    with pytest.raises(CamlabInputError, match=re.escape(reason)):
        decode_photo(data, name)


def test_nothing_is_written_by_default(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    up = PhotoUpload("Your photos")
    _upload(up, ("a.png", _encode(_image())))
    assert up.photos and list(tmp_path.iterdir()) == []


def test_save_to_writes_inside_the_folder_and_keeps_the_old_file(tmp_path):
    folder = tmp_path / "mine"
    up = PhotoUpload("Your photos", save_to=folder)
    img = _image()
    _upload(up, ("a.png", _encode(img)))
    np.testing.assert_array_equal(cv2.imread(str(folder / "a.png")), img)
    _upload(up, ("a.png", _encode(255 - img)))
    copies = sorted(p.name for p in folder.iterdir())
    assert len(copies) == 2 and copies[0] == "a.png" and copies[1].startswith("a.previous-")
    np.testing.assert_array_equal(cv2.imread(str(folder / copies[1])), img)
    np.testing.assert_array_equal(cv2.imread(str(folder / "a.png")), 255 - img)
    assert "kept as a.previous-" in up.status.value


@pytest.mark.parametrize(
    "name", ["../x.jpg", "/tmp/evil.png", "sub/../../x.png", "..\\x.png", "sub/x.png", ".."]
)
def test_save_to_refuses_a_name_that_leads_outside_the_folder(tmp_path, name):
    folder = tmp_path / "inside" / "mine"
    up = PhotoUpload("Your photos", save_to=folder)
    _upload(up, (name, _encode(_image())))
    assert up.photos == []
    (problem,) = up.problems
    assert (
        "only a plain file name is written inside the folder" in problem and repr(name) in problem
    )
    written = [p for p in tmp_path.rglob("*") if p.is_file()]
    assert written == []


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"max_pixels": 0}, "max_pixels: expected at least"),
        ({"max_pixels": 1.5e6}, "max_pixels: expected a whole number"),
        ({"max_pixels": True}, "max_pixels: expected a whole number"),
        ({"save_to": 3}, "save_to: expected a folder path"),
    ],
)
def test_bad_arguments_are_named(kwargs, message):
    with pytest.raises(CamlabInputError, match=message):
        PhotoUpload("Your photos", **kwargs)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (("not bytes", "x.png"), "data: expected the file's content as bytes"),
        ((b"", "x.png", 0), "max_pixels: expected a positive whole number"),
        ((b"", "x.png", 2.5), "max_pixels: expected a positive whole number"),
    ],
)
def test_decode_photo_names_a_bad_argument(args, message):
    with pytest.raises(CamlabInputError, match=message):
        decode_photo(*args)


def test_without_a_kernel_the_control_shows_one_sentence_as_a_picture_with_alt_text():
    data, metadata = PhotoUpload("Your photos")._repr_mimebundle_()
    assert "application/vnd.jupyter.widget-view+json" in data
    assert data["image/png"] and data["text/plain"] == UPLOAD_NEEDS_KERNEL
    assert metadata["image/png"]["alt"] == UPLOAD_NEEDS_KERNEL
    assert "text/html" not in data  # static pages use the PNG and its alt text
