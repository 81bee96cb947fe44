"""Fully discrete dispersion (dispersion.time_stepping.fully_discrete): closed forms and series."""
from __future__ import annotations

import numpy as np
import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

from dispersion.errors import InputError
from dispersion.time_stepping.fully_discrete import (
    fully_discrete_series,
    time_frequency,
    time_frequency_slope,
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
    from dispersion.time_stepping.timestep import bar_omega_squared

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
    from dispersion.discretization.discrete_branches import fundamental_branches
    from dispersion.continuum.exact_branches import trace_branches
    from dispersion.time_stepping.fully_discrete import fully_discrete_error

    patch, kappa = plate_patch(mass="lumped"), np.array([0.3])
    semi = fundamental_branches(patch, 0.3, kappa)
    exact = trace_branches(0.3, kappa, 3.0).omega
    for label in ("S0", "A0"):
        semi_err = semi[label][0] / exact[label][0] - 1
        big = fully_discrete_error(patch, 0.3, kappa, 1.0)[label][0] - semi_err
        small = fully_discrete_error(patch, 0.3, kappa, 0.01)[label][0] - semi_err
        assert big > 0 and abs(small) <= 2e-4 * big


# --- promise: fully discrete branches to 1e-10 at every kappa > 0 (docs/promises.md) -------
import math  # noqa: E402

import mpmath  # noqa: E402
from hypothesis import example  # noqa: E402

from promise_search import FAST, FAST_FEW, SLOW, record  # noqa: E402

_SCHEMES = ("central", "average-acceleration", "linear-acceleration", "fox-goodwin")


def _mp_time_frequency(w, tau, beta, gamma):
    """|arg z| / tau of the Newmark recurrence's complex root (Hughes 2000, 9.3) by the
    quadratic formula in mpmath, digits raised by the cancellation the textbook form has."""
    lost = max(0, -2 * math.log10(max(float(w) * tau, 1e-300)))
    with mpmath.workdps(50 + int(lost)):
        beta, gamma = mpmath.mpf(beta), mpmath.mpf(gamma)
        X = (mpmath.mpf(w) * mpmath.mpf(tau)) ** 2
        a = 1 + beta * X
        b = -(2 - (mpmath.mpf(1) / 2 - 2 * beta + gamma) * X)
        c = 1 + (mpmath.mpf(1) / 2 + beta - gamma) * X
        disc = b * b - 4 * a * c
        if disc >= 0:
            return None
        z = (-b + mpmath.sqrt(disc)) / (2 * a)
        if abs(z) > 1 + mpmath.mpf(10) ** (5 - mpmath.mp.dps):   # |z| = 1 up to rounding
            return None
        return abs(mpmath.arg(z)) / tau


def _check_map(wt, frac_beta, frac_gamma, scheme_index):
    if scheme_index < len(_SCHEMES):
        sch = time_scheme(_SCHEMES[scheme_index])
    else:
        sch = time_scheme("newmark", frac_beta / 2, 0.5 + frac_gamma / 2)
    tau = 0.37
    w = wt / tau
    got = float(time_frequency(np.array([w]), tau, sch)[0])
    ref = _mp_time_frequency(w, tau, float(sch.beta), float(sch.gamma))
    if ref is None:
        assert math.isnan(got)
        return
    p, q = 0.5 - 2 * float(sch.beta) + float(sch.gamma), 0.5 + float(sch.beta) - float(sch.gamma)
    if math.isnan(got) and (p * p - 4 * float(sch.beta) * q) * wt * wt > 4 * (1 - 1e-13):
        return   # on the stability limit to rounding of the input: either side is right
    # condition of the map (output relative change per input relative change): 1 at small
    # X, 1/cos(theta tau / 2) central; measured here as the mpmath slope, so the bound is
    # the inherent one (four roundings of the input), not a loosened tolerance
    slope = float(time_frequency_slope(np.array([w]), tau, sch)[0])
    cond = max(1.0, abs(slope) * w / float(ref))
    err = abs(got - float(ref)) / float(ref)
    record("fully discrete map", err, 8 * cond * np.finfo(float).eps, wt=wt,
           beta=float(sch.beta), gamma=float(sch.gamma))


def _map_domain(fn):
    """Every scheme, Omega_h tau from 1e-300 to beyond the stability limit; ends as examples."""
    for ex in [dict(wt=1e-300, frac_beta=0.0, frac_gamma=0.0, scheme_index=0),
               dict(wt=1e-8, frac_beta=0.0, frac_gamma=0.0, scheme_index=0),   # X = 1e-16
               dict(wt=2.0 * (1 - 1e-6), frac_beta=0.0, frac_gamma=0.0, scheme_index=0),
               dict(wt=1e-8, frac_beta=1.0, frac_gamma=1.0, scheme_index=4),
               dict(wt=2.0, frac_beta=1.0, frac_gamma=0.0, scheme_index=4)]:
        fn = example(**ex)(fn)
    return given(wt=st.floats(1e-300, 2.0), frac_beta=st.floats(0, 1),
                 frac_gamma=st.floats(0, 1), scheme_index=st.integers(0, len(_SCHEMES)))(fn)


@FAST
@_map_domain
def test_time_frequency_against_mpmath(wt, frac_beta, frac_gamma, scheme_index):
    _check_map(wt, frac_beta, frac_gamma, scheme_index)


@pytest.mark.slow
@SLOW
@_map_domain
def test_time_frequency_against_mpmath_slow(wt, frac_beta, frac_gamma, scheme_index):
    _check_map(wt, frac_beta, frac_gamma, scheme_index)


def _check_branches(mass, p, log_kappa, scheme_index, courant_frac):
    # the whole path (discrete branches, the critical step, the map) against mpmath: the
    # semi-discrete frequencies of the pencil at 60+ digits (tests/mp_pencil.py), mapped
    # by the quadratic formula of the recurrence (_mp_time_frequency)
    from dispersion.symbolic.plate import plate_patch
    from dispersion.discretization.discrete_branches import discrete_branches
    from dispersion.time_stepping.fully_discrete import fully_discrete_branches
    from dispersion.time_stepping.timestep import patch_omega_max
    from mp_pencil import mp_frequencies

    n = max(p + 1, 3)
    patch = plate_patch(p, n, "bloch", 2, mass)
    kappa = min(10.0**log_kappa, math.pi / 2)
    scheme = _SCHEMES[scheme_index]
    sch = time_scheme(scheme)
    limit = 1.0 if sch.explicit else 10.0
    tau = limit * courant_frac * 2 / patch_omega_max(patch, 0.3, exact=False)[0]
    fd = fully_discrete_branches(discrete_branches(patch, 0.3, [kappa]), tau, scheme)
    got = sorted(float(w[0]) for w in fd.omega.values() if np.isfinite(w[0]))
    listed = {k for what, k, _ in fd.failures if what == "omega"}
    ref = [_mp_time_frequency(float(w), tau, float(sch.beta), float(sch.gamma))
           for w in mp_frequencies(patch, 0.3, kappa, dps=60 + 4 * max(0, -int(log_kappa)))]
    ref = sorted(float(w) for w in ref if w is not None)
    if kappa in listed:   # a listed failure is allowed (never silent)
        return
    assert len(got) == len(ref)
    err = max((abs(a / b - 1) for a, b in zip(got, ref)), default=0.0)
    record("fully discrete branches", err, 1e-10, mass=mass, p=p, kappa=kappa, scheme=scheme,
           courant=limit * courant_frac)


def _branch_domain(fn, full=False):
    """Every mass rule, p = 1..4, kappa from 1e-40 to the zone edge, every scheme,
    Courant up to 1 - 1e-6 of the explicit limit (10 implicit)."""
    ends = [dict(mass="lumped", p=2, log_kappa=-4.0, scheme_index=0, courant_frac=0.9),
            dict(mass="singular", p=2, log_kappa=-3.0, scheme_index=0, courant_frac=0.9),
            dict(mass="consistent", p=2, log_kappa=-40.0, scheme_index=0, courant_frac=1e-6),
            dict(mass="consistent", p=4, log_kappa=1.0, scheme_index=0, courant_frac=1 - 1e-6),
            dict(mass="hrz", p=1, log_kappa=1.0, scheme_index=1, courant_frac=1.0)]
    for ex in ends if full else ends[:2]:
        fn = example(**ex)(fn)
    from dispersion.mass_rules.mass_rule import BLOCH_RULE_NAMES as MASS_VARIANTS

    return given(mass=st.sampled_from(MASS_VARIANTS), p=st.integers(1, 4),
                 log_kappa=st.floats(-40, 0.2), scheme_index=st.integers(0, len(_SCHEMES) - 1),
                 courant_frac=st.floats(1e-6, 1 - 1e-6))(fn)


@FAST_FEW
@_branch_domain
def test_fully_discrete_branches_against_mpmath(mass, p, log_kappa, scheme_index, courant_frac):
    _check_branches(mass, p, log_kappa, scheme_index, courant_frac)


@pytest.mark.slow
@SLOW
@lambda fn: _branch_domain(fn, full=True)
def test_fully_discrete_branches_against_mpmath_slow(mass, p, log_kappa, scheme_index,
                                                     courant_frac):
    _check_branches(mass, p, log_kappa, scheme_index, courant_frac)


def test_fully_discrete_group_velocity_is_the_chain_rule(tmp_path):
    # the map's slope against a central difference of the map itself (mpmath, 50 digits),
    # and the command that raised KeyError 'S0' (issue 26) now writes c_g in m/s
    from dispersion.cli import main

    for scheme in _SCHEMES:
        sch = time_scheme(scheme)
        for w in (1e-6, 0.7, 1.9):
            h = mpmath.mpf(10) ** -20
            with mpmath.workdps(50):
                ref = (_mp_time_frequency(mpmath.mpf(w) + h, 1.0, sch.beta, sch.gamma)
                       - _mp_time_frequency(mpmath.mpf(w) - h, 1.0, sch.beta, sch.gamma)) / (2 * h)
            got = float(time_frequency_slope(np.array([w]), 1.0, scheme)[0])
            assert got == pytest.approx(float(ref), rel=1e-13)
    out = tmp_path / "o.csv"
    assert main(["branches", "--scheme", "central", "--courant", "0.9", "--material", "steel",
                 "--thickness", "1", "--count", "5", "--mass", "lumped", "--csv", str(out)]) == 0
    rows = [line.split(",") for line in out.read_text().splitlines() if not line.startswith("#")]
    col = rows[0].index("c_g [m/s]")
    assert all(r[col] != "" for r in rows[1:] if "central" in ",".join(r) and r[0] != "0.0")
