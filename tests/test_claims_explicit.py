"""Claims about the critical time step and the fully discrete series (dispersion.claims.explicit)."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from dispersion.claims import parse_claims, verify_claims
from dispersion.cli import main
from dispersion.errors import InputError

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "timestep_claims.toml"


def test_example_file_verifies_from_the_cli(capsys):
    assert main(["verify", str(EXAMPLE)]) == 0
    out = capsys.readouterr().out
    assert "4 of 4 claims hold as recorded" in out and "differs (expected)" in out


@pytest.mark.slow
def test_a_false_step_claim_fails_and_a_plate_claim_holds():
    # the plate value: HRZ over consistent on the p = 2, n = 3, r = 2 patch is
    # 7.4248.../2.4944... (dispersion.time_stepping.timestep; the HRZ maximum 2 sqrt(14)/3 is exact)
    claims = parse_claims('''
[[claim]]
name = "hrz plate"
kind = "critical_step"
model = "bloch"
p = 2
n = 3
r = 2
mass = "hrz"
nu = 0.3
omega_max = "2*sqrt(14)/3"

[[claim]]
name = "too long a step"
kind = "critical_step"
model = "bar"
p = 1
mass = "consistent"
ratio = 1.01
''')
    res = verify_claims(claims, jobs=1)
    assert [r.status for r in res.results] == ["holds", "differs"]
    assert "relative difference" in res.results[1].difference


@pytest.mark.parametrize("body,field", [
    ('kind = "critical_step"\nmodel = "bar"\nmass = "singular"\nratio = 1', "mass"),
    ('kind = "critical_step"\nmodel = "bar"\nratio = 1\nomega_max = "2"', "ratio"),
    ('kind = "critical_step"\nmodel = "bar"\nratio = -1', "ratio"),
    ('kind = "critical_step"\nmodel = "bar"\nn = 4\nratio = 1', "n"),
    ('kind = "fully_discrete_series"\nmodel = "bar"\ncoefficients = {"kappa^3" = "1"}',
     "kappa^3"),
    ('kind = "fully_discrete_series"\nmodel = "bar"\ncoefficients = {"tau^2" = "1"}', "tau^2"),
    ('kind = "fully_discrete_series"\nmodel = "bar"\nscheme = "euler"\n'
     'coefficients = {"kappa^2" = "1"}', "scheme"),
    ('kind = "critical_step"\nmodel = "rayleigh-lamb"\nratio = 1', "model"),
])
def test_bad_explicit_claims_name_the_field(body, field):
    with pytest.raises(InputError, match=re.escape(f"field '{field}'")):
        parse_claims(f'[[claim]]\nname = "x"\n{body}\n')


def test_series_claims_take_any_registered_rule():
    # leading S0 coefficient 2/(1 - nu) (Rayleigh-Lamb long-wave limit) for rules keeping the
    # translational mass; the exact comparison says 'differs' for a wrong one
    claims = parse_claims('''
[defaults]
model = "x-exact"
branch = "S0"
nu = "3/10"
[[claim]]
name = "lobatto"
mass = "nodal-lobatto"
coefficients = {2 = "20/7"}
[[claim]]
name = "hrz, wrong"
mass = "hrz"
coefficients = {2 = "2"}
expect = "differs"
''')
    res = verify_claims(claims, jobs=1)
    assert [r.status for r in res.results] == ["holds", "differs (expected)"]
