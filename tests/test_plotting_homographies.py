"""camlab.plotting.homographies: lesson 07's static figures draw what the lesson computed."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from camlab import fixtures  # noqa: E402
from camlab import homography as hg  # noqa: E402
from camlab.plotting.homographies import draw_hypotheses, draw_verdicts, torn_outline  # noqa: E402

FRAME = np.array([[0, 0], [399, 0], [399, 299], [0, 299], [0, 0]], float)


def test_torn_outline_breaks_where_w_changes_sign():
    H = np.array([[1.0, 0, 0], [0, 1, 0], [-1 / 200, 0, 1]])  # w = 0 on the line u = 200
    pts = torn_outline(H, FRAME, n=50)
    assert pts.shape == (200, 2)
    assert np.isnan(pts[:, 0]).sum() == 2  # the top and the bottom side cross u = 200 once each
    assert not np.isnan(torn_outline(np.eye(3), FRAME)).any()


def test_draw_hypotheses_titles_quote_the_support_and_magnify_the_first():
    H_s, src, dst, out = fixtures.outlier_matches(0.4, 0)
    picks = [
        np.flatnonzero(out)[:1].tolist() + np.flatnonzero(~out)[:3].tolist(),
        np.flatnonzero(~out),
    ]
    steps = []
    for k, pick in enumerate(picks):
        H = hg.estimate_homography(src[pick], dst[pick])
        steps.append(
            (f"step {k}", np.asarray(pick), H, hg.symmetric_transfer_error(H, src, dst) < 3.0)
        )
    steps.append(
        ("step 2", np.flatnonzero(~out), H_s, hg.symmetric_transfer_error(H_s, src, dst) < 3.0)
    )
    fig = draw_hypotheses(src, dst, H_s, steps, FRAME)
    titles = [ax.get_title() for ax in fig.axes]
    assert f"{int(steps[2][3].sum())} pairs within 3 px" in titles[2]
    assert any(t.startswith("panel 1's box, magnified") for t in titles)
    plt.close(fig)


def test_draw_verdicts_counts_each_verdict_in_the_legend():
    rng = np.random.default_rng(0)
    src, e = rng.uniform(0, 300, (40, 2)), rng.uniform(0.5, 20, 40)
    kept = e < 3
    fig = draw_verdicts(
        np.zeros((300, 300)),
        src,
        e,
        [(kept, "k", "o", 4, "inliers"), (~kept, "0.5", "X", 6, "rest")],
    )
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert labels == [f"inliers ({kept.sum()})", f"rest ({(~kept).sum()})"]
    plt.close(fig)
