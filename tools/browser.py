"""Headless Debian Chromium and a throwaway JupyterLab, for the browser tests and benchmarks.

Playwright drives the system Chromium (never `playwright install`, which downloads a browser);
JupyterLab runs on loopback with a token, a free port and temporary config, runtime, settings
and workspace folders, so nothing touches the user's setup (see ../shared ECOSYSTEM notes).
"""

from __future__ import annotations

import contextlib
import json
import os
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import time
import urllib.request
from collections.abc import Iterator
from pathlib import Path

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
CHROMIUM_ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-dev-shm-usage",
]

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

RUN_ALL = "() => { window.jupyterapp.commands.execute('notebook:run-all-cells'); }"  # never await it: it can hang


def require_chromium() -> None:
    """For a browser test's fixture: skip it under CAMLAB_SKIP_BROWSER=1, fail it (saying how to
    install) when Debian's chromium is missing: a browser test never passes by not running."""
    import pytest

    if os.environ.get("CAMLAB_SKIP_BROWSER") == "1":
        pytest.skip("CAMLAB_SKIP_BROWSER=1")
    if not Path(CHROMIUM).exists():
        pytest.fail(
            "Debian chromium is not installed: `apt-get install chromium` (make test does this as root)"
        )


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_for_http(url: str, process: subprocess.Popen, log: Path, timeout: float = 60) -> None:
    """Poll ``url`` until it answers 200; raise with the server's log if it dies or times out."""
    deadline = time.time() + timeout
    while True:
        try:
            with urllib.request.urlopen(url, timeout=2) as r:
                if r.status == 200:
                    return
        except OSError:
            pass
        if time.time() > deadline or process.poll() is not None:
            raise RuntimeError(
                f"{url} did not come up:\n" + log.read_text(errors="replace")[-3000:]
            )
        time.sleep(0.5)


def stop(process: subprocess.Popen) -> None:
    process.terminate()
    try:
        process.wait(timeout=15)
    except subprocess.TimeoutExpired:
        process.kill()


@contextlib.contextmanager
def lecture_mode(lesson: str, base: Path) -> Iterator[int]:
    """Run ``camlab present LESSON`` (Voila) on a free port with scratch folders under ``base``.

    Yields the port once Voila listens (it renders the lesson when the page is requested);
    raises with Voila's log if it dies or does not listen within 60 s. The whole process
    group is stopped on exit, kernels included.
    """
    port = free_port()
    env = dict(
        os.environ,
        JUPYTER_CONFIG_DIR=str(base / "config"),
        JUPYTER_RUNTIME_DIR=str(base / "runtime"),
        MPLBACKEND="module://ipympl.backend_nbagg",
    )
    env.pop("CAMLAB_FIGURE_MODE", None)
    log_path = base / "voila.log"
    with open(log_path, "wb") as log:
        server = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "camlab.cli",
                "present",
                lesson,
                f"--port={port}",
                "--no-browser",
            ],
            env=env,
            stdout=log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
        try:
            deadline = time.time() + 60
            while True:
                try:
                    with socket.create_connection(("127.0.0.1", port), timeout=2):
                        break
                except OSError:
                    pass
                if time.time() > deadline or server.poll() is not None:
                    raise RuntimeError(
                        "voila did not start:\n" + log_path.read_text(errors="replace")[-3000:]
                    )
                time.sleep(0.5)
            yield port
        finally:
            os.killpg(server.pid, signal.SIGTERM)
            try:
                server.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(server.pid, signal.SIGKILL)


@contextlib.contextmanager
def jupyterlab(root: Path, base: Path) -> Iterator[dict]:
    """Serve ``root`` with JupyterLab (ipympl backend) using scratch folders under ``base``.

    Yields ``dict(url, token, profile)``; ``profile`` is a fresh Chromium profile folder.
    """
    settings = base / "settings" / "@jupyterlab" / "apputils-extension"
    settings.mkdir(parents=True)
    (settings / "notification.jupyterlab-settings").write_text(
        json.dumps({"fetchNews": "false", "checkForUpdates": False})
    )
    # Every cell attached and laid out: under JupyterLab's default ("contentVisibility") an
    # off-screen ipympl canvas has no size to take, and CI saw one stay 0 x 0 under load.
    notebook = base / "settings" / "@jupyterlab" / "notebook-extension"
    notebook.mkdir(parents=True)
    (notebook / "tracker.jupyterlab-settings").write_text(json.dumps({"windowingMode": "none"}))
    env = dict(
        os.environ,
        JUPYTER_CONFIG_DIR=str(base / "config"),
        JUPYTER_RUNTIME_DIR=str(base / "runtime"),
        JUPYTERLAB_SETTINGS_DIR=str(base / "settings"),
        JUPYTERLAB_WORKSPACES_DIR=str(base / "workspaces"),
        MPLBACKEND="module://ipympl.backend_nbagg",
    )
    env.pop("CAMLAB_FIGURE_MODE", None)
    token, port = secrets.token_hex(16), free_port()
    cmd = [
        sys.executable,
        "-m",
        "jupyter",
        "lab",
        "--no-browser",
        f"--port={port}",
        "--ip=127.0.0.1",
        f"--ServerApp.token={token}",
        f"--ServerApp.root_dir={root}",
        "--LabApp.expose_app_in_browser=True",
        "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate",
        "--ServerApp.open_browser=False",
    ]
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        cmd.append("--allow-root")
    log_path = base / "lab.log"
    with open(log_path, "wb") as log:
        server = subprocess.Popen(cmd, env=env, stdout=log, stderr=subprocess.STDOUT)
        url = f"http://127.0.0.1:{port}"
        try:
            wait_for_http(f"{url}/api/status?token={token}", server, log_path)
            yield dict(url=url, token=token, profile=base / "chromium")
        finally:
            stop(server)


def launch(playwright, profile: Path, **kw):
    """A persistent headless Chromium context on the system browser."""
    return playwright.chromium.launch_persistent_context(
        str(profile),
        executable_path=CHROMIUM,
        headless=True,
        args=CHROMIUM_ARGS,
        viewport={"width": 1400, "height": 1000},
        **kw,
    )


def run_notebook(page, lab: dict, path: str) -> None:
    """Open ``path`` in a fresh workspace, wait for its kernel and start running every cell.

    Run-all is started, not awaited (awaiting its promise can hang): wait for
    :data:`ALL_CELLS_RUN` or for the element you need.
    """
    page.goto(
        f"{lab['url']}/lab/workspaces/t{secrets.token_hex(4)}/tree/{path}?reset&token={lab['token']}"
    )
    page.wait_for_function(KERNEL_IDLE, polling=500)
    page.evaluate(RUN_ALL)


def click_slider(page, demo: str, fraction: float) -> tuple[bytes, bytes, str, str]:
    """Click the first slider of the demo with CSS class ``demo`` at ``fraction`` of its track.

    Returns ``(figure PNG before, after, readout text before, after)``. A click needs no
    keyboard focus (which JupyterLab may move while it renders); the HTML readout replaces
    its <pre> on every update, so it is queried afresh while waiting for the change.
    """
    box_ = page.locator(f".{demo}")
    box_.scroll_into_view_if_needed()
    figure, readout = box_.locator("canvas").first, box_.locator("pre").first
    before_png, before_text = figure.screenshot(), readout.text_content()
    track = box_.locator(".noUi-base").first
    box = track.bounding_box()
    track.click(position={"x": fraction * box["width"], "y": box["height"] / 2})
    page.wait_for_function(
        f"(old) => document.querySelector('.{demo} pre').textContent !== old",
        arg=before_text,
        polling=250,
    )
    after_png = figure.screenshot()
    for _ in range(
        60
    ):  # the kernel's new image reaches the canvas after the readout: up to 15 s on a busy machine
        if after_png != before_png:
            break
        page.wait_for_timeout(250)
        after_png = figure.screenshot()
    page.wait_for_timeout(500)  # and let it finish drawing
    return before_png, figure.screenshot(), before_text, readout.text_content()


# Arm: at the next keydown, poll every animation frame until the canvas's pixels differ.
# Sets window.__camlabLatency = {pixels: ms (-1: none in 5 s), frames: [[ms, bytes], ...]}; the
# frames are the websocket messages a watcher (benchmarks/browser_latency.py) logged while armed.
ARM_KEY_TO_CANVAS = """(selector) => {
  window.__camlabLatency = undefined;
  window.__camlabFrames = [];
  window.__camlabArmed = true;
  const canvas = document.querySelector(selector);
  const ctx = canvas.getContext('2d', {willReadFrequently: true});
  const checksum = () => {
    const d = ctx.getImageData(0, 0, canvas.width, canvas.height).data;
    let s = 0;
    for (let i = 0; i < d.length; i += 7) s = (s * 31 + d[i]) | 0;
    return s;
  };
  const before = checksum();
  document.addEventListener('keydown', () => {
    const t0 = performance.now();
    const done = (ms) => {
      window.__camlabArmed = false;
      const frames = window.__camlabFrames.map(([t, n]) => [t - t0, n]);
      window.__camlabLatency = {pixels: ms, frames: frames};
    };
    const poll = () => {
      if (checksum() !== before) done(performance.now() - t0);
      else if (performance.now() - t0 > 5000) done(-1);
      else requestAnimationFrame(poll);
    };
    requestAnimationFrame(poll);
  }, {capture: true, once: true});
}"""


def key_to_pixels(page, demo: str, canvas: str, presses: int = 20) -> list[float]:
    """Milliseconds from each keydown on the demo's first slider to the first frame its canvas changed.

    ``demo`` is the demo's CSS class, ``canvas`` a selector inside it. Arrow keys alternate right and
    left, so the slider stays near its value. Measured in the page with ``performance.now()``: the
    keydown, then every animation frame until the canvas's pixels differ (-1: none in 5 s).
    """
    handle = page.locator(f".{demo} .widget-slider:not(.mod-disabled) .noUi-handle").first
    samples = []
    for i in range(presses):
        handle.focus()
        page.evaluate(ARM_KEY_TO_CANVAS, f".{demo} {canvas}")
        page.keyboard.press("ArrowRight" if i % 2 == 0 else "ArrowLeft")
        page.wait_for_function("() => window.__camlabLatency !== undefined", polling=20)
        samples.append(float(page.evaluate("() => window.__camlabLatency.pixels")))
        page.wait_for_timeout(200)
    return samples
