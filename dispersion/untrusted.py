"""Files and names written by strangers: read within limits, shown without escape sequences.

A file a user hands the toolkit (a ``--mass-rule`` table; the claims files follow the same
rules in :mod:`dispersion.claims.claims_file`) may have been written by anyone, so it is read
as data, within limits checked before the work:

- **Regular file only.** It is opened without blocking (a named pipe does not hang) and
  checked on the open descriptor: ``/dev/zero``, a FIFO, a folder or a socket is refused
  before a byte is read.
- **Size before reading.** A file larger than the caller's limit is refused from its size;
  at most one byte more than the limit is ever read (a file that grows while it is read is
  refused too).
- **UTF-8**, refused with the offset of the first bad byte.
- **TOML by a parser, never evaluated**, with its nesting depth bounded (tables and arrays
  nested deeper than the limit are refused, also where the parser itself would run out of
  stack) and the name of the file in every message.

:func:`printable` makes any text safe for a terminal (names of files found on disk, values
read from a file): escape sequences are removed and control characters written as visible
escapes, so a name cannot move the cursor, clear the screen or forge another line.

>>> printable("a\\x1b[2Jb\\nc")
'ab\\\\x0ac'
"""
from __future__ import annotations

import os
import re
import stat
import unicodedata
from fractions import Fraction

from dispersion.errors import InputError

__all__ = ["printable", "read_text", "load_toml", "nesting_depth", "read_fraction"]

# CSI / OSC / other ESC sequences (ECMA-48): removed whole, so no fragment stays behind
_ESCAPE = re.compile(r"\x1b(?:\[[0-?]*[ -/]*[@-~]|\][^\x07\x1b]*(?:\x07|\x1b\\)|[@-Z\\-_])")


def _escape(ch: str) -> str:
    code = ord(ch)
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def printable(text, limit: int = 300) -> str:
    """``text`` safe for one terminal line: escape sequences removed, every control or
    format character (newlines, bidirectional overrides, zero-width joiners) escaped,
    at most ``limit`` characters (an ellipsis marks a cut).

    >>> printable("\\u202eevil")
    '\\\\u202eevil'
    """
    text = _ESCAPE.sub("", str(text))
    text = "".join(_escape(ch) if unicodedata.category(ch) in ("Cc", "Cf", "Zl", "Zp")
                   or ch == "\x7f" else ch for ch in text)
    return text if len(text) <= limit else text[:limit - 3] + "..."


def read_text(path, what: str, max_bytes: int, *, suffix: str | None = None) -> str:
    """The text of the file ``path``, refused unless a regular UTF-8 file of at most
    ``max_bytes`` bytes; ``what`` names the kind of file in the messages (``"mass rule
    file"``), ``suffix`` the ending its name must have (``".toml"``).

    Raises
    ------
    InputError
        naming the file: not a path, a wrong ending, cannot be opened, not a regular file,
        too large, not UTF-8.

    >>> read_text("/dev/zero", "mass rule file", 1000)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: mass rule file /dev/zero: not a regular file
    """
    if not isinstance(path, (str, os.PathLike)):
        raise InputError(f"{what} must be a path, got {type(path).__name__}")
    shown = printable(os.fspath(path))
    if suffix is not None and not os.fspath(path).lower().endswith(suffix):
        raise InputError(f"{what} {shown}: the name must end in {suffix}")
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOCTTY | os.O_CLOEXEC)
    except (OSError, ValueError) as exc:  # ValueError: a NUL byte in the name
        raise InputError(f"{what} {shown}: cannot read it "
                         f"({getattr(exc, 'strerror', None) or exc})") from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise InputError(f"{what} {shown}: not a regular file")
        if info.st_size > max_bytes:
            raise InputError(f"{what} {shown}: {info.st_size} bytes, more than the limit of "
                             f"{max_bytes} bytes")
        chunks, size = [], 0
        while size <= max_bytes:
            chunk = os.read(fd, max_bytes + 1 - size)
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
    except OSError as exc:
        raise InputError(f"{what} {shown}: cannot read it ({exc.strerror or exc})") from None
    finally:
        os.close(fd)
    data = b"".join(chunks)
    if len(data) > max_bytes:  # it grew while we read it
        raise InputError(f"{what} {shown}: more than the limit of {max_bytes} bytes")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"{what} {shown}: not UTF-8 text (byte 0x{data[exc.start]:02x} at "
                         f"offset {exc.start})") from None


def nesting_depth(data, stop: int) -> int:
    """Nesting depth of parsed data (dicts and lists; the top level is 0), counted without
    recursion and only down to ``stop + 1``."""
    deepest, stack = 0, [(data, 0)]
    while stack:
        node, level = stack.pop()
        if isinstance(node, (dict, list)):
            deepest = max(deepest, level)
            if level <= stop:
                stack += [(x, level + 1) for x in (node.values() if isinstance(node, dict)
                                                  else node)]
    return deepest


def load_toml(text: str, file: str, what: str, max_depth: int) -> dict:
    """The TOML ``text`` of ``file`` as a dict, nested at most ``max_depth`` levels.

    >>> load_toml('a = [[1]]', "r.toml", "mass rule file", 1)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: mass rule file r.toml: tables and arrays nested more than 1 levels deep
    """
    try:  # Python >= 3.11
        import tomllib
    except ModuleNotFoundError:  # pragma: no cover - Python 3.10
        import tomli as tomllib

    shown = printable(file)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{what} {shown}: malformed TOML: {printable(exc)}") from None
    except RecursionError:
        raise InputError(f"{what} {shown}: tables and arrays nested more than {max_depth} "
                         "levels deep") from None
    except ValueError as exc:  # e.g. an integer of more than 4300 digits
        raise InputError(f"{what} {shown}: malformed TOML: {printable(exc, 200)}") from None
    if nesting_depth(data, max_depth) > max_depth:
        raise InputError(f"{what} {shown}: tables and arrays nested more than {max_depth} "
                         "levels deep")
    return data


# a decimal such as 0.125, -1e-3 or .5; two of them with a slash make a fraction
_DECIMAL = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d{1,3})?"
_FRACTION = re.compile(rf"({_DECIMAL})(?:/({_DECIMAL}))?")


def read_fraction(text: str, what: str, max_chars: int = 60) -> Fraction:
    """The number written in ``text`` as an exact fraction: a decimal (``0.125``, ``-1e-3``)
    or a quotient of two (``1/8``), read by a regular expression (a whitelist: nothing else
    is accepted, nothing is evaluated), at most ``max_chars`` characters, exponents of at
    most three digits.

    >>> read_fraction("1/8", "thickness")
    Fraction(1, 8)
    >>> read_fraction("2**99", "thickness")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: thickness must be a number such as 0.125 or 1/8, got '2**99'
    """
    text = str(text).strip()
    match = _FRACTION.fullmatch(text) if len(text) <= max_chars else None
    if match is None:
        raise InputError(f"{what} must be a number such as 0.125 or 1/8, got "
                         f"{printable(text, 40)!r}")
    value = Fraction(match.group(1))
    if match.group(2) is not None:
        denominator = Fraction(match.group(2))
        if denominator == 0:
            raise InputError(f"{what}: division by zero in {printable(text, 40)!r}")
        value /= denominator
    return value
