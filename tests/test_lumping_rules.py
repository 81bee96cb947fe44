"""The rules of the lumping literature (dispersion.mass_rules.lumping_rules and its modules):
quadrature exactness, closed-form critical steps, spectra, stated costs, leading error terms
(two routes), and the order_range / relative_to claims."""
from __future__ import annotations

import math

import pytest
import sympy
from hypothesis import example, given, settings
from hypothesis import strategies as st

from dispersion.errors import InputError
from dispersion.splines.bspline import open_knot_vector
from dispersion.splines.interpolatory_spline import interpolatory_weights
from dispersion.mass_rules.lumping_rules import ENTRIES
from dispersion.mass_rules.rule_families import approximate_dual_rule, sms_rule
from dispersion.mass_rules.mass_rule import RULES, get_rule, x_mass_coefficients
from dispersion.discretization.leading_error import bar_leading_term
from dispersion.time_stepping.timestep import _z, bar_omega_max, bar_omega_squared

NEW = tuple(ENTRIES)


def test_every_new_rule_is_registered_with_source_and_cost():
    for name in NEW:
        rule = get_rule(name)
        assert rule.description and rule.explicit_cost.describe()
    assert RULES["dual-gram"].explicit_cost.stiffness == "dense"
    assert RULES["dual-lumped"].explicit_cost.mass == "banded"
    assert RULES["dual-consistent"].explicit_cost.stiffness == "banded-wide"


@settings(max_examples=5, deadline=None)
@given(p=st.integers(1, 4), ne=st.integers(1, 6))
@example(p=1, ne=1)
@example(p=4, ne=6)
def test_interpolatory_quadrature_integrates_polynomials(p, ne):
    # sum_q w_q g_q^k = int_0^1 x^k = 1/(k+1) for k <= p (closed form, independent)
    kv = open_knot_vector(p, ne)
    w = interpolatory_weights(kv)
    g = kv.greville()
    for k in range(p + 1):
        assert sum(wq * gq**k for wq, gq in zip(w, g)) == sympy.Rational(1, k + 1)


@pytest.mark.parametrize("p", [1, 2, 3, pytest.param(4, marks=pytest.mark.slow)])
def test_sms_critical_step_closed_form(p):
    # Omega_max^2 = d_max / (1 + beta d_max), d_max the lumped bar's (m = 1) maximum
    beta = sympy.Rational(1, 2)
    d_max = bar_omega_max("lumped", p)[0] ** 2
    # at 40 digits (the maxima are algebraic numbers: simplifying them exactly is slow)
    d = sympy.N(d_max, 40)
    assert abs(sympy.N(bar_omega_max("sms", p)[0] ** 2, 40) - d / (1 + beta * d)) < 1e-30
    assert abs(sympy.N(bar_omega_max(sms_rule(1), p)[0] ** 2, 40) - d / (1 + d)) < 1e-30


@pytest.mark.parametrize("name", ["dual-gram", "dual-consistent"])
def test_dual_rules_without_lumping_have_the_consistent_spectrum(name):
    for p in (1, 2, 3):
        assert sympy.cancel(bar_omega_squared(name, p) - bar_omega_squared("consistent", p)) == 0


def test_reproduction_degree_zero_is_row_sum_lumping():
    for p in (1, 2, 3):
        assert sympy.cancel(bar_omega_squared(approximate_dual_rule(0), p)
                            - bar_omega_squared("lumped", p)) == 0


def test_interpolatory_periodic_row_is_nodal_greville():
    for p in (1, 2, 3, 4):
        assert x_mass_coefficients("interpolatory-nodal", p) == \
            x_mass_coefficients("nodal-greville", p)


@pytest.mark.parametrize("rule", ["consistent", "lumped", "dual-lumped", "sms",
                                  pytest.param("interpolatory-nodal", marks=pytest.mark.slow)])
@pytest.mark.parametrize("p", [1, 2])
def test_bar_leading_term_two_routes(rule, p):
    # exact power series of the symbols against sympy's series of the rational function
    th = sympy.Symbol("theta")
    k, c = bar_leading_term(rule, p, 2 * p + 4)
    f = bar_omega_squared(rule, p).subs(_z, sympy.cos(th))
    ser = sympy.expand(sympy.series(f / th**2 - 1, th, 0, 2 * p + 5).removeO())
    assert ser.coeff(th, k) == sympy.Rational(c)
    assert all(ser.coeff(th, j) == 0 for j in range(k))


def test_dual_lumped_keeps_consistent_order_and_lumped_does_not():
    for p in (1, 2, 3, 4):
        kc = bar_leading_term("consistent", p, 2 * p + 4)[0]
        assert kc == 2 * p  # Cottrell et al. 2006: omega error O(theta^(2p))
        assert bar_leading_term("dual-lumped", p, 2 * p + 4)[0] == kc
        assert bar_leading_term("lumped", p, 2 * p + 4)[0] == 2


def test_sms_beta_checked():
    with pytest.raises(InputError, match="beta"):
        sms_rule(-1)
    with pytest.raises(InputError, match="reproduction degree"):
        approximate_dual_rule(-1)


def test_study_small():
    from dispersion.studies.lumping_orders import lumping_orders

    res = lumping_orders(degrees=(2,), rules=("consistent", "lumped", "dual-lumped"))
    keeps = {(r.rule, r.model): r.keeps_order for r in res.terms}
    assert keeps[("dual-lumped", "plate S0")] and keeps[("dual-lumped", "bar")]
    assert not keeps[("lumped", "bar")]
    assert res.to_json()["terms"] and res.rows() and "rules" in repr(res)


ORDER = '''
[[claim]]
name = "x"
kind = "order_range"
model = "bar"
mass = "dual-lumped"
p_from = {p_from}
p = 2
'''


def test_order_claim_parse_and_refusals():
    from dispersion.claims.schema import parse_claims
    from dispersion.claims.verify import verify_claims

    claims = parse_claims(ORDER.format(p_from=1))
    assert verify_claims(claims).results[0].status == "holds"
    with pytest.raises(InputError, match="p_from"):
        parse_claims(ORDER.format(p_from=3))
    with pytest.raises(InputError, match="square-element"):
        parse_claims(ORDER.format(p_from=1).replace('"bar"', '"bloch"\nbranch = "S0"\nn = 4'))
    with pytest.raises(InputError, match="relative_to"):
        parse_claims('[[claim]]\nname = "y"\nkind = "critical_step"\nmodel = "bar"\np = 1\n'
                     'mass = "sms"\nratio = 1.5\nrelative_to = "nope"\n')


def test_relative_step_claim():
    from dispersion.claims.schema import parse_claims
    from dispersion.claims.verify import verify_claims

    text = ('[[claim]]\nname = "y"\nkind = "critical_step"\nmodel = "bar"\np = 1\n'
            f'mass = "sms"\nratio = {math.sqrt(3)!r}\nrelative_to = "lumped"\n')
    assert verify_claims(parse_claims(text)).results[0].status == "holds"


@pytest.mark.parametrize("mass", ["sem-consistent", "sem-lumped"])
@pytest.mark.parametrize("p", [1, 2, 3, 4])
def test_sem_acoustic_series_matches_the_bloch_pencil(mass, p):
    # exact series (condensation + reversion) against the p x p Bloch pencil's lowest root
    from dispersion.splines.lagrange_sem import acoustic_series
    from dispersion.discretization.sem_bar import sem_bar_frequency

    theta = 0.4
    s = acoustic_series(mass, p, 2 * p + 8)
    lam = theta**2 * sum(float(c) * theta ** (2 * k) for k, c in enumerate(s))
    assert float(sem_bar_frequency(mass, p, theta)) ** 2 == pytest.approx(lam, rel=1e-9)


def test_sem_p1_is_the_linear_element():
    # p = 1: C0 linear elements are the p = 1 B-splines; GLL lumping is row-sum lumping
    from dispersion.time_stepping.timestep import critical_step

    for sem, bsp in (("sem-consistent", "consistent"), ("sem-lumped", "lumped")):
        assert bar_leading_term(sem, 1, 6) == bar_leading_term(bsp, 1, 6)
        assert critical_step(sem, 1, model="bar", wave_speed=1.0).omega_max == \
            pytest.approx(critical_step(bsp, 1, model="bar", wave_speed=1.0).omega_max)


def test_sem_on_the_plate_x_exact_only():
    from dispersion.symbolic.patch import Patch

    with pytest.raises(InputError, match="Lagrange elements"):
        Patch(p=2, n=5, mass="sem-lumped")
    with pytest.raises(InputError, match="n - 1 divisible by p"):
        Patch(p=2, n=4, model="x-exact", mass="sem-lumped")
    assert Patch(p=2, n=5, model="x-exact", mass="sem-lumped").basis == "lagrange"


def test_sms_family_member_on_the_plate_uses_its_own_beta():
    from dispersion.symbolic.plate import plate_patch

    patch = plate_patch(p=1, n=3, mass=sms_rule(1))
    assert dict(patch.x_mass) == {-1: -1, 0: 3, 1: -1}   # 1 + 1 * (-1, 2, -1)
