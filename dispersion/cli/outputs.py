"""What the commands write: a figure path checked before any work, text to a file or stdout,
and CSV tables that start with ``#`` lines naming their inputs.

One helper per job, shared by ``branches`` (kappa and frequency axes) and ``impact``, so a
figure path is refused with the same one-line message everywhere and every CSV cell of an
undefined value is written the same way (empty, never ``nan`` or ``inf``).

>>> print(csv_text([{"kappa": 0.5, "c_g/c_T": float("nan")}], ["# nu: 0.3"]), end="")
# nu: 0.3
kappa,c_g/c_T
0.5,
"""
from __future__ import annotations

import csv
import io
import math
import sys

from dispersion.errors import InputError

__all__ = ["FIGURE_SUFFIXES", "EMPTY_NOTE", "check_figure", "cell", "csv_text", "emit"]

#: File endings a ``--figure`` may have (matplotlib writes each of them without extras).
FIGURE_SUFFIXES = (".png", ".pdf", ".svg")
#: The ``#`` line every CSV of the commands carries about empty cells.
EMPTY_NOTE = "empty cell: not defined (no value is written as nan or inf)"


def check_figure(path: str, command: str, option: str = "--figure") -> None:
    """Refuse, before any work, a figure path that cannot receive a figure of ``command``:
    a wrong ending, ``-``, a folder, an unwritable place, or no matplotlib installed.

    >>> check_figure("out.txt", "impact")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: --figure must name a file ending in one of .png, .pdf, .svg, got 'out.txt'
    """
    from dispersion.io import check_output_file
    from dispersion.plotting import require_matplotlib

    if not str(path).lower().endswith(FIGURE_SUFFIXES):
        raise InputError(f"{option} must name a file ending in one of "
                         f"{', '.join(FIGURE_SUFFIXES)}, got {path!r}")
    check_output_file(path, option=option, allow_stdout=False, suffixes=FIGURE_SUFFIXES)
    require_matplotlib(f"{command} {option}")


def emit(path: str, text: str) -> None:
    """Write ``text`` to ``path`` atomically, or to standard output for ``-``."""
    if path == "-":
        sys.stdout.write(text)
    else:
        from dispersion.io import write_text

        write_text(path, text)


def cell(value) -> str:
    """A CSV cell: floats by ``repr`` (round-trip exact), undefined values empty."""
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else ""
    return "" if value is None else str(value)


def csv_text(rows: list[dict], header: list[str]) -> str:
    """``header`` lines (each a ``# ...`` line), then the rows as CSV with a column line;
    no rows: the header lines alone."""
    buf = io.StringIO()
    for line in header:
        buf.write(line + "\n")
    if rows:
        w = csv.DictWriter(buf, fieldnames=list(rows[0]), lineterminator="\n")
        w.writeheader()
        for row in rows:
            w.writerow({k: cell(v) for k, v in row.items()})
    return buf.getvalue()
