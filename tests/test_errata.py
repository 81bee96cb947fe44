"""Errata table (paper eqs 13-20) built from the paper's claims file; LaTeX that compiles."""
from __future__ import annotations

import shutil
import subprocess

import pytest
import sympy

from dispersion import results
from dispersion.claims.errata import (eq13_note, errata_document, errata_table, format_table,
                               paper_claims, paper_errata)
from dispersion.errors import InputError

nu, w = sympy.symbols("nu w")


@pytest.fixture(scope="module")
def rows():
    return errata_table()


def test_errata_statuses(rows):
    by_key = {(r.equation, r.power): r for r in rows}
    differs = {key for key, r in by_key.items() if r.status == "differs"}
    # eq 17 kappa^6 and eq 19 kappa^4 are misprints (derived independently in
    # tests/test_power_balance.py); eq 20 holds for gamma_s = 0 but not for the stated 1/2
    assert differs == {("17", 6), ("19", 4), ("20, gamma_s = 1/2", 6)}
    # eqs 18 and 20 at kappa^6 hold for Bloch with square elements only (r = b/h = 2)
    assert by_key[("18", 6)].reproduced_by == ("bloch r=2",)
    assert by_key[("20", 6)].reproduced_by == ("bloch r=2",)
    assert all(r.reproduced_by == ("exact",) for key, r in by_key.items() if key[0] in ("14", "15"))
    # eq 19 as printed is the derived kappa^4 term with its sign flipped
    assert sympy.cancel(by_key[("19", 4)].printed + by_key[("19", 4)].derived) == 0


def test_printed_eq13_leading_balance():
    notes = {b: (std, pr) for b, std, pr in eq13_note()}
    # the printed form's A0 balance is the constant -4: no root, no A0 branch through 0
    assert notes["A0"][1] == "-4"
    # standard form: the bar speed w = 2/(1 - nu) (eq 14's leading term) is a root; printed: not
    std_s0 = sympy.sympify(notes["S0"][0], locals={"nu": nu, "w": w})
    pr_s0 = sympy.sympify(notes["S0"][1], locals={"nu": nu, "w": w})
    assert sympy.cancel(std_s0.subs(w, 2 / (1 - nu))) == 0
    assert sympy.cancel(pr_s0.subs(w, 2 / (1 - nu))) != 0


def test_formats_render_every_row(rows):
    md = format_table(rows, "markdown").splitlines()
    assert len(md) == len(rows) + 2
    for row, line in zip(rows, md[2:]):
        assert line.startswith(f"| ({row.equation}) | kappa^{row.power} | {row.printed} |")
    text = format_table(rows, "text").splitlines()
    assert len(text) == len(rows) + 2 and all(r.status in t for r, t in zip(rows, text[2:]))
    tex = format_table(rows, "latex").splitlines()
    assert len(tex) == len(rows) + 3 and tex[0].startswith(r"\begin{tabular}")


def test_rows_from_json_render_like_rows(rows):
    data = results.jsonable(rows)
    assert format_table(data, "markdown") == format_table(rows, "markdown")
    assert format_table(data, "latex") == format_table(rows, "latex")


def _compile(tmp_path, tex: str) -> None:
    engine = shutil.which("pdflatex")
    if engine is None:
        pytest.skip("pdflatex not installed (apt-get install texlive-latex-base)")
    (tmp_path / "doc.tex").write_text(tex)
    proc = subprocess.run([engine, "-interaction=nonstopmode", "-halt-on-error", "doc.tex"],
                          cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stdout[-2000:]
    assert (tmp_path / "doc.pdf").stat().st_size > 0


def test_latex_table_compiles_in_a_minimal_document(tmp_path, rows):
    _compile(tmp_path, "\\documentclass{article}\n\\begin{document}\n"
             + format_table(rows, "latex") + "\n\\end{document}\n")


def test_errata_document_compiles(tmp_path, rows):
    _compile(tmp_path, errata_document(rows, eq13_note()))


def test_series_paper_latex_output_compiles(tmp_path, capsys):
    # issue 11: `dispersion series --paper --format latex` printed plain text after the table
    from dispersion.cli import main

    assert main(["series", "--paper", "--format", "latex"]) == 0
    _compile(tmp_path, capsys.readouterr().out)


def test_coefficients_section_renders_from_json_and_its_tex_compiles(tmp_path):
    from dispersion.report import section_module

    section = section_module("coefficients")
    assert section.measure is paper_errata
    measured = paper_errata(quick=True)
    results.save(tmp_path / "coefficients.json", "coefficients", measured)
    data = results.load(tmp_path / "coefficients.json")["result"]
    md = section.render(data, tmp_path)
    assert "eq 17, eq 19" in md and "differs (expected)" in md
    errata_lines = [line for line in md.splitlines() if line.startswith("| (")]
    assert len(errata_lines) == len(measured.rows)  # one errata line per printed term
    _compile(tmp_path, (tmp_path / "coefficients.tex").read_text())


@pytest.mark.parametrize("equations", [("99",), ("14", "16"), "99", [None], (18.0,), 3.5])
def test_unknown_equations_are_refused_naming_the_known_ones(equations):
    with pytest.raises(InputError, match=r"equations must .*one of 14, 15, 17, 18, 19, 20"):
        errata_table(equations=equations)


def test_equations_given_as_numbers_or_bare():
    assert [c.name for c in paper_claims(equations=("20",))] == ["eq 20", "eq 20, gamma_s = 1/2"]
    assert paper_claims(equations=20) == paper_claims(equations=["20"])
    assert paper_claims(equations=(14, "15")) == paper_claims(equations=("14", "15"))
