"""Render what a student sees in one lesson, for the review loop (../shared/REVIEW.md, step 1).

    python tools/render_review.py 01 review/01
    python tools/render_review.py 01 review/01 --setting "pinhole_projection:focal_mm=90,distance=1.0"

writes into the folder:

* ``NN_name.executed.ipynb``: the lesson run top to bottom in a fresh kernel (as the site
  builds it: no widget state, every figure and demo as its static PNG);
* ``NN_cellCC_K.png``: every image output, by cell index (0-based) and output number;
* ``NN_<demo>_default.png``, ``NN_<demo>_<control>=<value>.png``: every demo of the lesson
  at its default and at every value of each control's sweep, each control moved from the
  default alone, drawn through the live path (the frame a moved control sends, not a full
  redraw); ``--setting`` adds the settings the prose recommends (several controls at once,
  file ``NN_<demo>_<control>=<value>,....png``);
* ``NN_<demo>_<setting>.txt`` beside each demo frame: the text the demo shows beside its figure at that
  setting (its readouts: numbers, warnings), which a PNG of the canvas does not capture.
"""

from __future__ import annotations

import argparse
import base64
import os
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "tools" / "site"))


def save_static_figures(executed, prefix: str, out: Path) -> int:
    """Every image/png output of an executed notebook, as ``<prefix>_cellCC_K.png``; returns the count."""
    count = 0
    for index, cell in enumerate(executed.cells):
        pngs = [
            o["data"]["image/png"]
            for o in cell.get("outputs", [])
            if "image/png" in o.get("data", {})
        ]
        for k, png in enumerate(pngs):
            (out / f"{prefix}_cell{index:02d}_{k}.png").write_bytes(base64.b64decode(png))
            count += 1
    return count


def parse_setting(text: str) -> tuple[str, dict]:
    """``"demo:a=1,b=true"`` -> ("demo", {"a": 1, "b": True}) (numbers, booleans, else strings).

    A comma splits only before the next ``name=``, so a text value may hold commas
    (``"demo:label=a, b,n=2"`` -> {"label": "a, b", "n": 2}).
    """
    import re

    demo, _, rest = text.partition(":")
    values = {}
    for item in filter(None, re.split(r",(?=\s*[A-Za-z_]\w*\s*=)", rest)):
        key, _, raw = item.partition("=")
        low = raw.strip().lower()
        if low in ("true", "false"):
            values[key.strip()] = low == "true"
            continue
        try:
            values[key.strip()] = int(raw) if raw.strip().lstrip("-").isdigit() else float(raw)
        except ValueError:
            values[key.strip()] = raw.strip()
    return demo.strip(), values


def readout_text(widget) -> str:
    """The text of every HTML widget inside ``widget`` (a demo's readouts), tags removed, in display order."""
    import html
    import re

    texts, stack = [], [widget]
    while stack:
        w = stack.pop(0)
        stack[:0] = list(getattr(w, "children", ()))
        if type(w).__name__ == "HTML" and w.value:
            texts.append(html.unescape(re.sub(r"<[^>]+>", "", w.value)).strip())
    return "\n\n".join(t for t in texts if t)


def render_demos(lesson: str, out: Path, settings: list[tuple[str, dict]]) -> int:
    """Every demo of ``lesson`` at its default, its sweep and ``settings``, through the live path."""
    import matplotlib.pyplot as plt

    from camlab.widgets import all_demos

    count = 0
    for name, spec in sorted(all_demos().items()):
        if spec.lesson != lesson:
            continue
        points = [{}] + [
            {control: value} for control, values in spec.sweep.items() for value in values
        ]
        points += [values for demo, values in settings if demo == name]
        for point in points:
            demo = spec.builder()  # each point from the default, so one control moves at a time
            demo.set(**point)
            label = (
                ",".join(f"{k}={v}" for k, v in point.items()).replace("/", "-").replace(" ", "")
                or "default"
            )
            plt.imsave(out / f"{lesson}_{name}_{label}.png", demo.view.pixels())
            text = readout_text(demo.widget)
            if text:
                (out / f"{lesson}_{name}_{label}.txt").write_text(text + "\n")
            plt.close(demo.figure)
            count += 1
    unknown = {demo for demo, _ in settings} - {
        n for n, s in all_demos().items() if s.lesson == lesson
    }
    if unknown:
        raise SystemExit(f"--setting: no demo {sorted(unknown)} in lesson {lesson}")
    return count


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("lesson", help="lesson number, e.g. 01")
    parser.add_argument(
        "out", type=Path, help="folder for the executed notebook and the PNGs (created)"
    )
    parser.add_argument(
        "--setting", action="append", default=[], help='"demo:control=value,..." (repeatable)'
    )
    args = parser.parse_args(argv)
    import nbformat

    from build import execute
    from camlab.classroom.lessons import find_lesson

    args.out.mkdir(parents=True, exist_ok=True)
    path = find_lesson(args.lesson)
    executed = execute(path, args.out)
    final = executed.with_name(f"{path.stem}.executed.ipynb")
    executed.replace(final)
    figures = save_static_figures(nbformat.read(final, as_version=4), args.lesson, args.out)
    os.environ["CAMLAB_FIGURE_MODE"] = "agg"
    demos = render_demos(args.lesson, args.out, [parse_setting(s) for s in args.setting])
    print(f"{final}: {figures} static figures, {demos} demo frames in {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
