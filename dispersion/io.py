"""Safe file output: complete or absent, never a user's file lost, paths checked up front.

Every file the toolkit writes goes through this module, with these guarantees:

- **Atomic files.** :func:`atomic_write` writes a hidden temporary beside the target, flushes
  and ``fsync``\\ s it, then renames it onto the target: a reader sees the old file or the
  new one, never a partial one. On any error the temporary is removed. The temporary lives in
  a stage folder ``.dispersion-stage.TOKEN`` (:mod:`dispersion.staging`) that records a
  random token; a process killed with SIGKILL leaves it, and the next writer into that
  folder removes it, acting only on stages whose name and token verify (never on a file we
  did not write). :func:`stale_temporaries` lists them, :func:`remove_stale_temporaries`
  removes them.
- **Modes follow the umask.** A new file gets ``0o666 & ~umask`` (not ``mkstemp``'s 0600);
  a file that is replaced keeps its permission bits; new folders get ``0o777 & ~umask``.
- **``-`` is standard output.** Devices, FIFOs and sockets (``/dev/stdout``, ``/dev/null``,
  a named pipe) are written through, never replaced; a symbolic link is never renamed over:
  the file it points to is replaced and the link stays.
- **Paths are checked before the work.** :func:`check_output_file` and
  :func:`check_output_dir` raise :class:`~dispersion.errors.InputError` naming the option
  (an existing folder where a file is wanted, a missing or read-only parent, ``''``...).
- **Write errors are one line.** A full disk, a read-only file system or a permission error
  while writing raises :class:`OutputError` (a :class:`~dispersion.errors.DispersionError`)
  or :class:`~dispersion.errors.InputError` (the path is not writable), with no partial file.
- **Several files as one unit.** :func:`write_files` (one folder) and :func:`write_unit`
  (any folders) stage every file first and rename them only once all are staged, under a
  journal; see their docstrings for the exact guarantee.

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
import os
import stat
import sys
from collections.abc import Mapping
from pathlib import Path

from dispersion.errors import DispersionError, InputError
from dispersion.staging import Stage, checkpoint, recover

__all__ = [
    "OutputError",
    "STDOUT",
    "atomic_write",
    "write_text",
    "write_bytes",
    "save_figure",
    "write_files",
    "check_output_file",
    "check_output_dir",
    "make_dir",
    "umask",
    "write_unit",
    "unit_target",
    "stale_temporaries",
    "remove_stale_temporaries",
]

#: The path that means standard output.
STDOUT = "-"
# errno values that mean "this path cannot be written by you": the user's choice, exit 2.
_PATH_ERRORS = {errno.EACCES, errno.EPERM, errno.EROFS, errno.ENOENT, errno.ENOTDIR,
                errno.EISDIR, errno.ENAMETOOLONG, errno.ELOOP, errno.EEXIST}
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


def _error(exc: OSError, path, option: str | None) -> DispersionError:
    """One-line toolkit error for an ``OSError`` met while writing ``path``."""
    what = f"{option} {path}" if option else str(path)
    reason = exc.strerror or type(exc).__name__
    if exc.errno in _PATH_ERRORS:
        return InputError(f"cannot write {what}: {reason} (choose a writable path)")
    return OutputError(f"cannot write {what}: {reason}; nothing was written")


@contextlib.contextmanager
def _named(path, option: str | None, errnos: frozenset | set | None = None):
    """An ``OSError`` in the block becomes the one-line error about ``path`` (:func:`_error`);
    with ``errnos``, only those (other errors are the caller's, passed on unchanged)."""
    try:
        yield
    except OSError as exc:
        if errnos is None or exc.errno in errnos:
            raise _error(exc, path, option) from None
        raise


def _is_stream(st: os.stat_result) -> bool:
    return stat.S_ISCHR(st.st_mode) or stat.S_ISFIFO(st.st_mode) or stat.S_ISSOCK(st.st_mode)


def _stat(path: Path) -> os.stat_result | None:
    try:
        return path.stat()
    except (FileNotFoundError, NotADirectoryError):
        return None


_STREAM_PATHS = {"/dev/stdout": "stdout", "/dev/fd/1": "stdout", "/proc/self/fd/1": "stdout",
                 "/dev/stderr": "stderr", "/dev/fd/2": "stderr", "/proc/self/fd/2": "stderr"}


def _through_dev(path: Path) -> bool:
    """True if ``path`` or a link on the way to its target lies in /dev or /proc.

    Such paths name devices or open file descriptors (``/dev/stdout`` may resolve to the
    file the shell redirected to): they are written through, never renamed over.
    """
    probe = os.path.abspath(path)
    for _ in range(40):
        if probe.startswith(("/dev/", "/proc/")):
            return True
        if not os.path.islink(probe):
            return False
        probe = os.path.join(os.path.dirname(probe), os.readlink(probe))
    return False


def make_dir(path, option: str | None = None) -> Path:
    """Create folder ``path`` (and parents) with modes from the umask; return it.

    >>> import tempfile, pathlib
    >>> make_dir(pathlib.Path(tempfile.mkdtemp()) / "a" / "b").is_dir()
    True
    """
    path = Path(path)
    try:
        path.mkdir(parents=True, exist_ok=True)  # mkdir applies 0o777 & ~umask
    except FileExistsError:
        raise InputError(f"{option or 'folder'} {path} exists and is not a folder") from None
    except OSError as exc:
        raise _error(exc, path, option) from None
    return path


@contextlib.contextmanager
def atomic_write(path, mode: str = "w", *, option: str | None = None, **kwargs):
    """Open a temporary file beside ``path``; rename it onto ``path`` only on success.

    The temporary lives in a stage folder ``.dispersion-stage.TOKEN`` beside ``path``
    (:class:`dispersion.staging.Stage`); an error, Ctrl-C or SIGTERM removes it, and what a
    SIGKILL leaves is removed by the next writer into that folder.

    ``path`` ``"-"`` yields standard output (text or binary by ``mode``); a device, FIFO or
    socket is opened and written through; a symbolic link to a regular file has its target
    replaced (the link stays). ``option`` names the CLI option in error messages.

    >>> import tempfile, pathlib
    >>> target = pathlib.Path(tempfile.mkdtemp()) / "out.txt"
    >>> with atomic_write(target) as fh:
    ...     _ = fh.write("done")
    >>> target.read_text()
    'done'
    """
    binary = "b" in mode
    if not os.fspath(path).strip():
        raise InputError(f"{option or 'output'} must be a file path or '-', got {os.fspath(path)!r}")
    name = "stdout" if str(path) == STDOUT else _STREAM_PATHS.get(os.path.abspath(path))
    if name is not None:
        stream = getattr(sys, name)
        stream = stream.buffer if binary else stream
        yield stream
        stream.flush()
        return
    path = Path(path)
    st = _stat(path)
    if st is None and path.is_symlink():
        raise InputError(f"cannot write {option + ' ' if option else ''}{path}: "
                         "it is a dangling symbolic link")
    if st is not None and (_is_stream(st) or _through_dev(path)):
        with _named(path, option):
            fh = open(path, mode, **kwargs)
        with _named(path, option), fh:
            yield fh
        return
    if st is not None and stat.S_ISDIR(st.st_mode):
        raise InputError(f"{option or 'output'} must name a file, but {path} is an existing folder")
    target = Path(os.path.realpath(path)) if path.is_symlink() else path
    perms = stat.S_IMODE(st.st_mode) if st is not None else 0o666 & ~umask()
    with Stage() as unit:
        with _named(target, option):
            tmp = unit.file(target)
            fh = open(tmp, mode, **kwargs)
        # a full disk while writing is ours to name; other errors are the body's
        with _named(target, option, _FULL_ERRORS), fh:
            yield fh
            fh.flush()
            os.fsync(fh.fileno())
        checkpoint()
        with _named(target, option):
            os.chmod(tmp, perms)
            unit.commit()


def unit_target(path) -> Path | None:
    """Where a unit writes ``path``: the file a link points to; None for a stream (``-``,
    a device, a FIFO, a path through ``/dev``), which is written through, not staged.

    >>> unit_target("-") is None, unit_target("/dev/null") is None
    (True, True)
    """
    if str(path) == STDOUT or os.path.abspath(path) in _STREAM_PATHS:
        return None
    path = Path(path)
    st = _stat(path)
    if st is not None and (_is_stream(st) or _through_dev(path)):
        return None
    return Path(os.path.realpath(path)) if path.is_symlink() else path


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
    path = Path(path) if str(path) != STDOUT else path
    fmt = Path(str(path)).suffix.lstrip(".") or "png"
    with atomic_write(path, "wb", option=option) as fh:
        fig.savefig(fh, format=fmt, **kwargs)
    return Path(path)


def _nearest_existing(path: Path) -> Path:
    probe = path
    while not probe.exists() and not probe.is_symlink():
        if probe.parent == probe:
            break
        probe = probe.parent
    return probe


def _check_parent(path: Path, option: str, create_parents: bool) -> None:
    parent = path.parent
    if not parent.exists():
        if not create_parents:
            raise InputError(f"{option}: folder {parent} does not exist (create it first)")
        parent = _nearest_existing(parent)
        if not parent.is_dir():
            raise InputError(f"{option}: {parent} is a file, so {path} cannot be created")
    elif not parent.is_dir():
        raise InputError(f"{option}: {parent} is not a folder")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(f"{option}: folder {parent} is not writable")


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
        ``''``; an existing folder; a dangling link; a missing (unless ``create_parents``),
        non-folder or read-only parent; a read-only existing file; a wrong suffix.

    >>> check_output_file("-", option="--csv")
    '-'
    >>> check_output_file("", option="--csv")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: --csv must be a file path or '-' (standard output), got ''
    """
    text = os.fspath(path) if path is not None else ""
    if text == STDOUT:
        if allow_stdout:
            return STDOUT
        raise InputError(f"{option} must be a file path ('-' is not accepted here)")
    if not text.strip():
        alt = " or '-' (standard output)" if allow_stdout else ""
        raise InputError(f"{option} must be a file path{alt}, got {text!r}")
    if "\0" in text:
        raise InputError(f"{option} must not contain a NUL character")
    path = Path(text)
    if text.endswith(os.sep):
        raise InputError(f"{option} must name a file, got the folder path {text!r}")
    if suffixes and not text.lower().endswith(tuple(s.lower() for s in suffixes)):
        raise InputError(f"{option} must end in {', '.join(suffixes)}, got {text!r}")
    st = _stat(path)
    if st is None and path.is_symlink():
        raise InputError(f"{option}: {path} is a dangling symbolic link")
    if st is not None:
        if stat.S_ISDIR(st.st_mode):
            raise InputError(f"{option} must name a file, but {path} is an existing folder")
        if not os.access(path, os.W_OK):
            raise InputError(f"{option}: {path} is not writable")
        if _is_stream(st):
            return path
    real = Path(os.path.realpath(path)) if path.is_symlink() else path
    _check_parent(real, option, create_parents)
    return path


def check_output_dir(path, option: str = "--out") -> Path:
    """Check, before any work, that ``path`` is or can become a writable folder; return it.

    A missing folder (and missing parents) is accepted: it will be created.

    >>> check_output_dir("-", option="--out")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: --out must be a folder path, got '-'
    """
    text = os.fspath(path) if path is not None else ""
    if not text.strip() or text == STDOUT or "\0" in text:
        raise InputError(f"{option} must be a folder path, got {text!r}")
    path = Path(text)
    st = _stat(path)
    if st is None and path.is_symlink():
        raise InputError(f"{option}: {path} is a dangling symbolic link")
    if st is not None:
        if not stat.S_ISDIR(st.st_mode):
            raise InputError(f"{option} must be a folder, but {path} is an existing file")
        if not os.access(path, os.W_OK | os.X_OK):
            raise InputError(f"{option}: folder {path} is not writable")
        return path
    _check_parent(path, option, create_parents=True)
    return path


def stale_temporaries(folder) -> list[Path]:
    """Stages of killed writers in ``folder`` that verify as ours (see :mod:`dispersion.staging`).

    A stage whose writer is alive, or a look-alike that does not verify, is not listed.
    """
    from dispersion.staging import stale_stages

    return stale_stages(folder)


def remove_stale_temporaries(folder, *, notice=None) -> list[Path]:
    """Finish or undo what killed writers left in ``folder`` (only what verifies as ours).

    A unit whose journal was written is completed (all new); one without is removed (all
    old). Returns the stage folders that went. See :func:`dispersion.staging.recover`.
    """
    return recover(folder, notice=notice)


def _check_name(name: str) -> str:
    parts = Path(name).parts if isinstance(name, str) else ()
    if not parts or Path(name).is_absolute() or ".." in parts or "\0" in name \
            or any(part.startswith(".dispersion-") for part in parts):
        raise InputError(f"file names in write_files must be relative paths inside the folder "
                         f"without '..', got {name!r}")
    return name


def write_files(folder, files: Mapping[str, str | bytes], *, option: str | None = None
                ) -> list[Path]:
    """Write several files into ``folder`` as one unit: all new, or all old.

    Every file is staged (``fsync``\\ ed) in a hidden stage folder beside its target, under
    a random token (:class:`dispersion.staging.Stage`). If anything fails or the process is
    interrupted while staging, the stages are removed, every target keeps its old content and
    a folder this call created is removed again (no empty new folder on a full disk). Once
    all are staged, a journal is written and the files are renamed onto their targets. A kill
    in that last short phase leaves the journal; the next writer into the folder (or
    :func:`remove_stale_temporaries`) completes the renames, so the folder ends all new. Until
    then a reader can see a mix: the guarantee is "all old or all new once recovered", not a
    single atomic switch. Files not named in ``files`` are never touched. Concurrent calls on
    one folder do not corrupt each other's files; the last rename of a name wins.

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
    >>> out = pathlib.Path(tempfile.mkdtemp())
    >>> [p.name for p in write_files(out, {"a.csv": "x\\n", "b.json": b"{}"})]
    ['a.csv', 'b.json']
    """
    folder = check_output_dir(folder, option or "folder")
    names = [_check_name(n) for n in files]
    return write_unit({folder / name: files[name] for name in names}, option=option)


def write_unit(files: Mapping[Path, str | bytes], *, option: str | None = None) -> list[Path]:
    """Write files that may lie in different folders as one unit (see :func:`write_files`).

    Each target must be a regular file or absent (a link or a device is refused: pass
    :func:`unit_target` of a user's path, which resolves links and says which paths are
    streams to write through instead).

    >>> import tempfile, pathlib
    >>> root = pathlib.Path(tempfile.mkdtemp())
    >>> [p.name for p in write_unit({root / "a" / "x.csv": "1\\n", root / "y.png": b""})]
    ['x.csv', 'y.png']
    """
    targets = [Path(t) for t in files]
    with Stage() as unit:
        for target, data in zip(targets, files.values()):
            st = _stat(target)
            if target.is_symlink() or (st is not None and not stat.S_ISREG(st.st_mode)):
                raise InputError(f"{option or 'output'}: {target} is not a regular file; "
                                 "refusing to replace it")
            perms = stat.S_IMODE(st.st_mode) if st is not None else 0o666 & ~umask()
            with _named(target, option):
                tmp = unit.file(target)
                with open(tmp, "xb") as fh:
                    fh.write(data.encode() if isinstance(data, str) else bytes(data))
                    fh.flush()
                    os.fsync(fh.fileno())
                os.chmod(tmp, perms)
            checkpoint()
        with _named(targets[0].parent, option):
            unit.commit()
    return targets
