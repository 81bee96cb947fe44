"""The one owner rule: what a writer of dispersion may replace, decided before any work.

Every command that writes (``reproduce --out``, ``ring/impact --out``, ``bench --out``,
``branches --csv/--figure/--json``, ``series --json``, ``verify --junit``, and any new one)
asks this module, through :mod:`dispersion.io`, whether its target may be written. The
checks run twice: before the work (so a refusal costs nothing) and again when the output
is put in place (so what changed meanwhile is refused too).

**A file** (``--csv``, ``--figure``, ``--json``, ``--junit``) may be written if it is absent
or a regular file owned by the user who runs the command (the effective uid): the user
named it. A symbolic link (even one to a file of the user), a folder, another user's file,
a block device or a socket is refused with one line. ``-`` is standard output;
``/dev/stdout`` and ``/dev/stderr`` are the streams themselves; a named pipe or a character
device of the user (a FIFO they made, their terminal) is a stream, written through and never
replaced, and so is the null device; a named pipe or device of another user is refused like
their files (in a shared sticky folder, a pipe planted under the name of an output would
otherwise receive it).

**Outputs never name inputs.** :func:`check_apart` refuses, before any work, an output that
is one of the command's input files (the same ``(st_dev, st_ino)`` where both exist, so
through ``./``, ``sub/..``, a link or a hard link; the same normalized path otherwise).

**A folder** (``--out``) may be written if it is absent, an empty folder of the user, or a
folder of the user that carries the marker :data:`MARKER` (a regular file) and holds
nothing but regular files and folders of the user: no link, device, pipe or socket, and
nothing of another user, at any depth. Anything else is refused, naming the first entry
that breaks the rule. Every folder a writer writes gets the marker.

**The way there.** The folders on the way to a target are opened as the system resolves
the path the user wrote (links among them are followed, once, when the writer opens the
folder; everything after that happens relative to the open folder). ``.`` or ``..`` as the
last name and a ``..`` after a folder that does not exist (``results/../README.md`` names
nothing until ``results`` exists) are refused. Missing folders on the way are created by
the writer (modes from the umask) and removed again if the write fails.

Nothing found on disk is an instruction: no file is read to decide what to rename, move or
delete; the marker is only looked for.

>>> import tempfile, pathlib
>>> home = pathlib.Path(tempfile.mkdtemp())
>>> (home / "notes").mkdir(); _ = (home / "notes" / "thesis.tex").write_text("mine")
>>> check_folder(home / "notes", "--out")
Traceback (most recent call last):
...
dispersion.errors.InputError: --out .../notes holds files that dispersion did not write (no .dispersion-report marker); name a new or empty folder
>>> check_file(home / "out.csv", "--csv").kind
'new'
"""
from __future__ import annotations

import contextlib
import os
import signal
import stat
import threading
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field

from dispersion.errors import InputError
from dispersion.untrusted import printable

__all__ = ["MARKER", "MARKER_TEXT", "STDOUT", "Target", "Way", "check_file", "check_folder",
           "file_state", "folder_state", "tree", "open_way", "interrupts_held", "same_file",
           "check_apart"]

#: The file that marks a folder as written by dispersion (the name ``dispersion reproduce``
#: has always used, so report folders of earlier versions stay writable).
MARKER = ".dispersion-report"
#: What a writer puts in the marker (constant: rewriting a folder does not change it).
MARKER_TEXT = ("This folder is written by dispersion: a later run may replace it as a whole.\n"
               "Files you add here are carried over to the next version of the folder.\n")
#: The path that means standard output.
STDOUT = "-"
#: Paths that name the streams of this process: written to them, never opened by name.
STREAM_NAMES = {"/dev/stdout": "stdout", "/dev/fd/1": "stdout", "/proc/self/fd/1": "stdout",
                "/dev/stderr": "stderr", "/dev/fd/2": "stderr", "/proc/self/fd/2": "stderr"}
_KINDS = ((stat.S_ISBLK, "block device"), (stat.S_ISSOCK, "socket"), (stat.S_ISFIFO, "named pipe"),
          (stat.S_ISCHR, "character device"), (stat.S_ISLNK, "symbolic link"),
          (stat.S_ISDIR, "folder"), (stat.S_ISREG, "file"))


def _kind(mode: int) -> str:
    return next((name for test, name in _KINDS if test(mode)), "special file")


@contextlib.contextmanager
def interrupts_held() -> Iterator[None]:
    """Ctrl-C and SIGTERM held back for the block and delivered at its end: a step that
    creates something on disk and records it for removal is never split by an interrupt
    (the record exists before the interrupt can unwind).

    The Python handlers are set aside for the block (a signal mask would not do: a process
    with other threads, numpy's among them, takes the signal on any of them) and a signal
    that came meanwhile is handed to them at its end. Outside the main thread, where Python
    runs no signal handler, a plain block.
    """
    signals = (signal.SIGINT, signal.SIGTERM)
    if threading.current_thread() is not threading.main_thread() or any(
            signal.getsignal(sig) is None for sig in signals):  # None: set outside Python
        yield
        return
    caught: list[int] = []
    previous = {sig: signal.signal(sig, lambda signum, frame: caught.append(signum))
                for sig in signals}
    try:
        yield
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        for sig in dict.fromkeys(caught):  # now, as it would have been at once
            handler = previous[sig]
            if callable(handler):
                handler(sig, None)
            elif handler == signal.SIG_DFL:
                os.kill(os.getpid(), sig)


def _null_device(st: os.stat_result) -> bool:
    """True for the null device (it discards what it is given: nobody's data)."""
    try:
        null = os.stat(os.devnull)
    except OSError:  # pragma: no cover - no /dev/null
        return False
    return stat.S_ISCHR(st.st_mode) and st.st_rdev == null.st_rdev


def _fail(message: str):
    raise InputError(message)


@dataclass(frozen=True)
class Target:
    """What a writer found at its target: ``kind`` is ``"new"`` (absent), ``"file"``,
    ``"folder"``, ``"stream"`` (a character device or named pipe), ``"stdout"`` or
    ``"stderr"``; ``ident`` is ``(st_dev, st_ino)`` of what exists, ``mode`` its
    permission bits and ``gid`` its group (both kept by the new version)."""

    text: str
    option: str
    kind: str
    ident: tuple[int, int] | None = None
    mode: int | None = None
    gid: int | None = None

    @property
    def shown(self) -> str:
        """The path as the user wrote it, safe for a terminal."""
        return printable(self.text)


@dataclass
class Way:
    """The open folder a target lies in (``fd``), the target's ``name``, and the folders
    created on the way (``created``: ``(folder fd, name)``, outermost first)."""

    fd: int
    name: str
    shown: str
    created: list = field(default_factory=list)

    def close(self, *, remove_created: bool = False) -> None:
        """Close the descriptors; with ``remove_created``, remove the folders made on the
        way (each only if still empty)."""
        # each descriptor is forgotten before it is closed: an interrupt raised between the
        # two (a signal handler) must not leave it to be closed twice
        while self.created:
            fd, name = self.created.pop()
            if remove_created:
                try:
                    os.rmdir(name, dir_fd=fd)
                except OSError:
                    remove_created = False  # not empty: keep it and those above it
            os.close(fd)
        fd, self.fd = self.fd, None
        if fd is not None:
            os.close(fd)


def _text(path, option: str, what: str) -> str:
    text = os.fspath(path) if path is not None else ""
    if isinstance(text, bytes):
        _fail(f"{option} must be text, got bytes")
    if not text.strip():
        _fail(f"{option} must be a {what} path, got {text!r}")
    if "\0" in text:
        _fail(f"{option} must not contain a NUL character")
    return text


def _parts(text: str, option: str, what: str) -> tuple[bool, list[str], str]:
    parts = [p for p in text.split("/") if p]
    if not parts:
        _fail(f"{option} must not be the root folder")
    if parts[-1] in (".", ".."):
        _fail(f"{option} must end in the name of the {what}, got {printable(text)!r}")
    return text.startswith("/"), parts[:-1], parts[-1]


def open_way(path, option: str, what: str, *, create: bool,
             register=None) -> Way | list[str]:
    """Open the folder ``path`` lies in (following the system's resolution of the folders
    on the way); with ``create``, make the missing ones and return a :class:`Way`.
    Without ``create`` nothing is made: a :class:`Way` if the folder exists, else the
    list of missing names (after checking that they can be made). ``register(way)``
    records the :class:`Way` in the caller's cleanup record before an interrupt can unwind
    (the folders it made are then removed by the caller's :meth:`Way.close`)."""
    text = _text(path, option, what)
    absolute, folders, name = _parts(text, option, what)
    shown = printable(text)
    flags = os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC
    fd = os.open("/" if absolute else ".", flags)
    created: list = []
    missing: list[str] = []
    try:
        for i, part in enumerate(folders):
            here = printable("/".join(folders[:i + 1]))
            if part == ".":
                continue
            if missing:
                if part == "..":
                    _fail(f"{option} {shown}: {printable(missing[0])} does not exist, so a '..' "
                          "after it names no folder")
                missing.append(part)
                continue
            try:
                new = os.open(part, flags, dir_fd=fd)
            except FileNotFoundError:
                try:
                    os.stat(part, dir_fd=fd, follow_symlinks=False)
                    _fail(f"{option} {shown}: {here} is a dangling symbolic link")
                except FileNotFoundError:
                    pass
                if not create:
                    missing.append(part)
                    continue
                # made and recorded as one step: an interrupt right after the mkdir finds it
                # in ``created`` and the unwinding removes it; a folder that appeared
                # meanwhile is not ours, and is never removed
                with interrupts_held():
                    held = os.dup(fd)
                    try:
                        os.mkdir(part, 0o777, dir_fd=fd)
                    except OSError as exc:
                        os.close(held)
                        if not isinstance(exc, FileExistsError):  # else: not ours, kept
                            raise
                    else:
                        created.append((held, part))
                new = os.open(part, flags | os.O_NOFOLLOW, dir_fd=fd)
            except NotADirectoryError:
                _fail(f"{option} {shown}: {here} is a file, not a folder")
            except PermissionError:
                _fail(f"{option} {shown}: folder {here} cannot be opened (permission denied)")
            old, fd = fd, new  # forgotten before closed (see Way.close)
            os.close(old)
        if missing:
            if not os.access(".", os.W_OK | os.X_OK, dir_fd=fd, effective_ids=True):
                _fail(f"{option} {shown}: the folder that would hold "
                      f"{printable(missing[0])} is not writable")
            old, fd = fd, None  # forgotten before closed (see Way.close)
            os.close(old)
            return missing
        if not os.access(".", os.W_OK | os.X_OK, dir_fd=fd, effective_ids=True):
            _fail(f"{option} {shown}: its folder is not writable")
        with interrupts_held():  # handed over as one step: the caller's record has it
            way = Way(fd, name, shown, created)
            if register is not None:
                register(way)
                fd = None  # the caller closes it now (an interrupt at the end of this block)
        return way
    except BaseException:
        if fd is not None:
            Way(fd, name, shown, created).close(remove_created=True)
        raise


def file_state(fd: int, name: str, shown: str, option: str) -> Target:
    """The owner rule for file ``name`` in open folder ``fd`` (see the module doc)."""
    try:
        st = os.stat(name, dir_fd=fd, follow_symlinks=False)
    except FileNotFoundError:
        return Target(shown, option, "new")
    mode = st.st_mode
    if stat.S_ISLNK(mode):
        _fail(f"{option} {shown} is a symbolic link; dispersion never writes through a link "
              "(name the file itself)")
    if stat.S_ISDIR(mode):
        _fail(f"{option} must name a file, but {shown} is an existing folder")
    if stat.S_ISCHR(mode) or stat.S_ISFIFO(mode):
        if st.st_uid != os.geteuid() and not _null_device(st):
            _fail(f"{option} {shown} is a {_kind(mode)} of another user (uid {st.st_uid}); "
                  "dispersion writes only to your own files and streams")
        return Target(shown, option, "stream", (st.st_dev, st.st_ino))
    if not stat.S_ISREG(mode):
        _fail(f"{option} {shown} is a {_kind(mode)}; dispersion writes only regular files")
    if st.st_uid != os.geteuid():
        _fail(f"{option} {shown} belongs to another user (uid {st.st_uid}); dispersion "
              "replaces only your own files")
    return Target(shown, option, "file", (st.st_dev, st.st_ino), stat.S_IMODE(mode), st.st_gid)


def tree(fd: int, shown: str, option: str):
    """Every entry under the open folder ``fd``, folders before their contents, as
    ``(relative path, lstat)``; refuses a link, a device, a pipe, a socket or an entry of
    another user, naming it. Folders are opened without following links."""
    me = os.geteuid()
    stack = [((), os.dup(fd))]
    try:
        while stack:
            rel, dfd = stack.pop()
            try:
                for name in sorted(os.listdir(dfd)):
                    path = (*rel, name)
                    st = os.stat(name, dir_fd=dfd, follow_symlinks=False)
                    where = printable("/".join(path))
                    if not (stat.S_ISREG(st.st_mode) or stat.S_ISDIR(st.st_mode)):
                        _fail(f"{option} {shown}: {where} is a {_kind(st.st_mode)}; an output "
                              "folder may hold only regular files and folders (links are "
                              "never followed)")
                    if st.st_uid != me:
                        _fail(f"{option} {shown}: {where} belongs to another user (uid "
                              f"{st.st_uid}); dispersion replaces only folders that are "
                              "wholly yours")
                    yield path, st
                    if stat.S_ISDIR(st.st_mode):
                        sub = os.open(name, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW
                                      | os.O_CLOEXEC, dir_fd=dfd)
                        stack.append((path, sub))
            finally:
                os.close(dfd)
    finally:
        for _, dfd in stack:
            os.close(dfd)


def folder_state(fd: int, name: str, shown: str, option: str) -> Target:
    """The owner rule for folder ``name`` in open folder ``fd`` (see the module doc)."""
    try:
        st = os.stat(name, dir_fd=fd, follow_symlinks=False)
    except FileNotFoundError:
        return Target(shown, option, "new")
    if stat.S_ISLNK(st.st_mode):
        _fail(f"{option} {shown} is a symbolic link; dispersion never writes through a link "
              "(name the folder itself)")
    if not stat.S_ISDIR(st.st_mode):
        _fail(f"{option} must be a folder, but {shown} is an existing {_kind(st.st_mode)}")
    if st.st_uid != os.geteuid():
        _fail(f"{option} {shown} belongs to another user (uid {st.st_uid}); dispersion "
              "writes only folders of your own")
    sub = os.open(name, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC, dir_fd=fd)
    try:
        if os.fstat(sub)[1:3] != (st.st_ino, st.st_dev):
            _fail(f"{option} {shown} changed while it was checked; try again")
        names = os.listdir(sub)
        if names:
            try:
                mark = os.stat(MARKER, dir_fd=sub, follow_symlinks=False)
            except FileNotFoundError:
                mark = None
            if mark is None or not stat.S_ISREG(mark.st_mode):
                _fail(f"{option} {shown} holds files that dispersion did not write (no {MARKER} "
                      "marker); name a new or empty folder")
            for _ in tree(sub, shown, option):
                pass
    finally:
        os.close(sub)
    return Target(shown, option, "folder", (st.st_dev, st.st_ino), stat.S_IMODE(st.st_mode),
                  st.st_gid)


def _stream(text: str) -> str | None:
    if text in STREAM_NAMES:
        return STREAM_NAMES[text]
    return STREAM_NAMES.get(os.path.abspath(text))


def check_file(path, option: str = "--out", *, allow_stdout: bool = True,
               suffixes: tuple[str, ...] | None = None,
               create_parents: bool = True) -> Target:
    """Check, before any work, that the file ``path`` may be written (the module's rule).

    ``suffixes`` are the accepted endings (case-insensitive); ``create_parents=False``
    refuses a missing folder on the way. Raises :class:`InputError` (one line, naming
    ``option``) or returns the :class:`Target`.

    >>> check_file("-", "--csv").kind, check_file("/dev/null", "--csv").kind
    ('stdout', 'stream')
    """
    if path is not None and os.fspath(path) == STDOUT:
        if allow_stdout:
            return Target(STDOUT, option, "stdout")
        _fail(f"{option} must be a file path ('-' is not accepted here)")
    text = _text(path, option, "file")
    if not allow_stdout and _stream(text) is not None:
        _fail(f"{option} must be a file path (standard streams are not accepted here)")
    if text.endswith("/"):
        _fail(f"{option} must name a file, got the folder path {printable(text)!r}")
    if suffixes and not text.lower().endswith(tuple(s.lower() for s in suffixes)):
        _fail(f"{option} must end in {', '.join(suffixes)}, got {printable(text)!r}")
    if _stream(text) is not None:
        return Target(text, option, _stream(text))
    way = open_way(text, option, "file", create=False)
    if isinstance(way, list):
        if not create_parents:
            _fail(f"{option}: folder {printable(os.path.dirname(text))} does not exist "
                  "(create it first)")
        return Target(text, option, "new")
    try:
        return file_state(way.fd, way.name, way.shown, option)
    finally:
        way.close()


def check_folder(path, option: str = "--out") -> Target:
    """Check, before any work, that the folder ``path`` may be written (the module's rule);
    raises :class:`InputError` (one line) or returns the :class:`Target`."""
    text = _text(path, option, "folder")
    if text == STDOUT:
        _fail(f"{option} must be a folder path, got '-'")
    way = open_way(text, option, "folder", create=False)
    if isinstance(way, list):
        return Target(text, option, "new")
    try:
        return folder_state(way.fd, way.name, way.shown, option)
    finally:
        way.close()


def _identity(path) -> tuple:
    """What ``path`` names: ``(st_dev, st_ino)`` of what exists there (links followed), else
    its normalized absolute path."""
    text = os.fspath(path)
    try:
        st = os.stat(text)
        return ("file", st.st_dev, st.st_ino)
    except (OSError, ValueError):
        return ("path", os.path.normpath(os.path.abspath(text)))


def same_file(a, b) -> bool:
    """True if paths ``a`` and ``b`` name the same file or folder: the same ``(st_dev,
    st_ino)`` where it exists (through ``./``, ``sub/..``, a link or a hard link), the same
    normalized path otherwise.

    >>> same_file("/dev/null", "/dev/../dev/./null"), same_file("/dev/null", "/dev/zero")
    (True, False)
    """
    return _identity(a) == _identity(b)


def check_apart(outputs: Mapping[str, object], inputs: Mapping[str, Iterable]) -> None:
    """Refuse, before any work, an output that names one of the command's inputs.

    ``outputs`` maps an option to its path (``-`` and None are skipped); ``inputs`` maps an
    option (or the name of a positional argument) to its paths.

    >>> check_apart({"--json": "/dev/./null"}, {"--mass-rule": ["/dev/null"]})
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: --json /dev/./null is the --mass-rule file /dev/null: an output never replaces an input of its command
    """
    for out_option, out in outputs.items():
        if out is None or os.fspath(out) == STDOUT:
            continue
        for in_option, paths in inputs.items():
            for path in paths or ():
                if same_file(out, path):
                    _fail(f"{out_option} {printable(os.fspath(out))} is the {in_option} file "
                          f"{printable(os.fspath(path))}: an output never replaces an input "
                          "of its command")
