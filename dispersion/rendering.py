"""The result-rendering protocol: every result a user can get renders itself, in every format.

A result is a frozen dataclass that carries the value it was computed from and mixes in
:class:`Rendered`. It states four things, each rendered from its own fields (never typed):

- ``title() -> str``: one line naming what was computed and from what;
- ``header_lines() -> list[str]``: the inputs that apply, in words with units
  (``material: steel (c_L 5960 m/s, c_T 3235 m/s, rho 7850 kg/m^3)``), no Python reprs;
- ``columns() -> tuple[str, ...]`` (names with units, ``c_p [m/s]``) and
  ``rows() -> list[dict]`` (one dict per row, keyed by the columns);
- ``failures``: what could not be certified or computed (a tuple of lines; a result may also
  hold tuples, dicts or a method returning them: :func:`failure_lines` reads every form).

From these :class:`Rendered` draws every format: :meth:`~Rendered.to_text` (an aligned table
rounded to 7 significant digits, the failures as a footer), :meth:`~Rendered.to_csv` (``#``
lines with the title, the inputs and every failure, then exact floats), :meth:`~Rendered.to_json`
(strict JSON text: ``null``, never NaN; keys ``title``, ``header``, ``columns``, ``rows``,
``failures``; the same data as Python values: :meth:`~Rendered.to_dict`),
:meth:`~Rendered.to_markdown`, :meth:`~Rendered.to_dataframe` (pandas, imported
when called), a short ``repr`` and ``_repr_html_`` for notebooks. :data:`FORMATS` is the one
``--format`` vocabulary of the command line; :func:`render` picks a format by name.

>>> from dataclasses import dataclass
>>> @dataclass(frozen=True, repr=False)
... class Speeds(Rendered):
...     material: str
...     values: tuple
...     failures: tuple = ()
...     def title(self):
...         return f"bulk speeds of {self.material}"
...     def header_lines(self):
...         return [f"material: {self.material}"]
...     def columns(self):
...         return ("wave", "c [m/s]")
...     def rows(self):
...         return [{"wave": w, "c [m/s]": c} for w, c in self.values]
>>> s = Speeds("steel", (("L", 5960.0), ("T", float("nan"))), ("c_T: not measured",))
>>> s
<Speeds: bulk speeds of steel (2 rows, 1 failure)>
>>> print(s.to_text())
bulk speeds of steel
<BLANKLINE>
wave  c [m/s]
----  -------
L        5960
T
<BLANKLINE>
material: steel
<BLANKLINE>
failure: c_T: not measured
>>> print(s.to_csv(version=None), end="")
# bulk speeds of steel
# material: steel
# failure: c_T: not measured
# empty cell: not defined (no value is written as nan or inf)
wave,c [m/s]
L,5960.0
T,
>>> s.to_dict()["rows"][1]
{'wave': 'T', 'c [m/s]': None}
>>> s.to_json().splitlines()[0:2]      # text, like every other to_ method
['{', ' "title": "bulk speeds of steel",']
"""
from __future__ import annotations

import csv
import html
import io
import math
from collections.abc import Mapping

__all__ = ["FORMATS", "TEXT_DIGITS", "EMPTY_NOTE", "DATAFRAME_EXTRA", "Rendered",
           "failure_lines", "render", "require_pandas", "text_cell", "csv_cell"]

#: The ``--format`` vocabulary of every command (a command refuses, in one line, a format its
#: result has no form for; ``series`` adds ``latex``).
FORMATS = ("text", "csv", "json", "markdown")
#: Significant digits of a number in a text or Markdown table (CSV and JSON keep every digit).
TEXT_DIGITS = 7
#: The ``#`` line every CSV carries about empty cells.
EMPTY_NOTE = "empty cell: not defined (no value is written as nan or inf)"
#: What to install for ``to_dataframe()``.
DATAFRAME_EXTRA = 'pip install "dispersion-iga[dataframe]"'
#: Failures listed in a text footer before the rest are counted (every one is in CSV and JSON).
TEXT_FAILURES = 10


def _clean(value) -> str:
    """Text without terminal escape sequences or control characters: a cell may come from a
    stranger's file (a claim's name) and never reaches a terminal as an instruction."""
    from dispersion.table import clean

    return clean(value)


def text_cell(value, digits: int = TEXT_DIGITS) -> str:
    """A table cell for people: numbers rounded to ``digits`` significant digits, undefined
    values (None, NaN, inf) empty.

    >>> text_cell(5414.6123456789), text_cell(1e-20), text_cell(float("nan")), text_cell(3)
    ('5414.612', '1e-20', '', '3')
    """
    if isinstance(value, bool) or value is None:
        return "" if value is None else str(value)
    if isinstance(value, float) or type(value).__module__ == "numpy":
        try:
            value = float(value)
        except (TypeError, ValueError):
            return _clean(value)
        return f"{value:.{digits}g}" if math.isfinite(value) else ""
    return _clean(value)


def csv_cell(value) -> str:
    """A CSV cell: floats by ``repr`` (they read back exactly), undefined values empty."""
    if isinstance(value, bool) or value is None:
        return "" if value is None else str(value)
    if isinstance(value, float) or type(value).__module__ == "numpy":
        try:
            value = float(value)
        except (TypeError, ValueError):
            return _clean(value)
        return repr(value) if math.isfinite(value) else ""
    return _clean(value)


def _failure_text(item) -> str:
    if isinstance(item, str):
        return item
    if isinstance(item, Mapping):
        return ", ".join(f"{k} {text_cell(v, 10)}" if not isinstance(v, str) else f"{k}: {v}"
                         for k, v in item.items())
    if isinstance(item, (tuple, list)):
        if len(item) == 3 and isinstance(item[0], str) and isinstance(item[2], str):
            what, where, why = item  # (quantity or branch, kappa, reason) of the wave solvers
            return f"{what} at kappa = {text_cell(where, 10)}: {why}"
        return "; ".join(_failure_text(x) for x in item)
    return str(item)


def failure_lines(result) -> list[str]:
    """The failures of ``result`` as lines of text, whatever form it holds them in (a tuple of
    lines, of ``(what, kappa, why)`` tuples, of dicts, or a method returning them).

    >>> class R:
    ...     failures = [("omega", 0.5, "not certified"), {"f [kHz]": 200.0, "reason": "count"}]
    >>> failure_lines(R())
    ['omega at kappa = 0.5: not certified', 'f [kHz] 200, reason: count']
    """
    items = getattr(result, "failures", ())
    if callable(items):
        items = items()
    return [_failure_text(x) for x in (items or ())]


def require_pandas():
    """pandas, or :class:`~dispersion.errors.InputError` naming the ``dataframe`` extra."""
    try:
        import pandas
    except ImportError:
        from dispersion.errors import InputError

        raise InputError(f"to_dataframe() needs pandas, which is not installed: "
                         f"{DATAFRAME_EXTRA}") from None
    return pandas


def _version() -> str:
    from dispersion.results import package_versions

    return package_versions(("dispersion-iga",))["dispersion-iga"]


class Rendered:
    """Mix-in of a result: every format drawn from ``title``, ``header_lines``, ``columns``,
    ``rows`` and ``failures`` (see the module). Declare the dataclass with ``repr=False`` so
    that the short :meth:`__repr__` here is kept."""

    failures: tuple = ()

    def title(self) -> str:  # pragma: no cover - every result states its own
        raise NotImplementedError

    def header_lines(self) -> list[str]:
        return []

    def rows(self) -> list[dict]:  # pragma: no cover - every result states its own
        raise NotImplementedError

    def columns(self) -> tuple[str, ...]:
        rows = self.rows()
        return tuple(rows[0]) if rows else ()

    def text_columns(self) -> tuple[str, ...]:
        """The columns a person reads first (text and Markdown tables); every column is in
        CSV, JSON and the DataFrame."""
        return self.columns()

    # ------------------------------------------------------------------ formats

    def to_text(self, digits: int = TEXT_DIGITS) -> str:
        """Title, an aligned table of :meth:`text_columns` (numbers right-aligned, ``digits``
        significant digits, undefined cells empty), the inputs and the failures below it."""
        lines = [self.title()]
        table = self._text_table(digits)
        if table:
            lines += ["", table]
        if self.header_lines():
            lines += ["", *self.header_lines()]
        fails = failure_lines(self)
        if fails:
            lines.append("")
            lines += [f"failure: {f}" for f in fails[:TEXT_FAILURES]]
            if len(fails) > TEXT_FAILURES:
                lines.append(f"... {len(fails) - TEXT_FAILURES} more failures (all of them are "
                             "in the CSV and JSON forms)")
        return "\n".join(lines)

    def _text_table(self, digits: int) -> str:
        from dispersion.table import clean

        cols = self.text_columns()
        rows = self.rows()
        if not cols or not rows:
            return ""
        body = [[clean(text_cell(row.get(c), digits)) for c in cols] for row in rows]
        numeric = [all(_numeric(row.get(c)) for row in rows) for c in cols]
        widths = [max(len(c), *(len(r[j]) for r in body)) for j, c in enumerate(cols)]

        def line(cells):
            return "  ".join(c.rjust(w) if num else c.ljust(w)
                             for c, w, num in zip(cells, widths, numeric)).rstrip()
        return "\n".join([line(cols), line(["-" * w for w in widths])]
                         + [line(r) for r in body])

    def to_csv(self, version: str | None = "installed") -> str:
        """``#`` lines (title, inputs, failures, the empty-cell rule, the package version),
        then the columns and rows with every digit (floats by ``repr``)."""
        from dispersion.table import clean

        buf = io.StringIO()
        for line in [self.title(), *self.header_lines()]:
            buf.write(f"# {clean(line)}\n")
        for f in failure_lines(self):
            buf.write(f"# failure: {clean(f)}\n")
        buf.write(f"# {EMPTY_NOTE}\n")
        if version is not None:
            buf.write(f"# dispersion-iga: {_version() if version == 'installed' else version}\n")
        cols = self.columns()
        if cols:
            w = csv.writer(buf, lineterminator="\n")
            w.writerow(cols)
            for row in self.rows():
                w.writerow([csv_cell(row.get(c)) for c in cols])
        return buf.getvalue()

    def json_extra(self) -> dict:
        """More keys of :meth:`to_dict` (cut-offs, ZGV points, ...); none by default."""
        return {}

    def to_json(self) -> str:
        """The result as strict JSON text (what ``--format json`` prints): :meth:`to_dict`
        dumped, ``null`` for every non-finite number, never NaN."""
        import json

        return json.dumps(self.to_dict(), indent=1, allow_nan=False) + "\n"

    def to_dict(self) -> dict:
        """Strict-JSON data: ``title``, ``header``, ``columns``, ``rows``, ``failures``, the
        package version and the result's own extra keys (non-finite numbers become ``None``)."""
        from dispersion.results import jsonable

        cols = self.columns()
        out = {"title": self.title(), "header": list(self.header_lines()),
               "columns": list(cols),
               "rows": [{c: row.get(c) for c in cols} for row in self.rows()],
               "failures": failure_lines(self), "dispersion-iga": _version()}
        out.update(self.json_extra())
        return jsonable(out)

    def to_markdown(self, digits: int = TEXT_DIGITS) -> str:
        """The title in bold, the inputs as a list, a Markdown table and the failures."""
        from dispersion.table import markdown_table

        parts = [f"**{self.title()}**"]
        if self.header_lines():
            parts.append("\n".join(f"- {line}" for line in self.header_lines()))
        cols = self.text_columns()
        if cols:
            parts.append(markdown_table(cols, [[text_cell(r.get(c), digits) for c in cols]
                                               for r in self.rows()]))
        fails = failure_lines(self)
        if fails:
            parts.append("\n".join(f"- failure: {f}" for f in fails))
        return "\n\n".join(parts)

    def to_dataframe(self):
        """The rows as a pandas DataFrame (the ``dataframe`` extra); ``attrs`` hold the title,
        the header lines and the failures."""
        pd = require_pandas()
        frame = pd.DataFrame(self.rows(), columns=list(self.columns()))
        frame.attrs.update(title=self.title(), header=list(self.header_lines()),
                           failures=failure_lines(self))
        return frame

    def __repr__(self) -> str:
        n, f = len(self.rows()), len(failure_lines(self))
        fails = f", {f} failure{'s' if f != 1 else ''}" if f else ""
        return f"<{type(self).__name__}: {self.title()} ({n} row{'s' if n != 1 else ''}{fails})>"

    def __str__(self) -> str:
        return self.to_text()

    def _repr_html_(self, max_rows: int = 60) -> str:
        esc = html.escape
        cols = self.columns()
        rows = self.rows()
        head = "".join(f"<th>{esc(c)}</th>" for c in cols)
        body = "".join("<tr>" + "".join(f"<td>{esc(text_cell(r.get(c)))}</td>" for c in cols)
                       + "</tr>" for r in rows[:max_rows])
        more = (f"<p>... {len(rows) - max_rows} more rows (<code>to_dataframe()</code>, "
                "<code>to_csv()</code>)</p>" if len(rows) > max_rows else "")
        items = "".join(f"<li>{esc(x)}</li>" for x in self.header_lines())
        fails = "".join(f"<li>failure: {esc(x)}</li>" for x in failure_lines(self))
        return (f"<p><b>{esc(self.title())}</b></p>"
                + (f"<ul>{items}</ul>" if items else "")
                + (f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"
                   if cols else "") + more + (f"<ul>{fails}</ul>" if fails else ""))


def _numeric(value) -> bool:
    return value is None or (not isinstance(value, (str, bool)) and (
        isinstance(value, (int, float)) or type(value).__module__ == "numpy"))


def render(result, fmt: str) -> str:
    """``result`` in the format named ``fmt`` (one of :data:`FORMATS`), ending in a newline.

    >>> from dispersion.rendering import render
    >>> render(object(), "yaml")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: --format must be one of text, csv, json, markdown, got 'yaml'
    """
    from dispersion.errors import InputError

    if fmt == "latex" and hasattr(result, "to_latex"):  # the results that have a LaTeX form
        return result.to_latex() + "\n"
    if fmt not in FORMATS:
        raise InputError(f"--format must be one of {', '.join(FORMATS)}, got {fmt!r}")
    if fmt == "json":
        return result.to_json()
    text = {"text": result.to_text, "csv": result.to_csv,
            "markdown": result.to_markdown}[fmt]()
    return text if text.endswith("\n") else text + "\n"
