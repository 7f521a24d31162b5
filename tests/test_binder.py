"""Binder: repo2docker picks the Python buildpack, Python 3.11 and a non-editable install from the lock.

Docker cannot run here, so the first test reads the Dockerfile repo2docker would build
(``jupyter-repo2docker --no-build --debug .``). The second (marked ``binder``, run by ``make
test-binder``) repeats the image's install step in a fresh venv on a copy of the repository,
then runs every lesson from a working folder outside both.
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
BIN = Path(sys.executable).parent


@pytest.fixture(scope="module")
def dockerfile() -> str:
    out = subprocess.run([str(BIN / "jupyter-repo2docker"), "--no-build", "--debug", str(REPO)],
                         capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    return out.stdout + out.stderr


def _install_steps(dockerfile: str) -> list[str]:
    """The `pip install` commands the image runs after copying the repository in."""
    after_copy = dockerfile.split("COPY --chown=0:0 src/ ${REPO_DIR}/", 1)[1]
    return re.findall(r"^RUN \$\{KERNEL_PYTHON_PREFIX\}/bin/(pip install .*)$", after_copy, flags=re.M)


def test_repo2docker_picks_python_311_and_installs_from_the_lock_not_editable(dockerfile):
    runtime = (REPO / "binder" / "runtime.txt").read_text().strip()
    assert runtime == "python-3.11"
    assert "Building conda environment for python=3.11" in dockerfile
    assert "FROM docker.io/library/buildpack-deps:" in dockerfile
    assert "environment.yml" not in dockerfile  # the Python buildpack (binder/requirements.txt), not conda's
    assert _install_steps(dockerfile) == ['pip install --no-cache-dir -r "binder/requirements.txt"']
    requirements = [ln.strip() for ln in (REPO / "binder" / "requirements.txt").read_text().splitlines()
                    if ln.strip() and not ln.startswith("#")]
    assert requirements == ["-r ../requirements/lock.txt", "."]  # the lock, then camlab itself, never -e
    lock = (REPO / "requirements" / "lock.txt").read_text()
    for package in ("numpy", "matplotlib", "ipympl", "ipywidgets", "jupyterlab", "opencv-python-headless"):
        assert re.search(rf"^{package}==\d", lock, flags=re.M), f"{package} is not pinned in the lock"


@pytest.mark.binder
def test_binder_install_runs_every_lesson_outside_the_repo(dockerfile, tmp_path):
    if f"python-{sys.version_info[0]}.{sys.version_info[1]}" != (REPO / "binder" / "runtime.txt").read_text().strip():
        pytest.skip("this interpreter is not the Python binder/runtime.txt pins")
    tracked = subprocess.run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"], cwd=REPO,
                             capture_output=True, text=True, check=True).stdout.split("\0")
    repo = tmp_path / "repo"  # what repo2docker copies into the image: the repository's files
    for rel in filter(None, tracked):
        if (REPO / rel).is_file():
            (repo / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(REPO / rel, repo / rel)
    env_dir = tmp_path / "env"
    subprocess.run([sys.executable, "-m", "venv", str(env_dir)], check=True)
    python = env_dir / "bin" / "python"
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV", "CAMLAB_FIGURE_MODE")}
    for step in _install_steps(dockerfile):  # exactly the image's install command, in the copied repository
        run = subprocess.run([str(env_dir / "bin" / "pip"), *shlex.split(step)[1:]], cwd=repo, env=env,
                             capture_output=True, text=True, timeout=1800)
        assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    where = subprocess.run([str(python), "-c", "import camlab; print(camlab.__file__)"], cwd=tmp_path, env=env,
                           capture_output=True, text=True, check=True).stdout.strip()
    assert where.startswith(str(env_dir)) and "site-packages" in where, where  # installed, not editable
    subprocess.run([str(env_dir / "bin" / "pip"), "install", "--quiet", "pytest", "pytest-xdist", "nbval"],
                   env=env, check=True, timeout=600)
    work = tmp_path / "work"  # a student's folder outside the repository
    shutil.copytree(repo / "lessons", work / "lessons")
    lessons = sorted(p.name for p in (work / "lessons").glob("[0-9][0-9]_*.ipynb"))
    run = subprocess.run([str(python), "-m", "pytest", "-p", "no:cacheprovider", "-n", "2", "--dist", "loadfile",
                          "--nbval-lax", "--nbval-current-env", "-q", "lessons"], cwd=work, env=env,
                         capture_output=True, text=True, timeout=2400)
    assert run.returncode == 0, run.stdout[-4000:] + run.stderr[-2000:]
    passed = int(re.search(r"(\d+) passed", run.stdout).group(1))
    assert len(lessons) == 12 and passed >= 12 * 10, run.stdout[-500:]
