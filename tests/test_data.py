"""Tests for camlab.data: the bundled sets regenerate (to a stated tolerance), are true, and are found anywhere."""

import fnmatch
import hashlib
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import cv2
import numpy as np
import pytest

from camlab import data, render
from camlab._validate import CamlabInputError
from camlab.fixtures.regenerate import GENERATED_SETS, regenerate

# Regeneration must give the bundled files back. Compared as decoded pixels and parsed ground
# truth, not bytes, so a patch release of OpenCV (its resize, libpng or libjpeg) does not break it:
PIXEL_MEAN_TOL = 0.5  # mean |difference| per image, grey levels (0-255 scale)
PIXEL_MAX_TOL = 24  # largest single-pixel |difference|, grey levels (a JPEG block edge may move)
TRUTH_TOL = 1e-6  # ground-truth numbers: pixels, metres, matrix entries


def _same_truth(a, b, where="truth.json"):
    """Assert two parsed truth.json trees agree: strings and keys exactly, numbers within TRUTH_TOL."""
    if isinstance(a, dict):
        assert set(a) == set(b), f"{where}: keys differ: {set(a) ^ set(b)}"
        for k in a:
            _same_truth(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), f"{where}: length {len(a)} != {len(b)}"
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            _same_truth(x, y, f"{where}[{i}]")
    elif isinstance(a, (int, float)) and not isinstance(a, bool):
        assert abs(a - b) <= TRUTH_TOL * max(1.0, abs(a)), f"{where}: {a} != {b}"
    else:
        assert a == b, f"{where}: {a!r} != {b!r}"


def _manifest(path: Path) -> dict[str, tuple[str, int]]:
    rows = [
        line.split() for line in path.read_text().splitlines() if line and not line.startswith("#")
    ]
    return {name: (sha, int(size)) for sha, size, name in rows}


LOCK = Path(__file__).resolve().parent.parent / "requirements" / "lock.txt"


def _locked_series(package: str) -> str:
    """``major.minor`` of ``package`` in requirements/lock.txt (the versions the bundled data were made with)."""
    m = re.search(rf"^{re.escape(package)}==(\d+\.\d+)", LOCK.read_text(), re.M)
    assert m, f"requirements/lock.txt does not pin {package}"
    return m.group(1)


@pytest.fixture(scope="module")
def regenerated(tmp_path_factory):
    # Another minor series of OpenCV (resize, JPEG) or matplotlib (text) renders visibly different
    # pixels: the comparison is pinned to the lock's series, and tolerates its patch releases.
    import matplotlib

    for package, version in (
        ("opencv-python-headless", cv2.__version__),
        ("matplotlib", matplotlib.__version__),
    ):
        series = _locked_series(package)
        if not version.startswith(series + "."):
            pytest.skip(
                f"the bundled data were rendered with {package} {series}.x (requirements/lock.txt); "
                f"this is {version}: regeneration is compared only on the locked series"
            )
    root = tmp_path_factory.mktemp("data")
    regenerate(root)
    return root


@pytest.mark.parametrize("name", GENERATED_SETS)
def test_regeneration_reproduces_the_bundled_set(regenerated, name):
    bundled = data.data_dir() / name
    made = sorted(p.name for p in (regenerated / name).iterdir())
    assert made == sorted(p.name for p in bundled.iterdir())
    for f in made:
        new, old = regenerated / name / f, bundled / f
        if f.endswith(".json"):
            _same_truth(json.loads(new.read_text()), json.loads(old.read_text()), f"{name}/{f}")
            continue
        a = cv2.imread(str(new), cv2.IMREAD_UNCHANGED).astype(float)
        b = cv2.imread(str(old), cv2.IMREAD_UNCHANGED).astype(float)
        scale = (
            256.0 if f == "disparity.png" else 1.0
        )  # uint16 disparity = round(256 d): compare in 1/256 px
        diff = np.abs(a - b) / scale
        assert (
            a.shape == b.shape and diff.mean() <= PIXEL_MEAN_TOL and diff.max() <= PIXEL_MAX_TOL
        ), f"{name}/{f}: mean |diff| {diff.mean():.3f}, max {diff.max():.1f}"


def test_manifest_lists_every_generated_file_with_its_hash():
    root = data.data_dir()
    listed = _manifest(root / "MANIFEST.txt")
    present = {p.relative_to(root).as_posix(): p for p in root.rglob("*") if p.is_file()}
    generated = {name: p for name, p in present.items() if name.split("/")[0] in GENERATED_SETS}
    assert sorted(listed) == sorted(generated), (
        "data/MANIFEST.txt is stale: run `python -m camlab.data`"
    )
    for name, path in generated.items():
        assert listed[name] == (
            hashlib.sha256(path.read_bytes()).hexdigest(),
            path.stat().st_size,
        ), f"{name} changed since data/MANIFEST.txt was written: run `python -m camlab.data`"
    total = sum(p.stat().st_size for p in present.values())
    assert total < 10e6, f"data/ holds {total / 1e6:.1f} MB; keep the shipped assets under 10 MB"


def test_calibration_set_ground_truth():
    cs = data.load_calibration_set()
    assert 15 <= len(cs.images) <= 20 and cs.images[0].shape == (480, 640)
    assert cs.corners.shape == (len(cs.images), 54, 2) and cs.pattern_size == (9, 6)
    # the stored corners are the projections of the object points with the stored truth
    for R, t, c in zip(cs.R, cs.t, cs.corners, strict=True):
        assert np.abs(render.project(cs.object_points, cs.K, R, t, cs.dist) - c).max() < 1e-6
    # and OpenCV's detector finds them in the images
    ok, found = cv2.findChessboardCornersSB(cs.images[0], cs.pattern_size)
    assert ok
    assert (
        np.sqrt(
            np.mean(
                np.sum(
                    (render.align_detected_corners(found, cs.corners[0]) - cs.corners[0]) ** 2, 1
                )
            )
        )
        < 0.15
    )


def test_missing_directory(tmp_path):
    with pytest.raises(CamlabInputError, match="no truth.json"):
        data.load_calibration_set(tmp_path)


def test_camlab_data_overrides_one_set(tmp_path, monkeypatch):
    monkeypatch.setenv("CAMLAB_DATA", str(tmp_path))
    assert data.dataset_dir("stereo") == data.data_dir() / "stereo"  # nothing regenerated there yet
    (tmp_path / "calib_chessboard").mkdir()
    assert data.dataset_dir("calib_chessboard") == tmp_path / "calib_chessboard"
    with pytest.raises(CamlabInputError, match="no truth.json"):
        data.load_calibration_set()  # the override is used, and it is empty
    assert data.regeneration_dir() == tmp_path == data.cache_dir()


def test_regeneration_never_targets_an_installed_package(monkeypatch, tmp_path):
    monkeypatch.delenv("CAMLAB_DATA", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    target = data.regeneration_dir()
    site = Path(np.__file__).parent.parent  # site-packages of this interpreter
    assert site not in target.resolve().parents
    if data.data_dir() != data.regeneration_dir():  # an installed camlab: the user cache
        assert target == tmp_path / "camlab" / "data"


def test_python_m_camlab_data_writes_where_asked(tmp_path):
    env = dict(os.environ, CAMLAB_DATA=str(tmp_path / "unused"))
    out = subprocess.run(
        [sys.executable, "-m", "camlab.data", "--help"], capture_output=True, text=True, env=env
    )
    assert out.returncode == 0 and "usage: python -m camlab.data" in out.stdout


def test_photos_load_and_are_attributed():
    names = data.photo_names()
    assert {"calib_left01", "calib_left14", "street", "walls_left", "walls_right"} <= set(names)
    attribution = (data.data_dir() / "photos" / "ATTRIBUTION.md").read_text()
    for name in names:  # every shipped photo is listed with its source
        assert f"`{name}." in attribution or name.startswith(("calib_left", "calib_right")), name
    rgb, gray = data.load_photo("church"), data.load_photo("calib_left01", gray=True)
    assert rgb.dtype == np.uint8 and rgb.shape == (532, 800, 3) and gray.shape == (480, 640)
    assert rgb[..., 2].mean() > rgb[..., 0].mean()  # a blue sky: RGB order, not OpenCV's BGR
    ok, _ = cv2.findChessboardCorners(gray, (9, 6))
    assert ok


def test_unknown_photo():
    with pytest.raises(CamlabInputError, match="name: expected one of"):
        data.load_photo("nope")


def test_every_shipped_file_is_attributed():
    root = data.data_dir()
    table = (root / "ATTRIBUTION.md").read_text()
    rows = [line.split("|")[1] for line in table.splitlines() if line.startswith("| `")]
    patterns = [p for row in rows for p in re.findall(r"`([^`]+)`", row)]
    assert "photos/*" in patterns and "calib_chessboard/*" in patterns
    for path in root.rglob("*"):
        if path.is_file():
            rel = path.relative_to(root).as_posix()
            assert any(fnmatch.fnmatch(rel, p) for p in patterns), (
                f"data/{rel} is not in data/ATTRIBUTION.md"
            )


def test_encode_image_raises_when_opencv_reports_failure(monkeypatch):
    """cv2.imencode's ok flag used to be ignored: a failed encode would write garbage into a data set."""
    import cv2

    from camlab.data._resources import encode_image

    img = np.zeros((4, 4), np.uint8)
    assert encode_image(img, ".png")[:4] == b"\x89PNG"
    monkeypatch.setattr(cv2, "imencode", lambda *a, **k: (False, None))
    with pytest.raises(
        OSError, match=r"cv2.imencode could not encode a \(4, 4\) uint8 image as .png"
    ):
        encode_image(img, ".png")


def test_panorama_rotation_helpers_say_their_direction():
    from camlab.fixtures import panorama

    Rc = panorama.cam_from_world(0.3, -0.1, 0.05)
    # a camera turned right by yaw sees a point that lies ahead-right of the world straight ahead
    ahead_right = np.array([np.sin(0.3), 0.0, np.cos(0.3)])
    assert np.allclose(
        panorama._rot(0.3, 0, 0) @ [0, 0, 1.0], ahead_right
    )  # world_from_cam maps its axis out
    assert np.allclose(Rc @ panorama._rot(0.3, -0.1, 0.05), np.eye(3))


def test_surface_points_span_each_plane_and_name_a_bad_n():
    from camlab.fixtures import panorama

    room = panorama.room_scene()
    pts = panorama.surface_points([room[1]], n=5)
    corners = np.asarray(room[1].corners_world)
    assert pts.shape == (25, 3)
    assert all(
        np.min(np.linalg.norm(pts - c, axis=1)) < 1e-12 for c in corners
    )  # the corners are in
    assert np.allclose(pts.mean(axis=0), corners.mean(axis=0))  # spread evenly
    assert panorama.surface_points(room[3], n=3).shape == (6 * 9, 3)  # the box: six faces
    with pytest.raises(CamlabInputError, match="n must be at least 2"):
        panorama.surface_points([room[1]], n=1)


def test_panorama_set_exposures_are_its_gains():
    s = data.load_panorama_set(scale=0.25)
    assert s.exposures is s.gains and np.allclose(s.exposures, [1.0, 0.86, 1.12, 0.93])


def test_lesson_01_church_window_heights_are_where_the_photo_says():
    """Lesson 01 measures five windows down their middle columns, each edge where the brightness crosses half-way
    between the white frame and the dark glass, interpolated: an independent walk from the frame finds the same
    heights (the lesson prints 88.8 ... 59.9 px) to 0.3 px, and the lesson's rough rows lie within a pixel of them."""
    import ast

    import nbformat

    lesson = nbformat.read(
        Path(__file__).parent.parent / "lessons" / "01_pinhole_camera.ipynb", as_version=4
    )
    source = next(
        c.source for c in lesson.cells if c.cell_type == "code" and "by_eye = {" in c.source
    )
    by_eye = ast.literal_eval(re.search(r"by_eye = (\{[^}]*\})", source).group(1))
    grey = data.load_photo("church").astype(float).mean(axis=2)

    def half_way(column, row, step):
        """Sub-pixel row where the profile crosses half-way, walking from the bright frame at ``row`` by ``step``."""
        bright = column[row]
        dark = np.median(column[row + 4 * step : row + 12 * step : step])
        level = (bright + dark) / 2
        while (column[row] - level) * (column[row + step] - level) > 0:
            row += step
        return row + step * (column[row] - level) / (column[row] - column[row + step])

    heights = []
    for u, (top, bottom) in by_eye.items():
        column = grey[:, u]
        frame_above = (
            top - 1 - int(np.argmax(column[top - 1 : top - 6 : -1] > 170))
        )  # last white row above the glass
        frame_below = bottom + 1 + int(np.argmax(column[bottom + 1 : bottom + 6] > 170))
        edges = half_way(column, frame_above, 1), half_way(column, frame_below, -1)
        assert abs(edges[0] - top) <= 1 and abs(edges[1] - bottom) <= 1, u
        heights.append(edges[1] - edges[0])
    assert np.allclose(heights, [88.8, 79.7, 72.0, 65.7, 59.9], atol=0.3)


def test_middlebury_pair_loads_with_its_truth():
    """The real pair of lesson 11: left pixel (u, v) matches right (u - d, v), and the truth is where it says."""
    m = data.load_middlebury()
    assert m.left.shape == m.right.shape == m.disparity.shape == (500, 741)
    assert m.left.dtype == np.uint8
    known = np.isfinite(m.disparity)
    assert 0.9 < known.mean() < 0.95 and 7 < np.nanmin(m.disparity) and np.nanmax(m.disparity) < 61
    v, u = np.nonzero(known & (np.arange(741)[None, :] > 70))
    d = m.disparity[v, u]
    match = np.abs(m.left[v, u].astype(float) - m.right[v, np.round(u - d).astype(int)]).mean()
    wrong_sign = np.abs(
        m.left[v, u].astype(float) - m.right[v, np.clip(np.round(u + d), 0, 740).astype(int)]
    ).mean()
    assert match < 10 < 30 < wrong_sign
    assert m.focal == pytest.approx(994.978) and m.baseline == pytest.approx(0.193001)
    assert m.doffs == pytest.approx(31.086)
