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


def test_readme_binder_badge_opens_the_first_lesson():
    link = re.search(r"\(https://mybinder\.org/v2/gh/([^)]*)\)", (REPO / "README.md").read_text()).group(1)
    path = re.search(r"labpath=([^&]+)", link).group(1).replace("%2F", "/")
    assert path == "lessons/00_start_here.ipynb" and (REPO / path).is_file() and "/HEAD?" in link


def _copy_repo(dest: Path) -> Path:
    """The repository's files (tracked and new, not ignored), as repo2docker or `docker build` sees them."""
    files = subprocess.run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"], cwd=REPO,
                           capture_output=True, text=True, check=True).stdout.split("\0")
    for rel in filter(None, files):
        if (REPO / rel).is_file():
            (dest / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(REPO / rel, dest / rel)
    return dest


def _fresh_venv(folder: Path) -> tuple[Path, dict]:
    if f"python-{sys.version_info[0]}.{sys.version_info[1]}" != (REPO / "binder" / "runtime.txt").read_text().strip():
        pytest.skip("this interpreter is not the Python binder/runtime.txt pins")
    subprocess.run([sys.executable, "-m", "venv", str(folder)], check=True)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV", "CAMLAB_FIGURE_MODE")}
    env["PATH"] = f"{folder / 'bin'}{os.pathsep}{env['PATH']}"
    return folder / "bin" / "python", env


def _imported_from(python: Path, cwd: Path, env: dict) -> str:
    return subprocess.run([str(python), "-c", "import camlab; print(camlab.__file__)"], cwd=cwd, env=env,
                          capture_output=True, text=True, check=True).stdout.strip()


heavy = pytest.mark.skipif(os.environ.get("CAMLAB_TEST_BINDER") != "1",
                           reason="installs whole environments afresh: run `make test-binder` (CI does)")


@pytest.mark.binder
@heavy
def test_binder_install_step_installs_camlab_from_the_lock_not_editable(dockerfile, tmp_path):
    """The image's install command, run in a copy of the repository; `make test-binder` then runs
    every lesson against this venv from a folder outside the repository (Makefile:
    run-lessons-outside, shared with `make test-wheel`)."""
    repo = _copy_repo(tmp_path / "repo")
    python, env = _fresh_venv(Path(os.environ.get("CAMLAB_BINDER_VENV", tmp_path / "env")).resolve())
    for step in _install_steps(dockerfile):  # exactly the image's install command, in the copied repository
        run = subprocess.run([str(python.parent / "pip"), *shlex.split(step)[1:]], cwd=repo, env=env,
                             capture_output=True, text=True, timeout=1800)
        assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    where = _imported_from(python, tmp_path, env)
    assert where.startswith(str(python.parent.parent)) and "site-packages" in where, where  # not editable
    frozen = subprocess.run([str(python.parent / "pip"), "freeze"], env=env, capture_output=True, text=True,
                            check=True).stdout
    lock = (REPO / "requirements" / "lock.txt").read_text()
    for package in ("numpy", "ipympl", "opencv-python-headless", "jupyterlab"):
        pinned = re.search(rf"^{package}==([^\s;]+)", lock, flags=re.M).group(1)
        assert f"{package}=={pinned}" in frozen, f"{package} is not the lock's {pinned}"


def _teaching_dockerfile() -> str:
    blocks = re.findall(r"```dockerfile\n(.*?)```", (REPO / "docs" / "teaching.md").read_text(), flags=re.S)
    return next(b for b in blocks if b.startswith("FROM quay.io/jupyter/"))


def test_the_hub_image_pins_its_base_by_date():
    image = _teaching_dockerfile().splitlines()[0].split()[1]
    assert re.fullmatch(r"quay\.io/jupyter/[a-z-]+-notebook:\d{4}-\d{2}-\d{2}", image), image


@pytest.mark.binder
@heavy
def test_the_hub_images_run_steps_work_in_a_fresh_venv(tmp_path):
    """docs/teaching.md's Dockerfile cannot be built here (no Docker daemon): run its RUN steps in a venv."""
    text = _teaching_dockerfile().replace("\\\n", " ")
    copy = re.search(r"^COPY \S+ \. (\S+)$", text, flags=re.M).group(1)
    repo = _copy_repo(tmp_path / "repo")
    python, env = _fresh_venv(tmp_path / "env")
    for step in re.findall(r"^RUN (.*)$", text, flags=re.M):
        run = subprocess.run(["bash", "-ec", step.replace(copy, str(repo))], env=env, capture_output=True,
                             text=True, timeout=1800)
        assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    assert not repo.exists()  # the image's clean-up ran
    where = _imported_from(python, tmp_path, env)
    assert where.startswith(str(python.parent.parent)) and "site-packages" in where, where
    copied = subprocess.run([str(python.parent / "camlab"), "lessons", str(tmp_path / "home" / "camlab-course")],
                            env=env, capture_output=True, text=True, timeout=120)
    assert copied.returncode == 0 and (tmp_path / "home" / "camlab-course" / "lessons" / "00_start_here.ipynb").is_file()
    extensions = subprocess.run([str(python.parent / "jupyter"), "server", "extension", "list"], env=env,
                                capture_output=True, text=True, timeout=120)
    assert "nbgitpuller" in extensions.stdout + extensions.stderr
