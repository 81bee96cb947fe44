"""The certificate of a root (``dispersion.continuum.root_certificate``) and its two halves: the float
Rayleigh-Lamb function with a proven rounding bound and the function in ball arithmetic.

References: the textbook equation in p and q at 60 digits (plus the cosh-sized cancellation),
``tests/mp_lamb.py``, at the same exact inputs (floats kappa and Omega, s rational).
"""
from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from dispersion.continuum.numeric_frequency import frequency_function_bound
from dispersion.continuum.rayleigh_lamb import arb_frequency_function, speed_ratio_squared
from dispersion.continuum.root_certificate import (arb_certified, bracket_points, exact_square,
                                               float_certified, refine_in_squares)
from mp_lamb import mp_exact, textbook_F
from promise_search import FAST, SLOW, record


def _reference(kind, kappa, omega, nu_q):
    """60 digits plus the digits the cosh-sized terms cancel (kappa / ln 10)."""
    with mpmath.workdps(60 + int(kappa / 2.3)):
        k = mpmath.mpf(kappa)
        return textbook_F(kind, k * k, mpmath.mpf(omega), mp_exact(nu_q))


def _bound(kind, kappa, omega, nu_q):
    s = speed_ratio_squared(nu_q)
    F, B = frequency_function_bound(kind, np.array([kappa]), np.array([omega]), float(s),
                                    0.5 * float(np.spacing(float(s))))
    return float(F[0]), float(B[0])


def _check_bound(kind, kappa, omega, nu):
    nu_q = Fraction(nu)
    F, B = _bound(kind, kappa, omega, nu_q)
    ref = _reference(kind, kappa, omega, nu_q)
    # the bound is proven: the exact F lies within it (an error above B is a counterexample)
    err = float(abs(mpmath.mpf(F) - ref))
    record("float F within its rounding bound", err / B if B > 0 else err, 1.0,
           kind=kind, kappa=kappa, omega=omega, nu=nu)
    with mpmath.workdps(60):   # and the ball of the arb form holds it
        ball = arb_frequency_function(kind, exact_square(kappa), omega,
                                      speed_ratio_squared(nu_q), 128)
        lo, hi = (mpmath.mpf(x.str(60, radius=False)) for x in (ball.lower(), ball.upper()))
        assert lo - abs(ref) * mpmath.mpf(10) ** -50 <= ref <= hi + abs(ref) * mpmath.mpf(10) ** -50


def _bound_domain(fn, full=False):
    s3 = math.sqrt(1 / 3)
    ends = [("S", 1.0, 1.0, 0.25),                 # Q = 0 (Omega = kappa)
            ("A", 1.0, 1.0 / s3, 0.25),            # P = 0 to rounding (Omega = kappa / sqrt s)
            ("S", 1e-8, math.pi, 0.3),              # next to a cut-off, kappa tiny
            ("A", 300.0, 280.0, 0.3),               # cosh-sized terms at the kappa limit
            ("S", 0.5990758101, 1.0, 0.3),          # next to S0's root
            ("A", 1e-8, 2e-3, -0.999), ("S", 300.0, 30.0, 0.4999)]
    for ex in ends if full else ends[:4]:
        fn = example(*ex)(fn)
    kappa = st.floats(-8.0, math.log10(300.0)).map(lambda u: 10.0**u)
    return given(st.sampled_from(["S", "A"]), kappa, st.floats(2e-3, 30.0),
                 st.floats(-0.999, 0.4999))(fn)


@FAST
@_bound_domain
def test_float_rounding_bound_holds(kind, kappa, omega, nu):
    _check_bound(kind, kappa, omega, nu)



@pytest.mark.slow
@SLOW
@lambda fn: _bound_domain(fn, full=True)
def test_float_rounding_bound_holds_slow(kind, kappa, omega, nu):
    _check_bound(kind, kappa, omega, nu)


def _arb(kind, omega, nu_q):
    ratio = speed_ratio_squared(nu_q)
    return lambda x, prec: arb_frequency_function(kind, x, omega, ratio, prec)


def _float(kind, omega, nu_q):
    s = float(speed_ratio_squared(nu_q))
    return lambda k: frequency_function_bound(kind, k, np.full(k.shape, omega), s,
                                              0.5 * float(np.spacing(s)))


def test_a_root_is_certified_and_a_near_miss_is_not():
    # A0 of nu = 0.3 at Omega = 1 (the frequency module's doctest): closed in ball arithmetic
    # from a wide bracket, certified both ways; 1e-12 off it, neither certifies it
    nu_q = Fraction(3, 10)
    F = _arb("A", 1.0, nu_q)
    k = refine_in_squares(F, 1.0, 2.0, 128)
    with mpmath.workdps(50):
        ref = mpmath.findroot(lambda x: textbook_F("A", x * x, 1, mp_exact(nu_q)), k)
    assert abs(k / float(ref) - 1) < 2**-52
    assert arb_certified(F, k, 2.5e-13, 128)
    assert float_certified(_float("A", 1.0, nu_q), np.array([k]), 2.5e-13)[0]
    off = k * (1 + 1e-12)
    assert not arb_certified(F, off, 2.5e-13, 128)
    assert not float_certified(_float("A", 1.0, nu_q), np.array([off]), 2.5e-13)[0]


def test_a_root_next_to_a_cut_off_needs_ball_arithmetic():
    # S2 of nu = 0.3 1e-14 above its cut-off pi: kappa ~ 1e-7, F flat in kappa^2; floats
    # cannot decide its sign at kappa (1 +- 2.5e-13), balls can
    nu_q = Fraction(3, 10)
    omega = math.pi * (1 + 1e-14)
    F = _arb("S", omega, nu_q)
    k = refine_in_squares(F, 0.0, 0.02, 160)
    with mpmath.workdps(60):
        ref = mpmath.sqrt(mpmath.findroot(
            lambda x: textbook_F("S", x, mpmath.mpf(omega), mp_exact(nu_q)), mpmath.mpf(k) ** 2))
    assert abs(k / float(ref) - 1) < 1e-15
    assert arb_certified(F, k, 2.5e-13, 160)
    assert not float_certified(_float("S", omega, nu_q), np.array([k]), 2.5e-13)[0]
    lo, hi = bracket_points(k, 2.5e-13)
    assert lo < float(ref) < hi


def test_numpy_elementary_functions_are_as_accurate_as_the_bound_assumes():
    # the float bound rests on LIBM_ULPS: checked on this machine's numpy against mpmath, on
    # random arguments of the calculator's range and next to the zeros of cos and sin
    from dispersion.continuum.numeric_frequency import LIBM_ULPS

    rng = np.random.default_rng(34)
    trig = np.concatenate([rng.uniform(0, 300, 300), np.arange(1, 200) * np.pi / 2])
    hyper = rng.uniform(0, 300, 200)
    worst = 0.0
    with mpmath.workdps(40):
        for f, g, xs in ((np.cos, mpmath.cos, trig), (np.sin, mpmath.sin, trig),
                         (np.cosh, mpmath.cosh, hyper), (np.sinh, mpmath.sinh, hyper),
                         (np.sqrt, mpmath.sqrt, hyper)):
            for x, v in zip(xs, f(xs)):
                ref = g(mpmath.mpf(float(x)))
                if ref != 0:
                    worst = max(worst, float(abs(mpmath.mpf(float(v)) - ref))
                                / float(np.spacing(abs(float(ref)))))
    assert worst <= LIBM_ULPS
