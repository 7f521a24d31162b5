"""The course website (`make site`, tools/site/build.py): built, then read as a visitor would.

The site is built once per run into a temporary folder (about 2 minutes), or taken from
CAMLAB_SITE_DIR when CI has just built it with `make site` (its executed notebooks are in
build/executed). Pages are served over HTTP on 127.0.0.1 and opened in headless Debian
Chromium, like tests/test_browser.py.
"""

import functools
import http.server
import json
import os
import re
import resource
import subprocess
import sys
import threading
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import urlsplit

import pytest

from camlab.widgets import all_demos

# Without CAMLAB_SITE_DIR the module's first test builds the site (all thirteen lessons executed) inside
# its deadline: about 2 min on a quiet 2-core machine, past 5 min under load. Still bounded.
pytestmark = [pytest.mark.site, pytest.mark.timeout(900)]

REPO = Path(__file__).resolve().parent.parent
LESSONS = sorted((REPO / "lessons").glob("[0-9][0-9]_*.ipynb"))
DEMOS = all_demos()
DEMO_CALL = re.compile(r"\bdemos\.(\w+)\(")
FIGURE_CALL = re.compile(r"\bplt\.(subplots|figure)\(")
# 3.3 MB a lesson: 30 MB was set for twelve lessons (about 2.5 each); with lesson 12 the site
# measured 32.3 MB, and 39.2 MB after the tenth review session's figures and demos (lessons 09,
# 11, 12), mostly photographs inside figures; 43.0 MB after the twelfth session's real-photo
# figures (lesson 09's real building panorama and its zooms, lesson 12's stereo rig and Middlebury)
MAX_BYTES = 3.5e6 * len(LESSONS)
# CPU seconds of building the site: 180 was set for twelve lessons; with lesson 12 and the real-photo
# figures a build measured 316 and 282 CPU s (2026-11-28, -29), most of it executing the lessons
# (issue 32's lessons row). 420 leaves a third over that: a lesson that doubles its time still fails.
MAX_BUILD_S = 420


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    given = os.environ.get("CAMLAB_SITE_DIR")
    if given:
        out, executed, seconds = Path(given).resolve(), REPO / "build" / "executed", None
        assert (out / "pages.json").is_file(), (
            f"CAMLAB_SITE_DIR={given} holds no built site: run `make site`"
        )
    else:
        base = tmp_path_factory.mktemp("site")
        out, executed = base / "site", base / "executed"
        cpu_before = _children_cpu()
        run = subprocess.run(
            [
                sys.executable,
                str(REPO / "tools" / "site" / "build.py"),
                str(out),
                "--executed",
                str(executed),
            ],
            capture_output=True,
            text=True,
        )
        seconds = (
            _children_cpu() - cpu_before
        )  # the build and its kernels; wall time varies with load
        assert run.returncode == 0, (
            f"the site build failed:\n{run.stdout[-2000:]}\n{run.stderr[-4000:]}"
        )
    return dict(
        out=out,
        executed=executed,
        seconds=seconds,
        pages=json.loads((out / "pages.json").read_text()),
    )


def _code_cells(nb: dict) -> list[tuple[str, list]]:
    return [
        ("".join(c["source"]), c.get("outputs", []))
        for c in nb["cells"]
        if c["cell_type"] == "code"
    ]


def expected_images(lesson: Path) -> int:
    """Figures and demos a lesson makes, counted from its source and the demo registry."""
    count = 0
    for source, _ in _code_cells(json.loads(lesson.read_text(encoding="utf-8"))):
        count += len(FIGURE_CALL.findall(source))
        count += sum(name in DEMOS for name in DEMO_CALL.findall(source))
    return count


def test_site_has_every_page_and_stays_small(site):
    pages = site["pages"]
    assert pages["pages"][0] == "index.html" and "conventions.html" in pages["pages"]
    assert pages["lessons"] == [p.stem + ".html" for p in LESSONS]
    size = sum(f.stat().st_size for f in site["out"].rglob("*") if f.is_file())
    assert size < MAX_BYTES, (
        f"the site is {size / 1e6:.1f} MB; the budget is {MAX_BYTES / 1e6:.0f} MB"
    )
    if site["seconds"] is not None:
        # CPU seconds of the build and its kernels: under MAX_BUILD_S the build ends within
        # 7 minutes even on one free core, however loaded the shared machine is now.
        assert site["seconds"] < MAX_BUILD_S, (
            f"the site took {site['seconds']:.0f} CPU s to build (budget {MAX_BUILD_S} s)"
        )


@pytest.mark.parametrize("lesson", LESSONS, ids=lambda p: p.name)
def test_executed_lesson_has_a_static_image_for_every_demo_and_figure(site, lesson):
    nb = json.loads((site["executed"] / lesson.name).read_text(encoding="utf-8"))
    demo_cells = 0
    for source, outputs in _code_cells(nb):
        displays = [
            o for o in outputs if o.get("output_type") in ("display_data", "execute_result")
        ]
        widgets = [o for o in displays if "application/vnd.jupyter.widget-view+json" in o["data"]]
        for out in widgets:
            assert "image/png" in out["data"], (
                f"{lesson.name}: a live figure without a static PNG:\n{source[:200]}"
            )
            alt = out.get("metadata", {}).get("image/png", {}).get("alt", "")
            assert len(alt) > 20 and not re.fullmatch(r"Figure( \d+)?\.?", alt), (
                f"{lesson.name}: weak alt text {alt!r}"
            )
        if any(name in DEMOS for name in DEMO_CALL.findall(source)):
            demo_cells += 1
            assert widgets, f"{lesson.name}: the demo cell shows no live widget:\n{source[:200]}"
    assert demo_cells, f"{lesson.name}: no demo cell found (calls like demos.<registered name>())"


WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"
WIDGET_STATE = "application/vnd.jupyter.widget-state+json"
STRAY_REPRS = ("Text(", "<matplotlib.", "[<matplotlib.", "<Figure ", "<IPython.core.display")
LOCAL_PATH = re.compile(
    r"(/tmp/|/var/folders/|/home/|/root/|/Users/|[A-Za-z]:\\Users\\|ipykernel_\d+)"
)


def _text(value) -> str:
    return "".join(value) if isinstance(value, list) else str(value)


def _output_problem(out: dict) -> str | None:
    """What is wrong with one output a reader sees (None when nothing is)."""
    kind = out.get("output_type")
    if kind == "stream":
        text = _text(out.get("text", ""))
        if out.get("name") == "stderr" and LOCAL_PATH.search(text):
            return f"stderr names a local path: {text.strip()[:160]!r}"
        return None
    data = out.get("data", {})
    if kind not in ("execute_result", "display_data") or WIDGET_VIEW in data:
        return None  # a live figure's text/plain is its alt text
    if set(data) & {
        "image/png",
        "text/html",
        "text/markdown",
        "text/latex",
        "image/svg+xml",
        "application/javascript",
    }:
        return None  # a rich output; its text/plain is the fallback nobody sees
    plain = _text(data.get("text/plain", "")).strip()
    if kind == "execute_result" and plain in ("True", "False"):
        return f"a stray {plain} ends the cell"
    if plain.startswith(STRAY_REPRS):
        return f"a stray repr {plain[:80]!r}"
    return None


def _canvas_problems(nb: dict) -> list[str]:
    """ipympl canvases (MPLCanvasModel) in the saved widget state that show the "Figure N" header."""
    state = nb.get("metadata", {}).get("widgets", {}).get(WIDGET_STATE, {}).get("state", {})
    canvases = {k: m["state"] for k, m in state.items() if m.get("model_name") == "MPLCanvasModel"}
    if not canvases:
        return ["no ipympl canvas in the saved widget state (execute with store_widget_state=True)"]
    return [
        f"canvas {k} shows ipympl's header {c.get('_figure_label', 'Figure')!r}"
        for k, c in canvases.items()
        if c.get("header_visible", True)
    ]


def output_problems(nb: dict) -> list[str]:
    """Everything in an executed lesson that a student should not see.

    A stray ``True``/``False`` or matplotlib repr ending a cell, a warning naming a local or
    temporary path, and a live figure with ipympl's "Figure N" header.
    """
    problems = []
    cells = [c for c in nb["cells"] if c["cell_type"] == "code"]
    for number, cell in enumerate(cells, 1):
        for out in cell.get("outputs", []):
            problem = _output_problem(out)
            if problem:
                problems.append(
                    f"code cell {number} ({_text(cell['source']).strip()[:60]!r}...): {problem}"
                )
    return problems + _canvas_problems(nb)


@pytest.mark.parametrize("lesson", LESSONS, ids=lambda p: p.name)
def test_executed_lesson_shows_no_stray_output(site, lesson):
    nb = json.loads((site["executed"] / lesson.name).read_text(encoding="utf-8"))
    problems = output_problems(nb)
    assert not problems, f"{lesson.name}:\n" + "\n".join(problems)


def _nb(outputs: list[dict], header_visible: bool = False) -> dict:
    canvas = {
        "model_name": "MPLCanvasModel",
        "state": {"header_visible": header_visible, "_figure_label": "Figure 3"},
    }
    return {
        "cells": [{"cell_type": "code", "source": "x", "outputs": outputs}],
        "metadata": {"widgets": {WIDGET_STATE: {"state": {"m1": canvas}}}},
    }


def test_output_problems_finds_each_kind_of_stray_output():
    def result(text, kind="execute_result"):
        return {"output_type": kind, "data": {"text/plain": text}}

    clean = [
        result("array([1, 2])"),
        {"output_type": "stream", "name": "stdout", "text": "ok False\n"},
        {"output_type": "stream", "name": "stderr", "text": "UserWarning: stitch: left out\n"},
        {"output_type": "display_data", "data": {WIDGET_VIEW: {}, "text/plain": "False"}},
    ]
    assert output_problems(_nb(clean)) == []
    faults = [
        ("a stray False", result("False")),
        ("a stray True", result("True")),
        ('stray repr "Text(0.5', result("Text(0.5, 1.0, 'warped')")),
        (
            "stray repr '[<matplotlib.lines",
            result("[<matplotlib.lines.Line2D at 0x7f>]", "display_data"),
        ),
        (
            "local path: '/tmp/ipykernel_6366",
            {
                "output_type": "stream",
                "name": "stderr",
                "text": "/tmp/ipykernel_6366/305.py:2: UserWarning: left out\n",
            },
        ),
        (
            "local path: '/home/ada",
            {"output_type": "stream", "name": "stderr", "text": "/home/ada/x.py:1: W\n"},
        ),
    ]
    for phrase, out in faults:
        found = output_problems(_nb([out]))
        assert len(found) == 1 and phrase in found[0], (phrase, found)
    assert "shows ipympl's header 'Figure 3'" in output_problems(_nb([], header_visible=True))[0]
    no_state = _nb([])
    no_state["metadata"] = {}
    assert "no ipympl canvas" in output_problems(no_state)[0]


class _Links(HTMLParser):
    def __init__(self):
        super().__init__()
        self.ids, self.links = set(), []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if "id" in attrs:
            self.ids.add(attrs["id"])
        for key in ("href", "src"):
            if attrs.get(key) and tag in ("a", "link", "img", "script"):
                self.links.append(attrs[key])


@functools.cache
def _parse(path: Path) -> _Links:
    parser = _Links()
    parser.feed(path.read_text(encoding="utf-8"))
    return parser


def test_internal_links_resolve(site):
    out, broken, checked = site["out"], [], 0
    for page in site["pages"]["pages"]:
        for url in _parse(out / page).links:
            parts = urlsplit(url)
            if parts.scheme in ("http", "https", "mailto", "data"):
                continue
            target = out / parts.path if parts.path else out / page
            checked += 1
            if not target.is_file():
                broken.append(f"{page}: {url} (no such file)")
            elif (
                parts.fragment
                and target.suffix == ".html"
                and parts.fragment not in _parse(target).ids
            ):
                broken.append(f"{page}: {url} (no such anchor)")
    assert checked > 100
    assert not broken, "broken links:\n" + "\n".join(broken[:20])


@pytest.fixture(scope="module")
def server(site):
    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass

    handler = functools.partial(Quiet, directory=str(site["out"]))
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{httpd.server_address[1]}"
    httpd.shutdown()
    httpd.server_close()


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    """A headless Debian Chromium context (tools/browser.py, shared with tests/test_browser.py)."""
    sys.path.insert(0, str(REPO / "tools"))
    import browser as chromium

    chromium.require_chromium()
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        context = chromium.launch(p, tmp_path_factory.mktemp("chromium"))
        yield context
        context.close()


AXE = REPO / "build" / "npm" / "node_modules" / "axe-core" / "axe.min.js"
AXE_RULES = ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa", "best-practice"]


def visit(browser, url: str) -> dict:
    """Open a page; return its console errors, outside requests, failures, maths, images and axe results."""
    page = browser.new_page()
    page.set_default_timeout(120_000)  # a stuck page fails with its name, not the suite's deadline
    seen = dict(errors=[], outside=[], failed=[])
    host = urlsplit(url).netloc
    page.on("console", lambda m: seen["errors"].append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: seen["errors"].append(str(e)))
    page.on(
        "request",
        lambda r: seen["outside"].append(r.url) if urlsplit(r.url).netloc != host else None,
    )
    page.on("requestfailed", lambda r: seen["failed"].append(r.url))
    page.on(
        "response",
        lambda r: seen["failed"].append(f"{r.status} {r.url}") if r.status >= 400 else None,
    )
    try:
        page.goto(url, wait_until="load")
        page.wait_for_function("() => window.MathJax && MathJax.startup && MathJax.startup.promise")
        page.evaluate("() => MathJax.startup.promise")
        seen.update(
            page.evaluate("""() => ({
            math: document.querySelectorAll('mjx-container').length,
            math_errors: document.querySelectorAll('mjx-merror').length,
            assistive: document.querySelectorAll('mjx-container mjx-assistive-mml math').length,
            dollars: [...document.querySelectorAll('.jp-MarkdownCell')].some(c => /\\$[^$]+\\$/.test(c.textContent)),
            images: [...document.querySelectorAll('main img')].map(i => ({alt: i.alt, ok: i.complete && i.naturalWidth > 0})),
        })""")
        )
        page.add_script_tag(path=str(AXE))  # inline: no request
        # resultTypes: axe details only the violations, not every passing node: on lesson 04's 14,800-element
        # page 11 s instead of 28 (quiet machine); the full check at 2 cores under load passed the 900 s limit.
        result = page.evaluate(
            "(rules) => axe.run(document, {runOnly: rules, resultTypes: ['violations']})", AXE_RULES
        )
        seen["axe"] = [
            (v["impact"], v["id"], len(v["nodes"]), v["nodes"][0]["target"])
            for v in result["violations"]
        ]
    finally:
        page.close()
    return seen


@pytest.fixture(scope="module")
def visits(site, server, browser) -> dict:
    assert AXE.is_file(), f"axe-core is missing at {AXE}: run `make site-deps`"
    return {name: visit(browser, f"{server}/{name}") for name in site["pages"]["pages"]}


@pytest.mark.browser
def test_every_page_loads_offline_without_errors(visits):
    problems = [
        f"{name}: console {s['errors'][:2]} outside {s['outside'][:2]} failed {s['failed'][:2]}"
        for name, s in visits.items()
        if s["errors"] or s["outside"] or s["failed"]
    ]
    assert not problems, "\n".join(problems)


@pytest.mark.browser
def test_maths_is_typeset_from_the_local_mathjax_with_assistive_mathml(visits):
    problems = []
    for name, s in visits.items():
        if s["math_errors"] or s["dollars"]:
            problems.append(
                f"{name}: {s['math_errors']} maths errors; untypeset $...$ left: {s['dollars']}"
            )
        if s["assistive"] < s["math"]:
            problems.append(
                f"{name}: {s['math'] - s['assistive']} of {s['math']} formulas without assistive MathML"
            )
    for lesson in LESSONS:
        markdown = "".join(
            "".join(c["source"])
            for c in json.loads(lesson.read_text("utf-8"))["cells"]
            if c["cell_type"] == "markdown"
        )
        if "$" in markdown and visits[lesson.stem + ".html"]["math"] == 0:
            problems.append(f"{lesson.name}: the lesson writes maths but the page typeset none")
    assert not problems, "\n".join(problems)


@pytest.mark.browser
def test_every_figure_and_demo_is_an_image_with_alt_text(visits):
    problems = []
    for name, s in visits.items():
        broken = [i for i in s["images"] if not i["ok"] or len(i["alt"]) < 20]
        if broken:
            problems.append(
                f"{name}: {len(broken)} images broken or without alt text: {broken[:2]}"
            )
    for lesson in LESSONS:
        shown, want = len(visits[lesson.stem + ".html"]["images"]), expected_images(lesson)
        print(f"{lesson.name}: {shown} images for {want} figures and demos")
        if shown < want:
            problems.append(
                f"{lesson.name}: {shown} images on the page, but it makes {want} figures and demos"
            )
    assert not problems, "\n".join(problems)


@pytest.mark.browser
def test_axe_core_finds_no_critical_or_serious_violation(visits):
    bad = {
        name: [v for v in s["axe"] if v[0] in ("critical", "serious")] for name, s in visits.items()
    }
    for name, s in visits.items():
        print(
            f"axe {name}: "
            + (", ".join(f"{v[1]} ({v[0]}, {v[2]} nodes)" for v in s["axe"]) or "no violations")
        )
    assert not any(bad.values()), "\n".join(f"{k}: {v}" for k, v in bad.items() if v)
