"""Tests of ``dispersion reproduce`` (dispersion/cli/reproduce.py, dispersion/report/index.py).

The fast tests run the orchestration on stub sections: every file index.md links exists, a
failing section leaves the previous output untouched and no temporary directory behind. The
slow test runs the real quick subset end to end.
"""
from __future__ import annotations

import re
import sys
import types
from pathlib import Path

import pytest

from dispersion.cli import main
from dispersion.cli.reproduce import SECTIONS, build_reports, load_sections
from dispersion.errors import DispersionError
from dispersion.io import write_text
from dispersion.report.index import PACKAGES

LINK = re.compile(r"\]\(([^)#]+)\)")


def _linked_files(index: Path) -> list[str]:
    return [m for m in LINK.findall(index.read_text()) if "://" not in m]


def _stub(name: str, fail: bool = False):
    def report(out, quick=False, executor=None):
        if fail:
            raise RuntimeError(f"{name} broke")
        write_text(Path(out) / f"{name}.csv", f"quick,{quick}\n")
        return f"## {name}\n\nThe [{name} data]({name}.csv)."

    return report


def _leftovers(parent: Path, name: str) -> list[Path]:
    return [p for p in parent.iterdir() if p.name.startswith(f".{name}.")]


def test_index_links_every_section_file(tmp_path):
    out = tmp_path / "reports"
    sections = [(n, _stub(n)) for n in ("alpha", "beta")]
    results = build_reports(out, sections, quick=True, command="dispersion reproduce --quick",
                            progress=False)
    assert [r.name for r in results] == ["alpha", "beta"]
    index = out / "index.md"
    links = _linked_files(index)
    assert sorted(links) == ["alpha.csv", "beta.csv"]
    for link in links:
        assert (out / link).read_text() == "quick,True\n"
    text = index.read_text()
    assert "dispersion reproduce --quick" in text
    for pkg in PACKAGES:  # the page names the version of every package it promises
        assert f"| {pkg} |" in text
    assert _leftovers(tmp_path, "reports") == []


def test_failed_section_leaves_previous_output_untouched(tmp_path):
    out = tmp_path / "reports"
    build_reports(out, [("alpha", _stub("alpha"))], progress=False)
    before = {p.name: p.read_text() for p in out.iterdir()}
    sections = [("beta", _stub("beta")), ("gamma", _stub("gamma", fail=True))]
    with pytest.raises(RuntimeError, match="gamma broke"):
        build_reports(out, sections, progress=False)
    assert {p.name: p.read_text() for p in out.iterdir()} == before
    assert not (out / "beta.csv").exists()
    assert _leftovers(tmp_path, "reports") == []


def test_failed_first_run_creates_nothing(tmp_path):
    out = tmp_path / "fresh"
    with pytest.raises(RuntimeError):
        build_reports(out, [("gamma", _stub("gamma", fail=True))], progress=False)
    assert list(tmp_path.iterdir()) == []


def test_cli_runs_all_sections_in_order(tmp_path, monkeypatch, capsys):
    calls = []
    for name in SECTIONS:
        module = types.ModuleType(f"dispersion.report.{name}")

        def report(out, quick=False, executor=None, _name=name):
            calls.append((_name, quick, executor is not None))
            return _stub(_name)(out, quick, executor)

        module.report = report
        monkeypatch.setitem(sys.modules, f"dispersion.report.{name}", module)
    out = tmp_path / "rep"
    assert main(["reproduce", "--quick", "--out", str(out), "--jobs", "1"]) == 0
    assert calls == [(n, True, True) for n in SECTIONS]
    assert sorted(_linked_files(out / "index.md")) == sorted(f"{n}.csv" for n in SECTIONS)
    assert "--quick" in (out / "index.md").read_text()
    assert "index.md" in capsys.readouterr().out


def test_bad_input_is_one_line_exit_2(tmp_path, capsys):
    assert main(["reproduce", "--out", str(tmp_path / "x"), "--jobs", "0"]) == 2
    assert main(["reproduce", "--out", str(tmp_path / "x"), "--sections", "nope"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and "jobs" in err[0] and "sections" in err[1]
    assert not (tmp_path / "x").exists()


def test_missing_section_module_is_an_error(monkeypatch):
    monkeypatch.setitem(sys.modules, "dispersion.report.ring", None)
    with pytest.raises((DispersionError, ImportError)):
        load_sections(["ring"])


@pytest.mark.slow
def test_quick_reproduce_end_to_end(tmp_path):
    out = tmp_path / "reports"
    assert main(["reproduce", "--quick", "--out", str(out)]) == 0
    index = out / "index.md"
    links = _linked_files(index)
    assert links, "index.md links no files"
    for link in links:
        assert (out / link).is_file(), link
    for name in SECTIONS:
        assert f"| {name} |" in index.read_text()
