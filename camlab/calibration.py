r"""Camera calibration: Zhang's method stage by stage, refined by Levenberg-Marquardt.

A flat chessboard with known square size is photographed in several orientations. Each
view gives a homography :math:`H = \lambda K [r_1\ r_2\ t]` from the board plane (Z = 0)
to the image (:func:`camlab.homography.pose_homography`). Zhang (2000) turns those into
the camera:

1. **detect** the inner corners in every image (:func:`find_chessboard`, OpenCV finds them,
   camlab normalises shapes and says why a detection failed);
2. **homographies** board -> image per view (:func:`view_homographies`, the normalised DLT
   of :mod:`camlab.homography`);
3. **constraints** on :math:`B = K^{-\top} K^{-1}`: :math:`r_1 \perp r_2` and
   :math:`\|r_1\| = \|r_2\|` give two linear equations :math:`v_{12}^\top b = 0`,
   :math:`(v_{11} - v_{22})^\top b = 0` per view (:func:`zhang_v`, :func:`zhang_constraints`);
4. **K in closed form** from the null vector b (:func:`intrinsics_from_b`,
   :func:`intrinsics_from_homographies`);
5. **poses** :math:`r_1 = \lambda K^{-1} h_1` ... made a true rotation by the nearest
   rotation (:func:`extrinsics_from_homography`, :func:`nearest_rotation`);
6. **radial distortion**, linear least squares for k1, k2 (:func:`initial_radial_distortion`);
7. **refinement** of everything by :func:`camlab.optimize.levenberg_marquardt` on the
   reprojection error with an analytic, per-view block Jacobian (:func:`calibrate_camera`).

Then judge the result (:func:`coach`), undistort images (:func:`undistort`,
:func:`optimal_new_camera_matrix`) and save it for OpenCV (:func:`save_calibration`).

Conventions (docs/conventions.md): pixels (u, v) = (column, row), origin at the centre of
the top-left pixel; ``X_cam = R X_board + t`` (cam_from_world); rotations as axis-angle
``rvec`` (cv2.Rodrigues); ``dist = (k1, k2, p1, p2, k3)`` in OpenCV's order
(:mod:`camlab.distortion`); board points in metres. See lesson 08.
"""
from __future__ import annotations

import glob as _glob
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple, Sequence

import numpy as np
from numpy.typing import ArrayLike

from ._validate import CamlabInputError, ConvergenceError, DegenerateError, as_points, check_finite, check_intrinsics, check_positive, check_size
from .camera import axis_angle_from_rotation, rotation_from_axis_angle
from .distortion import as_dist, distort_points, distortion_jacobian, undistort_image, undistort_points
from .homography import estimate_homography
from .optimize import LMResult, levenberg_marquardt

__all__ = [
    "PARAM_NAMES", "CalibrationResult", "ChessboardDetection", "CoachReport", "ImageCalibration",
    "SyntheticSet", "board_points", "calibrate_camera", "calibrate_from_images", "coach",
    "extrinsics_from_homography", "find_chessboard", "initial_radial_distortion", "intrinsics_from_b",
    "intrinsics_from_homographies", "load_calibration", "make_synthetic_views", "nearest_rotation",
    "optimal_new_camera_matrix", "parse_pattern", "projection_uncertainty", "reproject",
    "save_calibration", "undistort", "undistortion_tradeoff", "view_homographies", "zhang_constraints",
    "zhang_v",
]

PARAM_NAMES = ("fx", "fy", "cx", "cy", "skew", "k1", "k2", "p1", "p2", "k3")
"""The global (per-camera) parameters in the order camlab refines them."""


# ======================================================================== 1. detection

class ChessboardDetection(NamedTuple):
    """The outcome of :func:`find_chessboard`.

    ``found``; ``corners`` (N, 2) sub-pixel (u, v) in row-major order, first corner nearest
    the image's top-left, or None; ``reason`` a plain-language explanation when not found
    ("" when found); ``pattern_size`` (cols, rows) inner corners asked for.
    """

    found: bool
    corners: np.ndarray | None
    reason: str
    pattern_size: tuple[int, int]


def parse_pattern(pattern: str | Sequence[int]) -> tuple[int, int]:
    """``"9x6"`` or ``(9, 6)`` -> ``(9, 6)`` inner corners (columns, rows).

    >>> parse_pattern("9x6")
    (9, 6)
    """
    try:
        if isinstance(pattern, str):
            cols, rows = (int(p) for p in pattern.lower().replace("*", "x").split("x"))
        else:
            cols, rows = (int(p) for p in pattern)
    except (TypeError, ValueError):
        raise CamlabInputError(
            f"pattern_size: expected inner corners as (cols, rows) or 'COLSxROWS' like '9x6', got {pattern!r}"
        ) from None
    if cols < 2 or rows < 2:
        raise CamlabInputError(f"pattern_size: expected at least 2 x 2 inner corners, got {pattern!r}")
    return cols, rows


def board_points(pattern_size: Sequence[int] | str, square_size: float) -> np.ndarray:
    """The (N, 3) model points of a chessboard's inner corners in the board frame, metres.

    Row-major like OpenCV's corner order: ``(i * square, j * square, 0)`` for row j, column i,
    N = cols * rows.

    >>> board_points((3, 2), 0.5)
    array([[0. , 0. , 0. ],
           [0.5, 0. , 0. ],
           [1. , 0. , 0. ],
           [0. , 0.5, 0. ],
           [0.5, 0.5, 0. ],
           [1. , 0.5, 0. ]])
    """
    cols, rows = parse_pattern(pattern_size)
    s = check_positive(square_size, "square_size", "metres")
    j, i = np.divmod(np.arange(cols * rows), cols)
    return np.column_stack([i * s, j * s, np.zeros(cols * rows)])


def _grey(image: ArrayLike, name: str = "image") -> np.ndarray:
    import cv2

    img = np.asarray(image)
    if img.ndim == 3 and img.shape[2] in (3, 4):
        img = cv2.cvtColor(img, cv2.COLOR_RGB2GRAY if img.shape[2] == 3 else cv2.COLOR_RGBA2GRAY)
    if img.ndim != 2 or img.size == 0:
        raise CamlabInputError(f"{name}: expected an (H, W) grey or (H, W, 3) colour image, got shape {img.shape}")
    if img.dtype != np.uint8:
        f = img.astype(float)
        if not np.isfinite(f).all():
            raise CamlabInputError(f"{name}: the image holds NaN or inf pixels")
        lo, hi = f.min(), f.max()
        img = np.zeros(f.shape, np.uint8) if hi <= lo else np.round(255 * (f - lo) / (hi - lo)).astype(np.uint8)
    return img


def _detect(img: np.ndarray, pattern: tuple[int, int]) -> np.ndarray | None:
    """OpenCV's classic detector + cornerSubPix, normalised to (N, 2) in a fixed order."""
    import cv2

    flags = cv2.CALIB_CB_ADAPTIVE_THRESH | cv2.CALIB_CB_NORMALIZE_IMAGE | cv2.CALIB_CB_FAST_CHECK
    ok, corners = cv2.findChessboardCorners(img, pattern, flags=flags)
    if not ok or corners is None:
        return None
    c = np.asarray(corners, dtype=np.float32).reshape(-1, 2)  # (N, 1, 2) in OpenCV 4, (N, 2) in 5
    spacing = np.min(np.linalg.norm(np.diff(c.reshape(pattern[1], pattern[0], 2), axis=1), axis=2))
    half = int(np.clip(0.4 * spacing, 2, 5))  # the search window must stay inside one square
    crit = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_COUNT, 50, 1e-4)
    c = cv2.cornerSubPix(img, c.reshape(-1, 1, 2), (half, half), (-1, -1), crit)
    c = np.asarray(c, dtype=float).reshape(-1, 2)
    if c[0].sum() > c[-1].sum():  # a fixed order: start at the corner nearer the image's top-left
        c = c[::-1].copy()
    return c


def _edge_width(img: np.ndarray) -> float:
    """Typical width in pixels of the strongest edges: intensity range / steepest gradients."""
    f = img.astype(np.float32)
    gy, gx = np.gradient(f)
    g = np.hypot(gx, gy)
    contrast = np.percentile(f, 99) - np.percentile(f, 1)
    steep = np.percentile(g, 99.7)
    return float(contrast / max(steep, 1e-6))


def find_chessboard(image: ArrayLike, pattern_size: Sequence[int] | str) -> ChessboardDetection:
    """Find a chessboard's inner corners with sub-pixel accuracy, or say why not.

    Parameters
    ----------
    image : (H, W) or (H, W, 3) array_like
        The photo; any dtype (non-uint8 images are stretched to 0..255).
    pattern_size : (cols, rows) or "COLSxROWS"
        *Inner* corners (where four squares meet): a board of 10 x 7 squares has 9 x 6.

    Returns
    -------
    ChessboardDetection
        ``corners`` (cols * rows, 2) pixels (u, v), row by row, starting at the end of the
        board nearer the image's top-left; ``reason`` explains a failure: no contrast,
        squares counted instead of inner corners, board cut off by the image border,
        partly hidden or the wrong size, too blurry.

    Notes
    -----
    ``cv2.findChessboardCorners`` finds the board and ``cv2.cornerSubPix`` refines each
    corner to the saddle point of the intensity (window at most 11 x 11 pixels, smaller
    for small boards). OpenCV 4 returns (N, 1, 2), OpenCV 5 (N, 2); both become (N, 2).
    """
    pattern = parse_pattern(pattern_size)
    img = _grey(image)
    corners = _detect(img, pattern)
    if corners is not None:
        return ChessboardDetection(True, corners, "", pattern)
    return ChessboardDetection(False, None, _why_not_found(img, pattern), pattern)


def _why_not_found(img: np.ndarray, pattern: tuple[int, int]) -> str:
    cols, rows = pattern
    lo, hi = np.percentile(img, [1, 99])
    if hi - lo < 25:
        return (f"no chessboard found: the image has almost no contrast (grey levels {lo:.0f} to {hi:.0f}); "
                f"check exposure and that the board is in view")
    if cols > 2 and rows > 2 and _detect(img, (cols - 1, rows - 1)) is not None:
        return (f"wrong pattern size: a board with {cols - 1} x {rows - 1} inner corners was found; "
                f"pattern_size counts inner corners (where four squares meet), not squares: "
                f"use --pattern {cols - 1}x{rows - 1}")
    # OpenCV's "SB" detector with CALIB_CB_LARGER also reports partial boards
    import cv2

    h, w = img.shape
    ok, part, meta = cv2.findChessboardCornersSBWithMeta(img, (3, 3), cv2.CALIB_CB_LARGER)
    if ok and part is not None:
        part = np.asarray(part, dtype=float).reshape(-1, 2)
        spacing = np.median(np.linalg.norm(np.diff(part[:2], axis=0), axis=1))
        margin = min(part[:, 0].min(), part[:, 1].min(), w - 1 - part[:, 0].max(), h - 1 - part[:, 1].max())
        if len(part) < cols * rows and margin < 1.5 * spacing:  # fewer corners, and they reach the border
            return (f"board cut off: the chessboard runs into the image border, so not all {cols} x {rows} inner "
                    f"corners are visible; keep the whole board (with its white border) in view")
        return (f"a chessboard is visible but its {cols} x {rows} inner corners could not all be matched: check "
                f"--pattern (count inner corners, where four squares meet), glare and anything covering the board")
    width = _edge_width(img)
    if width > 4.0:
        return (f"no chessboard found: the image looks too blurry (edges about {width:.0f} px wide); "
                f"focus on the board and hold the camera still")
    return (f"no {cols} x {rows} chessboard found: check --pattern (inner corners, e.g. 9x6 for a board of "
            f"10 x 7 squares), that the whole board is visible with a white border, and that it is in focus")


# ======================================================================== 2-6. Zhang's stages

def _check_views(object_points, image_points, min_views: int = 1):
    """Lists of (N_v, 3) and (N_v, 2) float arrays, validated view by view."""
    if isinstance(image_points, np.ndarray) and image_points.ndim == 2:
        image_points = [image_points]
    try:
        n = len(image_points)
    except TypeError:
        raise CamlabInputError(
            f"image_points: expected a list of (N, 2) arrays, one per view, got {type(image_points).__name__}"
        ) from None
    if n < min_views:
        raise CamlabInputError(
            f"image_points: expected at least {min_views} views, got {n}; take more photos of the board "
            f"in different orientations"
        )
    obj = np.asarray(object_points, dtype=float) if not isinstance(object_points, (list, tuple)) else None
    if obj is not None and obj.ndim == 2:
        objs = [obj] * n  # one board for all views
    else:
        objs = list(object_points)
        if len(objs) != n:
            raise CamlabInputError(
                f"object_points: expected one (N, 3) array per view (or one for all), got {len(objs)} "
                f"for {n} views"
            )
    out_obj, out_img = [], []
    for v, (o, p) in enumerate(zip(objs, image_points)):
        o = as_points(np.asarray(o, dtype=float).reshape(-1, 3) if np.size(o) % 3 == 0 else o, 3,
                      f"object_points[{v}]", min_count=4).array
        p = as_points(np.asarray(p, dtype=float).reshape(-1, 2) if np.size(p) % 2 == 0 else p, 2,
                      f"image_points[{v}]", min_count=4, finite=False).array
        if len(o) != len(p):
            raise CamlabInputError(
                f"image_points[{v}]: expected {len(o)} points like object_points[{v}], got {len(p)}"
            )
        if not np.isfinite(p).all():
            bad = int(np.argwhere(~np.isfinite(p).all(axis=1))[0, 0])
            raise CamlabInputError(
                f"image_points[{v}]: corner {bad} is NaN or inf ({int((~np.isfinite(p)).any(axis=1).sum())} "
                f"non-finite corners in this view); drop the view or the bad corners"
            )
        out_obj.append(o)
        out_img.append(p)
    return out_obj, out_img


def _planar_xy(obj: np.ndarray, v: int) -> np.ndarray:
    scale = max(np.abs(obj[:, :2]).max(), 1e-300)
    if np.abs(obj[:, 2]).max() > 1e-9 * scale:
        raise CamlabInputError(
            f"object_points[{v}]: Zhang's method needs a flat target with Z = 0 (a chessboard in its own frame), "
            f"got Z up to {np.abs(obj[:, 2]).max():.3g}; for a 3-D target use "
            f"camlab.camera.estimate_projection_matrix (DLT resectioning)"
        )
    return obj[:, :2]


def view_homographies(object_points: Sequence[ArrayLike] | ArrayLike,
                      image_points: Sequence[ArrayLike]) -> np.ndarray:
    """(V, 3, 3) homographies board plane (X, Y) -> image (u, v), one per view (normalised DLT).

    Uses :func:`camlab.homography.estimate_homography` (Hartley normalisation); each H is
    scaled so H[2, 2] = 1.
    """
    objs, imgs = _check_views(object_points, image_points)
    return np.stack([estimate_homography(_planar_xy(o, v), p) for v, (o, p) in enumerate(zip(objs, imgs))])


def zhang_v(H: ArrayLike, i: int, j: int) -> np.ndarray:
    r"""Zhang's vector :math:`v_{ij}` with :math:`h_i^\top B h_j = v_{ij}^\top b`.

    With :math:`h_i` the i-th column of H (i, j in 0, 1, 2) and
    :math:`b = (B_{11}, B_{12}, B_{22}, B_{13}, B_{23}, B_{33})` the six distinct entries of
    the symmetric :math:`B = K^{-\top} K^{-1}`:

    .. math::
        v_{ij} = (h_{i1} h_{j1},\ h_{i1} h_{j2} + h_{i2} h_{j1},\ h_{i2} h_{j2},\
                  h_{i3} h_{j1} + h_{i1} h_{j3},\ h_{i3} h_{j2} + h_{i2} h_{j3},\ h_{i3} h_{j3})

    >>> zhang_v(np.eye(3), 0, 0)
    array([1., 0., 0., 0., 0., 0.])
    """
    Hm = np.asarray(H, dtype=float)
    if Hm.shape != (3, 3):
        raise CamlabInputError(f"H: expected a (3, 3) homography, got shape {Hm.shape}")
    a, c = Hm[:, i], Hm[:, j]
    return np.array([a[0] * c[0], a[0] * c[1] + a[1] * c[0], a[1] * c[1],
                     a[2] * c[0] + a[0] * c[2], a[2] * c[1] + a[1] * c[2], a[2] * c[2]])


def zhang_constraints(H: ArrayLike) -> np.ndarray:
    r"""The (2, 6) rows one view adds to :math:`V b = 0`.

    :math:`H = \lambda K [r_1\ r_2\ t]`, so :math:`r_k = \lambda^{-1} K^{-1} h_k`; the
    columns of a rotation are orthonormal, so

    .. math::
        h_1^\top B h_2 = 0 \;\Rightarrow\; v_{12}^\top b = 0, \qquad
        h_1^\top B h_1 = h_2^\top B h_2 \;\Rightarrow\; (v_{11} - v_{22})^\top b = 0 .

    (In 0-based column indices: ``zhang_v(H, 0, 1)`` and ``zhang_v(H, 0, 0) - zhang_v(H, 1, 1)``.)
    """
    return np.stack([zhang_v(H, 0, 1), zhang_v(H, 0, 0) - zhang_v(H, 1, 1)])


def intrinsics_from_b(b: ArrayLike) -> np.ndarray:
    r"""K from :math:`b \propto (B_{11}, B_{12}, B_{22}, B_{13}, B_{23}, B_{33})` in closed form.

    Zhang (2000), appendix B, with :math:`B = \lambda K^{-\top} K^{-1}`:

    .. math::
        c_y &= (B_{12} B_{13} - B_{11} B_{23}) / (B_{11} B_{22} - B_{12}^2) \\
        \lambda &= B_{33} - [B_{13}^2 + c_y (B_{12} B_{13} - B_{11} B_{23})] / B_{11} \\
        f_x &= \sqrt{\lambda / B_{11}}, \qquad
        f_y = \sqrt{\lambda B_{11} / (B_{11} B_{22} - B_{12}^2)} \\
        s &= -B_{12} f_x^2 f_y / \lambda, \qquad
        c_x = s\, c_y / f_y - B_{13} f_x^2 / \lambda

    b is known only up to scale and sign; the sign is chosen to make B positive definite.

    Raises
    ------
    DegenerateError
        If no sign of b gives a positive definite B (the views do not determine K).
    """
    bv = np.asarray(b, dtype=float).ravel()
    if bv.shape != (6,) or not np.isfinite(bv).all():
        raise CamlabInputError(f"b: expected 6 finite numbers (B11, B12, B22, B13, B23, B33), got {np.shape(b)}")
    if bv[0] < 0:
        bv = -bv
    B11, B12, B22, B13, B23, B33 = bv
    den = B11 * B22 - B12 * B12
    if B11 <= 0 or den <= 0:
        raise DegenerateError(
            "intrinsics_from_b: B = K^-T K^-1 came out indefinite, so the views do not determine K; this "
            "happens when the board has nearly the same orientation in every view (for instance always "
            "parallel to the image plane): tilt it by 20-45 degrees in different directions"
        )
    cy = (B12 * B13 - B11 * B23) / den
    lam = B33 - (B13 * B13 + cy * (B12 * B13 - B11 * B23)) / B11
    if lam / B11 <= 0:
        raise DegenerateError(
            "intrinsics_from_b: the closed-form focal length is imaginary (lambda / B11 < 0): the views do "
            "not determine K; the board has nearly the same orientation in every view (e.g. parallel to the image "
            "plane): use more views with the board tilted by 20-45 degrees in different directions"
        )
    fx = np.sqrt(lam / B11)
    fy = np.sqrt(lam * B11 / den)
    s = -B12 * fx * fx * fy / lam
    cx = s * cy / fy - B13 * fx * fx / lam
    return np.array([[fx, s, cx], [0.0, fy, cy], [0.0, 0.0, 1.0]])


def intrinsics_from_homographies(homographies: ArrayLike, *, skew: bool = False,
                                 image_size: Sequence[int] | None = None) -> np.ndarray:
    r"""K in closed form from V >= 2 view homographies (>= 3 with ``skew=True``).

    Stacks :func:`zhang_constraints` into V (2V x 6), takes b as the right singular vector
    with the smallest singular value and applies :func:`intrinsics_from_b`. With
    ``skew=False`` the column of :math:`B_{12}` is dropped (zero skew makes
    :math:`B_{12} = 0`), leaving 5 unknowns.

    For conditioning, the homographies are first expressed in pixels scaled to about
    [-1, 1] by :math:`T` (from ``image_size``, or from their own translations):
    :math:`T H = (T K) [r_1\ r_2\ t]`, so the method yields :math:`T K` and
    :math:`K = T^{-1} (T K)`.

    Raises
    ------
    DegenerateError
        Too few views, or a set that leaves b undetermined (all boards parallel).
    """
    Hs = np.asarray(homographies, dtype=float)
    if Hs.ndim != 3 or Hs.shape[1:] != (3, 3):
        raise CamlabInputError(f"homographies: expected (V, 3, 3), got shape {Hs.shape}")
    need = 3 if skew else 2
    if len(Hs) < need:
        raise DegenerateError(
            f"intrinsics_from_homographies: expected at least {need} views (each gives 2 equations on "
            f"{5 if skew else 4} unknowns), got {len(Hs)}; add views"
        )
    if image_size is not None:
        w, h = (float(x) for x in image_size)
        c = np.array([(w - 1) / 2, (h - 1) / 2])
        sc = (w + h) / 4
    else:
        pts = Hs[:, :2, 2] / Hs[:, 2:, 2]
        c, sc = pts.mean(axis=0), max(np.abs(pts - pts.mean(axis=0)).max(), 1.0)
    T = np.array([[1 / sc, 0, -c[0] / sc], [0, 1 / sc, -c[1] / sc], [0, 0, 1]])
    Hn = T @ Hs
    Hn /= np.linalg.norm(Hn, axis=(1, 2), keepdims=True)
    V = np.concatenate([zhang_constraints(H) for H in Hn])
    cols = [0, 1, 2, 3, 4, 5] if skew else [0, 2, 3, 4, 5]
    _, sv, Vt = np.linalg.svd(V[:, cols])
    if sv[-2] < 1e-3 * sv[0]:  # well-spread views: 0.03-0.2; all boards parallel: < 1e-4
        raise DegenerateError(
            f"intrinsics_from_homographies: the {len(Hs)} views do not fix K (V b = 0 has more than one "
            f"solution: singular values {sv[-2] / sv[0]:.1g} and {sv[-1] / sv[0]:.1g} of the largest); the board is at nearly the same orientation in every view, e.g. parallel to the "
            f"image plane: tilt it by 20-45 degrees in different directions"
        )
    b = np.zeros(6)
    b[cols] = Vt[-1]
    Kn = intrinsics_from_b(b)
    K = np.linalg.solve(T, Kn)
    K = K / K[2, 2]
    K[1, 0] = K[2, 0] = K[2, 1] = 0.0
    return K


def nearest_rotation(M: ArrayLike) -> np.ndarray:
    r"""The rotation closest to M in the Frobenius norm: :math:`U \operatorname{diag}(1, 1, \det UV^\top) V^\top`.

    With the SVD :math:`M = U \Sigma V^\top`, :math:`\min_R \|R - M\|_F` over rotations is
    solved by replacing the singular values with ones (Zhang 2000, appendix C); the last
    sign keeps :math:`\det R = +1`.

    >>> np.round(nearest_rotation(2 * np.eye(3)), 12) + 0.0
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    Mm = np.asarray(M, dtype=float)
    if Mm.shape != (3, 3) or not np.isfinite(Mm).all():
        raise CamlabInputError(f"M: expected a finite (3, 3) matrix, got shape {Mm.shape}")
    U, _, Vt = np.linalg.svd(Mm)
    D = np.diag([1.0, 1.0, np.sign(np.linalg.det(U @ Vt))])
    return U @ D @ Vt


def extrinsics_from_homography(K: ArrayLike, H: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    r"""A view's pose (R, t), cam_from_board, from K and its homography.

    :math:`K^{-1} H = \lambda [r_1\ r_2\ t]` with :math:`\lambda = 1 / \|K^{-1} h_1\|`
    (sign chosen so the board is in front, :math:`t_z > 0`), :math:`r_3 = r_1 \times r_2`.
    With noise :math:`[r_1\ r_2\ r_3]` is not orthonormal; :func:`nearest_rotation` fixes that.
    """
    Km = np.asarray(K, dtype=float)
    A = np.linalg.solve(Km, np.asarray(H, dtype=float))
    lam = 2.0 / (np.linalg.norm(A[:, 0]) + np.linalg.norm(A[:, 1]))
    if A[2, 2] * lam < 0:
        lam = -lam
    r1, r2, t = lam * A[:, 0], lam * A[:, 1], lam * A[:, 2]
    R = nearest_rotation(np.column_stack([r1, r2, np.cross(r1, r2)]))
    return R, t


def _normalised(K: np.ndarray, Xc: np.ndarray) -> np.ndarray:
    return Xc[..., :2] / Xc[..., 2:3]


def _to_normalised(pix: np.ndarray, K: np.ndarray) -> np.ndarray:
    """Pixels (N, 2) -> normalised image coordinates: K^-1 [u, v, 1]."""
    return (np.column_stack([pix, np.ones(len(pix))]) @ np.linalg.inv(K).T)[:, :2]


def _from_normalised(x: np.ndarray, K: np.ndarray) -> np.ndarray:
    """Normalised image coordinates (N, 2) -> pixels: K [x, y, 1]."""
    return x @ K[:2, :2].T + K[:2, 2]


def initial_radial_distortion(K: ArrayLike, object_points, image_points, R: ArrayLike, t: ArrayLike) -> np.ndarray:
    r"""Linear least-squares (k1, k2) given K and every view's pose (Zhang 2000, section 3.3).

    With ideal normalised points :math:`x` (from K, R, t, no distortion), radius
    :math:`r^2 = x^2 + y^2` and ideal pixels :math:`(u, v)`, the radial model says the
    observed pixels are :math:`\breve u = u + (u - c_x)(k_1 r^2 + k_2 r^4)` (same for v):
    two linear equations in (k1, k2) per corner,

    .. math::
        \begin{pmatrix} (u - c_x) r^2 & (u - c_x) r^4 \\ (v - c_y) r^2 & (v - c_y) r^4 \end{pmatrix}
        \begin{pmatrix} k_1 \\ k_2 \end{pmatrix} = \begin{pmatrix} \breve u - u \\ \breve v - v \end{pmatrix}.

    Returns
    -------
    (2,) ndarray
        (k1, k2).
    """
    Km = np.asarray(K, dtype=float)
    objs, imgs = _check_views(object_points, image_points)
    Rs, ts = np.asarray(R, dtype=float).reshape(-1, 3, 3), np.asarray(t, dtype=float).reshape(-1, 3)
    rows, rhs = [], []
    for o, p, Rv, tv in zip(objs, imgs, Rs, ts):
        x = _normalised(Km, o @ Rv.T + tv)
        r2 = np.sum(x * x, axis=1)
        uv = x @ Km[:2, :2].T + Km[:2, 2]
        d = uv - Km[:2, 2]
        rows.append(np.stack([d * r2[:, None], d * (r2 * r2)[:, None]], axis=-1).reshape(-1, 2))
        rhs.append((p - uv).ravel())
    k, *_ = np.linalg.lstsq(np.concatenate(rows), np.concatenate(rhs), rcond=None)
    return k


# ======================================================================== 7. refinement

def _rotations_and_left_jacobians(rvecs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r"""Rotations :math:`R(r)` and left Jacobians :math:`J_l(r)` of V axis-angle vectors at once, (V, 3, 3) each.

    The batched form of :func:`camlab.camera.rotation_from_axis_angle` (Rodrigues,
    :math:`R = I + \frac{\sin\theta}{\theta}[r]_\times + \frac{1 - \cos\theta}{\theta^2}[r]_\times^2`),
    vectorised because the refinement evaluates every view's rotation at every iteration. The
    derivative of a rotated point is :math:`\partial (R(r) X) / \partial r = -[R X]_\times J_l(r)` with
    :math:`J_l = I + \frac{1 - \cos\theta}{\theta^2} [r]_\times + \frac{\theta - \sin\theta}{\theta^3} [r]_\times^2`.
    Near :math:`\theta = 0` the coefficients use their Taylor limits (1, 1/2, 1/6).
    """
    theta = np.linalg.norm(rvecs, axis=1)
    S = _skew(rvecs)
    S2 = S @ S
    small = theta < 1e-6
    th = np.where(small, 1.0, theta)
    a = np.where(small, 1.0 - theta**2 / 6, np.sin(th) / th)            # sin(t) / t
    b = np.where(small, 0.5 - theta**2 / 24, (1 - np.cos(th)) / th**2)  # (1 - cos t) / t^2
    c = np.where(small, 1.0 / 6 - theta**2 / 120, (th - np.sin(th)) / th**3)
    eye = np.eye(3)
    R = eye + a[:, None, None] * S + b[:, None, None] * S2
    Jl = eye + b[:, None, None] * S + c[:, None, None] * S2
    return R, Jl


def _skew(w: np.ndarray) -> np.ndarray:
    """[w]_x for (..., 3) vectors: (..., 3, 3)."""
    out = np.zeros(w.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2] = -w[..., 2], w[..., 1]
    out[..., 1, 0], out[..., 1, 2] = w[..., 2], -w[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -w[..., 1], w[..., 0]
    return out


def _project(g: np.ndarray, poses: np.ndarray, X: np.ndarray, jac: bool = False):
    r"""Project padded board points X (V, M, 3) with global parameters g (10,) and poses (V, 6).

    Returns uv (V, M, 2) and, with ``jac``, d uv / d g (V, M, 2, 10) and d uv / d pose
    (V, M, 2, 6) (pose = rvec, t). The chain rule, point by point:
    :math:`u = K_p\,\mathrm{distort}(\pi(R X + t))` with :math:`K_p = [[f_x, s], [0, f_y]]`.
    """
    fx, fy, cx, cy, s, k1, k2, p1, p2, k3 = g
    R, Jl = _rotations_and_left_jacobians(poses[:, :3])
    RX = np.einsum("vij,vmj->vmi", R, X)
    Xc = RX + poses[:, None, 3:]
    z = Xc[..., 2]
    x, y = Xc[..., 0] / z, Xc[..., 1] / z
    r2 = x * x + y * y
    radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3))
    xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)
    yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y
    uv = np.stack([fx * xd + s * yd + cx, fy * yd + cy], axis=-1)
    if not jac:
        return uv
    V, M = x.shape
    Jg = np.zeros((V, M, 2, 10))
    Jg[..., 0, 0], Jg[..., 0, 2], Jg[..., 0, 4] = xd, 1.0, yd
    Jg[..., 1, 1], Jg[..., 1, 3] = yd, 1.0
    r4 = r2 * r2
    dxd = np.stack([x * r2, x * r4, 2 * x * y, r2 + 2 * x * x, x * r4 * r2], axis=-1)  # d xd / d(k1 k2 p1 p2 k3)
    dyd = np.stack([y * r2, y * r4, r2 + 2 * y * y, 2 * x * y, y * r4 * r2], axis=-1)
    Jg[..., 0, 5:] = fx * dxd + s * dyd
    Jg[..., 1, 5:] = fy * dyd
    Jd = distortion_jacobian(np.stack([x, y], axis=-1).reshape(-1, 2), g[5:]).reshape(V, M, 2, 2)
    A = np.empty_like(Jd)  # d uv / d (x, y) = K_p @ Jd
    A[..., 0, :] = fx * Jd[..., 0, :] + s * Jd[..., 1, :]
    A[..., 1, :] = fy * Jd[..., 1, :]
    inv_z = 1.0 / z
    P = np.zeros((V, M, 2, 3))  # d (x, y) / d Xc
    P[..., 0, 0], P[..., 0, 2] = inv_z, -x * inv_z
    P[..., 1, 1], P[..., 1, 2] = inv_z, -y * inv_z
    dXc = A @ P  # (V, M, 2, 3): d uv / d Xc = d uv / d t
    dR = -_skew(RX) @ Jl[:, None]  # d (R X) / d rvec, (V, M, 3, 3)
    Jp = np.concatenate([dXc @ dR, dXc], axis=-1)
    return uv, Jg, Jp


class _BlockNormal:
    r"""The normal equations of calibration in block form.

    Parameters are ``[intrinsics (n_i), pose_1 (6), ..., pose_V (6)]``. Each view's pose only
    touches that view's residuals, so

    .. math::
        J^\top J = \begin{pmatrix} U & W_1 & \cdots & W_V \\ W_1^\top & V_1 & & \\
                   \vdots & & \ddots & \\ W_V^\top & & & V_V \end{pmatrix},\quad
        U = \sum_v J_{i,v}^\top J_{i,v},\ W_v = J_{i,v}^\top J_{p,v},\ V_v = J_{p,v}^\top J_{p,v}.

    The damped system is solved by eliminating the poses (the Schur complement): with
    :math:`V'_v = V_v + \mu\,\mathrm{diag}(V_v)`,
    :math:`S = U' - \sum_v W_v V_v'^{-1} W_v^\top`,
    :math:`S \delta_i = -g_i + \sum_v W_v V_v'^{-1} g_v` and then
    :math:`\delta_v = V_v'^{-1}(-g_v - W_v^\top \delta_i)`: one n_i x n_i solve and V 6 x 6
    inverses instead of a dense (n_i + 6V)-square solve.
    """

    def __init__(self, Ji: np.ndarray, Jp: np.ndarray, r: np.ndarray):
        JiT = Ji.transpose(0, 2, 1)
        self.U = (JiT @ Ji).sum(axis=0)
        self.W = JiT @ Jp
        self.Vb = Jp.transpose(0, 2, 1) @ Jp
        self.gi = np.einsum("vki,vk->i", Ji, r)
        self.gp = np.einsum("vki,vk->vi", Jp, r)

    def gradient(self) -> np.ndarray:
        return np.concatenate([self.gi, self.gp.ravel()])

    def diagonal(self) -> np.ndarray:
        return np.concatenate([np.diag(self.U), np.diagonal(self.Vb, axis1=1, axis2=2).ravel()])

    def schur(self, mu: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(S, V'^-1, W V'^-1) for damping mu."""
        dU = np.diag(self.U)
        Ud = self.U + mu * np.diag(np.maximum(dU, 1e-12 * max(dU.max(initial=0.0), 1e-300)))
        dV = np.diagonal(self.Vb, axis1=1, axis2=2)
        Vd = self.Vb + mu * dV[:, :, None] * np.eye(6)
        Vinv = np.linalg.inv(Vd)
        Y = self.W @ Vinv
        S = Ud - (Y @ self.W.transpose(0, 2, 1)).sum(axis=0)
        return S, Vinv, Y

    def solve(self, mu: float) -> np.ndarray:
        S, Vinv, Y = self.schur(mu)
        di = np.linalg.solve(S, -self.gi + np.einsum("vij,vj->i", Y, self.gp))
        dp = np.einsum("vij,vj->vi", Vinv, -self.gp - np.einsum("vij,i->vj", self.W, di))
        return np.concatenate([di, dp.ravel()])


class _Problem:
    """Packs the calibration unknowns into one vector and evaluates residuals and Jacobians."""

    def __init__(self, X: np.ndarray, obs: np.ndarray, mask: np.ndarray, g0: np.ndarray, free: np.ndarray):
        self.X, self.obs, self.mask = X, obs, mask
        self.g0, self.free = g0, free
        self.ni = int(free.sum())
        self.V = X.shape[0]
        self._last = None

    def pack(self, g: np.ndarray, poses: np.ndarray) -> np.ndarray:
        return np.concatenate([g[self.free], poses.ravel()])

    def unpack(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        g = self.g0.copy()
        g[self.free] = x[:self.ni]
        return g, x[self.ni:].reshape(self.V, 6)

    def _evaluate(self, x: np.ndarray):
        """Residuals and Jacobian blocks at x, computed together and kept for the next call.

        LM asks for r(x) at a trial point and then, if the step is accepted, for J(x) at the
        same point: one projection pass serves both.
        """
        if self._last is not None and np.array_equal(self._last[0], x):
            return self._last[1]
        g, poses = self.unpack(x)
        uv, Jg, Jp = _project(g, poses, self.X, jac=True)
        m = self.mask[..., None]
        V, M = self.mask.shape
        r = ((uv - self.obs) * m).ravel()
        J = ((Jg[..., self.free] * m[..., None]).reshape(V, 2 * M, self.ni), (Jp * m[..., None]).reshape(V, 2 * M, 6))
        self._last = (x.copy(), (r, J))
        return r, J

    def residuals(self, x: np.ndarray) -> np.ndarray:
        return self._evaluate(x)[0]

    def jacobian(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return self._evaluate(x)[1]

    def normal_equations(self, J, r: np.ndarray):
        A = _BlockNormal(J[0], J[1], r.reshape(self.V, -1))
        return A, A.gradient()


@dataclass(frozen=True, eq=False)
class CalibrationResult:
    r"""A calibrated camera and everything needed to judge it.

    Attributes
    ----------
    K : (3, 3) ndarray
        Intrinsics [[fx, skew, cx], [0, fy, cy], [0, 0, 1]], pixels.
    dist : (5,) ndarray
        (k1, k2, p1, p2, k3), OpenCV's order.
    rvecs, tvecs : (V, 3) ndarray
        Each view's pose, cam_from_board: axis-angle (radians) and translation (metres).
    rms : float
        :math:`\sqrt{\sum_i \|e_i\|^2 / N}` over all N corners, pixels: the number
        ``cv2.calibrateCamera`` returns. (The RMS per coordinate is ``rms / sqrt(2)``.)
    per_view_rms : (V,) ndarray
        The same per view.
    residuals : list of (N_v, 2) ndarray
        Observed minus reprojected corner, pixels, per view.
    std : dict
        Standard deviation of each refined global parameter (``PARAM_NAMES``; 0 for fixed
        ones) from :math:`\hat\sigma^2 (J^\top J)^{-1}` with
        :math:`\hat\sigma^2 = \sum r^2 / (2N - p)`, OpenCV's definition.
    covariance : (n_free, n_free) ndarray
        Covariance of the free global parameters ``free_params``.
    free_params : tuple of str
    image_size : (width, height)
    object_points, image_points : lists of (N_v, 3) and (N_v, 2) ndarrays, the data.
    cost_history : ndarray
        LM cost :math:`\tfrac12\|r\|^2` per iteration; ``rms_history`` the matching rms.
    iterations : int
    converged : bool
    initial : dict
        Zhang's closed-form stages: ``K``, ``dist``, ``homographies``, ``rvecs``, ``tvecs``.
    """

    K: np.ndarray
    dist: np.ndarray
    rvecs: np.ndarray
    tvecs: np.ndarray
    rms: float
    per_view_rms: np.ndarray
    residuals: list
    std: dict
    covariance: np.ndarray
    free_params: tuple
    image_size: tuple
    object_points: list
    image_points: list
    cost_history: np.ndarray
    iterations: int
    converged: bool
    initial: dict = field(default_factory=dict)

    @property
    def R(self) -> np.ndarray:
        """(V, 3, 3) rotations, cam_from_board."""
        return np.stack([rotation_from_axis_angle(r) for r in self.rvecs])

    @property
    def n_views(self) -> int:
        return len(self.rvecs)

    @property
    def n_points(self) -> int:
        return int(sum(len(p) for p in self.image_points))

    @property
    def rms_history(self) -> np.ndarray:
        """The rms (OpenCV's definition) after each LM iteration."""
        return np.sqrt(2 * self.cost_history / self.n_points)

    @property
    def intrinsics(self) -> dict:
        """{name: value} for every global parameter in ``PARAM_NAMES``."""
        vals = [self.K[0, 0], self.K[1, 1], self.K[0, 2], self.K[1, 2], self.K[0, 1], *self.dist]
        return dict(zip(PARAM_NAMES, (float(v) for v in vals)))

    def reprojected(self, view: int) -> np.ndarray:
        """(N_v, 2) pixels where the calibrated model puts view ``view``'s corners."""
        return reproject(self.object_points[view], self.K, self.dist, self.rvecs[view], self.tvecs[view])

    def summary(self) -> str:
        """A few lines for people: parameters with their standard deviations, rms."""
        p, s = self.intrinsics, self.std
        lines = [f"calibrated from {self.n_views} views, {self.n_points} corners; rms reprojection error "
                 f"{self.rms:.3f} px ({'converged' if self.converged else 'NOT converged'} in {self.iterations} "
                 f"LM iterations)"]
        lines.append("  " + "  ".join(f"{k} = {p[k]:.2f} ± {s[k]:.2f}" for k in ("fx", "fy", "cx", "cy")))
        if "skew" in self.free_params:
            lines.append(f"  skew = {p['skew']:.3f} ± {s['skew']:.3f}")
        lines.append("  " + "  ".join(f"{k} = {p[k]:+.4g} ± {s[k]:.2g}" for k in PARAM_NAMES[5:]))
        return "\n".join(lines)


def reproject(object_points: ArrayLike, K: ArrayLike, dist: ArrayLike | None, rvec: ArrayLike,
              tvec: ArrayLike) -> np.ndarray:
    """Project (N, 3) board points with intrinsics, distortion and an axis-angle pose (like cv2.projectPoints)."""
    X = as_points(object_points, 3, "object_points").array
    Km = np.asarray(K, dtype=float)
    g = np.array([Km[0, 0], Km[1, 1], Km[0, 2], Km[1, 2], Km[0, 1], *as_dist(dist)])
    pose = np.concatenate([np.ravel(rvec), np.ravel(tvec)]).astype(float)
    return _project(g, pose[None], X[None])[0]


def _rms(res: np.ndarray, mask: np.ndarray) -> tuple[float, np.ndarray]:
    sq = (np.sum(res * res, axis=-1) * mask)
    return float(np.sqrt(sq.sum() / mask.sum())), np.sqrt(sq.sum(axis=1) / mask.sum(axis=1))


def calibrate_camera(
    object_points: Sequence[ArrayLike] | ArrayLike,
    image_points: Sequence[ArrayLike],
    image_size: Sequence[int],
    *,
    skew: bool = False,
    fix: Sequence[str] = (),
    K_guess: ArrayLike | None = None,
    dist_guess: ArrayLike | None = None,
    pose_guess: ArrayLike | None = None,
    max_iter: int = 100,
) -> CalibrationResult:
    r"""Calibrate a camera from V >= 3 views of a flat target: Zhang's closed form, then LM.

    Parameters
    ----------
    object_points : (N, 3) array_like, or a list of V (N_v, 3)
        Board points in the board frame, metres, Z = 0 (:func:`board_points`); one array
        for all views or one per view.
    image_points : list of V (N_v, 2) array_like
        Detected corners (u, v) per view, pixels.
    image_size : (width, height)
        Pixels.
    skew : bool
        Also estimate the skew K[0, 1] (OpenCV never does; default False keeps it 0).
    fix : sequence of str
        Parameters held at their initial value: any of ``PARAM_NAMES`` (e.g.
        ``("k3",)`` like ``cv2.CALIB_FIX_K3``, ``("p1", "p2")`` like
        ``CALIB_ZERO_TANGENT_DIST``). Fixed coefficients stay at their start: 0, or ``dist_guess``.
    K_guess : (3, 3) array_like, optional
        Start from this K instead of Zhang's closed form.
    dist_guess : (5,) array_like, optional
        Start from these coefficients instead of the linear radial estimate (with ``K_guess``,
        a warm start from an earlier calibration converges in a few iterations).
    pose_guess : (V, 6) array_like, optional
        Start each view's pose from (rvec, tvec) instead of its homography; needs ``K_guess``.
        With all three guesses Zhang's closed form is skipped entirely (``initial`` is then
        empty).
    max_iter : int
        Most LM iterations.

    Returns
    -------
    CalibrationResult

    Raises
    ------
    CamlabInputError
        Fewer than 3 views, mismatched or non-finite points, non-planar targets, bad names.
    DegenerateError
        The views do not determine K (e.g. the board parallel to the image in every view).
    ConvergenceError
        The refinement failed to produce finite parameters.

    Notes
    -----
    The refinement minimises :math:`\sum_{v,i} \|x_{vi} - \pi(K, d, R_v, t_v, X_i)\|^2` over
    :math:`p = n_{free} + 6V` unknowns with :func:`camlab.optimize.levenberg_marquardt`;
    its analytic Jacobian has one dense block for the intrinsics and a 6-column block per
    view, and the damped normal equations are solved by eliminating the poses (Schur
    complement, see ``_BlockNormal``). Zhang's closed form starts close to the minimum, so
    the initial damping is small (``tau = 1e-5`` relative to diag(J^T J)): the distortion
    coefficients are strongly correlated, and a larger damping would crawl along that valley
    for many iterations before it shrank.
    """
    objs, imgs = _check_views(object_points, image_points, min_views=1)
    if len(imgs) < 3:
        raise CamlabInputError(
            f"image_points: expected at least 3 views of the board, got {len(imgs)}; "
            f"photograph it in more orientations"
        )
    w, h = check_size(image_size, "image_size")
    unknown = [f for f in fix if f not in PARAM_NAMES]
    if unknown:
        raise CamlabInputError(f"fix: unknown parameter(s) {unknown}; choose from {list(PARAM_NAMES)}")
    for v, o in enumerate(objs):
        _planar_xy(o, v)

    if pose_guess is not None and K_guess is None:
        raise CamlabInputError("pose_guess: pass K_guess too (the poses only make sense with a camera)")
    if K_guess is None:  # Zhang's closed form
        Hs = view_homographies(objs, imgs)
        K0 = intrinsics_from_homographies(Hs, skew=skew, image_size=(w, h))
    else:
        K0 = check_intrinsics(K_guess, "K_guess")
        Hs = view_homographies(objs, imgs) if pose_guess is None else None
    if not skew:
        K0[0, 1] = 0.0
    if pose_guess is None:
        poses0 = []
        for H in Hs:
            R, t = extrinsics_from_homography(K0, H)
            poses0.append(np.concatenate([axis_angle_from_rotation(R), t]))
        poses0 = np.array(poses0)
    else:
        poses0 = np.array(pose_guess, dtype=float)
        if poses0.shape != (len(imgs), 6) or not np.isfinite(poses0).all():
            raise CamlabInputError(f"pose_guess: expected ({len(imgs)}, 6) finite (rvec, tvec) rows, got {poses0.shape}")
    fixed = set(fix) | ({"skew"} if not skew else set())
    d0 = np.zeros(5)
    if dist_guess is not None:
        d0 = as_dist(dist_guess, "dist_guess")
    elif not {"k1", "k2"} & fixed:
        d0[:2] = initial_radial_distortion(K0, objs, imgs, [rotation_from_axis_angle(p[:3]) for p in poses0],
                                           poses0[:, 3:])
    elif "k1" not in fixed:
        d0[0] = initial_radial_distortion(K0, objs, imgs, [rotation_from_axis_angle(p[:3]) for p in poses0],
                                          poses0[:, 3:])[0]
    g0 = np.array([K0[0, 0], K0[1, 1], K0[0, 2], K0[1, 2], K0[0, 1], *d0])
    free = np.array([name not in fixed for name in PARAM_NAMES])

    # pad the views to one (V, M) array so everything is vectorised; padded rows have weight 0
    V, M = len(objs), max(len(o) for o in objs)
    X, obs, mask = np.zeros((V, M, 3)), np.zeros((V, M, 2)), np.zeros((V, M))
    for v, (o, p) in enumerate(zip(objs, imgs)):
        X[v, :len(o)], obs[v, :len(o)], mask[v, :len(o)] = o, p, 1.0
        X[v, len(o):] = o[0]
    prob = _Problem(X, obs, mask, g0, free)
    lm: LMResult = levenberg_marquardt(prob.residuals, prob.pack(g0, poses0), prob.jacobian,
                                       normal_equations=prob.normal_equations,
                                       damped_solve=lambda A, g, mu: A.solve(mu), max_iter=max_iter,
                                       ftol=1e-10, xtol=1e-10, gtol=1e-12, tau=1e-5)
    if not np.all(np.isfinite(lm.x)):
        raise ConvergenceError("calibrate_camera: the refinement produced non-finite parameters; check the data")
    g, poses = prob.unpack(lm.x)
    res = (obs - _project(g, poses, X)) * mask[..., None]
    rms, per_view = _rms(res, mask)
    # covariance of the free intrinsics: sigma^2 S^-1 with S the undamped Schur complement
    n_res, p = 2 * mask.sum(), prob.ni + 6 * V
    sigma2 = 2 * lm.cost / max(n_res - p, 1)
    S, _, _ = lm.normal[0].schur(0.0)
    try:
        cov = sigma2 * np.linalg.inv(S)
    except np.linalg.LinAlgError:
        cov = np.full((prob.ni, prob.ni), np.inf)
    std = dict.fromkeys(PARAM_NAMES, 0.0)
    for name, var in zip(np.array(PARAM_NAMES)[free], np.diag(cov)):
        std[str(name)] = float(np.sqrt(max(var, 0.0)))
    K = np.array([[g[0], g[4], g[2]], [0.0, g[1], g[3]], [0.0, 0.0, 1.0]])
    initial = {"K": K0, "dist": d0, "homographies": Hs, "rvecs": poses0[:, :3].copy(), "tvecs": poses0[:, 3:].copy(),
               "closed_form": K_guess is None}
    return CalibrationResult(
        K=K, dist=g[5:].copy(), rvecs=poses[:, :3].copy(), tvecs=poses[:, 3:].copy(), rms=rms,
        per_view_rms=per_view, residuals=[res[v, :len(o)] for v, o in enumerate(objs)], std=std,
        covariance=cov, free_params=tuple(str(n) for n in np.array(PARAM_NAMES)[free]), image_size=(w, h),
        object_points=objs, image_points=imgs, cost_history=lm.cost_history, iterations=lm.iterations,
        converged=lm.converged, initial=initial,
    )


# ======================================================================== images -> calibration

class ImageCalibration(NamedTuple):
    """The outcome of :func:`calibrate_from_images`.

    ``result`` the :class:`CalibrationResult` over the good views; ``names`` every input's
    name (file path or ``image[i]``); ``used`` the indices that went into ``result`` (view v
    of ``result`` is input ``used[v]``); ``failed`` {index: reason} for the rest;
    ``detections`` (N, 2) corners or None per input.
    """

    result: CalibrationResult
    names: list
    used: list
    failed: dict
    detections: list

    def report(self) -> str:
        """Which images were used, which failed and why."""
        lines = [f"{len(self.used)} of {len(self.names)} images used"]
        for i, why in sorted(self.failed.items()):
            lines.append(f"  skipped {self.names[i]}: {why}")
        return "\n".join(lines)


def _load_images(images_or_paths) -> tuple[list, list, dict]:
    """Images and names; unreadable files become failures."""
    import cv2

    if isinstance(images_or_paths, (str, os.PathLike)):
        pattern = str(images_or_paths)
        paths = sorted(_glob.glob(pattern)) if any(ch in pattern for ch in "*?[") else [pattern]
        if not paths:
            raise CamlabInputError(f"images_or_paths: no files match {pattern!r}; check the path and quote the pattern")
        images_or_paths = paths
    items = list(images_or_paths)
    if not items:
        raise CamlabInputError("images_or_paths: expected images or file paths, got an empty list")
    images, names, failed = [], [], {}
    for i, item in enumerate(items):
        if isinstance(item, (str, os.PathLike)):
            names.append(str(item))
            img = cv2.imread(str(item), cv2.IMREAD_GRAYSCALE) if Path(item).is_file() else None
            if img is None:
                failed[i] = "could not read the file (missing, or not an image)"
            images.append(img)
        else:
            names.append(f"image[{i}]")
            images.append(np.asarray(item))
    return images, names, failed


def calibrate_from_images(images_or_paths, pattern_size: Sequence[int] | str, square_size: float,
                          **kwargs: Any) -> ImageCalibration:
    """Detect the chessboard in every image, report failures, calibrate from the rest.

    Parameters
    ----------
    images_or_paths : sequence of images or paths, or a glob pattern like ``"photos/*.png"``
    pattern_size : (cols, rows) or "COLSxROWS"
        Inner corners.
    square_size : float
        Side of one square, metres (sets the units of the translations).
    **kwargs
        Passed to :func:`calibrate_camera` (``skew``, ``fix``, ...).

    Returns
    -------
    ImageCalibration

    Raises
    ------
    CamlabInputError
        Fewer than 3 images with a detected board (the message lists each failure).
    """
    pattern = parse_pattern(pattern_size)
    obj = board_points(pattern, square_size)
    images, names, failed = _load_images(images_or_paths)
    sizes = {}
    for i, img in enumerate(images):
        if i not in failed:
            try:
                g = _grey(img, f"images[{i}]")
                images[i] = g
                sizes.setdefault(g.shape[::-1], []).append(i)
            except CamlabInputError as exc:
                failed[i] = str(exc)
    size = max(sizes, key=lambda s: len(sizes[s])) if sizes else None
    for s, idx in sizes.items():
        if s != size:
            for i in idx:
                failed[i] = (f"image size {s[0]} x {s[1]} differs from the other images' {size[0]} x {size[1]}; "
                             f"calibrate each camera/resolution separately")
    detections: list = [None] * len(images)
    for i, img in enumerate(images):
        if i in failed:
            continue
        det = find_chessboard(img, pattern)
        if det.found:
            detections[i] = det.corners
        else:
            failed[i] = det.reason
    used = [i for i in range(len(images)) if detections[i] is not None]
    if len(used) < 3:
        why = "\n".join(f"  {names[i]}: {r}" for i, r in sorted(failed.items()))
        raise CamlabInputError(
            f"calibrate_from_images: need at least 3 images with the board detected, got {len(used)} of "
            f"{len(images)}:\n{why}"
        )
    result = calibrate_camera(obj, [detections[i] for i in used], size, **kwargs)
    return ImageCalibration(result, names, used, dict(sorted(failed.items())), detections)


# ======================================================================== quality coach

def projection_uncertainty(result: CalibrationResult, step: int = 20) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r"""How uncertain the calibrated projection is across the image (pixels, 1 sigma).

    For a grid of pixels, take the ray the calibrated camera assigns to each, and ask how
    far its projection would move if the intrinsics and distortion varied within their
    covariance :math:`\Sigma`: with :math:`J_g` = d pixel / d (free global parameters) at that
    ray (the same analytic Jacobian as the refinement), the pixel covariance is
    :math:`J_g \Sigma J_g^\top`; we report the square root of its largest eigenvalue.

    Returns
    -------
    (us, vs, sigma) with ``us`` (W',), ``vs`` (H',) grid coordinates and ``sigma`` (H', W').
    """
    w, h = result.image_size
    us = np.arange(step / 2, w, step, dtype=float)
    vs = np.arange(step / 2, h, step, dtype=float)
    U, Vv = np.meshgrid(us, vs)
    pix = np.column_stack([U.ravel(), Vv.ravel()])
    K = result.K
    xd = _to_normalised(pix, K)
    try:
        x = undistort_points(xd, result.dist)
    except ConvergenceError:
        x = xd
    Xc = np.column_stack([x, np.ones(len(x))])
    g = np.array([K[0, 0], K[1, 1], K[0, 2], K[1, 2], K[0, 1], *result.dist])
    _, Jg, _ = _project(g, np.zeros((1, 6)), Xc[None], jac=True)
    free = np.array([n in result.free_params for n in PARAM_NAMES])
    J = Jg[0][..., free]  # (N, 2, n_free)
    C = J @ result.covariance @ J.transpose(0, 2, 1)
    sigma = np.sqrt(np.maximum(np.linalg.eigvalsh(C)[:, -1], 0.0))
    return us, vs, sigma.reshape(U.shape)


class CoachReport(NamedTuple):
    """The quality coach's verdict on a calibration (see :func:`coach`).

    ``coverage`` (rows, cols) fraction of grid cells of the image with at least one corner
    (``coverage_grid`` holds the counts); ``worst_views`` view indices, worst first, with
    ``error_ratio`` each view's rms over the median; ``relative_std`` {param: std / |value|}
    for fx, fy and std in pixels for cx, cy; ``tilt_degrees`` each view's angle between the
    board normal and the optical axis; ``uncertainty`` max projection sigma over the image (px);
    ``advice`` plain-language sentences, most important first.
    """

    coverage: float
    coverage_grid: np.ndarray
    worst_views: list
    error_ratio: np.ndarray
    relative_std: dict
    tilt_degrees: np.ndarray
    uncertainty: float
    advice: list

    def text(self) -> str:
        return "\n".join(f"- {a}" for a in self.advice)


def coach(result: CalibrationResult, grid: tuple[int, int] = (4, 6)) -> CoachReport:
    """Judge a calibration and give plain-language advice.

    Checks: corner coverage of the image (edges and corners are where distortion is
    largest, so they must be sampled), views whose rms is >= 2x the median (bad detection
    or blur), the spread of board tilts (Zhang needs tilted views; tilts under about 10
    degrees add little), parameter uncertainties, the overall rms, the number of views, and
    whether the optimiser converged.

    Parameters
    ----------
    result : CalibrationResult
    grid : (rows, cols)
        Cells for the coverage check.
    """
    w, h = result.image_size
    rows, cols = grid
    pts = np.concatenate(result.image_points)
    ci = np.clip((pts[:, 0] / w * cols).astype(int), 0, cols - 1)
    ri = np.clip((pts[:, 1] / h * rows).astype(int), 0, rows - 1)
    counts = np.zeros((rows, cols), int)
    np.add.at(counts, (ri, ci), 1)
    covered = counts > 0
    coverage = float(covered.mean())
    med = float(np.median(result.per_view_rms))
    ratio = result.per_view_rms / max(med, 1e-12)
    worst = [int(i) for i in np.argsort(-result.per_view_rms)]
    normals = result.R[:, :, 2]
    tilt = np.degrees(np.arccos(np.clip(np.abs(normals[:, 2]), 0, 1)))
    p = result.intrinsics
    rel = {"fx": result.std["fx"] / abs(p["fx"]), "fy": result.std["fy"] / abs(p["fy"]),
           "cx": result.std["cx"], "cy": result.std["cy"]}
    _, _, sig = projection_uncertainty(result, step=max(8, min(w, h) // 12))
    advice = []
    if not result.converged:
        advice.append("the optimiser did not converge: the result may be poor; add views or check the detections")
    for v in worst:
        if ratio[v] >= 2.0 and result.per_view_rms[v] > 0.1:
            advice.append(f"view {v} has {ratio[v]:.1f}x the median error ({result.per_view_rms[v]:.2f} px vs "
                          f"{med:.2f} px): check its focus and detection, or drop it")
    regions = {"left edge": covered[:, 0], "right edge": covered[:, -1], "top edge": covered[0, :],
               "bottom edge": covered[-1, :]}
    for name, cells in regions.items():
        if not cells.any():
            advice.append(f"no corners near the {name}: add views with the board there")
        elif cells.mean() < 0.5:
            advice.append(f"few corners near the {name}: add views with the board there")
    for name, cell in {"top-left": covered[0, 0], "top-right": covered[0, -1], "bottom-left": covered[-1, 0],
                       "bottom-right": covered[-1, -1]}.items():
        if not cell:
            advice.append(f"no corners in the {name} corner of the image, where distortion is strongest: "
                          f"add a view with the board there")
    if np.ptp(tilt) < 10 or tilt.max() < 15:
        advice.append(f"the board tilts are all similar ({tilt.min():.0f}-{tilt.max():.0f} degrees): tilt it "
                      f"by 20-45 degrees towards different sides for a better focal length")
    if result.n_views < 10:
        advice.append(f"only {result.n_views} views: 10-20 give a more stable result")
    if rel["fx"] > 0.01 or rel["fy"] > 0.01:
        advice.append(f"the focal length is uncertain (±{100 * max(rel['fx'], rel['fy']):.1f}%): add tilted views")
    if max(rel["cx"], rel["cy"]) > 5:
        advice.append(f"the principal point is uncertain (±{max(rel['cx'], rel['cy']):.1f} px): add views "
                      f"tilted in different directions and near the image corners")
    if result.rms > 1.0:
        advice.append(f"the rms error is high ({result.rms:.2f} px): check for motion blur, a non-flat board, "
                      f"or the wrong pattern size")
    if not advice:
        advice.append(f"looks good: rms {result.rms:.2f} px, coverage {100 * coverage:.0f}% of the image, "
                      f"projection uncertainty below {sig.max():.2f} px everywhere")
    return CoachReport(coverage, counts, worst, ratio, rel, tilt, float(sig.max()), advice)


# ======================================================================== undistortion

def _rectangles(K: np.ndarray, dist: np.ndarray, size: tuple[int, int], n: int = 9):
    """Inner and outer rectangles (x0, y0, x1, y1) of the undistorted image border, normalised coords."""
    w, h = size
    gx, gy = np.meshgrid(np.linspace(0, w - 1, n), np.linspace(0, h - 1, n))
    pix = np.column_stack([gx.ravel(), gy.ravel()])
    x = undistort_points(_to_normalised(pix, K), dist).reshape(n, n, 2)
    outer = (x[..., 0].min(), x[..., 1].min(), x[..., 0].max(), x[..., 1].max())
    inner = (x[:, 0, 0].max(), x[0, :, 1].max(), x[:, -1, 0].min(), x[-1, :, 1].min())
    return inner, outer


def optimal_new_camera_matrix(K: ArrayLike, dist: ArrayLike | None, image_size: Sequence[int],
                              alpha: float) -> np.ndarray:
    r"""The intrinsics of the undistorted image, trading black borders for lost pixels.

    Undistortion bends the image border outwards (barrel) or inwards (pincushion). With
    ``alpha = 0`` the new camera zooms in until every output pixel comes from inside the
    photo (no black borders, but pixels near the edges are lost); with ``alpha = 1`` it
    zooms out until every photo pixel is kept (black borders appear). In between the new
    K is interpolated linearly, as ``cv2.getOptimalNewCameraMatrix`` does: from a 9 x 9 grid
    of border-to-border pixels undistorted to normalised coordinates, the inner rectangle
    (inside all of them) and outer rectangle (around all of them) are mapped onto the image.

    Returns
    -------
    (3, 3) ndarray
        New K (zero skew), pixels.
    """
    Km = check_intrinsics(K)
    d = as_dist(dist)
    a = float(alpha)
    if not 0.0 <= a <= 1.0:
        raise CamlabInputError(f"alpha: expected a number in [0, 1] (0: no black borders, 1: keep all pixels), got {alpha!r}")
    w, h = check_size(image_size, "image_size")
    inner, outer = _rectangles(Km, d, (w, h))

    def fit(r):
        fx, fy = (w - 1) / (r[2] - r[0]), (h - 1) / (r[3] - r[1])
        return np.array([fx, fy, -fx * r[0], -fy * r[1]])

    p = (1 - a) * fit(inner) + a * fit(outer)
    return np.array([[p[0], 0.0, p[2]], [0.0, p[1], p[3]], [0.0, 0.0, 1.0]])


def undistortion_tradeoff(K: ArrayLike, dist: ArrayLike | None, image_size: Sequence[int], new_K: ArrayLike,
                          step: int = 4) -> tuple[float, float]:
    """(black_fraction, lost_fraction) of undistorting with ``new_K``.

    ``black_fraction``: share of output pixels that sample outside the photo (black
    border); ``lost_fraction``: share of photo pixels that land outside the output. Both on
    a grid every ``step`` pixels.
    """
    Km, Kn = check_intrinsics(K), check_intrinsics(new_K, "new_K")
    d = as_dist(dist)
    w, h = check_size(image_size, "image_size")
    U, Vv = np.meshgrid(np.arange(0, w, step, dtype=float), np.arange(0, h, step, dtype=float))
    pix = np.column_stack([U.ravel(), Vv.ravel()])
    # output pixel -> source pixel: K distort(Kn^-1 p); same as distort_pixels with a change of K
    src = _from_normalised(distort_points(_to_normalised(pix, Kn), d), Km)
    inside = (src[:, 0] >= -0.5) & (src[:, 0] <= w - 0.5) & (src[:, 1] >= -0.5) & (src[:, 1] <= h - 0.5)
    try:
        dst = _from_normalised(undistort_points(_to_normalised(pix, Km), d), Kn)
        kept = (dst[:, 0] >= -0.5) & (dst[:, 0] <= w - 0.5) & (dst[:, 1] >= -0.5) & (dst[:, 1] <= h - 0.5)
    except ConvergenceError:
        kept = np.zeros(len(pix), bool)
    return float(1 - inside.mean()), float(1 - kept.mean())


class Undistorted(NamedTuple):
    """``image`` the undistorted image; ``K`` its intrinsics (no distortion); ``black_fraction`` and
    ``lost_fraction`` as in :func:`undistortion_tradeoff`."""

    image: np.ndarray
    K: np.ndarray
    black_fraction: float
    lost_fraction: float


def undistort(image: ArrayLike, result: CalibrationResult | None = None, *, K: ArrayLike | None = None,
              dist: ArrayLike | None = None, alpha: float = 0.0) -> Undistorted:
    """Undistort an image with a calibration (or K and dist), choosing the new K with ``alpha``.

    ``alpha`` as in :func:`optimal_new_camera_matrix`: 0 crops to valid pixels, 1 keeps all.
    The remap uses :func:`camlab.distortion.undistort_image` (bilinear, black outside).
    """
    img = np.asarray(image)
    if img.ndim not in (2, 3) or img.size == 0:
        raise CamlabInputError(f"image: expected an (H, W) or (H, W, C) array, got shape {img.shape}")
    if result is not None:
        K, dist = result.K, result.dist
    if K is None:
        raise CamlabInputError("undistort: pass a CalibrationResult or K (and dist)")
    size = (img.shape[1], img.shape[0])
    new_K = optimal_new_camera_matrix(K, dist, size, alpha)
    black, lost = undistortion_tradeoff(K, dist, size, new_K)
    return Undistorted(undistort_image(img, K, dist, new_K), new_K, black, lost)


# ======================================================================== files

def save_calibration(result: CalibrationResult, path: str | os.PathLike) -> Path:
    """Write K, dist and the quality numbers with ``cv2.FileStorage`` (``.json``, ``.yaml``/``.yml`` or ``.xml``).

    OpenCV users load it with ``fs = cv2.FileStorage(path, cv2.FILE_STORAGE_READ);
    K = fs.getNode("camera_matrix").mat(); dist = fs.getNode("distortion_coefficients").mat()``.
    """
    import cv2

    p = Path(path)
    if p.suffix.lower() not in (".json", ".yaml", ".yml", ".xml"):
        raise CamlabInputError(f"path: expected a .json, .yaml, .yml or .xml file name, got {str(path)!r}")
    fs = cv2.FileStorage(str(p), cv2.FILE_STORAGE_WRITE)
    try:
        fs.write("image_width", int(result.image_size[0]))
        fs.write("image_height", int(result.image_size[1]))
        fs.write("camera_matrix", np.asarray(result.K, dtype=np.float64))
        fs.write("distortion_coefficients", np.asarray(result.dist, dtype=np.float64).reshape(1, 5))
        fs.write("rms", float(result.rms))
        fs.write("n_views", int(result.n_views))
        fs.write("per_view_rms", np.asarray(result.per_view_rms, dtype=np.float64).reshape(1, -1))
        fs.write("std_intrinsics", np.array([result.std[k] for k in PARAM_NAMES], dtype=np.float64).reshape(1, -1))
        fs.write("std_names", " ".join(PARAM_NAMES))
        fs.write("rvecs", np.asarray(result.rvecs, dtype=np.float64))
        fs.write("tvecs", np.asarray(result.tvecs, dtype=np.float64))
    finally:
        fs.release()
    return p


def load_calibration(path: str | os.PathLike) -> tuple[np.ndarray, np.ndarray, tuple[int, int]]:
    """Read ``(K, dist, image_size)`` from a file written by :func:`save_calibration` (or by OpenCV
    with the same node names)."""
    import cv2

    if not Path(path).is_file():
        raise CamlabInputError(f"path: no file {str(path)!r}")
    fs = cv2.FileStorage(str(path), cv2.FILE_STORAGE_READ)
    try:
        K = fs.getNode("camera_matrix").mat()
        dist = fs.getNode("distortion_coefficients").mat()
        size = (int(fs.getNode("image_width").real()), int(fs.getNode("image_height").real()))
    finally:
        fs.release()
    if K is None or dist is None:
        raise CamlabInputError(f"path: {str(path)!r} has no camera_matrix / distortion_coefficients nodes")
    return np.asarray(K, dtype=float), np.asarray(dist, dtype=float).ravel(), size


# ======================================================================== synthetic data

class SyntheticSet(NamedTuple):
    """Views of a board with known truth: ``object_points`` (N, 3), ``image_points`` list of (N, 2)
    (noisy), ``exact`` list of (N, 2) (noise-free), ``K``, ``dist``, ``R`` (V, 3, 3), ``t`` (V, 3),
    ``image_size``, ``noise`` (sigma, pixels)."""

    object_points: np.ndarray
    image_points: list
    exact: list
    K: np.ndarray
    dist: np.ndarray
    R: np.ndarray
    t: np.ndarray
    image_size: tuple
    noise: float


DEFAULT_K = np.array([[820.0, 0.0, 322.4], [0.0, 818.0, 236.8], [0.0, 0.0, 1.0]])
DEFAULT_DIST = np.array([-0.21, 0.09, 0.0006, -0.0004, -0.02])


def make_synthetic_views(n_views: int = 15, noise: float = 0.0, *, K: ArrayLike = DEFAULT_K,
                         dist: ArrayLike | None = DEFAULT_DIST, pattern_size: Sequence[int] = (9, 6),
                         square: float = 0.025, image_size: Sequence[int] = (640, 480), margin: float = 20.0,
                         rng: np.random.Generator | None = None) -> SyntheticSet:
    """Random well-spread views of a chessboard through a known camera (corners only, no images).

    Each view tilts the board by 15-50 degrees about a random in-plane axis, spins it,
    places it 0.3-0.6 m away at a random spot so that every corner lands at least
    ``margin`` pixels inside the image, and adds Gaussian noise of ``noise`` pixels to the
    exact corners (projected with :func:`camlab.render.project`).
    """
    from .camera import rotation_from_euler
    from .render import project

    rng = np.random.default_rng() if rng is None else rng
    Km = check_intrinsics(K)
    d = as_dist(dist)
    obj = board_points(pattern_size, square)
    centre = obj.mean(axis=0)
    w, h = (int(v) for v in image_size)
    Rs, ts, exact = [], [], []
    tries = 0
    while len(Rs) < n_views:
        tries += 1
        if tries > 200 * max(n_views, 1):
            raise CamlabInputError("make_synthetic_views: could not place the board inside the image; "
                                   "use a smaller board or a wider camera")
        axis = rng.uniform(0, 2 * np.pi)
        tilt = np.radians(rng.uniform(15, 50))
        R_tilt = rotation_from_axis_angle(tilt * np.array([np.cos(axis), np.sin(axis), 0.0]))
        R = R_tilt @ rotation_from_euler(0, 0, rng.uniform(-0.5, 0.5))
        depth = rng.uniform(0.3, 0.6)
        target = np.array([rng.uniform(-0.35, 0.35), rng.uniform(-0.3, 0.3), 1.0]) * depth
        t = target - R @ centre
        uv = project(obj, Km, R, t, d)
        if np.all(np.isfinite(uv)) and uv[:, 0].min() >= margin and uv[:, 1].min() >= margin \
                and uv[:, 0].max() <= w - 1 - margin and uv[:, 1].max() <= h - 1 - margin:
            Rs.append(R)
            ts.append(t)
            exact.append(uv)
    noisy = [e + rng.normal(0, noise, e.shape) if noise > 0 else e.copy() for e in exact]
    return SyntheticSet(obj, noisy, exact, Km, d, np.array(Rs), np.array(ts), (w, h), float(noise))
