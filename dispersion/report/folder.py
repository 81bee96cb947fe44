"""The report folder of ``dispersion reproduce``: written as one unit by the toolkit's one
folder writer, never replacing what the toolkit did not write.

The rules are those of every output folder (:mod:`dispersion.ownership`,
:func:`dispersion.io.open_folder`):

- ``--out`` must be a new folder, an empty one, or one that holds the marker :data:`MARKER`
  and nothing but regular files and folders of the user; anything else (a user's folder, a
  link, a regular file, ``''``) is refused with :class:`~dispersion.errors.InputError`
  before any work starts.
- A run builds the new version beside the target, starting as a copy of what the target
  holds (a run of some sections keeps every other file), and swaps it in with one atomic
  exchange: under every interruption the target holds either the complete old or the
  complete new report (:mod:`dispersion.staging` states what a kill leaves).
- One run at a time per parent folder: a second concurrent run is refused in one line.
- Nothing beside the target is ever deleted, renamed or adopted, whatever its name;
  temporaries of killed runs are reported in one line and left to the user.

>>> import tempfile, pathlib
>>> root = pathlib.Path(tempfile.mkdtemp())
>>> with open_report(root / "reports") as staged:
...     _ = (staged / "a.md").write_text("new")
>>> sorted(p.name for p in (root / "reports").iterdir())
['.dispersion-report', 'a.md']
"""
from __future__ import annotations

import contextlib
import fcntl
import os
from collections.abc import Iterator
from pathlib import Path

from dispersion.errors import InputError
from dispersion.io import open_folder, stale_temporaries as _stale
from dispersion.ownership import MARKER, check_folder

__all__ = ["MARKER", "check_target", "open_report", "stale_temporaries"]


def check_target(out, option: str = "--out") -> Path:
    """Return ``out`` as an absolute path if a report may be written there, else raise.

    Raises
    ------
    InputError
        ``out`` is empty or ``-``, a file or a link, or an existing non-empty folder without
        :data:`MARKER` (or with anything but regular files and folders of the user).

    >>> check_target("")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: --out must be a folder path, got ''
    """
    check_folder(out, option)
    out = Path(os.path.abspath(os.fspath(out)))
    if not out.parent.is_dir():
        raise InputError(f"{option} {out}: the parent folder {out.parent} does not exist")
    return out


def stale_temporaries(out) -> list[Path]:
    """Temporaries of killed runs beside ``out`` (listed, never changed)."""
    return _stale(Path(os.path.abspath(out)).parent)


@contextlib.contextmanager
def _lock(out: Path) -> Iterator[None]:
    # The lock is on the parent folder itself (flock on a directory descriptor): it leaves no
    # lock file behind, and it covers the new version, which is built in the parent too.
    fd = os.open(out.parent, os.O_RDONLY)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise InputError(f"--out {out}: another dispersion run is writing into {out.parent}; "
                             "wait for it to finish") from None
        yield
    finally:
        os.close(fd)


@contextlib.contextmanager
def open_report(out, *, notice=None) -> Iterator[Path]:
    """Stage a report for ``out``; on success it replaces ``out`` as one unit.

    Yields the staged folder, which starts as a copy of what ``out`` holds. If the body raises
    (or the process is interrupted), ``out`` is left exactly as it was and the staged folder is
    removed. ``notice(text)`` receives one-line notices (default: print to stderr).
    """
    out = check_target(out)
    with _lock(out), open_folder(out, option="--out", notice=notice) as staged:
        yield staged
