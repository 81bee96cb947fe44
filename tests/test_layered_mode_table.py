"""``dispersion branches --exact --layup``: the layered plate's table
(dispersion/answers/layered_mode_table.py) through the API and the command line."""
from __future__ import annotations

import csv
import json

import pytest

from dispersion.answers.layered_mode_table import layered_lamb_modes
from dispersion.cli import main
from dispersion.continuum.layered.layered_plate import layered_plate
from dispersion.errors import InputError
from dispersion.materials.materials import material


def _rows(text: str) -> list[dict]:
    return list(csv.DictReader(line for line in text.splitlines() if not line.startswith("#")))


def test_two_layer_plate_on_the_command_line(capsys):
    argv = ["branches", "--exact", "--layup", "steel:0.71,aluminium:0.29", "--frequency",
            "2MHz", "--format", "json"]
    assert main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["failures"] == []
    # every Lamb and SH mode below 2 MHz of this stack, named by the count
    assert [r["mode"] for r in data["rows"]] == ["L0", "SH0", "L1", "SH1", "L2"]
    api = layered_lamb_modes(layered_plate([(material("steel"), 0.71),
                                            (material("aluminium"), 0.29)]),
                             frequency_khz=[2000.0]).rows()
    assert [r["c_p [m/s]"] for r in data["rows"]] == [r["c_p [m/s]"] for r in api]


def test_one_isotropic_layer_is_todays_table_byte_for_byte(capsys):
    assert main(["branches", "--exact", "--material", "steel", "--thickness", "1",
                 "--frequency", "100:3000:7", "--format", "csv"]) == 0
    today = capsys.readouterr().out
    assert main(["branches", "--exact", "--layup", "steel:1", "--frequency", "100:3000:7",
                 "--format", "csv"]) == 0
    assert capsys.readouterr().out == today


def test_laminate_by_its_layup_string(capsys):
    assert main(["branches", "--exact", "--layup", "[0/90]s", "--ply", "T800/913",
                 "--ply-thickness", "0.125", "--frequency", "500", "--modes", "A,SH"]) == 0
    rows = _rows(capsys.readouterr().out)
    assert [r["mode"] for r in rows] == ["A0", "SH0"]


@pytest.mark.parametrize("argv, message", [
    (["--layup", "steel:1", "--material", "steel", "--frequency", "100"], "--layup applies"),
    (["--material", "steel", "--thickness", "1", "--ply", "T800/913", "--frequency", "100"],
     "--ply applies"),
    (["--layup", "steel:1,copper:1", "--thickness", "1", "--frequency", "100"],
     "--thickness applies"),
    (["--layup", "steel:1", "--frequency", "100", "--modes", "Q"], "--modes must be"),
    (["--layup", "[0/90]s", "--frequency", "100"], "needs a ply"),
    (["--layup", "steel:1,copper:1", "--frequency", "1e9"], "frequency"),
    (["--material", "steel", "--thickness", "1", "--frequency", "100", "--zgv"],
     "--zgv applies"),
    (["--layup", "steel:1", "--damping", "0.01", "--frequency", "100", "--zgv"],
     "damped plate"),
])
def test_bad_layered_requests_are_one_line_and_exit_2(capsys, argv, message):
    assert main(["branches", "--exact", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and "\n" not in err


def test_out_of_range_frequencies_name_the_range_in_khz():
    plate = layered_plate([(material("steel"), 0.5), (material("copper"), 0.5)])
    with pytest.raises(InputError, match=r"frequency_khz must lie in \[.* kHz"):
        layered_lamb_modes(plate, frequency_khz=[1e9])


def test_a_coupled_laminate_lists_its_skew_and_a_decoupled_one_none(capsys):
    """Waves along the plies' axes carry their energy along the waves (skew 0 by symmetry);
    at 30 deg the table's skew is the energy flow's (its test: test_layered_mode_shapes)."""
    assert main(["branches", "--exact", "--layup", "[0/90]s", "--ply", "T800/913",
                 "--ply-thickness", "0.125", "--frequency", "500", "--angle", "30",
                 "--format", "csv"]) == 0
    rows = _rows(capsys.readouterr().out)
    assert any(abs(float(r["skew [deg]"])) > 1 for r in rows)
    assert main(["branches", "--exact", "--layup", "[0/90]s", "--ply", "T800/913",
                 "--ply-thickness", "0.125", "--frequency", "500", "--format", "csv"]) == 0
    assert all(float(r["skew [deg]"]) == 0.0 for r in _rows(capsys.readouterr().out))


@pytest.mark.slow
def test_the_laminate_table_lists_its_zgv_point():
    from dispersion.continuum.layered.layered_plate import laminate
    from dispersion.continuum.layered.layered_zgv import zgv_points
    from dispersion.materials.materials import ply

    plate = laminate("[0/90]s", ply("T800/913"), 0.125)
    t = layered_lamb_modes(plate, fd_mhz_mm=[1.0, 1.3], zgv=True)   # S1: ZGV at 1.24 MHz mm
    (label, kappa, W), = zgv_points(plate, 1.05 * float(t.roots.omega.max()))
    assert [p["mode"] for p in t.zgv()] == [label] == ["S1"]
    assert abs(t.zgv()[0]["f [kHz]"] - t._khz(W)) < 1e-9 * t._khz(W)
    assert any(line.startswith("ZGV S1") for line in t.header_lines())


@pytest.mark.slow
def test_zgv_on_the_command_line_is_the_apis(capsys):
    """``--zgv`` lists the ZGV points that :func:`layered_zgv.zgv_points` finds (their own
    test: the Rayleigh-Lamb calculator's for one layer), in the CSV's comments and the JSON."""
    from dispersion.continuum.layered.layered_zgv import zgv_points

    plate = layered_plate([(material("steel"), 0.71), (material("aluminium"), 0.29)])
    assert main(["branches", "--exact", "--layup", "steel:0.71,aluminium:0.29",
                 "--frequency", "3MHz", "--zgv", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    t = layered_lamb_modes(plate, frequency_khz=[3000.0])
    points = zgv_points(plate, 1.05 * float(t.roots.omega.max()))
    assert [p["mode"] for p in data["zgv"]] == [p[0] for p in points] and points
    for row, (_, _, W) in zip(data["zgv"], points):
        assert row["f [kHz]"] == pytest.approx(t._khz(W), rel=1e-12)
