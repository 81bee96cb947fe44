"""The orders promise of the lumping rules (docs/promises.md), searched over its domain
against an independent computation: the discrete S0 / A0 frequencies of the Bloch patch at 80
digits (tests/mp_pencil.py, no characteristic polynomial, no series) and the exact
Rayleigh-Lamb roots (tests/mp_lamb.py): the error falls as kappa^k with k the consistent
mass's leading power, for every degree and Poisson's ratio."""
from __future__ import annotations

import mpmath
import pytest
import sympy
from hypothesis import example, given, settings
from hypothesis import strategies as st
from mp_lamb import mp_F
from mp_pencil import mp_frequencies

from dispersion.symbolic.plate import plate_patch
from dispersion.discretization.leading_error import plate_leading_terms, square_patch

#: Nu from near -1 to near 1/2 (the ends of its range as explicit examples).
NU = st.fractions(sympy.Rational(-9, 10), sympy.Rational(12, 25), max_denominator=50)


def _error(patch, nu, kappa, branch):
    with mpmath.workdps(80):
        disc = mp_frequencies(patch, nu, kappa, dps=80)[0 if branch == "A0" else 1]
        kind = "S" if branch == "S0" else "A"
        exact = mpmath.findroot(lambda w: mp_F(kind, mpmath.mpf(kappa), w, mpmath.mpf(nu)),
                                disc)
        return disc**2 - exact**2


def _check(rule, p, nu, branch):
    k = plate_leading_terms("consistent", p, 2 * p + 4)[f"plate {branch}"][0]
    patch = plate_patch(square_patch(rule, p))
    nu = sympy.Rational(nu)
    e1, e2 = (_error(patch, nu, kap, branch) for kap in ("0.002", "0.001"))
    with mpmath.workdps(80):
        rate = mpmath.log(abs(e1 / e2), 2)
    # leading term kappa^k: the rate is k up to O(kappa^2) corrections (and at least k when
    # the leading coefficient happens to vanish at this nu)
    assert float(rate) > k - 0.05, (rule, p, float(nu), branch, float(rate), k)


@settings(max_examples=4, deadline=None)
@given(p=st.integers(1, 2), nu=NU, branch=st.sampled_from(["S0", "A0"]))
@example(p=2, nu=sympy.Rational(-9, 10), branch="S0")
def test_dual_lumped_keeps_the_consistent_order(p, nu, branch):
    _check("dual-lumped", p, nu, branch)


@pytest.mark.slow
@settings(max_examples=25, deadline=None)
@given(p=st.integers(1, 4), nu=NU, branch=st.sampled_from(["S0", "A0"]),
       rule=st.sampled_from(["dual-lumped", "dual-gram", "dual-consistent"]))
@example(p=4, nu=sympy.Rational(12, 25), branch="A0", rule="dual-lumped")
@example(p=4, nu=sympy.Rational(-9, 10), branch="S0", rule="dual-lumped")
@example(p=1, nu=sympy.Rational(0), branch="S0", rule="dual-lumped")
def test_rules_keep_the_consistent_order_every_degree(p, nu, branch, rule):
    _check(rule, p, nu, branch)


def test_row_sum_lumping_does_not():
    # the search can fail: lumped p = 2 falls as kappa^4, not the consistent kappa^6
    with pytest.raises(AssertionError):
        _check("lumped", 2, sympy.Rational(3, 10), "S0")
