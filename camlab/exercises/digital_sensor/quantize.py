"""Lesson 03's second exercise: quantise an image to digital numbers, DN = round(I (2**bits - 1)), clipped."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ... import sensor
from .._answers import shape_problem
from .._core import Exercise, Mistake, first_mistake, register_exercise


def _quantize_cases():
    rng = np.random.default_rng(3)
    # grey images (H, W), as the prompt says: a solution that starts with H, W = image.shape must run
    return [
        (np.linspace(0, 1, 12).reshape(3, 4), 2),
        (rng.uniform(0, 1, (4, 5)), 8),
        (np.array([[0.0, 0.25, 0.5, 0.75], [1.0, 1.3, -0.2, 0.1]]), 3),
        (rng.uniform(0, 1, (4, 5)), 12),
    ]


def _unpack_hint(exc: Exception, args: tuple) -> str:
    """The likely cause when unpacking ``image.shape`` fails: the test images are grey, (H, W)."""
    if isinstance(exc, ValueError) and "unpack" in str(exc):
        shape = np.shape(args[0])
        return (
            f"the test image has shape {shape}, a grey image (H, W) with no colour axis: unpack it as "
            f"H, W = image.shape, or, simpler, work on the whole array at once (np.round(image * (2**bits - 1)), "
            f"np.clip), which suits any shape"
        )
    return ""


def not_an_array(got) -> str | None:
    """The hint for an answer that is no numpy array (a list from .tolist() or a comprehension), else None.

    Parameters
    ----------
    got : object
        The student's answer.

    Returns
    -------
    str or None
        The hint naming the answer's type and the fix, or None for a numpy array.
    """
    if isinstance(got, np.ndarray):
        return None
    return (
        f"you returned a {type(got).__name__}; return a numpy array (np.array(...) or numpy operations "
        f"on the whole image, without .tolist())"
    )


def _same_after_cast(got: np.ndarray, candidate: np.ndarray) -> bool:
    """``got`` equals ``candidate`` cast to got's dtype (so a wrapped-around uint8 still matches its cause)."""
    with np.errstate(invalid="ignore", over="ignore"):
        return np.array_equal(got, np.asarray(candidate).astype(got.dtype))


def _wrong_top(s):
    """The top code the answer scales to when it is half the levels or one too few, else None."""
    for top in sorted({2 ** (s.bits - 1) - 1, 2 ** (s.bits - 1), 2**s.bits - 2} - {s.levels}):
        if top > 0 and any(
            _same_after_cast(s.g, c)
            for c in (
                np.clip(np.rint(s.img * top), 0, top),
                np.clip(np.rint(s.clipped * top), 0, s.levels),
            )
        ):
            return top
    return None


def _top_code_hint(s) -> str:
    top, bits = _wrong_top(s), s.bits
    causes = [
        cause
        for value, cause in (
            (2 ** (bits - 1), "2**(bits - 1), half of the levels (the sign bit's worth)"),
            (2 ** (bits - 1) - 1, "2**(bits - 1) - 1, half of the levels"),
            (
                2**bits - 2,
                "2**bits - 2, one level too few (an "
                "off-by-one: 2**bits - 1 is already the top code)",
            ),
        )
        if value == top
    ]
    return (
        f"your top code is {top}, from {' or from '.join(causes)}: {bits} bits give 2**bits = {2**bits} "
        f"levels, 0 to 2**bits - 1 = {s.levels}; scale by 2**bits - 1"
    )


def _context(img, bits, g):
    """What the rows of :data:`_MISTAKES` read: the input, the answer ``g`` and the numbers slips start from."""
    levels = 2**bits - 1
    clipped = np.clip(img, 0, 1)
    with np.errstate(invalid="ignore", over="ignore"):
        wrapped = [np.rint(img * levels).astype(t).astype(g.dtype) for t in (g.dtype, np.int64)]
        top_only = np.minimum(np.rint(img * levels), levels)
    return SimpleNamespace(
        img=img,
        bits=bits,
        g=g,
        levels=levels,
        clipped=clipped,
        right=_right_quantize_numbers(img, bits),
        wrapped=wrapped,
        top_only=top_only,
        adc=np.floor(clipped * 2**bits),  # many real converters: 2**bits bins of width 1 / 2**bits
    )


_MISTAKES = (
    Mistake(
        "fractions of full scale",
        lambda s: (
            np.issubdtype(s.g.dtype, np.floating) and _same_after_cast(s.g, s.right / s.levels)
        ),
        lambda s: (
            f"you returned fractions of full scale, DN / (2**bits - 1) (the dequantised values); return the "
            f"digital numbers themselves, whole numbers from 0 to 2**bits - 1 = {s.levels}"
        ),
    ),
    Mistake(
        "encoded before quantising",
        lambda s: (
            not _same_after_cast(s.g, s.right)
            and any(
                _same_after_cast(s.g, np.clip(np.rint(v * s.levels), 0, s.levels))
                for v in (sensor.gamma_encode(s.clipped), s.clipped ** (1 / 2.2))
            )
        ),
        (
            "you gamma-encoded (sRGB or a 1/2.2 power) before quantising: the converter quantises the linear "
            "fraction of full scale the sensor measured, I itself; sRGB encoding comes later in the pipeline "
            "(section 5), so DN = round(I * (2**bits - 1)), clipped"
        ),
    ),
    Mistake(
        "cast before clipping",
        lambda s: (
            any(_same_after_cast(s.g, np.clip(w, 0, s.levels)) for w in s.wrapped)
            and (not _same_after_cast(s.g, s.right))
        ),
        (
            "you cast to an unsigned type before clipping: a value below 0 (-0.2 x 7 rounds to -1) wraps around "
            "in uint8 to 255, so the clip sees a bright pixel; clip first (np.clip(..., 0, 2**bits - 1)), "
            "then cast"
        ),
    ),
    Mistake(
        "clipped only the top",
        lambda s: (
            np.any(s.img < 0)
            and s.g.dtype.kind == "u"
            and _same_after_cast(s.g, s.top_only)
            and (not _same_after_cast(s.g, s.right))
        ),
        (
            "you clipped only the top: a value below 0 (-0.2 x 7 rounds to -1) wraps around in an unsigned type, "
            "to 255 in uint8, a bright pixel; clip both ends, np.clip(..., 0, 2**bits - 1), before the cast"
        ),
    ),
    Mistake(
        "clipped only the bottom",
        lambda s: (
            np.any(s.img > 1)
            and _same_after_cast(s.g, np.maximum(np.rint(s.img * s.levels), 0))
            and (not _same_after_cast(s.g, s.right))
        ),
        lambda s: (
            f"you clipped only the bottom: an overexposed value above 1 scales past the top code "
            f"2**bits - 1 = {s.levels} (and wraps in a small unsigned type); the converter saturates there, so clip "
            f"the top too, np.clip(..., 0, 2**bits - 1)"
        ),
    ),
    Mistake(
        "I * 2**bits - 1",
        lambda s: any(
            _same_after_cast(s.g, c)
            for c in (
                np.clip(np.rint(s.img * 2**s.bits - 1), 0, s.levels),
                np.rint(s.img * 2**s.bits - 1),
                np.clip(np.rint(s.clipped * 2**s.bits - 1), 0, s.levels),
            )
        ),
        (
            "I * 2**bits - 1 is (I * 2**bits) - 1: Python multiplies before it subtracts, so white lands on "
            "2**bits - 1 but every other code is off; write I * (2**bits - 1), with the brackets"
        ),
    ),
    Mistake(
        "clipped to [0, 1] after scaling",
        lambda s: (
            any(
                _same_after_cast(s.g, np.clip(f(s.img * s.levels), 0, 1))
                for f in (np.rint, np.floor)
            )
            or _same_after_cast(s.g, np.rint(np.clip(s.img * s.levels, 0, 1)))
        ),
        lambda s: (
            f"you clipped to [0, 1] after scaling: by then the values are digital numbers from 0 to "
            f"{s.levels}; clip the fraction I to [0, 1] before scaling, or the digital numbers to "
            f"[0, 2**bits - 1] after"
        ),
    ),
    Mistake(
        "bits levels",
        lambda s: (
            s.bits - 1 != s.levels
            and any(
                _same_after_cast(s.g, np.clip(np.rint(x * top), 0, top))
                for x in (s.img, s.clipped)
                for top in (s.bits - 1,)
            )
        ),
        lambda s: (
            f"your top code is {s.bits - 1}: you took bits = {s.bits} as the number of levels, 0 to bits - 1"
            f"{' (or scaled by 2**(bits - 1) - 1, half of the levels, the same number at 2 bits)' if s.bits == 2 else ''}; "
            f"{s.bits} bits give 2**bits = {2**s.bits} levels, 0 to 2**bits - 1 = {s.levels}: scale by 2**bits - 1"
        ),
    ),
    Mistake(
        "one bit too many",
        lambda s: any(
            _same_after_cast(s.g, np.clip(np.rint(x * (2 ** (s.bits + 1) - 1)), 0, top))
            for x in (s.img, s.clipped)
            for top in (s.levels, 2 ** (s.bits + 1) - 1)
        ),
        lambda s: (
            f"you scaled by 2**(bits + 1) - 1 = {2 ** (s.bits + 1) - 1}, one bit too many: {s.bits} bits give "
            f"codes 0 to 2**bits - 1 = {s.levels}; scale by 2**bits - 1"
        ),
    ),
    Mistake(
        "^ for a power",
        lambda s: any(
            x != s.levels and _same_after_cast(s.g, np.clip(np.rint(s.img * x), 0, max(x, 0)))
            for x in (2 ^ (s.bits - 1), (2 ^ s.bits) - 1)
        ),
        lambda s: (
            f"you wrote 2^bits: in Python ^ is bitwise XOR, not a power, and binds after the minus, so "
            f"2^bits - 1 is 2 XOR (bits - 1) = {2 ^ (s.bits - 1)} at {s.bits} bits, not {s.levels}; powers are "
            f"**: 2**bits - 1"
        ),
    ),
    Mistake(
        "clipped one code low",
        lambda s: any(
            _same_after_cast(s.g, np.clip(np.rint(x * s.levels), 0, s.levels - 1))
            for x in (s.img, s.clipped)
        ),
        lambda s: (
            f"you clipped to 2**bits - 2 = {s.levels - 1}, so white loses its code (the scaling is right): the "
            f"top code is 2**bits - 1 = {s.levels}; clip to [0, 2**bits - 1]"
        ),
    ),
    Mistake("top code too low", _wrong_top, _top_code_hint),
    Mistake(
        "codes from 1",
        lambda s: any(
            _same_after_cast(s.g, c)
            for c in (
                np.clip(np.rint(s.img * s.levels), 1, s.levels + 1),
                np.clip(np.rint(s.img * s.levels) + 1, 1, s.levels + 1),
            )
        ),
        lambda s: (
            f"your codes run from 1 to 2**bits = {s.levels + 1}: digital numbers count from 0, like Python's "
            f"indices, so black is 0 and white is 2**bits - 1 = {s.levels}; clip to [0, 2**bits - 1]"
        ),
    ),
    Mistake(
        "floor",
        lambda s: _same_after_cast(s.g, np.floor(s.clipped * s.levels)),
        ("you truncated (floor); round to the nearest level so the error is at most half a step"),
    ),
    Mistake(
        "rounded up",
        lambda s: (
            _same_after_cast(s.g, np.ceil(s.clipped * s.levels))
            or _same_after_cast(s.g, np.clip(np.rint(s.img * s.levels + 0.5), 0, s.levels))
        ),
        (
            "you rounded up: np.ceil, or np.round(x + 0.5), which adds a half step that np.round does not need "
            "(the + 0.5 belongs to np.floor(x + 0.5), the other way to round to nearest); round once, "
            "np.round(x) or np.floor(x + 0.5), so the error is at most half a step"
        ),
    ),
    Mistake(
        "an ADC's floor",
        lambda s: (
            _same_after_cast(s.g, s.adc) or _same_after_cast(s.g, np.minimum(s.adc, s.levels))
        ),
        (
            "you used an ADC's floor(I * 2**bits); this lesson's DN = round(I * (2**bits - 1)) maps 0 and 1 "
            "exactly to 0 and 2**bits - 1 with at most half a step of error: scale by 2**bits - 1 and round"
        ),
    ),
    Mistake(
        "scaled by 2**bits",
        lambda s: any(
            _same_after_cast(s.g, np.clip(np.rint(s.img * 2**s.bits), 0, top))
            for top in (s.levels, 2**s.bits)
        ),
        lambda s: (
            f"you scaled by 2**bits = {2**s.bits}; white (I = 1) must land on the top code 2**bits - 1 = {s.levels}: "
            f"scale by 2**bits - 1"
        ),
    ),
    Mistake(
        "not clipped",
        lambda s: _same_after_cast(s.g, np.rint(s.img * s.levels)),
        (
            "clip to [0, 2**bits - 1]: values outside [0, 1] saturate (the scaling by 2**bits - 1 is right)"
        ),
    ),
    Mistake(
        "beyond the top code",
        lambda s: s.g.max() > s.levels,
        lambda s: (
            f"a {s.bits}-bit number runs from 0 to 2**bits - 1 = {s.levels}: scale by 2**bits - 1 and clip"
        ),
    ),
)
"""The quantisation slips, in the order they are tested, each a test of the answer ``s.g`` (compared after a
cast to its dtype, so a wrapped-around uint8 still shows its cause)."""


def _quantize_diagnosis(args, got, expected) -> str:
    problem = not_an_array(got) or shape_problem(got, expected)
    if problem:
        return problem
    img, bits = args
    g = np.asarray(got)
    levels = 2**bits - 1
    wanted = np.asarray(expected).dtype
    if np.array_equal(g, expected):  # right numbers, wrong type
        if not np.issubdtype(g.dtype, np.integer):
            return (
                f"the values are right but the dtype is {g.dtype}: digital numbers are integers; "
                f"end with .astype(np.uint8) for <= 8 bits, np.uint16 above"
            )
        return (
            f"the values are right but the dtype is {g.dtype}; the prompt asks for {wanted} at {bits} bits "
            f"(np.uint8 up to 8 bits, np.uint16 above): end with .astype(np.{wanted})"
        )
    if bits > 8 and g.dtype == np.uint8:
        return (
            f"{bits}-bit numbers reach {levels}, but uint8 stops at 255 and wraps around: "
            f"use np.uint16 above 8 bits"
        )
    return first_mistake(_MISTAKES, _context(img, bits, g)) or (
        "DN = round(I * (2**bits - 1)), clipped to [0, 2**bits - 1]"
    )


def _right_quantize_numbers(img, bits):
    return np.clip(np.rint(img * (2**bits - 1)), 0, 2**bits - 1)


def quantize_image(image, bits):
    """Digital numbers DN = round(I (2**bits - 1)), clipped; uint8 up to 8 bits, uint16 above.

    Parameters
    ----------
    image : ndarray
        Intensities, 0 to 1 (values beyond saturate).
    bits : int
        The converter's bit depth (uint16 holds up to 16).

    Returns
    -------
    ndarray of uint8 (bits <= 8) or uint16
        The digital numbers, 0 .. 2**bits - 1, of ``image``'s shape.
    """
    levels = 2**bits - 1
    dn = np.clip(np.round(image * levels), 0, levels)  # round to nearest, then saturate
    return dn.astype(np.uint8 if bits <= 8 else np.uint16)


register_exercise(
    Exercise(
        name="quantize_image",
        lesson="03",
        reference=sensor.quantise,
        cases=_quantize_cases,
        # the prompt fixes the type: a numpy array of uint8 up to 8 bits, uint16 above
        compare=lambda got, exp: (
            isinstance(got, np.ndarray) and got.dtype == exp.dtype and np.array_equal(got, exp)
        ),
        diagnose=_quantize_diagnosis,
        exception_hint=_unpack_hint,
        wrong_variants=(
            (
                lambda img, bits: np.clip(np.rint(img * (bits - 1)), 0, bits - 1).astype(np.uint8),
                "as the number of levels",
            ),
            (
                lambda img, bits: np.clip(
                    np.rint(img * (2 ** (bits + 1) - 1)), 0, 2**bits - 1
                ).astype(np.uint8 if bits <= 8 else np.uint16),
                "one bit too many",
            ),
            (
                lambda img, bits: np.floor(np.clip(img, 0, 1) * (2**bits - 1)).astype(np.uint16),
                "round to the nearest",
            ),
            (
                lambda img, bits: np.clip(np.rint(img * 2**bits), 0, 2**bits).astype(np.uint16),
                "2**bits",
            ),
            (
                lambda img, bits: np.minimum(
                    np.floor(np.clip(img, 0, 1) * 2**bits), 2**bits - 1
                ).astype(np.uint16),
                "an ADC's floor",
            ),
            (
                lambda img, bits: np.floor(np.clip(img, 0, 1) * 2**bits).astype(np.uint16),
                "an ADC's floor",
            ),
            (lambda img, bits: np.rint(img * (2**bits - 1)).astype(np.int64), "dtype is int64"),
            (
                lambda img, bits: sensor.quantise(sensor.gamma_encode(np.clip(img, 0, 1)), bits),
                "sRGB encoding comes later",
            ),
            (
                lambda img, bits: np.clip(np.rint(img * (2**bits - 1)), 0, 2**bits - 1),
                "dtype is float64",
            ),
            (lambda img, bits: _right_quantize_numbers(img, bits).astype(np.uint8), "wraps around"),
            (
                lambda img, bits: _right_quantize_numbers(img, bits).astype(np.uint16),
                "the prompt asks for uint8",
            ),
            (
                lambda img, bits: _right_quantize_numbers(img, bits).astype(np.uint16).tolist(),
                "you returned a list",
            ),
            (
                lambda img, bits: np.clip(np.rint(img * 2**bits), 0, 2**bits - 1).astype(np.uint16),
                "you scaled by 2**bits",
            ),
            (
                lambda img, bits: np.clip(np.ceil(img * (2**bits - 1)), 0, 2**bits - 1).astype(
                    np.uint16
                ),
                "ceil",
            ),
            (
                lambda img, bits: np.clip(
                    np.round(img * (2**bits - 1) + 0.5), 0, 2**bits - 1
                ).astype(np.uint8 if bits <= 8 else np.uint16),
                "adds a half step",
            ),
            (
                lambda img, bits: np.clip(np.rint(img * (2**bits - 2)), 0, 2**bits - 2).astype(
                    np.uint8 if bits <= 8 else np.uint16
                ),
                "2**bits - 2, one level too few",
            ),
            (
                lambda img, bits: np.rint(img * (2**bits - 1)).astype(
                    np.uint8 if bits <= 8 else np.uint16
                ),
                "saturate",
            ),
            (
                lambda img, bits: _right_quantize_numbers(img, bits) / (2**bits - 1),
                "fractions of full scale",
            ),
            (
                lambda img, bits: np.clip(
                    np.rint(img * (2**bits - 1)).astype(np.uint8 if bits <= 8 else np.uint16),
                    0,
                    2**bits - 1,
                ),
                "cast to an unsigned type before clipping",
            ),
            (
                lambda img, bits: np.clip(np.rint(img * (2**bits - 1)), 0, 1).astype(
                    np.uint8 if bits <= 8 else np.uint16
                ),
                "after scaling: by then",
            ),
            (
                lambda img, bits: np.clip(
                    np.rint(img * (2 ** (bits - 1) - 1)), 0, 2 ** (bits - 1) - 1
                ).astype(np.uint8 if bits <= 8 else np.uint16),
                "top code is",
            ),
            (
                lambda img, bits: np.clip(
                    np.rint(img * 2 ** (bits - 1)), 0, 2 ** (bits - 1)
                ).astype(np.uint8 if bits <= 8 else np.uint16),
                "top code is",
            ),
            (
                lambda img, bits: np.clip(np.rint(img * 2**bits - 1), 0, 2**bits - 1).astype(
                    np.uint8 if bits <= 8 else np.uint16
                ),
                "multiplies before it subtracts",
            ),
            (
                lambda img, bits: np.clip(np.rint(img * (2**bits - 1)), 1, 2**bits).astype(
                    np.uint8 if bits <= 8 else np.uint16
                ),
                "count from 0",
            ),
            (
                lambda img, bits: np.clip(np.rint(img * (2 ^ bits - 1)), 0, 2 ^ bits - 1).astype(
                    np.uint8 if bits <= 8 else np.uint16
                ),
                "bitwise XOR",
            ),
            (
                lambda img, bits: np.clip(np.rint(img * (2**bits - 1)), 0, 2**bits - 2).astype(
                    np.uint8 if bits <= 8 else np.uint16
                ),
                "you clipped to 2**bits - 2",
            ),
            (
                lambda img, bits: np.minimum(np.rint(img * (2**bits - 1)), 2**bits - 1).astype(
                    np.uint8 if bits <= 8 else np.uint16
                ),
                "clipped only the top",
            ),
        ),
        teaching=quantize_image,
    )
)
