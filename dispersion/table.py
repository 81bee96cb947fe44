"""Tables as text: the one Markdown and plain-text table writer of the toolkit.

Every report page, the errata table and ``dispersion verify`` write their tables here, so a
cell is escaped the same way everywhere (``|`` in Markdown, control characters always).

>>> print(markdown_table(("a", "b"), [(1, "x|y")]))
| a | b |
|---|---|
| 1 | x\\|y |
>>> print(text_table(("name", "n"), [("S0", 2), ("A0", 10)]))
name  n
----  --
S0    2
A0    10
"""
from __future__ import annotations

import re
from collections.abc import Iterable, Sequence

__all__ = ["clean", "markdown_table", "text_table"]

_CONTROL = re.compile(r"\x1b\[[0-?]*[ -/]*[@-~]|[\x00-\x08\x0b-\x1f\x7f-\x9f]")


def clean(text) -> str:
    """``text`` as a string without terminal escape sequences or control characters
    (tabs and newlines become spaces)."""
    return _CONTROL.sub("", str(text).replace("\t", " ").replace("\n", " "))


def markdown_table(header: Sequence, rows: Iterable[Sequence]) -> str:
    """A GitHub-flavoured Markdown table; ``|`` in cells is escaped."""
    cell = lambda v: clean(v).replace("|", "\\|")
    lines = ["| " + " | ".join(cell(h) for h in header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(cell(v) for v in row) + " |" for row in rows]
    return "\n".join(lines)


def text_table(header: Sequence, rows: Iterable[Sequence], sep: str = "  ") -> str:
    """A plain-text table with columns padded to their widest cell."""
    body = [[clean(v) for v in row] for row in rows]
    head = [clean(h) for h in header]
    widths = [max(len(x) for x in col) for col in zip(head, *body)]
    fmt = lambda row: sep.join(c.ljust(w) for c, w in zip(row, widths)).rstrip()
    return "\n".join([fmt(head), fmt(["-" * w for w in widths])] + [fmt(r) for r in body])
