r"""``camlab stitch FOLDER --out pano.jpg``: a panorama from overlapping photos."""

from __future__ import annotations

import argparse

from .._validate import CamlabInputError
from .photos import (
    check_positive_megapixels,
    photo_paths,
    read_or_skip,
    within_work_size,
    write_image,
)

__all__ = []


def add_stitch(p: argparse.ArgumentParser) -> None:
    """The arguments of ``camlab stitch``: the photos, ``--out``, ``--projection``, ``--crop`` and ``--max-megapixels``.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The subcommand's parser; its arguments are added in place.
    """
    p.add_argument(
        "images", nargs="+", help="a folder of photos, photo files, or a quoted glob pattern"
    )
    p.add_argument("--out", required=True, help="the panorama (.jpg or .png)")
    p.add_argument(
        "--projection",
        choices=["auto", "planar", "cylindrical", "spherical"],
        default="auto",
        help="canvas: planar for a flat scene or a narrow turn, spherical for wide turns (default auto)",
    )
    p.add_argument(
        "--crop", action="store_true", help="crop to the largest rectangle without empty canvas"
    )
    p.add_argument(
        "--max-megapixels",
        type=float,
        default=4.0,
        help="shrink larger photos to this size first (default 4; phone photos are 12-50)",
    )


def run_stitch(args: argparse.Namespace) -> int:
    """Stitch the photos; exit 1 if some could not be read or overlap nothing (named).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed arguments of ``camlab stitch`` (:func:`add_stitch`).

    Returns
    -------
    int
        The exit status: 0 when every photo is in the panorama, 1 when some were unreadable or overlap no other (named on the last line).

    Raises
    ------
    CamlabInputError
        On an error the user can fix; :func:`camlab.cli.main` prints it and exits with status 2.
    """
    import warnings
    from pathlib import Path

    from .._files import check_not_an_input, check_output_path
    from ..stitching import stitch

    check_output_path(args.out, "--out", (".jpg", ".jpeg", ".png"))
    check_positive_megapixels(args.max_megapixels)
    files = photo_paths(args.images)
    check_not_an_input([args.out], "--out", files, "give the panorama a name of its own")
    images, names, unreadable = [], [], []
    for name in files:
        img = read_or_skip(name, "rgb")
        if img is None:
            unreadable.append(Path(name).name)
            continue
        images.append(within_work_size(img, args.max_megapixels, name))
        names.append(Path(name).name)
    if len(images) < 2:
        raise CamlabInputError(f"images: need at least two readable photos, got {len(images)}")
    print(f"camlab stitch: {len(images)} photos, projection {args.projection}", flush=True)
    with warnings.catch_warnings(
        record=True
    ) as caught:  # one line each, not Python's warning format
        warnings.simplefilter("always")
        res = stitch(images, projection=args.projection, crop=args.crop, names=names)
    for w in caught:
        print(f"  warning: {w.message}")
    for pair in res.pairs:
        if pair.accepted:
            print(
                f"  {names[pair.i]} - {names[pair.j]}: {pair.inliers} of {pair.matches} matches agree, "
                f"rms {pair.residual_rms:.2f} px"
            )
    groups = [g for g in res.graph.groups() if len(g) > 1]
    if len(groups) > 1:
        print(
            f"  {len(groups)} separate groups of overlapping photos (stitch each on its own): "
            + "; ".join(" + ".join(names[k] for k in g) for g in groups)
        )
    left_out = [names[i] for i in res.unconnected]
    write_image(args.out, res.panorama, "--out")
    h, w = res.panorama.shape[:2]
    print(
        f"wrote {args.out}: {w} x {h} px, {res.projection} canvas, {len(images) - len(left_out)} of "
        f"{len(images) + len(unreadable)} photos used"
        + (f"; left out: {', '.join(unreadable + left_out)}" if unreadable or left_out else "")
    )
    return 1 if unreadable or left_out else 0
