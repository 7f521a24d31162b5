"""Lesson 02's first exercise.

The field of view of a lens focused closer than infinity (the thin lens of section 1 with the field
of view of section 3).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import lens
from .._core import Exercise, Mistake, first_mistake, register_exercise
from .._numbers import is_number as _is_number
from .._numbers import not_one_number, same_number

# -- field_of_view ----------------------------------------------------------------------------


def _field_of_view_cases():
    # the first case focuses close (z_i = 1.2 f), so every slip in z_i or in the angle shows at once
    return [(0.05, 0.036, 0.3), (0.035, 0.0236, 2.0), (0.1, 0.036, 0.25), (0.024, 0.0063, 0.1)]


def _fov_context(f, w, zo, g, expected):
    """What the rows of :data:`_FOV_MISTAKES` read.

    The input, the answer ``g``, the sensor distance ``zi``, the signed magnification ``m`` and
    ``fov(distance, width)``, the field of view 2 arctan(width / (2 distance)).
    """

    def fov(distance, width=w):
        return 2 * np.arctan(width / (2 * distance))

    return SimpleNamespace(
        f=f,
        w=w,
        zo=zo,
        g=g,
        expected=expected,
        zi=f * zo / (zo - f),
        m=-f / (zo - f),  # the signed magnification, negative for a real image
        fov=fov,
    )


_FOV_MISTAKES = (
    Mistake(
        "the narrowing",
        lambda s: any(
            np.isclose(s.g, narrowing)
            for narrowing in (
                s.fov(s.f) - s.expected,
                np.degrees(s.fov(s.f) - s.expected),
                1 - s.expected / s.fov(s.f),
            )
        ),
        (
            "that is how much narrower the view is than focused at infinity; the function returns the field of "
            "view itself, 2 arctan(w / (2 z_i)) in radians (the check prints the narrowing once it passes)"
        ),
    ),
    Mistake(
        "degrees",
        lambda s: np.isclose(s.g, np.degrees(s.expected)),
        (
            "that is the angle in degrees; the course's functions return radians (np.degrees only for printing)"
        ),
    ),
    Mistake(
        "focused at infinity, in degrees",
        lambda s: np.isclose(s.g, np.degrees(s.fov(s.f))),
        (
            "two slips: that is the field of view focused at infinity, 2 arctan(w / 2f), and in degrees. Focused at "
            "z_o the sensor sits at z_i = f z_o / (z_o - f), so use 2 arctan(w / (2 z_i)), in radians"
        ),
    ),
    Mistake(
        "half-angle in degrees",
        lambda s: np.isclose(s.g, np.degrees(s.expected / 2)),
        (
            "two slips: that is the half-angle, and in degrees; the field of view spans both sides of the axis, "
            "2 arctan(w / (2 z_i)), in radians (np.degrees only for printing)"
        ),
    ),
    Mistake(
        "arctan2's arguments swapped",
        lambda s: np.isclose(s.g, np.pi - s.expected),
        (
            "that is pi minus the field of view: np.arctan2's arguments are swapped. It takes (y, x), the side "
            "opposite the angle first: 2 np.arctan2(w / 2, z_i)"
        ),
    ),
    Mistake(
        "arcsine",
        lambda s: s.w < 2 * s.zi and np.isclose(s.g, 2 * np.arcsin(s.w / (2 * s.zi))),
        (
            "you took the arcsine: half the sensor width over z_i is the angle's tangent (the two legs of a right "
            "triangle), not its sine (that would need the hypotenuse): 2 np.arctan(w / (2 z_i))"
        ),
    ),
    Mistake(
        "negative",
        lambda s: np.isclose(-s.g, s.expected),
        (
            "the angle came out negative: a sign slip; the field of view 2 arctan(w / (2 z_i)) is positive"
        ),
    ),
    Mistake(
        "negative z_i",
        lambda s: s.g < 0,
        (
            "the angle came out negative, so your z_i is negative: 1/f - 1/z_o < 0 means z_o < f in your units. "
            "Mixed units? (f in millimetres, z_o in metres: 50 mm 'inside' 0.3 m); keep every length in metres"
        ),
    ),
    Mistake(
        "tangent of the ratio",
        lambda s: np.isclose(s.g, 2 * np.tan(s.w / (2 * s.zi))),
        (
            "you took the tangent of the ratio; the angle is its arctangent: 2 np.arctan(w / (2 z_i))"
        ),
    ),
    Mistake(
        "focused at infinity",
        lambda s: np.isclose(s.g, s.fov(s.f)),
        (
            "that is the field of view focused at infinity, 2 arctan(w / 2f); focused at z_o the sensor sits at "
            "z_i = f z_o / (z_o - f), farther than f, so the pinhole focal length is z_i: 2 arctan(w / (2 z_i))"
        ),
    ),
    Mistake(
        "object distance",
        lambda s: np.isclose(s.g, s.fov(s.zo)),
        (
            "you used the object distance z_o; the angle is set on the sensor's side: half the sensor width "
            "over the lens-to-sensor distance z_i = f z_o / (z_o - f)"
        ),
    ),
    Mistake(
        "half-angle",
        lambda s: np.isclose(s.g, np.arctan(s.w / (2 * s.zi))),
        (
            "that is the half-angle; the field of view spans both sides of the axis: 2 arctan(w / (2 z_i))"
        ),
    ),
    Mistake(
        "full width with the half-angle",
        lambda s: (
            np.isclose(s.g, 2 * np.arctan(s.w / s.zi)) or np.isclose(s.g, np.arctan(s.w / s.zi))
        ),
        (
            "half the sensor width goes with the half-angle: tan(FOV / 2) = (w / 2) / z_i, so "
            "FOV = 2 arctan(w / (2 z_i))"
        ),
    ),
    Mistake(
        "small-angle",
        lambda s: np.isclose(s.g, s.w / s.zi),
        ("w / z_i is the small-angle approximation; take the arctangent: 2 arctan(w / (2 z_i))"),
    ),
    Mistake(
        "z_i with + f",
        lambda s: np.isclose(s.g, s.fov(s.f * s.zo / (s.zo + s.f))),
        ("sign slip in the thin lens: 1/z_i = 1/f - 1/z_o, so z_i = f z_o / (z_o - f)"),
    ),
    Mistake(
        "z_i from the size of m",
        lambda s: np.isclose(s.g, s.fov(s.f * (1 + s.m))),
        (
            "z_i = (1 + |m|) f takes the size of m; the signed m = -f / (z_o - f) is negative "
            "for a real image, so f (1 + m) comes out shorter than f instead of longer"
        ),
    ),
    Mistake(
        "z_i to first order",
        lambda s: np.isclose(s.g, s.fov(s.f * (1 + s.f / s.zo))),
        (
            "f (1 + f / z_o) is the first-order approximation of z_i (good only for "
            "z_o >> f); the check wants the exact thin lens, z_i = f z_o / (z_o - f)"
        ),
    ),
    Mistake(
        "z_i from F'",
        lambda s: np.isclose(s.g, s.fov(s.f**2 / (s.zo - s.f))),
        (
            "f^2 / (z_o - f) is the image's distance from the focal point F', not from "
            "the lens; the lens-to-sensor distance is f plus that: z_i = f z_o / (z_o - f)"
        ),
    ),
    Mistake(
        "1/z_i as the distance",
        lambda s: np.isclose(s.g, s.fov(1 / s.f - 1 / s.zo)),
        ("you used 1/z_i as the distance; invert it: z_i = 1 / (1/f - 1/z_o)"),
    ),
    Mistake(
        "z_i = f + z_o",
        lambda s: np.isclose(s.g, s.fov(s.f + s.zo)),
        (
            "z_i = f + z_o adds the distances; the thin lens adds their reciprocals, 1/f = 1/z_o + 1/z_i, "
            "so z_i = f z_o / (z_o - f) (60 mm for a 50 mm lens at 0.3 m)"
        ),
    ),
    Mistake(
        "z_o - f",
        lambda s: np.isclose(s.g, s.fov(s.zo - s.f)),
        (
            "z_o - f is not where the image forms (it is the object's distance from the focal point F); the "
            "thin lens puts it at z_i = f z_o / (z_o - f), from 1/f = 1/z_o + 1/z_i"
        ),
    ),
    Mistake(
        "diagonal field of view",
        lambda s: any(
            np.isclose(s.g, s.fov(s.zi, diagonal)) or np.isclose(s.g, s.fov(s.f, diagonal))
            for diagonal in (np.hypot(s.w, 2 * s.w / 3), np.hypot(s.w, 3 * s.w / 4), 0.0433)
        ),
        (
            "that is the diagonal field of view; the horizontal one uses the sensor's width w as given: "
            "2 arctan(w / (2 z_i))"
        ),
    ),
    Mistake(
        "w and f swapped",
        lambda s: (
            np.isclose(s.g, s.fov(s.zi, s.f))
            or (
                s.zo > s.w and np.isclose(s.g, 2 * np.arctan(s.f / (2 * s.w * s.zo / (s.zo - s.w))))
            )
        ),
        (
            "w and f are swapped: the sensor width w goes over the lens-to-sensor distance, 2 arctan(w / (2 z_i))"
        ),
    ),
    Mistake(
        "mixed units",
        lambda s: any(np.isclose(s.g, s.fov(s.zi, s.w * factor)) for factor in (1e3, 1e-3)),
        (
            "mixed units: the width and the distance must be in one unit (the inputs are all in metres; "
            "0.036 is 36 mm)"
        ),
    ),
    Mistake(
        "infinity's angle scaled",
        lambda s: np.isclose(s.g, s.fov(s.f) * s.f / s.zi),
        (
            "you scaled the field of view at infinity by f / z_i: the angle is not proportional to the distance "
            "(it is an arctangent). Compute it afresh over z_i: 2 arctan(w / (2 z_i))"
        ),
    ),
    Mistake(
        "the sensor's height",
        lambda s: np.isclose(s.g, s.fov(s.zi, 2 * s.w / 3)),
        (
            "that is the field of view across the sensor's height (2/3 of its width on a 3:2 sensor); the "
            "horizontal field of view takes the width w itself: 2 arctan(w / (2 z_i))"
        ),
    ),
    Mistake(
        "rounded",
        lambda s: (
            any(
                np.isclose(s.g, conv(round(float(np.degrees(s.expected)), k)), rtol=0, atol=1e-12)
                for k in (0, 1, 2)
                for conv in (np.radians, float)
            )
            or any(
                np.isclose(s.g, round(float(s.expected), k), rtol=0, atol=1e-12)
                for k in (1, 2, 3, 4)
            )
        ),
        (
            "you rounded the angle; return it exact, in radians (round only when you print it, as the "
            "check's note does)"
        ),
    ),
)
"""The field of view's slips, in the order they are tested: in the angle (degrees, sign, tangent, half) and in
the distance it is taken over (z_i from a wrong thin lens, z_o, f), or in the width."""


def _field_of_view_diagnosis(args, got, expected) -> str:
    f, w, zo = args
    if not _is_number(got):
        return not_one_number(got, "the field of view in radians")
    g = float(got)
    cause = first_mistake(_FOV_MISTAKES, _fov_context(f, w, zo, g, expected))
    return cause or (
        "find z_i from 1/f = 1/z_o + 1/z_i, then the field of view 2 arctan(w / (2 z_i)) in radians"
    )


def _field_of_view_note(run) -> str:
    """Exercise 1's question, answered with the student's own function once it passes."""
    close, far = np.degrees(run(0.05, 0.036, 0.3)), np.degrees(2 * np.arctan(0.036 / (2 * 0.05)))
    return (
        f"The question: a 50 mm lens on full frame (w = 36 mm) sees {far:.1f} deg focused at infinity and "
        f"{close:.1f} deg focused at 0.3 m (z_i = 60 mm): {far - close:.1f} deg, {1 - close / far:.0%} narrower."
    )


def field_of_view(f, w, z_o):
    """Horizontal field of view (radians) of a lens f focused at z_o on a sensor w wide (metres).

    Parameters
    ----------
    f : float
        The focal length, m.
    w : float
        The sensor's width, m.
    z_o : float
        The distance focused on, m (z_o > f).

    Returns
    -------
    float
        2 arctan(w / (2 z_i)), rad, with the image distance z_i = f z_o / (z_o - f) (thin-lens equation).
    """
    z_i = f * z_o / (z_o - f)  # the sensor's distance behind the lens: the pinhole focal length
    return 2 * np.arctan(w / (2 * z_i))  # half the width over z_i is the tangent of the half-angle


register_exercise(
    Exercise(
        name="field_of_view",
        lesson="02",
        reference=lens.angle_of_view,
        cases=_field_of_view_cases,
        compare=same_number(rtol=1e-9),
        diagnose=_field_of_view_diagnosis,
        success_note=_field_of_view_note,
        wrong_variants=(
            (lambda f, w, zo: 2 * np.arctan(w / (2 * f)), "focused at infinity"),
            (lambda f, w, zo: np.degrees(2 * np.arctan(w / (2 * f * zo / (zo - f)))), "degrees"),
            (lambda f, w, zo: np.arctan(w / (2 * f * zo / (zo - f))), "half-angle"),
            (lambda f, w, zo: 2 * np.arctan(w / (f * zo / (zo - f))), "half the sensor width"),
            (lambda f, w, zo: w / (f * zo / (zo - f)), "small-angle"),
            (lambda f, w, zo: 2 * np.arctan(w / (2 * f * zo / (zo + f))), "sign slip"),
            (
                lambda f, w, zo: 2 * np.arctan(w / (2 * f**2 / (zo - f))),
                "from the focal point F', not from",
            ),
            (
                lambda f, w, zo: 2 * np.arctan(w / (2 * f * (1 - f / (zo - f)))),
                "takes the size of m",
            ),
            (
                lambda f, w, zo: 2 * np.arctan(w / (2 * f * (1 + f / zo))),
                "first-order approximation",
            ),
            (
                lambda f, w, zo: 2 * np.arctan(w / (2 * 1e3 * f * zo / (zo - 1e3 * f))),
                "came out negative, so your z_i",
            ),
            (lambda f, w, zo: 2 * np.arctan(w / (2 * zo)), "object distance"),
            (lambda f, w, zo: 2 * np.arctan(1e3 * w / (2 * f * zo / (zo - f))), "mixed units"),
            (lambda f, w, zo: [2 * np.arctan(w / (2 * f * zo / (zo - f)))], "return one number"),
            (lambda f, w, zo: (2 * np.arctan(w / (2 * f * zo / (zo - f))),), "a trailing comma"),
            (
                lambda f, w, zo: 2 * np.arctan(w / (2 * (zo - f))),
                "z_o - f is not where the image forms",
            ),
            (
                lambda f, w, zo: 2 * np.arctan(np.hypot(w, 2 * w / 3) / (2 * f * zo / (zo - f))),
                "diagonal field of view",
            ),
            (lambda f, w, zo: 2 * np.arctan(f / (2 * w * zo / (zo - w))), "w and f are swapped"),
            (lambda f, w, zo: -2 * np.arctan(w / (2 * f * zo / (zo - f))), "a sign slip"),
            (lambda f, w, zo: 2 * np.tan(w / (2 * f * zo / (zo - f))), "its arctangent"),
            (
                lambda f, w, zo: 2 * np.arctan2(f * zo / (zo - f), w / 2),
                "arctan2's arguments are swapped",
            ),
            (lambda f, w, zo: 2 * np.arcsin(w / (2 * f * zo / (zo - f))), "you took the arcsine"),
            (lambda f, w, zo: 2 * np.arctan(w / (2 * (f + zo))), "adds the distances"),
            (
                lambda f, w, zo: np.degrees(np.arctan(w / (2 * f * zo / (zo - f)))),
                "half-angle, and in degrees",
            ),
            (
                lambda f, w, zo: np.degrees(2 * np.arctan(w / (2 * f))),
                "two slips: that is the field",
            ),
            (
                lambda f, w, zo: 2 * np.arctan(w / (2 * f)) * (zo - f) / zo,
                "scaled the field of view at infinity",
            ),
            (
                lambda f, w, zo: 2 * np.arctan(2 * w / 3 / (2 * f * zo / (zo - f))),
                "across the sensor's height",
            ),
            (
                lambda f, w, zo: np.radians(
                    round(float(np.degrees(lens.angle_of_view(f, w, zo))), 1)
                ),
                "you rounded the angle",
            ),
            (
                lambda f, w, zo: round(float(lens.angle_of_view(f, w, zo)), 3),
                "you rounded the angle",
            ),
            (
                lambda f, w, zo: 2 * np.arctan(w / (2 * f)) - lens.angle_of_view(f, w, zo),
                "how much narrower the view is",
            ),
        ),
        teaching=field_of_view,
    )
)
