"""Fully discrete dispersion (dispersion.waves.fully_discrete): closed forms and series."""
from __future__ import annotations

import numpy as np
import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

from dispersion.errors import InputError
from dispersion.waves.fully_discrete import (
    fully_discrete_series,
    time_frequency,
    time_scheme,
    time_series,
)


@settings(max_examples=50, deadline=None)
@given(w=st.floats(1e-3, 10), frac=st.floats(0.01, 1.0))
def test_central_differences_closed_form(w, frac):
    # Hughes 2000, 9.3: sin(omega dt / 2) = omega_h dt / 2, stable for omega_h dt <= 2
    tau = frac * 2 / w
    got = float(time_frequency(np.array([w]), tau)[0])
    assert np.sin(got * tau / 2) == pytest.approx(w * tau / 2, rel=1e-12, abs=1e-15)


def test_trapezoidal_closed_form_and_unstable_nan():
    # average acceleration: tan(omega dt / 2) = omega_h dt / 2 (Hughes 2000, 9.3)
    w, tau = np.array([0.5, 3.0, 40.0]), 0.2
    got = time_frequency(w, tau, "average-acceleration")
    assert np.allclose(np.tan(got * tau / 2), w * tau / 2, rtol=1e-12)
    assert np.isnan(time_frequency(np.array([2.01]), 1.0)[0])  # beyond 2 / omega_h


def test_general_newmark_matches_gamma_half_branch():
    # the complex-root path (gamma != 1/2) tends to the closed form as gamma -> 1/2
    w, tau = np.array([0.3, 1.1]), 0.5
    near = time_frequency(w, tau, time_scheme("newmark", 0.25, 0.5 + 1e-9))
    assert np.allclose(near, time_frequency(w, tau, "average-acceleration"), rtol=1e-7)
    with pytest.raises(InputError, match="gamma"):
        time_scheme("newmark", 0.25, 0.4)


def test_time_series_matches_arcsin_expansion():
    # (2 arcsin(x/2))^2 = x^2 + x^4/12 + x^6/90 + x^8/560 (sympy's own series, independent)
    x = sympy.Symbol("x")
    ref = sympy.series((2 * sympy.asin(x / 2)) ** 2, x, 0, 10).removeO()
    assert [ref.coeff(x, 2 * m) for m in range(1, 5)] == time_series(4)


def test_magic_time_step_p1_lumped_bar_is_exact():
    # p = 1 lumped bar, central differences at C = 1 (tau = h / c): omega = c k exactly, so
    # the fully discrete series in theta with tau = 1 is theta^2 with no error term
    from dispersion.waves.timestep import bar_omega_squared

    z, theta = sympy.Symbol("z"), sympy.Symbol("kappa")
    semi = sympy.series(bar_omega_squared("lumped", 1).subs(z, sympy.cos(theta)), theta, 0, 11)
    coeffs = {k: semi.removeO().coeff(theta, k) for k in range(1, 11)}
    series = fully_discrete_series(coeffs, 10)
    assert sympy.expand(series.subs(sympy.Symbol("tau"), 1)) == theta**2
    # and at half the step an error of order kappa^4 remains: -1/12 + 1/48 = -1/16
    assert sympy.expand(series.subs(sympy.Symbol("tau"), sympy.Rational(1, 2))).coeff(
        theta, 4) == sympy.Rational(-1, 16)


def test_fully_discrete_error_tends_to_the_semi_discrete_one():
    # as the step goes to zero the time error vanishes like tau^2: at C = 0.01 the fully
    # discrete error differs from the semi-discrete one by ~1e-4 of the C = 1 difference
    from dispersion.symbolic.plate import plate_patch
    from dispersion.waves.discrete_branches import fundamental_branches
    from dispersion.waves.exact_branches import trace_branches
    from dispersion.waves.fully_discrete import fully_discrete_error

    patch, kappa = plate_patch(mass="lumped"), np.array([0.3])
    semi = fundamental_branches(patch, 0.3, kappa)
    exact = trace_branches(0.3, kappa, 3.0).omega
    for label in ("S0", "A0"):
        semi_err = semi[label][0] / exact[label][0] - 1
        big = fully_discrete_error(patch, 0.3, kappa, 1.0)[label][0] - semi_err
        small = fully_discrete_error(patch, 0.3, kappa, 0.01)[label][0] - semi_err
        assert big > 0 and abs(small) <= 2e-4 * big
