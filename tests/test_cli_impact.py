"""``dispersion impact``: the history CSV and the summary agree with the API."""
from __future__ import annotations

import argparse
import csv
import json

import pytest

from dispersion.cli import impact
from dispersion.contact.signorini import signorini_1d
from dispersion.errors import InputError


def _args(argv):
    parser = argparse.ArgumentParser()
    impact.register(parser.add_subparsers())
    return parser.parse_args(["impact", *argv])


def test_writes_history_and_summary(tmp_path, capsys):
    out = tmp_path / "sig"
    args = _args(["signorini-1d", "--mass", "singular", "--dt", "0.004", "--t-end", "3",
                  "--out", str(out), "--format", "json"])
    assert args.func(args) == 0
    printed = json.loads(capsys.readouterr().out)
    stored = json.loads((out / "summary.json").read_text())
    api = signorini_1d(mass="singular", dt=0.004, t_end=3.0).errors
    assert stored["stress_rel_l2"] == pytest.approx(api["stress_rel_l2"], rel=1e-12)
    assert printed["summary"]["steps"] == 750 and len(printed["rows"]) == 751
    lines = (out / "history.csv").read_text().splitlines()
    assert lines[0].startswith("# signorini-1d: P1, 20 elements, singular mass")
    rows = list(csv.DictReader(line for line in lines if not line.startswith("#")))
    assert len(rows) == 751
    assert set(rows[0]) >= {"t [-]", "u0 [-]", "contact_stress [-]", "total [-]"}


def test_bad_input_names_the_parameter(tmp_path):
    with pytest.raises(SystemExit):  # argparse: one line, exit 2
        _args(["signorini-1d", "--p", "0"])
    f = tmp_path / "f"
    f.write_text("")
    args = _args(["signorini-1d", "--out", str(f)])
    with pytest.raises(InputError, match="--out must be a folder"):
        args.func(args)


def test_out_and_step_count_are_refused_before_the_run(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for argv, name in ((["--out", "-"], "--out must be a folder path"),
                       (["--out", str(tmp_path / "f" / "x")], "--out"),
                       (["--t-end", "1e12"], "t_end / dt must be <=")):
        if "f" in argv[-1]:
            (tmp_path / "f").write_text("")
        args = _args(["signorini-1d", *argv])
        with pytest.raises(InputError, match=name):
            args.func(args)
    assert [p.name for p in tmp_path.iterdir()] == ["f"]
