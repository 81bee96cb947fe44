"""The exact tracer's root count against an independent method: Chebyshev collocation.

The reference here is the plane-strain Navier equations collocated through the thickness (no
Rayleigh-Lamb function, no Mindlin bounds): at fixed kappa a generalized eigenproblem in
Omega^2 per symmetry class, whose finite positive eigenvalues below Omega_max^2 are counted.
Rules, fixed before looking at any answer: the collocation uses N = 0.8 max(kappa, Omega_max)
+ 32 points on the half thickness (more than pi points per wavelength of the fastest oscillation
sqrt(Omega^2 - kappa^2) <= Omega_max over the half thickness, with the evanescent layer
e^{-kappa (1 - y)} resolved by the clustering of the points near the face; an under-resolved
reference shows as a count or value mismatch, i.e. a failing test, not a passing one); counts must be
equal, or the kappa is listed in ``failures``; roots must agree with the eigenvalues to 1e-6
relative in Omega^2 (far below any spacing of roots, far above the collocation error) or to the
collocation's round-off, 1e-13 ||A||_F absolute in Omega^2 (backward-stable eigensolver); kappa
stays >= 0.2 in the property tests, so that the smallest eigenvalue (A0, ~kappa^4 >= 1.6e-3)
stays far above that round-off (~1e-7) and the reference count is not in doubt; a reference
eigenvalue within 1e-6 of Omega_max would make the count ambiguous and fails the test loudly.
"""
from __future__ import annotations

import mpmath
import numpy as np
import pytest
import scipy.linalg
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dispersion.cli import main
from dispersion.errors import InputError
from dispersion.continuum.exact_branches import trace_branches
from dispersion.continuum.rayleigh_lamb import frequency_function


def cheb(N):
    """Chebyshev points and differentiation matrix on [-1, 1] (Trefethen 2000, ``cheb.m``)."""
    x = np.cos(np.pi * np.arange(N + 1) / N)
    c = np.hstack([2, np.ones(N - 1), 2]) * (-1) ** np.arange(N + 1)
    dX = x[:, None] - x[None, :]
    D = np.outer(c, 1 / c) / (dX + np.eye(N + 1))
    return D - np.diag(D.sum(axis=1)), x


def navier_omega(kind: str, kappa: float, nu: float, omega_max: float) -> np.ndarray:
    """Omega of the class below omega_max by collocation of the Navier equations on 0 <= y <= 1.

    u_x = i U(y) e^{i kappa x}, u_y = V(y) e^{i kappa x}, c_T = rho = 1, L = (c_L/c_T)^2:
    U'' - L k^2 U + (L-1) k V' = -Omega^2 U,  L V'' - k^2 V - (L-1) k U' = -Omega^2 V;
    free face y = 1: U' + k V = 0 and L V' - (L-2) k U = 0; centre y = 0: S has U' = V = 0,
    A has U = V' = 0.
    """
    N = int(0.8 * max(kappa, omega_max)) + 32
    L = 2 * (1 - nu) / (1 - 2 * nu)
    D, x = cheb(N)
    D1 = 2 * D                      # y = (x + 1) / 2: face at index 0, centre at index N
    D2 = D1 @ D1
    n, k = N + 1, kappa
    eye = np.eye(n)
    A = np.block([[-D2 + L * k**2 * eye, -(L - 1) * k * D1], [(L - 1) * k * D1, k**2 * eye - L * D2]])
    B = np.eye(2 * n)
    face, centre = 0, N
    for r in (face, n + face, centre, n + centre):
        A[r], B[r] = 0, 0
    A[face, :n], A[face, n + face] = D1[face], k
    A[n + face, face], A[n + face, n:] = -(L - 2) * k, L * D1[face]
    if kind == "S":
        A[centre, :n], A[n + centre, n + centre] = D1[centre], 1
    else:
        A[centre, centre], A[n + centre, n:] = 1, D1[centre]
    ev = scipy.linalg.eigvals(A, B)
    ev = ev[np.isfinite(ev)]
    ev = ev[(np.abs(ev.imag) <= 1e-6 * np.abs(ev)) & (ev.real > 0)].real
    w = np.sort(np.sqrt(ev))
    assert not np.any(np.abs(w / omega_max - 1) < 1e-6), "reference root at omega_max"
    return w[w <= omega_max], 1e-13 * np.linalg.norm(A)


def _compare(nu, kappa, omega_max):
    br = trace_branches(nu, [kappa], omega_max)
    failed = {f[0] for f in br.failures}
    counts = {}
    for kind in "SA":
        ref, atol = navier_omega(kind, kappa, nu, omega_max)
        got = np.array([w[0] for lab, w in br.omega.items() if lab[0] == kind and np.isfinite(w[0])])
        got.sort()
        if kind in failed:
            continue  # listed as a failure: allowed, never silent
        assert got.size == ref.size, (kind, nu, kappa, got.size, ref.size)
        np.testing.assert_allclose(got**2, ref**2, rtol=1e-6, atol=atol)
        counts[kind] = got.size
    return counts


@pytest.mark.parametrize("nu, kappa, omega_max, expect", [
    (0.25, 70.0, 80.0, {"S": 12, "A": 13}),   # issue 17 item 5: 12 S + 13 A (none returned)
    pytest.param(0.3, 50.0, 60.0, {"S": 11, "A": 11}, marks=pytest.mark.slow),  # 1 S / 1 A
    pytest.param(0.3, 40.0, 45.0, None, marks=pytest.mark.slow),  # four A roots were missing
])
def test_count_equals_collocation_issue_cases(nu, kappa, omega_max, expect):
    counts = _compare(nu, kappa, omega_max)
    assert sorted(counts) == ["A", "S"]
    if expect is not None:
        assert counts == expect


def test_issue_root_at_kappa_40_is_42_78213():
    # issue 17: 42.7843 was reported for 42.78213; the reference root is found here by mpmath
    br = trace_branches(0.3, [40.0], 45.0, kinds=("A",))
    w = np.array([v[0] for v in br.omega.values()])
    near = w[np.argmin(np.abs(w - 42.782))]
    with mpmath.workdps(40):
        def f(W):
            return mpmath.re(frequency_function(
                "A", mpmath.mpf(40) ** 2, W**2, mpmath.mpf(0.3),
                lambda z: mpmath.cos(mpmath.sqrt(z)), lambda z: mpmath.sinc(mpmath.sqrt(z))))
        ref = mpmath.findroot(f, (mpmath.mpf(near) - mpmath.mpf("1e-6"),
                                  mpmath.mpf(near) + mpmath.mpf("1e-6")), solver="anderson")
    assert abs(near - float(ref)) <= 1e-12 * float(ref)
    assert abs(float(ref) - 42.78213) < 1e-5


@pytest.mark.slow
@pytest.mark.parametrize("nu", [0.0, 0.25, 0.3, 0.45, 0.49])
@pytest.mark.parametrize("kappa", [40.0, 50.0, 70.0, 100.0, 200.0])
def test_count_equals_collocation_grid(nu, kappa):
    # issue 17 "what to build" 4: kappa up to 200 and Omega up to 200 (260 at kappa = 200,
    # where the branches above the Rayleigh pair start at Omega > kappa)
    omega_max = max(200.5, kappa + 60.5)
    counts = _compare(nu, kappa, omega_max)
    assert sorted(counts) == ["A", "S"]  # no failure expected on this grid


def _property(kappa, nu, top):
    omega_max = kappa * top + 3.3
    _compare(nu, kappa, omega_max)


_KAPPA = st.floats(0.2, 300.0)
_NU = st.floats(-0.9, 0.49)
_TOP = st.floats(0.5, 1.3)


@settings(max_examples=3, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(kappa=st.floats(0.2, 20.0), nu=_NU, top=_TOP)
def test_count_property(kappa, nu, top):
    _property(kappa, nu, top)


@pytest.mark.slow
@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(kappa=_KAPPA, nu=_NU, top=_TOP)
def test_count_property_long(kappa, nu, top):
    _property(kappa, nu, top)


def test_cli_prints_rows_at_large_kappa(capsys):
    # issue 17: this printed only the header and exited 0
    rc = main(["branches", "--exact", "--nu", "0.25", "--kappa-min", "69.9", "--kappa-max", "70",
               "--count", "2", "--omega-max", "80", "--format", "csv"])
    assert rc == 0
    rows = [line for line in capsys.readouterr().out.splitlines()
            if line and not line.startswith("#")][1:]
    assert len(rows) == 2 * (12 + 13)


@pytest.mark.parametrize("bad", ["x", -1, 0, 2.5, True, None])
def test_max_depth_is_checked(bad):
    with pytest.raises(InputError, match="max_depth"):
        trace_branches(0.3, [1.0], 2.0, max_depth=bad)


@settings(max_examples=8, deadline=None)
@given(log_kappa=st.floats(-30.0, -6.0), nu=_NU, omega_max=st.floats(0.5, 40.0))
def test_small_kappa_count_equals_the_cutoffs(log_kappa, nu, omega_max):
    _small_kappa(log_kappa, nu, omega_max)


@pytest.mark.slow
@settings(max_examples=150, deadline=None)
@given(log_kappa=st.floats(-30.0, -6.0), nu=_NU, omega_max=st.floats(0.5, 40.0))
def test_small_kappa_count_equals_the_cutoffs_long(log_kappa, nu, omega_max):
    _small_kappa(log_kappa, nu, omega_max)


def _small_kappa(log_kappa, nu, omega_max):
    # independent closed form: at kappa <= 1e-6 every branch lies within |dOmega/dkappa| kappa
    # <= 2 kappa of its cut-off (cutoff_frequencies, Rose 2004 ch. 8; the slope bound 2 covers
    # the cone 2/pi at coincident cut-offs), plus 16 eps for the roundings of two float forms
    # of the same closed form; a cut-off within 1e-4 of omega_max is skipped
    from hypothesis import assume

    from dispersion.continuum.rayleigh_lamb import cutoff_frequencies

    kappa = 10.0**log_kappa
    br = trace_branches(nu, [kappa], omega_max)
    assert br.failures == []
    for kind in "SA":
        cuts = np.array([w for w, _ in cutoff_frequencies(kind, nu, omega_max + 1)])
        assume(np.all(np.abs(cuts - omega_max) > 1e-4))
        cuts = cuts[cuts <= omega_max]
        got = np.sort([w[0] for lab, w in br.omega.items()
                       if lab[0] == kind and np.isfinite(w[0])])
        assert got.size == cuts.size
        assert np.all(np.abs(got[1:] - cuts[1:]) <= 2 * kappa + 16 * 2.2e-16 * cuts[1:])
