"""``camlab board``: the PDF is read back and every square, the ruler and the page measured."""

import re
from collections import Counter

import pytest

from camlab import cli

PT_PER_M = 72 / 0.0254
RECT = re.compile(r"^(-?[\d.]+) (-?[\d.]+) ([\d.]+) ([\d.]+) re f$")


def read_pdf(path):
    """The page size and the content stream's rectangles, by section (``% board``, ``% ruler``)."""
    data = path.read_bytes()
    assert data.startswith(b"%PDF-1.4\n") and data.rstrip().endswith(b"%%EOF")
    start = int(re.search(rb"startxref\n(\d+)\n", data).group(1))
    assert data[start:].startswith(b"xref\n")
    offsets = re.findall(rb"(\d{10}) 00000 n ", data[start:])
    for number, offset in enumerate(offsets, 1):  # the cross-reference table points at each object
        assert data[int(offset) :].startswith(b"%d 0 obj" % number)
    box = re.search(rb"/MediaBox \[0 0 ([\d.]+) ([\d.]+)\]", data)
    length = int(re.search(rb"/Length (\d+) >>\nstream\n", data).group(1))
    body = data.index(b"stream\n") + len(b"stream\n")
    stream = data[body : body + length].decode("ascii")
    assert data[body + length :].startswith(b"endstream")
    sections, name = {}, None
    for line in stream.splitlines():
        if line.startswith("% "):
            name = line[2:]
            sections[name] = {"rects": [], "text": []}
        elif (m := RECT.match(line)) is not None:
            sections[name]["rects"].append(tuple(float(v) for v in m.groups()))
        elif line.startswith("BT "):
            literal = re.search(r"\((.*)\) Tj", line).group(1)
            sections[name]["text"].append(re.sub(r"\\(.)", r"\1", literal))
    return float(box.group(1)), float(box.group(2)), sections


def run(args, capsys):
    status = cli.main(["board", *args])
    out = capsys.readouterr()
    return status, out.out, out.err


def test_9x6_board_of_25_mm_squares_is_true_to_scale_and_centred(tmp_path, capsys):
    out = tmp_path / "board.pdf"
    status, text, _ = run(["--pattern", "9x6", "--square", "0.025", "--out", str(out)], capsys)
    assert status == 0 and "10 x 7 squares of 25 mm" in text and "A4 landscape" in text
    page_w, page_h, sections = read_pdf(out)
    assert page_w == pytest.approx(0.297 * PT_PER_M, abs=0.01)  # A4 landscape: 841.89 pt
    assert page_h == pytest.approx(0.210 * PT_PER_M, abs=0.01)
    squares = sections["board"]["rects"]
    side = 0.025 * PT_PER_M
    assert side == pytest.approx(70.866, abs=0.001)
    for _, _, w, h in squares:
        assert w == pytest.approx(side, abs=0.01) and h == pytest.approx(side, abs=0.01)
    # the black squares are every other one of a 10 x 7 grid, the top-left one black
    cols = sorted({round((x - squares[0][0]) / side) for x, *_ in squares})
    rows = sorted({round((y - squares[-1][1]) / side) for _, y, *_ in squares})
    assert cols == list(range(10)) and rows == list(range(7)) and len(squares) == 35
    left = min(x for x, *_ in squares)
    bottom = min(y for _, y, *_ in squares)
    right = max(x + w for x, _, w, _ in squares)
    top = max(y + h for _, y, _, h in squares)
    assert right - left == pytest.approx(10 * side, abs=0.01)
    assert top - bottom == pytest.approx(7 * side, abs=0.01)
    assert (left + right) / 2 == pytest.approx(page_w / 2, abs=0.01)
    assert (bottom + top) / 2 == pytest.approx(page_h / 2, abs=0.01)
    top_left = next(s for s in squares if s[0] == left and s[1] + s[3] == pytest.approx(top))
    assert top_left
    # the ruler: a 10 cm bar and ticks whose end centres are 10 cm apart
    bar, *ticks = sections["ruler"]["rects"]
    assert bar[2] == pytest.approx(283.46, abs=0.01)
    centres = [x + w / 2 for x, _, w, _ in ticks]
    assert len(ticks) == 101 and centres[-1] - centres[0] == pytest.approx(283.46, abs=0.01)
    assert Counter(round(h, 1) for *_, h in ticks)[8.0] == 11  # one tall tick per centimetre
    assert bar[1] + 16 < bottom and sections["ruler"]["text"][-1] == "10 cm"
    line1, line2 = sections["text"]["text"]
    assert "9x6 inner corners (10 x 7 squares)" in line1 and "25 mm" in line1
    assert "100 %" in line2 and "10 cm" in line2


def test_a_small_board_goes_portrait_and_letter_paper_is_letter(tmp_path, capsys):
    out = tmp_path / "small.pdf"
    assert run(["--pattern", "6x4", "--square", "0.02", "--out", str(out)], capsys)[0] == 0
    page_w, page_h, sections = read_pdf(out)
    assert (page_w, page_h) == (pytest.approx(595.276, abs=0.01), pytest.approx(841.89, abs=0.01))
    assert len(sections["board"]["rects"]) == 18  # half of 7 x 5, rounded up
    out = tmp_path / "letter.pdf"
    assert run(["--square", "0.026", "--paper", "letter", "--out", str(out)], capsys)[0] == 0
    page_w, page_h, sections = read_pdf(out)
    assert (page_w, page_h) == (pytest.approx(792.0), pytest.approx(612.0))
    assert sections["board"]["rects"][0][2] == pytest.approx(0.026 * PT_PER_M, abs=0.01)


def test_an_existing_file_is_kept_before_it_is_replaced(tmp_path, capsys):
    out = tmp_path / "board.pdf"
    out.write_bytes(b"my old board")
    status, text, _ = run(["--out", str(out)], capsys)
    (copy,) = [p for p in tmp_path.iterdir() if p.name != "board.pdf"]
    assert status == 0 and copy.name.startswith("board.previous-") and copy.suffix == ".pdf"
    assert (
        copy.read_bytes() == b"my old board"
        and f"kept the previous board.pdf as {copy.name}" in text
    )
    assert read_pdf(out)[2]["board"]["rects"]


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--pattern", "9by6"], "--pattern: expected inner corners as whole numbers"),
        (["--pattern", "1x6"], "--pattern: expected at least 2 x 2"),
        (["--square", "0"], "--square: expected the side of one square in metres"),
        (["--square", "-0.025"], "--square: expected the side of one square in metres"),
        (["--square", "nan"], "--square: expected the side of one square in metres"),
        (["--square", "inf"], "--square: expected a finite number of metres"),
        (["--square", "25"], "the largest square that fits is 0.0255 m"),
        (
            ["--square", "0.026"],
            "the largest square that fits is 0.0255 m (--square 0.0255), or print on --paper letter",
        ),
        (["--out", "missing/board.pdf"], "--out: the folder 'missing' does not exist"),
        (["--out", "board.png"], "--out: expected a file name ending in .pdf"),
    ],
)
def test_bad_input_is_refused_with_a_message_naming_the_argument(
    args, message, tmp_path, capsys, monkeypatch
):
    monkeypatch.chdir(tmp_path)
    status, _, err = run(args, capsys)
    assert status == 2 and message in err, err
    assert list(tmp_path.iterdir()) == []  # nothing written


def test_board_is_registered_beside_calibrate():
    assert list(cli.COMMANDS).index("board") == list(cli.COMMANDS).index("calibrate") + 1
    args = cli.build_parser().parse_args(["board", "--pattern", "9x6", "--square", "0.025"])
    assert args.run is cli.COMMANDS["board"][2] and args.out == "board.pdf" and args.paper == "a4"
