"""What went wrong with x and y in lesson 00's lift: the table :func:`xy_slip` reads, and its helpers.

A lifted point keeps x and y as they are. :data:`XY_MISTAKES` lists, in order, the slips that change
them (an array never filled, an int cast, a half-pixel shift, a flipped sign, a y-up flip, a unit
factor, x and y swapped) as :class:`~camlab.exercises._core.Mistake` rows; :func:`xy_slip` names the
first that the answer shows, else which coordinate is wrong (:func:`one_coordinate_slip`). The
phrases the other lift modules share (:data:`APPEND`, :data:`KEEP`, :data:`ONE_POINT`) and the
check's test inputs (:func:`cases`) live here too.
"""

from __future__ import annotations

import sys
from functools import cached_property

import numpy as np

from .._core import Mistake, first_mistake

KEEP = "append 1 to the point, keeping x and y as they are"
APPEND = "np.append(p, 1.0)"

ONE_POINT = (
    "p is one point, a 1-D array of shape (2,), not a batch of points (N, 2) like the worked "
    "example's `points`"
)


class _XY:
    """The answer's x and y beside the point ``p`` they should equal, and what the rows derive from them.

    ``swapped`` is set when ``xy`` is an answer's x and y swapped back, to name what else is wrong.
    """

    def __init__(self, xy: np.ndarray, p: np.ndarray, swapped: bool):
        self.xy, self.p, self.swapped = xy, p, swapped

    @cached_property
    def clipped(self) -> str:
        return clip_slip(self.xy, self.p)

    @cached_property
    def image_slip(self) -> str:
        return image_convention_slip(self.xy, self.p)

    @cached_property
    def factor(self) -> float | None:
        """k when x and y are the point times one factor k (its nonzero coordinates tell), else None."""
        nonzero = np.abs(self.p) > 0
        factor = self.xy[nonzero] / self.p[nonzero]
        if np.allclose(factor, factor[0]) and np.allclose(self.xy, factor[0] * self.p):
            return factor[0]
        return None

    @property
    def may_swap(self) -> bool:
        """Whether a swap of x and y can show: not when judging a swapped answer, nor for x = y."""
        return not self.swapped and not np.allclose(self.p, self.p[::-1])

    @cached_property
    def swapped_too(self) -> str:
        """What else is wrong once x and y are swapped back ('' when a coordinate's name is all it gives)."""
        also = xy_slip(self.xy[::-1], self.p, swapped=True)
        return also if also and not also.startswith(("x is", "y is")) else ""


def _rounded(s: _XY) -> bool:
    """x and y lost the fractions the point has: an int cast or a rounding to whole pixels."""
    fractional = not np.array_equal(s.p, np.trunc(s.p))
    whole = (np.trunc(s.p), np.round(s.p), np.floor(s.p + 0.5), np.floor(s.p), np.ceil(s.p))
    return fractional and any(np.allclose(s.xy, k) for k in whole)


def _rounding(s: _XY) -> str:
    """Which rounding took the fractions off: np.ceil and np.floor named, the others together."""
    for way, name in ((np.ceil, "np.ceil rounds up"), (np.floor, "np.floor rounds down")):
        if np.allclose(s.xy, way(s.p)) and not np.allclose(s.xy, np.round(s.p)):
            return f"{name} ({s.p[0]:g} became {way(s.p[0]):g})"
    return "you cast to int or rounded to whole pixels (int, np.round, np.floor(p + 0.5))"


def _decimals(s: _XY) -> int | None:
    """The k in 1..6 with x and y = np.round(p, k) != p, if there is one."""
    if np.allclose(s.xy, s.p):
        return None
    return next((k for k in range(1, 7) if np.allclose(s.xy, np.round(s.p, k))), None)


def _float16_hint(s: _XY) -> str:
    short = np.float16
    return (
        f"x and y went through {np.dtype(short).name} (.astype(np.{np.dtype(short).name})), which keeps about "
        f"{np.finfo(short).precision} significant digits: ({s.p[0]:g}, {s.p[1]:g}) came back as "
        f"({s.xy[0]:.6g}, {s.xy[1]:.6g}); keep numpy's float64"
    )


_SHIFTS = (
    (
        0.5,
        "pixel centres sit at whole numbers in this course (section 3), so a point needs no "
        "half-pixel shift",
    ),
    (1.0, "numpy and this course count pixels from 0, not 1 (a 1-based index?)"),
)


def _conversion(k: float) -> str:
    way = "degrees to radians (np.radians)" if k < 1 else "radians to degrees (np.degrees)"
    return (
        f"x and y are {k:g} times the point's: the factor that converts {way}; a point's coordinates "
        f"are pixels, not angles, and lifting converts nothing"
    )


def _scaled(s: _XY, test) -> bool:
    return s.factor is not None and bool(test(s.factor))


# Checked in order by :func:`xy_slip` on an ``_XY``; each row's test says whether x and y show the slip.
XY_MISTAKES = (
    Mistake("clipped to the image", lambda s: s.clipped, lambda s: s.clipped),
    Mistake(
        "never filled (zeros)",
        lambda s: np.allclose(s.xy, 0.0) and np.all(s.p != 0),
        (
            "x and y are 0: the array was created (np.zeros, np.empty) but the point was never put in it; "
            f"build it from p: {APPEND}"
        ),
    ),
    Mistake(
        "never filled (ones)",
        lambda s: np.allclose(s.xy, 1.0),
        (
            "x and y are 1: an array of ones (np.ones(3)) that the point was never put in; "
            f"build it from p: {APPEND}"
        ),
    ),
    Mistake(
        "rounded to whole pixels",
        _rounded,
        lambda s: (
            f"the coordinates lost their fractions: {_rounding(s)}, but image points are real numbers (sub-pixel positions, such as this input's "
            f"({s.p[0]:g}, {s.p[1]:g})); keep floats"
        ),
    ),
    Mistake(
        "rounded to decimals",
        lambda s: _decimals(s) is not None,
        lambda s: (
            f"you rounded the result to {_decimals(s)} decimal{'s' * (_decimals(s) > 1)} (np.round(..., {_decimals(s)})): "
            f"({float(s.p[0])!r}, {float(s.p[1])!r}) came back as ({s.xy[0]:g}, {s.xy[1]:g}); lifting keeps x and y "
            "as they are: round only when you print"
        ),
    ),
    Mistake(
        "through float16",
        lambda s: np.array_equal(s.xy, s.p.astype(np.float16).astype(float)),
        _float16_hint,
    ),
    *(
        Mistake(
            f"off by {sign * shift:+g}",
            lambda s, d=sign * shift: np.allclose(s.xy, s.p + d),
            f"x and y are off by {sign * shift:+g}: {cause}",
        )
        for shift, cause in _SHIFTS
        for sign in (1, -1)
    ),
    Mistake(
        "y's sign",
        lambda s: np.allclose(s.xy, [s.p[0], -s.p[1]]),
        "y changed sign: y points down in this course, and lifting keeps its sign",
    ),
    Mistake(
        "x's sign",
        lambda s: np.allclose(s.xy, [-s.p[0], s.p[1]]),
        "x changed sign: lifting keeps both coordinates and their signs (x points right)",
    ),
    Mistake(
        "the mean subtracted",
        lambda s: np.allclose(s.xy, s.p - s.p.mean()),
        (
            "you subtracted the mean of the point's two coordinates (p - p.mean()): centring belongs to a batch "
            "of points, one mean per column (the normalisation of lesson 04 §5), and lifting changes neither "
            "coordinate"
        ),
    ),
    Mistake("an image convention", lambda s: s.image_slip, lambda s: s.image_slip),
    Mistake(
        "divided by y",
        lambda s: _scaled(s, lambda k: s.p[-1] != 0 and np.isclose(k, 1 / s.p[-1])),
        (
            "you divided by p[-1], which is y: the point has no w yet (dividing by w is the way back from "
            "homogeneous coordinates, section 4 of this lesson), and lifting divides nothing"
        ),
    ),
    Mistake(
        "divided by the length",
        lambda s: _scaled(s, lambda k: np.isclose(k, 1 / np.linalg.norm(s.p))),
        "you divided by the point's length: lifting normalises nothing",
    ),
    Mistake(
        "degrees or radians",
        lambda s: _scaled(s, lambda k: np.isclose(k, np.pi / 180) or np.isclose(k, 180 / np.pi)),
        lambda s: _conversion(s.factor),
    ),
    Mistake(
        "millimetres or metres",
        lambda s: _scaled(s, lambda k: np.isclose(k, 1e-3) or np.isclose(k, 1e3)),
        lambda s: (
            f"x and y are {s.factor:g} times the point's: a millimetre-metre conversion? A point's coordinates are "
            "pixels, and lifting converts nothing"
        ),
    ),
    Mistake(
        "another factor",
        lambda s: s.factor is not None,
        lambda s: (
            f"x and y are {s.factor:g} times the point's "
            f"({'a sign flip' if s.factor == -1 else 'a unit change or a stray factor'})"
        ),
    ),
    Mistake(
        "x and y swapped",
        lambda s: s.may_swap and np.allclose(s.xy, s.p[::-1]),
        "x and y are swapped: keep the point's order, (x, y) = (u, v) = (column, row)",
    ),
    Mistake(
        "x and y swapped, and more",
        lambda s: s.may_swap and s.swapped_too,
        lambda s: (
            f"x and y are swapped (keep the point's order, (x, y) = (u, v)), and {s.swapped_too}"
        ),
    ),
)


def xy_slip(xy: np.ndarray, p: np.ndarray, swapped: bool = False) -> str:
    """The likely cause when x and y came out wrong ('' when they are right; w is judged elsewhere).

    The first row of :data:`XY_MISTAKES` that ``xy`` shows, else which coordinate is wrong and what it
    holds (:func:`one_coordinate_slip`). ``swapped``: ``xy`` is an answer's x and y swapped back.
    """
    if np.allclose(xy, p):
        return ""
    return first_mistake(XY_MISTAKES, _XY(xy, p, swapped)) or one_coordinate_slip(xy, p)


# The 640 x 480 image of the lesson's examples: its size, its centre, and its y-up heights (OpenGL, section 3).
_SIZE = np.array([640.0, 480.0])


def clip_slip(xy: np.ndarray, p: np.ndarray) -> str:
    """A point clipped to the image (np.clip, np.maximum(p, 0)): every changed coordinate now sits on an edge.

    Test input 2, (-1.5, 0), lies left of the image; clipped, it becomes (0, 0), which is not "an
    array never filled" (its y was 0 already).
    """
    changed = ~np.isclose(xy, p)
    edges = [(0.0, _SIZE[0] - 1, _SIZE[0]), (0.0, _SIZE[1] - 1, _SIZE[1])]
    if not changed.any() or not all(
        any(np.isclose(xy[k], e) for e in edges[k]) for k in np.flatnonzero(changed)
    ):
        return ""
    outside = (p < 0) | (p > _SIZE - 1)
    if not np.array_equal(changed, changed & outside):
        return ""
    names = " and ".join(f"{'xy'[k]} = {p[k]:g}" for k in np.flatnonzero(changed))
    return (
        f"{names} became {', '.join(f'{xy[k]:g}' for k in np.flatnonzero(changed))}: clipped to the image (np.clip, "
        "np.maximum)? This point lies outside the 640 x 480 image, and it is still a point: lifting keeps "
        f"every coordinate as it is: {APPEND}"
    )


def image_convention_slip(xy: np.ndarray, p: np.ndarray) -> str:
    """Slips that bring in section 3's image conventions: a y-up flip, the centre subtracted, a division by the size."""
    H = _SIZE[1]
    for flipped in (H - 0.5, H - 1.0, H):
        if np.isclose(xy[0], p[0]) and np.isclose(xy[1], flipped - p[1]):
            return (
                f"y is {xy[1]:g} = {flipped:g} - v: you flipped it to a y-up convention (OpenGL's rows count from "
                "the bottom); the course keeps y down, and lifting changes no coordinate"
            )
    for centre in (_SIZE - 1) / 2, _SIZE / 2:
        if np.allclose(xy, p - centre):
            return (
                f"you subtracted the image centre ({centre[0]:g}, {centre[1]:g}): lifting keeps the pixel "
                "coordinates, with the origin at the top-left pixel's centre"
            )
    for size in _SIZE, _SIZE - 1:
        if np.allclose(xy, p / size):
            return (
                f"you divided by the image size ({size[0]:g}, {size[1]:g}): lifting keeps pixels as they are; it "
                "does not rescale them to [0, 1]"
            )
    return ""


def cases() -> list[tuple[np.ndarray]]:
    """The check's test inputs.

    The first has fractions, so an int cast shows at once; the second lies outside the image (left
    of it, on the top row); the third is the bottom-right pixel of 640 x 480; the fourth has decimals
    no binary float holds exactly, so a detour through float16 (3 digits) shows; the last, (π / 10, e),
    has endless decimals, so an answer rounded to a few decimals shows.
    """
    return [
        (np.array([2.5, 4.25]),),
        (np.array([-1.5, 0.0]),),
        (np.array([639.0, 479.0]),),
        (np.array([100.1, 0.7]),),
        (np.array([np.pi / 10, np.e]),),
    ]


def not_from_p(xy: np.ndarray, p: np.ndarray) -> str:
    """Why x and y, both wrong, do not come from ``p`` at all: another test input's point, or a notebook variable.

    A function that returns the same numbers for every point was written for one input (copied from a
    check's message) or reads a variable of the notebook (``points[0]``, ``roof_tip``) instead of its
    argument; '' when neither explains ``xy``.
    """
    for k, (other,) in enumerate(cases()):
        if not np.allclose(other, p) and np.allclose(xy, other):
            return (
                f"x and y are ({xy[0]:g}, {xy[1]:g}), test input {k + 1}'s point, not this input's: the answer "
                f"does not depend on p; build it from the argument p, not from fixed numbers: {APPEND}"
            )
    main = sys.modules.get("__main__")
    for name, value in vars(main).items() if main is not None else ():
        if (
            name.startswith("_")
            or not isinstance(value, np.ndarray)
            or value.dtype.kind not in "iuf"
            or value.ndim not in (1, 2)
            or value.shape[-1] not in (2, 3)
            or value.size > 3000
        ):
            continue
        rows = value.reshape(-1, value.shape[-1])
        for k, row in enumerate(rows):
            if np.allclose(row[:2], xy):
                where = name if value.ndim == 1 else f"{name}[{k}]"
                return (
                    f"x and y are ({xy[0]:g}, {xy[1]:g}), those of the notebook's `{where}`, not of p: your "
                    f"function reads a variable of the notebook instead of its argument p; lift p: {APPEND}"
                )
    return ""


def one_coordinate_slip(xy: np.ndarray, p: np.ndarray) -> str:
    """Name the coordinate that is wrong, and what it holds when that is recognisable (x twice, a 0)."""
    names = ("x", "y")
    wrong = [k for k in range(2) if not np.isclose(xy[k], p[k])]
    if len(wrong) == 2:
        fixed = not_from_p(xy, p)
        if fixed:
            return fixed
    parts = []
    for k in wrong:
        holds = ""
        if np.isclose(xy[k], p[1 - k]):
            holds = f" (it holds {names[1 - k]}: p[{1 - k}] where p[{k}] belongs)"
        elif xy[k] == 0:
            holds = " (it is 0: never filled?)"
        elif xy[k] == 1:
            holds = " (it is 1: did the 1 land there?)"
        parts.append(f"{names[k]} is {xy[k]:g}, not p[{k}] = {p[k]:g}{holds}")
    return "; ".join(parts)
