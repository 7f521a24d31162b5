"""The fast browser-frame encoder sends exactly the pixels matplotlib's own encoder sends."""
import io

import numpy as np
import pytest
from PIL import Image

from camlab.widgets import _transport


@pytest.fixture
def ipympl_canvas(monkeypatch):
    monkeypatch.setenv("MPLBACKEND", "module://ipympl.backend_nbagg")
    pytest.importorskip("ipympl")
    import matplotlib.pyplot as plt

    with plt.ioff():
        fig = plt.figure(figsize=(4, 3), dpi=80)
    ax = fig.add_subplot()
    image = ax.imshow(np.random.default_rng(0).random((30, 40)))
    yield fig.canvas, image
    plt.close(fig)


def _decode(png: bytes) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGBA"))


def test_fast_diff_matches_matplotlib(ipympl_canvas):
    canvas, image = ipympl_canvas
    sent = []
    canvas.send_binary = sent.append  # what would go to the browser
    frames = {}
    for name in ("matplotlib", "fast"):
        if name == "fast":
            _transport.use_fast_png(canvas)
        canvas._force_full = True
        canvas.draw()  # a full frame
        image.set_data(np.random.default_rng(1).random((30, 40)))
        canvas.draw()  # only the changed pixels, the rest transparent
        image.set_data(np.random.default_rng(0).random((30, 40)))
        frames[name], sent[:] = list(sent), []
    assert len(frames["fast"]) == len(frames["matplotlib"]) == 2
    for slow, fast in zip(frames["matplotlib"], frames["fast"]):
        assert np.array_equal(_decode(slow), _decode(fast))
    changed = _decode(frames["fast"][1])[..., 3] > 0
    assert 0 < changed.mean() < 0.9  # a diff frame, not a full one


def test_nothing_sent_when_nothing_changed(ipympl_canvas):
    canvas, _ = ipympl_canvas
    _transport.use_fast_png(canvas)
    canvas.draw()
    canvas._png_is_old = False
    assert canvas.get_diff_image() is None
