"""A real browser: JupyterLab in headless Debian Chromium runs lesson 06 and moves a slider.

Playwright drives the system Chromium (never `playwright install`, which downloads a browser).
JupyterLab serves a temporary copy of the lessons so autosave never touches the repository.
"""
import json
import os
import secrets
import shutil
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

pytestmark = pytest.mark.browser

REPO = Path(__file__).resolve().parent.parent
CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 "--disable-dev-shm-usage"]


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="module")
def lab(tmp_path_factory):
    if os.environ.get("CAMLAB_SKIP_BROWSER") == "1":
        pytest.skip("CAMLAB_SKIP_BROWSER=1")
    if not Path(CHROMIUM).exists():
        pytest.fail("Debian chromium is not installed: `apt-get install chromium` (make test does this as root)")
    base = tmp_path_factory.mktemp("lab")
    root = base / "root"
    shutil.copytree(REPO / "lessons", root / "lessons")
    settings = base / "settings" / "@jupyterlab" / "apputils-extension"
    settings.mkdir(parents=True)
    (settings / "notification.jupyterlab-settings").write_text(
        json.dumps({"fetchNews": "false", "checkForUpdates": False}))
    env = dict(os.environ, JUPYTER_CONFIG_DIR=str(base / "config"), JUPYTER_RUNTIME_DIR=str(base / "runtime"),
               JUPYTERLAB_SETTINGS_DIR=str(base / "settings"), JUPYTERLAB_WORKSPACES_DIR=str(base / "workspaces"),
               MPLBACKEND="module://ipympl.backend_nbagg")
    env.pop("CAMLAB_FIGURE_MODE", None)
    token, port = secrets.token_hex(16), _free_port()
    cmd = [sys.executable, "-m", "jupyter", "lab", "--no-browser", f"--port={port}", "--ip=127.0.0.1",
           f"--ServerApp.token={token}", f"--ServerApp.root_dir={root}", "--LabApp.expose_app_in_browser=True",
           "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate", "--ServerApp.open_browser=False"]
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        cmd.append("--allow-root")
    log = open(base / "lab.log", "wb")
    server = subprocess.Popen(cmd, env=env, stdout=log, stderr=subprocess.STDOUT)
    url = f"http://127.0.0.1:{port}"
    try:
        deadline = time.time() + 60
        while True:
            try:
                with urllib.request.urlopen(f"{url}/api/status?token={token}", timeout=2) as r:
                    if r.status == 200:
                        break
            except OSError:
                pass
            if time.time() > deadline or server.poll() is not None:
                pytest.fail("JupyterLab did not start:\n" + (base / "lab.log").read_text(errors="replace")[-3000:])
            time.sleep(0.5)
        yield dict(url=url, token=token, profile=base / "chromium")
    finally:
        server.terminate()
        try:
            server.wait(timeout=15)
        except subprocess.TimeoutExpired:
            server.kill()
        log.close()


KERNEL_IDLE = """() => {
  const w = window.jupyterapp && window.jupyterapp.shell.currentWidget;
  const k = w && w.sessionContext && w.sessionContext.session && w.sessionContext.session.kernel;
  return !!k && k.connectionStatus === 'connected' && k.status === 'idle';
}"""

# The kernel is briefly idle between cells, so also require every code cell to have run.
ALL_CELLS_RUN = """() => {
  const w = window.jupyterapp.shell.currentWidget;
  const k = w.sessionContext.session.kernel;
  const code = w.content.widgets.filter((c) => c.model.type === 'code');
  return k.status === 'idle' && code.every((c) => c.model.executionCount !== null);
}"""


def test_lesson_06_runs_and_a_slider_moves_the_figure(lab):
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        context = p.chromium.launch_persistent_context(
            str(lab["profile"]), executable_path=CHROMIUM, headless=True, args=CHROMIUM_ARGS,
            viewport={"width": 1400, "height": 1000})
        try:
            page = context.new_page()
            page.set_default_timeout(90_000)
            page.goto(f"{lab['url']}/lab/workspaces/t{secrets.token_hex(4)}/tree/lessons/06_projective_plane.ipynb"
                      f"?reset&token={lab['token']}")
            page.wait_for_function(KERNEL_IDLE, polling=500)
            # Trigger run-all without awaiting its promise (awaiting it can hang).
            page.evaluate("() => { window.jupyterapp.commands.execute('notebook:run-all-cells'); }")
            demo = page.locator(".camlab-demo-parallel-lines")
            demo.wait_for(state="attached")
            demo.scroll_into_view_if_needed()
            figure = demo.locator("canvas").first
            figure.wait_for(state="visible")
            readout = demo.locator("pre").first
            page.wait_for_function(
                "() => (document.querySelector('.camlab-demo-parallel-lines pre') || {}).textContent?.includes('l1 × l2')")
            page.wait_for_function(ALL_CELLS_RUN, polling=500)
            page.wait_for_timeout(1000)
            demo.scroll_into_view_if_needed()
            before_png, before_text = figure.screenshot(), readout.text_content()

            # Click the angle slider's track at 80 % (a click needs no keyboard focus, which
            # JupyterLab may move while it renders).
            track = demo.locator(".noUi-base").first
            box = track.bounding_box()
            track.click(position={"x": 0.8 * box["width"], "y": box["height"] / 2})
            # The HTML readout replaces its <pre> on every update: query it afresh each poll.
            page.wait_for_function(
                "(old) => document.querySelector('.camlab-demo-parallel-lines pre').textContent !== old",
                arg=before_text, polling=250)
            page.wait_for_timeout(1500)  # let the kernel's blitted image reach the canvas
            after_png, after_text = figure.screenshot(), readout.text_content()
            errors = page.locator(".jp-OutputArea-output[data-mime-type='application/vnd.jupyter.stderr']")
            stderr = [t for t in errors.all_text_contents() if "Error" in t]
        finally:
            context.close()
    assert before_text != after_text, "the slider did not reach the kernel"
    assert before_png != after_png, "the slider moved but the figure did not change"
    assert not stderr, f"lesson 06 printed errors in the browser: {stderr[:2]}"
