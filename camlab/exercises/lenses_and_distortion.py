"""Exercises for lesson 02: the thin lens and lens distortion."""
from __future__ import annotations

import numpy as np

from .. import distortion, lens
from ._numbers import is_number as _is_number, same_number
from ._core import Exercise, register_exercise, same_array, shape_problem, unit_slip


def _thin_lens_cases():
    return [(0.05, 0.1), (0.05, 2.0), (0.2, 0.35), (0.018, 0.5)]


def _thin_lens_diagnosis(args, got, expected) -> str:
    f, zo = args
    if not _is_number(got):
        return "return one number: the image distance in metres"
    slip = unit_slip(got, expected)
    if slip:
        return slip
    g = float(got)
    if np.isclose(g, f * zo / (zo + f)):
        return "sign slip: 1/z_i = 1/f - 1/z_o, so z_i = f z_o / (z_o - f)"
    if np.isclose(g, f * zo / (f - zo)):
        return ("sign slip: z_i = f z_o / (z_o - f), not / (f - z_o); your z_i is negative, but an object beyond f "
                "forms a real image behind the lens, z_i > 0")
    if np.isclose(g, 1 / f - 1 / zo) or np.isclose(g, 1 / f + 1 / zo):
        return "you returned 1/z_i; invert it to get the distance"
    if np.isclose(g, f**2 / (zo - f)):
        return ("that is Newton's form f^2 / (z_o - f), the distance from the focal point F' to the image, not from the "
                "lens; add f (z_i = f + f^2 / (z_o - f) = f z_o / (z_o - f))")
    if np.isclose(g, -f / (zo - f)) or np.isclose(g, f / (zo - f)):
        return "you returned the magnification m = -z_i / z_o; the exercise asks for the distance z_i"
    return "solve 1/f = 1/z_o + 1/z_i for z_i"


def thin_lens_image_distance(f, z_o):
    """Solve the thin-lens equation 1/f = 1/z_o + 1/z_i for z_i (all in metres)."""
    return f * z_o / (z_o - f)


register_exercise(Exercise(
    name="thin_lens_image_distance",
    lesson="02",
    reference=lens.image_distance,
    cases=_thin_lens_cases,
    compare=same_number(rtol=1e-9),
    diagnose=_thin_lens_diagnosis,
    wrong_variants=(
        (lambda f, zo: f * zo / (zo + f), "sign slip"),
        (lambda f, zo: 1 / f - 1 / zo, "invert it"),
        (lambda f, zo: 1e3 * f * zo / (zo - f), "millimetres"),
        (lambda f, zo: f * zo / (f - zo), "your z_i is negative"),
        (lambda f, zo: f**2 / (zo - f), "from the focal point"),
        (lambda f, zo: -f / (zo - f), "magnification"),
    ),
    teaching=thin_lens_image_distance,
))


def _distort_cases():
    rng = np.random.default_rng(2)
    pts = rng.uniform(-0.5, 0.5, (8, 2))
    return [
        (pts, np.array([-0.2, 0.0, 0.0, 0.0, 0.0])),
        (pts, np.array([-0.25, 0.08, 0.0, 0.0, -0.01])),
        (pts, np.array([0.1, -0.02, 0.004, -0.003, 0.0])),
        (np.array([[0.3, 0.4]]), np.array([-0.1, 0.02, 0.01, 0.02, 0.005])),
    ]


def _brown_variant(x, d, cross: float = 2.0, squares_swapped: bool = False, divide: bool = False) -> np.ndarray:
    """The Brown-Conrady model with one typical slip: the cross term's 2, x^2 / y^2 swapped, or x / L for x L."""
    k1, k2, p1, p2, k3 = d
    u, v = x[:, 0], x[:, 1]
    r2 = u**2 + v**2
    L = 1 + k1 * r2 + k2 * r2**2 + k3 * r2**3
    su, sv = (v, u) if squares_swapped else (u, v)
    radial = np.column_stack([u, v]) / L[:, None] if divide else np.column_stack([u, v]) * L[:, None]
    return radial + np.column_stack([cross * p1 * u * v + p2 * (r2 + 2 * su**2),
                                     p1 * (r2 + 2 * sv**2) + cross * p2 * u * v])


def _sign_slip(x, d, g) -> str:
    """A hint when ``g`` is the model with the radial or a tangential coefficient's sign flipped ('' if not)."""
    k1, k2, p1, p2, k3 = d
    flips = (((-k1, -k2, p1, p2, -k3), "the radial terms have the wrong sign: L = 1 + k1 r^2 + k2 r^4 + k3 r^6 "
                                       "(k1 < 0 pulls points in, barrel)", k1 or k2 or k3),
             ((k1, k2, -p1, -p2, k3), "the tangential terms have the wrong sign: x gets + 2 p1 x y + p2 (r^2 + 2 x^2), "
                                      "y gets + p1 (r^2 + 2 y^2) + 2 p2 x y", p1 and p2),
             ((k1, k2, -p1, p2, k3), "the p1 terms have the wrong sign: + 2 p1 x y in x_d, + p1 (r^2 + 2 y^2) in y_d", p1),
             ((k1, k2, p1, -p2, k3), "the p2 terms have the wrong sign: + p2 (r^2 + 2 x^2) in x_d, + 2 p2 x y in y_d", p2))
    for flipped, hint, present in flips:
        if present and np.allclose(g, distortion.distort_points(x, flipped)):
            return hint
    return ""


def _distort_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    x, d = args
    g = np.asarray(got, dtype=float)
    k1, k2, p1, p2, k3 = d
    if (p1 or p2 or k3) and np.allclose(g, distortion.distort_points(x, [k1, k2, p2, k3, p1])):
        return ("you read dist as (k1, k2, k3, p1, p2); OpenCV's order is (k1, k2, p1, p2, k3): "
                "k3 comes last, after the tangential p1, p2")
    swapped = distortion.distort_points(x, [k1, k2, p2, p1, k3])
    if np.allclose(g, swapped):
        return "p1 and p2 are swapped: OpenCV's order is (k1, k2, p1, p2, k3), and x gets 2 p1 x y + p2 (r^2 + 2 x^2)"
    if (p1 or p2) and np.allclose(g, _brown_variant(x, d, cross=1.0)):
        return "the cross terms need their factor 2: x gets 2 p1 x y, y gets 2 p2 x y"
    if (p1 or p2) and np.allclose(g, _brown_variant(x, d, squares_swapped=True)):
        return "x^2 and y^2 are swapped in the tangential terms: x gets p2 (r^2 + 2 x^2), y gets p1 (r^2 + 2 y^2)"
    if np.allclose(g, _brown_variant(x, d, divide=True)):
        return "you divided by the radial factor L; distortion multiplies: x_d = x L + ... (dividing is a rough inverse)"
    sign = _sign_slip(x, d, g)
    if sign:
        return sign
    radial_only = distortion.distort_points(x, [k1, k2, 0, 0, k3])
    if np.allclose(g, radial_only) and (p1 or p2):
        return "you left out the tangential terms p1, p2"
    r = np.hypot(x[:, 0], x[:, 1])
    wrong_r = x * (1 + k1 * r + k2 * r**2 + k3 * r**3)[:, None]
    if np.allclose(g[:, :2], wrong_r) or np.allclose(g, wrong_r + (expected - radial_only)):
        return "the radial factor uses even powers of r: 1 + k1 r^2 + k2 r^4 + k3 r^6 with r^2 = x^2 + y^2"
    if np.allclose(g, distortion.distort_points(x, [k1, k2, p1, p2, 0])) and k3:
        return "you dropped k3 (the fifth coefficient, r^6)"
    return "compare term by term with the model in the lesson: radial factor, then the two tangential terms"


def distort_points(x, dist):
    """Brown-Conrady distortion of (N, 2) normalised points, dist in OpenCV's order."""
    k1, k2, p1, p2, k3 = dist                      # note: k3 comes last
    u, v = x[:, 0], x[:, 1]
    r2 = u**2 + v**2
    radial = 1 + k1 * r2 + k2 * r2**2 + k3 * r2**3  # even powers of r
    ud = u * radial + 2 * p1 * u * v + p2 * (r2 + 2 * u**2)
    vd = v * radial + p1 * (r2 + 2 * v**2) + 2 * p2 * u * v
    return np.column_stack([ud, vd])


register_exercise(Exercise(
    name="distort_points",
    lesson="02",
    reference=distortion.distort_points,
    cases=_distort_cases,
    compare=same_array(rtol=0, atol=1e-12),
    diagnose=_distort_diagnosis,
    wrong_variants=(
        (lambda x, d: distortion.distort_points(x, [d[0], d[1], d[3], d[2], d[4]]), "p1 and p2 are swapped"),
        (lambda x, d: distortion.distort_points(x, [d[0], d[1], 0, 0, d[4]]), "tangential"),
        (lambda x, d: distortion.distort_points(x, [d[0], d[1], d[3], d[4], d[2]]), "k3 comes last"),
        (lambda x, d: x * (1 + d[0] * np.hypot(*x.T) + d[1] * np.hypot(*x.T) ** 2
                           + d[4] * np.hypot(*x.T) ** 3)[:, None], "even powers"),
        (lambda x, d: _brown_variant(x, d, cross=1.0), "factor 2"),
        (lambda x, d: _brown_variant(x, d, squares_swapped=True), "swapped in the tangential terms"),
        (lambda x, d: _brown_variant(x, d, divide=True), "divided by the radial factor"),
        (lambda x, d: distortion.distort_points(x, [-d[0], -d[1], d[2], d[3], -d[4]]), "radial terms have the wrong sign"),
        (lambda x, d: distortion.distort_points(x, [d[0], d[1], -d[2], -d[3], d[4]]), "tangential terms have the wrong"),
        (lambda x, d: _in_place_distortion(x, d), "in place"),
    ),
    teaching=distort_points,
))


# -- hyperfocal_distance ------------------------------------------------------------------

def _hyperfocal_cases():
    return [(0.05, 8.0, 0.03e-3), (0.028, 2.8, 0.02e-3), (0.1, 16.0, 0.03e-3), (0.018, 5.6, 0.015e-3)]


def _hyperfocal_diagnosis(args, got, expected) -> str:
    f, N, c = args
    if not _is_number(got):
        return "return one number: the hyperfocal distance in metres"
    slip = unit_slip(got, expected)
    if slip:
        return slip
    g = float(got)
    if np.isclose(g, f**2 / (N * c), rtol=1e-9):
        return "you dropped the + f: H = f^2 / (N c) + f (small, but it is where the thin-lens algebra puts it)"
    if np.isclose(g, f**2 / (N * c) - f, rtol=1e-9):
        return "the sign of f: c = A f / (H - f) gives H - f = f^2 / (N c), so H = f^2 / (N c) + f"
    if np.isclose(g, expected / 2, rtol=1e-9):
        return "you returned H / 2, the near limit of the depth of field when focused at H; H itself is f^2 / (N c) + f"
    if np.isclose(g, f**2 * N / c, rtol=1e-9) or np.isclose(g, f**2 * N / c + f, rtol=1e-9):
        return "N belongs in the denominator: a larger f-number (smaller aperture) brings H closer"
    if np.isclose(g, f / (N * c) + f, rtol=1e-9) or np.isclose(g, f / (N * c), rtol=1e-9):
        return "square the focal length: H = f^2 / (N c) + f"
    for scale, hint in ((1e-3, "c arrives in metres already (0.03 mm is 3e-05): multiplying it by 1e-3 again makes "
                               "H about 1000 times too large"),
                        (1e3, "c arrives in metres (0.03 mm is 3e-05), not millimetres: multiplying it by 1000 "
                              "makes H about 1000 times too small"),
                        (0.5, "c is the blur circle's diameter, not its radius: use c itself, H = f^2 / (N c) + f")):
        if np.isclose(g, f**2 / (N * c * scale) + f, rtol=1e-9) or np.isclose(g, f**2 / (N * c * scale), rtol=1e-9):
            return hint
    if np.isclose(g, f**2 / (N**2 * c) + f, rtol=1e-9):
        return "N enters once: A = f / N, so c = A f / (H - f) gives H - f = f^2 / (N c)"
    return "set the blur circle of a point at infinity, A f / (H - f) with A = f / N, equal to c and solve for H"


def hyperfocal_distance(f, N, c):
    """Focus here and everything from H/2 to infinity is sharp: the far limit of the depth of field reaches infinity."""
    return f**2 / (N * c) + f     # all lengths in metres


register_exercise(Exercise(
    name="hyperfocal_distance",
    lesson="02",
    reference=lens.hyperfocal_distance,
    cases=_hyperfocal_cases,
    compare=same_number(rtol=1e-9),
    diagnose=_hyperfocal_diagnosis,
    wrong_variants=(
        (lambda f, N, c: f**2 / (N * c), "dropped the + f"),
        (lambda f, N, c: f**2 * N / c + f, "denominator"),
        (lambda f, N, c: f / (N * c) + f, "square the focal length"),
        (lambda f, N, c: 1e3 * (f**2 / (N * c) + f), "millimetres"),
        (lambda f, N, c: f**2 / (N * c) - f, "the sign of f"),
        (lambda f, N, c: (f**2 / (N * c) + f) / 2, "H / 2"),
        (lambda f, N, c: f**2 / (N * c * 1e-3) + f, "metres already"),
        (lambda f, N, c: f**2 / (N * c * 1e3) + f, "not millimetres"),
        (lambda f, N, c: f**2 / (N * c / 2) + f, "not its radius"),
        (lambda f, N, c: f**2 / (N**2 * c) + f, "N enters once"),
    ),
    teaching=hyperfocal_distance,
))


# -- undistort_newton ------------------------------------------------------------------------

def _undistort_cases():
    """Three problems solved to convergence (8 steps), then two cut short at 1 and 2 steps.

    A Newton iteration with a wrong Jacobian still converges, only more slowly, so the
    converged answers cannot see it: the short runs can (each step is fixed by J).
    """
    rng = np.random.default_rng(5)
    pts = rng.uniform(-0.4, 0.4, (8, 2))
    strong = np.array([[0.45, -0.2], [0.0, 0.0], [-0.3, 0.35]])  # strong barrel, inside its fold (0.609)
    return [
        (pts, -0.25, 0.05, 8),
        (pts, 0.12, 0.0, 8),
        (strong, -0.4, 0.0, 8),
        (pts, -0.25, 0.05, 1),
        (strong, -0.4, 0.1, 2),
    ]


def _undistort_reference(x_d, k1, k2, steps):
    """camlab's Newton iteration run for exactly ``steps`` steps from x = x_d (converged after 8 here)."""
    return distortion.newton_undistort(np.array(x_d, dtype=float), distortion.as_dist([k1, k2, 0, 0, 0]),
                                       tol=0.0, max_iter=steps).points


def _radial_iterates(x_d, k1, k2, *, chain: float = 2.0, k2_chain: float = 4.0, step_sign: float = -1.0,
                     frozen: bool = False, steps: int = 40) -> list:
    """Iterates of x <- x + step_sign J^-1 (x L - x_d) from x = x_d, with J = L I + (chain k1 + k2_chain k2 r^2) x x^T.

    chain = 2, k2_chain = 4 is Newton; chain = k2_chain = 0 (J = L I) is the fixed-point iteration
    x = x_d / L; chain = 1 drops the chain rule's 2; k2_chain = 2 differentiates r^4 as 2 r^2 x;
    step_sign = +1 steps along the residual; frozen keeps the J of x_d for every step (the chord method).
    """
    x, out = np.array(x_d, dtype=float), []
    J0 = None
    with np.errstate(all="ignore"):
        for _ in range(steps):
            r2 = (x**2).sum(axis=1, keepdims=True)
            L = 1 + k1 * r2 + k2 * r2**2
            J = L[:, :, None] * np.eye(2) + ((chain * k1 + k2_chain * k2 * r2))[:, :, None] * x[:, :, None] * x[:, None, :]
            if frozen:
                J0 = J if J0 is None else J0
                J = J0
            x = x + step_sign * np.linalg.solve(J, (x * L - x_d)[:, :, None])[:, :, 0]
            out.append(x)
    return out


def _matches_an_iterate(g, iterates) -> int:
    """1-based index of the iterate ``g`` equals (0 if none)."""
    return next((k + 1 for k, it in enumerate(iterates) if np.allclose(g, it, rtol=0, atol=1e-10)), 0)


_WRONG_JACOBIANS = (
    (dict(chain=0.0, k2_chain=0.0),
     "you used J = L I, leaving out how L changes with x: that is the fixed-point iteration x = x_d / L(x), which "
     "converges slowly; differentiate x L(r^2) with the product rule: J = L I + x (dL/dx)^T"),
    (dict(chain=1.0, k2_chain=2.0),
     "the Jacobian misses the chain rule's factor 2: d(r^2)/dx = 2 x, so dL/dx = (2 k1 + 4 k2 r^2) x "
     "(with it Newton converges in a few steps)"),
    (dict(chain=2.0, k2_chain=2.0),
     "the k2 term of the Jacobian is off: d(r^4)/dx = 2 r^2 d(r^2)/dx = 4 r^2 x, so dL/dx = (2 k1 + 4 k2 r^2) x"),
    (dict(chain=1.0, k2_chain=4.0),
     "the k1 term of the Jacobian misses the chain rule's factor 2: d(r^2)/dx = 2 x, so dL/dx = (2 k1 + 4 k2 r^2) x"),
    (dict(frozen=True),
     "you computed J once, at x_d, and reused it for every step (a chord method, which converges only linearly): "
     "recompute r^2, L and J from the current x inside the loop"),
    (dict(step_sign=1.0),
     "step against the residual: x <- x - J^-1 (x L - x_d); stepping along it walks away from the answer"),
)


def _undistort_diagnosis(args, got, expected) -> str:
    problem = shape_problem(got, expected)
    if problem:
        return problem
    x_d, k1, k2, steps = args
    g = np.asarray(got, dtype=float)
    r2 = (x_d**2).sum(axis=1, keepdims=True)
    if np.allclose(g, x_d * (1 + k1 * r2 + k2 * r2**2)):
        return "you distorted x_d again; undistorting solves x L(r^2) = x_d for x, where r^2 = x^2 + y^2 of the unknown x"
    newton = [np.asarray(x_d, dtype=float)] + _radial_iterates(x_d, k1, k2)   # newton[k]: after k steps
    taken = _matches_an_iterate(g, newton) - 1
    if steps < 8 and np.allclose(g, newton[-1], rtol=0, atol=1e-10):
        return (f"you ran to convergence, but this test asked for steps = {steps}: take exactly `steps` Newton steps "
                f"(`for _ in range(steps)`); the check stops you early to see each step, and so your Jacobian")
    if taken >= 0:
        return (f"you took {taken} Newton step{'s' * (taken != 1)}, but steps = {steps}: loop `for _ in range(steps)` "
                f"and step once per pass, starting from x = x_d")
    for wrong, hint in _WRONG_JACOBIANS:
        if _matches_an_iterate(g, _radial_iterates(x_d, k1, k2, steps=max(steps, 40), **wrong)):
            return hint
    if not np.all(np.abs(g) < 10):
        return _WRONG_JACOBIANS[-1][1]
    r = np.sqrt((g**2).sum(axis=1, keepdims=True))
    if np.allclose(g * (1 + k1 * r + k2 * r**2), x_d, atol=1e-9):
        return "the radial factor uses even powers of r: L = 1 + k1 r^2 + k2 r^4 with r^2 = x^2 + y^2"
    return ("one Newton step solves J dx = -(x L - x_d) with J = L I + (2 k1 + 4 k2 r^2) x x^T, the 2 x 2 Jacobian "
            "of x L(r^2), evaluated at the current x; start from x = x_d and take exactly `steps` steps")


def _undistort_exception_hint(exc, args) -> str:
    """np.linalg.solve on a stack: the right-hand side must be (N, 2, 1), not (N, 2)."""
    if isinstance(exc, (ValueError, np.linalg.LinAlgError)) and ("solve" in str(exc) or "core dimension" in str(exc)):
        return ("np.linalg.solve on a stack of N systems: J is (N, 2, 2), so give the right-hand side as (N, 2, 1), "
                "residual[:, :, None], and take [:, :, 0] of the result (an (N, 2) b is read as one N x 2 matrix)")
    return ""


def undistort_newton(x_d, k1, k2, steps=8):
    """Invert x_d = x L(r^2), L = 1 + k1 r^2 + k2 r^4, for (N, 2) normalised points by `steps` Newton steps."""
    x = np.array(x_d, dtype=float)                     # start at the distorted point (a copy: x_d stays as it is)
    for _ in range(steps):                             # from x = x_d, 8 steps reach 1e-12 inside the fold
        r2 = (x**2).sum(axis=1, keepdims=True)         # (N, 1)
        L = 1 + k1 * r2 + k2 * r2**2
        residual = x * L - x_d                         # F(x) - x_d: zero at the answer
        # J = dF/dx = L I + x (dL/dx)^T, with dL/dx = (2 k1 + 4 k2 r^2) x (chain rule: d(r^2)/dx = 2x)
        J = L[:, :, None] * np.eye(2) + (2 * k1 + 4 * k2 * r2)[:, :, None] * x[:, :, None] * x[:, None, :]
        x = x - np.linalg.solve(J, residual[:, :, None])[:, :, 0]   # the Newton step: J dx = -residual
    return x


def _in_place_distortion(x, d):
    out = distortion.distort_points(x, d)
    x[:] = out  # the typical slip: the answer written over the caller's points
    return out


def _until_converged(x_d, k1, k2, steps):
    """Ignores ``steps``: Newton until the step is tiny (right at 8 steps, wrong when the check asks for 1 or 2)."""
    return undistort_newton(x_d, k1, k2, 40)


def _flat_rhs_newton(x_d, k1, k2, steps):
    """np.linalg.solve(J, residual) with an (N, 2) residual: a ValueError in NumPy 2."""
    x = np.array(x_d, dtype=float)
    for _ in range(steps):
        r2 = (x**2).sum(axis=1, keepdims=True)
        L = 1 + k1 * r2 + k2 * r2**2
        J = L[:, :, None] * np.eye(2) + (2 * k1 + 4 * k2 * r2)[:, :, None] * x[:, :, None] * x[:, None, :]
        x = x - np.linalg.solve(J, x * L - x_d)
    return x


register_exercise(Exercise(
    name="undistort_newton",
    lesson="02",
    reference=_undistort_reference,
    cases=_undistort_cases,
    compare=same_array(rtol=0, atol=1e-9),
    diagnose=_undistort_diagnosis,
    exception_hint=_undistort_exception_hint,
    wrong_variants=(
        (lambda x_d, k1, k2, steps: _radial_iterates(x_d, k1, k2, steps=1)[0], "you took 1 Newton step"),
        (lambda x_d, k1, k2, steps: _radial_iterates(x_d, k1, k2, steps=steps + 1)[-1], "but steps ="),
        (lambda x_d, k1, k2, steps: ([np.array(x_d)] + _radial_iterates(x_d, k1, k2, steps=steps))[steps - 1],
         "but steps ="),
        (_until_converged, "you ran to convergence"),
        (lambda x_d, k1, k2, steps: _radial_iterates(x_d, k1, k2, chain=0.0, k2_chain=0.0, steps=8)[-1],
         "fixed-point iteration"),
        # a wrong J run to convergence passes the 8-step tests; the short ones first ask for `steps`, then see J
        (lambda x_d, k1, k2, steps: _radial_iterates(x_d, k1, k2, chain=0.0, k2_chain=0.0, steps=max(steps, 60))[-1],
         "you ran to convergence"),
        (lambda x_d, k1, k2, steps: _radial_iterates(x_d, k1, k2, chain=1.0, k2_chain=2.0, steps=steps)[-1],
         "chain rule's factor 2"),
        (lambda x_d, k1, k2, steps: _radial_iterates(x_d, k1, k2, chain=1.0, k2_chain=2.0, steps=max(steps, 40))[-1],
         "you ran to convergence"),
        (lambda x_d, k1, k2, steps: _radial_iterates(x_d, k1, k2, k2_chain=2.0, steps=steps)[-1], "k2 term"),
        (lambda x_d, k1, k2, steps: _radial_iterates(x_d, k1, k2, frozen=True, steps=steps)[-1], "computed J once"),
        (lambda x_d, k1, k2, steps: _radial_iterates(x_d, k1, k2, step_sign=1.0, steps=steps)[-1],
         "against the residual"),
        (lambda x_d, k1, k2, steps: x_d * (1 + k1 * (x_d**2).sum(1, keepdims=True)
                                           + k2 * (x_d**2).sum(1, keepdims=True) ** 2), "distorted x_d again"),
        (lambda x_d, k1, k2, steps: _in_place_newton(x_d, k1, k2, steps), "in place"),
        (_flat_rhs_newton, "residual[:, :, None]"),
    ),
    teaching=undistort_newton,
))


def _in_place_newton(x_d, k1, k2, steps):
    x = undistort_newton(x_d, k1, k2, steps)
    x_d[:] = x  # overwrites the caller's points
    return x

