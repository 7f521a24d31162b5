r"""Stages 2-6 of Zhang's method: homographies, constraints on B, K in closed form, poses, radial distortion.

See :mod:`camlab.calibration` for the whole pipeline and lesson 08 for the derivations.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import (
    CamlabInputError,
    DegenerateError,
    as_float,
    as_points,
    check_intrinsics,
    check_matrix,
)
from ..camera import Pose, nearest_rotation
from ..homography import estimate_homography


def _rows(x, dim: int, name: str) -> np.ndarray:
    """One view's points as rows: OpenCV's (N, 1, dim) is squeezed; a transposed (dim, N) is refused."""
    a = as_float(x, name)
    if a.ndim == 3 and a.shape[1] == 1:
        a = a[:, 0, :]
    if a.ndim == 2 and a.shape[0] == dim and a.shape[1] > dim:
        raise CamlabInputError(
            f"{name}: got shape {a.shape}, which looks transposed; points are rows, "
            f"pass ({a.shape[1]}, {dim}) (use .T)"
        )
    return a


class Views(NamedTuple):
    """Views of a flat board, validated once by :func:`check_views`.

    Attributes
    ----------
    object_points : list of (N_v, 3) ndarray
        Each view's board points, metres, Z = 0.
    image_points : list of (N_v, 2) ndarray
        Each view's detected corners, pixels (finite, as many as its board points).
    """

    object_points: list
    image_points: list


def check_views(object_points, image_points, min_views: int = 1) -> Views:
    """Validate views of a flat board, view by view, into lists of float arrays.

    Each view needs as many corners as board points, finite corners and a flat board (Z = 0,
    :func:`planar_xy`). The public estimators (:func:`view_homographies`,
    :func:`initial_radial_distortion`) check their arguments with it; a pipeline that has
    checked its views once passes the :class:`Views` to :func:`homographies_of` and
    :func:`radial_distortion_of`.

    Parameters
    ----------
    object_points : (N, 3) array_like or sequence of V (N_v, 3) array_like
        The board points, metres, Z = 0: one array for every view, or one per view.
    image_points : sequence of V (N_v, 2) array_like
        Each view's detected corners, pixels (a single (N, 2) array is one view). OpenCV's
        (N, 1, 2) shape is accepted.
    min_views : int
        The fewest views accepted.

    Returns
    -------
    Views
        ``object_points`` (V arrays (N_v, 3)) and ``image_points`` (V arrays (N_v, 2)).

    Raises
    ------
    CamlabInputError
        Fewer than ``min_views`` views, a view with fewer than 4 points, a corner count that
        differs from the board's, a non-finite corner, or a board with Z != 0.
    """
    if isinstance(image_points, np.ndarray) and image_points.ndim == 2:
        image_points = [image_points]
    try:
        if isinstance(image_points, str):
            raise TypeError
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
    if object_points is None or isinstance(object_points, str):
        raise CamlabInputError(
            f"object_points: expected (N, 3) board points, or one such array per view, got "
            f"{type(object_points).__name__}"
        )
    obj = (
        as_float(object_points, "object_points")
        if not isinstance(object_points, (list, tuple))
        else None
    )
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
    for v, (o, p) in enumerate(zip(objs, image_points, strict=True)):
        o = as_points(
            _rows(o, 3, f"object_points[{v}]"), 3, f"object_points[{v}]", min_count=4
        ).array
        p = as_points(
            _rows(p, 2, f"image_points[{v}]"), 2, f"image_points[{v}]", min_count=4, finite=False
        ).array
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
        planar_xy(o, v)
        out_obj.append(o)
        out_img.append(p)
    return Views(out_obj, out_img)


def planar_xy(obj: np.ndarray, v: int) -> np.ndarray:
    """The (X, Y) of a flat board's points, after checking that every Z is 0.

    Parameters
    ----------
    obj : (N, 3) ndarray
        One view's board points, metres.
    v : int
        The view's index, for the error message.

    Returns
    -------
    (N, 2) ndarray
        The points' X, Y (a view of ``obj``).

    Raises
    ------
    CamlabInputError
        A Z larger than 1e-9 times the board's extent: the target is not flat.
    """
    scale = max(np.abs(obj[:, :2]).max(), 1e-300)
    if np.abs(obj[:, 2]).max() > 1e-9 * scale:
        raise CamlabInputError(
            f"object_points[{v}]: Zhang's method needs a flat target with Z = 0 (a chessboard in its own frame), "
            f"got Z up to {np.abs(obj[:, 2]).max():.3g}; for a 3-D target use "
            f"camlab.camera.estimate_projection_matrix (DLT resectioning)"
        )
    return obj[:, :2]


def view_homographies(
    object_points: Sequence[ArrayLike] | ArrayLike, image_points: Sequence[ArrayLike]
) -> np.ndarray:
    """One homography per view, board plane (X, Y) to image (u, v), by the normalised DLT.

    Uses :func:`camlab.homography.estimate_homography` (Hartley normalisation) on the views
    :func:`check_views` validates; each H is scaled so H[2, 2] = 1.

    Parameters
    ----------
    object_points : (N, 3) array_like or sequence of V (N_v, 3) array_like
        The board points, metres, Z = 0 (one array for all views, or one per view).
    image_points : sequence of V (N_v, 2) array_like
        Each view's detected corners, pixels.

    Returns
    -------
    (V, 3, 3) ndarray
        The homographies, H[2, 2] = 1 where possible.

    Raises
    ------
    CamlabInputError
        No views, a view with fewer than 4 points, a corner count that
        differs from the board's, a non-finite corner, or a board with Z != 0.

    References
    ----------
    .. [1] Z. Zhang, 2000, "A flexible new technique for camera calibration", *IEEE
       Transactions on Pattern Analysis and Machine Intelligence* 22(11), 1330-1334,
       section 2.2 and appendix A.
    """
    return homographies_of(check_views(object_points, image_points))


def homographies_of(views: Views) -> np.ndarray:
    """:func:`view_homographies` of views :func:`check_views` has validated.

    Parameters
    ----------
    views : Views
        From :func:`check_views`.

    Returns
    -------
    (V, 3, 3) ndarray
        One board -> image homography per view.
    """
    return np.stack([estimate_homography(o[:, :2], p) for o, p in zip(*views, strict=True)])


def zhang_v(H: ArrayLike, i: int, j: int) -> np.ndarray:
    r"""Zhang's vector :math:`v_{ij}` with :math:`h_i^\top B h_j = v_{ij}^\top b`.

    With :math:`h_i` the i-th column of H (i, j in 0, 1, 2) and
    :math:`b = (B_{11}, B_{12}, B_{22}, B_{13}, B_{23}, B_{33})` the six distinct entries of
    the symmetric :math:`B = K^{-\top} K^{-1}`:

    .. math::
        v_{ij} = (h_{i1} h_{j1},\ h_{i1} h_{j2} + h_{i2} h_{j1},\ h_{i2} h_{j2},\
                  h_{i3} h_{j1} + h_{i1} h_{j3},\ h_{i3} h_{j2} + h_{i2} h_{j3},\ h_{i3} h_{j3})

    Parameters
    ----------
    H : (3, 3) array_like
        A view's board -> image homography.
    i, j : int
        Column indices, 0, 1 or 2.

    Returns
    -------
    (6,) ndarray
        :math:`v_{ij}`.

    Raises
    ------
    CamlabInputError
        ``H`` not (3, 3), or ``i``, ``j`` not 0, 1 or 2.
    DegenerateError
        ``H`` all zeros.

    References
    ----------
    .. [1] Z. Zhang, 2000, "A flexible new technique for camera calibration", *IEEE
       Transactions on Pattern Analysis and Machine Intelligence* 22(11), 1330-1334,
       section 3.1 (eq. 7).

    Examples
    --------
    >>> zhang_v(np.eye(3), 0, 0)
    array([1., 0., 0., 0., 0., 0.])
    """
    Hm = check_matrix(H, (3, 3), "H")
    if not Hm.any():
        raise DegenerateError("H: all zeros; pass the board -> image homography of a view")
    for value, name in ((i, "i"), (j, "j")):
        if (
            isinstance(value, bool)
            or not isinstance(value, (int, np.integer))
            or value not in (0, 1, 2)
        ):
            raise CamlabInputError(f"{name}: expected a column index 0, 1 or 2, got {value!r}")
    a, c = Hm[:, i], Hm[:, j]
    return np.array(
        [
            a[0] * c[0],
            a[0] * c[1] + a[1] * c[0],
            a[1] * c[1],
            a[2] * c[0] + a[0] * c[2],
            a[2] * c[1] + a[1] * c[2],
            a[2] * c[2],
        ]
    )


def zhang_constraints(H: ArrayLike) -> np.ndarray:
    r"""The (2, 6) rows one view adds to :math:`V b = 0`.

    :math:`H = \lambda K [r_1\ r_2\ t]`, so :math:`r_k = \lambda^{-1} K^{-1} h_k`; the
    columns of a rotation are orthonormal, so

    .. math::
        h_1^\top B h_2 = 0 \;\Rightarrow\; v_{12}^\top b = 0, \qquad
        h_1^\top B h_1 = h_2^\top B h_2 \;\Rightarrow\; (v_{11} - v_{22})^\top b = 0 .

    (In 0-based column indices: ``zhang_v(H, 0, 1)`` and ``zhang_v(H, 0, 0) - zhang_v(H, 1, 1)``.)

    Parameters
    ----------
    H : (3, 3) array_like
        A view's board -> image homography.

    Returns
    -------
    (2, 6) ndarray
        The rows :math:`v_{12}^\top` and :math:`(v_{11} - v_{22})^\top`.

    Raises
    ------
    CamlabInputError
        ``H`` not (3, 3).
    DegenerateError
        ``H`` all zeros.

    References
    ----------
    .. [1] Z. Zhang, 2000, "A flexible new technique for camera calibration", *IEEE
       Transactions on Pattern Analysis and Machine Intelligence* 22(11), 1330-1334,
       sections 2.3 and 3.1 (eq. 8).
    """
    return np.stack([zhang_v(H, 0, 1), zhang_v(H, 0, 0) - zhang_v(H, 1, 1)])


def intrinsics_from_b(b: ArrayLike) -> np.ndarray:
    r"""K from :math:`b \propto (B_{11}, B_{12}, B_{22}, B_{13}, B_{23}, B_{33})` in closed form.

    Zhang [1]_, appendix B, with :math:`B = \lambda K^{-\top} K^{-1}`:

    .. math::
        c_y &= (B_{12} B_{13} - B_{11} B_{23}) / (B_{11} B_{22} - B_{12}^2) \\
        \lambda &= B_{33} - [B_{13}^2 + c_y (B_{12} B_{13} - B_{11} B_{23})] / B_{11} \\
        f_x &= \sqrt{\lambda / B_{11}}, \qquad
        f_y = \sqrt{\lambda B_{11} / (B_{11} B_{22} - B_{12}^2)} \\
        s &= -B_{12} f_x^2 f_y / \lambda, \qquad
        c_x = s\, c_y / f_y - B_{13} f_x^2 / \lambda

    b is known only up to scale and sign; the sign is chosen to make B positive definite.

    Parameters
    ----------
    b : (6,) array_like
        :math:`(B_{11}, B_{12}, B_{22}, B_{13}, B_{23}, B_{33})`, up to scale and sign.

    Returns
    -------
    (3, 3) ndarray
        K, upper triangular with K[2, 2] = 1 (pixels), skew ``s`` included.

    Raises
    ------
    CamlabInputError
        ``b`` not 6 finite numbers.
    DegenerateError
        If no sign of b gives a positive definite B, or the focal length comes out
        imaginary (the views do not determine K).

    References
    ----------
    .. [1] Z. Zhang, 2000, "A flexible new technique for camera calibration", *IEEE
       Transactions on Pattern Analysis and Machine Intelligence* 22(11), 1330-1334,
       appendix B.
    """
    bv = np.asarray(b, dtype=float).ravel()
    if bv.shape != (6,) or not np.isfinite(bv).all():
        raise CamlabInputError(
            f"b: expected 6 finite numbers (B11, B12, B22, B13, B23, B33), got {np.shape(b)}"
        )
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


def intrinsics_from_homographies(
    homographies: ArrayLike, *, skew: bool = False, image_size: Sequence[int] | None = None
) -> np.ndarray:
    r"""K in closed form from V >= 2 view homographies (>= 3 with ``skew=True``).

    Stacks :func:`zhang_constraints` into V (2V x 6), takes b as the right singular vector
    with the smallest singular value and applies :func:`intrinsics_from_b`. With
    ``skew=False`` the column of :math:`B_{12}` is dropped (zero skew makes
    :math:`B_{12} = 0`), leaving 5 unknowns.

    For conditioning, the homographies are first expressed in pixels scaled to about
    [-1, 1] by :math:`T` (from ``image_size``, or from their own translations):
    :math:`T H = (T K) [r_1\ r_2\ t]`, so the method yields :math:`T K` and
    :math:`K = T^{-1} (T K)`.

    Parameters
    ----------
    homographies : (V, 3, 3) array_like
        The views' board -> image homographies.
    skew : bool
        Estimate the skew too (otherwise it is 0).
    image_size : (width, height), optional
        The image size, pixels, for the conditioning :math:`T`; default from the homographies'
        translations.

    Returns
    -------
    (3, 3) ndarray
        K, pixels, with K[2, 2] = 1.

    Raises
    ------
    CamlabInputError
        ``homographies`` not (V, 3, 3).
    DegenerateError
        Too few views, or a set that leaves b undetermined (all boards parallel).

    References
    ----------
    .. [1] Z. Zhang, 2000, "A flexible new technique for camera calibration", *IEEE
       Transactions on Pattern Analysis and Machine Intelligence* 22(11), 1330-1334,
       section 3.1 (closed-form solution).
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


def extrinsics_from_homography(K: ArrayLike, H: ArrayLike) -> Pose:
    r"""A view's pose (R, t), cam_from_board, from K and its homography.

    :math:`K^{-1} H = \lambda [r_1\ r_2\ t]` with :math:`\lambda = 1 / \|K^{-1} h_1\|`
    (sign chosen so the board is in front, :math:`t_z > 0`), :math:`r_3 = r_1 \times r_2`.
    With noise :math:`[r_1\ r_2\ r_3]` is not orthonormal; :func:`nearest_rotation` fixes that.
    (The code takes :math:`\lambda` from the mean of :math:`\|K^{-1} h_1\|` and
    :math:`\|K^{-1} h_2\|`.)

    Parameters
    ----------
    K : (3, 3) array_like
        Intrinsics, pixels.
    H : (3, 3) array_like
        The view's board -> image homography.

    Returns
    -------
    Pose
        ``R`` (3, 3) and ``t`` (3,), metres in the board's units: cam_from_board.

    Raises
    ------
    CamlabInputError
        ``K`` not intrinsics or ``H`` not (3, 3).
    DegenerateError
        ``H``'s first two columns are dependent.

    References
    ----------
    .. [1] Z. Zhang, 2000, "A flexible new technique for camera calibration", *IEEE
       Transactions on Pattern Analysis and Machine Intelligence* 22(11), 1330-1334,
       section 3.1 and appendix C (the nearest rotation).
    """
    Km = check_intrinsics(K, "K")
    Hm = check_matrix(H, (3, 3), "H")
    if np.linalg.matrix_rank(Hm[:, :2]) < 2:
        raise DegenerateError(
            "H: its first two columns are dependent, so they cannot be the images of the "
            "board's x and y axes; pass the board -> image homography"
        )
    A = np.linalg.solve(Km, Hm)
    lam = 2.0 / (np.linalg.norm(A[:, 0]) + np.linalg.norm(A[:, 1]))
    if A[2, 2] * lam < 0:
        lam = -lam
    r1, r2, t = lam * A[:, 0], lam * A[:, 1], lam * A[:, 2]
    R = nearest_rotation(np.column_stack([r1, r2, np.cross(r1, r2)]))
    return Pose(R, t)


def initial_radial_distortion(
    K: ArrayLike, object_points, image_points, R: ArrayLike, t: ArrayLike
) -> np.ndarray:
    r"""Linear least-squares radial distortion (k1, k2) given K and every view's pose.

    With ideal normalised points :math:`x` (from K, R, t, no distortion), radius
    :math:`r^2 = x^2 + y^2` and ideal pixels :math:`(u, v)`, the radial model says the
    observed pixels are :math:`\breve u = u + (u - c_x)(k_1 r^2 + k_2 r^4)` (same for v):
    two linear equations in (k1, k2) per corner,

    .. math::
        \begin{pmatrix} (u - c_x) r^2 & (u - c_x) r^4 \\ (v - c_y) r^2 & (v - c_y) r^4 \end{pmatrix}
        \begin{pmatrix} k_1 \\ k_2 \end{pmatrix} = \begin{pmatrix} \breve u - u \\ \breve v - v \end{pmatrix}.

    Parameters
    ----------
    K : (3, 3) array_like
        Intrinsics, pixels.
    object_points : (N, 3) array_like or sequence of V (N_v, 3) array_like
        The board points, metres, Z = 0.
    image_points : sequence of V (N_v, 2) array_like
        The observed (distorted) corners, pixels.
    R : (V, 3, 3) array_like
        Each view's rotation, cam_from_board.
    t : (V, 3) array_like
        Each view's translation, cam_from_board (board units).

    Returns
    -------
    (2,) ndarray
        (k1, k2).

    Raises
    ------
    CamlabInputError
        No views, a view with fewer than 4 points, a corner count that
        differs from the board's, a non-finite corner, or a board with Z != 0.

    References
    ----------
    .. [1] Z. Zhang, 2000, "A flexible new technique for camera calibration", *IEEE
       Transactions on Pattern Analysis and Machine Intelligence* 22(11), 1330-1334,
       section 3.3 (dealing with radial distortion).
    """
    return radial_distortion_of(K, check_views(object_points, image_points), R, t)


def radial_distortion_of(K: ArrayLike, views: Views, R: ArrayLike, t: ArrayLike) -> np.ndarray:
    """:func:`initial_radial_distortion` for views :func:`check_views` has validated.

    Parameters
    ----------
    K : (3, 3) array_like
        Intrinsics, pixels.
    views : Views
        From :func:`check_views`.
    R : (V, 3, 3) array_like
        Each view's rotation, cam_from_board.
    t : (V, 3) array_like
        Each view's translation, cam_from_board.

    Returns
    -------
    (2,) ndarray
        (k1, k2).
    """
    Km = np.asarray(K, dtype=float)
    Rs, ts = np.asarray(R, dtype=float).reshape(-1, 3, 3), np.asarray(t, dtype=float).reshape(-1, 3)
    rows, rhs = [], []
    for o, p, Rv, tv in zip(*views, Rs, ts, strict=True):
        Xc = o @ Rv.T + tv
        x = Xc[:, :2] / Xc[:, 2:3]  # ideal normalised points
        r2 = np.sum(x * x, axis=1)
        uv = x @ Km[:2, :2].T + Km[:2, 2]
        d = uv - Km[:2, 2]
        rows.append(np.stack([d * r2[:, None], d * (r2 * r2)[:, None]], axis=-1).reshape(-1, 2))
        rhs.append((p - uv).ravel())
    k, *_ = np.linalg.lstsq(np.concatenate(rows), np.concatenate(rhs), rcond=None)
    return k
