"""``dispersion branches --frequency/--fd``: the practitioner's table, exports, figures, errors."""
from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest

from dispersion.cli import main
from dispersion.materials.materials import material
from dispersion.answers.mode_table import lamb_modes


def _rows(text: str) -> list[dict]:
    return list(csv.DictReader(line for line in text.splitlines() if not line.startswith("#")))


def test_issue_20_command_prints_s0_a0_sh0(capsys):
    # issue 20, "done means": the command as written
    argv = ["branches", "--exact", "--material", "steel", "--thickness", "3", "--frequency", "200"]
    assert main(argv) == 0
    rows = _rows(capsys.readouterr().out)
    assert [r["mode"] for r in rows] == ["S0", "A0", "SH0"]
    ref = lamb_modes(material("steel"), 3.0, frequency_khz=[200.0]).rows()
    for r, x in zip(rows, ref):  # the CLI prints what the API computes, to the last digit
        for col in ("c_p [m/s]", "c_g [m/s]", "wavelength [mm]"):
            assert float(r[col]) == x[col]


def test_help_states_units(capsys):
    with pytest.raises(SystemExit):
        main(["branches", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    for unit in ("in kHz", "MHz mm", "kg/m^3", "in GPa", "d = 2h in mm"):
        assert unit in out


@pytest.mark.slow
def test_units_lists_and_grids_agree(capsys):
    base = ["branches", "--exact", "--material", "aluminium", "--thickness", "2"]
    assert main([*base, "--frequency", "0.5MHz,750kHz", "--format", "json"]) == 0
    a = json.loads(capsys.readouterr().out)["rows"]
    assert main([*base, "--fd", "1:1.5:2", "--format", "json"]) == 0
    b = json.loads(capsys.readouterr().out)["rows"]
    assert [(r["mode"], r["c_p [m/s]"]) for r in a] == [(r["mode"], r["c_p [m/s]"]) for r in b]
    assert {r["f [kHz]"] for r in a} == {500.0, 750.0}


def test_csv_has_no_nan_or_inf_and_lists_zgv_and_cutoffs(tmp_path):
    out = tmp_path / "al.csv"
    assert main(["branches", "--exact", "--material", "aluminium", "--thickness", "1",
                 "--frequency", "10kHz:3MHz:40", "--csv", str(out)]) == 0
    text = out.read_text()
    assert "# ZGV S1: f = 28" in text and "# cut-off A1: 1565 kHz" in text
    rows = _rows(text)
    assert {"S0", "A0", "SH0", "A1", "SH1", "S1"} <= {r["mode"] for r in rows}
    for r in rows:
        for key, v in r.items():
            assert v.lower() not in ("nan", "inf", "-inf")
            if key not in ("mode", "family"):
                assert math.isfinite(float(v))


def test_kappa_grid_csv_writes_empty_cells_not_nan(capsys):
    # issue 20: c_p at kappa = 0 was written as nan/inf
    assert main(["branches", "--exact", "--material", "aluminium", "--thickness", "1",
                 "--kappa-max", "1", "--count", "2", "--omega-max", "2", "--csv", "-"]) == 0
    text = capsys.readouterr().out
    assert "nan" not in text.lower().replace("# empty cell: not defined (no value is written "
                                             "as nan or inf)", "")
    at_cutoff = [r for r in _rows(text) if float(r["kappa"]) == 0]
    assert at_cutoff and all(r["c_p [m/s]"] == "" for r in at_cutoff)


@pytest.mark.slow  # two figures drawn: seconds on a shared machine
def test_figures_in_physical_units(tmp_path):
    fig, fig2 = tmp_path / "f.png", tmp_path / "k.png"
    assert main(["branches", "--exact", "--material", "brass", "--thickness", "1",
                 "--frequency", "20kHz:3MHz:60", "--figure", str(fig)]) == 0
    assert main(["branches", "--exact", "--material", "brass", "--thickness", "1",
                 "--kappa-max", "4", "--count", "40", "--omega-max", "4",
                 "--figure", str(fig2)]) == 0
    for f in (fig, fig2):
        assert f.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.slow
def test_mode_shape_is_traction_free(tmp_path):
    out = tmp_path / "s.csv"
    assert main(["branches", "--exact", "--material", "titanium", "--thickness", "2",
                 "--frequency", "1MHz", "--mode-shape", "A1", "--csv", str(out)]) == 0
    rows = _rows(out.read_text())
    faces = [r for r in rows if abs(abs(float(r["y [mm]"])) - 1.0) < 1e-12]
    assert len(faces) == 2
    for r in faces:  # free faces: sigma_yy = sigma_xy = 0 (relative to the largest stress)
        big = max(abs(float(x["sigma_xx"])) for x in rows)
        assert abs(float(r["sigma_yy"])) < 1e-9 * big
        assert abs(float(r["sigma_xy"])) < 1e-9 * big


@pytest.mark.parametrize("argv", [
    ["--frequency", "200"],                                        # no --exact
    ["--exact", "--frequency", "200"],                             # no material
    ["--exact", "--material", "steel", "--frequency", "200"],      # no thickness
    ["--exact", "--material", "steel", "--thickness", "3", "--frequency", "200GHz"],
    ["--exact", "--material", "steel", "--thickness", "3", "--frequency", "-5"],
    ["--exact", "--material", "steel", "--thickness", "3", "--frequency", "1e9"],
    ["--exact", "--material", "steel", "--thickness", "3", "--frequency", "5:1:3"],
    ["--exact", "--material", "steel", "--thickness", "3", "--frequency", "1:5:1000000"],
    ["--exact", "--material", "steel", "--thickness", "3", "--frequency", "200", "--fd", "1"],
    ["--exact", "--material", "steel", "--thickness", "3", "--frequency", "200",
     "--kappa-max", "2"],
    ["--exact", "--material", "steel", "--thickness", "3", "--frequency", "200,300",
     "--mode-shape", "S0"],
    ["--exact", "--material", "steel", "--thickness", "3", "--frequency", "200",
     "--mode-shape", "S7"],
    ["--exact", "--material", "steel", "--cl", "6000", "--thickness", "3", "--frequency", "200"],
    ["--exact", "--cl", "6000", "--ct", "3000", "--nu", "0.3", "--thickness", "3",
     "--frequency", "200"],
    ["--exact", "--youngs-modulus", "200", "--rho", "7800", "--thickness", "3",
     "--frequency", "200"],                                         # E without nu
    ["--exact", "--mode-shape", "S0"],                              # kappa grid: no mode shape
])
def test_bad_input_exits_2(argv, tmp_path, capsys):
    rc = main(["branches", "--csv", str(tmp_path / "x.csv"), *argv])
    assert rc == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "error" in err
    assert not (tmp_path / "x.csv").exists()


@pytest.mark.slow
def test_user_material_from_moduli_matches_speeds(capsys):
    m = material("steel")
    E = m.rho * m.c_T**2 * (3 * m.c_L**2 - 4 * m.c_T**2) / (m.c_L**2 - m.c_T**2)
    base = ["branches", "--exact", "--thickness", "3", "--frequency", "200", "--format", "json"]
    assert main([*base, "--youngs-modulus", repr(E / 1e9), "--nu", repr(m.nu),
                 "--rho", repr(m.rho)]) == 0
    a = json.loads(capsys.readouterr().out)["rows"]
    assert main([*base, "--cl", repr(m.c_L), "--ct", repr(m.c_T)]) == 0
    b = json.loads(capsys.readouterr().out)["rows"]
    np.testing.assert_allclose([r["c_p [m/s]"] for r in a], [r["c_p [m/s]"] for r in b],
                               rtol=1e-12)


@pytest.mark.slow
def test_csv_never_has_nan_or_inf_over_random_plates():
    # the "never" of issue 20 searched for counterexamples: random plates and frequencies
    from hypothesis import given, settings
    from hypothesis import strategies as st

    @settings(max_examples=25, deadline=None)
    @given(ct=st.floats(1000.0, 4000.0), ratio=st.floats(1.2, 3.0), d=st.floats(0.2, 10.0),
           fd=st.lists(st.floats(0.01, 8.0), min_size=1, max_size=4))
    def check(ct, ratio, d, fd):
        from dispersion.materials.materials import user_material

        t = lamb_modes(user_material(c_L=ct * ratio, c_T=ct), d, fd_mhz_mm=fd)
        text = t.to_csv()
        for r in _rows(text):
            for key, v in r.items():
                if key not in ("mode", "family"):
                    assert math.isfinite(float(v)), (key, v)

    check()
