"""``dispersion ring``: JSON summary, output files, one-line errors."""
from __future__ import annotations

import csv
import json

from dispersion.cli import main


def test_json_summary(capsys):
    assert main(["ring", "--mass", "lumped", "--t-end", "0.5", "--json", "--no-progress"]) == 0
    summary = json.loads(capsys.readouterr().out)
    for key in ("energy_change_percent", "max_penetration", "contact_events", "mass"):
        assert key in summary
    assert summary["mass"] == "lumped" and summary["t_end"] == 0.5


def test_out_dir_files(tmp_path, capsys):
    out = tmp_path / "ring"
    assert main(["ring", "--t-end", "0.3", "--dt", "0.1", "--out", str(out)]) == 0
    assert {p.name for p in out.iterdir()} == {"summary.json", "result.json", "history.csv",
                                               "figure.png"}
    rows = list(csv.DictReader((out / "history.csv").open()))
    assert len(rows) == 4 and float(rows[0]["t"]) == 0.0  # 3 steps + initial state
    assert "energy change" in capsys.readouterr().out


def test_bad_input_exits_2(capsys):
    assert main(["ring", "--dt", "-0.1"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "dt" in err
    assert main(["ring", "--level", "-1"]) == 2
