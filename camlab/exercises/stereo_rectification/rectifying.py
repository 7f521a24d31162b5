"""Exercise 5 of lesson 11: the common orientation of a rectified pair (`rectifying_rotation`)."""

from __future__ import annotations

import numpy as np

from ...camera import Camera, rotation_from_axis_angle
from .._answers import same_array, shape_problem
from .._core import Exercise, register_exercise
from ._rig import converging_pair

# --------------------------------------------------------------------------- R_new (Fusiello)


def _rectifying_cases():
    """A tilted rig, a converging one, one with a vertical step in the baseline, and a parallel one.

    The parallel rig comes last: there R1 is symmetric enough that some slips coincide.
    """
    rng = np.random.default_rng(11)
    R1 = rotation_from_axis_angle(rng.normal(0, 0.15, 3)) @ converging_pair(0.3, 0.0)[0].R
    C1 = np.array([0.1, -0.2, 1.3])
    cases = [(C1, C1 + 0.25 * R1[0] + 0.03 * R1[1], R1)]
    for c1, c2 in (
        converging_pair(0.5, np.deg2rad(30)),
        (
            Camera.look_at([0, 0, 1.0], [0.2, 3, 1.0]),
            Camera.look_at([0.3, 0.02, 1.05], [0.2, 3, 1]),
        ),
        converging_pair(0.2, 0.0),
    ):
        cases.append((c1.centre, c2.centre, c1.R))
    return cases


def rectifying_rotation(C1, C2, R1):
    r"""The rectified cameras' common orientation: x along the baseline (Fusiello, Trucco & Verri).

    Rows of :math:`R_{new}` (cam_from_world, so its rows are the new camera axes in world
    coordinates):

    - :math:`x = (C_2 - C_1) / \|C_2 - C_1\|`, the baseline, so that a point moves left
      (positive disparity) from image 1 to image 2;
    - :math:`y = z_1 \times x` normalised, with :math:`z_1` camera 1's old optical axis in world
      coordinates, the third *row* of :math:`R_1`: perpendicular to the baseline and to the old
      viewing direction, pointing down like the old :math:`y`;
    - :math:`z = x \times y`: the old viewing direction made orthogonal to the baseline.

    Both images are then warped by :math:`K_{new} R_{new} R_i^\top K_i^{-1}`.

    Parameters
    ----------
    C1, C2 : (3,) array_like
        The camera centres, world metres.
    R1 : (3, 3) array_like
        Camera 1's rotation (cam_from_world).

    Returns
    -------
    (3, 3) ndarray
        :math:`R_{new}`, a rotation with rows x, y, z.

    References
    ----------
    Fusiello, Trucco & Verri, A compact algorithm for rectification of stereo pairs, MVA 2000;
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., section 11.12.
    """
    base = np.asarray(C2, dtype=float) - np.asarray(C1, dtype=float)
    x = base / np.linalg.norm(base)
    y = np.cross(np.asarray(R1, dtype=float)[2], x)
    y /= np.linalg.norm(y)
    return np.vstack([x, y, np.cross(x, y)])


def _fusiello(C1, C2, z_old, sign=1.0, y_first=True, normalise=True, z_kept=False):
    x = sign * (np.asarray(C2, float) - np.asarray(C1, float))
    x /= np.linalg.norm(x)
    y = np.cross(z_old, x) if y_first else np.cross(x, z_old)
    if normalise:
        y /= np.linalg.norm(y)
    return np.vstack([x, y, np.asarray(z_old, float) if z_kept else np.cross(x, y)])


def _baseline_not_unit(norms, C1, C2) -> str | None:
    """The hint for x = C2 - C1 left at the baseline's length (rows of lengths |B|, 1, |B|), else None."""
    if np.isclose(norms[0], 1.0, atol=1e-6) or not np.isclose(
        norms[0], np.linalg.norm(C2 - C1), rtol=1e-6
    ):
        return None
    return (
        f"your x is the baseline C2 - C1 itself, of length |C2 - C1| = {norms[0]:.4g} m, not a unit "
        "vector (rows of lengths "
        + ", ".join(f"{n:.4g}" for n in norms)
        + "): divide it by its length, "
        "x = (C2 - C1) / |C2 - C1|, before y = z_old × x and z = x × y"
    )


def _rectifying_forms(C1, C2, R1, expected) -> list:
    """Each typical slip's R_new on this input, with its hint."""
    return [
        (
            expected.T,
            "you put x, y, z in the COLUMNS: that is world_from_cam. R_new is cam_from_world, so the new "
            "axes (in world coordinates) are its ROWS: np.vstack([x, y, z])",
        ),
        (
            _fusiello(C1, C2, R1[2], sign=-1.0),
            "your x points from C2 to C1: the baseline is C2 - C1, so that camera 2 sits at +x and a "
            "point's disparity u1 - u2 is positive",
        ),
        (
            _fusiello(C1, C2, R1[:, 2]),
            "your old viewing direction is the third COLUMN of R1; R1 is cam_from_world, so camera 1's "
            "optical axis in world coordinates is its third ROW, R1[2] (= R1^T (0, 0, 1))",
        ),
        (
            _fusiello(C1, C2, R1[2], y_first=False),
            "your y is x × z_old, which points up, and so z points backwards: y = z_old × x (z_old = R1[2]) "
            "keeps y pointing down and z looking forward, like the old camera",
        ),
        (
            _fusiello(C1, C2, np.array([0.0, 0.0, 1.0])),
            "your old viewing direction is the world's z axis (0, 0, 1), which is UP in this course's "
            "worlds, not where camera 1 looks: its optical axis in world coordinates is R1[2]",
        ),
        (
            expected * [[1.0], [-1.0], [1.0]],
            "your y is x × z_old (it points up) and your z = y × x: the rows x, y, z make det R_new = -1, a "
            "left-handed frame, and the image comes out upside down. y = z_old × x, then z = x × y",
        ),
        (
            _fusiello(C1, C2, np.array([0.0, 1.0, 0.0])),
            "your old viewing direction is the world's y axis (0, 1, 0), roughly ahead in this course's "
            "worlds but not where camera 1 looks: its optical axis in world coordinates is R1[2]",
        ),
        (
            _fusiello(C1, C2, R1[1]),
            "your old viewing direction is R1[1], camera 1's y axis (down in its image): the optical "
            "axis is the third row, z_old = R1[2]",
        ),
    ]


def _rectifying_diagnosis(args, got, expected) -> str:
    C1, C2, R1 = (np.asarray(a, dtype=float) for a in args)
    problem = shape_problem(got, expected)
    if problem:
        return problem + ". Return R_new as a (3, 3) array whose rows are the new x, y and z axes."
    g = np.asarray(got, dtype=float)
    forms = _rectifying_forms(C1, C2, R1, expected)
    for wrong, hint in forms:
        if np.allclose(g, wrong, atol=1e-8):
            return hint
    if np.allclose(g[:2], expected[:2], atol=1e-8) and np.allclose(g[2], -expected[2], atol=1e-8):
        return "your z = y × x is -z: det R_new = -1, a left-handed frame. z = x × y"
    gram = g @ g.T
    norms = np.linalg.norm(g, axis=1)
    if np.allclose(norms, 1.0, atol=1e-6) and not np.allclose(gram, np.eye(3), atol=1e-6):
        i, k = np.unravel_index(np.argmax(np.abs(gram - np.eye(3))), gram.shape)
        names = "xyz"
        return (
            f"your rows are unit vectors but not perpendicular: {names[i]} . {names[k]} = {gram[i, k]:.3g}"
            + (
                ". Your z is the old viewing direction itself, which is not perpendicular to the "
                "baseline x when the cameras converge: take z = x × y"
                if np.allclose(g[2], R1[2], atol=1e-8)
                else ". Build y = z_old × x (normalised) and then z = x × y, so each is perpendicular to the others"
            )
        )
    unit = _baseline_not_unit(norms, C1, C2)
    if unit:
        return unit
    if not np.allclose(gram, np.eye(3), atol=1e-6):
        return (
            f"your rows have lengths {', '.join(f'{n:.4g}' for n in norms)} (R R^T != I): z_old × x has "
            "length sin(angle between them), not 1 when the cameras converge or the baseline is tilted; "
            "normalise y (and x) before z = x × y"
        )
    if abs(g[0] @ (C2 - C1)) > 1e-6 * np.linalg.norm(C2 - C1) and not np.allclose(
        g[0], expected[0]
    ):
        return "your first row is not the baseline direction: x = (C2 - C1) / |C2 - C1|"
    return (
        "rows x = (C2 - C1)/|C2 - C1|, y = z_old × x normalised (z_old = R1[2], camera 1's optical axis), "
        "z = x × y"
    )


register_exercise(
    Exercise(
        name="rectifying_rotation",
        lesson="11",
        reference=rectifying_rotation,
        cases=_rectifying_cases,
        compare=same_array(rtol=0.0, atol=1e-8),
        diagnose=_rectifying_diagnosis,
        wrong_variants=(
            (lambda C1, C2, R1: rectifying_rotation(C1, C2, R1).T, "COLUMNS"),
            (lambda C1, C2, R1: _fusiello(C1, C2, np.asarray(R1)[2], sign=-1.0), "from C2 to C1"),
            (lambda C1, C2, R1: _fusiello(C1, C2, np.asarray(R1)[:, 2]), "third COLUMN"),
            (lambda C1, C2, R1: _fusiello(C1, C2, np.asarray(R1)[2], y_first=False), "points up"),
            (
                lambda C1, C2, R1: rectifying_rotation(C1, C2, R1) * [[1], [1], [-1]],
                "left-handed",
            ),
            (
                lambda C1, C2, R1: _fusiello(C1, C2, np.asarray(R1)[2], normalise=False),
                "normalise y",
            ),
            (
                lambda C1, C2, R1: (
                    _fusiello(C1, C2, np.asarray(R1)[2])
                    * [
                        [np.linalg.norm(np.subtract(C2, C1))],
                        [1],
                        [np.linalg.norm(np.subtract(C2, C1))],
                    ]
                ),
                "not a unit vector",
            ),
            (lambda C1, C2, R1: _fusiello(C1, C2, np.array([0.0, 0.0, 1.0])), "world's z axis"),
            (lambda C1, C2, R1: _fusiello(C1, C2, np.asarray(R1)[2], z_kept=True), "z = x × y"),
            (lambda C1, C2, R1: _fusiello(C1, C2, np.asarray(R1)[1]), "camera 1's y axis"),
            (
                lambda C1, C2, R1: rectifying_rotation(C1, C2, R1) * [[1], [-1], [1]],
                "upside down",
            ),
            (lambda C1, C2, R1: _fusiello(C1, C2, np.array([0.0, 1.0, 0.0])), "world's y axis"),
        ),
        teaching=rectifying_rotation,
        solution_note=(
            "# camlab's rectify_calibrated (camlab.rectification.rectify_calibrated) builds R_new the same\n"
            "# way, but takes z from the mean of both cameras' optical axes, not camera 1's alone"
        ),
    )
)
