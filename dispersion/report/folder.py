"""The report folder: written as one unit, never deleting what the toolkit did not write.

A folder that ``dispersion reproduce`` writes carries a marker file, :data:`MARKER`. The rules:

- ``--out`` must be a new folder, an empty one, or one that holds the marker. Anything else
  (a user's folder, a regular file) is refused with :class:`~dispersion.errors.InputError`
  before any work starts, so nothing of the user's is moved or deleted.
- A run stages its files in a temporary folder beside the target, after copying what the
  target already holds, so a run of some sections keeps every other file (other sections'
  results, anything a user put there). The staged folder then replaces the target in one
  atomic exchange (Linux ``renameat2(RENAME_EXCHANGE)``): under every interruption the target
  holds either the complete old or the complete new result. Where the exchange is not
  available, two renames are used and a later run restores the old folder if a kill fell
  between them.
- One run at a time per parent folder: a second concurrent run is refused in one line.
- Temporaries left by a killed run (``.NAME.tmp-*``) are removed by the next run, which names
  them in a one-line notice.
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
import ctypes
import errno
import fcntl
import os
import shutil
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

from dispersion.errors import InputError

__all__ = ["MARKER", "check_target", "open_report", "stale_temporaries"]

#: Name of the file that marks a folder as written by ``dispersion reproduce``.
MARKER = ".dispersion-report"
_MARKER_TEXT = "This folder is written by `dispersion reproduce`; it may replace files here.\n"


def check_target(out: Path, option: str = "--out") -> Path:
    """Return ``out`` as an absolute path if a report may be written there, else raise.

    Raises
    ------
    InputError
        ``out`` is a file, or an existing non-empty folder without :data:`MARKER`, or its
        parent is not a writable folder.
    """
    if str(out) in ("", "-"):
        raise InputError(f"{option} must name a folder (new, empty or a report folder), "
                         f"got {str(out)!r}")
    out = Path(out)
    out = out.absolute()
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


def stale_temporaries(out: Path) -> list[Path]:
    """Temporaries of earlier runs into ``out`` that are still beside it."""
    out = Path(out).absolute()
    return sorted(out.parent.glob(f".{out.name}.tmp-*")) + sorted(out.parent.glob(f".{out.name}.old-*"))


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _exchange(a: Path, b: Path) -> bool:
    """Atomically swap two paths (Linux ``renameat2`` RENAME_EXCHANGE); False if unsupported."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        renameat2 = libc.renameat2
    except (OSError, AttributeError):
        return False
    at_fdcwd, rename_exchange = -100, 2
    if renameat2(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), rename_exchange) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.EINVAL, errno.ENOSYS, errno.ENOTSUP):
        return False
    raise OSError(err, os.strerror(err), str(a))


@contextlib.contextmanager
def _lock(out: Path) -> Iterator[None]:
    # The lock is on the parent folder itself (flock on a directory descriptor): it leaves no
    # lock file behind, and it covers the temporaries, which live in the parent too.
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


def _recover(out: Path, notice) -> None:
    """Restore a target left missing by a kill between the two renames of the fallback swap."""
    olds = sorted(out.parent.glob(f".{out.name}.old-*"))
    if not out.exists() and olds:
        olds[-1].rename(out)
        notice(f"restored {out} from {olds[-1].name}, left by an interrupted run")


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
        _recover(out, notice)
        stale = stale_temporaries(out)
        for path in stale:
            shutil.rmtree(path, ignore_errors=True)
        if stale:
            notice(f"removed {len(stale)} temporary folder(s) left by an interrupted run: "
                   + ", ".join(p.name for p in stale))
        staged = Path(tempfile.mkdtemp(dir=out.parent, prefix=f".{out.name}.tmp-"))
        try:
            os.chmod(staged, 0o777 & ~_umask())
            if out.is_dir():
                shutil.copytree(out, staged, dirs_exist_ok=True, symlinks=True)
            (staged / MARKER).write_text(_MARKER_TEXT, encoding="utf-8")
            yield staged
            if out.exists() and _exchange(staged, out):
                pass  # the old report now sits at ``staged``; removed below
            else:
                old = None
                if out.exists():
                    old = Path(tempfile.mkdtemp(dir=out.parent, prefix=f".{out.name}.old-"))
                    old.rmdir()
                    out.rename(old)
                staged.rename(out)
                if old is not None:
                    shutil.rmtree(old, ignore_errors=True)
        finally:
            if staged.exists():
                shutil.rmtree(staged, ignore_errors=True)
