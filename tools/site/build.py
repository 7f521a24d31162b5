"""Build the course as a static website: ``make site`` (``python tools/site/build.py site``).

Every lesson is executed top to bottom in a fresh kernel (two at a time), then exported
with nbconvert and the ``camlab`` template beside this file. The site is flat::

    site/index.html          lessons/README.md: the lesson table
    site/conventions.html    docs/conventions.md (and any other Markdown file a page links to)
    site/NN_slug.html        one page per executed lesson, with previous/next links
    site/figures/*.png       every figure and demo, as the static PNG its display bundle carries
    site/static/             JupyterLab's notebook CSS, site.css and a local MathJax 3

Why nbconvert with a template: the lessons are notebooks and nbconvert is what Jupyter
itself uses to turn them into HTML, so code, outputs and Markdown look as they do in
JupyterLab with one small template on top (navigation, local MathJax, alt text). It
needs nothing beyond the test environment's Python packages and MathJax from the npm
registry. Jupyter Book 2 / MyST would bring its own Node toolchain, theme and a second
Markdown dialect to learn for a dozen pages; Sphinx + myst-nb the same in Python.

Figures come from the display bundles (see ``camlab.plotting.static``): the PNG entry,
with its alt text from the output metadata. The executed notebooks keep their widget
state (what each live figure and control was set to, which the tests read: no figure
shows ipympl's "Figure N" header); the pages drop it, so nothing on a page needs a widget
manager or a kernel.

The executed notebooks are kept in ``--executed`` (default ``build/executed``) for the
tests (tests/test_site.py also checks their outputs for stray reprs and warnings). Nothing is fetched from the network; MathJax must be installed first
(``make site-deps`` puts it in ``build/npm``).
"""

from __future__ import annotations

import argparse
import concurrent.futures
import json
import os
import re
import shutil
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent
MATHJAX = REPO / "build" / "npm" / "node_modules" / "mathjax" / "es5"
# MathJax files the pages load: the combined TeX component, its fonts, and the parts it
# loads on demand (TeX extensions, accessibility, the menu's options).
MATHJAX_PARTS = ("tex-chtml.js", "output/chtml/fonts/woff-v2", "input/tex/extensions", "a11y", "ui")
LINK = re.compile(r'(href|src)="([^"]*)"')


@dataclass
class Page:
    """One page of the site: its source file in the repository and its file name on the site."""

    source: Path  # relative to the repository
    href: str
    title: str
    notebook: dict = field(default_factory=dict, repr=False)


def execute(path: Path, executed_dir: Path) -> Path:
    """Run one lesson top to bottom in a fresh kernel; save it with its widget state (for the tests)."""
    import nbformat
    from nbclient import NotebookClient

    nb = nbformat.read(path, as_version=4)
    client = NotebookClient(
        nb,
        timeout=600,
        kernel_name="python3",
        store_widget_state=True,
        resources={"metadata": {"path": str(path.parent)}},
    )
    client.execute()
    out = executed_dir / path.name
    nbformat.write(nb, out)
    return out


def execute_all(lessons: list[Path], executed_dir: Path, jobs: int) -> list[Path]:
    executed_dir.mkdir(parents=True, exist_ok=True)
    os.environ.pop("CAMLAB_FIGURE_MODE", None)  # the lessons' own %matplotlib widget decides
    with concurrent.futures.ProcessPoolExecutor(max_workers=jobs) as pool:
        futures = [pool.submit(execute, path, executed_dir) for path in lessons]
        return [f.result() for f in futures]


def _title(markdown: str, fallback: str) -> str:
    match = re.search(r"^#\s+(.+)$", markdown, flags=re.MULTILINE)
    return match.group(1).strip() if match else fallback


def _markdown_notebook(text: str) -> dict:
    import nbformat

    return nbformat.v4.new_notebook(cells=[nbformat.v4.new_markdown_cell(text)])


def _linked_markdown(markdown: str, source: Path) -> set[Path]:
    """Repository Markdown files that ``markdown`` (found in ``source``) links to."""
    found = set()
    for target in re.findall(r"\]\(([^)#\s]+\.md)(?:#[^)]*)?\)", markdown):
        if "://" not in target:
            path = (REPO / source.parent / target).resolve()
            if path.is_file():
                found.add(path.relative_to(REPO))
    return found


def collect_pages(executed: list[Path], lessons: list[Path]) -> list[Page]:
    """The index, the lessons in order, the conventions and every Markdown page they link to."""
    import nbformat

    pages = []
    readme = Path("lessons/README.md")
    pages.append(
        Page(
            readme,
            "index.html",
            "camlab lessons",
            _markdown_notebook((REPO / readme).read_text("utf-8")),
        )
    )
    for run, lesson in zip(executed, lessons, strict=True):
        nb = nbformat.read(run, as_version=4)
        nb.metadata.pop("widgets", None)  # static pages: no widget manager, no script from a CDN
        first = "".join(nb.cells[0].source) if nb.cells else ""
        pages.append(
            Page(lesson.relative_to(REPO), lesson.stem + ".html", _title(first, lesson.stem), nb)
        )
    todo = [Path("docs/conventions.md")]
    for page in pages:
        text = "\n".join(
            "".join(c.source) for c in page.notebook.cells if c.cell_type == "markdown"
        )
        todo += sorted(_linked_markdown(text, page.source))
    known = {p.source for p in pages}
    while todo:
        source = todo.pop(0)
        if source in known:
            continue
        known.add(source)
        text = (REPO / source).read_text("utf-8")
        href = (
            "conventions.html"
            if source == Path("docs/conventions.md")
            else str(source.with_suffix(".html")).replace("/", "-")
        )
        pages.append(Page(source, href, _title(text, source.stem), _markdown_notebook(text)))
        todo += sorted(_linked_markdown(text, source))
    return pages


def rewrite_links(html: str, page: Page, hrefs: dict[Path, str]) -> tuple[str, list[str]]:
    """Point links to repository files at their pages on the site; return the ones left dangling."""
    dangling = []

    def fix(match: re.Match) -> str:
        attr, url = match.groups()
        if attr != "href" or not url or url.startswith(("#", "data:", "mailto:")) or "://" in url:
            return match.group(0)
        path, _, fragment = url.partition("#")
        if path.startswith("figures/") or path.startswith("static/") or path in set(hrefs.values()):
            return match.group(0)
        target = (REPO / page.source.parent / path).resolve()
        try:
            site_href = hrefs[target.relative_to(REPO)]
        except (KeyError, ValueError):
            dangling.append(url)
            return match.group(0)
        return f'{attr}="{site_href}{"#" + fragment if fragment else ""}"'

    return LINK.sub(fix, html), dangling


def exporter():
    from nbconvert import HTMLExporter
    from nbconvert.preprocessors import ExtractOutputPreprocessor

    exp = HTMLExporter(
        template_name="camlab",
        extra_template_basedirs=[str(HERE / "templates")],
        exclude_input_prompt=True,
        exclude_output_prompt=True,
    )
    # Static pages show a bundle's PNG, never its widget view (no kernel, no widget manager).
    exp.display_data_priority = [
        "image/png",
        "text/html",
        "text/markdown",
        "image/svg+xml",
        "image/jpeg",
        "text/latex",
        "text/plain",
    ]
    exp.register_preprocessor(
        ExtractOutputPreprocessor(extract_output_types={"image/png", "image/jpeg"}), enabled=True
    )
    return exp


def render(pages: list[Page], out: Path) -> list[str]:
    """Write every page and its figures; return the dangling links found."""
    exp = exporter()
    hrefs = {p.source: p.href for p in pages}
    lessons = [p for p in pages if p.source.suffix == ".ipynb"]
    (out / "figures").mkdir(parents=True, exist_ok=True)
    dangling = []
    for page in pages:
        i = lessons.index(page) if page in lessons else None
        nav = {
            "page": page.href,
            "prev": None,
            "next": None,
            "notebook": str(page.source) if i is not None else "",
        }
        if i is not None:
            nav["prev"] = (
                {"href": lessons[i - 1].href, "title": lessons[i - 1].title}
                if i > 0
                else {"href": "index.html", "title": "All lessons"}
            )
            if i + 1 < len(lessons):
                nav["next"] = {"href": lessons[i + 1].href, "title": lessons[i + 1].title}
        resources = {
            "camlab": nav,
            "unique_key": Path(page.href).stem,
            "output_files_dir": "figures",
            "metadata": {"name": page.title},
        }
        html, res = exp.from_notebook_node(page.notebook, resources=resources)
        for name, data in res.get("outputs", {}).items():
            (out / name).write_bytes(data)
        html, bad = rewrite_links(html, page, hrefs)
        for other in lessons:  # a link written as a file name reads as the lesson's title
            html = html.replace(
                f'href="{other.href}">{other.source.name}</a>',
                f'href="{other.href}">{other.title}</a>',
            )
        dangling += [f"{page.href}: {url}" for url in bad]
        (out / page.href).write_text(html, encoding="utf-8")
    return dangling


def copy_static(out: Path) -> None:
    if not (MATHJAX / "tex-chtml.js").is_file():
        sys.exit(
            f"MathJax is missing at {MATHJAX}: run `make site-deps` (npm install of mathjax@3)"
        )
    static = out / "static"
    static.mkdir(parents=True, exist_ok=True)
    lab = Path(sys.prefix) / "share" / "jupyter" / "nbconvert" / "templates" / "lab" / "static"
    (static / "lab.css").write_text(
        (lab / "index.css").read_text("utf-8") + (lab / "theme-light.css").read_text("utf-8"),
        encoding="utf-8",
    )
    shutil.copy(HERE / "site.css", static / "site.css")
    for part in MATHJAX_PARTS:
        src, dst = MATHJAX / part, static / "mathjax" / part
        if src.is_dir():
            shutil.copytree(src, dst, dirs_exist_ok=True)
        else:
            dst.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(src, dst)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "out", type=Path, nargs="?", default=REPO / "site", help="output folder (replaced)"
    )
    parser.add_argument(
        "--executed",
        type=Path,
        default=REPO / "build" / "executed",
        help="where the executed notebooks go (kept for the tests)",
    )
    parser.add_argument("--jobs", type=int, default=2, help="lessons executed at once")
    parser.add_argument("--lessons", nargs="*", help="only these lesson files (default: all)")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    lessons = (
        sorted(Path(p).resolve() for p in args.lessons)
        if args.lessons
        else sorted((REPO / "lessons").glob("[0-9][0-9]_*.ipynb"))
    )
    out = args.out.resolve()
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    copy_static(out)
    executed = execute_all(lessons, args.executed.resolve(), args.jobs)
    ran = time.perf_counter() - start
    pages = collect_pages(executed, lessons)
    dangling = render(pages, out)
    for link in dangling:
        print(f"warning: link to a file that is not on the site: {link}", file=sys.stderr)
    size = sum(f.stat().st_size for f in out.rglob("*") if f.is_file())
    manifest = {
        "pages": [p.href for p in pages],
        "lessons": [p.href for p in pages if p.source.suffix == ".ipynb"],
    }
    (out / "pages.json").write_text(json.dumps(manifest, indent=1), encoding="utf-8")
    print(
        f"site: {len(pages)} pages in {out} ({size / 1e6:.1f} MB); executed {len(lessons)} lessons in "
        f"{ran:.0f} s, total {time.perf_counter() - start:.0f} s"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
