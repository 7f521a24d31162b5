"""A real JupyterHub for a class: four students run a lesson through it at once, each in their own folder.

JupyterHub (PyPI) with configurable-http-proxy (npm, installed by `make hub-deps`) on loopback,
DummyAuthenticator and SimpleLocalProcessSpawner; see tools/classhub.py.
"""

import asyncio
import json
import sys
import time
from pathlib import Path

import pytest

from camlab.classroom.lessons import find_lesson

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tools"))
import classhub  # noqa: E402

# Four servers and four kernels on two cores take one to three minutes; past ten something hangs.
pytestmark = [pytest.mark.hub, pytest.mark.timeout(600)]

STUDENTS = ["ada", "blaise", "carl", "dora"]


async def _cross_reads(hub, tokens, path):
    """What each student gets when reaching for the next student's files through the hub."""
    statuses = []
    for me, other in zip(STUDENTS, STUDENTS[1:] + STUDENTS[:1], strict=True):
        mine = tokens[me]
        for method, url, body in [
            ("GET", f"{hub.url}/user/{other}/api/contents/{path}", None),
            (
                "PUT",
                f"{hub.url}/user/{other}/api/contents/intrusion.txt",
                {"type": "file", "format": "text", "content": f"written by {me}"},
            ),
            ("GET", f"{hub.url}/user/{me}/api/contents/..%2F{other}%2F{path}", None),
            ("GET", f"{hub.url}/user/{me}/files/..%2F{other}%2F{path}", None),
        ]:
            status, _ = await classhub.api(url, mine, method, body, ok=())
            statuses.append((me, other, method, url.split("/user/")[1], status))
    own, _ = await classhub.api(
        f"{hub.url}/user/{STUDENTS[0]}/api/contents/{path}", tokens[STUDENTS[0]], ok=()
    )
    return own, statuses


def test_four_students_run_a_lesson_at_once_each_in_their_own_folder(tmp_path):
    if not classhub.CHP.exists():
        pytest.fail(f"configurable-http-proxy is missing at {classhub.CHP}: run `make hub-deps`")
    lesson = find_lesson("06")
    code_cells = sum(c["cell_type"] == "code" for c in json.loads(lesson.read_text())["cells"])
    t0 = time.perf_counter()
    with classhub.class_hub(tmp_path / "hub") as hub:
        t_hub = time.perf_counter() - t0
        tokens, rows = asyncio.run(classhub.run_class(hub, STUDENTS, [lesson]))
        t_class = time.perf_counter() - t0 - t_hub
        with classhub.failing_with_log(hub):
            own, crossed = asyncio.run(_cross_reads(hub, tokens, lesson.name))
    print(
        f"\nhub up in {t_hub:.1f} s; 4 servers started and lesson 06 run by all in {t_class:.1f} s; "
        + ", ".join(
            f"{r['student']} {r['wall_s']:.1f} s / {r['peak_mb']:.0f} MB / {r['cpu_s']:.1f} cpu-s"
            for r in rows
        )
        + f"; cross-student requests answered {sorted({c[-1] for c in crossed})}"
    )

    assert [r["student"] for r in rows] == STUDENTS
    for r in rows:
        assert r["errors"] == [] and r["cells"] == code_cells + 1, r
        assert (
            r["kernel_user"] == r["student"] and Path(r["kernel_cwd"]) == hub.homes / r["student"]
        ), r
        assert r["kernel_transport"] == "ipc", (
            r
        )  # TCP ports picked by four servers at once can collide
        assert 60 < r["peak_mb"] < 2000 and 0.5 < r["cpu_s"] < 300, r
    for name in STUDENTS:
        files = sorted(
            p.relative_to(hub.homes / name).as_posix()
            for p in (hub.homes / name).rglob("*.ipynb")
            if ".ipynb_checkpoints" not in p.parts
        )
        assert files == [lesson.name], (name, files)
        saved = json.loads((hub.homes / name / lesson.name).read_text())
        first = "".join("".join(o.get("text", "")) for o in saved["cells"][0]["outputs"])
        assert first.startswith(f"camlab-hub-run {name} {hub.homes / name}"), first
        assert saved["cells"][-1]["cell_type"] == "markdown"
        last_code = [c for c in saved["cells"] if c["cell_type"] == "code"][-1]
        assert (
            last_code["execution_count"] == code_cells + 1
        )  # the saved notebook is the executed one
        for other in set(STUDENTS) - {name}:
            text = (hub.homes / other / lesson.name).read_text()
            assert (
                f"camlab-hub-run {name} " not in text
            )  # nobody else's notebook holds this student's run
    assert own == 200
    denied = [c for c in crossed if c[-1] in (200, 201)]
    assert not denied, f"a student reached another student's files: {denied}"
    assert {c[-1] for c in crossed if c[2] == "PUT"} <= {403, 404} and not list(
        hub.homes.rglob("intrusion.txt")
    )


def test_a_wait_past_its_deadline_fails_with_the_hub_log(tmp_path):
    """What replaced the hang: a wait that passes its deadline names what it waited for and shows the log."""
    log = tmp_path / "hub.log"
    log.write_text("...\n[E] ZMQError: Address already in use\n")
    hub = classhub.Hub("http://127.0.0.1:1", "token", tmp_path, log, process=None)
    with pytest.raises(
        RuntimeError, match=r"(?s)the kernel running 'x = 1': no answer within 0 s.*Address already"
    ):
        with classhub.failing_with_log(hub):
            asyncio.run(classhub.within(0.05, asyncio.sleep(10), "the kernel running 'x = 1'"))
