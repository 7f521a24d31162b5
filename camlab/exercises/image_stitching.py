"""Exercises for lesson 09, image stitching: the canvas bounds (canvas_box) and feathering weights."""
from __future__ import annotations

import numpy as np

from .. import stitching as st
from ..homography import rotation_homography
from ._core import Exercise, register_exercise, same_array


# ----------------------------------------------------------------------------- canvas bounds

def _canvas_cases():
    K = np.array([[400.0, 0, 159.5], [0, 400.0, 119.5], [0, 0, 1]])

    def yaw(deg):
        a = np.radians(deg)
        return np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])

    shift = np.array([[1.0, 0, 50], [0, 1, -30], [0, 0, 1]])
    return [
        ([np.eye(3), shift], [(240, 320), (240, 320)]),                               # a translation
        ([np.eye(3), rotation_homography(K, yaw(20))], [(240, 320), (240, 320)]),    # a turning camera
        ([rotation_homography(K, yaw(-15)), np.eye(3), rotation_homography(K, yaw(15))],
         [(240, 320), (200, 300, 3), (240, 320)]),                                   # three images, sizes differ
    ]


def _corners(Hs, shapes, divide: bool = True, last: int = 1) -> np.ndarray:
    pts = []
    for H, s in zip(Hs, shapes):
        h, w = s[:2]
        c = np.array([[0, 0, 1], [w - last, 0, 1], [w - last, h - last, 1], [0, h - last, 1]], float) @ np.asarray(H).T
        pts.append(c[:, :2] / c[:, 2:] if divide else c[:, :2])
    return np.vstack(pts)


def _box(p: np.ndarray) -> np.ndarray:
    return np.array([np.floor(p.min(axis=0) + 1e-9), np.ceil(p.max(axis=0) - 1e-9)])


def _canvas_diagnosis(args, got, expected) -> str:
    g = np.asarray(got, dtype=float)
    if g.shape != (2, 2):
        return f"return a (2, 2) array [[u_min, v_min], [u_max, v_max]], got shape {g.shape}."
    Hs, shapes = args
    if np.allclose(g, expected[:, ::-1]):
        return "your columns are (v, u); points are (u, v) = (column, row), as everywhere in camlab."
    if np.allclose(g, _box(_corners(Hs, shapes, divide=False))):
        return "you forgot to divide the mapped corners by their third coordinate w (homogeneous to pixels)."
    if np.allclose(g, _box(_corners(Hs, shapes, last=0))):
        return "the last pixel of a w-wide image is at u = w - 1 (pixel centres start at 0), not at u = w."
    p = _corners(Hs, shapes)
    if np.allclose(g, [np.ceil(p.min(axis=0)), np.floor(p.max(axis=0))]) or np.allclose(g, [p.min(0), p.max(0)]):
        return "round outwards: floor the minimum and ceil the maximum, so no warped pixel is cut off."
    return ("map the four corners (0, 0), (w-1, 0), (w-1, h-1), (0, h-1) of every image by its H (divide by w), "
            "take the bounding box of all of them and round it outwards.")


register_exercise(Exercise(
    name="canvas_box",
    lesson="09",
    reference=st.canvas_box,
    cases=_canvas_cases,
    compare=same_array(atol=1e-9),
    diagnose=_canvas_diagnosis,
    wrong_variants=(
        (lambda Hs, shapes: st.canvas_box(Hs, shapes)[:, ::-1], "(u, v)"),
        (lambda Hs, shapes: _box(_corners(Hs, shapes, divide=False)), "divide"),
        (lambda Hs, shapes: _box(_corners(Hs, shapes, last=0)), "w - 1"),
        (lambda Hs, shapes: np.array([_corners(Hs, shapes).min(0), _corners(Hs, shapes).max(0)]), "round outwards"),
    ),
))


# ----------------------------------------------------------------------------- feather weights

def _feather_cases():
    return [((3, 4),), ((5, 5),), ((6, 9),), ((1, 3),)]


def _feather_diagnosis(args, got, expected) -> str:
    g = np.asarray(got, dtype=float)
    if g.shape != expected.shape:
        return f"the weights should have the image's shape {expected.shape} (rows, columns), got {g.shape}."
    if np.allclose(g, expected - 0.5):
        return ("off by half a pixel: pixel centres are at integer u and the border at u = -1/2, so the first "
                "column is 1/2 from the border (u + 1/2), not 0.")
    if np.allclose(g, expected + 0.5):
        return "off by half a pixel: the border is at u = -1/2 and u = W - 1/2; use u + 1/2 and W - 1/2 - u."
    h, w = expected.shape
    u = np.arange(w, dtype=float)
    du = np.minimum(u + 0.5, w - 0.5 - u)
    if np.allclose(g, np.broadcast_to(du, (h, w))):
        return "you only used the distance to the left and right borders; take the minimum with the vertical distance too."
    return "w(u, v) = min(u + 1/2, W - 1/2 - u, v + 1/2, H - 1/2 - v): the distance to the nearest border."


register_exercise(Exercise(
    name="feather_weights",
    lesson="09",
    reference=st.feather_weights,
    cases=_feather_cases,
    compare=same_array(atol=1e-9),
    diagnose=_feather_diagnosis,
    wrong_variants=(
        (lambda shape: st.feather_weights(shape) - 0.5, "half a pixel"),
        (lambda shape: np.broadcast_to(np.minimum(np.arange(shape[1]) + 0.5, shape[1] - 0.5 - np.arange(shape[1])),
                                       tuple(shape)).copy(), "vertical"),
    ),
))
