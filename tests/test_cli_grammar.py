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


@pytest.mark.parametrize("command", _SUBCOMMANDS)
def test_help_is_in_the_users_words(command, capsys):
    text = _help(command, capsys)
    assert not INTERNAL.findall(text), INTERNAL.findall(text)
    assert not re.search(r"\d\.\.\d", text), "ranges are written [lo, hi]"


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


@pytest.mark.parametrize("extra", [["--csv", "-"], ["--figure", "f.png"]])
@pytest.mark.parametrize("fmt", ["text", "csv", "json"])
def test_format_with_a_named_file_is_an_error(fmt, extra, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["branches", "--exact", "--count", "3", "--format", fmt, *extra]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--format" in err[0] and "does not apply" in err[0]
    assert list(tmp_path.iterdir()) == []


def test_exact_only_csv_lists_only_what_applies(capsys):
    assert main(["branches", "--exact", "--count", "3", "--kappa-max", "1",
                 "--omega-max", "2", "--no-progress"]) == 0
    header = [line for line in capsys.readouterr().out.splitlines() if line.startswith("#")]
    keys = {line[2:].split(":")[0] for line in header}
    assert keys == {"nu", "kappa", "omega_max", "dispersion-iga"}, keys
