"""Normalise notebooks in place: valid nbformat 4.5 with stable cell ids, stripped, written as Jupyter writes them.

Usage: python tools/strip_notebooks.py lessons/*.ipynb      (``make strip``)

For each notebook (see :func:`normalised`):

* nbformat 4.5, every cell with an id: ids already there are kept; a missing, invalid or
  repeated one gets a stable id (a hash of the file name, the cell's position and source),
  so running the tool twice, or on two clones, gives the same ids;
* outputs, execution counts, cell timings and collapsed/scrolled state, and the notebook's
  saved widget state are dropped; the kernelspec is ipykernel's (what JupyterLab records when
  it runs the lesson) and ``language_info`` keeps only the language name, so the metadata does
  not depend on the Python that last ran the lesson;
* written with nbformat exactly as the Jupyter server writes a notebook JupyterLab saves
  (sorted keys, indent 1, UTF-8 unescaped, sources split into lines, a trailing newline), and
  validated.

So opening a lesson in JupyterLab and saving it changes nothing but the kernel's
``language_info`` (and outputs, if cells ran), and ``make strip`` undoes even that.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import re
import sys
from pathlib import Path

import nbformat

KERNELSPEC = {"display_name": "Python 3 (ipykernel)", "language": "python", "name": "python3"}
TRANSIENT_CELL_METADATA = ("execution", "ExecuteTime", "collapsed", "scrolled")
VALID_ID = re.compile(r"^[a-zA-Z0-9-_]{1,64}$")  # nbformat 4.5's schema for cell ids


def _stable_id(name: str, index: int, source: str, taken: set[str]) -> str:
    for salt in itertools.count():
        cell_id = hashlib.sha256(f"{name}\0{index}\0{salt}\0{source}".encode()).hexdigest()[:8]
        if cell_id not in taken:
            return cell_id
    raise AssertionError("unreachable")


def _strip_cell(cell: dict) -> None:
    if cell["cell_type"] == "code":
        cell["outputs"] = []
        cell["execution_count"] = None
    metadata = cell.setdefault("metadata", {})
    for key in TRANSIENT_CELL_METADATA:
        metadata.pop(key, None)


def normalised(text: str, name: str) -> str:
    """The normalised form of notebook ``text`` (file ``name``, which seeds new cell ids).

    Raises ``nbformat.ValidationError`` if the result is still not a valid notebook.
    """
    nb = nbformat.from_dict(
        json.loads(text)
    )  # not nbformat.reads: it complains about what we fix here
    if nb.nbformat != 4:
        raise ValueError(f"{name}: expected nbformat 4, got {nb.nbformat}")
    nb.nbformat_minor = max(nb.nbformat_minor, 5)
    taken: set[str] = set()
    for index, cell in enumerate(nb.cells):
        cell["source"] = "".join(
            cell["source"]
        )  # nbformat splits it into lines again, as the server's save does
        if not (
            isinstance(cell.get("id"), str)
            and VALID_ID.match(cell["id"])
            and cell["id"] not in taken
        ):
            cell["id"] = _stable_id(name, index, cell["source"], taken)
        taken.add(cell["id"])
        _strip_cell(cell)
    nb.metadata.pop("widgets", None)
    nb.metadata["kernelspec"] = dict(KERNELSPEC)
    nb.metadata["language_info"] = {"name": "python"}
    nbformat.validate(nb)
    out = nbformat.writes(nb, version=nbformat.NO_CONVERT)
    return (
        out if out.endswith("\n") else out + "\n"
    )  # as nbformat.write (the server's save) ends the file


def strip(path: str | Path) -> bool:
    """Normalise one notebook in place; return True if the file changed."""
    path = Path(path)
    text = path.read_text(encoding="utf-8")
    new = normalised(text, path.name)
    if new != text:
        path.write_text(new, encoding="utf-8")
    return new != text


def main(argv: list[str]) -> int:
    if not argv or any(a in ("-h", "--help") for a in argv):
        print(
            __doc__.split("\n\n")[1]
            if argv
            else "give the notebooks to normalise, e.g. lessons/*.ipynb"
        )
        return 0 if argv else 2
    missing = [a for a in argv if not Path(a).is_file()]
    if missing:
        print(
            f"not a notebook file: {', '.join(missing)} (give .ipynb paths, e.g. lessons/*.ipynb)",
            file=sys.stderr,
        )
        return 2
    changed = [p for p in argv if strip(p)]
    print(
        f"normalised {len(changed)} of {len(argv)} notebooks"
        + (f": {', '.join(changed)}" if changed else "")
    )
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
