"""dispersion.claims.claim_model: the model keys of a claims entry become the one Patch value.

Searched with hypothesis through the real reader path (TOML text -> ``parse_claims``):

1. any valid model table yields a :class:`~dispersion.symbolic.patch.Patch` equal to the one
   built directly from the same values (the reference: ``Patch(**fields)`` with the numbers
   as exact rationals, never read from text), its label that patch's label;
2. a table with one invalid value (each key's invalid values listed below, each outside the
   range :class:`Patch` or the claims format states) raises ``InputError`` naming that key.

The periodic bar (:class:`~dispersion.claims.bar_model.BarModel`) and the exact plate
(:class:`~dispersion.claims.exact_model.ExactModel`) are checked the same way.
"""
from __future__ import annotations

import json
from fractions import Fraction

import pytest
import sympy
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dispersion.budget import BAR_P_MAX
from dispersion.claims import BarModel, ExactModel, parse_claims
from dispersion.claims.claim_model import PATCH_KEYS
from dispersion.errors import InputError
from dispersion.mass_rules.mass import CONTACT_SETS
from dispersion.mass_rules.mass_rule import RULE_NAMES, get_rule
from dispersion.symbolic.patch import Patch

QUICK = settings(max_examples=25, deadline=None, derandomize=True,
                 suppress_health_check=[HealthCheck.too_slow])
LONG = settings(max_examples=400, deadline=None,
                suppress_health_check=[HealthCheck.too_slow])
SERIES = {"branch": "S0", "coefficients": {"2": "2/(1-nu)"}}


def _toml(value) -> str:
    """A TOML value: numbers as written, a Fraction as the string "p/q", tables inline."""
    if isinstance(value, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {_toml(v)}" for k, v in value.items()) + "}"
    if isinstance(value, Fraction):
        return json.dumps(f"{value.numerator}/{value.denominator}")
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    return json.dumps(value)


def _entry(table: dict, kind: dict = SERIES) -> str:
    body = {"name": "c", **kind, **table}
    return "[[claim]]\n" + "\n".join(f"{json.dumps(k)} = {_toml(v)}" for k, v in body.items())


def _exact(q) -> sympy.Rational:
    q = Fraction(q)
    return sympy.Rational(q.numerator, q.denominator)


# a number as a claims file may write it: an integer, a decimal float, or a "p/q" string
def _written(q: Fraction):
    forms = [q]
    if q.denominator == 1:
        forms.append(int(q))
    if float(q) == q:  # exactly a binary float, so its shortest decimal reads back to q
        forms.append(float(q))
    return st.sampled_from(forms)


RATIOS = st.fractions(Fraction(1, 60), 1000, max_denominator=60).flatmap(_written)
GAMMAS = st.fractions(0, 1, max_denominator=16).flatmap(_written)


@st.composite
def model_tables(draw):
    """A valid model table: any subset of the patch keys, each in its range."""
    model = draw(st.sampled_from(["bloch", "x-exact", None]))  # None: the default (bloch)
    p = draw(st.integers(1, 3))
    n = draw(st.integers(max(p + 1, 3), p + 3))
    table = {"model": model, "p": p, "n": n,
             "r": draw(RATIOS) if model != "x-exact" else None,
             # the C0 Lagrange rules need x-exact and n = p e + 1: not a free draw here
             "mass": draw(st.sampled_from([m for m in RULE_NAMES
                                           if get_rule(m).basis == "bspline"])),
             "contact": draw(st.sampled_from(CONTACT_SETS)), "gamma_s": draw(GAMMAS)}
    if draw(st.booleans()):  # the top point's weights moved to the two below it
        w = draw(st.fractions(0, 1, max_denominator=8))
        table["weights"] = {str(n - 1): {str(n - 2): 1 - w, str(n - 3): w}}
    keep = set(draw(st.lists(st.sampled_from(sorted(table)), unique=True)))
    if keep & {"p", "weights"}:  # they are valid for the n drawn with them
        keep.add("n")
    out = {k: table[k] for k in sorted(keep) if table[k] is not None}
    # contact on both surfaces of n = 3 points: each surface's second neighbour is the other
    # surface (paper eqs 2-3), so only gamma_s = 0 is a patch (Patch states the rule)
    if (out.get("contact") == "both" and out.get("n", 3) == 3 and "weights" not in out
            and out.get("gamma_s", Fraction(1, 2)) != 0):
        out["contact"] = "top"
    return out


def _reference(table: dict) -> Patch:
    """The patch of ``table`` built directly from its values (unset keys: Patch's defaults)."""
    fields = {k: v for k, v in table.items() if k in ("p", "n", "mass", "contact", "model")}
    for key in ("r", "gamma_s"):
        if key in table:
            fields[key] = _exact(table[key])
    if "weights" in table:
        fields["weights"] = {int(c): {int(j): _exact(w) for j, w in ws.items()}
                             for c, ws in table["weights"].items()}
    return Patch(**fields)


def _check_round_trip(table):
    model = parse_claims(_entry(table))[0].model
    expected = _reference(table)
    assert isinstance(model, Patch) and model == expected, (table, model, expected)
    for key in PATCH_KEYS:
        assert getattr(model, key) == getattr(expected, key), key
    assert model.label() == expected.label()


@QUICK
@given(model_tables())
def test_any_valid_model_table_round_trips_to_its_patch(table):
    _check_round_trip(table)


@pytest.mark.slow
@LONG
@given(model_tables())
def test_any_valid_model_table_round_trips_to_its_patch_long(table):
    _check_round_trip(table)


#: Values outside each key's stated range (Patch, check_size, the claims format), or of the
#: wrong type.
INVALID = {
    "p": [0, -1, 25, 2.5, "2", True],
    "n": [1, 201, 3.0, "3", False],
    "r": [0, -1, "0", "1/0", "nan", 10**6, "1/1000000", "abc", True, 1e400],
    "mass": ["heavy", "", 3, "Singular"],
    "contact": ["left", "", 1, "both"],  # both: n = 3 and gamma_s = 1/2, see above
    "gamma_s": [2, -1, "3/2", "x", float("inf"), True],
    "weights": [{}, "w", {"a": {"1": 1}}, {"2": {"2": 1}}, {"2": {"1": Fraction(1, 2)}},
                {"9": {"1": 1}}, {"2": {"1": 2, "0": -1}}],
    "model": ["fem", "Bloch", 3],
}


@st.composite
def broken_tables(draw):
    """A valid singular-mass table with one key given a value outside its range."""
    key = draw(st.sampled_from(sorted(INVALID)))
    table = {"model": "bloch", "p": 2, "n": 3, "mass": "singular", "contact": "top",
             "gamma_s": Fraction(1, 2), "r": 2}
    table[key] = draw(st.sampled_from(INVALID[key]))
    return key, table


def _check_refused(key, table):
    with pytest.raises(InputError, match=f"field '{key}'"):
        parse_claims(_entry(table))


@QUICK
@given(broken_tables())
def test_an_invalid_model_value_is_refused_naming_its_key(case):
    _check_refused(*case)


@pytest.mark.slow
@LONG
@given(broken_tables())
def test_an_invalid_model_value_is_refused_naming_its_key_long(case):
    _check_refused(*case)


@pytest.mark.parametrize("key", ["p", "n", "gamma_s", "contact"])
def test_the_range_is_stated(key):
    value = {"p": 25, "n": 201, "gamma_s": 2, "contact": "left"}[key]
    with pytest.raises(InputError) as info:
        parse_claims(_entry({key: value}))
    assert {"p": "[1, 24]", "n": "200", "gamma_s": "[0, 1]", "contact": "top"}[key] in str(
        info.value)


def test_a_degree_too_high_for_the_default_n_names_the_degree():
    with pytest.raises(InputError, match="field 'p': .*n must be >= p \\+ 1 = 4, got 3"):
        parse_claims(_entry({"p": 3}))


def test_the_aspect_ratio_of_x_exact_is_refused():
    with pytest.raises(InputError, match="field 'r': the aspect ratio belongs to the bloch"):
        parse_claims(_entry({"model": "x-exact", "r": 2}))


# --------------------------------------------------------------------------- bar and exact

STEP = {"kind": "critical_step", "ratio": 1.5}


@QUICK
@given(st.integers(1, BAR_P_MAX), st.sampled_from([m for m in RULE_NAMES
                                                    if not get_rule(m).redistributes]))
def test_the_bar_holds_its_degree_and_mass(p, mass):
    # up to the cost bound of the bar's exact maximum (dispersion.budget; beyond it a claim
    # is refused before work: tests/test_writer_findings.py, finding 8)
    model = parse_claims(_entry({"model": "bar", "p": p, "mass": mass}, STEP))[0].model
    assert model == BarModel(p, mass) and model.label() == f"periodic bar p={p}, {mass} mass"


@pytest.mark.parametrize("key,value", [("p", 0), ("p", 25), ("p", 2.0), ("mass", "singular"),
                                       ("mass", "heavy"), ("n", 3), ("r", 2), ("contact", "top"),
                                       ("gamma_s", 0), ("weights", {"2": {"1": 1}})])
def test_the_bar_refuses_what_it_has_not(key, value):
    with pytest.raises(InputError, match=f"field '{key}'"):
        parse_claims(_entry({"model": "bar", key: value}, STEP))


def test_the_bar_is_a_model_of_the_explicit_claims_only():
    with pytest.raises(InputError, match="field 'model'.*got 'bar'"):
        parse_claims(_entry({"model": "bar"}))


@pytest.mark.parametrize("key", PATCH_KEYS)
def test_the_exact_model_has_no_patch_keys(key):
    value = {"weights": {"2": {"1": 1}}, "mass": "lumped", "contact": "top"}.get(key, 2)
    assert parse_claims(_entry({"model": "rayleigh-lamb"}))[0].model == ExactModel()
    with pytest.raises(InputError, match=f"field '{key}': not a setting of the exact model"):
        parse_claims(_entry({"model": "rayleigh-lamb", key: value}))
