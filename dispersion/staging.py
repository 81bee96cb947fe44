"""The staged writer: files and folders replaced as one unit, with one recovery routine.

Every output the toolkit writes (a single file of :func:`dispersion.io.atomic_write`, the
files of :func:`dispersion.io.write_files`, a report folder of
:mod:`dispersion.report.folder`) goes through a :class:`Stage`:

1. **Stage.** A hidden folder ``.dispersion-stage.TOKEN`` is made beside each target, where
   ``TOKEN`` is 128 random bits; its first file, ``.stage.json``, records the token, the
   writer's pid and the primary stage of the unit. The writer holds an exclusive ``flock`` on
   every stage folder while it lives (the kernel drops it when the process dies, even by
   SIGKILL). The new content is written into the stage as ``0``, ``1``, ... and ``fsync``\\ ed.
2. **Commit.** A journal ``.journal.json`` (the token and each rename) is written atomically
   into the primary stage: that is the point of no return.
3. **Rename.** Each staged entry is renamed onto its target (a folder is swapped with
   ``renameat2(RENAME_EXCHANGE)`` where Linux offers it), then the stages are removed,
   the secondary ones first, the journal last. Ctrl-C or SIGTERM (under the CLI's handler)
   in this phase is held until the unit is complete; a kill before the journal leaves the
   unit all old, one after it all new once recovered.

**Recovery** (:func:`recover`, run by every writer on the folder it writes into) acts on a
leftover only when everything verifies: the folder's name is ``.dispersion-stage.`` plus 32
hex digits, it is a real folder (not a link), its ``.stage.json`` holds the same token, no
live writer holds its lock, it holds only the names a writer makes there (``.stage.json``,
``.journal.json``, numbered entries), and every journal entry renames ``STAGE/k`` (``k`` a number) to
a plain name in the very folder that holds that stage (no ``/``, no ``..``, no link on the
way). A verified stage with a journal is rolled forward (the unit ends all new); one without
is removed (the unit stays all old). Inside a stage only the names the writer makes are
deleted. Anything else is never touched; a name that looks like ours but does not verify is
reported in one line (once per process).

>>> import tempfile, pathlib
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> with Stage() as stage:
...     _ = stage.file(folder / "a.txt").write_text("new")
...     stage.commit()
1
>>> sorted(p.name for p in folder.iterdir())
['a.txt']
"""
from __future__ import annotations

import contextlib
import errno
import fcntl
import json
import os
import re
import signal
import stat
import sys
from pathlib import Path

__all__ = ["Stage", "recover", "stale_stages", "STAGE_PREFIX", "is_stage_name", "checkpoint",
           "marker_text"]

#: Name prefix of every stage folder; the rest is the token (32 hex digits).
STAGE_PREFIX = ".dispersion-stage."
_STAGE_NAME = re.compile(r"\.dispersion-stage\.([0-9a-f]{32})")
_MARK = ".stage.json"
_JOURNAL = ".journal.json"
_JOURNAL_TMP = ".journal.json.tmp"
_ENTRY = re.compile(r"(?:old-)?[0-9]{1,6}")
# Names that look like leftovers of a writer of this toolkit (this one, or an older one
# that named journals ``.dispersion-write.PID.json``): reported when they do not verify.
_LOOKALIKE = re.compile(r"\.dispersion-(?:stage|write)\b.*")
#: Environment variable of the fault tests: ``"N:SIGNAL"`` sends SIGNAL to this process at
#: the N-th :func:`checkpoint` (numbered from 1), so a test can kill a writer at every step.
FAULT_ENV = "DISPERSION_FAULT_AT"
_checkpoints = [0]
_noticed: set[str] = set()


def checkpoint() -> None:
    """A point where a writer may be interrupted; the fault tests stop the process here."""
    spec = os.environ.get(FAULT_ENV)
    if not spec:
        return
    _checkpoints[0] += 1
    at, _, sig = spec.partition(":")
    if at.isdigit() and int(at) == _checkpoints[0]:
        os.kill(os.getpid(), getattr(signal, sig or "SIGKILL"))


def is_stage_name(name: str) -> bool:
    """True if ``name`` has the form of a stage folder (``.dispersion-stage.`` + 32 hex)."""
    return _STAGE_NAME.fullmatch(name) is not None


def _notice(text: str) -> None:
    print(f"dispersion: {text}", file=sys.stderr)


def _fsync_dir(path: Path) -> None:
    with contextlib.suppress(OSError):
        fd = os.open(path, os.O_RDONLY | os.O_DIRECTORY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


def _exchange(a: Path, b: Path) -> bool:
    """Atomically swap two paths (Linux ``renameat2`` RENAME_EXCHANGE); False if unsupported."""
    if not sys.platform.startswith("linux"):
        return False
    import ctypes  # only here: the rest of the writer needs no ctypes (start-up time)

    try:
        renameat2 = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError):
        return False
    at_fdcwd, rename_exchange = -100, 2
    if renameat2(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), rename_exchange) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.EINVAL, errno.ENOSYS, errno.ENOTSUP):
        return False
    raise OSError(err, os.strerror(err), str(a))


def _lock(path: Path, *, wait: bool) -> int | None:
    """An exclusive ``flock`` on folder ``path`` (not following a link); None if held."""
    fd = os.open(path, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
    except BlockingIOError:
        os.close(fd)
        return None
    except BaseException:
        os.close(fd)
        raise
    return fd


def _empty_dir(path: Path) -> bool:
    try:
        return stat.S_ISDIR(os.lstat(path).st_mode) and not os.listdir(path)
    except OSError:
        return False


def _held(path: Path) -> bool:
    """True if a live writer holds the lock of folder ``path``."""
    try:
        fd = _lock(path, wait=False)
    except OSError:
        return False
    if fd is None:
        return True
    os.close(fd)
    return False


def _marker_token(folder: Path, marker: str) -> str | None:
    """The token recorded in ``folder/marker`` (a line ``token: HEX``), if any."""
    path = folder / marker
    try:
        if not stat.S_ISREG(os.lstat(path).st_mode):
            return None
        text = path.read_text(encoding="utf-8", errors="replace")[:4096]
    except OSError:
        return None
    found = re.search(r"^token: ([0-9a-f]{32})$", text, re.MULTILINE)
    return found.group(1) if found else None


def marker_text(text: str, token: str) -> str:
    """The content of a unit marker file: ``text`` and the line ``token: TOKEN``."""
    return f"{text.rstrip()}\ntoken: {token}\n"


class Stage:
    """One unit of outputs (files or folders), staged then renamed onto their targets.

    Use as a context manager: :meth:`file` and :meth:`folder` return the staged path of a
    target (write into it), :meth:`commit` renames everything; leaving the block without a
    commit (an error, Ctrl-C, SIGTERM) removes the stages and leaves every target as it was.

    Parameters
    ----------
    notice : callable, optional
        Receives one-line notices of recovery (default: print to stderr).
    """

    def __init__(self, *, notice=None):
        self.token = os.urandom(16).hex()  # 128 bits from the OS's CSPRNG, as secrets does
        self.notice = notice or _notice
        self._stages: dict[Path, tuple[Path, int]] = {}  # parent -> (stage folder, lock fd)
        self._entries: list[dict] = []
        self._created: list[Path] = []  # folders made for targets, removed again on abort
        self._done = False

    # -- staging -------------------------------------------------------------------------
    def __enter__(self) -> Stage:
        return self

    def __exit__(self, kind, exc, tb) -> None:
        if not self._done:
            self.abort()

    def _stage_in(self, parent: Path) -> Path:
        if parent in self._stages:
            return self._stages[parent][0]
        for folder in reversed([parent, *parent.parents]):
            if not folder.exists() and not folder.is_symlink():
                folder.mkdir()  # mkdir applies 0o777 & ~umask
                self._created.append(folder)
        recover(parent, notice=self.notice)
        stage = parent / f"{STAGE_PREFIX}{self.token}"
        os.mkdir(stage, 0o700)
        try:
            fd = _lock(stage, wait=True)
        except BaseException:
            os.rmdir(stage)
            raise
        self._stages[parent] = (stage, fd)
        primary = next(iter(self._stages.values()))[0]
        mark = {"token": self.token, "pid": os.getpid(), "primary": str(primary)}
        with open(stage / _MARK, "x", encoding="utf-8") as fh:
            json.dump(mark, fh)
        checkpoint()
        return stage

    def _add(self, target, kind: str, marker: str | None = None) -> Path:
        target = Path(os.path.abspath(target))
        parent = Path(os.path.realpath(target.parent))
        stage = self._stage_in(parent)
        index = len(self._entries)
        entry = {"stage": str(stage), "k": str(index), "name": target.name, "kind": kind}
        if marker is not None:
            entry["marker"] = marker
        self._entries.append(entry)
        return stage / str(index)

    def file(self, target) -> Path:
        """Staged path for file ``target`` (absolute or relative to the current folder)."""
        return self._add(target, "file")

    def folder(self, target, marker: str) -> Path:
        """Staged path (a new folder) for folder ``target``; it must contain ``marker``, a
        file whose :func:`marker_text` carries :attr:`token` (how recovery tells the new
        folder from the old)."""
        path = self._add(target, "dir", marker)
        os.mkdir(path)
        return path

    # -- commit --------------------------------------------------------------------------
    def commit(self) -> int:
        """Rename every staged entry onto its target; return the number of entries."""
        if not self._entries:
            self.abort()
            return 0
        for entry in self._entries:
            if entry["kind"] == "dir" and \
                    _marker_token(Path(entry["stage"]) / entry["k"], entry["marker"]) != self.token:
                raise RuntimeError(f"staged folder for {entry['name']} lacks its marker")
        for stage, _ in self._stages.values():
            _fsync_dir(stage)
        checkpoint()
        primary = next(iter(self._stages.values()))[0]
        tmp = primary / _JOURNAL_TMP
        with open(tmp, "x", encoding="utf-8") as fh:
            json.dump({"token": self.token, "entries": self._entries}, fh)
            fh.flush()
            os.fsync(fh.fileno())
        checkpoint()
        os.rename(tmp, primary / _JOURNAL)  # the point of no return
        _fsync_dir(primary)
        checkpoint()
        self._done = True
        interrupted = None
        try:
            for entry in self._entries:
                while True:  # Ctrl-C or SIGTERM now: finish the unit first (renames are quick)
                    try:
                        _apply(entry, self.token)  # safe to repeat
                        checkpoint()
                        break
                    except KeyboardInterrupt as exc:
                        interrupted = exc
        except BaseException:
            for _, fd in self._stages.values():  # the next writer here finishes the unit
                os.close(fd)
            self._stages.clear()
            raise
        self._remove_stages()
        if interrupted is not None:
            raise interrupted
        return len(self._entries)

    def abort(self) -> None:
        """Remove the stages (and folders made for the targets); every target stays old."""
        self._done = True
        self._remove_stages()
        for folder in reversed(self._created):
            with contextlib.suppress(OSError):
                folder.rmdir()  # only if still empty

    def _remove_stages(self) -> None:
        stages = list(self._stages.values())
        for stage, fd in stages[1:] + stages[:1]:  # the primary (with the journal) last
            _remove_stage(stage)
            os.close(fd)
        self._stages.clear()


def _apply(entry: dict, token: str) -> None:
    """Perform (or finish) one rename of a committed unit; safe to repeat."""
    stage = Path(entry["stage"])
    new, target = stage / entry["k"], stage.parent / entry["name"]
    if entry["kind"] == "file":
        with contextlib.suppress(FileNotFoundError):  # a concurrent recovery was first
            os.replace(new, target)
        return
    if _marker_token(target, entry["marker"]) == token or not os.path.lexists(new):
        return  # already in place
    if os.path.lexists(target):
        # only a folder of ours (it carries the same kind of marker) or an empty one is moved
        if not os.path.isdir(target) or os.path.islink(target) or not (
                os.path.isfile(target / entry["marker"]) or not os.listdir(target)):
            raise OSError(errno.EEXIST, "not a folder written by dispersion", str(target))
        if _exchange(new, target):
            return
        old = stage / f"old-{entry['k']}"
        os.rename(target, old)
        checkpoint()
    os.rename(new, target)


def _remove_stage(stage: Path) -> bool:
    """Delete the entries a writer makes in ``stage``, then the folder; True if gone."""
    try:
        names = os.listdir(stage)
    except FileNotFoundError:
        return True
    except OSError:
        return False
    ours = {_MARK, _JOURNAL, _JOURNAL_TMP}
    for name in sorted(names, key=lambda n: n == _MARK):  # the marker last
        path = stage / name
        if name not in ours and not _ENTRY.fullmatch(name):
            continue
        try:
            if os.path.isdir(path) and not os.path.islink(path):
                import shutil

                shutil.rmtree(path)
            else:
                os.unlink(path)
        except FileNotFoundError:
            pass
        except OSError:
            return False  # e.g. read-only: left for a later run
    try:
        os.rmdir(stage)
    except FileNotFoundError:
        pass
    except OSError:
        return False
    return True


def _pid_alive(pid) -> bool:
    if not isinstance(pid, int) or isinstance(pid, bool) or pid <= 0:
        return False
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return pid <= 2**22  # a process of another user, or an impossible pid
    return True


def _read_json(path: Path):
    """Parsed JSON of a small regular file ``path`` (not a link), or None."""
    try:
        st = os.lstat(path)
        if not stat.S_ISREG(st.st_mode) or st.st_size > 1 << 20:
            return None
        return json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError, UnicodeDecodeError):
        return None


def _only_ours(stage: Path) -> bool:
    """True if ``stage`` holds nothing but names a writer makes there."""
    try:
        names = os.listdir(stage)
    except OSError:
        return False
    return all(n in (_MARK, _JOURNAL, _JOURNAL_TMP) or _ENTRY.fullmatch(n) for n in names)


def _verified_stage(stage: Path, token: str | None = None) -> dict | None:
    """The marker of ``stage`` if it is a stage folder of ours whose token verifies and
    which holds nothing a writer does not make (a user's file in it: not ours)."""
    found = _STAGE_NAME.fullmatch(stage.name)
    if found is None or (token is not None and found.group(1) != token):
        return None
    try:
        if not stat.S_ISDIR(os.lstat(stage).st_mode):
            return None
    except OSError:
        return None
    mark = _read_json(stage / _MARK)
    if not isinstance(mark, dict) or mark.get("token") != found.group(1) \
            or not _only_ours(stage):
        return None
    return mark


def _verified_entries(journal: dict, token: str) -> list[dict] | None:
    """The entries of a journal if every one stays inside the folder of a verified stage."""
    if not isinstance(journal, dict) or journal.get("token") != token:
        return None
    entries = journal.get("entries")
    if not isinstance(entries, list):
        return None
    for entry in entries:
        if not isinstance(entry, dict) or not all(isinstance(entry.get(k), str)
                                                  for k in ("stage", "k", "name", "kind")):
            return None
        stage = Path(entry["stage"])
        name = entry["name"]
        if not stage.is_absolute() or ".." in stage.parts or not entry["k"].isdigit() \
                or not _ENTRY.fullmatch(entry["k"]) or entry["kind"] not in ("file", "dir"):
            return None
        if name in ("", ".", "..") or "/" in name or "\0" in name or _LOOKALIKE.match(name):
            return None
        if entry["kind"] == "dir" and (not isinstance(entry.get("marker"), str)
                                       or "/" in entry["marker"]
                                       or entry["marker"] in ("", ".", "..")):
            return None
        # the stage must be a real folder of ours, reached without links: its parent resolves
        # to itself, so every rename stays in the folder that holds the stage
        if os.path.realpath(stage.parent) != str(stage.parent) \
                or _verified_stage(stage, token) is None:
            return None
        target = stage.parent / name
        if os.path.islink(target):
            return None
    return entries


def stale_stages(folder) -> list[Path]:
    """Stages in ``folder`` that verify as ours and whose writer is gone (nothing is changed)."""
    folder = Path(os.path.realpath(folder))
    stale = []
    try:
        names = sorted(e.name for e in os.scandir(folder) if is_stage_name(e.name))
    except OSError:
        return stale
    for name in names:
        mark = _verified_stage(folder / name)
        if mark is None or (_pid_alive(mark.get("pid")) and mark.get("pid") != os.getpid()):
            continue
        try:
            fd = _lock(folder / name, wait=False)
        except OSError:
            continue
        if fd is not None:
            os.close(fd)
            stale.append(folder / name)
    return stale


def recover(folder, *, notice=None) -> list[Path]:
    """Finish or undo the units that killed writers left in ``folder``; return what went.

    Only stages that verify (see the module docstring) are acted on; a look-alike name is
    reported through ``notice`` (default: one line on stderr) and left as it is.
    """
    notice = notice or _notice
    folder = Path(os.path.realpath(folder))
    removed = []
    try:
        names = [e.name for e in os.scandir(folder) if e.name.startswith(".dispersion-")]
    except OSError:
        return removed
    for name in sorted(names):
        path = folder / name
        if is_stage_name(name) and (_held(path) or _empty_dir(path)):
            continue  # a live writer (at work, or between its mkdir and its lock)
        mark = _verified_stage(path)
        if mark is None:
            if _LOOKALIKE.match(name) and str(path) not in _noticed:
                _noticed.add(str(path))
                notice(f"left {path} untouched: it looks like a leftover of dispersion but "
                       "does not verify as one")
            continue
        try:
            if _settle(path, mark, notice):
                removed.append(path)
        except OSError as exc:  # e.g. a folder now stands where a file is to go
            notice(f"left {path} as it is: {exc.strerror or exc} ({exc.filename or path})")
    return removed


def _settle(stage: Path, mark: dict, notice) -> bool:
    """Roll a verified dead stage forward (journal) or back (none); True if it is gone."""
    token = mark["token"]
    if _pid_alive(mark.get("pid")) and mark.get("pid") != os.getpid():
        return False
    try:
        fd = _lock(stage, wait=False)
    except OSError:
        return False
    if fd is None:
        return False  # its writer is alive
    try:
        primary = Path(mark["primary"]) if isinstance(mark.get("primary"), str) else stage
        journal = _read_json(primary / _JOURNAL) if primary == stage or (
            _verified_stage(primary, token) is not None) else None
        if journal is not None:
            entries = _verified_entries(journal, token)
            if entries is None:
                if str(stage) not in _noticed:
                    _noticed.add(str(stage))
                    notice(f"left {stage} untouched: its journal does not verify")
                return False
            for entry in entries:
                _apply(entry, token)
            others = {Path(e["stage"]) for e in entries} - {primary}
            for other in sorted(others):
                _remove_stage(other)
            gone = _remove_stage(primary) and not stage.exists()
            notice(f"finished the output of an interrupted run ({stage.name})")
            return gone
        gone = _remove_stage(stage)
        notice(f"removed the temporaries of an interrupted run ({stage.name})")
        return gone
    finally:
        os.close(fd)
