"""``dispersion branches``: files written, rows consistent with the API, bad input exits 2."""
from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from dispersion.cli import main
from dispersion.continuum.exact_branches import trace_branches


def _rows(text: str) -> list[dict]:
    return list(csv.DictReader(line for line in text.splitlines() if not line.startswith("#")))


def test_exact_only_csv_matches_api(tmp_path):
    out = tmp_path / "rl.csv"
    rc = main(["branches", "--exact", "--kappa-max", "3", "--count", "7",
               "--omega-max", "5", "--csv", str(out)])
    assert rc == 0
    rows = _rows(out.read_text())
    assert {r["source"] for r in rows} == {"exact"}
    ref = trace_branches(0.3, np.linspace(0, 3, 7), 5.0)
    for r in rows:
        i = round(float(r["kappa"]) / 0.5)
        assert float(r["Omega"]) == ref.omega[r["branch"]][i]
        assert r["symmetry"] == r["branch"][0]
    assert len(rows) == sum(int(np.isfinite(v).sum()) for v in ref.omega.values())


def test_discrete_csv_and_figure(tmp_path):
    out, fig = tmp_path / "b.csv", tmp_path / "b.png"
    rc = main(["branches", "--mass", "consistent", "--mass", "singular", "--count", "20",
               "--csv", str(out), "--figure", str(fig)])
    assert rc == 0
    rows = _rows(out.read_text())
    sources = {r["source"] for r in rows}
    assert sources == {"exact", "consistent", "singular"}
    sym = {r["symmetry"] for r in rows if r["source"] == "singular"}
    assert sym == {"mixed"}  # top-surface contact breaks the mirror symmetry
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert not list(tmp_path.glob(".*.tmp"))


@pytest.mark.parametrize("argv", [
    ["--kappa-min", "2", "--kappa-max", "1"],
    ["--kappa-min", "1", "--kappa-max", "1"],
    ["--omega-max", "0"],
    ["--omega-max", "nan"],
    ["--kappa-max", "inf"],
    ["--count", "1"],
    ["--nu", "0.6"],
    ["--r", "-1"],
    ["--count", "100000000"],       # issue 11: 3.3 GiB before; refused up front
    ["--omega-max", "1e6"],         # issue 11: MemoryError asking 59.5 GiB before
    ["--exact", "--mass", "singular"],
    ["--exact", "--r", "2"],
    ["--mass", "consistent", "--gamma-s", "0.5"],
    ["--model", "x-exact", "--r", "2"],
    ["--material", "aluminium"],    # no thickness
    ["--thickness", "1"],           # no material
    ["--material", "aluminium", "--thickness", "1", "--nu", "0.3"],
    ["--figure", "fig.txt"],        # a rejected figure name writes no csv either
])
def test_bad_input_exits_2(argv, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    rc = main(["branches", "--csv", str(tmp_path / "x.csv"), *argv])
    assert rc == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "error" in err
    assert not (tmp_path / "x.csv").exists()


def test_progress_bar_goes_to_stderr(tmp_path, capsys):
    rc = main(["branches", "--exact", "--count", "5", "--progress",
               "--csv", str(tmp_path / "p.csv")])
    assert rc == 0
    captured = capsys.readouterr()
    assert "branches" in captured.err and captured.out == ""


def test_stdout_formats_carry_inputs(capsys):
    argv = ["branches", "--exact", "--kappa-max", "1", "--count", "3", "--omega-max", "2"]
    assert main([*argv, "--format", "csv"]) == 0
    text = capsys.readouterr().out
    assert "# Poisson's ratio: nu = 0.3" in text and "# dispersion-iga:" in text
    rows = _rows(text)
    assert {"c_p/c_T", "c_g/c_T"} <= set(rows[0])
    assert main([*argv, "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert "Poisson's ratio: nu = 0.3" in data["header"] and len(data["rows"]) == len(rows)
    assert main([*argv, "--format", "text"]) == 0
    assert "Omega" in capsys.readouterr().out


def test_aluminium_columns_in_units(capsys):
    # A1 cut-off at kappa = 0: f d = c_T / 2 = 1.565 MHz mm (Dispersion Calculator, aluminium)
    assert main(["branches", "--exact", "--material", "aluminium", "--thickness", "1",
                 "--kappa-max", "1", "--count", "2", "--omega-max", "2", "--csv", "-"]) == 0
    text = capsys.readouterr().out
    # the inputs in words with units, never a Python repr (issue 28)
    assert "# material: aluminium (c_L 6320 m/s, c_T 3130 m/s, rho 2700 kg/m^3" in text
    assert "{" not in text and "[" not in "".join(ln for ln in text.splitlines()
                                                 if ln.startswith("#") and "kappa" not in ln)
    a1 = [r for r in _rows(text) if r["branch"] == "A1" and float(r["kappa"]) == 0][0]
    assert float(a1["fd [MHz mm]"]) == pytest.approx(1.565, rel=1e-12)
    assert float(a1["f [kHz]"]) == pytest.approx(1565.0, rel=1e-12)  # d = 1 mm
    assert {"c_p [m/s]", "c_g [m/s]", "wavelength [mm]"} <= set(a1)


def test_discrete_rows_have_group_velocity(tmp_path):
    out = tmp_path / "d.csv"
    assert main(["branches", "--mass", "consistent", "--kappa-min", "0.5", "--kappa-max", "1",
                 "--count", "2", "--omega-max", "3", "--csv", str(out)]) == 0
    rows = [r for r in _rows(out.read_text()) if r["source"] == "consistent"]
    assert rows and all(np.isfinite(float(r["c_g/c_T"])) for r in rows)


@pytest.mark.slow
def test_largest_discrete_patch_is_accepted(tmp_path, capsys):
    # the size limits are the patch's own (patch.check_size), the same as for the series;
    # the numeric work bound count * masses * n^3 is the branches' own
    from dispersion.answers.branch_table import MAX_DISCRETE_WORK
    from dispersion.symbolic.plate import N_MAX

    out = tmp_path / "o.csv"
    argv = ["branches", "--mass", "consistent", "--kappa-min", "0.5", "--kappa-max", "1",
            "--count", "400", "--omega-max", "2", "--csv", str(out)]
    n_work = int(round((MAX_DISCRETE_WORK / 400) ** (1 / 3), 9))
    # inside the work bound: it runs, or (where the float eigen-solver cannot certify the
    # eigenvalues) the extended solver's own time bound refuses it in one line
    code = main([*argv, "--n", str(n_work)])
    err = capsys.readouterr().err
    assert code == 0 or (code == 2 and "extended-precision eigen-solver" in err
                         and len(err.strip().splitlines()) == 1), err
    assert main([*argv, "--n", str(n_work + 1)]) == 2
    assert f"<= {MAX_DISCRETE_WORK}" in capsys.readouterr().err
    assert main([*argv, "--n", str(N_MAX + 1)]) == 2
    assert str(N_MAX) in capsys.readouterr().err
