"""Fitted orders inside the window the error series allows (``dispersion/studies/asymptotic_fit.py``)."""
from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dispersion.studies import asymptotic_fit as A

NU = Fraction(3, 10)
SINGULAR_R2 = {"p": 2, "n": 3, "model": "bloch", "r": 2, "mass": "singular", "contact": "top",
               "gamma_s": 0}

coef = st.fractions(min_value=Fraction(-1000), max_value=Fraction(1000)).filter(lambda c: c != 0)


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 4), coef, st.lists(st.tuples(st.integers(1, 6), coef), max_size=4))
def test_window_satisfies_its_rule_and_is_maximal(m, cm, later):
    series = {m: cm}
    for gap, c in later:
        series[m + gap] = c
    w = A.asymptotic_window(series)
    lead = lambda k: abs(float(cm)) * k**m  # noqa: E731
    rest = lambda k: sum(abs(float(c)) * k**j for j, c in series.items() if j > m)  # noqa: E731
    if len(series) == 1:  # nothing bounds the window from above: no window is claimed
        assert w is None and A.asymptotic_window(series, kappa_max=1.0) is not None or (
            A.asymptotic_window(series, kappa_max=1.0) is None
            and (A.ERROR_FLOOR / abs(float(cm))) ** (1 / m) * A.MIN_SPAN > 1.0)
        return
    if w is None:  # empty: the dominance ends below twice the floor's kappa, or never ends
        k2 = A.MIN_SPAN * (A.ERROR_FLOOR / abs(float(cm))) ** (1 / m)
        assert (lead(k2) < A.LEAD_OVER_REST * rest(k2) * (1 + 1e-9)
                or lead(1e6) >= A.LEAD_OVER_REST * rest(1e6))
        return
    lo, hi = w
    assert hi >= A.MIN_SPAN * lo
    assert math.isclose(lead(lo), A.ERROR_FLOOR, rel_tol=1e-9)
    for k in np.geomspace(lo, hi, 7):  # the leading term dominates on the whole window
        assert lead(k) >= A.LEAD_OVER_REST * rest(k) * (1 - 1e-9)
    if len(series) > 1:  # and the window is as wide as the rule allows
        assert lead(hi * 1.001) < A.LEAD_OVER_REST * rest(hi * 1.001)


def test_fit_recovers_a_power_law_and_refuses_noise_and_empty_windows():
    series = {2: Fraction(1, 100), 4: Fraction(-1, 10)}
    exact = A.fit_in_window(series, lambda k: 0.01 * k**2 - 0.1 * k**4)
    assert exact["verdict"] == "fitted" and abs(exact["fitted"] - exact["series_slope"]) < 1e-9
    rng = np.random.default_rng(1)
    noisy = A.fit_in_window(series, lambda k: 0.01 * k**2 * np.exp(rng.normal(0, 0.5, k.size)))
    assert noisy["fitted"] is None or noisy["verdict"] != "fitted"
    assert noisy["verdict"].startswith("no order") and noisy["window"] is not None
    tight = A.fit_in_window({2: Fraction(1, 10**6), 4: Fraction(10**3)}, lambda k: k)
    assert tight["window"] is None and tight["verdict"].startswith("no window")
    assert A.fit_in_window({}, lambda k: k)["verdict"].startswith("no window")


def test_error_series_agrees_with_the_numeric_branches():
    # independent: the numeric eigenvalues of the patch against the traced exact roots, at
    # kappa where the series' next unknown term is negligible (the series from the symbolic
    # determinant, the numbers from the float pencil and the root tracer)
    from dispersion.symbolic.plate import plate_patch
    from dispersion.continuum.exact_branches import exact_fundamental
    from dispersion.discretization.discrete_branches import fundamental_branches

    series = A.relative_error_series("A0", NU, **SINGULAR_R2)
    assert min(series) == 2
    kappa = np.array([0.01, 0.03, 0.1])
    num = fundamental_branches(plate_patch(**SINGULAR_R2), 0.3, kappa)["A0"]
    measured = num / exact_fundamental("A", kappa, 0.3) - 1
    predicted = sum(float(c) * kappa**k for k, c in series.items())
    # rule: inside the radius, with terms falling geometrically, the truncation error is below
    # the last term kept; plus 1e-12 for the float solvers
    last = max(series)
    bound = abs(float(series[last])) * kappa**last + 1e-12
    assert np.all(np.abs(measured - predicted) <= bound)
    assert np.all(np.abs(measured - predicted) < 1e-3 * np.abs(measured))


@pytest.mark.slow  # traces and pairs 10 kappas for one patch: about 2 s on a loaded machine
def test_singular_a0_order_is_two_inside_its_window():
    # issue 18: fitted over kappa in [0.04, 0.16] the singular A0 order was 1.35 (predicted 2)
    from dispersion.studies.branch_study import _orders
    from dispersion.symbolic.patch import Patch

    (s0, a0) = _orders(0.3, patches=[Patch(**SINGULAR_R2)])
    assert a0["verdict"] == "fitted" and a0["series_order"] == 2
    assert abs(a0["fitted"] - 2) < 0.05
    assert a0["window"][1] < 0.1 and a0["points"] == A.POINTS
    assert s0["verdict"] == "fitted" and abs(s0["fitted"] - 2) < 0.05


@pytest.mark.parametrize("mass,order", [("consistent", 4), ("singular", 2)])
def test_leading_power_of_the_error_matches_the_power_balance(mass, order):
    # the S0 relative error's leading power = (first power where Omega^2 series differ) - 2
    from dispersion.symbolic.power_balance import discrete_series, first_difference
    from dispersion.continuum.exact_series import exact_series

    kw = dict(SINGULAR_R2, mass=mass)
    d, e = discrete_series("S0", 8, **kw), exact_series("S0", 8)
    assert first_difference(d, e) - 2 == order == min(A.relative_error_series("S0", NU, order=8,
                                                                                **kw))
