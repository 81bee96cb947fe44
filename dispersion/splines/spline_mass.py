"""Exact mass matrices of 1D B-spline spaces: Gram, HRZ, nodal quadrature, periodic rows.

The numbers behind the built-in rules of :mod:`dispersion.mass_rules.mass_rule`, in exact
rational arithmetic (``fractions.Fraction``) from the Bezier extraction of the knot vector
(:mod:`dispersion.splines.bspline`) and the Bernstein Gram integrals
:math:`\\int_0^1 B_i B_j = \\binom{p}{i}\\binom{p}{j} / ((2p+1)\\binom{2p}{i+j})`:

* :func:`gram_matrix` :math:`\\int N N^T`; :func:`hrz_matrix` (element diagonal scaled to
  the element mass, assembled);
* :func:`greville_matrix`: quadrature at the Greville points with weights :math:`\\int N_q`;
* :func:`lobatto_matrix`: p + 1 Gauss-Lobatto points per element, exact through the Lobatto
  error term (Abramowitz, Stegun 25.4.32), so no irrational point is ever formed;
* :data:`PERIODIC_ROWS`: the same rules on the uniform periodic mesh as one assembled row
  :math:`a_L` (the Bloch coefficients of the x-direction), from the cardinal B-spline.

>>> from dispersion.splines.bspline import open_knot_vector
>>> hrz_matrix(open_knot_vector(2, 1, -1, 1)).tolist()
[[3/4, 0, 0], [0, 1/2, 0], [0, 0, 3/4]]

References
----------
E. Hinton, T. Rock, O. C. Zienkiewicz, Earthq. Eng. Struct. Dyn. 4 (1976) 245-249.
M. J. Borden et al., IJNME 87 (2011) 15-47. M. Abramowitz, I. Stegun, 25.4.32.
"""
from __future__ import annotations

import math
from fractions import Fraction
from functools import lru_cache

import numpy as np
import sympy

from dispersion.errors import check_positive_int

__all__ = ["gram_matrix", "hrz_matrix", "greville_matrix", "lobatto_matrix", "lobatto_rule",
           "PERIODIC_ROWS"]


@lru_cache(maxsize=64)
def _elements(kv) -> tuple:
    """Per span: ``(a, b, active, C)``, C the exact extraction operator as Fractions (Borden 2011)."""
    from dispersion.splines.bspline import as_fraction_matrix, extraction_operators

    return tuple((Fraction(int(a.p), int(a.q)), Fraction(int(b.p), int(b.q)), tuple(act),
                  as_fraction_matrix(C)) for (a, b), act, C in extraction_operators(kv))


@lru_cache(maxsize=None)
def _bernstein_gram(p: int) -> np.ndarray:
    r""":math:`\int_0^1 B_i B_j du = \binom{p}{i}\binom{p}{j} / ((2p+1)\binom{2p}{i+j})`."""
    return np.array([[Fraction(math.comb(p, i) * math.comb(p, j),
                               (2 * p + 1) * math.comb(2 * p, i + j)) for j in range(p + 1)]
                     for i in range(p + 1)], dtype=object)


def _bernstein_at(p: int, u: Fraction) -> np.ndarray:
    return np.array([math.comb(p, b) * u**b * (1 - u) ** (p - b) for b in range(p + 1)],
                    dtype=object)


def _element_gram(a, b, C, p):
    return (b - a) * C.dot(_bernstein_gram(p)).dot(C.T)


def _to_sympy(A: np.ndarray) -> sympy.ImmutableMatrix:
    return sympy.ImmutableMatrix(A.shape[0], A.shape[1],
                                 lambda i, j: sympy.Rational(A[i, j].numerator,
                                                             A[i, j].denominator))


def _zeros(n: int) -> np.ndarray:
    return np.full((n, n), Fraction(0), dtype=object)


@lru_cache(maxsize=64)
def gram_matrix(kv) -> sympy.ImmutableMatrix:
    M = _zeros(kv.n)
    for a, b, act, C in _elements(kv):
        M[np.ix_(act, act)] += _element_gram(a, b, C, kv.p)
    return _to_sympy(M)


@lru_cache(maxsize=64)
def hrz_matrix(kv) -> sympy.ImmutableMatrix:
    d = np.full(kv.n, Fraction(0), dtype=object)
    for a, b, act, C in _elements(kv):
        Me = _element_gram(a, b, C, kv.p)
        diag = np.array([Me[k, k] for k in range(len(act))], dtype=object)
        d[list(act)] += diag * (Me.sum() / diag.sum())
    return _to_sympy(np.diag(d) + _zeros(kv.n))


@lru_cache(maxsize=64)
def greville_matrix(kv) -> sympy.ImmutableMatrix:
    n, p = kv.n, kv.p
    w = np.full(n, Fraction(0), dtype=object)
    for a, b, act, C in _elements(kv):
        w[list(act)] += (b - a) * C.dot(np.full(p + 1, Fraction(1, p + 1), dtype=object))
    g = [Fraction(int(x.p), int(x.q)) for x in kv.greville()]
    N = _zeros(n)  # N[q, i] = N_i(g_q)
    last = Fraction(int(kv.knots[-1].p), int(kv.knots[-1].q))
    for a, b, act, C in _elements(kv):
        for q, gq in enumerate(g):
            # a point on a knot belongs to the span on its right (the last one to its left)
            if a <= gq < b or (gq == b == last):
                N[q, list(act)] = C.dot(_bernstein_at(p, (gq - a) / (b - a)))
    return _to_sympy(N.T.dot(np.diag(w) + _zeros(n)).dot(N))


def lobatto_rule(m: int) -> tuple[np.ndarray, np.ndarray]:
    """Float Gauss-Lobatto points and weights on [-1, 1] with ``m >= 2`` points.

    Points: :math:`\\pm 1` and the roots of :math:`P'_{m-1}`; weights
    :math:`2 / (m (m-1) P_{m-1}(x_q)^2)` (Abramowitz, Stegun 25.4.32).

    >>> x, w = lobatto_rule(3)
    >>> x.round(12).tolist(), w.round(12).tolist()
    ([-1.0, 0.0, 1.0], [0.333333333333, 1.333333333333, 0.333333333333])
    """
    m = check_positive_int("Lobatto points m", m, minimum=2)
    P = np.polynomial.legendre.Legendre.basis(m - 1)
    inner = np.sort(P.deriv().roots().real) if m > 2 else np.array([])
    x = np.concatenate([[-1.0], inner, [1.0]])
    return x, 2.0 / (m * (m - 1) * P(x) ** 2)


def _lobatto_error_constant(m: int) -> sympy.Rational:
    """:math:`K_m` with :math:`Q_m(g) = \\int_{-1}^1 g + K_m g^{(2m-2)}` for deg g <= 2m - 2.

    Abramowitz, Stegun 25.4.32: the Lobatto error is
    :math:`-\\frac{m (m-1)^3 2^{2m-1} ((m-2)!)^4}{(2m-1) ((2m-2)!)^3} f^{(2m-2)}(\\xi)`.
    """
    f = sympy.factorial
    return sympy.Rational(m * (m - 1) ** 3 * 2 ** (2 * m - 1) * f(m - 2) ** 4,
                          (2 * m - 1) * f(2 * m - 2) ** 3)


@lru_cache(maxsize=64)
def lobatto_matrix(kv) -> sympy.ImmutableMatrix:
    # p + 1 Lobatto points per span integrate N_i N_j (degree 2p) up to the error term, which
    # is exact and rational: Q = (h/2) (int g + K g^(2p)) with g the product in s in [-1, 1];
    # g^(2p) = (2p)! lead_i lead_j / 2^(2p), lead the u^p coefficient (u = (s + 1)/2)
    p, n = kv.p, kv.n
    K = _lobatto_error_constant(p + 1)
    K = Fraction(int(K.p), int(K.q))
    lead_b = np.array([math.comb(p, b) * (-1) ** (p - b) for b in range(p + 1)], dtype=object)
    M = _zeros(n)
    for a, b, act, C in _elements(kv):
        lead = C.dot(lead_b)
        corr = (b - a) / 2 * K * math.factorial(2 * p) / 2 ** (2 * p) * np.outer(lead, lead)
        M[np.ix_(act, act)] += _element_gram(a, b, C, p) + corr
    return _to_sympy(M)


@lru_cache(maxsize=None)
def _uniform_powers(p: int) -> np.ndarray:
    """Power-basis coefficients (row k: :math:`u^0..u^p`) of the p + 1 functions on the unit
    span [0, 1] of a uniform mesh, left to right: function k is the cardinal piece p - k,
    :math:`N(j + u) = \\frac{1}{p!} \\sum_{i \\le j} (-1)^i \\binom{p+1}{i} (j - i + u)^p`."""
    P = np.full((p + 1, p + 1), Fraction(0), dtype=object)
    for k in range(p + 1):
        j = p - k
        for i in range(j + 1):
            c = Fraction((-1) ** i * math.comb(p + 1, i), math.factorial(p))
            for m in range(p + 1):
                P[k, m] += c * math.comb(p, m) * (j - i) ** (p - m)
    return P


def _uniform_gram(p: int) -> np.ndarray:
    P = _uniform_powers(p)
    H = np.array([[Fraction(1, i + j + 1) for j in range(p + 1)] for i in range(p + 1)],
                 dtype=object)
    return P.dot(H).dot(P.T)


def _periodic_row(E: np.ndarray) -> dict:
    """Row of the assembled periodic matrix of one element matrix E on unit elements:
    :math:`a_L = \\sum_k E_{k, k+L}` (a function meets the p + 1 elements as k = 0..p)."""
    q = E.shape[0]
    return {L: sum((E[k, k + L] for k in range(q) if 0 <= k + L < q), Fraction(0))
            for L in range(-(q - 1), q)}


def _uniform_consistent(p):
    return _periodic_row(_uniform_gram(p))


def _uniform_lumped(p):
    return {0: Fraction(1)}  # row sums of a partition of unity on unit elements


def _uniform_hrz(p):
    Me = _uniform_gram(p)
    d = np.array([Me[k, k] for k in range(p + 1)], dtype=object)
    return _periodic_row(np.diag(d * (Me.sum() / d.sum())) + _zeros(p + 1))


def _uniform_lobatto(p):
    K = _lobatto_error_constant(p + 1)
    lead = _uniform_powers(p)[:, p]  # u^p coefficients (u in [0, 1], unit span)
    corr = Fraction(int(K.p), int(K.q)) * math.factorial(2 * p) / 2 ** (2 * p + 1) \
        * np.outer(lead, lead)
    return _periodic_row(_uniform_gram(p) + corr)


def _cardinal(p: int, x: Fraction) -> Fraction:
    """Cardinal B-spline on [0, p+1]: :math:`\\frac{1}{p!} \\sum_i (-1)^i \\binom{p+1}{i} (x-i)_+^p`."""
    return sum((Fraction((-1) ** i * math.comb(p + 1, i)) * (x - i) ** p
                for i in range(p + 2) if x > i), Fraction(0)) / math.factorial(p)


def _uniform_greville(p):
    # function j: N(x - j), Greville point j + (p+1)/2, weight 1 (unit elements)
    c = Fraction(p + 1, 2)
    vals = {j: _cardinal(p, c + j) for j in range(-p - 1, p + 2)}  # N_0 at g_j
    return {L: sum((vals[j] * vals[j - L] for j in vals if j - L in vals), Fraction(0))
            for L in range(-p, p + 1)}


#: Closed periodic rows of the built-in rules (the mesh fallback gives the same; tested).
PERIODIC_ROWS = {"consistent": _uniform_consistent, "lumped": _uniform_lumped, "hrz": _uniform_hrz,
            "nodal-lobatto": _uniform_lobatto, "nodal-greville": _uniform_greville}
