"""``dispersion ring``: the JSON summary is the API's, output files, one-line errors."""
from __future__ import annotations

import csv
import json
from dataclasses import replace

import pytest

from dispersion.cli import main
from dispersion.contact.scenario import Scenario
from dispersion.contact.simulate import simulate_ring


def test_json_summary_is_the_api_summary(capsys):
    assert main(["ring", "--mass", "lumped", "--t-end", "0.5", "--format", "json",
                 "--no-progress"]) == 0
    summary = json.loads(capsys.readouterr().out)["summary"]
    api = simulate_ring(replace(Scenario(), t_end=0.5), "lumped").summary
    assert summary["mass"] == "lumped" and summary["t_end"] == 0.5
    assert summary["energy_change_percent"] == pytest.approx(api["energy_change_percent"],
                                                             rel=1e-12, abs=1e-12)
    assert summary["contact_events"] == api["contact_events"]


def test_json_is_strict_when_the_run_ends_in_contact(capsys):
    # t_end 2 s ends during the first impact: no free flight, no NaN in the output
    assert main(["ring", "--t-end", "2", "--format", "json", "--no-progress"]) == 0
    text = capsys.readouterr().out
    data = json.loads(text, parse_constant=lambda c: pytest.fail(f"non-strict {c}"))
    assert data["summary"]["free_flight_energy_spread_percent"] is None


def test_out_dir_files_and_csv_rows(tmp_path, capsys):
    out = tmp_path / "ring"
    assert main(["ring", "--t-end", "0.3", "--dt", "0.1", "--out", str(out)]) == 0
    assert {p.name for p in out.iterdir()} == {".dispersion-report", "summary.json", "result.json", "history.csv",
                                               "figure.png"}
    lines = (out / "history.csv").read_text().splitlines()
    assert lines[0] == "# ring on a rigid plane: singular mass, Kane's contact-modified Newmark"
    assert any(line.startswith("# scene: r_inner = ") and "dt = 0.1 s" in line for line in lines)
    rows = list(csv.DictReader(line for line in lines if not line.startswith("#")))
    assert len(rows) == 4 and float(rows[0]["t [s]"]) == 0.0  # 3 steps + initial state
    assert float(rows[-1]["t [s]"]) == pytest.approx(0.3)
    assert {"contact_force [N/m]", "total [J/m]", "penetration [m]"} <= set(rows[0])
    assert "energy change" in capsys.readouterr().out


def test_material_and_geometry_options_reach_the_scenario(capsys):
    assert main(["ring", "--t-end", "0.1", "--rho", "2000", "--r-outer", "170",
                 "--format", "json", "--no-progress"]) == 0
    summary = json.loads(capsys.readouterr().out)["summary"]
    assert summary["E"] == pytest.approx(Scenario(rho=2000.0).E)


@pytest.mark.parametrize("argv, name", [
    (["--dt", "-0.1"], "dt"),
    (["--level", "-1"], "level"),
    (["--dt", "1e-7"], "t_end / dt"),
    (["--dt", "1e-300", "--t-end", "1e-299"], "dt"),
    (["--t-end", "0.01"], "t_end"),
    (["--t-end", "0.07"], "t_end"),
    (["--mass", "lumped", "--gamma-s", "0.3"], "gamma-s"),
    (["--gap", "inf"], "gap"),
])
def test_bad_input_exits_2_with_one_line_naming_the_parameter(argv, name, capsys):
    assert main(["ring", *argv, "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and name in err


def test_out_that_is_a_file_is_refused_before_the_run(tmp_path, capsys):
    f = tmp_path / "file.txt"
    f.write_text("x")
    assert main(["ring", "--out", str(f), "--no-progress"]) == 2
    assert "--out must be a folder" in capsys.readouterr().err


@pytest.mark.parametrize("argv, stated", [
    (["--level", "abc"], "--level must be an integer in [0, 4]"),
    (["--level", "5"], "--level must be an integer in [0, 4]"),
    (["--out", ""], "--out must be a folder path"),
    (["--out", "-"], "--out must be a folder path"),
])
def test_level_and_out_state_their_range_and_touch_nothing(argv, stated, tmp_path, monkeypatch,
                                                          capsys):
    monkeypatch.chdir(tmp_path)
    try:
        status = main(["ring", *argv, "--no-progress"])
    except SystemExit as exc:  # argparse
        status = exc.code
    assert status == 2
    assert stated in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []
