"""The classroom kit: Binder (binder/), the hub image (hub/Dockerfile) and its hub (hub/config.yaml).

Binder: repo2docker picks the Python buildpack, Python 3.11 and a non-editable install from the
students' lock. There is no Docker daemon here, so the quick tests read the Dockerfile
repo2docker would build (``jupyter-repo2docker --no-build --debug .``), hub/Dockerfile and the
build context .dockerignore leaves; the heavy ones (marked ``binder``, run by ``make
test-binder``) repeat each image's install steps in a fresh venv on a copy of that context, and
the Makefile then runs every lesson from a working folder outside both.
"""

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path
from typing import NamedTuple

import pytest

REPO = Path(__file__).resolve().parent.parent
BIN = Path(sys.executable).parent
STUDENTS_LOCK = REPO / "requirements" / "students.txt"
sys.path.insert(0, str(REPO / "tools"))


@pytest.fixture(scope="module")
def dockerfile() -> str:
    out = subprocess.run(
        [str(BIN / "jupyter-repo2docker"), "--no-build", "--debug", str(REPO)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    return out.stdout + out.stderr


def _install_steps(dockerfile: str) -> list[str]:
    """The `pip install` commands the image runs after copying the repository in."""
    after_copy = dockerfile.split("COPY --chown=0:0 src/ ${REPO_DIR}/", 1)[1]
    return re.findall(
        r"^RUN \$\{KERNEL_PYTHON_PREFIX\}/bin/(pip install .*)$", after_copy, flags=re.M
    )


def test_repo2docker_picks_python_311_and_installs_from_the_lock_not_editable(dockerfile):
    runtime = (REPO / "binder" / "runtime.txt").read_text().strip()
    assert runtime == "python-3.11"
    assert "Building conda environment for python=3.11" in dockerfile
    assert "FROM docker.io/library/buildpack-deps:" in dockerfile
    assert (
        "environment.yml" not in dockerfile
    )  # the Python buildpack (binder/requirements.txt), not conda's
    assert _install_steps(dockerfile) == ['pip install --no-cache-dir -r "binder/requirements.txt"']
    requirements = [
        ln.strip()
        for ln in (REPO / "binder" / "requirements.txt").read_text().splitlines()
        if ln.strip() and not ln.startswith("#")
    ]
    assert requirements == [
        "-r ../requirements/students.txt",
        ".",
    ]  # the students' lock, then camlab, never -e
    lock = STUDENTS_LOCK.read_text()
    for package in (
        "numpy",
        "matplotlib",
        "ipympl",
        "ipywidgets",
        "jupyterlab",
        "opencv-python-headless",
    ):
        assert re.search(rf"^{package}==\d", lock, flags=re.M), (
            f"{package} is not pinned in the students' lock"
        )
    # repo2docker's own jupyterhub-singleuser (mybinder.org's hub version) must stay
    assert not re.search(r"^jupyterhub==", lock, flags=re.M)


def test_binder_link_is_derived_from_the_clones_github_remote():
    from binder_link import FIRST_LESSON, binder_link, github_path

    for url in (
        "https://github.com/ada/camera-course.git",
        "git@github.com:ada/camera-course.git\n",
        "ssh://git@github.com/ada/camera-course",
        "https://github.com/ada/camera-course/",
    ):
        assert github_path(url) == "ada/camera-course", url
    with pytest.raises(
        ValueError, match="'https://gitlab.com/ada/course.git' is not a GitHub repository"
    ):
        github_path("https://gitlab.com/ada/course.git")
    link = binder_link("ada/camera-course")
    assert (
        link
        == "https://mybinder.org/v2/gh/ada/camera-course/HEAD?labpath=lessons%2F00_start_here.ipynb"
    )
    assert (REPO / FIRST_LESSON).is_file()
    readme = (REPO / "README.md").read_text()
    assert (
        "make binder-link" in readme and "OWNER/REPO" not in readme
    )  # no badge that points nowhere


def test_binder_link_without_the_remote_says_what_to_add(capsys):
    from binder_link import main

    assert main(["no-such-remote"]) == 2
    assert "no git remote 'no-such-remote'" in capsys.readouterr().err


def _dockerignore() -> list[str]:
    lines = (REPO / ".dockerignore").read_text().splitlines()
    return [ln.strip() for ln in lines if ln.strip() and not ln.startswith("#")]


def _build_context(root: Path) -> set[str]:
    """The files under ``root`` that `docker build` (and repo2docker, binder/.dockerignore) sends:
    docker-py's own reading of .dockerignore, the one repo2docker uses."""
    from docker.utils.build import exclude_paths

    return {p for p in exclude_paths(str(root), _dockerignore()) if (root / p).is_file()}


def _copy_repo(dest: Path) -> Path:
    """The repository as the image sees it: its build context, copied to ``dest``."""
    for rel in _build_context(REPO):
        (dest / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(REPO / rel, dest / rel)
    return dest


def test_the_build_context_leaves_out_a_dev_clones_environments_builds_and_history(tmp_path):
    left_out = [
        ".venv/lib/python3.11/site-packages/numpy/__init__.py",
        ".venv-oldest/bin/python",
        "build/venv-wheel/bin/python",
        "dist/camlab_course-0.1.0-py3-none-any.whl",
        "site/index.html",
        ".git/HEAD",
        "camlab/__pycache__/pinhole.cpython-311.pyc",
        "lessons/.ipynb_checkpoints/00_start_here-checkpoint.ipynb",
        "camlab_course.egg-info/PKG-INFO",
    ]
    kept = [
        "pyproject.toml",
        "setup.py",
        "README.md",
        "LICENSE",
        "camlab/pinhole.py",
        "requirements/students.txt",
        "lessons/00_start_here.ipynb",
        "camlab/data/chessboard/left01.jpg",
        "hub/Dockerfile",
    ]
    for rel in left_out + kept:
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text("x")
    assert _build_context(tmp_path) == set(kept)
    # binder/.dockerignore, which repo2docker reads, is the same file
    assert (REPO / "binder" / ".dockerignore").resolve() == (REPO / ".dockerignore").resolve()


def test_every_tracked_file_goes_into_the_build_context():
    tracked = subprocess.run(
        ["git", "ls-files", "-z"], cwd=REPO, capture_output=True, text=True, check=True
    ).stdout.split("\0")
    missing = sorted(set(filter(None, tracked)) - _build_context(REPO))
    assert not missing, f".dockerignore leaves out tracked files: {missing[:10]}"


def _fresh_venv(folder: Path) -> tuple[Path, dict]:
    if (
        f"python-{sys.version_info[0]}.{sys.version_info[1]}"
        != (REPO / "binder" / "runtime.txt").read_text().strip()
    ):
        pytest.skip("this interpreter is not the Python binder/runtime.txt pins")
    subprocess.run([sys.executable, "-m", "venv", str(folder)], check=True)
    env = {
        k: v
        for k, v in os.environ.items()
        if k not in ("PYTHONPATH", "VIRTUAL_ENV", "CAMLAB_FIGURE_MODE")
    }
    env["PATH"] = f"{folder / 'bin'}{os.pathsep}{env['PATH']}"
    return folder / "bin" / "python", env


def _imported_from(python: Path, cwd: Path, env: dict) -> str:
    return subprocess.run(
        [str(python), "-c", "import camlab; print(camlab.__file__)"],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()


heavy = pytest.mark.skipif(
    os.environ.get("CAMLAB_TEST_BINDER") != "1",
    reason="installs whole environments afresh: run `make test-binder` (CI does)",
)


@pytest.mark.binder
@heavy
def test_binder_install_step_installs_camlab_from_the_students_lock_not_editable(
    dockerfile, tmp_path
):
    """The image's install command, run in a copy of the repository; `make test-binder` then runs
    every lesson against this venv from a folder outside the repository (Makefile:
    run-lessons-outside, shared with `make test-wheel`)."""
    repo = _copy_repo(tmp_path / "repo")
    python, env = _fresh_venv(
        Path(os.environ.get("CAMLAB_BINDER_VENV", tmp_path / "env")).resolve()
    )
    for step in _install_steps(
        dockerfile
    ):  # exactly the image's install command, in the copied repository
        run = subprocess.run(
            [str(python.parent / "pip"), *shlex.split(step)[1:]],
            cwd=repo,
            env=env,
            capture_output=True,
            text=True,
            timeout=1800,
        )
        assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    where = _imported_from(python, tmp_path, env)
    assert where.startswith(str(python.parent.parent)) and "site-packages" in where, (
        where
    )  # not editable
    frozen = subprocess.run(
        [str(python.parent / "pip"), "freeze"], env=env, capture_output=True, text=True, check=True
    ).stdout
    lock = STUDENTS_LOCK.read_text()
    for package in ("numpy", "ipympl", "opencv-python-headless", "jupyterlab"):
        pinned = re.search(rf"^{package}==([^\s;]+)", lock, flags=re.M).group(1)
        assert f"{package}=={pinned}" in frozen, f"{package} is not the students' lock's {pinned}"


class HubDockerfile(NamedTuple):
    """What the tests read from hub/Dockerfile (continuation lines joined, comments dropped)."""

    base: str  # the FROM image
    args: dict[str, str]  # ARG name -> default
    copy_dest: str  # where COPY puts the build context
    runs: list[str]  # the RUN steps' shell commands


def _hub_dockerfile() -> HubDockerfile:
    lines = [
        ln
        for ln in (REPO / "hub" / "Dockerfile").read_text().splitlines()
        if not ln.lstrip().startswith("#")
    ]
    text = "\n".join(lines).replace("\\\n", " ")
    return HubDockerfile(
        base=re.search(r"^FROM (\S+)$", text, flags=re.M).group(1),
        args=dict(re.findall(r"^ARG (\w+)=(\S+)$", text, flags=re.M)),
        copy_dest=re.search(r"^COPY \S+ \. (\S+)$", text, flags=re.M).group(1),
        runs=re.findall(r"^RUN (.*)$", text, flags=re.M),
    )


def test_the_hub_image_pins_its_base_by_date_and_installs_the_students_lock():
    image = _hub_dockerfile()
    assert re.fullmatch(r"quay\.io/jupyter/[a-z-]+-notebook:\d{4}-\d{2}-\d{2}", image.base), (
        image.base
    )
    assert any(f"-r {image.copy_dest}/requirements/students.txt" in step for step in image.runs), (
        image.runs
    )
    assert (
        "hub/Dockerfile" in (REPO / "docs" / "teaching.md").read_text()
    )  # the page points at the file


def test_the_hub_images_jupyterhub_defaults_to_the_version_the_hub_test_runs():
    """Its single-user server must match the hub; by default the version of requirements/lock.txt."""
    default = _hub_dockerfile().args["JUPYTERHUB_VERSION"]
    pinned = re.search(
        r"^jupyterhub==(\S+)$", (REPO / "requirements" / "lock.txt").read_text(), flags=re.M
    )
    assert pinned and default == pinned.group(1), (default, pinned)


def test_the_hubs_login_is_github_oauth_limited_to_the_class_organisation():
    """hub/config.yaml: every setting is a real setting of its class, with the values a class needs."""
    from importlib.metadata import entry_points

    import yaml
    from jupyterhub.app import JupyterHub
    from jupyterhub.auth import Authenticator
    from traitlets.config import Config

    config = yaml.safe_load((REPO / "hub" / "config.yaml").read_text())["hub"]["config"]
    name = config["JupyterHub"]["authenticator_class"]
    found = entry_points(group="jupyterhub.authenticators", name=name)
    assert found, (
        f"no JupyterHub authenticator {name!r} installed: install the class extra (oauthenticator)"
    )
    github = next(iter(found)).load()
    assert github.__name__ == "GitHubOAuthenticator"
    classes = {
        "JupyterHub": JupyterHub,
        "Authenticator": Authenticator,
        "GitHubOAuthenticator": github,
    }
    assert set(config) == set(classes)
    for section, settings in config.items():
        unknown = set(settings) - set(classes[section].class_trait_names(config=True))
        assert not unknown, f"hub/config.yaml: {section} has no settings {sorted(unknown)}"
    login = github(config=Config(config))
    assert login.allowed_organizations == {"camlab-class-2026"} and "read:org" in login.scope
    assert login.admin_users == {"your-github-username"} and not login.allow_all
    assert (
        "client_secret" not in config["GitHubOAuthenticator"]
    )  # secrets stay out of the repository


@pytest.mark.binder
@heavy
def test_the_hub_images_run_steps_work_in_a_fresh_venv(tmp_path):
    """hub/Dockerfile cannot be built here (no Docker daemon): run its RUN steps in a venv, with
    its ARG defaults in the environment and its COPY destination replaced by a copy of the context."""
    image = _hub_dockerfile()
    repo = _copy_repo(tmp_path / "repo")
    python, env = _fresh_venv(tmp_path / "env")
    env.update(image.args)
    for step in image.runs:
        run = subprocess.run(
            ["bash", "-ec", step.replace(image.copy_dest, str(repo))],
            env=env,
            capture_output=True,
            text=True,
            timeout=1800,
        )
        assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    assert not repo.exists()  # the image's clean-up ran
    where = _imported_from(python, tmp_path, env)
    assert where.startswith(str(python.parent.parent)) and "site-packages" in where, where
    copied = subprocess.run(
        [str(python.parent / "camlab"), "lessons", str(tmp_path / "home" / "camlab-course")],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert (
        copied.returncode == 0
        and (tmp_path / "home" / "camlab-course" / "lessons" / "00_start_here.ipynb").is_file()
    )
    extensions = subprocess.run(
        [str(python.parent / "jupyter"), "server", "extension", "list"],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert "nbgitpuller" in extensions.stdout + extensions.stderr
    hub = subprocess.run(
        [str(python.parent / "jupyterhub-singleuser"), "--version"],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert hub.stdout.strip() == image.args["JUPYTERHUB_VERSION"], hub.stdout + hub.stderr


@pytest.mark.binder
@heavy
@pytest.mark.parametrize("jupyterhub", ["5.*", "6.*"])
def test_the_hub_image_resolves_with_the_jupyterhub_of_zero_to_jupyterhub(jupyterhub, tmp_path):
    """docs/teaching.md's advice, `--build-arg JUPYTERHUB_VERSION='5.*'`, resolves against the students' lock."""
    extra = tmp_path / "hub.in"
    extra.write_text(f"jupyterhub=={jupyterhub}\nnbgitpuller==1.3.0\n")
    run = subprocess.run(
        [
            str(BIN / "uv"),
            "pip",
            "compile",
            "--quiet",
            "--python-version",
            "3.11",
            str(STUDENTS_LOCK),
            str(extra),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert run.returncode == 0, run.stderr[-3000:]
    assert re.search(rf"^jupyterhub=={jupyterhub.replace('.*', '.')}", run.stdout, flags=re.M), (
        run.stdout
    )
