"""``dispersion branches``: files written, rows consistent with the API, bad input exits 2."""
from __future__ import annotations

import csv

import numpy as np
import pytest

from dispersion.cli import main
from dispersion.rayleigh_lamb import trace_branches


def test_exact_only_csv_matches_api(tmp_path):
    out = tmp_path / "rl.csv"
    rc = main(["branches", "--exact-only", "--kappa-max", "3", "--count", "7",
               "--omega-max", "5", "--csv", str(out)])
    assert rc == 0
    rows = list(csv.DictReader(out.open()))
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
    rows = list(csv.DictReader(out.open()))
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
])
def test_bad_input_exits_2(argv, tmp_path, capsys):
    rc = main(["branches", "--csv", str(tmp_path / "x.csv"), *argv])
    assert rc == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "error" in err
    assert not (tmp_path / "x.csv").exists()


def test_progress_bar_goes_to_stderr(tmp_path, capsys):
    rc = main(["branches", "--exact-only", "--count", "5", "--progress",
               "--csv", str(tmp_path / "p.csv")])
    assert rc == 0
    captured = capsys.readouterr()
    assert "branches" in captured.err and captured.out == ""
