"""A real JupyterHub for a class, on loopback, and students who run lessons through it.

Used by tests/test_hub.py and benchmarks/class_load.py (``make class-load N=...``).

:func:`class_hub` starts JupyterHub (PyPI) with configurable-http-proxy (npm), the
DummyAuthenticator and the SimpleLocalProcessSpawner (every student's server runs as this OS
user with ``HOME`` in its own folder ``homes/<name>``), and an admin *service* token.
:func:`run_class` then does what a class does: the admin creates the students through the
REST API, starts their servers and issues each a token; every student, concurrently, uploads a
lesson into their folder, opens a session on their own server, executes the lesson cell by cell
over the kernel's websocket, saves the executed notebook back through the contents API, and
reads the kernel's own peak memory and CPU time (``getrusage``) at the end.

Two things keep a class run from hanging. Kernels talk over IPC (Unix sockets in a runtime
folder per student), not TCP: every single-user server picks its kernels' TCP ports on its own,
so servers started at once could pick the same free port (``ZMQError: Address already in use``)
and a kernel would never answer. And every wait has a deadline: a request, a server's start,
each kernel message; one that passes fails with the hub log's tail instead of waiting forever.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request
import uuid
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
BIN = Path(sys.executable).parent
CHP = Path(
    os.environ.get(
        "CAMLAB_CHP", REPO / ".venv" / "chp" / "node_modules" / ".bin" / "configurable-http-proxy"
    )
)

MARKER = (
    'import json, os, ipykernel; print("camlab-hub-run", os.environ.get("JUPYTERHUB_USER"), os.getcwd(), '
    'json.loads(ipykernel.get_connection_info())["transport"])'
)
METRICS = (
    "import json as _j, resource as _r\n"
    "_s, _c = _r.getrusage(_r.RUSAGE_SELF), _r.getrusage(_r.RUSAGE_CHILDREN)\n"
    "print('camlab-hub-metrics', _j.dumps({'peak_mb': _s.ru_maxrss / 1024, "
    "'cpu_s': _s.ru_utime + _s.ru_stime + _c.ru_utime + _c.ru_stime}))"
)


REQUEST_S = 120  # one REST call (starting a server is answered at once: 202)
SERVERS_READY_S = 240  # every student's server up
KERNEL_MESSAGE_S = 300  # the longest silence of a kernel running one cell


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@dataclass
class Hub:
    url: str  # the proxy's public URL, http://127.0.0.1:PORT
    admin_token: str
    homes: Path
    log: Path
    process: subprocess.Popen = field(repr=False)

    def log_tail(self, chars: int = 4000) -> str:
        return self.log.read_text(errors="replace")[-chars:]


async def within(seconds: float, awaitable, what: str):
    """Await ``awaitable`` for at most ``seconds``; past that, fail naming ``what``."""
    try:
        return await asyncio.wait_for(awaitable, seconds)
    except TimeoutError:
        raise TimeoutError(f"{what}: no answer within {seconds:.0f} s") from None


@contextlib.contextmanager
def failing_with_log(hub: Hub) -> Iterator[None]:
    """Re-raise any failure in the block with the hub log's tail: what the hub and servers said."""
    try:
        yield
    except Exception as exc:
        raise RuntimeError(
            f"{type(exc).__name__}: {exc}\nthe hub log ends:\n{hub.log_tail()}"
        ) from exc


def _config(base: Path, port: int, token: str, runtime: Path) -> str:
    # IPC kernels: their sockets are files named after the kernel's id, so no two can collide.
    # A runtime folder per student under a short path keeps socket paths under the 107-byte limit.
    args = ["--KernelManager.transport=ipc"]
    args += ["--allow-root"] if hasattr(os, "geteuid") and os.geteuid() == 0 else []
    return f"""
c = get_config()
c.JupyterHub.bind_url = "http://127.0.0.1:{port}"
c.JupyterHub.hub_bind_url = "http://127.0.0.1:{free_port()}"
c.ConfigurableHTTPProxy.api_url = "http://127.0.0.1:{free_port()}"
c.ConfigurableHTTPProxy.command = [{str(CHP)!r}]
c.ConfigurableHTTPProxy.pid_file = {str(base / "proxy.pid")!r}
c.JupyterHub.db_url = "sqlite:///{base / "hub.sqlite"}"
c.JupyterHub.cookie_secret_file = {str(base / "cookie_secret")!r}
c.JupyterHub.authenticator_class = "dummy"
c.Authenticator.allow_all = True
c.JupyterHub.spawner_class = "simple"
c.SimpleLocalProcessSpawner.home_dir_template = {str(base / "homes" / "{username}")!r}
c.Spawner.cmd = [{str(BIN / "jupyterhub-singleuser")!r}]
c.Spawner.args = {args!r}
c.Spawner.environment = {{"JUPYTER_RUNTIME_DIR": lambda spawner: {str(runtime)!r} + "/" + spawner.user.name}}
c.Spawner.default_url = "/lab"
c.Spawner.start_timeout = 180
c.Spawner.http_timeout = 180
c.JupyterHub.services = [{{"name": "class-admin", "api_token": {token!r}}}]
c.JupyterHub.load_roles = [{{"name": "class-admin", "services": ["class-admin"],
                            "scopes": ["admin:users", "admin:servers", "tokens", "list:users"]}}]
"""


def _wait_ready(url: str, process: subprocess.Popen, log: Path, timeout: float = 90) -> None:
    """Poll the hub's API through the proxy until it answers (the proxy listens before its route exists)."""
    deadline = time.time() + timeout
    while True:
        with (
            contextlib.suppress(OSError),
            urllib.request.urlopen(f"{url}/hub/api/", timeout=2) as r,
        ):
            if r.status == 200:
                return
        if time.time() > deadline or process.poll() is not None:
            raise RuntimeError(
                "JupyterHub did not start:\n" + log.read_text(errors="replace")[-4000:]
            )
        time.sleep(0.3)


def processes_under(folder: Path) -> list:
    """Processes whose working folder is inside ``folder`` (the students' servers and kernels)."""
    import psutil

    found = []
    for p in psutil.process_iter(["pid"]):
        with contextlib.suppress(psutil.Error):
            if Path(p.cwd()).is_relative_to(folder):
                found.append(p)
    return found


@contextlib.contextmanager
def class_hub(base: Path) -> Iterator[Hub]:
    """Run a JupyterHub under ``base`` (config, database, homes, log) until the block ends."""
    if not CHP.exists():
        raise RuntimeError(
            f"configurable-http-proxy not found at {CHP}: run `make hub-deps` "
            f"(npm install --prefix .venv/chp configurable-http-proxy)"
        )
    base.mkdir(parents=True, exist_ok=True)
    (base / "homes").mkdir(exist_ok=True)
    port, token = free_port(), secrets.token_hex(32)
    runtime = Path(tempfile.mkdtemp(prefix="camlab-hub-"))
    (base / "jupyterhub_config.py").write_text(_config(base, port, token, runtime))
    env = {
        k: v
        for k, v in os.environ.items()
        if not k.startswith(("JUPYTERHUB", "CAMLAB_FIGURE", "MPLBACKEND"))
    }
    env["PATH"] = f"{BIN}{os.pathsep}{env.get('PATH', '')}"
    log = base / "hub.log"
    with open(log, "wb") as out:
        process = subprocess.Popen(
            [str(BIN / "jupyterhub"), "-f", str(base / "jupyterhub_config.py")],
            cwd=base,
            env=env,
            stdout=out,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
        try:
            _wait_ready(f"http://127.0.0.1:{port}", process, log)
            yield Hub(f"http://127.0.0.1:{port}", token, base / "homes", log, process)
        finally:
            process.send_signal(signal.SIGINT)  # the hub stops every student's server and the proxy
            try:
                process.wait(timeout=60)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
            for leftover in processes_under(base):
                leftover.kill()
            shutil.rmtree(runtime, ignore_errors=True)


# --- the REST and kernel clients (tornado, which Jupyter already installs) ---------------------


async def api(
    url: str, token: str, method: str = "GET", body: dict | None = None, ok=(200, 201, 202, 204)
):
    """One REST call with ``Authorization: token``; returns (status, parsed JSON or None)."""
    from tornado.httpclient import AsyncHTTPClient, HTTPClientError

    try:
        response = await AsyncHTTPClient().fetch(
            url,
            method=method,
            headers={"Authorization": f"token {token}"},
            follow_redirects=False,
            body=None if body is None and method in ("GET", "DELETE") else json.dumps(body or {}),
            allow_nonstandard_methods=True,
            connect_timeout=REQUEST_S,
            request_timeout=REQUEST_S,
        )
        status, text = response.code, response.body
    except HTTPClientError as exc:
        if exc.response is None:  # a timeout or a dropped connection (599) is never an answer
            raise TimeoutError(f"{method} {url}: {exc}") from None
        status, text = exc.code, exc.response.body
    if ok and status not in ok:
        raise RuntimeError(f"{method} {url}: HTTP {status} {text[:300]!r}")
    return status, (json.loads(text) if text and text.strip().startswith((b"{", b"[")) else None)


async def start_students(hub: Hub, names: list[str]) -> dict[str, str]:
    """Create the students, start their servers (all at once) and return a token for each."""
    await api(f"{hub.url}/hub/api/users", hub.admin_token, "POST", {"usernames": names})
    await asyncio.gather(
        *(api(f"{hub.url}/hub/api/users/{n}/server", hub.admin_token, "POST") for n in names)
    )
    deadline = time.time() + SERVERS_READY_S
    for name in names:
        while True:
            _, user = await api(f"{hub.url}/hub/api/users/{name}", hub.admin_token)
            server = user.get("servers", {}).get("", {})
            if server.get("ready"):
                break
            if time.time() > deadline:
                raise RuntimeError(
                    f"{name}'s server did not become ready: {user}\n"
                    + hub.log.read_text(errors="replace")[-3000:]
                )
            await asyncio.sleep(0.5)
    tokens = {}
    for name in names:
        _, made = await api(
            f"{hub.url}/hub/api/users/{name}/tokens",
            hub.admin_token,
            "POST",
            {"note": "class test", "expires_in": 7200},
        )
        tokens[name] = made["token"]
    return tokens


def _message(msg_type: str, content: dict, session: str) -> dict:
    return {
        "header": {
            "msg_id": uuid.uuid4().hex,
            "msg_type": msg_type,
            "session": session,
            "username": "",
            "version": "5.3",
            "date": "",
        },
        "parent_header": {},
        "metadata": {},
        "content": content,
        "channel": "shell",
        "buffers": [],
    }


async def _execute(ws, code: str, session: str) -> tuple[str, list[dict]]:
    """Run ``code``; return the reply status and the outputs in nbformat form."""
    request = _message(
        "execute_request",
        {
            "code": code,
            "silent": False,
            "store_history": True,
            "user_expressions": {},
            "allow_stdin": False,
            "stop_on_error": True,
        },
        session,
    )
    await ws.write_message(json.dumps(request))
    msg_id, outputs, status, idle = request["header"]["msg_id"], [], None, False
    while status is None or not idle:
        raw = await within(
            KERNEL_MESSAGE_S, ws.read_message(), f"the kernel running {code[:60]!r}..."
        )
        if raw is None:
            raise RuntimeError("the kernel's websocket closed")
        if isinstance(raw, bytes):
            continue  # binary frames carry widget buffers (ipympl images): not needed here
        msg = json.loads(raw)
        if msg.get("parent_header", {}).get("msg_id") != msg_id:
            continue
        kind, content = msg["msg_type"], msg["content"]
        if msg["channel"] == "shell" and kind == "execute_reply":
            status = content["status"]
        elif kind == "status" and content["execution_state"] == "idle":
            idle = True
        elif kind == "stream":
            outputs.append(
                {"output_type": "stream", "name": content["name"], "text": content["text"]}
            )
        elif kind in ("execute_result", "display_data"):
            out = {
                "output_type": kind,
                "data": content["data"],
                "metadata": content.get("metadata", {}),
            }
            if kind == "execute_result":
                out["execution_count"] = content["execution_count"]
            outputs.append(out)
        elif kind == "error":
            outputs.append(
                {
                    "output_type": "error",
                    "ename": content["ename"],
                    "evalue": content["evalue"],
                    "traceback": content["traceback"],
                }
            )
    return status, outputs


@contextlib.asynccontextmanager
async def kernel(hub: Hub, name: str, token: str, path: str):
    """A session for notebook ``path`` on ``name``'s server; yields ``run(code) -> (status, outputs)``."""
    from tornado.httpclient import HTTPRequest
    from tornado.websocket import websocket_connect

    server = f"{hub.url}/user/{name}"
    _, session = await api(
        f"{server}/api/sessions",
        token,
        "POST",
        {"path": path, "type": "notebook", "name": path, "kernel": {"name": "python3"}},
    )
    ws_url = (
        server.replace("http", "ws", 1)
        + f"/api/kernels/{session['kernel']['id']}/channels?session_id={uuid.uuid4().hex}"
    )
    ws = await websocket_connect(
        HTTPRequest(
            ws_url,
            headers={"Authorization": f"token {token}"},
            connect_timeout=REQUEST_S,
            request_timeout=REQUEST_S,
        ),
        max_message_size=256 * 1024 * 1024,
    )
    try:
        yield lambda code: _execute(ws, code, session["id"])
    finally:
        ws.close()
        await api(f"{server}/api/sessions/{session['id']}", token, "DELETE")


def printed(outputs: list[dict], tag: str) -> str | None:
    """The rest of the printed line that starts with ``tag``, or None."""
    text = "".join(o.get("text", "") for o in outputs)
    return text.split(tag, 1)[1].splitlines()[0].strip() if tag in text else None


async def run_lesson(hub: Hub, name: str, token: str, lesson: Path) -> dict:
    """One student runs one lesson on their server; returns timings, kernel metrics and errors."""
    contents = f"{hub.url}/user/{name}/api/contents/{lesson.name}"
    nb = json.loads(lesson.read_text(encoding="utf-8"))
    nb["cells"].insert(
        0,
        {
            "cell_type": "code",
            "metadata": {},
            "source": MARKER,
            "outputs": [],
            "execution_count": None,
        },
    )
    await api(contents, token, "PUT", {"type": "notebook", "format": "json", "content": nb})
    errors, count = [], 0
    async with kernel(hub, name, token, lesson.name) as run:
        t0 = time.perf_counter()
        for cell in nb["cells"]:
            if cell["cell_type"] != "code":
                continue
            count += 1
            status, cell["outputs"] = await run("".join(cell["source"]))
            cell["execution_count"] = count
            if status != "ok":
                errors.append(
                    next(
                        (
                            f"{o['ename']}: {o['evalue']}"
                            for o in cell["outputs"]
                            if o["output_type"] == "error"
                        ),
                        status,
                    )
                )
                break
        wall = time.perf_counter() - t0
        _, metrics = await run(METRICS)
    await api(contents, token, "PUT", {"type": "notebook", "format": "json", "content": nb})
    marker = (printed(nb["cells"][0]["outputs"], "camlab-hub-run") or "").split()
    return {
        "student": name,
        "lesson": lesson.stem,
        "wall_s": wall,
        "errors": errors,
        "cells": count,
        **dict(
            zip(
                ("kernel_user", "kernel_cwd", "kernel_transport"),
                [*marker, None, None, None],  # padded: a missing marker leaves None
                strict=False,
            )
        ),
        **json.loads(printed(metrics, "camlab-hub-metrics") or "{}"),
    }


def server_rss_mb(hub: Hub) -> dict[str, float]:
    """Resident memory of each student's single-user server process (without its kernels), MB."""
    return {
        p.cwd().split("/")[-1]: p.memory_info().rss / 2**20
        for p in processes_under(hub.homes)
        if "jupyterhub-singleuser" in " ".join(p.cmdline())
    }


async def run_class(
    hub: Hub, names: list[str], lessons: list[Path]
) -> tuple[dict[str, str], list[dict]]:
    """Start ``names``' servers, then every student runs ``lessons`` in turn, all students at once.

    A request that fails or times out fails the run with the hub log's tail (what the servers said).
    """

    async def student(name: str) -> list[dict]:
        return [await run_lesson(hub, name, tokens[name], lesson) for lesson in lessons]

    with failing_with_log(hub):
        tokens = await start_students(hub, names)
        results = await asyncio.gather(*(student(n) for n in names))
    return tokens, [r for rows in results for r in rows]
