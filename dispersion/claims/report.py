"""Verified claims presented: text for a terminal, a Markdown table, JUnit XML for CI.

Claims files are written by strangers, so every text taken from one (names, sources, the
claim as written, file names) is made inert before it is shown: :func:`plain` removes
terminal control sequences and escapes other control and format characters, and
:func:`junit_xml` writes only characters XML 1.0 allows. Expressions are shown whole,
wrapped to the width, never cut.
"""
from __future__ import annotations

import re
import shutil
import textwrap
import unicodedata
from pathlib import Path
from xml.etree import ElementTree as ET

import sympy

from dispersion.errors import InputError

__all__ = ["plain", "xml_text", "readable", "format_results", "junit_xml", "FORMATS"]

FORMATS = ("text", "markdown")
_FIELDS = ("name", "source", "model", "printed", "derived", "status", "difference")
# CSI (ESC [ ... final), OSC (ESC ] ... BEL or ST), and two-character escapes (ESC x)
_ESCAPE = re.compile(r"\x1b\[[0-?]*[ -/]*[@-~]|\x1b\][^\x07\x1b]*(?:\x07|\x1b\\)?"
                     r"|\x9b[0-?]*[ -/]*[@-~]|\x1b[@-_]?")
_XML_BAD = re.compile("[^\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


#: Largest expression :func:`readable` factors (terms of numerator and denominator, bits of
#: the largest coefficient). Factoring multivariate input with long coefficients takes
#: minutes ((10^60 + nu)^18 against a series in nu and r: 45 s); below these sizes it takes
#: well under a second, and the paper's coefficients (at most 10 terms of 60 bits) pass.
READABLE_TERMS = 40
READABLE_BITS = 512


def readable(expr):
    """``expr`` factored for display when factoring is cheap, else cancelled (never slow).

    >>> nu = sympy.Symbol("nu")
    >>> readable(2*nu**2 - 2)
    2*(nu - 1)*(nu + 1)
    """
    expr = sympy.cancel(expr)
    if expr.is_number:
        return expr
    gens = sorted(expr.free_symbols, key=str)
    num, den = sympy.fraction(expr)
    try:
        polys = [sympy.Poly(part, *gens) for part in (num, den)]
    except sympy.PolynomialError:  # roots, Order terms: shown as they are
        return expr
    terms = sum(len(p.terms()) for p in polys)
    bits = max((max(abs(c.p).bit_length(), c.q.bit_length()) if c.is_Rational
                else READABLE_BITS + 1) for p in polys for c in p.coeffs())
    return sympy.factor(expr) if terms <= READABLE_TERMS and bits <= READABLE_BITS else expr


def _escape(ch: str) -> str:
    code = ord(ch)
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def plain(text, *, newlines: bool = False) -> str:
    """``text`` safe for a terminal: escape sequences removed, control characters escaped.

    Tabs become spaces; newlines are kept if ``newlines`` else become spaces. Unicode format
    characters (bidirectional overrides, zero-width joiners) are escaped like controls.

    >>> plain("a\\x1b[31mred\\x1b[0m\\x07b")
    'ared\\\\x07b'
    """
    text = _ESCAPE.sub("", str(text)).replace("\t", " ")
    if not newlines:
        text = text.replace("\r\n", " ").replace("\n", " ").replace("\r", " ")
    keep = "\n" if newlines else ""
    return "".join(_escape(ch) if ch not in keep and unicodedata.category(ch) in ("Cc", "Cf")
                   else ch for ch in text)


def xml_text(text) -> str:
    """``text`` with every character XML 1.0 forbids written as a visible escape."""
    return _XML_BAD.sub(lambda m: _escape(m.group()), str(text))


def _row(r) -> dict:
    r = r if isinstance(r, dict) else {f: getattr(r, f) for f in _FIELDS}
    return {f: str(r.get(f) or "") for f in _FIELDS}


def _width(width) -> int:
    if width is None:
        width = shutil.get_terminal_size((100, 24)).columns
    if isinstance(width, bool) or not isinstance(width, int) or width < 1:
        raise InputError(f"width must be a positive integer, got {width!r}")
    return max(width, 40)


def format_results(results, fmt: str = "text", width: int | None = None) -> str:
    """Results (objects or their JSON dictionaries) as ``text`` or a ``markdown`` table.

    Text is one block per claim: its name, source and status, then the model, the printed
    and the derived form and the difference, each wrapped to ``width`` columns (default:
    the terminal's) and never shortened.
    """
    if fmt not in FORMATS:
        raise InputError(f"format must be one of {', '.join(FORMATS)}, got {fmt!r}")
    rows = [_row(r) for r in results]
    if fmt == "markdown":
        from dispersion.table import markdown_table

        keys = ("name", "source", "printed", "derived", "status", "difference")
        head = ("claim", *keys[1:])
        return markdown_table(head, [[plain(row[k]) for k in keys] for row in rows])
    width = _width(width)
    blocks = []
    for row in rows:
        source = f" [{plain(row['source'])}]" if row["source"] else ""
        lines = textwrap.wrap(f"{plain(row['name'])}{source}: {plain(row['status'])}", width,
                              subsequent_indent="    ", break_on_hyphens=False)
        for key in ("model", "printed", "derived", "difference"):
            if row[key]:
                lines += textwrap.wrap(plain(row[key]), width, break_on_hyphens=False,
                                       initial_indent=f"  {key + ':':<12}",
                                       subsequent_indent=" " * 14)
        blocks.append("\n".join(lines))
    return "\n".join(blocks)


def junit_xml(verification) -> str:
    """JUnit XML: one test suite per file, one test case per claim (failure = not as expected).

    Well-formed for any claim name: characters XML forbids are written as escapes.

    >>> from dispersion.claims.verify import Verification
    >>> v = Verification(("f.toml",), (), 0.0)
    >>> junit_xml(v).splitlines()[1]
    '<testsuites name="dispersion verify" tests="0" failures="0" errors="0" time="0.000">'
    """
    res = verification.results
    x = xml_text
    root = ET.Element("testsuites", {
        "name": "dispersion verify", "tests": str(len(res)),
        "failures": str(sum(not r.passed and r.status != "error" for r in res)),
        "errors": str(sum(r.status == "error" for r in res)),
        "time": f"{verification.seconds:.3f}"})
    for file in verification.files:
        mine = [r for r in res if r.file == file]
        suite = ET.SubElement(root, "testsuite", {
            "name": x(file), "tests": str(len(mine)),
            "failures": str(sum(not r.passed and r.status != "error" for r in mine)),
            "errors": str(sum(r.status == "error" for r in mine))})
        for r in mine:
            case = ET.SubElement(suite, "testcase", {
                "classname": x(Path(file).stem), "name": x(r.name), "file": x(file),
                "line": str(r.line)})
            detail = x(f"claim: {r.name}\nsource: {r.source or '-'}\nmodel: {r.model}\n"
                       f"printed: {r.printed}\nderived: {r.derived}\nstatus: {r.status}\n"
                       f"difference: {r.difference or '-'}")
            if r.status == "error":
                ET.SubElement(case, "error", {"message": x(r.difference)}).text = detail
            elif not r.passed:
                ET.SubElement(case, "failure", {"message": x(f"{r.status}: {r.difference}")}
                              ).text = detail
            else:
                ET.SubElement(case, "system-out").text = detail
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, "unicode") + "\n"
