"""Lesson 02's exercise f_number_for_depth.

The aperture that makes a depth range sharp (section 2's c(z) solved the other way).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import lens
from .._core import Exercise, Mistake, first_mistake, register_exercise
from .._numbers import is_number as _is_number
from .._numbers import not_one_number, same_number

# -- f_number_for_depth -------------------------------------------------------------------------


def _f_number_cases():
    # the first range has far != 2 near, so c / 2 or 2 c cannot be mistaken for the two ends' mix-ups
    return [
        (0.05, 0.03e-3, 2.0, 3.5),
        (0.028, 0.02e-3, 0.8, 1.6),
        (0.085, 0.03e-3, 1.9, 2.1),
        (0.1, 0.015e-3, 9.0, 11.0),
    ]


def _f_number_reference(f, c, near, far):
    """camlab.lens.aperture_for_depth_of_field(f, c, near, far).f_number: the same two equal-blur conditions."""
    return lens.aperture_for_depth_of_field(f, c, near, far).f_number


_H_OFF = (
    "H is off by f: with section 2's exact limits the hyperfocal distance is H = f^2 / (N c) + f, so "
    "N = f^2 / (c (H - f)); the + f belongs to the thin lens's exact H"
)
_APEX = (
    "the cone's apex is the image point z_i, so similar triangles give c / A = |z_s - z_i| / z_i: "
    "divide by z_i (the end point's image distance), not by the sensor distance z_s"
)


def _by_sensor(s, end):
    """N from the blur at ``end`` with similar triangles' apex at the sensor z_s instead of the image point."""
    z_s, z_i = s.f * s.focus / (s.focus - s.f), s.f * end / (end - s.f)
    return s.f / s.c * abs(z_s - z_i) / z_s


def _n_focused_at(s, focus, end):
    """N that blurs ``end`` to exactly c with the lens focused at ``focus``: f^2 |end - focus| / (c end (focus - f))."""
    return s.f**2 * abs(end - focus) / (s.c * end * (focus - s.f))


def _focused_at(s, focus):
    """True when the answer is N focused at ``focus`` with the blur c at the near or the far end."""
    return np.isclose(s.g, _n_focused_at(s, focus, s.n)) or np.isclose(
        s.g, _n_focused_at(s, focus, s.r)
    )


def _one_end(s):
    """'near' or 'far' when the answer is N focused at that end (sharp there, c at the other), else None."""
    for focus, other, where in ((s.n, s.r, "near"), (s.r, s.n, "far")):
        if np.isclose(s.g, _n_focused_at(s, focus, other)):
            return where
    return None


_F_NUMBER_MISTAKES = (
    Mistake(
        "geometric mean focus",
        lambda s: _focused_at(s, s.geometric),
        (
            "you focused at the geometric mean sqrt(near far); equal blur at both ends needs "
            "(s - near) / near = (far - s) / far, whose solution is the harmonic mean 2 near far / (near + far)"
        ),
    ),
    Mistake(
        "1/N",
        lambda s: np.isclose(s.g, 1 / s.expected),
        ("you returned 1/N; N = f / A is large for a small aperture (f/11 is N = 11)"),
    ),
    Mistake(
        "a focus distance",
        lambda s: np.isclose(s.g, s.focus) or np.isclose(s.g, (s.n + s.r) / 2),
        (
            "that is a focus distance; the function returns the f-number N (the focus is only a step on the way)"
        ),
    ),
    Mistake(
        "midpoint focus",
        lambda s: _focused_at(s, s.mid),
        (
            "you focused at the midpoint (near + far) / 2; the blur grows as |z - s| / z, faster in front of the "
            "focus than behind it, so equal blur at both ends needs s = 2 near far / (near + far), the harmonic mean"
        ),
    ),
    Mistake(
        "f dropped from s - f",
        lambda s: np.isclose(s.g, s.f**2 * (s.r - s.n) / (2 * s.c * s.n * s.r)),
        (
            "you dropped f from s - f: the sensor sits at f s / (s - f), and c(z) = (f/N) (f/(s - f)) |z - s| / z; "
            "the check wants the exact thin-lens N (neglecting f against s is the usual approximation, and the "
            "same as the textbook's H = f^2 / (N c) with near = H s / (H + s), far = H s / (H - s))"
        ),
    ),
    Mistake(
        "H off by f",
        lambda s: np.isclose(s.g, s.f**2 / (s.c * s.H_plain)),
        lambda s: (
            # for the harmonic-mean focus, the z_s slip at the far end gives exactly this N too: name both
            "two routes give exactly this N, each with one slip. Through H: "
            + _H_OFF
            + ". Or through the "
            "blur at the far end: " + _APEX
            if np.isclose(s.g, _by_sensor(s, s.r))
            else _H_OFF
        ),
    ),
    Mistake(
        "divided by the sensor distance",
        lambda s: any(np.isclose(s.g, _by_sensor(s, end)) for end in (s.n, s.r)),
        _APEX,
    ),
    Mistake(
        "divided by s, not z",
        lambda s: any(
            np.isclose(s.g, s.f**2 * abs(end - s.focus) / (s.c * s.focus * (s.focus - s.f)))
            for end in (s.n, s.r)
        ),
        (
            "c(z) = (f/N) (f/(s - f)) |z - s| / z divides by z, the depth of the end whose blur you set to c (near or "
            "far), not by the focus distance s: the cone's apex sits at that depth's image point"
        ),
    ),
    Mistake(
        "focused at one end",
        lambda s: _one_end(s) is not None,
        lambda s: (
            f"you focused at the {_one_end(s)} end"
            + (
                " (with far = 2 near that is also focusing at the hyperfocal distance H = 2 near)"
                if _one_end(s) == "far" and np.isclose(s.r, 2 * s.n)
                else ""
            )
            + ": that end is then perfectly sharp and the whole blur budget goes to the other end, which needs a "
            "larger N than necessary. Focus where both ends blur equally, (s - near) / near = (far - s) / far, "
            "s = 2 near far / (near + far), then N from c(near) = c"
        ),
    ),
    Mistake(
        "c / 2 and f dropped",
        lambda s: np.isclose(s.g, s.f**2 * (s.r - s.n) / (s.c * s.n * s.r)),
        lambda s: (
            "two slips: c / 2 (c is the blur circle's diameter, not its radius) and f dropped from s - f "
            "(c(z) = (f/N) (f/(s - f)) |z - s| / z, exactly)"
            + (
                " (with far = 2 near this is also f^2 / (c H) with H = 2 near: focusing at an approximate "
                "hyperfocal distance, which makes everything beyond near sharp, more than asked)"
                if np.isclose(s.r, 2 * s.n)
                else ""
            )
        ),
    ),
    Mistake(
        "focused at the hyperfocal distance",
        lambda s: any(
            np.isclose(s.g, s.f**2 / (s.c * H)) or np.isclose(s.g, s.f**2 / (s.c * (H - s.f)))
            for H in (2 * s.n, 2 * s.n - s.f)  # "focus at H, so near = H / 2"
        ),
        (
            "you focused at the hyperfocal distance (near = H / 2, so H = 2 near): that makes everything from "
            "near to infinity sharp, far more than asked, at a needlessly large N. Focus where both ends blur "
            "equally, s = 2 near far / (near + far), and find N from c(near) = c"
        ),
    ),
    Mistake(
        "2 N c s^2 / f^2",
        lambda s: any(
            np.isclose(s.g, s.f**2 * (s.r - s.n) / (2 * s.c * focus**2))
            for focus in (s.focus, (s.n + s.r) / 2)
        ),
        lambda s: (
            "that is the textbook approximation depth of field = far - near = 2 N c s^2 / f^2, which holds "
            f"only for s far below the hyperfocal distance and s >> f ({abs(s.g / s.expected - 1):.0%} off here); "
            "the check wants the exact N: focus at s = 2 near far / (near + far), then solve c(near) = c"
        ),
    ),
    Mistake(
        "the two ends mixed",
        lambda s: any(
            np.isclose(s.g, s.f**2 * abs(end - s.focus) / (s.c * other * (s.focus - s.f)))
            for end, other in ((s.n, s.r), (s.r, s.n))
        ),
        (
            "you mixed the two ends: each end's blur is c(z) = (f/N) (f/(s - f)) |z - s| / z with that end's own "
            "z in both places, (s - near) / near at the near end, (far - s) / far at the far end"
        ),
    ),
    Mistake(
        "harmonic mean without its 2",
        lambda s: any(
            np.isclose(abs(s.g), s.f**2 * abs(end - half) / (s.c * end * abs(half - s.f)))
            for half in (s.n * s.r / (s.n + s.r),)
            for end in (s.n, s.r)
        ),
        (
            "your focus distance misses the harmonic mean's factor 2: near far / (near + far) lies in front of "
            "near; equal blur at both ends needs s = 2 near far / (near + far)"
        ),
    ),
    Mistake(
        "c / 2",
        lambda s: np.isclose(s.g, 2 * s.expected),
        ("c is the blur circle's diameter, not its radius: you used c / 2"),
    ),
    Mistake(
        "2 c",
        lambda s: np.isclose(s.g, s.expected / 2),
        ("you doubled c; c is the blur circle's diameter already"),
    ),
    Mistake(
        "1000 times off",
        lambda s: np.isclose(s.g, s.expected * 1e3) or np.isclose(s.g, s.expected * 1e-3),
        (
            "N is 1000 times off: mixed units (c in millimetres, f in metres?); keep every length in metres"
        ),
    ),
    Mistake(
        "sign of f",
        lambda s: np.isclose(s.g, s.f**2 * (s.focus - s.n) / (s.c * s.n * (s.focus + s.f))),
        (
            "the sign of f: the sensor sits at f s / (s - f), so the cone's factor is f / (s - f), not f / (s + f)"
        ),
    ),
    Mistake(
        "f not squared",
        lambda s: np.isclose(s.g, s.expected / s.f),
        ("f enters squared: the aperture A = f / N and the cone's f / (s - f) each bring one f"),
    ),
    Mistake(
        "|z - s| sign",
        lambda s: np.isclose(s.g, -s.expected),
        (
            "|z - s| with the wrong sign: the near end is in front of the focus, |near - s| = s - near; the far "
            "end behind it, |far - s| = far - s"
        ),
    ),
    Mistake(
        "aperture diameter",
        lambda s: np.isclose(s.g, s.f / s.expected),
        ("that is the aperture's diameter A = f / N (metres); return the f-number N itself"),
    ),
    Mistake(
        "negative",
        lambda s: s.g < 0,
        (
            "N came out negative: an |z - s| taken with the wrong sign, or s - f < 0 because f and the "
            "distances are in different units (f in millimetres, s in metres?); keep every length in metres"
        ),
    ),
)
"""The f-number's slips after rounding, in the order they are tested: the focus taken elsewhere (``s.geometric``,
``s.mid``), the thin lens or the blur cone done wrong, a unit or a factor; each a test of the answer ``s.g``
against the right ``s.expected``, with ``s.focus`` the right focus distance."""


def _f_number_diagnosis(args, got, expected) -> str:
    f, c, n, r = args
    if (
        isinstance(got, (tuple, list, np.ndarray))
        and np.size(got) == 2
        and np.isclose(np.ravel(got), expected).any()
    ):
        return "return N alone, one number: the focus distance s is only a step on the way"
    if not _is_number(got):
        return not_one_number(got, "the f-number N")
    g = float(got)
    focus = 2 * n * r / (n + r)
    stop = [N for N in _MARKED_STOPS if np.isclose(g, N, rtol=1e-9)]
    # a whole number (int, floor, ceil, round), a marked full stop, or an exact half or third stop 2^(k/4), 2^(k/6)
    fraction_stop = g > 0 and any(
        np.isclose(k * np.log2(g), round(k * np.log2(g)), rtol=0, atol=1e-9) for k in (4, 6)
    )
    near_it = g > 0 and abs(np.log2(g / expected)) < 1  # within a stop of the answer
    if (
        (
            stop
            or fraction_stop
            or np.isclose(g, np.floor(expected))
            or np.isclose(g, np.ceil(expected))
            or np.isclose(g, np.round(expected))
            or any(np.isclose(g, round(expected, k), rtol=0, atol=1e-12) for k in (1, 2, 3, 4))
        )
        and near_it
        and not np.isclose(g, expected)
    ):
        return (
            f"you rounded N (to {g:g}); return the exact f-number, {expected:.6g} here (round only when you print "
            f"it): picking the next marked stop on the lens is your step afterwards, not the function's"
        )
    mid = (n + r) / 2
    context = SimpleNamespace(
        g=g,
        f=f,
        c=c,
        n=n,
        r=r,
        focus=focus,
        expected=expected,
        geometric=np.sqrt(n * r),
        mid=mid,
        H_plain=(n * (focus - 2 * f) + focus * f)
        / (focus - n),  # near = s (H - f) / (H + s - 2 f) solved for H
    )
    return first_mistake(_F_NUMBER_MISTAKES, context) or (
        "first the focus s with c(near) = c(far), i.e. (s - near) / near = (far - s) / far; then N from "
        "c(near) = c, with c(z) = (f/N) (f/(s - f)) |z - s| / z"
    )


def _f_number_note(run) -> str:
    """Exercise 2's diffraction caveat, computed with the student's own function once it passes."""
    N = float(run(0.028, 0.02e-3, 0.8, 1.6))
    airy = 2.44 * 550e-9 * N  # the Airy disc's diameter in green light
    best = np.sqrt(N * 0.02e-3 / (2.44 * 550e-9))  # where the defocus N c / N' meets the Airy disc
    return (
        f"Diffraction: 28 mm for 0.8 m to 1.6 m at c = 20 µm needs f/{N:.1f}, where the Airy disc 2.44 λN is "
        f"already {airy * 1e6:.1f} µm, {airy / 20e-6:.0%} of c. Section 2's blur budget adds the two: at best "
        f"(f/{best:.1f}) they make {np.sqrt(2) * 2.44 * 550e-9 * best * 1e6:.0f} µm: by that rule of thumb (with "
        f"the Airy disc measured to its first dark ring, a conservative size) no f-number holds this range to 20 µm."
    )


_MARKED_STOPS = (1.0, 1.4, 2.0, 2.8, 4.0, 5.6, 8.0, 11.0, 16.0, 22.0, 32.0, 45.0, 64.0)


def f_number_for_depth(f, c, near, far):
    """The f-number that keeps blur <= c from near to far (metres), focused where both ends blur equally.

    Parameters
    ----------
    f : float
        The focal length, m.
    c : float
        The largest blur circle allowed (the circle of confusion), m.
    near, far : float
        The nearest and farthest distances to keep sharp, m (f < near < far).

    Returns
    -------
    float
        N = f^2 (s - near) / (c near (s - f)), focused at the harmonic mean s = 2 near far / (near + far).
    """
    # equal blur at both ends, (s - near) / near = (far - s) / far: the harmonic mean
    s = 2 * near * far / (near + far)
    # c(near) = (f/N) (f/(s - f)) (s - near) / near = c, solved for N
    return f**2 * (s - near) / (c * near * (s - f))


register_exercise(
    Exercise(
        name="f_number_for_depth",
        lesson="02",
        reference=_f_number_reference,
        cases=_f_number_cases,
        compare=same_number(rtol=1e-9),
        diagnose=_f_number_diagnosis,
        success_note=_f_number_note,
        wrong_variants=(
            (
                lambda f, c, n, r: f**2 * ((n + r) / 2 - n) / (c * n * ((n + r) / 2 - f)),
                "harmonic mean",
            ),
            (
                lambda f, c, n, r: f**2 * (r - (n + r) / 2) / (c * r * ((n + r) / 2 - f)),
                "harmonic mean",
            ),
            (lambda f, c, n, r: f**2 * (r - n) / (2 * c * n * r), "dropped f from s - f"),
            (
                lambda f, c, n, r: (
                    f**2
                    * (2 * n * r / (n + r) - n)
                    / (c * (2 * n * r / (n + r)) * (2 * n * r / (n + r) - f))
                ),
                "not by the focus distance s",
            ),
            (
                lambda f, c, n, r: (
                    f**2 * (2 * n * r / (n + r) - n) / (c * r * (2 * n * r / (n + r) - f))
                ),
                "you mixed the two ends",
            ),
            (
                lambda f, c, n, r: (
                    f**2 * (r - 2 * n * r / (n + r)) / (c * n * (2 * n * r / (n + r) - f))
                ),
                "you mixed the two ends",
            ),
            (
                lambda f, c, n, r: f**2 * (n * r / (n + r) - n) / (c * n * (n * r / (n + r) - f)),
                "misses the harmonic mean's factor 2",
            ),
            (lambda f, c, n, r: round(_f_number_reference(f, c, n, r), 1), "you rounded N"),
            (lambda f, c, n, r: round(_f_number_reference(f, c, n, r), 2), "you rounded N"),
            (lambda f, c, n, r: 2 * _f_number_reference(f, c, n, r), "not its radius"),
            (lambda f, c, n, r: _f_number_reference(f, c, n, r) / 2, "you doubled c"),
            (lambda f, c, n, r: 1e3 * _f_number_reference(f, c, n, r), "mixed units"),
            (lambda f, c, n, r: 1 / _f_number_reference(f, c, n, r), "1/N"),
            (lambda f, c, n, r: 2 * n * r / (n + r), "focus distance"),
            (lambda f, c, n, r: _f_number_reference(f, c, n, r) / f, "f enters squared"),
            (
                lambda f, c, n, r: (
                    f**2 * (2 * n * r / (n + r) - n) / (c * n * (2 * n * r / (n + r) + f))
                ),
                "the sign of f",
            ),
            (lambda f, c, n, r: np.array([_f_number_reference(f, c, n, r)]), "return one number"),
            (
                lambda f, c, n, r: min(
                    N for N in _MARKED_STOPS if N >= _f_number_reference(f, c, n, r)
                ),
                "you rounded N",
            ),
            (lambda f, c, n, r: float(np.ceil(_f_number_reference(f, c, n, r))), "you rounded N"),
            (lambda f, c, n, r: int(_f_number_reference(f, c, n, r)), "you rounded N"),
            (
                lambda f, c, n, r: 2 ** (np.ceil(4 * np.log2(_f_number_reference(f, c, n, r))) / 4),
                "you rounded N",
            ),
            (
                lambda f, c, n, r: (
                    f**2
                    / (
                        c
                        * (
                            (n * (2 * n * r / (n + r) - 2 * f) + 2 * n * r / (n + r) * f)
                            / (2 * n * r / (n + r) - n)
                        )
                    )
                ),
                "H is off by f",
            ),
            (
                lambda f, c, n, r: (
                    f
                    / c
                    * abs(f * 2 * n * r / (n + r) / (2 * n * r / (n + r) - f) - f * n / (n - f))
                    / (f * 2 * n * r / (n + r) / (2 * n * r / (n + r) - f))
                ),
                "not by the sensor distance z_s",
            ),
            (
                lambda f, c, n, r: f**2 * (np.sqrt(n * r) - n) / (c * n * (np.sqrt(n * r) - f)),
                "geometric mean",
            ),
            (
                lambda f, c, n, r: (
                    f**2 * (2 * n * r / (n + r) - r) / (c * r * (2 * n * r / (n + r) - f))
                ),
                "the wrong sign",
            ),
            (lambda f, c, n, r: f / _f_number_reference(f, c, n, r), "the aperture's diameter"),
            (
                lambda f, c, n, r: (2 * n * r / (n + r), _f_number_reference(f, c, n, r)),
                "return N alone",
            ),
            (
                lambda f, c, n, r: f**2 * (r - n) / (c * r * (n - f)),
                "you focused at the near end",
            ),
            (lambda f, c, n, r: f**2 / (c * (2 * n - f)), "hyperfocal distance"),
            (
                lambda f, c, n, r: f**2 * (r - n) / (2 * c * (2 * n * r / (n + r)) ** 2),
                "textbook approximation",
            ),
            (lambda f, c, n, r: f**2 * (r - n) / (c * n * r), "two slips: c / 2"),
            (
                lambda f, c, n, r: (
                    (1e3 * f) ** 2
                    * (2 * n * r / (n + r) - n)
                    / (c * n * (2 * n * r / (n + r) - 1e3 * f))
                ),
                "N came out negative",
            ),
        ),
        teaching=f_number_for_depth,
    )
)
