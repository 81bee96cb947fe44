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
- **Bounded before parsed** (:func:`check_toml`): the raw text is measured by one linear
  scan before the TOML parser sees it: its size in bytes, the depth of tables, arrays and
  inline tables (a table header ``[a.b.c]`` and a dotted key ``a.b.c = 1`` count a level per
  part, as the parsed data nests), the length of every key and the number of keys. The
  parser's cost grows with the square of a dotted key's depth (a 60 KB key 30,000 parts deep
  took over a minute and 3.5 GiB); the scan refuses it at the first part over the limit.
- **TOML by a parser, never evaluated**, with its nesting depth bounded again on the parsed
  data, and the name of the file in every message.

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

from dispersion.errors import InputError

__all__ = ["MAX_KEY_CHARS", "MAX_KEYS", "printable", "read_text", "check_toml", "load_toml",
           "nesting_depth"]

#: Longest key (characters, quotes excluded) of an untrusted TOML file: the toolkit's keys
#: have at most 20; names of claims and rules are values, not keys.
MAX_KEY_CHARS = 256
#: Most keys and table headers of an untrusted TOML file (a claims file of a thousand claims
#: has about 10,000); callers may set their own.
MAX_KEYS = 50_000

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


# Tokens of TOML that may hold any character: strings (a bracket or a '#' inside one is text).
# Written as unrolled loops ("[^"\\]*(?:\\.[^"\\]*)*"), so a string as long as the file is
# matched without a backtracking entry per character.
_BASIC = re.compile(r'"[^"\\\n]*(?:\\[^\n][^"\\\n]*)*"')
_LITERAL = re.compile(r"'[^'\n]*'")
_ML_BASIC = re.compile(r'"""[^"\\]*(?:(?:\\[\s\S]|"(?!""))[^"\\]*)*"{3,5}')
_ML_LITERAL = re.compile(r"'''[^']*(?:'(?!'')[^']*)*'{3,5}")
_STRINGS = ((_ML_BASIC, '"""'), (_ML_LITERAL, "'''"), (_BASIC, '"'), (_LITERAL, "'"))
_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")
# numbers, booleans, dates and times (a date and a time may be joined by one space)
_SCALAR = re.compile(r"[^\s,\]}#\[{=\"']+(?: [0-9][^\s,\]}#\[{=\"']*)?")
_BLANKS = re.compile(r"[ \t]*")
_GAPS = re.compile(r"[ \t\r\n]*(?:#[^\n]*[ \t\r\n]*)*")
# the common lines and items, read in one match: ``key = 1``, ``"k" = 'v'``, ``[table]``:
# one key (bare or quoted on one line) and a number or a one-line string
_KEY_PART = r"""([A-Za-z0-9_-]+|"[^"\\\n]*(?:\\[^\n][^"\\\n]*)*"|'[^'\n]*')"""
_ONE_LINE_VALUE = (r"""(?:"[^"\\\n]*(?:\\[^\n][^"\\\n]*)*"|'[^'\n]*'|""" + _SCALAR.pattern
                   + ")")
_SIMPLE_LINE = re.compile(_KEY_PART + r"[ \t]*=[ \t]*" + _ONE_LINE_VALUE
                          + r"[ \t]*(?:#[^\n]*)?(?=\r?\n|\Z)")
_SIMPLE_HEADER = re.compile(r"\[[ \t]*" + _KEY_PART + r"[ \t]*\][ \t]*(?:#[^\n]*)?(?=\r?\n|\Z)")
_SIMPLE_ITEM = re.compile(_KEY_PART + r"[ \t]*=[ \t]*" + _ONE_LINE_VALUE + r"[ \t]*(?=[,}])")


def _key_chars(key: str) -> int:
    """Characters of a key as the simple patterns caught it (quotes excluded)."""
    return len(key) - 2 if key[0] in "\"'" else len(key)


class _TomlShape:
    """One linear scan of TOML text measuring what the parser would build (see
    :func:`check_toml`); refuses at the first excess, so its stack never passes the limit."""

    def __init__(self, text: str, where: str, max_depth: int, max_key_chars: int,
                 max_keys: int):
        self.t, self.i, self.n, self.line = text, 0, len(text), 1
        self.where, self.max_depth = where, max_depth
        self.max_key_chars, self.max_keys, self.keys = max_key_chars, max_keys, 0
        self.arrays: set[tuple[str, ...]] = set()  # paths of [[...]]: a list, then a table

    def fail(self, message: str) -> None:
        raise InputError(f"{self.where}: {message}")

    def too_deep(self) -> None:
        self.fail(f"tables and arrays nested more than {self.max_depth} levels deep (line "
                  f"{self.line}; a table header or dotted key counts a level per part)")

    def malformed(self, what: str) -> None:
        rest = self.t[self.i:self.i + 20].split("\n")[0].rstrip("\r")
        found = ("the end of the text" if self.i >= self.n else repr(printable(rest, 30))
                 if rest else "the end of the line")
        column = self.i - self.t.rfind("\n", 0, self.i)
        self.fail(f"malformed TOML: {what}, found {found} (at line {self.line}, column "
                  f"{column})")

    def peek(self) -> str:
        return self.t[self.i] if self.i < self.n else ""

    def blanks(self) -> None:
        """Spaces and tabs."""
        self.i = _BLANKS.match(self.t, self.i).end()

    def gaps(self) -> None:
        """Spaces, newlines and comments (between lines, and inside arrays)."""
        end = _GAPS.match(self.t, self.i).end()
        self.line += self.t.count("\n", self.i, end)
        self.i = end

    def end_of_line(self) -> None:
        self.blanks()
        if self.peek() == "#":
            end = self.t.find("\n", self.i)
            self.i = self.n if end < 0 else end
        if self.peek() == "\r":
            self.i += 1
        if self.peek() not in ("\n", ""):
            self.malformed("a new line was expected")

    def count(self) -> None:
        self.keys += 1
        if self.keys > self.max_keys:
            self.fail(f"more than {self.max_keys} keys and table headers (the limit)")

    def string(self) -> str:
        """Skip one string; return what it holds (escapes as written)."""
        for pattern, quote in _STRINGS:
            if self.t.startswith(quote, self.i):
                m = pattern.match(self.t, self.i)
                if m is None:
                    self.malformed("an unterminated string")
                self.line += self.t.count("\n", m.start(), m.end())
                self.i = m.end()
                return m.group()[len(quote):-len(quote)]
        self.malformed("a string was expected")

    def key(self, level: int, extra: int) -> list[str]:
        """Skip a dotted key; return its parts. Part j of n makes a table at ``level + j``
        (the last one too, and its list, in a header: ``extra`` 1 or 2)."""
        parts = []
        while True:
            self.blanks()
            if self.peek() in ("\"", "'"):
                if self.t.startswith(('"""', "'''"), self.i):
                    self.malformed("a key on one line was expected")
                name = self.string()
            else:
                m = _BARE_KEY.match(self.t, self.i)
                if m is None:
                    self.malformed("a key was expected")
                name = m.group()
                self.i = m.end()
            if len(name) > self.max_key_chars:
                self.fail(f"a key of {len(name)} characters at line {self.line}, more than "
                          f"the limit of {self.max_key_chars}")
            parts.append(name)
            if level + len(parts) - 1 + extra > self.max_depth:
                self.too_deep()
            self.blanks()
            if self.peek() != ".":
                return parts
            self.i += 1

    def value(self, level: int) -> None:
        """Skip one value, which sits at ``level`` if it is an array or an inline table."""
        ch = self.peek()
        if ch == "[" or ch == "{":
            if level > self.max_depth:
                self.too_deep()
            self.i += 1
            if ch == "[":
                self.array(level)
            else:
                self.inline_table(level)
            self.i += 1
        elif ch == "\"" or ch == "'":
            self.string()
        else:
            m = _SCALAR.match(self.t, self.i)
            if m is None:
                self.malformed("a value was expected")
            self.i = m.end()

    def array(self, level: int) -> None:
        while True:
            self.gaps()
            if self.peek() == "]":
                return
            self.value(level + 1)
            self.gaps()
            if self.peek() == ",":
                self.i += 1
            elif self.peek() != "]":
                self.malformed("',' or ']' was expected")

    def inline_table(self, level: int) -> None:
        self.blanks()
        while self.peek() != "}":
            simple = _SIMPLE_ITEM.match(self.t, self.i)
            if simple is not None and _key_chars(simple.group(1)) <= self.max_key_chars:
                self.count()  # one bare key and a number: nothing deeper
                self.i = simple.end()
            else:
                parts = self.key(level, 0)
                self.count()
                self.blanks()
                if self.peek() != "=":
                    self.malformed("'=' was expected")
                self.i += 1
                self.blanks()
                self.value(level + len(parts))
                self.blanks()
            if self.peek() == ",":
                self.i += 1
                self.blanks()
            elif self.peek() != "}":
                self.malformed("',' or '}' was expected")

    def scan(self) -> None:
        base = 0  # the level of the table the lines are in
        while True:
            self.gaps()
            if self.i >= self.n:
                return
            self.count()
            header = self.t[self.i] == "["
            simple = (_SIMPLE_HEADER if header else _SIMPLE_LINE).match(self.t, self.i)
            if simple is not None and _key_chars(simple.group(1)) <= self.max_key_chars:
                # one key: its table at level 1, or a number or a string in the current table
                base = 1 if header else base
                if base > self.max_depth:
                    self.too_deep()
                self.i = simple.end()
                continue
            if header:
                double = self.t.startswith("[[", self.i)
                self.i += 2 if double else 1
                parts = self.key(0, 2 if double else 1)
                close = "]]" if double else "]"
                if not self.t.startswith(close, self.i):
                    self.malformed("the end of a table header was expected")
                self.i += len(close)
                path = tuple(parts)
                # a table inside an element of [[...]] sits one level deeper
                base = len(path) + double + sum(path[:j] in self.arrays
                                                for j in range(1, len(path)))
                if base > self.max_depth:
                    self.too_deep()
                if double:
                    self.arrays.add(path)
            else:
                parts = self.key(base, 0)
                self.blanks()
                if self.peek() != "=":
                    self.malformed("'=' was expected")
                self.i += 1
                self.blanks()
                self.value(base + len(parts))
            self.end_of_line()


def check_toml(text: str, where: str, max_bytes: int, max_depth: int, *,
               max_key_chars: int = MAX_KEY_CHARS, max_keys: int = MAX_KEYS) -> None:
    """Refuse TOML ``text`` before it is parsed if it is larger than ``max_bytes`` (UTF-8),
    nests tables, arrays or inline tables deeper than ``max_depth`` (the top level is 0; a
    table header or a dotted key counts a level per part, ``[[a]]`` two: the list and its
    table), has a key longer than ``max_key_chars`` or more than ``max_keys`` keys and table
    headers. One linear scan, in which strings and comments are text; ``where`` begins each
    message (the kind of file and its name).

    >>> check_toml("x" + ".y" * 30000 + " = 1", "mass rule file r.toml", 2**16, 2)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: mass rule file r.toml: tables and arrays nested more than 2 levels deep (line 1; a table header or dotted key counts a level per part)
    >>> check_toml('a = "[[[[[[[[" # [[[[', "f.toml", 100, 1)  # brackets in text are text
    """
    size = len(text) if len(text) > max_bytes else len(text.encode("utf-8", "surrogatepass"))
    if size > max_bytes:
        raise InputError(f"{where}: {size} {'characters' if size == len(text) else 'bytes'}, "
                         f"more than the limit of {max_bytes} bytes")
    _TomlShape(text, where, max_depth, max_key_chars, max_keys).scan()


def load_toml(text: str, file: str, what: str, max_depth: int, max_bytes: int, *,
              max_keys: int = MAX_KEYS) -> dict:
    """The TOML ``text`` of ``file`` as a dict, nested at most ``max_depth`` levels, of at most
    ``max_bytes`` bytes: bounded on the raw text (:func:`check_toml`) before it is parsed.

    >>> load_toml('a = [[1]]', "r.toml", "mass rule file", 1, 100)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: mass rule file r.toml: tables and arrays nested more than 1 levels deep (line 1; a table header or dotted key counts a level per part)
    """
    try:  # Python >= 3.11
        import tomllib
    except ModuleNotFoundError:  # pragma: no cover - Python 3.10
        import tomli as tomllib

    shown = printable(file)
    check_toml(text, f"{what} {shown}", max_bytes, max_depth, max_keys=max_keys)
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

