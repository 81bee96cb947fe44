"""New outputs beside their targets, swapped in whole; nothing on disk is an instruction.

Every output of the toolkit is put in place by one of two moves, after the owner rule of
:mod:`dispersion.ownership` has allowed it:

- **A file** (:class:`NewFile`): a new temporary ``.NAME.dispersion-tmp-HEX`` is created in
  the target's folder (``O_EXCL``, ``O_NOFOLLOW``, mode 0600, under 64 random bits this
  process chose), written, ``fsync``\\ ed, given its final mode, then renamed onto ``NAME``
  (``os.replace``; onto an absent name with ``renameat2(RENAME_NOREPLACE)`` where Linux
  offers it, so a file that appeared meanwhile is never clobbered). A reader sees the old
  file or the new one.
- **A folder** (:class:`NewFolder`): a new folder ``.NAME.dispersion-tmp-HEX`` (mode 0700) is
  made beside ``NAME``; what ``NAME`` holds is copied into it (regular files and folders
  only, opened without following links), the new files are written there, the marker of
  :mod:`dispersion.ownership` last; then the two folders are exchanged in one step
  (``renameat2(RENAME_EXCHANGE)``, or ``RENAME_NOREPLACE`` for a new ``NAME``). The old
  folder, now under the temporary name, is removed entry by entry, and only entries that
  are exactly those copied (same inode, size and mtime): what a user put there during the
  run stays, with a one-line notice. While a folder is built it holds a ``.gitignore``
  (``*``, removed just before the exchange), so a run inside a git checkout does not show
  in ``git status``.

Where ``RENAME_EXCHANGE`` is not available (not Linux, or a file system without it), a
folder is put in place by two renames: ``NAME`` to ``.NAME.dispersion-tmp-HEX2``, then the
new folder to ``NAME``. Between them (two system calls) ``NAME`` is absent; see below.

**Temporaries are recorded before an interrupt can find them.** A temporary is created and
handed to its writer's cleanup record (``register``) as one step, with Ctrl-C and SIGTERM
held back for those few system calls (:func:`dispersion.ownership.interrupts_held`): an
interrupt that arrives right after the ``open`` or ``mkdir`` is delivered once the record
exists, and the unwinding removes the temporary. The writers set up the record before they
create anything.

**What a kill leaves** (SIGKILL, power loss; Ctrl-C and SIGTERM under the command line unwind
and remove the temporaries, except that they are held back while a folder swap is finished):

- before the rename or exchange: the target unchanged, and the unfinished temporary;
- after it: the target complete and new, and (a folder) the remains of the old version
  under the temporary name if the kill came while it was removed;
- with the two-rename fallback, between the renames: ``NAME`` absent, the old version under
  the first temporary name and the new one under the second (rename either back);
- several files of one command (``branches --csv --figure``) are renamed one after the
  other, in the order given, after all are written: a kill between two renames leaves the
  first new and the second old (each file whole), and the second's temporary.

**Leftovers are never touched.** A writer neither renames, moves nor deletes anything it did
not create in this process; it reads no file to decide what to do. Temporaries of killed
runs (``.NAME.dispersion-tmp-HEX``) and those of older versions (``.dispersion-stage.*``,
``.dispersion-write.*``) are reported in one line per folder (:func:`notice_leftovers`) and
left for the user to delete; a temporary whose writer is alive (it holds an ``flock`` on it)
is not reported.

**Fault injection.** Each step above passes a :func:`checkpoint`; the environment variable
:data:`FAULT_ENV` (``"N:SIGKILL"``, ``"N:SIGTERM"`` or ``"N:raise"``) stops the process at the
N-th one, so the tests kill every writer at every checkpoint.

>>> import tempfile, pathlib, os
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY)
>>> new = NewFile(fd, "a.txt", "a.txt")
>>> _ = os.write(new.fd, b"new")
>>> new.commit(0o644)
>>> sorted(p.name for p in folder.iterdir()), (folder / "a.txt").read_text()
(['a.txt'], 'new')
>>> os.close(fd)
"""
from __future__ import annotations

import contextlib
import errno
import fcntl
import os
import re
import secrets
import shutil
import signal
import stat
import sys

from dispersion.ownership import file_state, interrupts_held, tree
from dispersion.untrusted import printable

__all__ = ["NewFile", "NewFolder", "Fault", "FAULT_ENV", "checkpoint", "temp_name",
           "is_leftover", "leftovers", "notice_leftovers", "exchange", "rename_new"]

#: Environment variable of the fault tests: ``"N:SIGNAL"`` sends SIGNAL to this process at
#: the N-th :func:`checkpoint` (numbered from 1); ``"N:raise"`` raises :class:`Fault` there.
FAULT_ENV = "DISPERSION_FAULT_AT"
_TAG = ".dispersion-tmp-"
#: Names of temporaries of this and of earlier versions of the writer (reported, never touched).
_LEFTOVER = re.compile(r"\..*\.dispersion-tmp-[0-9a-f]{16}|\.dispersion-(?:stage|write)\b.*",
                       re.DOTALL)
_checkpoints = [0]
_noticed: set = set()
# renameat2 flags (<linux/fs.h>)
_NOREPLACE, _EXCHANGE = 1, 2


class Fault(Exception):
    """Raised at a checkpoint chosen by :data:`FAULT_ENV` (``"N:raise"``)."""


def checkpoint() -> None:
    """A point where a writer may be interrupted; the fault tests stop the process here."""
    spec = os.environ.get(FAULT_ENV)
    if not spec:
        return
    _checkpoints[0] += 1
    at, _, how = spec.partition(":")
    if at.isdigit() and int(at) == _checkpoints[0]:
        if how == "raise":
            raise Fault(f"fault injected at checkpoint {at}")
        os.kill(os.getpid(), getattr(signal, how or "SIGKILL"))


def temp_name(name: str) -> str:
    """A new temporary name beside ``name``: ``.NAME.dispersion-tmp-`` and 16 random hex
    digits (the name is cut so that the whole stays within 255 bytes)."""
    stem = name
    while len(os.fsencode(stem)) > 200:
        stem = stem[:-1]
    return f".{stem}{_TAG}{secrets.token_hex(8)}"


def is_leftover(name: str) -> bool:
    """True if ``name`` has the form of a writer's temporary (this version or an older one)."""
    return _LEFTOVER.fullmatch(name) is not None


def _renameat2(fd: int, old: str, new: str, flag: int) -> bool:
    """``renameat2`` within folder ``fd``; False where unsupported (not Linux, old kernel,
    a file system without the flag), else True or the OSError."""
    if not sys.platform.startswith("linux"):
        return False
    import ctypes  # here only: no start-up cost for commands that never write

    try:
        func = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError):
        return False
    if func(fd, os.fsencode(old), fd, os.fsencode(new), flag) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.EINVAL, errno.ENOSYS, errno.ENOTSUP):
        return False
    raise OSError(err, os.strerror(err), new)


def exchange(fd: int, a: str, b: str) -> bool:
    """Swap names ``a`` and ``b`` of folder ``fd`` in one step; False if not supported."""
    return _renameat2(fd, a, b, _EXCHANGE)


def rename_new(fd: int, old: str, new: str) -> None:
    """Rename ``old`` to ``new`` in folder ``fd`` only if ``new`` does not exist
    (``FileExistsError`` otherwise). Without ``RENAME_NOREPLACE`` the absence is checked
    just before a plain rename (a window of one system call)."""
    if _renameat2(fd, old, new, _NOREPLACE):
        return
    try:
        os.stat(new, dir_fd=fd, follow_symlinks=False)
    except FileNotFoundError:
        os.rename(old, new, src_dir_fd=fd, dst_dir_fd=fd)
        return
    raise FileExistsError(errno.EEXIST, os.strerror(errno.EEXIST), new)


def _group(fd: int, gid: int | None) -> None:
    """Give the open file ``fd`` group ``gid`` where the system allows (a member may)."""
    if gid is not None and os.fstat(fd).st_gid != gid:
        with contextlib.suppress(OSError):
            os.fchown(fd, -1, gid)


def _fsync(fd: int) -> None:
    with contextlib.suppress(OSError):  # some file systems cannot sync a folder
        os.fsync(fd)


def _ident(st: os.stat_result) -> tuple[int, int]:
    return st.st_dev, st.st_ino


def _still(fd: int, name: str, ident) -> bool:
    """True if ``name`` in folder ``fd`` is still the entry ``ident`` (not a link)."""
    try:
        return _ident(os.stat(name, dir_fd=fd, follow_symlinks=False)) == ident
    except OSError:
        return False


def _live(fd: int, name: str, st: os.stat_result) -> bool:
    """True if a live writer holds the ``flock`` of the temporary ``name``."""
    if not (stat.S_ISREG(st.st_mode) or stat.S_ISDIR(st.st_mode)):
        return False
    flags = os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_NOCTTY | os.O_CLOEXEC
    try:
        probe = os.open(name, flags | (os.O_DIRECTORY if stat.S_ISDIR(st.st_mode) else 0),
                        dir_fd=fd)
    except OSError:
        return False
    try:
        fcntl.flock(probe, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        return True
    except OSError:
        return False
    finally:
        os.close(probe)
    return False


def leftovers(fd: int, own: tuple[str, ...] = ()) -> list[str]:
    """Names in folder ``fd`` that look like temporaries of a writer no longer alive
    (nothing is changed; ``own`` names are skipped)."""
    out = []
    for name in sorted(os.listdir(fd)):
        if name in own or not is_leftover(name):
            continue
        try:
            st = os.stat(name, dir_fd=fd, follow_symlinks=False)
        except OSError:
            continue
        if not _live(fd, name, st):
            out.append(name)
    return out


def _print_notice(text: str) -> None:
    print(f"dispersion: {text}", file=sys.stderr)


def notice_leftovers(fd: int, shown: str, notice=None, own: tuple[str, ...] = ()) -> list[str]:
    """Report, in one line (once per folder and process), the :func:`leftovers` of folder
    ``fd`` (``shown``: its path for the message); they are left as they are."""
    try:
        st = os.fstat(fd)
        found = leftovers(fd, own)
    except OSError:
        return []
    key = _ident(st)
    if found and key not in _noticed:
        _noticed.add(key)
        first = printable(found[0], 120)
        more = f" and {len(found) - 1} more" if len(found) > 1 else ""
        (notice or _print_notice)(
            f"left {first}{more} in {shown or '.'} untouched: temporaries of an interrupted "
            "or concurrent dispersion run (or look-alikes); delete them once no run writes "
            "there")
    return found


class NewFile:
    """A new file for ``name`` in the open folder ``fd``: write to :attr:`fd`, then
    :meth:`commit` (or :meth:`discard`). ``option`` names the option in refusals;
    ``register(self)`` records it in the writer's cleanup record as it is created (module
    doc: an interrupt right after the ``open`` then finds it there)."""

    def __init__(self, fd: int, name: str, shown: str, option: str = "output", *,
                 register=None):
        self.folder, self.name, self.shown, self.option = fd, name, shown, option
        self.tmp = temp_name(name)
        self.done = True  # nothing to discard until the temporary exists
        self.fd = None
        flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC
        with interrupts_held():
            new = os.open(self.tmp, flags, 0o600, dir_fd=fd)  # ours: O_EXCL, a secret name
            try:
                checkpoint()  # the window right after the creation
                self._ident = _ident(os.fstat(new))
                fcntl.flock(new, fcntl.LOCK_EX)  # alive: not reported as a leftover
            except BaseException:
                os.close(new)
                with contextlib.suppress(OSError):
                    os.unlink(self.tmp, dir_fd=fd)
                raise
            self.fd, self.done = new, False
            if register is not None:
                register(self)

    def commit(self, mode: int, gid: int | None = None) -> None:
        """``fsync``, give mode ``mode`` (and group ``gid``), rename onto the target, unless
        the target now breaks the owner rule (then :class:`~dispersion.errors.InputError`,
        the temporary removed)."""
        try:
            self.sync(mode, gid)
            self.swap()
        except BaseException:
            self.discard()
            raise
        self.close()

    def sync(self, mode: int, gid: int | None = None) -> None:
        """``fsync`` the data, give the file mode ``mode`` and group ``gid`` (the replaced
        file's; kept where the system allows), before :meth:`swap`."""
        os.fsync(self.fd)
        _group(self.fd, gid)
        os.fchmod(self.fd, mode)
        checkpoint()

    def swap(self) -> None:
        """The rename alone (after :meth:`sync`), if the target still passes the owner
        rule of :func:`~dispersion.ownership.file_state` (else its InputError)."""
        now = file_state(self.folder, self.name, self.shown, self.option)
        if now.kind == "stream":
            from dispersion.errors import InputError

            raise InputError(f"{self.option} {self.shown} became a device or pipe while "
                             "dispersion wrote it; nothing was written")
        if not _still(self.folder, self.tmp, self._ident):
            raise FileNotFoundError(errno.ENOENT, "the temporary went away", self.tmp)
        if now.kind == "new":
            rename_new(self.folder, self.tmp, self.name)
        else:
            os.replace(self.tmp, self.name, src_dir_fd=self.folder, dst_dir_fd=self.folder)
        self.done = True
        _fsync(self.folder)
        checkpoint()

    def close(self) -> None:
        # the descriptor is forgotten before it is closed: a signal handler that raises
        # between the two (SIGTERM under the CLI) must not leave it to be closed twice
        fd, self.fd = self.fd, None
        if fd is not None:
            os.close(fd)

    def discard(self) -> None:
        """Remove the temporary (only if it is still the file this object created)."""
        if not self.done and _still(self.folder, self.tmp, self._ident):
            with contextlib.suppress(OSError):
                os.unlink(self.tmp, dir_fd=self.folder)
        self.done = True
        self.close()


def _open_dir(name: str, fd: int) -> int:
    return os.open(name, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC, dir_fd=fd)


def _copy_file(src_dir: int, dst_dir: int, name: str, st: os.stat_result) -> None:
    src = os.open(name, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC,
                  dir_fd=src_dir)
    try:
        if _ident(os.fstat(src)) != _ident(st):
            raise FileNotFoundError(errno.ENOENT, "changed while it was copied", name)
        dst = os.open(name, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC,
                      0o600, dir_fd=dst_dir)
        try:
            with open(src, "rb", closefd=False) as fin, open(dst, "wb", closefd=False) as fout:
                shutil.copyfileobj(fin, fout, 1 << 20)
            os.fsync(dst)
            _group(dst, st.st_gid)
            os.fchmod(dst, stat.S_IMODE(st.st_mode))
            os.utime(dst, ns=(st.st_atime_ns, st.st_mtime_ns))
        finally:
            os.close(dst)
    finally:
        os.close(src)


def _remove_all(fd: int, name: str) -> None:
    """Remove ``name`` in folder ``fd`` with everything in it (a temporary of ours)."""
    try:
        st = os.stat(name, dir_fd=fd, follow_symlinks=False)
    except FileNotFoundError:
        return
    if not stat.S_ISDIR(st.st_mode):
        os.unlink(name, dir_fd=fd)
        return
    sub = _open_dir(name, fd)
    try:
        for entry in os.listdir(sub):
            _remove_all(sub, entry)
    finally:
        os.close(sub)
    os.rmdir(name, dir_fd=fd)


class NewFolder:
    """A new version of folder ``name`` (in the open folder ``fd``), built beside it and
    swapped in whole. ``target`` is what the owner rule found
    (:func:`dispersion.ownership.folder_state`), ``parent_text`` the folder as the user wrote
    it (for :attr:`path`).

    :attr:`path` is the new folder (write into it); :meth:`commit` swaps it in,
    :meth:`discard` removes it.
    """

    def __init__(self, fd: int, name: str, shown: str, parent_text: str, target, *,
                 notice=None, register=None):
        self.folder, self.name, self.shown, self.target = fd, name, shown, target
        self.notice = notice or _print_notice
        self.tmp = temp_name(name)
        self.path = os.path.join(parent_text, self.tmp) if parent_text else self.tmp
        self.copied: dict[tuple[str, ...], tuple] = {}
        self.ignore = False
        self.done, self.fd = True, None  # nothing to discard until the folder exists
        with interrupts_held():  # made and recorded as one step (module doc)
            os.mkdir(self.tmp, 0o700, dir_fd=fd)  # ours: mkdir fails on any existing name
            try:
                checkpoint()  # the window right after the creation
                new = _open_dir(self.tmp, fd)
                try:
                    self._ident = _ident(os.fstat(new))
                    fcntl.flock(new, fcntl.LOCK_EX)
                except BaseException:
                    os.close(new)
                    raise
            except BaseException:
                with contextlib.suppress(OSError):
                    os.rmdir(self.tmp, dir_fd=fd)
                raise
            self.fd, self.done = new, False
            if register is not None:
                register(self)
        try:
            if target.kind == "folder":
                self._copy_old()
            if ".gitignore" not in os.listdir(self.fd):
                with open(os.open(".gitignore", os.O_WRONLY | os.O_CREAT | os.O_EXCL
                                  | os.O_NOFOLLOW | os.O_CLOEXEC, 0o600, dir_fd=self.fd),
                          "w") as fh:
                    fh.write("*\n")
                self.ignore = True
            checkpoint()
        except BaseException:
            self.discard()
            raise

    def _copy_old(self) -> None:
        """Copy the old folder into the new one (the owner rule checked again on the way)."""
        old = _open_dir(self.name, self.folder)
        try:
            if _ident(os.fstat(old)) != self.target.ident:
                from dispersion.errors import InputError

                raise InputError(f"{self.target.option} {self.shown} was replaced while "
                                 "dispersion checked it; run again")
            dirs = {(): (old, self.fd)}
            try:
                for rel, st in tree(old, self.shown, self.target.option):
                    src, dst = dirs[rel[:-1]]
                    if stat.S_ISDIR(st.st_mode):
                        os.mkdir(rel[-1], 0o700, dir_fd=dst)
                        dirs[rel] = (_open_dir(rel[-1], src), _open_dir(rel[-1], dst))
                        _group(dirs[rel][1], st.st_gid)
                        if _ident(os.fstat(dirs[rel][0])) != _ident(st):
                            raise FileNotFoundError(errno.ENOENT, "changed while copied",
                                                    "/".join(rel))
                    else:
                        _copy_file(src, dst, rel[-1], st)
                    self.copied[rel] = (_ident(st), st.st_size, st.st_mtime_ns,
                                        stat.S_IMODE(st.st_mode))
                for rel in sorted((r for r in dirs if r), key=len, reverse=True):
                    os.chmod(rel[-1], self.copied[rel][3], dir_fd=dirs[rel[:-1]][1])
            finally:
                for rel, (src, dst) in dirs.items():
                    if rel:
                        os.close(src)
                        os.close(dst)
        finally:
            os.close(old)

    def commit(self, mode: int, gid: int | None = None) -> None:
        """Swap the new folder in (mode ``mode``, group ``gid``); remove what the old one
        held that was copied. A target that changed since the check is refused (the new
        folder removed)."""
        try:
            if self.ignore:
                os.unlink(".gitignore", dir_fd=self.fd)
            _fsync(self.fd)
            _group(self.fd, gid)
            os.fchmod(self.fd, mode)
            checkpoint()
            self._swap()
        except BaseException:
            if not self.done:
                self.discard()
                raise
            self._finish()  # interrupted just after the swap: the old version still goes
            raise
        self._finish()

    def _finish(self) -> None:
        fd, self.fd = self.fd, None  # forgotten before closed (see NewFile.close)
        if fd is not None:
            os.close(fd)
        if self.target.kind == "folder":
            self._remove_old()

    def _swap(self) -> None:
        # Ctrl-C and SIGTERM wait until the folder is in place (a few system calls)
        with interrupts_held():
            self._swap_now()

    def _swap_now(self) -> None:
        from dispersion.errors import InputError

        changed = InputError(f"{self.target.option} {self.shown} changed while dispersion "
                             "wrote it; it was left as it was (run again)")
        if self.target.kind == "new":
            try:
                rename_new(self.folder, self.tmp, self.name)
            except FileExistsError:
                raise changed from None
        elif exchange(self.folder, self.tmp, self.name):
            if not _still(self.folder, self.tmp, self.target.ident):  # not what we checked
                exchange(self.folder, self.tmp, self.name)  # swap back
                raise changed
        else:  # two renames: NAME is absent between them
            old = temp_name(self.name)
            if not _still(self.folder, self.name, self.target.ident):
                raise changed
            os.rename(self.name, old, src_dir_fd=self.folder, dst_dir_fd=self.folder)
            try:
                checkpoint()
                os.rename(self.tmp, self.name, src_dir_fd=self.folder, dst_dir_fd=self.folder)
            except BaseException:  # unwound in this process: the old folder goes back
                os.rename(old, self.name, src_dir_fd=self.folder, dst_dir_fd=self.folder)
                raise
            self.tmp = old
        self.done = True
        _fsync(self.folder)
        checkpoint()

    def _remove_old(self) -> None:
        """Remove, from the old version (now under :attr:`tmp`), the entries that are
        exactly those copied; keep the rest and say so. Ctrl-C and SIGTERM wait."""
        kept: list[str] = []
        with interrupts_held():
            try:
                self._prune(self.folder, self.tmp, (), kept)
            except OSError as exc:
                kept.append(f"({exc.strerror or exc})")
        if kept:
            self.notice(f"kept {self.shown} as it was before this run under "
                        f"{printable(self.tmp)}: {printable(kept[0], 80)}"
                        f"{f' and {len(kept) - 1} more' if len(kept) > 1 else ''} changed "
                        "while the run wrote, so they are not in the new version")
        checkpoint()

    def _prune(self, fd: int, name: str, rel: tuple[str, ...], kept: list[str]) -> None:
        sub = _open_dir(name, fd)
        try:
            if rel and _ident(os.fstat(sub)) != self.copied.get(rel, (None,))[0]:
                kept.append("/".join(rel))
                return
            for entry in sorted(os.listdir(sub)):
                path = (*rel, entry)
                st = os.stat(entry, dir_fd=sub, follow_symlinks=False)
                if stat.S_ISDIR(st.st_mode) and path in self.copied:
                    self._prune(sub, entry, path, kept)
                elif path in self.copied and self.copied[path][:3] == (
                        _ident(st), st.st_size, st.st_mtime_ns) and stat.S_ISREG(st.st_mode):
                    os.unlink(entry, dir_fd=sub)
                else:
                    kept.append("/".join(path))
        finally:
            os.close(sub)
        with contextlib.suppress(OSError):  # not empty: something was kept
            os.rmdir(name, dir_fd=fd)

    def discard(self) -> None:
        """Remove the new folder (only while it is still the one this object made)."""
        if not self.done and _still(self.folder, self.tmp, self._ident):
            with contextlib.suppress(OSError):
                _remove_all(self.folder, self.tmp)
        self.done = True
        fd, self.fd = self.fd, None  # forgotten before closed (see NewFile.close)
        if fd is not None:
            os.close(fd)
