"""Lesson 01's exercise focal_length_pixels: f_x in pixels from a horizontal field of view and the image size."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from .._answers import Tolerance
from .._core import Exercise, Mistake, first_mistake, register_exercise
from .._numbers import SameNumber

# ---------------------------------------------------------------- focal_length_pixels


def _fx_reference(fov_deg, size):
    """f_x = (W / 2) / tan(FOV / 2): the sensor's half-width W / 2 pixels seen at half the field of view."""
    W = size[0]
    return float(W / 2 / np.tan(np.radians(fov_deg) / 2))


def _fx_cases():
    # no 60 or 90 degrees: tan 30 = 1 / tan 60 and tan 45 = 1 make slips coincide with each other or the answer
    # and one odd width, last: W // 2 equals W / 2 for the three even ones (641 // 2 is 320, not 320.5)
    return [(50.0, (640, 480)), (75.0, (1920, 1080)), (39.6, (320, 240)), (55.0, (641, 481))]


FX_TOLERANCE = Tolerance(2e-4, 0.0)
"""f_x to 0.1 px passes (a rounded 444.4 is 9e-5 off); (W - 1) / 2 for W / 2 (5e-4 off at W = 1920) does not."""


def one_number(got, what: str) -> str | None:
    """Why ``got`` is not one number (a list or an array of numbers, say), or None.

    Parameters
    ----------
    got : object
        The student's answer.
    what : str
        What the number is, for the message ("f_x in pixels").

    Returns
    -------
    str or None
        The hint, or None when ``got`` is one number.
    """
    if np.ndim(got) != 0:
        kind = "numpy array" if isinstance(got, np.ndarray) else type(got).__name__
        return (
            f"you returned a {kind} of shape {np.shape(got)}; return one number, {what} (a float:"
            f" take the entry out, x[0], or build a number, not a list or an array)"
        )
    try:
        float(got)
    except (TypeError, ValueError):
        return f"return one number: {what}"
    return None


_FX_SLIPS = (
    Mistake(
        "degrees",
        lambda s: s.W / 2 / np.tan(s.fov / 2),
        ("np.tan takes radians: convert the field of view with np.radians(fov_deg) first"),
    ),
    Mistake(
        "degrees and W",
        lambda s: s.W / np.tan(s.fov / 2),
        ("np.tan takes radians (np.radians(fov_deg)), and the half-width is W / 2"),
    ),
    Mistake(
        "full angle",
        lambda s: s.W / 2 / np.tan(s.full),
        (
            "use half the field of view: the ray to the sensor's edge makes FOV / 2 with the axis,"
            " so tan(FOV / 2) = (W / 2) / f_x"
        ),
    ),
    Mistake(
        "W not W / 2",
        lambda s: s.W / np.tan(s.half),
        (
            "the ray to the sensor's edge runs W / 2 pixels sideways, not W: tan(FOV / 2) = (W / 2) / f_x"
        ),
    ),
    Mistake(
        "full angle and W",
        lambda s: s.W / np.tan(s.full),
        ("both halves missing: tan(FOV / 2) = (W / 2) / f_x (half the angle, half the width)"),
    ),
    Mistake(
        "W // 2",
        lambda s: s.W // 2 / np.tan(s.half),
        (
            "size[0] // 2 drops the half pixel of an odd width (641 // 2 is 320, not 320.5): the half-width is"
            " W / 2, divided with /, not //"
        ),
    ),
    Mistake(
        "(W - 1) / 2",
        lambda s: (s.W - 1) / 2 / np.tan(s.half),
        (
            "the sensor spans all W pixels: its edges are the outer edges of the first and"
            " last pixels, W pixels apart; (W - 1) / 2 is the centre's coordinate, not the"
            " half-width"
        ),
    ),
    Mistake(
        "(W + 1) / 2",
        lambda s: (s.W + 1) / 2 / np.tan(s.half),
        (
            "off by one, 1-based: (W + 1) / 2 is the centre pixel counted from 1; the half-width is W / 2,"
            " since the sensor's edges are the outer edges of its first and last pixels"
        ),
    ),
    Mistake(
        "(W - 1) // 2",
        lambda s: (s.W - 1) // 2 / np.tan(s.half),
        (
            "(W - 1) // 2 is the centre pixel's index rounded down by the integer division"
            " //; the half-width is W / 2 (the sensor's edges are the outer edges of its"
            " first and last pixels), and divide with /"
        ),
    ),
    Mistake(
        "small-angle",
        lambda s: s.W / s.full,
        (
            "the small-angle shortcut tan(a) ~ a: FOV / 2 is no small angle (tan 25 deg is 0.466, against"
            " 0.436 rad); use the tangent itself, f_x = (W / 2) / tan(FOV / 2)"
        ),
    ),
    Mistake(
        "arctan",
        lambda s: s.W / 2 / np.arctan(s.half),
        ("arctan is the inverse of tan: tan(FOV / 2) = (W / 2) / f_x needs np.tan, not np.arctan"),
    ),
    Mistake(
        "radians of the tangent",
        lambda s: s.W / 2 / np.radians(np.tan(s.fov / 2)),
        (
            "np.radians(np.tan(...)) converts the tangent, a plain number, as if it"
            " were an angle: convert the angle first, np.tan(np.radians(fov_deg) / 2)"
        ),
    ),
    Mistake(
        "degrees of degrees",
        lambda s: s.W / 2 / np.tan(np.degrees(s.fov) / 2),
        (
            "np.degrees converts radians to degrees, the wrong way here: fov_deg is already in degrees, and"
            " np.tan wants radians, np.radians(fov_deg)"
        ),
    ),
    Mistake(
        "degrees of the tangent",
        lambda s: s.W / 2 / np.degrees(np.tan(s.half)),
        (
            "np.degrees(np.tan(...)) converts the tangent, a plain number, as if it were an angle: the"
            " tangent needs no conversion, f_x = (W / 2) / np.tan(np.radians(fov_deg) / 2)"
        ),
    ),
    Mistake(
        "halved twice",
        lambda s: s.W / 2 / np.tan(s.half / 2),
        (
            "the angle is halved twice: np.radians(fov_deg) / 2 is already FOV / 2 (or"
            " np.radians(fov_deg / 2)); do not halve it again"
        ),
    ),
    Mistake(
        "height",
        lambda s: s.H / 2 / np.tan(s.half),
        ("size is (width, height): the horizontal field of view spans the width, size[0]"),
    ),
    Mistake(
        "sin",
        lambda s: s.W / 2 / np.sin(s.half),
        ("tan, not sin: the right triangle has legs f_x (along the axis) and W / 2 (across)"),
    ),
    Mistake(
        "upside down",
        lambda s: 2 * np.tan(s.half) / s.W,
        ("upside down: tan(FOV / 2) = (W / 2) / f_x, so f_x = (W / 2) / tan(FOV / 2)"),
    ),
    Mistake(
        "the FOV formula",
        lambda s: np.degrees(2 * np.arctan(s.W / (2 * s.fov))),
        (
            "that is the field-of-view formula run the other way; solve"
            " FOV = 2 atan(W / (2 f_x)) for f_x"
        ),
    ),
    Mistake(
        "times the tangent",
        lambda s: s.W / 2 * np.tan(s.half),
        (
            "you multiplied by tan(FOV / 2); divide: tan(FOV / 2) = (W / 2) / f_x, so"
            " f_x = (W / 2) / tan(FOV / 2)"
        ),
    ),
    Mistake(
        "sign",
        lambda s: -s.expected,
        ("a sign flip: f_x is a positive length, (W / 2) / tan(FOV / 2)"),
    ),
    Mistake(
        "diagonal",
        lambda s: np.hypot(s.W, s.H) / 2 / np.tan(s.half),
        (
            "you used the diagonal, hypot(W, H): the field of view here is the"
            " horizontal one, across the width W"
        ),
    ),
    Mistake(
        "f in metres",
        lambda s: 0.018 / np.tan(s.half),
        (
            "that is f in metres for section 2's 36 mm sensor; the answer is in pixels, the"
            " sensor's W pixels: f_x = (W / 2) / tan(FOV / 2)"
        ),
    ),
    Mistake(
        "f in millimetres",
        lambda s: 18 / np.tan(s.half),
        (
            "that is f in millimetres for section 2's 36 mm sensor; the answer is in pixels, the"
            " sensor's W pixels: f_x = (W / 2) / tan(FOV / 2)"
        ),
    ),
)
"""Slips in f_x: each row's answer from the field of view ``s.fov`` (degrees; ``s.half`` and ``s.full`` in
radians), the size ``s.W``, ``s.H`` and the right answer ``s.expected``."""


def _fx_diagnosis(args, got, expected) -> str:
    fov, (W, H) = args
    if np.shape(got) == (2,) and not isinstance(got, str):
        return (
            "you returned two numbers, perhaps (f_x, f_y): return f_x alone, one float (the pixels are square, so"
            " f_y is the same number)"
        )
    problem = one_number(got, "f_x in pixels")
    if problem:
        return problem
    g = float(got)
    half, full = np.radians(fov) / 2, np.radians(fov)
    context = SimpleNamespace(W=W, H=H, fov=fov, half=half, full=full, expected=expected)
    cause = first_mistake(
        _FX_SLIPS, context, g, lambda got, wrong: np.isclose(got, wrong, rtol=1e-6)
    )
    if cause:
        return cause
    # two slips at once: a sign flip on top of one of the table's (the degrees slip alone can come out negative)
    cause = first_mistake(
        _FX_SLIPS, context, -g, lambda got, wrong: np.isclose(got, wrong, rtol=1e-6)
    )
    if cause:
        return f"a sign flip (f_x is a positive length), and besides: {cause}"
    if abs(g - expected) <= 1.0 and g == round(g):
        return (
            "you rounded f_x to a whole pixel (round() or int()); return it unrounded, or to 0.1 px at least: a"
            " focal length in pixels is a measurement, not a pixel index"
        )
    return (
        "tan(FOV / 2) = (W / 2) / f_x, so f_x = (W / 2) / tan(FOV / 2); the tangent of the half-angle in radians,"
        " np.tan(np.radians(fov_deg) / 2)"
    )


def focal_length_pixels(fov_deg, size):
    """f_x in pixels for a horizontal field of view ``fov_deg`` (degrees) and an image ``size`` (width, height).

    The edge ray makes FOV / 2 with the axis and meets the sensor W / 2 pixels from its centre:
    tan(FOV / 2) = (W / 2) / f_x.

    Parameters
    ----------
    fov_deg : float
        The horizontal field of view, degrees.
    size : (2,) array_like
        The image's (width, height), pixels.

    Returns
    -------
    float
        f_x = (W / 2) / tan(FOV / 2), pixels.
    """
    width = size[0]
    half_angle = np.radians(fov_deg) / 2
    return float(width / 2 / np.tan(half_angle))


register_exercise(
    Exercise(
        name="focal_length_pixels",
        lesson="01",
        reference=_fx_reference,
        cases=_fx_cases,
        compare=SameNumber(FX_TOLERANCE),
        diagnose=_fx_diagnosis,
        wrong_variants=(
            (lambda fov, size: size[0] / 2 / np.tan(fov / 2), "radians"),
            (lambda fov, size: size[0] / 2 / np.tan(np.radians(fov)), "half the field of view"),
            (lambda fov, size: size[0] / np.tan(np.radians(fov) / 2), "W / 2"),
            (lambda fov, size: (size[0] - 1) / 2 / np.tan(np.radians(fov) / 2), "all W pixels"),
            (lambda fov, size: size[1] / 2 / np.tan(np.radians(fov) / 2), "(width, height)"),
            (lambda fov, size: np.array([size[0] / 2 / np.tan(np.radians(fov) / 2)]), "one number"),
            (lambda fov, size: size[0] / 2 * np.tan(np.radians(fov) / 2), "you multiplied by tan"),
            (lambda fov, size: float(int(size[0] / 2 / np.tan(np.radians(fov) / 2))), "rounded"),
            (lambda fov, size: np.hypot(*size) / 2 / np.tan(np.radians(fov) / 2), "diagonal"),
            (lambda fov, size: 0.018 / np.tan(np.radians(fov) / 2), "f in metres"),
            (lambda fov, size: (size[0] + 1) / 2 / np.tan(np.radians(fov) / 2), "1-based"),
            (
                lambda fov, size: (size[0] - 1) // 2 / np.tan(np.radians(fov) / 2),
                "integer division",
            ),
            (lambda fov, size: size[0] / np.radians(fov), "small-angle"),
            (
                lambda fov, size: size[0] / 2 / np.arctan(np.radians(fov) / 2),
                "arctan is the inverse",
            ),
            (lambda fov, size: size[0] / 2 / np.tan(np.radians(fov / 2) / 2), "halved twice"),
            (lambda fov, size: size[0] / 2 / np.tan(np.degrees(fov) / 2), "the wrong way here"),
            (
                lambda fov, size: size[0] / 2 / np.degrees(np.tan(np.radians(fov) / 2)),
                "needs no conversion",
            ),
            (
                lambda fov, size: -(size[0] - 1) / 2 / np.tan(np.radians(fov) / 2),
                "and besides: the sensor spans all W pixels",
            ),
            (lambda fov, size: (size[0] / 2 / np.tan(np.radians(fov) / 2),), "trailing comma"),
            (lambda fov, size: size[0] // 2 / np.tan(np.radians(fov) / 2), "641 // 2 is 320"),
            (
                lambda fov, size: (size[0] / 2 / np.tan(np.radians(fov) / 2),) * 2,
                "perhaps (f_x, f_y)",
            ),
            (
                lambda fov, size: f"{size[0] / 2 / np.tan(np.radians(fov) / 2):.1f}",
                "you returned a str",
            ),
        ),
        teaching=focal_length_pixels,
    )
)
