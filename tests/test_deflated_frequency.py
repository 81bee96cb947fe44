"""The deflated function G = F / Omega^2 and the evanescent scaling, against the defining
equation (dispersion.continuum.rayleigh_lamb.frequency_function) evaluated by mpmath at 40 digits."""
from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from mp_lamb import mp_C, mp_F

from dispersion.continuum.deflated_frequency import (
    deflated_frequency_function,
    deflated_with_noise,
    evanescent_frequency_function,
)
from dispersion.continuum.numeric_frequency import numeric_frequency_function
from dispersion.continuum.rayleigh_lamb import speed_ratio_squared

DPS = 40  # digits of the mpmath references


def ref_F(kind, kappa, Omega, nu, power=0):
    """Omega^-power F of the defining equation, computed at DPS digits, as a float."""
    with mpmath.workdps(DPS):
        return float(mp_F(kind, kappa, Omega, nu) / mpmath.mpf(Omega) ** power)


def ref_evanescent(kind, kappa, Omega, nu):
    """F / (C(P) c_Q), c_Q = C(Q) where Q < 0 else 1, at DPS digits, as a float."""
    with mpmath.workdps(DPS):
        s = speed_ratio_squared(mpmath.mpf(nu))
        W2, k2 = mpmath.mpf(Omega) ** 2, mpmath.mpf(kappa) ** 2
        P, Q = s * W2 - k2, W2 - k2
        cq = mp_C(Q) if Q < 0 else 1
        return float(mpmath.re(mp_F(kind, kappa, Omega, nu) / (mp_C(P) * cq)))


@pytest.mark.parametrize("kind", ["S", "A"])
def test_numeric_twin_and_deflation_match_the_definition(kind):
    # Omega^2 G = F at points covering small/large kappa and evanescent P, Q < 0
    rng = np.random.default_rng(1)
    pts = list(zip(rng.uniform(0, 12, 25), rng.uniform(0, 8, 25))) + [(0.05, 0.002), (15, 0.1)]
    for kappa, Omega in pts:
        ref = ref_F(kind, kappa, Omega, 0.3)
        F = float(numeric_frequency_function(kind, kappa, Omega, 0.3))
        G = float(deflated_frequency_function(kind, kappa, Omega, 0.3))
        # rounding is relative to the size of the terms: |a|^2 + 4 k^2 (|P| + |Q|) times cosh^2
        k2, W2 = kappa**2, Omega**2
        terms = ((W2 - 2 * k2) ** 2 + 4 * k2 * 2 * (k2 + W2)) * math.cosh(math.sqrt(k2 + W2)) ** 2
        assert abs(F - ref) <= 1e-13 * terms
        assert abs(W2 * G - ref) <= 1e-13 * terms
    # where deflation matters: near A0 at small kappa, G keeps full relative accuracy
    for kappa, Omega in [(0.05, 0.002), (0.01, 1e-4), (0.2, 0.03)]:
        ref = ref_F(kind, kappa, Omega, 0.3, power=2)
        G = float(deflated_frequency_function(kind, kappa, Omega, 0.3))
        assert abs(G - ref) <= 1e-13 * abs(ref)


@pytest.mark.parametrize("kind", ["S", "A"])
def test_divided_differences_by_series_and_by_half_angles_agree_with_the_definition(kind):
    # G's divided differences C[P,Q], S[P,Q] come from their power series where |P|, |Q| <= 2
    # and from half-angle forms beyond: on both sides of that edge (and across it on one
    # frequency line) G holds 1e-13 of the size of its terms against 40-digit Omega^-2 F
    nu = 0.3
    s = speed_ratio_squared(nu)
    rng = np.random.default_rng(7)
    pts = [(k, w) for k, w in zip(rng.uniform(0, 1.6, 30), rng.uniform(0, 2.5, 30))]
    pts += [(0.5, w) for w in np.linspace(1.3, 1.6, 7)]  # Q crosses 2 near Omega = 1.5
    for kappa, Omega in pts:
        ref = ref_F(kind, kappa, Omega, nu, power=2)
        G = float(deflated_frequency_function(kind, kappa, Omega, nu))
        k2, W2 = kappa**2, Omega**2
        size = (W2 - 2 * k2) ** 2 + W2 + 4 * k2 + abs(s * W2 - k2) + 1
        assert abs(G - ref) <= 1e-13 * size, (kappa, Omega)


@pytest.mark.parametrize("kind", ["S", "A"])
def test_evanescent_form_is_the_definition_divided_by_its_growth(kind):
    # F / (C(P) c_Q), c_Q = C(Q) where Q < 0 else 1, in 40 digits; roots of F with P < 0 are
    # its roots, and it stays of order one where F grows like exp(2 kappa)
    nu = 0.3
    for kappa in (3.0, 10.0, 40.0):
        for frac in (0.3, 0.8, 0.95):   # Omega = frac * kappa: P < 0 (s < 1)
            Omega = frac * kappa
            ref = ref_evanescent(kind, kappa, Omega, nu)
            got = float(evanescent_frequency_function(kind, kappa, Omega, nu))
            assert abs(got - ref) <= 1e-12 * (abs(ref) + kappa**4), (kappa, frac)


def test_noise_bound_marks_the_trivial_cancellation():
    # at a cut-off (kappa -> 0, Omega = pi: S(Q) = 0) G is round-off; the bound says so
    g, e = deflated_with_noise("S", 1e-8, math.pi, 0.3)
    assert abs(g) <= e
    # away from roots the bound is far below the value
    g, e = deflated_with_noise("A", 0.5, 1.0, 0.3)
    assert 0 < e < 1e-12 * abs(g)
