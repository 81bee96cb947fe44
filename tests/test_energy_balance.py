"""Energy balance of contact runs (``dispersion/contact/energy_balance.py``): growth beyond the
stated bound, known-unstable (scheme, mass) pairs, and the flag in the CLI and summaries."""
from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dispersion.cli import main
from dispersion.contact.energy_balance import (GROWTH_BOUND_PERCENT, KNOWN_UNSTABLE,
                                               energy_balance)
from dispersion.contact.signorini import signorini_1d

SCHEMES = ("kane", "standard", "central")
MASSES = ("lumped", "consistent", "singular")
histories = st.lists(st.floats(0.01, 100.0), min_size=1, max_size=50)


@settings(max_examples=200, deadline=None)
@given(histories, st.sampled_from(SCHEMES), st.sampled_from(MASSES))
def test_flag_iff_growth_beyond_bound_or_known_unstable(values, scheme, mass):
    # the rule, stated independently: growth = max(E) / E(0) - 1 in percent
    total = np.array(values)
    growth = 100 * (total.max() - total[0]) / total[0]
    b = energy_balance(total, scheme, mass)
    assert b.flagged == (growth > GROWTH_BOUND_PERCENT or (scheme, mass) in KNOWN_UNSTABLE)
    assert b.growth_percent == pytest.approx(growth, abs=1e-9)


@settings(max_examples=50, deadline=None)
@given(histories, st.sampled_from(SCHEMES), st.sampled_from(MASSES),
       st.sampled_from([np.nan, np.inf, -np.inf]), st.integers(0, 49))
def test_a_history_that_blew_up_is_always_flagged(values, scheme, mass, bad, where):
    total = np.array(values)
    total[where % len(total)] = bad
    assert energy_balance(total, scheme, mass).flagged


def test_signorini_standard_newmark_is_flagged_on_stderr_and_in_json(capsys):
    # issue 18: plain Newmark with the lumped mass gains +1670 % energy and exited 0 silently
    assert main(["impact", "signorini-1d", "--mass", "lumped", "--scheme", "standard",
                 "--t-end", "3", "--format", "json"]) == 0
    out, err = capsys.readouterr()
    s = json.loads(out)["summary"]
    assert s["energy_flag"] and "unstable" in s["energy_flag"]
    assert s["energy_growth_percent"] > GROWTH_BOUND_PERCENT
    assert err.startswith("warning: signorini-1d (lumped mass, standard)")


@pytest.mark.parametrize("scheme", ["kane", "central"])
@pytest.mark.parametrize("mass", MASSES)
def test_stable_schemes_are_not_flagged(mass, scheme):
    r = signorini_1d(1, 20, mass, scheme, 0.002, 3.0)
    assert r.errors["energy_flag"] is None and r.errors["energy_growth_percent"] <= 1.0


def test_help_documents_which_schemes_are_stable(capsys):
    for cmd in ("impact", "ring"):
        with pytest.raises(SystemExit):
            main([cmd, "--help"])
        text = " ".join(capsys.readouterr().out.split())
        assert "standard (plain Newmark) is unstable with the lumped and consistent" in text
