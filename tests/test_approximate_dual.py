"""Approximate dual B-splines (dispersion.mass_rules.approximate_dual): reproduction, symbol,
Petrov-Galerkin = Galerkin with S^-1, Dirichlet treatment; every check against an independent
computation (sympy integration of the basis polynomials, mpmath at 50 digits)."""
from __future__ import annotations

import mpmath
import numpy as np
import pytest
import scipy.linalg as sla
import sympy
from hypothesis import example, given, settings
from hypothesis import strategies as st

from dispersion.errors import InputError
from dispersion.splines import bspline
from dispersion.mass_rules.approximate_dual import (
    approximate_dual_matrix,
    customized_mass,
    dirichlet_dual,
    dual_symbol,
    monomial_coefficients,
)
from dispersion.splines.bspline import open_knot_vector

x = sympy.Symbol("x")


def _integral(f, a, b):
    prim = sympy.Poly(f, x).integrate()
    return prim.eval(b) - prim.eval(a)


def _integrals(kv, weight):
    """int N_i * weight(x) dx for every basis function, by polynomial integration of the
    basis pieces in x (independent of the Bernstein-Gram route of spline_mass)."""
    out = [sympy.Integer(0)] * kv.n
    for (a, b), polys, active in bspline.basis_polynomials(kv, x, local=False):
        for i, f in zip(active, polys):
            out[i] += _integral(f * weight, a, b)
    return out


def _gram(kv, deriv=0):
    K = sympy.zeros(kv.n, kv.n)
    for (a, b), polys, active in bspline.basis_polynomials(kv, x, local=False):
        d = [sympy.Poly(f, x).diff(x) if deriv else sympy.Poly(f, x) for f in polys]
        for i, fi in zip(active, d):
            for j, fj in zip(active, d):
                prim = (fi * fj).integrate()
                K[i, j] += prim.eval(b) - prim.eval(a)
    return K


def _stiffness(kv):
    return _gram(kv, 1)


@settings(max_examples=8, deadline=None)
@given(p=st.integers(1, 3), ne=st.integers(1, 5), data=st.data())
@example(p=1, ne=1, data=None)
@example(p=3, ne=5, data=None)
def test_dual_reproduces_polynomials(p, ne, data):
    # int S N x^k = B-spline coefficient of x^k for k <= q, every q in [0, p]; the coefficients
    # are checked to represent x^k (Marsden), the integrals come from sympy
    q = p if data is None else data.draw(st.integers(0, p))
    kv = open_knot_vector(p, ne, 0, sympy.Rational(ne, 2))
    S = sympy.Matrix(approximate_dual_matrix(kv, q))
    for k in range(q + 1):
        c = monomial_coefficients(kv, k)
        for (a, b), polys, active in bspline.basis_polynomials(kv, x, local=False):
            assert sympy.expand(sum(sympy.Rational(c[i].numerator, c[i].denominator) * f
                                    for i, f in zip(active, polys)) - x**k) == 0
        lhs = S * sympy.Matrix(_integrals(kv, x**k))
        assert list(lhs) == [sympy.Rational(v.numerator, v.denominator) for v in c]


@pytest.mark.parametrize("p", [1, 2, 3, 4])
def test_interior_rows_are_the_uniform_symbol(p):
    # the linear-solve route on a long open mesh against the series route of 1/g
    ne = 3 * p + 3
    S = approximate_dual_matrix(open_knot_vector(p, ne, 0, ne))
    mid = S.rows // 2
    row = {L: S[mid, mid + L] for L in range(-p, p + 1) if S[mid, mid + L] != 0}
    assert row == dual_symbol(p)


@pytest.mark.parametrize("p", [2, 3])
def test_petrov_galerkin_lumped_is_galerkin_with_inverse_dual(p):
    # row sums of S G are one; eig(S K) = eig(K, S^-1) (the Galerkin interpretation)
    kv = open_knot_vector(p, 4, 0, 4)
    S = sympy.Matrix(approximate_dual_matrix(kv))
    G = _gram(kv)
    assert list((S * G) * sympy.ones(kv.n, 1)) == [1] * kv.n
    K = _stiffness(kv)
    pg = np.sort(np.linalg.eigvals(np.array(S * K, dtype=float)).real)
    gal = sla.eigh(np.array(K, dtype=float), np.array(customized_mass(kv), dtype=float),
                   eigvals_only=True)
    assert np.allclose(pg, gal, rtol=1e-9, atol=1e-9)


def test_customized_mass_keeps_total_mass_and_is_definite():
    for p in (1, 2, 3, 4):
        kv = open_knot_vector(p, 3, -1, 1)
        M = customized_mass(kv)
        assert M.is_symmetric() and sum(M) == 2
        assert min(np.linalg.eigvalsh(np.array(M, dtype=float))) > 0


def test_dirichlet_dual_is_the_inverse_of_the_restricted_galerkin_mass():
    kv = open_knot_vector(2, 4)
    S = sympy.Matrix(approximate_dual_matrix(kv))
    M = S.inv()
    for c in ([0], [0, kv.n - 1]):
        r = [i for i in range(kv.n) if i not in c]
        assert dirichlet_dual(S, c) == M.extract(r, r).inv()
    with pytest.raises(InputError, match="constrained"):
        dirichlet_dual(S, [kv.n])


@pytest.mark.parametrize("q", [-1, 3, True])
def test_bad_reproduction_degree(q):
    with pytest.raises(InputError, match="reproduction degree q"):
        approximate_dual_matrix(open_knot_vector(2, 2), q)


@settings(max_examples=10, deadline=None)
@given(p=st.integers(1, 2), theta=st.floats(0.05, float(np.pi)))
@example(p=1, theta=float(np.pi))
@example(p=2, theta=0.05)
def test_bar_symbol_matches_the_assembled_operator(p, theta):
    _check_bar_symbol(p, theta)


@pytest.mark.slow
@settings(max_examples=30, deadline=None)
@given(p=st.integers(1, 4), theta=st.floats(0.05, float(np.pi)))
@example(p=4, theta=float(np.pi))
@example(p=4, theta=0.05)
def test_bar_symbol_matches_the_assembled_operator_every_degree(p, theta):
    _check_bar_symbol(p, theta)


def _check_bar_symbol(p, theta):
    # the bar's omega^2 from the Bloch symbols (bar_frequency: d * s / 1) against the
    # assembled open-mesh S K applied to a Bloch wave in the interior, at 50 digits
    from dispersion.discretization.bar_dispersion import bar_frequency

    ne = 4 * p + 4  # the middle row of S K sees uniform knots only
    kv = open_knot_vector(p, ne, 0, ne)
    SK = approximate_dual_matrix(kv) * _stiffness_cached(p, ne)
    mid = kv.n // 2
    with mpmath.workdps(50):
        th = mpmath.mpf(theta)
        val = sum(mpmath.mpf(SK[mid, j].p) / SK[mid, j].q * mpmath.cos((j - mid) * th)
                  for j in range(kv.n) if SK[mid, j] != 0)
    assert float(val) == pytest.approx(float(bar_frequency(p, "dual-lumped", theta)) ** 2,
                                       rel=1e-9, abs=1e-12)


_K: dict = {}


def _stiffness_cached(p, ne):
    if (p, ne) not in _K:
        _K[(p, ne)] = _stiffness(open_knot_vector(p, ne, 0, ne))
    return _K[(p, ne)]
