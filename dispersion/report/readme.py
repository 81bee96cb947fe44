"""Generated blocks of the README: numbers quoted from ``reports/*.json``, never typed in.

A block in a Markdown file

.. code-block:: markdown

    <!-- generated from reports/ring.json by `dispersion reproduce --readme README.md` -->
    ...
    <!-- end generated -->

is replaced by ``summary(data)`` of the report section named in its opening line
(:mod:`dispersion.report`), where ``data`` is the ``"result"`` of that section's JSON. A
section that has nothing to say in the README defines no ``summary``. The test suite checks
that the committed README equals its regeneration from the committed reports.

>>> text = "a\\n<!-- generated from reports/demo.json by x -->\\nold\\n<!-- end generated -->\\nb"
>>> [m.group("section") for m in BLOCK.finditer(text)]
['demo']
"""
from __future__ import annotations

import re
from pathlib import Path

from dispersion import results
from dispersion.errors import DispersionError

__all__ = ["BLOCK", "render_readme", "update_readme"]

BLOCK = re.compile(
    r"(?P<open><!-- generated from reports/(?P<section>\w+)\.json by [^\n]*-->\n)"
    r"(?P<body>.*?)"
    r"(?P<close><!-- end generated -->)",
    re.S,
)


def render_readme(text: str, reports: Path) -> str:
    """``text`` with every generated block rendered from ``reports/<section>.json``."""
    from dispersion.report import section_module

    def block(match: re.Match) -> str:
        name = match.group("section")
        path = Path(reports) / f"{name}.json"
        if not path.is_file():
            raise DispersionError(f"README block needs {path}, which does not exist")
        summary = getattr(section_module(name), "summary", None)
        if summary is None:
            raise DispersionError(f"report section {name!r} defines no summary() for the README")
        body = summary(results.load(path)["result"]).strip("\n")
        return f"{match.group('open')}{body}\n{match.group('close')}"

    return BLOCK.sub(block, text)


def update_readme(path: Path, reports: Path) -> bool:
    """Rewrite the generated blocks of the file ``path`` in place; True if it changed."""
    from dispersion.io import write_text

    path = Path(path)
    old = path.read_text(encoding="utf-8")
    new = render_readme(old, reports)
    if new != old:
        write_text(path, new)
    return new != old
