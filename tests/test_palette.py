"""Every colour a figure uses is named in ``camlab.plotting.palette``: none is spelt anywhere else.

The scan reads the source of camlab/ (its syntax tree, not its text) and finds each string
constant that matplotlib accepts as a colour (``matplotlib.colors.is_color_like``) in a place
where it is used as one:

- a keyword argument named like a colour (``color=``, ``colors=``, ``c=``, ``fc=``, ``ec=``,
  ``mec=``, ``mfc=``, ``facecolor=``, ``edgecolor=``, ``foreground=``, any name holding
  "colo"), also inside ``dict(...)``, lists and conditional expressions;
- a ``{"color": ...}`` dict entry, a parameter default or an assignment whose name holds "colo";
- a positional argument of a call named like a colour (``set_color``, ``set_facecolor``...)
  and the colour argument of ``palette.halo``;
- the format string of ``plot`` (``"r-"``, ``"bo"``: the letter is a colour).

The rule: a colour with a hue comes from the palette. Neutrals (black, white, the grey levels
``"0.0"``-``"1.0"``: red = green = blue) and ``"none"`` may be spelt directly, as the palette
module says: they have no hue to mean something or to collapse for a colour-blind reader.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import camlab

ROOT = Path(camlab.__file__).parent
PALETTE = ROOT / "plotting" / "palette.py"

_COLOUR_KEYWORDS = {
    "c",
    "fc",
    "ec",
    "mec",
    "mfc",
    "foreground",
}
_PLOT_METHODS = {"plot", "semilogx", "semilogy", "loglog", "errorbar"}


def _colourish(name: str) -> bool:
    return name in _COLOUR_KEYWORDS or "colo" in name.lower()


def _is_raw_colour(value) -> bool:
    """True for a colour with a hue (not a neutral, not "none"): a string or an RGB(A) tuple."""
    from matplotlib.colors import is_color_like, to_rgb

    if (isinstance(value, str) and value.lower() == "none") or not is_color_like(value):
        return False
    r, g, b = to_rgb(value)
    return not (r == g == b)


def _format_colour(fmt: str) -> str | None:
    """The colour a plot format string like ``"r--"`` names, or None (also for non-formats)."""
    from matplotlib.axes._base import _process_plot_format

    try:
        return _process_plot_format(fmt)[2]
    except ValueError:
        return None


def _strings(node: ast.AST):
    for n in ast.walk(node):
        if isinstance(n, ast.Constant) and isinstance(n.value, str):
            yield n


def raw_colours_in(source: str, filename: str = "<source>") -> list[str]:
    """Each raw colour of ``source`` used as a colour, as ``"file:line: 'value' (where)"``."""
    tree = ast.parse(source, filename)
    found: list[tuple[int, str, str]] = []

    def check(node: ast.AST, where: str) -> None:
        found.extend((n.lineno, n.value, where) for n in _strings(node) if _is_raw_colour(n.value))

    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            for kw in node.keywords:
                if kw.arg and _colourish(kw.arg):
                    check(kw.value, f"{kw.arg}=")
            func = node.func
            name = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")
            if name == "halo":
                for arg in node.args[1:]:
                    check(arg, "halo colour")
            elif _colourish(name):
                for arg in node.args:
                    check(arg, f"{name}()")
            if name in _PLOT_METHODS:
                for arg in node.args:
                    if isinstance(arg, ast.Constant) and isinstance(arg.value, str):
                        colour = _format_colour(arg.value)
                        if colour is not None and _is_raw_colour(colour):
                            found.append((arg.lineno, arg.value, "plot format"))
        elif isinstance(node, ast.Dict):
            for key, value in zip(node.keys, node.values, strict=True):
                if isinstance(key, ast.Constant) and isinstance(key.value, str):
                    if _colourish(key.value):
                        check(value, f"{key.value!r}:")
        elif isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda):
            a = node.args
            positional = a.posonlyargs + a.args
            pairs = list(
                zip(positional[len(positional) - len(a.defaults) :], a.defaults, strict=True)
            )
            pairs += [
                (arg, d)
                for arg, d in zip(a.kwonlyargs, a.kw_defaults, strict=True)
                if d is not None
            ]
            for arg, default in pairs:
                if _colourish(arg.arg):
                    check(default, f"default of {arg.arg}")
        elif isinstance(node, ast.Assign | ast.AnnAssign) and node.value is not None:
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            names = [
                n.id if isinstance(n, ast.Name) else n.attr
                for t in targets
                for n in ast.walk(t)
                if isinstance(n, ast.Name | ast.Attribute)
            ]
            if any(_colourish(n) for n in names):
                check(node.value, "assignment")
    return [f"{filename}:{line}: {value!r} ({where})" for line, value, where in sorted(set(found))]


def raw_colours(root: Path = ROOT) -> list[str]:
    """Every raw colour in the package outside the palette module."""
    return [
        hit
        for path in sorted(root.rglob("*.py"))
        if path != PALETTE
        for hit in raw_colours_in(path.read_text(), str(path.relative_to(root.parent)))
    ]


def test_no_raw_colour_outside_the_palette():
    """A colour with a hue is ``palette.NAME``; add a name to the palette rather than spell one."""
    assert raw_colours() == []


@pytest.mark.parametrize(
    "line",
    [
        'ax.plot(x, y, color="tab:red")',
        'ax.axhspan(0, 1, fc="#CC3311", alpha=0.2)',
        'ax.text(0, 0, "A", bbox=dict(fc="white", ec="tab:red"))',
        'ax.scatter(x, y, c=["tab:blue" if ok else "tab:red" for ok in good])',
        'ax.plot(x, y, "r--")',
        'ln.set_color("yellow")',
        'art.set_path_effects(palette.halo(1.0, "magenta"))',
        'colours = ("tab:blue", "tab:orange")',
        'style = {"color": "C1", "lw": 2}',
        'def box(ax, color: str = "red"):\n    pass',
    ],
)
def test_the_scan_catches_a_planted_colour(line, tmp_path):
    """Each way a colour reaches matplotlib is found, in a file of the package's own layout."""
    package = tmp_path / "camlab"
    (package / "plotting").mkdir(parents=True)
    (package / "plotting" / "palette.py").write_text('RED = "#CC3311"\n')
    (package / "widgets.py").write_text(f"from .plotting import palette\n\n{line}\n")
    assert len(raw_colours(package)) >= 1
    assert raw_colours(package)[0].startswith("camlab/widgets.py:3: ")


def test_the_scan_lets_neutrals_and_palette_names_pass():
    source = (
        'ax.plot(x, y, "k--", color=palette.RED, mec="k", mfc="none")\n'
        'ax.axhline(0, color="0.6", lw=0.5)\n'
        'ax.text(0, 0, "red", bbox=dict(fc="white", ec="0.3"), label="tab:red")\n'
        'box.set_path_effects(palette.halo(1.5, "black"))\n'
        'ax.set_title(f"{x:.3g}", loc="center")\n'
        'ax.imshow(im, cmap="gray")\n'
    )
    assert raw_colours_in(source) == []


def test_the_palette_names_are_colours():
    from matplotlib.colors import is_color_like

    from camlab.plotting import palette

    names = [n for n in vars(palette) if n.isupper()]
    for name in names:
        value = getattr(palette, name)
        for colour in value if isinstance(value, tuple) else (value,):
            assert is_color_like(colour), f"palette.{name} = {colour!r} is not a colour"
