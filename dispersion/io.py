"""Safe output: every writer of the toolkit, under one owner rule, complete or absent.

Every file and folder the toolkit writes goes through this module:

- **One owner rule, checked up front and again at the end** (:mod:`dispersion.ownership`):
  a file is written only if it is absent or a regular file of the user; a folder only if
  it is absent, empty, or carries the ``.dispersion-report`` marker and holds nothing but
  regular files and folders of the user. Links are never followed, other users' files
  never replaced. :func:`check_output_file` and :func:`check_output_dir` apply the rule
  before any work and raise :class:`~dispersion.errors.InputError` naming the option.
- **Atomic files.** :func:`atomic_write` (and :func:`write_text`, :func:`write_bytes`,
  :func:`save_figure`) writes a new temporary beside the target and renames it onto the
  target (:class:`dispersion.staging.NewFile`): a reader sees the old file or the new one.
- **Atomic folders.** :func:`open_folder` (and :func:`write_files`) builds the new version
  of a folder beside it, starting as a copy of what it holds, and swaps it in whole
  (:class:`dispersion.staging.NewFolder`); the folder gets the marker.
- **Several files** of one command (:func:`write_unit`: ``branches --csv --figure``) are all
  written first, then renamed one after the other: each file is whole, old or new.
- **What a kill leaves** is stated in :mod:`dispersion.staging`: never a partial file or
  folder under the target's name, and temporaries that later runs report and never touch.
- **Modes follow the umask.** A new file gets ``0o666 & ~umask``, a new folder
  ``0o777 & ~umask``; a replaced file or folder keeps its permission bits.
- **Streams.** ``-`` is standard output, ``/dev/stdout`` and ``/dev/stderr`` the streams
  themselves; a character device or named pipe of the user (or the null device) is written
  through (a pipe nobody opens for reading within :data:`PIPE_WAIT` seconds is refused,
  never waited on for ever); one of another user is refused like their files.
- **Write errors are one line.** A full disk or an I/O error raises :class:`OutputError`; a
  path that cannot be written :class:`~dispersion.errors.InputError`; nothing partial stays.

>>> import tempfile, pathlib
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> check_output_file(folder, option="--csv")
Traceback (most recent call last):
...
dispersion.errors.InputError: --csv must name a file, but ... is an existing folder
>>> write_text(folder / "a.txt", "one").read_text()
'one'
"""
from __future__ import annotations

import contextlib
import errno
import fcntl
import os
import re
import sys
import time
from collections.abc import Iterator, Mapping
from pathlib import Path

from dispersion import ownership
from dispersion.errors import DispersionError, InputError
from dispersion.ownership import MARKER, MARKER_TEXT, STDOUT
from dispersion.staging import NewFile, NewFolder, checkpoint, leftovers, notice_leftovers
from dispersion.untrusted import printable

__all__ = [
    "OutputError",
    "STDOUT",
    "MARKER",
    "atomic_write",
    "write_text",
    "write_bytes",
    "save_figure",
    "open_folder",
    "write_files",
    "write_unit",
    "check_output_file",
    "check_output_dir",
    "unit_target",
    "umask",
    "stale_temporaries",
]

#: Seconds a writer waits for a reader of a named pipe it is asked to write to.
PIPE_WAIT = 10.0
# errno values that mean "this path cannot be written by you": the user's choice, exit 2.
_PATH_ERRORS = {errno.EACCES, errno.EPERM, errno.EROFS, errno.ENOENT, errno.ENOTDIR,
                errno.EISDIR, errno.ENAMETOOLONG, errno.ELOOP, errno.EEXIST, errno.ENXIO}
# errno values of a full disk or quota, wherever they surface (a write, a flush, a close)
_FULL_ERRORS = {errno.ENOSPC, errno.EDQUOT, errno.EFBIG}


class OutputError(DispersionError):
    """Writing an output failed (full disk, I/O error); no partial file was left."""


def umask() -> int:
    """The process umask, read without changing it where Linux allows (``/proc``)."""
    with contextlib.suppress(OSError, ValueError):
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("Umask:"):
                return int(line.split()[1], 8)
    old = os.umask(0o022)  # pragma: no cover - not Linux
    os.umask(old)  # pragma: no cover
    return old  # pragma: no cover


def _error(exc: OSError, shown: str, option: str | None) -> DispersionError:
    """One-line toolkit error for an ``OSError`` met while writing ``shown``."""
    what = f"{option} {shown}" if option else shown
    reason = exc.strerror or type(exc).__name__
    if exc.errno in _PATH_ERRORS:
        return InputError(f"cannot write {what}: {reason} (choose a writable path)")
    return OutputError(f"cannot write {what}: {reason}; nothing was written")


@contextlib.contextmanager
def _named(shown: str, option: str | None, errnos=None):
    """An ``OSError`` in the block becomes the one-line error about ``shown``; with
    ``errnos``, only those (other errors are the caller's, passed on unchanged)."""
    try:
        yield
    except OSError as exc:
        if errnos is None or exc.errno in errnos:
            raise _error(exc, shown, option) from None
        raise


def _text(path) -> str:
    return os.fspath(path) if path is not None else ""


def check_output_file(path, option: str = "--out", *, allow_stdout: bool = True,
                      suffixes: tuple[str, ...] | None = None,
                      create_parents: bool = False) -> Path | str:
    """Check, before any work, that ``path`` can receive a file; return it.

    Parameters
    ----------
    path : str or Path
        The output file; ``"-"`` means standard output when ``allow_stdout``.
    option : str
        The option (or parameter) name used in the error message, e.g. ``"--csv"``.
    allow_stdout : bool
        Accept ``"-"``.
    suffixes : tuple of str, optional
        Accepted file name endings (case-insensitive), e.g. ``(".png", ".pdf")``.
    create_parents : bool
        Accept a missing parent folder (it will be created); default: refuse it.

    Returns
    -------
    Path or str
        ``Path(path)``, or ``"-"``.

    Raises
    ------
    InputError
        ``''``; an existing folder; a link; another user's file; a block device or socket;
        a missing (unless ``create_parents``), non-folder or read-only parent; a wrong suffix.

    >>> check_output_file("-", option="--csv")
    '-'
    >>> check_output_file("", option="--csv")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: --csv must be a file path, got ''
    """
    target = ownership.check_file(path, option, allow_stdout=allow_stdout, suffixes=suffixes,
                                  create_parents=create_parents)
    return STDOUT if target.kind == "stdout" else Path(_text(path))


def check_output_dir(path, option: str = "--out") -> Path:
    """Check, before any work, that ``path`` is or can become an output folder (new, empty,
    or written by dispersion and wholly the user's: :mod:`dispersion.ownership`); return it.

    >>> check_output_dir("-", option="--out")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: --out must be a folder path, got '-'
    """
    ownership.check_folder(path, option)
    return Path(_text(path))


def unit_target(path) -> Path | None:
    """Where a unit writes ``path``: the path itself; None for a stream (``-``, a standard
    stream, a character device or named pipe), which is written through, not staged.

    >>> unit_target("-") is None, unit_target("/dev/null") is None
    (True, True)
    """
    kind = ownership.check_file(path, "output").kind
    return None if kind in ("stdout", "stderr", "stream") else Path(_text(path))


def _stream(target, way, mode: str, kwargs):
    """The open stream of ``target`` (standard streams, devices, pipes)."""
    binary = "b" in mode
    if target.kind in ("stdout", "stderr"):
        stream = getattr(sys, target.kind)
        return stream.buffer if binary else stream, False
    flags = os.O_WRONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_NOCTTY | os.O_CLOEXEC
    deadline = time.monotonic() + PIPE_WAIT
    while True:  # a named pipe opens for writing once a reader has it open
        try:
            fd = os.open(way.name, flags, dir_fd=way.fd)
            break
        except OSError as exc:
            if exc.errno != errno.ENXIO:
                raise
            if time.monotonic() > deadline:
                raise InputError(f"{target.option} {way.shown}: no process opened this named "
                                 f"pipe for reading within {PIPE_WAIT:g} s") from None
            time.sleep(0.02)
    st = os.fstat(fd)
    if (st.st_dev, st.st_ino) != target.ident:  # replaced since the owner rule allowed it
        os.close(fd)
        raise InputError(f"{target.option} {way.shown} changed while dispersion checked it; "
                         "nothing was written")
    flags = fcntl.fcntl(fd, fcntl.F_GETFL)
    fcntl.fcntl(fd, fcntl.F_SETFL, flags & ~os.O_NONBLOCK)
    return open(fd, mode, **kwargs), True


def _write_all(fd: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view):]


def _folder_text(text: str) -> str:
    head = os.path.dirname(text.rstrip("/"))
    return head if head else ""


@contextlib.contextmanager
def atomic_write(path, mode: str = "w", *, option: str | None = None, notice=None, **kwargs):
    """Open a new temporary beside the file ``path``; rename it onto ``path`` on success.

    The owner rule (:mod:`dispersion.ownership`) is applied when the writing starts and
    again before the rename; an error, Ctrl-C or SIGTERM removes the temporary, and what a
    SIGKILL leaves is reported (never removed) by later writers. ``path`` ``"-"`` yields
    standard output (text or binary by ``mode``); a character device or named pipe is
    written through. Missing folders on the way are made (and removed again on failure).
    ``option`` names the CLI option in error messages.

    >>> import tempfile, pathlib
    >>> target = pathlib.Path(tempfile.mkdtemp()) / "out.txt"
    >>> with atomic_write(target) as fh:
    ...     _ = fh.write("done")
    >>> target.read_text()
    'done'
    """
    opt = option or "output"
    target = ownership.check_file(path, opt)
    if target.kind in ("stdout", "stderr"):
        stream, _ = _stream(target, None, mode, kwargs)
        yield stream
        stream.flush()
        return
    text = _text(path)
    ok = False
    ways: list = []  # the cleanup record of the way there, set up before anything is made
    try:
        with _named(printable(text), option):
            way = ownership.open_way(text, opt, "file", create=True, register=ways.append)
        state = ownership.file_state(way.fd, way.name, way.shown, opt)
        if state.kind == "stream":
            with _named(way.shown, option):
                fh, _ = _stream(state, way, mode, kwargs)
            with _named(way.shown, option), fh:
                yield fh
            ok = True
            return
        notice_leftovers(way.fd, printable(_folder_text(text)), notice)
        perms = state.mode if state.kind == "file" else 0o666 & ~umask()
        temps: list = []  # the cleanup record, before the temporary exists
        try:
            with _named(way.shown, option):
                new = NewFile(way.fd, way.name, way.shown, opt, register=temps.append)
            fh = open(new.fd, mode, closefd=False, **kwargs)
            with _named(way.shown, option, _FULL_ERRORS), fh:  # other errors: the body's
                yield fh
                fh.flush()
            with _named(way.shown, option):
                new.commit(perms, state.gid)
        except BaseException:
            for new in temps:
                new.discard()
            raise
        ok = True
    finally:
        for way in ways:
            way.close(remove_created=not ok)


def write_text(path, text: str, *, option: str | None = None) -> Path:
    """Write ``text`` to ``path`` atomically and return the path (``"-"``: stdout)."""
    with atomic_write(path, option=option) as fh:
        fh.write(text)
    return Path(path)


def write_bytes(path, data: bytes, *, option: str | None = None) -> Path:
    """Write ``data`` to ``path`` atomically and return the path (``"-"``: stdout)."""
    with atomic_write(path, "wb", option=option) as fh:
        fh.write(data)
    return Path(path)


def save_figure(fig, path, *, option: str | None = None, **kwargs) -> Path:
    """Save a matplotlib figure atomically (format from the suffix of ``path``; PNG if none)."""
    fmt = Path(str(path)).suffix.lstrip(".") or "png"
    with atomic_write(path, "wb", option=option) as fh:
        fig.savefig(fh, format=fmt, **kwargs)
    return Path(path)


@contextlib.contextmanager
def open_folder(path, *, option: str = "--out", notice=None) -> Iterator[Path]:
    """Build a new version of the output folder ``path``; swap it in whole on success.

    The owner rule (:func:`dispersion.ownership.check_folder`) is applied when the writing
    starts and the folder is refused unless new, empty or written by dispersion. Yields
    the new folder (a temporary beside ``path``), which starts as a copy of what ``path``
    holds: write the outputs there. On success the marker is written and the new folder
    replaces ``path`` in one exchange; if the block raises (or the process is interrupted),
    ``path`` stays as it was and the new folder is removed. ``notice(text)`` receives
    one-line notices (default: stderr).

    This is the function every command that writes a folder calls (``reproduce``,
    ``ring/impact --out``, ``bench --out``, and new ones).

    >>> import tempfile, pathlib
    >>> root = pathlib.Path(tempfile.mkdtemp())
    >>> with open_folder(root / "run") as new:
    ...     _ = write_text(new / "a.csv", "1\\n")
    >>> sorted(p.name for p in (root / "run").iterdir())
    ['.dispersion-report', 'a.csv']
    """
    ownership.check_folder(path, option)
    text = _text(path)
    ok = False
    ways: list = []  # the cleanup record of the way there, set up before anything is made
    try:
        with _named(printable(text), option):
            way = ownership.open_way(text, option, "folder", create=True,
                                     register=ways.append)
        target = ownership.folder_state(way.fd, way.name, way.shown, option)
        notice_leftovers(way.fd, printable(_folder_text(text)), notice)
        mode = target.mode if target.kind == "folder" else 0o777 & ~umask()
        temps: list = []  # the cleanup record, before the new folder exists
        try:
            with _named(way.shown, option):
                new = NewFolder(way.fd, way.name, way.shown, _folder_text(text), target,
                                notice=notice, register=temps.append)
            yield Path(new.path)
            with _named(way.shown, option):
                marker = NewFile(new.fd, MARKER, MARKER, option)
                _write_all(marker.fd, MARKER_TEXT.encode())
                marker.commit(0o666 & ~umask())
                new.commit(mode, target.gid)
        except BaseException:
            for new in temps:
                new.discard()
            raise
        ok = True
    finally:
        for way in ways:
            way.close(remove_created=not ok)


_RESERVED = re.compile(r"\.dispersion-.*|.*\.dispersion-tmp-.*", re.DOTALL)


def _check_name(name: str) -> str:
    parts = Path(name).parts if isinstance(name, str) else ()
    if not parts or Path(name).is_absolute() or ".." in parts or "\0" in name \
            or any(_RESERVED.fullmatch(part) for part in parts):
        raise InputError(f"file names in write_files must be relative paths inside the folder "
                         f"without '..', got {printable(name)!r}")
    return name


def write_files(folder, files: Mapping[str, str | bytes], *, option: str | None = None,
                notice=None) -> list[Path]:
    """Write several files into the output folder ``folder`` as one unit: all new, or all
    old, at every moment (:func:`open_folder`; the folder must be new, empty or written by
    dispersion). Files of the folder not named in ``files`` are kept.

    Parameters
    ----------
    folder : str or Path
        Target folder, created if missing.
    files : mapping ``{relative name: text or bytes}``
    option : str, optional
        Option name for error messages (e.g. ``"--out"``).

    Returns
    -------
    list of Path
        The written paths, in the order of ``files``.

    >>> import tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "run"
    >>> [p.name for p in write_files(out, {"a.csv": "x\\n", "b.json": b"{}"})]
    ['a.csv', 'b.json']
    """
    names = [_check_name(n) for n in files]
    with open_folder(folder, option=option or "folder", notice=notice) as new:
        for name in names:
            data = files[name]
            write_bytes(new / name, data.encode() if isinstance(data, str) else bytes(data),
                        option=option)
    return [Path(folder) / name for name in names]


def write_unit(files: Mapping[Path, str | bytes], *, option: str | None = None) -> list[Path]:
    """Write files that may lie in different folders: all are written and synced first,
    then renamed onto their targets one after the other, in the order given.

    Each file is whole, old or new, at every moment; a kill between two renames leaves the
    earlier files new and the later ones old (see :mod:`dispersion.staging`). Each target
    must pass the owner rule for files (streams are written by the caller: see
    :func:`unit_target`).

    >>> import tempfile, pathlib
    >>> root = pathlib.Path(tempfile.mkdtemp())
    >>> [p.name for p in write_unit({root / "a" / "x.csv": "1\\n", root / "y.png": b""})]
    ['x.csv', 'y.png']
    """
    opt = option or "output"
    staged: list[tuple] = []
    try:
        for target, data in files.items():
            text = _text(target)
            state = ownership.check_file(target, opt)
            if state.kind not in ("new", "file"):
                raise InputError(f"{opt}: {state.shown} is not a regular file; write streams "
                                 "apart from the unit")
            with _named(printable(text), option):
                way = ownership.open_way(text, opt, "file", create=True,
                                         register=lambda made: staged.append([made, None]))
            state = ownership.file_state(way.fd, way.name, way.shown, opt)
            notice_leftovers(way.fd, printable(_folder_text(text)))
            perms = state.mode if state.kind == "file" else 0o666 & ~umask()
            with _named(way.shown, option):
                entry = staged[-1]
                new = NewFile(way.fd, way.name, way.shown, opt,
                              register=lambda made, entry=entry: entry.__setitem__(1, made))
                _write_all(new.fd, data.encode() if isinstance(data, str) else bytes(data))
                new.sync(perms, state.gid)
        checkpoint()
        for way, new in staged:
            with _named(way.shown, option):
                new.swap()
                new.close()
    finally:
        for way, new in staged:
            renamed = new is not None and new.done  # before discard, which sets done
            if new is not None:
                new.discard()
            way.close(remove_created=not renamed)
    return [Path(_text(t)) for t in files]


def stale_temporaries(folder) -> list[Path]:
    """Temporaries of killed or concurrent writers in ``folder`` (see
    :mod:`dispersion.staging`): listed, never changed; a live writer's are not listed."""
    fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
    try:
        return [Path(folder) / name for name in leftovers(fd)]
    finally:
        os.close(fd)
