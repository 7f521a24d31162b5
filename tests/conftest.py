"""Shared test settings: headless figures and a fixed hypothesis profile."""

import os

os.environ.setdefault("CAMLAB_FIGURE_MODE", "agg")
os.environ.setdefault("MPLBACKEND", "Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
from hypothesis import settings  # noqa: E402

settings.register_profile("camlab", max_examples=60, deadline=None, derandomize=True)
settings.load_profile("camlab")


@pytest.fixture
def rng():
    """A seeded generator: every test that draws random data draws the same data each run."""
    return np.random.default_rng(0)


@pytest.fixture
def cam():
    """A general camera (skewed K, off-centre principal point) looking at the origin from above and aside."""
    from camlab import camera as cm

    return cm.Camera.look_at(
        [4.0, -3.0, 2.0], [0.0, 0.0, 0.5], K=cm.intrinsic_matrix(810, 790, 330, 235, 1.5)
    )


def assert_close_to_cv2_warp(ours, ref) -> None:
    """A float bilinear warp agrees with OpenCV's warpPerspective/remap, whatever OpenCV version.

    OpenCV interpolates in fixed point: 4.x rounds each source position to 1/32 pixel
    (INTER_BITS = 5), so on a sharp edge (up to 255 grey levels per pixel) a value moves by up
    to 255/64 = 4 grey levels; 5.x agrees to rounding (1). Away from edges both agree to
    rounding, so the mean difference stays below a quarter of a grey level (measured 0.0001 on
    OpenCV 5.0, up to 0.11 on 4.12).
    """
    import numpy as np

    diff = np.abs(np.asarray(ours).astype(int) - np.asarray(ref).astype(int))
    assert diff.max() <= 4, f"max |diff| {diff.max()} grey levels (OpenCV's fixed point allows 4)"
    assert diff.mean() < 0.25, (
        f"mean |diff| {diff.mean():.3f} grey levels: more than fixed-point rounding"
    )


def _long_file(item) -> bool:
    """A notebook, or a file whose tests start a hub or a browser: tens of seconds each."""
    return item.path.suffix == ".ipynb" or any(
        item.get_closest_marker(m) for m in ("hub", "browser", "binder")
    )


def pytest_collection_modifyitems(items):
    """Long files first; deadlines beyond the default 300 s, still finite so nothing can hang CI.

    ``--dist loadfile`` hands whole files to the two workers in collection order: a long file
    collected last (the hub, the browser test) ran alone at the end, one core idle for a minute
    and more. The sort is stable, so each file's own tests keep their order.

    Tests that install whole environments (marked ``binder``) get 30 minutes. Tests that drive a
    real Chromium (marked ``browser``) get 15 minutes: the site's module fixture opens all 14
    pages with MathJax and axe-core, 190 s on a loaded 2-core machine, more than 300 s beside
    the rest of ``make test -n 2`` (the sixth clean-clone run).
    """
    long_files = {item.path for item in items if _long_file(item)}
    items.sort(key=lambda item: item.path not in long_files)
    for item in items:
        if item.get_closest_marker("timeout"):
            continue
        if item.get_closest_marker("binder"):
            item.add_marker(pytest.mark.timeout(1800))
        elif item.get_closest_marker("browser"):
            item.add_marker(pytest.mark.timeout(900))
