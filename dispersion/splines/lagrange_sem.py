"""C0 Lagrange elements of degree p with Gauss-Lobatto-Legendre points: the spectral element method.

The space of continuous piecewise polynomials of degree p is the B-spline space whose
interior knots repeat p times (:func:`c0_knot_vector`); its Bernstein (B-spline) basis and the
nodal Lagrange basis at the p + 1 Gauss-Lobatto-Legendre (GLL) points of each element span
the same functions. Two masses on it:

* ``sem-consistent``: the Gram matrix (consistent mass of the Lagrange elements);
* ``sem-lumped``: GLL quadrature with the p + 1 element nodes, diagonal in the nodal basis
  (the spectral element method, Maday and Patera 1989). In the Bernstein basis the same mass
  is :func:`dispersion.splines.spline_mass.lobatto_matrix` of the C0 knot vector, congruent
  to the diagonal one by the collocation matrix at the GLL nodes, so every frequency is the
  same; it is derived exactly through the Lobatto error term (no irrational node is formed).

The stiffness is the C0 space's own (:func:`element_matrices`), not the smooth B-splines':
the rules change the basis, not only the mass (``MassRule.basis == "lagrange"``).

On the periodic bar (unit elements) the interior DOFs of an element condense at each
frequency :math:`\\lambda = (\\omega h / c)^2`: the element's dynamic stiffness reduces to
:math:`\\begin{bmatrix} a & b \\\\ b & a \\end{bmatrix}` on its end nodes and a Bloch wave
gives the exact dispersion relation

.. math:: \\cos\\theta = -a(\\lambda) / b(\\lambda)

(:func:`condensed_cos_series`), whose reversion :func:`acoustic_series` is the acoustic
branch :math:`\\lambda(\\theta)` as an exact power series.

>>> acoustic_series("sem-consistent", 1, 3)[:3]     # p = 1: the linear element, theta^2 (1 + theta^2/12)
[Fraction(1, 1), Fraction(1, 12), Fraction(1, 360)]

References
----------
Y. Maday, A. T. Patera, "Spectral element methods for the incompressible Navier-Stokes
equations", in State-of-the-Art Surveys on Computational Mechanics, ASME (1989) 71-143.
M. Ainsworth, H. A. Wajid, "Dispersive and dissipative behavior of the spectral element
method", SIAM J. Numer. Anal. 47 (2009) 3910-3937, doi:10.1137/080724976.
"""
from __future__ import annotations

import math
from fractions import Fraction
from functools import lru_cache

import sympy

from dispersion.errors import InputError, check_positive_int

__all__ = ["SEM_RULES", "c0_knot_vector", "c0_elements", "element_matrices",
           "condensed_cos_series", "acoustic_series"]

SEM_RULES = ("sem-consistent", "sem-lumped")


def c0_knot_vector(p: int, n_elements: int, a=0, b=1):
    """Open knot vector of the C0 space: each interior breakpoint repeated p times.

    >>> [str(k) for k in c0_knot_vector(2, 2).knots]
    ['0', '0', '0', '1/2', '1/2', '1', '1', '1']
    """
    from dispersion.splines.bspline import KnotVector

    p = check_positive_int("degree p", p)
    ne = check_positive_int("elements", n_elements)
    from dispersion.reader import rational

    a, b = rational("interval end a", a), rational("interval end b", b)
    inner = [a + (b - a) * sympy.Rational(e, ne) for e in range(1, ne)]
    return KnotVector(tuple([a] * (p + 1) + [k for k in inner for _ in range(p)]
                            + [b] * (p + 1)), p)


def c0_elements(p: int, n: int) -> int:
    """Elements of the C0 space with ``n`` DOFs: ``(n - 1) / p``, else :class:`InputError`."""
    if (n - 1) % p:
        raise InputError(f"Lagrange elements of degree p = {p} need n = p * elements + 1 "
                         f"control points (n - 1 divisible by p), got n = {n}")
    return (n - 1) // p


@lru_cache(maxsize=None)
def element_matrices(mass: str, p: int) -> tuple[sympy.ImmutableMatrix, sympy.ImmutableMatrix]:
    """Stiffness and mass of one unit element (Bernstein basis, ends first and last)."""
    from dispersion.splines.bspline import open_knot_vector
    from dispersion.splines.derivative_gram import derivative_gram
    from dispersion.splines.spline_mass import gram_matrix, lobatto_matrix

    if mass not in SEM_RULES:
        raise InputError(f"mass must be one of {', '.join(SEM_RULES)}, got {mass!r}")
    p = check_positive_int("degree p", p)
    kv = open_knot_vector(p, 1, 0, 1)
    K = derivative_gram(kv)
    M = gram_matrix(kv) if mass == "sem-consistent" else lobatto_matrix(kv)
    return sympy.ImmutableMatrix(K), sympy.ImmutableMatrix(M)


def _series_inverse(A: sympy.Matrix, B: sympy.Matrix, K: int) -> list[sympy.Matrix]:
    """Power series of :math:`(A - \\lambda B)^{-1} = \\sum_k \\lambda^k (A^{-1} B)^k A^{-1}`."""
    Ai = A.inv()
    out, T = [], Ai
    for _ in range(K + 1):
        out.append(T)
        T = Ai * B * T
    return out


@lru_cache(maxsize=None)
def condensed_cos_series(mass: str, p: int, K: int) -> tuple[Fraction, ...]:
    """Coefficients :math:`f_k` of :math:`\\cos\\theta = -a(\\lambda)/b(\\lambda) = \\sum f_k \\lambda^k`."""
    Ke, Me = (sympy.Matrix(m) for m in element_matrices(mass, p))
    inner = list(range(1, p))
    a = [Ke[0, 0] if k == 0 else (-Me[0, 0] if k == 1 else sympy.Integer(0))
         for k in range(K + 1)]
    b = [Ke[0, p] if k == 0 else (-Me[0, p] if k == 1 else sympy.Integer(0))
         for k in range(K + 1)]
    if inner:
        inv = _series_inverse(Ke.extract(inner, inner), Me.extract(inner, inner), K)
        for name, col in (("a", 0), ("b", p)):
            target = a if name == "a" else b
            # - D_0i D_ii^{-1} D_i,col with D = K - lambda M: a product of three series
            D0 = [Ke.extract([0], inner), -Me.extract([0], inner)]
            Dc = [Ke.extract(inner, [col]), -Me.extract(inner, [col])]
            for i in range(2):
                for j in range(K + 1):
                    for k in range(2):
                        if i + j + k <= K:
                            target[i + j + k] -= (D0[i] * inv[j] * Dc[k])[0, 0]
    # -a / b as a power series (b_0 != 0)
    q: list[sympy.Rational] = []
    for k in range(K + 1):
        q.append((-a[k] - sum((q[j] * b[k - j] for j in range(k)), sympy.Integer(0))) / b[0])
    return tuple(Fraction(int(v.p), int(v.q)) for v in q)


def acoustic_series(mass: str, p: int, K: int) -> list[Fraction]:
    """Coefficients :math:`l_k` of :math:`\\lambda(\\theta)/\\theta^2 = \\sum_{k} l_k \\theta^{2k}`,
    k = 0..K - 1, the acoustic branch from :func:`condensed_cos_series` by series reversion."""
    K = check_positive_int("terms K", K)
    f = condensed_cos_series(mass, p, K + 1)
    c = [Fraction((-1) ** k, math.factorial(2 * k)) for k in range(K + 2)]  # cos, t = theta^2
    lam: list[Fraction] = [Fraction(0)]  # lambda(t) coefficients, lambda_0 = 0
    for k in range(1, K + 1):
        # coefficient of t^k in sum_j f_j lambda(t)^j with lambda_k unknown (enters as f_1 l_k)
        lam.append(Fraction(0))
        total = Fraction(0)
        power = [Fraction(1)] + [Fraction(0)] * k  # lambda^0
        for j in range(1, k + 1):
            power = [sum((power[i] * lam[m - i] for i in range(m + 1)), Fraction(0))
                     for m in range(k + 1)]
            total += f[j] * power[k]
        lam[k] = (c[k] - total) / f[1]
    return lam[1:]
