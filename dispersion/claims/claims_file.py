"""A claims file as untrusted text: read within limits, parsed as TOML, lines found for messages.

A claims file is refused with one :class:`~dispersion.errors.InputError` naming the file
unless it is a regular UTF-8 file of at most :data:`MAX_FILE_BYTES`, valid TOML, nested at
most :data:`MAX_NESTING` tables deep. :class:`Lines` finds the line of a ``[[claim]]`` entry
and of its keys, so that every later error names file and line.

>>> data = read_toml('[[claim]]\\nname = "a"\\n', "f.toml")
>>> data["claim"][0]["name"], Lines('[[claim]]\\nname = "a"\\n', "f.toml").at(0, "name")
('a', 'f.toml:2')
"""
from __future__ import annotations

import os
import re
import stat
from pathlib import Path

from dispersion.errors import InputError

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = ["MAX_FILE_BYTES", "MAX_NESTING", "paper_claims_path", "read_text", "read_toml",
           "Lines"]

#: Largest claims file read. The paper's file has 4 KiB; a manuscript with a thousand claims
#: stays under 1 MiB, and TOML parsing of 1 MiB takes well under a second.
MAX_FILE_BYTES = 2**20
#: Deepest nesting of tables and arrays: ``[[claim]]`` -> ``weights`` -> contact -> neighbour.
MAX_NESTING = 6


def paper_claims_path() -> Path:
    """The claims file of the paper's eqs (14)-(20) shipped with the package."""
    from importlib import resources

    return Path(str(resources.files("dispersion") / "data" / "paper_claims.toml"))


def read_text(path) -> str:
    """The text of a claims file, refused unless a regular UTF-8 file of bounded size.

    Opened without blocking (a fifo does not hang) and checked on the open descriptor, so
    ``/dev/zero`` or a named pipe is refused before a byte is read.
    """
    if not isinstance(path, (str, os.PathLike)):
        raise InputError(f"claims file must be a path, got {type(path).__name__}")
    path = Path(path)
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0))
    except (OSError, ValueError) as exc:  # ValueError: a NUL byte in the name
        raise InputError(f"{path}: cannot read claims file "
                         f"({getattr(exc, 'strerror', None) or exc})") from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise InputError(f"{path}: not a regular file (a claims file is TOML text)")
        if info.st_size > MAX_FILE_BYTES:
            raise InputError(f"{path}: claims file of {info.st_size} bytes, more than the limit "
                             f"of {MAX_FILE_BYTES} bytes")
        with os.fdopen(fd, "rb", closefd=False) as handle:
            data = handle.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise InputError(f"{path}: cannot read claims file ({exc.strerror or exc})") from None
    finally:
        os.close(fd)
    if len(data) > MAX_FILE_BYTES:  # grew while we read it
        raise InputError(f"{path}: claims file larger than the limit of {MAX_FILE_BYTES} bytes")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"{path}: not UTF-8 text (byte 0x{data[exc.start]:02x} at offset "
                         f"{exc.start})") from None


def _depth(data) -> int:
    """Nesting depth of parsed TOML (tables and arrays), counted without recursion."""
    deepest, stack = 0, [(data, 0)]
    while stack:
        node, level = stack.pop()
        if isinstance(node, (dict, list)):
            deepest = max(deepest, level)
            if level <= MAX_NESTING:
                stack += [(x, level + 1) for x in (node.values() if isinstance(node, dict)
                                                  else node)]
    return deepest


def read_toml(text: str, file: str = "<string>") -> dict:
    """The TOML ``text`` of claims file ``file`` as a dict, within the size and depth limits."""
    if not isinstance(text, str):
        raise InputError(f"claims text must be a string (TOML), got {type(text).__name__}")
    if not isinstance(file, str):
        raise InputError(f"file must be a string naming the claims file, got "
                         f"{type(file).__name__}")
    if len(text) > MAX_FILE_BYTES:
        raise InputError(f"{file}: claims text of {len(text)} characters, more than the limit "
                         f"of {MAX_FILE_BYTES}")
    from dispersion.untrusted import check_toml

    # bounded on the raw text before the parser sees it (its cost is quadratic in the depth
    # of a dotted key)
    check_toml(text, file, MAX_FILE_BYTES, MAX_NESTING)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{file}: malformed TOML: {exc}") from None
    except RecursionError:
        raise InputError(f"{file}: malformed TOML: nested more than {MAX_NESTING} levels "
                         "deep") from None
    except ValueError as exc:  # e.g. an integer of more than 4300 digits
        raise InputError(f"{file}: malformed TOML: {str(exc)[:200]}") from None
    if _depth(data) > MAX_NESTING:
        raise InputError(f"{file}: tables and arrays nested more than {MAX_NESTING} levels deep")
    return data


class Lines:
    """Line numbers of ``[[claim]]`` entries and their keys, for error messages."""

    def __init__(self, text: str, file: str):
        self.file = file
        self.text = text.splitlines()
        self.heads = [i for i, s in enumerate(self.text) if re.match(r"\s*\[\[\s*claim\s*\]\]", s)]

    def _find(self, key: str, lo: int, hi: int) -> int | None:
        pat = re.compile(rf"\s*(\[\s*(claim|defaults)\.)?\"?{re.escape(key)}\"?\s*(=|\])")
        return next((i for i in range(lo, hi) if pat.match(self.text[i])), None)

    def top(self, key: str) -> str:
        """``file:line`` of a top-level key (before the first ``[[claim]]``)."""
        hit = self._find(key, 0, self.heads[0] if self.heads else len(self.text))
        return f"{self.file}:{hit + 1 if hit is not None else 1}"

    def line(self, i: int, key: str | None = None) -> int:
        """Line of ``key`` in entry ``i`` (the entry's own line if the key is not found)."""
        lo = self.heads[i] if i < len(self.heads) else 0
        hi = self.heads[i + 1] if i + 1 < len(self.heads) else len(self.text)
        hit = self._find(key[:100], lo, hi) if key else None
        return (hit if hit is not None else lo) + 1

    def at(self, i: int, key: str | None = None) -> str:
        """``file:line`` of ``key`` in entry ``i``."""
        return f"{self.file}:{self.line(i, key)}"
