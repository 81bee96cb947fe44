"""Slowness curves of layered plates (dispersion/answers/slowness_table.py): round for an
isotropic stack, mirror-symmetric for a cross-ply, the energy flowing along the normal of the
slowness curve, and the command line (``--angle START:STOP:COUNT``)."""
from __future__ import annotations

import csv
import math

import pytest

from dispersion.answers.layered_mode_table import layered_lamb_modes
from dispersion.answers.slowness_table import slowness_curves
from dispersion.cli import main
from dispersion.continuum.layered.layered_plate import laminate, layered_plate
from dispersion.errors import InputError
from dispersion.materials.materials import material, ply

BILAYER = layered_plate([(material("steel"), 0.71), (material("aluminium"), 0.29)])
CROSS_PLY = laminate("[0/90]s", ply("T800/913"), 0.125)


def _by_angle(table):
    out = {}
    for r in table.rows():
        out.setdefault(r["angle [deg]"], []).append(r)
    return out


def test_an_isotropic_stack_has_round_slowness_curves():
    # isotropic layers: nothing in the plane tells one direction from another, so every
    # direction has the modes of direction 0 (the mode table's, certified against the 40-digit
    # transfer matrix), and the energy flows along the waves
    t = slowness_curves(BILAYER, 800.0, [0.0, 37.0])
    ref = layered_lamb_modes(BILAYER, frequency_khz=[800.0]).rows()
    for angle, rows in _by_angle(t).items():
        assert [r["mode"] for r in rows] == [r["mode"] for r in ref], angle
        for r, q in zip(rows, ref):
            assert abs(r["c_p [m/s]"] / q["c_p [m/s]"] - 1) < 1e-12
            assert r["skew [deg]"] == 0.0 and r["c_e [m/s]"] == pytest.approx(q["c_g [m/s]"],
                                                                                rel=1e-10)


def test_a_cross_ply_is_mirror_symmetric_and_each_direction_is_the_mode_table():
    # the [0/90]s plies are orthotropic in the plate's axes: the direction -theta is the
    # mirror image of theta (same slowness, skew of opposite sign)
    t = slowness_curves(CROSS_PLY, 200.0, [-30.0, 30.0])
    rows = _by_angle(t)
    for a, b in zip(rows[-30.0], rows[30.0]):
        assert a["mode"] == b["mode"]
        assert abs(a["slowness [s/km]"] / b["slowness [s/km]"] - 1) < 1e-12
        assert abs(a["skew [deg]"] + b["skew [deg]"]) < 1e-9
    table = layered_lamb_modes(CROSS_PLY.turned(30.0), frequency_khz=[200.0]).rows()
    assert [(r["mode"], r["c_p [m/s]"], r["c_g [m/s]"], r["skew [deg]"]) for r in rows[30.0]] \
        == [(r["mode"], r["c_p [m/s]"], r["c_g [m/s]"], r["skew [deg]"]) for r in table]


@pytest.mark.slow
@pytest.mark.parametrize("angle, mode", [(30.0, "A0"), (30.0, "S0"), (60.0, "S1")])
def test_energy_flows_along_the_normal_of_the_slowness_curve(angle, mode):
    """tan(skew) = -(ds/dtheta) / s at fixed frequency (Auld, ch. 7), s(theta) from the
    certified roots at theta +- 1e-3, 2e-3 deg (4-point difference). Bound chosen first:
    roots to 1e-12 over a step of 1.7e-5 rad leave about 1e-7 in the derivative: 1e-6."""
    d = 1e-3
    t = slowness_curves(CROSS_PLY, 200.0, [angle - 2 * d, angle - d, angle, angle + d,
                                           angle + 2 * d])
    rows = _by_angle(t)
    s = [[r["slowness [s/km]"] for r in rows[a] if r["mode"] == mode][0]
         for a in sorted(rows)]
    ds = (-s[4] + 8 * s[3] - 8 * s[1] + s[0]) / (12 * math.radians(d))
    skew = [r["skew [deg]"] for r in rows[sorted(rows)[2]] if r["mode"] == mode][0]
    assert abs(math.tan(math.radians(skew)) + ds / s[2]) < 1e-6


def _rows(text):
    return list(csv.DictReader(line for line in text.splitlines() if not line.startswith("#")))


def test_slowness_on_the_command_line(capsys):
    assert main(["branches", "--exact", "--layup", "steel:0.71,aluminium:0.29",
                 "--frequency", "500", "--angle", "0:90:3", "--format", "csv"]) == 0
    rows = _rows(capsys.readouterr().out)
    assert sorted({float(r["angle [deg]"]) for r in rows}) == [0.0, 45.0, 90.0]
    assert {r["mode"] for r in rows} == {"L0", "SH0", "L1"}


@pytest.mark.parametrize("argv, message", [
    (["--layup", "steel:1,copper:1", "--frequency", "100,200", "--angle", "0,45"],
     "exactly one frequency"),
    (["--layup", "steel:1,copper:1", "--frequency", "100", "--angle", "0:90:1"], "COUNT"),
    (["--layup", "steel:1,copper:1", "--frequency", "100", "--angle", "90:0:3"], "STOP > START"),
    (["--layup", "steel:1,copper:1", "--frequency", "100", "--angle", "0:400:3"], "--angle"),
    (["--layup", "steel:1,copper:1", "--frequency", "100", "--angle", "1:2:3:4"], "--angle"),
    (["--layup", "steel:1,copper:1", "--frequency", "100", "--angle", "0,45", "--zgv"],
     "--zgv applies to one direction"),
    (["--layup", "steel:1,copper:1", "--frequency", "100", "--angle", "0,45",
      "--damping", "0.01"], "damped plate"),
])
def test_bad_slowness_requests_are_one_line_and_exit_2(capsys, argv, message):
    assert main(["branches", "--exact", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and "\n" not in err


def test_bad_api_requests_name_the_parameter():
    with pytest.raises(InputError, match="angles"):
        slowness_curves(BILAYER, 500.0, [0.0] * 400)
    with pytest.raises(InputError, match="frequency_khz"):
        slowness_curves(BILAYER, 1e9, [0.0])


@pytest.mark.slow
def test_the_slowness_figure_is_written(tmp_path, capsys):
    out = tmp_path / "slowness.png"
    assert main(["branches", "--exact", "--layup", "[0/90]s", "--ply", "T800/913",
                 "--ply-thickness", "0.125", "--frequency", "200", "--angle", "0:90:4",
                 "--figure", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
