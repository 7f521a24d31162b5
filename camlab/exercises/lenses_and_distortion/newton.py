"""Lesson 02's exercise newton_step.

One Newton step of undistortion from any current estimate (the whole 2 x 2 Jacobian matters).
"""

from __future__ import annotations

import re

import numpy as np

from ... import distortion
from .._answers import same_array, shape_problem
from .._core import Exercise, Mistake, first_mistake, register_exercise

# -- newton_step --------------------------------------------------------------------------------


def _newton_cases():
    """Starts off the ray through x_d (rotated and scaled), where the residual has a part across the ray.

    From x = x_d a radial model keeps every iterate on that ray, so only J's radial
    eigenvalue acts; off it, the whole 2 x 2 Jacobian does (a scalar J or a dropped
    off-diagonal gives another step). The last case starts at x_d, as undistortion does.
    """
    rng = np.random.default_rng(5)
    x_d = rng.uniform(-0.4, 0.4, (8, 2))
    turn = np.array([[np.cos(0.3), -np.sin(0.3)], [np.sin(0.3), np.cos(0.3)]])
    x_a = 1.1 * x_d @ turn.T + rng.normal(0, 0.02, (8, 2))
    strong_d = np.array(
        [[0.45, -0.2], [0.05, 0.02], [-0.3, 0.35]]
    )  # strong barrel, inside its fold (0.609)
    strong_x = np.array([[0.5, -0.3], [0.0, 0.06], [-0.42, 0.4]])
    return [
        (x_a, x_d, -0.25, 0.05),
        (x_a, x_d, 0.12, 0.0),
        (strong_x, strong_d, -0.4, 0.1),
        (x_d, x_d, -0.25, 0.05),
    ]


def _newton_step_reference(x, x_d, k1, k2):
    """x - J(x)^-1 (F(x) - x_d) with camlab.distortion.distortion_jacobian and distort_points (dist = (k1, k2, 0, 0, 0)); camlab.distortion.newton_undistort repeats the step until it converges."""
    d = [k1, k2, 0.0, 0.0, 0.0]
    J = distortion.distortion_jacobian(x, d)
    return x - np.linalg.solve(J, (distortion.distort_points(x, d) - x_d)[:, :, None])[:, :, 0]


def _wrong_step(
    x,
    x_d,
    k1,
    k2,
    *,
    jacobian: str = "newton",
    chain: float = 2.0,
    k2_chain: float = 4.0,
    k1_power: float = 0.0,
    k2_power: float = 1.0,
    j_at_target: bool = False,
    l_at_target: bool = False,
    step_sign: float = -1.0,
    start_at_target: bool = False,
    return_delta: bool = False,
    residual_to_x: bool = False,
    multiply: bool = False,
) -> np.ndarray:
    """One step x - J^-1 (F(x) - x_d) with one typical slip (see :data:`_WRONG_STEPS`).

    ``k1_power``, ``k2_power``: the slope's k1 and k2 terms carry r^2 to these powers (right: 0 and 1);
    ``residual_to_x``: the residual x L - x; ``multiply``: delta = -J (F(x) - x_d), J not inverted.
    """
    x = np.array(x_d if start_at_target else x, dtype=float)
    where_j = np.asarray(x_d, dtype=float) if j_at_target else x
    r2 = (where_j**2).sum(axis=1, keepdims=True)
    L = 1 + k1 * r2 + k2 * r2**2
    slope = (
        chain * k1 * r2**k1_power + k2_chain * k2 * r2**k2_power
    )  # (1/x) dL/dx, times x x^T below
    outer = where_j[:, :, None] * where_j[:, None, :]
    eye = np.eye(2)
    J = {
        "newton": L[:, :, None] * eye + slope[:, :, None] * outer,
        "scalar": (L + slope * r2)[:, :, None] * eye,  # x^T x for x x^T
        "diagonal": (L[:, :, None] + slope[:, :, None] * where_j[:, :, None] ** 2) * eye,
        "minus": L[:, :, None] * eye - slope[:, :, None] * outer,
        "fixed": L[:, :, None] * eye,
        "no L": eye + slope[:, :, None] * outer,  # d(x L)/dx's first term L I written as I
    }[jacobian]
    r2x = (x**2).sum(axis=1, keepdims=True)
    L_res = (
        (1 + k1 * (x_d**2).sum(1, keepdims=True) + k2 * (x_d**2).sum(1, keepdims=True) ** 2)
        if l_at_target
        else 1 + k1 * r2x + k2 * r2x**2
    )
    residual = x * L_res - (x if residual_to_x else x_d)
    with np.errstate(all="ignore"):
        delta = (
            step_sign
            * (J @ residual[:, :, None] if multiply else np.linalg.solve(J, residual[:, :, None]))[
                :, :, 0
            ]
        )
    return delta if return_delta else x + delta


_WRONG_STEPS = (  # each row's answer: the step with that slip, from the test input (x, x_d, k1, k2)
    Mistake(
        "J a number times I",
        lambda args: _wrong_step(*args, jacobian="scalar"),
        "your J is a number times I: you wrote x^T x (the number r^2) where the outer product x x^T (a 2 x 2 matrix) "
        "belongs. J = L I + (2 k1 + 4 k2 r^2) x x^T; for a stack of points x[:, :, None] * x[:, None, :]. (From "
        "x = x_d both give the same step, because the iterates stay on the ray; off it they differ)",
    ),
    Mistake(
        "J diagonal",
        lambda args: _wrong_step(*args, jacobian="diagonal"),
        "your J has no off-diagonal terms: d(x L)/dy = x dL/dy = 2 x y (k1 + 2 k2 r^2) is not 0. "
        "J = L I + (2 k1 + 4 k2 r^2) x x^T, whose off-diagonal entries are (2 k1 + 4 k2 r^2) x y",
    ),
    Mistake(
        "x x^T sign",
        lambda args: _wrong_step(*args, jacobian="minus"),
        "the x x^T term of J has the wrong sign: J = L I + (2 k1 + 4 k2 r^2) x x^T (product rule: d(x L) = L dx + x dL)",
    ),
    Mistake(
        "J = L I",
        lambda args: _wrong_step(*args, jacobian="fixed"),
        "you used J = L I, leaving out how L changes with x: that is the fixed-point step x = x_d / L(x); "
        "differentiate x L(r^2) with the product rule: J = L I + x (dL/dx)^T = L I + (2 k1 + 4 k2 r^2) x x^T",
    ),
    Mistake(
        "I for L I",
        lambda args: _wrong_step(*args, jacobian="no L"),
        "your J starts with I where L I belongs: the product rule gives d(x L)/dx = L I + x (dL/dx)^T, and the "
        "first term keeps L (dx/dx = I, times L). J = L I + (2 k1 + 4 k2 r^2) x x^T",
    ),
    Mistake(
        "chain-rule 2 twice",
        lambda args: _wrong_step(*args, chain=4.0, k2_chain=8.0),
        "the x x^T term of J is twice too large: the chain rule's 2 from d(r^2)/dx = 2 x is already in "
        "dL/dx = (2 k1 + 4 k2 r^2) x, so J = L I + (2 k1 + 4 k2 r^2) x x^T (do not double it again)",
    ),
    Mistake(
        "no chain-rule 2",
        lambda args: _wrong_step(*args, chain=1.0, k2_chain=2.0),
        "the Jacobian misses the chain rule's factor 2: d(r^2)/dx = 2 x, so dL/dx = (2 k1 + 4 k2 r^2) x",
    ),
    Mistake(
        "no chain-rule 2 on k1",
        lambda args: _wrong_step(*args, chain=1.0, k2_chain=4.0),
        "the k1 term of the Jacobian misses the chain rule's factor 2: d(r^2)/dx = 2 x, so dL/dx = (2 k1 + 4 k2 r^2) x",
    ),
    Mistake(
        "no chain-rule 2 on k2",
        lambda args: _wrong_step(*args, k2_chain=2.0),
        "the k2 term of the Jacobian is off: d(r^4)/dx = 2 r^2 d(r^2)/dx = 4 r^2 x, so dL/dx = (2 k1 + 4 k2 r^2) x",
    ),
    Mistake(
        "no k2 in J",
        lambda args: _wrong_step(*args, k2_chain=0.0),
        "your J has no k2 term: L's k2 r^4 changes with x too, d(r^4)/dx = 4 r^2 x, so dL/dx = (2 k1 + 4 k2 r^2) x",
    ),
    Mistake(
        "J at x_d",
        lambda args: _wrong_step(*args, j_at_target=True),
        "you evaluated J at x_d; Newton's J belongs to the current estimate x (recompute r^2, L and J from x)",
    ),
    Mistake(
        "L at x_d",
        lambda args: _wrong_step(*args, l_at_target=True),
        "your residual uses L of x_d: F(x) = x L(r^2) with r^2 = x^2 + y^2 of the current x, so the residual is "
        "x L(x) - x_d",
    ),
    Mistake(
        "step sign",
        lambda args: _wrong_step(*args, step_sign=1.0),
        "step against the residual: x + delta with J delta = -(F(x) - x_d); stepping along it walks away from the answer",
    ),
    Mistake(
        "step from x_d",
        lambda args: _wrong_step(*args, start_at_target=True),
        "you stepped from x_d, not from the current estimate x: the step is x + delta with J(x) delta = -(F(x) - x_d) "
        "(the check's x is off the ray through x_d, where the whole 2 x 2 J matters)",
    ),
    Mistake(
        "the step returned",
        lambda args: _wrong_step(*args, return_delta=True),
        "you returned the step delta; return the new estimate x + delta",
    ),
    Mistake(
        "multiplied by J",
        lambda args: _wrong_step(*args, multiply=True),
        "you multiplied the residual by J; Newton divides by it: solve J delta = -(F(x) - x_d), "
        "delta = np.linalg.solve(J, -residual[:, :, None])[:, :, 0] (J^-1, not J)",
    ),
    Mistake(
        "residual to x",
        lambda args: _wrong_step(*args, residual_to_x=True),
        "your residual is F(x) - x; it measures how far F(x) is from the distorted point x_d: F(x) - x_d, "
        "which is zero at the answer",
    ),
    Mistake(
        "k1 r",
        lambda args: _wrong_step(*args, k1_power=0.5),
        "the k1 term of the Jacobian has an extra r: d(k1 r^2)/dx = 2 k1 x (r^2 = x^2 + y^2, no square root), "
        "so dL/dx = (2 k1 + 4 k2 r^2) x",
    ),
    Mistake(
        "k2 r^2",
        lambda args: _wrong_step(*args, k2_power=2.0),
        "the k2 term of the Jacobian has r^4 where r^2 belongs: d(k2 r^4)/dx = 4 k2 r^2 x, so "
        "dL/dx = (2 k1 + 4 k2 r^2) x",
    ),
    Mistake(
        "k2 r",
        lambda args: _wrong_step(*args, k2_power=0.5),
        "the k2 term of the Jacobian has r where r^2 belongs: d(k2 r^4)/dx = 4 k2 r^2 x (r^2 = x^2 + y^2, "
        "no square root), so dL/dx = (2 k1 + 4 k2 r^2) x",
    ),
)


def _newton_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    x, x_d, k1, k2 = args
    g = np.asarray(got, dtype=float)
    if k1 != k2 and np.allclose(g, _newton_step_reference(x, x_d, k2, k1), rtol=0, atol=1e-10):
        return "k1 and k2 are swapped: L = 1 + k1 r^2 + k2 r^4 (k1 with r^2), and J = L I + (2 k1 + 4 k2 r^2) x x^T"
    if k2 and np.allclose(g, _newton_step_reference(x, x_d, k1, 0.0), rtol=0, atol=1e-10):
        return "you left k2 out: L = 1 + k1 r^2 + k2 r^4, and J = L I + (2 k1 + 4 k2 r^2) x x^T"
    converged = distortion.undistort_points(x_d, [k1, k2, 0.0, 0.0, 0.0])
    estimate = _newton_step_reference(x, x_d, k1, k2)
    for steps in (2, 3):  # a loop inside the step (not yet converged: that case follows)
        estimate = _newton_step_reference(estimate, x_d, k1, k2)
        if np.allclose(g, estimate, rtol=0, atol=1e-10) and not np.allclose(
            g, converged, rtol=0, atol=1e-8
        ):
            return (
                f"that is {steps} Newton steps from x; newton_step takes exactly one, from the x it is given "
                "(the loop that repeats it is the caller's)"
            )
    if np.allclose(g, converged, rtol=0, atol=1e-8):
        return (
            "that is the converged answer, after many steps; newton_step takes one step only, from the x it is "
            "given: return x + delta with J(x) delta = -(F(x) - x_d) (the loop that repeats it is the caller's)"
        )
    cause = first_mistake(
        _WRONG_STEPS, args, g, lambda got, step: np.allclose(got, step, rtol=0, atol=1e-10)
    )
    if cause:
        return cause
    stepped = np.isclose(g, expected, rtol=0, atol=1e-10).all(axis=1)
    untouched = np.isclose(g, x, rtol=0, atol=1e-12).all(axis=1) & ~np.isclose(expected, x).all(
        axis=1
    )
    if untouched.all():
        return (
            "you returned x itself, unchanged: the step was never added (x + delta makes a new array: "
            "return it, or assign it first); take the Newton step x + delta with J(x) delta = -(F(x) - x_d)"
        )
    if untouched.any() and stepped.any() and (stepped | untouched).all():
        rows = np.flatnonzero(untouched).tolist()
        return (
            f"row{'s' if len(rows) > 1 else ''} {rows} came back unchanged, the others are right: a loop over the "
            "points that skipped "
            + (
                "the first, point 0 (range(1, N)? Python counts from 0)"
                if rows == [0]
                else "some of them"
            )
            + "; step every row, or drop the loop: the stacked np.linalg.solve handles all N at once"
        )
    r2 = (x**2).sum(axis=1, keepdims=True)
    if np.allclose(g, x * (1 + k1 * r2 + k2 * r2**2)):
        return "you returned F(x), the current estimate distorted; return x + delta, with J(x) delta = -(F(x) - x_d)"
    r = np.sqrt(r2)
    L_odd = 1 + k1 * r + k2 * r**2
    J_odd = (
        L_odd[:, :, None] * np.eye(2)
        + ((k1 + 2 * k2 * r) / np.maximum(r, 1e-300))[:, :, None] * x[:, :, None] * x[:, None, :]
    )
    with np.errstate(all="ignore"):
        odd = x - np.linalg.solve(J_odd, (x * L_odd - x_d)[:, :, None])[:, :, 0]
    if np.allclose(g, odd):
        return (
            "the radial factor uses even powers of r: L = 1 + k1 r^2 + k2 r^4 with r^2 = x^2 + y^2"
        )
    if np.allclose(g, expected, rtol=0, atol=1e-6):
        return (
            "close but not exact (within 1e-6): a numerical Jacobian? Derive it as asked, "
            "J = L I + (2 k1 + 4 k2 r^2) x x^T, and solve with it"
        )
    return (
        "one Newton step from the current x: J delta = -(x L - x_d) with J = L I + (2 k1 + 4 k2 r^2) x x^T, "
        "L and r^2 of x; return x + delta"
    )


def _numerical_jacobian_newton(x, x_d, k1, k2):
    """A typical slip: the Jacobian by central differences, close to the exact step but not equal."""

    def F(p):
        return p * (
            1 + k1 * (p**2).sum(-1, keepdims=True) + k2 * (p**2).sum(-1, keepdims=True) ** 2
        )

    h = 1e-7
    J = np.stack([(F(x + h * e) - F(x - h * e)) / (2 * h) for e in np.eye(2)], axis=-1)
    return x - np.linalg.solve(J, (F(x) - x_d)[:, :, None])[:, :, 0]


def _newton_exception_hint(exc, args) -> str:
    """np.linalg.solve on a stack: the right-hand side must be (N, 2, 1), not (N, 2)."""
    if isinstance(exc, (ValueError, np.linalg.LinAlgError)) and (
        "solve" in str(exc) or "core dimension" in str(exc)
    ):
        return (
            "np.linalg.solve on a stack of N systems: J is (N, 2, 2), so give the right-hand side as (N, 2, 1), "
            "residual[:, :, None], and take [:, :, 0] of the result (an (N, 2) b is read as one N x 2 matrix)"
        )
    if isinstance(exc, ValueError) and "broadcast" in str(exc):
        shapes = [
            tuple(int(n) for n in found.split(",") if n.strip())
            for found in re.findall(r"\(([\d,\s]*)\)", str(exc))
        ]
        if any(len(shape) == 3 and shape[-1] == 1 for shape in shapes):
            return (
                "an (N, 2, 1) array met an (N, 2) one: np.linalg.solve on the stack returns (N, 2, 1), one column "
                "per point, so take [:, :, 0] of its result before adding it to x "
                "(delta = np.linalg.solve(J, -residual[:, :, None])[:, :, 0])"
            )
        return (
            "a broadcasting slip: r2 = (x**2).sum(axis=1) is (N,), so L is (N,) too, and x * L lines it up with "
            "x's last axis (of size 2), not with its rows. Keep one value per row as a column: "
            "(x**2).sum(axis=1, keepdims=True), or L[:, None]"
        )
    return ""


def newton_step(x, x_d, k1, k2):
    """One Newton step towards x L(r^2) = x_d (L = 1 + k1 r^2 + k2 r^4) from the current (N, 2) estimate x.

    Parameters
    ----------
    x : (N, 2) ndarray
        The current estimates of the undistorted normalised points.
    x_d : (N, 2) ndarray
        The distorted normalised points.
    k1, k2 : float
        The radial coefficients.

    Returns
    -------
    (N, 2) ndarray
        x + delta, where J delta = -(x L - x_d) with each point's 2 x 2 Jacobian
        J = L I + (2 k1 + 4 k2 r^2) x x^T; a new array (``x`` and ``x_d`` stay as they are).
    """
    r2 = (x**2).sum(axis=1, keepdims=True)  # (N, 1), of the current x
    L = 1 + k1 * r2 + k2 * r2**2
    residual = x * L - x_d  # F(x) - x_d: zero at the answer
    # J = dF/dx = L I + x (dL/dx)^T, with dL/dx = (2 k1 + 4 k2 r^2) x (chain rule: d(r^2)/dx = 2x)
    slope = 2 * k1 + 4 * k2 * r2  # (N, 1)
    outer = x[:, :, None] * x[:, None, :]  # x x^T, (N, 2, 2)
    J = L[:, :, None] * np.eye(2) + slope[:, :, None] * outer
    # J delta = -residual, one 2 x 2 system per point: the right-hand side as (N, 2, 1)
    delta = np.linalg.solve(J, -residual[:, :, None])[:, :, 0]
    return x + delta  # a new array: x and x_d stay as they are


def _in_place_newton(x, x_d, k1, k2):
    out = _newton_step_reference(x, x_d, k1, k2)
    x[:] = out  # `x -= ...`: overwrites the caller's estimate
    return out


def _flat_rhs_newton(x, x_d, k1, k2):
    """np.linalg.solve(J, residual) with an (N, 2) residual: a ValueError in NumPy 2."""
    r2 = (x**2).sum(axis=1, keepdims=True)
    L = 1 + k1 * r2 + k2 * r2**2
    J = (
        L[:, :, None] * np.eye(2)
        + (2 * k1 + 4 * k2 * r2)[:, :, None] * x[:, :, None] * x[:, None, :]
    )
    return x - np.linalg.solve(J, x * L - x_d)


def _flat_r2_newton(x, x_d, k1, k2):
    """r^2 without keepdims: x * L broadcasts (N, 2) against (N,), a ValueError for N != 2."""
    r2 = (x**2).sum(axis=1)
    L = 1 + k1 * r2 + k2 * r2**2
    return x - (x * L - x_d)


def _no_column_newton(x, x_d, k1, k2):
    """The stacked solve's (N, 2, 1) result added to x without [:, :, 0]: a broadcasting ValueError."""
    r2 = (x**2).sum(axis=1, keepdims=True)
    L = 1 + k1 * r2 + k2 * r2**2
    J = (
        L[:, :, None] * np.eye(2)
        + (2 * k1 + 4 * k2 * r2)[:, :, None] * x[:, :, None] * x[:, None, :]
    )
    return x + np.linalg.solve(J, -(x * L - x_d)[:, :, None])


def _loop_from_one_newton(x, x_d, k1, k2):
    """A per-point loop that starts at 1: row 0 comes back unchanged."""
    out = np.array(x, dtype=float)
    out[1:] = _newton_step_reference(x[1:], x_d[1:], k1, k2)
    return out


register_exercise(
    Exercise(
        name="newton_step",
        lesson="02",
        reference=_newton_step_reference,
        cases=_newton_cases,
        compare=same_array(rtol=0, atol=1e-10),
        diagnose=_newton_diagnosis,
        exception_hint=_newton_exception_hint,
        ndarray_only=True,
        wrong_variants=tuple(
            (lambda x, x_d, k1, k2, row=row: row.answer((x, x_d, k1, k2)), phrase)
            for row, phrase in zip(
                _WRONG_STEPS,
                (
                    "your J is a number times I",
                    "no off-diagonal terms",
                    "term of J has the wrong sign",
                    "fixed-point step",
                    "your J starts with I where L I belongs",
                    "twice too large",
                    "misses the chain rule's factor 2",
                    "the k1 term of the Jacobian",
                    "the k2 term of the Jacobian",
                    "no k2 term",
                    "you evaluated J at x_d",
                    "your residual uses L of x_d",
                    "step against the residual",
                    "you stepped from x_d",
                    "you returned the step delta",
                    "you multiplied the residual by J",
                    "measures how far",
                    "has an extra r",
                    "the k2 term of the Jacobian has r",
                    "Jacobian has r where",
                ),
                strict=True,
            )
        )
        + (
            (
                lambda x, x_d, k1, k2: (
                    x
                    * (
                        1
                        + k1 * (x**2).sum(1, keepdims=True)
                        + k2 * (x**2).sum(1, keepdims=True) ** 2
                    )
                ),
                "the current estimate distorted",
            ),
            (_in_place_newton, "in place"),
            (
                lambda x, x_d, k1, k2: _newton_step_reference(x, x_d, k2, k1),
                "k1 and k2 are swapped",
            ),
            (lambda x, x_d, k1, k2: _newton_step_reference(x, x_d, k1, 0.0), "you left k2 out"),
            (
                lambda x, x_d, k1, k2: distortion.undistort_points(x_d, [k1, k2, 0, 0, 0]),
                "the converged answer",
            ),
            (
                lambda x, x_d, k1, k2: newton_step(newton_step(x, x_d, k1, k2), x_d, k1, k2),
                "that is 2 Newton steps",
            ),
            (_flat_rhs_newton, "np.linalg.solve on a stack"),
            (_flat_r2_newton, "x * L lines it up"),
            (_no_column_newton, "take [:, :, 0] of its result"),
            (_loop_from_one_newton, "skipped the first, point 0"),
            (lambda x, x_d, k1, k2: x.copy(), "you returned x itself"),
            (_numerical_jacobian_newton, "a numerical Jacobian"),
            (
                lambda x, x_d, k1, k2: _newton_step_reference(x, x_d, k1, k2).tolist(),
                "wrap the values in np.array",
            ),
        ),
        teaching=newton_step,
    )
)
