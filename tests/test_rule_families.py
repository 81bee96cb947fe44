"""Members of the literature's rule families by name (``dispersion/symbolic/rule_families.py``),
and the promise of the reproduction degree: on the periodic bar the approximate dual of
degree q, row-sum lumped, errs at theta^min(2q + 2, 2p), and q = p has the consistent mass's
leading term (docs/promises.md). Reference: the middle row of the approximate-dual matrix
assembled on an open uniform mesh (the Chui-He-Stoeckler levels, exact rationals; not the
Taylor route of ``dual_symbol`` the rule uses) times the middle row of the assembled
derivative Gram matrix, summed as a Bloch symbol in mpmath at 100 digits at theta = 1e-5
and 5e-6 (no series)."""
from __future__ import annotations

from fractions import Fraction

import mpmath
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from dispersion.errors import InputError
from dispersion.mass_rules.mass_rule import get_rule
from dispersion.mass_rules.rule_families import approximate_dual_rule, family_rule
from dispersion.discretization.leading_error import bar_leading_exact


def test_family_names_are_read_whole_and_bounded():
    assert get_rule("dual-lumped-q1") is approximate_dual_rule(1)
    assert get_rule("dual-lumped-q0").name == "dual-lumped-q0"
    for bad in ("dual-lumped-q01", "dual-lumped-q9", " dual-lumped-q1", "dual-lumped-q-1",
                "dual-lumped-q1 ", "dual-lumped-q", "DUAL-LUMPED-Q1", "dual-lumped-q1" * 3):
        assert family_rule(bad) is None, bad
        with pytest.raises(InputError, match="dual-lumped-q<q>"):
            get_rule(bad)


def _middle_row(A) -> dict[int, Fraction]:
    mid = A.rows // 2
    return {j - mid: Fraction(int(A[mid, j].p), int(A[mid, j].q))
            for j in range(A.rows) if A[mid, j] != 0}


def _bar_error(p: int, q: int, theta: str):
    """omega_h^2 h^2 / theta^2 - 1 of the row-sum lumped Petrov-Galerkin bar (S K u = w^2 u),
    from the assembled open-mesh rows (h = 1/n_el: both rows scale as 1/h)."""
    from dispersion.mass_rules.approximate_dual import approximate_dual_matrix
    from dispersion.splines.bspline import open_knot_vector
    from dispersion.splines.derivative_gram import derivative_gram

    n_el = 3 * p + 6  # the middle rows of both matrices reach no boundary knot
    kv = open_knot_vector(p, n_el)
    s, k = _middle_row(approximate_dual_matrix(kv, q)), _middle_row(derivative_gram(kv))
    with mpmath.workdps(100):
        th = mpmath.mpf(theta)
        h = mpmath.mpf(1) / n_el

        def symbol(row):
            return sum(mpmath.mpf(v.numerator) / v.denominator * h * mpmath.cos(L * th)
                       for L, v in row.items())

        return symbol(k) * symbol(s) / th**2 - 1


def _check(p: int, q: int) -> None:
    k, c = bar_leading_exact(f"dual-lumped-q{q}", p, 2 * p + 4)
    assert k == min(2 * q + 2, 2 * p), (p, q, k)
    if q == p:
        assert (k, c) == bar_leading_exact("consistent", p, 2 * p + 4)
    e1, e2 = _bar_error(p, q, "1e-5"), _bar_error(p, q, "5e-6")
    with mpmath.workdps(100):
        assert abs(e1 / e2 - 2**k) < 1e-4 * 2**k, (p, q, e1 / e2)
        lead = e1 / mpmath.mpf("1e-5") ** k
        assert abs(lead - mpmath.mpf(c.numerator) / c.denominator) < 1e-4 * abs(lead), \
            (p, q, lead, c)


@settings(max_examples=4, deadline=None)
@given(p=st.integers(1, 2), data=st.data())
@example(p=1, data=None)
@example(p=2, data=None)
def test_reproduction_degree_sets_the_bar_order(p, data):
    q = data.draw(st.integers(0, p)) if data is not None else (0 if p == 1 else 1)
    _check(p, q)


@pytest.mark.slow
@pytest.mark.parametrize("p", [1, 2, 3, 4])
def test_reproduction_degree_sets_the_bar_order_every_q(p):
    for q in range(p + 1):
        _check(p, q)
