"""Approximate dual B-splines: the test functions of higher-order accurate mass lumping.

An *approximate dual* of the B-splines :math:`N_i` of degree p is a set of splines
:math:`\\tilde N_i = \\sum_j S_{ij} N_j` with local support whose inner products with every
polynomial :math:`f` of degree :math:`\\le q` give the B-spline coefficients of f,

.. math::

    \\int \\tilde N_i \\, f = \\lambda_i(f), \\qquad f \\in \\mathcal P_q, \\quad
    f = \\sum_i \\lambda_i(f) N_i ,

i.e. :math:`S G c_f = c_f` with :math:`G = \\int N N^T` the Gram matrix and :math:`c_f` the
coefficients (Marsden's identity: :math:`x^k = \\sum_i \\sigma_k(t_{i+1..i+p}) / \\binom{p}{k}
N_i`). Following Chui, He, Stoeckler (2004) as used by Nguyen et al. (2023), the matrix has
the form

.. math::

    S_q = \\sum_{v=0}^{q} \\Delta_v U_v \\Delta_v^T, \\qquad
    \\Delta_v = \\prod_{l=1}^{v} D(t, p + l), \\quad
    D(t, k)_{jj} = a_j, \\; D(t, k)_{j+1, j} = -a_{j+1}, \\; a_j = \\frac{k}{t_{j+k} - t_j},

with diagonal :math:`U_v`. Here the :math:`U_v` are *derived* (not tabulated): level by
level, :math:`U_v` is the unique diagonal for which :math:`S_v` reproduces :math:`\\mathcal
P_v` (an exact rational linear solve; uniqueness is checked, and the levels are nested, so
:math:`S_q` for every :math:`q \\le p` comes from one sequence). On uniform knots the symbol
of :math:`S_q` is the Taylor polynomial of degree q of :math:`1/g` in
:math:`w = 2 - 2\\cos\\theta` (g the Gram symbol): :func:`dual_symbol`, tested.

**Mass lumping** (Nguyen et al. 2023): the Petrov-Galerkin mass :math:`S G` has row sums
:math:`S G \\mathbf 1 = \\mathbf 1` (reproduction of constants), so row-sum lumping gives the
identity and the scheme is :math:`\\ddot u = S (f - K u)`: explicit, with the banded S.
**Galerkin interpretation** (Hiemstra et al. 2025): the same equations are the Galerkin
method with the customized mass :math:`M = S^{-1}` (symmetric positive definite, dense, its
inverse banded): :func:`customized_mass`. **Dirichlet boundary** (Hiemstra et al. 2025): a
constrained DOF removed from the Galerkin form keeps :math:`M_{rr} = (S^{-1})_{rr}`, whose
inverse is the Schur complement :math:`S_{rr} - S_{rc} S_{cc}^{-1} S_{cr}`, still banded:
:func:`dirichlet_dual`.

>>> from dispersion.splines.bspline import open_knot_vector
>>> S = approximate_dual_matrix(open_knot_vector(1, 2), 1)
>>> S.tolist()
[[6, -1, 0], [-1, 3, -1], [0, -1, 6]]
>>> dual_symbol(2, 2)          # 1 + w/4 + 13 w^2/240, w = 2 - 2 cos(theta)
{-2: 13/240, -1: -7/15, 0: 73/40, 1: -7/15, 2: 13/240}

References
----------
C. K. Chui, W. He, J. Stoeckler, "Nonstationary tight wavelet frames, I: Bounded intervals",
Appl. Comput. Harmon. Anal. 17 (2004) 141-197, doi:10.1016/j.acha.2004.02.003.
T.-H. Nguyen, R. R. Hiemstra, S. Eisentraeger, D. Schillinger, "Towards higher-order accurate
mass lumping in explicit isogeometric analysis for structural dynamics", CMAME 417 (2023)
116233, doi:10.1016/j.cma.2023.116233, arXiv:2305.12916 (approximate dual test functions,
row-sum lumping). R. R. Hiemstra, T.-H. Nguyen, S. Eisentraeger, W. Dornisch, D. Schillinger,
"Higher-order accurate mass lumping for explicit isogeometric methods based on approximate
dual basis functions", Comput. Mech. 76 (2025) 205-226, doi:10.1007/s00466-025-02596-3
(Galerkin interpretation as a customized mass matrix; Dirichlet conditions).
"""
from __future__ import annotations

import math
from fractions import Fraction
from functools import lru_cache
from itertools import combinations

import sympy

from dispersion.errors import InputError, check_positive_int

__all__ = ["approximate_dual_matrix", "customized_mass", "dirichlet_dual", "dual_symbol",
           "monomial_coefficients", "bloch_product"]


def _knots(kv) -> list[Fraction]:
    return [Fraction(int(k.p), int(k.q)) for k in kv.knots]


def monomial_coefficients(kv, k: int) -> list[Fraction]:
    """B-spline coefficients of :math:`x^k` (Marsden's identity), exact.

    >>> from dispersion.splines.bspline import open_knot_vector
    >>> [str(c) for c in monomial_coefficients(open_knot_vector(2, 2), 1)]   # Greville points
    ['0', '1/4', '3/4', '1']
    """
    t, p = _knots(kv), kv.p
    if not 0 <= k <= p:
        raise InputError(f"monomial degree k must lie in [0, {p}], got {k}")
    return [sum((math.prod(s, start=Fraction(1)) for s in combinations(t[i + 1:i + p + 1], k)),
                Fraction(0)) / math.comb(p, k) for i in range(kv.n)]


def _difference(t: list[Fraction], k: int) -> list[list[Fraction]]:
    """:math:`D(t, k)`: rows len(t) - k, columns one fewer (module docstring)."""
    rows = len(t) - k
    a = [Fraction(k) / (t[j + k] - t[j]) for j in range(rows)]
    D = [[Fraction(0)] * (rows - 1) for _ in range(rows)]
    for j in range(rows - 1):
        D[j][j], D[j + 1][j] = a[j], -a[j + 1]
    return D


def _matmul(A, B):
    return [[sum((A[i][k] * B[k][j] for k in range(len(B))), Fraction(0))
             for j in range(len(B[0]))] for i in range(len(A))]


@lru_cache(maxsize=64)
def _levels(kv, q: int) -> tuple:
    """``(Delta_v, U_v)`` for v = 0..q as Fraction lists (module docstring)."""
    from dispersion.splines.spline_mass import gram_matrix

    n, p = kv.n, kv.p
    t = _knots(kv)
    G = [[Fraction(int(v.p), int(v.q)) for v in row] for row in gram_matrix(kv).tolist()]
    coeffs = [monomial_coefficients(kv, k) for k in range(q + 1)]
    moments = [[sum((G[i][j] * c[j] for j in range(n)), Fraction(0)) for i in range(n)]
               for c in coeffs]  # G c_k
    S = [[Fraction(0)] * n for _ in range(n)]
    Delta = [[Fraction(int(i == j)) for j in range(n)] for i in range(n)]
    out = []
    for v in range(q + 1):
        if v:
            Delta = _matmul(Delta, _difference(t, p + v))
        m = n - v
        # equations: Delta diag(Delta^T G c_k) u = c_k - S G c_k, k = 0..v
        rows, rhs = [], []
        for k in range(v + 1):
            w = [sum((Delta[i][j] * moments[k][i] for i in range(n)), Fraction(0))
                 for j in range(m)]
            resid = [coeffs[k][i] - sum((S[i][j] * moments[k][j] for j in range(n)),
                                        Fraction(0)) for i in range(n)]
            for i in range(n):
                rows.append([Delta[i][j] * w[j] for j in range(m)])
                rhs.append(resid[i])
        A = sympy.Matrix(rows)
        b = sympy.Matrix(rhs)
        try:
            sol, params = A.gauss_jordan_solve(b)
        except ValueError:
            raise InputError(f"no approximate dual of reproduction degree {v} on this knot "
                             "vector (the reproduction equations are inconsistent)") from None
        if params.shape[0]:
            raise InputError(f"the approximate dual of level {v} is not unique on this knot "
                             "vector")
        u = [Fraction(int(x.p), int(x.q)) for x in sol]
        for i in range(n):
            for j in range(n):
                S[i][j] += sum((Delta[i][l] * u[l] * Delta[j][l] for l in range(m)),
                               Fraction(0))
        out.append((Delta, u))
    return tuple(out), tuple(tuple(row) for row in S)


def approximate_dual_matrix(kv, q: int | None = None) -> sympy.ImmutableMatrix:
    """Exact :math:`S_q` of knot vector ``kv``: :math:`\\tilde N = S_q N` reproduces
    :math:`\\mathcal P_q`; ``q`` defaults to the degree p (full reproduction).

    >>> from dispersion.splines.bspline import open_knot_vector
    >>> approximate_dual_matrix(open_knot_vector(2, 2), 0).tolist()   # 1 / int N_i
    [[6, 0, 0, 0], [0, 3, 0, 0], [0, 0, 3, 0], [0, 0, 0, 6]]
    """
    q = kv.p if q is None else q
    if isinstance(q, bool) or not isinstance(q, int) or not 0 <= q <= kv.p:
        raise InputError(f"reproduction degree q must be an integer in [0, {kv.p}], got {q!r}")
    S = _levels(kv, q)[1]
    return sympy.ImmutableMatrix(len(S), len(S), lambda i, j: sympy.Rational(
        S[i][j].numerator, S[i][j].denominator))


def customized_mass(kv, q: int | None = None) -> sympy.ImmutableMatrix:
    """The Galerkin mass :math:`S_q^{-1}` equivalent to row-sum-lumped approximate-dual
    Petrov-Galerkin (Hiemstra et al. 2025): symmetric, dense, total mass kept.

    >>> from dispersion.splines.bspline import open_knot_vector
    >>> M = customized_mass(open_knot_vector(1, 2), 1)
    >>> M.tolist(), sum(M)
    ([[17/96, 1/16, 1/96], [1/16, 3/8, 1/16], [1/96, 1/16, 17/96]], 1)
    """
    from sympy.polys.matrices import DomainMatrix

    S = DomainMatrix.from_Matrix(sympy.Matrix(approximate_dual_matrix(kv, q))).to_field()
    return sympy.ImmutableMatrix(S.inv().to_Matrix())


def dirichlet_dual(S, constrained) -> sympy.Matrix:
    """The banded inverse of the Galerkin mass with the DOFs ``constrained`` removed.

    :math:`(S^{-1})_{rr}^{-1} = S_{rr} - S_{rc} S_{cc}^{-1} S_{cr}` (Schur complement): the
    Dirichlet treatment of Hiemstra et al. (2025), derived from the Galerkin form.

    >>> S = sympy.Matrix([[4, -2, 1], [-2, 4, -2], [1, -2, 4]])
    >>> dirichlet_dual(S, [0]).tolist()
    [[3, -3/2], [-3/2, 15/4]]
    """
    S = sympy.Matrix(S)
    c = sorted({int(i) for i in constrained})
    if not c or c[0] < 0 or c[-1] >= S.rows:
        raise InputError(f"constrained DOFs must lie in [0, {S.rows - 1}], got {constrained!r}")
    r = [i for i in range(S.rows) if i not in c]
    return S.extract(r, r) - S.extract(r, c) * S.extract(c, c).inv() * S.extract(c, r)


def _laurent_power_w(k: int) -> dict[int, Fraction]:
    """Laurent coefficients of :math:`w^k = (2 - e^{i\\theta} - e^{-i\\theta})^k`."""
    out = {0: Fraction(1)}
    for _ in range(k):
        nxt: dict[int, Fraction] = {}
        for L, v in out.items():
            for dL, c in ((0, 2), (1, -1), (-1, -1)):
                nxt[L + dL] = nxt.get(L + dL, Fraction(0)) + c * v
        out = nxt
    return out


@lru_cache(maxsize=None)
def _gram_in_w(p: int) -> tuple[Fraction, ...]:
    """The uniform Gram symbol :math:`g = \\sum_L c^{00}_L \\cos L\\theta` as a polynomial in w."""
    from dispersion.splines.spline_mass import PERIODIC_ROWS

    z = sympy.Symbol("z")  # cos(theta) = 1 - w/2
    w = sympy.Symbol("w")
    g = sum(sympy.Rational(v.numerator, v.denominator) * sympy.chebyshevt(abs(L), z)
            for L, v in PERIODIC_ROWS["consistent"](p).items() if v != 0)
    poly = sympy.Poly(sympy.expand(g.subs(z, 1 - w / 2)), w)
    return tuple(Fraction(int(c.p), int(c.q)) for c in reversed(poly.all_coeffs()))


def dual_symbol(p: int, q: int | None = None) -> dict[int, sympy.Rational]:
    """Bloch coefficients :math:`s_L` of :math:`S_q` on uniform unit knots.

    :math:`s(w) = \\sum_{k \\le q} t_k w^k` with :math:`1/g(w) = \\sum_k t_k w^k`.
    """
    p = check_positive_int("degree p", p)
    q = p if q is None else q
    if isinstance(q, bool) or not isinstance(q, int) or not 0 <= q <= p:
        raise InputError(f"reproduction degree q must be an integer in [0, {p}], got {q!r}")
    g = _gram_in_w(p)
    inv = [Fraction(1) / g[0]]
    for k in range(1, q + 1):
        inv.append(-sum((g[j] * inv[k - j] for j in range(1, min(k, len(g) - 1) + 1)),
                        Fraction(0)) / g[0])
    out: dict[int, Fraction] = {}
    for k, tk in enumerate(inv):
        for L, v in _laurent_power_w(k).items():
            out[L] = out.get(L, Fraction(0)) + tk * v
    return {L: sympy.Rational(v.numerator, v.denominator) for L, v in sorted(out.items())
            if v != 0}


def bloch_product(a: dict, b: dict) -> dict:
    """Laurent coefficients of the product of two Bloch symbols :math:`\\sum_L a_L e^{iL\\theta}`.

    >>> bloch_product({-1: 1, 1: 1}, {0: 2, 1: 1})
    {-1: 2, 0: 1, 1: 2, 2: 1}
    """
    out: dict = {}
    for L, v in a.items():
        for J, u in b.items():
            out[L + J] = out.get(L + J, 0) + v * u
    return {L: v for L, v in sorted(out.items())}
