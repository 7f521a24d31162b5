r"""The panorama data of lesson 09, ``data/panorama/``: its loaders, and the real aerial mosaic.

``rot_00.jpg`` ... ``rot_03.jpg``
    A camera turning about its centre (yaw -27, -9, 9, 27 degrees, a little pitch and roll)
    in a room: a wide textured back wall 6 m away (16 m wide), a photograph, a text page and a box
    closer by. 640 x 480 RGB, fx = 800; each view has its own exposure gain and sensor
    noise, and is stored as a quality-95 JPEG like a camera's (a noisy PNG is 5x larger,
    and ``data/`` must stay small). Because the centre does not move, view i maps to view j by the homography
    :math:`H_{ji} = K R_j R_i^T K^{-1}` whatever the depth (lesson 09, section 1).
``plane_0.jpg``, ``plane_1.jpg``
    A flat poster photographed from two different positions: related by the plane-induced
    homography :math:`K (R - t n^T / d) K^{-1}`.
``truth.json``
    The generator's parameters, K, every view's pose (cam_from_world ``R``, ``t``), gains,
    and the true homographies.

Load them with :func:`load_panorama_set` and :func:`load_planar_pair`. The generator (the room
scene, ``python -m camlab.data``) and the turning sets rendered from a real photograph are
fixtures: :mod:`camlab.fixtures.panorama`.
"""

from __future__ import annotations

from pathlib import Path
from typing import NamedTuple

import numpy as np

from .._validate import CamlabInputError
from ..camera import scale_intrinsics
from ._resources import read_truth

__all__ = [
    "PanoramaSet",
    "PlanarPair",
    "load_aerial_mosaic",
    "load_panorama_set",
    "load_planar_pair",
]


class PanoramaSet(NamedTuple):
    """The rotation set.

    RGB ``images``, shared ``K``, cam_from_world ``R`` (n, 3, 3), ``gains`` (each view's rendered
    exposure, the factor its signal was multiplied by; also readable as ``exposures``),
    ``H_true[j][i]`` = the true homography from view i to view j, and the generator ``params``.
    """

    images: list
    K: np.ndarray
    R: np.ndarray
    gains: np.ndarray
    params: dict

    @property
    def exposures(self) -> np.ndarray:
        """Each view's rendered exposure (the same array as ``gains``).

        Returns
        -------
        (n,) ndarray
            The factor each view's signal was rendered with; gain compensation's gains undo it
            (about ``exposures[ref] / exposures``).
        """
        return self.gains

    def true_homography(self, i: int, j: int) -> np.ndarray:
        """The ground-truth homography mapping view ``i``'s pixels to view ``j``'s: K R_j R_i^T K^-1.

        Parameters
        ----------
        i, j : int
            View indices.

        Returns
        -------
        (3, 3) ndarray
            H, view j's pixels ~ H view i's pixels.
        """
        from ..homography import rotation_homography

        return rotation_homography(self.K, self.R[j] @ self.R[i].T)


class PlanarPair(NamedTuple):
    """Two views of a flat poster; ``H`` maps view 0's pixels to view 1's.

    ``R`` and ``t`` (metres) take view 0's camera frame to view 1's, ``X_1 = R X_0 + t``; the poster is
    the plane ``n^T X_0 + d = 0`` (``plane_n``, ``plane_d`` in metres), so ``H ~ K (R - t n^T / d) K^-1``.
    """

    images: list
    K: np.ndarray
    H: np.ndarray
    params: dict
    R: np.ndarray | None = None
    t: np.ndarray | None = None
    plane_n: np.ndarray | None = None
    plane_d: float | None = None


def _read(path: Path, scale: float) -> np.ndarray:
    import cv2

    img = cv2.imread(str(path), cv2.IMREAD_COLOR)
    if img is None:
        raise CamlabInputError(
            f"directory: cannot read {path}; run `python -m camlab.data` to generate it"
        )
    img = np.ascontiguousarray(img[..., ::-1])
    if scale != 1.0:
        h, w = img.shape[:2]
        img = cv2.resize(
            img, (int(round(w * scale)), int(round(h * scale))), interpolation=cv2.INTER_AREA
        )
    return img


def load_panorama_set(directory: Path | str | None = None, scale: float = 1.0) -> PanoramaSet:
    """Load ``data/panorama`` (or ``directory``); ``scale`` < 1 resizes the images (K follows).

    Parameters
    ----------
    directory : str or pathlib.Path, optional
        Where the set is (default: the shipped copy).
    scale : float, optional
        Resize factor of the images (default 1; K follows, :func:`camlab.camera.scale_intrinsics`).

    Returns
    -------
    PanoramaSet
        The images, ``K``, the rotations, gains, true homographies and generator parameters.

    Examples
    --------
    >>> s = load_panorama_set(scale=0.5)
    >>> len(s.images), s.images[0].shape, float(s.K[0, 0])
    (4, (240, 320, 3), 400.0)
    """
    d, truth = read_truth(directory, "panorama")
    images = [_read(d / v["file"], scale) for v in truth["views"]]
    K = scale_intrinsics(np.array(truth["K"]), scale)
    return PanoramaSet(
        images,
        K,
        np.array([v["R"] for v in truth["views"]]),
        np.array([v["gain"] for v in truth["views"]]),
        truth["params"],
    )


def load_planar_pair(directory: Path | str | None = None, scale: float = 1.0) -> PlanarPair:
    """Load the two views of the flat poster; ``H`` maps view 0's pixels to view 1's (at ``scale``).

    Parameters
    ----------
    directory : str or pathlib.Path, optional
        Where the set is (default: the shipped copy).
    scale : float, optional
        Resize factor of the images (default 1; K follows, :func:`camlab.camera.scale_intrinsics`).

    Returns
    -------
    PlanarPair
        The two images, ``K`` and ``H``, view 1 ~ H view 0, at ``scale``.
    """
    d, truth = read_truth(directory, "panorama")
    pp = truth["plane_pair"]
    images = [_read(d / f, scale) for f in pp["files"]]
    S = scale_intrinsics(np.eye(3), scale)
    H = S @ np.array(pp["H_10"]) @ np.linalg.inv(S)
    return PlanarPair(
        images,
        scale_intrinsics(np.array(truth["K"]), scale),
        H / H[2, 2],
        truth["params"],
        np.array(pp["R1"], dtype=float),
        np.array(pp["t1"], dtype=float),
        np.array(pp["plane_n"], dtype=float),
        float(pp["plane_d"]),
    )


# --------------------------------------------------------------------------- a real photo as the world


def load_aerial_mosaic(count: int = 6) -> list:
    """The real planar mosaic: ``count`` (2-6) overlapping aerial photographs (grey, 900 px wide).

    A flat scene seen from six positions (mvtb-data ``mosaic/aerial2-00*``, MIT; see
    data/photos/ATTRIBUTION.md), so consecutive photos are related by homographies.

    Parameters
    ----------
    count : int, optional
        How many photographs, 2 to 6 (default 6).

    Returns
    -------
    list of (H, W) uint8 ndarray
        The photographs, in order along the flight.
    """
    from .photos import load_photo

    if not 2 <= int(count) <= 6:
        raise CamlabInputError(f"count: expected 2 to 6 aerial photos, got {count!r}")
    return [load_photo(f"aerial_{k}", gray=True) for k in range(1, int(count) + 1)]
