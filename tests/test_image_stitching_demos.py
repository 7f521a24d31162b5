"""Demo-specific tests for lesson 09 (the generic sweep test lives in tests/test_widgets.py)."""

import os

import numpy as np
import pytest

os.environ.setdefault("CAMLAB_FIGURE_MODE", "agg")

import camlab.exercises as ex  # noqa: E402
from camlab.widgets import image_stitching as demos  # noqa: E402


def test_feature_matches_ratio_lets_wrong_matches_in():
    d = demos.feature_matches()
    d.set(ratio=0.6)
    strict = dict(d.state)
    d.set(ratio=1.0)
    assert d.state["matches"] > strict["matches"] and d.state["wrong"] > 10 * max(
        strict["wrong"], 1
    )
    assert strict["precision"] > 0.95
    d.set(mutual=True)
    mutual = dict(d.state)
    d.set(mutual=False)
    assert mutual["wrong"] < d.state["wrong"]


def test_feature_matches_keypoints_lie_light_under_the_lines_and_the_key_names_the_drawing():
    """The keypoints must not bury the red dashed wrong matches; the key says what is drawn."""
    d = demos.feature_matches()
    ax = d.view._animated[0].axes
    kps = [c for c in ax.collections if c.get_offsets().shape[0] > 100]  # the two keypoint sets
    lines = [c for c in ax.collections if c not in kps]  # good, bad, the dropped and their rim
    assert len(kps) == 2 and len(lines) == 4
    assert max(k.get_zorder() for k in kps) < min(c.get_zorder() for c in lines)

    def dark_pixels():
        return int((d.view.pixels()[..., :3].max(axis=2) < 60).sum())

    d.set(keypoints=False)
    without = dark_pixels()
    d.set(keypoints=True)
    assert dark_pixels() < 1.05 * without  # no black rings: 1900 haloed circles added 68 % dark ink

    d.set(mutual=True)
    assert "black-edged grey dashes" in d.view.fig.axes[0].get_title()
    rim, dropped = (c for c in lines if c.get_zorder() == 2.5)
    grey, black = dropped.get_edgecolor()[0][:3], rim.get_edgecolor()[0][:3]
    assert np.ptp(grey) == 0 and 0.4 < grey[0] < 0.8 and not black.any()
    assert rim.get_linewidth()[0] > dropped.get_linewidth()[0]  # the black shows as the grey's edge


def test_thin_matches_keeps_the_true_share():
    import numpy as np

    from camlab.plotting.stitching import thin_matches

    rng = np.random.default_rng(1)
    for n, share in ((150, 0.9), (656, 0.47), (1123, 0.28), (5000, 0.02)):
        good = rng.random(n) < share
        show, every = thin_matches(good, 200)
        assert show.sum() <= 202 and (every == 1) == (n <= 200)
        assert abs(good[show].mean() - good.mean()) < 0.02
    assert thin_matches(np.ones(10, bool), 200)[0].all()
    with pytest.raises(ValueError, match="limit"):
        thin_matches(np.ones(3, bool), 0)
    # a fixed stride: fewer matches never draw more lines (J12: 300 matches drew 101, 305 drew 77)
    good = rng.random(1000) < 0.3
    drawn = [thin_matches(good[:n], every=4).show.sum() for n in range(0, 1001, 50)]
    assert drawn == sorted(drawn) and thin_matches(good, every=4).every == 4
    with pytest.raises(ValueError, match="every"):
        thin_matches(good, every=0)


@pytest.mark.parametrize("ratio", [0.75, 0.95, 1.0])
def test_feature_matches_draws_1_in_4_in_the_true_share(ratio):
    from camlab.widgets.image_stitching.matching import MATCH_STRIDE

    d = demos.feature_matches()
    d.set(ratio=ratio)
    s = d.state
    drawn = s["drawn_right"] + s["drawn_wrong"]
    assert MATCH_STRIDE == 4 and abs(drawn / s["matches"] - 1 / 4) < 0.015
    assert (
        s["drawn_right"] >= 1 and abs(s["drawn_wrong"] / drawn - s["wrong"] / s["matches"]) < 0.03
    )
    d.set(mutual=True)  # fewer matches: fewer lines, never more
    assert d.state["drawn_right"] + d.state["drawn_wrong"] <= drawn


def test_thin_matches_by_key_is_stable_under_filtering():
    """With a key, a surviving match keeps its line: a filter removes only its own matches' lines."""
    from camlab.plotting.stitching import thin_matches

    key = np.arange(40)
    good = key % 3 > 0
    full = thin_matches(good, every=4, key=key).show
    kept = key % 5 > 0  # a filter that drops 1 match in 5
    sub = thin_matches(good[kept], every=4, key=key[kept]).show
    assert np.array_equal(sub, full[kept])
    with pytest.raises(ValueError, match="key"):
        thin_matches(good, every=4, key=key[:3])


def test_ransac_true_frame_lies_under_the_moving_marks():
    """A full redraw layers the static true frame as the live path does: under every animated artist."""
    d = demos.ransac_registration()
    ax = d.view._animated[0].axes
    true = next(ln for ln in ax.get_lines() if ln.get_label() == "true")
    assert all(a.get_zorder() > true.get_zorder() for a in d.view._animated if a.axes is ax)


def test_ransac_demo_threshold():
    d = demos.ransac_registration()
    d.set(threshold=3.0)
    at3 = d.state["inliers"]
    assert d.state["accepted"] and d.state["corner_error"] < 1.0 and d.state["false_inliers"] <= 5
    d.set(threshold=40.0, ratio=1.0)
    # a loose threshold without the ratio test lets wrong matches in, and they drag H away (the lesson's claim)
    assert d.state["false_inliers"] > 5
    assert d.state["accepted"] and d.state["corner_error"] > 10
    d.set(threshold=0.3, ratio=0.75)
    assert d.state["inliers"] < at3  # a tight threshold rejects good matches too
    d.set(threshold=0.05)
    assert (
        not d.state["accepted"] and d.state["inliers"] < 0.3 * at3
    )  # tighter than the features' noise: the fit starves


def test_ransac_histogram_green_holds_every_inlier():
    """At the slider's lowest threshold the inliers sit in the clipped first bar: it must be green."""
    d = demos.ransac_registration()
    for threshold in (0.02, 0.05, 3.0, 40.0):
        d.set(threshold=threshold)
        assert d.state["inliers"] > 0
        assert d.state["histogram_inliers"] == d.state["inliers"], threshold
    d.set(threshold=0.02)
    inl_bars, out_bars = d.view._animated[0].figure.axes[1].containers
    assert inl_bars[0].get_height() > 0  # the hatched "< 0.02 px" bar shows its inliers in green
    # ... and only them: it lies wholly left of the threshold, so no rejected match can be in it
    assert out_bars[0].get_height() == 0
    assert inl_bars[0].get_x() + inl_bars[0].get_width() <= 0.02 + 1e-12
    assert all(b.get_x() >= 0.02 - 1e-12 for b in inl_bars[1:])
    # a straddling bin shows both kinds: the grey part starts where the green ends
    assert all(
        abs(o.get_y() - i.get_height()) < 1e-12 for i, o in zip(inl_bars, out_bars, strict=True)
    )


def image_fills_the_axes(d, pad: float = 0.0) -> bool:
    """The demo's picture touches both sides of its axes in one direction (no stale limits).

    ``pad`` is the margin the axes keep beyond the picture's box on every side (the canvas demos'
    black border, so that outlines on the canvas edge are drawn whole).
    """
    from matplotlib.image import AxesImage

    im = next(a for a in d.view._animated if isinstance(a, AxesImage))
    left, right, bottom, top = im.get_extent()
    x0, x1 = im.axes.get_xlim()
    y0, y1 = im.axes.get_ylim()
    return (abs(left - x0 - pad) < 1e-6 and abs(x1 - right - pad) < 1e-6) or (
        abs(y0 - bottom - pad) < 1e-6 and abs(top - y1 - pad) < 1e-6
    )


@pytest.mark.parametrize(
    "name, control, values",
    [
        ("panorama_canvas", "reference", [0, 1, 2, 3]),
        ("full_panorama", "projection", ["planar", "cylindrical", "spherical"]),
        ("parallax_ghosting", "baseline", [0.0, 0.2, 0.4]),
    ],
)
def test_every_canvas_fills_the_axes(name, control, values):
    from camlab.widgets.image_stitching.canvas import CANVAS_PAD

    d = getattr(demos, name)()
    pad = 0.0 if name == "parallax_ghosting" else CANVAS_PAD
    for v in values:
        d.set(**{control: v})
        assert image_fills_the_axes(d, pad), (
            f"{name} {control}={v}: the picture sits in a corner of stale axis limits"
        )


def test_canvas_demo_reference_changes_canvas():
    d = demos.panorama_canvas()
    d.set(reference=1)
    mid = d.state["canvas"]
    d.set(reference=3)
    end = d.state["canvas"]
    assert end[0] * end[1] > 1.3 * mid[0] * mid[1]  # an end reference stretches the far images


def test_blending_demo_seam_steps():
    d = demos.blending_seams()
    d.set(method="overwrite", gains=False)
    over = d.state["seam_jump"]
    d.set(method="multiband")
    assert over > 15 and d.state["seam_jump"] < over / 4
    d.set(method="overwrite", gains=True)
    assert d.state["seam_jump"] < over / 4
    assert d.state["seam_own"] < 2 < d.state["seam_jump"]  # what is left is the scene's own step


def test_blending_demo_registration_error_ghosts_feathering_only():
    """R12: the slider shows where multi-band beats feathering: view 2 moved 8 px, feathering loses detail."""
    d = demos.blending_seams()
    d.set(method="feather", gains=True, offset=0)
    assert d.state["kept"] == 1.0
    aligned = d.state["image"]
    d.set(offset=8)
    assert d.state["kept"] < 0.9 and (d.state["image"] != aligned).any()
    d.set(method="multiband")
    assert d.state["kept"] > 0.97


def test_parallax_demo_residuals_grow_with_baseline():
    d = demos.parallax_ghosting()
    d.set(baseline=0.0)
    still = dict(d.state)
    assert still["misalignment"] < 4  # only noise: the views align exactly
    d.set(baseline=0.1)
    small = d.state["misalignment"]
    d.set(baseline=0.4)
    assert (
        d.state["inlier_fraction"] < still["inlier_fraction"] - 0.1
    )  # near objects stop fitting the homography
    assert (
        d.state["misalignment"] > small > 3 * still["misalignment"]
    )  # ghosts grow with the baseline


def test_full_panorama_demo():
    d = demos.full_panorama()
    d.set(projection="planar")
    planar = d.state["shape"]
    d.set(projection="cylindrical")
    assert d.state["shape"][1] < planar[1]  # the cylinder does not stretch the ends
    assert d.state["legend"]
    d.set(outlines=False)
    assert (
        d.state["outlines_drawn"] == 0 and not d.state["legend"]
    )  # no legend for outlines not drawn


@pytest.mark.parametrize("home, name", [("warp", "canvas_box"), ("stitching", "feather_weights")])
def test_exercises_reference_passes_and_solution_prints(home, name, capsys):
    import importlib

    reference = getattr(importlib.import_module(f"camlab.{home}"), name)
    assert getattr(ex, f"check_{name}")(reference).passed is True
    assert ex.solution(name) is None and f"def {name}" in capsys.readouterr().out


def _focal_student(method, scale, cut_off=0.0):
    """A student's (f_from, f_to) from a rotation H: ``method`` combines each pair of Szeliski-Shum formulas."""
    import numpy as np

    def student(H, shape):
        h, w = shape[:2]
        C = np.array([[1.0, 0, (w - 1) / 2], [0, 1, (h - 1) / 2], [0, 0, 1]])
        Hc = np.linalg.inv(C) @ np.asarray(H, float) @ C
        Hc = Hc / {"h22": Hc[2, 2], "norm": np.linalg.norm(Hc), "none": 1.0}[scale]
        h0, h1, h2, h3, h4, h5, h6, h7, _ = Hc.ravel()
        rows = [(-h2 * h5, h0 * h3 + h1 * h4), (h5**2 - h2**2, h0**2 + h1**2 - h3**2 - h4**2)]
        cols = [(-(h0 * h1 + h3 * h4), h6 * h7), (h0**2 + h3**2 - h1**2 - h4**2, h7**2 - h6**2)]
        out = []
        with np.errstate(all="ignore"):
            for (a, b), (c, d) in (rows, cols):
                if method == "larger denominator":
                    n, den = (a, b) if abs(b) > abs(d) else (c, d)
                    f2 = [n / den if abs(den) > cut_off else np.nan]
                else:
                    f2 = [c / d] if method == "equal-length only" else [a / b, c / d]
                fs = [
                    np.sqrt(v) for v in f2 if np.isfinite(v) and v > 0
                ]  # the natural filter drops 0/0
                agg = np.mean if method == "mean of both" else np.median
                out.append(float(agg(fs)) if fs else np.nan)
        return tuple(out)

    return student


@pytest.mark.parametrize("scale", ["h22", "norm", "none"])
@pytest.mark.parametrize("method", ["median of both", "mean of both", "equal-length only"])
def test_focal_check_rejects_ignoring_the_larger_denominator_rule_naming_0_over_0(method, scale):
    with pytest.raises(AssertionError, match="is 0/0 because") as info:
        ex.check_focal_from_rotation_homography(_focal_student(method, scale))
    assert "f^2 > 0" in str(info.value)


def test_focal_check_names_the_centred_h_transposed():
    """Transposing after centring gives (1/f_to, 1/f_from): the hint says so, with the numbers."""
    import numpy as np

    from camlab.exercises.image_stitching.focal import focal_from_rotation_homography

    def student(H, shape):
        h, w = shape[:2]
        C = np.array([[1.0, 0, (w - 1) / 2], [0, 1, (h - 1) / 2], [0, 0, 1]])
        Hc_t = (np.linalg.inv(C) @ np.asarray(H, float) @ C).T
        return focal_from_rotation_homography(C @ Hc_t @ np.linalg.inv(C), shape)

    with pytest.raises(
        AssertionError,
        match=r"\(1/f_to, 1/f_from\) = \(0\.0016722\d*, 0\.0019230\d*\) = \(1/598\.0, 1/520\.0\)",
    ):
        ex.check_focal_from_rotation_homography(student)


@pytest.mark.parametrize(
    "cut_off, where", [(1e-12, "test input 4 of 8"), (1e-10, "test input 1 of 8")]
)
def test_focal_check_names_a_fixed_cut_off_on_the_denominator(cut_off, where):
    """A guard abs(d) > 1e-12 on the normalised centred H rejects a real turn (input 4: a 1020 px lens)."""
    with pytest.raises(AssertionError, match="fixed cut-off") as info:
        ex.check_focal_from_rotation_homography(
            _focal_student("larger denominator", "norm", cut_off)
        )
    assert where in str(info.value)


@pytest.mark.parametrize("scale", ["h22", "norm", "none"])
def test_focal_check_passes_the_rule_at_any_scale_and_a_numerical_search(scale, capsys):
    import numpy as np
    from scipy.optimize import least_squares

    assert ex.check_focal_from_rotation_homography(
        _focal_student("larger denominator", scale)
    ).passed

    def search(
        H, shape
    ):  # the (f_from, f_to) that make K_to^-1 H K_from closest to a rotation (up to scale)
        h, w = shape[:2]

        def K(f):
            return np.array([[f, 0, (w - 1) / 2], [0, f, (h - 1) / 2], [0, 0, 1]])

        def off(fs):
            R = np.linalg.inv(K(fs[1])) @ np.asarray(H, float) @ K(fs[0])
            R = R / np.cbrt(np.linalg.det(R))
            return (R.T @ R - np.eye(3)).ravel()

        fit = least_squares(
            off, [500.0, 500.0], x_scale=[500.0, 500.0], xtol=1e-15, ftol=1e-15, gtol=1e-15
        )
        if np.abs(fit.fun).max() > 1e-6:  # no rotation fits (the check's last input): no focal
            return np.nan, np.nan
        return tuple(fit.x)

    assert ex.check_focal_from_rotation_homography(search).passed


def test_focal_check_names_a_sign_flip_hidden_by_abs():
    """K12: a sign flip silenced by sqrt(|f^2|) passes every rotation; the last input (no rotation) shows it."""
    from camlab.exercises.image_stitching.focal import _abs_student

    with pytest.raises(AssertionError, match="hides a sign flip") as info:
        ex.check_focal_from_rotation_homography(_abs_student("sign"))
    assert "test input 8 of 8" in str(info.value) and "NaN" in str(info.value)


@pytest.mark.parametrize(
    ("value", "cause"),
    [
        (0.0, "not 0. 0 is what sqrt(f^2 + 0j).real"),
        (float("inf"), "not inf. Infinity is no focal"),
        (-1.0, "not -1. A negative focal"),
        ("complex", "sqrt(f^2 + 0j).real"),
        (None, "not None"),
    ],
)
def test_focal_check_names_a_sentinel_for_the_non_rotation(value, cause):
    """S12: 0, inf, -1, sqrt(f^2 + 0j).real or None where f^2 <= 0 is named as that, not "the same number
    twice" or "got tuple"."""
    from camlab.exercises.image_stitching.focal import _sentinel_student

    with pytest.raises(AssertionError, match="this H is not a rotation") as info:
        ex.check_focal_from_rotation_homography(_sentinel_student(value))
    message = str(info.value)
    assert "test input 8 of 8" in message and cause in message
    assert "same number twice" not in message and "got tuple" not in message


@pytest.mark.parametrize("formula", ["c1", "c2", "r1", "r2"])
def test_focal_check_names_a_sign_flip_in_any_one_formula(formula):
    from camlab.exercises.image_stitching.focal import _flipped

    with pytest.raises(AssertionError, match="sign flip"):
        ex.check_focal_from_rotation_homography(_flipped(formula))


def _box_student(rounding="ceil", route="numpy"):
    """A student's canvas_box: the corners mapped by ``route``, the box rounded by ``rounding``."""
    import cv2

    def student(Hs, shapes):
        pts = []
        for H, shape in zip(Hs, shapes, strict=True):
            h, w = shape[:2]
            H = np.asarray(H, float)
            corners = np.array([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]], float)
            if route == "cv2":  # divides by w itself, so a negative H needs nothing more
                pts.append(cv2.perspectiveTransform(corners[None], H)[0])
                continue
            if route == "unit norm":
                H = H / np.linalg.norm(H)
            dtype = np.float32 if route == "float32" else float
            c = np.c_[corners, np.ones(4)].astype(dtype) @ H.T.astype(dtype)
            pts.append(c[:, :2] / c[:, 2:])
        lo, hi = np.min(pts, axis=(0, 1)), np.max(pts, axis=(0, 1))
        top = {"ceil": np.ceil(hi), "floor + 1": np.floor(hi) + 1, "int + 1": hi.astype(int) + 1}
        return np.array([np.floor(lo), top[rounding]], float)

    return student


@pytest.mark.parametrize("route", ["numpy", "cv2", "float32", "unit norm"])
def test_canvas_box_check_passes_every_right_route_and_names_floor_plus_one(route, capsys):
    """A corner exactly on a pixel (the reference image, H = I) tells np.ceil from floor(max) + 1."""
    assert ex.check_canvas_box(_box_student("ceil", route)).passed
    assert "correct on all 7" in capsys.readouterr().out
    for rounding in ("floor + 1", "int + 1"):
        with pytest.raises(AssertionError, match=r"(?s)test input 7 of 7.*floor\(max\) \+ 1"):
            ex.check_canvas_box(_box_student(rounding, route))


def test_shape_unpacked_without_channels_gets_the_hint():
    from camlab.stitching import feather_weights
    from camlab.warp import canvas_box

    def feather(shape):
        h, w = shape  # (h, w, 3) fails here
        return feather_weights((h, w))

    def box(Hs, shapes):
        for s in shapes:
            h, w = s
        return canvas_box(Hs, shapes)

    for name, student, fix in (
        ("feather_weights", feather, "shape[:2]"),
        ("canvas_box", box, "s[:2]"),
    ):
        with pytest.raises(AssertionError) as info:
            getattr(ex, f"check_{name}")(student)
        assert "too many values to unpack" in str(info.value) and f"h, w = {fix}" in str(info.value)


def test_gains_check_passes_an_optimiser_that_stopped_short_and_names_brown_and_lowes_sigma():
    import numpy as np
    from scipy.optimize import minimize

    def bfgs(N, I_mean):  # e minimised directly: converged to about 2e-6, not to round-off
        N = np.array(N, dtype=float)
        M = np.asarray(I_mean, dtype=float)
        np.fill_diagonal(N, 0)

        def e(g):
            return 0.5 * np.sum(
                N * ((g[:, None] * M - g[None, :] * M.T) ** 2 / 100 + (1 - g[:, None]) ** 2)
            )

        return minimize(e, np.ones(len(N)), method="BFGS").x

    assert ex.check_gains_from_overlaps(bfgs).passed

    from camlab.exercises.image_stitching.gains import _solve

    with pytest.raises(AssertionError, match="Brown & Lowe's value"):
        ex.check_gains_from_overlaps(lambda N, M: _solve(N, np.asarray(M, float), sigma_g=0.1))
    # the data term 100 x too weak gives the same gains: the hint names that cause too
    with pytest.raises(AssertionError, match=r"sigma_N = 100"):
        ex.check_gains_from_overlaps(lambda N, M: _solve(N, np.asarray(M, float), sigma_n=100.0))


def _loop_student(data=2.0, prior="N"):
    """A student's loop over (i, j): data terms with factor ``data``; the prior weighted by N_ij ("N"),
    by 1 per overlap ("one per overlap"), once per image ("per image") or doubled ("N twice")."""
    import numpy as np

    def student(N, I_mean):
        N = np.array(N, dtype=float)
        M = np.asarray(I_mean, dtype=float)
        n = len(N)
        A, b = np.zeros((n, n)), np.zeros(n)
        for i in range(n):
            if prior == "per image":
                A[i, i] += 1.0
                b[i] += 1.0
            for j in range(n):
                if j == i or N[i, j] == 0:
                    continue
                w = {"N": N[i, j], "N twice": 2 * N[i, j], "one per overlap": 1.0}.get(prior, 0.0)
                A[i, i] += data * N[i, j] * M[i, j] ** 2 / 100 + w
                A[i, j] -= data * N[i, j] * M[i, j] * M[j, i] / 100
                b[i] += w
        return np.linalg.solve(A, b)

    return student


@pytest.mark.parametrize(
    "student, cause",
    [
        (
            _loop_student(prior="N twice"),
            "or the prior gained one",
        ),  # the data keeps its 2: both causes named
        (_loop_student(data=1.0), "lost their factor 2"),
        (_loop_student(data=4.0), "twice what it should"),
        (_loop_student(data=1.0, prior="N twice"), "a quarter"),
        (_loop_student(prior="one per overlap"), "weighted by the overlap size N_ij"),
        (_loop_student(prior="per image"), "one 1 / sigma_g^2 per image"),
    ],
)
def test_gains_check_names_the_real_cause_of_a_misweighted_prior(student, cause):
    assert ex.check_gains_from_overlaps(_loop_student()).passed  # the loop itself is right
    with pytest.raises(AssertionError) as info:
        ex.check_gains_from_overlaps(student)
    assert cause in str(info.value)
    assert "sigma_N = 10/255" not in str(info.value)  # a prior too weak is not blamed on sigma_N


def test_focal_inverse_route_named_on_the_no_rotation_input():
    """C13: f_from from the columns of H^-1 passes every turn; on the last input (no rotation) the check
    names that route (the orthogonality formulas on H^-1 give f^2 > 0 there, all four on H give f^2 < 0)."""
    from camlab.exercises.image_stitching import focal as F

    H, shape = F._focal_cases()[-1]
    on_h = F._focal_formulas(H, shape, squared=True)
    on_inv = F._focal_formulas(np.linalg.inv(H), shape, squared=True)
    assert max(on_h.values()) < 0 and on_inv["c1"] > 0 and on_inv["r1"] > 0

    def inverse_route(H, shape):
        return F.focal_from_rotation_homography(np.linalg.inv(H), shape)[::-1]

    with pytest.raises(AssertionError, match="test input 8 of 8(?s:.*)formulas give on H\\^-1"):
        ex.check_focal_from_rotation_homography(inverse_route)


def test_gains_slips_fail_first_on_the_dark_trio_by_percents():
    """C13: a weight slip must fail first where it moves the gains by percents, not by 2e-4."""
    from camlab.exercises.image_stitching import gains as G

    cases = G._gains_cases()
    moved = [np.abs(G._variant("no factor 2")(*a) / G._reference(*a) - 1).max() for a in cases]
    assert moved[0] > 0.02 and max(moved[1:]) < 0.002


def test_canvas_projections_frames_the_canvas_in_grey_where_the_box_leaves_room():
    from camlab.widgets.image_stitching.canvas import BOX, _place

    white = np.full((100, 200, 4), 255, np.uint8)
    out = _place(white)
    y0, x0 = (BOX[0] - 100) // 2, (BOX[1] - 200) // 2
    assert (out[y0 : y0 + 100, x0 : x0 + 200] == 255).all()  # the canvas as given, centred
    grey = np.all(out[..., :3] == 153, axis=2)
    rows, cols = slice(y0 - 3, y0 + 103), slice(x0 - 3, x0 + 203)
    assert grey[y0 - 3, cols].all() and grey[y0 + 102, cols].all() and grey[y0 - 2, cols].all()
    assert grey[rows, x0 - 3].all() and grey[rows, x0 + 202].all() and grey[rows, x0 + 201].all()
    assert (
        grey.sum() == 206 * 106 - 202 * 102
    )  # the frame, 2 px wide and 3 px outside the canvas, nothing else
    wide = _place(np.full((100, BOX[1], 4), 255, np.uint8))  # fills the width: no side frame
    grey = np.all(wide[..., :3] == 153, axis=2)
    assert (wide[y0 : y0 + 100, :, :3] == 255).all() and grey.sum() == 4 * BOX[1]
