"""dispersion.testing: pytest helpers that hold a manuscript's equations."""
from __future__ import annotations

from pathlib import Path

import pytest

from dispersion.testing import assert_claim, assert_claims_file, assert_series, claims_in

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "claims.toml"


def test_correct_series_passes_and_returns_the_result():
    # paper eq (15), exact A0 to kappa^6
    r = assert_series("A0", {4: "2/(3*(1-nu))", 6: "2*(7*nu - 17)/(45*(1-nu)^2)"},
                      model="rayleigh-lamb")
    assert r.status == "holds" and [t.power for t in r.terms] == [4, 6]


def test_mistyped_series_fails_with_printed_and_derived():
    # eq (19) as printed: its kappa^4 term has the wrong sign (singular mass, gamma_s = 0)
    with pytest.raises(AssertionError) as info:
        assert_series("S0", "2/(1-nu)*kappa^2 - 2*(41*nu^2 - 10*nu - 35)/(45*(1-nu)^3)*kappa^4",
                      name="eq 19", mass="singular", contact="top", gamma_s=0)
    msg = str(info.value)
    assert msg.startswith("claim 'eq 19' (<string>:1) differs")
    assert "ok  kappa^2" in msg and "BAD kappa^4" in msg
    assert "sign: printed = -(derived)" in msg


@pytest.mark.parametrize("claim", claims_in(EXAMPLE), ids=lambda c: c.name)
def test_example_file_claims_each_hold(claim):
    assert assert_claim(claim).passed


def test_file_helper_lists_every_failing_claim(tmp_path):
    path = tmp_path / "c.toml"
    path.write_text(EXAMPLE.read_text().replace('{2 = "2/(1 - nu)"}', '{2 = "2/(1 + nu)"}'))
    with pytest.raises(AssertionError, match="claim 'bar speed'.*differs"):
        assert_claims_file(path)
