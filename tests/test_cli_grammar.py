"""One command-line grammar: options that do not apply are errors, help in the user's words.

Help texts name no internal identifiers (module constants, dataclass field names); every range
is written ``[lo, hi]``; every file an ``--out`` writes is named in its help.
"""
from __future__ import annotations

import re

import pytest

from dispersion.cli import _SUBCOMMANDS, main

#: Internal names a user cannot know (module constants, field names of Scenario).
INTERNAL = re.compile(r"P_MAX|N_MAX|MAX_ORDER|MAX_JOBS|theta0_deg|n_xi_elements|"
                      r"n_eta_elements|v0_over_cT|\bplate\.|power_balance\.|dispersion\.claims\.")


def _help(command: str, capsys) -> str:
    with pytest.raises(SystemExit) as done:
        main([command, "--help"])
    assert done.value.code == 0
    return capsys.readouterr().out


#: What a help text must never show (issue 28): empty defaults, reST markup, issue numbers.
NOISE = re.compile(r"\(default: (None|False)\)|``|:(func|data|mod|class):|\bissue \d+")


@pytest.mark.parametrize("command", _SUBCOMMANDS)
def test_help_is_in_the_users_words(command, capsys):
    text = _help(command, capsys)
    assert not INTERNAL.findall(text), INTERNAL.findall(text)
    assert not NOISE.findall(text), NOISE.findall(text)
    helps = text.split("options:", 1)[-1]  # the usage line may show a metavar like {1..10}
    helps = re.sub(r"\{\d+\.\.\d+\}", "", helps)
    assert not re.search(r"\d\.\.\d", helps), "ranges are written [lo, hi]"


def test_every_file_an_out_writes_is_in_its_help(capsys):
    from dispersion.cli.ring import OUT_FILES

    ring = " ".join(_help("ring", capsys).split())
    assert all(name in ring for name in OUT_FILES) and "result.json" in ring
    impact = " ".join(_help("impact", capsys).split())
    assert "history.csv" in impact and "summary.json" in impact
    reproduce = " ".join(_help("reproduce", capsys).split())
    assert "comparison.md" in reproduce and "index.md" in reproduce


def test_the_degree_range_is_stated_alike(capsys):
    series = " ".join(_help("series", capsys).split())
    branches = " ".join(_help("branches", capsys).split())
    assert re.search(r"degree through the thickness, in \[1, \d+\]", series)
    assert re.search(r"degree through the thickness, in \[1, \d+\]", branches)


@pytest.mark.parametrize("fmt", ["text", "csv", "json"])
def test_format_beside_a_stdout_file_is_an_error(fmt, tmp_path, monkeypatch, capsys):
    # two outputs never share stdout (issue 26: --json - --csv - interleaved them)
    monkeypatch.chdir(tmp_path)
    assert main(["branches", "--exact", "--count", "3", "--format", fmt, "--csv", "-"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--format" in err[0] and "stdout" in err[0]
    assert list(tmp_path.iterdir()) == []


def test_format_beside_a_named_file_also_prints(tmp_path, capsys):
    out = tmp_path / "b.csv"
    argv = ["branches", "--exact", "--count", "3", "--omega-max", "2", "--csv", str(out)]
    assert main(argv) == 0 and capsys.readouterr().out == ""   # the file alone
    assert main([*argv, "--format", "json"]) == 0                 # the file, and JSON
    assert __import__("json").loads(capsys.readouterr().out)["rows"]
    assert out.read_text().startswith("# Rayleigh-Lamb branches")


def test_exact_only_csv_lists_only_what_applies(capsys):
    assert main(["branches", "--exact", "--count", "3", "--kappa-max", "1",
                 "--omega-max", "2", "--no-progress"]) == 0
    header = [line for line in capsys.readouterr().out.splitlines() if line.startswith("#")]
    keys = {line[2:].split(":")[0] for line in header[1:]}
    assert keys == {"Poisson's ratio", "kappa = k h", "Omega = omega h / c_T", "source",
                    "dispersion-iga", "empty cell"}, keys


# --------------------------------------------------------------------------- formats

def test_latex_shows_the_factored_forms_of_the_text(capsys):
    assert main(["series", "--exact", "--order", "6", "--format", "latex"]) == 0
    latex = capsys.readouterr().out  # text: -2/(3*(nu - 1)), 2*(7*nu - 17)/(45*(nu - 1)**2)
    assert r"- \frac{2}{3 \left(\nu - 1\right)}" in latex and r"3 \nu - 3" not in latex
    assert r"\frac{2 \left(7 \nu - 17\right)}{45 \left(\nu - 1\right)^{2}}" in latex


@pytest.mark.slow  # lark's Earley parser takes tens of seconds on a shared machine
def test_latex_keeps_the_factored_forms_of_the_text(capsys):
    """Each LaTeX coefficient is the text one, same factors (lark's LaTeX parser reads it back)."""
    import lark  # noqa: F401  (the test extra installs it; a missing reader must fail, not skip terms)
    import sympy
    from sympy.parsing.latex import parse_latex

    assert main(["series", "--exact", "--order", "6", "--format", "json"]) == 0
    records = __import__("json").loads(capsys.readouterr().out)
    assert main(["series", "--exact", "--order", "6", "--format", "latex"]) == 0
    latex = capsys.readouterr().out
    assert r"\frac{2}{3 \left(\nu - 1\right)}" in latex and r"3 \nu - 3" not in latex
    terms = []
    for line in latex.splitlines():
        if line.startswith("\\Omega_"):
            body = line.split(" = ", 1)[1].rsplit(" + O(", 1)[0]
            for part in re.split(r"\\right\)\\kappa\^\{\d+\}(?: \+ )?", body)[:-1]:
                terms.append(part.removeprefix("\\left("))
    nu = sympy.Symbol("nu")
    text = [sympy.sympify(c, locals={"nu": nu})
            for r in records for c in r["coefficients"].values()]
    assert len(terms) == len(text) == 5
    assert r"\frac{2 \left(7 \nu - 17\right)}{45 \left(\nu - 1\right)^{2}}" in latex
    parsed = 0
    for tex, expected in zip(terms, text):
        try:  # lark's grammar has no implicit product before \left( in some places
            got = parse_latex(tex, backend="lark").subs(sympy.Symbol("nu"), nu)
        except Exception:
            continue
        parsed += 1
        assert sympy.simplify(got - expected) == 0, (tex, expected)
    assert parsed >= 3


def test_paper_table_wraps_to_the_terminal(capsys, monkeypatch):
    monkeypatch.setenv("COLUMNS", "60")
    assert main(["series", "--paper"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert max(map(len, lines)) <= 60
    assert any(line.strip().startswith("printed: ") for line in lines)


@pytest.mark.slow  # one interpreter per benchmark script
def test_benchmark_help_has_no_issue_numbers():
    import subprocess
    import sys
    from pathlib import Path

    bench = Path(__file__).resolve().parents[1] / "benchmarks"
    for script in sorted(bench.glob("bench_*.py")):
        text = subprocess.run([sys.executable, str(script), "--help"], capture_output=True,
                              text=True, timeout=120).stdout
        assert text and not NOISE.findall(text), (script.name, NOISE.findall(text))


@pytest.mark.parametrize("command", [c for c in _SUBCOMMANDS if c != "reproduce"])
def test_one_format_vocabulary(command, capsys):
    # every --format speaks the words of dispersion.rendering.FORMATS (series adds latex,
    # bench has no CSV form); a word it has no form for is refused in one line
    from dispersion.rendering import FORMATS

    argv = {"impact": ["impact", "signorini-1d"], "verify": ["verify", "x.toml"]}.get(
        command, [command])
    assert main([*argv, "--format", "yaml"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--format must be one of" in err
    words = err.split("one of ", 1)[1].split(", got")[0].split(", ")
    assert set(words) <= set(FORMATS) | {"latex"} and {"text", "json"} <= set(words), words
