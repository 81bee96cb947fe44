"""Claims about a finite mesh (dispersion/claims/mesh_claims.py): parsed, bounded, verified.

The literature's files are examples/literature/{deng2021,deng2022,manni2022,nguyen2022}.toml;
their numbers are the papers' (abstracts), the derivations the toolkit's finite patch.
"""
from __future__ import annotations

import pytest

from dispersion.claims.schema import load_claims, parse_claims
from dispersion.claims.verify import verify_claims
from dispersion.errors import InputError

BASE = ('[[claim]]\nname = "c"\nsource = "s"\nkind = "mesh_step"\nmodel = "bar"\np = 2\n'
        'mass = "lumped"\n')


@pytest.mark.parametrize("extra, field", [
    ('elements = 0\nquantity = "ratio"\nvalue = 1\n', "elements"),
    ('elements = 5000\nquantity = "ratio"\nvalue = 1\n', "elements"),
    ('elements = 10\nquantity = "speed"\nvalue = 1\n', "quantity"),
    ('elements = 10\nquantity = "gain"\nvalue = 1\n', "removal"),
    ('elements = 10\nquantity = "ratio"\n', "value"),
    ('elements = 10\nquantity = "outliers"\nvalue = "1/2"\n', "value"),
    ('elements = 10\nquantity = "outliers"\nvalue = 0\nrtol = 0.1\n', "rtol"),
    ('elements = 10\nends = "sliding"\nquantity = "ratio"\nvalue = 1\n', "ends"),
    ('elements = 10\nremoval = "magic"\nquantity = "ratio"\nvalue = 1\n', "removal"),
    ('elements = 10\nquantity = "ratio"\nvalue = "__import__(1)"\n', "value"),
])
def test_bad_mesh_claims_name_their_field(extra, field):
    with pytest.raises(InputError, match=f"field '{field}'"):
        parse_claims(BASE + extra)


def test_a_mesh_claim_can_fail_and_names_the_mesh():
    # the table: the lumped p = 2 bar with free ends, omega_max h / c = 2.320 (3 digits)
    good = parse_claims(BASE + 'elements = 60\nends = "free"\nquantity = "omega_max"\n'
                        'value = 2.32003\nrtol = 1e-5\n')
    bad = parse_claims(BASE + 'elements = 60\nends = "free"\nquantity = "omega_max"\n'
                       'value = 1.2247\nrtol = 1e-3\n')
    res = verify_claims(good + [c for c in bad], jobs=1)
    assert [r.status for r in res.results] == ["holds", "differs"]
    assert good[0].model.label() == "bar p=2 N=60 free-free, lumped mass"


def test_manni_claims_file_verifies():
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "examples" / "literature" / "manni2022.toml"
    result = verify_claims(load_claims(path), jobs=1)
    assert result.passed, [(r.name, r.status, r.difference) for r in result.results]
