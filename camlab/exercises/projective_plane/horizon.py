"""Lesson 06, exercise 4: the horizon, the image of the ground's line at infinity."""

from __future__ import annotations

import numpy as np

from ... import projective
from ...camera import centred_intrinsics, rotation_x, rotation_y, rotation_z
from .._answers import same_up_to_scale, shape_problem
from .._core import Exercise, Mistake, first_mistake, mistake_variant, register_exercise
from .lines import followed_by, incidence, silenced

# --- Exercise 4: the horizon, the image of the ground's line at infinity ---------------------


def _ground_homography(
    pitch_deg: float, yaw_deg: float, focal: float, height: float, roll_deg: float = 0.0
) -> np.ndarray:
    """H = K [r1 r3 h r2]: ground (X, Z, 1) -> pixels for the scene of ``fixtures.ground_plane_view``.

    The same camera as that fixture (K centred on a 640 x 480 image, R tilted down by the pitch
    after the yaw), built here because exercises sit below the fixtures; ``roll_deg`` then turns
    the camera about its optical axis, which tilts the horizon in the image.
    """
    K = centred_intrinsics(focal, (640, 480))
    R = (
        rotation_z(np.radians(roll_deg))
        @ rotation_x(np.radians(pitch_deg))
        @ rotation_y(-np.radians(yaw_deg))
    )
    return K @ np.column_stack([R[:, 0], R[:, 2], height * R[:, 1]])


def _horizon_cases():
    return [
        (_ground_homography(8.0, 25.0, 650.0, 1.6),),
        (
            _ground_homography(20.0, 0.0, 500.0, 1.2),
        ),  # yaw 0: the ground's x direction vanishes at infinity
        (_ground_homography(0.0, -30.0, 800.0, 2.0),),  # level camera: the horizon is the row c_y
        # rolled 12 deg and pitched 15 deg: the horizon is tilted, so no image row is the horizon
        (_ground_homography(15.0, 20.0, 700.0, 1.5, roll_deg=12.0),),
    ]


def _horizon_reference(H):
    return projective.map_lines(H, projective.LINE_AT_INFINITY)


_HORIZON_RULE = "lines move by H^-T, so the horizon is inv(H).T @ (0, 0, 1)"


def _image_row(point) -> np.ndarray | None:
    """The horizontal image line v = v0 through a finite homogeneous point, or None if it is ideal."""
    point = np.asarray(point, dtype=float)
    return None if abs(point[2]) < 1e-12 else np.array([0.0, 1.0, -point[1] / point[2]])


def _row_hint(where: str):
    return lambda a: (
        f"your line is the image row v = const through {where}. That is the horizon only when the camera "
        f"has no roll: this test camera is rolled, and its horizon is tilted by {a.tilt:.1f} deg to the rows. "
        "Do not assume a horizontal horizon: join two ground vanishing points, H[:, 0] x H[:, 1], or move "
        "the line at infinity, " + _HORIZON_RULE
    )


_HORIZON_MISTAKES = (
    Mistake(
        "the points' rule",
        lambda a: a.H @ a.l,
        "you moved the line like a point (H @ l): that is H's third column, the image of the ground's "
        "origin, a point. Incidence l'.x' = l.x needs lines to move by the inverse transpose: "
        + _HORIZON_RULE,
    ),
    Mistake(
        "transpose forgotten",
        lambda a: np.linalg.inv(a.H) @ a.l,
        "inv(H) @ l (or H[0] x H[1], the rows' cross product) drops the transpose: it is inv(H)'s third "
        "column, and the horizon is its third row. " + _HORIZON_RULE[0].upper() + _HORIZON_RULE[1:],
    ),
    Mistake(
        "the backward map",
        lambda a: a.H.T @ a.l,
        "H.T @ l pulls an image line back to the ground (the way back, ground <- image); to push the "
        "ground's line at infinity into the image, " + _HORIZON_RULE,
    ),
    Mistake(
        "l_inf unchanged",
        lambda a: a.l,
        "you returned (0, 0, 1), the ground's own line at infinity; its image is the horizon: "
        + _HORIZON_RULE,
    ),
    Mistake(
        "a finite point joined (x axis)",
        lambda a: np.cross(a.H[:, 0], a.H[:, 2]),
        "your line is the image of the ground's x axis, the line Z = 0: either you moved the line "
        "(0, 1, 0) with inv(H).T instead of l_inf = (0, 0, 1), or you joined H[:, 0] and H[:, 2] "
        "(H[:, 2] is the image of the ground's origin, a finite point). The horizon joins the images of two "
        "ideal points, (1, 0, 0) and (0, 1, 0): H[:, 0] x H[:, 1]",
    ),
    Mistake(
        "a finite point joined (z axis)",
        lambda a: np.cross(a.H[:, 1], a.H[:, 2]),
        "your line is the image of the ground's z axis, the line X = 0: either you moved the line "
        "(1, 0, 0) with inv(H).T instead of l_inf = (0, 0, 1), or you joined H[:, 1] and H[:, 2] "
        "(H[:, 2] is the image of the ground's origin, a finite point). The horizon joins the images of two "
        "ideal points, (1, 0, 0) and (0, 1, 0): H[:, 0] x H[:, 1]",
    ),
    *(
        Mistake(
            f"the image's centre row v = {row:g}",
            lambda a, row=row: np.array([0.0, 1.0, -row]),
            lambda a, row=row: (
                f"your line is the image's centre row v = {row:g} (the principal point's row, c_y): that is "
                "the horizon only for a level camera, pitch 0 and no roll. This test camera looks down, so "
                "its horizon lies above c_y (at roll 0, v = c_y - f tan(pitch), section 5). Take it from H: "
                + _HORIZON_RULE
            ),
        )
        for row in (239.5, 240.0)
    ),
    Mistake(
        "an image row through the vanishing point ahead",
        lambda a: _image_row(a.H[:, 1]),
        _row_hint("the vanishing point ahead, H[:, 1]"),
    ),
    Mistake(
        "an image row through the vanishing point across",
        lambda a: _image_row(a.H[:, 0]),
        _row_hint("the vanishing point across, H[:, 0]"),
    ),
)


def _horizon_context(H):
    from types import SimpleNamespace

    H = np.asarray(H, dtype=float)
    horizon = np.linalg.inv(H).T @ [0.0, 0.0, 1.0]
    tilt = np.degrees(np.arctan2(-horizon[0], horizon[1]))  # the horizon's angle to the image rows
    return SimpleNamespace(H=H, l=np.array([0.0, 0.0, 1.0]), tilt=tilt)


def _horizon_diagnosis(args, got, expected) -> str:
    (H,) = args
    problem = shape_problem(got, expected)
    if problem and np.shape(got) == (3,) and abs(np.asarray(H)[2, 0]) < 1e-12:
        return followed_by(
            problem,
            "This camera has yaw 0, so the ground's x direction (1, 0, 0) vanishes at infinity: H[:, 0] "
            "has w = 0. Dividing a vanishing point by its w fails there; join them as they are.",
        )
    if problem and np.shape(got) == (3,) and abs(np.asarray(H)[2, 2]) < 1e-12:
        return followed_by(
            problem,
            "This camera is level (pitch 0), so H[2, 2] = h r2_z = 0: the ground point below the camera "
            "images at infinity. Dividing H by H[2, 2] (lesson 07's habit) divides by 0 here; any scale "
            "of H gives the same horizon, so do not normalise it.",
        )
    if problem:
        return followed_by(problem, "A line is the 3-vector (a, b, c) of a u + b v + c = 0.")
    g = np.asarray(got, dtype=float)
    named = first_mistake(_HORIZON_MISTAKES, _horizon_context(H), g, same_up_to_scale)
    if named:
        return named
    vps = [np.asarray(H, dtype=float)[:, k] for k in (0, 1)]
    off = [incidence(v, g) for v in vps]
    if min(off) < 1e-9:
        on, missed = ("across, H[:, 0]", "ahead, H[:, 1]")[:: 1 if off[0] < off[1] else -1]
        return (
            f"your line passes through the vanishing point {on} but misses the one {missed} (normalised "
            f"|l . v| = {max(off):.3g}): right point, wrong direction. The horizon holds both: join them, "
            "H[:, 0] x H[:, 1], or " + _HORIZON_RULE + "."
        )
    return (
        "your line misses the ground's vanishing points H[:, 0] and H[:, 1] (normalised |l . v| = "
        f"{off[0]:.3g} and {off[1]:.3g}), and every ground vanishing point lies on the horizon. "
        + _HORIZON_RULE[0].upper()
        + _HORIZON_RULE[1:]
        + "."
    )


def _horizon_note(run) -> str:
    (H,) = _horizon_cases()[0]
    line = np.asarray(run(H), dtype=float)
    off = max(incidence(H[:, k], line) for k in (0, 1))
    return (
        "Your horizon also holds H[:, 0] and H[:, 1], the images of the ground's ideal points (1, 0, 0) and "
        f"(0, 1, 0) (normalised |l . v| {'below 1e-12' if off < 1e-12 else f'= {off:.1e}'}): "
        "H[:, 0] x H[:, 1] is the same line, up to scale."
    )


def horizon_line(H):
    """The ground's line at infinity l = (0, 0, 1) seen through H: lines move by H^-T.

    Parameters
    ----------
    H : (3, 3) array_like
        The homography from the ground (X, Z, 1) to pixels.

    Returns
    -------
    (3,) ndarray
        The horizon (a, b, c), a u + b v + c = 0, up to scale: inv(H).T @ (0, 0, 1).

    References
    ----------
    Hartley & Zisserman, Multiple View Geometry, 2nd ed., sections 2.3.1 (eq. 2.6, how lines move) and 8.6.
    """
    return np.linalg.inv(H).T @ np.array([0.0, 0.0, 1.0])


register_exercise(
    Exercise(
        name="horizon_line",
        lesson="06",
        reference=_horizon_reference,
        cases=_horizon_cases,
        compare=same_up_to_scale,
        diagnose=_horizon_diagnosis,
        wrong_variants=(
            *(
                (mistake_variant(_HORIZON_MISTAKES, row.name, _horizon_context), hint_start)
                for row, hint_start in zip(
                    _HORIZON_MISTAKES[:-1],
                    (
                        "like a point",
                        "drops the transpose",
                        "pulls an image line back",
                        "own line at infinity",
                        "ground's x axis",
                        "ground's z axis",
                        "centre row v = 239.5",
                        "centre row v = 240",
                        "image row v = const through the vanishing point ahead",
                    ),
                    strict=True,
                )
            ),
            (
                silenced(lambda H: np.cross(H[:, 0] / H[2, 0], H[:, 1] / H[2, 1])),
                "yaw 0",
            ),
            (
                silenced(lambda H: np.linalg.inv(H / H[2, 2]).T @ [0.0, 0.0, 1.0]),
                "H[2, 2] = h r2_z = 0",
            ),
            (  # the row through the vanishing point across, where it is finite (right at roll 0)
                lambda H: _image_row(H[:, 0]) if H[2, 0] else _horizon_reference(H),
                "image row v = const through the vanishing point across",
            ),
        ),
        success_note=_horizon_note,
        solution_note="# camlab: camlab.projective.map_lines(H, camlab.projective.LINE_AT_INFINITY),\n# or camlab.projective.join(H[:, 0], H[:, 1]), the two ground vanishing points joined",
        teaching=horizon_line,
    )
)
