"""Lecture mode: `camlab present 07` serves lesson 07's demos without code; a real browser moves a slider."""
import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

from camlab.classroom.lessons import find_lesson, lesson_files
from camlab.classroom.present import is_demo_cell, presentation_notebook

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tools"))
import browser  # noqa: E402


def _lesson(spec: str) -> dict:
    return json.loads(find_lesson(spec).read_text())


def test_presentation_keeps_every_demo_in_order_and_silences_the_rest():
    for path in lesson_files():
        lesson = json.loads(path.read_text())
        show = presentation_notebook(lesson)
        demos = ["".join(c["source"]) for c in lesson["cells"] if is_demo_cell(c)]
        assert [c["source"] for c in show["cells"] if is_demo_cell(c)] == demos and demos, path.stem
        assert show["cells"][0]["source"] == "".join(lesson["cells"][0]["source"]).splitlines()[0]
        for cell in show["cells"]:
            text = "".join(cell["source"])
            assert cell["cell_type"] == "markdown" or is_demo_cell(cell) or text.startswith("%%capture\n")
            lines = text.splitlines()
            assert not any(ln.startswith(("check_", "solution(", "    raise NotImplementedError")) for ln in lines), path.stem
    headings = [c["source"] for c in presentation_notebook(_lesson("07"))["cells"] if c["cell_type"] == "markdown"]
    assert headings[0].startswith("# 07 ·") and "## 2. The transformation hierarchy" in headings


def test_presentation_of_lesson_07_runs_and_shows_only_demos():
    from nbclient import NotebookClient
    import nbformat

    nb = nbformat.from_dict(presentation_notebook(_lesson("07")))
    NotebookClient(nb, timeout=300, kernel_name="python3").execute()  # raises if any hidden cell fails
    shown = [c for c in nb.cells if c.cell_type == "code" and c.outputs]
    assert len(shown) == 4 and all(is_demo_cell(c) for c in shown)
    assert all("application/vnd.jupyter.widget-view+json" in c.outputs[0]["data"] for c in shown)


@pytest.mark.browser
def test_camlab_present_serves_demos_without_code_and_a_slider_moves_a_figure(tmp_path):
    if os.environ.get("CAMLAB_SKIP_BROWSER") == "1":
        pytest.skip("CAMLAB_SKIP_BROWSER=1")
    from playwright.sync_api import sync_playwright

    if not Path(browser.CHROMIUM).exists():
        pytest.fail("Debian chromium is not installed: `apt-get install chromium` (make test does this as root)")
    port = browser.free_port()
    env = dict(os.environ, JUPYTER_CONFIG_DIR=str(tmp_path / "config"), JUPYTER_RUNTIME_DIR=str(tmp_path / "runtime"),
               MPLBACKEND="module://ipympl.backend_nbagg")
    env.pop("CAMLAB_FIGURE_MODE", None)
    log = open(tmp_path / "voila.log", "wb")
    server = subprocess.Popen([sys.executable, "-m", "camlab.cli", "present", "07", f"--port={port}", "--no-browser"],
                              env=env, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
    url = f"http://127.0.0.1:{port}/"
    try:
        deadline = time.time() + 60
        while True:
            try:
                with socket.create_connection(("127.0.0.1", port), timeout=2):
                    break  # voila listens (it renders the lesson when the page is requested)
            except OSError:
                pass
            if time.time() > deadline or server.poll() is not None:
                pytest.fail("voila did not start:\n" + (tmp_path / "voila.log").read_text(errors="replace")[-3000:])
            time.sleep(0.5)
        with sync_playwright() as p:
            context = browser.launch(p, tmp_path / "chromium")
            try:
                page = context.new_page()
                page.set_default_timeout(120_000)
                started = time.time()
                page.goto(url, wait_until="commit")
                demo_names = ["transformation-hierarchy", "drag-homography", "ransac-outliers", "forward-vs-inverse"]
                for name in demo_names:
                    page.locator(f".camlab-demo-{name} canvas").first.wait_for(state="visible")
                load_seconds = time.time() - started
                page.wait_for_timeout(2000)
                page.screenshot(path=str(tmp_path / "present_07.png"))
                before_png, after_png, before_text, after_text = browser.click_slider(
                    page, "camlab-demo-transformation-hierarchy", 0.85)  # the rotation slider
                text = page.locator("body").inner_text()
                code_cells = page.locator(".jp-InputArea-editor").count()
            finally:
                context.close()
    finally:
        os.killpg(server.pid, signal.SIGTERM)
        try:
            server.wait(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(server.pid, signal.SIGKILL)
        log.close()
    print(f"lesson 07 in lecture mode: all 4 demos visible after {load_seconds:.1f} s")
    assert code_cells == 0 and "import " not in text and "demos." not in text, "code is visible"
    assert "07 · Estimate and apply homographies" in text and "2. The transformation hierarchy" in text
    assert before_text != after_text, "the slider did not reach the kernel"
    assert before_png != after_png, "the slider moved but the figure did not change"
    assert "Traceback" not in text and "Error" not in text
