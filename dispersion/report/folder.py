"""The report folder: written as one unit, never deleting what the toolkit did not write.

A folder that ``dispersion reproduce`` writes carries a marker file, :data:`MARKER`, which
records the random token of the run that wrote it. The rules:

- ``--out`` must be a new folder, an empty one, or one that holds the marker. Anything else
  (a user's folder, a regular file, ``''``) is refused with
  :class:`~dispersion.errors.InputError` before any work starts, so nothing of the user's is
  moved or deleted.
- A run stages its files with the toolkit's one staged writer
  (:class:`dispersion.staging.Stage`): a stage folder ``.dispersion-stage.TOKEN`` beside the
  target, starting as a copy of what the target already holds, so a run of some sections
  keeps every other file (other sections' results, anything a user put there). The staged
  folder then replaces the target in one atomic exchange (Linux
  ``renameat2(RENAME_EXCHANGE)``): under every interruption the target holds either the
  complete old or the complete new result. Where the exchange is not available, two renames
  are used under a journal (a kill between them leaves the target absent), and the next run
  finishes them.
- One run at a time per parent folder: a second concurrent run is refused in one line.
- What a killed run left is settled by the next run, by :func:`dispersion.staging.recover`:
  only stage folders whose name and recorded token verify; it names them in a one-line
  notice. No other folder beside the target is ever deleted, renamed or adopted, whatever its
  name (``.reports.old-2``, ``.reports.tmp-x``...).
- Files and folders follow the umask.

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
import shutil
import sys
from collections.abc import Iterator
from pathlib import Path

from dispersion.errors import InputError
from dispersion.staging import Stage, marker_text, recover, stale_stages

__all__ = ["MARKER", "check_target", "open_report", "stale_temporaries"]

#: Name of the file that marks a folder as written by ``dispersion reproduce``.
MARKER = ".dispersion-report"
_MARKER_TEXT = "This folder is written by `dispersion reproduce`; it may replace files here.\n"


def check_target(out, option: str = "--out") -> Path:
    """Return ``out`` as an absolute path if a report may be written there, else raise.

    Raises
    ------
    InputError
        ``out`` is empty or ``-``, a file, or an existing non-empty folder without
        :data:`MARKER`, or its parent is not a writable folder.

    >>> check_target("")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: --out must name a folder (new, empty or a report folder), got ''
    """
    text = os.fspath(out) if out is not None else ""
    if not text.strip() or text == "-" or "\0" in text:
        raise InputError(f"{option} must name a folder (new, empty or a report folder), "
                         f"got {text!r}")
    out = Path(os.path.abspath(text))
    if out == out.parent:
        raise InputError(f"{option} must not be the root folder")
    if out.exists() or out.is_symlink():
        if out.is_symlink() or not out.is_dir():
            raise InputError(f"{option} {out} exists and is not a folder; name a new or a report folder")
        if any(out.iterdir()) and not (out / MARKER).is_file():
            raise InputError(
                f"{option} {out} holds files that dispersion did not write (no {MARKER} marker); "
                "name a new or empty folder")
    parent = out.parent
    if not parent.is_dir():
        raise InputError(f"{option} {out}: the parent folder {parent} does not exist")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(f"{option} {out}: the parent folder {parent} is not writable")
    return out


def stale_temporaries(out) -> list[Path]:
    """Stages of killed runs beside ``out`` that verify as ours (see :mod:`dispersion.staging`)."""
    return stale_stages(Path(os.path.abspath(out)).parent)


@contextlib.contextmanager
def _lock(out: Path) -> Iterator[None]:
    # The lock is on the parent folder itself (flock on a directory descriptor): it leaves no
    # lock file behind, and it covers the stages, which live in the parent too.
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
    notice = notice or (lambda text: print(f"dispersion: {text}", file=sys.stderr))
    out = check_target(out)
    with _lock(out):
        recover(out.parent, notice=notice)
        with Stage(notice=notice) as unit:
            staged = unit.folder(out, MARKER)
            if out.is_dir():
                shutil.copytree(out, staged, dirs_exist_ok=True, symlinks=True)
            (staged / MARKER).write_text(marker_text(_MARKER_TEXT, unit.token), encoding="utf-8")
            yield staged
            unit.commit()
