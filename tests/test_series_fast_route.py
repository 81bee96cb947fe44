"""The fast route of the branch solve (fmpq_poly and Horner in Y, one parameter) against the
reference route (fmpq_mpoly and the table of powers of Y, ``univariate=False``): the same
coefficients, searched by hypothesis.

Two independent checks: (1) both routes give identical numerators and denominators;
(2) the series they give solves F(t, w(t)) = O(t^(N+1)) at a random rational value of the
parameter, checked by plain Fraction arithmetic (not by the kernel).
"""
from __future__ import annotations

from fractions import Fraction

import flint
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dispersion.symbolic import series_kernel as _k
from dispersion.symbolic.power_balance import format_coefficient
from dispersion.symbolic.series_kernel import Series, branch_coefficients, context
from dispersion.continuum.exact_series import exact_series_raw

CTX = context(("g",))
W, G = CTX.gens()

small = st.integers(-4, 4)
nonzero = small.filter(lambda v: v != 0)


def _poly_g(coeffs):
    """sum c_i g^i as a polynomial of the context."""
    out = CTX.from_dict({})
    for i, c in enumerate(coeffs):
        out += c * G**i
    return out


@st.composite
def characteristic(draw, max_order=6):
    """F = w (a1 w + a0)(u + w^2 s) + sum_{k>=1} t^k V_k(w, g): a unique simple non-zero root
    w0 = -a0/a1 at t = 0 (u a non-zero constant, s a square-free-safe multiplier so that the
    extra factor u + s w^2 has no rational root when u s > 0)."""
    N = draw(st.integers(1, max_order))
    a1 = _poly_g([draw(nonzero), draw(small)])
    a0 = _poly_g([draw(nonzero), draw(small)])
    u = draw(st.integers(1, 3))
    s = draw(st.integers(0, 2))
    q0 = W * (a1 * W + a0) * (u + s * W * W)
    deg_w = draw(st.integers(1, 4))
    coeffs = [q0]
    for _ in range(N + 1):
        term = CTX.from_dict({})
        for e in range(deg_w + 1):
            term += _poly_g([draw(small), draw(small)]) * W**e
        coeffs.append(term)
    return Series(CTX, coeffs, N + 1), N


def _at(p, g: Fraction) -> dict[int, Fraction]:
    """{power of w: value} of a polynomial in (w, g) at the rational g."""
    out: dict[int, Fraction] = {}
    for (e, i), c in p.to_dict().items():
        e, i = int(e), int(i)
        out[e] = out.get(e, Fraction(0)) + Fraction(int(c.p), int(c.q)) * g**i
    return out


def _residual(F: Series, nums, dens, g: Fraction, N: int) -> list[Fraction]:
    """Coefficients t^0..t^N of F(t, w(t)) at g, w(t) = sum nums_k/dens_k t^k (Fractions)."""
    wser = []
    for a, b in zip(nums, dens):
        va, vb = _at(a, g).get(0, Fraction(0)), _at(b, g).get(0, Fraction(0))
        wser.append(va / vb)

    def mul(x, y):
        return [sum(x[i] * y[k - i] for i in range(k + 1)) for k in range(N + 1)]

    out = [Fraction(0)] * (N + 1)
    for k, c in enumerate(F.coeffs[: N + 1]):
        power = [Fraction(1)] + [Fraction(0)] * N  # w(t)^e, built up
        by_e = _at(c, g)
        total = [Fraction(0)] * (N + 1)
        for e in range(max(by_e, default=0) + 1):
            if e:
                power = mul(power, wser)
            if e in by_e:
                total = [x + by_e[e] * y for x, y in zip(total, power)]
        for i in range(N + 1 - k):
            out[i + k] += total[i]
    return out


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(characteristic(), st.fractions(min_value=-3, max_value=3, max_denominator=9))
def test_fast_route_equals_reference_route_and_solves_the_equation(case, g):
    F, N = case
    fast = branch_coefficients(F, N)
    ref = branch_coefficients(F, N, univariate=False)
    # the same rational coefficients w_k = num_k / den_k (the routes scale by different
    # constants: rho against the monic rho / L)
    assert len(fast[0]) == len(ref[0]) == N + 1
    for a, b, c, d in zip(fast[0], fast[1], ref[0], ref[1]):
        assert a * d == b * c and not b.is_zero()
    dens = [d for d in fast[1]]
    if any(_at(d, g).get(0, 0) == 0 for d in dens):
        return  # g is a pole of a coefficient: the residual is not defined there
    assert _residual(F, fast[0], dens, g, N) == [0] * (N + 1)


def _reference_raw(monkeypatch, branch: str, order: int):
    def reference(F, N, univariate=None):
        return original(F, N, univariate=False)

    original = _k.branch_coefficients
    with monkeypatch.context() as m:
        m.setattr(_k, "branch_coefficients", reference)
        return exact_series_raw(branch, order)


def _check_exact(monkeypatch, branch: str, order: int):
    fast = exact_series_raw(branch, order)
    ref = _reference_raw(monkeypatch, branch, order)
    assert [k for k, _, _ in fast] == [k for k, _, _ in ref]
    for (_, a, b), (_, c, d) in zip(fast, ref):
        assert a * d == b * c  # the same rational function of nu
        assert format_coefficient(a, b) == format_coefficient(c, d)  # and the same text


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.sampled_from(["S0", "A0"]), st.integers(2, 8))
def test_exact_series_fast_route_equals_reference_route(monkeypatch, branch, half):
    if branch == "A0" and half < 2:
        half = 2
    _check_exact(monkeypatch, branch, 2 * half)


@pytest.mark.slow
@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.sampled_from(["S0", "A0"]), st.integers(9, 32))
def test_exact_series_fast_route_equals_reference_route_high_orders(monkeypatch, branch, half):
    _check_exact(monkeypatch, branch, 2 * half)


@pytest.mark.slow
@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(characteristic(max_order=16), st.fractions(min_value=-5, max_value=5, max_denominator=30))
def test_fast_route_equals_reference_route_larger(case, g):
    test_fast_route_equals_reference_route_and_solves_the_equation.hypothesis.inner_test(case, g)


def test_fmpq_poly_round_trip():
    # the representation change itself: any polynomial in g survives _to_uni / _from_uni
    p = _poly_g([flint.fmpq(3, 7), 0, -5, flint.fmpq(1, 11)])
    assert _k._from_uni(CTX, _k._to_uni(p)) == p
    assert _k._from_uni(CTX, _k._to_uni(CTX.from_dict({}))) == CTX.from_dict({})


@settings(max_examples=60, deadline=None)
@given(st.lists(st.integers(-50, 50), min_size=1, max_size=8), st.integers(0, 4),
       st.fractions(min_value=-3, max_value=3, max_denominator=11).filter(lambda v: v != 1))
def test_g_to_nu_equals_direct_substitution(coeffs, extra, nu):
    # p(g) (2 (1 - nu))^e at g = (1 - 2 nu) / (2 (1 - nu)), evaluated directly with Fractions
    from dispersion.continuum.exact_series import _g_to_nu

    p = _poly_g(coeffs)
    e = len(coeffs) - 1 + extra
    g = (1 - 2 * nu) / (2 * (1 - nu))
    direct = sum(Fraction(c) * g**i for i, c in enumerate(coeffs)) * (2 * (1 - nu)) ** e
    value = _g_to_nu(p, e)(flint.fmpq(nu.numerator, nu.denominator))
    assert Fraction(int(value.p), int(value.q)) == direct
