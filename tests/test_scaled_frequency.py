"""The Rayleigh-Lamb function scaled by its Mindlin bounds: values and rounding bound against
the defining equation in 40-digit mpmath, the bounds against their closed forms, and the sign
structure the tracer's exact count rests on."""
from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st
from mp_lamb import mp_C, mp_F, mp_S

from dispersion.errors import InputError
from dispersion.continuum.scaled_frequency import (
    bound_table,
    mindlin_bounds,
    removable_bound,
    scaled_frequency_function,
    scaled_slope,
    scaled_with_noise,
)


def mp_scaled(kind, kappa, Omega, nu):
    """R from its definition: R_S = F_S / (Omega^2 P S(P) S(Q)), R_A = -F_A / (Omega^2 C(P) C(Q)),
    F the defining equation (frequency_function) in 40-digit arithmetic."""
    with mpmath.workdps(40):
        k, W, n = mpmath.mpf(kappa), mpmath.mpf(Omega), mpmath.mpf(nu)
        s = (1 - 2 * n) / (2 * (1 - n))
        P, Q = s * W**2 - k**2, W**2 - k**2
        F = mp_F(kind, k, W, n)
        R = F / (W**2 * P * mp_S(P) * mp_S(Q)) if kind == "S" else -F / (W**2 * mp_C(P) * mp_C(Q))
        return float(mpmath.re(R))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(kind=st.sampled_from("SA"), log_k=st.floats(-3, 1.5), log_w=st.floats(-3, 1.5),
       nu=st.floats(-0.5, 0.49))
def test_value_within_its_own_rounding_bound(kind, log_k, log_w, nu):
    # the tracer certifies a root by the sign of R above the bound of scaled_with_noise: the
    # bound must cover the actual error (searched over nu, and kappa, Omega in [1e-3, 30],
    # which holds the deflated small-argument form, the quotient form and the evanescent one)
    kappa, Omega = 10.0**log_k, 10.0**log_w
    r, e = scaled_with_noise(kind, kappa, Omega, nu)
    assert abs(float(r) - mp_scaled(kind, kappa, Omega, nu)) <= float(e)


def _closed_form_bounds(kind, kappa, nu, omega_max):
    """The bounds enumerated one by one from P = (j pi)^2 (j + 1/2 for A) and
    Q = (j pi)^2, j >= 1 for S (j + 1/2, j >= 0 for A), up to the first above omega_max."""
    s = (1 - 2 * nu) / (2 * (1 - nu))
    off = 0.0 if kind == "S" else 0.5
    out = []
    for scale, first in ((s, 0), (1.0, 1 if kind == "S" else 0)):
        j = first
        while True:
            w = math.sqrt((kappa**2 + ((j + off) * math.pi) ** 2) / scale)
            out.append(w)
            if w > omega_max:
                break
            j += 1
    out.sort()
    return out[:next(i for i, w in enumerate(out) if w > omega_max) + 1]


@pytest.mark.parametrize("kind", ["S", "A"])
@pytest.mark.parametrize("nu", [-0.4, 0.0, 0.3, 1 / 3, 0.49])
def test_bounds_are_the_closed_forms(kind, nu):
    for kappa in (0.0, 0.3, 2.0, 17.0):
        for omega_max in (0.5, 3.0, 40.0):
            got = mindlin_bounds(kind, kappa, nu, omega_max)
            ref = _closed_form_bounds(kind, kappa, nu, omega_max)
            assert got == pytest.approx(ref, rel=1e-15, abs=0)
            row = bound_table(kind, [kappa], nu, omega_max)[0]
            assert row[-1] > omega_max and np.all(np.diff(row) >= 0)


@settings(max_examples=40, deadline=None)
@given(kind=st.sampled_from("SA"), kappa=st.floats(1e-2, 20),
       nu=st.floats(-0.5, 0.49).filter(lambda v: v == 0 or abs(v) >= 1e-6))
@example(kind="S", kappa=9.5, nu=3e-6)  # a root within 1e-13 of the bound 13.435049 (found)
@example(kind="S", kappa=9.0, nu=1e-6)  # a root within 1e-13 above a bound (found)
def test_one_sign_change_between_consecutive_bounds(kind, kappa, nu):
    # R falls from +inf to -inf between poles: positive just above a bound (and at 0+),
    # negative just below the next one; this is what makes the tracer's count exact. "Just":
    # 1e-13 relative. A root may lie closer than that to its bound (near nu = 0, where bounds
    # turn removable: S at kappa = 9.5, nu = 3e-6 has one 1.3e-12 below 13.435049); there the
    # sign cannot show it, and the tracer must return that root on the bound, certified (the
    # bound's own sign counts, exact_branches._certify)
    first = 1 if removable_bound(kind, nu) else 0
    row = bound_table(kind, [kappa], nu, 12.0, first_p=first)[0]
    lo = np.concatenate([[0.0], row[:-1]])
    hi = row
    keep = hi - lo > 1e-6 * hi           # a double bound holds a root on it, no interval
    above = np.where(lo > 0, lo * (1 + 1e-13), 1e-6 * hi)  # 0+: below A0 (~ kappa^2)
    below = hi * (1 - 1e-13)
    r_above, e_above = scaled_with_noise(kind, np.full(keep.sum(), kappa), above[keep], nu)
    r_below, e_below = scaled_with_noise(kind, np.full(keep.sum(), kappa), below[keep], nu)
    # a root closer than 1e-13 above a bound shows the same way (S at kappa = 9, nu = 1e-6:
    # found by the search): the tracer must return it on that bound; at 0+ nothing is near
    root_above = ~(r_above > e_above)
    assert not np.any(root_above & (lo[keep] == 0))
    on_bound = np.concatenate([hi[keep][~(r_below < -e_below)], lo[keep][root_above]])
    if on_bound.size:
        from dispersion.continuum.exact_branches import trace_branches

        br = trace_branches(nu, [kappa], float(on_bound.max()) * 1.01)
        roots = np.array([v[0] for k, v in br.omega.items() if k[0] == kind], dtype=float)
        assert not br.failures
        for h in on_bound:
            assert np.any(np.abs(roots - h) <= 1e-13 * h), (h, roots)


def test_removable_bound_only_for_symmetric_modes_at_nu_zero():
    assert removable_bound("S", 0.0) and not removable_bound("A", 0.0)
    assert not removable_bound("S", 1e-3)


def test_slope_at_a_root_is_the_group_velocity():
    # S0 at small kappa moves at the plate speed sqrt(2/(1-nu)) (paper eq 14)
    cp = math.sqrt(2 / 0.7)
    assert abs(float(scaled_slope("S", 1e-3, cp * 1e-3, 0.3)) - cp) < 1e-6


def test_bad_kind_is_refused():
    with pytest.raises(InputError, match="kind"):
        scaled_frequency_function("X", 1.0, 1.0, 0.3)
    with pytest.raises(InputError, match="kind"):
        mindlin_bounds("X", 1.0, 0.3, 2.0)
