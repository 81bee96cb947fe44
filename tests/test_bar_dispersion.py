"""1D bar dispersion of periodic B-splines: closed forms for p = 1, 2 and the error orders."""
from __future__ import annotations

import math

import numpy as np
import pytest

from dispersion.discretization.bar_dispersion import bar_dispersion, bar_frequency
from dispersion.errors import InputError


def test_linear_closed_forms():
    # p = 1: consistent (omega h)^2 = 6 (1 - c)/(2 + c), lumped 2 (1 - c), c = cos kh
    theta = np.linspace(0.01, math.pi, 17)
    c = np.cos(theta)
    assert np.allclose(bar_frequency(1, "consistent", theta) ** 2, 6 * (1 - c) / (2 + c))
    assert np.allclose(bar_frequency(1, "lumped", theta) ** 2, 2 * (1 - c))


def test_quadratic_against_an_independent_gram_integral():
    # p = 2: Gram integrals of the cardinal quadratic B-spline computed here by Gauss quadrature
    def n2(u):  # cardinal quadratic B-spline on [0, 3]
        return np.where(u < 1, u**2 / 2, np.where(u < 2, (-2 * u**2 + 6 * u - 3) / 2,
                                                  (3 - u) ** 2 / 2)) * ((u >= 0) & (u <= 3))

    def dn2(u):
        return np.where(u < 1, u, np.where(u < 2, -2 * u + 3, u - 3)) * ((u >= 0) & (u <= 3))

    x, w = np.polynomial.legendre.leggauss(6)
    pts = np.concatenate([(x + 1) / 2 + e for e in range(3)])
    wts = np.tile(w / 2, 3)
    m = {L: float(np.sum(wts * n2(pts) * n2(pts - L))) for L in range(-2, 3)}
    d = {L: float(np.sum(wts * dn2(pts) * dn2(pts - L))) for L in range(-2, 3)}
    theta = np.linspace(0.05, math.pi, 9)
    ref = sum(d[L] * np.cos(L * theta) for L in d) / sum(m[L] * np.cos(L * theta) for L in m)
    assert np.allclose(bar_frequency(2, "consistent", theta) ** 2, ref, rtol=1e-12)


@pytest.mark.parametrize("p", [1, 2, 3])
def test_error_orders(p):
    # consistent mass: relative frequency error ~ (kh)^(2p) (Cottrell et al. 2006);
    # row-sum lumped: ~ (kh)^2 for every p
    theta = np.array([0.05, 0.1, 0.2])
    for mass, q in (("consistent", 2 * p), ("lumped", 2)):
        e = np.abs(bar_frequency(p, mass, theta) / theta - 1)
        slope = np.polyfit(np.log(theta), np.log(e), 1)[0]
        assert slope == pytest.approx(q, abs=0.05), (mass, slope)


def test_sign_of_the_error():
    # consistent mass over-estimates the frequency, lumped mass under-estimates it
    bd = bar_dispersion((1, 2, 3), elements_per_wavelength=[4.0, 10.0, 40.0])
    for key, err in bd.error.items():
        assert np.all(err > 0) if "consistent" in key else np.all(err < 0), key


def test_bad_input():
    with pytest.raises(InputError):
        bar_frequency(2, "singular", 0.1)
    with pytest.raises(InputError):
        bar_dispersion(elements_per_wavelength=[1.0])


@pytest.mark.parametrize("mass", ["singular", "singular-lumped"])
def test_one_bar_rule_check_for_dispersion_and_time_step(mass):
    # one check (bar_dispersion.bar_rule) refuses a contact mass for the periodic bar in
    # both places that use it, with the same message
    from dispersion.discretization.bar_dispersion import bar_rule
    from dispersion.time_stepping.timestep import bar_omega_squared

    with pytest.raises(InputError) as direct:
        bar_rule(mass)
    for call in (lambda: bar_frequency(2, mass, [0.5]), lambda: bar_omega_squared(mass, 2)):
        with pytest.raises(InputError) as got:
            call()
        assert str(got.value) == str(direct.value)
    assert "periodic bar" in str(direct.value)
