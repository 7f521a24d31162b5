"""Print this clone's Binder link and README badge, from its GitHub remote (`make binder-link`).

mybinder.org builds a GitHub repository by its path (owner/name); the README cannot know which
fork an instructor teaches from, so this derives it from ``git remote get-url origin`` (or the
remote named on the command line): ``python tools/binder_link.py [REMOTE]``.
"""

import re
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
FIRST_LESSON = "lessons/00_start_here.ipynb"
# https://github.com/o/r(.git), git@github.com:o/r(.git), ssh://git@github.com/o/r(.git)
GITHUB_URL = re.compile(
    r"^(?:https://(?:[^@/]+@)?github\.com/|git@github\.com:|ssh://git@github\.com/)"
    r"([A-Za-z0-9_.-]+)/([A-Za-z0-9_.-]+?)(?:\.git)?/?$"
)


def github_path(remote_url: str) -> str:
    """``owner/name`` of a GitHub remote URL; ValueError naming the URL for any other host."""
    match = GITHUB_URL.match(remote_url.strip())
    if not match:
        raise ValueError(
            f"remote {remote_url.strip()!r} is not a GitHub repository: mybinder.org builds "
            "github.com/OWNER/REPO; push the course there or write the link by hand "
            "(docs/teaching.md, section 1)"
        )
    return f"{match.group(1)}/{match.group(2)}"


def binder_link(path: str, lesson: str = FIRST_LESSON) -> str:
    """The mybinder.org URL that builds ``path``'s default branch and opens ``lesson`` in JupyterLab."""
    return f"https://mybinder.org/v2/gh/{path}/HEAD?labpath={lesson.replace('/', '%2F')}"


def main(argv: list[str]) -> int:
    remote = argv[0] if argv else "origin"
    found = subprocess.run(
        ["git", "remote", "get-url", remote], cwd=REPO, capture_output=True, text=True
    )
    if found.returncode != 0:
        print(
            f"binder-link: this clone has no git remote {remote!r} ({found.stderr.strip()}); add the "
            "GitHub repository you teach from: git remote add origin https://github.com/OWNER/REPO",
            file=sys.stderr,
        )
        return 2
    try:
        link = binder_link(github_path(found.stdout))
    except ValueError as error:
        print(f"binder-link: {error}", file=sys.stderr)
        return 2
    print(link)
    print(f"[![Binder](https://mybinder.org/badge_logo.svg)]({link})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
