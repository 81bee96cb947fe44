"""Exact Gram matrices of B-spline derivatives, :math:`\\int N' N'^T`, for rules that need them.

Selective mass scaling adds a multiple of :math:`\\int N' N'^T`
(:mod:`dispersion.mass_rules.mass_scaling`) and a C0 Lagrange element is stiffened by it
(:mod:`dispersion.splines.lagrange_sem`); both sit below the plate in the import order, so
the integrals are taken here from the basis pieces of :mod:`dispersion.splines.bspline`
(polynomial integration, exact) and, on the uniform periodic mesh, from the cardinal
B-spline's pieces of :mod:`dispersion.splines.spline_mass`.

>>> from dispersion.splines.bspline import open_knot_vector
>>> derivative_gram(open_knot_vector(1, 1)).tolist()
[[1, -1], [-1, 1]]
>>> uniform_derivative_row(1)
{-1: Fraction(-1, 1), 0: Fraction(2, 1), 1: Fraction(-1, 1)}
"""
from __future__ import annotations

from fractions import Fraction
from functools import lru_cache

__all__ = ["derivative_gram", "uniform_derivative_row"]


@lru_cache(maxsize=64)
def derivative_gram(kv):
    """:math:`\\int N'_i N'_j` over the knot vector ``kv``, an exact sympy matrix."""
    import sympy

    from dispersion.splines import bspline

    x = sympy.Symbol("x")
    n = kv.n
    D = sympy.zeros(n, n)
    for (a, b), polys, active in bspline.basis_polynomials(kv, x, local=False):
        ders = [sympy.Poly(f, x).diff(x) for f in polys]
        for i, gi in zip(active, ders):
            for j, gj in zip(active, ders):
                prim = (gi * gj).integrate()
                D[i, j] += prim.eval(b) - prim.eval(a)
    return sympy.ImmutableMatrix(D)


@lru_cache(maxsize=None)
def uniform_derivative_row(p: int) -> dict[int, Fraction]:
    """The periodic row :math:`c^{11}_L = \\int N_0' N_L'` on unit elements (zeros dropped)."""
    import numpy as np

    from dispersion.splines.spline_mass import _periodic_row, _uniform_powers

    P = _uniform_powers(p)  # row k: u^0..u^p coefficients of the piece on the unit span
    D = np.array([[m * P[k, m] for m in range(1, p + 1)] for k in range(p + 1)], dtype=object)
    H = np.array([[Fraction(1, i + j + 1) for j in range(p)] for i in range(p)], dtype=object)
    row = _periodic_row(D.dot(H).dot(D.T))
    return {L: v for L, v in sorted(row.items()) if v != 0}
