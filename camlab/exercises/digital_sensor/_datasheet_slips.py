"""More slips of lesson 03's datasheet exercise (reviews G12-8, F12-7, N12-7), rows of its mistake table.

Each row reads the context :mod:`.datasheet` builds: ``g`` the answer, ``f_mm``, ``w_mm``, ``h_mm``,
``W``, ``H``, ``cx``, ``cy``.
"""

from __future__ import annotations

import numpy as np

from .._core import Mistake


def _near(a, b):
    """Equal to rounding (the check's own tolerance is 1e-9)."""
    return np.isclose(a, b, rtol=1e-6, atol=1e-9)


AXIS_AND_SIGN_SLIPS = (
    Mistake(
        "the diagonal over W and over H",
        lambda s: (
            _near(s.g[0, 0], s.f_mm * s.W / np.hypot(s.w_mm, s.h_mm))
            and _near(s.g[1, 1], s.f_mm * s.H / np.hypot(s.w_mm, s.h_mm))
        ),
        lambda s: (
            f"you divided the sensor's diagonal ({np.hypot(s.w_mm, s.h_mm):.2f} mm) by W and by H: each pitch is "
            f"its own axis's length over its own pixel count, s_x = width / W = {s.w_mm / s.W * 1e3:.4g} µm and "
            f"s_y = height / H = {s.h_mm / s.H * 1e3:.4g} µm; the diagonal belongs to neither axis"
        ),
    ),
    Mistake(
        "principal point with its sign flipped",
        lambda s: (_near(s.g[0, 2], -s.cx) or _near(s.g[1, 2], -s.cy)) and s.cx > 0,
        (
            "the principal point has its sign flipped: c_x = -(W - 1) / 2 would put the image centre left of "
            "pixel 0. u counts from the top-left pixel's centre, so the centre sits at +(W - 1) / 2, "
            "+(H - 1) / 2"
        ),
    ),
)
"""The diagonal divided by each axis's pixel count; the principal point with its sign flipped."""


EQUIVALENT_OVER_FULL_WIDTH = Mistake(
    "35 mm-equivalent focal length over a full frame's width",
    lambda s: np.isclose(
        s.g[0, 0], s.f_mm * np.hypot(36, 24) / np.hypot(s.w_mm, s.h_mm) * s.W / 36, rtol=0.02
    ),
    lambda s: (
        f"f_x is f_eq * W / 36 = {s.g[0, 0]:.0f} px: you used the 35 mm-equivalent focal length "
        f"(f_eq = {s.f_mm * np.hypot(36, 24) / np.hypot(s.w_mm, s.h_mm):.1f} mm here) with a full frame's 36 mm "
        f"width. Both belong to a 36 x 24 mm sensor, and this one's aspect differs; K needs the real focal "
        f"length over the real pitch, f_x = f / s_x = {s.f_mm} mm / ({s.w_mm} mm / {s.W})"
    ),
)
"""The 35 mm-equivalent focal length over a full frame's 36 mm width: f_x = f_eq W / 36 (review N12-7)."""


PITCH_FROM_OTHER_COUNT = Mistake(
    "pitches from the other axis's pixel count",
    lambda s: (
        (_near(s.g[0, 0], s.f_mm * s.H / s.w_mm) and _near(s.g[1, 1], s.f_mm * s.W / s.h_mm))
        and (not _near(s.W, s.H))
    ),
    (
        "the pitches divide each sensor side by the other side's pixel count: s_x = width / W (W pixels across), "
        "s_y = height / H (H pixels down), not width / H and height / W"
    ),
)
"""Each side divided by the other side's pixel count: s_x = width / H, s_y = height / W (review A13-11)."""


PITCH_SLIPS = (
    PITCH_FROM_OTHER_COUNT,
    Mistake(
        "f_x and f_y swapped",
        lambda s: _near(s.g[0, 0], s.fy) and _near(s.g[1, 1], s.fx) and (not _near(s.fx, s.fy)),
        (
            "f_x and f_y are swapped: f_x = f / s_x with the horizontal pitch s_x = width / W, f_y = f / s_y with "
            "s_y = height / H"
        ),
    ),
)
"""The pitch slips, in the order the table tries them."""
