"""Leading-error-term claims (``dispersion/claims/orders.py``): the exact kind tells rules of
one order apart, the bound keeps its old key readable, bad fields are refused."""
from __future__ import annotations

import pytest

from dispersion.claims.schema import parse_claims
from dispersion.claims.verify import verify_claims
from dispersion.errors import InputError

TERM = '''
[[claim]]
name = "t"
kind = "leading_term"
model = "bar"
mass = "{mass}"
p = {p}
power = {power}
coefficient = "{c}"
'''

RANGE = '''
[[claim]]
name = "r"
kind = "order_range"
model = "bar"
mass = "{mass}"
p_from = 1
p = {p}
{key} = "consistent"
'''


def _status(text: str) -> str:
    return verify_claims(parse_claims(text), jobs=1).results[0].status


def test_q1_and_q2_share_the_order_at_p2_but_not_the_coefficient():
    # reference: the series of 6 (1 - cos t)/(2 + cos t) (consistent, the q = p dual-lumped)
    # and the exact symbol of S_1 on the p = 2 bar; -19/360 = 1/720 - 13/240 * 1 (the q = 1
    # truncation of 1/g(w) misses t_2 w^2 = 13/240 theta^4 of the full inverse)
    assert _status(TERM.format(mass="dual-lumped", p=2, power=4, c="1/720")) == "holds"
    assert _status(TERM.format(mass="dual-lumped-q1", p=2, power=4, c="-19/360")) == "holds"
    assert _status(TERM.format(mass="dual-lumped-q1", p=2, power=4, c="1/720")) == "differs"
    assert _status(TERM.format(mass="dual-lumped", p=2, power=2, c="1/720")) == "differs"
    # the bound cannot tell them apart; the exact comparison can
    for key, q1 in (("at_least_order_of", "holds"), ("same_order_as", "holds"),
                    ("same_leading_term_as", "differs")):
        assert _status(RANGE.format(mass="dual-lumped-q1", p=2, key=key)) == q1, key
        assert _status(RANGE.format(mass="dual-lumped", p=2, key=key)) == "holds", key


def test_thirteen_two_hundred_fortieths_is_the_missing_term():
    # independent check of -19/360: 1/720 - 13/240 (dual_symbol(2, 2) prints t_2 = 13/240)
    from fractions import Fraction

    from dispersion.mass_rules.approximate_dual import dual_symbol

    s2, s1 = dual_symbol(2, 2), dual_symbol(2, 1)
    w2 = {-2: 1, -1: -4, 0: 6, 1: -4, 2: 1}  # (2 - 2 cos)^2: theta^4 + O(theta^6)
    t2 = Fraction(str(s2[2] - s1.get(2, 0)))
    assert all(Fraction(str(s2[L] - s1.get(L, 0))) == t2 * w2[L] for L in w2)
    assert Fraction(1, 720) - t2 == Fraction(-19, 360)


def test_deprecated_key_is_named_in_the_claim_text():
    claim = parse_claims(RANGE.format(mass="dual-lumped", p=2, key="same_order_as"))[0]
    assert "deprecated" in claim.written and "at_least_order_of" in claim.written


def test_plate_coefficient_exact_in_nu():
    text = '''
[[claim]]
name = "a0"
kind = "leading_term"
model = "bloch"
branch = "A0"
mass = "consistent"
p = 1
power = 4
coefficient = "(4*nu**2 - 3*nu + 1)/(12*(nu - 1)*(2*nu - 1))"
'''
    assert _status(text) == "holds"
    assert _status(text.replace("- 3*nu", "- 3.001*nu")) == "differs"


@pytest.mark.parametrize("change, field", [
    (("power = 4", "power = 3"), "power"),
    (("power = 4", "power = 40"), "power"),
    (('coefficient = "1/720"', 'coefficient = "nu/720"'), "coefficient"),
    (('coefficient = "1/720"', 'coefficient = "0"'), "coefficient"),
    (('coefficient = "1/720"', 'coefficient = "__import__(1)"'), "coefficient"),
    (('mass = "dual-lumped"', 'mass = "dual-lumped-q9"'), "mass"),
])
def test_leading_term_refusals(change, field):
    text = TERM.format(mass="dual-lumped", p=2, power=4, c="1/720").replace(*change)
    with pytest.raises(InputError, match=field):
        parse_claims(text)


def test_one_comparison_only():
    text = RANGE.format(mass="dual-lumped", p=2, key="same_leading_term_as") \
        + 'at_least_order_of = "lumped"\n'
    with pytest.raises(InputError, match="one comparison"):
        parse_claims(text)
