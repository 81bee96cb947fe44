"""The commit a benchmark races against, named once for every benchmark script.

Without a ref: the merge base of HEAD with ``main`` (where a branch started), or ``HEAD~1``
where that is HEAD itself (on ``main``, the previous commit) or cannot be found.
"""
from __future__ import annotations

import subprocess
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def _git(*args: str, check: bool = False) -> subprocess.CompletedProcess:
    return subprocess.run(["git", "-C", str(REPO), *args], capture_output=True, text=True,
                          check=check)


def previous_commit(ref: str | None = None) -> str:
    """The short hash of ``ref`` (module docstring for the default)."""
    if ref is None:
        base, head = _git("merge-base", "HEAD", "main"), _git("rev-parse", "HEAD")
        ref = base.stdout.strip()
        if base.returncode != 0 or not ref or ref == head.stdout.strip():
            ref = "HEAD~1"
    return _git("rev-parse", "--short", ref, check=True).stdout.strip()
