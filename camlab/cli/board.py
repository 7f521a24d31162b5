r"""``camlab board``: a printable chessboard at true scale, with a 10 cm ruler to check the print.

``camlab board --pattern 9x6 --square 0.025 --out board.pdf`` writes a board of 9 x 6 *inner
corners* (10 x 7 squares, as ``camlab calibrate --pattern 9x6`` expects) whose squares are
25 mm, centred on an A4 (or ``--paper letter``) page, portrait if it fits, else landscape.
A line of text above the board gives the pattern and the square size; a 10 cm ruler below it
lets the student check that the printer did not scale the page ("fit to page" shrinks A4 by
about 3 %, enough to bias every length the calibrated camera measures).

The PDF is written by hand, a page of filled rectangles (``x y w h re f``, in points, 1 pt =
1/72 inch = 0.3528 mm) in one uncompressed content stream, so the file says in plain text
what size each square is (``tests/test_cli_board.py`` reads it back). Sections of the stream
are marked with PDF comments (``% board``, ``% ruler``).
"""

from __future__ import annotations

import argparse
import math
from typing import NamedTuple

from .._validate import CamlabInputError

__all__ = []

PT_PER_M = 72 / 0.0254  # PDF points per metre
PAPERS = {"a4": (0.210, 0.297), "letter": (0.2159, 0.2794)}  # (width, height) in metres, portrait
MARGIN_PT = 18.0  # 1/4 inch: what most printers leave unprinted at the page's edge
BAND_PT = 18.0  # height of the text above the board and of the ruler below it
QUIET_PT = 8.0  # white between the board and the text or ruler (the detector needs some)
RULER_M = 0.10


class BoardLayout(NamedTuple):
    """Where everything goes on the page, in PDF points (origin bottom-left, y up).

    Attributes
    ----------
    page_w, page_h : float
        The page size (the paper in the orientation chosen).
    orientation : str
        ``"portrait"`` or ``"landscape"``.
    x0, y0 : float
        The board's bottom-left corner.
    square : float
        The side of one square.
    squares : tuple of int
        (columns, rows) of squares: inner corners + 1 each way.
    """

    page_w: float
    page_h: float
    orientation: str
    x0: float
    y0: float
    square: float
    squares: tuple[int, int]


def _fits(page_w: float, page_h: float, board_w: float, board_h: float) -> bool:
    """Whether a board fits centred with the margins, the text line and the ruler."""
    return (
        board_w <= page_w - 2 * MARGIN_PT
        and RULER_M * PT_PER_M <= page_w - 2 * MARGIN_PT
        and (page_h - board_h) / 2 >= MARGIN_PT + BAND_PT + QUIET_PT
    )


def _largest_square(page: tuple[float, float], squares: tuple[int, int]) -> float:
    """The largest square (metres, rounded down to 0.1 mm) whose board fits ``page`` either way round."""
    best = 0.0
    for w, h in (page, page[::-1]):
        side = min(
            (w - 2 * MARGIN_PT) / squares[0],
            (h - 2 * (MARGIN_PT + BAND_PT + QUIET_PT)) / squares[1],
        )
        best = max(best, side / PT_PER_M)
    return math.floor(best * 1e4) / 1e4


def board_layout(pattern, square: float, paper: str = "a4") -> BoardLayout:
    """Place a board of ``pattern`` inner corners and ``square`` metres squares on a page.

    Parameters
    ----------
    pattern : str or (2,) sequence of int
        Inner corners, ``"COLSxROWS"`` as ``camlab calibrate --pattern`` takes them.
    square : float
        Side of one square in metres (e.g. 0.025).
    paper : {"a4", "letter"}
        The paper; portrait is used if the board fits, else landscape.

    Returns
    -------
    BoardLayout
        The page and the board's place on it, centred.

    Raises
    ------
    CamlabInputError
        A bad pattern, a square that is not a positive number of metres, an unknown paper, or
        a board that does not fit the page (the message gives the largest square that does).
    """
    from ..calibration import parse_pattern

    cols, rows = parse_pattern(pattern, "--pattern")
    if paper not in PAPERS:
        raise CamlabInputError(f"--paper: expected one of {sorted(PAPERS)}, got {paper!r}")
    if isinstance(square, bool) or not isinstance(square, (int, float)) or not square > 0:
        raise CamlabInputError(
            f"--square: expected the side of one square in metres, a positive number such as "
            f"0.025 (25 mm), got {square!r}"
        )
    if not math.isfinite(square):
        raise CamlabInputError(f"--square: expected a finite number of metres, got {square!r}")
    squares = (cols + 1, rows + 1)
    side = square * PT_PER_M
    board_w, board_h = squares[0] * side, squares[1] * side
    page = tuple(v * PT_PER_M for v in PAPERS[paper])
    for (w, h), orientation in ((page, "portrait"), (page[::-1], "landscape")):
        if _fits(w, h, board_w, board_h):
            return BoardLayout(
                w, h, orientation, (w - board_w) / 2, (h - board_h) / 2, side, squares
            )
    largest = _largest_square(page, squares)
    other = next(p for p in PAPERS if p != paper)
    hint = ""
    if _largest_square(tuple(v * PT_PER_M for v in PAPERS[other]), squares) >= square:
        hint = f", or print on --paper {other}"
    raise CamlabInputError(
        f"--square: a board of {squares[0]} x {squares[1]} squares of {square * 1000:g} mm "
        f"({board_w / PT_PER_M * 1000:.0f} x {board_h / PT_PER_M * 1000:.0f} mm) does not fit "
        f"on {paper.upper() if paper == 'a4' else paper} paper with its margins, text and ruler; "
        f"the largest square that fits is {largest:g} m (--square {largest:g}){hint}"
    )


def _pdf_text(x: float, y: float, size: float, text: str) -> str:
    """A line of Helvetica at (x, y), its parentheses and backslashes escaped."""
    safe = text.replace("\\", "\\\\").replace("(", "\\(").replace(")", "\\)")
    return f"BT /F1 {size:g} Tf {x:.4f} {y:.4f} Td ({safe}) Tj ET"


def _ruler(x0: float, y0: float) -> list[str]:
    """A 10 cm ruler from (x0, y0): a bar and a tick every millimetre, labelled every centimetre."""
    mm = 0.001 * PT_PER_M
    ops = ["% ruler", f"{x0:.4f} {y0:.4f} {RULER_M * PT_PER_M:.4f} 0.5000 re f"]
    for k in range(101):
        height = 8.0 if k % 10 == 0 else (5.5 if k % 5 == 0 else 3.5)
        ops.append(f"{x0 + k * mm - 0.2:.4f} {y0:.4f} 0.4000 {height:.4f} re f")
    for cm in range(11):
        label = f"{cm} cm" if cm == 10 else str(cm)
        ops.append(_pdf_text(x0 + cm * 10 * mm - 2, y0 + 10, 6, label))
    return ops


def board_content(layout: BoardLayout, pattern_text: str, square_m: float) -> str:
    """The page's content stream: the black squares, the text line above, the ruler below.

    Parameters
    ----------
    layout : BoardLayout
        From :func:`board_layout`.
    pattern_text : str
        The pattern as the text line shows it, e.g. ``"9x6"``.
    square_m : float
        The square's side in metres, for the text line.

    Returns
    -------
    str
        PDF content operators, one per line (ASCII).
    """
    n_cols, n_rows = layout.squares
    s = layout.square
    ops = ["% board", "0 g"]
    for j in range(n_rows):  # row 0 at the top; the top-left square is black
        for i in range(n_cols):
            if (i + j) % 2 == 0:
                y = layout.y0 + (n_rows - 1 - j) * s
                ops.append(f"{layout.x0 + i * s:.4f} {y:.4f} {s:.4f} {s:.4f} re f")
    top = layout.y0 + n_rows * s + QUIET_PT
    ruler_x = (layout.page_w - RULER_M * PT_PER_M) / 2
    text_x = min(layout.x0, ruler_x)  # a small board's left edge may be too far right for the text
    ops.append("% text")
    ops.append(
        _pdf_text(
            text_x,
            top + 9,
            8,
            f"camlab board: pattern {pattern_text} inner corners ({n_cols} x {n_rows} squares), "
            f"square {square_m:g} m = {square_m * 1000:g} mm",
        )
    )
    ops.append(
        _pdf_text(text_x, top, 8, "Print at 100 % / actual size; check the ruler measures 10 cm.")
    )
    ops += _ruler(ruler_x, layout.y0 - QUIET_PT - BAND_PT)
    return "\n".join(ops) + "\n"


def pdf_bytes(page_w: float, page_h: float, content: str) -> bytes:
    """A one-page PDF 1.4 file: the page size in points and its uncompressed content stream.

    Parameters
    ----------
    page_w, page_h : float
        The page's MediaBox in points.
    content : str
        ASCII content operators (:func:`board_content`).

    Returns
    -------
    bytes
        The file, with a correct cross-reference table.
    """
    stream = content.encode("ascii")
    objects = [
        b"<< /Type /Catalog /Pages 2 0 R >>",
        b"<< /Type /Pages /Kids [3 0 R] /Count 1 >>",
        (
            f"<< /Type /Page /Parent 2 0 R /MediaBox [0 0 {page_w:.4f} {page_h:.4f}] "
            f"/Contents 4 0 R /Resources << /Font << /F1 5 0 R >> >> >>"
        ).encode("ascii"),
        b"<< /Length %d >>\nstream\n" % len(stream) + stream + b"endstream",
        b"<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica >>",
    ]
    out = bytearray(b"%PDF-1.4\n")
    offsets = []
    for number, body in enumerate(objects, 1):
        offsets.append(len(out))
        out += b"%d 0 obj\n" % number + body + b"\nendobj\n"
    xref = len(out)
    out += b"xref\n0 %d\n0000000000 65535 f \n" % (len(objects) + 1)
    out += b"".join(b"%010d 00000 n \n" % off for off in offsets)
    out += b"trailer\n<< /Size %d /Root 1 0 R >>\nstartxref\n%d\n%%%%EOF\n" % (
        len(objects) + 1,
        xref,
    )
    return bytes(out)


def add_board(p: argparse.ArgumentParser) -> None:
    """The arguments of ``camlab board``: ``--pattern``, ``--square``, ``--out`` and ``--paper``.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The subcommand's parser; its arguments are added in place.
    """
    p.add_argument(
        "--pattern",
        default="9x6",
        help="inner corners COLSxROWS, as `camlab calibrate --pattern` (default 9x6: 10 x 7 squares)",
    )
    p.add_argument(
        "--square",
        type=float,
        default=0.025,
        help="side of one square in metres, as `camlab calibrate --square` (default 0.025)",
    )
    p.add_argument("--out", default="board.pdf", help="the PDF to write (default board.pdf)")
    p.add_argument("--paper", choices=sorted(PAPERS), default="a4", help="paper size (default a4)")


def run_board(args: argparse.Namespace) -> int:
    """Write the board's PDF at true scale, keeping a copy of a file it replaces.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed arguments of ``camlab board`` (:func:`add_board`).

    Returns
    -------
    int
        0.

    Raises
    ------
    CamlabInputError
        On an error the user can fix; :func:`camlab.cli.main` prints it and exits with status 2.
    """
    from .._files import atomic_output, check_output_path, keep_a_copy
    from ..calibration import parse_pattern

    layout = board_layout(args.pattern, args.square, args.paper)
    out = check_output_path(args.out, "--out", (".pdf",))
    cols, rows = parse_pattern(args.pattern, "--pattern")
    data = pdf_bytes(
        layout.page_w, layout.page_h, board_content(layout, f"{cols}x{rows}", args.square)
    )
    copy = keep_a_copy(out, "--out")
    with atomic_output(out, "--out") as tmp:
        tmp.write_bytes(data)
    paper = "A4" if args.paper == "a4" else "Letter"
    print(
        f"wrote {out}: {layout.squares[0]} x {layout.squares[1]} squares of "
        f"{args.square * 1000:g} mm ({cols}x{rows} inner corners) on {paper} {layout.orientation}"
    )
    if copy is not None:
        print(f"kept the previous {out.name} as {copy.name}")
    print(
        "print it at 100 % (actual size, not 'fit to page'), check that the ruler measures 10 cm, "
        f"and glue it flat; then: camlab calibrate photos/*.jpg --pattern {cols}x{rows} "
        f"--square {args.square:g}"
    )
    return 0
